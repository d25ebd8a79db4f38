"""Large tables stream: peak memory and time to the first row of a 10-million-row csv.

Runs ``symlink fourbar`` in a child process with its stdout read through a
pipe, and reports the time until the first data row arrived, the total time,
the rows counted and the child's peak resident memory (``ru_maxrss``).  The
bound to hold: peak RSS below 300 MB, and the first row within a second.

    python benchmarks/streaming.py            # 10 M rows (5 M angles, both branches)
    python benchmarks/streaming.py --rows 1e6
"""
from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import time


def measure(rows: int) -> dict:
    angles = rows // 2  # both branches
    step = 360.0 / angles
    command = [sys.executable, "-m", "symlink", "fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56",
               "--ground", "80", "--crank-speed", "10.5", "--step", repr(step), "--format", "csv"]
    start = time.perf_counter()
    child = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                             env={**os.environ, "PYTHONUNBUFFERED": "1"})
    header = child.stdout.readline()
    first = child.stdout.readline()
    first_row = time.perf_counter() - start
    counted = 1 if first else 0
    while True:
        chunk = child.stdout.read(1 << 20)
        if not chunk:
            break
        counted += chunk.count(b"\n")
    child.wait()
    total = time.perf_counter() - start
    peak_kib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    return {"rows": counted, "header": header.decode().strip(), "first_row_s": first_row, "total_s": total,
            "peak_rss_mb": peak_kib / 1024, "status": child.returncode}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=float, default=1e7, help="rows to stream (default 1e7)")
    found = measure(int(parser.parse_args(argv).rows))
    print(f"rows {found['rows']:,}  first row after {found['first_row_s']:.3f} s  total {found['total_s']:.1f} s  "
          f"peak RSS {found['peak_rss_mb']:.0f} MB  exit {found['status']}")
    held = found["peak_rss_mb"] < 300 and found["first_row_s"] < 1.0 and found["status"] == 0
    print("bound (peak RSS < 300 MB, first row < 1 s):", "held" if held else "MISSED")
    return 0


if __name__ == "__main__":
    sys.exit(main())
