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
from symlink.mechanism.catalog import EXAMPLE_VALUES
from symlink.codegen.numpy import load_numpy_module, numpy_module
from symlink.codegen.program import straight_line
from symlink.codegen.trigonometry import angle_sums
from symlink.symbolic.linkage import Program
from symlink.io.scene import catalog_linkage


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


@pytest.mark.parametrize("name", ["fourbar", "fivebar", "watt2", "jansen"])
def test_a_triangles_angles_come_with_their_atan2_arguments_length_and_no_square_root(name):
    """The two-angle case knows each angle's |(x, y)| (2 r w^2, by Heron): equal to sqrt(x^2 + y^2) at 30 digits,
    and full kinematics take no square root beyond the loops' roots."""
    linkage = catalog_linkage(name)
    unknowns = [q.name for q in linkage.unknowns]
    program = linkage.program(unknowns + [f"{q}dot" for q in unknowns])
    code = straight_line(program)
    assert set(code.radii) == set(linkage.unknowns), code.radii  # every unknown: a triangle's angle
    example = {**EXAMPLE_VALUES[name], "theta": 0.7, "thetadot": 1.3}  # a pose of the catalog's example design
    values = {s: sp.Float(example.get(s.name, 1.0), 30) for s in program.arguments}  # branches +1
    known = dict(values)
    for symbol, expr in code.assignments:
        known[symbol] = expr.xreplace(known).evalf(30)
    for angle, radius in code.radii.items():
        y, x = dict(code.assignments)[angle].args
        y, x, radius = (e.xreplace(known).evalf(30) for e in (y, x, radius))
        assert abs(radius - sp.sqrt(x**2 + y**2)) <= 1e-25 * abs(radius), (angle, radius, x, y)
    everything = numpy_module([("f", program, "")]).split("def _f_block")[1]
    assert everything.count("numpy.sqrt(") == 0 and everything.count("_clamped_sqrt(") == len(linkage.plan)
