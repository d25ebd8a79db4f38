"""Tables print as a textbook (issue 32, item 4): integers as integers, never -0.0000, units in the headers;
``derive`` is ``export``; pylinkage JSON written keeps the driver's speed."""
from __future__ import annotations

import io
import json

import pytest

from symlink.cli import main
from symlink.cli.output import print_rows
from symlink.io.pylinkage import read_pylinkage, write_pylinkage


def table(capsys, *arguments) -> list[str]:
    assert main(list(arguments)) == 0
    return capsys.readouterr().out.splitlines()


@pytest.mark.parametrize("value, shown", [(3, "3"), (-0.00004, "0.0000"), (-0.0, "0.0000"), (-0.00005, "-0.0001"),
                                          (12.34567, "12.3457"), (-2.5, "-2.5000")])
def test_a_cell_as_a_textbook_prints_it(value, shown):
    out = io.StringIO()
    print_rows([{"rank": 1, "x": value}], ["rank", "x"], "table", out, units={"x": "deg"})
    header, row = out.getvalue().splitlines()
    assert header.split() == ["rank", "x", "(deg)"]
    assert row.split() == ["1", shown]


def test_csv_keeps_its_exact_header_and_no_negative_zero():
    out = io.StringIO()
    print_rows([{"rank": 2, "x": -0.0}], ["rank", "x"], "csv", out, units={"x": "deg"})
    assert out.getvalue() == "rank,x\n2,0.0\n"


def test_the_seed_table_has_units_in_its_header_and_no_negative_zero(capsys):
    lines = table(capsys, "fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
                  "--step", "30", "--crank-speed", "0")
    assert lines[0].split()[:5] == ["crank", "(deg)", "branch", "coupler", "(deg)"]
    assert "coupler_speed (rad/s)" in lines[0] and "rocker_accel (rad/s^2)" in lines[0]
    assert "transmission (deg)" in lines[0]
    assert not any("-0.0000" in line for line in lines)
    radians = table(capsys, "fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
                    "--angles", "0", "--units", "rad")
    assert radians[0].split()[:2] == ["crank", "(rad)"]


def test_any_linkage_s_table_shows_the_units_it_knows(capsys):
    lines = table(capsys, "table", "slider-crank", "--step", "45")
    header = lines[0]
    assert "crank (deg)" in header and "conrod_speed (rad/s)" in header
    assert " slider " in f" {header} "  # a length: its unit is the user's
    assert not any("-0.0000" in line for line in lines)


def test_derive_is_export(tmp_path, capsys):
    table(capsys, "export", "slider-crank", "--to", "numpy", "--out", str(tmp_path / "export"))
    table(capsys, "derive", "slider-crank", "--to", "numpy", "--out", str(tmp_path / "derive"))
    exported = sorted(p.name for p in (tmp_path / "export").iterdir())
    assert exported == sorted(p.name for p in (tmp_path / "derive").iterdir()) and exported
    for name in exported:
        assert (tmp_path / "export" / name).read_text() == (tmp_path / "derive" / name).read_text()
    assert main(["derive", "--help"]) == 0
    assert "usage: symlink export" in capsys.readouterr().out


FOURBAR_JSON = {"joints": [
    {"id": "O1", "type": "ground", "position": [0, 0]}, {"id": "O2", "type": "ground", "position": [100, 0]},
    {"id": "B", "type": "revolute", "position": [0, 25]}, {"id": "C", "type": "revolute", "position": [60, 50]}],
    "links": [{"id": "ground", "type": "ground", "joints": ["O1", "O2"]},
              {"id": "crank", "type": "driver", "joints": ["O1", "B"], "motor_joint": "O1",
               "angular_velocity": 0.07},
              {"id": "coupler", "type": "link", "joints": ["B", "C"]},
              {"id": "rocker", "type": "link", "joints": ["C", "O2"]}], "ground": "ground"}


def test_pylinkage_json_written_keeps_the_driver_s_speed():
    written = json.loads(json.dumps(write_pylinkage(read_pylinkage(FOURBAR_JSON).build())))
    (driver,) = [link for link in written["links"] if link["type"] == "driver"]
    assert driver["angular_velocity"] == 0.07
    still = {**FOURBAR_JSON, "links": [{k: v for k, v in link.items() if k != "angular_velocity"}
                                       for link in FOURBAR_JSON["links"]]}
    (driver,) = [link for link in write_pylinkage(read_pylinkage(still).build())["links"] if link["type"] == "driver"]
    assert "angular_velocity" not in driver  # none read: pylinkage's default, not a number made up


def test_a_legacy_crank_s_step_angle_is_its_speed():
    legacy = {"name": "old", "joints": [
        {"type": "Static", "name": "O", "x": 0, "y": 0}, {"type": "Static", "name": "D", "x": 3, "y": 0},
        {"type": "Crank", "name": "B", "x": 0, "y": 1, "distance": 1, "angle": 0.31, "joint0": {"ref": "O"}},
        {"type": "Revolute", "name": "C", "x": 3, "y": 2, "distance0": 3.1622776601683795, "distance1": 2,
         "joint0": {"ref": "B"}, "joint1": {"ref": "D"}}]}
    (driver,) = [link for link in write_pylinkage(read_pylinkage(legacy).build())["links"] if link["type"] == "driver"]
    assert driver["angular_velocity"] == 0.31


def test_a_speed_that_is_not_a_number_is_refused():
    bad = json.loads(json.dumps(FOURBAR_JSON))
    bad["links"][1]["angular_velocity"] = "fast"
    with pytest.raises(ValueError, match="angular_velocity: a driver's speed must be a finite number"):
        read_pylinkage(bad)
