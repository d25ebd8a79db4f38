"""Shape targets: a curve without timing, scale, rotation or position, matched by a shape distance, then placed.

A designer often knows the *shape* of the path wanted (a D-shaped foot path, a straight stretch)
but not where it sits, how large it is or how it is turned.  :func:`shape_distance` compares
two curves given as points, blind to all of that:

* **closed** curves by Fourier descriptors: each is resampled at equal arc length, centred
  (the descriptors without the constant term), and the descriptors of one are correlated with
  the other's over every starting point at once (a cyclic shift of the samples multiplies the
  k-th descriptor by ``exp(-2 pi i k s / M)``, so one inverse FFT gives them all); the best
  complex factor (scale and turn) leaves the distance
  ``sqrt(1 - |<a, b>|^2 / (|a|^2 |b|^2))``, 0 for similar curves and at most 1; both
  directions of travel are tried, and ``harmonics`` may keep only the low descriptors (the
  overall shape, not the noise);
* **open** curves by a normalised arc-length resampling of both, centred, with the same
  similarity alignment (both directions);
* **partial** targets (an open piece of a closed path) against every window of the closed
  curve (its starting point and its length as a fraction of the whole).

:func:`similarity_fit` gives the placement (``x0, y0, angle, scale`` as in
:mod:`symlink.synthesis.general`) that brings corresponding points closest, and
:func:`shape_search` ranks sampled designs of any one-input linkage (with a closed form) by the
shape distance of a point's path to the target, and places the best by its similarity fit.
:func:`synthesize_shape` then refines the best by exact gradients (the untimed path fit's
residuals, the placement free) until the point passes through the target points, and verifies
the design with the linkage's own solver: a shape the linkage can trace is matched to rounding,
not to the sampling's resolution.

>>> t = numpy.linspace(0, 2 * math.pi, 60, endpoint=False)
>>> ellipse = numpy.stack([2 * numpy.cos(t), numpy.sin(t)], axis=1)
>>> moved = similarity_transform(ellipse[::-1], {"x0": 3.0, "y0": -1.0, "angle": 0.4, "scale": 0.5})
>>> shape_distance(ellipse, moved) < 1e-3, shape_distance(ellipse, numpy.stack([numpy.cos(t), numpy.sin(t)], 1)) > 0.1
(True, True)
"""
from __future__ import annotations

import heapq
import math
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy
from numpy.typing import ArrayLike

from ..common.display import record_html
from ..common.limits import available_memory, require_memory, require_time
from ..symbolic.linkage import Linkage
from .design_fit import DesignOutputs, check_branches, check_linkage, free_bounds, refine, sampled_designs
from .general import FRAME_NAMES, PathSynthesis, path_residuals, synthesize_path, traced_points
from .path import check_starts, ordered_inputs, ordered_inputs_jacobian

__all__ = ["shape_distance", "similarity_fit", "similarity_transform", "resampled", "shape_search", "ShapeMatch",
           "synthesize_shape", "ShapeSynthesis", "REACHED",
           "KINDS", "SAMPLES"]

#: What a target curve may be.
KINDS = ("closed", "open", "partial")
#: Points each curve is resampled to at equal arc length.
SAMPLES = 256
_WINDOWS = 48                                   # partial targets: starting points along the closed curve ...
_SPANS = tuple(numpy.linspace(0.05, 1.0, 39))   # ... and lengths, as fractions of it
_SWEEP = 360                                    # input values over a turn, tracing a design's path
_COARSE = 64                                    # partial targets: samples of a path when ranking windows
_REFINED = 4                                    # closed, partial: this many times ``keep`` designs refined
#: Seconds a sampled design takes to trace and rank, at most (measured 1 ms closed, 1 ms open, 10 ms partial on a
#: shared machine, a four-bar): a shape search is estimated before it starts.
SECONDS_PER_DESIGN = 0.01
#: Bytes of the arrays a chunk of designs is traced into, at most: designs are traced this much at a time.
CHUNK_BYTES = 64 * 10**6


def bytes_per_design(free: int) -> int:
    """Bytes a design needs while its chunk is traced, with ``free`` free parameters: at each of the input values,
    the point's two coordinates with their slopes by the free parameters and by the input, the path, the mask and
    NumPy's temporaries (measured 72 to 163 bytes a value from one to seven free parameters; counted as 8 bytes
    times ``2 (free + 2) + 8``)."""
    return _SWEEP * 8 * (2 * (free + 2) + 8)


def design_chunk(free: int, available: int | None = None) -> int:
    """Designs traced at once with ``free`` free parameters: :data:`CHUNK_BYTES` of arrays, or a quarter of the
    memory available (:func:`symlink.common.limits.available_memory`) where that is less."""
    room = available_memory() if available is None else available
    budget = CHUNK_BYTES if room is None else min(CHUNK_BYTES, room // 4)
    return max(1, budget // bytes_per_design(free))


def _complex(points: ArrayLike, least: int = 3) -> numpy.ndarray:
    array = numpy.asarray(points, dtype=float)
    if array.ndim != 2 or array.shape[1] != 2 or len(array) < least:
        raise ValueError(f"a curve is at least {least} rows of (x, y), got shape {array.shape}")
    if not numpy.all(numpy.isfinite(array)):
        raise ValueError("a curve's points must be finite numbers")
    return array[:, 0] + 1j * array[:, 1]


def resampled(points: ArrayLike, count: int = SAMPLES, closed: bool = True) -> numpy.ndarray:
    """The curve through ``points`` (rows x, y) at ``count`` points equally spaced along its length, as complex numbers.

    A closed curve's last point joins its first (the samples start at the first point and do not repeat it).

    >>> resampled([[0, 0], [2, 0], [2, 2], [0, 2]], 8).round(12).tolist()
    [0j, (1+0j), (2+0j), (2+1j), (2+2j), (1+2j), 2j, 1j]
    """
    z = _complex(points, 2)
    path = numpy.concatenate([z, z[:1]]) if closed else z
    arc = numpy.concatenate([[0.0], numpy.cumsum(numpy.abs(numpy.diff(path)))])
    if not arc[-1] > 0:
        raise ValueError("the curve has no length: its points are all the same")
    where = numpy.linspace(0.0, arc[-1], count, endpoint=not closed)
    return numpy.interp(where, arc, path.real) + 1j * numpy.interp(where, arc, path.imag)


def similarity_transform(points: ArrayLike, placement: Mapping[str, float]) -> numpy.ndarray:
    """Points (rows x, y) moved by a placement: ``(x0, y0) + scale * R(angle) p`` (missing parts: no move).

    Parameters
    ----------
    points : array_like
        Rows (x, y).
    placement : mapping of str to float
        ``x0``, ``y0``, ``angle`` and ``scale``; missing parts do not move.

    Returns
    -------
    numpy.ndarray
        The moved points, rows (x, y).

    Examples
    --------
    >>> import math, symlink
    >>> symlink.similarity_transform([[1.0, 0.0]], {"angle": math.pi / 2, "scale": 2.0}).round(12).tolist()
    [[0.0, 2.0]]
    """
    where = {"x0": 0.0, "y0": 0.0, "angle": 0.0, "scale": 1.0, **placement}
    z = _complex(points, 1)
    moved = complex(where["x0"], where["y0"]) + where["scale"] * numpy.exp(1j * where["angle"]) * z
    return numpy.stack([moved.real, moved.imag], axis=1)


def similarity_fit(source: ArrayLike, target: ArrayLike) -> tuple[dict[str, float], float]:
    """The placement bringing ``source`` points closest to the corresponding ``target`` points, and the rms left.

    Least squares over shift, turn and scale (``x0, y0, angle, scale``): with both centred, the
    complex factor ``scale * e^{i angle} = <s, t> / <s, s>``.

    >>> fit, rms = similarity_fit([[0, 0], [1, 0], [0, 1]], [[1, 1], [1, 3], [-1, 1]])
    >>> {k: round(v, 12) for k, v in fit.items()}, rms < 1e-12
    ({'x0': 1.0, 'y0': 1.0, 'angle': 1.570796326795, 'scale': 2.0}, True)
    """
    s, t = _complex(source, 2), _complex(target, 2)
    if s.shape != t.shape:
        raise ValueError(f"a similarity fit pairs points: {len(s)} source and {len(t)} target points")
    ds, dt = s - s.mean(), t - t.mean()
    weight = float(numpy.sum(numpy.abs(ds) ** 2))
    if not weight > 0:
        raise ValueError("the source points are all the same: no turn or scale fits them")
    factor = numpy.sum(numpy.conj(ds) * dt) / weight
    shift = t.mean() - factor * s.mean()
    rms = float(numpy.sqrt(numpy.mean(numpy.abs(shift + factor * s - t) ** 2)))
    return {"x0": float(shift.real), "y0": float(shift.imag), "angle": float(numpy.angle(factor)),
            "scale": float(abs(factor))}, rms


def _aligned_distance(a: numpy.ndarray, b: numpy.ndarray) -> numpy.ndarray:
    """``sqrt(1 - |<a, b>|^2 / (|a|^2 |b|^2))`` of centred rows (the last axis), both directions of ``b``."""
    a = a - a.mean(axis=-1, keepdims=True)
    b = b - b.mean(axis=-1, keepdims=True)
    norms = numpy.sum(numpy.abs(a) ** 2, axis=-1) * numpy.sum(numpy.abs(b) ** 2, axis=-1)
    with numpy.errstate(all="ignore"):
        forward = numpy.abs(numpy.sum(numpy.conj(a) * b, axis=-1)) ** 2 / norms
        backward = numpy.abs(numpy.sum(numpy.conj(a) * b[..., ::-1], axis=-1)) ** 2 / norms
    best = numpy.maximum(forward, backward)
    return numpy.where(norms > 0, numpy.sqrt(numpy.clip(1.0 - best, 0.0, 1.0)), 1.0)


def _descriptors(z: numpy.ndarray, harmonics: int | None) -> numpy.ndarray:
    """Fourier descriptors of closed curves sampled at equal arc length (rows), the constant term and, with
    ``harmonics``, those above it set to zero."""
    spectrum = numpy.fft.fft(z, axis=-1) / z.shape[-1]
    spectrum[..., 0] = 0.0
    if harmonics is not None:
        k = numpy.fft.fftfreq(z.shape[-1], 1.0 / z.shape[-1])
        spectrum[..., numpy.abs(k) > harmonics] = 0.0
    return spectrum


def _closed_distance(a: numpy.ndarray, b: numpy.ndarray, harmonics: int | None) -> float:
    """The shape distance of two closed curves (equal-arc samples) over every starting point, both ways.

    The correlation of the descriptors over the starting point ``s`` is the trigonometric sum
    ``c(s) = sum_k conj(A_k) B_k e^{2 pi i k s / M}``: one inverse FFT gives it at whole samples,
    and a golden-section search refines the best between its neighbours (a start between two
    samples).
    """
    A = _descriptors(a, harmonics)
    k = numpy.fft.fftfreq(len(a), 1.0 / len(a))
    best = 0.0
    for b_way in (b, b[::-1]):
        B = _descriptors(b_way, harmonics)
        norms = float(numpy.sum(numpy.abs(A) ** 2) * numpy.sum(numpy.abs(B) ** 2))
        if not norms > 0:
            continue
        product = numpy.conj(A) * B
        cross = numpy.abs(numpy.fft.ifft(product) * len(a))
        low, high = float(numpy.argmax(cross)) - 1.0, float(numpy.argmax(cross)) + 1.0

        def size(shift: float) -> float:
            return -abs(numpy.sum(product * numpy.exp(2j * math.pi * k * shift / len(a))))

        golden = (math.sqrt(5.0) - 1.0) / 2.0
        left, right = high - golden * (high - low), low + golden * (high - low)
        f_left, f_right = size(left), size(right)
        for _ in range(60):
            if f_left < f_right:
                high, right, f_right = right, left, f_left
                left = high - golden * (high - low)
                f_left = size(left)
            else:
                low, left, f_left = left, right, f_right
                right = low + golden * (high - low)
                f_right = size(right)
        peak = max(float(numpy.max(cross)), -f_left, -f_right)
        best = max(best, peak ** 2 / norms)
    return math.sqrt(min(max(1.0 - best, 0.0), 1.0))


def _coarse_closed_distance(a: numpy.ndarray, b: numpy.ndarray, harmonics: int | None) -> float:
    """:func:`_closed_distance` with the start at whole samples only (one inverse FFT a direction): for ranking."""
    A = _descriptors(a, harmonics)
    best = 0.0
    for b_way in (b, b[::-1]):
        B = _descriptors(b_way, harmonics)
        norms = float(numpy.sum(numpy.abs(A) ** 2) * numpy.sum(numpy.abs(B) ** 2))
        if norms > 0:
            best = max(best, float(numpy.max(numpy.abs(numpy.fft.ifft(numpy.conj(A) * B)) * len(a))) ** 2 / norms)
    return math.sqrt(min(max(1.0 - best, 0.0), 1.0))


def _partial_distance(piece: numpy.ndarray, whole: numpy.ndarray, fine: bool = True) -> tuple[float, float, float]:
    """The least distance of an open ``piece`` (equal-arc samples) to windows of a closed curve, with the window
    (start, span) as fractions of the closed curve's length (``fine``: refined between the grid's values)."""
    count = len(whole)
    arc = numpy.linspace(0.0, 2.0, 2 * count + 1)  # two turns, so that a window may cross the seam
    doubled = numpy.concatenate([whole, whole, whole[:1]])
    fractions = numpy.linspace(0.0, 1.0, len(piece))
    starts = numpy.linspace(0.0, 1.0, _WINDOWS, endpoint=False)
    spans = numpy.array(_SPANS)
    where = starts[:, None, None] + spans[None, :, None] * fractions[None, None, :]  # (W, S, N)
    windows = numpy.interp(where, arc, doubled.real) + 1j * numpy.interp(where, arc, doubled.imag)
    distance = _aligned_distance(numpy.broadcast_to(piece, windows.shape), windows)
    w, s = numpy.unravel_index(numpy.argmin(distance), distance.shape)
    best = (float(distance[w, s]), float(starts[w]), float(spans[s]))
    if not fine:
        return best
    # refine the best window between the grid's values: a shrinking 5 x 5 pattern around it
    step_start, step_span = 1.0 / _WINDOWS, float(spans[1] - spans[0])
    for _ in range(24):
        trial_starts = best[1] + step_start * numpy.linspace(-1.0, 1.0, 5)
        trial_spans = numpy.clip(best[2] + step_span * numpy.linspace(-1.0, 1.0, 5), 1e-3, 1.0)
        where = (trial_starts[:, None, None] % 1.0 + trial_spans[None, :, None] * fractions[None, None, :])
        windows = numpy.interp(where, arc, doubled.real) + 1j * numpy.interp(where, arc, doubled.imag)
        trial = _aligned_distance(numpy.broadcast_to(piece, windows.shape), windows)
        w, s = numpy.unravel_index(numpy.argmin(trial), trial.shape)
        if trial[w, s] < best[0]:
            best = (float(trial[w, s]), float(trial_starts[w] % 1.0), float(trial_spans[s]))
        step_start, step_span = step_start / 2, step_span / 2
    return best


def shape_distance(first: ArrayLike, second: ArrayLike, kind: str = "closed", *, samples: int = SAMPLES,
                   harmonics: int | None = None) -> float:
    """How far the shapes of two curves (rows x, y) differ, blind to position, turn, scale, start and direction.

    ``kind``: ``"closed"`` (Fourier descriptors), ``"open"`` (arc-length resampling, similarity
    aligned) or ``"partial"`` (``first`` an open piece of the closed ``second``).  0 for similar
    curves, at most 1; ``harmonics`` keeps the descriptors up to that order (closed curves only).

    Parameters
    ----------
    first, second : array_like
        The two curves, rows (x, y).
    kind : {"closed", "open", "partial"}, optional
        Closed curves (default), open ones, or ``first`` a piece of the closed ``second``.
    samples : int, optional
        Resampling points (default 256).
    harmonics : int, optional
        Fourier descriptors kept (closed curves only).

    Returns
    -------
    float
        0 for similar curves, at most 1.

    Examples
    --------
    >>> import math, numpy, symlink
    >>> turn = numpy.linspace(0.0, 2 * math.pi, 64, endpoint=False)
    >>> circle = numpy.stack([numpy.cos(turn), numpy.sin(turn)], axis=1)
    >>> round(symlink.shape_distance(circle, 3 * circle[::-1] + 1), 12)  # moved, scaled, reversed: the same shape
    0.0
    >>> symlink.shape_distance(circle, circle * [2.0, 1.0]) > 0.1  # an ellipse is not a circle
    True
    """
    if kind not in KINDS:
        raise ValueError(f"kind is one of {', '.join(KINDS)}, got {kind!r}")
    if samples < 8:
        raise ValueError(f"resample to at least 8 points, got {samples}")
    _complex(first), _complex(second)  # ValueError for fewer than three points, or not finite
    if kind == "closed":
        return _closed_distance(resampled(first, samples), resampled(second, samples), harmonics)
    if kind == "open":
        return float(_aligned_distance(resampled(first, samples, closed=False), resampled(second, samples,
                                                                                            closed=False)))
    return _partial_distance(resampled(first, samples, closed=False), resampled(second, samples))[0]


@dataclass(frozen=True)
class ShapeMatch:
    """A design whose point's path has the target's shape: its distance, and the placement that fits it best.

    ``design`` holds every parameter; ``placement`` (``x0, y0, angle, scale``) moves the
    design's path onto the target (least squares over the matched points); ``rms`` is what that
    fit leaves over the target's size; ``curve`` the placed path (rows x, y) over a turn of the
    input (or its assembled stretch); ``inputs`` the input's value where each target point is
    matched on it (by arc length), the start of :func:`synthesize_shape`'s refinement.
    """

    design: dict[str, float]
    branches: dict[str, int]
    distance: float
    placement: dict[str, float]
    rms: float
    curve: numpy.ndarray
    inputs: tuple[float, ...] = ()

    _repr_html_ = record_html  # a notebook shows the fields as a table


def _traced(outputs: DesignOutputs, rows: numpy.ndarray, signs, sweep: numpy.ndarray):
    values, ok = outputs.batch(rows, signs, sweep)
    return values[0] + 1j * values[1], ok


def shape_search(linkage: Linkage, point: str, target: ArrayLike, free: Mapping[str, tuple[float, float]], *,
                 kind: str = "closed", values: Mapping[str, float] | None = None,
                 branches: Mapping[str, int] | None = None, designs: int = 2000, keep: int = 5,
                 seed: int | None = 0, harmonics: int | None = None,
                 candidates: Sequence[Mapping[str, float]] = ()) -> list[ShapeMatch]:
    """The ``keep`` designs of ``linkage`` whose ``point`` traces the shape of ``target`` best, each placed on it.

    ``designs`` random designs (free parameters uniform within their bounds, branches random
    unless fixed), after the ``candidates`` given (complete designs), are traced over a turn of the
    input; a closed target needs a design assembled over the whole turn, an open or partial one
    takes the longest assembled stretch.  They are ranked by :func:`shape_distance`; each kept
    one is placed by the similarity fit of its path, resampled at the matched points, to the
    target, with the input where each target point is matched on its path (``inputs``).
    ``ValueError`` for bad input or when no design is assembled.
    """
    check_linkage(linkage, "shape matching")
    if kind not in KINDS:
        raise ValueError(f"kind is one of {', '.join(KINDS)}, got {kind!r}")
    if point not in linkage.points:
        raise ValueError(f"{linkage.name} has no point {point!r}; it has {', '.join(linkage.points)}")
    wanted = _complex(target)
    target_rows = numpy.stack([wanted.real, wanted.imag], axis=1)
    bounds, fixed = free_bounds(linkage, free, {k: v for k, v in (values or {}).items() if k not in free})
    chosen = check_branches(linkage, branches)
    if designs < 0 or keep < 1:
        raise ValueError("designs must be at least 0 and keep at least 1")
    closed = kind == "closed"
    goal = resampled(target_rows, SAMPLES, closed=closed)
    coarse_goal = resampled(target_rows, _COARSE // 2, closed=False)  # partial: windows ranked at fewer samples
    outputs = DesignOutputs(linkage, (f"{point}_x", f"{point}_y"), tuple(bounds), fixed)
    require_time(designs, SECONDS_PER_DESIGN, f"a shape search of {designs:,} designs", "designs")
    chunk = design_chunk(len(bounds))
    require_memory(chunk, bytes_per_design(len(bounds)), f"tracing {chunk:,} designs at once (a chunk)")
    first = [([float(c[name]) for name in bounds], chosen) for c in candidates]
    rng = numpy.random.default_rng(seed)
    sweep = numpy.linspace(-math.pi, math.pi, _SWEEP, endpoint=False)
    # the best kept whatever the number of designs: those refined, and as many again as can still be chosen
    kept = _REFINED * keep + keep if kind != "open" else keep
    scored: list = []  # (distance, index, z, q, row, signs) of the best so far
    offset = 0
    for begin in range(0, len(first) + designs, chunk):  # the same random numbers in the same order, chunk by chunk
        given = first[begin:begin + chunk]
        drawn = min(chunk - len(given), len(first) + designs - begin - len(given))
        rows, signs = sampled_designs(linkage, bounds, rng, drawn, chosen, given)
        traced, ok = _traced(outputs, rows, signs, sweep)
        for index in range(len(rows)):
            found = _path(traced[index], ok[index], closed, sweep)
            if found is None:
                continue
            z, q = found
            curve = resampled(numpy.stack([z.real, z.imag], axis=1), SAMPLES, closed=closed or kind == "partial")
            if kind == "closed":
                distance = _coarse_closed_distance(goal, curve, harmonics)
            elif kind == "open":
                distance = float(_aligned_distance(goal, curve))
            else:
                distance = _partial_distance(coarse_goal, curve[::SAMPLES // _COARSE], fine=False)[0]
            scored.append((distance, offset + index, z, q, rows[index].copy(), signs[index]))
        del traced, ok
        scored = heapq.nsmallest(kept, scored, key=lambda item: (item[0], item[1]))
        offset += len(rows)
    if kind != "open":  # the coarse distances rank; the best are refined between samples (start, window)
        scored[:_REFINED * keep] = [(_fine_distance(goal, z, kind, harmonics), index, z, q, row, sign)
                                    for _, index, z, q, row, sign in scored[:_REFINED * keep]]
    if not scored:
        raise ValueError(f"no design of {linkage.name} within the bounds traces a " + (
            "whole turn" if closed else "path") + "; widen the bounds or change the fixed values")
    scored.sort(key=lambda item: (item[0], item[1]))
    size = float(numpy.hypot(numpy.ptp(wanted.real), numpy.ptp(wanted.imag))) or 1.0
    matches = []
    for distance, index, z, q, row, sign in scored[:keep]:
        placement, rms, inputs = _placed_on(z, q, wanted, kind)
        design = {**fixed, **{name: float(v) for name, v in zip(bounds, row)}}
        moved = similarity_transform(numpy.stack([z.real, z.imag], axis=1), placement)
        matches.append(ShapeMatch(design, dict(sign), distance, placement, rms / size, moved,
                                  tuple(map(float, inputs))))
    return matches


def _fine_distance(goal: numpy.ndarray, z: numpy.ndarray, kind: str, harmonics: int | None) -> float:
    """The shape distance of a target (equal-arc samples) to a traced path, its start or window between samples."""
    curve = resampled(numpy.stack([z.real, z.imag], axis=1), SAMPLES)
    return _closed_distance(goal, curve, harmonics) if kind == "closed" else _partial_distance(goal, curve)[0]


def _path(z: numpy.ndarray, ok: numpy.ndarray, closed: bool,
          sweep: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray] | None:
    """The traced path and its inputs: the whole turn (closed targets need it), else the longest assembled stretch."""
    if numpy.all(ok):
        return z, sweep
    if closed:
        return None
    shift = int(numpy.argmin(ok))  # start the sweep where it is not assembled: a stretch across the seam is whole
    z, ok = numpy.roll(z, -shift), numpy.roll(ok, -shift)
    sweep = numpy.concatenate([sweep[shift:], sweep[:shift] + 2 * math.pi])
    best, start = (0, 0), None
    for k, flag in enumerate(list(ok) + [False]):
        if flag and start is None:
            start = k
        elif not flag and start is not None:
            best = max(best, (k - start, start))
            start = None
    return (z[best[1]:best[1] + best[0]], sweep[best[1]:best[1] + best[0]]) if best[0] >= 8 else None


def _placed_on(z: numpy.ndarray, q: numpy.ndarray, wanted: numpy.ndarray,
               kind: str) -> tuple[dict[str, float], float, numpy.ndarray]:
    """The best similarity placement of a design's path ``z`` (at inputs ``q``) on the target ``wanted``: over the
    matched starting point and direction (closed), direction (open) or window (partial), by the target's own points;
    with the input where each target point is matched (unwrapped: a closed path's seam crossed smoothly)."""
    target = numpy.stack([wanted.real, wanted.imag], axis=1)
    path, inputs = numpy.concatenate([z, z[:1]]), numpy.concatenate([q, q[:1] + 2 * math.pi])
    if kind == "closed":
        arc = numpy.concatenate([[0.0], numpy.cumsum(numpy.abs(numpy.diff(path)))])
        chords = numpy.concatenate([[0.0], numpy.cumsum(numpy.abs(numpy.diff(wanted)))])
        fraction = chords / (chords[-1] + abs(wanted[-1] - wanted[0]))
        candidates = [numpy.mod(start + way * fraction, 1.0) for way in (1.0, -1.0)
                      for start in numpy.linspace(0.0, 1.0, 4 * SAMPLES, endpoint=False)]
    else:
        chords = numpy.concatenate([[0.0], numpy.cumsum(numpy.abs(numpy.diff(wanted)))])
        fraction = chords / chords[-1]
        if kind == "partial":
            whole = resampled(numpy.stack([z.real, z.imag], axis=1), SAMPLES)
            _, start, span = _partial_distance(resampled(target, SAMPLES, closed=False), whole)
            candidates = [numpy.mod(start + span * fraction, 1.0), numpy.mod(start + span * (1 - fraction), 1.0)]
        else:
            path, inputs = z, q
            candidates = [fraction, 1.0 - fraction]
        arc = numpy.concatenate([[0.0], numpy.cumsum(numpy.abs(numpy.diff(path)))])
    best: tuple[dict[str, float], float, numpy.ndarray] | None = None
    for where in candidates:
        at = where * arc[-1]
        sample = numpy.interp(at, arc, path.real) + 1j * numpy.interp(at, arc, path.imag)
        placement, rms = similarity_fit(numpy.stack([sample.real, sample.imag], axis=1), target)
        if best is None or rms < best[1]:
            best = (placement, rms, at)
    assert best is not None
    return best[0], best[1], numpy.unwrap(numpy.interp(best[2], arc, inputs))


#: A refined design that reaches the target points within this (over their size) ends the refinement.
REACHED = 1e-10
_TRACE = 720  # input values over a turn, tracing a refined design's path for its shape distance


@dataclass(frozen=True)
class ShapeSynthesis:
    """A design whose point traces a target shape: the sampled match, and its exact-gradient refinement.

    ``path`` is the refined, verified design (a :class:`~symlink.synthesis.general.PathSynthesis`:
    ``design``, ``placement``, ``branches``, the input at each target point, the distance of
    each from the placed point and ``error``, the largest over the target's size);
    ``match`` the sampled design it started from.  ``sampled_distance`` and ``distance`` are the
    shape distances (:func:`shape_distance`) of the target to the sampled design's path and to
    the refined one's (``curve``, placed; for an open target the stretch from the first target's
    input to the last one's): refinement brings a shape the linkage can trace from the sampling's
    resolution down to rounding.
    """

    kind: str
    path: PathSynthesis
    match: ShapeMatch
    sampled_distance: float
    distance: float
    curve: numpy.ndarray

    _repr_html_ = record_html  # a notebook shows the fields as a table

    @property
    def design(self) -> dict[str, float]:
        """Every parameter of the refined design."""
        return self.path.design

    @property
    def placement(self) -> dict[str, float]:
        """Where the refined design sits: ``x0, y0, angle, scale``."""
        return self.path.placement

    @property
    def error(self) -> float:
        """The largest distance of a target point from the placed point, over the target's size."""
        return self.path.error


def _refined_curve(linkage: Linkage, point: str, found: PathSynthesis, kind: str) -> numpy.ndarray:
    """The refined design's placed path: a turn of the input (closed, partial), else the stretch the targets span."""
    first, last = found.inputs[0], found.inputs[-1]
    sweep = (numpy.linspace(first, last, _TRACE) if kind == "open"
             else first + numpy.linspace(0.0, 2 * math.pi, _TRACE, endpoint=False))
    return traced_points(linkage, point, found.design, sweep, found.branches, found.placement)


def _shape_after(target: numpy.ndarray, curve: numpy.ndarray, kind: str, harmonics: int | None) -> float:
    if not numpy.all(numpy.isfinite(curve)):
        return math.nan  # a closed or partial target on a design whose input no longer turns fully
    if kind == "partial":
        return shape_distance(target, curve, "partial")
    return shape_distance(target, curve, kind, harmonics=harmonics if kind == "closed" else None)


def _refined_match(linkage: Linkage, point: str, target: numpy.ndarray, match: ShapeMatch,
                   free: Mapping[str, tuple[float, float]], evaluations: int):
    """The match's design, placement and inputs moved until the placed point passes through the target points.

    The untimed path fit of :mod:`symlink.synthesis.general`'s residuals
    (:func:`~symlink.synthesis.general.path_residuals`: the free parameters, the placement and the
    input at each target point, with their exact Jacobian), by the accelerated Levenberg-Marquardt
    of path synthesis, from where the shape match put every target point on the design's path.
    The inputs are unknowns as the first one and squared steps to the next (``q_i = q_1 +
    direction * sum(s_k^2)``, as the untimed path fit writes them), so that they stay in order; a
    trial outside the bounds is evaluated at its projection onto them (it slides along a bound),
    one off the assembly, at a toggle or over a turn is refused.  Returns
    ``(design, placement, inputs)``, or None if nothing is feasible.
    """
    names = list(free)
    low, high = (numpy.array([float(free[name][k]) for name in names]) for k in (0, 1))
    positive = numpy.array([name in {p.name for p in linkage.parameters if p.is_positive} for name in names])
    width = len(names) + len(FRAME_NAMES)
    start = numpy.asarray(match.inputs, dtype=float)
    direction = 1.0 if start[-1] >= start[0] else -1.0

    def split(x: numpy.ndarray):
        design = {**match.design, **{name: float(v) for name, v in zip(names, x[:len(names)])}}
        inputs = ordered_inputs(x[width], x[width + 1:], direction)
        return design, dict(zip(FRAME_NAMES, map(float, x[len(names):width]))), inputs

    def projected(x: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
        """``x`` with its free parameters clipped to their bounds, and which were outside."""
        inside = x.copy()
        inside[:len(names)] = numpy.clip(x[:len(names)], low, high)
        return inside, inside != x

    def residuals(x: numpy.ndarray):
        # a trial outside the bounds is evaluated at its projection onto them, the columns of the parameters held
        # at a bound zero: the refinement slides along a bound instead of stopping at it (as the path fit does)
        x, outside = projected(x)
        design, placement, inputs = split(x)
        if (numpy.any(x[:len(names)][positive] <= 0) or not placement["scale"] > 0
                or abs(inputs[-1] - inputs[0]) >= 2 * math.pi or not numpy.all(numpy.isfinite(x))):
            return None
        try:
            r, jacobian = path_residuals(linkage, point, target, design, inputs, names, FRAME_NAMES, placement,
                                         match.branches)
        except ValueError:  # not assembled at an input
            return None
        chain = ordered_inputs_jacobian(x[width + 1:], direction)  # d inputs / d (q_1, s_1 ... s_{N-1})
        jacobian = numpy.concatenate([jacobian[:, :width], jacobian[:, width:] @ chain], axis=1)
        jacobian[:, outside] = 0.0
        return r, jacobian

    x0 = numpy.concatenate([[match.design[name] for name in names], [match.placement[k] for k in FRAME_NAMES],
                            [start[0]], numpy.sqrt(numpy.abs(numpy.diff(start)))])
    found = refine(residuals, x0, evaluations, 1e-15)
    return None if found is None else split(projected(found[0])[0])


def synthesize_shape(linkage: Linkage, point: str, target: ArrayLike, free: Mapping[str, tuple[float, float]], *,
                     kind: str = "closed", values: Mapping[str, float] | None = None,
                     branches: Mapping[str, int] | None = None, designs: int = 2000, refine: int = 3,
                     seed: int | None = 0, harmonics: int | None = None, starts: int = 1, evaluations: int = 2000,
                     candidates: Sequence[Mapping[str, float]] = ()) -> ShapeSynthesis:
    """A design of ``linkage`` whose ``point`` traces the shape of ``target``, placed on it and refined to it.

    :func:`shape_search` ranks ``designs`` sampled designs by their shape distance to the target
    (points in order along the curve, without timing, position, turn or scale) and places the
    best by its similarity fit.  Each of the ``refine`` best in turn is then refined by exact
    gradients from where the match put every target point on its path: the free parameters, the
    placement (shift, turn and scale) and the input at each target point move until the point
    passes through the target points (the untimed path fit's residuals,
    :func:`symlink.synthesis.general.path_residuals`, by the accelerated Levenberg-Marquardt of
    path synthesis, at most ``evaluations`` evaluations; the inputs kept in order, within a turn).
    The refined design is verified by the linkage's own solver through the timed path fit at the
    inputs found (:func:`symlink.synthesis.general.synthesize_path` with ``timed``, the design its
    first start, ``starts`` its own sampled starts besides): every target point on one branch, in
    order, no toggle between them.  It stops at the first design within :data:`REACHED` of the
    target's size, else returns the verified design of the least shape distance.

    ``kind``: ``"closed"`` (the target is a whole closed path: the design's input must turn
    fully), ``"open"`` (the whole path of a design whose input rocks between its limits) or
    ``"partial"`` (a piece of a closed path).  ``ValueError`` for bad input, or when no sampled
    design traces such a path.

    Parameters
    ----------
    linkage : Linkage
        Any linkage with one input.
    point : str
        The tracing point's name.
    target : array_like
        The target curve, rows (x, y) in order along it.
    free : mapping of str to (float, float)
        Each parameter that may change, and its bounds.
    kind : {"closed", "open", "partial"}, optional
        The target is a whole closed path (default), a rocking input's whole path, or a piece of a closed one.
    values : mapping of str to float, optional
        Every other parameter.
    branches : mapping of str to int, optional
        Branch signs to keep.
    designs : int, optional
        How many designs are sampled and ranked by shape (default 2000).
    refine : int, optional
        How many of the best are refined (default 3).
    seed : int or None, optional
        The sampling's seed (default 0).
    harmonics : int, optional
        Fourier descriptors kept (closed curves).
    starts, evaluations : int, optional
        The refinement's own starts and evaluations.
    candidates : sequence of mapping, optional
        Designs to rank besides the sampled ones.

    Returns
    -------
    ShapeSynthesis
        The design, its placement on the target, its shape distance and error.

    Raises
    ------
    ValueError
        For bad input, or when no sampled design traces such a path.

    Examples
    --------
    >>> import math, numpy, symlink
    >>> turn = numpy.linspace(0.0, 2 * math.pi, 24, endpoint=False)
    >>> circle = numpy.stack([3 + 2 * numpy.cos(turn), 1 + 2 * numpy.sin(turn)], axis=1)  # the crank pin's shape
    >>> found = symlink.synthesize_shape(symlink.fourbar(), "B", circle, {"b": (2.5, 3.5)},
    ...                                  values={"a": 1.0, "c": 2.5, "d": 3.2}, designs=50, refine=1)
    >>> found.error < 1e-10, round(found.placement["scale"], 9)  # a crank of 1 placed at twice its size
    (True, 2.0)
    """
    if refine < 1 or starts < 1 or evaluations < 1:
        raise ValueError("refine, starts and evaluations must be at least 1")
    check_starts(refine, evaluations, max(1, designs + len(candidates)), "designs sampled for the shape match",
                 "refine")
    matches = shape_search(linkage, point, target, free, kind=kind, values=values, branches=branches,
                           designs=designs, keep=refine, seed=seed, harmonics=harmonics, candidates=candidates)
    points = numpy.asarray(target, dtype=float)
    best: ShapeSynthesis | None = None
    for match in matches:
        refined = _refined_match(linkage, point, points, match, free, evaluations)
        if refined is None:
            continue  # the match is not assembled at the inputs it put the targets at: the next match
        design, placement, inputs = refined
        try:  # verified by the linkage's own solver along the inputs found (its timed path fit starts at the design)
            found = synthesize_path(linkage, point, points, free, values=design, frame=FRAME_NAMES,
                                    timed=inputs, branches=match.branches or None, starts=starts, seed=seed,
                                    evaluations=evaluations)
        except ValueError:
            continue
        if not found.assembled:
            continue
        curve = _refined_curve(linkage, point, found, kind)
        result = ShapeSynthesis(kind, found, match, match.distance, _shape_after(points, curve, kind, harmonics),
                                curve)
        if best is None or (found.error < REACHED, -_ordered(result.distance)) > (
                best.error < REACHED, -_ordered(best.distance)):
            best = result
        if found.error < REACHED:
            break
    if best is None:
        raise ValueError(f"no refinement of the {len(matches)} best sampled design(s) of {linkage.name} is verified "
                         "along the target (every point on one branch, in order); widen the bounds or sample more "
                         "designs")
    return best


def _ordered(distance: float) -> float:
    return distance if math.isfinite(distance) else math.inf
