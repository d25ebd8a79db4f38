"""The atlas of one-DOF linkages (symlink.mechanism.atlas, ``symlink atlas``) against the literature and brute force.

* The counts of chains (1, 2, 16) and of mechanisms by choice of ground (1, 5, 71) are the literature's
  (Tsai 2001; Mruthyunjaya 2003), and for six links also a brute force written here: every graph of 6
  links and 7 pins, kept when no group of links is rigid, reduced by trying all 720 relabellings.
* The canonical code does not depend on how a chain's links are numbered; the automorphisms are automorphisms.
* Every entry assembles at its example coordinates and follows a whole turn of its driver; its plan from the
  joints (symlink.mechanism.joints) is the one the topology predicts (dyads, else Newton); closed-form solvers agree
  with Newton's method on the closure along a turn.
"""
import math
import random
from itertools import combinations, permutations

import numpy as np
import pytest

from symlink.mechanism.atlas import ATLAS, LITERATURE_COUNTS, ChainGraph, atlas_entry, chains, dyads, mechanisms, turns_fully
from symlink.cli import main
from symlink.numeric.solver import NumericSolver, Solver


def test_the_counts_are_the_literature_s():
    for links, (chain_count, mechanism_count) in LITERATURE_COUNTS.items():
        assert len(chains(links)) == chain_count
        assert len(mechanisms(links)) == mechanism_count
        assert sum(1 for e in ATLAS.values() if e.links == links) == mechanism_count
    assert LITERATURE_COUNTS == {4: (1, 1), 6: (2, 5), 8: (16, 71)}


def _brute_code(count, edges, root=None):
    """The least sorted edge list over every relabelling (the root, if any, relabelled 0)."""
    best = None
    for order in permutations(range(count)):
        if root is not None and order[root] != 0:
            continue
        code = tuple(sorted(tuple(sorted((order[a], order[b]))) for a, b in edges))
        best = code if best is None or code < best else best
    return best


def _rigid_somewhere(count, edges):
    for size in range(3, count):
        for group in combinations(range(count), size):
            inside = set(group)
            if 3 * (size - 1) - 2 * sum(1 for a, b in edges if a in inside and b in inside) < 1:
                return True
    return False


def test_six_link_chains_and_mechanisms_by_brute_force():
    pairs = list(combinations(range(6), 2))
    codes = set()
    for edges in combinations(pairs, 7):
        degrees = [sum(v in e for e in edges) for v in range(6)]
        if min(degrees) < 2 or _rigid_somewhere(6, edges):
            continue
        reached, stack = {0}, [0]
        while stack:
            v = stack.pop()
            for a, b in edges:
                for u, w in ((a, b), (b, a)):
                    if u == v and w not in reached:
                        reached.add(w)
                        stack.append(w)
        if len(reached) == 6:
            codes.add(_brute_code(6, edges))
    assert len(codes) == 2
    rooted = {_brute_code(6, code, root) for code in codes for root in range(6)}
    assert len(rooted) == 5
    assert {ChainGraph(6, code).code for code in codes} == {c.code for c in chains(6)}


@pytest.mark.parametrize("index", range(16))
def test_the_canonical_code_does_not_depend_on_the_numbering(index):
    chain = chains(8)[index]
    rng = random.Random(index)
    for _ in range(3):
        relabel = list(range(8))
        rng.shuffle(relabel)
        shuffled = ChainGraph(8, tuple((relabel[a], relabel[b]) for a, b in chain.edges))
        assert shuffled.code == chain.code
        assert len(shuffled.automorphisms) == len(chain.automorphisms)
    edges = {frozenset(e) for e in chain.edges}
    for image in chain.automorphisms:
        assert {frozenset((image[a], image[b])) for a, b in chain.edges} == edges
    # Orbit-stabiliser: an orbit's size times its stabiliser's order is the group's order.
    for orbit in chain.orbits():
        stabiliser = sum(1 for m in chain.automorphisms if m[orbit[0]] == orbit[0])
        assert len(orbit) * stabiliser == len(chain.automorphisms)


def test_every_eight_link_chain_is_proper_and_they_differ():
    for chain in chains(8):
        assert len(chain.edges) == 10 and min(chain.degrees) >= 2
        assert not _rigid_somewhere(8, chain.edges)
    assert len({c.code for c in chains(8)}) == 16
    assortments = sorted(tuple(sorted(c.assortment.items())) for c in chains(8))
    # The link assortments of the sixteen eight-link chains (Tsai 2001): 9 with 4 binary and 4 ternary links,
    # 5 with 5 binary, 2 ternary and 1 quaternary, 2 with 6 binary and 2 quaternary.  The last by hand: two
    # quaternaries joined by four chains of binaries, six binaries in all; adjacent quaternaries need the other
    # three chains of two (a chain of one would close a triangle): one chain; apart, the chains are (2, 2, 1, 1)
    # (three chains of one would make five links with six pins, rigid): a second.
    assert assortments.count(((2, 4), (3, 4))) == 9
    assert assortments.count(((2, 5), (3, 2), (4, 1))) == 5
    assert assortments.count(((2, 6), (4, 2))) == 2


def test_the_six_bars_are_named_by_their_ground():
    for name in ("watt-i", "watt-ii", "stephenson-i", "stephenson-ii", "stephenson-iii"):
        entry = ATLAS[name]
        ternary = [v for v in range(6) if entry.chain.degrees[v] == 3]
        adjacent = ternary[1] in entry.chain.neighbours[ternary[0]]
        assert adjacent == name.startswith("watt")
        assert (entry.chain.degrees[entry.ground] == 3) == name.endswith("-ii")
    stephenson_one = ATLAS["stephenson-i"]
    assert all(stephenson_one.chain.degrees[v] == 3 for v in stephenson_one.chain.neighbours[stephenson_one.ground])
    # The catalog's Stephenson III has no closed form whichever ground pivot drives; the Watt II always has one.
    assert [ok for _, ok in ATLAS["stephenson-iii"].drivers] == [False, False]
    assert all(ok for _, ok in ATLAS["watt-ii"].drivers)


@pytest.mark.parametrize("name", list(ATLAS))
def test_every_entry_assembles_turns_and_is_solved_as_its_topology_says(name):
    entry = ATLAS[name]
    links, pins = entry.description()
    coordinates = entry.coordinates()
    assert turns_fully(links, coordinates, pins[0])
    drawn = entry.joint_linkage()
    assert drawn.linkage.has_closed_form == entry.closed_form
    pairs, rest = dyads(entry.chain, entry.ground, entry.driver)
    # The same dyads, then (without a closed form) one group for Newton's method with the links left.
    assert len(drawn.structure) == len(pairs) + (0 if entry.closed_form else 1)
    assert all(len(links_) == 2 for _, links_ in drawn.structure[:len(pairs)])
    assert drawn.mobility.dof == 1
    if not entry.closed_form:
        assert len(drawn.structure[-1][1]) == len(rest) >= 4  # an Assur group of class III or more


@pytest.mark.parametrize("name", ["fourbar", "watt-i", "watt-ii", "stephenson-i", "stephenson-ii", "stephenson-iii",
                                  "eightbar-02b", "eightbar-05d", "eightbar-16b"])
def test_the_generated_solver_agrees_with_newton_on_the_closure_along_a_turn(name):
    entry = atlas_entry(name)
    drawn = entry.joint_linkage()
    linkage = drawn.linkage
    coordinates = entry.coordinates()
    points = [f"{p}_{axis}" for p in coordinates for axis in "xy"]
    start = drawn.pose[linkage.inputs[0].name]
    sweep = start + np.linspace(0.0, 2 * math.pi, 91)
    newton = NumericSolver(linkage)(guess=drawn.guess, **{**drawn.parameters, linkage.inputs[0].name: sweep})
    assert bool(np.all(newton["assembled"]))
    for p, (x, y) in coordinates.items():  # the drawn pose, and back to it after a turn
        for k in (0, -1):
            assert abs(float(newton[p + "_x"][k]) - x) < 1e-9 and abs(float(newton[p + "_y"][k]) - y) < 1e-9
    if linkage.has_closed_form:
        closed = Solver(linkage, points)(**{**drawn.defaults, linkage.inputs[0].name: sweep})
        for name_ in points:
            assert np.max(np.abs(np.asarray(closed[name_]) - np.asarray(newton[name_]))) < 1e-9, name_


def test_an_unknown_entry_is_refused_naming_the_entries():
    with pytest.raises(ValueError, match="no atlas entry 'watt-iii'; the entries are fourbar, watt-i"):
        atlas_entry("watt-iii")
    with pytest.raises(ValueError, match="4, 6 or 8 links"):
        chains(10)


def test_the_command_lists_the_atlas_with_its_counts(capsys):
    assert main(["atlas"]) == 0
    out = capsys.readouterr().out
    assert "4 links: 1 chains, 1 mechanisms by choice of ground (literature: 1 and 1)" in out
    assert "6 links: 2 chains, 5 mechanisms by choice of ground (literature: 2 and 5)" in out
    # Watt I and II, Stephenson II and III each have two drivers up to symmetry, Stephenson I one; the
    # Stephenson II at one of its two and the Stephenson III at both need Newton's method (a triad is left).
    assert "9 by ground and driven link, 6 of them in closed form" in out
    assert "8 links: 16 chains, 71 mechanisms by choice of ground (literature: 16 and 71)" in out
    assert out.count("\n  ") == 77


def test_the_command_shows_and_draws_an_entry(tmp_path, capsys):
    out_file = tmp_path / "watt.png"
    assert main(["atlas", "watt-ii", "--draw", str(out_file)]) == 0
    out = capsys.readouterr().out
    assert "closed form, loop by loop" in out and "links: ground A B C" in out and f"wrote {out_file}" in out
    assert out_file.read_bytes().startswith(b"\x89PNG")


@pytest.mark.parametrize("argv, message", [
    (["atlas", "nope"], "no atlas entry 'nope'"),
    (["atlas", "--draw", "x.png"], "--draw needs an atlas entry NAME"),
    (["atlas", "watt-ii", "--draw", "x.pdf"], "must end in .png or .svg"),
])
def test_bad_atlas_command_lines_are_one_line_and_status_2(argv, message, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err


#: The 19 one-DOF topologies of pylinkage's catalog (``src/pylinkage/topology/data/catalog.json``, pylinkage 1.x,
#: MIT licence, (c) Hugo Farajallah), each as the link pairs of its joints (its joint ids ``J<a>_<b>``):
#: an independent enumeration to compare with.
PYLINKAGE_TOPOLOGIES = {
    "four-bar": [(0, 1), (0, 2), (1, 3), (2, 3)],
    "watt": [(0, 1), (0, 4), (1, 5), (2, 3), (2, 4), (3, 5), (4, 5)],
    "stephenson": [(0, 1), (0, 4), (1, 5), (2, 4), (2, 5), (3, 4), (3, 5)],
    "eight-bar-01": [(0, 1), (0, 6), (1, 7), (2, 3), (2, 6), (3, 7), (4, 5), (4, 6), (5, 7), (6, 7)],
    "eight-bar-02": [(0, 1), (0, 6), (1, 7), (2, 3), (2, 6), (3, 7), (4, 6), (4, 7), (5, 6), (5, 7)],
    "eight-bar-03": [(0, 1), (0, 5), (1, 7), (2, 3), (2, 6), (3, 7), (4, 5), (4, 6), (5, 7), (6, 7)],
    "eight-bar-04": [(0, 1), (0, 5), (1, 7), (2, 3), (2, 6), (3, 7), (4, 5), (4, 7), (5, 6), (6, 7)],
    "eight-bar-05": [(0, 1), (0, 5), (1, 7), (2, 5), (2, 6), (3, 6), (3, 7), (4, 6), (4, 7), (5, 7)],
    "eight-bar-06": [(0, 1), (0, 5), (1, 7), (2, 5), (2, 7), (3, 6), (3, 7), (4, 6), (4, 7), (5, 6)],
    "eight-bar-07": [(0, 5), (0, 6), (1, 5), (1, 7), (2, 5), (2, 7), (3, 6), (3, 7), (4, 6), (4, 7)],
    "eight-bar-08": [(0, 1), (0, 4), (1, 5), (2, 3), (2, 6), (3, 7), (4, 5), (4, 6), (5, 7), (6, 7)],
    "eight-bar-09": [(0, 1), (0, 4), (1, 5), (2, 3), (2, 6), (3, 7), (4, 6), (4, 7), (5, 6), (5, 7)],
    "eight-bar-10": [(0, 1), (0, 4), (1, 5), (2, 4), (2, 6), (3, 5), (3, 6), (4, 7), (5, 7), (6, 7)],
    "eight-bar-11": [(0, 1), (0, 4), (1, 5), (2, 4), (2, 6), (3, 5), (3, 7), (4, 7), (5, 6), (6, 7)],
    "eight-bar-12": [(0, 1), (0, 4), (1, 5), (2, 4), (2, 6), (3, 6), (3, 7), (4, 7), (5, 6), (5, 7)],
    "eight-bar-13": [(0, 1), (0, 4), (1, 5), (2, 6), (2, 7), (3, 6), (3, 7), (4, 5), (4, 6), (5, 7)],
    "eight-bar-14": [(0, 4), (0, 5), (1, 4), (1, 5), (2, 6), (2, 7), (3, 6), (3, 7), (4, 6), (5, 7)],
    "eight-bar-15": [(0, 4), (0, 5), (1, 4), (1, 6), (2, 4), (2, 7), (3, 5), (3, 6), (5, 7), (6, 7)],
    "eight-bar-16": [(0, 4), (0, 5), (1, 4), (1, 6), (2, 5), (2, 7), (3, 6), (3, 7), (4, 7), (5, 6)],
}


def test_the_chains_are_pylinkage_s_nineteen_topologies():
    ours = {c.code for n in (4, 6, 8) for c in chains(n)}
    theirs = {ChainGraph(max(max(e) for e in edges) + 1, tuple(edges)).code for edges in PYLINKAGE_TOPOLOGIES.values()}
    assert len(theirs) == 19 and theirs == ours


def test_an_atlas_entry_by_name_is_a_linkage_for_every_command(capsys):
    from symlink.io.linkage_file import load_linkage
    found = load_linkage("atlas:watt-ii")
    points = [f"{p}_{axis}" for p in ATLAS["watt-ii"].coordinates() for axis in "xy"]
    got = Solver(found.linkage, points)(**found.defaults)  # branches by default +1: the example's assembly
    for p, (x, y) in ATLAS["watt-ii"].coordinates().items():
        assert abs(float(got[p + "_x"]) - x) < 1e-12 and abs(float(got[p + "_y"]) - y) < 1e-12, p
    assert main(["plan", "atlas:stephenson-iii"]) == 0
    assert "solved numerically" in capsys.readouterr().out
    assert main(["plan", "atlas:watt-iii"]) == 2
