"""Every assembly of the Stephenson II six-bar at one crank angle, found by a scan.

The catalog's :func:`~symlink.mechanism.catalog.stephenson2` has no loop-by-loop closed
form; its numeric solver continues one assembly along the crank sweep from a
starting assembly.  This module finds the starting assemblies: with the crank
angle fixed, a trial coupler angle beta places C and E; F is where the circle
of radius c about C meets the circle of radius f about D (two sides, or none),
which gives the rocker angle phi and so H; the assemblies are the beta where
``|E - H| = g``.  The residual ``|E - H|^2 - g^2`` is scanned over a full turn
of beta on both sides and each change of sign is bisected to rounding.

Assemblies whose coupler angle lies within one scan step of a position where
C, F and D line up (a toggle of the first loop) can be missed.

>>> found = stephenson2_assemblies(0.0, a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1,
...                                alpha=0.9, delta=0.3)
>>> len(found), [round(x, 4) for x in found[-1].values()]  # beta, mu, phi, eta
(4, [0.9239, 0.2704, 1.4126, -0.1733])
"""
from __future__ import annotations

import math

import numpy

from ..common.angles import wrap

__all__ = ["stephenson2_assemblies"]

#: Points of the scan of the coupler angle over a full turn.
SCAN_POINTS = 7200
BISECTIONS = 60


def _circle_point(C, c, D, f, side):
    """The point F with |F - C| = c and |F - D| = f, left (+1) or right (-1) of C -> D, and where it exists."""
    span = D - C
    length = numpy.abs(span)
    along = (c * c - f * f + length * length) / (2 * length)
    height2 = c * c - along * along
    return C + span / length * (along + side * 1j * numpy.sqrt(numpy.maximum(height2, 0.0))), height2 >= 0


def _closing(theta, beta, side, p):
    """The positions for trial coupler angles beta, and the residual |E - H|^2 - g^2 of the second loop."""
    B = p["a"] * numpy.exp(1j * theta)
    C = B + p["b"] * numpy.exp(1j * beta)
    F, exists = _circle_point(C, p["c"], complex(p["d"]), p["f"], side)
    phi = numpy.angle(F - p["d"])
    E = B + p["e"] * numpy.exp(1j * (beta + p["alpha"]))
    H = p["d"] + p["h"] * numpy.exp(1j * (phi + p["delta"]))
    residual = numpy.abs(E - H) ** 2 - p["g"] ** 2
    return residual, exists, {"beta": beta, "mu": numpy.angle(F - C), "phi": phi, "eta": numpy.angle(H - E)}


def stephenson2_assemblies(theta: float, *, a: float, b: float, c: float, d: float, e: float, f: float,
                           g: float, h: float, alpha: float, delta: float) -> list[dict[str, float]]:
    """The assemblies at crank angle ``theta`` (radians), as ``{"beta", "mu", "phi", "eta"}`` in radians.

    Sorted by the coupler angle beta in (-pi, pi]; an empty list where the
    linkage cannot be assembled.  Parameters as in
    :func:`~symlink.mechanism.catalog.stephenson2`.
    """
    p = dict(a=a, b=b, c=c, d=d, e=e, f=f, g=g, h=h, alpha=alpha, delta=delta)
    step = 2 * math.pi / SCAN_POINTS
    grid = -math.pi + step * numpy.arange(SCAN_POINTS)
    found: list[dict[str, float]] = []
    for side in (1, -1):
        residual, exists, _ = _closing(theta, grid, side, p)
        following = numpy.roll(residual, -1)
        bracketed = exists & numpy.roll(exists, -1) & (numpy.sign(residual) != numpy.sign(following))
        low = grid[bracketed]
        high = low + step
        low_sign = numpy.sign(residual[bracketed])
        for _ in range(BISECTIONS):
            middle = 0.5 * (low + high)
            value, _, _ = _closing(theta, middle, side, p)
            same = numpy.sign(value) == low_sign
            low, high = numpy.where(same, middle, low), numpy.where(same, high, middle)
        beta = 0.5 * (low + high)
        value, exists, angles = _closing(theta, beta, side, p)
        scale = (p["e"] + p["g"] + p["h"] + abs(p["a"]) + p["d"]) ** 2
        good = exists & (numpy.abs(value) <= 1e-9 * scale)
        for k in numpy.flatnonzero(good):
            found.append({name: float(wrap(values[k])) for name, values in angles.items()})
    unique: list[dict[str, float]] = []
    for assembly in sorted(found, key=lambda q: q["beta"]):
        if not any(all(abs(wrap(assembly[n] - other[n])) < 1e-7 for n in assembly) for other in unique):
            unique.append(assembly)
    return unique
