"""A drawing of any linkage: its bodies and joints at a pose, read off :func:`symlink.mechanism.bodies.mechanism`.

The bodies and joints come from the linkage's vectors
(:mod:`symlink.mechanism.bodies`); the pose from its closed form
(:class:`~symlink.numeric.solver.Solver`) or, where it has none, from Newton's
method (:class:`~symlink.numeric.solver.NumericSolver`).  Every joint is placed by
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

>>> from symlink.mechanism.catalog import jansen, EXAMPLE_VALUES
>>> drawing = draw_linkage(jansen(), EXAMPLE_VALUES["jansen"], trace=("H",))
>>> len(drawing.polygons), drawing.axes.get_xlabel()
(2, 'x (length unit)')
"""
from __future__ import annotations

import itertools
import math
from typing import TYPE_CHECKING, Mapping, Sequence, cast

import numpy

from ..numeric.poses import Placement, Poses, traced_paths
from .figures import _ground_marker, extent

if TYPE_CHECKING:  # the symbolic side (SymPy) only where a linkage is given: a placement from the disk cache
    # draws without it (symlink.numeric.poses.cached_placement)
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import Polygon

    from ..numeric.poses import Geometry
    from ..symbolic.linkage import Linkage

__all__ = ["LinkageDrawing", "draw_linkage", "draw_placement"]

BODY_COLORS = ("tab:red", "tab:blue", "tab:green", "tab:orange", "tab:purple", "tab:brown", "tab:pink",
               "tab:olive", "tab:cyan")

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

    def __init__(self, axes: "Axes", geometry: Placement, poses: Poses,
                 traces: Mapping[str, numpy.ndarray] | None = None, unit: str | None = None,
                 letters: bool = True) -> None:
        from matplotlib.patches import Polygon
        self.axes, self.geometry, self.poses = axes, geometry, poses
        self.figure: "Figure" = axes.figure.figure  # the top-level figure, also for a subfigure's axes
        facts = geometry.facts
        self.scale = self._scale(poses, traces)
        self.traces = {name: axes.plot(path.real, path.imag, color="tab:purple", linewidth=1.2, alpha=0.8,
                                       zorder=1, label=f"path of {name}")[0]
                       for name, path in (traces or {}).items()}
        self.bars, self.polygons, self._bodies = [], [], []
        colors = itertools.cycle(BODY_COLORS)
        for body, corners in facts["bodies"]:  # the moving bodies, each with the corners of its outline
            color = next(colors)
            artist: "Polygon | Line2D"
            if len(corners) >= 3:
                artist = Polygon(numpy.zeros((len(corners), 2)), closed=True, facecolor=color, alpha=0.45,
                                 edgecolor=color, linewidth=2.5, zorder=3, label=body)
                axes.add_patch(artist)
                self.polygons.append(artist)
            elif len(corners) == 2:
                artist = axes.plot([], [], color=color, linewidth=6, solid_capstyle="round", zorder=3,
                                   label=body)[0]
                self.bars.append(artist)
            else:
                continue
            self._bodies.append((corners, artist))
        self.guides, self.blocks = [], []
        for _ in facts["sliders"]:
            self.guides.append(axes.plot([], [], color="0.3", linewidth=1.5, zorder=2)[0])
            block = Polygon(numpy.zeros((4, 2)), closed=True, facecolor="0.85", edgecolor="black", linewidth=1.2,
                            zorder=4)
            axes.add_patch(block)
            self.blocks.append(block)
        self._pivots = [name for name in facts["pivots"] if name in poses.positions]
        self.frame = axes.plot([], [], color="0.5", linestyle="--", linewidth=1, zorder=1)[0]
        self.ground = axes.plot([], [], linestyle="none", marker=_ground_marker(), markersize=22,
                                markeredgecolor="0.25", markerfacecolor="none", markeredgewidth=1.2, zorder=2)[0]
        self._pins = [name for name in facts["pins"] if name in poses.positions]
        self.pins = axes.plot([], [], linestyle="none", marker="o", markersize=7, markerfacecolor="white",
                              markeredgecolor="black", zorder=5)[0]
        named = list(dict.fromkeys(self._pins + [p for p in facts["points"] if p in poses.positions]))
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

    @staticmethod
    def _scale(poses: Poses, traces) -> float:
        values = numpy.concatenate([p.ravel() for p in poses.positions.values()]
                                   + [t.ravel() for t in (traces or {}).values()])
        values = values[numpy.isfinite(values)]
        if values.size == 0:
            return 1.0
        return float(max(numpy.ptp(values.real), numpy.ptp(values.imag), 1e-300))

    def _guide_span(self, k: int, index: int) -> tuple[complex, complex]:
        name, fixed = self.geometry.facts["sliders"][index]
        start = self.poses.positions.get(f"{name} guide", numpy.zeros(len(self.poses)))
        along = numpy.exp(1j * self.poses.directions[name])
        travel = ((self.poses.positions[name] - start) * numpy.conj(along)).real
        block = 0.08 * self.scale
        if fixed:  # a fixed guide: long enough for the whole travel
            finite = travel[numpy.isfinite(travel)]
            low, high = (min(0.0, finite.min()), max(0.0, finite.max())) if finite.size else (0.0, 0.0)
        else:
            low, high = min(0.0, travel[k]), max(0.0, travel[k])
        return start[k] + along[k] * (low - block), start[k] + along[k] * (high + block)

    def limits(self, traces=None) -> tuple[tuple[float, float], tuple[float, float]]:
        """Axis limits holding every joint and point of every pose, the traced paths and the guides."""
        points = [p.ravel() for p in self.poses.positions.values()] + [t.ravel() for t in (traces or {}).values()]
        for index in range(len(self.geometry.slider_names)):
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
        for index, name in enumerate(self.geometry.slider_names):
            start, end = self._guide_span(k, index)
            self.guides[index].set_data(*(([start.real, end.real], [start.imag, end.imag]) if shown else ([], [])))
            centre, along = at[name], numpy.exp(1j * self.poses.directions[name][k])
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


def _input_text(geometry: Placement, name: str, value: float) -> str:
    if name in geometry.angles:
        return f"{name} = {math.degrees(float(value)):.4g}°"
    return f"{name} = {float(value):.4g}"


def draw_linkage(linkage: Linkage, values: Mapping[str, float], ax: "Axes | None" = None, *,
                 trace: Sequence[str] = (), unit: str | None = None, guess: Mapping[str, float] | None = None,
                 title: str | None = None, bodies: Mapping[str, Sequence[str]] | None = None,
                 geometry: Geometry | None = None) -> LinkageDrawing:
    """Draw ``linkage`` at ``values`` on ``ax`` (a new figure's axes by default), with the paths of ``trace``.

    ``values`` by symbol name (inputs default to 0, branches to +1);
    ``guess`` picks the assembly of a linkage without a closed form;
    ``bodies`` says which vectors share a body where the vectors alone are
    ambiguous (:func:`symlink.mechanism.bodies.mechanism`).  ``ValueError`` where the
    linkage cannot be assembled at these values.

    Parameters
    ----------
    linkage : Linkage
        Any linkage.
    values : mapping of str to float
        Every parameter by name; inputs default to 0, branches to +1.
    ax : Matplotlib Axes, optional
        Where to draw (default: a new figure's).
    trace : sequence of str, optional
        Points whose paths over the input's range are drawn.
    unit : str, optional
        The lengths' unit, for the axes' labels.
    guess : mapping of str to float, optional
        For a linkage without a closed form: its unknowns near the wanted assembly.
    title : str, optional
        The axes' title.
    bodies : mapping of str to sequence of str, optional
        Which vectors share a body, where the vectors alone are ambiguous.
    geometry : Geometry, optional
        The linkage's geometry, if made already.

    Returns
    -------
    LinkageDrawing
        The artists (``bars``, ``pins``, ``traces``, ...) and the figure, movable to another pose.

    Raises
    ------
    ValueError
        Where the linkage cannot be assembled at these values.

    Examples
    --------
    >>> import symlink
    >>> drawing = symlink.draw_linkage(symlink.fourbar(), dict(theta=0.0, a=20, b=66, c=56, d=80), trace=["C"])
    >>> len(drawing.bars), sorted(drawing.traces)  # crank, coupler, rocker
    (3, ['C'])
    """
    if geometry is None:
        from ..numeric.poses import Geometry
        geometry = Geometry(linkage, bodies)
    return draw_placement(geometry, values, ax, trace=trace, unit=unit, guess=guess, title=title)


def draw_placement(geometry: Placement, values: Mapping[str, float], ax: "Axes | None" = None, *,
                   trace: Sequence[str] = (), unit: str | None = None, guess: Mapping[str, float] | None = None,
                   title: str | None = None) -> LinkageDrawing:
    """:func:`draw_linkage` from a linkage's :class:`~symlink.numeric.poses.Placement`: what a drawing needs of it,
    as plain data and NumPy code, such as :func:`~symlink.numeric.poses.cached_placement` takes from the disk
    cache (the drawing then imports no SymPy).  Arguments and ``ValueError`` as for :func:`draw_linkage`.

    >>> from symlink.mechanism.catalog import fourbar
    >>> from symlink.numeric.poses import Geometry
    >>> drawing = draw_placement(Geometry(fourbar()), dict(theta=0.0, a=20, b=66, c=56, d=80))
    >>> drawing.axes.get_title()
    'fourbar at theta = 0°'
    """
    completed = geometry.check_values(values)
    poses = geometry.poses(completed, guess=guess)
    if not poses.assembled[0]:
        inputs = ", ".join(f"{name} = {float(completed[name]):g}" for name in geometry.input_names)
        raise ValueError(f"{geometry.name} cannot be assembled at {inputs}")
    if guess is None and not geometry.closed_form:
        guess = geometry.find_guess(completed)
    paths = traced_paths(geometry, completed, trace, guess)
    axes = _axes(ax)
    drawing = LinkageDrawing(axes, geometry, poses, paths, unit)
    drawing.update(0)
    inputs = ", ".join(_input_text(geometry, name, completed[name]) for name in geometry.input_names)
    axes.set_title(title if title is not None else f"{geometry.name} at {inputs}", fontsize="medium")
    if paths:
        axes.legend(handles=list(drawing.traces.values()), loc="best", fontsize="small")
    return drawing
