"""Motion generation of any one-input linkage (symlink.synthesis.general_motion), on problems with a known answer.

The poses are a known design's link poses, placed by a known frame, computed here by hand (circle intersections of
``hand_linkages``); every found design is checked by the same hand formulas, never by the code under test; the
Jacobian against central differences of the generated solver's poses.
"""
from __future__ import annotations

import cmath
import math

import numpy
import pytest

from hand_linkages import fourbar_joints, watt2_joints, wrapped
from symlink.mechanism.catalog import EXAMPLE_VALUES, fourbar, watt2
from symlink.synthesis.general_motion import link_poses, synthesize_motion

WATT = EXAMPLE_VALUES["watt2"]


def placed(placement, z: complex, angle: float):
    turn = placement["scale"] * cmath.exp(1j * placement["angle"])
    p = complex(placement["x0"], placement["y0"]) + turn * z
    return p.real, p.imag, angle + placement["angle"]


def coupler_pose(v, q, branch, placement):
    B, C = fourbar_joints(v["a"], v["b"], v["c"], v["d"], q, branch)
    return placed(placement, B, cmath.phase(C - B))


def watt_link_pose(v, q, signs, placement):
    joints = watt2_joints(v, q, signs)
    return placed(placement, joints["E"], joints["mu"])


def worst(found_poses, wanted, size):
    return max(max(math.hypot(f[0] - w[0], f[1] - w[1]) / size, abs(wrapped(f[2] - w[2])))
               for f, w in zip(found_poses, wanted))


def test_link_poses_are_the_hand_poses():
    v = {"a": 1.0, "b": 3.0, "c": 2.5, "d": 3.2}
    where = {"x0": 0.4, "y0": -0.2, "angle": 0.3, "scale": 1.5}
    inputs = [0.3, 1.1, 2.0]
    found = link_poses(fourbar(), "B", "beta", v, inputs, placement=where)
    assert worst(found, [coupler_pose(v, q, 1, where) for q in inputs], 1.0) < 1e-13


@pytest.mark.parametrize("seed", range(5))
def test_fourbar_coupler_through_poses_untimed(seed):
    rng = numpy.random.default_rng(300 + seed)
    truth = {"a": 1.0, "b": rng.uniform(2.6, 3.4), "c": rng.uniform(2.2, 2.8), "d": rng.uniform(2.9, 3.5)}
    where = {"x0": rng.uniform(-1, 1), "y0": rng.uniform(-1, 1), "angle": rng.uniform(-math.pi, math.pi), "scale": 1.0}
    inputs = numpy.sort(rng.uniform(0.0, 2 * math.pi, 5))
    poses = [coupler_pose(truth, q, 1, where) for q in inputs]
    found = synthesize_motion(fourbar(), "B", "beta", poses, {"b": (2.0, 4.0), "c": (1.5, 3.5), "d": (2.5, 4.0)},
                              values={"a": 1.0}, frame=("x0", "y0", "angle"), seed=seed)
    assert found.assembled, found.why
    size = math.hypot(*(numpy.ptp(numpy.array(poses)[:, :2], axis=0)))
    reached = [coupler_pose(found.design, q, found.branches["branch"], found.placement) for q in found.inputs]
    assert worst(reached, poses, size) < 1e-8


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("timed", [True, False])
def test_watt_two_link_through_poses(seed, timed):
    rng = numpy.random.default_rng(400 + seed)
    names = ("b", "c", "e", "f", "g")
    truth = dict(WATT)
    truth.update({name: WATT[name] * rng.uniform(0.9, 1.1) for name in names})
    where = {"x0": rng.uniform(-1, 1), "y0": rng.uniform(-1, 1), "angle": rng.uniform(-math.pi, math.pi), "scale": 1.0}
    inputs = numpy.linspace(0.3, 4.5, 6)
    poses = [watt_link_pose(truth, q, (1, 1), where) for q in inputs]
    free = {name: (0.7 * WATT[name], 1.3 * WATT[name]) for name in names}
    found = synthesize_motion(watt2(), "E", "mu", poses, free, values={k: v for k, v in truth.items() if k not in free},
                              frame=("x0", "y0", "angle"), timed=inputs if timed else None, seed=seed)
    assert found.assembled, found.why
    size = math.hypot(*(numpy.ptp(numpy.array(poses)[:, :2], axis=0)))
    signs = (found.branches["branch_ABCD"], found.branches["branch_DEFG"])
    reached = [watt_link_pose(found.design, q, signs, found.placement) for q in found.inputs]
    assert worst(reached, poses, size) < 1e-8
    if timed:
        assert found.inputs == tuple(inputs)


def test_jacobian_matches_central_differences():
    from symlink.synthesis.general_motion import _Problem
    v = {"a": 1.0, "b": 3.0, "c": 2.5, "d": 3.2}
    poses = numpy.array([[0.1, 0.2, 0.3], [0.5, 1.0, 0.1], [0.2, 1.4, -0.2]])
    problem = _Problem(fourbar(), ("B_x", "B_y", "beta"), poses, {"b": (2, 4), "c": (2, 3)}, {"a": 1.0, "d": 3.2},
                       ("x0", "y0", "angle", "scale"), {}, None, {})
    y = numpy.array([3.0, 2.5, 0.1, -0.2, 0.4, 1.3, 0.5, 1.0, 1.6])
    r, J = problem.residuals(y, {"branch": 1})

    def by_hand(y):
        where = dict(zip(("x0", "y0", "angle", "scale"), y[2:6]))
        design = {**v, "b": y[0], "c": y[1]}
        size = math.hypot(*numpy.ptp(poses[:, :2], axis=0))
        rows = []
        for q, pose in zip(y[6:], poses):
            x, yy, a = coupler_pose(design, q, 1, where)
            rows += [(x - pose[0]) / size, (yy - pose[1]) / size, wrapped(a - pose[2])]
        return numpy.array(rows)

    assert numpy.allclose(r, by_hand(y), atol=1e-13)
    h = 1e-6
    numeric = numpy.stack([(by_hand(y + h * e) - by_hand(y - h * e)) / (2 * h) for e in numpy.eye(len(y))], axis=1)
    assert numpy.allclose(J, numeric, atol=1e-7)


@pytest.mark.parametrize("call, message", [
    (lambda: synthesize_motion(fourbar(), "Q", "beta", [[0, 0, 0], [1, 1, 1]], {"b": (2, 4)},
                               values={"a": 1, "c": 2.5, "d": 3.2}), "no point 'Q'"),
    (lambda: synthesize_motion(fourbar(), "B", "B_x", [[0, 0, 0], [1, 1, 1]], {"b": (2, 4)},
                               values={"a": 1, "c": 2.5, "d": 3.2}), "not an angle"),
    (lambda: synthesize_motion(fourbar(), "B", "beta", [[0, 0, 0]], {"b": (2, 4)},
                               values={"a": 1, "c": 2.5, "d": 3.2}), "at least two rows"),
    (lambda: synthesize_motion(fourbar(), "B", "beta", [[0, 0, 0], [1, math.inf, 1]], {"b": (2, 4)},
                               values={"a": 1, "c": 2.5, "d": 3.2}), "finite"),
    (lambda: synthesize_motion(fourbar(), "B", "beta", [[0, 0, 0], [1, 1, 1]], {"b": (2, 4)},
                               values={"a": 1, "c": 2.5, "d": 3.2}, frame=("tilt",)), "frame names"),
    (lambda: synthesize_motion(fourbar(), "B", "beta", [[0, 0, 0], [1, 1, 1]], {"b": (2, 4)},
                               values={"a": 1, "c": 2.5, "d": 3.2}, timed=[0.0]), "2 poses need 2"),
])
def test_bad_input_is_a_value_error_naming_it(call, message):
    with pytest.raises(ValueError) as error:
        call()
    assert message in str(error.value)
