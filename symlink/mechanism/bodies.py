"""Rigid bodies and joints of a linkage, derived from its vector loops and points, and its mobility.

A :class:`~symlink.symbolic.linkage.Linkage` says how its vectors close; this module
reads off what a drawing and a mobility count need from the same vectors:

* **Joints are where vectors meet.**  Every vector is a segment from its tail
  to its head.  Consecutive terms of a loop or of a named point's sum share
  an end (a term walked backwards, ``- BC``, goes from its head to its tail),
  every point's sum starts at the origin, and one :class:`Vector` used in
  several loops and points is one segment.  So the ends of the segments fall
  into nodes: the joints, the corners inside a body, and the named points.
  This needs each loop and point written in walking order (each vector
  starting where the one before ends); where the points show that it is not,
  ``ValueError`` says so.  Fixed vectors in a row are the exception: they add
  up to one offset whatever their order, so a ground offset ``OP = OPx + OPy``
  may be subtracted whole in a loop (``... - PQ - OP``, whose terms walk
  ``- OPx - OPy``) or summed in another order by another point; such a run is
  walked in the order the points already chain it.
* **A vector's direction tells its body.**  Vectors with a constant angle lie
  on the ground; vectors whose angles share the same time-varying part
  (``phi`` and ``phi + alpha``) turn together, so they lie on one rigid body
  (the Watt II rocker ``DC``, ``DE``: a ternary link).
* **A vector whose length is a coordinate is a slider travel**: a prismatic
  joint whose tail lies on the guide (the body of its direction) and whose
  head lies on a block, one more body.  Fixed vectors in the guide's direction
  that carry on from the head move with the block (a translating block keeps
  its guide's orientation): the slider-crank's offset ``SC`` after the travel
  ``AS = s e^{i 0}`` is part of the block that the connecting rod is pinned to.
  A travel that starts on a block along its own direction slides on that
  block (a Scotch yoke's slot, cut in the yoke that slides on the ground).
* Where vectors of k different bodies meet at one node there is a pin joining
  k bodies, which counts as k - 1 revolute joints.  Two bodies that turn
  relative to each other share at most one pin, so two nodes that join the
  same two bodies (a pivot reached by two loops through different vectors)
  are one joint.

Where the vectors alone are ambiguous (two links that a user drives with the
same angle, or a fixed vector that sits on a block rather than the ground),
say it with ``bodies={"body name": ["vector name", ...]}``: each listed vector
is put on that body, every other one is placed as above.

The mobility is Gruebler/Kutzbach's ``M = 3 (n - 1) - 2 j1 - j2`` with n
bodies (the ground included), j1 one-freedom joints (revolute and prismatic)
and j2 two-freedom joints: every joint that vector loops show is a pin or a
slider, so j2 counts only the gear pairs and cams given as ``higher_pairs``.

>>> from symlink.mechanism.catalog import fourbar, watt2
>>> four = mechanism(fourbar())
>>> [body.name for body in four.bodies], four.mobility
(['ground', 'crank', 'coupler', 'rocker'], 1)
>>> four.body("coupler").joints
('B', 'C')
>>> six = mechanism(watt2())
>>> six.body("rocker").joints, six.mobility
(('C', 'D', 'E'), 1)
>>> str(six.joint("C").position)
'AB + BC'
"""
from __future__ import annotations

import itertools
from collections import Counter
from fractions import Fraction
from dataclasses import dataclass
from typing import Mapping, Sequence

import sympy as sp

from ..common.display import record_html
from ..symbolic.linkage import Linkage
from ..symbolic.vectors import Vector, VectorSum

__all__ = ["Body", "Joint", "Mechanism", "mechanism", "drawn_points", "same_point", "REVOLUTE", "PRISMATIC", "GROUND"]

REVOLUTE = "revolute"
PRISMATIC = "prismatic"
GROUND = "ground"
_ORIGIN = "origin"


@dataclass(frozen=True)
class Joint:
    """A pin or a slider.

    ``name`` is the linkage's point there, else ``J1``, ``J2``, ...; a slider
    is named after its travel vector (else ``P1``, ...).
    ``bodies`` are the names of the bodies it joins: a pin joining k bodies
    counts as k - 1 joints (:attr:`count`), a slider joins its guide and its
    block.  ``position`` is the joint as a sum of vectors from the origin
    (an empty sum at the origin), evaluated like a linkage's points, or
    ``None`` where no point's vectors tie the joint to the origin.  A
    slider also has ``guide_start``, the tail of its travel on the guide, and
    ``direction``, the angle of its guide.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    name: str
    kind: str
    bodies: tuple[str, ...]
    position: VectorSum | None
    guide_start: VectorSum | None = None
    direction: sp.Expr | None = None

    @property
    def count(self) -> int:
        """How many one-freedom joints this is in a Gruebler count: k - 1 for a pin joining k bodies."""
        return len(self.bodies) - 1 if self.kind == REVOLUTE else 1

    @property
    def grounded(self) -> bool:
        """Whether the ground is one of the bodies joined (a ground pivot or a slider on a fixed guide)."""
        return GROUND in self.bodies


@dataclass(frozen=True)
class Body:
    """A rigid body: the vectors on it and the names of its joints.

    A body with two joints is a binary link (draw it as a bar), with three or
    more a ternary or larger link (draw it as a polygon through its joints).
    ``points`` are the linkage's named points on the body, joints or not (the
    Jansen leg's foot H is a corner of its lower triangle but no joint).
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    name: str
    vectors: tuple[str, ...]
    joints: tuple[str, ...]
    points: tuple[str, ...] = ()

    @property
    def is_ground(self) -> bool:
        return self.name == GROUND


@dataclass(frozen=True)
class Mechanism:
    """A linkage's bodies and joints, and its Gruebler/Kutzbach mobility."""

    _repr_html_ = record_html  # a notebook shows the fields as a table

    bodies: tuple[Body, ...]
    joints: tuple[Joint, ...]
    higher_pairs: tuple[tuple[str, str], ...] = ()

    @property
    def one_freedom_joints(self) -> int:
        """j1: revolute joints (a pin joining k bodies counted k - 1 times) plus prismatic joints."""
        return sum(joint.count for joint in self.joints)

    @property
    def mobility(self) -> int:
        """Gruebler/Kutzbach: ``3 (n - 1) - 2 j1 - j2``, j2 the :attr:`higher_pairs` (gears, cams)."""
        return 3 * (len(self.bodies) - 1) - 2 * self.one_freedom_joints - len(self.higher_pairs)

    def body(self, name: str) -> Body:
        for body in self.bodies:
            if body.name == name:
                return body
        raise ValueError(f"no body {name!r}; the bodies are {', '.join(b.name for b in self.bodies)}")

    def joint(self, name: str) -> Joint:
        for joint in self.joints:
            if joint.name == name:
                return joint
        raise ValueError(f"no joint {name!r}; the joints are {', '.join(j.name for j in self.joints)}")


def drawn_points(linkage: Linkage, mechanism: Mechanism) -> dict[str, VectorSum]:
    """Every place a drawing marks, as a sum of vectors from the origin, in this order: each joint that has
    a position, right after it a slider's guide start (``"<joint> guide"``), then each named point (an
    empty sum at the origin).  What :class:`symlink.numeric.poses.Geometry` places and the JavaScript
    printer's drawing solver computes (:func:`symlink.codegen.javascript.javascript_geometry`).

    >>> from symlink.mechanism.catalog import slider_crank
    >>> list(drawn_points(slider_crank(), mechanism(slider_crank())))
    ['A', 'B', 'C', 'AS', 'AS guide']
    """
    sums: dict[str, VectorSum] = {}
    for joint in mechanism.joints:
        if joint.position is not None:
            sums[joint.name] = joint.position
        if joint.kind == PRISMATIC and joint.guide_start is not None:
            sums[f"{joint.name} guide"] = joint.guide_start
    for name, point in linkage.points.items():
        sums[name] = VectorSum(()) if point is None else point.as_sum()
    return sums


class _Nodes:
    """Union-find over the ends of the vectors: ``(vector, "tail")`` and ``(vector, "head")``."""

    def __init__(self) -> None:
        self.parent: dict[object, object] = {}

    def find(self, item: object) -> object:
        self.parent.setdefault(item, item)
        while self.parent[item] != item:
            self.parent[item] = self.parent[self.parent[item]]
            item = self.parent[item]
        return item

    def join(self, first: object, second: object) -> None:
        first, second = self.find(first), self.find(second)
        if first != second:
            self.parent[second] = first


def _start(sign: int, vector: Vector) -> tuple:
    return (vector, "tail") if sign > 0 else (vector, "head")


def _end(sign: int, vector: Vector) -> tuple:
    return (vector, "head") if sign > 0 else (vector, "tail")


def _moving_part(angle: sp.Expr, coordinates: set[sp.Symbol]) -> sp.Expr:
    """The time-varying part of an angle: zero for a fixed direction, ``phi`` for ``phi + alpha``."""
    return sp.Add(*(term for term in sp.Add.make_args(sp.expand(angle)) if term.free_symbols & coordinates))


def _vector_name(vector: Vector) -> str:
    return vector.name or str(vector)


def _first_shared_pair(order: Sequence, at_node: Mapping, refused: set[frozenset]) -> tuple | None:
    """The first two nodes (in ``order``, by the first, then the second) that join two bodies or more between
    them and are not ``refused``; ``None`` where no two do.  Nodes are grouped by each pair of bodies that meet
    there, so that only nodes sharing a pair are compared (not every node with every other).
    """
    place = {node: k for k, node in enumerate(order)}
    sharing: dict[frozenset, list] = {}
    for node in order:
        bodies = list(dict.fromkeys(at_node[node]))
        for k, first in enumerate(bodies):
            for second in bodies[k + 1:]:
                sharing.setdefault(frozenset((first, second)), []).append(node)
    best = None
    for group in sharing.values():
        for k, first in enumerate(group):
            for second in group[k + 1:]:
                if frozenset((first, second)) not in refused:
                    key = (place[first], place[second])
                    if best is None or key < best[0]:
                        best = (key, (first, second))
                    break  # later seconds of this first come after it
    return None if best is None else best[1]


def mechanism(linkage: Linkage, bodies: Mapping[str, Sequence[str]] | None = None,
              higher_pairs: Sequence[tuple[str, str]] = ()) -> Mechanism:
    """The bodies and joints of ``linkage``, derived from its loops and points (see the module docstring).

    ``bodies`` maps a body name to names of vectors that lie on it, overriding
    where they would be placed from their directions alone.  ``higher_pairs``
    names pairs of bodies in two-freedom contact (a gear pair, a cam and its
    follower), which vector loops cannot show; each counts once in j2.

    >>> from symlink.mechanism.catalog import slider_crank
    >>> found = mechanism(slider_crank())
    >>> [(body.name, body.joints) for body in found.bodies]
    [('ground', ('A', 'AS')), ('crank', ('A', 'B')), ('slider', ('C', 'AS')), ('conrod', ('B', 'C'))]
    >>> found.joint("AS").kind, str(found.joint("AS").position), found.mobility
    ('prismatic', 'AS', 1)
    """
    coordinates = set(linkage.coordinates)
    nodes, vectors, ends = _segments(linkage)
    names = [_vector_name(v) for v in vectors]
    repeated = sorted(n for n, k in Counter(names).items() if k > 1)
    if repeated:
        raise ValueError(f"{linkage.name}: two different vectors are both named {repeated[0]!r}; "
                         "give each vector its own name (or use one Vector object for one segment)")
    travels = [v for v in vectors if v.length.free_symbols & coordinates]
    body_of, block_of = _bodies_of_vectors(linkage, vectors, travels, nodes)
    by_name = dict(zip(names, vectors))
    for body, listed in (bodies or {}).items():
        if not isinstance(body, str) or not body:
            raise ValueError(f"body names must be non-empty strings, got {body!r}")
        for name in listed:
            if name not in by_name:
                raise ValueError(f"body {body!r}: {linkage.name} has no vector {name!r}; "
                                 f"its vectors are {', '.join(names)}")
            if by_name[name] in block_of:
                raise ValueError(f"body {body!r}: {name} is a slider travel, the joint between its guide and "
                                 "its block; list the block's other vectors instead")
            body_of[by_name[name]] = body

    # Which bodies meet at each node.  Two bodies that turn relative to each other can share one
    # pin only: where two nodes join the same two bodies (a pivot that two loops reach by
    # different vectors), they are one point, and are merged.
    origin_on_ground = any(p is None for p in linkage.points.values())
    refused: set[frozenset] = set()
    while True:
        at_node, order = _bodies_at_nodes(vectors, nodes, body_of, block_of, origin_on_ground)
        first_pair = _first_shared_pair(order, at_node, refused)
        if first_pair is None:
            break
        first, second = first_pair
        # Points the vectors place apart stay apart (then the bodies were misread: say them explicitly).
        placed = _positions(linkage, vectors, nodes)
        if first in placed and second in placed and not _coincide(linkage, vectors, placed[first], placed[second]):
            refused.add(frozenset((first, second)))
            continue
        nodes.join(first, second)
    point_names: dict[object, str] = {}  # names of nodes: the linkage's points
    for name, point in linkage.points.items():
        node = nodes.find(_ORIGIN if point is None else ends[name])
        point_names.setdefault(node, name)

    positions = _positions(linkage, vectors, nodes)
    for name, point in linkage.points.items():  # a named point keeps the sum it was defined by
        node = nodes.find(_ORIGIN if point is None else ends[name])
        positions[node] = VectorSum(()) if point is None else point.as_sum()
    joints: list[Joint] = []
    joint_names: dict[object, str] = {}
    used = set(linkage.points)
    for node in order:
        if len(at_node[node]) < 2:
            continue
        name = point_names.get(node) or _fresh("J", used)
        used.add(name)
        joint_names[node] = name
        joints.append(Joint(name, REVOLUTE, _ground_first(at_node[node]), positions.get(node)))
    slider_joints: dict[Vector, str] = {}
    for travel in travels:
        name = travel.name if travel.name and travel.name not in used else _fresh("P", used)
        used.add(name)
        slider_joints[travel] = name
        head, tail = nodes.find(_end(1, travel)), nodes.find(_start(1, travel))
        joints.append(Joint(name, PRISMATIC, (body_of[travel], block_of[travel]), positions.get(head),
                            positions.get(tail), travel.angle))

    body_names = _ground_first([GROUND] + list(dict.fromkeys(body_of.values())) + list(block_of.values()))
    # Each body's vectors, joints and slider joints, gathered in one pass over each (not a pass a body).
    vectors_of: dict[str, list[Vector]] = {}
    for v in vectors:
        if v not in block_of:
            vectors_of.setdefault(body_of[v], []).append(v)
    joints_of: dict[str, list[str]] = {}
    for n in order:
        if n in joint_names:
            for body in dict.fromkeys(at_node[n]):
                joints_of.setdefault(body, []).append(joint_names[n])
    for t in travels:
        for body in dict.fromkeys((body_of[t], block_of[t])):
            joints_of.setdefault(body, []).append(slider_joints[t])
    place = {n: k for k, n in enumerate(order)}
    named = {n: k for k, n in enumerate(point_names)}
    result = []
    for body in dict.fromkeys(body_names):
        on_body = vectors_of.get(body, [])
        members = joints_of.get(body, [])
        corners = {nodes.find(end) for v in on_body for end in (_start(1, v), _end(1, v))}
        if body == GROUND and any(p is None for p in linkage.points.values()):
            corners.add(nodes.find(_ORIGIN))
        # The points at its corners: first in the order of the nodes, then the others in the points' order.
        points = [point_names[n] for n in sorted((n for n in corners if n in named and n in place), key=place.__getitem__)]
        points += [point_names[n] for n in sorted((n for n in corners if n in named and n not in place),
                                                  key=named.__getitem__)]
        if body == GROUND or on_body or members:
            result.append(Body(body, tuple(_vector_name(v) for v in on_body), tuple(members), tuple(points)))
    known = [body.name for body in result]
    pairs = []
    for pair in higher_pairs:
        if len(pair) != 2 or any(name not in known for name in pair) or pair[0] == pair[1]:
            raise ValueError(f"higher pair {pair!r} must name two different bodies of {linkage.name} "
                             f"({', '.join(known)})")
        pairs.append((pair[0], pair[1]))
    return Mechanism(tuple(result), tuple(joints), tuple(pairs))


def _segments(linkage: Linkage) -> tuple[_Nodes, list[Vector], dict[str, tuple]]:
    """Every vector once (points' vectors first, then the loops'), which of their ends are one node, and
    the vector end at which each named point (but the origin) lies.

    A run of fixed vectors in a loop or a point is walked in the order that the points and loops before
    chain them, whatever order it is written in (:func:`_fixed_runs_in_walking_order`).
    """
    coordinates = set(linkage.coordinates)
    nodes = _Nodes()
    vectors: list[Vector] = []
    ends: dict[str, tuple] = {}
    chains: list[tuple[str, tuple[tuple[int, Vector], ...], bool]] = [
        (name, point.as_sum().terms, False) for name, point in linkage.points.items() if point is not None]
    chains += [("", loop.terms, True) for loop in linkage.loops]
    seen: set[Vector] = set()
    for name, terms, closed in chains:
        for _, vector in terms:
            if vector not in seen:
                seen.add(vector)
                vectors.append(vector)
        terms = _fixed_runs_in_walking_order(terms, nodes, coordinates, closed)
        for before, after in zip(terms, terms[1:] + (terms[:1] if closed else ())):
            nodes.join(_end(*before), _start(*after))
        if not closed:
            nodes.join(_ORIGIN, _start(*terms[0]))
            ends[name] = _end(*terms[-1])
    return nodes, vectors, ends


#: Longest run of fixed vectors whose walking order is searched (its orders are tried one by one).
_LONGEST_RUN = 6


def _fixed(vector: Vector, coordinates: set[sp.Symbol]) -> bool:
    return not ((vector.length.free_symbols | vector.angle.free_symbols) & coordinates)


def _fixed_runs_in_walking_order(terms: tuple[tuple[int, Vector], ...], nodes: _Nodes,
                                 coordinates: set[sp.Symbol], closed: bool = True) -> tuple[tuple[int, Vector], ...]:
    """A chain's terms with each run of consecutive fixed vectors in the order the chains known so far walk them.

    Fixed vectors add up to one offset whatever their order, so a loop may subtract a point's sum
    whole (``OP = OPx + OPy`` and the loop ``OM + MQ - PQ - OP``, whose terms ``- OPx - OPy`` walk
    from P through the wrong corner), and two points may sum one offset in two orders: of the
    orders of a run, the one whose corners the chains before already join most is walked (the
    written one on a tie, or where nothing joins them).  ``closed``: a loop, whose last term
    runs into its first.
    """
    moving = [k for k, (_, vector) in enumerate(terms) if not _fixed(vector, coordinates)]
    if closed and not moving:
        return terms
    count = len(terms)
    first = moving[0] if closed else 0
    rotated = terms[first:] + terms[:first]  # a loop starts with a moving term: no run wraps around
    result: list[tuple[int, Vector]] = []
    run: list[tuple[int, Vector]] = []
    for term in rotated + ((0, None),):  # a sentinel closes the last run
        if term[1] is not None and _fixed(term[1], coordinates):
            run.append(term)
            continue
        if 1 < len(run) <= _LONGEST_RUN:
            orders = [list(order) for order in itertools.permutations(run)]
            corners = [sum(nodes.find(_end(*before)) == nodes.find(_start(*after))
                           for before, after in zip(order, order[1:])) for order in orders]
            run = orders[corners.index(max(corners))]  # the first of the best: the written order on a tie
        result += run
        run = []
        if term[1] is not None:
            result.append(term)
    start = count - first  # rotate back, so that the loop starts where it was written to
    return tuple(result[start:] + result[:start])


def _bodies_of_vectors(linkage: Linkage, vectors: Sequence[Vector], travels: Sequence[Vector],
                       nodes: _Nodes) -> tuple[dict[Vector, str], dict[Vector, str]]:
    """The body of each vector (a travel's: its guide), and the block at the head of each travel."""
    coordinates = set(linkage.coordinates)
    role_of = _roles_by_coordinate(linkage)
    body_of = {vector: _body_name(role_of, _moving_part(vector.angle, coordinates)) for vector in vectors}
    block_of = {travel: _block_name(role_of, travel, coordinates) for travel in travels}
    block_nodes: dict[Vector, set] = {}
    for travel in travels:  # fixed vectors along the guide that carry on from the head ride on the block
        guide = _moving_part(travel.angle, coordinates)
        frontier = [nodes.find(_end(1, travel))]
        seen = block_nodes[travel] = set(frontier)
        while frontier:
            node = frontier.pop()
            for vector in vectors:
                if vector in block_of or _moving_part(vector.angle, coordinates) != guide:
                    continue
                ends = {nodes.find(_start(1, vector)), nodes.find(_end(1, vector))}
                if node in ends and body_of[vector] != block_of[travel]:
                    body_of[vector] = block_of[travel]
                    for other in ends - seen:
                        seen.add(other)
                        frontier.append(other)
    for travel in travels:  # a guide on a block (a Scotch yoke's slot) moves with that block
        tail = nodes.find(_start(1, travel))
        for other in travels:
            if (other is not travel and tail in block_nodes[other]
                    and _moving_part(other.angle, coordinates) == _moving_part(travel.angle, coordinates)):
                body_of[travel] = block_of[other]
    return body_of, block_of


def _bodies_at_nodes(vectors, nodes: _Nodes, body_of, block_of, origin_on_ground: bool):
    """The bodies that meet at each node, and the nodes in order of first appearance."""
    at_node: dict[object, list[str]] = {}
    order: list[object] = []

    def touch(node: object, body: str) -> None:
        node = nodes.find(node)
        if node not in at_node:
            at_node[node] = []
            order.append(node)
        if body not in at_node[node]:
            at_node[node].append(body)

    if origin_on_ground:
        touch(_ORIGIN, GROUND)
    for vector in vectors:
        touch(_start(1, vector), body_of[vector])
        touch(_end(1, vector), block_of.get(vector, body_of[vector]))
    return at_node, order


def _ground_first(names: Sequence[str]) -> tuple[str, ...]:
    unique = list(dict.fromkeys(names))
    return tuple(([GROUND] if GROUND in unique else []) + [n for n in unique if n != GROUND])


def _fresh(prefix: str, used: set[str]) -> str:
    number = 1
    while f"{prefix}{number}" in used:
        number += 1
    return f"{prefix}{number}"


def _roles_by_coordinate(linkage: Linkage) -> dict[sp.Expr, str]:
    """The first role of each coordinate (a look-up a vector, not a pass over every role)."""
    found: dict[sp.Expr, str] = {}
    for role, coordinate in linkage.roles.items():
        found.setdefault(coordinate, role)
    return found


def _body_name(role_of: Mapping[sp.Expr, str], moving: sp.Expr) -> str:
    """A body's name: ``ground``, else the role of the coordinate it turns with, else that coordinate."""
    if moving == 0:
        return GROUND
    return role_of.get(moving, str(moving))


def _block_name(role_of: Mapping[sp.Expr, str], travel: Vector, coordinates: set[sp.Symbol]) -> str:
    """A slider block's name: the role of its travel coordinate, else ``block_<travel coordinate>``."""
    moving = _moving_part(travel.length, coordinates)
    return role_of.get(moving, f"block_{moving}")


def _positions(linkage: Linkage, vectors: Sequence[Vector], nodes: _Nodes) -> dict[object, VectorSum]:
    """Every node reachable from the origin, as a sum of vectors from it (walked breadth first).

    Two walks to one node must agree up to whole loops (which add up to zero);
    if they do not, a loop's or a point's vectors were not written in walking
    order, and the joints read off them would be wrong: ``ValueError``.
    """
    positions: dict[object, VectorSum] = {nodes.find(_ORIGIN): VectorSum(())}
    leaving: dict[object, list[tuple[int, Vector, object]]] = {}  # each node's vectors, in the vectors' order
    for vector in vectors:
        for sign in (1, -1):
            start = nodes.find(_start(sign, vector))
            leaving.setdefault(start, []).append((sign, vector, nodes.find(_end(sign, vector))))
    loops = _LoopSpace(linkage)
    frontier = [nodes.find(_ORIGIN)]
    while frontier:
        following = []
        for node in frontier:
            for sign, vector, end in leaving.get(node, ()):
                reached = positions[node] + VectorSum(((sign, vector),))
                if end not in positions:
                    positions[end] = reached
                    following.append(end)
                    continue
                if not loops.holds(reached, positions[end]):
                    raise ValueError(
                        f"{linkage.name}: {_described(reached)} and {_described(positions[end])} end at one "
                        "joint but are not the same point; write each loop's and each point's vectors in "
                        "walking order (every vector starting where the one before it ends)")
        frontier = following
    return positions


def _described(position: VectorSum) -> str:
    return str(position) if position.terms else "the origin"


def same_point(linkage: Linkage, first: VectorSum, second: VectorSum) -> bool:
    """Whether two sums of ``linkage``'s vectors reach one point in every pose: they differ by whole loops.

    A pin may be written through either side of its loop (the slider-crank's C as ``AB + BC`` or
    as the travel ``AC``); both are that pin.

    >>> from symlink.mechanism.catalog import fourbar
    >>> four = fourbar()
    >>> loop = four.loops[0].terms      # AD + DC - BC - AB
    >>> AB, BC, AD, DC = (dict((v.name, v) for _, v in loop)[n] for n in ("AB", "BC", "AD", "DC"))
    >>> same_point(four, AB + BC, AD + DC), same_point(four, AB + BC, AD.as_sum())
    (True, False)
    """
    vectors = list(dict.fromkeys(v for chain in [first.terms, second.terms] + [loop.terms for loop in linkage.loops]
                                 for _, v in chain))
    return _coincide(linkage, vectors, first, second)


def _coincide(linkage: Linkage, vectors: Sequence[Vector], first: VectorSum, second: VectorSum) -> bool:
    """Whether two walks from the origin end at one point for every pose: they differ by whole loops."""
    return _LoopSpace(linkage).holds(first, second)


class _LoopSpace:
    """The sums of whole loops (integer combinations of the loops' vectors, as rows over the vectors), reduced once
    to rows in echelon form with exact fractions, so that each question "do these two walks differ by whole loops"
    costs a reduction of one sparse row, not the rank of a matrix as large as the linkage."""

    def __init__(self, linkage: Linkage) -> None:
        self.basis: dict[int, dict[int, Fraction]] = {}  # pivot column -> row (pivot entry 1)
        self.column: dict[Vector, int] = {}
        for loop in linkage.loops:
            self._add(self._row(loop.terms))

    def _row(self, terms) -> dict[int, Fraction]:
        row: dict[int, Fraction] = {}
        for sign, vector in terms:
            k = self.column.setdefault(vector, len(self.column))
            row[k] = row.get(k, Fraction(0)) + sign
        return {k: v for k, v in row.items() if v}

    def _reduced(self, row: dict[int, Fraction]) -> dict[int, Fraction]:
        row = dict(row)
        while row:
            pivot = min(row)
            if pivot not in self.basis:
                return row
            factor = row[pivot]
            for k, v in self.basis[pivot].items():
                value = row.get(k, Fraction(0)) - factor * v
                if value:
                    row[k] = value
                else:
                    row.pop(k, None)
        return row

    def _add(self, row: dict[int, Fraction]) -> None:
        row = self._reduced(row)
        if row:
            pivot = min(row)
            self.basis[pivot] = {k: v / row[pivot] for k, v in row.items()}

    def holds(self, first: VectorSum, second: VectorSum) -> bool:
        """Whether ``first`` and ``second`` differ by whole loops (or not at all)."""
        difference = self._row(tuple(first.terms) + tuple((-sign, vector) for sign, vector in second.terms))
        return not self._reduced(difference)
