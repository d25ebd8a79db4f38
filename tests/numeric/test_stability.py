"""Stress tests of numerical stability: the generated solvers against 50-digit mpmath.

Property-based (Hypothesis, derandomized so that CI is reproducible) over link
lengths from 1e-6 to 1e6 in scale with ratios up to 1e4 inside one linkage,
every Grashof class, and crank angles drawn near the places where closed forms
go wrong: the toggles (coupler and rocker in line, ``|BD| = b + c`` or
``|b - c|``, computed here in mpmath), within 1e-12 to 1e-3 rad on either
side; the crank folded over and extended along the frame (theta = 0, pi); the
crank and coupler in line (``|AC| = a + b`` or ``|a - b|``, the rocker's limit
positions); and where the half-angle formula's leading coefficient vanishes
(seed 003's ``A = K - a (d - c) cos(theta) - c d = 0``, the rocker at 180 deg).

**The error bound.**  Let ``w = |BD|`` be the diagonal, ``mu`` the
transmission angle (the triangle B, C, D has sides b, c, w and
``sin(mu) = Delta / (2 b c)`` with Heron's
``Delta^2 = (b + c + w)(b + c - w)(w + b - c)(w - b + c)``),
``P = a + b + c + d`` the perimeter and ``eps = 2.2e-16``.  The computed angles
satisfy::

    |beta - beta_exact| <= K eps (P / w + P / (b |sin mu|))
    |phi  - phi_exact | <= K eps (P / w + P / (c |sin mu|)),   K = 4.

Derivation.  Every step of the solver is a rounded operation on sums of link
lengths (Heron's factored product keeps the triangle's defect exact up to the
rounding of ``w``), so the result is the exact one for data moved by a few
ulps of ``P``.  Moving the data by ``eps P`` moves the vector B -> D by about
``eps P``, which turns its direction by ``eps P / w``; it also changes the
triangle's sides b, c, w by about ``eps P``.  Differentiating the law of
cosines and using the law of sines (``b w sin(psi_B) = b c sin(mu)``), the
angle ``psi_B`` at B changes by ``dw cos(psi_D) / (b sin mu)``,
``db cos(mu) / (b sin mu)`` and ``dc / (b sin mu)``: at most
``eps P / (b sin mu)`` each; likewise at D with c.  The coupler angle is the
direction of B -> D plus ``psi_B``, the rocker's the same direction plus
``pi - psi_D``.  K = 4 covers the few ulps (measured: at most 1.14 in 55,000
draws; see the README's accuracy section, made by running this file).

Near a toggle ``sin(mu)`` vanishes like the square root of the triangle's
defect ``delta`` (``b + c - w`` at the extended toggle, ``w - |b - c|`` at the
folded one): Heron gives ``sin(mu) ~ sqrt(2 w_t delta / (b c))`` with
``w_t = b + c`` or ``|b - c|``, and ``delta ~ (a d |sin(theta_t)| / w_t)
|theta - theta_t|`` grows linearly with the crank's distance to the toggle
``theta_t``.  So the bound, and the error, grow like
``eps / sqrt(|theta - theta_t|)``: up to about 1e-9 rad at 1e-12 rad from a
toggle of a linkage with link ratios up to 3, 4e-14 at 1e-3 (measured).  That is the conditioning of
the problem (the data's own rounding moves the exact answer that much), not a
weakness of the formulas: the half-angle form of seed 003 is worse, see the
README.

**The loop still closes** to 1e-12 of the longest link even where the angles
are off by the bound above: the error lies along the motion the linkage
nearly has at a toggle, where the coupler and rocker turn together.

**Outside the reachable range** the solvers report ``assembled`` False and NaN.
Within ``TOLERANCE`` (1e-14) times the loop's size of a toggle
(``a + b + c + d + w``, the size of the rounding in the triangle's defect)
the input is taken as at the toggle: the result is the toggle position (to
rounding, ``singular`` True where the root comes out zero) and closes the loop.

**Singular configurations.**  The rates divide by the loop's root
(``sin(beta - phi) = -branch Delta / (2 b c)``), so where the root is zero
(the toggle, to within rounding) the generated code returns ``singular`` True
and speeds and accelerations that are not finite (inf or NaN): that is how
the API says "singular".  Everywhere else in the reachable range they are
finite.  Where the angles are well conditioned (``kappa``, the larger of the
bound's two factors, at most 100) the speeds are within
``K eps kappa^2`` of the reference relative to ``max(|speed|, crank speed)``,
and the accelerations relative to ``max(|accel|, w^2 + |al|)``: they divide
by ``sin(mu)``, whose relative rounding error is about ``eps P / delta``,
i.e. ``eps kappa^2``.  Nearer a toggle that error grows like
``1 / |theta - theta_t|`` (faster for the accelerations), and within rounding
of one (a toggle at a change point, where the exact rates stay bounded) only
their finiteness is promised.

Run ``python tests/test_stability.py`` to print the tables of the README's
accuracy section.
"""
from __future__ import annotations

import functools
import importlib.util
import math
import pathlib

import mpmath as mp
import numpy
import pytest
from hypothesis import HealthCheck, assume, given, settings, strategies as st

from references import mp_fourbar, mp_slider_crank, seed002_positions, seed003_positions
from symlink.mechanism import catalog
from symlink.numeric.solver import Solver

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
EPS = float(numpy.finfo(float).eps)
#: The constant of the stated error bound (module docstring).
K = 4.0
#: Well conditioned: P/w + P/(min(b, c) sin mu) at most this; angle errors within 1e-13 rad there.
WELL_CONDITIONED = 100.0
#: The generated code's rounding tolerance at a toggle (symlink.symbolic.position.TOLERANCE, restated).
TOLERANCE = 1e-14
CRANK_SPEED, CRANK_ACCEL = 1.7, -0.6

STRESS = settings(max_examples=300, deadline=None, derandomize=True, database=None,
                  suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


def _load_generated(name: str):
    spec = importlib.util.spec_from_file_location(f"generated_{name}", ROOT / "generated" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


generated = _load_generated("fourbar")


def solve_fourbar(theta, a, b, c, d, branch) -> dict:
    """The generated solver's every output, as Python floats and bools."""
    with numpy.errstate(divide="ignore", invalid="ignore"):
        result = generated.accelerations(theta, a, b, c, d, branch, CRANK_SPEED, CRANK_ACCEL)
    return {k: (bool(v) if v.dtype == bool else float(v)) for k, v in result.items()}


def angle_error(x: float, exact) -> float:
    """|x - exact| modulo 2 pi, at 50 digits."""
    with mp.workdps(50):
        difference = mp.mpf(x) - exact
        return float(abs(difference - 2 * mp.pi * mp.nint(difference / (2 * mp.pi))))


# --- exact geometry of the four-bar, in mpmath ----------------------------------------

def fourbar_geometry(a, b, c, d, theta) -> dict:
    """Diagonal w = |BD|, the triangle's defect (negative: cannot close), sin(mu), at 50 digits."""
    with mp.workdps(50):
        a, b, c, d, theta = (mp.mpf(v) for v in (a, b, c, d, theta))
        # |BD|^2 = (a - d)^2 + 4 a d sin^2(theta/2): no cancellation even at 50 digits.
        w = mp.sqrt((a - d) ** 2 + 4 * a * d * mp.sin(theta / 2) ** 2)
        defect = min(b + c - w, w - abs(b - c))
        heron = (b + c + w) * (b + c - w) * (w + b - c) * (w - b + c)
        sin_mu = mp.sqrt(heron) / (2 * b * c) if heron > 0 else mp.mpf(0)
        return dict(w=w, defect=defect, sin_mu=sin_mu, size=a + b + c + d + w, perimeter=a + b + c + d)


def error_bounds(a, b, c, d, geometry) -> tuple[float, float]:
    """The stated bound's factors (P/w + P/(b sin mu), P/w + P/(c sin mu)) for coupler and rocker."""
    with mp.workdps(50):
        L, w, s = geometry["perimeter"], geometry["w"], geometry["sin_mu"]
        if s == 0 or w == 0:
            return math.inf, math.inf
        return float(L / w + L / (b * s)), float(L / w + L / (c * s))


def rate_errors(got: dict, exact: dict) -> list[float]:
    """Errors of the speeds relative to max(|speed|, crank speed), of the accelerations to max(|accel|, w^2 + |al|)."""
    floors = (abs(CRANK_SPEED),) * 2 + (CRANK_SPEED**2 + abs(CRANK_ACCEL),) * 2
    pairs = (("coupler_speed", "beta_speed"), ("rocker_speed", "phi_speed"),
             ("coupler_accel", "beta_accel"), ("rocker_accel", "phi_accel"))
    return [float(abs(got[k] - exact[r]) / max(abs(exact[r]), floor)) for (k, r), floor in zip(pairs, floors)]


def closure_residual(a, b, c, d, theta, beta, phi) -> float:
    """|a e^{i theta} + b e^{i beta} - d - c e^{i phi}| / (longest link), at 50 digits."""
    with mp.workdps(50):
        a, b, c, d, theta, beta, phi = (mp.mpf(v) for v in (a, b, c, d, theta, beta, phi))
        gap = a * mp.expj(theta) + b * mp.expj(beta) - d - c * mp.expj(phi)
        return float(abs(gap) / max(a, b, c, d))


def toggle_angles(a, b, c, d) -> dict[str, list]:
    """Crank angles (mpf) of the special configurations that exist for these lengths.

    ``extended``/``folded`` toggles: |BD| = b + c or |b - c|, i.e.
    ``cos(theta) = (a^2 + d^2 - (b +- c)^2) / (2 a d)``; ``crank-coupler``:
    |AC| = a + b or |a - b| with C on the rocker's circle,
    ``cos(theta) = (e^2 + d^2 - c^2) / (2 e d)`` for e = a + b, a - b;
    ``half-angle A = 0``: ``cos(theta) = (K - c d) / (a (d - c))`` with
    ``K = (a^2 - b^2 + c^2 + d^2) / 2`` (seed 003).
    """
    with mp.workdps(50):
        a, b, c, d = (mp.mpf(v) for v in (a, b, c, d))
        cosines = {
            "extended toggle": [(a * a + d * d - (b + c) ** 2) / (2 * a * d)],
            "folded toggle": [(a * a + d * d - (b - c) ** 2) / (2 * a * d)],
            "crank-coupler": [(e * e + d * d - c * c) / (2 * e * d) for e in (a + b, a - b) if e != 0],
            "half-angle A = 0": [((a * a - b * b + c * c + d * d) / 2 - c * d) / (a * (d - c))] if d != c else [],
        }
        return {kind: [s * mp.acos(x) for x in values if abs(x) <= 1 for s in (1, -1)]
                for kind, values in cosines.items()}


# --- strategies ----------------------------------------------------------------------

GRASHOF_CLASSES = ("crank-rocker", "double-crank", "double-rocker", "rocker-crank", "change-point",
                   "triple-rocker")
SHORTEST_LINK = {"crank-rocker": 0, "double-crank": 3, "double-rocker": 1, "rocker-crank": 2}


@st.composite
def fourbars(draw, classes=GRASHOF_CLASSES):
    """(a, b, c, d, class): lengths from 1e-6 to 1e6 in scale, ratios up to 1e4, a given Grashof class.

    With s <= p <= q <= l the sorted lengths: Grashof is s + l < p + q (the
    shortest link's position names the class), change point s + l = p + q
    (exact: small integers times a power of two), triple rocker s + l > p + q.
    """
    kind = draw(st.sampled_from(classes))
    if kind == "change-point":
        s, p, q = sorted(draw(st.lists(st.integers(1, 1000), min_size=3, max_size=3)))
        links = [s, p, q, p + q - s]
        scale = 2.0 ** draw(st.integers(-20, 20))
    else:
        s, p, q = sorted(10 ** draw(st.floats(-2, 2)) for _ in range(3))
        fraction = draw(st.floats(0.001, 0.999))
        longest = q + fraction * (p - s) if kind != "triple-rocker" else p + q - s + 2 * fraction * s
        links = [s, p, q, longest]
        scale = 10 ** draw(st.floats(-6, 6))
    shortest, others = links[0], draw(st.permutations(links[1:]))
    position = SHORTEST_LINK.get(kind, draw(st.integers(0, 3)))
    a, b, c, d = (float(v * scale) for v in others[:position] + [shortest] + others[position:])
    return a, b, c, d, kind


#: Crank angles anywhere: 0, or at least 1e-12 rad from it (nearer, B is within 1e-12 of the
#: frame line and a rhombus's B within 1e-12 of D, where products of such distances underflow).
ANY_CRANK_ANGLE = st.one_of(st.just(0.0), st.floats(1e-12, math.pi), st.floats(-math.pi, -1e-12))
PLACES = ("extended toggle", "folded toggle", "crank-frame", "crank-coupler", "half-angle A = 0", "anywhere")


def crank_angle(draw, a, b, c, d, place: str, outside: bool | None = None) -> float:
    """A crank angle near ``place``: within 1e-12 to 1e-3 rad of it, on either side.

    ``outside`` True/False asks for the side where the linkage cannot/can be
    assembled (only meaningful at a toggle); places that these lengths do not
    have fall back to a uniform angle.
    """
    if place == "crank-frame":
        centre = draw(st.sampled_from((0.0, math.pi)))
        if draw(st.booleans()):
            return centre
        return float(centre + draw(st.sampled_from((-1, 1))) * 10 ** draw(st.floats(-12, -3)))
    centres = toggle_angles(a, b, c, d).get(place, [])
    if not centres:
        return draw(ANY_CRANK_ANGLE)
    centre = draw(st.sampled_from(centres))
    distance, side = 10 ** draw(st.floats(-12, -3)), draw(st.sampled_from((-1, 1)))
    with mp.workdps(50):
        theta = float(centre + side * mp.mpf(distance))
        if outside is not None and (fourbar_geometry(a, b, c, d, theta)["defect"] < 0) != outside:
            theta = float(centre - side * mp.mpf(distance))
    return theta


# --- four-bar properties -------------------------------------------------------------

@STRESS
@given(data=st.data(), linkage=fourbars(), place=st.sampled_from(PLACES))
def test_fourbar_inside_the_reachable_range(data, linkage, place):
    """Finite, closing, within the stated bound of the 50-digit reference; rates finite unless singular."""
    a, b, c, d, _ = linkage
    theta = crank_angle(data.draw, a, b, c, d, place, outside=False)
    geometry = fourbar_geometry(a, b, c, d, theta)
    assume(geometry["defect"] >= 0 and geometry["w"] > 0)
    bound_beta, bound_phi = error_bounds(a, b, c, d, geometry)
    for branch in (1, -1):
        got = solve_fourbar(theta, a, b, c, d, branch)
        assert got["assembled"], (a, b, c, d, theta, branch)
        assert math.isfinite(got["coupler"]) and math.isfinite(got["rocker"])
        assert closure_residual(a, b, c, d, theta, got["coupler"], got["rocker"]) < 1e-12
        if geometry["sin_mu"] > 0:  # else exactly at a toggle: the rates' reference does not exist
            exact = mp_fourbar(a, b, c, d, theta, branch, CRANK_SPEED, CRANK_ACCEL)
            beta_error = angle_error(got["coupler"], exact["beta"])
            phi_error = angle_error(got["rocker"], exact["phi"])
            assert beta_error <= K * EPS * bound_beta and phi_error <= K * EPS * bound_phi
            if max(bound_beta, bound_phi) <= WELL_CONDITIONED:
                assert max(beta_error, phi_error) < 1e-13
                assert max(rate_errors(got, exact)) <= K * EPS * max(bound_beta, bound_phi) ** 2
        rates = [got[k] for k in ("coupler_speed", "rocker_speed", "coupler_accel", "rocker_accel")]
        if got["singular"]:  # the root is zero: only at a toggle, to within rounding
            assert geometry["defect"] <= 2 * TOLERANCE * geometry["size"]
            assert not any(map(math.isfinite, rates[:2]))
        else:
            assert all(map(math.isfinite, rates))


@STRESS
@given(data=st.data(), linkage=fourbars(("double-rocker", "triple-rocker", "change-point", "rocker-crank")),
       place=st.sampled_from(("extended toggle", "folded toggle", "anywhere")))
def test_fourbar_outside_the_reachable_range_is_reported_never_a_number(data, linkage, place):
    """Beyond rounding of a toggle: not assembled and NaN; within it, the toggle itself."""
    a, b, c, d, _ = linkage
    theta = crank_angle(data.draw, a, b, c, d, place, outside=True)
    geometry = fourbar_geometry(a, b, c, d, theta)
    assume(geometry["defect"] < 0)
    for branch in (1, -1):
        got = solve_fourbar(theta, a, b, c, d, branch)
        if -geometry["defect"] > 2 * TOLERANCE * geometry["size"]:
            assert not got["assembled"], (a, b, c, d, theta, branch)
            assert all(math.isnan(v) for k, v in got.items() if k not in ("assembled", "singular"))
            assert not got["singular"]
        elif got["assembled"]:  # within rounding of the toggle: a position that closes the loop
            assert closure_residual(a, b, c, d, theta, got["coupler"], got["rocker"]) < 1e-12


@STRESS
@given(data=st.data(), linkage=fourbars(), place=st.sampled_from(PLACES), power=st.integers(-40, 40))
def test_fourbar_scaling_by_a_power_of_two_changes_no_bit(data, linkage, place, power):
    """Every operation is homogeneous in the lengths: a power-of-two factor is exact, so is the result."""
    a, b, c, d, _ = linkage
    theta = crank_angle(data.draw, a, b, c, d, place)
    factor = 2.0**power
    for branch in (1, -1):
        got = solve_fourbar(theta, a, b, c, d, branch)
        scaled = solve_fourbar(theta, a * factor, b * factor, c * factor, d * factor, branch)
        assert scaled.keys() == got.keys()
        for key, value in got.items():
            assert scaled[key] == value or (math.isnan(scaled[key]) and math.isnan(value)), key


@settings(STRESS, max_examples=100)
@given(linkage=fourbars(), thetas=st.lists(st.floats(-math.pi, math.pi), min_size=1, max_size=20))
def test_fourbar_a_sweep_and_single_calls_give_the_same_bits(linkage, thetas):
    """Array and scalar evaluation take the same path (x*x, not pow(x, 2.0), for squares)."""
    a, b, c, d, _ = linkage
    with numpy.errstate(divide="ignore", invalid="ignore"):
        sweep = generated.accelerations(numpy.array(thetas), a, b, c, d, 1, CRANK_SPEED, CRANK_ACCEL)
    for i, theta in enumerate(thetas):
        single = solve_fourbar(theta, a, b, c, d, 1)
        for key, value in single.items():
            assert sweep[key][i] == value or (math.isnan(value) and math.isnan(sweep[key][i])), key

@STRESS
@given(data=st.data(), linkage=fourbars(), place=st.sampled_from(PLACES), exponent=st.floats(-6, 6))
def test_fourbar_scaling_by_any_factor_changes_the_angles_by_rounding_only(data, linkage, place, exponent):
    """Scaled lengths are rounded, so the angles move within the stated bound (twice, plus the data's rounding)."""
    a, b, c, d, _ = linkage
    theta = crank_angle(data.draw, a, b, c, d, place, outside=False)
    factor = 10**exponent
    geometry = fourbar_geometry(a, b, c, d, theta)
    assume(geometry["defect"] > 2 * TOLERANCE * geometry["size"])
    bound_beta, bound_phi = error_bounds(a, b, c, d, geometry)
    for branch in (1, -1):
        got = solve_fourbar(theta, a, b, c, d, branch)
        scaled = solve_fourbar(theta, a * factor, b * factor, c * factor, d * factor, branch)
        assert got["assembled"] and scaled["assembled"]
        assert angle_error(scaled["coupler"], mp.mpf(got["coupler"])) <= 3 * K * EPS * bound_beta
        assert angle_error(scaled["rocker"], mp.mpf(got["rocker"])) <= 3 * K * EPS * bound_phi


@STRESS
@given(links=st.lists(st.integers(1, 1000), min_size=3, max_size=3), power=st.integers(-20, 20),
       extended=st.booleans())
def test_fourbar_exactly_at_a_toggle_is_singular(links, power, extended):
    """Exact toggles (a + d = b + c at theta = pi, |a - d| = |b - c| at theta = 0): singular, speeds not finite."""
    a, d, b = links
    c = a + d - b if extended else b + abs(a - d)
    assume(c > 0 and a != d)
    theta = math.pi if extended else 0.0
    a, b, c, d = (v * 2.0**power for v in (a, b, c, d))
    for branch in (1, -1):
        got = solve_fourbar(theta, a, b, c, d, branch)
        assert got["assembled"] and got["singular"]
        assert closure_residual(a, b, c, d, theta, got["coupler"], got["rocker"]) < 1e-12
        assert not math.isfinite(got["coupler_speed"]) and not math.isfinite(got["rocker_speed"])
        assert not math.isfinite(got["coupler_accel"]) and not math.isfinite(got["rocker_accel"])


# --- slider-crank --------------------------------------------------------------------

SLIDER_OUTPUTS = ["conrod", "slider", "conrod_speed", "slider_speed", "conrod_accel", "slider_accel", "singular"]


@functools.cache
def slider_crank_solver():
    builder = getattr(catalog, "slider_crank", None)
    if builder is None:
        pytest.skip("symlink.mechanism.catalog has no slider-crank")
    return Solver(builder(), SLIDER_OUTPUTS)


def solve_slider_crank(theta, a, b, offset, branch) -> dict:
    result = slider_crank_solver()(theta=theta, a=a, b=b, offset=offset, branch=branch,
                                   thetadot=CRANK_SPEED, thetaddot=CRANK_ACCEL)
    return {k: (bool(v) if v.dtype == bool else float(v)) for k, v in result.items()}


def slider_geometry(a, b, offset, theta) -> dict:
    """Height h = offset - a sin(theta) of B under the guide, defect b - |h|, root b |cos(beta)|, at 50 digits."""
    with mp.workdps(50):
        a, b, offset, theta = (mp.mpf(v) for v in (a, b, offset, theta))
        h = offset - a * mp.sin(theta)
        defect = b - abs(h)
        return dict(defect=defect, root=mp.sqrt((b - h) * (b + h)) if defect > 0 else mp.mpf(0),
                    perimeter=a + b + abs(offset))


def slider_residual(a, b, offset, theta, beta, s) -> float:
    """|a e^{i theta} + b e^{i beta} - s - i offset| / max(a, b, |offset|), at 50 digits."""
    with mp.workdps(50):
        a, b, offset, theta, beta, s = (mp.mpf(v) for v in (a, b, offset, theta, beta, s))
        return float(abs(a * mp.expj(theta) + b * mp.expj(beta) - s - 1j * offset) / max(a, b, abs(offset)))


@st.composite
def slider_cranks(draw):
    """(a, b, offset): 1e-6 to 1e6 in scale, ratios up to 1e4, offset zero or of either sign."""
    scale = 10 ** draw(st.floats(-6, 6))
    a, b = (10 ** draw(st.floats(-2, 2)) * scale for _ in range(2))
    offset = draw(st.sampled_from((0, 1, -1))) * 10 ** draw(st.floats(-2, 2)) * scale
    return a, b, offset


SLIDER_PLACES = ("toggle", "crank-frame", "dead centre", "anywhere")


def slider_crank_angle(draw, a, b, offset, place: str, outside: bool | None = None) -> float:
    """Near a toggle (|offset - a sin(theta)| = b), theta = 0 or pi, or a dead centre (|AC| = a +- b)."""
    with mp.workdps(50):
        A, B, E = mp.mpf(a), mp.mpf(b), mp.mpf(offset)
        if place == "toggle":
            sines = [(E - s * B) / A for s in (1, -1)]
            centres = [t for x in sines if abs(x) <= 1 for t in (mp.asin(x), mp.pi - mp.asin(x))]
        elif place == "dead centre":
            reach = [r for r in (A + B, abs(A - B)) if r > abs(E)]
            centres = [mp.atan2(E, s * mp.sqrt(r * r - E * E)) for r in reach for s in (1, -1)]
        elif place == "crank-frame":
            centres = [mp.mpf(0), mp.pi]
        else:
            centres = []
        if not centres:
            return draw(ANY_CRANK_ANGLE)
        centre = draw(st.sampled_from(centres))
        distance, side = mp.mpf(10 ** draw(st.floats(-12, -3))), draw(st.sampled_from((-1, 1)))
        theta = float(centre + side * distance)
        if outside is not None and (slider_geometry(a, b, offset, theta)["defect"] < 0) != outside:
            theta = float(centre - side * distance)
        return theta


@settings(STRESS, max_examples=200)
@given(data=st.data(), linkage=slider_cranks(), place=st.sampled_from(SLIDER_PLACES))
def test_slider_crank_inside_the_reachable_range(data, linkage, place):
    """|beta error| <= K eps P / Delta, |s error| <= K eps P (1 + b / Delta), P = a + b + |offset|, Delta = b |cos beta|.

    The same derivation as the four-bar's: h = offset - a sin(theta) and the
    factor b - |h| carry a few ulps of P; sin(beta) = h / b turns that into
    d(beta) = dh / Delta, and s = a cos(theta) + branch Delta moves by
    h dh / Delta + b db / Delta.  Near a toggle Delta ~ sqrt(2 b (b - |h|)).
    """
    a, b, offset = linkage
    theta = slider_crank_angle(data.draw, a, b, offset, place, outside=False)
    geometry = slider_geometry(a, b, offset, theta)
    assume(geometry["defect"] > 0)
    with mp.workdps(50):
        P, root = geometry["perimeter"], geometry["root"]
        beta_bound, s_bound = float(K * EPS * P / root), float(K * EPS * P * (1 + b / root))
    for branch in (1, -1):
        got = solve_slider_crank(theta, a, b, offset, branch)
        assert got["assembled"] and math.isfinite(got["conrod"]) and math.isfinite(got["slider"])
        assert slider_residual(a, b, offset, theta, got["conrod"], got["slider"]) < 1e-12
        exact = mp_slider_crank(a, b, offset, theta, branch, CRANK_SPEED, CRANK_ACCEL)
        assert angle_error(got["conrod"], exact["beta"]) <= beta_bound
        assert abs(got["slider"] - exact["s"]) <= s_bound
        rates = [got[k] for k in ("conrod_speed", "slider_speed", "conrod_accel", "slider_accel")]
        if got["singular"]:
            assert geometry["defect"] <= 2 * TOLERANCE * P
            assert not math.isfinite(got["conrod_speed"])
        else:
            assert all(map(math.isfinite, rates))


@settings(STRESS, max_examples=200)
@given(data=st.data(), linkage=slider_cranks(), place=st.sampled_from(("toggle", "anywhere")))
def test_slider_crank_outside_the_reachable_range_is_reported_never_a_number(data, linkage, place):
    a, b, offset = linkage
    theta = slider_crank_angle(data.draw, a, b, offset, place, outside=True)
    geometry = slider_geometry(a, b, offset, theta)
    assume(geometry["defect"] < 0)
    for branch in (1, -1):
        got = solve_slider_crank(theta, a, b, offset, branch)
        if -geometry["defect"] > 2 * TOLERANCE * geometry["perimeter"]:
            assert not got["assembled"] and not got["singular"]
            assert all(math.isnan(v) for k, v in got.items() if k not in ("assembled", "singular"))
        elif got["assembled"]:
            assert slider_residual(a, b, offset, theta, got["conrod"], got["slider"]) < 1e-12


@settings(STRESS, max_examples=200)
@given(data=st.data(), linkage=slider_cranks(), place=st.sampled_from(SLIDER_PLACES), power=st.integers(-40, 40))
def test_slider_crank_scaling_by_a_power_of_two_changes_no_bit(data, linkage, place, power):
    a, b, offset = linkage
    theta = slider_crank_angle(data.draw, a, b, offset, place)
    factor = 2.0**power
    for branch in (1, -1):
        got = solve_slider_crank(theta, a, b, offset, branch)
        scaled = solve_slider_crank(theta, a * factor, b * factor, offset * factor, branch)
        for key, value in got.items():
            expected = value * factor if key in ("slider", "slider_speed", "slider_accel") else value
            assert scaled[key] == expected or (math.isnan(scaled[key]) and math.isnan(expected)), key


@settings(STRESS, max_examples=100)
@given(a=st.integers(1, 1000), offset=st.integers(-1000, 1000), power=st.integers(-20, 20))
def test_slider_crank_exactly_at_a_toggle_is_singular(a, offset, power):
    """At theta = pi/2 with b = |offset - a| (sin(pi/2) is exactly 1): singular, speeds not finite."""
    b = abs(offset - a)
    assume(b > 0)
    a, b, offset = (v * 2.0**power for v in (a, b, offset))
    for branch in (1, -1):
        got = solve_slider_crank(math.pi / 2, a, b, offset, branch)
        assert got["assembled"] and got["singular"]
        assert not math.isfinite(got["conrod_speed"]) and not math.isfinite(got["slider_speed"])


# --- measurements for the README (python tests/test_stability.py) ----------------------

def _random_fourbar(rng, classes=GRASHOF_CLASSES, ratio=2.0, scale=6.0):
    """Lengths as :func:`fourbars` draws them, from a NumPy generator."""
    kind = classes[rng.integers(len(classes))]
    if kind == "change-point":
        s, p, q = sorted(rng.integers(1, 1001, 3))
        links, factor = [s, p, q, p + q - s], 2.0 ** rng.integers(-20, 21)
    else:
        s, p, q = sorted(10 ** rng.uniform(-ratio, ratio, 3))
        f = rng.uniform(0.001, 0.999)
        links = [s, p, q, q + f * (p - s) if kind != "triple-rocker" else p + q - s + 2 * f * s]
        factor = 10 ** rng.uniform(-scale, scale)
    others = list(rng.permutation(links[1:]))
    position = SHORTEST_LINK.get(kind, rng.integers(4))
    return tuple(float(v * factor) for v in others[:position] + [links[0]] + others[position:]) + (kind,)


def _random_angle(rng, a, b, c, d, place, distance=None):
    if place == "crank-frame":
        centres = [mp.mpf(0), mp.pi]
    else:
        centres = toggle_angles(a, b, c, d).get(place, [])
    if not centres:
        return None
    distance = 10 ** rng.uniform(-12, -3) if distance is None else distance
    with mp.workdps(50):
        centre = centres[rng.integers(len(centres))]
        candidates = [float(centre + s * mp.mpf(distance)) for s in (1, -1)]
    inside = [t for t in candidates if fourbar_geometry(a, b, c, d, t)["defect"] >= 0]
    return inside[rng.integers(len(inside))] if inside else None


def measure_bound(count: int = 2000, seed: int = 1) -> dict:
    """Largest error / (eps * bound factor), residual, and well-conditioned error over random draws."""
    rng = numpy.random.default_rng(seed)
    worst = dict(ratio=0.0, residual=0.0, well_conditioned=0.0, rates=0.0, rates_ratio=0.0, samples=0)
    while worst["samples"] < count:
        a, b, c, d, _ = _random_fourbar(rng)
        place = PLACES[rng.integers(len(PLACES))]
        theta = (rng.uniform(-math.pi, math.pi) if place == "anywhere"
                 else _random_angle(rng, a, b, c, d, place))
        if theta is None:
            continue
        geometry = fourbar_geometry(a, b, c, d, theta)
        if geometry["defect"] < 0 or geometry["sin_mu"] == 0:
            continue
        bounds = error_bounds(a, b, c, d, geometry)
        for branch in (1, -1):
            got = solve_fourbar(theta, a, b, c, d, branch)
            exact = mp_fourbar(a, b, c, d, theta, branch)
            errors = angle_error(got["coupler"], exact["beta"]), angle_error(got["rocker"], exact["phi"])
            ratio = max(e / (EPS * k) for e, k in zip(errors, bounds))
            if ratio > worst["ratio"]:
                worst.update(ratio=ratio, case=(a, b, c, d, theta, branch, place, bounds, errors))
            worst["residual"] = max(worst["residual"],
                                    closure_residual(a, b, c, d, theta, got["coupler"], got["rocker"]))
            if max(bounds) <= WELL_CONDITIONED:
                worst["well_conditioned"] = max(worst["well_conditioned"], *errors)
                rates = rate_errors(got, mp_fourbar(a, b, c, d, theta, branch, CRANK_SPEED, CRANK_ACCEL))
                worst["rates"] = max(worst["rates"], *rates)
                worst["rates_ratio"] = max(worst["rates_ratio"], max(rates) / (EPS * max(bounds) ** 2))
        worst["samples"] += 1
    return worst


def toggle_table(count: int = 200, seed: int = 2, distances=(1e-3, 1e-6, 1e-9, 1e-12)) -> list[dict]:
    """Largest angle errors at a given distance inside a toggle: symlink, the bound, two textbook forms.

    Random linkages with toggles (link ratios up to 3, unit scale), both
    branches; the half-angle form is seed 003's eq. 2, the arccos form seed
    002's "imaginary line" (branch +1 only), both from tests/references.py.
    """
    rng = numpy.random.default_rng(seed)
    rows = []
    for distance in distances:
        worst = dict(distance=distance, symlink=0.0, bound=0.0, half_angle=0.0, arccos=0.0)
        samples = 0
        while samples < count:
            a, b, c, d, _ = _random_fourbar(rng, ("double-rocker", "triple-rocker", "rocker-crank"), 0.5, 0.0)
            place = ("extended toggle", "folded toggle")[rng.integers(2)]
            theta = _random_angle(rng, a, b, c, d, place, distance)
            if theta is None:
                continue
            geometry = fourbar_geometry(a, b, c, d, theta)
            if geometry["sin_mu"] == 0:
                continue
            samples += 1
            bounds = error_bounds(a, b, c, d, geometry)
            worst["bound"] = max(worst["bound"], K * EPS * max(bounds))
            for branch in (1, -1):
                exact = mp_fourbar(a, b, c, d, theta, branch)
                got = solve_fourbar(theta, a, b, c, d, branch)
                worst["symlink"] = max(worst["symlink"], angle_error(got["coupler"], exact["beta"]),
                                       angle_error(got["rocker"], exact["phi"]))
                with numpy.errstate(invalid="ignore", divide="ignore"):
                    beta, phi = seed003_positions(a, b, c, d, theta, branch)
                worst["half_angle"] = max(worst["half_angle"], _error_or_inf(beta, exact["beta"]),
                                          _error_or_inf(phi, exact["phi"]))
                if branch == 1:
                    with numpy.errstate(invalid="ignore"):
                        _, _, beta, rocker_back, _ = seed002_positions(d, a, b, c, 0.0, theta)
                    worst["arccos"] = max(worst["arccos"], _error_or_inf(beta, exact["beta"]),
                                          _error_or_inf(rocker_back - math.pi, exact["phi"]))
        rows.append(worst)
    return rows


def _error_or_inf(value, exact) -> float:
    value = float(value)
    return angle_error(value, exact) if math.isfinite(value) else math.inf


def half_angle_zero_table(count: int = 300, seed: int = 3) -> dict:
    """Largest errors within 1e-12 to 1e-3 rad of seed 003's A = 0 (rocker at 180 deg): symlink, half-angle."""
    rng = numpy.random.default_rng(seed)
    worst = dict(symlink=0.0, half_angle=0.0, samples=0)
    while worst["samples"] < count:
        a, b, c, d, _ = _random_fourbar(rng, GRASHOF_CLASSES[:4] + ("triple-rocker",), 0.5, 0.0)
        theta = _random_angle(rng, a, b, c, d, "half-angle A = 0")
        if theta is None or fourbar_geometry(a, b, c, d, theta)["sin_mu"] < 0.1:
            continue
        worst["samples"] += 1
        for branch in (1, -1):
            exact = mp_fourbar(a, b, c, d, theta, branch)
            got = solve_fourbar(theta, a, b, c, d, branch)
            with numpy.errstate(invalid="ignore", divide="ignore"):
                beta, phi = seed003_positions(a, b, c, d, theta, branch)
            worst["symlink"] = max(worst["symlink"], angle_error(got["rocker"], exact["phi"]))
            worst["half_angle"] = max(worst["half_angle"], _error_or_inf(phi, exact["phi"]))
    return worst


def scaling_table(count: int = 2000, seed: int = 4) -> dict:
    """Power-of-two scalings: outputs that differ in any bit; factors 10^e: largest change / (eps kappa)."""
    rng = numpy.random.default_rng(seed)
    worst = dict(samples=0, bits_differing=0, ratio=0.0)
    while worst["samples"] < count:
        a, b, c, d, _ = _random_fourbar(rng)
        place = PLACES[rng.integers(len(PLACES))]
        theta = rng.uniform(-math.pi, math.pi) if place == "anywhere" else _random_angle(rng, a, b, c, d, place)
        if theta is None:
            continue
        geometry = fourbar_geometry(a, b, c, d, theta)
        if geometry["defect"] <= 2 * TOLERANCE * geometry["size"]:
            continue
        worst["samples"] += 1
        bounds = error_bounds(a, b, c, d, geometry)
        two, ten = 2.0 ** rng.integers(-40, 41), 10 ** rng.uniform(-6, 6)
        for branch in (1, -1):
            got = solve_fourbar(theta, a, b, c, d, branch)
            by_two = solve_fourbar(theta, a * two, b * two, c * two, d * two, branch)
            worst["bits_differing"] += sum(by_two[k] != v and not (math.isnan(v) and math.isnan(by_two[k]))
                                           for k, v in got.items())
            by_ten = solve_fourbar(theta, a * ten, b * ten, c * ten, d * ten, branch)
            for key, bound in zip(("coupler", "rocker"), bounds):
                worst["ratio"] = max(worst["ratio"], angle_error(by_ten[key], mp.mpf(got[key])) / (EPS * bound))
    return worst


def measure_slider_bound(count: int = 3000, seed: int = 5) -> dict:
    """Largest slider-crank errors / their stated bounds, near toggles, dead centres and anywhere."""
    rng = numpy.random.default_rng(seed)
    worst = dict(beta=0.0, s=0.0, samples=0)
    while worst["samples"] < count:
        scale = 10 ** rng.uniform(-6, 6)
        a, b = 10 ** rng.uniform(-2, 2, 2) * scale
        offset = float(rng.choice((0, 1, -1)) * 10 ** rng.uniform(-2, 2) * scale)
        with mp.workdps(50):
            sines = [(mp.mpf(offset) - s * mp.mpf(b)) / mp.mpf(a) for s in (1, -1)]
            centres = [t for x in sines if abs(x) <= 1 for t in (mp.asin(x), mp.pi - mp.asin(x))]
            if not centres:
                continue
            theta = float(centres[rng.integers(len(centres))] + rng.choice((1, -1)) * 10 ** rng.uniform(-12, -3))
        geometry = slider_geometry(a, b, offset, theta)
        if geometry["defect"] <= 0:
            continue
        worst["samples"] += 1
        for branch in (1, -1):
            got = solve_slider_crank(theta, a, b, offset, branch)
            exact = mp_slider_crank(a, b, offset, theta, branch)
            with mp.workdps(50):
                P, root = geometry["perimeter"], geometry["root"]
                worst["beta"] = max(worst["beta"], float(angle_error(got["conrod"], exact["beta"]) * root / (EPS * P)))
                worst["s"] = max(worst["s"], float(abs(got["slider"] - exact["s"]) / (EPS * P * (1 + b / root))))
    return worst


if __name__ == "__main__":
    print("bound:", measure_bound(45000 // 3, seed=2))
    print("| distance inside a toggle (rad) | symlink | stated bound | half-angle (seed 003) | arccos (seed 002) |")
    for row in toggle_table():
        print(f"| {row['distance']:.0e} | {row['symlink']:.1e} | {row['bound']:.1e} | "
              f"{row['half_angle']:.1e} | {row['arccos']:.1e} |")
    print("A = 0:", half_angle_zero_table())
    print("scaling:", scaling_table())
