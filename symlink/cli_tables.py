"""Table commands built from catalog entries, in the shape of ``symlink fourbar``.

A :class:`Table` describes one command: the catalog linkage it solves, an
option for each of the linkage's parameters, and where the reachable crank
range is known in closed form.  Everything else follows from the linkage:

* columns: the crank angle, ``branch``, any further input (the five-bar's
  ``crank2``), then each unknown's angle or length, then their speeds
  (``_speed``) and accelerations (``_accel``), each unknown named by its
  role in the catalog (``rocker``) or else by its coordinate (``mu``);
* branches: one sign a loop.  With one loop the branch column is ``1`` or
  ``-1`` (``+1`` in the table) as in ``symlink fourbar``; with several loops
  it is one sign a loop, in solve-plan order, joined by ``/`` (``+1/-1``),
  and ``--branch`` takes ``both`` (every combination), one sign for every
  loop, or one of ``+1``, ``-1``, ``both`` a loop separated by commas.  A
  linkage with one assembly has no ``--branch`` and prints branch ``+1``;
* further inputs (two degrees of freedom): ``--ROLE-angle`` is their angle
  when the crank is at 0 and ``--ROLE-ratio`` turns them with the crank,
  ``angle + ratio * crank`` (default 0: held still);
* a linkage without a closed form is solved by the generated Newton solver
  (:class:`symlink.solver.NumericSolver`), continued along the sweep from an assembly at the
  first crank angle: the one nearest ``--guess``, or by default the first (in
  the order the entry lists them: Stephenson III by coupler angle) that
  continues over the whole sweep.

>>> print(", ".join(table_columns(catalog_linkage("watt2"))))
crank, branch, coupler, rocker, coupler2, output, coupler_speed, rocker_speed, coupler2_speed, output_speed, coupler_accel, rocker_accel, coupler2_accel, output_accel
>>> loop_branches(2)("+1,both")
[(1,), (1, -1)]
"""
from __future__ import annotations

import argparse
import itertools
import math
from dataclasses import dataclass
from typing import Callable, Mapping

import numpy
import sympy as sp

from .analysis import crank_range
from .angles import from_radians, half_turn, to_radians, wrap
from .assemblies import stephenson3_assemblies
from .closure import is_angle
from .linkage import Linkage
from .scene import catalog_linkage
from .solver import NumericSolver, Solver, check_lengths, crank_speeds
from .vectors import acceleration, rate

__all__ = ["Option", "Table", "TABLES", "table_columns", "loop_branches", "scanned_range",
           "add_table_command", "add_commands", "run_table"]

LENGTH, NUMBER, ANGLE = "length", "number", "angle"
#: Points a turn of the scan that finds a reachable crank range without a closed form.
SCAN_POINTS = 3600


@dataclass(frozen=True)
class Option:
    """``--name METAVAR``: sets the linkage parameter ``symbol``.

    ``kind``: a positive ``LENGTH``, any finite ``NUMBER``, or an ``ANGLE``
    given in the command's ``--units``.  ``default`` None: required.
    """

    name: str
    symbol: str
    metavar: str
    meaning: str
    kind: str = LENGTH
    default: float | None = None


@dataclass(frozen=True)
class Table:
    """A table command for the catalog linkage ``linkage`` (the command has its name).

    ``reachable(values)`` gives the reachable crank range (radians, closed
    intervals, ``[(-pi, pi)]`` a full turn) or a sentence, from the parameter
    values by symbol name (angles in radians; further inputs under their
    coordinate name and ``NAME_ratio``); where it (or it in turn) gives None,
    the range is found by a scan of the solver (:func:`scanned_range`).
    ``undetermined(values, result)`` marks solved positions that the
    linkage leaves undetermined (left out like those that cannot be assembled).
    ``assemblies(theta, values)`` lists the assemblies at one crank angle, for
    a linkage that is solved numerically.
    """

    linkage: str
    summary: str
    options: tuple[Option, ...]
    notes: str = ""
    reachable: Callable[[Mapping[str, float]], list[tuple[float, float]] | str | None] | None = None
    undetermined: Callable[[Mapping[str, float], Mapping[str, numpy.ndarray]], numpy.ndarray] | None = None
    assemblies: Callable[[float, Mapping[str, float]], list[dict[str, float]]] | None = None


def _label(linkage: Linkage, q: sp.Symbol) -> str:
    """A coordinate's column name: its role, else its own name."""
    return next((role for role, symbol in linkage.roles.items() if symbol == q), q.name)


def _outputs(linkage: Linkage) -> dict[str, str]:
    """The solved columns and the output names behind them: unknowns, then their rates, then accelerations."""
    columns = {_label(linkage, u): u.name for u in linkage.unknowns}
    columns.update({_label(linkage, u) + "_speed": rate(u).name for u in linkage.unknowns})
    columns.update({_label(linkage, u) + "_accel": acceleration(u).name for u in linkage.unknowns})
    return columns


def table_columns(linkage: Linkage) -> list[str]:
    """The csv header of a linkage's table command."""
    first, *further = linkage.inputs
    return [_label(linkage, first), "branch"] + [_label(linkage, x) for x in further] + list(_outputs(linkage))


def loop_branches(loops: int) -> Callable[[str], list[tuple[int, ...]]]:
    """A parser of ``--branch`` for ``loops`` loops: the signs each loop is solved on."""
    signs = {"+1": (1,), "1": (1,), "-1": (-1,), "both": (1, -1)}

    def parse(text: str) -> list[tuple[int, ...]]:
        items = [item.strip() for item in text.split(",")]
        if len(items) == 1:
            items *= loops
        if len(items) != loops or any(item not in signs for item in items):
            raise argparse.ArgumentTypeError(
                f"expected both, +1, -1, or one of them for each of the {loops} loops separated by commas "
                f"(e.g. +1,both), got {text!r}")
        return [signs[item] for item in items]

    return parse


def _guess(text: str) -> dict[str, float]:
    """``NAME=ANGLE,...`` from the command line (numbers only)."""
    from .cli import finite

    guess = {}
    for item in text.split(","):
        name, equals, value = item.partition("=")
        if not equals or not name.strip():
            raise argparse.ArgumentTypeError(f"expected NAME=ANGLE,..., got {item.strip()!r}")
        guess[name.strip()] = finite(value)
    return guess


def scanned_range(assembled: Callable[[numpy.ndarray], numpy.ndarray],
                  points: int = SCAN_POINTS) -> list[tuple[float, float]]:
    """The crank angles where ``assembled`` holds, from a scan of a full turn, edges bisected to rounding.

    ``assembled`` maps an array of crank angles (radians) to a boolean mask.
    Intervals as in :func:`symlink.analysis.crank_range`; stretches narrower
    than the scan step (a tenth of a degree) can be missed.

    >>> [tuple(round(math.degrees(x), 9) for x in span) for span in scanned_range(lambda t: numpy.cos(t) >= 0.5)]
    [(-60.0, 60.0)]
    """
    step = 2 * math.pi / points
    grid = -math.pi + step * numpy.arange(points)
    inside = numpy.asarray(assembled(grid), dtype=bool)
    if inside.all():
        return [(-math.pi, math.pi)]
    if not inside.any():
        return []
    edges = numpy.flatnonzero(inside != numpy.roll(inside, -1))
    low, high, rising = grid[edges], grid[edges] + step, ~inside[edges]
    for _ in range(60):
        middle = 0.5 * (low + high)
        same = numpy.asarray(assembled(middle), dtype=bool) == inside[edges]
        low, high = numpy.where(same, middle, low), numpy.where(same, high, middle)
    # The boundary points are reachable: rising edges start at `high`, falling edges end at `low`.
    marks = sorted(zip(numpy.where(rising, high, low).tolist(), rising.tolist()))
    if not marks[0][1]:  # the first interval began before -pi: start it a turn earlier
        marks.append((marks[0][0] + 2 * math.pi, False))
        marks = marks[1:]
    return [(start, end) for (start, _), (end, _) in zip(marks[::2], marks[1::2])]


def _spans_text(spans: list[tuple[float, float]] | str, units: str) -> str:
    """A reachable crank range for messages: intervals in ``units``, or a sentence as it is."""
    from .cli import describe_spans

    return spans if isinstance(spans, str) else describe_spans(spans, units)


# --- the command ------------------------------------------------------------------

def _description(table: Table, linkage: Linkage) -> str:
    lines = [table.summary + ".", "", "csv header: " + ",".join(table_columns(linkage))]
    return "\n".join(lines + (["", table.notes] if table.notes else []))


def add_table_command(commands: argparse._SubParsersAction, table: Table) -> argparse.ArgumentParser:
    """Register the command of ``table``; returns its parser.

    The linkage is built, and the command's options added, only when the
    command is used: every other command starts without that symbolic work.
    """
    return commands.add_parser(table.linkage, help=table.summary,
                               formatter_class=argparse.RawDescriptionHelpFormatter,
                               populate=lambda command: _add_options(command, table))


def _add_options(command: argparse.ArgumentParser, table: Table) -> None:
    """The options of ``table``'s command, from its catalog linkage."""
    from .cli import add_sweep_options, finite

    linkage = catalog_linkage(table.linkage)
    command.description = _description(table, linkage)
    for option in table.options:
        default = "" if option.default is None else f"; default {option.default:g}"
        command.add_argument(f"--{option.name}", type=finite, required=option.default is None,
                             default=option.default, metavar=option.metavar,
                             help=f"{option.symbol} = {option.meaning}{default}")
    for x in linkage.inputs[1:]:
        role = _label(linkage, x)
        command.add_argument(f"--{role}-angle", type=finite, required=True, metavar="DEG",
                             help=f"{x.name} = {role} angle when the crank is at 0 (in --units)")
        command.add_argument(f"--{role}-ratio", type=finite, default=0.0, metavar="R",
                             help=f"{x.name} = {role}-angle + R * crank: {role} turns R times as fast as the "
                                  "crank (default 0: held still)")
    add_sweep_options(command, branch=len(linkage.branches) == 1)
    if len(linkage.branches) > 1:
        command.add_argument("--branch", type=loop_branches(len(linkage.branches)), default="both",
                             metavar="+1|-1|both[,...]",
                             help="both (default: every combination), one sign for every loop, or one of "
                                  "+1, -1, both a loop, in solve-plan order, separated by commas")
    if not linkage.has_closed_form:
        names = ", ".join(_label(linkage, u) for u in linkage.unknowns)
        command.add_argument("--guess", type=_guess, metavar="NAME=ANGLE,...",
                             help=f"start from the assembly nearest these angles at the first crank angle "
                                  f"(names: {names}; any of them; in --units)")
        if table.assemblies is not None:
            command.add_argument("--list-assemblies", action="store_true",
                                 help="print the assemblies found at the first crank angle and exit")
    command.set_defaults(run=lambda args: run_table(table, args))


def _values(table: Table, linkage: Linkage, args: argparse.Namespace) -> dict[str, float]:
    """The parameter values by symbol name (angles in radians), lengths checked, by option name."""
    lengths = {option.name: getattr(args, option.name.replace("-", "_"))
               for option in table.options if option.kind == LENGTH}
    check_lengths(**lengths)
    values = {}
    for option in table.options:
        value = getattr(args, option.name.replace("-", "_"))
        values[option.symbol] = float(to_radians(value, args.units)) if option.kind == ANGLE else value
    for x in linkage.inputs[1:]:
        role = _label(linkage, x).replace("-", "_")
        values[x.name] = float(to_radians(getattr(args, f"{role}_angle"), args.units))
        values[f"{x.name}_ratio"] = getattr(args, f"{role}_ratio")
    return values


def _input_values(linkage: Linkage, values: Mapping[str, float], theta, speeds, accel) -> dict:
    """The inputs, their rates and accelerations along the sweep (further inputs geared to the crank)."""
    first, *further = linkage.inputs
    inputs = {first.name: theta, rate(first).name: speeds, acceleration(first).name: accel}
    for x in further:
        ratio = values[f"{x.name}_ratio"]
        inputs.update({x.name: values[x.name] + ratio * numpy.asarray(theta), rate(x).name: ratio * speeds,
                       acceleration(x).name: ratio * accel})
    return inputs


def _branch_signs(linkage: Linkage, args: argparse.Namespace) -> dict[object, dict[str, int]]:
    """The branch column's value and the branch arguments, for each branch asked for."""
    from .cli import branches

    names = [b.name for b in linkage.branches]
    if not names:
        return {1: {}}
    if len(names) == 1:
        return {sign: {names[0]: sign} for sign in branches(args)}
    return {"/".join(f"{s:+d}" for s in signs): dict(zip(names, signs)) for signs in itertools.product(*args.branch)}


def _closed_form(table: Table, linkage: Linkage, values: dict, inputs: dict, args: argparse.Namespace):
    """Results for each branch asked for, and a function giving the reachable crank range of each."""
    outputs = _outputs(linkage)
    solver = Solver(linkage, list(outputs.values()))
    parameters = {s.name: values[s.name] for s in linkage.parameters}
    choices = _branch_signs(linkage, args)

    def solve(branch: Mapping[str, int], given: Mapping) -> dict:
        result = solver(**given, **parameters, **branch)
        assembled = result["assembled"]
        if table.undetermined is not None:
            assembled = assembled & ~table.undetermined(values, result)
        solved = {column: result[name] for column, name in outputs.items()}
        return {**solved, **{_label(linkage, x): given[x.name] for x in linkage.inputs[1:]}, "assembled": assembled}

    results = {key: solve(branch, inputs) for key, branch in choices.items()}

    def reachable():
        known = table.reachable(values) if table.reachable is not None else None
        if known is not None:
            return _spans_text(known, args.units)

        def assembled(branch, theta):
            return solve(branch, _input_values(linkage, values, theta, 0.0, 0.0))["assembled"]

        texts = {key: _spans_text(scanned_range(lambda t, b=branch: assembled(b, t)), args.units)
                 for key, branch in choices.items()}
        return texts if len(set(texts.values())) > 1 else next(iter(texts.values()))

    return results, reachable


def _start(table: Table, linkage: Linkage, values: dict, theta: float, args: argparse.Namespace):
    """The assemblies to continue from at the first crank angle, in the order they are tried."""
    labels = {_label(linkage, u): u.name for u in linkage.unknowns}
    found = table.assemblies(theta, values) if table.assemblies is not None else []
    if args.guess is None:
        return found
    wrong = sorted(set(args.guess) - set(labels))
    if wrong:
        raise ValueError(f"--guess names {', '.join(wrong)}; {linkage.name} has {', '.join(labels)}")
    guess = {labels[name]: float(to_radians(value, args.units)) for name, value in args.guess.items()}
    if found:  # the nearest: the largest wrapped difference of the angles named
        return [min(found, key=lambda q: max(abs(float(wrap(q[n] - v))) for n, v in guess.items()))]
    return [guess] if len(guess) == len(labels) else []


def _numeric(table: Table, linkage: Linkage, values: dict, inputs: dict, angles, args: argparse.Namespace):
    """Results of the Newton solver, continued from the first assembly (of those chosen) that gets through."""
    theta = inputs[linkage.inputs[0].name]
    candidates = _start(table, linkage, values, float(theta[0]), args)
    if not candidates:
        first = f"{float(wrap(angles[0], half_turn(args.units))):.6g} {args.units}"
        if table.assemblies is None:
            raise ValueError(f"{linkage.name} needs a --guess of every unknown "
                             f"({', '.join(_label(linkage, u) for u in linkage.unknowns)}) at crank angle {first}")
        raise ValueError(f"{linkage.name} cannot be assembled at the first crank angle, {first} "
                         "(its scan for assemblies finds none)")
    solver = NumericSolver(linkage)
    parameters = {s.name: values[s.name] for s in linkage.parameters}
    failure = None
    for start in candidates:
        try:
            result = solver(guess=start, **inputs, **parameters)
        except ValueError as error:
            failure = failure or error
            continue
        columns = {column: result[name] for column, name in _outputs(linkage).items()}
        return {1: {**columns, "assembled": result["assembled"]}}
    raise failure


def _print_assemblies(table: Table, linkage: Linkage, values: dict, angles, args: argparse.Namespace) -> None:
    """``--list-assemblies``: the assemblies at the first crank angle, angles wrapped, in the table's format."""
    from .cli import print_rows

    theta = float(to_radians(angles[0], args.units))
    shown = (linkage.inputs[0],) + linkage.unknowns
    columns = [_label(linkage, q) for q in shown]
    rows = []
    for found in table.assemblies(theta, values):
        radians = {linkage.inputs[0].name: theta, **found}
        rows.append({_label(linkage, q): float(wrap(from_radians(radians[q.name], args.units), half_turn(args.units)))
                     for q in shown})
    print_rows(rows, columns, args.format)


def run_table(table: Table, args: argparse.Namespace) -> int:
    """Print the table of ``table``'s linkage for the parsed ``args``."""
    from .cli import assemble_rows, print_rows, sweep_angles

    linkage = catalog_linkage(table.linkage)
    values = _values(table, linkage, args)
    angles = sweep_angles(args)
    if getattr(args, "list_assemblies", False):
        _print_assemblies(table, linkage, values, angles, args)
        return 0
    theta = to_radians(angles, args.units)
    speeds = crank_speeds(theta, args.crank_speed, args.crank_accel)
    inputs = _input_values(linkage, values, theta, speeds, args.crank_accel)
    spans: str | dict = ""
    if linkage.has_closed_form:
        results, reachable = _closed_form(table, linkage, values, inputs, args)
        if not all(result["assembled"].all() for result in results.values()):
            spans = reachable()
    else:
        results = _numeric(table, linkage, values, inputs, angles, args)
    columns = table_columns(linkage)
    angle_columns = {_label(linkage, q) for q in linkage.coordinates if is_angle(linkage, q)}
    rows = assemble_rows(angles, results, columns, args.units, spans, angle_columns=angle_columns)
    print_rows(rows, columns, args.format)
    return 0


# --- the catalog's entries ----------------------------------------------------------

def _inverted_reachable(values: Mapping[str, float]) -> list[tuple[float, float]] | str:
    if values["a"] != values["d"]:
        return [(-math.pi, math.pi)]
    return "every crank angle but 0, where B passes over the rocker pivot D and the rocker angle is undetermined"


def _inverted_undetermined(values: Mapping[str, float], result: Mapping[str, numpy.ndarray]) -> numpy.ndarray:
    """B over D: the block sits on the pivot and the rocker angle follows from nothing."""
    return result["r"] <= 64 * numpy.finfo(float).eps * (values["a"] + values["d"])


def _fivebar_reachable(values: Mapping[str, float]) -> list[tuple[float, float]] | str | None:
    """Crank 2 held still: a four-bar over the ground A -> D (an exact range); geared: a scan."""
    ratio = values["psi_ratio"]
    if ratio != 0:
        if ratio != round(ratio):
            return "not periodic in the crank angle for a non-integer --crank2-ratio; not computed"
        return None
    D = values["d"] + values["e"] * complex(math.cos(values["psi"]), math.sin(values["psi"]))
    a, b, c = values["a"], values["b"], values["c"]
    if abs(D) <= 64 * numpy.finfo(float).eps * (values["d"] + values["e"]):  # D on A: |BD| = a everywhere
        return [(-math.pi, math.pi)] if abs(b - c) <= a <= b + c else []
    spans = crank_range(a, b, c, abs(D))
    if spans == [(-math.pi, math.pi)]:
        return spans
    turn = math.atan2(D.imag, D.real)
    shifted = [(low + turn, high + turn) for low, high in spans]
    return [(low - 2 * math.pi, high - 2 * math.pi) if low > math.pi else
            (low + 2 * math.pi, high + 2 * math.pi) if low <= -math.pi else (low, high) for low, high in shifted]


INVERTED = Table(
    "inverted-slider-crank", "positions, speeds and accelerations of an inverted slider-crank (crank-shaper)",
    (Option("crank", "a", "A", "crank length AB"),
     Option("ground", "d", "D", "distance AD to the rocker pivot D = (d, 0)")),
    notes="One assembly (the block at distance slider = r >= 0 along the rocker), printed as branch +1; "
          "no --branch.\nThe slider column is r = DB in the length unit, its speed and acceleration per "
          "second and per second squared.\nWhere B passes over D (crank = ground, crank angle 0) the rocker "
          "angle is undetermined: that angle is left out.",
    reachable=_inverted_reachable, undetermined=_inverted_undetermined)

WATT2 = Table(
    "watt2", "positions, speeds and accelerations of a Watt II six-bar",
    (Option("crank", "a", "A", "crank length AB"),
     Option("coupler", "b", "B", "coupler length BC"),
     Option("rocker", "c", "C", "rocker length DC"),
     Option("ground", "d", "D", "ground length AD, D = (d, 0)"),
     Option("rocker-arm", "e", "E", "second arm DE of the ternary rocker DCE"),
     Option("rocker-arm-angle", "alpha", "ALPHA", "angle from DC to DE, counter-clockwise (in --units)",
            kind=ANGLE),
     Option("coupler2", "f", "F", "second coupler length EF"),
     Option("output", "g", "G", "output rocker length GF"),
     Option("output-x", "gx", "GX", "x of the output rocker's pivot G", kind=NUMBER),
     Option("output-y", "gy", "GY", "y of the output rocker's pivot G", kind=NUMBER)),
    notes="Branch: one sign a loop, ABCD then DEFG, as in the four-bar: +1 puts C left of B->D and F left "
          "of E->G.\nThe reachable crank range of a branch is found by a scan (0.1 deg, edges bisected).")

STEPHENSON3 = Table(
    "stephenson3", "positions, speeds and accelerations of a Stephenson III six-bar (numeric)",
    (Option("crank", "a", "A", "crank length AB"),
     Option("coupler", "b", "B", "side BC of the ternary coupler BCE"),
     Option("coupler-arm", "e", "E", "side BE of the ternary coupler"),
     Option("coupler-arm-angle", "alpha", "ALPHA", "angle from BC to BE, counter-clockwise (in --units)",
            kind=ANGLE),
     Option("rocker", "f", "F", "side DF of the ternary rocker DFH"),
     Option("rocker-arm", "h", "H", "side DH of the ternary rocker"),
     Option("rocker-arm-angle", "delta", "DELTA", "angle from DF to DH, counter-clockwise (in --units)",
            kind=ANGLE),
     Option("link-cf", "c", "C", "binary link CF (its angle is the mu column)"),
     Option("link-eh", "g", "G", "binary link EH (its angle is the eta column)"),
     Option("ground", "d", "D", "ground length AD, D = (d, 0)")),
    notes="No closed form: Newton's method continued along the sweep (in the order given) from one assembly "
          "at the first crank angle, printed as branch +1; no --branch.\nThe assemblies there are found by a "
          "scan of the coupler angle (--list-assemblies prints them); --guess picks the nearest, and by "
          "default the first in order of the coupler angle that continues over the whole sweep is used.\n"
          "Where Newton's method does not converge (the linkage cannot be assembled, or a dead centre) the "
          "command stops with one line naming the crank angle.",
    assemblies=lambda theta, values: stephenson3_assemblies(theta, **{k: values[k] for k in "abcdefgh"},
                                                            alpha=values["alpha"], delta=values["delta"]))

FIVEBAR = Table(
    "fivebar", "positions, speeds and accelerations of a five-bar with two driven cranks",
    (Option("crank", "a", "A", "crank length AB (the swept input, theta)"),
     Option("coupler", "b", "B", "coupler length BC"),
     Option("coupler2", "c", "C", "second coupler length DC"),
     Option("crank2", "e", "E", "second crank length ED (input psi)"),
     Option("ground", "d", "D", "ground length AE, E = (d, 0)")),
    notes="Branch +1 puts C left of the line B->D.\nWith crank 2 held still (ratio 0) the reachable crank "
          "range is exact (a four-bar over A->D); with an integer ratio it is found by a scan.",
    reachable=_fivebar_reachable)

#: The table commands of this module (``symlink slider-crank`` is registered by :mod:`symlink.cli_slider`).
TABLES = (INVERTED, WATT2, STEPHENSON3, FIVEBAR)


def add_commands(commands: argparse._SubParsersAction) -> None:
    """Register ``symlink inverted-slider-crank``, ``watt2``, ``stephenson3`` and ``fivebar``."""
    for table in TABLES:
        add_table_command(commands, table)
