"""Velocities and accelerations: time derivatives of the closure, solved for the unknown rates.

Differentiating ``sum_k s_k r_k e^{i t_k} = 0`` once gives
``sum_k s_k (r_k' + i r_k t_k') e^{i t_k} = 0`` and twice
``sum_k s_k ((r_k'' - r_k t_k'^2) + i (r_k t_k'' + 2 r_k' t_k')) e^{i t_k} = 0``.
Both are linear in the unknown rates.  Rather than invert the 2x2 system, each
equation is projected across the direction in which the other unknown acts
(the classic trick of the textbooks): the other rate drops out and the one
left is a ratio, with sines of angle differences, as in the C-program paper on velocities and accelerations:

    rocker_speed = a * crank_speed * sin(beta - theta) / (c * sin(beta - phi))

Loops are taken in solve-plan order, so the rates found in earlier loops are
known in later ones and every step is one of these 2x2 projections.

>>> from symlink.symbolic.vectors import Vector, coordinates, lengths, rate
>>> from symlink.symbolic.loops import Loop
>>> theta, beta, phi = coordinates("theta beta phi")
>>> a, b, c, d = lengths("a b c d")
>>> closure = Loop(Vector(a, theta) + Vector(b, beta) - Vector(c, phi) - Vector(d, 0))
>>> rates = loop_rates(closure, [beta, phi], [theta, beta, phi], order=1)
>>> rates[rate(phi)]
a*thetadot*sin(beta - theta)/(c*sin(beta - phi))
"""
from __future__ import annotations

from typing import Sequence

import sympy as sp

from .loops import Loop, Unknown
from .vectors import acceleration, rate, time_derivative

__all__ = ["loop_rates"]


def _own(expr, coordinates) -> list:
    """The coordinates that ``expr`` moves with (itself or its rate appears in it), in their order.

    A total derivative by the chain rule needs only these: differentiating by every coordinate of
    the linkage made the cost of a vector grow with the linkage (a chain of k loops: k^2).
    """
    symbols = sp.sympify(expr).free_symbols
    return [q for q in coordinates if q in symbols or rate(q) in symbols]


def _derivative(expr, coordinates):
    """The total time derivative of ``expr``, over its own coordinates only (the same expression)."""
    return time_derivative(expr, _own(expr, coordinates))


def _derivative_parts(length, angle, coordinates, order):
    """Real and imaginary parts, in the vector's own frame, of the derivative of ``r e^{i t}``."""
    dr = _derivative(length, coordinates)
    dt = _derivative(angle, coordinates)
    if order == 1:
        return dr, length * dt
    ddr = _derivative(dr, coordinates)
    ddt = _derivative(dt, coordinates)
    return ddr - length * dt**2, length * ddt + 2 * dr * dt


def _projected_equation(loop: Loop, eliminated: Unknown, coordinates, order) -> sp.Expr:
    """The differentiated closure, projected so that ``eliminated``'s rate drops out."""
    reference = eliminated.vector.angle
    total = sp.S.Zero
    for sign, vector in loop.terms:
        along, across = _derivative_parts(vector.length, vector.angle, coordinates, order)
        if along == 0 and across == 0:
            continue
        relative = vector.angle - reference
        if eliminated.part == "length":   # keep the part across the eliminated vector
            total += sign * (along * sp.sin(relative) + across * sp.cos(relative))
        else:                             # keep the part along it
            total += sign * (across * sp.sin(relative) - along * sp.cos(relative))
    return total


def _by_cramer(loop: Loop, unknowns, coordinates, order, target) -> dict[sp.Symbol, sp.Expr]:
    """The two unknowns' derivatives from the differentiated closure, by Cramer's rule."""
    equations = [sp.expand(component) for component in loop.equations()]
    for _ in range(order):
        equations = [_derivative(e, coordinates) for e in equations]
    symbols = [target(u) for u in unknowns]
    matrix = [[sp.diff(e, x) for x in symbols] for e in equations]
    rest = [-e.subs({x: 0 for x in symbols}) for e in equations]
    # The determinant is a short trigonometric polynomial of the loop's own angles (for a slider on a turning
    # guide it is the slider's travel, -s): simplified once here, at derivation time, it prints short and
    # cancels no digits when evaluated.
    determinant = sp.trigsimp(sp.expand(matrix[0][0] * matrix[1][1] - matrix[0][1] * matrix[1][0]))
    return {
        symbols[0]: (rest[0] * matrix[1][1] - matrix[0][1] * rest[1]) / determinant,
        symbols[1]: (matrix[0][0] * rest[1] - rest[0] * matrix[1][0]) / determinant,
    }


def loop_rates(loop: Loop, unknowns: Sequence[sp.Symbol], coordinates: Sequence[sp.Symbol],
               order: int) -> dict[sp.Symbol, sp.Expr]:
    """The two unknowns' rates (``order=1``) or accelerations (``order=2``).

    ``coordinates`` are all time-varying symbols of the linkage (inputs and
    unknowns).  The result is written in terms of the coordinates, their lower
    derivatives and the inputs' rates, all of which are known by then.
    """
    target = rate if order == 1 else acceleration
    try:
        first, second = (loop.locate(u) for u in unknowns)
    except ValueError:  # an unknown angle turns several vectors (case 2c): solve the 2x2 system directly
        return _by_cramer(loop, unknowns, coordinates, order, target)
    result = {}
    for solved, eliminated in ((first, second), (second, first)):
        equation = _projected_equation(loop, eliminated, coordinates, order)
        symbol = target(solved.symbol)
        coefficient = sp.diff(equation, symbol)
        if coefficient == 0:
            raise ValueError(f"the rate of {solved.symbol} does not enter loop {loop.name!r}")
        rest = equation.subs(symbol, 0)
        result[symbol] = sp.factor_terms(-rest / coefficient)
    return {target(u): result[target(u)] for u in unknowns}
