"""Linkages from their joints (symlink.mechanism.joints, symlink.mechanism.topology) against hand-written loops and geometry.

* The catalog's four-bar, slider-crank, Watt II and Jansen leg, described by
  their joints at a pose the catalog's own solver gives, reproduce the
  catalog's joint positions along a whole turn of the crank, both branches.
* Linkages that are not in the catalog (Hoeken's straight-line linkage,
  Chebyshev's lambda, a Watt I six-bar, a Klann-like leg) against a
  circle-intersection reference written here: each joint is where two circles
  about known joints meet, on the side of the line through their centres where
  the drawing puts it.  Positions at the drawn pose and along a turn; the rates
  of the link angles against central differences of the reference angles.
* Mobility and the refusals that name where a structure is wrong.
"""
import math

import numpy as np
import pytest

from symlink.mechanism.catalog import CATALOG, EXAMPLE_VALUES
from symlink.mechanism.joints import Slider, from_joints
from symlink.numeric.solver import NumericSolver, Solver
from symlink.mechanism.topology import Chain


def points_outputs(names):
    return [f"{p}_{axis}" for p in names for axis in "xy"]


def catalog_points(name, theta, branch, names):
    linkage = CATALOG[name]()
    result = Solver(linkage, points_outputs(names))(
        **EXAMPLE_VALUES[name], **{linkage.inputs[0].name: theta}, **{b.name: branch for b in linkage.branches})
    return {p: (np.asarray(result[f"{p}_x"], float), np.asarray(result[f"{p}_y"], float)) for p in names}


CATALOG_BY_JOINTS = {
    "fourbar": dict(links={"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]}),
    "slider-crank": dict(links={"ground": ["A", "C"], "crank": ["A", "B"], "rod": ["B", "C"]},
                         joints={"C": Slider("ground", 0.0)}),
    "watt2": dict(links={"ground": ["A", "D", "G"], "crank": ["A", "B"], "coupler": ["B", "C"],
                         "rocker": ["D", "C", "E"], "coupler2": ["E", "F"], "output": ["G", "F"]}),
    "jansen": dict(links={"ground": ["A", "D"], "crank": ["A", "B"], "j": ["B", "C"], "k": ["B", "F"],
                          "upper": ["D", "C", "E"], "lower": ["D", "F"], "tie": ["E", "G"], "leg": ["F", "G", "H"]}),
}


@pytest.mark.parametrize("branch", [1, -1])
@pytest.mark.parametrize("name", sorted(CATALOG_BY_JOINTS))
def test_a_catalog_linkage_from_its_joints_moves_as_its_hand_written_loops(name, branch):
    spec = CATALOG_BY_JOINTS[name]
    names = sorted({j for joints in spec["links"].values() for j in joints})
    drawn_at = 0.3
    pose = {p: (float(x), float(y)) for p, (x, y) in catalog_points(name, drawn_at, branch, names).items()}
    drawn = from_joints(coordinates=pose, driver="A", **spec)
    linkage = drawn.linkage
    assert linkage.has_closed_form
    assert set(drawn.branches.values()) == {1}  # the drawn assembly is every loop's +1
    assert 2 * len(linkage.loops) == len(linkage.unknowns)
    sweep = np.linspace(drawn_at, drawn_at + 2 * math.pi, 73)
    expected = catalog_points(name, sweep, branch, names)
    got = Solver(linkage, points_outputs(names))(**{**drawn.defaults, linkage.inputs[0].name: sweep})
    # Where the catalog's linkage assembles (Jansen's leg with every branch -1 does not turn fully), so does this.
    assembled = np.isfinite(expected[names[-1]][0])
    assert np.array_equal(np.asarray(got["assembled"]), assembled) and assembled.sum() > 36
    size = max(abs(c) for xy in pose.values() for c in xy)
    for p in names:
        assert np.max(np.abs(got[f"{p}_x"] - expected[p][0])[assembled]) < 1e-13 * size, p
        assert np.max(np.abs(got[f"{p}_y"] - expected[p][1])[assembled]) < 1e-13 * size, p


def test_the_four_bar_from_its_joints_is_the_catalog_s_case_and_names_its_sides():
    drawn = from_joints(CATALOG_BY_JOINTS["fourbar"]["links"],
                        {"A": (0, 0), "B": (12, 16), "C": (70, 50), "D": (80, 0)}, driver="A")
    linkage = drawn.linkage
    assert [s.case.name for s in linkage.plan] == ["3"]
    assert {p.name for p in linkage.parameters} == {"AB", "BC", "DC", "AD", "alpha_AD"}
    assert drawn.parameters["AB"] == 20.0 and drawn.parameters["AD"] == 80.0 and drawn.parameters["alpha_AD"] == 0.0
    assert drawn.parameters["BC"] == pytest.approx(math.hypot(58, 34), rel=1e-15)
    assert linkage.roles == {"crank": linkage.inputs[0], "coupler": linkage.unknowns[0], "rocker": linkage.unknowns[1]}
    assert drawn.mobility.dof == 1


# --- a circle-intersection reference ---------------------------------------------------------------------------

def circles(p, r, q, s, side):
    """The point at distance r from p and s from q, left of p -> q for side +1, right for -1."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    d = math.hypot(dx, dy)
    along = (r * r - s * s + d * d) / (2 * d)
    across = math.sqrt(r * r - along * along)
    ux, uy = dx / d, dy / d
    return (p[0] + along * ux - side * across * uy, p[1] + along * uy + side * across * ux)


def side_of(p, q, x):
    return 1 if (q[0] - p[0]) * (x[1] - p[1]) - (q[1] - p[1]) * (x[0] - p[0]) > 0 else -1


def dist(p, q):
    return math.hypot(q[0] - p[0], q[1] - p[1])


def rigid(p, q, p0, q0, x0):
    """Where x lands when the rigid body that carries p0, q0, x0 moves p0 -> p and q0 -> q."""
    a0 = math.atan2(q0[1] - p0[1], q0[0] - p0[0])
    a = math.atan2(q[1] - p[1], q[0] - p[0])
    c, s = math.cos(a - a0), math.sin(a - a0)
    rx, ry = x0[0] - p0[0], x0[1] - p0[1]
    return (p[0] + c * rx - s * ry, p[1] + s * rx + c * ry)


class Reference:
    """A one-crank linkage solved dyad by dyad by circle intersections, from its drawing.

    ``steps`` are ``(joint, first, second)``: the joint meets the circles about the
    known joints ``first`` and ``second`` (radii from the drawing), on the side of
    the drawing; ``carried`` are ``(point, p, q)``: a point riding rigidly with the
    known joints p, q (a third corner of a ternary link, a coupler point).
    """

    def __init__(self, drawing, pivot, crank_pin, steps, carried=()):
        self.d, self.pivot, self.pin, self.steps, self.carried = drawing, pivot, crank_pin, steps, carried
        self.sides = {j: side_of(drawing[a], drawing[b], drawing[j]) for j, a, b in steps}

    def crank_angle(self):
        p, b = self.d[self.pivot], self.d[self.pin]
        return math.atan2(b[1] - p[1], b[0] - p[0])

    def at(self, theta):
        d = self.d
        p = dict((k, d[k]) for k in d if k not in {j for j, _, _ in self.steps} | {c for c, _, _ in self.carried})
        radius = dist(d[self.pivot], d[self.pin])
        o = d[self.pivot]
        p[self.pin] = (o[0] + radius * math.cos(theta), o[1] + radius * math.sin(theta))
        for joint, a, b in self.steps:
            p[joint] = circles(p[a], dist(d[a], d[joint]), p[b], dist(d[b], d[joint]), self.sides[joint])
            for point, u, v in self.carried:
                if point not in p and u in p and v in p:
                    p[point] = rigid(p[u], p[v], d[u], d[v], d[point])
        for point, u, v in self.carried:
            p.setdefault(point, rigid(p[u], p[v], d[u], d[v], d[point]))
        return p


def hoeken():
    # Hoeken: crank 1, ground 2, rocker 2.5 pinned at the middle C of a coupler 5 long; P at its end.
    a, d = (0.0, 0.0), (2.0, 0.0)
    theta = 2.1
    b = (math.cos(theta), math.sin(theta))
    c = circles(b, 2.5, d, 2.5, -1)
    p = (2 * c[0] - b[0], 2 * c[1] - b[1])
    drawing = {"A": a, "B": b, "C": c, "D": d, "P": p}
    links = {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C", "P"], "rocker": ["D", "C"]}
    return links, drawing, Reference(drawing, "A", "B", [("C", "B", "D")], [("P", "B", "C")])


def chebyshev_lambda():
    # Chebyshev's lambda (link 2 = 1, link 4 = 2.5, link 3 = 2.5 + 2.5, link 1 = 2), drawn elbow the other way and
    # scaled by 3, its crank at (1, -0.5).
    a, d = (1.0, -0.5), (1.0 + 6.0 * math.cos(0.2), -0.5 + 6.0 * math.sin(0.2))
    theta = -0.7
    b = (a[0] + 3 * math.cos(theta), a[1] + 3 * math.sin(theta))
    c = circles(b, 7.5, d, 7.5, 1)
    p = (2 * c[0] - b[0], 2 * c[1] - b[1])
    drawing = {"A": a, "B": b, "C": c, "D": d, "P": p}
    links = {"ground": ["A", "D"], "crank": ["A", "B"], "lam": ["B", "C", "P"], "rocker": ["D", "C"]}
    return links, drawing, Reference(drawing, "A", "B", [("C", "B", "D")], [("P", "B", "C")])


def watt_one():
    # Watt I: the ground is a binary link; the crank ABE and the coupler BCF are the two adjacent ternary links.
    drawing = {"A": (0.0, 0.0), "D": (4.0, 0.0), "B": (0.8, 0.6), "E": (-0.3, 1.1), "C": (3.6, 2.9),
               "F": (2.0, 3.6), "G": (0.4, 4.4)}
    links = {"ground": ["A", "D"], "crank": ["A", "B", "E"], "coupler": ["B", "C", "F"], "rocker": ["D", "C"],
             "link5": ["E", "G"], "link6": ["G", "F"]}
    reference = Reference(drawing, "A", "B", [("C", "B", "D"), ("G", "E", "F")], [("E", "A", "B"), ("F", "B", "C")])
    return links, drawing, reference


def klann_like():
    # A Klann-like leg: ternary frame O, P1, P2; crank OA; ternary coupler ABC; lower rocker P1-B;
    # the leg C-D-foot, held by the upper rocker P2-D.
    drawing = {"O": (0.0, 0.0), "A": (0.25, 0.45), "P1": (-1.6, -0.5), "P2": (-1.1, 1.6), "B": (-1.0, -0.9),
               "C": (-1.7, 0.5), "D": (-2.3, 1.5), "foot": (-3.1, -2.2)}
    links = {"ground": ["O", "P1", "P2"], "crank": ["O", "A"], "coupler": ["A", "B", "C"], "lower": ["P1", "B"],
             "leg": ["C", "D", "foot"], "upper": ["P2", "D"]}
    reference = Reference(drawing, "O", "A", [("B", "A", "P1"), ("D", "C", "P2")],
                          [("C", "A", "B"), ("foot", "C", "D")])
    return links, drawing, reference


REFERENCES = {"hoeken": hoeken, "chebyshev-lambda": chebyshev_lambda, "watt-i": watt_one, "klann-like": klann_like}


@pytest.mark.parametrize("name", sorted(REFERENCES))
def test_positions_and_rates_equal_a_circle_intersection_reference(name):
    links, drawing, reference = REFERENCES[name]()
    pivot = reference.pivot
    drawn = from_joints(links, drawing, driver=pivot)
    linkage = drawn.linkage
    assert linkage.has_closed_form
    names = sorted(drawing)
    rates = [q.name + "dot" for q in linkage.unknowns]
    solver = Solver(linkage, points_outputs(names) + rates + [q.name for q in linkage.unknowns])
    theta0 = reference.crank_angle()
    size = max(abs(c) for xy in drawing.values() for c in xy)
    # The drawn pose itself.
    at_drawing = solver(**drawn.defaults)
    for p in names:
        assert abs(float(at_drawing[p + "_x"]) - drawing[p][0]) < 1e-12 * size, p
        assert abs(float(at_drawing[p + "_y"]) - drawing[p][1]) < 1e-12 * size, p
    # Along a turn of the crank (or as far as the reference assembles), with a crank speed of 1.7 rad/s.
    sweep = theta0 + np.linspace(-math.pi, math.pi, 61)
    speed = 1.7
    got = solver(**{**drawn.defaults, linkage.inputs[0].name: sweep, linkage.inputs[0].name + "dot": speed})
    checked = 0
    for k, theta in enumerate(sweep):
        try:
            expected = reference.at(theta)
        except ValueError:  # math domain error: the reference does not assemble there
            assert not bool(got["assembled"][k])
            continue
        assert bool(got["assembled"][k])
        checked += 1
        for p in names:
            assert abs(float(got[p + "_x"][k]) - expected[p][0]) < 1e-12 * size, (p, theta)
            assert abs(float(got[p + "_y"][k]) - expected[p][1]) < 1e-12 * size, (p, theta)
        # Rates: each unknown link angle's derivative by central differences of the reference.
        h = 1e-6
        ahead, behind = reference.at(theta + h), reference.at(theta - h)
        for q in linkage.unknowns:
            first, second = _side_of(q.name, links)
            def angle(p):
                return math.atan2(p[second][1] - p[first][1], p[second][0] - p[first][0])
            finite = math.remainder(angle(ahead) - angle(behind), 2 * math.pi) / (2 * h) * speed
            assert abs(float(got[q.name + "dot"][k]) - finite) < 1e-6 * max(1.0, abs(finite)), (q.name, theta)
    assert checked >= 20


def _side_of(coordinate, links):
    """The two joints whose side a link angle ``theta_XY`` is the direction of."""
    side = coordinate.removeprefix("theta_")
    for joints in links.values():
        for k, first in enumerate(joints):
            for second in joints[k + 1:]:
                if first + second == side or f"{first}_{second}" == side:
                    return first, second
    raise AssertionError(coordinate)


def test_the_hoeken_coupler_point_traces_its_straight_line():
    """Hoeken's point P moves along a near-straight line for about half a turn: the shape, from its joints."""
    links, drawing, _ = hoeken()
    drawn = from_joints(links, drawing, driver="A")
    solver = Solver(drawn.linkage, ["P_x", "P_y"])
    # Where the crank points away from D (theta near pi) P runs along a straight line
    theta = np.linspace(math.pi - 1.2, math.pi + 1.2, 41)
    got = solver(**{**drawn.defaults, "theta_AB": theta})
    ys = np.asarray(got["P_y"])
    assert np.ptp(ys) < 0.02 * np.ptp(np.asarray(got["P_x"]))


# --- sliders ------------------------------------------------------------------------------------------------------

def test_an_offset_slider_crank_from_its_joints_equals_the_geometry():
    # Crank 1.3 at A = (0.5, 0.2); rod 4.1; the slider pin C on the line y = 0.9 through C at 15 degrees... no:
    # a guide line at 10 degrees on the ground, through C.
    a, theta = (0.5, 0.2), 0.8
    guide = math.radians(10)
    b = (a[0] + 1.3 * math.cos(theta), a[1] + 1.3 * math.sin(theta))
    c = (b[0] + 3.5, b[1] + 0.4)
    drawn = from_joints({"ground": ["A", "C"], "crank": ["A", "B"], "rod": ["B", "C"]},
                        {"A": a, "B": b, "C": c}, driver="A", joints={"C": Slider("ground", guide)})
    linkage = drawn.linkage
    assert [s.case.name for s in linkage.plan] == ["2b"]
    solver = Solver(linkage, ["C_x", "C_y", "B_x", "B_y", "s_C"])
    rod = dist(b, c)
    # the line: points c + t (cos g, sin g); the pin is where the circle of radius rod about B meets it, on C's side
    for t in np.linspace(theta, theta + 2 * math.pi, 25):
        pin = (a[0] + 1.3 * math.cos(t), a[1] + 1.3 * math.sin(t))
        u = (math.cos(guide), math.sin(guide))
        w = (c[0] - pin[0], c[1] - pin[1])
        along = w[0] * u[0] + w[1] * u[1]
        across = w[0] * u[1] - w[1] * u[0]
        step = -along + math.sqrt(rod * rod - across * across)  # the far assembly, as drawn (C ahead of B)
        expected = (c[0] + step * u[0], c[1] + step * u[1])
        got = solver(**{**drawn.defaults, "theta_AB": t})
        assert abs(float(got["C_x"]) - expected[0]) < 1e-13 * 5 and abs(float(got["C_y"]) - expected[1]) < 1e-13 * 5


def test_an_inverted_slider_crank_from_its_joints():
    # The block pinned to the crank at B slides on the rocker through D (Whitworth): the rocker's angle is B's
    # direction from D, the travel B's distance from D.
    a, d = (0.0, 0.0), (1.2, 0.0)
    b = (2.0 * math.cos(0.4), 2.0 * math.sin(0.4))
    direction = math.atan2(b[1] - d[1], b[0] - d[0])
    drawn = from_joints({"ground": ["A", "D"], "crank": ["A", "B"], "rocker": ["D", "B"]},
                        {"A": a, "B": b, "D": d}, driver="A", joints={"B": Slider("rocker", direction)})
    linkage = drawn.linkage
    assert [s.case.name for s in linkage.plan] == ["2a"]
    solver = Solver(linkage, ["theta_DB", "s_B"])
    for t in np.linspace(0.0, 2 * math.pi, 13):
        got = solver(**{**drawn.defaults, "theta_AB": t})
        pin = (2.0 * math.cos(t) - 1.2, 2.0 * math.sin(t))
        assert abs(math.remainder(float(got["theta_DB"]) - math.atan2(pin[1], pin[0]), 2 * math.pi)) < 1e-13
        assert abs(float(got["s_B"]) - math.hypot(*pin)) < 1e-13 * 2


def test_a_slider_can_be_the_driver():
    drawn = from_joints({"ground": ["A", "C"], "crank": ["A", "B"], "rod": ["B", "C"]},
                        {"A": (0, 0), "B": (0.6, 1.0), "C": (3.0, 0.0)}, driver="C",
                        joints={"C": Slider("ground", 0.0)})
    assert [q.name for q in drawn.linkage.inputs] == ["s_C"]
    got = Solver(drawn.linkage, ["B_x", "B_y"])(**{**drawn.defaults, "s_C": 2.5})
    rod, crank = math.hypot(2.4, 1.0), math.hypot(0.6, 1.0)
    assert math.hypot(float(got["B_x"]), float(got["B_y"])) == pytest.approx(crank, rel=1e-14)
    assert math.hypot(float(got["B_x"]) - 2.5, float(got["B_y"])) == pytest.approx(rod, rel=1e-14)


# --- Newton where no dyad is left --------------------------------------------------------------------------------

def test_a_stephenson_iii_driven_at_the_wrong_link_falls_back_to_newton_and_reproduces_its_drawing():
    # The catalog's Stephenson II: ground A-D binary; crank AB; ternary coupler BCE; ternary rocker DFH; CF and EH.
    drawing = {"A": (0.0, 0.0), "D": (4.5, 0.0), "B": (0.3, 0.95), "C": (3.2, 2.0), "E": (1.5, 4.2),
               "F": (5.3, 2.8), "H": (4.8, 4.6)}
    links = {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C", "E"], "rocker": ["D", "F", "H"],
             "cf": ["C", "F"], "eh": ["E", "H"]}
    drawn = from_joints(links, drawing, driver="A")
    linkage = drawn.linkage
    assert not linkage.has_closed_form
    assert len(linkage.loops) == 2 and len(linkage.unknowns) == 4
    assert drawn.structure[-1][1] == ("coupler", "rocker", "cf", "eh")
    got = NumericSolver(linkage)(guess=drawn.guess, **drawn.defaults)
    for p, (x, y) in drawing.items():
        assert abs(float(np.ravel(got[p + "_x"])[0]) - x) < 1e-12, p
        assert abs(float(np.ravel(got[p + "_y"])[0]) - y) < 1e-12, p
    # Driven at its other ground pivot the rest is still one triad (crank, coupler and the two binary links hang
    # from A, F and H): no loop has two unknowns, whichever ground pivot drives.
    assert not from_joints(links, drawing, driver="D").linkage.has_closed_form


# --- structure and refusals ------------------------------------------------------------------------------------------

def test_gruebler_mobility_counts_pins_and_sliders():
    assert Chain({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"],
                  "rocker": ["D", "C"]}).mobility().dof == 1
    five = Chain({"ground": ["A", "E"], "l1": ["A", "B"], "l2": ["B", "C"], "l3": ["C", "D"], "l4": ["D", "E"]})
    assert five.mobility().dof == 2
    # A pin joining three links counts as two joints.
    triple = Chain({"ground": ["A", "D", "F"], "crank": ["A", "B"], "c1": ["B", "C"], "r1": ["D", "C"],
                    "c2": ["C", "E"], "r2": ["F", "E"]})
    assert triple.mobility().revolute == 7 and triple.mobility().dof == 1
    slider = Chain({"ground": ["A", "C"], "crank": ["A", "B"], "rod": ["B", "C"]}, sliders={"C": "ground"})
    assert (slider.mobility().links, slider.mobility().prismatic, slider.mobility().dof) == (4, 1, 1)


def test_a_structure_with_too_many_or_too_few_drivers_is_refused_naming_the_count():
    links = {"ground": ["A", "E"], "l1": ["A", "B"], "l2": ["B", "C"], "l3": ["C", "D"], "l4": ["D", "E"]}
    drawing = {"A": (0, 0), "B": (0, 1), "C": (1, 2), "D": (2, 1), "E": (2, 0)}
    with pytest.raises(ValueError, match="under-constrained: Gruebler gives mobility 2 .* 1 driver"):
        from_joints(links, drawing, driver="A")
    two = from_joints(links, drawing, driver=["A", "E"])
    assert len(two.linkage.inputs) == 2 and two.linkage.has_closed_form


def test_an_over_constrained_part_is_named():
    # A four-bar with an extra link between B and D: the triangle B, C, D (coupler, rocker, extra) is rigid, and the
    # whole has mobility 0.
    links = {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"],
             "extra": ["B", "D"]}
    drawing = {"A": (0, 0), "B": (0, 1), "C": (2, 2), "D": (3, 0)}
    with pytest.raises(ValueError, match="over-constrained"):
        from_joints(links, drawing, driver="A")
    # Two links sharing two pins are one rigid link twice over.
    doubled = {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"],
               "again": ["B", "C"]}
    with pytest.raises(ValueError, match="links coupler, again are over-constrained"):
        from_joints(doubled, {"A": (0, 0), "B": (0, 1), "C": (2, 2), "D": (3, 0)}, driver="A")


@pytest.mark.parametrize("links, coordinates, driver, joints, message", [
    ({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
     {"A": (0, 0), "B": (0, 1), "C": (2, 2)}, "A", None, "no position for joint D"),
    ({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
     {"A": (0, 0), "B": (0, 1), "C": (2, 2), "D": (3, 0)}, [("B", "rocker")], None,
     "driver 'B' joins crank, coupler: a relative driver is a pin between two moving links"),
    ({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
     {"A": (0, 0), "B": (0, 1), "C": (2, 2), "D": (3, 0)}, "Q", None, "driver 'Q' is not a joint"),
    ({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
     {"A": (0, 0), "B": (0, 0), "C": (2, 2), "D": (3, 0)}, "A", None, "joints 'A' and 'B' are drawn at the same"),
    ({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
     {"A": (0, 0), "B": (0, float("nan")), "C": (2, 2), "D": (3, 0)}, "A", None, "B.y must be finite"),
    ({"ground": ["A", "D"], "crank": ["A"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
     {"A": (0, 0), "B": (0, 1), "C": (2, 2), "D": (3, 0)}, "A", None, "link 'crank' holds 1 joint"),
    ({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
     {"A": (0, 0), "B": (0, 1), "C": (2, 2), "D": (3, 0)}, "A", {"C": "slot"}, "a joint is 'R'"),
    ({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
     {"A": (0, 0), "B": (0, 1), "C": (2, 2), "D": (3, 0)}, "A", {"C": Slider("crank", 0.0)},
     "its guide 'crank' does not list it"),
    ({"base": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
     {"A": (0, 0), "B": (0, 1), "C": (2, 2), "D": (3, 0)}, "A", None, "no ground link 'ground'"),
    ({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"], "lost": ["X", "Y"]},
     {"A": (0, 0), "B": (0, 1), "C": (2, 2), "D": (3, 0), "X": (5, 5), "Y": (6, 6)}, "A", None,
     "links lost are not connected"),
    ({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
     {"A": (0, 0), "B": (0, 1), "C": (2, 2), "D": (3, 0)}, [], None, "name the driven joint"),
])
def test_bad_descriptions_are_refused_with_a_sentence_naming_the_problem(links, coordinates, driver, joints, message):
    with pytest.raises(ValueError, match=message):
        from_joints(links, coordinates, driver=driver, joints=joints)


def test_the_cycles_of_a_watt_chain_and_their_rank():
    chain = Chain({"ground": ["A", "D", "G"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C", "E"],
                   "c2": ["E", "F"], "out": ["G", "F"]})
    assert [c.name for c in chain.cycles()] == ["ABCD", "DEFG", "ABCEFG"]
    assert chain.cycle_rank() == 2


# --- the [links] and [joints] tables of a linkage file --------------------------------------------------------------

JOINT_FILE = '''
name = "offset slider-crank"
driver = "A"

[links]
ground = ["A", "C"]
crank = ["A", "B"]
rod = ["B", "C"]

[joints]
A = [0, 0]
B = [0.6, 1.0]
C = {at = [3.0, 0.4], slider = "ground", angle = "0 deg"}
'''


def test_a_linkage_file_by_its_joints_gives_the_linkage_and_its_drawing():
    from symlink.io.linkage_file import linkage_from_text
    found = linkage_from_text(JOINT_FILE, source="slider.toml")
    linkage = found.linkage
    assert [s.case.name for s in linkage.plan] == ["2b"]
    got = Solver(linkage, ["C_x", "C_y", "B_x", "B_y"])(**found.defaults)  # the branches' default: the drawing
    assert (float(got["C_x"]), float(got["C_y"])) == pytest.approx((3.0, 0.4), abs=1e-14)
    assert (float(got["B_x"]), float(got["B_y"])) == pytest.approx((0.6, 1.0), abs=1e-14)
    # Along a turn the pin stays on its line y = 0.4 and the rod keeps its drawn length.
    turn = Solver(linkage, ["C_x", "C_y", "B_x", "B_y"])(**{**found.defaults, "theta_AB": np.linspace(0, 6.2, 32)})
    assert np.max(np.abs(np.asarray(turn["C_y"]) - 0.4)) < 1e-14
    rod = np.hypot(np.asarray(turn["C_x"]) - turn["B_x"], np.asarray(turn["C_y"]) - turn["B_y"])
    assert np.max(np.abs(rod - math.hypot(2.4, 0.6))) < 1e-13


@pytest.mark.parametrize("change, message", [
    (('B = [0.6, 1.0]', 'B = [0.6, "one"]'), "slider.toml:12: joints.B: y must be a number, got 'one'"),
    (('B = [0.6, 1.0]', 'B = [0.6]'), "slider.toml:12: joints.B: a position is [x, y]"),
    (('angle = "0 deg"', 'angle = "sin(0)"'), "slider.toml:13: joints.C: angle"),
    (('angle = "0 deg"}', 'angle = "0 deg", speed = 2}'), "slider.toml:13: joints.C: a slider is"),
    (('driver = "A"', 'driver = 3'), "slider.toml:3: driver must be a joint name"),
    (('rod = ["B", "C"]', 'rod = ["B"]'), "slider.toml:8: links.rod: link 'rod' holds 1 joint"),
    (('driver = "A"', 'driver = "A"\ninputs = ["x"]'), "slider.toml:4: unknown key 'inputs'"),
    (('crank = ["A", "B"]', 'crank = ["A", "B"]\nspare = ["B", "Q"]'), "slider.toml:11: coordinates: no position for joint Q"),
    ((('crank = ["A", "B"]', 'crank = ["A", "B"]\nspare = ["B", "Q"]'), ("A = [0, 0]", "A = [0, 0]\nQ = [5, 5]")),
     "slider.toml:5: the linkage is under-constrained: Gruebler gives mobility 2"),

])
def test_a_bad_joint_file_is_one_line_naming_the_file_and_line(change, message):
    from symlink.io.linkage_file import linkage_from_text
    text = JOINT_FILE
    for old, new in (change if isinstance(change[0], tuple) else [change]):
        text = text.replace(old, new)
    with pytest.raises(ValueError) as error:
        linkage_from_text(text, source="slider.toml")
    assert message in str(error.value) and "\n" not in str(error.value)


def test_a_pin_between_two_moving_links_drives_their_relative_angle():
    # A four-bar driven at C by the angle between coupler and rocker.  Reference: the triangle B, C, D has the
    # sides BC, DC and the angle q at C, so BD by the law of cosines; B where the circles (A, AB) and (D, BD)
    # meet on its drawn side of A-D; C the meeting point of (B, BC) and (D, DC) whose angle from C->B to C->D is q.
    links = {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]}
    drawing = {"A": (0.0, 0.0), "B": (0.5, 1.9), "C": (3.2, 2.6), "D": (4.0, 0.0)}
    drawn = from_joints(links, drawing, driver="C")
    linkage = drawn.linkage
    assert [q.name for q in linkage.inputs] == ["theta_C"] and linkage.has_closed_form
    ab, bc, dc = (math.dist(drawing[p], drawing[q]) for p, q in (("A", "B"), ("B", "C"), ("D", "C")))
    a, d = drawing["A"], drawing["D"]
    side = side_of(a, d, drawing["B"])
    q0 = drawn.pose["theta_C"]
    assert q0 == pytest.approx(math.remainder(math.atan2(-2.6, 0.8) - math.atan2(-0.7, -2.7), 2 * math.pi), abs=1e-15)
    sweep = q0 + np.linspace(-0.4, 0.4, 17)
    solver = Solver(linkage, ["B_x", "B_y", "C_x", "C_y", "theta_ABdot"])
    got = solver(**{**drawn.defaults, "theta_C": sweep, "theta_Cdot": 1.0})

    def reference(q):
        bd = math.sqrt(bc * bc + dc * dc - 2 * bc * dc * math.cos(q))
        b = circles(a, ab, d, bd, side)
        both = [circles(b, bc, d, dc, s) for s in (1, -1)]
        c = min(both, key=lambda p: abs(math.remainder(
            math.atan2(d[1] - p[1], d[0] - p[0]) - math.atan2(b[1] - p[1], b[0] - p[0]) - q, 2 * math.pi)))
        return b, c

    for k, q in enumerate(sweep):
        b, c = reference(q)
        assert abs(got["B_x"][k] - b[0]) < 1e-12 * 4 and abs(got["B_y"][k] - b[1]) < 1e-12 * 4, q
        assert abs(got["C_x"][k] - c[0]) < 1e-12 * 4 and abs(got["C_y"][k] - c[1]) < 1e-12 * 4, q
        h = 1e-6
        (b1, _), (b0, _) = reference(q + h), reference(q - h)
        finite = math.remainder(math.atan2(b1[1], b1[0]) - math.atan2(b0[1], b0[0]), 2 * math.pi) / (2 * h)
        assert abs(got["theta_ABdot"][k] - finite) < 1e-6 * max(1.0, abs(finite)), q
    with pytest.raises(ValueError, match="a relative driver is a pin between two moving links"):
        from_joints({**links, "extra": ["B", "E"], "tie": ["E", "D"]}, {**drawing, "E": (2.0, -1.0)}, driver="B")
