"""The dynamics on the command line: the four-bar's torque and reaction columns, ``symlink flywheel``, bad input.

Expected values are hand statics and the closed forms of a crank under gravity (see
tests/dynamics/test_flywheel.py for the derivation), not the library's own output.
"""
from __future__ import annotations

import csv
import io
import math

import pytest

from symlink.cli import main
from symlink.cli.dynamics import FLYWHEEL_COLUMNS, MASS_COLUMNS

FOURBAR = ["fourbar", "--crank", "0.2", "--coupler", "0.66", "--rocker", "0.56", "--ground", "0.8"]
FLYWHEEL = ["flywheel", "--crank", "0.2", "--coupler", "0.66", "--rocker", "0.56", "--ground", "0.8"]
CRANK_ONLY = ["--masses", "1,0,0", "--inertias", "0.03,0,0", "--centres", "0.1:0,0.33:0,0.28:0", "--gravity", "9.81"]


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def rows(text: str) -> list[dict[str, float]]:
    return [{k: (v if k == "branch" else float(v)) for k, v in row.items()} for row in csv.DictReader(io.StringIO(text))]


def test_fourbar_statics_of_a_crank_under_gravity(capsys):
    # At rest, only the crank massive (1 kg at 0.1 m from A): the motor holds m g r cos(theta) and the pin A
    # carries the weight; the massless coupler and rocker carry nothing.
    status, out, err = run(capsys, *FOURBAR, *CRANK_ONLY, "--angles", "60,120", "--branch", "+1", "--format", "csv")
    assert status == 0, err
    header = out.splitlines()[0].split(",")
    assert header[-len(MASS_COLUMNS):] == MASS_COLUMNS
    for row in rows(out):
        theta = math.radians(row["crank"])
        assert row["input_torque"] == pytest.approx(9.81 * 0.1 * math.cos(theta), rel=1e-12)
        assert row["joint_A_x"] == pytest.approx(0.0, abs=1e-12)
        assert row["joint_A_y"] == pytest.approx(9.81, rel=1e-12)
        for column in ("joint_B_x", "joint_B_y", "joint_C_x", "joint_C_y", "joint_D_x", "joint_D_y"):
            assert row[column] == pytest.approx(0.0, abs=1e-12)
        assert row["shaking_force_y"] == pytest.approx(-9.81, rel=1e-12)  # the crank hangs on the frame
        assert row["shaking_force_x"] == pytest.approx(0.0, abs=1e-12)


def test_fourbar_reactions_are_finite_where_a_lever_arm_vanishes(capsys):
    # At crank angles 0 and 180 the crank's arm to B has no y component; an elimination that pivoted on it
    # returned NaN there.  The statics are those of the test above.
    status, out, err = run(capsys, *FOURBAR, *CRANK_ONLY, "--angles", "0,180", "--branch", "+1", "--format", "csv")
    assert status == 0, err
    for row in rows(out):
        assert row["input_torque"] == pytest.approx(9.81 * 0.1 * math.cos(math.radians(row["crank"])), rel=1e-12)
        assert row["joint_A_y"] == pytest.approx(9.81, rel=1e-12)
        assert row["joint_B_x"] == pytest.approx(0.0, abs=1e-12)


def test_fourbar_without_masses_keeps_its_columns(capsys):
    status, out, _ = run(capsys, *FOURBAR, "--angles", "60", "--format", "csv")
    assert status == 0 and "input_torque" not in out.splitlines()[0]


def test_flywheel_of_a_crank_under_gravity(capsys):
    # T = 4 + g m r cos(theta): mean 4, dE = 2 g m r; textbook I = dE / (Cs w^2); exact = I - (I2 + m r^2);
    # the textbook flywheel on the crank gives Cs I / (I + I2 + m r^2).
    status, out, err = run(capsys, *FLYWHEEL, *CRANK_ONLY, "--load-torque", "-4", "--rpm", "200",
                           "--coefficient", "0.04", "--format", "csv")
    assert status == 0, err
    assert out.splitlines()[0] == ",".join(FLYWHEEL_COLUMNS)
    (row,) = rows(out)
    w = 200 * 2 * math.pi / 60
    energy = 2 * 9.81 * 1.0 * 0.1
    textbook = energy / (0.04 * w * w)
    own = 0.03 + 1.0 * 0.1 ** 2
    assert row["mean_speed"] == pytest.approx(w, rel=1e-15)
    assert row["mean_torque"] == pytest.approx(4.0, rel=1e-12)
    assert row["energy_fluctuation"] == pytest.approx(energy, rel=1e-12)
    assert row["flywheel_inertia"] == pytest.approx(textbook, rel=1e-12)
    assert row["exact_flywheel_inertia"] == pytest.approx(textbook - own, rel=1e-9)
    assert row["achieved_coefficient"] == pytest.approx(0.04 * textbook / (textbook + own), rel=1e-7)
    assert (row["speed_max"] + row["speed_min"]) / 2 == pytest.approx(w, rel=1e-9)


def test_flywheel_json_and_rad_per_s(capsys):
    status, out, err = run(capsys, *FLYWHEEL, *CRANK_ONLY, "--load-torque", "-4", "--rad-per-s", "20",
                           "--coefficient", "0.04", "--format", "json")
    assert status == 0, err
    import json
    (record,) = json.loads(out)
    assert list(record) == FLYWHEEL_COLUMNS and record["mean_speed"] == 20.0


MISTAKES = [
    ("flywheel without masses", [*FLYWHEEL, "--rpm", "100", "--coefficient", "0.05"], "--masses"),
    ("two masses", [*FLYWHEEL, "--masses", "1,2", "--rpm", "100", "--coefficient", "0.05"], "three numbers"),
    ("negative mass", [*FLYWHEEL, "--masses", "-1,2,3", "--rpm", "100", "--coefficient", "0.05"],
     "must not be negative"),
    ("centre not a number", [*FLYWHEEL, "--masses", "1,2,3", "--centres", "1:x,2,3", "--rpm", "100",
                             "--coefficient", "0.05"], "not a number"),
    ("gravity of three numbers", [*FLYWHEEL, "--masses", "1,2,3", "--gravity", "1,2,3", "--rpm", "100",
                                  "--coefficient", "0.05"], "G or G,ANGLE"),
    ("zero coefficient", [*FLYWHEEL, "--masses", "1,2,3", "--rpm", "100", "--coefficient", "0"],
     "coefficient of speed fluctuation must be a positive"),
    ("huge coefficient", [*FLYWHEEL, "--masses", "1,2,3", "--rpm", "100", "--coefficient", "2.5", "--load-torque",
                          "-1"], "below 2"),
    ("zero speed", [*FLYWHEEL, "--masses", "1,2,3", "--rpm", "0", "--coefficient", "0.05"], "must be positive"),
    ("both speeds", [*FLYWHEEL, "--masses", "1,2,3", "--rpm", "1", "--rad-per-s", "1", "--coefficient", "0.05"],
     "not allowed with"),
    ("no speed", [*FLYWHEEL, "--masses", "1,2,3", "--coefficient", "0.05"], "required"),
    ("few samples", [*FLYWHEEL, "--masses", "1,2,3", "--rpm", "100", "--coefficient", "0.05", "--samples", "3"],
     "samples must be"),
    ("crank cannot turn", ["flywheel", "--crank", "0.4", "--coupler", "0.3", "--rocker", "0.35", "--ground", "0.5",
                           "--masses", "1,2,3", "--rpm", "100", "--coefficient", "0.05"], "does not turn a whole"),
    ("inertias without masses", [*FOURBAR, "--inertias", "1,2,3"], "needs --masses"),
    ("fourbar two inertias", [*FOURBAR, "--masses", "1,2,3", "--inertias", "1,2"], "three numbers"),
]


@pytest.mark.parametrize("what, argv, message", MISTAKES, ids=[m[0] for m in MISTAKES])
def test_bad_input_is_one_line_and_exit_2(capsys, what, argv, message):
    status, out, err = run(capsys, *argv)
    assert status == 2
    assert out == ""
    assert err.count("\n") == 1 and err.startswith("symlink: error:")
    assert message in err
