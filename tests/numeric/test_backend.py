"""Which backend a Solver uses: compiled where a C compiler works (auto, the default), NumPy otherwise or on request."""
from __future__ import annotations

import warnings

import numpy
import pytest

from references import SEED003_LINKAGE, mp_fourbar
from symlink.numeric import cache, compiled, compiled_library
from symlink.mechanism.catalog import fourbar
from symlink.numeric.compiled import FallbackWarning, chosen_backend
from symlink.numeric.solver import Solver

OUTPUTS = ["coupler", "rocker", "coupler_speed", "rocker_accel", "transmission"]


def _forget() -> None:
    compiled.wait_for_builds()
    compiled._builds.clear()
    compiled._probed.clear()
    compiled._loaded.clear()
    cache.clear_memory()


@pytest.fixture()
def fresh(tmp_path, monkeypatch):
    """An empty cache, nothing in memory, no SYMLINK_BACKEND: a new machine."""
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("SYMLINK_BACKEND", raising=False)
    _forget()
    yield tmp_path / "cache"
    _forget()


@pytest.fixture()
def compiler(fresh):
    if not compiled.compiler_works():
        pytest.skip("no working C compiler here")
    return fresh


def test_auto_is_the_default_and_compiles_in_the_background_while_numpy_answers(compiler):
    solver = Solver(fourbar(), OUTPUTS)
    assert solver.backend_choice == "auto"
    theta = numpy.radians(numpy.arange(0.0, 360.0, 10.0))
    values = dict(theta=theta, a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0, thetadot=10.5, thetaddot=2.0)
    first = {k: v.copy() for k, v in solver(**values).items()}  # answered now, whichever backend is ready
    assert solver.wait_for_backend(timeout=600) == "compiled"
    assert list((compiler / "compiled").glob("*.so"))  # built once into the cache
    again = solver(**values)
    for key in OUTPUTS:
        numpy.testing.assert_allclose(again[key], first[key], rtol=1e-13, atol=1e-13 * 110.25)
    # a new process (nothing in memory) finds the library in the cache: compiled from its first call, no build
    compiled._loaded.clear()
    compiled._builds.clear()
    cache.clear_memory()
    runs = []
    original = compiled_library._run_compiler
    compiled_library._run_compiler = lambda *a, **k: runs.append(a) or original(*a, **k)
    try:
        assert Solver(fourbar(), OUTPUTS).backend == "compiled" and not runs
    finally:
        compiled_library._run_compiler = original


def test_compiled_results_match_the_50_digit_reference_and_numpy(compiler):
    fast = Solver(fourbar(), ["coupler", "rocker", "coupler_speed", "rocker_accel"], backend="compiled")
    plain = Solver(fourbar(), ["coupler", "rocker", "coupler_speed", "rocker_accel"], backend="numpy")
    assert (fast.backend, plain.backend) == ("compiled", "numpy")
    a, b, c, d = (SEED003_LINKAGE[k] for k in "abcd")
    theta = numpy.radians(numpy.arange(0.5, 360.0, 20.0))
    for branch in (1, -1):
        got = fast(theta=theta, a=a, b=b, c=c, d=d, branch=branch, thetadot=10.5, thetaddot=2.0)
        want = plain(theta=theta, a=a, b=b, c=c, d=d, branch=branch, thetadot=10.5, thetaddot=2.0)
        for i, angle in enumerate(theta):
            exact = mp_fourbar(a, b, c, d, float(angle), branch, crank_speed=10.5, crank_accel=2.0)
            assert abs(numpy.angle(numpy.exp(1j * (got["rocker"][i] - float(exact["phi"]))))) < 1e-13
            assert got["coupler_speed"][i] == pytest.approx(float(exact["beta_speed"]), rel=1e-11, abs=1e-11)
        for key in want:
            if key != "assembled":
                numpy.testing.assert_allclose(got[key], want[key], rtol=1e-13, atol=1e-12)
        assert numpy.array_equal(got["assembled"], want["assembled"])


def test_small_calls_and_checks_on_the_compiled_backend(compiler):
    solver = Solver(fourbar(), ["rocker"], backend="compiled")
    result = solver(theta=numpy.linspace(0.0, 1.0, 10), a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0)
    assert result["rocker"].shape == (10,) and result.units["rocker"] == "rad"
    with pytest.raises(ValueError, match="a must be a positive finite length"):
        solver(theta=numpy.linspace(0.0, 1.0, 10), a=-20.0, b=66.0, c=56.0, d=80.0, branch=1.0)
    with pytest.raises(ValueError, match="takes theta"):
        solver(theta=0.0, a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0, e=1.0)


def test_the_environment_variable_chooses_and_bad_values_are_named(fresh, monkeypatch):
    monkeypatch.setenv("SYMLINK_BACKEND", "numpy")
    solver = Solver(fourbar(), ["rocker"])
    assert solver.backend_choice == "numpy" and solver.backend == "numpy" and not compiled._builds
    assert Solver(fourbar(), ["rocker"], backend="auto").backend_choice == "auto"  # the argument wins
    monkeypatch.setenv("SYMLINK_BACKEND", "fast")
    with pytest.raises(ValueError, match="SYMLINK_BACKEND must be one of auto, numpy, compiled; got 'fast'"):
        Solver(fourbar(), ["rocker"])
    with pytest.raises(ValueError, match="backend must be one of auto, numpy, compiled; got 'C'"):
        Solver(fourbar(), ["rocker"], backend="C")
    assert chosen_backend("compiled") == "compiled"


def test_without_a_compiler_auto_is_numpy_quietly_and_compiled_warns_once(fresh, tmp_path, monkeypatch):
    empty = tmp_path / "empty"
    empty.mkdir()
    monkeypatch.setenv("PATH", str(empty))
    monkeypatch.delenv("CC", raising=False)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        quiet = Solver(fourbar(), ["rocker"])
        assert quiet.backend == "numpy" and quiet._build is None and not caught
        loud = Solver(fourbar(), ["rocker"], backend="compiled")
    assert loud.backend == "numpy"
    assert [w.category for w in caught] == [FallbackWarning]
    result = quiet(theta=0.0, a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0)
    assert round(float(numpy.degrees(result["rocker"])), 2) == 110.74


def test_a_background_build_writes_where_it_was_asked_even_after_the_cache_moved(compiler, tmp_path, monkeypatch):
    # a build asked under one cache and run after SYMLINK_CACHE changed (a test's fixture, a user's script) used to
    # land in the new folder: it keeps the folder it was asked in
    facts = {"source": f"double symlink_moved(double x) {{ return x + {len(str(tmp_path))}.25; }}\n"}
    build = compiled.build_in_background(facts)
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "elsewhere"))
    assert build.wait(timeout=600) and build.error is None
    assert list((compiler / "compiled").glob("*.so"))
    assert not (tmp_path / "elsewhere").exists()
