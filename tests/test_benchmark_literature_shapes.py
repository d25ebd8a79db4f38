"""benchmarks/literature_shapes.py: the literature's shape targets and the published answers' distances.

Wu et al.'s target is a four-bar's coupler curve, so one run must reach its points to rounding and sit at the floor
the target's polygon leaves (its own linkage's distance); the published answer, a slightly different linkage, lies
above that floor.
"""
from __future__ import annotations

import math

from benchmarks.literature_shapes import TARGETS, floor_distance, published_distance, run_target


def test_the_wu_target_is_its_linkage_curve_and_is_reached():
    assert len(TARGETS["wu1"][0]) == 72
    run = run_target("wu1", 0)  # the target drawn by circle intersections, reached by symlink's refined design
    assert run["error"] < 1e-10, run
    assert abs(run["distance"] - floor_distance("wu1")) < 1e-6
    assert published_distance("wu1") > floor_distance("wu1")
    assert math.isnan(published_distance("mcgarva"))
