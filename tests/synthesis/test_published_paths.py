"""The published path-synthesis problem of ``benchmarks/published_paths.py``, checked against its source.

Morgan and Wampler's Problem 7 (A. P. Morgan and C. W. Wampler, "Solving a Planar Four-Bar
Design Problem Using Continuation", ASME J. Mechanical Design 112 (1990) 544-550), with the
numbers as PHCpack's documentation restates them (J. Verschelde, PHCpack,
``src/Python/PHCpy3/doc/source/fourbar.rst``, "visualization of a straight line design"):
five precision points "on a line", fixed pivots (0, 0) and (1, 0), and "33 solutions ... Of
those 33 solutions, 15 are real".

The checks can fail on a mistyped point or pivot: the points must lie on one straight line,
and the published equations, solved here by Newton's method from random starts, must have
exactly the published 15 real solutions.  Then each published solution, turned into a
symlink four-bar, must put symlink's closed-form coupler point on every target (sum of
squared distances 0 to rounding): an independent check that the objective the benchmark
evaluates with symlink is the published one.

(A misprint noted in the source: its general-configuration script forms the fourth
constant as ``0.5*(d3.transpose()*d4 - d0.transpose()*d0)``, d3 where d4 is meant; the
equations it prints, which are used here, have ``d_j^T d_j``.)
"""
import numpy
import pytest

from benchmarks.published_paths import (MORGAN_WAMPLER_PIVOT, MORGAN_WAMPLER_POINTS, MORGAN_WAMPLER_REAL,
                                        design_from_solution, dyad_equations, real_solutions)


def test_the_five_points_lie_on_one_line():
    first, *rest = MORGAN_WAMPLER_POINTS
    direction = MORGAN_WAMPLER_POINTS[1] - first
    for point in rest:
        offset = point - first
        assert abs(direction[0] * offset[1] - direction[1] * offset[0]) < 1e-12


@pytest.fixture(scope="module")
def solutions():
    return real_solutions(MORGAN_WAMPLER_POINTS, MORGAN_WAMPLER_PIVOT, starts=6000, seed=1)


def test_the_published_equations_have_the_published_fifteen_real_solutions(solutions):
    assert len(solutions) == MORGAN_WAMPLER_REAL
    values, _ = dyad_equations(numpy.array(solutions), MORGAN_WAMPLER_POINTS, MORGAN_WAMPLER_PIVOT)
    assert numpy.max(numpy.abs(values)) < 1e-11


def test_a_slightly_moved_point_changes_the_equations():
    # The count is a property of these exact points: move one by 0.01 and the published
    # solutions no longer solve the equations (guards against the check passing vacuously).
    moved = MORGAN_WAMPLER_POINTS.copy()
    moved[2, 1] += 0.01
    found = real_solutions(MORGAN_WAMPLER_POINTS, MORGAN_WAMPLER_PIVOT, starts=1500, seed=3)
    values, _ = dyad_equations(numpy.array(found), moved, MORGAN_WAMPLER_PIVOT)
    assert numpy.min(numpy.max(numpy.abs(values), axis=1)) > 1e-4


def test_symlinks_coupler_point_passes_through_every_target_at_the_published_solutions(solutions):
    for solution in solutions:
        design, theta, branches, objective = design_from_solution(solution, MORGAN_WAMPLER_POINTS,
                                                                  MORGAN_WAMPLER_PIVOT)
        assert objective < 1e-20
        assert design.crank_pivot == (0.0, 0.0) and design.rocker_pivot == pytest.approx((1.0, 0.0), abs=1e-15)
        assert set(branches.tolist()) <= {1, -1}
