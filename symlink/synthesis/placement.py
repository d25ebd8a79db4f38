"""A synthesised design placed in the plane, as a linkage of its own: what a linkage file of the design holds.

Path and motion synthesis (:mod:`symlink.synthesis.general`, :mod:`symlink.synthesis.general_motion`)
place the linkage's frame in the plane: a point ``p`` of the linkage's own frame goes to
``(x0, y0) + scale * R(angle) p`` and every link turns by ``angle``.  A linkage file has no
placement, so :func:`placed_design` writes it into the linkage itself: the scale into the lengths
(every length parameter times ``scale``, which scales every point when the lengths are homogeneous
of degree one, as they are in the catalog), the turn into the vectors' angles (a parameter
``place_angle`` added to each fixed direction and the input's, so that the unknown angles come out
turned too), and the shift as a fixed vector from the origin to the old origin (``place_x,
place_y``), walked at the start and the end of every loop and at the start of every point.  The
input keeps its meaning (measured from the turned frame); the points, the joints drawn and the
unknown angles (a coupler's ``beta``) are where the design put them.

>>> from symlink.mechanism.catalog import slider_crank
>>> linkage, values = placed_design(slider_crank(), {"a": 1.0, "b": 3.0, "offset": 0.0},
...                                 {"x0": 1.0, "y0": 2.0, "angle": math.pi / 2, "scale": 2.0})
>>> values["a"], values["place_x"], [str(v.angle) for _, v in linkage.loops[0].terms][2:4]
(2.0, 1.0, ['place_angle + theta', 'beta'])
"""
from __future__ import annotations

import math
from typing import Mapping

import sympy as sp

from ..numeric.units import PLACEMENT_NAMES  # the shift and the turn a placed linkage adds (kinds of parameter)
from ..symbolic.linkage import Linkage
from ..symbolic.loops import Loop
from ..symbolic.vectors import Vector, VectorSum

__all__ = ["placed_design", "placed_assembly", "with_default_branches", "length_parameters", "PLACEMENT_NAMES"]



def length_parameters(linkage: Linkage) -> set[str]:
    """The parameters that are lengths: scaled by k together they scale every point by k (empty if not so).

    The parameters in the vectors' lengths (loops and points), when every length is homogeneous of
    degree one in them and in the coordinates that are lengths (a slider's travel, solved, scales
    with them), and none of them turns up in an angle.

    >>> from symlink.mechanism.catalog import slider_crank
    >>> sorted(length_parameters(slider_crank()))
    ['a', 'b', 'offset']
    """
    vectors = [v for loop in linkage.loops for _, v in loop.terms]
    vectors += [v for sum_ in linkage.points.values() if sum_ is not None for _, v in sum_.as_sum().terms]
    lengths = set().union(*(v.length.free_symbols for v in vectors))
    symbols = lengths & set(linkage.parameters)
    factor = sp.Dummy("k", positive=True)
    scaled = {symbol: factor * symbol for symbol in lengths & (set(linkage.parameters) | set(linkage.coordinates))}
    for vector in vectors:
        if vector.angle.free_symbols & set(scaled) or sp.expand(vector.length.xreplace(scaled)
                                                                - factor * vector.length) != 0:
            return set()
    return {symbol.name for symbol in symbols}


def placed_design(linkage: Linkage, values: Mapping[str, float],
                  placement: Mapping[str, float]) -> tuple[Linkage, dict[str, float]]:
    """``linkage`` with its points placed by ``placement`` (x0, y0, angle, scale), and the values of its parameters.

    The identity placement returns ``linkage`` and ``values`` as they are.  ``ValueError`` when the
    scale is not 1 and the linkage's lengths are not all parameters (nothing to scale), or when the
    linkage already has a parameter named like :data:`PLACEMENT_NAMES`.
    """
    where = {"x0": 0.0, "y0": 0.0, "angle": 0.0, "scale": 1.0, **placement}
    if not all(math.isfinite(float(v)) for v in where.values()) or not where["scale"] > 0:
        raise ValueError(f"a placement is finite with a positive scale, got {dict(placement)!r}")
    result = {name: float(v) for name, v in values.items()}
    if where["scale"] != 1.0:
        lengths = length_parameters(linkage)
        if not lengths:
            raise ValueError(f"{linkage.name}: a scale of {where['scale']:g} cannot be written into its lengths "
                             "(they are not all parameters); fix the scale at 1")
        result.update({name: result[name] * float(where["scale"]) for name in lengths})
    if where["x0"] == 0.0 and where["y0"] == 0.0 and where["angle"] == 0.0:
        return linkage, result
    taken = {s.name for s in linkage.parameters + linkage.coordinates}
    clash = [name for name in PLACEMENT_NAMES if name in taken]
    if clash:
        raise ValueError(f"{linkage.name} already has a symbol named {clash[0]!r}, which its placement needs")
    x0, y0, turn = sp.symbols(PLACEMENT_NAMES, real=True)
    shift_x, shift_y = Vector(x0, 0, "place_shift_x"), Vector(y0, sp.pi / 2, "place_shift_y")
    shift = shift_x + shift_y
    turned_unknowns = {u: u + turn for u in linkage.unknowns}
    cache: dict[str, Vector] = {}

    def turned(vector: Vector) -> Vector:
        """The vector with its direction turned: the turn added to what the turned unknowns do not turn."""
        if vector.name not in cache:
            moved_by = sp.expand(vector.angle.xreplace(turned_unknowns) - vector.angle)
            if moved_by.free_symbols - {turn}:
                raise ValueError(f"{linkage.name}: the angle {vector.angle} of vector {vector.name} is not linear in "
                                 "the unknowns; its placement cannot be written")
            cache[vector.name] = Vector(vector.length, sp.expand(vector.angle + turn - moved_by), vector.name)
        return cache[vector.name]

    def walked(vectors: Vector | VectorSum | None) -> VectorSum:
        placed = shift
        for sign, vector in (vectors.as_sum().terms if vectors is not None else ()):
            placed = placed + turned(vector) if sign > 0 else placed - turned(vector)
        return placed

    loops = [Loop(walked(loop.vectors) - shift_y - shift_x, name=loop.name) for loop in linkage.loops]  # walked back
    points: dict[str, Vector | VectorSum | None] = {name: walked(vectors) for name, vectors in linkage.points.items()}
    moved = Linkage(linkage.name, loops, inputs=list(linkage.inputs), unknowns=list(linkage.unknowns),
                    parameters=list(linkage.parameters) + [x0, y0, turn], points=points, roles=dict(linkage.roles))
    result.update(place_x=float(where["x0"]), place_y=float(where["y0"]), place_angle=float(where["angle"]))
    return moved, result



def placed_assembly(linkage: Linkage, assembly: Mapping[str, float],
                    placement: Mapping[str, float]) -> dict[str, float]:
    """The unknowns of an assembly of ``linkage`` as they are in its :func:`placed_design`: the guess that picks it there.

    A linkage without a closed form has no branch sign: its assembly is the unknowns' values
    (the initial guess of Newton's method).  Placed, every unknown angle turns by the
    placement's angle and every unknown length scales by its scale.

    >>> from symlink.mechanism.catalog import slider_crank
    >>> placed_assembly(slider_crank(), {"beta": 0.5, "s": 2.0}, {"angle": 1.0, "scale": 3.0})
    {'beta': 1.5, 's': 6.0}
    """
    from ..symbolic.closure import is_angle
    where = {"angle": 0.0, "scale": 1.0, **placement}
    symbols = {q.name: q for q in linkage.unknowns}
    return {name: float(value) + float(where["angle"]) if is_angle(linkage, symbols[name])
            else float(value) * float(where["scale"]) for name, value in assembly.items()}


def with_default_branches(linkage: Linkage, branches: Mapping[str, int]) -> tuple[Linkage, dict[str, int]]:
    """``linkage`` rewritten so that its assembly at ``branches`` is every branch's +1, and the signs it could not.

    A linkage file holds no branch signs, and every command takes +1 by default.  A two-angle
    loop (case 3) whose sign is -1 gets its two unknowns in the other order (they name the
    "first" unknown vector, which +1 turns counter-clockwise: :mod:`symlink.analysis.loopcase`), so that
    its +1 is the assembly that was -1, as :func:`symlink.mechanism.joints.from_joints` orders them for its
    drawing.  A loop of another case whose sign is -1 (a slider's length and an angle, case 2b:
    +1 is the larger travel) cannot be turned so: it is returned in the dict, to be given as
    ``--branch``.  The loops, points and every name are unchanged.

    >>> from symlink.mechanism.catalog import fourbar
    >>> turned, left = with_default_branches(fourbar(), {"branch": -1})
    >>> turned.unknowns, left
    ((phi, beta), {})
    """
    unknowns = list(linkage.unknowns)
    left: dict[str, int] = {}
    for step in linkage.plan if linkage.has_closed_form else ():
        if step.branch is None or int(branches.get(step.branch.name, 1)) == 1:
            continue
        if step.case.name != "3":
            left[step.branch.name] = -1
            continue
        first, second = unknowns.index(step.case.first.symbol), unknowns.index(step.case.second.symbol)
        unknowns[first], unknowns[second] = unknowns[second], unknowns[first]
    if unknowns == list(linkage.unknowns):
        return linkage, left
    turned = Linkage(linkage.name, list(linkage.loops), inputs=list(linkage.inputs), unknowns=unknowns,
                     parameters=list(linkage.parameters), points=dict(linkage.points), roles=dict(linkage.roles),
                     extras=dict(linkage.extras))
    return turned, left
