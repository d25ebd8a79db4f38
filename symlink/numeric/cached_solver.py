"""A catalog linkage's solver from the disk cache alone: a warm process never imports SymPy.

Deriving a linkage needs SymPy, whose import alone takes half a second; a
catalog linkage whose code is already cached needs none of it.  The first
request for some outputs of a catalog linkage derives them as
:class:`~symlink.numeric.solver.Solver` does and stores, beside the generated module,
what a call needs: the argument names, which of them are lengths and branch
signs, each output's unit and the memory a value takes.  That entry's key
(:func:`symlink.numeric.cache.catalog_key`) is computed from the catalog name, the
outputs and the digest of the code that builds and prints the linkage, so a
later process finds it without building the linkage, and runs the generated
module (NumPy only).

:class:`CachedSolver` checks and returns what :class:`~symlink.numeric.solver.Solver`
does (the generated function checks its arguments, as ``Solver`` does with
the same check); pint quantities are handed to a ``Solver``, built then.

>>> solver = CachedSolver("fourbar", ["rocker"])
>>> round(float(numpy.degrees(solver(theta=0.0, a=20, b=66, c=56, d=80, branch=1)["rocker"])), 2)
110.74
>>> solver.check_lengths(crank=20.0, rocker=-1.0)
Traceback (most recent call last):
ValueError: rocker must be a positive finite length, got -1.0
"""
from __future__ import annotations

import math
import numbers
from functools import cached_property
from typing import Any, Callable, Sequence

import numpy

from .cache import cached_module, catalog_key
from .call_arguments import check_argument_names
from ..common.limits import require_memory
from .results import Results
from .background_backend import BackgroundBackend

__all__ = ["CachedSolver", "CachedNewtonSolver", "ENTRY_KIND", "DESCRIPTION", "entry_text", "newton_entry_text"]

#: The kind of cache entry (:func:`symlink.numeric.cache.catalog_key`) that holds a catalog solver (``/2``: its
#: description has the arguments' units).
ENTRY_KIND = "catalog-solver/2"
#: The name of the function in the generated module, and of its argument check.
FUNCTION, CHECK = "solve", "_arguments"
#: The name of the dictionary that the entry adds to the module: arguments, lengths, branches, units, memory.
DESCRIPTION = "SOLVER_DESCRIPTION"


def _derived_entry(name: str, outputs: Sequence[str]) -> str:
    """The cache entry of ``outputs`` of the catalog linkage ``name``: symbolic work (SymPy), done once.

    The generated module, followed by a dictionary of what a call needs (:data:`DESCRIPTION`).
    """
    from ..mechanism.catalog import CATALOG
    if name not in CATALOG:
        raise ValueError(f"no linkage {name!r} in the catalog; it has {', '.join(sorted(CATALOG))}")
    return entry_text(CATALOG[name](), outputs)


def entry_text(linkage: Any, outputs: Sequence[str], **more: Any) -> str:
    """A cache entry of ``outputs`` of ``linkage``: its generated NumPy module and what a call needs.

    ``more`` adds further facts to the description (plain Python values), for the entry's user.
    """
    from .solver import Solver
    solver = Solver(linkage, outputs, backend="numpy")
    described = {
        "arguments": solver.arguments, "branches": solver.branches,
        "lengths": [s.name for s in linkage.parameters if s.is_positive], "units": solver.units,
        "input_units": solver.input_units, "required": solver.required,
        "bytes_per_value": solver.bytes_per_value, **more,
    }
    return (f"{solver.source.rstrip()}\n\n\n#: What a call needs, for symlink.numeric.cached_solver (names, units, memory).\n"
            f"{DESCRIPTION} = {described!r}\n")


def newton_entry_text(linkage: Any, **more: Any) -> str:
    """A cache entry of Newton's method on ``linkage``'s closure (:mod:`symlink.codegen.newton`): its generated NumPy
    module and what a call needs, for :class:`CachedNewtonSolver`; ``more`` as for :func:`entry_text`."""
    from .solver import NumericSolver
    from .units import argument_units
    solver = NumericSolver(linkage, backend="numpy")
    arguments = [name for name in solver.arguments if name != "guess"]
    described = {
        "arguments": solver.arguments, "lengths": [s.name for s in linkage.parameters if s.is_positive],
        "required": [s.name for s in linkage.inputs + linkage.parameters] + ["guess"], "units": solver.units,
        "input_units": argument_units(linkage, arguments), "bytes_per_value": solver.bytes_per_value, **more,
    }
    return (f"{solver.source.rstrip()}\n\n\n#: What a call needs, for symlink.numeric.cached_solver (names, units, memory).\n"
            f"{DESCRIPTION} = {described!r}\n")


def _plain(value: object) -> bool:
    """A number, an array or a list of numbers: what the generated code takes as it is (not a pint quantity)."""
    return isinstance(value, (numbers.Number, numpy.ndarray, numpy.generic, list, tuple))


class CachedSolver(BackgroundBackend):
    """The solver of ``outputs`` of the catalog linkage ``name``, run from its cache entry (see the module).

    The entry is derived the first time (SymPy); ``ValueError`` for a name that is not in the catalog, or an
    output the linkage does not have.
    """

    def __init__(self, name: str, outputs: Sequence[str], *, key: str | None = None,
                 derive: Callable[[], str] | None = None, full: Callable[[], Any] | None = None,
                 compiled: bool = False) -> None:
        """``key``, ``derive`` and ``full``: an entry of another request than a catalog linkage's (a scene's
        dynamics, keyed by what it names): its cache key, how to derive it (:func:`entry_text`) and the
        :class:`~symlink.numeric.solver.Solver` that takes quantities.  ``compiled``: the entry's description
        holds the C source of its outputs (``c_solver``: :func:`symlink.numeric.compiled_library.c_solver_source`
        as JSON), and the compiled backend answers as it answers a :class:`~symlink.numeric.solver.Solver`
        (chosen alike: ``SYMLINK_BACKEND``, else where a C compiler works), loaded without SymPy."""
        self.name = name
        self.outputs = list(outputs)
        self._full = full
        if key is None or derive is None:
            key, derive = catalog_key(name, self.outputs, ENTRY_KIND), lambda: _derived_entry(name, self.outputs)
        self.source, namespace = cached_module(key, derive)  # a verified entry of a private cache (never user text)
        entry = namespace[DESCRIPTION]
        self.description: dict[str, Any] = entry
        self.arguments: list[str] = entry["arguments"]
        self.branches: list[str] = entry["branches"]
        self.lengths: list[str] = entry["lengths"]
        self.units: dict[str, str] = entry["units"]
        self.input_units: dict[str, str] = entry["input_units"]
        self.required: list[str] = entry["required"]
        self.bytes_per_value: int = entry["bytes_per_value"]
        self.function: Callable[..., dict] = namespace[FUNCTION]
        self._check: Callable[..., Any] = namespace[CHECK]
        self._compiled: Any = None  # the compiled function where it answers (symlink.numeric.compiled_library)
        self._build: Any = None  # its background build, until it is over
        if compiled:
            import json
            from . import compiled_library
            facts = json.loads(entry["c_solver"])
            choice = compiled_library.chosen_backend()
            if choice == "compiled":
                self._compiled = compiled_library.compiled_or_warning_of(facts)
            elif choice == "auto":
                self._compiled, self._build = compiled_library.entry_or_build_of(facts)

    def check_lengths(self, **lengths: float) -> None:
        """``ValueError`` naming the first length that is not a positive finite number (the generated check)."""
        self._check(True, tuple(lengths), tuple(lengths.values()), tuple(lengths))

    @cached_property
    def full(self) -> Any:
        """The :class:`~symlink.numeric.solver.Solver` of the same outputs (builds the linkage: SymPy), for quantities."""
        if self._full is not None:
            return self._full()
        from ..mechanism.catalog import CATALOG
        from .solver import Solver
        return Solver(CATALOG[self.name](), self.outputs)

    def __call__(self, **values) -> Results:
        """The outputs at ``values``, checked and returned as :class:`~symlink.numeric.solver.Solver` does it.

        >>> CachedSolver("fourbar", ["rocker"])(theta=0.0, a=20, b=66, d=80)
        Traceback (most recent call last):
        ValueError: fourbar needs c (missing); it takes theta, a, b, c, d, branch
        """
        check_argument_names(self.name, self.arguments, self.required, values)
        if not all(_plain(value) for value in values.values()):
            return self.full(**values)
        try:
            count = math.prod(numpy.broadcast_shapes(*(numpy.shape(value) for value in values.values())))
        except ValueError:
            count = 0  # the argument check says which shapes do not broadcast
        if count:
            require_memory(count, self.bytes_per_value, f"solving {count:.3g} input values with the {self.name} solver")
        compiled = self._answering()
        with numpy.errstate(invalid="ignore", divide="ignore"):
            if compiled is None:
                result = self.function(**values)
            else:  # checked as the NumPy module checks (its own check), then the C function: as Solver calls it
                names = tuple(values)
                arrays, _ = self._check(True, names, tuple(values.values()), tuple(self.lengths),
                                        tuple(self.branches))
                result = compiled(**dict(zip(names, arrays)))
        return Results(result, {name: self.units.get(name, "") for name in result}, values, self.input_units)

    def __repr__(self) -> str:
        return f"CachedSolver({self.name!r}, {self.outputs})"


class CachedNewtonSolver:
    """Newton's method on a linkage's closure, run from a cache entry (:func:`newton_entry_text`) without the linkage.

    The twin of :class:`CachedSolver` for a linkage without a closed form: a warm process loads the generated
    NumPy module (the driver of :mod:`symlink.codegen.newton_driver` and the closure system) and imports no
    SymPy.  It answers as :class:`~symlink.numeric.solver.NumericSolver` with ``backend="numpy"`` does, with the
    same checks; plain numbers only (no pint quantities).

    Parameters
    ----------
    name : str
        The linkage's name, for messages.
    key : str
        The entry's cache key (:func:`symlink.numeric.cache.catalog_key`: made without building the linkage).
    derive : callable
        Makes the entry the first time (:func:`newton_entry_text`: builds the linkage, SymPy).

    Examples
    --------
    >>> from symlink.mechanism.catalog import fourbar
    >>> from symlink.numeric.cache import catalog_key
    >>> solver = CachedNewtonSolver("fourbar", catalog_key("fourbar", ["newton"], "newton-example/1"),
    ...                             lambda: newton_entry_text(fourbar()))
    >>> result = solver(theta=[0.0, 0.1], a=20, b=66, c=56, d=80, guess={"beta": 1.0, "phi": 2.0})
    >>> [round(float(v), 2) for v in numpy.degrees(result["rocker"])]  # seed 003: 110.74 at theta = 0
    [110.74, 108.94]
    """

    def __init__(self, name: str, key: str, derive: Callable[[], str]) -> None:
        self.name = name
        self.source, namespace = cached_module(key, derive)  # a verified entry of a private cache (never user text)
        entry = namespace[DESCRIPTION]
        self.description: dict[str, Any] = entry
        self.arguments: list[str] = entry["arguments"]
        self.lengths: list[str] = entry["lengths"]
        self.required: list[str] = entry["required"]
        self.units: dict[str, str] = entry["units"]
        self.input_units: dict[str, str] = entry["input_units"]
        self.bytes_per_value: int = entry["bytes_per_value"]
        self.function: Callable[..., dict] = namespace["accelerations"]
        self._check: Callable[..., Any] = namespace[CHECK]

    def check_lengths(self, **lengths: float) -> None:
        """``ValueError`` naming the first length that is not a positive finite number (the generated check)."""
        self._check(True, tuple(lengths), tuple(lengths.values()), tuple(lengths))

    def __call__(self, guess: Any = None, **values: Any) -> Results:
        """Positions, rates and accelerations along the sweep, from ``guess`` at its first input value."""
        check_argument_names(self.name, self.arguments, self.required,
                             list(values) + (["guess"] if guess is not None else []))
        if not all(_plain(value) for value in values.values()):
            raise ValueError(f"the cached {self.name} solver takes plain numbers; give quantities to NumericSolver")
        try:
            count = math.prod(numpy.broadcast_shapes(*(numpy.shape(value) for value in values.values())))
        except ValueError:
            count = 0  # the argument check says which shapes do not broadcast
        if count:
            require_memory(count, self.bytes_per_value,
                           f"solving {count:.3g} input values with the {self.name} numeric solver")
        with numpy.errstate(invalid="ignore", divide="ignore"):
            result = self.function(guess=guess, **values)
        return Results(result, {name: self.units.get(name, "") for name in result}, values, self.input_units)

    def __repr__(self) -> str:
        return f"CachedNewtonSolver({self.name!r})"
