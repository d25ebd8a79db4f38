"""The path-synthesis benchmark (``benchmarks/synthesis.py``): its problems, the objective differential evolution
minimises and the table's arithmetic are right (no timings are asserted)."""
import math

import numpy as np
import pytest

pytest.importorskip("scipy")

from benchmarks.synthesis import (SUCCESS, coupler_points, first_arrival, problems,  # noqa: E402
                                  run_differential_evolution, summary, time_to_error)
from symlink.analysis import grashof  # noqa: E402


def test_problems_are_crank_rockers_through_their_own_points_and_repeat():
    first = problems("untimed", 10, 2024, 3)
    again = problems("untimed", 10, 2024, 3)
    for (targets, theta, design), (targets_again, _, _) in zip(first, again):
        assert np.array_equal(targets, targets_again)  # every method and run gets the same problems
        assert grashof(*design.lengths).name == "crank-rocker"
        assert np.all(np.diff(theta) > 0) and targets.shape == (10, 2)


def test_the_objective_of_differential_evolution_is_the_coupler_point():
    # The generated points DE evaluates (whole population at once) against symlink's four-bar solver at the same
    # crank angles: the same geometry, so both methods minimise the same distances.
    targets, theta, design = problems("timed", 5, 7, 1)[0]
    population = np.stack([design.vector, design.vector + 0.01], axis=1)  # (nine dimensions, two members)
    out = coupler_points()(theta[:, None], 0.0, *population[:, None, :], float(design.branch), check=False)
    assert np.allclose(out["P_x"][:, 0], targets[:, 0], atol=1e-12)
    assert np.allclose(out["P_y"][:, 0], targets[:, 1], atol=1e-12)
    assert not np.allclose(out["P_x"][:, 1], targets[:, 0], atol=1e-6)


def test_differential_evolution_runs_and_reports_a_distance():
    targets, theta, _ = problems("timed", 5, 7, 1)[0]
    result = run_differential_evolution(targets, theta, True, 0, 3)
    assert 0 < result["error"] < math.inf and result["seconds"] > 0
    times, errors = zip(*result["progress"])  # a best error after each generation, and after each polish
    assert len(times) >= 4 and list(times) == sorted(times) and list(errors) == sorted(errors, reverse=True)
    assert errors[-1] == result["error"] and 0 < first_arrival(result) <= result["seconds"]


def test_first_arrival_is_when_de_first_had_its_final_error():
    record = {"error": 1e-3, "seconds": 9.0, "progress": [(1.0, 1e-1), (2.5, 1e-3), (9.0, 1e-3)]}
    assert first_arrival(record) == 2.5
    assert first_arrival({"error": 1e-3, "seconds": 9.0}) == 9.0  # an old log without progress: its whole run


def test_time_to_error_is_the_first_verified_design_good_enough():
    record = {"error": 1e-15, "seconds": 3.0, "progress": [(0.5, 1e-3), (1.0, 2e-5), (2.0, 1e-15)]}
    assert time_to_error(record, 1e-4) == 1.0
    assert time_to_error(record, 1e-3) == 0.5
    assert time_to_error(record, 1e-16) == math.inf


def test_summary_counts_successes():
    records = [{"method": "symlink", "case": "timed5", "problem": k, "error": e, "seconds": 1.0,
                "progress": [(1.0, e)]} for k, e in enumerate([1e-15, 1e-15, 1e-3, 2 * SUCCESS])]
    records.append({"method": "de", "case": "timed5", "problem": 0, "error": 1e-3, "seconds": 40.0,
                    "iterations": 10, "progress": [(5.0, 1e-2), (20.0, 1e-3), (40.0, 1e-3)]})
    table = summary(records)
    assert "| symlink (exact Jacobian, LM) | timed | 5 | 4 | 50% |" in table
    assert "| differential evolution (10 generations) | timed | 5 | 1 | 0% |" in table
    assert "median 20x" in table  # DE's first arrival at its error, 20 s, over symlink's 1 s to it
