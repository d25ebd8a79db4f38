"""The benchmark (``benchmarks/bench.py``, ``symlink bench``): it runs, writes valid records, and its references and baselines are right (no timings)."""
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy
import pytest

from cache_fixture import empty_cache  # noqa: F401 - a fixture
from references import mp_fourbar, seed003_positions
from symlink.reachability import crank_range
from benchmarks.bench import (METHODS, SEED_LINKAGES, benchmark, hand_numpy, is_grashof, newton, reference_positions,
                           targets, workload)
from symlink.cli import main

REQUIRED = {"symlink", "symlink-positions", "hand-numpy", "lambdify-nocse", "newton", "sympy-evalf"}


pytestmark = pytest.mark.usefixtures("empty_cache")  # every test derives from scratch


def has_scipy():
    try:
        import scipy.optimize  # noqa: F401
    except ImportError:
        return False
    return True


def test_quick_run_writes_records_and_plot(tmp_path, capsys):
    records, picture = tmp_path / "bench.json", tmp_path / "bench.png"
    status = main(["bench", "--quick", "--sizes", "120", "--json", str(records), "--plot", str(picture)])
    out, err = capsys.readouterr()
    assert status == 0, err
    found = json.loads(records.read_text())
    assert isinstance(found, list) and found
    for record in found:
        assert {"method", "n", "us_per_value", "max_error"} <= set(record)
        assert record["method"] in METHODS and record["n"] >= 1 and record["us_per_value"] > 0
    names = {r["method"] for r in found}
    assert REQUIRED | ({"fsolve"} if has_scipy() else set()) <= names
    by_name = {r["method"]: r for r in found}
    for name in ("symlink", "symlink-positions", "hand-numpy", "sympy-evalf"):
        assert by_name[name]["max_error"] < 1e-9, name  # closed forms, against 50 digits
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "us/value" in out and "symlink-positions / hand-numpy" in out
    assert "from cache" in out and "loading the generated module" in out


ROOT = Path(__file__).parent.parent


@pytest.mark.parametrize("command", [["-m", "benchmarks"], [str(ROOT / "benchmarks" / "bench.py")]])
def test_entry_points_and_method_choice_progress_on_stderr(tmp_path, command):
    records = tmp_path / "r.json"
    done = subprocess.run([sys.executable, *command, "--sizes", "60", "--methods", "hand-numpy,newton",
                           "--no-derivation", "--json", str(records)], capture_output=True, text=True,
                          cwd=ROOT if command[0] == "-m" else tmp_path)  # the script runs from anywhere
    assert done.returncode == 0, done.stderr
    assert sorted(r["method"] for r in json.loads(records.read_text())) == ["hand-numpy", "newton"]
    assert "N = 60" in done.stderr and "us/value" in done.stderr  # progress
    assert "N = 60" not in done.stdout and done.stdout.splitlines()[0].split()[:2] == ["method", "N"]  # results


def test_symlink_bench_without_the_source_checkout_says_so_in_one_line(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "benchmarks", None)  # as if benchmarks/ were not importable
    monkeypatch.setitem(sys.modules, "benchmarks.bench", None)
    assert main(["bench", "--quick"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and err.startswith("symlink: error: symlink bench needs")


def test_failed_write_is_one_line_exit_1(tmp_path, capsys):
    (tmp_path / "taken").mkdir()  # a folder where the file should go
    status = main(["bench", "--sizes", "30", "--methods", "hand-numpy", "--no-derivation",
                   "--json", str(tmp_path / "taken")])
    _, err = capsys.readouterr()
    errors = [line for line in err.splitlines() if ": error:" in line or "Traceback" in line]
    assert status == 1 and len(errors) == 1 and errors[0].startswith("symlink: error: cannot write")
    assert err.endswith(errors[0] + "\n")  # after the progress lines, and nothing after it
    assert [p.name for p in tmp_path.iterdir()] == ["taken"]  # no temporary file left


@pytest.mark.parametrize("argv, message", [
    (["--methods", "abacus"], "unknown method 'abacus'"),
    (["--sizes", "0"], "--sizes must be positive whole numbers"),
    (["--sizes", "1.5"], "--sizes must be positive whole numbers"),
    (["--json", "/no/such/folder/x.json"], "no folder /no/such/folder"),
    (["--sizes", "x"], "not a number"),
])
def test_bad_options_one_line_exit_2(capsys, argv, message):
    status = main(["bench", "--no-derivation", *argv])
    _, err = capsys.readouterr()
    assert status == 2 and err.count("\n") == 1 and message in err


def test_missing_optional_methods_are_skipped_with_a_note(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "scipy.optimize", None)
    monkeypatch.setitem(sys.modules, "symlink.compiled", None)
    status = main(["bench", "--sizes", "40", "--methods", "fsolve,symlink-c,hand-c,hand-numpy", "--no-derivation"])
    out, err = capsys.readouterr()
    assert status == 0
    assert "skipped fsolve: scipy is not installed" in err  # a note, with the progress
    assert "skipped symlink-c" in err and "skipped hand-c" in err
    assert "hand-numpy" in out.split("method")[-1]


def test_reference_agrees_with_the_independent_one():
    rng = numpy.random.default_rng(5)
    for name, lengths in SEED_LINKAGES.items():
        for theta in rng.uniform(-math.pi, math.pi, 5):
            for branch in (1, -1):
                mine = reference_positions(*lengths, theta, branch)
                try:
                    theirs = mp_fourbar(*lengths, theta=theta, branch=branch)
                except ValueError:
                    assert mine is None
                    continue
                assert abs(float(mine[0] - theirs["beta"])) < 1e-40
                assert abs(float(mine[1] - theirs["phi"])) < 1e-40


def test_hand_numpy_is_the_seed_formula():
    theta = numpy.radians(numpy.arange(0.0, 360.0, 7.0))
    lengths = SEED_LINKAGES["seed003"]
    for branch in (1, -1):
        numpy.testing.assert_allclose(hand_numpy(theta, *lengths, branch),
                                      seed003_positions(*lengths, theta, branch), rtol=0, atol=1e-13)


def test_newton_converges_from_the_offset_start():
    lengths, theta = SEED_LINKAGES["seed003"], numpy.radians([10.0, 100.0, 250.0])
    expected = [mp_fourbar(*lengths, theta=t, branch=1) for t in theta]
    beta, phi = newton(theta, *lengths, numpy.array([float(e["beta"]) + 0.05 for e in expected]),
                       numpy.array([float(e["phi"]) - 0.05 for e in expected]))
    numpy.testing.assert_allclose(phi, [float(e["phi"]) for e in expected], rtol=0, atol=1e-13)
    numpy.testing.assert_allclose(beta, [float(e["beta"]) for e in expected], rtol=0, atol=1e-13)


def test_workload_is_fixed_and_covers_both_classes_and_branches():
    first, again = workload(500, 7, 100), workload(500, 7, 100)
    assert sum(len(s.theta) for s in first) == 500
    assert all(numpy.array_equal(s.theta, t.theta) for s, t in zip(first, again))
    assert {s.branch for s in first} == {1, -1}
    assert {is_grashof(*s.lengths) for s in first} == {True, False}
    assert {s.lengths for s in first} >= set(SEED_LINKAGES.values())
    for sweep in first:
        spans = crank_range(*sweep.lengths)
        assert all(any(lo <= t <= hi for lo, hi in spans) for t in sweep.theta)
    assert 80 <= sum(len(s.sample) for s in first) <= 120


def test_records_carry_errors_and_residuals():
    records = benchmark(sizes=[90], methods=["symlink-positions", "newton"], reference=90, verbose=False)
    for record in records:
        assert record["reference_n"] == 90 and record["failures"] == 0
        assert record["max_residual"] < 1e-12 and record["median_error"] <= record["max_error"]


def test_target_lines_state_the_ratios():
    records = [
        {"method": "symlink", "n": 1000, "us_per_value": 0.2, "max_error": 1e-15, "failures": 0},
        {"method": "symlink-positions", "n": 1000, "us_per_value": 0.08, "max_error": 1e-15, "failures": 0},
        {"method": "hand-numpy", "n": 1000, "us_per_value": 0.1, "max_error": 1e-13, "failures": 0},
        {"method": "fsolve", "n": 100, "us_per_value": 30.0, "max_error": 1e-10, "failures": 0},
    ]
    lines = "\n".join(targets(records))
    assert "symlink-positions / hand-numpy at N=1000: 0.80x (target <= 1.3x: held)" in lines
    assert "at least as accurate: held" in lines
    assert "symlink-positions / symlink at N=1000: 0.40x (target <= 0.5x: held)" in lines
    # fsolve solves positions only: compared with symlink-positions, 30 / 0.08 = 375
    assert "fsolve (100 values) / symlink-positions at N=1000, per value: 375x (target >= 100x: held)" in lines
    records[1]["us_per_value"] = 0.15
    assert "target <= 1.3x: MISSED" in "\n".join(targets(records))


def test_stacked_call_gives_the_per_sweep_results():
    from benchmarks.bench import hand_numpy, stacked, unstacked, workload
    sweeps = workload(90, seed=3, reference=10)
    together = unstacked(hand_numpy(*(lambda s: (s.theta, *s.lengths, s.branch))(stacked(sweeps))), sweeps)
    for sweep, (beta, phi) in zip(sweeps, together):
        alone = hand_numpy(sweep.theta, *sweep.lengths, sweep.branch)
        assert numpy.array_equal(alone[0], beta) and numpy.array_equal(alone[1], phi)
