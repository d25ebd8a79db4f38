"""A call's outputs: one block a call, reused once no caller holds it, or the caller's own arrays (``out=``)."""
from __future__ import annotations

import numpy
import pytest

from symlink.mechanism.catalog import fourbar
from symlink.numeric import compiled_library
from symlink.numeric.solver import Solver

POSITIONS = ["coupler", "rocker"]
FULL = ["coupler", "rocker", "coupler_speed", "rocker_speed", "coupler_accel", "rocker_accel"]
#: 10 values take the compiled small-call path, 5000 the general one (more than SMALL_CALL).
SIZES = (10, 5000)


@pytest.fixture(scope="module", params=["numpy", "compiled"])
def backend(request):
    if request.param == "compiled" and not compiled_library.compiler_works():
        pytest.skip("no working C compiler here")
    return request.param


@pytest.fixture(scope="module")
def solvers(backend):
    made = {"positions": Solver(fourbar(), POSITIONS, backend=backend),
            "full": Solver(fourbar(), FULL, backend=backend)}
    assert all(solver.backend == backend for solver in made.values())
    return made


def arguments(n: int, shift: float = 0.0) -> dict:
    """A triple-rocker (a = 60: the crank cannot reach 180 degrees), so that some outputs are NaN, unassembled."""
    theta = numpy.linspace(-numpy.pi, numpy.pi, n) + shift
    return dict(theta=theta, a=60.0, b=66.0, c=56.0, d=80.0, branch=1.0, thetadot=10.5, thetaddot=2.0)


def call(solver: Solver, values: dict, **more):
    return solver(**{k: v for k, v in values.items() if k in solver.arguments}, **more)


def bits(array: numpy.ndarray) -> numpy.ndarray:
    """The bytes of an array (NaN payloads and signed zeros too): equal bits, not just equal values."""
    return numpy.ascontiguousarray(array).view(numpy.uint8)


def empty_like(result) -> dict[str, numpy.ndarray]:
    """Arrays of each output's shape and dtype, each its own allocation, filled with something else (7)."""
    return {name: numpy.full(value.shape, 7, dtype=value.dtype) for name, value in result.items()}


@pytest.mark.parametrize("n", SIZES)
@pytest.mark.parametrize("kind", ["positions", "full"])
def test_out_gives_the_fresh_call_bit_for_bit_in_the_callers_arrays(solvers, kind, n):
    solver = solvers[kind]
    values = arguments(n)
    fresh = {name: value.copy() for name, value in call(solver, values).items()}
    assert not fresh["assembled"].all() and fresh["assembled"].any()  # NaN rows among them
    out = empty_like(fresh)
    written = call(solver, values, out=out)
    assert sorted(written) == sorted(fresh) == sorted(solver.outputs + ["assembled"])
    for name, value in fresh.items():
        assert written[name] is out[name]
        assert numpy.shares_memory(written[name], out[name])
        assert numpy.array_equal(bits(out[name]), bits(value)), name
    assert written.units == call(solver, values).units


@pytest.mark.parametrize("n", SIZES)
def test_a_result_is_an_out_of_the_next_call_of_its_shape(solvers, n):
    solver = solvers["full"]
    result = call(solver, arguments(n))
    rows = {name: value for name, value in result.items()}
    again = call(solver, arguments(n, shift=0.3), out=result)
    expected = {name: value.copy() for name, value in call(solver, arguments(n, shift=0.3)).items()}
    for name, value in expected.items():
        assert again[name] is rows[name]
        assert numpy.array_equal(bits(again[name]), bits(value)), name


def _spans(result) -> list[tuple[int, int]]:
    return sorted((value.__array_interface__["data"][0], value.nbytes) for value in result.values())


@pytest.mark.parametrize("n", SIZES)
@pytest.mark.parametrize("kind", ["positions", "full"])
def test_the_outputs_of_one_compiled_call_are_one_block(solvers, backend, kind, n):
    if backend != "compiled":
        pytest.skip("the NumPy module's outputs are its own arrays")
    result = call(solvers[kind], arguments(n))
    spans = _spans(result)
    for (start, size), (following, _) in zip(spans, spans[1:]):
        assert following == start + size  # each output starts where the one before ends: one allocation
    if n > compiled_library.SMALL_CALL:
        block = result["coupler"].base
        assert all(value.base is block and numpy.shares_memory(value, block) for value in result.values())


def test_a_held_block_is_never_written_again_and_a_dropped_one_is_reused(solvers, backend):
    if backend != "compiled":
        pytest.skip("the NumPy module allocates its own arrays")
    solver = solvers["full"]
    n = 5000
    first = call(solver, arguments(n))
    kept = {name: value.copy() for name, value in first.items()}
    piece = first["rocker"][100:200]  # a view of a row, held after the result is dropped
    address = first["coupler"].__array_interface__["data"][0]
    del first
    later = [call(solver, arguments(n, shift=0.1 * k)) for k in range(1, 2 * compiled_library.KEPT_BLOCKS + 2)]
    assert numpy.array_equal(bits(piece), bits(kept["rocker"][100:200]))
    assert all(result["coupler"].__array_interface__["data"][0] != address for result in later)
    held = later[0]
    copy = {name: value.copy() for name, value in held.items()}
    made = {result["coupler"].__array_interface__["data"][0] for result in later}
    for _ in range(3):
        made.add(call(solver, arguments(n, shift=2.0))["coupler"].__array_interface__["data"][0])
    for name, value in copy.items():
        assert numpy.array_equal(bits(held[name]), bits(value)), name
    # dropped: the next calls write the blocks of before (no new pages), never one still held
    del piece, later, held
    # (the first block among them: kept while the caller held results, KEPT_LARGE_MOST, and free once piece is gone)
    again = [call(solver, arguments(n))["coupler"].__array_interface__["data"][0] for _ in range(6)]
    assert set(again) <= made | {address}


def _bad_outs(solver: Solver, values: dict) -> list[tuple[str, dict, str]]:
    """(what is wrong, the out given, what the message must say)."""
    good = empty_like(call(solver, values))
    n = len(values["theta"])
    read_only = numpy.empty(n)
    read_only.flags.writeable = False
    cases = [
        ("wrong shape", {**good, "rocker": numpy.empty(n + 1)}, "out['rocker'] must have the call's shape"),
        ("wrong dtype", {**good, "rocker": numpy.empty(n, dtype=numpy.float32)},
         "out['rocker'] must have dtype float64, got float32"),
        ("flag as float", {**good, "assembled": numpy.empty(n)}, "out['assembled'] must have dtype bool"),
        ("not contiguous", {**good, "coupler": numpy.empty(2 * n)[::2]}, "out['coupler'] must be C-contiguous"),
        ("missing output", {k: v for k, v in good.items() if k != "rocker"},
         "out has no array for the output 'rocker'"),
        ("missing assembled", {k: v for k, v in good.items() if k != "assembled"},
         "out has no array for the output 'assembled'"),
        ("unknown output", {**good, "rocker_sped": numpy.empty(n)}, "out['rocker_sped']: the call has no output"),
        ("a list", {**good, "rocker": [0.0] * n}, "out['rocker'] must be a NumPy array, got list"),
        ("read-only", {**good, "rocker": read_only}, "out['rocker'] must be writable"),
        ("overlapping outputs", {**good, "rocker": good["coupler"]}, "out['rocker'] overlaps out['coupler']"),
        ("overlapping an argument", {**good, "coupler": values["theta"]}, "out['coupler'] overlaps the argument theta"),
    ]
    if "singular" in good:
        cases.append(("missing singular", {k: v for k, v in good.items() if k != "singular"},
                      "out has no array for the output 'singular'"))
    return cases


@pytest.mark.parametrize("n", SIZES)
@pytest.mark.parametrize("kind", ["positions", "full"])
def test_a_bad_out_is_refused_naming_the_output_and_nothing_is_written(solvers, kind, n):
    solver = solvers[kind]
    values = arguments(n)
    for what, out, message in _bad_outs(solver, values):
        before = {name: value.copy() for name, value in out.items() if isinstance(value, numpy.ndarray)}
        theta = values["theta"].copy()
        with pytest.raises(ValueError) as raised:
            call(solver, values, out=out)
        assert message in str(raised.value), (what, str(raised.value))
        for name, value in before.items():
            assert numpy.array_equal(bits(out[name]), bits(value)), (what, name)
        assert numpy.array_equal(values["theta"], theta)
    with pytest.raises(ValueError, match="out must be a dict of NumPy arrays"):
        call(solver, values, out=[numpy.empty(n)])


def test_small_results_kept_a_few_calls_are_never_overwritten_and_cost_no_new_block(solvers, backend):
    if backend != "compiled":
        pytest.skip("the compiled small-call path's blocks")
    solver = solvers["full"]
    function = solver._compiled
    kept_blocks = function._entries if function._plan is not None else function._kept
    held: list = []
    made: dict[int, object] = {}  # every block this function has kept, held here so that no id is reused
    for step in range(40):
        values = arguments(10, shift=0.01 * step)
        result = call(solver, values)
        held = (held + [(result, {name: value.copy() for name, value in result.items()})])[-4:]
        for kept, copy in held:  # the four results held so far are untouched by the calls since
            for name, value in copy.items():
                assert numpy.array_equal(bits(kept[name]), bits(value)), (step, name)
        made.update((id(block), block) for block in kept_blocks)
    # four results held at a time: answered from the blocks kept before, not one new block a call
    assert len(made) <= compiled_library.KEPT_OUTPUTS


@pytest.mark.parametrize("n", SIZES)
@pytest.mark.parametrize("kept_for", range(1, 21))
def test_a_kept_result_is_never_overwritten_and_equals_a_fresh_call_bit_for_bit(backend, n, kept_for):
    """Each result kept for ``kept_for`` calls (more than the blocks kept for reuse, from 9 on) stays as it was,
    and equals, bit for bit, the same call on a solver of its own; the NumPy module agrees to rounding."""
    solver, fresh = (Solver(fourbar(), FULL, backend=backend) for _ in range(2))
    reference = Solver(fourbar(), FULL, backend="numpy")
    held: list = []
    for step in range(kept_for + 12):
        values = arguments(n, shift=0.37 * step)
        result = call(solver, values)
        expected = {name: value.copy() for name, value in call(fresh, values).items()}
        for name, value in expected.items():
            assert numpy.array_equal(bits(result[name]), bits(value)), (step, name)
        if step % 5 == 0:  # the NumPy module's answer: an independent evaluation of the same formulas
            independent = call(reference, values)
            assert numpy.array_equal(independent["assembled"], result["assembled"])
            for name in FULL:
                numpy.testing.assert_allclose(result[name], independent[name], rtol=1e-8, atol=1e-10)  # (near a toggle)
        held = (held + [(result, expected)])[-kept_for:]
        for kept, copy in held:
            for name, value in copy.items():
                assert numpy.array_equal(bits(kept[name]), bits(value)), (step, name)


def test_a_call_of_several_chunks_equals_its_values_called_one_by_one_and_refuses_a_value_in_the_last(backend):
    """A call of more values than one fused chunk (codegen.c.FUSED_CHUNK: checked and evaluated a chunk at a
    time) gives each value what a call of that value alone gives, bit for bit; a bad length in its last chunk
    is refused by name, fresh outputs and out= alike."""
    if backend != "compiled":
        pytest.skip("the compiled call's chunks (NumPy's own loops round a lone value and an array apart)")
    from symlink.codegen.c import FUSED_CHUNK
    solver = Solver(fourbar(), FULL, backend=backend)
    n = 2 * FUSED_CHUNK + 37
    values = arguments(n)
    values["b"] = numpy.linspace(64.0, 68.0, n)  # a per-value length too
    result = {name: value.copy() for name, value in call(solver, values).items()}
    for k in (0, FUSED_CHUNK - 1, FUSED_CHUNK, 2 * FUSED_CHUNK + 5, n - 1):
        alone = call(solver, {**values, "theta": values["theta"][k:k + 1], "b": values["b"][k:k + 1]})
        for name, value in alone.items():
            assert numpy.array_equal(bits(value), bits(result[name][k:k + 1])), (k, name)
    out = empty_like(result)
    bad = values["b"].copy()
    bad[n - 3] = -1.0
    for given in ({}, {"out": out}):
        with pytest.raises(ValueError, match="b must be a positive finite length, got -1.0"):
            call(solver, {**values, "b": bad}, **given)


def test_strided_and_single_value_arrays_give_what_contiguous_arrays_and_numbers_give(backend):
    solver = Solver(fourbar(), FULL, backend=backend)
    n = 5000
    values = arguments(n)
    expected = {name: value.copy() for name, value in call(solver, values).items()}
    every_other = numpy.empty(2 * n)
    every_other[::2] = values["theta"]
    reversed_theta = values["theta"][::-1].copy()[::-1]  # a negative step over the same values
    for theta in (every_other[::2], reversed_theta):
        for given in ({}, {"out": empty_like(expected)}):
            got = call(solver, {**values, "theta": theta, "a": numpy.array([60.0])}, **given)
            for name, value in expected.items():
                assert numpy.array_equal(bits(got[name]), bits(value)), name


def test_two_threads_making_large_calls_at_once_get_their_own_results(backend):
    """Large compiled calls run with the GIL released: two threads calling one solver at once (new outputs,
    some kept a few calls, and out=) each get their own call's values, and no kept result is written again."""
    import threading
    solver = Solver(fourbar(), FULL, backend=backend)
    n = 3 * 4096  # more values than a call holding the GIL takes
    inputs = [arguments(n, shift=0.2 * k) for k in range(4)]
    expected = [{name: value.copy() for name, value in call(solver, values).items()} for values in inputs]
    failures: list[str] = []

    def work(offset: int) -> None:
        held: list = []
        out = empty_like(expected[0])
        for step in range(40):
            k = (step + offset) % len(inputs)
            result = call(solver, inputs[k], **({"out": out} if step % 3 == 0 else {}))
            held = (held + [(k, result)])[-3:] if step % 3 else held
            for j, kept in held + [(k, result)]:
                if not all(numpy.array_equal(bits(kept[name]), bits(expected[j][name])) for name in expected[j]):
                    failures.append(f"thread {offset}, step {step}: result of input {j} changed")
                    return

    threads = [threading.Thread(target=work, args=(offset,)) for offset in (0, 1)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not failures, failures[:3]
