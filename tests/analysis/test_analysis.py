"""Mobility, Grashof class, limit positions and transmission angle, against independent computations."""
import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from references import mp_fourbar, transmission_angle
from symlink import Linkage, Loop, Vector, coordinates, lengths
from symlink.numeric.reachability import crank_range
from symlink.analysis import (GRASHOF_CLASSES, degrees_of_freedom, grashof, limit_positions,
                              transmission_curve, transmission_range, triangle_angle)
from symlink.mechanism.catalog import CATALOG, fourbar

SEED003 = (20.0, 66.0, 56.0, 80.0)
SEED002 = (16.084, 69.743, 50.0, 70.0)  # the paper's printed linkage of case 4.3


# --- degrees of freedom ----------------------------------------------------------------

def slider_crank():
    theta, beta, x = coordinates("theta beta x")
    a, b = lengths("a b")
    loop = Loop(Vector(a, theta, "AB") + Vector(b, beta, "BC") - Vector(x, 0, "AC"), "ABC")
    return Linkage("slider-crank", [loop], inputs=[theta], unknowns=[beta, x])


def inverted_slider_crank():
    theta, phi, s = coordinates("theta phi s")
    a, d = lengths("a d")
    loop = Loop(Vector(a, theta, "AB") - Vector(s, phi, "DB") - Vector(d, 0, "AD"), "ABD")
    return Linkage("inverted slider-crank", [loop], inputs=[theta], unknowns=[phi, s])


def offset_slider_crank():
    """Slider pin C = S + offset: the travel AS ends on the block, which carries the offset SC."""
    theta, beta, s = coordinates("theta beta s")
    a, b, e = lengths("a b e")
    loop = Loop(Vector(a, theta, "AB") + Vector(b, beta, "BC") - Vector(e, math.pi / 2, "SC")
                - Vector(s, 0, "AS"), "ABC")
    return Linkage("offset slider-crank", [loop], inputs=[theta], unknowns=[beta, s])


def five_bar():
    theta1, theta2, beta1, beta2 = coordinates("theta1 theta2 beta1 beta2")
    a1, a2, b1, b2, e = lengths("a1 a2 b1 b2 e")
    loop = Loop(Vector(a1, theta1, "AB") + Vector(b1, beta1, "BC") - Vector(b2, beta2, "DC")
                - Vector(a2, theta2, "ED") - Vector(e, 0, "AE"), "ABCDE")
    return Linkage("five-bar", [loop], inputs=[theta1, theta2], unknowns=[beta1, beta2])


def watt_six_bar():
    """Two four-bars sharing the ternary rocker D-C-E (DE at a fixed angle alpha to DC)."""
    theta, beta, phi, gamma, psi = coordinates("theta beta phi gamma psi")
    a, b, c, d, e, f, g, h, alpha = lengths("a b c d e f g h alpha")
    first = Loop(Vector(a, theta, "AB") + Vector(b, beta, "BC") - Vector(c, phi, "DC") - Vector(d, 0, "AD"), "ABCD")
    second = Loop(Vector(e, phi + alpha, "DE") + Vector(f, gamma, "EF") - Vector(g, psi, "GF")
                  - Vector(h, 0, "DG"), "DEFG")
    return Linkage("watt", [first, second], inputs=[theta], unknowns=[beta, phi, gamma, psi])


@pytest.mark.parametrize("build, links, revolute, prismatic, dof", [
    (fourbar, 4, 4, 0, 1),
    (slider_crank, 4, 3, 1, 1),
    (inverted_slider_crank, 4, 3, 1, 1),
    (offset_slider_crank, 4, 3, 1, 1),
    (five_bar, 5, 5, 0, 2),
    (watt_six_bar, 6, 7, 0, 1),
])
def test_gruebler_counts(build, links, revolute, prismatic, dof):
    linkage = build()
    mobility = degrees_of_freedom(linkage)
    assert (mobility.links, mobility.revolute, mobility.prismatic, mobility.dof) == (links, revolute, prismatic, dof)
    # Independent check: each loop closes with two equations on the coordinates.
    assert mobility.dof == len(linkage.coordinates) - 2 * len(linkage.loops) == len(linkage.inputs)


@pytest.mark.parametrize("name", sorted(CATALOG))
def test_catalog_mobility_matches_its_inputs(name):
    linkage = CATALOG[name]()
    assert degrees_of_freedom(linkage).dof == len(linkage.inputs)


def test_seed002_formula():
    # seed 002: D.O.F = 3 (n - 1) - 2 R = 3 (4 - 1) - 2 (4) = 1
    assert degrees_of_freedom(fourbar()).dof == 3 * (4 - 1) - 2 * 4 == 1


# --- Grashof ---------------------------------------------------------------------------

def turns_fully(a, b, c, d):
    """Whether the link at A (length a) can make full turns relative to the ground d."""
    return crank_range(a, b, c, d) == [(-math.pi, math.pi)]


@pytest.mark.parametrize("links, name, shortest", [
    (SEED003, "crank-rocker", "crank"),           # seed 003's linkage
    (SEED002, "crank-rocker", "crank"),           # seed 002: "Crank Rocker Grashof Mechanism"
    ((4.0, 5.0, 6.0, 2.0), "double-crank", "ground"),     # drag link: shortest is the ground
    ((4.0, 2.0, 5.0, 6.0), "double-rocker", "coupler"),   # Grashof double rocker
    ((5.0, 6.0, 2.0, 4.0), "rocker-crank", "rocker"),
    ((2.0, 5.0, 2.0, 5.0), "change-point", "crank"),      # parallelogram
    ((2.0, 5.0, 5.0, 2.0), "change-point", "crank"),      # deltoid (kite)
    ((5.0, 6.0, 7.0, 10.0), "triple-rocker", "crank"),    # s + l = 15 > 13
])
def test_grashof_textbook_classes(links, name, shortest):
    found = grashof(*links)
    assert found.name == name and found.shortest == shortest and found.description == GRASHOF_CLASSES[name]
    ordered = sorted(links)
    assert found.shortest_plus_longest == ordered[0] + ordered[3]
    assert found.is_grashof == (ordered[0] + ordered[3] <= ordered[1] + ordered[2])


@pytest.mark.parametrize("links", [SEED003, (4.0, 5.0, 6.0, 2.0), (4.0, 2.0, 5.0, 6.0), (5.0, 6.0, 2.0, 4.0),
                                   (5.0, 6.0, 7.0, 10.0)])
def test_grashof_class_agrees_with_which_links_turn(links):
    # Independent of the s + l rule: ask the triangle inequalities whether crank and rocker turn.
    a, b, c, d = links
    crank, rocker = turns_fully(a, b, c, d), turns_fully(c, b, a, d)
    expected = {(True, False): "crank-rocker", (False, True): "rocker-crank", (True, True): "double-crank"}
    name = grashof(*links).name
    assert expected.get((crank, rocker), name) == name
    if name in ("double-rocker", "triple-rocker"):
        assert not crank and not rocker


def test_grashof_rejects_bad_lengths():
    with pytest.raises(ValueError, match="rocker must be a positive"):
        grashof(1, 2, -3, 4)


# --- limit positions, time ratio ------------------------------------------------------

def collinear_limits(a, b, c, d, branch):
    """Crank angles where crank and coupler are in line, by root-finding on sin(beta - theta).

    A dense scan brackets the sign changes, then mpmath's bisection-secant (anderson) solves
    each to 30 digits; positions from ``mp_fourbar`` (circle intersections).
    """
    def f(theta):
        return mp.sin(mp_fourbar(a, b, c, d, theta, branch)["beta"] - theta)

    with mp.workdps(30):
        grid = [mp.mpf(2) * mp.pi * k / 360 - mp.pi for k in range(361)]
        values = [f(t) for t in grid]
        roots = [mp.findroot(f, (lo, hi), solver="anderson")
                 for lo, hi, flo, fhi in zip(grid, grid[1:], values, values[1:]) if flo * fhi < 0]
    return roots


@pytest.mark.parametrize("links", [SEED003, SEED002, (1.0, 3.0, 2.5, 3.2)])
@pytest.mark.parametrize("branch", [1, -1])
def test_limit_positions_against_root_finding(links, branch):
    a, b, c, d = links
    limits = limit_positions(a, b, c, d, branch)
    roots = collinear_limits(a, b, c, d, branch)
    assert len(roots) == 2
    for crank, rocker in ((limits.extended_crank, limits.extended_rocker),
                          (limits.folded_crank, limits.folded_rocker)):
        nearest = min(roots, key=lambda r: abs(math.remainder(float(r) - crank, 2 * math.pi)))
        assert abs(math.remainder(float(nearest) - crank, 2 * math.pi)) < 1e-12
        phi = float(mp_fourbar(a, b, c, d, nearest, branch)["phi"])
        assert abs(math.remainder(phi - rocker, 2 * math.pi)) < 1e-12
    # extended: |AC| = a + b
    with mp.workdps(30):
        beta = mp_fourbar(a, b, c, d, limits.extended_crank, branch)["beta"]
        cx = a * mp.cos(limits.extended_crank) + b * mp.cos(beta)
        cy = a * mp.sin(limits.extended_crank) + b * mp.sin(beta)
        assert abs(mp.sqrt(cx**2 + cy**2) - (a + b)) < 1e-12
    # stroke and time ratio from the roots
    phis = [float(mp_fourbar(a, b, c, d, r, branch)["phi"]) for r in roots]
    stroke = abs(math.remainder(phis[1] - phis[0], 2 * math.pi))
    turn = float(roots[1] - roots[0]) % (2 * math.pi)
    assert limits.stroke == pytest.approx(stroke, abs=1e-12)
    assert limits.time_ratio == pytest.approx(max(turn, 2 * math.pi - turn) / min(turn, 2 * math.pi - turn),
                                              rel=1e-12)


def test_rocker_extremes_are_the_extremes_of_a_dense_sweep():
    a, b, c, d = SEED003
    theta = np.linspace(-math.pi, math.pi, 20001)
    phi = np.array([float(mp_fourbar(a, b, c, d, t, 1)["phi"]) for t in theta[::40]])
    limits = limit_positions(a, b, c, d, 1)
    assert max(limits.extended_rocker, limits.folded_rocker) >= phi.max() - 1e-12
    assert min(limits.extended_rocker, limits.folded_rocker) <= phi.min() + 1e-12
    assert max(limits.extended_rocker, limits.folded_rocker) - phi.max() < 1e-3


def test_limit_positions_that_cannot_be_assembled():
    with pytest.raises(ValueError, match="extended limit position"):
        limit_positions(5.0, 6.0, 2.0, 4.0)  # rocker-crank: |AC| = 11 is out of the rocker's reach
    with pytest.raises(ValueError, match="branch must be"):
        limit_positions(*SEED003, branch=0)


# --- transmission angle ---------------------------------------------------------------

def test_seed002_printed_linkage_stroke_and_time_ratio():
    # Seed 002, case 4.3, prints "Stroke = 39.950 degrees, Time Ratio = 1.114" for its drawn
    # (rounded) lengths; they give 39.9508 deg and 1.11417.
    limits = limit_positions(*SEED002)
    assert round(math.degrees(limits.stroke), 2) == 39.95
    assert round(limits.time_ratio, 3) == 1.114


def test_seed002_transmission_range():
    # Seed 002 prints "Maximum Transmission = 90.380 degrees, Minimum Transmission = 50.277 degrees";
    # its rounded printed lengths give 50.2766 and 90.3809 (the last digit of the maximum differs).
    found = transmission_range(*SEED002)
    assert round(math.degrees(found.minimum), 3) == 50.277 and found.minimum_at == 0.0
    assert round(math.degrees(found.maximum), 2) == 90.38 and found.maximum_at == pytest.approx(math.pi)


@pytest.mark.parametrize("links", [SEED003, SEED002, (50.0, 20.0, 40.0, 30.0), (4.0, 2.0, 5.0, 6.0),
                                   (5.0, 6.0, 7.0, 10.0)])
def test_transmission_range_against_a_dense_sweep(links):
    a, b, c, d = links
    theta = np.linspace(-math.pi, math.pi, 3601)
    # law of cosines over the diagonal BD, written here independently
    bd2 = a * a + d * d - 2 * a * d * np.cos(theta)
    with np.errstate(invalid="ignore"):
        mu = np.arccos((b * b + c * c - bd2) / (2 * b * c))
    found = transmission_range(a, b, c, d)
    assert found.minimum <= np.nanmin(mu) + 1e-12 and found.maximum >= np.nanmax(mu) - 1e-12
    # near a toggle mu changes like a square root of the crank angle: the grid comes within 0.1 rad
    assert found.minimum >= np.nanmin(mu) - 0.1 and found.maximum <= np.nanmax(mu) + 0.1
    for where, value in ((found.minimum_at, found.minimum), (found.maximum_at, found.maximum)):
        e2 = a * a + d * d - 2 * a * d * math.cos(where)
        assert math.cos(value) == pytest.approx((b * b + c * c - e2) / (2 * b * c), abs=1e-12)
    assert found.worst == pytest.approx(min(found.minimum, math.pi - found.maximum))


def test_transmission_curve_against_mpmath():
    a, b, c, d = SEED003
    theta = np.linspace(-3, 3, 13)
    curve = transmission_curve(a, b, c, d, theta)
    for t, mu in zip(theta, curve):
        ref = mp_fourbar(a, b, c, d, t, 1)
        assert mu == pytest.approx(float(transmission_angle(float(ref["beta"]), float(ref["phi"]))), abs=1e-12)
    assert np.isnan(transmission_curve(50, 20, 40, 30, [math.pi]))[0]


@settings(max_examples=40, deadline=None)
@given(st.floats(0.1, 10), st.floats(0.1, 10), st.floats(0.1, 10))
def test_triangle_angle_matches_law_of_cosines(x, y, z):
    assume(x + y > z * 1.001 and y + z > x * 1.001 and x + z > y * 1.001)
    angle = float(triangle_angle(x, y, z))
    assert math.cos(angle) == pytest.approx((y * y + z * z - x * x) / (2 * y * z), abs=1e-12)
    assert math.isnan(float(triangle_angle(x + y + z, y, z)))


# --- held over the motion: what synthesis checks each trial against (issue 32, item 2) ------------------------

def test_least_over_inputs_finds_a_minimum_between_grid_values():
    from symlink.analysis.transmission import least_over_inputs
    centre = 0.123456789  # not on a grid of 360 a turn: the grid alone is 2e-5 above the least
    least, at = least_over_inputs(lambda q: 1.0 - np.cos(q - centre), -math.pi, math.pi, periodic=True)
    assert least == pytest.approx(0.0, abs=1e-12) and at == pytest.approx(centre, abs=1e-6)
    # not periodic: the least at an end of the range, and a second, shallower basin ignored
    least, at = least_over_inputs(lambda q: np.cos(3 * q) + 0.1 * q, 0.5, 2.5)
    dense = np.linspace(0.5, 2.5, 2_000_001)
    assert least == pytest.approx(float(np.min(np.cos(3 * dense) + 0.1 * dense)), abs=1e-12)
    # NaN (not assembled) anywhere on the grid: NaN, and where
    least, at = least_over_inputs(lambda q: np.where(q > 1.0, np.nan, q), 0.0, 2.0)
    assert math.isnan(least) and at > 1.0


def _hand_worst(a, b, c, d, low, high, samples=2_000_001):
    """min(mu, pi - mu) over crank angles low..high: the law of cosines over the diagonal BD, written here."""
    theta = np.linspace(low, high, samples)
    bd2 = a * a + d * d - 2 * a * d * np.cos(theta)
    mu = np.arccos(np.clip((b * b + c * c - bd2) / (2 * b * c), -1, 1))
    return float(np.min(np.minimum(mu, math.pi - mu)))


@pytest.mark.parametrize("links, theta, over", [
    (SEED003, [0.5, 1.0], "full turn"),                         # a crank-rocker runs the full turn
    ((4.0, 5.0, 6.0, 2.0), [0.5], "full turn"),                 # a double-crank too
    ((1.0, 3.0, 2.0, 2.0), [0.5, 1.0], "full turn"),            # a change point, the crank the shortest: flat at 0
    ((2.6, 3.0, 2.5, 3.2), [0.9, 1.4, 2.2], "rocking range"),   # a triple rocker rocks between its targets
    ((2.6, 3.0, 2.5, 3.2), [-0.4, 0.3, 1.0], "rocking range"),  # through theta = 0, where mu is least
    ((2.0, 1.0, 2.5, 3.0), [1.2, 0.6], "rocking range"),        # targets in either order
])
def test_fourbar_held_transmission_against_a_dense_sweep(links, theta, over):
    from symlink.analysis.transmission import fourbar_held_transmission
    held = fourbar_held_transmission(*links, theta)
    low, high = (-math.pi, math.pi) if over == "full turn" else (min(theta), max(theta))
    assert (held.over, held.low, held.high) == (over, low, high)
    assert held.worst == pytest.approx(_hand_worst(*links, low, high), abs=1e-9)
