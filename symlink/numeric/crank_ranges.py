"""Reachable crank ranges in closed form, and the scan and words for any other: plain arithmetic, SymPy-free.

The four-bar's crank range from the triangle over its diagonal, the
slider-crank's from the rod reaching its guide, the five-bar's as a
four-bar, :func:`scanned_range` for a linkage given as a test of assembly
(a scan of a full turn with each edge bisected to rounding), and
:func:`describe_spans` in words.  A warm table command (its solver from the
disk cache) says its reachable range from here without importing SymPy;
:mod:`symlink.numeric.reachability` (the one home of reachable ranges of any
linkage: toggles, margins, design spans) builds on these.

Ranges are lists of closed intervals in radians; ``[(-pi, pi)]`` is a full
turn and an empty list means the linkage closes at no input angle.

>>> [tuple(round(math.degrees(x), 2) for x in span) for span in crank_range(0.3, 0.1, 0.25, 0.30)]
[(-71.37, -28.96), (28.96, 71.37)]
>>> describe_spans(crank_range(60, 30, 50, 40), "deg")
'[-104.478, 104.478] deg'
"""
from __future__ import annotations

import math
from typing import Callable, Mapping

import numpy

__all__ = ["crank_range", "closing_crank_range", "slider_crank_range", "inverted_slider_crank_range", "fivebar_range", "scanned_range",
           "reachable_turn", "turn_angles", "describe_spans", "SCAN_POINTS", "TURN_SAMPLES"]

#: Points a turn of the scan that finds a reachable crank range without a closed form.
SCAN_POINTS = 3600
#: Samples of a full crank turn in the plots: every half degree, both ends included.
TURN_SAMPLES = 721


def crank_range(a: float, b: float, c: float, d: float) -> list[tuple[float, float]]:
    """The crank angles (radians) at which a four-bar can be assembled, as closed intervals.

    The coupler and rocker close a triangle over the diagonal BD when
    ``|b - c| <= |BD| <= b + c``, with ``|BD|^2 = a^2 + d^2 - 2 a d cos(theta)``;
    that bounds ``cos(theta)``.  A full turn is ``[(-pi, pi)]``; an empty list
    means the linkage cannot be assembled at all.

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths.

    Returns
    -------
    list of (float, float)
        The intervals of the crank angle (radians) where it assembles; ``[(-pi, pi)]`` for a full turn.

    Examples
    --------
    >>> import math, symlink
    >>> symlink.crank_range(20, 66, 56, 80) == [(-math.pi, math.pi)]  # seed 003: a Grashof crank-rocker
    True
    >>> [round(math.degrees(x), 4) for x in symlink.crank_range(60, 30, 50, 40)[0]]  # acos(-1/4)
    [-104.4775, 104.4775]
    """
    lowest = (a * a + d * d - (b + c) ** 2) / (2 * a * d)   # cos(theta) at the extended toggle
    highest = (a * a + d * d - (b - c) ** 2) / (2 * a * d)  # cos(theta) at the folded toggle
    if lowest > 1 or highest < -1 or lowest > highest:
        return []
    if lowest <= -1 and highest >= 1:
        return [(-math.pi, math.pi)]
    far = math.acos(max(lowest, -1.0))
    near = math.acos(min(highest, 1.0))
    if highest >= 1:
        return [(-far, far)]
    if lowest <= -1:
        return [(near, 2 * math.pi - near)]
    return [(-far, -near), (near, far)]


def closing_crank_range(a: float, b: float, c: float, d: float) -> list[tuple[float, float]]:
    """:func:`crank_range` of a four-bar that closes somewhere; ``ValueError`` where it closes at no crank angle.

    >>> closing_crank_range(60, 10, 10, 10)
    Traceback (most recent call last):
    ValueError: a four-bar with crank 60, coupler 10, rocker 10 and ground 10 cannot be assembled at any crank angle
    """
    spans = crank_range(a, b, c, d)
    if not spans:
        raise ValueError(f"a four-bar with crank {a:g}, coupler {b:g}, rocker {c:g} and ground {d:g} "
                         "cannot be assembled at any crank angle")
    return spans


def slider_crank_range(a: float, b: float, offset: float) -> list[tuple[float, float]]:
    """The crank angles (radians) at which the slider-crank can be assembled, as closed intervals.

    The rod reaches the guide while ``|offset - a sin(theta)| <= b``, which
    bounds ``sin(theta)``.  A full turn is ``[(-pi, pi)]``; an empty list means
    it cannot be assembled at all.

    >>> [tuple(round(math.degrees(x), 6) for x in span) for span in slider_crank_range(2, 1, 0)]
    [(-30.0, 30.0), (150.0, 210.0)]
    """
    low, high = (offset - b) / a, (offset + b) / a  # the bounds of sin(theta)
    if low > 1 or high < -1:
        return []
    if low <= -1 and high >= 1:
        return [(-math.pi, math.pi)]
    if high >= 1:
        return [(math.asin(low), math.pi - math.asin(low))]
    if low <= -1:
        return [(math.pi - math.asin(high), 2 * math.pi + math.asin(high))]
    return [(math.asin(low), math.asin(high)), (math.pi - math.asin(high), math.pi - math.asin(low))]


def inverted_slider_crank_range(values: Mapping[str, float]) -> list[tuple[float, float]] | str:
    """The inverted slider-crank's crank range: a full turn, or a sentence where B passes over D.

    ``values`` by symbol name: a (crank), d (ground).
    """
    if values["a"] != values["d"]:
        return [(-math.pi, math.pi)]
    return "every crank angle but 0, where B passes over the rocker pivot D and the rocker angle is undetermined"


def fivebar_range(values: Mapping[str, float]) -> list[tuple[float, float]] | str | None:
    """The five-bar's reachable crank range: exact with crank 2 held still, None (scan it) when geared.

    ``values`` by symbol name: a, b, c, d, e, psi (radians) and psi_ratio.
    Crank 2 held still makes a four-bar over the ground A -> D; geared with a
    non-integer ratio the motion is not periodic in the crank angle (a
    sentence says so); with an integer ratio, None: scan the solver.
    """
    ratio = values["psi_ratio"]
    if ratio != 0:
        if ratio != round(ratio):
            return "not periodic in the crank angle for a non-integer --crank2-ratio; not computed"
        return None
    D = values["d"] + values["e"] * complex(math.cos(values["psi"]), math.sin(values["psi"]))
    a, b, c = values["a"], values["b"], values["c"]
    if abs(D) <= 64 * numpy.finfo(float).eps * (values["d"] + values["e"]):  # D on A: |BD| = a everywhere
        return [(-math.pi, math.pi)] if abs(b - c) <= a <= b + c else []
    spans = crank_range(a, b, c, abs(D))
    if spans == [(-math.pi, math.pi)]:
        return spans
    turn = math.atan2(D.imag, D.real)
    shifted = [(low + turn, high + turn) for low, high in spans]
    return [(low - 2 * math.pi, high - 2 * math.pi) if low > math.pi else
            (low + 2 * math.pi, high + 2 * math.pi) if low <= -math.pi else (low, high) for low, high in shifted]


def scanned_range(assembled: Callable[[numpy.ndarray], numpy.ndarray],
                  points: int = SCAN_POINTS) -> list[tuple[float, float]]:
    """The crank angles where ``assembled`` holds, from a scan of a full turn, edges bisected to rounding.

    ``assembled`` maps an array of crank angles (radians) to a boolean mask.
    Intervals as in :func:`symlink.analysis.crank_range`; stretches narrower
    than the scan step (a tenth of a degree) can be missed.

    >>> [tuple(round(math.degrees(x), 9) for x in span) for span in scanned_range(lambda t: numpy.cos(t) >= 0.5)]
    [(-60.0, 60.0)]
    """
    step = 2 * math.pi / points
    grid = -math.pi + step * numpy.arange(points)
    inside = numpy.asarray(assembled(grid), dtype=bool)
    if inside.all():
        return [(-math.pi, math.pi)]
    if not inside.any():
        return []
    edges = numpy.flatnonzero(inside != numpy.roll(inside, -1))
    low, high, rising = grid[edges], grid[edges] + step, ~inside[edges]
    for _ in range(60):
        middle = 0.5 * (low + high)
        same = numpy.asarray(assembled(middle), dtype=bool) == inside[edges]
        low, high = numpy.where(same, middle, low), numpy.where(same, high, middle)
    # The boundary points are reachable: rising edges start at `high`, falling edges end at `low`.
    marks = sorted(zip(numpy.where(rising, high, low).tolist(), rising.tolist()))
    if not marks[0][1]:  # the first interval began before -pi: start it a turn earlier
        marks.append((marks[0][0] + 2 * math.pi, False))
        marks = marks[1:]
    return [(start, end) for (start, _), (end, _) in zip(marks[::2], marks[1::2])]


def reachable_turn(a: float, b: float, c: float, d: float) -> list[tuple[float, float]]:
    """The crank angles in [0, 2 pi] where the four-bar closes, as intervals (radians).

    >>> reachable_turn(20, 66, 56, 80) == [(0.0, 2 * math.pi)]
    True
    """
    full = 2 * math.pi
    pieces = []
    for low, high in crank_range(a, b, c, d):
        if high - low >= full:
            return [(0.0, full)]
        low, high = low % full, high % full
        pieces += [(low, high)] if low <= high else [(0.0, high), (low, full)]
    return sorted(pieces)


def turn_angles(a: float, b: float, c: float, d: float, samples: int = TURN_SAMPLES) -> numpy.ndarray:
    """A full crank turn [0, 2 pi] in ``samples`` even steps plus the exact toggle angles.

    >>> len(turn_angles(0.1, 0.4, 0.25, 0.30, 5)), len(turn_angles(0.3, 0.1, 0.25, 0.30, 5))
    (5, 9)
    """
    even = numpy.linspace(0.0, 2 * math.pi, samples)
    toggles = [bound for piece in reachable_turn(a, b, c, d) for bound in piece]
    return numpy.unique(numpy.concatenate([even, toggles]))


def describe_spans(spans: list[tuple[float, float]], units: str) -> str:
    """A reachable input range in words: ``full turn``, intervals in ``units``, or none."""
    if not spans:
        return "none: the links cannot close at any crank angle"
    convert = math.degrees if units == "deg" else float
    if spans == [(-math.pi, math.pi)]:
        return "full turn"
    return ", ".join(f"[{convert(lo):.6g}, {convert(hi):.6g}] {units}" for lo, hi in spans)
