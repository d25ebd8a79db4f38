"""Numeric solvers compiled from a linkage's outputs, with checked inputs.

A :class:`Solver` generates the NumPy code for the outputs it is asked for,
loads it, and calls it with validated values: lengths must be positive and
finite, branches +1 or -1.  Where the linkage cannot be assembled the result
says so in its ``assembled`` mask.

>>> from symlink.catalog import fourbar
>>> solver = Solver(fourbar(), ["rocker"])
>>> result = solver(theta=0.0, a=20, b=66, c=56, d=80, branch=1)
>>> round(float(numpy.degrees(result["rocker"])), 2)
110.74
"""
from __future__ import annotations

import math
from functools import cached_property, lru_cache
from typing import Callable, Sequence

import numpy

from .cache import generated_code
from .linkage import Linkage, Program, is_branch_name

__all__ = ["Solver", "shared_solver", "check_lengths", "crank_speeds"]


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
