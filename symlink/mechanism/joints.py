"""Linkages from their joints: links, joints and the coordinates of one drawn pose give the loops.

A designer's sketch says which link holds which joint and where the joints
are; :func:`from_joints` turns that into an ordinary
:class:`~symlink.symbolic.linkage.Linkage` (closed forms, code, drawings, analysis and
everything else work on it unchanged) and the values that reproduce the
drawing:

* **One vector a link side, named after its joints.**  Side ``AB`` of a link
  is ``Vector(AB, theta_AB)`` from joint A to joint B, its length the symbol
  ``AB`` (the distance in the drawing).  A link with k joints has the k - 1
  sides from its first joint (as listed) to the others, so that its shape is
  fixed by independent dimensions; a loop that crosses a ternary link between
  two other joints walks through its first joint.  A moving link turns with
  one angle, that of its first side; every other side sits at a fixed angle
  to it, ``theta_AB + alpha_AC``, with ``alpha_AC`` read from the drawing (a
  ternary link's shape).  The ground's sides have fixed angles ``alpha_AD``;
  if the ground's first joint is not at the origin, the points start with its
  coordinates ``x_A``, ``y_A``.
* **A slider** (:class:`Slider`) is a pin in a slot: the joint's pin slides
  along a line of its guide link, through the joint's drawn position at the
  drawn angle, and turns in the other links that hold it (with
  ``turns=False`` the one other link is a block that does not turn on the
  guide).  On the guide, the joint is the guide's first fixed joint R plus
  the travel ``s_C`` along the line (a coordinate) and the offset ``e_C``
  square to it (left out where the line passes through R).
* **Loops found, not written.**  The loops are simple cycles of the joint
  graph, chosen one after another so that each has exactly two unknowns that
  earlier loops have not solved (a dyad, in closed form by the four cases of
  :mod:`symlink.symbolic.loops`).  Where no such loop is left (an Assur group of a
  higher class, such as the triad of the Stephenson II six-bar driven from
  either ground pivot), the rest are completed to an independent set of loops and the linkage is
  solved by Newton's method (:class:`symlink.numeric.solver.NumericSolver`) as any
  linkage without a closed form.
* **Branch signs from the drawing**: each loop's assembly is the one the
  drawing shows, so the returned values reproduce the drawn pose exactly; the
  order of a loop's two angles (and the direction a slider's travel is
  measured in) is chosen so that the drawn assembly is branch +1, the
  default of every solver and command.
* **Mobility** by Gruebler and Kutzbach; a structure whose mobility differs
  from its number of drivers, or that has an over-constrained part, is
  refused with a ``ValueError`` naming the links.

A driver is a joint: a pin on the ground drives the angle of the moving link
it holds (that link's first side), a slider drives its travel, and a pin
between two moving links drives their relative angle ``theta_<joint>`` (from
the first side of one to the first side of the other, the driven one named
as ``(joint, link)`` or else the second that holds it).

>>> drawn = from_joints(
...     links={"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
...     coordinates={"A": (0, 0), "B": (0, 20), "C": (60, 50), "D": (80, 0)}, driver="A")
>>> drawn.linkage.inputs, drawn.linkage.unknowns, [s.case.name for s in drawn.linkage.plan]
((theta_AB,), (theta_BC, theta_DC), ['3'])
>>> drawn.parameters["AB"], drawn.branches
(20.0, {'branch': 1})
"""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field, replace
from typing import Collection, Mapping, Sequence

import sympy as sp

from .drawn_branches import DrawnPoseError, drawn_branch_signs
from .mobility import Mobility
from ..common.display import record_html
from ..symbolic.linkage import Linkage
from ..symbolic.loops import Loop
from .topology import GROUND, Chain, Cycle, Traversal, independent
from ..symbolic.vectors import Vector, VectorSum

__all__ = ["Slider", "REVOLUTE", "JointLinkage", "JointDescription", "from_joints", "DrawnPoseError"]

REVOLUTE = "R"

#: Relative size (of the drawing) below which two joints coincide or a slider's line passes through its guide's pin.
_COINCIDENT = 1e-12
#: Coordinates beyond this size, or non-zero below its inverse, are out of range: lengths are squared and
#: multiplied in the closed forms (the bound of synthesis targets).
MAX_COORDINATE = 1e100


@dataclass(frozen=True)
class Slider:
    """A slider joint: its pin slides on link ``guide`` along a line at ``angle`` (radians, in the drawing).

    The line passes through the joint's drawn position and turns with the guide.
    With ``turns=False`` the joint is a prismatic joint proper: the one other link
    that holds it is a block that slides on the guide without turning on it.

    Parameters
    ----------
    guide : str
        The link the pin slides on.
    angle : float
        The direction of the sliding line in the drawing, in radians.
    turns : bool, optional
        True (default): a pin in a slot, free to turn; False: a prismatic block that does not turn on the guide.

    Examples
    --------
    >>> import symlink
    >>> symlink.Slider("ground", 0.0)
    Slider(guide='ground', angle=0.0, turns=True)
    """

    guide: str
    angle: float
    turns: bool = True

    def __post_init__(self) -> None:
        if not isinstance(self.guide, str):
            raise ValueError(f"a slider's guide is a link name, not {self.guide!r}")
        angle = _number(self.angle, f"slider on {self.guide!r}: angle")
        object.__setattr__(self, "angle", angle)


@dataclass(frozen=True)
class JointLinkage:
    """What :func:`from_joints` derives: the linkage, and the values that reproduce the drawn pose.

    ``parameters`` are the lengths, fixed angles and offsets read from the drawing;
    ``pose`` every coordinate (inputs and unknowns) in the drawing; ``branches`` each
    loop's assembly sign there (none for a linkage solved by Newton's method): +1
    wherever the loop allows (each case-3 loop takes its two angles, each slider
    its travel, in the order or direction that makes the drawing +1), so that
    the branches' default shows the drawing.
    ``structure`` lists the groups the linkage is solved in, in order: each dyad's
    links and loop, then (if any) the rest that Newton's method solves together.
    ``coordinates``, ``sliders`` and ``drivers`` are the description it was made
    from (the writers of other tools' formats need them); ``speeds`` each driver
    joint's speed as another tool's file gave it (pylinkage's ``angular_velocity``,
    rad a step), kept for writing it back.

    Parameters
    ----------
    linkage : Linkage
        The linkage the joints make.
    chain : Chain
        Its links and joints as a graph.
    parameters : dict of str to float
        Lengths, fixed angles and offsets read from the drawing.
    pose : dict of str to float
        Every coordinate in the drawing.
    branches : dict of str to int
        Each loop's assembly sign in the drawing.
    mobility : Mobility
        Its Gruebler/Kutzbach count.
    structure : tuple of (str, tuple of str)
        The groups it is solved in, in order.
    coordinates, sliders, drivers : optional
        The description it was made from.
    speeds : dict of str to float, optional
        Each driver joint's speed as another tool's file gave it.

    Examples
    --------
    >>> import symlink
    >>> made = symlink.from_joints({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"],
    ...                             "rocker": ["D", "C"]},
    ...                            {"A": (0, 0), "B": (0, 1), "C": (3, 2), "D": (3, 0)}, driver="A")
    >>> made.parameters["AB"], made.parameters["AD"], round(made.parameters["BC"] ** 2, 9)  # |BC|^2 = 3^2 + 1^2
    (1.0, 3.0, 10.0)
    >>> made.mobility.dof, made.branches
    (1, {'branch': 1})
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    linkage: Linkage
    chain: Chain
    parameters: dict[str, float]
    pose: dict[str, float]
    branches: dict[str, int]
    mobility: Mobility
    structure: tuple[tuple[str, tuple[str, ...]], ...]
    coordinates: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    sliders: Mapping[str, Slider] = field(default_factory=dict)
    drivers: tuple[tuple[str, str | None], ...] = ()
    speeds: Mapping[str, float] = field(default_factory=dict)

    @property
    def slider_angles(self) -> dict[str, float]:
        """Each slider's line angle in the drawing (radians)."""
        return {joint: slider.angle for joint, slider in self.sliders.items()}

    @property
    def values(self) -> dict[str, float]:
        """Parameters and the inputs at the drawn pose: a linkage file's defaults (every branch is +1 there)."""
        return {**self.parameters, **{q.name: self.pose[q.name] for q in self.linkage.inputs}}

    @property
    def defaults(self) -> dict[str, float]:
        """Parameters, the inputs at the drawn pose and the branch signs: the arguments of a generated solver."""
        inputs = {q.name: self.pose[q.name] for q in self.linkage.inputs}
        return {**self.parameters, **inputs, **{k: float(v) for k, v in self.branches.items()}}

    @property
    def guess(self) -> dict[str, float]:
        """The unknowns at the drawn pose: the initial guess of :class:`symlink.numeric.solver.NumericSolver`."""
        return {q.name: self.pose[q.name] for q in self.linkage.unknowns}


@dataclass(frozen=True)
class JointDescription:
    """The arguments of :func:`from_joints` as data: what the readers of other tools' files return.

    ``names`` maps the names the source used (a tool's joint ids) to the joint names here.

    Parameters
    ----------
    links : mapping of str to sequence of str
        Each link and the joints it holds, as for :func:`from_joints`.
    coordinates : mapping of str to (float, float)
        Every joint's drawn position.
    drivers : tuple of str or (str, str)
        The driven joints.
    joints : mapping of str to Slider, optional
        The joints that are not revolute pins.
    ground : str, optional
        The ground link's name.
    name : str, optional
        The linkage's name.
    names : mapping of str to str, optional
        The source's names of the joints (a tool's ids) to the names here.

    Examples
    --------
    >>> import symlink
    >>> description = symlink.JointDescription(
    ...     {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
    ...     {"A": (0, 0), "B": (0, 1), "C": (3, 2), "D": (3, 0)}, ("A",))
    >>> description.build().linkage.unknowns
    (theta_BC, theta_DC)
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    links: Mapping[str, Sequence[str]]
    coordinates: Mapping[str, tuple[float, float]]
    drivers: tuple[str | tuple[str, str], ...]
    joints: Mapping[str, object] | None = None
    ground: str = GROUND
    name: str = "linkage"
    names: Mapping[str, str] | None = None
    speeds: Mapping[str, float] | None = None

    def build(self) -> "JointLinkage":
        """The linkage (:func:`from_joints`), with the drivers' ``speeds`` kept."""
        built = from_joints(self.links, self.coordinates, driver=list(self.drivers), joints=self.joints,
                            ground=self.ground, name=self.name)
        return replace(built, speeds=dict(self.speeds)) if self.speeds else built


def _number(value: object, what: str) -> float:
    """A finite real number (NumPy's scalars too), never text."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"{what} must be a number, not {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{what} must be finite, got {value}")
    return value


def _wrap(angle: float) -> float:
    """An angle in (-pi, pi]."""
    wrapped = math.remainder(angle, 2 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def _side_name(first: str, second: str) -> str:
    return first + second if len(first) == len(second) == 1 else f"{first}_{second}"


class _Builder:
    """The vectors of a chain drawn at ``points``: sides, sliders and walks along links."""

    def __init__(self, chain: Chain, points: Mapping[str, tuple[float, float]], sliders: Mapping[str, Slider],
                 drivers: Sequence[tuple[str, str | None]]) -> None:
        self.chain, self.points, self.sliders = chain, points, sliders
        self.values: dict[sp.Symbol, float] = {}
        self.lengths: list[sp.Symbol] = []
        self.angles: list[sp.Symbol] = []
        self.offsets: list[sp.Symbol] = []
        self.pose: dict[sp.Symbol, float] = {}
        self.sides: dict[tuple[str, str, str], Vector] = {}
        self.slides: dict[str, tuple[Vector, ...]] = {}
        span = [c for xy in points.values() for c in xy]
        self.scale = max(max(span) - min(span), max(abs(c) for c in span), 1e-300)
        self.angle_of: dict[str, sp.Expr] = {}      # a moving link's angle symbol
        self.reference: dict[str, float] = {}       # its value in the drawing
        self.travel: dict[str, sp.Symbol] = {}
        self.driven: dict[sp.Symbol, tuple[str, str | None]] = {}
        for link in chain.links:
            if self.frame(link) == link:
                self._link_angle(link)
        for joint in chain.sliders:
            self.travel[joint] = sp.Symbol(f"s_{joint}", real=True)
        for driver in drivers:
            coordinate = self._driven_coordinate(driver)
            if coordinate in self.driven:
                raise ValueError(f"drivers {self.driven[coordinate][0]!r} and {driver[0]!r} drive the same "
                                 f"{coordinate}")
            self.driven[coordinate] = driver

    # --- symbols ------------------------------------------------------------
    def _parameter(self, name: str, value: float, kind: list, **assumptions) -> sp.Symbol:
        symbol = sp.Symbol(name, **assumptions)
        if symbol not in self.values:
            self.values[symbol] = value
            kind.append(symbol)
        return symbol

    def _direction(self, first: str, second: str) -> float:
        (x0, y0), (x1, y1) = self.points[first], self.points[second]
        apart = math.hypot(x1 - x0, y1 - y0)
        if apart == 0:
            raise ValueError(f"joints {first!r} and {second!r} are drawn at the same point, so the side "
                             f"{_side_name(first, second)} has no direction; draw them apart")
        if apart <= _COINCIDENT * self.scale:
            raise ValueError(f"joints {first!r} and {second!r} are {apart:.3g} apart in a drawing {self.scale:.3g} "
                             f"across: closer than {_COINCIDENT:g} of its size, too close to tell the side "
                             f"{_side_name(first, second)}'s direction; draw them apart")
        return math.atan2(y1 - y0, x1 - x0)

    def frame(self, link: str) -> str | None:
        """The link whose angle turns ``link``: itself, its guide's frame for a block, None on the ground."""
        seen: list[str] = []
        while link != self.chain.ground:
            guide = self.chain.block_guide(link)
            if guide is None:
                return link
            if link in seen:
                raise ValueError(f"links {', '.join(seen)} slide on each other in a ring, without turning")
            seen.append(link)
            link = guide
        return None

    def _link_angle(self, link: str) -> None:
        """A moving link's angle: of its first side, or of its slider's line if it holds one fixed joint only."""
        rigid = self.chain.rigid_joints(link)
        if len(rigid) >= 2:
            name, value = _side_name(rigid[0], rigid[1]), self._direction(rigid[0], rigid[1])
        else:
            joint = next(j for j in self.chain.links[link] if self.chain.sliders.get(j) == link)
            name, value = _side_name(rigid[0], joint), self.sliders[joint].angle
        symbol = sp.Symbol(f"theta_{name}", real=True)
        self.angle_of[link], self.reference[link], self.pose[symbol] = symbol, value, value

    def _driven_coordinate(self, driver: tuple[str, str | None]) -> sp.Symbol:
        joint, link = driver
        if joint not in self.points:
            raise ValueError(f"driver {joint!r} is not a joint of the linkage (its joints are "
                             f"{', '.join(self.points)})")
        if link is not None and link not in self.chain.links:
            raise ValueError(f"driver ({joint!r}, {link!r}): no link {link!r} (the links are "
                             f"{', '.join(self.chain.links)})")
        if joint in self.chain.sliders:
            if link is not None:
                raise ValueError(f"driver {joint!r} is a slider: it drives its travel, not link {link!r}")
            return self.travel[joint]
        holders = self.chain.links_of(joint)
        if self.chain.ground not in holders:
            return self._relative(joint, link, holders)
        moving = [other for other in holders if other != self.chain.ground]
        if any(other not in self.angle_of for other in ([link] if link is not None else moving)):
            raise ValueError(f"driver {joint!r} turns a link that slides on its guide without turning")
        if link is not None:
            if link not in moving:
                raise ValueError(f"driver ({joint!r}, {link!r}): {link!r} is not a moving link at {joint!r} "
                                 f"(those are {', '.join(moving)})")
            return self.angle_of[link]
        if len(moving) != 1:
            raise ValueError(f"driver {joint!r} joins the ground to {len(moving)} links ({', '.join(moving)}); "
                             f"name the driven one: ({joint!r}, {moving[0]!r})")
        return self.angle_of[moving[0]]

    def _relative(self, joint: str, link: str | None, holders: Sequence[str]) -> sp.Symbol:
        """A pin between two moving links driven by their relative angle ``theta_<joint>``: the driven link (the
        one named, else the second that holds the pin) turns with the other one's angle plus this input, which
        is the angle from the other link's first side to the driven link's, as drawn."""
        if len(holders) != 2 or (link is not None and link not in holders):
            raise ValueError(f"driver {joint!r} joins {', '.join(holders)}: a relative driver is a pin between "
                             "two moving links (name the driven one as (joint, link))")
        driven = link if link is not None else holders[1]
        base = next(other for other in holders if other != driven)
        if not isinstance(self.angle_of.get(driven), sp.Symbol) or base not in self.angle_of:
            raise ValueError(f"driver {joint!r}: link {driven!r} turns with another link already; "
                             "drive a pin between two links that each turn on their own")
        symbol = sp.Symbol(f"theta_{joint}", real=True)
        self.pose[symbol] = _wrap(self.reference[driven] - self.reference[base])
        self.pose.pop(self.angle_of[driven])  # no coordinate of its own any more
        self.angle_of[driven] = self.angle_of[base] + symbol
        return symbol

    def _turning(self, link: str, absolute: float, name: str) -> sp.Expr:
        """The angle of a line drawn at ``absolute`` on ``link``: a fixed angle on the ground (or a block sliding
        on it), else the angle of the link that turns it plus a fixed offset (none for that link's own line)."""
        frame = self.frame(link)
        if frame is None:
            return self._parameter(f"alpha_{name}", absolute, self.angles, real=True)
        offset = _wrap(absolute - self.reference[frame])
        if frame == link and f"theta_{name}" == getattr(self.angle_of[link], "name", None):
            return self.angle_of[link]
        return self.angle_of[frame] + self._parameter(f"alpha_{name}", offset, self.angles, real=True)

    # --- vectors ------------------------------------------------------------
    def side(self, link: str, first: str, second: str) -> Vector:
        """The vector of a link side from ``first`` (the link's first fixed joint) to ``second``."""
        key = (link, first, second)
        if key not in self.sides:
            name = _side_name(first, second)
            (x0, y0), (x1, y1) = self.points[first], self.points[second]
            length = self._parameter(name, math.hypot(x1 - x0, y1 - y0), self.lengths, positive=True)
            angle = self._turning(link, self._direction(first, second), name)
            self.sides[key] = Vector(length, angle, name)
        return self.sides[key]

    def slide(self, joint: str) -> tuple[Vector, ...]:
        """The vectors from the guide's first fixed joint to the slider: the travel along the line and the offset
        square to it (if any), in the order :mod:`symlink.mechanism.bodies` reads as a block on its guide: on a fixed line
        the travel first (the offset rides on the block), on a turning guide the offset first (it turns with
        the guide)."""
        if joint not in self.slides:
            guide = self.chain.sliders[joint]
            anchor = self.chain.rigid_joints(guide)[0]
            angle = self.sliders[joint].angle
            (x0, y0), (x1, y1) = self.points[anchor], self.points[joint]
            along = math.cos(angle) * (x1 - x0) + math.sin(angle) * (y1 - y0)
            across = math.cos(angle) * (y1 - y0) - math.sin(angle) * (x1 - x0)
            direction = self._turning(guide, angle, _side_name(anchor, joint))
            travel = self.travel[joint]
            self.pose[travel] = along
            if abs(across) <= _COINCIDENT * self.scale:
                self.slides[joint] = (Vector(travel, direction, _side_name(f"{joint}s", joint)),)
                return self.slides[joint]
            offset = self._parameter(f"e_{joint}", abs(across), self.offsets, positive=True)
            square = direction + math.copysign(1, across) * sp.pi / 2
            if self.frame(guide) is None:  # on a fixed line the offset rides on the block, after the travel
                self.slides[joint] = (Vector(travel, direction, _side_name(anchor, f"{joint}s")),
                                      Vector(offset, square, _side_name(f"{joint}s", joint)))
            else:  # on a turning guide the offset turns with the guide, before the travel
                self.slides[joint] = (Vector(offset, square, _side_name(anchor, f"{joint}e")),
                                      Vector(travel, direction, _side_name(f"{joint}s", joint)))
        return self.slides[joint]

    def walk(self, link: str, start: str, end: str) -> VectorSum:
        """The vectors walked along ``link`` from joint ``start`` to joint ``end``, in walking order."""
        guide = self.chain.sliders
        if guide.get(end) == link:
            anchor = self.chain.rigid_joints(link)[0]
            before = self.walk(link, start, anchor) if start != anchor else VectorSum(())
            for vector in self.slide(end):
                before = before + vector
            return before
        if guide.get(start) == link:  # the way back: the same vectors in the reverse order, each walked backwards
            back = self.walk(link, end, start)
            return VectorSum(tuple((-sign, vector) for sign, vector in reversed(back.terms)))
        base = self.chain.rigid_joints(link)[0]
        if start == base:
            return self.side(link, base, end).as_sum()
        if end == base:
            return -self.side(link, base, start)
        return -self.side(link, base, start) + self.side(link, base, end)

    def loop(self, cycle: Cycle) -> Loop:
        total = VectorSum(())
        for t in cycle.traversals:
            total = total + self.walk(t.link, t.entry, t.exit)
        return Loop(total, name=cycle.name)

    def coordinates_in(self, traversal: Traversal) -> list[sp.Symbol]:
        """The coordinates a walk along a link turns or stretches, in walking order."""
        found: list[sp.Symbol] = []
        for joint in (traversal.entry, traversal.exit):
            if self.chain.sliders.get(joint) == traversal.link:
                found.append(self.travel[joint])
        frame = self.frame(traversal.link)
        if frame is not None:  # the link's own angle, or (driven relative to another) that one's and the input
            angle = self.angle_of[frame]
            turning = [angle] if isinstance(angle, sp.Symbol) else sorted(
                (q for q in angle.free_symbols if q.name.startswith("theta_") and q not in self.values), key=str)
            found[:0] = turning
        return found

    def points_from_origin(self) -> dict[str, VectorSum | None]:
        """Every joint as a sum of vectors from the origin, walked link by link from the ground's first joint."""
        ground = self.chain.ground
        start = self.chain.rigid_joints(ground)[0]
        x, y = self.points[start]
        origin = VectorSum(())
        if abs(x) > 0:
            origin = origin + Vector(self._parameter(f"x_{start}", x, self.offsets, real=True), 0, f"O{start}x")
        if abs(y) > 0:
            origin = origin + Vector(self._parameter(f"y_{start}", y, self.offsets, real=True), sp.pi / 2,
                                     f"O{start}y")
        found: dict[str, VectorSum] = {start: origin}
        queue = [start]
        for joint in queue:  # breadth first: the queue grows as it is walked
            for link in self.chain.links_of(joint):
                for other in self.chain.links[link]:
                    if other not in found:
                        found[other] = found[joint] + self.walk(link, joint, other)
                        queue.append(other)
        return {joint: (found[joint] if found[joint].terms else None) for joint in self.chain.joints}


def _joint_kinds(joints: Mapping[str, object] | None, chain_joints: Sequence[str]) -> dict[str, Slider]:
    sliders: dict[str, Slider] = {}
    for name, kind in (joints or {}).items():
        if name not in chain_joints:
            raise ValueError(f"joints: {name!r} is on no link (the links hold {', '.join(chain_joints)})")
        if isinstance(kind, Slider):
            sliders[name] = kind
        elif kind not in (REVOLUTE, "revolute"):
            raise ValueError(f"joints: {name!r} is {kind!r}; a joint is 'R' (revolute) or a Slider(guide, angle)")
    return sliders


def _pins_on_slides(links: Mapping[str, Sequence[str]], sliders: dict[str, Slider],
                    coordinates: Mapping[str, Sequence[float]], drivers: list[tuple[str, str | None]]) -> tuple:
    """The links, sliders, coordinates and drivers with every block whose pin lies on its slide taken as the pin
    sliding on the guide.

    The textbook slider-crank's block: a link holding a pin C (to the rod) and a prismatic joint S (on its guide,
    ``turns=False``), both drawn at one point, and nothing else.  It moves as the pin C sliding along the line
    on the guide (the block only carries it, without turning on the guide): the block and S are taken out, C
    becomes ``Slider(guide, angle)`` (the pin turns in the rod), the guide holds C where it held S, and a driver
    of S drives C's travel.  Mobility is unchanged (a link, a pin and a prismatic joint: -1; a pin in a slot:
    -1).  Anything malformed is left as it is, for the checks that name it.
    """
    merged = {name: list(joints) for name, joints in links.items()}
    kinds = dict(sliders)
    points = dict(coordinates)
    for joint, slider in sliders.items():
        if slider.turns or slider.guide not in merged:
            continue
        holders = [name for name, joints in merged.items() if joint in joints and name != slider.guide]
        if len(holders) != 1:
            continue
        block = holders[0]
        others = [j for j in merged[block] if j != joint]
        if len(others) != 1 or others[0] in kinds or others[0] in merged[slider.guide]:
            continue
        pin = others[0]
        try:
            (x0, y0), (x1, y1) = ((float(v) for v in points[j]) for j in (joint, pin))
        except (KeyError, TypeError, ValueError):
            continue
        if math.hypot(x1 - x0, y1 - y0) > _COINCIDENT * max(1.0, abs(x0), abs(y0)):
            continue
        del merged[block]
        merged[slider.guide] = [pin if j == joint else j for j in merged[slider.guide]]
        del kinds[joint]
        kinds[pin] = Slider(slider.guide, slider.angle)
        del points[joint]
        drivers = [(pin, None) if j == joint else (j, link) for j, link in drivers]
    return merged, kinds, points, drivers


def _drawn(coordinates: Mapping[str, Sequence[float]], joints: Sequence[str]) -> dict[str, tuple[float, float]]:
    missing = [j for j in joints if j not in coordinates]
    if missing:
        raise ValueError(f"coordinates: no position for joint{'s' if len(missing) > 1 else ''} {', '.join(missing)}")
    known = set(joints)
    extra = [j for j in coordinates if j not in known]
    if extra:
        raise ValueError(f"coordinates: {', '.join(map(repr, extra))} is on no link")
    points = {}
    for joint in coordinates:  # in the order given (a tool's joint order survives a round trip)
        xy = coordinates[joint]
        if isinstance(xy, str) or not hasattr(xy, "__len__") or len(xy) != 2:
            raise ValueError(f"coordinates: joint {joint!r} needs two numbers (x, y), not {xy!r}")
        points[joint] = (_number(xy[0], f"coordinates: {joint}.x"), _number(xy[1], f"coordinates: {joint}.y"))
        for axis, value in zip("xy", points[joint]):
            if value != 0 and not 1 / MAX_COORDINATE <= abs(value) <= MAX_COORDINATE:
                raise ValueError(f"coordinates: {joint}.{axis} = {value:g} is out of range (a coordinate is 0 or "
                                 f"between {1 / MAX_COORDINATE:g} and {MAX_COORDINATE:g} in size; rescale the "
                                 "drawing)")
    return points


def _check_structure(chain: Chain, drivers: Sequence[tuple[str, str | None]]) -> Mobility:
    mobility = chain.mobility()
    given = [joint if link is None else (joint, link) for joint, link in drivers]
    stuck = chain.overconstrained(given)
    if stuck is not None:
        joints = sorted({j for link in stuck for j in chain.links[link]
                         if sum(other in stuck for other in chain.links_of(j)) > 1})
        inside = [d for d in given if all(link in stuck for link in chain.driven_links(d))]
        driven = f" and {len(inside)} driver{'s' if len(inside) > 1 else ''}" if inside else ""
        raise ValueError(f"links {', '.join(stuck)} are over-constrained: joined by {', '.join(joints)}{driven} "
                         f"they have mobility {chain.local_mobility(stuck, given)}, so they move only for special "
                         "dimensions (a rigid part, or a loop that closes twice)")
    if mobility.dof != len(drivers):
        kind = "under" if mobility.dof > len(drivers) else "over"
        raise ValueError(f"the linkage is {kind}-constrained: Gruebler gives mobility {mobility.dof} "
                         f"({mobility.links} links with the ground, {mobility.revolute} revolute and "
                         f"{mobility.prismatic} prismatic joints) but it has {len(drivers)} "
                         f"driver{'s' if len(drivers) != 1 else ''}")
    return mobility


def _plan(builder: _Builder, cycles: Sequence[Cycle], unknowns: Sequence[sp.Symbol],
          swapped: Collection[str] = frozenset()) -> list[tuple[Cycle, Loop, list]]:
    """Loops that each solve two new unknowns (dyads), in order, with the unknowns each solves.

    Each step takes the first loop of ``cycles`` that has exactly two unknowns left and a closed form for them.
    A loop with fewer than two unknowns left, or with two but no closed form, never becomes one that fits (the
    unknowns left only shrink): it is dropped, so that planning n dyads scans each loop about once.
    """
    left = dict.fromkeys(unknowns)
    chosen: list[tuple[Cycle, Loop, list]] = []
    candidates = [(cycle, [q for t in cycle.traversals for q in builder.coordinates_in(t)]) for cycle in cycles]
    progress = True
    while left and progress:
        progress = False
        alive = []
        for at, (cycle, coordinates) in enumerate(candidates):
            found = [q for q in coordinates if q in left]
            if len(found) < 2:
                continue
            if len(found) > 2:
                alive.append((cycle, coordinates))
                continue
            loop = builder.loop(cycle)
            try:
                loop.case(found)
            except ValueError:
                continue
            chosen.append((cycle, loop, found[::-1] if cycle.name in swapped else found))
            for q in found:
                left.pop(q, None)
            candidates = alive + candidates[at + 1:]
            progress = True
            break
    return chosen


def _complete(builder: _Builder, chosen: Sequence[Cycle], cycles: Sequence[Cycle], unknowns: int) -> list[Cycle]:
    """The shortest loops independent of ``chosen`` and each other, until there are two equations an unknown."""
    loops = list(chosen)
    for cycle in cycles:
        if 2 * len(loops) >= unknowns:
            break
        if all(cycle is not c for c in loops) and independent(loops + [cycle]):
            loops.append(cycle)
    return loops[len(chosen):]


def _planned(builder: _Builder, chain: Chain, unknowns: Sequence[sp.Symbol],
             swapped: Collection[str]) -> tuple[list[tuple[Cycle, Loop, list]], list[Cycle]]:
    """The dyad plan (:func:`_plan`) and, for unknowns it leaves, the loops that close them (:func:`_complete`).

    The dyads are looked for among the chain's shortest loops first: the loops of up to 4 joints, then 8, ...
    (the first loops of the full list, in its order), until the plan solves every unknown, so the plan is the one
    the full list gives; a chain of dyads is planned in a time that grows with its size, not with the number of
    its loops.  A plan that leaves unknowns (a numeric fallback) searches every loop, as before."""
    longest, everything = 4, len(chain.joints)
    while True:
        cycles = chain.cycles(longest=min(longest, everything))
        steps = _plan(builder, cycles, unknowns, swapped)
        planned = {q for _, _, found in steps for q in found}
        if len(planned) < len(unknowns) and longest < everything:
            longest *= 2  # a longer loop may solve the next dyad: the plan is the full list's only when it is done
            continue
        more = _complete(builder, [cycle for cycle, _, _ in steps], cycles, len(unknowns)) \
            if len(planned) < len(unknowns) else []
        return steps, more


def _derive(chain: Chain, points: Mapping[str, tuple[float, float]], sliders: Mapping[str, Slider],
            drivers: Sequence[tuple[str, str | None]], name: str, swapped: set[str]) -> tuple:
    """The linkage, its builder, its structure and its branch signs at the drawing (``swapped``: loops whose two
    unknowns are taken in the other order)."""
    ground = chain.ground
    builder = _Builder(chain, points, sliders, drivers)
    inputs = list(builder.driven)
    unknowns = [q for link in chain.links if link in builder.angle_of for q in [builder.angle_of[link]]
                if isinstance(q, sp.Symbol) and q not in builder.driven]
    unknowns += [s for s in builder.travel.values() if s not in builder.driven]
    steps, more = _planned(builder, chain, unknowns, swapped)
    loops = [loop for _, loop, _ in steps]
    order = [q for _, _, found in steps for q in found]
    link_of = {q: link for link, q in builder.angle_of.items() if isinstance(q, sp.Symbol)}
    structure: list[tuple[str, tuple[str, ...]]] = [
        (loop.name, tuple(link_of[q] for q in found if q in link_of)) for _, loop, found in steps]
    planned = set(order)
    rest = [q for q in unknowns if q not in planned]
    if rest:
        loops += [builder.loop(cycle) for cycle in more]
        structure.append(("+".join(c.name for c in more), tuple(link_of[q] for q in rest if q in link_of)))
        order += rest
    for joint in chain.joints:  # every slider's vectors, in the drawing, even one that no loop walks
        if joint in chain.sliders:
            builder.slide(joint)
    points_from_origin = builder.points_from_origin()
    parameters = builder.lengths + builder.angles + builder.offsets
    taken = {s.name for s in parameters + inputs + order} | set(points)
    roles = {link: q for link, q in builder.angle_of.items()
             if isinstance(q, sp.Symbol) and link not in taken and link != ground}
    linkage = Linkage(name, loops, inputs=inputs, unknowns=order,
                      parameters=parameters, points=points_from_origin, roles=roles)
    values = dict(builder.values)
    values.update(builder.pose)
    branches = drawn_branch_signs(linkage, values, builder.scale) if linkage.has_closed_form else {}
    return linkage, builder, tuple(structure), branches


def _drivers(driver: object) -> list[tuple[str, str | None]]:
    """Drivers as (joint, driven link or None): a joint name, or a list of joint names and (joint, link) pairs."""
    items = [driver] if isinstance(driver, str) else driver
    if not isinstance(items, (list, tuple)) or not items:
        raise ValueError("driver: name the driven joint (a pin on the ground or a slider), or list them")
    found: list[tuple[str, str | None]] = []
    for item in items:
        if isinstance(item, str):
            found.append((item, None))
        elif isinstance(item, (list, tuple)) and len(item) == 2 and all(isinstance(i, str) for i in item):
            found.append((item[0], item[1]))
        else:
            raise ValueError(f"driver {item!r}: give a joint name or a (joint, link) pair")
    return found


def from_joints(links: Mapping[str, Sequence[str]], coordinates: Mapping[str, Sequence[float]],
                driver: str | Sequence[str | tuple[str, str]], joints: Mapping[str, object] | None = None, *,
                ground: str = GROUND, name: str = "linkage") -> JointLinkage:
    """The linkage that ``links`` and ``joints`` make, dimensioned and posed by the drawn ``coordinates``.

    ``links`` maps each link (``ground`` among them) to the joints it holds, in an
    order that names its sides (the first two give the link's angle);
    ``coordinates`` gives every joint's (x, y) in one assembled pose; ``driver``
    is the driven joint (or a list, one per degree of freedom; a pin on the ground
    that holds several moving links is given with the driven one, ``("A", "crank")``); ``joints`` gives
    the kind of any joint that is not a revolute pin (``Slider(guide, angle)``).
    The result's :attr:`~JointLinkage.linkage` is an ordinary linkage; its
    :attr:`~JointLinkage.defaults` reproduce the drawing.

    Parameters
    ----------
    links : mapping of str to sequence of str
        Each link (the ground among them) and the joints it holds; the first two give the link's angle.
    coordinates : mapping of str to (float, float)
        Every joint's (x, y) in one assembled pose.
    driver : str or sequence of str or (str, str)
        The driven joint, or one a degree of freedom; ``("A", "crank")`` where a ground pin holds several links.
    joints : mapping of str to Slider, optional
        The kind of each joint that is not a revolute pin.
    ground : str, optional
        The name of the ground link (default ``"ground"``).
    name : str, optional
        The linkage's name (default ``"linkage"``).

    Returns
    -------
    JointLinkage
        The linkage, with the parameters, pose and branches that reproduce the drawing.

    Raises
    ------
    ValueError
        A structure that is not a linkage of the given mobility, or a joint without coordinates.

    Examples
    --------
    >>> import symlink
    >>> slider = symlink.from_joints({"ground": ["A", "C"], "crank": ["A", "B"], "rod": ["B", "C"]},
    ...                              {"A": (0, 0), "B": (1, 1), "C": (4, 0.5)}, driver="A",
    ...                              joints={"C": symlink.Slider("ground", 0.0)})
    >>> slider.linkage.unknowns, [s.case.name for s in slider.linkage.plan], slider.pose["s_C"]
    ((theta_BC, s_C), ['2b'], 4.0)
    """
    drivers = _drivers(driver)
    if isinstance(links, Mapping):
        listed = [j for js in links.values() if not isinstance(js, str) for j in js]
    else:
        raise ValueError("links: give a mapping of link names to the joints each link holds")
    sliders = _joint_kinds(joints, listed)
    if isinstance(coordinates, Mapping) and all(isinstance(js, (list, tuple)) for js in links.values()):
        links, sliders, coordinates, drivers = _pins_on_slides(links, sliders, coordinates, drivers)
    chain = Chain(links, {j: s.guide for j, s in sliders.items()}, ground,
                  frozenset(j for j, s in sliders.items() if not s.turns))
    points = _drawn(coordinates, chain.joints)
    mobility = _check_structure(chain, drivers)
    linkage, builder, structure, branches = _derive(chain, points, sliders, drivers, name, set())
    # Make the drawing every loop's assembly +1, so that anything that takes the branches' default (+1) shows it:
    # a case-3 loop takes its two angles in the other order, a slider's travel is measured the other way along
    # its line (cases 2b and 2c: +1 is the larger travel).
    swapped: set[str] = set()
    flipped = dict(sliders)
    for step in linkage.plan if linkage.has_closed_form else ():
        if step.branch is None or branches[step.branch.name] == 1:
            continue
        if step.case.name == "3":
            swapped.add(step.loop.name)
        else:
            travel = next(u for u in (step.case.first, step.case.second) if u.part == "length").symbol
            joint = next(j for j, q in builder.travel.items() if q == travel)
            flipped[joint] = replace(flipped[joint], angle=_wrap(flipped[joint].angle + math.pi))
    if swapped or flipped != sliders:
        linkage, builder, structure, branches = _derive(chain, points, flipped, drivers, name, swapped)
        sliders = flipped
    return JointLinkage(linkage, chain, {s.name: v for s, v in builder.values.items()},
                        {s.name: v for s, v in builder.pose.items()}, branches, mobility, structure,
                        points, dict(sliders), tuple(drivers))
