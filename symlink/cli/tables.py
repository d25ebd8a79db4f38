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
  (:class:`symlink.numeric.solver.NumericSolver`), continued along the sweep from an assembly at the
  first crank angle: the one nearest ``--guess``, or by default the first (in
  the order the entry lists them: Stephenson II by coupler angle) that
  continues over the whole sweep.

>>> from symlink.io.scene import catalog_linkage
>>> print(", ".join(table_columns(catalog_linkage("watt2"))))
crank, branch, coupler, rocker, coupler2, output, coupler_speed, rocker_speed, coupler2_speed, output_speed, coupler_accel, rocker_accel, coupler2_accel, output_accel
>>> loop_branches(2)("+1,both")
[(1,), (1, -1)]
"""
from __future__ import annotations

import argparse
import itertools
import warnings
from typing import TYPE_CHECKING, Any, Callable, Collection, Iterable, Mapping, NamedTuple

import numpy

from ..common.angles import from_radians, half_turn, to_radians, wrap
from ..common.names import FORMER_CATALOG_NAMES, SixBarNameNote, former_name_note
from ..numeric.input_sweep import InputSweep, crank_speeds, table_inputs
from ..io.table_source import TableSource, facts_values, table_columns, table_facts
from .options import (add_fourbar_lengths, add_sweep_options, angle, assignments, branches, command_help, finite,
                      fourbar_lengths, input_sweep)
from .output import RowWriter, TableAssembler, print_rows

if TYPE_CHECKING:
    from ..symbolic.linkage import Linkage

# The symbolic side (linkages, their labels, Solver: SymPy) is imported inside the functions that need it, so
# that ``symlink fourbar`` with its code in the disk cache never imports SymPy (symlink.numeric.cached_solver).

__all__ = ["Option", "Table", "TABLES", "table_columns", "loop_branches", "write_table", "register"]

LENGTH, NUMBER, ANGLE = "length", "number", "angle"
FOURBAR_COLUMNS = ["crank", "branch", "coupler", "rocker", "coupler_speed", "rocker_speed",
                   "coupler_accel", "rocker_accel", "transmission"]
ANGLE_COLUMNS = {"crank", "coupler", "rocker"}


class Option(NamedTuple):
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


class Table(NamedTuple):
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
    example: str
    notes: str = ""
    reachable: Callable[[Mapping[str, float]], list[tuple[float, float]] | str | None] | None = None
    undetermined: Callable[[Mapping[str, float], Mapping[str, numpy.ndarray]], numpy.ndarray] | None = None
    assemblies: Callable[[float, Mapping[str, float]], list[dict[str, float]]] | None = None


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


_guess = assignments("NAME=ANGLE")


def _spans_text(spans: list[tuple[float, float]] | str, units: str) -> str:
    """A reachable crank range for messages: intervals in ``units``, or a sentence as it is."""
    from ..numeric.crank_ranges import describe_spans
    return spans if isinstance(spans, str) else describe_spans(spans, units)


# --- the command ------------------------------------------------------------------

def _description(table: Table, facts: Mapping[str, Any]) -> str:
    lines = [table.summary[0].upper() + table.summary[1:] + ".", "",
             "units: lengths in any one unit; angles in --units (deg by default), speeds rad/s, "
             "accelerations rad/s^2",
             f"example: symlink {table.linkage} {table.example}", "",
             "csv header: " + ",".join(facts["columns"])]
    return "\n".join(lines + (["", table.notes] if table.notes else []))


def add_table_command(commands: argparse._SubParsersAction, table: Table) -> argparse.ArgumentParser:
    """Register the command of ``table``; returns its parser.

    The command's options are added only when the command is used, from its linkage's table facts (the disk
    cache: :class:`TableSource`): every other command starts without that work, and a warm one without SymPy.
    """
    return commands.add_parser(table.linkage, help=table.summary,
                               populate=lambda command: _add_options(command, table))


def _add_options(command: argparse.ArgumentParser, table: Table) -> TableSource:
    """The options of ``table``'s command, from its catalog linkage's table facts; returns where they came from."""
    source = TableSource(table.linkage)
    facts = source.facts
    command.description = _description(table, facts)
    for option in table.options:
        default = "" if option.default is None else f"; default {option.default:g}"
        command.add_argument(f"--{option.name}", type=finite, required=option.default is None,
                             default=option.default, metavar=option.metavar,
                             help=f"{option.symbol} = {option.meaning}{default}")
    for name in facts["inputs"][1:]:
        role = facts["labels"][name]
        command.add_argument(f"--{role}-angle", type=angle, required=True, metavar="DEG",
                             help=f"{name} = {role} angle when the crank is at 0 (in --units)")
        command.add_argument(f"--{role}-ratio", type=finite, default=0.0, metavar="R",
                             help=f"{name} = {role}-angle + R * crank: {role} turns R times as fast as the "
                                  "crank (default 0: held still)")
    loops = len(facts["branches"])
    add_sweep_options(command, branch=loops == 1)
    if loops > 1:
        command.add_argument("--branch", type=loop_branches(loops), default="both",
                             metavar="+1|-1|both[,...]",
                             help="both (default: every combination), one sign for every loop, or one of "
                                  "+1, -1, both a loop, in solve-plan order, separated by commas")
    if not facts["closed_form"]:
        names = ", ".join(facts["newton"]["unknowns"])
        command.add_argument("--guess", type=_guess, metavar="NAME=ANGLE,...",
                             help=f"start from the assembly nearest these angles at the first crank angle "
                                  f"(names: {names}; any of them; in --units)")
        if table.assemblies is not None:
            command.add_argument("--list-assemblies", action="store_true",
                                 help="print the assemblies found at the first crank angle and exit")
    command.set_defaults(run=lambda args: run_table(table, args, source))
    return source


def _values(table: Table, facts: Mapping[str, Any], args: argparse.Namespace,
            check_lengths: Callable[..., None]) -> dict[str, float]:
    """The parameter values by symbol name (angles in radians), lengths checked (``check_lengths``), by option name."""
    lengths = {option.name: getattr(args, option.name.replace("-", "_"))
               for option in table.options if option.kind == LENGTH}
    check_lengths(**lengths)
    values = {}
    for option in table.options:
        value = getattr(args, option.name.replace("-", "_"))
        values[option.symbol] = float(to_radians(value, args.units)) if option.kind == ANGLE else value
    for name in facts["inputs"][1:]:
        role = facts["labels"][name].replace("-", "_")
        values[name] = float(to_radians(getattr(args, f"{role}_angle"), args.units))
        values[f"{name}_ratio"] = getattr(args, f"{role}_ratio")
    return values


def _branch_signs(facts: Mapping[str, Any], args: argparse.Namespace) -> dict[object, dict[str, int]]:
    """The branch column's value and the branch arguments, for each branch asked for."""
    names = facts["branches"]
    if not names:
        return {1: {}}
    if len(names) == 1:
        return {sign: {names[0]: sign} for sign in branches(args)}
    return {"/".join(f"{s:+d}" for s in signs): dict(zip(names, signs)) for signs in itertools.product(*args.branch)}


def _closed_form(table: Table, facts: Mapping[str, Any], solver: Any, values: dict, args: argparse.Namespace):
    """A solver of one block of inputs for each branch asked for, and the reachable crank range of each.

    ``solver`` solves ``facts["outputs"]`` (a :class:`~symlink.numeric.solver.Solver` or a cached one).
    """
    outputs = facts["outputs"]
    parameters = {name: values[name] for name in facts["parameters"]}
    choices = _branch_signs(facts, args)
    further = [(name, facts["labels"][name]) for name in facts["inputs"][1:]]

    def solve(branch: Mapping[str, int], given: Mapping) -> dict:
        result = solver(**given, **parameters, **branch)
        assembled = result["assembled"]
        if table.undetermined is not None:
            assembled = assembled & ~table.undetermined(values, result)
        solved = {column: result[name] for column, name in outputs.items()}
        flag = {"singular": result["singular"]} if "singular" in result else {}
        return {**solved, **{column: given[name] for name, column in further}, **flag, "assembled": assembled}

    def solve_block(inputs: Mapping) -> dict:
        return {key: solve(branch, inputs) for key, branch in choices.items()}

    def reachable():
        known = table.reachable(values) if table.reachable is not None else None
        if known is not None:
            return _spans_text(known, args.units)
        from ..numeric.crank_ranges import scanned_range

        def assembled(branch, theta):
            return solve(branch, table_inputs(facts, values, theta, 0.0, 0.0))["assembled"]

        texts = {key: _spans_text(scanned_range(lambda t, b=branch: assembled(b, t)), args.units)
                 for key, branch in choices.items()}
        return texts if len(set(texts.values())) > 1 else next(iter(texts.values()))

    return solve_block, reachable


def _start(table: Table, name: str, labels: Mapping[str, str], values: dict, theta: float,
           args: argparse.Namespace):
    """The assemblies to continue from at the first crank angle, in the order they are tried (``labels``: the
    column label of each unknown, and its name)."""
    found = table.assemblies(theta, values) if table.assemblies is not None else []
    if args.guess is None:
        return found
    wrong = sorted(set(args.guess) - set(labels))
    if wrong:
        raise ValueError(f"--guess names {', '.join(wrong)}; {name} has {', '.join(labels)}")
    guess = {labels[label]: float(to_radians(value, args.units)) for label, value in args.guess.items()}
    if found:  # the nearest: the largest wrapped difference of the angles named
        return [min(found, key=lambda q: max(abs(float(wrap(q[n] - v))) for n, v in guess.items()))]
    return [guess] if len(guess) == len(labels) else []


def _newton_solver(linkage: Linkage | None, solver: Any) -> Callable[[], Any]:
    """What makes the Newton solver of a table: ``solver`` where the caller has one (a cached one), else a
    :class:`~symlink.numeric.solver.NumericSolver` of ``linkage``, made when called."""
    if solver is not None:
        return lambda: solver

    def made() -> Any:
        from ..numeric.solver import NumericSolver
        assert linkage is not None
        return NumericSolver(linkage)
    return made


def _numeric(table: Table, facts: Mapping[str, Any], solver: Callable[[], Any], values: dict, inputs: dict, angles,
             args: argparse.Namespace):
    """Results of the Newton solver (:func:`symlink.numeric.newton_table.newton_results`), continued from the first
    assembly (of those chosen: :func:`_start`) that gets through.

    ``facts``: :func:`table_facts` (its ``newton`` entry, :func:`newton_facts`); ``solver`` makes the solver (a
    :class:`~symlink.numeric.solver.NumericSolver` or a cached one), once a start is known.
    """
    name, newton = facts["name"], facts["newton"]
    theta = inputs[facts["inputs"][0]]
    candidates = _start(table, name, newton["unknowns"], values, float(theta[0]), args)
    if not candidates:
        first = f"{float(wrap(angles[0], half_turn(args.units))):.6g} {args.units}"
        if table.assemblies is None:
            raise ValueError(f"{name} needs a --guess of every unknown ({', '.join(newton['unknowns'])}) at crank "
                             f"angle {first}")
        raise ValueError(f"{name} cannot be assembled at the first crank angle, {first} "
                         "(its scan for assemblies finds none)")
    from ..numeric.newton_table import newton_results
    return newton_results(facts, solver, values, inputs, candidates,
                          advice=lambda fits: f"use at most {fits:,} crank angles (a larger --step or fewer --angles)")


def _print_assemblies(table: Table, facts: Mapping[str, Any], values: dict, first: float,
                      args: argparse.Namespace) -> None:
    """``--list-assemblies``: the assemblies at the first crank angle, angles wrapped, in the table's format."""
    theta = float(to_radians(first, args.units))
    crank = facts["inputs"][0]
    shown = {facts["labels"][crank]: crank, **facts["newton"]["unknowns"]}  # column label: name
    rows = []
    assert table.assemblies is not None  # the option exists only for tables that list assemblies
    for found in table.assemblies(theta, values):
        radians = {crank: theta, **found}
        rows.append({column: float(wrap(from_radians(radians[name], args.units), half_turn(args.units)))
                     for column, name in shown.items()})
    print_rows(rows, list(shown), args.format)


def shown_units(units_in_radians: Mapping[str, str], units: str) -> dict[str, str]:
    """The unit of each column as a table's header shows it: angles in ``units`` (deg or rad), rates per second.

    >>> shown_units({"crank": "rad", "conrod_speed": "rad/s"}, "deg")
    {'crank': 'deg', 'conrod_speed': 'rad/s'}
    """
    return {name: units if unit == "rad" else unit for name, unit in units_in_radians.items()}


def write_table(blocks: Iterable[tuple[numpy.ndarray, Mapping[object, Mapping[str, numpy.ndarray]]]],
                columns: list[str], units: str, fmt: str, angle_columns: Collection[str],
                spans: Callable[[], str | Mapping[object, str]],
                column_units: Mapping[str, str] | None = None) -> None:
    """Print a table block by block: ``blocks`` yields input angles (in ``units``) and each branch's results.

    Rows that cannot be assembled are left out and named on stderr, with the
    reachable range ``spans()``; nothing at all assembled is a ``ValueError``
    (and nothing is printed).  ``column_units`` are shown in a table's header.
    """
    assembler = TableAssembler(columns, units, angle_columns)
    writer = RowWriter(columns, fmt, units=column_units)
    for angles, results in blocks:
        writer.write(assembler.rows_of(angles, results))
    assembler.finish(spans)
    writer.close()


def _check_crank_speeds(sweep: InputSweep, units: str, speed: float, accel: float) -> None:
    """``ValueError`` before anything is printed if a uniformly accelerated crank stops within the sweep."""
    if accel != 0:
        first = float(to_radians(sweep.first, units))
        for angles in sweep.blocks():
            crank_speeds(to_radians(angles, units), speed, accel, first)


def _speeds_at(sweep: InputSweep, args: argparse.Namespace) -> Callable[[numpy.ndarray], tuple]:
    """Crank angles (radians) and speeds at a block of the sweep (in the command's units)."""
    first = float(to_radians(sweep.first, args.units))

    def at(angles: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
        theta = to_radians(angles, args.units)
        return theta, crank_speeds(theta, args.crank_speed, args.crank_accel, first)

    return at


def run_table(table: Table, args: argparse.Namespace, source: TableSource | None = None) -> int:
    """Print the table of ``table``'s linkage for the parsed ``args`` (``source``: where its facts and solver
    come from; by default the catalog's entry)."""
    source = source or TableSource(table.linkage)
    solver = source.solver()
    return _print_table(table, None, _values(table, source.facts, args, solver.check_lengths), args, source.facts,
                        solver)


def _print_table(table: Table, linkage: Linkage | None, values: dict[str, float], args: argparse.Namespace,
                 facts: Mapping[str, Any] | None = None, solver: Any = None) -> int:
    """The table of ``linkage`` at parameter ``values`` (by symbol name, angles in radians).

    ``facts`` (:func:`table_facts`) and ``solver`` (of their outputs), where the caller has them: then a linkage
    with a closed form is not needed (None: a warm ``symlink table``, from the disk cache without SymPy).
    """
    if facts is None:
        assert linkage is not None
        facts = table_facts(linkage)

    sweep = input_sweep(args)
    if getattr(args, "list_assemblies", False):
        _print_assemblies(table, facts, values, sweep.first, args)
        return 0
    _check_crank_speeds(sweep, args.units, args.crank_speed, args.crank_accel)
    speeds_at = _speeds_at(sweep, args)

    def inputs_at(angles):
        theta, speeds = speeds_at(angles)
        return table_inputs(facts, values, theta, speeds, args.crank_accel)

    if facts["closed_form"]:
        if solver is None:
            from ..numeric.solver import Solver
            assert linkage is not None
            solver = Solver(linkage, list(facts["outputs"].values()))
        solve_block, reachable = _closed_form(table, facts, solver, values, args)
        blocks: Iterable[tuple[numpy.ndarray, Any]] = ((angles, solve_block(inputs_at(angles)))
                                                       for angles in sweep.blocks())
    else:  # Newton continues along the whole sweep: one block
        angles = sweep.array()
        blocks = [(angles, _numeric(table, facts, _newton_solver(linkage, solver), values, inputs_at(angles), angles,
                                    args))]
        reachable = lambda: ""  # noqa: E731 - the numeric solver stops with a message instead
    write_table(blocks, facts["columns"], args.units, args.format, set(facts["angle_columns"]), reachable,
                shown_units(facts["column_units"], args.units))
    return 0


# --- the catalog's entries ----------------------------------------------------------

def _reachability():
    """:mod:`symlink.numeric.crank_ranges`, imported when a table needs a reachable range (SymPy-free)."""
    from ..numeric import crank_ranges
    return crank_ranges


def _stephenson2_assemblies(theta: float, values: Mapping[str, float]) -> Any:
    """The Stephenson II's assemblies at crank angle ``theta`` (:mod:`symlink.numeric.assemblies`, imported when asked)."""
    from ..numeric.assemblies import stephenson2_assemblies
    return stephenson2_assemblies(theta, **{k: values[k] for k in "abcdefgh"}, alpha=values["alpha"],
                                  delta=values["delta"])


def _inverted_undetermined(values: Mapping[str, float], result: Mapping[str, numpy.ndarray]) -> numpy.ndarray:
    """B over D: the block sits on the pivot and the rocker angle follows from nothing."""
    return result["r"] <= 64 * numpy.finfo(float).eps * (values["a"] + values["d"])


INVERTED = Table(
    "inverted-slider-crank", "positions, speeds and accelerations of an inverted slider-crank (crank-shaper)",
    (Option("crank", "a", "A", "crank length AB"),
     Option("ground", "d", "D", "distance AD to the rocker pivot D = (d, 0)")),
    "--crank 2 --ground 1.2 --crank-speed 3 --step 40",
    notes="One assembly (the block at distance slider = r >= 0 along the rocker), printed as branch +1; "
          "no --branch.\nThe slider column is r = DB in the length unit, its speed and acceleration per "
          "second and per second squared.\nWhere B passes over D (crank = ground, crank angle 0) the rocker "
          "angle is undetermined: that angle is left out.",
    reachable=lambda values: _reachability().inverted_slider_crank_range(values), undetermined=_inverted_undetermined)

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
    "--crank 1 --coupler 3.5 --rocker 3 --ground 3.2 --rocker-arm 2 --rocker-arm-angle 35 --coupler2 4 "
    "--output 3 --output-x 4.5 --output-y 3.5 --angles 0,90 --branch +1,both",
    notes="Branch: one sign a loop, ABCD then DEFG, as in the four-bar: +1 puts C left of B->D and F left "
          "of E->G.\nThe reachable crank range of a branch is found by a scan (0.1 deg, edges bisected).")

STEPHENSON2 = Table(
    "stephenson2", "positions, speeds and accelerations of a Stephenson II six-bar (numeric)",
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
    "--crank 1 --coupler 3.1 --link-cf 2.2 --ground 4.5 --coupler-arm 3.9 --rocker 3.1 --link-eh 4.1 "
    "--rocker-arm 3.1 --coupler-arm-angle 51.5 --rocker-arm-angle 17.2 --step 30",
    notes="No closed form: Newton's method continued along the sweep (in the order given) from one assembly "
          "at the first crank angle, printed as branch +1; no --branch.\nThe assemblies there are found by a "
          "scan of the coupler angle (--list-assemblies prints them); --guess picks the nearest, and by "
          "default the first in order of the coupler angle that continues over the whole sweep is used.\n"
          "Where Newton's method does not converge (the linkage cannot be assembled, or a dead centre) the "
          "command stops with one line naming the crank angle.",
    assemblies=lambda theta, values: _stephenson2_assemblies(theta, values))

FIVEBAR = Table(
    "fivebar", "positions, speeds and accelerations of a five-bar with two driven cranks",
    (Option("crank", "a", "A", "crank length AB (the swept input, theta)"),
     Option("coupler", "b", "B", "coupler length BC"),
     Option("coupler2", "c", "C", "second coupler length DC"),
     Option("crank2", "e", "E", "second crank length ED (input psi)"),
     Option("ground", "d", "D", "ground length AE, E = (d, 0)")),
    "--crank 2 --coupler 3 --coupler2 3 --crank2 2 --ground 5 --crank2-angle 90 --step 30",
    notes="Branch +1 puts C left of the line B->D.\nWith crank 2 held still (ratio 0) the reachable crank "
          "range is exact (a four-bar over A->D); with an integer ratio it is found by a scan.",
    reachable=lambda values: _reachability().fivebar_range(values))

SLIDER = Table(
    "slider-crank", "positions, speeds and accelerations of a slider-crank",
    (Option("crank", "a", "A", "crank length AB"),
     Option("conrod", "b", "B", "connecting rod length BC"),
     Option("offset", "offset", "E", "the slider's line is y = offset (any sign)", kind=NUMBER, default=0.0)),
    "--crank 20 --conrod 66 --offset 5 --crank-speed 10 --step 90",
    notes="Branch +1 is the assembly with the larger slider position.\nThe slider column is its x on the "
          "line y = offset, in the length unit; its speed and acceleration per second and per second squared.",
    reachable=lambda values: _reachability().slider_crank_range(values["a"], values["b"], values["offset"]))

#: The table commands made from catalog entries, in the order ``symlink --help`` lists them.
TABLES = (SLIDER, INVERTED, WATT2, STEPHENSON2, FIVEBAR)


# --- symlink fourbar ------------------------------------------------------------------

def _add_fourbar_options(command: argparse.ArgumentParser) -> None:
    add_fourbar_lengths(command)
    add_sweep_options(command)
    from .dynamics import add_mass_options
    add_mass_options(command)
    from .pictures import add_fourbar_plot_options
    add_fourbar_plot_options(command)


def run_fourbar(args: argparse.Namespace) -> int:
    """``symlink fourbar``: the table of seed 003, and optionally its plots."""
    a, b, c, d = fourbar_lengths(args)
    from ..numeric.cached_solver import CachedSolver
    from .dynamics import MASS_COLUMNS, fourbar_dynamics_solver
    # the plain table: from the disk cache without SymPy, once derived (its generated check checks the lengths)
    solver = CachedSolver("fourbar", FOURBAR_COLUMNS[2:])
    solver.check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    sweep = input_sweep(args)
    _check_crank_speeds(sweep, args.units, args.crank_speed, args.crank_accel)
    speeds_at = _speeds_at(sweep, args)
    columns = FOURBAR_COLUMNS
    # with --masses: the torque and reactions, from the disk cache too (derived once, with SymPy)
    dynamic = fourbar_dynamics_solver(args, (a, b, c, d), FOURBAR_COLUMNS[2:] + MASS_COLUMNS)
    if dynamic is not None:
        solver, columns = dynamic, FOURBAR_COLUMNS + MASS_COLUMNS
    signs = branches(args)

    def blocks():
        for angles in sweep.blocks():
            theta, speeds = speeds_at(angles)
            yield angles, {sign: solver(theta=theta, a=a, b=b, c=c, d=d, branch=sign, thetadot=speeds,
                                        thetaddot=args.crank_accel) for sign in signs}

    def spans() -> str:
        from ..numeric.crank_ranges import crank_range, describe_spans
        return describe_spans(crank_range(a, b, c, d), args.units)

    write_table(blocks(), columns, args.units, args.format, ANGLE_COLUMNS, spans,
                {name: args.units if name in ANGLE_COLUMNS or name == "transmission" else
                 "rad/s" if name.endswith("_speed") else "rad/s^2" if name.endswith("_accel") else ""
                 for name in columns})
    if args.plot or args.plot_transmission:
        from .pictures import write_fourbar_plots
        write_fourbar_plots(a, b, c, d, signs, args.units, args.plot, args.plot_transmission)
    return 0


# --- symlink table NAME|FILE ---------------------------------------------------------

_assignments = assignments("NAME=VALUE")


def _add_generic_options(command: argparse.ArgumentParser) -> None:
    command.add_argument("linkage", metavar="NAME|FILE", help="a catalog linkage or a linkage file (.toml)")
    command.add_argument("--set", type=_assignments, default={}, metavar="NAME=VALUE,...",
                         help="parameter values by symbol (angles in --units); the rest from the file's defaults "
                              "(a catalog entry: its example values); NAME_ratio gears a further input to the crank")
    add_sweep_options(command, branch=False)
    command.add_argument("--branch", default="both", metavar="+1|-1|both[,...]",
                         help="both (default: every combination), one sign for every loop, or one of +1, -1, both "
                              "a loop, in solve-plan order, separated by commas")
    command.add_argument("--guess", type=_guess, metavar="NAME=ANGLE,...",
                         help="without a closed form: the assembly to start from at the first crank angle")
    command.set_defaults(run=run_generic_table)


def run_generic_table(args: argparse.Namespace) -> int:
    """``symlink table``: the table of any linkage, from the catalog or a file.

    A linkage with a closed form is tabulated from the disk cache: its facts (:func:`table_facts`) and its solver
    are keyed by the catalog name or the file's bytes, so that a warm table builds no linkage and imports no SymPy.
    """
    source = TableSource(args.linkage)
    facts = source.facts
    name, inputs = facts["name"], facts["inputs"]
    ratios = {f"{x}_ratio" for x in inputs[1:]}
    values = facts_values(facts, args.set, args.units, extra=sorted(ratios))
    if not inputs:
        raise ValueError(f"{name} has no input to sweep")
    if inputs[0] in args.set:
        raise ValueError(f"--set: {inputs[0]} is the swept input; give --start/--stop/--step or --angles")
    if args.guess is not None and facts["closed_form"]:
        raise ValueError(f"--guess: {name} is solved in closed form, where --branch chooses the assembly; "
                         "--guess is for linkages without a closed form")
    missing = [n for n in facts["parameters"] + inputs[1:] if n not in values]
    if missing:
        raise ValueError(f"{name} needs values for {', '.join(missing)} (--set NAME=VALUE,...)")
    values.update({ratio: values.get(ratio, 0.0) for ratio in ratios})
    lengths = {n: values[n] for n in facts["positive"]}
    solver = source.solver()
    if solver is not None:
        solver.check_lengths(**lengths)
    else:
        from ..numeric.solver import check_lengths
        check_lengths(**lengths)
    if len(facts["branches"]) > 1:
        try:
            args.branch = loop_branches(len(facts["branches"]))(args.branch)
        except argparse.ArgumentTypeError as error:
            raise ValueError(f"--branch: {error}") from None
    elif args.branch not in ("+1", "1", "-1", "both"):
        raise ValueError(f"--branch must be +1, -1 or both for {name}, got {args.branch!r}")
    table = Table(name, f"the table of {name}", (), "")
    linkage = None if solver is not None else source.found().linkage
    return _print_table(table, linkage, values, args, facts, solver)


def register(commands: argparse._SubParsersAction) -> None:
    """Register ``symlink fourbar``, ``symlink table`` and a table command for each entry of :data:`TABLES`."""
    commands.add_parser("fourbar", populate=_add_fourbar_options, **command_help(
        "positions, rates and accelerations of a four-bar, as a table",
        "lengths in any one unit; angles in --units (deg by default), speeds rad/s, accelerations rad/s^2",
        "symlink fourbar --crank 20 --coupler 66 --rocker 56 --ground 80 --crank-speed 10.5 --step 40",
        "csv header: " + ",".join(FOURBAR_COLUMNS))).set_defaults(run=run_fourbar)
    commands.add_parser("table", populate=_add_generic_options, **command_help(
        "positions, speeds and accelerations of any linkage (a catalog name or a linkage file), as a table",
        "lengths in any one unit; angles in --units (deg by default), speeds rad/s, accelerations rad/s^2",
        "symlink table jansen --step 90 --branch +1")).set_defaults(run=run_generic_table)
    for table in TABLES:
        add_table_command(commands, table)
    for former, current in FORMER_TABLE_COMMANDS.items():
        table = next(t for t in TABLES if t.linkage == current)
        commands.add_parser(former, help=f"{table.linkage}'s table, by its former name (a note says so)",
                            populate=lambda command, table=table, former=former: _add_former(command, table, former))


#: Table commands by a former name of their catalog linkage (symlink.mechanism.atlas.FORMER_SIX_BAR_NAMES), kept
#: working: a one-line note says what the name names now (symlink.common.names.former_name_note).
FORMER_TABLE_COMMANDS = FORMER_CATALOG_NAMES


def _add_former(command: argparse.ArgumentParser, table: Table, former: str) -> None:
    source = _add_options(command, table)
    command.description = (f"{former} is the former name of {table.linkage}: this is its table.\n\n"
                           + (command.description or "").replace(f"example: symlink {table.linkage} ",
                                                                 f"example: symlink {former} "))
    command.set_defaults(run=lambda args: _run_former(table, former, args, source))


def _run_former(table: Table, former: str, args: argparse.Namespace, source: TableSource) -> int:
    note = former_name_note(former)  # what the former name names now, in the words of every reader of it
    if FORMER_TABLE_COMMANDS.get(former) != table.linkage or note is None:
        raise ValueError(f"{former} no longer names {table.linkage}")
    warnings.warn(note, SixBarNameNote)
    return run_table(table, args, source)
