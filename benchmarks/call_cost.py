"""A user's call at the loop's cost: the four-bar's compiled call beside its loop and the physical limit.

The four-bar's positions (coupler and rocker angles) and full kinematics (with their
speeds and accelerations), N = 10^3 ... 10^6 values a call, every argument a per-value
array (crank angle, the four lengths of seed 003, the branch; the crank's speed and
acceleration numbers), as :mod:`benchmarks.bench` calls every method.  Nanoseconds a
value (CPU time of this thread; the calls take turns round after round, and each method's
median over the rounds is printed: the machine is shared, so interleaved medians):

* ``limit``: the physical limit, a C loop of only the transcendental calls every solver of the
  positions makes (cos, sin, a square root, two atan2) and two stores a value
  (:func:`benchmarks.hand_c.vector_math_limit`, same compiler and flags);
* ``loop``: the generated C loop function alone, writing into outputs allocated once beforehand;
* ``call out=``: the default :class:`symlink.numeric.solver.Solver` (compiled) as a user calls it,
  writing into the caller's arrays (``out=``);
* ``call``: the same, new outputs a call, each result dropped before the next call returns
  (``result = solver(...)`` in a loop: its block is written again, no page faulted in);
* ``call kept``: the same, each result kept for three calls (the block freed by the result three calls
  before written again, where the kept blocks' cap allows: :data:`symlink.numeric.compiled_library.KEPT_LARGE_BYTES`;
  else a new block a call: fresh pages);
* ``numba loop``: the hand-written numba loop of the same formulas (:mod:`benchmarks.numba_loops`:
  exactly the generated code's transcendental calls), into outputs allocated once;
* ``numba call``: that loop called as a user's numba function is, new output arrays a call (dropped).

Beside each: the minor page faults a call (``resource.getrusage(RUSAGE_THREAD).ru_minflt``),
and the ratios of the calls to the loop and to the limit.  Targets (issue 33): ``call out=``
within 1.2x the loop and ``call`` within 1.5x at 10^5-10^6 values.  numba is optional (the
``bench`` extra); without it its rows are left out.

Then small calls kept or dropped (:func:`kept_calls`): the default ``Solver``'s full
kinematics at 10, 100 and 1000 values, each result dropped before the next call
(``dropped``) or kept for 1, 8 or 100 calls (a ``collections.deque`` of that length):
microseconds a call, median of interleaved rounds, and the ratio to the dropped call
(target, issue 33: a kept result costs what a dropped one does).  Then large calls kept or dropped
(:func:`kept_large_calls`): the same at 10^4 to the largest N, each result dropped or kept for 1, 3 or 8
calls, beside the loop: ns a value and minor page faults a call.  The CPU and the load
average (before and after) are printed first.

    python -m benchmarks.call_cost                # N = 10^3 ... 10^6
    python -m benchmarks.call_cost --largest 1e5
"""
from __future__ import annotations

import argparse
import collections
import gc
import math
import os
import resource
import statistics
import time

import numpy

from benchmarks.blocks import ACCEL, LENGTHS, OUTPUTS, SPEED

POSITIONS = ["coupler", "rocker"]
KINDS = {"positions": POSITIONS, "full kinematics": OUTPUTS}
SIZES = (10**3, 10**4, 10**5, 10**6)
METHODS = ("limit", "loop", "call out=", "call", "call kept", "numba loop", "numba call")


def _faults() -> int:
    """Minor page faults of this thread so far (of the process where a thread's are not counted apart)."""
    who = getattr(resource, "RUSAGE_THREAD", resource.RUSAGE_SELF)
    return resource.getrusage(who).ru_minflt


def best_of_turns(calls: dict, budget: float) -> dict[str, tuple[float, float]]:
    """Median CPU seconds a call of each of ``calls`` and its median minor page faults a call, taking turns.

    Each takes one call before any clock starts (its outputs faulted in, its library loaded), then
    rounds of calls, at least five, until about ``budget`` seconds have passed; a call faster than
    a millisecond is repeated back to back within a round and timed by the mean.  The garbage
    collector is off while timing.
    """
    repeats = {}
    for name, call in calls.items():
        call()
        start = time.thread_time()
        call()
        repeats[name] = max(1, min(1000, math.ceil(1e-3 / max(time.thread_time() - start, 1e-7))))
    times: dict[str, list[float]] = {name: [] for name in calls}
    faults: dict[str, list[float]] = {name: [] for name in calls}
    gc.collect()
    gc.disable()
    try:
        end, rounds = time.perf_counter() + budget, 0
        while rounds < 5 or time.perf_counter() < end:
            for name, call in calls.items():
                before, start = _faults(), time.thread_time()
                for _ in range(repeats[name]):
                    call()
                times[name].append((time.thread_time() - start) / repeats[name])
                faults[name].append((_faults() - before) / repeats[name])
            rounds += 1
    finally:
        gc.enable()
    return {name: (statistics.median(times[name]), statistics.median(faults[name])) for name in calls}


def calls_of(kind: str, n: int) -> dict:
    """The calls timed for ``kind`` at ``n`` values (those that cannot run here left out)."""
    from benchmarks.compiled_loops import loop_alone
    from benchmarks.hand_c import hand_library
    from symlink.mechanism.catalog import fourbar
    from symlink.numeric.solver import Solver
    outputs = KINDS[kind]
    full = outputs == OUTPUTS
    theta = numpy.linspace(0.0, 2 * math.pi, n)
    lengths = [numpy.full(n, value) for value in LENGTHS]
    branch = numpy.ones(n)
    values = dict(theta=theta, **dict(zip("abcd", lengths)), branch=branch)
    if full:
        values.update(thetadot=SPEED, thetaddot=ACCEL)
    # One solver for each way of calling (each keeps its own output blocks: one's held results do not
    # take another's).
    solver, fresh, keeping = (Solver(fourbar(), outputs) for _ in range(3))
    if any(made.wait_for_backend() != "compiled" for made in (solver, fresh, keeping)):
        raise RuntimeError("the compiled backend does not answer here (no C compiler?)")
    library = hand_library()
    limit_outputs = [numpy.empty(n), numpy.empty(n)]

    def limit():
        library.vector_math_limit(n, theta.ctypes.data, limit_outputs[0].ctypes.data, limit_outputs[1].ctypes.data)

    out = {name: numpy.empty_like(value) for name, value in solver(**values).items()}
    kept: collections.deque = collections.deque(maxlen=3)
    found = {"limit": limit, "loop": loop_alone(solver._compiled, values, n),
             "call out=": lambda: solver(**values, out=out), "call": lambda: fresh(**values),
             "call kept": lambda: kept.append(keeping(**values))}
    try:
        import numba
    except ImportError:
        return found
    from benchmarks.numba_loops import numba_kernels
    from symlink.symbolic.position import TOLERANCE
    positions, everything = numba_kernels(numba, TOLERANCE)
    arrays = (theta, *lengths, branch)
    rows = numpy.empty((len(outputs), n))
    if full:
        found["numba loop"] = lambda: everything(*arrays, SPEED, ACCEL, *rows)

        def numba_call():
            fresh = numpy.empty((6, n))
            everything(*arrays, SPEED, ACCEL, *fresh)
            return fresh
    else:
        found["numba loop"] = lambda: positions(*arrays, *rows)

        def numba_call():
            fresh = numpy.empty((2, n))
            positions(*arrays, *fresh)
            return fresh
    found["numba call"] = numba_call
    return found


def measure(sizes=SIZES, budget: float = 2.0) -> list[dict]:
    rows = []
    for kind in KINDS:
        for n in sizes:
            timed = best_of_turns(calls_of(kind, n), budget)
            rows.append({"kind": kind, "n": n, **{name: {"ns": 1e9 * seconds / n, "faults": faults}
                                                  for name, (seconds, faults) in timed.items()}})
    return rows


KEPT_SIZES = (10, 100, 1000)
#: How long each result is kept: 0 dropped before the next call, else a deque of that many results.
KEPT_FOR = (0, 1, 8, 100)


def kept_calls(sizes=KEPT_SIZES, kept_for=KEPT_FOR, rounds: int = 30, calls: int = 200) -> list[dict]:
    """Microseconds a call of the default ``Solver`` (full kinematics) at each size, each result dropped or kept
    for ``kept_for`` calls: the median over ``rounds`` rounds taking turns, ``calls`` calls a round (timed by
    their mean).  A solver for each way (each keeps its own blocks)."""
    from symlink.mechanism.catalog import fourbar
    from symlink.numeric.solver import Solver
    found = []
    for n in sizes:
        values = dict(theta=numpy.linspace(0.0, 2 * math.pi, n), **dict(zip("abcd", LENGTHS)), branch=1.0,
                      thetadot=SPEED, thetaddot=ACCEL)
        solvers = {k: Solver(fourbar(), OUTPUTS) for k in kept_for}
        held = {k: collections.deque(maxlen=max(k, 1)) for k in kept_for}
        times: dict[int, list[float]] = {k: [] for k in kept_for}
        for k, solver in solvers.items():
            solver.wait_for_backend()
            for _ in range(2 * calls):  # the blocks made, the deques full
                held[k].append(solver(**values)) if k else solver(**values)
        gc.collect()
        gc.disable()
        try:
            for _ in range(rounds):
                for k, solver in solvers.items():
                    keep = held[k].append
                    start = time.thread_time()
                    if k:
                        for _ in range(calls):
                            keep(solver(**values))
                    else:
                        for _ in range(calls):
                            solver(**values)
                    times[k].append((time.thread_time() - start) / calls)
        finally:
            gc.enable()
        found.append({"n": n, **{k: 1e6 * statistics.median(v) for k, v in times.items()}})
    return found


def kept_report(rows: list[dict]) -> str:
    kept_for = [k for k in rows[0] if k != "n"]
    lines = ["small calls, full kinematics: us a call (median of interleaved rounds), kept / dropped",
             f"{'N':>6} " + " ".join(f"{'dropped' if k == 0 else f'kept {k}':>9}" for k in kept_for)
             + " " + " ".join(f"{f'kept {k}/dropped':>15}" for k in kept_for if k)]
    for row in rows:
        lines.append(f"{row['n']:>6} " + " ".join(f"{row[k]:>9.2f}" for k in kept_for) + " "
                     + " ".join(f"{row[k] / row[0]:>15.2f}" for k in kept_for if k))
    return "\n".join(lines)


LARGE_KEPT_SIZES = (10**4, 10**5, 10**6)
#: How long each result of a large call is kept: 0 dropped before the next call returns, else a deque of that many.
LARGE_KEPT_FOR = (0, 1, 3, 8)


def kept_large_calls(sizes=LARGE_KEPT_SIZES, kept_for=LARGE_KEPT_FOR, budget: float = 2.0) -> list[dict]:
    """The default ``Solver``'s full kinematics at each size, each result dropped or kept for ``kept_for`` calls
    (a ``collections.deque`` of that length), beside the loop alone: nanoseconds a value and minor page faults
    a call, medians of interleaved rounds (:func:`best_of_turns`).  A solver for each way (each keeps its own
    blocks); each deque filled before the clock starts."""
    from benchmarks.compiled_loops import loop_alone
    from symlink.mechanism.catalog import fourbar
    from symlink.numeric.solver import Solver
    found = []
    for n in sizes:
        values = dict(theta=numpy.linspace(0.0, 2 * math.pi, n), **dict(zip("abcd", (numpy.full(n, v) for v in LENGTHS))),
                      branch=numpy.ones(n), thetadot=SPEED, thetaddot=ACCEL)
        solvers = {k: Solver(fourbar(), OUTPUTS) for k in kept_for}
        for solver in solvers.values():
            solver.wait_for_backend()
        calls = {"loop": loop_alone(solvers[kept_for[0]]._compiled, values, n)}
        for k, solver in solvers.items():
            if k:
                held: collections.deque = collections.deque(maxlen=k)
                calls[f"kept {k}"] = (lambda keep, solver: lambda: keep(solver(**values)))(held.append, solver)
                for _ in range(k + 2):
                    calls[f"kept {k}"]()
            else:
                calls["dropped"] = (lambda solver: lambda: solver(**values))(solver)
        timed = best_of_turns(calls, budget)
        found.append({"n": n, **{name: {"ns": 1e9 * seconds / n, "faults": faults}
                                 for name, (seconds, faults) in timed.items()}})
        del calls, solvers
        gc.collect()
    return found


def kept_large_report(rows: list[dict]) -> str:
    names = [k for k in rows[0] if k != "n"]
    lines = ["large calls, full kinematics: ns a value (minor page faults a call), medians of interleaved rounds",
             f"{'N':>8} " + " ".join(f"{m:>17}" for m in names) + " "
             + " ".join(f"{f'{m}/loop':>14}" for m in names if m != "loop") + " "
             + " ".join(f"{f'{m}/dropped':>15}" for m in names if m.startswith("kept"))]
    for row in rows:
        lines.append(f"{row['n']:>8.0e} " + " ".join(f"{row[m]['ns']:>8.2f} ({row[m]['faults']:>6.0f})" for m in names)
                     + " " + " ".join(f"{row[m]['ns'] / row['loop']['ns']:>14.2f}" for m in names if m != "loop")
                     + " " + " ".join(f"{row[m]['ns'] / row['dropped']['ns']:>15.2f}"
                                      for m in names if m.startswith("kept")))
    return "\n".join(lines)


def machine() -> str:
    """The CPU (its model name and whether it has AVX2 and AVX-512) and the load average now."""
    model, flags = "unknown CPU", set()
    try:
        with open("/proc/cpuinfo") as info:
            for line in info:
                key, _, value = line.partition(":")
                if key.strip() == "model name" and model == "unknown CPU":
                    model = value.strip()
                elif key.strip() == "flags" and not flags:
                    flags = set(value.split())
    except OSError:
        pass
    vectors = "AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags else "no AVX2"
    return f"{model}, {os.cpu_count()} logical cores, {vectors}; load average {' '.join(f'{v:.2f}' for v in os.getloadavg())}"


def report(rows: list[dict]) -> str:
    present = [m for m in METHODS if any(m in row for row in rows)]
    lines = []
    for kind in KINDS:
        lines.append(f"{kind}: ns a value (minor page faults a call)")
        lines.append(f"{'N':>8} " + " ".join(f"{m:>17}" for m in present)
                     + f" {'call out=/loop':>14} {'call/loop':>9} {'kept/loop':>9} {'out=/limit':>10} "
                       f"{'call/limit':>10} {'loop/limit':>10}")
        for row in (r for r in rows if r["kind"] == kind):
            cells = " ".join(f"{row[m]['ns']:>8.2f} ({row[m]['faults']:>6.0f})" if m in row else f"{'':>17}"
                             for m in present)
            loop, limit = row["loop"]["ns"], row["limit"]["ns"]
            lines.append(f"{row['n']:>8.0e} {cells} {row['call out=']['ns'] / loop:>14.2f} "
                         f"{row['call']['ns'] / loop:>9.2f} {row['call kept']['ns'] / loop:>9.2f} "
                         f"{row['call out=']['ns'] / limit:>10.2f} "
                         f"{row['call']['ns'] / limit:>10.2f} {loop / limit:>10.2f}")
    large = [r for r in rows if r["n"] >= 10**5]
    if large:
        out = max(r["call out="]["ns"] / r["loop"]["ns"] for r in large)
        fresh = max(r["call"]["ns"] / r["loop"]["ns"] for r in large)
        lines.append(f"at 10^5-10^6 values, worst over both kinds: call out=/loop {out:.2f} (target <= 1.2), "
                     f"call/loop {fresh:.2f} (target <= 1.5)")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--largest", type=float, default=1e6, help="largest N (a power of ten)")
    parser.add_argument("--budget", type=float, default=2.0, help="seconds of timing for each kind and N")
    options = parser.parse_args()
    sizes = [10**k for k in range(3, int(round(math.log10(options.largest))) + 1)]
    print(machine())
    print(report(measure(sizes, options.budget)))
    print(kept_report(kept_calls()))
    print(kept_large_report(kept_large_calls(tuple(n for n in sizes if n >= 10**4), budget=options.budget)))
    print(f"after: load average {' '.join(f'{v:.2f}' for v in os.getloadavg())}")


if __name__ == "__main__":
    main()
