"""``symlink bench``: a thin entry point to the benchmark, which lives outside the runtime package."""
from __future__ import annotations

import argparse
import os
import sys

from .options import command_help


def register(commands) -> None:
    """Register ``symlink bench``: every argument after it goes to the benchmark."""
    command = commands.add_parser("bench", add_help=False, **command_help(
        "run time against error of the four-bar solvers (a source checkout's benchmarks/)",
        "seconds per value; errors in radians against 50-digit mpmath",
        "symlink bench --quick",
        "Progress goes to stderr, results to stdout; 'symlink bench --help' lists the benchmark's options."))
    command.set_defaults(run=run, passes_arguments_on=True)  # main() puts them in args.arguments


def run(args: argparse.Namespace) -> int:
    """The benchmark of the source checkout (``benchmarks/``, beside ``symlink/``), imported now."""
    checkout = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # symlink/cli/..
    if checkout not in sys.path:
        sys.path.append(checkout)  # an editable install maps only symlink/
    try:
        from benchmarks.bench import main
    except ModuleNotFoundError as error:
        if not (error.name or "").startswith("benchmarks"):
            raise
        raise ValueError("symlink bench needs the source checkout's benchmarks/ folder; "
                         "run it from the repository root (python -m benchmarks)") from None
    return main(args.arguments, prog="symlink bench")
