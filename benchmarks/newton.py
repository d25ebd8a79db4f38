"""The compiled Newton fallback against the closed-form C and the NumPy Newton, per value, in one run.

Linkages without a loop-by-loop closed form (the Stephenson II six-bar) are solved by Newton's
method on the closure (:class:`symlink.numeric.solver.NumericSolver`): the compiled driver
(:mod:`symlink.codegen.newton_c`, ``backend="compiled"``) or the generated NumPy module
(``backend="numpy"``).  Each computes full kinematics (positions, rates, accelerations, points)
over one turn of the crank, continued value by value.  Timed, CPU time of this thread, best of
repeated calls, nanoseconds per value:

* ``newton-c loop``: the C sweep alone (``symlink_newton_sweep``, outputs allocated once);
* ``newton-c call``: a ``NumericSolver`` call as a user makes it (checks, sweep, points, results);
* ``numpy call``: the same call on the NumPy backend (on fewer values: it is slow);
* ``closed-form C loop``: the compiled closed-form solver's C loop (:mod:`benchmarks.compiled_loops`),
  full kinematics, of the Watt II six-bar (four unknowns, like Stephenson II) and of the four-bar.

Also the four-bar by Newton (``NumericSolver`` works on any linkage): the same linkage both ways.
Printed: each time and the ratios newton-c / closed-form C (target <= 20x) and numpy / newton-c, and
the Stephenson II's loop against the four-bar's closed-form loop (a six-bar against a four-bar).

    python -m benchmarks.newton [-n 36000]
"""
from __future__ import annotations

import argparse
import ctypes
import math
import os

import numpy

from benchmarks.compiled_loops import cpu_time, loop_alone, parameters

#: The Stephenson II example of the tests and docs (a crank that turns fully) and its assembly guess.
STEPHENSON2 = dict(a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1, alpha=0.9, delta=0.3)
STEPHENSON2_GUESS = dict(beta=0.96, mu=0.27, phi=1.43, eta=-0.16)
FOURBAR = dict(a=20.0, b=66.0, c=56.0, d=80.0)
FOURBAR_GUESS = dict(beta=0.3, phi=1.9)


def _sweep_alone(solver, values: dict, guess: dict):
    """A call of the compiled driver's C sweep alone on ``values``, into outputs allocated here, once."""
    compiled = solver._answering()
    facts = compiled.facts
    count = len(values["theta"])
    x = numpy.ascontiguousarray([numpy.broadcast_to(values[name], count) for name in facts["inputs"]], dtype=float)
    p = numpy.ascontiguousarray([values[name] for name in facts["parameters"]], dtype=float)
    start = numpy.ascontiguousarray([guess[name] for name in facts["unknowns"]], dtype=float)
    rates = numpy.full((len(facts["inputs"]), count), 10.5)
    accels = numpy.full((len(facts["inputs"]), count), 2.0)
    n = len(facts["unknowns"])
    q, qdot, qddot = (numpy.empty((n, count)) for _ in range(3))
    residual, report = numpy.empty(count), numpy.zeros(3 + 2 * len(facts["inputs"]))
    pointers = [a.ctypes.data for a in (x, p, start)] + [1] + [a.ctypes.data for a in (
        rates, accels, q, qdot, qddot, residual, report)]
    kept = (x, p, start, rates, accels, q, qdot, qddot, residual, report)

    def call():
        if compiled.sweep_entry(count, *pointers):
            raise ValueError("the benchmark's sweep did not solve")
        return kept
    return call


def _closed_form_loop(build, n: int) -> float:
    """ns a value of the closed-form compiled solver's C loop, full kinematics, over one turn."""
    from symlink.numeric.compiled import CompiledSolver
    linkage = build()
    unknowns = [q.name for q in linkage.unknowns]
    full = unknowns + [f"{q}dot" for q in unknowns] + [f"{q}ddot" for q in unknowns]
    entry = CompiledSolver(linkage, full).function
    values = dict(parameters(linkage.name), theta=numpy.linspace(0.0, 2 * math.pi, n), thetadot=10.5,
                  thetaddot=2.0)
    arguments = {k: v for k, v in values.items() if k in entry.arguments}
    return 1e9 * cpu_time(loop_alone(entry, arguments, n)) / n


def measure(n: int = 36000, numpy_n: int = 3600) -> list[dict]:
    """One row a linkage: ns a value of each way, and the closed-form C loop it is compared with."""
    from symlink.mechanism.catalog import fourbar, stephenson2, watt2
    from symlink.numeric.solver import NumericSolver
    rows = []
    for build, dimensions, guess, closed in ((stephenson2, STEPHENSON2, STEPHENSON2_GUESS, watt2),
                                             (fourbar, FOURBAR, FOURBAR_GUESS, fourbar)):
        linkage = build()
        compiled = NumericSolver(linkage, backend="compiled")
        plain = NumericSolver(linkage, backend="numpy")
        if compiled.backend != "compiled":
            raise RuntimeError("no compiled backend here (no C compiler?)")
        theta = numpy.linspace(0.0, 2 * math.pi, n)
        values = dict(dimensions, theta=theta, thetadot=10.5, thetaddot=2.0)
        few = dict(values, theta=numpy.linspace(0.0, 2 * math.pi, numpy_n))
        ours, theirs = compiled(guess=guess, **few), plain(guess=guess, **few)
        agreement = max(float(numpy.max(numpy.abs(ours[q.name] - theirs[q.name]))) for q in linkage.unknowns)
        rows.append({
            "linkage": linkage.name, "n": n, "numpy_n": numpy_n, "agreement": agreement,
            "loop_ns": 1e9 * cpu_time(_sweep_alone(compiled, values, guess)) / n,
            "call_ns": 1e9 * cpu_time(lambda: compiled(guess=guess, **values)) / n,
            "numpy_ns": 1e9 * cpu_time(lambda: plain(guess=guess, **few), budget=2.0) / numpy_n,
            "closed": closed().name, "closed_ns": _closed_form_loop(closed, n),
        })
    return rows


def report(rows: list[dict]) -> str:
    lines = [f"{'linkage':>12} {'N':>6} | {'newton-c loop':>13} {'call':>7} | {'numpy call':>10} "
             f"| {'closed-form C loop':>24} | {'loop/closed':>11} {'call/closed':>11} {'numpy/call':>10} "
             f"| {'max |C - NumPy|':>15}"]
    for r in rows:
        lines.append(f"{r['linkage']:>12} {r['n']:>6} | {r['loop_ns']:>13.0f} {r['call_ns']:>7.0f} | "
                     f"{r['numpy_ns']:>10.0f} | {r['closed']:>15} {r['closed_ns']:>8.1f} | "
                     f"{r['loop_ns'] / r['closed_ns']:>10.1f}x {r['call_ns'] / r['closed_ns']:>10.1f}x "
                     f"{r['numpy_ns'] / r['call_ns']:>9.1f}x | {r['agreement']:>15.2g}")
    by_name = {r["linkage"]: r for r in rows}
    if "stephenson2" in by_name and "fourbar" in by_name:
        six, four = by_name["stephenson2"], by_name["fourbar"]
        lines.append(f"Stephenson II newton-c loop / four-bar closed-form C loop: "
                     f"{six['loop_ns'] / four['closed_ns']:.1f}x (a six-bar against a four-bar)")
    lines.append(f"ns per value, full kinematics (CPU time, best of repeats; NumPy on {rows[0]['numpy_n']} values); "
                 f"target: newton-c within 20x the closed-form C; load {os.getloadavg()[0]:.2f}")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("-n", type=float, default=36000, help="input values a call (default 36000: 0.01 deg steps)")
    options = parser.parse_args()
    print(report(measure(int(options.n))))


if __name__ == "__main__":
    main()
