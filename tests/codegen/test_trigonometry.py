"""Sines and cosines of solved angles from their atan2 arguments, in the NumPy modules.

The C side of the same rewrite is tested in ``test_c.py``; here the NumPy module
that prints it is checked against NumPy's own calls, and for the catalog's
linkages the number of transcendental calls of full kinematics against positions.
"""
from __future__ import annotations

import re

import numpy
import pytest
import sympy as sp

from symlink.codegen.numpy import load_numpy_module, numpy_module
from symlink.codegen.program import straight_line
from symlink.codegen.trigonometry import angle_sums
from symlink.linkage import Program
from symlink.scene import catalog_linkage


def test_numpy_module_takes_sines_and_cosines_of_a_solved_angle_from_its_atan2():
    """cos q, sin q, sin(q - t), cos(q - t) for q = atan2(y, x) without calling them, zeros of both signs included."""
    x, y, t, q = sp.symbols("x y t q", real=True)
    program = Program((x, y, t), ((q, sp.atan2(y, x)),),
                      {"q": q, "cos_q": sp.cos(q), "sin_q": sp.sin(q), "sin_t": sp.sin(t), "cos_t": sp.cos(t),
                       "sin_difference": sp.sin(q - t), "cos_difference": sp.cos(q - t)})
    source = numpy_module([("angles", program, "")])
    kernel = source.split("def _angles_block")[1]
    assert "numpy.sin(q" not in kernel and "numpy.cos(q" not in kernel and "_cos_atan2(" in kernel
    rng = numpy.random.default_rng(5)
    xs = numpy.concatenate([[0.0, -0.0, 0.0, -0.0, 3.0, -3.0, 0.0, 0.0], rng.normal(size=200)])
    ys = numpy.concatenate([[0.0, 0.0, -0.0, -0.0, 0.0, -0.0, 2.0, -2.0], rng.normal(size=200)])
    ts = rng.uniform(-4, 4, size=xs.size)
    result = load_numpy_module(source)["angles"](xs, ys, ts)
    angle = numpy.arctan2(ys, xs)
    expected = {"q": angle, "cos_q": numpy.cos(angle), "sin_q": numpy.sin(angle), "sin_t": numpy.sin(ts),
                "cos_t": numpy.cos(ts), "sin_difference": numpy.sin(angle - ts), "cos_difference": numpy.cos(angle - ts)}
    for key, want in expected.items():  # a few units in the last place of 1 (angle - ts itself rounds by 4e-16)
        numpy.testing.assert_allclose(result[key], want, rtol=0, atol=1.5e-15 if "difference" in key else 4.5e-16,
                                      err_msg=key)
    # where x = y = 0, atan2 picks 0 or pi by the sign of x, and the sine keeps y's signed zero
    numpy.testing.assert_array_equal(result["cos_q"][:8], [1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 0.0, 0.0])
    numpy.testing.assert_array_equal(numpy.signbit(result["sin_q"][:6]), numpy.signbit(ys[:6]))


def _transcendental_calls(source: str) -> int:
    return len(re.findall(r"numpy\.(?:sin|cos|arctan2)\(", source))


@pytest.mark.parametrize("name", ["fourbar", "slider-crank", "inverted-slider-crank", "fivebar", "watt2", "jansen"])
def test_full_kinematics_call_sin_cos_and_atan2_no_more_often_than_positions(name):
    linkage = catalog_linkage(name)
    unknowns = [q.name for q in linkage.unknowns]
    full = unknowns + [f"{q}dot" for q in unknowns] + [f"{q}ddot" for q in unknowns]
    positions, everything = (numpy_module([("f", linkage.program(outputs), "")]) for outputs in (unknowns, full))
    assert _transcendental_calls(everything) == _transcendental_calls(positions)


def test_a_program_without_solved_angles_is_left_as_it_is():
    x = sp.Symbol("x", real=True)
    code = straight_line(Program((x,), (), {"s": sp.sin(x), "c": sp.cos(2 * x)}))
    assert angle_sums(code, set()) is code
