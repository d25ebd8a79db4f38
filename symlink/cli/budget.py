"""What a command may plan to use: memory and time, estimated before any work starts.

Every command that can be asked for an amount of work (flywheel samples, sweep designs,
animation frames, synthesis starts, table rows) estimates the memory and the time that
amount needs from its size alone, and refuses it, with what it would need and how to
lower it, when the estimate is beyond the budget: :data:`MEMORY_BUDGET` (so that every
command line stays under 2 GB with the interpreter and its libraries) or less when the
machine has less available, and :data:`TIME_BUDGET` of work.

>>> require_budget(10**7, 1500, 1e-5, "a flywheel of --samples 10000000", "--samples", available=8 * 10**9)
Traceback (most recent call last):
ValueError: a flywheel of --samples 10000000 would need about 15 GB of memory (at most 1.5 GB a command); use --samples 1,000,000 or fewer
"""
from __future__ import annotations

import math

from ..common.limits import available_memory, format_bytes, format_duration

__all__ = ["MEMORY_BUDGET", "TIME_BUDGET", "require_budget", "format_duration"]

#: Bytes a command may plan for its own arrays (the interpreter, NumPy, SymPy and Matplotlib take about 0.3 GB more).
MEMORY_BUDGET = 1_500_000_000
#: Seconds of work a command may plan for (one command line, not a sweep on a cluster).
TIME_BUDGET = 3600.0


def require_budget(count: float, bytes_each: float, seconds_each: float, what: str, option: str,
                   available: int | None = None, fixed_seconds: float = 0.0) -> None:
    """``ValueError`` (one line) if ``count`` units of work at ``bytes_each`` and ``seconds_each`` are beyond budget.

    ``what`` names the request; the message ends with the largest ``option`` value that fits both budgets.
    ``available`` (bytes) defaults to what the machine has now; the memory budget is the smaller of that and
    :data:`MEMORY_BUDGET`.
    """
    if available is None:
        available = available_memory()
    memory = MEMORY_BUDGET if available is None else min(MEMORY_BUDGET, available)
    fits_memory = memory / bytes_each if bytes_each > 0 else math.inf
    fits_time = max(TIME_BUDGET - fixed_seconds, 0.0) / seconds_each if seconds_each > 0 else math.inf
    fits = max(1, int(min(fits_memory, fits_time)))
    if count * bytes_each > memory:
        raise ValueError(f"{what} would need about {format_bytes(count * bytes_each)} of memory (at most "
                         f"{format_bytes(memory)} a command); use {option} {_round_down(fits):,} or fewer")
    if fixed_seconds + count * seconds_each > TIME_BUDGET:
        raise ValueError(f"{what} would take about {format_duration(fixed_seconds + count * seconds_each)} (at most "
                         f"{format_duration(TIME_BUDGET)} a command); use {option} {_round_down(fits):,} or fewer")


def _round_down(value: int) -> int:
    """``value`` down to two significant digits: a suggestion people can type."""
    if value < 100:
        return value
    scale = 10 ** (len(str(value)) - 2)
    return value // scale * scale
