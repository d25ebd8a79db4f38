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

    ``units`` maps an output to its unit (``"rad"``, ``"rad/s"``, a length
    unit, ``""`` for none or unknown); outputs not in it have no stated unit.
    What every solver returns (:class:`~symlink.solver.Solver`,
    :class:`~symlink.solver.NumericSolver`, the compiled solver): a plain
    dict, so ``result["rocker"]`` works as before, that shows itself as a
    table in a notebook and becomes a pandas DataFrame with :meth:`to_frame`.

    Parameters
    ----------
    values : mapping of str to array_like, optional
        The outputs by name.
    units : mapping of str to str, optional
        Each output's unit.

    Attributes
    ----------
    units : dict of str to str
        Each output's unit, as given.

    Examples
    --------
    >>> from symlink.catalog import fourbar
    >>> from symlink.solver import Solver
    >>> result = Solver(fourbar(), ["rocker", "rocker_speed"])(theta=[0.0, 0.5], a=20, b=66, c=56, d=80,
    ...                                                       branch=1, thetadot=10.5)
    >>> sorted(result), result.units["rocker_speed"]
    (['assembled', 'rocker', 'rocker_speed'], 'rad/s')
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

        Returns
        -------
        pandas.DataFrame
            One column per output (and ``assembled``), one row per value of
            the broadcast inputs.

        Raises
        ------
        ImportError
            pandas is not installed (the message names the extra to install).

        Examples
        --------
        >>> frame = Results({"rocker": numpy.array([1.0, 2.0])}, units={"rocker": "rad"}).to_frame()
        >>> len(frame), frame.attrs["units"]
        (2, {'rocker': 'rad'})
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
