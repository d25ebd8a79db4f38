"""The reference implementations in ``references.py`` checked against each other.

The seed formulas (NumPy, double precision) are compared with the 50-digit mpmath
references, and those with central finite differences of their own positions, so that a
sign error in any one of them shows up. The seed 003 table and the seed 000/002 worked
numbers are checked to their printed precision, except for the recorded misprints.
"""

import mpmath as mp
import numpy as np
import pytest

from references import (
    SEED003_BRANCHES, SEED003_LINKAGE, SEED003_MISPRINTS, SEED003_TABLE, mp_fourbar,
    mp_slider_crank, seed000_case1, seed000_case2a, seed000_case2b, seed000_case3,
    seed002_positions, seed003_accels, seed003_coefficients, seed003_positions,
    seed003_rates, transmission_angle,
)

BRANCHES = (1, -1)


def wrap(x):
    return np.angle(np.exp(1j * np.asarray(x, dtype=float)))


def mp_wrap(x):
    return x - 2 * mp.pi * mp.nint(x / (2 * mp.pi))


def random_fourbars(n, seed, min_sin_mu=0.1):
    """n random (a, b, c, d, theta) that assemble, away from toggles (|sin mu| > min_sin_mu)."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        a, b, c, d = rng.uniform(0.2, 3.0, 4)
        theta = rng.uniform(-np.pi, np.pi)
        try:
            ref = mp_fourbar(a, b, c, d, theta, 1)
        except ValueError:
            continue
        if abs(np.sin(transmission_angle(float(ref["beta"]), float(ref["phi"])))) > min_sin_mu:
            out.append((a, b, c, d, theta))
    return out


FOURBARS = random_fourbars(150, seed=2024)


def fd_rates(position, theta, w, al, key, angle=True, h="1e-12"):
    """Central differences (speed, accel) of position(theta)[key] along theta + w t + al t^2/2."""
    with mp.workdps(50):
        h, theta = mp.mpf(h), mp.mpf(theta)
        p = [position(theta + w * t + al * t * t / 2)[key] for t in (-h, 0, h)]
        dm, dp = p[0] - p[1], p[2] - p[1]
        if angle:
            dm, dp = mp_wrap(dm), mp_wrap(dp)
        return (dp - dm) / (2 * h), (dp + dm) / h**2


# --- mp references -------------------------------------------------------------------

@pytest.mark.parametrize("branch", BRANCHES)
def test_mp_fourbar_closes_the_loop_on_its_branch(branch):
    for a, b, c, d, theta in FOURBARS[:40]:
        r = mp_fourbar(a, b, c, d, theta, branch)
        with mp.workdps(50):
            B = a * mp.expj(theta)
            C = B + b * mp.expj(r["beta"])
            assert abs(C - d - c * mp.expj(r["phi"])) < mp.mpf("1e-40")
            cross = (d - B.real) * (C.imag - B.imag) + B.imag * (C.real - B.real)
            assert mp.sign(cross) == branch


def test_mp_fourbar_seed003_branch_at_zero():
    r = mp_fourbar(20, 66, 56, 80, 0, 1)
    assert float(mp.degrees(r["phi"])) == pytest.approx(110.74, abs=0.005)


@pytest.mark.parametrize("branch", BRANCHES)
def test_mp_fourbar_rates_match_finite_differences(branch):
    rng = np.random.default_rng(7)
    for a, b, c, d, theta in FOURBARS[:20]:
        w, al = rng.uniform(-20, 20), rng.uniform(-50, 50)
        r = mp_fourbar(a, b, c, d, theta, branch, w, al)
        for key in ("beta", "phi"):
            speed, accel = fd_rates(lambda t: mp_fourbar(a, b, c, d, t, branch), theta, w, al, key)
            assert abs(speed - r[key + "_speed"]) < 1e-15 * (1 + abs(speed))
            assert abs(accel - r[key + "_accel"]) < 1e-15 * (1 + abs(accel))


def test_mp_fourbar_rejects_bad_input():
    with pytest.raises(ValueError, match="cannot be assembled"):
        mp_fourbar(1, 1, 1, 10, 0, 1)
    with pytest.raises(ValueError, match="positive"):
        mp_fourbar(-1, 2, 2, 2, 0, 1)
    with pytest.raises(ValueError, match="branch"):
        mp_fourbar(1, 2, 2, 2, 0, 0)


@pytest.mark.parametrize("branch", BRANCHES)
def test_mp_slider_crank(branch):
    rng = np.random.default_rng(11)
    checked = 0
    while checked < 20:
        a, b = rng.uniform(0.2, 3.0, 2)
        e, theta = rng.uniform(-1, 1), rng.uniform(-np.pi, np.pi)
        w, al = rng.uniform(-20, 20), rng.uniform(-50, 50)
        try:
            r = mp_slider_crank(a, b, e, theta, branch, w, al)
            other = mp_slider_crank(a, b, e, theta, -branch)
        except ValueError:
            continue
        if abs(mp.cos(r["beta"])) < 0.1:
            continue
        checked += 1
        with mp.workdps(50):
            assert abs(a * mp.expj(theta) + b * mp.expj(r["beta"]) - r["s"] - 1j * e) < mp.mpf("1e-40")
        assert branch * (r["s"] - other["s"]) > 0
        for key, angle in (("beta", True), ("s", False)):
            speed, accel = fd_rates(lambda t: mp_slider_crank(a, b, e, t, branch), theta, w, al, key, angle)
            assert abs(speed - r[key + "_speed"]) < 1e-15 * (1 + abs(speed))
            assert abs(accel - r[key + "_accel"]) < 1e-15 * (1 + abs(accel))


# --- seed 003 --------------------------------------------------------------------------

def test_half_angle_matches_mp_fourbar_on_both_branches():
    """Also shows that the "+" root is branch -1 whatever the signs of A and d - a cos(theta)."""
    signs = set()
    for a, b, c, d, theta in FOURBARS:
        _, A, _, _ = seed003_coefficients(a, b, c, d, theta)
        signs.add((np.sign(A), np.sign(d - a * np.cos(theta))))
        for branch in BRANCHES:
            beta, phi = seed003_positions(a, b, c, d, theta, branch)
            r = mp_fourbar(a, b, c, d, theta, branch)
            assert abs(wrap(phi - float(r["phi"]))) < 1e-10
            assert abs(wrap(beta - float(r["beta"]))) < 1e-10
    assert signs == {(1, 1), (1, -1), (-1, 1), (-1, -1)}


def test_half_angle_is_vectorised_and_nan_where_open():
    theta = np.linspace(-np.pi, np.pi, 7)
    beta, phi = seed003_positions(20, 66, 56, 80, theta, 1)
    assert beta.shape == phi.shape == theta.shape
    assert np.all(np.isnan(seed003_positions(1, 1, 1, 10, theta, 1)[1]))


def test_seed003_plus_root_is_branch_minus_one():
    a, b, c, d = 20, 66, 56, 80
    theta = np.linspace(-np.pi, np.pi, 73)
    _, A, B, C = seed003_coefficients(a, b, c, d, theta)
    phi_plus = 2 * np.arctan((-B + np.sqrt(B * B - 4 * A * C)) / (2 * A))
    assert np.all(A < 0)
    np.testing.assert_allclose(wrap(phi_plus - seed003_positions(a, b, c, d, theta, -1)[1]), 0, atol=1e-12)
    assert np.degrees(seed003_positions(a, b, c, d, 0.0, 1)[1]) == pytest.approx(110.74, abs=0.005)


def test_seed003_worked_example():
    K, A, B, C = seed003_coefficients(20, 66, 56, 80, np.radians(40))
    assert K == 2790  # printed 2K = 5588: 2K = 5580
    assert (A, B, C) == pytest.approx((-2057.70, -1439.84, 5186.35), abs=0.01)  # C = 5186.359
    phi = [np.degrees(seed003_positions(20, 66, 56, 80, np.radians(40), s)[1]) for s in BRANCHES]
    assert phi == pytest.approx([103.82, -126.30], abs=0.005)  # printed: "-113.27 OR 120"


def test_seed003_rates_and_accels_match_mp_and_finite_differences():
    rng = np.random.default_rng(3)
    for i, (a, b, c, d, theta) in enumerate(FOURBARS):
        w, al = rng.uniform(-20, 20), rng.uniform(-50, 50)
        for branch in BRANCHES:
            r = mp_fourbar(a, b, c, d, theta, branch, w, al)
            beta, phi = float(r["beta"]), float(r["phi"])
            wb, wc = seed003_rates(a, b, c, theta, beta, phi, w)
            ab, ac = seed003_accels(a, b, c, theta, beta, phi, w, al, wb, wc)
            references = [[r["beta_speed"], r["phi_speed"], r["beta_accel"], r["phi_accel"]]]
            if i < 10:  # finite differences of the mp positions, too
                position = lambda t: mp_fourbar(a, b, c, d, t, branch)
                (sb, ab_fd), (sp, ap_fd) = (fd_rates(position, theta, w, al, key) for key in ("beta", "phi"))
                references.append([sb, sp, ab_fd, ap_fd])
            for ref in references:
                ref = np.array(ref, dtype=float)
                assert np.all(abs(np.array([wb, wc, ab, ac]) - ref) < 1e-9 * (1 + abs(ref)))


def test_seed003_eq41_as_printed_is_wrong():
    """Eq. 4.1 printed W_b = -a W_a sin(phi - theta) / (b sin(theta - beta))."""
    r = mp_fourbar(20, 66, 56, 80, np.radians(40), 1, 10.5)
    theta, beta, phi = np.radians(40), float(r["beta"]), float(r["phi"])
    printed = -20 * 10.5 * np.sin(phi - theta) / (66 * np.sin(theta - beta))
    assert seed003_rates(20, 66, 56, theta, beta, phi, 10.5)[0] == pytest.approx(float(r["beta_speed"]))
    assert abs(printed - float(r["beta_speed"])) > 1


def _exact_row(theta_deg, branch):
    with mp.workdps(50):
        theta = mp.radians(theta_deg)
    r = mp_fourbar(**SEED003_LINKAGE, theta=theta, branch=branch, crank_speed=10.5, crank_accel=0)
    return [float(mp.degrees(r["phi"])), float(mp.degrees(r["beta"])), float(r["phi_speed"]),
            float(r["beta_speed"]), float(r["phi_accel"]), float(r["beta_accel"])]


def test_seed003_table_matches_except_misprints():
    misprints = {(row, col): (printed, right) for row, col, printed, right in SEED003_MISPRINTS}
    wrong_if_velb_were_rocker = 0
    for i, (row, branch) in enumerate(zip(SEED003_TABLE, SEED003_BRANCHES)):
        assert row[1:3] == (10.5, 0.0)
        exact = _exact_row(row[0], branch)
        for col, value in enumerate(exact, start=3):
            printed = row[col]
            if (i, col) in misprints:
                assert misprints[i, col] == (printed, round(value, 2))
                assert abs(printed - value) > 0.01
            else:
                assert abs(printed - value) <= 0.01, (i, col, printed, value)
        wrong_if_velb_were_rocker += abs(row[6] - exact[2]) > 0.01
    assert wrong_if_velb_were_rocker > 10  # the paper's "O/P variables" list is wrong


# --- seed 002 ----------------------------------------------------------------------------

def test_imaginary_line_matches_mp_fourbar():
    for a, b, c, d, theta in FOURBARS:
        r = mp_fourbar(a, b, c, d, theta, 1)
        beta, phi = float(r["beta"]), float(r["phi"])
        theta5, L5, theta3, theta4, gamma34 = seed002_positions(d, a, b, c, 0.0, theta)
        assert L5 * np.exp(1j * theta5) == pytest.approx(d - a * np.exp(1j * theta), abs=1e-12)
        assert abs(wrap(theta3 - beta)) < 1e-10
        assert abs(wrap(theta4 - phi - np.pi)) < 1e-10
        assert gamma34 == pytest.approx(transmission_angle(beta, phi), abs=1e-10)


def test_imaginary_line_in_a_rotated_frame():
    for a, b, c, d, theta in FOURBARS[:30]:
        turn = 2.0
        plain = seed002_positions(d, a, b, c, 0.0, theta)
        turned = seed002_positions(d, a, b, c, turn, theta + turn)
        for i in (0, 2, 3):
            assert abs(wrap(turned[i] - plain[i] - turn)) < 1e-10
        assert turned[4] == pytest.approx(plain[4], abs=1e-10)


def test_seed002_transmission_angle_range():
    theta = np.linspace(0, 2 * np.pi, 100001)
    _, _, theta3, theta4, gamma34 = seed002_positions(70, 16.084, 69.743, 50, 0.0, theta)
    assert np.degrees([gamma34.min(), gamma34.max()]) == pytest.approx([50.28, 90.38], abs=0.005)
    assert np.all(gamma34 > 0)


# --- seed 000 ----------------------------------------------------------------------------

def test_seed000_worked_example():
    rad = np.radians
    R3, R4 = seed000_case1(300, rad(270), 640.3124, rad(308.663), rad(180), rad(63.435))
    assert (round(R3, 4), round(R4, 4)) == (800.0158, 894.4019)


def random_loops(n, seed):
    """n random closed loops (R1, t1, R2, t2, R3, t3, R4, t4), all lengths positive."""
    rng = np.random.default_rng(seed)
    loops = []
    for _ in range(n):
        R1, R2, R3 = rng.uniform(0.2, 3.0, 3)
        t1, t2, t3 = rng.uniform(-np.pi, np.pi, 3)
        z4 = -(R1 * np.exp(1j * t1) + R2 * np.exp(1j * t2) + R3 * np.exp(1j * t3))
        loops.append((R1, t1, R2, t2, R3, t3, abs(z4), np.angle(z4)))
    return loops


def residual(R1, t1, R2, t2, R3, t3, R4, t4):
    return abs(sum(R * np.exp(1j * t) for R, t in ((R1, t1), (R2, t2), (R3, t3), (R4, t4))))


def test_seed000_cases_recover_and_close_the_loop():
    for R1, t1, R2, t2, R3, t3, R4, t4 in random_loops(200, seed=5):
        known = (R1, t1, R2, t2)
        assert seed000_case1(*known, t3, t4) == pytest.approx((R3, R4), rel=1e-9)
        R3a, t3a = seed000_case2a(*known, R4, t4)
        assert (R3a, wrap(t3a - t3)) == pytest.approx((R3, 0), abs=1e-9)
        solutions = seed000_case2b(*known, R3, t4)
        pairs = seed000_case3(*known, R3, R4)
        for R4b, t3b in solutions:
            assert residual(*known, R3, t3b, R4b, t4) < 1e-10
        for t3c, t4c in pairs:
            assert residual(*known, R3, t3c, R4, t4c) < 1e-10
        assert min(abs(R4b - R4) + abs(wrap(t3b - t3)) for R4b, t3b in solutions) < 1e-9
        assert min(abs(wrap(t3c - t3)) + abs(wrap(t4c - t4)) for t3c, t4c in pairs) < 1e-9


def test_seed000_eq4_as_printed_does_not_close():
    """Eq. 4 printed [R1 sin(t1-t4) - R2 sin(t2-t4)]; with '+' it is the case 2b solution."""
    R1, t1, R2, t2, R3, t3, R4, t4 = random_loops(1, seed=9)[0]
    q = (-R1 * np.sin(t1 - t4) - R2 * np.sin(t2 - t4)) / R3
    base = -R1 * np.cos(t1 - t4) - R2 * np.cos(t2 - t4)
    k = np.sqrt(1 - q * q) / q
    corrected = [base + s * k * (R1 * np.sin(t1 - t4) + R2 * np.sin(t2 - t4)) for s in (1, -1)]
    printed = [base + s * k * (R1 * np.sin(t1 - t4) - R2 * np.sin(t2 - t4)) for s in (1, -1)]
    assert corrected == pytest.approx([R4b for R4b, _ in seed000_case2b(R1, t1, R2, t2, R3, t4)], rel=1e-12)
    assert min(abs(np.array(printed) - R4)) > 1e-3


def test_seed000_case3_is_the_fourbar():
    """z1 = d e^{i pi}, z2 crank, z3 coupler, z4 = rocker reversed: eq. 9-10 is branch +1."""
    for a, b, c, d, theta in FOURBARS[:50]:
        pairs = seed000_case3(d, np.pi, a, theta, b, c)
        for (t3, t4), branch in zip(pairs, (-1, 1)):
            r = mp_fourbar(a, b, c, d, theta, branch)
            assert abs(wrap(t3 - float(r["beta"]))) < 1e-10
            assert abs(wrap(t4 - float(r["phi"]) - np.pi)) < 1e-10
