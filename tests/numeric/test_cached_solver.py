"""A cached catalog scene runs without SymPy: the warm ``symlink fourbar`` never imports it, and agrees with a cold run."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy
import pytest

from cache_fixture import edit_module, empty_cache, forget_source_digests  # noqa: F401 - a fixture
from references import mp_fourbar
from symlink.numeric import cache
from symlink.numeric.cached_solver import ENTRY_KIND, CachedSolver
from symlink.io.scene import catalog_linkage
from symlink.numeric.solver import Solver

ROOT = Path(__file__).resolve().parent.parent.parent
FOURBAR = ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
           "--crank-speed", "10.5", "--crank-accel", "2", "--step", "40", "--format", "csv"]

# Runs the command line as ``python -m symlink`` does and reports, as JSON on stderr's last line, its exit status,
# every SymPy module the process imported (anything on the path that imports SymPy leaves it in sys.modules), and
# the symlink and Matplotlib modules it imported.
_WATCHED = r"""
import json, sys
from symlink.cli import main
status = main(sys.argv[1:])
loaded = sorted(name for name in sys.modules if name.split(".")[0] == "sympy")
symlink = sorted(name for name in sys.modules if name.split(".")[0] == "symlink")
matplotlib = sorted(name for name in sys.modules if name.split(".")[0] == "matplotlib")
print(json.dumps({"status": status, "sympy": loaded[:3], "symlink": symlink, "matplotlib": matplotlib[:3]}),
      file=sys.stderr)
"""

#: Every symlink module a warm ``symlink fourbar`` table needs: the command line's entry, the table command with
#: the option groups it shares (mass and plot options), the cached solver and the cache, and nothing else.
WARM_TABLE_MODULES = {
    "symlink", "symlink.version", "symlink.common", "symlink.numeric", "symlink.common.angles", "symlink.numeric.input_sweep", "symlink.common.files", "symlink.common.limits",
    "symlink.numeric.results", "symlink.numeric.call_arguments", "symlink.numeric.cache", "symlink.numeric.cached_solver",
    "symlink.numeric.background_backend",  # what a solver says of its compiled backend (no build imported)
    "symlink.io", "symlink.io.table_source", "symlink.codegen", "symlink.codegen.loading",
    "symlink.cli", "symlink.cli.options", "symlink.cli.output", "symlink.cli.tables", "symlink.cli.dynamics",
    "symlink.cli.pictures", "symlink.cli.budget",
    "symlink.common.numbers",  # the one reader of the numbers an option takes
    "symlink.common.names"}  # the catalog's former names (a table command by its former name)


def _run(arguments: list[str], cache_folder: Path) -> tuple[subprocess.CompletedProcess, dict]:
    env = dict(os.environ, SYMLINK_CACHE=str(cache_folder), PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-c", _WATCHED, *arguments], capture_output=True, text=True, env=env,
                          cwd=ROOT, timeout=300)
    return done, json.loads(done.stderr.strip().splitlines()[-1])


def test_a_warm_fourbar_table_never_imports_sympy_and_equals_the_cold_one(tmp_path):
    folder = tmp_path / "cache"
    cold, cold_report = _run(FOURBAR, folder)
    assert cold_report["status"] == 0, cold.stderr
    assert cold_report["sympy"], "the check cannot fail: a cold run derives, with SymPy"
    warm, report = _run(FOURBAR, folder)
    assert (report["status"], report["sympy"]) == (0, []), warm.stderr
    assert warm.stdout == cold.stdout
    assert cold.stdout.count("\n") == 1 + 2 * 9  # header, 9 angles on both branches


def test_a_warm_fourbar_table_imports_no_other_command_and_no_plotting(tmp_path):
    """What a warm table imports beyond NumPy is its own command's modules: the other commands' modules (a
    dozen more), the linkage model and Matplotlib stay unimported (the count, not the time, is checked)."""
    folder = tmp_path / "cache"
    assert _run(FOURBAR, folder)[1]["status"] == 0
    warm, report = _run(FOURBAR, folder)
    assert report["status"] == 0, warm.stderr
    assert set(report["symlink"]) == WARM_TABLE_MODULES
    assert report["matplotlib"] == []
    other, other_report = _run(["quick-return", "--help"], folder)  # the check can fail: another command's module
    assert other_report["status"] == 0, other.stderr
    assert "symlink.cli.quick_return" in other_report["symlink"]
    assert "symlink.cli.quick_return" not in WARM_TABLE_MODULES


def test_bad_lengths_are_one_line_from_the_cached_solver(tmp_path):
    folder = tmp_path / "cache"
    assert _run(FOURBAR, folder)[1]["status"] == 0
    arguments = list(FOURBAR)
    arguments[arguments.index("--rocker") + 1] = "-5"
    warm, report = _run(arguments, folder)
    assert warm.stderr.startswith("symlink: error: rocker must be a positive finite length, got -5.0\n")
    assert (report["status"], report["sympy"]) == (2, [])


@pytest.mark.usefixtures("empty_cache")
def test_cached_solver_matches_the_solver_and_the_50_digit_reference():
    outputs = ["coupler", "rocker", "rocker_speed", "transmission"]
    theta = numpy.radians(numpy.arange(-170.0, 180.0, 20.0))
    values = dict(theta=theta, a=20.0, b=66.0, c=56.0, d=80.0, thetadot=10.5)
    derived = CachedSolver("fourbar", outputs)  # an empty cache: derived, entry written
    cache.clear_memory()  # as in a new process
    loaded = CachedSolver("fourbar", outputs)  # from the disk entry
    full = Solver(catalog_linkage("fourbar"), outputs, backend="numpy")  # the NumPy module, as the cached one
    for sign in (1, -1):
        mine, again, theirs = (s(**values, branch=sign) for s in (derived, loaded, full))
        for name in outputs + ["assembled"]:
            assert numpy.array_equal(mine[name], theirs[name]) and numpy.array_equal(again[name], theirs[name])
        assert mine.units == theirs.units
        for angle, coupler, rocker in zip(theta, mine["coupler"], mine["rocker"]):
            reference = mp_fourbar(20.0, 66.0, 56.0, 80.0, theta=float(angle), branch=sign)
            assert abs(numpy.angle(numpy.exp(1j * (rocker - float(reference["phi"]))))) < 1e-12
            assert abs(numpy.angle(numpy.exp(1j * (coupler - float(reference["beta"]))))) < 1e-12


@pytest.mark.usefixtures("empty_cache")
@pytest.mark.parametrize("name, outputs, values, message", [
    ("abacus", ["rocker"], {}, "no linkage 'abacus' in the catalog"),
    ("fourbar", ["stroke"], {}, "stroke"),
    ("fourbar", ["rocker"], {"theta": 0.0, "a": 1.0, "b": 1.0, "c": 1.0, "d": 1.0, "e": 1.0}, "not e"),
    ("fourbar", ["rocker"], {"theta": 0.0, "a": -1.0, "b": 1.0, "c": 1.0, "d": 1.0}, "a must be a positive"),
    ("fourbar", ["rocker"], {"theta": 0.0, "a": 1.0, "b": 1.0, "c": 1.0, "d": 1.0, "branch": 2},
     r"branch must be \+1 or -1"),
    ("fourbar", ["rocker"], {"theta": [0.0, 1.0, 2.0], "a": [1.0, 2.0], "b": 1.0, "c": 1.0, "d": 1.0},
     "do not broadcast"),
])
def test_bad_requests_and_values_are_refused(name, outputs, values, message):
    with pytest.raises(ValueError, match=message):
        CachedSolver(name, outputs)(**values)


@pytest.mark.usefixtures("empty_cache")
def test_quantities_go_through_the_full_solver():
    pint = pytest.importorskip("pint")
    unit = pint.UnitRegistry()
    solver = CachedSolver("fourbar", ["rocker", "C_x"])
    result = solver(theta=0.0, a=20 * unit.mm, b=66 * unit.mm, c=56 * unit.mm, d=80 * unit.mm, branch=1)
    plain = solver(theta=0.0, a=20.0, b=66.0, c=56.0, d=80.0, branch=1)
    assert result["rocker"] == plain["rocker"] and result.units["C_x"] == "millimeter"


def test_the_catalog_key_covers_what_builds_a_catalog_linkage():
    """Every symlink module that symlink.mechanism.catalog imports, directly or not, is hashed into the catalog key."""
    from test_architecture import import_graph
    graph = import_graph()
    seen, todo = set(), ["symlink.mechanism.catalog"]
    while todo:
        module = todo.pop()
        if module not in seen:
            seen.add(module)
            todo.extend(target for target in graph.get(module, ()) if target in graph)
    hashed = {path.relative_to(ROOT).with_suffix("").as_posix().replace("/", ".")
              for path in cache.code_shaping_files(cache.CATALOG_SHAPING)}
    assert seen - {"symlink"} <= {name.removesuffix(".__init__") for name in hashed}


def test_the_catalog_key_changes_with_what_it_stands_for(monkeypatch):
    key = cache.catalog_key("fourbar", ["rocker"], ENTRY_KIND)
    assert key != cache.catalog_key("fourbar", ["rocker"], "numpy")
    assert key != cache.catalog_key("slider-crank", ["rocker"], ENTRY_KIND)
    monkeypatch.setattr(cache, "sympy_version", lambda: "0.0")
    assert key != cache.catalog_key("fourbar", ["rocker"], ENTRY_KIND)
    monkeypatch.undo()
    edit_module(monkeypatch, "common/notation.py", b" ")
    try:
        assert key != cache.catalog_key("fourbar", ["rocker"], ENTRY_KIND)
    finally:
        monkeypatch.undo()
        forget_source_digests()


# --- every input dtype is computed in float64 (issue 22, item 5) ----------------------------------------------

#: Crank angles of the seed 003 four-bar (lengths 20, 66, 56, 80) in each dtype that NumPy may hand a solver; the
#: integer and bool ones are whole radians.  float16 keeps 11 bits: its angles are far from their float64 values,
#: but the solver must compute exactly as for the float64 rounding of the values it was given.
_ANGLES = numpy.radians(numpy.arange(-170.0, 180.0, 20.0))
DTYPE_CASES = [
    ("float16", _ANGLES.astype(numpy.float16)),
    ("float32", _ANGLES.astype(numpy.float32)),
    ("float32 big-endian", _ANGLES.astype(">f4")),
    ("float64 big-endian", _ANGLES.astype(">f8")),
    ("longdouble", _ANGLES.astype(numpy.longdouble)),
    ("int8", numpy.arange(-3, 4, dtype=numpy.int8)),
    ("int64", numpy.arange(-3, 4, dtype=numpy.int64)),
    ("uint16", numpy.arange(0, 7, dtype=numpy.uint16)),
    ("bool", numpy.array([True, False])),
    ("float32 scalar", numpy.float32(0.3)),
    ("float16 scalar", numpy.float16(2.5)),
]
DTYPE_OUTPUTS = ["coupler", "rocker", "C_x"]


def _dtype_solvers():
    """The three ways to call a generated NumPy function: the cached catalog solver, the scene cache's generated
    function (``symlink.numeric.cache.generated_code``) and the full Solver (which always converted)."""
    from symlink.numeric.cache import generated_code
    linkage = catalog_linkage("fourbar")
    return {"CachedSolver": CachedSolver("fourbar", DTYPE_OUTPUTS),
            "generated_code": generated_code(linkage, DTYPE_OUTPUTS).function,
            "Solver": Solver(linkage, DTYPE_OUTPUTS)}


@pytest.mark.usefixtures("empty_cache")
@pytest.mark.parametrize("what, angles", DTYPE_CASES, ids=[case[0] for case in DTYPE_CASES])
def test_any_real_dtype_is_computed_in_float64(what, angles):
    """float16/float32/int/bool angles and lengths give, bit for bit, the results of their float64 values, and
    those agree with the 50-digit reference at those float64 values to 1e-12 (float32 computed in float32 was off
    by 1.6e-8 rad, float16 by 1e-4)."""
    exact = numpy.asarray(angles).astype(numpy.float64)  # the float64 rounding of the values given (exact here)
    lengths = {name: numpy.asarray(value, dtype=angles.dtype if angles.dtype.kind in "f" else numpy.float64)
               for name, value in dict(a=20, b=66, c=56, d=80).items()}
    float_lengths = {name: float(value) for name, value in lengths.items()}
    for name, solve in _dtype_solvers().items():
        given = solve(theta=angles, **lengths, branch=numpy.int8(1))
        wanted = solve(theta=exact, **float_lengths, branch=1.0)
        for output in DTYPE_OUTPUTS:
            assert given[output].dtype == numpy.float64, (name, output)
            assert numpy.array_equal(given[output], wanted[output], equal_nan=True), (name, output)
        assert numpy.array_equal(given["assembled"], wanted["assembled"])
        for angle, rocker in zip(numpy.atleast_1d(exact), numpy.atleast_1d(given["rocker"])):
            reference = mp_fourbar(20.0, 66.0, 56.0, 80.0, theta=float(angle), branch=1)
            assert abs(numpy.angle(numpy.exp(1j * (rocker - float(reference["phi"]))))) < 1e-12, (name, angle)


@pytest.mark.usefixtures("empty_cache")
@pytest.mark.parametrize("argument", ["theta", "a", "branch"])
@pytest.mark.parametrize("value", [numpy.array([0.5 + 0j, 1.0 + 0j]), numpy.complex64(1.0), 1 + 2j],
                         ids=["complex128 array", "complex64 scalar", "python complex"])
def test_complex_values_are_refused_by_every_solver(argument, value):
    values = dict(theta=0.5, a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0)
    values[argument] = value
    for name, solve in _dtype_solvers().items():
        with pytest.raises(ValueError, match=f"{argument} must be real numbers"):
            solve(**values)


def test_float64_arguments_are_not_copied():
    """The float64 conversion costs nothing for float64 input: the array itself goes on."""
    from symlink.codegen.numpy import checked_arguments
    angles = numpy.linspace(0.0, 1.0, 5)
    (converted, lengths), _ = checked_arguments(["theta", "a"], [angles, numpy.float32(2.0)], lengths=["a"])
    assert converted is angles and lengths.dtype == numpy.float64


def test_a_warm_newton_solver_runs_its_cached_bytecode(empty_cache, monkeypatch):
    """The Newton module (the largest generated module a warm table loads) is not compiled again in a new process,
    and a truncated bytecode file of it is compiled again from its entry, with the same answers."""
    import symlink.codegen.loading as loading
    from symlink.mechanism.catalog import fourbar
    from symlink.numeric.cached_solver import CachedNewtonSolver, newton_entry_text
    key = cache.catalog_key("fourbar", ["newton"], "newton-bytecode-test/1")
    compilations = []
    original = loading.compile_numpy_module
    monkeypatch.setattr(loading, "compile_numpy_module", lambda source: compilations.append(1) or original(source))
    theta = numpy.array([0.0, 0.7, 2.0])
    expected = [float(mp_fourbar(a=20, b=66, c=56, d=80, theta=t, branch=1)["phi"]) for t in theta]

    def rocker() -> list[float]:
        solver = CachedNewtonSolver("fourbar", key, lambda: newton_entry_text(fourbar()))
        return [float(v) for v in solver(theta=theta, a=20, b=66, c=56, d=80, guess={"beta": 0.3, "phi": 1.9})["rocker"]]

    assert rocker() == pytest.approx(expected, abs=1e-9)
    cold = len(compilations)
    assert cold >= 1
    cache.clear_memory()  # a new process
    assert rocker() == pytest.approx(expected, abs=1e-9)
    assert len(compilations) == cold  # from the bytecode file
    path = cache.entry_path(empty_cache, key, bytecode=True)
    path.write_bytes(path.read_bytes()[:100])  # truncated
    cache.clear_memory()
    assert rocker() == pytest.approx(expected, abs=1e-9)
    assert len(compilations) == cold + 1  # compiled again from the verified text, and rewritten
    cache.clear_memory()
    assert rocker() == pytest.approx(expected, abs=1e-9) and len(compilations) == cold + 1
