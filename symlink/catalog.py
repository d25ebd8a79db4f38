"""Ready-made linkages, each defined once with the public API and reused everywhere.

>>> linkage = fourbar()
>>> linkage.unknowns
(beta, phi)
"""
from __future__ import annotations

import sympy as sp

from .linkage import Linkage
from .loops import Loop
from .vectors import Vector, coordinates, lengths

__all__ = ["fourbar", "CATALOG"]


def transmission_angle(coupler_angle: sp.Expr, rocker_angle: sp.Expr) -> sp.Expr:
    """Interior angle at the coupler-rocker joint, in [0, pi], accurate near 0 and pi (atan2, not acos)."""
    difference = coupler_angle - rocker_angle
    return sp.Abs(sp.atan2(sp.sin(difference), sp.cos(difference)))


def fourbar() -> Linkage:
    """The four-bar of DESIGN.md, closed as in the worksheet of ``seeds/001``.

    Crank a = AB at theta from pivot A at the origin, coupler b = BC at beta,
    rocker c = DC at phi from pivot D at (d, 0):
    ``a e^{i theta} + b e^{i beta} = d + c e^{i phi}``.  Branch +1 puts C to
    the left of the line from B to D.
    """
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, d = lengths("a b c d")
    AB, BC = Vector(a, theta, "AB"), Vector(b, beta, "BC")
    DC, AD = Vector(c, phi, "DC"), Vector(d, 0, "AD")
    closure = Loop(AD + DC - BC - AB, name="ABCD")
    return Linkage(
        "fourbar", [closure], inputs=[theta], unknowns=[beta, phi],
        points={"A": None, "B": AB.as_sum(), "C": AB + BC, "D": AD.as_sum()},
        roles={"crank": theta, "coupler": beta, "rocker": phi},
        extras={"transmission": transmission_angle(beta, phi)},
    )


#: Catalog entries by name: functions that build a fresh :class:`Linkage`.
CATALOG = {"fourbar": fourbar}
