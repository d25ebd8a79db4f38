"""Reachable input ranges and toggles of any one-input linkage, against hand formulas and mpmath brute force."""
import math

import mpmath as mp
import numpy as np
import pytest

from symlink.mechanism.catalog import EXAMPLE_VALUES, fivebar, fourbar, inverted_slider_crank, slider_crank, stephenson2, watt2
from symlink.numeric.reachability import InputMotion, reachable_range
from symlink.numeric.solver import Solver


def turn(angle):
    """An angle mapped into [-pi, pi)."""
    return (angle + math.pi) % (2 * math.pi) - math.pi


def same_angle(x, y, tolerance):
    return abs(math.remainder(x - y, 2 * math.pi)) <= tolerance


# --- slider-crank: the rod reaches the guide while |offset - a sin(theta)| <= b ----------------

@pytest.mark.parametrize("a, b, offset", [(2.0, 1.0, 0.0), (2.0, 1.0, 0.5), (2.0, 1.0, -1.5), (1.0, 3.0, 2.5),
                                          (3.0, 1.0, 3.5)])
def test_slider_crank_range_against_its_closed_form(a, b, offset):
    found = reachable_range(slider_crank(), dict(a=a, b=b, offset=offset))
    # Written here by hand: sin(theta) between (offset - b)/a and (offset + b)/a.
    low, high = (offset - b) / a, (offset + b) / a
    ends = []
    for bound in (low, high):
        if -1 < bound < 1:
            ends += [math.asin(bound), math.pi - math.asin(bound)]
    if not ends:
        assert found.full_turn and found.toggles == ()
        return
    assert sorted(turn(t.at) for t in found.toggles) == pytest.approx(sorted(turn(e) for e in ends), abs=1e-14)
    assert all(t.loop == "ABC" and t.ends_range and not t.degenerate for t in found.toggles)
    # inside each span the rod reaches the guide; just outside it does not
    for start, end in found.spans:
        for theta in np.linspace(start, end, 7)[1:-1]:
            assert low <= math.sin(theta) <= high
        for theta in (start - 1e-9, end + 1e-9):
            assert not low <= math.sin(theta) <= high


def test_slider_crank_that_never_closes():
    found = reachable_range(slider_crank(), dict(a=1.0, b=1.0, offset=5.0))
    assert found.spans == () and found.toggles == ()


# --- four-bar: the triangle over the diagonal BD ---------------------------------------------

def fourbar_ends(a, b, c, d):
    """Crank angles where |BD| = b + c or |b - c| (law of cosines), written here by hand."""
    ends = []
    for reach in (b + c, abs(b - c)):
        cosine = (a * a + d * d - reach * reach) / (2 * a * d)
        if -1 < cosine < 1:
            ends += [math.acos(cosine), -math.acos(cosine)]
    return ends


@pytest.mark.parametrize("links", [(50.0, 20.0, 40.0, 30.0), (0.3, 0.1, 0.25, 0.30), (5.0, 6.0, 7.0, 10.0),
                                   (4.0, 2.0, 5.0, 6.0), (20.0, 66.0, 56.0, 80.0)])
@pytest.mark.parametrize("branch", [1, -1])
def test_fourbar_range_against_the_law_of_cosines(links, branch):
    a, b, c, d = links
    found = reachable_range(fourbar(), dict(a=a, b=b, c=c, d=d, branch=branch))
    ends = sorted(fourbar_ends(a, b, c, d))
    edges = sorted(t.at for t in found.toggles if t.ends_range)
    assert edges == pytest.approx(ends, abs=1e-13)
    assert all(t.loop == "ABCD" for t in found.toggles)
    assert found.exact and found.full_turn == (ends == [])


def test_parallelogram_passes_its_change_points_inside_the_range():
    # a = c, b = d: at theta = 0 and pi all four links line up (|BD| = b - c, then b + c)
    found = reachable_range(fourbar(), dict(a=2.0, b=5.0, c=2.0, d=5.0))
    assert found.full_turn
    assert len(found.toggles) == 2 and not any(t.ends_range for t in found.toggles)
    # the root vanishes like the square of the distance: located to about the square root of rounding
    for toggle, at in zip(sorted(found.toggles, key=lambda t: abs(t.at)), (0.0, math.pi)):
        assert same_angle(toggle.at, at, 1e-7) and toggle.loop == "ABCD"


@pytest.mark.parametrize("build, values, at", [
    (fourbar, dict(a=2.0, b=5.0, c=5.0, d=2.0), 0.0),      # deltoid: B passes over D
    (inverted_slider_crank, dict(a=2.0, d=2.0), 0.0),       # the crank pin passes over the rocker pivot
])
def test_points_that_coincide_are_degenerate_ends(build, values, at):
    found = reachable_range(build(), values)
    assert len(found.toggles) == 2 and all(t.degenerate for t in found.toggles)
    assert all(abs(t.at - at) < 1e-12 for t in found.toggles)
    (start, end), = found.spans
    assert start == pytest.approx(at, abs=1e-12) and end == pytest.approx(at + 2 * math.pi, abs=1e-12)


# --- Watt II: a dense brute-force check with mpmath circle intersections ---------------------

def circle_left(P, r, Q, s):
    """The intersection of circle (P, r) and circle (Q, s) left of the line P -> Q, or None."""
    with mp.workdps(30):
        dx, dy = Q[0] - P[0], Q[1] - P[1]
        w = mp.sqrt(dx * dx + dy * dy)
        if not abs(r - s) <= w <= r + s:
            return None
        along = (r * r - s * s + w * w) / (2 * w)
        across = mp.sqrt(max(r * r - along * along, 0))
        return (P[0] + (along * dx - across * dy) / w, P[1] + (along * dy + across * dx) / w)


def watt2_assembles(theta, v):
    """Whether the Watt II closes at theta (both loops on branch +1): C left of B -> D, F left of E -> G."""
    with mp.workdps(30):
        B = (v["a"] * mp.cos(theta), v["a"] * mp.sin(theta))
        D = (mp.mpf(v["d"]), mp.mpf(0))
        C = circle_left(B, v["b"], D, v["c"])
        if C is None:
            return None
        phi = mp.atan2(C[1] - D[1], C[0] - D[0])
        E = (D[0] + v["e"] * mp.cos(phi + v["alpha"]), D[1] + v["e"] * mp.sin(phi + v["alpha"]))
        G = (mp.mpf(v["gx"]), mp.mpf(v["gy"]))
        F = circle_left(E, v["f"], G, v["g"])
        return None if F is None else F


WATT2_SWINGING = dict(a=1.0, b=3.5, c=3.0, d=3.2, e=2.0, f=2.2, g=1.6, alpha=0.6, gx=4.5, gy=3.5)


def test_watt2_range_against_brute_force():
    values = WATT2_SWINGING
    found = reachable_range(watt2(), values)
    assert found.spans and not found.full_turn
    assert {t.loop for t in found.toggles} == {"DEFG"}  # the second loop limits this one
    grid = np.linspace(-math.pi, math.pi, 721)[:-1]
    for theta in grid:
        near_edge = any(abs(math.remainder(theta - t.at, 2 * math.pi)) < 1e-6 for t in found.toggles)
        inside = any(start <= theta <= end or start <= theta + 2 * math.pi <= end for start, end in found.spans)
        if not near_edge:
            assert inside == (watt2_assembles(theta, values) is not None), theta
    # at each end the second loop's triangle E, F, G is flat: |EG| = f + g or |f - g|
    for toggle in found.toggles:
        with mp.workdps(30):
            B = (mp.cos(toggle.at), mp.sin(toggle.at))
            C = circle_left(B, values["b"], (mp.mpf(values["d"]), 0), values["c"])
            phi = mp.atan2(C[1], C[0] - values["d"])
            E = (values["d"] + values["e"] * mp.cos(phi + values["alpha"]), values["e"] * mp.sin(phi + values["alpha"]))
            EG = mp.sqrt((E[0] - values["gx"]) ** 2 + (E[1] - values["gy"]) ** 2)
            flat = min(abs(EG - (values["f"] + values["g"])), abs(EG - abs(values["f"] - values["g"])))
        assert flat < 1e-13


def test_watt2_example_turns_fully():
    found = reachable_range(watt2(), EXAMPLE_VALUES["watt2"])
    assert found.full_turn and found.toggles == ()
    assert all(watt2_assembles(theta, EXAMPLE_VALUES["watt2"]) is not None for theta in np.linspace(-3.1, 3.1, 63))


# --- Newton's continuation: where there is no closed form, and against one --------------------

@pytest.mark.parametrize("links, start", [((0.3, 0.1, 0.25, 0.30), 1.0), ((5.0, 6.0, 7.0, 10.0), 0.5)])
def test_continuation_finds_the_closed_form_range(links, start):
    a, b, c, d = links
    solved = Solver(fourbar(), ["beta", "phi"])(theta=start, a=a, b=b, c=c, d=d)
    guess = {"beta": float(solved["beta"]), "phi": float(solved["phi"])}
    found = reachable_range(fourbar(), dict(a=a, b=b, c=c, d=d), numeric=True, guess=guess, start=start, points=360)
    assert not found.exact
    (low, high), = found.spans
    ends = fourbar_ends(a, b, c, d)
    # the span holding the start, from the law of cosines
    below = max(e for e in ends if e < start)
    above = min(e for e in ends if e > start)
    assert (low, high) == pytest.approx((below, above), abs=1e-9)
    assert all(t.loop is None for t in found.toggles)


def test_stephenson2_turns_fully_by_continuation():
    found = reachable_range(stephenson2(), EXAMPLE_VALUES["stephenson2"],
                            guess=dict(beta=0.5, mu=0.2, phi=1.5, eta=0.3), points=360)
    assert found.full_turn and not found.exact


# --- a second input held still, a length input ----------------------------------------------

def test_fivebar_with_its_second_crank_held_is_a_fourbar():
    v = dict(a=2.0, b=4.0, c=4.0, d=3.0, e=2.0, psi=2.2)
    found = reachable_range(fivebar(), v)
    # crank 2 held: D = (d + e cos psi, e sin psi) is a ground pivot; the triangle over BD again
    D = complex(v["d"] + v["e"] * math.cos(v["psi"]), v["e"] * math.sin(v["psi"]))
    ground = abs(D)
    ends = [turn(x + math.atan2(D.imag, D.real)) for x in fourbar_ends(v["a"], v["b"], v["c"], ground)]
    assert sorted(turn(t.at) for t in found.toggles) == pytest.approx(sorted(ends), abs=1e-13)


def test_a_slider_driven_slider_crank_over_an_interval():
    # Driven by the slider s, the crank angle theta is solved: s within b - a .. a + b (zero offset).
    import sympy as sp
    from symlink import Linkage, Loop, Vector, coordinates, lengths
    theta, beta, s = coordinates("theta beta s")
    a, b = lengths("a b")
    loop = Loop(Vector(a, theta, "AB") + Vector(b, beta, "BC") - Vector(s, 0, "AC"), "ABC")
    linkage = Linkage("slider-driven", [loop], inputs=[s], unknowns=[theta, beta])
    found = reachable_range(linkage, dict(a=1.0, b=3.0), interval=(0.0, 6.0))
    (low, high), = found.spans
    assert (low, high) == pytest.approx((2.0, 4.0), abs=1e-14) and not found.periodic
    assert sp.Symbol("s") not in linkage.parameters


# --- bad input -------------------------------------------------------------------------------

@pytest.mark.parametrize("build, values, options, message", [
    (fourbar, dict(a=1.0, b=2.0, c=2.0), {}, "give a value for d"),
    (fourbar, dict(a=1.0, b=2.0, c=2.0, d=2.0, e=3.0), {}, "not e"),
    (fourbar, dict(a=1.0, b=2.0, c=2.0, d=2.0), dict(input="phi"), "has the inputs theta"),
    (fourbar, dict(a=1.0, b=2.0, c=2.0, d=2.0), dict(guess={"beta": 0.0, "phi": 1.0}), "closed form"),
    (stephenson2, EXAMPLE_VALUES["stephenson2"], {}, "give a guess"),
    (fivebar, dict(a=2.0, b=4.0, c=4.0, d=3.0, e=2.0), {}, "give a value for psi"),
    (fourbar, dict(a=1.0, b=2.0, c=2.0, d=2.0), dict(points=2), "at least 4"),
    (fourbar, dict(a=1.0, b=2.0, c=2.0, d=2.0), dict(interval=(1.0, 0.0)), "low < high"),
    (fourbar, dict(a=-1.0, b=2.0, c=2.0, d=2.0), {}, "a must be a positive"),
    (slider_crank, dict(a=1.0, b=2.0, offset=math.nan), {}, "offset must be finite"),
    (fourbar, dict(a=1.0, b=2.0, c=2.0, d=2.0, branch=0), {}, "branch must be"),
])
def test_bad_input(build, values, options, message):
    with pytest.raises(ValueError, match=message):
        reachable_range(build(), values, **options)


def test_a_length_input_needs_an_interval():
    from symlink import Linkage, Loop, Vector, coordinates, lengths
    theta, beta, s = coordinates("theta beta s")
    a, b = lengths("a b")
    loop = Loop(Vector(a, theta, "AB") + Vector(b, beta, "BC") - Vector(s, 0, "AC"), "ABC")
    linkage = Linkage("slider-driven", [loop], inputs=[s], unknowns=[theta, beta])
    with pytest.raises(ValueError, match="is a length: give the interval"):
        reachable_range(linkage, dict(a=1.0, b=3.0))


def test_motion_without_a_scan_says_so():
    motion = InputMotion(stephenson2(), EXAMPLE_VALUES["stephenson2"], guess=dict(beta=0.5, mu=0.2, phi=1.5, eta=0.3))
    with pytest.raises(ValueError, match="scan the linkage first"):
        motion.at([0.0])
