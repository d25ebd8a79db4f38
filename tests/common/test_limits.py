"""Size limits: a request's memory is estimated before anything is allocated, and one too large is refused
in one line that says how much it needs and how to split it."""
import os

import numpy as np
import pytest

from symlink.common import limits
from symlink.mechanism.catalog import fourbar, stephenson3
from symlink.common.limits import available_memory, format_bytes, require_memory
from symlink.numeric.solver import NumericSolver, Solver

GIGABYTE = 10**9


def test_available_memory_reads_memavailable(tmp_path, monkeypatch):
    meminfo = tmp_path / "meminfo"
    meminfo.write_text("MemTotal:       16384000 kB\nMemFree:         1000000 kB\nMemAvailable:    8000000 kB\n")
    monkeypatch.setattr(limits, "_MEMINFO", str(meminfo))
    assert available_memory() == 8_000_000 * 1024


def test_available_memory_falls_back_to_sysconf(tmp_path, monkeypatch):
    monkeypatch.setattr(limits, "_MEMINFO", str(tmp_path / "absent"))
    if not hasattr(os, "sysconf") or "SC_AVPHYS_PAGES" not in os.sysconf_names:
        assert available_memory() is None
    else:
        assert available_memory() == os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")


def test_the_machine_reports_some_memory():
    assert available_memory() is None or available_memory() > 0


@pytest.mark.parametrize("count, text", [(0, "0 bytes"), (999, "999 bytes"), (1000, "1 kB"), (1.5e6, "1.5 MB"),
                                         (24e9, "24 GB"), (3.2e12, "3.2 TB")])
def test_format_bytes(count, text):
    assert format_bytes(count) == text


def test_require_memory_passes_what_fits_and_refuses_what_does_not():
    require_memory(1000, 8, "x", available=8000)  # exactly fits
    with pytest.raises(ValueError) as refused:
        require_memory(1001, 8, "solving 1001 values", available=8000)
    message = str(refused.value)
    assert "\n" not in message
    # 1001 * 8 = 8008 bytes; half of 8000 bytes holds 500 values of 8 bytes.
    assert message.startswith("solving 1001 values needs about 8 kB of memory, more than the 8 kB available")
    assert "at most 500 values at a time" in message


def test_unknown_memory_is_not_checked(monkeypatch):
    monkeypatch.setattr(limits, "available_memory", lambda: None)
    require_memory(10**15, 10**6, "a huge request")


@pytest.fixture
def two_gigabytes(monkeypatch):
    monkeypatch.setattr(limits, "available_memory", lambda: 2 * GIGABYTE)


def test_1e8_values_through_the_solver_end_in_one_clear_line(two_gigabytes):
    solver = Solver(fourbar(), ["rocker"])
    theta = np.broadcast_to(0.0, (10**8,))  # a view: nothing is allocated for the 1e8 values
    with pytest.raises(ValueError) as refused:
        solver(theta=theta, a=20, b=66, c=56, d=80)
    message = str(refused.value)
    assert "\n" not in message
    assert message.startswith("solving 1e+08 input values with the fourbar solver needs about ")
    assert "more than the 2 GB available; call it with at most " in message
    # The estimate counts at least the output and assembled arrays: 1e8 * 9 bytes.
    needed = float(message.split("needs about ")[1].split(" GB")[0])
    assert needed >= 0.9
    fits = int(message.split("at most ")[1].split(" values")[0].replace(",", ""))
    assert 0 < fits * solver.bytes_per_value <= GIGABYTE
    # A call of that many values goes through.
    assert solver(theta=np.zeros(min(fits, 1000)), a=20, b=66, c=56, d=80)["rocker"].shape == (min(fits, 1000),)


def test_the_estimate_counts_every_intermediate_array():
    small, large = Solver(fourbar(), ["rocker"]), Solver(fourbar(), ["rocker_accel", "coupler_accel"])
    assert small.bytes_per_value >= 8 * 10 and large.bytes_per_value > small.bytes_per_value


def test_broadcast_arguments_count_as_their_broadcast_size(two_gigabytes):
    solver = Solver(fourbar(), ["rocker"])
    theta = np.broadcast_to(0.0, (10**4, 1))
    lengths = np.broadcast_to(20.0, (1, 10**4))  # 1e4 x 1e4 = 1e8 configurations
    with pytest.raises(ValueError, match="solving 1e[+]08 input values"):
        solver(theta=theta, a=lengths, b=66, c=56, d=80)


def test_the_numeric_solver_refuses_too_large_sweeps(two_gigabytes):
    solver = NumericSolver(stephenson3())
    with pytest.raises(ValueError, match=r"^solving 1e\+08 input values with the stephenson3 numeric solver needs "
                                         r"about [0-9.]+ [GT]B of memory, more than the 2 GB available; call it "
                                         r"with at most [0-9,]+ values at a time"):
        solver(theta=np.broadcast_to(0.0, (10**8,)), a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1,
               alpha=0.9, delta=0.3, guess=dict(beta=0.96, mu=0.27, phi=1.43, eta=-0.16))
