"""``symlink plan NAME``: how a catalog linkage is solved, loop by loop, and its mobility.

The plan is derived (SymPy) once: its printed text is kept in the disk cache, keyed as ``symlink table NAME|FILE``
keys its entries (:class:`~symlink.io.table_source.TableSource`: the catalog or atlas name, or the file's bytes), so that
a warm ``symlink plan`` builds no linkage and imports no SymPy.
"""
from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from .options import command_help

if TYPE_CHECKING:
    from ..symbolic.linkage import Linkage

#: The kind of cache entry of a printed plan (:func:`symlink.numeric.cache.catalog_key`).
PLAN_ENTRY_KIND = "plan-text/1"
#: Besides the code that shapes generated code and reads linkage files (the table's): what counts the joints, and
#: this module, whose words the text is in.
PLAN_SHAPING = ("mechanism/mobility", "cli/plan")


def register(commands) -> None:
    """Register ``symlink plan NAME``."""
    commands.add_parser("plan", populate=_add_options, **command_help(
        "show how a linkage (catalog name or file) is solved, loop by loop",
        "none (names and counts only)", "symlink plan watt2"))


def _add_options(command: argparse.ArgumentParser) -> None:
    from ..io.scene_text import catalog_file_names  # the catalog's files: no linkage built, no SymPy
    command.add_argument("name", metavar="NAME|FILE",
                         help=f"a catalog linkage ({', '.join(catalog_file_names())}) or a linkage file (.toml)")
    command.set_defaults(run=run)


def plan_text(linkage: Linkage) -> str:
    """What ``symlink plan`` prints of ``linkage``: its solve plan and its degrees of freedom (Gruebler).

    >>> from symlink.mechanism.catalog import fourbar
    >>> print(plan_text(fourbar()), end="")
    fourbar: closed form, loop by loop (inputs: theta)
      1. loop ABCD, case 3 (two angles): beta, phi from theta; branch sign branch
    degrees of freedom: 1 (Gruebler: 4 links with the ground, 4 revolute and 0 prismatic joints)
    """
    from ..mechanism.mobility import degrees_of_freedom
    from ..symbolic.plan import solve_plan
    mobility = degrees_of_freedom(linkage)
    return (f"{solve_plan(linkage)}\n"
            f"degrees of freedom: {mobility.dof} (Gruebler: {mobility.links} links with the ground, "
            f"{mobility.revolute} revolute and {mobility.prismatic} prismatic joints)\n")


def run(args: argparse.Namespace) -> int:
    from ..io.table_source import GENERIC_SHAPING, TableSource
    source = TableSource(args.name)
    if source.request is None:  # not keyed: the reader says what is wrong
        from ..io.linkage_file import load_linkage
        text = plan_text(load_linkage(args.name).linkage)
    else:
        from ..numeric.cache import cached_text, catalog_key
        key = catalog_key("table", ["plan"], PLAN_ENTRY_KIND, source.request, GENERIC_SHAPING + PLAN_SHAPING)
        text = cached_text(key, lambda: plan_text(source.found().linkage))
    print(text, end="")
    return 0
