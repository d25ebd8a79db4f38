"""Design-space sweeps: designs per second in one process, and on Dask with 1 and 2 workers.

The four-bar's ratio space (crank, coupler and rocker over ground, a random
sample), a turn of 360 input values a design, every column of
:mod:`symlink.workshop.sweep`.  Rows:

* ``in process``: :func:`symlink.workshop.sweep.evaluate_designs` on one chunk, no Dask, no Parquet;
* ``synchronous``, ``threads N``, ``auto N``: ``run_sweep`` on those schedulers (``auto``: what a user
  gets, :func:`symlink.workshop.sweep.local_scheduler`) with N workers, into a fresh folder;
* ``processes N``: ``run_sweep(scheduler="processes", workers=N)`` into a fresh folder, the
  pool's start (a Python with symlink imported in each worker) included;
* ``cluster N``: a ``distributed.LocalCluster`` of N single-threaded worker processes, started
  before the clock and warmed up by one chunk.

Each row also says the CPU time a design took (this process's and its worker processes'), which other
engineers' load disturbs less than the wall time, and the load average is printed before and after: on a
machine whose cores are busy with other work a second worker cannot gain what it would on an idle one.
The machine's other load shows in every number: compare the rows of one run.  ``--blocked`` measures
what a free core could not remove: it runs the chunks on 1 and 2 threads (no Dask) and splits each worker
thread's wall time, from the kernel's scheduler statistics (``/proc/self/task/TID/schedstat``, Linux), into
time on a CPU, time runnable but waiting for one (the machine's other load), and time blocked (the workers
do no I/O: waiting for the GIL).  On a machine with a free core for each worker, the wall time is about the
CPU and blocked time, so the gain of a second worker is projected from those.

    python benchmarks/sweep.py                      # 40 000 designs
    python benchmarks/sweep.py --designs 1e5 --chunk 2000
    python benchmarks/sweep.py --linkage jansen --designs 4000 --chunk 500 --no-cluster
    python benchmarks/sweep.py --designs 8000 --chunk 1000 --blocked
"""
from __future__ import annotations

import argparse
import logging
import math
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from symlink.numeric.compiled_library import wait_for_builds  # noqa: E402
from symlink.workshop.sweep import SweepSettings, evaluate_designs, missing_modules, run_sweep  # noqa: E402

RATIOS = {"a": (0.1, 1.5), "b": (0.1, 3.0), "c": (0.1, 3.0)}


def settings(designs: int, chunk: int, samples: int, linkage: str = "fourbar") -> SweepSettings:
    """The four-bar's ratio space, or any catalog linkage's lengths within 0.8 to 1.2 times its example's."""
    if linkage == "fourbar":
        return SweepSettings("fourbar", RATIOS, values={"d": 1.0}, mode="random", count=designs, seed=1,
                             chunk=chunk, samples=samples)
    from symlink.mechanism.catalog import CATALOG, EXAMPLE_VALUES
    example = EXAMPLE_VALUES[linkage]
    ranges = {s.name: (0.8 * example[s.name], 1.2 * example[s.name]) for s in CATALOG[linkage]().parameters
              if s.is_positive}
    return SweepSettings(linkage, ranges, mode="random", count=designs, seed=1, chunk=chunk, samples=samples)


def cpu_seconds() -> float:
    """CPU seconds of this process (every thread) and of its finished child processes."""
    import resource
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


def in_process(found: SweepSettings) -> tuple[float, float]:
    """Designs a second and CPU seconds a design of one chunk evaluated here (no Dask, no Parquet)."""
    count = min(found.chunk, found.designs)
    start, cpu = time.perf_counter(), cpu_seconds()
    evaluate_designs(found, range(count))
    return count / (time.perf_counter() - start), (cpu_seconds() - cpu) / count


def on_scheduler(found: SweepSettings, scheduler: str, workers: int) -> tuple[float, float]:
    """Designs a second and CPU seconds a design of the whole sweep run on a local scheduler into a fresh folder."""
    with tempfile.TemporaryDirectory() as folder:
        start, cpu = time.perf_counter(), cpu_seconds()
        run_sweep(found, Path(folder) / "out", scheduler=scheduler, workers=workers)
        return found.designs / (time.perf_counter() - start), (cpu_seconds() - cpu) / found.designs


def thread_times() -> tuple[float, float, float]:
    """This thread's wall clock, seconds on a CPU and seconds runnable waiting for one (Linux schedstat)."""
    import threading
    with open(f"/proc/self/task/{threading.get_native_id()}/schedstat", encoding="ascii") as file:
        on_cpu, waiting, _ = map(int, file.read().split())
    return time.perf_counter(), on_cpu / 1e9, waiting / 1e9


def blocked_rows(found: SweepSettings) -> None:
    """Each chunk on 1 and 2 threads: its worker's wall time split into on a CPU, runnable and blocked."""
    from concurrent.futures import ThreadPoolExecutor

    def chunk(index: int) -> tuple[float, float, float]:
        wall, cpu, waiting = thread_times()
        evaluate_designs(found, range(index * found.chunk, min((index + 1) * found.chunk, found.designs)))
        after = thread_times()
        return after[0] - wall, after[1] - cpu, after[2] - waiting

    idle = {}
    for workers in (1, 2):
        with ThreadPoolExecutor(workers) as pool:
            start = time.perf_counter()
            parts = list(pool.map(chunk, range(found.chunks)))
            seconds = time.perf_counter() - start
        wall, cpu, waiting = (sum(part[k] for part in parts) for k in range(3))
        blocked = max(0.0, wall - cpu - waiting)
        idle[workers] = (cpu + blocked) / workers  # each worker with a core of its own
        print(f"threads {workers} (no Dask)   {found.designs / seconds:>10,.0f} designs/s; workers' time {wall:.2f} s ="
              f" on a CPU {cpu:.2f} + runnable {waiting:.2f} + blocked {blocked:.2f} ({100 * blocked / wall:.1f} %)",
              flush=True)
    print(f"projected on free cores: 2 threads / 1 thread = {idle[1] / idle[2]:.2f}")


def on_cluster(found: SweepSettings, workers: int) -> tuple[float, float]:
    import distributed
    with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=logging.ERROR) as cluster, distributed.Client(cluster) as client:
        with tempfile.TemporaryDirectory() as folder:
            warm = settings(workers * 50, 50, found.samples, found.linkage)
            run_sweep(warm, Path(folder) / "warm", scheduler=client)  # every worker loads the solver
            start = time.perf_counter()
            run_sweep(found, Path(folder) / "out", scheduler=client)
            return found.designs / (time.perf_counter() - start), math.nan  # the workers' CPU is not ours to see


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=float, default=4e4, help="designs a run (default 4e4)")
    parser.add_argument("--chunk", type=int, default=2000, help="designs a chunk (default 2000)")
    parser.add_argument("--samples", type=int, default=360, help="input values a turn (default 360)")
    parser.add_argument("--no-cluster", action="store_true", help="skip the distributed LocalCluster rows")
    parser.add_argument("--linkage", default="fourbar", help="a catalog linkage (default fourbar: its ratio space)")
    parser.add_argument("--blocked", action="store_true",
                        help="only the split of the threads' time (on a CPU, runnable, blocked by the GIL)")
    parser.add_argument("--rows", default="", help="only these rows, by name, comma-separated (e.g. 'threads 1,"
                                                  "threads 2'): a long sweep's rows in runs of their own")
    args = parser.parse_args(argv)
    missing = missing_modules()
    if missing:
        print(f"needs {', '.join(missing)}: pip install 'symlink-kinematics[sweep]'", file=sys.stderr)
        return 2
    found = settings(int(args.designs), args.chunk, args.samples, args.linkage)
    load = os.getloadavg()
    print(f"{args.linkage}, {found.designs:,} random designs, {found.samples} input values each, chunks of "
          f"{found.chunk} ({found.chunks} chunks); {os.cpu_count()} cores, load average {load[0]:.2f} "
          f"(1 min) {load[1]:.2f} (5 min)")
    warm = settings(min(found.designs, 2 * found.chunk), found.chunk, found.samples, args.linkage)
    evaluate_designs(warm, range(warm.designs))  # derived and loaded; compiled code built, before any clock
    wait_for_builds(300)
    evaluate_designs(warm, range(warm.designs))
    if args.blocked:
        blocked_rows(found)
        return 0
    rows = [("in process (no Dask)", lambda: in_process(found)),
            ("synchronous", lambda: on_scheduler(found, "synchronous", 1))]
    for kind in ("threads", "processes", "auto"):
        rows += [(f"{kind} {n}", lambda kind=kind, n=n: on_scheduler(found, kind, n)) for n in (1, 2)]
    if not args.no_cluster:
        rows += [(f"cluster {n}", lambda n=n: on_cluster(found, n)) for n in (1, 2)]
    if args.rows:
        wanted = [name.strip() for name in args.rows.split(",")]
        unknown = [name for name in wanted if name not in dict(rows)]
        if unknown:
            print(f"no row {', '.join(unknown)}; the rows are {', '.join(dict(rows))}", file=sys.stderr)
            return 2
        rows = [(name, dict(rows)[name]) for name in wanted]
    rates = {}
    for name, measure in rows:
        rates[name], cpu = measure()
        print(f"{name:<22}{rates[name]:>10,.0f} designs/s {1e3 * cpu:8.3f} ms CPU a design", flush=True)
    for kind in ("threads", "processes", "auto", "cluster"):
        if f"{kind} 1" in rates and f"{kind} 2" in rates:
            print(f"{kind}: 2 workers / 1 worker = {rates[f'{kind} 2'] / rates[f'{kind} 1']:.2f}")
    load = os.getloadavg()
    print(f"load average after: {load[0]:.2f} (1 min) {load[1]:.2f} (5 min)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
