"""Inverse dynamics checked against references that share nothing with the derivation.

* Power balance: ``sum(Q_i q_i') = dT/dt + dV/dt - P_loads`` with T, V and the loads' power written
  here from the test's own centres of mass (tests/mp_dynamics.py), differentiated by mpmath at 50
  digits along the prescribed motion, on the four-bar, slider-crank, Watt II and the five-bar with
  one input held, for random mass properties and loads.
* Newton-Euler reactions: every body's forces and moments balance its inertia (with accelerations
  taken here by finite differences), the shaking force and moment equal the loads less the rate of
  momentum, and the Newton-Euler driving torque equals the virtual-power one.
* Statics: zero rates and a known load give the torque of the principle of virtual work, by hand.
"""
from __future__ import annotations

import random

import mpmath as mp
import numpy
import pytest
import sympy as sp

from mp_closures import DPS
from mp_dynamics import CASES, Motion, derivative, random_masses
from symlink.mechanism.catalog import CATALOG
from symlink.dynamics import BodyTorque, Damper, DynamicModel, Gravity, MassProperties, PointForce, Spring
from symlink.dynamics.inverse import driving_efforts, dynamic_linkage, reactions
from symlink.io.scene import Scene
from symlink.symbolic.vectors import acceleration, rate

#: Loads per case: a spring from a ground point, a damper and a force on moving points, a torque on a body.
LOADS = {"fourbar": ("D", "B", "A", "C", "C", "rocker"),
         "slider-crank": ("A", "B", "A", "C", "B", "conrod"),
         "watt2": ("G", "E", "A", "F", "C", "coupler2"),
         "fivebar": ("A", "C", "E", "B", "C", "coupler2")}


def symbolic_model(name: str) -> DynamicModel:
    """A model with every mass property and load a name (so one derivation serves every random draw)."""
    case = CASES[name]()
    spring_from, spring_to, damper_from, damper_to, force_at, torque_on = LOADS[name]
    masses = [MassProperties(body, f"m_{body}", f"r_{body}", f"delta_{body}", f"I_{body}", origin=origin)
              for body, (origin, _, _) in case.bodies.items()]
    loads = [Spring(spring_from, spring_to, "k", "L0"), Damper(damper_from, damper_to, "cd"),
             PointForce(force_at, "load_x", "load_y"), BodyTorque(torque_on, "T_load")]
    return DynamicModel(CATALOG[name](), masses, loads, Gravity("g_x", "g_y"))


_MODELS: dict[str, DynamicModel] = {}


def model_of(name: str) -> DynamicModel:
    if name not in _MODELS:
        _MODELS[name] = symbolic_model(name)
    return _MODELS[name]


def draw(name: str, seed: int):
    """Random mass properties, loads and input motion; the five-bar's second input held (no rate)."""
    rng = random.Random(seed)
    case = CASES[name]()
    values = {"k": rng.uniform(1, 20), "L0": rng.uniform(0.1, 2), "cd": rng.uniform(0.1, 3),
              "load_x": rng.uniform(-5, 5), "load_y": rng.uniform(-5, 5), "T_load": rng.uniform(-5, 5),
              "g_x": rng.uniform(-3, 3), "g_y": rng.uniform(-10, -5)}
    masses = random_masses(case, rng)
    for body, (mass, distance, angle, inertia) in masses.items():
        values.update({f"m_{body}": mass, f"r_{body}": distance, f"delta_{body}": angle, f"I_{body}": inertia})
    x0 = [rng.uniform(-3, 3)] + ([2.2] if name == "fivebar" else [])
    xdot = [rng.uniform(-4, 4)] + ([0.0] if name == "fivebar" else [])
    xddot = [rng.uniform(-6, 6)] + ([0.0] if name == "fivebar" else [])
    return case, values, masses, x0, xdot, xddot


def state(case, motion: Motion) -> dict:
    """Coordinates, rates and accelerations at t = 0 (names as symlink's symbols), 50 digits."""
    found = {}
    for k, name in enumerate(case.inputs):
        found[name], found[name + "dot"], found[name + "ddot"] = motion.x0[k], motion.xdot[k], motion.xddot[k]
    for k, name in enumerate(case.unknowns):
        found[name] = motion.q(mp.mpf(0))[k]
        found[name + "dot"] = derivative(lambda t: motion.q(t)[k])
        found[name + "ddot"] = derivative(lambda t: motion.q(t)[k], 2)
    return found


def evaluate(expr: sp.Expr, values: dict):
    """An expression of symlink's at 50 digits (its symbols by name)."""
    symbols = sorted(expr.free_symbols, key=lambda s: s.name)
    function = sp.lambdify(symbols, expr, modules="mpmath")
    with mp.workdps(DPS):
        return function(*(mp.mpf(values[s.name]) if not isinstance(values[s.name], mp.mpf) else values[s.name]
                          for s in symbols))


def power_reference(name: str, case, values: dict, masses: dict, motion: Motion):
    """dT/dt + dV/dt - P_loads at t = 0, from this test's own energy expressions."""
    spring_from, spring_to, damper_from, damper_to, force_at, torque_on = LOADS[name]
    p = {k: mp.mpf(v) for k, v in values.items()}
    gravity = mp.mpc(p["g_x"], p["g_y"])

    def centre(body, t):
        mass, distance, angle, inertia = masses[body]
        return motion.centre(body, mp.mpf(distance), mp.mpf(angle), t)

    def energy(t):
        kinetic = potential = mp.mpf(0)
        for body, (mass, _, _, inertia) in masses.items():
            v = mp.diff(lambda u: mp.re(centre(body, u)), t), mp.diff(lambda u: mp.im(centre(body, u)), t)
            w = mp.diff(lambda u: motion.body_angle(body, u), t)
            kinetic += (mp.mpf(mass) * (v[0] ** 2 + v[1] ** 2) + mp.mpf(inertia) * w ** 2) / 2
            g = centre(body, t)
            potential -= mp.mpf(mass) * (mp.re(gravity) * mp.re(g) + mp.im(gravity) * mp.im(g))
        stretch = abs(motion.point(case.points[spring_to], t) - motion.point(case.points[spring_from], t))
        return kinetic + potential + p["k"] * (stretch - p["L0"]) ** 2 / 2

    with mp.workdps(DPS):
        rate_of_energy = mp.diff(energy, 0)
        force_velocity = derivative(lambda t: motion.point(case.points[force_at], t))
        torque_speed = derivative(lambda t: motion.body_angle(torque_on, t))
        damper_rate = derivative(lambda t: abs(motion.point(case.points[damper_to], t)
                                               - motion.point(case.points[damper_from], t)))
        power = (p["load_x"] * mp.re(force_velocity) + p["load_y"] * mp.im(force_velocity)
                 + p["T_load"] * torque_speed - p["cd"] * damper_rate ** 2)
        return rate_of_energy - power


@pytest.mark.parametrize("name", ["fourbar", "slider-crank", pytest.param("watt2", marks=pytest.mark.slow), "fivebar"])
@pytest.mark.parametrize("seed", [1, pytest.param(2, marks=pytest.mark.slow)])
def test_power_balance(name, seed):
    """Q q' (the driving effort's power) equals the rate of energy less the loads' power, to 1e-12."""
    model = model_of(name)
    case, values, masses, x0, xdot, xddot = draw(name, seed)
    motion = Motion(case, case.parameters, x0, xdot, xddot)
    values.update(case.parameters)
    values.update(state(case, motion))
    outputs = dynamic_linkage(model).extras
    efforts = [outputs[model.input_effort_name(i)] for i in range(len(case.inputs))]
    with mp.workdps(DPS):
        power = sum(evaluate(e, values) * mp.mpf(values[q + "dot"]) for e, q in zip(efforts, case.inputs))
        expected = power_reference(name, case, values, masses, motion)
        assert abs(power - expected) <= mp.mpf("1e-12") * (abs(expected) + 1e-3), (power, expected)


@pytest.mark.parametrize("name", [pytest.param("fourbar", marks=pytest.mark.slow), "slider-crank"])
def test_generated_torque_matches_the_power_balance(name):
    """The NumPy module's torque (positions solved by it) matches the reference effort to 1e-9."""
    model = model_of(name)
    case, values, masses, x0, xdot, xddot = draw(name, 7)
    motion = Motion(case, case.parameters, x0, xdot, xddot)
    values.update(case.parameters)
    expected = power_reference(name, case, {**values}, masses, motion) / mp.mpf(xdot[0])
    arguments = {**values, "theta": x0[0], "thetadot": xdot[0], "thetaddot": xddot[0]}
    result = Scene(dynamic_linkage(model), ["input_torque"], arguments).evaluate()[1]
    assert float(result["input_torque"]) == pytest.approx(float(expected), rel=1e-9)


@pytest.mark.parametrize("name", [pytest.param("fourbar", marks=pytest.mark.slow), "slider-crank",
                                  pytest.param("watt2", marks=pytest.mark.slow)])
def test_bodies_balance_their_reactions(name):
    """Each moving body: joint forces + loads = m a_G and moments about G = I alpha (a_G by finite differences)."""
    model = model_of(name)
    case, values, masses, x0, xdot, xddot = draw(name, 3)
    motion = Motion(case, case.parameters, x0, xdot, xddot)
    values.update(case.parameters)
    values.update(state(case, motion))
    found = {key: evaluate(expr, values) for key, expr in reactions(model).items()}
    spring_from, spring_to, damper_from, damper_to, force_at, torque_on = LOADS[name]
    p = {k: mp.mpf(v) for k, v in values.items()}
    with mp.workdps(DPS):
        zero = mp.mpf(0)
        net = {body: [mp.mpc(0), zero] for body in case.bodies}  # force, moment about G

        def centre(body, t=zero):
            mass, distance, angle, inertia = masses[body]
            return motion.centre(body, mp.mpf(distance), mp.mpf(angle), t)

        def push(body, at, force):
            if body in net:
                net[body][0] += force
                arm = at - centre(body)
                net[body][1] += mp.re(arm) * mp.im(force) - mp.im(arm) * mp.re(force)

        point = {n: motion.point(f, zero) for n, f in case.points.items()}
        for joint in model.mechanism.joints:
            key = f"joint_{joint.name}"
            force = mp.mpc(found[key + "_x"], found[key + "_y"])
            first, second = joint.bodies
            push(second, point[joint.name], force)
            push(first, point[joint.name], -force)
            if key + "_moment" in found:  # a slider's couple, on its block and back on its guide
                for body, sign in ((second, 1), (first, -1)):
                    if body in net:
                        net[body][1] += sign * found[key + "_moment"]
        net["crank"][1] += found["input_torque"]
        gravity = mp.mpc(p["g_x"], p["g_y"])
        for body, (mass, _, _, _) in masses.items():
            push(body, centre(body), mp.mpf(mass) * gravity)
        length = point[spring_to] - point[spring_from]
        tension = p["k"] * (abs(length) - p["L0"])
        carriers = {n: next(b.name for b in model.mechanism.bodies if not b.is_ground
                            and (n in b.joints or n in b.points)) if any(
            not b.is_ground and (n in b.joints or n in b.points) for b in model.mechanism.bodies) else "ground"
            for n in case.points}
        push(carriers[spring_from], point[spring_from], tension * length / abs(length))
        push(carriers[spring_to], point[spring_to], -tension * length / abs(length))
        gap = point[damper_to] - point[damper_from]
        gap_rate = derivative(lambda t: abs(motion.point(case.points[damper_to], t)
                                            - motion.point(case.points[damper_from], t)))
        push(carriers[damper_from], point[damper_from], p["cd"] * gap_rate * gap / abs(gap))
        push(carriers[damper_to], point[damper_to], -p["cd"] * gap_rate * gap / abs(gap))
        push(carriers[force_at], point[force_at], mp.mpc(p["load_x"], p["load_y"]))
        net[torque_on][1] += p["T_load"]
        momentum_rate, angular_rate = mp.mpc(0), zero
        for body, (mass, _, _, inertia) in masses.items():
            a_g = derivative(lambda t: centre(body, t), 2)
            alpha = derivative(lambda t: motion.body_angle(body, t), 2)
            scale = abs(mp.mpf(mass) * a_g) + 1
            assert abs(net[body][0] - mp.mpf(mass) * a_g) < 1e-12 * scale, body
            assert abs(net[body][1] - mp.mpf(inertia) * alpha) < 1e-12 * (abs(alpha) + 1), body
        # The frame takes the loads on the moving parts less the rate of their momentum (all joints and drives).
        for body, (mass, _, _, inertia) in masses.items():
            g = centre(body)
            a_g = derivative(lambda t: centre(body, t), 2)
            inertia_force = mp.mpf(mass) * a_g
            momentum_rate += inertia_force
            angular_rate += (mp.re(g) * mp.im(inertia_force) - mp.im(g) * mp.re(inertia_force)
                             + mp.mpf(inertia) * derivative(lambda t: motion.body_angle(body, t), 2))
        ground_force = sum((-mp.mpc(found[f"joint_{j.name}_x"], found[f"joint_{j.name}_y"])
                            for j in model.mechanism.joints if j.grounded), mp.mpc(0))
        assert abs(mp.mpc(found["shaking_force_x"], found["shaking_force_y"]) - ground_force) < 1e-12
        external = mp.mpc(0)
        external_moment = p["T_load"]
        loads = [(carriers[spring_from], point[spring_from], tension * length / abs(length)),
                 (carriers[spring_to], point[spring_to], -tension * length / abs(length)),
                 (carriers[damper_from], point[damper_from], p["cd"] * gap_rate * gap / abs(gap)),
                 (carriers[damper_to], point[damper_to], -p["cd"] * gap_rate * gap / abs(gap)),
                 (carriers[force_at], point[force_at], mp.mpc(p["load_x"], p["load_y"]))]
        loads += [(body, centre(body), mp.mpf(mass) * gravity) for body, (mass, _, _, _) in masses.items()]
        for body, at, force in loads:
            if body != "ground":
                external += force
                external_moment += mp.re(at) * mp.im(force) - mp.im(at) * mp.re(force)
        shaking = mp.mpc(found["shaking_force_x"], found["shaking_force_y"])
        assert abs(shaking - (external - momentum_rate)) < 1e-12 * (abs(momentum_rate) + 1)
        assert abs(found["shaking_moment"] - (external_moment - angular_rate)) < 1e-12 * (abs(angular_rate) + 1)


@pytest.mark.parametrize("name", ["fourbar", "slider-crank", pytest.param("watt2", marks=pytest.mark.slow),
                                  pytest.param("fivebar", marks=pytest.mark.slow)])
def test_newton_euler_effort_equals_virtual_power(name):
    """Two formulations of the driving effort agree (solved reactions vs virtual power)."""
    model = model_of(name)
    case, values, masses, x0, xdot, xddot = draw(name, 5)
    motion = Motion(case, case.parameters, x0, xdot, xddot)
    values.update(case.parameters)
    values.update(state(case, motion))
    solved = reactions(model)
    for index, effort in enumerate(driving_efforts(model)):
        key = model.input_effort_name(index)
        by_power, by_forces = evaluate(effort, values), evaluate(solved[key], values)
        assert abs(by_power - by_forces) < 1e-12 * (abs(by_power) + 1)


def test_statics_slider_crank_by_virtual_work():
    """At rest with a force P along the slider's line, T = -P ds/dtheta (virtual work, by hand)."""
    model = DynamicModel(CATALOG["slider-crank"](), [], [PointForce("C", "P", 0, body="slider")])
    torque = dynamic_linkage(model).extras["input_torque"]
    a, b, offset, theta, P = 1.3, 4.1, 0.7, 0.9, 250.0
    root = numpy.sqrt(b * b - (offset - a * numpy.sin(theta)) ** 2)
    s = a * numpy.cos(theta) + root
    ds = -a * numpy.sin(theta) - (offset - a * numpy.sin(theta)) * (-a * numpy.cos(theta)) / root
    beta = numpy.arctan2(offset - a * numpy.sin(theta), s - a * numpy.cos(theta))
    values = {"a": a, "b": b, "offset": offset, "theta": theta, "P": P, "beta": beta, "s": s,
              "thetadot": 0.0, "thetaddot": 0.0, "betadot": 0.0, "sdot": 0.0, "betaddot": 0.0, "sddot": 0.0}
    found = float(evaluate(torque, values))
    assert found == pytest.approx(-P * ds, rel=1e-12)
    # The generated code, which solves its own positions, agrees.
    result = Scene(dynamic_linkage(model), ["input_torque", "joint_AS_y"], {"a": a, "b": b, "offset": offset, "theta": theta,
                                                                     "P": P}).evaluate()[1]
    assert float(result["input_torque"]) == pytest.approx(-P * ds, rel=1e-12)


def test_statics_fourbar_rocker_torque_by_virtual_work():
    """A couple T4 on the rocker at rest needs T = -T4 dphi/dtheta, dphi/dtheta = a sin(beta - theta) / (c sin(beta - phi))."""
    model = DynamicModel(CATALOG["fourbar"](), [MassProperties("coupler", 3.0)], [BodyTorque("rocker", "T4")])
    a, b, c, d, theta = 1.0, 3.0, 2.5, 3.2, 0.4
    with mp.workdps(DPS):
        beta, phi = CASES["fourbar"]().guess([mp.mpf(theta)], dict(a=a, b=b, c=c, d=d))
    ratio = a * mp.sin(beta - theta) / (c * mp.sin(beta - phi))
    values = {"a": a, "b": b, "c": c, "d": d, "theta": theta, "beta": beta, "phi": phi, "T4": 7.5}
    values.update({f"{q}{suffix}": 0 for q in ("theta", "beta", "phi") for suffix in ("dot", "ddot")})
    with mp.workdps(DPS):
        ratio = a * mp.sin(beta - theta) / (c * mp.sin(beta - phi))
        assert abs(evaluate(dynamic_linkage(model).extras["input_torque"], values) + 7.5 * ratio) < 1e-40


def test_a_torque_request_derives_no_reactions_and_positions_no_dynamics():
    """Laziness: the torque's program has the accelerations but no reaction; the rocker's has no rates."""
    linkage = dynamic_linkage(model_of("fourbar"))
    torque = linkage.program(["input_torque"])
    kept = {symbol for symbol, _ in torque.assignments}
    assert acceleration(sp.Symbol("phi", real=True)) in kept
    assert sp.count_ops(torque.outputs["input_torque"]) < sp.count_ops(linkage.extras["joint_A_x"])
    positions = linkage.program(["rocker"])
    assert not {rate(sp.Symbol(q, real=True)) for q in ("beta", "phi")} & {s for s, _ in positions.assignments}
    plain = CATALOG["fourbar"]().program(["rocker"])
    assert positions.assignments == plain.assignments and positions.outputs == plain.outputs
