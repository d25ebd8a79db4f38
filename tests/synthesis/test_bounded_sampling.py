"""Every search and sampling is bounded: an absurd size (1e9, 1e12) is refused at once, before anything is
allocated or traced, in one line with the estimate and the largest request that would do; from the Python API
(``ValueError``) and from the command line (one error line, exit status 2).

The expected numbers are worked out here from the documented costs (seconds a design, bytes a value, the pools of
designs sampled for starts), not read back from the messages.
"""
from __future__ import annotations

import math
import re

import numpy
import pytest

from symlink.cli import main
from symlink.common.limits import WORK_SECONDS, format_duration
from symlink.mechanism.catalog import fourbar, with_point
from symlink.io.linkage_file import write_linkage

ABSURD = (10**9, 10**12)
TURN = numpy.linspace(0.0, 2 * math.pi, 24, endpoint=False)
CIRCLE = numpy.stack([3 + 2 * numpy.cos(TURN), 1 + 2 * numpy.sin(TURN)], axis=1)
FOURBAR = {"a": 1.0, "b": 3.0, "c": 2.5, "d": 3.2}


def one_line(error: BaseException) -> str:
    message = str(error)
    assert "\n" not in message
    return message


# --- the Python API -------------------------------------------------------------------------------

def shape_search(size):
    from symlink.synthesis.shape import shape_search
    return shape_search(fourbar(), "B", CIRCLE, {"b": (2.5, 3.5)}, values={"a": 1.0, "c": 2.5, "d": 3.2},
                        designs=size)


def synthesize_shape_designs(size):
    from symlink.synthesis.shape import synthesize_shape
    return synthesize_shape(fourbar(), "B", CIRCLE, {"b": (2.5, 3.5)}, values={"a": 1.0, "c": 2.5, "d": 3.2},
                            designs=size)


def synthesize_shape_refine(size):
    from symlink.synthesis.shape import synthesize_shape
    return synthesize_shape(fourbar(), "B", CIRCLE, {"b": (2.5, 3.5)}, values={"a": 1.0, "c": 2.5, "d": 3.2},
                            designs=50, refine=size)


def general_path(size):
    from symlink.synthesis.general import synthesize_path
    return synthesize_path(fourbar(), "B", CIRCLE[:6], {"b": (2.5, 3.5)}, values={"a": 1.0, "c": 2.5, "d": 3.2},
                           starts=size)


def general_function(size):
    from symlink.synthesis.general_function import synthesize_function
    inputs = numpy.radians([10.0, 40.0, 70.0, 100.0])
    return synthesize_function(fourbar(), "rocker", inputs, inputs / 2 + 1.0, {"b": (2.5, 3.5), "c": (2, 3)},
                               values={"a": 1.0, "d": 3.2}, starts=size)


def general_motion(size):
    from symlink.synthesis.general_motion import synthesize_motion
    poses = numpy.array([[1.0, 1.0, 0.1], [1.5, 1.2, 0.2], [2.0, 1.1, 0.3]])
    return synthesize_motion(fourbar(), "B", "coupler", poses, {"b": (2.5, 3.5)},
                             values={"a": 1.0, "c": 2.5, "d": 3.2}, starts=size)


def fourbar_path(size):
    from symlink.synthesis.path import synthesize_path
    return synthesize_path(CIRCLE[:6], starts=size)


def monte_carlo(size):
    from symlink.workshop.sampled_builds import sample_builds
    return sample_builds(fourbar(), "rocker", {"a": 20, "b": 66, "c": 56, "d": 80}, {"b": 0.3},
                         inputs={"theta": [0.0, 0.5]}, builds=size)


def atlas_turn(size):
    from symlink.mechanism.atlas import ATLAS, example_coordinates, turns_fully
    entry = ATLAS["watt-ii"]
    links, pins = entry.description()
    return turns_fully(links, example_coordinates(entry), pins[0], steps=size)


def sweep(size, tmp_path):
    from symlink.workshop.sweep import SweepSettings, run_sweep
    settings = SweepSettings("fourbar", {"a": (1.0, 2.0)}, mode="random", count=size)
    return run_sweep(settings, tmp_path / "sweep", scheduler="synchronous")


def seconds(size, each):
    return format_duration(size * each)


def expect_shape(size):
    from symlink.synthesis.shape import SECONDS_PER_DESIGN
    return (f"a shape search of {size:,} designs would take about {seconds(size, SECONDS_PER_DESIGN)} (at most "
            f"24 hours a call); use designs {int(WORK_SECONDS / SECONDS_PER_DESIGN):,} or fewer")


def expect_starts(pool, evaluations, name="starts", what="designs sampled for the starts"):
    return lambda size: (f"{name}={size:,} is more than the {pool:,} {what} (at most {pool:,} refinements of up to "
                         f"{evaluations:,} evaluations each); give {name}={pool:,} or fewer")


def expect_builds(size):
    values = size * 2  # two input values, one output
    return (f"{size:,} builds x 2 input values x 1 output are {values:,} values (about "
            f"{'32 GB' if size == 10**9 else '32 TB'} of memory), more than the 50,000,000 sample_builds keeps; "
            "ask for at most 25,000,000 builds")


def expect_turn(size):
    from symlink.mechanism.atlas import SECONDS_PER_STEP
    return (f"following a turn in {size:,} steps would take about {seconds(size, SECONDS_PER_STEP)} (at most "
            f"24 hours a call); use steps {int(WORK_SECONDS / SECONDS_PER_STEP):,} or fewer")


API = {
    "shape_search designs": (shape_search, expect_shape),
    "synthesize_shape designs": (synthesize_shape_designs, expect_shape),
    # 50 designs sampled: no more matches to refine
    "synthesize_shape refine": (synthesize_shape_refine,
                                expect_starts(50, 2000, "refine", "designs sampled for the shape match")),
    # 1,500 sampled designs and the user's own
    "general path starts": (general_path, expect_starts(1501, 2000)),
    # 1,000 sampled designs, the user's own and Freudenstein's
    "general function starts": (general_function, expect_starts(1002, 400)),
    "general motion starts": (general_motion, expect_starts(1001, 1000)),
    # 1,500 atlas four-bars at 24 offsets each
    "four-bar path starts": (fourbar_path, expect_starts(36_000, 300, what="atlas four-bars a call fits")),
    "Monte Carlo builds": (monte_carlo, expect_builds),
    "atlas turn steps": (atlas_turn, expect_turn),
}


@pytest.mark.parametrize("size", ABSURD, ids=["1e9", "1e12"])
@pytest.mark.parametrize("name", API)
def test_the_python_api_refuses_absurd_sizes_in_one_line(name, size):
    call, expected = API[name]
    with pytest.raises(ValueError) as refused:
        call(size)
    assert one_line(refused.value) == expected(size)


def test_a_sweep_of_1e12_designs_is_refused_before_a_chunk_is_written(tmp_path):
    pytest.importorskip("dask")
    pytest.importorskip("pyarrow")
    with pytest.raises(ValueError) as refused:
        sweep(10**12, tmp_path)
    message = one_line(refused.value)
    assert re.match(r"a sweep of 1e\+12 designs needs at least [0-9.]+ TB of disk|a sweep of 1e\+12 designs "
                    r"(of 360 samples )?would take", message), message
    assert not (tmp_path / "sweep").exists() or not any((tmp_path / "sweep").glob("chunk-*"))


def test_the_largest_shape_search_named_is_accepted():
    """The bound is the estimate: the suggested size passes the check (the search itself is not run)."""
    from symlink.common.limits import require_time
    from symlink.synthesis.shape import SECONDS_PER_DESIGN
    fits = int(WORK_SECONDS / SECONDS_PER_DESIGN)
    require_time(fits, SECONDS_PER_DESIGN, "x", "designs")
    with pytest.raises(ValueError):
        require_time(fits + 1, SECONDS_PER_DESIGN, "x", "designs")


def test_a_shape_search_in_chunks_keeps_its_memory_and_its_answer(monkeypatch):
    """Designs traced a few at a time (the chunk made tiny) give the designs traced all at once."""
    from symlink.synthesis import shape
    whole = shape.shape_search(fourbar(), "B", CIRCLE, {"b": (2.5, 3.5), "c": (2.0, 3.0)},
                               values={"a": 1.0, "d": 3.2}, designs=60, keep=3)
    monkeypatch.setattr(shape, "CHUNK_BYTES", 7 * shape.bytes_per_design(2))  # chunks of 7 designs
    assert shape.design_chunk(2, available=10**12) == 7
    chunked = shape.shape_search(fourbar(), "B", CIRCLE, {"b": (2.5, 3.5), "c": (2.0, 3.0)},
                                 values={"a": 1.0, "d": 3.2}, designs=60, keep=3)
    for one, other in zip(whole, chunked):
        assert one.design == pytest.approx(other.design, rel=1e-12)
        assert one.branches == other.branches
        assert one.distance == pytest.approx(other.distance, rel=1e-9, abs=1e-15)


def test_a_chunk_shrinks_to_a_quarter_of_the_memory_available():
    from symlink.synthesis.shape import CHUNK_BYTES, bytes_per_design, design_chunk
    per = bytes_per_design(3)
    assert per == 360 * 8 * (2 * 5 + 8)  # 360 input values, 18 numbers of 8 bytes each
    assert design_chunk(3, available=10**12) == CHUNK_BYTES // per
    assert design_chunk(3, available=40 * per) == 10
    assert design_chunk(3, available=1) == 1


# --- the command line -----------------------------------------------------------------------------

@pytest.fixture
def files(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    base = fourbar()
    write_linkage(with_point(base, "B", base.roles["coupler"]), tmp_path / "fp.toml",
                  {**FOURBAR, "u": 1.0, "v": 0.0})
    (tmp_path / "shape.csv").write_text("x,y\n" + "".join(f"{float(x)!r},{float(y)!r}\n" for x, y in CIRCLE))
    (tmp_path / "points.csv").write_text("x,y\n" + "".join(f"{float(x)!r},{float(y)!r}\n" for x, y in CIRCLE[:6]))
    (tmp_path / "function.csv").write_text("theta,rocker\n10,20\n40,35\n70,50\n100,65\n")
    (tmp_path / "poses.csv").write_text("x,y,angle\n1,1,5\n1.5,1.2,10\n2,1.1,15\n")
    return tmp_path


CLI = {
    "shape --samples": (["synthesize", "path", "fp.toml", "shape.csv", "--shape", "--free", "b", "--point", "P",
                         "--samples", "{n}"],
                        r"a shape match of --samples {n:,} would take about .+ \(at most 60 min a command, "
                        r"--time-budget\); use --samples 360,000 or fewer"),
    "four-bar path --starts": (["synthesize", "path", "points.csv", "--starts", "{n}"],
                               r"a path synthesis of 6 points from {n:,} starts could take about .+ \(at most 60 min "
                               r"a command, --time-budget\); use --starts 6,000 or fewer"),
    "general path --starts": (["synthesize", "path", "fp.toml", "points.csv", "--free", "b", "--point", "P",
                               "--starts", "{n}"],
                              r"a path synthesis of 6 points from {n:,} starts could take about .+; use --starts "
                              r"6,000 or fewer"),
    "general function --starts": (["synthesize", "function", "fourbar", "function.csv", "--free", "b,c",
                                   "--set", "a=1,d=3.2", "--starts", "{n}"],
                                  r"a function synthesis of 4 points from {n:,} starts could take about .+; use "
                                  r"--starts 9,000 or fewer"),
    "general motion --starts": (["synthesize", "motion", "fourbar", "poses.csv", "--free", "b", "--set",
                                 "a=1,c=2.5,d=3.2", "--angle", "coupler", "--starts", "{n}"],
                                r"a motion synthesis of 3 points from {n:,} starts could take about .+; use --starts "
                                r"12,000 or fewer"),
    "tolerance --samples": (["tolerance", "fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56",
                             "--ground", "80", "--tolerance", "0.1", "--angles", "0,30", "--samples", "{n}"],
                            r"{n:,} builds x 2 input values x 1 output are .+ values \(about .+ of memory\), more "
                            r"than the 50,000,000 sample_builds keeps; ask for at most 25,000,000 builds"),
    "table --step": (["table", "fourbar", "--step", "{tiny}"],
                     r"about 1e\+(09|12) input values is too many \(at most 10,000,000 a sweep\); use --step 3.6e-05 "
                     r"or larger"),
}


@pytest.mark.parametrize("size", ABSURD, ids=["1e9", "1e12"])
@pytest.mark.parametrize("name", CLI)
def test_the_command_line_refuses_absurd_sizes_in_one_line_with_status_2(name, size, files, capsys):
    arguments, pattern = CLI[name]
    arguments = [a.format(n=size, tiny=360 / size) for a in arguments]
    assert main(arguments) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("symlink: error: "), captured.err
    assert re.fullmatch(pattern.format(n=size), lines[0][len("symlink: error: "):]), lines[0]
    assert sorted(p.name for p in files.iterdir()) == ["fp.toml", "function.csv", "points.csv", "poses.csv",
                                                       "shape.csv"]


@pytest.mark.parametrize("option", ["--random", "--grid"])
def test_the_command_line_refuses_a_sweep_of_1e12_designs(option, tmp_path, capsys):
    pytest.importorskip("dask")
    size = 10**12 if option == "--random" else 10**6  # two parameters on a grid of 1e6: 1e12 designs
    assert main(["sweep", "fourbar", str(tmp_path / "sweep"), "--vary", "a=1:2,b=3:4", option, str(size),
                 "--scheduler", "synchronous"]) == 2
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("symlink: error: a sweep of 1e+12 designs of 360 samples would "
                                                   "take about "), lines
    assert not (tmp_path / "sweep").exists()
