"""The four-bar's transmission angle in closed form: triangle angles by hand and against 50-digit mpmath, the
extremes over the crank's range by hand (the law of cosines over the diagonal BD) and against a dense hand scan."""
import math

import mpmath as mp
import numpy as np
import pytest

from symlink.numeric.fourbar_transmission import transmission_range, triangle_angle
from references import fourbar_joint_c

SEED003 = (20.0, 66.0, 56.0, 80.0)


def law_of_cosines(opposite, side1, side2):
    """The angle between side1 and side2, by the plain law of cosines (well-shaped triangles only)."""
    return math.acos((side1**2 + side2**2 - opposite**2) / (2 * side1 * side2))


# --- triangle_angle ----------------------------------------------------------------------------

@pytest.mark.parametrize("opposite, side1, side2, expected", [
    (5.0, 3.0, 4.0, math.pi / 2),          # 3-4-5
    (1.0, 1.0, 1.0, math.pi / 3),          # equilateral
    (2.0, 1.0, 1.0, math.pi),              # flat, opposite the sum
    (0.0, 1.0, 1.0, 0.0),                  # flat, folded
    (math.sqrt(2.0), 1.0, 1.0, math.pi / 2),
])
def test_triangle_angle_by_hand(opposite, side1, side2, expected):
    assert float(triangle_angle(opposite, side1, side2)) == pytest.approx(expected, abs=1e-15)


@pytest.mark.parametrize("shortfall", [1e-3, 1e-7, 1e-10, 1e-12])
def test_triangle_angle_keeps_its_digits_near_flat_against_mpmath(shortfall):
    """Near flat (opposite = side1 + side2 less a little) acos loses half the digits; atan2 of Heron's product
    keeps them: the 50-digit law of cosines is the reference."""
    mp.mp.dps = 50
    side1, side2 = 1.25, 2.5
    opposite = side1 + side2 - shortfall
    exact = mp.acos((mp.mpf(side1)**2 + mp.mpf(side2)**2 - mp.mpf(opposite)**2) / (2 * mp.mpf(side1) * side2))
    assert float(triangle_angle(opposite, side1, side2)) == pytest.approx(float(exact), rel=1e-14)


def test_triangle_angle_no_triangle_is_nan_unless_clamped():
    assert math.isnan(float(triangle_angle(2.0, 0.5, 1.0)))
    assert float(triangle_angle(2.0, 0.5, 1.0, clamp=True)) == math.pi   # past flat, opposite the sum
    assert float(triangle_angle(0.1, 0.5, 1.0, clamp=True)) == 0.0       # past flat, folded
    assert float(triangle_angle(1.5 * (1 + 1e-16), 0.5, 1.0)) == math.pi  # rounding past flat is flat


# --- transmission extremes ------------------------------------------------------------------

@pytest.mark.parametrize("lengths, minimum, minimum_at, maximum, maximum_at", [
    # seed 003: BD is d - a = 60 long at theta = 0 and d + a = 100 at pi
    (SEED003, law_of_cosines(60, 66, 56), 0.0, law_of_cosines(100, 66, 56), math.pi),
    # B on D at theta = 0 (a = d, b = c): BD is 0 long, mu = 0; the crank reaches cos(theta) = (4 + 4 - 4) / 8
    # = 1/2 at most, where BD = b + c and mu = pi (the printout said nan before)
    ((2.0, 1.0, 1.0, 2.0), 0.0, 0.0, math.pi, -math.pi / 3),
    # a kite that turns fully: mu = 0 at theta = 0, and at pi BD = 4: cos(mu) = (9 + 9 - 16) / 18 = 1/9
    ((2.0, 3.0, 3.0, 2.0), 0.0, 0.0, math.acos(1 / 9), math.pi),
    # 1, 2, 2, 1: at pi BD = 2, an equilateral triangle with b and c
    ((1.0, 2.0, 2.0, 1.0), 0.0, 0.0, math.pi / 3, math.pi),
    # a triple rocker: mu = acos((36 + 49 - 25) / 84) at theta = 0, pi at its extended toggles
    ((5.0, 6.0, 7.0, 10.0), law_of_cosines(5, 6, 7), 0.0, math.pi, -law_of_cosines(13, 5, 10)),
])
def test_transmission_range_by_hand(lengths, minimum, minimum_at, maximum, maximum_at):
    found = transmission_range(*lengths)
    assert found.minimum == pytest.approx(minimum, abs=1e-12)
    assert found.minimum_at == pytest.approx(minimum_at, abs=1e-12)
    assert found.maximum == pytest.approx(maximum, abs=1e-12)
    assert found.maximum_at == pytest.approx(maximum_at, abs=1e-12)
    assert not any(math.isnan(x) for x in (found.minimum, found.maximum, found.worst))


def test_transmission_range_is_the_extreme_of_a_dense_hand_scan():
    """The transmission angle at C from C found by hand, over a dense crank scan of a double crank."""
    a, b, c, d = 4.0, 5.0, 6.0, 2.0
    angles = []
    for theta in np.linspace(-math.pi, math.pi, 20001):
        cx, cy = fourbar_joint_c(theta, a, b, c, d)
        to_b = (a * math.cos(theta) - cx, a * math.sin(theta) - cy)
        to_d = (d - cx, -cy)
        angles.append(math.atan2(abs(to_b[0] * to_d[1] - to_b[1] * to_d[0]), to_b[0] * to_d[0] + to_b[1] * to_d[1]))
    found = transmission_range(a, b, c, d)
    assert found.minimum == pytest.approx(min(angles), abs=1e-9)
    assert found.maximum == pytest.approx(max(angles), abs=1e-9)
