"""Design sensitivities against 50-digit central differences, for every catalog entry.

The reference never uses symlink's derivation: each linkage's closure is typed
by hand as an mpmath function (``mp_closures`` and the two below), its
unknowns are found by ``mpmath.findroot`` at 50 digits (started from the
generated solver's float solution, which only picks the assembly; the root
found must agree with it), and each sensitivity is the central difference
``(q(p + h) - q(p - h)) / 2h`` with ``h = 1e-20``, every q(p +- h) solved
again by ``findroot`` (truncation ~h^2, rounding ~1e-27).  Points and extras
are the catalog's own definitions (vector sums of the parameters and
coordinates, not derived forms) evaluated in mpmath at those roots.

Parameters are random (lengths scaled by U(0.85, 1.15) from the catalog's
example, fixed angles and pivot coordinates moved by U(-0.15, 0.15)), inputs
uniform over a turn, branches random.  A sample is rejected, never loosened
for, when it cannot be assembled or lies near a toggle, by one stated
criterion: the closure Jacobian with its columns scaled to unit length (each
column is a vector the unknown turns or slides) has ``|det| < 0.05``.  For a
loop with two unknown angles that determinant is the sine of the angle between
the two vectors it closes with (the product of such sines over the loops), so
a sample is rejected when one loop is within about 3 degrees of lining up (or
several are nearly so): there the sensitivities grow without bound and a float
comparison measures conditioning, not the derivation.  Agreement is then
required to 1e-9 relative to each entry's magnitude; entries smaller than 1e-6
of the output's largest sensitivity (exact zeros, say) are held to 1e-9 of
that 1e-6 instead.  The worst error measured is about 1e-13.
"""
import math

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings, strategies as st

import mp_closures as ref
from symlink.mechanism.catalog import CATALOG, EXAMPLE_VALUES
from symlink.numeric.design_jacobian import DesignJacobian, design_jacobian, sensitivity_outputs
from symlink.symbolic.linkage import Linkage
from symlink.io.scene import Scene
from symlink.symbolic.sensitivity import sensitivity_name
from symlink.numeric.solver import NumericSolver, Solver
from symlink.symbolic.vectors import acceleration, rate

RNG_SEED = 20261123
DPS = 50
STEP = mp.mpf(10) ** -20
#: Toggle guard: |det| of the closure Jacobian with unit columns below this rejects a sample.
TOGGLE_GUARD = 0.05
TOLERANCE = 1e-9
#: Entries that vanish are compared to this fraction of the output's largest sensitivity instead.
FLOOR = 1e-6


def offset_inverted_closure(x, q, p):
    (theta,), (phi, s) = x, q
    z = p["a"] * mp.expj(theta) - s * mp.expj(phi) - p["e"] * mp.expj(phi + mp.pi / 2) - p["d"]
    return [z.real, z.imag]


def jansen_closure(x, q, p):
    """Jansen's leg in the catalog's parameters: D = -a - i l, the triangles' angles alpha (at D) and gamma."""
    (theta,), (phi, beta, mu, psi, eta, kappa) = x, q
    D = mp.mpc(-p["a"], -p["l"])
    B = p["m"] * mp.expj(theta)
    upper = D + p["b"] * mp.expj(phi) - B - p["j"] * mp.expj(beta)
    lower = B + p["k"] * mp.expj(mu) - D - p["c"] * mp.expj(psi)
    legs = p["c"] * mp.expj(psi) + p["g"] * mp.expj(eta) - p["f"] * mp.expj(kappa) - p["d"] * mp.expj(phi + p["alpha"])
    return [upper.real, upper.imag, lower.real, lower.imag, legs.real, legs.imag]


CLOSURES = {
    "fourbar": ref.fourbar_closure,
    "slider-crank": ref.slider_closure,
    "inverted-slider-crank": ref.inverted_closure,
    "offset-inverted-slider-crank": offset_inverted_closure,
    "watt2": ref.watt2_closure,
    "stephenson2": ref.stephenson2_closure,
    "fivebar": ref.fivebar_closure,
    "jansen": jansen_closure,
}


def position_outputs(linkage: Linkage) -> list[str]:
    return ([q.name for q in linkage.unknowns] + list(linkage.roles)
            + [f"{point}_{axis}" for point in linkage.points for axis in "xy"] + list(linkage.extras))


def random_values(name: str, linkage: Linkage, rng) -> dict[str, float]:
    example = EXAMPLE_VALUES[name]
    values = {}
    for p in linkage.parameters:
        if p.is_positive:
            values[p.name] = example[p.name] * rng.uniform(0.85, 1.15)
        else:
            values[p.name] = example[p.name] + rng.uniform(-0.15, 0.15)
    for x in linkage.inputs:
        values[x.name] = rng.uniform(-math.pi, math.pi)
    return values


def mp_root(closure, x, p, start):
    with mp.workdps(DPS):
        found = mp.findroot(lambda *u: closure(x, list(u), p), list(start))
        return [found[i] for i in range(len(start))]


def unit_column_determinant(closure, x, p, q) -> float:
    """|det| of the closure Jacobian dF/dq with each column scaled to unit length (mpmath derivatives)."""
    n = len(q)
    with mp.workdps(DPS):
        matrix = mp.matrix(n, n)
        for j in range(n):
            def moved(s, j=j):
                return closure(x, [v + (s if k == j else 0) for k, v in enumerate(q)], p)
            column = [mp.diff(lambda s: moved(s)[i], 0) for i in range(n)]
            size = mp.sqrt(sum(c * c for c in column))
            for i in range(n):
                matrix[i, j] = column[i] / size
        return float(abs(mp.det(matrix)))


def definitions(linkage: Linkage, outputs):
    """The outputs' definitions (catalog vector sums and extras) as mpmath functions of inputs, unknowns, parameters."""
    arguments = list(linkage.inputs + linkage.unknowns + linkage.parameters)
    return {name: sp.lambdify(arguments, linkage.output(name), "mpmath") for name in outputs}


def mp_sensitivities(linkage, closure, outputs, x, p, q0):
    """{(output, parameter): d output / d parameter} by 50-digit central differences of findroot solutions."""
    functions = definitions(linkage, outputs)
    inputs = [mp.mpf(v) for v in x]
    found = {}
    with mp.workdps(DPS):
        for parameter in linkage.parameters:
            sides = []
            for sign in (1, -1):
                moved = dict(p)
                moved[parameter.name] = p[parameter.name] + sign * STEP
                q = mp_root(closure, inputs, moved, q0)
                args = inputs + q + [moved[s.name] for s in linkage.parameters]
                sides.append({name: functions[name](*args) for name in outputs})
            for name in outputs:
                found[name, parameter.name] = (sides[0][name] - sides[1][name]) / (2 * STEP)
    return found


def worst_error(got: dict, expected: dict, linkage, outputs) -> tuple[float, str]:
    """The largest error relative to max(|entry|, FLOOR * the output's largest sensitivity), and where."""
    worst, where = 0.0, ""
    for name in outputs:
        row = float(max(abs(expected[name, p.name]) for p in linkage.parameters))
        for p in linkage.parameters:
            want = float(expected[name, p.name])
            value = float(np.ravel(got[sensitivity_name(name, p.name)])[0])
            error = abs(value - want) / max(abs(want), FLOOR * row, 1e-300)
            if not error <= worst:  # NaN counts as worst
                worst, where = error, f"d{name}/d{p.name} = {value!r}, 50 digits say {want!r}"
    return worst, where


# --- every closed-form catalog entry against 50 digits ------------------------------------------------------

CLOSED_FORM = sorted(name for name in CATALOG if name != "stephenson2")


def check_samples(name: str, samples: int, seed: int) -> None:
    linkage = CATALOG[name]()
    closure = CLOSURES[name]
    outputs = position_outputs(linkage)
    solver = Solver(linkage, outputs + sensitivity_outputs(linkage, outputs))
    rng = np.random.default_rng(seed)
    checked = tries = 0
    while checked < samples:
        tries += 1
        assert tries < 20 * samples, "too many rejected samples: the random ranges are wrong"
        values = random_values(name, linkage, rng)
        branches = {b.name: int(rng.choice([1, -1])) for b in linkage.branches}
        got = solver(**values, **branches)
        if not bool(got["assembled"]):
            continue  # cannot be assembled: nothing to differentiate
        x = [mp.mpf(values[s.name]) for s in linkage.inputs]
        with mp.workdps(DPS):
            p = {s.name: mp.mpf(values[s.name]) for s in linkage.parameters}
            start = [float(got[u.name]) for u in linkage.unknowns]
            q0 = mp_root(closure, x, p, [mp.mpf(v) for v in start])
        assert max(abs(float(a) - b) for a, b in zip(q0, start)) < 1e-9, "findroot left the solver's assembly"
        if unit_column_determinant(closure, x, p, q0) < TOGGLE_GUARD:
            continue  # near a toggle
        expected = mp_sensitivities(linkage, closure, outputs, x, p, q0)
        error, where = worst_error(got, expected, linkage, outputs)
        assert error <= TOLERANCE, f"{name} at {values} {branches}: {where}"
        checked += 1


@pytest.mark.parametrize("name", CLOSED_FORM)
def test_every_closed_form_entry_against_50_digit_central_differences(name):
    check_samples(name, 2, RNG_SEED + CLOSED_FORM.index(name))


@pytest.mark.slow
@pytest.mark.parametrize("name", CLOSED_FORM)
def test_many_random_samples_against_50_digits(name):
    check_samples(name, 25, 7 * RNG_SEED + CLOSED_FORM.index(name))


# --- the Newton fallback ---------------------------------------------------------------------------------

def stephenson2_around(rng):
    """Random Stephenson II dimensions built around a random configuration at theta = 0, so that it assembles."""
    a, b, e, f, h, d = 1.0, *rng.uniform(2, 5, 4), rng.uniform(3, 6)
    alpha, delta = rng.uniform(0.3, 1.5, 2)
    beta, phi = rng.uniform(-0.5, 1.0), rng.uniform(1.0, 2.5)
    B = complex(a, 0)
    C, E = B + b * np.exp(1j * beta), B + e * np.exp(1j * (beta + alpha))
    F, H = d + f * np.exp(1j * phi), d + h * np.exp(1j * (phi + delta))
    p = dict(a=a, b=b, c=abs(F - C), d=d, e=e, f=f, g=abs(H - E), h=h, alpha=alpha, delta=delta)
    return p, dict(beta=beta, mu=np.angle(F - C), phi=phi, eta=np.angle(H - E))


def test_stephenson2_newton_sensitivities_against_50_digits():
    """No closed form: dq/dp solves J dq/dp = -dF/dp with the converged Jacobian, over a continued sweep."""
    linkage = CATALOG["stephenson2"]()
    outputs = position_outputs(linkage)
    jacobian = DesignJacobian(linkage, outputs)
    rng = np.random.default_rng(RNG_SEED)
    theta = np.array([0.0, 0.15, 0.3])
    checked = tries = 0
    while checked < 2:
        tries += 1
        assert tries < 50
        p, guess = stephenson2_around(rng)
        if min(p["c"], p["g"]) < 1.0:
            continue
        try:
            values, slopes = jacobian(theta=theta, guess=guess, **p)
        except ValueError:  # the sweep meets a dead centre or leaves the assembly: not this sample
            continue
        with mp.workdps(DPS):
            mp_p = {k: mp.mpf(v) for k, v in p.items()}
            roots = [mp_root(ref.stephenson2_closure, [mp.mpf(t)], mp_p,
                             [mp.mpf(float(values[u.name][i])) for u in linkage.unknowns]) for i, t in enumerate(theta)]
        if min(unit_column_determinant(ref.stephenson2_closure, [mp.mpf(t)], mp_p, q)
               for t, q in zip(theta, roots)) < TOGGLE_GUARD:
            continue
        for i, t in enumerate(theta):
            expected = mp_sensitivities(linkage, ref.stephenson2_closure, outputs, [t], mp_p, roots[i])
            got = {sensitivity_name(o, s.name): slopes[i, k, j]
                   for k, o in enumerate(outputs) for j, s in enumerate(linkage.parameters)}
            error, where = worst_error(got, expected, linkage, outputs)
            assert error <= TOLERANCE, f"stephenson2 at theta = {t}, {p}: {where}"
        checked += 1


def test_newton_module_agrees_with_closed_form_where_both_exist():
    """The four-bar solved by Newton's method has the closed form's sensitivities (two derivations, one answer)."""
    linkage = CATALOG["fourbar"]()
    values = dict(a=20.0, b=66.0, c=56.0, d=80.0)
    theta = np.radians(np.arange(0.0, 360.0, 30.0))
    outputs = ["rocker", "coupler", "C_x", "C_y", "transmission"]
    names = sensitivity_outputs(linkage, outputs)
    closed = Solver(linkage, outputs + names)(theta=theta, branch=1, **values)
    guess = dict(beta=float(closed["coupler"][0]) + 0.01, phi=float(closed["rocker"][0]) - 0.01)
    numeric = NumericSolver(linkage).functions["sensitivities"](theta=theta, guess=guess, **values)
    for name in names:
        assert np.allclose(numeric[name], closed[name], rtol=1e-10, atol=1e-12), name


# --- the generated languages and the request ---------------------------------------------------------------

@pytest.mark.parametrize("name", ["fourbar", "watt2", "jansen", "offset-inverted-slider-crank"])
def test_numpy_and_c_agree(name):
    from symlink.numeric.compiled import CompiledSolver, CompilerUnavailable
    linkage = CATALOG[name]()
    points = [o for o in position_outputs(linkage) if o.endswith(("_x", "_y"))][-2:]
    outputs = points + list(linkage.extras)  # the last point's sensitivities need every unknown's
    wanted = outputs + sensitivity_outputs(linkage, outputs)
    try:
        compiled = CompiledSolver(linkage, wanted)
    except CompilerUnavailable:
        pytest.skip("no C compiler")
    values = dict(EXAMPLE_VALUES[name])
    values[linkage.inputs[0].name] = np.radians(np.arange(-180.0, 180.0, 7.0))
    expected = Solver(linkage, wanted)(**values)
    got = compiled(**values)
    assert np.array_equal(got["assembled"], expected["assembled"]) and expected["assembled"].any()
    ok = expected["assembled"]
    for output in wanted:
        assert np.allclose(got[output][ok], expected[output][ok], rtol=1e-12, atol=1e-12 * np.max(np.abs(expected[output][ok]))), output


def test_positions_and_sensitivities_derive_no_rates():
    linkage = CATALOG["fourbar"]()
    scene = Scene(linkage, ["rocker", "rocker__d_a", "C_x__d_d", "transmission__d_b"],
                  dict(theta=0.4, a=20.0, b=66.0, c=56.0, d=80.0))
    program = scene.program()
    symbols = {s for s, _ in program.assignments} | set(program.arguments)
    for _, expr in program.assignments:
        symbols |= expr.free_symbols
    moving = {f(q) for q in linkage.coordinates for f in (rate, acceleration)}
    assert not symbols & moving
    assert "velocities" not in linkage.__dict__ and "accelerations" not in linkage.__dict__
    assert "dot" not in scene.source
    result = scene.evaluate()[1]
    # A sensitivity by a loop's length divides by the loop's determinant: the singular mask comes with it.
    assert set(result) == {"rocker", "rocker__d_a", "C_x__d_d", "transmission__d_b", "singular", "assembled"}
    # Only the parameters asked for are differentiated.
    assert sorted(s.name for s in linkage._sensitivities) == ["a", "b", "d"]


def test_positions_derive_no_sensitivities():
    linkage = CATALOG["watt2"]()
    scene = Scene(linkage, ["output", "F_x"], dict(EXAMPLE_VALUES["watt2"], theta=0.3))
    assert "__d_" not in scene.source and not linkage._sensitivities
    scene.evaluate()
    assert not linkage._sensitivities


def test_the_sensitivities_of_an_input_role_are_zero_and_of_a_fixed_pivot_too():
    result = Solver(CATALOG["fourbar"](), ["crank__d_a", "A_x__d_a", "D_x__d_d", "D_x__d_a"])(
        theta=[0.1, 2.0], a=20.0, b=66.0, c=56.0, d=80.0)
    assert result["crank__d_a"].tolist() == [0.0, 0.0] and result["A_x__d_a"].tolist() == [0.0, 0.0]
    assert result["D_x__d_d"].tolist() == [1.0, 1.0] and result["D_x__d_a"].tolist() == [0.0, 0.0]


@pytest.mark.parametrize("name, why", [
    ("rocker_speed__d_a", "positions"),
    ("phidot__d_a", "positions"),
    ("singular__d_a", "positions"),
    ("rocker__d_a__d_b", "second derivative"),
    ("rocker__d_theta", "no output"),   # an input is not a parameter
    ("rocker__d_zz", "no output"),
    ("__d_a", "no output"),
])
def test_what_has_no_sensitivity_is_refused_by_name(name, why):
    with pytest.raises(ValueError, match=why):
        CATALOG["fourbar"]().output(name)


@pytest.mark.parametrize("outputs, parameters, why", [
    (["rocker"], ["zz"], "no parameter 'zz'"),
    (["rocker"], ["a", "a"], "once"),
    (["rocker", "rocker"], ["a"], "once"),
    (["rocker_speed"], ["a"], "positions"),
])
def test_design_jacobian_bad_requests(outputs, parameters, why):
    with pytest.raises(ValueError, match=why):
        DesignJacobian(CATALOG["fourbar"](), outputs, parameters)


def test_an_ambiguous_sensitivity_name_is_refused_and_plain_outputs_come_first():
    from symlink.symbolic.loops import Loop
    from symlink.symbolic.vectors import Vector, coordinates
    theta, beta, s = coordinates("theta beta s")
    y, odd = sp.symbols("y x__d_y", positive=True)
    closure = Loop(Vector(y, theta) + Vector(odd, beta) - Vector(s, 0) - Vector(1, sp.pi / 2), name="ABC")
    linkage = Linkage("odd names", [closure], inputs=[theta], unknowns=[beta, s],
                      points={"C": Vector(s, 0).as_sum(), "C__d_x": Vector(s, 0).as_sum(), "beta__d": None})
    assert linkage.output("beta__d_y") == 0  # point beta__d's y, not d(beta)/dy: a plain output comes first
    with pytest.raises(ValueError, match="ambiguous"):
        linkage.output("C__d_x__d_y")


def test_design_jacobian_matches_the_solver_and_broadcasts():
    linkage = CATALOG["fourbar"]()
    theta = np.linspace(0.0, 6.0, 12).reshape(3, 4)
    values, slopes = design_jacobian(linkage, ["C_x", "C_y"], ["a", "d"], theta=theta, a=20.0, b=66.0, c=56.0,
                                     d=80.0)
    assert slopes.shape == (3, 4, 2, 2) and values["C_x"].shape == (3, 4)
    plain = Solver(linkage, ["C_x", "C_y__d_d"])(theta=theta, a=20.0, b=66.0, c=56.0, d=80.0)
    assert np.allclose(values["C_x"], plain["C_x"], rtol=1e-14) and np.allclose(slopes[..., 1, 1], plain["C_y__d_d"],
                                                                                rtol=1e-13)
    assert design_jacobian(linkage, ["C_x", "C_y"], ["a", "d"], theta=0.0, a=20.0, b=66.0, c=56.0, d=80.0)[1].shape \
        == (2, 2)


def test_where_it_cannot_be_assembled_the_jacobian_is_nan():
    values, slopes = design_jacobian(CATALOG["fourbar"](), ["rocker"], None, theta=[0.0, 0.0],
                                     a=20.0, b=[66.0, 1.0], c=56.0, d=80.0)
    assert values["assembled"].tolist() == [True, False]
    assert np.isfinite(slopes[0]).all() and np.isnan(slopes[1]).all()


LENGTHS = {"fourbar": "abcd", "fivebar": "abcde"}


@settings(max_examples=15, deadline=None)
@given(st.sampled_from(sorted(LENGTHS)), st.floats(-math.pi, math.pi), st.floats(0.95, 1.05))
def test_scaling_every_length_turns_nothing(name, theta, scale):
    """Euler's theorem: angles are homogeneous of degree 0 in the lengths, points of degree 1, so
    sum_p p d(angle)/dp = 0 and sum_p p d(point)/dp = point (an identity the derivation does not use)."""
    linkage = CATALOG[name]()
    lengths = [s for s in linkage.parameters if s.name in LENGTHS[name]]
    angles = [q.name for q in linkage.unknowns]
    points = [f"{p}_{axis}" for p in linkage.points for axis in "xy"]
    values = {k: (v * scale if k in LENGTHS[name] else v) for k, v in EXAMPLE_VALUES[name].items()}
    found, slopes = design_jacobian(linkage, angles + points, [s.name for s in lengths], theta=theta, **values)
    assume(bool(found["assembled"]))
    weights = np.array([values[s.name] for s in lengths])
    euler = slopes @ weights
    size = sum(weights)
    assert np.allclose(euler[:len(angles)], 0.0, atol=1e-9 * np.max(np.abs(slopes[:len(angles)]) * size))
    assert np.allclose(euler[len(angles):], [found[p] for p in points], atol=1e-12 * size)


def test_exports_take_sensitivities_and_latex_shows_them_as_partial_derivatives():
    from symlink.io.export import export_texts
    outputs = ["rocker", "rocker__d_a", "C_x__d_d"]
    for fmt in ("numpy", "c", "octave", "javascript"):
        text = "\n".join(export_texts("fourbar", fmt, outputs).values())
        assert "rocker__d_a" in text and "C_x__d_d" in text and "phidot" not in text, fmt
    document = "\n".join(export_texts("fourbar", "latex", outputs).values())
    assert r"\frac{\partial \phi}{\partial a}" in document and r"\frac{\partial \beta}{\partial d}" in document
    assert r"\dot" not in document and r"\partial b}" not in document  # no rates, no parameter not asked for
    with pytest.raises(ValueError, match="no parameter 'theta'"):
        CATALOG["fourbar"]().equations(sensitivities=["theta"])


# --- the four-bar of path synthesis: its whole design space ---------------------------------------------

def synthesis_fourbar() -> Linkage:
    """A four-bar placed anywhere: crank pivot (x0, y0), frame at angle theta0, coupler point at r, gamma from B."""
    from symlink.symbolic.loops import Loop
    from symlink.symbolic.vectors import Vector, coordinates, lengths
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, d, r = lengths("a b c d r")
    x0, y0, theta0, gamma = sp.symbols("x0 y0 theta0 gamma", real=True)
    AB, BC, DC, AD = Vector(a, theta + theta0), Vector(b, beta), Vector(c, phi), Vector(d, theta0)
    pivot = Vector(x0, 0) + Vector(y0, sp.pi / 2)
    return Linkage("path fourbar", [Loop(AD + DC - BC - AB, name="ABCD")], inputs=[theta], unknowns=[beta, phi],
                   parameters=[a, b, c, d, gamma, r, theta0, x0, y0],
                   points={"P": pivot + AB + Vector(r, beta + gamma)})


def synthesis_closure(x, q, p):
    (theta,), (beta, phi) = x, q
    z = (p["a"] * mp.expj(theta + p["theta0"]) + p["b"] * mp.expj(beta) - p["c"] * mp.expj(phi)
         - p["d"] * mp.expj(p["theta0"]))
    return [z.real, z.imag]


def test_the_path_synthesis_fourbar_against_50_digits():
    """Pivot position, frame angle, four lengths and the coupler point: every parameter synthesis moves."""
    linkage = synthesis_fourbar()
    outputs = ["beta", "phi", "P_x", "P_y"]
    jacobian = DesignJacobian(linkage, outputs)
    assert jacobian.parameters == ["a", "b", "c", "d", "gamma", "r", "theta0", "x0", "y0"]
    rng = np.random.default_rng(RNG_SEED)
    checked = tries = 0
    while checked < 3:
        tries += 1
        assert tries < 60
        p = dict(a=rng.uniform(0.5, 1.5), b=rng.uniform(2, 4), c=rng.uniform(2, 4), d=rng.uniform(2.5, 4),
                 r=rng.uniform(0.5, 3), gamma=rng.uniform(-3, 3), theta0=rng.uniform(-3, 3),
                 x0=rng.uniform(-5, 5), y0=rng.uniform(-5, 5))
        theta = rng.uniform(-math.pi, math.pi)
        values, slopes = jacobian(theta=theta, branch=int(rng.choice([1, -1])), **p)
        if not bool(values["assembled"]):
            continue
        with mp.workdps(DPS):
            mp_p = {k: mp.mpf(v) for k, v in p.items()}
            x = [mp.mpf(theta)]
            q0 = mp_root(synthesis_closure, x, mp_p, [mp.mpf(float(values[u])) for u in ("beta", "phi")])
        if unit_column_determinant(synthesis_closure, x, mp_p, q0) < TOGGLE_GUARD:
            continue
        expected = mp_sensitivities(linkage, synthesis_closure, outputs, [theta], mp_p, q0)
        got = {sensitivity_name(o, name): slopes[k, j]
               for k, o in enumerate(outputs) for j, name in enumerate(jacobian.parameters)}
        error, where = worst_error(got, expected, linkage, outputs)
        assert error <= TOLERANCE, f"at theta = {theta}, {p}: {where}"
        checked += 1
