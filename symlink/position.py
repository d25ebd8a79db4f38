"""Closed-form position solutions of a loop's four cases, with the assembly branch.

Write the loop as ``sum_k s_k r_k e^{i t_k} = 0`` and move the known vectors
to the right: the two unknown vectors must add up to ``W = -(known part)``.
Each case is then elementary geometry, written with ``atan2`` and a square
root whose argument is clamped at zero within rounding (:class:`ClampedSqrt`),
so the solution stays finite and accurate up to the toggle positions.  The
half-angle tangent form of the textbooks is avoided: it breaks at an angle of
pi and loses accuracy where its leading coefficient vanishes.

Branches (the sign ``sigma`` of the square root):

* case 3 (two angles): ``+1`` turns the first unknown vector counter-clockwise
  from ``W``, i.e. the joint between the two unknown vectors lies to the left
  of the line they close.  For the four-bar with unknowns (beta, phi) this is
  DESIGN.md's rule: joint C left of the directed line from B to D.
* case 2b (a length and another vector's angle): ``+1`` gives the larger
  unknown length (the slider-crank's far position).
* cases 1 and 2a have one solution (a non-negative length in 2a).

>>> from symlink.vectors import Vector, coordinates, lengths
>>> from symlink.loops import Loop
>>> theta, beta, phi = coordinates("theta beta phi")
>>> a, b, c, d = lengths("a b c d")
>>> closure = Loop(Vector(a, theta) + Vector(b, beta) - Vector(c, phi) - Vector(d, 0))
>>> solution = solve_loop(closure, [beta, phi], sp.Symbol("branch"))
>>> solution.case.name, solution.branch
('3', branch)
>>> sorted(solution.positions, key=str)
[beta, phi]
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

import sympy as sp

from .loops import Loop, LoopCase, Unknown

__all__ = ["ClampedSqrt", "LoopSolution", "solve_loop", "TOLERANCE"]

#: Relative size below which a negative square-root argument is rounding, not
#: a configuration that cannot be assembled: with the scales the cases give
#: (see ``_rounding_size``), inputs within ``TOLERANCE`` times the loop's size of
#: a toggle are taken as at the toggle (about 45 units in the last place).
TOLERANCE = 1e-14


class ClampedSqrt(sp.Function):
    """``sqrt(x)`` where ``x`` may round below zero: ``ClampedSqrt(x, scale)``.

    ``x >= 0`` gives ``sqrt(x)``; ``-TOLERANCE*scale <= x < 0`` is rounding and
    gives 0 (the toggle position itself); anything lower cannot be assembled
    and gives NaN, which the generated solvers report as not assembled.
    Printed as ``sqrt(max(x, 0))`` in every language, never as a Piecewise.

    >>> ClampedSqrt(4, 1), ClampedSqrt(-1e-16, 1), ClampedSqrt(-1, 1)
    (2, 0, nan)
    """

    nargs = 2

    @classmethod
    def eval(cls, x, scale):
        if x.is_Number and scale.is_Number:
            if x >= 0:
                return sp.sqrt(x)
            return sp.S.Zero if x >= -TOLERANCE * scale else sp.nan
        return None

    def fdiff(self, argindex=1):
        if argindex == 1:
            return 1 / (2 * self)
        return sp.S.Zero

    def _latex(self, printer):
        return r"\sqrt{\left[%s\right]_{+}}" % printer._print(self.args[0])


@dataclass(frozen=True)
class LoopSolution:
    """The closed-form solution of one loop.

    ``positions`` maps each unknown to its expression, in the unknowns' order;
    the expressions use the named ``intermediates`` (the closing vector
    ``Wx_k, Wy_k``, its length ``w_k`` and the root ``Delta_k`` of loop k), the
    way a textbook names them, so that they read well and print as LaTeX.

    ``singular_factors`` rewrites the sine or cosine that vanishes at this
    loop's singular configurations (the toggles, where the two branches
    meet) in terms of the root ``Delta_k``: ``sin(beta - phi)`` of the
    four-bar is ``-branch Delta_1 / (2 b c)``.  With it the rates divide by
    exactly zero where the root is zero, and are not finite there.
    """

    loop: Loop
    case: LoopCase
    branch: sp.Symbol | None
    intermediates: dict[sp.Symbol, sp.Expr]
    positions: dict[sp.Symbol, sp.Expr]
    singular_factors: dict[sp.Expr, sp.Expr] = field(default_factory=dict)


def _cross(ux, uy, vx, vy):
    return ux * vy - uy * vx


def _absolute(unknown: Unknown, value: sp.Expr) -> sp.Expr:
    """The unknown itself, from the value of the length or angle that it owns."""
    return value - unknown.offset


class _Intermediates(dict):
    """Named helper quantities of loop ``label``: ``name(expr)`` stores and returns the symbol."""

    def __init__(self, label: str):
        super().__init__()
        self.label = label
        self.singular_factors: dict[sp.Expr, sp.Expr] = {}

    def identity(self, function, argument: sp.Expr, value: sp.Expr, odd: bool) -> None:
        """Record ``function(argument) = value`` (and of ``-argument``) for the rates' denominators."""
        for arg, val in ((argument, value), (-argument, -value if odd else value)):
            if isinstance(function(arg), function):
                self.singular_factors[function(arg)] = val

    def __call__(self, name: str, expr: sp.Expr) -> sp.Symbol:
        symbol = sp.Symbol(f"{name}_{self.label}", real=True)
        self[symbol] = expr
        return symbol


def _rounding_size(case: LoopCase) -> sp.Expr:
    """Sum of the known vectors' lengths: ``W`` carries a rounding error of a few ulps of it.

    A root's argument is a product with one factor that vanishes at the
    toggle; that factor's rounding error is a few ulps of the loop's size
    (this sum plus the unknown vectors' lengths), and the :class:`ClampedSqrt`
    scale is that size times the other factors' product there: inputs
    within ``TOLERANCE`` times the loop's size of a toggle are taken as at
    the toggle, anything farther out cannot be assembled.
    """
    return sp.Add(*(sp.Abs(v.length) for _, v in case.known))


def _two_lengths(case: LoopCase, wx, wy, branch, named):
    p, q = case.first, case.second
    tp, tq = p.vector.angle, q.vector.angle
    determinant = sp.sin(tq - tp)
    rp = _cross(wx, wy, sp.cos(tq), sp.sin(tq)) / (p.sign * determinant)
    rq = _cross(sp.cos(tp), sp.sin(tp), wx, wy) / (q.sign * determinant)
    return {p.symbol: _absolute(p, rp), q.symbol: _absolute(q, rq)}


def _length_and_angle_of_one(case: LoopCase, wx, wy, branch, named):
    length, angle = (case.first, case.second) if case.first.part == "length" else (case.second, case.first)
    s = length.sign
    return {
        length.symbol: _absolute(length, sp.sqrt(wx**2 + wy**2)),
        angle.symbol: _absolute(angle, sp.atan2(s * wy, s * wx)),
    }


def _length_and_other_angle(case: LoopCase, wx, wy, branch, named):
    # p owns the unknown length, q the unknown angle.
    p, q = (case.first, case.second) if case.first.part == "length" else (case.second, case.first)
    tp, rq = p.vector.angle, q.vector.length
    ux, uy = sp.cos(tp), sp.sin(tp)
    across = _cross(ux, uy, wx, wy)          # s_q r_q sin(t_q - t_p)
    along = ux * wx + uy * wy                # s_p r_p + s_q r_q cos(t_q - t_p)
    # At a toggle one factor vanishes, off by a few ulps of the loop's size,
    # and the other is 2 r_q.
    root = named("Delta", ClampedSqrt((rq - across) * (rq + across),
                                      2 * sp.Abs(rq) * (sp.Abs(rq) + _rounding_size(case))))
    rp = p.sign * along + branch * root
    tq = tp + sp.atan2(q.sign * across, -p.sign * q.sign * branch * root)
    if rq.is_positive:
        named.identity(sp.cos, q.vector.angle - tp, -p.sign * q.sign * branch * root / rq, odd=False)
    return {p.symbol: _absolute(p, rp), q.symbol: _absolute(q, tq)}


def _two_angles(case: LoopCase, wx, wy, branch, named):
    p, q = case.first, case.second
    sign_q = q.sign * p.sign
    if p.sign < 0:  # walk the loop the other way so that the first vector is added
        wx, wy = -wx, -wy
    rp, rq = p.vector.length, q.vector.length
    w = named("w", sp.sqrt(wx**2 + wy**2))
    # Triangle P + Q = W with |P| = rp, |Q| = rq: 2w times the components of P
    # along and across W are xp and y; Heron's product keeps y accurate near
    # the toggles, where the triangle is flat.
    xp = (rp - rq) * (rp + rq) + w**2
    xq = (rq - rp) * (rq + rp) + w**2
    # At a toggle (w = rp + rq or |rp - rq|) one factor vanishes, off by a few
    # ulps of the loop's size, and the other three multiply to 8 rp rq w.
    size = sp.Abs(rp) + sp.Abs(rq) + w + _rounding_size(case)
    y = branch * named("Delta", ClampedSqrt((rp + rq + w) * (rp + rq - w) * (w + rq - rp) * (w + rp - rq),
                                            8 * sp.Abs(rp * rq) * w * size))
    tp = sp.atan2(xp * wy + y * wx, xp * wx - y * wy)
    tq = sp.atan2(sign_q * (xq * wy - y * wx), sign_q * (xq * wx + y * wy))
    # P = (xp + i y) W / (2 w^2) and Q = (xq - i y) W / (2 w^2), so the cross
    # product P x Q = rp rq sign_q sin(tq - tp) is -y (xp + xq) / (4 w^2) = -y/2.
    if rp.is_positive and rq.is_positive:
        named.identity(sp.sin, q.vector.angle - p.vector.angle, -sign_q * y / (2 * rp * rq), odd=True)
    return {p.symbol: _absolute(p, tp), q.symbol: _absolute(q, tq)}


_SOLVERS = {"1": _two_lengths, "2a": _length_and_angle_of_one,
            "2b": _length_and_other_angle, "3": _two_angles}


def solve_loop(loop: Loop, unknowns: Sequence[sp.Symbol], branch: sp.Symbol | None = None,
               label: str = "1") -> LoopSolution:
    """Solve ``loop`` for its two ``unknowns`` in closed form.

    ``branch`` is the symbol that carries the assembly sign (+1 or -1) for
    the cases that have two solutions; it is ignored by the others.
    ``label`` tells this loop's intermediates from other loops' (``w_1``).
    """
    case = loop.case(list(unknowns))
    if case.branches == 2 and branch is None:
        raise ValueError(f"loop {loop.name!r} (case {case.name}) has two assemblies: give a branch symbol")
    named = _Intermediates(label)
    # W: the vector that the two unknown terms must add up to.
    wx = named("Wx", -sp.Add(*(s * v.x for s, v in case.known)))
    wy = named("Wy", -sp.Add(*(s * v.y for s, v in case.known)))
    positions = _SOLVERS[case.name](case, wx, wy, branch, named)
    positions = {u: positions[u] for u in unknowns}
    return LoopSolution(loop, case, branch if case.branches == 2 else None, dict(named), positions,
                        named.singular_factors)
