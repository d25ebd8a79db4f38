"""Hand-written C loops of the four-bar positions: the baselines that the generated C is measured against.

:data:`HAND_C_SOURCE` is what a careful programmer writes by hand for the
four-bar (``a e^{i theta} + b e^{i beta} = d + c e^{i phi}``),
with the link lengths and the branch given per value (arrays, as every method
of the benchmark gets them: many linkages in one call):

* ``hand_fourbar_positions`` (``hand-c`` in the benchmark): the triangle B, C,
  D solved with atan2 and Heron's product, derived on paper from the geometry,
  with the same clamped square root as symlink: rounding tolerated at a toggle
  in proportion to 8 b c w (a + b + c + w + d), NaN where it cannot close.
  Let W = B - D (length w).  C lies at the distance (b^2 - c^2 + w^2)/(2w)
  from B along D - B and sqrt(Heron)/(2w) to its left (branch +1), so
  ``b e^{i beta}`` is parallel to ``-(b^2 - c^2 + w^2) W + branch sqrt(H) n``
  and ``c e^{i phi}`` to ``(w^2 - b^2 + c^2) W + branch sqrt(H) n``, with
  ``n = (Wy, -Wx)`` (W turned clockwise) and
  ``H = (b+c+w)(b+c-w)(w+b-c)(w-b+c)``.
* ``vector_math_limit``: not a solver, the floor under every solver of the
  four-bar's positions: per value cos and sin of the crank, a square root,
  two atan2 and two stores (the benchmark prints its time as the physical limit).
* ``hand_fourbar_halfangle``: the half-angle (Freudenstein) solution of
  seed paper 003 (K, A, B, C; phi = 2 atan((-B - branch sqrt(B^2 - 4AC))/(2A)),
  its "-" root being branch +1), beta from the loop's x and y components.

Both are compiled with :func:`symlink.compiled.compile_shared`, so with the
same flags as the generated C, and marked ``SYMLINK_LOOP`` as its loops are
(vectorised where the compiler can).

>>> import numpy
>>> result = hand_positions(numpy.radians([0.0]), 20.0, 66.0, 56.0, 80.0, 1)  # doctest: +SKIP
>>> round(float(numpy.degrees(result["rocker"][0])), 2)  # doctest: +SKIP
110.74
"""
from __future__ import annotations

import ctypes
import functools

import numpy

from symlink.position import TOLERANCE

__all__ = ["HAND_C_SOURCE", "hand_library", "hand_positions"]

HAND_C_SOURCE = r"""
#include <math.h>
#include <stddef.h>
#ifndef SYMLINK_LOOP  /* set by symlink's compiled backend, as for the generated C */
#define SYMLINK_LOOP
#endif

SYMLINK_LOOP void hand_fourbar_positions(size_t n, const double *theta, const double *a_, const double *b_,
                            const double *c_, const double *d_, const double *branch_, double *beta, double *phi,
                            unsigned char *assembled)
{
    for (size_t i = 0; i < n; ++i) {
        const double a = a_[i], b = b_[i], c = c_[i], d = d_[i], branch = branch_[i];
        const double s = b + c, t = b - c, bc = s * t;      /* b^2 - c^2 */
        const double wx = a * cos(theta[i]) - d, wy = a * sin(theta[i]);   /* W = B - D */
        const double w2 = wx * wx + wy * wy, w = sqrt(w2);
        const double heron = (s + w) * (s - w) * (t + w) * (w - t);
        const double scale = 8 * b * c * w * (a + s + w + d);   /* a flat triangle's rounding */
        const double root = heron >= -TOLERANCE * scale ? sqrt(heron > 0.0 ? heron : 0.0) : NAN;
        const double along_b = bc + w2, along_c = w2 - bc, across = branch * root;
        beta[i] = atan2(-wy * along_b - wx * across, -wx * along_b + wy * across);
        phi[i] = atan2(wy * along_c - wx * across, wx * along_c + wy * across);
        assembled[i] = (unsigned char)isfinite(root);
    }
}

SYMLINK_LOOP void hand_fourbar_halfangle(size_t n, const double *theta, const double *a_, const double *b_,
                            const double *c_, const double *d_, const double *branch_, double *beta, double *phi,
                            unsigned char *assembled)
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
SYMLINK_LOOP void vector_math_limit(size_t n, const double *theta, double *beta, double *phi)
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
__all__ += ["vector_math_limit"]


@functools.lru_cache(maxsize=1)
def hand_library() -> ctypes.CDLL:
    """:data:`HAND_C_SOURCE` compiled with the flags of the generated C (``CompilerUnavailable`` without a compiler).

    Loaded once a process, as a caller of a C library would.
    """
    from symlink.compiled import compile_shared
    library = compile_shared(HAND_C_SOURCE)
    for name in _FUNCTIONS:
        function = getattr(library, name)
        function.restype = None
        function.argtypes = [ctypes.c_size_t] + [ctypes.c_void_p] * 9
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
    arrays = [numpy.asarray(v, dtype=numpy.float64) for v in (theta, a, b, c, d, branch)]
    shape = numpy.broadcast_shapes(*(x.shape for x in arrays))
    arrays = [x if x.shape == shape and x.flags.c_contiguous else numpy.ascontiguousarray(numpy.broadcast_to(x, shape))
              for x in arrays]
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
