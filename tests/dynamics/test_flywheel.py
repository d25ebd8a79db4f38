"""Flywheel sizing: energy fluctuations of torques with closed-form integrals, a printed example, the speed band
checked by integrating the forward dynamics."""
from __future__ import annotations

import math

import numpy
import pytest

pytest.importorskip("scipy")

from symlink.mechanism.catalog import fourbar  # noqa: E402
from symlink.dynamics.flywheel import (FlywheelSizing, energy_fluctuation, flywheel_inertia,  # noqa: E402
                                       rpm_to_rad_per_s)
from symlink.dynamics.model import BodyTorque, Damper, DynamicModel, Gravity, MassProperties  # noqa: E402

SI = dict(a=0.2, b=0.66, c=0.56, d=0.80)  # the seed 003 crank-rocker in metres
BODIES = dict(m2=1.0, r2=0.1, I2=0.03, m3=2.0, r3=0.33, g3=0.3, I3=0.07, m4=1.5, r4=0.28, g4=-0.2, I4=0.04)


@pytest.fixture(scope="module")
def model() -> DynamicModel:
    """A four-bar with masses, gravity along -y and a load torque L on the crank shaft."""
    return DynamicModel(fourbar(), [
        MassProperties("crank", "m2", distance="r2", inertia="I2"),
        MassProperties("coupler", "m3", distance="r3", angle="g3", inertia="I3"),
        MassProperties("rocker", "m4", distance="r4", angle="g4", inertia="I4", origin="D")],
        loads=[BodyTorque("crank", "L")], gravity=Gravity(0, "g_y"))


# --- energy fluctuation of a torque ------------------------------------------------------

def test_a_sine_torque_fluctuates_by_its_amplitude():
    # T = T0 + A sin(2 theta): E = -A/2 cos(2 theta), from -A/2 (theta = 0, pi) to A/2 (pi/2, 3 pi/2): dE = A.
    angles = numpy.arange(48) * 2 * math.pi / 48
    cycle = energy_fluctuation(7.0 + 3.0 * numpy.sin(2 * angles))
    assert cycle.mean_torque == pytest.approx(7.0, rel=1e-14)
    assert cycle.energy_fluctuation == pytest.approx(3.0, rel=1e-13)
    assert cycle.energy_max[0] % math.pi == pytest.approx(math.pi / 2, abs=1e-12)
    assert cycle.energy_min[0] % math.pi == pytest.approx(0.0, abs=1e-12)


def test_a_torque_that_is_not_a_trigonometric_polynomial():
    # T = 1 / (2 - cos theta), mean 1/sqrt(3); E = (2/sqrt 3) atan(sqrt 3 tan(theta/2)) - theta/sqrt 3 on (-pi, pi),
    # extreme where cos theta = 2 - sqrt 3.  With 40 samples the extremes lie between samples: Newton finds them.
    root3 = math.sqrt(3)
    turn = math.acos(2 - root3)

    def energy(theta):
        return 2 / root3 * math.atan(root3 * math.tan(theta / 2)) - theta / root3

    angles = numpy.arange(40) * 2 * math.pi / 40
    cycle = energy_fluctuation(1 / (2 - numpy.cos(angles)))
    assert cycle.mean_torque == pytest.approx(1 / root3, rel=1e-12)
    assert cycle.energy_fluctuation == pytest.approx(energy(turn) - energy(-turn), rel=1e-9)
    assert cycle.energy_max[0] == pytest.approx(turn, abs=1e-7)
    assert cycle.energy_min[0] == pytest.approx(2 * math.pi - turn, abs=1e-7)
    sampled_only = cycle.energy.max() - cycle.energy.min()
    assert abs(sampled_only - cycle.energy_fluctuation) > 1e-4  # the refinement matters here


def test_a_printed_example_of_the_flywheel_formula():
    # The FOSSEE Python Textbook Companion of "Theory of Machines", chapter 16 (Turning Moment Diagrams and
    # Flywheel), Example 16.1 (https://tbc-python.fossee.in/convert-notebook/Theory_Of_Machines/ch16.ipynb):
    # a flywheel of 6.5 t with radius of gyration 1.8 m, energy fluctuation 56 kN m, mean speed 120 rpm, swings
    # between 121 and 119 rpm (printed rounded to the rpm).  Here: the inertia those printed speeds ask for
    # is m k^2 = 21060 kg m^2 within the rounding of the printed speeds (Cs = 2/120 +- 1/120).
    inertia = flywheel_inertia(56e3, rpm_to_rad_per_s(120.0), (121.0 - 119.0) / 120.0)
    assert inertia == pytest.approx(6500 * 1.8 ** 2, rel=0.02)
    # and the other way round: Cs = dE / (I w^2) gives 121.0 and 119.0 rpm to the printed digits
    cs = 56e3 / (6500 * 1.8 ** 2 * rpm_to_rad_per_s(120.0) ** 2)
    assert (round(120 * (1 + cs / 2)), round(120 * (1 - cs / 2))) == (121, 119)


# --- a crank under gravity: closed forms ----------------------------------------------------

def test_a_crank_under_gravity_closed_forms(model):
    # Only the crank is massive: T(theta) = -L - g_y m r cos(theta) at any constant speed, mean -L,
    # E = -g_y m r sin(theta), dE = 2 g m r.  Its own inertia Jc = I2 + m r^2 is constant, so by energy the
    # exact flywheel is the textbook one less Jc, and the textbook one gives Cs * I / (I + Jc).
    values = {**SI, **BODIES, "m3": 0.0, "I3": 0.0, "m4": 0.0, "I4": 0.0, "g_y": -9.81, "L": -4.0}
    w, cs = rpm_to_rad_per_s(200.0), 0.04
    sizing = FlywheelSizing(model, values, w, cs)
    m, r = values["m2"], values["r2"]
    assert sizing.mean_torque == pytest.approx(4.0, rel=1e-12)
    assert sizing.energy_fluctuation == pytest.approx(2 * 9.81 * m * r, rel=1e-12)
    textbook = 2 * 9.81 * m * r / (cs * w * w)
    assert sizing.inertia == pytest.approx(textbook, rel=1e-12)
    own = values["I2"] + m * r * r
    assert sizing.exact_inertia() == pytest.approx(textbook - own, rel=1e-9)
    band = sizing.speed_band()  # the forward dynamics over one cycle
    assert band.coefficient == pytest.approx(cs * textbook / (textbook + own), rel=1e-7)
    assert band.mean == pytest.approx(w, rel=1e-9)
    # The linkage needs more than the mean torque while E rises: the speed is lowest where E is largest
    # (theta = pi/2, E = g m r) and highest at 3 pi/2.
    angle, speed = band.motion.solution.sol(numpy.linspace(0.0, band.motion.time[-1], 2001))
    assert angle[numpy.argmin(speed)] == pytest.approx(math.pi / 2, abs=0.01)
    assert angle[numpy.argmax(speed)] == pytest.approx(3 * math.pi / 2, abs=0.01)
    assert sizing.cycle.energy_max[0] == pytest.approx(math.pi / 2, abs=1e-9)


# --- the four-bar: textbook, exact, and the integrated check --------------------------------------

@pytest.fixture(scope="module")
def sizing(model) -> FlywheelSizing:
    return FlywheelSizing(model, {**SI, **BODIES, "g_y": -9.81, "L": -15.0}, rpm_to_rad_per_s(300.0), 0.05)


def test_the_exact_flywheel_gives_the_band_asked_for_when_integrated(sizing):
    exact = sizing.exact_inertia()
    assert 0 < exact < sizing.inertia
    predicted = sizing.speed_from_energy(exact)
    assert predicted.coefficient == pytest.approx(0.05, rel=1e-10)
    band = sizing.speed_band(exact)
    assert band.coefficient == pytest.approx(0.05, rel=1e-7)
    assert band.mean == pytest.approx(sizing.mean_speed, rel=1e-9)
    assert band.highest == pytest.approx(predicted.highest, rel=1e-9)
    assert band.lowest == pytest.approx(predicted.lowest, rel=1e-9)


def test_the_textbook_flywheel_is_within_its_approximation(sizing):
    # The textbook inertia ignores the linkage's own inertia (here about a tenth of the flywheel):
    # the band it gives is narrower than asked, by about that fraction.
    band = sizing.speed_band()
    assert band.coefficient == pytest.approx(sizing.speed_from_energy(sizing.inertia).coefficient, rel=1e-7)
    assert 0.8 * 0.05 < band.coefficient < 0.05
    terms = sizing.dynamics.terms(sizing.cycle.angles)
    own = float(numpy.mean(terms["generalised_inertia"]))
    assert band.coefficient == pytest.approx(0.05 * sizing.inertia / (sizing.inertia + own), rel=0.02)


def test_a_heavy_flywheel_makes_the_textbook_exact(model):
    # As Cs -> 0 the flywheel dwarfs the linkage: textbook minus exact tends to the linkage's own inertia at
    # the angles of the extreme speeds, somewhere between its least and largest value over the cycle.
    values = {**SI, **BODIES, "g_y": -9.81, "L": -15.0}
    sizing = FlywheelSizing(model, values, rpm_to_rad_per_s(300.0), 0.001)
    own = sizing.dynamics.terms(sizing.cycle.angles)["generalised_inertia"]
    assert own.min() <= sizing.inertia - sizing.exact_inertia() <= own.max()
    assert own.max() < 0.01 * sizing.inertia


# --- bad input ----------------------------------------------------------------------------

GOOD = {**SI, **BODIES, "g_y": -9.81, "L": -15.0}
BAD = [
    (dict(values=GOOD, mean_speed=0.0, coefficient=0.05), "mean speed must be a positive"),
    (dict(values=GOOD, mean_speed=math.nan, coefficient=0.05), "mean speed must be a positive finite"),
    (dict(values=GOOD, mean_speed=10.0, coefficient=-0.1), "coefficient of speed fluctuation must be a positive"),
    (dict(values=GOOD, mean_speed=10.0, coefficient="0.1"), "coefficient of speed fluctuation must be a number"),
    (dict(values=GOOD, mean_speed=10.0, coefficient=0.05, samples=8), "samples must be"),
    (dict(values={**GOOD, "a": 0.4, "b": 0.3, "c": 0.35, "d": 0.5}, mean_speed=10.0, coefficient=0.05),
     "does not turn a whole cycle"),
]


@pytest.mark.parametrize("arguments, message", BAD)
def test_bad_input_is_refused(model, arguments, message):
    with pytest.raises(ValueError, match=message):
        FlywheelSizing(model, **arguments)


@pytest.mark.parametrize("torque, message", [([1.0, 2.0, 3.0], "at least 4"), ([1.0, math.nan, 2.0, 3.0], "finite")])
def test_bad_torque_samples_are_refused(torque, message):
    with pytest.raises(ValueError, match=message):
        energy_fluctuation(torque)


def test_flywheel_formula_refuses_a_coefficient_of_two_or_more():
    with pytest.raises(ValueError, match="below 2"):
        flywheel_inertia(1.0, 1.0, 2.0)


def test_speed_dependent_loads_are_refused():
    damped = DynamicModel(fourbar(), [MassProperties("crank", 1.0, distance=0.1, inertia=0.03)],
                          loads=[Damper("A", "C", 0.5)])
    with pytest.raises(ValueError, match="depend on speed"):
        FlywheelSizing(damped, SI, 10.0, 0.05)


# --- the series in bounded memory -----------------------------------------------------------

@pytest.mark.parametrize("count", [15, 16, 64, 101])
@pytest.mark.parametrize("fine", [1, 3, 8])
def test_the_series_on_a_grid_is_the_hand_function_and_its_integral(count, fine):
    """f = 3 + 2 sin 2x + cos 5x (plus the Nyquist cosine for an even count): values and integral by hand."""
    from symlink.dynamics.flywheel import _Periodic
    nyquist = count // 2 if count % 2 == 0 else 0

    def hand(x):
        return 3 + 2 * numpy.sin(2 * x) + numpy.cos(5 * x) + (numpy.cos(nyquist * x) if nyquist else 0)

    def hand_integral(x):  # of f - mean, from 0 (the Nyquist cosine is unresolved in the integral: left out)
        return (1 - numpy.cos(2 * x)) + numpy.sin(5 * x) / 5

    series = _Periodic(hand(numpy.arange(count) * 2 * math.pi / count), 2 * math.pi)
    grid = numpy.arange(fine * count) * 2 * math.pi / (fine * count)
    assert numpy.max(abs(series.value_on_grid(fine * count) - hand(grid))) < 1e-13
    if not nyquist:
        assert numpy.max(abs(series.integral_on_grid(fine * count) - hand_integral(grid))) < 1e-13
    off_grid = numpy.array([0.1, 1.0, 2.5, 6.0])
    assert numpy.max(abs(series.value(off_grid) - hand(off_grid))) < 1e-12  # summed directly, off the grid


def test_many_samples_run_in_bounded_memory():
    """200,000 samples: an outer product of points by wavenumbers would be 320 GB; by FFT and chunks it is not.

    Measured in a subprocess under a 2 GiB address-space limit: the series must stay far below it.
    """
    import resource
    import subprocess
    import sys
    script = ("import math, numpy\n"
              "from symlink.dynamics.flywheel import energy_fluctuation\n"
              "n = 200_000\n"
              "x = numpy.arange(n) * 2 * math.pi / n\n"
              "cycle = energy_fluctuation(1 + numpy.sin(3 * x))\n"
              "print(repr(cycle.energy_fluctuation))\n")

    def cap():
        resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, preexec_fn=cap,
                          env={"OPENBLAS_NUM_THREADS": "1", "PATH": "/usr/bin:/bin",
                               "PYTHONPATH": str(__import__("pathlib").Path(__file__).resolve().parents[2])},
                          timeout=300)
    assert done.returncode == 0, done.stderr
    assert float(done.stdout) == pytest.approx(2 / 3, rel=1e-10)  # E = (1 - cos 3x) / 3: from 0 to 2/3
