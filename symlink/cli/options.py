"""Parsing the command line: the parser, value types and the option groups that several commands share.

Every value is parsed as a number or a name, never as code.  Negative numbers
(``-1e-3``, ``--angles -90,0``) are values, not options.  A bad value is one
line of error and exit status 2.

>>> finite("1e3"), number_list("-90, 0,90")
(1000.0, [-90.0, 0.0, 90.0])
"""
from __future__ import annotations

import argparse
import math
import re
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Collection, Mapping, NoReturn, Sequence

from ..common.angles import to_radians
from ..common.files import excerpt
from ..common.numbers import number_from_text
from ..numeric.input_sweep import MAX_ANGLE, InputSweep

if TYPE_CHECKING:
    from ..io.linkage_file import LinkageFile

__all__ = ["UsageError", "Parser", "finite", "angle", "MAX_MAGNITUDE",
           "whole", "seed", "MAX_WHOLE", "number_list", "distinct_number_list", "name_list", "pair", "OutputPath", "OutputFolder", "output_file", "output_folder", "check_outputs", "refuse_together", "assignments", "figure_path", "add_sweep_options",
           "add_fourbar_lengths", "fourbar_lengths", "add_branch_option", "add_units_option", "add_format_option",
           "input_sweep", "branches", "command_help", "linkage_values", "fourbar_or_linkage",
           "require_held_inputs", "given_options"]

FOURBAR_LENGTHS = (("crank", "AB"), ("coupler", "BC"), ("rocker", "DC"), ("ground", "AD"))
FIGURE_SUFFIXES = (".png", ".svg")


class UsageError(ValueError):
    """Bad input from the command line."""


_NUMBER = r"(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?"
#: The attribute of a parsed namespace that lists the options given so far (see :class:`_StoreOnce`).
_GIVEN = "_symlink_options_given"


class _StoreOnce(argparse._StoreAction):
    """argparse's ``store``, refusing an option given twice: ``--vary c=1:2 --vary c=3:4`` would keep the last
    and drop the first without a word."""

    def __call__(self, parser, namespace, values, option_string=None):
        given = namespace.__dict__.setdefault(_GIVEN, set())
        if option_string is not None and self.dest in given:
            several = "NAME=" in str(self.metavar or "")
            raise argparse.ArgumentError(self, "given twice; give each option once" + (
                " (every NAME=... in one, separated by commas)" if several else ""))
        given.add(self.dest)
        super().__call__(parser, namespace, values, option_string)


# argparse passes each of its messages through gettext, which imports locale and looks on disk for a catalogue of
# the domain "messages" (some thirty looks to parse one command line, a few milliseconds of a warm table's start).
# CPython ships no such catalogue, and symlink's own messages are English: argparse's stay English too, unlooked-up.
argparse._ = str  # type: ignore[attr-defined]
argparse.ngettext = lambda singular, plural, count: singular if count == 1 else plural  # type: ignore[attr-defined]


class Parser(argparse.ArgumentParser):
    """argparse with one-line errors, and negative numbers (-1e-3, -70,0) taken as values, not options.

    ``populate`` adds a command's arguments when that command is used, so the
    command line starts without building every command's linkage.
    """

    #: Whether help is being formatted: only then is the terminal's width looked up (:meth:`_get_formatter`).
    _for_help = False

    def __init__(self, *args, populate: Callable[[argparse.ArgumentParser], None] | None = None, **kwargs):
        kwargs.setdefault("formatter_class", argparse.RawDescriptionHelpFormatter)
        super().__init__(*args, **kwargs)
        # -1,both and -0.1:0,0.2:0 (a list of numbers or of pairs, the first negative)
        self._negative_number_matcher = re.compile(rf"^-{_NUMBER}([,:]\s*([-+]?{_NUMBER}|both))*$")
        self._populate = populate
        self.register("action", None, _StoreOnce)
        self.register("action", "store", _StoreOnce)

    def parse_known_args(self, args=None, namespace=None):
        if self._populate is not None:
            populate, self._populate = self._populate, None
            populate(self)
        return super().parse_known_args(args, namespace)

    def format_help(self) -> str:
        if self._populate is not None:
            populate, self._populate = self._populate, None
            populate(self)
        self._for_help = True
        try:
            return super().format_help()
        finally:
            self._for_help = False

    def _get_formatter(self) -> argparse.HelpFormatter:
        # add_argument makes a formatter only to check a metavar, where the width does not matter; finding the
        # terminal's width imports shutil (and bz2, lzma with it): looked up for help only.
        if self._for_help:
            return super()._get_formatter()
        return self.formatter_class(prog=self.prog, width=80)  # type: ignore[call-arg]

    def error(self, message: str) -> NoReturn:  # one line, exit status 2, no usage dump
        raise UsageError(message)


def command_help(summary: str, units: str, example: str, more: str = "") -> dict:
    """``help`` and ``description`` of a subcommand: a one-line summary, its units and an example."""
    description = f"{summary[0].upper()}{summary[1:]}.\n\nunits: {units}\nexample: {example}"
    return {"help": summary, "description": description + (f"\n\n{more}" if more else "")}


#: Numbers on the command line beyond this size, or non-zero below its inverse, are refused: lengths, masses,
#: speeds and loads are multiplied together in the outputs, and 1e50 ** 6 is still a float.  The same bound as
#: linkage files (``symlink.io.linkage_file.MAX_MAGNITUDE``).
MAX_MAGNITUDE = 1e50


def _number(text: str) -> float:
    """:func:`~symlink.common.numbers.number_from_text` as an argparse type error (any digits, never rounded to
    0 or to infinity without a word)."""
    try:
        return number_from_text(text)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def finite(text: str) -> float:
    """A finite number from the command line (no expressions): 0 or between 1e-50 and 1e50 in size."""
    value = _number(text)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"not a finite number: {excerpt(text)}")
    if value != 0 and not 1 / MAX_MAGNITUDE <= abs(value) <= MAX_MAGNITUDE:
        raise argparse.ArgumentTypeError(f"{text} is out of range: numbers must be 0 or between "
                                         f"{1 / MAX_MAGNITUDE:g} and {MAX_MAGNITUDE:g} in size (change the units)")
    return value


def angle(text: str) -> float:
    """A finite angle from the command line, at most :data:`~symlink.numeric.input_sweep.MAX_ANGLE` in size (either unit)."""
    value = _number(text)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"not a finite number: {excerpt(text)}")
    if abs(value) > MAX_ANGLE:
        raise argparse.ArgumentTypeError(f"the angle {text} is more than {MAX_ANGLE:g} in size (larger angles have "
                                         "lost their precision)")
    return value


#: The largest whole number the command line takes (a count, a seed): the largest int64, what NumPy can count to.
MAX_WHOLE = 2 ** 63 - 1


def whole(text: str) -> int:
    """A whole number from the command line, at most :data:`MAX_WHOLE` in size (any digits: range-checked)."""
    stripped = text.strip()
    if not re.fullmatch(r"[-+]?\d+", stripped):
        raise argparse.ArgumentTypeError(f"not a whole number: {excerpt(text)}")
    if len(stripped.lstrip("+-").lstrip("0")) > 19 or abs(int(stripped)) > MAX_WHOLE:
        raise argparse.ArgumentTypeError(f"{excerpt(stripped)} is out of range: whole numbers are at most "
                                         f"{MAX_WHOLE:,} in size")
    return int(stripped)


def seed(text: str) -> int:
    """A random seed from the command line: a whole number from 0 to :data:`MAX_WHOLE`.

    >>> seed("7")
    7
    >>> seed("-1")
    Traceback (most recent call last):
    argparse.ArgumentTypeError: a --seed must be 0 or more (a whole number), got -1
    """
    value = whole(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"a --seed must be 0 or more (a whole number), got {value}")
    return value


def number_list(text: str) -> list[float]:
    """Comma-separated finite numbers."""
    return [finite(item) for item in text.split(",") if item.strip()]


def distinct_number_list(text: str) -> list[float]:
    """Comma-separated finite numbers, each once: a list that repeats a value asks for the same row twice.

    >>> distinct_number_list("0, 90")
    [0.0, 90.0]
    >>> distinct_number_list("10,10")
    Traceback (most recent call last):
    argparse.ArgumentTypeError: 10 appears more than once; list each value once
    """
    values = number_list(text)
    seen: set[float] = set()
    for value in values:
        if value in seen:
            raise argparse.ArgumentTypeError(f"{value:g} appears more than once; list each value once")
        seen.add(value)
    return values


def name_list(text: str) -> list[str]:
    """Comma-separated names (``--free a,b``, ``--outputs rocker,coupler``, ``--trace C,P``), each once: a list
    that repeats a name asks for the same thing twice.

    >>> name_list("a, b")
    ['a', 'b']
    >>> name_list("rocker,rocker")
    Traceback (most recent call last):
    argparse.ArgumentTypeError: 'rocker' appears more than once; list each name once
    """
    names = [item.strip() for item in text.split(",") if item.strip()]
    if not names:
        raise argparse.ArgumentTypeError(f"expected NAME[,NAME...], got {excerpt(text)}")
    for k, name in enumerate(names):
        if name in names[:k]:
            raise argparse.ArgumentTypeError(f"{excerpt(name)} appears more than once; list each name once")
    return names


def pair(what: str) -> Callable[[str], tuple[float, float]]:
    """A parser of two comma-separated numbers, named ``what`` in messages (``X,Y``, ``DIST,ANGLE``)."""
    def parse(text: str) -> tuple[float, float]:
        values = number_list(text)
        if len(values) != 2:
            raise argparse.ArgumentTypeError(f"expected {what} (two numbers), got {text!r}")
        return values[0], values[1]
    return parse


def assignments(what: str) -> Callable[[str], dict[str, float]]:
    """A parser of ``NAME=VALUE,...`` (numbers only), named ``what`` (``NAME=ANGLE``) in messages."""
    def parse(text: str) -> dict[str, float]:
        values = {}
        for item in text.split(","):
            name, equals, value = item.partition("=")
            if not equals or not name.strip():
                raise argparse.ArgumentTypeError(f"expected {what},..., got {excerpt(item.strip())}")
            if name.strip() in values:
                raise argparse.ArgumentTypeError(f"{excerpt(name.strip())} is given twice")
            values[name.strip()] = finite(value)
        return values
    return parse


def linkage_values(found: LinkageFile, settings: Mapping[str, float], units: str,
                   extra: Collection[str] = ()) -> dict[str, float]:
    """A linkage's values by symbol name: its defaults (a catalog entry's example values, see
    :func:`~symlink.io.linkage_file.load_linkage`) updated by ``--set`` (fixed angles and inputs in
    ``units``, stored in radians).

    Names other than the linkage's parameters, inputs and ``extra`` (a
    command's own settings, such as a geared input's ``psi_ratio``) are refused.
    """
    from ..symbolic.closure import is_angle
    linkage = found.linkage
    known = {s.name: s for s in linkage.parameters + linkage.inputs}
    for name in settings:
        if name not in known and name not in extra:
            raise ValueError(f"--set: {linkage.name} has no value {name!r}; it takes {', '.join([*known, *extra])}")
    values = dict(found.defaults)
    values.update({name: float(to_radians(value, units)) if name in known and is_angle(linkage, known[name]) else value
                   for name, value in settings.items()})
    return values


def require_held_inputs(linkage, settings: Mapping[str, float], command: str) -> None:
    """``ValueError`` unless every input of ``linkage`` after the first is given a value in ``settings`` (``--set``).

    ``command`` turns the first input only; holding the others at the file's defaults without a word would
    answer a question the user did not ask (a five-bar with one crank held still).
    """
    require_held_input_names(linkage.name, [q.name for q in linkage.inputs], settings, command)


def require_held_input_names(name: str, inputs: Sequence[str], settings: Mapping[str, float], command: str) -> None:
    """:func:`require_held_inputs` of the linkage ``name`` by its inputs' names (from its facts, without SymPy)."""
    if len(inputs) < 2:
        return
    unset = [q for q in inputs[1:] if q not in settings]
    if unset:
        raise ValueError(f"{name} has {len(inputs)} inputs ({', '.join(inputs)}) and {command} turns the first "
                         f"only: to hold the others still, give their values with --set {unset[0]}=VALUE"
                         f"{',...' if len(unset) > 1 else ''}")


class OutputPath(str):
    """A file (``folder`` False) or folder a command writes, as given: every one on a command line is checked
    before the command starts (:func:`check_outputs`), so a bad output fails before any work or output."""

    folder = False
    #: How a message names the option (None: ``--`` and the destination).
    label: str | None = None


class OutputFolder(OutputPath):
    """A folder a command writes into (created if missing)."""

    folder = True


def output_file(text: str) -> OutputPath:
    """The name of a file a command writes (checked by :func:`check_outputs`)."""
    return OutputPath(text)


def output_folder(text: str) -> OutputFolder:
    """The name of a folder a command writes into (checked by :func:`check_outputs`)."""
    return OutputFolder(text)


def _option_name(dest: str, value: OutputPath) -> str:
    return value.label or "--" + dest.replace("_", "-")


def check_outputs(args: argparse.Namespace) -> None:
    """Before a command starts: refuse two options that write one file (``UsageError`` naming both), and an
    output that cannot be written (``OSError`` naming it with the real reason: a folder or a file in the way,
    a read-only folder), so that a command fails before any work, output or file, never half way.

    >>> check_outputs(argparse.Namespace(plot=OutputPath("a.png"), plot_transmission=OutputPath("./a.png")))
    Traceback (most recent call last):
    symlink.cli.options.UsageError: --plot and --plot-transmission both write ./a.png: give each output its own file
    """
    import os

    from ..common.files import check_writable
    outputs = {dest: value for dest, value in vars(args).items() if isinstance(value, OutputPath) and value != "-"}
    seen: dict[str, str] = {}
    for dest, value in outputs.items():
        key = os.path.realpath(value)
        if key in seen:
            raise UsageError(f"{_option_name(seen[key], outputs[seen[key]])} and {_option_name(dest, value)} both write {excerpt(str(value))[1:-1]}:"
                             " give each output its own file")
        seen[key] = dest
    for value in outputs.values():
        check_writable(value, folder=value.folder)


def figure_path(text: str) -> OutputPath:
    """A .png or .svg file name."""
    if Path(text).suffix.lower() not in FIGURE_SUFFIXES:
        raise argparse.ArgumentTypeError(f"cannot draw into {text!r}: the file must end in "
                                         f"{' or '.join(FIGURE_SUFFIXES)}")
    return OutputPath(text)


def add_fourbar_lengths(parser: argparse.ArgumentParser, defaults: dict[str, float] | None = None,
                        beside_linkage: bool = False) -> None:
    """``--crank --coupler --rocker --ground``: required, or with ``defaults``; ``beside_linkage``: the
    four-bar form of a command that also takes a linkage NAME|FILE (see :func:`fourbar_or_linkage`)."""
    for option, what in FOURBAR_LENGTHS:
        if beside_linkage:
            default = "" if not defaults else f"; default {defaults[option]:g}"
            parser.add_argument(f"--{option}", type=finite, help=f"four-bar length {what} (without NAME{default})")
        elif defaults:
            parser.add_argument(f"--{option}", type=finite, default=defaults[option],
                                help=f"length {what} (default {defaults[option]:g})")
        else:
            parser.add_argument(f"--{option}", type=finite, required=True, help=f"length {what}")


def given_options(args: argparse.Namespace) -> set[str]:
    """The destinations of the options given on the command line (not left at their defaults)."""
    return set(getattr(args, _GIVEN, ()))


def fourbar_or_linkage(args: argparse.Namespace, command: str, lengths_required: bool = True,
                       linkage_only: Collection[str] = (), fourbar_only: Collection[str] = ()) -> bool:
    """Whether a command was given a linkage NAME|FILE (else the four-bar's lengths); ``ValueError`` for
    both, or (``lengths_required``) for neither, and for an option of the other form, which would do nothing
    (``linkage_only`` and ``fourbar_only`` name options by destination: ``coupler_point``)."""
    given = [v is not None for v in fourbar_lengths(args)]
    if args.linkage is not None and any(given):
        raise ValueError(f"{command}: give a catalog NAME or a linkage FILE, or the four-bar's --crank --coupler "
                         "--rocker --ground, not both")
    if args.linkage is None and lengths_required and not all(given):
        raise ValueError(f"{command}: give a catalog NAME (e.g. jansen) or a linkage FILE, or all of --crank "
                         "--coupler --rocker --ground")
    named = args.linkage is not None
    unused = sorted(given_options(args) & set(fourbar_only if named else linkage_only))
    if unused:
        option = "--" + unused[0].replace("_", "-")
        raise ValueError(f"{command}: {option} does nothing "
                         + (f"with a linkage NAME|FILE ({args.linkage}); it belongs to the four-bar form (--crank "
                            "--coupler --rocker --ground)" if named else
                            "in the four-bar form (--crank --coupler --rocker --ground); it belongs to a linkage "
                            "NAME|FILE"))
    return named


def refuse_together(args: argparse.Namespace, *conflicts: tuple[str, str, bool, str]) -> None:
    """``UsageError`` naming both options of the first conflict that holds: each is ``(destination, how it
    conflicts, naming the other option, whether that is in force, why)``, the first option counting when it
    was given on the command line (not left at its default).

    >>> args = argparse.Namespace(**{"workers": 2, _GIVEN: {"workers"}})
    >>> refuse_together(args, ("workers", "conflicts with --scheduler synchronous", True, "it runs in this process"))
    Traceback (most recent call last):
    symlink.cli.options.UsageError: --workers conflicts with --scheduler synchronous: it runs in this process
    """
    given = given_options(args)
    for dest, conflict, in_force, why in conflicts:
        if dest in given and in_force:
            raise UsageError(f"--{dest.replace('_', '-')} {conflict}: {why}")


def fourbar_lengths(args: argparse.Namespace) -> tuple[float, float, float, float]:
    """The four-bar's lengths a, b, c, d from ``--crank --coupler --rocker --ground``."""
    return args.crank, args.coupler, args.rocker, args.ground


def add_units_option(parser: argparse.ArgumentParser, what: str = "input and printed angles") -> None:
    parser.add_argument("--units", choices=["deg", "rad"], default="deg", help=f"of the {what} (default deg)")


def add_format_option(parser: argparse.ArgumentParser, formats=("table", "csv", "json")) -> None:
    parser.add_argument("--format", choices=list(formats), default=formats[0], help=f"default {formats[0]}")


def add_branch_option(parser: argparse.ArgumentParser, both: bool = True, default: str = "both") -> None:
    choices = ["+1", "1", "-1"] + (["both"] if both else [])
    parser.add_argument("--branch", choices=choices, default=default,
                        help=f"assembly: +1 (C left of B->D), -1{', or both' if both else ''} (default {default})")


def add_sweep_options(parser: argparse.ArgumentParser, branch: bool = True) -> None:
    """The input sweep and output options shared by the table commands (``branch=False``: no ``--branch``)."""
    parser.add_argument("--crank-speed", type=finite, default=0.0, metavar="W", help="rad/s (default 0)")
    parser.add_argument("--crank-accel", type=finite, default=0.0, metavar="AL",
                        help="rad/s^2, uniform from the first angle (default 0)")
    parser.add_argument("--start", type=angle, help="first crank angle (default 0)")
    parser.add_argument("--stop", type=angle, help="last crank angle, exclusive (default 360 deg)")
    parser.add_argument("--step", type=finite, help="crank angle step (default 10 deg)")
    parser.add_argument("--angles", type=distinct_number_list, metavar="LIST", help="comma-separated crank angles")
    if branch:
        add_branch_option(parser)
    add_units_option(parser)
    add_format_option(parser)


def input_sweep(args: argparse.Namespace) -> InputSweep:
    """The crank angles asked for by ``--start/--stop/--step`` or ``--angles``, in the command's units."""
    return InputSweep.from_options(args.start, args.stop, args.step, args.angles, args.units, prefix="--")


def branches(args: argparse.Namespace) -> list[int]:
    """The branch signs of ``--branch`` (``both``: +1 and -1)."""
    return [1, -1] if args.branch == "both" else [int(args.branch)]

