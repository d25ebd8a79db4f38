"""The closure of all loops at once, as one symbolic system: residuals, Jacobian, rate systems.

Where no loop-by-loop closed form exists (the Stephenson II six-bar), the
closure equations of all loops are solved together, numerically.  This module
derives what that needs symbolically: the residuals (two a loop), their
Jacobian with respect to the unknowns, and the right-hand sides of the linear
systems whose solutions are the unknowns' rates and accelerations.  The
generator :mod:`symlink.codegen.newton` prints them as NumPy code.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import sympy as sp

from .vectors import acceleration, rate, time_derivative
from ..common.display import record_html

if TYPE_CHECKING:
    from .linkage import Linkage

__all__ = ["ClosureSystem", "closure_system", "is_angle"]


@dataclass(frozen=True)
class ClosureSystem:
    """The closure of all loops at once, and its linear velocity and acceleration systems.

    ``residuals`` (two a loop) must vanish; ``jacobian`` is their derivative by
    the unknowns; the unknowns' rates solve ``jacobian * qdot = velocity_rhs``
    and their accelerations ``jacobian * qddot = acceleration_rhs``.
    ``scales`` give each equation's size (the sum of its loop's vector
    lengths) and ``units`` each unknown's (1 for an angle, a mean link length
    for a length), so that tolerances are relative.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    linkage: Linkage
    residuals: tuple[sp.Expr, ...]
    jacobian: sp.Matrix
    velocity_rhs: tuple[sp.Expr, ...]
    acceleration_rhs: tuple[sp.Expr, ...]
    scales: tuple[sp.Expr, ...]
    units: tuple[sp.Expr, ...]


def closure_system(linkage: Linkage) -> ClosureSystem:
    """Derive the closure system of ``linkage``; ``ValueError`` unless it has as many equations as unknowns.

    Parameters
    ----------
    linkage : Linkage
        Any linkage, with two equations a loop and two unknowns a loop.

    Returns
    -------
    ClosureSystem
        Its residuals, their Jacobian by the unknowns, the right-hand sides of the rate systems and the scales.

    Raises
    ------
    ValueError
        When the number of equations differs from the number of unknowns.

    Examples
    --------
    >>> import symlink
    >>> system = symlink.closure_system(symlink.slider_crank())
    >>> system.jacobian
    Matrix([
    [-b*sin(beta), -1],
    [ b*cos(beta),  0]])
    """
    unknowns = linkage.unknowns
    if 2 * len(linkage.loops) != len(unknowns):
        raise ValueError(f"{linkage.name}: {len(linkage.loops)} loops give {2 * len(linkage.loops)} equations "
                         f"for {len(unknowns)} unknowns; Newton's method needs as many of each")
    residuals, scales = [], []
    for loop in linkage.loops:
        size = sp.Add(*(sp.Abs(vector.length) for _, vector in loop.terms))
        residuals += list(loop.equations())
        scales += [size, size]
    jacobian = sp.Matrix(residuals).jacobian(unknowns)
    coordinates = linkage.coordinates
    first = [time_derivative(f, coordinates) for f in residuals]
    velocity_rhs = tuple(-f.subs({rate(u): 0 for u in unknowns}) for f in first)
    second = [time_derivative(f, coordinates) for f in first]
    acceleration_rhs = tuple(-f.subs({acceleration(u): 0 for u in unknowns}) for f in second)
    units = []
    for u in unknowns:
        if is_angle(linkage, u):
            units.append(sp.S.One)
        else:
            loop = next(loop for loop in linkage.loops if u in loop.symbols())
            units.append(sp.Add(*(sp.Abs(v.length) for _, v in loop.terms)) / len(loop.terms))
    return ClosureSystem(linkage, tuple(residuals), jacobian, velocity_rhs, acceleration_rhs,
                         tuple(scales), tuple(units))


def is_angle(linkage: Linkage, symbol: sp.Symbol) -> bool:
    """Whether a coordinate or a parameter is an angle (it turns a vector of a loop or of a point) rather than a
    length (a slider's travel, a side).

    A fixed angle that only a point's vectors turn (the angle of a coupler point on a ternary link, off every
    loop) is an angle too: the same rule for every symbol, wherever it appears.

    >>> from symlink.mechanism.catalog import slider_crank
    >>> linkage = slider_crank()
    >>> [(q.name, is_angle(linkage, q)) for q in linkage.unknowns]
    [('beta', True), ('s', False)]
    """
    if any(symbol in vector.angle.free_symbols for loop in linkage.loops for _, vector in loop.terms):
        return True
    return any(symbol in vector.angle.free_symbols for vectors in linkage.points.values() if vectors is not None
               for _, vector in vectors.as_sum().terms)
