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

>>> from symlink.mechanism.catalog import fourbar
>>> from symlink.dynamics.model import DynamicModel, MassProperties
>>> model = DynamicModel(fourbar(), [MassProperties("crank", "m2", inertia="I2")])
>>> driving_efforts(model)[0]
I2*thetaddot
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Callable, Iterator, Mapping, Sequence, TypeVar

import sympy as sp

from ..mechanism.bodies import GROUND, PRISMATIC, _moving_part, same_point
from ..symbolic.closure import is_angle
from ..symbolic.linkage import Linkage
from ..symbolic.typeset import EquationSet
from ..symbolic.vectors import expression
from ..common.display import record_html

if TYPE_CHECKING:
    from .model import DynamicModel

__all__ = ["EQUATION_OUTPUTS", "NewtonEuler", "driving_efforts", "newton_euler", "reactions", "equation_of_motion",
           "linkage_with_outputs", "dynamic_outputs", "DynamicLinkage", "dynamic_linkage", "dynamic_output_names",
           "DerivedOutputs"]

LinkageKind = TypeVar("LinkageKind", bound=Linkage)

#: The outputs the equation of motion is made of (one input): M, dM/dq, Q_applied; not a table of forces.
EQUATION_OUTPUTS = ("generalised_inertia", "generalised_inertia_slope", "applied_generalised_force")


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
            turning = [b.name for b in model.mechanism.bodies
                       if not b.is_ground and _moving_part(model.body_angle(b.name), set(linkage.coordinates)) == q]
            if not turning:
                raise ValueError(f"input {q} of {linkage.name} is not the angle of a body; its torque has no body "
                                 "to act on")
            drives.append(("torque", turning[0]))
            continue
        travel = next((v for loop in linkage.loops for _, v in loop.terms if q in v.length.free_symbols), None)
        # The travel's head, however the points write it (the crank side of the loop or the guide side).
        joint = next((j for j in model.mechanism.joints if j.kind == PRISMATIC and travel is not None
                      and j.position is not None and j.guide_start is not None
                      and same_point(linkage, j.position, j.guide_start + travel)), None)
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


@dataclass
class NewtonEuler:
    """The Newton-Euler equations of a model's moving bodies, ``matrix * unknowns = rhs``, three rows a body.

    Rows ``3k, 3k+1, 3k+2`` of body ``bodies[k]`` are its force balance in x and y and its
    moment balance about its centre of mass; ``matrix`` and ``rhs`` hold generic placeholders
    (``placeholders`` maps them to their expressions) so that solving them never tests a real
    expression for zero; ``symbols`` are readable names of the unknowns (``F_{B,x}``, ``N_{J}``,
    ``T_{theta}``) for the derivation document.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    bodies: list[str]
    unknowns: list[sp.Symbol]
    symbols: list[sp.Symbol]
    matrix: sp.Matrix
    rhs: sp.Matrix
    placeholders: dict[sp.Symbol, sp.Expr]
    outputs: dict[str, sp.Expr]
    ground_loads: list[tuple[sp.Symbol, tuple[sp.Expr, sp.Expr], tuple[sp.Expr, sp.Expr], sp.Expr]]
    applied: list[sp.Expr]
    massive: tuple[str, ...] = ()

    def equations(self) -> list[tuple[sp.Symbol, sp.Expr]]:
        """Each row as ``m a_G,x = the joint forces and drives in x + the applied loads in x`` (and y, and
        ``I alpha`` = the moments about G), the unknowns by their readable names."""
        readable = dict(zip(self.unknowns, self.symbols))
        rows = []
        for k, body in enumerate(self.bodies):
            names = (f"m_{{{body}}} a_{{G,{body},x}}", f"m_{{{body}}} a_{{G,{body},y}}",
                     f"I_{{G,{body}}} \\alpha_{{{body}}}")
            for offset, name in enumerate(names):
                row = 3 * k + offset
                forces = sum((self.matrix[row, j] * readable[u] for j, u in enumerate(self.unknowns)
                              if self.matrix[row, j] != 0), sp.S.Zero)
                left = sp.Symbol(name) if body in self.massive else sp.S.Zero  # a massless body balances
                rows.append((left, (forces + self.applied[row]).xreplace(self.placeholders)))
        return rows


def reactions(model: DynamicModel) -> EquationSet:
    """Every joint's reaction, the driving efforts and the shaking force and moment (Newton-Euler, solved once).

    Keys are the output names of the module docstring (the efforts under their
    :meth:`~symlink.dynamics.model.DynamicModel.input_effort_name`).
    """
    system = newton_euler(model)
    solution = _solve(system.matrix, system.rhs)
    by_unknown = dict(zip(system.unknowns, solution))
    result = {name: value.xreplace(by_unknown) for name, value in system.outputs.items()}
    # The frame: what the moving parts exert on it through its joints and drives.
    shaking_x = shaking_y = moment = sp.S.Zero
    for symbol, point, direction, couple in system.ground_loads:
        value = by_unknown[symbol]
        if couple:
            moment += couple * value
            continue
        fx, fy = direction[0] * value, direction[1] * value
        shaking_x, shaking_y = shaking_x + fx, shaking_y + fy
        moment += point[0] * fy - point[1] * fx
    # act() stored each force and couple on the ground with the ground's sign: they are the shaking loads.
    result.update({"shaking_force_x": shaking_x, "shaking_force_y": shaking_y, "shaking_moment": moment})
    return EquationSet({name: value.xreplace(system.placeholders) for name, value in result.items()})


def newton_euler(model: DynamicModel) -> NewtonEuler:
    """The Newton-Euler equations of ``model`` (see :class:`NewtonEuler`); ``ValueError`` if not square."""
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
    readable: list[sp.Symbol] = []
    columns: list[dict[int, sp.Expr]] = []  # per unknown: row -> coefficient
    ground_loads: list[tuple[sp.Symbol, tuple[sp.Expr, sp.Expr], tuple[sp.Expr, sp.Expr], sp.Expr]] = []
    outputs: dict[str, sp.Expr] = {}  # name -> placeholder expression of unknowns

    def unknown(name: str) -> sp.Symbol:
        symbol = sp.Dummy(f"x{len(unknowns)}")
        unknowns.append(symbol)
        readable.append(sp.Symbol(name))
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
            force, couple = unknown(f"N_{{{joint.name}}}"), unknown(f"M_{{{joint.name}}}")
            for body, sign in ((block, 1), (guide, -1)):
                act(force, body, position, normal, sign)
                act(couple, body, None, None, sign)
            outputs[next(names)] = force * normal[0]
            outputs[next(names)] = force * normal[1]
            outputs[next(names)] = couple
            continue
        first = joint.bodies[0]
        for other in joint.bodies[1:]:
            at = joint.name if len(joint.bodies) == 2 else f"{joint.name},{other}"
            fx, fy = unknown(f"F_{{{at},x}}"), unknown(f"F_{{{at},y}}")
            for symbol, axis in ((fx, x_axis), (fy, y_axis)):
                act(symbol, other, position, axis, 1)
                act(symbol, first, position, axis, -1)
            outputs[next(names)] = fx
            outputs[next(names)] = fy
    for index, drive in enumerate(_input_drives(model)):
        effort = unknown(f"{'T' if drive[0] == 'torque' else 'P'}_{{{sp.latex(model.kinematics.inputs[index])}}}")
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
    inertial = [sp.S.Zero] * size
    applied = [sp.S.Zero] * size
    for body in bodies:
        row = row_of[body]
        if body in model.masses:
            mass, centre, inertia = model.masses[body]
            a = model.acceleration_of(centre)
            inertial[row:row + 3] = [mass * a[0], mass * a[1], inertia * model.angular_acceleration(body)]
    for force in model.forces:
        if force.body == GROUND:
            continue
        row = row_of[force.body]
        g = centres[force.body]
        rx, ry = force.point[0] - g[0], force.point[1] - g[1]
        applied[row] += force.force[0]
        applied[row + 1] += force.force[1]
        applied[row + 2] += rx * force.force[1] - ry * force.force[0]
    for body, couple in model.couples:
        if body != GROUND:
            applied[row_of[body] + 2] += couple
    held_rhs = sp.Matrix([hold(m - f) for m, f in zip(inertial, applied)])
    return NewtonEuler(bodies, unknowns, readable, matrix, held_rhs, placeholders, outputs, ground_loads, applied,
                       tuple(model.masses))


def _solve(matrix: sp.Matrix, rhs: sp.Matrix) -> list[sp.Expr]:
    """Solve the generic sparse system so that no step divides by what may vanish where the system does not.

    Gaussian elimination first uses only pivots that are nonzero numbers (the unit
    coefficients of the force balances, a drive's unit couple), chosen by Markowitz's
    rule to keep the rows short.  What is left (the moment balances, a few rows) falls
    apart into blocks that can be solved one after the other (:func:`_diagonal_blocks`):
    a dyad of a multi-loop linkage carries its own loads and passes them on, as the solve
    plan closes its loops one after the other.  Each block is solved by Cramer's rule,
    whose one denominator, the block's determinant (a factor of the whole system's
    determinant over the numeric pivots), vanishes only where the linkage cannot carry
    the load (a toggle of that dyad), never at a pose where a lever arm happens to be
    zero.  An elimination that pivoted on an arm (say ``sin(theta)`` of the crank) would
    return NaN there although the forces are finite; Cramer's rule on all the moment
    balances at once expands products of every dyad's arms, whose terms cancel in
    floating point (a Watt II pose of tests/dynamics/test_multiloop_accuracy.py lost
    3e-14 of its largest force that way, 1e-13 in the shaking moment), and takes
    determinants of a size that grows with the number of loops.

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
    rest_columns = sorted(set(range(size)) - {c for _, c, _ in steps})  # the rows left hold no other columns
    if len(rest_rows) != len(rest_columns):
        raise ValueError("the Newton-Euler equations are structurally singular")
    for block_rows, block_columns in _diagonal_blocks({i: rows[i] for i in rest_rows}, rest_columns):
        known = {i: right[i] - sum((value * solution[j] for j, value in rows[i].items() if j in solution), sp.S.Zero)
                 for i in block_rows}
        block = sp.Matrix([[rows[i].get(j, 0) for j in block_columns] for i in block_rows])
        determinant = block.det(method="berkowitz")
        if determinant == 0:
            raise ValueError("the Newton-Euler equations are structurally singular")
        # Cramer's rule with generic right-hand sides, then the right-hand sides put in: the determinants
        # are taken of the block's own short entries, never of the long expressions the earlier blocks left.
        generic = [sp.Dummy(f"r{i}") for i in block_rows]
        put_in = dict(zip(generic, (known[i] for i in block_rows)))
        for k, j in enumerate(block_columns):
            replaced = block.copy()
            replaced[:, k] = sp.Matrix(generic)
            solution[j] = (replaced.det(method="berkowitz") / determinant).xreplace(put_in)
    for row, column, entries in reversed(steps):
        known = sum((value * solution[j] for j, value in entries.items() if j != column), sp.S.Zero)
        solution[column] = (right[row] - known) / entries[column]
    return [solution[j] for j in range(size)]


def _diagonal_blocks(rows: Mapping[int, Mapping[int, sp.Expr]],
                     columns: list[int]) -> list[tuple[list[int], list[int]]]:
    """The square system ``rows`` (row -> column -> entry) in block-triangular form: ``(rows, columns)`` of
    each diagonal block, in the order they can be solved (each needs only the columns of the blocks before it).

    A perfect matching of rows to columns (augmenting paths) pairs each unknown with an equation; the
    blocks are the strongly connected components (Tarjan) of "the equation of column j holds column k",
    each after those it holds.  ``ValueError`` where no perfect matching exists (structurally singular).

    >>> _diagonal_blocks({0: {0: 1, 1: 2}, 1: {1: 3}}, [0, 1])   # row 1 alone fixes column 1, then row 0
    [([1], [1]), ([0], [0])]
    """
    row_of: dict[int, int] = {}

    def augment(row: int, seen: set[int]) -> bool:
        for column in rows[row]:
            if column in seen:
                continue
            seen.add(column)
            if column not in row_of or augment(row_of[column], seen):
                row_of[column] = row
                return True
        return False

    for row in sorted(rows):
        if not augment(row, set()):
            raise ValueError("the Newton-Euler equations are structurally singular")
    needs = {column: [k for k in rows[row_of[column]] if k != column] for column in columns}
    index: dict[int, int] = {}
    lowest: dict[int, int] = {}
    stack: list[int] = []
    on_stack: set[int] = set()
    blocks: list[tuple[list[int], list[int]]] = []

    def connect(column: int) -> None:  # Tarjan: a component is closed after every component it needs
        index[column] = lowest[column] = len(index)
        stack.append(column)
        on_stack.add(column)
        for other in needs[column]:
            if other not in index:
                connect(other)
                lowest[column] = min(lowest[column], lowest[other])
            elif other in on_stack:
                lowest[column] = min(lowest[column], index[other])
        if lowest[column] == index[column]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == column:
                    break
            component.sort()
            blocks.append(([row_of[c] for c in component], component))

    for column in columns:
        if column not in index:
            connect(column)
    return blocks


def dynamic_outputs(model: DynamicModel) -> dict[str, sp.Expr]:
    """Every dynamic output of ``model``: efforts (virtual power), reactions, shaking, and M, dM/dq, Q (one input)."""
    efforts = driving_efforts(model)
    outputs = {model.input_effort_name(i): effort for i, effort in enumerate(efforts)}
    found = reactions(model)
    for i in range(len(efforts)):
        found.pop(model.input_effort_name(i))
    outputs.update(found)
    if len(model.kinematics.inputs) == 1:
        outputs.update(equation_of_motion(model))
    return outputs


def equation_of_motion(model: DynamicModel) -> EquationSet:
    """``M``, ``dM/dq`` and ``Q_applied`` of a one-input model, under the names of :data:`EQUATION_OUTPUTS`."""
    inertia, slope, applied = EQUATION_OUTPUTS
    return EquationSet({inertia: model.generalised_inertia()[0, 0], slope: model.generalised_inertia_slope(),
                        applied: model.applied_generalised_forces()[0]})


def linkage_with_outputs(model: DynamicModel, outputs: Mapping[str, sp.Expr],
                         kind: type[LinkageKind] = Linkage) -> LinkageKind:  # type: ignore[assignment]  # a default for a TypeVar
    """The model's kinematic linkage (as ``kind``) with ``outputs`` as further extras and the model's symbols as
    parameters."""
    base = model.kinematics
    return kind(base.name, base.loops, base.inputs, base.unknowns,
                parameters=list(base.parameters) + list(model.new_parameters),
                points=base.points, roles=base.roles, extras={**base.extras, **outputs})


class DynamicLinkage(Linkage):
    """A linkage whose extra outputs include the dynamic ones; :attr:`dynamic_outputs` names them.

    Parameters
    ----------
    name, loops, inputs, unknowns, parameters, points, roles, extras
        As for :class:`Linkage`; made by :func:`dynamic_linkage`, not by hand.

    Examples
    --------
    >>> import symlink
    >>> model = symlink.DynamicModel(symlink.fourbar(), [symlink.MassProperties("crank", "m2", inertia="I2")])
    >>> linkage = symlink.dynamic_linkage(model)
    >>> isinstance(linkage, symlink.Linkage), "input_torque" in linkage.dynamic_outputs
    (True, True)
    """

    dynamic_outputs: tuple[str, ...] = ()
    model: DynamicModel

    def described_extras(self) -> list | None:
        """What the extras are, for the cache key (:func:`symlink.numeric.cache.definition`), without deriving them.

        The kinematic linkage's own extras, and the model as given: each mass with its centre and inertia,
        the applied forces and couples (gravity's among them), the bodies and joints the reactions are of,
        and the dynamic outputs' names (the same whether they have been derived yet or not); ``None`` for a
        linkage made with the expressions themselves (:func:`linkage_with_outputs`: the key then takes them).
        """
        if not isinstance(self.extras, DerivedOutputs):
            return None
        model = self.model
        text = sp.srepr
        return [[name, text(value)] for name, value in model.kinematics.extras.items()] + [["dynamics", {
            "outputs": list(self.dynamic_outputs),
            "masses": [[body, text(mass), text(centre[0]), text(centre[1]), text(inertia)]
                       for body, (mass, centre, inertia) in model.masses.items()],
            "forces": [[force.body, text(force.point[0]), text(force.point[1]), text(force.force[0]),
                        text(force.force[1])] for force in model.forces],
            "couples": [[body, text(value)] for body, value in model.couples],
            "gravity": [text(value) for value in model.gravity],
            "bodies": [[body.name, list(body.vectors), list(body.joints), list(body.points)]
                       for body in model.mechanism.bodies],
            "joints": [[joint.name, joint.kind, list(joint.bodies)] for joint in model.mechanism.joints],
        }]]

    def divides_by_determinant(self, name: str) -> bool:
        """Every dynamic output does: the efforts and ``M(q)`` through the rates, the reactions through the
        Newton-Euler determinant, both zero at a toggle."""
        return name in self.dynamic_outputs or super().divides_by_determinant(name)

    @property
    def force_outputs(self) -> tuple[str, ...]:
        """The driving efforts, joint reactions and shaking loads: the columns a table adds."""
        return tuple(name for name in self.dynamic_outputs if name not in EQUATION_OUTPUTS)

    def derivation_sections(self) -> list[tuple[str, list[tuple[sp.Expr, sp.Expr]]]]:
        """``(title, rows)`` of the dynamics for the derivation document: the mass properties, the driving
        effort by virtual power, the Newton-Euler equations body by body, and (one input) the equation of motion.

        The reactions are shown as the equations they solve, in terms of the coordinates and their
        rates and accelerations, not as their long closed forms.
        """
        model = self.model
        masses, accelerations = [], []
        for body, (mass, centre, inertia) in model.masses.items():
            masses += [(sp.Symbol(f"m_{{{body}}}"), mass), (sp.Symbol(f"x_{{G,{body}}}"), centre[0]),
                       (sp.Symbol(f"y_{{G,{body}}}"), centre[1]), (sp.Symbol(f"I_{{G,{body}}}"), inertia)]
            a = model.acceleration_of(centre)
            accelerations += [(sp.Symbol(f"a_{{G,{body},x}}"), a[0]), (sp.Symbol(f"a_{{G,{body},y}}"), a[1]),
                              (sp.Symbol(f"\\alpha_{{{body}}}"), model.angular_acceleration(body))]
        system = newton_euler(model)
        effort_symbols = {name: system.symbols[system.unknowns.index(value)]
                          for name, value in system.outputs.items() if value in system.unknowns}
        efforts = [(effort_symbols[model.input_effort_name(i)], effort)
                   for i, effort in enumerate(driving_efforts(model))]
        sections = [("Mass properties (centres of mass in the frame)", masses),
                    ("Accelerations of the centres of mass and angular accelerations", accelerations),
                    ("Driving effort by virtual power", efforts),
                    ("Newton-Euler equations, body by body: the joint forces F (of a pin's first body on the other), "
                     "slider normal forces N and couples M, and the drive", system.equations())]
        if len(model.kinematics.inputs) == 1:
            inertia, slope, applied = EQUATION_OUTPUTS
            q = sp.latex(model.kinematics.inputs[0])
            motion = sp.Symbol(f"M \\ddot{{{q}}} + \\frac{{1}}{{2}} M' \\dot{{{q}}}^{{2}}")
            sections.append(("Equation of motion, with the generalised inertia M, its slope M' = dM/dq and the "
                             "applied generalised force Q",
                             [(motion, sp.Symbol("Q") + efforts[0][0]), (sp.Symbol("M"), self.extras[inertia]),
                              (sp.Symbol("M'"), self.extras[slope]), (sp.Symbol("Q"), self.extras[applied])]))
        return sections


def dynamic_linkage(model: DynamicModel) -> DynamicLinkage:
    """The model's kinematic linkage with the dynamic outputs as extras and the model's symbols as parameters.

    Scenes, exports and LaTeX take it like any linkage, and derive only what a request
    needs (a torque: accelerations, no reactions).  The outputs are named at once
    (:func:`dynamic_output_names`) and derived together on first use of any of their
    expressions; a cached request (a :class:`~symlink.numeric.solver.Solver` whose code is in the
    cache) uses none, so it derives nothing: its key is made from the model as given
    (:meth:`DynamicLinkage.described_extras`), not from the derived expressions.

    Parameters
    ----------
    model : DynamicModel
        The linkage with its masses and loads.

    Returns
    -------
    DynamicLinkage
        The linkage with the dynamic outputs (``input_torque``, ``joint_<J>_x`` ...) as extras.

    Examples
    --------
    >>> import symlink
    >>> model = symlink.DynamicModel(symlink.fourbar(), [symlink.MassProperties("crank", "m2", inertia="I2")])
    >>> linkage = symlink.dynamic_linkage(model)
    >>> linkage.dynamic_outputs[:3], linkage.extras["input_torque"]
    (('input_torque', 'joint_A_x', 'joint_A_y'), I2*thetaddot)
    """
    names = dynamic_output_names(model)
    base = model.kinematics
    # Named with placeholders, so that the linkage checks every output name as it checks any extra's ...
    result = DynamicLinkage(base.name, base.loops, base.inputs, base.unknowns,
                            parameters=list(base.parameters) + list(model.new_parameters), points=base.points,
                            roles=base.roles, extras={**base.extras, **{name: sp.S.Zero for name in names}})
    # ... then the expressions, derived on first use.
    result.extras = DerivedOutputs(base.extras, names, lambda: dynamic_outputs(model))  # type: ignore[assignment]
    result.dynamic_outputs = tuple(names)
    result.model = model
    return result


def dynamic_output_names(model: DynamicModel) -> list[str]:
    """The names of :func:`dynamic_outputs`, in its order, without deriving anything.

    >>> from symlink.mechanism.catalog import fourbar
    >>> from symlink.dynamics.model import DynamicModel
    >>> dynamic_output_names(DynamicModel(fourbar()))[:5]
    ['input_torque', 'joint_A_x', 'joint_A_y', 'joint_B_x', 'joint_B_y']
    """
    names = [model.input_effort_name(i) for i in range(len(model.kinematics.inputs))]
    names += _names(model) + ["shaking_force_x", "shaking_force_y", "shaking_moment"]
    if len(model.kinematics.inputs) == 1:
        names += list(EQUATION_OUTPUTS)
    return names


class DerivedOutputs(Mapping[str, sp.Expr]):
    """A dynamic linkage's extras: the kinematic linkage's own, then the dynamic outputs, named at once and derived
    (all together, once) where an expression of one of them is first asked for.

    ``derive`` returns the dynamic outputs by name; they must be ``names``, in order.
    """

    def __init__(self, own: Mapping[str, sp.Expr], names: Sequence[str], derive: Callable[[], Mapping[str, sp.Expr]]):
        self._own, self._names, self._derive = dict(own), list(names), derive
        self._known = set(self._own) | set(self._names)
        self._derived: dict[str, sp.Expr] | None = None

    @property
    def derived(self) -> bool:
        """Whether the dynamic outputs' expressions have been derived (in this process)."""
        return self._derived is not None

    def _expressions(self) -> dict[str, sp.Expr]:
        if self._derived is None:
            found = dict(self._derive())
            if list(found) != self._names:
                raise RuntimeError(f"the dynamic outputs derived ({', '.join(found)}) are not those named "
                                   f"({', '.join(self._names)})")
            self._derived = {**self._own, **{name: expression(value) for name, value in found.items()}}
        return self._derived

    def __getitem__(self, name: str) -> sp.Expr:
        if name in self._own:
            return self._own[name]
        if name not in self._known:
            raise KeyError(name)
        return self._expressions()[name]

    def __contains__(self, name: object) -> bool:
        return name in self._known

    def __iter__(self) -> Iterator[str]:
        return iter([*self._own, *self._names])

    def __len__(self) -> int:
        return len(self._own) + len(self._names)
