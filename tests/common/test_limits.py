"""Size limits: a request's memory is estimated before anything is allocated, and one too large is refused
in one line that says how much it needs and how to split it."""
import os
import re

import numpy as np
import pytest

from symlink.common import limits
from symlink.mechanism.catalog import fourbar, stephenson2
from symlink.common.limits import available_memory, format_bytes, require_memory
from symlink.numeric.solver import NumericSolver, Solver

GIGABYTE = 10**9


def test_machine_memory_reads_memavailable(tmp_path, monkeypatch):
    meminfo = tmp_path / "meminfo"
    meminfo.write_text("MemTotal:       16384000 kB\nMemFree:         1000000 kB\nMemAvailable:    8000000 kB\n")
    monkeypatch.setattr(limits, "_MEMINFO", str(meminfo))
    assert limits.machine_memory() == 8_000_000 * 1024


def test_machine_memory_falls_back_to_sysconf(tmp_path, monkeypatch):
    monkeypatch.setattr(limits, "_MEMINFO", str(tmp_path / "absent"))
    if not hasattr(os, "sysconf") or "SC_AVPHYS_PAGES" not in os.sysconf_names:
        assert limits.machine_memory() is None
    else:
        assert limits.machine_memory() == os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")


KB, MB, GB = 1024, 2**20, 2**30
V1_UNLIMITED = "9223372036854771712"


def _status(vmsize_kb):
    return f"Name:\tpython\nVmPeak:\t  999999 kB\nVmSize:\t {vmsize_kb} kB\nVmRSS:\t 1000 kB\n"


# Each case: the files the process would see (relative to a fake root), the RLIMIT_AS (None: unlimited),
# and the bytes available (None: nothing known).  The memory of the machine is 8 GB throughout unless absent.
LIMIT_CASES = {
    "the machine alone": ({}, None, 8 * GB),
    "nothing readable": ({"proc/meminfo": None}, None, None),
    "ulimit -v below the machine": ({"proc/self/status": _status(500 * 1024)}, 2 * GB, 2 * GB - 500 * MB),
    "ulimit -v above the machine": ({"proc/self/status": _status(500 * 1024)}, 64 * GB, 8 * GB),
    "ulimit -v already used up": ({"proc/self/status": _status(3 * 1024 * 1024)}, 2 * GB, 0),
    "ulimit -v without a status file": ({}, 2 * GB, 2 * GB),
    "a status without VmSize": ({"proc/self/status": "Name:\tpython\n"}, 2 * GB, 2 * GB),
    "cgroup v2 at the root": ({"proc/self/cgroup": "0::/\n", "cg/memory.max": f"{3 * GB}\n",
                               "cg/memory.current": f"{GB}\n"}, None, 2 * GB),
    "cgroup v2 max": ({"proc/self/cgroup": "0::/\n", "cg/memory.max": "max\n", "cg/memory.current": "5\n"},
                      None, 8 * GB),
    "cgroup v2 in the process's own group": (
        {"proc/self/cgroup": "0::/box/job\n", "cg/box/job/memory.max": f"{GB}\n",
         "cg/box/job/memory.current": f"{256 * MB}\n", "cg/memory.max": "max\n"}, None, 768 * MB),
    "cgroup v2 limited by a parent": (
        {"proc/self/cgroup": "0::/box/job\n", "cg/box/job/memory.max": "max\n",
         "cg/box/memory.max": f"{GB}\n", "cg/box/memory.current": f"{512 * MB}\n"}, None, 512 * MB),
    "cgroup v2 without memory.current": ({"proc/self/cgroup": "0::/\n", "cg/memory.max": f"{GB}\n"}, None, GB),
    "cgroup v2 garbage": ({"proc/self/cgroup": "0::/\n", "cg/memory.max": "lots\n"}, None, 8 * GB),
    "cgroup v1": ({"proc/self/cgroup": "4:memory:/docker/abc\n0::/\n",
                   "cg/memory/memory.limit_in_bytes": f"{4 * GB}\n",
                   "cg/memory/memory.usage_in_bytes": f"{GB}\n"}, None, 3 * GB),
    "cgroup v1 unlimited": ({"proc/self/cgroup": "4:memory:/\n", "cg/memory/memory.limit_in_bytes": V1_UNLIMITED,
                             "cg/memory/memory.usage_in_bytes": f"{GB}\n"}, None, 8 * GB),
    "cgroup v1 with controllers joined": ({"proc/self/cgroup": "3:cpu,memory:/a\n",
                                           "cg/memory/a/memory.limit_in_bytes": f"{GB}\n",
                                           "cg/memory/a/memory.usage_in_bytes": "0\n"}, None, GB),
    "cgroup over its limit": ({"proc/self/cgroup": "0::/\n", "cg/memory.max": f"{GB}\n",
                               "cg/memory.current": f"{2 * GB}\n"}, None, 0),
    "the least of all three": ({"proc/self/status": _status(100 * 1024), "proc/self/cgroup": "0::/\n",
                                "cg/memory.max": f"{2 * GB}\n", "cg/memory.current": f"{GB}\n"},
                               GB + 100 * MB + 1, GB),
}


@pytest.mark.parametrize("files, rlimit, expected", LIMIT_CASES.values(), ids=LIMIT_CASES.keys())
def test_available_memory_is_the_least_of_the_machine_the_address_space_and_the_cgroup(
        tmp_path, monkeypatch, files, rlimit, expected):
    files = {"proc/meminfo": f"MemTotal: 16777216 kB\nMemAvailable: {8 * GB // KB} kB\n", **files}
    for name, text in files.items():
        if text is not None:
            (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
            (tmp_path / name).write_text(text)
    monkeypatch.setattr(limits, "_MEMINFO", str(tmp_path / "proc/meminfo"))
    monkeypatch.setattr(limits, "_STATUS", str(tmp_path / "proc/self/status"))
    monkeypatch.setattr(limits, "_CGROUPS", str(tmp_path / "proc/self/cgroup"))
    monkeypatch.setattr(limits, "_CGROUP_V2", str(tmp_path / "cg"))
    monkeypatch.setattr(limits, "_CGROUP_V1", str(tmp_path / "cg/memory"))
    monkeypatch.setattr(limits, "_address_space_limit", lambda: rlimit)
    if files["proc/meminfo"] is None:
        monkeypatch.setattr(os, "sysconf", lambda name: (_ for _ in ()).throw(ValueError(name)))
    assert available_memory() == expected


def test_the_real_address_space_limit_is_read():
    resource = pytest.importorskip("resource")
    soft = resource.getrlimit(resource.RLIMIT_AS)[0]
    assert limits._address_space_limit() == (None if soft == resource.RLIM_INFINITY else soft)
    used = limits._address_space_used()
    assert used is None or used > 10 * MB  # an interpreter with NumPy and SymPy loaded


def test_the_machine_reports_some_memory():
    assert available_memory() is None or available_memory() > 0


@pytest.mark.parametrize("count, text", [(0, "0 bytes"), (999, "999 bytes"), (1000, "1 kB"), (1.5e6, "1.5 MB"),
                                         (24e9, "24 GB"), (3.2e12, "3.2 TB")])
def test_format_bytes(count, text):
    assert format_bytes(count) == text


def test_a_small_request_is_not_checked_against_the_machine(monkeypatch):
    """At most UNCHECKED_BYTES: the limits are not read (a solver's small calls); one byte more: they are."""
    import symlink.common.limits as limits
    readings = []
    monkeypatch.setattr(limits, "available_memory", lambda: readings.append(1) or 10)
    require_memory(limits.UNCHECKED_BYTES // 8, 8, "a small call")
    assert readings == []
    with pytest.raises(ValueError, match="a larger call needs"):
        require_memory(limits.UNCHECKED_BYTES + 1, 1, "a larger call")
    assert readings == [1]


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
    solver = NumericSolver(stephenson2())
    with pytest.raises(ValueError, match=r"^solving 1e\+08 input values with the stephenson2 numeric solver needs "
                                         r"about [0-9.]+ [GT]B of memory, more than the 2 GB available; call it "
                                         r"with at most [0-9,]+ values at a time"):
        solver(theta=np.broadcast_to(0.0, (10**8,)), a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1,
               alpha=0.9, delta=0.3, guess=dict(beta=0.96, mu=0.27, phi=1.43, eta=-0.16))


# A process under ``ulimit -v 1500000`` (1.5 GB of address space, less what the interpreter, NumPy and SymPy take)
# on a machine that may well have far more memory available.
ULIMIT_KB = 1_500_000
PROJECT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

TOO_LARGE_FOR_THE_LIMIT = """
import numpy as np
from symlink.mechanism.catalog import fourbar
from symlink.numeric.solver import Solver
solver = Solver(fourbar(), ["rocker"])
try:  # 1e4 crank angles x 1e4 coupler lengths: 1e8 configurations, 763 MiB an output array
    solver(theta=np.linspace(0, 6, 10**4)[:, None], a=20, b=np.linspace(60, 70, 10**4)[None, :], c=56, d=80)
except ValueError as refused:
    print("refused:", refused)
"""


def _under_ulimit(command: str, tmp_path):
    import shutil
    import subprocess
    import sys
    if sys.platform != "linux" or shutil.which("bash") is None:
        pytest.skip("ulimit -v needs Linux and bash")
    env = {**os.environ, "PYTHONPATH": PROJECT, "MPLBACKEND": "Agg", "SYMLINK_CACHE": str(tmp_path / "cache"),
           "OPENBLAS_NUM_THREADS": "1"}
    return subprocess.run(["bash", "-c", f"ulimit -v {ULIMIT_KB} && {command}"], capture_output=True, text=True,
                          env=env, cwd=str(tmp_path), timeout=600)


def test_a_call_too_large_for_ulimit_is_refused_in_one_line_before_allocating(tmp_path):
    import shlex
    import sys
    run = _under_ulimit(f"{shlex.quote(sys.executable)} -c {shlex.quote(TOO_LARGE_FOR_THE_LIMIT)}", tmp_path)
    assert "MemoryError" not in run.stderr, run.stderr
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert len(lines) == 1 and lines[0].startswith(
        "refused: solving 1e+08 input values with the fourbar solver needs about "), run.stdout
    available = lines[0].split("more than the ")[1].split(" available")[0]
    amount, unit = available.split()
    # what is left of 1.5 GB of address space, not the machine's memory
    assert float(amount) * {"MB": 1e6, "GB": 1e9}[unit] <= ULIMIT_KB * 1024


def test_the_command_line_refuses_a_table_too_large_for_ulimit_in_one_line(tmp_path):
    import shlex
    import sys
    stephenson2 = ("stephenson2 --crank 1 --coupler 3.1 --link-cf 2.2 --ground 4.5 --coupler-arm 3.9 --rocker 3.1 "
                   "--link-eh 4.1 --rocker-arm 3.1 --coupler-arm-angle 51.57 --rocker-arm-angle 17.19")
    # 9e6 crank angles solved by Newton's method at once (a table without a closed form)
    run = _under_ulimit(f"{shlex.quote(sys.executable)} -m symlink {stephenson2} --step 0.00004", tmp_path)
    assert run.returncode == 2, run.stderr
    assert run.stdout == ""
    assert run.stderr.count("\n") == 1 and "MemoryError" not in run.stderr, run.stderr
    assert run.stderr.startswith("symlink: error: a table of 9,000,000 crank angles of stephenson2 (solved by "
                                 "Newton's method all at once) needs about "), run.stderr
    assert re.search(r" available; use at most [0-9,]+ crank angles \(a larger --step or fewer --angles\)\n\Z",
                     run.stderr), run.stderr
