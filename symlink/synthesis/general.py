"""Path generation for any one-input linkage: a named point through given points, by exact gradients.

:mod:`symlink.synthesis.path` is written around the four-bar's nine dimensions; here the
linkage is any one with one input (a catalog entry or a linkage file), with a closed form or
solved by Newton's method (see below).  The
user names the point that traces the path, the parameters that are free (each with bounds), and
which parts of the frame placement are free: the traced point, in the linkage's own frame
``p``, is placed in the plane as ``(x0, y0) + scale * R(angle) p``.

* With timing (``timed``: the input's value at each target) the unknowns are the free
  parameters and the free placement.
* Without (``timed=None``) the input values are unknowns too, written as the first value and
  squared steps to the next (``q_i = q_1 + direction * sum(s_k^2)``), so the targets are
  reached in order, the input moving one way.

The residuals are the placed point minus the targets over the targets' size.  Their exact
Jacobian: the free parameters' columns come from the generated sensitivities
(:class:`symlink.numeric.design_jacobian.DesignJacobian`) of a copy of the linkage whose input is
shifted by a parameter ``input_phase``; held at zero, the derivative by that phase is the
derivative by the input (the point's rate along its path), which the untimed unknowns need by
the chain rule.  The placement's columns are written by hand.  The refinement is the
Levenberg-Marquardt with geodesic acceleration of the four-bar
(:func:`symlink.synthesis.path._accelerated_levenberg_marquardt`), which never accepts an
infeasible trial (outside the bounds, not assembled, or at a toggle).

Starts are the linkage's own feasible designs: random free parameters within their bounds and
random branch signs, kept if assembled at every target input (timed) or over the input sweep
the targets are matched along by arc length (untimed); the free placement of each is the best
similarity fit of its points to the targets.  The closest are refined, and the best refined
design is verified afresh with the generated solver of the linkage itself (not the Jacobian's
code): assembled at every target, and between consecutive targets the input moves without
leaving the assembly or passing a toggle, so the whole path is on one branch.

A linkage without a closed form (the Stephenson II six-bar) has no branch sign: its assembly is
the one Newton's method continues from an initial guess.  There the Jacobian's code is the
generated Newton module (sensitivities from the converged closure Jacobian), continued along the
input from the unknowns found at the first target by the previous evaluation, so that a
refinement carries its start's assembly along as the design moves; starts are sampled designs
on an assembly found by Newton's method from random guesses, the user's own from ``guess``, all
continued together along the input (:func:`symlink.synthesis.design_fit.newton_traced_batch`:
through the target inputs with timing, over two turns without); the verification continues the
assembly with the linkage's :class:`~symlink.numeric.solver.NumericSolver` through every target in order,
and the design reports it as ``assembly`` (the unknowns at the first target).  There each
evaluation is a Newton continuation (tens of milliseconds), so an untimed start that the
screening already brought close is refined to the end at once (:data:`_PROMISING`).

>>> from symlink.mechanism.catalog import slider_crank
>>> linkage = slider_crank()
>>> truth = {"a": 1.3, "b": 4.1, "offset": 0.7}
>>> inputs = numpy.linspace(0.0, 2.5, 6)
>>> targets = traced_points(linkage, "B", truth, inputs)  # the crank pin: a circle of radius a
>>> found = synthesize_path(linkage, "B", targets, {"a": (0.5, 2.0)}, values={"b": 4.1, "offset": 0.7},
...                         frame=(), timed=inputs)
>>> found.error < 1e-10, round(found.design["a"], 9)
(True, 1.3)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Mapping, Sequence

import numpy
import sympy as sp
from numpy.typing import ArrayLike

from ..analysis.transmission import (RUN_SAMPLES, HeldTransmission, held_over_text, least_over_inputs,
                                     transmission_arrays, transmission_coordinates)
from ..common.display import record_html
from ..symbolic.linkage import Linkage
from .design_fit import (BRANCH_SAMPLES, INPUT_PHASE, _jacobian, _newton_solver, _solver, branch_break, check_branches,
                         find_assembly, free_bounds, newton_traced_batch)
from .path import (_accelerated_levenberg_marquardt, check_distinct_targets, check_starts, ordered_inputs,
                   ordered_inputs_jacobian, steps_under_a_turn)

__all__ = ["PathSynthesis", "synthesize_path", "traced_points", "find_assembly", "path_residuals", "FRAME_NAMES"]

#: The placement of the linkage's frame in the plane: pivot shift, turn and scale.
FRAME_NAMES = ("x0", "y0", "angle", "scale")
_IDENTITY = {"x0": 0.0, "y0": 0.0, "angle": 0.0, "scale": 1.0}
_SAMPLED = 1500            # random designs drawn for the starts
_SWEEP = 96                # input values over a turn, for matching untimed targets by arc length
_PHASES = 32               # untimed: starting positions along each swept curve ...
_SPANS = tuple(numpy.linspace(0.1, 1.0, 19))  # ... and fractions of its arc length matched to the targets
_SCALED_SPANS = (0.95, 0.8, 0.6, 0.4)  # ... those fractions where the fit scales the design (path.py's)
_PATH_SAMPLES = BRANCH_SAMPLES  # input values checked between consecutive targets by the verification
_SHAPE_RATIO = 16.0        # shape-normalised starts: link lengths within this ratio of each other ...
_SHAPED = 0.5              # ... this fraction of the sampled designs (the rest uniform within the bounds)
_OFFSET_SPAN = 2.0         # ... and signed lengths (a point's offsets) within this many times the median link
_ROTATION_SAMPLES = 48     # input values over a turn checked for full rotation
_SCREENED = 4              # untimed: this many times ``starts`` starts screened by successive halving ...
_SCREEN_EVALUATIONS = 40   # ... this many evaluations each in the first round, twice as many each round after
_PARTIAL_RANK = 4.0        # untimed starts: a design whose input cannot turn fully ranks as if this much farther
_ACTIVE = 1e-6             # a constraint within this (relative) of its limit is reported active
_FLAT = 1e-6               # a transmission angle below this (radians) is a toggle: the input does not turn through it
_GAP = 1e-5                # a gap in the assembly narrower than this (radians of the input) is a change point
_MOTION_CHECKED = 300      # starts: the closest fits looked at for one that meets the constraints over the motion
_PROMISING = 1e-9          # without a closed form: a screened start this close (cost: rms 4e-5 of the size) goes on
_PROMOTED_EVALUATIONS = 400  # ... at once, for at most this many more evaluations
_NEWTON_TRACED = 1500      # without a closed form: designs drawn for the starts (traced at once: newton_traced_batch) ...
_TIMED_SUBSTEPS = 8        # ... timed: continued in this many steps from target to target
_NEWTON_GUESSES = 4        # ... random initial guesses tried for an assembly of each


@dataclass(frozen=True)
class PathSynthesis:
    """A synthesised design: parameters, placement, branches, the input at each target, and its errors.

    ``design`` holds every parameter of the linkage (free and fixed), ``placement`` the frame
    (``x0, y0, angle, scale``), ``inputs`` the input's value at each target.  ``errors`` are the
    distances from each target to the placed point, from the linkage's own generated solver;
    ``error`` the largest over the targets' size (the diagonal of their bounding box);
    ``assembled`` whether the verification passed (every target reached on one branch, no toggle
    between them); ``evaluations`` the residual evaluations spent.  ``constraints`` states every
    constraint the design was held to with its value at the design (bounds of the free
    parameters and placement, link ratio, transmission angle, full rotation), ``active`` those
    at their limit (within 1e-6 relative): the ones that stop the design from coming closer.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    linkage: str
    point: tuple[str, str]
    design: dict[str, float]
    placement: dict[str, float]
    branches: dict[str, int]
    inputs: tuple[float, ...]
    errors: tuple[float, ...] = ()
    error: float = math.nan
    assembled: bool = False
    evaluations: int = 0
    why: str = field(default="", repr=False)
    constraints: tuple[str, ...] = ()
    active: tuple[str, ...] = ()
    #: Linkages without a closed form: the unknowns at the first target's input, the assembly the design is on
    #: (the ``guess`` of :class:`symlink.numeric.solver.NumericSolver` that reproduces it); empty for closed forms.
    assembly: dict[str, float] = field(default_factory=dict)


def _point_outputs(linkage: Linkage, point: str | Sequence[str]) -> tuple[str, str]:
    names = (f"{point}_x", f"{point}_y") if isinstance(point, str) else tuple(point)
    if len(names) != 2:
        raise ValueError(f"the traced point is a point name or two output names (x, y), got {point!r}")
    for name in names:
        linkage.output(name)  # ValueError naming the outputs there are
    return names[0], names[1]


def _targets(targets: ArrayLike) -> numpy.ndarray:
    array = numpy.asarray(targets, dtype=float)
    if array.ndim != 2 or array.shape[1] != 2 or len(array) < 2:
        raise ValueError(f"the targets must be at least two rows of (x, y), got shape {array.shape}")
    if not numpy.all(numpy.isfinite(array)):
        raise ValueError("the targets must be finite numbers")
    return array


def _size(targets: numpy.ndarray) -> float:
    return float(numpy.hypot(*(targets.max(axis=0) - targets.min(axis=0))))


def _placed(local: numpy.ndarray, placement: Mapping[str, float]) -> numpy.ndarray:
    """Points (..., 2) of the linkage's frame placed in the plane: ``(x0, y0) + scale R(angle) p``."""
    c, s = math.cos(placement["angle"]), math.sin(placement["angle"])
    k = placement["scale"]
    x, y = local[..., 0], local[..., 1]
    return numpy.stack([placement["x0"] + k * (c * x - s * y), placement["y0"] + k * (s * x + c * y)], axis=-1)


def traced_points(linkage: Linkage, point: str | Sequence[str], values: Mapping[str, float], inputs: ArrayLike,
                  branches: Mapping[str, int] | None = None,
                  placement: Mapping[str, float] | None = None,
                  guess: Mapping[str, float] | None = None) -> numpy.ndarray:
    """The point at each input as rows (x, y), placed, from the linkage's generated solver; NaN where not assembled.

    A linkage without a closed form is solved by Newton's method continued along the inputs in
    their order from ``guess`` (its unknowns near an assembly at the first input; default: the
    first assembly :func:`find_assembly` finds there); every row is NaN if it cannot be continued.

    Parameters
    ----------
    linkage : Linkage
        Any linkage with one input.
    point : str or (str, str)
        A point's name or two output names.
    values : mapping of str to float
        Every parameter.
    inputs : array_like
        The input values.
    branches : mapping of str to int, optional
        Branch signs (default +1).
    placement : mapping of str to float, optional
        ``x0, y0, angle, scale`` that place the linkage (default: where it is).
    guess : mapping of str to float, optional
        For a linkage without a closed form: its unknowns near an assembly at the first input.

    Returns
    -------
    numpy.ndarray
        One row (x, y) an input; NaN where it is not assembled.

    Examples
    --------
    >>> import symlink
    >>> symlink.traced_points(symlink.fourbar(), "B", {"a": 2.0, "b": 6.0, "c": 5.0, "d": 7.0}, [0.0],
    ...                       placement={"scale": 2.0})  # the crank pin at (a, 0), scaled by 2
    array([[4., 0.]])
    """
    names = _point_outputs(linkage, point)
    where = {**_IDENTITY, **(placement or {})}
    if not linkage.has_closed_form:
        swept = numpy.atleast_1d(numpy.asarray(inputs, dtype=float))
        arguments = _arguments(linkage, values, None)
        if guess is None:
            guess = find_assembly(linkage, arguments, float(swept[0]), numpy.random.default_rng(0))
        local = numpy.full((len(swept), 2), numpy.nan)
        if guess is not None:
            try:
                with numpy.errstate(all="ignore"):
                    solved = _newton_solver(linkage)(guess=dict(guess), **arguments,
                                                     **{linkage.inputs[0].name: swept})
                local = numpy.stack([numpy.asarray(solved[names[0]]), numpy.asarray(solved[names[1]])], axis=-1)
            except ValueError:
                pass
        return _placed(local, where)
    solved = _solver(linkage, names)(**_arguments(linkage, values, branches), **{linkage.inputs[0].name: numpy.asarray(
        inputs, dtype=float)})
    ok = numpy.asarray(solved["assembled"])
    local = numpy.stack([numpy.where(ok, solved[names[0]], numpy.nan), numpy.where(ok, solved[names[1]], numpy.nan)],
                        axis=-1)
    return _placed(local, where)


def _arguments(linkage: Linkage, values: Mapping[str, float], branches: Mapping[str, int] | None) -> dict:
    known = {p.name for p in linkage.parameters}
    unknown = set(values) - known
    if unknown:
        raise ValueError(f"{linkage.name} has no parameter {sorted(unknown)[0]!r}; it has {', '.join(sorted(known))}")
    missing = known - set(values)
    if missing:
        raise ValueError(f"give a value for each parameter of {linkage.name}: {', '.join(sorted(missing))} missing")
    arguments: dict[str, object] = {name: float(value) for name, value in values.items()}
    for symbol in linkage.branches:
        arguments[symbol.name] = int((branches or {}).get(symbol.name, 1))
    return arguments


def _length_parameters(linkage: Linkage) -> set[str]:
    """The parameters that are lengths: scaled by k together they scale every point by k (empty if not so).

    The symbols of the vectors' lengths (loops and points), when every length is homogeneous of
    degree one in them and none of them turns up in an angle or in an extra.
    """
    vectors = [v for loop in linkage.loops for _, v in loop.terms]
    vectors += [v for sum_ in linkage.points.values() if sum_ is not None for _, v in sum_.as_sum().terms]
    parameters = set(linkage.parameters)
    symbols = set().union(*(v.length.free_symbols for v in vectors)) & parameters
    factor = sp.Dummy("k", positive=True)
    scaled = {symbol: factor * symbol for symbol in symbols}
    for vector in vectors:
        if vector.angle.free_symbols & symbols or sp.expand(vector.length.xreplace(scaled)
                                                             - factor * vector.length) != 0:
            return set()
    if any(expr.free_symbols & symbols for expr in linkage.extras.values()):
        return set()
    return {symbol.name for symbol in symbols}


# --- the problem -------------------------------------------------------------------------------------

class _Problem:
    """Residuals and their exact Jacobian for one linkage, point, targets and choice of free names."""

    def __init__(self, linkage: Linkage, outputs: tuple[str, str], targets: numpy.ndarray,
                 free: Mapping[str, tuple[float, float]], values: Mapping[str, float], frame: Sequence[str],
                 placement: Mapping[str, float], timed: numpy.ndarray | None,
                 frame_bounds: Mapping[str, tuple[float, float]] | None = None, max_link_ratio: float = math.inf,
                 min_transmission: float = 0.0, full_rotation: bool = False) -> None:
        self.linkage, self.outputs, self.targets = linkage, outputs, targets
        self.max_link_ratio, self.min_transmission, self.full_rotation = max_link_ratio, min_transmission, full_rotation
        self.direction: int | None = None  # untimed: the input grows (+1) or shrinks (-1) from target to target
        self.size = _size(targets)
        self.free = tuple(free)
        self.bounds = numpy.array([free[name] for name in self.free], dtype=float).reshape(len(self.free), 2)
        self.values = dict(values)
        self.frame = tuple(frame)
        #: Bounds of the free parameters, then of the free placement (unbounded unless ``frame_bounds`` says).
        self.limits = numpy.concatenate([self.bounds, numpy.array(
            [(frame_bounds or {}).get(name, (-numpy.inf, numpy.inf)) for name in self.frame],
            dtype=float).reshape(len(self.frame), 2)])
        self.placement = {**_IDENTITY, **placement}
        self.timed = timed
        #: Without a closed form the Jacobian's code is Newton's method: it also gives the unknowns, whose values
        #: at the first input (``assembly``) are the next evaluation's initial guess, so that a refinement
        #: continues the start's assembly as the design moves (there is no branch sign to hold).
        self.newton = not linkage.has_closed_form
        self.unknown_names = tuple(q.name for q in linkage.unknowns) if self.newton else ()
        self.assembly: dict[str, float] | None = None
        self.jacobian = _jacobian(linkage, outputs + tuple(n for n in self.unknown_names if n not in outputs), self.free)
        positive = {p.name for p in linkage.parameters if p.is_positive}
        self.positive = numpy.array([name in positive for name in self.free], dtype=bool)
        lengths = _length_parameters(linkage)
        #: Which free parameters are lengths: scaled together they scale the linkage's drawing.
        self.lengths = numpy.array([name in lengths for name in self.free], dtype=bool)
        #: Starts are fitted with a free scale, then the scale goes into the lengths: possible when every
        #: length of the linkage is free and the scale is not.
        self.absorbs = bool(lengths) and lengths <= set(self.free) and "scale" not in self.frame
        #: The link lengths (positive parameters), free ones by index, fixed ones by value: the link ratio's.
        self.links = numpy.array([name in positive for name in self.free], dtype=bool)
        self.fixed_links = [abs(float(values[p.name])) for p in linkage.parameters
                            if p.is_positive and p.name not in self.free and p.name in values]
        #: The coordinates the transmission angles of its two-angle loops need (none without a closed form).
        self.joints = transmission_coordinates(linkage) if not self.newton else []
        self.transmission = ((self.joints, min_transmission) if min_transmission > 0 else None)

    @property
    def width(self) -> int:
        """Unknowns besides the input values: free parameters, then free placement."""
        return len(self.free) + len(self.frame)

    def split(self, x: numpy.ndarray) -> tuple[dict[str, float], dict[str, float]]:
        design = {**self.values, **{name: float(v) for name, v in zip(self.free, x[:len(self.free)])}}
        placement = {**self.placement, **{name: float(v) for name, v in zip(self.frame, x[len(self.free):self.width])}}
        return design, placement

    def local(self, design: Mapping[str, float], inputs: numpy.ndarray, branches: Mapping[str, float]):
        """Points (N, 2) in the linkage's frame, their Jacobian (N, 2, free + 1: the input last), feasibility (N)."""
        if self.newton:
            return self._newton_local(design, inputs, branches)
        given: dict[str, float | numpy.ndarray] = {**design, INPUT_PHASE: 0.0, self.linkage.inputs[0].name: inputs,
                 **{name: float(sign) for name, sign in branches.items()}}
        with numpy.errstate(all="ignore"):
            values, slopes, assembled = self.jacobian.arrays(*(given[name] for name in self.jacobian.arguments))
        points = numpy.moveaxis(values, 0, -1).reshape(len(inputs), 2)
        jac = numpy.moveaxis(slopes, -1, 0).reshape(len(inputs), 2, len(self.free) + 1)
        ok = (numpy.broadcast_to(assembled, inputs.shape) & numpy.all(numpy.isfinite(jac), axis=(1, 2))
              & numpy.all(numpy.isfinite(points), axis=1))
        return points, jac, ok

    def _newton_local(self, design: Mapping[str, float], inputs: numpy.ndarray, start: Mapping[str, float]):
        """:meth:`local` by Newton's method, continued along ``inputs`` from :attr:`assembly` (else ``start``).

        Where it converges at every input, :attr:`assembly` becomes the unknowns found at the first
        one; anywhere it does not (no assembly, a dead centre), nothing is feasible.
        """
        guess = dict(self.assembly if self.assembly is not None else start)
        count = len(inputs)
        try:
            with numpy.errstate(all="ignore"):
                values, slopes = self.jacobian(guess=guess, **design, **{INPUT_PHASE: 0.0,
                                                                         self.linkage.inputs[0].name: inputs})
        except ValueError:
            return (numpy.full((count, 2), numpy.nan), numpy.full((count, 2, len(self.free) + 1), numpy.nan),
                    numpy.zeros(count, dtype=bool))
        points = numpy.stack([numpy.asarray(values[name], dtype=float) for name in self.outputs], axis=-1)
        jac = numpy.asarray(slopes[:, :2, :], dtype=float)
        ok = (numpy.asarray(values["assembled"], dtype=bool) & numpy.all(numpy.isfinite(jac), axis=(1, 2))
              & numpy.all(numpy.isfinite(points), axis=1))
        if numpy.all(ok):
            self.assembly = {name: float(numpy.asarray(values[name])[0]) for name in self.unknown_names}
        return points, jac, ok

    def allowed(self, x: numpy.ndarray) -> bool:
        bounded = x[:self.width]
        inside = numpy.all((bounded >= self.limits[:, 0]) & (bounded <= self.limits[:, 1]))
        ok = bool(inside and numpy.all(x[:len(self.free)][self.positive] > 0) and numpy.all(numpy.isfinite(x)))
        return ok and (not math.isfinite(self.max_link_ratio) or self.link_ratio(x) <= self.max_link_ratio)

    def link_ratio(self, x: numpy.ndarray) -> float:
        """The longest link over the shortest (positive length parameters, free and fixed); 1 with none."""
        links = numpy.concatenate([numpy.abs(x[:len(self.free)][self.links]), self.fixed_links])
        return float(links.max() / links.min()) if len(links) and links.min() > 0 else (
            math.inf if len(links) else 1.0)

    def solved(self, names: Sequence[str], design: Mapping[str, float], inputs: numpy.ndarray,
               branches: Mapping[str, float]) -> dict[str, numpy.ndarray]:
        """The coordinates ``names`` at ``inputs`` from the linkage's own generated solver.

        Closed form: the branch signs ``branches``.  Without: Newton's method continued along the
        inputs in order from :attr:`assembly` (the unknowns at the first target), else from
        ``branches`` (the start's assembly), ``ValueError`` where it cannot be continued.
        """
        linkage = self.linkage
        if not self.newton:
            signs = {name: int(sign) for name, sign in branches.items()}
            return _solver(linkage, tuple(names))(**_arguments(linkage, design, signs),
                                                  **{linkage.inputs[0].name: inputs})
        guess = dict(self.assembly if self.assembly is not None else branches)
        with numpy.errstate(all="ignore"):
            found = _newton_solver(linkage)(guess=guess, **_arguments(linkage, design, None),
                                            **{linkage.inputs[0].name: numpy.asarray(inputs, dtype=float)})
        return {name: numpy.asarray(found[name], dtype=float) for name in names}

    def feasible_motion(self, design: Mapping[str, float], inputs: numpy.ndarray,
                        branches: Mapping[str, float]) -> str:
        """Why the design breaks the transmission or rotation constraint over the motion it runs ('' if it does not).

        ``inputs``: the input at each target.  The motion (:meth:`motion_run`) is the full turn where the input
        turns fully, else the range of ``inputs``; the transmission angle is held over all of it
        (:meth:`held_transmissions`), not only at the targets.
        """
        if self.transmission is None and not self.full_rotation:
            return ""
        linkage = self.linkage
        if self.newton:  # no transmission angle without a closed form (refused up front): full rotation only
            # Newton's method continued a whole turn from the assembly at the first input: it stops (ValueError)
            # where the assembly ends or at a dead centre.
            turn = float(inputs[0]) + numpy.linspace(0.0, 2 * math.pi, _ROTATION_SAMPLES + 1)
            try:
                self.solved(self.unknown_names, design, turn, branches)
            except ValueError:
                return "the input cannot turn fully (the assembly ends or meets a dead centre over the turn)"
            return ""
        arguments = _arguments(linkage, design, {k: int(v) for k, v in branches.items()})
        turns, low, high, over_turn, toggles = self.motion_run(design, arguments, inputs)
        if self.full_rotation and not (turns and not toggles):
            return "the input cannot turn fully (no assembly or a toggle over the turn)"
        if self.transmission is None:
            return ""
        least = self.transmission[1]
        worst, at, loop = over_turn if over_turn is not None else self._least_transmission(
            design, arguments, low, high, turns)
        if not worst >= least:
            over = held_over_text("full turn" if turns else "rocking range", low, high, self._input_is_angle)
            shown = "not assembled" if math.isnan(worst) else f"falls to {math.degrees(worst):.6g} deg"
            return (f"the transmission angle at {loop} {shown} at input {self._show_input(at)} (held >= "
                    f"{math.degrees(least):.6g} deg over {over})")
        return ""

    @property
    def _input_is_angle(self) -> bool:
        from ..symbolic.closure import is_angle
        return bool(is_angle(self.linkage, self.linkage.inputs[0]))

    def _show_input(self, value: float) -> str:
        """An input value as the constraints' report shows it: degrees in (-180, 180] for an angle (to 1e-4 deg)."""
        from ..common.angles import wrap_angle
        return f"{round(math.degrees(wrap_angle(value)), 4) + 0.0:.6g} deg" if self._input_is_angle else f"{value:.6g}"

    def motion_run(self, design: Mapping[str, float], arguments: Mapping[str, object], inputs: numpy.ndarray
                   ) -> tuple[bool, float, float, tuple[float, float, str] | None, bool]:
        """The motion a closed-form design runs: ``(turns, low, high, over_turn, toggles)``.

        ``turns``: its input reaches the whole turn (assembled at :data:`~symlink.analysis.transmission.
        RUN_SAMPLES` values over a turn from the first target and, where it has two-angle loops, at every value
        the refinement of their least transmission angle tries: a gap in the assembly narrower than a sample is
        found there, where the triangle goes flat); it then runs the full turn from there, as
        :func:`symlink.analysis.transmission.run_transmission` reports it.  A gap narrower than :data:`_GAP` is
        a change point (the design is within rounding of one: its input passes it, through a flat triangle,
        transmission angle zero), not an end of its motion.  Otherwise it rocks between the least and the
        greatest of ``inputs`` (the targets' inputs, which the verification walks in order on one branch).
        ``over_turn``: the least transmission angle over the turn, where, and its loop (None where it was not
        found).  ``toggles``: a toggle or change point on the turn (a sample at one, or a least transmission
        angle below :data:`_FLAT`).
        """
        linkage = self.linkage
        turn = float(inputs[0]) + numpy.linspace(0.0, 2 * math.pi, RUN_SAMPLES, endpoint=False)
        solver = _solver(linkage, ("singular",))
        solved = solver(**arguments, **{linkage.inputs[0].name: turn})
        rocking = (False, float(numpy.min(inputs)), float(numpy.max(inputs)), None, True)
        assembled = numpy.asarray(solved["assembled"], dtype=bool)
        toggles = bool(numpy.any(numpy.asarray(solved["singular"], dtype=bool)))
        low, high = float(turn[0]), float(turn[0] + 2 * math.pi)
        gaps = turn[~assembled]
        if len(gaps):
            if len(gaps) > 2 or not self._narrow_gaps(arguments, gaps):
                return rocking
            loops = list(self._transmission_worsts(design, arguments, numpy.array([low]))) if self.joints else []
            return True, low, high, ((0.0, float(gaps[0]), loops[0]) if loops else None), True
        if not self.joints:
            return True, low, high, None, toggles
        over_turn = self._least_transmission(design, arguments, low, high, True)
        if math.isnan(over_turn[0]):  # a gap narrower than a sample
            if not self._narrow_gaps(arguments, numpy.array([over_turn[1]])):
                return rocking
            return True, low, high, (0.0, over_turn[1], over_turn[2]), True
        return True, low, high, over_turn, toggles or not over_turn[0] > _FLAT

    def _narrow_gaps(self, arguments: Mapping[str, object], gaps: numpy.ndarray) -> bool:
        """Whether the design is assembled :data:`_GAP` before and after each input of ``gaps`` (where it is not)."""
        around = (gaps[:, None] + numpy.array([-_GAP, _GAP])[None, :]).ravel()
        solved = _solver(self.linkage, ("singular",))(**arguments, **{self.linkage.inputs[0].name: around})
        return bool(numpy.all(numpy.asarray(solved["assembled"], dtype=bool)))

    def _transmission_worsts(self, design: Mapping[str, float], arguments: Mapping[str, object],
                             values: numpy.ndarray) -> dict[str, numpy.ndarray]:
        """``min(mu, pi - mu)`` of every two-angle loop at the inputs ``values``; NaN where not assembled."""
        names = tuple(self.joints)
        solved = _solver(self.linkage, names)(**arguments, **{self.linkage.inputs[0].name: values})
        ok = numpy.asarray(solved["assembled"], dtype=bool)
        return {loop: numpy.where(ok, numpy.minimum(mu, math.pi - mu), numpy.nan)
                for loop, mu in transmission_arrays(self.linkage, {**design, **arguments}, solved).items()}

    def _least_transmission(self, design: Mapping[str, float], arguments: Mapping[str, object], low: float,
                            high: float, turns: bool) -> tuple[float, float, str]:
        """The least ``min(mu, pi - mu)`` of every two-angle loop over ``low`` to ``high``, where, and which loop."""
        def worst_at(values: numpy.ndarray) -> numpy.ndarray:
            return numpy.min(numpy.stack(list(self._transmission_worsts(design, arguments, values).values())), axis=0)

        worst, at = least_over_inputs(worst_at, low, high, periodic=turns)
        by_loop = self._transmission_worsts(design, arguments, numpy.array([at]))
        loop = min(by_loop, key=lambda name: (numpy.nan_to_num(by_loop[name][0], nan=-1.0), name))
        return worst, at, loop

    def held_transmissions(self, design: Mapping[str, float], inputs: numpy.ndarray,
                           branches: Mapping[str, float]) -> dict[str, HeldTransmission]:
        """Each two-angle loop's worst transmission angle over the motion the design runs (:meth:`motion_run`)."""
        assert self.transmission is not None and not self.newton
        arguments = _arguments(self.linkage, design, {k: int(v) for k, v in branches.items()})
        turns, low, high, _, _ = self.motion_run(design, arguments, inputs)
        held = {}
        for loop in self._transmission_worsts(design, arguments, numpy.array([float(inputs[0])])):
            def worst_at(values: numpy.ndarray, loop: str = loop) -> numpy.ndarray:
                return self._transmission_worsts(design, arguments, values)[loop]

            worst, at = least_over_inputs(worst_at, low, high, periodic=turns)
            held[loop] = HeldTransmission(worst, at, "full turn" if turns else "rocking range", low, high)
        return held

    def projected(self, x: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
        """``x`` with its free parameters and placement clipped to their bounds, and which entries were outside."""
        low = numpy.concatenate([self.limits[:, 0], numpy.full(len(x) - self.width, -numpy.inf)])
        high = numpy.concatenate([self.limits[:, 1], numpy.full(len(x) - self.width, numpy.inf)])
        return numpy.clip(x, low, high), (x < low) | (x > high)

    def evaluate(self, x: numpy.ndarray, inputs: numpy.ndarray, branches: Mapping[str, int], project: bool = False):
        """Residuals (2N) and Jacobian (2N, width + N: d/d each input value last), or None where infeasible.

        ``project``: a design outside the bounds is evaluated at its projection onto them, and the
        columns of the parameters held at a bound are zero (the residuals do not move with them),
        so that a refinement slides along a bound instead of stopping at it.
        """
        outside = numpy.zeros(len(x), dtype=bool)
        if project:
            x, outside = self.projected(x)
        if not self.allowed(x):
            return None
        design, placement = self.split(x)
        if "scale" in placement and not placement["scale"] > 0:
            return None
        local, jac, ok = self.local(design, inputs, branches)
        if not numpy.all(ok):
            return None
        if self.feasible_motion(design, inputs, branches):
            return None
        c, s, k = math.cos(placement["angle"]), math.sin(placement["angle"]), placement["scale"]
        turn = numpy.array([[c, -s], [s, c]])
        placed = _placed(local, placement)
        count = len(inputs)
        # d placed / d free parameters and d input: the scaled turn of the local derivatives.
        moved = k * numpy.einsum("ij,njk->nik", turn, jac)
        columns = [moved[:, :, :len(self.free)]]
        by_hand = {"x0": numpy.tile([1.0, 0.0], (count, 1)), "y0": numpy.tile([0.0, 1.0], (count, 1)),
                   "angle": numpy.stack([-(placed[:, 1] - placement["y0"]), placed[:, 0] - placement["x0"]], axis=1),
                   "scale": local @ turn.T}
        for name in self.frame:
            columns.append(by_hand[name][:, :, None])
        dense = numpy.concatenate(columns, axis=2).reshape(2 * count, self.width)
        by_input = numpy.zeros((2 * count, count))
        by_input[numpy.arange(2 * count), numpy.repeat(numpy.arange(count), 2)] = moved[:, :, -1].ravel()
        residuals = ((placed - self.targets) / self.size).ravel()
        if numpy.any(outside):
            dense[:, outside[:self.width]] = 0.0
        return residuals, numpy.concatenate([dense, by_input], axis=1) / self.size


def path_residuals(linkage: Linkage, point: str | Sequence[str], targets: ArrayLike, design: Mapping[str, float],
                   inputs: ArrayLike, free: Sequence[str], frame: Sequence[str] = FRAME_NAMES,
                   placement: Mapping[str, float] | None = None,
                   branches: Mapping[str, int] | None = None) -> tuple[numpy.ndarray, numpy.ndarray]:
    """The residuals ``(placed point - target) / size`` (x, y of each target in turn) and their exact Jacobian.

    The Jacobian's columns: the ``free`` parameters, the free ``frame`` names, then the input at
    each target (what :func:`synthesize_path` refines).  ``ValueError`` where the design is not
    assembled at an input.

    >>> from symlink.mechanism.catalog import slider_crank
    >>> r, J = path_residuals(slider_crank(), "B", [[1.0, 0.0], [0.0, 2.0]], {"a": 1.0, "b": 3.0, "offset": 0.0},
    ...                       [0.0, 1.5707963267948966], ["a"], frame=())
    >>> J.shape, [round(float(v), 9) for v in J[:, 0]]  # dB/da = (cos q, sin q) over the size, sqrt(5)
    ((4, 3), [0.447213595, 0.0, 0.0, 0.447213595])
    """
    linkage_inputs = numpy.asarray(inputs, dtype=float)
    points = _targets(targets)
    names = _point_outputs(linkage, point)
    values = {name: float(v) for name, v in design.items()}
    problem = _Problem(linkage, names, points, {name: (-math.inf, math.inf) for name in free}, values, frame,
                       placement or {}, linkage_inputs)
    x = numpy.array([values[name] for name in free] + [problem.placement[name] for name in frame])
    found = problem.evaluate(x, linkage_inputs, {s.name: int((branches or {}).get(s.name, 1))
                                                 for s in linkage.branches})
    if found is None:
        raise ValueError(f"{linkage.name} is not assembled (or at a toggle) at one of the inputs")
    return found


# --- starts ------------------------------------------------------------------------------------------

def _fit_placements(problem: _Problem, z: numpy.ndarray, w: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
    """The free placement bringing each row of local points ``z`` (complex, M x N) closest to ``w`` (N).

    Returns ``(placements, rms)``: rows (x0, y0, angle, scale), fixed parts as given, and the rms
    distance left.  All four free: the complex least-squares similarity; otherwise the best turn
    (Procrustes), then the best scale along it, then the mean shift, for the parts that are free.
    """
    fixed = problem.placement
    rows = z.shape[0]
    frame = set(problem.frame) | ({"scale"} if problem.absorbs else set())
    shift_free = "x0" in frame or "y0" in frame
    origin = complex(fixed["x0"], fixed["y0"])
    if shift_free:
        dz, dw = z - z.mean(axis=-1, keepdims=True), (w - w.mean())[None, :]
    else:
        dz, dw = z, (w - origin)[None, :]
    with numpy.errstate(all="ignore"):
        cross = numpy.sum(numpy.conj(dz) * dw, axis=-1)
        weight = numpy.sum(numpy.abs(dz) ** 2, axis=-1)
        angle = numpy.angle(cross) if "angle" in frame else numpy.full(rows, fixed["angle"])
        along = (numpy.exp(-1j * angle) * cross).real
        scale = (numpy.where((weight > 0) & (along > 0), along / weight, fixed["scale"])
                 if "scale" in frame else numpy.full(rows, fixed["scale"]))
        turn = scale * numpy.exp(1j * angle)
        shift = numpy.full(rows, origin)
        if shift_free:
            offset = numpy.mean(w[None, :] - (origin + turn[:, None] * z), axis=-1)
            shift = shift + (offset.real if "x0" in frame else 0.0) + (
                1j * offset.imag if "y0" in frame else 0.0)
        rms = numpy.sqrt(numpy.mean(numpy.abs(shift[:, None] + turn[:, None] * z - w[None, :]) ** 2, axis=-1))
    rms = numpy.where(numpy.isfinite(rms) & (scale > 0), rms, numpy.inf)
    return numpy.stack([shift.real, shift.imag, angle, scale], axis=1), rms


def _start(problem: _Problem, free: numpy.ndarray, row: numpy.ndarray) -> numpy.ndarray | None:
    """The unknowns of a start: free parameters and the free parts of a placement row (x0, y0, angle, scale).

    A fitted scale the problem cannot move goes into the lengths (the drawing is the same);
    a placement outside its bounds is clipped to them; None if a parameter is outside its bounds.
    """
    free = numpy.array(free, dtype=float)
    if problem.absorbs:
        free[problem.lengths] *= row[3] / problem.placement["scale"]
    x = numpy.concatenate([free, [float(row[FRAME_NAMES.index(name)]) for name in problem.frame]])
    x[len(free):] = problem.projected(x)[0][len(free):]  # a placement outside its bounds: the nearest within
    return x if problem.allowed(x) else None


def _sampled_designs(problem: _Problem, rng: numpy.random.Generator, count: int, given: Mapping[str, float],
                     branch_choice: Mapping[str, int] | None) -> tuple[numpy.ndarray, list[dict[str, int]]]:
    """Free parameters (rows) and branch signs: the user's design first (if all its free values are given),
    then random ones uniform within the bounds, branches random unless fixed.

    Not :func:`symlink.synthesis.design_fit.sampled_designs`, on purpose: path synthesis places
    the linkage by a similarity fit that may scale it, so when every length is free
    (:attr:`_Problem.absorbs`) half the rows are shape-normalised (:func:`_shaped_design`);
    function and motion generation have no scale to fit, so they draw uniformly within the bounds.
    """
    names = [s.name for s in problem.linkage.branches]
    chosen = dict(branch_choice or {})
    rows, signs = [], []
    if all(name in given for name in problem.free):
        rows.append([given[name] for name in problem.free])
        signs.append({n: int(chosen.get(n, 1)) for n in names})
    low, high = problem.bounds[:, 0], problem.bounds[:, 1]
    shaped = int(round(_SHAPED * count)) if problem.absorbs else 0
    for k in range(count):
        rows.append(list(_shaped_design(problem, rng) if k < shaped else rng.uniform(low, high)))
        signs.append({n: int(chosen[n]) if n in chosen else int(rng.choice([-1, 1])) for n in names})
    return numpy.array(rows, dtype=float).reshape(len(rows), len(problem.free)), signs


def _shaped_design(problem: _Problem, rng: numpy.random.Generator) -> numpy.ndarray:
    """Free parameters of a shape-normalised design (the four-bar atlas's way, for any linkage).

    Used when every length is free, so the placement fit scales the whole design to the
    targets' size (:func:`_start`): only the shape is drawn.  The links (positive lengths) are
    log-uniform within :data:`_SHAPE_RATIO` (and the link-ratio bound) of each other, about 1;
    signed lengths (a point's offsets, pivot coordinates) uniform within :data:`_OFFSET_SPAN`
    times the median link; the other free parameters (angles) uniform within their bounds.
    Uniform draws within wide bounds give flat, huge linkages (link ratios of 100), from which
    the refinement drifts further along flat valleys instead of closing on the targets.
    """
    ratio = min(_SHAPE_RATIO, problem.max_link_ratio)
    x = rng.uniform(problem.bounds[:, 0], problem.bounds[:, 1])
    links = problem.links & problem.lengths
    x[links] = numpy.exp(rng.uniform(-0.5, 0.5, int(links.sum())) * math.log(ratio))
    signed = problem.lengths & ~problem.links
    middle = float(numpy.median(x[links])) if links.any() else 1.0
    x[signed] = rng.uniform(-_OFFSET_SPAN, _OFFSET_SPAN, int(signed.sum())) * middle
    return x


def _traced_batch(problem: _Problem, rows: numpy.ndarray, signs: list[dict[str, int]],
                  inputs: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
    """The point (complex, designs x inputs) of many designs at once, and where it is assembled off a toggle."""
    given: dict[str, float | numpy.ndarray] = {**problem.values, INPUT_PHASE: 0.0,
                                               problem.linkage.inputs[0].name: inputs[None, :]}
    for k, name in enumerate(problem.free):
        given[name] = rows[:, k:k + 1]
    for symbol in problem.linkage.branches:
        given[symbol.name] = numpy.array([[float(sign[symbol.name])] for sign in signs])
    shape = (len(rows), len(inputs))
    # every argument at the full shape: the generated arithmetic gathers some intermediates into arrays
    arguments = [numpy.broadcast_to(numpy.asarray(given[name], dtype=float), shape)
                 for name in problem.jacobian.arguments]
    with numpy.errstate(all="ignore"):
        values, slopes, assembled = problem.jacobian.arrays(*arguments)
    z = numpy.broadcast_to(values[0], shape) + 1j * numpy.broadcast_to(values[1], shape)
    ok = (numpy.broadcast_to(assembled, shape) & numpy.isfinite(z)
          & numpy.all(numpy.isfinite(numpy.broadcast_to(slopes, slopes.shape[:2] + shape)), axis=(0, 1)))
    return z, ok


def _timed_starts(problem: _Problem, rng, count: int, given, branch_choice):
    inputs = problem.timed
    assert inputs is not None
    w = problem.targets[:, 0] + 1j * problem.targets[:, 1]
    rows, signs = _sampled_designs(problem, rng, _SAMPLED, given, branch_choice)
    z, ok = _traced_batch(problem, rows, signs, inputs)
    placements, rms = _fit_placements(problem, numpy.where(ok, z, 0.0), w)
    rms = numpy.where(numpy.all(ok, axis=1), rms, numpy.inf)
    fits = []
    for k in numpy.flatnonzero(numpy.isfinite(rms)):
        x = _start(problem, rows[k], placements[k])
        if x is not None:
            fits.append((float(rms[k]), x, signs[k], inputs.copy()))
    return _ranked(fits, count, given, problem)


def _untimed_starts(problem: _Problem, rng, count: int, given, branch_choice, guess=None):
    """Designs whose swept path, matched to the targets by arc length (phases, spans, both ways), fits best.

    The input sweeps two turns; a design assembled over a whole turn is matched anywhere along
    it (across the seam too), any other along its longest assembled stretch.
    """
    w = problem.targets[:, 0] + 1j * problem.targets[:, 1]
    chords = numpy.concatenate([[0.0], numpy.cumsum(numpy.abs(numpy.diff(w)))])
    fraction = chords / chords[-1] if chords[-1] > 0 else numpy.linspace(0.0, 1.0, len(w))
    sweep = numpy.linspace(-math.pi, 3 * math.pi, 2 * _SWEEP + 1)
    # Where the fit scales the design, a short, nearly straight stretch of any curve, magnified, fits any smooth
    # targets (collinear ones exactly) and starts the refinement on a huge, flat linkage: long stretches only.
    spans = numpy.array(_SCALED_SPANS if problem.absorbs or "scale" in problem.frame else _SPANS)
    phases = numpy.linspace(0.0, 1.0, _PHASES, endpoint=False)
    ways = {None: [fraction, 1.0 - fraction], 1: [fraction], -1: [1.0 - fraction]}[problem.direction]
    shapes = numpy.stack(ways)  # along the curve with the input growing, shrinking, or both
    if problem.newton:
        rows, signs = _sampled_designs(problem, rng, _NEWTON_TRACED, given, None)
        traced, assembled, unknowns = _newton_traced(problem, rows, sweep, rng, guess,
                                                     all(name in given for name in problem.free))
    else:
        rows, signs = _sampled_designs(problem, rng, _SAMPLED, given, branch_choice)
        traced, assembled = _traced_batch(problem, rows, signs, sweep)
    fits = []
    for index in range(len(rows)):
        ok = assembled[index]
        turning = bool(numpy.all(ok))
        run = (0, len(sweep)) if turning else _longest_run(ok[:_SWEEP + 1])
        if run is None:
            continue
        start, stop = run
        q, z = sweep[start:stop], traced[index, start:stop]
        arc = numpy.concatenate([[0.0], numpy.cumsum(numpy.abs(numpy.diff(z)))])
        if not arc[-1] > 0:
            continue
        arc /= arc[-1] / 2 if turning else arc[-1]  # a whole turn is 1: the second turn lets a match cross the seam
        usable = spans[None, :, None, None] * shapes[None, None, :, :]  # (1, spans, ways, N)
        origin = phases[:, None, None, None] * (1.0 if turning else (1.0 - spans)[None, :, None, None])
        where = (origin + usable).reshape(-1, len(w))
        angles = numpy.interp(where, arc, q)
        zz = numpy.interp(angles, q, z.real) + 1j * numpy.interp(angles, q, z.imag)
        placements, rms = _fit_placements(problem, zz, w)
        # Targets matched within one or two sweep intervals are matched to a straight chord of the interpolation
        # (exactly, for collinear targets), not to the curve: such fits are no starts.
        cells = numpy.sort(numpy.floor((angles - q[0]) / (q[1] - q[0])), axis=1)
        distinct = 1 + numpy.sum(numpy.diff(cells, axis=1) > 0, axis=1)
        rms = numpy.where(distinct >= min(len(w), 4), rms, numpy.inf)
        for k in numpy.argsort(rms)[:4]:  # the best match that stays within the bounds
            x = _start(problem, rows[index], placements[k])
            if math.isfinite(rms[k]) and x is not None:
                # without a closed form the start's "branches" are its unknowns at the first target's input
                assembly: Mapping[str, float] = signs[index] if not problem.newton else {
                    name: float(numpy.interp(angles[k][0], q, unknowns[index, start:stop, j]))
                    for j, name in enumerate(problem.unknown_names)}
                fits.append((float(rms[k]) * (1.0 if turning else _PARTIAL_RANK), x, assembly, angles[k]))
                break
    return _ranked(fits, count, given, problem)


def _newton_timed_starts(problem: _Problem, rng, count: int, given, guess: Mapping[str, float] | None):
    """Timed starts of a linkage without a closed form: sampled designs continued along the target inputs at once.

    :data:`_NEWTON_TRACED` sampled designs (the user's own first, from ``guess`` when given) are
    assembled at the first target's input and continued through every target in order, with
    :data:`_TIMED_SUBSTEPS` steps between consecutive targets, all together
    (:func:`symlink.synthesis.design_fit.newton_traced_batch`); those assembled through all of
    them are placed by the similarity fit and ranked.  The start's "branches" are its assembly
    (the unknowns at the first input), which the refinement then continues.
    """
    inputs = problem.timed
    assert inputs is not None
    w = problem.targets[:, 0] + 1j * problem.targets[:, 1]
    rows, _ = _sampled_designs(problem, rng, _NEWTON_TRACED, given, None)
    users = all(name in given for name in problem.free)
    steps = numpy.linspace(0.0, 1.0, _TIMED_SUBSTEPS + 1)[:-1]
    sweep = numpy.concatenate([(inputs[:-1, None] + numpy.diff(inputs)[:, None] * steps[None, :]).ravel(),
                               inputs[-1:]])
    traced, assembled, unknowns = _newton_traced(problem, rows, sweep, rng, guess, users)
    at = numpy.arange(len(inputs)) * _TIMED_SUBSTEPS
    through = numpy.all(assembled[:, at], axis=1) & numpy.all(assembled, axis=1)
    placements, rms = _fit_placements(problem, numpy.where(through[:, None], traced[:, at], 0.0), w)
    fits = []
    for index in numpy.flatnonzero(through & numpy.isfinite(rms)):
        x = _start(problem, rows[index], placements[index])
        if x is not None:
            assembly = {name: float(unknowns[index, 0, j]) for j, name in enumerate(problem.unknown_names)}
            fits.append((float(rms[index]), x, assembly, inputs.copy()))
    return _ranked(fits, count, given, problem)


def _newton_traced(problem: _Problem, rows: numpy.ndarray, sweep: numpy.ndarray, rng,
                   guess: Mapping[str, float] | None, users: bool):
    """Untimed starts' sweeps without a closed form: the point (complex) and the unknowns along ``sweep``.

    All designs at once (:func:`symlink.synthesis.design_fit.newton_traced_batch`): each is
    assembled at the sweep's first input (the user's design, first, from ``guess`` when given;
    the others from random guesses) and continued value by value until Newton's method stops or
    meets a dead centre: what follows is not assembled.  Returns ``(traced (M, N), assembled (M, N),
    unknowns (M, N, unknowns))``.
    """
    linkage = problem.linkage
    designs: dict[str, float | numpy.ndarray] = dict(problem.values)
    for k, name in enumerate(problem.free):
        designs[name] = rows[:, k]
    starts = None
    if users and guess is not None:
        starts = numpy.full((len(rows), len(problem.unknown_names)), numpy.nan)
        starts[0] = [float(guess[name]) for name in problem.unknown_names]
    unknowns, assembled = newton_traced_batch(linkage, designs, sweep, rng, _NEWTON_GUESSES, starts)
    functions = _newton_solver(linkage).functions
    parameters = [numpy.broadcast_to(numpy.asarray(designs[name], dtype=float)[..., None], assembled.shape)
                  if numpy.ndim(designs[name]) else float(designs[name]) for name in functions["PARAMETERS"]]
    with numpy.errstate(all="ignore"):
        named = functions["_outputs"](sweep[None, :], *parameters, *numpy.moveaxis(unknowns, -1, 0))
    named.update({name: unknowns[..., k] for k, name in enumerate(problem.unknown_names)})
    x, y = (numpy.broadcast_to(numpy.asarray(named[name], dtype=float), assembled.shape) for name in problem.outputs)
    traced = numpy.where(assembled, x + 1j * y, numpy.nan)
    return traced, assembled & numpy.isfinite(traced), unknowns


def _ranked(fits: list, count: int, given: Mapping[str, float], problem: _Problem) -> list:
    """The ``count`` closest fits, the user's own design (sampled first) kept first if it is feasible.

    With a constraint over the motion (transmission angle, full rotation) on a closed-form linkage, only fits
    that meet it are kept (the closest :data:`_MOTION_CHECKED` are looked at): a refinement never leaves
    an infeasible start, so the closest fits, which break it when the targets come from a design that does,
    would all be lost.
    """
    first = fits[:1] if fits and all(name in given for name in problem.free) and numpy.array_equal(
        fits[0][1][:len(problem.free)], [given[name] for name in problem.free]) else []
    rest = sorted(fits[len(first):], key=lambda item: item[0])
    ordered = first + rest
    if problem.newton or (problem.transmission is None and not problem.full_rotation):
        return ordered[:count]
    kept = []
    for fit in ordered[:_MOTION_CHECKED]:
        design, _ = problem.split(fit[1])
        if not problem.feasible_motion(design, numpy.asarray(fit[3], dtype=float), fit[2]):
            kept.append(fit)
            if len(kept) >= count:
                break
    return kept


def _longest_run(ok: numpy.ndarray) -> tuple[int, int] | None:
    """The longest stretch of True (start, stop), at least four long; None if there is none."""
    best, start = None, None
    for k, flag in enumerate(list(ok) + [False]):
        if flag and start is None:
            start = k
        elif not flag and start is not None:
            if k - start >= 4 and (best is None or k - start > best[1] - best[0]):
                best = (start, k)
            start = None
    return best


# --- refinement and verification ---------------------------------------------------------------------

def _refine(problem: _Problem, x0: numpy.ndarray, branches: Mapping[str, int], inputs: numpy.ndarray,
            evaluations: int, tolerance: float):
    """One start refined: (x, input values, cost, evaluations), or None if the start is infeasible."""
    width = problem.width
    problem.assembly = dict(branches) if problem.newton else None  # the start's assembly, continued from here
    if problem.timed is not None:
        def residuals(x: numpy.ndarray):
            found = problem.evaluate(x, inputs, branches, project=True)
            return None if found is None else (found[0], found[1][:, :width])

        result = _accelerated_levenberg_marquardt(residuals, x0.copy(), evaluations, tolerance)
        if result is None:
            return None
        x, cost, used = result
        return problem.projected(x)[0], inputs, cost, used
    direction = 1.0 if inputs[-1] >= inputs[0] else -1.0

    def angles_of(y: numpy.ndarray) -> numpy.ndarray:
        return ordered_inputs(y[width], y[width + 1:], direction)

    def under_a_turn(y: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
        """y with its steps on just under a full turn if they make one (it slides along that wall), and the chain."""
        moved = y.copy()
        moved[width + 1:], chain = steps_under_a_turn(y[width + 1:])
        return moved, chain

    def untimed(y: numpy.ndarray):
        y, step_chain = under_a_turn(y)
        angles = angles_of(y)
        if abs(angles[-1] - angles[0]) >= 2 * math.pi:
            return None
        found = problem.evaluate(y[:width], angles, branches, project=True)
        if found is None:
            return None
        r, jac = found
        by_input = jac[:, width:]  # (2N, N): d r / d q_i, diagonal blocks
        chain = ordered_inputs_jacobian(y[width + 1:], direction)
        chain[:, 1:] = chain[:, 1:] @ step_chain
        return r, numpy.concatenate([jac[:, :width], by_input @ chain], axis=1)

    y0 = numpy.concatenate([x0, [inputs[0]], numpy.sqrt(numpy.abs(numpy.diff(inputs)))])
    result = _accelerated_levenberg_marquardt(untimed, y0, evaluations, tolerance)
    if result is None:
        return None
    y, cost, used = result
    y = under_a_turn(y)[0]
    return problem.projected(y[:width])[0], angles_of(y), cost, used


def _verify(problem: _Problem, x: numpy.ndarray, branches: Mapping[str, int], inputs: numpy.ndarray,
            evaluations: int) -> PathSynthesis:
    """The design checked with the linkage's own generated solver: errors at the targets, one branch between them."""
    if problem.newton:
        return _verify_newton(problem, x, branches, inputs, evaluations)
    design, placement = problem.split(x)
    linkage = problem.linkage
    reached = traced_points(linkage, problem.outputs, design, inputs, branches, placement)
    errors = numpy.hypot(*(reached - problem.targets).T)
    why = ""
    if not numpy.all(numpy.isfinite(errors)):
        why = "not assembled at every target"
    else:
        why = branch_break(linkage, design, branches, inputs)
        if not why:
            why = problem.feasible_motion(design, inputs, branches)
    if not why and not problem.allowed(x):
        why = "outside the bounds or the link ratio"
    stated, active = _constraint_report(problem, x, design, branches, inputs)
    return PathSynthesis(linkage.name, problem.outputs, design, placement, dict(branches),
                         tuple(map(float, inputs)), tuple(map(float, errors)),
                         float(numpy.max(errors) / problem.size) if not why else math.inf, not why, evaluations, why,
                         stated, active)


def _verify_newton(problem: _Problem, x: numpy.ndarray, start: Mapping[str, float], inputs: numpy.ndarray,
                   evaluations: int) -> PathSynthesis:
    """:func:`_verify` without a closed form: the linkage's own numeric solver continued along the targets.

    The assembly the refinement continued is found again at the design (Newton's method from
    the last one), then the linkage's :class:`~symlink.numeric.solver.NumericSolver` (not the
    Jacobian's code) follows it from the first target through every other, in order, with
    :data:`_PATH_SAMPLES` input values between consecutive targets: it stops at a point not
    assembled or at a dead centre, so a design it passes keeps one assembly along the targets.
    """
    design, placement = problem.split(x)
    linkage = problem.linkage
    if problem.assembly is None:
        problem.assembly = dict(start)
    _, _, ok = problem.local(design, inputs, start)
    assembly = dict(problem.assembly)
    errors = numpy.full(len(inputs), numpy.inf)
    why = ""
    if not numpy.all(ok):
        why = "not assembled at every target (Newton's method from the refined assembly)"
    else:
        steps = numpy.linspace(0.0, 1.0, _PATH_SAMPLES + 1)
        moves = inputs[:-1, None] + numpy.diff(inputs)[:, None] * steps[None, :]
        try:
            with numpy.errstate(all="ignore"):
                solved = _newton_solver(linkage)(guess=assembly, **_arguments(linkage, design, None),
                                                 **{linkage.inputs[0].name: moves.ravel()})
        except ValueError as error:
            why = f"the input cannot move along the targets on one assembly: {error}"
        else:
            local = numpy.stack([numpy.asarray(solved[name], dtype=float) for name in problem.outputs],
                                axis=-1).reshape(moves.shape + (2,))
            reached = _placed(numpy.concatenate([local[:, 0], local[-1:, -1]]), placement)
            errors = numpy.hypot(*(reached - problem.targets).T)
            assembly = {name: float(numpy.asarray(solved[name])[0]) for name in problem.unknown_names}
            problem.assembly = assembly
            why = problem.feasible_motion(design, inputs, assembly)
    if not why and not problem.allowed(x):
        why = "outside the bounds or the link ratio"
    stated, active = _constraint_report(problem, x, design, {}, inputs)
    return PathSynthesis(linkage.name, problem.outputs, design, placement, {}, tuple(map(float, inputs)),
                         tuple(map(float, errors)),
                         float(numpy.max(errors) / problem.size) if not why else math.inf, not why, evaluations, why,
                         stated, active, assembly)


def _constraint_report(problem: _Problem, x: numpy.ndarray, design: Mapping[str, float], branches: Mapping[str, int],
                       inputs: numpy.ndarray) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Every constraint the design was held to, with its value, and those at their limit (relative ``_ACTIVE``)."""
    stated: list[str] = []
    active: list[str] = []
    names = list(problem.free) + list(problem.frame)

    def near(value: float, limit: float) -> bool:
        return abs(value - limit) <= _ACTIVE * max(abs(limit), problem.size, 1e-300)

    for name, value, (low, high) in zip(names, x[:problem.width], problem.limits):
        if math.isfinite(low) or math.isfinite(high):
            stated.append(f"{low:.6g} <= {name} = {value:.9g} <= {high:.6g}")
            if near(value, low):
                active.append(f"{name} at its lower bound {low:.6g}")
            if near(value, high):
                active.append(f"{name} at its upper bound {high:.6g}")
    if math.isfinite(problem.max_link_ratio):
        ratio = problem.link_ratio(x)
        stated.append(f"link ratio {ratio:.6g} <= {problem.max_link_ratio:.6g}")
        if abs(ratio - problem.max_link_ratio) <= _ACTIVE * problem.max_link_ratio:
            active.append(f"link ratio at {problem.max_link_ratio:.6g}")
    if problem.transmission is not None and not problem.newton:
        least = problem.transmission[1]
        for loop, held in problem.held_transmissions(design, inputs, branches).items():
            over = held_over_text(held.over, held.low, held.high, problem._input_is_angle)
            stated.append(f"transmission angle at {loop} >= {math.degrees(least):.6g} deg over {over}: "
                          f"{math.degrees(held.worst):.6g} deg at input {problem._show_input(held.at)}")
            if abs(held.worst - least) <= 1e-6:
                active.append(f"transmission angle at {loop} at {math.degrees(least):.6g} deg")
    if problem.full_rotation:
        stated.append("the input turns fully")
    stated.append("targets in order on one assembly branch, no toggle between them")
    return tuple(stated), tuple(active)


def synthesize_path(linkage: Linkage, point: str | Sequence[str], targets: ArrayLike,
                    free: Mapping[str, tuple[float, float]], *, values: Mapping[str, float] | None = None,
                    frame: Sequence[str] = FRAME_NAMES, placement: Mapping[str, float] | None = None,
                    frame_bounds: Mapping[str, tuple[float, float]] | None = None, timed: ArrayLike | None = None,
                    branches: Mapping[str, int] | None = None, starts: int = 16,
                    seed: int | None = 0, evaluations: int = 2000, tolerance: float = 1e-15,
                    max_link_ratio: float | None = None, min_transmission: float = 0.0,
                    full_rotation: bool = False, direction: int | None = None,
                    guess: Mapping[str, float] | None = None) -> PathSynthesis:
    """A design of ``linkage`` whose ``point`` passes through ``targets`` (rows x, y), verified.

    ``point`` is a point name (``"C"``) or two output names (``("P_x", "P_y")``).  ``free`` maps
    each parameter that may change to its bounds ``(low, high)``; ``values`` gives every other
    parameter (and, if it gives the free ones too, that design is the first start).  ``frame``
    names the free parts of the placement (:data:`FRAME_NAMES`; ``()`` keeps the linkage where
    it is), ``placement`` the values of the fixed ones (default no shift, no turn, scale 1),
    ``frame_bounds`` optional bounds ``(low, high)`` of free ones (the pivot inside a box).
    ``timed`` is the input's value at each target, or None to find them too (reached in order).
    ``branches`` fixes branch signs by name (default: tried both ways across the starts).
    The ``starts`` closest feasible designs are refined with at most ``evaluations`` residual
    evaluations each; the search stops at the first verified design below 1e-10 (error over the
    targets' size).  Returns the best verified design, or the closest one with ``assembled``
    False and its reason; ``ValueError`` for bad input or when no sampled design is feasible.

    Constraints a designer states, besides the bounds (link lengths, and with ``frame_bounds``
    the pivot inside a box) and what every design meets (the targets reached in order on one
    assembly branch, no toggle between them): ``max_link_ratio`` bounds the longest link over
    the shortest (positive length parameters, free and fixed; None: no bound);
    ``min_transmission`` (radians) bounds the transmission angle of every two-angle loop from 0 and
    from pi (:func:`symlink.analysis.transmission.transmission_arrays`) over the motion the design
    runs, in every trial: the full turn where its input turns fully, else the range of the inputs at
    the targets (sampled at one a degree, the least refined:
    :func:`symlink.analysis.transmission.least_over_inputs`; ``constraints`` says over what);
    ``full_rotation`` asks that the input turn a whole turn without leaving the assembly or
    passing a toggle; ``direction`` (without timing: +1 or -1) that the input grow (+1) or shrink
    from target to target (default: either).  Infeasible trials are refused, never penalised; the design reports each
    constraint with its value (``constraints``) and those at their limit (``active``).
    When every length is free (and the scale is not), half the sampled starts are
    shape-normalised (:func:`_shaped_design`) and scaled to the targets by the placement fit.

    A linkage without a closed form (solved by Newton's method) has no branches; ``guess``
    gives its unknowns near an assembly at the first target's input for the design in
    ``values`` (default: one found by :func:`find_assembly`), and the design found reports its
    assembly as ``assembly``.  There ``full_rotation`` asks that Newton's method continue that
    assembly a whole turn of the input from the first target (it stops where the assembly ends
    or at a dead centre), and ``min_transmission`` is measured on the assembly continued along
    the targets; a linkage none of whose loops has two unknown angles (the Stephenson II) has
    no transmission angle in symlink's sense, and ``min_transmission`` there is a ``ValueError``.

    Parameters
    ----------
    linkage : Linkage
        Any linkage with one input.
    point : str or (str, str)
        A point's name (``"C"``) or two output names (``("P_x", "P_y")``).
    targets : array_like
        The target points, rows (x, y).
    free : mapping of str to (float, float)
        Each parameter that may change, and its bounds.
    values : mapping of str to float, optional
        Every other parameter (and free ones too: that design is the first start).
    frame : sequence of str, optional
        The free parts of the placement, of ``x0, y0, angle, scale`` (default all; ``()`` keeps it fixed).
    placement : mapping of str to float, optional
        The values of the fixed parts of the placement.
    frame_bounds : mapping of str to (float, float), optional
        Bounds of free parts of the placement.
    timed : array_like, optional
        The input's value at each target, or None (default) to find them too.
    branches : mapping of str to int, optional
        Branch signs to keep (default: tried both ways).
    starts : int, optional
        How many of the closest sampled designs are refined (default 16).
    seed : int or None, optional
        The sampling's seed (default 0).
    evaluations : int, optional
        Residual evaluations a refinement may take (default 2000).
    tolerance : float, optional
        The refinement's step tolerance (default 1e-15).
    max_link_ratio : float, optional
        A bound on the longest link over the shortest (default none).
    min_transmission : float, optional
        A bound (radians) on every two-angle loop's transmission angle from 0 and pi over the motion the design
        runs (the full turn where its input turns fully, else the range of the inputs at the targets).
    full_rotation : bool, optional
        Ask that the input turn fully without a toggle.
    direction : {1, -1}, optional
        Without timing: the input grows (+1) or shrinks from target to target (default either).
    guess : mapping of str to float, optional
        For a linkage without a closed form: its unknowns near an assembly at the first target.

    Returns
    -------
    PathSynthesis
        The best verified design (``design``, ``placement``, ``inputs``, ``error``, ``constraints``), or the closest
        with ``assembled`` False and its reason.

    Raises
    ------
    ValueError
        For bad input, or when no sampled design is feasible.

    See Also
    --------
    synthesize_fourbar_path : the four-bar's own route, from an atlas of four-bars.

    Examples
    --------
    >>> import numpy, symlink
    >>> linkage = symlink.slider_crank()
    >>> inputs = numpy.linspace(0.0, 2.5, 6)
    >>> targets = symlink.traced_points(linkage, "B", {"a": 1.3, "b": 4.1, "offset": 0.7}, inputs)  # a circle, radius a
    >>> found = symlink.synthesize_path(linkage, "B", targets, {"a": (0.5, 2.0)}, values={"b": 4.1, "offset": 0.7},
    ...                                 frame=(), timed=inputs)
    >>> found.error < 1e-10, round(found.design["a"], 9)
    (True, 1.3)
    """
    if len(linkage.inputs) != 1:
        raise ValueError(f"path synthesis drives one input; {linkage.name} has {len(linkage.inputs)}")
    newton = not linkage.has_closed_form
    if newton and min_transmission > 0 and not transmission_coordinates(linkage):
        raise ValueError(f"min_transmission cannot be held on {linkage.name}: no loop of it has exactly two unknown "
                         "angles, the joint where symlink measures a transmission angle")
    if guess is not None and (not newton or set(guess) != {q.name for q in linkage.unknowns}
                              or not all(math.isfinite(float(v)) for v in guess.values())):
        raise ValueError(f"guess gives the unknowns of a linkage without a closed form near an assembly at the "
                         f"first target ({', '.join(q.name for q in linkage.unknowns)}), finite numbers; "
                         f"got {guess!r}")
    names = _point_outputs(linkage, point)
    points = _targets(targets)
    size = _size(points)
    if not size > 0:
        raise ValueError("the targets are all the same point")
    bounds, fixed = free_bounds(linkage, free, values)
    given = {k: float(v) for k, v in (values or {}).items()}
    unknown_frame = [name for name in frame if name not in FRAME_NAMES]
    if unknown_frame or len(set(frame)) != len(frame):
        raise ValueError(f"frame names the free parts of the placement among {', '.join(FRAME_NAMES)}, "
                         f"each once; got {tuple(frame)!r}")
    fixed_placement = {k: float(v) for k, v in (placement or {}).items()}
    if set(fixed_placement) - set(FRAME_NAMES) or not fixed_placement.get("scale", 1.0) > 0:
        raise ValueError(f"placement gives values of {', '.join(FRAME_NAMES)} (scale positive), got {placement!r}")
    inputs = None if timed is None else numpy.asarray(timed, dtype=float)
    if inputs is not None and (inputs.shape != (len(points),) or not numpy.all(numpy.isfinite(inputs))):
        raise ValueError(f"{len(points)} targets need {len(points)} finite input values, got shape {inputs.shape}")
    if inputs is None and len(points) < 3:
        raise ValueError("path synthesis without timing needs at least three targets")
    check_distinct_targets(points, inputs)
    check_branches(linkage, branches)
    check_starts(starts, evaluations, (_NEWTON_TRACED if newton else _SAMPLED) + 1)  # the user's design besides
    for name, bound in (frame_bounds or {}).items():
        if name not in frame or not (float(bound[0]) < float(bound[1])):
            raise ValueError(f"frame_bounds bounds free parts of the placement ({', '.join(frame) or 'none'}) "
                             f"with low < high; got {name!r}: {bound!r}")
    ratio = math.inf if max_link_ratio is None else float(max_link_ratio)
    if not ratio >= 1:
        raise ValueError(f"max_link_ratio must be at least 1 (or None), got {max_link_ratio!r}")
    if not 0 <= min_transmission < math.pi / 2:
        raise ValueError(f"min_transmission must lie in [0, pi/2) radians, got {min_transmission!r}")
    if direction not in (None, 1, -1) or (direction is not None and inputs is not None):
        raise ValueError(f"direction is +1, -1 or None, for targets without timing; got {direction!r}")
    problem = _Problem(linkage, names, points, bounds, fixed,
                       frame, fixed_placement, inputs, frame_bounds, ratio, float(min_transmission),
                       bool(full_rotation))
    problem.direction = direction
    rng = numpy.random.default_rng(seed)
    untimed = inputs is None
    if untimed:
        found = _untimed_starts(problem, rng, _SCREENED * starts, given, branches, guess)
    elif newton:
        found = _newton_timed_starts(problem, rng, starts, given, guess)
    else:
        found = _timed_starts(problem, rng, starts, given, branches)
    held = ([f"min_transmission={min_transmission:.6g} rad (held over the motion each design runs)"]
            if min_transmission > 0 else []) + (["full_rotation"] if full_rotation else [])
    if not found:
        if held and not newton:
            raise ValueError(f"no sampled design of {linkage.name} within the bounds is assembled along the targets "
                             f"and meets {' and '.join(held)}; widen the bounds or ease the constraints")
        raise ValueError(f"no design of {linkage.name} within the bounds is assembled along the targets; widen the "
                         "bounds or change the fixed values")
    best: PathSynthesis | None = None
    spent = 0

    def verified(x, signs, angles_found) -> bool:
        """Verify a refined design, keep the best: True when it reaches the targets (1e-10 of their size)."""
        nonlocal best
        design = _verify(problem, x, signs, angles_found, spent)
        if best is None or (design.assembled, -design.error) > (best.assembled, -best.error):
            best = design
        return best.assembled and best.error < 1e-10

    if untimed and all(name in given for name in problem.free) and found:
        # the user's own design (the first start) is refined in full first, as with timing
        _, x0, signs, angles = found[0]
        refined = _refine(problem, x0, signs, numpy.asarray(angles, dtype=float), evaluations, tolerance)
        found = found[1:]
        if refined is not None:
            x, angles_found, _, used = refined
            spent += used
            if verified(x, signs, angles_found):
                found = []
    if untimed:
        # Successive halving (as symlink.synthesis.path does): every start a short refinement, then the closer half
        # twice as long from where it stopped, and so on; most untimed starts lead nowhere, a few dozen
        # evaluations tell which.
        alive = [(math.inf, x0, signs, numpy.asarray(angles, dtype=float), False) for _, x0, signs, angles in found]
        budget, closest = _SCREEN_EVALUATIONS, math.inf
        while alive:
            results = []
            for cost, x, signs, angles, stopped in alive:
                if not stopped:
                    origin = (x, signs, angles)
                    refined = _refine(problem, x, signs, angles, min(budget, evaluations), tolerance)
                    if refined is None:
                        continue
                    x, angles, cost, used = refined
                    spent += used
                    if problem.newton and problem.assembly is not None:
                        signs = dict(problem.assembly)  # the assembly continued so far: the next round's start
                    stopped = used < min(budget, evaluations)
                    if problem.newton and not stopped and cost < _PROMISING:
                        # Without a closed form an evaluation is a Newton continuation, dear: a start already this
                        # close is refined to the end now, not after a round of every other start.  Again from
                        # where this round began, in one run: a refinement restarted where one stopped begins
                        # with the damping reset, and near such a point (an ill-conditioned valley, residuals
                        # with the continuation's rounding) its steps' gains are below that rounding, so it stops.
                        allowed = min(evaluations, min(budget, evaluations) + _PROMOTED_EVALUATIONS)
                        further = _refine(problem, *origin, allowed, tolerance)
                        if further is not None:
                            spent += further[3]
                        if further is not None and further[2] < cost:
                            x, angles, cost, used = further
                            stopped = used < allowed
                            if problem.assembly is not None:
                                signs = dict(problem.assembly)
                    if cost < closest:
                        closest = cost
                        if verified(x, signs, angles):
                            alive = []
                            break
                results.append((cost, x, signs, angles, stopped))
            else:
                results.sort(key=lambda item: item[0])
                if len(results) <= 1 or budget >= evaluations:
                    break
                alive = results[:max(1, len(results) // 2)]
                budget *= 2
                continue
            break
    else:
        for _, x0, signs, angles in found:
            refined = _refine(problem, x0, signs, numpy.asarray(angles, dtype=float), evaluations, tolerance)
            if refined is None:
                continue
            x, angles_found, _, used = refined
            spent += used
            if verified(x, signs, angles_found):
                break
    if best is None:
        stated = ([f"max_link_ratio={max_link_ratio:g}"] if max_link_ratio is not None else []) + held + (
            [f"direction={direction:+d}"] if direction is not None else [])
        raise ValueError("no start could be refined: every trial left the bounds" + (
            " or broke " + ", ".join(stated) if stated else "") + " (widen the bounds, free more parameters"
            + (" or ease the constraints)" if stated else ")"))
    return best if best.evaluations == spent else PathSynthesis(**{**best.__dict__, "evaluations": spent})
