"""Branch signs at a drawing (symlink.mechanism.drawn_branches): the double-precision decision, where its rounding
bound allows one, is the decision that evaluating every expression at 20 digits makes (many random drawings, and
drawings at and near a toggle, where the 20 digits must decide); and the decided branches reproduce the drawing and
move as an independent Newton solve of the links' distances.
"""
from __future__ import annotations

import math
import random

import numpy as np
import pytest

from symlink.mechanism import drawn_branches, joints
from symlink.mechanism.joints import Slider, from_joints
from tests.mechanism.test_chain_growth import newton_pose


def random_chain(seed: int, n: int) -> tuple[dict, dict]:
    """A crank A-P0 and n dyads on ground pivots, every joint drawn at random: each assembly occurs."""
    rng = random.Random(seed)
    links = {"ground": ["A"] + [f"G{j}" for j in range(1, n + 1)], "crank": ["A", "P0"]}
    coordinates = {"A": (0.0, 0.0), "P0": (rng.uniform(-1, 1), rng.uniform(0.5, 1.5))}
    for j in range(1, n + 1):
        links[f"r{j}"] = [f"G{j}", f"P{j}"]
        links[f"c{j}"] = [f"P{j - 1}", f"P{j}"]
        coordinates[f"G{j}"] = (2.0 * j + rng.uniform(-0.5, 0.5), rng.uniform(-1, 1))
        coordinates[f"P{j}"] = (2.0 * j + rng.uniform(-0.8, 0.8), rng.uniform(-2, 2))
    return links, coordinates


def random_truss(seed: int, n: int) -> tuple[dict, dict]:
    """A four-bar, then dyad j hung on the two joints before it, drawn at random."""
    rng = random.Random(seed)
    links = {"ground": ["A", "D"], "crank": ["A", "P0"], "r1": ["D", "P1"], "c1": ["P0", "P1"]}
    coordinates = {"A": (0.0, 0.0), "P0": (rng.uniform(-1, 1), 1.0), "D": (2.5, 0.0),
                   "P1": (rng.uniform(1.5, 3.0), rng.uniform(-2, 2))}
    for j in range(2, n + 1):
        links[f"r{j}"] = [f"P{j - 2}", f"P{j}"]
        links[f"c{j}"] = [f"P{j - 1}", f"P{j}"]
        coordinates[f"P{j}"] = (1.5 * j + rng.uniform(-1, 1), rng.uniform(-2, 2))
    return links, coordinates


def random_slider_crank(seed: int) -> tuple[dict, dict, dict]:
    """A slider-crank (case 2b: a length and an angle) on a line at a random angle, drawn at random."""
    rng = random.Random(seed)
    links = {"ground": ["A", "C"], "crank": ["A", "B"], "rod": ["B", "C"]}
    coordinates = {"A": (0.0, 0.0), "B": (rng.uniform(-1, 1), rng.uniform(-1, 1)),
                   "C": (rng.uniform(2, 4), rng.uniform(-1.5, 1.5))}
    return links, coordinates, {"C": Slider("ground", rng.uniform(-1, 1))}


def near_toggle(offset: float) -> tuple[dict, dict]:
    """A four-bar drawn with its coupler and rocker in line (C on the line from B through D, beyond D), C moved
    ``offset`` square to that line: at and near the toggle the two assemblies meet."""
    links = {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]}
    bx, by, dx, dy = 0.3, 1.0, 2.5, 0.0
    length = math.hypot(dx - bx, dy - by)
    ux, uy = (dx - bx) / length, (dy - by) / length
    cx, cy = dx + 0.8 * ux - offset * uy, dy + 0.8 * uy + offset * ux
    return links, {"A": (0.0, 0.0), "B": (bx, by), "C": (cx, cy), "D": (dx, dy)}


def decisions(monkeypatch, build, exact: bool) -> tuple[list, int, object]:
    """Every branch-sign decision ``from_joints`` makes for the drawing ``build()`` gives (both passes: before and
    after it turns each drawn assembly into +1), how many loops were evaluated at 20 digits, and the result (or the
    error's type and message).  ``exact``: every loop at 20 digits (the decision as it was made before)."""
    made, exact_loops = [], [0]
    decide, misses_exact = drawn_branches.drawn_branch_signs, drawn_branches._misses_exact

    def recorded(linkage, values, scale):
        made.append(decide(linkage, values, scale))
        return made[-1]

    def counted(step, values, scale):
        exact_loops[0] += 1
        return misses_exact(step, values, scale)

    with monkeypatch.context() as patch:
        patch.setattr(joints, "drawn_branch_signs", recorded)
        patch.setattr(drawn_branches, "_misses_exact", counted)
        if exact:
            patch.setattr(drawn_branches, "_sure_sign", lambda misses: None)
        try:
            links, coordinates, *kinds = build()
            drawn = from_joints(links, coordinates, driver="A", joints=kinds[0] if kinds else None)
            outcome: object = (drawn.linkage.unknowns, drawn.branches, drawn.defaults)
        except ValueError as error:
            outcome = (type(error), str(error))
    return made, exact_loops[0], outcome


CASES = ([("chain", seed, lambda s=seed: random_chain(s, 6)) for seed in range(12)]
         + [("truss", seed, lambda s=seed: random_truss(s, 6)) for seed in range(12)]
         + [("slider", seed, lambda s=seed: random_slider_crank(s)) for seed in range(12)])


def test_random_drawings_get_the_signs_that_20_digits_give_mostly_without_them(monkeypatch):
    """36 random drawings (dyads on the ground, on the joints before, slider-cranks), both assemblies among them:
    every decision and every result is the 20-digit one, and the double precision decides almost every loop."""
    loops = fast_exact_loops = 0
    signs = set()
    for kind, seed, build in CASES:
        fast, used_exact, fast_outcome = decisions(monkeypatch, build, exact=False)
        slow, _, slow_outcome = decisions(monkeypatch, build, exact=True)
        assert fast == slow, (kind, seed)
        assert repr(fast_outcome) == repr(slow_outcome), (kind, seed)
        loops += sum(len(made) for made in fast)
        fast_exact_loops += used_exact
        signs |= {sign for made in fast[:1] for sign in made.values()}
    assert signs == {1, -1}  # the first pass met both assemblies
    assert loops > 200 and fast_exact_loops <= loops // 20, (loops, fast_exact_loops)


@pytest.mark.parametrize("offset", [0.0, 1e-15, 1e-12, 1e-9, -1e-9, 1e-6, -1e-3])
def test_at_and_near_a_toggle_20_digits_decide_as_before(monkeypatch, offset):
    """Where the assemblies (nearly) meet, the double bound cannot separate them and 20 digits decide: the same
    signs, the same result or the same error as evaluating every loop at 20 digits."""
    fast, used_exact, fast_outcome = decisions(monkeypatch, lambda: near_toggle(offset), exact=False)
    slow, _, slow_outcome = decisions(monkeypatch, lambda: near_toggle(offset), exact=True)
    assert fast == slow
    assert repr(fast_outcome) == repr(slow_outcome)
    if abs(offset) <= 1e-9:
        assert used_exact >= 1  # too close to call in double precision


def test_the_chain_of_the_benchmark_is_decided_in_double_precision(monkeypatch):
    """The growth benchmark's chain (dyads on ground pivots, drawn well away from toggles): no loop needs 20 digits."""
    from benchmarks.growth import chain_by_joints
    made, used_exact, _ = decisions(monkeypatch, lambda: chain_by_joints(30), exact=False)
    assert used_exact == 0 and sum(len(m) for m in made) >= 30


@pytest.mark.parametrize("seed", [0, 5])
def test_the_decided_branches_reproduce_the_drawing_and_move_as_a_newton_solve(seed):
    """Independent of the closed forms: the drawn pose is the solver's at the drawn crank angle with the default
    branches, and at a turned crank it is the pose that Newton's method on every link's length continues to."""
    from symlink.numeric.solver import Solver
    n = 4
    links, coordinates = random_chain(seed, n)
    drawn = from_joints(links, coordinates, driver="A")
    moving = [f"P{j}" for j in range(n + 1)]
    solver = Solver(drawn.linkage, [f"{p}_{axis}" for p in moving for axis in "xy"], backend="numpy")
    start = drawn.defaults["theta_A_P0"]
    for angle in (start, start + 0.05):
        got = solver(**{**drawn.defaults, "theta_A_P0": angle})
        reference = newton_pose(links, coordinates, angle) if angle != start else \
            {p: np.array(coordinates[p]) for p in moving}
        for p in moving:
            assert np.allclose([float(got[p + "_x"]), float(got[p + "_y"])], reference[p], rtol=0, atol=1e-8), \
                (seed, angle, p)
