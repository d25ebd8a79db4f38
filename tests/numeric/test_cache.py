"""The scene cache: keys, verified disk entries, and no symbolic work on a second run."""
import hashlib
import importlib.util
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy
import pytest
import sympy as sp

import symlink.numeric.cache as cache
import symlink.numeric.cache_folder as cache_folder
from cache_fixture import edit_module, empty_cache, forget_source_digests  # noqa: F401 - a fixture
from references import mp_fourbar
from symlink.numeric.cache import cache_directory, cache_key, clear_memory, definition, generated_code
from symlink.mechanism.catalog import fourbar
from symlink.symbolic.linkage import Linkage
from symlink.symbolic.loops import Loop
from symlink.symbolic.vectors import Vector, coordinates, lengths

OUTPUTS = ["coupler", "rocker", "rocker_speed", "rocker_accel"]
SEED003 = dict(a=20.0, b=66.0, c=56.0, d=80.0)


@pytest.fixture
def folder(empty_cache):
    return empty_cache


def count_calls(monkeypatch, owner, name):
    """Count the calls of ``owner.name`` (still calling it)."""
    calls = []
    original = getattr(owner, name)

    def counted(*args, **kwargs):
        calls.append(args)
        return original(*args, **kwargs)
    monkeypatch.setattr(owner, name, counted)
    return calls


def forbid_symbolic_work(monkeypatch):
    """Make every derivation step fail: a second run must not reach any of them."""
    def fail(*args, **kwargs):
        raise AssertionError("symbolic work on a cached scene")
    import symlink.symbolic.linkage
    monkeypatch.setattr(symlink.symbolic.linkage, "solve_loop", fail)
    monkeypatch.setattr(symlink.symbolic.linkage, "loop_rates", fail)
    monkeypatch.setattr(Linkage, "program", fail)
    import symlink.codegen.numpy
    monkeypatch.setattr(symlink.codegen.numpy, "numpy_module", fail)  # imported when cache.generated_code runs
    monkeypatch.setattr(sp, "cse", fail)


def check_against_reference(code):
    theta = 0.7
    result = code.function(theta=theta, **SEED003, branch=1, thetadot=10.5, thetaddot=2.0)
    expected = mp_fourbar(**SEED003, theta=theta, branch=1, crank_speed=10.5, crank_accel=2.0)
    assert float(result["rocker"]) == pytest.approx(float(expected["phi"]), abs=1e-13)
    assert float(result["rocker_accel"]) == pytest.approx(float(expected["phi_accel"]), rel=1e-12)


def test_folder_from_the_environment(tmp_path, monkeypatch):
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "here"))
    assert cache_directory() == tmp_path / "here"
    monkeypatch.delenv("SYMLINK_CACHE")
    monkeypatch.setenv("HOME", str(tmp_path))
    assert cache_directory() == tmp_path / ".cache" / "symlink"
    monkeypatch.setenv("SYMLINK_CACHE", "")
    assert cache_directory() is None


def test_second_run_does_no_symbolic_work(folder, monkeypatch):
    programs = count_calls(monkeypatch, Linkage, "program")
    first = generated_code(fourbar(), OUTPUTS)
    assert len(programs) == 1
    check_against_reference(first)
    assert generated_code(fourbar(), OUTPUTS) is first  # memory
    assert len(programs) == 1

    clear_memory()        # a new process: only the disk entry is left
    forbid_symbolic_work(monkeypatch)
    second = generated_code(fourbar(), OUTPUTS)  # building the linkage solves nothing either
    assert second.source == first.source and second.key == first.key
    check_against_reference(second)


def test_entry_is_one_verified_json_file_and_its_bytecode_written_atomically(folder):
    code = generated_code(fourbar(), ["rocker"])
    files = sorted(p.name for p in folder.iterdir())
    magic = importlib.util.MAGIC_NUMBER.hex()
    assert files == [f"{code.key}.{magic}.code", f"{code.key}.json"]  # no temporary file left behind
    entry = json.loads((folder / files[1]).read_text())
    assert entry["key"] == code.key and entry["text"] == code.source
    assert len(entry["sha256"]) == 64


def corruptions(entry: dict, other: dict):
    """Ways a disk entry can go wrong, each as the bytes left in the file."""
    text = json.dumps(entry)
    forged = dict(entry, text="raise SystemExit('never run')")
    return {
        "empty": b"",
        "truncated": text[: len(text) // 2].encode(),
        "not json": b"\x00\xff garbage",
        "not a dict": b"[1, 2, 3]",
        "missing checksum": json.dumps({k: v for k, v in entry.items() if k != "sha256"}).encode(),
        "changed text": json.dumps(forged).encode(),
        "another key's entry": json.dumps(other).encode(),
        "text not a string": json.dumps(dict(entry, text=123)).encode(),
        "other format": json.dumps(dict(entry, format=999)).encode(),
    }


@pytest.mark.parametrize("kind", list(corruptions({"text": ""}, {})))
def test_corrupt_entry_is_detected_and_rebuilt(folder, monkeypatch, kind):
    good = generated_code(fourbar(), OUTPUTS)
    other = generated_code(fourbar(), ["rocker"])
    path = folder / f"{good.key}.json"
    entries = {p: json.loads(p.read_text()) for p in folder.glob("*.json")}  # not compiled/, a background build's
    path.write_bytes(corruptions(entries[path], entries[folder / f"{other.key}.json"])[kind])
    clear_memory()
    programs = count_calls(monkeypatch, Linkage, "program")
    rebuilt = generated_code(fourbar(), OUTPUTS)
    assert len(programs) == 1  # derived again, not trusted
    assert rebuilt.source == good.source
    check_against_reference(rebuilt)
    assert json.loads(path.read_text()) == entries[path]  # and rewritten whole


def test_unwritable_folder_keeps_working_in_memory(tmp_path, monkeypatch):
    blocker = tmp_path / "a file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("SYMLINK_CACHE", str(blocker / "cache"))
    clear_memory()
    check_against_reference(generated_code(fourbar(), OUTPUTS))
    assert blocker.read_text() == "not a folder"
    clear_memory()


def test_empty_variable_turns_the_disk_cache_off(tmp_path, monkeypatch):
    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.setenv("SYMLINK_CACHE", "")
    clear_memory()
    check_against_reference(generated_code(fourbar(), OUTPUTS))
    assert list(tmp_path.iterdir()) == []
    clear_memory()


def test_unknown_output_fails_before_anything_is_cached(folder):
    with pytest.raises(ValueError, match="no output 'piston'"):
        generated_code(fourbar(), ["rocker", "piston"])
    with pytest.raises(ValueError, match="at least one output"):
        generated_code(fourbar(), [])
    assert not folder.exists() or list(folder.iterdir()) == []


def renamed_fourbar(**changes):
    """The catalog four-bar rebuilt with one thing changed."""
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, d = lengths("a b c d")
    e = changes.get("ground_angle", 0)
    AB, BC, DC, AD = Vector(a, theta), Vector(b, beta), Vector(c, phi), Vector(d, e)
    extras = changes.get("extras", {"transmission": sp.Abs(sp.atan2(sp.sin(beta - phi), sp.cos(beta - phi)))})
    return Linkage(changes.get("name", "fourbar"), [Loop(AD + DC - BC - AB, name="ABCD")], [theta], [beta, phi],
                   points={"A": None, "B": AB.as_sum(), "C": AB + BC, "D": AD.as_sum()},
                   roles={"crank": theta, "coupler": beta, "rocker": phi}, extras=extras)


def test_key_depends_on_everything_the_code_depends_on(monkeypatch):
    base = cache_key(fourbar(), OUTPUTS)
    assert cache_key(fourbar(), OUTPUTS) == base
    different = {
        cache_key(fourbar(), ["rocker"]),
        cache_key(fourbar(), OUTPUTS[::-1]),
        cache_key(fourbar(), OUTPUTS, kind="c"),
        cache_key(renamed_fourbar(name="other"), OUTPUTS),
        cache_key(renamed_fourbar(ground_angle=sp.pi / 6), OUTPUTS),
        cache_key(renamed_fourbar(extras={}), OUTPUTS),
    }
    monkeypatch.setattr(cache, "__version__", "99.0")
    different.add(cache_key(fourbar(), OUTPUTS))
    monkeypatch.undo()
    monkeypatch.setattr(sp, "__version__", "0.0.1")
    different.add(cache_key(fourbar(), OUTPUTS))
    assert base not in different and len(different) == 8


def test_definition_is_the_same_in_every_process():
    program = ("from symlink.mechanism.catalog import fourbar; import symlink.numeric.cache as c; import hashlib; "
               "c._source_digest = lambda: 'pinned'; "  # other work on the tree may change the real digest
               "print(c.cache_key(fourbar(), ['rocker']), "
               "hashlib.sha256(c.definition(fourbar()).encode()).hexdigest())")
    seen = set()
    for seed in ("1", "12345"):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, env=env,
                              cwd=Path(__file__).parent.parent.parent, check=True)
        seen.add(done.stdout)
    assert len(seen) == 1  # keys and definitions agree whatever the hash seed
    assert seen.pop().split()[1] == hashlib.sha256(definition(fourbar()).encode()).hexdigest()


def test_solver_goes_through_the_cache(folder, monkeypatch):
    from symlink.numeric.solver import Solver
    first = Solver(fourbar(), OUTPUTS)
    assert (folder / f"{cache_key(fourbar(), fourbar().with_singular(OUTPUTS))}.json").is_file()  # rates bring their flag
    clear_memory()
    forbid_symbolic_work(monkeypatch)
    second = Solver(fourbar(), OUTPUTS)
    assert second.source == first.source and second.arguments == first.arguments
    result = second(theta=numpy.array([0.0]), **SEED003, branch=1)
    assert numpy.degrees(result["rocker"][0]) == pytest.approx(110.7424, abs=1e-4)  # seed 003 table


# --- what the key digests ------------------------------------------------------

def key_with(monkeypatch, edit: str | None = None) -> str:
    """The four-bar's key, as a new process works it out, with the package file ``edit`` edited."""
    if edit is not None:
        edit_module(monkeypatch, edit)
    forget_source_digests()
    try:
        return cache_key(fourbar(), OUTPUTS)
    finally:
        monkeypatch.undo()
        forget_source_digests()


@pytest.mark.parametrize("relative", ["plot/__init__.py", "plot/animation.py", "plot/view.py", "cli/__init__.py",
                                      "cli/bench.py", "analysis/__init__.py", "common/files.py",
                                      "numeric/results.py"])
def test_editing_a_module_that_shapes_no_code_keeps_the_key(monkeypatch, relative):
    base = key_with(monkeypatch)
    assert key_with(monkeypatch, relative) == base


@pytest.mark.parametrize("relative", ["symbolic/vectors.py", "symbolic/loops.py", "symbolic/position.py",
                                      "symbolic/motion.py", "symbolic/linkage.py", "codegen/c.py", "codegen/octave.py",
                                      "codegen/newton.py", "codegen/latex.py", "io/export.py", "numeric/compiled.py"])
def test_editing_a_module_that_shapes_code_changes_the_key(monkeypatch, relative):
    base = key_with(monkeypatch)
    assert key_with(monkeypatch, relative) != base


def test_a_warm_process_reads_the_source_digest_from_the_cache_and_an_edit_hashes_again(folder, monkeypatch):
    """The digest of symlink's source is an entry keyed by each file's time, size and inode: a second process
    reads no source file; an edited file (a new size and time) is read and hashed again."""
    import hashlib
    names = cache._code_shaping_names(cache.CODE_SHAPING)
    package = Path(cache.__file__).parent.parent
    expected = hashlib.blake2b()  # the digest written out: each file's name and its BLAKE2b
    for name in names:
        expected.update(name.encode() + b"\0" + hashlib.blake2b((package / name).read_bytes()).digest())
    forget_source_digests()
    assert cache._source_digest() == expected.hexdigest()
    read = count_calls(monkeypatch, cache, "_module_bytes")
    forget_source_digests()
    clear_memory()  # a new process: the digest comes from the disk entry
    assert cache._source_digest() == expected.hexdigest() and len(read) == 0
    edit_module(monkeypatch, "codegen/c.py")
    clear_memory()
    assert cache._source_digest() != expected.hexdigest() and len(read) >= 1
    monkeypatch.undo()
    forget_source_digests()


def test_every_code_shaping_name_is_a_module_or_package():
    package = Path(cache.__file__).parent.parent
    for name in cache.CODE_SHAPING:
        assert (package / f"{name}.py").is_file() or (package / name).is_dir(), \
            f"cache.CODE_SHAPING names {name!r}, which is gone: update the list"
    files = cache.code_shaping_files()
    if (package / "codegen").is_dir():  # every printer of the code generation package counts
        assert set((package / "codegen").rglob("*.py")) <= set(files)
    assert not {path.stem for path in files} & {"plot", "animation", "view", "cli", "bench", "scene", "solver"}


def test_folder_follows_xdg_when_symlink_cache_is_unset(tmp_path, monkeypatch):
    monkeypatch.delenv("SYMLINK_CACHE", raising=False)
    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert cache_directory() == tmp_path / "xdg" / "symlink"
    monkeypatch.setenv("XDG_CACHE_HOME", "relative/path")  # ignored, as the XDG specification says
    assert cache_directory() == tmp_path / ".cache" / "symlink"
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "mine"))  # the variable of symlink comes first
    assert cache_directory() == tmp_path / "mine"


# --- a cache only its owner can write ------------------------------------------

def planted(folder: Path, marker: Path) -> None:
    """Rewrite every entry in ``folder`` as an attacker would: code that leaves ``marker``, checksum fixed up."""
    for path in folder.glob("*.json"):
        entry = json.loads(path.read_text())
        if len(entry["text"]) == 128 and entry["text"].isalnum():
            continue  # the digest of symlink's source (cache._source_digest): a key's part, not code
        entry["text"] = f"import pathlib; pathlib.Path({str(marker)!r}).write_text('ran')\n" + entry["text"]
        entry["sha256"] = cache._checksum(entry["key"], entry["text"])
        path.write_text(json.dumps(entry))
        path.chmod(0o600)


def cache_warnings(caught) -> list[str]:
    return [str(w.message) for w in caught if issubclass(w.category, cache.CacheWarning)]


def test_created_private_whatever_the_umask(folder):
    previous = os.umask(0)
    try:
        code = generated_code(fourbar(), ["rocker"])
    finally:
        os.umask(previous)
    assert oct(os.stat(folder).st_mode & 0o777) == "0o700"
    assert oct(os.stat(folder / f"{code.key}.json").st_mode & 0o777) == "0o600"


def chown_to_nobody(path: Path) -> None:
    try:
        os.chown(path, 65534, -1)
    except (PermissionError, AttributeError):
        pytest.skip("cannot give a file to another user here")


@pytest.mark.parametrize("how", ["folder group-writable", "folder other-writable", "folder owned by another user",
                                 "entry group-writable", "entry owned by another user"])
def test_nothing_is_loaded_unless_only_its_owner_could_have_written_it(folder, tmp_path, monkeypatch, how):
    good = generated_code(fourbar(), OUTPUTS)
    marker = tmp_path / "planted-code-ran"
    planted(folder, marker)
    entry = folder / f"{good.key}.json"
    what, change = how.split(" ", 1)
    target = folder if what == "folder" else entry
    if change == "owned by another user":
        chown_to_nobody(target)
    else:
        target.chmod((0o700 if what == "folder" else 0o600) | (0o020 if "group" in change else 0o002))
    clear_memory()
    programs = count_calls(monkeypatch, Linkage, "program")
    with pytest.warns(cache.CacheWarning) as caught:
        code = generated_code(fourbar(), OUTPUTS)
    assert not marker.exists() and len(programs) == 1  # derived again, the planted code never ran
    check_against_reference(code)
    messages = cache_warnings(caught)
    assert len(messages) == 1 and ("owned by user" in messages[0] or "writable by" in messages[0])
    if what == "folder":  # and nothing is written to such a folder either
        assert json.loads(entry.read_text())["text"].startswith("import pathlib")


def test_the_planted_entry_would_run_from_a_private_folder(folder, tmp_path):
    """The control of the test above: with the folder private, the owner's (planted) entry is used."""
    generated_code(fourbar(), OUTPUTS)
    marker = tmp_path / "planted-code-ran"
    planted(folder, marker)
    clear_memory()
    generated_code(fourbar(), OUTPUTS)
    assert marker.exists()


@pytest.mark.parametrize("how", ["group-writable", "owned by another user", "private (control)"])
def test_command_line_loads_nothing_from_a_cache_others_can_write(tmp_path, how):
    folder, marker = tmp_path / "cache", tmp_path / "planted-code-ran"
    command = [sys.executable, "-m", "symlink", "fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56",
               "--ground", "80", "--step", "90"]
    env = dict(os.environ, SYMLINK_CACHE=str(folder))
    run = lambda: subprocess.run(command, capture_output=True, text=True, env=env,  # noqa: E731
                                 cwd=Path(__file__).parent.parent.parent)
    first = run()
    assert first.returncode == 0, first.stderr
    planted(folder, marker)
    if how == "group-writable":
        folder.chmod(0o770)
    elif how == "owned by another user":
        chown_to_nobody(folder)
    second = run()
    assert second.returncode == 0 and second.stdout == first.stdout, second.stderr
    assert marker.exists() == (how == "private (control)")


# --- faults: each entry that cannot be used is rebuilt, with one warning ---------------

@pytest.fixture
def bounded_time():
    """Fail (instead of hanging the suite) if the test blocks for a minute."""
    import signal

    def hung(*_):
        raise TimeoutError("blocked on a cache entry")
    previous = signal.signal(signal.SIGALRM, hung)
    signal.alarm(60)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, previous)


@pytest.mark.parametrize("kind", ["deeply nested", "a FIFO", "a folder", "a symbolic link", "binary garbage"])
def test_an_entry_that_is_not_a_readable_file_is_rebuilt_with_one_warning(folder, tmp_path, monkeypatch,
                                                                          bounded_time, kind):
    good = generated_code(fourbar(), OUTPUTS)
    path = folder / f"{good.key}.json"
    path.unlink()
    if kind == "deeply nested":
        path.write_text("[" * 200_000)
    elif kind == "a FIFO":
        os.mkfifo(path)
    elif kind == "a folder":
        path.mkdir()
    elif kind == "a symbolic link":
        elsewhere = tmp_path / "elsewhere.json"
        elsewhere.write_text(json.dumps({"format": 1, "key": good.key, "text": "x = 1",
                                         "sha256": cache._checksum(good.key, "x = 1")}))
        path.symlink_to(elsewhere)
    else:
        path.write_bytes(bytes(range(256)) * 10)
    clear_memory()
    programs = count_calls(monkeypatch, Linkage, "program")
    with pytest.warns(cache.CacheWarning) as caught:
        code = generated_code(fourbar(), OUTPUTS)
    assert len(programs) == 1 and code.source == good.source
    check_against_reference(code)
    assert len(cache_warnings(caught)) == 1
    if kind != "a folder":  # replaced by a good entry (a folder in the way stays: memory only)
        assert path.is_file() and not path.is_symlink() and json.loads(path.read_text())["text"] == good.source


def test_a_full_disk_keeps_the_text_in_memory_and_leaves_nothing(folder, monkeypatch):
    import errno

    def full(*_):
        raise OSError(errno.ENOSPC, "No space left on device")
    private = cache.trusted_directory()  # the folder exists; writing into it fails
    with pytest.MonkeyPatch.context() as disk:
        disk.setattr(os, "write", full)
        code = generated_code(fourbar(), OUTPUTS)
    check_against_reference(code)
    assert list(private.iterdir()) == []  # no entry, no temporary file


def test_leftovers_of_killed_runs_are_removed_on_the_next_run(folder):
    import time
    generated_code(fourbar(), ["rocker"])
    old = time.time() - 2 * cache.LEFTOVER_AGE
    leftovers = [folder / ".build-abc123", folder / f".{'0' * 64}.json.1a2b3c.tmp", folder / ".load-77.so"]
    leftovers[0].mkdir()
    (leftovers[0] / "symlink.c").write_text("int x;")
    for path in leftovers[1:]:
        path.write_text("partial")
    for path in leftovers:
        os.utime(path, (old, old))
    running = folder / ".build-running"  # another process's, still young
    running.mkdir()
    clear_memory()  # the next run
    generated_code(fourbar(), ["rocker"])
    assert not any(path.exists() for path in leftovers) and running.is_dir()


# symlink cache info / clear: counting and removing symlink's own names only.

HEX = "0123456789abcdef" * 4


def plant_others(folder):
    """Names in the cache folder that symlink never writes: each must survive a clear.  Returns them."""
    outside = folder.parent / "outside.json"
    outside.write_text("not in the cache")
    planted = {
        "notes.txt": "mine", "ABC.json": "{}", f"{HEX}.json.bak": "{}", f"{HEX.upper()}.json": "{}",
        f"{HEX}.code": "", f"{HEX}.0d0d0a.code": "", f"{HEX}.0d0d0a0d.pyc": "", f"{HEX}.0d0d0a0d.code.bak": "",
        f".other.{HEX[:12]}.tmp": "", "compiled/mine.so": "x", f"compiled/{HEX}.json": "{}",
    }
    for name, text in planted.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    (folder / f"{'f' * 64}.json").symlink_to(outside)  # our kind of name, but a link: not ours
    (folder / ".build-abcdefgh").mkdir()  # our kind of name, but only in compiled/
    return set(planted) | {f"{'f' * 64}.json", ".build-abcdefgh"}, outside


def listing(folder):
    return {path.relative_to(folder).as_posix() for path in folder.rglob("*") if not path.is_dir() or
            path.name.startswith(".build-")}


def test_info_counts_and_clear_removes_only_what_symlink_wrote(folder):
    from symlink.numeric.cache_folder import cache_contents, clear_cache
    code = generated_code(fourbar(), ["rocker"])
    entry = folder / f"{code.key}.json"
    bytecode = cache.entry_path(folder, code.key, bytecode=True)
    assert entry.is_file() and bytecode.is_file()
    ours = {path.name: path.stat().st_size for path in folder.iterdir()}  # and the source digest's entry, if new
    (folder / "compiled").mkdir(mode=0o700)
    build = folder / "compiled" / ".build-x1y2z3_4"  # a killed build: a folder with a half-written source
    build.mkdir()
    (build / "symlink.c").write_text("double f(double x) { return x; }\n")
    ours["compiled/.build-x1y2z3_4"] = len("double f(double x) { return x; }\n")
    for name, text in {f"compiled/{HEX}.so": "\x7fELF...", f"compiled/{HEX}.sha256": "ab\n",
                       f"compiled/.load-{HEX[:16]}.so": "\x7fELF", f".{HEX}.json.{HEX[:12]}.tmp": "{",
                       f"{HEX}.0d0d0a0d.code": "another Python's", f"{HEX}.0d0d0a0d.opt-2.code": "at -OO",
                       f".{HEX}.0d0d0a0d.code.{HEX[:12]}.tmp": "half"}.items():
        (folder / name).write_text(text)
        ours[name] = len(text.encode())
    others, outside = plant_others(folder)

    contents = cache_contents(folder)
    assert (contents.trusted, contents.problem, contents.exists) == (True, "", True)
    assert (contents.entries, contents.size, contents.others) == (len(ours), sum(ours.values()), len(others))
    assert listing(folder) >= set(ours) | others, "counting changes nothing"

    removed = clear_cache(folder)
    assert (removed.entries, removed.size, removed.others) == (len(ours), sum(ours.values()), len(others))
    left = listing(folder)
    assert not left & set(ours) and left >= others, left
    assert outside.read_text() == "not in the cache"
    assert cache_contents(folder).entries == 0
    again = generated_code(fourbar(), ["rocker"])  # the next run derives it again
    assert again.key == code.key and entry.is_file() and bytecode.is_file()


def test_a_real_compiled_library_is_counted_and_cleared(folder):
    from symlink.numeric.cache_folder import cache_contents, clear_cache
    from symlink.numeric.compiled import CompilerUnavailable, compile_shared
    try:
        compile_shared("double twice(double x) { return 2 * x; }")
    except CompilerUnavailable as why:
        pytest.skip(f"no C compiler: {why}")
    written = list((folder / "compiled").iterdir())
    assert sorted(path.suffix for path in written) == [".sha256", ".so"]
    assert cache_contents(folder).entries == 2 and cache_contents(folder).others == 0
    size = sum(path.stat().st_size for path in written)
    assert cache_contents(folder).size == size and clear_cache(folder).size == size
    assert not (folder / "compiled").exists()  # symlink made it; empty now, so it goes too


@pytest.mark.parametrize("mode, why", [(0o770, "writable by group"), (0o707, "writable by others")])
def test_clear_refuses_a_folder_others_can_write(tmp_path, mode, why):
    from symlink.numeric.cache_folder import cache_contents, clear_cache
    folder = tmp_path / "shared"
    folder.mkdir()
    (folder / f"{HEX}.json").write_text("{}")
    folder.chmod(mode)
    contents = cache_contents(folder)
    assert not contents.trusted and why in contents.problem and contents.entries == 0
    with pytest.raises(ValueError, match=f"not clearing the cache folder: .*{why}"):
        clear_cache(folder)
    assert (folder / f"{HEX}.json").read_text() == "{}"


def test_a_compiled_folder_others_can_write_is_left_alone(folder):
    from symlink.numeric.cache_folder import cache_contents, clear_cache
    folder.mkdir(mode=0o700)
    (folder / "compiled").mkdir()
    (folder / "compiled" / f"{HEX}.so").write_text("planted")
    (folder / "compiled").chmod(0o777)
    assert (cache_contents(folder).entries, cache_contents(folder).others) == (0, 1)
    assert clear_cache(folder).entries == 0
    assert (folder / "compiled" / f"{HEX}.so").read_text() == "planted"


def test_a_folder_that_does_not_exist_is_empty_and_not_created(tmp_path):
    from symlink.numeric.cache_folder import cache_contents, clear_cache
    folder = tmp_path / "never"
    assert (cache_contents(folder).exists, clear_cache(folder).entries) == (False, 0)
    assert not folder.exists()


def test_a_file_where_the_folder_should_be_is_not_trusted(tmp_path):
    from symlink.numeric.cache_folder import cache_contents, clear_cache
    (tmp_path / "file").write_text("")
    assert "not a folder" in cache_contents(tmp_path / "file").problem
    with pytest.raises(ValueError, match="not a folder"):
        clear_cache(tmp_path / "file")
    assert (tmp_path / "file").is_file()


# --- bytecode beside a generated module's entry: a warm load compiles nothing ---------------

def count_compilations(monkeypatch):
    """Count the compilations of generated module source (still compiling)."""
    import symlink.codegen.loading
    return count_calls(monkeypatch, symlink.codegen.loading, "compile_numpy_module")


def bytecode_file(folder, key):
    return cache.entry_path(folder, key, bytecode=True)


def test_a_warm_load_runs_the_cached_bytecode_without_compiling(folder, monkeypatch):
    compilations = count_compilations(monkeypatch)
    first = generated_code(fourbar(), OUTPUTS)
    assert len(compilations) == 1 and bytecode_file(folder, first.key).is_file()
    clear_memory()  # a new process
    forbid_symbolic_work(monkeypatch)
    warm = generated_code(fourbar(), OUTPUTS)
    assert len(compilations) == 1  # the code came from the bytecode file
    check_against_reference(warm)
    assert oct(os.stat(bytecode_file(folder, first.key)).st_mode & 0o777) == "0o600"


def test_the_bytecode_file_is_named_and_marked_for_this_python(folder):
    code = generated_code(fourbar(), ["rocker"])
    path = bytecode_file(folder, code.key)
    magic = importlib.util.MAGIC_NUMBER
    assert path.name == f"{code.key}.{magic.hex()}.code"  # tests run without -O
    data = path.read_bytes()
    entry = json.loads((folder / f"{code.key}.json").read_text())
    assert magic in data[:64] and entry["sha256"].encode() in data[:128]  # bound to this Python and this entry


def bytecode_corruptions(data: bytes, other: bytes, magic: bytes) -> dict[str, bytes]:
    """Ways a bytecode file can go wrong, each as the bytes left in it (``other``: another entry's good file)."""
    flipped = bytearray(data)
    flipped[-10] ^= 0xFF
    return {
        "empty": b"",
        "truncated": data[: len(data) // 2],
        "cut at the end": data[:-1],
        "a byte of code changed": bytes(flipped),
        "garbage": b"\x00\xff garbage",
        "another Python's magic number": data.replace(magic, bytes([magic[0] ^ 1]) + magic[1:], 1),
        "another entry's bytecode": other,
    }


@pytest.mark.parametrize("kind", list(bytecode_corruptions(b"0123456789ab", b"", b"0123")))
def test_a_bad_bytecode_file_is_ignored_and_rewritten(folder, monkeypatch, kind):
    good = generated_code(fourbar(), OUTPUTS)
    other = generated_code(fourbar(), ["rocker"])
    path = bytecode_file(folder, good.key)
    path.write_bytes(bytecode_corruptions(path.read_bytes(), bytecode_file(folder, other.key).read_bytes(),
                                          importlib.util.MAGIC_NUMBER)[kind])
    clear_memory()
    compilations = count_compilations(monkeypatch)
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # ignored silently: a cache of the text's compilation, nothing to report
        rebuilt = generated_code(fourbar(), OUTPUTS)
    assert len(compilations) == 1  # compiled again from the verified text
    assert rebuilt.source == good.source
    check_against_reference(rebuilt)
    clear_memory()  # the file was rewritten: the next process uses it
    again = generated_code(fourbar(), OUTPUTS)
    assert len(compilations) == 1
    check_against_reference(again)


def test_a_bytecode_file_others_can_write_is_not_run(folder, monkeypatch, tmp_path):
    good = generated_code(fourbar(), OUTPUTS)
    path = bytecode_file(folder, good.key)
    path.chmod(0o666)
    clear_memory()
    compilations = count_compilations(monkeypatch)
    with pytest.warns(cache.CacheWarning) as caught:
        code = generated_code(fourbar(), OUTPUTS)
    assert len(compilations) == 1 and len(cache_warnings(caught)) == 1 and "bytecode" in cache_warnings(caught)[0]
    check_against_reference(code)
    assert oct(os.stat(path).st_mode & 0o777) == "0o600"  # replaced by a private file


def test_an_untrusted_folder_s_bytecode_is_not_read(folder, monkeypatch):
    good = generated_code(fourbar(), OUTPUTS)
    path = bytecode_file(folder, good.key)
    before = path.read_bytes()
    folder.chmod(0o770)
    clear_memory()
    compilations = count_compilations(monkeypatch)
    reads = count_calls(monkeypatch, cache, "_read_bytecode")
    with pytest.warns(cache.CacheWarning):
        code = generated_code(fourbar(), OUTPUTS)
    assert len(compilations) == 1 and reads == []  # a good bytecode file there, and still not read
    check_against_reference(code)
    assert path.read_bytes() == before  # nor written


def test_a_bytecode_file_that_cannot_be_written_costs_a_compilation_only(folder, monkeypatch):
    good = generated_code(fourbar(), OUTPUTS)
    path = bytecode_file(folder, good.key)
    path.unlink()
    path.mkdir()  # a folder in the way: the write fails, as in a read-only cache
    for _ in range(2):  # two processes
        clear_memory()
        compilations = count_compilations(monkeypatch)
        code = generated_code(fourbar(), OUTPUTS)
        assert len(compilations) == 1
        check_against_reference(code)
    assert path.is_dir() and not [p for p in folder.iterdir() if p.name.endswith(".tmp")]


def test_the_same_code_in_one_process_is_compiled_once(folder, monkeypatch):
    from symlink.numeric.cached_solver import CachedSolver
    first = CachedSolver("fourbar", ["rocker"])
    compilations = count_compilations(monkeypatch)
    second = CachedSolver("fourbar", ["rocker"])
    assert compilations == [] and first.function is not second.function  # the same code, each its own namespace
    # The rocker angle by the law of cosines (seed 003 at theta = 0: the diagonal BD = d - a).
    a, b, c, d = 20.0, 66.0, 56.0, 80.0
    diagonal = d - a
    expected = numpy.pi - numpy.arccos((c * c + diagonal * diagonal - b * b) / (2 * c * diagonal))
    result = second(theta=0.0, a=a, b=b, c=c, d=d, branch=1)["rocker"]
    assert float(result) == pytest.approx(expected, abs=1e-12)


def test_under_python_O_the_bytecode_has_its_own_name_which_symlink_counts_as_its_own(folder, monkeypatch):
    import re
    import types
    plain, plain_header = cache.entry_path(folder, HEX, bytecode=True).name, cache._bytecode_header(HEX, "x = 1\n")
    monkeypatch.setattr(cache, "sys", types.SimpleNamespace(flags=types.SimpleNamespace(optimize=2)))
    optimized = cache.entry_path(folder, HEX, bytecode=True).name
    assert optimized == f"{HEX}.{importlib.util.MAGIC_NUMBER.hex()}.opt-2.code" and optimized != plain
    assert re.match(cache_folder._OWN_NAMES, optimized) and re.match(cache_folder._OWN_NAMES, f".{optimized}.{HEX[:12]}.tmp")
    assert cache._bytecode_header(HEX, "x = 1\n") != plain_header  # a file renamed across levels is not used
