"""The loop z1 + z2 + z3 + z4 = 0 of seed 000: each case against a hand solution, and invariants.

Expected values come from the seed's worked example, from hand geometry written here
(Cramer's rule, law of cosines, right triangles with whole-number sides) and from the
seed's own formulas in ``references.py``; never from symlink.
"""
import cmath
import math

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from references import seed000_case1, seed000_case2b, seed000_case3
from symlink.analysis.loopcase import NAMES, solve_case

deg = math.radians

SEED000 = {"r1": 300.0, "t1": deg(270), "r2": 640.3124, "t2": deg(308.663), "t3": deg(180), "t4": deg(63.435)}


def closure(values):
    """|z1 + z2 + z3 + z4| of a complete set of values."""
    return abs(sum(values[f"r{k}"] * cmath.exp(1j * values[f"t{k}"]) for k in "1234"))


def angle_difference(x, y):
    return abs(math.remainder(x - y, 2 * math.pi))


def test_seed000_worked_example_to_printed_precision():
    result = solve_case(SEED000)
    assert result.case == "1" and result.missing == ("r3", "r4") and len(result.solutions) == 1
    solution = result.solutions[0]
    # Paper, eq. 13: R3 = 800.0158, R4 = 894.4019.
    assert round(solution["r3"], 4) == 800.0158
    assert round(solution["r4"], 4) == 894.4019


def test_case1_matches_cramers_rule_by_hand():
    # z3 + z4 = W with known directions: W = r3 u3 + r4 u4, solved by Cramer's rule.
    v = SEED000
    wx = -(v["r1"] * math.cos(v["t1"]) + v["r2"] * math.cos(v["t2"]))
    wy = -(v["r1"] * math.sin(v["t1"]) + v["r2"] * math.sin(v["t2"]))
    u3, u4 = (math.cos(v["t3"]), math.sin(v["t3"])), (math.cos(v["t4"]), math.sin(v["t4"]))
    det = u3[0] * u4[1] - u3[1] * u4[0]
    r3 = (wx * u4[1] - wy * u4[0]) / det
    r4 = (u3[0] * wy - u3[1] * wx) / det
    solution = solve_case(v).solutions[0]
    assert solution["r3"] == pytest.approx(r3, rel=1e-12)
    assert solution["r4"] == pytest.approx(r4, rel=1e-12)
    # and the paper's matrix form, eq. 2
    paper = seed000_case1(v["r1"], v["t1"], v["r2"], v["t2"], v["t3"], v["t4"])
    assert (solution["r3"], solution["r4"]) == pytest.approx(paper, rel=1e-12)


def test_case2a_by_hand():
    # z1 = 3 (east), z2 = 4i (north), z4 = -2 (west): z3 = -(1 + 4i), |z3| = sqrt(17).
    result = solve_case({"r1": 3, "t1": 0, "r2": 4, "t2": deg(90), "r4": 2, "t4": deg(180)})
    assert result.case == "2a" and result.missing == ("r3", "t3")
    (solution,) = result.solutions
    assert solution["r3"] == pytest.approx(math.sqrt(17), rel=1e-14)
    assert solution["t3"] == pytest.approx(-math.pi + math.atan(4.0), abs=1e-14)  # -104.04 deg


def test_case2b_by_hand_both_branches():
    # z1 = 5i, z2 = -30: W = -(z1 + z2) = 30 - 5i = z3 + z4 with |z3| = 13, z4 along +x.
    # 13 sin(t3) = -5, so cos(t3) = +-12/13 and r4 = 30 - 13 cos(t3) = 18 or 42.
    result = solve_case({"r1": 5, "t1": deg(90), "r2": 30, "t2": deg(180), "r3": 13, "t4": 0.0})
    assert result.case == "2b" and result.missing == ("r4", "t3") and result.branches == (1, -1)
    larger, smaller = result.solutions
    assert larger["r4"] == pytest.approx(42, rel=1e-14)  # branch +1: the larger length
    assert larger["t3"] == pytest.approx(math.atan2(-5, -12), abs=1e-14)
    assert smaller["r4"] == pytest.approx(18, rel=1e-14)
    assert smaller["t3"] == pytest.approx(math.atan2(-5, 12), abs=1e-14)
    # the paper's eq. 4-6 (with its misprint corrected in references.py) agree
    paper = seed000_case2b(5, deg(90), 30, deg(180), 13, 0.0)
    assert sorted(s["r4"] for s in result.solutions) == pytest.approx(sorted(r for r, _ in paper), rel=1e-13)


def test_case2b_drops_a_negative_length_and_says_so():
    # As above with z2 = +2: W = -2 - 5i, r4 = -2 - 13 cos(t3) = 10 or -14 (left out).
    result = solve_case({"r1": 5, "t1": deg(90), "r2": 2, "t2": 0.0, "r3": 13, "t4": 0.0})
    assert [s["r4"] for s in result.solutions] == pytest.approx([10.0], rel=1e-14)
    assert result.branches == (1,)
    assert len(result.notes) == 1 and "branch -1 left out" in result.notes[0] and "r4 = -14" in result.notes[0]


@pytest.mark.parametrize("turn", [0.0, 30.0, -150.0])
def test_case3_by_the_law_of_cosines(turn):
    # z1 + z2 = -5 e^{i turn}: W = 5 e^{i turn}; |z3| = 3, |z4| = 4 close a 3-4-5 triangle.
    r1, r2 = 2.0, 3.0
    t = deg(180 + turn)
    result = solve_case({"r1": r1, "t1": t, "r2": r2, "t2": t, "r3": 3, "r4": 4})
    assert result.case == "3" and result.missing == ("t3", "t4") and result.branches == (1, -1)
    w = 5.0
    at_tail = math.acos((3**2 + w**2 - 4**2) / (2 * 3 * w))  # angle between W and z3
    for branch, solution in zip(result.branches, result.solutions):
        t3 = deg(turn) + branch * at_tail  # branch +1 turns z3 counter-clockwise from W
        z4 = w * cmath.exp(1j * deg(turn)) - 3 * cmath.exp(1j * t3)
        assert angle_difference(solution["t3"], t3) < 1e-14
        assert angle_difference(solution["t4"], cmath.phase(z4)) < 1e-14
    # 3-4-5: z3 and z4 are perpendicular
    for solution in result.solutions:
        assert abs(math.cos(solution["t3"] - solution["t4"])) < 1e-14


def test_case3_matches_the_papers_equations():
    v = {"r1": 300.0, "t1": deg(270), "r2": 640.3124, "t2": deg(308.663), "r3": 800.0, "r4": 500.0}
    result = solve_case(v)
    paper = seed000_case3(v["r1"], v["t1"], v["r2"], v["t2"], v["r3"], v["r4"])
    # eq. 9-10 are branch +1 here (z3 counter-clockwise from W), eq. 7-8 branch -1
    for solution, (t3, t4) in zip(result.solutions, reversed(paper)):
        assert angle_difference(solution["t3"], t3) < 1e-12 and angle_difference(solution["t4"], t4) < 1e-12


def test_values_fill_in_the_missing_two():
    result = solve_case(SEED000)
    values = result.values(0)
    assert list(values) == list(NAMES)
    assert closure(values) < 1e-12 * 1000


# --- loops that cannot close, and bad input ------------------------------------------

def test_case1_parallel_unknown_lengths_cannot_close():
    with pytest.raises(ValueError, match="cannot close: z3 and z4 are parallel.*gap of 300"):
        solve_case({"r1": 300, "t1": deg(90), "r2": 100, "t2": 0.0, "t3": 0.0, "t4": deg(180)})


def test_case1_parallel_along_the_known_sum_is_undetermined():
    with pytest.raises(ValueError, match="parallel.*not determined"):
        solve_case({"r1": 300, "t1": 0.0, "r2": 100, "t2": 0.0, "t3": 0.0, "t4": deg(180)})


def test_case1_negative_length_cannot_close():
    with pytest.raises(ValueError, match=r"positive lengths: r3 = -800.0\d* < 0"):
        solve_case({**SEED000, "t3": 0.0})


def test_case3_too_short_and_too_different():
    base = {"r1": 300.0, "t1": deg(270), "r2": 640.3124, "t2": deg(308.663)}
    with pytest.raises(ValueError, match="reach at most 60, but the other two vectors leave a gap of 894"):
        solve_case({**base, "r3": 10, "r4": 50})
    with pytest.raises(ValueError, match="differ by 1900"):
        solve_case({**base, "r3": 100, "r4": 2000})


def test_case2b_too_short_to_reach():
    with pytest.raises(ValueError, match="z3 .length 4. cannot reach the line of z4, which passes 5 from"):
        solve_case({"r1": 5, "t1": deg(90), "r2": 2, "t2": 0.0, "r3": 4, "t4": 0.0})


def test_case2a_already_closed():
    with pytest.raises(ValueError, match="close the loop already"):
        solve_case({"r1": 1, "t1": 0.0, "r2": 1, "t2": deg(120), "r4": 1, "t4": deg(240)})


@pytest.mark.parametrize("drop, count", [(("r3",), 1), (("r3", "r4", "t4"), 3), ((), 0), (NAMES, 8)])
def test_exactly_two_missing(drop, count):
    values = {"r1": 1.0, "r2": 2.0, "r3": 2.5, "r4": 2.0, "t1": 0.0, "t2": 1.0, "t3": 2.0, "t4": 3.0}
    values = {k: v for k, v in values.items() if k not in drop}
    with pytest.raises(ValueError, match=f"exactly two .* {count} (is|are) missing"):
        solve_case(values)


@pytest.mark.parametrize("bad, message", [({"r1": -300}, "r1 must be a positive"),
                                          ({"r2": 0}, "r2 must be a positive"),
                                          ({"t1": math.nan}, "t1 must be finite"),
                                          ({"z5": 1.0}, "not z5")])
def test_bad_values(bad, message):
    with pytest.raises(ValueError, match=message):
        solve_case({**SEED000, **bad})


# --- every pair of unknowns, on random closed loops ----------------------------------

PAIRS = [(p, q) for i, p in enumerate(NAMES) for q in NAMES[i + 1:]]


@settings(max_examples=60, deadline=None)
@given(pair=st.sampled_from(PAIRS),
       lengths=st.lists(st.floats(0.5, 20), min_size=3, max_size=3),
       angles=st.lists(st.floats(-math.pi, math.pi), min_size=3, max_size=3))
def test_random_closed_loops_are_recovered(pair, lengths, angles):
    z = [r * cmath.exp(1j * t) for r, t in zip(lengths, angles)]
    z.append(-sum(z))
    assume(abs(z[3]) > 0.5)
    truth = {f"r{k + 1}": abs(v) for k, v in enumerate(z)} | {f"t{k + 1}": cmath.phase(v) for k, v in enumerate(z)}
    owners = [int(name[1]) - 1 for name in pair]
    kinds = {name[0] for name in pair}
    # stay away from the singular configurations of each case, where the answer is ill-conditioned
    if owners[0] != owners[1]:
        relative = math.sin(truth[f"t{owners[0] + 1}"] - truth[f"t{owners[1] + 1}"])
        assume(abs(relative) > 0.05)
    result = solve_case({k: v for k, v in truth.items() if k not in pair})
    assert result.case == ("2a" if owners[0] == owners[1] else {"r": "1", "t": "3"}.get("".join(kinds), "2b"))
    for index in range(len(result.solutions)):
        assert closure(result.values(index)) < 1e-9 * sum(lengths)
    found = [all(angle_difference(s[n], truth[n]) < 1e-7 if n[0] == "t" else
                 abs(s[n] - truth[n]) < 1e-7 * truth[n] for n in pair) for s in result.solutions]
    assert any(found)
