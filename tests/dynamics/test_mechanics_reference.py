"""An independent multibody reference: the four-bar and the slider-crank in ``sympy.physics.mechanics``
(Lagrange's method).

The four-bar is set up from scratch as three bodies with generalised coordinates
theta, beta, phi, the loop closure as two holonomic constraints, gravity as a potential
and the driving torque as a couple on the crank's frame.  At a state (positions by
circle intersection, the dependent rates and accelerations from the differentiated
constraints, all in this file) Lagrange's equations with their two multipliers are a
linear system in the torque and the multipliers.  The torque must equal symlink's
``input_torque`` (virtual power over its closed forms) and the multipliers, which are
the force the coupler and rocker exert on each other at C, symlink's ``joint_C``.

The slider-crank likewise: crank, connecting rod and a block that slides along the
line ``y = offset`` (coordinates theta, beta, s; the guide's normal force does no work
and is not a multiplier), the closure at the block's pin C cut into two constraints
whose multipliers are the force between rod and block there.
"""
from __future__ import annotations

import functools
import math

import numpy as np
import pytest
import sympy as sp
from sympy.physics import mechanics as me

from symlink.mechanism.catalog import fourbar, slider_crank
from symlink.dynamics import DynamicModel, Gravity, MassProperties, dynamic_linkage
from symlink.io.scene import Scene

LENGTHS = dict(a=0.8, b=2.6, c=2.0, d=2.4)
#: body: (mass, distance of the centre from the origin joint, its angle from the body's axis, inertia, origin)
BODIES = {"crank": (1.3, 0.35, 0.2, 0.09, "A"), "coupler": (2.1, 1.1, -0.15, 1.3, "B"),
          "rocker": (1.7, 0.9, 0.1, 0.6, "D")}
GRAVITY = (0.7, -9.81)


@functools.lru_cache(maxsize=None)
def lagrange_reference():
    """``(equations, unknowns, coordinates)``: Lagrange's equations of the four-bar, zero at a true state."""
    theta, beta, phi = me.dynamicsymbols("theta beta phi")
    torque, t = sp.symbols("torque"), me.dynamicsymbols._t
    a, b, c, d = (sp.Float(LENGTHS[k]) for k in "abcd")
    N = me.ReferenceFrame("N")
    frames = {name: N.orientnew(name, "Axis", [angle, N.z])
              for name, angle in (("crank", theta), ("coupler", beta), ("rocker", phi))}
    origin = me.Point("O")
    origin.set_vel(N, 0)
    B = origin.locatenew("B", a * frames["crank"].x)
    D = origin.locatenew("D", d * N.x)
    D.set_vel(N, 0)
    starts = {"crank": origin, "coupler": B, "rocker": D}
    bodies = []
    for name, (mass, distance, angle, inertia, _) in BODIES.items():
        frame = frames[name]
        centre = starts[name].locatenew(f"G_{name}", distance * (math.cos(angle) * frame.x + math.sin(angle) * frame.y))
        centre.set_vel(N, centre.pos_from(origin).dt(N))
        body = me.RigidBody(name, centre, frame, mass, (me.inertia(frame, 0, 0, inertia), centre))
        body.potential_energy = -mass * (GRAVITY[0] * centre.pos_from(origin).dot(N.x)
                                         + GRAVITY[1] * centre.pos_from(origin).dot(N.y))
        bodies.append(body)
    lagrangian = me.Lagrangian(N, *bodies)
    closure = (B.pos_from(origin) + b * frames["coupler"].x - d * N.x - c * frames["rocker"].x)
    constraints = [closure.dot(N.x), closure.dot(N.y)]
    method = me.LagrangesMethod(lagrangian, [theta, beta, phi], hol_coneqs=constraints,
                                forcelist=[(frames["crank"], torque * N.z)], frame=N)
    equations = method.form_lagranges_equations()
    return equations, [torque, *method.lam_vec], (theta, beta, phi), constraints, t


def fourbar_positions(crank: float, branch: int) -> tuple[float, float, float]:
    """theta, beta, phi by circle intersection (C left of B->D for branch +1)."""
    a, b, c, d = (LENGTHS[k] for k in "abcd")
    B = a * complex(math.cos(crank), math.sin(crank))
    w = abs(d - B)
    along = (b * b - c * c + w * w) / (2 * w)
    unit = (d - B) / w
    C = B + along * unit + branch * math.sqrt(b * b - along * along) * 1j * unit
    return crank, math.atan2((C - B).imag, (C - B).real), math.atan2(C.imag, (C - d).real)


def reference_at(crank: float, speed: float, accel: float, branch: int):
    """Torque and the multipliers of the four-bar at a state."""
    return state_solution(lagrange_reference(), fourbar_positions(crank, branch), speed, accel)


def state_solution(reference, positions, speed: float, accel: float):
    """Torque and the multipliers from Lagrange's equations at given positions, input rate and acceleration."""
    equations, unknowns, coordinates, constraints, t = reference
    # Dependent rates and accelerations: the constraints' first and second time derivatives vanish.
    # Plain symbols stand for the coordinates and their derivatives (second derivatives replaced first).
    q, qd, qdd = (sp.symbols(f"q0:3{suffix}") for suffix in ("", "d", "dd"))
    plain = {**{x.diff(t, 2): s for x, s in zip(coordinates, qdd)}, **{x.diff(t): s for x, s in zip(coordinates, qd)}}

    def symbolic(expr):
        return expr.subs(plain).subs(dict(zip(coordinates, q)))

    known = {**dict(zip(q, positions)), qd[0]: speed, qdd[0]: accel}
    first = [symbolic(sp.diff(f, t)).subs(known) for f in constraints]
    known.update(sp.solve(first, [qd[1], qd[2]], dict=True)[0])
    second = [symbolic(sp.diff(f, t, 2)).subs(known) for f in constraints]
    known.update(sp.solve(second, [qdd[1], qdd[2]], dict=True)[0])
    lams = [symbolic(u) for u in unknowns]
    numeric = [symbolic(e).subs(known) for e in equations]
    solution = sp.solve(numeric, lams, dict=True)[0]
    return {"torque": float(solution[lams[0]]), "lambda": (float(solution[lams[1]]), float(solution[lams[2]]))}


# --- the slider-crank ------------------------------------------------------------------------

SLIDER = dict(a=0.5, b=1.7, offset=0.3)
#: body: (mass, distance, angle, inertia, origin) as above; the block's centre is its pin C
SLIDER_BODIES = {"crank": (0.9, 0.2, -0.3, 0.05, "A"), "conrod": (1.6, 0.7, 0.1, 0.4, "B"),
                 "slider": (2.3, 0.0, 0.0, 0.0, "C")}


@functools.lru_cache(maxsize=None)
def slider_crank_reference():
    """Lagrange's equations of the offset slider-crank (see the module docstring)."""
    theta, beta, s = me.dynamicsymbols("theta beta s")
    torque, t = sp.symbols("torque"), me.dynamicsymbols._t
    a, b, offset = (sp.Float(SLIDER[k]) for k in ("a", "b", "offset"))
    N = me.ReferenceFrame("N")
    crank, rod = N.orientnew("crank", "Axis", [theta, N.z]), N.orientnew("conrod", "Axis", [beta, N.z])
    origin = me.Point("O")
    origin.set_vel(N, 0)
    B = origin.locatenew("B", a * crank.x)
    bodies = []
    for name, frame, start in (("crank", crank, origin), ("conrod", rod, B)):
        mass, distance, angle, inertia, _ = SLIDER_BODIES[name]
        centre = start.locatenew(f"G_{name}", distance * (math.cos(angle) * frame.x + math.sin(angle) * frame.y))
        centre.set_vel(N, centre.pos_from(origin).dt(N))
        body = me.RigidBody(name, centre, frame, mass, (me.inertia(frame, 0, 0, inertia), centre))
        body.potential_energy = -mass * (GRAVITY[0] * centre.pos_from(origin).dot(N.x)
                                         + GRAVITY[1] * centre.pos_from(origin).dot(N.y))
        bodies.append(body)
    block = origin.locatenew("C", s * N.x + offset * N.y)
    block.set_vel(N, block.pos_from(origin).dt(N))
    mass = SLIDER_BODIES["slider"][0]
    slider = me.Particle("slider", block, mass)
    slider.potential_energy = -mass * (GRAVITY[0] * s + GRAVITY[1] * offset)
    bodies.append(slider)
    closure = B.pos_from(origin) + b * rod.x - block.pos_from(origin)
    constraints = [closure.dot(N.x), closure.dot(N.y)]
    method = me.LagrangesMethod(me.Lagrangian(N, *bodies), [theta, beta, s], hol_coneqs=constraints,
                                forcelist=[(crank, torque * N.z)], frame=N)
    return method.form_lagranges_equations(), [torque, *method.lam_vec], (theta, beta, s), constraints, t


def slider_crank_positions(crank: float, branch: int) -> tuple[float, float, float]:
    """theta, beta, s: the pin C on y = offset, to the right of B for branch +1."""
    a, b, offset = SLIDER["a"], SLIDER["b"], SLIDER["offset"]
    bx, by = a * math.cos(crank), a * math.sin(crank)
    run = branch * math.sqrt(b * b - (offset - by) ** 2)
    return crank, math.atan2(offset - by, run), bx + run


@pytest.mark.parametrize("crank, speed, accel, branch", [(0.0, 3.0, 1.0, 1), (2.4, -4.0, 2.5, 1), (4.4, 1.5, -3.0, -1)])
def test_slider_crank_torque_and_pin_force_agree_with_lagranges_method(crank, speed, accel, branch):
    expected = state_solution(slider_crank_reference(), slider_crank_positions(crank, branch), speed, accel)
    masses = [MassProperties(name, mass, distance, angle, inertia, origin)
              for name, (mass, distance, angle, inertia, origin) in SLIDER_BODIES.items()]
    linkage = dynamic_linkage(DynamicModel(slider_crank(), masses, gravity=Gravity(*GRAVITY)))
    found = Scene(linkage, ["input_torque", "joint_C_x", "joint_C_y"], dict(SLIDER), branch=branch).evaluate(
        theta=np.array([crank]), thetadot=speed, thetaddot=accel)[branch]
    assert bool(found["assembled"][0])
    assert float(found["input_torque"][0]) == pytest.approx(expected["torque"], rel=1e-10)
    joint = np.array([float(found["joint_C_x"][0]), float(found["joint_C_y"][0])])
    multipliers = np.array(expected["lambda"])
    sign = 1.0 if np.dot(joint, multipliers) >= 0 else -1.0  # the constraint's direction, as for the four-bar
    assert joint == pytest.approx(sign * multipliers, rel=1e-10, abs=1e-10 * np.abs(multipliers).max())


@pytest.fixture(scope="module")
def generated():
    masses = [MassProperties(name, mass, distance, angle, inertia, origin)
              for name, (mass, distance, angle, inertia, origin) in BODIES.items()]
    linkage = dynamic_linkage(DynamicModel(fourbar(), masses, gravity=Gravity(*GRAVITY)))
    return Scene(linkage, ["input_torque", "joint_C_x", "joint_C_y"], dict(LENGTHS), branch="both")


@pytest.mark.parametrize("crank, speed, accel, branch", [
    (0.3, 2.0, 0.0, 1), (2.1, -3.5, 1.7, 1), (4.0, 5.0, -2.0, -1), (5.5, 0.4, 6.0, -1)])
def test_torque_and_the_cut_joint_force_agree_with_lagranges_method(generated, crank, speed, accel, branch):
    expected = reference_at(crank, speed, accel, branch)
    found = generated.evaluate(theta=np.array([crank]), thetadot=speed, thetaddot=accel)[branch]
    assert bool(found["assembled"][0])
    assert float(found["input_torque"][0]) == pytest.approx(expected["torque"], rel=1e-10)
    joint = np.array([float(found["joint_C_x"][0]), float(found["joint_C_y"][0])])
    multipliers = np.array(expected["lambda"])
    # The multipliers are the force at the cut joint C; its sign depends on the constraint's direction (coupler
    # minus rocker here): the same vector up to one sign for both components.
    sign = 1.0 if np.dot(joint, multipliers) >= 0 else -1.0
    assert joint == pytest.approx(sign * multipliers, rel=1e-10, abs=1e-10 * np.abs(multipliers).max())
