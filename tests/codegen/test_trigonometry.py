"""Sines and cosines of solved angles from their atan2 arguments, in the NumPy modules.

The C side of the same rewrite is tested in ``test_c.py``; here the NumPy module
that prints it is checked against NumPy's own calls, and for the catalog's
linkages the number of transcendental calls of full kinematics against positions.
"""
from __future__ import annotations

import re

import pytest
import sympy as sp

from export_checks import assert_atan2_angles, atan2_angle_case
from symlink.codegen.numpy import load_numpy_module, numpy_module
from symlink.codegen.program import straight_line
from symlink.codegen.trigonometry import angle_sums
from symlink.linkage import Program
from symlink.scene import catalog_linkage


def test_numpy_module_takes_sines_and_cosines_of_a_solved_angle_from_its_atan2():
    """cos q, sin q, sin(q - t), cos(q - t) for q = atan2(y, x) without calling them, zeros of both signs included."""
    program, arguments, expected = atan2_angle_case()
    source = numpy_module([("angles", program, "")])
    kernel = source.split("def _angles_block")[1]
    assert "numpy.sin(q" not in kernel and "numpy.cos(q" not in kernel and "_cos_atan2(" in kernel
    assert_atan2_angles(load_numpy_module(source)["angles"](**arguments), expected)


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
