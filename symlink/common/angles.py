"""Angle conventions: wrapping to (-180, 180] (or (-pi, pi]) and unit conversion.

>>> wrap([-180.0, 200.0, -0.001], 180.0).tolist()
[180.0, -160.0, -0.001]
>>> wrap_angle(3 * math.pi / 2)
-1.5707963267948966
"""
from __future__ import annotations

import math

import numpy

__all__ = ["UNITS", "wrap", "wrap_angle", "to_radians", "from_radians", "half_turn"]


def wrap(angle, half_turn: float = math.pi):
    """Angles wrapped to (-half_turn, half_turn]: (-pi, pi] or (-180, 180].

    Angles already in range come back unchanged, to the last bit.
    """
    angle = numpy.asarray(angle, dtype=float)
    wrapped = half_turn - numpy.mod(half_turn - angle, 2 * half_turn)
    inside = (angle > -half_turn) & (angle <= half_turn)
    return numpy.where(inside, angle, wrapped)[()]


def wrap_angle(angle: float) -> float:
    """One angle (radians) wrapped to (-pi, pi], as a float."""
    return float(wrap(angle))


UNITS = ("deg", "rad")


def _in_degrees(units: str) -> bool:
    if units not in UNITS:
        raise ValueError(f"units must be 'deg' or 'rad', got {units!r}")
    return units == "deg"


def to_radians(values, units: str):
    """Values in ``units`` ("deg" or "rad") as radians."""
    return numpy.radians(values) if _in_degrees(units) else numpy.asarray(values, dtype=float)


def from_radians(values, units: str):
    """Radians as values in ``units`` ("deg" or "rad")."""
    return numpy.degrees(values) if _in_degrees(units) else numpy.asarray(values, dtype=float)


def half_turn(units: str) -> float:
    """Half a turn in ``units``: 180 or pi."""
    return 180.0 if _in_degrees(units) else math.pi
