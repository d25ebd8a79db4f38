"""Sweeps of any linkage: designs a second of the Watt II six-bar and Jansen's leg against the four-bar's.

In one process (:func:`symlink.workshop.sweep.evaluate_designs`, every column of the sweep table, no Dask),
random designs around each catalog linkage's example (every length within 0.8 to 1.2 times its
example value), a turn of ``--samples`` input values a design.  Printed: designs a second and
microseconds per value evaluated (design times samples) of each, and the ratios to the four-bar's
per value (target: within 3x).  Ratios inside one run only (the machine is shared): the linkages take turns,
``--rounds`` times, and each one's best round counts, in wall time and in this process's CPU time (which other
processes' load disturbs less).

    python -m benchmarks.sweep_linkages [--designs 200] [--samples 360] [--rounds 3]
"""
from __future__ import annotations

import argparse
import math
import os
import time

from symlink.mechanism.catalog import CATALOG, EXAMPLE_VALUES


def settings(name: str, designs: int, samples: int):
    from symlink.workshop.sweep import SweepSettings
    linkage = CATALOG[name]()
    example = EXAMPLE_VALUES[name]
    lengths = [s.name for s in linkage.parameters if s.is_positive]
    ranges = {n: (0.8 * example[n], 1.2 * example[n]) for n in lengths}
    return SweepSettings(name, ranges, mode="random", count=designs, seed=3, samples=samples, chunk=designs)


def measure(designs: int, samples: int, names=("fourbar", "watt2", "jansen"),
            rounds: int = 3) -> dict[str, tuple[float, float]]:
    """Each linkage's best (wall, CPU) seconds for ``designs`` designs over ``rounds`` rounds taken in turn."""
    from symlink.workshop.sweep import evaluate_designs
    chosen = {name: settings(name, designs, samples) for name in names}
    for found in chosen.values():  # derived, generated and loaded before the clock (every design: the margins too)
        evaluate_designs(found, range(designs))
    _wait_for_compiled(chosen.values())  # compiled in the background the first time: those builds are waited for
    best = {name: (math.inf, math.inf) for name in names}
    for _ in range(rounds):
        for name in names:
            wall, cpu = time.perf_counter(), time.process_time()
            evaluate_designs(chosen[name], range(designs))
            wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
            best[name] = (min(best[name][0], wall), min(best[name][1], cpu))
    return best


def _wait_for_compiled(sweeps, timeout: float = 300.0) -> None:
    """Wait for the background builds of the compiled solvers and margins that the ``sweeps`` use, and adopt them."""
    from symlink.numeric.compiled_library import wait_for_builds
    from symlink.workshop.sweep import evaluate_designs
    wait_for_builds(timeout)
    for found in sweeps:
        evaluate_designs(found, range(found.designs))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--designs", type=int, default=200)
    parser.add_argument("--samples", type=int, default=360)
    parser.add_argument("--rounds", type=int, default=3)
    options = parser.parse_args()
    load = os.getloadavg()[0]
    found = measure(options.designs, options.samples, rounds=options.rounds)
    base_wall, base_cpu = found["fourbar"]
    values = options.designs * options.samples
    for name, (wall, cpu) in found.items():
        print(f"{name:>8}: {options.designs / wall:9.1f} designs/s, {1e6 * wall / values:7.3f} us a value "
              f"({1e6 * cpu / values:7.3f} CPU), {wall / base_wall:6.2f}x the four-bar ({cpu / base_cpu:5.2f}x CPU)")
    print(f"load {load:.2f} before, {os.getloadavg()[0]:.2f} after; best of {options.rounds} rounds")


if __name__ == "__main__":
    main()
