"""``symlink synthesize function|path|motion``: designs from csv targets, checked independently; bad input is one line, exit 2."""
from __future__ import annotations

import csv
import io
import json
import math

import numpy as np
import pytest

from symlink.cli import main
from symlink.synthesis.path import fourbar_design

TRUE = fourbar_design((0.2, 0.1), 0.4, (0.5, 2.0, 1.8, 2.2), (1.0, 0.6), branch=1)
THETA = np.sort(np.random.default_rng(1).uniform(0, 2 * np.pi, 8))


def _hand_point(x0, y0, frame, a, b, c, d, u, v, branch, theta):
    """Coupler point by circle intersection (plain floats), independent of symlink's code."""
    B = a * complex(math.cos(theta), math.sin(theta))
    w = abs(d - B)
    along = (b * b - c * c + w * w) / (2 * w)
    unit = (d - B) / w
    C = B + along * unit + branch * math.sqrt(b * b - along * along) * 1j * unit
    beta = math.atan2((C - B).imag, (C - B).real)
    local = B + complex(u, v) * complex(math.cos(beta), math.sin(beta))
    return complex(x0, y0) + complex(math.cos(frame), math.sin(frame)) * local


def assert_one_error_line(err, message):
    """One ``symlink: error:`` line, the last on stderr, naming the problem (warnings of other code may precede it)."""
    errors = [line for line in err.splitlines() if line.startswith("symlink: error:")]
    assert len(errors) == 1 and err.rstrip("\n").endswith(errors[0]) and message in errors[0], err


@pytest.fixture
def timed_csv(tmp_path):
    path = tmp_path / "timed.csv"
    points = TRUE.points(THETA)
    path.write_text("theta,x,y\n" + "".join(f"{math.degrees(t)!r},{x!r},{y!r}\n" for t, (x, y) in
                                            zip(THETA.tolist(), points.tolist())))
    return path


def test_timed_path_as_json_reaches_every_point(timed_csv, capsys, tmp_path):
    picture = tmp_path / "path.png"
    assert main(["synthesize", "path", str(timed_csv), "--format", "json", "--designs", "2",
                 "--plot", str(picture)]) == 0
    designs = json.loads(capsys.readouterr().out)
    assert 1 <= len(designs) <= 2
    best = designs[0]
    targets = TRUE.points(THETA)
    for theta, target in zip(best["theta"], targets):
        point = _hand_point(best["x0"], best["y0"], math.radians(best["frame"]), best["crank"], best["coupler"],
                            best["rocker"], best["ground"], best["u"], best["v"], best["branch"], math.radians(theta))
        assert abs(point - complex(*target)) < 1e-8
    assert picture.read_bytes().startswith(b"\x89PNG")


def test_untimed_path_as_csv(tmp_path, capsys):
    path = tmp_path / "points.csv"
    points = TRUE.points(THETA[:6])
    path.write_text("x,y\n" + "".join(f"{x!r},{y!r}\n" for x, y in points.tolist()))
    assert main(["synthesize", "path", str(path), "--format", "csv", "--designs", "1", "--seed", "5"]) == 0
    captured = capsys.readouterr()
    rows = list(csv.DictReader(io.StringIO(captured.out)))
    assert len(rows) == 1 and float(rows[0]["error"]) < 1e-8
    assert "crank angles at the points" in captured.err


def test_function_three_points_and_table(tmp_path, capsys):
    path = tmp_path / "pairs.csv"
    pairs = [(48.0, 141.0), (75.0, 180.0), (102.0, 218.0)]
    path.write_text("theta,phi\n" + "".join(f"{t},{p}\n" for t, p in pairs))
    assert main(["synthesize", "function", str(path), "--format", "json"]) == 0
    design = json.loads(capsys.readouterr().out)[0]
    # Freudenstein by hand with the printed K's: K1 cos(phi) - K2 cos(theta) + K3 = cos(theta - phi) at each pair,
    # and the printed lengths are d/K1, d/K2 (in size) and b^2 = a^2 + c^2 + d^2 - 2 a c K3 with signed a, c.
    k1, k2, k3 = design["K1"], design["K2"], design["K3"]
    for t, p in pairs:
        t, p = math.radians(t), math.radians(p)
        assert k1 * math.cos(p) - k2 * math.cos(t) + k3 == pytest.approx(math.cos(t - p), abs=1e-12)
    a, c = 1 / k1, 1 / k2
    assert design["crank"] == pytest.approx(abs(a)) and design["rocker"] == pytest.approx(abs(c))
    assert design["coupler"] == pytest.approx(math.sqrt(a * a + c * c + 1 - 2 * a * c * k3))
    assert design["rocker_offset"] == pytest.approx(180.0 if c < 0 else 0.0)
    assert main(["synthesize", "function", str(path)]) == 0
    assert "structural_error" in capsys.readouterr().out


BAD_FILES = [
    ("no header", "", "no header"),
    ("wrong header", "a,b\n1,2\n", "header"),
    ("text value", "x,y\n1,2\n3,four\n", ":3: y: not a number"),
    ("short row", "x,y\n1,2\n3\n", ":3: 1 values"),
    ("nan", "x,y\n1,2\nnan,3\n", "finite"),
    ("too few points", "x,y\n1,2\n3,4\n5,6\n", "at least 4"),
    ("one point", "theta,x,y\n0,1,1\n10,1,1\n20,1,1\n", "same point"),
]


@pytest.mark.parametrize("name,text,message", BAD_FILES, ids=[b[0] for b in BAD_FILES])
def test_bad_path_files(name, text, message, tmp_path, capsys):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    assert main(["synthesize", "path", str(path)]) == 2
    assert_one_error_line(capsys.readouterr().err, message)


BAD_FUNCTION = [
    ("two pairs", "theta,phi\n1,2\n3,4\n", "at least 3"),
    ("path header", "x,y\n1,2\n3,4\n5,6\n", "header"),
    ("repeated", "theta,phi\n10,20\n10,20\n10,20\n", "same target"),
]


@pytest.mark.parametrize("name,text,message", BAD_FUNCTION, ids=[b[0] for b in BAD_FUNCTION])
def test_bad_function_files(name, text, message, tmp_path, capsys):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    assert main(["synthesize", "function", str(path)]) == 2
    assert_one_error_line(capsys.readouterr().err, message)


@pytest.mark.parametrize("arguments,message", [
    (["synthesize"], "required"),
    (["synthesize", "motion-x", "f.csv"], "invalid choice"),
    (["synthesize", "motion", "f.csv", "--moving-pivot", "1"], "X,Y"),
    (["synthesize", "motion", "f.csv", "--rotation", "ten"], "not a number"),
    (["synthesize", "path", "f.csv", "--grashof", "crank"], "invalid choice"),
    (["synthesize", "path", "f.csv", "--plot", "x.pdf"], ".png or .svg"),
    (["synthesize", "path", "f.csv", "--max-link-ratio", "x"], "not a number"),
])
def test_bad_command_lines(arguments, message, capsys):
    assert main(arguments) == 2
    assert_one_error_line(capsys.readouterr().err, message)


def test_missing_file_is_bad_input_with_the_path_and_the_reason(tmp_path, capsys):
    """An input file that is not there is the user's mistake (exit 2, as for linkage and scene files)."""
    assert main(["synthesize", "path", str(tmp_path / "none.csv")]) == 2
    assert capsys.readouterr().err == (f"symlink: error: cannot read csv of targets {tmp_path / 'none.csv'}: "
                                       "No such file or directory\n")


# --- motion generation ------------------------------------------------------------------------

def _hand_poses(a, b, c, d, thetas, branch=1):
    """Coupler poses (B, angle of B->C) of the four-bar A=(0,0), D=(d,0), by circle intersection (plain floats)."""
    poses = []
    for theta in thetas:
        B = a * complex(math.cos(theta), math.sin(theta))
        w = abs(d - B)
        along = (b * b - c * c + w * w) / (2 * w)
        unit = (d - B) / w
        C = B + along * unit + branch * math.sqrt(b * b - along * along) * 1j * unit
        poses.append((B.real, B.imag, math.atan2((C - B).imag, (C - B).real)))
    return poses


def _poses_csv(path, poses, degrees=True):
    rows = [f"{x!r},{y!r},{(math.degrees(g) if degrees else g)!r}" for x, y, g in poses]
    path.write_text("x,y,angle\n" + "\n".join(rows) + "\n")
    return path


@pytest.mark.parametrize("units", ["deg", "rad"])
def test_five_poses_give_back_the_four_bar_they_came_from(units, tmp_path, capsys):
    poses = _hand_poses(1.0, 3.0, 2.5, 3.2, [0.2, 0.7, 1.3, 2.0, 2.6])
    path = _poses_csv(tmp_path / "poses.csv", poses, degrees=units == "deg")
    assert main(["synthesize", "motion", str(path), "--format", "csv", "--units", units,
                 "--plot", str(tmp_path / "motion.png")]) == 0
    out, err = capsys.readouterr()
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [row["rank"] for row in rows] == [str(k) for k in range(1, len(rows) + 1)]
    pivots = lambda row: {(round(float(row[f"{p}_pivot_x"]), 9), round(float(row[f"{p}_pivot_y"]), 9))
                          for p in ("crank", "rocker")}  # noqa: E731
    original = [row for row in rows if pivots(row) == {(0.0, 0.0), (3.2, 0.0)} and float(row["crank"]) < 1.5]
    assert original, out
    row = original[0]
    assert [float(row[k]) for k in ("crank", "coupler", "rocker", "ground")] == pytest.approx([1.0, 3.0, 2.5, 3.2],
                                                                                             rel=1e-9)
    assert row["grashof"] == "crank-rocker" and row["branch_defect"] == "false" and row["order_defect"] == "false"
    turn = 1.0 if units == "rad" else math.degrees(1.0)  # crank angles in the command's units
    assert [float(row[f"crank_angle_{k}"]) / turn for k in range(1, 6)] == pytest.approx([0.2, 0.7, 1.3, 2.0, 2.6],
                                                                                         abs=1e-9)
    assert (tmp_path / "motion.png").stat().st_size > 0 and err.rstrip().endswith("motion.png")


def test_three_poses_with_two_moving_pivots_put_each_on_a_circle(tmp_path, capsys):
    poses = [(0.0, 0.0, 0.0), (1.0, 0.3, math.radians(20)), (1.8, 1.0, math.radians(45))]
    path = _poses_csv(tmp_path / "poses.csv", poses)
    assert main(["synthesize", "motion", str(path), "--moving-pivot", "0.5,0.2", "--moving-pivot", "1.5,-0.1",
                 "--format", "json"]) == 0
    designs = json.loads(capsys.readouterr().out)
    assert designs
    for design in designs:  # each moving pivot's three positions are equally far from its fixed pivot
        for which, local in (("crank", (0.5, 0.2)), ("rocker", (1.5, -0.1))):
            centre = complex(design[f"{which}_pivot_x"], design[f"{which}_pivot_y"])
            if abs(complex(design[f"{which}_moving_x"], design[f"{which}_moving_y"]) - complex(*local)) > 1e-9:
                continue  # this design uses the pivots the other way round
            radii = [abs(complex(x, y) + complex(*local) * complex(math.cos(g), math.sin(g)) - centre)
                     for x, y, g in poses]
            assert radii == pytest.approx([radii[0]] * 3, rel=1e-9)


BAD_MOTION = [
    ("six poses", "x,y,angle\n" + "".join(f"{k},{k % 2},{10 * k}\n" for k in range(6)), [], "2 to 5 poses"),
    ("path header", "x,y\n1,2\n3,4\n", [], "header"),
    ("four poses, no rotation", "x,y,angle\n0,0,0\n1,0,10\n2,1,20\n3,1,30\n", [], "rotations"),
    ("one moving pivot", "x,y,angle\n0,0,0\n1,0,10\n2,1,20\n", ["--moving-pivot", "1,1"], "two moving pivots"),
    ("no designs asked", "x,y,angle\n0,0,0\n1,0,10\n2,1,20\n", ["--designs", "0"], "--designs"),
]


@pytest.mark.parametrize("name,text,options,message", BAD_MOTION, ids=[b[0] for b in BAD_MOTION])
def test_bad_motion_files(name, text, options, message, tmp_path, capsys):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    assert main(["synthesize", "motion", str(path), *options]) == 2
    assert_one_error_line(capsys.readouterr().err, message)
