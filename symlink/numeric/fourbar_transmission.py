"""The four-bar's transmission angle over its crank turn, in closed form: SymPy-free (its curve once cached).

The transmission angle mu is the interior angle at C between coupler and rocker, the same on both branches,
from the triangle over the diagonal BD.  :func:`transmission_curve` evaluates it along crank angles with the
catalog four-bar's generated solver of ``transmission`` from the disk cache
(:class:`~symlink.numeric.cached_solver.CachedSolver`, NumPy only), so that a warm drawing of it
(``symlink fourbar --plot-transmission``) imports no SymPy; :func:`transmission_range` finds its extremes
over the reachable turn in closed form (:func:`triangle_angle` of the triangle over BD: no solver, no cache).
:mod:`symlink.analysis.transmission` (the transmission angle of any linkage) shows these under its name too.

>>> [round(math.degrees(x), 2) for x in transmission_curve(20, 66, 56, 80, [0.0, math.pi])]
[58.23, 109.83]
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy

from ..common.angles import wrap_angle
from ..codegen.arguments import check_lengths
from ..common.display import record_html
from ..common.rounding import TOLERANCE
from .cached_solver import CachedSolver
from .crank_ranges import closing_crank_range

__all__ = ["triangle_angle", "TransmissionRange", "transmission_range", "transmission_curve", "transmission_solver"]


def triangle_angle(opposite, side1, side2, clamp: bool = False):
    """The angle between ``side1`` and ``side2`` of a triangle, accurate when it is flat.

    ``atan2`` of Heron's product and the law of cosines, so that angles near 0 and pi
    keep their digits; NaN where the three lengths make no triangle (beyond rounding),
    or with ``clamp`` the flat angle they come nearest to (0 or pi): for a triangle
    known to close, whose lengths only round past flat.  Broadcasts over arrays.

    >>> float(numpy.degrees(triangle_angle(5.0, 3.0, 4.0)))
    90.0
    >>> float(triangle_angle(2.0, 0.5, 1.0)), float(triangle_angle(2.0, 0.5, 1.0, clamp=True))  # 2 > 0.5 + 1
    (nan, 3.141592653589793)
    """
    opposite, side1, side2 = (numpy.asarray(x, dtype=float) for x in (opposite, side1, side2))
    product = ((side1 + side2 + opposite) * (side1 + side2 - opposite)
               * (opposite + side1 - side2) * (opposite - side1 + side2))
    if not clamp:
        product = numpy.where(product >= -TOLERANCE * (side1 + side2 + opposite) ** 4, product, numpy.nan)
    return numpy.arctan2(numpy.sqrt(numpy.maximum(product, 0.0)), side1 * side1 + side2 * side2 - opposite * opposite)


@lru_cache(maxsize=1)
def transmission_solver() -> CachedSolver:
    """The catalog four-bar's solver of ``transmission`` from the disk cache (derived once; NumPy), made once a
    process: its generated check checks the lengths as :func:`symlink.numeric.solver.check_lengths` does.

    >>> transmission_solver().check_lengths(crank=20.0, coupler=0.0)
    Traceback (most recent call last):
    ValueError: coupler must be a positive finite length, got 0.0
    """
    return CachedSolver("fourbar", ["transmission"])


@dataclass(frozen=True)
class TransmissionRange:
    """Smallest and largest transmission angle over the reachable crank angles, and where (radians)."""

    _repr_html_ = record_html  # a notebook shows the fields as a table

    minimum: float
    minimum_at: float
    maximum: float
    maximum_at: float

    @property
    def worst(self) -> float:
        """The smallest of ``min(mu, pi - mu)``: how close the linkage comes to locking."""
        return min(self.minimum, math.pi - self.maximum)


def transmission_range(a: float, b: float, c: float, d: float) -> TransmissionRange:
    """Extremes of the transmission angle mu over every crank angle the four-bar reaches.

    By the law of cosines in the triangles B, C, D and A, B, D, the square of the length of BD is
    ``b^2 + c^2 - 2 b c cos(mu) = a^2 + d^2 - 2 a d cos(theta)``: mu grows with that length, which
    falls with cos(theta).  So mu is smallest at theta = 0 and largest at theta = pi
    when the crank gets there (there BD is ``|d - a|`` and ``d + a`` long, and mu
    is the triangle's angle at C, clamped to 0 or pi where it rounds flat), and
    otherwise at the ends of the crank's range (the toggles, where mu is 0 or pi).
    It is the same on both branches.

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths.

    Returns
    -------
    TransmissionRange
        The smallest and largest transmission angle (radians) and the crank angles where they are.

    Examples
    --------
    >>> import math, symlink
    >>> found = symlink.transmission_range(20, 66, 56, 80)  # BD is 60 long at theta = 0, 100 at pi
    >>> round(math.degrees(found.minimum), 2), round(math.degrees(found.maximum), 2), found.maximum_at
    (58.23, 109.83, 3.141592653589793)
    >>> found = symlink.transmission_range(2, 1, 1, 2)  # B on D at theta = 0; BD = b + c at the toggles
    >>> found.minimum, found.minimum_at, round(math.degrees(found.maximum), 4), round(math.degrees(found.maximum_at), 4)
    (0.0, 0.0, 180.0, -60.0)
    """
    check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    spans = closing_crank_range(a, b, c, d)
    candidates: dict[float, float] = {}
    for theta, diagonal in ((0.0, abs(d - a)), (math.pi, d + a)):
        if any(lo <= theta <= hi or lo <= theta - 2 * math.pi <= hi for lo, hi in spans):
            candidates[theta] = float(triangle_angle(diagonal, b, c, clamp=True))
    if spans != [(-math.pi, math.pi)]:
        far = math.acos(max((a * a + d * d - (b + c) ** 2) / (2 * a * d), -1.0))
        for lo, hi in spans:  # toggles: coupler and rocker in line
            for end in (lo, hi):
                candidates.setdefault(wrap_angle(end), math.pi if math.isclose(abs(wrap_angle(end)), far) else 0.0)
    low = min(candidates, key=candidates.__getitem__)
    high = max(candidates, key=candidates.__getitem__)
    return TransmissionRange(candidates[low], low, candidates[high], high)


def transmission_curve(a: float, b: float, c: float, d: float, theta) -> numpy.ndarray:
    """The transmission angle (radians) at crank angles ``theta``, NaN where it cannot be assembled.

    >>> [round(math.degrees(x), 2) for x in transmission_curve(20, 66, 56, 80, [0.0, math.pi])]
    [58.23, 109.83]
    """
    transmission_solver().check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    solved = transmission_solver()(theta=numpy.asarray(theta, dtype=float), a=a, b=b, c=c, d=d, branch=1)
    return numpy.where(solved["assembled"], solved["transmission"], numpy.nan)
