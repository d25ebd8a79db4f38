"""Function generation of any one-input linkage (symlink.synthesis.general_function), on problems with a known answer.

The wanted function is a known design's, computed here by hand (the slider's triangle, circle intersections of
``hand_linkages``); every found design is checked by the same hand formulas, never by the code under test.
"""
from __future__ import annotations

import math

import numpy
import pytest

from hand_linkages import fourbar_joints, slider_travel, watt2_joints, wrapped
from symlink.mechanism.catalog import EXAMPLE_VALUES, fourbar, slider_crank, watt2
from symlink.synthesis.general_function import chebyshev_inputs, function_values, synthesize_function

WATT = EXAMPLE_VALUES["watt2"]


def test_chebyshev_inputs_are_the_textbook_spacing():
    # x_j = mid - half cos((2j - 1) pi / 2n), n = 4 on [0, 2]: 1 - cos(pi/8), 1 - cos(3pi/8), ...
    expected = [1 - math.cos(math.pi / 8), 1 - math.cos(3 * math.pi / 8), 1 + math.cos(3 * math.pi / 8),
                1 + math.cos(math.pi / 8)]
    assert numpy.allclose(chebyshev_inputs(0.0, 2.0, 4), expected, atol=1e-15)


def test_function_values_are_the_hand_travel():
    inputs = numpy.linspace(0.0, 6.0, 7)
    found = function_values(slider_crank(), "s", {"a": 1.3, "b": 4.1, "offset": 0.7}, inputs)
    assert numpy.allclose(found, [slider_travel(1.3, 4.1, 0.7, q) for q in inputs], atol=1e-13)


@pytest.mark.parametrize("seed", range(6))
def test_slider_crank_travel_is_recovered(seed):
    rng = numpy.random.default_rng(100 + seed)
    truth = {"a": rng.uniform(0.8, 1.6), "b": rng.uniform(3.0, 5.0), "offset": rng.uniform(-0.8, 0.8)}
    inputs = chebyshev_inputs(0.0, rng.uniform(2.0, 6.0), 8)
    wanted = [slider_travel(truth["a"], truth["b"], truth["offset"], q) for q in inputs]
    found = synthesize_function(slider_crank(), "s", inputs, wanted,
                                {"a": (0.5, 2.0), "b": (2.5, 6.0), "offset": (-1.0, 1.0)}, seed=seed)
    assert found.assembled, found.why
    v = found.design
    reached = [slider_travel(v["a"], v["b"], v["offset"], q, found.branches["branch"]) for q in inputs]
    size = max(abs(w) for w in wanted)
    assert max(abs(r - w) for r, w in zip(reached, wanted)) < 1e-8 * size


def test_precision_points_as_many_as_free_parameters():
    truth = {"a": 1.2, "b": 4.0, "offset": 0.3}
    inputs = chebyshev_inputs(0.5, 2.5, 2)
    wanted = [slider_travel(1.2, 4.0, 0.3, q) for q in inputs]
    found = synthesize_function(slider_crank(), "s", inputs, wanted, {"a": (0.5, 2.0), "b": (3.0, 5.0)},
                                values={"offset": 0.3})
    assert found.assembled
    reached = [slider_travel(found.design["a"], found.design["b"], 0.3, q) for q in inputs]
    assert max(abs(r - w) for r, w in zip(reached, wanted)) < 1e-10
    assert found.design["offset"] == 0.3


@pytest.mark.parametrize("seed", range(4))
def test_watt_two_output_angle_is_recovered(seed):
    rng = numpy.random.default_rng(200 + seed)
    names = ("b", "c", "e", "f", "g")
    truth = dict(WATT)
    truth.update({name: WATT[name] * rng.uniform(0.9, 1.1) for name in names})
    inputs = numpy.linspace(0.3, 5.5, 12)
    wanted = [watt2_joints(truth, q)["psi"] for q in inputs]
    assert all(math.isfinite(w) for w in wanted)
    free = {name: (0.7 * WATT[name], 1.3 * WATT[name]) for name in names}
    fixed = {k: v for k, v in truth.items() if k not in free}
    found = synthesize_function(watt2(), "psi", inputs, wanted, free, values=fixed, seed=seed)
    assert found.assembled, found.why
    signs = (found.branches["branch_ABCD"], found.branches["branch_DEFG"])
    reached = [watt2_joints(found.design, q, signs)["psi"] for q in inputs]
    assert max(abs(wrapped(r - w)) for r, w in zip(reached, wanted)) < 1e-8


def test_fourbar_rocker_starts_from_freudenstein():
    truth = (1.0, 3.0, 2.5, 3.2)
    inputs = numpy.linspace(0.2, 2.5, 8)
    rocker_pins = [fourbar_joints(*truth, q)[1] for q in inputs]
    wanted = [math.atan2(c.imag, c.real - 3.2) for c in rocker_pins]
    found = synthesize_function(fourbar(), "phi", inputs, wanted, {"a": (0.5, 2.0), "b": (2.0, 4.0), "c": (1.5, 3.5)},
                                values={"d": 3.2})
    assert found.assembled
    assert found.evaluations <= 5  # Freudenstein's least squares is exact here: nothing left to refine
    B, C = zip(*(fourbar_joints(found.design["a"], found.design["b"], found.design["c"], 3.2, q,
                                found.branches["branch"]) for q in inputs))
    assert max(abs(wrapped(math.atan2(c.imag, c.real - 3.2) - w)) for c, w in zip(C, wanted)) < 1e-12


@pytest.mark.parametrize("call, message", [
    (lambda: synthesize_function(slider_crank(), "nothing", [0.0, 1.0], [4.0, 4.1], {"a": (0.5, 2.0)},
                                 values={"b": 3.0, "offset": 0.0}), "no output 'nothing'"),
    (lambda: synthesize_function(slider_crank(), "theta", [0.0, 1.0], [4.0, 4.1], {"a": (0.5, 2.0)},
                                 values={"b": 3.0, "offset": 0.0}), "the input itself"),
    (lambda: synthesize_function(slider_crank(), "s", [0.0, 1.0], [4.0], {"a": (0.5, 2.0)},
                                 values={"b": 3.0, "offset": 0.0}), "same length"),
    (lambda: synthesize_function(slider_crank(), "s", [0.0, math.nan], [4.0, 4.1], {"a": (0.5, 2.0)},
                                 values={"b": 3.0, "offset": 0.0}), "finite"),
    (lambda: synthesize_function(slider_crank(), "s", [0.0, 1.0], [4.0, 4.1], {"a": (2.0, 0.5)},
                                 values={"b": 3.0, "offset": 0.0}), "low < high"),
    (lambda: synthesize_function(slider_crank(), "s", [0.0, 1.0], [4.0, 4.1], {"z": (0.5, 2.0)},
                                 values={"b": 3.0, "offset": 0.0}), "no parameter 'z'"),
    (lambda: synthesize_function(slider_crank(), "s", [0.0, 1.0], [4.0, 4.1], {"a": (0.5, 2.0)},
                                 values={"b": 3.0}), "not free: offset"),
    (lambda: synthesize_function(slider_crank(), "s", [0.0, 1.0], [4.0, 4.1], {"a": (0.5, 2.0)},
                                 values={"b": 3.0, "offset": 0.0}, branches={"branch": 2}), "+1 or -1"),
    (lambda: synthesize_function(slider_crank(), "s", [0.0, 1.0], [40.0, 41.0], {"a": (0.5, 0.6)},
                                 values={"b": 0.1, "offset": 5.0}), "no design"),
])
def test_bad_input_is_a_value_error_naming_it(call, message):
    with pytest.raises(ValueError) as error:
        call()
    assert message in str(error.value)


def test_minimax_levels_the_errors_of_a_log_generator():
    """Freudenstein's classic log10 generator (x in [1, 2] on theta 45-105 deg, rocker over 90 deg; in symlink's
    convention the rocker angle is the textbook's plus 180 deg), 21 points: no four-bar meets them all.  Minimax
    must lower the largest error below least squares' and level it (Chebyshev: the extremes alternate with equal
    size, four of them for three free lengths); the errors are measured here by hand."""
    x = numpy.linspace(1.0, 2.0, 21)
    inputs = numpy.radians(45 + 60 * (x - 1))
    wanted = numpy.radians(135 + 90 * numpy.log10(x) / math.log10(2)) + math.pi
    free = {"a": (0.2, 3.0), "b": (0.2, 5.0), "c": (0.2, 3.0)}

    def hand_errors(found):
        pins = [fourbar_joints(found.design["a"], found.design["b"], found.design["c"], 1.0, q,
                               found.branches["branch"])[1] for q in inputs]
        return numpy.array([wrapped(math.atan2(C.imag, C.real - 1.0) - w) for C, w in zip(pins, wanted)])

    squares = synthesize_function(fourbar(), "phi", inputs, wanted, free, values={"d": 1.0})
    level = synthesize_function(fourbar(), "phi", inputs, wanted, free, values={"d": 1.0}, minimax=True)
    assert squares.assembled and level.assembled
    worst_squares = numpy.max(numpy.abs(hand_errors(squares)))
    errors = hand_errors(level)
    worst = numpy.max(numpy.abs(errors))
    assert worst < 0.8 * worst_squares
    assert abs(worst - level.structural_error) < 1e-12
    # the local extremes of the error curve (ends included) alternate in sign with nearly equal size
    interior = [k for k in range(1, len(errors) - 1) if abs(errors[k]) >= abs(errors[k - 1])
                and abs(errors[k]) >= abs(errors[k + 1])]
    extremes = errors[[0, *interior, len(errors) - 1]]
    assert len(extremes) >= 4 and numpy.all(numpy.sign(extremes[1:]) != numpy.sign(extremes[:-1]))
    assert numpy.min(numpy.abs(extremes)) > 0.9 * worst  # levelled to within the 21 points' sampling
