"""Singular poses are reported: ``singular`` comes with every rate, force and sensitivity, beside ``assembled``.

The toggle is placed by hand: the four-bar a = 3, b = 2, c = 3, d = 4 at crank angle 90 deg has
|BD|^2 = a^2 + d^2 = 25 = (b + c)^2, so coupler and rocker lie on one line (the loop's determinant
sin(beta - phi) is zero) and the crank can go no farther (|BD| grows with the angle beyond it).  At
30 deg, |BD|^2 = 25 - 24 cos(30 deg) is well inside (|b - c| < |BD| < b + c): no toggle.
"""
from __future__ import annotations

import csv
import io
import math

import numpy as np
import pytest

from symlink.mechanism.catalog import fourbar, watt2
from symlink.cli import main
from symlink.numeric.design_jacobian import DesignJacobian
from symlink.dynamics import BodyTorque, DynamicModel, Gravity, MassProperties, dynamic_linkage
from symlink.symbolic.position import ClampedSqrt
from symlink.numeric.solver import Solver

TOGGLE = dict(a=3.0, b=2.0, c=3.0, d=4.0)
THETA = np.array([math.pi / 2, math.radians(30)])


def test_the_hand_toggle_is_one():
    a, b, c, d = (TOGGLE[k] for k in "abcd")
    assert a * a + d * d == (b + c) ** 2
    inside = a * a + d * d - 2 * a * d * math.cos(THETA[1])
    assert (b - c) ** 2 < inside < (b + c) ** 2


def test_rates_come_with_the_flag_and_positions_without_it():
    result = Solver(fourbar(), ["rocker", "rocker_speed"])(theta=THETA, **TOGGLE, branch=1, thetadot=1.0)
    assert result["assembled"].tolist() == [True, True]
    assert result["singular"].tolist() == [True, False]
    assert not math.isfinite(result["rocker_speed"][0]) and math.isfinite(result["rocker_speed"][1])
    # At the toggle C lies between B = (0, 3) and D = (4, 0): the rocker DC points from D back to B.
    assert result["rocker"][0] == pytest.approx(math.atan2(3.0, -4.0), abs=1e-12)
    assert "singular" not in Solver(fourbar(), ["rocker", "C_x"])(theta=THETA, **TOGGLE, branch=1)


def test_sensitivities_come_with_the_flag():
    result = Solver(fourbar(), ["rocker__d_a"])(theta=THETA, **TOGGLE, branch=1)
    assert result["singular"].tolist() == [True, False] and result["assembled"].all()
    assert not math.isfinite(result["rocker__d_a"][0]) and math.isfinite(result["rocker__d_a"][1])
    jacobian = DesignJacobian(fourbar(), ["rocker", "C_y"], ["a", "d"])
    values, slopes = jacobian(theta=THETA, **TOGGLE, branch=1)
    assert values["singular"].tolist() == [True, False] and values["assembled"].tolist() == [True, True]
    assert slopes.shape == (2, 2, 2)
    # The hot loop leaves the flag out: values of both outputs, a derivative by each parameter.
    with np.errstate(divide="ignore", invalid="ignore"):  # the unchecked call: the toggle divides by zero
        found, derivatives, assembled = jacobian.arrays(THETA, *TOGGLE.values(), 1.0)
    assert found.shape == (2, 2) and derivatives.shape == (2, 2, 2) and assembled.tolist() == [True, True]
    np.testing.assert_array_equal(derivatives[:, :, 1], slopes[1])
    np.testing.assert_array_equal(found[:, 1], [values["rocker"][1], values["C_y"][1]])


def test_a_sensitivity_by_a_parameter_outside_the_loops_has_no_flag():
    # A point placed by a parameter that closes no loop moves without solving anything: nothing divides.
    linkage = fourbar()
    assert linkage.divides_by_determinant("rocker__d_a")
    assert not any(linkage.divides_by_determinant(name) for name in ("rocker", "C_x", "thetadot", "singular"))


@pytest.mark.parametrize("masses, loads, requests", [
    ([MassProperties("coupler", 2.0, 1.0, 0.1, 0.3), MassProperties("rocker", 1.5, 1.5, 0.0, 0.4)], [],
     (["input_torque"], ["joint_C_x", "shaking_moment"], ["generalised_inertia"])),
    # Statics: the reactions divide by the Newton-Euler determinant alone (no mass: M = 0 divides by nothing).
    ([], [BodyTorque("rocker", 5.0)], (["input_torque"], ["joint_C_x", "shaking_moment"])),
])
def test_dynamic_outputs_come_with_the_flag(masses, loads, requests):
    linkage = dynamic_linkage(DynamicModel(fourbar(), masses, loads, Gravity(0, -9.81)))
    for outputs in requests:
        solver = Solver(linkage, outputs)
        rates = {"thetadot": 1.0} if "thetadot" in solver.arguments else {}  # M(q) takes positions only
        result = solver(theta=THETA, **TOGGLE, branch=1, **rates)
        assert result["singular"].tolist() == [True, False], outputs
        assert result["assembled"].tolist() == [True, True]
        assert all(math.isfinite(result[name][1]) for name in outputs)


def roots_in(expr) -> set[str]:
    return {s.name for s in expr.free_symbols}


def test_the_flag_looks_at_the_loops_the_outputs_depend_on():
    linkage = watt2()
    # the roots generated code guards (loop units: the root of each loop and the length that sets its direction)
    first, second = ({s.name for s, e in step.in_loop_units.intermediates.items() if isinstance(e, ClampedSqrt)}
                     for step in linkage.plan)
    both = roots_in(linkage.program(["singular"]).outputs["singular"])
    assert first <= both and second <= both
    # The first loop's rates do not divide by the second loop's determinant: its toggle is not theirs.
    assert roots_in(linkage.program(["coupler_speed", "singular"]).outputs["singular"]) <= first
    assert second & roots_in(linkage.program(["output_speed", "singular"]).outputs["singular"])
    assert linkage.with_singular(["coupler_speed"]) == ["coupler_speed", "singular"]


def test_the_table_names_a_singular_row_of_forces(capsys):
    argv = ["fourbar", "--crank", "3", "--coupler", "2", "--rocker", "3", "--ground", "4", "--masses", "1,2,1.5",
            "--angles", "90,30", "--crank-speed", "1", "--branch", "+1", "--format", "csv"]
    status = main(argv)
    out, err = capsys.readouterr()
    assert status == 0, err
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [float(row["crank"]) for row in rows] == [90.0, 30.0]
    assert math.isfinite(float(rows[1]["input_torque"]))
    assert "singular (toggle) position at crank angles 90 deg" in err
    assert "forces" in err
