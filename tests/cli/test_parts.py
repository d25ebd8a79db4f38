"""``symlink parts``: the parts list, the files it writes together, and every bad command line refused.

Expected numbers are the design's own dimensions (the seed 003 four-bar: a = 20, b = 66,
c = 56, d = 80 mm) and, for the assembly drawing, the joints placed by hand: A at the origin,
B = a e^{i theta}, D = (d, 0), C = D + c e^{i phi} with phi from the 50-digit four-bar of
tests/references.py.
"""
from __future__ import annotations

import csv
import io
import json
import math
import os
import sys
import xml.etree.ElementTree as ET

import pytest

from symlink.cli import main
from tests.references import mp_fourbar

SVG = "{http://www.w3.org/2000/svg}"
FOURBAR = {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0}
PARTS = ["parts", "fourbar", "--pin-diameter", "4"]


def _rows(text: str) -> list[tuple[str, str, float, str]]:
    return [(row["part"], row["dimension"], float(row["length"]), row["unit"]) for row in csv.DictReader(io.StringIO(text))]


def _holes(svg_path) -> dict[str, list[tuple[float, float]]]:
    """Every hole of an SVG drawing by joint name, y pointing up again."""
    seen: dict[str, list[tuple[float, float]]] = {}
    for circle in ET.parse(svg_path).getroot().iter(f"{SVG}circle"):
        seen.setdefault(circle.get("data-joint"), []).append((float(circle.get("cx")), -float(circle.get("cy"))))
    return seen


def test_the_four_bar_becomes_four_bars_and_every_file_asked_for(tmp_path, capsys):
    files = {option: tmp_path / name for option, name in
             (("svg", "parts.svg"), ("dxf", "parts.dxf"), ("assembly", "assembly.svg"), ("json", "design.json"))}
    argv = PARTS + [arg for option, path in files.items() for arg in (f"--{option}", str(path))]
    assert main(argv + ["--angle", "40", "--format", "csv"]) == 0
    out, err = capsys.readouterr()
    rows = _rows(out)
    assert [(part, dimension, unit) for part, dimension, _, unit in rows] == [
        ("ground", "AD", "mm"), ("crank", "AB", "mm"), ("coupler", "BC", "mm"), ("rocker", "CD", "mm")]
    assert [length for *_, length, _ in rows] == pytest.approx([80.0, 20.0, 66.0, 56.0], abs=1e-12)
    assert sorted(os.listdir(tmp_path)) == sorted(path.name for path in files.values())
    assert all(f"wrote {path}" in err for path in files.values())
    # The assembly at 40 degrees: both links at each joint have their hole where the joint is.
    theta = math.radians(40.0)
    phi = float(mp_fourbar(20, 66, 56, 80, theta, 1)["phi"])
    expected = {"A": (0.0, 0.0), "B": (20 * math.cos(theta), 20 * math.sin(theta)), "D": (80.0, 0.0),
                "C": (80 + 56 * math.cos(phi), 56 * math.sin(phi))}
    holes = _holes(files["assembly"])
    assert {name: len(places) for name, places in holes.items()} == {"A": 2, "B": 2, "C": 2, "D": 2}
    for name, places in holes.items():
        assert all(math.dist(place, expected[name]) < 1e-9 for place in places), name
    # The parts drawing: the holes of each part a bar's length apart.
    groups = {g.get("id"): g for g in ET.parse(files["svg"]).getroot().findall(f"{SVG}g")}
    for part, (first, second), length in (("ground", "AD", 80), ("crank", "AB", 20), ("coupler", "BC", 66),
                                          ("rocker", "CD", 56)):
        centres = {c.get("data-joint"): (float(c.get("cx")), float(c.get("cy")))
                   for c in groups[part].iter(f"{SVG}circle")}
        assert math.dist(centres[first], centres[second]) == pytest.approx(length, abs=1e-9)
    # The design reads back with its dimensions and unit; the DXF reopens with its unit.
    record = json.loads(files["json"].read_text())
    assert record["unit"] == "mm" and record["format"] == "symlink-design"
    ezdxf = pytest.importorskip("ezdxf", reason="pip install symlink-kinematics[fabrication]")
    document = ezdxf.readfile(files["dxf"])
    assert document.header["$INSUNITS"] == 4  # millimetres
    assert len(document.modelspace().query("CIRCLE")) == 8  # two holes a bar


def test_a_design_file_is_read_back_in_its_unit(tmp_path, capsys):
    design = tmp_path / "design.json"
    assert main(["parts", "fourbar", "--pin-diameter", "0.2", "--unit", "in", "--set", "a=1,b=3.3,c=2.8,d=4",
                 "--json", str(design)]) == 0
    capsys.readouterr()
    drawing = tmp_path / "again.svg"
    assert main(["parts", str(design), "--pin-diameter", "0.2", "--svg", str(drawing), "--format", "csv"]) == 0
    rows = _rows(capsys.readouterr().out)
    assert [(part, unit) for part, _, _, unit in rows] == [("ground", "in"), ("crank", "in"), ("coupler", "in"),
                                                           ("rocker", "in")]
    assert [length for _, _, length, _ in rows] == pytest.approx([4.0, 1.0, 3.3, 2.8], abs=1e-12)
    root = ET.parse(drawing).getroot()
    assert root.get("data-unit") == "in"
    # Its real size: the viewBox (in inches) is the width (in mm) over 25.4.
    view_width = float(root.get("viewBox").split()[2])
    assert float(root.get("width").removesuffix("mm")) == pytest.approx(view_width * 25.4, rel=1e-5)


def test_slider_and_ternary_links_are_listed_with_their_slot_and_their_three_sides(capsys):
    """Slider-crank (a = 1.3, b = 4.1, offset e = 0.7): the ground's slot spans the travel
    sqrt((a + b)^2 - e^2) - sqrt((b - a)^2 - e^2); Watt II's rocker CDE: c, e and the law of cosines."""
    assert main(["parts", "slider-crank", "--pin-diameter", "0.2", "--format", "csv"]) == 0
    rows = {(part, dimension): length for part, dimension, length, _ in _rows(capsys.readouterr().out)}
    travel = math.sqrt(5.4 ** 2 - 0.49) - math.sqrt(2.8 ** 2 - 0.49)
    assert rows[("ground", "slot")] == pytest.approx(travel, rel=1e-6)
    assert rows[("crank", "AB")] == pytest.approx(1.3, abs=1e-12) and rows[("conrod", "BC")] == pytest.approx(4.1)
    assert ("slider", "block") in rows
    assert main(["parts", "watt2", "--pin-diameter", "0.2", "--format", "csv"]) == 0
    rows = {(part, dimension): length for part, dimension, length, _ in _rows(capsys.readouterr().out)}
    c, e, alpha = 3.0, 2.0, 0.6
    assert rows[("rocker", "CD")] == pytest.approx(c) and rows[("rocker", "DE")] == pytest.approx(e)
    assert rows[("rocker", "CE")] == pytest.approx(math.sqrt(c * c + e * e - 2 * c * e * math.cos(alpha)))


def test_without_an_angle_a_linkage_that_does_not_assemble_at_zero_is_drawn_where_it_does(tmp_path, capsys):
    """Crank 40 on a ground of 40: at theta = 0 the crank pin sits on D, and coupler 66 and rocker 56 cannot
    meet there (|66 - 56| > 0).  The drawing moves to the nearest crank angle where the four-bar closes."""
    drawing = tmp_path / "assembly.svg"
    assert main(PARTS + ["--set", "a=40,d=40", "--assembly", str(drawing)]) == 0
    err = capsys.readouterr().err
    assert "cannot be assembled at theta = 0 deg" in err and "assembly drawn" in err
    holes = _holes(drawing)
    b, c = holes["B"][0], holes["C"][0]
    assert math.dist(holes["A"][0], (0, 0)) < 1e-9 and math.dist(holes["D"][0], (40, 0)) < 1e-9
    assert math.dist(b, (0, 0)) == pytest.approx(40) and math.dist(b, c) == pytest.approx(66)
    assert math.dist(c, (40, 0)) == pytest.approx(56)


BAD = [
    ("no pin diameter", ["parts", "fourbar"], 2),
    ("pin diameter zero", PARTS[:-1] + ["0"], 2),
    ("pin diameter negative", PARTS[:-1] + ["-4"], 2),
    ("pin diameter nan", PARTS[:-1] + ["nan"], 2),
    ("pin diameter text", PARTS[:-1] + ["four"], 2),
    ("width below the pin", PARTS + ["--width", "3"], 2),
    ("width negative", PARTS + ["--width", "-8"], 2),
    ("unknown unit", PARTS + ["--unit", "furlong"], 2),
    ("svg of the wrong kind", PARTS + ["--svg", "{tmp}/parts.png"], 2),
    ("dxf of the wrong kind", PARTS + ["--dxf", "{tmp}/parts.svg"], 2),
    ("json of the wrong kind", PARTS + ["--json", "{tmp}/design.toml"], 2),
    ("one file twice", PARTS + ["--svg", "{tmp}/a.svg", "--assembly", "{tmp}/a.svg"], 2),
    ("an option twice", PARTS + ["--svg", "{tmp}/a.svg", "--svg", "{tmp}/b.svg"], 2),
    ("unknown linkage", ["parts", "sixbar", "--pin-diameter", "4", "--svg", "{tmp}/a.svg"], 2),
    ("unknown --set name", PARTS + ["--set", "z=1", "--svg", "{tmp}/a.svg"], 2),
    ("negative length", PARTS + ["--set", "a=-20", "--svg", "{tmp}/a.svg"], 2),
    ("no assembly at the angle", PARTS + ["--set", "a=30,b=10", "--angle", "180", "--svg", "{tmp}/a.svg",
                                          "--assembly", "{tmp}/b.svg"], 2),
    ("no assembly anywhere", PARTS + ["--set", "a=1,b=1,c=1,d=10", "--svg", "{tmp}/a.svg"], 2),
    ("a huge angle", PARTS + ["--angle", "1e300", "--assembly", "{tmp}/a.svg"], 2),
    ("branch 2", PARTS + ["--branch", "2", "--assembly", "{tmp}/a.svg"], 2),
    ("unknown format", PARTS + ["--format", "xml", "--svg", "{tmp}/a.svg"], 2),
    ("a design that is not JSON", ["parts", "{design:not json}", "--pin-diameter", "4", "--svg", "{tmp}/a.svg"], 2),
    ("a design of another unit", ["parts", "{design:good}", "--pin-diameter", "4", "--unit", "cm",
                                  "--svg", "{tmp}/a.svg"], 2),
    ("a design that is not there", ["parts", "{tmp}/none.json", "--pin-diameter", "4", "--svg", "{tmp}/a.svg"], 2),
    ("a design that is a folder", ["parts", "{folder:json}", "--pin-diameter", "4", "--svg", "{tmp}/a.svg"], 2),
    # Failed writes: exit status 1, and the other files of the set are not written either.
    ("one file into /proc", PARTS + ["--svg", "{tmp}/a.svg", "--json", "/proc/symlink-test.json"], 1),
    ("one file where a folder is", PARTS + ["--json", "{tmp}/d.json", "--svg", "{folder:svg}"], 1),
]

DESIGNS = {"not json": "{ not json"}


def _expand(argv: list[str], tmp_path) -> list[str]:
    from symlink.workshop.fabrication import design_json
    from symlink.mechanism.catalog import fourbar
    expanded = []
    for item in argv:
        if item.startswith("{design:"):
            name = item[len("{design:"):-1]
            path = tmp_path / f"{name.replace(' ', '_')}.json"
            path.write_text(design_json(fourbar(), FOURBAR) if name == "good" else DESIGNS[name])
            item = str(path)
        elif item.startswith("{folder:"):
            folder = tmp_path / f"taken.{item[len('{folder:'):-1]}"
            folder.mkdir()
            item = str(folder)
        expanded.append(item.replace("{tmp}", str(tmp_path)))
    return expanded


def _listing(folder) -> dict[str, bytes | None]:
    return {str(p.relative_to(folder)): p.read_bytes() if p.is_file() else None for p in folder.rglob("*")}


@pytest.mark.parametrize("argv, status", [pytest.param(argv, status, id=what) for what, argv, status in BAD])
def test_a_bad_command_line_is_one_line_and_writes_nothing(argv, status, tmp_path, capsys):
    argv = _expand(argv, tmp_path)
    before = _listing(tmp_path)
    got = main(argv)
    out, err = capsys.readouterr()
    assert "Traceback" not in err, err
    assert got == status, f"exit {got}, stderr: {err}"
    assert err.count("\n") == 1 and err.startswith("symlink: error: "), err
    assert out == ""
    assert _listing(tmp_path) == before, "files left behind or changed"
    assert not os.path.exists("/proc/symlink-test.json")


def test_without_ezdxf_the_dxf_is_refused_and_the_svg_beside_it_is_not_written(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "ezdxf", None)
    old = tmp_path / "parts.svg"
    old.write_text("the old drawing")
    got = main(PARTS + ["--svg", str(old), "--dxf", str(tmp_path / "parts.dxf")])
    err = capsys.readouterr().err
    assert got == 2 and err.count("\n") == 1 and "symlink-kinematics[fabrication]" in err
    assert os.listdir(tmp_path) == ["parts.svg"] and old.read_text() == "the old drawing"


def test_a_set_whose_last_rename_fails_is_taken_back_whole(tmp_path, capsys, monkeypatch):
    """All or none: the files are staged beside their targets and renamed last; a failure among the renames
    puts back the file that was there before, removes the new one, and leaves no staged file behind."""
    old = tmp_path / "a.svg"
    old.write_text("the old drawing")
    design = tmp_path / "sub" / "d.json"
    real = os.replace

    def failing(source, target):
        if str(target) == str(design):
            raise OSError(28, "No space left on device", str(target))
        real(source, target)

    monkeypatch.setattr(os, "replace", failing)
    got = main(PARTS + ["--svg", str(old), "--json", str(design)])
    err = capsys.readouterr().err
    assert got == 1 and "No space left on device" in err and err.count("\n") == 1, err
    left = sorted(str(p.relative_to(tmp_path)) for p in tmp_path.rglob("*") if p.is_file())
    assert left == ["a.svg"] and old.read_text() == "the old drawing"


def test_the_how_to_pictures_are_what_its_command_draws(tmp_path, monkeypatch, capsys):
    """docs/howto/fabrication.md shows fabrication_parts.svg and fabrication_assembly.svg: its console command,
    run again, draws them (numbers to 1e-9: the backends may differ in the last digits)."""
    import re
    import shlex
    from pathlib import Path

    from readme_text import fenced_blocks
    howto = Path(__file__).resolve().parents[2] / "docs" / "howto"
    block, = fenced_blocks((howto / "fabrication.md").read_text(), "console")
    command = block.split("\n$")[0].removeprefix("$ ").split("\nsymlink:")[0].replace("\\\n", " ")
    argv = shlex.split(command)
    assert argv[:2] == ["symlink", "parts"]
    monkeypatch.chdir(tmp_path)
    assert main(argv[1:]) == 0, capsys.readouterr().err
    number = re.compile(r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")
    for drawn, shown in (("parts.svg", "fabrication_parts.svg"), ("assembly.svg", "fabrication_assembly.svg")):
        new, old = (tmp_path / drawn).read_text(), (howto / shown).read_text()
        assert number.sub("#", new) == number.sub("#", old), f"docs/howto/{shown} is not what the command draws"
        assert all(math.isclose(float(a), float(b), abs_tol=1e-9)
                   for a, b in zip(number.findall(new), number.findall(old))), shown
    assert {p.name for p in tmp_path.iterdir()} == {"parts.svg", "parts.dxf", "assembly.svg", "design.json"}
