"""Multi-loop joint forces as accurate as their conditioning allows: Watt II against a 50-digit Newton-Euler.

The reference is written here: the five moving bodies of the Watt II six-bar (crank AB, coupler BC, ternary
rocker DCE, coupler EF, output GF), their pins' forces and the driving torque as fifteen unknowns, the fifteen
force and moment balances assembled by hand from the test's own geometry (tests/mp_dynamics.py: positions
by circle intersection refined at 50 digits, rates and accelerations from the differentiated closure) and
solved by mpmath's LU at 50 digits.  symlink's generated float64 code must agree to 1e-14 of the largest
force (the shaking moment: of the largest force times the farthest pin's distance from the origin) at
crank angles a whole turn round, on both branches of both loops, away from the toggles (the systems there
are well conditioned: a few units of rounding is what their conditioning explains).  Two mass models: the
centres anywhere on their bodies, and every centre at a pin (zero lever arms, which change which pivots
the elimination takes).
"""
from __future__ import annotations

import math
import random

import mpmath as mp
import pytest

from mp_closures import DPS, watt2_positions
from mp_dynamics import CASES, Motion, derivative, random_masses
from symlink.bodies import mechanism
from symlink.catalog import watt2
from symlink.dynamics import BodyTorque, DynamicModel, Gravity, MassProperties, PointForce, dynamic_linkage
from symlink.solver import Solver

#: The pins of the hand model: (name, body that exerts the force, body that takes it); "ground" is the frame.
PINS = [("A", "ground", "crank"), ("B", "crank", "coupler"), ("C", "coupler", "rocker"), ("D", "ground", "rocker"),
        ("E", "rocker", "coupler2"), ("F", "coupler2", "output"), ("G", "ground", "output")]
#: The loads of the two models: gravity, a couple on one body and a force at F on the output rocker.
LOADS = {"centres anywhere": ((0.8, -9.81), ("coupler2", 2.5), (-3.0, 4.0)),
         "centres at pins": ((0.0, -9.81), ("output", 3.0), (0.0, 0.0))}


def masses(seed: int, at_joints: bool) -> dict:
    """Random mass properties; ``at_joints``: every centre at its body's frame origin (a pin), as often drawn."""
    found = random_masses(CASES["watt2"](), random.Random(seed))
    return {body: (m, 0.0, 0.0, inertia) if at_joints else (m, r, angle, inertia)
            for body, (m, r, angle, inertia) in found.items()}


@pytest.fixture(scope="module", params=sorted(LOADS))
def solver(request):
    """The generated forces of a Watt II with random masses (centres anywhere, or at pins) and loads."""
    case = CASES["watt2"]()
    found = masses(11, request.param == "centres at pins")
    loads = LOADS[request.param]
    model = DynamicModel(watt2(), [MassProperties(body, m, r, angle, inertia, origin=case.bodies[body][0])
                                   for body, (m, r, angle, inertia) in found.items()],
                         [BodyTorque(*loads[1]), PointForce("F", *loads[2], body="output")], Gravity(*loads[0]))
    linkage = dynamic_linkage(model)
    return Solver(linkage, list(linkage.force_outputs)), mechanism(linkage), found, loads


def hand_newton_euler(branch: tuple[int, int], x0: float, xdot: float, xddot: float, found: dict,
                      loads: tuple) -> dict:
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
        (gravity, load), (torque_on, load_torque) = (mp.mpc(*loads[0]), mp.mpc(*loads[2])), loads[1]
        for body, (mass, _, _, inertia) in found.items():
            row = row_of[body]
            applied = mp.mpf(mass) * gravity
            moment = zero
            if body == "output":
                applied += load
                arm = point["F"] - centre[body]
                moment += mp.re(arm) * mp.im(load) - mp.im(arm) * mp.re(load)
            if body == torque_on:
                moment += mp.mpf(load_torque)
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
    generated, found_mechanism, found, loads = solver
    parameters = CASES["watt2"]().parameters
    first_body = {joint.name: joint.bodies[0] for joint in found_mechanism.joints}
    for branch, x0, xdot, xddot in poses(24, 7):
        hand = hand_newton_euler(branch, x0, xdot, xddot, found, loads)
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

