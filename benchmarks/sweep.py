"""Design-space sweeps: designs per second in one process, and on Dask with 1 and 2 workers.

The four-bar's ratio space (crank, coupler and rocker over ground, a random
sample), a turn of 360 input values a design, every column of
:mod:`symlink.sweep`.  Rows:

* ``in process``: :func:`symlink.sweep.evaluate_designs` on one chunk, no Dask, no Parquet;
* ``processes N``: ``run_sweep(scheduler="processes", workers=N)`` into a fresh folder, the
  pool's start (a Python with symlink imported in each worker) included;
* ``cluster N``: a ``distributed.LocalCluster`` of N single-threaded worker processes, started
  before the clock and warmed up by one chunk.

The machine's other load shows in every number: compare the rows of one run.

    python benchmarks/sweep.py                      # 40 000 designs
    python benchmarks/sweep.py --designs 1e5 --chunk 2000
"""
from __future__ import annotations

import argparse
import logging
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from symlink.sweep import SweepSettings, evaluate_designs, missing_modules, run_sweep  # noqa: E402

RATIOS = {"a": (0.1, 1.5), "b": (0.1, 3.0), "c": (0.1, 3.0)}


def settings(designs: int, chunk: int, samples: int) -> SweepSettings:
    return SweepSettings("fourbar", RATIOS, values={"d": 1.0}, mode="random", count=designs, seed=1, chunk=chunk,
                         samples=samples)


def in_process(found: SweepSettings) -> float:
    evaluate_designs(found, range(min(100, found.designs)))  # load the solver
    count = min(found.chunk, found.designs)
    start = time.perf_counter()
    evaluate_designs(found, range(count))
    return count / (time.perf_counter() - start)


def on_processes(found: SweepSettings, workers: int) -> float:
    with tempfile.TemporaryDirectory() as folder:
        start = time.perf_counter()
        run_sweep(found, Path(folder) / "out", scheduler="processes", workers=workers)
        return found.designs / (time.perf_counter() - start)


def on_cluster(found: SweepSettings, workers: int) -> float:
    import distributed
    with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=logging.ERROR) as cluster, distributed.Client(cluster) as client:
        with tempfile.TemporaryDirectory() as folder:
            warm = settings(workers * 50, 50, found.samples)
            run_sweep(warm, Path(folder) / "warm", scheduler=client)  # every worker loads the solver
            start = time.perf_counter()
            run_sweep(found, Path(folder) / "out", scheduler=client)
            return found.designs / (time.perf_counter() - start)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=float, default=4e4, help="designs a run (default 4e4)")
    parser.add_argument("--chunk", type=int, default=2000, help="designs a chunk (default 2000)")
    parser.add_argument("--samples", type=int, default=360, help="input values a turn (default 360)")
    parser.add_argument("--no-cluster", action="store_true", help="skip the distributed LocalCluster rows")
    args = parser.parse_args(argv)
    missing = missing_modules()
    if missing:
        print(f"needs {', '.join(missing)}: pip install 'symlink-kinematics[sweep]'", file=sys.stderr)
        return 2
    found = settings(int(args.designs), args.chunk, args.samples)
    print(f"four-bar ratio space, {found.designs:,} random designs, {found.samples} input values each, "
          f"chunks of {found.chunk}; {os.cpu_count()} cores")
    rows = [("in process (no Dask)", lambda: in_process(found))]
    rows += [(f"processes {n}", lambda n=n: on_processes(found, n)) for n in (1, 2)]
    if not args.no_cluster:
        rows += [(f"cluster {n}", lambda n=n: on_cluster(found, n)) for n in (1, 2)]
    rates = {}
    for name, measure in rows:
        rates[name] = measure()
        print(f"{name:<22}{rates[name]:>10,.0f} designs/s", flush=True)
    for kind in ("processes", "cluster"):
        if f"{kind} 1" in rates and f"{kind} 2" in rates:
            print(f"{kind}: 2 workers / 1 worker = {rates[f'{kind} 2'] / rates[f'{kind} 1']:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
