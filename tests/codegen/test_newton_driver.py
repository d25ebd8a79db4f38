"""The Newton driver on its own: a four-bar closure written by hand here, against the 50-digit reference.

The driver's placeholders for the system (what a generated module defines)
are replaced with the four-bar's closure
``a e^{i theta} + b e^{i beta} - c e^{i phi} - d = 0``, its Jacobian and its
rate systems, differentiated by hand; nothing of symlink's derivation is used.
"""
import math

import numpy as np
import pytest

from references import mp_fourbar
from symlink.codegen import newton_driver as driver

DIMENSIONS = dict(a=20.0, b=66.0, c=56.0, d=80.0)


def _stack(items):
    return np.stack(np.broadcast_arrays(*items), axis=-1)


def closure(theta, a, b, c, d, beta, phi):
    F = _stack([a * np.cos(theta) + b * np.cos(beta) - c * np.cos(phi) - d,
                a * np.sin(theta) + b * np.sin(beta) - c * np.sin(phi)])
    J = np.stack(np.broadcast_arrays(_stack([-b * np.sin(beta), c * np.sin(phi)]),
                                     _stack([b * np.cos(beta), -c * np.cos(phi)])), axis=-2)
    return F, J, _stack([a + b + c + d] * 2), _stack([1.0, 1.0])


def velocity_rhs(theta, a, b, c, d, beta, phi, thetadot):
    return _stack([a * thetadot * np.sin(theta), -a * thetadot * np.cos(theta)])


def acceleration_rhs(theta, a, b, c, d, beta, phi, betadot, phidot, thetadot, thetaddot):
    return _stack([a * thetadot**2 * np.cos(theta) + a * thetaddot * np.sin(theta)
                   + b * betadot**2 * np.cos(beta) - c * phidot**2 * np.cos(phi),
                   a * thetadot**2 * np.sin(theta) - a * thetaddot * np.cos(theta)
                   + b * betadot**2 * np.sin(beta) - c * phidot**2 * np.sin(phi)])


def outputs(theta, a, b, c, d, beta, phi):
    return {"C_x": a * np.cos(theta) + b * np.cos(beta), "C_y": a * np.sin(theta) + b * np.sin(beta)}


@pytest.fixture
def fourbar_driver(monkeypatch):
    """The driver module with the hand-written four-bar as its system."""
    system = dict(INPUTS=("theta",), PARAMETERS=("a", "b", "c", "d"), UNKNOWNS=("beta", "phi"),
                  ANGLE_INPUTS=("theta",), ROLES={"crank": "theta", "rocker": "phi"},
                  _closure=closure, _velocity_rhs=velocity_rhs, _acceleration_rhs=acceleration_rhs, _outputs=outputs)
    for name, value in system.items():
        monkeypatch.setattr(driver, name, value)
    return driver


def reference(theta, branch=1, crank_speed=0.0, crank_accel=0.0, **dimensions):
    values = mp_fourbar(*(dimensions or DIMENSIONS).values(), theta, branch, crank_speed, crank_accel)
    return {name: float(value) for name, value in values.items()}


def angle_gap(first, second):
    return abs(math.remainder(first - second, 2 * math.pi))


def test_the_placeholders_say_that_the_system_is_generated():
    with pytest.raises(NotImplementedError, match="generated module defines"):
        driver._closure(0.0)


def test_a_full_turn_against_50_digits(fourbar_driver):
    theta = np.radians(np.arange(0.0, 361.0, 7.5))
    start = reference(0.0)
    guess = [start["beta"] + 0.05, start["phi"] - 0.05]
    shape, inputs, q, qdot, qddot, residual = fourbar_driver._sweep(
        (theta,), tuple(DIMENSIONS.values()), guess, (1.5,), (-0.4,))
    assert shape == theta.shape and np.all(residual <= fourbar_driver.RESIDUAL_TOLERANCE)
    for i, t in enumerate(theta):
        want = reference(float(t), 1, 1.5, -0.4)
        assert angle_gap(q[i, 0], want["beta"]) < 1e-13 and angle_gap(q[i, 1], want["phi"]) < 1e-13
        assert abs(qdot[i, 0] - want["beta_speed"]) < 1e-12 and abs(qdot[i, 1] - want["phi_speed"]) < 1e-12
        assert abs(qddot[i, 0] - want["beta_accel"]) < 1e-11 and abs(qddot[i, 1] - want["phi_accel"]) < 1e-11
    # Continued, not wrapped: one turn of the crank brings the rocker back where it was.
    assert abs(q[-1, 1] - q[0, 1]) < 1e-12


def test_the_other_branch_is_kept_from_its_guess(fourbar_driver):
    theta = np.radians(np.arange(0.0, 360.0, 30.0))
    start = reference(0.0, branch=-1)
    _, _, q, _, _, _ = fourbar_driver._sweep((theta,), tuple(DIMENSIONS.values()), [start["beta"], start["phi"]])
    for i, t in enumerate(theta):
        want = reference(float(t), branch=-1)
        assert angle_gap(q[i, 0], want["beta"]) < 1e-13 and angle_gap(q[i, 1], want["phi"]) < 1e-13


def test_results_name_unknowns_roles_rates_and_outputs(fourbar_driver):
    theta = np.radians([10.0, 20.0])
    start = reference(0.1)
    swept = fourbar_driver._sweep((theta,), tuple(DIMENSIONS.values()), {"beta": start["beta"], "phi": start["phi"]},
                                  (2.0,), (0.0,))
    result = fourbar_driver._results(*swept[:2], tuple(DIMENSIONS.values()), *swept[2:], order=2)
    assert set(result) == {"beta", "phi", "betadot", "phidot", "betaddot", "phiddot", "crank", "rocker",
                           "rocker_speed", "rocker_accel", "C_x", "C_y", "residual", "assembled"}
    want = reference(float(theta[1]), 1, 2.0)
    C = DIMENSIONS["d"] + DIMENSIONS["c"] * np.exp(1j * want["phi"])  # C from the rocker's side
    assert abs(complex(result["C_x"][1], result["C_y"][1]) - C) < 1e-12
    assert result["rocker_speed"][1] == result["phidot"][1] and abs(result["phidot"][1] - want["phi_speed"]) < 1e-12
    assert result["crank"].tolist() == theta.tolist() and result["assembled"].all()


def test_a_correction_that_would_leave_the_branch_is_refused(fourbar_driver):
    want = reference(0.5)
    parameters = tuple(np.asarray(v) for v in DIMENSIONS.values())
    near = np.array([[want["beta"] + 1e-3, want["phi"] - 1e-3]])
    far = np.array([[want["beta"] + 0.3, want["phi"] - 0.3]])  # a first step larger than MAX_CORRECTION
    q, good, singular, _ = fourbar_driver._correct((np.array([0.5]),), parameters, near)
    assert good[0] and not singular[0]
    assert angle_gap(q[0, 0], want["beta"]) < 1e-13 and angle_gap(q[0, 1], want["phi"]) < 1e-13
    _, good, singular, _ = fourbar_driver._correct((np.array([0.5]),), parameters, far)
    assert not good[0] and not singular[0]


def test_the_taylor_prediction_is_second_order(fourbar_driver):
    parameters = tuple(np.asarray(v) for v in DIMENSIONS.values())
    here = reference(0.4)
    errors = []
    for step in (0.02, 0.01):
        predicted, local = fourbar_driver._predict((0.4,), parameters, np.array([here["beta"], here["phi"]]),
                                                   (np.array([0.4 + step]),))
        there = reference(0.4 + step)
        assert local[0]
        errors.append(angle_gap(predicted[0, 1], there["phi"]))
    assert 6 < errors[0] / errors[1] < 10  # a third-order remainder: halving the step divides it by about 8


@pytest.mark.parametrize("dimensions, guess, message", [
    (dict(a=1.0, b=1.0, c=1.0, d=100.0), [1.0, 2.0], r"did not converge at theta = 0 rad \(0 deg\)"),
    (dict(a=1.0, b=2.0, c=5.0, d=4.0), [2.5, 3.0], r"singular Jacobian at theta = 0 rad \(0 deg\)"),
])
def test_assembly_failures_name_the_input(fourbar_driver, dimensions, guess, message):
    parameters = tuple(np.asarray(v) for v in dimensions.values())
    with pytest.raises(ValueError, match=message):
        fourbar_driver._assemble((np.array([0.0]),), parameters, np.array(guess))


def test_a_sweep_past_the_reachable_range_stops_there(fourbar_driver):
    # a=50, b=20, c=40, d=30: the crank reaches |theta| <= acos((50^2 + 30^2 - 60^2) / (2 * 50 * 30)) only.
    limit = math.degrees(math.acos((50**2 + 30**2 - 60**2) / (2 * 50 * 30)))
    with pytest.raises(ValueError, match=rf"did not converge beyond theta = .*\({limit:.4}.* deg\)"):
        fourbar_driver._sweep((np.radians([30.0, 60.0, 90.0, 100.0]),), (50.0, 20.0, 40.0, 30.0), [1.0, 2.0])


@pytest.mark.parametrize("inputs, parameters, guess, message", [
    (([[0.0, 1.0]],), (20.0, 66.0, 56.0, 80.0), [0.3, 1.9], "one-dimensional"),
    (([],), (20.0, 66.0, 56.0, 80.0), [0.3, 1.9], "empty"),
    (([0.0, np.nan],), (20.0, 66.0, 56.0, 80.0), [0.3, 1.9], "theta must be finite"),
    (([0.0],), ([20.0, 21.0], 66.0, 56.0, 80.0), [0.3, 1.9], "a must be one number"),
    (([0.0],), (20.0, 66.0, 56.0, 80.0), {"beta": 0.3}, "needs exactly beta, phi"),
    (([0.0],), (20.0, 66.0, 56.0, 80.0), [0.3], "must be 2 finite numbers"),
])
def test_bad_sweeps_are_refused(fourbar_driver, inputs, parameters, guess, message):
    with pytest.raises(ValueError, match=message):
        fourbar_driver._sweep(inputs, parameters, guess)


def test_every_name_the_driver_uses_is_defined():
    # What a linter's undefined-name check does: the driver runs inside generated modules, so a name it
    # uses must be its own, a placeholder that every generated module defines, a builtin, or numpy.
    import ast
    import builtins
    import inspect

    tree = ast.parse(inspect.getsource(driver))
    defined = set(dir(builtins)) | {"numpy"}
    defined |= {target.id for node in tree.body if isinstance(node, ast.Assign) for target in node.targets}
    defined |= {node.target.id for node in tree.body if isinstance(node, ast.AnnAssign)}
    defined |= {node.name for node in tree.body if isinstance(node, ast.FunctionDef)}
    for function in (node for node in tree.body if isinstance(node, ast.FunctionDef)):
        local = {a.arg for a in ast.walk(function.args) if isinstance(a, ast.arg)}
        local |= {n.id for n in ast.walk(function) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
        used = {n.id for n in ast.walk(function) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
        assert used <= defined | local, (function.name, sorted(used - defined - local))
