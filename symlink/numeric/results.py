"""A solver's results: a plain dict of arrays that also knows its units, its inputs, and shows itself as a table.

:class:`Results` is a :class:`dict` (``result["rocker"]`` and every dict
operation work as before) with :attr:`~Results.units` per output, the
:attr:`~Results.inputs` of the call that made it, a small HTML table for
notebooks (:meth:`~Results._repr_html_`, the first rows) and
:meth:`~Results.to_frame`, a pandas DataFrame (pandas is optional: the
``symlink-kinematics[pandas]`` extra) whose columns are the inputs and the
outputs by their plain names (``df["phi"]``), units in
``DataFrame.attrs["units"]``.  A grid (inputs broadcast along different axes,
``theta[:, None]`` and ``c[None, :]``) keeps its axes: the frame's index is a
:class:`pandas.MultiIndex` over the inputs that span them.

>>> import numpy
>>> results = Results({"rocker": numpy.array([1.0, 2.0]), "assembled": numpy.array([True, False])},
...                   units={"rocker": "rad", "assembled": ""},
...                   inputs={"theta": numpy.array([0.0, 0.5]), "a": 20.0}, input_units={"theta": "rad"})
>>> results["rocker"].tolist(), isinstance(results, dict)
([1.0, 2.0], True)
>>> results.columns()
['theta', 'rocker', 'assembled']
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Mapping, Sequence

import numpy

if TYPE_CHECKING:
    import pandas

__all__ = ["Results", "HTML_ROWS", "checked_out", "refuse_overlaps"]

#: Rows a notebook shows of a result (the first ones, then how many more there are).
HTML_ROWS = 10


class Results(dict):
    """Outputs by name (arrays broadcast to one shape, ``assembled`` a bool mask), with their units and inputs.

    Two bool masks say where the numbers are not to be read as they stand:

    * ``assembled``: False where the linkage cannot close (every output is NaN there);
    * ``singular``: True where it closes at a toggle, a pose where a loop's determinant
      vanishes (its two assemblies meet).  Rates, accelerations, joint forces, driving
      efforts and sensitivities divide by that determinant, so they are inf, NaN or
      meaningless there while the positions are right.  A :class:`~symlink.numeric.solver.Solver`
      adds it to any request with such an output (the loops those outputs depend on).

    ``units`` maps an output to its unit (``"rad"``, ``"rad/s"``, a length
    unit, ``""`` for none or unknown); outputs not in it have no stated unit.
    What every solver returns (:class:`~symlink.numeric.solver.Solver`,
    :class:`~symlink.numeric.solver.NumericSolver`, the compiled solver): a plain
    dict, so ``result["rocker"]`` works as before, that shows itself as a
    table in a notebook and becomes a pandas DataFrame with :meth:`to_frame`.

    ``inputs`` are the values the solver was called with (``theta``, the
    lengths, the branch signs...), ``input_units`` their units: those that are
    arrays become columns (or index levels) of :meth:`to_frame`, the numbers
    its ``attrs["constants"]``.

    Parameters
    ----------
    values : mapping of str to array_like, optional
        The outputs by name.
    units : mapping of str to str, optional
        Each output's unit.
    inputs : mapping of str to array_like, optional
        The values the solver was called with.
    input_units : mapping of str to str, optional
        Their units.

    Attributes
    ----------
    units : dict of str to str
        Each output's unit, as given.

    Examples
    --------
    >>> import symlink
    >>> result = symlink.Solver(symlink.fourbar(), ["rocker", "rocker_speed"])(
    ...     theta=[0.0, 0.5], a=20, b=66, c=56, d=80, branch=1, thetadot=10.5)
    >>> sorted(result), result.units["rocker_speed"]
    (['assembled', 'rocker', 'rocker_speed', 'singular'], 'rad/s')
    """

    def __init__(self, values: Mapping[str, object] | None = None, units: Mapping[str, str] | None = None,
                 inputs: Mapping[str, object] | None = None, input_units: Mapping[str, str] | None = None) -> None:
        super().__init__(values or {})
        self.units: dict[str, str] = dict(units or {})
        # kept as given (a solver call's hot path); an input named like an output is left out where read
        self.inputs: dict[str, Any] = dict(inputs) if inputs else {}
        self.input_units: dict[str, str] = dict(input_units) if input_units else {}

    def _unit(self, name: str) -> str:
        return self.units.get(name, "") if name in self else self.input_units.get(name, "")

    def column(self, name: str) -> str:
        """A column's name with its unit in parentheses (``"rocker (rad)"``), or the bare name: the HTML header."""
        unit = self._unit(name)
        return f"{name} ({unit})" if unit else name

    def varying_inputs(self) -> list[str]:
        """The inputs given as arrays (the columns or index levels of :meth:`to_frame`), in call order."""
        return [name for name, value in self.inputs.items() if name not in self and numpy.ndim(value) > 0]

    def columns(self) -> list[str]:
        """The column names of :meth:`to_frame` for a one-dimensional result: the varying inputs, then the outputs."""
        return self.varying_inputs() + list(self)

    def _shape(self) -> tuple[int, ...]:
        arrays = [numpy.shape(value) for value in self.values()] + [numpy.shape(self.inputs[n])
                                                                      for n in self.varying_inputs()]
        return numpy.broadcast_shapes(*arrays) if arrays else ()

    def _grid_axes(self, shape: tuple[int, ...]) -> list[tuple[str, numpy.ndarray | None]]:
        """For each axis of ``shape``: the first input that varies along it alone and its values, else
        ``("axis_<k>", None)``."""
        axes: list[tuple[str, numpy.ndarray | None]] = []
        for axis in range(len(shape)):
            found: tuple[str, numpy.ndarray | None] = (f"axis_{axis}", None)
            for name in self.varying_inputs():
                value = numpy.asarray(self.inputs[name])
                full = (1,) * (len(shape) - value.ndim) + value.shape
                if full[axis] == shape[axis] and all(extent == 1 for k, extent in enumerate(full) if k != axis):
                    found = (name, value.reshape(-1))
                    break
            axes.append(found)
        return axes

    def _table(self, names: list[str]) -> dict[str, numpy.ndarray]:
        """Each of ``names`` (inputs or outputs) as a flat column, all broadcast to the result's shape."""
        shape = self._shape()
        return {name: numpy.broadcast_to(numpy.asarray(self[name] if name in self else self.inputs[name]),
                                         shape).ravel() for name in names}

    def to_frame(self) -> "pandas.DataFrame":
        """A :class:`pandas.DataFrame`: a row per input value, columns the inputs and outputs by plain name.

        One-dimensional (or scalar) results have a row index ``0..n-1`` and the
        inputs given as arrays as columns (``theta``), then the outputs
        (``beta``, ``phi``, ``assembled``...).  A grid, its inputs broadcast
        along different axes, keeps its axes: the index is a
        :class:`pandas.MultiIndex` whose levels are the inputs that span them,
        in axis order (an axis no single input spans is ``axis_<k>``, by
        position).  ``attrs["units"]`` maps each column and index level to
        its unit, ``attrs["constants"]`` the inputs given as numbers.
        ``ImportError`` naming the extra to install where pandas is missing.

        >>> import numpy
        >>> from symlink.mechanism.catalog import fourbar
        >>> from symlink.numeric.solver import Solver
        >>> grid = Solver(fourbar(), ["rocker"])(theta=numpy.array([0.0, 1.0])[:, None], a=20, b=66,
        ...                                      c=numpy.array([56.0, 60.0]), d=80, branch=1)
        >>> frame = grid.to_frame()
        >>> list(frame.index.names), list(frame.columns), frame.attrs["units"]["rocker"]
        (['theta', 'c'], ['rocker', 'assembled'], 'rad')
        """
        try:
            import pandas  # an optional extra
        except ImportError:
            raise ImportError("Results.to_frame needs pandas: pip install 'symlink-kinematics[pandas]' "
                              "(or pip install pandas)") from None
        shape = self._shape()
        varying = self.varying_inputs()
        levels: list[str] = []
        if len(shape) > 1:
            axes = self._grid_axes(shape)
            levels = [name for name, _ in axes]
            index = pandas.MultiIndex.from_product(
                [values if values is not None else numpy.arange(extent) for (_, values), extent in zip(axes, shape)],
                names=levels)
            names = [name for name in varying if name not in levels] + list(self)
            frame = pandas.DataFrame(self._table(names), index=index)
        else:
            names = varying + list(self)
            frame = pandas.DataFrame(self._table(names))
        frame.attrs["units"] = {name: self._unit(name) for name in levels + names}
        frame.attrs["constants"] = {name: value for name, value in self.inputs.items()
                                    if name not in self and numpy.ndim(value) == 0}
        return frame

    def _repr_html_(self) -> str:
        """The first :data:`HTML_ROWS` rows as an HTML table (inputs, then outputs, with units), and how many
        rows there are; a grid says its shape."""
        names = self.columns()
        table = self._table(names)
        shape = self._shape()
        rows = int(numpy.prod(shape)) if names else 0
        import html
        head = "".join(f"<th>{html.escape(self.column(name))}</th>" for name in names)
        body = []
        for k in range(min(rows, HTML_ROWS)):
            cells = "".join(f"<td>{html.escape(_cell(column[k]))}</td>" for column in table.values())
            body.append(f"<tr><th>{k}</th>{cells}</tr>")
        grid = f" (a {' x '.join(map(str, shape))} grid, in row-major order)" if len(shape) > 1 else ""
        more = f"<p>{rows - HTML_ROWS} more rows of {rows}{grid}</p>" if rows > HTML_ROWS else (
            f"<p>{rows} rows{grid}</p>" if grid else "")
        return f"<table><thead><tr><th></th>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>{more}"


def checked_out(out: object, dtypes: Mapping[str, numpy.dtype], shape: tuple[int, ...],
                arguments: Sequence[tuple[str, object]] = (), overlaps: bool = True) -> dict[str, numpy.ndarray]:
    """The caller's output arrays ``out`` by name, checked: one for each output, each one a writable
    C-contiguous array of its dtype and of the call's ``shape``, overlapping no other and no argument.

    ``dtypes`` names the call's outputs (``assembled`` among them) and their dtypes;
    ``arguments`` are ``(name, array)`` pairs of the call.  ``ValueError`` naming the output
    otherwise, before anything is written.  ``overlaps=False`` leaves the overlaps to the
    caller, who knows the addresses already (:func:`refuse_overlaps`).

    >>> rocker, assembled = numpy.empty(2), numpy.empty(2, dtype=bool)
    >>> kinds = {"rocker": numpy.dtype(float), "assembled": numpy.dtype(bool)}
    >>> checked_out({"rocker": rocker, "assembled": assembled}, kinds, (2,))["rocker"] is rocker
    True
    >>> checked_out({"rocker": rocker}, kinds, (2,))
    Traceback (most recent call last):
    ValueError: out has no array for the output 'assembled' (a call writes rocker, assembled)
    >>> checked_out({"rocker": numpy.empty(4)[::2], "assembled": assembled}, kinds, (2,))
    Traceback (most recent call last):
    ValueError: out['rocker'] must be C-contiguous (a call writes its values in order)
    """
    names = ", ".join(dtypes)
    if not isinstance(out, Mapping):
        raise ValueError(f"out must be a dict of NumPy arrays by output name ({names}), got {type(out).__name__}")
    for name in out:
        if name not in dtypes:
            raise ValueError(f"out[{name!r}]: the call has no output {name!r}; it writes {names}")
    checked: dict[str, numpy.ndarray] = {}
    for name, dtype in dtypes.items():
        if name not in out:
            raise ValueError(f"out has no array for the output {name!r} (a call writes {names})")
        array = out[name]
        if type(array) is not numpy.ndarray:
            raise ValueError(f"out[{name!r}] must be a NumPy array, got {type(array).__name__}")
        if array.dtype != dtype:
            raise ValueError(f"out[{name!r}] must have dtype {dtype}, got {array.dtype}")
        if array.shape != tuple(shape):
            raise ValueError(f"out[{name!r}] must have the call's shape {tuple(shape)}, got {array.shape}")
        if not array.flags.c_contiguous:
            raise ValueError(f"out[{name!r}] must be C-contiguous (a call writes its values in order)")
        if not array.flags.writeable:
            raise ValueError(f"out[{name!r}] must be writable")
        checked[name] = array
    if overlaps:
        refuse_overlaps([(name, _byte_span(array)) for name, array in checked.items()],
                        [(name, _byte_span(value)) for name, value in arguments
                         if isinstance(value, numpy.ndarray) and value.size])
    return checked


def refuse_overlaps(outputs: Sequence[tuple[str, tuple[int, int]]],
                    arguments: Sequence[tuple[str, tuple[int, int]]] = ()) -> None:
    """``ValueError`` naming the first output whose bytes overlap an earlier output's or an argument's.

    Each output and argument is a name and its extent in memory: the first byte and the one past the
    last (numpy.may_share_memory's test, on bounds found once).

    >>> refuse_overlaps([("rocker", (0, 80)), ("assembled", (80, 90))], [("theta", (100, 180))])
    >>> refuse_overlaps([("rocker", (0, 80))], [("theta", (40, 120))])
    Traceback (most recent call last):
    ValueError: out['rocker'] overlaps the argument theta; give each output its own memory
    """
    given = [(f"the argument {name}", span) for name, span in arguments]
    for k, (name, (start, end)) in enumerate(outputs):
        for where, (low, high) in [(f"out[{other!r}]", span) for other, span in outputs[:k]] + given:
            if start < high and low < end:
                raise ValueError(f"out[{name!r}] overlaps {where}; give each output its own memory")


def _byte_span(array: numpy.ndarray) -> tuple[int, int]:
    """The first byte an array reaches and the one past its last (its extent in memory, whatever its strides)."""
    start = end = array.__array_interface__["data"][0]
    for extent, stride in zip(array.shape, array.strides):
        if extent == 0:
            return start, start
        if stride < 0:
            start += stride * (extent - 1)
        else:
            end += stride * (extent - 1)
    return start, end + array.itemsize


def _cell(value: object) -> str:
    if isinstance(value, (bool, numpy.bool_)):
        return str(bool(value))
    if isinstance(value, (float, numpy.floating)):
        return f"{float(value):.6g}"
    return str(value)
