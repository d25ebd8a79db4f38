"""How much memory a request needs, and a one-line refusal of a request the machine cannot hold.

A solver evaluates every input value at once: its outputs, its intermediate
arrays and NumPy's temporaries are all as large as the input.  Asked for
1e8 values, NumPy would allocate for a while and then fail with a bare
``MemoryError`` (or the system would start swapping).  So the solvers
estimate the bytes a call needs *before* allocating anything and refuse a
call beyond the memory the machine has available, with one line saying how
much it needs and how to split it.

>>> format_bytes(3.5e9)
'3.5 GB'
>>> require_memory(10**8, 240, "solving 1e+08 input values", available=2 * 10**9)
Traceback (most recent call last):
ValueError: solving 1e+08 input values needs about 24 GB of memory, more than the 2 GB available; call it with at most 4,166,666 values at a time and join the results (InputSweep.blocks() yields a long sweep block by block)
"""
from __future__ import annotations

import os
from typing import Callable

__all__ = ["available_memory", "format_bytes", "require_memory"]

_MEMINFO = "/proc/meminfo"


def available_memory() -> int | None:
    """Bytes the machine can still give this process without swapping; None where that cannot be found out.

    ``MemAvailable`` of ``/proc/meminfo`` on Linux (free memory plus the caches
    it can drop), else the free physical pages that ``os.sysconf`` reports.
    """
    try:
        with open(_MEMINFO, encoding="ascii") as meminfo:
            for line in meminfo:
                if line.startswith("MemAvailable:"):
                    amount, unit = line.split()[1:3]
                    return int(amount) * (1024 if unit == "kB" else 1)
    except (OSError, ValueError):
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, OSError, ValueError):
        return None


def format_bytes(count: float) -> str:
    """A byte count the way people read it: two significant digits and a decimal unit.

    >>> format_bytes(512), format_bytes(1.234e6), format_bytes(58e9), format_bytes(158e9)
    ('512 bytes', '1.2 MB', '58 GB', '158 GB')
    """
    for unit, size in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if count >= size:
            return f"{count / size:{'.0f' if count >= 100 * size else '.2g'}} {unit}"
    return f"{count:.0f} bytes"


def require_memory(values: int, bytes_per_value: int, what: str, available: int | None = None,
                   advice: Callable[[int], str] | None = None) -> None:
    """``ValueError`` (one line) if ``values`` at ``bytes_per_value`` each need more memory than is available.

    ``what`` names the request (``"solving 1e+08 input values"``);
    ``available`` defaults to :func:`available_memory` (no check where that
    is unknown).  The message ends with what to do, given the number of values
    that fits in half the available memory: ``advice(fits)`` if given, else
    calling with at most that many values at a time.
    """
    needed = values * bytes_per_value
    if available is None:
        available = available_memory()
    if available is None or needed <= available:
        return
    fits = max(1, available // 2 // max(1, bytes_per_value))
    remedy = advice(fits) if advice is not None else (
        f"call it with at most {fits:,} values at a time and join the results "
        "(InputSweep.blocks() yields a long sweep block by block)")
    raise ValueError(f"{what} needs about {format_bytes(needed)} of memory, more than the "
                     f"{format_bytes(available)} available; {remedy}")
