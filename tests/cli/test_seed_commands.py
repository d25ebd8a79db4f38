"""The seed papers from the command line: `symlink loop` (000), `symlink quick-return` (002),
and seed 003's non-uniform crank in `symlink fourbar`, against references computed here."""
import csv
import io
import json
import math

import mpmath as mp
import pytest

from references import mp_fourbar
from symlink.cli import main

SEED000 = ["loop", "--r1", "300", "--t1", "270", "--r2", "640.3124", "--t2", "308.663", "--t3", "180",
           "--t4", "63.435"]
PAPER002 = ["quick-return", "--time-ratio", "1.25", "--stroke", "40", "--rocker", "50"]
SEED003 = ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80"]


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def one_line_error(status, out, err):
    return status == 2 and out == "" and err.startswith("symlink: error: ") and err.count("\n") == 1


# --- symlink loop (seed 000) ----------------------------------------------------------

def hand_case1():
    """R3, R4 of the worked example by Cramer's rule, at 40 digits."""
    with mp.workdps(40):
        r = lambda x: mp.radians(mp.mpf(x))  # noqa: E731
        wx = -(300 * mp.cos(r(270)) + mp.mpf("640.3124") * mp.cos(r("308.663")))
        wy = -(300 * mp.sin(r(270)) + mp.mpf("640.3124") * mp.sin(r("308.663")))
        c3, s3, c4, s4 = mp.cos(r(180)), mp.sin(r(180)), mp.cos(r("63.435")), mp.sin(r("63.435"))
        det = c3 * s4 - s3 * c4
        return (wx * s4 - wy * c4) / det, (c3 * wy - s3 * wx) / det


def test_loop_json_seed000(capsys):
    status, out, err = run(capsys, *SEED000, "--format", "json")
    assert status == 0 and err == ""
    record = json.loads(out)
    assert list(record) == ["case", "solutions"] and record["case"] == "1"
    (solution,) = record["solutions"]
    assert list(solution) == ["r3", "r4"]
    assert round(solution["r3"], 4) == 800.0158 and round(solution["r4"], 4) == 894.4019
    r3, r4 = hand_case1()
    # full double precision in the JSON text
    assert abs(solution["r3"] - float(r3)) < 1e-12 * 800 and abs(solution["r4"] - float(r4)) < 1e-12 * 900
    assert len(repr(solution["r3"]).replace(".", "")) >= 15


def test_loop_table_seed000(capsys):
    status, out, _ = run(capsys, *SEED000)
    assert status == 0
    assert out.splitlines()[0].startswith("case 1: two lengths")
    assert "800.0158" in out and "894.4019" in out


def test_loop_case3_both_branches_in_degrees_and_radians(capsys):
    base = ["loop", "--r1", "2", "--r2", "3", "--r3", "3", "--r4", "4"]
    status, out, _ = run(capsys, *base, "--t1", "210", "--t2", "210", "--format", "json")
    record = json.loads(out)
    assert status == 0 and record["case"] == "3" and len(record["solutions"]) == 2
    # W = 5 e^{i 30 deg}; z3 at 30 +- acos(3/5) deg (law of cosines), branch +1 first
    spread = math.degrees(math.acos(0.6))
    assert [s["t3"] for s in record["solutions"]] == pytest.approx([30 + spread, 30 - spread], abs=1e-12)
    status, out, _ = run(capsys, *base, "--t1", str(math.radians(210)), "--t2", str(math.radians(210)),
                         "--units", "rad", "--format", "json")
    radians = json.loads(out)["solutions"]
    assert [s["t3"] for s in radians] == pytest.approx([math.radians(30 + spread), math.radians(30 - spread)],
                                                       abs=1e-12)


def test_loop_table_lists_branches(capsys):
    status, out, _ = run(capsys, "loop", "--r1", "5", "--t1", "90", "--r2", "30", "--t2", "180", "--r3", "13",
                         "--t4", "0")
    lines = out.splitlines()
    assert status == 0 and lines[0].startswith("case 2b") and lines[1].split() == ["branch", "r4", "t3"]
    assert lines[2].split()[:2] == ["+1", "42.0000"] and lines[3].split()[:2] == ["-1", "18.0000"]


@pytest.mark.parametrize("drop, count", [(["--t4", "63.435"], "3 are missing"), ([], "1 is missing")])
def test_loop_counts_missing_values(capsys, drop, count):
    argv = [a for a in SEED000 if a not in drop]
    if not drop:
        argv += ["--r3", "800"]
    status, out, err = run(capsys, *argv)
    assert one_line_error(status, out, err) and count in err


def test_loop_that_cannot_close_exits_2(capsys):
    status, out, err = run(capsys, "loop", "--r1", "300", "--t1", "270", "--r2", "640.3124", "--t2", "308.663",
                           "--r3", "10", "--r4", "50")
    assert one_line_error(status, out, err) and "cannot close" in err and "reach at most 60" in err


@pytest.mark.parametrize("bad", [["--r1", "-3"], ["--t1", "nan"], ["--format", "csv"], ["--units", "grad"],
                                 ["--r5", "1"]])
def test_loop_bad_input(capsys, bad):
    assert one_line_error(*run(capsys, *SEED000, *bad))


def test_loop_plot_writes_a_picture(capsys, tmp_path):
    plot = pytest.importorskip("symlink.plot")
    if not hasattr(plot, "draw_loop"):
        pytest.skip("symlink.plot has no draw_loop")
    import matplotlib
    matplotlib.use("Agg")
    from matplotlib.image import imread
    path = tmp_path / "loop.png"
    status, out, err = run(capsys, *SEED000, "--plot", str(path))
    assert status == 0 and "800.0158" in out
    image = imread(path)
    assert image.ndim == 3 and image.shape[0] > 100 and image.shape[1] > 100


# --- symlink quick-return (seed 002) ---------------------------------------------------

REQUIRED = ["crank", "coupler", "rocker", "ground", "crank_pivot", "rocker_pivot", "stroke", "time_ratio",
            "transmission_min", "transmission_max", "grashof"]


def test_quick_return_paper_pivot(capsys):
    status, out, err = run(capsys, *PAPER002, "--rocker-min-angle", "90", "--crank-pivot", "-70,0",
                           "--format", "json")
    assert status == 0
    record = json.loads(out)
    assert all(key in record for key in REQUIRED)
    assert round(record["crank"], 3) == 16.084 and record["ground"] == 70.0 and record["rocker"] == 50.0
    assert record["crank_pivot"] == [-70.0, 0.0] and record["rocker_pivot"] == [0.0, 0.0]
    assert round(record["time_ratio"], 3) == 1.115 and record["stroke"] == pytest.approx(40, abs=1e-9)
    assert record["grashof"] == "crank-rocker"
    # by hand, full precision: a = (|O2 B1| - |O2 B2|) / 2
    far = math.hypot(70, 50)
    near = math.hypot(70 + 50 * math.cos(math.radians(130)), 50 * math.sin(math.radians(130)))
    assert abs(record["crank"] - (far - near) / 2) < 1e-13
    assert "symlink: warning: the requested time ratio 1.25 is not met" in err and "-0.1349" in err


def test_quick_return_exact(capsys):
    status, out, err = run(capsys, *PAPER002, "--format", "json")
    record = json.loads(out)
    assert status == 0 and all(key in record for key in REQUIRED)
    assert abs(record["time_ratio"] - 1.25) < 1e-12 and abs(record["stroke"] - 40) < 1e-11
    assert round(record["worst_transmission"], 1) == 42.8 and record["transmission_min"] == record["worst_transmission"]
    assert "below the usual 45 deg" in err


def test_quick_return_table(capsys):
    status, out, err = run(capsys, *PAPER002, "--crank-pivot", "-70,0")
    assert status == 0
    assert "crank          16.0835" in out and "time ratio     1.1151 (requested 1.25)" in out
    assert "Grashof        crank-rocker" in out and "not met" in err


@pytest.mark.parametrize("change, reason", [
    (["--time-ratio", "0.8"], "at least 1"),
    (["--stroke", "0"], "strictly between 0 and 180"),
    (["--stroke", "180"], "strictly between 0 and 180"),
    (["--stroke", "270"], "strictly between 0 and 180"),
    (["--rocker", "0"], "rocker must be a positive"),
    (["--rocker", "-50"], "rocker must be a positive"),
    (["--crank-pivot", "1,2,3"], "X,Y"),
    (["--crank-pivot", "0,1000"], "not a crank-rocker"),
    (["--time-ratio", "5", "--stroke", "20"], "no crank-rocker"),
])
def test_quick_return_impossible_requests(capsys, change, reason):
    argv = list(PAPER002)
    for flag, value in zip(change[::2], change[1::2]):
        if flag in argv:
            argv[argv.index(flag) + 1] = value
        else:
            argv += [flag, value]
    status, out, err = run(capsys, *argv)
    assert one_line_error(status, out, err) and reason in err


# --- seed 003: a crank that speeds up uniformly ----------------------------------------

def reference_rows(angles_deg, speed, accel, branches):
    """Rows computed here: omega^2 = W^2 + 2 AL (theta - theta_first), positions and rates by mp_fourbar."""
    rows = []
    with mp.workdps(40):
        first = mp.radians(mp.mpf(angles_deg[0]))
        for angle in angles_deg:
            theta = mp.radians(mp.mpf(angle))
            omega = mp.sqrt(mp.mpf(speed)**2 + 2 * mp.mpf(accel) * (theta - first))
            for branch in branches:
                ref = mp_fourbar(20, 66, 56, 80, theta, branch, omega, accel)
                mu = abs(float(mp.atan2(mp.sin(ref["beta"] - ref["phi"]), mp.cos(ref["beta"] - ref["phi"]))))
                rows.append(dict(
                    crank=math.remainder(angle, 360), branch=branch,
                    coupler=float(mp.degrees(ref["beta"])), rocker=float(mp.degrees(ref["phi"])),
                    coupler_speed=float(ref["beta_speed"]), rocker_speed=float(ref["phi_speed"]),
                    coupler_accel=float(ref["beta_accel"]), rocker_accel=float(ref["phi_accel"]),
                    transmission=math.degrees(mu)))
    return rows


def same_angle(x, y, tolerance):
    return abs(math.remainder(x - y, 360)) < tolerance


def compare(found, expected, tolerance):
    assert len(found) == len(expected)
    for row, ref in zip(found, expected):
        assert same_angle(float(row["crank"]), ref["crank"], 1e-9) and int(row["branch"]) == ref["branch"]
        for key in ("coupler", "rocker"):
            assert same_angle(float(row[key]), ref[key], tolerance)
        for key in ("coupler_speed", "rocker_speed", "coupler_accel", "rocker_accel", "transmission"):
            assert float(row[key]) == pytest.approx(ref[key], abs=tolerance * max(1.0, abs(ref[key])))


@pytest.mark.parametrize("fmt", ["csv", "json"])
def test_seed003_accelerating_crank_any_interval_both_branches(capsys, fmt):
    # 15 deg to 375 deg (across a full turn) every 45 deg, 10.5 rad/s, speeding up at 25 rad/s^2
    status, out, err = run(capsys, *SEED003, "--crank-speed", "10.5", "--crank-accel", "25", "--start", "15",
                           "--stop", "375", "--step", "45", "--format", fmt)
    assert status == 0 and err == ""
    rows = list(csv.DictReader(io.StringIO(out))) if fmt == "csv" else json.loads(out)
    expected = reference_rows([15 + 45 * i for i in range(8)], 10.5, 25, (1, -1))
    compare(rows, expected, 1e-10)


def test_seed003_decelerating_crank_at_listed_angles_one_branch(capsys):
    status, out, _ = run(capsys, *SEED003, "--crank-speed", "10.5", "--crank-accel", "-3", "--angles",
                         "40,100,250,300", "--branch", "-1", "--format", "csv")
    assert status == 0
    compare(list(csv.DictReader(io.StringIO(out))), reference_rows([40, 100, 250, 300], 10.5, -3, (-1,)), 1e-10)


def test_seed003_accelerating_crank_table(capsys):
    status, out, _ = run(capsys, *SEED003, "--crank-speed", "10.5", "--crank-accel", "25", "--step", "40")
    lines = out.splitlines()
    header = [name for name in lines[0].split() if not name.startswith("(")]  # units in the header: crank (deg)
    assert lines[0].split()[:3] == ["crank", "(deg)", "branch"] and "coupler_speed (rad/s)" in lines[0]
    rows = [dict(zip(header, line.split())) for line in lines[1:]]
    compare(rows, reference_rows(list(range(0, 360, 40)), 10.5, 25, (1, -1)), 1e-4)  # 4 decimals


def test_seed003_crank_that_stops_exits_2(capsys):
    status, out, err = run(capsys, *SEED003, "--crank-speed", "1", "--crank-accel", "-1", "--step", "40")
    assert one_line_error(status, out, err) and "stops" in err
