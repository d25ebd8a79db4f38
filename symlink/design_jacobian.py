"""The Jacobian of some outputs by some design parameters, evaluated through generated code: what synthesis calls.

A least-squares synthesis moves a linkage's parameters (lengths, fixed
angles, coupler-point offsets, pivot coordinates) until some position outputs
hit targets; it needs the outputs and their exact derivatives by those
parameters at many input values, thousands of times.  :class:`DesignJacobian`
asks the linkage for the outputs and their sensitivities
(:mod:`symlink.sensitivity`, named ``<output>__d_<parameter>``), generates
and loads the NumPy code once (cached like every solver), and then each call
is one call of that code, returning the outputs and the Jacobian as one array
of shape ``input shape + (outputs, parameters)``.  Linkages without a closed
form go through the generated Newton module, whose sensitivities come from
the converged closure Jacobian; they need an initial ``guess``.

Where the linkage cannot be assembled ``assembled`` is False and the
Jacobian's entries there are NaN, never a number.

>>> from symlink.catalog import fourbar
>>> jacobian = DesignJacobian(fourbar(), ["B_x", "C_y"], ["a", "b"])
>>> values, slopes = jacobian(theta=[0.0, 0.5], a=20.0, b=66.0, c=56.0, d=80.0)
>>> slopes.shape
(2, 2, 2)
>>> round(float(slopes[1, 0, 0]), 12) == round(float(numpy.cos(0.5)), 12)  # d(B_x)/da = cos(theta)
True
"""
from __future__ import annotations

from functools import lru_cache
from typing import Callable, Mapping, Sequence

import numpy

from .cache import generated_code
from .linkage import Linkage
from .sensitivity import sensitivity_name
from .solver import NumericSolver

__all__ = ["DesignJacobian", "design_jacobian", "sensitivity_outputs"]


def sensitivity_outputs(linkage: Linkage, outputs: Sequence[str], parameters: Sequence[str] | None = None) -> list[str]:
    """The names of each output's derivative by each parameter (all parameters by default), output by output.

    ``ValueError`` for an output that is not a position of ``linkage`` (a rate, ``singular``) or a name that
    is not one of its parameters.

    >>> from symlink.catalog import fourbar
    >>> sensitivity_outputs(fourbar(), ["rocker"], ["a", "d"])
    ['rocker__d_a', 'rocker__d_d']
    """
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


class DesignJacobian:
    """Outputs of a linkage and their derivatives by chosen parameters, from generated code loaded once.

    Call it with the generated function's arguments (inputs, every parameter,
    branch signs; for a linkage without a closed form also ``guess``, the
    unknowns near the wanted assembly at the first input value, over a
    one-dimensional sweep).  It returns ``(values, jacobian)``: ``values``
    maps each output (and ``assembled``) to its array; ``jacobian[..., i, j]``
    is d(outputs[i])/d(parameters[j]).  The generated code checks its arguments; in a hot loop whose
    arguments are known good, ``check=False`` skips that.
    """

    def __init__(self, linkage: Linkage, outputs: Sequence[str], parameters: Sequence[str] | None = None) -> None:
        self.linkage = linkage
        self.outputs = list(outputs)
        if not self.outputs:
            raise ValueError(f"ask {linkage.name} for at least one output")
        self.parameters = [p.name for p in linkage.parameters] if parameters is None else list(parameters)
        self.names = sensitivity_outputs(linkage, self.outputs, self.parameters)
        self._function: Callable[..., Mapping[str, numpy.ndarray]]
        if linkage.has_closed_form:
            self._function = generated_code(linkage, self.outputs + self.names).function
        else:
            self._function = NumericSolver(linkage).functions["sensitivities"]

    def __call__(self, **values: object) -> tuple[dict[str, numpy.ndarray], numpy.ndarray]:
        found = self._function(**values)
        shape = numpy.shape(found["assembled"])
        columns = [numpy.broadcast_to(found[name], shape) for name in self.names]
        jacobian = numpy.stack(columns, axis=-1).reshape(shape + (len(self.outputs), len(self.parameters)))
        result = {name: numpy.broadcast_to(found[name], shape) for name in self.outputs}
        result["assembled"] = numpy.asarray(found["assembled"])
        return result, jacobian

    def __repr__(self) -> str:
        return f"DesignJacobian({self.linkage.name!r}, {self.outputs}, {self.parameters})"


@lru_cache(maxsize=64)
def _shared(linkage: Linkage, outputs: tuple[str, ...], parameters: tuple[str, ...] | None) -> DesignJacobian:
    return DesignJacobian(linkage, outputs, parameters)


def design_jacobian(linkage: Linkage, outputs: Sequence[str], parameters: Sequence[str] | None = None,
                    **values: object) -> tuple[dict[str, numpy.ndarray], numpy.ndarray]:
    """One call of a :class:`DesignJacobian` of ``linkage`` (made once a process for each linkage and request).

    >>> from symlink.catalog import slider_crank
    >>> values, slopes = design_jacobian(slider_crank(), ["slider"], ["a", "b"], theta=0.0, a=1.0, b=3.0,
    ...                                  offset=0.0)
    >>> [round(float(v), 12) for v in slopes[0]]  # s = a + b at theta = 0, offset 0
    [1.0, 1.0]
    """
    return _shared(linkage, tuple(outputs), None if parameters is None else tuple(parameters))(**values)
