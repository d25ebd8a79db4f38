"""``symlink slider-crank``: the slider-crank with offset as a table, in the shape of ``symlink fourbar``.

::

    symlink slider-crank --crank A --conrod B [--offset E] [--crank-speed W] [--crank-accel AL]
                         [--start DEG --stop DEG --step DEG | --angles LIST] [--branch +1|-1|both]
                         [--units deg|rad] [--format table|csv|json]

Angles (crank, conrod) in degrees or radians, wrapped; the slider position in
the length unit, its speed and acceleration per second and per second squared.
Branch +1 is the assembly with the larger slider position.
"""
from __future__ import annotations

import argparse
import math

from .catalog import slider_crank
from .solver import Solver, check_lengths, crank_speeds

__all__ = ["SLIDER_COLUMNS", "slider_crank_range", "add_command", "run"]

SLIDER_COLUMNS = ["crank", "branch", "conrod", "slider", "conrod_speed", "slider_speed",
                  "conrod_accel", "slider_accel"]
SLIDER_ANGLE_COLUMNS = {"crank", "conrod"}


def slider_crank_range(a: float, b: float, offset: float) -> list[tuple[float, float]]:
    """The crank angles (radians) at which the slider-crank can be assembled, as closed intervals.

    The rod reaches the guide while ``|offset - a sin(theta)| <= b``, which
    bounds ``sin(theta)``.  A full turn is ``[(-pi, pi)]``; an empty list means
    it cannot be assembled at all.

    >>> [tuple(round(math.degrees(x), 6) for x in span) for span in slider_crank_range(2, 1, 0)]
    [(-30.0, 30.0), (150.0, 210.0)]
    """
    low, high = (offset - b) / a, (offset + b) / a  # the bounds of sin(theta)
    if low > 1 or high < -1:
        return []
    if low <= -1 and high >= 1:
        return [(-math.pi, math.pi)]
    if high >= 1:
        return [(math.asin(low), math.pi - math.asin(low))]
    if low <= -1:
        return [(math.pi - math.asin(high), 2 * math.pi + math.asin(high))]
    return [(math.asin(low), math.asin(high)), (math.pi - math.asin(high), math.pi - math.asin(low))]


def add_command(commands: argparse._SubParsersAction) -> None:
    """Register ``symlink slider-crank``."""
    from .cli import add_sweep_options, finite

    table = commands.add_parser("slider-crank", help="positions, speeds and accelerations of a slider-crank")
    table.add_argument("--crank", type=finite, required=True, metavar="A", help="crank length AB")
    table.add_argument("--conrod", type=finite, required=True, metavar="B", help="connecting rod length BC")
    table.add_argument("--offset", type=finite, default=0.0, metavar="E",
                       help="the slider's line is y = offset (any sign; default 0)")
    add_sweep_options(table)
    table.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from .angles import to_radians
    from .cli import assemble_rows, branches, describe_spans, print_rows, sweep_angles

    check_lengths(crank=args.crank, conrod=args.conrod)
    angles = sweep_angles(args)
    theta = to_radians(angles, args.units)
    speeds = crank_speeds(theta, args.crank_speed, args.crank_accel)
    solver = Solver(slider_crank(), SLIDER_COLUMNS[2:])
    results = {sign: solver(theta=theta, a=args.crank, b=args.conrod, offset=args.offset, branch=sign,
                            thetadot=speeds, thetaddot=args.crank_accel)
               for sign in branches(args)}
    spans = describe_spans(slider_crank_range(args.crank, args.conrod, args.offset), args.units)
    rows = assemble_rows(angles, results, SLIDER_COLUMNS, args.units, spans, angle_columns=SLIDER_ANGLE_COLUMNS)
    print_rows(rows, SLIDER_COLUMNS, args.format)
    return 0
