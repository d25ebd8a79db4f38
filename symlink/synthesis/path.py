"""Path generation: a four-bar whose coupler point passes through given points, with or without timing.

The design space is the four-bar's whole: crank pivot ``(x0, y0)``, frame angle (the
direction of the ground line from the crank pivot to the rocker pivot), crank a, coupler
b, rocker c, ground d, and the coupler point ``(u, v)`` in the coupler's frame (u along
B->C, v to its left), so that in the four-bar's own frame (:func:`symlink.mechanism.catalog.fourbar`)
``P = a e^{i theta} + (u + i v) e^{i beta}`` and in the plane ``(x0, y0) + e^{i frame} P``.

* With timing (:func:`synthesize_path` with ``theta``) the crank angles of the points are
  given (measured from the ground line, as everywhere in symlink); the unknowns are the
  nine dimensions.
* Without, the crank angles are unknowns too, written as the first angle and squared
  steps to the next ones, so the points are reached in order, turning one way.

With timing each start is refined by ``scipy.optimize.least_squares`` (Levenberg-Marquardt;
SciPy is the ``synthesis`` extra) with the exact Jacobian: the design sensitivities of the
placed four-bar's coupler point (:func:`path_fourbar`), generated and cached like every solver
and called through :class:`symlink.numeric.design_jacobian.DesignJacobian` (:func:`path_jacobian`).
Without timing ten points barely fix the four-bar (twenty residuals, nineteen unknowns) and
leave long curved valleys, along which plain Levenberg-Marquardt crawls: there the same
Jacobian drives Levenberg-Marquardt with geodesic acceleration
(:func:`_accelerated_levenberg_marquardt`).

Starts come from a coarse atlas of random four-bars: the coupler points of each, at the
given crank angles (with timing) or at crank angles matched to the points by arc length
(without), are fitted to the targets by the best rotation, scale and shift (a complex
least-squares fit), and the best fits are refined.  Without timing, four times as many fits
are refined by successive halving (a short refinement each, then the closer half twice as
long, and so on), each new closest design verified at once; if none reaches the targets,
new atlases give batches twice as wide, and a design that stops short gets one long second
refinement (at most two a call).

Constraints are enforced, not only penalised.  A trial design that breaks one (cannot be
assembled at a point, passes a toggle, breaks the Grashof class asked for, the link-ratio
bound or the minimum transmission angle over the motion it runs) gets a residual far above any feasible one (with
timing) or is refused as a trial step (without), so the solvers never accept it, and every
start is feasible.  The walls that are linear in the dimensions (``bounds``, and a Grashof
class with its shortest link named: ``s + l <= p + q``) are slid along instead; with timing, a
design that ends on one is refined on those walls exactly by an active set
(:func:`_active_set_levenberg_marquardt`), which lets go of a wall the cost falls away from, so
an optimum on a corner of walls (a change-point linkage with a link at its bound) is reached,
not approached.  Each design is then verified afresh with symlink's generated four-bar
solver, independently of the Jacobian's code: every point is reached on the one branch, and
between consecutive points the crank moves without leaving the assembly or passing a toggle
(:func:`check_design`).

>>> design = fourbar_design((0.0, 0.0), 0.0, (1.0, 3.0, 2.5, 3.2), (1.5, 0.8), branch=1)
>>> targets = design.points(numpy.linspace(0.0, 5.0, 6))
>>> found = synthesize_path(targets, theta=numpy.linspace(0.0, 5.0, 6))[0]
>>> found.error < 1e-8
True
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Mapping, Sequence

import numpy
import sympy as sp
from numpy.typing import ArrayLike

from ..analysis import grashof
from ..analysis.transmission import fourbar_held_transmission, fourbar_transmission_solver, held_over_text
from ..mechanism.catalog import fourbar
from ..numeric.design_jacobian import DesignJacobian
from ..common.display import record_html
from ..symbolic.linkage import Linkage
from ..symbolic.loops import Loop
from ..numeric.solver import check_lengths, settled, shared_solver
from ..symbolic.vectors import Vector, coordinates, lengths as length_symbols

__all__ = ["check_distinct_targets", "PathDesign", "fourbar_design", "synthesize_path", "path_fourbar", "path_jacobian", "check_design",
           "DESIGN_NAMES", "GRASHOF_CHOICES", "path_error"]

#: The nine dimensions of a path-generating four-bar, in the order of the design vector.
DESIGN_NAMES = ("x0", "y0", "frame", "a", "b", "c", "d", "u", "v")
#: Grashof classes that can be asked for (None: any).
GRASHOF_CHOICES = ("crank-rocker", "double-crank", "rocker-crank", "double-rocker", "triple-rocker", "any",
                   "crank-turns")

_INFEASIBLE = 1e6        # residual of a design that breaks a constraint (the solver never accepts it)
_PATH_SAMPLES = 24       # crank angles checked between consecutive points for assembly and toggles
_ATLAS = 1500            # random four-bars in the coarse atlas
_CURVE_SAMPLES = 96      # points of each atlas curve (without timing)
_CURVE_ATLAS = 500       # four-bars in each atlas without timing
_ARC_BINS = 512          # arc-length fractions tabulated for each atlas curve
_PROJECTED = 160         # the best arc-length fits kept from all phases and spans
_SPANS = (0.95, 0.8, 0.6, 0.4)  # fractions of an atlas curve's arc length the targets are matched along ...
_PHASES = 16             # ... from this many starting points spread along it
_MAX_EVALUATIONS = 300   # residual evaluations of one refinement with timing
_SCREENED = 4            # untimed: this many times ``starts`` atlas fits are refined by successive halving ...
_SCREEN_EVALUATIONS = 40  # ... this many evaluations each in the first round, twice as many each round after ...
_LAST_ROUND = 1280       # ... up to this many
_ATTEMPTS = 4            # batches of starts (a new atlas each) before giving up ...
_WIDER = 2               # ... the batches after the first this many times as many
_POLISHED = 2            # designs of a call (in all) that get a long second refinement ...
_POLISH_BELOW = 1e-3     # ... if their error is below this
_POLISH_EVALUATIONS = 6000
_FULL_TURN = (2 * math.pi) * (1 - 1e-12)  # untimed: the most the crank turns from the first point to the last
_GRASHOF_MARGIN = 1e-11   # a timed trial past a Grashof boundary is moved this far (relative to the links' sum) inside
_ACTIVE = 1e-9           # a wall is active where its slack is below this, relative to the size of its terms
_RELEASES = 8            # walls a refinement on the walls may let go (the cost falls inward) before it stops
#: The Grashof classes that are convex sets of lengths (the shortest link named), as the index of that link.
_SHORTEST_LINK = {"crank-rocker": 0, "double-rocker": 1, "rocker-crank": 2, "double-crank": 3}
_PHASE_STARTS = 24       # timed with a free phase: offsets over a turn at which each atlas four-bar is fitted


def check_starts(starts: int, evaluations: int, pool: int, what: str = "designs sampled for the starts",
                 name: str = "starts") -> None:
    """``ValueError`` (one line) unless ``starts`` and ``evaluations`` are at least 1 and ``starts`` at most
    ``pool``: the designs a synthesis samples for its starts, of which it can refine no more (``starts=10**9`` is a
    mistake, not a long run: it would refine every one of the pool, each up to ``evaluations`` evaluations).
    ``name``: the argument's name in the message.

    >>> check_starts(10**9, 2000, 1500)
    Traceback (most recent call last):
    ValueError: starts=1,000,000,000 is more than the 1,500 designs sampled for the starts (at most 1,500 refinements of up to 2,000 evaluations each); give starts=1,500 or fewer
    """
    if starts < 1 or evaluations < 1:
        raise ValueError(f"{name} and evaluations must be at least 1")
    if starts > pool:
        raise ValueError(f"{name}={starts:,} is more than the {pool:,} {what} (at most {pool:,} refinements of up "
                         f"to {evaluations:,} evaluations each); give {name}={pool:,} or fewer")


def ordered_inputs(first: float, steps: numpy.ndarray, direction: float) -> numpy.ndarray:
    """Input values kept in order through a refinement: the first, then steps of ``s_k^2`` in ``direction`` (+-1).

    Untimed fits refine ``(first, s_1 ... s_{N-1})`` instead of the inputs themselves, so that no
    trial puts the targets out of order (:func:`ordered_inputs_jacobian` is its derivative).

    >>> ordered_inputs(0.5, numpy.array([1.0, 2.0]), -1.0)
    array([ 0.5, -0.5, -4.5])
    """
    return first + direction * numpy.concatenate([[0.0], numpy.cumsum(steps ** 2)])


def ordered_inputs_jacobian(steps: numpy.ndarray, direction: float) -> numpy.ndarray:
    """d inputs / d (first, s_1 ... s_{N-1}) of :func:`ordered_inputs`: ones, then ``2 direction s_k`` below the diagonal.

    >>> ordered_inputs_jacobian(numpy.array([1.0, 2.0]), -1.0)
    array([[ 1.,  0.,  0.],
           [ 1., -2.,  0.],
           [ 1., -2., -4.]])
    """
    return numpy.tril(numpy.tile(numpy.concatenate([[1.0], 2 * direction * steps]), (len(steps) + 1, 1)))


def steps_under_a_turn(steps: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
    """``steps`` scaled onto just under a full turn if their squares make one, and d(scaled)/d(steps).

    A trial past a full turn is evaluated there, so that a refinement slides along that wall (a
    closed curve through its first target again) instead of stopping at it.
    """
    turn = float(steps @ steps)
    if turn < _FULL_TURN:
        return steps, numpy.eye(len(steps))
    length = math.sqrt(turn)
    unit = steps / length
    return unit * math.sqrt(_FULL_TURN), math.sqrt(_FULL_TURN) / length * (numpy.eye(len(steps))
                                                                           - numpy.outer(unit, unit))


@dataclass(frozen=True)
class PathDesign:
    """A path-generating four-bar: dimensions, branch, the crank angle at each target point, and its errors.

    Lengths in the targets' unit, angles in radians.  ``errors`` are the distances from each
    target to the coupler point at its crank angle; ``error`` is the largest over the size of
    the targets (the diagonal of their bounding box).

    Parameters
    ----------
    crank_pivot : (float, float)
        The crank's fixed pivot.
    frame : float
        The ground line's angle (radians).
    crank, coupler, rocker, ground : float
        The link lengths.
    coupler_point : (float, float)
        The coupler point (u, v) in the coupler's frame.
    branch : int
        The assembly, +1 or -1.
    theta : tuple of float, optional
        The crank angle at each target.
    errors : tuple of float, optional
        The distance from each target to the coupler point.
    error : float, optional
        The largest error over the targets' size.
    grashof : str, optional
        Its Grashof class.
    worst_transmission : float, optional
        Its worst transmission angle (``min(mu, pi - mu)``) over the motion it runs.
    transmission_over : str, optional
        Over what that is: ``the full turn`` (a crank that turns fully) or ``input 12-87.5 deg`` (it rocks
        between the crank angles of its first and last target).
    evaluations : int, optional
        The residual evaluations its refinement took.

    Examples
    --------
    >>> import numpy, symlink
    >>> design = symlink.fourbar_design((0.0, 0.0), 0.0, (1.0, 3.0, 2.5, 3.2), (1.5, 0.8), branch=1)
    >>> theta = numpy.linspace(0.0, 5.0, 6)
    >>> targets = design.points(theta)  # its own coupler curve
    >>> [round(float(x), 6) for x in targets[0]]  # B = (1, 0), cos(beta) = 1.725 / 3: B + (u, v) turned by beta
    [1.207977, 1.68723]
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    crank_pivot: tuple[float, float]
    frame: float
    crank: float
    coupler: float
    rocker: float
    ground: float
    coupler_point: tuple[float, float]
    branch: int
    theta: tuple[float, ...] = ()
    errors: tuple[float, ...] = ()
    error: float = math.nan
    grashof: str = ""
    worst_transmission: float = math.nan
    evaluations: int = 0
    transmission_over: str = ""

    @property
    def lengths(self) -> tuple[float, float, float, float]:
        return self.crank, self.coupler, self.rocker, self.ground

    @property
    def rocker_pivot(self) -> tuple[float, float]:
        return (self.crank_pivot[0] + self.ground * math.cos(self.frame),
                self.crank_pivot[1] + self.ground * math.sin(self.frame))

    @property
    def coupler_point_polar(self) -> tuple[float, float]:
        """The coupler point as (distance from B, angle from B->C): the form of ``symlink curve --coupler-point``."""
        u, v = self.coupler_point
        return math.hypot(u, v), math.atan2(v, u)

    @property
    def vector(self) -> numpy.ndarray:
        """The design vector in :data:`DESIGN_NAMES` order."""
        return numpy.array([*self.crank_pivot, self.frame, *self.lengths, *self.coupler_point])

    def joints(self, theta: ArrayLike) -> dict[str, numpy.ndarray]:
        """Joints A, B, C, D and the coupler point P in the plane (complex numbers) at crank angles ``theta``.

        Solved by the generated four-bar solver (not the Jacobian's code); NaN where it cannot close.
        """
        angles = numpy.asarray(theta, dtype=float)
        a, b, c, d = self.lengths
        solved = settled(shared_solver(fourbar, ("B_x", "B_y", "C_x", "C_y", "coupler")))(
            theta=angles, a=a, b=b, c=c, d=d, branch=self.branch)
        origin, turn = complex(*self.crank_pivot), complex(math.cos(self.frame), math.sin(self.frame))
        ok = numpy.asarray(solved["assembled"])
        B = numpy.where(ok, solved["B_x"] + 1j * solved["B_y"], numpy.nan)
        C = numpy.where(ok, solved["C_x"] + 1j * solved["C_y"], numpy.nan)
        P = B + complex(*self.coupler_point) * numpy.exp(1j * numpy.asarray(solved["coupler"]))
        place = lambda z: origin + turn * z  # noqa: E731
        return {"A": numpy.broadcast_to(origin, angles.shape), "B": place(B), "C": place(C),
                "D": numpy.broadcast_to(place(d), angles.shape), "P": place(P)}

    def points(self, theta: ArrayLike) -> numpy.ndarray:
        """The coupler point at crank angles ``theta`` as rows (x, y)."""
        P = self.joints(theta)["P"]
        return numpy.stack([P.real, P.imag], axis=-1)


def fourbar_design(crank_pivot: tuple[float, float], frame: float, lengths: Sequence[float],
                   coupler_point: tuple[float, float], branch: int = 1) -> PathDesign:
    """A :class:`PathDesign` from its dimensions (no errors yet), checked: positive lengths, finite numbers.

    Parameters
    ----------
    crank_pivot : (float, float)
        The crank's fixed pivot.
    frame : float
        The ground line's angle (radians).
    lengths : sequence of float
        Crank, coupler, rocker and ground lengths.
    coupler_point : (float, float)
        The coupler point (u, v) in the coupler's frame.
    branch : int, optional
        The assembly, +1 (default) or -1.

    Returns
    -------
    PathDesign
        The design, without errors.

    Raises
    ------
    ValueError
        For a length that is not positive or a number that is not finite.

    Examples
    --------
    >>> import symlink
    >>> design = symlink.fourbar_design((0, 0), 0, (1, 3, 2.5, 3.2), (1.5, 0.8))
    >>> design.rocker_pivot  # the ground d along the frame from the crank pivot
    (3.2, 0.0)
    """
    a, b, c, d = (float(x) for x in lengths)
    check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    numbers = [*crank_pivot, frame, *coupler_point]
    if not all(math.isfinite(float(x)) for x in numbers):
        raise ValueError("the crank pivot, frame angle and coupler point must be finite numbers")
    if branch not in (1, -1):
        raise ValueError(f"branch must be +1 or -1, got {branch}")
    return PathDesign((float(crank_pivot[0]), float(crank_pivot[1])), float(frame), a, b, c, d,
                      (float(coupler_point[0]), float(coupler_point[1])), int(branch))


# --- the exact Jacobian -------------------------------------------------------------------------

#: The path four-bar's parameters, in the order of the Jacobian's columns: the crank phase, then the dimensions.
_PARAMETERS = ("crank_phase",) + DESIGN_NAMES


def path_fourbar() -> Linkage:
    """The four-bar of :func:`symlink.mechanism.catalog.fourbar` placed in the plane, with its coupler point ``P``.

    The loop is the catalog four-bar's, in its own frame (crank pivot at the origin, ground
    along x); the extras ``P_x`` and ``P_y`` place the coupler point ``(u, v)`` (coupler frame)
    by the crank pivot ``(x0, y0)`` and the frame angle.  The crank stands at ``theta +
    crank_phase``: the sensitivities are derivatives by parameters, and held at zero the
    phase's is the derivative by the crank angle, which synthesis without timing needs.

    Returns
    -------
    Linkage
        The placed four-bar, parameters ``crank_phase, x0, y0, frame, a, b, c, d, u, v``, extras ``P_x``, ``P_y``.

    Examples
    --------
    >>> import symlink
    >>> [p.name for p in symlink.path_fourbar().parameters]
    ['crank_phase', 'x0', 'y0', 'frame', 'a', 'b', 'c', 'd', 'u', 'v']
    """
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, d = length_symbols("a b c d")
    phase, x0, y0, frame, u, v = sp.symbols("crank_phase x0 y0 frame u v", real=True)
    AB, BC = Vector(a, theta + phase, "AB"), Vector(b, beta, "BC")
    DC, AD = Vector(c, phi, "DC"), Vector(d, 0, "AD")
    local = AB.as_sum() + Vector(u, beta) + Vector(v, beta + sp.pi / 2)
    return Linkage("path_fourbar", [Loop(AD + DC - BC - AB, name="ABCD")], inputs=[theta], unknowns=[beta, phi],
                   parameters=[phase, x0, y0, frame, a, b, c, d, u, v],
                   roles={"crank": theta, "coupler": beta, "rocker": phi},
                   extras={"P_x": x0 + sp.cos(frame) * local.x - sp.sin(frame) * local.y,
                           "P_y": y0 + sp.sin(frame) * local.x + sp.cos(frame) * local.y})


@lru_cache(maxsize=None)
def path_jacobian() -> DesignJacobian:
    """The coupler point of :func:`path_fourbar` and its Jacobian by the crank angle and the nine dimensions.

    A :class:`symlink.numeric.design_jacobian.DesignJacobian` (generated once, then loaded from the
    scene cache); synthesis calls its unchecked :meth:`~symlink.numeric.design_jacobian.DesignJacobian.arrays`.

    >>> values, slopes, assembled = path_jacobian().arrays(0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 3.0, 2.5, 3.2, 1.0, 0.0,
    ...                                                  1.0)
    >>> round(float(values[0]), 9), float(slopes[0, 1])  # P_x = 1 + cos(beta), cos(beta) = 1.725 / 3; dP_x/dx0
    (1.575, 1.0)
    """
    return DesignJacobian(path_fourbar(), ["P_x", "P_y"], list(_PARAMETERS))


def _evaluate(design: numpy.ndarray, theta: numpy.ndarray, branch: int) -> tuple[numpy.ndarray, numpy.ndarray,
                                                                                 numpy.ndarray]:
    """Coupler points (N, 2), Jacobian (N, 2, 10: theta then the dimensions) and a feasibility mask (N).

    Feasible: assembled and away from a toggle (where the derivatives divide by zero).
    """
    values, slopes, assembled = path_jacobian().arrays(theta, 0.0, *design, float(branch))
    points = values.T
    jacobian = numpy.moveaxis(slopes, -1, 0)
    ok = assembled & numpy.all(numpy.isfinite(slopes), axis=(0, 1)) & numpy.all(numpy.isfinite(values), axis=0)
    return points, jacobian, ok


# --- constraints --------------------------------------------------------------------------------

@dataclass(frozen=True)
class _Constraints:
    grashof: str = "any"
    max_link_ratio: float = math.inf
    min_transmission: float = 0.0
    box: tuple[tuple[int, float, float], ...] = ()  # (index in the design vector, low, high)

    def allow_design(self, vector: numpy.ndarray, theta: ArrayLike) -> bool:
        """:meth:`allow` for the design vector's lengths, and every bounded dimension within its bounds."""
        return self.allow(vector[3:7], theta) and all(low <= vector[k] <= high for k, low, high in self.box)

    def allow(self, lengths: Sequence[float] | numpy.ndarray, theta: ArrayLike) -> bool:
        """Whether lengths, Grashof class, link ratio and transmission angle are within the constraints, the
        transmission angle over the motion the design runs with its crank at ``theta`` at the targets (the full turn
        for a crank that turns fully, else the range ``theta`` spans: :func:`~symlink.analysis.transmission.
        fourbar_held_transmission`)."""
        a, b, c, d = lengths
        if min(lengths) <= 0 or not all(math.isfinite(x) for x in lengths):
            return False
        if max(lengths) > self.max_link_ratio * min(lengths):
            return False
        if self.grashof != "any":
            name = grashof(a, b, c, d).name
            wanted = ("crank-rocker", "double-crank") if self.grashof == "crank-turns" else (self.grashof,)
            if name not in wanted:
                return False
        if self.min_transmission > 0:
            if not fourbar_held_transmission(a, b, c, d, theta).worst >= self.min_transmission:
                return False
        return True


def _reached_in_order(design: PathDesign, crank_angles: ArrayLike) -> str | None:
    """Why the crank cannot move from point to point on one branch (None if it can)."""
    theta = numpy.asarray(crank_angles, dtype=float)
    a, b, c, d = design.lengths
    solver = settled(shared_solver(fourbar, ("singular",)))
    steps = numpy.linspace(0.0, 1.0, _PATH_SAMPLES + 1)
    moves = theta[:-1, None] + (theta[1:] - theta[:-1])[:, None] * steps[None, :] if len(theta) > 1 \
        else theta[:, None]
    solved = solver(theta=moves, a=a, b=b, c=c, d=d, branch=design.branch)
    ok = numpy.asarray(solved["assembled"]) & ~numpy.asarray(solved["singular"])
    if not numpy.all(ok):
        where = numpy.argwhere(~ok)[0]
        return (f"the crank cannot move from point {where[0] + 1} to point {where[0] + 2} on branch "
                f"{design.branch:+d} (no assembly or a toggle at {math.degrees(moves[tuple(where)]):.6g} deg)")
    return None


def check_design(design: PathDesign, targets: ArrayLike, crank_angles: ArrayLike,
                 grashof_class: str = "any", max_link_ratio: float = math.inf,
                 min_transmission: float = 0.0, bounds: Mapping[str, tuple[float, float]] | None = None) -> PathDesign:
    """Verify a design with symlink's four-bar solver and return it with its errors; ``ValueError`` if it fails.

    Every target is reached on the design's branch, in order (the crank moves from each
    point's angle to the next without leaving the assembly or passing a toggle), the turn
    from first to last point is less than a full turn, and the constraints hold.

    Parameters
    ----------
    design : PathDesign
        The design.
    targets : array_like
        The target points, rows (x, y).
    crank_angles : array_like
        The crank angle at each target.
    grashof_class : str, optional
        The Grashof class required (default ``"any"``).
    max_link_ratio : float, optional
        A bound on the longest link over the shortest (default none).
    min_transmission : float, optional
        A bound (radians) on the worst transmission angle over the motion the design runs: the full turn for a
        crank that turns fully, else the crank angles from the first target's to the last's (default 0).
    bounds : mapping of str to (float, float), optional
        Bounds of the dimensions.

    Returns
    -------
    PathDesign
        The design with its errors, Grashof class and worst transmission angle over the motion it runs.

    Raises
    ------
    ValueError
        If a target is not reached on the branch and in order, or a constraint fails.

    Examples
    --------
    >>> import numpy, symlink
    >>> design = symlink.fourbar_design((0.0, 0.0), 0.0, (1.0, 3.0, 2.5, 3.2), (1.5, 0.8), branch=1)
    >>> theta = numpy.linspace(0.0, 5.0, 6)
    >>> targets = design.points(theta)  # its own coupler curve
    >>> checked = symlink.check_design(design, targets, theta)
    >>> checked.error, checked.grashof
    (0.0, 'crank-rocker')
    """
    points = _targets(targets)
    theta = numpy.asarray(crank_angles, dtype=float)
    if theta.shape != (len(points),):
        raise ValueError(f"{len(points)} targets need {len(points)} crank angles, got {theta.size}")
    constraints = _Constraints(grashof_class, max_link_ratio, min_transmission, _box(bounds))
    if not constraints.allow(design.lengths, theta):
        raise ValueError(f"the design {tuple(round(x, 6) for x in design.lengths)} breaks a constraint "
                         f"(Grashof class {grashof_class}, link ratio <= {max_link_ratio:g}, transmission >= "
                         f"{math.degrees(min_transmission):g} deg over the motion it runs)")
    if not constraints.allow_design(design.vector, theta):
        outside = [DESIGN_NAMES[k] for k, low, high in constraints.box if not low <= design.vector[k] <= high]
        raise ValueError(f"the design's {', '.join(outside)} lie outside their bounds")
    if abs(theta[-1] - theta[0]) >= 2 * math.pi or (len(theta) > 2 and not (
            numpy.all(numpy.diff(theta) >= 0) or numpy.all(numpy.diff(theta) <= 0))):
        raise ValueError("the crank angles must turn one way, less than a full turn from the first to the last point")
    why = _reached_in_order(design, theta)
    if why is not None:
        raise ValueError(why)
    reached = design.points(theta)
    errors = numpy.hypot(*(reached - points).T)
    a, b, c, d = design.lengths
    held = fourbar_held_transmission(a, b, c, d, theta)
    return replace(design, theta=tuple(map(float, theta)), errors=tuple(map(float, errors)),
                   error=float(errors.max() / _size(points)), grashof=grashof(a, b, c, d).name,
                   worst_transmission=held.worst, transmission_over=held_over_text(held.over, held.low, held.high))


def _box(bounds: Mapping[str, tuple[float, float]] | None) -> tuple[tuple[int, float, float], ...]:
    """Bounds by dimension name (``x0, y0, a, b, c, d, u, v``) as (index, low, high); ValueError if malformed."""
    box = []
    for name, bound in (bounds or {}).items():
        if name not in DESIGN_NAMES or name == "frame":
            raise ValueError(f"bounds name dimensions among {', '.join(n for n in DESIGN_NAMES if n != 'frame')}, "
                             f"not {name!r}")
        try:
            low, high = (float(b) for b in bound)
        except (TypeError, ValueError):
            raise ValueError(f"the bounds of {name!r} must be two numbers (low, high), got {bound!r}") from None
        if not (low < high) or math.isnan(low) or math.isnan(high):
            raise ValueError(f"the bounds of {name!r} must have low < high, got {bound!r}")
        box.append((DESIGN_NAMES.index(name), low, high))
    return tuple(box)


def path_error(design: PathDesign, targets: ArrayLike) -> float:
    """The largest distance from a target to the design's coupler point at its crank angle, over the targets' size."""
    points = _targets(targets)
    return float(numpy.max(numpy.hypot(*(design.points(design.theta) - points).T)) / _size(points))


def _targets(targets) -> numpy.ndarray:
    array = numpy.asarray(targets, dtype=float)
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(f"the target points must be rows of (x, y), got shape {array.shape}")
    if not numpy.all(numpy.isfinite(array)):
        raise ValueError("the target points must be finite numbers")
    # The lengths a design takes are the points' size: outside this range their squares over- or underflow.
    magnitude = numpy.abs(array)
    if magnitude.max(initial=0.0) > TARGET_MAGNITUDE or 0.0 < _size(array) < 1.0 / TARGET_MAGNITUDE:
        raise ValueError(f"the target points must lie within {TARGET_MAGNITUDE:g} of the origin and span more than "
                         f"{1.0 / TARGET_MAGNITUDE:g} (express them in another unit)")
    return array


def check_distinct_targets(points: numpy.ndarray, times: numpy.ndarray | None = None) -> None:
    """``ValueError`` naming the first target given twice (the same point, and the same input where timed).

    A request that repeats a target asks the same thing twice: untimed, a path passes a point once; timed,
    the same point at the same input is one target.  (A point at two inputs, a closed path's start and end,
    is two targets.)

    >>> check_distinct_targets(numpy.array([[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]]))
    Traceback (most recent call last):
    ValueError: target points 1 and 3 are the same point (0, 0): give each target once
    >>> check_distinct_targets(numpy.array([[0.0, 0.0], [0.0, 0.0]]), numpy.array([0.0, 3.0]))  # two inputs
    """
    rows = points if times is None else numpy.column_stack([points, times])
    seen: dict[tuple[float, ...], int] = {}
    for number, row in enumerate(map(tuple, rows.tolist()), start=1):
        if row in seen:
            x, y = row[0], row[1]
            raise ValueError(f"target points {seen[row]} and {number} are the same point ({x:g}, {y:g})"
                             + (" at the same input" if times is not None else "") + ": give each target once")
        seen[row] = number


#: The largest coordinate a target point may have (and one over the smallest span of the points).
TARGET_MAGNITUDE = 1e50


def _size(targets: numpy.ndarray) -> float:
    return float(numpy.hypot(*(targets.max(axis=0) - targets.min(axis=0))))


# --- the atlas of starts ------------------------------------------------------------------------

def _atlas(rng: numpy.random.Generator, count: int) -> numpy.ndarray:
    """Random four-bars in their own frame, ground 1: rows (a, b, c, d, u, v) and a branch column."""
    a = rng.uniform(0.15, 1.0, count)
    b = rng.uniform(0.4, 3.0, count)
    c = rng.uniform(0.4, 3.0, count)
    u = rng.uniform(-1.5, 2.5, count) * b
    v = rng.uniform(-1.5, 1.5, count) * b
    branch = rng.choice([-1.0, 1.0], count)
    return numpy.stack([a, b, c, numpy.ones(count), u, v, branch], axis=1)


def _local_points(rows: numpy.ndarray, theta: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
    """Coupler points (complex, rows x angles) of atlas four-bars in their own frame, and where they are feasible."""
    values, slopes, assembled = path_jacobian().arrays(theta, 0.0, 0.0, 0.0, 0.0,
                                                      *(rows[:, [k]] for k in range(6)), rows[:, [6]])
    z = values[0] + 1j * values[1]
    ok = assembled & numpy.isfinite(slopes[0, 0]) & numpy.isfinite(slopes[1, 0])
    return z, ok


def _similarity(z: numpy.ndarray, w: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray, numpy.ndarray]:
    """Best ``w ~ scale_turn * z + shift`` (complex least squares, along the last axis): factor, shift, rms error."""
    zm, wm = z.mean(axis=-1, keepdims=True), w.mean(axis=-1, keepdims=True)
    dz, dw = z - zm, w - wm
    with numpy.errstate(all="ignore"):
        factor = numpy.sum(numpy.conj(dz) * dw, axis=-1, keepdims=True) / numpy.sum(numpy.abs(dz) ** 2, axis=-1,
                                                                                   keepdims=True)
    shift = wm - factor * zm
    rms = numpy.sqrt(numpy.mean(numpy.abs(factor * z + shift - w) ** 2, axis=-1))
    return factor[..., 0], shift[..., 0], rms


def _placed(row: numpy.ndarray, factor: complex, shift: complex) -> numpy.ndarray:
    """The design vector of an atlas four-bar scaled, turned and shifted by a similarity."""
    scale, turn = abs(factor), math.atan2(factor.imag, factor.real)
    a, b, c, d, u, v = row[:6] * scale
    return numpy.array([shift.real, shift.imag, turn, a, b, c, d, u, v])


def _timed_starts(w: numpy.ndarray, theta: numpy.ndarray, rng, count: int, constraints: _Constraints,
                  branch: int | None = None, free_phase: bool = False):
    """The atlas four-bars whose coupler points at the crank angles fit the targets best, placed on them.

    ``branch``: only that assembly branch.  ``free_phase``: the angles are known up to a common
    offset; each atlas four-bar is tried at :data:`_PHASE_STARTS` offsets over a turn and the
    start's angles are the offset ones.
    """
    rows = _atlas(rng, _ATLAS)
    if branch is not None:
        rows[:, 6] = branch
    offsets = numpy.linspace(0.0, 2 * math.pi, _PHASE_STARTS, endpoint=False) if free_phase else numpy.zeros(1)
    shifted = theta[None, None, :] + offsets[None, :, None]  # (1, offsets, count)
    z, ok = _local_points(rows[:, None, :].repeat(len(offsets), axis=1).reshape(-1, 7),
                          shifted.repeat(len(rows), axis=0).reshape(-1, len(theta)))
    factor, shift, rms = _similarity(z, w[None, :])
    rms = numpy.where(numpy.all(ok, axis=1) & numpy.isfinite(rms), rms, numpy.inf)
    starts: list[tuple[numpy.ndarray, int, numpy.ndarray]] = []
    for k in numpy.argsort(rms):
        if not numpy.isfinite(rms[k]) or len(starts) >= count:
            break
        row, offset = divmod(int(k), len(offsets))
        vector = _placed(rows[row], factor[k], shift[k])
        if constraints.allow_design(vector, theta + offsets[offset]):
            starts.append((vector, int(rows[row, 6]), theta + offsets[offset]))
    return starts


@lru_cache(maxsize=1)
def _curve_atlas() -> tuple[numpy.ndarray, numpy.ndarray, numpy.ndarray]:
    """The first atlas without timing, the same in every call (made once a process): rows, curves, arc tables.

    Rows (a, b, c, d, u, v, branch) of four-bars whose crank turns fully, their coupler
    points (complex, own frame) at :data:`_CURVE_SAMPLES` crank angles over a turn, and the
    arc-length tables of :func:`_curves`.
    """
    return _curves(_atlas(numpy.random.default_rng(20240611), _CURVE_ATLAS))


def _curves(rows: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray, numpy.ndarray]:
    """The atlas four-bars whose crank turns fully, their curves, and each curve's arc-length table.

    The table inverts the arc length: column j holds the fractional sample position where the
    curve's arc length from the first sample is the fraction ``j / _ARC_BINS`` of the whole.
    """
    samples = numpy.linspace(-math.pi, math.pi, _CURVE_SAMPLES + 1)[:-1]
    z, ok = _local_points(rows, samples[None, :])
    turning = numpy.all(ok, axis=1)
    rows, z = rows[turning], z[turning]
    closed = numpy.concatenate([z, z[:, :1]], axis=1)
    arc = numpy.concatenate([numpy.zeros((len(z), 1)), numpy.cumsum(numpy.abs(numpy.diff(closed, axis=1)), axis=1)],
                            axis=1)
    arc /= arc[:, -1:]
    fractions, positions = numpy.linspace(0.0, 1.0, _ARC_BINS + 1), numpy.arange(_CURVE_SAMPLES + 1, dtype=float)
    table = numpy.array([numpy.interp(fractions, row, positions) for row in arc]).reshape(len(z), _ARC_BINS + 1)
    return rows, z, table


def _untimed_starts(w: numpy.ndarray, rng, count: int, constraints: _Constraints, first: bool,
                    branch: int | None = None, direction: int | None = None):
    """Atlas curves matched to the targets by arc length: several phases, spans and both directions; the best fits.

    The crank angles where a curve's arc length has the targets' chord-length fractions give a
    similarity fit (rotation, scale, shift).  The curve's samples, interpolated, stand in for its
    coupler points (no solver call).  (Projecting the targets onto the atlas curves and fitting
    again, and alternating timed solves with projections of the angles onto the refined curve,
    were tried and found no more solutions on twenty test problems.)
    """
    rows, z, table = _curve_atlas() if first else _curves(_atlas(rng, _CURVE_ATLAS))
    if branch is not None:
        on_branch = rows[:, 6] == branch
        rows, z, table = rows[on_branch], z[on_branch], table[on_branch]
    samples = len(z[0])
    grid = numpy.linspace(-math.pi, math.pi, samples + 1)[:-1]
    closed = numpy.concatenate([z, z[:, :1]], axis=1)
    chords = numpy.concatenate([[0.0], numpy.cumsum(numpy.abs(numpy.diff(w)))])
    fraction = chords / chords[-1] if chords[-1] > 0 else numpy.linspace(0, 1, len(w))
    fits = []  # (rms, row, sample positions)
    for span in _SPANS:
        for phase in numpy.linspace(0, 1, _PHASES, endpoint=False):
            for way in (1, -1):
                if direction is not None and way != direction:
                    continue  # (the curve's samples run with the crank angle: a way is a crank direction)
                where = (phase + way * span * fraction) % 1.0
                position = _arc_position(table, where)  # fractional sample index, rows x targets
                zz = _sampled(closed, position)
                _, _, rms = _similarity(zz, w[None, :])
                rms = numpy.where(numpy.isfinite(rms), rms, numpy.inf)
                for k in numpy.argsort(rms)[:_PROJECTED // 8]:
                    fits.append((rms[k], k, position[k]))
    fits.sort(key=lambda item: item[0])
    fits = fits[:_PROJECTED]
    chosen = numpy.array([k for _, k, _ in fits])
    position = numpy.array([p for _, _, p in fits])
    curves = z[chosen]
    factor, shift, rms = _similarity(_sampled(numpy.concatenate([curves, curves[:, :1]], axis=1), position),
                                     w[None, :])
    starts: list[tuple[numpy.ndarray, int, numpy.ndarray]] = []
    used: set[int] = set()
    for m in numpy.argsort(numpy.where(numpy.isfinite(rms), rms, numpy.inf)):
        if len(starts) >= count or not numpy.isfinite(rms[m]):
            break
        forward = numpy.diff(position[m]) % samples
        steps = forward if numpy.sum(forward) < samples else -((-numpy.diff(position[m])) % samples)
        theta = grid[0] + (position[m][0] + numpy.concatenate([[0.0], numpy.cumsum(steps)])) * (2 * math.pi / samples)
        if chosen[m] in used or abs(theta[-1] - theta[0]) >= 2 * math.pi:
            continue
        if direction is not None and (theta[-1] - theta[0]) * direction < 0:
            continue
        vector = _placed(rows[chosen[m]], factor[m], shift[m])
        if constraints.allow_design(vector, theta):
            used.add(chosen[m])
            starts.append((vector, int(rows[chosen[m], 6]), theta))
    return starts


def _sampled(closed: numpy.ndarray, position: numpy.ndarray) -> numpy.ndarray:
    """A closed curve's samples (rows, samples + 1, the first repeated) linearly interpolated at fractional indices."""
    position = position % (closed.shape[1] - 1)
    low = numpy.floor(position).astype(int)
    part = position - low
    first = numpy.take_along_axis(closed, low, axis=1)
    return first + part * (numpy.take_along_axis(closed, low + 1, axis=1) - first)


def _arc_position(table: numpy.ndarray, where: numpy.ndarray) -> numpy.ndarray:
    """Fractional sample positions (rows x len(where)) where each curve's arc length has the fractions ``where``.

    ``table[k, j]`` is curve k's position at the fraction ``j / (columns - 1)``; linear in between.
    """
    bins = table.shape[1] - 1
    scaled = numpy.clip(where, 0.0, 1.0) * bins
    low = numpy.minimum(numpy.floor(scaled).astype(int), bins - 1)
    part = scaled - low
    return table[:, low] + part * (table[:, low + 1] - table[:, low])


# --- the refinement -----------------------------------------------------------------------------

def _refine(start: numpy.ndarray, branch: int, theta: numpy.ndarray, targets: numpy.ndarray, timed: bool,
            constraints: _Constraints, size: float, tolerance: float, evaluations: int, free_phase: bool = False):
    """One start refined: (design vector, crank angles, evaluations, cost), or None if the start is infeasible.

    With timing: Levenberg-Marquardt (``least_squares(method="lm")``; trust-region reflective
    for fewer than five points) over the nine dimensions, sliding along the walls (:func:`_slid`);
    a design that ends on a wall is refined again on the walls (:func:`_linear_walls`) by
    :func:`_active_set_levenberg_marquardt`, kept if closer.  Without: :func:`_refine_untimed`.
    No bounds are needed for the lengths: a length at or below zero breaks a constraint and is
    never accepted.  ``free_phase`` (with timing): a common offset added to the crank angles is
    a tenth unknown (its Jacobian column is the point's derivative by its crank angle).
    """
    if not timed:
        return _refine_untimed(start, branch, theta, targets, constraints, size, tolerance, evaluations)
    from scipy.optimize import least_squares

    count = len(targets)
    last: dict[str, numpy.ndarray] = {}  # the generated code gives points and Jacobian in one call: keep it

    def angles_of(x: numpy.ndarray) -> numpy.ndarray:
        return theta + x[9] if free_phase else theta

    def residuals(x: numpy.ndarray) -> numpy.ndarray:
        design, chain = _slid(x[:9], constraints)
        if not constraints.allow_design(design, angles_of(x)):
            return numpy.full(2 * count, _INFEASIBLE)
        with numpy.errstate(all="ignore"):
            points, jac, ok = _evaluate(design, angles_of(x), branch)
        if not numpy.all(ok):
            return numpy.full(2 * count, _INFEASIBLE)
        last.update(x=x.copy(), jac=jac, chain=chain)
        return ((points - targets) / size).ravel()

    def jacobian(x: numpy.ndarray) -> numpy.ndarray:
        if "x" in last and numpy.array_equal(last["x"], x):
            jac, chain = last["jac"], last["chain"]
        else:
            design, chain = _slid(x[:9], constraints)
            with numpy.errstate(all="ignore"):
                _, jac, _ = _evaluate(design, angles_of(x), branch)
        columns = jac[:, :, 1:].reshape(2 * count, 9) @ chain
        if free_phase:
            columns = numpy.concatenate([columns, jac[:, :, 0].reshape(2 * count, 1)], axis=1)
        return columns / size

    x0 = numpy.concatenate([start, [0.0]]) if free_phase else start.copy()
    if residuals(x0)[0] == _INFEASIBLE:
        return None
    # Levenberg-Marquardt needs at least as many residuals as unknowns; fewer points (three or four) go to the
    # trust-region reflective method.
    method = "lm" if 2 * count >= len(x0) else "trf"
    fit = least_squares(residuals, x0, jac=jacobian, method=method, x_scale="jac", xtol=tolerance, ftol=tolerance,
                        gtol=tolerance, max_nfev=evaluations)
    x, used, cost = fit.x.copy(), fit.nfev + (fit.njev or 0), float(fit.cost)
    x[:9] = _slid(fit.x[:9], constraints)[0]

    def exact(x: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray] | None:
        """Residuals and Jacobian of a design as it is (no sliding), None where it is infeasible."""
        if not constraints.allow_design(x[:9], angles_of(x)):
            return None
        with numpy.errstate(all="ignore"):
            points, jac, ok = _evaluate(x[:9], angles_of(x), branch)
        if not numpy.all(ok):
            return None
        columns = jac[:, :, 1:].reshape(2 * count, 9)
        if free_phase:
            columns = numpy.concatenate([columns, jac[:, :, 0].reshape(2 * count, 1)], axis=1)
        return ((points - targets) / size).ravel(), columns / size

    # Sliding moves a trial onto the walls it crosses, but the solver cannot see a wall's corner (a length clipped
    # at its bound has no column, so it never comes back) nor follow a narrow valley along a wall: where the design
    # ends on a wall, it is refined on the walls exactly (:func:`_active_set_levenberg_marquardt`).
    lower, upper, normals, offsets = _linear_walls(constraints, x)
    if _active_walls(x, lower, upper, normals, offsets):
        walled = _active_set_levenberg_marquardt(exact, x, lower, upper, normals, offsets, evaluations, tolerance)
        if walled is not None:
            used += walled[2]
            if walled[1] < cost:
                x, cost = walled[0], walled[1]
    return x[:9], angles_of(x), used, cost


def _linear_walls(constraints: _Constraints, x: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray, numpy.ndarray,
                                                                          numpy.ndarray]:
    """The constraints on the unknowns ``x`` (a design vector, then any angles) that are linear: their walls.

    ``(lower, upper, normals, offsets)``: the bounds (``bounds=``; infinite where none) and the
    inequalities ``normals @ x <= offsets``.  A Grashof class with its shortest link named
    (``crank-rocker``: the crank) is the three inequalities ``s + l <= p + q``, one for each
    other link as ``l`` (together they make ``s`` the shortest and the four-bar Grashof), each
    kept :data:`_GRASHOF_MARGIN` of the links' sum inside, so that the class is strict;
    ``crank-turns`` holds to the class of the design ``x`` (crank-rocker or double-crank: a union
    of two such sets, whose walls are those of the one ``x`` lies in).
    """
    count = len(x)
    lower, upper = numpy.full(count, -math.inf), numpy.full(count, math.inf)
    for k, low, high in constraints.box:
        lower[k], upper[k] = low, high
    name = constraints.grashof
    if name == "crank-turns":
        name = grashof(*(float(v) for v in x[3:7])).name
    normals = []
    if name in _SHORTEST_LINK:
        shortest = _SHORTEST_LINK[name]
        for longest in range(4):
            if longest != shortest:
                row = numpy.zeros(count)
                row[3:7] = _GRASHOF_MARGIN - 1.0
                row[[3 + shortest, 3 + longest]] = _GRASHOF_MARGIN + 1.0
                normals.append(row)
    return lower, upper, numpy.array(normals).reshape(-1, count), numpy.zeros(len(normals))


def _wall_rows(lower: numpy.ndarray, upper: numpy.ndarray, normals: numpy.ndarray,
               offsets: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
    """All walls as ``rows @ x <= right``: the finite upper bounds, the finite lower bounds, then the inequalities."""
    unit = numpy.eye(len(lower))
    high, low = numpy.isfinite(upper), numpy.isfinite(lower)
    rows = numpy.concatenate([unit[high], -unit[low], normals])
    return rows, numpy.concatenate([upper[high], -lower[low], offsets])


def _active_walls(x: numpy.ndarray, lower: numpy.ndarray, upper: numpy.ndarray, normals: numpy.ndarray,
                  offsets: numpy.ndarray) -> list[int]:
    """The walls (indices into :func:`_wall_rows`) ``x`` lies on: slack within :data:`_ACTIVE` of its terms' size."""
    rows, right = _wall_rows(lower, upper, normals, offsets)
    slack = right - rows @ x
    return [int(i) for i in numpy.flatnonzero(slack <= _ACTIVE * (numpy.abs(rows) @ numpy.abs(x) + numpy.abs(right)))]


def _null_space(rows: numpy.ndarray, count: int) -> numpy.ndarray:
    """An orthonormal basis (columns) of the directions along every wall of ``rows`` (all of them if none)."""
    if len(rows) == 0:
        return numpy.eye(count)
    _, singular, turned = numpy.linalg.svd(rows)
    rank = int(numpy.sum(singular > 1e-12 * singular[0]))
    return turned[rank:].T


def _active_set_levenberg_marquardt(residuals, x0: numpy.ndarray, lower: numpy.ndarray, upper: numpy.ndarray,
                                    normals: numpy.ndarray, offsets: numpy.ndarray, evaluations: int,
                                    tolerance: float):
    """Levenberg-Marquardt held to linear walls by an active set: (x, cost = |r|^2 / 2, evaluations), None if x0 fails.

    The walls are ``lower <= x <= upper`` and ``normals @ x <= offsets``; ``x0`` satisfies them and
    ``residuals(x)`` gives ``(r, J)``, or None where x is infeasible for another reason (never
    accepted).  The walls ``x0`` lies on are held: each step is the damped Gauss-Newton step
    along them (in an orthonormal basis of the directions that keep every held wall), so a
    design on a wall stays exactly on it, however narrow the valley along it.  A step that
    would cross another wall is cut short at it, and that wall is held from then on.  When the
    refinement stops on its walls, the multipliers of the held walls (``J^T r + rows^T mu = 0``,
    least squares) say which of them holds the design back (``mu >= 0``); one with a negative
    multiplier (the cost falls inward, away from it) is let go and the refinement goes on, at most
    :data:`_RELEASES` times.  This is the active-set method for linearly constrained least
    squares (Nocedal and Wright, *Numerical Optimization*, 2nd ed., ch. 16: active-set methods),
    with the damping of :func:`_accelerated_levenberg_marquardt` (Marquardt's scaling, Nielsen's
    update).
    Stops when the cost's decrease (relative) or the step (relative to x) is below ``tolerance``
    and no wall is to be let go, or the damping grows hopeless.
    """
    rows, right = _wall_rows(lower, upper, normals, offsets)
    x = numpy.clip(x0, lower, upper)
    first = residuals(x)
    if first is None:
        return None
    r, J = first
    cost, used = 0.5 * float(r @ r), 1
    held = set(_active_walls(x, lower, upper, normals, offsets))
    basis, scale = None, None
    damping, growth, released = 1e-3, 2.0, 0
    while used < evaluations and cost > 0:
        if basis is None:
            basis = _null_space(rows[sorted(held)], len(x))
            scale = None
        converged = basis.shape[1] == 0
        if not converged:
            along = J @ basis
            gradient, normal = along.T @ r, along.T @ along
            scale = numpy.maximum(scale if scale is not None else 1e-300, numpy.sum(along * along, axis=0))
            try:
                velocity = -numpy.linalg.solve(normal + damping * numpy.diag(scale), gradient)
            except numpy.linalg.LinAlgError:
                damping *= 10
                if damping > 1e16:
                    break
                continue
            step = basis @ velocity
            toward, room = rows @ step, right - rows @ x
            cut, blocking = 1.0, None
            for i in numpy.flatnonzero(toward > 0):
                if int(i) not in held and max(room[i], 0.0) < cut * toward[i]:
                    cut, blocking = max(room[i], 0.0) / toward[i], int(i)
            if blocking is not None and cut <= 0.0:
                held.add(blocking)  # already on that wall: hold it and take the step along it
                basis = None
                continue
            trial_x = numpy.clip(x + cut * step, lower, upper)
            trial = residuals(trial_x)
            used += 1
            if trial is not None and 0.5 * float(trial[0] @ trial[0]) < cost:
                new_cost = 0.5 * float(trial[0] @ trial[0])
                predicted = -cut * float(gradient @ velocity) - 0.5 * cut ** 2 * float(velocity @ (normal @ velocity))
                gain = (cost - new_cost) / predicted if predicted > 0 else 0.0
                damping = max(damping * max(1 / 3, 1 - (2 * min(gain, 1.0) - 1) ** 3), 1e-15)
                growth = 2.0
                stalled = cost - new_cost <= tolerance * cost
                small = numpy.max(numpy.abs(trial_x - x) / (numpy.abs(trial_x) + 1e-300)) < tolerance
                x, (r, J), cost = trial_x, trial, new_cost
                if blocking is not None:
                    held.add(blocking)
                    basis = None
                    continue
                converged = stalled or small
            else:
                damping *= growth
                growth *= 2
                converged = damping > 1e16
        if not converged:
            continue
        if not held or released >= _RELEASES:
            break
        order = sorted(held)
        gradient = J.T @ r
        multipliers = numpy.linalg.lstsq(rows[order].T, -gradient, rcond=None)[0]
        pull = multipliers * numpy.linalg.norm(rows[order], axis=1)
        weakest = int(numpy.argmin(pull))
        if not pull[weakest] < -1e-6 * numpy.linalg.norm(gradient):
            break
        held.discard(order[weakest])  # the cost falls inward from this wall: let it go
        basis, damping, growth, released = None, 1e-3, 2.0, released + 1
    return x, cost, used


def _slid(design: numpy.ndarray, constraints: _Constraints) -> tuple[numpy.ndarray, numpy.ndarray]:
    """A timed trial design moved onto the walls it crosses, and d(moved)/d(design) (9 x 9).

    Bounded dimensions beyond a bound go to the bound (their column zero).  With
    ``grashof_class="crank-rocker"``, a design whose crank is the shortest link but which breaks
    Grashof's inequality ``a + longest <= the other two`` is projected onto it (just inside, by
    :data:`_GRASHOF_MARGIN` of the links' sum, so it stays a crank-rocker): the lengths move along
    the inequality's normal.  The refinement then slides along these walls instead of stopping at
    the first trial past them (the optimum of a problem can lie on them: a change-point linkage at
    a length bound); where it ends on one, :func:`_refine` refines on the walls exactly.
    """
    moved = design.copy()
    chain = numpy.eye(9)
    for k, low, high in constraints.box:
        if not low <= moved[k] <= high:
            moved[k] = min(max(moved[k], low), high)
            chain[k, :] = 0.0
    if constraints.grashof == "crank-rocker":
        lengths = moved[3:7]
        longest = 1 + int(numpy.argmax(lengths[1:]))
        if lengths[0] < lengths[1:].min() and longest >= 1:
            normal = -numpy.ones(4)
            normal[[0, longest]] = 1.0
            excess = float(normal @ lengths) + _GRASHOF_MARGIN * float(lengths.sum())
            if excess > 0:
                moved[3:7] = lengths - excess / 4 * normal
                block = numpy.eye(9)
                block[3:7, 3:7] -= numpy.outer(normal, normal) / 4
                chain = block @ chain
    return moved, chain


def _refine_untimed(start: numpy.ndarray, branch: int, theta: numpy.ndarray, targets: numpy.ndarray,
                    constraints: _Constraints, size: float, tolerance: float, evaluations: int):
    """:func:`_refine` without timing: the nine dimensions and the crank angles, in order.

    The angles are the first one and squared steps to the next (``theta_i = theta_1 +
    direction * sum(s_k^2)``), so they turn one way with no bounds, and two points at one
    angle are no wall.  Two walls are slid along instead of stopping the solver: a trial that
    turns a full turn or more is evaluated at its projection onto just under a full turn (the
    steps scaled down together), and a bounded dimension (``bounds``) beyond its bound at the
    bound; the Jacobian is the chain rule through the projection (a clipped dimension's column
    zero), so the refinement moves along the wall.  Designs the optimum presses against a full
    turn (a closed curve through its first point again) or against a bound end there, instead of
    wherever the first refused trial left them.  (One free angle per point, with trials out of
    order infeasible, solved fewer problems.)
    """
    count = len(targets)
    direction = 1.0 if len(theta) < 2 or theta[-1] >= theta[0] else -1.0

    def angles_of(x: numpy.ndarray) -> numpy.ndarray:
        return ordered_inputs(x[9], x[10:], direction)

    def projected(x: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray, numpy.ndarray]:
        """x on the walls (bounds, under a full turn), which dimensions were clipped, d(projected steps)/d(steps)."""
        y = x.copy()
        clipped = numpy.zeros(len(x), dtype=bool)
        for k, low, high in constraints.box:
            if not low <= y[k] <= high:
                y[k], clipped[k] = min(max(y[k], low), high), True
        y[10:], chain = steps_under_a_turn(y[10:])
        return y, clipped, chain

    def residuals(x: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray] | None:
        y, clipped, step_chain = projected(x)
        design, angles = y[:9], angles_of(y)
        if not constraints.allow_design(design, angles) or abs(angles[-1] - angles[0]) >= 2 * math.pi:
            return None
        with numpy.errstate(all="ignore"):
            points, jac, ok = _evaluate(design, angles, branch)
        if not numpy.all(ok):
            return None
        by_theta = jac[:, :, 0]  # (count, 2): d point_i / d theta_i
        # d theta_i / d theta_1 = 1 and d theta_i / d s_k = 2 direction s_k for k < i: a lower triangle
        chain = ordered_inputs_jacobian(y[10:], direction)
        angle_columns = (by_theta[:, :, None] * chain[:, None, :]).reshape(2 * count, count)
        angle_columns[:, 1:] = angle_columns[:, 1:] @ step_chain
        jacobian = numpy.concatenate([jac[:, :, 1:].reshape(2 * count, 9), angle_columns], axis=1)
        jacobian[:, clipped] = 0.0
        return ((points - targets) / size).ravel(), jacobian / size

    x0 = numpy.concatenate([start, [theta[0]], numpy.sqrt(numpy.abs(numpy.diff(theta)))])
    result = _accelerated_levenberg_marquardt(residuals, x0, evaluations, tolerance)
    if result is None:
        return None
    x, cost, used = result
    y = projected(x)[0]
    return y[:9], angles_of(y), used, cost


def _accelerated_levenberg_marquardt(residuals, x0: numpy.ndarray, evaluations: int, tolerance: float):
    """Levenberg-Marquardt with geodesic acceleration: (x, cost = |r|^2 / 2, evaluations), None if x0 is infeasible.

    ``residuals(x)`` gives ``(r, J)`` or None where x is infeasible (never accepted).  Coupler
    points that barely fix the four-bar (ten points, nineteen unknowns without timing) leave
    long curved valleys, along which plain Levenberg-Marquardt crawls in short steps; the
    second-order correction of Transtrum and Sethna (Phys. Rev. E 83, 036701 (2011); "Improvements
    to the Levenberg-Marquardt algorithm for nonlinear least-squares minimization", 2012) bends
    each step along the valley: with the velocity ``v`` (the damped Gauss-Newton step) and the
    residuals' second derivative along it by one extra evaluation, ``r_vv ~ 2/h ((r(x + h v) -
    r(x)) / h - J v)``, the acceleration ``a`` solves the same damped system with ``J^T r_vv``,
    and the step ``v + a / 2`` is tried if ``|a| <= alpha |v|`` (scaled), else ``v``.  Damping: Marquardt's
    diagonal scaling (the largest column norms seen), Nielsen's update from the gain ratio.
    Stops when the residuals' norm, the step (relative to x) or the cost's decrease (relative
    to the cost) is below ``tolerance``, or the damping grows hopeless.
    """
    first = residuals(x0)
    if first is None:
        return None
    r, J = first
    x, cost, used = x0.copy(), 0.5 * float(r @ r), 1
    scale = numpy.maximum(numpy.sum(J * J, axis=0), 1e-300)
    damping, growth = 1e-3, 2.0
    probe, alpha = 0.1, 0.75
    while used < evaluations and math.sqrt(2 * cost) > tolerance:
        gradient, normal = J.T @ r, J.T @ J
        scale = numpy.maximum(scale, numpy.sum(J * J, axis=0))
        system = normal + damping * numpy.diag(scale)
        try:
            velocity = -numpy.linalg.solve(system, gradient)
        except numpy.linalg.LinAlgError:
            damping *= 10
            continue
        probed = residuals(x + probe * velocity)
        used += 1
        step = velocity
        if probed is not None:
            second = 2.0 / probe * ((probed[0] - r) / probe - J @ velocity)
            acceleration = -numpy.linalg.solve(system, J.T @ second)
            if 2 * math.sqrt(acceleration @ (scale * acceleration)) <= alpha * math.sqrt(velocity @ (scale * velocity)):
                step = velocity + 0.5 * acceleration
        # Near convergence the second difference is rounding noise and fails the test: the plain step then.
        trial = residuals(x + step)
        used += 1
        if trial is not None and 0.5 * float(trial[0] @ trial[0]) < cost:
            new_cost = 0.5 * float(trial[0] @ trial[0])
            stalled = cost - new_cost <= tolerance * cost
            predicted = -float(gradient @ velocity) - 0.5 * float(velocity @ (normal @ velocity))
            gain = (cost - new_cost) / predicted if predicted > 0 else 0.0
            damping = max(damping * max(1 / 3, 1 - (2 * min(gain, 1.0) - 1) ** 3), 1e-15)
            growth = 2.0
            x, (r, J), cost = x + step, trial, new_cost
            if stalled or numpy.max(numpy.abs(step) / (numpy.abs(x) + 1e-300)) < tolerance:
                break
            continue
        damping *= growth
        growth *= 2
        if damping > 1e16:
            break
    return x, cost, used


def _successive_halving(candidates: list, targets: numpy.ndarray, constraints: _Constraints, size: float,
                        tolerance: float, keep) -> bool:
    """Untimed starts refined in rounds, the closest half kept each round with twice the evaluations: solved?

    Most starts lead nowhere, and a few dozen evaluations tell the promising ones: every start
    gets :data:`_SCREEN_EVALUATIONS`, then the better half as many again, and so on, each from
    where it stopped, until one is left or a start has had :data:`_LAST_ROUND` in one round (a
    start that stops on its own, converged or stalled, is not refined again).
    ``keep(vector, branch, angles, evaluations)`` verifies a design (None if it fails); every
    refined start closer than every verified one before it is verified at once, so a verified design is at
    hand from the first start on; True as soon as one verifies below 1e-8.
    """
    alive = [(math.inf, vector, branch, numpy.asarray(angles, dtype=float), 0, False)
             for vector, branch, angles in candidates]
    budget, closest = _SCREEN_EVALUATIONS, math.inf
    while alive:
        results = []
        for cost, vector, branch, angles, used, stopped in alive:
            if not stopped:
                result = _refine(vector, branch, angles, targets, False, constraints, size, tolerance, budget)
                if result is None:
                    continue
                vector, angles, spent, cost = result
                used, stopped = used + spent, spent < budget
                if cost < closest:
                    design = keep(vector, branch, angles, used)
                    if design is not None:
                        closest = cost
                        if design.error < 1e-8:
                            return True
            results.append((cost, vector, branch, angles, used, stopped))
        results.sort(key=lambda item: item[0])
        if len(results) <= 1 or budget >= _LAST_ROUND:
            break
        alive = results[:len(results) // 2]
        budget *= 2
    return False


def synthesize_path(targets: ArrayLike, theta: ArrayLike | None = None, *, starts: int = 8, designs: int = 3,
                    grashof_class: str = "any", max_link_ratio: float = 20.0, min_transmission: float = 0.0,
                    seed: int | None = 0, tolerance: float = 1e-15, branch: int | None = None,
                    direction: int | None = None, free_phase: bool = False,
                    bounds: Mapping[str, tuple[float, float]] | None = None) -> list[PathDesign]:
    """Four-bars whose coupler point passes through ``targets`` (rows x, y), best first, up to ``designs``.

    ``theta``: the crank angles at the targets (timing), or None to find them too (the
    points are then reached in their order, the crank turning one way).  ``starts`` atlas
    fits are refined (without timing four times as many by successive halving, twice that in
    the batches after the first); ``grashof_class`` is one of :data:`GRASHOF_CHOICES` ("crank-turns":
    crank-rocker or double-crank); ``max_link_ratio`` bounds the longest link over the
    shortest; ``min_transmission`` (radians) bounds the worst transmission angle over the
    motion the design runs, in every trial of the search: the full turn for a crank that turns fully (Grashof
    crank-rocker or double-crank), else the crank angles from the first target's to the last's (the design's
    ``transmission_over`` says which).  ``branch`` (+1 or -1) keeps to that assembly branch; ``direction`` (without
    timing; +1 or -1) makes the crank angle grow (+1, counter-clockwise) or shrink from point to
    point; ``free_phase`` (with timing) takes ``theta`` as known up to a common offset (equal
    steps from an unknown first angle, say), which is found too.  ``bounds`` maps dimensions
    (``x0, y0, a, b, c, d, u, v``: the crank pivot in a box, link lengths, the coupler point) to
    ``(low, high)``; trials outside are refused like any infeasible one.  Needs SciPy
    (``pip install 'symlink-kinematics[synthesis]'``).
    ``ValueError`` for bad input or when no start satisfies the constraints.

    Parameters
    ----------
    targets : array_like
        The target points, rows (x, y).
    theta : array_like, optional
        The crank angles at the targets (timing), or None (default) to find them too.
    starts : int, optional
        Atlas fits refined (default 8).
    designs : int, optional
        How many designs to return at most (default 3).
    grashof_class : str, optional
        One of ``GRASHOF_CHOICES`` (default ``"any"``; ``"crank-turns"``: crank-rocker or double-crank).
    max_link_ratio : float, optional
        A bound on the longest link over the shortest (default 20).
    min_transmission : float, optional
        A bound (radians) on the worst transmission angle over the motion the design runs (default 0).
    seed : int or None, optional
        The sampling's seed (default 0).
    tolerance : float, optional
        The refinement's step tolerance.
    branch : {1, -1}, optional
        Keep to that assembly branch (default either).
    direction : {1, -1}, optional
        Without timing: the crank angle grows (+1) or shrinks from point to point.
    free_phase : bool, optional
        With timing: ``theta`` known up to a common offset, found too.
    bounds : mapping of str to (float, float), optional
        Bounds of ``x0, y0, a, b, c, d, u, v``.

    Returns
    -------
    list of PathDesign
        The designs found, best first.

    Raises
    ------
    ValueError
        For bad input, or when no start satisfies the constraints.

    See Also
    --------
    symlink.synthesize_path : path synthesis of any linkage.

    Examples
    --------
    >>> import numpy, symlink
    >>> design = symlink.fourbar_design((0.0, 0.0), 0.0, (1.0, 3.0, 2.5, 3.2), (1.5, 0.8), branch=1)
    >>> theta = numpy.linspace(0.0, 5.0, 6)
    >>> targets = design.points(theta)  # its own coupler curve
    >>> found = symlink.synthesize_fourbar_path(targets, theta=theta, starts=1, designs=1)  # needs SciPy
    >>> len(found), found[0].error < 1e-8
    (1, True)
    """
    try:
        import scipy.optimize  # noqa: F401
    except ImportError as missing:  # pragma: no cover - the extra is installed in the tests
        raise ImportError("path synthesis needs SciPy: pip install 'symlink-kinematics[synthesis]'") from missing
    settled(fourbar_transmission_solver())  # its filter and record repeat bit for bit, whenever its build ends
    points = _targets(targets)
    count = len(points)
    timed = theta is not None
    if count < (3 if timed else 4):
        raise ValueError(f"path synthesis needs at least {3 if timed else 4} target points, got {count}")
    size = _size(points)
    if not size > 0:
        raise ValueError("the target points are all the same point")
    crank_angles = numpy.asarray(theta if theta is not None else numpy.zeros(count), dtype=float)
    if crank_angles.shape != (count,):
        raise ValueError(f"{count} target points need {count} crank angles, got {crank_angles.size}")
    if not numpy.all(numpy.isfinite(crank_angles)):
        raise ValueError("the crank angles must be finite numbers")
    check_distinct_targets(points, crank_angles if timed else None)
    if grashof_class not in GRASHOF_CHOICES:
        raise ValueError(f"grashof_class must be one of {', '.join(GRASHOF_CHOICES)}, not {grashof_class!r}")
    if not (max_link_ratio >= 1):
        raise ValueError(f"the link ratio bound must be at least 1, got {max_link_ratio:g}")
    if not (0 <= min_transmission < math.pi / 2):
        raise ValueError(f"the minimum transmission angle must lie in [0, 90) deg, got "
                         f"{math.degrees(min_transmission):g} deg")
    if designs < 1:
        raise ValueError("starts and designs must be at least 1")
    # the largest atlas a call fits (timed with a free phase: each four-bar at every offset)
    check_starts(starts, _MAX_EVALUATIONS, _ATLAS * _PHASE_STARTS, "atlas four-bars a call fits")
    for name, sign in (("branch", branch), ("direction", direction)):
        if sign not in (None, 1, -1):
            raise ValueError(f"{name} must be +1, -1 or None, not {sign!r}")
    if direction is not None and timed:
        raise ValueError("direction is for targets without timing (with timing the crank angles fix it)")
    if free_phase and not timed:
        raise ValueError("free_phase needs the crank angles (timing) it offsets")
    constraints = _Constraints(grashof_class, max_link_ratio, min_transmission, _box(bounds))
    rng = numpy.random.default_rng(seed)
    w = points[:, 0] + 1j * points[:, 1]
    found: list[PathDesign] = []

    def refined(vector, on_branch, angles, evaluations) -> PathDesign | None:
        """A start refined and verified (None if it fails the constraints or the check)."""
        result = _refine(vector, on_branch, numpy.asarray(angles, dtype=float), points, timed, constraints, size,
                         tolerance, evaluations, free_phase and timed)
        if result is None:
            return None
        design_vector, design_theta, used, _ = result
        return verified(design_vector, on_branch, design_theta, used)

    def verified(design_vector, on_branch, design_theta, used) -> PathDesign | None:
        """A design checked by :func:`check_design` (None if it fails)."""
        a, b, c, d = (float(x) for x in design_vector[3:7])
        design = PathDesign((float(design_vector[0]), float(design_vector[1])), float(design_vector[2]),
                            a, b, c, d, (float(design_vector[7]), float(design_vector[8])), on_branch,
                            evaluations=used)
        try:
            return check_design(design, points, design_theta, grashof_class, max_link_ratio, min_transmission,
                                bounds)
        except ValueError:
            return None

    def kept(vector, on_branch, angles, used) -> PathDesign | None:
        """An untimed design verified (None if it fails the check) and kept."""
        design = verified(vector, on_branch, angles, used)
        if design is not None:
            found.append(design)
        return design

    polished = 0
    for attempt in range(_ATTEMPTS):
        if timed:
            for vector, on_branch, angles in _timed_starts(w, crank_angles, rng, starts, constraints, branch,
                                                           free_phase):
                design = refined(vector, on_branch, angles, _MAX_EVALUATIONS)
                if design is not None:
                    found.append(design)
                    if design.error < 1e-10:
                        break
        elif _successive_halving(_untimed_starts(w, rng, _SCREENED * starts * (1 if attempt == 0 else _WIDER),
                                                 constraints, attempt == 0, branch, direction),
                                 points, constraints, size, tolerance, kept):
            break
        if found and min(d.error for d in found) < 1e-8:
            break
        # Near-degenerate problems (points that barely fix the four-bar) crawl along a flat valley and stop
        # short: the closest designs get a long second run from where they stopped, at most _POLISHED in all.
        for design in _distinct(sorted(found, key=lambda d: d.error), _POLISHED - polished, size):
            if design.error < _POLISH_BELOW and polished < _POLISHED and design.evaluations < _POLISH_EVALUATIONS:
                polished += 1
                again = refined(design.vector, design.branch, design.theta, _POLISH_EVALUATIONS)
                if again is not None:
                    found.append(again)
                    if again.error < 1e-8:
                        break
        if found and min(d.error for d in found) < 1e-8:
            break
    if not found:
        held = (f" (a transmission angle of at least {math.degrees(min_transmission):g} deg held over the motion "
                "each design runs: the full turn for a crank, else between its first and last target)"
                if min_transmission > 0 else "")
        raise ValueError(f"no four-bar satisfying the constraints{held} was found from the starts; relax the "
                         "constraints or allow more starts")
    return _distinct(sorted(found, key=lambda d: d.error), designs, size)


def _distinct(ordered: list[PathDesign], count: int, size: float) -> list[PathDesign]:
    """The best designs that differ from each other (dimensions over the targets' size, frame angle modulo a turn)."""
    scale = numpy.array([size, size, 1, size, size, size, size, size, size])
    kept: list[PathDesign] = []
    for design in ordered:
        if count < 1:
            break
        if all(design.branch != other.branch or _differs(design.vector - other.vector, scale) for other in kept):
            kept.append(design)
        if len(kept) >= count:
            break
    return kept


def _differs(difference: numpy.ndarray, scale: numpy.ndarray) -> bool:
    relative = difference / scale
    relative[2] = math.remainder(relative[2], 2 * math.pi)
    return bool(numpy.max(numpy.abs(relative)) > 1e-4)
