"""The NumPy printer: CSE, no SymPy or Piecewise in the output, broadcasting, assembly mask, escaped docstrings,
checked arguments."""
import ast
import collections
import inspect
import warnings
from pathlib import Path

import numpy
import pytest
import sympy as sp

from symlink.mechanism.catalog import fourbar
from symlink.codegen.numpy import _arguments, docstring_text, export_files, load_numpy_module, numpy_module


def test_common_subexpressions_are_computed_once():
    source = numpy_module([("f", fourbar().program(["coupler_accel", "rocker_accel"]), "")])
    function = next(n for n in ast.parse(source).body if isinstance(n, ast.FunctionDef) and n.name == "_f_block")
    values = [ast.dump(node.value) for node in function.body if isinstance(node, ast.Assign)]
    assert len(values) > 20
    calls = collections.Counter(ast.dump(n) for v in function.body if isinstance(v, ast.Assign)
                                for n in ast.walk(v.value) if isinstance(n, ast.Call))
    assert len(values) == len(set(values))
    assert max(calls.values()) == 1, [c for c, k in calls.items() if k > 1]


def test_no_sympy_no_piecewise_no_eval():
    source = numpy_module([("f", fourbar().program(fourbar().output_names()), "")])
    assert "sympy" not in source and "Piecewise" not in source and "select(" not in source
    assert "eval(" not in source


def test_constant_outputs_broadcast_to_the_input_shape():
    namespace = load_numpy_module(numpy_module([("f", fourbar().program(["A_x", "D_x", "rocker"]), "")]))
    result = namespace["f"](numpy.zeros(4), 20, 66, 56, 80)
    assert result["A_x"].shape == (4,) and result["D_x"].tolist() == [80.0] * 4


def test_module_header_names_versions():
    source = numpy_module([("f", fourbar().program(["rocker"]), "")], regenerate="python derivations/x.py")
    assert f"SymPy {sp.__version__}" in source and "Regenerate with: python derivations/x.py" in source


def test_titles_and_docstrings_cannot_break_out_of_the_module():
    hostile = 'x""" + __import__("os").system("echo no") + """\\'
    source = numpy_module([("f", fourbar().program(["rocker"]), hostile)], title=hostile, regenerate=hostile)
    tree = ast.parse(source)  # still a docstring, the import, TOLERANCE, BLOCK and functions: nothing else would run
    assert ast.get_docstring(tree).startswith(hostile)
    assert [type(n).__name__ for n in tree.body] == ["Expr", "Import", "Assign", "Assign"] + ["FunctionDef"] * 9
    function = next(n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "f")
    assert ast.get_docstring(function).startswith(hostile)
    assert [type(n).__name__ for n in function.body[:2]] == ["Expr", "Assign"]


def test_docstring_text_reads_back_as_the_text():
    for text in ['"', '""', '"""', "\\", "a\\", '\\"""', "tab\there", "nul\x00", "line\u2028sep", "é"]:
        assert ast.literal_eval('"""' + docstring_text(text) + '\n"""') == text + "\n", text


def test_export_files_is_one_module():
    files = export_files(fourbar(), "fb", [("positions", ["rocker"], "Rocker."), ("speeds", ["rocker_speed"], "")],
                         "Four-bar.", "make it")
    assert list(files) == ["fb.py"]
    namespace = load_numpy_module(files["fb.py"])
    assert {"positions", "speeds"} <= set(namespace)


# --- argument checks (every generated function; check=False skips them) -------------------------------

GOOD = dict(theta=numpy.array([0.0, 1.0, 2.0]), a=20.0, b=66.0, c=56.0, d=80.0, branch=1)


def _generated_fourbar():
    """The committed generated module (as a user copies it), not one generated in this test."""
    path = Path(__file__).resolve().parents[2] / "generated" / "fourbar.py"
    return load_numpy_module(path.read_text(encoding="utf-8"))


@pytest.mark.parametrize("change, message", [
    (dict(branch=0), r"branch must be \+1 or -1, got 0.0"),
    (dict(branch=2), r"branch must be \+1 or -1, got 2.0"),
    (dict(branch=0.5), r"branch must be \+1 or -1, got 0.5"),
    (dict(branch=float("nan")), r"branch must be \+1 or -1, got nan"),
    (dict(branch=[1, -1, 0]), r"branch must be \+1 or -1, got 0.0"),
    (dict(a=float("inf")), "a must be a positive finite length, got inf"),
    (dict(b=0.0), "b must be a positive finite length, got 0.0"),
    (dict(c=-56.0), "c must be a positive finite length, got -56.0"),
    (dict(d=[80.0, float("nan"), 80.0]), "d must be a positive finite length, got nan"),
    (dict(theta=[0.0, float("inf")]), "theta must be finite, got inf"),
    (dict(theta=float("nan")), "theta must be finite, got nan"),
    (dict(thetadot=float("-inf")), "thetadot must be finite, got -inf"),
    (dict(theta=numpy.array([0.0, 1.0 + 1e-9j])), r"theta must be real numbers, got complex128 values \(its imaginary"),
    (dict(a=20 + 0j), "a must be real numbers, got complex128"),
    (dict(theta=numpy.array([0.0, 1j], dtype=object)), "theta must be real numbers, got object values"),
    (dict(theta="0.5"), "theta must be real numbers, got <U3 values"),
    (dict(theta=numpy.zeros(3), a=numpy.ones(4) * 20), r"do not broadcast together: theta has shape \(3,\), a has "
                                                        r"shape \(4,\)"),
])
def test_generated_functions_refuse_bad_arguments(change, message):
    function = _generated_fourbar()["velocities"]
    values = {**GOOD, "thetadot": 1.0, **change}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # refused before NumPy could warn (of a dropped imaginary part, say)
        with pytest.raises(ValueError, match=message):
            function(**values)


def test_good_arguments_of_every_kind_pass_the_check():
    function = _generated_fourbar()["positions"]
    expected = function(**GOOD, check=False)["rocker"]
    for values in [GOOD, {**GOOD, "theta": GOOD["theta"].astype(numpy.float32)}, {**GOOD, "a": 20, "branch": -1},
                   {**GOOD, "theta": list(GOOD["theta"]), "branch": numpy.array([1, -1, 1])},
                   {**GOOD, "a": numpy.array([[20.0], [21.0]])}, {**GOOD, "branch": True},
                   {**GOOD, "theta": numpy.array([0.0, 1.0, 2.0], dtype=object)}]:
        result = function(**values)
        assert result["rocker"].shape == numpy.broadcast_shapes(*(numpy.shape(v) for v in values.values()))
    assert numpy.array_equal(function(**GOOD)["rocker"], expected)


def test_check_false_skips_the_check():
    function = _generated_fourbar()["positions"]
    result = function(**{**GOOD, "branch": 0}, check=False)  # no error: the caller vouched for the arguments
    assert result["rocker"].shape == (3,)
    with pytest.raises(ValueError, match="branch must be"):
        function(**{**GOOD, "branch": 0}, check=True)


def test_every_generated_module_embeds_the_check_and_imports_numpy_only():
    folder = Path(__file__).resolve().parents[2] / "generated"
    for path in sorted(folder.glob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        imports = [alias.name for node in ast.walk(tree) if isinstance(node, ast.Import) for alias in node.names]
        imports += [node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)]
        assert imports == ["numpy"], path.name
        public = [n for n in tree.body if isinstance(n, ast.FunctionDef) and not n.name.startswith("_")]
        assert public and all([a.arg for a in n.args.kwonlyargs] == ["check"] for n in public), path.name
        assert any(isinstance(n, ast.FunctionDef) and n.name == "_arguments" for n in tree.body), path.name


def test_checked_arguments_is_the_function_every_module_embeds():
    source = numpy_module([("f", fourbar().program(["rocker"]), "")])
    assert inspect.getsource(_arguments) in source


# --- blocked evaluation: bit for bit the unblocked result, memory bounded by a block --------------------

def _random_arguments(function, rng, shape):
    """Random arguments of a generated function: angles anywhere, lengths over a decade (many do not assemble)."""
    values = {}
    for name, parameter in inspect.signature(function).parameters.items():
        if parameter.kind is inspect.Parameter.KEYWORD_ONLY:
            continue
        if name.startswith("branch"):
            values[name] = rng.choice([-1.0, 1.0], size=shape)
        elif parameter.default is not inspect.Parameter.empty:  # a rate or an acceleration of the input
            values[name] = rng.normal(0.0, 5.0, size=shape)
        else:
            values[name] = rng.uniform(-4.0, 4.0, size=shape)
    return values


@pytest.mark.parametrize("stem", ["fourbar", "watt2", "jansen", "slider_crank", "fivebar"])
def test_blocked_evaluation_is_bit_identical_to_one_call(stem):
    path = Path(__file__).resolve().parents[2] / "generated" / f"{stem}.py"
    namespace = load_numpy_module(path.read_text(encoding="utf-8"))
    namespace["BLOCK"] = 7  # many blocks and a ragged last one, even for a short input
    rng = numpy.random.default_rng(13)
    public = [name for name in namespace if not name.startswith("_") and callable(namespace[name])
              and name[0].islower() and "check" in inspect.signature(namespace[name]).parameters]
    assert public
    for name in public:
        function, kernel = namespace[name], namespace[f"_{name}_block"]
        for shape in [(101,), (23, 5), (1, 40)]:
            values = _random_arguments(function, rng, shape)
            for argument in list(values)[1:]:  # lengths positive; some arguments shared (scalars, broadcast rows)
                if rng.random() < 0.5:
                    values[argument] = values[argument].flat[0] if rng.random() < 0.5 else values[argument][:1]
                values[argument] = numpy.abs(values[argument]) + 0.5 if not argument.startswith("branch") \
                    else values[argument]
            blocked = function(**values, check=False)
            arrays = [numpy.asarray(values[a], dtype=float) for a in inspect.signature(kernel).parameters]
            whole = kernel(*arrays)
            assert list(blocked) == list(blocked)[:len(whole)] and len(blocked) == len(whole)
            for key, expected in zip(blocked, whole):
                expected = numpy.broadcast_to(expected, shape)
                assert blocked[key].shape == shape and blocked[key].dtype == expected.dtype, (stem, name, key)
                assert numpy.array_equal(blocked[key], expected, equal_nan=True), (stem, name, key, shape)
            assembled = blocked["assembled"]
            if name == public[0] and shape == (101,):
                assert 0 < assembled.sum() < assembled.size, (stem, name)  # NaN patterns of both kinds compared


def test_a_long_input_needs_about_one_block_beyond_its_outputs():
    import tracemalloc
    namespace = _generated_fourbar()
    function = namespace["accelerations"]
    theta = numpy.linspace(0.0, 6.0, 200_000)
    tracemalloc.start()
    try:
        before = tracemalloc.get_traced_memory()[0]
        result = function(theta, 20.0, 66.0, 56.0, 80.0, 1, 10.5, 2.0, check=False)
        peak = tracemalloc.get_traced_memory()[1] - before
    finally:
        tracemalloc.stop()
    outputs = sum(array.nbytes for array in result.values())
    block = namespace["BLOCK"] * 8
    assert peak - outputs < 64 * block  # an unblocked call holds dozens of input-sized temporaries (~100 MB here)


# --- fewer NumPy calls, the same bits ---------------------------------------------------------------------

def test_a_loop_unit_is_the_largest_power_of_two_not_above_the_mean_length():
    """Against the exponent of each number's hexadecimal form (``0x1.8p+3`` is 1.5 * 2**3), at powers of two and next to them."""
    import math
    unit = load_numpy_module(numpy_module([("f", fourbar().program(["rocker"]), "")]))["_power_of_two_below"]
    powers = numpy.ldexp(1.0, numpy.arange(-1020, 1023))
    rng = numpy.random.default_rng(11)
    values = numpy.concatenate([powers, numpy.nextafter(powers, 0.0), numpy.nextafter(powers, numpy.inf),
                                10.0 ** rng.uniform(-300, 300, 2000)])
    expected = [math.ldexp(1.0, int(float(v).hex().split("p")[1])) for v in values]
    assert unit(values).tolist() == expected
    assert [unit(float(v)) for v in values[:50]] == expected[:50]  # one number, as for lengths given alone


def test_a_sum_that_starts_with_a_negative_term_is_printed_as_a_difference():
    from symlink.codegen.numpy import NumPyCodePrinter
    x, y, z, w = sp.symbols("x y z w")
    printer = NumPyCodePrinter()
    assert printer.doprint(-x + y) == "y - x"
    assert printer.doprint(-x * y + z) == "z - x*y"
    assert printer.doprint(-x - y) == "-x - y"  # nothing positive to start with: as SymPy prints it
    from sympy.printing.numpy import NumPyPrinter
    assert NumPyPrinter().doprint(-2 * x + y + z) == "-2*x + y + z"  # SymPy's own order of the terms
    assert printer.doprint(-2 * x + y + z) == "y - 2.0*x + z"  # only the first two terms trade places
    assert printer.doprint(w - x + y) == NumPyPrinter().doprint(w - x + y) == "w - x + y"  # starts positive: as is
    rng = numpy.random.default_rng(5)
    a, b, c = (rng.normal(size=1000) * 10.0 ** rng.integers(-200, 200, size=1000) for _ in range(3))
    with numpy.errstate(over="ignore", invalid="ignore"):  # infinities and NaN among them
        assert ((-a) * b + c).tobytes() == (c - a * b).tobytes()  # the same bits: IEEE negation is exact
        assert ((-a) + b + c).tobytes() == (b - a + c).tobytes()


def test_a_short_input_returns_fresh_arrays_that_share_no_memory():
    namespace = _generated_fourbar()
    theta = numpy.linspace(0.0, 6.0, 50)
    result = namespace["accelerations"](theta, 20.0, 66.0, 56.0, 80.0, 1, 10.5, 2.0)
    arrays = list(result.values())
    assert all(array.shape == theta.shape for array in arrays)
    assert not any(numpy.shares_memory(array, theta) for array in arrays)
    assert not any(numpy.shares_memory(first, second) for k, first in enumerate(arrays) for second in arrays[k + 1:])
