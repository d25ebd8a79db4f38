"""The small-call extension (symlink.codegen.call_extension): the compiled path's keywords handled in C.

Checked: results equal to the NumPy module's on random inputs and bit for bit equal to the Python fast
path (the extension turned off); every call it refuses answered by the general path as before (errors,
broadcasting, shape-() results, coercion); no reference leaked or lost over many calls, with arrays
freed between them; correct results from two threads at once; results kept for many calls answered from
blocks made before (no new block a call), never written again, and right against the law of cosines and
finite differences; the kept blocks' caps; and, without the extension, everything as before.
"""
from __future__ import annotations

import collections
import sys
import threading
import weakref

import numpy
import pytest

from export_checks import angles_of, assert_agree, random_arguments
from symlink.numeric import compiled_library
from symlink.codegen.call_extension import ENTRY_FIELDS, PLAN_FIELDS
from symlink.numeric.compiled import CompiledSolver, CompilerUnavailable, find_compiler
from symlink.numeric.results import Results
from symlink.io.scene import catalog_linkage
from symlink.numeric.solver import Solver

OUTPUTS = ["coupler", "rocker", "coupler_speed", "rocker_speed", "coupler_accel", "rocker_accel", "transmission",
           "C_x", "C_y", "singular"]
LENGTHS = dict(a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0, thetadot=10.5, thetaddot=2.0)


@pytest.fixture(scope="module")
def fourbar():
    return catalog_linkage("fourbar")


@pytest.fixture(scope="module")
def solvers(fourbar):
    """A compiled solver with the extension, and the NumPy solver, of OUTPUTS."""
    try:
        find_compiler()
        compiled = CompiledSolver(fourbar, OUTPUTS)
    except CompilerUnavailable as error:
        pytest.skip(f"no working C compiler: {error}")
    if compiled.function._plan is None:
        pytest.skip("the small-call extension cannot be built here (no Python headers?)")
    return compiled, Solver(fourbar, OUTPUTS, backend="numpy")


def without_extension(fourbar) -> CompiledSolver:
    """A compiled solver of OUTPUTS whose small calls take the Python fast path."""
    solver = CompiledSolver(fourbar, OUTPUTS)
    solver.function._plan = None
    return solver


def test_the_extension_agrees_with_numpy_and_bit_for_bit_with_the_python_path(solvers, fourbar):
    compiled, plain = solvers
    python_path = without_extension(fourbar)
    linkage = fourbar
    for seed, count in enumerate((1, 2, 10, 17, 300)):
        values = random_arguments(linkage, compiled.arguments, count, seed)
        theta = values.pop("theta")
        numbers = {name: float(array[0]) for name, array in values.items()}  # lengths as numbers, angles an array
        fast = compiled(theta=theta, **numbers)
        assert type(fast) is Results and fast["rocker"].base is not None  # made in C, rows of a kept block
        reference = plain(theta=theta, **numbers)
        assert_agree(fast, reference, angles_of("fourbar", OUTPUTS), 1e-12, f"seed {seed}")
        slow = python_path(theta=theta, **numbers)
        for name in reference:
            assert numpy.array_equal(fast[name], slow[name], equal_nan=True), (seed, name)
            assert fast[name].dtype == reference[name].dtype and fast[name].shape == (count,)
        assert fast.units == reference.units and fast.input_units == reference.input_units
        assert fast.inputs.keys() == reference.inputs.keys()
        # Arrays for every argument (one length) go through the extension too.
        arrays = compiled(theta=theta, **values)
        assert arrays["rocker"].base is not None
        assert_agree(arrays, plain(theta=theta, **values), angles_of("fourbar", OUTPUTS), 1e-12, f"arrays {seed}")


def test_a_results_own_units_and_inputs_are_copies(solvers):
    compiled, _ = solvers
    first = compiled(theta=numpy.linspace(0.0, 1.0, 10), **LENGTHS)
    first.units["rocker"] = "changed"
    first.inputs["a"] = -1.0
    first.input_units.clear()
    second = compiled(theta=numpy.linspace(0.0, 1.0, 10), **LENGTHS)
    assert second.units["rocker"] == "rad" and second.inputs["a"] == 20.0 and second.input_units["theta"] == "rad"
    assert second.varying_inputs() == ["theta"] and second.to_frame().shape == (10, 1 + len(second))


def test_defaults_left_out_are_filled_in(solvers):
    compiled, plain = solvers
    theta = numpy.linspace(-1.0, 1.0, 10)
    lengths = dict(a=20.0, b=66.0, c=56.0, d=80.0)  # branch, thetadot and thetaddot left to their defaults
    small = compiled.function._extension.call(compiled.function._plan, dict(theta=theta, **lengths))
    assert small is not None
    expected = plain(theta=theta, **lengths)
    assert_agree(small, {k: v for k, v in expected.items()}, angles_of("fourbar", OUTPUTS), 1e-12)


class Name(str):
    """A keyword name that is not exactly a str (its comparisons could run Python code)."""


REFUSED = {  # keyword values the extension leaves to the general path
    "a list": dict(theta=[0.0, 1.0]),
    "numbers only": dict(theta=0.5),
    "a bool": dict(theta=numpy.linspace(0.0, 1.0, 5), branch=True),
    "an int too large for a double": dict(theta=numpy.linspace(0.0, 1.0, 5), a=10 ** 400),
    "a 2-d array": dict(theta=numpy.linspace(0.0, 1.0, 6).reshape(2, 3)),
    "a 0-d array": dict(theta=numpy.array(0.5)),
    "a strided array": dict(theta=numpy.linspace(0.0, 1.0, 10)[::2]),
    "an int array": dict(theta=numpy.arange(5)),
    "a float32 array": dict(theta=numpy.linspace(0.0, 1.0, 5, dtype=numpy.float32)),
    "a big-endian array": dict(theta=numpy.linspace(0.0, 1.0, 5).astype(">f8")),
    "an empty array": dict(theta=numpy.empty(0)),
    "arrays of two lengths": dict(theta=numpy.linspace(0.0, 1.0, 5), a=numpy.full(4, 20.0)),
    "too many values": dict(theta=numpy.linspace(0.0, 1.0, compiled_library.SMALL_CALL + 1)),
    "an unknown name": dict(theta=numpy.linspace(0.0, 1.0, 5), alpha=1.0),
    "a missing name": dict(theta=numpy.linspace(0.0, 1.0, 5), a=None),
    "a complex number": dict(theta=numpy.linspace(0.0, 1.0, 5), a=20.0 + 0j),
    "a string": dict(theta=numpy.linspace(0.0, 1.0, 5), a="20"),
    "a subclass of ndarray": dict(theta=numpy.ma.masked_array(numpy.linspace(0.0, 1.0, 5))),
    "a name that is a str subclass": {Name("theta"): numpy.linspace(0.0, 1.0, 5)},
    "a negative length": dict(theta=numpy.linspace(0.0, 1.0, 5), a=-20.0),  # refused by the packed C check
}


@pytest.mark.parametrize("case", sorted(REFUSED))
def test_what_the_extension_refuses_the_general_path_answers_as_before(solvers, fourbar, case):
    compiled, _ = solvers
    python_path = without_extension(fourbar)
    values = {**LENGTHS, **REFUSED[case]}
    values = {name: value for name, value in values.items() if value is not None}
    function = compiled.function
    assert function._extension.call(function._plan, dict(values)) is None
    assert function._extension.results(function._plan, dict(values), Results, {}, {}) is None
    try:
        expected = python_path(**values)
    except ValueError as error:
        with pytest.raises(ValueError) as raised:
            compiled(**values)
        assert str(raised.value) == str(error)
        return
    got = compiled(**values)
    assert sorted(got) == sorted(expected)
    for name in expected:
        assert numpy.array_equal(got[name], expected[name], equal_nan=True), name
        assert got[name].shape == expected[name].shape and got[name].dtype == expected[name].dtype


def test_many_calls_leak_no_reference_and_survive_freed_arrays(solvers):
    compiled, _ = solvers
    theta = numpy.linspace(0.0, 1.0, 10)
    a = 20.5
    before = sys.getrefcount(theta), sys.getrefcount(a)
    for _ in range(2000):
        compiled(theta=theta, a=a, b=66.0, c=56.0, d=80.0, branch=1)
    assert (sys.getrefcount(theta), sys.getrefcount(a)) == before
    held = []
    for k in range(2000):  # a new array each call, freed at once or kept a while (blocks busy, then freed)
        result = compiled(theta=numpy.full(7, 0.001 * k), **LENGTHS)
        if k % 97 == 0:
            held.append((k, result))
        if len(held) > 5:
            held.pop(0)
    assert len(compiled.function._entries) <= compiled_library.KEPT_OUTPUTS
    for k, result in held:  # results held across later calls were never written again
        expected = compiled.function(theta=numpy.full(7, 0.001 * k), **LENGTHS)
        assert numpy.array_equal(result["rocker"], expected["rocker"])


def test_a_call_while_another_is_inside_takes_the_general_path(solvers):
    compiled, plain = solvers
    busy = compiled.function._plan[PLAN_FIELDS.index("busy")]
    theta = numpy.linspace(0.0, 1.0, 10)
    busy[0] = 1  # as while another thread's call is making an output block
    try:
        assert compiled.function._extension.call(compiled.function._plan, dict(theta=theta, **LENGTHS)) is None
        result = compiled(theta=theta, **LENGTHS)
        # the general path's own block (one allocation, numpy's), not an output block of the extension
        assert type(result["rocker"].base) is numpy.ndarray and result["rocker"].base.base is None
    finally:
        busy[0] = 0
    assert_agree(result, plain(theta=theta, **LENGTHS), angles_of("fourbar", OUTPUTS), 1e-12)


def test_two_threads_calling_at_once_get_their_own_results(solvers):
    compiled, _ = solvers
    inputs = [numpy.linspace(0.1 * k, 0.1 * k + 1.0, 10) for k in range(8)]
    expected = [compiled.function(theta=theta.copy(), **LENGTHS) for theta in inputs]  # each call's own answer
    failures: list[str] = []

    def work(offset: int) -> None:
        held: list = []  # results held a few calls: new output blocks made in Python, where threads switch
        for step in range(3000):
            k = (step + offset) % len(inputs)
            result = compiled(theta=inputs[k].copy() if step % 2 else inputs[k], **LENGTHS)
            held = (held + [(k, result)])[-4 if step % 3 else 0:]
            for j, old in held:
                if not numpy.array_equal(old["rocker"], expected[j]["rocker"]):
                    failures.append(f"thread {offset} step {step}")
                    return

    previous = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # switch threads as often as possible
    try:
        threads = [threading.Thread(target=work, args=(offset,)) for offset in (0, 3)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
    finally:
        sys.setswitchinterval(previous)
    assert not failures


def test_without_the_extension_everything_works_as_before(fourbar, monkeypatch, solvers):
    compiled, plain = solvers
    monkeypatch.setattr(compiled_library, "_call_extension", [])
    monkeypatch.setenv(compiled_library.NO_EXTENSION_VARIABLE, "1")
    assert compiled_library.call_extension() is None
    solver = CompiledSolver(fourbar, OUTPUTS)
    assert solver.function._plan is None
    theta = numpy.linspace(0.0, 1.0, 10)
    result = solver(theta=theta, **LENGTHS)
    assert result["rocker"].base is not None  # the Python fast path
    with_extension = compiled(theta=theta, **LENGTHS)
    for name in result:
        assert numpy.array_equal(result[name], with_extension[name], equal_nan=True), name
    with pytest.raises(ValueError, match="a must be a positive finite length"):
        solver(theta=theta, **{**LENGTHS, "a": -1.0})


def test_a_failed_build_falls_back_with_one_warning(monkeypatch):
    monkeypatch.setattr(compiled_library, "_call_extension", [])

    def broken(build: bool) -> None:
        raise compiled_library.CompileError("rejected")

    monkeypatch.setattr(compiled_library, "_load_call_extension", broken)
    with pytest.warns(compiled_library.FallbackWarning, match="without the C extension"):
        assert compiled_library.call_extension() is None
    assert compiled_library._call_extension == [None]


def test_quantities_take_the_general_path_with_their_units(solvers):
    pint = pytest.importorskip("pint")
    compiled, plain = solvers
    millimetre = pint.UnitRegistry().millimetre
    values = {**LENGTHS, "a": 20.0 * millimetre, "b": 66.0 * millimetre, "c": 56.0 * millimetre,
              "d": 80.0 * millimetre}
    theta = numpy.linspace(0.0, 1.0, 10)
    got, expected = compiled(theta=theta, **values), plain(theta=theta, **values)
    assert got.units == expected.units and got.input_units == expected.input_units
    assert_agree(got, expected, angles_of("fourbar", OUTPUTS), 1e-12)


def test_a_background_build_brings_the_extension_with_the_library(fourbar, monkeypatch, solvers):
    """So that the thread adopting a finished build (backend="auto") finds the extension built, not builds it."""
    monkeypatch.setattr(compiled_library, "_call_extension", [])
    build = compiled_library.Build(compiled_library.c_solver_source(fourbar, ["rocker"]))
    build.run()  # what the background builder runs
    assert build.error is None and compiled_library._call_extension[0] is not None
    entry = build.entry()
    assert entry is not None and entry._plan is not None


def test_a_new_small_block_is_made_in_c_without_python(solvers):
    """Results kept longer than the blocks kept for reuse: each call makes a new block, and the plan's Python
    ``make`` is never called for it (the extension makes the block and its rows itself)."""
    compiled, plain = solvers
    function = compiled.function

    def refuse(length: int) -> tuple:
        raise AssertionError("a small call's block was made in Python")

    plan = tuple(refuse if field == "make" else value for field, value in zip(PLAN_FIELDS, function._plan))
    theta = numpy.linspace(0.0, 1.0, 10)
    kept = [function._extension.results(plan, dict(theta=theta + 0.01 * k, **LENGTHS), Results, {}, {})
            for k in range(3 * compiled_library.KEPT_OUTPUTS)]
    assert len({id(result["rocker"].base) for result in kept}) == len(kept)  # a block each
    for k, result in enumerate(kept):
        assert_agree(result, plain(theta=theta + 0.01 * k, **LENGTHS), angles_of("fourbar", OUTPUTS), 1e-12)


def test_a_large_call_into_out_is_answered_in_c_into_the_callers_arrays(solvers):
    compiled, plain = solvers
    function = compiled.function
    theta = numpy.linspace(0.0, 2 * numpy.pi, 3 * compiled_library.SMALL_CALL)
    first = compiled(theta=theta, **LENGTHS)
    out = {name: numpy.empty_like(value) for name, value in first.items()}
    made = function._extension.large(function._plan, dict(theta=theta, **LENGTHS), out, Results, {"rocker": "rad"}, {})
    assert type(made) is Results and made.units == {"rocker": "rad"} and list(made) == list(first)
    assert all(made[name] is out[name] for name in out)
    assert_agree(made, plain(theta=theta, **LENGTHS), angles_of("fourbar", OUTPUTS), 1e-12)
    # what it cannot take is left to the general path: an out of another shape, a float32 row, a 2-d argument
    for bad_out, values in (({**out, "rocker": numpy.empty(5)}, dict(theta=theta)),
                            ({**out, "rocker": out["rocker"].astype(numpy.float32)}, dict(theta=theta)),
                            (out, dict(theta=theta[None, :]))):
        assert function._extension.large(function._plan, {**LENGTHS, **values}, bad_out, Results, {}, {}) is None


def law_of_cosines(theta: numpy.ndarray, a: float, b: float, c: float, d: float, branch: float) -> tuple:
    """(coupler, rocker) angles of the four-bar, by hand: joint C where the circles about B (radius b) and D
    (radius c) meet, the rocker's angle at D off the line DB by the law of cosines, the side by the branch
    (+1: C to the left of the directed line B -> D)."""
    bx, by = a * numpy.cos(theta), a * numpy.sin(theta)
    reach = numpy.hypot(d - bx, by)  # |BD|
    towards_b = numpy.arctan2(by, bx - d)  # the direction of DB at D
    off = numpy.arccos((c * c + reach * reach - b * b) / (2 * c * reach))
    rocker = numpy.where(numpy.sign((d - bx) * (c * numpy.sin(towards_b + off) - by)
                                    + by * (d + c * numpy.cos(towards_b + off) - bx)) == branch,
                         towards_b + off, towards_b - off)
    coupler = numpy.arctan2(c * numpy.sin(rocker) - by, d + c * numpy.cos(rocker) - bx)
    return coupler, rocker


def wrapped(angle: numpy.ndarray) -> numpy.ndarray:
    return numpy.angle(numpy.exp(1j * angle))


def check_against_hand(result, theta: numpy.ndarray) -> None:
    """Positions against the law of cosines, speeds against central differences of it (seed 003's crank-rocker:
    assembled everywhere, away from its toggles)."""
    lengths = [LENGTHS[name] for name in "abcd"]
    coupler, rocker = law_of_cosines(theta, *lengths, LENGTHS["branch"])
    assert numpy.allclose(wrapped(result["coupler"] - coupler), 0.0, atol=1e-12)
    assert numpy.allclose(wrapped(result["rocker"] - rocker), 0.0, atol=1e-12)
    step = 1e-6
    ahead, behind = law_of_cosines(theta + step, *lengths, 1.0), law_of_cosines(theta - step, *lengths, 1.0)
    for name, k in (("coupler_speed", 0), ("rocker_speed", 1)):
        difference = LENGTHS["thetadot"] * wrapped(ahead[k] - behind[k]) / (2 * step)
        assert numpy.allclose(result[name], difference, rtol=1e-6, atol=1e-6), name


def crank_angles(step: int, n: int = 10) -> numpy.ndarray:
    return numpy.linspace(0.0, 2 * numpy.pi, n, endpoint=False) + 0.01 * step  # each call its own


@pytest.mark.parametrize("kept_for", [1, 8, 9, 40, 100])
def test_results_kept_for_many_calls_come_from_blocks_made_before_and_are_never_written_again(fourbar, kept_for):
    """A caller keeping each result for ``kept_for`` calls (a deque): once the blocks have grown to what it holds,
    no call makes a new block (every result's block is one seen before: counted by weak references, which
    hold nothing), each result is its own (no memory shared with one held) and keeps its values through
    every later call (calls into out= among them), right against the law of cosines and finite differences."""
    solver = CompiledSolver(fourbar, OUTPUTS)
    function = solver.function
    if function._plan is None:
        pytest.skip("the small-call extension cannot be built here (no Python headers?)")
    held: collections.deque = collections.deque(maxlen=kept_for)
    for step in range(kept_for + 2):  # the blocks grow to what the caller holds, plus the one being written
        held.append((step, solver(theta=crank_angles(step), **LENGTHS)))
    assert len(function._entries) == kept_for + 1
    made_before = [weakref.ref(entry[ENTRY_FIELDS.index("block")]) for entry in function._entries]
    copies = {step: {name: value.copy() for name, value in result.items()} for step, result in held}
    out = {name: numpy.empty_like(value) for name, value in held[-1][1].items()}
    for step in range(kept_for + 2, 3 * kept_for + 20):
        result = solver(theta=crank_angles(step), **LENGTHS)
        block = result["rocker"].base
        assert any(known() is block for known in made_before), f"a new block at step {step}"
        assert not any(numpy.may_share_memory(result["rocker"], old["rocker"]) for _, old in held)
        check_against_hand(result, crank_angles(step))
        copies[step] = {name: value.copy() for name, value in result.items()}
        held.append((step, result))
        copies = {k: copies[k] for k, _ in held}
        if step % 7 == 0:  # a call into the caller's arrays writes there, and nowhere else
            assert solver(theta=crank_angles(-step), **LENGTHS, out=out)["rocker"] is out["rocker"]
            check_against_hand(out, crank_angles(-step))
        for k, kept in held:  # every result held is as it was made
            for name, value in copies[k].items():
                assert numpy.array_equal(kept[name], value, equal_nan=True), (step, k, name)
    for k, kept in held:
        check_against_hand(kept, crank_angles(k))


def test_the_kept_blocks_grow_no_further_than_their_caps_and_shrink_back_once_results_are_dropped(fourbar):
    solver = CompiledSolver(fourbar, OUTPUTS)
    function = solver.function
    if function._plan is None:
        pytest.skip("the small-call extension cannot be built here (no Python headers?)")
    entries, most = function._entries, compiled_library.KEPT_OUTPUTS_MOST
    held = [solver(theta=crank_angles(step), **LENGTHS) for step in range(most + 40)]  # all kept: more than the cap
    assert len(entries) == most
    for step, result in enumerate(held):
        check_against_hand(result, crank_angles(step))
    held.clear()
    for step in range(2 * most):  # results dropped: one block fewer a call, back to KEPT_OUTPUTS
        result = solver(theta=crank_angles(step), **LENGTHS)
    assert len(entries) == compiled_library.KEPT_OUTPUTS
    # The bytes: blocks of SMALL_CALL values, each the size of a result's arrays (counted here by hand).
    n = compiled_library.SMALL_CALL
    held = [solver(theta=crank_angles(step, n), **LENGTHS) for step in range(most)]
    size = sum(value.nbytes for value in held[0].values())
    assert size == n * (8 * (len(OUTPUTS) - 1) + 2)  # the number rows, then singular and assembled
    assert len(entries) == max(compiled_library.KEPT_OUTPUTS, compiled_library.KEPT_OUTPUTS_BYTES // size) < most
    check_against_hand(held[-1], crank_angles(most - 1, n))
    # Calls of another length: the free blocks of the length before, past KEPT_OUTPUTS, are dropped at once
    # (the first call's new block comes on top), and the next calls find the new one.
    held.clear()
    for step in range(3):
        check_against_hand(solver(theta=crank_angles(step, 20), **LENGTHS), crank_angles(step, 20))
        assert len(entries) == compiled_library.KEPT_OUTPUTS + (step == 0)
        assert sum(entry[ENTRY_FIELDS.index("length")] == 20 for entry in entries) == 1


def default_solver(fourbar) -> Solver:
    """The default Solver of OUTPUTS, whose large calls the extension answers (else the test is skipped)."""
    solver = Solver(fourbar, OUTPUTS)
    if solver.wait_for_backend() != "compiled" or solver._compiled._plan is None:
        pytest.skip("no compiled backend with the call extension here")
    return solver


LARGE = 3 * compiled_library.SMALL_CALL  # a large call (above the small calls' limit), blocks well under the caps


@pytest.mark.parametrize("kept_for", [1, 3, 8])
def test_large_results_kept_for_a_few_calls_come_from_blocks_they_freed_and_are_never_written_again(fourbar,
                                                                                                   kept_for):
    """As the small calls' test above, for large calls: once the blocks have grown to what the caller holds plus
    one, no call makes a new block, each result is its own and keeps its values through every later call
    (calls into out= among them), right against the law of cosines and finite differences."""
    solver = default_solver(fourbar)
    entries = solver._compiled._large_entries
    held: collections.deque = collections.deque(maxlen=kept_for)
    for step in range(kept_for + 2):
        held.append((step, solver(theta=crank_angles(step, LARGE), **LENGTHS)))
    assert len(entries) == max(kept_for + 1, compiled_library.KEPT_BLOCKS)
    made_before = [weakref.ref(entry[ENTRY_FIELDS.index("block")]) for entry in entries]
    copies = {step: {name: value.copy() for name, value in result.items()} for step, result in held}
    out = {name: numpy.empty_like(value) for name, value in held[-1][1].items()}
    for step in range(kept_for + 2, 3 * kept_for + 8):
        result = solver(theta=crank_angles(step, LARGE), **LENGTHS)
        assert len(result["rocker"]) == LARGE
        assert any(known() is result["rocker"].base for known in made_before), f"a new block at step {step}"
        assert not any(numpy.may_share_memory(result[name], old[name]) for _, old in held for name in result)
        check_against_hand(result, crank_angles(step, LARGE))
        copies[step] = {name: value.copy() for name, value in result.items()}
        held.append((step, result))
        copies = {k: copies[k] for k, _ in held}
        if step % 3 == 0:  # a call into the caller's arrays writes there, and nowhere else
            assert solver(theta=crank_angles(-step, LARGE), **LENGTHS, out=out)["rocker"] is out["rocker"]
            check_against_hand(out, crank_angles(-step, LARGE))
        for k, kept in held:
            for name, value in copies[k].items():
                assert numpy.array_equal(kept[name], value, equal_nan=True), (step, k, name)
    for k, kept in held:
        check_against_hand(kept, crank_angles(k, LARGE))


def test_the_kept_large_blocks_grow_no_further_than_their_caps_and_shrink_back_once_results_are_dropped(
        fourbar, monkeypatch):
    solver = default_solver(fourbar)
    entries, most = solver._compiled._large_entries, compiled_library.KEPT_LARGE_MOST
    held = [solver(theta=crank_angles(step, LARGE), **LENGTHS) for step in range(most + 5)]  # more than the cap
    assert len(entries) == most
    for step, result in enumerate(held):
        check_against_hand(result, crank_angles(step, LARGE))
    held.clear()
    for step in range(2 * most):  # results dropped: one block fewer a call, back to KEPT_BLOCKS
        result = solver(theta=crank_angles(step, LARGE), **LENGTHS)
        assert len(entries) == max(compiled_library.KEPT_BLOCKS, most - 1 - step)
    check_against_hand(result, crank_angles(step, LARGE))
    del result
    # The bytes: a block is the size of a result's arrays (counted here by hand); a cap of three blocks and a half
    # keeps three, however many the caller holds.
    size = LARGE * (8 * (len(OUTPUTS) - 1) + 2)  # the number rows, then singular and assembled
    monkeypatch.setattr(compiled_library, "KEPT_LARGE_BYTES", 7 * size // 2)
    held = [solver(theta=crank_angles(step, LARGE), **LENGTHS) for step in range(8)]
    assert sum(value.nbytes for value in held[0].values()) == size
    assert len(entries) == 3
    assert sum(entry[ENTRY_FIELDS.index("block")].nbytes for entry in entries) == 3 * size
    for step, result in enumerate(held):
        check_against_hand(result, crank_angles(step, LARGE))


def test_two_threads_keeping_large_results_get_their_own_and_never_see_them_written(fourbar):
    """Two threads share one Solver's kept large blocks (the loop runs without the GIL), each holding its last 0 to
    4 results: every result held stays right against the law of cosines through the other thread's calls."""
    solver = default_solver(fourbar)
    inputs = [crank_angles(k, LARGE) for k in range(6)]
    expected = [law_of_cosines(theta, *(LENGTHS[name] for name in "abcd"), LENGTHS["branch"])[1] for theta in inputs]
    failures: list[str] = []

    def work(offset: int) -> None:
        held: list = []
        for step in range(150):
            k = (step + offset) % len(inputs)
            held = (held + [(k, solver(theta=inputs[k], **LENGTHS))])[-(step % 5):] if step % 5 else []
            for j, old in held:
                if not numpy.allclose(wrapped(old["rocker"] - expected[j]), 0.0, atol=1e-12):
                    failures.append(f"thread {offset} step {step}")
                    return

    threads = [threading.Thread(target=work, args=(offset,)) for offset in (0, 3)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not failures
    assert len(solver._compiled._large_entries) <= compiled_library.KEPT_LARGE_MOST
