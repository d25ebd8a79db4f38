"""Runtime solvers: the generated Newton fallback (NumericSolver) against the closed forms, against 50 digits
on Stephenson II, and its errors."""
import itertools
import math

import numpy as np
import pytest

import mp_closures as ref
from symlink.mechanism.catalog import CATALOG, fivebar, fourbar, stephenson2
from symlink.symbolic.linkage import Linkage
from symlink.symbolic.loops import Loop
from symlink.numeric.solver import NumericSolver, Solver
from symlink.symbolic.vectors import Vector, coordinates, lengths

STEPHENSON2 = dict(a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1, alpha=0.9, delta=0.3)
STEPHENSON2_GUESS = dict(beta=0.96, mu=0.27, phi=1.43, eta=-0.16)

#: Closed-form linkages, their dimensions, and a start near branch +1 (or the one assembly).
CLOSED_FORMS = {
    "fourbar": (dict(a=20.0, b=66.0, c=56.0, d=80.0), dict(beta=0.3, phi=1.9)),
    "slider-crank": (dict(a=1.3, b=4.1, offset=0.7), dict(beta=0.0, s=5.0)),
    "inverted-slider-crank": (dict(a=2.0, d=1.2), dict(phi=0.5, r=1.0)),
    "watt2": (dict(a=1.0, b=3.5, c=3.0, d=3.2, e=2.0, f=4.0, g=3.0, alpha=0.6, gx=4.5, gy=3.5),
              dict(beta=1.0, phi=1.8, mu=0.2, psi=1.6)),
}


def angle_gap(first, second):
    return np.abs(np.remainder(np.asarray(first) - np.asarray(second) + np.pi, 2 * np.pi) - np.pi)


def kinematics(linkage):
    names = [u.name for u in linkage.unknowns]
    return names + [n + "dot" for n in names] + [n + "ddot" for n in names]


@pytest.mark.parametrize("name", sorted(CLOSED_FORMS))
def test_numeric_agrees_with_the_closed_form(name):
    linkage = CATALOG[name]()
    dimensions, guess = CLOSED_FORMS[name]
    theta = np.radians(np.arange(-180.0, 180.0, 3.0))
    numeric = NumericSolver(linkage)(theta=theta, guess=guess, thetadot=2.5, thetaddot=-0.7, **dimensions)
    assert np.all(numeric["residual"] <= 64 * np.finfo(float).eps)
    # The branch the numeric solver followed is the one whose closed form it matches.
    matched = 0
    for signs in itertools.product((1, -1), repeat=len(linkage.branches)):
        branches = {b.name: s for b, s in zip(linkage.branches, signs)}
        closed = Solver(linkage, kinematics(linkage))(theta=theta, thetadot=2.5, thetaddot=-0.7,
                                                      **dimensions, **branches)
        if any(angle_gap(closed[u.name][0], numeric[u.name][0]) > 1e-6 for u in linkage.unknowns):
            continue
        matched += 1
        for u in linkage.unknowns:
            is_angle = closed_is_angle(linkage, u)
            gap = angle_gap if is_angle else (lambda x, y: np.abs(x - y))
            assert np.max(gap(numeric[u.name], closed[u.name])) < 1e-12 * (1 if is_angle else 10)
            for suffix, tolerance in (("dot", 1e-11), ("ddot", 1e-10)):
                scale = max(1.0, float(np.max(np.abs(closed[u.name + suffix]))))
                assert np.max(np.abs(numeric[u.name + suffix] - closed[u.name + suffix])) < tolerance * scale
    assert matched == 1


def closed_is_angle(linkage, symbol):
    return any(symbol in v.angle.free_symbols for loop in linkage.loops for _, v in loop.terms)


def test_numeric_fivebar_sweeps_both_inputs_together():
    linkage = fivebar()
    dimensions = dict(a=2.0, b=4.0, c=4.0, d=3.0, e=2.0)
    t = np.linspace(0.0, 1.0, 41)
    theta, psi = 1.0 + 0.8 * np.sin(2 * np.pi * t), 2.0 + 0.6 * np.cos(2 * np.pi * t)
    rates = dict(thetadot=1.1, psidot=-0.3, thetaddot=0.2, psiddot=0.5)
    closed = Solver(linkage, kinematics(linkage))(theta=theta, psi=psi, branch=1, **dimensions, **rates)
    start = {name: float(closed[name][0]) + 0.05 for name in ("beta", "phi")}
    numeric = NumericSolver(linkage)(theta=theta, psi=psi, guess=start, **dimensions, **rates)
    for name in kinematics(linkage):
        gap = angle_gap if name in ("beta", "phi") else (lambda x, y: np.abs(x - y))
        assert np.max(gap(numeric[name], closed[name])) < 1e-11, name


def test_stephenson2_full_turn_against_a_50_digit_continuation():
    solver = NumericSolver(stephenson2())
    theta = np.radians(np.arange(0.0, 361.0, 15.0))
    result = solver(theta=theta, guess=STEPHENSON2_GUESS, thetadot=3.0, thetaddot=1.5, **STEPHENSON2)
    unknowns = ["beta", "mu", "phi", "eta"]
    reference = ref.continue_sweep(ref.stephenson2_closure, [(t,) for t in theta],
                                   [STEPHENSON2_GUESS[n] for n in unknowns], STEPHENSON2, substeps=6)
    for i, t in enumerate(theta):
        q, qdot, qddot, _ = ref.kinematics(ref.stephenson2_closure, [t], reference[i], STEPHENSON2,
                                           [3.0], [1.5], refine=False)
        for k, name in enumerate(unknowns):
            assert abs(result[name][i] - float(q[k])) < 1e-13, (name, i)   # continued, not wrapped
            assert abs(result[name + "dot"][i] - float(qdot[k])) < 1e-12 * max(1, abs(float(qdot[k])))
            assert abs(result[name + "ddot"][i] - float(qddot[k])) < 1e-11 * max(1, abs(float(qddot[k])))
    # The crank turned once and the linkage came back to where it started.
    assert np.max(np.abs(result["phi"][-1] - result["phi"][0])) < 1e-12


def test_coarse_and_fine_sweeps_follow_the_same_branch():
    solver = NumericSolver(stephenson2())
    fine = solver(theta=np.radians(np.arange(0.0, 360.0, 1.0)), guess=STEPHENSON2_GUESS, **STEPHENSON2)
    coarse = solver(theta=np.radians(np.arange(0.0, 360.0, 60.0)), guess=STEPHENSON2_GUESS, **STEPHENSON2)
    for name in ("beta", "mu", "phi", "eta", "E_x", "H_y"):
        assert np.max(np.abs(coarse[name] - fine[name][::60])) < 1e-12


#: Two more assemblies of the example at theta = 0 (found by mpmath.findroot from random starts; it has four):
#: one more that turns fully, and one on a circuit that folds back near theta = 54.65 deg.
OTHER_FULL_TURN = dict(beta=-0.578922, mu=-0.61753, phi=-1.280091, eta=-1.189465)
FOLDING = dict(beta=0.785649, mu=-2.447163, phi=2.88568, eta=-1.361976)


def test_each_assembly_is_kept_from_its_guess():
    solver = NumericSolver(stephenson2())
    theta = np.radians(np.arange(0.0, 360.0, 5.0))
    first = solver(theta=theta, guess=STEPHENSON2_GUESS, **STEPHENSON2)
    second = solver(theta=theta, guess=OTHER_FULL_TURN, **STEPHENSON2)
    assert np.min(angle_gap(second["phi"], first["phi"])) > 0.5
    reference = ref.continue_sweep(ref.stephenson2_closure, [(t,) for t in theta[::9]],
                                   list(OTHER_FULL_TURN.values()), STEPHENSON2, substeps=8)
    for i, q in enumerate(reference):
        for k, name in enumerate(OTHER_FULL_TURN):
            assert abs(second[name][9 * i] - float(q[k])) < 1e-13


def test_a_circuit_that_folds_back_stops_with_the_input_value():
    solver = NumericSolver(stephenson2())
    reached = solver(theta=np.radians(np.arange(0.0, 54.6, 1.0)), guess=FOLDING, **STEPHENSON2)
    assert np.all(reached["residual"] <= 64 * np.finfo(float).eps)
    with pytest.raises(ValueError, match=r"did not converge beyond theta = .*\(54\.6.* deg\) on the way to "
                                         r"theta = .*\(55 deg\)"):
        solver(theta=np.radians(np.arange(0.0, 60.0, 5.0)), guess=FOLDING, **STEPHENSON2)
    # Independently: 50-digit Newton continues to 54.6 deg but finds no real position at 54.7 deg.
    steps = [(math.radians(t),) for t in np.arange(0.0, 54.61, 0.5)]
    last = ref.continue_sweep(ref.stephenson2_closure, steps, list(FOLDING.values()), STEPHENSON2, substeps=2)[-1]
    with pytest.raises((ValueError, ZeroDivisionError)):
        ref.continue_sweep(ref.stephenson2_closure, [(math.radians(54.6),), (math.radians(54.7),)],
                           [float(v) for v in last], STEPHENSON2, substeps=4)


def test_points_roles_and_scalar_inputs():
    solver = NumericSolver(stephenson2())
    result = solver(theta=0.0, guess=STEPHENSON2_GUESS, **STEPHENSON2)
    assert result["phi"].shape == () and result["rocker"] == result["phi"]
    F = STEPHENSON2["d"] + STEPHENSON2["f"] * np.exp(1j * result["phi"])
    assert abs(complex(result["F_x"], result["F_y"]) - F) < 1e-14
    B = complex(result["B_x"], result["B_y"])
    assert abs(B - STEPHENSON2["a"]) < 1e-15


def test_sweep_beyond_the_reachable_range_names_the_input_value():
    # a=50, b=20, c=40, d=30: the crank reaches |theta| <= 93.82 deg only.
    solver = NumericSolver(fourbar())
    theta = np.radians([30.0, 60.0, 90.0, 100.0, 110.0])
    with pytest.raises(ValueError, match=r"did not converge beyond theta = .*\(93\.82.* deg\) on the way to "
                                         r"theta = .*\(100 deg\)"):
        solver(theta=theta, a=50, b=20, c=40, d=30, guess={"beta": 1.0, "phi": 2.0})


def test_no_assembly_near_the_first_input_is_an_error():
    with pytest.raises(ValueError, match=r"did not converge at theta = 0 rad \(0 deg\) from the initial guess"):
        NumericSolver(fourbar())(theta=[0.0, 0.1], a=1, b=1, c=1, d=100, guess={"beta": 1.0, "phi": 2.0})


def test_singular_jacobian_is_an_error():
    # a=1, b=2, c=5, d=4 at theta = 0: |BD| = 3 = c - b, coupler and rocker lie along one line.
    with pytest.raises(ValueError, match=r"singular Jacobian at theta = 0 rad \(0 deg\)"):
        NumericSolver(fourbar())(theta=[0.0, 0.1], a=1, b=2, c=5, d=4, guess={"beta": 2.5, "phi": 3.0})
    # A guess where coupler and rocker are parallel: J is exactly singular there.
    with pytest.raises(ValueError, match=r"singular Jacobian at theta = 0\.3 rad"):
        NumericSolver(fourbar())(theta=0.3, a=20, b=66, c=56, d=80, guess={"beta": 1.0, "phi": 1.0})


@pytest.mark.parametrize("change, message", [
    (dict(guess={"beta": 1.0}), "the initial guess needs exactly beta, phi"),
    (dict(guess=[1.0, float("nan")]), "the initial guess must be 2 finite numbers"),
    (dict(theta=[[0.0, 1.0]]), "one-dimensional"),
    (dict(theta=[]), "empty"),
    (dict(theta=[0.0, float("nan")]), "theta must be finite"),
    (dict(a=[20.0, 21.0]), "a must be one number"),
    (dict(a=-20.0), "a must be a positive finite length"),
    (dict(thetadot=float("inf")), "thetadot|must be finite"),
    (dict(omega=1.0), "takes theta, a, b, c, d, guess"),
])
def test_bad_input(change, message):
    values = dict(theta=[0.0, 0.1], a=20.0, b=66.0, c=56.0, d=80.0, guess={"beta": 0.3, "phi": 1.9})
    values.update(change)
    with pytest.raises(ValueError, match=message):
        NumericSolver(fourbar())(**values)


def test_a_slider_unknown_uses_a_length_unit():
    # A user's linkage whose unknowns are a length and an angle, solved only numerically.
    theta, beta, s = coordinates("theta beta s")
    a, b = lengths("a b")
    loop = Loop(Vector(a, theta) + Vector(b, beta) - Vector(s, 0), name="ABC")
    linkage = Linkage("rod", [loop], inputs=[theta], unknowns=[beta, s])
    result = NumericSolver(linkage)(theta=np.radians(np.arange(0, 360, 30.0)), a=1.0, b=3.0, guess=[0.1, 3.9])
    expected = np.cos(np.radians(np.arange(0, 360, 30.0))) + np.sqrt(9 - np.sin(np.radians(np.arange(0, 360, 30.0)))**2)
    assert np.max(np.abs(result["s"] - expected)) < 1e-14 * 4


def test_a_linkage_with_too_few_equations_is_refused():
    theta, p, q, r = coordinates("theta p q r")
    a, b, c = lengths("a b c")
    with pytest.raises(ValueError, match="exactly two unknowns"):
        Linkage("three", [Loop(Vector(a, theta) + Vector(b, p) + Vector(c, q) + Vector(1, r))],
                inputs=[theta], unknowns=[p, q, r])


def test_second_solver_comes_from_the_cache(tmp_path, monkeypatch):
    from symlink.numeric import cache
    from symlink.codegen import newton
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path))
    cache.clear_memory()
    first = NumericSolver(stephenson2())
    cache.clear_memory()  # a new process: only the disk entry is left

    def fail(linkage):
        raise AssertionError("derived again")
    monkeypatch.setattr(newton, "numeric_module", fail)
    second = NumericSolver(stephenson2())
    assert second.source == first.source
    cache.clear_memory()


@pytest.mark.parametrize("change, message", [
    (dict(theta=np.array([0.0, 1j])), "theta must be real numbers, got complex128"),
    (dict(a=20 + 0j), "a must be real numbers"),
    (dict(branch=0), r"branch must be \+1 or -1, got 0.0"),
    (dict(branch=np.nan), r"branch must be \+1 or -1, got nan"),
    (dict(theta=np.zeros(3), a=np.full(2, 20.0)), "do not broadcast together: theta has shape"),
    (dict(d=np.inf), "d must be a positive finite length, got inf"),
])
def test_the_closed_form_solver_checks_like_the_generated_functions(change, message):
    with pytest.raises(ValueError, match=message):
        Solver(fourbar(), ["rocker"])(**{**dict(theta=0.3, a=20.0, b=66.0, c=56.0, d=80.0, branch=1), **change})


@pytest.mark.parametrize("change, message", [
    (dict(theta=np.array([0.0, 0.1 + 1j])), "theta must be real numbers, got complex128"),
    (dict(a=np.inf), "a must be a positive finite length"),
    (dict(thetadot=1j), "thetadot must be real numbers"),
])
def test_the_numeric_solver_checks_like_the_generated_functions(change, message):
    values = dict(theta=[0.0, 0.1], a=20.0, b=66.0, c=56.0, d=80.0, guess={"beta": 0.3, "phi": 1.9})
    with pytest.raises(ValueError, match=message):
        NumericSolver(fourbar())(**{**values, **change})


def _seed001_fourbar(crank: str, lengths_: str) -> Linkage:
    """The worksheet's four-bar with its own names: crank angle ``crank``, lengths ``lengths_`` (crank first)."""
    q, beta, phi = coordinates(f"{crank} beta phi")
    a1, a2, a3, a4 = lengths(lengths_)
    AB, BC = Vector(a1, q, "AB"), Vector(a2, beta, "BC")
    loop = Loop(Vector(a4, 0, "AD") + Vector(a3, phi, "DC") - BC - AB, name="ABCD")
    return Linkage("seed001", [loop], inputs=[q], unknowns=[beta, phi], points={"B": AB.as_sum(), "C": AB + BC})


@pytest.mark.parametrize("crank, lengths_", [("q", "a1 a2 a3 a4"), ("theta", "q qdot qddot a4")])
def test_names_q_qdot_qddot_reach_no_local_of_the_numeric_module(crank, lengths_):
    # seed 001 calls the crank angle q; the Newton module's own locals once were q, qdot and qddot.
    linkage = _seed001_fourbar(crank, lengths_)
    names = lengths_.split()
    dimensions = dict(zip(names, (0.1, 0.4, 0.25, 0.30)))  # the worksheet's a1..a4 (m)
    angles = np.radians(np.arange(0.0, 361.0, 30.0))
    numeric = NumericSolver(linkage)(**{crank: angles, f"{crank}dot": 2.0}, **dimensions,
                                     guess={"beta": 0.9, "phi": 1.9})
    # B is the crank's end: a1 (cos q, sin q), by hand.
    assert np.max(np.abs(numeric["B_x"] - 0.1 * np.cos(angles))) < 1e-15
    assert np.max(np.abs(numeric["B_y"] - 0.1 * np.sin(angles))) < 1e-15
    # The loop closes at the solved angles, and C lies a3 from D = (a4, 0).
    C = numeric["C_x"] + 1j * numeric["C_y"]
    assert np.max(np.abs(np.abs(C - 0.30) - 0.25)) < 1e-14
    assert np.max(np.abs(np.abs(C - (numeric["B_x"] + 1j * numeric["B_y"])) - 0.4)) < 1e-14
    closed = Solver(linkage, ["phi", "phidot"])(**{crank: angles, f"{crank}dot": 2.0}, **dimensions, branch=1)
    branch = 1 if abs(angle_gap(closed["phi"][0], numeric["phi"][0])) < 1e-9 else -1
    closed = Solver(linkage, ["phi", "phidot"])(**{crank: angles, f"{crank}dot": 2.0}, **dimensions, branch=branch)
    assert np.max(angle_gap(closed["phi"], numeric["phi"])) < 1e-13
    assert np.max(np.abs(closed["phidot"] - numeric["phidot"])) < 1e-12


# --- pint quantities: converted consistently or refused ---------------------------------------------------------
def test_pint_quantities_convert_to_one_length_unit_and_radians():
    pint = pytest.importorskip("pint")
    units = pint.UnitRegistry()
    solver = Solver(fourbar(), ["rocker", "rocker_speed", "C_x"])
    mixed = solver(theta=units.Quantity([0.0, 30.0], "degree"), a=2 * units.cm, b=0.066 * units.m,
                   c=56 * units.mm, d=80 * units.mm, branch=1, thetadot=60 * units.rpm)
    # The same linkage by hand: lengths in cm (the first length's unit), angles in rad, rates in rad/s.
    plain = solver(theta=[0.0, math.pi / 6], a=2.0, b=6.6, c=5.6, d=8.0, branch=1, thetadot=2 * math.pi)
    for name in ("rocker", "rocker_speed", "C_x"):
        np.testing.assert_allclose(mixed[name], plain[name], rtol=1e-12)
    assert mixed.units["C_x"] == "centimeter" and mixed.units["rocker_speed"] == "rad/s"


def test_pint_length_rates_follow_the_length_unit():
    pint = pytest.importorskip("pint")
    units = pint.UnitRegistry()
    linkage = CATALOG["slider-crank"]()
    solver = Solver(linkage, ["s", "sdot"])
    quantities = solver(theta=0.4, a=1.3 * units.m, b=4100 * units.mm, offset=70 * units.cm, branch=1, thetadot=3.0)
    plain = solver(theta=0.4, a=1.3, b=4.1, offset=0.7, branch=1, thetadot=3.0)
    for name in ("s", "sdot"):
        np.testing.assert_allclose(quantities[name], plain[name], rtol=1e-12)
    assert quantities.units["s"] == "meter" and quantities.units["sdot"] == "meter/s"


@pytest.mark.parametrize("values, message", [
    (dict(a="mm"), "carry units but"),                 # one length with units, the others plain numbers
    (dict(a="s", b="mm", c="mm", d="mm"), "a must be a length"),
    (dict(a="mm", b="kg", c="mm", d="mm"), "b must be a length"),
    (dict(theta="mm"), "theta must be an angle"),
    (dict(thetadot="m"), "thetadot must be an angle per second"),
    (dict(branch="dimensionless"), "branch is a plain number"),
])
def test_pint_quantities_that_would_mix_are_refused(values, message):
    pint = pytest.importorskip("pint")
    units = pint.UnitRegistry()
    arguments = dict(theta=0.1, a=20.0, b=66.0, c=56.0, d=80.0, branch=1)
    arguments.update({name: units.Quantity(arguments.get(name, 1.0), unit) for name, unit in values.items()})
    with pytest.raises(ValueError, match=message):
        Solver(fourbar(), ["rocker", "rocker_speed"])(**arguments)


def test_numeric_solver_converts_quantities():
    pint = pytest.importorskip("pint")
    units = pint.UnitRegistry()
    solver = NumericSolver(fourbar())
    guess = {"beta": 1.0, "phi": 2.0}
    mixed = solver(theta=units.Quantity([0.0, 5.0], "degree"), a=20 * units.mm, b=6.6 * units.cm,
                   c=56 * units.mm, d=80 * units.mm, guess=guess)
    plain = solver(theta=[0.0, math.radians(5.0)], a=20.0, b=66.0, c=56.0, d=80.0, guess=guess)
    np.testing.assert_allclose(mixed["rocker"], plain["rocker"], rtol=1e-12)
    assert mixed.units["C_x"] == "millimeter"
