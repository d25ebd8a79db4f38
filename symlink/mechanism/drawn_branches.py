"""Each loop's branch sign at a drawn pose: the assembly whose closed form gives the drawn unknowns.

A linkage drawn by its joints (:mod:`symlink.mechanism.joints`) has every
unknown's value in the drawing; for each loop with two assemblies, the sign
whose closed form (:attr:`symlink.symbolic.linkage.Linkage.plan`) reproduces
those values is the drawing's branch.  For each sign, each of the loop's
intermediates and positions is evaluated in turn, the worst miss against the
drawing is taken (angles wrapped, lengths relative to the drawing's size), and
the sign that misses least is chosen (+1 on a tie); a drawing that neither
sign reproduces to 1e-7 raises :class:`DrawnPoseError`.

The decision is the one that evaluating every expression at 20 digits gives,
at a fraction of its cost.  Each expression is first evaluated in double
precision with a bound of its rounding error carried along (every sum, product,
power, square root, sine, cosine and atan2 adds its own rounding to what its
arguments bring): where the bounds leave no doubt (the chosen sign misses by
far less than 1e-7 and by less than the other sign, bounds included), that is
the decision; anywhere else (near a toggle, where a square root's argument
might be negative or an atan2's point might be the origin, or for a function
the bound does not know) the loop is evaluated at 20 digits as before.
"""
from __future__ import annotations

import math
from collections import ChainMap
from typing import Mapping, MutableMapping

import sympy as sp

from ..symbolic.linkage import Linkage
from ..symbolic.position import ClampedSqrt

__all__ = ["DrawnPoseError", "drawn_branch_signs", "DRAWN_MISS"]

#: The largest miss (radians, or a fraction of the drawing's size) at which a sign reproduces the drawing.
DRAWN_MISS = 1e-7
#: Double precision's unit roundoff, doubled: every operation's own rounding is bounded by this relative error.
_ROUNDING = 2.0 ** -52
#: How many times its bound a double result may be off before a decision counts as sure (the 20-digit
#: evaluation rounds too, by at most about as much).
_MARGIN = 8.0


class DrawnPoseError(ValueError):
    """The drawing cannot be reproduced (a bug, if the drawing was accepted): never expected."""


class _Unsure(Exception):
    """The double evaluation cannot vouch for its result (a bound too wide, or a function it does not know)."""


def _wrap(angle: float) -> float:
    """An angle in (-pi, pi]."""
    wrapped = math.remainder(angle, 2 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def _value(expr: sp.Expr, values: Mapping[sp.Symbol, float]) -> float:
    """``expr`` at ``values`` with 20 significant digits (SymPy's evalf), as a float."""
    return float(sp.N(expr.xreplace(values), 20))


def _bounded(expr: sp.Expr, values: Mapping[sp.Symbol, tuple[float, float]]) -> tuple[float, float]:
    """``expr`` at ``values`` in double precision and a bound of its error: ``(value, bound)`` such that the exact
    value (every operation exact, on the same inputs, each within its own bound) lies within ``bound`` of
    ``value``.  ``values`` maps each symbol to its value and that value's bound.  ``_Unsure`` where the
    bound cannot be kept (a square root of what may be negative, atan2 of what may be the origin or may
    straddle its cut, a function not known here) or a value is not finite."""
    if expr.is_Symbol:
        try:
            return values[expr]
        except KeyError:
            raise _Unsure from None
    if expr.is_Number:
        value = float(expr)
        exact = expr.is_Integer and abs(value) < 2.0 ** 53
        return value, 0.0 if exact else abs(value) * _ROUNDING
    if expr.is_NumberSymbol:  # pi, E: rounded once
        value = float(expr)
        return value, abs(value) * _ROUNDING
    kind = type(expr)
    args = expr.args
    if expr.is_Add:
        total = width = spread = 0.0
        for arg in args:
            value, bound = _bounded(arg, values)
            total += value
            width += bound
            spread += abs(value) + bound
        return _finite(total, width + 2 * len(args) * _ROUNDING * spread)
    if expr.is_Mul:
        product, high = 1.0, 1.0
        for arg in args:
            value, bound = _bounded(arg, values)
            product *= value
            high *= abs(value) + bound
        return _finite(product, (high - abs(product)) + 4 * len(args) * _ROUNDING * high)
    if expr.is_Pow:
        base, bound = _bounded(args[0], values)
        exponent = args[1]
        if exponent.is_Integer and 0 < exponent <= 8:
            n = int(exponent)
            value, high = base ** n, (abs(base) + bound) ** n
            return _finite(value, (high - abs(value)) + 4 * n * _ROUNDING * high)
        if exponent.is_Integer and -8 <= exponent < 0:
            n = -int(exponent)
            if not abs(base) > 2 * bound:
                raise _Unsure
            value, high = base ** -n, (abs(base) - bound) ** -n
            return _finite(value, (high - abs(value)) + 4 * (n + 1) * _ROUNDING * high)
        if exponent == sp.S.Half:
            return _square_root(base, bound)
        raise _Unsure
    if kind is ClampedSqrt and len(args) == 1:
        return _square_root(*_bounded(args[0], values))
    if kind is sp.cos or kind is sp.sin:
        angle, bound = _bounded(args[0], values)
        return _finite((math.cos if kind is sp.cos else math.sin)(angle), bound + 2 * _ROUNDING)
    if kind is sp.atan2:
        (y, ey), (x, ex) = _bounded(args[0], values), _bounded(args[1], values)
        radius, moved = math.hypot(x, y), ex + ey
        if not radius > 4 * _MARGIN * moved or (x <= _MARGIN * ex and abs(y) <= _MARGIN * ey):
            # near the origin, or maybe across the cut (the 20-digit evaluation's own rounding allowed for)
            raise _Unsure
        return _finite(math.atan2(y, x), 2 * moved / radius + 8 * _ROUNDING)
    raise _Unsure


def _square_root(value: float, bound: float) -> tuple[float, float]:
    if not value - _MARGIN * bound > 0:  # maybe negative (no assembly, or a toggle): only 20 digits can tell
        raise _Unsure
    root = math.sqrt(value)
    return _finite(root, bound / math.sqrt(value - bound) + 2 * _ROUNDING * root)


def _finite(value: float, bound: float) -> tuple[float, float]:
    if not (math.isfinite(value) and math.isfinite(bound)):
        raise _Unsure
    return value, bound


def _misses_bounded(step, values: Mapping[sp.Symbol, float], scale: float) -> dict[int, tuple[float, float]]:
    """Each sign's worst miss against the drawing and its bound, in double precision (``_Unsure``: undecided)."""
    found = {}
    for sign in (1, -1):
        known = _Exact(values)
        known[step.branch] = (float(sign), 0.0)
        for symbol, expr in step.intermediates.items():
            known[symbol] = _bounded(expr, known)
        miss, width = 0.0, 0.0
        for symbol, expr in step.positions.items():
            got, bound = _bounded(expr, known)
            drawn = values[symbol]
            rounding = 2 * _ROUNDING * (abs(got) + abs(drawn))
            if symbol.name.startswith("theta_"):
                this, this_bound = abs(_wrap(got - drawn)), bound + rounding
            else:
                this, this_bound = abs(got - drawn) / scale, (bound + rounding) / scale
            miss, width = max(miss, this), max(width, this_bound)  # the worst of values each within its bound
        found[sign] = (miss, width)
    return found


class _Exact(dict):
    """A loop's values with their bounds: its own (intermediates, branch sign) as set, and over them the drawing's
    values as ``(value, 0.0)``, inputs that both evaluations share, exact as given (looked up as they are asked)."""

    def __init__(self, values: Mapping[sp.Symbol, float]) -> None:
        super().__init__()
        self.drawing = values

    def __missing__(self, symbol):
        found = self[symbol] = (self.drawing[symbol], 0.0)  # KeyError: not a value of the drawing
        return found


def _sure_sign(misses: Mapping[int, tuple[float, float]]) -> int | None:
    """The sign the double misses decide beyond doubt, or None."""
    (plus, plus_bound), (minus, minus_bound) = misses[1], misses[-1]
    best, other = (1, -1) if plus <= minus else (-1, 1)
    best_high = misses[best][0] + _MARGIN * misses[best][1]
    other_low = misses[other][0] - _MARGIN * misses[other][1]
    return best if best_high < DRAWN_MISS / 10 and best_high < other_low else None


def _misses_exact(step, values: dict[sp.Symbol, float], scale: float) -> dict[int, float]:
    """Each sign's worst miss against the drawing, every expression evaluated at 20 digits."""
    misses = {}
    for sign in (1, -1):
        # The loop's own values over the drawing's (no copy of every value of the linkage a loop).
        local: MutableMapping[sp.Symbol, float] = ChainMap({step.branch: sign}, values)
        for symbol, expr in step.intermediates.items():
            local[symbol] = _value(expr, local)
        miss = 0.0
        for symbol, expr in step.positions.items():
            got, drawn = _value(expr, local), values[symbol]
            is_angle = symbol.name.startswith("theta_")
            miss = max(miss, abs(_wrap(got - drawn)) if is_angle else abs(got - drawn) / scale)
        misses[sign] = miss
    return misses


def drawn_branch_signs(linkage: Linkage, values: dict[sp.Symbol, float], scale: float) -> dict[str, int]:
    """Each loop's branch sign at the drawn pose ``values``: the sign whose closed form gives the drawn unknowns.

    Parameters
    ----------
    linkage : Linkage
        A linkage with a closed form (its :attr:`~symlink.symbolic.linkage.Linkage.plan`).
    values : dict of sympy.Symbol to float
        Every parameter, input and unknown at the drawing.
    scale : float
        The drawing's size: a length's miss is relative to it.

    Returns
    -------
    dict of str to int
        Each branch symbol's name and its sign, +1 or -1, in plan order.

    Raises
    ------
    DrawnPoseError
        Neither sign of a loop reproduces the drawing within :data:`DRAWN_MISS`.

    Examples
    --------
    >>> from symlink.mechanism.joints import from_joints
    >>> drawn = from_joints({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
    ...                     {"A": (0, 0), "B": (0, 20), "C": (60, 50), "D": (80, 0)}, driver="A")
    >>> known = {**drawn.parameters, **drawn.pose}
    >>> values = {s: known[s.name] for s in drawn.linkage.parameters + drawn.linkage.coordinates}
    >>> drawn_branch_signs(drawn.linkage, values, 80.0)
    {'branch': 1}
    """
    signs: dict[str, int] = {}
    for step in linkage.plan:
        if step.branch is None:
            continue
        try:
            sure = _sure_sign(_misses_bounded(step, values, scale))
        except _Unsure:
            sure = None
        if sure is not None:
            signs[step.branch.name] = sure
            continue
        misses = _misses_exact(step, values, scale)
        best = min(misses, key=lambda s: (misses[s], -s))
        if not misses[best] < DRAWN_MISS:
            raise DrawnPoseError(f"loop {step.loop.name}: neither assembly reproduces the drawing "
                                 f"(misses {misses[1]:.3g} and {misses[-1]:.3g})")
        signs[step.branch.name] = best
    return signs
