"""Hand-written C loops of the four-bar positions: the baselines that the generated C is measured against.

:data:`HAND_C_SOURCE` is what a careful programmer writes by hand for the
four-bar (``a e^{i theta} + b e^{i beta} = d + c e^{i phi}``),
with the link lengths and the branch given per value (arrays, as every method
of the benchmark gets them: many linkages in one call):

* ``hand_fourbar_positions`` (``hand-c-positions`` in the benchmark): the triangle B, C,
  D solved with atan2 and Heron's product, derived on paper from the geometry,
  with the same clamped square root as symlink: rounding tolerated at a toggle
  in proportion to 8 b c v (a + b + c + v + d) with v = |Wx| + |Wy| (at least w,
  at most sqrt(2) w), NaN where it cannot close.
  Let W = B - D (length w).  C lies at the distance (b^2 - c^2 + w^2)/(2w)
  from B along D - B and sqrt(Heron)/(2w) to its left (branch +1), so
  ``b e^{i beta}`` is parallel to ``-(b^2 - c^2 + w^2) W + branch sqrt(H) n``
  and ``c e^{i phi}`` to ``(w^2 - b^2 + c^2) W + branch sqrt(H) n``, with
  ``n = (Wy, -Wx)`` (W turned clockwise) and
  ``H = (b+c+w)(b+c-w)(w+b-c)(w-b+c) = ((b+c)^2 - w^2)(w^2 - (b-c)^2)``: every
  term needs w only squared, so, as in the generated code, w itself is never
  computed and a value takes one square root (of H).
* ``hand_fourbar_everything`` (``hand-c`` in the benchmark): the same, with
  speeds and accelerations by the formulas and shared terms of the generated
  code: cos and sin of beta and phi from their atan2 arguments (``x / r``,
  ``y / r``), whose lengths r are known without a square root (``2 b w^2`` and
  ``2 c w^2``, by Heron's formula), so a value calls cos, sin, two atan2 and one
  square root, as the generated code does (a test counts them in both sources).
* ``vector_math_limit``: not a solver, the floor under every solver of the
  four-bar's positions: per value cos and sin of the crank, a square root,
  two atan2 and two stores (the benchmark prints its time as the physical limit).
* ``hand_fourbar_halfangle``: the half-angle (Freudenstein) solution of
  seed paper 003 (K, A, B, C; phi = 2 atan((-B - branch sqrt(B^2 - 4AC))/(2A)),
  its "-" root being branch +1), beta from the loop's x and y components.

All are compiled with :func:`symlink.numeric.compiled.compile_shared`, so with the
same flags as the generated C, marked ``SYMLINK_LOOP`` as its loops are, and
their arrays declared ``restrict`` (without it GCC cannot rule out that an
output overlaps an input, and does not vectorise the loop).

>>> import numpy
>>> result = hand_positions(numpy.radians([0.0]), 20.0, 66.0, 56.0, 80.0, 1)  # doctest: +SKIP
>>> round(float(numpy.degrees(result["rocker"][0])), 2)  # doctest: +SKIP
110.74
"""
from __future__ import annotations

import ctypes
import functools

import numpy

from symlink.symbolic.position import TOLERANCE

__all__ = ["HAND_C_SOURCE", "hand_library", "hand_positions"]

HAND_C_SOURCE = r"""
#include <math.h>
#include <stddef.h>
#ifndef SYMLINK_LOOP  /* set by symlink's compiled backend, as for the generated C */
#define SYMLINK_LOOP
#endif

/* The atan2 arguments of beta and phi and the branch-signed root, from cos and sin of the crank: symlink's
   atan2 form with its shared terms (W = B - D, Heron's product under the clamped square root). */
static inline __attribute__((always_inline)) void hand_triangle(double cos_t, double sin_t, double a, double b,
    double c, double d, double branch, double *beta_y, double *beta_x, double *phi_y, double *phi_x, double *across,
    double *w_squared_out)
{
    const double wx = a * cos_t - d, wy = a * sin_t;   /* W = B - D */
    const double w_squared = wx * wx + wy * wy;   /* w only squared: no square root for it */
    const double s = b + c, t = b - c;
    const double heron = (s * s - w_squared) * (w_squared - t * t);
    const double bound = fabs(wx) + fabs(wy);   /* from w to sqrt(2) w */
    const double scale = 8 * b * c * bound * (s + bound + d + a);   /* a flat triangle's rounding */
    const double root = heron >= -TOLERANCE * scale ? sqrt(heron > 0.0 ? heron : 0.0) : NAN;
    const double along_b = s * t + w_squared, along_c = w_squared - s * t;
    *across = root * branch;
    *beta_y = -wy * along_b - wx * *across;
    *beta_x = -wx * along_b + wy * *across;
    *phi_y = wy * along_c - wx * *across;
    *phi_x = wx * along_c + wy * *across;
    *w_squared_out = w_squared;
}

SYMLINK_LOOP void hand_fourbar_positions(size_t n, const double *restrict theta, const double *restrict a,
    const double *restrict b, const double *restrict c, const double *restrict d, const double *restrict branch,
    double *restrict beta, double *restrict phi, unsigned char *restrict assembled)
{
    for (size_t i = 0; i < n; ++i) {
        double beta_y, beta_x, phi_y, phi_x, across, w_squared;
        hand_triangle(cos(theta[i]), sin(theta[i]), a[i], b[i], c[i], d[i], branch[i], &beta_y, &beta_x, &phi_y,
                      &phi_x, &across, &w_squared);
        beta[i] = atan2(beta_y, beta_x);
        phi[i] = atan2(phi_y, phi_x);
        assembled[i] = across == across;
    }
}

/* Positions, speeds and accelerations: cos and sin of beta and phi from their atan2 arguments (x / r, y / r),
   as the generated code takes them, not from further calls of cos and sin; r = 2 b w^2 and 2 c w^2 (Heron). */
SYMLINK_LOOP void hand_fourbar_everything(size_t n, const double *restrict theta, const double *restrict a,
    const double *restrict b, const double *restrict c, const double *restrict d, const double *restrict branch,
    double speed, double accel, double *restrict beta, double *restrict phi, double *restrict beta_speed,
    double *restrict phi_speed, double *restrict beta_accel, double *restrict phi_accel,
    unsigned char *restrict assembled, unsigned char *restrict singular)
{
    const double speed2 = speed * speed;
    for (size_t i = 0; i < n; ++i) {
        const double sin_t = sin(theta[i]), cos_t = cos(theta[i]), a_ = a[i], b_ = b[i], c_ = c[i];
        double beta_y, beta_x, phi_y, phi_x, across, w_squared;
        hand_triangle(cos_t, sin_t, a_, b_, c_, d[i], branch[i], &beta_y, &beta_x, &phi_y, &phi_x, &across,
                      &w_squared);
        const double beta_r = 2.0 * b_ * w_squared, phi_r = 2.0 * c_ * w_squared;   /* |(x, y)| without sqrt */
        const double sin_b = beta_y * (1.0 / beta_r), cos_b = beta_x * (1.0 / beta_r);
        const double sin_p = phi_y * (1.0 / phi_r), cos_p = phi_x * (1.0 / phi_r);
        beta[i] = atan2(beta_y, beta_x);
        phi[i] = atan2(phi_y, phi_x);
        const double scale = 2.0 * b_ * c_ / across;   /* 1 / sin(beta - phi) */
        const double over_b = scale / b_, over_c = scale / c_;
        const double s_pt = cos_t * sin_p - cos_p * sin_t;   /* sin(phi - theta) */
        const double s_bt = cos_t * sin_b - cos_b * sin_t;   /* sin(beta - theta) */
        const double c_bp = cos_b * cos_p + sin_b * sin_p;   /* cos(beta - phi) */
        const double a_speed = a_ * speed, a_accel = a_ * accel;
        const double bs = -s_pt * over_b * a_speed, ps = -a_speed * s_bt * over_c;
        const double bs2 = bs * bs, c_ps2 = c_ * (ps * ps);
        beta_speed[i] = bs;
        phi_speed[i] = ps;
        beta_accel[i] = over_b * (a_ * speed2 * (cos_p * cos_t + sin_p * sin_t) + b_ * bs2 * c_bp - s_pt * a_accel
                                  - c_ps2);
        phi_accel[i] = over_c * (a_ * speed2 * (cos_b * cos_t + sin_b * sin_t) + b_ * bs2 - s_bt * a_accel
                                 - c_ps2 * c_bp);
        assembled[i] = across == across;
        singular[i] = across == 0.0;   /* the rates' flag, as the generated code gives it with them */
    }
}

SYMLINK_LOOP void hand_fourbar_halfangle(size_t n, const double *restrict theta, const double *restrict a_,
    const double *restrict b_, const double *restrict c_, const double *restrict d_, const double *restrict branch_,
    double *restrict beta, double *restrict phi, unsigned char *restrict assembled)
{
    for (size_t i = 0; i < n; ++i) {
        const double a = a_[i], b = b_[i], c = c_[i], d = d_[i], branch = branch_[i];
        const double K = (a * a - b * b + c * c + d * d) / 2;
        const double ct = cos(theta[i]), st = sin(theta[i]);
        const double A = K - a * (d - c) * ct - c * d, B = -2 * a * c * st, C = K - a * (d + c) * ct + c * d;
        const double discriminant = B * B - 4 * A * C;
        const double p = 2 * atan((-B - branch * sqrt(discriminant)) / (2 * A));
        phi[i] = p;
        beta[i] = atan2(c * sin(p) - a * st, d + c * cos(p) - a * ct);
        assembled[i] = discriminant >= 0;
    }
}

/* The physical limit of four-bar positions: only what every solver of them must do for one value, the
   transcendental calls (cos and sin of the crank, a square root, two atan2) and the two stores, with no
   other arithmetic than what keeps the calls from being folded away. */
SYMLINK_LOOP void vector_math_limit(size_t n, const double *restrict theta, double *restrict beta,
                                    double *restrict phi)
{
    for (size_t i = 0; i < n; ++i) {
        const double ct = cos(theta[i]), st = sin(theta[i]);
        const double w = sqrt(2.0 + ct);
        beta[i] = atan2(st, ct + w);
        phi[i] = atan2(ct, st - w);
    }
}
""".replace("TOLERANCE", repr(TOLERANCE))

_FUNCTIONS = ("hand_fourbar_positions", "hand_fourbar_halfangle")
__all__ += ["vector_math_limit", "hand_everything"]


@functools.lru_cache(maxsize=1)
def hand_library() -> ctypes.CDLL:
    """:data:`HAND_C_SOURCE` compiled with the flags of the generated C (``CompilerUnavailable`` without a compiler).

    Loaded once a process, as a caller of a C library would.
    """
    from symlink.numeric.compiled import compile_shared
    library = compile_shared(HAND_C_SOURCE)
    for name in _FUNCTIONS:
        function = getattr(library, name)
        function.restype = None
        function.argtypes = [ctypes.c_size_t] + [ctypes.c_void_p] * 9
    library.hand_fourbar_everything.restype = None
    library.hand_fourbar_everything.argtypes = ([ctypes.c_size_t] + [ctypes.c_void_p] * 6 + [ctypes.c_double] * 2
                                                + [ctypes.c_void_p] * 8)
    library.vector_math_limit.restype = None
    library.vector_math_limit.argtypes = [ctypes.c_size_t] + [ctypes.c_void_p] * 3
    return library


def hand_positions(theta, a: float, b: float, c: float, d: float, branch: int = 1,
                   formula: str = "atan2") -> dict[str, numpy.ndarray]:
    """Coupler and rocker angles by the hand-written C: ``formula`` ``"atan2"`` (hand-c) or ``"halfangle"`` (seed 003).

    ``theta``, the lengths and the branch broadcast against each other (numbers or arrays, one value
    each per crank angle); arrays of the full shape, contiguous and of doubles, are used as they are.
    """
    names = {"atan2": "hand_fourbar_positions", "halfangle": "hand_fourbar_halfangle"}
    if formula not in names:
        raise ValueError(f"formula must be 'atan2' or 'halfangle', got {formula!r}")
    arrays = _full_arrays(theta, a, b, c, d, branch)
    shape = arrays[0].shape
    coupler, rocker = numpy.empty(shape), numpy.empty(shape)
    assembled = numpy.empty(shape, dtype=bool)
    getattr(hand_library(), names[formula])(coupler.size, *(x.ctypes.data for x in arrays),
                                            coupler.ctypes.data, rocker.ctypes.data, assembled.ctypes.data)
    return {"coupler": coupler, "rocker": rocker, "assembled": assembled}


def vector_math_limit(theta: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
    """The physical-limit kernel on ``theta`` (contiguous doubles): cos, sin, sqrt, two atan2 and two stores a value."""
    theta = numpy.ascontiguousarray(theta, dtype=numpy.float64)
    first, second = numpy.empty_like(theta), numpy.empty_like(theta)
    hand_library().vector_math_limit(theta.size, theta.ctypes.data, first.ctypes.data, second.ctypes.data)
    return first, second


def hand_everything(theta, a, b, c, d, branch, speed: float, accel: float) -> dict[str, numpy.ndarray]:
    """Positions, speeds and accelerations by the hand-written C (``hand_fourbar_everything``).

    ``theta``, the lengths and the branch broadcast against each other; the crank's speed and
    acceleration are numbers.  Keys: coupler, rocker, coupler_speed, rocker_speed, coupler_accel,
    rocker_accel, assembled, singular (the flag a compiled solver gives with rates: the root is zero).
    """
    arrays = _full_arrays(theta, a, b, c, d, branch)
    shape = arrays[0].shape
    outputs = [numpy.empty(shape) for _ in range(6)] + [numpy.empty(shape, dtype=bool) for _ in range(2)]
    hand_library().hand_fourbar_everything(arrays[0].size, *(x.ctypes.data for x in arrays), float(speed),
                                           float(accel), *(o.ctypes.data for o in outputs))
    names = ("coupler", "rocker", "coupler_speed", "rocker_speed", "coupler_accel", "rocker_accel", "assembled",
             "singular")
    return dict(zip(names, outputs))


def _full_arrays(*values) -> list[numpy.ndarray]:
    """The values as contiguous arrays of doubles of their broadcast shape (no copy where one already is)."""
    arrays = [numpy.asarray(v, dtype=numpy.float64) for v in values]
    shape = numpy.broadcast_shapes(*(x.shape for x in arrays))
    return [x if x.shape == shape and x.flags.c_contiguous else numpy.ascontiguousarray(numpy.broadcast_to(x, shape))
            for x in arrays]
