"""``symlink export NAME --to numpy|c|octave|latex --out DIR``: a catalog linkage's solvers as files."""
from __future__ import annotations

import argparse

from ..catalog import CATALOG
from ..export import FORMATS, export
from .options import command_help


def register(commands) -> None:
    """Register ``symlink export``."""
    command = commands.add_parser("export", **command_help(
        "write a catalog linkage's solvers as NumPy, C, Octave or LaTeX",
        "the generated functions take angles in rad, speeds in rad/s, lengths in any one unit",
        "symlink export fourbar --to c --out build/"))
    command.add_argument("name", metavar="NAME", help=f"a catalog linkage ({', '.join(sorted(CATALOG))})")
    command.add_argument("--to", required=True, choices=list(FORMATS), help="the format")
    command.add_argument("--out", required=True, metavar="DIR", help="the folder to write into")
    command.add_argument("--outputs", metavar="LIST",
                         help="comma-separated output names, as one function (default: positions, velocities, "
                              "accelerations and joints)")
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Write the files (all or none) and name them."""
    outputs = None if args.outputs is None else [o.strip() for o in args.outputs.split(",") if o.strip()]
    for path in export(args.name, args.to, args.out, outputs):
        print(f"wrote {path}")
    return 0
