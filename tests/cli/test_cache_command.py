"""``symlink cache info|clear``: the folder, its entries and bytes, and clearing only symlink's own files."""
import pytest

from cache_fixture import empty_cache  # noqa: F401 - a fixture
from symlink.cli import main

FOURBAR = ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80", "--angles", "0"]


def run(capsys, *argv):
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return status, out, err


def fields(out):
    return dict(line.split(None, 1) for line in out.splitlines())


def test_info_then_clear_after_a_table(empty_cache, capsys, monkeypatch):
    monkeypatch.setenv("SYMLINK_BACKEND", "numpy")  # no compiled solver building in the background meanwhile
    status, out, _ = run(capsys, "cache", "info")
    assert status == 0 and fields(out)["folder"] == f"{empty_cache} (not created yet)"
    assert run(capsys, *FOURBAR)[0] == 0
    (empty_cache / "notes.txt").write_text("mine")
    entries = [path for path in empty_cache.iterdir() if path.suffix in (".json", ".code")]  # texts, bytecode
    texts = {path.name.split(".")[0] for path in entries if path.suffix == ".json"}
    codes = [path.name.split(".")[0] for path in entries if path.suffix == ".code"]
    assert codes and set(codes) <= texts and len(set(codes)) == len(codes)  # each beside its text entry
    size = sum(path.stat().st_size for path in entries)
    status, out, err = run(capsys, "cache", "info")
    assert status == 0 and err == ""
    assert fields(out) == {"folder": str(empty_cache), "entries": str(len(entries)), "bytes": str(size),
                           "trusted": "yes (only you can write it)",
                           "leftovers": "0 (of builds or writes interrupted or failed)",
                           "others": "1 (not written by symlink, left alone)"}
    status, out, _ = run(capsys, "cache", "clear")
    assert status == 0 and fields(out)["removed"] == f"{len(entries)} entries, {size} bytes"
    assert [path.name for path in empty_cache.iterdir()] == ["notes.txt"]


def test_another_folder_and_a_folder_others_can_write(tmp_path, capsys):
    shared = tmp_path / "shared"
    shared.mkdir(mode=0o777)
    shared.chmod(0o777)
    entry = shared / f"{'a' * 64}.json"
    entry.write_text("{}")
    status, out, _ = run(capsys, "cache", "info", "--folder", shared)
    assert status == 0 and fields(out)["trusted"].startswith("no: ") and "writable by group and others" in out
    status, out, err = run(capsys, "cache", "clear", "--folder", shared)
    assert status == 2 and out == "" and err.startswith("symlink: error: not clearing the cache folder")
    assert entry.read_text() == "{}"


def test_no_disk_cache(monkeypatch, capsys):
    monkeypatch.setenv("SYMLINK_CACHE", "")
    for action in ("info", "clear"):
        assert run(capsys, "cache", action)[1] == "no disk cache: SYMLINK_CACHE is set empty\n"


@pytest.mark.parametrize("argv", [["cache", "--help"], ["cache", "info", "--help"], ["cache", "clear", "--help"]])
def test_help_has_a_summary_units_and_an_example(argv, capsys):
    status, out, _ = run(capsys, *argv)
    assert status == 0 and "units: sizes in bytes" in out and "example: symlink cache " in out


@pytest.mark.parametrize("planted", [
    ("compiled", ".build-abcd1234", "folder"),  # a compiler's build folder of a killed run
    ("", "." + "a" * 64 + ".json.0123456789ab.tmp", "file"),  # a write killed between its temporary and its rename
    ("compiled", ".load-0123456789abcdef.so", "file"),  # a private copy of a library, left by a killed load
], ids=["a build folder", "a derived module's temporary", "a library's private copy"])
def test_leftovers_of_interrupted_builds_are_reported_and_cleared(planted, tmp_path, monkeypatch, capsys):
    from symlink.cli import main
    folder = tmp_path / "cache"
    where, name, kind = planted
    place = folder / where if where else folder
    place.mkdir(parents=True, mode=0o700)
    folder.chmod(0o700)
    (place / name).mkdir() if kind == "folder" else (place / name).write_bytes(b"half")
    assert main(["cache", "info", "--folder", str(folder)]) == 0
    assert "leftovers 1 (of builds or writes interrupted or failed; 'symlink cache clear' removes them)" \
        in capsys.readouterr().out
    assert main(["cache", "clear", "--folder", str(folder)]) == 0
    assert "removed  1 entries" in capsys.readouterr().out
    assert [p for p in folder.rglob("*")] == []
    assert main(["cache", "info", "--folder", str(folder)]) == 0
    assert "leftovers 0 (of builds or writes interrupted or failed)" in capsys.readouterr().out
