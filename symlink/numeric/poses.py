"""A linkage's poses: every joint and named point placed, over a sweep of its inputs.

The bodies and joints come from the linkage's vectors (:mod:`symlink.mechanism.bodies`);
the pose from its closed form (:class:`~symlink.numeric.solver.Solver`) or, where it has
none, from Newton's method (:class:`~symlink.numeric.solver.NumericSolver`).  Every joint
is placed by its sum of vectors from the origin, each vector evaluated at the solved
coordinates, so a drawing, an animation, a part or the studio needs no knowledge of the
linkage beyond its loops and points.  Unassembled values are NaN and masked, never a
wrong pose.

>>> from symlink.mechanism.catalog import fourbar
>>> geometry = Geometry(fourbar())
>>> poses = geometry.poses(dict(a=20, b=66, c=56, d=80), {"theta": numpy.array([0.0])})
>>> round(complex(poses.positions["C"][0]).real, 3)  # seed 003 by hand: 80 + 56 cos(110.74 deg) = 60.167
60.167
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Mapping, Sequence

import numpy
import sympy as sp

from ..mechanism.bodies import PRISMATIC, Mechanism, drawn_points, mechanism
from ..symbolic.closure import is_angle
from ..codegen.numpy import load_numpy_module, numpy_module
from ..symbolic.linkage import Linkage, Program
from .reachability import scanned_range
from .solver import NumericSolver, Solver
from ..symbolic.vectors import Vector

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["Geometry", "Poses", "input_range", "sweep_inputs", "traced_paths", "TRACE_SAMPLES"]

#: Samples of the sweep along which traced paths are drawn.
TRACE_SAMPLES = 721
#: Guesses tried, at the first input value, to find an assembly for Newton's method.
GUESSES = 400

@dataclass(frozen=True)
class Poses:
    """A linkage's joints and points over a sweep of its inputs.

    ``inputs`` maps each input's name to its values (shape ``(n,)``);
    ``positions`` maps every joint and named point to complex positions
    ``x + i y`` (NaN where it cannot be assembled); ``directions`` maps each
    slider to its guide's angle; ``assembled`` is the mask.
    """

    inputs: dict[str, numpy.ndarray]
    positions: dict[str, numpy.ndarray]
    directions: dict[str, numpy.ndarray]
    assembled: numpy.ndarray

    def __len__(self) -> int:
        return len(self.assembled)


class Geometry:
    """A linkage made ready to draw: its :class:`~symlink.mechanism.bodies.Mechanism`, its solver and its vectors.

    Built once for a drawing or an animation; :meth:`poses` solves and places
    every joint.  ``guess`` (unknowns by name) picks the assembly where the
    linkage has no closed form; by default one is searched for.
    """

    def __init__(self, linkage: Linkage, bodies: Mapping[str, Sequence[str]] | None = None) -> None:
        self.linkage = linkage
        self.mechanism: Mechanism = mechanism(linkage, bodies)
        sums = drawn_points(linkage, self.mechanism)
        self.sums = sums
        vectors: list[Vector] = []
        for total in sums.values():
            vectors += [v for _, v in total.terms if v not in vectors]
        self.vectors = vectors
        self.sliders = [j for j in self.mechanism.joints if j.kind == PRISMATIC]
        outputs: dict[str, sp.Expr] = {}
        for k, vector in enumerate(vectors):
            outputs[f"x{k}"], outputs[f"y{k}"] = vector.x, vector.y
        for k, joint in enumerate(self.sliders):
            outputs[f"direction{k}"] = joint.direction
        arguments = tuple(linkage.coordinates) + tuple(linkage.parameters)
        program = Program(arguments, (), outputs)
        self._evaluate = load_numpy_module(numpy_module([("ends", program, "")], "Vectors of a drawing."))["ends"]
        if linkage.has_closed_form:
            self.solver: Solver | NumericSolver = Solver(linkage, [q.name for q in linkage.unknowns])
        else:
            self.solver = NumericSolver(linkage)

    @property
    def input_names(self) -> list[str]:
        return [q.name for q in self.linkage.inputs]

    def check_values(self, values: Mapping[str, float]) -> dict[str, float]:
        """``values`` completed: inputs default to 0, branches to +1; ``ValueError`` naming a missing or unknown one."""
        linkage = self.linkage
        names = [s.name for s in linkage.parameters] + self.input_names
        branches = [b.name for b in linkage.branches]
        unknown = sorted(set(values) - set(names) - set(branches))
        if unknown:
            raise ValueError(f"{linkage.name} has no value {unknown[0]!r}; it takes {', '.join(names + branches)}")
        missing = [s.name for s in linkage.parameters if s.name not in values]
        if missing:
            raise ValueError(f"{linkage.name} needs a value for {', '.join(missing)}")
        completed = {name: 0.0 for name in self.input_names} | {name: 1 for name in branches}
        completed.update(values)
        for name, value in completed.items():
            if isinstance(value, bool) or not isinstance(value, (int, float, numpy.integer, numpy.floating)) \
                    or not math.isfinite(value):
                raise ValueError(f"{name} must be a finite number, got {value!r}")
        return completed

    def find_guess(self, values: Mapping[str, float]) -> dict[str, float]:
        """An assembly at the inputs of ``values`` for Newton's method: deterministic trial guesses, first that closes."""
        linkage = self.linkage
        scale = sum(abs(float(values[s.name])) for s in linkage.parameters) or 1.0
        generator = numpy.random.default_rng(0)
        inputs = {name: numpy.atleast_1d(float(values[name])) for name in self.input_names}
        parameters = {s.name: float(values[s.name]) for s in linkage.parameters}
        for _ in range(GUESSES):
            guess = {q.name: float(generator.uniform(-math.pi, math.pi)) if is_angle(linkage, q)
                     else float(generator.uniform(-scale, scale)) for q in linkage.unknowns}
            result = self.solver(guess=guess, **inputs, **parameters)
            if bool(numpy.all(result["assembled"])):
                return {q.name: float(result[q.name][0]) for q in linkage.unknowns}
        raise ValueError(f"{linkage.name} cannot be assembled at "
                         + ", ".join(f"{name} = {float(values[name]):g}" for name in self.input_names)
                         + f" (Newton's method closed from none of {GUESSES} starting guesses); "
                         "give a guess near an assembly")

    def poses(self, values: Mapping[str, float], sweep: Mapping[str, "ArrayLike"] | None = None,
              guess: Mapping[str, float] | None = None) -> Poses:
        """Every joint and point at ``values``, with inputs swept over ``sweep`` (name -> values) where given.

        Without a closed form the sweep is followed by Newton's method from
        ``guess`` (default: :meth:`find_guess` at the sweep's first values).
        """
        values = self.check_values(values)
        swept = {name: numpy.atleast_1d(numpy.asarray(v, dtype=float)) for name, v in (sweep or {}).items()}
        for name in swept:
            if name not in self.input_names:
                raise ValueError(f"{self.linkage.name} has no input {name!r}; its inputs are "
                                 f"{', '.join(self.input_names)}")
        length = max([len(v) for v in swept.values()] + [1])
        inputs = {name: numpy.broadcast_to(swept.get(name, numpy.float64(values[name])), (length,)).astype(float)
                  for name in self.input_names}
        parameters = {s.name: float(values[s.name]) for s in self.linkage.parameters}
        if isinstance(self.solver, Solver):
            branches = {b.name: int(values[b.name]) for b in self.linkage.branches}
            result = self.solver(**inputs, **parameters, **branches)
        else:
            base = {name: float(values[name]) for name in self.input_names}
            if guess is None:
                guess = self.find_guess(parameters | base)
            if any(inputs[name][0] != base[name] for name in base):  # follow the assembly to the sweep's start
                steps = max(2, int(max(abs(inputs[n][0] - base[n]) for n in base) / (2 * math.pi) * TRACE_SAMPLES))
                path = {name: numpy.linspace(base[name], inputs[name][0], steps) for name in base}
                there = self.solver(guess=dict(guess), **path, **parameters)
                guess = {q.name: float(there[q.name][-1]) for q in self.linkage.unknowns}
            result = self.solver(guess=dict(guess), **inputs, **parameters)
        assembled = numpy.broadcast_to(numpy.asarray(result["assembled"], dtype=bool), (length,)).copy()
        coordinates = {q.name: numpy.broadcast_to(numpy.asarray(result[q.name], dtype=float), (length,))
                       for q in self.linkage.unknowns}
        with numpy.errstate(invalid="ignore"):
            ends = self._evaluate(**inputs, **coordinates, **parameters, check=False)  # NaN where not assembled
        vectors = {vector: ends[f"x{k}"] + 1j * ends[f"y{k}"] for k, vector in enumerate(self.vectors)}
        positions = {}
        for name, total in self.sums.items():
            place = numpy.zeros(length, dtype=complex)
            for sign, vector in total.terms:
                place = place + sign * vectors[vector]
            positions[name] = numpy.where(assembled, place, complex(numpy.nan, numpy.nan))
        directions = {joint.name: numpy.broadcast_to(ends[f"direction{k}"], (length,))
                      for k, joint in enumerate(self.sliders)}
        return Poses(inputs, positions, directions, assembled)


def input_range(geometry: Geometry, values: Mapping[str, float],
                guess: Mapping[str, float] | None = None) -> list[tuple[float, float]]:
    """Where the first input can go with the others held at ``values``, as closed intervals (radians).

    With a closed form: :func:`~symlink.numeric.reachability.scanned_range` of the
    solver's ``assembled`` mask, edges bisected to rounding.  Without one,
    Newton's method is followed a turn forward and a turn back from the
    input's value, and the stretch it stays assembled in is returned (to the
    scan's step).  ``[(-pi, pi)]`` is a full turn.
    """
    values = geometry.check_values(values)
    name = geometry.input_names[0]
    if isinstance(geometry.solver, Solver):
        return scanned_range(lambda angles: geometry.poses(values, {name: angles}).assembled)
    start = float(values[name])
    step = 2 * math.pi / TRACE_SAMPLES
    turn = step * numpy.arange(TRACE_SAMPLES + 1)
    forward = _followed(geometry, values, name, start + turn, guess)
    if forward == len(turn):
        return [(-math.pi, math.pi)]
    backward = _followed(geometry, values, name, start - turn, guess)
    return [(start - turn[backward - 1], start + turn[forward - 1])] if forward else []


def _followed(geometry: Geometry, values: Mapping[str, float], name: str, sweep: numpy.ndarray,
              guess: Mapping[str, float] | None) -> int:
    """How many values of ``sweep`` Newton's method follows from its start (it stops where it cannot close)."""
    def reaches(count: int) -> bool:
        try:
            return bool(geometry.poses(values, {name: sweep[:count]}, guess).assembled.all())
        except ValueError:
            return False

    if reaches(len(sweep)):
        return len(sweep)
    low, high = 0, len(sweep)  # reaches(low) (or low == 0), not reaches(high)
    while high - low > 1:
        middle = (low + high) // 2
        low, high = (middle, high) if reaches(middle) else (low, middle)
    return low


def sweep_inputs(spans: Sequence[tuple[float, float]], start: float, samples: int) -> numpy.ndarray:
    """Input values from ``start`` over its span (else the first span): a full turn, or out and back.

    A full turn gives ``start + 2 pi k / samples``; a span ``[low, high]`` gives
    ``low + (high - low) (1 - cos(2 pi k / samples + phase)) / 2``, the phase
    putting the first value at ``start`` (at ``low`` where ``start`` is outside).
    It goes forward to ``high`` and back to ``low``, slowing at the ends as a
    rocker does, and never leaves the span, so every value can be assembled.

    >>> [round(math.degrees(x)) for x in sweep_inputs([(0.0, math.pi / 2)], 0.0, 4)]
    [0, 45, 90, 45]
    >>> [round(math.degrees(x)) for x in sweep_inputs([(-math.pi / 2, math.pi / 2)], 0.0, 4)]
    [0, 90, 0, -90]
    """
    if not spans:
        raise ValueError("the linkage cannot be assembled anywhere along its input")
    k = numpy.arange(samples)
    if spans[0][1] - spans[0][0] >= 2 * math.pi:
        return start + 2 * math.pi * k / samples
    for shift in (0.0, 2 * math.pi, -2 * math.pi):
        held = [(low, high) for low, high in spans if low <= start + shift <= high]
        if held:
            (low, high), start = held[0], start + shift
            break
    else:
        (low, high), start = spans[0], spans[0][0]
    phase = math.acos(min(1.0, max(-1.0, 1 - 2 * (start - low) / (high - low)))) if high > low else 0.0
    values = low + (high - low) * (1 - numpy.cos(2 * math.pi * k / samples + phase)) / 2
    values[0] = start
    return numpy.clip(values, low, high)


def traced_paths(geometry: Geometry, values: Mapping[str, float], trace: Sequence[str],
                 guess: Mapping[str, float] | None = None, samples: int = TRACE_SAMPLES) -> dict[str, numpy.ndarray]:
    """The paths of the joints or points ``trace`` over the reachable sweep of the first input."""
    known = [name for name in geometry.sums if not name.endswith(" guide")]
    for name in trace:
        if name not in known:
            raise ValueError(f"{geometry.linkage.name} has no point or joint {name!r} to trace; "
                             f"it has {', '.join(known)}")
    if not trace:
        return {}
    completed = geometry.check_values(values)
    first = geometry.input_names[0]
    spans = input_range(geometry, completed, guess)
    angles = sweep_inputs(spans, float(completed[first]), samples)
    if spans[0][1] - spans[0][0] >= 2 * math.pi:
        angles = numpy.append(angles, angles[0] + 2 * math.pi)  # a closed curve
    poses = geometry.poses(completed, {first: angles}, guess)
    return {name: poses.positions[name] for name in trace}
