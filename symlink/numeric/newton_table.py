"""The table of a linkage without a closed form: Newton's method from an assembly at the first input value,
continued from value to value along the sweep, in its order.

The one driver of such a table, for ``symlink table NAME --guess ...``, the catalog's table commands
(``symlink stephenson2``), and a scene file with a ``[guess]`` (``symlink run``,
:func:`symlink.io.scene.read_scene`).  It takes plain data: the table's facts
(:func:`symlink.io.table_source.table_facts`) and what makes its Newton solver (the disk cache's
:class:`~symlink.numeric.cached_solver.CachedNewtonSolver`, or a :class:`~symlink.numeric.solver.NumericSolver`), so
that a warm process imports no SymPy.  The continuation needs the whole sweep at once: one block.

>>> from symlink.mechanism.catalog import fourbar
>>> from symlink.numeric.solver import NumericSolver
>>> facts = {"name": "fourbar", "inputs": ["theta"], "parameters": ["a", "b", "c", "d"],
...          "newton": {"unknowns": {"coupler": "beta", "rocker": "phi"}, "outputs": {"rocker": "phi"}}}
>>> inputs = {"theta": numpy.radians([0.0, 40.0]), "thetadot": 10.5, "thetaddot": 0.0}
>>> results = newton_results(facts, lambda: NumericSolver(fourbar()), dict(a=20, b=66, c=56, d=80), inputs,
...                          [{"beta": 0.3, "phi": 1.9}])
>>> [round(float(v), 2) for v in numpy.degrees(results[1]["rocker"])]  # seed 003: 110.74 at theta = 0
[110.74, 103.82]
"""
from __future__ import annotations

from typing import Any, Callable, Mapping, Sequence

import numpy

from ..common.limits import require_memory

__all__ = ["newton_results"]


def newton_results(facts: Mapping[str, Any], solver: Callable[[], Any], values: Mapping[str, float],
                   inputs: Mapping[str, Any], starts: Sequence[Mapping[str, float]],
                   advice: Callable[[int], str] | None = None) -> dict[int, dict[str, numpy.ndarray]]:
    """The table's one block on its one branch (+1): each column (``facts["newton"]["outputs"]``, by label) and
    ``assembled``, solved by Newton's method from the first of ``starts`` that continues over the whole sweep.

    Parameters
    ----------
    facts : mapping
        The table's facts (:func:`symlink.io.table_source.table_facts`): ``name``, ``inputs``, ``parameters`` and
        ``newton`` (the unknowns' labels and the columns' outputs).
    solver : callable
        Makes the Newton solver, once the sweep is known to fit in memory.
    values : mapping of str to float
        The parameters by name (angles in radians); others are not read.
    inputs : mapping of str to array_like
        The inputs, their rates and accelerations along the sweep (:func:`symlink.numeric.input_sweep.table_inputs`).
    starts : sequence of mappings of str to float
        Assemblies at the first input value (each unknown by name, radians), tried in order.
    advice : callable, optional
        What to do when the sweep does not fit in memory, given the number of values that fits
        (:func:`symlink.common.limits.require_memory`).

    Raises
    ------
    ValueError
        The first start's failure where none gets through (Newton's method does not converge, or meets a dead
        centre, naming the input value), and a sweep that does not fit in memory.
    """
    name, newton = facts["name"], facts["newton"]
    newton_solver = solver()
    count = numpy.size(inputs[facts["inputs"][0]])  # Newton continues along the whole sweep at once
    require_memory(count, newton_solver.bytes_per_value, f"a table of {count:,} crank angles of {name} (solved by "
                   "Newton's method all at once)",
                   advice=advice or (lambda fits: f"use at most {fits:,} crank angles (a larger step or fewer angles)"))
    parameters = {p: values[p] for p in facts["parameters"]}
    failure: ValueError | None = None
    for start in starts:
        try:
            result = newton_solver(guess=start, **inputs, **parameters)
        except ValueError as error:
            failure = failure or error
            continue
        columns = {column: result[output] for column, output in newton["outputs"].items()}
        return {1: {**columns, "assembled": result["assembled"]}}
    if failure is None:
        raise ValueError(f"{name}: no assembly to start Newton's method from")
    raise failure
