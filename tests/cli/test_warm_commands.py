"""Warm is warm from the command line: a table command (or ``symlink plan``) whose code is in the disk cache imports
neither SymPy nor Matplotlib, and prints what its cold run printed, byte for byte, on stdout and on stderr (notes
included); a picture imports no SymPy and writes the bytes its cold run wrote.

Each command runs twice in new processes (:func:`warm_runs.run_twice`): first cold, which derives and caches, then
warm with ``python -X importtime``.  One cache folder serves the module, so a linkage derived for one test is
warm for the next (the first command of each linkage below is its cold run).
"""
from __future__ import annotations

import math

import pytest

from warm_runs import PROJECT, run_twice
from references import fourbar_joint_c

#: The four-bar of seed 003 (mm), whose closed forms are derived once for the module.
FOURBAR = ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80", "--angles", "0,50",
           "--format", "csv"]
STEPHENSON2 = ["--crank", "1", "--coupler", "3.1", "--link-cf", "2.2", "--ground", "4.5", "--coupler-arm", "3.9",
               "--rocker", "3.1", "--link-eh", "4.1", "--rocker-arm", "3.1", "--coupler-arm-angle", "51.5",
               "--rocker-arm-angle", "17.2", "--angles", "0,50", "--format", "csv"]
#: The four-bar of seed 003 analysed by its lengths (closed form: nothing derived, nothing cached).
ANALYZE = ["analyze", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80"]
#: Command lines by what they show; the number of output lines each prints (a header and its rows).
COMMANDS = {
    "four-bar": (FOURBAR, 5),
    "four-bar with a uniformly accelerated crank": (FOURBAR + ["--crank-speed", "3", "--crank-accel", "2"], 5),
    "four-bar with masses, gravity and a load": (FOURBAR + ["--masses", "1,2,3", "--gravity", "9.81",
                                                            "--load-torque", "-2", "--branch", "1"], 3),
    "four-bar that reaches part of a turn (a note names the rows left out)": (
        ["fourbar", "--crank", "60", "--coupler", "30", "--rocker", "50", "--ground", "40", "--angles", "0,150",
         "--format", "csv", "--branch", "1"], 2),
    "catalog table of the four-bar": (["table", "fourbar", "--angles", "0,50", "--format", "csv"], 5),
    "slider-crank": (["slider-crank", "--crank", "20", "--conrod", "66", "--offset", "5", "--angles", "0,90",
                      "--format", "csv"], 5),
    "slider-crank past its reach": (["slider-crank", "--crank", "20", "--conrod", "15", "--angles", "0,90",
                                     "--format", "csv", "--branch", "1"], 2),
    "tolerance stack-up of the four-bar": (["tolerance", "fourbar", "--crank", "20", "--coupler", "66", "--rocker",
                                            "56", "--ground", "80", "--tolerance", "0.05", "--output", "rocker",
                                            "--angles", "0,50", "--format", "csv"], 3),
    "tolerance stack-up of a rate": (
        ["tolerance", "fourbar", "--tolerance", "0.1", "--tolerances", "b=0.2", "--output", "rocker_speed",
         "--crank-speed", "3", "--angles", "0,90", "--format", "csv"], 3),
    "tolerance stack-up with sampled builds": (["tolerance", "fourbar", "--crank", "20", "--coupler", "66", "--rocker",
                                                "56", "--ground", "80", "--tolerance", "0.05", "--samples", "1000",
                                                "--angles", "0,50", "--format", "csv"], 3),
    "tolerance stack-up of the four-bar with masses": (["tolerance", "fourbar", "--crank", "20", "--coupler", "66",
                                                        "--rocker", "56", "--ground", "80", "--tolerance", "0.05",
                                                        "--masses", "1,2,3", "--angles", "0,50", "--format", "csv"], 3),
    "tolerance stack-up of the driving torque": (["tolerance", "fourbar", "--crank", "0.2", "--coupler", "0.66",
                                                  "--rocker", "0.56", "--ground", "0.8", "--tolerance", "0.001",
                                                  "--masses", "1,2,1.5", "--inertias", "0.03,0.07,0.04", "--gravity",
                                                  "9.81", "--output", "input_torque", "--crank-speed", "31.4",
                                                  "--angles", "0,50", "--format", "csv"], 3),
    "tolerance stack-up with the pins' play": (["tolerance", "fourbar", "--crank", "20", "--coupler", "66", "--rocker",
                                                "56", "--ground", "80", "--tolerance", "0.05", "--play",
                                                "B=0.02,C=0.02", "--angles", "0,50", "--format", "csv"], 3),
    "tolerance stack-up of a linkage file": (["tolerance", str(PROJECT / "linkages" / "slider-crank.toml"),
                                              "--tolerance", "0.05", "--angles", "0,40", "--format", "csv"], 3),
    "solve plan of a catalog linkage": (["plan", "fourbar"], 3),
    "solve plan of a linkage file (two loops)": (["plan", str(PROJECT / "linkages" / "watt2.toml")], 4),
    "analyze a four-bar by its lengths": (ANALYZE, 8),
    "analyze a four-bar by its lengths, in JSON": (ANALYZE + ["--format", "json", "--units", "rad"], None),
    "analyze a four-bar on branch -1 that does not turn fully": (
        ["analyze", "--crank", "60", "--coupler", "30", "--rocker", "50", "--ground", "40", "--branch", "-1"], 6),
    "analyze a catalog linkage by name": (["analyze", "fourbar"], 4),
    "analyze a linkage file, with --set": (["analyze", str(PROJECT / "symlink" / "linkages" / "watt2.toml"), "--set",
                                           "a=1.2", "--format", "json"], None),
    "analyze an output's limit positions (jansen)": (["analyze", "jansen", "--output", "H_y"], None),
    "analyze a slider-crank's stroke, in radians": (["analyze", "slider-crank", "--output", "slider", "--units",
                                                     "rad"], None),
    "analyze a five-bar with its second crank held": (["analyze", "fivebar", "--set", "psi=10"], 4),
}
SLOW_COMMANDS = {
    "inverted slider-crank": (["inverted-slider-crank", "--crank", "2", "--ground", "1.2", "--crank-speed", "3",
                               "--angles", "0,40", "--format", "csv"], 3),
    "Watt II (two loops)": (["watt2", "--crank", "1", "--coupler", "3.5", "--rocker", "3", "--ground", "3.2",
                             "--rocker-arm", "2", "--rocker-arm-angle", "35", "--coupler2", "4", "--output", "3",
                             "--output-x", "4.5", "--output-y", "3.5", "--angles", "0,90", "--branch", "+1,both",
                             "--format", "csv"], 5),
    "five-bar (two inputs)": (["fivebar", "--crank", "2", "--coupler", "3", "--coupler2", "3", "--crank2", "2",
                               "--ground", "5", "--crank2-angle", "90", "--angles", "0,30", "--format", "csv"], 5),
    "Stephenson II (Newton's method)": (["stephenson2", *STEPHENSON2], 3),
    "Stephenson II by its former name": (["stephenson3", *STEPHENSON2], 3),
    "Stephenson II's assemblies": (["stephenson2", *STEPHENSON2, "--list-assemblies"], None),
    "catalog table by the former name": (["table", "stephenson3", "--angles", "0,50", "--format", "csv", "--guess",
                                          "coupler=-33,mu=-35,rocker=-73,eta=-68"], 3),
}


@pytest.fixture(scope="module")
def shared_cache(tmp_path_factory):
    """One disk cache for the module's commands."""
    return tmp_path_factory.mktemp("warm-commands") / "cache"


def _check(name: str, commands: dict, folder, cache) -> None:
    arguments, lines = commands[name]
    runs = run_twice(folder, arguments, cache)
    assert "symlink" in runs.imported and "numpy" in runs.imported  # the import list was read
    heavy = runs.imported & {"sympy", "matplotlib", "scipy", "pandas", "distributed"}
    assert not heavy, f"the warm run imported {', '.join(sorted(heavy))}"
    assert runs.warm == runs.cold
    assert runs.warm_notes == runs.cold_notes
    if lines is not None:
        assert len(runs.warm.splitlines()) == lines, runs.warm


@pytest.mark.parametrize("name", COMMANDS)
def test_a_warm_table_command_imports_no_sympy_and_prints_the_same(name, shared_cache, tmp_path):
    _check(name, COMMANDS, tmp_path, shared_cache)


@pytest.mark.slow
@pytest.mark.parametrize("name", SLOW_COMMANDS)
def test_a_warm_six_bar_or_five_bar_command_imports_no_sympy_and_prints_the_same(name, shared_cache, tmp_path):
    _check(name, SLOW_COMMANDS, tmp_path, shared_cache)


def test_the_notes_are_those_of_the_cold_run(shared_cache, tmp_path):
    """Rows left out are named on stderr with the reachable range, warm as cold: the four-bar 60, 30, 50, 40
    reaches crank angles within acos(-1/4) = 104.4775 deg of 0 (the triangle over its diagonal, by hand), so 150
    is left out."""
    import math
    runs = run_twice(tmp_path, COMMANDS["four-bar that reaches part of a turn (a note names the rows left out)"][0],
                     shared_cache)
    limit = math.degrees(math.acos((60 ** 2 + 40 ** 2 - (30 + 50) ** 2) / (2 * 60 * 40)))
    assert f"{limit:.6g}" == "104.478"
    assert "150" in runs.warm_notes and "[-104.478, 104.478] deg" in runs.warm_notes
    assert runs.warm_notes == runs.cold_notes


@pytest.mark.slow
def test_the_former_name_is_noted_warm_as_cold(shared_cache, tmp_path):
    """``symlink stephenson3`` and ``symlink table stephenson3`` say once, warm as cold, what the name names now."""
    for arguments in (["stephenson3", *STEPHENSON2], SLOW_COMMANDS["catalog table by the former name"][0]):
        runs = run_twice(tmp_path, arguments, shared_cache)
        assert runs.warm_notes == runs.cold_notes
        assert runs.warm_notes.count("\n") == 1
        assert runs.warm_notes.startswith("symlink: warning: 'stephenson3' is symlink's former name of stephenson-ii")


def _rocker(theta: float, a: float, b: float, c: float, d: float) -> float:
    """The four-bar's rocker angle on branch +1, by hand: C from the circles about B and D."""
    cx, cy = fourbar_joint_c(theta, a, b, c, d)
    return math.atan2(cy, cx - d)


def test_a_warm_stack_up_takes_other_numbers(shared_cache, tmp_path):
    """The stack-up's cache entries are keyed by the linkage, the output and the toleranced dimensions, not by the
    numbers: another four-bar and band run warm (no SymPy), print what a cold run prints, and the worst case of
    the rocker for the coupler alone is |d(rocker)/db| * band, the slope by central differences of the rocker
    found by hand (:func:`_rocker`)."""
    first = ["tolerance", "fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
             "--tolerances", "b=0.3", "--output", "rocker", "--angles", "0", "--format", "csv"]
    run_twice(tmp_path, first, shared_cache)
    other = ["tolerance", "fourbar", "--crank", "25", "--coupler", "70", "--rocker", "60", "--ground", "85",
             "--tolerances", "b=0.6", "--output", "rocker", "--angles", "0.5", "--format", "csv", "--units", "rad"]
    warm = run_twice(tmp_path, other, shared_cache)  # both runs warm: the entries of the first command serve it
    assert not warm.imported & {"sympy", "matplotlib", "scipy", "pandas"}
    (tmp_path / "fresh").mkdir()
    cold = run_twice(tmp_path / "fresh", other)  # a cache of its own: its first run derives
    assert warm.cold == cold.cold and warm.cold_notes == cold.cold_notes
    header, row = warm.warm.splitlines()
    cells = dict(zip(header.split(","), row.split(",")))
    step = 1e-6
    slope = (_rocker(0.5, 25, 70 + step, 60, 85) - _rocker(0.5, 25, 70 - step, 60, 85)) / (2 * step)
    assert float(cells["worst_case"]) == pytest.approx(abs(slope) * 0.6, rel=1e-6)
    assert float(cells["rocker"]) == pytest.approx(_rocker(0.5, 25, 70, 60, 85), rel=1e-9)


#: Pictures (the file is the last argument): Matplotlib draws them, SymPy stays out; the file written warm is the one
#: written cold, byte for byte.
PICTURES = {
    "coupler curve of the four-bar (SVG)": ["curve", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground",
                                            "80", "--coupler-point", "40,30", "--out", "curve.svg"],
    "coupler curve on both branches at a crank angle (PNG)": [
        "curve", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80", "--coupler-point",
        "30,-20", "--branch", "both", "--crank-angle", "40", "--out", "curve.png"],
    "four-bar table with its angle plot": [*FOURBAR, "--plot", "angles.svg"],
    "catalog linkage with a traced point (curve NAME, SVG)": ["curve", "fourbar", "--trace", "C", "--out", "c.svg"],
    "linkage file, its last point traced (curve FILE, SVG)": ["curve", str(PROJECT / "linkages" / "jansen.toml"),
                                                              "--out", "j.svg"],
    "slider-crank drawn at an angle (draw NAME, PNG)": ["draw", "slider-crank", "--angle", "30", "--out", "d.png"],
    "Stephenson II by its former name, by Newton's method (draw NAME, SVG)": ["draw", "stephenson3", "--out", "s.svg"],
    "animation of a catalog linkage (animate NAME, GIF)": ["animate", "fourbar", "--frames", "3", "--out", "a.gif"],
    "four-bar table with its transmission-angle plot": [*FOURBAR, "--plot-transmission", "transmission.svg"],
    "view of a catalog linkage, saved (view NAME, PNG)": ["view", "fourbar", "--set", "a=25", "--angle", "40",
                                                         "--branch", "-1", "--trace", "B,C", "--save", "v.png"],
    "view of a linkage file, saved (view FILE, PNG)": ["view", str(PROJECT / "linkages" / "jansen.toml"), "--save",
                                                       "j.png"],
    "view of the four-bar by its lengths, saved (PNG)": ["view", "--crank", "20", "--coupler", "66", "--rocker", "56",
                                                         "--ground", "80", "--crank-angle", "30", "--branch", "-1",
                                                         "--save", "f.png"],
}


@pytest.mark.parametrize("name", PICTURES)
def test_a_warm_picture_imports_no_sympy_and_draws_the_same(name, shared_cache, tmp_path):
    arguments = PICTURES[name]
    out = arguments[-1]
    runs = run_twice(tmp_path, arguments, shared_cache, files=[out])
    assert "matplotlib" in runs.imported  # the import list was read, and it drew
    heavy = runs.imported & {"sympy", "scipy", "pandas", "distributed"}
    assert not heavy, f"the warm run imported {', '.join(sorted(heavy))}"
    assert runs.warm == runs.cold and runs.warm_notes == runs.cold_notes
    assert runs.warm_files[out] == runs.cold_files[out] and len(runs.cold_files[out]) > 1000


#: Command lines that write a folder (the files named, in ``tmp_path``) besides what they print: each run writes
#: them afresh (:func:`warm_runs.run_twice` reads and removes them), so the warm run resumes nothing.
FOLDERS = {
    "tolerance stack-up with sampled builds kept in a folder (three chunks, a manifest naming the definition)": (
        ["tolerance", "fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
         "--tolerance", "0.05", "--samples", "25000", "--folder", "mc", "--angles", "0,50", "--format", "csv"],
        ["mc/manifest.json", *(f"mc/chunk-{k:06d}.parquet" for k in range(3))]),
    "tolerance stack-up of a linkage file, its builds in a folder": (
        ["tolerance", str(PROJECT / "linkages" / "slider-crank.toml"), "--tolerance", "0.05", "--samples", "500",
         "--folder", "mc", "--angles", "0,40", "--format", "csv"], ["mc/manifest.json", "mc/chunk-000000.parquet"]),
}


@pytest.mark.parametrize("name", FOLDERS)
def test_a_warm_command_writing_a_folder_imports_no_sympy_and_writes_the_same(name, shared_cache, tmp_path):
    """Sampled builds kept in a ``--folder``: the warm run takes the definition's digest for the manifest from the
    cached facts (no SymPy), and writes the cold run's chunks and manifest, byte for byte; the manifest's digest is
    the SHA-256 of the linkage's definition, computed here from the linkage itself."""
    import hashlib
    import json

    from symlink.io.linkage_file import load_linkage
    from symlink.numeric.cache import definition
    pytest.importorskip("dask", reason="pip install -e '.[sweep]'")
    arguments, files = FOLDERS[name]
    runs = run_twice(tmp_path, arguments, shared_cache, files=files)
    assert "dask" in runs.imported and "pyarrow" in runs.imported  # the import list was read, and it sampled
    heavy = runs.imported & {"sympy", "matplotlib", "scipy", "pandas", "distributed"}
    assert not heavy, f"the warm run imported {', '.join(sorted(heavy))}"
    assert runs.warm == runs.cold and runs.warm_notes == runs.cold_notes and "0 chunks found done" in runs.warm_notes
    assert all(runs.warm_files[f] == runs.cold_files[f] for f in files)
    settings = json.loads(runs.warm_files["mc/manifest.json"])["settings"]
    assert settings["definition"] == hashlib.sha256(definition(load_linkage(arguments[1]).linkage).encode()).hexdigest()


def test_a_warm_drawing_takes_other_numbers(shared_cache, tmp_path):
    """A drawing's cache entries (its placement and its solver) are keyed by what names the linkage, not by the
    numbers: the four-bar with other lengths, at another angle, draws warm from the first drawing's entries (no
    SymPy), and writes what a cold run in a cache of its own writes, byte for byte."""
    run_twice(tmp_path, ["draw", "fourbar", "--trace", "C", "--out", "d.svg"], shared_cache)
    other = ["draw", "fourbar", "--set", "a=25,b=70,c=60,d=85", "--angle", "0.5", "--units", "rad", "--trace", "C",
             "--out", "d.svg"]
    warm = run_twice(tmp_path, other, shared_cache, files=["d.svg"])  # both runs warm
    assert "matplotlib" in warm.imported and not warm.imported & {"sympy", "scipy", "pandas"}
    (tmp_path / "fresh").mkdir()
    cold = run_twice(tmp_path / "fresh", other, files=["d.svg"])  # a cache of its own: its first run derives
    assert warm.cold_files["d.svg"] == cold.cold_files["d.svg"] == warm.warm_files["d.svg"]
    assert warm.cold == cold.cold == "wrote d.svg\n" and warm.cold_notes == cold.cold_notes == ""


def test_a_former_name_is_noted_once_warm_as_cold_by_a_drawing(shared_cache, tmp_path):
    """``symlink draw stephenson3`` says once, warm as cold, what the name names now."""
    runs = run_twice(tmp_path, PICTURES["Stephenson II by its former name, by Newton's method (draw NAME, SVG)"],
                     shared_cache, files=["s.svg"])
    assert runs.warm_notes == runs.cold_notes and runs.warm_notes.count("\n") == 1
    assert runs.warm_notes.startswith("symlink: warning: 'stephenson3' is symlink's former name of stephenson-ii")


PLAIN_DEFAULTS = """
[defaults]
a = 0.2
b = 0.66
c = 0.56
d = 0.8
"""
DYNAMICS = """m2 = 1.5
g = 9.81
T_load = 0.7

[dynamics]
gravity = [0, "-g"]

[dynamics.masses.crank]
mass = "m2"
distance = 0.08
inertia = 0.02

[[dynamics.torques]]
body = "crank"
torque = "T_load"
"""


def test_a_linkage_file_with_dynamics_is_drawn_as_without(shared_cache, tmp_path):
    """A linkage file whose [dynamics] table gives masses and loads, with their defaults, is drawn (warm without
    SymPy) as the same file without them is: masses and loads do not move a joint."""
    from symlink.io.linkage_file import linkage_text
    from symlink.mechanism.catalog import fourbar
    (tmp_path / "plain.toml").write_text(linkage_text(fourbar()) + PLAIN_DEFAULTS)
    (tmp_path / "massive.toml").write_text(linkage_text(fourbar()) + PLAIN_DEFAULTS + DYNAMICS)
    plain = run_twice(tmp_path, ["draw", "plain.toml", "--trace", "C", "--out", "d.svg"], shared_cache, files=["d.svg"])
    massive = run_twice(tmp_path, ["draw", "massive.toml", "--trace", "C", "--out", "d.svg"], shared_cache,
                        files=["d.svg"])
    assert not massive.imported & {"sympy", "scipy", "pandas"}
    assert massive.cold_files == massive.warm_files == plain.cold_files
    assert massive.warm == massive.cold == "wrote d.svg\n" and massive.warm_notes == massive.cold_notes == ""


def test_bad_input_to_a_warm_drawing_is_one_line_and_exit_2(shared_cache, tmp_path):
    """A warm drawing checks its values against the cached facts: a --set of no value, a point it does not have and
    a length that is not positive are refused in one line with exit status 2, in the words of a cold run, without
    importing SymPy."""
    import os
    import subprocess
    import sys

    from warm_runs import imported_packages, without_import_times
    run_twice(tmp_path, ["draw", "fourbar", "--out", "d.svg"], shared_cache)
    bad = {("--set", "q=1"): "symlink: error: --set: fourbar has no value 'q'; it takes a, b, c, d, theta\n",
           ("--trace", "Z"): "symlink: error: fourbar has no point or joint 'Z' to trace; it has A, B, C, D\n",
           ("--set", "a=-1"): "symlink: error: a must be a positive finite length, got -1.0\n"}
    env = {**os.environ, "PYTHONPATH": str(PROJECT), "SYMLINK_CACHE": str(shared_cache), "MPLBACKEND": "Agg"}
    for (option, value), message in bad.items():
        done = subprocess.run([sys.executable, "-X", "importtime", "-m", "symlink", "draw", "fourbar", option, value,
                               "--out", "bad.svg"], capture_output=True, text=True, env=env, cwd=str(tmp_path),
                              timeout=600)
        assert done.returncode == 2 and done.stdout == ""
        assert without_import_times(done.stderr) == message
        assert "symlink" in imported_packages(done.stderr) and "sympy" not in imported_packages(done.stderr)
        assert not (tmp_path / "bad.svg").exists()


#: Bad input to a warm ``symlink view NAME --save``: (the options) -> the error line of the cold run.
BAD_VIEWS = {
    ("--set", "q=1"): "symlink: error: --set: fourbar has no value 'q'; it takes a, b, c, d, theta\n",
    ("--trace", "Z"): "symlink: error: fourbar has no point or joint 'Z' to trace; it has A, B, C, D\n",
    # the length as given (the view named its slider's clamped value, -0.2, before)
    ("--set", "a=-1"): "symlink: error: a must be a positive finite length, got -1.0\n",
    ("--set", "a=1000"): "symlink: error: fourbar cannot be assembled at theta = 0\n",
}


@pytest.mark.parametrize("options", BAD_VIEWS)
def test_bad_input_to_a_warm_view_is_one_line_and_exit_2(options, shared_cache, tmp_path):
    """A warm view checks its values against the cached facts and placement: a --set of no value, a point it does
    not have, a length that is not positive and a linkage that cannot be assembled are refused in one line with exit
    status 2, in the words of a cold run (the first run below), without importing SymPy, and nothing is written."""
    import os
    import subprocess
    import sys

    from warm_runs import imported_packages, without_import_times
    env = {**os.environ, "PYTHONPATH": str(PROJECT), "SYMLINK_CACHE": str(shared_cache), "MPLBACKEND": "Agg"}
    runs = [subprocess.run([sys.executable, *flags, "-m", "symlink", "view", "fourbar", *options, "--save",
                            "bad.png"], capture_output=True, text=True, env=env, cwd=str(tmp_path), timeout=600)
            for flags in ([], ["-X", "importtime"])]
    for done in runs:
        assert done.returncode == 2 and done.stdout == ""
        assert without_import_times(done.stderr) == BAD_VIEWS[options]
        assert not (tmp_path / "bad.png").exists()
    assert "symlink" in imported_packages(runs[1].stderr) and "sympy" not in imported_packages(runs[1].stderr)


#: Sweeps of a catalog linkage and of a linkage file (the chunk is written into ``out``): the scheduler, and whether
#: its start may import Dask's distributed scheduler (a local scheduler's never does).
SWEEP = ["--grid", "3", "--samples", "36", "--no-progress"]
SWEEPS = {
    "four-bar, synchronous": (["sweep", "fourbar", "out", "--vary", "a=10:20", "--set", "b=66,c=56,d=80", *SWEEP,
                               "--scheduler", "synchronous"], 1),
    "four-bar, threads": (["sweep", "fourbar", "out", "--vary", "a=10:20,c=50:60", "--set", "b=66,d=80", *SWEEP,
                           "--scheduler", "threads", "--workers", "2", "--chunk", "5"], 2),
    "slider-crank file (transmission at its guide), default scheduler": (
        ["sweep", str(PROJECT / "linkages" / "slider-crank.toml"), "out", "--vary", "a=0.5:2.5", *SWEEP], 1),
}


@pytest.mark.parametrize("name", SWEEPS)
def test_a_warm_sweep_imports_no_sympy_and_writes_the_same_chunks(name, shared_cache, tmp_path):
    """A sweep whose linkage's facts and solver are in the disk cache imports no SymPy (a catalog linkage and a
    linkage file), and its start only what its scheduler needs (never distributed or pandas on a local one); its
    chunks and manifest are the cold run's, byte for byte (each run writes them afresh: the first run's are read
    and removed), and it prints the same but for the rate."""
    import re
    from symlink.workshop.sweep import missing_modules
    if missing_modules():
        pytest.skip("the sweep extra is not installed")
    arguments, chunks = SWEEPS[name]
    files = [f"out/chunk-{k:06d}.parquet" for k in range(chunks)] + ["out/manifest.json"]
    runs = run_twice(tmp_path, arguments, shared_cache, files=files)
    assert "dask" in runs.imported and "pyarrow" in runs.imported  # the import list was read, and it swept
    heavy = runs.imported & {"sympy", "scipy", "matplotlib", "distributed", "pandas"}
    assert not heavy, f"the warm run imported {', '.join(sorted(heavy))}"
    assert runs.warm == runs.cold == "out\n"
    assert all(runs.warm_files[f] == runs.cold_files[f] for f in files)
    assert b'"reach"' in runs.cold_files["out/manifest.json"] and len(runs.cold_files[files[0]]) > 1000

    def unrated(notes: str) -> str:
        return re.sub(r"; [0-9.e+-]+ designs/s", "", notes)
    assert unrated(runs.warm_notes) == unrated(runs.cold_notes)
    assert f"wrote {chunks}, found 0 already there" in runs.warm_notes  # it evaluated every chunk again


def test_bad_input_to_a_warm_stack_up_is_one_line_and_exit_2(shared_cache, tmp_path):
    """A warm stack-up checks its options against the cached facts: an unknown dimension, a --set of no value and
    the four-bar's lengths given to another linkage are refused in one line with exit status 2, in the words of a
    cold run, without importing SymPy."""
    import os
    import subprocess
    import sys

    from warm_runs import imported_packages, without_import_times
    run_twice(tmp_path, ["tolerance", "slider-crank", "--tolerance", "0.05", "--angles", "0", "--format", "csv"],
              shared_cache)
    bad = {("--tolerances", "e=0.1"): "symlink: error: --tolerances: slider-crank has no dimension 'e'; it has a, b, "
                                       "offset\n",
           ("--set", "q=1"): "symlink: error: --set: slider-crank has no value 'q'; it takes a, b, offset, theta\n",
           ("--crank", "2"): "symlink: error: tolerance: --crank --coupler --rocker --ground belong to the four-bar; "
                             "give the values of slider-crank with --set NAME=VALUE,...\n",
           # each of the four-bar's dynamics options is refused on another linkage, never silently left out
           ("--masses", "1,2,3"): "symlink: error: tolerance: --masses and the other dynamics options belong to the "
                                  "four-bar\n",
           ("--inertias", "1,2,3"): "symlink: error: tolerance: --inertias and the other dynamics options belong to "
                                    "the four-bar\n",
           ("--gravity", "9.81"): "symlink: error: tolerance: --gravity and the other dynamics options belong to the "
                                  "four-bar\n",
           ("--load-torque", "-2"): "symlink: error: tolerance: --load-torque and the other dynamics options belong "
                                    "to the four-bar\n"}
    env = {**os.environ, "PYTHONPATH": str(PROJECT), "SYMLINK_CACHE": str(shared_cache)}
    for (option, value), message in bad.items():
        done = subprocess.run([sys.executable, "-X", "importtime", "-m", "symlink", "tolerance", "slider-crank",
                               "--tolerance", "0.05", option, value], capture_output=True, text=True, env=env,
                              cwd=str(tmp_path), timeout=600)
        assert done.returncode == 2 and done.stdout == ""
        assert without_import_times(done.stderr) == message
        assert "symlink" in imported_packages(done.stderr) and "sympy" not in imported_packages(done.stderr)


NEWTON_SCENE = """\
linkage = "stephenson2"
outputs = ["coupler", "mu", "rocker", "eta", "rocker_speed", "eta_accel"]
format = "csv"

[parameters]
a = 1
b = 3.1
c = 2.2
d = 4.5
e = 3.9
f = 3.1
g = 4.1
h = 3.1
alpha = 0.8988445647770797
delta = 0.30019663134302466

[input]
angles = [0, 50, 100]
speed = 2
accel = 1

[guess]
coupler = -33
mu = -35
rocker = -73
eta = -68
"""


def test_a_warm_newton_scene_imports_no_sympy_and_prints_the_same(shared_cache, tmp_path):
    """``symlink run`` of a scene without a closed form (Newton's method from its [guess]): the second run is warm,
    and another scene of the same linkage with other numbers is warm from its first run."""
    (tmp_path / "six.toml").write_text(NEWTON_SCENE)
    runs = run_twice(tmp_path, ["run", "six.toml"], shared_cache)
    assert "symlink" in runs.imported and "numpy" in runs.imported
    assert not runs.imported & {"sympy", "matplotlib"}, sorted(runs.imported)
    assert runs.warm == runs.cold and runs.warm_notes == runs.cold_notes
    assert runs.warm.splitlines()[0] == "crank,branch,coupler,mu,rocker,eta,rocker_speed,eta_accel"
    assert len(runs.warm.splitlines()) == 4
    other = NEWTON_SCENE.replace("angles = [0, 50, 100]", "angles = [0, 20]").replace("b = 3.1", "b = 3.2")
    (tmp_path / "other.toml").write_text(other)
    again = run_twice(tmp_path, ["run", "other.toml"], shared_cache)
    assert not again.imported & {"sympy", "matplotlib"} and again.warm == again.cold
    assert again.warm.splitlines()[1] != runs.warm.splitlines()[1]


#: ``symlink flywheel`` of the example of its help (metres, kilograms: N m, J, kg m^2).
FLYWHEEL = ["flywheel", "--crank", "0.2", "--coupler", "0.66", "--rocker", "0.56", "--ground", "0.8", "--masses",
            "1,2,1.5", "--inertias", "0.03,0.07,0.04", "--gravity", "9.81", "--load-torque", "-15", "--rpm", "300",
            "--coefficient", "0.05", "--format", "csv"]


def test_a_warm_flywheel_imports_no_sympy_and_prints_the_same(shared_cache, tmp_path):
    """``symlink flywheel`` runs its equation of motion and driving torque from the disk cache, keyed by the options'
    numbers: the warm run builds no model and imports no SymPy.  SciPy stays: the speed band integrates the forward
    dynamics (solve_ivp) and the exact inertia is a root (brentq).  Another ground length is warm too (not in the
    key: a parameter of the code), and a bad one is refused warm in the cold run's words, exit status 2."""
    import os
    import subprocess
    import sys

    from warm_runs import imported_packages, without_import_times
    pytest.importorskip("scipy", reason="pip install -e '.[dynamics]'")
    runs = run_twice(tmp_path, FLYWHEEL, shared_cache)
    assert "symlink" in runs.imported and "scipy" in runs.imported  # the import list was read, and it integrated
    assert not runs.imported & {"sympy", "matplotlib", "pandas"}, sorted(runs.imported)
    assert runs.warm == runs.cold and runs.warm_notes == runs.cold_notes
    header, row = runs.warm.splitlines()
    cells = dict(zip(header.split(","), map(float, row.split(","))))
    assert cells["mean_speed"] == pytest.approx(300 * 2 * math.pi / 60, rel=1e-15)
    # the textbook flywheel is dE / (Cs w^2), from the printed energy fluctuation (seed-independent arithmetic)
    assert cells["flywheel_inertia"] == pytest.approx(cells["energy_fluctuation"] / (0.05 * cells["mean_speed"] ** 2),
                                                      rel=1e-12)
    other = [*FLYWHEEL]
    other[other.index("--ground") + 1] = "0.85"
    again = run_twice(tmp_path, other, shared_cache)  # both runs warm: the first command's entries serve it
    assert not again.imported & {"sympy", "matplotlib"} and again.warm == again.cold and again.warm != runs.warm
    bad = [*FLYWHEEL]
    bad[bad.index("--ground") + 1] = "-0.8"
    env = {**os.environ, "PYTHONPATH": str(PROJECT), "SYMLINK_CACHE": str(shared_cache)}
    done = subprocess.run([sys.executable, "-X", "importtime", "-m", "symlink", *bad], capture_output=True, text=True,
                          env=env, cwd=str(tmp_path), timeout=600)
    assert done.returncode == 2 and done.stdout == ""
    assert without_import_times(done.stderr) == "symlink: error: ground must be a positive finite length, got -0.8\n"
    assert "sympy" not in imported_packages(done.stderr)


def test_analyze_by_lengths_derives_nothing_and_imports_no_sympy_even_cold(tmp_path):
    """``symlink analyze --crank ...`` is closed-form geometry: in a fresh cache both runs print the same, neither
    writes a cache entry, and the second imports no SymPy.  The change-point four-bar 2, 1, 1, 2 (B passes over D
    at crank 0) used to print nan for its transmission angle: by hand the triangle over BD is flat there (BD = 0,
    mu = 0), and its crank stops where cos(theta) = (4 + 4 - 4) / 8, at 60 degrees, where BD = b + c (mu = 180)."""
    runs = run_twice(tmp_path, ["analyze", "--crank", "2", "--coupler", "1", "--rocker", "1", "--ground", "2"])
    assert not runs.imported & {"sympy", "matplotlib", "scipy"}
    assert runs.warm == runs.cold and runs.warm_notes == runs.cold_notes == ""
    assert not list((tmp_path / "cache").glob("*.json"))  # nothing derived
    assert "nan" not in runs.warm
    assert runs.warm.splitlines()[-1] == "transmission angle   0.0000 at crank 0.0000 to 180.0000 at crank -60.0000 deg"
    assert "crank range          [-60.0000, 0.0000] deg, [0.0000, 60.0000] deg" in runs.warm


def test_a_warm_analysis_takes_other_values_and_outputs(shared_cache, tmp_path):
    """The cached analysis of a linkage is keyed by what names it, not by its values: after one cold run, other
    --set values and --branch run warm (no SymPy) and print what a fresh cold run prints; the four-bar's limit
    positions by name agree with its closed form (the rocker's stroke by hand: the triangle A, D, C with AC of
    length b + a and b - a)."""
    import json
    run_twice(tmp_path, ["analyze", "fourbar", "--output", "phi"], shared_cache)
    other = ["analyze", "fourbar", "--set", "a=20,b=66,c=56,d=80", "--branch", "-1", "--output", "phi", "--format",
             "json"]
    warm = run_twice(tmp_path, other, shared_cache)
    assert not warm.imported & {"sympy", "matplotlib", "scipy"}
    (tmp_path / "fresh").mkdir()
    cold = run_twice(tmp_path / "fresh", other)
    assert warm.warm == cold.cold
    report = json.loads(warm.warm)
    a, b, c, d = 20, 66, 56, 80
    extended = math.pi - math.acos((c * c + d * d - (a + b) ** 2) / (2 * c * d))
    folded = math.pi - math.acos((c * c + d * d - (b - a) ** 2) / (2 * c * d))
    assert report["limits"]["stroke"] == pytest.approx(math.degrees(folded - extended), abs=1e-9)


#: ``symlink analyze NAME|FILE --output X`` where X has no limit positions: (linkage, output) -> the error line.  The
#: words are those of the derivation (``Linkage.output``, ``check_position_output``); a sensitivity's name was an
#: internal error (the output's code took it as an argument it was not given).
REFUSED_OUTPUTS = {
    ("fourbar", "phidot"): "'phidot' is not a position output of fourbar; give a coordinate, role, point coordinate "
                           "or extra",
    ("fourbar", "thetadot"): "'thetadot' is not a position output of fourbar; give a coordinate, role, point "
                             "coordinate or extra",
    ("fourbar", "rocker_accel"): "'rocker_accel' is not a position output of fourbar; give a coordinate, role, point "
                                 "coordinate or extra",
    ("fourbar", "singular"): "'singular' is not a position output of fourbar; give a coordinate, role, point "
                             "coordinate or extra",
    ("fourbar", "phi__d_a"): "'phi__d_a' is not a position output of fourbar; give a coordinate, role, point "
                             "coordinate or extra",
    ("fourbar", "nosuch"): "fourbar has no output 'nosuch'; it has beta, phi, betadot, phidot, betaddot, phiddot, "
                           "crank, crank_speed, crank_accel, coupler, coupler_speed, coupler_accel, rocker, "
                           "rocker_speed, rocker_accel, A_x, A_y, B_x, B_y, C_x, C_y, D_x, D_y, transmission, singular",
    ("slider-crank.toml", "slider_speed"): "'slider_speed' is not a position output of slider-crank; give a "
                                           "coordinate, role, point coordinate or extra",
}


@pytest.mark.parametrize("linkage, output", REFUSED_OUTPUTS)
def test_a_warm_analysis_refuses_an_output_without_limit_positions_in_one_line(linkage, output, shared_cache,
                                                                                 tmp_path):
    """An output that is no position output (a rate, an acceleration, the singularity flag, a sensitivity) or not
    an output at all is refused warm from the cached facts (its names and kinds), without SymPy, in the cold run's
    one line, exit status 2."""
    import os
    import subprocess
    import sys

    from warm_runs import imported_packages, without_import_times
    named = str(PROJECT / "linkages" / linkage) if linkage.endswith(".toml") else linkage
    env = {**os.environ, "PYTHONPATH": str(PROJECT), "SYMLINK_CACHE": str(shared_cache)}
    runs = [subprocess.run([sys.executable, *flags, "-m", "symlink", "analyze", named, "--output", output],
                           capture_output=True, text=True, env=env, cwd=str(tmp_path), timeout=600)
            for flags in ([], ["-X", "importtime"])]
    for done in runs:
        assert done.returncode == 2 and done.stdout == ""
        assert without_import_times(done.stderr) == f"symlink: error: {REFUSED_OUTPUTS[linkage, output]}\n"
    assert "symlink" in imported_packages(runs[1].stderr) and "sympy" not in imported_packages(runs[1].stderr)
