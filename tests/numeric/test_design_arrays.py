"""Sweeps' per-design analysis from generated code, all designs at once: the same spans and transmission angles as
the one-design functions (which the sweep used before), for linkages other than the four-bar."""
from __future__ import annotations

import math

import numpy
import pytest

from symlink.analysis.transmission import transmission_angles, transmission_arrays, transmission_coordinates
from symlink.mechanism.catalog import CATALOG, EXAMPLE_VALUES
from symlink.numeric.reachability import InputMotion, design_spans, reachable_range
from symlink.numeric.solver import Solver


def designs(name: str, count: int, spread: float, seed: int) -> dict[str, numpy.ndarray]:
    """Lengths within ``spread`` of the catalog example's, other parameters as they are."""
    linkage = CATALOG[name]()
    rng = numpy.random.default_rng(seed)
    example = EXAMPLE_VALUES[name]
    return {s.name: (example[s.name] * rng.uniform(1 - spread, 1 + spread, count) if s.is_positive
                     else numpy.full(count, float(example[s.name]))) for s in linkage.parameters}


@pytest.mark.parametrize("name, spread", [("watt2", 0.45), ("jansen", 0.45), ("slider-crank", 0.9)])
def test_design_spans_are_reachable_ranges_spans(name, spread):
    linkage = CATALOG[name]()
    values = designs(name, 12, spread, seed=4)
    branches = {s.name: 1.0 for s in linkage.branches}
    found = design_spans(linkage, {**values, **branches}, 12)
    partial = 0
    for k, spans in enumerate(found):
        one = {n: float(v[k]) for n, v in values.items()}
        expected = reachable_range(linkage, {**one, **branches}).spans
        assert len(spans) == len(expected), (k, spans, expected)
        for (low, high), (low_, high_) in zip(spans, expected):
            assert low == pytest.approx(low_, abs=1e-12) and high == pytest.approx(high_, abs=1e-12)
        partial += spans != [(-math.pi, math.pi)]
    assert partial >= 2  # the designs reach partial turns too: bisected edges are compared


@pytest.mark.parametrize("name", ["watt2", "jansen", "fourbar"])
def test_transmission_arrays_are_the_transmission_angles(name):
    linkage = CATALOG[name]()
    values = designs(name, 5, 0.1, seed=2)
    branches = {s.name: 1.0 for s in linkage.branches}
    inputs = numpy.linspace(-math.pi, math.pi, 37)
    solver = Solver(linkage, transmission_coordinates(linkage), backend="numpy")
    solved = solver(**{linkage.inputs[0].name: inputs[None, :]}, **{n: v[:, None] for n, v in values.items()},
                    **branches)
    found = transmission_arrays(linkage, {n: v[:, None] for n, v in values.items()}, solved)
    for k in range(5):
        one = {n: float(v[k]) for n, v in values.items()}
        expected = transmission_angles(linkage, {**one, **branches}, inputs,
                                       motion=InputMotion(linkage, {**one, **branches}))
        assert set(found) == set(expected)
        for loop in expected:
            numpy.testing.assert_allclose(found[loop][k], expected[loop], rtol=0, atol=1e-12)
    assert numpy.isfinite(found[next(iter(found))]).any()


def dense_spans(linkage, values: dict[str, float], points: int) -> tuple[list[tuple[float, float]], float]:
    """The runs of a dense scan of the whole turn where the solver says the design is assembled, and its step: an
    independent brute-force reach (positions only, no margins, no bisection)."""
    step = 2 * math.pi / points
    grid = -math.pi + step * numpy.arange(points)
    solver = Solver(linkage, [linkage.unknowns[-1].name], backend="numpy")
    inside = numpy.asarray(solver(**{linkage.inputs[0].name: grid}, **values)["assembled"], dtype=bool)
    if inside.all():
        return [(-math.pi, math.pi)], step
    change = numpy.flatnonzero(inside != numpy.roll(inside, -1))  # the last point before each change
    starts = [grid[(i + 1) % points] + (2 * math.pi if i + 1 == points else 0) for i in change if not inside[i]]
    ends = [grid[i] for i in change if inside[i]]
    runs = []
    for start in sorted(starts):
        end = min((e for e in ends if e >= start), default=min(ends) + 2 * math.pi)
        runs.append((start, end))
    return [(low - 2 * math.pi, high - 2 * math.pi) if low >= math.pi else (low, high) for low, high in runs], step


@pytest.mark.parametrize("name, spread, seed", [("jansen", 0.45, 11), ("watt2", 0.45, 12), ("jansen", 0.2, 13)])
def test_design_spans_agree_with_a_dense_scan(name, spread, seed):
    """Every span design_spans finds is a run of a scan 36x denser than its own, to within that scan's step."""
    linkage = CATALOG[name]()
    count = 16
    values = designs(name, count, spread, seed=seed)
    branches = {s.name: 1.0 for s in linkage.branches}
    found = design_spans(linkage, {**values, **branches}, count)
    partial = 0
    for k, spans in enumerate(found):
        one = {n: float(v[k]) for n, v in values.items()}
        expected, step = dense_spans(linkage, {**one, **branches}, 36 * 3600)
        assert len(spans) == len(expected), (k, spans, expected)
        for (low, high), (low_, high_) in zip(sorted(spans), sorted(expected)):
            # the dense runs start and end at grid points: the true ends lie within a step outside them
            assert low_ - step <= low <= low_ + 1e-12 and high_ - 1e-12 <= high <= high_ + step, (k, spans, expected)
        partial += spans != [(-math.pi, math.pi)]
    assert partial >= 3


@pytest.mark.parametrize("name", ["jansen", "watt2"])
def test_the_coarse_scan_finds_what_the_full_scan_finds(name):
    """The coarse scan then refinement gives the very spans of scanning every point (stride 1), to the bit."""
    linkage = CATALOG[name]()
    values = designs(name, 300, 0.45, seed=21)
    branches = {s.name: 1.0 for s in linkage.branches}
    full = design_spans(linkage, {**values, **branches}, 300, stride=1)
    assert design_spans(linkage, {**values, **branches}, 300) == full
    assert sum(spans != [(-math.pi, math.pi)] for spans in full) >= 50


def test_grashof_names_classify_each_design_as_grashof_does():
    """The classes of many four-bars at once, against the one-design function, ties and change points included."""
    from symlink.analysis.grashof import grashof, grashof_names
    rng = numpy.random.default_rng(5)
    lengths = rng.integers(1, 6, size=(4, 400)).astype(float)  # small whole numbers: ties and change points
    lengths = numpy.concatenate([lengths, rng.uniform(0.1, 3.0, size=(4, 400))], axis=1)
    found = grashof_names(*lengths)
    assert found == [grashof(*column).name for column in lengths.T.tolist()]
    assert {"change-point", "triple-rocker", "crank-rocker", "rocker-crank", "double-crank",
            "double-rocker"} <= set(found)
    with pytest.raises(ValueError, match="rocker must be a positive finite length"):
        grashof_names(1.0, 1.0, [1.0, -1.0], 1.0)
