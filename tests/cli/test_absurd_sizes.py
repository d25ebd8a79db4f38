"""Every count and sampling option of every command, at absurd sizes: refused before any work, in one line.

Each row is a command line with one count (``{n}``) or one step (``{tiny}``, a full turn over ``{n}``) made
absurd: 1e9, 1e12, 1e18 and 2**63 - 1 (the largest whole number an option takes; 2**63 itself is
refused as out of range by the one number reader, before any estimate).  Each must end with exit status 2 and one line on stderr that gives an
estimate (``about``: the time, memory or values the request would take) or the limit it is over, and must
write nothing (the request is refused before anything is derived, allocated or written).
"""
from __future__ import annotations

import math
import re

import pytest

from symlink.cli import main

SIZES = [10**9, 10**12, 10**18, 2**63 - 1]
FOURBAR = ["--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80"]
STEPHENSON2 = ["--crank", "1", "--coupler", "3.1", "--link-cf", "2.2", "--ground", "4.5", "--coupler-arm", "3.9",
               "--rocker", "3.1", "--link-eh", "4.1", "--rocker-arm", "3.1", "--coupler-arm-angle", "51.5",
               "--rocker-arm-angle", "17.2"]
SWEEP = ["sweep", "fourbar", "out", "--vary", "a=10:20", "--set", "b=66,c=56,d=80", "--no-progress"]
#: A sweep on one worker (``--scheduler synchronous``) at 6e5 values a second (the command's own rate) fits 6e6
#: designs of 360 samples in the default hour: a grid of 6e6 values of one parameter, or 2449 of two.
STEPS = r"about [\d.e+]+ input values is too many \(at most 10,000,000 a sweep\); use --step [\d.e-]+ or larger"
TAKES = r"would take about .+ \(at most 60 min a command, --time-budget\); use "

#: name: (the command line, the pattern of its one line, whether it needs the sweep extra)
CASES = {
    "fourbar --step": (["fourbar", *FOURBAR, "--step", "{tiny}"], STEPS),
    "fourbar --masses --step": (["fourbar", *FOURBAR, "--masses", "1,2,3", "--step", "{tiny}"], STEPS),
    "table (closed form) --step": (["table", "watt2", "--branch", "+1", "--step", "{tiny}"], STEPS),
    "table (no closed form) --step": (["table", "stephenson2", "--guess", "coupler=-33,mu=-35,rocker=-73,eta=-68",
                                       "--step", "{tiny}"], STEPS),
    "table (atlas) --step": (["table", "atlas:watt-ii", "--branch", "+1", "--step", "{tiny}"], STEPS),
    "stephenson2 --step": (["stephenson2", *STEPHENSON2, "--step", "{tiny}"], STEPS),
    "scene file step": (["run", "scene.toml"], "scene.toml: input: " + STEPS.replace("--step", "step")),
    "tolerance --samples": (["tolerance", "fourbar", *FOURBAR, "--tolerance", "0.1", "--angles", "0,30",
                             "--samples", "{n}"],
                            r"[\d,]+ builds x 2 input values x 1 output are [\d,]+ values \(about .+ of memory\), more "
                            r"than the 50,000,000 sample_builds keeps; ask for at most 25,000,000 builds"),
    "tolerance --step": (["tolerance", "fourbar", *FOURBAR, "--tolerance", "0.1", "--step", "{tiny}"], STEPS),
    "animate --frames": (["animate", "fourbar", "--frames", "{n}", "--out", "a.gif"],
                         r"--frames [\d,]+ would take about .+ to draw \(at most 3,600 frames\); use --frames 3,600 "
                         r"or fewer"),
    "flywheel --samples": (["flywheel", *FOURBAR, "--masses", "1,2,3", "--rpm", "100", "--coefficient", "0.05",
                            "--samples", "{n}"],
                           r"a flywheel of --samples \d+ would need about .+ of memory \(at most .+ a command\); use "
                           r"--samples [\d,]+ or fewer"),
    "sweep --grid": ([*SWEEP, "--scheduler", "synchronous", "--grid", "{n}"],
                     r"a sweep of [\d.e+]+ designs of 360 samples " + TAKES + "--grid 6,000,000 or fewer"),
    "sweep --grid of two": ([*SWEEP[:4], "a=10:20,b=60:70", "--set", "c=56,d=80", "--no-progress", "--scheduler",
                             "synchronous", "--grid", "{root}"],
                            r"a sweep of [\d.e+]+ designs of 360 samples " + TAKES + "--grid 2,449 or fewer"),
    "sweep --random": ([*SWEEP, "--scheduler", "synchronous", "--random", "{n}"],
                       r"a sweep of [\d.e+]+ designs of 360 samples " + TAKES + "--random 6,000,000 or fewer"),
    "sweep --samples": ([*SWEEP, "--scheduler", "synchronous", "--grid", "5", "--samples", "{n}"],
                        r"a sweep of 5 designs of \d+ samples " + TAKES + "--grid [\\d,]+ or fewer|.*use fewer "
                        r"--samples"),
    "sweep --workers": ([*SWEEP, "--scheduler", "threads", "--grid", "5", "--workers", "{n}"],
                        r"[\d,]+ workers evaluating chunks of 360 samples at once would need about .+ of memory even "
                        r"with --chunk 1 \(at most 1.5 GB\); use --workers [\d,]+ or fewer"),
    "sweep --harmonics": ([*SWEEP, "--scheduler", "synchronous", "--grid", "5", "--harmonics", "{n}"],
                          r"[\d,]+ harmonics need at least [\d,]+ samples a turn; with 360 samples use at most 179 "
                          r"harmonics"),
    "synthesize path --starts": (["synthesize", "path", "points.csv", "--starts", "{n}"],
                                 r"a path synthesis of 5 points from [\d,]+ starts could take about .+ \(at most 60 "
                                 r"min a command, --time-budget\); use --starts 7,200 or fewer"),
    "synthesize path LINKAGE --starts": (["synthesize", "path", "fourbar", "points.csv", "--free", "a,b",
                                          "--point", "C", "--starts", "{n}"],
                                         r"a path synthesis of 5 points from [\d,]+ starts could take about .+; use "
                                         r"--starts 7,200 or fewer"),
    "synthesize path LINKAGE --shape --samples": (["synthesize", "path", "fourbar", "points.csv", "--free", "a,b",
                                                   "--point", "C", "--shape", "--samples", "{n}"],
                                                  r"a shape match of --samples [\d,]+ " + TAKES +
                                                  r"--samples 360,000 or fewer"),
    "synthesize function LINKAGE --starts": (["synthesize", "function", "fourbar", "function.csv", "--free", "b,c",
                                              "--set", "a=1,d=3.2", "--starts", "{n}"],
                                             r"a function synthesis of 4 points from [\d,]+ starts could take about "
                                             r".+; use --starts 9,000 or fewer"),
    "synthesize motion LINKAGE --starts": (["synthesize", "motion", "fourbar", "poses.csv", "--free", "b", "--set",
                                            "a=1,c=2.5,d=3.2", "--angle", "coupler", "--starts", "{n}"],
                                           r"a motion synthesis of 3 points from [\d,]+ starts could take about .+; "
                                           r"use --starts 12,000 or fewer"),
}

FILES = {
    "points.csv": "x,y\n1,1\n1.2,1.3\n1.1,1.6\n0.8,1.5\n0.7,1.2\n",
    "function.csv": "theta,rocker\n10,20\n40,35\n70,50\n100,65\n",
    "poses.csv": "x,y,angle\n1,1,5\n1.5,1.2,10\n2,1.1,15\n",
}


def scene(step: float) -> str:
    return ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 20\nb = 66\nc = 56\nd = 80\n'
            f"[input]\nstart = 0\nstop = 360\nstep = {step!r}\n")


@pytest.mark.parametrize("size", SIZES, ids=["1e9", "1e12", "1e18", "2**63-1"])
@pytest.mark.parametrize("name", CASES)
def test_an_absurd_size_is_refused_in_one_line_with_its_estimate(name, size, tmp_path, monkeypatch, capsys):
    if name.startswith("sweep"):
        pytest.importorskip("dask")
        pytest.importorskip("pyarrow")
    monkeypatch.chdir(tmp_path)
    for file, text in {**FILES, "scene.toml": scene(360 / size)}.items():
        (tmp_path / file).write_text(text)
    before = sorted(p.name for p in tmp_path.iterdir())
    arguments, pattern = CASES[name]
    root = math.isqrt(size)  # two swept parameters on a grid of root: size designs
    arguments = [a.format(n=size, tiny=360 / size, root=root) for a in arguments]
    assert main(arguments) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("symlink: error: "), captured.err
    message = lines[0][len("symlink: error: "):]
    assert re.fullmatch(pattern, message), message
    assert "about" in message or "at most" in message  # the estimate, or the limit it is over
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # nothing written


def test_a_sweep_of_a_billion_designs_fits_a_raised_time_budget_only():
    """The estimate against the budget, by hand: 1e9 designs x 360 samples at 6e5 values a second on one worker
    are 6e5 s (6.9 days): over the default hour, and over --time-budget 6d, within 7d."""
    from symlink.cli.budget import use_time_budget
    from symlink.cli.sweep import estimate_sweep
    try:
        with pytest.raises(ValueError, match=r"about 6.9 days on 1 worker \(at most 60 min a command, "
                                             r"--time-budget\); use --random 6,000,000 or fewer"):
            estimate_sweep(10**9, 360, 1000, "synchronous", None, 1, "random")
        use_time_budget(6 * 86400)
        with pytest.raises(ValueError, match=r"at most 6 days a command, --time-budget\); use --grid 864,000,000 or "
                                             r"fewer"):
            estimate_sweep(10**9, 360, 1000, "synchronous", None, 1, "grid")
        use_time_budget(7 * 86400)
        assert estimate_sweep(10**9, 360, 1000, "synchronous", None, 1, "grid") == pytest.approx(1e9 * 360 / 6e5)
    finally:
        use_time_budget(None)


@pytest.mark.parametrize("text, seconds", [("90", 90.0), ("90s", 90.0), ("30m", 1800.0), ("2.5h", 9000.0),
                                           ("7d", 604800.0), ("365d", 365 * 86400.0)])
def test_time_budgets_read_as_durations(text, seconds):
    from symlink.cli.budget import duration
    assert duration(text) == seconds


@pytest.mark.parametrize("text", ["", "h", "0", "0.5", "-1h", "366d", "2y", "1e400", "nan", "inf", "1 week",
                                  "__import__('os')"])
def test_a_bad_time_budget_is_refused_in_one_line(text, capsys):
    assert main(["flywheel", *FOURBAR, "--masses", "1,2,3", "--rpm", "100", "--coefficient", "0.05",
                 "--time-budget", text]) == 2
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("symlink: error: argument --time-budget: "), lines


def test_a_raised_time_budget_lets_a_long_search_through(tmp_path, monkeypatch, capsys):
    """7,201 starts of 5 points at 0.1 s a point and start are 3600.5 s: refused by the hour, taken by 2h (the
    search is then stopped by its first check: a csv with a repeated point)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "points.csv").write_text(FILES["points.csv"])
    assert main(["synthesize", "path", "points.csv", "--starts", "7201"]) == 2
    assert "use --starts 7,200 or fewer" in capsys.readouterr().err
    (tmp_path / "twice.csv").write_text(FILES["points.csv"] + "1,1\n")
    assert main(["synthesize", "path", "twice.csv", "--starts", "7201", "--time-budget", "2h"]) == 2
    err = capsys.readouterr().err
    assert "starts" not in err and "the same point" in err, err
