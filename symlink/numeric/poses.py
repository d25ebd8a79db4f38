"""A linkage's poses: every joint and named point placed, over a sweep of its inputs.

The bodies and joints come from the linkage's vectors (:mod:`symlink.mechanism.bodies`);
the pose from its closed form (:class:`~symlink.numeric.solver.Solver`) or, where it has
none, from Newton's method (:class:`~symlink.numeric.solver.NumericSolver`).  Every joint
is placed by its sum of vectors from the origin, each vector evaluated at the solved
coordinates, so a drawing, an animation, a part or the studio needs no knowledge of the
linkage beyond its loops and points.  Unassembled values are NaN and masked, never a
wrong pose.

What placing needs is plain data and NumPy code (a :class:`Placement`): the names, which
of them are angles, each place as a sum of numbered vectors, the bodies' outlines, and a
generated module that evaluates the vectors' ends (:func:`placement_entry_text`).  A
:class:`Geometry` makes it from a linkage (SymPy); :func:`cached_placement` takes it, and
the solver, from the disk cache (:mod:`symlink.numeric.cache`), so that a warm drawing
builds no linkage and imports no SymPy.

>>> from symlink.mechanism.catalog import fourbar
>>> geometry = Geometry(fourbar())
>>> poses = geometry.poses(dict(a=20, b=66, c=56, d=80), {"theta": numpy.array([0.0])})
>>> round(complex(poses.positions["C"][0]).real, 3)  # seed 003 by hand: 80 + 56 cos(110.74 deg) = 60.167
60.167
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

import numpy

from .crank_ranges import scanned_range
from ..common.display import record_html

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..mechanism.bodies import Body, Mechanism
    from ..symbolic.linkage import Linkage
    from ..symbolic.vectors import Vector, VectorSum

__all__ = ["Placement", "Geometry", "Poses", "input_range", "sweep_inputs", "traced_paths", "TRACE_SAMPLES",
           "placement_entry_text", "cached_placement", "PLACEMENT", "PLACEMENT_ENTRY_KIND"]

#: Samples of the sweep along which traced paths are drawn.
TRACE_SAMPLES = 721
#: Guesses tried, at the first input value, to find an assembly for Newton's method.
GUESSES = 400
#: The name of the dictionary of plain facts in a placement's module (:func:`placement_entry_text`), and of its
#: function that evaluates the vectors' ends.
PLACEMENT, ENDS = "PLACEMENT", "ends"
#: The kind of cache entry of a placement (:func:`cached_placement`).
PLACEMENT_ENTRY_KIND = "placement/1"


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


def _corners(mechanism: Mechanism, sums: Mapping[str, VectorSum], body: Body) -> list[str]:
    """What a body's outline passes through: its pins, slider blocks it carries, and its named points."""
    from ..mechanism.bodies import REVOLUTE
    corners = []
    for name in body.joints:
        joint = mechanism.joint(name)
        if joint.kind == REVOLUTE or joint.bodies[-1] == body.name:  # a pin, or the block this body is
            corners.append(name)
    corners += [p for p in body.points if p not in corners]
    seen, unique = [], []
    for name in corners:  # a block pinned where its slider joint is (B on the inverted slider-crank)
        total = sums.get(name)
        key = None if total is None else tuple(sorted((s, str(v)) for s, v in total.terms))
        if total is not None and key not in seen:
            seen.append(key)
            unique.append(name)
    return unique


def _placement_parts(linkage: Linkage, bodies: Mapping[str, Sequence[str]] | None = None
                     ) -> tuple[Mechanism, dict[str, VectorSum], list[Vector], str]:
    """A linkage's mechanism, its places as sums of vectors, the vectors, and the text of its placement module."""
    import sympy as sp

    from ..codegen.numpy import numpy_module
    from ..mechanism.bodies import GROUND, PRISMATIC, REVOLUTE, drawn_points, mechanism
    from ..symbolic.closure import is_angle
    from ..symbolic.linkage import Program
    found = mechanism(linkage, bodies)
    sums = drawn_points(linkage, found)
    vectors: list[Vector] = []
    for total in sums.values():
        vectors += [v for _, v in total.terms if v not in vectors]
    sliders = [j for j in found.joints if j.kind == PRISMATIC]
    outputs: dict[str, sp.Expr] = {}
    for k, vector in enumerate(vectors):
        outputs[f"x{k}"], outputs[f"y{k}"] = vector.x, vector.y
    for k, joint in enumerate(sliders):
        assert joint.direction is not None  # a slider's guide has a direction
        outputs[f"direction{k}"] = joint.direction
    program = Program(tuple(linkage.coordinates) + tuple(linkage.parameters), (), outputs)
    named = linkage.parameters + linkage.inputs + linkage.unknowns
    # what turns a named point's vectors (a view shows those parameters and inputs as angles)
    turning = set().union(*(v.angle.free_symbols for point in linkage.points.values() if point is not None
                            for _, v in point.as_sum().terms))
    facts = {
        "name": linkage.name, "closed_form": bool(linkage.has_closed_form),
        "inputs": [q.name for q in linkage.inputs], "unknowns": [q.name for q in linkage.unknowns],
        "parameters": [s.name for s in linkage.parameters], "branches": [b.name for b in linkage.branches],
        "angles": [s.name for s in named if is_angle(linkage, s)],
        "places": {name: [[int(sign), vectors.index(v)] for sign, v in total.terms] for name, total in sums.items()},
        "sliders": [[joint.name, GROUND in joint.bodies[:1]] for joint in sliders],
        "bodies": [[body.name, _corners(found, sums, body)] for body in found.bodies if not body.is_ground],
        "pivots": [j.name for j in found.joints if j.kind == REVOLUTE and j.grounded and j.name in sums],
        "pins": [j.name for j in found.joints if j.kind == REVOLUTE and j.name in sums],
        "points": list(linkage.points),
        "roles": {role: symbol.name for role, symbol in linkage.roles.items()},
        "positive": [s.name for s in linkage.parameters if s.is_positive],
        "turning": [s.name for s in linkage.parameters + linkage.inputs if s in turning],
    }
    text = numpy_module([(ENDS, program, "")], "Vectors of a drawing.")
    return found, sums, vectors, text.rstrip() + f"\n\n\n#: What placing needs (symlink.numeric.poses).\n{PLACEMENT} = {facts!r}\n"


def placement_entry_text(linkage: Linkage, bodies: Mapping[str, Sequence[str]] | None = None) -> str:
    """The placement of ``linkage`` as a NumPy module: the function ``ends`` of its vectors' ends and slider
    directions (from its coordinates and parameters), and the dictionary ``PLACEMENT`` of plain facts (names,
    which are angles, each place as ``[sign, vector]`` terms, sliders, bodies' outlines, pivots, pins, points,
    the symbols' roles, the positive parameters (lengths) and the parameters and inputs that turn a named point's
    vectors).

    What a :class:`Placement` is made from; a cache entry (:func:`cached_placement`).

    >>> from symlink.codegen.loading import load_numpy_module
    >>> from symlink.mechanism.catalog import fourbar
    >>> facts = load_numpy_module(placement_entry_text(fourbar()))["PLACEMENT"]
    >>> facts["places"]["C"], facts["pivots"], facts["angles"]  # C = AB + BC, vectors 0 and 1
    ([[1, 0], [1, 1]], ['A', 'D'], ['theta', 'beta', 'phi'])
    """
    return _placement_parts(linkage, bodies)[3]


class Placement:
    """Where every joint and named point of a linkage is, from plain data and NumPy code (see the module).

    ``facts``: the ``PLACEMENT`` dictionary of :func:`placement_entry_text`; ``ends``: its function of the
    vectors' ends; ``solver``: the linkage's unknowns (a closed form's
    :class:`~symlink.numeric.solver.Solver` or a cached one), or Newton's method where it has none.
    :meth:`poses` solves and places every joint; ``guess`` (unknowns by name) picks the assembly where the
    linkage has no closed form; by default one is searched for.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    def __init__(self, facts: Mapping[str, Any], ends: Callable[..., dict], solver: Any) -> None:
        self.facts = dict(facts)
        self._evaluate = ends
        self.solver = solver
        self.name: str = facts["name"]
        self.closed_form: bool = facts["closed_form"]
        self.angles: set[str] = set(facts["angles"])
        self.places: dict[str, list[list[int]]] = facts["places"]
        self.slider_names: list[str] = [name for name, _ in facts["sliders"]]

    @property
    def input_names(self) -> list[str]:
        return list(self.facts["inputs"])

    def check_values(self, values: Mapping[str, float]) -> dict[str, float]:
        """``values`` completed: inputs default to 0, branches to +1; ``ValueError`` naming a missing or unknown one."""
        names = self.facts["parameters"] + self.input_names
        branches = self.facts["branches"]
        unknown = sorted(set(values) - set(names) - set(branches))
        if unknown:
            raise ValueError(f"{self.name} has no value {unknown[0]!r}; it takes {', '.join(names + branches)}")
        missing = [name for name in self.facts["parameters"] if name not in values]
        if missing:
            raise ValueError(f"{self.name} needs a value for {', '.join(missing)}")
        completed = {name: 0.0 for name in self.input_names} | {name: 1 for name in branches}
        completed.update(values)
        for name, value in completed.items():
            if isinstance(value, bool) or not isinstance(value, (int, float, numpy.integer, numpy.floating)) \
                    or not math.isfinite(value):
                raise ValueError(f"{name} must be a finite number, got {value!r}")
        return completed

    def find_guess(self, values: Mapping[str, float]) -> dict[str, float]:
        """An assembly at the inputs of ``values`` for Newton's method: deterministic trial guesses, first that closes."""
        scale = sum(abs(float(values[name])) for name in self.facts["parameters"]) or 1.0
        generator = numpy.random.default_rng(0)
        inputs = {name: numpy.atleast_1d(float(values[name])) for name in self.input_names}
        parameters = {name: float(values[name]) for name in self.facts["parameters"]}
        for _ in range(GUESSES):
            guess = {name: float(generator.uniform(-math.pi, math.pi)) if name in self.angles
                     else float(generator.uniform(-scale, scale)) for name in self.facts["unknowns"]}
            result = self.solver(guess=guess, **inputs, **parameters)
            if bool(numpy.all(result["assembled"])):
                return {name: float(result[name][0]) for name in self.facts["unknowns"]}
        raise ValueError(f"{self.name} cannot be assembled at "
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
                raise ValueError(f"{self.name} has no input {name!r}; its inputs are "
                                 f"{', '.join(self.input_names)}")
        length = max([len(v) for v in swept.values()] + [1])
        inputs = {name: numpy.broadcast_to(swept.get(name, numpy.float64(values[name])), (length,)).astype(float)
                  for name in self.input_names}
        parameters = {name: float(values[name]) for name in self.facts["parameters"]}
        unknowns = self.facts["unknowns"]
        if self.closed_form:
            branches = {name: int(values[name]) for name in self.facts["branches"]}
            result = self.solver(**inputs, **parameters, **branches)
        else:
            base = {name: float(values[name]) for name in self.input_names}
            if guess is None:
                guess = self.find_guess(parameters | base)
            if any(inputs[name][0] != base[name] for name in base):  # follow the assembly to the sweep's start
                steps = max(2, int(max(abs(inputs[n][0] - base[n]) for n in base) / (2 * math.pi) * TRACE_SAMPLES))
                path = {name: numpy.linspace(base[name], inputs[name][0], steps) for name in base}
                there = self.solver(guess=dict(guess), **path, **parameters)
                guess = {name: float(there[name][-1]) for name in unknowns}
            result = self.solver(guess=dict(guess), **inputs, **parameters)
        assembled = numpy.broadcast_to(numpy.asarray(result["assembled"], dtype=bool), (length,)).copy()
        coordinates = {name: numpy.broadcast_to(numpy.asarray(result[name], dtype=float), (length,))
                       for name in unknowns}
        with numpy.errstate(invalid="ignore"):
            ends = self._evaluate(**inputs, **coordinates, **parameters, check=False)  # NaN where not assembled
        vectors: dict[int, numpy.ndarray] = {}
        positions = {}
        for name, terms in self.places.items():
            place = numpy.zeros(length, dtype=complex)
            for sign, k in terms:
                if k not in vectors:
                    vectors[k] = ends[f"x{k}"] + 1j * ends[f"y{k}"]
                place = place + sign * vectors[k]
            positions[name] = numpy.where(assembled, place, complex(numpy.nan, numpy.nan))
        directions = {name: numpy.broadcast_to(ends[f"direction{k}"], (length,))
                      for k, name in enumerate(self.slider_names)}
        return Poses(inputs, positions, directions, assembled)


class Geometry(Placement):
    """A linkage made ready to draw: its :class:`~symlink.mechanism.bodies.Mechanism`, its solver and its vectors.

    Built once for a drawing or an animation (SymPy); a :class:`Placement` whose ``linkage``, ``mechanism``,
    ``sums`` and ``vectors`` say where its facts came from.
    """

    def __init__(self, linkage: Linkage, bodies: Mapping[str, Sequence[str]] | None = None) -> None:
        from ..codegen.loading import load_numpy_module
        from ..mechanism.bodies import PRISMATIC
        from .solver import NumericSolver, Solver
        self.linkage = linkage
        self.mechanism, self.sums, self.vectors, text = _placement_parts(linkage, bodies)
        self.sliders = [j for j in self.mechanism.joints if j.kind == PRISMATIC]
        namespace = load_numpy_module(text)
        solver: Solver | NumericSolver
        if linkage.has_closed_form:
            solver = Solver(linkage, [q.name for q in linkage.unknowns])
        else:
            solver = NumericSolver(linkage)
        super().__init__(namespace[PLACEMENT], namespace[ENDS], solver)


def cached_placement(key: str, solver_key: Callable[[list[str]], str], linkage: Callable[[], Linkage]) -> Placement:
    """A linkage's :class:`Placement` from the disk cache: its module (:func:`placement_entry_text`) under ``key``,
    and its solver under ``solver_key(outputs)``: :func:`~symlink.numeric.cached_solver.entry_text` of the unknowns
    (``outputs`` their names) or, without a closed form, Newton's method
    (:func:`~symlink.numeric.cached_solver.newton_entry_text`, ``outputs`` ``["newton"]``).  Evaluated from the
    cache warm or cold alike, so that both draw the same; the keys are made from what names the linkage, without
    building it (:func:`~symlink.numeric.cache.catalog_key`), and ``linkage()`` builds it (SymPy) only where an
    entry is missing.

    >>> import os, tempfile
    >>> from symlink.mechanism.catalog import fourbar
    >>> from symlink.numeric.cache import catalog_key
    >>> previous = os.environ.get("SYMLINK_CACHE")
    >>> os.environ["SYMLINK_CACHE"] = tempfile.mkdtemp()
    >>> key = lambda outputs: catalog_key("fourbar", outputs, "placement-example/1")
    >>> placement = cached_placement(key(["placement"]), key, fourbar)
    >>> poses = placement.poses(dict(a=20, b=66, c=56, d=80))
    >>> round(complex(poses.positions["C"][0]).real, 3)  # as Geometry places it (the module's example)
    60.167
    >>> _ = os.environ.pop("SYMLINK_CACHE") if previous is None else os.environ.update(SYMLINK_CACHE=previous)
    """
    from .cache import cached_module
    from .cached_solver import CachedNewtonSolver, CachedSolver, entry_text, newton_entry_text
    _, namespace = cached_module(key, lambda: placement_entry_text(linkage()))
    facts = namespace[PLACEMENT]
    solver: CachedSolver | CachedNewtonSolver
    if facts["closed_form"]:
        unknowns = list(facts["unknowns"])
        solver = CachedSolver(facts["name"], unknowns, key=solver_key(unknowns),
                              derive=lambda: entry_text(linkage(), unknowns))
    else:
        solver = CachedNewtonSolver(facts["name"], solver_key(["newton"]), lambda: newton_entry_text(linkage()))
    return Placement(facts, namespace[ENDS], solver)


def input_range(geometry: Placement, values: Mapping[str, float],
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
    if geometry.closed_form:
        return scanned_range(lambda angles: geometry.poses(values, {name: angles}).assembled)
    start = float(values[name])
    step = 2 * math.pi / TRACE_SAMPLES
    turn = step * numpy.arange(TRACE_SAMPLES + 1)
    forward = _followed(geometry, values, name, start + turn, guess)
    if forward == len(turn):
        return [(-math.pi, math.pi)]
    backward = _followed(geometry, values, name, start - turn, guess)
    return [(start - turn[backward - 1], start + turn[forward - 1])] if forward else []


def _followed(geometry: Placement, values: Mapping[str, float], name: str, sweep: numpy.ndarray,
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


def traced_paths(geometry: Placement, values: Mapping[str, float], trace: Sequence[str],
                 guess: Mapping[str, float] | None = None, samples: int = TRACE_SAMPLES) -> dict[str, numpy.ndarray]:
    """The paths of the joints or points ``trace`` over the reachable sweep of the first input."""
    known = [name for name in geometry.places if not name.endswith(" guide")]
    for name in trace:
        if name not in known:
            raise ValueError(f"{geometry.name} has no point or joint {name!r} to trace; "
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
