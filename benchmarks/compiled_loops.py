"""Whether the compiled loops stay vectorised as linkages grow: full kinematics against positions, in C.

For the four-bar, the Watt II six-bar and Jansen's leg (:mod:`symlink.mechanism.catalog`),
the compiled solver (:class:`symlink.numeric.compiled.CompiledSolver`) of the
unknowns' angles (positions) and of the angles, their rates and their
accelerations (full kinematics), on N = 10^4 and 10^5 crank angles (the
outputs of the larger N no longer fit in the cache), one set of parameters,
CPU time of this thread, best of repeated calls:

* ``loop``: the C loop function alone, writing into output arrays allocated
  once beforehand (what vectorisation decides);
* ``in cache``: the same N evaluations, in chunks of 10^4 written into the
  same 10^4-long outputs, which stay in the cache (at N = 10^4, the loop
  itself): the loop without the traffic of its outputs to memory;
* ``stores``: writing the outputs' bytes alone (NumPy ``fill`` of the
  arrays the loop writes), full kinematics less positions: what the extra
  outputs of full kinematics cost to store, whatever the arithmetic;
* ``call``: a call of the compiled function as a user makes it, new output
  arrays each call (at this size, writing fresh pages costs about as much as
  the arithmetic, and full kinematics write three times as many outputs).

Printed: nanoseconds per value of each and the ratio full/positions (target:
the loop's at most 1.5 for every linkage).  A loop that stops vectorising
costs 5-6x instead (glibc's vector sin, cos and atan2 are then no longer
called).

    python -m benchmarks.compiled_loops
"""
from __future__ import annotations

import argparse
import math
import time

import numpy

PARAMETERS = {
    "fourbar": dict(a=20.0, b=66.0, c=56.0, d=80.0),
    "watt2": dict(a=20.0, b=66.0, c=56.0, d=80.0, e=50.0, f=60.0, g=70.0, alpha=0.3, gx=120.0, gy=10.0),
}


def parameters(name: str) -> dict[str, float]:
    if name == "jansen":
        from symlink.mechanism.catalog import jansen_parameters
        return jansen_parameters()
    return PARAMETERS[name]


def cpu_time(call, budget: float = 1.0) -> float:
    """The fastest of repeated calls in CPU seconds of this thread (at least 3)."""
    times = []
    end = time.perf_counter() + budget
    while len(times) < 3 or time.perf_counter() < end:
        start = time.thread_time()
        call()
        times.append(time.thread_time() - start)
    return min(times)


def _loop(entry, arguments: dict, n: int, outputs_length: int):
    """Calls of ``entry``'s C loop over ``n`` values, in chunks of ``outputs_length`` into one chunk's outputs."""
    arrays = [numpy.ascontiguousarray(arguments[a] if a in arguments else entry.defaults[a], dtype=numpy.float64)
              for a in entry.arguments]
    outputs = [numpy.empty(outputs_length, dtype=numpy.uint8 if flag else numpy.float64) for flag in entry.flags]
    outputs.append(numpy.empty(outputs_length, dtype=numpy.uint8))
    pointers = [o.ctypes.data for o in outputs]
    chunks = []
    for start in range(0, n, outputs_length):
        slots = [value for array in arrays for value in (
            (array.ctypes.data, 0) if array.size == 1 else (array.ctypes.data + array.itemsize * start, 1))]
        chunks.append((min(outputs_length, n - start), slots))
    kept = arrays + outputs  # alive as long as the calls that use their pointers

    def call():
        for count, slots in chunks:
            entry.entry(count, *slots, *pointers)
        return kept
    return call, outputs


def loop_alone(entry, arguments: dict, n: int):
    """A call of ``entry``'s C loop function on ``arguments`` into outputs allocated here, once."""
    return _loop(entry, arguments, n, n)[0]


def loop_in_cache(entry, arguments: dict, n: int, chunk: int = 10**4):
    """The same ``n`` evaluations in chunks of ``chunk`` values, each written into the same ``chunk``-long outputs."""
    return _loop(entry, arguments, n, min(chunk, n))[0]


def stores_alone(entry, arguments: dict, n: int):
    """Writing every byte of the loop's ``n``-long outputs, and nothing else."""
    outputs = _loop(entry, arguments, n, n)[1]
    return lambda: [o.fill(1) for o in outputs]


def measure(n: int = 10**5) -> list[dict]:
    from symlink.mechanism.catalog import fourbar, jansen, watt2
    from symlink.numeric.compiled import CompiledSolver
    rows = []
    theta = numpy.linspace(0.0, 2 * math.pi, n)
    for build in (fourbar, watt2, jansen):
        linkage = build()
        unknowns = [q.name for q in linkage.unknowns]
        full = unknowns + [f"{q}dot" for q in unknowns] + [f"{q}ddot" for q in unknowns]
        values = dict(parameters(linkage.name), theta=theta, thetadot=10.5, thetaddot=2.0)
        row = {"linkage": linkage.name, "unknowns": len(unknowns), "n": n}
        for label, outputs in (("positions", unknowns), ("full", full)):
            entry = CompiledSolver(linkage, outputs).function
            arguments = {k: v for k, v in values.items() if k in entry.arguments}
            result = entry(**arguments)
            row[f"{label}_assembled"] = float(numpy.mean(result["assembled"]))
            row[f"{label}_call_ns"] = 1e9 * cpu_time(lambda: entry(**arguments)) / n
            row[f"{label}_loop_ns"] = 1e9 * cpu_time(loop_alone(entry, arguments, n)) / n
            row[f"{label}_cached_ns"] = 1e9 * cpu_time(loop_in_cache(entry, arguments, n)) / n
            row[f"{label}_stores_ns"] = 1e9 * cpu_time(stores_alone(entry, arguments, n)) / n
        rows.append(row)
    return rows


def report(rows: list[dict]) -> str:
    lines = [f"{'linkage':>10} {'unknowns':>8} {'N':>7} | {'loop: positions':>15} {'full':>6} {'full/pos':>8} | "
             f"{'in cache: positions':>19} {'full':>6} {'full/pos':>8} | {'stores: full-pos':>16} | "
             f"{'call: positions':>15} {'full':>6} {'full/pos':>8} | {'assembled':>9}"]
    for r in rows:
        loop = r["full_loop_ns"] / r["positions_loop_ns"]
        cached = r["full_cached_ns"] / r["positions_cached_ns"]
        stores = r["full_stores_ns"] - r["positions_stores_ns"]
        call = r["full_call_ns"] / r["positions_call_ns"]
        lines.append(f"{r['linkage']:>10} {r['unknowns']:>8} {r['n']:>7} | {r['positions_loop_ns']:>15.1f} "
                     f"{r['full_loop_ns']:>6.1f} {loop:>8.2f} | {r['positions_cached_ns']:>19.1f} "
                     f"{r['full_cached_ns']:>6.1f} {cached:>8.2f} | {stores:>16.1f} | "
                     f"{r['positions_call_ns']:>15.1f} {r['full_call_ns']:>6.1f} {call:>8.2f} | "
                     f"{r['full_assembled']:>9.2f}")
    worst = max(r["full_loop_ns"] / r["positions_loop_ns"] for r in rows)
    lines.append(f"ns per value; worst loop full/positions {worst:.2f} (target <= 1.5)")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("-n", type=float, nargs="+", default=[1e4, 1e5], help="input values a call (one or more)")
    options = parser.parse_args()
    print(report([row for n in options.n for row in measure(int(n))]))


if __name__ == "__main__":
    main()
