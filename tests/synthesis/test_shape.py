"""Shape targets (symlink.synthesis.shape): coupler curves of known four-bars, moved, turned, scaled and resampled.

The curves are traced by hand (circle intersections of ``hand_linkages``, the coupler point P = B + (u + i v) along
B -> C) and moved by a similarity written out here in complex arithmetic; the code under test only compares and fits
them.  (The Watt II's named points all lie on cranks or rockers, whose paths are circular arcs of one shape.)
"""
from __future__ import annotations

import cmath
import math

import numpy
import pytest


from hand_linkages import fourbar_joints
from symlink.mechanism.catalog import fourbar, with_point
from symlink.symbolic.linkage import Linkage
from symlink.synthesis.shape import resampled, shape_distance, shape_search, similarity_fit

TRUTH = {"a": 1.0, "b": 3.0, "c": 2.5, "d": 3.2, "u": 1.5, "v": 0.8}
OTHER = {**TRUTH, "b": 3.4, "v": 0.3}


def coupler_point_fourbar() -> Linkage:
    """The catalog four-bar with a point P = B + u along the coupler + v to its left."""
    base = fourbar()
    return with_point(base, "B", base.roles["coupler"])
MOVE = (complex(2.5, -1.25), 0.8, 1.7)  # shift, turn (rad), scale


def curve(values, inputs) -> numpy.ndarray:
    points = []
    for q in inputs:
        B, C = fourbar_joints(values["a"], values["b"], values["c"], values["d"], q)
        points.append(B + complex(values["u"], values["v"]) * (C - B) / abs(C - B))
    return numpy.array([[p.real, p.imag] for p in points])


def moved(points: numpy.ndarray) -> numpy.ndarray:
    shift, turn, scale = MOVE
    z = shift + scale * cmath.exp(1j * turn) * (points[:, 0] + 1j * points[:, 1])
    return numpy.stack([z.real, z.imag], axis=1)


TURN = numpy.linspace(0.0, 2 * math.pi, 720, endpoint=False)
#: The truth's closed curve as a user would give it: another start, the other way round, 150 points, moved.
TARGET = moved(curve(TRUTH, (1.234 - numpy.linspace(0.0, 2 * math.pi, 150, endpoint=False))))


def test_the_curves_are_closed_and_assembled():
    assert numpy.all(numpy.isfinite(curve(TRUTH, TURN))) and numpy.all(numpy.isfinite(curve(OTHER, TURN)))


def test_similarity_fit_recovers_the_transform():
    source = curve(TRUTH, numpy.linspace(0.3, 4.0, 40))
    fit, rms = similarity_fit(source, moved(source))
    shift, turn, scale = MOVE
    assert rms < 1e-12
    assert abs(fit["x0"] - shift.real) < 1e-10 and abs(fit["y0"] - shift.imag) < 1e-10
    assert abs(fit["angle"] - turn) < 1e-10 and abs(fit["scale"] - scale) < 1e-10


def test_resampling_is_at_equal_arc_length():
    t = numpy.sort(numpy.random.default_rng(5).uniform(0, 2 * math.pi, 4000))  # a circle, sampled unevenly
    z = resampled(numpy.stack([numpy.cos(t), numpy.sin(t)], axis=1), 64)
    steps = numpy.abs(numpy.diff(numpy.concatenate([z, z[:1]])))
    assert numpy.ptp(steps) < 1e-5 and abs(steps.mean() - 2 * math.sin(math.pi / 64)) < 1e-5  # equal chords


def test_closed_shape_is_recognised():
    same = shape_distance(curve(TRUTH, TURN), TARGET)
    different = shape_distance(curve(OTHER, TURN), TARGET)
    assert same < 1e-3 and different > 20 * same, (same, different)


def test_open_shape_is_recognised():
    stretch = numpy.linspace(0.5, 2.5, 200)
    target = moved(curve(TRUTH, stretch[::3])[::-1])
    same = shape_distance(target, curve(TRUTH, stretch), "open")
    different = shape_distance(target, curve(OTHER, stretch), "open")
    assert same < 1e-3 and different > 20 * same, (same, different)


def test_partial_shape_is_recognised():
    target = moved(curve(TRUTH, numpy.linspace(2.0, 3.5, 40)))
    same = shape_distance(target, curve(TRUTH, TURN), "partial")
    different = shape_distance(target, curve(OTHER, TURN), "partial")
    assert same < 2e-3 and different > 5 * same, (same, different)


def test_shape_search_ranks_the_true_design_first_and_places_it():
    free = {"b": (2.6, 3.6), "u": (0.5, 2.5), "v": (-1.0, 1.0)}
    fixed = {k: v for k, v in TRUTH.items() if k not in free}
    matches = shape_search(coupler_point_fourbar(), "P", TARGET, free, values=fixed, designs=150, keep=3,
                           branches={"branch": 1}, candidates=[OTHER, TRUTH])
    best = matches[0]
    assert all(abs(best.design[name] - TRUTH[name]) < 1e-12 for name in free)
    assert best.distance < 1e-3 and matches[1].distance > best.distance
    shift, turn, scale = MOVE
    assert abs(best.placement["scale"] - scale) < 1e-2 * scale
    assert abs(cmath.exp(1j * best.placement["angle"]) - cmath.exp(1j * turn)) < 1e-2
    assert abs(complex(best.placement["x0"], best.placement["y0"]) - shift) < 1e-2 * scale * 5
    assert best.rms < 1e-2


@pytest.mark.parametrize("call, message", [
    (lambda: shape_distance([[0, 0], [1, 1]], [[0, 0], [1, 0], [1, 1]]), "at least 3 rows"),
    (lambda: shape_distance([[0, 0], [1, 1], [2, 0]], [[0, 0], [1, 0], [1, 1]], "wavy"), "kind is one of"),
    (lambda: shape_distance([[0, 0], [0, 0], [0, 0]], [[0, 0], [1, 0], [1, 1]]), "no length"),
    (lambda: similarity_fit([[0, 0], [1, 1]], [[0, 0], [1, 0], [1, 1]]), "pairs points"),
    (lambda: shape_search(coupler_point_fourbar(), "Q", TARGET, {"b": (3, 4)}, values=TRUTH), "no point 'Q'"),
])
def test_bad_input_is_a_value_error_naming_it(call, message):
    with pytest.raises(ValueError) as error:
        call()
    assert message in str(error.value)
