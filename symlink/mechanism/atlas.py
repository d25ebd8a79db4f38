"""The atlas of one-degree-of-freedom planar linkages with revolute joints, up to eight links.

A kinematic chain is a graph: its links are the vertices and its pins the
edges.  A one-DOF chain of n links has ``j = (3 n - 4) / 2`` pins (Gruebler);
it is a proper chain when no group of its links is rigid or locked on its own
(every group of k links shares at most ``(3 k - 4) / 2`` pins, so no
triangle, no four links closing with five pins, ...).  :func:`chains`
enumerates the non-isomorphic ones: every labelled graph of each degree
sequence (how many binary, ternary and quaternary links), reduced to one
canonical form each (colour refinement, then the least adjacency code over the
orders that the refined colours allow).  The counts are the literature's
(Tsai, *Mechanism Design: Enumeration of Kinematic Structures According to
Function*, CRC 2001, table of one-DOF chains; Mruthyunjaya, "Kinematic
structure of mechanisms revisited", *Mech. Mach. Theory* 38, 2003):

====== ======= ==========================
links  chains  mechanisms (choice of ground)
====== ======= ==========================
4      1       1 (the four-bar)
6      2       5 (Watt I, II; Stephenson I, II, III)
8      16      71
====== ======= ==========================

The nineteen chains are also the nineteen topologies that pylinkage catalogues
(its ``topology/data/catalog.json``), an enumeration made independently.

A *mechanism* is a chain with one link held as the ground; two grounds give
the same mechanism when an automorphism of the chain maps one onto the other
(:meth:`ChainGraph.orbits`).  Each entry of :data:`ATLAS` is a mechanism with
a driven link on the ground (the first, among the ground's neighbours up to
symmetry, whose solve plan is closed form, if any), its other drivers and
their plans, and example dimensions by a constructive recipe: place the joints
(:func:`example_coordinates`), take the lengths from the coordinates
(:func:`symlink.mechanism.joints.from_joints`), so that it assembles by construction.

>>> [len(chains(n)) for n in (4, 6, 8)]
[1, 2, 16]
>>> [name for name in ATLAS if not name.startswith("eightbar")]
['fourbar', 'watt-i', 'watt-ii', 'stephenson-i', 'stephenson-ii', 'stephenson-iii']
>>> ATLAS["stephenson-ii"].closed_form
False

The six-bars' names
-------------------
A six-bar chain is a Watt chain when its two ternary links share a pin, a
Stephenson chain when binary links keep them apart; its mechanisms are named
by the link held as the ground (:data:`SIX_BAR_DEFINITIONS`):

============== ============================================================
watt-i         Watt chain, the ground a binary link
watt-ii        Watt chain, the ground a ternary link (two four-bars in series)
stephenson-i   Stephenson chain, the ground a binary link pinned to both ternary links
stephenson-ii  Stephenson chain, the ground a binary link pinned to one ternary link
stephenson-iii Stephenson chain, the ground a ternary link (a four-bar, and a dyad from its coupler to the ground)
============== ============================================================

This is the numbering of the linkage templates of PMKS+, the Planar Mechanism Kinematic Simulator (web app,
``templates-popup.component.ts``: Watt I grounds a binary link, Watt II a ternary one, Stephenson I a binary
link pinned to both ternary links, Stephenson III a ternary link), and of the Wikipedia article "Klann linkage"
(Klann's frame, a ternary link, makes it "a modified Stephenson type III kinematic chain").  Other texts swap
Stephenson II and III (the ternary ground is then Stephenson II: e.g. FIRGELLI's engineering library, "Stephenson
Topology Six-bar Linkage"), and so did symlink before this release.  :func:`six_bar_name` reads a name in either
numbering (``convention="ternary-ii"`` for the other), in any spelling (``Watt I``, ``watt-1``,
``stephenson_iii``), and the catalog's former name ``stephenson3`` (now ``stephenson2``), with a one-line note
(:class:`SixBarNameNote`) wherever a name does not mean what it reads in this numbering.

>>> six_bar_name("Stephenson III"), six_bar_name("watt 2"), ATLAS["stephenson-iii"].ground_kind
('stephenson-iii', 'watt-ii', 'ternary')
"""
from __future__ import annotations

import math
import re
import warnings
from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import TYPE_CHECKING, Iterator, Mapping, Sequence

from ..common.display import record_html
from ..common.limits import require_time
from ..common.names import FORMER_SIX_BAR_NAMES, SIX_BAR_DEFINITIONS, SixBarNameNote, former_name_note
from .topology import GROUND

if TYPE_CHECKING:
    from .joints import JointLinkage

__all__ = ["ChainGraph", "AtlasEntry", "chains", "mechanisms", "ATLAS", "atlas_entry", "example_coordinates",
           "LITERATURE_COUNTS", "SIX_BAR_DEFINITIONS", "SIX_BAR_CONVENTIONS", "FORMER_SIX_BAR_NAMES", "SixBarNameNote",
           "six_bar_name"]

#: Chains and mechanisms (grounds) of one-DOF planar chains with revolute joints, from the literature (Tsai 2001;
#: Mruthyunjaya 2003): links -> (chains, mechanisms).
LITERATURE_COUNTS = {4: (1, 1), 6: (2, 5), 8: (16, 71)}

Edge = tuple[int, int]


@dataclass(frozen=True)
class ChainGraph:
    """A chain as a graph: ``links`` vertices 0..n-1 and ``edges`` (pins) between them, in canonical order."""

    _repr_html_ = record_html  # a notebook shows the fields as a table

    links: int
    edges: tuple[Edge, ...]

    @cached_property
    def neighbours(self) -> tuple[frozenset[int], ...]:
        found: list[set[int]] = [set() for _ in range(self.links)]
        for a, b in self.edges:
            found[a].add(b)
            found[b].add(a)
        return tuple(frozenset(s) for s in found)

    @property
    def degrees(self) -> tuple[int, ...]:
        return tuple(len(s) for s in self.neighbours)

    @property
    def assortment(self) -> dict[int, int]:
        """How many links hold 2, 3, 4 ... pins (binary, ternary, quaternary)."""
        counts: dict[int, int] = {}
        for degree in self.degrees:
            counts[degree] = counts.get(degree, 0) + 1
        return dict(sorted(counts.items()))

    @cached_property
    def _canonical(self) -> tuple[tuple[Edge, ...], tuple[tuple[int, ...], ...]]:
        """The least edge code over the leaves of an individualisation-refinement search, and every order
        (leaf) that gives it.

        Colour refinement from the degrees, then, while a colour class has several links, each of them in
        turn is given a colour of its own and the colours refined again; a leaf (every link its own
        colour) orders the links.  The colours are canonical (ranks of sorted signatures), so isomorphic
        chains have the same leaves' codes; every automorphism maps a least leaf onto a least leaf.
        """
        best: list[tuple[Edge, ...]] = []
        orders: list[tuple[int, ...]] = []

        def search(colours: list[int]) -> None:
            cells: dict[int, list[int]] = {}
            for v, c in enumerate(colours):
                cells.setdefault(c, []).append(v)
            split = next((cells[c] for c in sorted(cells) if len(cells[c]) > 1), None)
            if split is None:
                order = tuple(sorted(range(self.links), key=lambda v: colours[v]))
                position = {v: k for k, v in enumerate(order)}
                code = tuple(sorted((min(position[a], position[b]), max(position[a], position[b]))
                                    for a, b in self.edges))
                if not best or code < best[0]:
                    best[:] = [code]
                    orders[:] = [order]
                elif code == best[0]:
                    orders.append(order)
                return
            for v in split:
                marked = [2 * c + (0 if u == v else 1) for u, c in enumerate(colours)]
                search(_refined_colours(self.links, self.neighbours, marked))

        search(_refined_colours(self.links, self.neighbours, [len(s) for s in self.neighbours]))
        return best[0], tuple(orders)

    @property
    def code(self) -> tuple[Edge, ...]:
        """The canonical edge list: equal for two chains exactly when they are isomorphic."""
        return self._canonical[0]

    def canonical(self) -> "ChainGraph":
        return ChainGraph(self.links, self.code)

    @cached_property
    def automorphisms(self) -> tuple[tuple[int, ...], ...]:
        """Every relabelling of the links that maps the chain onto itself (as ``image[link]``)."""
        orders = self._canonical[1]
        first = orders[0]
        found = []
        for order in orders:
            image = [0] * self.links
            for a, b in zip(first, order):
                image[a] = b
            found.append(tuple(image))
        return tuple(found)

    def orbits(self, fixed: int | None = None) -> list[list[int]]:
        """The links up to symmetry (of the automorphisms that keep ``fixed``, if given), each orbit sorted."""
        maps = [m for m in self.automorphisms if fixed is None or m[fixed] == fixed]
        seen: set[int] = set()
        found = []
        for v in range(self.links):
            if v not in seen:
                orbit = sorted({m[v] for m in maps})
                seen.update(orbit)
                found.append(orbit)
        return found

    def proper(self) -> bool:
        """Connected, and no group of k links (2 <= k < n) shares more than (3 k - 4) / 2 pins: nothing rigid."""
        if not _connected(self.links, self.neighbours):
            return False
        masks = [sum(1 << u for u in self.neighbours[v]) for v in range(self.links)]
        for group in range(1, 1 << self.links):
            size = bin(group).count("1")
            if 3 <= size < self.links:
                pins = sum(bin(masks[v] & group).count("1") for v in range(self.links) if group >> v & 1) // 2
                if 3 * (size - 1) - 2 * pins < 1:
                    return False
        return True


def _refined_colours(count: int, neighbours: Sequence[frozenset[int]], colours: list[int]) -> list[int]:
    """Colour refinement: canonical colours (ranks of sorted signatures) until no class splits any more."""
    while True:
        signatures = [(colours[v], tuple(sorted(colours[u] for u in neighbours[v]))) for v in range(count)]
        ranks = {s: k for k, s in enumerate(sorted(set(signatures)))}
        refined = [ranks[s] for s in signatures]
        if len(set(refined)) == len(set(colours)):
            return refined
        colours = refined


def _connected(count: int, neighbours: Sequence[frozenset[int]]) -> bool:
    reached, stack = {0}, [0]
    while stack:
        for u in neighbours[stack.pop()]:
            if u not in reached:
                reached.add(u)
                stack.append(u)
    return len(reached) == count


def _degree_sequences(links: int, pins: int) -> Iterator[tuple[int, ...]]:
    """Non-increasing degree sequences of ``links`` links with ``pins`` pins, each degree 2 .. links / 2."""
    top = links // 2

    def build(left: int, total: int, ceiling: int) -> Iterator[tuple[int, ...]]:
        if left == 0:
            if total == 0:
                yield ()
            return
        for degree in range(min(ceiling, total - 2 * (left - 1)), 1, -1):
            for rest in build(left - 1, total - degree, degree):
                yield (degree,) + rest

    yield from build(links, 2 * pins, top)


def _graphs(degrees: Sequence[int]) -> Iterator[tuple[Edge, ...]]:
    """Every labelled simple graph with these degrees and no triangle (a rigid group of three links)."""
    count = len(degrees)
    pairs = [(a, b) for a in range(count) for b in range(a + 1, count)]
    left = list(degrees)
    chosen: list[Edge] = []
    adjacent: list[set[int]] = [set() for _ in range(count)]

    def place(k: int) -> Iterator[tuple[Edge, ...]]:
        if k == len(pairs):
            if not any(left):
                yield tuple(chosen)
            return
        a, b = pairs[k]
        if b == a + 1 and left[a] > count - b:  # vertex a cannot be completed any more
            return
        if left[a] and left[b] and not (adjacent[a] & adjacent[b]):
            left[a] -= 1
            left[b] -= 1
            adjacent[a].add(b)
            adjacent[b].add(a)
            chosen.append((a, b))
            yield from place(k + 1)
            chosen.pop()
            adjacent[a].discard(b)
            adjacent[b].discard(a)
            left[a] += 1
            left[b] += 1
        if left[a] <= sum(1 for c, d in pairs[k + 1:] if c == a):
            yield from place(k + 1)

    yield from place(0)


@lru_cache(maxsize=None)
def chains(links: int) -> tuple[ChainGraph, ...]:
    """The non-isomorphic proper one-DOF chains of ``links`` links (an even number, 4 to 8) with revolute pins.

    Ordered by link assortment (the most binary links first), then by canonical code.
    """
    if links not in (4, 6, 8):
        raise ValueError(f"the atlas has chains of 4, 6 or 8 links, not {links!r}")
    pins = (3 * links - 4) // 2
    found: dict[tuple[Edge, ...], ChainGraph] = {}
    improper: set[tuple[Edge, ...]] = set()
    for degrees in _degree_sequences(links, pins):
        for edges in _graphs(degrees):
            graph = ChainGraph(links, edges)
            if graph.code in found or graph.code in improper:
                continue
            if graph.proper():
                found[graph.code] = graph.canonical()
            else:
                improper.add(graph.code)
    return tuple(sorted(found.values(), key=lambda g: (sorted(g.degrees), g.code)))


def mechanisms(links: int) -> list[tuple[int, int]]:
    """Every mechanism of ``links`` links as (chain index in :func:`chains`, ground link), one a symmetry class."""
    return [(k, orbit[0]) for k, chain in enumerate(chains(links)) for orbit in chain.orbits()]


def _bfs_order(chain: ChainGraph, ground: int, driver: int) -> list[int]:
    """The links from the ground, the driver first among its neighbours, then breadth first (lowest first)."""
    order, queue = [ground], [ground]
    while queue:
        link = queue.pop(0)
        nxt = sorted(chain.neighbours[link] - set(order), key=lambda v: (v != driver, v))
        order += nxt
        queue += nxt
    return order


def dyads(chain: ChainGraph, ground: int, driver: int) -> tuple[list[tuple[int, int]], list[int]]:
    """The dyads in solving order (pairs of adjacent links, each pinned to a link already placed), and the links
    left for Newton's method (an Assur group of a higher class) when no dyad is left.

    >>> four = chains(4)[0]
    >>> four.edges, dyads(four, 0, 1)
    (((0, 1), (0, 2), (1, 3), (2, 3)), ([(2, 3)], []))
    """
    known = {ground, driver}
    found: list[tuple[int, int]] = []
    while len(known) < chain.links:
        pair = next(((a, b) for a in range(chain.links) for b in sorted(chain.neighbours[a])
                     if a < b and a not in known and b not in known
                     and chain.neighbours[a] & known and chain.neighbours[b] & known), None)
        if pair is None:
            break
        found.append(pair)
        known.update(pair)
    return found, [v for v in range(chain.links) if v not in known]


@dataclass(frozen=True)
class AtlasEntry:
    """One mechanism of the atlas: a chain, its ground, a driver, and example dimensions.

    ``drivers`` lists every driver up to symmetry (a link pinned to the ground) with
    whether its solve plan is closed form; ``driver`` is the first closed-form one
    (else the first).  ``links`` and ``joints`` of :meth:`description` name the
    links ``ground``, ``link1`` ... and the pins ``A``, ``B`` ... (A drives).
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    name: str
    chain_index: int
    chain: ChainGraph
    ground: int
    driver: int
    drivers: tuple[tuple[int, bool], ...]

    @property
    def links(self) -> int:
        return self.chain.links

    @property
    def closed_form(self) -> bool:
        """Whether the solve plan with :attr:`driver` is closed form (dyads only)."""
        return not dyads(self.chain, self.ground, self.driver)[1]

    @property
    def ground_kind(self) -> str:
        return _KINDS.get(self.chain.degrees[self.ground], f"{self.chain.degrees[self.ground]}-pin")

    def description(self) -> tuple[dict[str, list[str]], list[str]]:
        """Link names to their pins, and the pins in order: what :func:`symlink.mechanism.joints.from_joints` takes."""
        order = _bfs_order(self.chain, self.ground, self.driver)
        names = {v: (GROUND if k == 0 else f"link{k}") for k, v in enumerate(order)}
        edges = sorted(self.chain.edges, key=lambda e: (min(order.index(e[0]), order.index(e[1])),
                                                        max(order.index(e[0]), order.index(e[1]))))
        first = next(e for e in edges if set(e) == {self.ground, self.driver})
        edges.remove(first)
        edges.insert(0, first)
        pins = [_pin_name(k) for k in range(len(edges))]
        links: dict[str, list[str]] = {names[v]: [] for v in order}
        for pin, (a, b) in zip(pins, edges):
            links[names[a]].append(pin)
            links[names[b]].append(pin)
        return links, pins

    def coordinates(self) -> dict[str, tuple[float, float]]:
        """Example joint coordinates that assemble and let the driver turn fully (see :func:`example_coordinates`)."""
        return example_coordinates(self)

    def joint_linkage(self) -> "JointLinkage":
        """The entry as a linkage, dimensioned by its example coordinates."""
        from .joints import from_joints
        links, pins = self.description()
        return from_joints(links, self.coordinates(), driver=pins[0], name=self.name)

    def summary(self) -> str:
        assortment = ", ".join(f"{count} {_KINDS.get(d, f'{d}-pin')}" for d, count in self.chain.assortment.items())
        others = ", ".join(f"link{self._link_number(v)} {'closed form' if ok else 'Newton'}" for v, ok in self.drivers)
        return (f"{self.name}: {self.links} links ({assortment}), chain {self.chain_index + 1}, ground "
                f"{self.ground_kind}; driven at link1: {'closed form' if self.closed_form else 'Newton'}"
                + (f" (drivers up to symmetry: {others})" if len(self.drivers) > 1 else ""))

    def _link_number(self, vertex: int) -> int:
        return _bfs_order(self.chain, self.ground, self.driver).index(vertex)


_KINDS = {2: "binary", 3: "ternary", 4: "quaternary"}


def _pin_name(k: int) -> str:
    return chr(ord("A") + k) if k < 26 else f"J{k}"


#: The five six-bars, each by its definition (the rule :func:`_six_bar_name` applies; the numbering of PMKS+), the
#: former names and their note: :data:`symlink.common.names.SIX_BAR_DEFINITIONS` (plain text, read without SymPy).

#: The numberings :func:`six_bar_name` reads: ``"ternary-iii"`` (symlink's, PMKS+'s: the Stephenson with a ternary
#: ground is Stephenson III) and ``"ternary-ii"`` (the other: it is Stephenson II, and Stephenson III grounds the
#: binary link pinned to one ternary link).  Watt I, Watt II and Stephenson I are the same in both.
SIX_BAR_CONVENTIONS = {"ternary-iii": {}, "ternary-ii": {"stephenson-ii": "stephenson-iii",
                                                         "stephenson-iii": "stephenson-ii"}}


_SIX_BAR_SPELLING = re.compile(r"(watt|stephenson)(?:'s)?[\s_-]*(iii|ii|i|[123])", re.IGNORECASE)
_NUMERALS = {"1": "i", "2": "ii", "3": "iii", "i": "i", "ii": "ii", "iii": "iii"}


def six_bar_name(text: str, convention: str = "ternary-iii") -> str | None:
    """The atlas name of the six-bar that ``text`` names, in any spelling; ``None`` for a text naming no six-bar.

    The one home of the six-bars' names: the atlas, the catalog, linkage files and every command read a six-bar
    name through it.  ``Watt I``, ``watt-1``, ``watt_i``, ``WATT 1`` are all ``watt-i``; the numeral is read in
    ``convention`` (:data:`SIX_BAR_CONVENTIONS`).  A name whose meaning differs from its plain reading in
    symlink's numbering (the other convention's Stephenson II or III, a former name of
    :data:`FORMER_SIX_BAR_NAMES`) gives a one-line :class:`SixBarNameNote` saying what it names.

    Parameters
    ----------
    text : str
        A six-bar's name: ``watt-i``, ``Watt II``, ``stephenson 3``, ``stephenson-iii`` ..., or any other text.
    convention : str
        ``"ternary-iii"`` (default: Stephenson III grounds a ternary link) or ``"ternary-ii"`` (Stephenson II and
        III swapped).

    Returns
    -------
    str or None
        One of the keys of :data:`SIX_BAR_DEFINITIONS`, or ``None`` when ``text`` does not name a six-bar.

    Raises
    ------
    ValueError
        For an unknown convention, or a six-bar spelling with no such mechanism (``watt-iii``, ``stephenson-4``),
        listing the names.

    Examples
    --------
    >>> import symlink
    >>> symlink.six_bar_name("Watt I"), symlink.six_bar_name("stephenson_3"), symlink.six_bar_name("fourbar")
    ('watt-i', 'stephenson-iii', None)
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     symlink.six_bar_name("Stephenson II", convention="ternary-ii")
    'stephenson-iii'
    >>> print(caught[0].message)  # doctest: +ELLIPSIS
    'Stephenson II' in the ternary-ii numbering is stephenson-iii here: Stephenson chain ..., the ground a ternary link
    """
    if convention not in SIX_BAR_CONVENTIONS:
        raise ValueError(f"no six-bar naming convention {convention!r}; the conventions are "
                         f"{', '.join(SIX_BAR_CONVENTIONS)}")
    if not isinstance(text, str):
        return None
    plain = text.strip()
    former = former_name_note(plain)
    if former is not None:
        _note(former)
        return FORMER_SIX_BAR_NAMES[plain.lower()]
    match = _SIX_BAR_SPELLING.fullmatch(plain)
    if match is None:
        return None
    read = f"{match.group(1).lower()}-{_NUMERALS[match.group(2).lower()]}"
    if read not in SIX_BAR_DEFINITIONS:
        raise ValueError(f"no six-bar {plain!r}; the six-bars are {', '.join(SIX_BAR_DEFINITIONS)}")
    name = SIX_BAR_CONVENTIONS[convention].get(read, read)
    if name != read:
        _note(f"{plain!r} in the {convention} numbering is {name} here: {SIX_BAR_DEFINITIONS[name]}")
    return name


def _note(text: str) -> None:
    warnings.warn(text, SixBarNameNote, stacklevel=3)


def _six_bar_name(chain: ChainGraph, ground: int) -> str:
    """The six-bar's name by the rule of :data:`SIX_BAR_DEFINITIONS` (the ternary links' adjacency, the ground's place)."""
    ternary = [v for v in range(6) if chain.degrees[v] == 3]
    if ternary[1] in chain.neighbours[ternary[0]]:  # the two ternary links share a pin: a Watt chain
        return "watt-ii" if chain.degrees[ground] == 3 else "watt-i"
    if chain.degrees[ground] == 3:
        return "stephenson-iii"
    return "stephenson-i" if all(t in chain.neighbours[ground] for t in ternary) else "stephenson-ii"


def _entries() -> dict[str, AtlasEntry]:
    found: dict[str, AtlasEntry] = {}
    for links in (4, 6, 8):
        for index, chain in enumerate(chains(links)):
            for number, orbit in enumerate(chain.orbits()):
                ground = orbit[0]
                drivers = tuple((o[0], not dyads(chain, ground, o[0])[1])
                                for o in chain.orbits(fixed=ground) if o[0] in chain.neighbours[ground])
                driver = next((v for v, ok in drivers if ok), drivers[0][0])
                if links == 4:
                    name = "fourbar"
                elif links == 6:
                    name = _six_bar_name(chain, ground)
                else:
                    name = f"eightbar-{index + 1:02d}{chr(ord('a') + number)}"
                found[name] = AtlasEntry(name, index, chain, ground, driver, drivers)
    six = [name for name in found if found[name].links == 6]
    ordered = sorted(six, key=list(SIX_BAR_DEFINITIONS).index)
    return {"fourbar": found["fourbar"], **{n: found[n] for n in ordered},
            **{n: e for n, e in found.items() if e.links == 8}}


class _Atlas(Mapping[str, AtlasEntry]):
    """The atlas entries by name, enumerated on first use."""

    @cached_property
    def _entries(self) -> dict[str, AtlasEntry]:
        return _entries()

    def __getitem__(self, name: str) -> AtlasEntry:
        return self._entries[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._entries)

    def __len__(self) -> int:
        return len(self._entries)


#: Every mechanism of the atlas by name: ``fourbar``, the five six-bars, ``eightbar-NNx`` (chain NN, ground x).
ATLAS: Mapping[str, AtlasEntry] = _Atlas()


def atlas_entry(name: str, convention: str = "ternary-iii") -> AtlasEntry:
    """The atlas entry ``name``; ``ValueError`` listing the names for any other.

    Parameters
    ----------
    name : str
        An atlas name: ``fourbar``, ``watt-i``, ``watt-ii``, ``stephenson-i`` ... or ``eightbar-NNx``; a six-bar in
        any spelling (``Watt I``, ``stephenson 3``: :func:`six_bar_name`).
    convention : str
        The numbering a six-bar's name is read in: ``"ternary-iii"`` (default, symlink's) or ``"ternary-ii"``
        (Stephenson II and III swapped; :data:`SIX_BAR_CONVENTIONS`).

    Returns
    -------
    AtlasEntry
        The chain, its ground and driver, and example dimensions.

    Raises
    ------
    ValueError
        For a name not in :data:`ATLAS`, listing the names.

    Examples
    --------
    >>> import symlink
    >>> entry = symlink.atlas_entry("watt-ii")
    >>> entry.ground_kind, entry.links, entry.closed_form
    ('ternary', 6, True)
    >>> symlink.atlas_entry("Stephenson III").ground_kind
    'ternary'
    """
    name = six_bar_name(name, convention) or name
    if not isinstance(name, str) or name not in ATLAS:
        six = [n for n in ATLAS if not n.startswith("eightbar")]
        raise ValueError(f"no atlas entry {name!r}; the entries are {', '.join(six)} and eightbar-01a ... "
                         f"{list(ATLAS)[-1]} (symlink atlas lists them)")
    return ATLAS[name]


#: Seeds tried by :func:`example_coordinates` before it gives up on a full turn.
_SEEDS = 1000
#: The driver's length relative to the spread of the other joints (a short crank turns most chains fully).
_CRANK = (0.12, 0.3)


def _placement(entry: AtlasEntry, seed: int) -> dict[str, tuple[float, float]]:
    """Joints placed at random (seeded): A at the origin, the driver's other pins close to it, the rest in a box."""
    import random
    links, pins = entry.description()
    rng = random.Random(seed)
    placed: dict[str, tuple[float, float]] = {pins[0]: (0.0, 0.0)}
    for pin in links["link1"][1:]:
        radius, angle = rng.uniform(*_CRANK), rng.uniform(-math.pi, math.pi)
        placed[pin] = (radius * math.cos(angle), radius * math.sin(angle))
    for pin in pins:
        if pin not in placed:
            placed[pin] = (rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0))
    return placed


def _well_drawn(links: Mapping[str, Sequence[str]], placed: Mapping[str, tuple[float, float]]) -> bool:
    """Joints apart from each other (but the crank's) and no link's pins nearly on one line."""
    pins = list(placed)
    for k, p in enumerate(pins):
        for q in pins[k + 1:]:
            if math.dist(placed[p], placed[q]) < (0.1 if p == pins[0] or q == pins[0] else 0.35):
                return False
    for joints in links.values():
        for a, b, c in _triples(joints):
            (ax, ay), (bx, by), (cx, cy) = placed[a], placed[b], placed[c]
            area = abs((bx - ax) * (cy - ay) - (by - ay) * (cx - ax)) / 2
            if area < 0.08 * max(math.dist(placed[a], placed[b]), math.dist(placed[a], placed[c])) ** 2:
                return False
    return True


def _triples(joints: Sequence[str]) -> Iterator[tuple[str, str, str]]:
    for i in range(len(joints)):
        for j in range(i + 1, len(joints)):
            for k in range(j + 1, len(joints)):
                yield joints[i], joints[j], joints[k]


#: Seconds :func:`turns_fully` takes a step of the driver, at least (measured 1.3 ms a four-bar's step to 3 ms an
#: eight-bar's on a shared machine, up to twelve Newton iterations a step): absurdly many steps are refused at once.
SECONDS_PER_STEP = 1e-3


def turns_fully(links: Mapping[str, Sequence[str]], placed: Mapping[str, tuple[float, float]],
                driver: str, steps: int = 180) -> bool:
    """Whether the linkage drawn at ``placed`` follows a whole turn of the link driven at the ground pin ``driver``.

    Newton's method on the pins' distances (every pair on a link), continued in ``steps`` steps of the driver's
    angle; a turn fails where it does not converge or the constraints' Jacobian loses rank (a toggle), and
    succeeds when it comes back to the drawn pose.
    """
    import numpy
    if isinstance(steps, bool) or not isinstance(steps, int) or steps < 1:
        raise ValueError(f"steps must be a whole number, at least 1; got {steps!r}")
    require_time(steps, SECONDS_PER_STEP, f"following a turn in {steps:,} steps", "steps")
    crank = next(name for name, joints in links.items() if name != GROUND and driver in joints)
    fixed = set(links[GROUND])
    turning = [p for p in links[crank] if p != driver]
    free = [p for p in placed if p not in fixed and p not in turning]
    index = {p: k for k, p in enumerate(free)}
    pairs = [(a, b, math.dist(placed[a], placed[b])) for name, joints in links.items() if name not in (GROUND, crank)
             for i, a in enumerate(joints) for b in joints[i + 1:]]
    start = numpy.array([c for p in free for c in placed[p]])
    origin = numpy.array(placed[driver])
    offsets = {p: numpy.array(placed[p]) - origin for p in turning}

    def known(angle: float) -> dict[str, numpy.ndarray]:
        c, s = math.cos(angle), math.sin(angle)
        found = {p: numpy.array(placed[p]) for p in fixed}
        found.update({p: origin + numpy.array([c * v[0] - s * v[1], s * v[0] + c * v[1]]) for p, v in offsets.items()})
        return found

    def residual(x: numpy.ndarray, given: dict) -> tuple[numpy.ndarray, numpy.ndarray]:
        f = numpy.empty(len(pairs))
        jac = numpy.zeros((len(pairs), len(x)))
        for row, (a, b, length) in enumerate(pairs):
            pa = x[2 * index[a]:2 * index[a] + 2] if a in index else given[a]
            pb = x[2 * index[b]:2 * index[b] + 2] if b in index else given[b]
            d = pa - pb
            f[row] = d @ d - length * length
            if a in index:
                jac[row, 2 * index[a]:2 * index[a] + 2] = 2 * d
            if b in index:
                jac[row, 2 * index[b]:2 * index[b] + 2] = -2 * d
        return f, jac

    x = start.copy()
    for step in range(1, steps + 1):
        given = known(2 * math.pi * step / steps)
        for _ in range(12):
            f, jac = residual(x, given)
            singular = numpy.linalg.svd(jac, compute_uv=False)
            if singular[len(x) - 1] < 0.05:
                return False
            x = x - numpy.linalg.lstsq(jac, f, rcond=None)[0]
            if numpy.max(numpy.abs(f)) < 1e-12:
                break
        else:
            return False
    return bool(numpy.max(numpy.abs(x - start)) < 1e-8)


@lru_cache(maxsize=None)
def _example(name: str) -> tuple[tuple[str, tuple[float, float]], ...]:
    entry = ATLAS[name]
    links, pins = entry.description()
    first = None
    for seed in range(_SEEDS):
        placed = _placement(entry, seed)
        if not _well_drawn(links, placed):
            continue
        first = first or placed
        if turns_fully(links, placed, pins[0]):
            return tuple(placed.items())
    assert first is not None
    return tuple(first.items())


def example_coordinates(entry: AtlasEntry) -> dict[str, tuple[float, float]]:
    """Example joint coordinates of an atlas entry: the first seeded placement that turns fully.

    The recipe: pin A (the driver's ground pin) at the origin, the driver's other pins
    0.12 to 0.3 from it, every other pin uniformly in the square [-2, 2]^2
    (:func:`random.Random` with seeds 0, 1, 2, ...), kept when no two pins are
    closer than 0.35 and no link's pins are nearly on a line, and when the
    linkage follows a whole turn of its driver (:func:`turns_fully`); the lengths
    are then the distances in this drawing.
    """
    return dict(_example(entry.name))
