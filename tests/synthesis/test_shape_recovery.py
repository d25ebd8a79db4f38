"""Shape targets refined to exact (symlink.synthesis.shape.synthesize_shape): the true design's curve recovered.

Each target is the path of a known design's point, moved, turned, scaled, started elsewhere, run the other way and
resampled unevenly: only its shape is the design's.  ``synthesize_shape`` finds a design by the shape distance and
refines it; the refined design (its parameters, placement and the input at each target point, as returned) is then
traced by a reference written here, independent of symlink's code: the four-bar by hand (circle intersections, plain
floats: ``hand_linkages``), the Watt II six-bar by its loop closure solved at 50 digits by mpmath (``mp_closures``,
from the circle construction refined by ``findroot``).  The point must reach every target point to 1e-8 of the
curve's size (the bounding-box diagonal), and the refined path's shape distance to the target be the true path's
(the distance of the target's polygon from the dense path, traced from the first target point's input: the chords
and the resampling leave a floor, the same for both).
"""
from __future__ import annotations

import cmath
import math

import mpmath as mp
import numpy
import pytest
import sympy as sp

from hand_linkages import fourbar_joints, watt2_joints
from mp_closures import watt2_closure, watt2_positions
from symlink.mechanism.catalog import EXAMPLE_VALUES, fourbar, watt2, with_point
from symlink.symbolic.linkage import Linkage
from symlink.synthesis.shape import shape_distance, synthesize_shape
from symlink.symbolic.vectors import Vector, lengths

TURN = numpy.linspace(0.0, 2 * math.pi, 720, endpoint=False)
MOVE = (complex(-1.5, 2.25), -2.1, 0.45)  # shift, turn (rad), scale


def moved(z: numpy.ndarray) -> numpy.ndarray:
    """Complex points moved by :data:`MOVE`, as rows (x, y)."""
    shift, turn, scale = MOVE
    w = shift + scale * cmath.exp(1j * turn) * numpy.asarray(z)
    return numpy.stack([w.real, w.imag], axis=1)


def uneven(start: float, stop: float, count: int, seed: int) -> numpy.ndarray:
    """``count`` inputs from ``start`` to ``stop``, unevenly spaced (a user's points are not at equal steps)."""
    steps = numpy.random.default_rng(seed).uniform(0.5, 1.5, count - 1)
    return start + (stop - start) * numpy.concatenate([[0.0], numpy.cumsum(steps) / steps.sum()])


def size(target: numpy.ndarray) -> float:
    return float(numpy.hypot(*numpy.ptp(target, axis=0)))


def placed(found, z: complex) -> complex:
    where = found.placement
    return complex(where["x0"], where["y0"]) + where["scale"] * cmath.exp(1j * where["angle"]) * z


# --- the four-bar with a coupler point P = B + (u + i v) along B -> C --------------------------------

def coupler_point_fourbar() -> Linkage:
    base = fourbar()
    return with_point(base, "B", base.roles["coupler"])


def fourbar_point(values, theta: float, branch: int = 1) -> complex:
    B, C = fourbar_joints(values["a"], values["b"], values["c"], values["d"], theta, branch)
    return B + complex(values["u"], values["v"]) * (C - B) / abs(C - B)


FOURBAR_FREE = {"b": (2.5, 3.6), "u": (0.5, 2.5), "v": (-1.2, 1.2)}


def same_shape_as_truth(found, target: numpy.ndarray, truth_path: numpy.ndarray) -> None:
    """The refined design's path is as far from the target's shape as the true path is (its floor: the chords)."""
    truth = shape_distance(target, numpy.stack([truth_path.real, truth_path.imag], axis=1), found.kind)
    assert abs(found.distance - truth) < 1e-6 and found.distance < found.sampled_distance, (
        found.distance, truth, found.sampled_distance)


def check_fourbar(found, target: numpy.ndarray) -> None:
    assert found.path.assembled, found.path.why
    branch = found.path.branches["branch"]
    reached = numpy.array([placed(found, fourbar_point(found.design, q, branch)) for q in found.path.inputs])
    distances = numpy.abs(reached - (target[:, 0] + 1j * target[:, 1]))
    assert numpy.max(distances) < 1e-8 * size(target), numpy.max(distances) / size(target)


def test_fourbar_closed_curve_is_recovered():  # a 150-point untimed fit: 3 to 7 s on a shared machine
    truth = {"a": 1.0, "b": 3.0, "c": 2.5, "d": 3.2, "u": 1.5, "v": 0.8}  # a crank-rocker: the input turns fully
    inputs = 1.1 - uneven(0.0, 2 * math.pi * (1 - 1 / 150), 150, 1)  # another start, the other way round
    target = moved(numpy.array([fourbar_point(truth, q) for q in inputs]))
    fixed = {k: truth[k] for k in "acd"}
    found = synthesize_shape(coupler_point_fourbar(), "P", target, FOURBAR_FREE, values=fixed, designs=1500)
    check_fourbar(found, target)
    same_shape_as_truth(found, target, numpy.array([fourbar_point(truth, q) for q in inputs[0] + TURN]))


def test_fourbar_open_curve_is_recovered():
    # a triple rocker: the input rocks where |B - D| <= b + c, |theta| <= acos((a^2 + d^2 - (b + c)^2) / (2 a d))
    # = 1.64276 rad, and P's path on branch +1 runs from one limit to the other: an open curve
    truth = {"a": 1.6, "b": 2.0, "c": 1.5, "d": 3.0, "u": 1.0, "v": 0.6}
    limit = math.acos((1.6 ** 2 + 3.0 ** 2 - 3.5 ** 2) / (2 * 1.6 * 3.0))
    assert not numpy.isfinite(fourbar_joints(1.6, 2.0, 1.5, 3.0, limit + 1e-6)[1])
    inputs = uneven(limit - 0.02, 0.03 - limit, 40, 2)
    target = moved(numpy.array([fourbar_point(truth, q) for q in inputs]))
    fixed = {k: truth[k] for k in "acd"}
    found = synthesize_shape(coupler_point_fourbar(), "P", target, {"b": (1.6, 2.6), "u": (0.3, 2.0), "v": (-1, 1)},
                             kind="open", values=fixed, designs=800, branches={"branch": 1})
    check_fourbar(found, target)
    same_shape_as_truth(found, target, numpy.array([fourbar_point(truth, q) for q in numpy.linspace(
        inputs[0], inputs[-1], 720)]))


@pytest.mark.slow  # the windows of 600 sampled paths ranked: about 10 s on a shared machine
def test_fourbar_partial_curve_is_recovered():
    # a piece (a third) of the crank-rocker's closed coupler curve, moved, turned, scaled
    truth = {"a": 1.0, "b": 3.0, "c": 2.5, "d": 3.2, "u": 1.5, "v": 0.8}
    inputs = uneven(0.4, 3.4, 30, 5)
    target = moved(numpy.array([fourbar_point(truth, q) for q in inputs]))
    fixed = {k: truth[k] for k in "acd"}
    found = synthesize_shape(coupler_point_fourbar(), "P", target, FOURBAR_FREE, kind="partial", values=fixed,
                             designs=600)
    check_fourbar(found, target)
    same_shape_as_truth(found, target, numpy.array([fourbar_point(truth, q) for q in inputs[0] + TURN]))


# --- the Watt II six-bar with a point P on its second coupler EF --------------------------------------

def watt2_with_point() -> Linkage:
    base = watt2()
    (p,), gamma = lengths("p"), sp.Symbol("gamma", real=True)
    P = base.points["E"] + Vector(p, base.roles["coupler2"] + gamma, "EP")
    return Linkage("watt2p", base.loops, base.inputs, base.unknowns, parameters=[*base.parameters, p, gamma],
                   points={**base.points, "P": P}, roles=base.roles)


def watt2_point_mp(values, theta: float, branches) -> complex:
    """P at 50 digits: the Watt II's loop closure solved by mpmath's findroot from the circle construction."""
    with mp.workdps(50):
        p = {k: mp.mpf(v) for k, v in values.items()}
        x = [mp.mpf(theta)]
        start = watt2_positions(x, p, branches)
        found = mp.findroot(lambda *q: watt2_closure(x, list(q), p), start)
        beta, phi, mu, psi = (found[i] for i in range(4))
        assert max(abs(r) for r in watt2_closure(x, [beta, phi, mu, psi], p)) < mp.mpf(10) ** -40
        E = p["d"] + p["e"] * mp.expj(phi + p["alpha"])
        P = E + p["p"] * mp.expj(mu + p["gamma"])
        return complex(P)


WATT_TRUTH = {**EXAMPLE_VALUES["watt2"], "b": 3.7, "f": 4.2, "p": 2.4, "gamma": 0.3}
WATT_FREE = {"b": (3.0, 4.5), "f": (3.5, 5.0), "p": (1.0, 3.0), "gamma": (-1.0, 1.0)}


@pytest.mark.slow  # sampling and a 100-point untimed fit of a six-bar: 12 to 16 s on a shared machine
def test_watt2_closed_curve_is_recovered():
    inputs = 2.0 + uneven(0.0, 2 * math.pi * (1 - 1 / 100), 100, 3)  # the input turns fully (checked by the fit)
    target = moved(numpy.array([watt2_point_mp(WATT_TRUTH, q, (1, 1)) for q in inputs]))
    fixed = {k: v for k, v in WATT_TRUTH.items() if k not in WATT_FREE}
    found = synthesize_shape(watt2_with_point(), "P", target, WATT_FREE, values=fixed, designs=2000,
                             branches={"branch_ABCD": 1, "branch_DEFG": 1})
    assert found.path.assembled, found.path.why
    signs = (found.path.branches["branch_ABCD"], found.path.branches["branch_DEFG"])
    reached = numpy.array([placed(found, watt2_point_mp(found.design, q, signs)) for q in found.path.inputs])
    distances = numpy.abs(reached - (target[:, 0] + 1j * target[:, 1]))
    assert numpy.max(distances) < 1e-8 * size(target), numpy.max(distances) / size(target)
    truth_path = []
    for q in inputs[0] + TURN:
        joints = watt2_joints(WATT_TRUTH, q)
        truth_path.append(joints["E"] + WATT_TRUTH["p"] * cmath.exp(1j * (joints["mu"] + WATT_TRUTH["gamma"])))
    same_shape_as_truth(found, target, numpy.array(truth_path))
