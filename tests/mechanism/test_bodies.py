"""Bodies, joints and Gruebler/Kutzbach mobility, against counts made by hand from each linkage's drawing."""
import numpy as np
import pytest
import sympy as sp

from symlink import Linkage, Loop, Vector, coordinates, lengths
from symlink.mechanism.bodies import GROUND, PRISMATIC, REVOLUTE, mechanism
from symlink.mechanism.catalog import CATALOG, fivebar, jansen, jansen_parameters
from symlink.numeric.solver import Solver

# Counted by hand from the catalog docstrings' drawings: the bodies (ground included), every
# pin with the bodies it joins (a pin joining k bodies is k - 1 joints), the sliders, and
# M = 3 (n - 1) - 2 j1.  Jansen leg: ground, crank m, links j, k, c, f, the triangles bde and ghi;
# the crank pin B joins crank, j and k, the pivot D joins ground, bde and c, F joins k, c and ghi.
HAND_COUNTS = {
    #                        n  pins: joint -> how many bodies            sliders  M
    "fourbar": (4, {"A": 2, "B": 2, "C": 2, "D": 2}, 0, 1),
    "slider-crank": (4, {"A": 2, "B": 2, "C": 2}, 1, 1),
    "inverted-slider-crank": (4, {"A": 2, "B": 2, "D": 2}, 1, 1),
    # ground, crank, rocker (with its offset arm DT and guide), block; the block slides on the guide
    "offset-inverted-slider-crank": (4, {"A": 2, "B": 2, "D": 2}, 1, 1),
    "watt2": (6, {"A": 2, "B": 2, "C": 2, "D": 2, "E": 2, "F": 2, "G": 2}, 0, 1),
    "stephenson2": (6, {"A": 2, "B": 2, "C": 2, "D": 2, "E": 2, "F": 2, "H": 2}, 0, 1),
    "fivebar": (5, {"A": 2, "B": 2, "C": 2, "D": 2, "E": 2}, 0, 2),
    "jansen": (8, {"A": 2, "B": 3, "C": 2, "D": 3, "E": 2, "F": 3, "G": 2}, 0, 1),
}


def test_every_catalog_entry_has_a_hand_count():
    assert set(HAND_COUNTS) == set(CATALOG)


@pytest.mark.parametrize("name", sorted(HAND_COUNTS))
def test_mobility_against_hand_count(name):
    bodies, pins, sliders, mobility = HAND_COUNTS[name]
    assert 3 * (bodies - 1) - 2 * (sum(k - 1 for k in pins.values()) + sliders) == mobility  # the hand count itself
    found = mechanism(CATALOG[name]())
    assert len(found.bodies) == bodies
    assert {j.name: len(j.bodies) for j in found.joints if j.kind == REVOLUTE} == pins
    assert sum(j.kind == PRISMATIC for j in found.joints) == sliders
    assert found.mobility == mobility == len(CATALOG[name]().inputs)


def test_jansen_leg_bodies_binary_and_ternary():
    found = mechanism(jansen())
    sizes = {body.name: set(body.points) for body in found.bodies}
    # two ternary links (the triangles), the foot H a corner of the lower one but no joint
    assert sizes["upper_rocker"] == {"C", "D", "E"} and sizes["leg"] == {"F", "G", "H"}
    assert set(found.body("leg").joints) == {"F", "G"}
    assert "H" not in {j.name for j in found.joints}
    binary = [b.name for b in found.bodies if len(b.points) == 2 and not b.is_ground]
    assert sorted(binary) == ["crank", "lower_link", "lower_rocker", "tie", "upper_link"]
    assert set(found.joint("D").bodies) == {GROUND, "upper_rocker", "lower_rocker"} and found.joint("D").grounded
    assert found.joint("B").count == 2 and found.joint("C").count == 1


@pytest.mark.parametrize("name", ["fourbar", "slider-crank", "inverted-slider-crank", "watt2", "fivebar", "jansen"])
def test_joint_positions_evaluate_to_the_solved_points(name):
    """A joint's position is a vector sum from the origin; evaluated, it is where the linkage puts the joint."""
    linkage = CATALOG[name]()
    values = {"fourbar": dict(a=1.0, b=3.0, c=2.5, d=3.2), "slider-crank": dict(a=1.0, b=3.0, offset=0.4),
              "inverted-slider-crank": dict(a=2.0, d=1.0), "fivebar": dict(a=2.0, b=4.0, c=4.0, d=3.0, e=2.0, psi=2.2),
              "watt2": dict(a=1.0, b=3.5, c=3.0, d=3.2, e=2.0, f=4.0, g=3.0, alpha=0.6, gx=4.5, gy=3.5),
              "jansen": jansen_parameters()}[name]
    theta = 0.7
    found = mechanism(linkage)
    names = [u.name for u in linkage.unknowns]
    solved = Solver(linkage, names)(theta=theta, **values)
    assert bool(np.all(solved["assembled"]))
    numbers = {s: values[s.name] for s in linkage.parameters} | {linkage.inputs[0]: theta}
    numbers |= {s: values[s.name] for s in linkage.inputs[1:]}
    numbers |= {u: float(solved[u.name]) for u in linkage.unknowns}
    points = Solver(linkage, [f"{p}_{axis}" for p in linkage.points for axis in "xy"])(theta=theta, **values)
    for joint in found.joints:
        x, y = (float(sp.sympify(part).subs(numbers)) for part in (joint.position.x, joint.position.y))
        if joint.name in linkage.points:
            assert abs(x - float(points[joint.name + "_x"])) < 1e-12
            assert abs(y - float(points[joint.name + "_y"])) < 1e-12
    assert all(joint.position is not None for joint in found.joints)


def scotch_yoke():
    theta, s, y = coordinates("theta s y")
    (a,) = lengths("a")
    AB, AS, SB = Vector(a, theta, "AB"), Vector(s, 0, "AS"), Vector(y, sp.pi / 2, "SB")
    return Linkage("yoke", [Loop(AS + SB - AB, name="ASB")], [theta], [s, y],
                   points={"A": None, "B": AB.as_sum(), "S": AS.as_sum()}, roles={"crank": theta, "yoke": s, "slot": y})


def test_scotch_yoke_slot_rides_on_the_yoke():
    # Hand count: ground, crank, yoke (slides on the ground), block (slides in the yoke's slot, pinned to
    # the crank): n = 4, revolutes A and B, prismatic ground-yoke and yoke-block: M = 9 - 8 = 1.
    found = mechanism(scotch_yoke())
    assert len(found.bodies) == 4 and found.mobility == 1
    assert found.joint("SB").bodies == ("yoke", "slot") and found.joint("AS").bodies == (GROUND, "yoke")
    assert found.joint("B").bodies == ("crank", "slot")
    assert {j.name for j in found.joints if j.kind == REVOLUTE} == {"A", "B"}
    assert str(found.joint("SB").guide_start) == "AS" and found.joint("SB").direction == sp.pi / 2


def geared_fivebar():
    """A five-bar whose second crank turns with the first (a 1:1 gear pair): ED at theta + delta."""
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, d, e = lengths("a b c d e")
    delta = sp.Symbol("delta", real=True)
    AB, BC, DC = Vector(a, theta, "AB"), Vector(b, beta, "BC"), Vector(c, phi, "DC")
    ED, AE = Vector(e, theta + delta, "ED"), Vector(d, 0, "AE")
    return Linkage("geared", [Loop(AE + ED + DC - BC - AB, name="ABCDE")], [theta], [beta, phi],
                   points={"A": None, "B": AB.as_sum(), "C": AB + BC, "D": AE + ED, "E": AE.as_sum()},
                   roles={"crank": theta})


def test_explicit_bodies_where_the_directions_are_ambiguous():
    # Read from the directions alone, the two cranks turn together, so they look like one body.
    merged = mechanism(geared_fivebar())
    assert set(merged.body("crank").vectors) == {"AB", "ED"}
    # Said explicitly: two cranks and the gear pair between them.  Hand count: ground, crank,
    # crank2, BC, DC = 5 bodies, 5 pins, one gear pair: M = 3 * 4 - 2 * 5 - 1 = 1.
    told = mechanism(geared_fivebar(), bodies={"crank2": ["ED"]}, higher_pairs=[("crank", "crank2")])
    assert len(told.bodies) == 5 and told.one_freedom_joints == 5 and told.mobility == 1
    assert set(told.body("crank2").joints) == {"D", "E"}


@pytest.mark.parametrize("bodies, higher_pairs, message", [
    ({"x": ["nope"]}, (), "has no vector 'nope'"),
    ({"": ["AB"]}, (), "non-empty strings"),
    ({}, [("crank", "nothing")], "must name two different bodies"),
    ({}, [("crank", "crank")], "must name two different bodies"),
])
def test_bad_explicit_bodies(bodies, higher_pairs, message):
    with pytest.raises(ValueError, match=message):
        mechanism(fivebar(), bodies=bodies, higher_pairs=higher_pairs)


def test_slider_travel_cannot_be_moved():
    with pytest.raises(ValueError, match="slider travel"):
        mechanism(scotch_yoke(), bodies={"x": ["AS"]})


def test_loop_not_in_walking_order_is_refused_when_points_show_it():
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, d = lengths("a b c d")
    AB, BC, DC, AD = Vector(a, theta, "AB"), Vector(b, beta, "BC"), Vector(c, phi, "DC"), Vector(d, 0, "AD")
    shuffled = Linkage("shuffled", [Loop(AB + BC - AD - DC)], [theta], [beta, phi],
                       points={"A": None, "C": AB + BC, "D": AD.as_sum()})
    with pytest.raises(ValueError, match="walking order"):
        mechanism(shuffled)


def test_two_vectors_with_one_name_are_refused():
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, d = lengths("a b c d")
    closure = Loop(Vector(d, 0, "X") + Vector(c, phi, "DC") - Vector(b, beta, "X") - Vector(a, theta, "AB"))
    with pytest.raises(ValueError, match="both named 'X'"):
        mechanism(Linkage("twice", [closure], [theta], [beta, phi]))


def test_a_pivot_reached_by_two_loops_through_different_vectors_is_one_pin():
    """Watt II written without points, its second loop starting at D with its own ground vector DG.

    Hand count: ground, crank, coupler, ternary rocker DCE, coupler EF, output GF: n = 6; pins A, B, C, D,
    E, F, G, each joining two bodies: j1 = 7; M = 15 - 14 = 1.  (Counting D once per loop would give -1.)
    """
    theta, beta, phi, mu, psi = coordinates("theta beta phi mu psi")
    a, b, c, d, e, f, g, h = lengths("a b c d e f g h")
    alpha = sp.Symbol("alpha", real=True)
    first = Loop(Vector(a, theta, "AB") + Vector(b, beta, "BC") - Vector(c, phi, "DC") - Vector(d, 0, "AD"), "ABCD")
    second = Loop(Vector(e, phi + alpha, "DE") + Vector(f, mu, "EF") - Vector(g, psi, "GF")
                  - Vector(h, 0, "DG"), "DEFG")
    found = mechanism(Linkage("watt", [first, second], [theta], [beta, phi, mu, psi]))
    assert len(found.bodies) == 6 and found.one_freedom_joints == 7 and found.mobility == 1
    assert sorted(len(body.joints) for body in found.bodies) == [2, 2, 2, 2, 3, 3]  # ground A D G; rocker D C E


def test_unnamed_vectors_and_points_get_plain_names():
    """The README's press: crank-rocker ABCD driving a rod CF to a slider F on y = h; only C is named.

    Hand count: ground, crank, coupler, rocker, rod, slider block: n = 6; pins A, B, D, F (two bodies
    each) and C (coupler, rocker, rod: 2 joints); one slider: j1 = 7; M = 15 - 14 = 1.
    """
    theta, beta, phi, psi, s = coordinates("theta beta phi psi s")
    a, b, c, d, e, h = lengths("a b c d e h")
    AB, BC, DC, AD = Vector(a, theta), Vector(b, beta), Vector(c, phi), Vector(d, 0)
    CF, AS, SF = Vector(e, psi), Vector(s, 0), Vector(h, sp.pi / 2)
    press = Linkage("press", [Loop(AD + DC - BC - AB, "ABCD"), Loop(AD + DC + CF - SF - AS, "DCF")],
                    inputs=[theta], unknowns=[beta, phi, psi, s], points={"C": AD + DC})
    found = mechanism(press)
    assert found.mobility == 1 and len(found.bodies) == 6
    assert sorted(j.name for j in found.joints) == ["C", "J1", "J2", "J3", "J4", "P1"]
    assert found.joint("C").count == 2 and found.joint("P1").bodies == (GROUND, "block_s")
