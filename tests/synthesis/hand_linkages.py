"""Positions of the slider-crank, the four-bar and the Watt II six-bar by hand (circle intersections, plain floats).

Independent of symlink's code: the references the recoveries of function and motion generation are checked against.
Branch signs as symlink's catalog states them: +1 puts the joint to the left of the directed line between the
centres of the two circles it lies on (B -> D for the four-bar's C, E -> G for the Watt II's F); the slider-crank's
+1 has the larger travel.
"""
from __future__ import annotations

import cmath
import math


def circles(first: complex, r1: float, second: complex, r2: float, branch: int) -> complex:
    """The intersection of the circles (first, r1) and (second, r2) left (+1) or right (-1) of first -> second."""
    w = abs(second - first)
    along = (r1 * r1 - r2 * r2 + w * w) / (2 * w)
    across = r1 * r1 - along * along
    if across < 0:
        return complex(math.nan, math.nan)
    unit = (second - first) / w
    return first + along * unit + branch * math.sqrt(across) * 1j * unit


def slider_travel(a: float, b: float, offset: float, theta: float, branch: int = 1) -> float:
    """s of the slider-crank: C = (s, offset) at distance b from B = a e^{i theta}."""
    dy = offset - a * math.sin(theta)
    return a * math.cos(theta) + branch * math.sqrt(b * b - dy * dy)


def fourbar_joints(a, b, c, d, theta, branch=1):
    """B, C of the four-bar (A at 0, D at d)."""
    B = a * cmath.exp(1j * theta)
    return B, circles(B, b, complex(d, 0.0), c, branch)


def watt2_joints(v: dict, theta: float, branches=(1, 1)):
    """B, C, E, F, G and the angles phi, mu, psi of the Watt II (catalog conventions)."""
    B, C = fourbar_joints(v["a"], v["b"], v["c"], v["d"], theta, branches[0])
    D = complex(v["d"], 0.0)
    phi = cmath.phase(C - D)
    E = D + v["e"] * cmath.exp(1j * (phi + v["alpha"]))
    G = complex(v["gx"], v["gy"])
    F = circles(E, v["f"], G, v["g"], branches[1])
    return {"B": B, "C": C, "E": E, "F": F, "G": G, "phi": phi, "mu": cmath.phase(F - E), "psi": cmath.phase(F - G)}


def wrapped(angle: float) -> float:
    """An angle difference wrapped to (-pi, pi]."""
    return math.atan2(math.sin(angle), math.cos(angle))
