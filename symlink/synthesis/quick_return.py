"""Quick-return synthesis of a crank-rocker four-bar (the MATLAB quick-return paper, after Norton), done exactly.

A crank-rocker's rocker swings between two extremes B1 and B2, reached where crank and
coupler are in line: at the extended one C is ``a + b`` from the crank pivot O2, at the
folded one ``b - a``.  So for a crank pivot P:

* crank ``a = (|P Be| - |P Bf|) / 2`` and coupler ``b = (|P Be| + |P Bf|) / 2``, where Be,
  the extreme farther from P, is the extended one, and Bf the folded one;
* between the two, the crank turns ``180 deg + delta`` one way and ``180 deg - delta`` the
  other, where ``delta`` is the angle Be P Bf; the time ratio is their quotient, so a
  ratio TR needs ``delta = 180 deg (TR - 1) / (TR + 1)``.

The rocker pivot O4 is at the origin; the rocker's minimum angle and the stroke fix B1 and
B2 (``rocker`` from O4 at ``rocker_min_angle`` and at ``rocker_min_angle + stroke``).

* With a given crank pivot (:func:`quick_return` with ``crank_pivot``), the paper's
  procedure: the lengths follow from the pivot, and the stroke is met, but the time ratio
  is whatever the pivot's angle ``delta`` gives (1.115 for the paper's 1.25), and a
  warning says so.
* Without one, P goes on the arc from which B1 B2 subtends ``delta`` (inscribed angle), so
  time ratio and stroke are both exact, and its place on the arc is chosen to maximise
  the worst transmission angle over a turn (the smallest of ``min(mu, 180 deg - mu)``).

Either way the result is analysed afresh (:mod:`symlink.analysis`, with the generated
four-bar solver): Grashof class, limit positions, stroke, time ratio, transmission range.

>>> design = quick_return(1.25, math.radians(40), 50)
>>> round(design.time_ratio, 9), round(math.degrees(design.stroke), 9)
(1.25, 40.0)
>>> round(math.degrees(design.transmission.worst), 2)
42.81
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy

from ..analysis import (LimitPositions, TransmissionRange, grashof, limit_positions, transmission_range,
                       triangle_angle, wrap_angle)
from ..common.display import record_html
from ..numeric.solver import check_lengths

__all__ = ["QuickReturn", "quick_return", "delta_for_time_ratio", "GOOD_TRANSMISSION", "MAX_LINK_RATIO",
           "as_record"]

#: The usual lower bound on the worst transmission angle (radians): 45 deg.
GOOD_TRANSMISSION = math.pi / 4

#: Default largest ratio of the longest link to the crank in the search for the best design.
MAX_LINK_RATIO = 10.0

_SAMPLES = 4001       # points per family of crank pivots before refining
_GOLDEN_STEPS = 90    # golden-section steps: the bracket shrinks by 0.618**90, about 1e-19


@dataclass(frozen=True)
class QuickReturn:
    """A synthesized quick-return crank-rocker and what it really does (lengths, radians).

    Frame: the rocker pivot O4 at the origin.  ``ground_angle`` is the direction of the
    ground line from the crank pivot to the rocker pivot; crank angles in ``limits`` and
    ``transmission`` are measured from it (the four-bar convention of the README), and
    ``branch`` is the assembly on which the rocker passes through B1 and B2.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    crank: float
    coupler: float
    rocker: float
    ground: float
    crank_pivot: tuple[float, float]
    ground_angle: float
    branch: int
    requested_time_ratio: float
    requested_stroke: float
    method: str
    grashof: str
    limits: LimitPositions
    transmission: TransmissionRange
    warnings: tuple[str, ...]

    rocker_pivot = (0.0, 0.0)

    @property
    def stroke(self) -> float:
        return self.limits.stroke

    @property
    def time_ratio(self) -> float:
        return self.limits.time_ratio

    @property
    def rocker_extremes(self) -> tuple[float, float]:
        """The rocker's angles at its two extremes, in the O4 frame (extended first)."""
        return (wrap_angle(self.limits.extended_rocker + self.ground_angle),
                wrap_angle(self.limits.folded_rocker + self.ground_angle))


def delta_for_time_ratio(time_ratio: float) -> float:
    """The angle ``delta`` (radians) that the rocker's extremes subtend at the crank pivot.

    >>> round(math.degrees(delta_for_time_ratio(1.25)), 9)
    20.0
    """
    return math.pi * (time_ratio - 1) / (time_ratio + 1)


def _check_request(time_ratio: float, stroke: float, rocker: float) -> None:
    if not math.isfinite(time_ratio) or time_ratio < 1:
        raise ValueError(f"the time ratio must be a finite number of at least 1 (slow stroke over quick "
                         f"stroke), got {time_ratio:g}")
    if not math.isfinite(stroke) or not 0 < stroke < math.pi:
        raise ValueError(f"the stroke must lie strictly between 0 and 180 deg, got {math.degrees(stroke):g} deg")
    check_lengths(rocker=rocker)


def _rocker_ends(rocker: float, rocker_min_angle: float, stroke: float) -> numpy.ndarray:
    """B1 and B2, the rocker's tip at its minimum angle and at minimum + stroke (rows)."""
    angles = numpy.array([rocker_min_angle, rocker_min_angle + stroke])
    return rocker * numpy.stack([numpy.cos(angles), numpy.sin(angles)], axis=-1)


def _crank_rocker_worst(a, b, c, d, max_link_ratio=math.inf):
    """Worst transmission angle of crank-rockers (vectorised); -inf where it is not a crank-rocker.

    Closed form used to search: mu is extreme where the crank lies on the ground line,
    ``|BD| = d - a`` and ``d + a`` (see :func:`symlink.analysis.transmission_range`).
    Linkages whose longest link exceeds ``max_link_ratio`` times the crank count as -inf.
    """
    links = numpy.stack(numpy.broadcast_arrays(a, b, c, d))
    longest = links.max(axis=0)
    others = links[1:].min(axis=0)
    with numpy.errstate(invalid="ignore"):
        crank_rocker = ((a > 0) & (a < others) & (a + longest < links.sum(axis=0) - a - longest)
                        & (longest <= max_link_ratio * a))
        worst = numpy.minimum(triangle_angle(abs(d - a), b, c), numpy.pi - triangle_angle(d + a, b, c))
    return numpy.where(crank_rocker & numpy.isfinite(worst), worst, -numpy.inf)


def _pivots(v, family: int, ends: numpy.ndarray, delta: float) -> numpy.ndarray:
    """Crank pivots P at which B1 B2 subtends ``delta``, parametrised by ``v`` in (0, 1).

    With u = chord / (2 b) running from sin(delta/2) to 1, the triangle B1 B2 P has the
    angle kappa' - delta/2 at B1, where sin(kappa') = sin(delta/2) / u, and
    ``|P B1| = b + chord cos(kappa') / (2 cos(delta/2))``.  ``family`` picks the side of
    B1 B2 (bit 0) and kappa' or pi - kappa' (bit 1); the form stays finite as delta -> 0
    (time ratio 1: P on the line B1 B2, outside the segment).
    """
    v = numpy.asarray(v, dtype=float)
    chord_vector = ends[1] - ends[0]
    chord = math.hypot(*chord_vector)
    half = math.sin(delta / 2)
    u = half + (1 - half) * v
    sin_k = half / u
    cos_k = numpy.sqrt(numpy.maximum(1 - sin_k * sin_k, 0.0)) * (1 if family & 2 == 0 else -1)
    kappa = numpy.arctan2(sin_k, cos_k) - delta / 2
    side = 1 if family & 1 == 0 else -1
    distance = chord / (2 * u) + chord * cos_k / (2 * math.cos(delta / 2))
    direction = kappa * side + math.atan2(chord_vector[1], chord_vector[0])
    return ends[0] + numpy.stack([distance * numpy.cos(direction), distance * numpy.sin(direction)], axis=-1)


def _linkage_at(pivots: numpy.ndarray, ends: numpy.ndarray):
    """Crank, coupler and ground of the construction for crank pivots (rows of ``pivots``).

    Where B1 and B2 lie on different sides of the ground line (crank pivot to O4) they
    are on different assembly branches, so no one linkage reaches both: the crank is
    given as NaN there.
    """
    far = numpy.linalg.norm(pivots[..., None, :] - ends, axis=-1)
    extended, folded = far.max(axis=-1), far.min(axis=-1)
    x, y = pivots[..., 0], pivots[..., 1]
    sides = [-x * (end[1] - y) + y * (end[0] - x) for end in ends]  # (O4 - P) x (B - P)
    crank = numpy.where(sides[0] * sides[1] > 0, (extended - folded) / 2, numpy.nan)
    return crank, (extended + folded) / 2, numpy.hypot(x, y)


def _worst_at(v, family, ends, delta, rocker, max_link_ratio):
    a, b, d = _linkage_at(_pivots(v, family, ends, delta), ends)
    return _crank_rocker_worst(a, b, rocker, d, max_link_ratio)


def _best_pivot(ends: numpy.ndarray, delta: float, rocker: float, max_link_ratio: float) -> numpy.ndarray | None:
    """The crank pivot on the delta-arcs with the largest worst transmission angle (None: no crank-rocker).

    A grid over each family of pivots, then golden-section search around the best point
    (the worst angle is unimodal there, or rises to the link-ratio limit).  The maximum
    is flat, so its value comes out to rounding while the pivot's place on the arc is
    known to about 1e-8 relative; time ratio and stroke are exact anywhere on the arc.
    """
    grid = (numpy.arange(_SAMPLES) + 0.5) / _SAMPLES
    best = (-math.inf, 0, 0.0)
    for family in range(4):
        worst = _worst_at(grid, family, ends, delta, rocker, max_link_ratio)
        i = int(numpy.argmax(worst))
        if worst[i] > best[0]:
            best = (float(worst[i]), family, float(grid[i]))
    if not math.isfinite(best[0]):
        return None
    _, family, start = best
    low, high = max(start - 1 / _SAMPLES, 0.0), min(start + 1 / _SAMPLES, 1.0)
    ratio = (math.sqrt(5) - 1) / 2
    for _ in range(_GOLDEN_STEPS):
        left, right = high - ratio * (high - low), low + ratio * (high - low)
        values = _worst_at(numpy.array([left, right]), family, ends, delta, rocker, max_link_ratio)
        best = max(best, (float(values[0]), family, left), (float(values[1]), family, right))
        if values[0] >= values[1]:
            high = right
        else:
            low = left
    return _pivots(best[2], family, ends, delta)


def quick_return(time_ratio: float, stroke: float, rocker: float, rocker_min_angle: float = math.pi / 2,
                 crank_pivot: tuple[float, float] | None = None,
                 max_link_ratio: float = MAX_LINK_RATIO) -> QuickReturn:
    """Synthesize a quick-return crank-rocker (angles in radians, O4 at the origin).

    With ``crank_pivot`` it follows the paper with that pivot fixed; without, it meets
    ``time_ratio`` and ``stroke`` exactly with the best worst transmission angle among
    the designs whose longest link is at most ``max_link_ratio`` times the crank (near a
    time ratio of 1 the worst angle keeps improving as coupler and ground grow without
    bound; a warning says when the limit decides the design).
    ``ValueError`` for impossible requests (time ratio below 1, stroke not strictly
    between 0 and 180 deg, a rocker that is not positive) and pivots that give no
    crank-rocker.  See the module's docstring for the construction.

    Parameters
    ----------
    time_ratio : float
        The time of the slow stroke over the quick one (above 1).
    stroke : float
        The rocker's swing (radians, strictly between 0 and pi).
    rocker : float
        The rocker's length.
    rocker_min_angle : float, optional
        The rocker's angle at its first limit (default pi / 2).
    crank_pivot : (float, float), optional
        Fix the crank pivot, as the paper does (default: the best one).
    max_link_ratio : float, optional
        The longest link over the crank, at most (default 10).

    Returns
    -------
    QuickReturn
        The crank-rocker, its time ratio, stroke and transmission angles.

    Raises
    ------
    ValueError
        For impossible requests and pivots that give no crank-rocker.

    Examples
    --------
    >>> import math, symlink
    >>> design = symlink.quick_return(1.25, math.radians(40), 50)
    >>> round(design.time_ratio, 9), round(math.degrees(design.stroke), 9)
    (1.25, 40.0)
    """
    _check_request(time_ratio, stroke, rocker)
    rocker = float(rocker)
    if not math.isfinite(rocker_min_angle):
        raise ValueError(f"the rocker's minimum angle must be finite, got {rocker_min_angle}")
    ends = _rocker_ends(rocker, rocker_min_angle, stroke)
    delta = delta_for_time_ratio(time_ratio)
    if crank_pivot is not None:
        pivot = numpy.array(crank_pivot, dtype=float)
        if pivot.shape != (2,) or not numpy.all(numpy.isfinite(pivot)):
            raise ValueError(f"the crank pivot must be two finite coordinates, got {crank_pivot}")
        method = "fixed crank pivot"
    else:
        if not max_link_ratio > 1:
            raise ValueError(f"the largest link ratio must be more than 1, got {max_link_ratio:g}")
        best = _best_pivot(ends, delta, rocker, max_link_ratio)
        if best is None:
            raise ValueError(f"no crank-rocker gives a time ratio of {time_ratio:g} with a stroke of "
                             f"{math.degrees(stroke):g} deg")
        pivot = best
        method = "best transmission angle"
    design = _analyse(pivot, ends, rocker, time_ratio, stroke, method)
    if crank_pivot is None and max(design.coupler, design.ground, rocker) > (1 - 1e-6) * max_link_ratio * design.crank:
        note = (f"the longest link is limited to {max_link_ratio:g} times the crank; longer links would give "
                "a better worst transmission angle")
        design = replace(design, warnings=design.warnings + (note,))
    return design


def _analyse(pivot: numpy.ndarray, ends: numpy.ndarray, rocker: float, time_ratio: float, stroke: float,
             method: str) -> QuickReturn:
    """The four-bar that the construction gives for ``pivot``, analysed afresh."""
    x, y = (float(v) for v in pivot)
    far = numpy.linalg.norm(ends - pivot, axis=-1)
    if min(far.min(), math.hypot(x, y)) <= 1e-12 * rocker:
        raise ValueError(f"the crank pivot ({x:g}, {y:g}) coincides with the rocker pivot or a rocker end")
    crank, coupler = float(far.max() - far.min()) / 2, float(far.max() + far.min()) / 2
    if crank <= 1e-12 * coupler:
        raise ValueError(f"the crank pivot ({x:g}, {y:g}) is equally far from both rocker ends: "
                         "the crank would have no length")
    ground = math.hypot(x, y)
    check_lengths(crank=crank, coupler=coupler, rocker=rocker, ground=ground)
    kind = grashof(crank, coupler, rocker, ground)
    if kind.name != "crank-rocker":
        raise ValueError(f"with the crank pivot at ({x:g}, {y:g}) the linkage (crank {crank:g}, coupler "
                         f"{coupler:g}, rocker {rocker:g}, ground {ground:g}) is a {kind.name}, not a "
                         "crank-rocker: the crank cannot turn fully")
    extended = ends[int(numpy.argmax(far))]
    to_rocker = -pivot
    branch = 1 if to_rocker[0] * (extended[1] - y) - to_rocker[1] * (extended[0] - x) > 0 else -1
    limits = limit_positions(crank, coupler, rocker, ground, branch)
    transmission = transmission_range(crank, coupler, rocker, ground)
    warnings = []
    if not math.isclose(limits.time_ratio, time_ratio, rel_tol=1e-9):
        change = limits.time_ratio - time_ratio
        warnings.append(f"the requested time ratio {time_ratio:g} is not met: this crank pivot gives "
                        f"{limits.time_ratio:.4f} ({change:+.4f}, {100 * change / time_ratio:+.1f}%); "
                        "without a fixed crank pivot the time ratio is met exactly")
    if not math.isclose(limits.stroke, stroke, rel_tol=1e-9):
        warnings.append(f"the rocker swings {math.degrees(limits.stroke):.4f} deg, not the requested "
                        f"{math.degrees(stroke):g} deg: its two end positions lie on opposite sides of the "
                        "ground line, on different assembly branches, and no one linkage reaches both")
    if transmission.worst < GOOD_TRANSMISSION:
        best = ", the best reachable for this time ratio and stroke," if method.startswith("best") else ""
        warnings.append(f"the worst transmission angle is {math.degrees(transmission.worst):.2f} deg{best} "
                        f"below the usual {math.degrees(GOOD_TRANSMISSION):g} deg")
    return QuickReturn(crank, coupler, rocker, ground, (x + 0.0, y + 0.0), math.atan2(-y, -x) + 0.0, branch,
                       time_ratio, stroke, method, kind.name, limits, transmission, tuple(warnings))


# --- command line ---------------------------------------------------------------------

def as_record(design: QuickReturn) -> dict:
    """The design as JSON-ready values: lengths in the rocker's unit, angles in degrees."""
    deg = math.degrees
    return {
        "crank": design.crank, "coupler": design.coupler, "rocker": design.rocker, "ground": design.ground,
        "crank_pivot": list(design.crank_pivot), "rocker_pivot": list(design.rocker_pivot),
        "stroke": deg(design.stroke), "time_ratio": design.time_ratio,
        "transmission_min": deg(design.transmission.minimum),
        "transmission_max": deg(design.transmission.maximum),
        "grashof": design.grashof,
        "worst_transmission": deg(design.transmission.worst),
        "transmission_min_at": deg(design.transmission.minimum_at),
        "transmission_max_at": deg(design.transmission.maximum_at),
        "rocker_extremes": [deg(angle) for angle in design.rocker_extremes],
        "ground_angle": deg(design.ground_angle),
        "branch": design.branch,
        "requested_time_ratio": design.requested_time_ratio,
        "requested_stroke": deg(design.requested_stroke),
        "method": design.method,
        "warnings": list(design.warnings),
    }
