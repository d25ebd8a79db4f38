"""Numeric solvers compiled from a linkage's outputs, with checked inputs.

A :class:`Solver` generates the NumPy code for the outputs it is asked for,
loads it, and calls it with validated values: lengths must be positive and
finite, branches +1 or -1.  Where the linkage cannot be assembled the result
says so in its ``assembled`` mask.  A :class:`NumericSolver` generates and
loads Newton's method on the closure instead, for linkages without a closed
form (and any other).

>>> from symlink.catalog import fourbar
>>> solver = Solver(fourbar(), ["rocker"])
>>> result = solver(theta=0.0, a=20, b=66, c=56, d=80, branch=1)
>>> round(float(numpy.degrees(result["rocker"])), 2)
110.74
"""
from __future__ import annotations

import math
from functools import cached_property, lru_cache
from typing import Callable, Mapping, Sequence

import numpy

from .cache import cache_key, cached_text, generated_code
from .codegen import newton
from .codegen.numpy import load_numpy_module
from .linkage import Linkage, Program, is_branch_name
from .vectors import acceleration, rate

__all__ = ["Solver", "NumericSolver", "shared_solver", "check_lengths", "crank_speeds"]


def check_lengths(**lengths: float) -> None:
    """``ValueError`` naming the first length that is not a positive finite number."""
    for name, value in lengths.items():
        values = numpy.asarray(value, dtype=float)
        if not numpy.all(numpy.isfinite(values)) or not numpy.all(values > 0):
            raise ValueError(f"{name} must be a positive finite length, got {value}")


class Solver:
    """A vectorised NumPy solver for some outputs of a linkage."""

    def __init__(self, linkage: Linkage, outputs: Sequence[str]) -> None:
        self.linkage = linkage
        self.outputs = list(outputs)
        code = generated_code(linkage, self.outputs)  # derived once, then from the scene cache
        self.source, self.function, self.arguments = code.source, code.function, code.arguments

    @property
    def branches(self) -> list[str]:
        """The names of the branch arguments (+1 or -1 each)."""
        return [name for name in self.arguments if is_branch_name(name)]

    @cached_property
    def program(self) -> Program:
        """The straight-line program behind the code (derived on first access only)."""
        return self.linkage.program(self.outputs)

    def __call__(self, **values) -> dict[str, numpy.ndarray]:
        unknown = set(values) - set(self.arguments)
        if unknown:
            raise ValueError(f"{self.linkage.name} takes {', '.join(self.arguments)}; not {', '.join(sorted(unknown))}")
        lengths = {s.name: values[s.name] for s in self.linkage.parameters
                   if s.is_positive and s.name in values}
        check_lengths(**lengths)
        for branch in self.branches:
            if branch in values and not numpy.all(numpy.isin(values[branch], (1, -1))):
                raise ValueError(f"{branch} must be +1 or -1, got {values[branch]}")
        for name, value in values.items():
            if not numpy.all(numpy.isfinite(numpy.asarray(value, dtype=float))):
                raise ValueError(f"{name} must be finite, got {value}")
        with numpy.errstate(invalid="ignore", divide="ignore"):
            return self.function(**values)


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

    def __call__(self, guess: Mapping[str, float] | Sequence[float], **values) -> dict[str, numpy.ndarray]:
        names = self.arguments
        unknown = set(values) - set(names)
        missing = [s.name for s in self.linkage.inputs + self.linkage.parameters if s.name not in values]
        if unknown or missing:
            raise ValueError(f"{self.linkage.name} takes {', '.join(names)}; "
                             + (f"not {', '.join(sorted(unknown))}" if unknown else f"missing {', '.join(missing)}"))
        check_lengths(**{s.name: values[s.name] for s in self.linkage.parameters if s.is_positive})
        return self.functions["accelerations"](guess=guess, **values)


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


def crank_speeds(angles: numpy.ndarray, speed: float, accel: float, first: float | None = None) -> numpy.ndarray:
    """Crank speed at each angle (radians) when it speeds up uniformly from ``first`` (default: the first angle).

    ``omega^2 = speed^2 + 2 accel (theta - theta_first)``, as the C program of
    the velocity and acceleration paper steps it.  ``ValueError`` where the
    crank would have stopped.

    >>> crank_speeds(numpy.array([0.0, 1.0]), 2.0, 1.5).tolist()  # sqrt(4 + 2 * 1.5 * 1) = sqrt(7)
    [2.0, 2.6457513110645907]
    """
    angles = numpy.asarray(angles, dtype=float)
    if angles.size == 0:
        return angles
    first = angles.flat[0] if first is None else first
    with numpy.errstate(over="ignore", invalid="ignore"):
        squared = numpy.square(numpy.float64(speed)) + 2 * numpy.float64(accel) * (angles - first)
    if not numpy.all(numpy.isfinite(squared)):
        raise ValueError(f"a crank speed of {speed:g} rad/s with an acceleration of {accel:g} rad/s^2 is too large: "
                         "its square overflows")
    if numpy.any(squared < 0):
        first = angles[squared < 0].flat[0]
        raise ValueError(f"the crank stops before reaching {math.degrees(first):.6g} deg "
                         f"(speed {speed} rad/s, acceleration {accel} rad/s^2)")
    return numpy.sign(speed if speed != 0 else accel) * numpy.sqrt(squared)
