"""Cost that grows with the work: derive, compile and solve a chain of n four-bars, n = 1, 2, 4, 8, 16 (not a test).

The chain is :func:`benchmarks.cold_chain.chain` (loop j's crank is loop j-1's rocker): 2 n unknowns, their
rates and accelerations.  For each n, in one process with the disk cache off (nothing reused between sizes):

* derive: the straight-line program of every unknown, rate and acceleration (SymPy), seconds;
* compile: the compiled solver of those outputs made cold (derivation, NumPy module, C source, the system
  compiler, loading), wall seconds, less the derivation measured just before;
* solve: a call of the NumPy solver and of the compiled one at ``--values`` crank angles (best of three), seconds.

Printed: a row per n, and for each cost the exponent p of a least-squares fit ``seconds ~ n^p`` over all n (the
slope of log seconds against log n), with the processor model and the load.

    python -m benchmarks.growth [--n 1 2 4 8 16] [--values 100000] [--no-compiled]
"""
from __future__ import annotations

import argparse
import math
import os
import time

from benchmarks.cold_chain import chain, full_kinematics


def processor() -> str:
    """The processor model from /proc/cpuinfo (Linux), else what the platform module says."""
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="replace") as info:
            for line in info:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    import platform
    return platform.processor() or "unknown processor"


def values(n: int) -> dict[str, float]:
    """Every loop the same four-bar (crank 1, coupler 3, rocker 2.5, ground 3.2): a chain that assembles."""
    return {name: value for j in range(1, n + 1)
            for name, value in ((f"a{j}", 1.0), (f"b{j}", 3.0), (f"c{j}", 2.5), (f"d{j}", 3.2))}


def best_call(solver, arguments: dict, repeats: int = 3) -> float:
    best = math.inf
    for _ in range(repeats):
        start = time.perf_counter()
        solver(**arguments)
        best = min(best, time.perf_counter() - start)
    return best


def measure(n: int, count: int, compiled: bool) -> dict[str, float]:
    from symlink.numeric.solver import Solver
    outputs = full_kinematics(chain(n))
    linkage = chain(n)
    start = time.perf_counter()
    linkage.program(outputs)
    row = {"n": n, "derive": time.perf_counter() - start}
    arguments = {"theta": numpy_linspace(count), "thetadot": 1.0, "thetaddot": 0.0, **values(n),
                 **{f"branch{j}" if n > 1 else "branch": 1 for j in range(1, n + 1)}}
    solver = Solver(linkage, outputs, backend="numpy")
    names = set(solver.arguments)
    arguments = {k: v for k, v in arguments.items() if k in names}
    arguments.update({name: 1 for name in solver.arguments if name.startswith("branch") and name not in arguments})
    row["solve_numpy"] = best_call(solver, arguments)
    if compiled:
        from symlink.numeric.compiled import CompiledSolver
        fresh = chain(n)
        start = time.perf_counter()
        fresh.program(outputs)
        derive_again = time.perf_counter() - start
        start = time.perf_counter()
        built = CompiledSolver(fresh, outputs)
        row["compile"] = time.perf_counter() - start
        row["derive_again"] = derive_again
        row["solve_compiled"] = best_call(built, arguments)
    return row


def numpy_linspace(count: int):
    import numpy
    return numpy.linspace(-math.pi, math.pi, count)


def fitted_exponent(rows: list[dict], key: str) -> float:
    """The least-squares slope of log(value) against log(n)."""
    xs = [math.log(row["n"]) for row in rows]
    ys = [math.log(row[key]) for row in rows]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, nargs="+", default=[1, 2, 4, 8, 16])
    parser.add_argument("--values", type=int, default=100_000, help="crank angles a solve call takes")
    parser.add_argument("--no-compiled", action="store_true", help="skip the compiled solver (no C compiler)")
    options = parser.parse_args()
    os.environ["SYMLINK_CACHE"] = ""  # nothing reused between sizes
    chain(1).program(full_kinematics(chain(1)))  # SymPy's first derivation warms its caches: not counted
    rows = [measure(n, options.values, not options.no_compiled) for n in options.n]
    for row in rows:
        text = (f"n = {row['n']:>2}: derive {row['derive']:7.2f} s; solve {options.values:,} values "
                f"{row['solve_numpy']:7.3f} s NumPy")
        if "compile" in row:
            text += (f", {row['solve_compiled']:7.3f} s compiled; compiled solver ready in {row['compile']:7.2f} s "
                     f"(after a derivation of {row['derive_again']:.2f} s)")
        print(text)
    keys = ["derive", "solve_numpy"] + (["compile", "solve_compiled"] if "compile" in rows[0] else [])
    print("fitted exponents (seconds ~ n^p): " + ", ".join(f"{key} {fitted_exponent(rows, key):.2f}" for key in keys))
    print(f"{processor()}; {os.cpu_count()} processors, load {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
