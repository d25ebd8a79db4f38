"""Shape targets refined to exact (symlink.synthesis.shape.synthesize_shape): the true design's curve recovered.

Each target is the path of a known design's point, moved, turned, scaled, started elsewhere, run the other way and
resampled unevenly: only its shape is the design's.  ``synthesize_shape`` finds a design by the shape distance and
refines it; the refined design (its parameters, placement and the input at each target point, as returned) is then
traced by a reference written here, independent of symlink's code: the four-bar by hand (circle intersections, plain
floats: ``hand_linkages``), the Watt II six-bar by its loop closure solved at 50 digits by mpmath (``mp_closures``,
from the circle construction refined by ``findroot``).  The point must reach every target point to 1e-8 of the
curve's size (the bounding-box diagonal).
"""
from __future__ import annotations

import cmath
import math

import numpy
import pytest
import sympy as sp

from hand_linkages import fourbar_joints
from symlink.catalog import fourbar
from symlink.linkage import Linkage
from symlink.synthesis.shape import synthesize_shape
from symlink.vectors import Vector

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
    u, v = sp.symbols("u v", real=True)
    beta = base.roles["coupler"]
    P = base.points["B"] + Vector(u, beta, "BU") + Vector(v, beta + sp.pi / 2, "UP")
    return Linkage("fourbar_point", base.loops, base.inputs, base.unknowns, parameters=list(base.parameters) + [u, v],
                   points={**base.points, "P": P}, roles=base.roles)


def fourbar_point(values, theta: float, branch: int = 1) -> complex:
    B, C = fourbar_joints(values["a"], values["b"], values["c"], values["d"], theta, branch)
    return B + complex(values["u"], values["v"]) * (C - B) / abs(C - B)


FOURBAR_FREE = {"b": (2.5, 3.6), "u": (0.5, 2.5), "v": (-1.2, 1.2)}


def check_fourbar(found, target: numpy.ndarray) -> None:
    assert found.path.assembled, found.path.why
    branch = found.path.branches["branch"]
    reached = numpy.array([placed(found, fourbar_point(found.design, q, branch)) for q in found.path.inputs])
    distances = numpy.abs(reached - (target[:, 0] + 1j * target[:, 1]))
    assert numpy.max(distances) < 1e-8 * size(target), numpy.max(distances) / size(target)
    # the shape distance compares the target's polygon with the dense path: its floor is the polygon's chords
    assert found.distance < 0.5 * found.sampled_distance, (found.distance, found.sampled_distance)


@pytest.mark.slow  # a 150-point untimed fit: about 10 s on a shared machine
def test_fourbar_closed_curve_is_recovered():
    truth = {"a": 1.0, "b": 3.0, "c": 2.5, "d": 3.2, "u": 1.5, "v": 0.8}  # a crank-rocker: the input turns fully
    inputs = 1.1 - uneven(0.0, 2 * math.pi * (1 - 1 / 150), 150, 1)  # another start, the other way round
    target = moved(numpy.array([fourbar_point(truth, q) for q in inputs]))
    fixed = {k: truth[k] for k in "acd"}
    found = synthesize_shape(coupler_point_fourbar(), "P", target, FOURBAR_FREE, values=fixed, designs=1500)
    check_fourbar(found, target)
    assert all(abs(found.design[k] - truth[k]) < 1e-7 for k in FOURBAR_FREE)  # this curve has one such design


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
