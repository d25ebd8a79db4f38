"""Other tools' descriptions (symlink.io): Pyslvs expressions and pylinkage JSON mechanisms.

* Pyslvs: mechanism expressions written for this test in Pyslvs's grammar (R, RP and P joints; a four-bar,
  slider-cranks, a slotted lever, a translating block, an inverted slider-crank, a Scotch yoke, Watt II and
  Stephenson II six-bars, Jansen's eight-bar leg and a two-input arm; at symlink's catalog values or at
  coordinates chosen here) read, build and move along a turn of their input with every link keeping the
  lengths of its drawing and every slot its line (a check by geometry, independent of the solver); written back
  and read again to the same joints; bad text refused with a column.
* pylinkage: its own published examples (the four-bar, crank-slider and Chebyshev mechanisms of its
  ``api/routers/examples.py``) built and serialised by the installed pylinkage, read here, and solved along the
  steps of pylinkage's own simulation to its positions; and symlink's linkages written for pylinkage, loaded
  and simulated by pylinkage, to symlink's positions.
* Either, written as symlink's own linkage file and read back, solves to the same positions.
"""
import json
import math

import numpy as np
import pytest

from symlink.io.pylinkage import read_pylinkage, write_pylinkage
from symlink.io.pyslvs import pyslvs_inputs, read_pyslvs, read_pyslvs_project, write_pyslvs
from symlink.io.joint_tables import joint_file_text
from symlink.mechanism.joints import Slider, from_joints
from symlink.io.linkage_file import linkage_from_text, linkage_text
from symlink.numeric.solver import NumericSolver, Solver

PYSLVS_EXAMPLES = {
    "four-bar crank-rocker": (  # the seed four-bar a = 20, b = 66, c = 56, d = 80, its crank at 50 degrees
        "M["
        "J[R, color[Blue], P[0, 0], L[ground, crank]],  # the crank's pivot\n"
        "J[R, color[Blue], P[80, 0], L[ground, rocker]],\n"
        "J[R, color[Red], P[12.856, 15.321], L[crank, coupler]],\n"
        "J[R, color[Green], P[66.146, 54.259], L[coupler, rocker]],\n"
        "J[R, color[Orange], P[20.035, 44.449], L[coupler]]  # a point of the coupler, 30 from the crank pin\n"
        "]", ((0, 2),)),
    "slider-crank (RP on the ground)": (  # symlink's slider_crank at 10 times its example values, at 45 degrees
        "M["
        "J[R, color[Blue], P[0, 0], L[ground, crank]],"
        "J[R, color[Green], P[9.192, 9.192], L[crank, rod]],"
        "J[RP, A[0], color[Dark-Green], P[50.134, 7], L[ground, rod]]"
        "]", ((0, 1),)),
    "oscillating cylinder (RP: a slot in the rod)": (  # the rod slides through a trunnion pinned to the ground
        "M["
        "J[R, color[Blue], P[0, 0], L[ground, crank]],"
        "J[R, color[Green], P[-6, 10.392], L[crank, rod]],"
        "J[RP, A[-5.454], color[Magenta], P[40, 6], L[rod, ground]]"
        "]", ((0, 1),)),
    "lifter (RP on the ground and on a lever)": (
        "M["
        "#[ a slider-crank on a guide at 10 degrees; a pin of its rod\n"
        "   drives a slotted lever about (40, 60) #]\n"
        "J[R, color[Blue], P[0, 0], L[ground, crank]],\n"
        "J[R, color[Green], P[7.5, 12.99], L[crank, rod]],\n"
        "J[RP, A[10], color[Green], P[50.967, 1.344], L[ground, rod]],\n"
        "J[RP, A[-100], color[Cyan], P[32, 20], L[lever, rod]],  # the slot is in the lever\n"
        "J[R, color[Blue], P[40, 60], L[ground, lever]],\n"
        "J[R, color[(200, 120, 0)], P[75, 85], L[lever]],\n"
        "]", ((0, 1),)),
    "block on an inclined guide (P on the ground)": (
        "M["
        "J[R, color[Blue], P[0, 0], L[ground, crank]],"
        "J[R, color[Green], P[-3.126, 17.727], L[crank, rod]],"
        "J[R, color[Green], P[50, 35], L[rod, block]],"
        "J[P, A[30], color[Dark-Red], P[60, 40.774], L[ground, block]],  # the block slides at 30 degrees\n"
        "J[R, color[Green], P[70, 30], L[block, link]],"
        "J[R, color[Green], P[100, 40], L[link, rocker]],"
        "J[R, color[Blue], P[95, 0], L[ground, rocker]]"
        "]", ((0, 1),)),
    "inverted slider-crank (P on a turning rocker)": (  # symlink's offset inverted slider-crank, 20 times
        "M["
        "J[R, color[Blue], P[0, 0], L[ground, crank]],"
        "J[R, color[Blue], P[50, 0], L[ground, rocker]],"
        "J[R, color[Green], P[6.84, 18.794], L[crank, block]],"
        "J[P, A[146.685], color[Yellow], P[19.375, 10.555], L[rocker, block]]"
        "]", ((0, 2),)),
    "Scotch yoke (two P joints)": (
        "M["
        "J[R, color[Blue], P[0, 0], L[ground, crank]],"
        "J[R, color[Green], P[19.151, 16.07], L[crank, block]],"
        "J[P, A[90], color[Green], P[19.151, 24], L[yoke, block]],  # a vertical slot in the yoke\n"
        "J[P, A[0], color[Gray], P[60, -5], L[ground, yoke]]"
        "]", ((0, 1),)),
    "Watt II six-bar": (  # symlink's watt2 at 20 times its example values, its crank at 70 degrees
        "M["
        "J[R, color[Blue], P[0, 0], L[ground, crank]],"
        "J[R, color[Green], P[6.84, 18.794], L[crank, coupler]],"
        "J[R, color[Green], P[63.429, 59.997], L[coupler, rocker]],"
        "J[R, color[Blue], P[64, 0], L[ground, rocker]],"
        "J[R, color[Green], P[41.101, 32.797], L[rocker, coupler2]],"
        "J[R, color[Green], P[47.674, 112.527], L[coupler2, output]],"
        "J[R, color[Blue], P[90, 70], L[ground, output]]"
        "]", ((0, 1),)),
    "Stephenson II six-bar": (  # symlink's stephenson2 at 20 times its example values, its crank at 80 degrees
        "M["
        "J[R, color[Blue], P[0, 0], L[ground, crank]],"
        "J[R, color[Green], P[3.473, 19.696], L[crank, bce]],"
        "J[R, color[Green], P[52.629, 57.481], L[bce, cf]],"
        "J[R, color[Green], P[4.678, 97.687], L[bce, eh]],"
        "J[R, color[Blue], P[90, 0], L[ground, dfh]],"
        "J[R, color[Green], P[96.429, 61.666], L[cf, dfh]],"
        "J[R, color[Green], P[77.919, 60.812], L[eh, dfh]]"
        "]", ((0, 1),)),
    "Jansen leg (eight-bar)": (  # Jansen's holy numbers (symlink.mechanism.catalog.jansen), its crank at 30 degrees
        "M["
        "J[R, color[Blue], P[0, 0], L[ground, m]],"
        "J[R, color[Blue], P[-38, -7.8], L[ground, bde, c]],"
        "J[R, color[Red], P[12.99, 7.5], L[m, j, k]],"
        "J[R, color[Green], P[-30.058, 32.933], L[j, bde]],"
        "J[R, color[Green], P[-76.776, 2.419], L[bde, f]],"
        "J[R, color[Green], P[-21.882, -43.643], L[k, c, ghi]],"
        "J[R, color[Green], P[-56.457, -31.337], L[f, ghi]],"
        "J[R, color[Dark-Orange], P[-30.806, -91.823], L[ghi]]  # the foot\n"
        "]", ((0, 2),)),
    "two-input arm (coaxial cranks)": (  # two cranks on one ground pin; a dyad to the ground carries the tip
        "M["
        "J[R, color[Blue], P[0, 0], L[ground, crank1, crank2]],"
        "J[R, color[Green], P[5.209, 29.544], L[crank1, upper]],"
        "J[R, color[Green], P[18.794, 6.84], L[crank2, fore]],"
        "J[R, color[Green], P[45, 40], L[upper, fore]],"
        "J[R, color[Green], P[58, 57], L[fore, link]],"
        "J[R, color[Green], P[50, 80], L[link, hand]],"
        "J[R, color[Blue], P[10, 70], L[ground, hand]],"
        "J[R, color[Pink], P[80, 90], L[link]]"
        "]", ((0, 1), (0, 2))),
}


def joint_positions(drawn, sweeps):
    """Every joint's position along ``sweeps`` (one array per input), closed form or Newton."""
    linkage = drawn.linkage
    names = [f"{p}_{axis}" for p in drawn.chain.joints for axis in "xy"] + list(linkage.roles)
    values = {q.name: s for q, s in zip(linkage.inputs, sweeps)}
    if linkage.has_closed_form:
        result = Solver(linkage, names)(**{**drawn.defaults, **values})
    else:
        result = NumericSolver(linkage)(guess=drawn.guess, **{**drawn.parameters, **values})
    found = {p: (np.asarray(result[p + "_x"], float), np.asarray(result[p + "_y"], float)) for p in drawn.chain.joints}
    found.update({role: np.asarray(result[role], float) for role in linkage.roles})
    return found, np.asarray(result["assembled"])


def check_rigid(drawn, got, assembled, size):
    """Each link keeps the distances between its joints that the drawing gives; each slider stays on its line."""
    c = drawn.coordinates
    for link, joints in drawn.chain.links.items():
        fixed = [j for j in joints if drawn.chain.sliders.get(j) != link]
        for k, a in enumerate(fixed):
            for b in fixed[k + 1:]:
                length = math.dist(c[a], c[b])
                moving = np.hypot(got[a][0] - got[b][0], got[a][1] - got[b][1])
                assert np.max(np.abs(moving - length)[assembled]) < 1e-9 * size, (link, a, b)
    for joint, guide in drawn.chain.sliders.items():
        anchor = [j for j in drawn.chain.links[guide] if drawn.chain.sliders.get(j) != guide]
        first = anchor[0]
        angle = drawn.slider_angles[joint]
        if guide == drawn.chain.ground or guide not in drawn.linkage.roles:  # a guide that does not turn (the
            direction = np.full(len(assembled), angle)  # ground, or a block translating on the ground: the yoke)
        else:  # the line turns with its guide, by as much as the guide's angle (solved) has turned since the drawing
            direction = got[guide] - got[guide][0] + angle
        drawn_across = ((c[joint][1] - c[first][1]) * math.cos(angle) - (c[joint][0] - c[first][0]) * math.sin(angle))
        across = ((got[joint][1] - got[first][1]) * np.cos(direction)
                  - (got[joint][0] - got[first][0]) * np.sin(direction))
        assert np.max(np.abs(across - drawn_across)[assembled]) < 1e-9 * size, joint
    for joint in drawn.chain.translating:  # a block keeps its drawn angle to its guide
        guide = drawn.chain.sliders[joint]
        block = next(link for link in drawn.chain.links_of(joint) if link != guide)
        own = [j for j in drawn.chain.links[block] if drawn.chain.sliders.get(j) != block]  # its points, not its slots'
        if len(own) < 2:  # one point of its own (the yoke: its slot's joint is the block's in it): its line checks it
            continue
        first, second = own[:2]
        turned = np.arctan2(got[second][1] - got[first][1], got[second][0] - got[first][0])
        guide_turned = got[guide] - got[guide][0] if guide in drawn.linkage.roles else 0.0
        change = np.remainder(turned - turned[0] - guide_turned + np.pi, 2 * np.pi) - np.pi
        assert np.max(np.abs(change)[assembled]) < 1e-9, (joint, block)


@pytest.mark.parametrize("name", sorted(PYSLVS_EXAMPLES))
def test_a_pyslvs_example_moves_as_its_drawing_says(name):
    expression, inputs = PYSLVS_EXAMPLES[name]
    description = read_pyslvs(expression, inputs)
    drawn = description.build()
    assert drawn.mobility.dof == len(inputs)
    size = max(abs(v) for xy in drawn.coordinates.values() for v in xy)
    starts = [drawn.pose[q.name] for q in drawn.linkage.inputs]
    turn = np.linspace(0.0, 2 * math.pi, 73) if len(inputs) == 1 else np.linspace(0.0, 0.3, 13)
    sweeps = [s + turn for s in starts]
    got, assembled = joint_positions(drawn, sweeps)
    assert assembled.sum() >= 10
    for joint, (x, y) in drawn.coordinates.items():  # the drawn pose first
        assert abs(got[joint][0][0] - x) < 1e-12 * size and abs(got[joint][1][0] - y) < 1e-12 * size
    check_rigid(drawn, got, assembled, size)


def test_pyslvs_comments_colours_and_trailing_commas_are_its_grammar():
    text = """# a crank-rocker
    M[
      J[R, color[(255, 0, 0)], P[0, 0], L[ground, L1]],  # the crank pivot
      #[ a comment
         over lines #]
      J[R, A[0], color[brick-red], P[0, 20], L[L1, L2,]],
      J[R, color[GREEN], P[+60, 5e1], L[L2, L3]],
      J[R, P[80.0, -.0], L[ground, L3]],
    ]"""
    description = read_pyslvs(text)
    assert description.coordinates == {"A": (0.0, 0.0), "B": (0.0, 20.0), "C": (60.0, 50.0), "D": (80.0, 0.0)}
    assert description.links == {"ground": ["A", "D"], "L1": ["A", "B"], "L2": ["B", "C"], "L3": ["C", "D"]}


def test_pyslvs_plans_name_the_closed_forms_and_the_newton_fallback():
    plans = {name: read_pyslvs(*PYSLVS_EXAMPLES[name]).build().linkage for name in PYSLVS_EXAMPLES}
    assert [s.case.name for s in plans["four-bar crank-rocker"].plan] == ["3"]
    assert [s.case.name for s in plans["slider-crank (RP on the ground)"].plan] == ["2b"]
    assert [s.case.name for s in plans["oscillating cylinder (RP: a slot in the rod)"].plan] == ["2c"]
    # the lifter's slot on its turning lever: 2c
    assert [s.case.name for s in plans["lifter (RP on the ground and on a lever)"].plan] == ["2b", "2c"]
    assert [s.case.name for s in plans["Watt II six-bar"].plan] == ["3", "3"]
    assert [s.case.name for s in plans["Jansen leg (eight-bar)"].plan] == ["3", "3", "3"]
    assert not plans["Stephenson II six-bar"].has_closed_form
    assert len(plans["two-input arm (coaxial cranks)"].inputs) == 2
    # Pyslvs's P joints: a block that slides on its guide without turning (the inverted slider's block on its
    # rocker; a block on a guide of the ground; the Scotch yoke's block in its yoke, the yoke on the ground).
    assert [s.case.name for s in plans["inverted slider-crank (P on a turning rocker)"].plan] == ["2c"]
    assert [s.case.name for s in plans["block on an inclined guide (P on the ground)"].plan] == ["2b", "3"]
    assert [s.case.name for s in plans["Scotch yoke (two P joints)"].plan] == ["1"]


@pytest.mark.parametrize("name", sorted(PYSLVS_EXAMPLES))
def test_a_pyslvs_expression_written_and_read_again_is_the_same_mechanism(name):
    description = read_pyslvs(*PYSLVS_EXAMPLES[name])
    drawn = description.build()
    text = write_pyslvs(drawn)
    assert pyslvs_inputs(drawn) == list(PYSLVS_EXAMPLES[name][1])
    again = read_pyslvs(text, pyslvs_inputs(drawn))
    assert {k: sorted(v) for k, v in again.links.items()} == {k: sorted(v) for k, v in description.links.items()}
    assert again.coordinates == description.coordinates
    assert again.drivers == description.drivers


@pytest.mark.parametrize("text, message", [
    ("M[J[R, P[0, 0], L[ground, L1]]", "column 31: expected ',' or ']' after a joint, found the end"),
    ("M[J[Q, P[0, 0], L[ground]]]", "column 5: expected 'R' or 'P' or 'RP', found 'Q'"),
    ("M[J[R, color[Mauve], P[0, 0], L[ground]]]", "column 14: 'Mauve' is not a Pyslvs colour"),
    ("M[J[R, P[0, 0, 1], L[ground]]]", "column 14: expected ']', found ','"),
    ("M[J[R, P[0, __import__], L[ground]]]", "column 13: expected a number"),
    ("M[J[R, P[0, 0], L[ground]]] extra", "column 29: expected the end"),
    ("M[J[R, P[0, 0], L[ground]]]; x", "column 28: unexpected ';'"),
    ("M[J[RP, P[0, 0], L[ground, L1]]]", "column 9: expected 'A'"),
    ("M[J[P, A[0], P[0, 0], L[L1]], J[R, P[1, 0], L[ground, L1]]]", "is a P joint on one link only"),
    ("M[]", "has no joints"),
    ("M[J[R, P[0, 0], L[ground, L1]], J[R, P[1, 1], L[L1]]]", "input pair"),
])
def test_bad_pyslvs_text_is_refused_naming_the_column(text, message):
    inputs = ((0, 1),) if "input pair" not in message else ((1, 0),)
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)").replace("[", r"\[")):
        read_pyslvs(text, inputs)


# --- pylinkage ---------------------------------------------------------------------------------------------------

#: Only the tests that run pylinkage itself need it (a peer of the benchmark, not a dependency): they skip, saying
#: so, where it is missing; the readers and the legacy files below need nothing.
PYLINKAGE = "pylinkage is a peer of the benchmark, not a dependency: pip install -e '.[bench]'"


def _pylinkage_examples():
    MechanismBuilder = pytest.importorskip("pylinkage.mechanism", reason=PYLINKAGE).MechanismBuilder
    four = (MechanismBuilder("Four-Bar Linkage").add_ground_link("ground", ports={"O1": (0, 0), "O2": (100, 0)})
            .add_driver_link("crank", length=25, motor_port="O1", omega=0.1, initial_angle=math.pi / 4)
            .add_link("coupler", length=70).add_link("rocker", length=60)
            .connect("crank.tip", "coupler.0").connect("coupler.1", "rocker.0").connect("rocker.1", "ground.O2")
            .build())
    slider = (MechanismBuilder("Crank-Slider Mechanism").add_ground_link("ground", ports={"O": (0, 0)})
              .add_driver_link("crank", length=50, motor_port="O", omega=0.1, initial_angle=math.atan2(40, 30))
              .add_link("connecting_rod", length=100).add_slide_axis("rail", through=(0, 0), direction=(1, 0))
              .connect("crank.tip", "connecting_rod.0").connect_prismatic("connecting_rod.1", "rail").build())
    chebyshev = (MechanismBuilder("Chebyshev Linkage").add_ground_link("ground", ports={"O1": (0, 0), "O2": (100, 0)})
                 .add_arc_driver_link("crank", length=125, motor_port="O1", omega=0.05, arc_start=math.acos(0.8),
                                      arc_end=math.acos(-0.2), initial_angle=(math.acos(0.8) + math.acos(-0.2)) / 2)
                 .add_link("coupler", length=50).add_link("rocker", length=125)
                 .connect("crank.tip", "coupler.0").connect("coupler.1", "rocker.0").connect("rocker.1", "ground.O2")
                 .add_point_tracker("coupler_midpoint", "coupler.0", "coupler.1").build())
    return {"four-bar": (four, 0.1), "crank-slider": (slider, 0.1), "chebyshev": (chebyshev, 0.05)}


@pytest.mark.parametrize("name", ["four-bar", "crank-slider", "chebyshev"])
def test_pylinkage_s_examples_read_here_move_as_pylinkage_moves_them(name):
    mechanism_to_dict = pytest.importorskip("pylinkage.mechanism.serialization", reason=PYLINKAGE).mechanism_to_dict
    mechanism, step = _pylinkage_examples()[name]
    data = json.loads(json.dumps(mechanism_to_dict(mechanism)))  # through JSON text, as a file would be
    description = read_pylinkage(json.dumps(data))
    drawn = description.build()
    ids = [j.id for j in mechanism.joints]
    steps = 6
    expected = list(mechanism.step(iterations=steps))
    sweep = drawn.pose[drawn.linkage.inputs[0].name] + step * np.arange(1, steps + 1)
    got, assembled = joint_positions(drawn, [sweep])
    assert bool(np.all(assembled))
    for k in range(steps):
        for index, joint_id in enumerate(ids):
            x, y = expected[k][index]
            joint = description.names[joint_id]
            assert abs(got[joint][0][k] - x) < 1e-9 * 100 and abs(got[joint][1][k] - y) < 1e-9 * 100, (k, joint_id)


def test_symlink_s_linkages_written_for_pylinkage_move_there_as_here():
    mechanism_from_dict = pytest.importorskip("pylinkage.mechanism.serialization",
                                              reason=PYLINKAGE).mechanism_from_dict
    # An offset slider-crank with a coupler point, and a Watt II six-bar with its ternary ground.
    slider = from_joints({"ground": ["A", "C"], "crank": ["A", "B"], "rod": ["B", "C", "P"]},
                         {"A": (0.0, 0.0), "B": (10.0, 20.0), "C": (70.0, 5.0), "P": (40.0, 30.0)}, driver="A",
                         joints={"C": Slider("ground", 0.0)})
    watt = from_joints({"ground": ["A", "D", "G"], "crank": ["A", "B"], "coupler": ["B", "C"],
                        "rocker": ["D", "C", "E"], "coupler2": ["E", "F"], "output": ["G", "F"]},
                       {"A": (0, 0), "B": (5, 9), "C": (35, 30), "D": (32, 0), "E": (20, 20), "F": (45, 45),
                        "G": (45, 35)}, driver="A")
    for drawn in (slider, watt):
        data = json.loads(json.dumps(write_pylinkage(drawn)))
        mechanism = mechanism_from_dict(data)
        for link in mechanism.links:
            if getattr(link, "angular_velocity", None) is not None:
                link.angular_velocity = 0.05
        ids = [j.id for j in mechanism.joints]
        expected = list(mechanism.step(iterations=5))
        sweep = drawn.pose[drawn.linkage.inputs[0].name] + 0.05 * np.arange(1, 6)
        got, _ = joint_positions(drawn, [sweep])
        for k in range(5):
            for index, joint in enumerate(ids):
                x, y = expected[k][index]
                assert abs(got[joint][0][k] - x) < 1e-8 and abs(got[joint][1][k] - y) < 1e-8, (drawn.linkage, k, joint)


@pytest.mark.parametrize("data, message", [
    ({"joints": []}, "no 'links'"),
    ({"joints": [{"id": "A", "position": [0, 0]}], "links": [{"id": "g", "type": "ground", "joints": ["B"]}]},
     r"links\[0\] \(g\): no joint 'B'"),
    ({"joints": [{"id": "A", "type": "hinge", "position": [0, 0]}, {"id": "B", "position": [1, 0]}],
      "links": [{"id": "c", "type": "driver", "joints": ["A", "B"], "motor_joint": "A"}]}, "type 'hinge' is not"),
    ({"joints": [{"id": "A", "type": "ground", "position": [0, "1"]}, {"id": "B", "position": [1, 0]}],
      "links": [{"id": "c", "type": "driver", "joints": ["A", "B"], "motor_joint": "A"}]}, "expected two numbers"),
    ({"joints": [{"id": "A", "type": "ground", "position": [0, 0]}, {"id": "B", "position": [1, 0]}],
      "links": [{"id": "c", "type": "link", "joints": ["A", "B"]}]}, "no driver link"),
    ({"joints": [{"id": "A", "type": "ground", "position": [0, 0]}, {"id": "A", "position": [1, 0]}],
      "links": []}, "'joints' and 'links' must be non-empty"),
    ({"joints": [{"id": "A", "type": "ground", "position": [0, 0]}, {"id": "A", "position": [1, 0]}],
      "links": [{"id": "c", "joints": ["A"]}]}, "the id 'A' is used twice"),
    ({"joints": [{"id": "A", "type": "ground", "position": [0, 0]},
                 {"id": "S", "type": "prismatic", "position": [3, 1], "axis": [1, 0], "line_point": [0, 0]}],
      "links": [{"id": "c", "type": "driver", "joints": ["A", "S"], "motor_joint": "A"}]}, "1 off its line"),
    ("{not json", "pylinkage JSON: not JSON: Expecting property name"),
])
def test_bad_pylinkage_mechanisms_are_refused_naming_the_entry(data, message):
    with pytest.raises(ValueError, match=message):
        read_pylinkage(data if isinstance(data, str) else json.dumps(data))


def test_a_slider_on_a_moving_guide_has_no_pylinkage_form():
    drawn = read_pyslvs(*PYSLVS_EXAMPLES["lifter (RP on the ground and on a lever)"]).build()
    with pytest.raises(ValueError, match="slides on 'lever', a moving link"):
        write_pylinkage(drawn)


@pytest.mark.parametrize("name", ["four-bar crank-rocker", "lifter (RP on the ground and on a lever)",
                                  "Jansen leg (eight-bar)"])
def test_a_description_written_as_a_symlink_linkage_file_solves_the_same(name):
    drawn = read_pyslvs(*PYSLVS_EXAMPLES[name]).build()
    start = drawn.linkage.inputs[0].name
    text = linkage_text(drawn.linkage, {**drawn.parameters, start: drawn.pose[start]})
    again = linkage_from_text(text, source=f"{name}.toml")
    points = [f"{p}_{axis}" for p in drawn.chain.joints for axis in "xy"]
    sweep = drawn.pose[start] + np.linspace(0, 2 * math.pi, 19)
    first = Solver(drawn.linkage, points)(**{**drawn.defaults, start: sweep})
    second = Solver(again.linkage, points)(**{**again.defaults, **drawn.branches, start: sweep})
    for p in points:
        assert np.allclose(np.asarray(first[p]), np.asarray(second[p]), rtol=0, atol=1e-12, equal_nan=True), p


@pytest.mark.parametrize("name", ["lifter (RP on the ground and on a lever)",
                                  "inverted slider-crank (P on a turning rocker)", "Scotch yoke (two P joints)",
                                  "block on an inclined guide (P on the ground)",
                                  "Jansen leg (eight-bar)"])
def test_a_description_written_as_a_linkage_file_by_joints_reads_back_the_same(name):
    drawn = read_pyslvs(*PYSLVS_EXAMPLES[name]).build()
    again = linkage_from_text(joint_file_text(drawn), source=f"{name}.toml")
    assert again.linkage.unknowns == drawn.linkage.unknowns
    assert [loop.name for loop in again.linkage.loops] == [loop.name for loop in drawn.linkage.loops]
    assert again.defaults == drawn.values


@pytest.mark.parametrize("name", sorted(PYSLVS_EXAMPLES))
def test_the_bodies_read_off_the_vectors_are_the_joints_links(name):
    """symlink.mechanism.bodies reads bodies and joints back off the derived vectors, by its own rules (walking order,
    directions, travels): its Gruebler count equals the joints' own, and the drawing of the linkage works."""
    from symlink.mechanism.mobility import degrees_of_freedom
    from symlink.plot.drawing import draw_linkage
    drawn = read_pyslvs(*PYSLVS_EXAMPLES[name]).build()
    assert degrees_of_freedom(drawn.linkage) == drawn.mobility
    guess = None if drawn.linkage.has_closed_form else drawn.guess
    drawing = draw_linkage(drawn.linkage, drawn.defaults, guess=guess)
    assert drawing.axes.get_title().startswith("pyslvs at")


# pylinkage's legacy JSON (Linkage.to_dict before 1.0), written here as its serializer wrote it: its README
# four-bar (``Crank`` B about (0, 0); ``Revolute`` C from B and the point (3, 0)), with a coupler point P
# (``Fixed`` on B-C) and, in a second file, a crank-slider (``Prismatic`` C along the line of two statics).
LEGACY_FOURBAR = {
    "name": "My four-bar linkage",
    "joints": [
        {"type": "Crank", "name": "B", "x": 0, "y": 1, "distance": 1, "angle": 0.31,
         "joint0": {"inline": True, "type": "Static", "x": 0, "y": 0, "name": "140093"}},
        {"type": "Revolute", "name": "C", "x": 3, "y": 2, "distance0": 3, "distance1": 1,
         "joint0": {"ref": "B"}, "joint1": {"inline": True, "type": "Static", "x": 3, "y": 0, "name": "140094"}},
        {"type": "Fixed", "name": "P", "x": 2, "y": 3, "distance": 2, "angle": 0.5,
         "joint0": {"ref": "B"}, "joint1": {"ref": "C"}},
    ],
    "solve_order": ["B", "C", "P"],
}
LEGACY_SLIDER = {
    "name": "crank slider",
    "joints": [
        {"type": "Static", "name": "O", "x": 0, "y": 0},
        {"type": "Static", "name": "L", "x": -5, "y": 0.5},
        {"type": "Static", "name": "R", "x": 5, "y": 0.5},
        {"type": "Crank", "name": "B", "x": 0.6, "y": 0.8, "distance": 1, "angle": 0.1, "joint0": {"ref": "O"}},
        {"type": "Prismatic", "name": "S", "x": 3.5, "y": 0.5, "revolute_radius": 3, "joint0": {"ref": "B"},
         "joint1": {"ref": "L"}, "joint2": {"ref": "R"}},
    ],
}


def test_pylinkage_s_legacy_four_bar_takes_its_distances_and_keeps_them_along_a_turn():
    description = read_pylinkage(json.dumps(LEGACY_FOURBAR))
    drawn = description.build()
    name = description.names
    b, c, p = name["B"], name["C"], name["P"]
    origin, pivot = description.coordinates[name["140093"]], description.coordinates[name["140094"]]
    assert (origin, pivot) == ((0.0, 0.0), (3.0, 0.0))
    # Placed as pylinkage places it: C where the circles (B, 3) and ((3, 0), 1) meet nearest its stored (3, 2).
    bx, by = description.coordinates[b]
    assert (bx, by) == pytest.approx((0.0, 1.0), abs=1e-15)
    d = math.dist((bx, by), pivot)
    along = (9 - 1 + d * d) / (2 * d)
    across = math.sqrt(9 - along * along)
    ux, uy = (pivot[0] - bx) / d, (pivot[1] - by) / d
    candidates = [(bx + along * ux - k * across * uy, by + along * uy + k * across * ux) for k in (1, -1)]
    expected_c = min(candidates, key=lambda q: math.dist(q, (3, 2)))
    assert description.coordinates[c] == pytest.approx(expected_c, abs=1e-14)
    angle = math.atan2(expected_c[1] - by, expected_c[0] - bx) + 0.5
    assert description.coordinates[p] == pytest.approx((bx + 2 * math.cos(angle), by + 2 * math.sin(angle)), abs=1e-14)
    assert drawn.parameters[f"{b}{c}" if len(b) == len(c) == 1 else f"{b}_{c}"] == pytest.approx(3, rel=1e-15)
    # Along a turn: the crank 1, B-C 3, C to (3, 0) 1, and P at 2 from B, 0.5 rad from B-C.
    sweep = drawn.pose[drawn.linkage.inputs[0].name] + np.linspace(0, 2 * math.pi, 25)
    got, assembled = joint_positions(drawn, [sweep])
    assert bool(np.all(assembled))
    assert np.allclose(np.hypot(*got[b]), 1, atol=1e-13)
    assert np.allclose(np.hypot(got[c][0] - got[b][0], got[c][1] - got[b][1]), 3, atol=1e-13)
    assert np.allclose(np.hypot(got[c][0] - 3, got[c][1]), 1, atol=1e-13)
    turned = np.arctan2(got[p][1] - got[b][1], got[p][0] - got[b][0]) - np.arctan2(got[c][1] - got[b][1],
                                                                                  got[c][0] - got[b][0])
    assert np.allclose(np.remainder(turned, 2 * np.pi), 0.5, atol=1e-12)


def test_pylinkage_s_legacy_prismatic_is_a_pin_sliding_along_its_line():
    description = read_pylinkage(LEGACY_SLIDER)
    drawn = description.build()
    assert [s.case.name for s in drawn.linkage.plan] == ["2b"]
    # S where the circle (B, 3) meets the line y = 0.5 nearest its stored (3.5, 0.5).
    bx, by = 0.6, 0.8
    assert description.coordinates["S"] == pytest.approx((bx + math.sqrt(9 - 0.3 ** 2), 0.5), abs=1e-14)
    sweep = drawn.pose[drawn.linkage.inputs[0].name] + np.linspace(0, 2 * math.pi, 25)
    got, assembled = joint_positions(drawn, [sweep])
    assert bool(np.all(assembled))
    assert np.allclose(got["S"][1], 0.5, atol=1e-13)
    assert np.allclose(np.hypot(got["S"][0] - got["B"][0], got["S"][1] - got["B"][1]), 3, atol=1e-13)


@pytest.mark.parametrize("change, message", [
    (lambda d: d["joints"][1].update(joint0={"ref": "Q"}), "its parent 'Q' is not a joint"),
    (lambda d: d["joints"][1].update(distance0=10), "cannot be placed: its constraints do not meet"),
    (lambda d: d["joints"][1].update(distance1="1"), "distance1 must be a finite number"),
    (lambda d: d.update(joints=[{"type": "Static", "name": "O", "x": 0, "y": 0}]), "no Crank joint"),
    (lambda d: d["joints"].pop(0), "its parent 'B' is not a joint"),
    (lambda d: d["joints"].append({"type": "Crank", "name": "K", "x": 4, "y": 0, "distance": 1, "angle": 0.1,
                                   "joint0": {"ref": "C"}}), "crank 'K' turns about 'C', which is not a Static"),
    (lambda d: d["joints"][0].update(joint0={"ref": "C"}), "their parents form a loop"),
])
def test_bad_legacy_pylinkage_files_are_refused(change, message):
    data = json.loads(json.dumps(LEGACY_FOURBAR))
    change(data)
    with pytest.raises(ValueError, match=message):
        read_pylinkage(data)


def test_a_pyslvs_ui_project_gives_its_expression_and_input_pairs():
    yaml = pytest.importorskip("yaml")
    expression, inputs = PYSLVS_EXAMPLES["Watt II six-bar"]
    text = yaml.safe_dump({"pyslvs_ver": "21.12.0", "file_type": 0, "mechanism": expression,
                           "links": {"ground": "White", "L1": "Blue"}, "input": [list(p) for p in inputs],
                           "storage": {}, "collection": [], "path": {}})
    description = read_pyslvs_project(text)
    assert description.drivers == read_pyslvs(expression, inputs).drivers
    assert description.build().linkage.has_closed_form
    with pytest.raises(ValueError, match="'input' must list the input pairs"):
        read_pyslvs_project({"mechanism": expression})
    with pytest.raises(ValueError, match="an input pair is"):
        read_pyslvs_project({"mechanism": expression, "input": [[0, "1"]]})
    with pytest.raises(ValueError, match="not YAML"):
        read_pyslvs_project("mechanism: [unclosed")


# --- readers as strict as the linkage file: one ValueError, short, for any bad input ------------------------------

_MECHANISM = ('{"joints": [{"id": "A", "type": "ground", "position": [0, 0]}, '
              '{"id": "D", "type": "ground", "position": [3, 0]}, '
              '{"id": "B", "type": "revolute", "position": [0, 1]}, {"id": "C", "type": "revolute", "position": [3, 2]}], '
              '"links": [{"id": "ground", "type": "ground", "joints": ["A", "D"]}, '
              '{"id": "crank", "type": "driver", "joints": ["A", "B"], "motor_joint": "A"}, '
              '{"id": "coupler", "type": "link", "joints": ["B", "C"]}, {"id": "rocker", "type": "link", "joints": ["D", "C"]}]}')


@pytest.mark.parametrize("text, words", [
    ("[" * 100_000 + "]" * 100_000, "nested too deeply"),
    ('{"a":' * 50_000 + "1" + "}" * 50_000, "nested too deeply"),
    (_MECHANISM.replace('"position": [0, 1]', '"position": [0, 1' + "0" * 5000 + "]"), "out of range"),
    (_MECHANISM.replace('"position": [0, 1]', '"position": [0, 1e400]'), "out of range"),
    (_MECHANISM.replace('"position": [0, 1]', '"position": [0, NaN]'), "NaN is not a number"),
    (_MECHANISM.replace('"position": [0, 1]', '"position": [0, -Infinity]'), "-Infinity is not a number"),
    (" " * (5 << 20) + _MECHANISM, "more than a mechanism needs"),
], ids=["deep list", "deep object", "5000 digits", "1e400", "NaN", "-Infinity", "too large"])
def test_pylinkage_bad_input_is_one_short_value_error(text, words):
    with pytest.raises(ValueError, match=words) as refused:
        read_pylinkage(text)
    assert len(str(refused.value)) < 300 and "\n" not in str(refused.value)


def test_the_strict_pylinkage_reader_still_reads_the_mechanism():
    assert read_pylinkage(_MECHANISM).build().linkage.unknowns  # the four-bar closes


@pytest.mark.parametrize("text, words", [
    ("M[J[R, color[Green], P[1" + "0" * 5000 + ", 0], L[ground, L1]]]", "out of range"),
    ("M[J[R, color[Green], P[1e400, 0], L[ground, L1]]]", "out of range"),
    ("M[J[R, color[Green], P[0, 0], L[" + "9" * 10_000 + "]]]", "expected a link name"),
    ("M[" + " " * (5 << 20) + "]", "more than a mechanism needs"),
], ids=["5000 digits", "1e400", "a long word", "too large"])
def test_pyslvs_bad_input_is_one_short_value_error(text, words):
    with pytest.raises(ValueError, match=words) as refused:
        read_pyslvs(text)
    assert len(str(refused.value)) < 300 and "\n" not in str(refused.value)
