"""Function generation: a four-bar whose rocker angle is a given function of its crank angle (Freudenstein).

symlink's four-bar closes as ``a e^{i theta} + b e^{i beta} = d + c e^{i phi}`` (crank a at
theta from A at the origin, coupler b, rocker c at phi from D = (d, 0)).  Eliminating the
coupler angle (``b^2 = |d + c e^{i phi} - a e^{i theta}|^2``) gives Freudenstein's equation

    ``K1 cos(phi) - K2 cos(theta) + K3 = cos(theta - phi)``,
    ``K1 = d / a``, ``K2 = d / c``, ``K3 = (a^2 - b^2 + c^2 + d^2) / (2 a c)``,

the textbooks' form (Norton's theta2 = theta, theta4 = phi, with the same signs).  It is
linear in K1, K2, K3, so

* three precision points ``(theta_j, phi_j)`` give the K's by one 3x3 solve
  (:func:`three_point_design`; :func:`chebyshev_points` spaces them to keep the error small);
* more points give them by linear least squares (:func:`least_squares_design`), each
  equation weighted by how fast it changes with phi, so that the residual measures an
  angle; a few passes re-weight at the new design.

Either design is then verified with symlink's generated four-bar solver: the branch that
passes through the points is found, the linkage must stay assembled on it, without a
toggle, between the first and the last crank angle, and the structural error (generated
minus wanted rocker angle) is measured over the whole range.  ``ValueError`` when the
K's give no four-bar (an imaginary coupler, singular equations) or when the points lie on two
branches.

>>> design = function_generator(math.log10, (1.0, 2.0), (math.radians(45), math.radians(105)),
...                             (math.radians(135), math.radians(225)))
>>> design.method, design.branch, design.structural_error < math.radians(0.5)
('three-point', 1, True)
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy
from numpy.typing import ArrayLike

from ..analysis import grashof, wrap_angle
from ..mechanism.catalog import fourbar
from ..common.display import record_html
from ..numeric.solver import check_lengths, settled, shared_solver

__all__ = ["FunctionDesign", "freudenstein_coefficients", "lengths_from_coefficients", "chebyshev_points", "check_function_targets",
           "three_point_design", "least_squares_design", "function_generator", "structural_error",
           "ERROR_SAMPLES"]

#: Crank angles at which the structural error is measured over the range.
ERROR_SAMPLES = 401

_REWEIGHTS = 4  # least-squares passes re-weighted at the new design
_LAWSON_STEPS = 60  # Lawson re-weightings towards the smallest largest error


@dataclass(frozen=True)
class FunctionDesign:
    """A four-bar function generator (lengths in the ground's unit, angles in radians).

    ``theta`` and ``phi`` are the pairs it was designed from; ``branch`` the assembly that
    passes through them.  The linkage's own crank angle is ``theta + crank_offset`` and its
    rocker angle ``phi + rocker_offset`` (offsets 0 or pi, where Freudenstein's K's give a
    negative length).  ``structural_error`` the largest ``|phi generated - phi wanted|``
    at ``error_theta`` (``errors``): the given pairs, or for :func:`function_generator`
    samples of the function over its whole range; measured with the generated solver.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    crank: float
    coupler: float
    rocker: float
    ground: float
    coefficients: tuple[float, float, float]
    branch: int
    method: str
    crank_offset: float
    rocker_offset: float
    theta: tuple[float, ...]
    phi: tuple[float, ...]
    grashof: str
    structural_error: float
    error_theta: numpy.ndarray
    errors: numpy.ndarray

    @property
    def lengths(self) -> tuple[float, float, float, float]:
        return self.crank, self.coupler, self.rocker, self.ground

    @property
    def offsets(self) -> tuple[float, float]:
        return self.crank_offset, self.rocker_offset


def freudenstein_coefficients(a: float, b: float, c: float, d: float) -> tuple[float, float, float]:
    """K1, K2, K3 of a four-bar (crank a, coupler b, rocker c, ground d).

    >>> [round(k, 6) for k in freudenstein_coefficients(20, 66, 56, 80)]
    [4.0, 1.428571, 2.491071]
    """
    check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    return d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)


def lengths_from_coefficients(k1: float, k2: float, k3: float, ground: float = 1.0) -> tuple[float, float, float]:
    """Crank, coupler and rocker for Freudenstein's K's and a ground length; ``ValueError`` if there is none.

    Crank and rocker come out signed: a negative crank (rocker) is a positive one turned
    by 180 deg, which :class:`FunctionDesign` records as ``crank_offset`` (``rocker_offset``).

    >>> [round(x, 6) for x in lengths_from_coefficients(4.0, 80 / 56, 2.491071428571, 80)]
    [20.0, 66.0, 56.0]
    """
    check_lengths(ground=ground)
    if not all(math.isfinite(k) for k in (k1, k2, k3)) or k1 == 0 or k2 == 0:
        raise ValueError("the precision points give no four-bar: Freudenstein's equations are singular "
                         "(repeated or aligned points); spread the angles")
    a, c = ground / k1, ground / k2
    squared = a * a + c * c + ground * ground - 2 * a * c * k3
    if not squared > 0:
        raise ValueError(f"the precision points need an imaginary coupler (b^2 = {squared:.6g}); "
                         "choose other angle ranges")
    return a, math.sqrt(squared), c


def chebyshev_points(start: float, end: float, count: int = 3) -> numpy.ndarray:
    """Chebyshev spacing of ``count`` precision points in [start, end]: ``mid - half cos((2j - 1) pi / (2 n))``.

    >>> [round(float(x), 6) for x in chebyshev_points(1.0, 2.0)]
    [1.066987, 1.5, 1.933013]
    """
    if count < 1:
        raise ValueError(f"at least one precision point is needed, got {count}")
    j = numpy.arange(1, count + 1)
    return (start + end) / 2 - (end - start) / 2 * numpy.cos((2 * j - 1) * math.pi / (2 * count))


def _angles(theta: ArrayLike, phi: ArrayLike, least: int) -> tuple[numpy.ndarray, numpy.ndarray]:
    theta_array, phi_array = numpy.asarray(theta, dtype=float), numpy.asarray(phi, dtype=float)
    if theta_array.ndim != 1 or theta_array.shape != phi_array.shape:
        raise ValueError(f"theta and phi must be two lists of the same length, got shapes {theta_array.shape} "
                         f"and {phi_array.shape}")
    if len(theta_array) < least:
        raise ValueError(f"function generation needs at least {least} (theta, phi) pairs, got {len(theta_array)}")
    if not (numpy.all(numpy.isfinite(theta_array)) and numpy.all(numpy.isfinite(phi_array))):
        raise ValueError("the crank and rocker angles must be finite numbers")
    check_function_targets(theta_array, phi_array)
    return theta_array, phi_array


def check_function_targets(inputs: ArrayLike, outputs: ArrayLike) -> None:
    """``ValueError`` naming the first two targets of a function at the same input.

    A function has one value at an input: two targets at one input are one target asked twice (the same
    value: the rows define nothing new) or a contradiction (two values).  Both are refused in one line.

    >>> check_function_targets([0.1, 0.2, 0.1], [0.5, 0.6, 0.5])
    Traceback (most recent call last):
    ValueError: targets 1 and 3 are the same target (input 0.1, output 0.5): give each target once
    >>> check_function_targets([0.1, 0.1], [0.5, 0.7])
    Traceback (most recent call last):
    ValueError: targets 1 and 2 are at the same input 0.1 with two outputs (0.5 and 0.7): a function has one value at an input
    """
    seen: dict[float, tuple[int, float]] = {}
    for number, (x, y) in enumerate(zip(numpy.asarray(inputs, dtype=float).tolist(),
                                        numpy.asarray(outputs, dtype=float).tolist()), start=1):
        if x in seen:
            first, value = seen[x]
            if value == y:
                raise ValueError(f"targets {first} and {number} are the same target (input {x:g}, output {y:g}): "
                                 "give each target once")
            raise ValueError(f"targets {first} and {number} are at the same input {x:g} with two outputs ({value:g} "
                             f"and {y:g}): a function has one value at an input")
        seen[x] = (number, y)


def _rows(theta: numpy.ndarray, phi: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
    """Freudenstein's equations as ``rows @ (K1, K2, K3) = right``."""
    return numpy.stack([numpy.cos(phi), -numpy.cos(theta), numpy.ones_like(theta)], axis=1), numpy.cos(theta - phi)


def three_point_design(theta: ArrayLike, phi: ArrayLike, ground: float = 1.0) -> FunctionDesign:
    """The four-bar through three precision points ``(theta_j, phi_j)`` exactly (one linear solve).

    >>> design = three_point_design([0.1, 0.6, 1.1], [1.9, 2.1, 2.4])
    >>> design.method, len(design.theta)
    ('three-point', 3)
    """
    theta_array, phi_array = _angles(theta, phi, 3)
    if len(theta_array) != 3:
        raise ValueError(f"a three-point design takes exactly three (theta, phi) pairs, got {len(theta_array)}")
    rows, right = _rows(theta_array, phi_array)
    with numpy.errstate(all="ignore"):
        try:
            k = numpy.linalg.solve(rows, right)
        except numpy.linalg.LinAlgError:
            k = numpy.full(3, numpy.nan)
    return _verified((float(k[0]), float(k[1]), float(k[2])), ground, theta_array, phi_array, "three-point")


def least_squares_design(theta: ArrayLike, phi: ArrayLike, ground: float = 1.0) -> FunctionDesign:
    """The four-bar closest to many ``(theta, phi)`` pairs: weighted linear least squares in the K's.

    Each Freudenstein equation is divided by its derivative with respect to phi at the
    current design, so that its residual is (to first order) the rocker-angle error.  Then
    Lawson's re-weighting (each weight multiplied by its point's error) drives the fit from
    the smallest sum of squares towards the smallest largest error, the measure the
    three-point design is judged by; the iterate with the smallest largest error is kept.

    >>> theta = numpy.linspace(0.2, 1.2, 20)
    >>> design = least_squares_design(theta, 1.8 + 0.4 * theta ** 2)
    >>> design.method
    'least-squares'
    """
    theta_array, phi_array = _angles(theta, phi, 3)
    rows, right = _rows(theta_array, phi_array)

    def fit(weights: numpy.ndarray) -> numpy.ndarray:
        return numpy.linalg.lstsq(rows * weights[:, None], right * weights, rcond=None)[0]

    def angle_errors(k: numpy.ndarray) -> numpy.ndarray:
        slope = numpy.abs(k[0] * numpy.sin(phi_array) + numpy.sin(theta_array - phi_array))
        return numpy.abs(rows @ k - right) / numpy.maximum(slope, 1e-300)

    with numpy.errstate(all="ignore"):
        k = fit(numpy.ones_like(theta_array))
        for _ in range(_REWEIGHTS):  # weights 1/slope: residuals in radians
            slope = numpy.abs(k[0] * numpy.sin(phi_array) + numpy.sin(theta_array - phi_array))
            if not numpy.all(numpy.isfinite(slope) & (slope > 0)):
                break
            k = fit(1 / slope)
        best, best_error = k, float(numpy.max(angle_errors(k)))
        lawson = numpy.full_like(theta_array, 1 / len(theta_array))
        for _ in range(_LAWSON_STEPS):
            errors = angle_errors(k)
            slope = numpy.abs(k[0] * numpy.sin(phi_array) + numpy.sin(theta_array - phi_array))
            if not (numpy.all(numpy.isfinite(errors)) and numpy.all(slope > 0)) or errors.max() == 0:
                break
            lawson = lawson * errors / numpy.sum(lawson * errors)
            k = fit(numpy.sqrt(lawson) / slope)
            error = float(numpy.max(angle_errors(k)))
            if error < best_error:
                best, best_error = k, error
    return _verified((float(best[0]), float(best[1]), float(best[2])), ground, theta_array, phi_array,
                     "least-squares")


def _solve_rocker(lengths: tuple[float, float, float, float], theta: numpy.ndarray, branch: int,
                  offsets: tuple[float, float] = (0.0, 0.0)):
    """The rocker angle (less ``offsets[1]``) at crank angles ``theta`` (plus ``offsets[0]``) on ``branch``."""
    a, b, c, d = lengths
    solved = dict(settled(shared_solver(fourbar, ("rocker", "singular")))(theta=theta + offsets[0], a=a, b=b, c=c, d=d,
                                                                 branch=branch))
    solved["rocker"] = solved["rocker"] - offsets[1]
    return solved


def structural_error(lengths: tuple[float, float, float, float], branch: int, theta: ArrayLike,
                     phi: ArrayLike, offsets: tuple[float, float] = (0.0, 0.0)) -> numpy.ndarray:
    """Generated minus wanted rocker angle (wrapped, radians) at crank angles ``theta`` on ``branch``.

    ``offsets`` are a design's ``crank_offset`` and ``rocker_offset``.  ``ValueError`` where
    the four-bar cannot be assembled on that branch or passes a toggle.

    >>> float(abs(structural_error((20, 66, 56, 80), 1, [0.0], [math.radians(110.74)])[0])) < 1e-4
    True
    """
    theta_array, phi_array = _angles(theta, phi, 1)
    solved = _solve_rocker(lengths, theta_array, branch, offsets)
    if not numpy.all(solved["assembled"]) or numpy.any(solved["singular"]):
        bad = theta_array[~numpy.asarray(solved["assembled"]) | numpy.asarray(solved["singular"])][0]
        raise ValueError(f"the four-bar {tuple(round(x, 6) for x in lengths)} cannot be assembled on branch "
                         f"{branch:+d} at crank angle {math.degrees(bad):.6g} deg (or passes a toggle there)")
    return numpy.array([wrap_angle(x) for x in numpy.asarray(solved["rocker"]) - phi_array])


def _verified(k: tuple[float, float, float], ground: float, theta: numpy.ndarray, phi: numpy.ndarray,
              method: str) -> FunctionDesign:
    """The design of the K's: its lengths, the branch through the points, its structural error over the range."""
    signed_crank, b, signed_rocker = lengths_from_coefficients(*k, ground=ground)
    a, c = abs(signed_crank), abs(signed_rocker)
    lengths = (a, b, c, ground)
    offsets = (math.pi if signed_crank < 0 else 0.0, math.pi if signed_rocker < 0 else 0.0)
    tolerance = 1e-6 if method == "three-point" else math.inf
    misses = {}
    for branch in (1, -1):
        solved = _solve_rocker(lengths, theta, branch, offsets)
        if numpy.all(solved["assembled"]):
            misses[branch] = float(numpy.max(numpy.abs([wrap_angle(x) for x in solved["rocker"] - phi])))
    if not misses or min(misses.values()) > tolerance:
        raise ValueError("the precision points lie on two branches of the four-bar (a branch defect): "
                         "no one assembly passes through them all; choose other angle ranges")
    branch = min(misses, key=misses.__getitem__)
    # Assembled, without a toggle, over the whole crank range; the error at the pairs themselves
    # (function_generator measures it against the function over the range).
    sweep = numpy.linspace(theta.min(), theta.max(), ERROR_SAMPLES)
    structural_error(lengths, branch, sweep, numpy.zeros_like(sweep), offsets)
    sweep, wanted = _sorted(theta, phi)
    errors = structural_error(lengths, branch, sweep, wanted, offsets)
    return FunctionDesign(a, b, c, ground, k, branch, method, *offsets, tuple(map(float, theta)), tuple(map(float, phi)),
                          grashof(a, b, c, ground).name, float(numpy.max(numpy.abs(errors))), sweep, errors)


def _sorted(theta: numpy.ndarray, phi: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
    order = numpy.argsort(theta)
    return theta[order], phi[order]


def function_generator(function: Callable[[float], float], x_range: tuple[float, float],
                       theta_range: tuple[float, float], phi_range: tuple[float, float], *,
                       method: str = "three-point", points: int = 3, ground: float = 1.0) -> FunctionDesign:
    """A four-bar generating ``y = function(x)`` for x in ``x_range``.

    x maps linearly onto the crank angle (``theta_range``: angles at the start and end of
    x), y onto the rocker angle (``phi_range``: at ``function(start)`` and
    ``function(end)``).  ``method="three-point"`` puts three precision points at the
    Chebyshev spacing; ``"least-squares"`` fits ``points`` Chebyshev-spaced points.  The
    structural error is measured against the function itself over the whole x range.

    Parameters
    ----------
    function : callable
        ``y = function(x)``.
    x_range : (float, float)
        The interval of x.
    theta_range : (float, float)
        The crank angles (radians) at its start and end.
    phi_range : (float, float)
        The rocker angles (radians) at ``function(start)`` and ``function(end)``.
    method : {"three-point", "least-squares"}, optional
        Three Chebyshev precision points (default), or a fit of ``points`` of them.
    points : int, optional
        Precision points of the least-squares fit (default 3).
    ground : float, optional
        The ground length (the design's scale), default 1.

    Returns
    -------
    FunctionDesign
        The four-bar, its branch and its structural error over the x range.

    Examples
    --------
    >>> import math, symlink
    >>> design = symlink.function_generator(math.log10, (1.0, 2.0), (math.radians(45), math.radians(105)),
    ...                                     (math.radians(135), math.radians(225)))
    >>> design.method, design.branch, design.structural_error < math.radians(0.5)
    ('three-point', 1, True)
    """
    x_start, x_end = (float(x) for x in x_range)
    theta_start, theta_end = (float(x) for x in theta_range)
    phi_start, phi_end = (float(x) for x in phi_range)
    if not all(math.isfinite(x) for x in (x_start, x_end, theta_start, theta_end, phi_start, phi_end)):
        raise ValueError("the x, theta and phi ranges must be finite numbers")
    if x_start == x_end or theta_start == theta_end or phi_start == phi_end:
        raise ValueError("the x, theta and phi ranges must each have two different ends")
    y_start, y_end = float(function(x_start)), float(function(x_end))
    if not (math.isfinite(y_start) and math.isfinite(y_end)) or y_start == y_end:
        raise ValueError(f"the function must take two different finite values at the ends of the x range, "
                         f"got {y_start:g} and {y_end:g}")

    def angles(x: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
        y = numpy.array([float(function(float(v))) for v in x])
        return (theta_start + (x - x_start) / (x_end - x_start) * (theta_end - theta_start),
                phi_start + (y - y_start) / (y_end - y_start) * (phi_end - phi_start))

    if method == "three-point":
        design = three_point_design(*angles(chebyshev_points(x_start, x_end, 3)), ground=ground)
    elif method == "least-squares":
        if points < 3:
            raise ValueError(f"least squares needs at least 3 points, got {points}")
        design = least_squares_design(*angles(chebyshev_points(x_start, x_end, points)), ground=ground)
    else:
        raise ValueError(f"method must be 'three-point' or 'least-squares', not {method!r}")
    sweep_x = numpy.linspace(x_start, x_end, ERROR_SAMPLES)
    sweep_theta, wanted = angles(sweep_x)
    errors = structural_error(design.lengths, design.branch, sweep_theta, wanted, design.offsets)
    return FunctionDesign(design.crank, design.coupler, design.rocker, design.ground, design.coefficients,
                          design.branch, design.method, design.crank_offset, design.rocker_offset, design.theta, design.phi, design.grashof,
                          float(numpy.max(numpy.abs(errors))), sweep_theta, errors)
