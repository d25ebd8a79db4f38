"""`symlink slider-crank`: the csv contract of issue 4, references at 50 digits, unassemblable angles, bad input."""
import csv
import io
import json
import math

import numpy as np
import pytest

from references import mp_slider_crank
from test_fourbar_table import run, wrapped_degrees
from symlink.cli import main
from symlink.numeric.reachability import slider_crank_range

HEADER = "crank,branch,conrod,slider,conrod_speed,slider_speed,conrod_accel,slider_accel"
BASE = ["slider-crank", "--crank", "20", "--conrod", "66", "--offset", "-5"]


def test_csv_header_and_rows_match_50_digits(capsys):
    status, out, err = run(capsys, *BASE, "--crank-speed", "10.5", "--crank-accel", "2", "--step", "30",
                           "--format", "csv")
    assert status == 0 and err == ""
    assert out.splitlines()[0] == HEADER
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 24 and {r["branch"] for r in rows} == {"1", "-1"}
    for row in rows:
        theta = math.radians(float(row["crank"]))
        speed = math.sqrt(10.5**2 + 2 * 2 * (math.remainder(theta, 2 * math.pi) % (2 * math.pi)))
        ref = mp_slider_crank(20, 66, -5, theta, int(row["branch"]), speed, 2)
        assert abs(float(row["conrod"]) - wrapped_degrees(float(ref["beta"]))) < 1e-10
        assert abs(float(row["slider"]) - float(ref["s"])) < 1e-12 * 86
        assert abs(float(row["conrod_speed"]) - float(ref["beta_speed"])) < 1e-12
        assert abs(float(row["slider_speed"]) - float(ref["s_speed"])) < 1e-11
        assert abs(float(row["conrod_accel"]) - float(ref["beta_accel"])) < 1e-10
        assert abs(float(row["slider_accel"]) - float(ref["s_accel"])) < 1e-9
        assert -180 < float(row["crank"]) <= 180


def test_branch_plus_one_is_the_larger_slider_position(capsys):
    _, out, _ = run(capsys, *BASE, "--angles", "10,100,250", "--format", "json")
    records = json.loads(out)
    for angle in (10, 100, -110):
        far, near = ([r["slider"] for r in records if r["crank"] == angle and r["branch"] == s] for s in (1, -1))
        assert far[0] > near[0]


def test_radians_in_and_out_and_zero_offset_by_default(capsys):
    _, out, _ = run(capsys, "slider-crank", "--crank", "2", "--conrod", "5", "--angles", "0.5", "--units", "rad",
                    "--branch", "-1", "--format", "csv")
    row = next(csv.DictReader(io.StringIO(out)))
    ref = mp_slider_crank(2, 5, 0, 0.5, -1)
    assert float(row["crank"]) == 0.5 and abs(float(row["conrod"]) - float(ref["beta"])) < 1e-13
    assert abs(float(row["slider"]) - float(ref["s"])) < 1e-13


def test_table_is_aligned_with_the_columns(capsys):
    _, out, _ = run(capsys, *BASE, "--angles", "0", "--branch", "+1")
    header, row = out.splitlines()
    names = [name for name in header.split() if not name.startswith("(")]  # units in the header: crank (deg)
    assert names == HEADER.split(",") and len(row.split()) == 8 and row.split()[1] == "+1"
    assert len(header) == len(row)  # each cell under its column


def test_unassemblable_angles_are_left_out_and_named(capsys):
    # a=20, b=10, offset=5: the rod reaches the guide only where -5 <= 20 sin(theta) <= 15.
    status, out, err = run(capsys, "slider-crank", "--crank", "20", "--conrod", "10", "--offset", "5",
                           "--step", "30", "--branch", "+1", "--format", "csv")
    assert status == 0
    cranks = [float(r["crank"]) for r in csv.DictReader(io.StringIO(out))]
    assert cranks == [0.0, 30.0, 150.0, 180.0]
    assert "cannot be assembled at crank angles 60, 90, 120, -150, -120, -90, -60, -30 deg" in err
    low, high = math.degrees(math.asin(-5 / 20)), math.degrees(math.asin(15 / 20))
    assert f"[{low:.6g}, {high:.6g}] deg, [{180 - high:.6g}, {180 - low:.6g}] deg" in err


def test_toggle_rows_are_kept_with_undefined_rates_and_named(capsys):
    # a=1, b=2, offset=1: at theta = -90 deg the rod stands vertical (offset - a sin(theta) = b).
    status, out, err = run(capsys, "slider-crank", "--crank", "1", "--conrod", "2", "--offset", "1",
                           "--angles=-90,0", "--crank-speed", "1", "--branch", "+1", "--format", "csv")
    assert status == 0
    rows = list(csv.DictReader(io.StringIO(out)))
    assert float(rows[0]["conrod"]) == 90.0 and not math.isfinite(float(rows[0]["slider_speed"]))
    assert math.isfinite(float(rows[1]["slider_speed"]))
    assert "singular (toggle) position at crank angles -90 deg" in err


def test_no_assemblable_angle_exits_2(capsys):
    status, out, err = run(capsys, "slider-crank", "--crank", "1", "--conrod", "1", "--offset", "10")
    assert status == 2 and out == ""
    assert err.startswith("symlink: error: ") and "cannot be assembled" in err and err.count("\n") == 1
    assert "none: the links cannot close at any crank angle" in err


@pytest.mark.parametrize("bad", [
    ["--crank", "0"], ["--crank", "-1"], ["--conrod", "nan"], ["--offset", "inf"], ["--offset", "1e"],
    ["--bogus", "3"], ["--branch", "2"], ["--step", "0"], ["--start", "10", "--stop", "5"],
    ["--angles", "10", "--step", "5"], ["--units", "grad"], ["--format", "xml"], ["--crank-speed", "x"],
])
def test_bad_input_one_line_exit_2(capsys, bad):
    argv = list(BASE)
    for flag in ("--crank", "--conrod", "--offset"):
        if flag in bad:
            index = argv.index(flag)
            del argv[index:index + 2]
    status, out, err = run(capsys, *argv, *bad)
    assert status == 2 and out == ""
    assert err.startswith("symlink: error: ") and err.count("\n") == 1


def test_missing_conrod_is_an_error(capsys):
    status, _, err = run(capsys, "slider-crank", "--crank", "2")
    assert status == 2 and "--conrod" in err


@pytest.mark.parametrize("a, b, offset", [(2, 1, 0), (20, 10, 5), (1, 3, 0.5), (1, 1, 1.5), (1, 1, -1.5),
                                          (3, 1, 3.5), (1, 1, 10)])
def test_reachable_range_against_a_dense_scan(a, b, offset):
    theta = np.linspace(-math.pi, 3 * math.pi, 40001)
    reachable = np.abs(offset - a * np.sin(theta)) <= b
    spans = slider_crank_range(a, b, offset)
    inside = np.zeros_like(reachable)
    for low, high in spans:
        for turn in (-2 * math.pi, 0.0, 2 * math.pi):
            inside |= (theta >= low + turn - 1e-9) & (theta <= high + turn + 1e-9)
    assert np.array_equal(inside, reachable) or np.all(inside[reachable])
    assert not np.any(inside & ~reachable & (np.abs(np.abs(offset - a * np.sin(theta)) - b) > 1e-6))
