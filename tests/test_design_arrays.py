"""Sweeps' per-design analysis from generated code, all designs at once: the same spans and transmission angles as
the one-design functions (which the sweep used before), for linkages other than the four-bar."""
from __future__ import annotations

import math

import numpy
import pytest

from symlink.analysis.transmission import transmission_angles, transmission_arrays, transmission_coordinates
from symlink.catalog import CATALOG, EXAMPLE_VALUES
from symlink.reachability import InputMotion, design_spans, reachable_range
from symlink.solver import Solver


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
