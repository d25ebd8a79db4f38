"""``symlink atlas [NAME] [--draw FILE]``: the one-DOF linkage topologies up to eight links, listed or shown."""
from __future__ import annotations

import argparse

from .options import command_help, figure_path


def register(commands) -> None:
    """Register ``symlink atlas``."""
    commands.add_parser("atlas", populate=_add_options, **command_help(
        "list the one-DOF planar linkages with revolute joints up to eight links, or show one",
        "none (names and counts; example coordinates in the drawing's unit)", "symlink atlas watt-ii --draw out.png",
        "Without NAME: one line a mechanism (chain, ground, driver, closed form or Newton) and the counts "
        "against the literature.  With NAME: its links and joints, example coordinates and solve plan."))


def _add_options(command: argparse.ArgumentParser) -> None:
    command.add_argument("name", metavar="NAME", nargs="?",
                         help="an atlas entry (fourbar, watt-i, ..., eightbar-16b); a six-bar in any spelling (Watt I)")
    command.add_argument("--convention", choices=("ternary-iii", "ternary-ii"), default="ternary-iii",
                         help="the numbering a six-bar's NAME is read in: ternary-iii (symlink's, default: Stephenson "
                              "III grounds a ternary link) or ternary-ii (Stephenson II and III swapped)")
    command.add_argument("--links", type=int, choices=(4, 6, 8), help="list only the mechanisms with this many links")
    command.add_argument("--draw", type=figure_path, metavar="FILE", help="draw NAME at its example pose (.png, .svg)")
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ..mechanism.atlas import ATLAS, LITERATURE_COUNTS, atlas_entry, chains
    if args.name is None:
        if args.draw:
            raise ValueError("--draw needs an atlas entry NAME to draw")
        for links in (4, 6, 8):
            if args.links not in (None, links):
                continue
            entries = [e for e in ATLAS.values() if e.links == links]
            expected = LITERATURE_COUNTS[links]
            driven = [ok for entry in entries for _, ok in entry.drivers]
            print(f"{links} links: {len(chains(links))} chains, {len(entries)} mechanisms by choice of ground "
                  f"(literature: {expected[0]} and {expected[1]}); {len(driven)} by ground and driven link, "
                  f"{sum(driven)} of them in closed form")
            for entry in entries:
                print(f"  {entry.summary()}")
        return 0
    entry = atlas_entry(args.name, args.convention)
    drawn = entry.joint_linkage()
    description, _ = entry.description()
    print(entry.summary())
    print("links: " + "; ".join(f"{name} {' '.join(joints)}" for name, joints in description.items()))
    print("joints: " + ", ".join(f"{pin} ({x:.6g}, {y:.6g})" for pin, (x, y) in entry.coordinates().items()))
    from ..symbolic.plan import solve_plan
    print(solve_plan(drawn.linkage))
    if args.draw:
        from ..plot import save_figure
        from ..plot.drawing import draw_linkage
        guess = None if drawn.linkage.has_closed_form else drawn.guess
        drawing = draw_linkage(drawn.linkage, drawn.defaults, guess=guess, title=f"{entry.name} (atlas)")
        save_figure(drawing.figure, args.draw)
        print(f"wrote {args.draw}")
    return 0
