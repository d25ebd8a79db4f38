"""``symlink loop``: solve ``z1 + z2 + z3 + z4 = 0`` for the two of its eight values left out."""
from __future__ import annotations

import argparse
import json

from ..common.angles import from_radians, half_turn, to_radians, wrap
from .options import add_units_option, angle, command_help, figure_path, finite
from .output import json_number, note, print_rows


def register(commands) -> None:
    """Register ``symlink loop``."""
    command = commands.add_parser("loop", **command_help(
        "solve z1+z2+z3+z4=0 for the two values left out (the four cases of a vector loop)",
        "lengths in any one unit; angles in --units (deg by default)",
        "symlink loop --r1 300 --t1 270 --r2 640.3124 --t2 308.663 --t3 180 --t4 63.435",
        "z_n = R_n e^(i t_n); give six of the eight values --r1..--r4, --t1..--t4."))
    for k in "1234":
        command.add_argument(f"--r{k}", type=finite, metavar="R", help=f"length of z{k}")
        command.add_argument(f"--t{k}", type=angle, metavar="T", help=f"angle of z{k}")
    add_units_option(command, "angles given and printed")
    command.add_argument("--format", choices=["table", "json"], default="table", help="default table")
    command.add_argument("--plot", type=figure_path, metavar="FILE", help="draw the closed loop (.png or .svg)")
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ..analysis.loopcase import NAMES, solve_case
    values = {n: getattr(args, n) for n in NAMES}
    values = {n: (float(to_radians(v, args.units)) if n.startswith("t") and v is not None else v)
              for n, v in values.items()}
    result = solve_case(values)

    def shown(name: str, value: float) -> float:
        if name.startswith("t"):
            return float(wrap(from_radians(value, args.units), half_turn(args.units)))
        return value

    rows = [{"branch": b, **{n: shown(n, s[n]) for n in result.missing}}
            for b, s in zip(result.branches, result.solutions)]
    for text in result.notes:
        note(f"note: {text}")
    if args.format == "json":
        print(json.dumps({"case": result.case,
                          "solutions": [{n: json_number(row[n]) for n in result.missing} for row in rows]}))
    else:
        print(f"case {result.case}: {result.description} ({', '.join(result.missing)}; angles in {args.units})")
        columns = (["branch"] if result.branches[0] else []) + list(result.missing)
        print_rows(rows, columns, "table")
    if args.plot:
        from ..plot import draw_loop
        solved = result.values(0)
        branch = f", branch {result.branches[0]:+d}" if result.branches[0] else ""
        draw_loop([solved[f"r{k}"] for k in "1234"], [solved[f"t{k}"] for k in "1234"], args.plot,
                  title=f"case {result.case}: {result.description}{branch}")
        if len(result.solutions) > 1:
            note(f"note: {args.plot} shows the first solution (branch {result.branches[0]:+d})")
    return 0
