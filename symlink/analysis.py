"""Analysis of linkages: mobility, and a four-bar's Grashof class, limits and transmission.

* :func:`degrees_of_freedom`: Gruebler/Kutzbach mobility of any :class:`~symlink.linkage.Linkage`,
  with its links and joints counted from the loops.
* :func:`grashof`: the Grashof class of a four-bar, which depends on which link is the
  shortest and which one is the ground.
* :func:`~symlink.reachability.crank_range` (in :mod:`symlink.reachability`): the crank
  angles at which a four-bar can be assembled; its ends are the toggle positions.
* :func:`limit_positions`: the rocker's two extreme positions (crank and coupler in line),
  with the rocker's stroke and the crank-rocker's time ratio.
* :func:`transmission_range` and :func:`transmission_curve`: the transmission angle (the
  interior angle at C between coupler and rocker) over a turn, its minimum and maximum
  and the crank angles where they occur.

Four-bar conventions as in DESIGN.md: crank a = AB from A at the origin, coupler b = BC,
rocker c = DC from D at (d, 0); crank angles (radians) are measured from the ground
line A -> D.  Positions are evaluated with the generated four-bar solver
(:class:`~symlink.solver.Solver`); the closed forms here only say *where* to look.

>>> [tuple(round(math.degrees(x), 4) for x in span) for span in crank_range(20, 66, 56, 80)]
[(-180.0, 180.0)]
>>> grashof(20, 66, 56, 80).name
'crank-rocker'
>>> limits = limit_positions(16.0843, 69.9385, 50, 70)
>>> round(math.degrees(limits.stroke), 2), round(limits.time_ratio, 3)
(40.0, 1.115)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy

from .angles import wrap_angle
from .bodies import PRISMATIC, mechanism
from .catalog import fourbar
from .linkage import Linkage
from .position import TOLERANCE
from .reachability import assembled_crank_range, crank_range
from .solver import check_lengths, shared_solver

__all__ = [
    "Mobility", "degrees_of_freedom", "Grashof", "GRASHOF_CLASSES", "grashof",
    "LimitPositions", "limit_positions", "TransmissionRange", "transmission_range",
    "transmission_curve", "triangle_angle", "wrap_angle",
]


# --- mobility -------------------------------------------------------------------------

@dataclass(frozen=True)
class Mobility:
    """Links and joints of a planar linkage, and its Gruebler/Kutzbach mobility.

    ``links`` counts the ground; every joint is a one-freedom pair (revolute or
    prismatic), so ``dof = 3 (links - 1) - 2 (revolute + prismatic)``.
    """

    links: int
    revolute: int
    prismatic: int

    @property
    def joints(self) -> int:
        return self.revolute + self.prismatic

    @property
    def dof(self) -> int:
        return 3 * (self.links - 1) - 2 * self.joints


def degrees_of_freedom(linkage: Linkage) -> Mobility:
    """Gruebler/Kutzbach mobility of ``linkage``: ``3 (n - 1) - 2 j1 - j2`` over its bodies and joints.

    The bodies and joints are those :func:`symlink.bodies.mechanism` derives
    from the loops and points (a pin joining k bodies counts as k - 1 joints;
    a slider on its guide is one prismatic joint).

    >>> degrees_of_freedom(fourbar()).dof
    1
    """
    found = mechanism(linkage)
    prismatic = sum(joint.kind == PRISMATIC for joint in found.joints)
    return Mobility(len(found.bodies), found.one_freedom_joints - prismatic, prismatic)

# --- Grashof --------------------------------------------------------------------------

#: Grashof classes of a four-bar, by name.
GRASHOF_CLASSES = {
    "crank-rocker": "Grashof, shortest link is the crank: the crank turns fully, the rocker swings",
    "rocker-crank": "Grashof, shortest link is the rocker: the rocker turns fully, the crank only swings",
    "double-crank": "Grashof, shortest link is the ground: crank and rocker both turn fully (drag link)",
    "double-rocker": "Grashof, shortest link is the coupler: crank and rocker both swing, "
                     "the coupler turns fully",
    "change-point": "s + l = p + q: every inversion passes a change point where all links line up",
    "triple-rocker": "non-Grashof (s + l > p + q): no link turns fully relative to another",
}

_LINK_NAMES = ("crank", "coupler", "rocker", "ground")


@dataclass(frozen=True)
class Grashof:
    """A four-bar's Grashof class and the sums it was decided by."""

    name: str
    shortest: str
    longest: str
    shortest_plus_longest: float
    other_two: float

    @property
    def description(self) -> str:
        return GRASHOF_CLASSES[self.name]

    @property
    def is_grashof(self) -> bool:
        """Some link turns fully: ``s + l <= p + q`` (the change point included)."""
        return self.name != "triple-rocker"


def grashof(a: float, b: float, c: float, d: float, tolerance: float = 1e-12) -> Grashof:
    """Grashof class of the four-bar with crank a, coupler b, rocker c and ground d.

    With s and l the shortest and longest links and p, q the others: ``s + l < p + q``
    is Grashof, and then the class depends on where the shortest link is (crank:
    crank-rocker; ground: double-crank; coupler: double-rocker; rocker: rocker-crank).
    ``s + l = p + q`` (within ``tolerance`` times l) is a change point and
    ``s + l > p + q`` a non-Grashof triple rocker.

    >>> grashof(4, 5, 6, 2).name, grashof(5, 6, 7, 10).name
    ('double-crank', 'triple-rocker')
    """
    check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    links = [float(a), float(b), float(c), float(d)]
    shortest = min(range(4), key=links.__getitem__)
    longest = max(range(4), key=links.__getitem__)
    ordered = sorted(links)
    s_l, p_q = ordered[0] + ordered[3], ordered[1] + ordered[2]
    if abs(s_l - p_q) <= tolerance * ordered[3]:
        name = "change-point"
    elif s_l > p_q:
        name = "triple-rocker"
    else:
        name = {"crank": "crank-rocker", "rocker": "rocker-crank", "ground": "double-crank",
                "coupler": "double-rocker"}[_LINK_NAMES[shortest]]
    return Grashof(name, _LINK_NAMES[shortest], _LINK_NAMES[longest], s_l, p_q)


# --- positions with the generated solver ---------------------------------------------

def triangle_angle(opposite, side1, side2):
    """The angle between ``side1`` and ``side2`` of a triangle, accurate when it is flat.

    ``atan2`` of Heron's product and the law of cosines, so that angles near 0 and pi
    keep their digits; NaN where the three lengths make no triangle (beyond rounding).
    Broadcasts over arrays.

    >>> float(numpy.degrees(triangle_angle(5.0, 3.0, 4.0)))
    90.0
    """
    opposite, side1, side2 = (numpy.asarray(x, dtype=float) for x in (opposite, side1, side2))
    product = ((side1 + side2 + opposite) * (side1 + side2 - opposite)
               * (opposite + side1 - side2) * (opposite - side1 + side2))
    product = numpy.where(product >= -TOLERANCE * (side1 + side2 + opposite) ** 4, numpy.maximum(product, 0.0),
                          numpy.nan)
    return numpy.arctan2(numpy.sqrt(product), side1 * side1 + side2 * side2 - opposite * opposite)


@dataclass(frozen=True)
class LimitPositions:
    """The rocker's extreme positions, where crank and coupler are in line (radians).

    ``extended``: the crank points along the coupler (|AC| = a + b); ``folded``: the
    crank points back along it.  Angles of crank and rocker in each, on ``branch``.
    """

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

    Crank and coupler are in line when ``|AC|`` is ``a + b`` (extended) or ``|b - a|``
    (folded); the triangle A, D, C then gives the crank angle in closed form (on branch
    +1, C lies above the ground line when b > a) and the generated solver gives the rocker
    angle there.  ``ValueError`` if either limit position cannot be assembled (the rocker
    of such a linkage stops at toggles instead: see :func:`crank_range`).
    """
    check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    if branch not in (1, -1):
        raise ValueError(f"branch must be +1 or -1, got {branch}")
    if a == b:
        raise ValueError("crank and coupler are equally long: the folded limit puts C on A")
    crank = []
    for reach, folded in ((a + b, False), (abs(b - a), True)):
        angle = float(triangle_angle(c, reach, d))  # at A, between A->D and A->C
        if math.isnan(angle):
            kind = "folded" if folded else "extended"
            raise ValueError(f"the {kind} limit position (|AC| = {reach:g}) cannot be assembled with "
                             f"rocker {c:g} and ground {d:g}")
        # C above the ground line is branch +1, except when folded with a > b, where C is on the crank.
        side = -branch if folded and a > b else branch
        crank.append(wrap_angle(side * angle + (math.pi if folded and b > a else 0.0)))
    solved = shared_solver(fourbar, ("rocker",))(theta=numpy.array(crank), a=a, b=b, c=c, d=d, branch=branch)
    rocker = [float(value) for value in solved["rocker"]]
    return LimitPositions(branch, crank[0], rocker[0], crank[1], rocker[1])


# --- transmission angle -------------------------------------------------------------

@dataclass(frozen=True)
class TransmissionRange:
    """Smallest and largest transmission angle over the reachable crank angles, and where (radians)."""

    minimum: float
    minimum_at: float
    maximum: float
    maximum_at: float

    @property
    def worst(self) -> float:
        """The smallest of ``min(mu, pi - mu)``: how close the linkage comes to locking."""
        return min(self.minimum, math.pi - self.maximum)


def transmission_range(a: float, b: float, c: float, d: float) -> TransmissionRange:
    """Extremes of the transmission angle mu over every crank angle the four-bar reaches.

    ``|BD|^2 = b^2 + c^2 - 2 b c cos(mu) = a^2 + d^2 - 2 a d cos(theta)``: mu grows with
    |BD|, which falls with cos(theta).  So mu is smallest at theta = 0 and largest at
    theta = pi when the crank gets there, and otherwise at the ends of the crank's range
    (the toggles, where mu is 0 or pi).  It is the same on both branches; the generated
    solver evaluates it at those crank angles.
    """
    spans = assembled_crank_range(a, b, c, d)
    candidates: dict[float, float] = {}
    reachable = [x for x in (0.0, math.pi) if any(lo <= x <= hi or lo <= x - 2 * math.pi <= hi
                                                  for lo, hi in spans)]
    if reachable:
        solved = shared_solver(fourbar, ("transmission",))(theta=numpy.array(reachable), a=a, b=b, c=c, d=d, branch=1)
        candidates.update(zip(reachable, (float(mu) for mu in solved["transmission"])))
    if spans != [(-math.pi, math.pi)]:
        far = math.acos(max((a * a + d * d - (b + c) ** 2) / (2 * a * d), -1.0))
        for lo, hi in spans:  # toggles: coupler and rocker in line
            for end in (lo, hi):
                candidates.setdefault(wrap_angle(end), math.pi if math.isclose(abs(wrap_angle(end)), far) else 0.0)
    low = min(candidates, key=candidates.__getitem__)
    high = max(candidates, key=candidates.__getitem__)
    return TransmissionRange(candidates[low], low, candidates[high], high)


def transmission_curve(a: float, b: float, c: float, d: float, theta) -> numpy.ndarray:
    """The transmission angle (radians) at crank angles ``theta``, NaN where it cannot be assembled.

    >>> [round(math.degrees(x), 2) for x in transmission_curve(20, 66, 56, 80, [0.0, math.pi])]
    [58.23, 109.83]
    """
    check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    solved = shared_solver(fourbar, ("transmission",))(theta=numpy.asarray(theta, dtype=float), a=a, b=b, c=c, d=d,
                                                branch=1)
    return numpy.where(solved["assembled"], solved["transmission"], numpy.nan)


# --- the command line -----------------------------------------------------------------

def fourbar_report(a: float, b: float, c: float, d: float, branch: int = 1) -> dict:
    """Everything :mod:`symlink.analysis` says of one four-bar, as a flat record (radians).

    ``limit_positions``, ``stroke`` and ``time_ratio`` are None unless the linkage is a
    crank-rocker (otherwise the output does not swing between two limits as the crank
    turns); ``toggles`` are the ends of the crank's range (empty for a full turn).

    >>> report = fourbar_report(20, 66, 56, 80)
    >>> report["grashof"], report["dof"], round(math.degrees(report["transmission_min"]), 2)
    ('crank-rocker', 1, 58.23)
    """
    spans = assembled_crank_range(a, b, c, d)
    kind = grashof(a, b, c, d)
    transmission = transmission_range(a, b, c, d)
    limits = limit_positions(a, b, c, d, branch) if kind.name == "crank-rocker" else None
    return {
        "crank": a, "coupler": b, "rocker": c, "ground": d, "branch": branch,
        "dof": degrees_of_freedom(fourbar()).dof,
        "grashof": kind.name, "shortest": kind.shortest, "longest": kind.longest,
        "shortest_plus_longest": kind.shortest_plus_longest, "other_two": kind.other_two,
        "crank_range": spans,
        "toggles": [] if spans == [(-math.pi, math.pi)] else [end for span in spans for end in span],
        "limit_positions": None if limits is None else {
            "extended_crank": limits.extended_crank, "extended_rocker": limits.extended_rocker,
            "folded_crank": limits.folded_crank, "folded_rocker": limits.folded_rocker},
        "stroke": None if limits is None else limits.stroke,
        "time_ratio": None if limits is None else limits.time_ratio,
        "transmission_min": transmission.minimum, "transmission_min_at": transmission.minimum_at,
        "transmission_max": transmission.maximum, "transmission_max_at": transmission.maximum_at,
        "worst_transmission": transmission.worst,
    }
