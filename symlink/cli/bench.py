"""``symlink bench``: a thin entry point to the benchmark, which lives outside the runtime package."""
from __future__ import annotations

import argparse

from .options import command_help


def register(commands) -> None:
    """Register ``symlink bench``: every argument after it goes to the benchmark."""
    command = commands.add_parser("bench", add_help=False, **command_help(
        "run time against error of the four-bar solvers (progress on stderr, results on stdout)",
        "seconds per value; errors in radians against 50-digit mpmath",
        "symlink bench --quick"))
    command.set_defaults(run=run, passes_arguments_on=True)  # main() puts them in args.arguments


def run(args: argparse.Namespace) -> int:
    from ..bench import main
    return main(args.arguments, prog="symlink bench")
