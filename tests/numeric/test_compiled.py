"""The compiled backend: agreement with the NumPy solver and the 50-digit reference, the disk cache, the fallback."""
from __future__ import annotations

import ctypes
import errno
import hashlib
import os
import stat
import warnings
from pathlib import Path

import numpy
import pytest

from export_checks import angles_of, assert_agree, closed_form_catalog, random_arguments, rounding_spread
from references import SEED003_LINKAGE, mp_fourbar
from symlink.numeric import cache, compiled, compiled_library
from symlink.numeric.compiled import (CompiledSolver, CompileError, CompilerUnavailable, compile_shared,
                              compiled_solver, find_compiler)
from symlink.io.scene import catalog_linkage
from symlink.numeric.solver import Solver

FOURBAR_OUTPUTS = ["coupler", "rocker", "coupler_speed", "rocker_speed", "coupler_accel", "rocker_accel",
                   "transmission", "C_x", "C_y"]


def _forget() -> None:
    compiled.wait_for_builds()  # no background build of an earlier test's solver runs on into this one
    compiled._builds.clear()
    compiled._probed.clear()
    cache.clear_memory()
    compiled._loaded.clear()
    compiled._private_folder.clear()  # a new process gets a new private folder


@pytest.fixture(scope="module", autouse=True)
def module_cache(tmp_path_factory):
    """One cache folder for this module's tests (so a library is compiled once), never the user's."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("SYMLINK_CACHE", str(tmp_path_factory.mktemp("cache")))
        _forget()
        yield
    _forget()


@pytest.fixture()
def fresh_cache(tmp_path, monkeypatch):
    """An empty cache folder, and nothing remembered in memory: the first run on a new machine."""
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "cache"))
    _forget()
    yield
    _forget()


@pytest.fixture(scope="module")
def compiler(module_cache):
    try:
        find_compiler()
        compile_shared("double symlink_test_probe(double x) { return x; }\n")
    except CompilerUnavailable as error:
        pytest.skip(f"no working C compiler, the compiled backend is not tested: {error}")


@pytest.fixture()
def compiler_runs(monkeypatch):
    """A list that grows by one each time the compiler is run."""
    runs = []
    original = compiled_library._run_compiler

    def counting(*args, **kwargs):
        runs.append(args)
        return original(*args, **kwargs)

    monkeypatch.setattr(compiled_library, "_run_compiler", counting)
    return runs


@pytest.mark.parametrize("name", closed_form_catalog())
def test_compiled_agrees_with_numpy_on_every_catalog_entry(compiler, name):
    linkage = catalog_linkage(name)
    outputs = linkage.output_names()
    fast, reference = compiled_solver(linkage, outputs), Solver(linkage, outputs, backend="numpy")
    assert isinstance(fast, CompiledSolver)
    assert fast.arguments == reference.arguments
    values = random_arguments(linkage, fast.arguments, 500, seed=7)
    want = {k: numpy.asarray(v) for k, v in reference(**values).items()}
    got = fast(**values)
    assert want["assembled"].sum() > 50
    assert_agree(got, want, angles_of(name, outputs), 1e-12, name, rounding_spread(reference, values))
    for key, value in got.items():
        assert value.dtype == want[key].dtype, key


def test_compiled_matches_the_50_digit_reference(compiler):
    solver = compiled_solver(catalog_linkage("fourbar"), FOURBAR_OUTPUTS)
    a, b, c, d = (SEED003_LINKAGE[k] for k in "abcd")
    theta = numpy.radians(numpy.arange(0.0, 360.0, 15.0) + 0.1)
    for branch in (1, -1):
        result = solver(theta=theta, a=a, b=b, c=c, d=d, branch=branch, thetadot=10.5, thetaddot=-2.0)
        assert result["assembled"].all()
        for i, angle in enumerate(theta):
            reference = mp_fourbar(a, b, c, d, float(angle), branch, 10.5, -2.0)
            for key, output in (("beta", "coupler"), ("phi", "rocker"), ("beta_speed", "coupler_speed"),
                                ("phi_speed", "rocker_speed"), ("beta_accel", "coupler_accel"),
                                ("phi_accel", "rocker_accel")):
                want = float(reference[key])
                assert abs(result[output][i] - want) <= 1e-12 * max(1.0, abs(want)), (branch, angle, key)


def test_broadcasting_views_and_scalars_like_the_numpy_solver(compiler):
    linkage = catalog_linkage("fourbar")
    fast, reference = compiled_solver(linkage, ["rocker", "C_x"]), Solver(linkage, ["rocker", "C_x"], backend="numpy")
    theta = numpy.linspace(-3.0, 3.0, 400)  # views longer than one block of the C loop (128)
    cases = [
        dict(theta=0.3, a=20, b=66, c=56, d=80),                                   # all scalars: 0-d
        dict(theta=theta, a=20, b=66, c=56, d=80, branch=-1),                       # the usual sweep
        dict(theta=theta[::3], a=20.0, b=66, c=56, d=80),                           # a strided view
        dict(theta=theta[::-1], a=20.0, b=66, c=56, d=80),                          # a reversed view
        dict(theta=theta.astype(numpy.float32), a=20, b=66, c=56, d=80),            # another dtype
        dict(theta=theta, a=numpy.array([[15.0], [20.0], [40.0]]), b=66, c=56, d=80),  # 2-d broadcasting
        dict(theta=list(theta[:4]), a=[20, 21, 22, 23], b=66, c=56, d=80, branch=[1, -1, 1, -1]),
        dict(theta=numpy.empty(0), a=20, b=66, c=56, d=80),                        # nothing to do
    ]
    for values in cases:
        want = {k: numpy.asarray(v) for k, v in reference(**values).items()}
        assert_agree(fast(**values), want, {"rocker"}, 1e-12, str(values)[:60])


def test_inputs_are_checked_like_the_numpy_solver(compiler):
    fast = compiled_solver(catalog_linkage("fourbar"), ["rocker"])
    with pytest.raises(ValueError, match="a must be a positive finite length"):
        fast(theta=0.0, a=-1, b=66, c=56, d=80)
    with pytest.raises(ValueError, match="branch must be"):
        fast(theta=0.0, a=20, b=66, c=56, d=80, branch=0)
    with pytest.raises(ValueError, match="not e"):
        fast(theta=0.0, a=20, b=66, c=56, d=80, e=1)
    with pytest.raises(ValueError, match="theta must be finite"):
        fast(theta=numpy.nan, a=20, b=66, c=56, d=80)
    with pytest.raises(ValueError, match="no output"):
        compiled_solver(catalog_linkage("fourbar"), ["rocker", "nope"])


def test_second_use_loads_from_the_cache_without_compiling(compiler, fresh_cache, compiler_runs):
    linkage = catalog_linkage("fourbar")
    first = compiled_solver(linkage, ["rocker"])
    assert len(compiler_runs) == 1
    libraries = set(compiled.cache_directory().glob("*.so"))
    _forget()  # a new process: memory forgotten, disk kept
    second = compiled_solver(linkage, ["rocker"])
    assert len(compiler_runs) == 1
    assert second.source == first.source and set(compiled.cache_directory().glob("*.so")) == libraries
    assert float(second(theta=0.0, a=20, b=66, c=56, d=80)["rocker"]) == pytest.approx(1.932819, abs=1e-6)


@pytest.mark.parametrize("damage", ["garbage", "truncated", "digest missing", "digest wrong",
                                    "truncated, digest recomputed", "garbage, digest recomputed"])
def test_a_corrupt_cache_entry_is_detected_and_rebuilt(compiler, fresh_cache, compiler_runs, damage):
    linkage = catalog_linkage("fourbar")
    solver = compiled_solver(linkage, ["rocker"])
    want = solver(theta=1.0, a=20, b=66, c=56, d=80)["rocker"]
    (library,) = compiled.cache_directory().glob("*.so")
    digest = library.with_suffix(".sha256")
    binary = library.read_bytes()
    library.unlink()  # a new file: never overwrite a library that this process has mapped
    if damage.endswith("digest recomputed"):  # passes the digest: the loader itself must refuse it, no crash
        bad = binary[: len(binary) // 2] if damage.startswith("truncated") else b"\x7fELF" + b"\0" * 100
        library.write_bytes(bad)
        digest.write_text(hashlib.sha256(bad).hexdigest() + "\n")
    elif damage == "garbage":
        library.write_bytes(b"\x7fELF" + b"\0" * 100)
    elif damage == "truncated":
        library.write_bytes(binary[: len(binary) // 2])
    else:
        library.write_bytes(binary)
        if damage == "digest missing":
            digest.unlink()
        else:
            digest.write_text("0" * 64 + "\n")
    _forget()
    runs = len(compiler_runs)
    got = compiled_solver(linkage, ["rocker"])(theta=1.0, a=20, b=66, c=56, d=80)["rocker"]
    assert len(compiler_runs) == runs + 1
    assert got == want
    assert compiled._intact(library)


def test_without_a_compiler_it_says_so_and_uses_numpy(tmp_path, monkeypatch):
    empty = tmp_path / "bin"
    empty.mkdir()
    monkeypatch.setenv("PATH", str(empty))
    monkeypatch.delenv("CC", raising=False)
    with pytest.raises(CompilerUnavailable, match="no C compiler found"):
        find_compiler()
    with pytest.warns(RuntimeWarning, match="no compiled backend, using NumPy instead"):
        solver = compiled_solver(catalog_linkage("fourbar"), ["rocker"])
    assert type(solver) is Solver
    assert float(solver(theta=0.0, a=20, b=66, c=56, d=80)["rocker"]) == pytest.approx(1.932819, abs=1e-6)


def test_cc_naming_a_missing_or_broken_compiler(monkeypatch):
    monkeypatch.setenv("CC", "/nonexistent/cc -O1")
    with pytest.raises(CompilerUnavailable, match="CC='/nonexistent/cc -O1' is not an executable"):
        find_compiler()
    monkeypatch.setenv("CC", "false")  # runs, and fails on everything
    with pytest.raises(CompilerUnavailable, match="cannot build a shared library"):
        compile_shared("double f(double x) { return x; }\n")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        solver = compiled_solver(catalog_linkage("fourbar"), ["rocker"])
    assert type(solver) is Solver and "cannot build" in str(caught[0].message)


def test_compile_shared_builds_any_source_and_reports_errors(compiler, fresh_cache):
    library = compile_shared("double twice(double x) { return 2.0 * x; }\n")
    library.twice.restype, library.twice.argtypes = ctypes.c_double, [ctypes.c_double]
    assert library.twice(1.25) == 2.5
    assert compile_shared("double twice(double x) { return 2.0 * x; }\n") is library
    with pytest.raises(CompileError, match="rejected the source"):
        compile_shared("double broken(double x) { return x +; }\n")
    with_header = compile_shared('#include "k.h"\ndouble k(void) { return K; }\n', {"k.h": "#define K 3.5\n"})
    with_header.k.restype = ctypes.c_double
    assert with_header.k() == 3.5


def test_with_the_disk_cache_off_a_private_folder_is_used(compiler, monkeypatch):
    monkeypatch.setenv("SYMLINK_CACHE", "")
    assert cache.cache_directory() is None
    folder = compiled.cache_directory()
    assert folder.name == "compiled" and folder.parent.name.startswith("symlink-")
    solver = compiled_solver(catalog_linkage("fourbar"), ["rocker"])
    assert isinstance(solver, CompiledSolver) and list(folder.glob("*.so"))


def test_source_has_no_fast_math_and_the_library_keeps_nan_semantics(compiler):
    assert not any("fast-math" in flag or flag.startswith("-march") for flag in compiled.FLAGS)
    fast = compiled_solver(catalog_linkage("fourbar"), ["rocker", "C_x"])
    result = fast(theta=numpy.array([numpy.pi / 2, numpy.pi]), a=50.0, b=30.0, c=40.0, d=45.0)
    # At theta = pi/2 B is 67.3 from D: 30 and 40 reach it. At theta = pi B is 95 from D: 30 + 40 < 95.
    assert result["assembled"].tolist() == [True, False]
    assert numpy.isfinite(result["rocker"][0]) and numpy.isnan(result["rocker"][1])
    assert numpy.isnan(result["C_x"][1])
    toggle = fast(theta=0.0, a=20.0, b=30.0, c=40.0, d=90.0)  # B 70 from D = b + c: the extended toggle
    assert bool(toggle["assembled"]) and abs(float(toggle["rocker"])) == pytest.approx(numpy.pi, abs=1e-12)  # C on BD


def test_an_unwritable_cache_folder_falls_back_to_a_private_one(tmp_path, monkeypatch):
    blocker = tmp_path / "a file"
    blocker.write_text("")
    monkeypatch.setenv("SYMLINK_CACHE", str(blocker))
    assert compiled.cache_directory().parent.name.startswith("symlink-")


def fallback_warnings(caught) -> list[str]:
    return [str(w.message) for w in caught if "no compiled backend, using NumPy instead" in str(w.message)]


def check_numpy_fallback(solver) -> None:
    assert type(solver) is Solver
    assert float(solver(theta=0.0, a=20, b=66, c=56, d=80)["rocker"]) == pytest.approx(1.932819, abs=1e-6)


def test_a_folder_at_the_librarys_name_falls_back_with_one_warning(compiler, fresh_cache):
    linkage = catalog_linkage("fourbar")
    compiled_solver(linkage, ["rocker"])
    (library,) = compiled.cache_directory().glob("*.so")
    library.unlink()
    library.mkdir()
    _forget()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        solver = compiled_solver(linkage, ["rocker"])
    check_numpy_fallback(solver)
    assert len(fallback_warnings(caught)) == 1 and len(caught) == 1
    assert library.is_dir() and not [p for p in library.parent.iterdir() if p.name.startswith(".")]


def test_a_full_disk_falls_back_with_one_warning_and_leaves_nothing(compiler, fresh_cache, monkeypatch):
    def full(*_):
        raise OSError(errno.ENOSPC, "No space left on device")
    with warnings.catch_warnings(record=True) as caught, pytest.MonkeyPatch.context() as disk:
        warnings.simplefilter("always")
        disk.setattr(os, "write", full)
        solver = compiled_solver(catalog_linkage("fourbar"), ["rocker"])
    check_numpy_fallback(solver)
    assert len(fallback_warnings(caught)) == 1 and "No space left" in fallback_warnings(caught)[0]
    assert list(compiled.cache_directory().iterdir()) == []  # no library, no .build-* folder, no temporary


def test_a_library_that_cannot_be_loaded_falls_back_with_one_warning(compiler, fresh_cache, monkeypatch):
    def broken_loader(name, *args, **kwargs):
        raise OSError(f"{name}: cannot open shared object file")
    monkeypatch.setattr(ctypes, "CDLL", broken_loader)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        solver = compiled_solver(catalog_linkage("fourbar"), ["rocker"])
    check_numpy_fallback(solver)
    assert len(fallback_warnings(caught)) == 1 and "cannot be loaded" in fallback_warnings(caught)[0]


def test_libraries_are_private_and_loaded_from_a_checked_private_copy(compiler, fresh_cache, monkeypatch):
    previous = os.umask(0)
    try:
        loaded = []
        original = ctypes.CDLL

        def loader(name, *args, **kwargs):
            path = Path(name)
            loaded.append((path, stat.S_IMODE(path.stat().st_mode), path.read_bytes()))
            return original(name, *args, **kwargs)
        monkeypatch.setattr(ctypes, "CDLL", loader)
        compiled_solver(catalog_linkage("fourbar"), ["rocker"])
    finally:
        os.umask(previous)
    folder = compiled.cache_directory()
    (library,) = folder.glob("*.so")
    assert stat.S_IMODE(folder.stat().st_mode) == 0o700
    assert {stat.S_IMODE(p.stat().st_mode) for p in folder.iterdir()} == {0o600}
    ((copy, mode, binary),) = loaded
    assert copy != library and copy.parent == folder and copy.name.startswith(".load-") and mode == 0o600
    assert binary == library.read_bytes()
    assert library.with_suffix(".sha256").read_text().strip() == hashlib.sha256(binary).hexdigest()
    assert not copy.exists()  # removed once loaded


def test_a_compiled_folder_others_can_write_is_not_used(compiler, fresh_cache, compiler_runs):
    linkage = catalog_linkage("fourbar")
    compiled_solver(linkage, ["rocker"])
    shared = compiled.cache_directory()
    shared.chmod(0o777)
    _forget()
    with pytest.warns(cache.CacheWarning, match="writable by group and others"):
        solver = compiled_solver(linkage, ["rocker"])
    assert isinstance(solver, CompiledSolver) and len(compiler_runs) == 2  # built again, privately
    assert compiled.cache_directory() != shared and compiled.cache_directory().parent.name.startswith("symlink-")


def _vector_math_expected() -> bool:
    """GCC >= 11 on x86-64 glibc >= 2.35: where VECTOR_MATH declares atan2 for vector registers."""
    import platform
    import subprocess
    if platform.machine() != "x86_64" or platform.libc_ver()[0] != "glibc":
        return False
    if tuple(int(p) for p in platform.libc_ver()[1].split(".")[:2]) < (2, 35):
        return False
    command = find_compiler()
    probe = subprocess.run(command + ["-dM", "-E", "-x", "c", "/dev/null"], capture_output=True, text=True,
                           check=False).stdout
    version = [line.split()[2] for line in probe.splitlines() if line.startswith("#define __GNUC__ ")]
    return "__clang__" not in probe and bool(version) and int(version[0]) >= 11


@pytest.mark.parametrize("name", ["fourbar", "watt2", "jansen"])
def test_full_kinematics_loops_are_vectorised(compiler, name, tmp_path):
    """Every loop calls glibc's vector atan2 (a loop that does not vectorise calls only the scalar one)."""
    if not _vector_math_expected():
        pytest.skip("glibc's vector math is used only by GCC >= 11 on x86-64 glibc >= 2.35")
    linkage = catalog_linkage(name)
    unknowns = [q.name for q in linkage.unknowns]
    outputs = unknowns + [f"{q}dot" for q in unknowns] + [f"{q}ddot" for q in unknowns] + ["singular"]
    source = compiled.c_solver_source(linkage, outputs)["source"]
    compiled_library._build(source, {}, find_compiler(), tmp_path / "solver.so")
    binary = (tmp_path / "solver.so").read_bytes()
    assert b"_ZGVdN4vv_atan2" in binary  # the AVX2 loop's vector atan2


def test_small_calls_take_the_fast_path_and_agree_with_the_general_one(compiler):
    fast = CompiledSolver(catalog_linkage("fourbar"), ["rocker", "coupler_accel", "singular"]).function
    lengths = dict(a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0, thetadot=10.5, thetaddot=2.0)
    theta = numpy.linspace(0.0, 6.0, 25)
    first = fast(theta=theta, **lengths)
    assert first["rocker"].base is not None  # the fast path ran: its rows are views of a kept block
    theta *= 0.5  # the same array, changed in place: read again, not remembered values
    second = fast(theta=theta, **lengths)
    general = fast(theta=list(theta), **lengths)  # a list: the general path
    third = fast(theta=theta.copy(), **{**lengths, "a": numpy.float64(20.0), "b": numpy.array(66.0)})
    for name in ["rocker", "coupler_accel", "singular", "assembled"]:
        assert numpy.array_equal(second[name], general[name], equal_nan=True), name
        assert numpy.array_equal(third[name], general[name], equal_nan=True), name
        assert second[name].dtype == general[name].dtype and second[name].shape == (25,)
    assert not numpy.array_equal(first["rocker"], second["rocker"])
    assert list(second) == ["rocker", "coupler_accel", "singular", "assembled"]


BAD_SMALL_CALLS = [  # (argument, value): each refused by the C wrapper's check, then named by the Solver's
    ("a", -20.0), ("a", 0.0), ("b", numpy.inf), ("c", numpy.nan), ("d", 1e306), ("branch", 0.5), ("branch", 0.0),
    ("thetadot", numpy.nan), ("thetaddot", -numpy.inf), ("theta", "array with a NaN"), ("a", "array with a zero"),
    ("branch", "array with a 2"),
]


@pytest.mark.parametrize("argument, value", BAD_SMALL_CALLS)
def test_small_calls_refuse_what_the_numpy_solver_refuses(compiler, argument, value):
    outputs = ["rocker", "coupler_accel"]
    compiled_, plain = CompiledSolver(catalog_linkage("fourbar"), outputs), Solver(catalog_linkage("fourbar"), outputs, backend="numpy")
    values = dict(theta=numpy.linspace(0.0, 6.0, 10), a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0, thetadot=10.5,
                  thetaddot=2.0)
    if isinstance(value, str):
        array = numpy.full(10, values[argument])
        array[3] = {"array with a NaN": numpy.nan, "array with a zero": 0.0, "array with a 2": 2.0}[value]
        value = array
    values[argument] = value
    with pytest.raises(ValueError) as expected:
        plain(**values)
    assert compiled_.function._small(values) is None  # the C wrapper refused it
    with pytest.raises(ValueError) as refused:
        compiled_(**values)
    assert str(refused.value) == str(expected.value)


def test_small_call_results_are_never_overwritten_while_held(compiler, monkeypatch):
    solver = CompiledSolver(catalog_linkage("fourbar"), ["rocker", "singular"])
    lengths = dict(a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0)
    first = solver(theta=numpy.linspace(0.0, 1.0, 12), **lengths)
    kept_row = first["rocker"]
    kept_slice = first["singular"][2:5].copy(), first["singular"][2:5]
    snapshot = kept_row.copy()
    for start in range(1, 8):  # more calls than blocks kept: each must find the held ones busy
        later = solver(theta=numpy.linspace(start, start + 1.0, 12), **lengths)
        assert not numpy.shares_memory(later["rocker"], kept_row)
        assert not numpy.shares_memory(later["singular"], kept_slice[1])
        del later
    numpy.testing.assert_array_equal(kept_row, snapshot)
    numpy.testing.assert_array_equal(kept_slice[1], kept_slice[0])
    expected = Solver(catalog_linkage("fourbar"), ["rocker", "singular"], backend="numpy")(
        theta=numpy.linspace(0.0, 1.0, 12), **lengths)
    # The first inputs' rockers still (glibc's vector atan2 may differ from NumPy's in the last place;
    # a later call's rockers, at other crank angles, would differ by far more than the tolerance).
    numpy.testing.assert_allclose(first["rocker"], expected["rocker"], rtol=0, atol=1e-12)
    # Results dropped, or held only until the next call returns: kept blocks are written again (no allocation).
    del first, kept_row, kept_slice
    made = []
    original = compiled_library._Outputs.__init__
    monkeypatch.setattr(compiled_library._Outputs, "__init__", lambda self, *args: made.append(args) or
                        original(self, *args))
    for start in range(6):
        assert solver(theta=numpy.linspace(start, start + 1.0, 12), **lengths)["rocker"].size == 12
    result = None
    for start in range(6):  # as a loop `result = solver(...)` does
        result = solver(theta=numpy.linspace(start, start + 1.0, 12), **lengths)
    assert result["rocker"].size == 12 and not made


@pytest.mark.parametrize("count", [1, 3, 10, 16, 17, 31, 100])
def test_a_value_does_not_depend_on_the_size_or_place_of_its_call(compiler, count):
    """A short call, and the short last block of a long one, are padded into the vectorised loop.

    So each value goes through the same vector math functions wherever it stands (no scalar
    remainder, whose libm functions may differ from them in the last place): bit for bit equal.
    """
    function = CompiledSolver(catalog_linkage("fourbar"), FOURBAR_OUTPUTS + ["singular"]).function
    rng = numpy.random.default_rng(count)
    theta = rng.uniform(-4.0, 4.0, 300)  # two whole blocks of the loop (128 each) and a short one
    values = dict(a=50.0, b=30.0, c=40.0, d=45.0, branch=-1.0, thetadot=10.5, thetaddot=2.0)  # a limited crank
    whole = function(theta=theta, **values)
    assert 0 < whole["assembled"].sum() < theta.size
    for start in (0, 5, 130, 300 - count):
        part = function(theta=theta[start:start + count].copy(), **values)
        for key, array in part.items():
            assert numpy.array_equal(array, whole[key][start:start + count], equal_nan=True), (start, key)


def test_small_calls_read_a_new_number_object_and_read_only_arrays(compiler):
    fast = CompiledSolver(catalog_linkage("fourbar"), ["rocker"]).function
    theta = numpy.linspace(0.0, 6.0, 10)
    theta.flags.writeable = False  # its address comes another way than a writable array's
    lengths = dict(b=66.0, c=56.0, d=80.0, branch=1.0)
    first = None
    for a in (20.0, 21.0, 20.0, 20):  # a new object each time, then an int: each written into its slot
        small = fast(theta=theta, a=a, **lengths)
        general = fast(theta=list(theta), a=a, **lengths)  # a list: the general path
        assert fast._plan is not None or fast._held[0] is theta  # the Python path holds it
        assert numpy.array_equal(small["rocker"], general["rocker"]), a
        if first is None:
            first = small["rocker"].copy()
        elif a == 21.0:
            assert not numpy.array_equal(small["rocker"], first)
        else:
            assert numpy.array_equal(small["rocker"], first)


def test_a_program_in_pieces_is_built_unit_by_unit_and_agrees_bit_for_bit(compiler, tmp_path, monkeypatch):
    """A large program's C comes in pieces (here Jansen's leg, cut small): each translation unit is compiled
    apart, two compilers at once, and linked into one library whose loops stay vectorised and whose values are
    bit for bit those of the one-loop library (the same operations on the same operands)."""
    import json
    from symlink.codegen.translation_units import translation_units
    linkage = catalog_linkage("jansen")
    unknowns = [q.name for q in linkage.unknowns]
    program = linkage.program(unknowns + [f"{q}dot" for q in unknowns] + [f"{q}ddot" for q in unknowns]
                              + ["singular"])
    lengths = [s.name for s in program.arguments if s.is_positive]
    whole = json.loads(compiled_library.program_facts(program, "jansen", "", lengths))
    cut = json.loads(compiled_library.program_facts(program, "jansen", "", lengths, piece_size=1500))
    assert len(translation_units(whole["source"])) == 1
    units = translation_units(cut["source"])
    assert len(units) >= 4
    batches = []
    original = compiled_library._run_all
    monkeypatch.setattr(compiled_library, "_compiler_jobs", lambda: 2)
    monkeypatch.setattr(compiled_library, "_run_all", lambda commands, folder: batches.append(len(commands))
                        or original(commands, folder))
    compiled_library._build(cut["source"], {}, find_compiler(), tmp_path / "cut.so")
    assert batches[:2] == [len(units), 1]  # every unit compiled apart, then one link
    if _vector_math_expected():
        assert b"_ZGVdN4vv_atan2" in (tmp_path / "cut.so").read_bytes()
    one, pieces = compiled_library._entry(compile_shared(whole["source"]), whole), \
        compiled_library._entry(ctypes.CDLL(str(tmp_path / "cut.so")), cut)
    values = random_arguments(linkage, whole["arguments"], 300, seed=5)  # blocks of 128, a short last one
    values["thetadot"] = 2.5  # a number: read at a step of 0
    expected, actual = one(**values), pieces(**values)
    assert 30 < expected["assembled"].sum() < 270  # both assembled and unassembled configurations
    assert set(actual) == set(expected)
    for key in expected:
        numpy.testing.assert_array_equal(actual[key], expected[key], err_msg=key)
