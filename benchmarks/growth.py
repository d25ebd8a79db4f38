"""Cost that grows with the work: time and peak memory against size, each with its fitted exponent (not a test).

Three families (issue #33, item 6):

* **chains of n dyads**, n = 1, 2, 4, ... 64, written two ways: *by joints* (:func:`chain_by_joints`, the chain
  a designer draws: dyad j is a rocker from the ground pivot G_j and a coupler from the joint before, P_(j-1),
  meeting at P_j, derived by :func:`symlink.mechanism.joints.from_joints`) and *by loops*
  (:func:`benchmarks.cold_chain.chain`: four-bar j's crank is four-bar j-1's rocker).  Each size runs in a child
  process of its own with the disk cache off, and is timed phase by phase, in CPU seconds of the child:

  - derive: the straight-line program of every unknown's position (for the chain by joints, with the
    derivation of its loops from the joints and their branch signs at the drawing);
  - generate: the NumPy module and the C source of that program;
  - compile: the system C compiler on that source (CPU seconds of the compiler processes);
  - solve: the NumPy solver at ``--values`` input angles (best of three calls);
  - memory: the child's peak resident set (ru_maxrss) less its size after its imports, MB.

* **shape search** (:func:`symlink.synthesis.shape.shape_search`) of the four-bar's crank pin, at doubling
  numbers of sampled designs: CPU seconds and peak traced memory (``tracemalloc``, NumPy's arrays included);
* **sweeps** of the catalog's four-bar, Watt II six-bar and Jansen leg (:func:`symlink.workshop.sweep.evaluate_designs`,
  every column of the sweep table, warm: code generated before the clock) at equal, doubling design counts.

The fitted exponent p of ``cost ~ size^p`` is the least-squares slope of log cost against log size over the upper
half of the sizes (where the fixed costs no longer hide the growth).  Printed: a table a family, the exponents,
the processor and the load; ``--plot PNG`` draws the figure of the growth page, ``--json FILE`` keeps the rows.
The machine is shared: read the exponents and the ratios inside one run.

    python -m benchmarks.growth                          # quick: up to 16 dyads (a few minutes)
    python -m benchmarks.growth --full --plot docs/images/growth.png --json growth.json   # up to 64 dyads
"""
from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

QUICK_DYADS = [1, 2, 4, 8, 16]
FULL_DYADS = [1, 2, 4, 8, 16, 32, 64]
QUICK_DESIGNS = [250, 500, 1000, 2000]
FULL_DESIGNS = [250, 500, 1000, 2000, 4000, 8000]
PHASES = ("derive", "generate", "compile", "solve")


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


def chain_by_joints(n: int) -> tuple[dict, dict]:
    """Links and drawn joints of a crank A-P0 and n dyads, dyad j hung on P_(j-1) and the ground pivot G_j."""
    links = {"ground": ["A"] + [f"G{j}" for j in range(1, n + 1)], "crank": ["A", "P0"]}
    coordinates = {"A": (0.0, 0.0), "P0": (0.3, 1.0)}
    for j in range(1, n + 1):
        links[f"r{j}"] = [f"G{j}", f"P{j}"]
        links[f"c{j}"] = [f"P{j - 1}", f"P{j}"]
        coordinates[f"G{j}"] = (2.0 * j + 0.5, -0.5)
        coordinates[f"P{j}"] = (2.0 * j + 0.7, 1.3 + 0.3 * (j % 2))
    return links, coordinates


def loop_values(n: int) -> dict[str, float]:
    """Every four-bar of the chain by loops the same (crank 1, coupler 3, rocker 2.5, ground 3.2): it assembles."""
    return {name: value for j in range(1, n + 1)
            for name, value in ((f"a{j}", 1.0), (f"b{j}", 3.0), (f"c{j}", 2.5), (f"d{j}", 3.2))}


def _cpu() -> float:
    return time.process_time()


def _compilers_cpu() -> float:
    times = os.times()
    return times.children_user + times.children_system


def _peak_mb() -> float:
    import resource
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # kB on Linux


def measure_chain(kind: str, n: int, count: int) -> dict[str, float]:
    """One size, in this process (a fresh child): the four phases' CPU seconds and the peak memory."""
    import numpy
    import sympy  # noqa: F401 - imported before the baseline of memory
    from symlink.codegen.numpy import numpy_module
    from symlink.codegen.loading import load_numpy_module
    from symlink.numeric.compiled_library import compile_shared, program_facts
    import symlink.mechanism.joints  # noqa: F401
    from benchmarks.cold_chain import chain
    baseline = _peak_mb()
    row: dict[str, float] = {"n": n}
    start = _cpu()
    if kind == "joints":
        from symlink.mechanism.joints import from_joints
        links, coordinates = chain_by_joints(n)
        drawn = from_joints(links, coordinates, driver="A", name=f"joints{n}")
        linkage, arguments = drawn.linkage, dict(drawn.defaults)
    else:
        linkage = chain(n)
        arguments = {**loop_values(n), **{s.name: 1.0 for s in linkage.branches}}
    outputs = [q.name for q in linkage.unknowns]
    program = linkage.program(outputs)
    row["derive"] = _cpu() - start
    start = _cpu()
    source = numpy_module([("solve", program, "")])
    facts = json.loads(program_facts(program, "solve", "", [s.name for s in program.arguments if s.is_positive]))
    row["generate"] = _cpu() - start
    row["source_kb"] = (len(source) + len(facts["source"])) / 1024
    start = _compilers_cpu()
    compile_shared(facts["source"])
    row["compile"] = _compilers_cpu() - start
    solve = load_numpy_module(source)["solve"]
    angle = linkage.inputs[0].name
    arguments[angle] = numpy.linspace(-math.pi, math.pi, count)
    arguments = {s.name: arguments[s.name] for s in program.arguments if s.name in arguments}
    best = math.inf
    for _ in range(3):
        start = _cpu()
        solve(**arguments)
        best = min(best, _cpu() - start)
    row["solve"] = best
    row["memory"] = _peak_mb() - baseline
    return row


def chain_row(kind: str, n: int, count: int) -> dict[str, float]:
    """One size measured in a child process of its own (nothing shared between sizes: caches, peak memory)."""
    with tempfile.TemporaryDirectory(prefix="symlink-growth-") as cache:
        env = {**os.environ, "SYMLINK_CACHE": cache, "MPLBACKEND": "Agg"}
        here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
        env["PYTHONPATH"] = here + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
        done = subprocess.run([sys.executable, "-m", "benchmarks.growth", "--child", kind, str(n),
                               "--values", str(count)], capture_output=True, text=True, env=env, cwd=here)
    if done.returncode != 0:
        raise RuntimeError(f"{kind} {n}: {done.stderr.strip().splitlines()[-1:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def shape_rows(counts: list[int]) -> list[dict[str, float]]:
    """Shape search of the four-bar's crank pin B (a circle) over two free lengths, at ``counts`` designs."""
    import numpy
    import tracemalloc
    from symlink.mechanism.catalog import EXAMPLE_VALUES, fourbar
    from symlink.synthesis.shape import shape_search
    linkage, values = fourbar(), EXAMPLE_VALUES["fourbar"]
    turn = numpy.linspace(0.0, 2 * math.pi, 48, endpoint=False)
    target = numpy.stack([3 + 2 * numpy.cos(turn), 1 + 2 * numpy.sin(turn)], axis=1)
    free = {"b": (50.0, 80.0), "c": (40.0, 70.0)}
    search = dict(values=values, designs=counts[0], seed=1)
    shape_search(linkage, "B", target, free, **search)  # generated and loaded before the clock
    rows = []
    for count in counts:
        tracemalloc.start()
        start = _cpu()
        shape_search(linkage, "B", target, free, **{**search, "designs": count})
        seconds = _cpu() - start
        peak = tracemalloc.get_traced_memory()[1] / 2 ** 20
        tracemalloc.stop()
        rows.append({"n": count, "search": seconds, "memory": peak})
    return rows


def sweep_rows(counts: list[int], names=("fourbar", "watt2", "jansen"), samples: int = 360) -> dict[str, list]:
    """Sweep tables of the catalog's linkages at ``counts`` designs each (warm): CPU seconds, traced peak MB."""
    import tracemalloc
    from benchmarks.sweep_linkages import settings
    from symlink.workshop.sweep import evaluate_designs
    found: dict[str, list] = {}
    for name in names:
        evaluate_designs(settings(name, counts[0], samples), range(counts[0]))  # generated before the clock
        found[name] = []
        for count in counts:
            chosen = settings(name, count, samples)
            tracemalloc.start()
            start = _cpu()
            evaluate_designs(chosen, range(count))
            seconds = _cpu() - start
            peak = tracemalloc.get_traced_memory()[1] / 2 ** 20
            tracemalloc.stop()
            found[name].append({"n": count, "sweep": seconds, "memory": peak})
    return found


def fitted_exponent(rows: list[dict], key: str) -> float:
    """The least-squares slope of log(value) against log(n) over the upper half of the rows (by n)."""
    upper = sorted(rows, key=lambda row: row["n"])[len(rows) // 2:] if len(rows) > 3 else rows
    upper = [row for row in upper if row[key] > 0]
    if len(upper) < 2:
        return math.nan
    xs = [math.log(row["n"]) for row in upper]
    ys = [math.log(row[key]) for row in upper]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def table(rows: list[dict], keys: list[str], size: str) -> str:
    """A Markdown table of the rows, and a last row of each column's fitted exponent."""
    lines = [f"| {size} | " + " | ".join(keys) + " |", "|---" * (len(keys) + 1) + "|"]
    for row in rows:
        lines.append(f"| {row['n']} | " + " | ".join(f"{row[k]:.3g}" for k in keys) + " |")
    lines.append("| exponent | " + " | ".join(f"{fitted_exponent(rows, k):.2f}" for k in keys) + " |")
    return "\n".join(lines)


def plot(results: dict, path: str) -> None:
    """Time and memory against size, log-log, a panel a family; the fitted exponents in the legends."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from symlink.common.files import write_atomic
    figure, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    for column, kind in enumerate(("joints", "loops")):
        rows = results["chains"][kind]
        ns = [row["n"] for row in rows]
        for key in PHASES:
            axes[0, column].loglog(ns, [max(row[key], 1e-4) for row in rows], "o-",
                                   label=f"{key} ~ n^{fitted_exponent(rows, key):.2f}")
        axes[1, column].loglog(ns, [max(row["memory"], 0.1) for row in rows], "o-",
                               label=f"peak memory ~ n^{fitted_exponent(rows, 'memory'):.2f}")
        axes[1, column].loglog(ns, [row["source_kb"] for row in rows], "s--",
                               label=f"generated source ~ n^{fitted_exponent(rows, 'source_kb'):.2f}")
        axes[0, column].set_title(f"dyads by {kind}: CPU seconds")
        axes[1, column].set_title(f"dyads by {kind}: peak MB, source kB")
        axes[1, column].set_xlabel("dyads n")
    shapes = results["shape"]
    axes[0, 2].loglog([r["n"] for r in shapes], [r["search"] for r in shapes], "o-",
                      label=f"shape search ~ N^{fitted_exponent(shapes, 'search'):.2f}")
    axes[1, 2].loglog([r["n"] for r in shapes], [r["memory"] for r in shapes], "o-",
                      label=f"shape search ~ N^{fitted_exponent(shapes, 'memory'):.2f}")
    for name, rows in results["sweeps"].items():
        axes[0, 2].loglog([r["n"] for r in rows], [r["sweep"] for r in rows], "s--",
                          label=f"sweep {name} ~ N^{fitted_exponent(rows, 'sweep'):.2f}")
        axes[1, 2].loglog([r["n"] for r in rows], [r["memory"] for r in rows], "s--",
                          label=f"sweep {name} ~ N^{fitted_exponent(rows, 'memory'):.2f}")
    axes[0, 2].set_title("shape search and sweeps: CPU seconds")
    axes[1, 2].set_title("shape search and sweeps: peak traced MB")
    axes[1, 2].set_xlabel("designs N")
    for axis in axes.flat:
        axis.grid(True, which="both", alpha=0.3)
        axis.legend(fontsize=7)
    figure.suptitle(f"Growth with size ({results['processor']}, {results['processors']} processors)", fontsize=10)
    figure.tight_layout()
    import io
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=90)
    plt.close(figure)
    write_atomic(path, buffer.getvalue())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--full", action="store_true", help="chains of up to 64 dyads and more designs")
    parser.add_argument("--n", type=int, nargs="+", help="the chains' sizes (default 1 ... 16, --full: ... 64)")
    parser.add_argument("--values", type=int, default=10_000, help="input angles a solve call takes")
    parser.add_argument("--plot", help="write the figure to this PNG")
    parser.add_argument("--json", help="write the rows to this JSON file")
    parser.add_argument("--child", nargs=2, metavar=("KIND", "N"), help=argparse.SUPPRESS)
    options = parser.parse_args()
    if options.child:
        print(json.dumps(measure_chain(options.child[0], int(options.child[1]), options.values)))
        return
    sizes = options.n or (FULL_DYADS if options.full else QUICK_DYADS)
    designs = FULL_DESIGNS if options.full else QUICK_DESIGNS
    os.environ["SYMLINK_CACHE"] = tempfile.mkdtemp(prefix="symlink-growth-")
    results: dict = {"processor": processor(), "processors": os.cpu_count(), "chains": {}}
    for kind in ("joints", "loops"):
        results["chains"][kind] = [chain_row(kind, n, options.values) for n in sizes]
        print(f"\nchain of n dyads by {kind} (CPU seconds; memory: peak MB over the imports; source kB)\n")
        print(table(results["chains"][kind], list(PHASES) + ["memory", "source_kb"], "n"), flush=True)
    results["shape"] = shape_rows(designs)
    print("\nshape search of the four-bar's crank pin (CPU seconds, peak traced MB)\n")
    print(table(results["shape"], ["search", "memory"], "designs"), flush=True)
    results["sweeps"] = sweep_rows(designs)
    for name, rows in results["sweeps"].items():
        print(f"\nsweep of {name} (CPU seconds, peak traced MB)\n")
        print(table(rows, ["sweep", "memory"], "designs"), flush=True)
    results["load"] = os.getloadavg()[0]
    print(f"\n{results['processor']}; {results['processors']} processors, load {results['load']:.2f}")
    if options.json:
        from symlink.common.files import write_atomic
        write_atomic(options.json, json.dumps(results, indent=1))
    if options.plot:
        plot(results, options.plot)


if __name__ == "__main__":
    main()
