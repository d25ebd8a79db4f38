"""Whether the compiled loops stay vectorised as linkages grow: full kinematics against positions, in C.

For the four-bar, the Watt II six-bar and Jansen's leg (:mod:`symlink.catalog`),
the compiled solver (:class:`symlink.compiled.CompiledSolver`) of the
unknowns' angles (positions) and of the angles, their rates and their
accelerations (full kinematics), called on N = 10^5 crank angles, one set of
parameters.  Printed: nanoseconds per value of each and their ratio (target:
full kinematics at most 1.5x positions, as the four-bar's are).  A loop that
stops vectorising costs 5-6x instead (glibc's vector sin, cos and atan2 are
then no longer called).

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
        from symlink.catalog import jansen_parameters
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


def measure(n: int = 10**5) -> list[dict]:
    from symlink.catalog import fourbar, jansen, watt2
    from symlink.compiled import CompiledSolver
    rows = []
    theta = numpy.linspace(0.0, 2 * math.pi, n)
    for build in (fourbar, watt2, jansen):
        linkage = build()
        unknowns = [q.name for q in linkage.unknowns]
        full = unknowns + [f"{q}dot" for q in unknowns] + [f"{q}ddot" for q in unknowns]
        values = dict(parameters(linkage.name), theta=theta, thetadot=10.5, thetaddot=2.0)
        row = {"linkage": linkage.name, "unknowns": len(unknowns)}
        for label, outputs in (("positions", unknowns), ("full", full)):
            entry = CompiledSolver(linkage, outputs).function
            arguments = {k: v for k, v in values.items() if k in entry.arguments}
            result = entry(**arguments)
            row[f"{label}_assembled"] = float(numpy.mean(result["assembled"]))
            row[f"{label}_ns"] = 1e9 * cpu_time(lambda: entry(**arguments)) / n
        rows.append(row)
    return rows


def report(rows: list[dict]) -> str:
    lines = [f"{'linkage':>10} {'unknowns':>8} {'positions ns':>13} {'full ns':>8} {'full/positions':>15} {'assembled':>9}"]
    for r in rows:
        lines.append(f"{r['linkage']:>10} {r['unknowns']:>8} {r['positions_ns']:>13.1f} {r['full_ns']:>8.1f} "
                     f"{r['full_ns'] / r['positions_ns']:>15.2f} {r['full_assembled']:>9.2f}")
    worst = max(r["full_ns"] / r["positions_ns"] for r in rows)
    lines.append(f"worst full/positions {worst:.2f} (target <= 1.5)")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("-n", type=float, default=1e5, help="input values a call")
    options = parser.parse_args()
    print(report(measure(int(options.n))))


if __name__ == "__main__":
    main()
