"""The bodies and the dynamics read a linkage by its geometry, not by the order its sums are written in.

* A ground offset written as a sum of fixed vectors (``OP = OPx + OPy``) and subtracted whole in a loop
  (``OM + MQ - PQ - OP``, whose terms ``- OPx - OPy`` walk from P through the wrong corner) is the same
  four-bar as the one written in walking order: one ground body, pivots O and P where the user put them.
* A slider's pin written through the crank side of its loop (``C = AB + BC``) drives the dynamics as the
  same pin written through the guide side (``C = AC``); the driving force matches virtual work by hand.
* A block on an inclined guide has its centre of mass measured along and across the guide (the
  documented frame of :mod:`symlink.dynamics.model`): the guide's normal force and couple, the pin forces
  and the shaking moment agree with a Newton-Euler solve written here at 50 digits.
"""
from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
import sympy as sp

from symlink import Linkage, Loop, Vector, coordinates, lengths
from symlink.mechanism.bodies import GROUND, mechanism
from symlink.mechanism.catalog import watt2
from symlink.dynamics import BodyTorque, DynamicModel, Gravity, MassProperties, dynamic_linkage
from symlink.numeric.solver import Solver

DPS = 50


def offset_fourbar(order: str) -> Linkage:
    """A four-bar whose rocker pivot P = (px, py) is a sum of two fixed vectors, in one of several writings."""
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, px, py = lengths("a b c px py")
    OM, MQ, PQ = Vector(a, theta, "OM"), Vector(b, beta, "MQ"), Vector(c, phi, "PQ")
    OPx, OPy = Vector(px, 0, "OPx"), Vector(py, sp.pi / 2, "OPy")
    point = OPy + OPx if order == "point y first" else OPx + OPy
    loop = {"subtracted whole": OM + MQ - PQ - point,
            "walking order": OM + MQ - PQ - OPy - OPx,
            "point y first": OM + MQ - PQ - point,
            "added first": OPx + OPy + PQ - MQ - OM,
            "run split by the loop's start": -OPy + OM + MQ - PQ - OPx}[order]
    return Linkage("offset_fourbar", [Loop(loop, name="OMQP")], [theta], [beta, phi], parameters=[a, b, c, px, py],
                   points={"O": None, "M": OM.as_sum(), "Q": OM + MQ, "P": point},
                   roles={"crank": theta, "coupler": beta, "rocker": phi})


OFFSET = dict(a=1.0, b=3.2, c=2.4, px=2.9, py=0.8)
ORDERS = ["subtracted whole", "walking order", "point y first", "added first", "run split by the loop's start"]


@pytest.mark.parametrize("order", ORDERS)
def test_a_ground_offset_summed_from_fixed_vectors_is_one_ground_body_whatever_its_order(order):
    # Hand count: ground (O, P), crank OM, coupler MQ, rocker PQ: n = 4, pins O, M, Q, P: M = 9 - 8 = 1.
    found = mechanism(offset_fourbar(order))
    assert [body.name for body in found.bodies] == ["ground", "crank", "coupler", "rocker"]
    assert found.mobility == 1
    assert set(found.body(GROUND).joints) == {"O", "P"}
    assert {joint.name: set(joint.bodies) for joint in found.joints} == {
        "O": {GROUND, "crank"}, "M": {"crank", "coupler"}, "Q": {"coupler", "rocker"}, "P": {GROUND, "rocker"}}
    pivot = found.joint("P").position
    numbers = {s: OFFSET[s.name] for s in pivot.x.free_symbols | pivot.y.free_symbols}
    assert (float(pivot.x.subs(numbers)), float(pivot.y.subs(numbers))) == (OFFSET["px"], OFFSET["py"])


def test_two_points_summing_one_ground_offset_in_two_orders_are_one_point():
    base = offset_fourbar("subtracted whole")
    vectors = {v.name: v for _, v in base.loops[0].terms}
    both = Linkage("offset_fourbar", base.loops, base.inputs, base.unknowns, parameters=base.parameters,
                   points={**base.points, "P2": vectors["OPy"] + vectors["OPx"]}, roles=base.roles)
    found, alone = mechanism(both), mechanism(base)
    # P2 is the pivot P again (one node, named by the first point there): the same bodies and joints.
    assert found.mobility == 1 and set(found.body(GROUND).joints) == {"O", "P"}
    assert [(b.name, b.joints) for b in found.bodies] == [(b.name, b.joints) for b in alone.bodies]
    assert [(j.name, j.bodies) for j in found.joints] == [(j.name, j.bodies) for j in alone.joints]


def test_a_ground_sum_subtracted_whole_in_a_watt_six_bar():
    """Watt II's second loop written from D, its ground offset AG = AGx + AGy subtracted whole."""
    base = watt2()
    vectors = {v.name: v for loop in base.loops for _, v in loop.terms}
    AG = vectors["AGx"] + vectors["AGy"]
    second = Loop(vectors["DE"] + vectors["EF"] - vectors["GF"] - AG + vectors["AD"], name="DEFG")
    linkage = Linkage("watt_written_from_d", [base.loops[0], second], base.inputs, base.unknowns,
                      parameters=base.parameters, points={**base.points, "G": AG}, roles=base.roles)
    found, expected = mechanism(linkage), mechanism(base)
    assert found.mobility == expected.mobility == 1
    assert {j.name: set(j.bodies) for j in found.joints} == {j.name: set(j.bodies) for j in expected.joints}


def test_the_offset_fourbar_moves_the_same_whatever_the_order():
    """The rocker angle of every writing is the hand solution: C on the circles about M (radius b) and P (c)."""
    theta = np.linspace(-math.pi, math.pi, 9)[:-1]
    a, b, c, px, py = (OFFSET[k] for k in ("a", "b", "c", "px", "py"))
    for order in ORDERS:
        found = Solver(offset_fourbar(order), ["rocker"])(theta=theta, **OFFSET, branch=1)
        for t, phi in zip(theta, found["rocker"]):
            M, P = complex(a * math.cos(t), a * math.sin(t)), complex(px, py)
            w = abs(P - M)
            along = (b * b - c * c + w * w) / (2 * w)
            unit = (P - M) / w
            Q = M + along * unit + math.sqrt(b * b - along * along) * 1j * unit  # left of M -> P: branch +1
            assert abs(complex(math.cos(phi), math.sin(phi)) - (Q - P) / c) < 1e-12, order


def slider_driven(pin: str) -> Linkage:
    """An in-line slider-crank driven by its slider s along AC; the pin C written through one side of the loop."""
    theta, beta, s = coordinates("theta beta s")
    a, b = lengths("a b")
    AB, BC, AC = Vector(a, theta, "AB"), Vector(b, beta, "BC"), Vector(s, 0, "AC")
    return Linkage("slider_driven", [Loop(AC - BC - AB, name="ABC")], [s], [theta, beta], parameters=[a, b],
                   points={"A": None, "B": AB.as_sum(), "C": AB + BC if pin == "crank side" else AC.as_sum()},
                   roles={"crank": theta, "conrod": beta, "slider": s})


def slider_model(pin: str) -> DynamicModel:
    masses = [MassProperties("crank", 1.2, 0.3, 0.2, 0.05), MassProperties("conrod", 2.0, 1.1, -0.1, 0.4),
              MassProperties("slider", 1.5, 0.2, 0.7, 0.03)]
    return DynamicModel(slider_driven(pin), masses, [BodyTorque("crank", "T_load")], Gravity(0.4, -9.81))


@pytest.fixture(scope="module")
def slider_solvers():
    found = {}
    for pin in ("crank side", "guide side"):
        linkage = dynamic_linkage(slider_model(pin))
        found[pin] = (Solver(linkage, list(linkage.force_outputs)), mechanism(linkage))
    return found


def test_a_slider_pin_written_through_the_crank_side_drives_the_dynamics(slider_solvers):
    a, b, T = 1.0, 3.0, 0.9
    s = np.array([2.3, 2.8, 3.4, 3.9])
    theta = np.arccos((a * a + s * s - b * b) / (2 * a * s))  # the crank above the guide: branch +1
    results = {}
    for pin, (solver, _) in slider_solvers.items():
        branches = {name: 1 for name in solver.branches}
        states = dict(s=s, sdot=[0.0, 1.3, -2.0, 0.4], sddot=[0.0, -4.0, 3.0, 2.5], a=a, b=b, T_load=T)
        results[pin] = solver(**states, **branches)
        assert bool(np.all(results[pin]["assembled"]))
    # Virtual work at rest, without gravity: P ds + T dtheta = 0 with s = a cos(theta) + sqrt(b^2 - a^2 sin^2).
    no_gravity = {}
    for pin in slider_solvers:
        model = DynamicModel(slider_driven(pin), [], [BodyTorque("crank", "T_load")])
        linkage = dynamic_linkage(model)
        static = Solver(linkage, ["input_force"])
        no_gravity[pin] = static(s=s, a=a, b=b, T_load=T, **{name: 1 for name in static.branches})["input_force"]
    ds = -a * np.sin(theta) - a * a * np.sin(theta) * np.cos(theta) / np.sqrt(b * b - (a * np.sin(theta)) ** 2)
    for pin in slider_solvers:
        assert np.allclose(no_gravity[pin], -T / ds, rtol=1e-12, atol=0)
    # With masses and motion: the two writings are one linkage.  A pin's force is that of its first body on
    # the other, so the order of the bodies at C (which differs) sets its sign.
    crank_side, guide_side = (slider_solvers[pin][1] for pin in ("crank side", "guide side"))
    flip = 1 if crank_side.joint("C").bodies == guide_side.joint("C").bodies else -1
    for name in slider_solvers["guide side"][0].outputs:
        sign = flip if name.startswith("joint_C_") else 1
        scale = max(np.max(np.abs(results["guide side"][n])) for n in ("input_force", "joint_A_x", "joint_A_y"))
        assert np.allclose(results["crank side"][name], sign * results["guide side"][name], rtol=0,
                           atol=1e-13 * scale), name


# --- A block on an inclined guide, by hand --------------------------------------------------------------

GAMMA = 0.45  # the guide's inclination
INCLINED = dict(a=1.1, b=3.3, gamma=GAMMA)
#: body: (mass, distance, angle from the body's axis, inertia); the block's axis is the guide.
MASSES = {"crank": (1.3, 0.4, 0.3, 0.07), "conrod": (2.2, 1.2, -0.2, 0.5), "slider": (1.6, 0.5, 1.1, 0.04)}
GRAVITY = (0.6, -9.81)


def inclined_slider_crank() -> Linkage:
    theta, beta, s = coordinates("theta beta s")
    a, b = lengths("a b")
    gamma = sp.Symbol("gamma", real=True)
    AB, BC, AC = Vector(a, theta, "AB"), Vector(b, beta, "BC"), Vector(s, gamma, "AC")
    return Linkage("inclined", [Loop(AC - BC - AB, name="ABC")], [theta], [beta, s], parameters=[a, b, gamma],
                   points={"A": None, "B": AB.as_sum(), "C": AC.as_sum()},
                   roles={"crank": theta, "conrod": beta, "slider": s})


def hand_newton_euler(theta0: float, speed: float, accel: float) -> dict:
    """Crank, rod and block by Newton-Euler, at 50 digits: positions by the circle about B, rates by mp.diff.

    Unknowns: F_A (ground on crank), F_B (crank on rod), F_C (rod on block), N (guide on block, along the
    guide's normal, at C), M (the guide's couple on the block), T (the drive on the crank).
    """
    with mp.workdps(DPS):
        a, b, gamma = (mp.mpf(INCLINED[k]) for k in ("a", "b", "gamma"))
        u, n = mp.expj(gamma), mp.expj(gamma + mp.pi / 2)

        def theta(t):
            return mp.mpf(theta0) + mp.mpf(speed) * t + mp.mpf(accel) * t * t / 2

        def pose(t):
            B = a * mp.expj(theta(t))
            along, across = mp.re(B * mp.conj(u)), mp.im(B * mp.conj(u))
            s = along + mp.sqrt(b * b - across * across)  # branch +1: the far position
            C = s * u
            return B, C, mp.arg(C - B)

        def centres(t):
            B, C, beta = pose(t)
            return {"crank": MASSES["crank"][1] * mp.expj(theta(t) + MASSES["crank"][2]),
                    "conrod": B + MASSES["conrod"][1] * mp.expj(beta + MASSES["conrod"][2]),
                    "slider": C + MASSES["slider"][1] * mp.expj(gamma + MASSES["slider"][2])}  # from the guide

        def second(function):
            return mp.mpc(mp.diff(lambda t: mp.re(function(t)), 0, 2), mp.diff(lambda t: mp.im(function(t)), 0, 2))

        B, C, beta = pose(mp.mpf(0))
        G = centres(mp.mpf(0))
        acc = {body: second(lambda t, body=body: centres(t)[body]) for body in MASSES}
        alpha = {"crank": mp.mpf(accel), "conrod": mp.diff(lambda t: pose(t)[2], 0, 2), "slider": mp.mpf(0)}
        g = mp.mpc(*GRAVITY)

        def cross(r, f):
            return mp.re(r) * mp.im(f) - mp.im(r) * mp.re(f)

        # Columns: FAx FAy FBx FBy FCx FCy N M T; rows: x, y, moment about G of crank, rod, block.
        rows, rhs = [], []

        def body(name, forces, couples):
            """forces: (column of x, sign, point) pairs for a force (x, y) in columns k, k + 1; couples: columns."""
            mass, _, _, inertia = MASSES[name]
            row_x, row_y, row_m = [mp.mpf(0)] * 9, [mp.mpf(0)] * 9, [mp.mpf(0)] * 9
            for column, sign, point, direction in forces:
                arm = point - G[name]
                if direction is None:  # a force with unknown x and y
                    row_x[column] += sign
                    row_y[column + 1] += sign
                    row_m[column] += -sign * mp.im(arm)
                    row_m[column + 1] += sign * mp.re(arm)
                else:  # a force of unknown size along a known direction
                    row_x[column] += sign * mp.re(direction)
                    row_y[column] += sign * mp.im(direction)
                    row_m[column] += sign * cross(arm, direction)
            for column in couples:
                row_m[column] += 1
            rows.extend([row_x, row_y, row_m])
            rhs.extend([mass * (mp.re(acc[name]) - mp.re(g)), mass * (mp.im(acc[name]) - mp.im(g)),
                        inertia * alpha[name]])

        body("crank", [(0, 1, mp.mpc(0), None), (2, -1, B, None)], [8])
        body("conrod", [(2, 1, B, None), (4, -1, C, None)], [])
        body("slider", [(4, 1, C, None), (6, 1, C, n)], [7])
        x = mp.lu_solve(mp.matrix(rows), mp.matrix(rhs))
        F_A, N, M, T = mp.mpc(x[0], x[1]), x[6], x[7], x[8]
        # The frame takes -F_A at A (the origin), -N n at C, -M, and -T from the drive.
        shaking = -cross(C, N * n) - M - T
        return {"joint_A": F_A, "joint_C_rod_on_block": mp.mpc(x[4], x[5]), "normal": N * n, "guide_moment": M,
                "input_torque": T, "shaking_moment": shaking, "shaking_force": -F_A - N * n,
                "scale": max(abs(v) for v in x) * (a + b + abs(C))}


@pytest.fixture(scope="module")
def inclined_solver():
    masses = [MassProperties(body, m, r, angle, inertia) for body, (m, r, angle, inertia) in MASSES.items()]
    model = DynamicModel(inclined_slider_crank(), masses, gravity=Gravity(*GRAVITY))
    linkage = dynamic_linkage(model)
    return Solver(linkage, list(linkage.force_outputs)), mechanism(linkage)


def test_the_block_frame_on_an_inclined_guide_is_the_guide(inclined_solver):
    """The block's frame has its origin at its pin C and its x axis along the guide (the module's docstring)."""
    solver, found = inclined_solver
    assert found.body("slider").joints[0] == "C"
    assert found.joint("C").bodies == ("slider", "conrod")  # the block's force on the rod: -F_C of the hand
    assert found.joint("AC").bodies == (GROUND, "slider")
    for theta, speed, accel in [(0.3, 2.0, -3.0), (1.9, -4.5, 6.0), (-2.4, 7.0, 0.5), (math.pi / 2, 0.0, 0.0)]:
        hand = hand_newton_euler(theta, speed, accel)
        result = solver(theta=theta, thetadot=speed, thetaddot=accel, **INCLINED, branch=1)
        scale = float(hand["scale"])
        for name, expected in [("joint_AC_moment", hand["guide_moment"]), ("shaking_moment", hand["shaking_moment"]),
                               ("input_torque", hand["input_torque"])]:
            assert abs(float(result[name]) - float(expected)) <= 1e-12 * scale, (name, theta)
        for name, expected in [("joint_A", hand["joint_A"]), ("joint_AC", hand["normal"]),
                               ("joint_C", -hand["joint_C_rod_on_block"]), ("shaking_force", hand["shaking_force"])]:
            got = complex(float(result[name + "_x"]), float(result[name + "_y"]))
            assert abs(got - complex(expected)) <= 1e-12 * scale, (name, theta)
