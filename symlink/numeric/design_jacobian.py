"""The Jacobian of some outputs by some design parameters, evaluated through generated code: what synthesis calls.

A least-squares synthesis moves a linkage's parameters (lengths, fixed
angles, coupler-point offsets, pivot coordinates) until some position outputs
hit targets; it needs the outputs and their exact derivatives by those
parameters at many input values, thousands of times.  :class:`DesignJacobian`
asks the linkage for the outputs and their sensitivities
(:mod:`symlink.symbolic.sensitivity`, named ``<output>__d_<parameter>``), generates
and loads the NumPy code once (cached like every solver), and then each call
is one call of that code, returning the outputs and the Jacobian as one array
of shape ``input shape + (outputs, parameters)``.  Linkages without a closed
form go through the generated Newton module, whose sensitivities come from
the converged closure Jacobian; they need an initial ``guess``.

Where the linkage cannot be assembled ``assembled`` is False and the
Jacobian's entries there are NaN, never a number (a derivative that is a
constant, such as that of a placed point by its pivot, too).  Where it is
assembled at a toggle, ``singular`` is True: the derivatives by a parameter
that closes a loop divide by the loop's determinant, zero there, and are
inf or NaN (:meth:`DesignJacobian.arrays`, the hot loop, leaves the flag out).

An optimiser's inner loop calls :meth:`DesignJacobian.arrays` instead: the
generated arithmetic alone, on arguments known good, given in calling order
(:attr:`DesignJacobian.arguments`), filling one array output by output; it
skips the argument check and the per-output dictionaries of the keyword call,
which on a few dozen input values cost more than the arithmetic.

>>> from symlink.mechanism.catalog import fourbar
>>> jacobian = DesignJacobian(fourbar(), ["B_x", "C_y"], ["a", "b"])
>>> values, slopes = jacobian(theta=[0.0, 0.5], a=20.0, b=66.0, c=56.0, d=80.0)
>>> slopes.shape
(2, 2, 2)
>>> round(float(slopes[1, 0, 0]), 12) == round(float(numpy.cos(0.5)), 12)  # d(B_x)/da = cos(theta)
True
"""
from __future__ import annotations

from functools import lru_cache
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

import numpy

from .cache import FUNCTION, generated_code
from ..codegen.loading import load_numpy_module
from ..common.display import record_html

if TYPE_CHECKING:  # the symbolic side is imported where a Jacobian is derived: one read from an entry needs no SymPy
    from ..symbolic.linkage import Linkage

__all__ = ["DesignJacobian", "design_jacobian", "sensitivity_outputs"]


def sensitivity_outputs(linkage: Linkage, outputs: Sequence[str], parameters: Sequence[str] | None = None) -> list[str]:
    """The names of each output's derivative by each parameter (all parameters by default), output by output.

    ``ValueError`` for an output that is not a position of ``linkage`` (a rate, ``singular``) or a name that
    is not one of its parameters.

    >>> from symlink.mechanism.catalog import fourbar
    >>> sensitivity_outputs(fourbar(), ["rocker"], ["a", "d"])
    ['rocker__d_a', 'rocker__d_d']
    """
    from ..symbolic.sensitivity import sensitivity_name
    known = [p.name for p in linkage.parameters]
    chosen = known if parameters is None else list(parameters)
    for name in chosen:
        if name not in known:
            raise ValueError(f"{linkage.name} has no parameter {name!r}; it has {', '.join(known)}")
    if len(set(chosen)) != len(chosen) or len(set(outputs)) != len(outputs):
        raise ValueError("each output and each parameter may be named once")
    names = [sensitivity_name(output, parameter) for output in outputs for parameter in chosen]
    for name in names:
        linkage.output(name)  # ValueError naming what cannot be differentiated
    return names


#: The name of the dictionary that :meth:`DesignJacobian.entry_text` adds to the generated module.
ENTRY_DESCRIPTION = "JACOBIAN_DESCRIPTION"


class DesignJacobian:
    """Outputs of a linkage and their derivatives by chosen parameters, from generated code loaded once.

    Call it with the generated function's arguments (inputs, every parameter,
    branch signs; for a linkage without a closed form also ``guess``, the
    unknowns near the wanted assembly at the first input value, over a
    one-dimensional sweep).  It returns ``(values, jacobian)``: ``values``
    maps each output (and ``assembled``, and ``singular`` where a derivative
    divides by a loop's determinant) to its array; ``jacobian[..., i, j]``
    is d(outputs[i])/d(parameters[j]).  The generated code checks its arguments; in a hot loop whose
    arguments are known good, ``check=False`` skips that.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    def __init__(self, linkage: Linkage, outputs: Sequence[str], parameters: Sequence[str] | None = None) -> None:
        self.linkage: Linkage | None = linkage
        #: The linkage's name, for messages.
        self.name = linkage.name
        #: Facts a cache entry carried beside the code (:meth:`entry_text`); empty for a derived Jacobian.
        self.facts: dict[str, Any] = {}
        self.outputs = list(outputs)
        if not self.outputs:
            raise ValueError(f"ask {linkage.name} for at least one output")
        self.parameters = [p.name for p in linkage.parameters] if parameters is None else list(parameters)
        self.names = sensitivity_outputs(linkage, self.outputs, self.parameters)
        self._function: Callable[..., Mapping[str, numpy.ndarray]]
        #: The generated arithmetic (closed forms only): arguments in calling order, results in output order.
        self._kernel: Callable[..., tuple] | None = None
        #: The generated function's argument names in calling order (what :meth:`arrays` takes).
        self.arguments: list[str]
        #: Whether the generated code also returns ``singular`` (the sensitivities divide by a loop's determinant).
        self._flagged = False
        #: The generated module's text (closed forms only): what :meth:`entry_text` keeps.
        self._source: str | None = None
        if linkage.has_closed_form:
            requested = linkage.with_singular(self.outputs + self.names)
            self._flagged = len(requested) > len(self.outputs) + len(self.names)
            code = generated_code(linkage, requested)
            self._source = code.source
            self._function = code.function
            self.arguments = code.arguments
            self._kernel = code.function.__globals__[f"_{FUNCTION}_block"]
        else:
            from .solver import NumericSolver
            numeric = NumericSolver(linkage)
            self._function = numeric.functions["sensitivities"]
            self.arguments = numeric.arguments

    def __call__(self, **values: object) -> tuple[dict[str, numpy.ndarray], numpy.ndarray]:
        with numpy.errstate(invalid="ignore", divide="ignore"):  # a toggle divides by zero: ``singular`` says so
            found = self._function(**values)
        assembled = numpy.asarray(found["assembled"])
        shape = assembled.shape
        columns = [numpy.broadcast_to(found[name], shape) for name in self.names]
        jacobian = numpy.stack(columns, axis=-1).reshape(shape + (len(self.outputs), len(self.parameters)))
        if not numpy.all(assembled):  # constant derivatives too are no numbers where nothing is assembled
            jacobian = numpy.where(assembled[..., None, None], jacobian, numpy.nan)
        result = {name: numpy.broadcast_to(found[name], shape) for name in self.outputs}
        if "singular" in found:
            result["singular"] = numpy.broadcast_to(found["singular"], shape)
        result["assembled"] = assembled
        return result, jacobian

    def arrays(self, *arguments: float | numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray, numpy.ndarray]:
        """``(values, jacobian, assembled)`` for float arguments in calling order, unchecked: the hot-loop entry.

        Output-major, the layout one array is filled fastest in: ``values[i]`` is output i and
        ``jacobian[i, j]`` d(output i)/d(parameter j), each of the arguments' broadcast shape
        (the inputs' values last), NaN where ``assembled`` is False.  The arguments are
        :attr:`arguments` in order (branch signs as floats), NumPy arrays or floats that
        broadcast together; nothing checks them.  Closed forms only (``ValueError`` otherwise:
        the Newton module needs its guess, so call the object).

        >>> from symlink.mechanism.catalog import fourbar
        >>> jacobian = DesignJacobian(fourbar(), ["B_x"], ["a"])
        >>> jacobian.arguments
        ['theta', 'a', 'b', 'c', 'd', 'branch']
        >>> values, slopes, assembled = jacobian.arrays(numpy.array([0.0, 0.5]), 20.0, 66.0, 56.0, 80.0, 1.0)
        >>> slopes.shape, bool(abs(slopes[0, 0, 1] - numpy.cos(0.5)) < 1e-15)  # d(B_x)/da = cos(theta)
        ((1, 1, 2), True)
        """
        if self._kernel is None:
            raise ValueError(f"{self.name} has no closed form: call the DesignJacobian with keywords and "
                             "a guess instead of arrays()")
        results = self._kernel(*arguments)
        shape = (numpy.broadcast(*arguments).shape if len(arguments) <= 32  # numpy.broadcast takes at most 32
                 else numpy.broadcast_shapes(*(numpy.shape(argument) for argument in arguments)))
        numbers = results[:-2] if self._flagged else results[:-1]  # the flag is no derivative: left out here
        block = numpy.empty((len(numbers),) + shape)
        for index, result in enumerate(numbers):
            block[index] = result
        assembled = numpy.broadcast_to(results[-1], shape)
        if not assembled.all():
            block[:, ~assembled] = numpy.nan
        count = len(self.outputs)
        return block[:count], block[count:].reshape((count, len(self.parameters)) + shape), assembled

    def entry_text(self, **more: Any) -> str:
        """This Jacobian as the text of a disk-cache entry: its generated module and what a call needs, plain data
        (``more`` adds further facts, for the entry's user: :attr:`facts`).  Closed forms only (``ValueError``
        otherwise).  :meth:`from_entry` loads it back without the linkage, and without SymPy.

        >>> from symlink.mechanism.catalog import fourbar
        >>> text = DesignJacobian(fourbar(), ["B_x"], ["a"]).entry_text(note="seed 003")
        >>> again = DesignJacobian.from_entry(text)
        >>> values, slopes = again(theta=[0.5], a=20.0, b=66.0, c=56.0, d=80.0)
        >>> bool(abs(slopes[0, 0, 0] - numpy.cos(0.5)) < 1e-15), again.facts["note"]  # d(B_x)/da = cos(theta)
        (True, 'seed 003')
        """
        if self._source is None:
            raise ValueError(f"{self.name} has no closed form: its Jacobian is Newton's, kept with its linkage")
        described = {"name": self.name, "outputs": self.outputs, "parameters": self.parameters, "names": self.names,
                     "arguments": self.arguments, "flagged": self._flagged, "facts": more}
        return (f"{self._source.rstrip()}\n\n\n#: What a call needs, for DesignJacobian.from_entry (names).\n"
                f"{ENTRY_DESCRIPTION} = {described!r}\n")

    @classmethod
    def from_entry(cls, text: str, namespace: Mapping[str, Any] | None = None) -> DesignJacobian:
        """The Jacobian of an entry's text (:meth:`entry_text`: symlink's own, from a verified cache entry, never
        user text), loaded without its linkage: :attr:`linkage` is None, and :attr:`facts` holds what the entry
        added.  ``namespace``: the text already run (:func:`symlink.numeric.cache.cached_module`: from its cached
        bytecode), else it is run here."""
        if namespace is None:
            namespace = load_numpy_module(text)
        described = namespace[ENTRY_DESCRIPTION]
        jacobian = cls.__new__(cls)
        jacobian.linkage = None
        jacobian.name = described["name"]
        jacobian.outputs, jacobian.parameters = list(described["outputs"]), list(described["parameters"])
        jacobian.names, jacobian.arguments = list(described["names"]), list(described["arguments"])
        jacobian._flagged = bool(described["flagged"])
        jacobian._source = text
        jacobian._function = namespace[FUNCTION]
        jacobian._kernel = namespace[f"_{FUNCTION}_block"]
        jacobian.facts = dict(described["facts"])
        return jacobian

    def __repr__(self) -> str:
        return f"DesignJacobian({self.name!r}, {self.outputs}, {self.parameters})"


@lru_cache(maxsize=64)
def _shared(linkage: Linkage, outputs: tuple[str, ...], parameters: tuple[str, ...] | None) -> DesignJacobian:
    return DesignJacobian(linkage, outputs, parameters)


def design_jacobian(linkage: Linkage, outputs: Sequence[str], parameters: Sequence[str] | None = None,
                    **values: object) -> tuple[dict[str, numpy.ndarray], numpy.ndarray]:
    """One call of a :class:`DesignJacobian` of ``linkage`` (made once a process for each linkage and request).

    Parameters
    ----------
    linkage : Linkage
        The linkage.
    outputs : sequence of str
        The outputs to differentiate.
    parameters : sequence of str, optional
        The design parameters to differentiate by (default: all of them).
    **values
        The inputs, parameters and branch signs, as for a :class:`Solver` call.

    Returns
    -------
    values : dict of str to numpy.ndarray
        The outputs.
    jacobian : numpy.ndarray
        Their derivatives by the parameters: one row an output, one column a parameter (more axes for arrays).

    Examples
    --------
    >>> import symlink
    >>> values, slopes = symlink.design_jacobian(symlink.slider_crank(), ["slider"], ["a", "b"], theta=0.0,
    ...                                          a=1.0, b=3.0, offset=0.0)
    >>> [round(float(v), 12) for v in slopes[0]]  # s = a + b at theta = 0, offset 0
    [1.0, 1.0]
    """
    return _shared(linkage, tuple(outputs), None if parameters is None else tuple(parameters))(**values)
