"""The driving torque as a tolerance output: its exact sensitivities against 50-digit central differences.

The reference shares nothing with symlink's derivation: the four-bar's kinematics at 50 digits
(tests/mp_closures.py, a Newton solve of the closure and linear solves for the rates), the
centres of mass placed in each body's documented frame (tests/mp_dynamics.py), and the
driving torque from the power balance written here, ``Q = d(T + V)/dt / thetadot`` (kinetic
energy T, gravity's potential V), differentiated in time by mpmath.  Each sensitivity is then
a central difference of that torque at 50 digits (step 1e-12: truncation error about 1e-24).
"""
from __future__ import annotations

import mpmath as mp
import numpy
import pytest

from mp_closures import DPS
from mp_dynamics import Motion, fourbar_case
from symlink.mechanism.catalog import fourbar
from symlink.dynamics import DynamicModel, Gravity, MassProperties, dynamic_linkage
from symlink.workshop.tolerance import Tolerance, stack_up

BODIES = ("crank", "coupler", "rocker")
GEOMETRY = {"a": 1.0, "b": 3.0, "c": 2.5, "d": 3.2}
MASSES = {"crank": (0.7, 0.4, 0.3, 0.05), "coupler": (1.9, 1.2, -0.4, 0.6), "rocker": (1.1, 0.9, 0.2, 0.3)}
MOTION = {"thetadot": 10.5, "thetaddot": -3.0}
GRAVITY = {"g_x": 0.0, "g_y": -9.81}
THETA = (0.7, 2.9)
#: Dimensions with a tolerance: the four lengths, some mass properties, the crank's speed.
TOLERANCES = {"a": 0.01, "b": 0.02, "c": 0.01, "d": 0.03, "m_coupler": 0.05, "I_rocker": Tolerance(sigma=0.01),
              "r_coupler": 0.02, "delta_rocker": 0.01, "thetadot": 0.2}


def _values() -> dict[str, float]:
    values = {**GEOMETRY, **MOTION, **GRAVITY, "branch": 1}
    for body, (mass, distance, angle, inertia) in MASSES.items():
        values.update({f"m_{body}": mass, f"r_{body}": distance, f"delta_{body}": angle, f"I_{body}": inertia})
    return values


def _mp_torque(values: dict, theta: float):
    """The driving torque at ``theta`` by the power balance at 50 digits."""
    case = fourbar_case()
    with mp.workdps(DPS):
        p = {k: mp.mpf(v) if not isinstance(v, mp.mpf) else v for k, v in values.items()}
        motion = Motion(case, {k: p[k] for k in GEOMETRY}, [mp.mpf(theta)], [p["thetadot"]], [p["thetaddot"]])

        def energy(t):
            total = mp.mpf(0)
            for body in BODIES:
                mass, distance, angle, inertia = (p[f"{kind}_{body}"] for kind in ("m", "r", "delta", "I"))

                def centre(u):
                    return motion.centre(body, distance, angle, u)
                vx = mp.diff(lambda u: mp.re(centre(u)), t)
                vy = mp.diff(lambda u: mp.im(centre(u)), t)
                omega = mp.diff(lambda u: motion.body_angle(body, u), t)
                g = centre(t)
                total += (mass * (vx ** 2 + vy ** 2) + inertia * omega ** 2) / 2
                total -= mass * (p["g_x"] * mp.re(g) + p["g_y"] * mp.im(g))
            return total

        return mp.diff(energy, 0) / p["thetadot"]


def _mp_sensitivity(name: str, theta: float) -> float:
    with mp.workdps(DPS):
        base = {k: mp.mpf(v) for k, v in _values().items()}
        h = mp.mpf("1e-12") * max(abs(base[name]), 1)
        ahead = _mp_torque({**base, name: base[name] + h}, theta)
        behind = _mp_torque({**base, name: base[name] - h}, theta)
        return float((ahead - behind) / (2 * h))


@pytest.fixture(scope="module")
def linkage():
    masses = [MassProperties(body, f"m_{body}", f"r_{body}", f"delta_{body}", f"I_{body}", origin=origin)
              for body, origin in zip(BODIES, ("A", "B", "D"))]
    return dynamic_linkage(DynamicModel(fourbar(), masses, gravity=Gravity("g_x", "g_y")))


def test_torque_and_its_sensitivities_equal_50_digit_differences(linkage):
    """Every sensitivity of the torque (by the lengths, the masses, their centres and the crank's speed) equals
    the 50-digit central difference of the power-balance torque to 1e-9 relative, and so do the worst-case
    and RSS bands made from them."""
    result = stack_up(linkage, "input_torque", _values(), TOLERANCES, inputs={"theta": list(THETA)})
    assert result.dimensions == tuple(TOLERANCES)
    expected = numpy.array([[_mp_sensitivity(name, theta) for theta in THETA] for name in TOLERANCES])
    torque = numpy.array([float(_mp_torque(_values(), theta)) for theta in THETA])
    numpy.testing.assert_allclose(result.nominal[0], torque, rtol=1e-9)
    scale = numpy.abs(expected).max(axis=0)  # a sensitivity that is nearly zero: 1e-9 of the largest
    assert numpy.all(numpy.abs(result.sensitivity[0] - expected) <= 1e-9 * scale), (result.sensitivity[0], expected)
    bands = numpy.array([TOLERANCES[n].band if isinstance(TOLERANCES[n], Tolerance) else TOLERANCES[n]
                         for n in TOLERANCES])
    sigmas = numpy.array([TOLERANCES[n].sigma if isinstance(TOLERANCES[n], Tolerance) else TOLERANCES[n] / 3
                          for n in TOLERANCES])
    numpy.testing.assert_allclose(result.worst_case[0], numpy.abs(expected).T @ bands, rtol=1e-9)
    numpy.testing.assert_allclose(result.rss[0], 3 * numpy.sqrt((expected ** 2).T @ sigmas ** 2), rtol=1e-9)


def test_a_mass_moves_the_torque_linearly_and_the_speed_quadratically(linkage):
    """The torque is linear in each mass (no curvature) and, at a given crank acceleration, quadratic in the
    crank's speed: Q = M thetaddot + M' thetadot^2 / 2 + gravity, so d2Q/dthetadot^2 = 2 (Q - Q at rest) /
    thetadot^2 with Q at rest (thetadot = 0) taken from the 50-digit reference."""
    result = stack_up(linkage, "input_torque", _values(), {"m_coupler": 0.05, "thetadot": 0.2},
                      inputs={"theta": list(THETA)})
    assert numpy.all(numpy.abs(result.curvature[0, 0]) < 1e-6 * numpy.abs(result.sensitivity[0, 0]))
    for k, theta in enumerate(THETA):
        moving = _mp_torque(_values(), theta)
        resting = _mp_torque({**_values(), "thetadot": mp.mpf("1e-30")}, theta)  # thetadot -> 0 (it divides)
        expected = float(2 * (moving - resting) / mp.mpf(MOTION["thetadot"]) ** 2)
        assert result.curvature[0, 1, k] == pytest.approx(expected, rel=1e-7)


def test_a_rate_output_names_the_input_rate_it_needs(linkage):
    values = _values()
    del values["thetadot"]
    with pytest.raises(ValueError, match="nominal: give the value of thetadot"):
        stack_up(linkage, "input_torque", values, {"a": 0.01}, inputs={"theta": [0.5]})


def test_the_rocker_speed_by_hand():
    """phidot = a thetadot sin(beta - theta) / (c sin(beta - phi)) (the C-program paper's formula), so its
    sensitivity by thetadot is phidot / thetadot exactly."""
    values = {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0, "branch": 1, "thetadot": 10.5}
    result = stack_up(fourbar(), "rocker_speed", values, {"thetadot": 0.3, "a": 0.05},
                      inputs={"theta": [0.3, 1.9]})
    numpy.testing.assert_allclose(result.sensitivity[0, 0], result.nominal[0] / 10.5, rtol=1e-13)


# --- the command line --------------------------------------------------------------------------

def _csv_rows(text: str) -> list[list[str]]:
    return [line.split(",") for line in text.splitlines()[1:]]


def test_command_torque_bands_equal_50_digit_differences(capsys):
    """symlink tolerance --masses ... --output input_torque: the worst case of bands on a and b is
    |dQ/da| 0.01 + |dQ/db| 0.02 from the 50-digit reference (its centres of mass at fixed distances along the
    links, as the command places them)."""
    from symlink.cli import main
    centres = ",".join(f"{MASSES[b][1]}:{MASSES[b][2]}" for b in BODIES)
    argv = ["tolerance", "fourbar", "--crank", "1", "--coupler", "3", "--rocker", "2.5", "--ground", "3.2",
            "--masses", ",".join(str(MASSES[b][0]) for b in BODIES),
            "--inertias", ",".join(str(MASSES[b][3]) for b in BODIES), "--centres", centres, "--gravity", "9.81",
            "--crank-speed", "10.5", "--crank-accel", "-3", "--tolerances", "a=0.01,b=0.02",
            "--output", "input_torque", "--units", "rad", "--angles", ",".join(map(str, THETA)), "--format", "csv"]
    assert main(argv) == 0
    rows = _csv_rows(capsys.readouterr().out)
    for row, theta in zip(rows, THETA):
        torque, worst = float(row[1]), float(row[2])
        assert torque == pytest.approx(float(_mp_torque(_values(), theta)), rel=1e-9)
        expected = abs(_mp_sensitivity("a", theta)) * 0.01 + abs(_mp_sensitivity("b", theta)) * 0.02
        assert worst == pytest.approx(expected, rel=1e-9)


def test_command_rocker_speed_bands_by_the_50_digit_four_bar(capsys):
    """--output rocker_speed --crank-speed 10.5: the nominal speed and the worst case of a band on a equal the
    50-digit four-bar's rocker speed (tests/references.py, linear solves of the differentiated loop) and its
    central difference in a; speeds stay in rad/s whatever --units."""
    from symlink.cli import main
    from tests.references import mp_fourbar
    argv = ["tolerance", "fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
            "--tolerances", "a=0.05", "--output", "rocker_speed", "--crank-speed", "10.5", "--angles", "40,250",
            "--format", "csv"]
    assert main(argv) == 0
    rows = _csv_rows(capsys.readouterr().out)
    for row, degrees in zip(rows, (40, 250)):
        with mp.workdps(DPS):
            theta = mp.radians(degrees)

            def speed(a):
                return mp_fourbar(a, 66, 56, 80, theta, 1, crank_speed=mp.mpf("10.5"))["phi_speed"]
            h = mp.mpf("1e-15")
            slope = (speed(20 + h) - speed(20 - h)) / (2 * h)
            assert float(row[1]) == pytest.approx(float(speed(mp.mpf(20))), rel=1e-12)
            assert float(row[2]) == pytest.approx(float(abs(slope) * mp.mpf("0.05")), rel=1e-9)


@pytest.mark.parametrize("extra, message", [
    (["--output", "input_torque", "--masses", "1,1,1", "--play", "B=0.01"], "--play is modelled for positions"),
    (["--inertias", "1,1,1"], "--inertias needs --masses"),
])
def test_command_dynamics_options_refused_where_they_do_not_apply(extra, message, capsys):
    from symlink.cli import main
    argv = ["tolerance", "fourbar", "--crank", "1", "--coupler", "3", "--rocker", "2.5", "--ground", "3.2",
            "--tolerance", "0.01", "--angles", "40"] + extra
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1
