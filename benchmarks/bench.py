"""The benchmark (``python -m benchmarks``, also ``symlink bench``): run time against error of four-bar solvers, in one run.

The workload is a fixed-seed set of four-bars: random ones (link lengths
log-uniform over a decade, scaled by 10^-3 to 10^3, half of them Grashof,
half not) and the seed linkages (seeds 001, 002 and 003), each on both
branches.  Every (linkage, branch) is one sweep of crank angles drawn
uniformly over the angles where it can be assembled (so non-Grashof sweeps
come close to their toggle positions); N input values are split evenly over
the sweeps.  Every method is called the same way: once for all N values, with
the crank angle, the four lengths and the branch as per-value arrays (and, for
full kinematics, the crank's speed and acceleration), as a user evaluates
many linkages at once.  pylinkage alone, whose API simulates one linkage with
a crank that steps evenly, is called once a linkage on its own angles (below).

Methods (``--methods`` picks some); ``full`` ones compute positions, speeds and accelerations:

===========================  ==========  ====================================================
``symlink``                  full        symlink's generated NumPy module
``hand-numpy``               full        the generated code's formulas and shared terms written by hand in NumPy
``numba``                    full        the generated code's formulas and shared terms as a hand-written
                                         numba loop (cos and sin of the solved angles from their atan2
                                         arguments, as the generated code takes them)
``symengine-llvm``           full        symlink's expressions through SymEngine's ``Lambdify``
                                         (LLVM backend, ``cse=True``)
``lambdify-cse``             full        symlink's expressions through ``sympy.lambdify(cse=True)``
``pylinkage``                full        pylinkage's numba simulation (``step_fast_with_kinematics``)
``symlink-c``                full        symlink's generated C, compiled (:mod:`symlink.numeric.compiled`)
``hand-c``                   full        the same formulas as a hand-written C loop, same compiler and flags
``symlink-positions``        positions   symlink's generated NumPy module
``hand-numpy-positions``     positions   symlink's atan2 formula written by hand in NumPy
``halfangle-numpy``          positions   the textbook half-angle (Freudenstein) form, seed paper 003
``numba-positions``          positions   hand-written numba loop, atan2 formula
``symengine-llvm-positions`` positions   SymEngine LLVM ``Lambdify``
``lambdify-cse-positions``   positions   ``sympy.lambdify(cse=True)``
``pylinkage-positions``      positions   pylinkage's ``step_fast``
``symlink-c-positions``      positions   symlink's generated C
``hand-c-positions``         positions   a hand-written C loop of the atan2 formula, same compiler and flags
``halfangle-c``              positions   the textbook half-angle form in C
``newton``                   positions   a vectorised Newton iteration on the loop closure
``fsolve``                   positions   ``scipy.optimize.fsolve`` on the loop closure, one call per value
``sympy-evalf``              positions   substitution into symlink's closed forms and ``evalf``, per value
===========================  ==========  ====================================================

``fsolve`` and ``newton`` start 0.05 rad from the answer (what one continuation
step of a few degrees gives) and ``fsolve`` uses its default tolerance;
``fsolve`` and ``sympy-evalf`` run on a subsample of the smallest N, the C
methods only where a C compiler works, numba, SymEngine, pylinkage and scipy
where installed (the ``bench`` extra).  Methods that are not available are
skipped with a note.  pylinkage gets each sweep whose crank turns fully, with
as many evenly spaced angles over the turn (its N is therefore smaller).

Errors are measured against a 50-digit mpmath reference (the intersection
of two circles, computed independently of symlink; the rates from the loop
differentiated by hand, in mpmath), on every value for N <= ``reference``
values and on a fixed-seed subsample above that (the maximum is then the
maximum over the subsample).  The closure residual
``|a e^{i theta} + b e^{i beta} - d - c e^{i phi}| / max(a, b, c, d)`` is
computed on every value, in extended precision.  The physical limit is the
time of a C loop that does only the vector-math calls every solver of the
positions needs (cos, sin, a square root, two atan2) and two stores a value.
The C loops (symlink's, the hand-written ones, the limit) and the numba loops
are also timed loop against loop (``*-loop`` records): each loop alone on the
whole workload, writing into outputs allocated once beforehand, so that no
call's argument handling or fresh output pages weigh in (a call of a compiled
solver as a user makes it is the ``symlink-c`` records).

>>> records = benchmark(sizes=[200], methods=["symlink-positions", "hand-numpy-positions"], reference=50,
...                     verbose=False)
>>> sorted(r["method"] for r in records), all(r["max_error"] < 1e-6 for r in records)
(['hand-numpy-positions', 'symlink-positions'], True)
"""
from __future__ import annotations

import argparse
import datetime
import functools
import gc
import json
import math
import os
import platform
import shlex
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Sequence

import mpmath
import numpy

if __package__ in (None, ""):  # run as a script, python benchmarks/bench.py: import from this checkout
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from symlink.analysis import crank_range
from symlink.common.files import write_atomic
from symlink.symbolic.position import TOLERANCE

__all__ = ["benchmark", "METHODS", "main", "hand_numpy", "hand_numpy_everything", "halfangle_numpy", "hand_rates", "reference_positions",
           "reference_rates", "loop_records"]

METHODS = ("symlink", "hand-numpy", "numba", "symengine-llvm", "lambdify-cse", "pylinkage", "symlink-c", "hand-c",
           "symlink-positions", "hand-numpy-positions", "halfangle-numpy", "numba-positions",
           "symengine-llvm-positions", "lambdify-cse-positions", "pylinkage-positions", "symlink-c-positions",
           "hand-c-positions", "halfangle-c", "newton", "fsolve", "sympy-evalf")
POSITIONS = ["coupler", "rocker"]
RATES = ["coupler_speed", "rocker_speed", "coupler_accel", "rocker_accel"]
EVERYTHING = POSITIONS + RATES
CRANK_SPEED, CRANK_ACCEL = 10.5, 2.0
START_OFFSET = 0.05
#: (a, b, c, d) of the seed papers' four-bars (seed 002: its time ratio 1.25 design).
SEED_LINKAGES = {"seed001": (0.1, 0.4, 0.25, 0.30), "seed002": (16.084, 69.743, 50.0, 70.0),
                 "seed003": (20.0, 66.0, 56.0, 80.0)}
FULL_SIZES = (10**3, 10**4, 10**5, 10**6)
QUICK_SIZES = (10**3, 2 * 10**4)
ERROR_FLOOR = 1e-17  # where a plot needs a positive error
DOCS = Path(__file__).resolve().parent.parent / "docs"  # where --report writes the docs page and its plot


@dataclass
class Sweep:
    """One linkage on one branch: crank angles, and the reference at the sampled ones."""

    name: str
    lengths: tuple[float, float, float, float]
    branch: int
    theta: numpy.ndarray
    sample: numpy.ndarray = field(default_factory=lambda: numpy.zeros(0, dtype=int))
    reference: tuple[numpy.ndarray, ...] = ()  # beta_hi, beta_lo, phi_hi, phi_lo at the sample
    rates: tuple[numpy.ndarray, ...] = ()  # coupler and rocker speed and acceleration at the sample


# --- the workload and its reference ------------------------------------------

def is_grashof(a: float, b: float, c: float, d: float) -> bool:
    """s + l <= p + q: some link turns fully."""
    s, p, q, l = sorted((a, b, c, d))
    return s + l <= p + q


def random_fourbars(rng: numpy.random.Generator, count: int) -> list[tuple[str, tuple[float, ...]]]:
    """``count`` assemblable random four-bars, alternately Grashof and not, at random scales."""
    found: list[tuple[str, tuple[float, ...]]] = []
    while len(found) < count:
        want_grashof = len(found) % 2 == 0
        scale = 10.0 ** rng.uniform(-3, 3)
        lengths = tuple(float(v) for v in scale * 10.0 ** rng.uniform(0, 1, 4))
        spans = crank_range(*lengths)
        if is_grashof(*lengths) == want_grashof and sum(hi - lo for lo, hi in spans) > 0.1:
            found.append((f"{'grashof' if want_grashof else 'non-grashof'}-{len(found)}", lengths))
    return found


def _angles(rng: numpy.random.Generator, spans: list[tuple[float, float]], count: int) -> numpy.ndarray:
    widths = numpy.array([hi - lo for lo, hi in spans])
    which = rng.choice(len(spans), size=count, p=widths / widths.sum())
    lows = numpy.array([lo for lo, _ in spans])[which]
    return numpy.sort(lows + rng.uniform(0, 1, count) * widths[which])


def reference_positions(a: float, b: float, c: float, d: float, theta: float, branch: int):
    """(beta, phi) as mpmath numbers at 50 digits, or ``None`` where the loop cannot close.

    C is where the circle of radius b about B = a e^{i theta} meets the circle
    of radius c about D = (d, 0), on the left of B -> D for branch +1.

    >>> beta, phi = reference_positions(20, 66, 56, 80, 0.0, 1)
    >>> round(float(mpmath.degrees(phi)), 4)
    110.7424
    """
    with mpmath.workdps(50):
        a, b, c, d, theta = (mpmath.mpf(v) for v in (a, b, c, d, theta))
        bx, by = a * mpmath.cos(theta), a * mpmath.sin(theta)
        ux, uy = d - bx, -by
        distance = mpmath.hypot(ux, uy)
        along = (b * b - c * c + distance * distance) / (2 * distance)
        if b * b < along * along:
            return None
        height = branch * mpmath.sqrt(b * b - along * along)
        cx = bx + (along * ux - height * uy) / distance
        cy = by + (along * uy + height * ux) / distance
        return mpmath.atan2(cy - by, cx - bx), mpmath.atan2(cy, cx - d)


def reference_rates(a: float, b: float, c: float, theta: float, beta, phi, speed: float, accel: float) -> list:
    """Coupler and rocker speed and acceleration at 50 digits, from the exact positions (mpmath numbers).

    The loop ``a e^{i theta} + b e^{i beta} = d + c e^{i phi}`` differentiated by hand, its imaginary
    parts taken after turning by -phi and by -beta:
    ``beta' = -a w sin(theta - phi) / (b sin(beta - phi))``, ``phi' = -a w sin(theta - beta) / (c sin(beta - phi))``,
    and once more for the accelerations.

    >>> beta, phi = reference_positions(20, 66, 56, 80, 0.0, 1)
    >>> [round(float(x), 4) for x in reference_rates(20, 66, 56, 0.0, beta, phi, 10.5, 2.0)]
    [-3.5, -3.5, -19.2237, 36.9151]
    """
    with mpmath.workdps(50):
        a, b, c, theta, w, alpha = (mpmath.mpf(v) for v in (a, b, c, theta, speed, accel))
        s_tp, c_tp = mpmath.sin(theta - phi), mpmath.cos(theta - phi)
        s_tb, c_tb = mpmath.sin(theta - beta), mpmath.cos(theta - beta)
        s_bp, c_bp = mpmath.sin(beta - phi), mpmath.cos(beta - phi)
        beta_speed = -a * w * s_tp / (b * s_bp)
        phi_speed = -a * w * s_tb / (c * s_bp)
        beta_accel = -(a * alpha * s_tp + a * w * w * c_tp + b * beta_speed ** 2 * c_bp - c * phi_speed ** 2) / (b * s_bp)
        phi_accel = -(a * alpha * s_tb + a * w * w * c_tb + b * beta_speed ** 2 - c * phi_speed ** 2 * c_bp) / (c * s_bp)
        return [beta_speed, phi_speed, beta_accel, phi_accel]


def _split(value) -> tuple[float, float]:
    """A 50-digit number as a double-double (hi + lo)."""
    high = float(value)
    return high, float(value - mpmath.mpf(high))


def workload(size: int, seed: int, reference: int) -> list[Sweep]:
    """The sweeps of ``size`` input values in all, with the reference on at most ``reference`` of them."""
    rng = numpy.random.default_rng(seed)
    linkages = random_fourbars(rng, 6) + list(SEED_LINKAGES.items())
    sweeps = [Sweep(name, lengths, branch, numpy.zeros(0)) for name, lengths in linkages for branch in (1, -1)]
    counts = numpy.full(len(sweeps), size // len(sweeps))
    counts[: size % len(sweeps)] += 1
    share = min(reference, size) / size
    for sweep, count in zip(sweeps, counts):
        sweep.theta = _angles(rng, crank_range(*sweep.lengths), int(count))
        _with_reference(sweep, rng, share)
    return sweeps


def _with_reference(sweep: Sweep, rng: numpy.random.Generator, share: float) -> None:
    """Pick ``share`` of the sweep's values at random and put the 50-digit positions and rates there."""
    count = len(sweep.theta)
    picked = rng.choice(count, size=min(count, max(1, round(share * count))), replace=False)
    values = [reference_positions(*sweep.lengths, t, sweep.branch) for t in sweep.theta[picked]]
    kept = [i for i, v in zip(picked, values) if v is not None]
    sweep.sample = numpy.array(sorted(kept), dtype=int)
    exact = dict(zip(picked, values))
    parts = numpy.array([_split(exact[i][0]) + _split(exact[i][1]) for i in sweep.sample]).reshape(-1, 4)
    sweep.reference = tuple(parts.T)
    a, b, c, _ = sweep.lengths
    rates = [[float(x) for x in reference_rates(a, b, c, sweep.theta[i], *exact[i], CRANK_SPEED, CRANK_ACCEL)]
             for i in sweep.sample]
    sweep.rates = tuple(numpy.array(rates).reshape(-1, 4).T)


def pylinkage_sweeps(sweeps: list[Sweep], seed: int, reference: int) -> list[Sweep]:
    """pylinkage's workload: each sweep whose crank turns fully, as many angles evenly over a turn from its first.

    (pylinkage steps its crank evenly from where the linkage is assembled; see :mod:`benchmarks.peers`.)
    """
    from benchmarks.peers import even_angles
    rng = numpy.random.default_rng(seed + 1)
    full = [s for s in sweeps if len(s.theta) > 1 and crank_range(*s.lengths) == [(-math.pi, math.pi)]]
    size = sum(len(s.theta) for s in full)
    own = []
    for sweep in full:
        theta, _ = even_angles(float(sweep.theta[0]), len(sweep.theta))
        mine = Sweep(sweep.name, sweep.lengths, sweep.branch, theta)
        _with_reference(mine, rng, min(reference, size) / max(size, 1))
        own.append(mine)
    return own


def angle_errors(sweep: Sweep, beta: numpy.ndarray, phi: numpy.ndarray) -> numpy.ndarray:
    """|error| (rad) of the worse of beta and phi at the sampled values; NaN where a method gave none."""
    beta_hi, beta_lo, phi_hi, phi_lo = sweep.reference
    def wrapped(x):
        return numpy.abs(numpy.remainder(x + numpy.pi, 2 * numpy.pi) - numpy.pi)
    return numpy.maximum(wrapped((beta[sweep.sample] - beta_hi) - beta_lo),
                         wrapped((phi[sweep.sample] - phi_hi) - phi_lo))


def closure_residual(sweep: Sweep, beta: numpy.ndarray, phi: numpy.ndarray) -> numpy.ndarray:
    """Relative loop closure residual at every value, in extended precision."""
    a, b, c, d = (numpy.longdouble(v) for v in sweep.lengths)
    with numpy.errstate(invalid="ignore"):
        theta, beta, phi = (numpy.asarray(v, dtype=numpy.longdouble) for v in (sweep.theta, beta, phi))
        x = a * numpy.cos(theta) + b * numpy.cos(beta) - d - c * numpy.cos(phi)
        y = a * numpy.sin(theta) + b * numpy.sin(beta) - c * numpy.sin(phi)
        return numpy.asarray(numpy.hypot(x, y) / max(a, b, c, d), dtype=float)


# --- the methods -------------------------------------------------------------
#
# Every method gets the whole workload in one call: crank angles, the four lengths and the branch as per-value
# arrays (N values of 18 linkages), and for full kinematics the crank speed and acceleration; it returns a dict
# with at least "coupler" and "rocker" (and the four rates for full kinematics).  Only pylinkage, whose API
# simulates one linkage with a uniformly stepping crank, is called once a linkage (see _pylinkage).

def hand_numpy(theta, a, b, c, d, branch):
    """(beta, phi) by the atan2 formula that symlink derives (the triangle B, C, D), vectorised by hand.

    W = B - D = (a cos theta - d, a sin theta), w = |W|; Heron's product
    H = (b+c+w)(b+c-w)(w+b-c)(w-b+c) = ((b+c)^2 - w^2)(w^2 - (b-c)^2) = 4 b^2 c^2 sin^2(phi - beta), from w^2
    alone (no square root for w), clamped as symlink clamps it (rounding tolerated in proportion to
    8 b c v (a + b + c + v + d), v = |Wx| + |Wy| standing in for w, NaN beyond); then
    ``beta = atan2(-Wy L - Wx sigma sqrt(H), -Wx L + Wy sigma sqrt(H))`` with L = b^2 - c^2 + w^2 and
    ``phi = atan2(Wy M - Wx sigma sqrt(H), Wx M + Wy sigma sqrt(H))`` with M = w^2 - b^2 + c^2.
    All arguments broadcast (arrays of lengths and branches: many linkages at once).

    >>> beta, phi = hand_numpy(numpy.array([0.0]), 20.0, 66.0, 56.0, 80.0, 1)
    >>> round(float(numpy.degrees(phi[0])), 4), round(float(numpy.degrees(beta[0])), 4)
    (110.7424, 52.5127)
    """
    beta_y, beta_x, phi_y, phi_x, _, _ = _atan2_arguments(numpy.cos(theta), numpy.sin(theta), a, b, c, d, branch)
    return numpy.arctan2(beta_y, beta_x), numpy.arctan2(phi_y, phi_x)


def _atan2_arguments(cos_t, sin_t, a, b, c, d, branch):
    """The atan2 arguments of beta and phi (y, x each), the branch-signed root and w^2 (see :func:`hand_numpy`)."""
    wx, wy = a * cos_t - d, a * sin_t
    w_squared = wx * wx + wy * wy  # w only squared, as in the generated code: no square root for it
    s, t = b + c, b - c
    heron = (s * s - w_squared) * (w_squared - t * t)
    bound = numpy.abs(wx) + numpy.abs(wy)  # from w to sqrt(2) w: the clamp's stand-in for w
    with numpy.errstate(invalid="ignore"):
        root = numpy.where(heron >= -TOLERANCE * 8 * b * c * bound * (s + bound + d + a),
                           numpy.sqrt(numpy.maximum(heron, 0.0)), numpy.nan)
    along_b, along_c, across = s * t + w_squared, w_squared - s * t, root * branch
    return -wy * along_b - wx * across, -wx * along_b + wy * across, wy * along_c - wx * across, \
        wx * along_c + wy * across, across, w_squared


def hand_numpy_everything(theta, a, b, c, d, branch, speed, accel):
    """The six outputs of full kinematics by the generated code's formulas and shared terms, written in NumPy.

    cos and sin of beta and phi come from their atan2 arguments (``x / r``, ``y / r``, with
    ``r = 2 b w^2`` and ``2 c w^2``), not from further calls of cos and sin; the rates are the loop differentiated (:func:`hand_rates`) with
    ``1 / sin(beta - phi) = 2 b c / (sigma sqrt(H))``.

    >>> values = hand_numpy_everything(numpy.array([0.0]), 20.0, 66.0, 56.0, 80.0, 1, 10.5, 2.0)
    >>> [round(float(v[0]), 4) for v in values[2:]]
    [-3.5, -3.5, -19.2237, 36.9151]
    """
    cos_t, sin_t = numpy.cos(theta), numpy.sin(theta)
    beta_y, beta_x, phi_y, phi_x, across, w_squared = _atan2_arguments(cos_t, sin_t, a, b, c, d, branch)
    with numpy.errstate(invalid="ignore", divide="ignore"):
        # the atan2 arguments' lengths, 2 b w^2 and 2 c w^2 (Heron), as the generated code knows them
        beta_over, phi_over = 1.0 / (2.0 * b * w_squared), 1.0 / (2.0 * c * w_squared)
        sin_b, cos_b, sin_p, cos_p = beta_y * beta_over, beta_x * beta_over, phi_y * phi_over, phi_x * phi_over
        scale = 2.0 * b * c / across  # 1 / sin(beta - phi)
        over_b, over_c = scale / b, scale / c
        s_pt = cos_t * sin_p - cos_p * sin_t  # sin(phi - theta)
        s_bt = cos_t * sin_b - cos_b * sin_t  # sin(beta - theta)
        c_bp = cos_b * cos_p + sin_b * sin_p  # cos(beta - phi)
        a_speed, a_accel = a * speed, a * accel
        beta_speed, phi_speed = -s_pt * over_b * a_speed, -a_speed * s_bt * over_c
        beta_speed2, c_phi_speed2 = beta_speed * beta_speed, c * (phi_speed * phi_speed)
        beta_accel = over_b * (a * (speed * speed) * (cos_p * cos_t + sin_p * sin_t) + b * beta_speed2 * c_bp
                               - s_pt * a_accel - c_phi_speed2)
        phi_accel = over_c * (a * (speed * speed) * (cos_b * cos_t + sin_b * sin_t) + b * beta_speed2
                              - s_bt * a_accel - c_phi_speed2 * c_bp)
    return (numpy.arctan2(beta_y, beta_x), numpy.arctan2(phi_y, phi_x), beta_speed, phi_speed, beta_accel,
            phi_accel)


def halfangle_numpy(theta, a, b, c, d, branch):
    """(beta, phi) by the textbook half-angle solution (Freudenstein; seed paper 003), vectorised by hand.

    ``A t^2 + B t + C = 0`` with ``t = tan(phi/2)``, K = (a^2 - b^2 + c^2 + d^2)/2,
    A = K - a(d - c) cos(theta) - c d, B = -2 a c sin(theta),
    C = K - a(d + c) cos(theta) + c d; its "-" root is branch +1.  beta from
    the loop's x and y components with atan2 (the seed's asin loses the quadrant).

    >>> beta, phi = halfangle_numpy(numpy.array([0.0]), 20.0, 66.0, 56.0, 80.0, 1)
    >>> round(float(numpy.degrees(phi[0])), 4), round(float(numpy.degrees(beta[0])), 4)
    (110.7424, 52.5127)
    """
    cos_t, sin_t = numpy.cos(theta), numpy.sin(theta)
    k = (a * a - b * b + c * c + d * d) / 2
    A = (k - c * d) - a * (d - c) * cos_t
    B = (-2 * a * c) * sin_t
    C = (k + c * d) - a * (d + c) * cos_t
    with numpy.errstate(invalid="ignore", divide="ignore"):
        phi = 2 * numpy.arctan((-B - branch * numpy.sqrt(B * B - 4 * A * C)) / (2 * A))
    beta = numpy.arctan2(c * numpy.sin(phi) - a * sin_t, d + c * numpy.cos(phi) - a * cos_t)
    return beta, phi


def hand_rates(theta, a, b, c, beta, phi, speed, accel):
    """Coupler and rocker speeds and accelerations from the positions: the loop differentiated by hand.

    With ``a w e^{i theta} + b beta' e^{i beta} = c phi' e^{i phi}`` (imaginary parts after turning by
    -phi and -beta): ``beta' = -a w sin(theta - phi) / (b sin(beta - phi))``,
    ``phi' = a w sin(theta - beta) / (c sin(phi - beta))``, and once more for the accelerations.
    """
    s_tp, c_tp = numpy.sin(theta - phi), numpy.cos(theta - phi)
    s_tb, c_tb = numpy.sin(theta - beta), numpy.cos(theta - beta)
    s_bp, c_bp = numpy.sin(beta - phi), numpy.cos(beta - phi)
    with numpy.errstate(invalid="ignore", divide="ignore"):
        beta_speed = -a * speed * s_tp / (b * s_bp)
        phi_speed = -a * speed * s_tb / (c * s_bp)
        beta_accel = -(a * accel * s_tp + a * speed * speed * c_tp + b * beta_speed * beta_speed * c_bp
                       - c * phi_speed * phi_speed) / (b * s_bp)
        phi_accel = -(a * accel * s_tb + a * speed * speed * c_tb + b * beta_speed * beta_speed
                      - c * phi_speed * phi_speed * c_bp) / (c * s_bp)
    return beta_speed, phi_speed, beta_accel, phi_accel


def _as_dict(beta, phi, rates=None) -> dict:
    found = {"coupler": beta, "rocker": phi}
    if rates is not None:
        found.update(zip(RATES, rates))
    return found


def _start(sweep: Sweep) -> tuple[numpy.ndarray, numpy.ndarray]:
    beta, phi = hand_numpy(sweep.theta, *sweep.lengths, sweep.branch)
    return beta + START_OFFSET, phi + START_OFFSET


def newton(theta, a, b, c, d, beta, phi, iterations: int = 30):
    """Vectorised Newton on the closure's x and y from (beta, phi); stops when no step exceeds 1e-15 rad."""
    cos_t, sin_t = a * numpy.cos(theta) - d, a * numpy.sin(theta)
    with numpy.errstate(invalid="ignore", divide="ignore"):
        for _ in range(iterations):
            cb, sb, cp, sp_ = numpy.cos(beta), numpy.sin(beta), numpy.cos(phi), numpy.sin(phi)
            fx, fy = cos_t + b * cb - c * cp, sin_t + b * sb - c * sp_
            # J = [[-b sb, c sp], [b cb, -c cp]]; det = b c (sb cp - cb sp) = b c sin(beta - phi)
            det = b * c * (sb * cp - cb * sp_)
            step_beta = (-c * cp * fx - c * sp_ * fy) / det
            step_phi = (-b * cb * fx - b * sb * fy) / det
            beta, phi = beta - step_beta, phi - step_phi
            if not numpy.nanmax(numpy.abs(step_beta) + numpy.abs(step_phi), initial=0.0) > 1e-15:
                break
    return beta, phi


@dataclass
class Method:
    """A method's name, what it computes (``positions`` or ``full`` kinematics), its solver of the workload.

    ``solve`` takes the workload as one :class:`Sweep` with per-value arrays (see :func:`stacked`) and
    returns a dict of arrays.  ``limit``: values per size for the slow ones (taken from the reference
    sample, at the smallest N only).  ``per_linkage``: it takes the sweeps one at a time (pylinkage).
    """

    name: str
    solve: Callable[[Sweep], dict]
    kind: str = "positions"
    limit: int | None = None
    note: str = ""
    per_linkage: bool = False


def stacked(sweeps: list[Sweep]) -> Sweep:
    """All sweeps as one, with per-value arrays for the lengths and the branch."""
    counts = [len(s.theta) for s in sweeps]
    lengths = tuple(numpy.repeat([s.lengths[k] for s in sweeps], counts) for k in range(4))
    return Sweep("all", lengths, numpy.repeat(numpy.array([s.branch for s in sweeps], dtype=float), counts),
                 numpy.concatenate([s.theta for s in sweeps]))


def unstacked(result: dict, sweeps: list[Sweep]) -> list[dict]:
    """A stacked call's result, split back into one result per sweep."""
    bounds = numpy.cumsum([len(s.theta) for s in sweeps])[:-1]
    parts = {name: numpy.split(numpy.asarray(values), bounds) for name, values in result.items()}
    return [{name: pieces[i] for name, pieces in parts.items()} for i in range(len(sweeps))]


class Unavailable(Exception):
    """A method that cannot run here (a missing optional dependency or compiler)."""


def _keywords(function: Callable[..., dict], full: bool) -> Callable[[Sweep], dict]:
    """A workload solver from a function called as the generated ones are (keywords in, dict of arrays out)."""
    rates = {"thetadot": CRANK_SPEED, "thetaddot": CRANK_ACCEL} if full else {}

    def solve(sweep):
        a, b, c, d = sweep.lengths
        return function(theta=sweep.theta, a=a, b=b, c=c, d=d, branch=sweep.branch, **rates)
    return solve


def _inlined(definitions) -> dict:
    """``(symbol, expression)`` pairs in dependency order, each with the earlier ones substituted."""
    whole: dict = {}
    for symbol, expr in definitions:
        whole[symbol] = expr.xreplace(whole)
    return whole


def _outputs(full: bool) -> list[str]:
    return EVERYTHING if full else POSITIONS


def _symlink(full: bool):
    from symlink.numeric.cache import generated_code
    from symlink.io.scene import catalog_linkage
    return _keywords(generated_code(catalog_linkage("fourbar"), _outputs(full)).function, full)


def _symbolic(full: bool):
    """symlink's closed forms as plain SymPy expressions (clamped roots as square roots) and their arguments."""
    import sympy as sp
    from symlink.symbolic.position import ClampedSqrt
    from symlink.io.scene import catalog_linkage
    program = catalog_linkage("fourbar").program(_outputs(full))
    whole = _inlined(program.assignments)
    expressions = [program.outputs[name].xreplace(whole).replace(ClampedSqrt, lambda x, *scale: sp.sqrt(x))
                   for name in _outputs(full)]
    return list(program.arguments), expressions


def _values(sweep: Sweep, count: int) -> list:
    return [sweep.theta, *sweep.lengths, sweep.branch, CRANK_SPEED, CRANK_ACCEL][:count]


def _lambdify(full: bool):
    import sympy as sp
    arguments, expressions = _symbolic(full)
    function = sp.lambdify(arguments, expressions, modules="numpy", cse=True)

    def solve(sweep):
        with numpy.errstate(invalid="ignore", divide="ignore"):
            values = function(*_values(sweep, len(arguments)))
        return dict(zip(_outputs(full), values))
    return solve


def _symengine(full: bool):
    try:
        import symengine
    except ImportError:
        raise Unavailable("symengine is not installed (pip install 'symlink-kinematics[bench]')") from None
    arguments, expressions = _symbolic(full)
    try:
        function = symengine.Lambdify([symengine.sympify(a) for a in arguments],
                                      [symengine.sympify(e) for e in expressions], backend="llvm", cse=True)
        note = "LLVM backend, cse=True"
    except (RuntimeError, ValueError, TypeError):
        function = symengine.Lambdify([symengine.sympify(a) for a in arguments],
                                      [symengine.sympify(e) for e in expressions], backend="lambda", cse=True)
        note = "no LLVM in this symengine: its lambda backend"

    def solve(sweep):
        inputs = numpy.empty((len(sweep.theta), len(arguments)))
        for k, value in enumerate(_values(sweep, len(arguments))):
            inputs[:, k] = value
        values = function(inputs)  # one row of outputs per row of inputs
        return dict(zip(_outputs(full), numpy.asarray(values).T))
    solve.note = note  # type: ignore[attr-defined]
    return solve


def _numba(full: bool):
    try:
        import numba
    except ImportError:
        raise Unavailable("numba is not installed (pip install 'symlink-kinematics[bench]')") from None
    from benchmarks.numba_loops import numba_kernels
    positions, everything = numba_kernels(numba, TOLERANCE)

    def solve(sweep):
        a, b, c, d = sweep.lengths
        if not full:
            beta, phi = numpy.empty_like(sweep.theta), numpy.empty_like(sweep.theta)
            positions(sweep.theta, a, b, c, d, sweep.branch, beta, phi)
            return _as_dict(beta, phi)
        out = numpy.empty((6, len(sweep.theta)))
        everything(sweep.theta, a, b, c, d, sweep.branch, CRANK_SPEED, CRANK_ACCEL, *out)
        return dict(zip(EVERYTHING, out))
    return solve


def _hand(full: bool):
    def solve(sweep):
        if not full:
            return _as_dict(*hand_numpy(sweep.theta, *sweep.lengths, sweep.branch))
        values = hand_numpy_everything(sweep.theta, *sweep.lengths, sweep.branch, CRANK_SPEED, CRANK_ACCEL)
        return dict(zip(EVERYTHING, values))
    return solve


def _fsolve():
    try:
        from scipy.optimize import fsolve
    except ImportError:
        raise Unavailable("scipy is not installed (pip install 'symlink-kinematics[bench]')") from None

    def closure(unknowns, theta, a, b, c, d):
        beta, phi = unknowns
        return [a * math.cos(theta) + b * math.cos(beta) - d - c * math.cos(phi),
                a * math.sin(theta) + b * math.sin(beta) - c * math.sin(phi)]

    def solve(sweep):
        starts = _start(sweep)
        beta, phi = numpy.empty_like(sweep.theta), numpy.empty_like(sweep.theta)
        for i, theta in enumerate(sweep.theta):
            lengths = tuple(float(x[i]) for x in sweep.lengths)
            beta[i], phi[i] = fsolve(closure, (starts[0][i], starts[1][i]), args=(theta, *lengths))
        return _as_dict(beta, phi)
    return solve


def _newton():
    def solve(sweep):
        return _as_dict(*newton(sweep.theta, *sweep.lengths, *_start(sweep)))
    return solve


def _evalf():
    import sympy as sp
    from symlink.io.scene import catalog_linkage
    linkage = catalog_linkage("fourbar")
    whole = _inlined(linkage.positions.items())
    beta, phi = (whole[q] for q in linkage.unknowns)
    symbols = linkage.inputs + linkage.parameters + linkage.branches

    def solve(sweep):
        out = numpy.empty((2, len(sweep.theta)))
        for i, theta in enumerate(sweep.theta):
            numbers = (sp.Float(theta), *(sp.Float(float(x[i])) for x in sweep.lengths), int(sweep.branch[i]))
            values = dict(zip(symbols, numbers))
            out[:, i] = [float(beta.subs(values).evalf()), float(phi.subs(values).evalf())]
        return _as_dict(out[0], out[1])
    return solve


def _compiled(full: bool):
    try:
        from symlink.numeric.compiled import CompiledSolver, CompileError, CompilerUnavailable
    except ImportError:
        raise Unavailable("symlink.numeric.compiled is not available") from None
    from symlink.io.scene import catalog_linkage
    try:
        return _keywords(CompiledSolver(catalog_linkage("fourbar"), _outputs(full)).function, full)
    except CompilerUnavailable as error:
        raise Unavailable(f"no C compiler: {error}") from None
    except (CompileError, OSError) as error:
        raise Unavailable(f"cannot build or load the library: {error}") from None


def _hand_c(formula: str):
    try:
        from symlink.numeric.compiled import CompileError, CompilerUnavailable
        from benchmarks.hand_c import hand_everything, hand_library, hand_positions
    except ImportError:
        raise Unavailable("benchmarks.hand_c is not available") from None
    try:
        hand_library()
    except CompilerUnavailable as error:
        raise Unavailable(f"no C compiler: {error}") from None
    except (CompileError, OSError) as error:
        raise Unavailable(f"cannot build or load the library: {error}") from None

    def solve(sweep):
        if formula == "everything":
            return hand_everything(sweep.theta, *sweep.lengths, sweep.branch, CRANK_SPEED, CRANK_ACCEL)
        return hand_positions(sweep.theta, *sweep.lengths, sweep.branch, formula)
    return solve


def _pylinkage(full: bool):
    """pylinkage's compiled (numba) simulation: one linkage a call, its crank stepping uniformly.

    Its API takes no list of crank angles: a crank turns by a fixed step from where the linkage is
    assembled, and each position continues from the one before.  So it gets each sweep of a linkage
    whose crank turns fully (its angles are then evenly spaced over the turn, as many as the sweep has,
    see :func:`pylinkage_sweeps`), starting on the sweep's branch; errors are measured at its own angles.
    """
    try:
        import pylinkage  # noqa: F401
    except ImportError:
        raise Unavailable("pylinkage is not installed (pip install 'symlink-kinematics[bench]')") from None
    from benchmarks.peers import pylinkage_fourbar

    def solve(sweep):
        linkage, crank, step = pylinkage_fourbar(sweep)
        if full:
            linkage.set_input_velocity(crank, CRANK_SPEED, CRANK_ACCEL)
            positions, velocities, accelerations = linkage.step_fast_with_kinematics(iterations=len(sweep.theta))
            return pylinkage_angles(sweep, positions, velocities, accelerations)
        return pylinkage_angles(sweep, linkage.step_fast(iterations=len(sweep.theta)))
    return solve


def pylinkage_angles(sweep: Sweep, positions, velocities=None, accelerations=None) -> dict:
    """Coupler and rocker angles (and rates) from pylinkage's joint positions: B is joint 2, C joint 3."""
    a, b, c, d = sweep.lengths
    bx, by, cx, cy = positions[:, 2, 0], positions[:, 2, 1], positions[:, 3, 0], positions[:, 3, 1]
    beta, phi = numpy.arctan2(cy - by, cx - bx), numpy.arctan2(cy, cx - d)
    if velocities is None:
        return _as_dict(beta, phi)
    # angular rates from the joints' velocities and accelerations: w = (r x v) / |r|^2
    rx, ry, ux, uy = cx - bx, cy - by, cx - d, cy
    vbx, vby, vcx, vcy = velocities[:, 2, 0], velocities[:, 2, 1], velocities[:, 3, 0], velocities[:, 3, 1]
    abx, aby, acx, acy = accelerations[:, 2, 0], accelerations[:, 2, 1], accelerations[:, 3, 0], accelerations[:, 3, 1]
    beta_speed = (rx * (vcy - vby) - ry * (vcx - vbx)) / (b * b)
    phi_speed = (ux * vcy - uy * vcx) / (c * c)
    beta_accel = (rx * (acy - aby) - ry * (acx - abx)) / (b * b)
    phi_accel = (ux * acy - uy * acx) / (c * c)
    return _as_dict(beta, phi, (beta_speed, phi_speed, beta_accel, phi_accel))


def _methods(quick: bool) -> dict[str, Callable[[], Method]]:
    """Every method by name: how to make it (a method that cannot run here raises :class:`Unavailable`)."""
    def made(name, factory, kind, **options):
        def make():
            solve = factory()
            return Method(name, solve, kind, note=getattr(solve, "note", options.pop("note", "")), **options)
        return make
    return {
        "symlink": made("symlink", lambda: _symlink(True), "full"),
        "hand-numpy": made("hand-numpy", lambda: _hand(True), "full"),
        "numba": made("numba", lambda: _numba(True), "full"),
        "symengine-llvm": made("symengine-llvm", lambda: _symengine(True), "full"),
        "lambdify-cse": made("lambdify-cse", lambda: _lambdify(True), "full"),
        "pylinkage": made("pylinkage", lambda: _pylinkage(True), "full", per_linkage=True,
                          note="its own evenly stepped crank, crank-rocker sweeps only"),
        "symlink-c": made("symlink-c", lambda: _compiled(True), "full"),
        "symlink-positions": made("symlink-positions", lambda: _symlink(False), "positions"),
        "hand-numpy-positions": made("hand-numpy-positions", lambda: _hand(False), "positions"),
        "halfangle-numpy": made("halfangle-numpy", lambda: (lambda s: _as_dict(*halfangle_numpy(
            s.theta, *s.lengths, s.branch))), "positions", note="textbook half-angle form"),
        "numba-positions": made("numba-positions", lambda: _numba(False), "positions"),
        "symengine-llvm-positions": made("symengine-llvm-positions", lambda: _symengine(False), "positions"),
        "lambdify-cse-positions": made("lambdify-cse-positions", lambda: _lambdify(False), "positions"),
        "pylinkage-positions": made("pylinkage-positions", lambda: _pylinkage(False), "positions", per_linkage=True,
                                    note="its own evenly stepped crank, crank-rocker sweeps only"),
        "symlink-c-positions": made("symlink-c-positions", lambda: _compiled(False), "positions"),
        "hand-c": made("hand-c", lambda: _hand_c("everything"), "full"),
        "hand-c-positions": made("hand-c-positions", lambda: _hand_c("atan2"), "positions"),
        "halfangle-c": made("halfangle-c", lambda: _hand_c("halfangle"), "positions",
                            note="textbook half-angle form"),
        "newton": made("newton", _newton, "positions"),
        "fsolve": made("fsolve", _fsolve, "positions", limit=200 if quick else 1000, note="default xtol"),
        "sympy-evalf": made("sympy-evalf", _evalf, "positions", limit=10 if quick else 60),
    }


# --- measuring ---------------------------------------------------------------

def _subset(sweeps: list[Sweep], limit: int) -> list[Sweep]:
    """Sweeps cut down to about ``limit`` of their reference values in all (for the slow methods)."""
    total = sum(len(s.sample) for s in sweeps)
    cut = []
    for sweep in sweeps:
        keep = sweep.sample[: max(1, round(limit * len(sweep.sample) / max(total, 1)))]
        if not len(keep):
            continue
        part = Sweep(sweep.name, sweep.lengths, sweep.branch, sweep.theta[keep], numpy.arange(len(keep)),
                     tuple(r[: len(keep)] for r in sweep.reference), tuple(r[: len(keep)] for r in sweep.rates))
        cut.append(part)
    return cut


def _timed(methods: list[Method], work: dict[str, list[Sweep]], budget: float,
           least: float = 0.01) -> dict[str, tuple[float, list]]:
    """Best time of each method over its whole workload, and its results, one per sweep.

    Each method is called once for the whole workload (pylinkage: once a linkage).  The methods take
    turns, round after round (up to 7), so that a change in the machine's load falls on all of them
    alike; after three rounds, a method sits out further rounds once its time would exceed ``budget``
    seconds (at 10^7 values a call takes seconds, and a single call pays for new memory that later
    rounds reuse: symlink's 10^7 time a value read 226 ns from one round, 183 ns from several).  A method
    whose first call took less than ``least`` seconds is called that many times more in each later
    round, back to back, and timed by their mean: a single call of a few hundred microseconds,
    right after thirteen other methods have run, measures cold caches as much as the method.  The
    garbage collector is off while timing, as in :mod:`timeit`.
    """
    best = {m.name: math.inf for m in methods}
    spent = {m.name: 0.0 for m in methods}
    calls_a_round = {m.name: 1 for m in methods}
    results: dict[str, list] = {}
    calls = {m.name: work[m.name] if m.per_linkage else [stacked(work[m.name])] for m in methods}
    gc.collect()
    gc.disable()
    try:
        for round_ in range(7):
            for method in methods:
                if round_ >= 3 and spent[method.name] + best[method.name] * calls_a_round[method.name] > budget:
                    continue
                repeats = calls_a_round[method.name]
                results[method.name] = []  # the previous round's arrays are freed before timing
                start = time.perf_counter()
                for _ in range(repeats):
                    results[method.name] = [method.solve(sweep) for sweep in calls[method.name]]
                elapsed = time.perf_counter() - start
                best[method.name] = min(best[method.name], elapsed / repeats)
                spent[method.name] += elapsed
                if round_ == 0 and elapsed < least:
                    calls_a_round[method.name] = min(100, math.ceil(least / max(elapsed, 1e-6)))
    finally:
        gc.enable()
    for method in methods:
        if not method.per_linkage:
            results[method.name] = unstacked(results[method.name][0], work[method.name])
    return {name: (best[name], results[name]) for name in best}


def rate_errors(sweep: Sweep, result: dict) -> numpy.ndarray:
    """Relative error of the worst of the four rates at the sampled values (NaN where a method gave none).

    Each rate's error is scaled by its size or the crank's (omega for speeds, omega^2 for accelerations),
    whichever is larger, so that a rate passing through zero does not inflate it.
    """
    scales = (CRANK_SPEED, CRANK_SPEED, CRANK_SPEED ** 2, CRANK_SPEED ** 2)
    worst = numpy.zeros(len(sweep.sample))
    for name, exact, scale in zip(RATES, sweep.rates, scales):
        found = numpy.asarray(result[name])[sweep.sample]
        worst = numpy.maximum(worst, numpy.abs(found - exact) / numpy.maximum(numpy.abs(exact), scale))
    return worst


def _record(method: Method, sweeps: list[Sweep], seconds: float, results: list) -> dict:
    """One record: time per value and the errors of ``method`` on ``sweeps``."""
    n = sum(len(s.theta) for s in sweeps)
    errors = numpy.concatenate([angle_errors(s, r["coupler"], r["rocker"]) for s, r in zip(sweeps, results)])
    residuals = numpy.concatenate([closure_residual(s, r["coupler"], r["rocker"]) for s, r in zip(sweeps, results)])
    failures = int(numpy.sum(~numpy.isfinite(errors)))
    finite = errors[numpy.isfinite(errors)]
    record = {
        "method": method.name, "kind": method.kind, "n": n, "us_per_value": seconds / n * 1e6,
        "max_error": float(finite.max()) if finite.size else None,
        "median_error": float(numpy.median(finite)) if finite.size else None,
        "max_residual": float(numpy.nanmax(residuals)) if numpy.isfinite(residuals).any() else None,
        "failures": failures, "reference_n": int(errors.size), "note": method.note,
        "max_rate_error": None,
    }
    if method.kind == "full":
        rates = numpy.concatenate([rate_errors(s, r) for s, r in zip(sweeps, results)])
        rates = rates[numpy.isfinite(rates)]
        record["max_rate_error"] = float(rates.max()) if rates.size else None
    return record


def _ratios(records: list[dict]) -> None:
    """Each record's time per value over symlink's of the same kind at the same N (the smallest N for subsampled
    methods): ``symlink`` for full kinematics, ``symlink-positions`` for positions."""
    reference = {"full": "symlink", "positions": "symlink-positions"}
    times = {(r["kind"], r.get("size", r["n"])): r["us_per_value"] for r in records
             if r["method"] == reference.get(r["kind"])}
    for record in records:
        mine = {n: t for (kind, n), t in times.items() if kind == record["kind"]}
        if not mine:
            record["ratio_to_symlink"] = None
            continue
        size = record.get("size", record["n"])
        size = size if size in mine else min(mine)
        record["ratio_to_symlink"] = record["us_per_value"] / mine[size]
        record["compared_at_n"] = size
    for record in records:
        record.setdefault("size", record["n"])


_DERIVATION_SCRIPT = r"""
import json, sys, time
started = time.perf_counter()
from symlink.numeric import cache
from symlink.io.scene import catalog_linkage
imported = time.perf_counter()
result = {"import_symlink": imported - started, "scenes": []}
for name, outputs in json.loads(sys.argv[1]):
    start = time.perf_counter()
    linkage = catalog_linkage(name)
    built = time.perf_counter()
    code = cache.generated_code(linkage, outputs)
    done = time.perf_counter()
    again = time.perf_counter()
    cache.generated_code(linkage, outputs)
    memory = time.perf_counter() - again
    result["scenes"].append({"linkage": name, "outputs": len(outputs), "build_linkage": built - start,
                             "code": done - built, "memory": memory, "source": code.source})
print(json.dumps(result))
"""


def derivation_scenes(quick: bool) -> list[tuple[str, list[str]]]:
    """The four-bar's positions and its full scene; unless quick, every closed-form catalog linkage's full scene."""
    from symlink.mechanism.catalog import CATALOG
    from symlink.io.scene import catalog_linkage
    from symlink.symbolic.vectors import acceleration, rate
    scenes = [("fourbar", POSITIONS), ("fourbar", EVERYTHING)]
    for name in ([] if quick else CATALOG):
        linkage = catalog_linkage(name)
        if name != "fourbar" and getattr(linkage, "has_closed_form", True):
            unknowns = linkage.unknowns
            scenes.append((name, [q.name for q in unknowns] + [rate(q).name for q in unknowns]
                           + [acceleration(q).name for q in unknowns]))
    return scenes


def derivation_times(scenes: list[tuple[str, list[str]]]) -> list[dict]:
    """Seconds to get each scene's code in a new process: with an empty cache, then from the disk cache."""
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        path = os.pathsep.join([str(Path(__file__).resolve().parent.parent), os.environ.get("PYTHONPATH", "")])
        env = dict(os.environ, SYMLINK_CACHE=folder, PYTHONPATH=path)
        runs = []
        for _ in ("cold", "cached"):
            done = subprocess.run([sys.executable, "-c", _DERIVATION_SCRIPT, json.dumps(scenes)],
                                  capture_output=True, text=True, env=env, check=True)
            runs.append(json.loads(done.stdout))
    from symlink.codegen.numpy import load_numpy_module
    for cold, cached in zip(runs[0]["scenes"], runs[1]["scenes"]):
        loads = []
        for _ in range(5):
            start = time.perf_counter()
            load_numpy_module(cold["source"])
            loads.append(time.perf_counter() - start)
        rows.append({"linkage": cold["linkage"], "outputs": cold["outputs"],
                     "cold": cold["build_linkage"] + cold["code"], "cached": cached["build_linkage"] + cached["code"],
                     "build_linkage": cached["build_linkage"], "memory": cold["memory"], "load_module": min(loads)})
    return rows


#: The loops timed loop against loop, by the method whose loop each is: (record name, kind).
LOOPS = {"symlink-c-positions": ("symlink-c-positions-loop", "positions"), "symlink-c": ("symlink-c-loop", "full"),
         "hand-c-positions": ("hand-c-positions-loop", "positions"), "hand-c": ("hand-c-loop", "full"),
         "numba-positions": ("numba-positions-loop", "positions"), "numba": ("numba-loop", "full")}
LIMIT_NOTE = "C loop of cos, sin, sqrt, 2 atan2 and 2 stores a value (symlink.numeric.compiled's flags, glibc libmvec)"


def _symlink_c_loop(work: Sweep, full: bool) -> Callable[[], object]:
    """The generated C loop function alone on ``work``, into outputs allocated here once."""
    from symlink.numeric.compiled import CompiledSolver
    from symlink.io.scene import catalog_linkage
    entry = CompiledSolver(catalog_linkage("fourbar"), _outputs(full)).function
    a, b, c, d = work.lengths
    given = {"theta": work.theta, "a": a, "b": b, "c": c, "d": d, "branch": work.branch,
             "thetadot": numpy.array([CRANK_SPEED]), "thetaddot": numpy.array([CRANK_ACCEL])}
    arrays = [numpy.ascontiguousarray(given[name], dtype=numpy.float64) for name in entry.arguments]
    slots = [value for array in arrays for value in (array.ctypes.data, 0 if array.size == 1 else 1)]
    outputs = [numpy.empty(len(work.theta), dtype=numpy.uint8 if flag else numpy.float64) for flag in entry.flags]
    outputs.append(numpy.empty(len(work.theta), dtype=numpy.uint8))
    pointers = [o.ctypes.data for o in outputs]
    kept = arrays + outputs  # alive as long as the loop uses their addresses

    def loop():
        entry.entry(len(work.theta), *slots, *pointers)
        return kept
    return loop


def _hand_c_loop(work: Sweep, full: bool) -> Callable[[], object]:
    """The hand-written C loop alone on ``work``, into outputs allocated here once."""
    from benchmarks.hand_c import hand_library
    library = hand_library()
    n = len(work.theta)
    arrays = [numpy.ascontiguousarray(x, dtype=numpy.float64) for x in (work.theta, *work.lengths, work.branch)]
    # the flags the generated loop writes too: assembled, and with the rates singular
    outputs = [numpy.empty(n) for _ in range(6 if full else 2)] + [numpy.empty(n, dtype=numpy.uint8)
                                                                   for _ in range(2 if full else 1)]
    inputs, written = [x.ctypes.data for x in arrays], [o.ctypes.data for o in outputs]
    kept = arrays + outputs
    if full:
        def loop():
            library.hand_fourbar_everything(n, *inputs, CRANK_SPEED, CRANK_ACCEL, *written)
            return kept
    else:
        def loop():
            library.hand_fourbar_positions(n, *inputs, *written)
            return kept
    return loop


def _numba_loop(work: Sweep, full: bool) -> Callable[[], object]:
    """The numba loop alone on ``work``, into outputs allocated here once."""
    import numba
    from benchmarks.numba_loops import numba_kernels
    positions, everything = numba_kernels(numba, TOLERANCE)
    arrays = [numpy.ascontiguousarray(x, dtype=numpy.float64) for x in (work.theta, *work.lengths, work.branch)]
    outputs = [numpy.empty(len(work.theta)) for _ in range(6 if full else 2)]
    if full:
        return lambda: everything(*arrays, CRANK_SPEED, CRANK_ACCEL, *outputs)
    return lambda: positions(*arrays, *outputs)


def _limit_loop(work: Sweep) -> Callable[[], object]:
    """The physical-limit loop (:func:`benchmarks.hand_c.vector_math_limit`) alone on ``work``'s crank angles."""
    from benchmarks.hand_c import hand_library
    library = hand_library()
    theta = numpy.ascontiguousarray(work.theta, dtype=numpy.float64)
    outputs = [numpy.empty_like(theta), numpy.empty_like(theta)]
    kept = [theta] + outputs
    addresses = [theta.ctypes.data] + [o.ctypes.data for o in outputs]

    def loop():
        library.vector_math_limit(len(theta), *addresses)
        return kept
    return loop


def _best_of_loops(loops: dict[str, Callable[[], object]], budget: float, least: float = 0.005) -> dict[str, float]:
    """Best seconds a call of each loop, the loops taking turns round after round (at least 3, up to 7).

    A loop faster than ``least`` seconds is called back to back enough times a round and timed by their mean.
    """
    best = {name: math.inf for name in loops}
    repeats = {name: 1 for name in loops}
    spent = {name: 0.0 for name in loops}
    for loop in loops.values():
        loop()  # pages of the outputs touched before any clock starts
    gc.collect()
    gc.disable()
    try:
        for round_ in range(7):
            for name, loop in loops.items():
                if round_ >= 3 and spent[name] + best[name] * repeats[name] > budget:
                    continue
                start = time.perf_counter()
                for _ in range(repeats[name]):
                    loop()
                elapsed = time.perf_counter() - start
                best[name] = min(best[name], elapsed / repeats[name])
                spent[name] += elapsed
                if round_ == 0 and elapsed < least:
                    repeats[name] = min(1000, math.ceil(least / max(elapsed, 1e-7)))
    finally:
        gc.enable()
    return best


def loop_records(sweeps: list[Sweep], methods: Sequence[str], limit: bool, budget: float = 0.5) -> list[dict]:
    """Loop against loop: the C and numba loops of ``methods`` (and the physical limit) on the whole workload.

    Each loop writes into outputs allocated once beforehand, so that neither a call's argument handling
    nor new output pages weigh in; a loop that cannot run here (no compiler, no numba) is left out.
    """
    work = stacked(sweeps)
    makers: dict[str, Callable[[], Callable[[], object]]] = {}
    for method in methods:
        if method in LOOPS:
            full = LOOPS[method][1] == "full"
            maker = {"symlink-c": _symlink_c_loop, "hand-c": _hand_c_loop, "numba": _numba_loop}[
                method.removesuffix("-positions")]
            makers[LOOPS[method][0]] = functools.partial(maker, work, full)
    if limit:
        makers["physical-limit"] = functools.partial(_limit_loop, work)
    loops = {}
    for name, make in makers.items():
        try:
            if not name.startswith("numba"):
                import symlink.numeric.compiled  # noqa: F401 - every C loop is built by it (ImportError where it is not there)
            loops[name] = make()
        except (ImportError, OSError, RuntimeError):  # no numba, no compiler (CompilerUnavailable, CompileError)
            continue
    kinds = {name: kind for name, kind in LOOPS.values()}
    records = []
    for name, seconds in _best_of_loops(loops, budget).items():
        n = len(work.theta)
        records.append({"method": name, "kind": kinds.get(name, "positions"), "n": n, "size": n,
                        "us_per_value": seconds / n * 1e6, "max_error": None, "median_error": None,
                        "max_residual": None, "failures": 0, "reference_n": 0, "max_rate_error": None,
                        "note": LIMIT_NOTE if name == "physical-limit" else "the loop alone, outputs allocated once"})
    return records


def benchmark(sizes: Sequence[int] = FULL_SIZES, methods: Sequence[str] = METHODS, quick: bool = False,
              seed: int = 2024, reference: int = 2000, verbose: bool = True, limit: bool = False) -> list[dict]:
    """Measure ``methods`` at each size; returns the records (and prints progress if ``verbose``).

    The C and numba loops of the chosen methods are also timed loop against loop (:func:`loop_records`);
    ``limit``: also the physical limit at each size, as a record of its own.
    """
    factories = _methods(quick)
    unknown = [m for m in methods if m not in factories]
    if unknown:
        raise ValueError(f"unknown method {unknown[0]!r}; choose from {', '.join(METHODS)}")
    if not sizes or any(n < 1 for n in sizes):
        raise ValueError(f"sizes must be positive, got {list(sizes)}")
    ready: list[Method] = []
    for name in methods:
        try:
            ready.append(factories[name]())
        except Unavailable as why:
            _say(verbose, f"skipped {name}: {why}")
    records = []
    for size in sorted(sizes):
        sweeps = workload(size, seed, reference)
        running = [m for m in ready if m.limit is None or size == min(sizes)]
        own = pylinkage_sweeps(sweeps, seed, reference) if any(m.per_linkage for m in running) else []
        work = {m.name: own if m.per_linkage else sweeps if m.limit is None else _subset(sweeps, m.limit)
                for m in running}
        timed = _timed(running, work, budget=0.5 if quick else 2.0)
        for method in running:
            records.append({**_record(method, work[method.name], *timed[method.name]), "size": size})
            _say(verbose, f"  {method.name:>24} N={records[-1]['n']:<8} {records[-1]['us_per_value']:.4g} us/value")
        for found in loop_records(sweeps, [m.name for m in ready], limit, budget=0.5 if quick else 2.0):
            records.append(found)
            _say(verbose, f"  {found['method']:>24} N={size:<8} {found['us_per_value']:.4g} us/value")
    _ratios(records)
    return records


def _say(verbose: bool, text: str) -> None:
    """A progress line, on stderr (stdout carries the results only)."""
    if verbose:
        print(text, file=sys.stderr, flush=True)


# --- reporting ---------------------------------------------------------------

def _short(value, digits: int = 2) -> str:
    return "-" if value is None else f"{value:.{digits}e}"


def table(records: list[dict]) -> str:
    """The records as an aligned text table: full kinematics first, then positions, each by N.

    ``ratio`` is the time per value over symlink's NumPy module's of the same kind at the same N;
    ``rate err`` the largest relative error of the speeds and accelerations (full kinematics).
    """
    header = f"{'method':>24} {'kind':>9} {'N':>8} {'us/value':>10} {'ratio':>8} {'max err':>9} {'median err':>10} " \
             f"{'max resid':>9} {'rate err':>9} {'fail':>5}"
    lines = [header]
    order = {"full": 0, "positions": 1}
    for r in sorted(records, key=lambda r: (order.get(r["kind"], 2), r["n"])):
        ratio = "-" if r.get("ratio_to_symlink") is None else f"{r['ratio_to_symlink']:.3g}"
        lines.append(f"{r['method']:>24} {r['kind']:>9} {r['n']:>8} {r['us_per_value']:>10.4g} {ratio:>8} "
                     f"{_short(r['max_error']):>9} {_short(r['median_error']):>10} {_short(r['max_residual']):>9} "
                     f"{_short(r.get('max_rate_error')):>9} {r['failures']:>5}")
    return "\n".join(lines)


def _find(records, method, size=None):
    """The record of ``method`` at workload size ``size`` (the N asked for; pylinkage's own N may be smaller)."""
    found = [r for r in records if r["method"] == method and (size is None or r.get("size", r["n"]) == size)]
    return found[-1] if found else None


def targets(records: list[dict]) -> list[str]:
    """Ratios measured in this run, each against a fair baseline, with the issue's targets marked held or missed.

    Every comparison is between methods called the same way on the same values, at the largest N both have.
    """
    lines = []

    def verdict(ok):
        return "held" if ok else "MISSED"

    def largest(*names):
        sizes = [{r.get("size", r["n"]) for r in records if r["method"] == name} for name in names]
        common = set.intersection(*sizes) if sizes else set()
        return max(common) if common else None

    def ratio_line(mine, theirs, what, target=None, at=None):
        size = at if at is not None else largest(mine, theirs)
        first, second = _find(records, mine, size), _find(records, theirs, size)
        if not (first and second):
            return
        ratio = first["us_per_value"] / second["us_per_value"]
        goal = "" if target is None else f" (target <= {target}x: {verdict(ratio <= target)})"
        lines.append(f"{mine} / {theirs} at N={size}: {ratio:.2f}x{goal}{what}")

    ratio_line("symlink", "numba", "; full kinematics: the NumPy module against a numba loop of the same formulas")
    ratio_line("symlink-positions", "hand-numpy-positions", "; the same atan2 formula written by hand in NumPy")
    accurate = []
    for mine, theirs in (("symlink-positions", "halfangle-numpy"),):
        size = largest(mine, theirs)
        first, second = _find(records, mine, size), _find(records, theirs, size)
        if first and second:
            ratio = first["us_per_value"] / second["us_per_value"]
            accurate.append(f"{mine} / {theirs} (textbook half-angle form) at N={size}: {ratio:.2f}x; max error "
                            f"{_short(first['max_error'])} vs {_short(second['max_error'])} rad")
    lines += accurate
    for peer in ("symengine-llvm", "lambdify-cse", "pylinkage"):
        size = largest("symlink", peer)
        first, second = _find(records, "symlink", size), _find(records, peer, size)
        if first and second:
            lines.append(f"symlink / {peer} at N={size}: {first['us_per_value'] / second['us_per_value']:.2f}x "
                         f"(full kinematics; {peer} {second['us_per_value']:.3g} us a value"
                         + ("" if second["n"] == size else f" on its {second['n']} values") + ")")
    full, positions = largest("symlink"), largest("symlink-positions")
    if full is not None:  # flat in N: the largest N against 10^5 (or the smallest N measured)
        sizes = sorted({r.get("size", r["n"]) for r in records if r["method"] == "symlink"})
        base = 10**5 if 10**5 in sizes and full > 10**5 else sizes[0]
        first, last = _find(records, "symlink", base), _find(records, "symlink", full)
        if base != full:
            ratio = last["us_per_value"] / first["us_per_value"]
            goal = f" (target <= 1.2x: {verdict(ratio <= 1.2)})" if base == 10**5 else ""
            lines.append(f"symlink at N={full} / at N={base}, per value: {ratio:.2f}x{goal}; flat in N")
    ratio_line("symlink-c", "numba", "; calls: the generated C against a numba loop of the same formulas")
    ratio_line("symlink-c-positions", "numba-positions", "; calls, positions")
    ratio_line("symlink-c-positions", "hand-c-positions", "; calls: the same formulas in hand-written C, same flags")
    ratio_line("symlink-c", "hand-c", "; calls, full kinematics")
    ratio_line("symlink-positions", "symlink-c-positions", "; the NumPy module over the compiled C")
    ratio_line("symlink-c-positions-loop", "hand-c-positions-loop", "; loop against loop: the generated C against "
               "the hand-written C of the same formulas, with restrict", 1.1)
    ratio_line("symlink-c-loop", "hand-c-loop", "; loop against loop, full kinematics", 1.1)
    ratio_line("symlink-c-positions-loop", "numba-positions-loop", "; loop against loop, positions")
    ratio_line("symlink-c-loop", "numba-loop", "; loop against loop, full kinematics")
    # The headline: the user's call (new outputs, arguments checked, a Results record) against the physical
    # limit, beside its loop alone (benchmarks.call_cost has the call into out= and the page faults).
    for call, loop in (("symlink-c-positions", "symlink-c-positions-loop"), ("symlink-c", "symlink-c-loop"),
                       ("numba-positions", "numba-positions-loop"), ("numba", "numba-loop")):
        size = largest(call, "physical-limit")
        mine, alone, limit = (_find(records, name, size) for name in (call, loop, "physical-limit"))
        if limit and mine:
            beside = (f"; its loop alone {alone['us_per_value'] / limit['us_per_value']:.2f}x, the call "
                      f"{mine['us_per_value'] / alone['us_per_value']:.2f}x its loop") if alone else ""
            lines.append(f"{call} (a call) / physical limit at N={size}: "
                         f"{mine['us_per_value'] / limit['us_per_value']:.2f}x{beside}")
    for name, target in (("symlink-c-positions-loop", 1.3), ("hand-c-positions-loop", None),
                         ("numba-positions-loop", None)):
        size = largest(name, "physical-limit")
        mine, limit = _find(records, name, size), _find(records, "physical-limit", size)
        if limit and mine:
            ratio = mine["us_per_value"] / limit["us_per_value"]
            goal = "" if target is None else f" (target <= {target}x: {verdict(ratio <= target)})"
            lines.append(f"{name} / physical limit at N={size}: {ratio:.2f}x{goal} (loop against loop; the limit: "
                         f"{limit['us_per_value'] * 1e3:.3g} ns a value)")
    fsolve = _find(records, "fsolve")
    if fsolve:  # one call a value: its time per value does not depend on N; both solve positions only
        for size in sorted({min((r["n"] for r in records if r["method"] == "symlink-positions"), default=None),
                            positions} - {None}):
            symlink = _find(records, "symlink-positions", size)
            if symlink:
                ratio = fsolve["us_per_value"] / symlink["us_per_value"]
                lines.append(f"fsolve ({fsolve['n']} values) / symlink-positions at N={size}, per value: "
                             f"{ratio:.0f}x (target >= 100x: {verdict(ratio >= 100)})")
    return lines


def machine() -> dict:
    """This machine as the report names it: CPU model, vector width (bits), cores, load average, date (UTC).

    The vector width is read from the CPU's flags in ``/proc/cpuinfo``: ``avx512f`` 512 bits, ``avx2``
    256, else 128 (SSE2 on x86-64, NEON on ARM).
    """
    model, flags = platform.processor() or platform.machine(), set[str]()
    try:
        with open("/proc/cpuinfo") as info:
            for line in info:
                key, _, value = line.partition(":")
                key = key.strip()
                if key in ("model name", "Hardware", "cpu model") and model in (platform.processor(),
                                                                                platform.machine(), ""):
                    model = value.strip()
                elif key in ("flags", "Features") and not flags:
                    flags = set(value.split())
    except OSError:
        pass
    width = 512 if "avx512f" in flags else 256 if "avx2" in flags else 128
    return {"cpu": model, "vector_bits": width, "cores": os.cpu_count(),
            "load": [round(x, 2) for x in os.getloadavg()],
            "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")}


def markdown(records: list[dict], found: dict, command: str) -> str:
    """The report page: the machine, the command, a table (method, N, time a value, ratio, max error), the ratios.

    ``ratio`` is the time a value over symlink's NumPy module's of the same kind and N (as in :func:`table`).
    """
    lines = ["# Benchmark results", "",
             f"- CPU: {found['cpu']} ({found['cores']} logical cores), vector width {found['vector_bits']} bits "
             f"(from the flags in /proc/cpuinfo)",
             f"- date: {found['date']}; load average at the start {found['load'][0]}, {found['load'][1]}, "
             f"{found['load'][2]} (1, 5, 15 minutes)",
             f"- command: `{command}`", "",
             "Every method solves the same fixed-seed four-bars (both branches, near their toggles too) in one "
             "call; `*-loop` rows time a loop alone into outputs allocated once (loop against loop); errors are "
             "against 50-digit mpmath. Ratios are inside this run only (the machine is shared).", "",
             "| method | kind | N | time a value (ns) | ratio to symlink (NumPy) | max error (rad) |",
             "|---|---|---:|---:|---:|---:|"]
    order = {"full": 0, "positions": 1}
    for r in sorted(records, key=lambda r: (order.get(r["kind"], 2), r["size"], r["us_per_value"])):
        ratio = "-" if r.get("ratio_to_symlink") is None else f"{r['ratio_to_symlink']:.3g}"
        lines.append(f"| {r['method']} | {r['kind']} | {r['n']} | {r['us_per_value'] * 1e3:.3g} | {ratio} | "
                     f"{_short(r['max_error'])} |")
    lines += ["", "## Ratios", ""] + [f"- {line}" for line in targets(records)] + [""]
    return "\n".join(lines)


def write_report(records: list[dict], folder: str | os.PathLike, found: dict, command: str) -> tuple[Path, Path]:
    """``folder/benchmark/results.md`` and ``folder/images/bench.png`` from this run's records (atomically)."""
    page, picture = Path(folder) / "benchmark" / "results.md", Path(folder) / "images" / "bench.png"
    page.parent.mkdir(parents=True, exist_ok=True)
    picture.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(page, markdown(records, found, command))
    plot(records, picture, found)
    return page, picture


def plot(records: list[dict], path: str | os.PathLike, found: dict | None = None) -> None:
    """Two panels: time per value against N (each method a line), and time against error at the largest N."""
    import io

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    markers = "os^vD<>pXh*P"
    figure, (by_size, by_error) = plt.subplots(1, 2, figsize=(13, 6))
    names = [name for name in dict.fromkeys(r["method"] for r in records)]
    for index, name in enumerate(names):
        mine = sorted((r for r in records if r["method"] == name), key=lambda r: r["n"])
        style = dict(marker=markers[index % len(markers)], linestyle="-" if mine[0]["kind"] == "full" else "--",
                     color="black" if name == "physical-limit" else None)
        if len(mine) > 1:  # the per-value methods (one N) are on the right only
            by_size.plot([r["n"] for r in mine], [r["us_per_value"] for r in mine], label=name, alpha=0.85, **style)
        last = mine[-1]
        if last["max_error"] is not None:
            by_error.scatter([max(last["max_error"], ERROR_FLOOR)], [last["us_per_value"]], marker=style["marker"],
                             s=50, label=f"{name} (N={last['n']:.0e})".replace("e+0", "e"), alpha=0.85)
            by_error.annotate(name, (max(last["max_error"], ERROR_FLOOR), last["us_per_value"]), fontsize=6,
                              xytext=(4, 3), textcoords="offset points")
    for axes in (by_size, by_error):
        axes.set_xscale("log")
        axes.set_yscale("log")
        axes.grid(True, which="both", alpha=0.3)
        axes.set_ylabel("run time per input value (microseconds)")
    by_size.set_xlabel("N, input values in one call")
    by_size.set_title("Four-bar: time per value against N\n(solid: full kinematics, dashed: positions)")
    by_size.legend(fontsize=6, loc="upper right", ncol=2)
    by_error.set_xlabel("max angle error against 50-digit mpmath (rad)")
    by_error.set_title("Time against error, at each method's largest N")
    if found is not None:
        figure.suptitle(f"{found['cpu']}, {found['vector_bits']}-bit vectors, load {found['load'][0]}; "
                        f"{found['date']}", fontsize=9)
    figure.tight_layout()
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=100)
    plt.close(figure)
    write_atomic(path, buffer.getvalue())


def report_derivations(rows: list[dict]) -> list[str]:
    lines = ["symbolic side (scenes in this order in one new process: 'cold' with an empty cache, "
             "then 'cached' in another from the disk cache):"]
    for row in rows:
        lines.append(f"  {row['linkage']} ({row['outputs']} outputs): derive + generate + load cold "
                     f"{row['cold'] * 1e3:.1f} ms, from cache {row['cached'] * 1e3:.1f} ms (of which building "
                     f"the linkage {row['build_linkage'] * 1e3:.1f} ms), from memory {row['memory'] * 1e6:.0f} us; "
                     f"loading the generated module {row['load_module'] * 1e3:.2f} ms")
    return lines


# --- the command line ----------------------------------------------------------

class _UsageError(ValueError):
    """A bad command line: reported in one line, exit status 2."""


class _Parser(argparse.ArgumentParser):
    """argparse whose errors are one line (raised, then printed by :func:`main`), not a usage dump."""

    def error(self, message: str) -> None:
        raise _UsageError(message)


def _sizes(text: str) -> list[float]:
    """Comma-separated numbers (checked to be positive whole numbers later, with the other options)."""
    values = []
    for item in (part.strip() for part in text.split(",")):
        if not item:
            continue
        try:
            value = float(item)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a number: {item!r}") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"not a finite number: {item!r}")
        values.append(value)
    return values


def build_parser(prog: str = "python -m benchmarks") -> argparse.ArgumentParser:
    """The benchmark's options."""
    parser = _Parser(prog=prog, description="Run time against error of the four-bar position solvers. "
                     "Progress goes to stderr, the table and the targets to stdout.",
                     epilog=f"example: {prog} --quick --json bench.json --plot bench.png")
    parser.add_argument("--quick", action="store_true", help=f"N = {', '.join(map(str, QUICK_SIZES))} (under a minute)")
    parser.add_argument("--sizes", type=_sizes, metavar="LIST", help="comma-separated N (overrides --quick's)")
    parser.add_argument("--methods", metavar="LIST", help=f"comma-separated, from {', '.join(METHODS)} (default all)")
    parser.add_argument("--seed", type=int, default=2024, help="random four-bars (default 2024)")
    parser.add_argument("--json", metavar="FILE", help="write the records as JSON")
    parser.add_argument("--plot", metavar="FILE", help="write the run-time-against-error plot (PNG)")
    parser.add_argument("--report", metavar="FOLDER", nargs="?", const=str(DOCS),
                        help=f"write FOLDER/benchmark/results.md and FOLDER/images/bench.png (default folder {DOCS})")
    parser.add_argument("--no-derivation", action="store_true", help="skip the symbolic-side timings")
    parser.add_argument("--no-limit", action="store_true", help="skip measuring the physical limit")
    return parser


def run(args: argparse.Namespace, command: str = "python -m benchmarks") -> int:
    """Run the benchmark as the options say: progress on stderr; the table, targets and symbolic timings on stdout.

    ``command``: the command line, as the report names it.
    """
    if args.sizes is not None:
        if not args.sizes or any(n != int(n) or n < 1 for n in args.sizes):
            raise ValueError(f"--sizes must be positive whole numbers, got {args.sizes}")
        sizes = [int(n) for n in args.sizes]
    else:
        sizes = list(QUICK_SIZES if args.quick else FULL_SIZES)
    methods = METHODS if args.methods is None else [m.strip() for m in args.methods.split(",") if m.strip()]
    unknown = [m for m in methods if m not in METHODS]
    if unknown:
        raise ValueError(f"unknown method {unknown[0]!r}; choose from {', '.join(METHODS)}")
    for path in (args.json, args.plot):
        if path is not None and not Path(path).parent.is_dir():
            raise ValueError(f"cannot write {path}: no folder {Path(path).parent}")
    if args.report is not None and Path(args.report).exists() and not Path(args.report).is_dir():
        raise ValueError(f"cannot write the report into {args.report}: not a folder")
    found = machine()  # the load before this run adds its own
    reference = 400 if args.quick else 2000
    _say(True, f"{found['cpu']}, {found['vector_bits']}-bit vectors, load {found['load'][0]}")
    _say(True, f"symlink bench: N = {', '.join(map(str, sizes))}; errors on up to {reference} values a size "
               f"(50-digit mpmath), residuals on all")
    records = benchmark(sizes, methods, quick=args.quick, seed=args.seed, reference=reference,
                        limit=not args.no_limit)
    print(table(records))
    print()
    limit = _find(records, "physical-limit", max(sizes))
    if limit is not None:
        print(f"physical limit (this machine): {limit['us_per_value'] * 1e3:.3g} ns a value at N={limit['n']}: "
              f"{limit['note']}")
    for line in targets(records):
        print(line)
    if not args.no_derivation:
        print()
        for line in report_derivations(derivation_times(derivation_scenes(args.quick))):
            print(line)
    if args.json:
        write_atomic(args.json, json.dumps(records, indent=1) + "\n")
    if args.plot:
        plot(records, args.plot, found)
    if args.report is not None:
        for path in write_report(records, args.report, found, command):
            _say(True, f"wrote {path}")
    return 0


def main(argv: Sequence[str] | None = None, prog: str = "python -m benchmarks") -> int:
    """Run the benchmark from command-line arguments; returns the exit status.

    Bad options: one line on stderr, status 2; a file that cannot be written:
    one line, status 1; Ctrl-C: status 130, quietly.
    """
    try:
        arguments = sys.argv[1:] if argv is None else list(argv)
        return run(build_parser(prog).parse_args(arguments), " ".join([prog, *map(shlex.quote, arguments)]))
    except ValueError as error:
        print(f"symlink: error: {error}", file=sys.stderr)
        return 2
    except OSError as error:
        if isinstance(error, BrokenPipeError):
            return 0
        print(f"symlink: error: cannot write: {error}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    sys.exit(main(prog="python benchmarks/bench.py"))
