"""Cold derivation of a chain of k four-bars: seconds and ``sympy.diff`` calls against k (not a test).

Loop j's crank is loop j-1's rocker (the first is driven by theta); every loop is a four-bar
``a_j e^{i phi_(j-1)} + b_j e^{i beta_j} = d_j + c_j e^{i phi_j}``.  For k = 2, 4, 8 (``--k``), in
one process with the disk cache off: the straight-line program of every unknown, its rate and
its acceleration (what a full-kinematics solver derives), timed, with the number of
``sympy.diff`` calls made.  Printed: seconds, calls, and the growth exponent between the
smallest and largest k (seconds ~ k^p; target p <= 1.15).

    python -m benchmarks.cold_chain [--k 2 4 8]
"""
from __future__ import annotations

import argparse
import math
import os
import time


def chain(k: int):
    """A chain of ``k`` four-bars, each driven by the rocker of the one before."""
    from symlink.linkage import Linkage
    from symlink.loops import Loop
    from symlink.vectors import Vector, coordinates, lengths
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
    from symlink.vectors import acceleration, rate
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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--k", type=int, nargs="+", default=[2, 4, 8])
    options = parser.parse_args()
    os.environ["SYMLINK_CACHE"] = ""
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
