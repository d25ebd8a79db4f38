"""``symlink sweep``: properties of many designs of a linkage, on Dask, into a folder of Parquet files.

The columns are those of :mod:`symlink.workshop.sweep` (angles in radians there,
whatever ``--units`` says about the command line's own angles).  Needs the
``sweep`` extra; without it the command says how to install it.

Continuing a folder verifies it (:mod:`symlink.io.sweep_folder`): a chunk that
is not what the manifest recorded is done again with one warning line.
Ctrl-C ends the command with one line, ``symlink: interrupted``, and exit
status 130, as every command (2 is for bad input); the chunks finished are
kept, and the worker processes end with the command.
"""
from __future__ import annotations

import argparse
import math
import os

from ..common.angles import to_radians
from ..common.files import excerpt
from ..common.limits import format_bytes
from .budget import MEMORY_BUDGET, add_time_budget_option, budget_text, format_duration, time_budget
from .options import (OutputFolder, add_units_option, assignments, command_help, finite, refuse_together,
                      require_held_input_names, seed, whole)
from .output import note


def ranges(text: str) -> dict[str, tuple[float, float]]:
    """``NAME=LOW:HIGH,...`` (numbers only)."""
    found = {}
    for item in text.split(","):
        name, equals, bounds = item.partition("=")
        low, colon, high = bounds.partition(":")
        if not equals or not colon or not name.strip():
            raise argparse.ArgumentTypeError(f"expected NAME=LOW:HIGH,..., got {excerpt(item.strip())}")
        if name.strip() in found:
            raise argparse.ArgumentTypeError(f"{excerpt(name.strip())} is given twice")
        found[name.strip()] = (finite(low), finite(high))
    return found


#: Input values a worker evaluates a second in a sweep (measured: 27,000 four-bar designs of 360 samples in 15 s on
#: one worker of a shared machine, 6.4e5 a second).
SWEEP_VALUES_PER_SECOND = 6e5
#: Workers a cluster (``--scheduler tcp://...``) is taken to have when estimating a sweep's time on it.
CLUSTER_WORKERS = 1000
#: Bytes a sweep holds for each chunk while it runs (its place in the to-do list and in the manifest).
SWEEP_BYTES_PER_CHUNK = 200


def _fewer_designs(most: int, dimensions: int, mode: str) -> str:
    """The largest request of at most ``most`` designs, as the option that asks for it: ``--random N`` or, for a
    grid of ``dimensions`` swept parameters, ``--grid N``."""
    if mode == "random":
        return f"use --random {most:,} or fewer"
    per = max(1, int(round(most ** (1 / dimensions))))
    while per > 1 and per ** dimensions > most:
        per -= 1
    while (per + 1) ** dimensions <= most:
        per += 1
    return f"use --grid {per:,} or fewer" if per >= 2 else "sweep fewer parameters (--vary)"


def estimate_sweep(designs: int, samples: int, chunk: int, scheduler: str, workers: int | None,
                   dimensions: int = 1, mode: str = "grid") -> float:
    """The seconds a sweep would take; ``ValueError`` (one line) for one that would not finish or fit in memory.

    Checked before anything starts: the time on the workers (at most the command's time budget,
    :func:`.budget.time_budget`: an hour unless ``--time-budget`` raises it), the memory that keeps track of the
    chunks, and the memory of the chunks the local workers evaluate at once (within the command budget of
    :mod:`.budget`).  A refusal ends with the largest request that fits (``--grid`` for a grid of ``dimensions``
    parameters, ``--random`` for ``mode`` random).  A note on stderr gives the estimate of a sweep of more than a
    minute.
    """
    from ..workshop.sweep import CHUNK_BYTES_PER_VALUE
    cluster = scheduler.startswith(("tcp://", "tls://"))
    count = CLUSTER_WORKERS if cluster else (1 if scheduler == "synchronous" else workers or os.cpu_count() or 1)
    seconds = designs * samples / (SWEEP_VALUES_PER_SECOND * count)
    where = f"{count:,} worker{'s' if count > 1 else ''}{' (taken for a cluster)' if cluster else ''}"
    budget = time_budget()
    if seconds > budget:
        most = int(budget * SWEEP_VALUES_PER_SECOND * count / samples)
        remedy = _fewer_designs(most, dimensions, mode) if most >= 1 else "use fewer --samples"
        raise ValueError(f"a sweep of {designs:.3g} designs of {samples} samples would take about "
                         f"{format_duration(seconds)} on {where} ({budget_text()}); {remedy}")
    chunks = -(-designs // chunk)
    if chunks * SWEEP_BYTES_PER_CHUNK > MEMORY_BUDGET:
        raise ValueError(f"a sweep of {chunks:,} chunks would need about {format_bytes(chunks * SWEEP_BYTES_PER_CHUNK)} "
                         f"of memory to keep track of them (at most {format_bytes(MEMORY_BUDGET)}); use a larger "
                         f"--chunk (at least {-(-designs * SWEEP_BYTES_PER_CHUNK // MEMORY_BUDGET):,})")
    at_once = 1 if cluster else count  # a cluster's workers hold their chunks in their own memory
    chunk_bytes = min(chunk, designs) * samples * CHUNK_BYTES_PER_VALUE
    if chunk_bytes * at_once > MEMORY_BUDGET:
        fits = MEMORY_BUDGET // (at_once * samples * CHUNK_BYTES_PER_VALUE)
        if fits < 1:  # even chunks of one design: too many workers at once
            most = max(1, MEMORY_BUDGET // (samples * CHUNK_BYTES_PER_VALUE))
            raise ValueError(f"{count:,} workers evaluating chunks of {samples} samples at once would need about "
                             f"{format_bytes(samples * CHUNK_BYTES_PER_VALUE * at_once)} of memory even with "
                             f"--chunk 1 (at most {format_bytes(MEMORY_BUDGET)}); use --workers {most:,} or fewer")
        raise ValueError(f"chunks of {min(chunk, designs):,} designs of {samples} samples on {where} would need about "
                         f"{format_bytes(chunk_bytes * at_once)} of memory at once (at most "
                         f"{format_bytes(MEMORY_BUDGET)}); use --chunk {fits:,} or fewer")
    if seconds > 60:
        note(f"{designs:,} designs of {samples} samples: about {format_duration(seconds)} on {where}")
    return seconds


def _sweep_folder(text: str) -> OutputFolder:
    folder = OutputFolder(text)
    folder.label = "FOLDER"
    return folder


def _require_an_assembly(folder: str, designs: int, fresh: bool) -> None:
    """``ValueError`` when no design of a finished sweep assembles at any input value: a table of nothing but
    non-assemblies (every column NaN but the design's own) answers no question, so the command refuses it as
    every command refuses a linkage that never assembles; a folder this run created is removed."""
    import shutil

    import pyarrow
    import pyarrow.parquet

    from ..io.sweep_folder import verified_chunks
    for _, data in verified_chunks(folder):
        # ParquetFile.read of pyarrow's own buffer on this thread: read_table imported pandas (a sweep's start
        # imports only what its scheduler needs), and a Python file object read by pyarrow's threads aborted the
        # process at exit ("terminate called without an active exception")
        reach = pyarrow.parquet.ParquetFile(pyarrow.BufferReader(data)).read(columns=["reach"], use_threads=False)
        # (the column as Python numbers: pyarrow.compute takes 50 ms to import, and to_numpy imports pandas)
        if any(value is not None and value > 0 for value in reach.column("reach").to_pylist()):
            return
    if fresh:
        shutil.rmtree(folder, ignore_errors=True)
    raise ValueError(f"no design of this sweep assembles at any input value (all {designs:,} designs cannot close "
                     "their loops): check --set and the --vary ranges"
                     + ("" if fresh else f"; {folder} keeps their rows"))


def register(commands) -> None:
    """Register ``symlink sweep`` (its options are added when it is used: they need the sweep module)."""
    commands.add_parser("sweep", populate=_add_options, **command_help(
        "evaluate many designs of a linkage on Dask into Parquet files (assembly, reach, Grashof, transmission, "
        "stroke, time ratio, path)",
        "lengths in any one unit; fixed angles and angle ranges in --units; angles in the table in radians",
        "symlink sweep fourbar atlas/ --vary a=0.1:1,b=0.2:2,c=0.2:2 --set d=1 --grid 40",
        "Run again with the same settings to continue an interrupted sweep: every chunk there is checked against "
        "the manifest (rows, designs, SHA-256) and a bad one is done again, with one warning.  A sweep estimated to "
        "take longer than --time-budget (default an hour), or to need more disk than there is, is refused before "
        "it starts, with the largest --grid or --random that fits.  Ctrl-C stops it with exit "
        "status 130 (the command line's 'interrupted'), keeping the chunks finished; its worker processes end with "
        "it.  Needs the sweep extra (symlink-kinematics[sweep])."))


def _add_options(command: argparse.ArgumentParser) -> None:
    from ..workshop.sweep import SCHEDULERS
    command.add_argument("linkage", metavar="NAME|FILE", help="a catalog linkage or a linkage file")
    command.add_argument("folder", type=_sweep_folder, metavar="FOLDER", help="where the chunks (chunk-NNNNNN.parquet) and manifest go")
    command.add_argument("--vary", type=ranges, required=True, metavar="NAME=LOW:HIGH,...",
                         help="the parameters swept and their ranges")
    command.add_argument("--set", type=assignments("NAME=VALUE"), default={}, metavar="NAME=VALUE,...",
                         help="values of the other parameters (default: the catalog's example or the file's)")
    how = command.add_mutually_exclusive_group()
    how.add_argument("--grid", type=whole, metavar="N", help="N values of each swept parameter (default 10)")
    how.add_argument("--random", type=whole, metavar="N", help="N designs uniform in the ranges (seeded)")
    command.add_argument("--seed", type=seed, default=0, help="of --random (default 0)")
    command.add_argument("--samples", type=whole, default=360, metavar="N", help="input values a turn (default 360)")
    command.add_argument("--output", metavar="NAME", help="the output whose stroke and time ratio are found "
                                                          "(default: the last role)")
    command.add_argument("--point", metavar="NAME", help="the point whose path is described (default: the last "
                                                         "moving point)")
    command.add_argument("--harmonics", type=whole, default=3, metavar="H",
                         help="Fourier coefficients -H..H of the path (default 3)")
    command.add_argument("--branch", choices=["+1", "1", "-1"], default="+1", help="every loop's sign (default +1)")
    command.add_argument("--chunk", type=whole, default=1000, metavar="N", help="designs a chunk (default 1000)")
    command.add_argument("--scheduler", default="auto", metavar="WHERE",
                         help=f"auto, {', '.join(SCHEDULERS)} (Dask's local schedulers; default auto: this process "
                              "for one chunk or one worker, else threads) or a distributed cluster's address "
                              "tcp://HOST:PORT")
    command.add_argument("--workers", type=whole, metavar="N", help="local workers (default: one a core)")
    command.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    add_time_budget_option(command)
    add_units_option(command, "fixed angles and angle ranges")
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """``symlink sweep``: the linkage's facts and solvers come from the disk cache (derived once: a warm sweep
    imports no SymPy), and its start imports only what its scheduler needs."""
    from ..io.table_source import facts_values
    from ..workshop.sweep import SCHEDULERS, SWEEP_EXTRA, SweepSettings, missing_modules, run_sweep, sweep_facts
    missing = missing_modules()
    if missing:
        raise ValueError(f"symlink sweep needs {', '.join(missing)}: {SWEEP_EXTRA}")
    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers must be at least 1, got {args.workers}")
    refuse_together(args, ("workers", "conflicts with --scheduler synchronous", args.scheduler == "synchronous",
                           "it evaluates every chunk in this process, one at a time"),
                    ("workers", f"conflicts with --scheduler {args.scheduler}",
                     args.scheduler.startswith(("tcp://", "tls://")), "a cluster's workers are its own"),
                    ("seed", "does nothing with --grid", args.random is None,
                     "a grid is not sampled; --seed belongs to --random N"))
    if args.scheduler not in (*SCHEDULERS, "auto") and not args.scheduler.startswith(("tcp://", "tls://")):
        raise ValueError(f"--scheduler must be auto, {', '.join(SCHEDULERS)} or a cluster's address tcp://HOST:PORT, "
                         f"got {args.scheduler!r}")
    facts = sweep_facts(args.linkage)
    both = sorted(set(args.vary) & set(args.set))
    if both:
        raise ValueError(f"--vary and --set both give {', '.join(both)}: a parameter is swept or set, not both")
    require_held_input_names(facts["name"], facts["inputs"], args.set, "a sweep")
    values = facts_values(facts, args.set, args.units)
    swept: dict[str, tuple[float, float]] = {}
    for name, (low, high) in args.vary.items():
        turned = name in facts["angles"]
        swept[name] = ((float(to_radians(low, args.units)), float(to_radians(high, args.units))) if turned
                       else (low, high))
    values = {name: value for name, value in values.items()
              if name not in swept and name != facts["inputs"][0]}
    mode, count = ("random", args.random) if args.random is not None else ("grid", 10 if args.grid is None else args.grid)
    if min(count, args.samples, args.chunk) >= 1:  # else SweepSettings says what is wrong
        designs = count ** len(swept) if mode == "grid" else count
        estimate_sweep(designs, args.samples, args.chunk, args.scheduler, args.workers, len(swept), mode)
    settings = SweepSettings(args.linkage, swept, values=values, mode=mode, count=count, seed=args.seed,
                             samples=args.samples, output=args.output, point=args.point, harmonics=args.harmonics,
                             branch=int(args.branch), chunk=args.chunk)
    fresh = not os.path.lexists(args.folder) or (os.path.isdir(args.folder) and not os.listdir(args.folder))
    done = run_sweep(settings, args.folder, scheduler=args.scheduler, workers=args.workers,
                     progress=not args.no_progress)
    _require_an_assembly(args.folder, done["designs"], fresh)
    rate = done["designs_per_second"]
    chunks = f"{done['chunks']} chunk{'s' if done['chunks'] != 1 else ''}"
    note(f"{done['designs']} designs in {chunks}: wrote {done['written']}, found {done['skipped']} already there"
         + ("" if math.isnan(rate) else f"; {rate:.4g} designs/s"))
    print(args.folder)
    return 0
