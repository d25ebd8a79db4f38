"""analyze_linkage: limit positions, stroke, time ratio and transmission of any one-input linkage, by hand geometry."""
import math

import mpmath as mp
import numpy as np
import pytest

from symlink.analysis import (analyze_linkage, fourbar_report, limit_positions, loop_transmissions, output_limits,
                              transmission_angles, transmission_joints, transmission_range)
from symlink.mechanism.catalog import EXAMPLE_VALUES, fourbar, inverted_slider_crank, jansen, slider_crank, stephenson2, watt2


def law_of_cosines(opposite, side1, side2):
    return math.acos((side1**2 + side2**2 - opposite**2) / (2 * side1 * side2))


def same_angle(x, y):
    return abs(math.remainder(x - y, 2 * math.pi))


# --- slider-crank -------------------------------------------------------------------------

@pytest.mark.parametrize("a, b", [(1.0, 3.0), (1.3, 4.1), (2.0, 2.5)])
def test_slider_crank_dead_centres_without_offset(a, b):
    found = output_limits(slider_crank(), dict(a=a, b=b, offset=0.0), "slider")
    (first, second) = found.positions
    # dead centres: crank and rod in line at theta = 0 (s = a + b) and pi (s = b - a)
    assert (first.at, first.value, first.kind) == (pytest.approx(0.0, abs=1e-15), pytest.approx(a + b, rel=1e-15),
                                                   "maximum")
    assert same_angle(second.at, math.pi) < 1e-15 and second.value == pytest.approx(b - a, rel=1e-14)
    assert found.stroke == pytest.approx(2 * a, rel=1e-14) and found.time_ratio == pytest.approx(1.0, rel=1e-14)
    assert not found.angle


@pytest.mark.parametrize("a, b, offset", [(1.0, 3.0, 0.5), (1.3, 4.1, 0.7), (1.0, 3.0, -1.2)])
def test_offset_slider_crank_limits_stroke_and_time_ratio(a, b, offset):
    found = output_limits(slider_crank(), dict(a=a, b=b, offset=offset), "slider")
    # extended: C = (a + b) e^{i theta} on y = offset; folded: C = (b - a) e^{i (theta + pi)}
    extended = math.asin(offset / (a + b))
    folded = math.asin(offset / (b - a)) + math.pi
    far, near = math.sqrt((a + b) ** 2 - offset**2), math.sqrt((b - a) ** 2 - offset**2)
    by_kind = {p.kind: p for p in found.positions}
    assert same_angle(by_kind["maximum"].at, extended) < 1e-14 and by_kind["maximum"].value == pytest.approx(far)
    assert same_angle(by_kind["minimum"].at, folded) < 1e-14 and by_kind["minimum"].value == pytest.approx(near)
    assert found.stroke == pytest.approx(far - near, rel=1e-13)
    forward = (folded - extended) % (2 * math.pi)
    assert found.time_ratio == pytest.approx(max(forward, 2 * math.pi - forward) / min(forward, 2 * math.pi - forward),
                                             rel=1e-13)


def test_slider_crank_transmission_against_the_rod_angle():
    a, b, offset = 1.0, 3.0, 0.5
    values = dict(a=a, b=b, offset=offset)
    (joint,) = transmission_joints(slider_crank())
    assert joint.guide and joint.loop == "ABC"
    theta = np.linspace(-3, 3, 13)
    # branch +1: the rod points right, sin(beta) = (offset - a sin(theta)) / b; mu = 90 deg - beta
    expected = math.pi / 2 - np.arcsin((offset - a * np.sin(theta)) / b)
    assert transmission_angles(slider_crank(), values, theta)["ABC"] == pytest.approx(expected, abs=1e-14)
    (found,) = loop_transmissions(slider_crank(), values)
    assert found.minimum == pytest.approx(math.pi / 2 - math.asin((offset + a) / b), abs=1e-14)
    assert found.maximum == pytest.approx(math.pi / 2 + math.asin((a - offset) / b), abs=1e-14)
    assert same_angle(found.minimum_at, -math.pi / 2) < 1e-7 and same_angle(found.maximum_at, math.pi / 2) < 1e-7
    assert found.worst == pytest.approx(math.pi / 2 - math.asin((offset + a) / b), abs=1e-14)


# --- inverted slider-crank: the rocker swings while d > a ------------------------------------

@pytest.mark.parametrize("a, d", [(1.0, 2.0), (1.2, 1.5)])
def test_crank_shaper_rocker_limits(a, d):
    found = output_limits(inverted_slider_crank(), dict(a=a, d=d), "rocker")
    # the rocker line D -> B touches the crank circle: AB perpendicular to DB, cos(theta) = a / d
    ends = sorted([math.acos(a / d), -math.acos(a / d)])
    assert [p.at for p in found.positions] == pytest.approx(ends, abs=1e-14)
    values = sorted(p.value % (2 * math.pi) for p in found.positions)
    assert values == pytest.approx([math.pi - math.asin(a / d), math.pi + math.asin(a / d)], abs=1e-14)
    assert found.stroke == pytest.approx(2 * math.asin(a / d), abs=1e-14)
    forward = 2 * math.acos(a / d)
    assert found.time_ratio == pytest.approx((2 * math.pi - forward) / forward, rel=1e-13)
    # a slider on a turning guide pushes normal to it: no transmission angle to watch
    assert transmission_joints(inverted_slider_crank()) == ()


def test_whitworth_rocker_turns_fully_and_has_no_limits():
    report = analyze_linkage(inverted_slider_crank(), EXAMPLE_VALUES["inverted-slider-crank"], output="rocker")
    assert report.reach.full_turn and report.limits.positions == () and report.limits.stroke is None


# --- four-bar: the special case ---------------------------------------------------------------

@pytest.mark.parametrize("links", [(20.0, 66.0, 56.0, 80.0), (16.084, 69.743, 50.0, 70.0), (1.0, 3.0, 2.5, 3.2)])
@pytest.mark.parametrize("branch", [1, -1])
def test_fourbar_rocker_limits_by_the_law_of_cosines(links, branch):
    a, b, c, d = links
    found = output_limits(fourbar(), dict(a=a, b=b, c=c, d=d, branch=branch), "rocker")
    # crank and coupler in line: |AC| = a + b or b - a, the triangle A, D, C (C above the ground on branch +1)
    extended = branch * law_of_cosines(c, a + b, d)
    folded = branch * law_of_cosines(c, b - a, d) - math.pi
    cranks = sorted(p.at for p in found.positions)
    assert cranks == pytest.approx(sorted(math.remainder(x, 2 * math.pi) for x in (extended, folded)), abs=1e-12)
    rockers = sorted(branch * (math.pi - law_of_cosines(r, c, d)) for r in (a + b, b - a))
    assert found.stroke == pytest.approx(abs(rockers[1] - rockers[0]), abs=1e-12)
    # the independent four-bar closed form agrees too
    closed = limit_positions(a, b, c, d, branch)
    assert found.stroke == pytest.approx(closed.stroke, abs=1e-12)
    assert found.time_ratio == pytest.approx(closed.time_ratio, rel=1e-12)


@pytest.mark.parametrize("links", [(20.0, 66.0, 56.0, 80.0), (16.084, 69.743, 50.0, 70.0), (50.0, 20.0, 40.0, 30.0),
                                   (4.0, 2.0, 5.0, 6.0)])
def test_fourbar_transmission_against_a_dense_sweep(links):
    a, b, c, d = links
    (found,) = loop_transmissions(fourbar(), dict(a=a, b=b, c=c, d=d))
    theta = np.linspace(-math.pi, math.pi, 3601)
    with np.errstate(invalid="ignore"):
        mu = np.arccos((b * b + c * c - (a * a + d * d - 2 * a * d * np.cos(theta))) / (2 * b * c))
    assert found.minimum <= np.nanmin(mu) + 1e-12 and found.maximum >= np.nanmax(mu) - 1e-12
    for where, value in ((found.minimum_at, found.minimum), (found.maximum_at, found.maximum)):
        diagonal = a * a + d * d - 2 * a * d * math.cos(where)
        assert math.cos(value) == pytest.approx((b * b + c * c - diagonal) / (2 * b * c), abs=1e-12)


def test_fourbar_report_agrees_with_the_general_analysis():
    a, b, c, d = 16.084, 69.743, 50.0, 70.0
    report = fourbar_report(a, b, c, d)
    # seed 002 prints stroke 39.950 deg, time ratio 1.114, transmission 50.277 to 90.380 deg
    assert round(math.degrees(report["stroke"]), 2) == 39.95 and round(report["time_ratio"], 3) == 1.114
    assert round(math.degrees(report["transmission_min"]), 3) == 50.277
    closed = limit_positions(a, b, c, d)
    limits = report["limit_positions"]
    assert limits["extended_crank"] == pytest.approx(closed.extended_crank, abs=1e-12)
    assert limits["folded_crank"] == pytest.approx(closed.folded_crank, abs=1e-12)
    assert limits["extended_rocker"] == pytest.approx(closed.extended_rocker, abs=1e-12)
    (general,) = analyze_linkage(fourbar(), dict(a=a, b=b, c=c, d=d)).transmission
    exact = transmission_range(a, b, c, d)
    assert general.minimum == pytest.approx(exact.minimum, abs=1e-14)
    assert general.maximum == pytest.approx(exact.maximum, abs=1e-14)


# --- Jansen's leg, Watt II: every two-angle loop ---------------------------------------------------

def interior(P, Q, R):
    """The angle at Q of the triangle P, Q, R (mpmath)."""
    u = (P[0] - Q[0], P[1] - Q[1])
    v = (R[0] - Q[0], R[1] - Q[1])
    return mp.acos((u[0] * v[0] + u[1] * v[1]) / (mp.sqrt(u[0] ** 2 + u[1] ** 2) * mp.sqrt(v[0] ** 2 + v[1] ** 2)))


def test_jansen_transmission_angles_at_its_joints():
    from symlink.numeric.solver import Solver
    values = EXAMPLE_VALUES["jansen"]
    linkage = jansen()
    assert [j.loop for j in transmission_joints(linkage)] == ["ABCD", "ABFD", "DFGE"]
    theta = np.array([-2.0, 0.0, 1.0, 2.5])
    angles = transmission_angles(linkage, values, theta)
    points = Solver(linkage, [f"{p}_{x}" for p in "BCDEFG" for x in "xy"])(theta=theta, **values)
    for k in range(len(theta)):
        P = {p: (mp.mpf(float(points[f"{p}_x"][k])), mp.mpf(float(points[f"{p}_y"][k]))) for p in "BCDEFG"}
        # the joints: C between the upper rocker DC and link BC; F between BF and the lower rocker DF;
        # G between the leg's side FG and the tie EG
        assert angles["ABCD"][k] == pytest.approx(float(interior(P["B"], P["C"], P["D"])), abs=1e-12)
        assert angles["ABFD"][k] == pytest.approx(float(interior(P["B"], P["F"], P["D"])), abs=1e-12)
        assert angles["DFGE"][k] == pytest.approx(float(interior(P["F"], P["G"], P["E"])), abs=1e-12)


def test_jansen_report():
    report = analyze_linkage(jansen(), EXAMPLE_VALUES["jansen"], output="H_y")
    assert report.mobility.dof == 1 and report.reach.full_turn
    assert [t.loop for t in report.transmission] == ["ABCD", "ABFD", "DFGE"]
    for t in report.transmission:
        assert 0 < t.minimum <= t.maximum < math.pi
    # the foot's height: its lowest point against a dense sweep (points are lengths, so no stroke wrap)
    from symlink.numeric.solver import Solver
    sweep = Solver(jansen(), ["H_y"])(theta=np.linspace(-math.pi, math.pi, 20001), **EXAMPLE_VALUES["jansen"])["H_y"]
    lowest = min(p.value for p in report.limits.positions if p.kind == "minimum")
    assert lowest <= sweep.min() + 1e-12 and lowest >= sweep.min() - 1e-6
    assert report.limits.stroke is None  # the foot's height has four extremes a turn


def test_watt2_output_limits_against_a_dense_sweep():
    from symlink.numeric.solver import Solver
    values = EXAMPLE_VALUES["watt2"]
    found = output_limits(watt2(), values, "output")
    sweep = Solver(watt2(), ["output"])(theta=np.linspace(-math.pi, math.pi, 20001), **values)["output"]
    assert len(found.positions) == 2
    top = max(p.value for p in found.positions)
    bottom = min(p.value for p in found.positions)
    assert top >= sweep.max() - 1e-12 and top - sweep.max() < 1e-6
    assert bottom <= sweep.min() + 1e-12 and sweep.min() - bottom < 1e-6
    assert found.stroke == pytest.approx(top - bottom, abs=1e-15)


def test_stephenson2_by_continuation_against_a_dense_sweep():
    from symlink.numeric.solver import NumericSolver
    guess = dict(beta=0.5, mu=0.2, phi=1.5, eta=0.3)
    values = EXAMPLE_VALUES["stephenson2"]
    report = analyze_linkage(stephenson2(), values, "rocker", guess=guess, points=720)
    assert report.transmission == () and report.reach.full_turn and not report.reach.exact
    theta = np.linspace(0.0, 2 * math.pi, 4001)
    sweep = NumericSolver(stephenson2())(theta=theta, guess=guess, **values)["rocker"]
    top = max(p.value for p in report.limits.positions)
    assert top >= sweep.max() - 1e-10 and top - sweep.max() < 1e-6


# --- bad input ------------------------------------------------------------------------------

@pytest.mark.parametrize("output, message", [("nothing", "has no output"), ("rocker_speed", "not a position output"),
                                             ("singular", "not a position output")])
def test_bad_outputs(output, message):
    with pytest.raises(ValueError, match=message):
        output_limits(fourbar(), dict(a=20.0, b=66.0, c=56.0, d=80.0), output)


def test_a_linkage_that_closes_nowhere():
    with pytest.raises(ValueError, match="cannot be assembled at any theta"):
        analyze_linkage(slider_crank(), dict(a=1.0, b=1.0, offset=5.0))
