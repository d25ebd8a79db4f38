"""How symlink's result records show in a notebook: a small HTML table of their fields.

A record (a :func:`dataclasses.dataclass` such as
:class:`~symlink.analysis.report.LinkageReport`, or any object with public
attributes) is shown as its class name over a two-column table, one row a
field or a public property (lengths in the record's unit, angles in radians as
symlink computes them): numbers to six significant digits, short arrays written out and long
ones by shape and range, nested records as nested tables, long sequences cut
after :data:`SHOWN_ITEMS` items with a count of the rest.  A record class
gets it with one line, ``_repr_html_ = record_html``; Jupyter, nbconvert
and the docs' executed notebooks then show the table instead of a one-line
``repr``.  Text is escaped: a name from a linkage file cannot inject markup.

>>> from dataclasses import dataclass
>>> @dataclass
... class Reach:
...     full_turn: bool
...     spans: tuple
>>> print(record_html(Reach(False, ((-1.0, 1.25),))))  # doctest: +NORMALIZE_WHITESPACE
<table class="symlink-record"><caption>Reach</caption><tbody><tr><th>full_turn</th><td>False</td></tr>
<tr><th>spans</th><td>((-1, 1.25))</td></tr></tbody></table>
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy

__all__ = ["record_html", "value_html", "SHOWN_ITEMS"]

#: Items of a sequence, entries of a mapping and values of an array written out before the rest is counted.
SHOWN_ITEMS = 8
#: Nested records deeper than this are shown by their class name only.
MAX_DEPTH = 3
#: Longest text shown of a value's ``repr`` (a SciPy solution, a linkage): the rest is cut with an ellipsis.
MAX_TEXT = 160


def _fields(record: Any) -> list[tuple[str, Any]]:
    """``(name, value)`` of a record's public fields (a dataclass's, else its public instance attributes),
    then of its public properties (``dof``, ``full_turn``: what it derives from them), those that answer."""
    if dataclasses.is_dataclass(record) and not isinstance(record, type):
        fields = [(field.name, getattr(record, field.name)) for field in dataclasses.fields(record)
                  if not field.name.startswith("_")]
    else:
        fields = [(name, value) for name, value in vars(record).items() if not name.startswith("_")]
    for cls in reversed(type(record).__mro__):
        for name, attribute in vars(cls).items():
            if isinstance(attribute, property) and not name.startswith("_"):
                try:
                    fields.append((name, getattr(record, name)))
                except Exception:  # noqa: BLE001 - a property that cannot answer here is left out of the display
                    pass
    return fields


def _is_record(value: Any) -> bool:
    return dataclasses.is_dataclass(value) and not isinstance(value, type) or (
        getattr(type(value), "_repr_html_", None) is record_html)


def record_html(record: Any, depth: int = 0) -> str:
    """``record`` as an HTML table: its class name as the caption, a row a public field."""
    import html  # when a record is shown (a command that shows none starts without it)
    name = html.escape(type(record).__name__)
    if depth > MAX_DEPTH:
        return f"<i>{name}</i>"
    rows = "\n".join(f"<tr><th>{html.escape(field)}</th><td>{value_html(value, depth + 1)}</td></tr>"
                     for field, value in _fields(record))
    return f'<table class="symlink-record"><caption>{name}</caption><tbody>{rows}</tbody></table>'


def _number(value: Any) -> str:
    if isinstance(value, (bool, numpy.bool_)):
        return str(bool(value))
    if isinstance(value, (int, numpy.integer)):
        return str(int(value))
    number = float(value)
    return f"{number:.6g}" if math.isfinite(number) else str(number)


def value_html(value: Any, depth: int = 0) -> str:
    """One field's value as HTML (escaped): a number, an array's summary, a nested record or table, text.

    >>> value_html(numpy.linspace(0.0, 1.0, 100))
    'array (100,) of float64, from 0 to 1'
    >>> value_html({"a": 20.0, "<b>": 1})
    'a = 20, &lt;b&gt; = 1'
    """
    import html
    if value is None or isinstance(value, (bool, numpy.bool_, int, float, numpy.number)):
        return "None" if value is None else _number(value)
    if isinstance(value, str):
        return html.escape(value if len(value) <= MAX_TEXT else value[:MAX_TEXT] + "…")
    if isinstance(value, numpy.ndarray):
        if value.size <= SHOWN_ITEMS:
            return html.escape(str([_number(v) for v in value.ravel()] if value.ndim else _number(value[()])))
        if value.dtype.kind in "biuf":
            finite = value[numpy.isfinite(value)] if value.dtype.kind == "f" else value
            span = (f", from {_number(finite.min())} to {_number(finite.max())}" if finite.size else "")
            return html.escape(f"array {value.shape} of {value.dtype}{span}")
        return html.escape(f"array {value.shape} of {value.dtype}")
    if _is_record(value):
        return record_html(value, depth)
    if isinstance(value, dict):
        items = list(value.items())
        shown = ", ".join(f"{html.escape(str(key))} = {value_html(item, depth)}" for key, item in items[:SHOWN_ITEMS])
        return shown + (f", … {len(items) - SHOWN_ITEMS} more" if len(items) > SHOWN_ITEMS else "")
    if isinstance(value, (tuple, list)):
        if any(_is_record(item) for item in value):
            parts = "".join(f"<li>{value_html(item, depth)}</li>" for item in value[:SHOWN_ITEMS])
            more = f"<li>… {len(value) - SHOWN_ITEMS} more</li>" if len(value) > SHOWN_ITEMS else ""
            return f"<ol>{parts}{more}</ol>" if value else "()"
        shown = ", ".join(value_html(item, depth) for item in value[:SHOWN_ITEMS])
        more = f", … {len(value) - SHOWN_ITEMS} more" if len(value) > SHOWN_ITEMS else ""
        return f"({shown}{more})" if isinstance(value, tuple) else f"[{shown}{more}]"
    text = repr(value)
    return html.escape(text if len(text) <= MAX_TEXT else text[:MAX_TEXT] + "…")
