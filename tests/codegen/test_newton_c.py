"""The compiled Newton fallback (symlink.codegen.newton_c) against a 30-digit mpmath reference written here and
against the NumPy driver: the same positions, rates and accelerations, the same failures with the same messages.

The reference types the Stephenson II closure out by hand (``a e^{i theta} + b e^{i beta} + c e^{i mu} - d
- f e^{i phi} = 0`` and ``a e^{i theta} + e e^{i (beta + alpha)} + g e^{i eta} - d - h e^{i (phi + delta)} = 0``,
the catalog's loops), with its Jacobian and its velocity and acceleration systems differentiated by hand; the
positions are continued along the crank's turn by ``mpmath.findroot`` in small steps
(``tests/mp_closures.py``'s ``stephenson2_continued``), the rates solved by
``mpmath.lu_solve``.  Nothing of symlink's derivation is used.
"""
import re

import mpmath as mp
import numpy as np
import pytest
from mp_closures import stephenson2_continued

from symlink.numeric import compiled_library
from symlink.mechanism.catalog import fourbar, stephenson2
from symlink.codegen import newton_driver
from symlink.codegen.newton_c import newton_c_facts
from symlink.mechanism.joints import from_joints
from symlink.numeric.solver import NumericSolver

pytestmark = pytest.mark.skipif(not compiled_library.compiler_works(), reason="no working C compiler")

DIMENSIONS = dict(a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1, alpha=0.9, delta=0.3)
#: Two assemblies at theta = 0 whose crank turns fully (tests/test_solver.py found them with mpmath.findroot).
ASSEMBLIES = {"first": dict(beta=0.96, mu=0.27, phi=1.43, eta=-0.16),
              "second": dict(beta=-0.578922, mu=-0.61753, phi=-1.280091, eta=-1.189465)}
#: An assembly on a circuit that folds back near theta = 54.65 deg.
FOLDING = dict(beta=0.785649, mu=-2.447163, phi=2.88568, eta=-1.361976)
UNKNOWNS = ("beta", "mu", "phi", "eta")
THETADOT, THETADDOT = 3.0, 1.5


def _jacobian(q, p):
    beta, mu, phi, eta = q
    first, second = beta + p["alpha"], phi + p["delta"]
    return mp.matrix([[-p["b"] * mp.sin(beta), -p["c"] * mp.sin(mu), p["f"] * mp.sin(phi), 0],
                      [p["b"] * mp.cos(beta), p["c"] * mp.cos(mu), -p["f"] * mp.cos(phi), 0],
                      [-p["e"] * mp.sin(first), 0, p["h"] * mp.sin(second), -p["g"] * mp.sin(eta)],
                      [p["e"] * mp.cos(first), 0, -p["h"] * mp.cos(second), p["g"] * mp.cos(eta)]])


def reference(thetas, guess, substeps=4):
    """(q, qdot, qddot) at each crank angle at 30 digits, continued from the assembly nearest ``guess``."""
    positions = stephenson2_continued(DIMENSIONS, thetas, guess, substeps=substeps, dps=30, jacobian=_jacobian)
    with mp.workdps(30):
        p = {k: mp.mpf(v) for k, v in DIMENSIONS.items()}
        found = []
        for theta, q in zip(map(mp.mpf, thetas), positions):
            J, w, wdot = _jacobian(q, p), mp.mpf(THETADOT), mp.mpf(THETADDOT)
            st, ct = mp.sin(theta), mp.cos(theta)
            qdot = mp.lu_solve(J, mp.matrix([p["a"] * st * w, -p["a"] * ct * w] * 2))
            beta, mu, phi, eta = q
            bd, md, fd, ed = (qdot[i] for i in range(4))
            crank_x = p["a"] * (ct * w ** 2 + st * wdot)
            crank_y = p["a"] * (st * w ** 2 - ct * wdot)
            qddot = mp.lu_solve(J, mp.matrix([
                crank_x + p["b"] * mp.cos(beta) * bd ** 2 + p["c"] * mp.cos(mu) * md ** 2
                - p["f"] * mp.cos(phi) * fd ** 2,
                crank_y + p["b"] * mp.sin(beta) * bd ** 2 + p["c"] * mp.sin(mu) * md ** 2
                - p["f"] * mp.sin(phi) * fd ** 2,
                crank_x + p["e"] * mp.cos(beta + p["alpha"]) * bd ** 2 + p["g"] * mp.cos(eta) * ed ** 2
                - p["h"] * mp.cos(phi + p["delta"]) * fd ** 2,
                crank_y + p["e"] * mp.sin(beta + p["alpha"]) * bd ** 2 + p["g"] * mp.sin(eta) * ed ** 2
                - p["h"] * mp.sin(phi + p["delta"]) * fd ** 2]))
            found.append(([float(v) for v in q], [float(qdot[i]) for i in range(4)],
                          [float(qddot[i]) for i in range(4)]))
        return found


@pytest.fixture(scope="module")
def solvers():
    """The Stephenson II by the compiled driver and by the NumPy module."""
    compiled, plain = NumericSolver(stephenson2(), backend="compiled"), NumericSolver(stephenson2(), backend="numpy")
    assert (compiled.backend, plain.backend) == ("compiled", "numpy")
    return compiled, plain


@pytest.mark.parametrize("assembly", sorted(ASSEMBLIES))
def test_a_full_turn_against_30_digits_and_the_numpy_driver(solvers, assembly):
    compiled, plain = solvers
    guess = ASSEMBLIES[assembly]
    theta = np.radians(np.arange(0.0, 361.0, 1.0))
    values = dict(DIMENSIONS, theta=theta, thetadot=THETADOT, thetaddot=THETADDOT)
    got, numpy_got = compiled(guess=guess, **values), plain(guess=guess, **values)
    assert set(got) == set(numpy_got) and np.all(got["residual"] <= newton_driver.RESIDUAL_TOLERANCE)
    assert got["assembled"].all() and numpy_got["assembled"].all()
    for name, value in numpy_got.items():
        if name not in ("residual", "assembled"):
            scale = max(1.0, float(np.max(np.abs(value))))
            assert np.max(np.abs(got[name] - value)) < 1e-12 * scale, name
    every = 15
    for i, (q, qdot, qddot) in enumerate(reference(theta[::every], guess)):
        for k, name in enumerate(UNKNOWNS):
            assert abs(got[name][every * i] - q[k]) < 1e-12, (name, i)  # continued, not wrapped
            assert abs(got[name + "dot"][every * i] - qdot[k]) < 1e-12 * max(1.0, abs(qdot[k])), (name, i)
            assert abs(got[name + "ddot"][every * i] - qddot[k]) < 1e-12 * max(1.0, abs(qddot[k])), (name, i)
    # F, the rocker's joint with CF, from its own geometry: D + f e^{i phi}.
    F = DIMENSIONS["d"] + DIMENSIONS["f"] * np.exp(1j * got["phi"])
    assert np.max(np.abs(got["F_x"] + 1j * got["F_y"] - F)) < 1e-13


def test_the_two_assemblies_stay_apart(solvers):
    compiled, _ = solvers
    theta = np.radians(np.arange(0.0, 360.0, 5.0))
    first, second = (compiled(guess=ASSEMBLIES[name], theta=theta, **DIMENSIONS) for name in ("first", "second"))
    assert np.min(np.abs(np.remainder(second["phi"] - first["phi"] + np.pi, 2 * np.pi) - np.pi)) > 0.5


def _message(error):
    """The error's text without the condition number (1-norm in C, 2-norm in NumPy: they differ)."""
    return re.sub(r"\(condition [^)]*\)", "(condition ...)", str(error))


FAILURES = [
    # A circuit that folds back: continuation stops at 54.6 deg (the 50-digit check is in tests/test_solver.py).
    ("stephenson2", dict(DIMENSIONS, theta=np.radians(np.arange(0.0, 60.0, 5.0))), FOLDING,
     r"did not converge beyond theta = .*\(54\.6.* deg\) on the way to theta = .*\(55 deg\)"),
    # A four-bar whose crank reaches |theta| <= 93.82 deg only.
    ("fourbar", dict(a=50, b=20, c=40, d=30, theta=np.radians([30.0, 60.0, 90.0, 100.0, 110.0])),
     dict(beta=1.0, phi=2.0), r"did not converge beyond theta = .*\(93\.82.* deg\)"),
    # Not assembled at all: the ground is longer than the other three links together.
    ("fourbar", dict(a=1, b=1, c=1, d=100, theta=[0.0, 0.1]), dict(beta=1.0, phi=2.0),
     r"did not converge at theta = 0 rad \(0 deg\) from the initial guess"),
    # Assembled only folded flat (b + c = d - a): a singular Jacobian at the assembly.
    ("fourbar", dict(a=1, b=2, c=5, d=4, theta=[0.0, 0.1]), dict(beta=2.5, phi=3.0),
     r"singular Jacobian at theta = 0 rad \(0 deg\)"),
    # Bad arguments, checked by the NumPy module's own checks on both backends.
    ("fourbar", dict(a=20, b=66, c=56, d=80, theta=[0.0, np.nan]), dict(beta=0.3, phi=1.9), "theta must be finite"),
    ("fourbar", dict(a=20, b=66, c=56, d=80, theta=[0.0, 0.1]), [0.3], "must be 2 finite numbers"),
    ("fourbar", dict(a=20, b=66, c=56, d=80, theta=[[0.0, 0.1]]), [0.3, 1.9], "one-dimensional"),
]


@pytest.mark.parametrize("name, values, guess, message", FAILURES)
def test_failures_are_flagged_the_same_with_the_same_message(solvers, name, values, guess, message):
    compiled, plain = solvers if name == "stephenson2" else (NumericSolver(fourbar(), backend="compiled"),
                                                             NumericSolver(fourbar(), backend="numpy"))
    with pytest.raises(ValueError, match=message) as from_c:
        compiled(guess=guess, **values)
    with pytest.raises(ValueError, match=message) as from_numpy:
        plain(guess=guess, **values)
    assert _message(from_c.value) == _message(from_numpy.value)


def test_a_linkage_from_its_joints_that_needs_newton():
    # The Stephenson II drawn by its joints and driven at A: no loop-by-loop closed form (tests/test_joints.py).
    drawing = {"A": (0.0, 0.0), "D": (4.5, 0.0), "B": (0.3, 0.95), "C": (3.2, 2.0), "E": (1.5, 4.2),
               "F": (5.3, 2.8), "H": (4.8, 4.6)}
    links = {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C", "E"], "rocker": ["D", "F", "H"],
             "cf": ["C", "F"], "eh": ["E", "H"]}
    drawn = from_joints(links, drawing, driver="A")
    assert not drawn.linkage.has_closed_form
    compiled = NumericSolver(drawn.linkage, backend="compiled")
    assert compiled.backend == "compiled"
    at_drawing = compiled(guess=drawn.guess, **drawn.defaults)
    for point, (x, y) in drawing.items():  # the drawing itself is the reference at the drawn pose
        assert abs(float(np.ravel(at_drawing[point + "_x"])[0]) - x) < 1e-12, point
        assert abs(float(np.ravel(at_drawing[point + "_y"])[0]) - y) < 1e-12, point
    crank = drawn.defaults["theta_AB"]
    sweep = dict(drawn.defaults, theta_AB=crank + np.radians(np.arange(0.0, 40.0, 0.5)), theta_ABdot=2.0)
    got = compiled(guess=drawn.guess, **sweep)
    want = NumericSolver(drawn.linkage, backend="numpy")(guess=drawn.guess, **sweep)
    for name, value in want.items():
        if name not in ("residual", "assembled"):
            assert np.max(np.abs(got[name] - value)) < 1e-12 * max(1.0, float(np.max(np.abs(value)))), name
    # Every link keeps its length along the sweep: |C - B| = BC, |F - C| = CF.
    for first, second, length in (("B", "C", "BC"), ("C", "F", "CF"), ("E", "H", "EH")):
        gap = np.hypot(got[second + "_x"] - got[first + "_x"], got[second + "_y"] - got[first + "_y"])
        assert np.max(np.abs(gap - drawn.defaults[length])) < 1e-12


def test_the_backend_switch(monkeypatch):
    plain = NumericSolver(fourbar(), backend="numpy")
    assert plain.backend == "numpy" and plain._build is None
    monkeypatch.setenv("SYMLINK_BACKEND", "numpy")
    assert NumericSolver(fourbar()).backend_choice == "numpy"
    monkeypatch.setenv("SYMLINK_BACKEND", "auto")
    automatic = NumericSolver(fourbar())
    assert automatic._build is None and automatic._compiled is None  # nothing derived or built before it is used
    values = dict(a=20, b=66, c=56, d=80, theta=np.radians(np.arange(0.0, 360.0, 10.0)), thetadot=10.5)
    first = automatic(guess=dict(beta=0.3, phi=1.9), **values)  # answered now, whichever backend is ready
    assert automatic.wait_for_backend(timeout=600) == "compiled"
    second = automatic(guess=dict(beta=0.3, phi=1.9), **values)
    assert np.max(np.abs(first["rocker_speed"] - second["rocker_speed"])) < 1e-12
    with pytest.raises(ValueError, match="backend must be one of auto, numpy, compiled; got 'C'"):
        NumericSolver(fourbar(), backend="C")


def test_the_c_driver_has_the_numpy_drivers_constants_and_no_svd():
    source = newton_c_facts(stephenson2())["source"]
    for name in ("RESIDUAL_TOLERANCE", "SINGULAR_CONDITION", "POSITION_TOLERANCE", "MAX_PREDICTION",
                 "MAX_CORRECTION", "CONTRACTION", "MIN_FRACTION"):
        found = re.search(rf"symlink_{name.lower()} = ([^;]+);", source)
        assert found and float(found.group(1)) == getattr(newton_driver, name), name
    for name in ("MAX_ITERATIONS", "ASSEMBLY_ITERATIONS"):
        assert f"symlink_{name.lower()} = {getattr(newton_driver, name)};" in source
    assert "malloc" not in source and "svd" not in source.lower()


def test_two_inputs_swept_together_agree_with_the_closed_form():
    # The five-bar has a closed form (symlink.numeric.solver.Solver), which the compiled Newton must reproduce on its
    # path for more than one input (the general velocity and acceleration systems).
    from symlink.mechanism.catalog import fivebar
    from symlink.numeric.solver import Solver
    linkage = fivebar()
    dimensions = dict(a=2.0, b=4.0, c=4.0, d=3.0, e=2.0)
    t = np.linspace(0.0, 1.0, 41)
    theta, psi = 1.0 + 0.8 * np.sin(2 * np.pi * t), 2.0 + 0.6 * np.cos(2 * np.pi * t)
    rates = dict(thetadot=1.1, psidot=-0.3, thetaddot=0.2, psiddot=0.5)
    names = ["beta", "phi", "betadot", "phidot", "betaddot", "phiddot"]
    closed = Solver(linkage, names, backend="numpy")(theta=theta, psi=psi, branch=1, **dimensions, **rates)
    start = {name: float(closed[name][0]) + 0.05 for name in ("beta", "phi")}
    solver = NumericSolver(linkage, backend="compiled")
    assert solver.backend == "compiled"
    got = solver(theta=theta, psi=psi, guess=start, **dimensions, **rates)
    for name in names:
        gap = np.abs(got[name] - closed[name])
        if name in ("beta", "phi"):
            gap = np.abs(np.remainder(gap + np.pi, 2 * np.pi) - np.pi)
        assert np.max(gap) < 1e-12 * max(1.0, float(np.max(np.abs(closed[name])))), name
