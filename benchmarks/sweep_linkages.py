"""Sweeps of any linkage: designs a second of the Watt II six-bar and Jansen's leg against the four-bar's.

In one process (:func:`symlink.sweep.evaluate_designs`, every column of the sweep table, no Dask),
random designs around each catalog linkage's example (every length within 0.8 to 1.2 times its
example value), a turn of ``--samples`` input values a design.  Printed: designs a second and
microseconds per value evaluated (design times samples) of each, and the ratios to the four-bar's
per value (target: within 3x).  Ratios inside one run only (the machine is shared).

    python -m benchmarks.sweep_linkages [--designs 200] [--samples 360]
"""
from __future__ import annotations

import argparse
import os
import time

from symlink.catalog import CATALOG, EXAMPLE_VALUES


def settings(name: str, designs: int, samples: int):
    from symlink.sweep import SweepSettings
    linkage = CATALOG[name]()
    example = EXAMPLE_VALUES[name]
    lengths = [s.name for s in linkage.parameters if s.is_positive]
    ranges = {n: (0.8 * example[n], 1.2 * example[n]) for n in lengths}
    return SweepSettings(name, ranges, mode="random", count=designs, seed=3, samples=samples, chunk=designs)


def measure(designs: int, samples: int, names=("fourbar", "watt2", "jansen")) -> dict[str, float]:
    from symlink.sweep import evaluate_designs
    found = {}
    for name in names:
        chosen = settings(name, designs, samples)
        evaluate_designs(chosen, range(min(designs, 8)))  # derived, generated and loaded before the clock
        start = time.perf_counter()
        evaluate_designs(chosen, range(designs))
        found[name] = time.perf_counter() - start
    return found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--designs", type=int, default=200)
    parser.add_argument("--samples", type=int, default=360)
    options = parser.parse_args()
    found = measure(options.designs, options.samples)
    base = found["fourbar"]
    for name, seconds in found.items():
        print(f"{name:>8}: {options.designs / seconds:9.1f} designs/s, "
              f"{1e6 * seconds / (options.designs * options.samples):7.3f} us a value, {seconds / base:6.2f}x the four-bar")
    print(f"load {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
