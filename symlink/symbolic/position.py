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
  the four-bar's rule: joint C left of the directed line from B to D.
* cases 2b (a length and another vector's angle) and 2c (a length on a body
  that the unknown angle turns): ``+1`` gives the larger unknown length (the
  slider-crank's far position).
* cases 1 and 2a have one solution (a non-negative length in 2a).

>>> from symlink.symbolic.vectors import Vector, coordinates, lengths
>>> from symlink.symbolic.loops import Loop
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

import sys
from dataclasses import dataclass, field
from functools import cached_property
from typing import Sequence

import sympy as sp

from ..common.rounding import TOLERANCE  # its home (SymPy-free); kept here for the symbolic layer
from .loops import Loop, LoopCase, Unknown

__all__ = ["ClampedSqrt", "NonzeroSquare", "PowerOfTwoBelow", "LoopSolution", "solve_loop", "TOLERANCE"]


class ClampedSqrt(sp.Function):
    """``sqrt(x)`` where ``x`` may round below zero: ``ClampedSqrt(x)`` as a textbook writes it, ``[x]_+``.

    The equations a user reads (:attr:`symlink.symbolic.linkage.Linkage.positions`, LaTeX)
    carry the one-argument form: the square root of ``x``, which is zero at a
    toggle and has no real value (no assembly) below it.  Generated code carries
    ``ClampedSqrt(x, scale)`` in loop units (see :attr:`LoopSolution.in_loop_units`):
    ``x >= 0`` gives ``sqrt(x)``; ``-TOLERANCE*scale <= x < 0`` is rounding and
    gives 0 (the toggle position itself); anything lower cannot be assembled
    and gives NaN, which the generated solvers report as not assembled.
    Printed as ``sqrt(max(x, 0))`` in every language, never as a Piecewise.
    A negative ``scale`` makes it a guard: NaN for any ``x`` below
    ``-TOLERANCE*scale`` (a length that is zero within rounding).

    >>> ClampedSqrt(4), ClampedSqrt(-1)
    (2, nan)
    >>> ClampedSqrt(4, 1), ClampedSqrt(-1e-16, 1), ClampedSqrt(-1, 1)
    (2, 0, nan)
    """

    nargs = (1, 2)

    @classmethod
    def eval(cls, x, scale=None):
        if x.is_Number and (scale is None or scale.is_Number):
            if x >= 0:
                return sp.sqrt(x)
            return sp.S.Zero if scale is not None and x >= -TOLERANCE * scale else sp.nan
        return None

    def fdiff(self, argindex=1):
        if argindex == 1:
            return 1 / (2 * self)
        return sp.S.Zero

    def _latex(self, printer):
        return r"\sqrt{\left[%s\right]_{+}}" % printer._print(self.args[0])


class NonzeroSquare(sp.Function):
    """A squared length that must not vanish: ``x`` where ``x >= smallest``, NaN below (or for NaN).

    Generated code only (loop units): the two-angle case needs the closing
    vector's length ``w`` only squared (Heron's product and the ``atan2``
    arguments are even in ``w``), so it keeps ``w^2`` and takes no square root
    for it; this guard is what the square root's guard was, ``ClampedSqrt(x,
    -smallest/TOLERANCE)`` (NaN where the two known points coincide, so that
    the pose, whose direction is then undefined, is reported not assembled),
    without the square root.  Printed as a comparison and a select in every
    language; nothing a user reads shows it.

    >>> NonzeroSquare(4, 1), NonzeroSquare(0, 1)
    (4, nan)
    """

    nargs = 2

    @classmethod
    def eval(cls, x, smallest):
        if x is sp.nan:
            return sp.nan
        if x.is_Number and smallest.is_Number:
            return x if x >= smallest else sp.nan
        return None


class PowerOfTwoBelow(sp.Function):
    """The largest power of two not above ``x > 0``: a loop's unit in generated code, so dividing by it is exact.

    Generated code takes it from the exponent bits of ``x`` (``frexp`` in NumPy,
    a mask of the bits in C): no logarithm, and exact where a rounded ``log2``
    near a power of two could be one off.

    >>> PowerOfTwoBelow(10), PowerOfTwoBelow(sp.Rational(1, 3)), PowerOfTwoBelow(8)
    (8, 1/4, 8)
    """

    nargs = 1

    @classmethod
    def eval(cls, x):
        if x.is_Float and x.is_positive:  # exact: the float's own exponent
            mantissa, exponent = sp.Float(x)._mpf_[1], sp.Float(x)._mpf_[2]
            return sp.Integer(2) ** (exponent + int(mantissa).bit_length() - 1)
        if x.is_Rational and x.is_positive:
            exponent = sp.floor(sp.log(x, 2))
            while 2**exponent > x:  # floor of an exact logarithm: SymPy evaluates it, this only guards
                exponent -= 1
            while 2 ** (exponent + 1) <= x:
                exponent += 1
            return sp.Integer(2) ** exponent
        return None


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

    ``radii`` (generated code only, :attr:`in_loop_units`) holds, for an unknown
    angle solved as ``atan2(y, x)``, the length ``sqrt(x^2 + y^2)`` where the closed
    form knows it without a square root: the rates take the angle's cosine and
    sine as ``x / r`` and ``y / r`` (:func:`symlink.codegen.trigonometry.angle_sums`).

    These are the textbook forms, in the linkage's own lengths and angles.
    :attr:`in_loop_units` is the same solution as generated code computes it.
    """

    loop: Loop
    case: LoopCase
    branch: sp.Symbol | None
    intermediates: dict[sp.Symbol, sp.Expr]
    positions: dict[sp.Symbol, sp.Expr]
    singular_factors: dict[sp.Expr, sp.Expr] = field(default_factory=dict)
    label: str = "1"
    radii: dict[sp.Symbol, sp.Expr] = field(default_factory=dict)

    @cached_property
    def in_loop_units(self) -> "LoopSolution":
        """The same solution as generated code computes it: exact at any scale, guarded at the toggles.

        Lengths are divided by the loop's unit ``size_k`` (its mean known length
        rounded down to a power of two, so the division is exact) into ``rho_j_k``,
        unknown lengths are scaled back, and each square root carries the clamping
        scale that tells rounding at a toggle from a loop that cannot close.  The
        intermediates keep their names (``Wx_k``, ``w_k``, ``Delta_k``) and hold the
        same quantities in loop units, so the rates can use either form; where a
        case needs ``w_k`` only squared (two angles, and a length on a turning
        body) it keeps ``wsq_k = Wx_k^2 + Wy_k^2`` instead and takes no square root
        for it (one square root a loop: ``Delta_k``), and the two-angle case gives
        the length of each angle's atan2 arguments (:attr:`radii`).  Code
        generation swaps this in (:func:`symlink.codegen.program.in_loop_units`);
        nothing a user reads shows it.

        >>> from symlink.mechanism.catalog import fourbar
        >>> step = fourbar().plan[0]
        >>> str(step.intermediates[sp.Symbol("Wx_1", real=True)])
        'a*cos(theta) - d'
        >>> str(step.in_loop_units.intermediates[sp.Symbol("Wx_1", real=True)])
        '-rho_1_1 + rho_2_1*cos(theta)'
        """
        return solve_loop(self.loop, list(self.positions), self.branch, self.label, loop_units=True)

    def _repr_latex_(self) -> str:
        """The intermediates, then the unknowns, one equation a line: what a notebook shows."""
        lines = [f"{sp.latex(name)} &= {sp.latex(value)}" for name, value in
                 list(self.intermediates.items()) + list(self.positions.items())]
        return "$\\displaystyle \\begin{aligned}" + " \\\\ ".join(lines) + "\\end{aligned}$"


def _cross(ux, uy, vx, vy):
    return ux * vy - uy * vx


def _absolute(unknown: Unknown, value: sp.Expr) -> sp.Expr:
    """The unknown itself, from the value of the length or angle that it owns."""
    return value - unknown.offset


class _Intermediates(dict):
    """Named helper quantities of loop ``label``: ``name(expr)`` stores and returns the symbol.

    With ``loop_units`` the square roots carry their numeric guards (what generated
    code computes); without, they are written as a textbook writes them.
    """

    def __init__(self, label: str, loop_units: bool = False):
        super().__init__()
        self.label = label
        self.loop_units = loop_units
        self.singular_factors: dict[sp.Expr, sp.Expr] = {}
        self.radii: dict[sp.Symbol, sp.Expr] = {}

    def clamped(self, x: sp.Expr, scale: sp.Expr) -> sp.Expr:
        """``[x]_+`` under a square root; in loop units with the scale that tells rounding from no assembly."""
        return ClampedSqrt(x, scale) if self.loop_units else ClampedSqrt(x)

    def nonzero(self, squared: sp.Expr, smallest: float = TOLERANCE**2) -> sp.Expr:
        """A length from its square; in loop units NaN where the square is below ``smallest`` (no direction)."""
        return _nonzero_length(squared, smallest) if self.loop_units else sp.sqrt(squared)

    def identity(self, function, argument: sp.Expr, value: sp.Expr, odd: bool) -> None:
        """Record ``function(argument) = value`` (and of ``-argument``) for the rates' denominators."""
        for arg, val in ((argument, value), (-argument, -value if odd else value)):
            if isinstance(function(arg), function):
                self.singular_factors[function(arg)] = val

    def __call__(self, name: str, expr: sp.Expr, positive: bool = False) -> sp.Symbol:
        symbol = (sp.Symbol(f"{name}_{self.label}", positive=True) if positive
                  else sp.Symbol(f"{name}_{self.label}", real=True))
        self[symbol] = expr
        return symbol


def _characteristic_length(case: LoopCase) -> sp.Expr:
    """The loop's mean known length, rounded down to a power of two: the unit the closed forms compute in.

    Every formula below is homogeneous in the lengths, so computing with
    lengths divided by this (and scaling unknown lengths back) gives the same
    angles at any scale: 1e-300 or 1e300 as at 1.  The mean, not the sum, so
    that it cannot overflow for any finite lengths; a power of two, so that
    the scaled lengths are the lengths themselves, exactly, only in other units.
    """
    lengths = [v.length for _, v in case.known]
    unknowns = {case.first.symbol, case.second.symbol}
    lengths += [u.vector.length for u in (case.first, case.second)
                if u.part == "angle" and not u.vector.length.free_symbols & unknowns]
    lengths += [v.length for _, v in case.turning]
    if not lengths:
        return sp.S.One
    mean = sp.Add(*(sp.Abs(r) for r in lengths)) / len(lengths)
    # A power of two, so that dividing by it is exact: data that meet a toggle exactly
    # (integers, say) still meet it exactly in loop units, and no length gains a rounding.
    return PowerOfTwoBelow(mean)


def _rounding_size(case: LoopCase, unit) -> sp.Expr:
    """Sum of the known vectors' lengths (in loop units): ``W`` carries a rounding error of a few ulps of it.

    A root's argument is a product with one factor that vanishes at the
    toggle; that factor's rounding error is a few ulps of the loop's size
    (this sum plus the unknown vectors' lengths), and the :class:`ClampedSqrt`
    scale is that size times the other factors' product there: inputs
    within ``TOLERANCE`` times the loop's size of a toggle are taken as at
    the toggle, anything farther out cannot be assembled.
    """
    return sp.Add(*(sp.Abs(unit(v.length)) for _, v in case.known))


def _nonzero_length(squared: sp.Expr, smallest: float = TOLERANCE**2) -> ClampedSqrt:
    """``sqrt(squared)``, but NaN where ``squared`` is below ``smallest`` (in loop units).

    A :class:`ClampedSqrt` with a negative scale: the same printed form in every
    language, exactly ``sqrt`` above the threshold.  It marks configurations
    where a direction is undefined (two points that coincide, parallel guides)
    as not assembled instead of letting ``atan2(0, 0)`` or a division by zero through.
    The default takes a length below ``TOLERANCE`` as zero, for the cases where
    the length itself sets the direction; :data:`_SMALLEST_SQUARE` takes only a
    length that is zero (its square not even a normal number) as zero.
    """
    return ClampedSqrt(squared, -smallest / TOLERANCE)  # NaN below smallest, exactly sqrt above


#: The smallest normal double: a squared length below it is zero (or has lost its digits to underflow).
_SMALLEST_SQUARE = sys.float_info.min


def _two_lengths(case: LoopCase, wx, wy, branch, named, unit, size):
    p, q = case.first, case.second
    tp, tq = p.vector.angle, q.vector.angle
    # sin(tq - tp), written out so that the rates' sin(tq - tp) can be replaced by it without a cycle.
    determinant = _cross(sp.cos(tp), sp.sin(tp), sp.cos(tq), sp.sin(tq))
    if named.loop_units:
        # Parallel unknown lengths: the loop closes nowhere or along a whole line; either way not assembled.
        magnitude = named("Delta", _nonzero_length(determinant**2))
        guarded = sp.sign(determinant) * magnitude
    else:  # Cramer's rule, as a textbook writes it
        guarded = named("Delta", determinant)
    rp = size * _cross(wx, wy, sp.cos(tq), sp.sin(tq)) / (p.sign * guarded)
    rq = size * _cross(sp.cos(tp), sp.sin(tp), wx, wy) / (q.sign * guarded)
    return {p.symbol: _absolute(p, rp), q.symbol: _absolute(q, rq)}


def _length_and_angle_of_one(case: LoopCase, wx, wy, branch, named, unit, size):
    length, angle = (case.first, case.second) if case.first.part == "length" else (case.second, case.first)
    s = length.sign
    # The vector's length is |W|; where W vanishes its angle is undefined: not assembled.
    w = named("w", named.nonzero(wx**2 + wy**2))
    # In loop units the components are divided by w, which is NaN where W vanishes: no direction.
    direction = w if named.loop_units else sp.S.One
    return {
        length.symbol: _absolute(length, size * w),
        angle.symbol: _absolute(angle, sp.atan2(s * wy / direction, s * wx / direction)),
    }


def _length_and_other_angle(case: LoopCase, wx, wy, branch, named, unit, size):
    # p owns the unknown length, q the unknown angle.
    p, q = (case.first, case.second) if case.first.part == "length" else (case.second, case.first)
    tp, rq = p.vector.angle, unit(q.vector.length)
    ux, uy = sp.cos(tp), sp.sin(tp)
    across = _cross(ux, uy, wx, wy)          # s_q r_q sin(t_q - t_p)
    along = ux * wx + uy * wy                # s_p r_p + s_q r_q cos(t_q - t_p)
    # At a toggle one factor vanishes, off by a few ulps of the loop's size,
    # and the other is 2 r_q.
    root = named("Delta", named.clamped((rq - across) * (rq + across),
                                        2 * sp.Abs(rq) * (sp.Abs(rq) + _rounding_size(case, unit))))
    rp = size * (p.sign * along + branch * root)
    tq = tp + sp.atan2(q.sign * across, -p.sign * q.sign * branch * root)
    if q.vector.length.is_positive:
        named.identity(sp.cos, q.vector.angle - tp, -p.sign * q.sign * branch * root / rq, odd=False)
    return {p.symbol: _absolute(p, rp), q.symbol: _absolute(q, tq)}


def _two_angles(case: LoopCase, wx, wy, branch, named, unit, size):
    p, q = case.first, case.second
    sign_q = q.sign * p.sign
    if p.sign < 0:  # walk the loop the other way so that the first vector is added
        wx, wy = -wx, -wy
    rp, rq = unit(p.vector.length), unit(q.vector.length)
    # Triangle P + Q = W with |P| = rp, |Q| = rq: 2w times the components of P
    # along and across W are xp and y; Heron's product keeps y accurate near
    # the toggles, where the triangle is flat.
    if named.loop_units:
        # Generated code needs w only squared (Heron's product and xp, xq are even in w): no square root for it.
        # NaN where the two known points coincide (W = 0): the direction of W, and so the pose, is undefined.
        # Only there: however short W is, if it is not zero the triangle is flat but well defined (a
        # toggle with rp = rq, or just inside one), its pose closes the loop and the root is Heron's.
        w_squared = named("wsq", NonzeroSquare(wx**2 + wy**2, _SMALLEST_SQUARE))
        # Heron's product as ((rp + rq)^2 - w^2) (w^2 - (rp - rq)^2): at a toggle one factor vanishes, off by
        # a few ulps of w times the loop's size (W's components carry a few ulps of the known lengths' sum,
        # and w^2 moves by 2 w times that), and the other is 4 rp rq, so the product's rounding is a few ulps
        # of 8 rp rq w (size).  |Wx| + |Wy| stands in for w there: it is at least w and at most sqrt(2) w,
        # so the clamp tolerates at most sqrt(2) times the rounding the factored form's w tolerated, at
        # any w, and needs no square root.
        heron = ((rp + rq) ** 2 - w_squared) * (w_squared - (rp - rq) ** 2)
        bound = sp.Abs(wx) + sp.Abs(wy)
        scale = 8 * sp.Abs(rp * rq) * bound * (sp.Abs(rp) + sp.Abs(rq) + bound + _rounding_size(case, unit))
    else:
        w = named("w", named.nonzero(wx**2 + wy**2, _SMALLEST_SQUARE))
        w_squared = w**2
        heron = (rp + rq + w) * (rp + rq - w) * (w + rq - rp) * (w + rp - rq)
        scale = sp.S.One
    xp = (rp - rq) * (rp + rq) + w_squared
    xq = (rq - rp) * (rq + rp) + w_squared
    y = branch * named("Delta", named.clamped(heron, scale))
    # Unevaluated: atan2 of symbolic polynomials never simplifies, and asking SymPy whether their signs are
    # known costs assumption queries that grew with the linkage (most of a long chain's derivation).
    tp = sp.atan2(xp * wy + y * wx, xp * wx - y * wy, evaluate=False)
    tq = sp.atan2(sign_q * (xq * wy - y * wx), sign_q * (xq * wx + y * wy), evaluate=False)
    # P = (xp + i y) W / (2 w^2) and Q = (xq - i y) W / (2 w^2), so the cross
    # product P x Q = rp rq sign_q sin(tq - tp) is -y (xp + xq) / (4 w^2) = -y/2.
    if p.vector.length.is_positive and q.vector.length.is_positive:
        named.identity(sp.sin, q.vector.angle - p.vector.angle, -sign_q * y / (2 * rp * rq), odd=True)
    if named.loop_units:
        # The atan2 arguments are (xp + i y) W and (xq - i y) W turned, of lengths |xp + i y| w = 2 rp w^2 and
        # 2 rq w^2 (Heron: xp^2 + y^2 = 4 rp^2 w^2): the rates' cosines and sines need no square root either.
        # Equal to the arguments' own length to a few ulps where the root is not clamped; where it is (within
        # rounding of a toggle, where the rates are not finite anyway) to TOLERANCE times the loop's size.
        named.radii.update({p.symbol: 2 * sp.Abs(rp) * w_squared, q.symbol: 2 * sp.Abs(rq) * w_squared})
    return {p.symbol: _absolute(p, tp), q.symbol: _absolute(q, tq)}


def _length_on_a_turning_body(case: LoopCase, wx, wy, branch, named, unit, size):
    """Case 2c: the unknown angle turns several vectors, one of which has the unknown length.

    With ``theta`` the unknown angle, the turning vectors are ``e^{i theta}``
    times ``s_p r e^{i c_p}`` (the unknown length ``r``) plus a known part ``C``.
    In the frame of the unknown-length vector, ``s_p r + A + i B = W e^{-i(theta + c_p)}``
    with ``A + i B = C e^{-i c_p}``: so ``(s_p r + A)^2 + B^2 = w^2`` fixes ``r`` (two
    branches, +1 the larger ``r``) and the direction of ``W`` fixes ``theta``.
    """
    p, q = (case.first, case.second) if case.first.part == "length" else (case.second, case.first)
    c_p = p.vector.angle - q.symbol
    along = sp.Add(*(sign * unit(v.length) * sp.cos(v.angle - q.symbol - c_p) for sign, v in case.turning))
    across = sp.Add(*(sign * unit(v.length) * sp.sin(v.angle - q.symbol - c_p) for sign, v in case.turning))
    if named.loop_units:
        # Generated code needs w only squared: no square root for it.  At the toggle (w = |A|) w^2 - A^2
        # rounds to a few ulps of w^2, as the factored form does; |Wx| + |Wy| (from w to sqrt(2) w) stands
        # in for w in the clamp's scale.
        bound = sp.Abs(wx) + sp.Abs(wy)
        root = named("Delta", named.clamped(named("wsq", wx**2 + wy**2) - across**2,
                                            2 * sp.Abs(across) * (bound + sp.Abs(across) + _rounding_size(case, unit))))
    else:
        w = named("w", sp.sqrt(wx**2 + wy**2))
        root = named("Delta", named.clamped((w - across) * (w + across), sp.S.One))
    x = p.sign * branch * root              # s_p r + A; branch +1 gives the larger r, as in case 2b
    rp = size * p.sign * (x - along)
    angle = sp.atan2(wy * x - wx * across, wx * x + wy * across) - c_p
    return {p.symbol: _absolute(p, rp), q.symbol: angle}


_SOLVERS = {"1": _two_lengths, "2a": _length_and_angle_of_one, "2b": _length_and_other_angle,
            "2c": _length_on_a_turning_body, "3": _two_angles}


def solve_loop(loop: Loop, unknowns: Sequence[sp.Symbol], branch: sp.Symbol | None = None,
               label: str = "1", *, loop_units: bool = False) -> LoopSolution:
    """Solve ``loop`` for its two ``unknowns`` in closed form.

    ``branch`` is the symbol that carries the assembly sign (+1 or -1) for
    the cases that have two solutions; it is ignored by the others.
    ``label`` tells this loop's intermediates from other loops' (``w_1``).
    ``loop_units`` gives the form generated code computes (see
    :attr:`LoopSolution.in_loop_units`) instead of the textbook form.
    """
    case = loop.case(list(unknowns))
    if case.branches == 2 and branch is None:
        raise ValueError(f"loop {loop.name!r} (case {case.name}) has two assemblies: give a branch symbol")
    named = _Intermediates(label, loop_units)
    scaled: dict[sp.Expr, sp.Symbol] = {}
    if loop_units:
        # Compute in units of the loop's characteristic length, so that any scale gives the same angles.
        size: sp.Expr = named("size", _characteristic_length(case))
    else:
        size = sp.S.One

    def unit(length: sp.Expr) -> sp.Expr:
        """A length in loop units, as a named intermediate (rho_<loop>_<k>) so that no product of
        two lengths (which could overflow or underflow) is ever formed; the length itself in a textbook."""
        if not loop_units:
            return length
        if length.is_number:
            return length / size
        if length not in scaled:
            scaled[length] = named(f"rho_{len(scaled) + 1}", length / size, positive=bool(length.is_positive))
        return scaled[length]

    # W: the vector that the two unknown terms must add up to.
    wx = named("Wx", -sp.Add(*(s * unit(v.length) * sp.cos(v.angle) for s, v in case.known)))
    wy = named("Wy", -sp.Add(*(s * unit(v.length) * sp.sin(v.angle) for s, v in case.known)))
    positions = _SOLVERS[case.name](case, wx, wy, branch, named, unit, size)
    positions = {u: positions[u] for u in unknowns}
    return LoopSolution(loop, case, branch if case.branches == 2 else None, dict(named), positions,
                        named.singular_factors, label, named.radii)
