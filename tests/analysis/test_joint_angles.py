"""The interior angle at a joint from solved coordinates (symlink.analysis.joint_angles), NumPy only, against hand
formulas: the four-bar's transmission angle by the law of cosines over the diagonal BD, and a slider-crank's rod
against the normal of its guide."""
from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy
import pytest

from symlink.analysis.joint_angles import joint_angle_arrays, joint_coordinates
from references import fourbar_joint_c

ROOT = Path(__file__).resolve().parent.parent.parent


def fourbar_angles(theta: float, a: float, b: float, c: float, d: float) -> tuple[float, float]:
    """Coupler and rocker angles on branch +1, by hand (C from the circles about B and D)."""
    cx, cy = fourbar_joint_c(theta, a, b, c, d)
    return math.atan2(cy - a * math.sin(theta), cx - a * math.cos(theta)), math.atan2(cy, cx - d)


@pytest.mark.parametrize("theta", [0.0, 0.7, 2.0, -2.5])
def test_the_fourbar_joint_angle_is_the_law_of_cosines(theta):
    a, b, c, d = 20.0, 66.0, 56.0, 80.0
    beta, phi = fourbar_angles(theta, a, b, c, d)
    joints = (("ABCD", False, ("phi", 0.0), ("beta", math.pi)),)  # into C along DC, out of C back along BC
    found = joint_angle_arrays(joints, {}, {"beta": numpy.array([beta]), "phi": numpy.array([phi])})
    diagonal = a * a + d * d - 2 * a * d * math.cos(theta)  # |BD|^2
    assert float(found["ABCD"][0]) == pytest.approx(math.acos((b * b + c * c - diagonal) / (2 * b * c)), abs=1e-12)


def test_a_guides_angle_is_the_rods_to_its_normal():
    """A rod at beta against a guide along +x: the angle from the guide's normal (+y) to the rod, in [0, pi]."""
    beta = numpy.array([0.0, 0.3, -0.4, math.pi - 0.2])
    joints = (("ABC", True, (None, 0.0), ("beta", 0.0)),)
    found = joint_angle_arrays(joints, {}, {"beta": beta})["ABC"]
    assert found.tolist() == pytest.approx([math.pi / 2, math.pi / 2 - 0.3, math.pi / 2 + 0.4, math.pi / 2 - 0.2],
                                           abs=1e-12)
    assert joint_coordinates(joints) == ["beta"]


def test_a_constant_part_may_be_a_function_of_the_values():
    """A joint whose side into it is turned by a fixed angle alpha (a value a design): -into points at
    phi + alpha + pi, out of it at beta + pi, so the angle between them is phi + alpha - beta (here 1 + alpha)."""
    joints = (("L", False, ("phi", lambda values: values["alpha"]), ("beta", math.pi)),)
    alpha = numpy.array([[0.0], [0.25]])
    found = joint_angle_arrays(joints, {"alpha": alpha}, {"beta": numpy.array([[0.0]]), "phi": numpy.array([[1.0]])})
    assert found["L"].ravel().tolist() == pytest.approx([1.0, 1.25], abs=1e-12)


def test_it_imports_no_sympy():
    done = subprocess.run([sys.executable, "-c", "import sys, symlink.analysis.joint_angles, symlink.analysis.grashof;"
                           " print('sympy' in sys.modules)"], capture_output=True, text=True, check=True,
                          env={"PYTHONPATH": str(ROOT), "PATH": ""})
    assert done.stdout.strip() == "False"
