"""Every catalog entry against 50-digit mpmath references computed here by other means.

Positions, rates and accelerations, both branches, random parameters: the
references (``mp_closures``, and ``references.mp_fourbar``/``mp_slider_crank``)
find positions by circle intersections or ``mpmath.findroot`` and rates by
mpmath linear solves of the hand-written, numerically differentiated closure.
Also: loop-closure residuals of the generated solvers, and finite-difference
checks of their rates and accelerations.
"""
import math

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings, strategies as st

import mp_closures as ref
from references import mp_fourbar, mp_slider_crank
from symlink.mechanism.catalog import (CATALOG, JANSEN_HOLY_NUMBERS, fivebar, inverted_slider_crank, jansen, jansen_parameters,
                             slider_crank, stephenson2, watt2)
from symlink.numeric.solver import NumericSolver, Solver

RNG_SEED = 20240601


def wrapped(angle):
    return math.remainder(float(angle), 2 * math.pi)


def kinematic_outputs(linkage):
    names = [u.name for u in linkage.unknowns]
    return names + [n + "dot" for n in names] + [n + "ddot" for n in names]


def solve_closed_form(linkage, **values):
    result = Solver(linkage, kinematic_outputs(linkage))(**values)
    assert bool(np.all(result["assembled"]))
    return result


def assert_matches(linkage, result, q, qdot, qddot, scale, index=()):
    """Angles agree modulo 2 pi, lengths relative to the linkage's size; rates and accelerations relative."""
    rate_size = max(1.0, max(abs(float(v)) for v in qdot))
    accel_size = max(1.0, max(abs(float(v)) for v in qddot))
    for k, u in enumerate(linkage.unknowns):
        got = float(result[u.name][index])
        if any(u in v.angle.free_symbols for loop in linkage.loops for _, v in loop.terms):
            assert abs(wrapped(got - float(q[k]))) < 1e-12, u
        else:
            assert abs(got - float(q[k])) < 1e-12 * scale, u
        assert abs(float(result[u.name + "dot"][index]) - float(qdot[k])) < 1e-11 * rate_size, u
        assert abs(float(result[u.name + "ddot"][index]) - float(qddot[k])) < 1e-10 * accel_size, u


def well_conditioned(jacobian, scale):
    """Keep away from toggles, where the rates blow up and any comparison is about conditioning."""
    n = jacobian.rows
    scaled = mp.matrix(n, n)
    for i in range(n):
        for j in range(n):
            scaled[i, j] = jacobian[i, j] / scale
    return abs(mp.det(scaled)) > 0.02


# --- slider-crank ---------------------------------------------------------------------

def slider_parameters(rng):
    return {"a": rng.uniform(0.5, 3), "b": rng.uniform(3, 8), "offset": rng.uniform(-2, 2)}


@pytest.mark.parametrize("branch", [1, -1])
def test_slider_crank_against_50_digits(branch):
    linkage = slider_crank()
    rng = np.random.default_rng(RNG_SEED)
    checked = 0
    for _ in range(8):
        p = slider_parameters(rng)
        theta, w, al = rng.uniform(-math.pi, math.pi), rng.uniform(-5, 5), rng.uniform(-5, 5)
        expected = mp_slider_crank(p["a"], p["b"], p["offset"], theta, branch, w, al)
        q, qdot, qddot, jacobian = ref.kinematics(ref.slider_closure, [theta], [expected["beta"], expected["s"]],
                                                  p, [w], [al], refine=False)
        # two independent references agree
        assert abs(qdot[1] - expected["s_speed"]) < 1e-30 and abs(qddot[0] - expected["beta_accel"]) < 1e-30
        result = solve_closed_form(linkage, theta=theta, branch=branch, thetadot=w, thetaddot=al, **p)
        assert_matches(linkage, result, q, qdot, qddot, p["a"] + p["b"])
        checked += 1
    assert checked == 8


def test_slider_crank_branch_plus_one_is_the_larger_slider_position():
    rng = np.random.default_rng(1)
    solver = Solver(slider_crank(), ["slider"])
    for _ in range(20):
        p = slider_parameters(rng)
        theta = rng.uniform(-math.pi, math.pi)
        far, near = (float(solver(theta=theta, branch=s, **p)["slider"]) for s in (1, -1))
        assert far > near


@settings(max_examples=60, deadline=None)
@given(a=st.floats(0.1, 10), b=st.floats(0.1, 10), offset=st.floats(-5, 5), theta=st.floats(-7, 7),
       branch=st.sampled_from([1, -1]))
def test_slider_crank_closes_or_says_it_cannot(a, b, offset, theta, branch):
    result = SLIDER_SOLVER(theta=theta, a=a, b=b, offset=offset, branch=branch)
    reachable = abs(offset - a * math.sin(theta)) <= b * (1 - 1e-12)
    if not result["assembled"]:
        assert not reachable
        return
    assert reachable or abs(abs(offset - a * math.sin(theta)) - b) < 1e-12 * (a + b + abs(offset))
    beta, s = float(result["conrod"]), float(result["slider"])
    size = a + b + abs(offset) + abs(s)
    assert abs(a * math.cos(theta) + b * math.cos(beta) - s) < 1e-14 * size
    assert abs(a * math.sin(theta) + b * math.sin(beta) - offset) < 1e-14 * size


SLIDER_SOLVER = Solver(slider_crank(), ["conrod", "slider"])


# --- inverted slider-crank ------------------------------------------------------------------

def test_inverted_slider_crank_against_50_digits():
    linkage = inverted_slider_crank()
    rng = np.random.default_rng(RNG_SEED)
    for _ in range(10):
        p = {"a": rng.uniform(0.5, 3), "d": rng.uniform(0.5, 3)}
        theta, w, al = rng.uniform(-math.pi, math.pi), rng.uniform(-5, 5), rng.uniform(-5, 5)
        with mp.workdps(ref.DPS):
            start = ref.inverted_positions([mp.mpf(theta)], {k: mp.mpf(v) for k, v in p.items()})
        q, qdot, qddot, _ = ref.kinematics(ref.inverted_closure, [theta], start, p, [w], [al], refine=False)
        assert q[1] > 0
        result = solve_closed_form(linkage, theta=theta, thetadot=w, thetaddot=al, **p)
        assert_matches(linkage, result, q, qdot, qddot, p["a"] + p["d"])


def test_whitworth_rocker_turns_fully_and_crank_shaper_swings():
    solver = Solver(inverted_slider_crank(), ["rocker"])
    theta = np.radians(np.arange(0.0, 360.0, 1.0))
    whitworth = np.unwrap(solver(theta=theta, a=2.0, d=1.0)["rocker"])  # d < a
    assert whitworth[-1] - whitworth[0] > math.radians(350)
    shaper = solver(theta=theta, a=1.0, d=2.0)["rocker"]                  # d > a: swings about 180 deg
    swing = np.ptp(np.unwrap(shaper))
    assert abs(swing - 2 * math.asin(1 / 2)) < 1e-3   # seen from D the crank circle spans 2 asin(a/d)


# --- four-bar ------------------------------------------------------------------------------------------

@pytest.mark.parametrize("branch", [1, -1])
def test_fourbar_against_50_digits(branch):
    linkage = CATALOG["fourbar"]()
    rng = np.random.default_rng(RNG_SEED)
    checked = 0
    while checked < 6:
        p = {k: rng.uniform(1, 5) for k in "abcd"}
        theta, w, al = rng.uniform(-math.pi, math.pi), rng.uniform(-5, 5), rng.uniform(-5, 5)
        try:
            expected = mp_fourbar(p["a"], p["b"], p["c"], p["d"], theta, branch, w, al)
        except ValueError:
            continue
        q, qdot, qddot, jacobian = ref.kinematics(ref.fourbar_closure, [theta], [expected["beta"], expected["phi"]],
                                                  p, [w], [al], refine=False)
        if not well_conditioned(jacobian, max(p.values())):
            continue
        assert abs(qddot[1] - expected["phi_accel"]) < 1e-25
        result = solve_closed_form(linkage, theta=theta, branch=branch, thetadot=w, thetaddot=al, **p)
        assert_matches(linkage, result, q, qdot, qddot, sum(p.values()))
        checked += 1


# --- Watt II --------------------------------------------------------------------------------------------

def watt2_parameters(rng):
    p = {k: rng.uniform(1, 5) for k in "abcdefg"}
    p.update(alpha=rng.uniform(-math.pi, math.pi), gx=rng.uniform(-3, 8), gy=rng.uniform(-3, 5))
    return p


@pytest.mark.parametrize("branches", [(1, 1), (1, -1), (-1, 1), (-1, -1)])
def test_watt2_against_50_digits(branches):
    linkage = watt2()
    rng = np.random.default_rng(RNG_SEED + branches[0] + 3 * branches[1])
    checked = tries = 0
    while checked < 5:
        tries += 1
        assert tries < 2000
        p = watt2_parameters(rng)
        theta, w, al = rng.uniform(-math.pi, math.pi), rng.uniform(-5, 5), rng.uniform(-5, 5)
        try:
            with mp.workdps(ref.DPS):
                start = ref.watt2_positions([mp.mpf(theta)], {k: mp.mpf(v) for k, v in p.items()}, branches)
        except ValueError:
            continue
        q, qdot, qddot, jacobian = ref.kinematics(ref.watt2_closure, [theta], start, p, [w], [al], refine=False)
        if not well_conditioned(jacobian, max(p.values())):
            continue
        result = solve_closed_form(linkage, theta=theta, branch_ABCD=branches[0], branch_DEFG=branches[1],
                                   thetadot=w, thetaddot=al, **p)
        assert_matches(linkage, result, q, qdot, qddot, sum(abs(v) for v in p.values()))
        checked += 1


# --- five-bar (two inputs) ----------------------------------------------------------------------------

@pytest.mark.parametrize("branch", [1, -1])
def test_fivebar_against_50_digits(branch):
    linkage = fivebar()
    rng = np.random.default_rng(RNG_SEED + branch)
    checked = 0
    while checked < 6:
        p = {k: rng.uniform(1, 5) for k in "abcde"}
        x = list(rng.uniform(-math.pi, math.pi, 2))
        xdot, xddot = list(rng.uniform(-5, 5, 2)), list(rng.uniform(-5, 5, 2))
        try:
            with mp.workdps(ref.DPS):
                start = ref.fivebar_positions([mp.mpf(v) for v in x], {k: mp.mpf(v) for k, v in p.items()}, branch)
        except ValueError:
            continue
        q, qdot, qddot, jacobian = ref.kinematics(ref.fivebar_closure, x, start, p, xdot, xddot, refine=False)
        if not well_conditioned(jacobian, max(p.values())):
            continue
        result = solve_closed_form(linkage, theta=x[0], psi=x[1], branch=branch, thetadot=xdot[0], psidot=xdot[1],
                                   thetaddot=xddot[0], psiddot=xddot[1], **p)
        assert_matches(linkage, result, q, qdot, qddot, sum(p.values()))
        checked += 1


# --- Stephenson II (numeric) -------------------------------------------------------------------------

def stephenson2_assembled_at(rng):
    """Random Stephenson II dimensions, built around a random configuration at theta = 0 (so it assembles)."""
    a, b, e, f, h, d = 1.0, *rng.uniform(2, 5, 4), rng.uniform(3, 6)
    alpha, delta = rng.uniform(0.3, 1.5, 2)
    beta, phi = rng.uniform(-0.5, 1.0), rng.uniform(1.0, 2.5)
    B = complex(a, 0)
    C, E = B + b * np.exp(1j * beta), B + e * np.exp(1j * (beta + alpha))
    F, H = d + f * np.exp(1j * phi), d + h * np.exp(1j * (phi + delta))
    p = dict(a=a, b=b, c=abs(F - C), d=d, e=e, f=f, g=abs(H - E), h=h, alpha=alpha, delta=delta)
    guess = dict(beta=beta, mu=np.angle(F - C), phi=phi, eta=np.angle(H - E))
    return p, guess


def test_stephenson2_random_dimensions_against_50_digits():
    linkage = stephenson2()
    solver = NumericSolver(linkage)
    rng = np.random.default_rng(RNG_SEED)
    theta = np.radians(np.arange(0.0, 41.0, 10.0))
    checked = 0
    while checked < 3:
        p, guess = stephenson2_assembled_at(rng)
        if min(p["c"], p["g"]) < 1.0:
            continue
        try:
            mp_positions = ref.continue_sweep(ref.stephenson2_closure, [(t,) for t in theta],
                                              [guess[u.name] for u in linkage.unknowns], p, substeps=8)
        except (ValueError, ZeroDivisionError):
            continue
        result = solver(theta=theta, guess=guess, thetadot=1.7, thetaddot=-0.4, **p)
        for i, t in enumerate(theta):
            q, qdot, qddot, jacobian = ref.kinematics(ref.stephenson2_closure, [t], mp_positions[i], p,
                                                      [1.7], [-0.4], refine=False)
            assert_matches(linkage, result, q, qdot, qddot, sum(p.values()), index=i)
        checked += 1


# --- every entry: closure residuals and finite differences --------------------------------------------

CLOSED_FORM_CASES = {
    "slider-crank": dict(a=1.3, b=4.1, offset=0.7, branch=1),
    "inverted-slider-crank": dict(a=2.0, d=1.2),
    "fourbar": dict(a=20.0, b=66.0, c=56.0, d=80.0, branch=-1),
    "watt2": dict(a=1.0, b=3.5, c=3.0, d=3.2, e=2.0, f=4.0, g=3.0, alpha=0.6, gx=4.5, gy=3.5,
                  branch_ABCD=1, branch_DEFG=-1),
    "fivebar": dict(a=2.0, b=4.0, c=4.0, d=3.0, e=2.0, psi=2.2, branch=1),
    "jansen": jansen_parameters(),
}


@pytest.mark.parametrize("name", sorted(CLOSED_FORM_CASES))
def test_closure_residual_and_finite_differences(name):
    linkage = CATALOG[name]()
    values = dict(CLOSED_FORM_CASES[name])
    solver = Solver(linkage, kinematic_outputs(linkage))
    theta = np.radians(np.arange(-170.0, 180.0, 17.0))
    h = 1e-5
    at = {shift: solver(theta=theta + shift, thetadot=1.0, thetaddot=0.0, **values) for shift in (-h, 0.0, h)}
    assert bool(np.all(at[0.0]["assembled"]))
    parameters = {s.name: values.get(s.name) for s in linkage.parameters}
    size = sum(abs(v) for v in parameters.values())
    symbols = {s: values[s.name] for s in linkage.parameters} | {s: values[s.name] for s in linkage.inputs[1:]}
    for loop in linkage.loops:
        for component in loop.equations():
            function = sp.lambdify([linkage.inputs[0], *linkage.unknowns],
                                                    component.subs(symbols), "numpy")
            residual = function(theta, *(at[0.0][u.name] for u in linkage.unknowns))
            assert np.max(np.abs(residual)) < 1e-13 * size
    for u in linkage.unknowns:
        difference = np.unwrap(at[h][u.name] - at[-h][u.name]) / (2 * h)
        assert np.allclose(difference, at[0.0][u.name + "dot"], rtol=1e-7, atol=1e-7)
        second = (at[h][u.name + "dot"] - at[-h][u.name + "dot"]) / (2 * h)
        assert np.allclose(second, at[0.0][u.name + "ddot"], rtol=1e-6, atol=1e-6)


def test_stephenson2_closure_residual_and_finite_differences():
    p, guess = STEPHENSON2
    solver = NumericSolver(stephenson2())
    theta = np.radians(np.arange(0.0, 360.0, 10.0))
    h = 1e-5
    at = {shift: solver(theta=theta + shift, guess=guess, thetadot=1.0, **p) for shift in (-h, 0.0, h)}
    with mp.workdps(20):
        for i, t in enumerate(theta):
            q = [at[0.0][n][i] for n in ("beta", "mu", "phi", "eta")]
            residual = ref.stephenson2_closure([t], [mp.mpf(v) for v in q], {k: mp.mpf(v) for k, v in p.items()})
            assert max(abs(r) for r in residual) < 1e-14 * sum(p.values())
    for name in ("beta", "mu", "phi", "eta"):
        difference = (at[h][name] - at[-h][name]) / (2 * h)
        assert np.allclose(difference, at[0.0][name + "dot"], rtol=1e-7, atol=1e-7)
        second = (at[h][name + "dot"] - at[-h][name + "dot"]) / (2 * h)
        assert np.allclose(second, at[0.0][name + "ddot"], rtol=1e-6, atol=1e-6)


#: The Stephenson II of derivations/stephenson2.py's example: its crank turns fully.
STEPHENSON2 = (dict(a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1, alpha=0.9, delta=0.3),
               dict(beta=0.96, mu=0.27, phi=1.43, eta=-0.16))


def test_catalog_entries_are_fresh_linkages_with_documented_names():
    assert set(CATALOG) == {"fourbar", "slider-crank", "inverted-slider-crank", "offset-inverted-slider-crank",
                            "watt2", "stephenson2", "fivebar", "jansen"}
    for name, build in CATALOG.items():
        first, second = build(), build()
        assert first is not second and first.name == name
        assert all(point in first.points for point in ("A", "B"))
    theta, beta, s = sp.symbols("theta beta s", real=True)
    assert slider_crank().roles == {"crank": theta, "conrod": beta, "slider": s}
    assert not stephenson2().has_closed_form and all(CATALOG[n]().has_closed_form for n in CLOSED_FORM_CASES)



# --- Theo Jansen leg: chains of circle intersections at 50 digits -------------------------------------------

def mp_circles(centre0, radius0, centre1, radius1, left):
    """The intersection of two circles left (or right) of the line from centre0 to centre1; None if they miss."""
    try:
        return ref.circle_point(centre0, radius0, centre1, radius1, 1 if left else -1)
    except ValueError:
        return None


def mp_jansen_joints(theta, n, signs):
    """Joints of a Jansen leg with Jansen's lengths ``n`` (e and h as lengths, not angles) at crank angle theta.

    ``signs`` choose each intersection: C left of D->B, F left of B->D, G left of F->E (+1 each is the leg);
    E is left of D->C and the foot H left of F->G (the triangles' orientation, not a choice).
    """
    n = {k: mp.mpf(v) for k, v in n.items()}
    B = n["m"] * mp.expjpi(theta / mp.pi)
    D = mp.mpc(-n["a"], -n["l"])
    C = mp_circles(D, n["b"], B, n["j"], signs[0] > 0)
    F = mp_circles(B, n["k"], D, n["c"], signs[1] > 0)
    if C is None or F is None:
        return None
    E = mp_circles(D, n["d"], C, n["e"], True)
    G = mp_circles(F, n["g"], E, n["f"], signs[2] > 0)
    if G is None:
        return None
    H = mp_circles(F, n["i"], G, n["h"], True)
    return dict(B=B, C=C, D=D, E=E, F=F, G=G, H=H)


#: Each unknown angle of jansen() as the direction from one joint to another.
JANSEN_ANGLES = dict(phi=("D", "C"), beta=("B", "C"), mu=("B", "F"), psi=("D", "F"), eta=("F", "G"), kappa=("E", "G"))


def mp_jansen_angle(theta, name, n, signs, near):
    joints = mp_jansen_joints(theta, n, signs)
    start, end = JANSEN_ANGLES[name]
    angle = mp.arg(joints[end] - joints[start])
    return near + mp.atan2(mp.sin(angle - near), mp.cos(angle - near))  # continuous near ``near``


@pytest.mark.parametrize("signs", [(1, 1, 1), (1, 1, -1), (1, -1, 1), (-1, 1, 1), (-1, -1, -1)])
def test_jansen_against_50_digits(signs):
    linkage = jansen()
    outputs = kinematic_outputs(linkage) + [f"{p}_{axis}" for p in "CEFGH" for axis in "xy"]
    branches = dict(branch_ABCD=signs[0], branch_ABFD=signs[1], branch_DFGE=signs[2])
    solver = Solver(linkage, outputs)
    rng = np.random.default_rng(RNG_SEED + 7 * signs[0] + 3 * signs[1] + signs[2])
    checked = unassembled = 0
    for theta in np.radians(np.arange(-180.0, 180.0, 30.0)) + rng.uniform(0, 0.1):
        w, al = rng.uniform(-5, 5), rng.uniform(-5, 5)
        result = solver(theta=theta, thetadot=w, thetaddot=al, **branches, **jansen_parameters())
        with mp.workdps(ref.DPS):
            joints = mp_jansen_joints(mp.mpf(theta), JANSEN_HOLY_NUMBERS, signs)
            if joints is None:
                assert not bool(result["assembled"])
                unassembled += 1
                continue
            assert bool(result["assembled"])
            for point in "CEFGH":
                assert abs(float(result[point + "_x"]) - float(joints[point].real)) < 1e-12
                assert abs(float(result[point + "_y"]) - float(joints[point].imag)) < 1e-12
            for name in JANSEN_ANGLES:
                near = mp.mpf(float(result[name]))
                q = lambda t: mp_jansen_angle(t, name, JANSEN_HOLY_NUMBERS, signs, near)  # noqa: E731
                first, second = mp.diff(q, mp.mpf(theta), 1), mp.diff(q, mp.mpf(theta), 2)
                rate, accel = first * w, second * w ** 2 + first * al
                assert abs(wrapped(float(result[name]) - float(q(mp.mpf(theta))))) < 1e-13, name
                assert abs(float(result[name + "dot"]) - float(rate)) < 1e-11 * max(1.0, abs(float(rate))), name
                assert abs(float(result[name + "ddot"]) - float(accel)) < 1e-10 * max(1.0, abs(float(accel))), name
        checked += 1
    assert checked >= 6


def test_jansen_leg_walks_a_flat_stride():
    """The holy numbers' point: for over a quarter of the turn the foot stays within 1 % of the
    path's height above its lowest point, over more than half of the path's width (a circle
    would stay there for a few degrees only)."""
    result = Solver(jansen(), ["H_x", "H_y"])(theta=np.radians(np.arange(0.0, 360.0, 1.0)), **jansen_parameters())
    x, y = result["H_x"], result["H_y"]
    low = y < y.min() + 0.01 * np.ptp(y)
    assert low.sum() > 90 and np.ptp(x[low]) > 0.5 * np.ptp(x)


def test_generated_jansen_module_against_50_digits():
    import importlib.util
    from pathlib import Path
    path = Path(__file__).resolve().parent.parent.parent / "generated" / "jansen.py"
    spec = importlib.util.spec_from_file_location("generated_jansen", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    theta = np.radians(np.arange(0.0, 360.0, 45.0))
    joints = module.joints(theta, **jansen_parameters())
    speeds = module.velocities(theta, **jansen_parameters(), thetadot=2.0)
    with mp.workdps(ref.DPS):
        for n, t in enumerate(theta):
            expected = mp_jansen_joints(mp.mpf(t), JANSEN_HOLY_NUMBERS, (1, 1, 1))
            for point in "BCEFGH":
                assert abs(joints[point + "_x"][n] - float(expected[point].real)) < 1e-12
                assert abs(joints[point + "_y"][n] - float(expected[point].imag)) < 1e-12
            near = mp.mpf(float(speeds["leg"][n]))
            rate = 2 * mp.diff(lambda s: mp_jansen_angle(s, "eta", JANSEN_HOLY_NUMBERS, (1, 1, 1), near), mp.mpf(t))
            assert abs(speeds["leg_speed"][n] - float(rate)) < 1e-11 * max(1.0, abs(float(rate)))


@pytest.mark.parametrize("branch", [1, -1])
def test_offset_inverted_slider_crank_against_its_tangent_construction(branch):
    """The catalog entry and its generated module against a 50-digit tangent-line construction (mp_closures):
    positions, rates and accelerations by mpmath differentiation, both branches, the guide's foot T."""
    import mpmath as mp

    from mp_closures import offset_inverted_positions
    from symlink.mechanism.catalog import offset_inverted_slider_crank
    linkage = offset_inverted_slider_crank()
    solver = Solver(linkage, ["rocker", "slider", "rocker_speed", "slider_speed", "rocker_accel", "slider_accel",
                              "T_x", "T_y"])
    a, d, e, omega, alpha = 1.0, 2.5, 0.4, 2.0, 0.3
    for angle in np.linspace(-3.1, 3.1, 11):
        got = solver(theta=angle, a=a, d=d, e=e, branch=branch, thetadot=omega, thetaddot=alpha)
        assert bool(got["assembled"])
        with mp.workdps(50):
            t0 = mp.mpf(float(angle))
            for k, name in ((0, "slider"), (1, "rocker")):
                position = lambda t: offset_inverted_positions(t, 1, mp.mpf(5) / 2, mp.mpf(2) / 5, branch)[k]  # noqa: E731
                first, second = mp.diff(position, t0, 1), mp.diff(position, t0, 2)
                expected = {name: position(t0), name + "_speed": first * omega,
                            name + "_accel": second * omega**2 + first * alpha}
                for key, value in expected.items():
                    difference = float(got[key]) - float(value)
                    if key == "rocker":
                        difference = math.remainder(difference, 2 * math.pi)
                    assert abs(difference) <= 1e-13 * (1 + abs(float(value))), (angle, key)
            phi = offset_inverted_positions(t0, 1, mp.mpf(5) / 2, mp.mpf(2) / 5, branch)[1]
            foot = mp.mpf(5) / 2 + mp.mpf(2) / 5 * mp.expj(phi + mp.pi / 2)
            assert abs(float(got["T_x"]) - float(mp.re(foot))) < 1e-14 and abs(float(got["T_y"]) - float(mp.im(foot))) < 1e-14
