"""The ``symlink`` command.

Every subcommand parses numbers and names only (never code), prints angles in
degrees (``--units rad`` for radians) wrapped to (-180, 180], and answers bad
input with one line on stderr and exit status 2.
"""
from __future__ import annotations

import argparse
import json
import math
import re
import sys
from typing import Collection, Mapping, Sequence

import numpy

from .analysis import crank_range
from .angles import from_radians, half_turn, to_radians, wrap  # noqa: F401 - wrap is used by the commands
from .catalog import fourbar
from .solver import Solver, check_lengths, crank_speeds

__all__ = ["main"]

FOURBAR_COLUMNS = ["crank", "branch", "coupler", "rocker", "coupler_speed", "rocker_speed",
                   "coupler_accel", "rocker_accel", "transmission"]
ANGLE_COLUMNS = {"crank", "coupler", "rocker"}


class UsageError(ValueError):
    """Bad input from the command line."""


_NUMBER = r"(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?"


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors, and negative numbers (-1e-3, -70,0) taken as values, not options."""

    def __init__(self, *args, populate: Callable[[argparse.ArgumentParser], None] | None = None, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(rf"^-{_NUMBER}(,\s*([-+]?{_NUMBER}|both))*$")  # -1,both
        self._populate = populate  # adds a subcommand's arguments when it is used, not at start-up

    def parse_known_args(self, args=None, namespace=None):
        if self._populate is not None:
            populate, self._populate = self._populate, None
            populate(self)
        return super().parse_known_args(args, namespace)

    def error(self, message: str) -> None:  # one line, exit status 2, no usage dump
        raise UsageError(message)


def finite(text: str) -> float:
    """A finite number from the command line (no expressions)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"not a finite number: {text!r}")
    return value


def number_list(text: str) -> list[float]:
    """Comma-separated finite numbers."""
    return [finite(item) for item in text.split(",") if item.strip()]


def add_sweep_options(parser: argparse.ArgumentParser, branch: bool = True) -> None:
    """The input sweep and output options shared by the table commands (``branch=False``: no ``--branch``)."""
    parser.add_argument("--crank-speed", type=finite, default=0.0, metavar="W", help="rad/s (default 0)")
    parser.add_argument("--crank-accel", type=finite, default=0.0, metavar="AL",
                        help="rad/s^2, uniform from the first angle (default 0)")
    parser.add_argument("--start", type=finite, help="first crank angle (default 0)")
    parser.add_argument("--stop", type=finite, help="last crank angle, exclusive (default 360 deg)")
    parser.add_argument("--step", type=finite, help="crank angle step (default 10 deg)")
    parser.add_argument("--angles", type=number_list, metavar="LIST", help="comma-separated crank angles")
    if branch:
        parser.add_argument("--branch", choices=["+1", "1", "-1", "both"], default="both")
    parser.add_argument("--units", choices=["deg", "rad"], default="deg")
    parser.add_argument("--format", choices=["table", "csv", "json"], default="table")


def sweep_angles(args: argparse.Namespace) -> numpy.ndarray:
    """The crank angles asked for, in the command's units."""
    ranged = (args.start, args.stop, args.step)
    if args.angles is not None:
        if any(v is not None for v in ranged):
            raise UsageError("give either --angles or --start/--stop/--step, not both")
        if not args.angles:
            raise UsageError("--angles needs at least one angle")
        return numpy.array(args.angles)
    full = 360.0 if args.units == "deg" else 2 * math.pi
    start = 0.0 if args.start is None else args.start
    stop = full if args.stop is None else args.stop
    step = (10.0 if args.units == "deg" else math.radians(10.0)) if args.step is None else args.step
    if step <= 0:
        raise UsageError(f"--step must be positive, got {step:g}")
    if stop <= start:
        raise UsageError(f"--stop ({stop:g}) must be greater than --start ({start:g})")
    count = math.ceil((stop - start) / step - 1e-9)
    if count > 10_000_000:
        raise UsageError(f"{count} crank angles is too many; use a larger --step")
    return start + step * numpy.arange(count)



def branches(args: argparse.Namespace) -> list[int]:
    return [1, -1] if args.branch == "both" else [int(args.branch)]


def format_number(value: float) -> str:
    """Full double precision for machine-readable output."""
    return repr(float(value))


def json_number(value):
    """A number for JSON: full precision, and null for NaN (JSON has no NaN)."""
    if isinstance(value, (int, str)):  # a branch: a sign, or one sign a loop ("+1/-1")
        return value
    return float(value) if math.isfinite(value) else None


def print_rows(rows: list[dict], columns: list[str], fmt: str, out=None) -> None:
    """Rows as an aligned table, csv with the exact header, or json records."""
    out = out or sys.stdout
    if fmt == "csv":
        print(",".join(columns), file=out)
        for row in rows:
            print(",".join(str(row[c]) if c == "branch" else format_number(row[c]) for c in columns), file=out)
    elif fmt == "json":
        print(json.dumps([{c: json_number(row[c]) for c in columns} for row in rows], indent=1), file=out)
    else:
        width = max(10, *(len(c) + 1 for c in columns))
        print("".join(f"{c:>{width}}" for c in columns), file=out)
        for row in rows:
            cells = [(row[c] if isinstance(row[c], str) else f"{row[c]:+d}") if c == "branch" else f"{row[c]:.4f}"
                     for c in columns]
            print("".join(f"{cell:>{width}}" for cell in cells), file=out)


def describe_spans(spans: list[tuple[float, float]], units: str) -> str:
    if not spans:
        return "none: the links cannot close at any crank angle"
    convert = math.degrees if units == "deg" else float
    if spans == [(-math.pi, math.pi)]:
        return "full turn"
    return ", ".join(f"[{convert(lo):.6g}, {convert(hi):.6g}] {units}" for lo, hi in spans)


def run_fourbar(args: argparse.Namespace) -> int:
    lengths = {"a": args.crank, "b": args.coupler, "c": args.rocker, "d": args.ground}
    check_lengths(crank=args.crank, coupler=args.coupler, rocker=args.rocker, ground=args.ground)
    angles = sweep_angles(args)
    theta = to_radians(angles, args.units)
    speeds = crank_speeds(theta, args.crank_speed, args.crank_accel)
    solver = Solver(fourbar(), FOURBAR_COLUMNS[2:])
    results = {sign: solver(theta=theta, **lengths, branch=sign, thetadot=speeds, thetaddot=args.crank_accel)
               for sign in branches(args)}
    spans = describe_spans(crank_range(args.crank, args.coupler, args.rocker, args.ground), args.units)
    rows = assemble_rows(angles, results, FOURBAR_COLUMNS, args.units, spans)
    print_rows(rows, FOURBAR_COLUMNS, args.format)
    if args.plot or args.plot_transmission:
        from .plot import write_fourbar_plots
        write_fourbar_plots(args)
    return 0


def assemble_rows(angles, results: dict, columns: list[str], units: str, spans: str | Mapping[object, str],
                  angle_columns: Collection[str] = ANGLE_COLUMNS) -> list[dict]:
    """Table rows (angle, then branch) of the assembled results; the rest named on stderr.

    ``spans`` describes the reachable crank range; a mapping gives one for each
    branch of ``results`` (they differ between branches), and the angles that
    cannot be assembled are then named branch by branch.

    Angles in ``columns`` are converted to ``units`` and wrapped; speeds and
    accelerations stay per second.  Singular rows (a toggle, where the rates
    are not defined) are kept with NaN rates and named on stderr too.
    """
    rows, singular = [], set()
    unassembled: dict[object, set[int]] = {sign: set() for sign in results}
    for i, angle in enumerate(angles):
        for sign, result in results.items():
            if not result["assembled"][i]:
                unassembled[sign].add(i)
                continue
            row = {columns[0]: float(wrap(angle, half_turn(units))), "branch": sign}
            for column in columns[2:]:
                value = float(result[column][i])
                if column in angle_columns:
                    value = float(wrap(from_radians(value, units), half_turn(units)))
                elif column == "transmission":
                    value = float(from_radians(value, units))
                elif not math.isfinite(value):
                    singular.add(i)
                row[column] = value
            rows.append(row)
    by_branch = isinstance(spans, Mapping)
    if not rows:
        known = "; ".join(f"branch {sign}: {text}" for sign, text in spans.items()) if by_branch else spans
        raise ValueError(f"the linkage cannot be assembled at any requested crank angle "
                         f"(reachable crank range: {known})")
    def listed(indices):
        return ", ".join(f"{float(wrap(angles[i], half_turn(units))):.6g}" for i in sorted(indices))
    if by_branch:
        for sign, indices in unassembled.items():
            if indices:
                print(f"symlink: branch {sign} cannot be assembled at crank angles {listed(indices)} {units} "
                      f"(reachable crank range: {spans[sign]})", file=sys.stderr)
    elif any(unassembled.values()):
        print(f"symlink: cannot be assembled at crank angles {listed(set().union(*unassembled.values()))} "
              f"{units} (reachable crank range: {spans})", file=sys.stderr)
    if singular:
        print(f"symlink: singular (toggle) position at crank angles {listed(singular)} {units}: "
              "rates and accelerations are not defined there (inf or nan)", file=sys.stderr)
    return rows


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="symlink", description="Symbolic derivation toolkit for planar linkages.")
    commands = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    table = commands.add_parser("fourbar", help="positions, rates and accelerations of a four-bar, as a table")
    for option, what in (("crank", "AB"), ("coupler", "BC"), ("rocker", "DC"), ("ground", "AD")):
        table.add_argument(f"--{option}", type=finite, required=True, help=f"length {what}")
    add_sweep_options(table)
    table.set_defaults(run=run_fourbar)
    from . import cli_slider, plan  # symlink slider-crank, symlink plan NAME
    cli_slider.add_command(commands)
    from . import cli_tables  # symlink inverted-slider-crank, watt2, stephenson3, fivebar
    cli_tables.add_commands(commands)
    plan.add_command(commands)
    from . import animation, plot, view  # light: Matplotlib is imported when something is drawn
    plot.add_fourbar_options(table)
    for module in (plot, animation, view):
        module.add_command(commands)
    from . import scene  # symlink run SCENE.toml
    scene.add_command(commands)
    # symlink bench: every argument goes to the benchmark (no option prefix here, so none is parsed)
    bench = commands.add_parser("bench", help="run time against error of the four-bar solvers (source checkout)",
                                add_help=False, prefix_chars="\0")
    bench.add_argument("arguments", nargs=argparse.REMAINDER)
    bench.set_defaults(run=run_bench)
    from . import analysis, loopcase, synthesis  # symlink analyze, loop, quick-return (seeds 000, 002, 003)
    analysis.add_command(commands)
    loopcase.add_command(commands)
    synthesis.add_command(commands)
    from . import export  # symlink export NAME --to numpy|c|octave|latex
    export.add_command(commands)
    return parser


def run_bench(args: argparse.Namespace) -> int:
    """``symlink bench``: the benchmark of the source checkout (``benchmarks/``, beside ``symlink/``), imported now."""
    import os

    import symlink
    checkout = os.path.dirname(os.path.dirname(os.path.abspath(symlink.__file__)))  # wherever this module moves
    if checkout not in sys.path:
        sys.path.append(checkout)  # an editable install maps only symlink/
    try:
        from benchmarks.bench import main as bench
    except ModuleNotFoundError as error:
        if not (error.name or "").startswith("benchmarks"):
            raise
        print("symlink: error: symlink bench needs the source checkout's benchmarks/ folder; "
              "run it from the repository root (python -m benchmarks)", file=sys.stderr)
        return 2
    return bench(args.arguments, prog="symlink bench")


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (2 for bad input)."""
    try:
        args = build_parser().parse_args(argv)
        return args.run(args)
    except ValueError as error:  # UsageError included
        print(f"symlink: error: {error}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        return 0


if __name__ == "__main__":
    sys.exit(main())
