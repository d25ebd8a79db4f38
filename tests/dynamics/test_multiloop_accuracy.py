"""Multi-loop joint forces as accurate as their conditioning allows: Watt II against a 50-digit Newton-Euler.

The reference is written here: the five moving bodies of the Watt II six-bar (crank AB, coupler BC, ternary
rocker DCE, coupler EF, output GF), their pins' forces and the driving torque as fifteen unknowns, the fifteen
force and moment balances assembled by hand from the test's own geometry (tests/mp_dynamics.py: positions
by circle intersection refined at 50 digits, rates and accelerations from the differentiated closure) and
solved by mpmath's LU at 50 digits.  symlink's generated float64 code must agree to 1e-14 of the largest
force (the shaking moment: of the largest force times the farthest pin's distance from the origin) at
crank angles a whole turn round, on both branches of both loops, away from the toggles (the systems there
are well conditioned: a few units of rounding is what their conditioning explains).  Three models: the
centres anywhere on their bodies, every centre at a pin (zero lever arms, which change which pivots the
elimination takes), and every kind of load (a spring, a damper, a force, a couple, gravity), at a pose
where one Cramer rule on all the moment balances (before the block-wise solve) was off by 3e-14 of the
largest force in every pin of the first loop.
"""
from __future__ import annotations

import math
import random

import mpmath as mp
import pytest

from mp_closures import DPS, watt2_positions
from mp_dynamics import CASES, Motion, derivative, random_masses
from symlink.mechanism.bodies import mechanism
from symlink.mechanism.catalog import watt2
from symlink.dynamics import (BodyTorque, Damper, DynamicModel, Gravity, MassProperties, PointForce, Spring,
                              dynamic_linkage)
from symlink.numeric.solver import Solver

#: The pins of the hand model: (name, body that exerts the force, body that takes it); "ground" is the frame.
PINS = [("A", "ground", "crank"), ("B", "crank", "coupler"), ("C", "coupler", "rocker"), ("D", "ground", "rocker"),
        ("E", "rocker", "coupler2"), ("F", "coupler2", "output"), ("G", "ground", "output")]
#: The models: mass properties (seed of random ones, centres anywhere or at pins, or given) and loads: gravity,
#: a couple (body, value), a force (point, body, (x, y)), and a spring (first point, its body, second point, its
#: body, stiffness, free length) and a damper (the same, coefficient), or None.
MODELS = {
    "centres anywhere": dict(masses=(11, False), gravity=(0.8, -9.81), couple=("coupler2", 2.5),
                             force=("F", "output", (-3.0, 4.0)), spring=None, damper=None),
    "centres at pins": dict(masses=(11, True), gravity=(0.0, -9.81), couple=("output", 3.0),
                            force=("F", "output", (0.0, 0.0)), spring=None, damper=None),
    # Every kind of load (tests/dynamics/test_inverse.py's draw 15): one Cramer rule on all moment balances
    # lost 1.4e-13 of the largest force in the shaking moment at the first pose of SPRING_POSES.
    "spring and damper": dict(
        masses={"crank": (1.7860135737222873, 1.4997427278325672, -1.5617089070172683, 0.3035583179425249),
                "coupler": (1.5622914994776915, 0.49281436018039215, -1.4201144571152358, 0.22145729401168718),
                "rocker": (1.7867556460913288, 1.3243456475230688, 1.7856959542648845, 0.2175434055121903),
                "coupler2": (1.8872574201966448, 0.8159179254520995, -1.6116847882949021, 0.3916526085176158),
                "output": (1.1298129911305907, 0.21054300550780886, 0.3881495207118588, 0.31997333637980246)},
        gravity=(2.276947608808027, -6.593246677992927), couple=("coupler2", -4.831193457920238),
        force=("C", "coupler", (-3.4198727523525188, 4.863394516628233)),
        spring=("G", "output", "E", "rocker", 19.339600689490336, 0.12214391820506815),
        damper=("A", "crank", "F", "coupler2", 2.2343756974109388)),
}
#: Poses of the spring-and-damper model tried first: (branch, crank angle, speed, acceleration).
SPRING_POSES = [((1, 1), 0.41769425489701817, 3.441738944889651, 1.746855001204155)]


def masses(model: dict) -> dict:
    """body -> (mass, distance, angle, inertia): given, or random (every centre at its frame's origin, a pin)."""
    if isinstance(model["masses"], dict):
        return model["masses"]
    seed, at_pins = model["masses"]
    found = random_masses(CASES["watt2"](), random.Random(seed))
    return {body: (m, 0.0, 0.0, inertia) if at_pins else (m, r, angle, inertia)
            for body, (m, r, angle, inertia) in found.items()}


@pytest.fixture(scope="module", params=sorted(MODELS))
def solver(request):
    """The generated forces of a Watt II with the mass properties and loads of one of MODELS."""
    case = CASES["watt2"]()
    given = MODELS[request.param]
    found = masses(given)
    loads = [BodyTorque(*given["couple"]), PointForce(given["force"][0], *given["force"][2], body=given["force"][1])]
    if given["spring"] is not None:
        first, first_body, second, second_body, stiffness, free = given["spring"]
        loads.append(Spring(first, second, stiffness, free, first_body=first_body, second_body=second_body))
    if given["damper"] is not None:
        first, first_body, second, second_body, coefficient = given["damper"]
        loads.append(Damper(first, second, coefficient, first_body=first_body, second_body=second_body))
    model = DynamicModel(watt2(), [MassProperties(body, m, r, angle, inertia, origin=case.bodies[body][0])
                                   for body, (m, r, angle, inertia) in found.items()], loads,
                         Gravity(*given["gravity"]))
    linkage = dynamic_linkage(model)
    return Solver(linkage, list(linkage.force_outputs)), mechanism(linkage), found, given


def hand_newton_euler(branch: tuple[int, int], x0: float, xdot: float, xddot: float, found: dict,
                      given: dict) -> dict:
    """The pins' forces (of the first body of PINS on the second), the torque and the shaking loads, 50 digits."""
    case = CASES["watt2"]()
    case.guess = lambda x, p: watt2_positions(x, p, branch)
    motion = Motion(case, case.parameters, [x0], [xdot], [xddot])
    zero = mp.mpf(0)
    with mp.workdps(DPS):
        point = {name: motion.point(function, zero) for name, function in case.points.items()}
        bodies = list(found)
        row_of = {body: 3 * k for k, body in enumerate(bodies)}
        centre, accel, alpha = {}, {}, {}
        for body, (mass, distance, angle, inertia) in found.items():
            centre[body] = motion.centre(body, mp.mpf(distance), mp.mpf(angle), zero)
            accel[body] = derivative(lambda t, body=body: motion.centre(body, mp.mpf(found[body][1]),
                                                                        mp.mpf(found[body][2]), t), 2)
            alpha[body] = derivative(lambda t, body=body: motion.body_angle(body, t), 2)
        size = 3 * len(bodies)
        matrix = mp.zeros(size, size)
        rhs = mp.zeros(size, 1)

        def push(column: int, body: str, at, sign: int) -> None:
            """Unknown force (columns column, column + 1) acting on ``body`` at ``at`` with ``sign``."""
            if body == "ground":
                return
            row, arm = row_of[body], at - centre[body]
            matrix[row, column] += sign
            matrix[row + 1, column + 1] += sign
            matrix[row + 2, column] += -sign * mp.im(arm)
            matrix[row + 2, column + 1] += sign * mp.re(arm)

        for k, (name, giver, taker) in enumerate(PINS):
            push(2 * k, taker, point[name], 1)
            push(2 * k, giver, point[name], -1)
        matrix[row_of["crank"] + 2, size - 1] = 1  # the drive's torque on the crank
        # The loads: (body, point, force) and (body, couple), written from the model's description.
        forces_on = [(body, centre[body], mp.mpf(mass) * mp.mpc(*given["gravity"]))
                     for body, (mass, _, _, _) in found.items()]
        at, body, (fx, fy) = given["force"]
        forces_on.append((body, point[at], mp.mpc(fx, fy)))
        couples = [(given["couple"][0], mp.mpf(given["couple"][1]))]
        for kind in ("spring", "damper"):
            if given[kind] is None:
                continue
            first, first_body, second, second_body, coefficient = given[kind][:5]
            gap = point[second] - point[first]
            if kind == "spring":  # tension k (length - free length) pulls the two points together
                tension = mp.mpf(coefficient) * (abs(gap) - mp.mpf(given[kind][5]))
            else:  # tension c times the rate of the length
                tension = mp.mpf(coefficient) * derivative(lambda t: abs(motion.point(case.points[second], t)
                                                                         - motion.point(case.points[first], t)))
            forces_on += [(first_body, point[first], tension * gap / abs(gap)),
                          (second_body, point[second], -tension * gap / abs(gap))]
        for body, (mass, _, _, inertia) in found.items():
            row = row_of[body]
            applied = sum((f for b, _, f in forces_on if b == body), mp.mpc(0))
            moment = sum((mp.re(p - centre[body]) * mp.im(f) - mp.im(p - centre[body]) * mp.re(f)
                          for b, p, f in forces_on if b == body), zero)
            moment += sum((c for b, c in couples if b == body), zero)
            rhs[row] = mp.mpf(mass) * mp.re(accel[body]) - mp.re(applied)
            rhs[row + 1] = mp.mpf(mass) * mp.im(accel[body]) - mp.im(applied)
            rhs[row + 2] = mp.mpf(inertia) * alpha[body] - moment
        unknowns = mp.lu_solve(matrix, rhs)
        forces = {name: mp.mpc(unknowns[2 * k], unknowns[2 * k + 1]) for k, (name, _, _) in enumerate(PINS)}
        torque = unknowns[size - 1]
        # The frame takes minus each grounded pin's force and the drive's reaction torque.
        shaking = -sum((forces[name] for name, giver, _ in PINS if giver == "ground"), mp.mpc(0))
        moment = -sum((mp.re(point[name]) * mp.im(forces[name]) - mp.im(point[name]) * mp.re(forces[name])
                       for name, giver, _ in PINS if giver == "ground"), zero) - torque
        largest = max(max(abs(f) for f in forces.values()), abs(torque))
        reach = max(abs(p) for p in point.values())
        return {"forces": forces, "torque": torque, "shaking": shaking, "moment": moment, "largest": largest,
                "reach": reach}


def poses(count: int, seed: int):
    """``count`` crank angles a whole turn round (the four branch pairs in turn), random speeds and accelerations."""
    rng = random.Random(seed)
    for index in range(count):
        theta = -math.pi + 2 * math.pi * (index + rng.random()) / count
        yield ((1, 1), (1, -1), (-1, 1), (-1, -1))[index % 4], theta, rng.uniform(-4, 4), rng.uniform(-6, 6)


def test_watt2_joint_forces_and_shaking_to_rounding_of_the_largest_force(solver):
    generated, found_mechanism, found, given = solver
    parameters = CASES["watt2"]().parameters
    first_body = {joint.name: joint.bodies[0] for joint in found_mechanism.joints}
    tried = (SPRING_POSES if given["spring"] is not None else []) + list(poses(24, 7))
    for branch, x0, xdot, xddot in tried:
        hand = hand_newton_euler(branch, x0, xdot, xddot, found, given)
        result = generated(theta=x0, thetadot=xdot, thetaddot=xddot, **parameters,
                           **dict(zip(generated.branches, branch)))
        assert bool(result["assembled"])
        scale = float(hand["largest"])
        errors = {}
        for name, giver, _ in PINS:
            sign = 1 if first_body[name] == giver else -1  # symlink's pin force is that of its first body
            got = complex(float(result[f"joint_{name}_x"]), float(result[f"joint_{name}_y"]))
            errors[name] = abs(got - sign * complex(hand["forces"][name])) / scale
        errors["torque"] = abs(float(result["input_torque"]) - float(hand["torque"])) / scale
        errors["shaking force"] = abs(complex(float(result["shaking_force_x"]), float(result["shaking_force_y"]))
                                      - complex(hand["shaking"])) / scale
        errors["shaking moment"] = abs(float(result["shaking_moment"]) - float(hand["moment"])) / (
            scale * float(hand["reach"]))
        assert max(errors.values()) < 1e-14, (branch, x0, errors)

