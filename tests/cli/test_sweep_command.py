"""``symlink sweep``: a small run into a folder, its continuation, and bad command lines (one line, exit 2)."""
from __future__ import annotations

import json

import pytest

import symlink.sweep as sweep_module
from symlink.cli import main
from symlink.sweep import MANIFEST, missing_modules, read_sweep

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
    ("reversed range", lambda a: a[:2] + ["a=2:1"] + a[3:], "low <= high"),
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
