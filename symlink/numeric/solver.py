"""Numeric solvers compiled from a linkage's outputs, with checked inputs.

A :class:`Solver` generates the NumPy code for the outputs it is asked for,
loads it, and calls it with validated values: lengths must be positive and
finite, branches +1 or -1, every value finite and real, shapes broadcasting
(the check that every generated function makes,
:func:`symlink.codegen.numpy.checked_arguments`), and the call must fit in
the memory the machine has (:mod:`symlink.common.limits`).  Where the linkage cannot
be assembled the result says so in its ``assembled`` mask; where it is assembled at a
toggle (a loop's determinant is zero) a request for rates, accelerations, dynamic forces
or sensitivities, which divide by that determinant, also gets the ``singular`` mask,
True there (see :class:`~symlink.numeric.results.Results`).  A :class:`NumericSolver` generates and
loads Newton's method on the closure instead, for linkages without a closed
form (and any other).

Both return :class:`~symlink.numeric.results.Results`: a dict of arrays by output
name that also knows each output's unit and shows itself as a table in a
notebook (``to_frame()`` for pandas).  Arguments may be pint quantities,
converted as :mod:`symlink.numeric.units` says (angles to radians, lengths to one
unit, rates per second) or refused where they would mix.

>>> from symlink.mechanism.catalog import fourbar
>>> solver = Solver(fourbar(), ["rocker"])
>>> result = solver(theta=0.0, a=20, b=66, c=56, d=80, branch=1)
>>> round(float(numpy.degrees(result["rocker"])), 2)
110.74
"""
from __future__ import annotations

import functools
import html
import inspect
import json
import math
import re
from functools import cached_property, lru_cache
from typing import Any, Callable, Mapping, Sequence, TypeVar

import numpy

from .cache import cache_key, cached_module, cached_text, generated_code
from .call_arguments import check_argument_names, required_arguments
from ..codegen import newton
from ..codegen.arguments import check_lengths, checked_arguments  # noqa: F401 - check_lengths' home is there
from .input_sweep import crank_speeds  # noqa: F401 - its home is input_sweep (no SymPy); kept here for callers
from ..common.limits import require_memory
from ..symbolic.linkage import Linkage, Program, is_branch_name
from .results import Results, checked_out
from .units import ANY_LENGTH, argument_units, output_units, plain_values
from ..symbolic.vectors import acceleration, rate
from .background_backend import BackgroundBackend

SolverOrNumeric = TypeVar("SolverOrNumeric", "Solver", "NumericSolver")

__all__ = ["Solver", "NumericSolver", "shared_solver", "settled", "check_lengths", "crank_speeds"]


class Solver(BackgroundBackend):
    """A vectorised solver for some outputs of a linkage: the compiled C loop where a C compiler works, else NumPy.

    The code for ``outputs``, and only for what they depend on, is
    derived, generated and loaded when the solver is made; the same request
    later, in this process or another, takes it from the cache
    (:mod:`symlink.numeric.cache`) and does no symbolic work.  A call checks its
    arguments and broadcasts them, so a whole turn of the crank, or many
    linkages at once, is one call.

    Parameters
    ----------
    linkage : Linkage
        A linkage with a closed-form plan: from :mod:`symlink.mechanism.catalog`, a
        linkage file (:mod:`symlink.io.linkage_file`) or your own loops.  For one
        without (``linkage.has_closed_form`` False) use :class:`NumericSolver`.
    outputs : sequence of str
        Output names (:meth:`Linkage.output_names` lists them): unknowns
        (``"phi"``), roles (``"rocker"``), rates and accelerations
        (``"rocker_speed"``, ``"phidot"``, ``"rocker_accel"``), coordinates of
        named points (``"C_x"``), extras (``"transmission"``), ``"singular"``
        and design sensitivities (``"rocker__d_a"``).
    backend : {"auto", "numpy", "compiled"}, optional
        Which code answers (default: the ``SYMLINK_BACKEND`` environment
        variable, else ``"auto"``); see the notes.

    Attributes
    ----------
    arguments : list of str
        The keywords a call takes, in order: inputs, parameters, branch signs,
        then the input rates the outputs need (``thetadot``, ``thetaddot``).
    source : str
        The generated NumPy module (it imports NumPy only).

    Raises
    ------
    ValueError
        An output the linkage does not have (the message lists those it has).

    See Also
    --------
    NumericSolver : Newton's method, for linkages without a closed form.
    symlink.numeric.compiled.compiled_solver : the same call, computed by generated C.

    Notes
    -----
    The backends:

    * ``"auto"``: the compiled backend (:mod:`symlink.numeric.compiled`) where a C compiler works (probed once
      a process). Its library is built once into the cache: where it is there already it is used from
      the first call; else it is compiled in the background while the NumPy module answers, and
      used from the first call after it is ready (:meth:`wait_for_backend` waits for it).
    * ``"numpy"``: the generated NumPy module only.
    * ``"compiled"``: the compiled backend, built now; where it cannot be, one ``FallbackWarning`` and NumPy.

    Both backends compute the same straight-line program and check the arguments alike; their results
    agree to a few units in the last place (libm's and NumPy's sin, cos and atan2 may round differently).
    :attr:`backend` says which one answers now.

    >>> import symlink
    >>> symlink.Solver(symlink.fourbar(), ["rocker"], backend="numpy").backend
    'numpy'

    Examples
    --------
    >>> import numpy, symlink
    >>> solver = symlink.Solver(symlink.fourbar(), ["rocker", "rocker_speed"])
    >>> solver.arguments
    ['theta', 'a', 'b', 'c', 'd', 'branch', 'thetadot']
    >>> result = solver(theta=numpy.radians([0.0, 40.0]), a=20, b=66, c=56, d=80, branch=1, thetadot=10.5)
    >>> numpy.degrees(result["rocker"]).round(2), result["rocker_speed"].round(4)
    (array([110.74, 103.82]), array([-3.5   ,  0.0733]))
    """

    def __init__(self, linkage: Linkage, outputs: Sequence[str], backend: str | None = None) -> None:
        from . import compiled_library as compiled  # the C libraries (it imports no solver)
        self.linkage = linkage
        self.outputs = linkage.with_singular(outputs)  # a rate, force or sensitivity brings its flag
        self.backend_choice = compiled.chosen_backend(backend)
        code = generated_code(linkage, self.outputs)  # derived once, then from the scene cache
        self.source, self.function, self.arguments = code.source, code.function, code.arguments
        self._compiled: Any = None  # the compiled function (symlink.numeric.compiled.CompiledFunction) once it answers
        self._build: Any = None  # its background build, until it is over
        if self.backend_choice == "compiled":
            self._compiled = compiled.compiled_or_warning(linkage, self.outputs)
        elif self.backend_choice == "auto":
            self._compiled, self._build = compiled.entry_or_build(linkage, self.outputs)

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
        """The unit of each output, lengths named ``length`` (:func:`symlink.numeric.units.output_units`)."""
        return output_units(self.linkage, self.outputs + ["assembled"])

    def _repr_html_(self) -> str:
        """What a call takes and gives, with units: a notebook's view of the solver.

        >>> from symlink.mechanism.catalog import fourbar
        >>> "<td>branch</td><td></td><td>no (default)</td>" in Solver(fourbar(), ["rocker"])._repr_html_()
        True
        """
        def rows(names: list[str], units: Mapping[str, str], needed: Callable[[str], str]) -> str:
            return "".join(f"<tr><td>{html.escape(name)}</td><td>{html.escape(units.get(name, ''))}</td>"
                           f"<td>{needed(name)}</td></tr>" for name in names)
        required = set(self.required)
        takes = rows(self.arguments, self.input_units, lambda name: "yes" if name in required else "no (default)")
        gives = rows(self.outputs + ["assembled"], self.units, lambda name: "")
        return (f"<p>{html.escape(type(self).__name__)} of {html.escape(self.linkage.name)}</p>"
                f"<table><thead><tr><th>argument</th><th>unit</th><th>required</th></tr></thead>"
                f"<tbody>{takes}</tbody></table><table><thead><tr><th>output</th><th>unit</th><th></th></tr></thead>"
                f"<tbody>{gives}</tbody></table>")

    @cached_property
    def input_units(self) -> dict[str, str]:
        """The unit of each argument (``rad``, ``rad/s``, ``length``; ``''`` for a branch sign)."""
        return argument_units(self.linkage, self.arguments)

    @cached_property
    def required(self) -> list[str]:
        """The arguments a call must give; the others (the inputs' rates and accelerations) default to 0."""
        return required_arguments(self.function)

    @cached_property
    def _layout(self) -> tuple[frozenset[str], frozenset[str], list[str], list[str]]:
        """What every call checks against, made once: the argument names, the required ones, the lengths and
        the branches."""
        return (frozenset(self.arguments), frozenset(self.required),
                [s.name for s in self.linkage.parameters if s.is_positive], self.branches)

    def __call__(self, *, out: Any = None, **values) -> Results:
        """Evaluate the outputs at ``values``: every argument by keyword, arrays broadcasting together.

        Parameters
        ----------
        out : dict of str to numpy.ndarray, optional
            Arrays to write the results into, one for each output of the call
            (the outputs, ``singular`` where the solver added it, and
            ``assembled``): each of the call's broadcast shape, C-contiguous,
            writable, float64 (bool for ``assembled`` and ``singular``), none
            overlapping another or an argument.  A result of an earlier call
            of the same shape is one (``out=result``).  The compiled backend
            writes into them directly; the NumPy backend computes, then copies.
            A bad ``out`` is refused before anything is written; the compiled
            backend checks the values chunk by chunk as it evaluates them, so a
            value it refuses may leave the chunks before it written.
            Without ``out`` the outputs are new arrays, views of one block a
            call; a block that no caller holds any more (no result, row or
            view of it referenced anywhere) is written again instead of a new
            one, and a block a caller holds is never written again.
        **values : float, array_like or pint quantity
            One value for each name in :attr:`arguments`: input angles in
            radians, lengths (positive and finite, any one unit), fixed angles,
            branch signs (+1 or -1, ``branch`` or ``branch_<LOOP>``) and input
            rates in rad/s and rad/s^2.  Any of them may be an array; their
            shapes broadcast, and the outputs take the broadcast shape.  pint
            quantities are converted as :mod:`symlink.numeric.units` says.

        Returns
        -------
        Results
            A dict of arrays by output name, and ``assembled``: False where the
            linkage cannot be assembled (its outputs are NaN there).
            ``Results.units`` names each output's unit.  With ``out``, its
            arrays are the caller's, written in place.

        Raises
        ------
        ValueError
            An argument the linkage does not take; a length that is not a
            positive finite number; a branch sign other than +1 or -1; a value
            that is not finite and real; shapes that do not broadcast; a call
            needing more memory than the machine has; lengths with and
            without units together; an unknown or a missing argument, by name
            (:func:`symlink.numeric.call_arguments.check_argument_names`).

        Examples
        --------
        >>> from symlink.mechanism.catalog import fourbar
        >>> solver = Solver(fourbar(), ["rocker", "C_x"])
        >>> result = solver(theta=numpy.radians([0.0, 180.0]), a=60, b=66, c=56, d=80, branch=1)
        >>> result["assembled"]          # this triple-rocker's crank cannot reach 180 degrees
        array([ True, False])
        >>> solver(theta=0.0, a=-20, b=66, c=56, d=80, branch=1)
        Traceback (most recent call last):
        ValueError: a must be a positive finite length, got -20.0

        A loop over many calls of one shape writes into the arrays of its first result:

        >>> theta = numpy.linspace(0.0, 2 * numpy.pi, 1000)
        >>> result = solver(theta=theta, a=20, b=66, c=56, d=80, branch=1)
        >>> again = solver(theta=theta, a=20, b=66, c=57, d=80, branch=1, out=result)
        >>> again["rocker"] is result["rocker"], bool(again["assembled"].all())
        (True, True)
        >>> solver(theta=theta[:10], a=20, b=66, c=56, d=80, branch=1, out=result)
        Traceback (most recent call last):
        ValueError: out['rocker'] must have the call's shape (10,), got (1000,)
        """
        compiled = self._compiled if self._build is None else self._answering()
        if compiled is not None and compiled._plan is not None:
            # With the call extension, a call of plain numbers and one-dimensional float arrays is answered in C:
            # the keywords walked, the values checked as the NumPy module does and evaluated chunk by chunk,
            # into the caller's arrays (out, checked) or a kept block nobody holds, the Results made without
            # __init__. Anything else, or a value it refuses, goes on below (which says what is wrong).
            plan, extension = compiled._plan, compiled._extension
            if out is None:  # a small call: its own slots and blocks (at most SMALL_CALL values)
                made = extension.results(plan, values, Results, self._result_units, self.input_units)
                if made is not None:
                    return made
            if compiled.before_allocating is None:
                compiled.before_allocating = self._before_block
            made = extension.large(plan, values, out, Results, self._result_units, self.input_units)
            if made is not None:
                return made
        elif compiled is not None and out is None:
            # Without the extension: a small call of plain numbers and float arrays takes the compiled function's
            # Python fast path, whose C wrapper checks the values as the NumPy module does.
            small = compiled._small_outputs(values)
            if small is not None:
                return Results(small.results, self._result_units, values, self.input_units)
        accepted, required, lengths, branches = self._layout
        if not (accepted.issuperset(values) and required.issubset(values)):
            check_argument_names(self.linkage.name, self.arguments, self.required, values)
        if all(type(value) in _PLAIN_TYPES for value in values.values()):  # no quantities: nothing to convert
            length_unit = None
        else:
            values, length_unit = plain_values(self.linkage, values)
        small = _surely_small(values, self.bytes_per_value)
        if compiled is not None and length_unit is None:
            # Numbers and one-dimensional float arrays: checked in C, in one pass (else below, in NumPy, which
            # says what is wrong with a value the C check refuses).
            with numpy.errstate(invalid="ignore", divide="ignore"):
                found = compiled.checked_call(values, out, None if small else functools.partial(
                    _require_memory, self, values, self.bytes_per_value, "solver"))
            if found is not None:
                return Results(found, self._result_units, values, self.input_units)
        if not small and compiled is None:
            _require_memory(self, values, self.bytes_per_value, "solver")
        names = list(values)
        arrays, shape = checked_arguments(names, list(values.values()), lengths, branches)
        if not small and compiled is not None and not compiled.allocates_nothing(arrays, shape, out):
            # (a compiled call writing into the caller's arrays or a kept block allocates nothing: not checked)
            _require_memory(self, values, self.bytes_per_value, "solver")
        with numpy.errstate(invalid="ignore", divide="ignore"):
            if compiled is not None:
                found = compiled(out=out, **dict(zip(names, arrays)))
            else:
                found = self._unchecked(**dict(zip(names, arrays)))
                if out is not None:
                    found = _copied(found, out, shape, list(zip(names, arrays)))
        return _results(found, self.units, length_unit, values, self.input_units)

    def _before_block(self, count: int) -> None:
        """Refuse (one line) a new output block of ``count`` values where the call needs more memory than
        there is (checked only above :data:`_SMALL_CALL_BYTES`: the check reads files)."""
        if count * self.bytes_per_value > _SMALL_CALL_BYTES:
            require_memory(count, self.bytes_per_value,
                           f"solving {count:.3g} input values with the {self.linkage.name} solver")

    @cached_property
    def _result_units(self) -> dict[str, str]:
        """The unit of each result of a call, ``assembled`` included (the fast path's, made once)."""
        return {name: self.units.get(name, "") for name in self.outputs + ["assembled"]}


#: Argument types that are never quantities and whose size is known without converting them.
_PLAIN_TYPES = frozenset({float, int, bool, numpy.float64, numpy.ndarray})

#: A call surely needing less memory than this is not checked against the memory available (a file read a call).
_SMALL_CALL_BYTES = 1 << 26


def _surely_small(values: Mapping[str, Any], bytes_per_value: int) -> bool:
    """Whether a call surely needs less than :data:`_SMALL_CALL_BYTES`: its broadcast size is at most the product
    of the sizes of its arrays' distinct shapes (arrays of one shape broadcast to that shape)."""
    bound, shapes = bytes_per_value, set()
    for value in values.values():
        kind = type(value)
        if kind is numpy.ndarray:
            if value.shape not in shapes:
                shapes.add(value.shape)
                bound *= value.size
        elif kind not in _PLAIN_TYPES:
            return False
        if bound > _SMALL_CALL_BYTES:
            return False
    return True


#: NumPy's own temporaries while it evaluates one generated line (counted generously), in arrays.
_TEMPORARIES = 4


def _results(values: Mapping[str, numpy.ndarray], units: Mapping[str, str], length_unit: str | None,
             inputs: Mapping[str, object], input_units: Mapping[str, str]) -> Results:
    """``values`` as :class:`~symlink.numeric.results.Results` with the call's ``inputs``, lengths in ``length_unit``
    where one was given."""
    if length_unit is not None:
        units = {name: unit.replace(ANY_LENGTH, length_unit) for name, unit in units.items()}
        input_units = {name: unit.replace(ANY_LENGTH, length_unit) for name, unit in input_units.items()}
    return Results(values, {name: units.get(name, "") for name in values}, inputs, input_units)


def _copied(found: Mapping[str, numpy.ndarray], out: Mapping[str, numpy.ndarray], shape: tuple[int, ...],
            arguments: list[tuple[str, numpy.ndarray]]) -> dict[str, numpy.ndarray]:
    """The NumPy module's results ``found`` copied into the caller's arrays ``out``, checked first
    (:func:`symlink.numeric.results.checked_out`): nothing is written where one is refused."""
    checked = checked_out(out, {name: value.dtype for name, value in found.items()}, shape, arguments)
    for name, value in found.items():
        numpy.copyto(checked[name], value)
    return checked


def _assignments(source: str) -> int:
    """The most assignments of any function of generated Python ``source``: its arrays, all alive at its end."""
    return max((len(re.findall(r"^    [A-Za-z_]\w* = ", function, re.MULTILINE))
                for function in source.split("\ndef ")[1:]), default=0)


def _require_memory(solver: Any, values: Mapping[str, Any], bytes_per_value: int, kind: str) -> None:
    """Refuse (one line, :func:`symlink.common.limits.require_memory`) a call of ``solver`` too large for the memory."""
    try:
        shape = numpy.broadcast_shapes(*(numpy.shape(value) for value in values.values()))
    except ValueError:
        return  # the argument check says which shapes do not broadcast
    count = math.prod(shape)
    require_memory(count, bytes_per_value, f"solving {count:.3g} input values with the {solver.linkage.name} {kind}")


class NumericSolver:
    """Newton's method on a linkage's closure, compiled as C where a C compiler works, else generated NumPy code.

    Call it with the inputs (a one-dimensional sweep), the parameters (one
    number each), ``guess`` (the unknowns near the wanted assembly at the first
    input value) and optionally the inputs' rates and accelerations; it
    returns positions, rates and accelerations like the closed-form solvers.
    It works with or without a closed form; see :mod:`symlink.codegen.newton`
    for how the generated module solves, and :mod:`symlink.codegen.newton_c` for the
    compiled driver (the same algorithm, constants and checks, one value at a time).

    ``backend`` chooses as for :class:`Solver` (default: ``SYMLINK_BACKEND``, else
    ``"auto"``): ``"auto"`` uses the compiled driver where its library is built (in
    the cache), else builds it in the background while the NumPy module answers
    (looked for on the first call, or the first look at :attr:`backend`);
    ``"compiled"`` builds it now (one ``FallbackWarning`` and NumPy where it cannot);
    ``"numpy"`` the NumPy module only.  Both agree to about 1e-13; the same inputs
    fail on both, with the same messages.

    Parameters
    ----------
    linkage : Linkage
        Any linkage, with or without a closed form.
    backend : {"auto", "numpy", "compiled"}, optional
        Which code answers, as for :class:`Solver` (default: ``SYMLINK_BACKEND``, else ``"auto"``).

    Examples
    --------
    >>> import numpy, symlink
    >>> solver = symlink.NumericSolver(symlink.fourbar())
    >>> result = solver(theta=[0.0, 0.1], a=20, b=66, c=56, d=80, guess={"beta": 1.0, "phi": 2.0})
    >>> [round(float(v), 2) for v in numpy.degrees(result["rocker"])]  # seed 003: 110.74 at theta = 0
    [110.74, 108.94]
    """

    def __init__(self, linkage: Linkage, backend: str | None = None) -> None:
        from . import compiled_library as compiled  # the C libraries (it imports no solver)
        self.linkage = linkage
        # Derived once, then from the scene cache, as every other generated solver.
        self.source, self.functions = cached_module(cache_key(linkage, [], "numeric"),
                                                    lambda: newton.numeric_module(linkage))
        self.backend_choice = compiled.chosen_backend(backend)
        self._compiled: _CompiledNewton | None = None  # the compiled driver once it answers
        self._build: Any = None  # its background build, until it is over
        # "auto" looks for (or starts building) the compiled driver on first use, so that a solver made for its
        # NumPy functions alone (design sensitivities) derives no C; "compiled" builds it now.
        self._looked = self.backend_choice != "auto"
        if self.backend_choice == "compiled":
            self._compiled, self._build = _compiled_newton(linkage, self.backend_choice)

    @property
    def backend(self) -> str:
        """``"compiled"`` or ``"numpy"``: the backend that answers the next call."""
        return "numpy" if self._answering() is None else "compiled"

    def wait_for_backend(self, timeout: float | None = None) -> str:
        """Wait (at most ``timeout`` seconds) for a background build of the compiled driver; the backend then."""
        self._answering()  # looks for it (or starts its build) if no call has yet
        if self._build is not None:
            self._build.wait(timeout)
        return self.backend

    def _answering(self) -> _CompiledNewton | None:
        """The compiled driver where it answers (a background build just finished is adopted here), else ``None``."""
        if not self._looked:
            self._looked = True
            self._compiled, self._build = _compiled_newton(self.linkage, self.backend_choice)
        if self._build is not None and self._build.done():
            from . import compiled_library as compiled
            library = None if self._build.error is not None else compiled.built_library(self._build.facts["source"])
            self._compiled = None if library is None else _CompiledNewton(library, self._build.facts)
            self._build = None
        return self._compiled

    @property
    def arguments(self) -> list[str]:
        signature = self.linkage.inputs + self.linkage.parameters
        rates = tuple(rate(x) for x in self.linkage.inputs) + tuple(acceleration(x) for x in self.linkage.inputs)
        return [s.name for s in signature] + ["guess"] + [s.name for s in rates]

    @cached_property
    def units(self) -> dict[str, str]:
        """The unit of each output, lengths named ``length`` (:func:`symlink.numeric.units.output_units`)."""
        return output_units(self.linkage, self.linkage.output_names() + ["assembled"])

    def __call__(self, guess: Mapping[str, float] | Sequence[float] | None = None, **values) -> Results:
        required = [s.name for s in self.linkage.inputs + self.linkage.parameters] + ["guess"]
        check_argument_names(self.linkage.name, self.arguments, required,
                             list(values) + (["guess"] if guess is not None else []))
        values, length_unit = plain_values(self.linkage, values)
        if not _surely_small(values, self.bytes_per_value):
            _require_memory(self, values, self.bytes_per_value, "numeric solver")
        compiled = self._answering()
        found = (self.functions["accelerations"](guess=guess, **values) if compiled is None
                 else self._compiled_sweep(compiled, guess, values))
        return _results(found, self.units, length_unit, values, self._argument_units(tuple(values)))

    def _argument_units(self, names: tuple[str, ...]) -> dict[str, str]:
        """The unit of each argument of a call (:func:`symlink.numeric.units.argument_units`), found once a set of names."""
        known = self.__dict__.setdefault("_units_of_arguments", {})
        if names not in known:
            known[names] = argument_units(self.linkage, list(names))
        return known[names]

    def _compiled_sweep(self, compiled: _CompiledNewton, guess: Any, values: Mapping[str, Any]) -> dict:
        """What the NumPy module's ``accelerations`` returns, from the compiled driver: the same checks (the
        module's own), the sweep in C, the same results."""
        functions, linkage = self.functions, self.linkage
        names = [s.name for s in linkage.inputs + linkage.parameters]
        rate_names = [rate(x).name for x in linkage.inputs]
        accel_names = [acceleration(x).name for x in linkage.inputs]
        checked = names + rate_names + accel_names
        functions["_arguments"](True, tuple(checked), tuple(values.get(n, 0.0) for n in checked),
                                tuple(s.name for s in linkage.parameters if s.is_positive))
        count = len(linkage.inputs)
        arguments = [values[n] for n in names]
        shape, inputs, parameters, guess, input_rates, input_accels = functions["_prepared"](
            arguments[:count], arguments[count:], guess, [values.get(n, 0.0) for n in rate_names],
            [values.get(n, 0.0) for n in accel_names])
        q, qdot, qddot, residual = compiled.sweep(inputs, parameters, guess, input_rates, input_accels,
                                                  functions["_failure"])
        return functions["_results"](shape, inputs, parameters, q, qdot, qddot, residual, 2,
                                     compiled.outputs(inputs, parameters, q))

    @cached_property
    def bytes_per_value(self) -> int:
        """Memory a call needs for each input value: positions, rates, Jacobians and their work arrays, outputs."""
        unknowns = len(self.linkage.unknowns)
        outputs = 2 * len(self.linkage.points) + len(self.linkage.extras) + 3 * (unknowns + len(self.linkage.roles))
        return 8 * (6 * unknowns * unknowns + 12 * unknowns + _assignments(self.source) + outputs + 2 + _TEMPORARIES)


class _CompiledNewton:
    """The compiled Newton driver of one linkage (:mod:`symlink.codegen.newton_c`), called through ctypes."""

    def __init__(self, library: Any, facts: Mapping[str, Any]) -> None:
        from . import compiled_library as compiled
        import ctypes
        self.facts = facts
        self.sweep_entry = library.symlink_newton_sweep
        pointer = ctypes.c_void_p
        self.sweep_entry.restype = ctypes.c_int
        self.sweep_entry.argtypes = [ctypes.c_size_t, pointer, pointer, pointer, ctypes.c_int, pointer, pointer,
                                     pointer, pointer, pointer, pointer, pointer]
        self.output_entry = (compiled.CompiledFunction(library, "newton_outputs", facts["output_arguments"], facts["outputs"],
                                             facts["output_flags"], {}) if facts["outputs"] else None)

    def sweep(self, inputs: Sequence[numpy.ndarray], parameters: Sequence[numpy.ndarray], guess: numpy.ndarray,
              input_rates: Sequence[numpy.ndarray] | None, input_accels: Sequence[numpy.ndarray] | None,
              failure: Callable[[int, numpy.ndarray], Exception]) -> tuple:
        """Positions, rates, accelerations and residuals (the NumPy driver's ``_sweep``'s) of checked arguments;
        ``failure(status, report)`` the error raised where the sweep fails."""
        count, unknowns = len(inputs[0]), len(self.facts["unknowns"])
        x = numpy.ascontiguousarray(numpy.stack(inputs), dtype=numpy.float64)
        p = numpy.ascontiguousarray([float(v) for v in parameters], dtype=numpy.float64)
        start = numpy.ascontiguousarray(guess, dtype=numpy.float64)
        rates = input_rates is not None and input_accels is not None
        xdot = numpy.ascontiguousarray(numpy.stack(input_rates) if input_rates is not None else x, dtype=numpy.float64)
        xddot = numpy.ascontiguousarray(numpy.stack(input_accels) if input_accels is not None else x,
                                        dtype=numpy.float64)
        q = numpy.empty((unknowns, count))  # unknown by unknown: each a contiguous array
        qdot, qddot = (numpy.empty((unknowns, count)), numpy.empty((unknowns, count))) if rates else (q, q)
        residual = numpy.empty(count)
        report = numpy.zeros(3 + 2 * len(inputs))
        status = self.sweep_entry(count, x.ctypes.data, p.ctypes.data, start.ctypes.data, int(rates),
                                  xdot.ctypes.data, xddot.ctypes.data, q.ctypes.data, qdot.ctypes.data,
                                  qddot.ctypes.data, residual.ctypes.data, report.ctypes.data)
        if status:
            raise failure(status, report)
        return q.T, (qdot.T if rates else None), (qddot.T if rates else None), residual

    def outputs(self, inputs: Sequence[numpy.ndarray], parameters: Sequence[numpy.ndarray],
                q: numpy.ndarray) -> dict[str, numpy.ndarray]:
        """The named points and extras at the solved positions (the NumPy module's ``_outputs``)."""
        if self.output_entry is None:
            return {}
        values = dict(zip(self.facts["inputs"], inputs))
        values.update(zip(self.facts["parameters"], parameters))
        values.update((name, q[:, k]) for k, name in enumerate(self.facts["unknowns"]))
        found = self.output_entry(**values)
        found.pop("assembled")
        return found


def _cached_newton_c_facts(linkage: Linkage) -> dict[str, Any]:
    """The compiled Newton driver's source and calling facts (:func:`symlink.codegen.newton_c.newton_c_facts`),
    derived once, then read from symlink's cache."""
    from ..codegen.newton_c import newton_c_facts as derive
    return json.loads(cached_text(cache_key(linkage, [], "newton-c"), lambda: json.dumps(derive(linkage))))


def _compiled_newton(linkage: Linkage, choice: str) -> tuple[_CompiledNewton | None, Any]:
    """The compiled driver for ``backend=choice`` ("auto" or "compiled"), or its background build ("auto"), or
    neither (NumPy answers; "compiled" warns once)."""
    from . import compiled_library as compiled
    import subprocess
    import warnings
    if choice == "auto" and not compiled.compiler_works():
        return None, None
    try:
        facts = _cached_newton_c_facts(linkage)
        if choice == "compiled":
            return _CompiledNewton(compiled.compile_shared(facts["source"]), facts), None
    except (compiled.CompilerUnavailable, compiled.CompileError, OSError, subprocess.SubprocessError,
            ValueError, NotImplementedError, TypeError) as error:
        if choice == "compiled":
            warnings.warn(f"symlink: no compiled Newton driver, using NumPy instead: {error}",
                          compiled.FallbackWarning, stacklevel=3)
        return None, None
    library = compiled.built_library(facts["source"])
    if library is not None:
        return _CompiledNewton(library, facts), None
    return None, compiled.build_in_background(facts)


@lru_cache(maxsize=None)
def shared_solver(build: Callable[..., Linkage], outputs: tuple[str, ...], *arguments: object) -> Solver:
    """A :class:`Solver` of ``outputs`` of ``build(*arguments)``, made once a process and then shared.

    The one memo in front of the scene cache, for library code that solves the
    same linkage over and over (a four-bar's analysis, its plots, the four
    cases of a vector loop): building a linkage and computing its cache key
    costs about half a millisecond, a call of the solver far less.

    Parameters
    ----------
    build : callable
        A function that makes the linkage (a catalog entry such as :func:`fourbar`); hashable.
    outputs : tuple of str
        The outputs, as for :class:`Solver`.
    *arguments
        Arguments of ``build``, hashable.

    Returns
    -------
    Solver
        The same solver for the same request, every time in a process.

    Examples
    --------
    >>> import math, symlink
    >>> solver = symlink.shared_solver(symlink.fourbar, ("rocker",))
    >>> solver is symlink.shared_solver(symlink.fourbar, ("rocker",))
    True
    >>> round(math.degrees(float(solver(theta=0.0, a=20, b=66, c=56, d=80)["rocker"])), 2)  # seed 003
    110.74
    """
    return Solver(build(*arguments), list(outputs))


def settled(solver: SolverOrNumeric) -> SolverOrNumeric:
    """``solver`` once its background build is over: from then on one backend answers every call.

    The default ``auto`` backend answers with NumPy while the compiled library builds, then with
    the library; the two agree to rounding, not bit for bit.  A seeded search that called a solver
    across that switch would follow other rounding from the switch on, so its result would depend
    on how long the build took.  Synthesis waits here before it starts: seeded runs are then
    reproducible bit for bit (compiled where a compiler works, NumPy throughout where none does).

    >>> import symlink
    >>> settled(symlink.shared_solver(symlink.fourbar, ("rocker",))).backend in ("compiled", "numpy")
    True
    """
    solver.wait_for_backend()
    return solver
