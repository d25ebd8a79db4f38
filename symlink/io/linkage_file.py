"""Linkage files: a new linkage in a TOML file, without writing Python.

A linkage file names the linkage's coordinates and constants, its vectors, its
loops as signed sums of vectors, its named points, roles and default values.
Numbers and names only: every expression is read by a small tokenizer and
parser of its own (below), never by ``eval``, ``sympify`` or ``parse_expr``.

The four-bar of the catalog as a file::

    name = "fourbar"
    inputs = ["theta"]                 # driven coordinates
    unknowns = ["beta", "phi"]         # what the loops determine, in the order that fixes each branch
    lengths = ["a", "b", "c", "d"]     # positive constants
    constants = []                     # other constants (fixed angles, signed offsets); may be left out

    [vectors]                          # name = [length, angle]
    AB = ["a", "theta"]
    BC = ["b", "beta"]
    DC = ["c", "phi"]
    AD = ["d", 0]

    [loops]                            # name = the vectors walked around the loop, each from where the last ends
    ABCD = "AD + DC - BC - AB"

    [points]                           # name = vectors walked from the origin ("0" is the origin)
    A = "0"
    B = "AB"
    C = "AB + BC"
    D = "AD"

    [roles]                            # plain names for coordinates
    crank = "theta"
    coupler = "beta"
    rocker = "phi"

    [defaults]                         # optional values of constants and inputs
    a = 20
    b = 66
    c = 56
    d = 80
    theta = "30 deg"

An optional ``[dynamics]`` table gives the bodies mass properties and the
linkage loads (see :mod:`symlink.dynamics.model`); with it the linkage also
has the dynamic outputs (``input_torque``, ``joint_B_x``, ``shaking_force_x``,
...; see :func:`LinkageFile.dynamic_linkage`)::

    [dynamics]
    gravity = [0, -9.81]               # frame components (default none)

    [dynamics.masses.crank]            # a moving body, by the name symlink.mechanism.bodies gives it
    mass = 1.2                         # a number, or a name (its value in [defaults])
    distance = 10                      # centre of mass: from origin (default the body's first joint),
    angle = "0 deg"                    # at this angle from the body's line (default 0)
    inertia = "I2"                     # about the centre of mass (default 0)
    origin = "A"

    [[dynamics.forces]]                # a force (frame components) at a point or joint
    point = "C"
    x = 0
    y = "-F"                           # a name's value in [defaults]; a leading - negates it

    [[dynamics.torques]]               # a couple on a body, counter-clockwise positive
    body = "rocker"
    torque = -15

    [[dynamics.springs]]               # tension stiffness * (length - free_length)
    first = "B"
    second = "D"
    stiffness = 100
    free_length = 50

    [[dynamics.dampers]]               # tension coefficient * (rate of the distance)
    first = "C"
    second = "D"
    coefficient = 2

A value is a number, a constant of the grammar below (``"30 deg"``), or a
name with an optional leading ``-``: the linkage's own constants keep their
meaning, other names become parameters of the dynamic outputs (give their
values under ``[defaults]`` or when evaluating).

The parameters of the generated functions are the lengths, then the
constants, in the order listed.  The grammar of a length, an angle or a
default value::

    sum      := ["-"] term (("+" | "-") term)*
    term     := name | constant
    constant := number ["/" number] [unit] | [number "*"] "pi" ["/" number]
    unit     := "deg" | "rad"                       (angles only)
    name     := a coordinate or constant of the file (ASCII letters, digits, _)

so ``"theta"``, ``0``, ``"pi/2"``, ``"-pi/2"``, ``"3*pi/4"``, ``"35 deg"``,
``"beta + 35 deg"`` and ``"phi + alpha"`` are all angles.  A name is never
multiplied: a vector turns with a coordinate or it does not.  A default
value is a number or a constant (``"30 deg"``).

Every value is checked where it is read, after evaluation: finite; an
angle at most 1e9 rad in size (``"1e308*pi"`` is refused, not wrapped); any
other value 0 or between 1e-50 and 1e50 in size (:data:`MAX_MAGNITUDE`);
fixed lengths positive; masses and inertias not negative.  A file is read
by :func:`~symlink.common.files.read_input` (a regular file of at most 4 MiB, never
a FIFO or a device); an expression has at most 100,000 characters and a
number 64, a table at most 1,000 entries: a hostile file is refused at
once, and the tokenizer and parser are linear in what they read.

Anything else is one line of error naming the file, the line and the
problem, such as ``fourbar.toml:9: vectors.AB: 'gamma' is not a coordinate
or constant of this file``.

>>> found = linkage_from_text('''
... name = "fourbar"
... inputs = ["theta"]
... unknowns = ["beta", "phi"]
... lengths = ["a", "b", "c", "d"]
... [vectors]
... AB = ["a", "theta"]
... BC = ["b", "beta"]
... DC = ["c", "phi"]
... AD = ["d", 0]
... [loops]
... ABCD = "AD + DC - BC - AB"
... [points]
... A = "0"
... C = "AB + BC"
... [defaults]
... theta = "30 deg"
... ''', source="fourbar.toml")
>>> found.linkage.unknowns, round(found.defaults["theta"], 12)
((beta, phi), 0.523598775598)
>>> linkage_from_text('name = "x"\\ninputs = ["theta"]\\nunknowns = ["beta"]\\nlengths = ["a"]\\n'
...                   '[vectors]\\nAB = ["a", "theta * 2"]\\n', source="x.toml")
Traceback (most recent call last):
ValueError: x.toml:6: vectors.AB: angle 'theta * 2': a name cannot be multiplied (write a sum of names and constants)
"""
from __future__ import annotations

import math
import re
import sys
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping, Union

import sympy as sp

from ..common.display import record_html
from ..common.files import excerpt, read_input_text, write_atomic
from ..common.numbers import float_of, number_from_text, toml_data
from ..numeric.input_sweep import MAX_ANGLE as INPUT_MAX_ANGLE
from ..symbolic.linkage import Linkage
from ..symbolic.loops import Loop
from ..symbolic.vectors import Vector, VectorSum

if TYPE_CHECKING:
    from ..dynamics.inverse import DynamicLinkage
    from ..dynamics.model import DynamicModel

if sys.version_info >= (3, 11):
    from tomllib import loads as toml_loads
else:  # Python 3.10: tomli is tomllib before it joined the standard library
    from tomli import loads as toml_loads

__all__ = ["LinkageFile", "toml_data", "load_linkage", "read_linkage", "linkage_from_text", "linkage_from_mapping",
           "linkage_text", "write_linkage", "write_catalog_files", "catalog_file", "CATALOG_FOLDER", "dynamic_model",
           "catalog_name", "SIX_BAR_ENTRIES"]

#: Where the catalog's linkage files ship: package data of symlink (``symlink/linkages/<name>.toml``),
#: installed with it, so that they are found from any folder (:func:`catalog_file`).
CATALOG_FOLDER = Path(__file__).resolve().parent.parent / "linkages"

TOP_KEYS = ("name", "inputs", "unknowns", "lengths", "constants")
TABLES = ("vectors", "loops", "points", "roles", "defaults", "dynamics")
#: The keys of ``[dynamics]``; of each of its entries, the keys it needs and those it may have.
DYNAMICS_KEYS = ("gravity", "masses", "forces", "torques", "springs", "dampers")
DYNAMICS_ENTRIES = {"masses": (("mass",), ("distance", "angle", "inertia", "origin")),
                    "forces": (("point",), ("x", "y", "body")),
                    "torques": (("body", "torque"), ()),
                    "springs": (("first", "second", "stiffness"), ("free_length", "first_body", "second_body")),
                    "dampers": (("first", "second", "coefficient"), ("first_body", "second_body"))}
#: The entries' keys that name a point, joint or body (the others are values).
DYNAMICS_NAMES = frozenset({"origin", "point", "body", "first", "second", "first_body", "second_body"})
RESERVED = {"pi", "deg", "rad"}
#: Linkage files larger than this are refused unread (the largest catalog linkage is a few kB).
MAX_LINKAGE_BYTES = 4 << 20
ORIGIN = "0"
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


@dataclass(frozen=True)
class LinkageFile:
    """A linkage read from a file, with the file's default values (radians for angles) and where it came from.

    ``model`` holds the mass properties and loads of the file's ``[dynamics]`` table, if it has one.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    linkage: Linkage
    defaults: dict[str, float] = field(default_factory=dict)
    source: str = ""
    model: DynamicModel | None = None

    def dynamic_linkage(self) -> DynamicLinkage:
        """The linkage with its dynamic outputs (derived here: keep the result); ``ValueError`` without dynamics."""
        if self.model is None:
            raise ValueError(f"{self.source or self.linkage.name}: no [dynamics] table (masses and loads) to derive "
                             "torques and joint forces from")
        from ..dynamics.inverse import dynamic_linkage
        return dynamic_linkage(self.model)

    def with_dynamics(self) -> LinkageFile:
        """This file with its dynamic linkage in place of the plain one (itself without a ``[dynamics]`` table)."""
        if self.model is None:
            return self
        return LinkageFile(self.dynamic_linkage(), self.defaults, self.source, self.model)


class _Problem(ValueError):
    """A problem at a key of the file: ``table`` ("" at the top level) and ``key`` ("" for the whole table)."""

    def __init__(self, table: str, key: str, message: str) -> None:
        super().__init__(message)
        self.table, self.key, self.message = table, key, message


# --- where keys are in the text -------------------------------------------------------

_HEADER_LINE = re.compile(r"\s*(\[\[?)\s*([A-Za-z0-9_.-]+)\s*\]\]?\s*(?:#.*)?$")
_KEY_LINE = re.compile(r"""\s*(?:([A-Za-z0-9_-]+)|"([^"\\]*)"|'([^']*)')\s*=""")


def _key_lines(text: str) -> tuple[dict[tuple[str, str], int], dict[str, int]]:
    """The line of each ``(table, key)`` and of each table header, found by scanning the text.

    tomllib reports no positions; linkage files are plain enough (one key a
    line, simple headers) for a line scan to find every key it accepts.
    """
    keys: dict[tuple[str, str], int] = {}
    headers: dict[str, int] = {}
    table = ""
    in_multiline = False
    entries: dict[str, int] = {}  # how many [[name]] headers so far: the k-th is table "name[k]" (from 0)
    for number, line in enumerate(text.splitlines(), start=1):
        if in_multiline:  # skip the continuation of an array written over several lines
            in_multiline = line.count("[") >= line.count("]") and "]" not in line
            continue
        header = _HEADER_LINE.match(line)
        if header:
            table = header.group(2)
            if header.group(1) == "[[":
                entries[table] = entries.get(table, -1) + 1
                table = f"{table}[{entries[table]}]"
            headers.setdefault(table, number)
            continue
        key = _KEY_LINE.match(line)
        if key:
            name = next(group for group in key.groups() if group is not None)
            keys.setdefault((table, name), number)
            rest = line[key.end():]
            in_multiline = rest.count("[") > rest.count("]")
    return keys, headers


def _line_of(problem: _Problem, text: str | None) -> int | None:
    if text is None:
        return None
    keys, headers = _key_lines(text)
    if (problem.table, problem.key) in keys:
        return keys[(problem.table, problem.key)]
    if f"{problem.table}.{problem.key}" in headers:  # a nested table [vectors.AB]
        return headers[f"{problem.table}.{problem.key}"]
    if problem.table and problem.table in headers:
        return headers[problem.table]
    if not problem.table and problem.key in headers:  # a table the top level does not allow
        return headers[problem.key]
    if ("", problem.table) in keys:  # an inline table: the line of its key
        return keys[("", problem.table)]
    return 1


# --- the expression grammar --------------------------------------------------------------

_SCAN = re.compile(r"\s*(?:((?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)|([A-Za-z_][A-Za-z0-9_]*)|([-+*/])"
                   r"|(\S))")
#: A number longer than this is refused as it is read (a float has 17 significant digits; 10**400 is no length).
MAX_NUMBER_CHARACTERS = 64


def _tokens(text: str) -> list[tuple[str, str]]:
    """``(kind, text)`` tokens of an expression: number, name, operator; ``ValueError`` for anything else.

    One ``findall`` over the text (every character is in a token, in white space or is the first bad
    one): linear in the length of the text.
    """
    found: list[tuple[str, str]] = []
    # without trailing space: \s* would retry it at each of its positions
    for number, name, operator, bad in _SCAN.findall(text.rstrip()):
        if bad:
            raise ValueError(f"unexpected {bad!r} (a sum of names and constants such as 'beta + 35 deg' or 'pi/2')")
        if number:
            if len(number) > MAX_NUMBER_CHARACTERS:
                raise ValueError(f"a number of {len(number):,} characters (at most {MAX_NUMBER_CHARACTERS}): "
                                 f"{excerpt(number, 20)}")
            found.append(("number", number))
        else:
            found.append(("name", name) if name else ("operator", operator))
    return found


#: Angles in a file beyond this size (radians) have lost their meaning (as on the command line).
MAX_ANGLE = INPUT_MAX_ANGLE
#: Lengths, masses, inertias, loads and other values of a file beyond this size are refused, and so are non-zero
#: ones below its inverse: the dynamics multiplies up to six of them (a force's moment is mass * length^2 * speed^2
#: / length ...), and 1e50 ** 6 is still a float.
MAX_MAGNITUDE = 1e50

#: Most entries of a table ([vectors], [loops], [points], ...), names of a list, and vectors of a loop or a point:
#: a linkage has a few dozen; tens of thousands would take the symbolic layer minutes, not a clear refusal.
MAX_ENTRIES = 1000
#: Longer expressions are refused before they are read (a sum of 10,000 terms is still read in a fraction of a
#: second: the tokenizer and the parser are linear).
MAX_EXPRESSION_CHARACTERS = 100_000
#: A constant as read: an exact ratio of whole numbers (numerator, denominator > 0), or a float.
_Number = Union[tuple[int, int], float]
#: Most different denominators among the exact constants of one expression (their sum is exact, in fractions).
MAX_DENOMINATORS = 64


def _number_value(text: str) -> _Number:
    """A number token as an exact ratio (whole numbers) or a float; ``ValueError`` when out of float range."""
    if not any(c in text for c in ".eE"):
        return int(text), 1
    return number_from_text(text)


def _divided(value: _Number, divisor: _Number) -> _Number:
    """``value / divisor`` (divisor not zero): exact when both are, else a float."""
    if isinstance(value, tuple) and isinstance(divisor, tuple):
        return value[0] * divisor[1], value[1] * divisor[0]  # both denominators positive, the divisor too
    as_float = [v[0] / v[1] if isinstance(v, tuple) else v for v in (value, divisor)]
    return as_float[0] / as_float[1]


class _Parser:
    """One pass over the tokens of one expression (see the module docstring for the grammar).

    Linear in the length of the text: a name's count and the constants are added up in plain
    Python numbers (ratios of whole numbers exactly, by denominator), and SymPy is called once at
    the end, not once a term.
    """

    def __init__(self, text: str, names: Mapping[str, sp.Symbol], units: bool) -> None:
        self.text, self.names, self.units = text, names, units
        self.tokens = _tokens(text)
        self.position = 0

    def peek(self) -> tuple[str, str] | None:
        return self.tokens[self.position] if self.position < len(self.tokens) else None

    def take(self) -> tuple[str, str]:
        token = self.peek()
        if token is None:
            raise ValueError("ends too early")
        self.position += 1
        return token

    def accept(self, operator: str) -> bool:
        if self.peek() == ("operator", operator):
            self.position += 1
            return True
        return False

    def parse(self) -> sp.Expr:
        if not self.tokens:
            raise ValueError("is empty")
        counts: dict[str, int] = {}
        exact: dict[tuple[int, int], int] = {}  # (1 for a multiple of pi else 0, denominator): sum of numerators
        inexact = [0.0, 0.0]
        floats = [False, False]
        sign = -1 if self.accept("-") else 1
        while True:
            name, value, with_pi = self.term()
            if name is not None:
                counts[name] = counts.get(name, 0) + sign
            elif isinstance(value, tuple):
                key = (with_pi, value[1])
                exact[key] = exact.get(key, 0) + sign * value[0]
                if len(exact) > MAX_DENOMINATORS:
                    raise ValueError(f"more than {MAX_DENOMINATORS} different fractions in one expression")
            else:
                inexact[with_pi] += sign * value
                floats[with_pi] = True
            token = self.peek()
            if token is None:
                break
            if token[0] != "operator" or token[1] not in "+-":
                raise ValueError(f"expected + or - before {excerpt(token[1], 20)}")
            sign = 1 if self.take()[1] == "+" else -1
        if not all(math.isfinite(x) for x in inexact):
            raise ValueError("adds up to more than a float can hold")
        sums = [Fraction(0), Fraction(0)]
        for (with_pi, denominator), numerator in exact.items():
            sums[with_pi] += Fraction(numerator, denominator)
        terms: list[sp.Expr] = [count * self.names[name] for name, count in counts.items()]
        for with_pi, factor in ((0, sp.S.One), (1, sp.pi)):
            if sums[with_pi]:
                terms.append(sp.Rational(sums[with_pi].numerator, sums[with_pi].denominator) * factor)
            if floats[with_pi]:
                terms.append(sp.Float(inexact[with_pi]) * factor if with_pi else sp.Float(inexact[with_pi]))
        return sp.Add(*terms)

    def number(self) -> _Number:
        kind, text = self.take()
        if kind != "number":
            raise ValueError(f"expected a number, got {excerpt(text, 20)}")
        return _number_value(text)

    def divisor(self) -> _Number:
        value = self.number()
        if value == 0 or value == (0, 1):
            raise ValueError("division by zero")
        return value

    def term(self) -> tuple[str | None, _Number, int]:
        """``(name, 0, 0)`` for a name, else ``(None, value, 1 if it is a multiple of pi else 0)``."""
        kind, text = self.peek() or ("", "")
        if kind == "name" and text == "pi":
            self.take()
            return None, (_divided((1, 1), self.divisor()) if self.accept("/") else (1, 1)), 1
        if kind == "name":
            self.take()
            if text in RESERVED:
                raise ValueError(f"{text!r} must follow a number (as in '35 deg')")
            if text not in self.names:
                raise ValueError(f"{excerpt(text, 30)} is not a coordinate or constant of this file")
            if self.peek() in (("operator", "*"), ("operator", "/")):
                raise ValueError("a name cannot be multiplied (write a sum of names and constants)")
            return text, (0, 1), 0
        if kind != "number":
            raise ValueError(f"expected a name or a number, got {excerpt(text, 20)}" if text else "ends too early")
        value = self.number()
        if self.accept("/"):
            value = _divided(value, self.divisor())
        if self.accept("*"):
            kind, text = self.take()
            if (kind, text) != ("name", "pi"):
                raise ValueError("a name cannot be multiplied (write a sum of names and constants)"
                                 if kind == "name" else f"only pi may follow '*', got {excerpt(text, 20)}")
            if self.accept("/"):
                value = _divided(value, self.divisor())
            return None, value, 1
        following = self.peek()
        if following is not None and following[0] == "name":
            if following[1] not in ("deg", "rad"):
                raise ValueError(f"unexpected {excerpt(following[1], 20)} after a number (units are deg and rad)")
            if not self.units:
                raise ValueError(f"a unit ({following[1]}) belongs to angles only")
            self.take()
            return (None, _divided(value, (180, 1)), 1) if following[1] == "deg" else (None, value, 0)
        return None, value, 0


def _constant_part(expr: sp.Expr) -> float:
    """The value of ``expr`` with every name at 0 (its constant terms), as a float (inf if beyond one)."""
    constant = sum((term for term in sp.Add.make_args(expr) if not term.free_symbols), sp.S.Zero)
    try:
        return float(constant)
    except OverflowError:
        return math.inf


def _check_range(value: float, kind: str) -> None:
    """``ValueError`` for a value out of range for its ``kind``: "angle", "length" (positive), "nonnegative"
    (a mass, an inertia) or "value" (any sign); all but angles within :data:`MAX_MAGNITUDE`."""
    if not math.isfinite(value):
        raise ValueError("is not a finite number")
    if kind == "angle":
        if abs(value) > MAX_ANGLE:
            raise ValueError(f"is {value:.3g} rad, more than {MAX_ANGLE:g} in size (larger angles have lost "
                             "their precision)")
        return
    if kind == "length" and value <= 0:
        raise ValueError(f"must be a positive length, got {value:.6g}")
    if kind == "nonnegative" and value < 0:
        raise ValueError(f"must not be negative, got {value:.6g}")
    if value != 0 and not 1 / MAX_MAGNITUDE <= abs(value) <= MAX_MAGNITUDE:
        raise ValueError(f"is {value:.3g}: values must be 0 or between {1 / MAX_MAGNITUDE:g} and "
                         f"{MAX_MAGNITUDE:g} in size (change the units)")


def _expression(value, names: Mapping[str, sp.Symbol], units: bool, kind: str | None = None) -> sp.Expr:
    """A length, an angle or a default from a TOML number or a string of the grammar.

    ``kind`` ("angle", "length" or "value"; default "angle" with ``units``, else "value") is the range the
    expression's constant part (its value with every name at 0) must be in: checked here, where the value is made.
    """
    kind = kind or ("angle" if units else "value")
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ValueError(f"must be a number or a string such as 'beta + 35 deg', got {excerpt(value)}")
    if isinstance(value, (int, float)):
        if not math.isfinite(float_of(value)):
            raise ValueError(f"must be finite, got {value!r}" if isinstance(value, float) else
                             f"{excerpt(str(value), 20)} is too large for a float")
        try:
            _check_range(float(value), kind)
        except ValueError as error:
            raise ValueError(f"{value!r} {error}") from None
        return sp.Integer(value) if isinstance(value, int) else sp.Float(value)
    if len(value) > MAX_EXPRESSION_CHARACTERS:
        raise ValueError(f"{excerpt(value)}: an expression of {len(value):,} characters (at most "
                         f"{MAX_EXPRESSION_CHARACTERS:,}; a linkage's lengths and angles are short sums)")
    try:
        expr = _Parser(value, names, units).parse()
        if kind != "length" or not expr.free_symbols:  # a length with names is checked when evaluated
            _check_range(_constant_part(expr), kind)
        return expr
    except ValueError as error:
        raise ValueError(f"{excerpt(value)}: {error}") from None


def _signed_sum(text, vectors: Mapping[str, Vector]) -> VectorSum:
    """A loop or a point: vector names joined by + and -."""
    if not isinstance(text, str):
        raise ValueError(f"must be a string such as 'AB + BC - DC', got {text!r}")
    if len(text) > MAX_EXPRESSION_CHARACTERS:
        raise ValueError(f"{excerpt(text)}: a sum of {len(text):,} characters (at most {MAX_EXPRESSION_CHARACTERS:,})")
    tokens = _tokens(text)
    if not tokens:
        raise ValueError("is empty")
    if len(tokens) > 2 * MAX_ENTRIES:
        raise ValueError(f"{excerpt(text)}: a sum of {(len(tokens) + 1) // 2:,} vectors (at most {MAX_ENTRIES:,})")
    terms, sign, expect_name = [], 1, True
    for index, (kind, token) in enumerate(tokens):
        if expect_name:
            if kind == "operator" and token in "+-" and index == 0:
                sign = -1 if token == "-" else 1
                continue
            if kind != "name":
                raise ValueError(f"{text!r}: expected a vector name, got {token!r}")
            if token not in vectors:
                raise ValueError(f"{text!r}: {token!r} is not a vector of [vectors]")
            terms.append((sign, vectors[token]))
            expect_name = False
        else:
            if kind != "operator" or token not in "+-":
                raise ValueError(f"{text!r}: expected + or - between vectors, got {token!r}")
            sign = 1 if token == "+" else -1
            expect_name = True
    if expect_name:
        raise ValueError(f"{text!r}: ends with {tokens[-1][1]!r}")
    return VectorSum(tuple(terms))


# --- reading --------------------------------------------------------------------------

def _names(data: Mapping, key: str, required: bool) -> list[str]:
    if key not in data:
        if required:
            raise _Problem("", "", f"missing {key} (a list of names, such as {key} = [\"theta\"])")
        return []
    value = data[key]
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise _Problem("", key, f"{key} must be a list of names, got {excerpt(value)}")
    if len(value) > MAX_ENTRIES:
        raise _Problem("", key, f"{key} has {len(value):,} names (at most {MAX_ENTRIES:,})")
    for name in value:
        if not _NAME.match(name):
            raise _Problem("", key, f"{key}: {name!r} is not a name (ASCII letters, digits and _, "
                                    "not starting with a digit)")
        if name in RESERVED:
            raise _Problem("", key, f"{key}: {name!r} is reserved by the grammar (pi, deg, rad)")
    return list(value)


def _table(data: Mapping, name: str) -> dict:
    value = data.get(name, {})
    if not isinstance(value, dict):
        raise _Problem("", name, f"{name} must be a table ([{name}]), got {excerpt(value)}")
    if len(value) > MAX_ENTRIES:
        raise _Problem("", name, f"[{name}] has {len(value):,} entries (at most {MAX_ENTRIES:,}: a linkage, not a "
                                 "data set)")
    for key, item in value.items():
        if isinstance(item, dict):
            raise _Problem(name, key, f"{name}.{key}: nested tables are not part of linkage files")
        if not _NAME.match(key):
            raise _Problem(name, key, f"{name}.{key}: a name is ASCII letters, digits and _, "
                                      "not starting with a digit")
    return value


def linkage_from_mapping(data: Mapping, source: str = "<mapping>", text: str | None = None) -> LinkageFile:
    """A :class:`LinkageFile` from parsed TOML; ``ValueError`` ``"source:line: problem"`` on anything wrong.

    ``text`` is the TOML the mapping was read from, to find the line of a
    problem; without it the message names ``source`` only.

    >>> found = linkage_from_mapping({"name": "crank", "inputs": ["theta"], "unknowns": ["beta", "s"],
    ...     "lengths": ["a", "b"], "vectors": {"AB": ["a", "theta"], "BC": ["b", "beta"], "AC": ["s", 0]},
    ...     "loops": {"ABC": "AB + BC - AC"}})
    >>> found.linkage.parameters, [step.case.name for step in found.linkage.plan]
    ((a, b), ['2b'])
    """
    try:
        return _from_mapping(data, source)
    except _Problem as problem:
        line = _line_of(problem, text)
        at = f"{source}:{line}" if line is not None else source
        raise ValueError(f"{at}: {problem.message}") from None


def _from_mapping(data: Mapping, source: str) -> LinkageFile:
    if not isinstance(data, Mapping):
        raise _Problem("", "", f"a linkage file is a TOML table, got {type(data).__name__}")
    if "links" in data or "joints" in data:  # a linkage by its joints: symlink.io.joint_tables derives the loops
        from .joint_tables import TableProblem, linkage_from_tables
        try:
            drawn = linkage_from_tables(data, angle=lambda value: float(_expression(value, {}, units=True)))
        except TableProblem as problem:
            raise _Problem(problem.table, problem.key, str(problem)) from None
        return LinkageFile(drawn.linkage, drawn.values, source)
    for key in data:
        if key not in TOP_KEYS + TABLES:
            raise _Problem("", key, f"unknown key {key!r} (a linkage file has {', '.join(TOP_KEYS + TABLES)})")
    name = data.get("name")
    if "name" not in data:
        raise _Problem("", "", 'missing name (such as name = "fourbar")')
    if not isinstance(name, str) or not name.strip():
        raise _Problem("", "name" if "name" in data else "", f"name must be a non-empty string, got {name!r}")
    inputs, unknowns = _names(data, "inputs", True), _names(data, "unknowns", True)
    positive, constants = _names(data, "lengths", False), _names(data, "constants", False)
    declared: dict[str, str] = {}
    for key, listed in (("inputs", inputs), ("unknowns", unknowns), ("lengths", positive), ("constants", constants)):
        for item in listed:
            if item in declared:
                raise _Problem("", key, f"{item!r} is listed in {declared[item]} and again in {key}")
            declared[item] = key
    symbols = {n: sp.Symbol(n, real=True) for n in inputs + unknowns + constants}
    symbols |= {n: sp.Symbol(n, positive=True) for n in positive}

    vectors: dict[str, Vector] = {}
    for key, value in _table(data, "vectors").items():
        if not isinstance(value, list) or len(value) != 2:
            raise _Problem("vectors", key, f"vectors.{key} must be [length, angle], got {value!r}")
        try:
            length = _expression(value[0], symbols, units=False, kind="length")
        except ValueError as error:
            raise _Problem("vectors", key, f"vectors.{key}: length {error}") from None
        try:
            angle = _expression(value[1], symbols, units=True)
        except ValueError as error:
            raise _Problem("vectors", key, f"vectors.{key}: angle {error}") from None
        vectors[key] = Vector(length, angle, key)

    loops = []
    for key, value in _table(data, "loops").items():
        try:
            loops.append(Loop(_signed_sum(value, vectors), name=key))
        except ValueError as error:
            raise _Problem("loops", key, f"loops.{key}: {error}") from None
    if not loops:
        raise _Problem("loops", "", "no loops: give at least one under [loops], such as ABCD = \"AD + DC - BC - AB\"")

    points: dict[str, VectorSum | None] = {}
    for key, value in _table(data, "points").items():
        if value == ORIGIN:
            points[key] = None
            continue
        try:
            points[key] = _signed_sum(value, vectors)
        except ValueError as error:
            raise _Problem("points", key, f"points.{key}: {error}") from None

    used = {v for loop in loops for _, v in loop.terms} | {v for p in points.values() if p for _, v in p.terms}
    for key, vector in vectors.items():
        if vector not in used:
            raise _Problem("vectors", key, f"vectors.{key} is in no loop and no point")
    in_vectors = set().union(*(v.length.free_symbols | v.angle.free_symbols for v in vectors.values()))
    for key, listed in (("lengths", positive), ("constants", constants), ("inputs", inputs), ("unknowns", unknowns)):
        for item in listed:
            if symbols[item] not in in_vectors:
                raise _Problem("", key, f"{key}: {item!r} appears in no vector")

    roles = {}
    for key, value in _table(data, "roles").items():
        if not isinstance(value, str) or value not in inputs + unknowns:
            raise _Problem("roles", key, f"roles.{key} must name a coordinate ({', '.join(inputs + unknowns)}), "
                                         f"got {value!r}")
        roles[key] = symbols[value]

    angles = set().union(*(v.angle.free_symbols for v in vectors.values()))
    try:
        linkage = Linkage(name, loops, [symbols[n] for n in inputs], [symbols[n] for n in unknowns],
                          parameters=[symbols[n] for n in positive + constants], points=points, roles=roles)
        missing = set().union(*(loop.symbols() for loop in loops)) - set(linkage.coordinates) - set(linkage.parameters)
        if missing:
            raise ValueError(f"the loops use {', '.join(sorted(map(str, missing)))}, which is not declared")
        linkage.has_closed_form  # a linkage with no solve plan at all is an error in its definition
    except ValueError as error:
        places: list[tuple[str, str]] = []
        names: list[str] = []
        for section, keys in (("loops", list(_table(data, "loops"))), ("points", list(points)),
                              ("vectors", list(vectors))):
            places += [(section, name) for name in keys]
            names += keys
        for list_key, declared_names in (("inputs", inputs), ("unknowns", unknowns), ("lengths", positive),
                                         ("constants", constants)):
            places += [("", list_key)] * len(declared_names)
            names += declared_names
        raise _Problem(*_blamed(str(error), places, names, ("loops", "")), f"{error}") from None
    model = _dynamics(data["dynamics"], linkage) if "dynamics" in data else None
    dynamic_names = [symbol.name for symbol in model.new_parameters] if model is not None else []
    nonnegative_names = _nonnegative_names(data.get("dynamics"))
    defaults = {}
    for key, value in _table(data, "defaults").items():
        if key not in positive + constants + inputs + dynamic_names:
            raise _Problem("defaults", key, f"defaults.{key}: only constants, inputs and the names of [dynamics] "
                                            f"have defaults ({', '.join(positive + constants + inputs + dynamic_names)})")
        angle = key in symbols and symbols[key] in angles
        kind = ("length" if key in positive else "angle" if angle else
                "nonnegative" if key in nonnegative_names else "value")
        try:
            number = _expression(value, {}, units=angle, kind=kind)
        except ValueError as error:
            raise _Problem("defaults", key, f"defaults.{key}: {error}") from None
        defaults[key] = float(number)
    return LinkageFile(linkage, defaults, source, model)


def _blamed(message: str, places: list[tuple[str, str]], names: list[str],
            otherwise: tuple[str, str]) -> tuple[str, str]:
    """The place (table, key) of the first of ``names`` that ``message`` mentions as a word, else ``otherwise``.

    A problem found by the linkage or the dynamics as a whole (a loop that cannot be solved, a body
    that does not exist) is pointed at the line that names what the message names, not at a table's header.
    """
    words = set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", message))
    for place, name in zip(places, names):
        if name in words:
            return place
    return otherwise


def _nonnegative_names(table) -> set[str]:
    """The names that ``[dynamics]`` gives as a mass or an inertia (their defaults must not be negative)."""
    bodies = table.get("masses") if isinstance(table, dict) else None
    if not isinstance(bodies, dict):
        return set()
    return {value.strip() for item in bodies.values() if isinstance(item, dict)
            for key, value in item.items() if key in NONNEGATIVE_KEYS and isinstance(value, str)}


def dynamic_model(table: Mapping, linkage: Linkage, source: str = "") -> DynamicModel:
    """The mass properties and loads of a ``[dynamics]`` table (see the module docstring) on ``linkage``.

    Scene files take the same table.  ``ValueError`` naming the key and the problem (after ``"source: "``
    if a source is given).

    >>> from symlink.mechanism.catalog import fourbar
    >>> model = dynamic_model({"masses": {"crank": {"mass": 2, "distance": 0.1}}}, fourbar())
    >>> model.generalised_inertia()[0, 0]
    0.02*sin(theta)**2 + 0.02*cos(theta)**2
    """
    try:
        return _dynamics(table, linkage)
    except _Problem as problem:
        raise ValueError(f"{source}: {problem.message}" if source else problem.message) from None


#: The ``[dynamics]`` keys whose values must not be negative.
NONNEGATIVE_KEYS = frozenset({"mass", "inertia"})


def _dynamic_value(value, table: str, key: str, known: Mapping[str, sp.Symbol], angle: bool = False):
    """A value of ``[dynamics]``: a number, a constant of the grammar (``"30 deg"``), or a name, maybe negated.

    A number is checked here, where it is read: finite, in range, and not negative for a mass or an inertia
    (a name's value is checked with ``[defaults]``, or when the outputs are evaluated).
    """
    where = f"{table}.{key}"
    kind = "angle" if angle else "nonnegative" if key in NONNEGATIVE_KEYS else "value"
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise _Problem(table, key, f"{where} must be a number or a name, got {excerpt(value)}")
    if isinstance(value, (int, float)):
        try:
            _check_range(float_of(value), kind)
        except ValueError as error:
            raise _Problem(table, key, f"{where} {error}") from None
        return value
    text = value.strip()
    negated = text.startswith("-") and bool(_NAME.match(text[1:].strip()))
    name = text[1:].strip() if negated else text
    if _NAME.match(name) and name not in RESERVED:
        if negated and kind == "nonnegative":
            raise _Problem(table, key, f"{where} must not be negative, got {excerpt(value)}")
        return -known.get(name, sp.Symbol(name, real=True)) if negated else name
    try:
        return float(_expression(text, {}, units=angle, kind=kind))
    except ValueError as error:
        raise _Problem(table, key, f"{where}: {error}") from None


def _dynamics(data, linkage: Linkage) -> DynamicModel:
    """The :class:`~symlink.dynamics.model.DynamicModel` of a ``[dynamics]`` table (see the module docstring)."""
    from ..dynamics.model import BodyTorque, Damper, DynamicModel, Gravity, MassProperties, PointForce, Spring
    if not isinstance(data, dict):
        raise _Problem("", "dynamics", f"dynamics must be a table ([dynamics]), got {data!r}")
    known = {symbol.name: symbol for symbol in linkage.parameters + linkage.coordinates}
    for key in data:
        if key not in DYNAMICS_KEYS:
            raise _Problem("dynamics", key, f"dynamics.{key}: unknown key (dynamics has {', '.join(DYNAMICS_KEYS)})")
    gravity = None
    if "gravity" in data:
        pair = data["gravity"]
        if not isinstance(pair, list) or len(pair) != 2:
            raise _Problem("dynamics", "gravity", f"dynamics.gravity must be [x, y], got {pair!r}")
        gravity = Gravity(*(_dynamic_value(v, "dynamics", "gravity", known) for v in pair))

    def entry(kind: str, table: str, key: str, item) -> dict:
        where = inner = f"{table}.{key}" if key else table
        required, optional = DYNAMICS_ENTRIES[kind]
        allowed = required + optional
        if not isinstance(item, dict):
            raise _Problem(table, key, f"{where} must be a table of {', '.join(allowed)}, got {item!r}")
        for name in item:
            if name not in allowed:
                raise _Problem(inner, name, f"{where}.{name}: unknown key ({kind} take {', '.join(allowed)})")
        for name in required:
            if name not in item:
                raise _Problem(table, key, f"{where}: missing {name}")
        found = {}
        for name, value in item.items():
            if name in DYNAMICS_NAMES:
                if not isinstance(value, str) or not _NAME.match(value):
                    raise _Problem(inner, name, f"{where}.{name} must name a point, joint or body, got {value!r}")
                found[name] = value
            else:
                found[name] = _dynamic_value(value, inner, name, known, angle=name == "angle")
        return found

    masses = []
    bodies = data.get("masses", {})
    if not isinstance(bodies, dict):
        raise _Problem("dynamics", "masses", f"dynamics.masses must be a table of bodies, got {bodies!r}")
    for body, item in bodies.items():
        masses.append(MassProperties(body, **entry("masses", "dynamics.masses", body, item)))
    loads: list = []
    kinds = {"forces": PointForce, "torques": BodyTorque, "springs": Spring, "dampers": Damper}
    for kind, make in kinds.items():
        items = data.get(kind, [])
        if not isinstance(items, list):
            raise _Problem("dynamics", kind, f"dynamics.{kind} must be a list of tables ([[dynamics.{kind}]]), "
                                             f"got {items!r}")
        for k, item in enumerate(items):
            found = entry(kind, f"dynamics.{kind}[{k}]", "", item)
            if kind == "forces":  # a component left out is zero
                found.setdefault("x", 0)
                found.setdefault("y", 0)
            loads.append(make(**found))
    try:
        return DynamicModel(linkage, masses, loads, gravity)
    except ValueError as error:
        places, names = [], []
        for body in bodies:
            places.append(("dynamics.masses", body))
            names.append(body)
        for kind in kinds:
            for k, item in enumerate(data.get(kind, [])):
                for name, value in item.items():
                    if name in DYNAMICS_NAMES and isinstance(value, str):
                        places.append((f"dynamics.{kind}[{k}]", name))
                        names.append(value)
        table, key = _blamed(str(error), places, names, ("dynamics", ""))
        raise _Problem(table, key, f"dynamics: {error}") from None


def linkage_from_text(text: str, source: str = "<text>") -> LinkageFile:
    """A :class:`LinkageFile` from the TOML text of a linkage file (see the module docstring).

    Parameters
    ----------
    text : str
        The TOML text of a linkage file.
    source : str, optional
        What to call it in error messages (default ``"<text>"``).

    Returns
    -------
    LinkageFile
        The linkage, its default values and the source.

    Raises
    ------
    ValueError
        ``"source:line: problem"`` for text that is not a valid linkage file.

    Examples
    --------
    >>> import symlink
    >>> found = symlink.linkage_from_text(symlink.linkage_text(symlink.slider_crank()))
    >>> found.linkage.unknowns, [step.case.name for step in found.linkage.plan]
    ((beta, s), ['2b'])
    """
    if not isinstance(text, str):
        raise ValueError(f"{source}: a linkage file's text is a str, not {type(text).__name__}")
    if len(text) > MAX_LINKAGE_BYTES:  # the file reader's bound, for text handed over directly too
        raise ValueError(f"{source}:1: {len(text):,} characters, more than a linkage file may hold "
                         f"(at most {MAX_LINKAGE_BYTES:,}); is it the right text?")
    text = text.removeprefix("\ufeff")  # a byte-order mark, as a file's reader drops it
    try:
        data = toml_data(text)
    except ValueError as error:  # "line L: problem"
        raise ValueError(f"{source}:{str(error)[len('line '):]}") from None
    return linkage_from_mapping(data, source, text)


def read_linkage(path: str | Path) -> LinkageFile:
    """Read a linkage file; ``ValueError`` ``"path:line: problem"`` if it cannot be read or is not valid.

    Read by :func:`~symlink.common.files.read_input`: a regular file of at most :data:`MAX_LINKAGE_BYTES`,
    never a FIFO or a device.

    Parameters
    ----------
    path : str or pathlib.Path
        The linkage file (TOML).

    Returns
    -------
    LinkageFile
        The linkage, its default values and where it came from.

    Raises
    ------
    ValueError
        ``"path:line: problem"`` for a file that cannot be read or is not a valid linkage file.

    Examples
    --------
    >>> import symlink, tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "fourbar.toml"
    >>> symlink.write_linkage(symlink.fourbar(), path, symlink.EXAMPLE_VALUES["fourbar"])
    >>> found = symlink.read_linkage(path)
    >>> found.linkage.name, found.linkage.unknowns, found.defaults["a"]
    ('fourbar', (beta, phi), 20.0)
    """
    return linkage_from_text(read_input_text(path, MAX_LINKAGE_BYTES, "linkage file"), str(path))


#: The catalog's six-bars by their names in the atlas (:data:`symlink.mechanism.atlas.SIX_BAR_DEFINITIONS`).
SIX_BAR_ENTRIES = {"watt-ii": "watt2", "stephenson-ii": "stephenson2"}


def catalog_name(text: str) -> str:
    """The catalog's name of the linkage ``text`` names: a catalog name, or a six-bar's name in any spelling.

    Six-bar names are read by :func:`symlink.mechanism.atlas.six_bar_name` (``Watt II``, ``stephenson-2``, the
    former ``stephenson3``, with a one-line note where an alias is read).

    Parameters
    ----------
    text : str
        ``"fourbar"``, ``"watt2"``, ``"Watt II"``, ``"stephenson2"`` ... (the keys of :data:`symlink.mechanism.catalog.CATALOG`).

    Returns
    -------
    str
        A key of :data:`symlink.mechanism.catalog.CATALOG`.

    Raises
    ------
    ValueError
        For a text naming no catalog linkage, listing those there are (and, for a six-bar the catalog has not,
        its atlas entry).

    Examples
    --------
    >>> from symlink.io.linkage_file import catalog_name
    >>> catalog_name("fourbar"), catalog_name("Watt II"), catalog_name("stephenson-ii")
    ('fourbar', 'watt2', 'stephenson2')
    """
    from ..mechanism.atlas import SIX_BAR_DEFINITIONS, six_bar_name
    from ..mechanism.catalog import CATALOG
    if isinstance(text, str) and text in CATALOG:
        return text
    six = six_bar_name(text)
    if six in SIX_BAR_ENTRIES:
        return SIX_BAR_ENTRIES[six]
    names = ", ".join(sorted(CATALOG))
    if six is not None:
        raise ValueError(f"the catalog has no {six} ({SIX_BAR_DEFINITIONS[six]}); the atlas has it: atlas:{six}. "
                         f"The catalog has {names}")
    raise ValueError(f"no linkage {excerpt(str(text), 40)} in the catalog; it has {names}")


def load_linkage(source: str | Path, folder: str | Path | None = None) -> LinkageFile:
    """A catalog entry by name (with its example values as defaults), an atlas entry (``atlas:watt-ii``), or a
    linkage file by path.

    Every command that takes a linkage takes either; a relative path is
    looked for in ``folder`` when given (a scene file's own folder).

    Parameters
    ----------
    source : str or pathlib.Path
        A catalog name (``"fourbar"``; a six-bar's in any spelling, ``"Watt II"``), an atlas name
        (``"atlas:watt-ii"``, ``"atlas:Stephenson III"``) or a linkage file's path.
    folder : str or pathlib.Path, optional
        Where a relative path is looked for (a scene file's own folder).

    Returns
    -------
    LinkageFile
        The linkage, its default values (a catalog entry's example values) and its source.

    Raises
    ------
    ValueError
        For a name that is neither a catalog nor an atlas entry nor a readable linkage file.

    Examples
    --------
    >>> import symlink
    >>> found = symlink.load_linkage("fourbar")
    >>> found.linkage.name, found.defaults["a"], found.source
    ('fourbar', 20.0, 'catalog')
    """
    from ..mechanism.catalog import CATALOG, EXAMPLE_VALUES
    text = str(source)
    if text in CATALOG:
        return LinkageFile(CATALOG[text](), dict(EXAMPLE_VALUES.get(text, {})), "catalog")
    if text.startswith("atlas:"):  # an atlas entry (symlink.mechanism.atlas) at its example dimensions: atlas:watt-ii
        from ..mechanism.atlas import atlas_entry
        drawn = atlas_entry(text.removeprefix("atlas:")).joint_linkage()
        return LinkageFile(drawn.linkage, drawn.values, "atlas")
    path = Path(folder) / text if folder is not None else Path(text)
    if text.endswith(".toml") or path.exists():
        return read_linkage(path)
    try:
        name = catalog_name(text)  # a catalog name, or a six-bar's in any spelling (Watt II, stephenson-2 ...)
    except ValueError as error:
        raise ValueError(f"{error} (an atlas entry is atlas:NAME, a linkage file ends in .toml)") from None
    return LinkageFile(CATALOG[name](), dict(EXAMPLE_VALUES.get(name, {})), "catalog")


# --- writing --------------------------------------------------------------------------

def _constant_text(value: sp.Expr) -> str:
    ratio = sp.nsimplify(value / sp.pi) if value.has(sp.pi) else None
    if ratio is not None and ratio.is_Rational and not value.free_symbols:
        p, q = ratio.p, ratio.q
        head = "pi" if abs(p) == 1 else f"{abs(p)}*pi"
        return ("-" if p < 0 else "") + head + (f"/{q}" if q != 1 else "")
    if value.is_Integer:
        return str(int(value))
    if value.is_Rational:
        return f"{value.p}/{value.q}"
    if value.is_Float:
        return repr(float(value))
    raise ValueError(f"{value} cannot be written in a linkage file (a sum of names and constants)")


def _expression_text(expr: sp.Expr) -> str | int | float:
    """The grammar's text for an expression: names with sign +-1 and one constant."""
    if expr.is_Integer:
        return int(expr)
    constant = sp.S.Zero
    names = []
    for term in sp.Add.make_args(expr):
        if term.is_Symbol:
            names.append((1, term))
        elif term.is_Mul and term.args[0] == -1 and len(term.args) == 2 and term.args[1].is_Symbol:
            names.append((-1, term.args[1]))
        elif not term.free_symbols:
            constant += term
        else:
            raise ValueError(f"{expr} cannot be written in a linkage file: {term} is not a name or a constant")
    names.sort(key=lambda pair: pair[1].name)
    text = ""
    for sign, symbol in names:
        text += (" - " if sign < 0 else (" + " if text else "")) + symbol.name
    if constant != 0 or not text:
        part = _constant_text(constant)
        if text:
            text += (" - " + part[1:]) if part.startswith("-") else (" + " + part)
        else:
            text = part
    return text.strip()


def _sum_text(vectors: VectorSum) -> str:
    text = ""
    for sign, vector in vectors.terms:
        text += (" - " if sign < 0 else (" + " if text else "")) + vector.name
    return text.lstrip()


def _toml_value(value) -> str:
    if isinstance(value, str):
        if '"' in value or "\\" in value:
            raise ValueError(f"{value!r} cannot be written as a simple TOML string")
        return f'"{value}"'
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return str(value)


def linkage_text(linkage: Linkage, defaults: Mapping[str, float] | None = None) -> str:
    """The TOML text of a linkage file for ``linkage`` (that :func:`linkage_from_text` reads back to it).

    Extras (named expressions such as the four-bar's transmission angle) are
    Python only and left out.

    Parameters
    ----------
    linkage : Linkage
        The linkage.
    defaults : mapping of str to float, optional
        Default values of its parameters, written in ``[defaults]``.

    Returns
    -------
    str
        The TOML text.

    Examples
    --------
    >>> import symlink
    >>> print(symlink.linkage_text(symlink.slider_crank()).split("[vectors]")[0].strip())
    # A symlink linkage file: vectors, loops and points (see symlink.io.linkage_file).
    name = "slider-crank"
    inputs = ["theta"]
    unknowns = ["beta", "s"]
    lengths = ["a", "b"]
    constants = ["offset"]
    """
    vectors: dict[str, Vector] = {}
    sums = [p.as_sum() for p in linkage.points.values() if p is not None] + [loop.vectors for loop in linkage.loops]
    for vectors_sum in sums:
        for _, vector in vectors_sum.terms:
            if not vector.name or not _NAME.match(vector.name):
                raise ValueError(f"vector {vector} needs a name of ASCII letters, digits and _ to be written")
            if vectors.setdefault(vector.name, vector) != vector:
                raise ValueError(f"two different vectors are named {vector.name!r}")
    positive = [s.name for s in linkage.parameters if s.is_positive]
    constants = [s.name for s in linkage.parameters if not s.is_positive]
    lines = ["# A symlink linkage file: vectors, loops and points (see symlink.io.linkage_file).",
             f"name = {_toml_value(linkage.name)}",
             f"inputs = {_toml_value([q.name for q in linkage.inputs])}",
             f"unknowns = {_toml_value([q.name for q in linkage.unknowns])}",
             f"lengths = {_toml_value(positive)}"]
    if constants:
        lines.append(f"constants = {_toml_value(constants)}")
    lines += ["", "[vectors]"]
    lines += [f"{name} = {_toml_value([_expression_text(v.length), _expression_text(v.angle)])}"
              for name, v in vectors.items()]
    lines += ["", "[loops]"] + [f"{loop.name} = {_toml_value(_sum_text(loop.vectors))}" for loop in linkage.loops]
    if linkage.points:
        lines += ["", "[points]"]
        lines += [f"{name} = {_toml_value(ORIGIN if p is None else _sum_text(p.as_sum()))}"
                  for name, p in linkage.points.items()]
    if linkage.roles:
        lines += ["", "[roles]"] + [f"{role} = {_toml_value(q.name)}" for role, q in linkage.roles.items()]
    if defaults:
        lines += ["", "[defaults]"] + [f"{name} = {_toml_value(float(value))}" for name, value in defaults.items()]
    return "\n".join(lines) + "\n"


def write_linkage(linkage: Linkage, path: str | Path, defaults: Mapping[str, float] | None = None) -> None:
    """Write ``linkage`` (and optional ``defaults``) as a linkage file, atomically.

    Parameters
    ----------
    linkage : Linkage
        The linkage (its extras, Python only, are left out).
    path : str or pathlib.Path
        Where to write; the file appears whole or not at all.
    defaults : mapping of str to float, optional
        Default values of its parameters, written in ``[defaults]``.

    Returns
    -------
    None

    Examples
    --------
    >>> import symlink, tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "fourbar.toml"
    >>> symlink.write_linkage(symlink.fourbar(), path, symlink.EXAMPLE_VALUES["fourbar"])
    >>> found = symlink.read_linkage(path)
    >>> found.linkage.name, found.linkage.unknowns, found.defaults["a"]
    ('fourbar', (beta, phi), 20.0)
    """
    write_atomic(path, linkage_text(linkage, defaults))


def catalog_file(name: str) -> Path:
    """The shipped linkage file of the catalog entry ``name``, wherever symlink is installed.

    Every catalog linkage ships as a file (:data:`CATALOG_FOLDER`): a starting
    point to copy and edit into a linkage of your own.  ``ValueError`` naming
    the catalog for a name that is not in it.

    >>> path = catalog_file("fourbar")
    >>> path.name, read_linkage(path).defaults["a"]
    ('fourbar.toml', 20.0)
    """
    return CATALOG_FOLDER / f"{catalog_name(name)}.toml"


def write_catalog_files(folder: str | Path = CATALOG_FOLDER) -> list[Path]:
    """Write every catalog entry as ``<folder>/<name>.toml`` with its example values: the shipped examples.

    By default into :data:`CATALOG_FOLDER`, the package's own ``symlink/linkages/`` (regenerate it from a
    checkout with ``python -c "from symlink.io.linkage_file import write_catalog_files; write_catalog_files()"``).
    """
    from ..mechanism.catalog import CATALOG, EXAMPLE_VALUES
    written = []
    for name, build in CATALOG.items():
        path = Path(folder) / f"{name}.toml"
        write_linkage(build(), path, EXAMPLE_VALUES.get(name))
        written.append(path)
    return written
