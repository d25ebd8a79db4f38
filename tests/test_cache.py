"""The scene cache: keys, verified disk entries, and no symbolic work on a second run."""
import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy
import pytest
import sympy as sp

import symlink.cache as cache
from cache_fixture import empty_cache  # noqa: F401 - a fixture
from references import mp_fourbar
from symlink.cache import cache_directory, cache_key, clear_memory, definition, generated_code
from symlink.catalog import fourbar
from symlink.linkage import Linkage
from symlink.loops import Loop
from symlink.vectors import Vector, coordinates, lengths

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
    import symlink.linkage
    monkeypatch.setattr(symlink.linkage, "solve_loop", fail)
    monkeypatch.setattr(symlink.linkage, "loop_rates", fail)
    monkeypatch.setattr(Linkage, "program", fail)
    monkeypatch.setattr(cache, "numpy_module", fail)
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


def test_entry_is_one_verified_json_file_written_atomically(folder):
    code = generated_code(fourbar(), ["rocker"])
    files = sorted(p.name for p in folder.iterdir())
    assert files == [f"{code.key}.json"]  # no temporary file left behind
    entry = json.loads((folder / files[0]).read_text())
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
    entries = {p: json.loads(p.read_text()) for p in folder.iterdir()}
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
    program = ("from symlink.catalog import fourbar; import symlink.cache as c; import hashlib; "
               "c._source_digest = lambda: 'pinned'; "  # other work on the tree may change the real digest
               "print(c.cache_key(fourbar(), ['rocker']), "
               "hashlib.sha256(c.definition(fourbar()).encode()).hexdigest())")
    seen = set()
    for seed in ("1", "12345"):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, env=env,
                              cwd=Path(__file__).parent.parent, check=True)
        seen.add(done.stdout)
    assert len(seen) == 1  # keys and definitions agree whatever the hash seed
    assert seen.pop().split()[1] == hashlib.sha256(definition(fourbar()).encode()).hexdigest()


def test_solver_goes_through_the_cache(folder, monkeypatch):
    from symlink.solver import Solver
    first = Solver(fourbar(), OUTPUTS)
    assert (folder / f"{cache_key(fourbar(), OUTPUTS)}.json").is_file()
    clear_memory()
    forbid_symbolic_work(monkeypatch)
    second = Solver(fourbar(), OUTPUTS)
    assert second.source == first.source and second.arguments == first.arguments
    result = second(theta=numpy.array([0.0]), **SEED003, branch=1)
    assert numpy.degrees(result["rocker"][0]) == pytest.approx(110.7424, abs=1e-4)  # seed 003 table
