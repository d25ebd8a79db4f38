"""Writing results: aligned tables, csv with an exact header, JSON records, streamed row by row.

Results go to stdout, notes and progress to stderr.  A table of millions of
rows is written as it is computed, a block at a time, so memory stays bounded
and the first row appears at once.

>>> import io
>>> out = io.StringIO()
>>> writer = RowWriter(["crank", "branch", "rocker"], "csv", out)
>>> writer.write([{"crank": 0.0, "branch": 1, "rocker": 110.74}])
>>> writer.close()
>>> print(out.getvalue().strip())
crank,branch,rocker
0.0,1,110.74
"""
from __future__ import annotations

import json
import math
import sys
from typing import Callable, Collection, Iterable, Iterator, Mapping, TextIO

import numpy

from ..common.angles import from_radians, half_turn, wrap

__all__ = ["format_number", "table_cell", "header_label", "json_number", "RowWriter", "print_rows", "TableAssembler",
           "note"]

#: Angles named one by one in a note before the rest are counted.
LISTED_ANGLES = 50
#: Lines written at once.
CHUNK = 2048


def note(text: str) -> None:
    """One line on stderr: ``symlink: TEXT``."""
    print(f"symlink: {text}", file=sys.stderr)


def format_number(value: float) -> str:
    """Full double precision for machine-readable output (a whole number, such as a rank, as it is; never -0.0).

    >>> format_number(3), format_number(-0.0), format_number(0.1)
    ('3', '0.0', '0.1')
    """
    if isinstance(value, (int, numpy.integer)) and not isinstance(value, bool):
        return str(int(value))
    value = float(value)
    return repr(value + 0.0 if value == 0 else value)  # -0.0 + 0.0 is 0.0


def table_cell(value: float) -> str:
    """A number as a table prints it, as a textbook would: a whole number (a rank, a count) as it is, others
    to four decimals, never ``-0.0000`` (a negative that rounds to zero is zero).

    >>> table_cell(2), table_cell(-0.00004), table_cell(110.7432), table_cell(float("nan"))
    ('2', '0.0000', '110.7432', 'nan')
    """
    if isinstance(value, (int, numpy.integer)) and not isinstance(value, bool):
        return str(int(value))
    text = f"{float(value):.4f}"
    return text[1:] if text.startswith("-") and not text.strip("-0.") else text


def header_label(column: str, unit: str | None) -> str:
    """A table's header cell: the column and its unit, ``rocker (deg)`` (the column alone without one)."""
    return f"{column} ({unit})" if unit else column


def json_number(value):
    """A number for JSON: full precision, and null for NaN (JSON has no NaN)."""
    if isinstance(value, (int, str)):  # a branch: a sign, or one sign a loop ("+1/-1")
        return value
    return float(value) if math.isfinite(value) else None


def _text(value) -> str | None:
    """A cell that is words, not a number: a name (a Grashof class, a branch ``+1/-1``) or a yes/no flag."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return value if isinstance(value, str) else None


class RowWriter:
    """Rows as an aligned table, csv with the exact header, or JSON records, written as they come.

    The header (and JSON's opening bracket) is written with the first rows,
    so a command that fails before any row has printed nothing.  ``units``
    (by column) are shown in the table's header, ``rocker (deg)``; csv and JSON
    keep their exact column names.
    """

    def __init__(self, columns: list[str], fmt: str, out: TextIO | None = None,
                 units: Mapping[str, str] | None = None) -> None:
        if fmt not in ("table", "csv", "json"):
            raise ValueError(f"format must be table, csv or json, got {fmt!r}")
        self.columns, self.format, self.out = list(columns), fmt, out or sys.stdout
        self.rows = 0
        self.labels = [header_label(c, (units or {}).get(c)) for c in self.columns]
        self._widths = [max(10, len(label) + 1) for label in self.labels]

    def _header(self) -> str:
        if self.format == "csv":
            return ",".join(self.columns) + "\n"
        if self.format == "json":
            return "["
        return "".join(f"{c:>{width}}" for c, width in zip(self.labels, self._widths)) + "\n"

    def _line(self, row: Mapping) -> str:
        if self.format == "csv":
            return ",".join(_text(row[c]) or (str(row[c]) if c == "branch" else format_number(row[c]))
                            for c in self.columns) + "\n"
        if self.format == "json":
            record = json.dumps([{c: json_number(row[c]) for c in self.columns}], indent=1)[1:-2]
            return ("," if self.rows else "") + record
        cells = [_text(row[c]) or (f"{row[c]:+d}" if c == "branch" else table_cell(row[c])) for c in self.columns]
        return "".join(f"{cell:>{width}}" for cell, width in zip(cells, self._widths)) + "\n"

    def write(self, rows: Iterable[Mapping]) -> None:
        """Write these rows (the header first, with the first row), a few thousand lines at a time."""
        parts = []
        for row in rows:
            if not self.rows:
                parts.append(self._header())
            parts.append(self._line(row))
            self.rows += 1
            if len(parts) >= CHUNK:
                self.out.write("".join(parts))
                parts.clear()
        if parts:
            self.out.write("".join(parts))
        self.out.flush()

    def close(self) -> None:
        """Finish the output: the header of an empty table, JSON's closing bracket."""
        if not self.rows:
            self.out.write(self._header())
        if self.format == "json":
            self.out.write("\n]\n" if self.rows else "]\n")
        self.out.flush()


def print_rows(rows: list[dict], columns: list[str], fmt: str, out: TextIO | None = None,
               units: Mapping[str, str] | None = None) -> None:
    """Rows as an aligned table (``units`` in its header), csv with the exact header, or JSON records."""
    writer = RowWriter(columns, fmt, out, units)
    writer.write(rows)
    writer.close()


class TableAssembler:
    """Table rows (input angle, then branch) from solver results, block by block; the rest named on stderr.

    ``columns`` are the input column, ``branch``, then result names; angles
    among them (``angle_columns``) are converted to ``units`` and wrapped,
    ``transmission`` converted; speeds and accelerations stay per second.
    Rows that cannot be assembled are left out and, with singular rows (a
    toggle, where rates, forces and sensitivities are not defined: the results'
    ``singular`` flag where they have one, else non-finite rates), named on
    stderr by :meth:`finish`.
    """

    def __init__(self, columns: list[str], units: str, angle_columns: Collection[str]) -> None:
        self.columns, self.units, self.angle_columns = columns, units, set(angle_columns)
        self.half = half_turn(units)
        self.rows = 0
        self.seen = 0  # input values so far: the index of the next block's first
        self.unassembled: dict[object, list[tuple[int, float]]] = {}
        self.singular: list[tuple[int, float]] = []

    @staticmethod
    def _listed(found: list[tuple[int, float]]) -> str:
        shown = ", ".join(f"{angle:.6g}" for _, angle in found[:LISTED_ANGLES])
        more = len(found) - LISTED_ANGLES
        return shown + (f" and {more} more" if more > 0 else "")

    def rows_of(self, angles: numpy.ndarray, results: Mapping[object, Mapping[str, numpy.ndarray]]) -> Iterator[dict]:
        """The rows of one block, one at a time: ``angles`` in ``units`` and each branch's results there."""
        shown_angles = numpy.atleast_1d(wrap(numpy.asarray(angles, dtype=float), self.half))
        converted = {}
        for sign, result in results.items():
            self.unassembled.setdefault(sign, [])
            columns = {}
            for column in self.columns[2:]:
                values = numpy.broadcast_to(numpy.asarray(result[column], dtype=float), shown_angles.shape)
                if column in self.angle_columns:
                    values = wrap(from_radians(values, self.units), self.half)
                elif column == "transmission":
                    values = from_radians(values, self.units)
                columns[column] = numpy.broadcast_to(values, shown_angles.shape).tolist()
            # The solver's flag where it has one (a toggle, not a NaN from elsewhere); else non-finite rates.
            flags = (numpy.broadcast_to(result["singular"], shown_angles.shape).tolist() if "singular" in result
                     else None)
            converted[sign] = (numpy.broadcast_to(result["assembled"], shown_angles.shape).tolist(), columns, flags)
        rates = [c for c in self.columns[2:] if c not in self.angle_columns and c != "transmission"]
        first = self.seen
        self.seen += len(shown_angles)
        for i, angle in enumerate(shown_angles.tolist()):
            singular = False
            for sign, (assembled, columns, flags) in converted.items():
                if not assembled[i]:
                    self.unassembled[sign].append((first + i, angle))
                    continue
                row = {self.columns[0]: angle, "branch": sign}
                for column in self.columns[2:]:
                    row[column] = columns[column][i]
                if flags is not None:
                    singular = singular or bool(flags[i])
                else:
                    singular = singular or any(not math.isfinite(row[c]) for c in rates)
                self.rows += 1
                yield row
            if singular:
                self.singular.append((first + i, angle))

    def finish(self, spans: Callable[[], str | Mapping[object, str]]) -> None:
        """Name on stderr what was left out; ``ValueError`` if nothing could be assembled.

        ``spans()`` describes the reachable input range (one text, or one a
        branch), computed only when something was left out.
        """
        if not self.rows or any(self.unassembled.values()):
            known = spans()
            if not self.rows:
                text = known if isinstance(known, str) else "; ".join(f"branch {sign}: {t}"
                                                                       for sign, t in known.items())
                raise ValueError(f"the linkage cannot be assembled at any requested crank angle "
                                 f"(reachable crank range: {text})")
            if not isinstance(known, str):
                for sign, angles in self.unassembled.items():
                    if angles:
                        note(f"branch {sign} cannot be assembled at crank angles {self._listed(angles)} "
                             f"{self.units} (reachable crank range: {known[sign]})")
            else:
                found = sorted(set().union(*map(set, self.unassembled.values())))
                note(f"cannot be assembled at crank angles {self._listed(found)} {self.units} "
                     f"(reachable crank range: {known})")
        if self.singular:
            note(f"singular (toggle) position at crank angles {self._listed(self.singular)} {self.units}: "
                 "rates, accelerations, forces and sensitivities are not defined there (inf, nan or meaningless)")
