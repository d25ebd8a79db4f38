"""``symlink slider-crank``: the slider-crank with offset as a table, in the shape of ``symlink fourbar``.

::

    symlink slider-crank --crank A --conrod B [--offset E] [--crank-speed W] [--crank-accel AL]
                         [--start DEG --stop DEG --step DEG | --angles LIST] [--branch +1|-1|both]
                         [--units deg|rad] [--format table|csv|json]

Angles (crank, conrod) in degrees or radians, wrapped; the slider position in
the length unit, its speed and acceleration per second and per second squared.
Branch +1 is the assembly with the larger slider position.  The command is
built by :mod:`symlink.cli_tables` from the catalog entry and :data:`SLIDER_TABLE`.
"""
from __future__ import annotations

import argparse
import math

from .cli_tables import NUMBER, Option, Table, add_table_command

__all__ = ["SLIDER_TABLE", "slider_crank_range", "add_command"]


def slider_crank_range(a: float, b: float, offset: float) -> list[tuple[float, float]]:
    """The crank angles (radians) at which the slider-crank can be assembled, as closed intervals.

    The rod reaches the guide while ``|offset - a sin(theta)| <= b``, which
    bounds ``sin(theta)``.  A full turn is ``[(-pi, pi)]``; an empty list means
    it cannot be assembled at all.

    >>> [tuple(round(math.degrees(x), 6) for x in span) for span in slider_crank_range(2, 1, 0)]
    [(-30.0, 30.0), (150.0, 210.0)]
    """
    low, high = (offset - b) / a, (offset + b) / a  # the bounds of sin(theta)
    if low > 1 or high < -1:
        return []
    if low <= -1 and high >= 1:
        return [(-math.pi, math.pi)]
    if high >= 1:
        return [(math.asin(low), math.pi - math.asin(low))]
    if low <= -1:
        return [(math.pi - math.asin(high), 2 * math.pi + math.asin(high))]
    return [(math.asin(low), math.asin(high)), (math.pi - math.asin(high), math.pi - math.asin(low))]


SLIDER_TABLE = Table(
    "slider-crank", "positions, speeds and accelerations of a slider-crank",
    (Option("crank", "a", "A", "crank length AB"),
     Option("conrod", "b", "B", "connecting rod length BC"),
     Option("offset", "offset", "E", "the slider's line is y = offset (any sign)", kind=NUMBER, default=0.0)),
    notes="Branch +1 is the assembly with the larger slider position.\nThe slider column is its x on the "
          "line y = offset, in the length unit; its speed and acceleration per second and per second squared.",
    reachable=lambda values: slider_crank_range(values["a"], values["b"], values["offset"]))


def add_command(commands: argparse._SubParsersAction) -> None:
    """Register ``symlink slider-crank``."""
    add_table_command(commands, SLIDER_TABLE)
