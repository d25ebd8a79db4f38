"""Mass properties and loads of a one-input (or several-input) linkage: the dynamic model.

A :class:`DynamicModel` puts masses on the bodies that :func:`symlink.mechanism.bodies.mechanism`
reads off a linkage's loops, and loads on its points:

* :class:`MassProperties` of a body: its ``mass``, its centre of mass G given in the
  body's own frame, and its moment of inertia about G.  The frame has its origin at
  one of the body's joints or named points (``origin``, by default its first joint)
  and its x axis along the body's angle: for a link, the time-varying part of the
  angles of its vectors (``beta`` for the four-bar's coupler, ``phi`` for the Watt II
  rocker whose arm DE is at ``phi + alpha``); for a slider block, its guide's whole
  direction, so that on a guide inclined at ``gamma`` G is measured along and across
  the guide.  G lies at ``distance`` from the origin, at ``angle`` counter-clockwise
  from that axis.  A body without mass properties is massless.
* Loads: :class:`Gravity` (a vector acting on every mass), :class:`PointForce` (a
  force at a named point or joint), :class:`BodyTorque` (a couple on a body), and a
  linear :class:`Spring` or :class:`Damper` between two points.  A load at a pin acts
  on the first moving body the pin joins unless ``body`` says which; that choice only
  moves the force between the two reactions of that pin.

Every value is a number, a SymPy expression, or a name: names become real symbols
(checked by :func:`symlink.common.names.identifier`, never parsed), and a name the linkage
already uses is that same symbol.

The model's kinematic building blocks are SymPy expressions of the positions (no
rates): the *velocity coefficients* ``dv/dq'`` of points and ``domega/dq'`` of bodies
for each input ``q`` (velocities are linear in the input rates), from which

* :meth:`DynamicModel.generalised_inertia` ``M(q) = sum(m |dv_G/dq'|^2 + I (domega/dq')^2)``
  (a matrix for several inputs),
* :meth:`DynamicModel.generalised_inertia_slope` ``dM/dq`` (one input),
* :meth:`DynamicModel.applied_generalised_forces` ``Q_applied`` (the virtual power of the
  loads per unit input rate, a function of positions and rates),

so that a one-input linkage moves by ``M q'' + M'(q) q'^2 / 2 = Q_applied + Q_drive``.
:mod:`symlink.dynamics.inverse` adds the driving effort and the joint reactions, and
:func:`symlink.dynamics.inverse.dynamic_linkage` gives a :class:`~symlink.symbolic.linkage.Linkage` whose extra outputs
are all of them, so scenes, exports and LaTeX take them like any other output.

>>> from symlink.mechanism.catalog import fourbar
>>> model = DynamicModel(fourbar(), [MassProperties("crank", "m2", inertia="I2", distance="r2")],
...                      gravity=Gravity(0, "g_y"))
>>> import sympy
>>> sympy.trigsimp(model.generalised_inertia()[0, 0])
I2 + m2*r2**2
>>> model.applied_generalised_forces()[0]
g_y*m2*r2*cos(theta)
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Mapping, Sequence, Union

import sympy as sp

from ..mechanism.bodies import GROUND, PRISMATIC, Body, Mechanism, _moving_part, mechanism
from ..symbolic.closure import is_angle
from ..symbolic.linkage import Linkage
from ..common.names import identifier
from ..symbolic.vectors import Vector, expression, rate, time_derivative
from ..common.display import record_html

__all__ = ["Value", "MassProperties", "Gravity", "PointForce", "BodyTorque", "Spring", "Damper", "Load",
           "DynamicModel"]

#: A value of the model: a number, a SymPy expression, or the name of a symbol.
Value = Union[int, float, str, sp.Expr]


@dataclass(frozen=True)
class MassProperties:
    """A body's mass, centre of mass (``distance`` and ``angle`` from ``origin`` in the body's frame), inertia about it.

    Parameters
    ----------
    body : str
        The body's name (``"crank"``, a role, or a link of the bodies).
    mass : float or str or sympy.Expr
        Its mass: a number, or a symbol's name that becomes a parameter.
    distance, angle : float or str or sympy.Expr, optional
        The centre of mass from ``origin`` in the body's frame (default 0, 0: at the origin).
    inertia : float or str or sympy.Expr, optional
        The moment of inertia about the centre of mass (default 0).
    origin : str, optional
        The joint the centre of mass is measured from (default: the body's first joint).

    Examples
    --------
    >>> import symlink
    >>> model = symlink.DynamicModel(symlink.fourbar(), [symlink.MassProperties("crank", "m2", inertia="I2")])
    >>> symlink.dynamic_linkage(model).extras["input_torque"]  # a crank alone: I2 theta''
    I2*thetaddot
    """

    body: str
    mass: Value
    distance: Value = 0
    angle: Value = 0
    inertia: Value = 0
    origin: str = ""


@dataclass(frozen=True)
class Gravity:
    """The acceleration of gravity as a vector (``Gravity(0, -9.81)``): a force ``m g`` at every centre of mass.

    Parameters
    ----------
    x, y : float or str or sympy.Expr
        The components of the acceleration of gravity in the frame.

    Examples
    --------
    >>> import symlink
    >>> model = symlink.DynamicModel(symlink.fourbar(), [symlink.MassProperties("crank", "m", distance="r")],
    ...                              gravity=symlink.Gravity(0, -9.81))
    >>> torque = symlink.dynamic_linkage(model).extras["input_torque"]
    >>> at_rest = {s: 0 for s in torque.free_symbols if s.name in ("thetadot", "thetaddot")}
    >>> torque.subs(at_rest)  # holding the crank's weight: m g r cos(theta)
    9.81*m*r*cos(theta)
    """

    x: Value
    y: Value


@dataclass(frozen=True)
class PointForce:
    """A force ``(x, y)`` (frame components) at a named point or joint, on ``body`` (default: the first moving one there).

    Parameters
    ----------
    point : str
        The named point or joint it acts at.
    x, y : float or str or sympy.Expr
        The force's components in the frame.
    body : str, optional
        The body it acts on (default: the first moving one at the point).

    Examples
    --------
    >>> import symlink
    >>> force = symlink.PointForce("B", 0, "F")
    >>> model = symlink.DynamicModel(symlink.fourbar(), loads=[force])
    >>> symlink.dynamic_linkage(model).extras["input_torque"]  # a force F up at the crank pin: -F a cos(theta)
    -F*a*cos(theta)
    """

    point: str
    x: Value
    y: Value
    body: str = ""


@dataclass(frozen=True)
class BodyTorque:
    """A couple on a body, counter-clockwise positive.

    Parameters
    ----------
    body : str
        The body it acts on.
    torque : float or str or sympy.Expr
        The couple, counter-clockwise positive.

    Examples
    --------
    >>> import symlink
    >>> model = symlink.DynamicModel(symlink.fourbar(), loads=[symlink.BodyTorque("rocker", "T")])
    >>> symlink.dynamic_linkage(model).extras["input_torque"]  # virtual power: -T phi' / theta'
    -T*a*sin(beta - theta)/(c*sin(beta - phi))
    """

    body: str
    torque: Value


@dataclass(frozen=True)
class Spring:
    """A linear spring between two points: tension ``stiffness (length - free_length)`` pulls them together.

    Parameters
    ----------
    first, second : str
        The two points (named points or joints) it joins.
    stiffness : float or str or sympy.Expr
        Its rate: tension per unit of stretch.
    free_length : float or str or sympy.Expr, optional
        Its length without tension (default 0).
    first_body, second_body : str, optional
        The bodies it is fixed to at each end (default: the first moving one at the point).

    Examples
    --------
    >>> import symlink
    >>> spring = symlink.Spring("B", "D", "k", free_length="L")
    >>> model = symlink.DynamicModel(symlink.fourbar(), loads=[spring])
    >>> "k" in map(str, symlink.dynamic_linkage(model).parameters), spring.free_length
    (True, 'L')
    """

    first: str
    second: str
    stiffness: Value
    free_length: Value = 0
    first_body: str = ""
    second_body: str = ""


@dataclass(frozen=True)
class Damper:
    """A linear damper between two points: tension ``coefficient * (rate of their distance)``.

    Parameters
    ----------
    first, second : str
        The two points (named points or joints) it joins.
    coefficient : float or str or sympy.Expr
        Tension per unit rate of their distance.
    first_body, second_body : str, optional
        The bodies it is fixed to at each end (default: the first moving one at the point).

    Examples
    --------
    >>> import symlink
    >>> damper = symlink.Damper("B", "D", "cd")
    >>> torque = symlink.dynamic_linkage(symlink.DynamicModel(symlink.fourbar(), loads=[damper])).extras["input_torque"]
    >>> torque.subs({s: 0 for s in torque.free_symbols if s.name == "thetadot"})  # it resists motion only
    0
    """

    first: str
    second: str
    coefficient: Value
    first_body: str = ""
    second_body: str = ""


Load = Union[PointForce, BodyTorque, Spring, Damper]


@dataclass(frozen=True)
class AppliedForce:
    """One force ``(x, y)`` on ``body`` at ``point`` (a pair of expressions), as the loads resolve into."""

    body: str
    point: tuple[sp.Expr, sp.Expr]
    force: tuple[sp.Expr, sp.Expr]


class DynamicModel:
    """Mass properties and loads on the bodies of ``linkage`` (see the module docstring).

    ``bodies`` is passed to :func:`symlink.mechanism.bodies.mechanism` where the vectors alone
    do not say which body a vector lies on.

    Parameters
    ----------
    linkage : Linkage
        The kinematic linkage.
    masses : sequence of MassProperties, optional
        The bodies' masses, centres of mass and inertias.
    loads : sequence of PointForce, BodyTorque, Spring or Damper, optional
        The applied loads.
    gravity : Gravity, optional
        The acceleration of gravity (none by default).
    bodies : mapping of str to sequence of str, optional
        Which vectors lie on which body, where the vectors alone do not say.

    Examples
    --------
    >>> import symlink
    >>> model = symlink.DynamicModel(symlink.fourbar(), [symlink.MassProperties("crank", "m", distance="r")],
    ...                              gravity=symlink.Gravity(0, -9.81))
    >>> torque = symlink.dynamic_linkage(model).extras["input_torque"]
    >>> at_rest = {s: 0 for s in torque.free_symbols if s.name in ("thetadot", "thetaddot")}
    >>> torque.subs(at_rest)  # holding the crank's weight: m g r cos(theta)
    9.81*m*r*cos(theta)
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    def __init__(self, linkage: Linkage, masses: Sequence[MassProperties] = (), loads: Sequence[Load] = (),
                 gravity: Gravity | None = None, bodies: Mapping[str, Sequence[str]] | None = None) -> None:
        if not isinstance(linkage, Linkage):
            raise ValueError(f"a dynamic model needs a Linkage, not {linkage!r}")
        if not linkage.has_closed_form:
            raise ValueError(f"{linkage.name} has no closed-form solve plan; its dynamics cannot be derived in "
                             "closed form")
        self.kinematics = linkage
        self.mechanism: Mechanism = mechanism(linkage, bodies)
        if self.mechanism.mobility != len(linkage.inputs):
            raise ValueError(f"{linkage.name} has mobility {self.mechanism.mobility} but {len(linkage.inputs)} "
                             "inputs; the dynamics need one input per degree of freedom")
        self._symbols: dict[str, sp.Symbol] = {}
        for symbol in set(linkage.parameters) | set(linkage.coordinates):
            self._symbols[symbol.name] = symbol
        for expr in list(linkage.extras.values()):
            for symbol in expr.free_symbols:
                self._symbols.setdefault(symbol.name, symbol)
        self.new_parameters: list[sp.Symbol] = []
        moving = [body.name for body in self.mechanism.bodies if not body.is_ground]
        self.masses: dict[str, tuple[sp.Expr, tuple[sp.Expr, sp.Expr], sp.Expr]] = {}
        for item in masses:
            if not isinstance(item, MassProperties):
                raise ValueError(f"masses must be MassProperties, not {item!r}")
            body = self._body(item.body, "mass properties")
            if body.is_ground:
                raise ValueError("the ground does not move: give mass properties to moving bodies only")
            if body.name in self.masses:
                raise ValueError(f"body {body.name!r} has mass properties twice")
            origin = item.origin or (body.joints[0] if body.joints else "")
            if origin not in body.joints and origin not in body.points:
                raise ValueError(f"mass properties of {body.name!r}: {origin!r} is not a joint or point of it "
                                 f"({', '.join(dict.fromkeys(body.joints + body.points))})")
            ox, oy = self.point(origin)
            distance = self.value(item.distance, f"{body.name} centre distance")
            angle = self.value(item.angle, f"{body.name} centre angle") + self.body_angle(body.name)
            centre = (ox + distance * sp.cos(angle), oy + distance * sp.sin(angle))
            self.masses[body.name] = (self.value(item.mass, f"{body.name} mass"), centre,
                                      self.value(item.inertia, f"{body.name} inertia"))
        self.moving_bodies = tuple(moving)
        self.gravity = (sp.S.Zero, sp.S.Zero) if gravity is None else (
            self.value(gravity.x, "gravity x"), self.value(gravity.y, "gravity y"))
        if gravity is not None and not isinstance(gravity, Gravity):
            raise ValueError(f"gravity must be a Gravity, not {gravity!r}")
        self.loads = tuple(loads)
        self.forces: list[AppliedForce] = []
        self.couples: list[tuple[str, sp.Expr]] = []
        for name, (mass, centre, _) in self.masses.items():
            if self.gravity != (0, 0):
                self.forces.append(AppliedForce(name, centre, (mass * self.gravity[0], mass * self.gravity[1])))
        for load in self.loads:
            self._resolve(load)

    # --- values, points and bodies -------------------------------------------------------
    def value(self, value: Value, where: str) -> sp.Expr:
        """A model value as an expression: a name becomes (or is) a real symbol; text is never parsed."""
        if isinstance(value, str):
            name = identifier(value, where)
            if name not in self._symbols:
                self._symbols[name] = sp.Symbol(name, real=True)
                self.new_parameters.append(self._symbols[name])
            symbol = self._symbols[name]
            if symbol in self.kinematics.coordinates:
                raise ValueError(f"{where}: {name!r} is a coordinate of {self.kinematics.name}, not a constant")
            return symbol
        try:
            result = expression(value)
        except ValueError as error:
            raise ValueError(f"{where}: {error}") from None
        unknown = [s for s in result.free_symbols if s.name not in self._symbols or self._symbols[s.name] != s]
        for symbol in unknown:
            identifier(symbol.name, where)
            if symbol.name in self._symbols:
                raise ValueError(f"{where}: two different symbols are named {symbol.name!r}; use one")
            self._symbols[symbol.name] = symbol
            self.new_parameters.append(symbol)
        if result.free_symbols & set(self.kinematics.coordinates):
            raise ValueError(f"{where}: {result} depends on a coordinate; give a constant")
        return result

    def _body(self, name: str, where: str) -> Body:
        try:
            return self.mechanism.body(name)
        except ValueError as error:
            raise ValueError(f"{where}: {error}") from None

    def point(self, name: str) -> tuple[sp.Expr, sp.Expr]:
        """A named point or joint of the linkage as ``(x, y)`` in the frame."""
        if name in self.kinematics.points:
            return self.kinematics.point(name)
        for joint in self.mechanism.joints:
            if joint.name == name:
                if joint.position is None:
                    raise ValueError(f"joint {name!r} is not tied to the origin by a point's vectors; name a point "
                                     "there")
                return joint.position.x, joint.position.y
        known = list(self.kinematics.points) + [j.name for j in self.mechanism.joints]
        raise ValueError(f"{self.kinematics.name} has no point or joint {name!r}; it has "
                         f"{', '.join(dict.fromkeys(known))}")

    def _point_body(self, point: str, body: str, where: str) -> str:
        """The body a load at ``point`` acts on: ``body`` if given (it must carry the point), else the first moving one."""
        self.point(point)
        carriers = [b.name for b in self.mechanism.bodies if point in b.joints or point in b.points]
        if body:
            if body not in carriers:
                raise ValueError(f"{where}: {point!r} is not on body {body!r} (it is on {', '.join(carriers)})")
            return body
        moving = [name for name in carriers if name != GROUND]
        return moving[0] if moving else GROUND

    @cached_property
    def _vectors(self) -> dict[str, Vector]:
        found: dict[str, Vector] = {}
        chains = [loop.terms for loop in self.kinematics.loops]
        chains += [p.as_sum().terms for p in self.kinematics.points.values() if p is not None]
        for terms in chains:
            for _, vector in terms:
                found.setdefault(vector.name or str(vector), vector)
        return found

    def body_angle(self, body: str) -> sp.Expr:
        """The angle of a body's frame: the moving part of its vectors' angles; a block's is its guide's
        direction (fixed part included: a block on a guide inclined at gamma has its x axis along the guide);
        0 on the ground."""
        found = self._body(body, "body angle")
        coordinates = set(self.kinematics.coordinates)
        for name in found.vectors:
            moving = _moving_part(self._vectors[name].angle, coordinates)
            if moving != 0:
                return moving
        for joint in self.mechanism.joints:
            if joint.kind == PRISMATIC and found.name == joint.bodies[-1] and joint.direction is not None:
                return expression(joint.direction)  # the block slides along its guide: its frame is the guide's
        for joint in self.mechanism.joints:
            if joint.kind == PRISMATIC and found.name in joint.bodies and joint.direction is not None:
                return _moving_part(joint.direction, coordinates)
        return sp.S.Zero

    def _resolve(self, load: Load) -> None:
        if isinstance(load, PointForce):
            body = self._point_body(load.point, load.body, f"force at {load.point}")
            self.forces.append(AppliedForce(body, self.point(load.point),
                                            (self.value(load.x, f"force at {load.point}"),
                                             self.value(load.y, f"force at {load.point}"))))
        elif isinstance(load, BodyTorque):
            self._body(load.body, "torque")
            self.couples.append((load.body, self.value(load.torque, f"torque on {load.body}")))
        elif isinstance(load, (Spring, Damper)):
            kind = "spring" if isinstance(load, Spring) else "damper"
            where = f"{kind} {load.first}-{load.second}"
            first = self._point_body(load.first, load.first_body, where)
            second = self._point_body(load.second, load.second_body, where)
            p, r = self.point(load.first), self.point(load.second)
            dx, dy = r[0] - p[0], r[1] - p[1]
            length = sp.sqrt(dx**2 + dy**2)
            if isinstance(load, Spring):
                tension = self.value(load.stiffness, where) * (length - self.value(load.free_length, where))
            else:
                coordinates = self.kinematics.coordinates
                stretch_rate = (dx * time_derivative(dx, coordinates) + dy * time_derivative(dy, coordinates)) / length
                tension = self.value(load.coefficient, where) * stretch_rate
            self.forces.append(AppliedForce(first, p, (tension * dx / length, tension * dy / length)))
            self.forces.append(AppliedForce(second, r, (-tension * dx / length, -tension * dy / length)))
        else:
            raise ValueError(f"a load is a PointForce, BodyTorque, Spring or Damper, not {load!r}")

    # --- kinematic building blocks -------------------------------------------------------
    @cached_property
    def rate_coefficients(self) -> dict[sp.Symbol, tuple[sp.Expr, ...]]:
        """``dq_j'/dq_i'`` for every coordinate q_j and input q_i: expressions of the positions only."""
        linkage = self.kinematics
        inputs = linkage.inputs
        result: dict[sp.Symbol, tuple[sp.Expr, ...]] = {
            q: tuple(sp.S.One if p == q else sp.S.Zero for p in inputs) for q in inputs}
        by_rate = {rate(q): q for q in linkage.coordinates}
        for symbol, expr in linkage.velocities.items():
            row = []
            for index, _ in enumerate(inputs):
                total = sp.S.Zero
                for other in expr.free_symbols & set(by_rate):
                    partial = sp.diff(expr, other)
                    total += partial * result[by_rate[other]][index]  # linear: no rate left
                row.append(total)
            result[by_rate[symbol]] = tuple(row)
        return result

    def point_coefficients(self, point: tuple[sp.Expr, sp.Expr]) -> list[tuple[sp.Expr, sp.Expr]]:
        """``dv/dq_i'`` of a point given by its ``(x, y)``, one pair an input."""
        rows = []
        for index in range(len(self.kinematics.inputs)):
            rows.append(tuple(sum((sp.diff(c, q) * k[index] for q, k in self.rate_coefficients.items()
                                   if c.has(q)), sp.S.Zero) for c in point))
        return rows

    def angle_coefficients(self, body: str) -> list[sp.Expr]:
        """``domega/dq_i'`` of a body, one an input."""
        angle = self.body_angle(body)
        return [sum((sp.diff(angle, q) * k[index] for q, k in self.rate_coefficients.items() if angle.has(q)),
                    sp.S.Zero) for index in range(len(self.kinematics.inputs))]

    def acceleration_of(self, point: tuple[sp.Expr, sp.Expr]) -> tuple[sp.Expr, sp.Expr]:
        """A point's acceleration in terms of coordinates, their rates and accelerations (symbols)."""
        coordinates = self.kinematics.coordinates
        return tuple(time_derivative(time_derivative(c, coordinates), coordinates) for c in point)

    def angular_acceleration(self, body: str) -> sp.Expr:
        coordinates = self.kinematics.coordinates
        return time_derivative(time_derivative(self.body_angle(body), coordinates), coordinates)

    # --- the generalised quantities --------------------------------------------------------
    def generalised_inertia(self) -> sp.Matrix:
        """``M(q)``: ``M_ik = sum(m dv_G/dq_i' . dv_G/dq_k' + I domega/dq_i' domega/dq_k')`` (positions only)."""
        n = len(self.kinematics.inputs)
        result = sp.zeros(n, n)
        for body, (mass, centre, inertia) in self.masses.items():
            v = self.point_coefficients(centre)
            w = self.angle_coefficients(body)
            for i in range(n):
                for k in range(n):
                    result[i, k] += mass * (v[i][0] * v[k][0] + v[i][1] * v[k][1]) + inertia * w[i] * w[k]
        return result

    def generalised_inertia_slope(self) -> sp.Expr:
        """``dM/dq`` of a one-input linkage: the total derivative along the motion (unknowns follow the input)."""
        if len(self.kinematics.inputs) != 1:
            raise ValueError("dM/dq is defined here for a one-input linkage")
        inertia = self.generalised_inertia()[0, 0]
        return sum((sp.diff(inertia, q) * k[0] for q, k in self.rate_coefficients.items() if inertia.has(q)),
                   sp.S.Zero)

    def applied_generalised_forces(self) -> list[sp.Expr]:
        """``Q_applied,i = sum(F . dv_P/dq_i') + sum(C domega/dq_i')``: the loads' virtual power per input rate."""
        n = len(self.kinematics.inputs)
        result = [sp.S.Zero] * n
        for force in self.forces:
            v = self.point_coefficients(force.point)
            for i in range(n):
                result[i] += force.force[0] * v[i][0] + force.force[1] * v[i][1]
        for body, couple in self.couples:
            w = self.angle_coefficients(body)
            for i in range(n):
                result[i] += couple * w[i]
        return result

    def input_effort_name(self, index: int) -> str:
        """``input_torque`` (an angle input) or ``input_force`` (a slider's travel), with ``_<input>`` for several."""
        q = self.kinematics.inputs[index]
        stem = "input_torque" if is_angle(self.kinematics, q) else "input_force"
        return stem if len(self.kinematics.inputs) == 1 else f"{stem}_{q.name}"
