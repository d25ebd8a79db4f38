"""A four-bar's analysis by its lengths in closed form: triangle geometry, no derivation, no SymPy.

Everything :func:`fourbar_report` says of the four-bar with crank a, coupler
b, rocker c and ground d follows from two triangles:

* over the diagonal BD, whose length squared is ``a^2 + d^2 - 2 a d cos(theta)``,
  the coupler and the rocker close a triangle: its angle at C is the
  transmission angle, and where it flattens the crank toggles (:func:`crank_spans`);
* over AC, which is ``a + b`` with crank and coupler extended and ``|b - a|``
  folded, the rocker and the ground close a triangle at the rocker's two
  limit positions (:func:`limit_positions`).

Each angle is :func:`~symlink.numeric.fourbar_transmission.triangle_angle`'s atan2 of Heron's
product and the law of cosines, so that it keeps its digits where the triangle is flat (the
transmission angle's extremes, :func:`~symlink.numeric.fourbar_transmission.transmission_range`,
are at home beside its curve).  A process
that only analyses four-bars by their lengths (``symlink analyze --crank ...``)
imports this module and NumPy, not the symbolic layer: cold or warm, it starts
as fast as NumPy does.

>>> report = fourbar_report(20, 66, 56, 80)  # seed 003
>>> report["grashof"], round(math.degrees(report["transmission_min"]), 2), round(math.degrees(report["stroke"]), 4)
('crank-rocker', 58.23, 42.0886)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..common.angles import wrap_angle
from ..codegen.arguments import check_lengths
from ..common.display import record_html
from ..common.rounding import TOLERANCE
from ..numeric.crank_ranges import closing_crank_range
from ..numeric.fourbar_transmission import transmission_range, triangle_angle
from .grashof import grashof

__all__ = ["LimitPositions", "limit_positions", "crank_spans", "fourbar_report", "FOURBAR_DOF"]

#: The four-bar's mobility by Gruebler: 3 (links - 1) - 2 (pin joints), four links and four pins.
FOURBAR_DOF = 3 * (4 - 1) - 2 * 4


# --- where the crank reaches ------------------------------------------------------------

def _closes_at(a: float, b: float, c: float, d: float, theta: float) -> bool:
    """Whether coupler and rocker close their triangle over BD at crank angle ``theta``, as the solver decides.

    The generated solver's test of its clamped root (:mod:`symlink.symbolic.position`), in the loop's unit (a
    power of two near the mean length): Heron's product of the triangle over BD may round below zero by
    ``TOLERANCE`` times its scale, which makes a change point (a toggle the linkage passes) part of the range;
    with B on D the coupler's direction is undefined, and the linkage is not assembled there.
    """
    size = math.ldexp(0.5, math.frexp(a / 4 + b / 4 + c / 4 + d / 4)[1])
    ground, crank, coupler, rocker = d / size, a / size, b / size, c / size
    across_x, across_y = crank * math.cos(theta) - ground, crank * math.sin(theta)
    diagonal_squared = across_x * across_x + across_y * across_y
    if not diagonal_squared >= 2.2250738585072e-308:  # B on D
        return False
    product = ((coupler + rocker) ** 2 - diagonal_squared) * (diagonal_squared - (coupler - rocker) ** 2)
    spread = abs(across_x) + abs(across_y)
    scale = 8 * coupler * rocker * spread * (ground + crank + coupler + rocker + spread)
    return product >= -TOLERANCE * scale


def crank_spans(a: float, b: float, c: float, d: float) -> list[tuple[float, float]]:
    """The crank angles (radians) where the four-bar can be assembled, as :func:`~symlink.analysis.analyze_linkage`
    finds them: closed intervals, ``[(-pi, pi)]`` for a full turn.

    The triangle over BD closes while ``|b - c| <= BD <= b + c``, which bounds
    ``cos(theta)`` (:func:`~symlink.numeric.crank_ranges.crank_range`); whether
    the crank gets to 0 and to pi, where a change point puts a double root, is
    decided within rounding as the generated solver decides it.  A crank that
    passes B over D (a equal to d) is cut there: its two sides are separate spans.
    ``ValueError`` for bad lengths and where the four-bar closes nowhere.

    >>> [tuple(round(math.degrees(x), 4) for x in span) for span in crank_spans(60, 30, 50, 40)]  # acos(-1/4)
    [(-104.4775, 104.4775)]
    >>> [tuple(round(math.degrees(x), 4) + 0.0 for x in span) for span in crank_spans(2, 1, 1, 2)]  # B on D at 0
    [(-60.0, 0.0), (0.0, 60.0)]
    """
    return _spans_and_toggles(a, b, c, d)[0]


def _spans_and_toggles(a: float, b: float, c: float, d: float) -> tuple[list[tuple[float, float]], list[float]]:
    """:func:`crank_spans`, and the toggles at their ends in (-pi, pi] ascending (none for a full turn); the end
    of a span past pi is named a turn earlier, as the general analysis names it (from -pi, the scan's start)."""
    check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    closing_crank_range(a, b, c, d)  # ValueError where it closes at no crank angle
    lowest = (a * a + d * d - (b + c) ** 2) / (2 * a * d)   # cos(theta) at the extended toggle
    highest = (a * a + d * d - (b - c) ** 2) / (2 * a * d)  # cos(theta) at the folded toggle
    far, near = math.acos(min(max(lowest, -1.0), 1.0)), math.acos(min(max(highest, -1.0), 1.0))
    at_zero, at_half_turn = _closes_at(a, b, c, d, 0.0), _closes_at(a, b, c, d, -math.pi)
    if at_zero and at_half_turn:
        return [(-math.pi, math.pi)], []
    if at_zero:
        return [(-far, far)], [-far, far]
    if at_half_turn:
        return [(near, 2 * math.pi - near)], [-near, near]
    return [(-far, -near), (near, far)], [-far, -near, near, far]


# --- limit positions ----------------------------------------------------------------------

@dataclass(frozen=True)
class LimitPositions:
    """The rocker's extreme positions, where crank and coupler are in line (radians).

    ``extended``: the crank points along the coupler (AC is ``a + b`` long); ``folded``: the
    crank points back along it.  Angles of crank and rocker in each, on ``branch``.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    branch: int
    extended_crank: float
    extended_rocker: float
    folded_crank: float
    folded_rocker: float

    @property
    def stroke(self) -> float:
        """The rocker's swing between its extremes."""
        return abs(wrap_angle(self.folded_rocker - self.extended_rocker))

    @property
    def crank_turns(self) -> tuple[float, float]:
        """Crank rotation (counter-clockwise) from extended to folded, and back to extended."""
        forward = (self.folded_crank - self.extended_crank) % (2 * math.pi)
        return forward, 2 * math.pi - forward

    @property
    def time_ratio(self) -> float:
        """Slow stroke over quick stroke at constant crank speed (1 or more)."""
        forward, back = self.crank_turns
        return max(forward, back) / min(forward, back)


def limit_positions(a: float, b: float, c: float, d: float, branch: int = 1) -> LimitPositions:
    """The limit positions of a four-bar on ``branch``, with its stroke and time ratio.

    Crank and coupler are in line when AC is ``a + b`` long (extended) or ``|b - a|``
    (folded); the triangle A, D, C then gives the angle of C about A in closed form (on
    branch +1, C lies above the ground line), hence the crank angle, and C itself gives
    the rocker angle, ``atan2`` of C about D.  ``ValueError`` if either limit position
    cannot be assembled (the rocker of such a linkage stops at toggles instead: see
    :func:`crank_spans`).

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths.
    branch : int, optional
        The assembly, +1 (default) or -1.

    Returns
    -------
    LimitPositions
        The crank and rocker angles (radians) with crank and coupler extended and folded.

    Raises
    ------
    ValueError
        If either limit position cannot be assembled.

    Examples
    --------
    >>> import math, symlink
    >>> found = symlink.limit_positions(20, 66, 56, 80)  # AC is 86 and 46 long in the triangle A, D, C
    >>> [round(math.degrees(x), 2) for x in (found.extended_crank, found.extended_rocker, found.folded_rocker)]
    [39.22, 103.82, 145.91]
    """
    check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    if branch not in (1, -1):
        raise ValueError(f"branch must be +1 or -1, got {branch}")
    if a == b:
        raise ValueError("crank and coupler are equally long: the folded limit puts C on A")
    crank, rocker = [], []
    for reach, folded in ((a + b, False), (abs(b - a), True)):
        angle = float(triangle_angle(c, reach, d))  # at A, between A->D and A->C
        if math.isnan(angle):
            kind = "folded" if folded else "extended"
            raise ValueError(f"the {kind} limit position (|AC| = {reach:g}) cannot be assembled with "
                             f"rocker {c:g} and ground {d:g}")
        # C above the ground line is branch +1, except when folded with a > b, where C is on the crank.
        toward_c = (-branch if folded and a > b else branch) * angle
        crank.append(wrap_angle(toward_c + (math.pi if folded and b > a else 0.0)))
        rocker.append(math.atan2(reach * math.sin(toward_c), reach * math.cos(toward_c) - d))
    return LimitPositions(branch, crank[0], rocker[0], crank[1], rocker[1])


# --- the report -----------------------------------------------------------------------------

def fourbar_report(a: float, b: float, c: float, d: float, branch: int = 1) -> dict:
    """Everything :mod:`symlink.analysis` says of one four-bar, as a flat record (radians).

    ``limit_positions``, ``stroke`` and ``time_ratio`` are None unless the linkage is a
    crank-rocker (otherwise the output does not swing between two limits as the crank
    turns); ``toggles`` are the ends of the crank's range (empty for a full turn).  The
    same record as :func:`~symlink.analysis.analyze_linkage` of the catalog's four-bar
    finds by its scan, here in closed form.

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths.
    branch : int, optional
        The assembly, +1 (default) or -1.

    Returns
    -------
    dict
        A flat record: ``grashof``, ``dof``, the crank's range and toggles, the transmission extremes,
        and for a crank-rocker ``limit_positions``, ``stroke`` and ``time_ratio`` (radians).

    Examples
    --------
    >>> import math, symlink
    >>> report = symlink.fourbar_report(20, 66, 56, 80)  # seed 003
    >>> report["grashof"], report["dof"], round(math.degrees(report["transmission_min"]), 2)
    ('crank-rocker', 1, 58.23)
    """
    spans, toggles = _spans_and_toggles(a, b, c, d)  # ValueError for bad lengths or a four-bar that closes nowhere
    if branch not in (1, -1):
        raise ValueError(f"branch must be +1 or -1, got {branch}")
    kind = grashof(a, b, c, d)
    transmission = transmission_range(a, b, c, d)
    swing = limit_positions(a, b, c, d, branch) if kind.name == "crank-rocker" else None
    return {
        "crank": a, "coupler": b, "rocker": c, "ground": d, "branch": branch,
        "dof": FOURBAR_DOF,
        "grashof": kind.name, "shortest": kind.shortest, "longest": kind.longest,
        "shortest_plus_longest": kind.shortest_plus_longest, "other_two": kind.other_two,
        "crank_range": spans,
        "toggles": toggles,
        "limit_positions": None if swing is None else {
            "extended_crank": swing.extended_crank, "extended_rocker": swing.extended_rocker,
            "folded_crank": swing.folded_crank, "folded_rocker": swing.folded_rocker},
        "stroke": None if swing is None else swing.stroke,
        "time_ratio": None if swing is None else swing.time_ratio,
        "transmission_min": transmission.minimum, "transmission_min_at": transmission.minimum_at,
        "transmission_max": transmission.maximum, "transmission_max_at": transmission.maximum_at,
        "worst_transmission": transmission.worst,
    }
