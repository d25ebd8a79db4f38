"""Cold derivation (and compile) of a chain of k four-bars: seconds and ``sympy.diff`` calls against k (not a test).

Loop j's crank is loop j-1's rocker (the first is driven by theta); every loop is a four-bar
``a_j e^{i phi_(j-1)} + b_j e^{i beta_j} = d_j + c_j e^{i phi_j}``.  For k = 2, 4, 8 (``--k``), in
one process with the disk cache off: the straight-line program of every unknown, its rate and
its acceleration (what a full-kinematics solver derives), timed, with the number of
``sympy.diff`` calls made.  Printed: seconds, calls, and the growth exponent between the
smallest and largest k (seconds ~ k^p; target p <= 1.15).

With ``--compiled``: the compiled solver of those outputs made cold (:class:`symlink.numeric.compiled.CompiledSolver`:
derivation, the NumPy module, the C source, compiling it with the system compiler and loading it), timed
as a user waits for it (wall seconds), with the CPU seconds of this process and of the compilers it ran
(the machine may be shared: CPU seconds do not count the waiting), and the growth exponents of both
(target: at most 1.15, and the k = 16 solver ready in under 10 s).  Each library is built in a private
folder of this process (the disk cache is off), so nothing is reused between sizes.

    python -m benchmarks.cold_chain [--k 2 4 8] [--compiled]
"""
from __future__ import annotations

import argparse
import math
import os
import time


def chain(k: int):
    """A chain of ``k`` four-bars, each driven by the rocker of the one before."""
    from symlink.symbolic.linkage import Linkage
    from symlink.symbolic.loops import Loop
    from symlink.symbolic.vectors import Vector, coordinates, lengths
    theta, = coordinates("theta")
    loops, unknowns, driver = [], [], theta
    for j in range(1, k + 1):
        beta, phi = coordinates(f"beta{j} phi{j}")
        a, b, c, d = lengths(f"a{j} b{j} c{j} d{j}")
        closure = Loop(Vector(d, 0) + Vector(c, phi) - Vector(b, beta) - Vector(a, driver), name=f"L{j}")
        loops.append(closure)
        unknowns += [beta, phi]
        driver = phi
    return Linkage(f"chain{k}", loops, inputs=[theta], unknowns=unknowns)


def measure(k: int) -> dict[str, float]:
    import sympy
    from symlink.symbolic.vectors import acceleration, rate
    calls = [0]
    original = sympy.diff

    def counting(*args, **kwargs):
        calls[0] += 1
        return original(*args, **kwargs)
    sympy.diff = counting
    try:
        linkage = chain(k)
        outputs = [q.name for q in linkage.unknowns] + [rate(q).name for q in linkage.unknowns] \
            + [acceleration(q).name for q in linkage.unknowns]
        start = time.perf_counter()
        linkage.program(outputs)
        seconds = time.perf_counter() - start
    finally:
        sympy.diff = original
    return {"k": k, "seconds": seconds, "diff_calls": calls[0]}


def full_kinematics(linkage) -> list[str]:
    """The names of the unknowns, their rates and their accelerations."""
    from symlink.symbolic.vectors import acceleration, rate
    return [q.name for q in linkage.unknowns] + [rate(q).name for q in linkage.unknowns] \
        + [acceleration(q).name for q in linkage.unknowns]


def measure_compiled(k: int) -> dict[str, float]:
    """Wall and CPU seconds (this process, and the compilers it ran) until the cold compiled solver of chain k
    answers, and how many translation units its C was compiled in."""
    from symlink.codegen.c import translation_units
    from symlink.numeric.compiled import CompiledSolver
    linkage = chain(k)
    before, start = os.times(), time.perf_counter()
    solver = CompiledSolver(linkage, full_kinematics(linkage))
    wall, after = time.perf_counter() - start, os.times()
    return {"k": k, "wall": wall, "python": after.user + after.system - before.user - before.system,
            "compilers": after.children_user + after.children_system - before.children_user - before.children_system,
            "units": len(translation_units(solver.source))}


def exponent(rows: list[dict], key: str) -> float:
    """p in value ~ k^p between the smallest and the largest k."""
    first, last = rows[0], rows[-1]
    return math.log(last[key] / first[key]) / math.log(last["k"] / first["k"])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--k", type=int, nargs="+", default=[2, 4, 8])
    parser.add_argument("--compiled", action="store_true", help="time the cold compiled solver (with its compile)")
    options = parser.parse_args()
    os.environ["SYMLINK_CACHE"] = ""
    if options.compiled:
        from symlink.numeric.compiled import CompiledSolver
        CompiledSolver(chain(1), ["phi1"])  # SymPy's first derivation and the compiler probe: not counted
        rows = [measure_compiled(k) for k in options.k]
        for row in rows:
            print(f"k = {row['k']:>2}: ready in {row['wall']:6.2f} s; CPU {row['python']:6.2f} s Python + "
                  f"{row['compilers']:6.2f} s compilers ({row['units']} translation units)")
        for row in rows:
            row["cpu"] = row["python"] + row["compilers"]
        print(f"wall ~ k^{exponent(rows, 'wall'):.2f}, CPU ~ k^{exponent(rows, 'cpu'):.2f}, compilers' CPU ~ "
              f"k^{exponent(rows, 'compilers'):.2f} (target <= 1.15); {os.cpu_count()} processors, "
              f"load {os.getloadavg()[0]:.2f}")
        return
    measure(1)  # SymPy's first derivation warms its caches: not counted
    rows = [measure(k) for k in options.k]
    for row in rows:
        print(f"k = {row['k']:>2}: {row['seconds']:7.2f} s, {row['diff_calls']:>6} sympy.diff calls")
    first, last = rows[0], rows[-1]
    power = math.log(last["seconds"] / first["seconds"]) / math.log(last["k"] / first["k"])
    calls = math.log(last["diff_calls"] / first["diff_calls"]) / math.log(last["k"] / first["k"])
    print(f"seconds ~ k^{power:.2f}, diff calls ~ k^{calls:.2f} (target <= 1.15); load {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
