"""A solver's results: a plain dict of arrays that also knows its units and shows itself as a table.

:class:`Results` is a :class:`dict` (``result["rocker"]`` and every dict
operation work as before) with :attr:`~Results.units` per output, a small
HTML table for notebooks (:meth:`~Results._repr_html_`, the first rows) and
:meth:`~Results.to_frame`, a pandas DataFrame (pandas is optional: the
``symlink-kinematics[pandas]`` extra) whose column names carry the units,
which are also in ``DataFrame.attrs["units"]``.

>>> import numpy
>>> results = Results({"rocker": numpy.array([1.0, 2.0]), "assembled": numpy.array([True, False])},
...                   units={"rocker": "rad", "assembled": ""})
>>> results["rocker"].tolist(), isinstance(results, dict)
([1.0, 2.0], True)
>>> results.columns()
['rocker (rad)', 'assembled']
"""
from __future__ import annotations

import html
from typing import Mapping

import numpy

__all__ = ["Results", "HTML_ROWS"]

#: Rows a notebook shows of a result (the first ones, then how many more there are).
HTML_ROWS = 10


class Results(dict):
    """Outputs by name (arrays broadcast to one shape, ``assembled`` a bool mask), with their units.

    Two bool masks say where the numbers are not to be read as they stand:

    * ``assembled``: False where the linkage cannot close (every output is NaN there);
    * ``singular``: True where it closes at a toggle, a pose where a loop's determinant
      vanishes (its two assemblies meet).  Rates, accelerations, joint forces, driving
      efforts and sensitivities divide by that determinant, so they are inf, NaN or
      meaningless there while the positions are right.  A :class:`~symlink.solver.Solver`
      adds it to any request with such an output (the loops those outputs depend on).

    ``units`` maps an output to its unit (``"rad"``, ``"rad/s"``, a length
    unit, ``""`` for none or unknown); outputs not in it have no stated unit.
    """

    def __init__(self, values: Mapping[str, object] | None = None, units: Mapping[str, str] | None = None) -> None:
        super().__init__(values or {})
        self.units: dict[str, str] = dict(units or {})

    def column(self, name: str) -> str:
        """A column's name with its unit in parentheses (``"rocker (rad)"``), or the bare name."""
        unit = self.units.get(name, "")
        return f"{name} ({unit})" if unit else name

    def columns(self) -> list[str]:
        """The column names of :meth:`to_frame`, in the order of the outputs."""
        return [self.column(name) for name in self]

    def _table(self) -> dict[str, numpy.ndarray]:
        """Each output as a flat column, all broadcast to one shape."""
        arrays = [numpy.asarray(value) for value in self.values()]
        shape = numpy.broadcast_shapes(*(array.shape for array in arrays)) if arrays else ()
        return {name: numpy.broadcast_to(array, shape).ravel() for name, array in zip(self, arrays)}

    def to_frame(self):
        """A :class:`pandas.DataFrame`, a row per input value, columns named with their units.

        ``DataFrame.attrs["units"]`` maps each output name to its unit.
        ``ImportError`` naming the extra to install where pandas is missing.
        """
        try:
            import pandas  # an optional extra
        except ImportError:
            raise ImportError("Results.to_frame needs pandas: pip install 'symlink-kinematics[pandas]' "
                              "(or pip install pandas)") from None
        table = self._table()
        frame = pandas.DataFrame({self.column(name): column for name, column in table.items()})
        frame.attrs["units"] = {name: self.units.get(name, "") for name in self}
        return frame

    def _repr_html_(self) -> str:
        """The first :data:`HTML_ROWS` rows as an HTML table, and how many rows there are."""
        table = self._table()
        rows = len(next(iter(table.values()))) if table else 0
        head = "".join(f"<th>{html.escape(name)}</th>" for name in self.columns())
        body = []
        for k in range(min(rows, HTML_ROWS)):
            cells = "".join(f"<td>{html.escape(_cell(column[k]))}</td>" for column in table.values())
            body.append(f"<tr><th>{k}</th>{cells}</tr>")
        more = f"<p>{rows - HTML_ROWS} more rows of {rows}</p>" if rows > HTML_ROWS else ""
        return (f"<table><thead><tr><th></th>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>{more}")


def _cell(value: object) -> str:
    if isinstance(value, (bool, numpy.bool_)):
        return str(bool(value))
    if isinstance(value, (float, numpy.floating)):
        return f"{float(value):.6g}"
    return str(value)
