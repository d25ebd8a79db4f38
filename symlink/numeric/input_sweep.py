"""The input values a table is evaluated at: an even sweep or a list, produced block by block.

A sweep of millions of crank angles is never held in memory whole: tables,
scene files and the command line evaluate and print it one block at a time,
so memory stays bounded however long the sweep is.

>>> sweep = InputSweep.from_range(start=0, stop=360, step=40)
>>> len(sweep), [block.tolist() for block in sweep.blocks(4)]
(9, [[0.0, 40.0, 80.0, 120.0], [160.0, 200.0, 240.0, 280.0], [320.0]])
>>> InputSweep.from_range(step=-1)
Traceback (most recent call last):
ValueError: step must be positive, got -1
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Iterator, Mapping, Sequence

import numpy

from ..common.angles import UNITS

__all__ = ["InputSweep", "MAX_VALUES", "MAX_ANGLE", "crank_speeds", "table_inputs"]

#: More input values than this in one sweep is a mistake, not a table.
MAX_VALUES = 10_000_000
#: Input angles (in either unit) beyond this size have lost their meaning: one ulp of 1e9 is 1e-7.
MAX_ANGLE = 1e9
#: Values evaluated at once by default: large enough for NumPy to run at full speed, small enough for the cache.
BLOCK = 16384


def _check_angle(value: float, what: str) -> float:
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{what} must be a finite number, got {value}")
    if abs(value) > MAX_ANGLE:
        raise ValueError(f"{what} must be at most {MAX_ANGLE:g} in size (larger angles have lost their "
                         f"precision), got {value:g}")
    return value


@dataclass(frozen=True)
class InputSweep:
    """``count`` input values: ``start + step * k`` (an even sweep), or the listed ``values``.

    Values are in the units the user gave them (the caller converts); the
    first value is where a uniformly accelerated input starts from.
    """

    start: float
    step: float
    count: int
    values: tuple[float, ...] | None = None

    @classmethod
    def from_range(cls, start: float | None = None, stop: float | None = None, step: float | None = None,
                   units: str = "deg", prefix: str = "") -> "InputSweep":
        """An even sweep; by default a full turn every 10 degrees from 0, in ``units`` ("deg" or "rad").

        ``prefix`` goes before the names in messages (``--`` on the command line).
        """
        if units not in UNITS:
            raise ValueError(f"units must be 'deg' or 'rad', got {units!r}")
        full = 360.0 if units == "deg" else 2 * math.pi
        start = 0.0 if start is None else _check_angle(start, prefix + "start")
        stop = full if stop is None else _check_angle(stop, prefix + "stop")
        step = (10.0 if units == "deg" else math.radians(10.0)) if step is None else float(step)
        if not math.isfinite(step) or step <= 0:
            raise ValueError(f"{prefix}step must be positive, got {step:g}")
        if stop <= start:
            raise ValueError(f"{prefix}stop ({stop:g}) must be greater than {prefix}start ({start:g})")
        count = (stop - start) / step
        if count > MAX_VALUES:
            least = (stop - start) / MAX_VALUES
            scale = 10.0 ** (math.floor(math.log10(least)) - 2)
            raise ValueError(f"about {count:.4g} input values is too many (at most {MAX_VALUES:,} a sweep); use "
                             f"{prefix}step {math.ceil(least / scale) * scale:.3g} or larger")
        count = math.ceil(count - 1e-9)
        if count > 1 and start + step * (count - 1) == start + step * (count - 2):
            raise ValueError(f"{prefix}step {step:g} is too small to change an angle of {start:g}")
        return cls(start, step, count)

    @classmethod
    def from_options(cls, start: float | None = None, stop: float | None = None, step: float | None = None,
                     angles: Sequence[float] | None = None, units: str = "deg", prefix: str = "") -> "InputSweep":
        """The sweep a table asks for: ``angles``, or else ``start``/``stop``/``step`` (not both)."""
        if angles is not None:
            if any(v is not None for v in (start, stop, step)):
                raise ValueError(f"give either {prefix}angles or {prefix}start/{prefix}stop/{prefix}step, not both")
            return cls.from_values(angles, prefix)
        return cls.from_range(start, stop, step, units, prefix)

    @classmethod
    def from_values(cls, values: Sequence[float], prefix: str = "") -> "InputSweep":
        """The listed values, in order, each once: a list that repeats a value asks for the same row twice (a full
        turn's 0 and 360 are two values, as ``start``/``stop`` may give them)."""
        values = tuple(_check_angle(v, f"every one of {prefix}angles") for v in values)
        if not values:
            raise ValueError(f"{prefix}angles needs at least one angle")
        seen: set[float] = set()
        for value in values:
            if value in seen:
                raise ValueError(f"{prefix}angles lists {value:g} more than once; list each value once")
            seen.add(value)
        if len(values) > MAX_VALUES:
            raise ValueError(f"{len(values):,} input values is too many (at most {MAX_VALUES:,} a sweep)")
        return cls(values[0], 0.0, len(values), values)

    def __len__(self) -> int:
        return self.count

    @property
    def first(self) -> float:
        """The first value: where a uniformly accelerated input starts from."""
        return self.start

    def block(self, begin: int, end: int) -> numpy.ndarray:
        """Values ``begin`` to ``end`` (exclusive)."""
        if self.values is not None:
            return numpy.array(self.values[begin:end], dtype=float)
        return self.start + self.step * numpy.arange(begin, min(end, self.count), dtype=float)

    def blocks(self, size: int = BLOCK) -> Iterator[numpy.ndarray]:
        """The values, ``size`` at a time."""
        for begin in range(0, self.count, size):
            yield self.block(begin, begin + size)

    def array(self) -> numpy.ndarray:
        """All values at once (for sweeps known to be small)."""
        return self.block(0, self.count)


def crank_speeds(angles: numpy.ndarray, speed: float, accel: float, first: float | None = None) -> numpy.ndarray:
    """Crank speed at each angle (radians) when it speeds up uniformly from ``first`` (default: the first angle).

    ``omega^2 = speed^2 + 2 accel turned``, as the C program of the velocity
    and acceleration paper steps it, where ``turned`` is the angle the crank
    has turned from ``first`` to reach the angle, in the direction it turns
    (the sign of ``speed``, or of ``accel`` from rest): ``theta - first`` for
    an angle ahead of ``first``; an angle behind it is reached after the
    whole turns that bring it ahead.  So a clockwise crank (negative speed)
    speeding up (negative acceleration) over a table of increasing angles
    reaches 350 deg from 0 after turning -10 deg.  ``ValueError`` where the
    crank would have stopped.

    >>> crank_speeds(numpy.array([0.0, 1.0]), 2.0, 1.5).tolist()  # sqrt(4 + 2 * 1.5 * 1) = sqrt(7)
    [2.0, 2.6457513110645907]
    >>> crank_speeds(numpy.array([0.0, 2 * math.pi - 1.0]), -2.0, -1.5).tolist()  # -1 rad turned: -sqrt(7)
    [-2.0, -2.6457513110645907]
    """
    angles = numpy.asarray(angles, dtype=float)
    if angles.size == 0:
        return angles
    first = angles.flat[0] if first is None else first
    direction = numpy.sign(speed if speed != 0 else accel) or 1.0
    with numpy.errstate(over="ignore", invalid="ignore"):
        ahead = direction * (angles - first)
        turned = direction * numpy.where(ahead >= 0, ahead, numpy.mod(ahead, 2 * math.pi))
        squared = numpy.square(numpy.float64(speed)) + 2 * numpy.float64(accel) * turned
    if not numpy.all(numpy.isfinite(squared)):
        raise ValueError(f"a crank speed of {speed:g} rad/s with an acceleration of {accel:g} rad/s^2 is too large: "
                         "its square overflows")
    if numpy.any(squared < 0):
        first = angles[squared < 0].flat[0]
        raise ValueError(f"the crank stops before reaching {math.degrees(first):.6g} deg "
                         f"(speed {speed} rad/s, acceleration {accel} rad/s^2)")
    return direction * numpy.sqrt(squared)


def table_inputs(facts: Mapping[str, Any], values: Mapping[str, float], theta: Any, speeds: Any,
                 accel: float) -> dict[str, Any]:
    """A table's inputs, their rates and accelerations by name, along the sweep: the first input at ``theta``
    (radians) turning at ``speeds`` with the uniform acceleration ``accel``, each further input geared to it,
    ``values[name] + values[name + "_ratio"] * theta``.  ``facts``: the table's names (``inputs``, ``rates``,
    ``accelerations``: :func:`symlink.io.table_source.table_facts`).

    >>> facts = {"inputs": ["theta", "psi"], "rates": ["thetadot", "psidot"], "accelerations": ["thetaddot", "psiddot"]}
    >>> inputs = table_inputs(facts, {"psi": 1.0, "psi_ratio": -2.0}, numpy.array([0.0, 0.5]), 3.0, 0.0)
    >>> inputs["psi"].tolist(), inputs["psidot"]
    ([1.0, 0.0], -6.0)
    """
    names, rates, accelerations = facts["inputs"], facts["rates"], facts["accelerations"]
    inputs = {names[0]: theta, rates[0]: speeds, accelerations[0]: accel}
    for name, speed, acceleration in zip(names[1:], rates[1:], accelerations[1:]):
        ratio = values[f"{name}_ratio"]
        inputs.update({name: values[name] + ratio * numpy.asarray(theta), speed: ratio * speeds,
                       acceleration: ratio * accel})
    return inputs
