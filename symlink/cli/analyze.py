"""``symlink analyze``: mobility, Grashof class, crank range, limit positions and transmission of a four-bar."""
from __future__ import annotations

import argparse
import json

from ..analysis import fourbar_report
from ..angles import from_radians
from .options import add_fourbar_lengths, add_units_option, command_help, fourbar_lengths

#: Fields of :func:`~symlink.analysis.fourbar_report` that are angles (converted to the command's units).
ANGLE_FIELDS = {"stroke", "transmission_min", "transmission_min_at", "transmission_max", "transmission_max_at",
                "worst_transmission", "extended_crank", "extended_rocker", "folded_crank", "folded_rocker"}


def in_units(report: dict, units: str) -> dict:
    """The report with its angles in ``units``."""
    convert = lambda x: float(from_radians(x, units))  # noqa: E731
    shown = dict(report)
    for key in ANGLE_FIELDS & set(report):
        if report[key] is not None:
            shown[key] = convert(report[key])
    shown["crank_range"] = [[convert(lo), convert(hi)] for lo, hi in report["crank_range"]]
    shown["toggles"] = [convert(x) for x in report["toggles"]]
    if report["limit_positions"] is not None:
        shown["limit_positions"] = {k: convert(v) for k, v in report["limit_positions"].items()}
    return shown


def register(commands) -> None:
    """Register ``symlink analyze``."""
    command = commands.add_parser("analyze", **command_help(
        "Grashof class, mobility, crank range, limit positions and transmission angle of a four-bar",
        "lengths in any one unit; printed angles in --units (deg by default)",
        "symlink analyze --crank 20 --coupler 66 --rocker 56 --ground 80"))
    add_fourbar_lengths(command)
    command.add_argument("--branch", choices=["+1", "1", "-1"], default="+1",
                         help="assembly for the limit positions (default +1)")
    add_units_option(command, "printed angles")
    command.add_argument("--format", choices=["table", "json"], default="table", help="default table")
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    a, b, c, d = fourbar_lengths(args)
    report = in_units(fourbar_report(a, b, c, d, int(args.branch)), args.units)
    if args.format == "json":
        print(json.dumps(report, indent=1))
        return 0
    unit = args.units
    spans = ("full turn" if not report["toggles"] else
             ", ".join(f"[{lo:.4f}, {hi:.4f}] {unit}" for lo, hi in report["crank_range"]))
    lines = [
        f"four-bar: crank {a:g}, coupler {b:g}, rocker {c:g}, ground {d:g}",
        f"degrees of freedom   {report['dof']}",
        f"Grashof              {report['grashof']} (s + l = {report['shortest_plus_longest']:g}, "
        f"p + q = {report['other_two']:g}; shortest: {report['shortest']})",
        f"crank range          {spans}",
    ]
    if report["toggles"]:
        lines.append("toggle positions     crank at " + ", ".join(f"{x:.4f}" for x in report["toggles"]) + f" {unit}")
    if report["limit_positions"] is not None:
        limits = report["limit_positions"]
        lines += [
            f"limit positions      extended: crank {limits['extended_crank']:.4f}, rocker "
            f"{limits['extended_rocker']:.4f} {unit}; folded: crank {limits['folded_crank']:.4f}, "
            f"rocker {limits['folded_rocker']:.4f} {unit} (branch {int(args.branch):+d})",
            f"stroke               {report['stroke']:.4f} {unit}",
            f"time ratio           {report['time_ratio']:.4f}",
        ]
    lines.append(f"transmission angle   {report['transmission_min']:.4f} at crank {report['transmission_min_at']:.4f} "
                 f"to {report['transmission_max']:.4f} at crank {report['transmission_max_at']:.4f} {unit}")
    print("\n".join(lines))
    return 0
