"""Hand-written numba loops of the four-bar: the fused loop a user writes instead of a code generator.

The same formulas as :func:`benchmarks.bench.hand_numpy` (symlink's atan2 form, with its clamped
square root) and :func:`benchmarks.bench.hand_rates`, one value at a time in a loop compiled by
numba (``@njit``, no fastmath, so every operation rounds as NumPy's do).  numba is an optional
extra (``pip install 'symlink-kinematics[bench]'``): it is imported by the caller and handed in.
"""
from __future__ import annotations

import math

__all__ = ["numba_kernels"]

_KERNELS: dict = {}


def numba_kernels(numba, tolerance: float):
    """``(positions, everything)``: the compiled loops, compiled on first use (and warmed up) once a process.

    ``positions(theta, a, b, c, d, branch, beta, phi)`` and ``everything(theta, a, b, c, d, branch, speed,
    accel, beta, phi, beta_speed, phi_speed, beta_accel, phi_accel)`` take contiguous arrays of doubles
    (the crank speed and acceleration are numbers) and write into the output arrays.
    """
    if tolerance in _KERNELS:
        return _KERNELS[tolerance]

    @numba.njit(cache=False, fastmath=False)
    def solve(theta, a, b, c, d, branch):
        wx, wy = a * math.cos(theta) - d, a * math.sin(theta)
        w2 = wx * wx + wy * wy
        w = math.sqrt(w2)
        s, t = b + c, b - c
        heron = (s + w) * (s - w) * (t + w) * (w - t)
        if heron >= -tolerance * 8 * b * c * w * (a + s + w + d):
            root = math.sqrt(max(heron, 0.0))
        else:
            root = math.nan
        along_b, along_c, across = s * t + w2, w2 - s * t, branch * root
        return (math.atan2(-wy * along_b - wx * across, -wx * along_b + wy * across),
                math.atan2(wy * along_c - wx * across, wx * along_c + wy * across))

    @numba.njit(cache=False, fastmath=False)
    def positions(theta, a, b, c, d, branch, beta, phi):
        for i in range(theta.size):
            beta[i], phi[i] = solve(theta[i], a[i], b[i], c[i], d[i], branch[i])

    @numba.njit(cache=False, fastmath=False)
    def everything(theta, a, b, c, d, branch, speed, accel, beta, phi, beta_speed, phi_speed, beta_accel,
                   phi_accel):
        for i in range(theta.size):
            q, p = solve(theta[i], a[i], b[i], c[i], d[i], branch[i])
            s_tp, c_tp = math.sin(theta[i] - p), math.cos(theta[i] - p)
            s_tb, c_tb = math.sin(theta[i] - q), math.cos(theta[i] - q)
            s_bp, c_bp = math.sin(q - p), math.cos(q - p)
            bs = -a[i] * speed * s_tp / (b[i] * s_bp)
            ps = -a[i] * speed * s_tb / (c[i] * s_bp)
            beta[i], phi[i], beta_speed[i], phi_speed[i] = q, p, bs, ps
            beta_accel[i] = -(a[i] * accel * s_tp + a[i] * speed * speed * c_tp + b[i] * bs * bs * c_bp
                              - c[i] * ps * ps) / (b[i] * s_bp)
            phi_accel[i] = -(a[i] * accel * s_tb + a[i] * speed * speed * c_tb + b[i] * bs * bs
                             - c[i] * ps * ps * c_bp) / (c[i] * s_bp)

    import numpy
    one = numpy.ones(2)
    outs = [numpy.empty(2) for _ in range(6)]
    positions(one, one, one, one, one, one, outs[0], outs[1])  # compile now, not in the first timed call
    everything(one, one, one, one, one, one, 1.0, 0.0, *outs)
    _KERNELS[tolerance] = (positions, everything)
    return _KERNELS[tolerance]
