"""``symlink plan NAME``: how a catalog linkage is solved, loop by loop, and its mobility."""
from __future__ import annotations

import argparse

from .options import command_help


def register(commands) -> None:
    """Register ``symlink plan NAME``."""
    commands.add_parser("plan", populate=_add_options, **command_help(
        "show how a linkage (catalog name or file) is solved, loop by loop",
        "none (names and counts only)", "symlink plan watt2"))


def _add_options(command: argparse.ArgumentParser) -> None:
    from ..mechanism.catalog import CATALOG
    command.add_argument("name", metavar="NAME|FILE",
                         help=f"a catalog linkage ({', '.join(sorted(CATALOG))}) or a linkage file (.toml)")
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ..analysis import degrees_of_freedom
    from ..io.linkage_file import load_linkage
    from ..symbolic.plan import solve_plan
    linkage = load_linkage(args.name).linkage
    mobility = degrees_of_freedom(linkage)
    print(solve_plan(linkage))
    print(f"degrees of freedom: {mobility.dof} (Gruebler: {mobility.links} links with the ground, "
          f"{mobility.revolute} revolute and {mobility.prismatic} prismatic joints)")
    return 0
