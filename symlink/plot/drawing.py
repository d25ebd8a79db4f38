"""A drawing of any linkage: its bodies and joints at a pose, read off :func:`symlink.bodies.mechanism`.

The bodies and joints come from the linkage's vectors
(:mod:`symlink.bodies`); the pose from its closed form
(:class:`~symlink.solver.Solver`) or, where it has none, from Newton's
method (:class:`~symlink.solver.NumericSolver`).  Every joint is placed by
its sum of vectors from the origin, each vector evaluated at the solved
coordinates, so the drawing needs no knowledge of the linkage beyond its
loops and points:

* a binary link (two joints) is a bar, a ternary or larger link a filled
  polygon through its joints and named points;
* a slider is a block on its guide (a line on the body that carries it);
* ground pivots are marked with a hatched support, joints and points named
  by their letters;
* the paths of chosen points (``trace``) are drawn over the reachable sweep
  of the first input (:func:`input_range`);
* equal aspect, and the length unit in the axis labels.

Functions take ``ax=`` (a Matplotlib Axes), so that drawings compose in a
notebook, and return the :class:`LinkageDrawing` (its ``figure``, ``axes``
and ``artists``).  Values are given by symbol name: lengths and fixed
angles (radians), the inputs (radians, or lengths for a driven slider) and
the branch signs (+1 by default).

>>> from symlink.catalog import jansen, EXAMPLE_VALUES
>>> drawing = draw_linkage(jansen(), EXAMPLE_VALUES["jansen"], trace=("H",))
>>> len(drawing.polygons), drawing.axes.get_xlabel()
(2, 'x (length unit)')
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Mapping, Sequence, cast

import numpy
import sympy as sp

from ..bodies import GROUND, PRISMATIC, REVOLUTE, Mechanism, mechanism
from ..closure import is_angle
from ..codegen.numpy import load_numpy_module, numpy_module
from ..linkage import Linkage, Program
from ..reachability import scanned_range
from ..solver import NumericSolver, Solver
from ..vectors import Vector, VectorSum
from .figures import _ground_marker, extent

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import Polygon
    from numpy.typing import ArrayLike

__all__ = ["Geometry", "Poses", "LinkageDrawing", "draw_linkage", "input_range", "sweep_inputs", "TRACE_SAMPLES"]

#: Samples of the sweep along which traced paths are drawn.
TRACE_SAMPLES = 721
#: Guesses tried, at the first input value, to find an assembly for Newton's method.
GUESSES = 400
BODY_COLORS = ("tab:red", "tab:blue", "tab:green", "tab:orange", "tab:purple", "tab:brown", "tab:pink",
               "tab:olive", "tab:cyan")


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
    """A linkage made ready to draw: its :class:`~symlink.bodies.Mechanism`, its solver and its vectors.

    Built once for a drawing or an animation; :meth:`poses` solves and places
    every joint.  ``guess`` (unknowns by name) picks the assembly where the
    linkage has no closed form; by default one is searched for.
    """

    def __init__(self, linkage: Linkage, bodies: Mapping[str, Sequence[str]] | None = None) -> None:
        self.linkage = linkage
        self.mechanism: Mechanism = mechanism(linkage, bodies)
        sums: dict[str, VectorSum] = {}
        for joint in self.mechanism.joints:
            if joint.position is not None:
                sums[joint.name] = joint.position
            if joint.kind == PRISMATIC and joint.guide_start is not None:
                sums[f"{joint.name} guide"] = joint.guide_start
        for name, point in linkage.points.items():
            sums[name] = VectorSum(()) if point is None else point.as_sum()
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

    With a closed form: :func:`~symlink.reachability.scanned_range` of the
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


def _corner_order(points: list[complex]) -> list[complex]:
    """The corners of a link as a simple polygon: ordered by angle about their centre."""
    centre = sum(points) / len(points)
    return sorted(points, key=lambda p: math.atan2((p - centre).imag, (p - centre).real))


class LinkageDrawing:
    """A linkage on an axes, movable from one pose of ``poses`` to another (:meth:`update`).

    ``bars`` and ``polygons`` are the links (binary, and ternary or larger),
    ``blocks`` and ``guides`` the sliders, ``ground`` the hatched pivots,
    ``pins`` the joints, ``labels`` the letters, ``traces`` the traced paths.
    """

    def __init__(self, axes: "Axes", geometry: Geometry, poses: Poses,
                 traces: Mapping[str, numpy.ndarray] | None = None, unit: str | None = None,
                 letters: bool = True) -> None:
        from matplotlib.patches import Polygon
        self.axes, self.geometry, self.poses = axes, geometry, poses
        self.figure: "Figure" = axes.figure.figure  # the top-level figure, also for a subfigure's axes
        found = geometry.mechanism
        self.scale = self._scale(poses, traces)
        self.traces = {name: axes.plot(path.real, path.imag, color="tab:purple", linewidth=1.2, alpha=0.8,
                                       zorder=1, label=f"path of {name}")[0]
                       for name, path in (traces or {}).items()}
        self.bars, self.polygons, self._bodies = [], [], []
        colors = iter(BODY_COLORS * (1 + len(found.bodies) // len(BODY_COLORS)))
        for body in found.bodies:
            if body.is_ground:
                continue
            corners = self._corners(body)
            color = next(colors)
            artist: "Polygon | Line2D"
            if len(corners) >= 3:
                artist = Polygon(numpy.zeros((len(corners), 2)), closed=True, facecolor=color, alpha=0.45,
                                 edgecolor=color, linewidth=2.5, zorder=3, label=body.name)
                axes.add_patch(artist)
                self.polygons.append(artist)
            elif len(corners) == 2:
                artist = axes.plot([], [], color=color, linewidth=6, solid_capstyle="round", zorder=3,
                                   label=body.name)[0]
                self.bars.append(artist)
            else:
                continue
            self._bodies.append((corners, artist))
        self.guides, self.blocks = [], []
        for joint in geometry.sliders:
            self.guides.append(axes.plot([], [], color="0.3", linewidth=1.5, zorder=2)[0])
            block = Polygon(numpy.zeros((4, 2)), closed=True, facecolor="0.85", edgecolor="black", linewidth=1.2,
                            zorder=4)
            axes.add_patch(block)
            self.blocks.append(block)
        pivots = [j.name for j in found.joints if j.kind == REVOLUTE and j.grounded and j.name in poses.positions]
        self._pivots = pivots
        self.frame = axes.plot([], [], color="0.5", linestyle="--", linewidth=1, zorder=1)[0]
        self.ground = axes.plot([], [], linestyle="none", marker=_ground_marker(), markersize=22,
                                markeredgecolor="0.25", markerfacecolor="none", markeredgewidth=1.2, zorder=2)[0]
        self._pins = [j.name for j in found.joints if j.kind == REVOLUTE and j.name in poses.positions]
        self.pins = axes.plot([], [], linestyle="none", marker="o", markersize=7, markerfacecolor="white",
                              markeredgecolor="black", zorder=5)[0]
        named = list(dict.fromkeys(self._pins + [p for p in geometry.linkage.points if p in poses.positions]))
        self.points = axes.plot([], [], linestyle="none", marker="o", markersize=4, color="black", zorder=6)[0]
        self._named = named
        self.labels = {name: axes.annotate(name, (0, 0), textcoords="offset points", xytext=(5, 5),
                                           fontsize="small", fontweight="bold", zorder=7)
                       for name in (named if letters else [])}
        (x0, x1), (y0, y1) = self.limits(traces)
        axes.set_xlim(x0, x1)
        axes.set_ylim(y0, y1)
        axes.set_aspect("equal", adjustable="datalim" if axes.get_adjustable() == "datalim" else "box")
        label = unit if unit else "length unit"
        axes.set_xlabel(f"x ({label})")
        axes.set_ylabel(f"y ({label})")
        axes.grid(True, alpha=0.3)

    def _corners(self, body) -> list[str]:
        """What a body's outline passes through: its pins, slider blocks it carries, and its named points."""
        corners = []
        for name in body.joints:
            joint = self.geometry.mechanism.joint(name)
            if joint.kind == REVOLUTE or joint.bodies[-1] == body.name:  # a pin, or the block this body is
                corners.append(name)
        corners += [p for p in body.points if p not in corners]
        seen, unique = [], []
        for name in corners:  # a block pinned where its slider joint is (B on the inverted slider-crank)
            sums = self.geometry.sums.get(name)
            key = None if sums is None else tuple(sorted((s, str(v)) for s, v in sums.terms))
            if sums is not None and key not in seen:
                seen.append(key)
                unique.append(name)
        return unique

    @staticmethod
    def _scale(poses: Poses, traces) -> float:
        values = numpy.concatenate([p.ravel() for p in poses.positions.values()]
                                   + [t.ravel() for t in (traces or {}).values()])
        values = values[numpy.isfinite(values)]
        if values.size == 0:
            return 1.0
        return float(max(numpy.ptp(values.real), numpy.ptp(values.imag), 1e-300))

    def _guide_span(self, k: int, index: int) -> tuple[complex, complex]:
        joint = self.geometry.sliders[index]
        start = self.poses.positions.get(f"{joint.name} guide", numpy.zeros(len(self.poses)))
        along = numpy.exp(1j * self.poses.directions[joint.name])
        travel = ((self.poses.positions[joint.name] - start) * numpy.conj(along)).real
        block = 0.08 * self.scale
        if GROUND in joint.bodies[:1]:  # a fixed guide: long enough for the whole travel
            finite = travel[numpy.isfinite(travel)]
            low, high = (min(0.0, finite.min()), max(0.0, finite.max())) if finite.size else (0.0, 0.0)
        else:
            low, high = min(0.0, travel[k]), max(0.0, travel[k])
        return start[k] + along[k] * (low - block), start[k] + along[k] * (high + block)

    def limits(self, traces=None) -> tuple[tuple[float, float], tuple[float, float]]:
        """Axis limits holding every joint and point of every pose, the traced paths and the guides."""
        points = [p.ravel() for p in self.poses.positions.values()] + [t.ravel() for t in (traces or {}).values()]
        for index in range(len(self.geometry.sliders)):
            for k in range(len(self.poses)):
                points.append(numpy.array(self._guide_span(k, index)))
        values = numpy.concatenate(points)
        return extent(values.real, values.imag, margin=0.1)

    def update(self, k: int) -> list:
        """Move to pose ``k``; a pose that cannot be assembled shows the ground only.  Returns the artists."""
        at = {name: complex(position[k]) for name, position in self.poses.positions.items()}
        shown = bool(self.poses.assembled[k])
        for corners, artist in self._bodies:
            xy = [at[name] for name in corners]
            if len(corners) >= 3:
                plate = cast("Polygon", artist)
                plate.set_visible(shown)
                if shown:
                    ordered = _corner_order(xy)
                    plate.set_xy([(p.real, p.imag) for p in ordered])
            else:
                cast("Line2D", artist).set_data(*(([p.real for p in xy], [p.imag for p in xy]) if shown else ([], [])))
        for index, joint in enumerate(self.geometry.sliders):
            start, end = self._guide_span(k, index)
            self.guides[index].set_data(*(([start.real, end.real], [start.imag, end.imag]) if shown else ([], [])))
            centre, along = at[joint.name], numpy.exp(1j * self.poses.directions[joint.name][k])
            half_length, half_width = 0.06 * self.scale, 0.035 * self.scale
            outline = [centre + along * (sx * half_length + 1j * sy * half_width)
                       for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
            self.blocks[index].set_visible(shown and numpy.isfinite(centre))
            if shown and numpy.isfinite(centre):
                self.blocks[index].set_xy([(p.real, p.imag) for p in outline])
        pivots = [at[name] for name in self._pivots]
        self.ground.set_data([p.real for p in pivots], [p.imag for p in pivots])
        self.frame.set_data([p.real for p in pivots], [p.imag for p in pivots])
        pins = [at[name] for name in self._pins if shown or name in self._pivots]
        self.pins.set_data([p.real for p in pins], [p.imag for p in pins])
        named = [at[name] for name in self._named if shown]
        self.points.set_data([p.real for p in named], [p.imag for p in named])
        for name, label in self.labels.items():
            visible = (shown or name in self._pivots) and numpy.isfinite(at[name])
            label.set_visible(bool(visible))
            if visible:
                label.xy = (at[name].real, at[name].imag)
        return self.artists

    @property
    def artists(self) -> list:
        """Everything :meth:`update` moves."""
        return ([artist for _, artist in self._bodies] + self.guides + self.blocks
                + [self.frame, self.ground, self.pins, self.points] + list(self.labels.values()))


def _axes(ax: "Axes | None", size: tuple[float, float] = (6.4, 5.2)) -> "Axes":
    if ax is not None:
        return ax
    from .inline import NotebookFigure
    return NotebookFigure(figsize=size, layout="constrained").add_subplot()


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


def _input_text(linkage: Linkage, symbol: sp.Symbol, value: float) -> str:
    if is_angle(linkage, symbol):
        return f"{symbol.name} = {math.degrees(float(value)):.4g}°"
    return f"{symbol.name} = {float(value):.4g}"


def draw_linkage(linkage: Linkage, values: Mapping[str, float], ax: "Axes | None" = None, *,
                 trace: Sequence[str] = (), unit: str | None = None, guess: Mapping[str, float] | None = None,
                 title: str | None = None, bodies: Mapping[str, Sequence[str]] | None = None,
                 geometry: Geometry | None = None) -> LinkageDrawing:
    """Draw ``linkage`` at ``values`` on ``ax`` (a new figure's axes by default), with the paths of ``trace``.

    ``values`` by symbol name (inputs default to 0, branches to +1);
    ``guess`` picks the assembly of a linkage without a closed form;
    ``bodies`` says which vectors share a body where the vectors alone are
    ambiguous (:func:`symlink.bodies.mechanism`).  ``ValueError`` where the
    linkage cannot be assembled at these values.
    """
    geometry = geometry or Geometry(linkage, bodies)
    completed = geometry.check_values(values)
    poses = geometry.poses(completed, guess=guess)
    if not poses.assembled[0]:
        inputs = ", ".join(f"{name} = {float(completed[name]):g}" for name in geometry.input_names)
        raise ValueError(f"{linkage.name} cannot be assembled at {inputs}")
    if guess is None and not isinstance(geometry.solver, Solver):
        guess = geometry.find_guess(completed)
    paths = traced_paths(geometry, completed, trace, guess)
    axes = _axes(ax)
    drawing = LinkageDrawing(axes, geometry, poses, paths, unit)
    drawing.update(0)
    inputs = ", ".join(_input_text(linkage, q, completed[q.name]) for q in linkage.inputs)
    axes.set_title(title if title is not None else f"{linkage.name} at {inputs}", fontsize="medium")
    if paths:
        axes.legend(handles=list(drawing.traces.values()), loc="best", fontsize="small")
    return drawing
