"""``symlink quick-return``: an exact quick-return crank-rocker from time ratio, stroke and rocker length."""
from __future__ import annotations

import argparse
import json
import math

from .options import angle, command_help, finite, pair
from .output import note


def register(commands) -> None:
    """Register ``symlink quick-return``."""
    commands.add_parser("quick-return", populate=_add_options, **command_help(
        "synthesize a quick-return crank-rocker from time ratio, stroke and rocker",
        "lengths in the rocker's unit; angles in degrees",
        "symlink quick-return --time-ratio 1.25 --stroke 40 --rocker 50",
        "Quick-return crank-rocker synthesis, exact. The rocker pivot is at the origin."))


def _add_options(command: argparse.ArgumentParser) -> None:
    from ..synthesis.quick_return import MAX_LINK_RATIO
    command.add_argument("--time-ratio", type=finite, required=True, metavar="TR", help="slow over quick stroke, >= 1")
    command.add_argument("--stroke", type=angle, required=True, metavar="DEG", help="rocker swing, degrees")
    command.add_argument("--rocker", type=finite, required=True, metavar="L", help="rocker length")
    command.add_argument("--rocker-min-angle", type=angle, default=90.0, metavar="DEG",
                         help="rocker angle at its minimum position (default 90)")
    command.add_argument("--crank-pivot", type=pair("X,Y"), metavar="X,Y",
                         help="fix the crank pivot (the paper's procedure); default: the best one")
    command.add_argument("--max-link-ratio", type=finite, default=MAX_LINK_RATIO, metavar="K",
                         help="without a crank pivot: longest link at most K times the crank "
                              f"(default {MAX_LINK_RATIO:g})")
    command.add_argument("--format", choices=["table", "json"], default="table", help="default table")
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ..synthesis.quick_return import as_record, quick_return
    design = quick_return(args.time_ratio, math.radians(args.stroke), args.rocker,
                          math.radians(args.rocker_min_angle), args.crank_pivot, args.max_link_ratio)
    record = as_record(design)
    for warning in design.warnings:
        note(f"warning: {warning}")
    if args.format == "json":
        print(json.dumps(record, indent=1))
        return 0
    lines = [
        f"Quick-return crank-rocker ({design.method}); rocker pivot O4 at (0, 0)",
        f"crank          {design.crank:.4f}",
        f"coupler        {design.coupler:.4f}",
        f"rocker         {design.rocker:.4f}",
        f"ground         {design.ground:.4f}",
        f"crank pivot    ({design.crank_pivot[0]:.4f}, {design.crank_pivot[1]:.4f})",
        f"stroke         {record['stroke']:.4f} deg (requested {record['requested_stroke']:g})",
        f"time ratio     {design.time_ratio:.4f} (requested {design.requested_time_ratio:g})",
        f"transmission   {record['transmission_min']:.4f} to {record['transmission_max']:.4f} deg "
        f"(worst {record['worst_transmission']:.4f})",
        f"rocker swings  {record['rocker_extremes'][0]:.4f} <-> {record['rocker_extremes'][1]:.4f} deg",
        f"Grashof        {design.grashof}",
    ]
    print("\n".join(lines))
    return 0
