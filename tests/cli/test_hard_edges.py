"""Hard edges of the command line: negative numbers as values, requests refused rather than bent, work and memory
estimated before a command starts.  Each bad command line is one line of error and exit status 2."""
from __future__ import annotations

import math

import numpy as np
import pytest

from symlink.cli import main
from symlink.input_sweep import crank_speeds

FOURBAR = ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80"]


def _one_error_line(err: str, *words: str) -> None:
    assert err.count("\n") == 1 and err.startswith("symlink: error: ") and "Traceback" not in err, err
    for word in words:
        assert word in err, err


# --- a crank turning clockwise and speeding up -------------------------------------------------------------------

def test_a_clockwise_crank_speeding_up_reaches_each_angle_turning_clockwise():
    """From 0 at -10.5 rad/s, -25 rad/s^2: 350 deg is reached after turning -10 deg (hand: w^2 = w0^2 + 2 al turned)."""
    angles = np.radians([0.0, 350.0, 180.0, 10.0])
    turned = np.radians([0.0, -10.0, -180.0, -350.0])
    expected = -np.sqrt(10.5 ** 2 + 2 * -25.0 * turned)
    assert crank_speeds(angles, -10.5, -25.0) == pytest.approx(expected, rel=1e-15)


def test_a_counter_clockwise_crank_is_as_before():
    angles = np.radians([0.0, 40.0, 80.0])
    assert crank_speeds(angles, 10.5, 25.0) == pytest.approx(np.sqrt(10.5 ** 2 + 50.0 * angles), rel=1e-15)


def test_a_clockwise_crank_slowing_down_still_stops():
    with pytest.raises(ValueError, match="the crank stops"):
        crank_speeds(np.radians(np.arange(0.0, 360.0, 10.0)), -1.0, 25.0)


def test_the_clockwise_table_is_printed(capsys):
    assert main([*FOURBAR, "--crank-speed", "-10.5", "--crank-accel", "-25", "--format", "csv"]) == 0
    rows = capsys.readouterr().out.strip().splitlines()
    assert len(rows) == 1 + 36 * 2
