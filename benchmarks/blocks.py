"""Large calls of the generated NumPy module: time per value against N, against a numba loop, and peak memory.

The four-bar's full kinematics (coupler and rocker angles, speeds and
accelerations) for N crank angles, one set of lengths, N = 10^3 ... 10^7:

* ``symlink``: the generated NumPy function, called once for all N values
  (``check=False``, as a hot loop calls it);
* ``numba``: a hand-written numba loop of the same formulas (the same
  common subexpressions, in the same order), compiled before timing.

Printed: microseconds per value of each, their ratio (target: symlink at
most 1.3x numba), symlink's time per value against its time at 10^5 (target:
at most 1.2x), and the peak memory tracemalloc sees during one call beyond the
outputs, in bytes per block and against the outputs' size.

    python benchmarks/blocks.py                # N = 10^3 ... 10^7
    python benchmarks/blocks.py --largest 1e6
"""
from __future__ import annotations

import argparse
import math
import time
import tracemalloc

import numpy

OUTPUTS = ["coupler", "rocker", "coupler_speed", "rocker_speed", "coupler_accel", "rocker_accel"]
LENGTHS = (20.0, 66.0, 56.0, 80.0)
SPEED, ACCEL = 10.5, 2.0


def symlink_function():
    from symlink.numeric.cache import generated_code
    from symlink.mechanism.catalog import fourbar
    return generated_code(fourbar(), OUTPUTS).function


def numba_function():
    """A numba loop of the generated module's formulas (four-bar, full kinematics), compiled for float64."""
    import numba

    @numba.njit(cache=False, fastmath=False, error_model="numpy")
    def kinematics(theta, a, b, c, d, branch, thetadot, thetaddot, out):
        tolerance = 1e-14
        size = 2.0 ** math.floor(math.log(0.25 * a + 0.25 * b + 0.25 * c + 0.25 * d) / math.log(2.0))
        inverse = 1.0 / size
        rho1, rho2, rho3, rho4 = inverse * d, a * inverse, b * inverse, c * inverse
        sum34, difference34, product34 = rho3 + rho4, rho3 - rho4, rho3 * rho4
        for i in range(theta.shape[0]):
            t = theta[i]
            wx = -rho1 + rho2 * math.cos(t)
            wy = rho2 * math.sin(t)
            x = wx * wx + wy * wy
            w = math.sqrt(max(x, 0.0)) if x >= tolerance * 2.2250738585072e-294 else math.nan
            s2 = sum34 + w
            ww = w * w
            c6 = sum34 * difference34 + ww
            c10 = -sum34 * difference34 + ww
            y = s2 * (sum34 - w) * (difference34 + w) * (-rho3 + rho4 + w)
            scale = 8.0 * product34 * w * (s2 + rho1 + rho2)
            delta = math.sqrt(max(y, 0.0)) if y >= -tolerance * scale else math.nan
            c7 = delta * branch
            c8, c9 = wx * c7, wy * c7
            c14 = 2.0 * product34 / (delta * branch)
            c15, c19 = c14 / b, c14 / c
            beta = math.atan2(-wy * c6 - c8, -wx * c6 + c9)
            c17 = beta - t
            c18 = math.sin(c17)
            phi = math.atan2(wy * c10 - c8, wx * c10 + c9)
            c12 = -t + phi
            c13 = math.sin(c12)
            c25 = math.cos(beta - phi)
            c16 = a * thetadot
            betadot = -c13 * c15 * c16
            phidot = -c16 * c18 * c19
            c20 = c * (phidot * phidot)
            c21, c22 = a * thetaddot, thetadot * thetadot
            out[0, i] = beta
            out[1, i] = phi
            out[2, i] = betadot
            out[3, i] = phidot
            out[4, i] = c15 * (a * c22 * math.cos(c12) + b * (betadot * betadot) * c25 - c13 * c21 - c20)
            out[5, i] = c19 * (a * c22 * math.cos(c17) + b * (betadot * betadot) - c18 * c21 - c20 * c25)

    def call(theta):
        out = numpy.empty((6, theta.shape[0]))
        kinematics(theta, *LENGTHS, 1.0, SPEED, ACCEL, out)
        return out
    call(numpy.linspace(0.0, 1.0, 8))  # compiled here, not while timed
    return call


def best_time(call, budget: float = 1.0, most: int = 50) -> float:
    """The fastest of repeated calls in CPU seconds (at least 2, within about ``budget`` seconds of wall time)."""
    times = []
    start = time.perf_counter()
    while len(times) < 2 or (time.perf_counter() - start < budget and len(times) < most):
        begin = time.thread_time()  # CPU time of this thread: other programs on the machine do not count
        call()
        times.append(time.thread_time() - begin)
    return min(times)


def peak_extra_bytes(call, output_bytes: int) -> int:
    """Peak bytes tracemalloc sees allocated during ``call()`` beyond the ``output_bytes`` of its results."""
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        base = tracemalloc.get_traced_memory()[0]
        result = call()
        peak = tracemalloc.get_traced_memory()[1] - base
    finally:
        tracemalloc.stop()
    del result
    return peak - output_bytes


def measure(sizes, memory: bool = True) -> list[dict]:
    function = symlink_function()
    hand = numba_function()
    rows = []
    for n in sizes:
        theta = numpy.linspace(0.0, 2 * math.pi, n)
        kwargs = dict(zip("abcd", LENGTHS), branch=1.0, thetadot=SPEED, thetaddot=ACCEL, check=False)
        generated = best_time(lambda: function(theta, **kwargs), budget=2.0 if n >= 10**6 else 1.0)
        loop = best_time(lambda: hand(theta), budget=2.0 if n >= 10**6 else 1.0)
        symlink_result = function(theta, **kwargs)
        numba_result = hand(theta)
        agree = max(float(numpy.nanmax(abs(symlink_result[name] - numba_result[k]))) for k, name in enumerate(OUTPUTS))
        row = {"n": n, "symlink_us": 1e6 * generated / n, "numba_us": 1e6 * loop / n, "max_difference": agree}
        if memory:
            output_bytes = n * 8 * len(OUTPUTS) + n  # the float outputs and the assembled mask
            row["extra_bytes"] = peak_extra_bytes(lambda: function(theta, **kwargs), output_bytes)
            row["output_bytes"] = output_bytes
        rows.append(row)
        del symlink_result, numba_result
    return rows


def report(rows: list[dict]) -> str:
    reference = next((r for r in rows if r["n"] == 10**5), rows[-1])
    lines = [f"{'N':>10} {'symlink us':>11} {'numba us':>9} {'ratio':>6} {'vs 1e5':>7} {'extra MB':>9} "
             f"{'extra/out':>9} {'max diff':>9}"]
    for r in rows:
        lines.append(f"{r['n']:>10.0e} {r['symlink_us']:>11.4f} {r['numba_us']:>9.4f} "
                     f"{r['symlink_us'] / r['numba_us']:>6.2f} {r['symlink_us'] / reference['symlink_us']:>7.2f} "
                     f"{r.get('extra_bytes', 0) / 1e6:>9.2f} {r.get('extra_bytes', 0) / r.get('output_bytes', 1):>9.2f} "
                     f"{r['max_difference']:>9.1e}")
    worst = max(r["symlink_us"] / r["numba_us"] for r in rows)
    flat = max(r["symlink_us"] / reference["symlink_us"] for r in rows if r["n"] >= reference["n"])
    lines.append(f"worst symlink/numba ratio {worst:.2f} (target <= 1.3); largest N against 1e5 {flat:.2f} "
                 f"(target <= 1.2)")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--largest", type=float, default=1e7, help="largest N (a power of ten)")
    parser.add_argument("--no-memory", action="store_true", help="skip the tracemalloc measurement")
    options = parser.parse_args()
    sizes = [10**k for k in range(3, int(round(math.log10(options.largest))) + 1)]
    print(report(measure(sizes, memory=not options.no_memory)))


if __name__ == "__main__":
    main()
