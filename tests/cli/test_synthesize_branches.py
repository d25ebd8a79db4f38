"""``symlink synthesize ... --out``: the written linkage file reproduces the found assembly with the default branch +1.

A four-bar path whose targets lie on branch -1 (hand formulas, ``tests/synthesis/hand_linkages.py``) is synthesised
with ``--branch branch=-1``; ``symlink table`` of the written file, at branch +1 (every command's default), prints the
found design's rocker and coupler angles on branch -1, computed by the hand formulas.
"""
from __future__ import annotations

import cmath
import csv
import io
import json
import math

import numpy

from symlink.mechanism.catalog import fourbar, slider_crank
from symlink.cli import main
from symlink.synthesis.placement import with_default_branches
from synthesis.hand_linkages import fourbar_joints, wrapped


def test_the_written_file_holds_a_found_minus_one_branch_as_plus_one(tmp_path, capsys):
    truth = dict(a=22.0, b=60.0, c=60.0, d=80.0)
    inputs = [float(q) for q in numpy.linspace(10.0, 130.0, 6)]  # degrees
    rows = []
    for q in inputs:
        _, C = fourbar_joints(truth["a"], truth["b"], truth["c"], truth["d"], math.radians(q), -1)
        rows.append(f"{q!r},{C.real!r},{C.imag!r}\n")
    (tmp_path / "t.csv").write_text("theta,x,y\n" + "".join(rows))
    out, record = tmp_path / "found.toml", tmp_path / "found.json"
    status = main(["synthesize", "path", "fourbar", str(tmp_path / "t.csv"), "--point", "C", "--set", "a=22,d=80",
                   "--bound", "b=50,70", "--bound", "c=50,70", "--branch", "branch=-1", "--frame", "none",
                   "--out", str(out), "--record", str(record)])
    assert status == 0, capsys.readouterr().err
    found = json.loads(record.read_text())
    assert found["assembled"] and found["branches"] == {"branch": -1}
    design = found["design"]
    assert "the default branch signs (+1) give the found assembly" in out.read_text().splitlines()[0]
    for q in (inputs[0], inputs[3]):
        capsys.readouterr()
        assert main(["table", str(out), "--angles", f"{q!r}", "--branch", "+1", "--format", "csv"]) == 0
        (row,) = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
        B, C = fourbar_joints(design["a"], design["b"], design["c"], design["d"], math.radians(q), -1)
        rocker, coupler = cmath.phase(C - design["d"]), cmath.phase(C - B)
        assert abs(wrapped(math.radians(float(row["rocker"])) - rocker)) < 1e-9
        assert abs(wrapped(math.radians(float(row["coupler"])) - coupler)) < 1e-9


def test_with_default_branches_reorders_two_angle_loops_only():
    turned, left = with_default_branches(fourbar(), {"branch": 1})
    assert turned.unknowns == fourbar().unknowns and left == {}
    _, left = with_default_branches(slider_crank(), {"branch": -1})  # a slider's loop (case 2b) keeps its sign
    assert left == {"branch": -1}
