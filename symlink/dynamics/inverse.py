"""Inverse dynamics: the driving effort by virtual power, the joint reactions and shaking by Newton-Euler.

For a prescribed input motion (angle, speed and acceleration of each input) the
driving effort of input ``q`` is, by the principle of virtual power,

    ``Q = sum(m a_G . dv_G/dq' + I alpha domega/dq') - Q_applied``

built from the velocity coefficients of :class:`~symlink.dynamics.model.DynamicModel`
(a torque for an angle input, acting from the ground on the body that turns with it;
a force along the travel for a slider input, from the guide on the block).  It needs
the accelerations but no joint forces, so a request for it derives no reactions.

The joint reactions follow from Newton-Euler body by body: each moving body gives
``sum F = m a_G`` and ``sum M_G = I alpha``; the unknowns are two force components a
pin (for a pin joining k bodies, the forces of the first body on each other one), the
normal force and couple of a slider, and the driving efforts.  Gruebler's count makes
this square.  It is solved symbolically once with generic placeholders for the lever
arms and right-hand sides (so the elimination never tests a real expression for zero
and never simplifies), and the placeholders are then replaced by their expressions,
which common-subexpression elimination in the generated code shares.

Output names (see :func:`dynamic_outputs`):

* ``input_torque`` / ``input_force`` (``input_torque_<q>`` with several inputs);
* ``joint_<J>_x``, ``joint_<J>_y``: the force that the pin's first body (the ground
  where it is one) exerts on its other body; ``joint_<J>_<body>_x`` at a pin of more
  than two bodies; at a slider, the guide's normal force on the block and
  ``joint_<J>_moment``, its couple on the block;
* ``shaking_force_x``, ``shaking_force_y``, ``shaking_moment``: the force and the
  moment about the origin that the moving parts exert on the frame through its
  joints and drives (loads applied by the frame itself, like a spring anchored to
  it, are not included);
* for one input, ``generalised_inertia``, ``generalised_inertia_slope`` (dM/dq) and
  ``applied_generalised_force``, for forward dynamics.

>>> from symlink.catalog import fourbar
>>> from symlink.dynamics.model import DynamicModel, MassProperties
>>> model = DynamicModel(fourbar(), [MassProperties("crank", "m2", inertia="I2")])
>>> driving_efforts(model)[0]
I2*thetaddot
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import sympy as sp

from ..bodies import GROUND, PRISMATIC
from ..closure import is_angle
from ..linkage import Linkage
from ..vectors import expression

if TYPE_CHECKING:
    from .model import DynamicModel

__all__ = ["driving_efforts", "reactions", "dynamic_outputs", "DynamicLinkage", "dynamic_linkage"]


def driving_efforts(model: DynamicModel) -> list[sp.Expr]:
    """The effort of each input (torque or force) by virtual power, in terms of positions, rates, accelerations."""
    n = len(model.kinematics.inputs)
    result = [sp.S.Zero] * n
    for body, (mass, centre, inertia) in model.masses.items():
        a = model.acceleration_of(centre)
        alpha = model.angular_acceleration(body)
        v = model.point_coefficients(centre)
        w = model.angle_coefficients(body)
        for i in range(n):
            result[i] += mass * (a[0] * v[i][0] + a[1] * v[i][1]) + inertia * alpha * w[i]
    applied = model.applied_generalised_forces()
    return [r - q for r, q in zip(result, applied)]


class _Unknown:
    """One unknown force or couple of the Newton-Euler system and where it acts."""

    def __init__(self, name: str, symbol: sp.Symbol) -> None:
        self.name = name
        self.symbol = symbol


def _input_drives(model: DynamicModel):
    """Per input: ``(body that turns with it, None)`` for an angle, ``(guide, block, point, direction)`` for a travel."""
    linkage = model.kinematics
    drives: list[tuple] = []
    for q in linkage.inputs:
        if is_angle(linkage, q):
            turning = [b.name for b in model.mechanism.bodies if not b.is_ground and model.body_angle(b.name) == q]
            if not turning:
                raise ValueError(f"input {q} of {linkage.name} is not the angle of a body; its torque has no body "
                                 "to act on")
            drives.append(("torque", turning[0]))
            continue
        travel = next((v for loop in linkage.loops for _, v in loop.terms if q in v.length.free_symbols), None)
        joint = next((j for j in model.mechanism.joints if j.kind == PRISMATIC and travel is not None
                      and j.position is not None and j.guide_start is not None
                      and sp.expand(j.position.x - j.guide_start.x - travel.x) == 0
                      and sp.expand(j.position.y - j.guide_start.y - travel.y) == 0), None)
        if joint is None or travel is None:
            raise ValueError(f"input {q} of {linkage.name} is neither a body's angle nor a slider's travel")
        drives.append(("force", joint, travel))
    return drives


def _names(model: DynamicModel) -> list[str]:
    names = []
    for joint in model.mechanism.joints:
        if joint.kind == PRISMATIC:
            names += [f"joint_{joint.name}_x", f"joint_{joint.name}_y", f"joint_{joint.name}_moment"]
        elif len(joint.bodies) == 2:
            names += [f"joint_{joint.name}_x", f"joint_{joint.name}_y"]
        else:
            names += [f"joint_{joint.name}_{body}_{axis}" for body in joint.bodies[1:] for axis in "xy"]
    return names


def reactions(model: DynamicModel) -> dict[str, sp.Expr]:
    """Every joint's reaction, the driving efforts and the shaking force and moment (Newton-Euler, solved once).

    Keys are the output names of the module docstring (the efforts under their
    :meth:`~symlink.dynamics.model.DynamicModel.input_effort_name`).
    """
    bodies = list(model.moving_bodies)
    row_of = {body: 3 * k for k, body in enumerate(bodies)}
    centres = {body: model.masses[body][1] if body in model.masses else model.point(
        (model.mechanism.body(body).joints or model.mechanism.body(body).points)[0]) for body in bodies}
    placeholders: dict[sp.Symbol, sp.Expr] = {}

    def hold(expr: sp.Expr) -> sp.Expr:
        """A generic symbol standing for ``expr`` in the elimination (numbers stay numbers)."""
        expr = sp.sympify(expr)
        if expr.is_number:
            return expr
        symbol = sp.Dummy(f"h{len(placeholders)}")
        placeholders[symbol] = expr
        return symbol

    arms: dict[tuple[str, tuple], tuple[sp.Expr, sp.Expr]] = {}

    def arm(body: str, point: tuple[sp.Expr, sp.Expr]) -> tuple[sp.Expr, sp.Expr]:
        key = (body, point)
        if key not in arms:
            g = centres[body]
            arms[key] = (hold(point[0] - g[0]), hold(point[1] - g[1]))
        return arms[key]

    unknowns: list[sp.Symbol] = []
    columns: list[dict[int, sp.Expr]] = []  # per unknown: row -> coefficient
    ground_loads: list[tuple[sp.Symbol, tuple[sp.Expr, sp.Expr], tuple[sp.Expr, sp.Expr], sp.Expr]] = []
    outputs: dict[str, sp.Expr] = {}  # name -> placeholder expression of unknowns

    def unknown() -> sp.Symbol:
        symbol = sp.Dummy(f"x{len(unknowns)}")
        unknowns.append(symbol)
        columns.append({})
        return symbol

    def act(symbol: sp.Symbol, body: str, point, direction: tuple[sp.Expr, sp.Expr] | None, sign: int) -> None:
        """``symbol`` times ``direction`` (a force at ``point``) or a couple (direction None) on ``body``."""
        column = columns[unknowns.index(symbol)]
        if body == GROUND:
            if direction is None:
                ground_loads.append((symbol, point, (0, 0), sign))
            else:
                ground_loads.append((symbol, point, (sign * direction[0], sign * direction[1]), 0))
            return
        row = row_of[body]
        if direction is None:
            column[row + 2] = column.get(row + 2, 0) + sign
            return
        rx, ry = arm(body, point)
        column[row] = column.get(row, 0) + sign * direction[0]
        column[row + 1] = column.get(row + 1, 0) + sign * direction[1]
        column[row + 2] = column.get(row + 2, 0) + sign * (rx * direction[1] - ry * direction[0])

    x_axis, y_axis = (sp.S.One, sp.S.Zero), (sp.S.Zero, sp.S.One)
    names = iter(_names(model))
    for joint in model.mechanism.joints:
        position = (joint.position.x, joint.position.y) if joint.position is not None else None
        if position is None:
            raise ValueError(f"joint {joint.name} is not tied to the origin by a point's vectors; its reaction "
                             "cannot be placed")
        if joint.kind == PRISMATIC:
            guide, block = joint.bodies
            angle = expression(joint.direction) + sp.pi / 2
            normal = (hold(sp.cos(angle)), hold(sp.sin(angle)))
            force, couple = unknown(), unknown()
            for body, sign in ((block, 1), (guide, -1)):
                act(force, body, position, normal, sign)
                act(couple, body, None, None, sign)
            outputs[next(names)] = force * normal[0]
            outputs[next(names)] = force * normal[1]
            outputs[next(names)] = couple
            continue
        first = joint.bodies[0]
        for other in joint.bodies[1:]:
            fx, fy = unknown(), unknown()
            for symbol, axis in ((fx, x_axis), (fy, y_axis)):
                act(symbol, other, position, axis, 1)
                act(symbol, first, position, axis, -1)
            outputs[next(names)] = fx
            outputs[next(names)] = fy
    for index, drive in enumerate(_input_drives(model)):
        effort = unknown()
        if drive[0] == "torque":
            act(effort, drive[1], None, None, 1)
            act(effort, GROUND, None, None, -1)
        else:
            joint, travel = drive[1], drive[2]
            guide, block = joint.bodies
            position = (joint.position.x, joint.position.y)
            direction = (hold(sp.cos(travel.angle)), hold(sp.sin(travel.angle)))
            act(effort, block, position, direction, 1)
            act(effort, guide, position, direction, -1)
        outputs[model.input_effort_name(index)] = effort

    size = 3 * len(bodies)
    if len(unknowns) != size:
        raise ValueError(f"{model.kinematics.name}: {size} Newton-Euler equations for {len(unknowns)} unknown "
                         "forces; the reactions are not determined (a redundant or under-constrained linkage)")
    matrix = sp.zeros(size, size)
    for k, column in enumerate(columns):
        for row, value in column.items():
            matrix[row, k] = value
    # Right-hand sides: m a_G - applied forces, I alpha - applied moments about G.
    rhs = [sp.S.Zero] * size
    for body in bodies:
        row = row_of[body]
        if body in model.masses:
            mass, centre, inertia = model.masses[body]
            a = model.acceleration_of(centre)
            rhs[row] += mass * a[0]
            rhs[row + 1] += mass * a[1]
            rhs[row + 2] += inertia * model.angular_acceleration(body)
    for force in model.forces:
        if force.body == GROUND:
            continue
        row = row_of[force.body]
        g = centres[force.body]
        rx, ry = force.point[0] - g[0], force.point[1] - g[1]
        rhs[row] -= force.force[0]
        rhs[row + 1] -= force.force[1]
        rhs[row + 2] -= rx * force.force[1] - ry * force.force[0]
    for body, couple in model.couples:
        if body != GROUND:
            rhs[row_of[body] + 2] -= couple
    held_rhs = sp.Matrix([hold(value) for value in rhs])
    solution = _solve(matrix, held_rhs)
    by_unknown = dict(zip(unknowns, solution))
    result = {name: value.xreplace(by_unknown) for name, value in outputs.items()}
    # The frame: what the moving parts exert on it through its joints and drives.
    shaking_x = shaking_y = moment = sp.S.Zero
    for symbol, point, direction, couple in ground_loads:
        value = by_unknown[symbol]
        if couple:
            moment += couple * value
            continue
        fx, fy = direction[0] * value, direction[1] * value
        shaking_x, shaking_y = shaking_x + fx, shaking_y + fy
        moment += point[0] * fy - point[1] * fx
    # act() stored each force and couple on the ground with the ground's sign: they are the shaking loads.
    result.update({"shaking_force_x": shaking_x, "shaking_force_y": shaking_y, "shaking_moment": moment})
    return {name: value.xreplace(placeholders) for name, value in result.items()}


def _solve(matrix: sp.Matrix, rhs: sp.Matrix) -> list[sp.Expr]:
    """Solve the generic sparse system so that no step divides by what may vanish where the system does not.

    Gaussian elimination first uses only pivots that are nonzero numbers (the unit
    coefficients of the force balances, a drive's unit couple), chosen by Markowitz's
    rule to keep the rows short; what is left (the moment balances, a few rows) is solved
    by Cramer's rule, whose one denominator, its determinant, is the whole system's
    determinant over the numeric pivots: it vanishes only where the linkage cannot carry
    the load (a toggle), never at a pose where a lever arm happens to be zero.  An
    elimination that pivoted on an arm (say ``sin(theta)`` of the crank) would return NaN
    there although the forces are finite.

    >>> a, b = sp.symbols("a b")
    >>> _solve(sp.Matrix([[a, 1], [1, 0]]), sp.Matrix([b, 2]))   # pivots on the 1s, never on a
    [2, -2*a + b]
    """
    size = matrix.rows
    rows: dict[int, dict[int, sp.Expr]] = {
        i: {j: matrix[i, j] for j in range(size) if matrix[i, j] != 0} for i in range(size)}
    right = list(rhs)
    steps: list[tuple[int, int, dict[int, sp.Expr]]] = []  # (row, column, the row as eliminated)
    while True:
        column_counts: dict[int, int] = {}
        for entries in rows.values():
            for j in entries:
                column_counts[j] = column_counts.get(j, 0) + 1
        candidates = [((len(entries) - 1) * (column_counts[j] - 1), abs(value) != 1, i, j)
                      for i, entries in rows.items() for j, value in entries.items() if value.is_number]
        if not candidates:
            break
        _, _, pivot_row, pivot_column = min(candidates)
        entries = rows.pop(pivot_row)
        pivot = entries[pivot_column]
        for i, other in rows.items():
            if pivot_column not in other:
                continue
            factor = other.pop(pivot_column) / pivot
            for j, value in entries.items():
                if j != pivot_column:
                    updated = other.get(j, 0) - factor * value
                    if updated == 0:
                        other.pop(j, None)
                    else:
                        other[j] = updated
            right[i] = right[i] - factor * right[pivot_row]
        steps.append((pivot_row, pivot_column, entries))
    solution: dict[int, sp.Expr] = {}
    rest_rows = sorted(rows)
    rest_columns = sorted({j for i in rest_rows for j in rows[i]} | (set(range(size)) - {c for _, c, _ in steps}))
    if len(rest_rows) != len(rest_columns):
        raise ValueError("the Newton-Euler equations are structurally singular")
    if rest_rows:
        schur = sp.Matrix([[rows[i].get(j, 0) for j in rest_columns] for i in rest_rows])
        determinant = schur.det(method="berkowitz")
        if determinant == 0:
            raise ValueError("the Newton-Euler equations are structurally singular")
        for k, j in enumerate(rest_columns):
            replaced = schur.copy()
            replaced[:, k] = sp.Matrix([right[i] for i in rest_rows])
            solution[j] = replaced.det(method="berkowitz") / determinant
    for row, column, entries in reversed(steps):
        known = sum((value * solution[j] for j, value in entries.items() if j != column), sp.S.Zero)
        solution[column] = (right[row] - known) / entries[column]
    return [solution[j] for j in range(size)]


def dynamic_outputs(model: DynamicModel) -> dict[str, sp.Expr]:
    """Every dynamic output of ``model``: efforts (virtual power), reactions, shaking, and M, dM/dq, Q (one input)."""
    efforts = driving_efforts(model)
    outputs = {model.input_effort_name(i): effort for i, effort in enumerate(efforts)}
    found = reactions(model)
    for i in range(len(efforts)):
        found.pop(model.input_effort_name(i))
    outputs.update(found)
    if len(model.kinematics.inputs) == 1:
        outputs["generalised_inertia"] = model.generalised_inertia()[0, 0]
        outputs["generalised_inertia_slope"] = model.generalised_inertia_slope()
        outputs["applied_generalised_force"] = model.applied_generalised_forces()[0]
    return outputs


class DynamicLinkage(Linkage):
    """A linkage whose extra outputs include the dynamic ones; :attr:`dynamic_outputs` names them."""

    dynamic_outputs: tuple[str, ...] = ()
    model: DynamicModel


def dynamic_linkage(model: DynamicModel) -> DynamicLinkage:
    """The model's kinematic linkage with the dynamic outputs as extras and the model's symbols as parameters.

    Scenes, exports and LaTeX take it like any linkage, and derive only what a request
    needs (a torque: accelerations, no reactions).  Building it derives every output's
    expression once: keep it rather than calling this again.

    >>> from symlink.catalog import fourbar
    >>> from symlink.dynamics.model import DynamicModel, MassProperties
    >>> linkage = dynamic_linkage(DynamicModel(fourbar(), [MassProperties("crank", "m2", inertia="I2")]))
    >>> linkage.dynamic_outputs[:3], linkage.extras["input_torque"]
    (('input_torque', 'joint_A_x', 'joint_A_y'), I2*thetaddot)
    """
    outputs = dynamic_outputs(model)
    base = model.kinematics
    result = DynamicLinkage(base.name, base.loops, base.inputs, base.unknowns,
                            parameters=list(base.parameters) + model.new_parameters,
                            points=base.points, roles=base.roles, extras={**base.extras, **outputs})
    result.dynamic_outputs = tuple(outputs)
    result.model = model
    return result
