"""Pictures from the command line: ``symlink draw``, ``curve``, ``animate``, ``view`` and ``fourbar --plot``.

``draw`` and ``animate`` take a catalog NAME (its example values, changed with
``--set a=20,b=66``) besides the four-bar's length options.
"""
from __future__ import annotations

import argparse
import math
import sys
from typing import TYPE_CHECKING, Sequence

from ..common.angles import to_radians, wrap
from .options import (name_list, output_file, add_branch_option, add_fourbar_lengths, add_units_option, angle, assignments, branches,
                      command_help, figure_path, finite, fourbar_lengths, fourbar_or_linkage, linkage_values, pair, whole)
from .output import note

if TYPE_CHECKING:
    from ..numeric.poses import Placement

__all__ = ["register", "add_fourbar_plot_options", "write_fourbar_plots", "drawn_linkage", "drawn_placement"]


def drawn_linkage(args: argparse.Namespace):
    """The linkage NAME|FILE and its values (``--set``), ``--angle`` (the first input, in --units) and
    ``--branch`` for every branch."""
    from ..symbolic.closure import is_angle
    from ..io.linkage_file import load_linkage
    found = load_linkage(args.linkage)
    linkage, values = found.linkage, linkage_values(found, args.set or {}, args.units)
    if args.angle is not None:
        first = linkage.inputs[0]
        values[first.name] = float(to_radians(args.angle, args.units)) if is_angle(linkage, first) else args.angle
    for branch in linkage.branches:
        values[branch.name] = int(args.branch)
    return linkage, values


#: Besides the code that shapes generated code and reads linkage files: what makes a placement's entry.
PLACEMENT_SHAPING = ("numeric/poses",)


def drawn_placement(args: argparse.Namespace) -> tuple[Placement, dict[str, float]]:
    """The linkage NAME|FILE and its values as :func:`drawn_linkage` gives them, the linkage as a
    :class:`~symlink.numeric.poses.Placement` from the disk cache (:func:`~symlink.numeric.poses.cached_placement`),
    so that a warm drawing imports no SymPy.

    The linkage is taken as ``symlink table NAME|FILE`` takes it (:class:`~symlink.io.table_source.TableSource`: a file's
    ``[dynamics]`` included, whose defaults name masses and loads), and keyed as it keys its entries (the catalog or
    atlas name, or the file's bytes): its facts give the values, and its solver entries are shared.  A linkage
    that cannot be keyed is drawn from the linkage itself (:class:`~symlink.numeric.poses.Geometry`).
    """
    from ..numeric.cache import catalog_key
    from ..numeric.poses import PLACEMENT_ENTRY_KIND, Geometry, cached_placement
    from ..io.table_source import GENERIC_SHAPING, TableSource, facts_values
    source = TableSource(args.linkage)
    if source.request is None:  # not keyed: the reader says what is wrong, or the linkage is drawn as it is
        linkage, values = drawn_linkage(args)
        return Geometry(linkage), values
    facts = source.facts
    values = facts_values(facts, args.set or {}, args.units)
    if args.angle is not None:
        first = facts["inputs"][0]
        values[first] = float(to_radians(args.angle, args.units)) if first in facts["angles"] else args.angle
    for branch in facts["branches"]:
        values[branch] = int(args.branch)
    key = catalog_key("table", ["placement"], PLACEMENT_ENTRY_KIND, source.request,
                      GENERIC_SHAPING + PLACEMENT_SHAPING)
    return cached_placement(key, source.key, lambda: source.found().linkage), values


def _add_catalog_options(parser: argparse.ArgumentParser, what: str) -> None:
    parser.add_argument("--set", type=assignments("NAME=VALUE"), metavar="NAME=VALUE,...",
                        help="change example values (fixed angles in --units), e.g. --set a=20,b=66")
    parser.add_argument("--angle", type=angle, metavar="A", help=f"{what} (in --units, default 0)")
    parser.add_argument("--trace", type=name_list,
                        default=None, metavar="POINTS", help="draw the paths of these points, e.g. --trace H")
    parser.add_argument("--unit", default=None, metavar="UNIT", help="length unit for the axis labels, e.g. mm")


def _default_trace(points: Sequence[str]) -> list[str]:
    """The last named point: the Jansen leg's foot, a coupler's tip."""
    return [points[-1]] if points else []


def _spans_note(rendered, name: str, units: str) -> None:
    if not rendered.full_turn and rendered.spans:
        low, high = (math.degrees(x) if units == "deg" else x for x in rendered.spans[0])
        note(f"the {name} cannot turn fully: swept from {low:.6g} to {high:.6g} {units} and back")


def add_fourbar_plot_options(parser: argparse.ArgumentParser) -> None:
    """The drawing options of ``symlink fourbar``."""
    parser.add_argument("--plot", type=figure_path, metavar="FILE",
                        help="also draw coupler and rocker angle over a full crank turn (.png or .svg)")
    parser.add_argument("--plot-transmission", type=figure_path, metavar="FILE",
                        help="also draw the transmission angle over a full crank turn (.png or .svg)")


def write_fourbar_plots(a: float, b: float, c: float, d: float, signs: Sequence[int], units: str,
                        angles_file: str | None, transmission_file: str | None) -> None:
    """The drawings ``symlink fourbar --plot/--plot-transmission`` asked for."""
    from pathlib import Path

    from ..common.files import write_files_together
    from ..plot import angle_figure, transmission_figure
    from ..plot.figures import figure_bytes
    figures = {}
    if angles_file:
        figures[Path(angles_file)] = figure_bytes(angle_figure(a, b, c, d, branches=signs, units=units), angles_file)
    if transmission_file:
        figures[Path(transmission_file)] = figure_bytes(transmission_figure(a, b, c, d, units=units),
                                                        transmission_file)
    write_files_together(figures)  # both or neither


def _coupler_point(args: argparse.Namespace) -> tuple[float, float] | None:
    """``--coupler-point DIST,ANGLE`` with the angle in radians."""
    if args.coupler_point is None:
        return None
    return args.coupler_point[0], float(to_radians(args.coupler_point[1], args.units))


def run_curve(args: argparse.Namespace) -> int:
    from ..plot import coupler_curve_figure, save_figure
    if fourbar_or_linkage(args, "curve", linkage_only=("set", "angle", "trace", "unit"),
                          fourbar_only=("coupler_point", "crank_angle")):
        return run_draw(args)
    point = _coupler_point(args)
    if point is None:
        raise ValueError("curve: the four-bar form needs --coupler-point DIST,ANGLE")
    crank_angle = None if args.crank_angle is None else float(to_radians(args.crank_angle, args.units))
    distance, angle = point
    figure = coupler_curve_figure(*fourbar_lengths(args), distance, angle, branches=branches(args),
                                  crank_angle=crank_angle)
    save_figure(figure, args.out)
    return 0


#: Frames a second an animation may ask for: a GIF keeps its frame times in hundredths of a second (at most 100 a
#: second), and no screen shows more than a few hundred.
MAX_FPS = 100.0
#: Seconds to draw and encode one frame (measured: 0.2 to 0.25 s of CPU a four-bar frame, 480x360 .gif).
SECONDS_PER_FRAME = 0.2


def check_frames(frames: int) -> None:
    """``ValueError`` (one line, with an estimate of the drawing time) for ``--frames`` outside 1 to
    :data:`~symlink.plot.animation.MAX_FRAMES`, before anything is derived or drawn.

    >>> check_frames(10**9)
    Traceback (most recent call last):
    ValueError: --frames 1,000,000,000 would take about 6.3 years to draw (at most 3,600 frames); use --frames 3,600 or fewer
    """
    from ..common.limits import format_duration
    from ..plot.animation import MAX_FRAMES
    if frames < 1:
        raise ValueError(f"--frames must be at least 1, got {frames}")
    if frames > MAX_FRAMES:
        raise ValueError(f"--frames {frames:,} would take about {format_duration(frames * SECONDS_PER_FRAME)} to draw "
                         f"(at most {MAX_FRAMES:,} frames); use --frames {MAX_FRAMES:,} or fewer")


def run_animate(args: argparse.Namespace) -> int:
    from ..plot.animation import animate
    if not 0 < args.fps <= MAX_FPS:
        raise ValueError(f"--fps must be above 0 and at most {MAX_FPS:g} frames a second, got {args.fps:g}")
    check_frames(args.frames)
    in_place = sys.stderr.isatty()
    every = 1 if in_place else max(1, args.frames // 4)

    def report(done: int, total: int) -> None:  # every frame on a terminal, in place; else every quarter
        if done % every == 0 or done == total:
            end = ("\n" if done == total else "") if in_place else "\n"
            print(f"{chr(13) if in_place else ''}symlink: rendered {done}/{total} frames", end=end,
                  file=sys.stderr, flush=True)

    if fourbar_or_linkage(args, "animate", linkage_only=("set", "angle", "trace", "unit"),
                          fourbar_only=("coupler_point",)):
        from ..plot.animation import animate_placement
        placement, values = drawn_placement(args)
        trace = _default_trace(placement.facts["points"]) if args.trace is None else args.trace
        rendered = animate_placement(placement, values, args.out, frames=args.frames, trace=trace, fps=args.fps,
                                     unit=args.unit, progress=report)
        first = placement.input_names[0]
        role = next((role for role, name in placement.facts["roles"].items() if name == first), first)
        _spans_note(rendered, role, args.units)
        print(f"wrote {rendered.path} ({rendered.frames} frames)")
        return 0
    rendered = animate(*fourbar_lengths(args), args.out, branch=int(args.branch), frames=args.frames,
                       coupler_point=_coupler_point(args), fps=args.fps, progress=report)
    _spans_note(rendered, "crank", "deg")
    if rendered.unassembled:
        angles = ", ".join(f"{float(wrap(math.degrees(t), 180.0)):.6g}" for t in rendered.unassembled)
        note(f"cannot be assembled at crank angles {angles} deg (those frames show the crank only)")
    print(f"wrote {rendered.path} ({rendered.frames} frames)")
    return 0


def run_draw(args: argparse.Namespace) -> int:
    from ..plot import save_figure
    from ..plot.drawing import draw_placement
    placement, values = drawn_placement(args)
    trace = _default_trace(placement.facts["points"]) if args.trace is None else args.trace
    drawing = draw_placement(placement, values, trace=trace, unit=args.unit)
    save_figure(drawing.figure, args.out)
    print(f"wrote {args.out}")
    return 0


def run_view(args: argparse.Namespace) -> int:
    from ..plot.view import SEED001, FourbarView, LinkageView, check_slider_range, interactive_backend
    if fourbar_or_linkage(args, "view", lengths_required=False, linkage_only=("set", "angle", "trace", "unit"),
                          fourbar_only=("crank_angle", "crank_speed")):
        placement, values = drawn_placement(args)  # from the disk cache: a warm view imports no SymPy
        trace = _default_trace(placement.facts["points"]) if args.trace is None else args.trace
        if args.save:
            from matplotlib.figure import Figure
            from ..plot import save_figure
            figure = Figure(figsize=(10, 7))
            LinkageView(placement, values, trace=trace, figure=figure)
            save_figure(figure, args.save)
            return 0
        pyplot = interactive_backend()
        view = LinkageView(placement, values, trace=trace)
        pyplot.show()
        del view
        return 0
    for name, value in SEED001.items():
        if getattr(args, name) is None:
            setattr(args, name, value)
    settings = dict(crank_angle=float(to_radians(args.crank_angle, args.units)), branch=int(args.branch),
                    crank_speed=args.crank_speed)
    lengths = fourbar_lengths(args)
    check_slider_range(*lengths, crank_speed=args.crank_speed)
    if args.save:
        from matplotlib.figure import Figure
        from ..plot import save_figure
        figure = Figure(figsize=(10, 6.5))
        FourbarView(*lengths, figure=figure, **settings)
        save_figure(figure, args.save)
        return 0
    pyplot = interactive_backend()
    fourbar_view = FourbarView(*lengths, **settings)
    pyplot.show()
    del fourbar_view
    return 0


def _catalog_names() -> str:
    from ..io.scene_text import catalog_file_names  # the catalog's files: no linkage built, no SymPy
    return ", ".join(catalog_file_names())


def register(commands) -> None:
    """Register ``symlink draw``, ``curve``, ``animate`` and ``view`` (their options are added when used: the
    catalog and Matplotlib are imported only then)."""
    commands.add_parser("draw", populate=_add_draw_options, **command_help(
        "draw a linkage (catalog name or file) at one input value, with the paths of its points, as PNG or SVG",
        "values of the catalog's example (lengths in any one unit); angles in --units (deg by default)",
        "symlink draw jansen --angle 30 --trace H --out jansen.png"))
    commands.add_parser("curve", populate=_add_curve_options, **command_help(
        "the curve of a coupler point over a crank turn (or of any linkage's points: NAME --trace P), as PNG or SVG",
        "lengths in any one unit; angles in --units (deg by default)",
        "symlink curve --crank 20 --coupler 66 --rocker 56 --ground 80 --coupler-point 40,30 --out curve.png"))
    commands.add_parser("animate", populate=_add_animate_options, **command_help(
        "animate a catalog linkage or a four-bar over a turn of its input (GIF, or MP4 with ffmpeg)",
        "lengths in any one unit; angles in --units (deg by default)",
        "symlink animate --crank 0.1 --coupler 0.4 --rocker 0.25 --ground 0.3 --out fourbar.gif",
        "A catalog NAME animates that linkage with its example values: symlink animate jansen --out jansen.gif.\n"
        "An input that cannot turn fully is swept over its reachable range, forward and back."))
    commands.add_parser("view", populate=_add_view_options, **command_help(
        "an interactive linkage (Matplotlib window with a slider for each parameter)",
        "lengths in any one unit; --crank-angle in --units (deg by default); --crank-speed rad/s",
        "symlink view --crank 0.1 --coupler 0.4 --rocker 0.25 --ground 0.3 --save view.png",
        "Without NAME|FILE the four-bar view (lengths default to the Maple worksheet's); with one, any linkage:\n"
        "symlink view jansen --save jansen-view.png"))


def _add_draw_options(draw: argparse.ArgumentParser) -> None:
    draw.add_argument("linkage", metavar="NAME|FILE",
                      help="a catalog linkage (" + _catalog_names() + ") or a linkage file (.toml)")
    _add_catalog_options(draw, "the first input's value")
    add_branch_option(draw, both=False, default="+1")
    add_units_option(draw, "angles given")
    draw.add_argument("--out", type=figure_path, required=True, metavar="FILE", help=".png or .svg")
    draw.set_defaults(run=run_draw)


def _add_curve_options(curve: argparse.ArgumentParser) -> None:
    curve.add_argument("linkage", nargs="?", metavar="NAME|FILE",
                       help="a catalog linkage or a linkage file: draws it with the paths of --trace points")
    add_fourbar_lengths(curve, beside_linkage=True)
    curve.add_argument("--coupler-point", type=pair("DIST,ANGLE"), metavar="DIST,ANGLE",
                       help="the four-bar's coupler point: distance from B, and angle from the coupler's direction B->C")
    _add_catalog_options(curve, "where the linkage is drawn (with NAME)")
    add_branch_option(curve, default="+1")
    curve.add_argument("--crank-angle", type=angle, metavar="ANGLE",
                       help="where the mechanism is drawn (default: 0, or the first reachable angle)")
    add_units_option(curve, "angles given")
    curve.add_argument("--out", type=figure_path, required=True, metavar="FILE", help=".png or .svg")
    curve.set_defaults(run=run_curve)


def _add_animate_options(animation: argparse.ArgumentParser) -> None:
    from ..plot.animation import FRAMES
    animation.add_argument("linkage", nargs="?", metavar="NAME|FILE",
                           help="a catalog linkage (" + _catalog_names() + ") or a linkage file (.toml)")
    add_fourbar_lengths(animation, beside_linkage=True)
    _add_catalog_options(animation, "where the input starts")
    add_branch_option(animation, both=False, default="+1")
    animation.add_argument("--frames", type=whole, default=FRAMES, help=f"frames in a turn (default {FRAMES})")
    animation.add_argument("--fps", type=finite, default=10.0, help=f"frames per second (default 10, at most {MAX_FPS})")
    animation.add_argument("--coupler-point", type=pair("DIST,ANGLE"), metavar="DIST,ANGLE",
                           help="also draw a coupler point: distance from B, angle from the coupler's direction B->C")
    add_units_option(animation, "coupler point's angle")
    animation.add_argument("--out", type=output_file, required=True, metavar="FILE", help=".gif or .mp4")
    animation.set_defaults(run=run_animate)


def _add_view_options(view: argparse.ArgumentParser) -> None:
    from ..plot.view import SEED001
    view.add_argument("linkage", nargs="?", metavar="NAME|FILE", help="a catalog linkage or a linkage file")
    add_fourbar_lengths(view, defaults=SEED001, beside_linkage=True)
    _add_catalog_options(view, "the first input's initial value (with NAME)")
    view.add_argument("--crank-angle", type=angle, default=0.0, metavar="ANGLE", help="initial (default 0)")
    view.add_argument("--crank-speed", type=finite, default=1.0, metavar="W", help="rad/s (default 1)")
    add_branch_option(view, both=False, default="+1")
    add_units_option(view, "--crank-angle and --angle")
    view.add_argument("--save", type=figure_path, metavar="FILE",
                      help="write the figure to a .png or .svg instead of opening a window")
    view.set_defaults(run=run_view)
