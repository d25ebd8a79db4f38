"""The `symlink fourbar` command: the csv contract, unassemblable angles, bad input."""
import csv
import io
import json
import math
import subprocess
import sys

import pytest

from references import SEED003_BRANCHES, SEED003_LINKAGE, SEED003_TABLE, mp_fourbar
from symlink.cli import main

SEED003 = ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80"]
HEADER = "crank,branch,coupler,rocker,coupler_speed,rocker_speed,coupler_accel,rocker_accel,transmission"


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def wrapped_degrees(radians):
    wrapped = math.remainder(math.degrees(radians), 360.0)
    return 180.0 if wrapped == -180.0 else wrapped


def test_csv_header_and_rows_match_the_reference(capsys):
    status, out, err = run(capsys, *SEED003, "--crank-speed", "10.5", "--step", "40", "--format", "csv")
    assert status == 0 and err == ""
    lines = out.splitlines()
    assert lines[0] == HEADER
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 18
    for row in rows:
        theta = math.radians(float(row["crank"]))
        ref = mp_fourbar(20, 66, 56, 80, theta, int(row["branch"]), 10.5, 0)
        assert abs(float(row["rocker"]) - wrapped_degrees(float(ref["phi"]))) < 1e-10
        assert abs(float(row["coupler"]) - wrapped_degrees(float(ref["beta"]))) < 1e-10
        assert abs(float(row["rocker_speed"]) - float(ref["phi_speed"])) < 1e-11
        assert abs(float(row["coupler_accel"]) - float(ref["beta_accel"])) < 1e-10
        assert -180 < float(row["crank"]) <= 180 and 0 <= float(row["transmission"]) <= 180


def test_seed003_table_rows_are_all_printed(capsys):
    status, out, _ = run(capsys, *SEED003, "--crank-speed", "10.5", "--step", "40", "--format", "json")
    records = json.loads(out)
    printed = {(round(wrapped_degrees(math.radians(r[0])), 9), b) for r, b in zip(SEED003_TABLE, SEED003_BRANCHES)}
    assert {(r["crank"], r["branch"]) for r in records} == printed


def test_radians_in_and_out(capsys):
    _, out, _ = run(capsys, *SEED003, "--angles", "0.5", "--units", "rad", "--branch", "+1", "--format", "csv")
    row = next(csv.DictReader(io.StringIO(out)))
    assert float(row["crank"]) == 0.5
    assert abs(float(row["rocker"]) - float(mp_fourbar(20, 66, 56, 80, 0.5, 1)["phi"])) < 1e-12


def test_full_precision_in_csv(capsys):
    _, out, _ = run(capsys, *SEED003, "--angles", "40", "--branch", "1", "--format", "csv")
    row = next(csv.DictReader(io.StringIO(out)))
    ref = float(mp_fourbar(20, 66, 56, 80, math.radians(40), 1)["phi"])
    assert abs(float(row["rocker"]) - math.degrees(ref)) < 1e-12 and len(row["rocker"]) > 12


def test_crank_acceleration_speeds_the_crank_up_from_the_first_angle(capsys):
    _, out, _ = run(capsys, *SEED003, "--crank-speed", "2", "--crank-accel", "3", "--start", "30",
                    "--stop", "100", "--step", "35", "--branch", "-1", "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [float(r["crank"]) for r in rows] == [30.0, 65.0]
    for row in rows:
        theta = math.radians(float(row["crank"]))
        speed = math.sqrt(2**2 + 2 * 3 * (theta - math.radians(30)))
        ref = mp_fourbar(20, 66, 56, 80, theta, -1, speed, 3)
        assert abs(float(row["rocker_accel"]) - float(ref["phi_accel"])) < 1e-10


def test_unassemblable_angles_are_left_out_and_named(capsys):
    # a=50, b=20, c=40, d=30: the crank reaches only |theta| <= 93.82 deg.
    status, out, err = run(capsys, "fourbar", "--crank", "50", "--coupler", "20", "--rocker", "40",
                           "--ground", "30", "--step", "30", "--branch", "+1", "--format", "csv")
    assert status == 0
    cranks = [float(r["crank"]) for r in csv.DictReader(io.StringIO(out))]
    assert 120.0 not in cranks and 90.0 in cranks
    assert "cannot be assembled at crank angles 120, 150, 180, -150, -120 deg" in err
    limit = math.degrees(math.acos((50**2 + 30**2 - 60**2) / (2 * 50 * 30)))
    assert f"[{-limit:.6g}, {limit:.6g}] deg" in err


def test_no_assemblable_angle_exits_2(capsys):
    status, out, err = run(capsys, "fourbar", "--crank", "1", "--coupler", "1", "--rocker", "1", "--ground", "100")
    assert status == 2 and out == ""
    assert err.startswith("symlink: error: ") and "cannot be assembled" in err and err.count("\n") == 1


@pytest.mark.parametrize("bad", [
    ["--crank", "0"], ["--crank", "-1"], ["--crank", "nan"], ["--crank", "inf"], ["--crank", "1e"],
    ["--bogus", "3"], ["--branch", "2"], ["--step", "0"], ["--start", "10", "--stop", "5"],
    ["--angles", "10", "--step", "5"], ["--units", "grad"], ["--format", "xml"],
])
def test_bad_input_one_line_exit_2(capsys, bad):
    argv = list(SEED003)
    for flag in ("--crank",):
        if flag in bad:
            index = argv.index(flag)
            del argv[index:index + 2]
    status, out, err = run(capsys, *argv, *bad)
    assert status == 2 and out == ""
    assert err.startswith("symlink: error: ") and err.count("\n") == 1


def test_console_entry_point_runs_as_a_module():
    done = subprocess.run([sys.executable, "-m", "symlink", *SEED003, "--crank", "-3"],
                          capture_output=True, text=True)
    assert done.returncode == 2 and "Traceback" not in done.stderr


def test_negative_numbers_are_values_not_options(capsys):
    status, out, _ = run(capsys, *SEED003, "--angles", "-90,-1e-3", "--branch", "1", "--format", "csv")
    assert status == 0
    assert [float(r["crank"]) for r in csv.DictReader(io.StringIO(out))] == [-90.0, -0.001]
