"""Numeric solvers compiled from a linkage's outputs, with checked inputs.

A :class:`Solver` generates the NumPy code for the outputs it is asked for,
loads it, and calls it with validated values: lengths must be positive and
finite, branches +1 or -1, every value finite and real, shapes broadcasting
(the check that every generated function makes,
:func:`symlink.codegen.numpy.checked_arguments`), and the call must fit in
the memory the machine has (:mod:`symlink.limits`).  Where the linkage cannot
be assembled the result says so in its ``assembled`` mask.  A :class:`NumericSolver` generates and
loads Newton's method on the closure instead, for linkages without a closed
form (and any other).

Both return :class:`~symlink.results.Results`: a dict of arrays by output
name that also knows each output's unit and shows itself as a table in a
notebook (``to_frame()`` for pandas).  Arguments may be pint quantities,
converted as :mod:`symlink.units` says (angles to radians, lengths to one
unit, rates per second) or refused where they would mix.

>>> from symlink.catalog import fourbar
>>> solver = Solver(fourbar(), ["rocker"])
>>> result = solver(theta=0.0, a=20, b=66, c=56, d=80, branch=1)
>>> round(float(numpy.degrees(result["rocker"])), 2)
110.74
"""
from __future__ import annotations

import functools
import inspect
import math
import re
from functools import cached_property, lru_cache
from typing import Any, Callable, Mapping, Sequence

import numpy

from .cache import cache_key, cached_text, generated_code
from .codegen import newton
from .codegen.numpy import checked_arguments, load_numpy_module
from .input_sweep import crank_speeds  # noqa: F401 - its home is input_sweep (no SymPy); kept here for callers
from .limits import require_memory
from .linkage import Linkage, Program, is_branch_name
from .results import Results
from .units import ANY_LENGTH, output_units, plain_values
from .vectors import acceleration, rate

__all__ = ["Solver", "NumericSolver", "shared_solver", "check_lengths", "crank_speeds"]


def check_lengths(**lengths: float) -> None:
    """``ValueError`` naming the first length that is not a positive finite (real) number.

    >>> check_lengths(crank=20.0, rocker=[56.0, -1.0])
    Traceback (most recent call last):
    ValueError: rocker must be a positive finite length, got -1.0
    """
    checked_arguments(list(lengths), list(lengths.values()), lengths=list(lengths))


class Solver:
    """A vectorised solver for some outputs of a linkage: the compiled C loop where a C compiler works, else NumPy.

    ``backend`` (else the ``SYMLINK_BACKEND`` environment variable, else ``"auto"``):

    * ``"auto"``: the compiled backend (:mod:`symlink.compiled`) where a C compiler works (probed once
      a process). Its library is built once into the cache: where it is there already it is used from
      the first call; else it is compiled in the background while the NumPy module answers, and
      used from the first call after it is ready (:meth:`wait_for_backend` waits for it).
    * ``"numpy"``: the generated NumPy module only.
    * ``"compiled"``: the compiled backend, built now; where it cannot be, one ``FallbackWarning`` and NumPy.

    Both backends compute the same straight-line program and check the arguments alike; their results
    agree to a few units in the last place (libm's and NumPy's sin, cos and atan2 may round differently).
    :attr:`backend` says which one answers now.

    >>> from symlink.catalog import fourbar
    >>> Solver(fourbar(), ["rocker"], backend="numpy").backend
    'numpy'
    """

    def __init__(self, linkage: Linkage, outputs: Sequence[str], backend: str | None = None) -> None:
        from . import compiled_library as compiled  # the C libraries (it imports no solver)
        self.linkage = linkage
        self.outputs = list(outputs)
        self.backend_choice = compiled.chosen_backend(backend)
        code = generated_code(linkage, self.outputs)  # derived once, then from the scene cache
        self.source, self.function, self.arguments = code.source, code.function, code.arguments
        self._compiled: Any = None  # the compiled function (symlink.compiled._Entry) once it answers
        self._build: Any = None  # its background build, until it is over
        if self.backend_choice == "compiled":
            self._compiled = compiled.compiled_or_warning(linkage, self.outputs)
        elif self.backend_choice == "auto":
            self._compiled, self._build = compiled.entry_or_build(linkage, self.outputs)

    @property
    def backend(self) -> str:
        """``"compiled"`` or ``"numpy"``: the backend that answers the next call."""
        return "numpy" if self._answering() is None else "compiled"

    def wait_for_backend(self, timeout: float | None = None) -> str:
        """Wait (at most ``timeout`` seconds) for a background build of the compiled backend; the backend then."""
        if self._build is not None:
            self._build.wait(timeout)
        return self.backend

    def _answering(self) -> Any:
        """The compiled function where it answers (a background build just finished is adopted here), else ``None``."""
        if self._build is not None and self._build.done():
            self._compiled, self._build = self._build.entry(), None
        return self._compiled

    @property
    def branches(self) -> list[str]:
        """The names of the branch arguments (+1 or -1 each)."""
        return [name for name in self.arguments if is_branch_name(name)]

    @cached_property
    def program(self) -> Program:
        """The straight-line program behind the code (derived on first access only)."""
        return self.linkage.program(self.outputs)

    @cached_property
    def _unchecked(self) -> Callable[..., dict]:
        """The function, told not to check again what :meth:`__call__` has checked (where it checks at all)."""
        if "check" in inspect.signature(self.function).parameters:
            return functools.partial(self.function, check=False)
        return self.function

    @cached_property
    def bytes_per_value(self) -> int:
        """Memory a call needs for each input value: its outputs, the generated code's intermediates, temporaries."""
        return 8 * (len(self.outputs) + 2 + _assignments(self.source) + _TEMPORARIES)

    @cached_property
    def units(self) -> dict[str, str]:
        """The unit of each output, lengths named ``length`` (:func:`symlink.units.output_units`)."""
        return output_units(self.linkage, self.outputs + ["assembled"])

    @cached_property
    def _layout(self) -> tuple[frozenset[str], list[str], list[str]]:
        """What every call checks against, made once: the argument names, the lengths and the branches."""
        return frozenset(self.arguments), [s.name for s in self.linkage.parameters if s.is_positive], self.branches

    def __call__(self, **values) -> Results:
        compiled = self._compiled if self._build is None else self._answering()
        if compiled is not None:
            # A small call of plain numbers and float arrays: the compiled function's fast path, whose C wrapper
            # checks the values as the NumPy module does (anything else, or a value it refuses, goes on below).
            small = compiled._small_outputs(values)
            if small is not None:
                return Results(small.results, self._result_units)
        accepted, lengths, branches = self._layout
        if not accepted.issuperset(values):
            unknown = set(values) - accepted
            raise ValueError(f"{self.linkage.name} takes {', '.join(self.arguments)}; not {', '.join(sorted(unknown))}")
        if all(type(value) in _PLAIN_TYPES for value in values.values()):  # no quantities: nothing to convert
            length_unit = None
        else:
            values, length_unit = plain_values(self.linkage, values)
        if not _surely_small(values, self.bytes_per_value):
            _require_memory(self, values, self.bytes_per_value, "solver")
        names = list(values)
        arrays, _ = checked_arguments(names, list(values.values()), lengths, branches)
        evaluate = self._unchecked if compiled is None else compiled
        with numpy.errstate(invalid="ignore", divide="ignore"):
            return _results(evaluate(**dict(zip(names, arrays))), self.units, length_unit)

    @cached_property
    def _result_units(self) -> dict[str, str]:
        """The unit of each result of a call, ``assembled`` included (the fast path's, made once)."""
        return {name: self.units.get(name, "") for name in self.outputs + ["assembled"]}


#: Argument types that are never quantities and whose size is known without converting them.
_PLAIN_TYPES = frozenset({float, int, bool, numpy.float64, numpy.ndarray})

#: A call surely needing less memory than this is not checked against the memory available (a file read a call).
_SMALL_CALL_BYTES = 1 << 26


def _surely_small(values: Mapping[str, Any], bytes_per_value: int) -> bool:
    """Whether a call surely needs less than :data:`_SMALL_CALL_BYTES`: its broadcast size is at most the product of its arrays' sizes."""
    bound = bytes_per_value
    for value in values.values():
        kind = type(value)
        if kind is numpy.ndarray:
            bound *= value.size
        elif kind not in _PLAIN_TYPES:
            return False
        if bound > _SMALL_CALL_BYTES:
            return False
    return True


#: NumPy's own temporaries while it evaluates one generated line (counted generously), in arrays.
_TEMPORARIES = 4


def _results(values: Mapping[str, numpy.ndarray], units: Mapping[str, str], length_unit: str | None) -> Results:
    """``values`` as :class:`~symlink.results.Results`, lengths in ``length_unit`` where one was given."""
    if length_unit is not None:
        units = {name: unit.replace(ANY_LENGTH, length_unit) for name, unit in units.items()}
    return Results(values, {name: units.get(name, "") for name in values})


def _assignments(source: str) -> int:
    """The most assignments of any function of generated Python ``source``: its arrays, all alive at its end."""
    return max((len(re.findall(r"^    [A-Za-z_]\w* = ", function, re.MULTILINE))
                for function in source.split("\ndef ")[1:]), default=0)


def _require_memory(solver: Any, values: Mapping[str, Any], bytes_per_value: int, kind: str) -> None:
    """Refuse (one line, :func:`symlink.limits.require_memory`) a call of ``solver`` too large for the memory."""
    try:
        shape = numpy.broadcast_shapes(*(numpy.shape(value) for value in values.values()))
    except ValueError:
        return  # the argument check says which shapes do not broadcast
    count = math.prod(shape)
    require_memory(count, bytes_per_value, f"solving {count:.3g} input values with the {solver.linkage.name} {kind}")


class NumericSolver:
    """Newton's method on a linkage's closure, generated as NumPy code and loaded.

    Call it with the inputs (a one-dimensional sweep), the parameters (one
    number each), ``guess`` (the unknowns near the wanted assembly at the first
    input value) and optionally the inputs' rates and accelerations; it
    returns positions, rates and accelerations like the closed-form solvers.
    It works with or without a closed form; see :mod:`symlink.codegen.newton`
    for how the generated module solves.

    >>> from symlink.catalog import fourbar
    >>> solver = NumericSolver(fourbar())
    >>> result = solver(theta=[0.0, 0.1], a=20, b=66, c=56, d=80, guess={"beta": 1.0, "phi": 2.0})
    >>> [round(float(v), 2) for v in numpy.degrees(result["rocker"])]
    [110.74, 108.94]
    """

    def __init__(self, linkage: Linkage) -> None:
        self.linkage = linkage
        # Derived once, then from the scene cache, as every other generated solver.
        self.source = cached_text(cache_key(linkage, [], "numeric"), lambda: newton.numeric_module(linkage))
        self.functions = load_numpy_module(self.source)

    @property
    def arguments(self) -> list[str]:
        signature = self.linkage.inputs + self.linkage.parameters
        rates = tuple(rate(x) for x in self.linkage.inputs) + tuple(acceleration(x) for x in self.linkage.inputs)
        return [s.name for s in signature] + ["guess"] + [s.name for s in rates]

    @cached_property
    def units(self) -> dict[str, str]:
        """The unit of each output, lengths named ``length`` (:func:`symlink.units.output_units`)."""
        return output_units(self.linkage, self.linkage.output_names() + ["assembled"])

    def __call__(self, guess: Mapping[str, float] | Sequence[float], **values) -> Results:
        names = self.arguments
        unknown = set(values) - set(names)
        missing = [s.name for s in self.linkage.inputs + self.linkage.parameters if s.name not in values]
        if unknown or missing:
            raise ValueError(f"{self.linkage.name} takes {', '.join(names)}; "
                             + (f"not {', '.join(sorted(unknown))}" if unknown else f"missing {', '.join(missing)}"))
        values, length_unit = plain_values(self.linkage, values)
        _require_memory(self, values, self.bytes_per_value, "numeric solver")
        return _results(self.functions["accelerations"](guess=guess, **values), self.units, length_unit)

    @cached_property
    def bytes_per_value(self) -> int:
        """Memory a call needs for each input value: positions, rates, Jacobians and their work arrays, outputs."""
        unknowns = len(self.linkage.unknowns)
        outputs = 2 * len(self.linkage.points) + len(self.linkage.extras) + 3 * (unknowns + len(self.linkage.roles))
        return 8 * (6 * unknowns * unknowns + 12 * unknowns + _assignments(self.source) + outputs + 2 + _TEMPORARIES)


@lru_cache(maxsize=None)
def shared_solver(build: Callable[..., Linkage], outputs: tuple[str, ...], *arguments: object) -> Solver:
    """A :class:`Solver` of ``outputs`` of ``build(*arguments)``, made once a process and then shared.

    The one memo in front of the scene cache, for library code that solves the
    same linkage over and over (a four-bar's analysis, its plots, the four
    cases of a vector loop): building a linkage and computing its cache key
    costs about half a millisecond, a call of the solver far less.

    >>> from symlink.catalog import fourbar
    >>> shared_solver(fourbar, ("rocker",)) is shared_solver(fourbar, ("rocker",))
    True
    """
    return Solver(build(*arguments), list(outputs))
