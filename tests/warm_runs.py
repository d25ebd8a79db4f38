"""A command run twice in new processes with one disk cache, the second with ``python -X importtime``: what a warm
command line prints and imports (the tests of warm commands share it)."""
from __future__ import annotations

import os
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Sequence

PROJECT = Path(__file__).resolve().parent.parent


def imported_packages(stderr: str) -> set[str]:
    """The top-level packages that ``python -X importtime`` reports imported."""
    return {line.rsplit("|", 1)[1].strip().split(".")[0] for line in stderr.splitlines()
            if line.startswith("import time:") and "|" in line}


def without_import_times(stderr: str) -> str:
    """``stderr`` without the lines of ``-X importtime``: what the command itself wrote."""
    return "".join(line for line in stderr.splitlines(keepends=True) if not line.startswith("import time:"))


@dataclass
class TwoRuns:
    """The first (cold) and second (warm) run of one command line: their output, notes and the warm imports."""

    cold: str
    warm: str
    cold_notes: str
    warm_notes: str
    imported: set[str]
    #: The bytes of the files asked for (``files`` of :func:`run_twice`) after the cold run, and after the warm one.
    cold_files: dict[str, bytes] = field(default_factory=dict)
    warm_files: dict[str, bytes] = field(default_factory=dict)


def run_twice(folder: Path, arguments: list[str], cache: Path | None = None, files: Sequence[str] = ()) -> TwoRuns:
    """``symlink ARGUMENTS`` in ``folder`` twice, each in a new process with the disk cache ``cache`` (default: a
    fresh one in ``folder``), the second with ``-X importtime``; both must succeed.  ``files``: what the command
    writes (names in ``folder``), read after each run and removed (the warm run writes them anew)."""
    env = {**os.environ, "PYTHONPATH": str(PROJECT), "MPLBACKEND": "Agg",
           "SYMLINK_CACHE": str(cache if cache is not None else folder / "cache")}
    runs = []
    written: list[dict[str, bytes]] = []
    for flags in ([], ["-X", "importtime"]):
        run = subprocess.run([sys.executable, *flags, "-m", "symlink", *arguments], capture_output=True, text=True,
                             env=env, cwd=str(folder), timeout=600)
        assert run.returncode == 0, run.stderr[-2000:]
        runs.append(run)
        written.append({name: (folder / name).read_bytes() for name in files})
        for name in files:
            (folder / name).unlink()
    return TwoRuns(runs[0].stdout, runs[1].stdout, runs[0].stderr, without_import_times(runs[1].stderr),
                   imported_packages(runs[1].stderr), *written)
