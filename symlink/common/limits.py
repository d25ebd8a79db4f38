"""How much memory a request needs, and a one-line refusal of a request the process cannot hold.

A solver evaluates every input value at once: its outputs, its intermediate
arrays and NumPy's temporaries are all as large as the input.  Asked for
1e8 values, NumPy would allocate for a while and then fail with a bare
``MemoryError`` (or the system would start swapping).  So the solvers
estimate the bytes a call needs *before* allocating anything and refuse a
call beyond the memory this process can still have, with one line saying how
much it needs and how to split it.

What the process can still have is the least of three limits, each read
defensively (a file that is missing or unreadable, or a limit of ``max``,
is no limit): the machine's available memory (:func:`machine_memory`), the
address space left under the process's ``RLIMIT_AS`` (``ulimit -v``,
:func:`address_space_room`) and the memory left under its control group's
limit (a container's, cgroup v2 or v1, :func:`cgroup_room`).

>>> format_bytes(3.5e9)
'3.5 GB'
>>> require_time(10**9, 0.01, "a shape search of 1,000,000,000 designs", "designs")
Traceback (most recent call last):
ValueError: a shape search of 1,000,000,000 designs would take about 116 days (at most 24 hours a call); use designs 8,640,000 or fewer
>>> require_memory(10**8, 240, "solving 1e+08 input values", available=2 * 10**9)
Traceback (most recent call last):
ValueError: solving 1e+08 input values needs about 24 GB of memory, more than the 2 GB available; call it with at most 4,166,666 values at a time and join the results (InputSweep.blocks() yields a long sweep block by block)
"""
from __future__ import annotations

import os
from typing import Callable

__all__ = ["available_memory", "machine_memory", "address_space_room", "cgroup_room", "format_bytes",
           "format_duration", "require_memory", "require_time", "WORK_SECONDS"]

#: Seconds of work one call may plan for: a search or sampling estimated to take longer is taken for a mistake
#: (a day; a command line allows less, :data:`symlink.cli.budget.TIME_BUDGET`).
WORK_SECONDS = 86400.0

_MEMINFO = "/proc/meminfo"
#: The process's own status: ``VmSize``, the address space it already uses.
_STATUS = "/proc/self/status"
#: Which control groups the process is in (``0::/path`` for cgroup v2, ``N:memory:/path`` for v1's memory).
_CGROUPS = "/proc/self/cgroup"
#: Where cgroup v2 and v1's memory controller are mounted.
_CGROUP_V2 = "/sys/fs/cgroup"
_CGROUP_V1 = "/sys/fs/cgroup/memory"
#: A request of at most this many bytes is not checked against what the process may have: reading it (meminfo,
#: cgroups, rlimits) costs about 0.2 ms, more than a small call's work (440 calls of a warm analysis: 0.1 s), and
#: a process short of a megabyte fails before any check could help.
UNCHECKED_BYTES = 1 << 20
#: A limit at least this large is no limit (cgroup v1 writes "unlimited" as about 2**63).
_UNLIMITED = 1 << 60


def _read_text(path: str) -> str | None:
    """The text of a small system file; None where it is missing or cannot be read."""
    try:
        with open(path, encoding="ascii", errors="replace") as file:
            return file.read()
    except OSError:
        return None


def _read_bytes(path: str) -> int | None:
    """A byte count written alone in a file (cgroup's files); None if missing, unreadable, ``max`` or unlimited."""
    text = _read_text(path)
    if text is None:
        return None
    try:
        value = int(text.strip())
    except ValueError:  # "max", or anything else
        return None
    return value if 0 <= value < _UNLIMITED else None


def machine_memory() -> int | None:
    """Bytes the machine can still give this process without swapping; None where that cannot be found out.

    ``MemAvailable`` of ``/proc/meminfo`` on Linux (free memory plus the caches
    it can drop), else the free physical pages that ``os.sysconf`` reports.
    """
    text = _read_text(_MEMINFO)
    for line in (text or "").splitlines():
        if line.startswith("MemAvailable:"):
            try:
                amount, unit = line.split()[1:3]
                return int(amount) * (1024 if unit == "kB" else 1)
            except ValueError:
                break
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, OSError, ValueError):
        return None


def _address_space_limit() -> int | None:
    """The soft ``RLIMIT_AS`` of this process in bytes; None where it is infinite or unknown."""
    try:
        import resource
    except ImportError:  # not on Windows
        return None
    try:
        soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    except (OSError, ValueError, AttributeError):
        return None
    return None if soft == resource.RLIM_INFINITY or soft < 0 or soft >= _UNLIMITED else int(soft)


def _address_space_used() -> int | None:
    """The address space this process already has (``VmSize`` of ``/proc/self/status``); None where unknown."""
    for line in (_read_text(_STATUS) or "").splitlines():
        if line.startswith("VmSize:"):
            try:
                amount, unit = line.split()[1:3]
                return int(amount) * (1024 if unit == "kB" else 1)
            except ValueError:
                return None
    return None


def address_space_room() -> int | None:
    """Bytes of address space left under the process's ``RLIMIT_AS`` (``ulimit -v``); None where it is unlimited.

    The limit less ``VmSize``; where the size in use cannot be read, the limit
    itself (an upper bound).
    """
    limit = _address_space_limit()
    if limit is None:
        return None
    used = _address_space_used()
    return max(0, limit - (used or 0))


def _cgroup_folders(version: int) -> list[str]:
    """The folders of the process's control group and of its ancestors, for cgroup ``version`` 2 or 1.

    The process's own path from ``/proc/self/cgroup`` under the mount point and
    each parent up to the mount point itself (in a container that mount point
    is the container's own group, whatever the path says).
    """
    mount = _CGROUP_V2 if version == 2 else _CGROUP_V1
    path = ""
    for line in (_read_text(_CGROUPS) or "").splitlines():
        fields = line.split(":", 2)
        if len(fields) != 3:
            continue
        if (version == 2 and fields[0] == "0" and fields[1] == "") or (
                version == 1 and "memory" in fields[1].split(",")):
            path = fields[2].strip()
            break
    parts = [part for part in path.split("/") if part and part not in (".", "..")]
    folders = [os.path.join(mount, *parts[:end]) for end in range(len(parts), 0, -1)]
    return folders + [mount]


def cgroup_room() -> int | None:
    """Bytes left under the memory limit of the process's control group; None where no limit is set or found.

    cgroup v2: ``memory.max`` less ``memory.current``; v1:
    ``memory.limit_in_bytes`` less ``memory.usage_in_bytes``; the least over
    the group and its ancestors that can be read.
    """
    rooms = []
    for version, limit_file, usage_file in ((2, "memory.max", "memory.current"),
                                            (1, "memory.limit_in_bytes", "memory.usage_in_bytes")):
        for folder in _cgroup_folders(version):
            limit = _read_bytes(os.path.join(folder, limit_file))
            if limit is not None:
                usage = _read_bytes(os.path.join(folder, usage_file))
                rooms.append(max(0, limit - (usage or 0)))
    return min(rooms) if rooms else None


def available_memory() -> int | None:
    """Bytes this process can still allocate: the least of the machine's, ``RLIMIT_AS``'s and its cgroup's room.

    :func:`machine_memory`, :func:`address_space_room` and
    :func:`cgroup_room`, each where known; None where none is.
    """
    known = [room for room in (machine_memory(), address_space_room(), cgroup_room()) if room is not None]
    return min(known) if known else None


def format_bytes(count: float) -> str:
    """A byte count the way people read it: two significant digits and a decimal unit.

    >>> format_bytes(512), format_bytes(1.234e6), format_bytes(58e9), format_bytes(158e9)
    ('512 bytes', '1.2 MB', '58 GB', '158 GB')
    """
    for unit, size in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if count >= size:
            return f"{count / size:{'.0f' if count >= 100 * size else '.2g'}} {unit}"
    return f"{count:.0f} bytes"


def format_duration(seconds: float) -> str:
    """A duration the way people read it.

    >>> format_duration(42), format_duration(3600), format_duration(9000), format_duration(3e7), format_duration(1e30)
    ('42 s', '60 min', '2.5 hours', '347 days', '3.2e+22 years')
    """
    for unit, size in (("years", 365.25 * 86400), ("days", 86400.0), ("hours", 3600.0), ("min", 60.0)):
        if seconds >= 2 * size:  # never "1 hours": 90 min, 36 hours
            value = seconds / size
            return f"{value:.0f} {unit}" if 10 <= value < 1e6 else f"{value:.2g} {unit}"
    return f"{seconds:.0f} s"


def require_time(count: float, seconds_each: float, what: str, option: str, budget: float = WORK_SECONDS,
                 fixed_seconds: float = 0.0) -> None:
    """``ValueError`` (one line) if ``count`` units of work at ``seconds_each`` would take longer than ``budget``.

    ``what`` names the request; the message gives the estimate and ends with the largest ``option`` value that
    fits (``fixed_seconds``: work the request does whatever its size).
    """
    seconds = fixed_seconds + count * seconds_each
    if seconds <= budget:
        return
    fits = max(1, int(max(budget - fixed_seconds, 0.0) / seconds_each)) if seconds_each > 0 else 1
    raise ValueError(f"{what} would take about {format_duration(seconds)} (at most {format_duration(budget)} a "
                     f"call); use {option} {fits:,} or fewer")


def require_memory(values: int, bytes_per_value: int, what: str, available: int | None = None,
                   advice: Callable[[int], str] | None = None) -> None:
    """``ValueError`` (one line) if ``values`` at ``bytes_per_value`` each need more memory than is available.

    ``what`` names the request (``"solving 1e+08 input values"``);
    ``available`` defaults to :func:`available_memory` (no check where that
    is unknown, nor for a request of at most :data:`UNCHECKED_BYTES`).  The message ends with what to do, given the number of values
    that fits in half the available memory: ``advice(fits)`` if given, else
    calling with at most that many values at a time.
    """
    needed = values * bytes_per_value
    if available is None:
        if needed <= UNCHECKED_BYTES:
            return
        available = available_memory()
    if available is None or needed <= available:
        return
    fits = max(1, available // 2 // max(1, bytes_per_value))
    remedy = advice(fits) if advice is not None else (
        f"call it with at most {fits:,} values at a time and join the results "
        "(InputSweep.blocks() yields a long sweep block by block)")
    raise ValueError(f"{what} needs about {format_bytes(needed)} of memory, more than the "
                     f"{format_bytes(available)} available; {remedy}")
