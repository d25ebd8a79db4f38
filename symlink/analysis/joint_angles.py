"""Interior angles at the joints of many designs at once, from their solved coordinates: NumPy only, no SymPy.

A two-angle loop's transmission angle is the angle at its joint between the two unknown vectors that meet
there (:func:`symlink.analysis.transmission.transmission_joints`).  Each side's direction is a coordinate plus a
constant part (an offset, half a turn where it is walked backwards); :func:`joint_angle_arrays` takes the joints
with those parts already made into numbers or functions of the values
(:func:`symlink.analysis.transmission.joint_functions` generates them from a linkage; a sweep keeps them as plain
numbers in the disk cache), so that a warm process finds the angles of every design and sample without the linkage.

>>> joints = (("ABCD", False, ("phi", 0.0), ("beta", math.pi)),)  # the four-bar's joint at C
>>> solved = {"beta": numpy.array([0.0]), "phi": numpy.array([math.pi / 2])}
>>> round(math.degrees(float(joint_angle_arrays(joints, {}, solved)["ABCD"][0])), 9)
90.0
"""
from __future__ import annotations

import math
from typing import Any, Callable, Iterable, Mapping, Union

import numpy

__all__ = ["joint_angle_arrays", "joint_coordinates", "Joint"]

#: A joint: its loop, whether it is a guide (a slider's), and each side (into the joint, out of it) as the coordinate
#: it turns with (None: a fixed direction) and its constant part (a number, or a function of the values by name).
Joint = tuple[str, bool, tuple[Union[str, None], Union[float, Callable[[Mapping[str, Any]], Any]]],
              tuple[Union[str, None], Union[float, Callable[[Mapping[str, Any]], Any]]]]


def joint_angle_arrays(joints: Iterable[Joint], values: Mapping[str, Any], solved: Mapping[str, numpy.ndarray]
                       ) -> dict[str, numpy.ndarray]:
    """The interior angle (radians, in [0, pi]) at each joint, by loop name, from solved coordinates.

    ``values``: the parameters (and held inputs) by name, numbers or arrays that broadcast against the solved
    coordinates (one row a design, say), for constant parts that are functions of them; ``solved``: the
    coordinates by name (NaN where not assembled).  A guide's angle is the rod's to the guide's normal.
    """
    found = {}
    for loop, guide, (into_q, into_rest), (out_q, out_rest) in joints:
        # the constant parts first (a number or a value a design), then one pass over the solved arrays
        into_part = into_rest(values) if callable(into_rest) else into_rest
        out_part = out_rest(values) if callable(out_rest) else out_rest
        offset = numpy.asarray(out_part - into_part - (math.pi / 2 if guide else math.pi), dtype=float)
        if into_q is None:
            angle = offset + 0.0 if out_q is None else solved[out_q] + offset
        else:
            angle = (offset - solved[into_q] if out_q is None else (solved[out_q] - solved[into_q]) + offset)
        found[loop] = _folded(numpy.asarray(angle, dtype=float))
    return found


def joint_coordinates(joints: Iterable[Joint]) -> list[str]:
    """The coordinates :func:`joint_angle_arrays` needs solved, by name, in the joints' order.

    >>> joint_coordinates((("ABC", True, (None, 0.0), ("beta", 0.0)),))
    ['beta']
    """
    return list(dict.fromkeys(q for _, _, (into_q, _), (out_q, _) in joints for q in (into_q, out_q) if q is not None))


def _folded(angle: numpy.ndarray) -> numpy.ndarray:
    """``|wrap(angle)|`` in [0, pi], in place on ``angle`` (a fresh array): the angle less its nearest whole turns.

    Five passes, where :func:`~symlink.common.angles.wrap` takes a dozen (the sweeps' transmission angles of every
    design and sample); equal to it to rounding (a whole turn or two subtracted).

    >>> _folded(numpy.array([3 * math.pi / 2, -0.25, 7.0])).round(12).tolist() == [round(math.pi / 2, 12), 0.25,
    ...                                                                              round(7.0 - 2 * math.pi, 12)]
    True
    """
    turns = angle * (1 / (2 * math.pi))
    numpy.rint(turns, out=turns)
    turns *= 2 * math.pi
    angle -= turns
    return numpy.abs(angle, out=angle)
