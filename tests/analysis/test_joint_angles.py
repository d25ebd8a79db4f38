"""The interior angle at a joint from solved coordinates and the joint's recipe (symlink.analysis.joint_angles),
NumPy only, against hand formulas: the four-bar's transmission angle by the law of cosines over the diagonal BD, a
slider-crank's rod against the normal of its guide, and directions turned by fixed angles and negative lengths."""
from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy
import pytest

from symlink.analysis.joint_angles import direction_parts, joint_angle_arrays, joint_coordinates
from references import fourbar_joint_c

ROOT = Path(__file__).resolve().parent.parent.parent


def side(sign: int, coordinate: str | None, offset=((0.0, None),), length=None) -> dict:
    """A side of a joint's recipe, written out (symlink.analysis.transmission.direction_recipe's form)."""
    return {"sign": sign, "coordinate": coordinate, "offset": [list(t) for t in offset],
            "length": None if length is None else [list(t) for t in length]}


def joint(loop: str, into: dict, out: dict, guide: bool = False) -> dict:
    return {"loop": loop, "name": loop, "guide": guide, "into": into, "out": out}


def fourbar_angles(theta: float, a: float, b: float, c: float, d: float) -> tuple[float, float]:
    """Coupler and rocker angles on branch +1, by hand (C from the circles about B and D)."""
    cx, cy = fourbar_joint_c(theta, a, b, c, d)
    return math.atan2(cy - a * math.sin(theta), cx - a * math.cos(theta)), math.atan2(cy, cx - d)


@pytest.mark.parametrize("theta", [0.0, 0.7, 2.0, -2.5])
def test_the_fourbar_joint_angle_is_the_law_of_cosines(theta):
    a, b, c, d = 20.0, 66.0, 56.0, 80.0
    beta, phi = fourbar_angles(theta, a, b, c, d)
    joints = [joint("ABCD", side(1, "phi"), side(-1, "beta"))]  # into C along DC, out of C back along BC
    found = joint_angle_arrays(joints, {}, {"beta": numpy.array([beta]), "phi": numpy.array([phi])})
    diagonal = a * a + d * d - 2 * a * d * math.cos(theta)  # |BD|^2
    assert float(found["ABCD"][0]) == pytest.approx(math.acos((b * b + c * c - diagonal) / (2 * b * c)), abs=1e-12)


def test_a_guides_angle_is_the_rods_to_its_normal():
    """A rod at beta against a guide along +x: the angle from the guide's normal (+y) to the rod, in [0, pi]."""
    beta = numpy.array([0.0, 0.3, -0.4, math.pi - 0.2])
    joints = [joint("ABC", side(1, None), side(1, "beta", length=[(1.0, "b")]), guide=True)]
    found = joint_angle_arrays(joints, {"b": 2.0}, {"beta": beta})["ABC"]
    assert found.tolist() == pytest.approx([math.pi / 2, math.pi / 2 - 0.3, math.pi / 2 + 0.4, math.pi / 2 - 0.2],
                                           abs=1e-12)
    assert joint_coordinates(joints) == ["beta"]


def test_a_constant_part_may_be_a_function_of_the_values():
    """A joint whose side into it is turned by a fixed angle alpha (a value a design): -into points at
    phi + alpha + pi, out of it at beta + pi, so the angle between them is phi + alpha - beta (here 1 + alpha)."""
    joints = [joint("L", side(1, "phi", offset=[(1.0, "alpha")]), side(-1, "beta"))]
    alpha = numpy.array([[0.0], [0.25]])
    found = joint_angle_arrays(joints, {"alpha": alpha}, {"beta": numpy.array([[0.0]]), "phi": numpy.array([[1.0]])})
    assert found["L"].ravel().tolist() == pytest.approx([1.0, 1.25], abs=1e-12)


def test_a_negative_length_turns_its_side_half_a_turn_a_design_at_a_time():
    """The side out of the joint has length e, a value a design: where e < 0 the vector points the other way, so
    the angle at the joint is pi less what it is for e > 0 (the four-bar's at C: 1 rad between phi and beta)."""
    joints = [joint("L", side(1, "phi"), side(-1, "beta", length=[(1.0, "e")]))]
    e = numpy.array([[2.0], [-2.0]])
    found = joint_angle_arrays(joints, {"e": e}, {"beta": numpy.array([[0.0]]), "phi": numpy.array([[1.0]])})
    assert found["L"].ravel().tolist() == pytest.approx([1.0, math.pi - 1.0], abs=1e-12)
    offset, flip = direction_parts(side(-1, "beta", offset=[(0.5, None), (2.0, "gamma")], length=[(1.0, "e")]),
                                   {"gamma": 0.25, "e": -1.0})
    assert (offset, flip) == (0.5 + 2.0 * 0.25, 2 * math.pi)  # walked back and negative: a whole turn


def test_it_imports_no_sympy():
    done = subprocess.run([sys.executable, "-c", "import sys, symlink.analysis.joint_angles, symlink.analysis.grashof;"
                           " print('sympy' in sys.modules)"], capture_output=True, text=True, check=True,
                          env={"PYTHONPATH": str(ROOT), "PATH": ""})
    assert done.stdout.strip() == "False"
