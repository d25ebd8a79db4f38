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
from symlink.numeric.reachability import crank_range
from benchmarks.bench import (EVERYTHING, METHODS, SEED_LINKAGES, Method, benchmark, halfangle_numpy, hand_numpy,
                               hand_rates, is_grashof, newton, pylinkage_sweeps, reference_positions, reference_rates,
                               targets, workload)
from symlink.cli import main

#: The peers of the bench extra, and what each needs.
OPTIONAL = {"numba": "numba", "numba-positions": "numba", "symengine-llvm": "symengine",
            "symengine-llvm-positions": "symengine", "pylinkage": "pylinkage", "pylinkage-positions": "pylinkage",
            "fsolve": "scipy.optimize"}


pytestmark = pytest.mark.usefixtures("empty_cache")  # every test derives from scratch


def installed(module: str) -> bool:
    try:
        __import__(module)
    except ImportError:
        return False
    return True


def test_quick_run_writes_records_and_plot(tmp_path, capsys):
    records, picture = tmp_path / "bench.json", tmp_path / "bench.png"
    status = main(["bench", "--quick", "--sizes", "120", "--json", str(records), "--plot", str(picture),
                   "--no-derivation", "--methods", "symlink,symlink-positions,hand-numpy,hand-numpy-positions,"
                   "halfangle-numpy,newton,fsolve"])
    out, err = capsys.readouterr()
    assert status == 0, err
    found = json.loads(records.read_text())
    assert isinstance(found, list) and found
    for record in found:
        assert {"method", "n", "us_per_value", "max_error"} <= set(record)
        assert record["method"] in METHODS + ("physical-limit",) and record["n"] >= 1 and record["us_per_value"] > 0
    names = {r["method"] for r in found}
    assert {"symlink", "symlink-positions", "hand-numpy", "hand-numpy-positions", "halfangle-numpy",
            "newton"} | ({"fsolve"} if installed("scipy.optimize") else set()) <= names
    by_name = {r["method"]: r for r in found}
    for name in ("symlink", "symlink-positions", "hand-numpy"):
        assert by_name[name]["max_error"] < 1e-9, name  # closed forms, against 50 digits
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "us/value" in out and "symlink-positions / hand-numpy-positions" in out
    assert "halfangle-numpy (textbook half-angle form)" in out and "nocse" not in out
    assert "physical limit (this machine)" in out or "no C compiler" in err


def test_report_names_the_machine_and_writes_the_page_and_plot(tmp_path, capsys):
    status = main(["bench", "--quick", "--sizes", "200", "--no-derivation", "--report", str(tmp_path),
                   "--methods", "symlink,symlink-positions,symlink-c-positions,hand-c-positions"])
    _, err = capsys.readouterr()
    assert status == 0, err
    page = (tmp_path / "benchmark" / "results.md").read_text()
    cpu = next(line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
               if line.startswith("model name")) if Path("/proc/cpuinfo").exists() else ""
    flags = Path("/proc/cpuinfo").read_text() if Path("/proc/cpuinfo").exists() else ""
    width = 512 if " avx512f" in flags else 256 if " avx2" in flags else 128
    assert f"CPU: {cpu}" in page and f"vector width {width} bits" in page
    assert "date: 20" in page and "load average at the start" in page
    assert "command: `symlink bench --quick --sizes 200 --no-derivation --report " in page
    assert "| method | kind | N | time a value (ns) | ratio to symlink (NumPy) | max error (rad) |" in page
    rows = [line for line in page.splitlines() if line.startswith("| symlink-positions |")]
    assert len(rows) == 1 and rows[0].split("|")[3].strip() == "200"
    if "no C compiler" not in err:
        assert "| physical-limit |" in page and "| symlink-c-positions-loop |" in page
        assert "symlink-c-positions-loop / physical limit" in page
    assert (tmp_path / "images" / "bench.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.slow  # derives every scene twice in new processes, and runs sympy-evalf
def test_symbolic_side_and_slow_methods(capsys):
    status = main(["bench", "--quick", "--sizes", "60", "--methods", "sympy-evalf,symlink", "--no-limit"])
    out, err = capsys.readouterr()
    assert status == 0, err
    assert "from cache" in out and "loading the generated module" in out
    assert "sympy-evalf" in out


ROOT = Path(__file__).parent.parent


@pytest.mark.parametrize("command", [["-m", "benchmarks"], [str(ROOT / "benchmarks" / "bench.py")]])
def test_entry_points_and_method_choice_progress_on_stderr(tmp_path, command):
    records = tmp_path / "r.json"
    done = subprocess.run([sys.executable, *command, "--sizes", "60", "--methods", "hand-numpy,newton",
                           "--no-derivation", "--no-limit", "--json", str(records)], capture_output=True, text=True,
                          cwd=ROOT if command[0] == "-m" else tmp_path)  # the script runs from anywhere
    assert done.returncode == 0, done.stderr
    assert sorted(r["method"] for r in json.loads(records.read_text())) == ["hand-numpy", "newton"]
    assert "N = 60" in done.stderr and "us/value" in done.stderr  # progress
    assert "N = 60" not in done.stdout and done.stdout.splitlines()[0].split()[:3] == ["method", "kind", "N"]  # results


def test_symlink_bench_without_the_source_checkout_says_so_in_one_line(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "benchmarks", None)  # as if benchmarks/ were not importable
    monkeypatch.setitem(sys.modules, "benchmarks.bench", None)
    assert main(["bench", "--quick"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and err.startswith("symlink: error: symlink bench needs")


def test_failed_write_is_one_line_exit_1(tmp_path, capsys):
    (tmp_path / "taken").mkdir()  # a folder where the file should go
    status = main(["bench", "--sizes", "30", "--methods", "hand-numpy", "--no-derivation", "--no-limit",
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
    status = main(["bench", "--no-derivation", "--no-limit", *argv])
    _, err = capsys.readouterr()
    assert status == 2 and err.count("\n") == 1 and message in err


def test_missing_optional_methods_are_skipped_with_a_note(monkeypatch, capsys):
    for module in ("scipy.optimize", "symlink.numeric.compiled", "numba", "symengine", "pylinkage"):
        monkeypatch.setitem(sys.modules, module, None)
    status = main(["bench", "--sizes", "40", "--no-derivation", "--methods",
                   "fsolve,symlink-c,hand-c-positions,numba,symengine-llvm,pylinkage,hand-numpy"])
    out, err = capsys.readouterr()
    assert status == 0
    assert "skipped fsolve: scipy is not installed" in err  # a note, with the progress
    for name in ("numba", "symengine-llvm", "pylinkage"):
        assert f"skipped {name}: " in err and "pip install 'symlink-kinematics[bench]'" in err
    assert "skipped symlink-c" in err and "skipped hand-c-positions" in err
    assert "physical limit" not in out  # no C here either
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


def test_halfangle_numpy_is_the_seed_formula():
    theta = numpy.radians(numpy.arange(0.0, 360.0, 7.0))
    lengths = SEED_LINKAGES["seed003"]
    for branch in (1, -1):
        numpy.testing.assert_allclose(halfangle_numpy(theta, *lengths, branch),
                                      seed003_positions(*lengths, theta, branch), rtol=0, atol=1e-13)


def test_hand_numpy_and_hand_rates_match_the_independent_reference():
    rng = numpy.random.default_rng(8)
    for name, lengths in SEED_LINKAGES.items():
        theta = numpy.sort(rng.uniform(-math.pi, math.pi, 12))
        for branch in (1, -1):
            beta, phi = hand_numpy(theta, *lengths, branch)
            rates = hand_rates(theta, *lengths[:3], beta, phi, 10.5, 2.0)
            for i, angle in enumerate(theta):
                try:
                    exact = mp_fourbar(*lengths, theta=angle, branch=branch, crank_speed=10.5, crank_accel=2.0)
                except ValueError:
                    assert numpy.isnan(phi[i])
                    continue
                assert abs(numpy.angle(numpy.exp(1j * (phi[i] - float(exact["phi"]))))) < 1e-12
                assert abs(numpy.angle(numpy.exp(1j * (beta[i] - float(exact["beta"]))))) < 1e-12
                for value, key in zip((r[i] for r in rates), ("beta_speed", "phi_speed", "beta_accel", "phi_accel")):
                    assert value == pytest.approx(float(exact[key]), rel=1e-9, abs=1e-9), (name, key)


def test_reference_rates_agree_with_the_independent_ones():
    lengths = SEED_LINKAGES["seed002"]
    for theta in (-2.0, 0.3, 1.7):
        for branch in (1, -1):
            beta, phi = reference_positions(*lengths, theta, branch)
            mine = reference_rates(*lengths[:3], theta, beta, phi, 10.5, 2.0)
            theirs = mp_fourbar(*lengths, theta=theta, branch=branch, crank_speed=10.5, crank_accel=2.0)
            for value, key in zip(mine, ("beta_speed", "phi_speed", "beta_accel", "phi_accel")):
                assert abs(float(value - theirs[key])) < 1e-30 * max(1.0, abs(float(theirs[key])))


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


def _available(names):
    return [name for name in names if name not in OPTIONAL or installed(OPTIONAL[name])]


NUMPY_METHODS = ["symlink", "symlink-positions", "hand-numpy", "hand-numpy-positions", "halfangle-numpy"]
#: Every method but the slow per-value ones (fsolve, sympy-evalf) and newton (it may converge to the other branch
#: near a toggle: the benchmark reports that as its error).
EVERY_METHOD = [m for m in METHODS if m not in ("fsolve", "sympy-evalf", "newton")]


@pytest.mark.parametrize("chosen", [NUMPY_METHODS, pytest.param(EVERY_METHOD, marks=pytest.mark.slow)],
                         ids=["numpy", "every"])
def test_every_method_gives_the_right_numbers(chosen):
    """Positions against 50-digit mpmath for every method, rates too for full kinematics (no timings).

    The peers (numba, SymEngine, pylinkage) compile for some 30 s here: that run is marked slow.
    """
    chosen = _available(chosen)
    stepping = [name for name in chosen if name.startswith("pylinkage")]
    # pylinkage continues each position from the one before: at 20 steps a turn it can jump to the other
    # assembly (a property of its method, which the benchmark reports as its error), so it gets 100 a turn
    records = benchmark(sizes=[360], methods=[m for m in chosen if m not in stepping], reference=360, verbose=False)
    if stepping:
        records += benchmark(sizes=[1800], methods=stepping, reference=360, verbose=False)
    found = {r["method"]: r for r in records}
    for name in chosen:
        if name not in found:  # a C method without a compiler
            assert "-c" in name
            continue
        record = found[name]
        bound = 1e-12 if "halfangle" in name else 1e-13  # the half-angle form loses digits where A is small
        assert record["failures"] == 0 and record["max_error"] < bound, name
        assert record["max_residual"] < 1e-12, name
        if record["kind"] == "full":
            assert record["max_rate_error"] < 1e-9, name
        assert record["reference_n"] >= (100 if name.startswith("pylinkage") else 300), name


@pytest.mark.slow  # compiles the numba loops and SymEngine's LLVM code
def test_methods_agree_with_each_other_on_every_output():
    """All full-kinematics methods on the same values give the same six outputs (to rounding)."""
    from benchmarks.bench import _methods, stacked
    sweeps = [s for s in workload(240, seed=9, reference=1) if s.name.startswith("seed")]
    everything = stacked(sweeps)
    names = _available(["symlink", "hand-numpy", "numba", "symengine-llvm", "lambdify-cse", "symlink-c"])
    results = {}
    for name in names:
        from benchmarks.bench import Unavailable
        try:
            results[name] = _methods(True)[name]().solve(everything)
        except Unavailable:
            continue
    reference = results["symlink"]
    for name, result in results.items():
        for output in EVERYTHING:
            mine, theirs = numpy.asarray(result[output]), numpy.asarray(reference[output])
            scale = numpy.maximum(numpy.abs(theirs), 10.5 if "speed" in output else 110.25 if "accel" in output
                                  else 1.0)
            assert numpy.nanmax(numpy.abs(mine - theirs) / scale) < 1e-9, (name, output)


def test_every_method_is_called_once_for_the_whole_workload():
    """The same calling convention for all: one call with every value (pylinkage: one call a linkage)."""
    from benchmarks.bench import _timed
    sweeps = workload(180, seed=4, reference=10)
    calls = []

    def solve(sweep):
        calls.append(len(sweep.theta))
        return {"coupler": numpy.zeros(len(sweep.theta)), "rocker": numpy.zeros(len(sweep.theta))}
    methods = [Method("together", solve), Method("alone", solve, per_linkage=True)]
    _timed(methods[:1], {"together": sweeps}, budget=0.0)
    assert len(calls) >= 3 and set(calls) == {180}  # at least three rounds, each call with all 180 values
    calls.clear()
    _timed(methods[1:], {"alone": sweeps}, budget=0.0)
    one_round = [len(s.theta) for s in sweeps]
    assert len(calls) >= 3 * len(one_round) and calls == one_round * (len(calls) // len(one_round))


def test_pylinkage_workload_is_the_full_turn_sweeps_evenly_spaced():
    sweeps = workload(900, seed=2, reference=50)
    own = pylinkage_sweeps(sweeps, seed=2, reference=50)
    assert own and len(own) < len(sweeps)
    for sweep in own:
        assert crank_range(*sweep.lengths) == [(-math.pi, math.pi)]
        steps = numpy.diff(sweep.theta)
        assert numpy.allclose(steps, 2 * math.pi / len(sweep.theta), rtol=1e-12)
        assert len(sweep.sample) and len(sweep.rates) == 4


def test_target_lines_state_the_ratios():
    def record(method, n, us, kind="positions", size=None, error=1e-15):
        return {"method": method, "kind": kind, "n": n, "size": size or n, "us_per_value": us, "max_error": error,
                "failures": 0}
    records = [
        record("symlink", 1000, 0.2, "full"), record("numba", 1000, 0.16, "full"),
        record("pylinkage", 600, 0.8, "full", size=1000),
        record("symlink-positions", 1000, 0.08), record("hand-numpy-positions", 1000, 0.1),
        record("halfangle-numpy", 1000, 0.1, error=1e-13), record("physical-limit", 1000, 0.01, error=None),
        record("symlink-c-positions-loop", 1000, 0.012, error=None),
        record("hand-c-positions-loop", 1000, 0.01, error=None),
        record("symlink-c-positions", 1000, 0.015),
        record("fsolve", 100, 30.0),
    ]
    lines = "\n".join(targets(records))
    # the headline: the user's call against the limit, beside its loop (0.015 / 0.01, 0.012 / 0.01, 0.015 / 0.012)
    assert ("symlink-c-positions (a call) / physical limit at N=1000: 1.50x; its loop alone 1.20x, the call 1.25x "
            "its loop") in lines
    assert "symlink / numba at N=1000: 1.25x; full kinematics" in lines
    assert "symlink-positions / hand-numpy-positions at N=1000: 0.80x" in lines
    assert "halfangle-numpy (textbook half-angle form) at N=1000: 0.80x; max error 1.00e-15 vs 1.00e-13" in lines
    assert "symlink / pylinkage at N=1000: 0.25x (full kinematics; pylinkage 0.8 us a value on its 600 values)" in lines
    assert "symlink-c-positions-loop / physical limit at N=1000: 1.20x (target <= 1.3x: held)" in lines
    assert "symlink-c-positions-loop / hand-c-positions-loop at N=1000: 1.20x (target <= 1.1x: MISSED)" in lines
    assert "symlink-positions / physical limit" not in lines  # a call with fresh outputs is not timed against it
    # fsolve solves positions only: compared with symlink-positions, 30 / 0.08 = 375
    assert "fsolve (100 values) / symlink-positions at N=1000, per value: 375x (target >= 100x: held)" in lines
    next(r for r in records if r["method"] == "hand-c-positions-loop")["us_per_value"] = 0.012
    assert "symlink-c-positions-loop / hand-c-positions-loop at N=1000: 1.00x (target <= 1.1x: held)" in \
        "\n".join(targets(records))


def test_stacked_call_gives_the_per_sweep_results():
    from benchmarks.bench import stacked, unstacked
    sweeps = workload(90, seed=3, reference=10)
    whole = stacked(sweeps)
    beta, phi = hand_numpy(whole.theta, *whole.lengths, whole.branch)
    together = unstacked({"coupler": beta, "rocker": phi}, sweeps)
    for sweep, part in zip(sweeps, together):
        alone = hand_numpy(sweep.theta, *sweep.lengths, sweep.branch)
        assert numpy.array_equal(alone[0], part["coupler"]) and numpy.array_equal(alone[1], part["rocker"])


# --- the baselines do the generated code's transcendental calls, no more and no fewer ----------------------------

import inspect  # noqa: E402
import re  # noqa: E402
from collections import Counter  # noqa: E402

#: The calls counted: every libm function a value may call (a clamped square root is a square root).
CALL = re.compile(r"(?<![\w.])(?:math\.|numpy\.)?(sin|cos|tan|asin|acos|atan|atan2|arctan2|exp|log|pow|sqrt"
                  r"|symlink_clamped_sqrt)\(")
RENAMED = {"symlink_clamped_sqrt": "sqrt", "arctan2": "atan2"}


def calls(text: str) -> Counter:
    """The calls in ``text`` by function (``symlink_clamped_sqrt`` counted as ``sqrt``), comments left out."""
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.DOTALL)  # C comments
    text = re.sub(r"#[^\n]*", "", text)  # Python comments (and C preprocessor lines, none in a function)
    return Counter(RENAMED.get(name, name) for name in CALL.findall(text))


def between(text: str, start: str, end: str) -> str:
    begin = text.index(start)
    return text[begin:text.index(end, begin + len(start))]


def generated_calls(outputs) -> Counter:
    """Calls a value makes in the generated C: the body of the per-value kernel, less its loop unit.

    The loop unit (``size_`` lines: lengths scaled by a power of two so that no product overflows) is a
    numeric device of the generated code that a hand-written loop does not have (its calls were
    ``pow`` and ``log``; from the exponent bits it has none).
    """
    from symlink.numeric.compiled import c_solver_source
    from symlink.io.scene import catalog_linkage
    source = c_solver_source(catalog_linkage("fourbar"), outputs)["source"]
    body = between(source, "symlink_solve_at(double theta", "\n}\n")
    return calls("\n".join(line for line in body.splitlines() if not re.match(r"\s*const double size_\d+ =", line)))


@pytest.mark.parametrize("full", [False, True], ids=["positions", "full"])
def test_each_baseline_makes_the_generated_codes_calls_a_value(full):
    from benchmarks import hand_c, numba_loops
    outputs = EVERYTHING if full else ["coupler", "rocker"]
    expected = generated_calls(outputs)
    assert expected == Counter({"sin": 1, "cos": 1, "atan2": 2, "sqrt": 1})  # read off by hand
    triangle = between(hand_c.HAND_C_SOURCE, "void hand_triangle(", "\n}\n")
    loop = between(hand_c.HAND_C_SOURCE, "void hand_fourbar_everything(" if full else "void hand_fourbar_positions(",
                   "\n}\n")
    assert calls(triangle) + calls(loop.replace("hand_triangle(", "")) == expected, "hand C"
    numba_source = inspect.getsource(numba_loops)
    shared = between(numba_source, "def solve_positions(", "\n\n\n")
    kernel = between(numba_source, "    def everything(" if full else "    def positions(", "\n\n")
    assert calls(shared) + calls(kernel) == expected, "numba"
    from benchmarks import bench
    bench_source = inspect.getsource(bench)
    shared = between(bench_source, "def _atan2_arguments(", "\n\n\n")
    body = between(bench_source, "def hand_numpy_everything(" if full else "def hand_numpy(", "\n\n\n")
    body = body[body.index('"""', body.index('"""') + 3):]  # the code, after the docstring
    assert calls(shared) + calls(body.replace("_atan2_arguments(", "")) == expected, "hand NumPy"


def test_hand_numpy_full_kinematics_match_the_independent_reference():
    from benchmarks.bench import hand_numpy_everything
    lengths = SEED_LINKAGES["seed002"]
    theta = numpy.linspace(-3.0, 3.0, 13)
    for branch in (1, -1):
        values = hand_numpy_everything(theta, *lengths, branch, 10.5, 2.0)
        for i, angle in enumerate(theta):
            exact = mp_fourbar(*lengths, theta=angle, branch=branch, crank_speed=10.5, crank_accel=2.0)
            for value, key in zip((v[i] for v in values), ("beta", "phi", "beta_speed", "phi_speed", "beta_accel",
                                                           "phi_accel")):
                assert value == pytest.approx(float(exact[key]), rel=1e-10, abs=1e-10), (angle, key)


def test_the_small_call_numba_baseline_is_the_counted_kernel():
    """benchmarks.small_calls times the numba loop whose transcendental calls the test above counts (exactly
    the generated code's), not a loop that also calls sin and cos of the solved angles."""
    from benchmarks import small_calls
    assert "numba_kernels" in inspect.getsource(small_calls.numba_baseline)
    assert "numba_function(" not in inspect.getsource(small_calls)  # (its docstring names the one before)
    pytest.importorskip("numba", reason="numba comes with the bench extra: pip install -e '.[bench]'")
    theta = numpy.linspace(0.0, 6.0, 7)
    found = small_calls.numba_baseline()(theta)
    for row, key in enumerate(("beta", "phi", "beta_speed", "phi_speed", "beta_accel", "phi_accel")):
        for i, angle in enumerate(theta):
            exact = mp_fourbar(20.0, 66.0, 56.0, 80.0, theta=angle, branch=1, crank_speed=10.5, crank_accel=2.0)
            assert found[row, i] == pytest.approx(float(exact[key]), rel=1e-10, abs=1e-10), (angle, key)
