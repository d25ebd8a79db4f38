"""``symlink synthesize path LINKAGE points.csv --shape``: a curve's shape matched from the command line.

The target is a four-bar's coupler curve drawn by hand (``tests/synthesis/hand_linkages.py``), moved, turned, scaled
and run the other way; the design the command writes to ``--record`` is traced by the same hand formulas at the
inputs it reports, and must reach every target point.  Bad command lines: one error line, exit status 2, nothing
written.
"""
from __future__ import annotations

import cmath
import json
import math

import numpy
import pytest

from symlink.mechanism.catalog import fourbar, with_point
from symlink.cli import main
from symlink.io.linkage_file import write_linkage
from synthesis.hand_linkages import fourbar_joints

TRUTH = {"a": 1.0, "b": 3.0, "c": 2.5, "d": 3.2, "u": 1.5, "v": 0.8}


def coupler_point(values, theta: float, branch: int = 1) -> complex:
    B, C = fourbar_joints(values["a"], values["b"], values["c"], values["d"], theta, branch)
    return B + complex(values["u"], values["v"]) * (C - B) / abs(C - B)


def write_coupler_point_fourbar(path) -> None:
    """The catalog four-bar with a point P = B + u along the coupler + v to its left, as a linkage file."""
    base = fourbar()
    linkage = with_point(base, "B", base.roles["coupler"])
    write_linkage(linkage, path, {**TRUTH, "b": 2.8, "u": 1.0, "v": 0.0})


@pytest.fixture
def folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write_coupler_point_fourbar(tmp_path / "fp.toml")
    turn = 0.7 - numpy.linspace(0.0, 2 * math.pi, 48, endpoint=False)  # the other way round, from elsewhere
    shift, scale, angle = complex(40.0, -12.0), 8.0, 2.5
    points = [shift + scale * cmath.exp(1j * angle) * coupler_point(TRUTH, q) for q in turn]
    (tmp_path / "shape.csv").write_text("x,y\n" + "".join(f"{p.real!r},{p.imag!r}\n" for p in points))
    (tmp_path / "timed.csv").write_text("theta,x,y\n0,0,0\n10,1,0.5\n20,2,0.7\n")
    (tmp_path / "two.csv").write_text("x,y\n0,0\n1,0.5\n")
    return tmp_path


def test_a_closed_shape_is_matched_and_refined(folder, capsys):
    status = main(["synthesize", "path", "fp.toml", "shape.csv", "--shape", "--point", "P", "--bound", "b=2.5,3.6",
                   "--bound", "u=0.5,2.5", "--bound", "v=-1.2,1.2", "--samples", "600", "--out", "found.toml",
                   "--record", "found.json", "--plot", "found.png"])
    err = capsys.readouterr().err
    assert status == 0, err
    assert "closed shape matched" in err
    found = json.loads((folder / "found.json").read_text())
    assert found["assembled"] and found["shape"] == "closed" and found["error"] < 1e-10
    assert found["shape_distance"] < found["sampled_distance"]
    where = found["placement"]
    # the design's lengths are recorded as written, scaled (issue 32): the placement's scale is in them
    turn = complex(where["x0"], where["y0"]), cmath.exp(1j * math.radians(where["angle"]))
    targets = [complex(x, y) for x, y in found["targets"]]
    size = math.hypot(*numpy.ptp([[z.real, z.imag] for z in targets], axis=0))
    for q, target in zip(found["inputs"], targets):
        reached = turn[0] + turn[1] * coupler_point(found["design"], math.radians(q), found["branches"]["branch"])
        assert abs(reached - target) < 1e-8 * size
    assert (folder / "found.png").stat().st_size > 0
    assert (folder / "found.toml").read_text().startswith("# Designed by 'symlink synthesize path fp.toml'")


BAD = [
    (["fp.toml", "shape.csv", "--free", "b", "--point", "P", "--open"], "--open belongs to a shape match: add --shape"),
    (["fp.toml", "shape.csv", "--free", "b", "--point", "P", "--samples", "50"], "--samples belongs to a shape match"),
    (["shape.csv", "--shape"], "does nothing without a LINKAGE"),
    (["shape.csv", "--partial"], "does nothing without a LINKAGE"),
    (["fp.toml", "timed.csv", "--shape", "--free", "b", "--point", "P"], "without timing"),
    (["fp.toml", "shape.csv", "--shape", "--free", "b", "--point", "P", "--frame", "x0,y0"],
     "--frame does nothing with --shape"),
    (["fp.toml", "shape.csv", "--shape", "--free", "b", "--point", "P", "--min-transmission", "30"],
     "--min-transmission does nothing with --shape"),
    (["fp.toml", "shape.csv", "--shape", "--free", "b", "--point", "P", "--full-rotation"],
     "--full-rotation does nothing with --shape"),
    (["fp.toml", "shape.csv", "--shape", "--open", "--closed", "--free", "b", "--point", "P"], "not allowed with"),
    (["fp.toml", "shape.csv", "--shape", "--free", "b", "--point", "P", "--samples", "many"], "--samples"),
    (["fp.toml", "shape.csv", "--shape", "--free", "b"], "--point"),
    (["fp.toml", "two.csv", "--shape", "--free", "b", "--point", "P"], "at least 3 rows"),
    (["stephenson2", "shape.csv", "--shape", "--free", "b", "--point", "E"], "no closed form"),
    (["fp.toml", "shape.csv", "--shape", "--bound", "b=10,11", "--point", "P", "--samples", "20"],
     "no design of fourbar_point within the bounds"),
]


@pytest.mark.parametrize("arguments, message", BAD, ids=[" ".join(a) for a, _ in BAD])
def test_bad_command_line_is_one_line_and_status_2(arguments, message, folder, capsys):
    before = sorted(p.name for p in folder.iterdir())
    assert main(["synthesize", "path", *arguments, "--out", "x.toml", "--record", "x.json"]) == 2
    err = capsys.readouterr().err
    errors = [line for line in err.splitlines() if line.startswith("symlink: error:")]
    assert len(errors) == 1 and err.rstrip("\n").endswith(errors[0]) and message in errors[0], err
    assert "Traceback" not in err
    assert sorted(p.name for p in folder.iterdir()) == before  # nothing written
