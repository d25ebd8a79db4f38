"""Every bad command line ends in one line on stderr and a documented exit status, never a traceback.

Exit status 2 for bad input (an input file that cannot be read among it), 1 for a file that cannot be
written; the error is one line starting ``symlink: error:``, and nothing is left behind in
the folder the command was asked to write into.
"""
from __future__ import annotations

import os

import pytest

from symlink.cli import main

FOURBAR = ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80"]
SLIDER = ["slider-crank", "--crank", "20", "--conrod", "66"]
INVERTED = ["inverted-slider-crank", "--crank", "2", "--ground", "1.2"]
WATT2 = ["watt2", "--crank", "1", "--coupler", "3.5", "--rocker", "3", "--ground", "3.2", "--rocker-arm", "2",
         "--rocker-arm-angle", "35", "--coupler2", "4", "--output", "3", "--output-x", "4.5", "--output-y", "3.5"]
FIVEBAR = ["fivebar", "--crank", "2", "--coupler", "3", "--coupler2", "3", "--crank2", "2", "--ground", "5",
           "--crank2-angle", "90"]
STEPHENSON2 = ["stephenson2", "--crank", "1", "--coupler", "3.1", "--link-cf", "2.2", "--ground", "4.5",
               "--coupler-arm", "3.9", "--rocker", "3.1", "--link-eh", "4.1", "--rocker-arm", "3.1",
               "--coupler-arm-angle", "51.57", "--rocker-arm-angle", "17.19"]
TABLES = {"fourbar": FOURBAR, "slider-crank": SLIDER, "inverted-slider-crank": INVERTED, "watt2": WATT2,
          "fivebar": FIVEBAR, "stephenson2": STEPHENSON2,
          "stephenson3": ["stephenson3", *STEPHENSON2[1:]]}  # stephenson2's table by its former name

#: (what, extra arguments) that every table command must refuse with exit status 2.
TABLE_MISTAKES = [
    ("unknown option", ["--bogus", "3"]),
    ("first length not a number", ["--crank", "x"]),
    ("first length nan", ["--crank", "nan"]),
    ("first length inf", ["--crank", "inf"]),
    ("negative length", ["--crank", "-2"]),
    ("zero length", ["--crank", "0"]),
    ("unknown units", ["--units", "grad"]),
    ("unknown format", ["--format", "xml"]),
    ("zero step", ["--step", "0"]),
    ("negative step", ["--step", "-5"]),
    ("subnormal step", ["--step", "1e-320"]),
    ("step too small for the start", ["--start", "1e8", "--stop", "100000001", "--step", "1e-9"]),
    ("stop before start", ["--start", "10", "--stop", "5"]),
    ("angles and a step", ["--angles", "10", "--step", "5"]),
    ("a huge angle", ["--angles", "1e300"]),
    ("an empty angle list", ["--angles", ","]),
    ("an angle that is text", ["--angles", "10,x"]),
    ("too many angles", ["--step", "1e-6"]),
    ("crank speed whose square overflows", ["--crank-speed", "1e308", "--angles", "0"]),
    ("crank that stops", ["--crank-speed", "1", "--crank-accel", "-100", "--step", "90"]),
]

CASES = [(f"{name}: {what}", argv + extra, 2) for name, argv in TABLES.items() for what, extra in TABLE_MISTAKES]
CASES += [
    ("no command", [], 2),
    ("unknown command", ["sixbar"], 2),
    ("fourbar: a missing length", FOURBAR[:-2], 2),
    ("fourbar: branch 2", FOURBAR + ["--branch", "2"], 2),
    ("fourbar: a length of 1e308", ["fourbar", "--crank", "1e308", "--coupler", "66", "--rocker", "56",
                                    "--ground", "80"], 2),
    ("fourbar: subnormal lengths", ["fourbar", "--crank", "2e-310", "--coupler", "6.6e-309", "--rocker", "5.6e-309",
                                    "--ground", "8e-309"], 2),
    ("slider-crank: a length of 1e308", ["slider-crank", "--crank", "1e308", "--conrod", "66"], 2),
    ("fourbar: cannot be assembled anywhere", ["fourbar", "--crank", "1", "--coupler", "1", "--rocker", "1",
                                              "--ground", "10"], 2),
    ("fourbar: plot of the wrong kind", FOURBAR + ["--plot", "{tmp}/angles.pdf"], 2),
    ("slider-crank: conrod text", SLIDER[:-1] + ["long"], 2),
    ("watt2: a branch for three loops", WATT2 + ["--branch", "+1,-1,+1"], 2),
    ("fivebar: a missing crank-2 angle", FIVEBAR[:-2], 2),
    ("stephenson2: guess of an unknown name", STEPHENSON2 + ["--guess", "psi=10"], 2),
    ("stephenson2: guess that is not NAME=ANGLE", STEPHENSON2 + ["--guess", "coupler"], 2),
    ("atlas: unknown entry", ["atlas", "watt-iii"], 2),
    ("atlas: --draw without an entry", ["atlas", "--draw", "{tmp}/atlas.png"], 2),
    ("atlas: a drawing of the wrong kind", ["atlas", "watt-ii", "--draw", "{tmp}/atlas.pdf"], 2),
    ("atlas: links not 4, 6 or 8", ["atlas", "--links", "5"], 2),
    ("tolerance: negative band", ["tolerance"] + FOURBAR[1:] + ["--tolerance", "-0.05"], 2),
    ("tolerance: no tolerance", ["tolerance"] + FOURBAR[1:], 2),
    ("tolerance: unknown dimension", ["tolerance", "fourbar", "--tolerances", "e=0.1"], 2),
    ("tolerance: unknown output", ["tolerance", "fourbar", "--tolerance", "0.1", "--output", "psi"], 2),
    ("tolerance: play at no pin", ["tolerance", "fourbar", "--tolerance", "0.1", "--play", "E=0.02"], 2),
    ("tolerance: negative play", ["tolerance", "fourbar", "--tolerance", "0.1", "--play", "B=-0.02"], 2),
    ("tolerance: no builds", ["tolerance", "fourbar", "--tolerance", "0.1", "--builds", "0"], 2),
    ("tolerance: too many builds", ["tolerance", "fourbar", "--tolerance", "0.1", "--builds", "100000000"], 2),
    ("tolerance: lengths of another linkage", ["tolerance", "slider-crank", "--crank", "3", "--tolerance", "1"], 2),
    ("parts: no pin diameter", ["parts", "fourbar", "--svg", "{tmp}/parts.svg"], 2),  # the rest: tests/cli/test_parts.py
    ("parts: no assembly at the angle", ["parts", "fourbar", "--pin-diameter", "4", "--set", "a=30,b=10", "--angle",
                                         "180", "--assembly", "{tmp}/assembly.svg"], 2),
    ("studio: unknown linkage", ["studio", "sixbar", "--no-browser"], 2),  # the rest: tests/studio/test_command.py
    ("studio: --html without a linkage", ["studio", "--html", "{tmp}/page.html"], 2),
    ("studio: no such port", ["studio", "--port", "0", "--no-browser"], 2),
    ("studio: --html of a linkage that cannot be drawn", ["studio", "--html", "{tmp}/page.html", "fivebar"], 2),
    ("plan: unknown linkage", ["plan", "sixbar"], 2),
    ("plan: no linkage", ["plan"], 2),
    ("analyze: negative length", ["analyze", "--crank", "-1", "--coupler", "2", "--rocker", "2", "--ground", "2"], 2),
    ("analyze: cannot close", ["analyze", "--crank", "1", "--coupler", "1", "--rocker", "1", "--ground", "10"], 2),
    ("analyze: branch both", ["analyze", "--crank", "1", "--coupler", "3", "--rocker", "3", "--ground", "3",
                              "--branch", "both"], 2),
    ("analyze: a name and four-bar lengths", ["analyze", "fourbar", "--crank", "1"], 2),
    ("analyze: neither a name nor lengths", ["analyze", "--crank", "1"], 2),
    ("analyze: an unknown --set name", ["analyze", "jansen", "--set", "zz=1"], 2),
    ("analyze: an unknown output", ["analyze", "jansen", "--output", "Q_x"], 2),
    ("analyze: no closed form", ["analyze", "stephenson2"], 2),
    ("loop: three values missing", ["loop", "--r1", "3", "--t1", "0", "--r2", "4", "--t2", "90", "--r3", "5"], 2),
    ("loop: nothing missing", ["loop"] + [f"--{k}" for k in ("r1", "1", "r2", "1", "r3", "1", "r4", "1", "t1", "0",
                                                              "t2", "90", "t3", "180", "t4", "270")], 2),
    ("loop: negative length", ["loop", "--r1", "-3", "--t1", "0", "--r2", "4", "--t2", "90", "--t3", "180",
                               "--t4", "270"], 2),
    ("loop: a plot of the wrong kind", ["loop", "--r1", "300", "--t1", "270", "--r2", "640.3124", "--t2", "308.663",
                                        "--t3", "180", "--t4", "63.435", "--plot", "{tmp}/loop.gif"], 2),
    ("flywheel: no masses", ["flywheel", "--crank", "2", "--coupler", "6", "--rocker", "5", "--ground", "8", "--rpm", "60",
                             "--coefficient", "0.05"], 2),  # the rest: tests/cli/test_dynamics.py
    ("quick-return: time ratio below 1", ["quick-return", "--time-ratio", "0.5", "--stroke", "40", "--rocker", "50"], 2),
    ("quick-return: stroke of 200 degrees", ["quick-return", "--time-ratio", "1.25", "--stroke", "200",
                                             "--rocker", "50"], 2),
    ("quick-return: pivot of three numbers", ["quick-return", "--time-ratio", "1.25", "--stroke", "40",
                                              "--rocker", "50", "--crank-pivot", "1,2,3"], 2),
    ("synthesize: no kind", ["synthesize"], 2),
    ("synthesize: a file that is not there", ["synthesize", "path", "{tmp}/none.csv"], 2),  # as a linkage or scene file
    ("synthesize: a plot of the wrong kind", ["synthesize", "function", "{tmp}/none.csv", "--plot", "{tmp}/f.gif"], 2),
    ("curve: no --out", ["curve", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
                         "--coupler-point", "40,30"], 2),
    ("curve: coupler point of one number", ["curve", "--crank", "20", "--coupler", "66", "--rocker", "56",
                                            "--ground", "80", "--coupler-point", "40", "--out", "{tmp}/c.png"], 2),
    ("curve: negative coupler distance", ["curve", "--crank", "20", "--coupler", "66", "--rocker", "56",
                                          "--ground", "80", "--coupler-point", "-40,30", "--out", "{tmp}/c.png"], 2),
    ("draw: unknown linkage", ["draw", "sixbar", "--out", "{tmp}/d.png"], 2),
    ("draw: --set without a value", ["draw", "jansen", "--set", "a", "--out", "{tmp}/d.png"], 2),
    ("animate: zero frames", ["animate", "--crank", "1", "--coupler", "4", "--rocker", "2.5", "--ground", "3",
                              "--frames", "0", "--out", "{tmp}/a.gif"], 2),
    ("animate: frames not whole", ["animate", "--crank", "1", "--coupler", "4", "--rocker", "2.5", "--ground", "3",
                                   "--frames", "2.5", "--out", "{tmp}/a.gif"], 2),
    ("animate: a billion frames", ["animate", "--crank", "1", "--coupler", "4", "--rocker", "2.5", "--ground", "3",
                                   "--frames", "1000000000", "--out", "{tmp}/a.gif"], 2),
    ("animate: zero fps", ["animate", "--crank", "1", "--coupler", "4", "--rocker", "2.5", "--ground", "3",
                           "--fps", "0", "--out", "{tmp}/a.gif"], 2),
    ("animate: a file of the wrong kind", ["animate", "--crank", "1", "--coupler", "4", "--rocker", "2.5",
                                           "--ground", "3", "--out", "{tmp}/a.avi"], 2),
    ("view: a length outside its sliders", ["view", "--crank", "0.001", "--save", "{tmp}/v.png"], 2),
    ("view: a picture of the wrong kind", ["view", "--save", "{tmp}/v.jpg"], 2),
    ("view: a name and four-bar lengths", ["view", "jansen", "--crank", "3", "--save", "{tmp}/v.png"], 2),
    ("view: an unknown linkage", ["view", "sixbar", "--save", "{tmp}/v.png"], 2),
    ("curve: four-bar without a coupler point", ["curve", "--crank", "20", "--coupler", "66", "--rocker", "56",
                                                 "--ground", "80", "--out", "{tmp}/c.png"], 2),
    ("curve: a name and four-bar lengths", ["curve", "jansen", "--crank", "3", "--out", "{tmp}/c.png"], 2),
    ("view: a huge crank speed", ["view", "--crank-speed", "1e300", "--save", "{tmp}/v.png"], 2),
    ("run: no such file", ["run", "{tmp}/missing.toml"], 2),
    ("run: a folder", ["run", "{tmp}"], 2),
    ("run: /dev/zero", ["run", "/dev/zero"], 2),
    ("run: huge integer", ["run", "{scene:huge}"], 2),
    ("run: deep nesting", ["run", "{scene:deep}"], 2),
    ("run: branch 1.0", ["run", "{scene:float branch}"], 2),
    ("run: not TOML", ["run", "{scene:not toml}"], 2),
    ("run: not UTF-8", ["run", "{scene:binary}"], 2),
    ("run: unknown format", ["run", "{scene:good}", "--format", "xml"], 2),
    ("export: unknown linkage", ["export", "sixbar", "--to", "c", "--out", "{tmp}/out"], 2),
    ("export: unknown format", ["export", "fourbar", "--to", "fortran", "--out", "{tmp}/out"], 2),
    ("export: unknown output", ["export", "fourbar", "--to", "c", "--out", "{tmp}/out", "--outputs", "piston"], 2),
    ("export: --out is a file", ["export", "fourbar", "--to", "c", "--out", "{file}"], 2),
    ("export: no closed form", ["export", "stephenson2", "--to", "numpy", "--out", "{tmp}/out"], 2),
    ("derive: no such file", ["derive", "{tmp}/missing.toml", "--to", "c", "--out", "{tmp}/out"], 2),
    ("derive: not a linkage file", ["derive", "{scene:not toml}", "--to", "c", "--out", "{tmp}/out"], 2),
    ("derive: a scene, not a linkage", ["derive", "{scene:good}", "--to", "numpy", "--out", "{tmp}/out"], 2),
    ("table: unknown linkage", ["table", "sixbar"], 2),
    ("table: unknown parameter", ["table", "fourbar", "--set", "z=1"], 2),
    ("table: negative length", ["table", "fourbar", "--set", "a=-1"], 2),
    ("table: --set not NAME=VALUE", ["table", "fourbar", "--set", "a"], 2),
    ("table: a branch for two loops", ["table", "jansen", "--branch", "+1,-1"], 2),
    ("table: no guess without a closed form", ["table", "stephenson2", "--angles", "0"], 2),
    ("plan: a file that is not a linkage", ["plan", "{scene:not toml}"], 2),
    ("bench: unknown method", ["bench", "--methods", "abacus", "--no-derivation"], 2),
    ("cache: no action", ["cache"], 2),
    ("cache: unknown action", ["cache", "purge"], 2),
    ("cache: unknown option", ["cache", "info", "--all"], 2),
    ("cache: --folder without a path", ["cache", "clear", "--folder"], 2),
    ("cache: clear a folder others can write", ["cache", "clear", "--folder", "/tmp"], 2),
    ("cache: clear a file, not a folder", ["cache", "clear", "--folder", "{file}"], 2),
    ("sweep: unknown parameter", ["sweep", "fourbar", "{tmp}/sweep", "--vary", "e=1:2"], 2),
    ("sweep: reversed range", ["sweep", "fourbar", "{tmp}/sweep", "--vary", "a=2:1"], 2),
    # Failed writes: exit status 1.
    ("sweep: into /proc", ["sweep", "fourbar", "/proc/symlink-sweep", "--vary", "a=0.2:0.3", "--grid", "2",
                           "--scheduler", "synchronous", "--no-progress"], 1),
    ("fourbar: plot into /proc", FOURBAR + ["--angles", "0", "--plot", "/proc/symlink-test.png"], 1),
    ("fourbar: plot where a folder is", FOURBAR + ["--angles", "0", "--plot", "{folder}"], 1),
    ("curve: into /proc", ["curve", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
                           "--coupler-point", "40,30", "--out", "/proc/symlink-test.png"], 1),
    ("curve: where a folder is", ["curve", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
                                  "--coupler-point", "40,30", "--out", "{folder}"], 1),
    ("animate: where a folder is", ["animate", "--crank", "1", "--coupler", "4", "--rocker", "2.5", "--ground", "3",
                                    "--frames", "2", "--out", "{folder:gif}"], 1),
    ("view: into /proc", ["view", "--save", "/proc/symlink-test.png"], 1),
    ("export: into /proc", ["export", "fourbar", "--to", "c", "--out", "/proc/symlink-test"], 1),
    ("export: where a folder is", ["export", "fourbar", "--to", "latex", "--out", "{tmp}/tex", "--outputs", "rocker"],
     1),
]

SCENES = {
    "good": 'linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 20\nb = 66\nc = 56\nd = 80\n',
    "huge": 'linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 1' + "0" * 400 + "\nb = 66\nc = 56\nd = 80\n",
    "deep": 'linkage = "fourbar"\noutputs = ' + "[" * 100000 + "]" * 100000 + "\n",
    "float branch": 'linkage = "fourbar"\noutputs = ["rocker"]\nbranch = 1.0\n[parameters]\na = 20\nb = 66\nc = 56\n'
                    "d = 80\n",
    "not toml": "linkage = fourbar\n",
    "binary": b"\xff\xfe\x00linkage",
}


def _expand(argv: list[str], tmp_path) -> list[str]:
    expanded = []
    for item in argv:
        if item.startswith("{scene:"):
            name = item[len("{scene:"):-1]
            path = tmp_path / f"{name.replace(' ', '_')}.toml"
            data = SCENES[name]
            path.write_bytes(data if isinstance(data, bytes) else data.encode())
            item = str(path)
        elif item == "{folder}" or item == "{folder:gif}":
            folder = tmp_path / ("taken.gif" if item.endswith("gif}") else "taken.png")
            folder.mkdir()
            item = str(folder)
        elif item == "{file}":
            (tmp_path / "a_file").write_text("")
            item = str(tmp_path / "a_file")
        expanded.append(item.replace("{tmp}", str(tmp_path)))
    if "{tmp}/tex" in argv:  # the export's .tex file name is taken by a folder
        (tmp_path / "tex" / "fourbar.tex").mkdir(parents=True)
    return expanded


def _listing(folder) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*")}


@pytest.mark.parametrize("argv, status", [pytest.param(argv, status, id=what) for what, argv, status in CASES])
def test_bad_command_line(argv, status, tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("TMPDIR", str(tmp_path))
    argv = _expand(argv, tmp_path)
    before = _listing(tmp_path)
    got = main(argv)
    out, err = capsys.readouterr()
    errors = [line for line in err.splitlines() if line.startswith("symlink: error:")]
    assert "Traceback" not in err, err
    assert got == status, f"exit {got}, stderr: {err}"
    assert len(errors) == 1 and err.rstrip("\n").endswith(errors[0]), err
    assert _listing(tmp_path) == before, "files left behind"
    assert not os.path.exists("/proc/symlink-test.png")


def test_the_table_has_a_hundred_cases_over_every_command():
    from symlink.cli import build_parser
    assert len(CASES) >= 100
    commands = build_parser()._subparsers._group_actions[0].choices
    covered = {argv[0] for _, argv, _ in CASES if argv}
    assert set(commands) <= covered, set(commands) - covered
