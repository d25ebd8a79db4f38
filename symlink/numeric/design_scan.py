"""The reachable spans of many designs at once, from the margins of their clamped roots: NumPy only, no SymPy.

A linkage in closed form closes where every clamped square root of its solve plan has a non-negative argument;
generated code gives each root's argument over its scale, its *margin* (:func:`symlink.numeric.reachability.
design_spans` derives it from a linkage).  :func:`margin_spans` scans a turn of the input for every design at once
and bisects each edge to rounding, given only the margins' function and the names of its roots, so that a sweep
whose margins are in the disk cache scans its designs without the linkage.  The scan's helpers (edges, bisection,
spans from marks) serve :mod:`symlink.numeric.reachability` too.

>>> def margins(check=True, theta=None, a=None):  # one root: closes where a cos(theta) >= -1/2
...     margin = numpy.asarray(a * numpy.cos(theta) + 0.5, dtype=float)
...     return {"margin_0": margin, "assembled": margin >= 0}
>>> spans = margin_spans(margins, [("margin_0", "L")], ["a"], [], "theta", {"a": numpy.array([1.0, 0.25])}, 2, 0.0)
>>> [[tuple(round(math.degrees(x), 6) for x in span) for span in found] for found in spans]
[[(-120.0, 120.0)], [(-180.0, 180.0)]]
"""
from __future__ import annotations

import math
from typing import Any, Callable, Mapping, Sequence

import numpy

from ..codegen.arguments import checked_arguments
from .compiled_library import BUILD_WAIT
from .crank_ranges import SCAN_POINTS

__all__ = ["margin_spans", "fastest_margins", "BISECTIONS", "COARSE_STRIDE", "NEAR_CHANGES", "NEAR_ZERO"]

#: Bisection steps that take a scan step (a tenth of a degree) down to rounding: 2^-60 of it.
BISECTIONS = 60
#: The coarse scan of :func:`design_spans` takes every this many points of the full scan (every 2 degrees of a
#: turn scanned at a tenth of a degree); the points between are evaluated only where the coarse scan cannot
#: rule out a change.  Measured on 5,000 random Watt II, Jansen, slider-crank and five-bar designs: the same
#: spans, to the bit, as scanning every point, at strides 10 to 60; about 11 times fewer margin evaluations.
COARSE_STRIDE = 20
#: A coarse cell is refined where a margin at either end is nearer zero than this many times the largest change
#: of that margin over the cell or its two neighbours: a margin that dips below zero inside a cell and is back
#: above it at both ends (a parabola) changes over a neighbour cell by more than 8 times its larger end value,
#: so 1 leaves a factor of 8 to spare.
NEAR_CHANGES = 1.0
#: ...or nearer zero than this at all (a root that touches zero, a toggle passed through, which the full scan's
#: rounding may see on either side).
NEAR_ZERO = 1e-6



def margin_spans(margins: Callable[..., dict[str, Any]], roots: Sequence[tuple[str, str]], lengths: Sequence[str],
                 branches: Sequence[str], driven: str, values: Mapping[str, Any], count: int, tolerance: float, *,
                 points: int = SCAN_POINTS, block: int = 1 << 18,
                 stride: int = COARSE_STRIDE) -> list[list[tuple[float, float]]]:
    """The reachable spans over a turn of the input ``driven`` of ``count`` designs at once (see the module).

    ``margins(check=False, **values)``: every root's margin by name (``margin_k``; ``guard_k`` for a length
    that must not vanish) and ``assembled``, of numbers or arrays; ``roots``: (margin name, loop) in plan order;
    ``lengths`` and ``branches``: the names checked as such; ``values``: every parameter, branch sign and held
    input by name, a number or an array of ``count``; ``tolerance``: the rounding a root's argument may fall
    below zero by (:data:`symlink.symbolic.position.TOLERANCE`).  The scan as
    :func:`symlink.numeric.reachability.design_spans` describes it.
    """
    if points < 4:
        raise ValueError(f"scan at least 4 points, got {points}")
    if isinstance(stride, bool) or not isinstance(stride, int) or stride < 1:
        raise ValueError(f"the coarse scan's stride must be a whole number, at least 1; got {stride!r}")
    step = 2 * math.pi / points
    arrays = {name: numpy.ascontiguousarray(numpy.broadcast_to(numpy.asarray(value, dtype=float), (count,)))
              for name, value in values.items()}
    # checked once, here (a ValueError naming the first bad value); the calls below check nothing again
    checked_arguments(list(arrays), list(arrays.values()), list(lengths), list(branches))
    grid = -math.pi + step * numpy.arange(points)
    following = numpy.append(grid, grid[0] + 2 * math.pi)

    def of(rows: numpy.ndarray) -> dict[str, numpy.ndarray]:
        """The values of designs ``rows``, gathered once for the calls on them (each bisection's steps)."""
        return {name: array[rows] for name, array in arrays.items()}

    def margin_values(at: numpy.ndarray, chosen: dict[str, numpy.ndarray]) -> dict[str, numpy.ndarray]:
        """The margins at input values ``at`` of the designs whose values are ``chosen`` (1-d arrays alike), a block
        at a time."""
        found: dict[str, numpy.ndarray] = {}
        for first in range(0, at.size, block):
            part = slice(first, first + block)
            whole = first == 0 and at.size <= block
            with numpy.errstate(all="ignore"):  # the values were checked above
                some = margins(**{driven: at if whole else at[part]},
                               **{name: value if whole else value[part] for name, value in chosen.items()},
                               check=False)
            if whole:
                return some
            for name, value in some.items():
                found.setdefault(name, numpy.empty(at.size, dtype=numpy.asarray(value).dtype))[part] = value
        return found

    def coarse_values(at: numpy.ndarray) -> dict[str, numpy.ndarray]:
        """The margins of every design at the input values ``at``: arrays of (designs, len(at)), one call."""
        found = margin_values(numpy.tile(at, count), {name: numpy.repeat(array, at.size) for name, array in arrays.items()})
        return {name: numpy.asarray(value).reshape(count, at.size) for name, value in found.items()}

    design, edge, before, inside_everywhere = _scanned_edges(
        coarse_values, lambda at, rows: margin_values(at, of(rows))["assembled"], [name for name, _ in roots],
        grid, count, stride if points % stride == 0 else 1)
    spans: list[list[tuple[float, float]]] = [[(-math.pi, math.pi)] if whole else [] for whole in inside_everywhere]
    if not design.size:
        return spans
    start, end = grid[edge], following[edge + 1]
    # Each edge is bisected on the mask and, at once, on the sign of every root's argument (the clamp takes
    # rounding below zero as the toggle itself: an edge where a root fails ends where its argument changes
    # sign), one margins call a step for them all; the root that fails beyond the mask's edge says which of
    # those bisections is the edge's.  Each bracket's steps are its own: the same bounds as bisecting them apart.
    tests = ["assembled"] + [name for name, _ in roots if name.startswith("margin")]
    edges = design.size
    tiled_of = of(numpy.tile(design, len(tests)))

    def closes(at: numpy.ndarray) -> numpy.ndarray:
        found = margin_values(at, tiled_of)
        result = numpy.asarray(found["assembled"], dtype=bool).copy()
        for k, name in enumerate(tests[1:], start=1):
            part = slice(k * edges, (k + 1) * edges)
            result[part] = numpy.asarray(found[name][part]) - tolerance >= 0
        return result

    lows, highs = _bisect(closes, numpy.tile(start, len(tests)), numpy.tile(end, len(tests)),
                          numpy.tile(before, len(tests)))
    in_low, out_high = lows[:edges], highs[:edges]
    rising = ~before
    beyond = margin_values(numpy.where(rising, in_low, out_high), of(design))
    failing = numpy.full(edges, -1)
    for k, (name, _) in reversed(list(enumerate(roots))):  # the first root whose margin is negative
        failing = numpy.where(numpy.asarray(beyond[name]) < 0, k, failing)
    at_low, at_high = in_low.copy(), out_high.copy()
    for k, (name, _) in enumerate(roots):
        chosen = numpy.flatnonzero(failing == k)
        if chosen.size and name.startswith("margin"):
            part = tests.index(name) * edges + chosen
            at_low[chosen], at_high[chosen] = lows[part], highs[part]
    bounds = numpy.where(rising, at_high, at_low)  # the reachable side of each edge
    for row in numpy.unique(design).tolist():
        mine = design == row
        marks = sorted(zip(bounds[mine].tolist(), rising[mine].tolist()))
        spans[row] = _spans_from_marks(marks, True, float(grid[0]), float(grid[-1]))
    return spans


def fastest_margins(numpy_margins: Callable[..., dict[str, Any]], c_facts: Callable[[], str | None],
                    lengths: Sequence[str], branches: Sequence[str]) -> Callable[..., dict[str, Any]]:
    """The margins in the compiled C loop where a compiler works, else ``numpy_margins`` (their NumPy module).

    ``c_facts()``: their C and its calling facts (:func:`symlink.numeric.compiled_library.program_facts`, JSON;
    None where there is none).  The library is built once into the cache; where it is being built, it is waited
    for (at most :data:`~symlink.numeric.compiled_library.BUILD_WAIT` seconds), so that the spans of a sweep's
    chunks never depend on when a build finished.  The compiled margins are called with keywords, and check
    their values as the NumPy module does (``lengths``, ``branches``) unless told ``check=False``; they say so
    (``compiled``).
    """
    import json
    from . import compiled_library as compiled
    if compiled.chosen_backend() == "numpy":
        return numpy_margins
    try:
        text = c_facts()
        facts = None if text is None else json.loads(text)
        entry = None if facts is None else compiled.compiled_or_building(facts)
        if entry is None and facts is not None and compiled.compiler_works():  # being built: one code for every scan
            building = compiled.build_in_background(facts)
            building.wait(BUILD_WAIT)
            entry = building.entry()
    except (OSError, ValueError, RuntimeError):
        entry = None
    if entry is None:
        return numpy_margins
    lengths, branches = list(lengths), list(branches)

    def margins(check: bool = True, **values: Any) -> dict[str, Any]:
        if check:  # the NumPy module's check of every value (ValueError naming the first bad one)
            checked_arguments(list(values), list(values.values()), lengths, branches)
        return entry(**values)
    margins.compiled = True  # type: ignore[attr-defined]
    return margins


def _edges(inside: numpy.ndarray, periodic: bool) -> numpy.ndarray:
    """Indices i where the mask changes between grid points i and i + 1 (and around, if periodic)."""
    if periodic:
        return numpy.flatnonzero(inside != numpy.roll(inside, -1))
    return numpy.flatnonzero(inside[:-1] != inside[1:])


def _bisect(test: Callable[[numpy.ndarray], numpy.ndarray], low: numpy.ndarray, high: numpy.ndarray,
            low_value: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
    """Bisect brackets [low, high] where ``test`` changes from ``low_value``, to rounding.

    Stops once no bracket can shrink (its midpoint rounds to an end): later steps would change nothing.
    """
    for _ in range(BISECTIONS):
        middle = 0.5 * (low + high)
        if numpy.all((middle == low) | (middle == high)):
            break
        same = numpy.asarray(test(middle), dtype=bool) == low_value
        low, high = numpy.where(same, middle, low), numpy.where(same, high, middle)
    return low, high


def _spans_from_marks(marks: list[tuple[float, bool]], periodic: bool, first: float, last: float):
    """Closed intervals from sorted (boundary, rising) marks."""
    if periodic and not marks[0][1]:  # the first interval began before the scan: start it a turn earlier
        marks = marks[1:] + [(marks[0][0] + 2 * math.pi, False)]
    if not periodic:
        if not marks[0][1]:
            marks = [(first, True)] + marks
        if marks[-1][1]:
            marks = marks + [(last, False)]
    return [(start, end) for (start, _), (end, _) in zip(marks[::2], marks[1::2])]


def _scanned_edges(coarse_values: Callable[[numpy.ndarray], dict[str, numpy.ndarray]],
                   assembled: Callable[[numpy.ndarray, numpy.ndarray], numpy.ndarray], names: list[str],
                   grid: numpy.ndarray, count: int, stride: int
                   ) -> tuple[numpy.ndarray, numpy.ndarray, numpy.ndarray, numpy.ndarray]:
    """Where a scan of every point of the periodic ``grid`` sees each of ``count`` designs open or close.

    Returns ``(design, index, before, everywhere)``: each edge's design and grid index ``i`` (the mask
    changes between points ``i`` and ``i + 1``, around the turn), the mask at ``i``, and for each design
    whether it closes everywhere.  At a cost that scales with what is needed: every ``stride``-th point
    first (``coarse_values``: every root's margin of every design, by name in ``names``, and
    ``assembled``); then (``assembled(at, designs)``, one call) the points inside each coarse cell whose
    ends differ or where any root's margin changes sign, is undefined at an end (an earlier loop opens
    there), or is near zero for its rate of change (:data:`NEAR_CHANGES`, :data:`NEAR_ZERO`).  Elsewhere
    every margin keeps its sign across the cell, so its points take the value of its ends: no edge.
    """
    coarse = numpy.arange(0, grid.size, stride)
    found = coarse_values(grid[coarse])
    mask = numpy.asarray(found["assembled"], dtype=bool)
    cyclic = numpy.concatenate([mask, mask[:, :1]], axis=1)
    refine = cyclic[:, :-1] != cyclic[:, 1:]  # cell j: from coarse point j to the next (around the turn)
    if stride > 1:
        for name in names:
            margin = numpy.asarray(found[name], dtype=float)
            padded = numpy.concatenate([margin[:, -1:], margin, margin[:, :2]], axis=1)  # j-1 .. j+2 around
            with numpy.errstate(invalid="ignore"):
                change = numpy.abs(numpy.diff(padded, axis=1))  # change[:, j + 1]: over cell j
                numpy.nan_to_num(change, copy=False, nan=numpy.inf)  # undefined beside a cell: refine it
                widest = numpy.maximum(numpy.maximum(change[:, :-2], change[:, 1:-1]), change[:, 2:])
                size = numpy.abs(padded[:, 1:-1])
                near = numpy.minimum(size[:, :-1], size[:, 1:])
                numpy.multiply(widest, NEAR_CHANGES, out=widest)
                numpy.maximum(widest, NEAR_ZERO, out=widest)
                refine |= near < widest
                signs = padded[:, 1:-1] >= 0  # NaN: False at both ends, or an end defined and one not
                defined = numpy.isnan(padded[:, 1:-1])
                refine |= (signs[:, :-1] != signs[:, 1:]) | (defined[:, :-1] != defined[:, 1:])
    design, cell = numpy.nonzero(refine)
    everywhere = numpy.asarray(mask.all(axis=1), dtype=bool)
    if not design.size:
        return design, cell, numpy.zeros(0, dtype=bool), everywhere
    local = numpy.empty((design.size, stride + 1), dtype=bool)  # each refined cell's points, both ends included
    local[:, 0], local[:, -1] = cyclic[design, cell], cyclic[design, cell + 1]
    if stride > 1:
        index = (coarse[cell][:, None] + numpy.arange(1, stride)[None, :]).ravel()
        local[:, 1:-1] = numpy.asarray(assembled(grid[index], numpy.repeat(design, stride - 1)),
                                       dtype=bool).reshape(design.size, stride - 1)
    which, offset = numpy.nonzero(local[:, :-1] != local[:, 1:])
    edge = (coarse[cell[which]] + offset) % grid.size
    return design[which], edge, local[which, offset], everywhere
