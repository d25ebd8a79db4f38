"""Path-synthesis benchmark: symlink's exact-Jacobian least squares against SciPy's differential evolution.

Random crank-rocker four-bars (placed anywhere, with a random coupler point) are sampled at
N crank angles (sorted, uniform over a turn); each method must find a four-bar through the
points from the points alone, with the crank angles given (timed) or not (untimed).  A
problem counts as solved when the largest distance from a target to the found coupler
point is below 1e-8 of the targets' size (bounding-box diagonal).  Both methods minimise
the same objective, the sum of squared normalised distances, with the same constraint
(every point assembled on one branch, no toggle).

Run from the repository root (not a test; SciPy needed)::

    python benchmarks/synthesis.py --problems 100 --de-problems 10

It prints one line per (method, timing, N): problems, success fraction, median and mean
seconds per problem, and the best and median final error.
"""
from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path

import numpy

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from symlink.analysis import grashof  # noqa: E402
from symlink.synthesis.path import coupler_point_gradient, fourbar_design, synthesize_path  # noqa: E402

SUCCESS = 1e-8
CASES = (("timed", 5), ("timed", 10), ("timed", 20), ("untimed", 10), ("untimed", 20))


def random_problem(rng: numpy.random.Generator, count: int):
    """A random crank-rocker's coupler points at ``count`` sorted random crank angles: (targets, theta, design)."""
    while True:
        a, b, c, d = rng.uniform(0.2, 1.0), *rng.uniform(0.5, 3.0, 3)
        if grashof(a, b, c, d).name == "crank-rocker":
            break
    design = fourbar_design(tuple(rng.normal(size=2)), rng.uniform(-math.pi, math.pi), (a, b, c, d),
                            (rng.uniform(-1, 2) * b, rng.uniform(-1, 1) * b), branch=int(rng.choice([-1, 1])))
    theta = numpy.sort(rng.uniform(-math.pi, math.pi, count))
    return design.points(theta), theta, design


def _size(targets: numpy.ndarray) -> float:
    return float(numpy.hypot(*(targets.max(axis=0) - targets.min(axis=0))))


def run_symlink(targets, theta, timed: bool, seed: int) -> tuple[float, float]:
    start = time.perf_counter()
    try:
        error = synthesize_path(targets, theta if timed else None, designs=1, seed=seed)[0].error
    except ValueError:
        error = math.inf
    return error, time.perf_counter() - start


def run_differential_evolution(targets, theta, timed: bool, seed: int, max_iterations: int) -> tuple[float, float]:
    """SciPy's differential evolution on the same objective; unassembled designs get a large value."""
    from scipy.optimize import differential_evolution
    gradient = coupler_point_gradient()
    size = _size(targets)
    low, high = targets.min(axis=0), targets.max(axis=0)
    count = len(targets)
    bounds = [(low[0] - size, high[0] + size), (low[1] - size, high[1] + size), (-math.pi, math.pi)]
    bounds += [(0.02 * size, 3 * size)] * 4 + [(-3 * size, 3 * size)] * 2
    if not timed:
        bounds += [(-math.pi, math.pi)] + [(0.0, 4 * math.pi / count)] * (count - 1)

    def angles(x):
        return theta if timed else x[9] + numpy.concatenate([[0.0], numpy.cumsum(x[10:])])

    def objective(x, branch):
        crank_angles = angles(x)
        if not timed and crank_angles[-1] - crank_angles[0] >= 2 * math.pi:
            return 1e6
        with numpy.errstate(all="ignore"):
            out = gradient(crank_angles, *x[:9], branch, check=False)
        if not numpy.all(out["assembled"]) or numpy.any(out["singular"]):
            return 1e6
        return float(numpy.sum(((out["P_x"] - targets[:, 0]) ** 2 + (out["P_y"] - targets[:, 1]) ** 2)) / size ** 2)

    start = time.perf_counter()
    best = math.inf
    for branch in (1, -1):
        fit = differential_evolution(objective, bounds, args=(branch,), seed=seed, maxiter=max_iterations,
                                     tol=1e-14, atol=0, polish=True, popsize=15)
        crank_angles = angles(fit.x)
        out = gradient(crank_angles, *fit.x[:9], branch, check=False)
        if numpy.all(out["assembled"]):
            distances = numpy.hypot(out["P_x"] - targets[:, 0], out["P_y"] - targets[:, 1])
            best = min(best, float(distances.max()) / size)
        if best < SUCCESS:
            break
    return best, time.perf_counter() - start


def summary(name: str, timing: str, count: int, results: list[tuple[float, float]]) -> str:
    errors = [e for e, _ in results]
    times = [t for _, t in results]
    solved = sum(e < SUCCESS for e in errors)
    finite = [e for e in errors if math.isfinite(e)]
    return (f"{name:22s} {timing:8s} N={count:<3d} problems {len(results):4d}  success {solved / len(results):6.1%}  "
            f"time/problem median {statistics.median(times):7.3f} s mean {statistics.fmean(times):7.3f} s  "
            f"error median {statistics.median(finite) if finite else math.inf:.2g}")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--problems", type=int, default=100, help="timed problems per N for symlink (default 100)")
    parser.add_argument("--untimed-problems", type=int, default=None,
                        help="untimed problems per N for symlink (default: --problems)")
    parser.add_argument("--de-problems", type=int, default=10, help="problems per case for differential evolution")
    parser.add_argument("--de-iterations", type=int, default=300, help="differential evolution generations")
    parser.add_argument("--seed", type=int, default=2024)
    parser.add_argument("--cases", default=",".join(f"{t}{n}" for t, n in CASES),
                        help="which cases, e.g. timed5,untimed10")
    args = parser.parse_args(argv)
    wanted = set(args.cases.split(","))
    for timing, count in CASES:
        if f"{timing}{count}" not in wanted:
            continue
        timed = timing == "timed"
        problems = args.problems if timed or args.untimed_problems is None else args.untimed_problems
        rng = numpy.random.default_rng(args.seed + count + (0 if timed else 1000))
        cases = [random_problem(rng, count) for _ in range(max(problems, args.de_problems))]
        ours = [run_symlink(t, th, timed, k) for k, (t, th, _) in enumerate(cases[:problems])]
        print(summary("symlink least_squares", timing, count, ours), flush=True)
        if args.de_problems:
            theirs = [run_differential_evolution(t, th, timed, k, args.de_iterations)
                      for k, (t, th, _) in enumerate(cases[:args.de_problems])]
            print(summary("differential_evolution", timing, count, theirs), flush=True)
            ours_same = ours[:args.de_problems]
            print(summary("symlink, same problems", timing, count, ours_same), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
