"""Hand-written numba loops of the four-bar: the fused loop a user writes instead of a code generator.

The same formulas as symlink's generated code, with the same shared subexpressions
(:data:`benchmarks.hand_c.HAND_C_SOURCE` has them in C): the triangle B, C, D solved with
atan2 and Heron's product under symlink's clamped square root, and for the rates the
cosine and sine of each solved angle taken from its atan2 arguments (``x / r`` and
``y / r``, with r known without a square root: ``2 b w^2`` and ``2 c w^2``), never from
extra ``sin``/``cos`` calls.  So a value
costs the same transcendental calls as in the generated code: ``cos`` and ``sin`` of the
crank, two ``atan2`` and one square root, for positions and full kinematics alike;
:func:`tests.test_bench` counts them in the source text of both.  The one difference is a
numeric device of the generated code, its loop unit (lengths scaled by a power of two,
so that no product overflows): a hand-written loop has none.

One value at a time in a loop compiled by numba (``@njit``, no fastmath, so every
operation rounds as NumPy's do).  numba is an optional extra
(``pip install 'symlink-kinematics[bench]'``): it is imported by the caller and handed in.
"""
from __future__ import annotations

import math

__all__ = ["numba_kernels", "solve_positions"]

_KERNELS: dict = {}


def solve_positions(cos_t, sin_t, a, b, c, d, branch, tolerance):
    """The atan2 arguments of beta and phi (y, x each), the branch-signed root and w^2: symlink's atan2 form."""
    wx, wy = a * cos_t - d, a * sin_t
    w_squared = wx * wx + wy * wy  # w only squared, as in the generated code: no square root for it
    s, t = b + c, b - c
    heron = (s * s - w_squared) * (w_squared - t * t)
    bound = abs(wx) + abs(wy)  # from w to sqrt(2) w: the clamp's stand-in for w
    if heron >= -tolerance * 8 * b * c * bound * (s + bound + d + a):
        root = math.sqrt(heron if heron > 0.0 else 0.0)
    else:
        root = math.nan
    along_b, along_c = s * t + w_squared, w_squared - s * t
    across = root * branch
    beta_y, beta_x = -wy * along_b - wx * across, -wx * along_b + wy * across
    phi_y, phi_x = wy * along_c - wx * across, wx * along_c + wy * across
    return beta_y, beta_x, phi_y, phi_x, across, w_squared


def numba_kernels(numba, tolerance: float):
    """``(positions, everything)``: the compiled loops, compiled on first use (and warmed up) once a process.

    ``positions(theta, a, b, c, d, branch, beta, phi)`` and ``everything(theta, a, b, c, d, branch, speed,
    accel, beta, phi, beta_speed, phi_speed, beta_accel, phi_accel)`` take contiguous arrays of doubles
    (the crank speed and acceleration are numbers) and write into the output arrays.
    """
    if tolerance in _KERNELS:
        return _KERNELS[tolerance]
    one_position = numba.njit(cache=False, fastmath=False, inline="always")(solve_positions)

    @numba.njit(cache=False, fastmath=False)
    def positions(theta, a, b, c, d, branch, beta, phi):
        for i in range(theta.size):
            beta_y, beta_x, phi_y, phi_x, _, _ = one_position(math.cos(theta[i]), math.sin(theta[i]), a[i], b[i], c[i],
                                                           d[i], branch[i], tolerance)
            beta[i], phi[i] = math.atan2(beta_y, beta_x), math.atan2(phi_y, phi_x)

    @numba.njit(cache=False, fastmath=False)
    def everything(theta, a, b, c, d, branch, speed, accel, beta, phi, beta_speed, phi_speed, beta_accel,
                   phi_accel):
        speed2 = speed * speed
        for i in range(theta.size):
            sin_t, cos_t = math.sin(theta[i]), math.cos(theta[i])
            a_, b_, c_ = a[i], b[i], c[i]
            beta_y, beta_x, phi_y, phi_x, across, w_squared = one_position(cos_t, sin_t, a_, b_, c_, d[i], branch[i],
                                                                           tolerance)
            # cos and sin of each angle from its atan2 arguments, as the generated code takes them; the arguments'
            # lengths 2 b w^2 and 2 c w^2 (Heron), without a square root
            beta_r, phi_r = 2.0 * b_ * w_squared, 2.0 * c_ * w_squared
            sin_b, cos_b = beta_y * (1.0 / beta_r), beta_x * (1.0 / beta_r)
            sin_p, cos_p = phi_y * (1.0 / phi_r), phi_x * (1.0 / phi_r)
            beta[i], phi[i] = math.atan2(beta_y, beta_x), math.atan2(phi_y, phi_x)
            scale = 2.0 * b_ * c_ / across  # 1 / sin(beta - phi)
            over_b, over_c = scale / b_, scale / c_
            s_pt = cos_t * sin_p - cos_p * sin_t  # sin(phi - theta)
            s_bt = cos_t * sin_b - cos_b * sin_t  # sin(beta - theta)
            c_bp = cos_b * cos_p + sin_b * sin_p  # cos(beta - phi)
            a_speed, a_accel = a_ * speed, a_ * accel
            bs = -s_pt * over_b * a_speed
            ps = -a_speed * s_bt * over_c
            bs2, c_ps2 = bs * bs, c_ * (ps * ps)
            beta_speed[i], phi_speed[i] = bs, ps
            beta_accel[i] = over_b * (a_ * speed2 * (cos_p * cos_t + sin_p * sin_t) + b_ * bs2 * c_bp
                                      - s_pt * a_accel - c_ps2)
            phi_accel[i] = over_c * (a_ * speed2 * (cos_b * cos_t + sin_b * sin_t) + b_ * bs2 - s_bt * a_accel
                                     - c_ps2 * c_bp)

    import numpy
    one = numpy.ones(2)
    outs = [numpy.empty(2) for _ in range(6)]
    positions(one, one, one, one, one, one, outs[0], outs[1])  # compile now, not in the first timed call
    everything(one, one, one, one, one, one, 1.0, 0.0, *outs)
    _KERNELS[tolerance] = (positions, everything)
    return _KERNELS[tolerance]
