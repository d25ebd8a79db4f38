"""Pictures from the command line: ``symlink curve``, ``animate``, ``view`` and ``fourbar --plot``."""
from __future__ import annotations

import argparse
import math
import sys
from typing import Sequence

from ..angles import to_radians, wrap
from .options import (add_branch_option, add_fourbar_lengths, add_units_option, branches, command_help, figure_path,
                      finite, fourbar_lengths, pair, whole)
from .output import note

__all__ = ["register", "add_fourbar_plot_options", "write_fourbar_plots"]


def add_fourbar_plot_options(parser: argparse.ArgumentParser) -> None:
    """The drawing options of ``symlink fourbar``."""
    parser.add_argument("--plot", type=figure_path, metavar="FILE",
                        help="also draw coupler and rocker angle over a full crank turn (.png or .svg)")
    parser.add_argument("--plot-transmission", type=figure_path, metavar="FILE",
                        help="also draw the transmission angle over a full crank turn (.png or .svg)")


def write_fourbar_plots(a: float, b: float, c: float, d: float, signs: Sequence[int], units: str,
                        angles_file: str | None, transmission_file: str | None) -> None:
    """The drawings ``symlink fourbar --plot/--plot-transmission`` asked for."""
    from ..plot import angle_figure, save_figure, transmission_figure
    if angles_file:
        save_figure(angle_figure(a, b, c, d, branches=signs, units=units), angles_file)
    if transmission_file:
        save_figure(transmission_figure(a, b, c, d, units=units), transmission_file)


def _coupler_point(args: argparse.Namespace) -> tuple[float, float] | None:
    """``--coupler-point DIST,ANGLE`` with the angle in radians."""
    if args.coupler_point is None:
        return None
    return args.coupler_point[0], float(to_radians(args.coupler_point[1], args.units))


def run_curve(args: argparse.Namespace) -> int:
    from ..plot import coupler_curve_figure, save_figure
    crank_angle = None if args.crank_angle is None else float(to_radians(args.crank_angle, args.units))
    distance, angle = _coupler_point(args)
    figure = coupler_curve_figure(*fourbar_lengths(args), distance, angle, branches=branches(args),
                                  crank_angle=crank_angle)
    save_figure(figure, args.out)
    return 0


def run_animate(args: argparse.Namespace) -> int:
    from ..plot.animation import animate
    in_place = sys.stderr.isatty()
    every = 1 if in_place else max(1, args.frames // 4)

    def report(done: int, total: int) -> None:  # every frame on a terminal, in place; else every quarter
        if done % every == 0 or done == total:
            end = ("\n" if done == total else "") if in_place else "\n"
            print(f"{chr(13) if in_place else ''}symlink: rendered {done}/{total} frames", end=end,
                  file=sys.stderr, flush=True)

    rendered = animate(*fourbar_lengths(args), args.out, branch=int(args.branch), frames=args.frames,
                       coupler_point=_coupler_point(args), fps=args.fps, progress=report)
    if rendered.unassembled:
        angles = ", ".join(f"{float(wrap(math.degrees(t), 180.0)):.6g}" for t in rendered.unassembled)
        note(f"cannot be assembled at crank angles {angles} deg (those frames show the crank only)")
    print(f"wrote {rendered.path} ({rendered.frames} frames)")
    return 0


def run_view(args: argparse.Namespace) -> int:
    from ..plot.view import FourbarView, check_slider_range, interactive_backend
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
    view = FourbarView(*lengths, **settings)
    pyplot.show()
    del view
    return 0


def register(commands) -> None:
    """Register ``symlink curve``, ``animate`` and ``view``."""
    from ..plot.animation import FRAMES
    from ..plot.view import SEED001
    curve = commands.add_parser("curve", **command_help(
        "the curve of a coupler point over a crank turn, as PNG or SVG",
        "lengths in any one unit; angles in --units (deg by default)",
        "symlink curve --crank 20 --coupler 66 --rocker 56 --ground 80 --coupler-point 40,30 --out curve.png"))
    add_fourbar_lengths(curve)
    curve.add_argument("--coupler-point", type=pair("DIST,ANGLE"), required=True, metavar="DIST,ANGLE",
                       help="distance from B, and angle from the coupler's direction B->C")
    add_branch_option(curve, default="+1")
    curve.add_argument("--crank-angle", type=finite, metavar="ANGLE",
                       help="where the mechanism is drawn (default: 0, or the first reachable angle)")
    add_units_option(curve, "angles given")
    curve.add_argument("--out", type=figure_path, required=True, metavar="FILE", help=".png or .svg")
    curve.set_defaults(run=run_curve)

    animation = commands.add_parser("animate", **command_help(
        "animate a four-bar over a crank turn (GIF, or MP4 with ffmpeg)",
        "lengths in any one unit; the coupler point's angle in --units (deg by default)",
        "symlink animate --crank 0.1 --coupler 0.4 --rocker 0.25 --ground 0.3 --out fourbar.gif"))
    add_fourbar_lengths(animation)
    add_branch_option(animation, both=False, default="+1")
    animation.add_argument("--frames", type=whole, default=FRAMES, help=f"frames in a turn (default {FRAMES})")
    animation.add_argument("--fps", type=finite, default=10.0, help="frames per second (default 10)")
    animation.add_argument("--coupler-point", type=pair("DIST,ANGLE"), metavar="DIST,ANGLE",
                           help="also draw a coupler point: distance from B, angle from the coupler's direction B->C")
    add_units_option(animation, "coupler point's angle")
    animation.add_argument("--out", required=True, metavar="FILE", help=".gif or .mp4")
    animation.set_defaults(run=run_animate)

    view = commands.add_parser("view", **command_help(
        "an interactive four-bar (Matplotlib window with sliders)",
        "lengths in any one unit; --crank-angle in --units (deg by default); --crank-speed rad/s",
        "symlink view --crank 0.1 --coupler 0.4 --rocker 0.25 --ground 0.3 --save view.png"))
    add_fourbar_lengths(view, defaults=SEED001)
    view.add_argument("--crank-angle", type=finite, default=0.0, metavar="ANGLE", help="initial (default 0)")
    view.add_argument("--crank-speed", type=finite, default=1.0, metavar="W", help="rad/s (default 1)")
    add_branch_option(view, both=False, default="+1")
    add_units_option(view, "--crank-angle")
    view.add_argument("--save", type=figure_path, metavar="FILE",
                      help="write the figure to a .png or .svg instead of opening a window")
    view.set_defaults(run=run_view)
