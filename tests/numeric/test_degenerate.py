"""Degenerate configurations are reported, never returned as a number marked assembled.

For each loop case the places where the closed form breaks down: two unknown lengths
along parallel lines (case 1), the vector with the unknown length and angle of zero
length (2a), a toggle where the two branches meet (2b, 2c, 3), the two known points of a
two-angle loop coinciding (3).  Evaluated through the generated NumPy code, as a user
would.  The rule: either ``assembled`` is False and every output is NaN, or the pose is
finite, and any rate that is not finite comes with ``singular`` True.
"""
import math

import numpy
import pytest
import sympy as sp

from symlink.symbolic.linkage import Linkage
from symlink.symbolic.loops import Loop
from symlink.numeric.solver import Solver
from symlink.symbolic.vectors import Vector


def symbols():
    a, b, c, d, e = sp.symbols("a b c d e", positive=True)
    theta, beta, phi, x, y, s = sp.symbols("theta beta phi x y s", real=True)
    alpha = sp.Symbol("alpha", real=True)
    return dict(a=a, b=b, c=c, d=d, e=e, theta=theta, beta=beta, phi=phi, x=x, y=y, s=s, alpha=alpha)


def two_lengths():
    """Case 1: a crank tip B reached by a travel x along +x and a guide y at angle alpha."""
    k = symbols()
    loop = Loop(Vector(k["a"], k["theta"]) - Vector(k["x"], 0) - Vector(k["y"], k["alpha"]), name="guide")
    return Linkage("guide", [loop], [k["theta"]], [k["x"], k["y"]])


def length_and_angle_of_one():
    """Case 2a: the inverted slider-crank, rocker pivot D at (d, 0), slider r along the rocker."""
    k = symbols()
    loop = Loop(Vector(k["a"], k["theta"]) - Vector(k["s"], k["phi"]) - Vector(k["d"], 0), name="ABD")
    return Linkage("inverted slider-crank", [loop], [k["theta"]], [k["phi"], k["s"]])


def length_and_other_angle():
    """Case 2b: the offset slider-crank, slider x along +x at height e."""
    k = symbols()
    loop = Loop(Vector(k["a"], k["theta"]) + Vector(k["b"], k["beta"]) - Vector(k["x"], 0)
                - Vector(k["e"], sp.pi / 2), name="ABC")
    return Linkage("slider-crank", [loop], [k["theta"]], [k["beta"], k["x"]])


def two_angles():
    """Case 3: the four-bar."""
    k = symbols()
    loop = Loop(Vector(k["a"], k["theta"]) + Vector(k["b"], k["beta"]) - Vector(k["c"], k["phi"])
                - Vector(k["d"], 0), name="ABCD")
    return Linkage("fourbar", [loop], [k["theta"]], [k["beta"], k["phi"]])


def offset_inverted():
    """Case 2c: the offset inverted slider-crank, the guide at distance e from the rocker pivot."""
    k = symbols()
    loop = Loop(Vector(k["a"], k["theta"]) - Vector(k["d"], 0) - Vector(k["s"], k["phi"])
                - Vector(k["e"], k["phi"] + sp.pi / 2), name="ABD")
    return Linkage("offset inverted slider-crank", [loop], [k["theta"]], [k["phi"], k["s"]])


LINKAGES = {"1": two_lengths, "2a": length_and_angle_of_one, "2b": length_and_other_angle, "3": two_angles,
            "2c": offset_inverted}


def solve(case, **values):
    linkage = LINKAGES[case]()
    unknowns = [q.name for q in linkage.unknowns]
    outputs = unknowns + [n + "dot" for n in unknowns] + [n + "ddot" for n in unknowns] + ["singular"]
    with numpy.errstate(all="ignore"):
        result = Solver(linkage, outputs)(thetadot=1.0, **values)
    return {k: numpy.asarray(v) for k, v in result.items()}, unknowns


def honest(result, unknowns):
    """The rule of this file, for one configuration; returns 'not assembled', 'singular' or 'regular'."""
    if not bool(result["assembled"]):
        assert all(numpy.isnan(result[name]) for name in unknowns)
        return "not assembled"
    assert all(numpy.isfinite(result[name]) for name in unknowns)
    rates = [result[n + suffix] for n in unknowns for suffix in ("dot", "ddot")]
    if not all(numpy.isfinite(r) for r in rates):
        assert bool(result["singular"]), "a rate that is not finite must be marked singular"
        return "singular"
    return "singular" if bool(result["singular"]) else "regular"


CASES = [
    # (case, values, what must come out)
    # case 1: the guide parallel to the travel (reported: x = +inf, y = -inf, assembled)
    ("1", dict(theta=0.3, a=1.0, alpha=0.0), "not assembled"),
    ("1", dict(theta=0.3, a=1.0, alpha=math.pi), "not assembled"),
    ("1", dict(theta=0.3, a=1.0, alpha=1e-17), "not assembled"),
    ("1", dict(theta=0.0, a=1.0, alpha=0.0), "not assembled"),    # along the line: lengths undetermined
    ("1", dict(theta=0.3, a=1.0, alpha=1.0), "regular"),
    # case 2a: the crank pin on the rocker pivot (reported: an infinite rate, singular False)
    ("2a", dict(theta=0.0, a=1.0, d=1.0), "not assembled"),
    ("2a", dict(theta=2 * math.pi, a=1.0, d=1.0), "not assembled"),
    ("2a", dict(theta=0.5, a=1.0, d=1.0), "regular"),
    # case 2b: the conrod perpendicular to the travel (a toggle); beyond it, no assembly
    ("2b", dict(theta=-math.pi / 2, a=1.0, b=2.0, e=1.0, branch=1), "singular"),
    ("2b", dict(theta=-math.pi / 2, a=1.0, b=1.5, e=1.0, branch=1), "not assembled"),
    ("2b", dict(theta=0.3, a=1.0, b=3.0, e=0.5, branch=-1), "regular"),
    # case 3: the two known points coincide (reported: a pose off by 1.4, assembled)
    ("3", dict(theta=0.0, a=1.0, b=2.0, c=2.0, d=1.0, branch=1), "not assembled"),
    ("3", dict(theta=0.0, a=1.0, b=2.0, c=2.0, d=1.0, branch=-1), "not assembled"),
    ("3", dict(theta=0.0, a=1.0, b=2.0, c=3.0, d=1.0, branch=1), "not assembled"),
    ("3", dict(theta=0.0, a=1.0, b=2.0, c=1.0, d=2.0, branch=1), "singular"),     # folded toggle, w = b - c
    ("3", dict(theta=math.pi, a=1.0, b=2.0, c=1.0, d=2.0, branch=1), "singular"),  # extended, w = b + c
    ("3", dict(theta=0.0, a=2.0, b=1.0, c=1.0, d=2.0, branch=1), "not assembled"),
    ("3", dict(theta=1.0, a=1.0, b=3.0, c=2.5, d=3.0, branch=1), "regular"),
    # case 2c: the guide tangent... the crank pin at the offset distance from the pivot (a toggle)
    ("2c", dict(theta=math.pi / 2, a=1.0, d=0.0 + 1e-300, e=1.0, branch=1), "singular"),
    ("2c", dict(theta=0.0, a=1.0, d=1.0, e=0.5, branch=1), "not assembled"),      # the pin on the pivot
    ("2c", dict(theta=0.7, a=1.0, d=2.0, e=0.5, branch=-1), "regular"),
]


@pytest.mark.parametrize("case, values, expected", CASES)
def test_degenerate_configurations_are_reported(case, values, expected):
    result, unknowns = solve(case, **values)
    assert honest(result, unknowns) == expected


def test_the_reported_parallel_guide_is_not_returned_as_infinity():
    result, _ = solve("1", theta=0.3, a=1.0, alpha=0.0)
    assert not bool(result["assembled"]) and numpy.isnan(result["x"]) and numpy.isnan(result["y"])


def test_near_coincident_points_still_give_the_right_pose():
    """Just off the degenerate point the pose is right (checked by closing the loop)."""
    a, b, c, d, theta = 1.0, 2.0, 2.0, 1.0, 1e-6
    result, _ = solve("3", theta=theta, a=a, b=b, c=c, d=d, branch=1)
    beta, phi = float(result["beta"]), float(result["phi"])
    gap = complex(a * math.cos(theta) + b * math.cos(beta) - c * math.cos(phi) - d,
                  a * math.sin(theta) + b * math.sin(beta) - c * math.sin(phi))
    assert bool(result["assembled"]) and abs(gap) < 1e-14
