"""Joints as drawn (issue 32, item 3): the textbook slider-crank's block, and refusals that name the real cause.

A slider block whose pin lies on its slide (pin C to the rod and the block's prismatic joint S drawn at one
point) is the common drawing of a slider-crank: accepted, and its poses are the catalog ``slider_crank``'s
(solved by its own generated solver, an independent formulation written by loops).
"""
from __future__ import annotations

import math

import numpy
import pytest

from symlink.io.linkage_file import linkage_from_text
from symlink.mechanism.catalog import slider_crank
from symlink.mechanism.joints import Slider, from_joints
from symlink.numeric.solver import Solver

A_, B_, OFFSET = 1.0, 3.0, 0.4
THETA0 = 1.0


def drawing(offset: float = OFFSET, angle: float = 0.0):
    """Joints of the slider-crank at crank angle THETA0: the block's pin C and slide S at one point."""
    B = (A_ * math.cos(THETA0), A_ * math.sin(THETA0))
    x = B[0] + math.sqrt(B_ ** 2 - (offset - B[1]) ** 2)
    return {"A": (0.0, 0.0), "B": B, "C": (x, offset), "S": (x, offset), "G": (-2.0, offset)}


LINKS = {"ground": ["A", "G", "S"], "crank": ["A", "B"], "rod": ["B", "C"], "block": ["C", "S"]}


@pytest.mark.parametrize("block", [["C", "S"], ["S", "C"]])
def test_the_textbook_slider_crank_by_its_joints_moves_as_the_catalog_one(block):
    drawn = from_joints({**LINKS, "block": block}, drawing(), driver="A",
                        joints={"S": Slider("ground", 0.0, turns=False)})
    assert drawn.mobility.dof == 1
    theta = numpy.radians(numpy.arange(0.0, 360.0, 15.0))
    mine = Solver(drawn.linkage, ["C_x", "C_y", "theta_BC"])(theta_AB=theta, **drawn.parameters, **drawn.branches)
    catalog = Solver(slider_crank(), ["C_x", "C_y", "beta"])(theta=theta, a=A_, b=B_, offset=OFFSET, branch=1)
    assert numpy.all(mine["assembled"]) and numpy.all(catalog["assembled"])
    numpy.testing.assert_allclose(mine["C_x"], catalog["C_x"], rtol=0, atol=1e-12)
    numpy.testing.assert_allclose(mine["C_y"], catalog["C_y"], rtol=0, atol=1e-12)
    numpy.testing.assert_allclose(numpy.cos(mine["theta_BC"] - catalog["beta"]), 1.0, rtol=0, atol=1e-12)
    # the drawn pose is the default's
    assert drawn.pose["theta_AB"] == pytest.approx(THETA0)


def test_the_block_in_a_linkage_file_and_driven_by_its_slide():
    C = drawing()["C"]
    text = f"""
name = "textbook"
driver = "S"
[links]
ground = ["A", "G", "S"]
crank = ["A", "B"]
rod = ["B", "C"]
block = ["C", "S"]
[joints]
A = [0, 0]
B = [{math.cos(THETA0)!r}, {math.sin(THETA0)!r}]
C = [{C[0]!r}, {C[1]!r}]
S = {{at = [{C[0]!r}, {C[1]!r}], block = "ground", angle = 0}}
G = [-2, {OFFSET!r}]
"""
    found = linkage_from_text(text)
    linkage = found.linkage
    assert [q.name for q in linkage.inputs] == ["s_C"]  # the slide drives the pin's travel
    assert linkage.has_closed_form
    solved = Solver(linkage, ["B_x", "B_y"])(**found.defaults)  # every branch +1: the drawing
    assert float(solved["B_x"]) == pytest.approx(math.cos(THETA0), abs=1e-9)
    assert float(solved["B_y"]) == pytest.approx(math.sin(THETA0), abs=1e-9)


FOURBAR = {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]}
POSE = {"A": (0, 0), "B": (0, 1), "C": (3, 2), "D": (3, 0)}


@pytest.mark.parametrize("links, coordinates, arguments, message", [
    (FOURBAR, POSE, {"driver": [("A", "crnk")]}, "driver ('A', 'crnk'): no link 'crnk'"),
    (FOURBAR, POSE, {"driver": "Q"}, "driver 'Q' is not a joint of the linkage"),
    (FOURBAR, POSE, {"driver": "A", "joints": {"C": Slider("grund", 0.0)}}, "slider 'C': no link 'grund'"),
    (FOURBAR, POSE, {"driver": "A", "joints": {"C": Slider("grund", 0.0, turns=False)}},
     "slider 'C': no link 'grund'"),
    (FOURBAR, POSE, {"driver": "A", "ground": "base"}, "no ground link 'base'"),
    (FOURBAR, {**POSE, "D": (1e300, 0)}, {"driver": "A"}, "D.x = 1e+300 is out of range"),
    (FOURBAR, {**POSE, "B": (0, 1e-200)}, {"driver": "A"}, "B.y = 1e-200 is out of range"),
    (FOURBAR, {**POSE, "D": (1e60, 0)}, {"driver": "A"}, "'A' and 'B' are 1 apart in a drawing 1e+60 across"),
    (FOURBAR, {**POSE, "B": (0, 0)}, {"driver": "A"}, "'A' and 'B' are drawn at the same point"),
    ({**FOURBAR, "rocker": ["D", "X"]}, POSE, {"driver": "A"}, "no position for joint X"),
])
def test_each_refusal_names_its_cause(links, coordinates, arguments, message):
    with pytest.raises(ValueError) as caught:
        from_joints(links, coordinates, **arguments)
    assert message in str(caught.value)
    assert "neither assembly" not in str(caught.value)
