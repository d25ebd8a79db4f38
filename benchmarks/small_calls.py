"""Small calls: microseconds a call at 1 to 1000 input values, through every way symlink is called.

Full kinematics of the four-bar (coupler and rocker angles, speeds and
accelerations) and its positions alone, one set of lengths, N crank angles:

* ``module``: the generated NumPy function (``check=True``, as a user calls it);
* ``module-nocheck``: the same with ``check=False`` (a hot loop);
* ``Solver``: :class:`symlink.numeric.solver.Solver` with ``backend="numpy"`` (units, memory and argument checks, a
  Results table);
* ``Solver-default``: a ``Solver`` as a user makes it (compiled where a C compiler works);
* ``compiled-entry``: the compiled C loop through its ctypes entry (``CompiledSolver.function``);
* ``compiled``: :class:`symlink.numeric.compiled.CompiledSolver`, called as a ``Solver`` is;
* ``compiled-python``: the same with the small-call extension turned off (the Python fast
  path of :class:`symlink.numeric.compiled_library.CompiledFunction`, as where the extension cannot be built);
* ``compiled-new-lengths``: the same, each call with new length objects (other values, as an
  optimiser's steps: an argument that is the very object of the call before is not read again);
* ``compiled-kept``: the same, each result kept until four calls later (a caller comparing a
  call with the ones before): its output block is not reused while it is held, but one of the
  blocks kept before is (:data:`symlink.numeric.compiled_library.KEPT_OUTPUTS`);
* ``Solver-kept``: the default ``Solver``, each result kept until four calls later;
* ``Solver-kept-all``: the default ``Solver``, every result kept for twice as many calls as the
  most blocks kept for reuse (:data:`symlink.numeric.compiled_library.KEPT_OUTPUTS_MOST`): a new
  block each call, the cost of new memory;
* ``numba``: the hand-written numba loop of :mod:`benchmarks.numba_loops` (the same formulas
  and exactly the generated code's transcendental calls a value: cos and sin of the crank, two
  atan2, one square root; :mod:`tests.test_bench` counts them), called as a user's numba
  function is: the lengths and branch as arrays made once, a new (6, N) output array a call.
  (Before issue 33 this baseline was :func:`benchmarks.blocks.numba_function`, which also
  calls sin and cos of the solved angles, five more transcendental calls a value than
  symlink's code makes.)

Targets: a compiled call with 10 values at most 10 us; a generated solver
called with 20 values at most 20 us; the default ``Solver`` (compiled) within 2x
the numba call at 10 values (issue 23); a result kept four calls as cheap as a dropped
one (issue 33).  Printed last: the ratios to numba of the
default ``Solver``, of the compiled entry and of the compiled solver without the small-call
extension at 10 and 1000 values, from the table, then timed back to back with numba
(:func:`interleaved_ratios`, steadier on a busy machine).

Times are CPU seconds of this thread (``time.thread_time``), so that a shared,
busy machine (other processes taking the processor between two calls) does not
inflate them; ``--wall`` times wall-clock seconds instead.

    python -m benchmarks.small_calls
"""
from __future__ import annotations

import argparse
import collections
import itertools
import math
import statistics
import time

import numpy

from benchmarks.blocks import LENGTHS, OUTPUTS, SPEED, ACCEL

POSITIONS = ["coupler", "rocker"]
SIZES = (1, 10, 20, 100, 1000)


#: The clock of :func:`per_call`: CPU time of this thread (``--wall``: ``time.perf_counter``).
CLOCK = [time.thread_time]


def per_call(call, budget: float = 0.3) -> tuple[float, float]:
    """Microseconds of one call: the best and the median mean of batches of calls, within about ``budget`` seconds."""
    clock = CLOCK[0]
    call()
    batch = 1
    while True:  # a batch lasting about a millisecond
        start = clock()
        for _ in range(batch):
            call()
        if clock() - start > 1e-3:
            break
        batch *= 2
    means: list[float] = []
    end = time.perf_counter() + budget
    while time.perf_counter() < end or len(means) < 5:
        start = clock()
        for _ in range(batch):
            call()
        means.append((clock() - start) / batch)
    return 1e6 * min(means), 1e6 * statistics.median(means)


def numba_baseline():
    """The numba call of full kinematics (:mod:`benchmarks.numba_loops`' ``everything``, exactly symlink's
    transcendental calls), as a function of the crank angles: lengths and branch as arrays made once for
    each N, a new (6, N) output array a call, its rows handed to the loop inside numba."""
    import numba
    from benchmarks.numba_loops import numba_kernels
    from symlink.symbolic.position import TOLERANCE
    _, everything = numba_kernels(numba, TOLERANCE)

    @numba.njit(cache=False, fastmath=False)
    def into(theta, a, b, c, d, branch, speed, accel, out):
        everything(theta, a, b, c, d, branch, speed, accel, out[0], out[1], out[2], out[3], out[4], out[5])

    arrays: dict[int, list] = {}

    def call(theta):
        n = theta.shape[0]
        if n not in arrays:
            arrays[n] = [numpy.full(n, value) for value in LENGTHS] + [numpy.ones(n)]
        a, b, c, d, branch = arrays[n]
        out = numpy.empty((6, n))
        into(theta, a, b, c, d, branch, SPEED, ACCEL, out)
        return out
    call(numpy.linspace(0.0, 1.0, 8))  # compiled here, not while timed
    return call


def methods(outputs: list[str]) -> dict:
    from symlink.mechanism.catalog import fourbar
    from symlink.numeric import compiled_library
    from symlink.numeric.compiled import CompiledSolver
    from symlink.numeric.solver import Solver
    linkage = fourbar()
    solver = Solver(linkage, outputs, backend="numpy")
    default = Solver(linkage, outputs)  # the default backend: compiled where a C compiler works
    default.wait_for_backend()
    compiled = CompiledSolver(linkage, outputs)
    python_path = CompiledSolver(linkage, outputs)
    python_path.function._plan = None  # the small-call extension off: the Python fast path
    rates = {"thetadot": SPEED, "thetaddot": ACCEL} if len(outputs) > 2 else {}
    lengths = dict(zip("abcd", LENGTHS))
    kept: collections.deque = collections.deque(maxlen=4)
    solver_kept: collections.deque = collections.deque(maxlen=4)
    # more than are ever kept for reuse: a new block a call
    kept_all: collections.deque = collections.deque(maxlen=2 * compiled_library.KEPT_OUTPUTS_MOST)
    steps = itertools.cycle([{k: v * (1.0 + 1e-9 * step) for k, v in lengths.items()} for step in range(1000)])
    found = {
        "module": lambda theta: solver.function(theta, **lengths, branch=1, **rates),
        "module-nocheck": lambda theta: solver.function(theta, **lengths, branch=1, **rates, check=False),
        "Solver": lambda theta: solver(theta=theta, **lengths, branch=1, **rates),
        "Solver-default": lambda theta: default(theta=theta, **lengths, branch=1, **rates),
        "compiled-entry": lambda theta: compiled.function(theta=theta, **lengths, branch=1, **rates),
        "compiled": lambda theta: compiled(theta=theta, **lengths, branch=1, **rates),
        "compiled-python": lambda theta: python_path(theta=theta, **lengths, branch=1, **rates),
        "compiled-new-lengths": lambda theta: compiled(theta=theta, **next(steps), branch=1, **rates),
        "compiled-kept": lambda theta: kept.append(compiled(theta=theta, **lengths, branch=1, **rates)),
        "Solver-kept": lambda theta: solver_kept.append(default(theta=theta, **lengths, branch=1, **rates)),
        "Solver-kept-all": lambda theta: kept_all.append(default(theta=theta, **lengths, branch=1, **rates)),
    }
    if len(outputs) > 2:
        try:
            found["numba"] = numba_baseline()
        except ImportError:  # numba is optional (the bench extra): no ratios then
            pass
    return found


def measure(sizes=SIZES) -> dict[str, dict[str, dict[int, tuple[float, float]]]]:
    table: dict = {}
    for label, outputs in (("full kinematics", OUTPUTS), ("positions", POSITIONS)):
        table[label] = {}
        for name, call in methods(outputs).items():
            table[label][name] = {}
            for n in sizes:
                theta = numpy.linspace(0.0, 2 * math.pi, n)
                table[label][name][n] = per_call(lambda: call(theta))
    return table


def report(table) -> str:
    lines = []
    for label, rows in table.items():
        sizes = list(next(iter(rows.values())))
        lines.append(f"{label}: us a call (best mean of batches)")
        lines.append(f"{'method':>20} " + " ".join(f"{f'N={n}':>9}" for n in sizes))
        for name, row in rows.items():
            lines.append(f"{name:>20} " + " ".join(f"{row[n][0]:>9.1f}" for n in sizes))
    full = table["full kinematics"]

    def both(name: str, n: int) -> str:
        return f"{full[name][n][0]:.1f} (median {full[name][n][1]:.1f}) us"

    lines.append(f"full kinematics, best and median batch: compiled-entry at N=10: {both('compiled-entry', 10)}, "
                 f"compiled at N=10: {both('compiled', 10)}, with new lengths: {both('compiled-new-lengths', 10)} "
                 f"(target <= 10); Solver at N=20: {both('Solver', 20)}, compiled at N=20: {both('compiled', 20)} "
                 "(target <= 20)")
    kept = [f"N={n}: kept {full['Solver-kept'][n][0] / full['Solver-default'][n][0]:.2f}x, "
            f"all kept {full['Solver-kept-all'][n][0] / full['Solver-default'][n][0]:.2f}x"
            for n in (10, 1000) if n in full["Solver-default"]]
    lines.append("full kinematics, the default Solver's result kept four calls (and every result kept) against "
                 "dropped: " + "; ".join(kept) + " (target: kept <= 1.1x)")
    if "numba" in full:
        ratios = [f"{name} {full[name][n][0] / full['numba'][n][0]:.2f}x at N={n}"
                  for name in ("Solver-default", "Solver-kept", "compiled-entry", "compiled-python") for n in (10, 1000)
                  if n in full[name]]
        lines.append("full kinematics against the numba call (best batches): " + ", ".join(ratios)
                     + " (target: Solver-default <= 2 at N=10)")
    return "\n".join(lines)


def interleaved_ratios(sizes=(10, 1000), rounds: int = 5) -> str:
    """Full kinematics against numba, each ratio's median over ``rounds`` rounds that time numba and then the
    method back to back (a busy machine slows both alike): the default ``Solver``, the compiled entry, and the
    compiled solver without the small-call extension (``compiled-python``)."""
    found = methods(OUTPUTS)
    if "numba" not in found:
        return "numba is not installed (pip install 'symlink-kinematics[bench]'): no ratios to it"
    parts = []
    for n in sizes:
        theta = numpy.linspace(0.0, 2 * math.pi, n)
        ratios: dict[str, list[float]] = {"Solver-default": [], "compiled-entry": [], "compiled-python": []}
        for _ in range(rounds):
            for name, found_ratios in ratios.items():
                base = per_call(lambda: found["numba"](theta), 0.1)[0]
                found_ratios.append(per_call(lambda: found[name](theta), 0.1)[0] / base)
        parts += [f"{name} {statistics.median(values):.2f}x at N={n} ({min(values):.2f}-{max(values):.2f})"
                  for name, values in ratios.items()]
    return "full kinematics against numba, timed back to back (median of rounds, range): " + ", ".join(parts)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--wall", action="store_true", help="wall-clock time instead of this thread's CPU time")
    if parser.parse_args().wall:
        CLOCK[0] = time.perf_counter
    print(report(measure()))
    print(interleaved_ratios())


if __name__ == "__main__":
    main()
