"""Drawings of synthesis results: the poses of a motion generation, its Burmester curves, the linkage at each pose.

:func:`motion_figure` draws the poses asked for as small frames (the coupler's x axis
dark, its y axis light), the centre-point and circle-point curves (four poses; for five,
those of poses 1234, with the Burmester points marked), and, given a
:class:`~symlink.synthesis.motion.Design`, the four-bar at every pose and its coupler
curve: the linkage is placed by the generated four-bar solver from the design's
lengths, crank angles and branches, not from the synthesis' own pivots, so the drawing
shows what the linkage does (a dot at each pose's origin) beside what was asked.

>>> from matplotlib.figure import Figure
>>> from symlink.synthesis.motion import motion_generation
>>> poses = [(0, 0, 0), (1, 0.2, 0.3), (1.8, 0.9, 0.8), (2.2, 2.0, 1.4), (2.0, 3.0, 2.0)]
>>> axes = Figure().subplots()
>>> motion_figure(poses, motion_generation(poses)[0], ax=axes) is axes.figure
True
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy

from ..numeric.reachability import turn_angles
from ..synthesis.motion import Design, burmester_curves, burmester_points, check_poses
from .figures import LINK_COLORS, _given, _new_figure, fourbar_positions, frame_plane

if TYPE_CHECKING:  # Matplotlib is imported when a drawing is made
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["motion_figure", "achieved_poses"]

_FRAME = 0.12          # length of a pose's frame axes, as a fraction of the poses' spread


def achieved_poses(design: Design) -> dict[str, numpy.ndarray]:
    """Where the design's linkage puts its joints and guided point at its crank angles (ground frame).

    Solved with the generated four-bar solver on each pose's branch, then turned by the
    ground angle and moved to the crank pivot.  Returns arrays by name: ``A``, ``B``,
    ``C``, ``D``, ``P`` (complex positions, one a pose) and ``angle`` (the pose angles).
    """
    theta = numpy.array(design.crank_angles)
    branch = numpy.array(design.branches, dtype=float)
    outputs = ["B_x", "B_y", "C_x", "C_y", "coupler"]
    point = None
    if design.coupler_point_distance > 1e-12 * max(design.crank, design.coupler):
        point = (design.coupler_point_distance, design.coupler_point_angle)
        outputs += ["P_x", "P_y"]
    solved = fourbar_positions(design.crank, design.coupler, design.rocker, design.ground, theta, branch,
                               outputs, point)
    turn = numpy.exp(1j * design.ground_angle)
    origin = complex(*design.crank_pivot)

    def place(name: str) -> numpy.ndarray:
        return origin + turn * (solved[f"{name}_x"] + 1j * solved[f"{name}_y"])

    joints = {"B": place("B"), "C": place("C")}
    joints["P"] = place("P") if point is not None else joints["B"]
    joints["A"] = numpy.full(len(theta), origin)
    joints["D"] = numpy.full(len(theta), origin + turn * design.ground)
    joints["angle"] = solved["coupler"] + design.ground_angle + design.pose_angle_offset
    return joints


def _frames(axes: "Axes", poses: numpy.ndarray, size: float, color: str, label: str) -> None:
    for j, (x, y, angle) in enumerate(poses):
        for turn, shade in ((0.0, 1.0), (math.pi / 2, 0.45)):
            axes.annotate("", xy=(x + size * math.cos(angle + turn), y + size * math.sin(angle + turn)), xytext=(x, y),
                          arrowprops=dict(arrowstyle="-|>", color=color, alpha=shade, linewidth=1.4), zorder=7)
        axes.annotate(str(j + 1), (x, y), textcoords="offset points", xytext=(-9, -11), fontsize="small", color=color)
    axes.plot(poses[:, 0], poses[:, 1], linestyle="none", marker="s", markersize=4, color=color, label=label, zorder=7)


def motion_figure(poses, design: Design | None = None, *, curves: bool = True, title: str | None = None,
                  unit: str = "", ax: "Axes | None" = None) -> "Figure":
    """The poses (rows of x, y, angle in radians), the Burmester curves and a design's linkage at each pose.

    ``curves``: draw the centre-point (solid) and circle-point (dotted) curves of the
    first four poses (four or five poses), and for five poses the Burmester points.
    ``ax``: the Matplotlib Axes to draw on (default: a new figure's).

    Parameters
    ----------
    poses : array_like
        The poses, rows (x, y, angle in radians).
    design : Design, optional
        A design of :func:`motion_generation`, drawn at each pose.
    curves : bool, optional
        Draw the Burmester curves (four or five poses) and points (five), default True.
    title : str, optional
        The axes' title.
    unit : str, optional
        The lengths' unit, for the axes' labels.
    ax : Matplotlib Axes, optional
        Where to draw (default: a new figure's).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Examples
    --------
    >>> import symlink
    >>> poses = [(0, 0, 0), (1, 0.2, 0.3), (1.8, 0.9, 0.8), (2.2, 2.0, 1.4)]
    >>> figure = symlink.motion_figure(poses, symlink.motion_generation(poses, rotations=[0.5, -0.5])[0], curves=False)
    >>> figure.axes[0].get_title().startswith("motion generation through 4 poses")
    True
    """
    poses = check_poses(poses, 2, 5)
    figure, (axes,) = _new_figure(6.4, 5.6, given=_given(ax))
    spread = float(numpy.ptp(poses[:, :2], axis=0).max()) or 1.0
    xs, ys = list(poses[:, 0]), list(poses[:, 1])
    if curves and len(poses) >= 4:
        sampled = burmester_curves(poses[:4])
        for way in range(2):
            label = "centre-point curve (poses 1-4)" if way == 0 else None
            axes.plot(*_broken(sampled.centre_points[way], 3 * spread).T, color="tab:purple", linewidth=1, label=label, zorder=1)
            label = "circle-point curve (pose 1)" if way == 0 else None
            axes.plot(*_broken(sampled.circle_points[way], 3 * spread).T, color="tab:orange", linewidth=1, linestyle=":", label=label,
                      zorder=1)
    if curves and len(poses) == 5:
        dyads = burmester_points(poses)
        if dyads:
            centres = numpy.array([dyad.fixed for dyad in dyads])
            circles = numpy.array([dyad.circle_point(poses) for dyad in dyads])
            axes.plot(*centres.T, linestyle="none", marker="D", color="tab:purple", label="Burmester centre points",
                      zorder=6)
            axes.plot(*circles.T, linestyle="none", marker="o", markerfacecolor="none", color="tab:orange",
                      label="Burmester circle points (pose 1)", zorder=6)
            xs += list(centres[:, 0]) + list(circles[:, 0])
            ys += list(centres[:, 1]) + list(circles[:, 1])
    if design is not None:
        joints = achieved_poses(design)
        for j in range(len(poses)):
            a, b, c, d, p = (joints[name][j] for name in "ABCDP")
            fade = 0.35 + 0.65 * (j + 1) / len(poses)
            axes.plot([a.real, b.real], [a.imag, b.imag], color=LINK_COLORS["crank"], linewidth=2.5, alpha=fade,
                      label="crank" if j == 0 else None, zorder=4)
            axes.plot([d.real, c.real], [d.imag, c.imag], color=LINK_COLORS["rocker"], linewidth=2.5, alpha=fade,
                      label="rocker" if j == 0 else None, zorder=4)
            axes.fill([b.real, c.real, p.real], [b.imag, c.imag, p.imag], color=LINK_COLORS["coupler"],
                      alpha=0.25 * fade, label="coupler" if j == 0 else None, zorder=3)
            axes.plot([b.real, c.real], [b.imag, c.imag], color=LINK_COLORS["coupler"], linewidth=2.5, alpha=fade,
                      zorder=4)
            axes.plot([b.real, c.real], [b.imag, c.imag], linestyle="none", marker="o", markersize=5,
                      markerfacecolor="yellow", markeredgecolor="black", zorder=5)
        pivots = numpy.array([joints["A"][0], joints["D"][0]])
        axes.plot(pivots.real, pivots.imag, linestyle="none", marker="^", markersize=10, markerfacecolor="none",
                  markeredgecolor="0.2", label="fixed pivots", zorder=5)
        axes.plot(joints["P"].real, joints["P"].imag, linestyle="none", marker="o", markersize=4, color="black",
                  label="achieved poses", zorder=8)
        curve = _coupler_curve(design)
        if curve is not None:
            axes.plot(curve.real, curve.imag, color="0.4", linewidth=0.8, label="coupler curve", zorder=2)
        for name in "ABCDP":
            xs += list(joints[name].real)
            ys += list(joints[name].imag)
    _frames(axes, poses, _FRAME * spread, "black", "target poses")
    frame_plane(axes, xs, ys, unit, margin=0.15)
    axes.legend(loc="best", fontsize="x-small")
    if title is None:
        title = f"motion generation through {len(poses)} poses"
        if design is not None:
            title += (f": {design.grashof}, worst transmission {math.degrees(design.transmission_worst):.1f}°"
                      + (", branch defect" if design.branch_defect else "")
                      + (", order defect" if design.order_defect else ""))
    axes.set_title(title, fontsize="medium")
    return figure


def _broken(points: numpy.ndarray, jump: float) -> numpy.ndarray:
    """The sampled curve with a NaN row wherever it leaps more than ``jump`` (through infinity) between samples."""
    steps = numpy.hypot(*numpy.diff(points, axis=0).T)
    cut = numpy.nonzero(steps > jump)[0] + 1
    return numpy.insert(points, cut, numpy.nan, axis=0)


def _coupler_curve(design: Design) -> numpy.ndarray | None:
    """The guided point over the crank's reachable angles on pose 1's branch (ground frame), NaN-broken; None if none."""
    if design.coupler_point_distance <= 1e-12 * max(design.crank, design.coupler):
        return None
    theta = turn_angles(design.crank, design.coupler, design.rocker, design.ground)
    solved = fourbar_positions(design.crank, design.coupler, design.rocker, design.ground, theta, design.branches[0],
                               ["P_x", "P_y"], (design.coupler_point_distance, design.coupler_point_angle))
    local = numpy.where(solved["assembled"], solved["P_x"] + 1j * solved["P_y"], numpy.nan)
    return complex(*design.crank_pivot) + numpy.exp(1j * design.ground_angle) * local
