"""Hard edges of the command line: negative numbers as values, requests refused rather than bent, work and memory
estimated before a command starts.  Each bad command line is one line of error and exit status 2."""
from __future__ import annotations

import math

import numpy as np
import pytest

from symlink.cli import main
from symlink.numeric.input_sweep import crank_speeds

FOURBAR = ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80"]


def _one_error_line(err: str, *words: str) -> None:
    assert err.count("\n") == 1 and err.startswith("symlink: error: ") and "Traceback" not in err, err
    for word in words:
        assert word in err, err


# --- a crank turning clockwise and speeding up -------------------------------------------------------------------

def test_a_clockwise_crank_speeding_up_reaches_each_angle_turning_clockwise():
    """From 0 at -10.5 rad/s, -25 rad/s^2: 350 deg is reached after turning -10 deg (hand: w^2 = w0^2 + 2 al turned)."""
    angles = np.radians([0.0, 350.0, 180.0, 10.0])
    turned = np.radians([0.0, -10.0, -180.0, -350.0])
    expected = -np.sqrt(10.5 ** 2 + 2 * -25.0 * turned)
    assert crank_speeds(angles, -10.5, -25.0) == pytest.approx(expected, rel=1e-15)


def test_a_counter_clockwise_crank_is_as_before():
    angles = np.radians([0.0, 40.0, 80.0])
    assert crank_speeds(angles, 10.5, 25.0) == pytest.approx(np.sqrt(10.5 ** 2 + 50.0 * angles), rel=1e-15)


def test_a_clockwise_crank_slowing_down_still_stops():
    with pytest.raises(ValueError, match="the crank stops"):
        crank_speeds(np.radians(np.arange(0.0, 360.0, 10.0)), -1.0, 25.0)


def test_the_clockwise_table_is_printed(capsys):
    assert main([*FOURBAR, "--crank-speed", "-10.5", "--crank-accel", "-25", "--format", "csv"]) == 0
    rows = capsys.readouterr().out.strip().splitlines()
    assert len(rows) == 1 + 36 * 2


# --- requests refused rather than bent, and work estimated before it starts: one line, exit 2 ---------------------

FLYWHEEL = ["flywheel", "--crank", "0.2", "--coupler", "0.66", "--rocker", "0.56", "--ground", "0.8", "--rpm", "300",
            "--coefficient", "0.05"]
SWEEP = ["--scheduler", "synchronous", "--no-progress"]

REFUSED = [
    # (what, command line ({tmp} is a fresh folder), words of the one error line)
    ("an option twice", [*FOURBAR, "--crank", "30"], "argument --crank: given twice"),
    ("--set twice", ["analyze", "jansen", "--set", "a=1", "--set", "a=2"], "argument --set: given twice"),
    ("a name twice in --set", ["analyze", "jansen", "--set", "a=1,a=2"], "'a' is given twice"),
    ("--vary twice", ["sweep", "fourbar", "{tmp}/s", "--vary", "c=1:2", "--vary", "c=3:4", *SWEEP],
     "argument --vary: given twice"),
    ("a name twice in --vary", ["sweep", "fourbar", "{tmp}/s", "--vary", "c=1:2,c=3:4", *SWEEP], "'c' is given twice"),
    ("--vary and --set of one name", ["sweep", "fourbar", "{tmp}/s", "--vary", "c=1:2", "--set", "c=3", *SWEEP],
     "--vary and --set both give c"),
    ("sweep of a two-input linkage", ["sweep", "fivebar", "{tmp}/s", "--vary", "a=1:2", *SWEEP],
     "fivebar has 2 inputs (theta, psi) and a sweep turns the first only"),
    ("analyze of a two-input linkage", ["analyze", "fivebar"], "fivebar has 2 inputs (theta, psi) and analyze"),
    ("--guess on a closed form", ["table", "fourbar", "--guess", "beta=10", "--angles", "0"],
     "--guess: fourbar is solved in closed form"),
    ("draw at an angle of 1e300", ["draw", "fourbar", "--angle", "1e300", "--out", "{tmp}/d.png"],
     "the angle 1e300 is more than 1e+09 in size"),
    ("analyze lengths near 1e300", ["analyze", "--crank", "1e300", "--coupler", "66", "--rocker", "56",
                                    "--ground", "80"], "1e300 is out of range"),
    ("a length that underflows", [*FOURBAR[:-1], "1e-300"], "1e-300 is out of range"),
    ("flywheel --rpm 1e-300", [*FLYWHEEL[:-4], "--rpm", "1e-300", "--coefficient", "0.05", "--masses", "1,2,1.5"],
     "1e-300 is out of range"),
    ("flywheel of no mass", [*FLYWHEEL, "--masses", "0,0,0"], "--masses 0,0,0 with no --inertias: the four-bar has no mass"),
    ("flywheel of 10^7 samples", [*FLYWHEEL, "--masses", "1,2,1.5", "--samples", "10000000"],
     "a flywheel of --samples 10000000 would need about 15 GB of memory"),
    ("a sweep that would never end", ["sweep", "fourbar", "{tmp}/s", "--vary", "a=1:2,b=1:2,c=1:2", "--grid",
                                      "1000000", *SWEEP], "a sweep of 1e+18 designs of 360 samples would take about"),
    ("a sweep of too many chunks", ["sweep", "fourbar", "{tmp}/s", "--vary", "a=1:2", "--random", "100000000",
                                    "--chunk", "1", "--time-budget", "1d", *SWEEP],
     "a sweep of 100,000,000 chunks would need about 20 GB"),
    ("analyze --output in the four-bar form", ["analyze", *FOURBAR[1:], "--output", "phi"],
     "analyze: --output does nothing in the four-bar form"),
    ("curve --coupler-point with a linkage", ["curve", "jansen", "--coupler-point", "1,2", "--out", "{tmp}/c.png"],
     "curve: --coupler-point does nothing with a linkage NAME|FILE (jansen)"),
    ("animate --trace in the four-bar form", ["animate", *FOURBAR[1:], "--trace", "C", "--out", "{tmp}/a.gif"],
     "animate: --trace does nothing in the four-bar form"),
    ("a sweep of huge chunks", ["sweep", "fourbar", "{tmp}/s", "--vary", "a=1:2,b=1:2", "--grid", "1000", "--chunk",
                                "1000000", *SWEEP], "would need about 35 GB of memory at once"),
    ("a table that repeats an angle", ["table", "fourbar", "--angles", "10,20,10"],
     "argument --angles: 10 appears more than once"),
    ("the four-bar table repeating an angle", [*FOURBAR, "--angles", "0,0"], "0 appears more than once"),
    ("a tolerance of a linkage that never assembles", ["tolerance", "fourbar", "--set", "a=100,b=1,c=1,d=1",
                                                      "--tolerance", "0.1"], "cannot be assembled at any of the input"),
    ("a sweep whose designs never assemble", ["sweep", "fourbar", "{tmp}/s", "--set", "a=100,b=1,c=1", "--vary",
                                              "d=1:1.1", "--grid", "2", *SWEEP],
     "no design of this sweep assembles at any input value (all 2 designs cannot close their loops)"),
    ("export of an output twice", ["export", "fourbar", "--to", "numpy", "--out", "{tmp}/o", "--outputs",
                                   "rocker,coupler,rocker"], "argument --outputs: 'rocker' appears more than once"),
    ("a path traced twice", ["draw", "jansen", "--trace", "H,H", "--out", "{tmp}/d.png"],
     "argument --trace: 'H' appears more than once"),
    ("a parameter freed twice", ["synthesize", "function", "fourbar", "{tmp}/none.csv", "--free", "a,b,a"],
     "argument --free: 'a' appears more than once"),
    ("a tolerance that repeats an angle", ["tolerance", "fourbar", "--tolerance", "0.1", "--angles", "5,5"],
     "5 appears more than once"),
]


@pytest.mark.parametrize("argv, words", [pytest.param(a, w, id=what) for what, a, w in REFUSED])
def test_refused_in_one_line_with_exit_2(argv, words, tmp_path, capsys):
    argv = [word.replace("{tmp}", str(tmp_path)) for word in argv]
    assert main(argv) == 2
    out, err = capsys.readouterr()
    _one_error_line(err, words)
    assert out == "" and list(tmp_path.iterdir()) == []  # nothing started, nothing written


@pytest.mark.parametrize("argv", [
    [*FOURBAR, "--masses", "1,2,1.5", "--centres", "-0.1:0,0.3:0,0.2:0", "--angles", "0"],  # a negative first pair
    ["analyze", "fivebar", "--set", "psi=10"],  # the second input held on purpose
])
def test_accepted(argv, capsys):
    assert main(argv) == 0, capsys.readouterr().err


@pytest.mark.parametrize("scale", ["1e-45", "1e45"])
def test_lengths_near_the_bounds_give_the_seed_angles(scale, capsys):
    """The seed 003 four-bar scaled by 1e+-45: its angles do not change (+1 branch: rocker 110.74 deg at 0)."""
    lengths = [f"{n}{scale[1:]}" for n in ("20", "66", "56", "80")]
    assert main(["fourbar", "--crank", lengths[0], "--coupler", lengths[1], "--rocker", lengths[2], "--ground",
                 lengths[3], "--angles", "0", "--branch", "+1", "--format", "csv"]) == 0
    row = capsys.readouterr().out.splitlines()[1].split(",")
    assert float(row[3]) == pytest.approx(110.7424, abs=1e-4)


def test_the_largest_flywheel_that_fits_is_what_the_refusal_suggests(capsys):
    """The suggestion of a refusal is itself accepted by the estimate (not run: it would take minutes)."""
    from symlink.cli.budget import require_budget
    from symlink.cli.dynamics import FLYWHEEL_BYTES_PER_SAMPLE, FLYWHEEL_SECONDS, FLYWHEEL_SECONDS_PER_SAMPLE
    with pytest.raises(ValueError) as caught:
        require_budget(10 ** 7, FLYWHEEL_BYTES_PER_SAMPLE, FLYWHEEL_SECONDS_PER_SAMPLE, "x", "--samples",
                       available=8 * 10 ** 9, fixed_seconds=FLYWHEEL_SECONDS)
    suggested = int(str(caught.value).split("--samples ")[1].split(" ")[0].replace(",", ""))
    require_budget(suggested, FLYWHEEL_BYTES_PER_SAMPLE, FLYWHEEL_SECONDS_PER_SAMPLE, "x", "--samples",
                   available=8 * 10 ** 9, fixed_seconds=FLYWHEEL_SECONDS)
    assert suggested * FLYWHEEL_BYTES_PER_SAMPLE <= 1.5e9


def test_the_command_line_bound_is_the_linkage_file_bound():
    from symlink.cli.options import MAX_MAGNITUDE
    from symlink.io.linkage_file import MAX_MAGNITUDE as FILE_MAGNITUDE
    assert MAX_MAGNITUDE == FILE_MAGNITUDE


@pytest.mark.parametrize("rows, options, words", [
    (9000, [], "a path synthesis of 9,000 points would need about 8.1 GB of memory"),
    (4, ["--starts", "1000000000"], "a path synthesis of 4 points from 1,000,000,000 starts could take about"),
    (4, ["--starts", "0"], "--starts must be at least 1"),
])
def test_path_synthesis_is_estimated_before_it_starts(rows, options, words, tmp_path, capsys):
    path = tmp_path / "points.csv"
    path.write_text("x,y\n" + "".join(f"{k},{(k * 7) % 5}\n" for k in range(rows)))
    assert main(["synthesize", "path", str(path), *options]) == 2
    _one_error_line(capsys.readouterr().err, words)


@pytest.mark.parametrize("fps", ["1e49", "0", "-1", "101"])
def test_animation_rates_beyond_a_gif(fps, tmp_path, capsys):
    assert main(["animate", *FOURBAR[1:], "--frames", "3", "--fps", fps, "--out", str(tmp_path / "a.gif")]) == 2
    _one_error_line(capsys.readouterr().err, "--fps must be above 0 and at most 100")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("argv", [
    ["analyze", "jansen", "--output", "x" * 100_000],
    ["plan", "y" * 5000 + ".toml"],
    ["fourbar", "--crank", "9" * 400, "--coupler", "66", "--rocker", "56", "--ground", "80"],
])
def test_hostile_text_is_cut_to_an_excerpt(argv, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and len(err) < 1100 and "..." in err, err


# --- a request that repeats itself is collapsed in Python, never computed twice ----------------------------------

def test_a_solver_asked_for_an_output_twice_computes_it_once():
    from symlink import Solver, fourbar
    solver = Solver(fourbar(), ["rocker", "rocker_speed", "rocker"] * 1000)
    assert solver.outputs == ["rocker", "rocker_speed", "singular"]
    result = solver(theta=0.0, a=20, b=66, c=56, d=80, thetadot=10.5)
    assert math.degrees(float(result["rocker"])) == pytest.approx(110.74, abs=0.005)  # seed 003's table


@pytest.mark.parametrize("output, words", [(3.5, "not by a float"), (None, "not by a NoneType")])
def test_an_output_that_is_no_name_is_refused_in_one_line(output, words):
    from symlink import Solver, fourbar
    with pytest.raises(ValueError, match=words):
        Solver(fourbar(), [output])


@pytest.mark.parametrize("rows, extra, words", [
    ("x,y\n1,2\n1,2\n3,4\n5,7\n", [], "target points 1 and 2 are the same point (1, 2)"),
    ("x,y\n1,2\n3,4\n5,7\n9,1\n3,4\n", [], "target points 2 and 5 are the same point (3, 4)"),
], ids=["adjacent", "apart"])
def test_path_targets_given_twice_are_refused_in_one_line(rows, extra, words, tmp_path, capsys):
    targets = tmp_path / "targets.csv"
    targets.write_text(rows)
    assert main(["synthesize", "path", str(targets), *extra]) == 2
    _one_error_line(capsys.readouterr().err, words)


def test_path_targets_given_twice_are_refused_by_both_python_routes():
    import symlink
    points = [[1.0, 2.0], [3.0, 4.0], [1.0, 2.0], [5.0, 7.0]]
    with pytest.raises(ValueError, match="target points 1 and 3 are the same point"):
        symlink.synthesize_fourbar_path(points)
    linkage = symlink.with_point(symlink.fourbar(), "B", symlink.fourbar().roles["coupler"])
    with pytest.raises(ValueError, match="target points 1 and 3 are the same point"):
        symlink.synthesize_path(linkage, "P", points, {"a": (1.0, 10.0)},
                                values={"b": 66.0, "c": 56.0, "d": 80.0, "u": 30.0, "v": 20.0})
    # timed: the same point at two inputs (a closed path's start and end) is two targets, not a repeat
    symlink.synthesis.path.check_distinct_targets(np.array(points), np.array([0.0, 1.0, 2.0, 3.0]))


# --- numbers of any digits, in every file format and numeric option: range-checked in one line, exit 2 -----------
# float() rounds without a word: 1e-400 to 0 (a speed or a target given becomes none), 400 digits to inf or, as an
# int, to an OverflowError.  Every reader goes through symlink.common.numbers.

_ROOT = __import__("pathlib").Path(__file__).resolve().parents[2]
_FOURBAR_FILE = (_ROOT / "linkages" / "fourbar.toml").read_text()
_HUGE = "1" + "0" * 400
_MECHANISM = ('{"joints": [{"id": "O1", "type": "ground", "position": [0, 0]}, {"id": "O2", "type": "ground", '
              '"position": [100, 0]}, {"id": "B", "type": "revolute", "position": [0, 25]}, {"id": "C", "type": '
              '"revolute", "position": [60, 50]}], "links": [{"id": "ground", "type": "ground", "joints": ["O1", '
              '"O2"]}, {"id": "crank", "type": "driver", "joints": ["O1", "B"], "motor_joint": "O1"}, {"id": '
              '"coupler", "type": "link", "joints": ["B", "C"]}, {"id": "rocker", "type": "link", "joints": ["C", '
              '"O2"]}], "ground": "ground"}')
_PYSLVS = ("M[J[R, color[Green], P[0, 0], L[ground, L1]], J[R, color[Green], P[0, 25], L[L1, L2]], "
           "J[R, color[Green], P[60, 50], L[L2, L3]], J[R, color[Green], P[100, 0], L[ground, L3]]]")
_SCENE = 'linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 20\nb = 66\nc = 56\nd = 80\n[input]\nstep = 40\n'

#: name -> (file name, text) of the files the NUMBERS table writes; {file:NAME} in a command line is its path.
_NUMBER_FILES = {
    "linkage 400 digits": ("l.toml", _FOURBAR_FILE.replace("a = 20.0", f"a = {_HUGE}")),
    "linkage 1e-400": ("l.toml", _FOURBAR_FILE.replace("a = 20.0", "a = 1e-400")),
    "linkage angle 1e-400": ("l.toml", _FOURBAR_FILE.replace('AD = ["d", 0]', 'AD = ["d", 1e-400]')),
    "scene 1e-400": ("s.toml", _SCENE.replace("step = 40", "step = 1e-400")),
    "scene 1e999": ("s.toml", _SCENE.replace("a = 20", "a = 1e999")),
    "path 1e-400": ("p.csv", "x,y\n1,2\n3,4\n5,7\n1e-400,1\n"),
    "path 400 digits": ("p.csv", f"x,y\n1,2\n3,4\n5,7\n{_HUGE},1\n"),
    "function 1e-400": ("f.csv", "theta,phi\n0,10\n30,40\n60,1e-400\n"),
    "pylinkage 1e-400": ("m.json", _MECHANISM.replace('"position": [0, 25]', '"position": [1e-400, 25]')),
    "pyslvs 1e-400": ("m.pmks", _PYSLVS.replace("P[0, 25]", "P[1e-400, 25]")),
}

NUMBERS = [
    # (what, command line, words of the one error line)
    ("an option of 1e-400", [*FOURBAR, "--crank-speed", "1e-400", "--angles", "0"],
     "argument --crank-speed: 1e-400 is too small for a float"),
    ("an angle of 1e-400", [*FOURBAR, "--angles", "10,1e-400"], "argument --angles: 1e-400 is too small"),
    ("a --set of -1e-400", ["table", "fourbar", "--set", "a=20,psi=-1e-400"], "-1e-400 is too small"),
    ("a count of 400 digits", [*FLYWHEEL, "--masses", "1,2,1.5", "--samples", _HUGE],
     "argument --samples: '100000000000000000000000000000000000000000000000000000000000'... is out of range"),
    ("a grid of 30 digits", ["sweep", "fourbar", "{tmp}/s", "--vary", "a=1:2", "--grid", "9" * 30, *SWEEP],
     "argument --grid:", "is out of range"),
    ("builds of 35 digits", ["tolerance", "fourbar", "--tolerance", "0.1", "--builds", "1" + "0" * 34],
     "is out of range"),
    ("a seed below 0", ["synthesize", "path", "{file:path 1e-400}", "--seed", "-1"],
     "argument --seed: a --seed must be 0 or more (a whole number), got -1"),
    ("a linkage default of 400 digits", ["table", "{file:linkage 400 digits}", "--angles", "0"],
     "l.toml:28: defaults.a:", "is too large for a float"),
    ("a linkage default of 1e-400", ["table", "{file:linkage 1e-400}", "--angles", "0"],
     "l.toml:28: 1e-400 is too small for a float"),
    ("a linkage angle of 1e-400", ["plan", "{file:linkage angle 1e-400}"], "l.toml:10: 1e-400 is too small"),
    ("a scene step of 1e-400", ["run", "{file:scene 1e-400}"], "s.toml: line 9: 1e-400 is too small"),
    ("a scene length of 1e999", ["run", "{file:scene 1e999}"], "s.toml: line 4: 1e999 is too large for a float"),
    ("a path target of 1e-400", ["synthesize", "path", "{file:path 1e-400}"], "p.csv:5: x: 1e-400 is too small"),
    ("a path target of 400 digits", ["synthesize", "path", "{file:path 400 digits}"], "p.csv:5: x:",
     "is too large for a float"),
    ("a function target of 1e-400", ["synthesize", "function", "fourbar", "{file:function 1e-400}", "--free", "a,b,c"],
     "f.csv:4: phi: 1e-400 is too small"),
    ("a pylinkage position of 1e-400", ["studio", "{file:pylinkage 1e-400}", "--html", "{tmp}/o.html"],
     "pylinkage JSON: the number is out of range: 1e-400 is too small"),
    ("a Pyslvs position of 1e-400", ["studio", "{file:pyslvs 1e-400}", "--html", "{tmp}/o.html"],
     "the number is out of range: 1e-400 is too small"),
]


@pytest.mark.parametrize("argv, words", [pytest.param(a, w, id=what) for what, a, *w in NUMBERS])
def test_numbers_of_any_digits_are_range_checked_in_one_line(argv, words, tmp_path, capsys):
    inputs = tmp_path / "inputs"
    inputs.mkdir()
    expanded = []
    for word in argv:
        if word.startswith("{file:"):
            name, text = _NUMBER_FILES[word[len("{file:"):-1]]
            (inputs / name).write_text(text)
            word = str(inputs / name)
        expanded.append(word.replace("{tmp}", str(tmp_path)))
    assert main(expanded) == 2
    out, err = capsys.readouterr()
    _one_error_line(err, *words)
    assert out == "" and [p.name for p in tmp_path.iterdir()] == ["inputs"]


@pytest.mark.parametrize("text", ["0", "-0", "0.000e-999", "+0.0"])
def test_zeros_of_any_digits_are_zero(text):
    from symlink.common.numbers import number_from_text
    assert number_from_text(text) == 0.0


# --- input that defines nothing new: a function's targets at one input, by both routes ---------------------------

@pytest.mark.parametrize("rows, route, words", [
    ("theta,phi\n10,20\n10,20\n10,20\n", [], "targets 1 and 2 are the same target"),
    ("theta,phi\n10,20\n10,20\n10,20\n", ["fourbar"], "targets 1 and 2 are the same target"),
    ("theta,phi\n10,20\n30,40\n10,30\n60,50\n", ["fourbar"], "targets 1 and 3 are at the same input"),
    ("theta,phi\n10,20\n30,40\n10,30\n60,50\n", [], "targets 1 and 3 are at the same input"),
], ids=["one row thrice, four-bar route", "one row thrice, any linkage", "one input two values, any linkage",
        "one input two values, four-bar route"])
def test_function_targets_at_one_input_are_refused_in_one_line(rows, route, words, tmp_path, capsys):
    targets = tmp_path / "pairs.csv"
    targets.write_text(rows)
    free = ["--free", "a,b,c"] if route else []
    assert main(["synthesize", "function", *route, str(targets), *free]) == 2
    _one_error_line(capsys.readouterr().err, words)


def test_function_targets_at_one_input_are_refused_by_both_python_routes():
    import symlink
    with pytest.raises(ValueError, match="targets 1 and 2 are the same target"):
        symlink.synthesis.function.least_squares_design([0.1, 0.1, 0.5, 0.9], [0.2, 0.2, 0.6, 1.0])
    with pytest.raises(ValueError, match="targets 2 and 3 are at the same input"):
        symlink.synthesis.general_function.synthesize_function(
            symlink.fourbar(), "rocker", [0.1, 0.5, 0.5], [0.2, 0.6, 0.7], {"a": (1.0, 30.0)},
            values={"b": 66.0, "c": 56.0, "d": 80.0})


# --- outputs that cannot be written: one line naming the user's file and the real reason, exit 1, checked before
# any work (no table printed first, no other file of the command written, nothing left behind) -------------------

UNWRITABLE = [
    # (what, command line: {tmp} a fresh folder holding a regular file "afile" and a folder "taken.gif")
    ("a figure under a file", [*FOURBAR, "--angles", "0", "--plot", "{tmp}/afile/x.png"]),
    ("the second figure under a file", [*FOURBAR, "--angles", "0", "--plot", "{tmp}/a.png", "--plot-transmission",
                                        "{tmp}/afile/x.png"]),
    ("a drawing under a file", ["draw", "fourbar", "--out", "{tmp}/afile/d.svg"]),
    ("an animation under a file", ["animate", "fourbar", "--frames", "2", "--out", "{tmp}/afile/a.gif"]),
    ("an atlas drawing under a file", ["atlas", "fourbar", "--draw", "{tmp}/afile/a.png"]),
    ("parts, the dxf under a file", ["parts", "fourbar", "--pin-diameter", "1", "--svg", "{tmp}/p.svg", "--dxf",
                                     "{tmp}/afile/p.dxf"]),
    ("generated code under a file", ["export", "fourbar", "--to", "c", "--out", "{tmp}/afile/code"]),
    ("a studio page under a file", ["studio", "fourbar", "--html", "{tmp}/afile/s.html"]),
    ("a synthesis plot under a file", ["synthesize", "path", "{tmp}/pts.csv", "--starts", "2", "--plot",
                                       "{tmp}/afile/x.png"]),
    ("a sweep under a file", ["sweep", "fourbar", "{tmp}/afile/s", "--vary", "a=1:2", "--grid", "2", *SWEEP]),
    ("sampled builds under a file", ["tolerance", "fourbar", "--tolerance", "0.1", "--samples", "10", "--folder",
                                     "{tmp}/afile/t"]),
]


def _unwritable_folder(tmp_path):
    (tmp_path / "afile").write_text("")
    (tmp_path / "taken.gif").mkdir()
    (tmp_path / "pts.csv").write_text("x,y\n1,2\n3,4\n5,7\n9,1\n")
    return {p.name for p in tmp_path.iterdir()}


@pytest.mark.parametrize("argv", [pytest.param(a, id=what) for what, a in UNWRITABLE])
def test_an_output_under_a_file_is_refused_before_any_work(argv, tmp_path, capsys):
    before = _unwritable_folder(tmp_path)
    argv = [word.replace("{tmp}", str(tmp_path)) for word in argv]
    assert main(argv) == 1
    out, err = capsys.readouterr()
    target = next(word for word in argv if "/afile/" in word)
    _one_error_line(err, target, f"{tmp_path / 'afile'} is a file, not a folder")
    assert out == "" and {p.name for p in tmp_path.iterdir()} == before  # no table, no other file, no temporary


@pytest.mark.parametrize("argv, words", [
    (["animate", "fourbar", "--frames", "2", "--out", "{tmp}/taken.gif"], "it is a folder, not a file"),
    (["studio", "fourbar", "--html", "{tmp}/taken.gif"], "it is a folder, not a file"),
    (["studio", "fourbar", "--html", "{tmp}/pipe"], "No such device or address"),  # written through, not replaced
], ids=["an animation where a folder is", "a page where a folder is", "a page into a FIFO no one reads"])
def test_an_output_that_cannot_be_written_names_it_and_why(argv, words, tmp_path, capsys):
    import os
    import stat
    os.mkfifo(tmp_path / "pipe")  # a device such as /dev/full is written the same way (ENOSPC)
    before = _unwritable_folder(tmp_path)
    argv = [word.replace("{tmp}", str(tmp_path)) for word in argv]
    assert main(argv) == 1
    _one_error_line(capsys.readouterr().err, argv[-1], words)
    assert {p.name for p in tmp_path.iterdir()} == before and list((tmp_path / "taken.gif").iterdir()) == []
    assert stat.S_ISFIFO(os.stat(tmp_path / "pipe").st_mode)  # never replaced by a file


def test_a_full_disk_under_an_animation_names_the_users_file(tmp_path, capsys, monkeypatch):
    """The frames go to a hidden folder beside the file; a full disk at the rename names the file asked for."""
    import errno

    import symlink.plot.animation as animation

    def full(source, target):
        raise OSError(errno.ENOSPC, "No space left on device", str(source))
    monkeypatch.setattr(animation.os, "replace", full)
    assert main(["animate", "fourbar", "--frames", "2", "--out", str(tmp_path / "a.gif")]) == 1
    err = capsys.readouterr().err
    errors = [line for line in err.splitlines() if line.startswith("symlink: error:")]  # after the progress lines
    assert errors == [err.splitlines()[-1]] and "Traceback" not in err, err
    assert f"{tmp_path / 'a.gif'}: No space left on device" in errors[0]
    assert ".symlink-animation-" not in err and list(tmp_path.iterdir()) == []


def test_a_full_disk_under_two_figures_writes_neither(tmp_path, capsys, monkeypatch):
    import errno

    import symlink.common.files as files
    written = []

    def write(handle, data):
        if written:
            raise OSError(errno.ENOSPC, "No space left on device")
        written.append(len(data))
        return len(data)
    monkeypatch.setattr(files.os, "write", write)
    assert main([*FOURBAR, "--angles", "0", "--plot", str(tmp_path / "a.png"), "--plot-transmission",
                 str(tmp_path / "t.png")]) == 1
    err = capsys.readouterr().err
    _one_error_line(err, "No space left on device")
    assert f"{tmp_path / 'a.png'}:" in err or f"{tmp_path / 't.png'}:" in err
    assert list(tmp_path.iterdir()) == []  # the figure written in full is taken back


# --- conflicting options and outputs named twice: one line naming both, exit 2, nothing written --------------------

CONFLICTS = [
    ("two figures to one file", [*FOURBAR, "--plot", "{tmp}/a.png", "--plot-transmission", "{tmp}/./a.png"],
     "--plot and --plot-transmission both write"),
    ("parts to one file by two paths", ["parts", "fourbar", "--pin-diameter", "1", "--svg", "{tmp}/a.svg",
                                        "--assembly", "{tmp}/sub/../a.svg"], "--svg and --assembly both write"),
    ("--workers with a synchronous sweep", ["sweep", "fourbar", "{tmp}/s", "--vary", "a=1:2", "--workers", "2",
                                            *SWEEP], "--workers conflicts with --scheduler synchronous"),
    ("--workers with a cluster", ["sweep", "fourbar", "{tmp}/s", "--vary", "a=1:2", "--workers", "2", "--scheduler",
                                  "tcp://127.0.0.1:1"], "--workers conflicts with --scheduler tcp://127.0.0.1:1"),
    ("--seed with a grid", ["sweep", "fourbar", "{tmp}/s", "--vary", "a=1:2", "--grid", "3", "--seed", "4", *SWEEP],
     "--seed does nothing with --grid"),
    ("--html with --no-browser", ["studio", "fourbar", "--html", "{tmp}/s.html", "--no-browser"],
     "--html and --no-browser conflict"),
    ("--html with --port", ["studio", "fourbar", "--html", "{tmp}/s.html", "--port", "9000"],
     "--html and --port conflict"),
    ("tolerance --seed without samples", ["tolerance", "fourbar", "--tolerance", "0.1", "--seed", "3"],
     "--seed does nothing without --samples N"),
    ("view --crank-angle with a linkage", ["view", "fourbar", "--crank-angle", "5", "--save", "{tmp}/v.png"],
     "view: --crank-angle does nothing with a linkage NAME|FILE"),
    ("view --angle in the four-bar form", ["view", *FOURBAR[1:], "--angle", "5", "--save", "{tmp}/v.png"],
     "view: --angle does nothing in the four-bar form"),
]


@pytest.mark.parametrize("argv, words", [pytest.param(a, w, id=what) for what, a, w in CONFLICTS])
def test_conflicting_options_are_refused_naming_both(argv, words, tmp_path, capsys):
    argv = [word.replace("{tmp}", str(tmp_path)) for word in argv]
    assert main(argv) == 2
    out, err = capsys.readouterr()
    _one_error_line(err, words)
    assert out == "" and list(tmp_path.iterdir()) == []
