"""``symlink plan NAME``: how a catalog linkage is solved, loop by loop, and its mobility."""
from __future__ import annotations

import argparse

from ..analysis import degrees_of_freedom
from ..catalog import CATALOG
from ..plan import solve_plan
from .options import command_help


def register(commands) -> None:
    """Register ``symlink plan NAME``."""
    command = commands.add_parser("plan", **command_help(
        "show how a catalog linkage is solved, loop by loop",
        "none (names and counts only)", "symlink plan watt2"))
    command.add_argument("name", choices=sorted(CATALOG), metavar="NAME",
                         help=f"a catalog linkage: {', '.join(sorted(CATALOG))}")
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    linkage = CATALOG[args.name]()
    mobility = degrees_of_freedom(linkage)
    print(solve_plan(linkage))
    print(f"degrees of freedom: {mobility.dof} (Gruebler: {mobility.links} links with the ground, "
          f"{mobility.revolute} revolute and {mobility.prismatic} prismatic joints)")
    return 0
