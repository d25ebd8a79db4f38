"""A placed design written into its linkage (symlink.synthesis.placement): points, angles and the file read back,
checked against the Watt II placed by hand (circle intersections of ``hand_linkages``, a similarity written out)."""
from __future__ import annotations

import cmath
import math

import pytest

from hand_linkages import watt2_joints, wrapped
from symlink.mechanism.catalog import EXAMPLE_VALUES, slider_crank, watt2
from symlink.io.linkage_file import linkage_from_text, linkage_text
from symlink.numeric.solver import Solver
from symlink.synthesis.placement import length_parameters, placed_design

WATT = EXAMPLE_VALUES["watt2"]
WHERE = {"x0": 0.3, "y0": -1.1, "angle": 0.7, "scale": 1.6}


def by_hand(theta: float):
    joints = watt2_joints(WATT, theta)
    turn = WHERE["scale"] * cmath.exp(1j * WHERE["angle"])
    return {name: complex(WHERE["x0"], WHERE["y0"]) + turn * joints[name] for name in ("B", "C", "E", "F", "G")}, {
        name: joints[name] + WHERE["angle"] for name in ("mu", "psi")}


@pytest.mark.parametrize("through_file", [False, True])
def test_placed_watt_two_matches_the_hand_placement(through_file):
    linkage, values = placed_design(watt2(), WATT, WHERE)
    if through_file:
        found = linkage_from_text(linkage_text(linkage, values))
        linkage, values = found.linkage, found.defaults
    names = ["B_x", "B_y", "C_x", "C_y", "E_x", "E_y", "F_x", "F_y", "G_x", "G_y", "mu", "psi"]
    for theta in (0.2, 1.4, 3.0, 5.1):
        solved = Solver(linkage, names)(theta=theta, **values, branch_ABCD=1, branch_DEFG=1)
        points, angles = by_hand(theta)
        for name, z in points.items():
            assert abs(complex(float(solved[f"{name}_x"]), float(solved[f"{name}_y"])) - z) < 1e-12
        for name, angle in angles.items():
            assert abs(wrapped(float(solved[name]) - angle)) < 1e-12


def test_identity_placement_changes_nothing():
    linkage, values = placed_design(slider_crank(), {"a": 1.0, "b": 3.0, "offset": 0.2}, {})
    assert linkage.points.keys() == slider_crank().points.keys() and values == {"a": 1.0, "b": 3.0, "offset": 0.2}


def test_length_parameters_scale_together():
    assert length_parameters(watt2()) == {"a", "b", "c", "d", "e", "f", "g", "gx", "gy"}
    assert math.isclose(placed_design(slider_crank(), {"a": 1.0, "b": 3.0, "offset": 0.2},
                                      {"scale": 2.0})[1]["offset"], 0.4)


@pytest.mark.parametrize("placement, message", [({"scale": -1.0}, "positive scale"), ({"x0": math.inf}, "finite")])
def test_bad_placement_is_a_value_error(placement, message):
    with pytest.raises(ValueError, match=message):
        placed_design(watt2(), WATT, placement)
