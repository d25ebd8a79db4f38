"""The JavaScript frame benchmark (``benchmarks/javascript_frame.py``): it runs and prints its lines (no timings asserted)."""
import re
import shutil

import pytest

from benchmarks.javascript_frame import cpu_model, main


def test_a_short_run_prints_the_cpu_and_microseconds_a_frame(capsys):
    if shutil.which("node") is None:
        pytest.skip("Node.js is not installed (no node on PATH): nothing to time")
    assert main(["--calls", "2000", "--repeats", "1", "--linkage", "fourbar"]) == 0
    out = capsys.readouterr().out
    assert out.startswith(f"CPU: {cpu_model()}; Node v") and "fourbar, 2000 solve calls a run" in out
    assert len(re.findall(r"solve: [0-9.]+ us a frame", out)) == 2
    assert "geometry (every joint's x, y): 8 outputs, 100 % assembled" in out  # A, B, C, D: a crank-rocker
