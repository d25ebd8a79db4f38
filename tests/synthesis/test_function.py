"""Function generation (Freudenstein), checked against an independent mpmath computation.

No printed textbook numbers were found that could be trusted to their last digit (the
searches found course notes reproducing Norton's and Shigley's derivations, not a table of
results), so the textbook-style example here -- y = log10(x) on [1, 2], crank 45..105 deg,
rocker 135..225 deg, three Chebyshev points, the classic exercise -- is checked against
mpmath: the precision points' K's by a 30-digit linear solve written here, and the
generated rocker angle by solving the four-bar's closure at 30 digits with findroot.
"""
import math

import mpmath as mp
import numpy as np
import pytest

from symlink.synthesis.function import (chebyshev_points, freudenstein_coefficients, function_generator,
                                        least_squares_design, lengths_from_coefficients, three_point_design)
from tests.mp_closures import fourbar_closure

deg = math.radians
EXAMPLE = dict(function=math.log10, x_range=(1.0, 2.0), theta_range=(deg(45), deg(105)),
               phi_range=(deg(135), deg(225)))


def mp_rocker(lengths, theta, guess):
    """The rocker angle at crank angle theta by findroot on the closure (30 digits), near ``guess`` (beta, phi)."""
    a, b, c, d = (mp.mpf(x) for x in lengths)
    p = dict(a=a, b=b, c=c, d=d)
    with mp.workdps(30):
        beta, phi = mp.findroot(lambda u, v: fourbar_closure([mp.mpf(theta)], [u, v], p), guess)
    return phi, beta


def mp_error(design, theta, wanted):
    """Rocker angle minus wanted (wrapped) on the design's branch: C where the circles about B and D meet,
    on the side of B->D that the branch names (+1 left), at 30 digits."""
    with mp.workdps(30):
        a, b, c, d = (mp.mpf(x) for x in design.lengths)
        B, D = a * mp.expj(mp.mpf(theta) + design.crank_offset), d
        w = abs(D - B)
        along = (b ** 2 - c ** 2 + w ** 2) / (2 * w)
        u = (D - B) / w
        C = B + along * u + design.branch * mp.sqrt(b ** 2 - along ** 2) * 1j * u
        difference = mp.arg(C - D) - design.rocker_offset - wanted
        return mp.atan2(mp.sin(difference), mp.cos(difference))


def test_freudenstein_sign_convention_matches_the_catalog_fourbar():
    # K1 cos(phi) - K2 cos(theta) + K3 = cos(theta - phi) with K1 = d/a, K2 = d/c, K3 = (a^2-b^2+c^2+d^2)/(2ac),
    # on closures solved by mpmath (seed 003's linkage, both branches, several crank angles).
    a, b, c, d = 20, 66, 56, 80
    k1, k2, k3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)
    assert freudenstein_coefficients(a, b, c, d) == pytest.approx((k1, k2, k3), rel=1e-15)
    for theta in np.linspace(-3, 3, 7):
        for guess in ((0.3, 1.9), (-0.9, -1.9)):
            phi, _ = mp_rocker((a, b, c, d), theta, guess)
            phi = float(phi)
            assert k1 * math.cos(phi) - k2 * math.cos(theta) + k3 == pytest.approx(math.cos(theta - phi), abs=1e-12)


def test_chebyshev_spacing_by_hand():
    # 1.5 -+ 0.5 cos(30 deg): 1.0669873, 1.5, 1.9330127
    assert chebyshev_points(1.0, 2.0) == pytest.approx([1.5 - 0.5 * math.sqrt(3) / 2, 1.5, 1.5 + 0.5 * math.sqrt(3) / 2])


def _example_angles_mp():
    """The three Chebyshev precision points of the example, at 30 digits."""
    with mp.workdps(30):
        xs = [mp.mpf(3) / 2 - mp.cos((2 * j - 1) * mp.pi / 6) / 2 for j in (1, 2, 3)]
        theta = [mp.radians(45) + (x - 1) * mp.radians(60) for x in xs]
        phi = [mp.radians(135) + mp.log10(x) / mp.log10(2) * mp.radians(90) for x in xs]
    return theta, phi


def test_three_point_design_of_the_example_against_mpmath():
    design = function_generator(**EXAMPLE)
    theta, phi = _example_angles_mp()
    with mp.workdps(30):
        rows = mp.matrix([[mp.cos(p), -mp.cos(t), 1] for t, p in zip(theta, phi)])
        right = mp.matrix([mp.cos(t - p) for t, p in zip(theta, phi)])
        k = mp.lu_solve(rows, right)
        a, c = 1 / k[0], 1 / k[1]
        b = mp.sqrt(a * a + c * c + 1 - 2 * a * c * k[2])
    assert design.coefficients == pytest.approx([float(x) for x in k], rel=1e-12)
    # This example needs a rocker turned by 180 deg (K2 < 0): the design records it as an offset.
    assert float(c) < 0 and design.rocker_offset == pytest.approx(math.pi)
    assert design.lengths == pytest.approx((float(abs(a)), float(b), float(abs(c)), 1.0), rel=1e-12)
    # The linkage passes through each precision point (30-digit circle intersection, rocker = phi + 180 deg),
    # and its structural error at samples of x is the mpmath one.
    for t, p in zip(theta, phi):
        assert abs(float(mp_error(design, t, p))) < 1e-13
    for x in (1.0, 1.25, 1.5, 1.75, 2.0):
        t = deg(45) + (x - 1) * deg(60)
        wanted = deg(135) + math.log10(x) / math.log10(2) * deg(90)
        index = int(np.argmin(np.abs(design.error_theta - t)))
        assert design.error_theta[index] == pytest.approx(t, abs=1e-12)
        assert design.errors[index] == pytest.approx(float(mp_error(design, t, wanted)), abs=1e-12)
    assert design.structural_error == pytest.approx(float(np.max(np.abs(design.errors))))
    assert design.structural_error < deg(0.2)


FUNCTIONS = [
    ("log10 on [1, 2]", EXAMPLE),
    ("x^2 on [0, 1]", dict(function=lambda x: x * x, x_range=(0.0, 1.0), theta_range=(deg(0), deg(90)),
                           phi_range=(deg(90), deg(150)))),
    ("sin on [0, pi/2]", dict(function=math.sin, x_range=(0.0, math.pi / 2), theta_range=(deg(-20), deg(70)),
                              phi_range=(deg(200), deg(260)))),
    ("exp on [0, 1]", dict(function=math.exp, x_range=(0.0, 1.0), theta_range=(deg(40), deg(100)),
                           phi_range=(deg(130), deg(200)))),
]


@pytest.mark.parametrize("name,problem", FUNCTIONS, ids=[f[0] for f in FUNCTIONS])
def test_least_squares_never_worse_than_three_points(name, problem):
    three = function_generator(**problem)
    fitted = function_generator(**problem, method="least-squares", points=40)
    assert fitted.branch in (1, -1) and three.branch in (1, -1)
    assert fitted.structural_error <= three.structural_error * (1 + 1e-9)


def test_least_squares_recovers_an_exact_four_bar():
    # Pairs taken from a four-bar's own (mpmath) input-output curve: least squares finds that four-bar.
    lengths = (20, 66, 56, 80)
    theta = np.linspace(-1.0, 1.0, 15)
    phi = [float(mp_rocker(lengths, t, (0.3, 1.9))[0]) for t in theta]
    design = least_squares_design(theta, phi, ground=80)
    assert design.lengths == pytest.approx(lengths, rel=1e-9)
    assert design.structural_error < 1e-9 and design.branch == 1


BAD = [
    ("too few pairs", dict(theta=[0.1, 0.2], phi=[1.0, 1.1]), "at least 3"),
    ("different lengths", dict(theta=[0.1, 0.2, 0.3], phi=[1.0, 1.1]), "same length"),
    ("NaN", dict(theta=[0.1, float("nan"), 0.3], phi=[1.0, 1.1, 1.2]), "finite"),
    ("repeated points", dict(theta=[0.1, 0.1, 0.1], phi=[1.0, 1.0, 1.0]), "same target"),
    ("bad ground", dict(theta=[0.1, 0.2, 0.3], phi=[1.0, 1.1, 1.3], ground=-1.0), "positive"),
]


@pytest.mark.parametrize("name,kwargs,message", BAD, ids=[b[0] for b in BAD])
def test_bad_input_is_a_value_error(name, kwargs, message):
    with pytest.raises(ValueError, match=message):
        three_point_design(**kwargs)


@pytest.mark.parametrize("kwargs,message", [
    (dict(method="newton"), "method"),
    (dict(x_range=(1.0, 1.0)), "two different ends"),
    (dict(method="least-squares", points=2), "at least 3"),
    (dict(function=lambda x: 1.0), "two different finite values"),
])
def test_bad_function_requests(kwargs, message):
    with pytest.raises(ValueError, match=message):
        function_generator(**{**EXAMPLE, **kwargs})


def test_imaginary_coupler_is_refused():
    with pytest.raises(ValueError, match="imaginary coupler"):
        lengths_from_coefficients(1.0, 1.0, 5.0)
