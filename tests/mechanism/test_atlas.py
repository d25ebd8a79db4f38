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
import warnings
from itertools import combinations, permutations

import numpy as np
import pytest

from symlink.mechanism.atlas import (ATLAS, LITERATURE_COUNTS, SIX_BAR_CONVENTIONS, SIX_BAR_DEFINITIONS, ChainGraph,
                                    SixBarNameNote, atlas_entry, chains, dyads, mechanisms, six_bar_name, turns_fully)
from symlink.io.linkage_file import SIX_BAR_ENTRIES, catalog_name
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


def _six_bar_by_definition(edges, ground):
    """The six-bar's name by the cited definitions, from its pins alone (symlink.mechanism.atlas's docstring):
    Watt when the two ternary links share a pin, else Stephenson; then by the ground: Watt I binary, Watt II
    ternary; Stephenson I binary pinned to both ternary links, II binary pinned to one, III ternary."""
    degree = {}
    for a, b in edges:
        degree[a] = degree.get(a, 0) + 1
        degree[b] = degree.get(b, 0) + 1
    ternary = sorted(v for v, d in degree.items() if d == 3)
    assert len(ternary) == 2 and sorted(degree.values()) == [2, 2, 2, 2, 3, 3]
    pinned = lambda u, v: (u, v) in edges or (v, u) in edges  # noqa: E731
    if pinned(*ternary):
        return "watt-ii" if degree[ground] == 3 else "watt-i"
    if degree[ground] == 3:
        return "stephenson-iii"
    return {2: "stephenson-i", 1: "stephenson-ii"}[sum(pinned(ground, t) for t in ternary)]


def _edges(links, joints):
    """Link pairs of each joint, from a table of link -> its joints (a joint on two links)."""
    names = sorted(links)
    on = {j: [names.index(name) for name in names if j in links[name]] for j in joints}
    assert all(len(pair) == 2 for pair in on.values()), on
    return [tuple(pair) for pair in on.values()], names.index("ground")


#: PMKS+'s six-bar templates (the Planar Mechanism Kinematic Simulator web app, templates-popup.component.ts),
#: each as its links and their joints, the ground pins gathered on "ground": the cited numbering's own examples.
PMKS_TEMPLATES = {
    "watt-i": {"ground": "AG", "AB": "AB", "CBD": "BCD", "DE": "DE", "FE": "EF", "CFG": "CFG"},
    "watt-ii": {"ground": "AFG", "AB": "AB", "CB": "BC", "DCG": "CDG", "ED": "DE", "FE": "EF"},
    "stephenson-i": {"ground": "AD", "ABE": "ABE", "CB": "BC", "GCD": "CDG", "EF": "EF", "GF": "FG"},
    "stephenson-iii": {"ground": "ADG", "AB": "AB", "BCE": "BCE", "DC": "CD", "EF": "EF", "GF": "FG"},
}


@pytest.mark.parametrize("name", ["watt-i", "watt-ii", "stephenson-i", "stephenson-ii", "stephenson-iii"])
def test_each_six_bar_is_named_by_the_cited_definition(name):
    entry = ATLAS[name]
    assert _six_bar_by_definition(entry.chain.edges, entry.ground) == name


@pytest.mark.parametrize("name", sorted(PMKS_TEMPLATES))
def test_the_cited_examples_are_the_atlas_entries_of_their_names(name):
    links = {k: set(v) for k, v in PMKS_TEMPLATES[name].items()}
    edges, ground = _edges(links, "ABCDEFG")
    assert _six_bar_by_definition(edges, ground) == name
    entry = ATLAS[name]  # the same mechanism: the same chain with the same ground, up to relabelling
    assert _brute_code(6, edges, root=ground) == _brute_code(6, entry.chain.edges, root=entry.ground)


def test_the_six_bars_differ_and_the_stephenson_ii_alone_needs_newton():
    six = [e for e in ATLAS.values() if e.links == 6]
    assert sorted(e.name for e in six) == sorted(SIX_BAR_DEFINITIONS)
    codes = {_brute_code(6, e.chain.edges, root=e.ground) for e in six}
    assert len(codes) == 5
    # Grounding the binary link beside one ternary leaves a triad whichever ground-pinned link drives.
    assert [ok for _, ok in ATLAS["stephenson-ii"].drivers] == [False, False]
    assert all(ok for _, ok in ATLAS["watt-ii"].drivers)


#: The catalog's six-bars by their joints, as their docstrings draw them (symlink.mechanism.catalog).
CATALOG_SIX_BARS = {
    "watt2": {"ground": "ADG", "AB": "AB", "BC": "BC", "DCE": "CDE", "EF": "EF", "GF": "FG"},
    "stephenson2": {"ground": "AD", "AB": "AB", "BCE": "BCE", "CF": "CF", "EH": "EH", "DFH": "DFH"},
}


@pytest.mark.parametrize("catalog, name", [("watt2", "watt-ii"), ("stephenson2", "stephenson-ii")])
def test_the_catalog_s_six_bars_carry_their_names(catalog, name):
    links = {k: set(v) for k, v in CATALOG_SIX_BARS[catalog].items()}
    edges, ground = _edges(links, sorted(set("".join(CATALOG_SIX_BARS[catalog].values()))))
    assert _six_bar_by_definition(edges, ground) == name
    assert SIX_BAR_ENTRIES[name] == catalog and catalog_name(name) == catalog


@pytest.mark.parametrize("text, name", [
    ("watt-i", "watt-i"), ("Watt I", "watt-i"), ("watt-1", "watt-i"), ("watt_i", "watt-i"), ("WATT 1", "watt-i"),
    ("Watt's I", "watt-i"), ("watt2", "watt-ii"), ("Watt II", "watt-ii"), (" watt - 2 ", "watt-ii"),
    ("stephenson-i", "stephenson-i"), ("Stephenson 1", "stephenson-i"), ("stephenson2", "stephenson-ii"),
    ("Stephenson II", "stephenson-ii"), ("stephenson-3", "stephenson-iii"), ("Stephenson III", "stephenson-iii"),
    ("stephenson_iii", "stephenson-iii"),
])
def test_every_spelling_of_a_six_bar_resolves_without_a_note(text, name):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert six_bar_name(text) == name
        assert atlas_entry(text) is ATLAS[name]


@pytest.mark.parametrize("text, name", [
    ("Stephenson II", "stephenson-iii"), ("stephenson-2", "stephenson-iii"), ("stephenson-iii", "stephenson-ii"),
    ("Stephenson 3", "stephenson-ii"),
])
def test_the_other_numbering_is_read_on_request_with_a_note(text, name):
    with pytest.warns(SixBarNameNote, match=f"in the ternary-ii numbering is {name} here"):
        assert six_bar_name(text, convention="ternary-ii") == name
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the names both numberings share need no note
        assert six_bar_name("Watt I", convention="ternary-ii") == "watt-i"
        assert six_bar_name("stephenson-i", convention="ternary-ii") == "stephenson-i"


def test_the_former_catalog_name_still_names_the_same_linkage_with_a_note(capsys):
    from symlink.io.linkage_file import load_linkage
    with pytest.warns(SixBarNameNote, match="'stephenson3' is symlink's former name of stephenson-ii"):
        assert catalog_name("stephenson3") == "stephenson2"
    with pytest.warns(SixBarNameNote):
        assert load_linkage("stephenson3").linkage.name == "stephenson2"
    with pytest.warns(SixBarNameNote):
        assert atlas_entry("stephenson3") is ATLAS["stephenson-ii"]
    assert load_linkage("Watt II").linkage.name == "watt2"
    assert main(["plan", "stephenson3"]) == 0
    captured = capsys.readouterr()
    assert captured.out.startswith("stephenson2: no closed form")
    assert captured.err.count("\n") == 1 and "symlink: warning: 'stephenson3' is symlink's former name" in captured.err


@pytest.mark.parametrize("call, message", [
    (lambda: six_bar_name("watt-iii"), "no six-bar 'watt-iii'; the six-bars are watt-i, watt-ii, stephenson-i, "
                                       "stephenson-ii, stephenson-iii"),
    (lambda: atlas_entry("Watt III"), "no six-bar 'Watt III'; the six-bars are watt-i"),
    (lambda: atlas_entry("stephenson-4"), "no atlas entry 'stephenson-4'; the entries are fourbar, watt-i"),
    (lambda: six_bar_name("watt-i", convention="norton"), "no six-bar naming convention 'norton'; the conventions "
                                                          "are ternary-iii, ternary-ii"),
    (lambda: catalog_name("Stephenson III"), "the catalog has no stephenson-iii .*atlas:stephenson-iii.*stephenson2"),
    (lambda: catalog_name("watt-i"), "the catalog has no watt-i"),
    (lambda: catalog_name("nope"), "no linkage 'nope' in the catalog; it has fivebar, fourbar"),
])
def test_a_name_naming_nothing_is_refused_with_the_list(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_the_command_line_s_conventions_are_the_atlas_s():
    from symlink.cli.atlas import _add_options
    import argparse
    parser = argparse.ArgumentParser()
    _add_options(parser)
    choices = next(a.choices for a in parser._actions if a.dest == "convention")
    assert tuple(choices) == tuple(SIX_BAR_CONVENTIONS)


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
    with pytest.raises(ValueError, match="no atlas entry 'nope'; the entries are fourbar, watt-i"):
        atlas_entry("nope")
    with pytest.raises(ValueError, match="4, 6 or 8 links"):
        chains(10)


def test_the_command_lists_the_atlas_with_its_counts(capsys):
    assert main(["atlas"]) == 0
    out = capsys.readouterr().out
    assert "4 links: 1 chains, 1 mechanisms by choice of ground (literature: 1 and 1)" in out
    assert "6 links: 2 chains, 5 mechanisms by choice of ground (literature: 2 and 5)" in out
    # Watt I and II, Stephenson II and III each have two drivers up to symmetry, Stephenson I one; the
    # Stephenson III at one of its two and the Stephenson II at both need Newton's method (a triad is left).
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
    (["atlas", "Watt III"], "no six-bar 'Watt III'; the six-bars are watt-i, watt-ii"),
    (["atlas", "watt-i", "--convention", "norton"], "--convention"),
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
    assert main(["plan", "atlas:stephenson-ii"]) == 0
    assert "solved numerically" in capsys.readouterr().out
    assert main(["plan", "atlas:watt-iii"]) == 2
