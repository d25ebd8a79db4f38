"""Interior angles at the joints of many designs at once, from their solved coordinates: NumPy only, no SymPy.

A two-angle loop's transmission angle is the angle at its joint between the two unknown vectors that meet
there (:func:`symlink.analysis.transmission.transmission_joints`).  Each side's direction is a coordinate plus a
constant part (an offset that is a sum of multiples of named values, half a turn where it is walked backwards or
its length is negative).  A joint is plain data (JSON), its recipe
(:func:`symlink.analysis.transmission.joint_recipe` makes it of a linkage): ``loop``, ``name``, ``guide`` (a
slider's) and, for the vector ``into`` the joint and the one ``out`` of it, ``sign`` (walked forwards +1 or
back -1), ``coordinate`` (the one it turns with; None: a fixed direction), ``offset`` and ``length`` (where the
values fix it; else None), each as ``[[coefficient, name or None], ...]``.  The analysis keeps its linkage's
recipes in the disk cache and a sweep in its facts, so that a warm process finds the angles of every design and
sample without the linkage; :func:`joint_angle_arrays` evaluates them, :func:`direction_parts` is each side's
constant part.

>>> side = lambda sign, coordinate: {"sign": sign, "coordinate": coordinate, "offset": [[0.0, None]], "length": None}
>>> joints = ({"loop": "ABCD", "guide": False, "into": side(1, "phi"), "out": side(-1, "beta")},)  # the four-bar's C
>>> solved = {"beta": numpy.array([0.0]), "phi": numpy.array([math.pi / 2])}
>>> round(math.degrees(float(joint_angle_arrays(joints, {}, solved)["ABCD"][0])), 9)
90.0
"""
from __future__ import annotations

import math
from typing import Any, Iterable, Mapping, Sequence

import numpy

__all__ = ["joint_angle_arrays", "joint_coordinates", "direction_parts", "sum_of_terms"]


def sum_of_terms(terms: Sequence[Sequence[Any]], values: Mapping[str, Any]) -> Any:
    """``sum(coefficient * values[name])`` over ``[[coefficient, name or None], ...]`` (None: the coefficient
    itself), added in the terms' order (a recipe's: the constant first, then by name), so that every process adds
    them alike; values may be numbers or arrays.

    >>> sum_of_terms([[0.5, None], [2.0, "alpha"]], {"alpha": 0.25})
    1.0
    """
    total = 0.0
    for coefficient, name in terms:
        total += coefficient if name is None else coefficient * values[name]
    return total


def direction_parts(side: Mapping[str, Any], values: Mapping[str, Any]) -> tuple[Any, Any]:
    """The constant parts of a walked vector's direction (a side of a joint's recipe), radians: its ``offset``
    from the coordinate it turns with, and its flip (half a turn walked backwards, and half a turn more where its
    length, fixed by the values, is negative; an array where those values are arrays).

    >>> direction_parts({"sign": -1, "coordinate": "beta", "offset": [[1.0, "gamma"]], "length": [[1.0, "e"]]},
    ...                 {"gamma": 0.5, "e": -2.0})
    (0.5, 6.283185307179586)
    """
    flip: Any = 0.0 if side["sign"] > 0 else math.pi
    if side["length"] is not None:
        negative = sum_of_terms(side["length"], values) < 0
        if numpy.ndim(negative):  # a length a design: a flip a design
            flip = flip + numpy.where(negative, math.pi, 0.0)
        else:
            flip += math.pi if negative else 0.0
    return sum_of_terms(side["offset"], values), flip


def joint_angle_arrays(joints: Iterable[Mapping[str, Any]], values: Mapping[str, Any],
                       solved: Mapping[str, numpy.ndarray]) -> dict[str, numpy.ndarray]:
    """The interior angle (radians, in [0, pi]) at each joint (a recipe), by loop name, from solved coordinates.

    ``values``: the named values of the recipes' offsets and lengths (parameters, held inputs, the moving input
    where a side turns with it and it is not solved), numbers or arrays that broadcast against the solved
    coordinates (one row a design, say); ``solved``: the coordinates by name (NaN where not assembled).  A guide's
    angle is the rod's to the guide's normal.
    """
    found = {}
    for joint in joints:
        into, out = joint["into"], joint["out"]
        # the constant parts first (a number or a value a design), then one pass over the solved arrays
        into_offset, into_flip = direction_parts(into, values)
        out_offset, out_flip = direction_parts(out, values)
        into_part, out_part = into_offset + into_flip, out_offset + out_flip
        offset = numpy.asarray(out_part - into_part - (math.pi / 2 if joint["guide"] else math.pi), dtype=float)
        into_q, out_q = into["coordinate"], out["coordinate"]
        if into_q is None:
            angle = offset + 0.0 if out_q is None else solved[out_q] + offset
        else:
            angle = (offset - solved[into_q] if out_q is None else (solved[out_q] - solved[into_q]) + offset)
        found[joint["loop"]] = _folded(numpy.asarray(angle, dtype=float))
    return found


def joint_coordinates(joints: Iterable[Mapping[str, Any]]) -> list[str]:
    """The coordinates :func:`joint_angle_arrays` needs solved, by name, in the joints' order.

    >>> guide = {"sign": 1, "coordinate": None, "offset": [[0.0, None]], "length": None}
    >>> rod = {"sign": 1, "coordinate": "beta", "offset": [[0.0, None]], "length": None}
    >>> joint_coordinates([{"loop": "ABC", "guide": True, "into": guide, "out": rod}])
    ['beta']
    """
    return list(dict.fromkeys(side["coordinate"] for joint in joints for side in (joint["into"], joint["out"])
                              if side["coordinate"] is not None))


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
