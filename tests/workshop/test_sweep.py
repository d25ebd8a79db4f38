"""Design-space sweeps: the same table on a LocalCluster, on the local scheduler and from a plain loop.

The plain loop is written here with symlink's public per-design functions
(the four-bar's closed-form crank range, Grashof class, transmission range and
limit positions, and a Solver call per design for the sampled values), and a
couple of designs are checked against hand formulas: Grashof's inequality
and the law of cosines for the transmission angle at crank angle 0.

Then the folder's integrity, table-driven: chunks damaged every way a disk,
a kill or a hand can damage them are refused by name when read and rebuilt
(one warning) when the sweep continues, their records checked against hashes
computed here; temporaries, the lock, interruptions, sweeps too large to end
(the advice checked against hand-computed cube roots); and, marked slow, a
process-pool sweep killed with SIGKILL whose workers must be gone in 5 s.
"""
from __future__ import annotations

import hashlib
import json
import logging
import math
import os
import shutil
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy
import pytest

import symlink.workshop.sweep as sweep_module
from symlink.analysis import grashof, limit_positions, transmission_range
from symlink.numeric.reachability import crank_range
from symlink.io.scene import catalog_linkage
from symlink.numeric.solver import Solver
from symlink.workshop.sweep import (MANIFEST, SweepSettings, columns, design_values, evaluate_designs, missing_modules,
                           read_sweep, run_sweep)
from symlink.io.sweep_folder import SweepWarning, open_folder
from interrupts import interruptible

pytestmark = pytest.mark.skipif(bool(missing_modules()), reason="the sweep extra is not installed")

ROOT = Path(__file__).resolve().parent.parent.parent
SAMPLES = 120
SMALL = SweepSettings("fourbar", {"a": (0.1, 0.6), "b": (0.4, 1.6), "c": (0.4, 1.6)}, values={"d": 1.0},
                      mode="random", count=48, seed=7, samples=SAMPLES, chunk=16, harmonics=2)


def plain_loop(settings: SweepSettings) -> dict[str, list]:
    """The table row by row, from public per-design functions (four-bar, branch +1)."""
    solver = Solver(catalog_linkage("fourbar"), ["rocker", "C_x", "C_y", "transmission"])
    inputs = 2 * math.pi * numpy.arange(settings.samples) / settings.samples
    swept = design_values(settings, range(settings.designs))
    rows: dict[str, list] = {name: [] for name in columns(settings)}
    for k in range(settings.designs):
        a, b, c = (float(swept[name][k]) for name in "abc")
        d = 1.0
        spans = crank_range(a, b, c, d)
        full = spans == [(-math.pi, math.pi)]
        solved = solver(theta=inputs, a=a, b=b, c=c, d=d, branch=1)
        mu = numpy.where(solved["assembled"], solved["transmission"], numpy.nan)
        if full:
            extremes = transmission_range(a, b, c, d)
            low, high = extremes.minimum, extremes.maximum
        else:
            low, high = numpy.nanmin(mu), numpy.nanmax(mu)
        kind = grashof(a, b, c, d).name
        stroke = ratio = math.nan
        if full and kind == "crank-rocker":
            limits = limit_positions(a, b, c, d, 1)
            stroke, ratio = limits.stroke, limits.time_ratio
        path = solved["C_x"] + 1j * solved["C_y"]
        row = {"design": k, "a": a, "b": b, "c": c, "d": d, "assembles": full,
               "reach": sum(hi - lo for lo, hi in spans) / (2 * math.pi), "spans": len(spans), "grashof": kind,
               "transmission_min": low, "transmission_max": high, "worst_transmission": min(low, math.pi - high),
               "stroke": stroke, "time_ratio": ratio}
        for harmonic, name in zip(range(-2, 3), ("m2", "m1", "0", "p1", "p2")):
            coefficient = numpy.mean(path * numpy.exp(-1j * harmonic * inputs)) if full else complex(math.nan,
                                                                                                  math.nan)
            row[f"path_{name}_re"], row[f"path_{name}_im"] = coefficient.real, coefficient.imag
        for name, value in row.items():
            rows[name].append(value)
    return rows


def assert_same_table(found, expected, tolerance: float = 1e-9) -> None:
    assert list(found) == list(expected)
    for name in expected:
        got, want = list(found[name]), list(expected[name])
        assert len(got) == len(want), name
        if name in ("grashof", "assembles", "spans", "design"):
            assert [type(w)(g) for g, w in zip(got, want)] == want, name
        else:
            numpy.testing.assert_allclose(numpy.array(got, dtype=float), numpy.array(want, dtype=float),
                                          rtol=tolerance, atol=tolerance, equal_nan=True, err_msg=name)


@pytest.fixture(scope="module")
def expected():
    return plain_loop(SMALL)


def as_columns(table) -> dict[str, list]:
    return {name: table.column(name).to_pylist() for name in table.column_names}


def test_the_plain_loop_agrees_with_hand_formulas(expected):
    """Two designs by hand: Grashof's inequality and the transmission angle at crank 0 by the law of cosines."""
    checked = 0
    for k in range(SMALL.designs):
        a, b, c, d = (expected[name][k] for name in "abcd")
        s, p, q, l = sorted([a, b, c, d])
        if s + l < p + q and s == a:
            assert expected["grashof"][k] == "crank-rocker"
            # at theta = 0, |BD| = d - a: the triangle B, C, D gives mu there, the smallest over the turn
            mu0 = math.acos((b * b + c * c - (d - a) ** 2) / (2 * b * c))
            assert math.isclose(expected["transmission_min"][k], mu0, rel_tol=1e-12)
            checked += 1
        if s + l > p + q:
            assert expected["grashof"][k] == "triple-rocker" and not expected["assembles"][k]
    assert checked >= 2


def test_local_scheduler_writes_the_plain_loops_table(tmp_path, expected):
    done = run_sweep(SMALL, tmp_path / "out", scheduler="threads", workers=2)
    assert (done["written"], done["skipped"], done["chunks"]) == (3, 0, 3)
    assert_same_table(as_columns(read_sweep(tmp_path / "out")), expected)


def test_a_distributed_client_writes_the_same_table(tmp_path, expected):
    """The distributed path (submit, a bounded window, results as they complete) on an in-process cluster."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None,
                                  silence_logs=logging.ERROR) as cluster, distributed.Client(cluster) as client:
        run_sweep(SMALL, tmp_path / "cluster", scheduler=client, window=2)
    assert_same_table(as_columns(read_sweep(tmp_path / "cluster")), expected)


@pytest.mark.slow  # starting two worker processes takes 15-30 s on a shared machine
def test_local_cluster_with_two_worker_processes_writes_the_same_table(tmp_path, expected):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=logging.ERROR) as cluster:
        run_sweep(SMALL, tmp_path / "cluster", scheduler=cluster.scheduler_address)
    run_sweep(SMALL, tmp_path / "local", scheduler="synchronous")
    on_cluster, local = read_sweep(tmp_path / "cluster"), read_sweep(tmp_path / "local")
    assert on_cluster.to_pandas().equals(local.to_pandas())  # bit for bit (NaN where NaN): chunks are made alike anywhere
    assert_same_table(as_columns(on_cluster), expected)


def test_a_failed_sweep_resumes_to_the_same_table(tmp_path, monkeypatch):
    """A chunk that fails stops the sweep after the chunks before it landed; run again, it ends alike."""
    import symlink.workshop.sweep as sweep
    evaluate = sweep.chunk_table

    def failing(settings, index):
        if index == 2:
            raise RuntimeError("injected failure")
        return evaluate(settings, index)

    monkeypatch.setattr(sweep, "chunk_table", failing)
    with pytest.raises(RuntimeError, match="injected"):
        run_sweep(SMALL, tmp_path / "failed", scheduler="synchronous", window=1)
    assert sorted(p.name for p in (tmp_path / "failed").glob("chunk-*")) == ["chunk-000000.parquet",
                                                                              "chunk-000001.parquet"]
    monkeypatch.setattr(sweep, "chunk_table", evaluate)
    done = run_sweep(SMALL, tmp_path / "failed", scheduler="synchronous")
    assert (done["written"], done["skipped"]) == (1, 2)
    run_sweep(SMALL, tmp_path / "whole", scheduler="synchronous")
    assert read_sweep(tmp_path / "failed").to_pandas().equals(read_sweep(tmp_path / "whole").to_pandas())


@pytest.mark.slow  # two runs of the command, each importing symlink and Dask: 20-30 s on a shared machine
def test_a_killed_sweep_resumes_to_the_same_table(tmp_path):
    """A sweep killed after its first chunks land, started again, ends with the table of one whole run."""
    folder = tmp_path / "killed"
    command = [sys.executable, "-m", "symlink", "sweep", "fourbar", str(folder), "--vary", "a=0.1:0.6,b=0.4:1.6",
               "--set", "c=1,d=1", "--grid", "40", "--chunk", "20", "--samples", "60", "--scheduler", "synchronous",
               "--no-progress"]
    process = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                               start_new_session=True)
    try:
        deadline = time.monotonic() + 120
        while len(list(folder.glob("chunk-*.parquet"))) < 3:
            assert process.poll() is None, process.stderr.read().decode()
            assert time.monotonic() < deadline, "no chunks written in two minutes"
            time.sleep(0.02)
        os.killpg(process.pid, signal.SIGKILL)
    finally:
        process.wait()
    landed = len(list(folder.glob("chunk-*.parquet")))
    assert 3 <= landed < 80, "the sweep was not interrupted midway"
    again = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    assert f"found {landed} already there" in again.stderr
    settings = SweepSettings("fourbar", {"a": (0.1, 0.6), "b": (0.4, 1.6)}, values={"c": 1.0, "d": 1.0}, count=40,
                             samples=60, chunk=20)
    run_sweep(settings, tmp_path / "whole", scheduler="synchronous")
    assert read_sweep(folder).to_pandas().equals(read_sweep(tmp_path / "whole").to_pandas())


def test_a_folder_of_other_settings_is_refused(tmp_path):
    settings = SweepSettings("fourbar", {"a": (0.2, 0.3)}, values={"d": 1.0}, count=2, samples=16)
    run_sweep(settings, tmp_path, scheduler="synchronous")
    other = SweepSettings("fourbar", {"a": (0.2, 0.3)}, values={"d": 1.0}, count=2, samples=32)
    with pytest.raises(ValueError, match="other settings .*samples"):
        run_sweep(other, tmp_path, scheduler="synchronous")
    assert run_sweep(settings, tmp_path, scheduler="synchronous")["skipped"] == 1
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "elsewhere" / "notes.txt").write_text("mine")
    with pytest.raises(ValueError, match="not empty"):
        run_sweep(settings, tmp_path / "elsewhere", scheduler="synchronous")


def test_designs_are_made_from_their_numbers_alone():
    """No design is materialised: the last of 10^12 designs is made on its own, and alike in any company."""
    huge = SweepSettings("fourbar", {"a": (1, 2), "b": (3, 4), "c": (5, 6)}, values={"d": 5.0}, count=10_000)
    assert huge.designs == 10**12
    assert {k: v.tolist() for k, v in design_values(huge, [10**12 - 1]).items()} == {"a": [2.0], "b": [4.0],
                                                                                         "c": [6.0]}
    alone = design_values(SMALL, [17])
    together = design_values(SMALL, range(SMALL.designs))
    assert all(alone[name][0] == together[name][17] for name in alone)
    assert evaluate_designs(huge, [10**12 - 1])["grashof"] == ["crank-rocker"]  # s + l = 2 + 6 < 4 + 5, s = a


@pytest.mark.parametrize("arguments, message", [
    (dict(ranges={}), "at least one parameter"),
    (dict(ranges={"e": (1, 2)}), "no parameter 'e'"),
    (dict(ranges={"a": (2, 1)}), "low < high"),
    (dict(ranges={"a": (2, 2)}), "zero length"),
    (dict(ranges={"a": (0, 1)}), "is a length"),
    (dict(ranges={"a": (1, math.nan)}), "finite"),
    (dict(mode="sobol"), "mode must be"),
    (dict(count=0), "count must be"),
    (dict(count=2.5), "count must be"),
    (dict(samples=4), "samples must be"),
    (dict(chunk=0), "chunk must be"),
    (dict(harmonics=-1), "harmonics must be"),
    (dict(harmonics=20, samples=16), "harmonics need"),
    (dict(branch=0), "branch must be"),
    (dict(seed=-1), "seed must be"),
    (dict(output="rocker_speed"), "no position output"),
    (dict(output="nowhere"), "no position output"),
    (dict(point="Q"), "no point 'Q'"),
    (dict(values={"q": 1.0}), "not 'q'"),
    (dict(values={"d": math.inf}), "finite"),
    (dict(count=1, ranges={"a": (1, 2)}), "count 2 or more"),
    (dict(linkage="nonesuch"), "no linkage 'nonesuch'"),
    (dict(mode="random", count=10**9, chunk=10**9, samples=100_000), r"at most [0-9,]+ designs \(--chunk\)"),
    (dict(count=10**7, ranges={"a": (1, 2), "b": (1, 2), "c": (1, 2)}), r"1e\+21 designs are too many .*--grid"),
])
def test_bad_settings_are_refused(arguments, message):
    given = dict(linkage="fourbar", ranges={"a": (1, 2)})
    given.update(arguments)
    with pytest.raises(ValueError, match=message):
        SweepSettings(**given)


def test_the_manifest_holds_the_settings_and_columns(tmp_path):
    settings = SweepSettings("fourbar", {"a": (0.2, 0.3)}, values={"d": 1.0}, count=2, samples=16, harmonics=1)
    run_sweep(settings, tmp_path, scheduler="synchronous")
    import json
    manifest = json.loads((tmp_path / MANIFEST).read_text())
    assert manifest["settings"]["samples"] == 16 and manifest["designs"] == 2
    assert manifest["columns"] == read_sweep(tmp_path).column_names
    assert manifest["columns"][-6:] == ["path_m1_re", "path_m1_im", "path_0_re", "path_0_im", "path_p1_re",
                                        "path_p1_im"]


def test_any_linkage_matches_its_per_design_analysis():
    """A slider-crank (no closed-form shortcut in the sweep) against symlink.analysis design by design.

    Without offset its stroke is 2 a (the crank's diameter), its time ratio 1, and its transmission
    angle (rod against the guide's normal) is smallest and largest at crank angles of +-90 deg.
    """
    from symlink.analysis import loop_transmissions, output_limits
    settings = SweepSettings("slider-crank", {"a": (0.5, 1.5), "b": (2.0, 3.0)}, values={"offset": 0.0}, count=2,
                             samples=72, harmonics=1)
    table = evaluate_designs(settings, range(settings.designs))
    linkage = catalog_linkage("slider-crank")
    for k in range(settings.designs):
        values = {"a": table["a"][k], "b": table["b"][k], "offset": 0.0, "branch": 1.0}
        limits = output_limits(linkage, values, "slider")
        (transmission,) = loop_transmissions(linkage, values)
        assert table["assembles"][k] and table["reach"][k] == 1.0 and table["grashof"][k] == ""
        assert table["stroke"][k] == pytest.approx(limits.stroke, abs=1e-9) == pytest.approx(2 * values["a"])
        assert table["time_ratio"][k] == pytest.approx(limits.time_ratio, abs=1e-9) == pytest.approx(1.0)
        assert table["transmission_min"][k] == pytest.approx(transmission.minimum, abs=1e-12)
        assert table["transmission_max"][k] == pytest.approx(transmission.maximum, abs=1e-12)
        mu = math.asin(values["a"] / values["b"])  # the rod's tilt at +-90 deg, from the right triangle
        assert table["worst_transmission"][k] == pytest.approx(math.pi / 2 - mu, abs=1e-12)


def test_a_linkage_that_does_not_turn_has_its_reach_from_the_bisected_scan():
    """A slider-crank whose rod cannot span the crank turns between +-30 deg and 150..210 deg: reach 1/3."""
    settings = SweepSettings("slider-crank", {"a": (2.0, 2.0)}, values={"b": 1.0, "offset": 0.0}, count=1,
                             samples=72, harmonics=1)
    table = evaluate_designs(settings, [0])
    assert not table["assembles"][0] and table["spans"][0] == 2
    assert table["reach"][0] == pytest.approx(1 / 3, abs=1e-12)  # two spans of 60 deg (asin(b / a) = 30 deg)
    assert math.isnan(table["stroke"][0]) and math.isnan(table["path_p1_re"][0])


def test_a_linkage_file_sweeps_as_its_catalog_entry(tmp_path, monkeypatch):
    """The file's text goes with the settings (workers anywhere read the same linkage), and the table is alike."""
    from symlink.io.linkage_file import write_linkage
    path = tmp_path / "four.toml"
    write_linkage(catalog_linkage("fourbar"), path, {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0})
    from_file = SweepSettings(str(path), {"a": (10.0, 30.0)}, count=3, samples=36)
    from_catalog = SweepSettings("fourbar", {"a": (10.0, 30.0)}, values={"b": 66.0, "c": 56.0, "d": 80.0}, count=3,
                                 samples=36)
    assert from_file.linkage_text == path.read_text()
    path.unlink()  # evaluated from the text, not the file
    found, expected = evaluate_designs(from_file, range(3)), evaluate_designs(from_catalog, range(3))
    assert found["grashof"] == expected["grashof"]
    for name in expected:  # the file's transmission angle is generated from its own text: alike to rounding
        if name != "grashof":
            # One solver may be compiled (built in the background) and the other not yet: they round alike to a
            # few units in the last place, which the polished stroke and time ratio (to about 1e-9 of the input)
            # can grow to 1e-11, and which leaves path coefficients that are zero at 1e-15 of the lengths (~60)
            polished = name in ("stroke", "time_ratio")
            numpy.testing.assert_allclose(numpy.asarray(found[name], dtype=float),
                                          numpy.asarray(expected[name], dtype=float), rtol=1e-9 if polished else 1e-13,
                                          atol=1e-12, err_msg=name)
    assert len(from_file.manifest()["linkage_sha256"]) == 64


# --- sweep folders that verify what they resume and what they read (issue 22, item 4) ---------------------------

#: Nine designs in three chunks of three: each chunk has the same size, so one can be copied over another.
TINY = SweepSettings("fourbar", {"a": (0.2, 0.4), "b": (0.9, 1.1)}, values={"c": 1.0, "d": 1.0}, count=3, samples=16,
                     chunk=3, harmonics=1)
#: Another sweep chunked alike (another rocker length): its chunks are foreign to TINY's folder.
OTHER = SweepSettings("fourbar", {"a": (0.2, 0.4), "b": (0.9, 1.1)}, values={"c": 1.2, "d": 1.0}, count=3,
                      samples=16, chunk=3, harmonics=1)
CHUNK = "chunk-000001.parquet"


def _manifest(folder: Path) -> dict:
    return json.loads((folder / MANIFEST).read_text())


def _truncate(folder, other, size):
    path = folder / CHUNK
    path.write_bytes(path.read_bytes()[:size])


def _flip_a_byte(folder, other):
    data = bytearray((folder / CHUNK).read_bytes())
    data[len(data) // 2] ^= 0x01
    (folder / CHUNK).write_bytes(bytes(data))


def _into_a_folder(folder, other):
    (folder / CHUNK).unlink()
    (folder / CHUNK).mkdir()
    (folder / CHUNK / "inside.parquet").write_bytes((folder / "chunk-000000.parquet").read_bytes())


def _into_a_link(folder, other):
    (folder / CHUNK).unlink()
    (folder / CHUNK).symlink_to(folder / "chunk-000000.parquet")


def _into_a_fifo(folder, other):
    (folder / CHUNK).unlink()
    os.mkfifo(folder / CHUNK)  # reading it would wait forever for a writer


def _unrecorded(folder, other):
    manifest = _manifest(folder)
    del manifest["done"][CHUNK]
    (folder / MANIFEST).write_text(json.dumps(manifest))


def _record_edited(folder, other):
    """The record made to match a copied file: its checksum matches, its design range does not."""
    manifest = _manifest(folder)
    manifest["done"][CHUNK] = manifest["done"]["chunk-000000.parquet"]
    (folder / MANIFEST).write_text(json.dumps(manifest))
    shutil.copyfile(folder / "chunk-000000.parquet", folder / CHUNK)


#: (what, damage(folder, other sweep's folder), chunks done again on resume).  Every damage is to chunk 1 of 3
#: but the extra chunks beyond the sweep's last, which are removed and never counted.
DAMAGES = [
    ("truncated", lambda folder, other: _truncate(folder, other, 100), 1),
    ("empty", lambda folder, other: _truncate(folder, other, 0), 1),
    ("a flipped byte", _flip_a_byte, 1),
    ("swapped with chunk 0", lambda folder, other: shutil.copyfile(folder / "chunk-000000.parquet", folder / CHUNK), 1),
    ("another sweep's chunk", lambda folder, other: shutil.copyfile(other / CHUNK, folder / CHUNK), 1),
    ("a folder", _into_a_folder, 1),
    ("a symbolic link", _into_a_link, 1),
    ("a FIFO", _into_a_fifo, 1),
    ("unrecorded", _unrecorded, 1),
    ("record edited to a copy", _record_edited, 1),
    ("an extra chunk beyond the last",
     lambda folder, other: shutil.copyfile(folder / "chunk-000000.parquet", folder / "chunk-000003.parquet"), 0),
    ("a chunk-like name", lambda folder, other: (folder / "chunk-x.parquet").write_bytes(b"PAR1"), 0),
]


@pytest.fixture(scope="module")
def tiny_folders(tmp_path_factory):
    """TINY's whole folder and OTHER's, written once: each test copies them."""
    root = tmp_path_factory.mktemp("tiny")
    run_sweep(TINY, root / "whole", scheduler="synchronous")
    run_sweep(OTHER, root / "other", scheduler="synchronous")
    return root / "whole", root / "other"


def _copy(tiny_folders, tmp_path) -> Path:
    folder = tmp_path / "sweep"
    shutil.copytree(tiny_folders[0], folder, symlinks=True)
    return folder


def _damaged_name(folder: Path, what: str) -> str:
    return {"an extra chunk beyond the last": "chunk-000003.parquet", "a chunk-like name": "chunk-x.parquet"}.get(
        what, CHUNK)


@pytest.mark.parametrize("what, damage, again", DAMAGES, ids=[case[0] for case in DAMAGES])
def test_a_bad_chunk_is_refused_by_name_when_read(tiny_folders, tmp_path, what, damage, again):
    folder = _copy(tiny_folders, tmp_path)
    damage(folder, tiny_folders[1])
    with pytest.raises(ValueError, match=_damaged_name(folder, what).replace(".", r"\.") + ".*run the sweep again"):
        read_sweep(folder)


@pytest.mark.parametrize("what, damage, again", DAMAGES, ids=[case[0] for case in DAMAGES])
def test_a_bad_chunk_is_rebuilt_on_resume_with_one_warning(tiny_folders, tmp_path, what, damage, again):
    """Continued, the folder warns once naming the chunk, does it again (never counted as done), and reads as the
    whole run: every design once, the same values bit for bit."""
    folder = _copy(tiny_folders, tmp_path)
    damage(folder, tiny_folders[1])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        done = run_sweep(TINY, folder, scheduler="synchronous")
    found = [str(w.message) for w in caught if issubclass(w.category, SweepWarning)]
    assert len(found) == 1 and _damaged_name(folder, what) in found[0] and "\n" not in found[0], found
    assert (done["written"], done["skipped"]) == (again, 3 - again)
    table = read_sweep(folder)
    assert table.column("design").to_pylist() == list(range(TINY.designs))
    assert table.to_pandas().equals(read_sweep(tiny_folders[0]).to_pandas())
    assert sorted(p.name for p in folder.iterdir()) == [*(f"chunk-00000{k}.parquet" for k in range(3)), MANIFEST]


def test_the_manifest_records_each_chunks_rows_designs_and_checksum(tiny_folders):
    """The records against the files themselves: hashed here, and read with pyarrow."""
    import pyarrow.parquet
    folder = tiny_folders[0]
    manifest = _manifest(folder)
    assert sorted(manifest["done"]) == [f"chunk-00000{k}.parquet" for k in range(3)]
    for k in range(3):
        name = f"chunk-00000{k}.parquet"
        record, data = manifest["done"][name], (folder / name).read_bytes()
        assert record["sha256"] == hashlib.sha256(data).hexdigest() and record["bytes"] == len(data)
        designs = pyarrow.parquet.read_table(folder / name).column("design").to_pylist()
        assert record["rows"] == len(designs) == 3 and record["designs"] == [designs[0], designs[-1]] == [3 * k,
                                                                                                            3 * k + 2]


def test_a_recorded_chunk_that_is_missing_is_done_again_without_a_word(tiny_folders, tmp_path):
    """What a kill between the manifest's write and the chunk's rename leaves: a partial table, then the whole."""
    folder = _copy(tiny_folders, tmp_path)
    (folder / CHUNK).unlink()
    assert read_sweep(folder).column("design").to_pylist() == [0, 1, 2, 6, 7, 8]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        done = run_sweep(TINY, folder, scheduler="synchronous")
    assert (done["written"], done["skipped"]) == (1, 2)
    assert read_sweep(folder).to_pandas().equals(read_sweep(tiny_folders[0]).to_pandas())


@pytest.mark.parametrize("manifest_too", [False, True], ids=["beside a manifest", "before the first manifest"])
def test_temporaries_of_killed_writes_are_removed_by_the_next_run(tiny_folders, tmp_path, manifest_too):
    """Fresh temporaries (a kill a second ago) go too: the folder is locked, so no other sweep writes them."""
    folder = _copy(tiny_folders, tmp_path)
    if manifest_too:
        shutil.rmtree(folder)
        folder.mkdir()
    (folder / CHUNK).unlink(missing_ok=True)
    leftovers = [f".{CHUNK}.0123456789ab.tmp", f".{MANIFEST}.a1b2c3d4e5f6.tmp"]
    for name in leftovers:
        (folder / name).write_bytes(b"half a write")
    if not manifest_too:
        (folder / ".mine.tmp").write_text("not the sweep's")  # a name the sweep never writes: left alone
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        run_sweep(TINY, folder, scheduler="synchronous")
    names = sorted(p.name for p in folder.iterdir())
    assert not set(leftovers) & set(names)
    assert (".mine.tmp" in names) != manifest_too
    assert read_sweep(folder).to_pandas().equals(read_sweep(tiny_folders[0]).to_pandas())


def test_a_folder_being_written_is_locked(tiny_folders, tmp_path):
    folder = _copy(tiny_folders, tmp_path)
    header = {"symlink": sweep_module.__version__, "settings": TINY.manifest(), "columns": columns(TINY)}
    with open_folder(folder, header, TINY.designs, TINY.chunk):
        with pytest.raises(ValueError, match="another sweep is writing into"):
            run_sweep(TINY, folder, scheduler="synchronous")
    assert run_sweep(TINY, folder, scheduler="synchronous")["skipped"] == 3


def test_an_interrupted_sweep_keeps_its_finished_chunks_and_leaves_no_temporaries(tmp_path, monkeypatch):
    """Ctrl-C (a KeyboardInterrupt) while chunk 2 is evaluated: chunks 0 and 1 are recorded and in place."""
    evaluate = sweep_module.chunk_table

    def interrupted(settings, index):
        if index == 2:
            raise KeyboardInterrupt
        return evaluate(settings, index)

    monkeypatch.setattr(sweep_module, "chunk_table", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(TINY, tmp_path / "cut", scheduler="synchronous", window=1)
    assert sorted(p.name for p in (tmp_path / "cut").iterdir()) == ["chunk-000000.parquet", "chunk-000001.parquet",
                                                                     MANIFEST]
    assert sorted(_manifest(tmp_path / "cut")["done"]) == ["chunk-000000.parquet", "chunk-000001.parquet"]
    monkeypatch.setattr(sweep_module, "chunk_table", evaluate)
    assert run_sweep(TINY, tmp_path / "cut", scheduler="synchronous")["written"] == 1


def test_a_manifest_of_an_older_layout_is_refused(tiny_folders, tmp_path):
    folder = _copy(tiny_folders, tmp_path)
    manifest = _manifest(folder)
    del manifest["format"], manifest["done"]
    (folder / MANIFEST).write_text(json.dumps(manifest))
    for action in (lambda: read_sweep(folder), lambda: run_sweep(TINY, folder, scheduler="synchronous")):
        with pytest.raises(ValueError, match="not a sweep's manifest .*older symlink"):
            action()


# --- sweeps too large to end are refused before anything is written -------------------------------------------

class _Disk:
    def __init__(self, free):
        self.free, self.total, self.used = free, free + 10**12, 10**12


@pytest.mark.parametrize("free, count, ranges, mode, words", [
    # 1e9 bytes free at 16 bytes a design: 62,500,000 designs; 396**3 = 62,099,136 <= that < 397**3 = 62,570,773
    (10**9, 1000, 3, "grid", ["1e+09 designs", "16 GB of disk", "1 GB free", "62,500,000 designs",
                              "a grid of at most 396 values a parameter (--grid)"]),
    (10**9, 10**8, 1, "random", ["1e+08 designs", "1.6 GB", "a random sample of at most 62,500,000 (--random)"]),
    # disk enough for anything: a year at 20,000 designs/s on one worker is 630,720,000,000 designs
    (10**30, 10**15, 1, "random", ["1e+15 designs", "1.59e+03 years on 1 worker", "630,720,000,000 designs"]),
    # 8575**3 = 630,525,109,375 <= 630,720,000,000 < 8576**3 = 630,745,726,976
    (10**30, 10**5, 3, "grid", ["1e+15 designs", "a grid of at most 8,575 values"]),
    # a full disk: no design fits
    (0, 3, 1, "grid", ["3 designs", "48 bytes of disk", "0 bytes free", "free some space on that disk"]),
])
def test_a_sweep_that_cannot_end_is_refused_with_its_estimate(tmp_path, monkeypatch, free, count, ranges, mode,
                                                              words):
    monkeypatch.setattr(shutil, "disk_usage", lambda path: _Disk(free))
    settings = SweepSettings("fourbar", dict(list({"a": (1, 2), "b": (3, 4), "c": (5, 6)}.items())[:ranges]),
                             values={"b": 3.5, "c": 5.5, "d": 5.0}, mode=mode, count=count)
    with pytest.raises(ValueError) as refused:
        run_sweep(settings, tmp_path / "never", scheduler="synchronous")
    message = str(refused.value)
    assert "\n" not in message and all(word in message for word in words), message
    assert not (tmp_path / "never").exists()


# --- a killed process-pool sweep leaves no workers behind -------------------------------------------------------

def children(pid: int) -> list[int]:
    """The processes whose parent is ``pid`` (from /proc)."""
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            if int(stat.rpartition(")")[2].split()[1]) == pid:
                found.append(int(entry.name))
    return found


def alive(pid: int) -> bool:
    """Running (a zombie waiting for its reaper counts as gone)."""
    try:
        return (Path("/proc") / str(pid) / "stat").read_text().rpartition(")")[2].split()[0] != "Z"
    except OSError:
        return False


def wait_until_gone(pids: list[int], seconds: float) -> list[int]:
    """The ``pids`` still alive after up to ``seconds``."""
    deadline = time.monotonic() + seconds
    while any(alive(pid) for pid in pids) and time.monotonic() < deadline:
        time.sleep(0.05)
    return [pid for pid in pids if alive(pid)]


#: A process-pool sweep of 14,400 designs in 144 chunks: seconds of work after its two workers start.
POOL_SWEEP = ["fourbar", "--vary", "a=0.1:0.6,b=0.4:1.6", "--set", "c=1,d=1", "--grid", "120", "--chunk", "100",
              "--samples", "120", "--scheduler", "processes", "--workers", "2", "--no-progress"]


def start_pool_sweep(folder: Path, wait_for_chunks: int) -> tuple[subprocess.Popen, list[int]]:
    """The sweep started in a session of its own, and its child processes once ``wait_for_chunks`` chunks landed
    (0: once its two workers and the resource tracker run)."""
    command = [sys.executable, "-m", "symlink", "sweep", POOL_SWEEP[0], str(folder), *POOL_SWEEP[1:]]
    process = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                               start_new_session=True, preexec_fn=interruptible)  # Ctrl-C as a terminal's
    deadline = time.monotonic() + 180
    while len(children(process.pid)) < 3 or len(list(folder.glob("chunk-*.parquet"))) < wait_for_chunks:
        assert process.poll() is None, process.stderr.read().decode()
        assert time.monotonic() < deadline, "the sweep did not start in three minutes"
        time.sleep(0.02)
    return process, children(process.pid)


@pytest.mark.slow  # a process pool's workers import symlink: 10-20 s on a shared machine
@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads processes from /proc")
def test_a_killed_process_pool_sweep_takes_its_workers_with_it(tmp_path):
    """kill -9 of the sweep alone (not its group): its workers end within seconds, not minutes, silently; the
    folder continues to the whole table."""
    folder = tmp_path / "killed"
    process, workers = start_pool_sweep(folder, wait_for_chunks=1)
    try:
        os.kill(process.pid, signal.SIGKILL)
        process.wait(timeout=60)
        left = wait_until_gone(workers, 5.0)
    finally:
        for pid in workers:
            if alive(pid):
                os.kill(pid, signal.SIGKILL)
    assert left == [], "workers outlived the sweep by 5 s"
    err = process.stderr.read().decode()  # the workers held it open too
    assert "Traceback" not in err and "leaked" not in err, err
    again = subprocess.run([sys.executable, "-m", "symlink", "sweep", POOL_SWEEP[0], str(folder),
                            *[word if word != "processes" else "synchronous" for word in POOL_SWEEP[1:]]],
                           cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    assert "warning" not in again.stderr, again.stderr
    assert read_sweep(folder).column("design").to_pylist() == list(range(120 * 120))


# --- a damaged manifest: rebuilt with one warning, or refused in one line naming the folder and what to do --------

def _edited(change):
    def damage(folder: Path) -> None:
        manifest = _manifest(folder)
        change(manifest)
        (folder / MANIFEST).write_text(json.dumps(manifest))
    return damage


def _text(text: bytes):
    def damage(folder: Path) -> None:
        (folder / MANIFEST).write_bytes(text)
    return damage


MANIFEST_DAMAGES = [
    # (what, damage): the folder cannot be continued as recorded; its chunks cannot be verified any more
    ("truncated", lambda folder: (folder / MANIFEST).write_text((folder / MANIFEST).read_text()[:150])),
    ("empty", _text(b"")),
    ("not UTF-8", _text(b"\xff\xfe{}")),
    ("a JSON list", _text(b"[]")),
    ("nested too deeply", _text(b"[" * 100_000 + b"]" * 100_000)),
    ("no settings", _edited(lambda m: m.pop("settings"))),
    ("no columns", _edited(lambda m: m.pop("columns"))),
    ("designs as text", _edited(lambda m: m.__setitem__("designs", "9"))),
    ("a layout as text", _edited(lambda m: m.__setitem__("format", "2"))),
    ("a setting of another type", _edited(lambda m: m["settings"].__setitem__("count", "three"))),
    ("a table setting missing", _edited(lambda m: m["settings"].__setitem__("ranges", None))),
    ("NaN samples", lambda folder: (folder / MANIFEST).write_text(
        (folder / MANIFEST).read_text().replace('"samples": 16', '"samples": NaN'))),
    ("no manifest", lambda folder: (folder / MANIFEST).unlink()),
    ("a key given twice", lambda folder: (folder / MANIFEST).write_text(  # JSON keeps the last without a word
        (folder / MANIFEST).read_text().replace('"samples": 16', '"samples": 16, "samples": 17'))),
    ("a number of 400 digits", lambda folder: (folder / MANIFEST).write_text(
        (folder / MANIFEST).read_text().replace('"samples": 16', '"samples": 1' + "0" * 400))),
]


#: Damages of the settings alone: the chunks still read (their records are whole), only a resume cannot trust them.
SETTINGS_ONLY = ("a setting of another type", "a table setting missing", "NaN samples")


@pytest.mark.parametrize("what, damage", MANIFEST_DAMAGES, ids=[what for what, _ in MANIFEST_DAMAGES])
def test_a_damaged_manifest_is_refused_when_read_and_rebuilt_on_resume(tiny_folders, tmp_path, what, damage):
    folder = _copy(tiny_folders, tmp_path)
    damage(folder)
    if what not in SETTINGS_ONLY:
        with pytest.raises(ValueError, match="run the sweep again|holds no sweep"):
            read_sweep(folder)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        done = run_sweep(TINY, folder, scheduler="synchronous")
    found = [str(w.message) for w in caught if issubclass(w.category, SweepWarning)]
    assert len(found) == 1 and f"{folder}: {MANIFEST} was damaged" in found[0] and "3 chunks found" in found[0], found
    assert (done["written"], done["skipped"]) == (3, 0)
    assert read_sweep(folder).to_pandas().equals(read_sweep(tiny_folders[0]).to_pandas())


@pytest.mark.parametrize("damage, words", [
    (_edited(lambda m: m.__setitem__("symlink", "0.0.1")), "holds a sweep of symlink '0.0.1'"),
    (_edited(lambda m: m.__setitem__("format", 7)), "of another layout, 7"),
], ids=["another version's", "another layout's"])
def test_a_manifest_of_another_symlink_is_refused_saying_what_to_do(tiny_folders, tmp_path, damage, words):
    folder = _copy(tiny_folders, tmp_path)
    damage(folder)
    with pytest.raises(ValueError, match=words) as refused:
        run_sweep(TINY, folder, scheduler="synchronous")
    message = str(refused.value)
    assert "\n" not in message and f"remove {folder / MANIFEST}" in message and "choose another folder" in message
    (folder / MANIFEST).unlink()  # as the message says: then the sweep is done again there, with one warning
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert run_sweep(TINY, folder, scheduler="synchronous")["written"] == 3
    assert sum(issubclass(w.category, SweepWarning) for w in caught) == 1


def test_a_damaged_manifest_beside_other_files_is_refused_and_they_are_left_alone(tiny_folders, tmp_path):
    folder = _copy(tiny_folders, tmp_path)
    (folder / MANIFEST).write_text("{")
    (folder / "notes.txt").write_text("mine")
    with pytest.raises(ValueError, match=r"is damaged .* holds other files \('notes.txt'\): move them"):
        run_sweep(TINY, folder, scheduler="synchronous")
    assert (folder / "notes.txt").read_text() == "mine" and (folder / CHUNK).exists()


#: A chunk evaluated in a new process: its Parquet bytes' SHA-256, and whether SymPy was imported.
_CHUNK_IN_A_PROCESS = r"""
import hashlib, json, sys
from symlink.workshop.sweep import SweepSettings, chunk_table
source, ranges, values = sys.argv[1], json.loads(sys.argv[2]), json.loads(sys.argv[3])
settings = SweepSettings(source, {k: tuple(v) for k, v in ranges.items()}, values=values, count=4, samples=60, chunk=4)
data = chunk_table(settings, 0)
print(json.dumps({"sha256": hashlib.sha256(data).hexdigest(), "sympy": "sympy" in sys.modules}))
"""


@pytest.mark.parametrize("source, ranges, values", [
    ("watt2", {"a": [0.5, 3.0]}, {}),  # a design that reaches part of the turn: its span from the roots' margins
    (str(ROOT / "linkages" / "slider-crank.toml"), {"a": [0.5, 2.5]}, {}),  # a file; transmission at its guide
    ("fourbar", {"a": [10.0, 60.0]}, {"b": 66.0, "c": 56.0, "d": 80.0}),  # Grashof classes, the closed-form reach
])
def test_a_warm_chunk_is_evaluated_without_sympy_and_is_the_cold_ones(tmp_path, source, ranges, values):
    """A worker whose linkage's facts, solver and margins are in the disk cache (a warm sweep, or any chunk after
    the first) builds no linkage: its chunk is the cold one's, byte for byte, and SymPy is never imported."""
    env = dict(os.environ, SYMLINK_CACHE=str(tmp_path / "cache"), PYTHONPATH=str(ROOT))
    runs = [json.loads(subprocess.run([sys.executable, "-c", _CHUNK_IN_A_PROCESS, source, json.dumps(ranges),
                                       json.dumps(values)], capture_output=True, text=True, env=env, check=True,
                                      timeout=600).stdout) for _ in range(2)]
    assert runs[0]["sympy"], "the check cannot fail: the cold chunk derives, with SymPy"
    assert not runs[1]["sympy"]
    assert runs[1]["sha256"] == runs[0]["sha256"]


def test_a_warm_chunk_of_a_file_whose_guide_is_turned_by_a_fixed_angle_imports_no_sympy(tmp_path):
    """A joint whose direction is turned by a fixed angle (a value a design) is plain data too (its recipe's terms):
    the warm chunk builds no linkage and is the cold one's, byte for byte."""
    text = (ROOT / "symlink" / "linkages" / "slider-crank.toml").read_text()
    for old, new in (('name = "slider-crank"', 'name = "tilted"'),
                     ('constants = ["offset"]', 'constants = ["offset", "delta"]'),
                     ('AS = ["s", 0]', 'AS = ["s", "delta"]'),
                     ('SC = ["offset", "pi/2"]', 'SC = ["offset", "delta + pi/2"]'),
                     ("offset = 0.7", 'offset = 0.7\ndelta = "20 deg"')):
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / "tilted.toml"
    path.write_text(text)
    env = dict(os.environ, SYMLINK_CACHE=str(tmp_path / "cache"), PYTHONPATH=str(ROOT))
    ranges = json.dumps({"delta": [0.0, 0.5]})
    runs = [json.loads(subprocess.run([sys.executable, "-c", _CHUNK_IN_A_PROCESS, str(path), ranges, "{}"],
                                      capture_output=True, text=True, env=env, check=True, cwd=tmp_path,
                                      timeout=600).stdout) for _ in range(2)]
    assert runs[0]["sympy"] and not runs[1]["sympy"]
    assert runs[1]["sha256"] == runs[0]["sha256"]


def test_a_partial_design_of_a_warm_sweep_reaches_what_the_hand_formula_says(tmp_path, monkeypatch):
    """The reach of a slider-crank that cannot turn, evaluated twice (cold, then from the cache's margins): the
    rod spans the guide where |offset - a sin(theta)| <= b, so with a = 2, b = 1, offset 0.5 the crank turns
    between asin((0.5 - 1) / 2) and asin((0.5 + 1) / 2) and the mirror span: reach 2 (asin(0.75) + asin(0.25)) / 2 pi."""
    from symlink.numeric import cache
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "cache"))
    cache.clear_memory()
    expected = 2 * (math.asin(0.75) + math.asin(0.25)) / (2 * math.pi)
    for _ in range(2):
        sweep_module._margins.cache_clear()
        settings = SweepSettings("slider-crank", {"a": (2.0, 2.0)}, values={"b": 1.0, "offset": 0.5}, count=1,
                                 samples=72, harmonics=1)
        table = evaluate_designs(settings, [0])
        assert table["spans"][0] == 2 and table["reach"][0] == pytest.approx(expected, abs=1e-12)
    cache.clear_memory()


# --- one home: a linkage file hashed once, one entry of the margins for the sweep and the analysis ----------------

def test_a_linkage_file_is_read_and_hashed_once_by_its_text(tmp_path, monkeypatch):
    """A sweep keys a file by its text (what its workers have: line ends read as \\n), read once: the SHA-256 of the
    bytes with CRLF made LF, by hashlib, for a file written with CRLF line ends."""
    path = tmp_path / "crlf.toml"
    data = (ROOT / "symlink" / "linkages" / "slider-crank.toml").read_bytes().replace(b"\n", b"\r\n")
    path.write_bytes(data)
    reads = []
    read_bytes, read_text = Path.read_bytes, Path.read_text
    monkeypatch.setattr(Path, "read_bytes", lambda self: reads.append("bytes") or read_bytes(self))
    monkeypatch.setattr(Path, "read_text", lambda self, *a, **k: reads.append("text") or read_text(self, *a, **k))
    expected = hashlib.sha256(data.replace(b"\r\n", b"\n")).hexdigest()
    assert sweep_module._request(str(path), None) == {"file_sha256": expected}
    assert reads == ["text"]
    assert sweep_module._request(str(path), data.decode().replace("\r\n", "\n")) == {"file_sha256": expected}


def test_the_sweep_and_the_analysis_share_one_entry_of_the_margins(tmp_path, monkeypatch):
    """The margins of a linkage's roots are derived once for a sweep and ``symlink analyze`` alike (one key, one
    builder), and they are the slider-crank's root argument by hand, b^2 - (a sin(theta) - offset)^2 (the rod spans
    the guide's distance from B), over a scale that does not change with the input, plus the rounding allowed."""
    from symlink.cli.analyze import AnalysisSource
    from symlink.numeric import cache, reachability
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "cache"))
    cache.clear_memory()
    sweep_module._margins.cache_clear()
    built = []
    margins_text = reachability.margins_text
    monkeypatch.setattr(reachability, "margins_text", lambda linkage: built.append(linkage.name) or
                        margins_text(linkage))
    try:
        assert sweep_module._margins("slider-crank", None) is not None
        margins = AnalysisSource("slider-crank")._margins()
        assert built == ["slider-crank"]
        a, b, offset, theta = 2.0, 1.0, 0.5, numpy.linspace(-0.3, 0.9, 7)  # closes from -14.5 to 48.6 deg
        found = margins(a=a, b=b, offset=offset, theta=theta, branch=1)["margin_0"] - reachability.TOLERANCE
        argument = b * b - (a * numpy.sin(theta) - offset) ** 2
        assert numpy.array_equal(numpy.sign(found), [-1, 1, 1, 1, 1, 1, -1])
        numpy.testing.assert_allclose(found / argument, found[3] / argument[3], rtol=1e-12)
    finally:
        sweep_module._margins.cache_clear()
        cache.clear_memory()
