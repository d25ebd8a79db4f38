"""The four-bar's transmission angle over its crank turn, in closed form: SymPy-free once its solver is cached.

The transmission angle mu is the interior angle at C between coupler and rocker, the same on both branches,
from the triangle over the diagonal BD.  :func:`transmission_curve` evaluates it along crank angles and
:func:`transmission_range` finds its extremes over the reachable turn, both with the catalog four-bar's
generated solver of ``transmission`` from the disk cache
(:class:`~symlink.numeric.cached_solver.CachedSolver`, NumPy only), so that a warm drawing of it
(``symlink fourbar --plot-transmission``) imports no SymPy.  :mod:`symlink.analysis.transmission` (the
transmission angle of any linkage) shows these under its name too.

>>> [round(math.degrees(x), 2) for x in transmission_curve(20, 66, 56, 80, [0.0, math.pi])]
[58.23, 109.83]
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy

from ..common.angles import wrap_angle
from ..common.display import record_html
from .cached_solver import CachedSolver
from .crank_ranges import closing_crank_range

__all__ = ["TransmissionRange", "transmission_range", "transmission_curve", "transmission_solver"]


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

    ``|BD|^2 = b^2 + c^2 - 2 b c cos(mu) = a^2 + d^2 - 2 a d cos(theta)``: mu grows with
    |BD|, which falls with cos(theta).  So mu is smallest at theta = 0 and largest at
    theta = pi when the crank gets there, and otherwise at the ends of the crank's range
    (the toggles, where mu is 0 or pi).  It is the same on both branches; the generated
    solver evaluates it at those crank angles.

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
    >>> found = symlink.transmission_range(20, 66, 56, 80)  # |BD| = 60 at theta = 0, 100 at pi
    >>> round(math.degrees(found.minimum), 2), round(math.degrees(found.maximum), 2), found.maximum_at
    (58.23, 109.83, 3.141592653589793)
    """
    transmission_solver().check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    spans = closing_crank_range(a, b, c, d)
    candidates: dict[float, float] = {}
    reachable = [x for x in (0.0, math.pi) if any(lo <= x <= hi or lo <= x - 2 * math.pi <= hi
                                                  for lo, hi in spans)]
    if reachable:
        solved = transmission_solver()(theta=numpy.array(reachable), a=a, b=b, c=c, d=d, branch=1)
        candidates.update(zip(reachable, (float(mu) for mu in solved["transmission"])))
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
