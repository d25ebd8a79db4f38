"""Analysis of a four-bar's mobility: where its crank can go.

>>> [tuple(round(math.degrees(x), 4) for x in span) for span in crank_range(20, 66, 56, 80)]
[(-180.0, 180.0)]
"""
from __future__ import annotations

import math

__all__ = ["crank_range"]


def crank_range(a: float, b: float, c: float, d: float) -> list[tuple[float, float]]:
    """The crank angles (radians) at which a four-bar can be assembled, as closed intervals.

    The coupler and rocker close a triangle over the diagonal BD when
    ``|b - c| <= |BD| <= b + c``, with ``|BD|^2 = a^2 + d^2 - 2 a d cos(theta)``;
    that bounds ``cos(theta)``.  A full turn is ``[(-pi, pi)]``; an empty list
    means the linkage cannot be assembled at all.
    """
    lowest = (a * a + d * d - (b + c) ** 2) / (2 * a * d)   # cos(theta) at the extended toggle
    highest = (a * a + d * d - (b - c) ** 2) / (2 * a * d)  # cos(theta) at the folded toggle
    if lowest > 1 or highest < -1 or lowest > highest:
        return []
    if lowest <= -1 and highest >= 1:
        return [(-math.pi, math.pi)]
    far = math.acos(max(lowest, -1.0))
    near = math.acos(min(highest, 1.0))
    if highest >= 1:
        return [(-far, far)]
    if lowest <= -1:
        return [(near, 2 * math.pi - near)]
    return [(-far, -near), (near, far)]

