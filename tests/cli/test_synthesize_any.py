"""``symlink synthesize path|function|motion LINKAGE FILE``: any linkage from the command line, checked by hand.

Targets are made by hand formulas (``tests/synthesis/hand_linkages.py``) from a known design; the design the command
finds is checked with the same formulas from its ``--record``, and the linkage file it writes (``--out``) is read
back by ``symlink table``, whose angles are checked too.  Bad command lines: one error line, exit status 2.
"""
from __future__ import annotations

import cmath
import csv
import io
import json
import math

import numpy
import pytest

from symlink.mechanism.catalog import EXAMPLE_VALUES
from symlink.cli import main
from synthesis.hand_linkages import fourbar_joints, slider_travel, watt2_joints, wrapped

WATT = EXAMPLE_VALUES["watt2"]
WHERE = {"x0": 0.7, "y0": -0.4, "angle": 0.5}


def table_row(capsys, *arguments) -> dict:
    capsys.readouterr()
    assert main(["table", *arguments, "--format", "csv"]) == 0
    rows = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    assert len(rows) == 1, rows
    return rows[0]


def placed(z: complex) -> complex:
    return complex(WHERE["x0"], WHERE["y0"]) + cmath.exp(1j * WHERE["angle"]) * z


def test_function_of_a_slider_crank(tmp_path, capsys):
    inputs = [float(q) for q in numpy.linspace(10.0, 150.0, 7)]  # degrees
    truth = (1.3, 4.1, 0.7)  # the catalog's offset 0.7 is kept; a and b start from 1.0 and 3.5
    (tmp_path / "t.csv").write_text("theta,s\n" + "".join(
        f"{q!r},{slider_travel(*truth, math.radians(q))!r}\n" for q in inputs))
    out, record = tmp_path / "design.toml", tmp_path / "design.json"
    status = main(["synthesize", "function", "slider-crank", str(tmp_path / "t.csv"), "--set", "a=1.0,b=3.5",
                   "--bound", "a=0.5,2", "--bound", "b=3,5", "--out", str(out), "--record", str(record),
                   "--plot", str(tmp_path / "f.png")])
    assert status == 0, capsys.readouterr().err
    found = json.loads(record.read_text())
    assert found["assembled"] and found["kind"] == "function" and found["units"] == "deg"
    v = found["design"]
    for q in inputs:
        assert abs(slider_travel(v["a"], v["b"], v["offset"], math.radians(q)) - slider_travel(*truth, math.radians(q))
                   ) < 1e-8
    assert (tmp_path / "f.png").stat().st_size > 0
    row = table_row(capsys, str(out), "--angles", "40", "--branch", "+1")  # the file's defaults read back
    assert abs(float(row["slider"]) - slider_travel(*truth, math.radians(40))) < 1e-6  # printed to 6 digits


WATT_TRUTH = {**WATT, "b": 3.7, "f": 4.2}
WATT_INPUTS = [float(q) for q in numpy.linspace(20.0, 250.0, 7)]  # degrees


def watt_path_command(tmp_path) -> list[str]:
    """``symlink synthesize path watt2`` on the placed point F of WATT_TRUTH at WATT_INPUTS (hand formulas)."""
    points = [placed(watt2_joints(WATT_TRUTH, math.radians(q))["F"]) for q in WATT_INPUTS]
    (tmp_path / "t.csv").write_text("theta,x,y\n" + "".join(f"{q!r},{p.real!r},{p.imag!r}\n"
                                                            for q, p in zip(WATT_INPUTS, points)))
    return ["synthesize", "path", "watt2", str(tmp_path / "t.csv"), "--point", "F", "--bound", "b=3,4.5",
            "--bound", "f=3.5,5", "--frame", "x0,y0,angle"]


def check_watt_path_reached(found: dict) -> None:
    """The recorded design, placed, puts F on every target to 1e-8 of their size (hand formulas)."""
    points = [placed(watt2_joints(WATT_TRUTH, math.radians(q))["F"]) for q in WATT_INPUTS]
    where = {**found["placement"], "angle": math.radians(found["placement"]["angle"])}
    design = {**found["design"], "alpha": math.radians(found["design"]["alpha"])}
    signs = (found["branches"]["branch_ABCD"], found["branches"]["branch_DEFG"])
    size = math.hypot(*numpy.ptp([[p.real, p.imag] for p in points], axis=0))
    for q, p in zip(WATT_INPUTS, points):
        F = watt2_joints(design, math.radians(q), signs)["F"]
        assert abs(complex(where["x0"], where["y0"]) + cmath.exp(1j * where["angle"]) * F - p) < 1e-8 * size


def test_path_of_a_watt_two_point_timed(tmp_path, capsys):
    truth, inputs = WATT_TRUTH, WATT_INPUTS
    out, record = tmp_path / "path.toml", tmp_path / "path.json"
    status = main([*watt_path_command(tmp_path), "--out", str(out), "--record", str(record)])
    assert status == 0, capsys.readouterr().err
    found = json.loads(record.read_text())
    assert found["assembled"]
    check_watt_path_reached(found)
    # the file holds the placement: its output angle is the placed one (turned by the frame's angle)
    row = table_row(capsys, str(out), "--angles", f"{inputs[2]!r}", "--branch", "+1,+1")
    psi = watt2_joints(truth, math.radians(inputs[2]))["psi"] + WHERE["angle"]
    assert abs(wrapped(math.radians(float(row["output"])) - psi)) < 1e-5


def test_motion_of_a_fourbar_coupler_timed(tmp_path, capsys):
    truth = (1.0, 3.0, 2.5, 3.2)
    inputs = [20.0, 60.0, 100.0, 140.0]
    rows = []
    for q in inputs:
        B, C = fourbar_joints(*truth, math.radians(q))
        p = placed(B)
        rows.append(f"{q!r},{p.real!r},{p.imag!r},{math.degrees(cmath.phase(C - B) + WHERE['angle'])!r}\n")
    (tmp_path / "poses.csv").write_text("theta,x,y,angle\n" + "".join(rows))
    out, record = tmp_path / "m.toml", tmp_path / "m.csv"
    status = main(["synthesize", "motion", "fourbar", str(tmp_path / "poses.csv"), "--angle", "coupler",
                   "--set", "a=1,b=2.5,c=2,d=3.2", "--bound", "b=2,4", "--bound", "c=1.5,3.5", "--out", str(out),
                   "--record", str(record), "--plot", str(tmp_path / "m.png"), "--format", "json"])
    assert status == 0, capsys.readouterr().err
    printed = json.loads(capsys.readouterr().out)
    assert printed["assembled"] and abs(printed["design"]["b"] - 3.0) < 1e-8 and abs(printed["design"]["c"] - 2.5) < 1e-8
    lines = list(csv.DictReader(io.StringIO(record.read_text())))
    assert numpy.allclose([float(line["input"]) for line in lines], inputs, rtol=0, atol=1e-12)
    assert all(float(line["position_error"]) < 1e-10 and abs(float(line["angle_error"])) < 1e-8 for line in lines)
    row = table_row(capsys, str(out), "--angles", "60", "--branch", "+1")
    B, C = fourbar_joints(*truth, math.radians(60))
    assert abs(wrapped(math.radians(float(row["coupler"])) - cmath.phase(C - B) - WHERE["angle"])) < 1e-5


def test_function_with_generic_columns_and_output_named(tmp_path, capsys):
    inputs = [0.2, 0.7, 1.2, 1.7, 2.2]  # radians
    (tmp_path / "t.csv").write_text("input,output\n" + "".join(
        f"{q!r},{slider_travel(1.1, 3.9, -0.2, q)!r}\n" for q in inputs))
    status = main(["synthesize", "function", "slider-crank", str(tmp_path / "t.csv"), "--output", "s", "--units",
                   "rad", "--set", "a=1,b=4,offset=0", "--free", "a,b,offset", "--format", "json"])
    assert status == 0, capsys.readouterr().err
    found = json.loads(capsys.readouterr().out)
    v = found["design"]
    assert found["inputs"] == inputs
    assert max(abs(slider_travel(v["a"], v["b"], v["offset"], q) - slider_travel(1.1, 3.9, -0.2, q))
               for q in inputs) < 1e-8


@pytest.fixture
def targets(tmp_path):
    (tmp_path / "xy.csv").write_text("x,y\n0,0\n1,0.5\n2,0.7\n")
    (tmp_path / "fn.csv").write_text("theta,s\n10,4\n20,4.1\n30,4.2\n")
    (tmp_path / "poses.csv").write_text("x,y,angle\n0,0,0\n1,0.5,10\n")
    return tmp_path


BAD = [
    (["path", "nowhere", "xy.csv", "--free", "a"], "no linkage 'nowhere'"),
    (["path", "watt2", "xy.csv", "--free", "zz", "--point", "F"], "no parameter 'zz'"),
    (["path", "watt2", "xy.csv", "--bound", "b=4,3", "--point", "F"], "low bound must be below"),
    (["path", "watt2", "xy.csv", "--bound", "b=4", "--point", "F"], "expected NAME=LO,HI"),
    (["path", "watt2", "xy.csv", "--bound", "b=3,x", "--point", "F"], "not a number"),
    (["path", "watt2", "xy.csv", "--free", "b", "--point", "F", "--frame", "x0,tilt"], "x0,y0,angle,scale"),
    (["path", "watt2", "xy.csv", "--free", "b", "--point", "F", "--out", "d.txt"], "must end in .toml"),
    (["path", "watt2", "xy.csv", "--free", "b", "--point", "F", "--record", "r.xml"], ".json or .csv"),
    (["path", "watt2", "xy.csv", "--free", "b"], "--point"),
    (["path", "watt2", "xy.csv", "--free", "b", "--point", "Q"], "no point 'Q'"),
    (["path", "watt2", "xy.csv", "--free", "b", "--point", "F", "--grashof", "crank-rocker"], "does nothing"),
    (["path", "xy.csv", "--free", "b"], "does nothing without a LINKAGE"),
    (["path", "watt2", "xy.csv", "--point", "F"], "--free NAME or --bound"),
    (["path", "watt2", "xy.csv", "--free", "b", "--point", "F", "--branch", "branch_ABCD=2"], "+1 or -1"),
    (["path", "watt2", "xy.csv", "--free", "b", "--point", "F", "--branch", "nope=1"], "branches maps"),
    (["function", "slider-crank", "xy.csv", "--free", "a"], "the header is"),
    (["function", "slider-crank", "fn.csv", "--free", "a", "--output", "B_x"], "B_x"),
    (["function", "slider-crank", "fn.csv", "--free", "a", "--ground", "2"], "does nothing"),
    (["function", "fn.csv", "--output", "s"], "does nothing without a LINKAGE"),
    (["function", "fn.csv", "--minimax"], "does nothing without a LINKAGE"),
    (["motion", "fourbar", "poses.csv", "--free", "b", "--point", "B"], "--angle"),
    (["motion", "fourbar", "poses.csv", "--free", "b", "--angle", "rocker"], "no named point of fourbar starts"),
    (["motion", "fourbar", "poses.csv", "--free", "b", "--point", "B", "--angle", "B_x"], "not an angle"),
    (["motion", "fourbar", "xy.csv", "--free", "b", "--point", "B", "--angle", "beta"], "the header is"),
]


@pytest.mark.parametrize("arguments, message", BAD, ids=[" ".join(a) for a, _ in BAD])
def test_bad_command_line_is_one_line_and_status_2(arguments, message, targets, capsys, monkeypatch):
    monkeypatch.chdir(targets)
    assert main(["synthesize", *arguments]) == 2
    err = capsys.readouterr().err
    errors = [line for line in err.splitlines() if line.startswith("symlink: error:")]
    assert len(errors) == 1 and err.rstrip("\n").endswith(errors[0]) and message in errors[0], err
    assert "Traceback" not in err
    assert sorted(p.name for p in targets.iterdir()) == ["fn.csv", "poses.csv", "xy.csv"]  # nothing written


def test_existing_fourbar_invocations_still_route_to_the_fourbar(targets, capsys, monkeypatch):
    monkeypatch.chdir(targets)
    (targets / "pairs.csv").write_text("theta,phi\n45,135\n75,180\n105,225\n")
    assert main(["synthesize", "function", "pairs.csv", "--ground", "1"]) == 0
    assert "three-point" in capsys.readouterr().err


@pytest.mark.slow  # four syntheses (one a shape match) and a table: about 30 s of CPU
def test_the_how_to_pages_commands_run(tmp_path, monkeypatch, capsys):
    """docs/howto/synthesis.md: its command-line section's Python block writes the files, then every ``$ symlink``
    line runs (exit status 0) and writes what it says."""
    import shlex
    from pathlib import Path

    from readme_text import fenced_blocks
    page = (Path(__file__).resolve().parents[2] / "docs" / "howto" / "synthesis.md").read_text()
    section = page[page.index("## On the command line"):]
    monkeypatch.chdir(tmp_path)
    for block in fenced_blocks(section, "python"):
        exec(compile(block, "synthesis.md", "exec"), {"__name__": "__docs__"})  # our own docs
    commands = [line[2:] for line in section.splitlines() if line.startswith("$ symlink ")]
    assert len(commands) >= 4
    for command in commands:
        arguments = shlex.split(command)[1:]
        assert main(arguments) == 0, (command, capsys.readouterr().err)
        for option in ("--out", "--record", "--plot"):
            if option in arguments:
                assert (tmp_path / arguments[arguments.index(option) + 1]).stat().st_size > 0
    found = json.loads((tmp_path / "found.json").read_text())
    assert found["assembled"] and found["error"] < 1e-10


def test_path_of_a_watt_two_with_the_designers_constraints(tmp_path, capsys):
    # the Watt II problem above, held to a transmission angle of 25 deg at every target, a full turn of the crank and
    # a link ratio of 8: the design still reaches every target (hand formulas), and says what it was held to;
    # 89.9 deg cannot be met by any design: refused in one line, nothing written
    common = watt_path_command(tmp_path)
    record = tmp_path / "path.json"
    status = main([*common, "--min-transmission", "25", "--full-rotation", "--max-link-ratio", "8",
                   "--record", str(record)])
    assert status == 0, capsys.readouterr().err
    found = json.loads(record.read_text())
    assert found["assembled"] and found["constraints"]
    assert "the input turns fully" in found["constraints"] and any("transmission" in c for c in found["constraints"])
    check_watt_path_reached(found)
    capsys.readouterr()
    out = tmp_path / "never.toml"
    assert main([*common, "--min-transmission", "89.9", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "min_transmission" in err and not out.exists()


#: Offsets of each pose from the Watt II's coupler (B and the coupler angle) at the inputs: the errors by hand.
MOTION_OFFSETS = [(0.01, 0.0, 0.5), (-0.02, 0.01, -1.5), (0.0, -0.005, 0.25), (0.015, 0.0, 1.0)]  # dx, dy, degrees


@pytest.mark.parametrize("units", ["deg", "rad"])
def test_motion_reports_position_and_angle_errors_each_in_its_own_unit(tmp_path, capsys, units):
    # The coupler's motion does not depend on the second loop's f (the only free parameter): the design keeps the
    # coupler where the poses were offset from, so the errors are the offsets, computed here by hand.
    inputs = [20.0, 60.0, 100.0, 140.0]
    rows = []
    for q, (dx, dy, turn) in zip(inputs, MOTION_OFFSETS):
        joints = watt2_joints(WATT, math.radians(q))
        B, C = joints["B"], joints["C"]
        angle = math.degrees(cmath.phase(C - B)) + turn
        row = [q, B.real + dx, B.imag + dy, angle] if units == "deg" else \
            [math.radians(q), B.real + dx, B.imag + dy, math.radians(angle)]  # the input in --units too
        rows.append(",".join(map(repr, row)) + "\n")
    (tmp_path / "poses.csv").write_text("theta,x,y,angle\n" + "".join(rows))
    scale = 1.0 if units == "deg" else math.pi / 180
    position = [math.hypot(dx, dy) for dx, dy, _ in MOTION_OFFSETS]
    turned = [-turn * scale for _, _, turn in MOTION_OFFSETS]  # the link's angle minus the pose's
    command = ["synthesize", "motion", "watt2", str(tmp_path / "poses.csv"), "--angle", "coupler", "--frame", "none",
               "--bound", "f=3.5,4.5", "--units", units, "--starts", "2"]
    record = tmp_path / "m.csv"
    assert main([*command, "--format", "json", "--record", str(record)]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert "error" not in printed and printed["assembled"]
    assert abs(printed["position_error"] - max(position)) < 1e-9
    assert abs(printed["angle_error"] - max(map(abs, turned))) < 1e-9 * scale
    assert numpy.allclose(printed["position_errors"], position, rtol=0, atol=1e-9)
    assert numpy.allclose(printed["angle_errors"], turned, rtol=0, atol=1e-9 * scale)
    size = math.hypot(*(max(watt2_joints(WATT, math.radians(q))["B"].real + o[0] for q, o in zip(inputs, MOTION_OFFSETS))
                        - min(watt2_joints(WATT, math.radians(q))["B"].real + o[0] for q, o in zip(inputs, MOTION_OFFSETS)),
                        max(watt2_joints(WATT, math.radians(q))["B"].imag + o[1] for q, o in zip(inputs, MOTION_OFFSETS))
                        - min(watt2_joints(WATT, math.radians(q))["B"].imag + o[1] for q, o in zip(inputs, MOTION_OFFSETS))))
    assert abs(printed["poses_size"] - size) < 1e-12
    lines = list(csv.DictReader(io.StringIO(record.read_text())))  # written as printed: one column each
    assert [float(line["position_error"]) for line in lines] == printed["position_errors"]
    assert [float(line["angle_error"]) for line in lines] == printed["angle_errors"]
    assert "error" not in lines[0]
    # The table and the csv print the same two columns, and the note says which unit each is in.
    assert main([*command, "--format", "csv"]) == 0
    captured = capsys.readouterr()
    table = next(csv.DictReader(io.StringIO(captured.out)))
    assert float(table["position_error"]) == printed["position_error"]
    assert float(table["angle_error"]) == printed["angle_error"]
    assert "error" not in table
    assert f"angle_error, the largest |link angle - pose angle| ({units})" in captured.err
    assert "the fit weighs one radian as the poses' size" in captured.err
