"""Reachable input ranges: where a linkage can be assembled, its toggles at the ends.

The one home of this concept.  Closed forms where the geometry gives them
(the four-bar's crank range from the triangle over its diagonal, the
slider-crank's from the rod reaching its guide, the five-bar's as a
four-bar), and :func:`scanned_range` for any other linkage: a scan of a
full turn with each edge bisected to rounding.  Those are plain arithmetic,
kept in :mod:`symlink.numeric.crank_ranges` (SymPy-free, for warm commands) and
named here too.

Ranges are lists of closed intervals in radians; ``[(-pi, pi)]`` is a full
turn and an empty list means the linkage closes at no input angle.

>>> [tuple(round(math.degrees(x), 4) for x in span) for span in crank_range(20, 66, 56, 80)]
[(-180.0, 180.0)]
>>> [tuple(round(math.degrees(x), 2) for x in span) for span in crank_range(0.3, 0.1, 0.25, 0.30)]
[(-71.37, -28.96), (28.96, 71.37)]
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import TYPE_CHECKING, Any, Callable, Mapping

import numpy

from ..common.angles import wrap_angle
from .cache import cache_key, cached_module, cached_text
from .design_scan import (BISECTIONS, COARSE_STRIDE, _bisect, _edges, _spans_from_marks,  # noqa: F401 - public names
                          fastest_margins, margin_spans)
from .crank_ranges import (SCAN_POINTS, TURN_SAMPLES, closing_crank_range, crank_range, describe_spans, fivebar_range,  # noqa: F401
                           inverted_slider_crank_range, reachable_turn, scanned_range, slider_crank_range, turn_angles)
from ..codegen.arguments import check_lengths
from ..common.display import record_html
from ..common.rounding import TOLERANCE
from .cached_linkage import CachedLinkage

if TYPE_CHECKING:  # the symbolic layer and the solvers are imported where used: a cached linkage needs neither
    from ..symbolic.linkage import Linkage, Program
    from .solver import Solver

__all__ = ["crank_range", "assembled_crank_range", "slider_crank_range", "inverted_slider_crank_range",
           "fivebar_range", "scanned_range", "describe_spans", "reachable_turn", "turn_angles", "SCAN_POINTS", "TURN_SAMPLES",
           "BISECTIONS", "COARSE_STRIDE", "Toggle", "InputRange", "InputMotion", "reachable_range", "design_spans"]


def assembled_crank_range(a: float, b: float, c: float, d: float) -> list[tuple[float, float]]:
    """:func:`crank_range` of checked lengths; ``ValueError`` where the four-bar closes at no crank angle
    (:func:`~symlink.numeric.crank_ranges.closing_crank_range`)."""
    check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    return closing_crank_range(a, b, c, d)


# --- any linkage with one input -----------------------------------------------------------

#: A root's argument, relative to its scale, at most this small at a local minimum inside the
#: range: the loop passes through a toggle there (its branches meet) without leaving the range.
TOUCH = 100 * TOLERANCE


@dataclass(frozen=True)
class Toggle:
    """An input value where a loop's two assemblies meet: its root vanishes, its Jacobian is singular.

    ``loop`` names the loop (None where a linkage without a closed form is found
    singular by Newton's method); ``ends_range``: the input cannot go on (an end
    of a span), else the linkage passes through it (a change point).
    ``degenerate``: not a toggle of two assemblies but a direction the pose does not
    fix (two points that coincide, parallel guides).

    Parameters
    ----------
    at : float
        The input value.
    loop : str or None
        The loop whose assemblies meet there (None when found by Newton's method).
    ends_range : bool, optional
        True (default) at an end of a span; False at a change point inside one.
    degenerate : bool, optional
        True for a direction the pose does not fix rather than a toggle of two assemblies.

    Examples
    --------
    >>> import math, symlink
    >>> found = symlink.reachable_range(symlink.fourbar(), dict(a=60, b=30, c=50, d=40))
    >>> toggle = found.toggles[0]
    >>> round(abs(math.degrees(toggle.at)), 4), toggle.loop, toggle.ends_range
    (104.4775, 'ABCD', True)
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    at: float
    loop: str | None
    ends_range: bool = True
    degenerate: bool = False


@dataclass(frozen=True)
class InputRange:
    """Where a one-input linkage can be assembled: closed intervals of its input, and its toggles.

    ``exact``: every loop is in closed form and each end was bisected to rounding
    on the sign of its root's argument; otherwise a scan of continuation by
    Newton's method (from ``guess``), ends bisected the same way.  Spans of an
    angle input lie in ``[-pi, pi)`` at their start and may end past ``pi``;
    ``[(-pi, pi)]`` is a full turn.

    Parameters
    ----------
    input : str
        The input's name.
    spans : tuple of (float, float)
        The closed intervals where the linkage assembles.
    toggles : tuple of Toggle
        The toggles at their ends and inside them.
    exact : bool
        True when each end was bisected on a closed form's root.
    periodic : bool
        True for an angle input.

    Examples
    --------
    >>> import math, symlink
    >>> found = symlink.reachable_range(symlink.fourbar(), dict(a=60, b=30, c=50, d=40))
    >>> found.input, found.exact, [tuple(round(math.degrees(x), 4) for x in span) for span in found.spans]
    ('theta', True, [(-104.4775, 104.4775)])
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    input: str
    spans: tuple[tuple[float, float], ...]
    toggles: tuple[Toggle, ...]
    exact: bool
    periodic: bool

    @property
    def full_turn(self) -> bool:
        return self.periodic and self.spans == ((-math.pi, math.pi),)


@lru_cache(maxsize=64)
def _motion_solver(linkage: Linkage, outputs: tuple[str, ...]) -> Solver:
    """The solver of an :class:`InputMotion`, made once a linkage (a sweep makes a motion a design: a solver's
    cache key and backend are worth making once, not each time)."""
    from .solver import Solver
    return Solver(linkage, list(outputs))


class InputMotion:
    """A one-input linkage at given values, evaluated at any input values: coordinates and rates.

    The input's rate is 1, so the rates are derivatives with respect to the input.
    Closed forms go straight to a generated :class:`~symlink.numeric.solver.Solver`; a
    linkage without one is continued by Newton's method from ``guess`` (the
    unknowns near the wanted assembly at the input value ``start``), each
    requested input value solved from the nearest pose of a scan that
    :func:`reachable_range` fills in (``numeric=True`` takes that way for any
    linkage, to cross-check a closed form).

    >>> from symlink.mechanism.catalog import fourbar
    >>> motion = InputMotion(fourbar(), dict(a=20, b=66, c=56, d=80))
    >>> round(float(numpy.degrees(motion.at([0.0])["phi"][0])), 2)
    110.74
    """

    def __init__(self, linkage: Linkage | CachedLinkage, values: Mapping[str, float], *, input: str | None = None,
                 guess: Mapping[str, float] | None = None, start: float = 0.0, numeric: bool = False) -> None:
        driven = [q.name for q in linkage.inputs]
        self.input = driven[0] if input is None else input
        if self.input not in driven:
            raise ValueError(f"{linkage.name} has the inputs {', '.join(driven)}; not {self.input!r}")
        held = [name for name in driven if name != self.input]
        needed = [s.name for s in linkage.parameters] + held
        missing = [name for name in needed if name not in values]
        if missing:
            raise ValueError(f"{linkage.name}: give a value for {', '.join(missing)}"
                             + (f" (the inputs other than {self.input} are held still)" if held else ""))
        allowed = set(needed) | {s.name for s in linkage.branches}
        unexpected = sorted(set(values) - allowed)
        if unexpected:
            raise ValueError(f"{linkage.name} takes values for {', '.join(sorted(allowed))}; "
                             f"not {', '.join(unexpected)}")
        self.linkage = linkage
        self.values = {name: float(value) for name, value in values.items()}
        check_lengths(**{s.name: self.values[s.name] for s in linkage.parameters if s.is_positive})
        for name, value in self.values.items():
            if not math.isfinite(value):
                raise ValueError(f"{name} must be finite, got {value}")
            if name in {s.name for s in linkage.branches} and value not in (1.0, -1.0):
                raise ValueError(f"{name} must be +1 or -1, got {value:g}")
        self.exact = linkage.has_closed_form and not numeric
        self.names = [q.name for q in linkage.unknowns]
        if isinstance(linkage, CachedLinkage):  # names and solver from the disk cache: no SymPy
            if not self.exact:
                raise ValueError(f"{linkage.name}: a cached linkage is analysed in closed form only")
            self.periodic = linkage.is_angle(self.input)
            rate_of = linkage.rates
        else:
            from ..symbolic.closure import is_angle
            from ..symbolic.vectors import rate
            self.periodic = is_angle(linkage, next(q for q in linkage.inputs if q.name == self.input))
            rate_of = {q.name: rate(q).name for q in linkage.unknowns + linkage.inputs}
        self.rates = [rate_of[q.name] for q in linkage.unknowns]
        self.speeds = {rate_of[q.name]: (1.0 if q.name == self.input else 0.0) for q in linkage.inputs}
        if self.exact:
            if guess is not None:
                raise ValueError(f"{linkage.name} is solved in closed form: give branch signs, not a guess")
            self._solver = (linkage.solver(self.names + self.rates) if isinstance(linkage, CachedLinkage)
                            else _motion_solver(linkage, tuple(self.names + self.rates)))
        else:
            from .solver import NumericSolver
            if guess is None:
                raise ValueError(f"{linkage.name} has no closed form: give a guess of "
                                 f"{', '.join(self.names)} at {self.input} = {start:g}")
            assert not isinstance(linkage, CachedLinkage)  # refused above: closed forms only
            self._numeric = NumericSolver(linkage)
            self.guess = dict(guess)
            self.start = float(start)
            self._scan: tuple[numpy.ndarray, numpy.ndarray] | None = None  # inputs, unknowns of the scan

    def _arguments(self) -> dict[str, float]:
        arguments = {name: value for name, value in self.values.items()}
        if self.exact:
            arguments.update(self.speeds)
        return arguments

    def at(self, inputs) -> dict[str, numpy.ndarray]:
        """Unknowns and their rates (by name) and ``assembled`` at ``inputs``; NaN where not assembled."""
        inputs = numpy.atleast_1d(numpy.asarray(inputs, dtype=float))
        if self.exact:
            found = self._solver(**{self.input: inputs}, **self._arguments())
            return {name: numpy.asarray(found[name]) for name in self.names + self.rates + ["assembled"]}
        if self._scan is None:
            raise ValueError("scan the linkage first (reachable_range) to solve it at any input")
        grid, poses = self._scan
        result = {name: numpy.full(inputs.shape, numpy.nan) for name in self.names + self.rates}
        result["assembled"] = numpy.zeros(inputs.shape, dtype=bool)
        if inputs.size > 2:  # a sweep: continue along it in one go from the scan's pose nearest its start
            nearest = int(numpy.argmin(numpy.abs(grid - inputs[0])))
            solved = self._sweep(numpy.concatenate([grid[nearest:nearest + 1], inputs]), poses[nearest])
            if solved is not None:
                for name in self.names + self.rates:
                    result[name] = numpy.asarray(solved[name])[1:]
                result["assembled"][:] = True
                return result
        for k, value in enumerate(inputs):
            nearest = int(numpy.argmin(numpy.abs(grid - value)))
            solved = self._sweep(numpy.array([grid[nearest], value]), poses[nearest])
            if solved is not None:
                for name in self.names + self.rates:
                    result[name][k] = solved[name][-1]
                result["assembled"][k] = True
        return result

    def _sweep(self, inputs: numpy.ndarray, guess) -> dict[str, numpy.ndarray] | None:
        """Newton's continuation along ``inputs`` from ``guess``; None where it fails on the way."""
        held = {q.name: self.values[q.name] for q in self.linkage.inputs if q.name != self.input}
        if held:
            inputs_of = {self.input: inputs, **{k: numpy.full(inputs.shape, v) for k, v in held.items()}}
        else:
            inputs_of = {self.input: inputs}
        parameters = {s.name: self.values[s.name] for s in self.linkage.parameters}
        try:
            with numpy.errstate(all="ignore"):
                return self._numeric(guess=guess, **inputs_of, **parameters, **self.speeds)
        except ValueError:
            return None


@lru_cache(maxsize=64)
def _margin_function(linkage: Linkage) -> tuple[Callable[..., dict], list[tuple[str, str]]]:
    """Generated code of every clamped root's argument over its scale (plus rounding), and their loops.

    A root's margin (``margin_k``) is ``x / scale + TOLERANCE``: the loop closes
    where it is not negative.  A guard's (``guard_k``: a length that must not
    vanish) is its argument less the square of TOLERANCE.  Later loops'
    margins are NaN where an earlier loop does not close.
    """
    names = _margin_names(linkage)
    key = cache_key(linkage, names, "root-margins")
    if key not in _MARGINS:
        _MARGINS[key] = cached_module(key, lambda: margins_text(linkage))[1]["margins"]
    return _MARGINS[key], [(name, loop) for name, (loop, _, _) in zip(names, _roots(linkage))]


def margin_roots(linkage: Linkage) -> list[tuple[str, str]]:
    """Each clamped root's margin name (``margin_k``, or ``guard_k`` for a length that must not vanish) and loop,
    in plan order: plain data, which a cached analysis keeps
    (:class:`~symlink.numeric.cached_linkage.CachedLinkage`)."""
    return [(name, loop) for name, (loop, _, _) in zip(_margin_names(linkage), _roots(linkage))]


def margins_text(linkage: Linkage) -> str:
    """The NumPy module of :func:`_margin_function` (function ``margins``): derived once, with SymPy."""
    from ..codegen.numpy import numpy_module
    return numpy_module([("margins", _margins_program(linkage, _margin_names(linkage)), _margins_doc(linkage))])


def _margin_names(linkage: Linkage) -> list[str]:
    """The names of the margins of :func:`_roots`: ``margin_k``, or ``guard_k`` for a length that must not vanish."""
    return [f"margin_{k}" if not expr.args[1].is_negative else f"guard_{k}"
            for k, (_, _, expr) in enumerate(_roots(linkage))]


def _margins_program(linkage: Linkage, names: list[str]) -> Program:
    """The straight-line program of the margins ``names`` (:func:`_margin_function`), in loop units."""
    from ..codegen.program import in_loop_units
    base = linkage.program([q.name for q in linkage.unknowns])
    # A guard (negative scale) is NaN below TOLERANCE^2: its margin is the argument past that.
    margins = {name: (expr.args[0] / expr.args[1] + TOLERANCE if name.startswith("margin")
                      else expr.args[0] + TOLERANCE * expr.args[1]) for name, (_, _, expr) in zip(names, _roots(linkage))}
    return replace(in_loop_units(base), outputs=margins)


def _margins_doc(linkage: Linkage) -> str:
    return f"{linkage.name}: the margins of its clamped roots."


def _margins_c_facts(linkage: Linkage, names: list[str]) -> str:
    """The C of the margins ``names`` and its calling facts (:func:`~symlink.numeric.compiled_library.program_facts`)."""
    from . import compiled_library as compiled
    program = _margins_program(linkage, names)
    return compiled.program_facts(program, "solve", _margins_doc(linkage),
                                  [s.name for s in program.arguments if s.is_positive])


#: The name of the dictionary that :func:`margins_entry_text` adds to the margins' module.
MARGINS_DESCRIPTION = "MARGINS_DESCRIPTION"


def margins_entry_text(linkage: Linkage) -> str:
    """A cache entry of the margins of ``linkage``'s clamped roots (:func:`design_spans`), for a process without
    the linkage (a warm sweep or analysis: :func:`symlink.io.table_source.margins_entry` keeps it): their NumPy
    module, as :func:`_margin_function` generates it, and a dictionary of their roots, lengths and branch signs,
    the rounding they allow and their C
    (:func:`symlink.numeric.design_scan.fastest_margins` and :func:`~symlink.numeric.design_scan.margin_spans`
    take them).

    >>> text = margins_entry_text(__import__("symlink").slider_crank())
    >>> namespace = {}
    >>> exec(compile(text, "<entry>", "exec"), namespace)
    >>> namespace[MARGINS_DESCRIPTION]["roots"], namespace[MARGINS_DESCRIPTION]["lengths"]
    ([['margin_0', 'ABC']], ['a', 'b'])
    """
    names = _margin_names(linkage)
    try:
        c_facts: str | None = _margins_c_facts(linkage, names)
    except (OSError, ValueError, RuntimeError, NotImplementedError, TypeError):
        c_facts = None  # a program the C printer cannot print: NumPy
    described = {"roots": [[name, loop] for name, (loop, _, _) in zip(names, _roots(linkage))],
                 "lengths": [s.name for s in linkage.parameters if s.is_positive],
                 "branches": [s.name for s in linkage.branches], "tolerance": TOLERANCE, "c_margins": c_facts}
    module = margins_text(linkage)
    return f"{module.rstrip()}\n\n\n{MARGINS_DESCRIPTION} = {described!r}\n"


_MARGINS: dict[str, Callable[..., dict]] = {}
_COMPILED_MARGINS: dict[str, Any] = {}


def _fast_margins(linkage: Linkage) -> Callable[..., dict]:
    """The margins as :func:`_margin_function` generates them, in the compiled C loop where a compiler works
    (:func:`~symlink.numeric.design_scan.fastest_margins`: built once into the cache and waited for), else the
    NumPy module: for scans of many designs at once (:func:`design_spans`).

    Called with keywords (``check=False`` skips the argument check, as the NumPy module's does).
    """
    numpy_margins, roots = _margin_function(linkage)
    names = [name for name, _ in roots]
    key = _compiled_margins_key(linkage, tuple(names))
    found = _COMPILED_MARGINS.get(key)
    if found is None:
        found = fastest_margins(numpy_margins, lambda: cached_text(key, lambda: _margins_c_facts(linkage, names)),
                                [s.name for s in linkage.parameters if s.is_positive],
                                [s.name for s in linkage.branches])
        if not getattr(found, "compiled", False):
            return found
        _COMPILED_MARGINS[key] = found
    return found


@lru_cache(maxsize=64)
def _compiled_margins_key(linkage: Linkage, names: tuple[str, ...]) -> str:
    """The cache key of the compiled margins, computed once a linkage (a sweep asks for it every chunk)."""
    return cache_key(linkage, names, "root-margins-c")


def _roots(linkage: Linkage) -> list:
    """Every clamped root of the plan as generated code computes it (loop units, with its scale):
    (loop name, symbol, expression), in plan order."""
    from ..symbolic.position import ClampedSqrt
    return [(step.loop.name, symbol, expr) for step in linkage.plan
            for symbol, expr in step.in_loop_units.intermediates.items() if isinstance(expr, ClampedSqrt)]


def reachable_range(linkage: Linkage | CachedLinkage, values: Mapping[str, float], *, input: str | None = None,
                    guess: Mapping[str, float] | None = None, start: float = 0.0,
                    interval: tuple[float, float] | None = None, points: int = SCAN_POINTS,
                    motion: InputMotion | None = None, numeric: bool = False) -> InputRange:
    """Where a linkage with one moving input can be assembled, and its toggles.

    ``values`` by name: every parameter, any branch sign (+1 default) and the
    other inputs (held still).  In closed form, where every loop's clamped root
    has a non-negative argument: a scan of ``points`` input values, each edge
    bisected to rounding, the loop whose root goes negative named at each end,
    and a root that only touches zero inside the range named as a toggle there
    too.  Without a closed form, Newton's continuation from ``guess`` (the
    unknowns at input ``start``) forward and back, each failure bisected: the
    span of the assembly the guess is on.  An angle input is scanned over a
    turn; a length input over ``interval`` (required).  ``numeric=True``
    continues by Newton's method even where a closed form exists; ``motion``
    reuses an :class:`InputMotion` of the same linkage and values.

    Parameters
    ----------
    linkage : Linkage
        A linkage with one moving input.
    values : mapping of str to float
        Every parameter, any branch sign (+1 default) and the other inputs.
    input : str, optional
        The moving input (default: the linkage's only input).
    guess : mapping of str to float, optional
        The unknowns at ``start`` on the wanted assembly (for Newton's continuation).
    start : float, optional
        The input value the continuation starts from (default 0).
    interval : (float, float), optional
        The span a length input is scanned over (required for one).
    points : int, optional
        The scan's number of input values (default 3600).
    motion : InputMotion, optional
        A motion of the same linkage and values to reuse.
    numeric : bool, optional
        Continue by Newton's method even where a closed form exists.

    Returns
    -------
    InputRange
        The spans of the input where it assembles (radians for an angle), and the toggles at their ends.

    Examples
    --------
    >>> import math, symlink
    >>> found = symlink.reachable_range(symlink.slider_crank(), dict(a=2.0, b=1.0, offset=0.0))
    >>> [tuple(round(math.degrees(x), 9) for x in span) for span in found.spans]  # sin(theta) <= b / a
    [(-30.0, 30.0), (150.0, 210.0)]
    >>> [t.loop for t in found.toggles]
    ['ABC', 'ABC', 'ABC', 'ABC']
    """
    if motion is None:
        motion = InputMotion(linkage, values, input=input, guess=guess, start=start, numeric=numeric)
    if motion.periodic:
        low, high = (-math.pi, math.pi) if interval is None else interval
    elif interval is None:
        raise ValueError(f"{motion.input} is a length: give the interval to search it over")
    else:
        low, high = interval
    if not (math.isfinite(low) and math.isfinite(high) and low < high):
        raise ValueError(f"the interval must be two finite numbers, low < high; got {interval}")
    if points < 4:
        raise ValueError(f"scan at least 4 points, got {points}")
    if motion.exact:
        return _closed_form_range(motion, low, high, points)
    return _continued_range(motion, low, high, points)


def design_spans(linkage: Linkage, values: Mapping[str, Any], count: int, *, input: str | None = None,
                 points: int = SCAN_POINTS, block: int = 1 << 18,
                 stride: int = COARSE_STRIDE) -> list[list[tuple[float, float]]]:
    """The reachable spans over a turn of the input of ``count`` designs at once, each as :func:`reachable_range`
    finds them in closed form (the same scan and bisections, to rounding), without its toggles.

    ``values``: every parameter, branch sign and held input by name, a number or an array of ``count``
    (one a design).  The scan's mask of ``points`` input values is made at a cost that scales with what
    it needs (:func:`~symlink.numeric.design_scan.margin_spans`): every ``stride``-th point of every design
    first, then the points in between only in the cells where a margin changes sign or comes near enough to zero to change it
    there.  Every step (the scans, each bisection) is one call of the generated margins for all designs
    and edges together, not one a design.

    >>> from symlink.mechanism.catalog import slider_crank
    >>> found = design_spans(slider_crank(), dict(a=numpy.array([2.0, 0.5]), b=1.0, offset=0.0), 2)
    >>> [[tuple(round(math.degrees(x), 9) for x in span) for span in spans] for spans in found]
    [[(-30.0, 30.0), (150.0, 210.0)], [(-180.0, 180.0)]]
    """
    driven = linkage.inputs[0].name if input is None else input
    if not linkage.has_closed_form:
        raise ValueError(f"{linkage.name} has no closed form: find its spans one design at a time (reachable_range)")
    _, roots = _margin_function(linkage)
    return margin_spans(_fast_margins(linkage), roots, [s.name for s in linkage.parameters if s.is_positive],
                        [s.name for s in linkage.branches], driven, values, count, TOLERANCE, points=points,
                        block=block, stride=stride)


def _closed_form_range(motion: InputMotion, low: float, high: float, points: int) -> InputRange:
    periodic = motion.periodic and (low, high) == (-math.pi, math.pi)
    linkage = motion.linkage
    margins, roots = linkage.margins() if isinstance(linkage, CachedLinkage) else _margin_function(linkage)
    arguments = {k: v for k, v in motion.values.items()}

    def margin_values(inputs: numpy.ndarray) -> dict[str, numpy.ndarray]:
        with numpy.errstate(all="ignore"):
            return margins(**{motion.input: inputs}, **arguments)

    def assembled(inputs: numpy.ndarray) -> numpy.ndarray:
        return numpy.asarray(margin_values(inputs)["assembled"], dtype=bool)

    step = (high - low) / points
    grid = low + step * numpy.arange(points + (0 if periodic else 1))
    found = margin_values(grid)
    inside = numpy.asarray(found["assembled"], dtype=bool)
    toggles = _touching_toggles(margin_values, roots, grid, found, step, periodic)
    if inside.all():
        spans = [(low, high)]
    elif not inside.any():
        spans = []
    else:
        edges = _edges(inside, periodic)
        start = grid[edges]
        # the next scan point itself (a turn later past the last), not start + step, which can round
        # past a point where the linkage does not close
        following = numpy.append(grid, grid[0] + 2 * math.pi) if periodic else grid
        end = following[edges + 1]
        in_low, out_high = _bisect(assembled, start, end, inside[edges])
        rising = ~inside[edges]
        outside = numpy.where(rising, in_low, out_high)
        beyond = margin_values(outside)
        bounds = []
        for k in range(len(edges)):
            name, loop = next(((name, loop) for name, loop in roots if beyond[name][k] < 0), (None, None))
            at_low, at_high = in_low[k:k + 1], out_high[k:k + 1]
            if name is not None and name.startswith("margin"):
                # The clamp takes rounding below zero as the toggle itself; the toggle is where the
                # root's argument changes sign: bisect that, from the scan's bracket.
                def closes(inputs, name=name):
                    return margin_values(inputs)[name] - TOLERANCE >= 0
                at_low, at_high = _bisect(closes, start[k:k + 1], end[k:k + 1], numpy.array([inside[edges][k]]))
            at = float(at_high[0] if rising[k] else at_low[0])  # the reachable side of the edge
            bounds.append(at)
            toggles.append(Toggle(at, loop, True, name is None or name.startswith("guard")))
        marks = sorted(zip(bounds, rising.tolist()))
        spans = _spans_from_marks(marks, periodic, float(grid[0]), float(grid[-1]))
    toggles.sort(key=lambda t: t.at)
    return InputRange(motion.input, tuple(spans), tuple(toggles), True, motion.periodic)


def _touching_toggles(margin_values, roots, grid, found, step, periodic) -> list[Toggle]:
    """Toggles inside the range: a root's margin with a local minimum that reaches zero (within TOUCH)."""
    toggles = []
    for name, loop in roots:
        if not name.startswith("margin"):
            continue
        margin = numpy.asarray(found[name], dtype=float)
        before, after = numpy.roll(margin, 1), numpy.roll(margin, -1)
        lowest = (margin <= before) & (margin <= after) & (margin >= 0) & (margin < 1e-3)
        if not periodic:  # the ends of an interval are no minimum inside it
            lowest[[0, -1]] = False
        for i in numpy.flatnonzero(lowest):
            left, right = float(grid[i] - step), float(grid[i] + step)
            for _ in range(BISECTIONS):  # golden-section search for the minimum
                one = right - 0.618 * (right - left)
                two = left + 0.618 * (right - left)
                values = margin_values(numpy.array([one, two]))[name]
                if values[0] <= values[1]:
                    right = two
                else:
                    left = one
            tried = numpy.array([0.5 * (left + right), grid[i]])  # the scan's own point may be the exact one
            margins = margin_values(tried)[name]
            best = int(numpy.argmin(margins))
            if margins[best] <= TOUCH:
                at = float(tried[best])
                toggles.append(Toggle(wrap_angle(at) if periodic else at, loop, False))
    return toggles


def _continued_range(motion: InputMotion, low: float, high: float, points: int) -> InputRange:
    """The span of the guessed assembly: continued forward and back from ``start`` until Newton fails."""
    step = (high - low) / points
    start = motion.start
    if motion.periodic:
        length = points + 1
        forward, backward = start + step * numpy.arange(length), start - step * numpy.arange(length)
    else:
        if not low <= start <= high:
            raise ValueError(f"the guess is at {motion.input} = {start:g}, outside the interval [{low:g}, {high:g}]")
        forward = numpy.append(numpy.arange(start, high, step), high)
        backward = numpy.append(numpy.arange(start, low, -step), low)
    first = motion._sweep(forward[:1], motion.guess)
    if first is None:
        raise ValueError(f"{motion.linkage.name} cannot be assembled near the guess at {motion.input} = {start:g}")
    poses: dict[float, numpy.ndarray] = {}
    ends: list[tuple[float, Toggle | None]] = []
    for path in (forward, backward):
        good, solved = _longest_sweep(motion, path)
        for k in range(good):
            poses[float(path[k])] = numpy.array([solved[name][k] for name in motion.names])
        if good == len(path):
            ends.append((float(path[-1]), None))
            continue
        last = numpy.array([solved[name][good - 1] for name in motion.names])

        def solvable(inputs, last=last, at=float(path[good - 1])):
            return numpy.array([motion._sweep(numpy.array([at, x]), last) is not None for x in inputs])

        inside, _ = _bisect(solvable, numpy.array([path[good - 1]]), numpy.array([path[good]]), numpy.array([True]))
        ends.append((float(inside[0]), Toggle(float(inside[0]), None)))
    grid = numpy.array(sorted(poses))
    motion._scan = (grid, numpy.array([poses[x] for x in grid]))
    (high_end, high_toggle), (low_end, low_toggle) = ends
    toggles = tuple(t for t in (low_toggle, high_toggle) if t is not None)
    if motion.periodic and high_toggle is None and low_toggle is None:
        spans = ((-math.pi, math.pi),)
    elif motion.periodic and (high_toggle is None or low_toggle is None):
        spans = ((-math.pi, math.pi),)  # continued a whole turn one way: the input turns fully
        toggles = ()
    else:
        shift = 0.0
        if motion.periodic:
            shift = 2 * math.pi * math.floor((low_end + math.pi) / (2 * math.pi))
        spans = ((low_end - shift, high_end - shift),)
        toggles = tuple(Toggle(t.at - shift, None) for t in toggles)
    return InputRange(motion.input, spans, toggles, False, motion.periodic)


def _longest_sweep(motion: InputMotion, path: numpy.ndarray) -> tuple[int, Any]:
    """How many points of ``path`` continuation solves from the guess (binary search), and their solution."""
    whole = motion._sweep(path, motion.guess)
    if whole is not None:
        return len(path), whole
    good, bad, solved = 1, len(path), motion._sweep(path[:1], motion.guess)
    while bad - good > 1:
        middle = (good + bad) // 2
        attempt = motion._sweep(path[:middle], motion.guess)
        if attempt is None:
            bad = middle
        else:
            good, solved = middle, attempt
    return good, solved
