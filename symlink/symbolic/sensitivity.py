"""Design sensitivities: how a linkage's positions move when one of its parameters changes.

At fixed inputs ``x`` the closure ``F(x, q, p) = 0`` ties the unknowns ``q``
to the parameters ``p`` (link lengths, fixed angles, coupler-point offsets,
pivot coordinates).  Differentiating it by one parameter gives

    J dq/dp = -dF/dp,      J = dF/dq,

the same linear system as the velocities (:mod:`symlink.symbolic.motion`) with the
parameter in the place of time: the parameter's rate is 1 and the inputs'
rates are 0.  So the derivation here is the velocity derivation itself,
:func:`symlink.symbolic.motion.loop_rates`, run loop by loop in solve-plan order on a
loop where the parameter is a moving symbol; earlier loops' sensitivities
enter later loops as known rates.  A point or an extra output then follows
by the chain rule (:func:`total_derivative`).  Where no closed form exists
(the Newton fallback) the same system is solved numerically with the
converged Jacobian (:func:`closure_parameter_rhs` gives ``-dF/dp``).

Sensitivities are outputs like any other, named ``<output>__d_<parameter>``
(:func:`sensitivity_name`): ``rocker__d_a`` is d(rocker)/da, ``C_x__d_d`` is
d(C_x)/dd.  A request for positions and their sensitivities derives no rates,
and a request for positions alone derives no sensitivities.  Only positions
(coordinates, roles, points and extras) have sensitivities; those of rates
and accelerations are not derived.

>>> from symlink.symbolic.vectors import Vector, coordinates, lengths
>>> from symlink.symbolic.loops import Loop
>>> theta, beta, phi = coordinates("theta beta phi")
>>> a, b, c, d = lengths("a b c d")
>>> closure = Loop(Vector(a, theta) + Vector(b, beta) - Vector(c, phi) - Vector(d, 0))
>>> found = loop_sensitivities(closure, [beta, phi], [], a)
>>> found[sensitivity_symbol(phi, a)]
cos(beta - theta)/(c*sin(beta - phi))
"""
from __future__ import annotations

from typing import Iterable, Sequence

import sympy as sp

from .loops import Loop
from .motion import loop_rates
from ..common.names import PLAIN_NAME, reason_reserved
from ..common.notation import SENSITIVITY_SEPARATOR
from .position import LoopSolution
from .vectors import Vector, VectorSum, rate

__all__ = ["SEPARATOR", "MAX_NAME_LENGTH", "sensitivity_name", "sensitivity_symbol", "split_sensitivity_name",
           "loop_sensitivities", "plan_sensitivities", "total_derivative", "closure_parameter_rhs"]

#: Between an output's name and a parameter's in a sensitivity's name: ``rocker__d_a``.
SEPARATOR = SENSITIVITY_SEPARATOR
#: Longest sensitivity name: MATLAB's limit on identifiers and struct fields.
MAX_NAME_LENGTH = 63


def sensitivity_name(output: str, parameter: str) -> str:
    """The name of d(output)/d(parameter); ``ValueError`` if generated code cannot take it.

    >>> sensitivity_name("rocker", "a")
    'rocker__d_a'
    """
    name = f"{output}{SEPARATOR}{parameter}"
    if not PLAIN_NAME.match(name):
        raise ValueError(f"sensitivity {name!r} is not a plain name (ASCII letters, digits and underscores)")
    if len(name) > MAX_NAME_LENGTH:
        raise ValueError(f"sensitivity {name!r} is longer than {MAX_NAME_LENGTH} characters, the most MATLAB "
                         "takes; use shorter names for the output or the parameter")
    why = reason_reserved(name)
    if why:
        raise ValueError(f"sensitivity {name!r} {why}; rename the output or the parameter")
    return name


def sensitivity_symbol(coordinate: sp.Symbol, parameter: sp.Symbol) -> sp.Symbol:
    """The symbol of d(coordinate)/d(parameter) in derivations and generated code (``phi__d_a``)."""
    return sp.Symbol(sensitivity_name(coordinate.name, parameter.name), real=True)


def split_sensitivity_name(name: str, parameters: Sequence[sp.Symbol]) -> tuple[str, sp.Symbol] | None:
    """``(output, parameter)`` if ``name`` is ``<output>__d_<parameter>`` for one of ``parameters``, else None.

    ``ValueError`` when two parameters fit (``x__d_y`` and ``y`` both parameters): the name is ambiguous.

    >>> a, b = sp.symbols("a b", positive=True)
    >>> split_sensitivity_name("rocker__d_a", [a, b])
    ('rocker', a)
    >>> split_sensitivity_name("rocker", [a, b]) is None
    True
    """
    found = [(name[:-len(SEPARATOR + p.name)], p) for p in parameters
             if name.endswith(SEPARATOR + p.name) and len(name) > len(SEPARATOR + p.name)]
    if len(found) > 1:
        raise ValueError(f"{name!r} is ambiguous: it is the sensitivity of "
                         + " and of ".join(f"{output!r} by {p.name!r}" for output, p in found)
                         + "; rename a parameter")
    return found[0] if found else None


def _moving(parameter: sp.Symbol) -> sp.Symbol:
    """A stand-in for ``parameter`` whose rate cannot clash with a user's symbol (``symlink_`` is reserved)."""
    return sp.Symbol("symlink_parameter", **parameter.assumptions0)


def loop_sensitivities(loop: Loop, unknowns: Sequence[sp.Symbol], solved: Sequence[sp.Symbol],
                       parameter: sp.Symbol) -> dict[sp.Symbol, sp.Expr]:
    """The derivatives by ``parameter`` of a loop's two ``unknowns``, at fixed inputs.

    ``solved`` are the unknowns of earlier loops; their sensitivities appear as
    the symbols :func:`sensitivity_symbol` names.  This is
    :func:`symlink.symbolic.motion.loop_rates` with the parameter as the one moving
    symbol besides the unknowns (inputs held): the same projections, the same
    denominators (so the same toggles make them infinite).
    """
    stand_in = _moving(parameter)
    swap = {parameter: stand_in}
    moved = Loop(VectorSum(tuple((sign, Vector(v.length.xreplace(swap), v.angle.xreplace(swap), v.name))
                                 for sign, v in loop.terms)), loop.name)
    rates = loop_rates(moved, unknowns, tuple(solved) + tuple(unknowns) + (stand_in,), order=1)
    back: dict[sp.Basic, sp.Basic] = {rate(stand_in): sp.S.One, stand_in: parameter}
    back.update({rate(q): sensitivity_symbol(q, parameter) for q in solved})
    return {sensitivity_symbol(u, parameter): rates[rate(u)].xreplace(back) for u in unknowns}


def plan_sensitivities(plan: Iterable[LoopSolution], parameter: sp.Symbol) -> dict[sp.Symbol, sp.Expr]:
    """Every unknown's derivative by ``parameter``, loop by loop in solve-plan order (each uses earlier ones)."""
    result: dict[sp.Symbol, sp.Expr] = {}
    solved: list[sp.Symbol] = []
    for step in plan:
        unknowns = list(step.positions)
        result.update(loop_sensitivities(step.loop, unknowns, solved, parameter))
        solved += unknowns
    return result


def total_derivative(expr: sp.Expr, unknowns: Sequence[sp.Symbol], parameter: sp.Symbol) -> sp.Expr:
    """d(expr)/d(parameter) at fixed inputs: its own dependence plus the chain through the unknowns.

    >>> x, s = sp.symbols("x s", real=True)
    >>> total_derivative(s * sp.cos(x), [x], s)
    -s*x__d_s*sin(x) + cos(x)
    """
    result = sp.diff(expr, parameter)
    for q in unknowns:
        partial = sp.diff(expr, q)
        if partial != 0:
            result += partial * sensitivity_symbol(q, parameter)
    return result


def closure_parameter_rhs(residuals: Sequence[sp.Expr], parameters: Sequence[sp.Symbol]) -> sp.Matrix:
    """``-dF/dp``: the right-hand sides (one column a parameter) of ``J dq/dp = -dF/dp`` for the Newton fallback.

    >>> s, a = sp.symbols("s a", real=True)
    >>> closure_parameter_rhs([a * sp.cos(s) - 1], [a])
    Matrix([[-cos(s)]])
    """
    return -sp.Matrix(list(residuals)).jacobian(list(parameters))
