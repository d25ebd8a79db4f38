"""The C export: compiled with the system compiler here, called through ctypes, compared with the NumPy module.

The C is compiled exactly as exported (plain C99, ``-pedantic -Wall -Wextra
-Werror``, no symlink flags) and checked against the NumPy module generated
from the same program, for every catalog entry that has a closed form, on
random arguments (both branches, assemblies that fail included), and for the
four-bar against the independent 50-digit reference of ``tests/references.py``.
"""
from __future__ import annotations

from dataclasses import replace

import ctypes
import re
import shutil
import subprocess

import numpy
import pytest
import sympy as sp

from export_checks import (angles_of, assert_agree, assert_atan2_angles, atan2_angle_case, closed_form_catalog, export_sets,
                           random_arguments, rounding_spread)
from references import SEED003_LINKAGE, mp_fourbar, seed003_positions
from symlink.codegen.c import c_code, c_comment, c_function, c_identifier, c_library, CPrinter
from symlink.codegen.numpy import load_numpy_module, numpy_module
from symlink.symbolic.linkage import Program
from symlink.symbolic.position import TOLERANCE, ClampedSqrt
from symlink.io.scene import catalog_linkage

STRICT = ["-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-O2", "-fPIC", "-shared"]


def _compiler() -> str:
    for name in ("cc", "gcc", "clang"):
        if shutil.which(name):
            return name
    pytest.skip("no C compiler (cc, gcc or clang) on PATH: the generated C is not compiled")


def build(tmp_path, header: str, source: str, name: str) -> ctypes.CDLL:
    """Write the two files and compile them strictly into a shared library."""
    (tmp_path / f"{name}.h").write_text(header)
    (tmp_path / f"{name}.c").write_text(source)
    result = subprocess.run([_compiler(), *STRICT, "-o", f"{name}.so", f"{name}.c", "-lm"], cwd=tmp_path,
                            capture_output=True, text=True, check=False)
    if result.returncode and "math.h" in result.stderr and "No such file" in result.stderr:
        pytest.skip(f"the C compiler has no C library headers (install libc6-dev): {result.stderr.strip()}")
    assert result.returncode == 0, result.stderr
    return ctypes.CDLL(str(tmp_path / f"{name}.so"))


def call(library: ctypes.CDLL, function, values: dict, steps: dict | None = None,
         count: int | None = None) -> dict[str, numpy.ndarray]:
    """Call a generated loop on 1-d arrays (step 1) or scalars (step 0) written independently of symlink.numeric.compiled."""
    arrays = [numpy.ascontiguousarray(values[a], dtype=numpy.float64) for a in function.arguments]
    count = max(a.size for a in arrays) if count is None else count
    outputs = [numpy.full(count, 7, dtype=numpy.uint8) if flag else numpy.full(count, 12345.0)
               for flag in function.flags]
    assembled = numpy.full(count, 7, dtype=numpy.uint8)
    arguments = []
    for name, array in zip(function.arguments, arrays):
        step = (steps or {}).get(name, 0 if array.size == 1 else 1)
        arguments += [ctypes.c_void_p(array.ctypes.data), ctypes.c_ssize_t(step)]
    entry = getattr(library, function.name)
    entry.restype = None
    entry(ctypes.c_size_t(count), *arguments, *(ctypes.c_void_p(o.ctypes.data) for o in outputs),
          ctypes.c_void_p(assembled.ctypes.data))
    for flags in [assembled] + [o for o, flag in zip(outputs, function.flags) if flag]:
        assert set(numpy.unique(flags)) <= {0, 1}
    outputs = [o.astype(bool) if flag else o for o, flag in zip(outputs, function.flags)]
    return {**dict(zip(function.outputs, outputs)), "assembled": assembled.astype(bool)}


@pytest.mark.parametrize("name", closed_form_catalog())
def test_every_catalog_entry_agrees_with_numpy(tmp_path, name):
    linkage = catalog_linkage(name)
    sets = export_sets(name)
    stem = name.replace("-", "_")
    functions = [c_function(linkage.program(outputs), f"{stem}_{set_name}", doc) for set_name, outputs, doc in sets]
    header, source = c_library(functions, stem, "test")
    assert "malloc" not in source and "free(" not in source
    assert [line for line in source.splitlines() if line.startswith("#include")] == [
        "#include <math.h>", "#include <stdint.h>", "#include <string.h>", f'#include "{stem}.h"']
    library = build(tmp_path, header, source, stem)
    module = load_numpy_module(numpy_module([(s, linkage.program(o), d) for s, o, d in sets]))
    for (set_name, outputs, _), function in zip(sets, functions):
        values = random_arguments(linkage, function.arguments, 400, seed=len(set_name))
        expected = module[set_name](**values)
        assembled = numpy.asarray(expected["assembled"])
        assert 40 < assembled.sum(), f"{name}: too few assembled samples to test"
        with numpy.errstate(all="ignore"):
            actual = call(library, function, values)
        assert_agree(actual, {k: numpy.asarray(v) for k, v in expected.items()},
                     angles_of(name, outputs), 1e-12, f"{name} {set_name}", rounding_spread(module[set_name], values))


def test_steps_broadcast_scalars_arrays_and_strides(tmp_path):
    linkage = catalog_linkage("fourbar")
    function = c_function(linkage.program(["coupler", "rocker_speed"]), "fb", "")
    library = build(tmp_path, *c_library([function], "fb"), "fb")
    count = 301  # more than one block of the loop (SYMLINK_BLOCK configurations)
    theta = numpy.linspace(-3, 3, count)
    lengths = numpy.linspace(15, 25, count)
    spread = numpy.zeros(3 * count)
    spread[::3] = theta  # theta at a step of 3 elements
    values = dict(theta=spread, a=lengths, b=66.0, c=56.0, d=80.0, branch=-1.0, thetadot=10.5)
    actual = call(library, function, values, steps={"theta": 3}, count=count)
    expected = load_numpy_module(numpy_module([("fb", linkage.program(["coupler", "rocker_speed"]), "")]))["fb"](
        theta=theta, a=lengths, b=66.0, c=56.0, d=80.0, branch=-1.0, thetadot=10.5)
    assert_agree(actual, {k: numpy.asarray(v) for k, v in expected.items()}, {"coupler"}, 1e-12)


def test_fourbar_matches_the_50_digit_reference_and_seed_003(tmp_path):
    linkage = catalog_linkage("fourbar")
    function = c_function(linkage.program(["coupler", "rocker", "coupler_speed", "rocker_speed",
                                           "coupler_accel", "rocker_accel"]), "fb", "")
    library = build(tmp_path, *c_library([function], "fb"), "fb")
    a, b, c, d = (SEED003_LINKAGE[k] for k in "abcd")
    theta = numpy.radians(numpy.arange(0.0, 360.0, 40.0) + 0.5)
    for branch in (1, -1):
        result = call(library, function, dict(theta=theta, a=a, b=b, c=c, d=d, branch=float(branch),
                                              thetadot=10.5, thetaddot=3.0))
        assert result["assembled"].all()
        hand_beta, hand_phi = seed003_positions(a, b, c, d, theta, branch)
        numpy.testing.assert_allclose(numpy.cos(result["rocker"] - hand_phi), 1.0, atol=1e-24)
        for i, angle in enumerate(theta):
            reference = mp_fourbar(a, b, c, d, float(angle), branch, 10.5, 3.0)
            for key, output in (("beta", "coupler"), ("phi", "rocker"), ("beta_speed", "coupler_speed"),
                                ("phi_speed", "rocker_speed"), ("beta_accel", "coupler_accel"),
                                ("phi_accel", "rocker_accel")):
                want = float(reference[key])
                assert abs(result[output][i] - want) <= 1e-12 * max(1.0, abs(want)), (branch, angle, key)


def test_unassembled_configurations_are_nan_and_flagged(tmp_path):
    linkage = catalog_linkage("fourbar")
    function = c_function(linkage.program(["rocker", "C_x"]), "fb", "")
    library = build(tmp_path, *c_library([function], "fb"), "fb")
    # a = 50 cannot pass theta = 0 with b + c = 30 + 40 < |a - d| + ... : crank range is limited.
    theta = numpy.radians([0.0, 90.0, 180.0])
    result = call(library, function, dict(theta=theta, a=50.0, b=30.0, c=40.0, d=45.0, branch=1.0))
    for angle, assembled in zip(theta, result["assembled"]):
        try:
            mp_fourbar(50.0, 30.0, 40.0, 45.0, float(angle), 1)
            reachable = True
        except ValueError:
            reachable = False
        assert bool(assembled) == reachable
    assert not result["assembled"].all() and result["assembled"].any()
    assert numpy.isnan(result["rocker"][~result["assembled"]]).all()
    assert numpy.isnan(result["C_x"][~result["assembled"]]).all()


def test_clamped_square_root_has_the_numpy_semantics(tmp_path):
    x, scale = sp.symbols("x scale", real=True)
    root = sp.Symbol("Delta_1", real=True)
    program = Program((x, scale), ((root, ClampedSqrt(x, scale)),), {"root": root})
    function = c_function(program, "clamped", "")
    library = build(tmp_path, *c_library([function], "clamped"), "clamped")
    xs = numpy.array([4.0, 0.0, -0.0, -0.5 * TOLERANCE, -TOLERANCE, -2 * TOLERANCE, -1.0, numpy.nan, numpy.inf])
    result = call(library, function, dict(x=xs, scale=1.0))
    # By definition (ClampedSqrt's docstring): sqrt for x >= 0, 0 down to -TOLERANCE*scale, NaN below or for NaN.
    expected = numpy.array([2.0, 0.0, 0.0, 0.0, 0.0, numpy.nan, numpy.nan, numpy.nan, numpy.inf])
    numpy.testing.assert_array_equal(result["root"], expected)
    assert not numpy.signbit(result["root"][2])  # sqrt(-0.0) would be -0.0; NumPy's maximum gives +0.0
    numpy.testing.assert_array_equal(result["assembled"], numpy.isfinite(expected))
    reference = load_numpy_module(numpy_module([("clamped", program, "")]))["clamped"](x=xs, scale=1.0, check=False)
    numpy.testing.assert_array_equal(result["root"], reference["root"])


def test_true_false_outputs_are_unsigned_char_arrays(tmp_path):
    x = sp.Symbol("x", real=True)
    root = sp.Symbol("Delta_1", real=True)
    program = Program((x,), ((root, ClampedSqrt(x, 1)),),
                      {"root": root, "toggle": sp.Eq(root, 0), "never": sp.false, "either": sp.Or(x > 3, x < -3)})
    function = c_function(program, "flags", "")
    assert function.flags == (False, True, True, True)
    assert "double *root, unsigned char *toggle, unsigned char *never, unsigned char *either" in function.prototype
    library = build(tmp_path, *c_library([function], "flags"), "flags")
    xs = numpy.array([4.0, 0.0, -1.0])
    result = call(library, function, dict(x=xs))
    assert result["toggle"].tolist() == [False, True, False]
    assert result["never"].tolist() == [False] * 3
    assert result["either"].tolist() == [True, False, False]
    reference = load_numpy_module(numpy_module([("flags", program, "")]))["flags"](x=xs)
    for key in ("toggle", "never", "either"):
        numpy.testing.assert_array_equal(result[key], numpy.broadcast_to(reference[key], xs.shape))


def test_printer_writes_small_powers_as_products_and_exact_literals():
    x, y = sp.symbols("x y", real=True)
    printer = CPrinter()
    assert printer.doprint(x**2) == "(x*x)"
    assert printer.doprint(1 / x) == "1.0/x"
    assert printer.doprint(x**-2) == "1.0/(x*x)"
    assert printer.doprint((x + y)**4) == "(((x + y)*(x + y))*((x + y)*(x + y)))"
    assert printer.doprint(x**5) == "pow(x, 5.0)"
    assert printer.doprint(sp.sqrt(x)) == "sqrt(x)"
    assert printer.doprint(sp.pi * x) == f"{numpy.pi!r}*x"  # no M_PI: it is not C99
    assert printer.doprint(sp.Float(0.1) * x) == "0.1*x"
    assert printer.doprint(sp.atan2(y, x)) == "atan2(y, x)"
    assert printer.doprint(sp.Abs(x)) == "fabs(x)"


def test_names_that_are_not_c_identifiers_are_refused():
    assert c_identifier("theta_1") == "theta_1"
    for bad in ("int", "2x", "a-b", "symlink_x", "θ"):
        with pytest.raises(ValueError, match="C identifier"):
            c_identifier(bad)
    x = sp.Symbol("double", real=True)
    with pytest.raises(ValueError, match="'double'"):
        c_function(Program((x,), (), {"y": 2 * x}), "f", "")
    with pytest.raises(ValueError, match="at least one output"):
        c_function(Program((), (), {}), "f", "")
    program = catalog_linkage("fourbar").program(["rocker"])
    with pytest.raises(ValueError, match="repeat"):
        c_library([c_function(program, "f"), c_function(program, "f")], "lib")


def test_an_output_named_like_an_argument_gets_its_own_parameter(tmp_path):
    linkage = catalog_linkage("fourbar")
    program = linkage.program(["rocker"])
    program = replace(program, outputs={**program.outputs, "theta": program.arguments[0]})
    function = c_function(program, "fb", "")
    assert function.output_parameters == ("rocker", "theta_out")
    library = build(tmp_path, *c_library([function], "fb"), "fb")
    theta = numpy.array([0.1, 0.2])
    result = call(library, function, dict(theta=theta, a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0))
    numpy.testing.assert_array_equal(result["theta"], theta)


def test_c_code_header_declares_every_function_and_compiles_as_cpp(tmp_path):
    linkage = catalog_linkage("fourbar")
    header, source = c_code([("fb_positions", linkage.program(["coupler", "rocker"]), "Positions."),
                             ("fb_joints", linkage.program(["C_x", "C_y"]), "Joints.")], "fb", "Four-bar.")
    assert header.count("\nvoid fb_") == 2 and "SYMLINK_FB_H" in header
    if shutil.which("g++"):
        (tmp_path / "fb.h").write_text(header)
        (tmp_path / "use.cpp").write_text('#include "fb.h"\nint main() { return 0; }\n')
        result = subprocess.run(["g++", "-fsyntax-only", "-Wall", "-Werror", "use.cpp"], cwd=tmp_path,
                                capture_output=True, text=True, check=False)
        assert result.returncode == 0, result.stderr


def test_comment_text_cannot_end_the_comment(tmp_path):
    assert c_comment("a */ b") == "/* a * / b */"
    for text in ("**/*/", "/*/", "*/*", "???/", "a ??/"):
        inside = c_comment(text)[2:-2]
        assert "*/" not in inside and "/*" not in inside and "??" not in inside, text
    hostile = "Title */ int injected(void) { return 1; } /* ??/"
    linkage = catalog_linkage("fourbar")
    header, source = c_code([("fb_rocker", linkage.program(["rocker"]), hostile)], "fb", title=hostile,
                            regenerate=hostile)
    library = build(tmp_path, header, source, "fb")  # compiles strictly: the text stayed inside comments
    assert not hasattr(library, "injected") and hasattr(library, "fb_rocker")


def test_export_files_are_a_header_and_a_source():
    from symlink.codegen.c import export_files
    files = export_files(catalog_linkage("fourbar"), "fb", [("positions", ["rocker"], "Rocker.")], "Four-bar.")
    assert list(files) == ["fb.h", "fb.c"] and "void fb_positions(size_t n," in files["fb.h"]


def test_sines_and_cosines_of_solved_angles_come_from_their_atan2(tmp_path):
    """cos and sin of q = atan2(y, x), and of q - t, without calls: x/r, y/r and the addition theorems.

    Checked against NumPy's own cos(arctan2(y, x)) (zeros of both signs included, where atan2
    decides the quadrant) and the generated C calls no sin or cos of q.
    """
    program, arguments, expected = atan2_angle_case()
    function = c_function(program, "angles", "")
    kernel = function.definition.split("SYMLINK_LOOP")[0]
    assert "sin(q" not in kernel and "cos(q" not in kernel and "symlink_cos_atan2(" in kernel
    assert kernel.count("sin(") - kernel.count("_sin(") == 1  # sin(t), once, and no other call
    library = build(tmp_path, *c_library([function], "angles"), "angles")
    result = call(library, function, arguments)
    assert_atan2_angles(result, expected)
    assert result["assembled"].all()


@pytest.mark.parametrize("name", ["fourbar", "watt2", "jansen"])
def test_full_kinematics_call_sin_and_cos_no_more_than_positions(name):
    linkage = catalog_linkage(name)
    unknowns = [q.name for q in linkage.unknowns]
    full = unknowns + [f"{q}dot" for q in unknowns] + [f"{q}ddot" for q in unknowns]

    def calls(outputs):
        kernel = c_function(linkage.program(outputs), "f", "").definition.split("SYMLINK_LOOP")[0]
        return sum(kernel.count(f"{f}(") - kernel.count(f"_{f}(") for f in ("sin", "cos", "atan2"))

    assert calls(full) == calls(unknowns)


def test_a_loop_unit_is_the_exponent_of_the_mean_length_bit_for_bit(tmp_path):
    """The C unit (the bits of x with the mantissa cleared) against the exponent of each number's hexadecimal form,
    at powers of two and next to them, and equal to the NumPy module's (``frexp``): no logarithm, no pow."""
    import math
    from symlink.symbolic.position import PowerOfTwoBelow
    x = sp.Symbol("x", positive=True)
    function = c_function(Program((x,), (), {"unit": PowerOfTwoBelow(x)}), "unit", "")
    assert "log" not in function.definition and "pow(" not in function.definition
    library = build(tmp_path, *c_library([function], "units"), "units")
    powers = numpy.ldexp(1.0, numpy.arange(-1020, 1023))
    rng = numpy.random.default_rng(12)
    values = numpy.concatenate([powers, numpy.nextafter(powers, 0.0), numpy.nextafter(powers, numpy.inf),
                                10.0 ** rng.uniform(-300, 300, 2000)])
    expected = numpy.array([math.ldexp(1.0, int(float(v).hex().split("p")[1])) for v in values])
    unit = call(library, function, {"x": values})["unit"]
    assert unit.view(numpy.int64).tolist() == expected.view(numpy.int64).tolist()
    numpy_unit = load_numpy_module(numpy_module([("f", Program((x,), (), {"unit": PowerOfTwoBelow(x)}), "")]))["f"]
    lengths = (values >= 1e-305) & (values <= 1e305)  # what a generated NumPy function takes as a length
    assert numpy_unit(values[lengths])["unit"].view(numpy.int64).tolist() == expected[lengths].view(numpy.int64).tolist()


def test_a_loop_units_reciprocal_is_the_division_bit_for_bit(tmp_path):
    """1/unit from the exponent bits (no division) equals 2.0**-k (exact: a power of two's reciprocal) for every
    unit 2**k a positive normal mean length has, k from -1022 to 1023, the subnormal 2**-1023 included, and
    infinity (1/0) for a unit of 0; the four-bar's loop uses it instead of a division."""
    import math
    from symlink.symbolic.position import PowerOfTwoBelow
    x = sp.Symbol("x", positive=True)
    unit = sp.Symbol("size_1", positive=True)
    program = Program((x,), ((unit, PowerOfTwoBelow(x)),), {"inverse": 1 / unit, "unit": unit})
    function = c_function(program, "inverse", "")
    assert "symlink_reciprocal_power_of_two(size_1)" in function.definition
    library = build(tmp_path, *c_library([function], "inverses"), "inverses")
    exponents = numpy.arange(-1022, 1024)
    values = numpy.array([math.ldexp(1.0, int(k)) for k in exponents])
    values = numpy.concatenate([values, numpy.nextafter(values[:-1], numpy.inf) * 1.5])  # inside an octave too
    expected = numpy.array([math.ldexp(1.0, -int(k)) for k in numpy.concatenate([exponents, exponents[:-1]])])
    result = call(library, function, {"x": values})
    assert result["unit"].view(numpy.int64).tolist() == numpy.concatenate([values[:2046], values[:2045]]).view(
        numpy.int64).tolist()
    assert result["inverse"].view(numpy.int64).tolist() == expected.view(numpy.int64).tolist()
    assert expected[2045] == 2.0 ** -1023 and 0 < expected[2045] < numpy.finfo(float).tiny  # the subnormal end
    below = call(library, function, {"x": numpy.array([0.0, 1e-310, 2.0 ** -1022 * 0.75])})  # a unit of 0: 1/0
    assert below["unit"].tolist() == [0.0, 0.0, 0.0] and below["inverse"].tolist() == [numpy.inf] * 3
    kernel = c_function(catalog_linkage("fourbar").program(["coupler", "rocker"]), "f", "").definition
    assert "symlink_reciprocal_power_of_two(" in kernel and "1.0/size" not in kernel


@pytest.mark.parametrize("name", ["fourbar", "watt2", "jansen"])
def test_a_loop_of_rates_carries_its_flags_in_32_bit_lanes_and_computes_the_same(tmp_path, name):
    """Positions keep 16-bit flag lanes, a loop with rates takes 32-bit ones (RATE_FLAG_LANE, measured faster);
    the lane is only how 1 and 0 are carried: the loop's outputs are bit for bit those of 16-bit lanes."""
    linkage = catalog_linkage(name)
    unknowns = [q.name for q in linkage.unknowns]
    full = unknowns + [f"{q}dot" for q in unknowns] + [f"{q}ddot" for q in unknowns] + ["singular"]
    positions = c_function(linkage.program(unknowns), "positions", "").definition
    rates = c_function(linkage.program(full), "rates", "")
    assert "unsigned short *restrict assembled" in positions and "unsigned int" not in positions
    assert "unsigned int *restrict assembled" in rates.definition and "unsigned short" not in rates.definition
    # the angles that only outputs read are computed last, after every rate (fewer values across atan2 calls)
    body = rates.definition.split("    out[0] =")[0].split("\n")
    values = [line for line in body if line.startswith("    const double ")]
    names = [line.split()[2] for line in values]
    read_later = {k for k, name in enumerate(names)
                  if any(re.search(r"\b" + name + r"\b", line.split(" = ", 1)[1]) for line in values[k + 1:])}
    last = [k for k, line in enumerate(values) if " = atan2(" in line and k not in read_later]
    assert last and last == list(range(len(values) - len(last), len(values)))
    header, source = c_library([rates], "lanes", "test")
    values = random_arguments(linkage, rates.arguments, 500, seed=3)
    (tmp_path / "wide").mkdir()
    (tmp_path / "narrow").mkdir()
    wide = call(build(tmp_path / "wide", header, source, "lanes"), rates, values)
    narrow_ = call(build(tmp_path / "narrow", header, source.replace("unsigned int", "unsigned short"), "lanes"),
                   rates, values)
    assert wide["assembled"].any() and (~wide["assembled"].astype(bool)).any()  # both kinds of configuration
    for key in wide:
        assert numpy.array_equal(wide[key], narrow_[key], equal_nan=True), key


@pytest.mark.parametrize("name", ["watt2", "jansen"])
def test_a_program_in_pieces_computes_what_one_loop_does_bit_for_bit(tmp_path, name):
    """Cut into pieces (each its own loop, values handed on in block arrays), a program exports as one strict
    C file whose function agrees with the NumPy module and, bit for bit, with the program as one loop."""
    linkage = catalog_linkage(name)
    unknowns = [q.name for q in linkage.unknowns]
    outputs = unknowns + [f"{q}dot" for q in unknowns] + [f"{q}ddot" for q in unknowns] + ["singular"]
    program = linkage.program(outputs)
    whole, cut = c_function(program, "whole", ""), c_function(program, "cut", "", piece_size=700)
    assert not whole.pieces and len(cut.pieces) >= 3
    header, source = c_library([whole, cut], "pieces", "test")
    assert [line for line in source.splitlines() if line.startswith("#include")] == [
        "#include <math.h>", "#include <stdint.h>", "#include <string.h>", '#include "pieces.h"']
    library = build(tmp_path, header, source, "pieces")
    values = random_arguments(linkage, whole.arguments, 300, seed=7)
    values["thetadot"] = numpy.array(1.5)  # one value for all, at a step of 0
    with numpy.errstate(all="ignore"):
        expected, actual = call(library, whole, values, count=300), call(library, cut, values, count=300)
    assert 30 < expected["assembled"].sum() < 270
    for key in expected:
        numpy.testing.assert_array_equal(actual[key], expected[key], err_msg=key)
    module = load_numpy_module(numpy_module([("f", program, "")]))["f"]
    reference = module(**values)
    assert_agree(actual, {k: numpy.asarray(v) for k, v in reference.items()}, angles_of(name, outputs), 1e-12,
                 name, rounding_spread(module, values))
