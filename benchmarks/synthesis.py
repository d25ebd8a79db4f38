"""Path-synthesis benchmark: symlink's exact-Jacobian least squares against SciPy's differential evolution.

Random crank-rocker four-bars (placed anywhere, with a random coupler point) are sampled at
N crank angles (sorted, uniform over a turn); each method must find a four-bar through the
points from the points alone, with the crank angles given (timed) or not (untimed).  A
problem counts as solved when the largest distance from a target to the found coupler
point is below 1e-8 of the targets' size (bounding-box diagonal).  Both methods work on
the same objective, the normalised distances from the targets to the coupler point (least
squares of them for symlink, their sum of squares for differential evolution), with the
same constraint (every point assembled on one branch, no toggle).

Differential evolution gets its fastest form: the whole population is evaluated in one
vectorised call of the generated coupler point (no derivatives), ``popsize`` 15 members per
unknown, up to ``--de-iterations`` generations, SciPy's own polish, once on each branch.
It never reaches 1e-8, so besides its time and error the benchmark records, for the same
problem, when symlink first had a verified design at least as good as differential
evolution's final one (symlink's time "to DE's error"), and compares it with differential
evolution's own first arrival at that error (its best member after each generation, the
seconds spent recording it not counted), not with its whole run time: a run goes on for
generations after its last improvement.

Each problem is one JSON line in ``--log`` as soon as it is done; the table is printed at the
end (or from a log alone with ``--summarize``).  ``--part symlink`` and ``--part de`` run one
method each, so that two processes started together can share the machine and one log.  Symlink runs every case first, then
differential evolution goes round the cases, one problem each, until ``--de-problems`` each
or the wall clock reaches ``--until`` (HH:MM, UTC), with at least ``--de-minimum`` each.
Run from the repository root (not a test; SciPy needed)::

    python benchmarks/synthesis.py --problems 100 --de-problems 10 --log /tmp/synthesis.jsonl

``python -m benchmarks.synthesis --literature [--seeds N] [--problems case1,...]`` runs the
literature's classical problems instead, each with its published objective, bounds and best
values (:mod:`benchmarks.literature`); ``--literature --shapes [--seeds N] [--targets ...]`` its
shape targets (:mod:`benchmarks.literature_shapes`).
"""
from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import statistics
import sys
import time
from pathlib import Path

import numpy

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from symlink.analysis import grashof  # noqa: E402
from symlink.numeric.cache import generated_code  # noqa: E402
from symlink.synthesis import path as path_synthesis  # noqa: E402
from symlink.synthesis.path import fourbar_design, path_fourbar, synthesize_path  # noqa: E402

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


def problems(timing: str, count: int, seed: int, how_many: int) -> list:
    """The case's problems, the same for every method and run (one generator per case)."""
    rng = numpy.random.default_rng(seed + count + (0 if timing == "timed" else 1000))
    return [random_problem(rng, count) for _ in range(how_many)]


def _size(targets: numpy.ndarray) -> float:
    return float(numpy.hypot(*(targets.max(axis=0) - targets.min(axis=0))))


def run_symlink(targets, theta, timed: bool, seed: int) -> dict:
    """Symlink's synthesis, and the (seconds, error) of every design it verified on the way (its progress)."""
    verified: list[tuple[float, float]] = []
    check = path_synthesis.check_design

    def recording(*arguments, **keywords):
        design = check(*arguments, **keywords)
        verified.append((time.perf_counter() - start, design.error))
        return design

    path_synthesis.check_design = recording  # synthesize_path looks the checker up at each call
    start = time.perf_counter()
    try:
        error = synthesize_path(targets, theta if timed else None, designs=1, seed=seed)[0].error
    except ValueError:
        error = math.inf
    finally:
        path_synthesis.check_design = check
    return {"error": error, "seconds": time.perf_counter() - start, "progress": verified}


def coupler_points():
    """The generated coupler point of the placed four-bar alone (no derivatives): what DE evaluates."""
    return generated_code(path_fourbar(), ["P_x", "P_y", "singular"]).function


def run_differential_evolution(targets, theta, timed: bool, seed: int, max_iterations: int) -> dict:
    """SciPy's differential evolution on the same objective, population evaluated at once; infeasible: 1e6."""
    from scipy.optimize import differential_evolution
    points = coupler_points()
    size = _size(targets)
    low, high = targets.min(axis=0), targets.max(axis=0)
    count = len(targets)
    bounds = [(low[0] - size, high[0] + size), (low[1] - size, high[1] + size), (-math.pi, math.pi)]
    bounds += [(0.02 * size, 3 * size)] * 4 + [(-3 * size, 3 * size)] * 2
    if not timed:
        bounds += [(-math.pi, math.pi)] + [(0.0, 4 * math.pi / count)] * (count - 1)

    def angles(x):  # x: (unknowns, members) -> crank angles (count, members)
        if timed:
            return theta[:, None] + 0 * x[:1]
        return x[9:10] + numpy.concatenate([numpy.zeros_like(x[:1]), numpy.cumsum(x[10:], axis=0)])

    def distances(x, branch):
        x = numpy.asarray(x, dtype=float).reshape(len(bounds), -1)
        crank_angles = angles(x)
        with numpy.errstate(all="ignore"):
            out = points(crank_angles, 0.0, *x[:9, None, :], float(branch), check=False)
        ok = numpy.all(out["assembled"] & ~out["singular"], axis=0)
        if not timed:
            ok &= crank_angles[-1] - crank_angles[0] < 2 * math.pi
        squared = ((out["P_x"] - targets[:, :1]) ** 2 + (out["P_y"] - targets[:, 1:]) ** 2) / size ** 2
        return squared, ok

    def objective(x, branch):
        squared, ok = distances(x, branch)
        value = numpy.where(ok, numpy.sum(squared, axis=0), 1e6)
        return value if numpy.ndim(x) == 2 else float(value[0])

    start = time.perf_counter()
    best = math.inf
    progress: list[tuple[float, float]] = []  # (seconds, best error so far) at each generation
    paused = [0.0]  # seconds spent recording the progress, not counted

    def error_of(x, branch) -> float:
        squared, ok = distances(x, branch)
        return float(numpy.sqrt(squared.max())) if ok[0] else math.inf

    def recorder(branch):
        def callback(intermediate_result):
            stopped = time.perf_counter()
            # DE minimises the sum of squares: its best member's largest distance may grow; the best so far counts
            reached = min(progress[-1][1] if progress else math.inf, error_of(intermediate_result.x, branch))
            progress.append((stopped - start - paused[0], reached))
            paused[0] += time.perf_counter() - stopped
        return callback

    for branch in (1, -1):
        fit = differential_evolution(objective, bounds, args=(branch,), seed=seed, maxiter=max_iterations,
                                     tol=1e-14, atol=0, polish=True, popsize=15, vectorized=True,
                                     updating="deferred", callback=recorder(branch))
        best = min(best, error_of(fit.x, branch), progress[-1][1] if progress else math.inf)
        progress.append((time.perf_counter() - start - paused[0], best))
        if best < SUCCESS:
            break
    return {"error": best, "seconds": time.perf_counter() - start - paused[0], "progress": progress}


def time_to_error(record: dict, error: float) -> float:
    """When a method (symlink, or DE by its generations) first had a verified design with at most ``error`` (inf if never)."""
    return min((seconds for seconds, reached in record["progress"] if reached <= error), default=math.inf)


def first_arrival(record: dict) -> float:
    """When differential evolution first reached its final error (its whole time for a log without progress)."""
    if not record.get("progress"):
        return record["seconds"]
    return min(time_to_error(record, record["error"]), record["seconds"])


def _median(values):
    return statistics.median(values) if values else math.nan


def summary(records: list[dict]) -> str:
    """The table: per case, symlink on all its problems, DE, and symlink on DE's problems (to 1e-8, to DE's error)."""
    lines = ["| method | timing | N | problems | solved (< 1e-8) | median s/problem | mean s/problem | "
             "median final error |", "|---|---|---|---|---|---|---|---|"]
    for timing, count in CASES:
        ours = {r["problem"]: r for r in records if r["method"] == "symlink" and r["case"] == f"{timing}{count}"}
        theirs = [r for r in records if r["method"] == "de" and r["case"] == f"{timing}{count}"]
        if not ours and not theirs:
            continue

        def row(name, chosen, seconds=None):
            seconds = [r["seconds"] for r in chosen] if seconds is None else seconds
            solved = sum(r["error"] < SUCCESS for r in chosen)
            finite = [r["error"] for r in chosen if math.isfinite(r["error"])]
            return (f"| {name} | {timing} | {count} | {len(chosen)} | {solved / len(chosen):.0%} | "
                    f"{_median(seconds):.3g} | {statistics.fmean(seconds):.3g} | {_median(finite):.2g} |")
        if ours:
            lines.append(row("symlink (exact Jacobian, LM)", list(ours.values())))
        if theirs:
            lines.append(row(f"differential evolution ({theirs[0]['iterations']} generations)", theirs))
            same = [ours[r["problem"]] for r in theirs if r["problem"] in ours]
            if same:
                lines.append(row("symlink, the same problems, to 1e-8", same))
                reach = [time_to_error(ours[r["problem"]], r["error"]) for r in theirs if r["problem"] in ours]
                reached = [s for s in reach if math.isfinite(s)]
                # DE's first arrival at its final error (not its whole run, which goes on without improving)
                ratios = [first_arrival(r) / s for r, s in zip(theirs, reach) if math.isfinite(s) and s > 0]
                lines.append(f"| symlink, the same problems, to DE's final error | {timing} | {count} | {len(same)} | "
                             f"reached on {len(reached)} of {len(same)} | {_median(reached):.3g} | "
                             f"{statistics.fmean(reached) if reached else math.nan:.3g} | "
                             f"DE's first arrival at it / symlink's: median {_median(ratios):.3g}x, "
                             f"min {min(ratios, default=math.nan):.3g}x |")
    return "\n".join(lines)


def main(argv=None) -> int:
    arguments = sys.argv[1:] if argv is None else list(argv)
    if "--literature" in arguments and "--shapes" in arguments:  # shape targets: benchmarks/literature_shapes.py
        from benchmarks import literature_shapes
        return literature_shapes.main([a for a in arguments if a != "--literature"])
    if "--literature" in arguments:  # the literature's classical problems: benchmarks/literature.py
        from benchmarks import literature
        return literature.main([a for a in arguments if a != "--literature"])
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--problems", type=int, default=100, help="problems per case for symlink (default 100)")
    parser.add_argument("--de-problems", type=int, default=10, help="most problems per case for differential "
                                                                     "evolution (default 10)")
    parser.add_argument("--de-minimum", type=int, default=5, help="problems per case for differential evolution "
                                                                  "even past --until (default 5)")
    parser.add_argument("--until", default=None, help="HH:MM UTC: start no DE problem beyond --de-minimum after it")
    parser.add_argument("--de-iterations", type=int, default=1000, help="differential evolution generations")
    parser.add_argument("--seed", type=int, default=2024)
    parser.add_argument("--cases", default=",".join(f"{t}{n}" for t, n in CASES),
                        help="which cases, e.g. timed5,untimed10")
    parser.add_argument("--log", default=None, help="append one JSON line per problem to this file")
    parser.add_argument("--summarize", default=None, help="print the table of a log and stop")
    parser.add_argument("--literature", action="store_true", help="run benchmarks/literature.py instead (its "
                                                                 "options: --seeds, --problems case1,...; with "
                                                                 "--shapes, benchmarks/literature_shapes.py)")
    parser.add_argument("--part", choices=("both", "symlink", "de"), default="both",
                        help="run one method only (two processes side by side share one --log)")
    args = parser.parse_args(argv)
    if args.summarize:
        with open(args.summarize) as log:
            print(summary([json.loads(line) for line in log if line.strip()]))
        return 0
    wanted = [(t, n) for t, n in CASES if f"{t}{n}" in args.cases.split(",")]
    deadline = None
    if args.until:
        hours, minutes = (int(x) for x in args.until.split(":"))
        now = datetime.datetime.now(datetime.timezone.utc)
        deadline = now.replace(hour=hours, minute=minutes, second=0, microsecond=0)
    records: list[dict] = []
    log = open(args.log, "a") if args.log else None

    def keep(record):
        records.append(record)
        if log:
            log.write(json.dumps(record) + "\n")
            log.flush()
    print(f"load average at start {os.getloadavg()}", flush=True)
    cases = {case: problems(*case, args.seed, max(args.problems, args.de_problems)) for case in wanted}
    # Imports and generated code loaded before any clock starts, for both methods.
    warm_targets, warm_theta, _ = problems("timed", 5, args.seed + 1, 1)[0]
    run_symlink(warm_targets, warm_theta, True, 0)
    run_differential_evolution(warm_targets, warm_theta, True, 0, 2)
    for (timing, count), chosen in cases.items():
        if args.part == "de":
            break
        for k, (targets, theta, _) in enumerate(chosen[:args.problems]):
            record = run_symlink(targets, theta, timing == "timed", k)
            keep({"method": "symlink", "case": f"{timing}{count}", "problem": k, **record,
                  "load": os.getloadavg()[0]})
        print(f"symlink {timing}{count} done, load {os.getloadavg()}", flush=True)
    for k in range(args.de_problems if args.part != "symlink" else 0):
        late = deadline is not None and datetime.datetime.now(datetime.timezone.utc) >= deadline
        if late and k >= args.de_minimum:
            break
        for (timing, count), chosen in cases.items():
            targets, theta, _ = chosen[k]
            record = run_differential_evolution(targets, theta, timing == "timed", k, args.de_iterations)
            keep({"method": "de", "case": f"{timing}{count}", "problem": k, **record,
                  "iterations": args.de_iterations, "load": os.getloadavg()[0]})
        print(f"differential evolution problem {k} done in every case, load {os.getloadavg()}", flush=True)
    print(f"load average at end {os.getloadavg()}")
    print(summary(records))
    return 0


if __name__ == "__main__":
    sys.exit(main())
