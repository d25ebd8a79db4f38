"""What a command may plan to use: memory and time, estimated before any work starts.

Every command that can be asked for an amount of work (flywheel samples, sweep designs,
animation frames, synthesis starts, table rows) estimates the memory and the time that
amount needs from its size alone, and refuses it, with what it would need and how to
lower it, when the estimate is beyond the budget: :data:`MEMORY_BUDGET` (so that every
command line stays under 2 GB with the interpreter and its libraries) or less when the
machine has less available, and the time budget: :data:`TIME_BUDGET` of work unless the
command line raises it with ``--time-budget`` (:func:`add_time_budget_option`; every command
that estimates its time takes it, and :func:`time_budget` is what they all compare with).

>>> require_budget(10**7, 1500, 1e-5, "a flywheel of --samples 10000000", "--samples", available=8 * 10**9)
Traceback (most recent call last):
ValueError: a flywheel of --samples 10000000 would need about 15 GB of memory (at most 1.5 GB a command); use --samples 1,000,000 or fewer
"""
from __future__ import annotations

import argparse
import math

from ..common.limits import available_memory, format_bytes, format_duration

__all__ = ["MEMORY_BUDGET", "TIME_BUDGET", "LONGEST_TIME_BUDGET", "require_budget", "format_duration",
           "time_budget", "use_time_budget", "duration", "add_time_budget_option", "budget_text"]

#: Bytes a command may plan for its own arrays (the interpreter, NumPy, SymPy and Matplotlib take about 0.3 GB more).
MEMORY_BUDGET = 1_500_000_000
#: Seconds of work a command may plan for by default (an hour: longer is more often a slip of the finger, 1e9 for
#: 1e6, than a wish; ``--time-budget`` raises it for a long sweep or search).
TIME_BUDGET = 3600.0
#: The largest ``--time-budget`` (a year): beyond it an estimate means the request is wrong, not long.
LONGEST_TIME_BUDGET = 365 * 86400.0
#: The units ``--time-budget`` takes, in seconds.
_DURATION_UNITS = {"s": 1.0, "m": 60.0, "min": 60.0, "h": 3600.0, "d": 86400.0}
#: The time budget of the command running now (:func:`use_time_budget`).
_budget = [TIME_BUDGET]


def time_budget() -> float:
    """Seconds of work the running command may plan for: ``--time-budget`` where given, else :data:`TIME_BUDGET`."""
    return _budget[0]


def use_time_budget(seconds: float | None) -> None:
    """Set the running command's time budget (None: the default, :data:`TIME_BUDGET`); the command line's
    ``main`` calls it with each command's ``--time-budget`` before running it."""
    _budget[0] = TIME_BUDGET if seconds is None else float(seconds)


def duration(text: str) -> float:
    """Seconds from the command line: a number with an optional unit s, m (min), h or d; 1 s to a year.

    >>> duration("90"), duration("30m"), duration("12h"), duration("7d")
    (90.0, 1800.0, 43200.0, 604800.0)
    >>> duration("2y")
    Traceback (most recent call last):
    argparse.ArgumentTypeError: expected a duration such as 3600, 90m, 12h or 7d (units s, m, h, d), got '2y'
    """
    stripped = text.strip().lower()
    number = stripped.rstrip("abcdefghijklmnopqrstuvwxyz")
    unit = stripped[len(number):] or "s"
    try:
        seconds = float(number) * _DURATION_UNITS[unit]
    except (ValueError, KeyError):
        raise argparse.ArgumentTypeError(f"expected a duration such as 3600, 90m, 12h or 7d (units s, m, h, d), "
                                         f"got {text[:40]!r}") from None
    if not 1.0 <= seconds <= LONGEST_TIME_BUDGET:  # NaN too
        raise argparse.ArgumentTypeError(f"must be from 1 s to {format_duration(LONGEST_TIME_BUDGET)}, got "
                                         f"{text[:40]!r}")
    return seconds


def add_time_budget_option(parser: argparse.ArgumentParser) -> None:
    """``--time-budget DURATION``: the most work the command may plan for (see :func:`time_budget`)."""
    parser.add_argument("--time-budget", type=duration, metavar="DURATION",
                        help=f"the longest work this command may plan for, estimated before it starts: seconds, or "
                             f"with a unit, 90m, 12h, 7d (default {format_duration(TIME_BUDGET)}, at most a year)")


def budget_text() -> str:
    """How a message names the time budget: ``at most 60 min a command`` and how to raise it."""
    return f"at most {format_duration(time_budget())} a command, --time-budget"


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
    budget = time_budget()
    fits_time = max(budget - fixed_seconds, 0.0) / seconds_each if seconds_each > 0 else math.inf
    fits = max(1, int(min(fits_memory, fits_time)))
    if count * bytes_each > memory:
        raise ValueError(f"{what} would need about {format_bytes(count * bytes_each)} of memory (at most "
                         f"{format_bytes(memory)} a command); use {option} {_round_down(fits):,} or fewer")
    if fixed_seconds + count * seconds_each > budget:
        remedy = (f"use {option} {_round_down(fits):,} or fewer" if fits_time >= 1 else
                  f"its fixed work alone takes about {format_duration(fixed_seconds)}: raise --time-budget")
        raise ValueError(f"{what} would take about {format_duration(fixed_seconds + count * seconds_each)} "
                         f"({budget_text()}); {remedy}")


def _round_down(value: int) -> int:
    """``value`` down to two significant digits: a suggestion people can type."""
    if value < 100:
        return value
    scale = 10 ** (len(str(value)) - 2)
    return value // scale * scale
