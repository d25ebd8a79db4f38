"""``symlink synthesize path stephenson2 points.csv``: a linkage without a closed form from the command line.

Targets are the true Stephenson II's coupler point from the 30-digit mpmath reference of
``tests/synthesis/test_general_newton.py``; the design the command records is checked with the same reference,
continued from the assembly it records.
"""
from __future__ import annotations

import json
import math

import numpy
import pytest

from symlink.cli import main
from synthesis.test_general_newton import ASSEMBLY, TRUTH, UNKNOWNS, coupler_points


@pytest.mark.slow
def test_path_of_the_stephenson2_from_the_command_line(tmp_path, capsys):
    inputs = numpy.linspace(0.3, 1.5, 7)
    targets = coupler_points(TRUTH, inputs, ASSEMBLY)
    points = tmp_path / "points.csv"
    points.write_text("theta,x,y\n" + "".join(f"{math.degrees(q)!r},{x!r},{y!r}\n"
                                               for q, (x, y) in zip(inputs, targets.tolist())))
    record, out = tmp_path / "design.json", tmp_path / "design.toml"
    assert main(["synthesize", "path", "stephenson2", str(points), "--set", "b=3.4,e=3.7,g=4.3", "--free", "b,e,g",
                 "--frame", "none", "--point", "E", "--record", str(record), "--out", str(out)]) == 0
    found = json.loads(record.read_text())
    assert found["assembled"] and found["error"] < 1e-8 and found["branches"] == {}
    design = {name: math.radians(v) if name in ("alpha", "delta") else v for name, v in found["design"].items()}
    assembly = {name: math.radians(found["assembly"][name]) for name in UNKNOWNS}
    reached = coupler_points(design, [math.radians(q) for q in found["inputs"]], assembly)
    size = float(numpy.hypot(*numpy.ptp(targets, axis=0)))
    assert numpy.max(numpy.hypot(*(reached - targets).T)) < 1e-8 * size
    assert "# Assembly at the first target" in out.read_text()


def test_a_bad_point_is_one_line_and_status_2(tmp_path, capsys):
    points = tmp_path / "points.csv"
    points.write_text("x,y\n0,4\n0.3,4.4\n0.4,4.6\n")
    assert main(["synthesize", "path", "stephenson2", str(points), "--free", "b", "--point", "Q"]) == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and "no point 'Q'" in error[0] and "Traceback" not in error[0]
