"""Independent reference implementations for checking symlink's generated solvers.

Everything here is written by hand from the seed papers (``/work/shared/seeds``) and from
first principles. It never imports ``symlink``, so a mistake in symlink's derivations
cannot slip into the references too.

Conventions (DESIGN.md). Radians throughout. Four-bar: crank pivot A at the origin, rocker
pivot D at (d, 0), crank a = AB at theta, coupler b = BC at beta, rocker c = DC at phi::

    a e^{i theta} + b e^{i beta} = d + c e^{i phi}            (x: ..cos, y: ..sin)

Branch +1: joint C lies to the left of the directed line B -> D; -1: to the right.

Contents

* Seed 003 (C-program paper): ``seed003_coefficients``, ``seed003_positions`` (Freudenstein
  half-angle solution), ``seed003_rates`` (eq. 4.1/4.2) and ``seed003_accels`` (its alpha
  formulas), plus the table ``SEED003_TABLE`` with ``SEED003_COLUMNS``,
  ``SEED003_LINKAGE``, ``SEED003_BRANCHES`` and ``SEED003_MISPRINTS``.
* Seed 002 (quick-return paper): ``seed002_positions``, the "imaginary line" L5 solution
  of its section 2.1, and ``transmission_angle``.
* Seed 000 (MATLAB position paper): the case formulas ``seed000_case1``,
  ``seed000_case2a``, ``seed000_case2b`` and ``seed000_case3`` for z1 + z2 + z3 + z4 = 0.
* ``fourbar_joint_c``: the four-bar's joint C where two circles meet, in double precision.
* ``mp_fourbar`` and ``mp_slider_crank``: 50-digit mpmath references computed a different
  way (circle intersections for the positions, and the 2x2 linear systems obtained by
  differentiating the loop's x and y equations by hand for the rates and accelerations).

The numerical seed formulas are vectorised with NumPy and give NaN where the loop cannot
close. Each misprint corrected below is marked ``MISPRINT`` with what the paper printed and
what is right.
"""

import math

import mpmath as mp
import numpy as np

_MP_DPS = 50


def _wrap(angle):
    """Angle(s) wrapped to (-pi, pi]."""
    return np.angle(np.exp(1j * np.asarray(angle, dtype=float)))


# --------------------------------------------------------------------------------------
# Seed 003: Freudenstein half-angle solution, velocity and acceleration formulas
# --------------------------------------------------------------------------------------

def seed003_coefficients(a, b, c, d, theta):
    """Seed 003's (K, A, B, C) for A t^2 + B t + C = 0, t = tan(phi/2), as printed in 3.1.

    They follow from |b e^{i beta}|^2 = |d + c e^{i phi} - a e^{i theta}|^2, i.e.
    K - a d cos(theta) + c (d - a cos(theta)) cos(phi) - a c sin(theta) sin(phi) = 0,
    and the text formulas are right. MISPRINTS nearby:
    * worked example 4.1: printed "2K = ... = 5588"; 20^2 - 66^2 + 56^2 + 80^2 = 5580
      (its K = 2790 is right);
    * the C program prints ``aa=k-a*(d-c*cos(thet)-c*d`` (unbalanced; right:
      ``k-a*(d-c)*cos(thet)-c*d``), ``bb=2*a*c*sin(thet)`` (sign; right:
      ``-2*a*c*sin(thet)``; as printed it solves the mirror image, theta -> -theta) and
      ``cc=k-a*d+c*cos(thet)+c*d`` (right: ``k-a*(d+c)*cos(thet)+c*d``). It also has
      ``#include<studio.h>``, ``for(j=0;j,iht+1,j++)``, undeclared ``dthet`` and
      unbalanced parentheses in ``accc``/``accb``: it does not compile as printed, and
      the table agrees with the text formulas, not with the program's ``bb``.
    """
    theta = np.asarray(theta, dtype=float)
    K = (a * a - b * b + c * c + d * d) / 2
    A = K - a * (d - c) * np.cos(theta) - c * d
    B = -2 * a * c * np.sin(theta)
    C = K - a * (d + c) * np.cos(theta) + c * d
    return K, A, B, C


def seed003_positions(a, b, c, d, theta, branch):
    """(beta, phi) of the four-bar by seed 003's eq. 2 and eq. 3; NaN where it cannot close.

    phi = 2 atan((-B + s sqrt(B^2 - 4AC)) / (2A)), s = +1 or -1 (eq. 2).

    Which s is which branch (derived, and checked in the tests against ``mp_fourbar``):
    write the Freudenstein equation as P + Q cos(phi) + R sin(phi) = 0 with
    (Q, R) = c (d - a cos(theta), -a sin(theta)) = c (D - B), so A = P - Q, B = 2R,
    C = P + Q and B^2 - 4AC = 4(Q^2 + R^2 - P^2). The branch is
    sign((D - B) x (C - D)) = sign(Q sin(phi) - R cos(phi)); substituting the root t_s
    gives branch = s * sign(Q A - R^2) = s * sign(Q P - (Q^2 + R^2)). Wherever the loop
    closes P^2 <= Q^2 + R^2, so Q P <= |Q| |P| <= Q^2 + R^2 and the sign is -1 (0 only at
    a toggle with B on the ground line). Hence, for every linkage and crank angle:
    the "+" root is branch -1 and the "-" root is branch +1 (seed 003 at theta = 0:
    "+" gives phi = -110.74 deg, "-" gives +110.74 deg).

    beta: eq. 3, "C sin(phi) = a sin(theta) + b sin(beta)", is the loop's y component (its
    "C" is the rocker length c, not the coefficient C). Solving it with asin, as the C
    program does, loses the quadrant (|beta| > 90 deg is never returned), so beta is taken
    from the x and y components together:
    beta = atan2(c sin(phi) - a sin(theta), d + c cos(phi) - a cos(theta)).

    Eq. 2 divides by 2A: near A = 0 one root has phi near 180 deg and the other is a
    difference of nearly equal numbers over a small one, so it loses digits there.
    """
    theta = np.asarray(theta, dtype=float)
    _, A, B, C = seed003_coefficients(a, b, c, d, theta)
    with np.errstate(invalid="ignore", divide="ignore"):
        phi = 2 * np.arctan((-B - np.asarray(branch) * np.sqrt(B * B - 4 * A * C)) / (2 * A))
    beta = np.arctan2(c * np.sin(phi) - a * np.sin(theta), d + c * np.cos(phi) - a * np.cos(theta))
    return beta, phi


def seed003_rates(a, b, c, theta, beta, phi, crank_speed):
    """(coupler_speed, rocker_speed) from seed 003's eq. 4.1 and 4.2 (corrected).

    Differentiating the loop: a w_a e^{i theta} + b w_b e^{i beta} = c w_c e^{i phi}.
    Multiplying by e^{-i phi} (or e^{-i beta}) and keeping the imaginary part gives
    w_b = a w_a sin(phi - theta) / (b sin(beta - phi)),
    w_c = a w_a sin(beta - theta) / (c sin(beta - phi)).
    MISPRINT eq. 4.1: printed W_b = -a W_a sin(phi - theta) / (b sin(theta - beta)); the
    denominator must be b sin(beta - phi) (the C program's ``velb`` has it right).
    Eq. 4.2 is right as printed.
    """
    den = np.sin(beta - phi)
    coupler_speed = a * crank_speed * np.sin(phi - theta) / (b * den)
    rocker_speed = a * crank_speed * np.sin(beta - theta) / (c * den)
    return coupler_speed, rocker_speed


def seed003_accels(a, b, c, theta, beta, phi, crank_speed, crank_accel, coupler_speed, rocker_speed):
    """(coupler_accel, rocker_accel) from seed 003's alpha formulas (section 3.3).

    Second derivative of the loop (w = speed, al = acceleration):
    a(al_a + i w_a^2) e^{i theta} + b(al_b + i w_b^2) e^{i beta} = c(al_c + i w_c^2) e^{i phi}.
    Times e^{-i phi}, imaginary part (al_c drops out):
    al_b = [a al_a sin(phi-theta) - a w_a^2 cos(phi-theta) - b w_b^2 cos(phi-beta) + c w_c^2]
           / (b sin(beta-phi)).
    Times e^{-i beta}, imaginary part (al_b drops out):
    al_c = [a al_a sin(beta-theta) - a w_a^2 cos(beta-theta) - b w_b^2 + c w_c^2 cos(beta-phi)]
           / (c sin(beta-phi)).
    MISPRINT: the paper prints both formulas with the label alpha_b; the second one (the
    one over c sin(beta - phi)) is alpha_c. Their right-hand sides are otherwise right, and
    agree with the C program's ``accb``/``accc`` once its parentheses are balanced.
    """
    wa2, wb2, wc2 = crank_speed**2, coupler_speed**2, rocker_speed**2
    den = np.sin(beta - phi)
    coupler_accel = (a * crank_accel * np.sin(phi - theta) - a * wa2 * np.cos(phi - theta)
                     - b * wb2 * np.cos(phi - beta) + c * wc2) / (b * den)
    rocker_accel = (a * crank_accel * np.sin(beta - theta) - a * wa2 * np.cos(beta - theta)
                    - b * wb2 + c * wc2 * np.cos(beta - phi)) / (c * den)
    return coupler_accel, rocker_accel


# Seed 003's table (section 5.1): a=20, b=66, c=56, d=80 mm, 10.5 rad/s, no crank
# acceleration. Transcribed exactly, printed column order:
#   thet (deg), vela, acca, phi, beta, velc, velb, Accc, Accb.
# Column meaning, found by comparison with mp_fourbar (see tests): the column labels are
# right and the paper's "O/P variables" list is not (it calls velc the speed of AB and velb
# the speed of CD; it also gives vela and acca in m/s and m/s^2, for rad/s and rad/s^2).
# In each pair the first row is branch -1 and the second is branch +1. Row 3 prints phi
# with three decimals, 103.821 (exact 103.8208): right, only the format differs.
SEED003_COLUMNS = ("theta_deg", "crank_speed", "crank_accel", "rocker_angle_deg",
                   "coupler_angle_deg", "rocker_speed", "coupler_speed", "rocker_accel",
                   "coupler_accel")
SEED003_TABLE = (
    (0, 10.5, 0.00, -110.74, -52.51, -3.50, -3.50, -37.58, 18.56),
    (0, 10.5, 0.00, 110.74, 52.51, -3.50, -3.50, 37.58, -18.56),
    (40, 10.5, 0.00, -126.30, -61.47, -4.06, -0.83, 15.50, 50.99),
    (40, 10.5, 0.00, 103.821, 38.99, 0.07, -3.15, 56.46, 20.96),
    (80, 10.5, 0.00, -139.02, -58.74, -2.51, 2.03, 26.17, 31.04),
    (80, 10.5, 0.00, 110.16, 29.87, 2.92, -1.62, 27.30, 22.42),
    (120, 10.5, 0.00, -145.28, -48.22, -0.77, 3.26, 26.64, 4.54),
    (120, 10.5, 0.00, 123.49, 26.44, 3.77, -0.20, -0.66, 21.44),
    (160, 10.5, 0.00, -144.69, -36.44, 1.12, 2.75, 29.94, -16.40),
    (160, 10.5, 0.00, 136.77, 28.52, 2.96, 1.32, -22.41, 23.99),
    (200, 10.5, 0.00, -136.77, -28.52, 2.96, 1.32, 22.41, -23.99),
    (200, 10.5, 0.00, 144.69, 36.44, 1.12, 2.75, -29.94, 16.40),
    (240, 10.5, 0.00, -123.49, -26.44, 3.77, -0.20, 0.66, -21.44),
    (240, 10.5, 0.00, 145.28, 48.22, -0.77, 3.20, -26.64, -4.54),
    (280, 10.5, 0.00, -110.16, -29.87, 2.92, -1.62, -27.30, 22.42),
    (280, 10.5, 0.00, 139.02, 58.74, -2.51, 2.03, -26.17, -31.04),
    (320, 10.5, 0.00, -103.82, -38.99, 0.07, -3.15, -56.46, -20.96),
    (320, 10.5, 0.00, 126.30, 61.47, -4.06, -0.83, -15.50, -50.99),
)
SEED003_LINKAGE = dict(a=20.0, b=66.0, c=56.0, d=80.0)
SEED003_BRANCHES = tuple(-1 if i % 2 == 0 else 1 for i in range(len(SEED003_TABLE)))
# (row index, column index, printed, correct to 2 decimals): entries further than 0.01
# from the exact value. Row 13 (240 deg, +1) prints the right coupler speed, 3.20, that
# row 6 misprints; rows 9 and 10 are mirror images and both misprint 23.93 as 23.99.
SEED003_MISPRINTS = (
    (6, 6, 3.26, 3.20),      # 120 deg, branch -1, coupler speed (exact 3.1952)
    (9, 8, 23.99, 23.93),    # 160 deg, branch +1, coupler accel (exact 23.9330)
    (10, 8, -23.99, -23.93),  # 200 deg, branch -1, coupler accel (exact -23.9330)
    (14, 8, 22.42, -22.42),  # 280 deg, branch -1, coupler accel: sign (exact -22.4192)
)
# Worked example 4.1 (theta = 40 deg) has more MISPRINTS: it substitutes -B as "-1439.84"
# (right: +1439.84) and 2A as "2 * -2057.76" (A = -2057.70), and its answer
# "-113.27 deg OR 120 deg" is wrong: the roots are -126.30 deg (branch -1, "+" root) and
# 103.82 deg (branch +1, "-" root), as in its own table.


# --------------------------------------------------------------------------------------
# Seed 002: the "imaginary line" L5
# --------------------------------------------------------------------------------------

def seed002_positions(L1, L2, L3, L4, theta1, theta2):
    """(theta5, L5, theta3, theta4, gamma34) by seed 002 section 2.1, corrected.

    Mapping: seed 002 (L2, L3, L4, L1, theta2, theta3) = ours (a, b, c, d, theta, beta).
    Its loop is L2 + L3 + L4 = L1 (the path A -> B -> C -> D equals the ground A -> D),
    so its ground angle theta1 is the direction of A -> D (0 in our frame) and its rocker
    vector points from C to D: theta4 = phi + pi. Only this reading makes its transmission
    angle gamma34 = theta4 - theta3 - 180 deg = phi - beta the interior angle at C (the
    paper's 50.28..90.38 deg). Then L5 e^{i theta5} = L1 e^{i theta1} - L2 e^{i theta2} is
    the vector B -> D, and theta3 = theta5 + acos(...) turns the coupler counter-clockwise
    from B -> D: the printed +acos is branch +1 (C left of B -> D), the only one it gives.

    Fixes to the printed formulas:
    * theta5 = tan^-1(y / x) is only right when x = L1 cos(theta1) - L2 cos(theta2) > 0
      (always so for theta1 = 0 and L1 > L2); atan2(y, x) is used.
    * L5 = y / sin(theta5) is 0/0 when B lies on the ground line; hypot(x, y) is used.
    * MISPRINT theta4: printed acos[(-L5 cos(theta5) - L3 cos(theta3)) / L4]; from
      L4 e^{i theta4} = L5 e^{i theta5} - L3 e^{i theta3} the right cosine is
      (L5 cos(theta5) - L3 cos(theta3)) / L4, and acos loses the sign of sin(theta4), so
      theta4 = atan2(L5 sin(theta5) - L3 sin(theta3), L5 cos(theta5) - L3 cos(theta3)).
    * gamma34 = theta4 - theta3 - 180 deg needs wrapping to (-180, 180]; wrapped, it is in
      [0, 180] on this branch (on branch -1 it would be the negative of the angle).
    Angles are returned wrapped to (-pi, pi]; NaN where the loop cannot close.
    """
    x = L1 * np.cos(theta1) - L2 * np.cos(theta2)
    y = L1 * np.sin(theta1) - L2 * np.sin(theta2)
    theta5 = np.arctan2(y, x)
    L5 = np.hypot(x, y)
    with np.errstate(invalid="ignore"):
        theta3 = theta5 + np.arccos((L3**2 + L5**2 - L4**2) / (2 * L3 * L5))
    theta4 = np.arctan2(L5 * np.sin(theta5) - L3 * np.sin(theta3),
                        L5 * np.cos(theta5) - L3 * np.cos(theta3))
    gamma34 = _wrap(theta4 - theta3 - np.pi)
    return theta5, L5, _wrap(theta3), theta4, gamma34


def transmission_angle(beta, phi):
    """Interior angle at C between coupler and rocker, in [0, pi]: |wrap(phi - beta)|.

    At C the coupler points back to B (beta + pi) and the rocker to D (phi + pi).
    """
    return np.abs(_wrap(np.asarray(phi) - np.asarray(beta)))


# --------------------------------------------------------------------------------------
# Seed 000: the four cases of z1 + z2 + z3 + z4 = 0, z_n = R_n e^{i t_n}
# --------------------------------------------------------------------------------------

def seed000_case1(R1, t1, R2, t2, t3, t4):
    """(R3, R4), two unknown lengths, eq. 2 (right as printed).

    The lengths are signed: a negative value means that link points along t + pi.
    """
    X = R1 * np.cos(t1) + R2 * np.cos(t2)
    Y = R1 * np.sin(t1) + R2 * np.sin(t2)
    k = -1 / np.sin(t4 - t3)
    return k * (np.sin(t4) * X - np.cos(t4) * Y), k * (-np.sin(t3) * X + np.cos(t3) * Y)


def seed000_case2a(R1, t1, R2, t2, R4, t4):
    """(R3, t3), unknown length and angle of the same link, eq. 3: z3 = -(z1 + z2 + z4)."""
    z3 = -(R1 * np.exp(1j * t1) + R2 * np.exp(1j * t2) + R4 * np.exp(1j * t4))
    return np.abs(z3), np.angle(z3)


def seed000_case2b(R1, t1, R2, t2, R3, t4):
    """[(R4, t3), (R4, t3)], unknown length R4 and angle t3 of different links, eq. 4-6.

    Times e^{-i t4}, the loop's imaginary part is eq. 6, q = sin(t3 - t4) =
    (-R1 sin(t1-t4) - R2 sin(t2-t4)) / R3 (eq. 5 writes "sen", Spanish for sin), and its
    real part is R4 = -R1 cos(t1-t4) - R2 cos(t2-t4) - R3 cos(t3-t4), where
    cos(t3-t4) = +-sqrt(1-q^2). With R3 = -(R1 sin(t1-t4) + R2 sin(t2-t4)) / q this is
    R4 = -R1 cos(t1-t4) - R2 cos(t2-t4) +- sqrt(1-q^2)/q [R1 sin(t1-t4) + R2 sin(t2-t4)].
    MISPRINT eq. 4: the bracket is printed [R1 sin(t1-t4) - R2 sin(t2-t4)]; the sign
    before R2 must be +. The "+" of eq. 4 is the solution with cos(t3 - t4) > 0. The form
    with R3 cos(t3 - t4) is used here: it equals eq. 4 and has no 0/0 at q = 0. q is known
    from the data (eq. 6), it is not a free parameter; |q| > 1 means no solution (NaN).
    R4 is signed (negative: z4 points along t4 + pi).
    """
    q = (-R1 * np.sin(t1 - t4) - R2 * np.sin(t2 - t4)) / R3
    with np.errstate(invalid="ignore"):
        root = np.sqrt(1 - q * q)
    base = -R1 * np.cos(t1 - t4) - R2 * np.cos(t2 - t4)
    return [(base - R3 * s * root, _wrap(t4 + np.arctan2(q, s * root))) for s in (1, -1)]


def seed000_case3(R1, t1, R2, t2, R3, R4):
    """[(t3, t4), (t3, t4)], two unknown angles, eq. 7-8 then eq. 9-10 (right as printed).

    z_T = R_T e^{i t_T} = z1 + z2 (eq. 11); |z4|^2 = |z_T + z3|^2 gives
    cos(t3 - t_T) = (R4^2 - R_T^2 - R3^2) / (2 R_T R3), and likewise for t4; the imaginary
    part of the loop times e^{-i t_T} pairs +acos for t3 with -acos (the printed
    "2 pi - acos") for t4. Angles wrapped to (-pi, pi]; NaN where the loop cannot close.
    Our four-bar in this loop (seed 000's t1 = pi): z1 = d e^{i pi} (D -> A), z2 crank,
    z3 coupler (t3 = beta), z4 = c e^{i(phi + pi)} (C -> D); then eq. 9-10 give branch +1
    and eq. 7-8 branch -1.
    """
    zT = R1 * np.exp(1j * t1) + R2 * np.exp(1j * t2)
    RT, tT = np.abs(zT), np.angle(zT)
    with np.errstate(invalid="ignore"):
        g3 = np.arccos((R4**2 - RT**2 - R3**2) / (2 * RT * R3))
        g4 = np.arccos((R3**2 - RT**2 - R4**2) / (2 * RT * R4))
    return [(_wrap(tT + g3), _wrap(tT + 2 * np.pi - g4)),
            (_wrap(tT + 2 * np.pi - g3), _wrap(tT + g4))]


def fourbar_joint_c(theta, a, b, c, d, branch=1):
    """The four-bar's joint C by hand, in double precision: where the circles about B (radius b) and D (radius c)
    meet, left of the directed line B -> D on branch +1 (right on -1); None where they do not meet."""
    bx, by = math.cos(theta) * a, math.sin(theta) * a
    dx, dy = d - bx, -by
    span = math.hypot(dx, dy)
    along = (b * b - c * c + span * span) / (2 * span)
    if b * b - along * along < 0:
        return None
    across = branch * math.sqrt(b * b - along * along)
    return bx + (along * dx - across * dy) / span, by + (along * dy + across * dx) / span


# --------------------------------------------------------------------------------------
# 50-digit mpmath references
# --------------------------------------------------------------------------------------

def _mp_check(lengths, branch):
    for name, value in lengths.items():
        if not (mp.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a positive finite length, got {value}")
    if branch not in (1, -1):
        raise ValueError(f"branch must be +1 or -1, got {branch}")


def _mp_solve2(M, rhs):
    """Solve the 2x2 system M x = rhs; ValueError where it is singular (a toggle)."""
    try:
        x = mp.lu_solve(mp.matrix(M), mp.matrix(rhs))
    except ZeroDivisionError:
        raise ValueError("velocity system is singular (toggle position)") from None
    return x[0], x[1]


def mp_fourbar(a, b, c, d, theta, branch, crank_speed=0, crank_accel=0):
    """Four-bar at 50 digits: dict of beta, phi, beta_speed, phi_speed, beta_accel, phi_accel.

    Position: C is an intersection of the circle of radius b about B = a e^{i theta} with
    the circle of radius c about D = (d, 0); of the two, the one whose cross product
    (D - B) x (C - B) has the sign of ``branch`` is taken. Rates: with the loop's
    components x: a cos(theta) + b cos(beta) - d - c cos(phi) = 0 and
    y: a sin(theta) + b sin(beta) - c sin(phi) = 0 differentiated once and twice,
        [-b sin(beta)   c sin(phi)] [w_b]   [a w sin(theta)]
        [ b cos(beta)  -c cos(phi)] [w_c] = [-a w cos(theta)],
    and the same matrix times [al_b, al_c] equals
        [a w^2 cos(theta) + a al sin(theta) + b w_b^2 cos(beta) - c w_c^2 cos(phi),
         a w^2 sin(theta) - a al cos(theta) + b w_b^2 sin(beta) - c w_c^2 sin(phi)].
    Inputs may be floats (taken exactly) or mpf. Raises ValueError if the linkage cannot
    be assembled at theta (or the rate system is exactly singular, at a toggle).
    """
    with mp.workdps(_MP_DPS):
        a, b, c, d = (mp.mpf(v) for v in (a, b, c, d))
        theta, w, al = mp.mpf(theta), mp.mpf(crank_speed), mp.mpf(crank_accel)
        _mp_check(dict(a=a, b=b, c=c, d=d), branch)
        bx, by = a * mp.cos(theta), a * mp.sin(theta)
        ex, ey = d - bx, -by  # B -> D
        L = mp.sqrt(ex * ex + ey * ey)
        if L == 0:
            raise ValueError("B coincides with D: the coupler direction is undefined")
        along = (b * b - c * c + L * L) / (2 * L)  # distance from B to the foot of C on BD
        h2 = b * b - along * along
        if h2 < 0:
            raise ValueError(f"the four-bar cannot be assembled at theta={mp.nstr(theta, 8)}")
        h = mp.sqrt(h2)
        fx, fy = bx + along * ex / L, by + along * ey / L
        candidates = [(fx - s * h * ey / L, fy + s * h * ex / L) for s in (1, -1)]
        cx, cy = max(candidates, key=lambda p: branch * (ex * (p[1] - by) - ey * (p[0] - bx)))
        beta, phi = mp.atan2(cy - by, cx - bx), mp.atan2(cy, cx - d)
        M = [[-b * mp.sin(beta), c * mp.sin(phi)], [b * mp.cos(beta), -c * mp.cos(phi)]]
        wb, wc = _mp_solve2(M, [a * w * mp.sin(theta), -a * w * mp.cos(theta)])
        ab, ac = _mp_solve2(M, [
            a * w**2 * mp.cos(theta) + a * al * mp.sin(theta)
            + b * wb**2 * mp.cos(beta) - c * wc**2 * mp.cos(phi),
            a * w**2 * mp.sin(theta) - a * al * mp.cos(theta)
            + b * wb**2 * mp.sin(beta) - c * wc**2 * mp.sin(phi),
        ])
        return dict(beta=beta, phi=phi, beta_speed=wb, phi_speed=wc, beta_accel=ab, phi_accel=ac)


def mp_slider_crank(a, b, offset, theta, branch, crank_speed=0, crank_accel=0):
    """Slider-crank a e^{i theta} + b e^{i beta} = s + i offset at 50 digits.

    Returns a dict of beta, s, beta_speed, s_speed, beta_accel, s_accel. Position: the
    slider pin C = (s, offset) is where the circle of radius b about B = a e^{i theta}
    meets the line y = offset, s = a cos(theta) + branch sqrt(b^2 - (offset - a sin(theta))^2)
    (branch +1: the larger s). Rates from the differentiated x/y equations,
        [-b sin(beta)  -1] [w_b]   [ a w sin(theta)]
        [ b cos(beta)   0] [s' ] = [-a w cos(theta)],
    and the same matrix times [al_b, s''] equals
        [a w^2 cos(theta) + a al sin(theta) + b w_b^2 cos(beta),
         a w^2 sin(theta) - a al cos(theta) + b w_b^2 sin(beta)].
    Raises ValueError if it cannot be assembled (or the rate system is exactly singular,
    cos(beta) = 0).
    """
    with mp.workdps(_MP_DPS):
        a, b, e = mp.mpf(a), mp.mpf(b), mp.mpf(offset)
        theta, w, al = mp.mpf(theta), mp.mpf(crank_speed), mp.mpf(crank_accel)
        _mp_check(dict(a=a, b=b), branch)
        if not mp.isfinite(e):
            raise ValueError(f"offset must be finite, got {e}")
        bx, by = a * mp.cos(theta), a * mp.sin(theta)
        h2 = b * b - (e - by) ** 2
        if h2 < 0:
            raise ValueError(f"the slider-crank cannot be assembled at theta={mp.nstr(theta, 8)}")
        s = bx + branch * mp.sqrt(h2)
        beta = mp.atan2(e - by, s - bx)
        M = [[-b * mp.sin(beta), -1], [b * mp.cos(beta), 0]]
        wb, ds = _mp_solve2(M, [a * w * mp.sin(theta), -a * w * mp.cos(theta)])
        ab, dds = _mp_solve2(M, [
            a * w**2 * mp.cos(theta) + a * al * mp.sin(theta) + b * wb**2 * mp.cos(beta),
            a * w**2 * mp.sin(theta) - a * al * mp.cos(theta) + b * wb**2 * mp.sin(beta),
        ])
        return dict(beta=beta, s=s, beta_speed=wb, s_speed=ds, beta_accel=ab, s_accel=dds)
