"""Units: which arguments are angles or lengths, and pint quantities converted to them."""
import math

import numpy as np
import pytest

from symlink.mechanism.catalog import fourbar, slider_crank
from symlink.plot import coupler_point_linkage
from symlink.numeric.units import is_quantity, output_units, plain_values


def test_plain_numbers_pass_unchanged():
    values = {"theta": np.array([0.0, 1.0]), "a": 2.0, "branch": 1}
    plain, unit = plain_values(fourbar(), values)
    assert plain == values and unit is None
    assert not any(is_quantity(value) for value in values.values())


def test_a_coupler_points_angle_is_an_angle_and_its_distance_a_length():
    pint = pytest.importorskip("pint")
    units = pint.UnitRegistry()
    values = dict(theta=0.0, a=1 * units.m, b=4 * units.m, c=2.5 * units.m, d=3 * units.m,
                  p=50 * units.cm, gamma=90 * units.degree)
    plain, unit = plain_values(coupler_point_linkage(), values)
    assert unit == "meter"
    assert plain["p"] == pytest.approx(0.5) and plain["gamma"] == pytest.approx(math.pi / 2)


def test_output_units_of_a_slider():
    units = output_units(slider_crank(), ["s", "sdot", "beta", "C_x", "singular"])
    assert units == {"s": "length", "sdot": "length/s", "beta": "rad", "C_x": "length", "singular": ""}


def test_output_units_of_design_sensitivities():
    # d(angle)/d(length) is rad per length; d(length)/d(length) has no unit; a fixed angle divides by rad.
    from symlink.mechanism.catalog import watt2
    units = output_units(watt2(), ["phi__d_a", "C_x__d_b", "E_x__d_alpha", "phi__d_alpha", "rocker__d_a"], "mm")
    assert units == {"phi__d_a": "rad/mm", "C_x__d_b": "", "E_x__d_alpha": "mm/rad", "phi__d_alpha": "",
                     "rocker__d_a": "rad/mm"}
