"""Drawings of a four-bar with Matplotlib: angle plots, the transmission angle, coupler curves, a solved loop.

Every ``*_figure`` function returns a :class:`matplotlib.figure.Figure` that
pyplot does not know about (nothing global is kept, and it is freed like any
object) and that a notebook displays inline by itself
(:class:`~symlink.plot.inline.NotebookFigure`); :func:`save_figure` writes
one atomically as PNG or SVG, chosen by the file's suffix.  Each also draws
on axes you give it (``ax=``, or ``axes=`` two of them for the two panels of
:func:`angle_figure`), to compose with other plots, and then returns the
figure those axes are on.  Matplotlib is imported only when a drawing is made, so the
``symlink`` command starts fast.

The curves are evaluated by generated solvers that derive positions only,
over a full crank turn sampled every half degree plus the exact toggle angles
where the crank cannot turn fully, so a curve ends exactly where the linkage
stops closing.  Crank angles the linkage cannot reach are shaded.

A coupler point P is given by its distance ``p`` from the joint B and its
angle ``gamma`` measured counter-clockwise from the coupler's direction B->C:
``P = B + p e^{i (beta + gamma)}``; ``gamma = 0, p = b`` is the joint C itself.

>>> figure = angle_figure(0.1, 0.4, 0.25, 0.30)
>>> [axes.get_ylabel() for axes in figure.axes]
['coupler angle β (deg)', 'rocker angle φ (deg)']
>>> from matplotlib.figure import Figure
>>> mine = Figure()
>>> left, right = mine.subplots(1, 2)
>>> transmission_figure(0.1, 0.4, 0.25, 0.30, ax=right) is mine
True
"""
from __future__ import annotations

import io
import math
from pathlib import Path
from functools import lru_cache
from typing import TYPE_CHECKING, Any, Callable, Sequence

import numpy

from ..common.angles import half_turn, wrap
from ..numeric.crank_ranges import TURN_SAMPLES, closing_crank_range, reachable_turn, turn_angles
from ..common.files import write_atomic

if TYPE_CHECKING:  # Matplotlib is imported when a drawing is made; the symbolic side (SymPy) where a figure
    # derives: a coupler curve whose solver is in the disk cache imports none of it (coupler_point_solver)
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import ArrayLike
    from ..numeric.cached_solver import CachedSolver
    from ..symbolic.linkage import Linkage

__all__ = ["coupler_point_linkage", "fourbar_positions", "reachable_turn", "turn_angles",
           "check_coupler_point", "angle_figure", "transmission_figure", "coupler_curve_figure", "draw_loop",
           "MechanismDrawing", "extent", "frame_plane", "save_figure", "figure_bytes", "figure_suffix", "FIGURE_SUFFIXES"]

#: File suffixes :func:`save_figure` writes, and the Matplotlib format of each.
FIGURE_SUFFIXES = {".png": "png", ".svg": "svg"}
#: The loop colours of the MATLAB GUI paper (z1..z4).
LOOP_COLORS = ("red", "yellow", "blue", "green")
#: The usual design limits of the transmission angle (the quick-return synthesis paper), degrees.
TRANSMISSION_LIMITS = (45.0, 135.0)
BRANCH_STYLES = {1: "-", -1: "--"}
LINK_COLORS = {"crank": "tab:red", "coupler": "tab:blue", "rocker": "tab:green"}


# --- evaluation --------------------------------------------------------------
def coupler_point_linkage() -> Linkage:
    """The four-bar of :func:`symlink.mechanism.catalog.fourbar` with a coupler point ``P``.

    ``P = B + p e^{i (beta + gamma)}``: the distance ``p`` from B, at the
    angle ``gamma`` from the coupler's direction B->C (counter-clockwise).

    >>> linkage = coupler_point_linkage()
    >>> linkage.expression("P_x")
    a*cos(theta) + p*cos(beta + gamma)
    """
    from ..mechanism.catalog import fourbar
    from ..symbolic.linkage import Linkage
    from ..symbolic.vectors import Vector, coordinates, lengths
    base = fourbar()
    (p,), (gamma,) = lengths("p"), coordinates("gamma")
    beta = base.roles["coupler"]
    points = dict(base.points)
    crank_end = base.points["B"]
    assert crank_end is not None  # the catalog four-bar names B
    points["P"] = crank_end + Vector(p, beta + gamma, "BP")
    return Linkage("fourbar_coupler_point", base.loops, base.inputs, base.unknowns,
                   parameters=base.parameters + (p, gamma), points=points,
                   roles=base.roles, extras=base.extras)


#: The kind of cache entry of the four-bar's solver with a coupler point (:func:`coupler_point_solver`).
COUPLER_POINT_ENTRY_KIND = "coupler-point-solver/1"


@lru_cache(maxsize=16)
def coupler_point_solver(outputs: tuple[str, ...]) -> CachedSolver:
    """The solver of ``outputs`` of :func:`coupler_point_linkage`, from the disk cache: derived once (SymPy) and keyed
    without building the linkage (:func:`symlink.numeric.cache.catalog_key`, with this module among the code that
    shapes it), so that a warm coupler curve imports no SymPy.  Made once a process for each request.

    >>> solver = coupler_point_solver(("P_x",))
    >>> round(float(solver(theta=0.0, a=20, b=66, c=56, d=80, p=30, gamma=0.0, branch=1)["P_x"]), 2)
    38.26
    """
    from ..numeric.cache import catalog_key
    from ..numeric.cached_solver import CachedSolver, entry_text
    chosen = list(outputs)

    def full() -> Any:
        from ..numeric.solver import Solver
        return Solver(coupler_point_linkage(), chosen)

    key = catalog_key("fourbar", chosen, COUPLER_POINT_ENTRY_KIND, {}, ("plot/figures",))
    return CachedSolver("fourbar_coupler_point", chosen, key=key,
                        derive=lambda: entry_text(coupler_point_linkage(), chosen), full=full)


@lru_cache(maxsize=16)
def _catalog_solver(outputs: tuple[str, ...]) -> CachedSolver:
    """The catalog four-bar's solver of ``outputs`` from the disk cache (its catalog entry), made once a process."""
    from ..numeric.cached_solver import CachedSolver
    return CachedSolver("fourbar", list(outputs))


def check_coupler_point(coupler_point: tuple[float, float] | None,
                        check_lengths: Callable[..., None] | None = None) -> None:
    """``ValueError`` unless the coupler point is (positive finite distance, finite angle).

    ``check_lengths``: the check of lengths to use (default :func:`symlink.numeric.solver.check_lengths`; a cached
    solver's, which checks alike, keeps SymPy out).
    """
    if coupler_point is None:
        return
    if check_lengths is None:
        from ..numeric.solver import check_lengths as checked
    else:
        checked = check_lengths
    distance, angle = coupler_point
    checked(**{"the coupler point's distance from B": distance})
    if not math.isfinite(angle):
        raise ValueError(f"the coupler point's angle must be finite, got {angle}")


def fourbar_positions(a: float, b: float, c: float, d: float, theta, branch: "int | numpy.ndarray",
                      outputs: Sequence[str], coupler_point: tuple[float, float] | None = None,
                      linkage: Linkage | None = None) -> dict[str, numpy.ndarray]:
    """Position outputs of a four-bar (radians, lengths' unit) at crank angles ``theta``.

    ``coupler_point`` is ``(distance from B, angle from B->C in radians)`` and
    adds the outputs ``P_x``, ``P_y`` where asked for.  With ``linkage`` the
    solver is derived from that linkage (a fresh one derives positions only);
    otherwise from a cached one.  NaN and ``assembled`` False where it cannot close.

    >>> result = fourbar_positions(20, 66, 56, 80, 0.0, 1, ["rocker"])
    >>> round(math.degrees(float(result["rocker"])), 2)
    110.74
    """
    values = dict(theta=theta, a=a, b=b, c=c, d=d, branch=branch)
    if coupler_point is not None:
        values.update(p=coupler_point[0], gamma=coupler_point[1])
    if linkage is None:  # from the disk cache: no SymPy once derived
        cached = coupler_point_solver(tuple(outputs)) if coupler_point is not None else _catalog_solver(tuple(outputs))
        check_coupler_point(coupler_point, cached.check_lengths)
        return cached(**values)
    from ..numeric.solver import Solver
    check_coupler_point(coupler_point)
    if coupler_point is not None and "P" not in linkage.points:
        raise ValueError(f"{linkage.name} has no coupler point P; use coupler_point_linkage()")
    return Solver(linkage, outputs)(**values)


def _wrapped_with_breaks(x: numpy.ndarray, angles: numpy.ndarray, half: float) -> tuple[numpy.ndarray, numpy.ndarray]:
    """Angles wrapped to (-half, half], with a NaN gap where they wrap (no vertical line across the plot)."""
    y = wrap(angles, half)
    jumps = numpy.flatnonzero(numpy.abs(numpy.diff(y)) > half) + 1
    return numpy.insert(x, jumps, numpy.nan), numpy.insert(y, jumps, numpy.nan)


def _shade_unreachable(axes: "Axes", a: float, b: float, c: float, d: float, scale: float) -> None:
    edges = [0.0] + [bound for piece in reachable_turn(a, b, c, d) for bound in piece] + [2 * math.pi]
    label: str | None = "cannot be assembled"
    for low, high in zip(edges[0::2], edges[1::2]):
        if high > low:
            axes.axvspan(low * scale, high * scale, color="0.88", zorder=0, label=label)
            label = None


def _new_figure(width: float, height: float, rows: int = 1,
                given: "Sequence[Axes] | None" = None) -> tuple["Figure", list["Axes"]]:
    """A new figure (one that displays itself in a notebook) with ``rows`` axes, or the ``given`` axes' figure."""
    if given is not None:
        given = list(given)
        if len(given) != rows or not all(hasattr(axes, "plot") and hasattr(axes, "figure") for axes in given):
            raise ValueError(f"give {'one Matplotlib Axes' if rows == 1 else f'{rows} Matplotlib Axes'} to draw on, "
                             f"got {given!r}")
        # The top-level figure, also for a subfigure's axes (a Figure is its own ``figure``).
        return given[0].figure.figure, given
    from .inline import NotebookFigure
    figure = NotebookFigure(figsize=(width, height), layout="constrained")
    axes = figure.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]
    return figure, list(axes)


def _given(ax: "Axes | None") -> "list[Axes] | None":
    return None if ax is None else [ax]


def _lengths_title(a: float, b: float, c: float, d: float) -> str:
    return f"four-bar: crank a = {a:g}, coupler b = {b:g}, rocker c = {c:g}, ground d = {d:g}"


def _crank_axis(axes: "Axes", units: str) -> None:
    if units == "deg":
        axes.set_xlim(0, 360)
        axes.set_xticks(numpy.arange(0, 361, 45))
    else:
        axes.set_xlim(0, 2 * math.pi)
    axes.set_xlabel(f"crank angle θ ({units})")


#: What the angle figure solves.
_ANGLE_OUTPUTS = ("coupler", "rocker")


def angle_figure(a: float, b: float, c: float, d: float, branches: Sequence[int] = (1, -1),
                 units: str = "deg", title: str | None = None, samples: int = TURN_SAMPLES,
                 axes: "Sequence[Axes] | None" = None) -> "Figure":
    """Coupler and rocker angle against the crank angle over a full turn (the Maple worksheet's two plots).

    One line per branch (solid +1, dashed -1), angles wrapped to (-180, 180]
    deg or (-pi, pi] rad; unreachable crank angles are shaded.  ``axes``:
    two Matplotlib Axes to draw the coupler and the rocker on (default: a new
    figure); the title then goes on the first.

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths.
    branches : sequence of int, optional
        The branches drawn (default both: +1 solid, -1 dashed).
    units : {"deg", "rad"}, optional
        The angles' unit (default degrees).
    title : str, optional
        The figure's title.
    samples : int, optional
        Crank angles over the turn (default 721).
    axes : two Matplotlib Axes, optional
        Where to draw the coupler and the rocker (default: a new figure).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Examples
    --------
    >>> import symlink
    >>> figure = symlink.angle_figure(20, 66, 56, 80, samples=9)
    >>> rocker = figure.axes[1].lines[0]  # branch +1
    >>> figure.axes[1].get_ylabel(), float(rocker.get_xdata()[0]), round(float(rocker.get_ydata()[0]), 2)  # seed 003
    ('rocker angle φ (deg)', 0.0, 110.74)
    """
    _catalog_solver(_ANGLE_OUTPUTS).check_lengths(crank=a, coupler=b, rocker=c, ground=d)  # as Solver's check
    closing_crank_range(a, b, c, d)
    half = half_turn(units)
    scale = half / math.pi
    theta = turn_angles(a, b, c, d, samples)
    figure, (top, bottom) = _new_figure(7.0, 6.0, rows=2, given=axes)
    for sign in _checked_branches(branches):
        result = fourbar_positions(a, b, c, d, theta, sign, list(_ANGLE_OUTPUTS))
        for panel, name in ((top, "coupler"), (bottom, "rocker")):
            x, y = _wrapped_with_breaks(theta * scale, result[name] * scale, half)
            panel.plot(x, y, BRANCH_STYLES[sign], color=LINK_COLORS[name], label=f"branch {sign:+d}")
    for panel, name, symbol in ((top, "coupler", "β"), (bottom, "rocker", "φ")):
        _shade_unreachable(panel, a, b, c, d, scale)
        panel.set_ylabel(f"{name} angle {symbol} ({units})")
        panel.grid(True, alpha=0.4)
        panel.legend(loc="best", fontsize="small")
        _crank_axis(panel, units)
    heading = title if title is not None else _lengths_title(a, b, c, d)
    if axes is None:
        top.set_xlabel("")
        figure.suptitle(heading)
    else:
        top.set_title(heading, fontsize="medium")
    return figure


def _checked_branches(branches: Sequence[int]) -> list[int]:
    branches = list(branches)
    if not branches or any(sign not in (1, -1) for sign in branches):
        raise ValueError(f"branches must be +1 and/or -1, got {branches}")
    return branches


def transmission_figure(a: float, b: float, c: float, d: float, units: str = "deg",
                        title: str | None = None, samples: int = TURN_SAMPLES, ax: "Axes | None" = None) -> "Figure":
    """The transmission angle against the crank angle over a turn (the quick-return synthesis paper, Fig. 5, 7, 9).

    The angle is the interior angle at C between coupler and rocker, the same
    on both branches (:func:`~symlink.numeric.fourbar_transmission.transmission_curve`).  Its
    smallest and largest values over the turn are marked where they occur
    (:func:`~symlink.numeric.fourbar_transmission.transmission_range`), and the usual design
    range 45 to 135 deg shaded.  ``ax``: the Matplotlib Axes to draw on
    (default: a new figure's).

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths.
    units : {"deg", "rad"}, optional
        The angles' unit (default degrees).
    title : str, optional
        The figure's title.
    samples : int, optional
        Crank angles over the turn (default 721).
    ax : Matplotlib Axes, optional
        Where to draw (default: a new figure's).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Examples
    --------
    >>> import symlink
    >>> figure = symlink.transmission_figure(20, 66, 56, 80, samples=9)
    >>> curve = figure.axes[0].lines[0]
    >>> round(float(curve.get_ydata()[0]), 2)  # at theta = 0, |BD| = 60: acos(3892 / 7392)
    58.23
    """
    from ..numeric.fourbar_transmission import transmission_curve, transmission_range
    extremes = transmission_range(a, b, c, d)  # ValueError for bad lengths or a four-bar closing nowhere, first
    half = half_turn(units)
    scale = half / math.pi
    theta = turn_angles(a, b, c, d, samples)
    mu = transmission_curve(a, b, c, d, theta)
    figure, (axes,) = _new_figure(7.0, 4.2, given=_given(ax))
    axes.plot(theta * scale, mu * scale, color="tab:purple", label="transmission angle μ")
    low, high = (math.radians(limit) * scale for limit in TRANSMISSION_LIMITS)
    axes.axhspan(low, high, color="tab:green", alpha=0.08, label="usual range 45°–135°")
    for word, value, where, marker in (("min", extremes.minimum, extremes.minimum_at, "v"),
                                       ("max", extremes.maximum, extremes.maximum_at, "^")):
        at = where % (2 * math.pi)
        axes.plot(at * scale, value * scale, marker, color="black", markersize=7, clip_on=False,
                  label=f"{word} {math.degrees(value):.3f}° at θ = {float(wrap(math.degrees(where), 180.0)):.4g}°")
    _shade_unreachable(axes, a, b, c, d, scale)
    axes.set_ylim(0, half)
    axes.set_ylabel(f"transmission angle μ ({units})")
    axes.grid(True, alpha=0.4)
    axes.legend(loc="best", fontsize="small")
    _crank_axis(axes, units)
    axes.set_title(title if title is not None else _lengths_title(a, b, c, d))
    return figure


# --- the mechanism -------------------------------------------------------------
def _ground_marker():
    """A pivot symbol: a triangle with its apex at the pivot, on a hatched base."""
    from matplotlib.path import Path as MarkerPath
    vertices = [(0, 0), (-0.55, -1), (0.55, -1), (0, 0), (-0.95, -1), (0.95, -1)]
    codes = [MarkerPath.MOVETO, MarkerPath.LINETO, MarkerPath.LINETO, MarkerPath.CLOSEPOLY,
             MarkerPath.MOVETO, MarkerPath.LINETO]
    for x in numpy.linspace(-0.7, 0.95, 5):
        vertices += [(x, -1), (x - 0.3, -1.35)]
        codes += [MarkerPath.MOVETO, MarkerPath.LINETO]
    return MarkerPath(vertices, codes)


class MechanismDrawing:
    """A four-bar on an axes: links as bars, pin joints as disks, ground pivots marked; moved in place.

    Crank, coupler and rocker are drawn red, blue and green; with a coupler
    point the coupler is drawn as the plate B, C, P.  Call :meth:`update` with
    the joints of one position, ``C=None`` where the linkage cannot close.
    """

    def __init__(self, axes: "Axes", coupler_point: bool = False) -> None:
        from matplotlib.patches import Polygon
        self.links = {name: axes.plot([], [], color=color, label=name, linewidth=7, solid_capstyle="round",
                                      zorder=3)[0]
                      for name, color in LINK_COLORS.items()}
        self.frame, = axes.plot([], [], color="0.5", linestyle="--", linewidth=1, zorder=1)
        self.ground, = axes.plot([], [], linestyle="none", marker=_ground_marker(), markersize=24,
                                 markeredgecolor="0.25", markerfacecolor="none", markeredgewidth=1.2, zorder=2)
        self.pins, = axes.plot([], [], linestyle="none", marker="o", markersize=9, markerfacecolor="yellow",
                               markeredgecolor="black", zorder=5)
        self.body = None
        if coupler_point:
            self.body = Polygon(numpy.zeros((3, 2)), closed=True, facecolor=LINK_COLORS["coupler"],
                                alpha=0.3, edgecolor="none", zorder=2.5)
            axes.add_patch(self.body)
        self.point, = axes.plot([], [], linestyle="none", marker="o", markersize=6, color="black", zorder=6)

    @property
    def artists(self) -> list:
        """Everything this drawing moves."""
        return [*self.links.values(), self.frame, self.ground, self.pins, self.point] + (
            [self.body] if self.body is not None else [])

    def update(self, d: float, B: tuple[float, float], C: tuple[float, float] | None = None,
               P: tuple[float, float] | None = None) -> None:
        """Move to joints B and C (and coupler point P); ``C=None`` draws the crank and ground only."""
        A, D = (0.0, 0.0), (d, 0.0)
        self.frame.set_data([A[0], D[0]], [A[1], D[1]])
        self.ground.set_data([A[0], D[0]], [A[1], D[1]])
        self.links["crank"].set_data([A[0], B[0]], [A[1], B[1]])
        joints = [A, B, D] if C is None else [A, B, C, D]
        self.pins.set_data([p[0] for p in joints], [p[1] for p in joints])
        for name, start in (("coupler", B), ("rocker", D)):
            self.links[name].set_data(*(([], []) if C is None else ([start[0], C[0]], [start[1], C[1]])))
        shown = C is not None and P is not None
        self.point.set_data(*(([P[0]], [P[1]]) if P is not None and C is not None else ([], [])))
        if self.body is not None:
            self.body.set_visible(shown)
            if C is not None and P is not None:
                self.body.set_xy([B, C, P])


def extent(xs: "ArrayLike", ys: "ArrayLike", margin: float = 0.08) -> tuple[tuple[float, float], tuple[float, float]]:
    """Axis limits around the finite points, with a margin of the larger side."""
    x, y = numpy.asarray(xs, dtype=float).ravel(), numpy.asarray(ys, dtype=float).ravel()
    keep = numpy.isfinite(x) & numpy.isfinite(y)
    x, y = x[keep], y[keep]
    pad = margin * max(numpy.ptp(x), numpy.ptp(y), 1e-300)
    return (float(x.min() - pad), float(x.max() + pad)), (float(y.min() - pad), float(y.max() + pad))


def frame_plane(axes: "Axes", xs: "ArrayLike", ys: "ArrayLike", unit: str | None = "", margin: float = 0.08) -> None:
    """A mechanism's plane on ``axes``: limits around the finite points, equal scales, a light grid, and
    ``x``/``y`` labels with the length ``unit`` (no labels for ``None``)."""
    (x0, x1), (y0, y1) = extent(xs, ys, margin=margin)
    axes.set_xlim(x0, x1)
    axes.set_ylim(y0, y1)
    axes.set_aspect("equal")
    axes.grid(True, alpha=0.3)
    if unit is not None:
        suffix = f" ({unit})" if unit else ""
        axes.set_xlabel(f"x{suffix}")
        axes.set_ylabel(f"y{suffix}")


#: What a coupler curve solves: the coupler point and the joints drawn.
_CURVE_OUTPUTS = ("P_x", "P_y", "B_x", "B_y", "C_x", "C_y")


def coupler_curve_figure(a: float, b: float, c: float, d: float, distance: float, angle: float,
                         branches: Sequence[int] = (1,), crank_angle: float | None = None,
                         title: str | None = None, unit: str = "", samples: int = TURN_SAMPLES,
                         ax: "Axes | None" = None) -> "Figure":
    """The curve of a coupler point over a crank turn, with the mechanism drawn at ``crank_angle``.

    The point is ``distance`` from B at ``angle`` (radians) from the coupler's
    direction B->C.  The mechanism is drawn at ``crank_angle`` (radians) on
    the first branch, by default at the first reachable crank angle from 0.
    ``ax``: the Matplotlib Axes to draw on (default: a new figure's).

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths.
    distance : float
        The coupler point's distance from B.
    angle : float
        Its angle (radians) from the coupler's direction B -> C.
    branches : sequence of int, optional
        The branches drawn (default +1).
    crank_angle : float, optional
        The crank angle (radians) the mechanism is drawn at (default: the first reachable from 0).
    title : str, optional
        The figure's title.
    unit : str, optional
        The lengths' unit, for the axes' labels.
    samples : int, optional
        Crank angles over the turn (default 721).
    ax : Matplotlib Axes, optional
        Where to draw (default: a new figure's).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Examples
    --------
    >>> import symlink
    >>> figure = symlink.coupler_curve_figure(20, 66, 56, 80, 30.0, 0.0, samples=9)
    >>> x, y = figure.axes[0].lines[0].get_xydata()[0]  # at theta = 0: B = (20, 0), 30 along BC at 52.51 deg
    >>> round(float(x), 2), round(float(y), 2)
    (38.26, 23.8)
    """
    solver = coupler_point_solver(_CURVE_OUTPUTS)  # its generated check of lengths, as Solver's
    solver.check_lengths(crank=a, coupler=b, rocker=c, ground=d)
    closing_crank_range(a, b, c, d)
    point = (distance, angle)
    check_coupler_point(point, solver.check_lengths)
    branches = _checked_branches(branches)
    theta = turn_angles(a, b, c, d, samples)
    figure, (axes,) = _new_figure(6.4, 5.2, given=_given(ax))
    xs: list["ArrayLike"] = [0.0, d]
    ys: list["ArrayLike"] = [0.0, 0.0]
    for sign in branches:
        result = fourbar_positions(a, b, c, d, theta, sign, list(_CURVE_OUTPUTS), point)
        axes.plot(result["P_x"], result["P_y"], BRANCH_STYLES[sign], color="tab:purple",
                  label=f"coupler curve, branch {sign:+d}", zorder=2)
        for name in ("P", "B", "C"):
            xs.append(result[f"{name}_x"])
            ys.append(result[f"{name}_y"])
    shown = theta[0] if crank_angle is None else crank_angle
    at = fourbar_positions(a, b, c, d, shown, branches[0], list(_CURVE_OUTPUTS), point)
    if crank_angle is None and not at["assembled"]:
        shown = reachable_turn(a, b, c, d)[0][0]
        at = fourbar_positions(a, b, c, d, shown, branches[0], list(_CURVE_OUTPUTS), point)
    drawing = MechanismDrawing(axes, coupler_point=True)
    joint = {name: (float(at[f"{name}_x"]), float(at[f"{name}_y"])) for name in ("B", "C", "P")}
    drawing.update(d, joint["B"], joint["C"] if at["assembled"] else None, joint["P"])
    frame_plane(axes, numpy.concatenate([numpy.ravel(v) for v in xs]),
                numpy.concatenate([numpy.ravel(v) for v in ys]), unit)
    axes.legend(loc="best", fontsize="small")
    axes.set_title(title if title is not None else
                   f"coupler point {distance:g} from B at {math.degrees(angle):g}° from BC; "
                   f"drawn at θ = {math.degrees(shown):.4g}°", fontsize="medium")
    return figure


# --- the loop of the MATLAB GUI paper ------------------------------------------------------------
def draw_loop(lengths: Sequence[float], angles_rad: Sequence[float], path=None, title: str = "", *,
              ax: "Axes | None" = None) -> "Figure":
    """Draw a closed loop ``z1 + z2 + z3 + z4 = 0`` head to tail, as the MATLAB GUI paper does, and save it.

    ``z_k = R_k e^{i t_k}``, starting at the origin; links red, yellow, blue,
    green with a legend of each length and angle (degrees).  ``ValueError``
    if the loop does not close (to 1e-6 of its total length).  The figure is
    saved to ``path`` where one is given (PNG or SVG); ``ax`` is the
    Matplotlib Axes to draw on (default: a new figure's, with the legend
    below the axes; on given axes the legend is inside them).

    Parameters
    ----------
    lengths : sequence of float
        The four lengths ``R_k``.
    angles_rad : sequence of float
        The four angles ``t_k`` (radians).
    path : str or os.PathLike, optional
        Where to save the figure (PNG or SVG); not saved by default.
    title : str, optional
        The figure's title.
    ax : Matplotlib Axes, optional
        Where to draw (default: a new figure's).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Raises
    ------
    ValueError
        If the loop does not close (to 1e-6 of its total length).

    Examples
    --------
    >>> import math, tempfile, pathlib, symlink
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "loop.png"
    >>> angles = [math.radians(t) for t in (270, 308.663, 180, 63.435)]
    >>> figure = symlink.draw_loop([300, 640.3124, 800.0158, 894.4019], angles, path)
    >>> path.stat().st_size > 0
    True
    """
    from matplotlib import patheffects
    lengths = [float(v) for v in lengths]
    angles = [float(v) for v in angles_rad]
    if len(lengths) != 4 or len(angles) != 4:
        raise ValueError(f"a loop z1..z4 needs four lengths and four angles, got {len(lengths)} and {len(angles)}")
    if not all(math.isfinite(v) for v in lengths + angles):
        raise ValueError(f"the loop's lengths and angles must be finite, got {lengths} and {angles}")
    vectors = numpy.array(lengths) * numpy.exp(1j * numpy.array(angles))
    heads = numpy.cumsum(vectors)
    total = sum(abs(v) for v in lengths)
    if total == 0 or abs(heads[-1]) > 1e-6 * total:
        raise ValueError(f"the loop does not close: z1 + z2 + z3 + z4 is {abs(heads[-1]):.6g} away from 0")
    tails = numpy.concatenate([[0], heads[:-1]])
    if path is not None:
        figure_suffix(path)  # a bad suffix is refused before anything is drawn
    figure, (axes,) = _new_figure(6.4, 5.2, given=_given(ax))
    outline = [patheffects.Stroke(linewidth=6, foreground="black"), patheffects.Normal()]
    for k, (tail, head, color) in enumerate(zip(tails, heads, LOOP_COLORS), start=1):
        degrees = float(wrap(math.degrees(angles[k - 1]), 180.0))
        label = f"z{k}: R{k} = {lengths[k - 1]:.7g}, θ{k} = {degrees:.7g}°"
        axes.plot([tail.real, head.real], [tail.imag, head.imag], color=color, linewidth=4,
                  path_effects=outline, label=label, zorder=2, solid_capstyle="round")
        start = head - 1e-3 * (head - tail)  # an arrowhead only: the link is the line
        axes.annotate("", xy=(head.real, head.imag), xytext=(start.real, start.imag),
                      arrowprops=dict(arrowstyle="-|>", facecolor=color, edgecolor="black", linewidth=1,
                                      mutation_scale=22, shrinkA=0, shrinkB=0), zorder=3)
        middle = (tail + head) / 2
        axes.annotate(f"z{k}", (middle.real, middle.imag), textcoords="offset points", xytext=(6, 6),
                      fontweight="bold")
    axes.plot(tails.real, tails.imag, "o", color="black", markersize=5, zorder=4)
    axes.set_aspect("equal")
    axes.margins(0.12)
    axes.grid(True, alpha=0.3)
    axes.set_xlabel("real axis")
    axes.set_ylabel("imaginary axis")
    if ax is None:
        figure.legend(loc="outside lower center", ncols=2, fontsize="small")
    else:
        axes.legend(loc="best", fontsize="small")
    axes.set_title(title or "loop z1 + z2 + z3 + z4 = 0")
    if path is not None:
        save_figure(figure, path)
    return figure


# --- files ---------------------------------------------------------------------
def figure_suffix(path) -> str:
    """The Matplotlib format for a figure file, or ``ValueError`` naming the ones there are."""
    suffix = Path(path).suffix.lower()
    if suffix not in FIGURE_SUFFIXES:
        raise ValueError(f"cannot draw into {str(path)!r}: the file must end in "
                         f"{' or '.join(FIGURE_SUFFIXES)}")
    return FIGURE_SUFFIXES[suffix]


def save_figure(figure: "Figure", path, dpi: float = 100) -> None:
    """Write a figure atomically as PNG or SVG (by suffix), without timestamps, so reruns give the same bytes.

    Parameters
    ----------
    figure : matplotlib.figure.Figure
        The figure.
    path : str or os.PathLike
        Where to write; ``.png`` or ``.svg``.
    dpi : float, optional
        Resolution of a PNG (default 100).

    Returns
    -------
    None

    Examples
    --------
    >>> import tempfile, pathlib, symlink
    >>> figure = symlink.transmission_figure(20, 66, 56, 80, samples=9)
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> symlink.save_figure(figure, folder / "one.png", dpi=20)
    >>> symlink.save_figure(figure, folder / "two.png", dpi=20)
    >>> (folder / "one.png").read_bytes() == (folder / "two.png").read_bytes()  # no timestamps
    True
    """
    write_atomic(path, figure_bytes(figure, path, dpi))


def figure_bytes(figure: "Figure", path, dpi: float = 100) -> bytes:
    """The bytes :func:`save_figure` writes to ``path`` (PNG or SVG by its suffix), for writing several files
    together (:func:`symlink.common.files.write_files_together`: all of them or none)."""
    import matplotlib
    fmt = figure_suffix(path)
    buffer = io.BytesIO()
    metadata = {"Software": None} if fmt == "png" else {"Date": None}
    with matplotlib.rc_context({"svg.hashsalt": "symlink"}):
        figure.savefig(buffer, format=fmt, dpi=dpi, metadata=metadata)
    return buffer.getvalue()
