"""``symlink sweep``: a small run into a folder, its continuation, and bad command lines (one line, exit 2)."""
from __future__ import annotations

import json
import os
import signal
from pathlib import Path

import pytest

import symlink.workshop.sweep as sweep_module
from symlink.cli import main
from symlink.workshop.sweep import MANIFEST, missing_modules, read_sweep

pytestmark = pytest.mark.skipif(bool(missing_modules()), reason="the sweep extra is not installed")

SMALL = ["fourbar", "--vary", "a=0.2:0.4,b=0.9:1.1", "--set", "c=1,d=1", "--grid", "3", "--samples", "36",
         "--chunk", "4", "--scheduler", "synchronous", "--no-progress"]


def test_a_sweep_writes_its_chunks_and_continues(tmp_path, capsys):
    folder = str(tmp_path / "out")
    assert main(["sweep", SMALL[0], folder, *SMALL[1:]]) == 0
    out, err = capsys.readouterr()
    assert out == folder + "\n"
    assert "9 designs in 3 chunks: wrote 3, found 0 already there" in err
    table = read_sweep(folder)
    assert table.num_rows == 9 and table.column("design").to_pylist() == list(range(9))
    assert sorted(set(table.column("a").to_pylist())) == pytest.approx([0.2, 0.3, 0.4])
    assert set(table.column("grashof").to_pylist()) == {"crank-rocker"}  # s = a, s + l < p + q
    manifest = json.loads((tmp_path / "out" / MANIFEST).read_text())
    assert manifest["settings"]["fixed"] == {"c": 1.0, "d": 1.0}
    assert main(["sweep", SMALL[0], folder, *SMALL[1:]]) == 0
    assert "wrote 0, found 3 already there" in capsys.readouterr().err


def test_angles_in_degrees_are_stored_in_radians(tmp_path, capsys):
    folder = tmp_path / "jansen"
    assert main(["sweep", "jansen", str(folder), "--vary", "alpha=85:87", "--grid", "2", "--samples", "24",
                 "--scheduler", "synchronous", "--no-progress"]) == 0
    capsys.readouterr()
    alpha = read_sweep(folder).column("alpha").to_pylist()
    assert alpha == pytest.approx([1.4835298641951802, 1.5184364492350666])  # 85 and 87 degrees


def test_without_the_extra_it_says_how_to_install_it(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(sweep_module, "missing_modules", lambda: ["dask", "pyarrow"])
    assert main(["sweep", SMALL[0], str(tmp_path / "x"), *SMALL[1:]]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "pip install 'symlink-kinematics[sweep]'" in err
    assert not (tmp_path / "x").exists()


@pytest.mark.parametrize("what, change, message", [
    ("no --vary", lambda a: a[:1] + a[3:], "required: --vary"),
    ("range without colon", lambda a: a[:2] + ["a=0.2"] + a[3:], "NAME=LOW:HIGH"),
    ("range not numbers", lambda a: a[:2] + ["a=x:1"] + a[3:], "not a number"),
    ("unknown parameter", lambda a: a[:2] + ["e=1:2"] + a[3:], "no parameter 'e'"),
    ("reversed range", lambda a: a[:2] + ["a=2:1"] + a[3:], "low < high"),
    ("negative length", lambda a: a[:2] + ["a=-1:1"] + a[3:], "is a length"),
    ("unknown --set", lambda a: a[:4] + ["q=1"] + a[5:], "no value 'q'"),
    ("grid and random", lambda a: a + ["--random", "5"], "not allowed with"),
    ("zero grid", lambda a: a[:6] + ["0"] + a[7:], "count must be"),
    ("few samples", lambda a: a[:8] + ["3"] + a[9:], "samples must be"),
    ("zero chunk", lambda a: a[:10] + ["0"] + a[11:], "chunk must be"),
    ("bad scheduler", lambda a: a[:12] + ["everywhere"] + a[13:], "--scheduler must be"),
    ("zero workers", lambda a: a + ["--workers", "0"], "--workers must be"),
    ("unknown output", lambda a: a + ["--output", "nowhere"], "no position output"),
    ("unknown point", lambda a: a + ["--point", "Q"], "no point 'Q'"),
    ("not a linkage", lambda a: ["nonesuch"] + a[1:], "no linkage 'nonesuch'"),
    ("negative seed", lambda a: a + ["--seed", "-1"], "seed must be"),
])
def test_bad_command_lines_are_one_line_and_exit_2(tmp_path, capsys, what, change, message):
    arguments = change(list(SMALL))
    folder = tmp_path / "never"
    assert main(["sweep", arguments[0], str(folder), *arguments[1:]]) == 2, what
    err = capsys.readouterr().err
    assert err.startswith("symlink: error:") and err.count("\n") == 1, err
    assert message in err, err
    assert not folder.exists()


def test_a_folder_of_another_sweep_is_refused(tmp_path, capsys):
    folder = str(tmp_path / "out")
    assert main(["sweep", SMALL[0], folder, *SMALL[1:]]) == 0
    other = [("40" if before == "--samples" else word) for before, word in zip(["", *SMALL], SMALL)]
    assert main(["sweep", other[0], folder, *other[1:]]) == 2
    assert "other settings (samples differ)" in capsys.readouterr().err


def test_a_bad_chunk_is_one_warning_line_and_rebuilt(tmp_path, capsys):
    folder = tmp_path / "out"
    assert main(["sweep", SMALL[0], str(folder), *SMALL[1:]]) == 0
    capsys.readouterr()
    (folder / "chunk-000001.parquet").write_bytes((folder / "chunk-000000.parquet").read_bytes())  # swapped
    assert main(["sweep", SMALL[0], str(folder), *SMALL[1:]]) == 0
    err = capsys.readouterr().err.splitlines()
    warnings = [line for line in err if line.startswith("symlink: warning:")]
    assert len(warnings) == 1 and "chunk-000001.parquet (" in warnings[0] and "did not match" in warnings[0], err
    assert "wrote 1, found 2 already there" in err[-1]
    assert read_sweep(folder).column("design").to_pylist() == list(range(9))


def test_a_sweep_that_cannot_end_is_one_line_and_exit_2(tmp_path, capsys):
    folder = tmp_path / "never"
    assert main(["sweep", "fourbar", str(folder), "--vary", "a=1:2,b=3:4,c=5:6", "--set", "d=5",
                 "--grid", "100000", "--scheduler", "synchronous", "--no-progress"]) == 2
    err = capsys.readouterr().err
    # The command's estimate of its work refuses it first (the years it would take); run_sweep's own check of
    # the disk it would need is tested in tests/test_sweep.py.
    assert err.startswith("symlink: error: a sweep of 1e+15 designs") and err.count("\n") == 1, err
    assert "years" in err and "--grid" in err
    assert not folder.exists()


def test_an_interrupted_sweep_is_one_line_and_exit_130_and_continues(tmp_path, capsys, monkeypatch):
    """Ctrl-C as the command sees it (a KeyboardInterrupt while the second chunk is evaluated, in whatever order
    Dask takes them), then the same command: the chunk finished before is kept."""
    folder = tmp_path / "out"
    evaluate = sweep_module.chunk_table
    finished = []

    def interrupted(settings, index):
        if finished:
            raise KeyboardInterrupt
        finished.append(index)
        return evaluate(settings, index)

    monkeypatch.setattr(sweep_module, "chunk_table", interrupted)
    assert main(["sweep", SMALL[0], str(folder), *SMALL[1:]]) == 130
    assert capsys.readouterr().err == "symlink: interrupted\n"
    monkeypatch.setattr(sweep_module, "chunk_table", evaluate)
    assert main(["sweep", SMALL[0], str(folder), *SMALL[1:]]) == 0
    assert "wrote 2, found 1 already there" in capsys.readouterr().err  # three chunks, one finished before
    assert read_sweep(folder).column("design").to_pylist() == list(range(9))


# --- Ctrl-C: one line, exit 130 (the command line's "interrupted"), no worker traceback ---------------------------

@pytest.mark.slow  # a process pool's workers import symlink: 10-20 s a case on a shared machine
@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads processes from /proc")
@pytest.mark.parametrize("chunks_first", [0, 2], ids=["as its workers start", "while chunks land"])
def test_ctrl_c_on_a_process_pool_sweep_is_one_line_and_exit_130(tmp_path, chunks_first):
    """SIGINT to the sweep's process group, as a terminal's Ctrl-C sends it to the sweep and its workers alike."""
    from test_sweep import alive, start_pool_sweep, wait_until_gone
    folder = tmp_path / "cut"
    process, workers = start_pool_sweep(folder, wait_for_chunks=chunks_first)
    try:
        os.killpg(process.pid, signal.SIGINT)
        process.wait(timeout=120)
        left = wait_until_gone(workers, 5.0)
    finally:
        for pid in workers:
            if alive(pid):
                os.kill(pid, signal.SIGKILL)
    assert left == [], "workers outlived the sweep by 5 s"
    assert (process.returncode, process.stderr.read().decode()) == (130, "symlink: interrupted\n")
    assert not [path.name for path in folder.iterdir() if path.name.endswith(".tmp")]
    assert len(read_sweep(folder).column("design")) % 100 == 0  # the chunks kept verify; whole chunks only
