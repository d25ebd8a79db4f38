"""Every input file a command reads (linkage, scene, csv targets) goes through one reader: a FIFO, a device, a
folder or a huge file is refused at once with one line and exit 2, never read without bound or waited on."""
from __future__ import annotations

import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import pytest

from symlink.cli import main

ROOT = Path(__file__).resolve().parents[2]
GOOD_LINKAGE = (ROOT / "linkages" / "fourbar.toml").read_text()


def symlink_process(*argv: str, limit_memory: int | None = None, stdin=None, timeout: float = 120):
    """``python -m symlink argv`` from the source tree; with ``limit_memory`` its address space is capped."""
    def cap() -> None:
        if limit_memory is not None:
            resource.setrlimit(resource.RLIMIT_AS, (limit_memory, limit_memory))
    environment = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MPLBACKEND": "Agg"}
    return subprocess.run([sys.executable, "-m", "symlink", *argv], cwd=ROOT, env=environment, capture_output=True,
                          text=True, preexec_fn=cap, stdin=stdin, timeout=timeout)


# (command line with {} for the file, what the file is called in the message)
READERS = [
    (["plan", "{}"], "linkage file"),
    (["table", "{}", "--angles", "0"], "linkage file"),
    (["run", "{}"], "scene file"),
    (["synthesize", "path", "{}"], "csv of targets"),
    (["synthesize", "function", "{}"], "csv of targets"),
]


def _with(argv, path):
    return [str(path) if word == "{}" else word for word in argv]


def _one_error_line(err: str, *words: str) -> None:
    assert err.count("\n") == 1 and err.startswith("symlink: error: ") and "Traceback" not in err, err
    for word in words:
        assert word in err, err


@pytest.mark.parametrize("argv, what", READERS, ids=[" ".join(a[:2]) for a, _ in READERS])
def test_a_fifo_is_refused_at_once(argv, what, tmp_path, capsys):
    path = tmp_path / ("pipe.csv" if "synthesize" in argv else "pipe.toml")
    os.mkfifo(path)
    assert main(_with(argv, path)) == 2
    _one_error_line(capsys.readouterr().err, f"cannot read {what} {path}: it is a FIFO")


@pytest.mark.parametrize("argv, what", READERS, ids=[" ".join(a[:2]) for a, _ in READERS])
def test_a_folder_is_refused(argv, what, tmp_path, capsys):
    path = tmp_path / ("folder.csv" if "synthesize" in argv else "folder.toml")
    path.mkdir()
    assert main(_with(argv, path)) == 2
    _one_error_line(capsys.readouterr().err, f"cannot read {what} {path}: it is a folder")


@pytest.mark.parametrize("argv, what", READERS, ids=[" ".join(a[:2]) for a, _ in READERS])
def test_a_huge_file_is_refused_unread(argv, what, tmp_path, capsys):
    path = tmp_path / ("huge.csv" if "synthesize" in argv else "huge.toml")
    with open(path, "wb") as file:
        file.truncate(1 << 30)  # 1 GiB, sparse: reading it whole would take the memory the limit protects
    assert main(_with(argv, path)) == 2
    _one_error_line(capsys.readouterr().err, f"{what} {path} is larger than")


@pytest.mark.parametrize("argv, what", READERS, ids=[" ".join(a[:2]) for a, _ in READERS])
def test_missing_file_names_the_path_and_the_reason(argv, what, tmp_path, capsys):
    path = tmp_path / ("none.csv" if "synthesize" in argv else "none.toml")
    assert main(_with(argv, path)) == 2
    _one_error_line(capsys.readouterr().err, f"cannot read {what} {path}: No such file or directory")


@pytest.mark.parametrize("argv, what", [(["plan", "/dev/zero"], "linkage file"), (["run", "/dev/zero"], "scene file"),
                                        (["synthesize", "path", "/dev/zero"], "csv of targets")])
def test_dev_zero_is_refused_under_a_memory_limit(argv, what):
    """In a process of at most 2 GiB of address space: reading /dev/zero to its end would fail with MemoryError."""
    done = symlink_process(*argv, limit_memory=2 << 30)
    assert done.returncode == 2 and done.stdout == ""
    _one_error_line(done.stderr, f"cannot read {what} /dev/zero: it is a character device")


@pytest.mark.parametrize("argv", [["run", "-"], ["synthesize", "path", "-"]])
def test_dev_zero_on_stdin_is_refused_under_a_memory_limit(argv):
    with open("/dev/zero", "rb") as zeros:
        done = symlink_process(*argv, limit_memory=2 << 30, stdin=zeros)
    assert done.returncode == 2
    _one_error_line(done.stderr, "on standard input is larger than")


@pytest.mark.parametrize("body", ["1 deg + " * 125_000 + "1 deg", " " * 1_000_000 + "1", "1" * 1_000_000,
                                  "theta + " * 125_000 + "0"])
def test_a_1mb_expression_is_answered_within_a_time_limit(body, tmp_path):
    """The tokenizer is linear and expressions are capped: a 1 MB expression is refused in well under a second.

    The quadratic tokenizer of before took over 30 s at 1 MB; the limit is loose for a shared machine.
    """
    path = tmp_path / "long.toml"
    path.write_text(GOOD_LINKAGE.replace('AD = ["d", 0]', f'AD = ["d", "{body}"]'))
    started = time.monotonic()
    done = symlink_process("plan", str(path), timeout=30)
    elapsed = time.monotonic() - started
    assert done.returncode == 2, done.stderr
    _one_error_line(done.stderr, f"{path}:", "vectors.AD")
    assert len(done.stderr) < 400  # the 1 MB text is cut to an excerpt
    assert elapsed < 30


def test_a_long_but_allowed_expression_is_read_exactly(tmp_path, capsys):
    """10,000 terms of 1 deg, under the cap: read (linearly) as exactly 10,001 deg."""
    body = "1 deg + " * 10_000 + "1 deg"
    path = tmp_path / "long.toml"
    path.write_text(GOOD_LINKAGE + f'theta = "{body}"\n')
    from symlink.io.linkage_file import read_linkage
    found = read_linkage(path)
    assert found.defaults["theta"] == pytest.approx(10_001 * 3.141592653589793 / 180, rel=1e-15)
