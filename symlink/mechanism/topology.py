"""The structure of a planar linkage from its links and joints: checks, loops, mobility, over-constraint.

A :class:`Chain` is what a designer's sketch says before any dimension: which
link holds which joint, which joints are sliders and on which link each one
slides, and which link is the ground.  From that alone follow

* the **loops**: the simple cycles of the graph whose nodes are the links and
  the joints (a link is joined to each joint it holds), each a walk
  ``link, joint, link, joint, ...`` back to where it started
  (:meth:`Chain.cycles`);
* the **mobility** by Gruebler and Kutzbach (:meth:`Chain.mobility`): a pin
  joining k links is k - 1 revolute joints, and a slider joint (a pin in a
  slot: the joint's pin turns in a block that slides along a line of its
  guide link) is a hidden block with one prismatic joint on the guide and one
  pin a link it joins;
* **where** a chain is over-constrained (:meth:`Chain.overconstrained`): the
  smallest group of links whose own mobility is negative (two links sharing
  two pins, four links closing with five joints ...).

Numbers and names only, no SymPy: :mod:`symlink.mechanism.joints` turns a chain with
joint coordinates into a :class:`~symlink.symbolic.linkage.Linkage`, and
:mod:`symlink.mechanism.atlas` enumerates chains.

>>> four = Chain({"ground": ("A", "D"), "crank": ("A", "B"), "coupler": ("B", "C"), "rocker": ("C", "D")})
>>> four.mobility().dof, len(four.cycles())
(1, 1)
>>> Chain({"ground": ("A", "C"), "one": ("A", "B"), "two": ("B", "C")}).mobility().dof
0
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import combinations
from typing import Callable, Iterable, Iterator, Mapping, Sequence

from .mobility import Mobility
from ..common.display import record_html
from ..common.names import PLAIN_NAME

__all__ = ["Chain", "Traversal", "Cycle", "GROUND", "independent"]

GROUND = "ground"

#: Largest chain whose groups of links are searched one by one for over-constraint (2^n groups).
_SUBSET_SEARCH_LIMIT = 14


@dataclass(frozen=True)
class Traversal:
    """One link of a loop, walked from the joint ``entry`` to the joint ``exit``."""

    link: str
    entry: str
    exit: str


@dataclass(frozen=True)
class Cycle:
    """A loop of the chain: the links walked in order, each from the joint it shares with the one before."""

    _repr_html_ = record_html  # a notebook shows the fields as a table

    traversals: tuple[Traversal, ...]

    @property
    def joints(self) -> tuple[str, ...]:
        """The joints in walking order, from the first (each the entry of a traversal)."""
        return tuple(t.entry for t in self.traversals)

    @property
    def links(self) -> tuple[str, ...]:
        return tuple(t.link for t in self.traversals)

    @property
    def name(self) -> str:
        """The joints in walking order (``ABCD``), joined by ``_`` where a joint name is longer than a letter."""
        joints = self.joints
        return "".join(joints) if all(len(j) == 1 for j in joints) else "_".join(joints)


@dataclass(frozen=True)
class Chain:
    """Links (each a set of joints; the ``ground`` one of them) and which joints are sliders on which link.

    ``links`` maps a link name to the joints it holds.  ``sliders`` maps a slider
    joint to its guide: the joint's pin slides along a line of the guide link
    (which lists the joint too) and turns in the other links that hold it.
    A slider in ``translating`` is a prismatic joint proper: the one other link
    that holds it slides on the guide without turning on it (a block; Pyslvs's
    ``P`` joint).  Every other joint is a revolute pin; a "joint" that one link alone holds is a
    point of that link (a coupler point, a foot), no joint.  ``ValueError`` names
    the problem with a chain that is no linkage (a link with fewer than two
    joints, a slider whose guide does not hold it, ...).
    """

    links: Mapping[str, Sequence[str]]
    sliders: Mapping[str, str] = field(default_factory=dict)
    ground: str = GROUND
    translating: frozenset[str] = frozenset()

    def __post_init__(self) -> None:
        links = {}
        if not isinstance(self.links, Mapping) or not self.links:
            raise ValueError("links: give a mapping of link names to the joints each link holds")
        for name, joints in self.links.items():
            _check_name(name, "link")
            if isinstance(joints, str) or not isinstance(joints, Iterable):
                raise ValueError(f"link {name!r}: give its joints as a list of names, not {joints!r}")
            joints = tuple(joints)
            for joint in joints:
                _check_name(joint, f"link {name!r}: joint")
            if len(set(joints)) != len(joints):
                raise ValueError(f"link {name!r} lists a joint twice: {', '.join(joints)}")
            if len(joints) < 2:
                raise ValueError(f"link {name!r} holds {len(joints)} joint{'s' if len(joints) != 1 else ''}; "
                                 "a link joins at least two joints")
            links[name] = joints
        object.__setattr__(self, "links", links)
        object.__setattr__(self, "sliders", dict(self.sliders))
        if self.ground not in links:
            raise ValueError(f"no ground link {self.ground!r} among the links ({', '.join(links)})")
        for joint, guide in self.sliders.items():
            if guide not in links:
                raise ValueError(f"slider {joint!r}: no link {guide!r} (its guide; the links are {', '.join(links)})")
            if joint not in self.joints:
                raise ValueError(f"slider {joint!r} is on no link")
            if len(self.links_of(joint)) < 2:
                raise ValueError(f"slider {joint!r} is on link {guide!r} only; it joins its guide to another link")
            if joint not in links[guide]:
                raise ValueError(f"slider {joint!r}: its guide {guide!r} does not list it among its joints")
        object.__setattr__(self, "translating", frozenset(self.translating))
        blocks: dict[str, str] = {}
        for joint in self.translating:
            if joint not in self.sliders:
                raise ValueError(f"prismatic joint {joint!r} names no guide")
            others = [link for link in self.links_of(joint) if link != self.sliders[joint]]
            if len(others) != 1:
                raise ValueError(f"prismatic joint {joint!r} joins its guide to {len(others)} links; "
                                 "a block that slides without turning is one link")
            if others[0] in blocks:
                raise ValueError(f"link {others[0]!r} slides without turning on two guides "
                                 f"({blocks[others[0]]} and {joint})")
            blocks[others[0]] = joint
        for name in links:
            if not self.rigid_joints(name):
                raise ValueError(f"link {name!r} holds only sliders that slide on it: "
                                 "a guide needs a pin (or a joint that does not slide on it) to place its line")
        self._check_connected()

    # --- the graph ----------------------------------------------------------
    @property
    def joints(self) -> tuple[str, ...]:
        """Every joint, in the order the links first list them."""
        return tuple(self._holders())

    def links_of(self, joint: str) -> tuple[str, ...]:
        return self._holders().get(joint, ())

    def _holders(self) -> dict[str, tuple[str, ...]]:
        """Each joint (in the order the links first list them) and the links that hold it, made once."""
        found = self.__dict__.get("_holders_made")
        if found is None:
            lists: dict[str, list[str]] = {}
            for name, joints in self.links.items():
                for joint in joints:
                    lists.setdefault(joint, []).append(name)
            found = {joint: tuple(names) for joint, names in lists.items()}
            object.__setattr__(self, "_holders_made", found)
        return found

    def block_guide(self, link: str) -> str | None:
        """The guide that ``link`` slides on without turning (through a translating joint), if any."""
        return next((self.sliders[j] for j in self.translating if j in self.links[link] and self.sliders[j] != link),
                    None)

    def rigid_joints(self, link: str) -> tuple[str, ...]:
        """The joints fixed on ``link`` (all but the sliders it guides), in its order; made once a link (the
        ground of n pivots is asked for its first joint once a side walked)."""
        made = self.__dict__.setdefault("_rigid_made", {})
        found = made.get(link)
        if found is None:
            found = made[link] = tuple(j for j in self.links[link] if self.sliders.get(j) != link)
        return found

    def _check_connected(self) -> None:
        reached, stack = {self.ground}, [self.ground]
        while stack:
            link = stack.pop()
            for joint in self.links[link]:
                for other in self.links_of(joint):
                    if other not in reached:
                        reached.add(other)
                        stack.append(other)
        apart = [name for name in self.links if name not in reached]
        if apart:
            raise ValueError(f"links {', '.join(apart)} are not connected to the ground {self.ground!r}")

    # --- mobility -----------------------------------------------------------
    def mobility(self) -> Mobility:
        """Gruebler/Kutzbach: a pin joining k links is k - 1 revolute joints; a slider is a hidden block.

        The block of a slider joint slides on the guide (one prismatic joint) and is
        pinned to the k other links holding the joint (k revolute joints); a
        translating joint is one prismatic joint between its guide and its block.
        """
        links, revolute, prismatic = len(self.links), 0, 0
        for joint in self.joints:
            holders = self.links_of(joint)
            if joint in self.translating:
                prismatic += 1
            elif joint in self.sliders:
                links, prismatic, revolute = links + 1, prismatic + 1, revolute + len(holders) - 1
            else:
                revolute += len(holders) - 1
        return Mobility(links, revolute, prismatic)

    def driven_links(self, driver: "str | tuple[str, str]") -> tuple[str, ...]:
        """The links a driver acts between: a joint's links, or (joint, link) at a ground pin the ground and that
        link."""
        if isinstance(driver, str) or self.ground not in self.links_of(driver[0]):
            return self.links_of(driver if isinstance(driver, str) else driver[0])
        return (self.ground, driver[1])

    def local_mobility(self, group: Iterable[str], drivers: "Sequence[str | tuple[str, str]]" = ()) -> int:
        """The mobility of the links ``group`` on their own (the first one held still), less their drivers.

        Counts only the joints between links of the group: a pin shared by k of them is
        k - 1 revolute joints (2 constraints each); a slider whose guide and k other
        holders are in the group is a pin in a slot (1 constraint) and k - 1 pins.
        """
        group = set(group)
        constraints = 0
        for joint in self.joints:
            inside = [link for link in self.links_of(joint) if link in group]
            guide = self.sliders.get(joint)
            if joint in self.translating:
                constraints += 2 if len(inside) == 2 else 0
            elif guide in inside:
                others = len(inside) - 1
                constraints += (1 + 2 * (others - 1)) if others else 0
            elif inside:
                constraints += 2 * (len(inside) - 1)
        driven = sum(1 for driver in drivers if all(link in group for link in self.driven_links(driver)))
        return 3 * (len(group) - 1) - constraints - driven

    def overconstrained(self, drivers: "Sequence[str | tuple[str, str]]" = ()) -> tuple[str, ...] | None:
        """The smallest group of links that cannot move as its joints (and drivers) say, or None.

        A group whose own mobility (:meth:`local_mobility`) is negative is over-constrained:
        its joints fit only for special dimensions.  Groups are searched smallest first
        (chains of up to 14 links; a larger chain is checked as a whole only).
        """
        names = list(self.links)
        if len(names) > _SUBSET_SEARCH_LIMIT:
            return tuple(names) if self.local_mobility(names, drivers) < 0 else None
        for size in range(2, len(names) + 1):
            for group in combinations(names, size):
                if self.local_mobility(group, drivers) < 0 and self._joined(group):
                    return group
        return None

    def _joined(self, group: Sequence[str]) -> bool:
        """Whether the links of ``group`` hang together through joints between them."""
        members = set(group)
        start = next(iter(members))
        reached, stack = {start}, [start]
        while stack:
            link = stack.pop()
            for joint in self.links[link]:
                for other in self.links_of(joint):
                    if other in members and other not in reached:
                        reached.add(other)
                        stack.append(other)
        return reached == members

    # --- loops --------------------------------------------------------------
    def cycles(self, longest: int | None = None) -> tuple[Cycle, ...]:
        """Every simple loop of the chain, shortest first (ties in a fixed order), each once.

        A loop visits a link and a joint at most once; it is rotated to start at
        its first joint by name and walked towards the neighbour whose name comes first.
        ``longest`` keeps the loops of at most that many joints: the same loops, in the same
        order, as the first ones of the full list (a chain of n dyads has of the order of n^2
        loops, and searching them all takes a time that grows faster than any power of n).

        Parameters
        ----------
        longest : int, optional
            The most joints a loop may have (default: no limit).

        Returns
        -------
        tuple of Cycle
            The loops, by number of joints, then by their joints' and links' order.

        Examples
        --------
        >>> watt = Chain({"ground": ("A", "D", "G"), "crank": ("A", "B"), "coupler": ("B", "C"),
        ...               "rocker": ("D", "C", "E"), "link5": ("E", "F"), "link6": ("F", "G")})
        >>> [c.name for c in watt.cycles()], [c.name for c in watt.cycles(longest=4)]
        (['ABCD', 'DEFG', 'ABCEFG'], ['ABCD', 'DEFG'])
        """
        joint_order = {j: k for k, j in enumerate(self.joints)}
        link_order = {name: k for k, name in enumerate(self.links)}
        nodes = [("J", j) for j in self.joints] + [("L", name) for name in self.links]
        index = {node: k for k, node in enumerate(nodes)}
        neighbours: dict[tuple[str, str], list[tuple[str, str]]] = {node: [] for node in nodes}
        for name, joints in self.links.items():
            for joint in joints:
                neighbours[("L", name)].append(("J", joint))
                neighbours[("J", joint)].append(("L", name))
        deepest = len(nodes) if longest is None else 2 * longest  # a loop of k joints walks 2 k nodes
        # With a longest loop, a walk goes on only to nodes from which it can still come back in time: without
        # that, every walk that crosses a link of n joints (the ground of n dyads) tries all n, and the search
        # takes a time n^2.  Distances back are computed around each start only (:class:`_Distances`).
        distances = _Distances(neighbours, deepest) if longest is not None else None
        found: dict[tuple, Cycle] = {}
        for start in nodes[:len(self.joints)]:
            lowest = index[start]
            back = distances.to(start) if distances is not None else None
            # A depth-first walk with a stack of its own (a chain of thousands of links is no recursion limit).
            path = [start]
            on_path = {start}
            pending = [iter(neighbours[start])]
            while pending:
                nxt = next(pending[-1], None)
                if nxt is None:
                    pending.pop()
                    on_path.discard(path.pop())
                elif nxt == start and len(path) >= 4:
                    self._record(path, found, joint_order)
                elif back is not None and len(path) + back.distance(nxt) > deepest:
                    continue  # the loop would have more than ``longest`` joints
                elif nxt not in on_path and index[nxt] > lowest and len(path) < deepest:
                    path.append(nxt)
                    on_path.add(nxt)
                    # From a hub, only the neighbours that can still come back without it (not all n of them).
                    hub = back is not None and distances is not None and nxt in distances.hub_set
                    pending.append(iter(back.around(nxt, deepest - len(path)) if hub and back is not None
                                        else neighbours[nxt]))
        ordered = sorted(found.values(), key=lambda c: (len(c.traversals), [joint_order[j] for j in c.joints],
                                                        [link_order[name] for name in c.links]))
        return tuple(ordered)

    def looped_links(self) -> frozenset[str]:
        """The links that lie on some loop, found in a time linear in the chain's size (no loop is listed).

        A link lies on a loop where one of its joints' links-to-joint edges is no bridge of the link-joint
        graph (bridges by Tarjan's depth-first search, with a stack of its own).

        Returns
        -------
        frozenset of str
            The links on a loop; the others hang on the chain by a single path (they swing freely).

        Examples
        --------
        >>> sorted(Chain({"ground": ("A", "D", "E"), "crank": ("A", "B"), "coupler": ("B", "C"),
        ...               "rocker": ("D", "C"), "arm": ("E", "F")}).looped_links())
        ['coupler', 'crank', 'ground', 'rocker']
        """
        neighbours: dict[tuple[str, str], list[tuple[str, str]]] = {}
        for name, joints in self.links.items():
            for joint in joints:
                neighbours.setdefault(("L", name), []).append(("J", joint))
                neighbours.setdefault(("J", joint), []).append(("L", name))
        found: dict[tuple[str, str], int] = {}
        low: dict[tuple[str, str], int] = {}
        bridges: set[frozenset] = set()
        for root in neighbours:
            if root in found:
                continue
            found[root] = low[root] = len(found)
            stack: list[tuple[tuple[str, str], tuple[str, str] | None, Iterator[tuple[str, str]]]] = [
                (root, None, iter(neighbours[root]))]
            while stack:
                node, parent, rest = stack[-1]
                nxt = next(rest, None)
                if nxt is None:
                    stack.pop()
                    if parent is not None:
                        low[parent] = min(low[parent], low[node])
                        if low[node] > found[parent]:
                            bridges.add(frozenset((parent, node)))
                elif nxt == parent:
                    continue
                elif nxt in found:
                    low[node] = min(low[node], found[nxt])
                else:
                    found[nxt] = low[nxt] = len(found)
                    stack.append((nxt, node, iter(neighbours[nxt])))
        return frozenset(name for name, joints in self.links.items()
                         if any(frozenset((("L", name), ("J", joint))) not in bridges for joint in joints))

    @staticmethod
    def _record(path: list[tuple[str, str]], found: dict, joint_order: Mapping[str, int]) -> None:
        """Store the closed walk ``path`` (joint, link, joint, link, ...) once: from its first joint by name,
        towards the neighbour that comes first by name."""
        joints = [name for kind, name in path if kind == "J"]
        links = [name for kind, name in path if kind == "L"]
        first = joints.index(min(joints))
        joints, links = joints[first:] + joints[:first], links[first:] + links[:first]
        if len(joints) > 2 and joints[1] > joints[-1]:
            joints, links = [joints[0]] + joints[:0:-1], links[::-1]
        elif len(joints) == 2 and links[0] > links[1]:
            links = links[::-1]
        # joints[k] -- links[k] -- joints[k + 1]: link k is entered at joint k and left at joint k + 1.
        count = len(joints)
        traversals = tuple(Traversal(links[k], joints[k], joints[(k + 1) % count]) for k in range(count))
        found.setdefault((tuple(joints), tuple(links)), Cycle(traversals))

    def cycle_rank(self) -> int:
        """How many independent loops the chain has: edges - nodes + 1 of the link-joint graph."""
        edges = sum(len(joints) for joints in self.links.values())
        return edges - len(self.links) - len(self.joints) + 1


class _Distances:
    """Shortest distances in a graph of bounded degree but for a few hubs (nodes of many neighbours), up to a
    bound, each start's found in a time that does not grow with the graph.

    Around a start, a breadth-first search that does not go on through hubs gives the distance of every node
    whose shortest path crosses none; a path that crosses hubs is, after its last hub H, a path from H that
    crosses none, whose length each hub's own search (made once) knows.  The distance of each hub from the
    start is the shortest over the hubs before it (Dijkstra over the hubs alone), so every distance is exact.
    """

    HUB = 8  # neighbours above which a node is a hub

    def __init__(self, neighbours: Mapping, bound: int) -> None:
        self.neighbours, self.bound = neighbours, bound
        self.hubs = [node for node, near in neighbours.items() if len(near) > self.HUB]
        self.hub_set = set(self.hubs)
        self.from_hub = {hub: self._search(hub) for hub in self.hubs}
        # Each hub's neighbours by position, and those that each other hub's search reaches.
        self.position = {hub: {node: k for k, node in enumerate(neighbours[hub])} for hub in self.hubs}
        self.between = {(other, hub): [node for node in self.from_hub[other] if node in self.position[hub]]
                        for other in self.hubs for hub in self.hubs if other != hub}

    def _search(self, source) -> dict:
        """Distances from ``source`` up to the bound, going on through no hub (a hub reached is kept)."""
        found = {source: 0}
        frontier = [source]
        for distance in range(1, self.bound + 1):
            following = []
            for node in frontier:
                if node != source and node in self.hub_set:
                    continue
                for nxt in self.neighbours[node]:
                    if nxt not in found:
                        found[nxt] = distance
                        following.append(nxt)
            frontier = following
        return found

    def to(self, start) -> "_Around":
        """The distances from ``start`` (infinite beyond the bound)."""
        near = self._search(start)
        hub_distance = {hub: near[hub] for hub in self.hubs if hub in near}
        settled: set = set()
        while len(settled) < len(hub_distance):  # Dijkstra over the few hubs
            hub = min((h for h in hub_distance if h not in settled), key=hub_distance.__getitem__)
            settled.add(hub)
            for other in self.hubs:
                step = self.from_hub[hub].get(other)
                if step is not None and hub_distance[hub] + step < hub_distance.get(other, math.inf):
                    hub_distance[other] = hub_distance[hub] + step
        return _Around(self, near, {hub: d for hub, d in hub_distance.items() if d <= self.bound})


class _Around:
    """The distances from one start (:meth:`_Distances.to`): of any node, and the neighbours of a hub worth a try."""

    def __init__(self, distances: _Distances, near: dict, via: dict) -> None:
        self.distances, self.near, self.via = distances, near, via

    def distance(self, node, avoiding=None) -> float:
        """The distance of ``node`` from the start (a lower bound of it by a path that avoids the hub
        ``avoiding``: the shortest crosses no hub, or last crosses another)."""
        best = self.near.get(node, math.inf)
        for hub, d in self.via.items():
            if hub != avoiding:
                reach = self.distances.from_hub[hub]
                if node in reach and d + reach[node] < best:
                    best = d + reach[node]
        return best

    def around(self, hub, left: int) -> list:
        """The neighbours of ``hub`` from which a path that avoids it comes back in at most ``left`` steps, in
        the order of its neighbours: those near the start, or reached from another hub (never all of them)."""
        position = self.distances.position[hub]
        candidates = {node for node in self.near if node in position}
        for other in self.via:
            if other != hub:
                candidates.update(self.distances.between[other, hub])
        return sorted((node for node in candidates if self.distance(node, avoiding=hub) <= left),
                      key=position.__getitem__)


def independent(cycles: Sequence[Cycle]) -> bool:
    """Whether no loop of ``cycles`` is a sum (mod 2) of the others, by the link-joint edges they walk."""
    basis: dict[int, int] = {}
    bits: dict[tuple[str, str], int] = {}
    for cycle in cycles:
        row = 0
        for t in cycle.traversals:
            for joint in (t.entry, t.exit):
                row ^= 1 << bits.setdefault((t.link, joint), len(bits))
        for top in sorted(basis, reverse=True):
            if row >> top & 1:
                row ^= basis[top]
        if row == 0:
            return False
        basis[row.bit_length() - 1] = row
    return True


def _check_name(name: object, what: str) -> None:
    if not isinstance(name, str) or not PLAIN_NAME.match(name):
        raise ValueError(f"{what} {name!r} is not a name (an ASCII letter, then letters, digits or _)")
