"""The four-bar path synthesis's keywords for stated problems (symlink.synthesis.path): ``branch``, ``direction``,
``free_phase`` and ``bounds``, and its refinements that slide along walls.

Targets are traced with the 30-digit hand formula of ``test_path.mp_point`` (circle intersection);
every found design is checked against it, never against the code under test.
"""
from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from symlink.synthesis.path import synthesize_path
from test_path import _check_against_mpmath, mp_point

pytest.importorskip("scipy")

TRUE = np.array([0.2, 0.1, 0.4, 0.5, 2.0, 1.8, 2.2, 1.0, 0.6])  # x0, y0, frame, a, b, c, d, u, v: a crank-rocker


def traced(theta, branch: int = 1, vector=TRUE) -> np.ndarray:
    return np.array([[float(p.real), float(p.imag)] for p in (mp_point(vector, mp.mpf(float(t)), branch)
                                                             for t in theta)])


@pytest.mark.parametrize("branch", [1, -1])
def test_branch_keeps_to_the_asked_assembly(branch):
    theta = np.linspace(0.3, 2.8, 7)
    targets = traced(theta, branch)
    found = synthesize_path(targets, theta, branch=branch, designs=2)
    assert all(design.branch == branch for design in found)
    assert found[0].error < 1e-8
    _check_against_mpmath(found[0], targets)


def test_direction_sets_which_way_the_crank_turns():
    theta = np.linspace(0.3, 3.3, 8)
    targets = traced(theta)
    found = synthesize_path(targets, None, direction=1, seed=2)[0]
    assert np.all(np.diff(found.theta) > 0)
    assert found.error < 1e-8
    _check_against_mpmath(found, targets)


def test_free_phase_finds_the_offset_of_equal_steps():
    steps = np.arange(9) * math.radians(25)
    offset = 1.1
    targets = traced(steps + offset)
    found = synthesize_path(targets, steps, free_phase=True, seed=1)[0]
    assert found.error < 1e-8
    _check_against_mpmath(found, targets)
    assert np.allclose(np.diff(found.theta), np.diff(steps))  # the steps are kept, only their start is found
    # without the offset the given angles are wrong: no exact design
    assert synthesize_path(targets, steps, seed=1)[0].error > 1e-6


def test_bounds_hold_and_a_bound_the_answer_needs_is_reached():
    theta = np.linspace(0.3, 2.8, 7)
    targets = traced(theta)
    bounds = {"a": (0.1, 0.45), "d": (0.5, 3.0), "x0": (-1.0, 1.0)}  # the true crank is 0.5
    found = synthesize_path(targets, theta, bounds=bounds, branch=1)[0]
    assert 0.1 <= found.crank <= 0.45 and 0.5 <= found.ground <= 3.0 and -1.0 <= found.crank_pivot[0] <= 1.0
    assert found.crank == pytest.approx(0.45, abs=1e-9)  # slid to the bound, not stopped short of it
    assert found.error > 1e-6
    with pytest.raises(ValueError, match="frame"):
        synthesize_path(targets, theta, bounds={"frame": (0.0, 1.0)})
    with pytest.raises(ValueError, match="low < high"):
        synthesize_path(targets, theta, bounds={"a": (1.0, 0.5)})


def test_bad_keywords_are_refused_by_name():
    theta = np.linspace(0.3, 2.8, 7)
    targets = traced(theta)
    with pytest.raises(ValueError, match="branch"):
        synthesize_path(targets, theta, branch=2)
    with pytest.raises(ValueError, match="direction"):
        synthesize_path(targets, theta, direction=1)  # with timing the angles fix it
    with pytest.raises(ValueError, match="free_phase"):
        synthesize_path(targets, None, free_phase=True)
