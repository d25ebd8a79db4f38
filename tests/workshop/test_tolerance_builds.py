"""The Monte Carlo check in a folder (symlink.workshop.sampled_builds.sample_builds(..., folder=)): resumable, verified, seeded.

The expected values come from outside the code under test: the same builds made in memory
(the NumPy route, which shares only the per-chunk seeding rule with the folder route), an
uninterrupted run beside an interrupted and resumed one, the first-order bands of
stack_up (checked against 50-digit differences in test_tolerance.py), and the sampling
error of a percentile of a normal sample.
"""
from __future__ import annotations

import json
import math

import numpy
import pytest

from symlink.mechanism.catalog import fourbar
from symlink.workshop.tolerance import Tolerance, stack_up
from symlink.workshop.sampled_builds import sample_builds



@pytest.fixture
def sweep_extra():
    """The builds in a folder need the optional extra 'sweep' (the NumPy route, in memory, needs neither)."""
    pytest.importorskip("dask", reason="the resumable Monte Carlo runs on Dask: the optional extra 'sweep'")
    pytest.importorskip("pyarrow", reason="the resumable Monte Carlo writes Parquet chunks: the optional extra 'sweep'")

DESIGN = {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0, "branch": 1}
LENGTHS = ("a", "b", "c", "d")
THETA = numpy.radians([40.0, 250.0])


def _sample(folder=None, **options):
    arguments = {"builds": 5000, "seed": 11, "chunk": 1000, **options}
    return sample_builds(fourbar(), "rocker", DESIGN, dict.fromkeys(LENGTHS, 0.3), inputs={"theta": THETA},
                         folder=folder, **arguments)


def test_a_resumed_run_gives_the_sample_of_an_uninterrupted_one(tmp_path, monkeypatch, sweep_extra):
    """The fourth chunk of five is interrupted (Ctrl-C): the three chunks done are kept; the run again makes
    only the two missing and gives the sample of an uninterrupted run, which is the in-memory sample."""
    from symlink.workshop import sampled_builds
    from symlink.io.sweep_folder import read_manifest
    whole = _sample(tmp_path / "whole", scheduler="threads", workers=2)
    in_memory = _sample()
    assert numpy.array_equal(whole.deviation, in_memory.deviation)
    assert whole.reused == 0 and numpy.isfinite(whole.deviation).all()

    table = sampled_builds._BuildModel.table
    made: list[int] = []

    def interrupted(self, index):
        if len(made) == 3:
            raise KeyboardInterrupt
        made.append(index)
        return table(self, index)

    monkeypatch.setattr(sampled_builds._BuildModel, "table", interrupted)
    with pytest.raises(KeyboardInterrupt):
        _sample(tmp_path / "stopped", scheduler="synchronous")
    assert len(made) == 3
    assert sorted(read_manifest(tmp_path / "stopped")[1]) == sorted(f"chunk-00000{k}.parquet" for k in made)
    first = set(made)
    made.clear()
    monkeypatch.setattr(sampled_builds._BuildModel, "table", lambda self, index: made.append(index) or table(self, index))
    resumed = _sample(tmp_path / "stopped", scheduler="synchronous")
    assert sorted(made) == sorted(set(range(5)) - first) and resumed.reused == 3
    assert numpy.array_equal(resumed.deviation, whole.deviation)
    again = _sample(tmp_path / "stopped")
    assert again.reused == 5 and len(made) == 2  # nothing made a third time
    assert numpy.array_equal(again.deviation, whole.deviation)


def test_a_damaged_chunk_is_made_again_and_other_settings_are_refused(tmp_path, sweep_extra):
    from symlink.io.sweep_folder import SweepWarning
    folder = tmp_path / "builds"
    first = _sample(folder)
    (folder / "chunk-000002.parquet").write_bytes(b"not a chunk")
    with pytest.warns(SweepWarning, match="chunk-000002"):
        mended = _sample(folder)
    assert mended.reused == 4 and numpy.array_equal(mended.deviation, first.deviation)
    with pytest.raises(ValueError, match="other settings.*seed"):
        _sample(folder, seed=12)
    with pytest.raises(ValueError, match="other settings"):
        _sample(folder, builds=6000)
    settings = json.loads((folder / "manifest.json").read_text())["settings"]
    assert settings["kind"] == "tolerance builds" and settings["sigmas"] == {name: pytest.approx(0.1, rel=1e-15) for name in LENGTHS}


def test_the_chunks_hold_the_drawn_dimensions_and_their_deviations(tmp_path, sweep_extra):
    """Each chunk's table: the build's number, the dimensions drawn (mean and spread of a normal sample) and the
    rocker's deviation, which the solver gives again from the drawn dimensions."""
    import pyarrow.parquet
    from symlink.numeric.solver import Solver
    _sample(tmp_path / "b")
    table = pyarrow.parquet.read_table(tmp_path / "b" / "chunk-000001.parquet").to_pydict()
    assert table["build"] == list(range(1000, 2000))
    drawn = {name: numpy.array(table[name]) for name in LENGTHS}
    for name in LENGTHS:  # sigma 0.1: the mean within 4 standard errors, the spread within 4 of its own
        assert abs(drawn[name].mean() - DESIGN[name]) < 4 * 0.1 / math.sqrt(1000)
        assert abs(drawn[name].std() / 0.1 - 1) < 4 / math.sqrt(2 * 1000)
    solver = Solver(fourbar(), ["rocker"], backend="numpy")
    built = solver(theta=THETA[1], **{k: v for k, v in drawn.items()}, branch=1)["rocker"]
    nominal = solver(theta=THETA[1], **DESIGN)["rocker"]
    numpy.testing.assert_allclose(table["rocker[1]"], built - nominal, rtol=1e-9, atol=1e-14)


@pytest.mark.parametrize("band, agrees", [(0.05, True), (12.0, False)])
def test_10_to_the_5_builds_on_dask_beside_the_linear_prediction(tmp_path, band, agrees, sweep_extra):
    """10^5 builds in a folder.  Small tolerances (0.05 on 20 to 80): the sampled 3-sigma percentiles are the
    linear RSS band within their sampling error (a 0.135 % percentile of 10^5: about 2 %), the spread within 4
    standard errors.  Large ones (a band of 12 on a crank of 20): the tails depart from the symmetric linear
    band by more than 8 %, and the mean from the nominal by more than the first-order mean shift's error."""
    count = 100_000
    tolerances = dict.fromkeys(LENGTHS, band)
    sampled = sample_builds(fourbar(), "rocker", DESIGN, tolerances, inputs={"theta": THETA}, builds=count,
                            seed=5, folder=tmp_path / "mc", scheduler="threads")
    linear = stack_up(fourbar(), "rocker", DESIGN, tolerances, inputs={"theta": THETA})
    low, high = sampled.percentile([0.135, 99.865])[:, 0]
    tails = numpy.abs(numpy.array([-low, high]) / linear.rss[0] - 1)
    if agrees:
        assert sampled.built.min() == 1.0
        numpy.testing.assert_allclose(sampled.standard_deviation[0], linear.standard_deviation[0],
                                      rtol=4 / math.sqrt(2 * count))
        assert tails.max() < 0.04
    else:
        assert tails.max() > 0.08


def test_without_dask_the_folder_is_refused_and_memory_still_works(monkeypatch, tmp_path):
    import symlink.workshop.sweep
    monkeypatch.setattr(symlink.workshop.sweep, "missing_modules", lambda names=(): ["dask"])
    with pytest.raises(ImportError, match=r"symlink-kinematics\[sweep\]"):
        _sample(tmp_path / "x")
    assert not (tmp_path / "x").exists()
    assert _sample(builds=10).deviation.shape == (1, 10, 2)


@pytest.mark.parametrize("options, message", [
    ({"chunk": 0}, "chunk must be a whole number"),
    ({"seed": -1}, "seed must be a whole number"),
    ({"scheduler": "processes"}, "scheduler must be one of"),
])
def test_bad_options_are_value_errors_naming_them(options, message):
    with pytest.raises(ValueError, match=message):
        _sample(**options)


def test_a_sigma_given_is_the_spread_drawn():
    sampled = sample_builds(fourbar(), "B_x", DESIGN, {"a": Tolerance(sigma=0.2)}, inputs={"theta": [0.0]},
                            builds=20_000, seed=2)
    # B_x = a cos(theta) = a at theta = 0: the deviation is the drawn a less 20, sigma 0.2
    assert abs(sampled.standard_deviation[0, 0] / 0.2 - 1) < 4 / math.sqrt(2 * 20_000)


# --- the command line --------------------------------------------------------------------------

COMMAND = ["tolerance", "fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
           "--tolerance", "0.05", "--angles", "40,250", "--format", "csv"]


def test_command_samples_into_a_folder_and_continues_it(tmp_path, capsys, sweep_extra):
    """--samples N --folder DIR: the sampled columns are the 3-sigma points of the linear band (0.05 on every
    length: small), the same again when the command is run again on the folder, which finds every chunk done."""
    from symlink.cli import main
    options = COMMAND + ["--samples", "100000", "--folder", str(tmp_path / "mc"), "--seed", "3"]
    assert main(options) == 0
    first = capsys.readouterr()
    assert "0 chunks found done" in first.err
    header, *rows = first.out.splitlines()
    assert header.endswith(",sampled_low,sampled_high")
    for row in rows:
        cells = [float(c) for c in row.split(",")[:5]] + [float(c) for c in row.split(",")[6:]]
        rss, low, high = cells[3], cells[5], cells[6]
        assert -low == pytest.approx(rss, rel=0.04) and high == pytest.approx(rss, rel=0.04)
    assert main(options) == 0
    again = capsys.readouterr()
    assert again.out == first.out and "10 chunks found done" in again.err


@pytest.mark.parametrize("extra, message", [
    (["--folder", "DIR"], "--folder holds sampled builds: give their number with --samples N"),
    (["--samples", "0"], "--samples must be at least 1"),
    (["--samples", "10", "--seed", "-1"], "--seed must be 0 or more"),
])
def test_command_bad_sampling_options_are_one_line_and_status_2(extra, message, tmp_path, capsys):
    from symlink.cli import main
    extra = [str(tmp_path / "f") if item == "DIR" else item for item in extra]
    assert main(COMMAND + extra) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1


def test_command_refuses_a_folder_of_other_builds(tmp_path, capsys, sweep_extra):
    from symlink.cli import main
    folder = str(tmp_path / "mc")
    assert main(COMMAND + ["--samples", "100", "--folder", folder]) == 0
    capsys.readouterr()
    assert main(COMMAND + ["--samples", "100", "--folder", folder, "--seed", "1"]) == 2
    err = capsys.readouterr().err
    assert "other settings (seed differ)" in err and len(err.strip().splitlines()) == 1
