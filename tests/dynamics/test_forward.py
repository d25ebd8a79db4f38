"""Forward dynamics: energy conservation against kinematics written here, the inverse dynamics fed back, closed forms.

The energy check does not use the model's M(q): the four-bar's positions are solved here
by intersecting two circles (mpmath, 30 digits), the velocity of every centre of mass and
the angular velocity of every link come from mpmath's numerical differentiation of those
positions with respect to the crank angle, and the kinetic and potential energies are
summed from them.
"""
from __future__ import annotations

import math
import sys

import mpmath
import numpy
import pytest

pytest.importorskip("scipy")

from symlink.mechanism.catalog import fourbar  # noqa: E402
from symlink.dynamics.forward import (ConstantTorque, ForwardDynamics, LinearMotor, equation_linkage,  # noqa: E402
                                      require_scipy, scalar_source)
from symlink.dynamics.model import Damper, DynamicModel, Gravity, MassProperties, Spring  # noqa: E402
from symlink.numeric.solver import Solver  # noqa: E402

GRASHOF = dict(a=20.0, b=66.0, c=56.0, d=80.0)  # the crank-rocker of the velocity paper (seed 003)
BODIES = dict(m2=1.0, r2=10.0, I2=30.0, m3=2.0, r3=33.0, g3=0.3, I3=700.0, m4=1.5, r4=28.0, g4=-0.2, I4=400.0)


@pytest.fixture(scope="module")
def model() -> DynamicModel:
    """A four-bar with a mass on every moving link (centres off the link lines) and gravity along -y."""
    return DynamicModel(fourbar(), [
        MassProperties("crank", "m2", distance="r2", inertia="I2"),
        MassProperties("coupler", "m3", distance="r3", angle="g3", inertia="I3"),
        MassProperties("rocker", "m4", distance="r4", angle="g4", inertia="I4", origin="D")],
        gravity=Gravity(0, "g_y"))


# --- the test's own four-bar (mpmath) ------------------------------------------------

def joints(theta, a, b, c, d, branch=1):
    """B and C (complex numbers) by intersecting the circles about B (radius b) and D (radius c)."""
    B = a * mpmath.expj(theta)
    D = mpmath.mpf(d)
    e = D - B
    distance = abs(e)
    along = (distance**2 + b**2 - c**2) / (2 * distance)
    across = mpmath.sqrt(b**2 - along**2)
    unit = e / distance
    # +1: C to the left of the directed line B -> D
    C = B + unit * (along + 1j * branch * across)
    return B, C


def centres(theta, p):
    """The centres of mass of crank, coupler and rocker, and the angles of the three links."""
    B, C = joints(theta, p["a"], p["b"], p["c"], p["d"])
    D = mpmath.mpf(p["d"])
    beta, phi = mpmath.arg(C - B), mpmath.arg(C - D)
    G2 = p["r2"] * mpmath.expj(theta)
    G3 = B + p["r3"] * mpmath.expj(beta + p["g3"])
    G4 = D + p["r4"] * mpmath.expj(phi + p["g4"])
    return (G2, G3, G4), (theta, beta, phi)


def energy(theta, speed, p) -> float:
    """Kinetic plus potential energy at one state, from the positions above and their derivatives in theta."""
    with mpmath.workdps(30):
        theta = mpmath.mpf(theta)
        kinetic = mpmath.mpf(0)
        masses, inertias = (p["m2"], p["m3"], p["m4"]), (p["I2"], p["I3"], p["I4"])
        for k in range(3):
            velocity = mpmath.diff(lambda t: centres(t, p)[0][k], theta) * speed
            omega = mpmath.diff(lambda t: _unwrapped(centres(t, p)[1][k], centres(theta, p)[1][k]), theta) * speed
            kinetic += masses[k] * abs(velocity)**2 / 2 + inertias[k] * omega**2 / 2
        positions = centres(theta, p)[0]
        potential = -sum(m * p["g_y"] * G.imag for m, G in zip(masses, positions))
        return float(kinetic + potential)


def _unwrapped(angle, near):
    return angle + 2 * mpmath.pi * mpmath.nint((near - angle) / (2 * mpmath.pi))


# --- energy ---------------------------------------------------------------------------

def conserved_energy(model, turns: float, samples: int):
    values = {**GRASHOF, **BODIES, "g_y": -9.81}
    dynamics = ForwardDynamics(model, values)
    speed = 12.0
    duration = turns * 2 * math.pi / speed
    motion = dynamics.simulate(0.0, speed, duration, samples=samples, rtol=1e-11, atol=1e-11)
    assert motion.finished, motion.message
    energies = numpy.array([energy(q, w, values) for q, w in zip(motion.angle, motion.speed)])
    kinetic_scale = energies.max() - energies.min() + abs(energies).max()
    return motion, energies, kinetic_scale


def test_energy_is_conserved_over_a_few_turns(model):
    motion, energies, scale = conserved_energy(model, turns=3, samples=25)
    assert motion.angle[-1] > 2 * 2 * math.pi  # it does go round
    assert numpy.ptp(motion.speed) > 0.1 * numpy.mean(motion.speed)  # the speed does vary: a real check
    assert numpy.ptp(energies) <= 1e-8 * scale


@pytest.mark.slow
def test_energy_is_conserved_over_a_hundred_turns(model):
    motion, energies, scale = conserved_energy(model, turns=100, samples=101)
    assert motion.angle[-1] > 95 * 2 * math.pi
    assert numpy.ptp(energies) <= 1e-7 * scale


# --- the inverse dynamics fed back ---------------------------------------------------------

@pytest.fixture(scope="module")
def loaded_model() -> DynamicModel:
    """The four-bar with gravity, a spring from the frame to the coupler and a damper on the rocker."""
    return DynamicModel(fourbar(), [
        MassProperties("crank", 0.4, distance=8.0, inertia=15.0),
        MassProperties("coupler", 1.2, distance=30.0, angle=0.1, inertia=500.0),
        MassProperties("rocker", 0.9, distance=25.0, inertia=250.0, origin="D")],
        loads=[Spring("D", "B", 0.8, free_length=60.0), Damper("A", "C", 0.05)], gravity=Gravity(0.0, -9.81))


def test_the_torque_of_the_inverse_dynamics_reproduces_the_motion(loaded_model):
    # Prescribed: speed(theta) = w0 (1 + eps sin theta), so theta'' = w0^2 (1 + eps sin theta) eps cos theta and
    # one turn takes 2 pi / (w0 sqrt(1 - eps^2)).  The torque that motion needs, fed to the forward dynamics
    # as a motor of the angle, must move the crank exactly so.
    w0, eps = 6.0, 0.3
    torque = Solver(equation_linkage(loaded_model), ["input_torque"])  # as in loaded_model.linkage

    def wanted(theta):
        return w0 * (1 + eps * math.sin(theta))

    def motor(theta, speed):
        acceleration = w0 * w0 * (1 + eps * math.sin(theta)) * eps * math.cos(theta)
        return float(torque(theta=theta, thetadot=wanted(theta), thetaddot=acceleration, **GRASHOF)["input_torque"])

    dynamics = ForwardDynamics(loaded_model, GRASHOF)
    period = 2 * math.pi / (w0 * math.sqrt(1 - eps * eps))
    motion = dynamics.simulate(0.0, wanted(0.0), period, motor, samples=40, rtol=1e-11, atol=1e-11)
    assert motion.finished, motion.message
    expected = numpy.array([wanted(q) for q in motion.angle])
    assert numpy.max(numpy.abs(motion.speed - expected)) <= 1e-8 * w0
    assert motion.angle[-1] == pytest.approx(2 * math.pi, abs=1e-8)
    # The load is not trivial: without the motor the crank would move otherwise.
    free = dynamics.simulate(0.0, wanted(0.0), period, samples=40)
    assert numpy.max(numpy.abs(free.speed - numpy.array([wanted(q) for q in free.angle]))) > 0.1


def test_vectorised_and_scalar_right_hand_sides_agree(loaded_model):
    dynamics = ForwardDynamics(loaded_model, GRASHOF)
    angles = numpy.linspace(-3.0, 3.0, 7)
    found = dynamics.terms(angles, 2.5)
    namespace: dict = {}
    exec(compile(scalar_source(equation_linkage(loaded_model)), "<test>", "exec"), namespace)  # symlink's generated code
    for k, q in enumerate(angles):
        inertia, slope, applied, assembled, margin = namespace["solve"](theta=q, thetadot=2.5, **GRASHOF)
        assert assembled and margin > 0
        assert inertia == pytest.approx(found["generalised_inertia"][k], rel=1e-12)
        assert slope == pytest.approx(found["generalised_inertia_slope"][k], rel=1e-12, abs=1e-9)
        assert applied == pytest.approx(found["applied_generalised_force"][k], rel=1e-12, abs=1e-9)


# --- closed forms ------------------------------------------------------------------------

def crank_only(**changes):
    """The model's values with only the crank massive: a compound pendulum about A."""
    return {**GRASHOF, **BODIES, "m3": 0.0, "I3": 0.0, "m4": 0.0, "I4": 0.0, "g_y": -9.81, **changes}


def test_a_pendulum_stops_and_reverses_where_its_energy_runs_out(model):
    values = crank_only()
    inertia = values["I2"] + values["m2"] * values["r2"] ** 2
    w0 = 1.0  # from the bottom, too slow to go over the top: sin(stop) = J w0^2 / (2 m g r) - 1
    stop = math.asin(inertia * w0 * w0 / (2 * values["m2"] * 9.81 * values["r2"]) - 1)
    motion = ForwardDynamics(model, values).simulate(-math.pi / 2, w0, 10.0, until_stop=True)
    assert len(motion.stops) == 1 and motion.stops[0].reverses
    assert motion.stops[0].angle == pytest.approx(stop, abs=1e-9)
    assert motion.stops[0].acceleration < 0
    assert motion.message.startswith("stopped")
    swinging = ForwardDynamics(model, values).simulate(-math.pi / 2, w0, 10.0)
    assert len(swinging.stops) >= 3  # a pendulum without damping swings on
    assert all(s.angle == pytest.approx(stop if s.angle > -math.pi / 2 else -math.pi - stop, abs=1e-8)
               for s in swinging.stops)


def test_a_linear_motor_spins_a_crank_up_exponentially(model):
    values = crank_only(g_y=0.0)
    inertia = values["I2"] + values["m2"] * values["r2"] ** 2
    stall, no_load = 50.0, 20.0  # J w' = stall (1 - w / no_load): w = no_load (1 - exp(-t stall / (J no_load)))
    motion = ForwardDynamics(model, values).simulate(0.0, 0.0, 20.0, LinearMotor(stall, no_load), samples=11)
    expected = no_load * (1 - numpy.exp(-motion.time * stall / (inertia * no_load)))
    assert numpy.max(numpy.abs(motion.speed - expected)) <= 1e-8 * no_load
    assert not motion.stops


def test_a_flywheel_on_the_input_adds_to_the_inertia(model):
    values = crank_only(g_y=0.0)
    inertia = values["I2"] + values["m2"] * values["r2"] ** 2
    dynamics = ForwardDynamics(model, values, input_inertia=370.0)
    assert float(dynamics.acceleration(1.0, 3.0, 100.0)) == pytest.approx(100.0 / (inertia + 370.0), rel=1e-13)
    motion = dynamics.simulate(0.0, 0.0, 2.0, ConstantTorque(100.0), samples=3)
    assert motion.angle[-1] == pytest.approx(0.5 * 100.0 / (inertia + 370.0) * 4.0, rel=1e-9)


def test_a_toggle_ends_the_motion_with_a_message_and_no_nan(model):
    # Not Grashof: the crank cannot pass theta_t, where B, C and D line up (b + c = BD).
    p = {**BODIES, "a": 40.0, "b": 30.0, "c": 35.0, "d": 50.0, "g_y": -9.81}
    toggle = math.acos((p["a"] ** 2 + p["d"] ** 2 - (p["b"] + p["c"]) ** 2) / (2 * p["a"] * p["d"]))
    dynamics = ForwardDynamics(model, p)
    motion = dynamics.simulate(0.0, 2.0, 5.0, ConstantTorque(500.0), samples=50)
    assert motion.toggle == pytest.approx(toggle, abs=1e-6) and motion.toggle <= toggle
    assert "toggle" in motion.message and not motion.finished
    assert numpy.all(numpy.isfinite(motion.angle)) and numpy.all(numpy.isfinite(motion.speed))
    assert numpy.all(motion.angle <= toggle)
    assert numpy.all(dynamics.terms(motion.angle, motion.speed)["assembled"])


# --- bad input ----------------------------------------------------------------------------

BAD_SETUPS = [
    (dict(values={**GRASHOF}), "needs values for"),
    (dict(values={**GRASHOF, **BODIES, "g_y": 1.0, "mass": 2.0}), "no parameter 'mass'"),
    (dict(values={**GRASHOF, **BODIES, "g_y": 1.0, "a": -1.0}), "a must be a positive"),
    (dict(values={**GRASHOF, **BODIES, "g_y": math.nan}), "g_y must be finite"),
    (dict(values={**GRASHOF, **BODIES, "g_y": 1.0}, branch=2), r"branch must be \+1 or -1"),
    (dict(values={**GRASHOF, **BODIES, "g_y": 1.0}, branch={"branch_x": 1}), "a sign for each of branch"),
    (dict(values={**GRASHOF, **BODIES, "g_y": 1.0}, input_inertia=-1.0), "must not be negative"),
]


@pytest.mark.parametrize("arguments, message", BAD_SETUPS)
def test_bad_setups_are_refused(model, arguments, message):
    with pytest.raises(ValueError, match=message):
        ForwardDynamics(model, **arguments)


BAD_RUNS = [
    (dict(angle=0.0, speed=1.0, duration=0.0), "duration must be positive"),
    (dict(angle=math.inf, speed=1.0, duration=1.0), "angle must be a finite number"),
    (dict(angle=0.0, speed=1.0, duration=1.0, motor="fast"), "motor must be a callable"),
    (dict(angle=0.0, speed=1.0, duration=1.0, samples=1), "samples must be"),
]


@pytest.mark.parametrize("arguments, message", BAD_RUNS)
def test_bad_runs_are_refused(model, arguments, message):
    with pytest.raises(ValueError, match=message):
        ForwardDynamics(model, crank_only()).simulate(**arguments)


def test_a_start_that_cannot_be_assembled_or_has_no_inertia_is_refused(model):
    p = {**BODIES, "a": 40.0, "b": 30.0, "c": 35.0, "d": 50.0, "g_y": -9.81}
    with pytest.raises(ValueError, match="cannot be assembled at the starting angle"):
        ForwardDynamics(model, p).simulate(3.0, 0.0, 1.0)
    massless = crank_only(m2=0.0, I2=0.0)
    with pytest.raises(ValueError, match="give the bodies mass"):
        ForwardDynamics(model, massless).simulate(0.0, 0.0, 1.0)


def test_without_scipy_the_message_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "scipy.integrate", None)
    with pytest.raises(ImportError, match=r"pip install 'symlink-kinematics\[dynamics\]'"):
        require_scipy()
