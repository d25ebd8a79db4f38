"""Hard edges of the command line, new cases of each class (issue #32, item 6): a set of files is written all or
none; a device or FIFO named as one of a set is written through, never replaced; a request that defines nothing
(a zero-length range) is refused in one line, exit 2."""
from __future__ import annotations

import errno
import math
import os
import stat

import numpy
import pytest

from symlink.cli import main


def _one_error_line(err: str, *words: str) -> None:
    assert err.count("\n") == 1 and err.startswith("symlink: error: ") and "Traceback" not in err, err
    for word in words:
        assert word in err, err


def _slider_travel(a: float, b: float, e: float, theta: float) -> float:
    """A slider-crank's slider position by hand: the pin B = a e^{i theta}, the slider on y = e at distance b."""
    return a * math.cos(theta) + math.sqrt(b * b - (a * math.sin(theta) - e) ** 2)


def _function_targets(tmp_path) -> str:
    inputs = numpy.linspace(10.0, 150.0, 7)
    path = tmp_path / "targets" / "t.csv"
    path.parent.mkdir()
    path.write_text("theta,s\n" + "".join(f"{float(q)!r},{_slider_travel(1.3, 4.1, 0.7, math.radians(q))!r}\n"
                                           for q in inputs))
    return str(path)


def _full_after_first_write(monkeypatch, folder) -> None:
    """The disk under ``folder`` fills after the up-front check: the first file's bytes there go out, every later
    write there fails (writes elsewhere, such as the cache's, go on)."""
    import symlink.common.files as files
    written: list[str] = []
    real = os.write

    def write(handle, data):
        where = os.readlink(f"/proc/self/fd/{handle}")
        if not where.startswith(str(folder)):
            return real(handle, data)
        if written:
            raise OSError(errno.ENOSPC, "No space left on device")
        written.append(where)
        return len(data)
    monkeypatch.setattr(files.os, "write", write)


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="needs /proc/self/fd to tell the files apart")
def test_a_full_disk_under_synthesize_writes_none_of_out_record_and_plot(tmp_path, capsys, monkeypatch):
    targets = _function_targets(tmp_path)
    out = tmp_path / "out"
    argv = ["synthesize", "function", "slider-crank", targets, "--set", "a=1.0,b=3.5", "--bound", "a=0.5,2",
            "--bound", "b=3,5", "--out", str(out / "design.toml"), "--record", str(out / "design.json"),
            "--plot", str(out / "f.png")]
    _full_after_first_write(monkeypatch, out)
    assert main(argv) == 1
    err = capsys.readouterr().err
    errors = [line for line in err.splitlines() if line.startswith("symlink: error:")]
    assert len(errors) == 1 and "No space left on device" in errors[0] and "Traceback" not in err, err
    assert any(f"{out / name}:" in errors[0] for name in ("design.toml", "design.json", "f.png")), errors
    assert ".tmp" not in errors[0]
    assert not out.exists() or list(out.iterdir()) == []  # the file written in full is taken back, no temporary
    monkeypatch.undo()
    assert main(argv) == 0  # and with room on the disk, all three
    assert sorted(p.name for p in out.iterdir()) == ["design.json", "design.toml", "f.png"]


@pytest.mark.parametrize("argv", [
    ["parts", "fourbar", "--pin-diameter", "4", "--svg", "{pipe}", "--assembly", "{tmp}/a.svg"],
    ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80", "--angles", "0",
     "--plot", "{pipe}", "--plot-transmission", "{tmp}/t.png"],
], ids=["parts", "two figures"])
def test_a_fifo_named_in_a_set_of_files_is_never_replaced_by_a_file(argv, tmp_path, capsys):
    pipe = tmp_path / "pipe.svg" if argv[0] == "parts" else tmp_path / "pipe.png"
    os.mkfifo(pipe)
    argv = [word.replace("{pipe}", str(pipe)).replace("{tmp}", str(tmp_path)) for word in argv]
    assert main(argv) == 1  # no reader on the pipe: the system's reason, naming it
    err = capsys.readouterr().err
    assert f"{pipe}:" in err and "Traceback" not in err, err
    assert stat.S_ISFIFO(os.stat(pipe).st_mode)  # still the FIFO
    assert sorted(p.name for p in tmp_path.iterdir()) == [pipe.name]  # the other file is not written either


SWEEP = ["--no-progress", "--scheduler", "synchronous", "--samples", "16"]


@pytest.mark.parametrize("argv, words", [
    (["sweep", "fourbar", "{tmp}/s", "--vary", "a=10:10", "--grid", "3", *SWEEP], "a=10:10"),
    (["sweep", "fourbar", "{tmp}/s", "--vary", "a=10:20,b=60:60", "--grid", "3", *SWEEP], "b=60:60"),
    (["sweep", "fourbar", "{tmp}/s", "--vary", "a=10:10", "--random", "4", *SWEEP], "a=10:10"),
], ids=["a grid", "a second range", "random designs"])
def test_a_zero_length_range_is_refused_naming_it(argv, words, tmp_path, capsys):
    argv = [word.replace("{tmp}", str(tmp_path)) for word in argv]
    assert main(argv) == 2
    out, err = capsys.readouterr()
    _one_error_line(err, words, "--set")
    assert out == "" and list(tmp_path.iterdir()) == []


# --- input angles listed twice: refused naming the value by every command that takes them; a full turn is kept ----

FOURBAR = ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80"]
_SCENE = ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 20\nb = 66\nc = 56\nd = 80\n'
          "[input]\nangles = [{angles}]\n")


@pytest.mark.parametrize("argv, repeated", [
    ([*FOURBAR, "--angles", "10,10,20"], "10"),
    (["table", "jansen", "--angles", "0,45,0"], "0"),
    (["tolerance", *FOURBAR[1:], "--tolerance", "0.05", "--output", "rocker", "--angles", "5,6,5"], "5"),
    (["run", "{scene:10, 20, 10}"], "10"),
    (["run", "{scene:0.5, 0.5}"], "0.5"),
], ids=["fourbar", "table", "tolerance", "a scene file", "a scene file, twice in a row"])
def test_an_input_angle_listed_twice_is_refused_naming_it(argv, repeated, tmp_path, capsys):
    if argv[-1].startswith("{scene:"):
        (tmp_path / "scene.toml").write_text(_SCENE.format(angles=argv[-1][len("{scene:"):-1]))
        argv = [*argv[:-1], str(tmp_path / "scene.toml")]
    assert main(argv) == 2
    out, err = capsys.readouterr()
    _one_error_line(err, f"{repeated} ", "more than once")
    assert out == ""


@pytest.mark.parametrize("argv", [
    [*FOURBAR, "--angles", "0,360", "--format", "csv"],
    ["run", "{scene:0, 360}", "--format", "csv"],
], ids=["fourbar", "a scene file"])
def test_a_full_turn_from_0_to_360_is_two_rows(argv, tmp_path, capsys):
    """0 and 360 deg are one pose, but a turn that ends where it began is a common request: both rows, alike."""
    if "{scene:0, 360}" in argv:
        (tmp_path / "scene.toml").write_text(_SCENE.format(angles="0, 360"))
        argv = [word.replace("{scene:0, 360}", str(tmp_path / "scene.toml")) for word in argv]
    assert main(argv) == 0
    rows = [line.split(",") for line in capsys.readouterr().out.strip().splitlines()[1:]]
    first, last = rows[0], rows[-1] if len(rows) == 2 else rows[len(rows) // 2]
    assert len(rows) in (2, 4)  # one branch or both
    assert [float(v) for v in first[2:]] == pytest.approx([float(v) for v in last[2:]], abs=1e-9)


@pytest.mark.parametrize("outputs, repeated", [('["rocker", "rocker"]', "'rocker'"),
                                               ('["coupler", "rocker", "coupler"]', "'coupler'")])
def test_a_scene_that_asks_for_an_output_twice_is_refused_naming_it(outputs, repeated, tmp_path, capsys):
    """As `export --outputs rocker,rocker` is: the same column twice is a request that repeats itself."""
    (tmp_path / "scene.toml").write_text(_SCENE.format(angles="0, 90").replace('["rocker"]', outputs))
    for _ in range(2):  # cold, then with whatever the first run cached
        assert main(["run", str(tmp_path / "scene.toml")]) == 2
        out, err = capsys.readouterr()
        _one_error_line(err, repeated, "more than once")
        assert out == ""


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="needs /proc/self/fd to tell the files apart")
@pytest.mark.parametrize("argv", [
    ["parts", "fourbar", "--pin-diameter", "4", "--svg", "{out}/deeper/p.svg", "--assembly", "{out}/a.svg",
     "--json", "{out}/d.json"],
    ["export", "fourbar", "--to", "c", "--out", "{out}/deeper"],
], ids=["parts", "export"])
def test_a_full_disk_leaves_nothing_not_even_the_folders_made_for_the_files(argv, tmp_path, capsys, monkeypatch):
    out = tmp_path / "new"
    argv = [word.replace("{out}", str(out)) for word in argv]
    _full_after_first_write(monkeypatch, out)
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert "No space left on device" in err and "Traceback" not in err and ".tmp" not in err, err
    assert list(tmp_path.iterdir()) == []
