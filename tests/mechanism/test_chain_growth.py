"""Chains of dyads described by their joints: derived in memory and a program that grow with the chain (issue #33).

Two legitimate one-freedom chains, each hung on a driven crank A-P0:

* ``ground``: dyad j is a rocker from the ground pivot G_j and a coupler from the joint before, P_(j-1), meeting
  at P_j (the issue's "each dyad hung on the joint before");
* ``truss``: a four-bar A-P0-P1-D, then dyad j hung on the two most recent moving joints P_(j-2) and P_(j-1): the
  chain whose loops a search of every simple loop took a time exponential in n to find (34 s for 20 dyads).

The reference pose is an independent Newton solve of the joint distances written here (NumPy only), continued
from the drawing in small steps of the crank angle.
"""
from __future__ import annotations

import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

from benchmarks.growth import chain_by_joints as ground_chain  # the benchmark's chain: one definition


def truss_chain(n: int) -> tuple[dict, dict]:
    links = {"ground": ["A", "D"], "crank": ["A", "P0"], "r1": ["D", "P1"], "c1": ["P0", "P1"]}
    coordinates = {"A": (0.0, 0.0), "P0": (0.3, 1.0), "D": (2.5, 0.0), "P1": (2.2, 1.6)}
    for j in range(2, n + 1):
        links[f"r{j}"] = [f"P{j - 2}", f"P{j}"]
        links[f"c{j}"] = [f"P{j - 1}", f"P{j}"]
        coordinates[f"P{j}"] = (2.0 * j + 0.3 * (j % 3), 1.0 + 1.1 * (j % 2) + 0.1 * j)
    return links, coordinates


CHAINS = {"ground": ground_chain, "truss": truss_chain}

# Run in a child process under a 1 GB address space (and a CPU-time guard, no timing assertion: the exponential
# loop search of before would never finish): derive the chain by its joints, solve its points with the NumPy
# solver at the drawing and at a turned crank, print them as JSON.
CHILD = """
import json, resource, sys
resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))
resource.setrlimit(resource.RLIMIT_CPU, (300, 300))
sys.path.insert(0, sys.argv[1])
from test_chain_growth import CHAINS
from symlink.mechanism.joints import from_joints
from symlink.numeric.solver import Solver
kind, n, turned = sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
links, coordinates = CHAINS[kind](n)
drawn = from_joints(links, coordinates, driver="A", name=f"{kind}{n}")
moving = [f"P{j}" for j in range(n + 1)]
solver = Solver(drawn.linkage, [f"{p}_{axis}" for p in moving for axis in "xy"], backend="numpy")
answers = {}
for label, angle in (("drawn", drawn.defaults["theta_A_P0"]), ("turned", turned)):
    got = solver(**{**drawn.defaults, "theta_A_P0": angle})
    answers[label] = {p: [float(got[p + "_x"]), float(got[p + "_y"])] for p in moving}
print(json.dumps({"cases": [step.case.name for step in drawn.linkage.plan], "points": answers}))
"""


def distances(links: dict, coordinates: dict) -> list[tuple[str, str, float]]:
    """Every pair of joints on one link, with its drawn distance (each link here is binary or the ground)."""
    pairs = []
    for name, joints in links.items():
        if name == "ground":
            continue
        first, second = joints
        (x0, y0), (x1, y1) = coordinates[first], coordinates[second]
        pairs.append((first, second, math.hypot(x1 - x0, y1 - y0)))
    return pairs


def newton_pose(links: dict, coordinates: dict, angle: float, steps: int = 40) -> dict[str, np.ndarray]:
    """The moving joints at crank angle ``angle``: Newton on every link's distance equation, the crank turned
    from the drawing in ``steps`` small steps (so each solve starts next to the assembly it continues)."""
    fixed = {j: np.array(xy) for j, xy in coordinates.items() if j in links["ground"]}
    moving = [j for j in coordinates if j not in fixed and j != "P0"]
    pairs = [p for p in distances(links, coordinates) if {p[0], p[1]} != {"A", "P0"}]
    crank = math.hypot(*coordinates["P0"])
    start = math.atan2(coordinates["P0"][1], coordinates["P0"][0])
    x = np.array([c for j in moving for c in coordinates[j]], dtype=float)
    where = {j: k for k, j in enumerate(moving)}
    for t in np.linspace(start, angle, steps + 1)[1:]:
        known = dict(fixed, P0=crank * np.array([math.cos(t), math.sin(t)]))
        for _ in range(30):
            residual, jacobian = np.zeros(len(pairs)), np.zeros((len(pairs), len(x)))
            for row, (first, second, length) in enumerate(pairs):
                p = known[first] if first in known else x[2 * where[first]:2 * where[first] + 2]
                q = known[second] if second in known else x[2 * where[second]:2 * where[second] + 2]
                residual[row] = (p - q) @ (p - q) - length ** 2
                if first in where:
                    jacobian[row, 2 * where[first]:2 * where[first] + 2] = 2 * (p - q)
                if second in where:
                    jacobian[row, 2 * where[second]:2 * where[second] + 2] = -2 * (p - q)
            step = np.linalg.solve(jacobian, residual)
            x -= step
            if np.max(np.abs(step)) < 1e-14:
                break
    result = {"P0": crank * np.array([math.cos(angle), math.sin(angle)])}
    result.update({j: x[2 * k:2 * k + 2] for j, k in where.items()})
    return result


def solved_in_child(kind: str, n: int, turned: float, tmp_path) -> dict:
    here = os.path.dirname(os.path.abspath(__file__))
    env = {**os.environ, "SYMLINK_CACHE": str(tmp_path / "cache"), "MPLBACKEND": "Agg"}
    done = subprocess.run([sys.executable, "-c", CHILD, here, kind, str(n), repr(turned)],
                          capture_output=True, text=True, env=env)
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout)


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["ground", "truss"])
def test_a_chain_of_24_dyads_by_joints_derives_and_solves_in_1_gb(kind, tmp_path):
    n, turned = 24, 1.45  # the drawing's crank is at atan2(1, 0.3) = 1.28 rad
    links, coordinates = CHAINS[kind](n)
    found = solved_in_child(kind, n, turned, tmp_path)
    assert found["cases"] == ["3"] * n  # every dyad a closed form (two angles), one after another
    for joint, xy in found["points"]["drawn"].items():  # the drawing reproduced
        assert np.allclose(xy, coordinates[joint], rtol=0, atol=1e-9), joint
    reference = newton_pose(links, coordinates, turned)
    for first, second, length in distances(links, coordinates):  # the reference closes every link
        p, q = (reference[j] if j in reference else np.array(coordinates[j]) for j in (first, second))
        assert abs(math.hypot(*(p - q)) - length) < 1e-10
    for joint, xy in found["points"]["turned"].items():
        assert np.allclose(xy, reference[joint], rtol=0, atol=1e-8), joint


def program_size(kind: str, n: int) -> tuple[int, int]:
    """The straight-line program of every unknown and every point: assignments after CSE, NumPy source length."""
    from symlink.codegen.numpy import numpy_function
    from symlink.codegen.program import straight_line
    from symlink.mechanism.joints import from_joints
    links, coordinates = CHAINS[kind](n)
    linkage = from_joints(links, coordinates, driver="A").linkage
    outputs = [q.name for q in linkage.unknowns] + [f"{p}_{axis}" for p in linkage.points for axis in "xy"]
    program = linkage.program(outputs)
    return len(straight_line(program).assignments), len(numpy_function(program, "solve"))


@pytest.mark.parametrize("kind", ["ground", "truss"])
def test_the_generated_program_grows_linearly_with_the_number_of_dyads(kind):
    """Each dyad's angles and points are named intermediates: 2 n dyads make at most 2.1 times n's program (a
    program that substituted each loop's closed form into the next would grow much faster)."""
    sizes = {n: program_size(kind, n) for n in (8, 16, 32)}
    for n in (8, 16):
        assignments, source = (big / small for big, small in zip(sizes[2 * n], sizes[n]))
        assert assignments < 2.1 and source < 2.1, (n, sizes)


def test_loops_of_hundreds_of_links_are_found_without_a_recursion_limit():
    """A depth-first search by recursion stopped at Python's limit (1000 frames) on a loop of 600 links, and a
    file of 2000 dyads was refused as "nested too deeply"; a chain of 600 dyads keeps its shortest loops."""
    from symlink.mechanism.topology import Chain
    ring = {"ground": ["J0", "J599"], **{f"l{k}": [f"J{k - 1}", f"J{k}"] for k in range(1, 600)}}
    loops = Chain(ring).cycles()
    assert len(loops) == 1 and len(loops[0].traversals) == 600
    links, _ = truss_chain(600)
    triangles = Chain(links).cycles(longest=3)
    assert [set(c.joints) for c in triangles] == [{f"P{j - 2}", f"P{j - 1}", f"P{j}"} for j in range(2, 601)]


@pytest.mark.parametrize("links", [
    {"ground": ["A", "D", "E"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"], "arm": ["E", "F"]},
    {"ground": ["A", "D", "G"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C", "E"],
     "link5": ["E", "F"], "link6": ["F", "G"], "tail": ["F", "H"], "tip": ["H", "K"]},
    {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C", "E"], "rocker": ["D", "C"],
     "a": ["E", "F"], "b": ["F", "G"], "c": ["G", "E2"], "d": ["E2", "F"]},
    {"ground": ["A", "B"], "one": ["A", "C"], "two": ["C", "D"]},
])
def test_the_links_on_a_loop_are_the_links_that_some_simple_loop_walks(links):
    """Linear (bridges) against the enumeration of every simple loop, which is fine for small chains."""
    from symlink.mechanism.topology import Chain
    chain = Chain(links)
    assert chain.looped_links() == {t.link for cycle in chain.cycles() for t in cycle.traversals}


def calls_in_generation(n: int) -> dict:
    """How often each function of symlink's own code runs while the NumPy module and the C source of a chain
    of n dyads by joints are generated (counted by a profile hook: calls, never times)."""
    from symlink.codegen.numpy import numpy_module
    from symlink.mechanism.joints import from_joints
    from symlink.numeric.compiled_library import program_facts
    package = os.path.dirname(os.path.abspath(sys.modules["symlink"].__file__))
    links, coordinates = ground_chain(n)
    linkage = from_joints(links, coordinates, driver="A").linkage
    program = linkage.program([q.name for q in linkage.unknowns])
    counts: dict = {}

    def count(frame, event, _):
        if event == "call" and frame.f_code.co_filename.startswith(package):
            counts[frame.f_code] = counts.get(frame.f_code, 0) + 1

    sys.setprofile(count)
    try:
        numpy_module([("solve", program, "")])
        program_facts(program, "solve", "", [])
    finally:
        sys.setprofile(None)
    return {f"{code.co_filename[len(package):]}:{code.co_firstlineno} {code.co_name}": k for code, k in counts.items()}


@pytest.mark.parametrize("n", [8, pytest.param(16, marks=pytest.mark.slow)])
def test_generating_twice_the_dyads_calls_no_function_of_symlink_more_than_about_twice_as_often(n):
    """A function called in proportion to the program's size squared (a pass over every known angle pair for
    each sine, over every output for each output chosen) runs four times as often for 2 n dyads as for n;
    every function of symlink's code generation runs at most 2.6 times as often (the number of C pieces, a
    few, is rounded up; sympy's own functions are not counted)."""
    small, large = calls_in_generation(n), calls_in_generation(2 * n)
    grown = {name: (k, small.get(name, 0)) for name, k in large.items() if k > 200 and k > 2.6 * small.get(name, 0)}
    assert not grown, grown


def test_the_shortest_loops_are_those_of_the_full_list_where_two_links_hold_many_joints():
    """The search that goes on only where a loop can still close in time (around hubs: the ground of 10
    pivots, a plate of 10 joints) keeps exactly the first loops of the full list, in its order."""
    from symlink.mechanism.topology import Chain
    links, _ = ground_chain(9)
    plate = {**links, "plate": [f"P{j}" for j in range(10)]}
    for chosen in (links, plate):
        chain = Chain(chosen)
        everything = chain.cycles()
        for longest in (3, 4, 5):
            assert [c.name for c in chain.cycles(longest=longest)] == \
                [c.name for c in everything if len(c.traversals) <= longest]


def walk_steps(n: int) -> int:
    """Lines of symlink's topology code run while the loops of at most 4 joints of n dyads on one ground are
    found (a trace counts them: steps, never times)."""
    from symlink.mechanism import topology
    links, _ = ground_chain(n)
    chain = topology.Chain(links)
    lines = [0]

    def trace(frame, event, _):
        if frame.f_code.co_filename != topology.__file__:
            return None
        if event == "line":
            lines[0] += 1
        return trace

    sys.settrace(trace)
    try:
        found = chain.cycles(longest=4)
    finally:
        sys.settrace(None)
    assert len(found) == n  # each dyad's loop through the ground: G(j-1), P(j-1), P(j), G(j)
    return lines[0]


def test_finding_the_dyads_loops_on_a_ground_of_many_pivots_grows_linearly():
    """Every walk that crossed the ground (a link of n + 1 joints) tried all n pivots: a search of n^2 steps
    (5 s for 500 dyads, 80 s for 2000).  Now twice the dyads take at most 2.2 times the steps."""
    assert walk_steps(200) <= 2.2 * walk_steps(100)


def calls_of(run, only_symlink: bool, also: tuple[str, ...] = ()) -> dict:
    """How often each Python function runs during ``run()`` (symlink's own and those of the packages ``also``, or
    every one: SymPy's, the dataclasses' comparisons), counted by a profile hook: calls, never times."""
    folders = tuple(os.path.dirname(os.path.abspath(sys.modules[name].__file__)) for name in ("symlink", *also))
    counts: dict = {}

    def count(frame, event, _):
        if event == "call" and (not only_symlink or frame.f_code.co_filename.startswith(folders)):
            counts[frame.f_code] = counts.get(frame.f_code, 0) + 1

    sys.setprofile(count)
    try:
        run()
    finally:
        sys.setprofile(None)
    return {f"{code.co_filename}:{code.co_firstlineno} {code.co_name}": k for code, k in counts.items()}


def test_drawing_twice_the_dyads_calls_no_function_of_symlink_more_than_about_twice_as_often():
    """Deriving a chain from its joints (loops, closed forms, branch signs at the drawing): a link's fixed joints
    were listed again for every side walked (the ground holds n pivots: n^2 steps, 3.6 times as many calls for
    2 n dyads); now every function of symlink runs at most 2.2 times as often for twice the dyads (SymPy's own
    functions are not counted: its cache of a fixed size holds less of a longer chain)."""
    from symlink.mechanism.joints import from_joints
    small, large = (calls_of(lambda: from_joints(*ground_chain(n), driver="A"), True) for n in (50, 100))
    grown = {name: (k, small.get(name, 0)) for name, k in large.items() if k > 200 and k > 2.2 * small.get(name, 0)}
    assert not grown, grown
    assert sum(large.values()) <= 2.2 * sum(small.values())


def test_reading_the_bodies_of_twice_the_dyads_makes_about_twice_the_calls():
    """The mechanism (bodies and joints) that ``symlink plan`` reads for its mobility: every vector was looked for
    in the list of those seen (a comparison of vectors each, n^2), every vector's body in every role; now twice
    the dyads make at most 2.2 times the calls of every Python function, SymPy's and the comparisons included."""
    from symlink.mechanism.bodies import mechanism
    from symlink.mechanism.joints import from_joints
    totals = []
    for n in (50, 100):
        linkage = from_joints(*ground_chain(n), driver="A").linkage
        totals.append(sum(calls_of(lambda: mechanism(linkage), False).values()))
    assert totals[1] <= 2.2 * totals[0], totals


def test_the_branch_signs_of_twice_the_dyads_make_about_twice_the_calls():
    """The branch signs at the drawing, the closed forms derived before the count: the calls of symlink's functions
    and of mpmath's (the 20-digit arithmetic, where the branch signs were decided before) at most 2.2 times as many
    for twice the dyads.  SymPy's own calls are not counted: its cache of a fixed size holds fewer of a longer
    chain's symbols, and equal symbols made again are compared by their contents (0 such calls at 50 dyads run
    alone, 16,800 at 100), however the signs are decided."""
    import mpmath  # noqa: F401 - its folder is counted
    from symlink.mechanism.drawn_branches import drawn_branch_signs
    from symlink.mechanism.joints import from_joints
    totals = []
    for n in (50, 100):
        drawn = from_joints(*ground_chain(n), driver="A")
        known = {**drawn.parameters, **drawn.pose}
        values = {s: known[s.name] for s in drawn.linkage.parameters + drawn.linkage.coordinates}
        drawn.linkage.plan  # noqa: B018 - derived before the count
        scale = max(abs(c) for xy in drawn.coordinates.values() for c in xy)
        signs: dict = {}
        totals.append(sum(calls_of(lambda: signs.update(drawn_branch_signs(drawn.linkage, values, scale)),
                                   True, ("mpmath",)).values()))
        assert signs == {b.name: 1 for b in drawn.linkage.branches}  # the drawing is every loop's +1
    assert totals[1] <= 2.2 * totals[0], totals
