"""Motion generation for any one-input linkage: a named link through poses (x, y, angle), by exact gradients.

:mod:`symlink.synthesis.motion` guides a four-bar's coupler by Burmester theory; here the
linkage is any one with one input and a closed form (a catalog entry or a linkage file), and the
guided link any of its moving links, named by a point on it (its frame point: the four-bar
coupler's ``B``, a Watt II link's ``E``) and the output that is its angle (``beta``, ``mu``).
A pose ``(x, y, angle)`` asks that point to be at (x, y) and the link's angle (plus the frame's
turn) to be ``angle``.  The linkage's frame is placed in the plane as in path synthesis
(:mod:`symlink.synthesis.general`): the point ``p`` of the linkage's own frame goes to
``(x0, y0) + scale * R(angle) p`` and every angle turns by the frame's angle; ``frame`` names the
free parts of that placement.

The unknowns are the free parameters, the free placement and, without timing, the input's value
at each pose.  The residuals at each pose: the placed point minus the target over the poses' size
(the diagonal of their bounding box), and the link's placed angle minus the target angle, wrapped
to (-pi, pi], in radians.  Their exact Jacobian comes from the generated sensitivities of the
linkage with its input shifted by a phase (:class:`symlink.synthesis.design_fit.DesignOutputs`:
the derivative by the input too); the placement's columns are written by hand.  The refinement
is the accelerated Levenberg-Marquardt of path synthesis.

Starts are random feasible designs (free parameters within their bounds, random branch signs):
each is swept over a turn of its input; untimed, the input at each pose is chosen where the
link's angle has turned from the first pose as the poses' angles do, the first pose tried at
every swept value; the placement is then fitted (the turn from the angles, scale and shift by
least squares), and the closest designs are refined.  The best refined design is verified afresh
with the linkage's own generated solver: the pose errors, and one branch without a toggle
between consecutive poses.

>>> from symlink.mechanism.catalog import fourbar
>>> truth = {"a": 1.0, "b": 3.0, "c": 2.5, "d": 3.2}
>>> poses = link_poses(fourbar(), "B", "beta", truth, [0.3, 0.9, 1.5, 2.1])
>>> found = synthesize_motion(fourbar(), "B", "beta", poses, {"a": (0.5, 2.0), "b": (2.0, 4.0), "c": (1.5, 3.5)},
...                           values={"d": 3.2}, frame=(), timed=[0.3, 0.9, 1.5, 2.1])
>>> found.assembled, found.error < 1e-12, round(found.design["c"], 9)
(True, True, 2.5)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Mapping, Sequence

import numpy
import sympy as sp
from numpy.typing import ArrayLike

from ..common.angles import wrap
from ..common.display import record_html
from ..symbolic.linkage import Linkage
from .design_fit import (DesignOutputs, branch_break, check_branches, check_linkage, free_bounds, inside,
                         is_angle_output, refine, sample_count, sampled_designs, solved_outputs)
from .general import FRAME_NAMES
from .path import check_starts

__all__ = ["MotionSynthesis", "synthesize_motion", "link_poses", "frame_point", "FRAME_NAMES"]

_IDENTITY = {"x0": 0.0, "y0": 0.0, "angle": 0.0, "scale": 1.0}
_SWEEP = 72      # input values over a turn, for choosing the input at each pose of a start
_CHUNK = 50      # sampled designs matched at once (memory: chunk x sweep^2 x poses)
_DONE = 1e-12    # a verified design below this error ends the search


@dataclass(frozen=True)
class MotionSynthesis:
    """A synthesised rigid-body guidance: design, placement, branches, the input at each pose, and its errors.

    ``design`` holds every parameter (free and fixed), ``placement`` the frame (``x0, y0, angle,
    scale``), ``inputs`` the input's value at each pose.  ``position_errors`` are the distances
    from each target to the placed point (in the poses' length unit), ``angle_errors`` the placed
    link angle minus the target (wrapped, radians), both from the linkage's own generated solver;
    :attr:`position_error` and :attr:`angle_error` are their largest sizes, each in its own unit.
    ``error`` is the fit's measure, a pure number: the largest of the position errors over ``size``
    (the poses' size, the diagonal of their bounding box) and the angle errors in radians, the weights
    of the least squares objective (one radian of the link's angle weighs as much as ``size`` of its
    point's position).  ``assembled`` whether the verification passed (every pose on one branch, no
    toggle between them), ``why`` what failed.

    Examples
    --------
    >>> found = MotionSynthesis("fourbar", "B", "beta", {}, {}, {}, (0.0, 1.0), position_errors=(0.002, 0.001),
    ...                         angle_errors=(-0.003, 0.001), error=0.003, size=2.0)
    >>> found.position_error, found.angle_error
    (0.002, 0.003)
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    linkage: str
    point: str
    angle: str
    design: dict[str, float]
    placement: dict[str, float]
    branches: dict[str, int]
    inputs: tuple[float, ...]
    position_errors: tuple[float, ...] = ()
    angle_errors: tuple[float, ...] = ()
    error: float = math.nan
    assembled: bool = False
    evaluations: int = 0
    why: str = field(default="", repr=False)
    #: Linkages without a closed form: the unknowns at the first pose's input, the assembly the design is on (the
    #: ``guess`` of :class:`symlink.numeric.solver.NumericSolver`, continued along the inputs in their order); else empty.
    assembly: dict[str, float] = field(default_factory=dict)
    #: The poses' size (the diagonal of their bounding box, 1 for poses at one point): the length that weighs as
    #: much as one radian in the objective and in ``error``.
    size: float = math.nan

    @property
    def position_error(self) -> float:
        """The largest distance from a pose's point to the link's point, in the poses' length unit (NaN: none)."""
        return max(self.position_errors, default=math.nan)

    @property
    def angle_error(self) -> float:
        """The largest size of a pose's angle error, in radians (NaN: none)."""
        return max(map(abs, self.angle_errors), default=math.nan)


def _placed(local: numpy.ndarray, placement: Mapping[str, float]) -> numpy.ndarray:
    c, s, k = math.cos(placement["angle"]), math.sin(placement["angle"]), placement["scale"]
    x, y = local[..., 0], local[..., 1]
    return numpy.stack([placement["x0"] + k * (c * x - s * y), placement["y0"] + k * (s * x + c * y)], axis=-1)


def frame_point(linkage: Linkage, angle: str) -> str:
    """The named point where the link turned by the output ``angle`` starts: its frame point, found from the points.

    A point written as ``... + V`` with ``V`` at exactly that angle (the link's vector) is on the
    link, and so is the named point that is the same sum without ``V``, where the link starts.
    ``ValueError`` when no named point is there.

    >>> from symlink.mechanism.catalog import fourbar, watt2
    >>> frame_point(fourbar(), "coupler"), frame_point(watt2(), "mu")
    ('B', 'E')
    """
    symbol = linkage.output(angle)  # ValueError naming the outputs there are
    sums = {name: tuple(v.as_sum().terms) if v is not None else () for name, v in linkage.points.items()}
    for terms in sums.values():
        if terms and sp.simplify(terms[-1][1].angle - symbol) == 0 and terms[-1][0] > 0:
            for name, other in sums.items():
                if other == terms[:-1]:
                    return name
    raise ValueError(f"no named point of {linkage.name} starts the link at angle {angle!r}; name the frame point")


def _outputs(linkage: Linkage, point: str, angle: str) -> tuple[str, str, str]:
    if point not in linkage.points:
        raise ValueError(f"{linkage.name} has no point {point!r}; it has {', '.join(linkage.points)}")
    if not is_angle_output(linkage, angle):  # ValueError naming the outputs there are
        raise ValueError(f"{angle!r} is not an angle of {linkage.name}: name the output that is the guided link's "
                         "angle (an unknown or role that turns a vector)")
    return f"{point}_x", f"{point}_y", angle


def link_poses(linkage: Linkage, point: str, angle: str, values: Mapping[str, float], inputs: ArrayLike,
               branches: Mapping[str, float] | None = None,
               placement: Mapping[str, float] | None = None) -> numpy.ndarray:
    """The link's pose (x, y, angle) at each input as rows, placed, from the generated solver; NaN where not assembled.

    Parameters
    ----------
    linkage : Linkage
        Any linkage with one input.
    point : str
        A point on the link.
    angle : str
        The output that is the link's angle.
    values : mapping of str to float
        Every parameter.
    inputs : array_like
        The input values.
    branches : mapping of str to int, optional
        Branch signs (default +1).
    placement : mapping of str to float, optional
        ``x0, y0, angle, scale`` that place the linkage.

    Returns
    -------
    numpy.ndarray
        One row (x, y, angle) an input; NaN where not assembled.

    Examples
    --------
    >>> import math, symlink
    >>> symlink.link_poses(symlink.fourbar(), "B", "theta", {"a": 2.0, "b": 6.0, "c": 5.0, "d": 7.0}, [0.0],
    ...                    placement={"angle": math.pi / 2}).round(12).tolist()  # B = (a, 0) turned a quarter
    [[0.0, 2.0, 1.570796326795]]
    """
    names = _outputs(linkage, point, angle)
    q = numpy.asarray(inputs, dtype=float)
    if linkage.output(angle) == linkage.inputs[0]:
        solved = solved_outputs(linkage, names[:2], values, branches or {}, q)
        solved[angle] = numpy.where(numpy.isfinite(solved[names[0]]), q, numpy.nan)
    else:
        solved = solved_outputs(linkage, names, values, branches or {}, q)
    where = {**_IDENTITY, **(placement or {})}
    placed = _placed(numpy.stack([solved[names[0]], solved[names[1]]], axis=-1), where)
    return numpy.concatenate([placed, (solved[angle] + where["angle"])[..., None]], axis=-1)


class _Problem:
    def __init__(self, linkage: Linkage, names: tuple[str, str, str], poses: numpy.ndarray,
                 bounds: Mapping[str, tuple[float, float]], fixed: Mapping[str, float], frame: Sequence[str],
                 placement: Mapping[str, float], timed: numpy.ndarray | None,
                 frame_bounds: Mapping[str, tuple[float, float]]) -> None:
        self.linkage, self.names, self.poses, self.timed = linkage, names, poses, timed
        self.target = poses[:, 0] + 1j * poses[:, 1]
        size = float(numpy.hypot(*(poses[:, :2].max(axis=0) - poses[:, :2].min(axis=0))))
        self.size = size if size > 0 else 1.0
        self.free = tuple(bounds)
        self.frame = tuple(frame)
        self.placement = {**_IDENTITY, **placement}
        self.bounds = numpy.array([bounds[name] for name in self.free] +
                                  [frame_bounds.get(name, (-numpy.inf, numpy.inf)) for name in self.frame],
                                  dtype=float).reshape(len(self.free) + len(self.frame), 2)
        positive = {p.name for p in linkage.parameters if p.is_positive} | {"scale"}
        self.positive = numpy.array([name in positive for name in self.free + self.frame], dtype=bool)
        self.input_is_angle = linkage.output(names[2]) == linkage.inputs[0]
        outputs = names[:2] if self.input_is_angle else names
        self.outputs = DesignOutputs(linkage, outputs, self.free, fixed)
        self.fixed = dict(fixed)

    @property
    def width(self) -> int:
        return len(self.free) + len(self.frame)

    def split(self, x: numpy.ndarray) -> tuple[dict[str, float], dict[str, float]]:
        design = {**self.fixed, **{name: float(v) for name, v in zip(self.free, x[:len(self.free)])}}
        placement = {**self.placement, **{name: float(v) for name, v in
                                          zip(self.frame, x[len(self.free):self.width])}}
        return design, placement

    def local(self, values: numpy.ndarray, slopes: numpy.ndarray, inputs: numpy.ndarray):
        """Point (N, 2), angle (N), and their derivatives (N, 2, free + 1), (N, free + 1): the input last."""
        point = numpy.stack([values[0], values[1]], axis=-1)
        dpoint = numpy.moveaxis(slopes[:2], -1, 0)  # (N, 2, free + 1)
        if self.input_is_angle:
            angle = numpy.asarray(inputs, dtype=float)
            dangle = numpy.zeros((len(inputs), len(self.free) + 1))
            dangle[:, -1] = 1.0
        else:
            angle = values[2]
            dangle = slopes[2].T
        return point, angle, dpoint, dangle

    def residuals(self, y: numpy.ndarray, branches: Mapping[str, float]):
        """Residuals (3N: x, y, angle of each pose) and their Jacobian by the unknowns; None where infeasible."""
        x = y[:self.width]
        if not inside(x, self.bounds, self.positive):
            return None
        inputs = self.timed if self.timed is not None else y[self.width:]
        if self.timed is None and numpy.ptp(inputs) >= 4 * math.pi:
            return None
        design, placement = self.split(y)
        values, slopes, ok = self.outputs.at(x[:len(self.free)], inputs, branches)
        if not numpy.all(ok):
            return None
        point, angle, dpoint, dangle = self.local(values, slopes, inputs)
        c, s, k = math.cos(placement["angle"]), math.sin(placement["angle"]), placement["scale"]
        turn = numpy.array([[c, -s], [s, c]])
        placed = _placed(point, placement)
        count = len(inputs)
        moved = k * numpy.einsum("ij,njk->nik", turn, dpoint)  # (N, 2, free + 1)
        frame_columns = {"x0": (numpy.tile([1.0, 0.0], (count, 1)), numpy.zeros(count)),
                         "y0": (numpy.tile([0.0, 1.0], (count, 1)), numpy.zeros(count)),
                         "angle": (numpy.stack([-(placed[:, 1] - placement["y0"]), placed[:, 0] - placement["x0"]],
                                               axis=1), numpy.ones(count)),
                         "scale": (point @ turn.T, numpy.zeros(count))}
        position = [moved[:, :, :len(self.free)] / self.size]
        turning = [dangle[:, :len(self.free)]]
        for name in self.frame:
            position.append(frame_columns[name][0][:, :, None] / self.size)
            turning.append(frame_columns[name][1][:, None])
        block = numpy.concatenate([numpy.concatenate(position, axis=2),
                                   numpy.concatenate(turning, axis=1)[:, None, :]], axis=1)  # (N, 3, width)
        jacobian = block.reshape(3 * count, self.width)
        if self.timed is None:
            by_input = numpy.zeros((count, 3, count))
            by_input[numpy.arange(count), :2, numpy.arange(count)] = moved[:, :, -1] / self.size
            by_input[numpy.arange(count), 2, numpy.arange(count)] = dangle[:, -1]
            jacobian = numpy.concatenate([jacobian, by_input.reshape(3 * count, count)], axis=1)
        residuals = numpy.concatenate([(placed - self.poses[:, :2]) / self.size,
                                       wrap(angle + placement["angle"] - self.poses[:, 2])[:, None]], axis=1)
        return residuals.ravel(), jacobian


def _fit(problem: _Problem, z: numpy.ndarray, angle: numpy.ndarray):
    """Placements (rows x0, y0, angle, scale) of local points ``z`` and link angles (..., N), and their rms misfit."""
    fixed = problem.placement
    w, goal = problem.target, problem.poses[:, 2]
    with numpy.errstate(all="ignore"):
        if "angle" in problem.frame:
            turn = numpy.angle(numpy.mean(numpy.exp(1j * (goal - angle)), axis=-1))
        else:
            turn = numpy.full(z.shape[:-1], fixed["angle"])
        rz = numpy.exp(1j * turn)[..., None] * z
        origin = complex(fixed["x0"], fixed["y0"])
        shift_free = "x0" in problem.frame or "y0" in problem.frame
        if "scale" in problem.frame:
            dz = rz - rz.mean(axis=-1, keepdims=True) if shift_free else rz
            dw = w - w.mean() if shift_free else w - origin
            scale = numpy.sum((numpy.conj(dz) * dw).real, axis=-1) / numpy.sum(numpy.abs(dz) ** 2, axis=-1)
        else:
            scale = numpy.full(z.shape[:-1], fixed["scale"])
        shift = numpy.full(z.shape[:-1], origin)
        if shift_free:
            offset = numpy.mean(w - origin - scale[..., None] * rz, axis=-1)
            shift = shift + (offset.real if "x0" in problem.frame else 0.0) + (
                1j * offset.imag if "y0" in problem.frame else 0.0)
        placed = shift[..., None] + scale[..., None] * rz
        misfit = (numpy.mean(numpy.abs(placed - w) ** 2, axis=-1) / problem.size ** 2
                  + numpy.mean(wrap(angle + turn[..., None] - goal) ** 2, axis=-1))
    misfit = numpy.where(numpy.isfinite(misfit) & (scale > 0), numpy.sqrt(misfit), numpy.inf)
    return numpy.stack([shift.real, shift.imag, turn, scale], axis=-1), misfit


def _starts(problem: _Problem, rows: numpy.ndarray, signs: list, count: int, given: int):
    """The ``count`` closest starts (misfit, unknowns, branch signs), the ``given`` first designs kept first."""
    timed = problem.timed
    sweep = timed if timed is not None else numpy.linspace(-math.pi, math.pi, _SWEEP, endpoint=False)
    values, ok = problem.outputs.batch(rows, signs, sweep)
    z = numpy.where(ok, values[0] + 1j * values[1], numpy.nan)
    angle = numpy.where(ok, numpy.broadcast_to(sweep, ok.shape) if problem.input_is_angle else values[2], numpy.nan)
    fits = []
    turns = problem.poses[:, 2] - problem.poses[0, 2]
    for first in range(0, len(rows), _CHUNK):
        part = slice(first, first + _CHUNK)
        if timed is not None:
            placements, misfit = _fit(problem, z[part], angle[part])  # the inputs are given: (M, N)
            fits += [(float(misfit[m]), first + m, None, placements[m]) for m in range(len(misfit))]
            continue
        a = angle[part]  # (M, S)
        if "angle" in problem.frame:
            wanted = a[:, :, None] + turns[None, None, :]  # (M, S first, N)
        else:
            wanted = numpy.broadcast_to((problem.poses[:, 2] - problem.placement["angle"])[None, None, :],
                                        a.shape + (len(turns),))
        # the closest angle has the largest cosine of the difference: cos a cos w + sin a sin w, (M, S first, N, S)
        closeness = (numpy.cos(a)[:, None, None, :] * numpy.cos(wanted)[..., None]
                     + numpy.sin(a)[:, None, None, :] * numpy.sin(wanted)[..., None])
        picks = numpy.argmax(numpy.where(numpy.isnan(closeness), -numpy.inf, closeness), axis=-1)  # (M, S, N)
        m_index = numpy.arange(a.shape[0])[:, None, None]
        placements, misfit = _fit(problem, z[part][m_index, picks], a[m_index, picks])
        best = numpy.argmin(misfit, axis=1)
        for m in range(a.shape[0]):
            fits.append((float(misfit[m, best[m]]), first + m, picks[m, best[m]], placements[m, best[m]]))
    chosen_fits = []
    order = sorted(range(len(fits)), key=lambda k: (k >= given, fits[k][0]))
    for k in order:
        misfit, m, picks, placement = fits[k]
        if not math.isfinite(misfit):
            continue
        unknowns = numpy.concatenate([rows[m], [placement[FRAME_NAMES.index(name)] for name in problem.frame]])
        unknowns[len(problem.free):] = numpy.clip(unknowns[len(problem.free):], problem.bounds[len(problem.free):, 0],
                                                  problem.bounds[len(problem.free):, 1])
        if timed is None:
            unknowns = numpy.concatenate([unknowns, sweep[picks]])
        chosen_fits.append((misfit, unknowns, signs[m]))
        if len(chosen_fits) == count:
            break
    return chosen_fits


def synthesize_motion(linkage: Linkage, point: str | None, angle: str, poses: ArrayLike,
                      free: Mapping[str, tuple[float, float]], *, values: Mapping[str, float] | None = None,
                      frame: Sequence[str] = FRAME_NAMES, placement: Mapping[str, float] | None = None,
                      frame_bounds: Mapping[str, tuple[float, float]] | None = None, timed: ArrayLike | None = None,
                      branches: Mapping[str, int] | None = None, starts: int = 12, seed: int | None = 0,
                      evaluations: int = 1000, tolerance: float = 1e-15) -> MotionSynthesis:
    """A design of ``linkage`` whose link (``point`` and its ``angle`` output) passes through ``poses``, verified.

    ``poses`` are rows ``(x, y, angle)`` (radians); ``point`` None is the link's
    :func:`frame_point`.  ``free`` maps each parameter that may change
    to its bounds; ``values`` gives every other parameter (and, if it gives the free ones too,
    that design is the first start).  ``frame`` names the free parts of the placement
    (:data:`FRAME_NAMES`; ``()`` keeps the linkage where it is), ``placement`` the values of the
    fixed ones, ``frame_bounds`` optional bounds of free ones.  ``timed`` is the input's value at
    each pose, or None to find those too.  ``branches`` fixes branch signs by name.  The ``starts``
    closest feasible designs are refined with at most ``evaluations`` residual evaluations each;
    the search stops at the first verified design below 1e-12.  Returns the best verified design,
    or the closest one with ``assembled`` False and its reason; ``ValueError`` for bad input.

    Parameters
    ----------
    linkage : Linkage
        Any linkage with one input.
    point : str or None
        A point on the guided link (None: the link's frame point).
    angle : str
        The output that is the guided link's angle.
    poses : array_like
        The poses, rows (x, y, angle) in radians.
    free : mapping of str to (float, float)
        Each parameter that may change, and its bounds.
    values : mapping of str to float, optional
        Every other parameter.
    frame : sequence of str, optional
        The free parts of the placement (default all; ``()`` keeps it fixed).
    placement : mapping of str to float, optional
        The values of its fixed parts.
    frame_bounds : mapping of str to (float, float), optional
        Bounds of its free parts.
    timed : array_like, optional
        The input's value at each pose, or None (default) to find them too.
    branches : mapping of str to int, optional
        Branch signs to keep.
    starts, seed, evaluations, tolerance : optional
        The search, as for :func:`synthesize_path` (defaults 12, 0, 1000, 1e-15).

    Returns
    -------
    MotionSynthesis
        The best verified design, or the closest with ``assembled`` False and its reason.

    Raises
    ------
    ValueError
        For bad input.

    Examples
    --------
    >>> import symlink
    >>> truth = {"a": 1.0, "b": 3.0, "c": 2.5, "d": 3.2}
    >>> poses = symlink.link_poses(symlink.fourbar(), "B", "beta", truth, [0.3, 0.9, 1.5, 2.1])
    >>> found = symlink.synthesize_motion(symlink.fourbar(), "B", "beta", poses,
    ...                                   {"a": (0.5, 2.0), "b": (2.0, 4.0), "c": (1.5, 3.5)},
    ...                                   values={"d": 3.2}, frame=(), timed=[0.3, 0.9, 1.5, 2.1])
    >>> found.assembled, found.error < 1e-12, round(found.design["c"], 9)
    (True, True, 2.5)
    """
    check_linkage(linkage, "motion generation", newton=True)
    if not linkage.has_closed_form and timed is None:
        raise ValueError(f"{linkage.name} has no closed form: motion generation of a Newton-solved linkage needs "
                         "the input at each pose (timed); without timing it is not supported yet")
    names = _outputs(linkage, frame_point(linkage, angle) if point is None else point, angle)
    array = numpy.asarray(poses, dtype=float)
    if array.ndim != 2 or array.shape[1] != 3 or len(array) < 2:
        raise ValueError(f"the poses must be at least two rows of (x, y, angle), got shape {array.shape}")
    if not numpy.all(numpy.isfinite(array)):
        raise ValueError("the poses must be finite numbers")
    bounds, fixed = free_bounds(linkage, free, {k: v for k, v in (values or {}).items() if k not in free})
    unknown_frame = [name for name in frame if name not in FRAME_NAMES]
    if unknown_frame or len(set(frame)) != len(frame):
        raise ValueError(f"frame names the free parts of the placement among {', '.join(FRAME_NAMES)}, each once; "
                         f"got {tuple(frame)!r}")
    fixed_placement = {k: float(v) for k, v in (placement or {}).items()}
    if set(fixed_placement) - set(FRAME_NAMES) or not fixed_placement.get("scale", 1.0) > 0:
        raise ValueError(f"placement gives values of {', '.join(FRAME_NAMES)} (scale positive), got {placement!r}")
    for name, bound in (frame_bounds or {}).items():
        if name not in frame or not float(bound[0]) < float(bound[1]):
            raise ValueError(f"frame_bounds bounds free parts of the placement ({', '.join(frame) or 'none'}) with "
                             f"low < high; got {name!r}: {bound!r}")
    inputs = None if timed is None else numpy.asarray(timed, dtype=float)
    if inputs is not None and (inputs.shape != (len(array),) or not numpy.all(numpy.isfinite(inputs))):
        raise ValueError(f"{len(array)} poses need {len(array)} finite input values, got shape {inputs.shape}")
    chosen = check_branches(linkage, branches)
    check_starts(starts, evaluations, sample_count(linkage) + 1)  # the user's design besides
    problem = _Problem(linkage, names, array, bounds, fixed, frame, fixed_placement, inputs,
                       {k: (float(v[0]), float(v[1])) for k, v in (frame_bounds or {}).items()})
    given = {k: float(v) for k, v in (values or {}).items()}
    first = [([given[name] for name in problem.free], chosen)] if all(name in given for name in problem.free) else []
    rng = numpy.random.default_rng(seed)
    rows, signs = sampled_designs(linkage, bounds, rng, sample_count(linkage), chosen, first)
    found = _starts(problem, rows, signs, starts, len(first))
    if not found:
        raise ValueError(f"no design of {linkage.name} within the bounds is assembled at the poses; widen the bounds "
                         "or change the fixed values")
    best: MotionSynthesis | None = None
    spent = 0
    for _, y0, sign in found:
        problem.outputs.assembly = dict(sign) if problem.outputs.newton else None  # continued by the refinement
        result = refine(lambda y: problem.residuals(y, sign), y0, evaluations, tolerance)
        if result is None:
            continue
        y, _, used = result
        spent += used
        candidate = _verified(problem, y, sign, spent)
        if best is None or (candidate.assembled, -candidate.error) > (best.assembled, -best.error):
            best = candidate
        if best.assembled and best.error < _DONE:
            break
    if best is None:
        raise ValueError("no start could be refined")
    return MotionSynthesis(**{**best.__dict__, "evaluations": spent})


def _verified(problem: _Problem, y: numpy.ndarray, branches: Mapping[str, float],
              evaluations: int) -> MotionSynthesis:
    design, placement = problem.split(y)
    inputs = problem.timed if problem.timed is not None else y[problem.width:]
    newton = problem.outputs.newton
    assembly: dict[str, float] = {}
    if newton:  # the assembly the refinement continued, found again at y: its unknowns at the first input
        problem.outputs.at(y[:len(problem.free)], numpy.asarray(inputs, dtype=float), branches)
        assembly = dict(problem.outputs.assembly or branches)
        branches = assembly
    reached = link_poses(problem.linkage, problem.names[0][:-2], problem.names[2], design, inputs, branches, placement)
    position = numpy.hypot(*(reached[:, :2] - problem.poses[:, :2]).T)
    turned = wrap(reached[:, 2] - problem.poses[:, 2])
    why = "not assembled at every pose" if not numpy.all(numpy.isfinite(position)) else ""
    if not why:
        why = branch_break(problem.linkage, design, branches, numpy.asarray(inputs, dtype=float))
    error = max(float(numpy.max(position)) / problem.size, float(numpy.max(numpy.abs(turned))))
    return MotionSynthesis(problem.linkage.name, problem.names[0][:-2], problem.names[2], design, placement,
                           {} if newton else {k: int(v) for k, v in branches.items()}, tuple(map(float, inputs)),
                           tuple(map(float, position)), tuple(map(float, turned)), error if not why else math.inf,
                           not why, evaluations, why, assembly, problem.size)
