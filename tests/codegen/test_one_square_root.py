"""The two-angle case with one square root a value: as accurate at the toggles as the factored form it replaced.

Generated code no longer takes ``w = sqrt(Wx^2 + Wy^2)``: Heron's product is
``((b + c)^2 - w^2) (w^2 - (b - c)^2)`` and the atan2 arguments use ``w^2``
alone (:func:`symlink.symbolic.position._two_angles`, loop units).  Near a toggle
(``b + c = w`` or ``|b - c| = w``) one factor of Heron's product vanishes, so
that is where the two forms could differ.  Here both are measured against a
50-digit mpmath solution written in this file (the circle intersection of the
triangle, not symlink's formulas), at inputs within 1e-9 relative of every
toggle, on both sides, for both branches, for the four-bar and for the second
loop of the Watt II six-bar (whose W carries the rounding of the first loop's
angle):

* the factored form, as symlink computed it before (``w`` from a square root,
  ``(b+c+w)(b+c-w)(w+b-c)(w-b+c)`` clamped in proportion to
  ``8 b c w (b + c + w + sum of the known lengths)``), is written out below in NumPy,
  and in C compiled as symlink compiles its solvers (the compiled backend is
  compared with that: the vector sin and cos round W differently from NumPy's);
* the one-square-root form is symlink's generated NumPy module and compiled C;
* the second loop's reference and factored form start from the rocker angle the
  solver returned, so that the second loop's own rounding is compared (the first
  loop's, an ulp or so of that angle, moves the exact answer near a toggle more);
* on the closing side, each group's (linkage, backend, toggle, branches) errors,
  scaled by the conditioning (an angle error near a toggle grows like
  ``eps / sqrt(defect)``, so ``error * sqrt(defect) / eps`` is the same at every
  offset), are no worse than the factored form's: their root mean square at
  most 1.5 times, their largest at most 3 times (one group holds one rounding
  draw a point, so single points may differ by that much either way; measured
  against symlink's own generated modules before the change, over 300 draws a
  group and crank angles varied, the one-root form's root mean square was 0.65-1.05
  times the factored one's in NumPy (four-bar, Watt II) and 0.88-0.92 times in C (Watt II));
* wherever the input is farther from the toggle than twice the factored form's
  clamping band (so that rounding cannot decide it), the assembled flag is the
  exact one, as the factored form's is.
"""
from __future__ import annotations

import ctypes
import functools
import math

import mpmath as mp
import numpy
import pytest

from mp_closures import circle_point
from symlink.mechanism import catalog
from symlink.symbolic.position import TOLERANCE
from symlink.numeric.solver import Solver

DIGITS = 50
EPS = float(numpy.finfo(float).eps)
#: Relative distances from a toggle, taken on both sides: 1e-9 down to 1e-13.
OFFSETS = tuple(float(x) for x in numpy.geomspace(1e-9, 1e-13, 13))
#: How much larger the one-root form's scaled errors in a group may be than the factored form's: root mean
#: square, largest; and a floor (in the scaled errors' units of eps / sqrt(defect)).
RMS_FACTOR, MAX_FACTOR, FLOOR = 1.5, 3.0, 0.5


# --- the reference: a triangle closed at 50 digits, by circle intersection ---------------------------------------

def mp_triangle(start, end, first: float, second: float, branch: int):
    """The joint J with |J - start| = first and |J - end| = second, left of start -> end for branch +1.

    ``start`` and ``end`` are complex mpmath numbers; returns J, or None where the circles do not meet.
    """
    try:
        return circle_point(start, first, end, second, branch)
    except ValueError:  # the circles do not meet
        return None


def mp_angle(z) -> mp.mpf:
    return mp.atan2(z.imag, z.real)


def angle_error(value: float, exact) -> float:
    """|value - exact| modulo 2 pi (NaN stays NaN)."""
    if math.isnan(value):
        return math.nan
    with mp.workdps(DIGITS):
        difference = mp.mpf(value) - exact
        return float(abs(difference - 2 * mp.pi * mp.nint(difference / (2 * mp.pi))))


# --- the factored form symlink computed before, in NumPy ----------------------------------------------------------

def factored_triangle(wx, wy, first, second, branch, known_sum):
    """The angles of P and Q with P + Q = W, |P| = first, |Q| = second: the factored Heron form with w = sqrt(w^2).

    As the generated code had it before one square root a value: clamped in proportion to
    ``8 first second w (first + second + w + known_sum)``, NaN beyond.
    """
    w = numpy.sqrt(wx * wx + wy * wy)
    s, t = first + second, first - second
    heron = (s + w) * (s - w) * (w - t) * (w + t)
    scale = 8 * first * second * w * (s + w + known_sum)
    with numpy.errstate(invalid="ignore"):
        root = numpy.where(heron >= -TOLERANCE * scale, numpy.sqrt(numpy.maximum(heron, 0.0)), numpy.nan) * branch
    along_p, along_q = s * t + w * w, w * w - s * t
    angle_p = numpy.arctan2(along_p * wy + root * wx, along_p * wx - root * wy)
    angle_q = numpy.arctan2(along_q * wy - root * wx, along_q * wx + root * wy)
    return angle_p, angle_q


def factored_fourbar(theta, a, b, c, d, branch):
    """(beta, phi) of a e^{i theta} + b e^{i beta} = d + c e^{i phi}: W = D - B = b e^{i beta} - c e^{i phi}."""
    beta, minus_phi = factored_triangle(d - a * numpy.cos(theta), -a * numpy.sin(theta), b, c, branch, a + d)
    return beta, minus_phi + numpy.pi


#: The same factored form in C, compiled as symlink compiles its solvers (its flags, its vector math library): the
#: compiled backend is compared with it, for the vector sin and cos round differently from NumPy's (a few ulps
#: of W, which near a toggle decide the error).
FACTORED_C = r"""
#include <math.h>
#include <stddef.h>
#ifndef SYMLINK_LOOP
#define SYMLINK_LOOP
#endif
static inline __attribute__((always_inline)) void factored(double wx, double wy, double first, double second,
    double branch, double known_sum, double *angle_p, double *angle_q)
{
    const double w = sqrt(wx * wx + wy * wy);
    const double s = first + second, t = first - second;
    const double heron = (s + w) * (s - w) * (w - t) * (w + t);
    const double scale = 8 * first * second * w * (s + w + known_sum);
    const double root = (heron >= -TOLERANCE * scale ? sqrt(heron > 0.0 ? heron : 0.0) : NAN) * branch;
    const double along_p = s * t + w * w, along_q = w * w - s * t;
    *angle_p = atan2(along_p * wy + root * wx, along_p * wx - root * wy);
    *angle_q = atan2(along_q * wy - root * wx, along_q * wx + root * wy) + 3.141592653589793;
}

SYMLINK_LOOP void factored_fourbar(size_t n, const double *restrict theta, double a, double b, double c, double d,
    double branch, double *restrict beta, double *restrict phi)
{
    for (size_t i = 0; i < n; ++i) {
        factored(d - a * cos(theta[i]), -a * sin(theta[i]), b, c, branch, a + d, &beta[i], &phi[i]);
    }
}

SYMLINK_LOOP void factored_second_loop(size_t n, const double *restrict phi, const double *restrict g, double d,
    double e, double f, double alpha, double gx, double gy, double branch, double *restrict mu,
    double *restrict psi)
{
    for (size_t i = 0; i < n; ++i) {
        const double ex = d + e * cos(phi[i] + alpha), ey = e * sin(phi[i] + alpha);
        factored(gx - ex, gy - ey, f, g[i], branch, d + e + fabs(gx) + fabs(gy), &mu[i], &psi[i]);
    }
}
""".replace("TOLERANCE", repr(TOLERANCE))


@functools.lru_cache(maxsize=1)
def factored_library() -> ctypes.CDLL:
    from symlink.numeric.compiled import compile_shared
    library = compile_shared(FACTORED_C)
    library.factored_fourbar.argtypes = [ctypes.c_size_t, ctypes.c_void_p] + [ctypes.c_double] * 5 + [ctypes.c_void_p] * 2
    library.factored_second_loop.argtypes = ([ctypes.c_size_t] + [ctypes.c_void_p] * 2 + [ctypes.c_double] * 7
                                             + [ctypes.c_void_p] * 2)
    return library


def factored_in_c(function: str, arrays, numbers) -> tuple[numpy.ndarray, numpy.ndarray]:
    """The two angles of ``factored_fourbar`` or ``factored_second_loop`` over contiguous ``arrays``."""
    arrays = [numpy.ascontiguousarray(x, dtype=float) for x in arrays]
    first, second = numpy.empty(arrays[0].size), numpy.empty(arrays[0].size)
    getattr(factored_library(), function)(arrays[0].size, *(x.ctypes.data for x in arrays), *map(float, numbers),
                                          first.ctypes.data, second.ctypes.data)
    return first, second


# --- the points near the toggles -----------------------------------------------------------------------------------

FOURBARS = {
    # a four-bar whose diagonal |BD| (10 to 110) passes both toggles: |b - c| = 20 and b + c = 70
    "general": dict(a=50.0, b=45.0, c=25.0, d=60.0),
    # the folded toggle at a short diagonal (w = 0.01, a hundredth of a percent of the other links): the case
    # where the clamp's stand-in for w must stay near w
    "short diagonal": dict(a=50.0, b=40.0, c=39.99, d=50.005),
}


def fourbar_points(name: str):
    """(toggle, offset, theta) with the diagonal |BD| at the toggle times 1 + offset, both signs."""
    lengths = FOURBARS[name]
    a, b, c, d = (mp.mpf(lengths[k]) for k in "abcd")
    points = []
    with mp.workdps(DIGITS):
        for toggle, diagonal in (("extended", b + c), ("folded", abs(b - c))):
            for offset in OFFSETS:
                for sign in (1, -1):
                    w = diagonal * (1 + sign * offset)
                    cosine = (a**2 + d**2 - w**2) / (2 * a * d)
                    if abs(cosine) <= 1:
                        points.append((toggle, sign * offset, float(mp.acos(cosine))))
    return points


def fourbar_exact(lengths: dict, theta: float, branch: int):
    """(beta, phi, defect relative to the toggle's diagonal), or (None, None, defect) where it cannot close."""
    with mp.workdps(DIGITS):
        a, b, c, d = (mp.mpf(lengths[k]) for k in "abcd")
        crank, ground = a * mp.expjpi(mp.mpf(theta) / mp.pi), mp.mpc(d, 0)
        joint = mp_triangle(crank, ground, b, c, branch)
        w = abs(ground - crank)
        defect = min((b + c - w) / (b + c), (w - abs(b - c)) / abs(b - c))
        if joint is None:
            return None, None, defect
        return mp_angle(joint - crank), mp_angle(joint - ground), defect


def clamping_band(first: float, second: float, diagonal: float, known_sum: float) -> float:
    """The factored form's clamp, as a relative distance of the diagonal from the toggle.

    Heron's product moves by 8 first second w_t per unit of w at a toggle w_t, and the clamp took
    ``TOLERANCE 8 first second w (first + second + w + known_sum)`` as rounding.
    """
    return TOLERANCE * (first + second + diagonal + known_sum) / diagonal


def solvers(linkage, outputs):
    """The generated NumPy module, and the compiled C where a compiler works."""
    found = {"numpy": Solver(linkage, outputs, backend="numpy")}
    compiled = Solver(linkage, outputs, backend="auto")
    if compiled.wait_for_backend(600) == "compiled":
        found["c"] = compiled
    return found


def scaled_error(value: float, exact, defect) -> float:
    """The angle error in units of the conditioning near a toggle, eps / sqrt(defect)."""
    return angle_error(value, exact) * math.sqrt(abs(float(defect))) / EPS


def check(groups: dict, flags: list) -> None:
    """Each group's scaled one-root errors no worse than the factored form's; clear flags exact."""
    for key, (new, old) in groups.items():
        assert not any(math.isnan(x) for x in new + old), key
        new_rms, old_rms = (math.sqrt(sum(x * x for x in errors) / len(errors)) for errors in (new, old))
        assert new_rms <= RMS_FACTOR * old_rms + FLOOR, (key, new_rms, old_rms)
        assert max(new) <= MAX_FACTOR * max(old) + FLOOR, (key, max(new), max(old))
    for key, exact, factored, one_root in flags:
        assert factored == exact and one_root == exact, key


@pytest.mark.parametrize("name", sorted(FOURBARS))
def test_fourbar_toggles_as_accurate_with_one_square_root(name):
    lengths = FOURBARS[name]
    points = fourbar_points(name)
    assert len(points) == 2 * 2 * len(OFFSETS), points  # both toggles, both sides, every offset
    theta = numpy.array([p[2] for p in points])
    groups: dict = {}
    flags: list = []
    for backend, solver in solvers(catalog.fourbar(), ["coupler", "rocker"]).items():
        for branch in (1, -1):
            result = solver(theta=theta, branch=float(branch), **lengths)
            old_beta, old_phi = factored_fourbar(theta, *(lengths[k] for k in "abcd"), branch) \
                if backend == "numpy" else factored_in_c("factored_fourbar", [theta], [*(lengths[k] for k in "abcd"),
                                                                                       branch])
            for i, (toggle, offset, angle) in enumerate(points):
                beta, phi, defect = fourbar_exact(lengths, angle, branch)
                diagonal = lengths["b"] + lengths["c"] if toggle == "extended" else abs(lengths["b"] - lengths["c"])
                band = clamping_band(lengths["b"], lengths["c"], diagonal, lengths["a"] + lengths["d"])
                if abs(defect) > 2 * band:
                    flags.append(((name, backend, branch, toggle, offset), beta is not None,
                                  bool(numpy.isfinite(old_phi[i])), bool(result["assembled"][i])))
                if beta is None or not (numpy.isfinite(old_phi[i]) and result["assembled"][i]):
                    continue
                key = (name, backend, branch, toggle)
                new, old = groups.setdefault(key, ([], []))
                new += [scaled_error(result["coupler"][i], beta, defect), scaled_error(result["rocker"][i], phi, defect)]
                old += [scaled_error(old_beta[i], beta, defect), scaled_error(old_phi[i], phi, defect)]
    assert len(groups) >= 2 * 2 * 1, groups.keys()  # both branches and toggles, each backend
    assert sum(not f[1] for f in flags) >= 4 and sum(f[1] for f in flags) >= 4  # clearly outside and inside
    check(groups, flags)


# --- Watt II: the second loop's toggles, approached through the output rocker's length g --------------------------

WATT2 = dict(a=20.0, b=66.0, c=56.0, d=80.0, e=50.0, f=60.0, alpha=0.3, gx=120.0, gy=10.0)
#: Crank angles, each a different rounding of the second loop's W (fixed by the first loop, whatever g is).
WATT2_THETAS = tuple(float(x) for x in numpy.linspace(0.6, 0.8, 7))
WATT2_OUTPUTS = ["coupler", "rocker", "coupler2", "output"]


def watt2_first_loop(theta: float, branch_1: int):
    """(beta, phi) at 50 digits: loop ABCD, the four-bar."""
    with mp.workdps(DIGITS):
        crank = WATT2["a"] * mp.expjpi(mp.mpf(theta) / mp.pi)
        ground = mp.mpc(WATT2["d"], 0)
        joint = mp_triangle(crank, ground, mp.mpf(WATT2["b"]), mp.mpf(WATT2["c"]), branch_1)
        return mp_angle(joint - crank), mp_angle(joint - ground)


def watt2_second_loop(phi, g: float, branch_2: int):
    """(mu, psi, |GE|) at 50 digits for the rocker at ``phi``; mu and psi None where loop DEFG cannot close.

    Given the rocker angle, so that the second loop's own rounding is measured: the first loop's
    (an ulp or so of phi, the same for both forms) moves the exact answer near a toggle far more.
    """
    with mp.workdps(DIGITS):
        e_point = WATT2["d"] + WATT2["e"] * mp.expjpi((mp.mpf(phi) + mp.mpf(WATT2["alpha"])) / mp.pi)
        g_point = mp.mpc(WATT2["gx"], WATT2["gy"])
        joint = mp_triangle(e_point, g_point, mp.mpf(WATT2["f"]), mp.mpf(g), branch_2)
        distance = abs(g_point - e_point)
        if joint is None:
            return None, None, distance
        return mp_angle(joint - e_point), mp_angle(joint - g_point), distance


def factored_second_loop(phi, g, branch_2):
    """(mu, psi) of loop DEFG by the factored form, from the rocker angle phi: W = G - E = f e^{i mu} - g e^{i psi}."""
    ex, ey = WATT2["d"] + WATT2["e"] * numpy.cos(phi + WATT2["alpha"]), WATT2["e"] * numpy.sin(phi + WATT2["alpha"])
    known = WATT2["d"] + WATT2["e"] + abs(WATT2["gx"]) + abs(WATT2["gy"])
    mu, minus_psi = factored_triangle(WATT2["gx"] - ex, WATT2["gy"] - ey, WATT2["f"], g, branch_2, known)
    return mu, minus_psi + numpy.pi


def test_a_later_loops_toggles_as_accurate_with_one_square_root():
    points = []  # (branch_1, toggle, offset, theta, g)
    for branch_1 in (1, -1):
        for theta in WATT2_THETAS:
            _, phi = watt2_first_loop(theta, branch_1)
            distance = watt2_second_loop(phi, 1.0, 1)[2]  # |GE|, fixed by the first loop
            with mp.workdps(DIGITS):
                for toggle in ("extended", "folded"):
                    for offset in OFFSETS:
                        for sign in (1, -1):
                            # extended: f + g = |GE| (1 + offset); folded: g - f = |GE| (1 - offset) (g > f here)
                            g = distance * (1 + sign * offset) - WATT2["f"] if toggle == "extended" \
                                else WATT2["f"] + distance * (1 - sign * offset)
                            points.append((branch_1, toggle, sign * offset, theta, float(g)))
    groups: dict = {}
    flags: list = []
    known = WATT2["d"] + WATT2["e"] + abs(WATT2["gx"]) + abs(WATT2["gy"])
    for backend, solver in solvers(catalog.watt2(), WATT2_OUTPUTS).items():
        for branch_1 in (1, -1):
            chosen = [p for p in points if p[0] == branch_1]
            theta, g = numpy.array([p[3] for p in chosen]), numpy.array([p[4] for p in chosen])
            first = {t: watt2_first_loop(t, branch_1) for t in WATT2_THETAS}
            for branch_2 in (1, -1):
                result = solver(theta=theta, g=g, branch_ABCD=float(branch_1), branch_DEFG=float(branch_2), **WATT2)
                # the old form from the same rocker angle, in the same language
                old = factored_second_loop(result["rocker"], g, branch_2) if backend == "numpy" else factored_in_c(
                    "factored_second_loop", [result["rocker"], g],
                    [WATT2[k] for k in ("d", "e", "f", "alpha", "gx", "gy")] + [branch_2])
                for i, (_, toggle, offset, angle, length) in enumerate(chosen):
                    # The first loop: well conditioned, a few ulps.
                    for name, exact in zip(WATT2_OUTPUTS, first[angle]):
                        assert angle_error(result[name][i], exact) < 1e-15, (backend, branch_1, name, angle)
                    mu, psi, distance = watt2_second_loop(result["rocker"][i], length, branch_2)
                    with mp.workdps(DIGITS):
                        f, g_ = mp.mpf(WATT2["f"]), mp.mpf(length)
                        defect = min((f + g_ - distance) / (f + g_), (distance - abs(f - g_)) / abs(f - g_))
                    diagonal = WATT2["f"] + length if toggle == "extended" else abs(WATT2["f"] - length)
                    if abs(defect) > 2 * clamping_band(WATT2["f"], length, diagonal, known):
                        flags.append(((backend, branch_1, branch_2, toggle, offset), mu is not None,
                                      bool(numpy.isfinite(old[1][i])), bool(result["assembled"][i])))
                    if mu is None or not (numpy.isfinite(old[1][i]) and result["assembled"][i]):
                        continue
                    new_errors, old_errors = groups.setdefault((backend, branch_1, branch_2, toggle), ([], []))
                    new_errors += [scaled_error(result["coupler2"][i], mu, defect),
                                   scaled_error(result["output"][i], psi, defect)]
                    old_errors += [scaled_error(old[0][i], mu, defect), scaled_error(old[1][i], psi, defect)]
    assert len(groups) >= 2 * 2 * 2 and min(len(new) for new, _ in groups.values()) >= 100, groups.keys()
    assert sum(not f[1] for f in flags) >= 100 and sum(f[1] for f in flags) >= 100
    check(groups, flags)
