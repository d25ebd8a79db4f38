"""Animation of a four-bar over a crank turn, as GIF (Pillow) or MP4 (ffmpeg).

As in the worksheet of ``seeds/001``: 30 frames by default at crank angles
``2 pi k / frames``, links drawn as bars, pin joints as disks and the ground
pivots marked.  A coupler point, if given, is drawn on the coupler plate with
its whole curve.  Only positions are derived and evaluated (the joints B, C
and the coupler point): an animation never differentiates anything.

Frames where the linkage cannot close show the crank and the ground only,
titled as such.

>>> positions = frame_positions(0.1, 0.4, 0.25, 0.30, frames=4)
>>> [round(math.degrees(t)) for t in positions["theta"]]
[0, 90, 180, 270]
"""
from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy

from ..catalog import fourbar
from ..reachability import TURN_SAMPLES, assembled_crank_range, turn_angles
from ..files import write_atomic
from ..linkage import Linkage
from .figures import MechanismDrawing, check_coupler_point, coupler_point_linkage, extent, fourbar_positions

__all__ = ["FRAMES", "ANIMATION_SUFFIXES", "frame_positions", "animate", "Rendered"]

#: Frames in a turn, as in ``seeds/001`` (t from 0 to 29/30).
FRAMES = 30
#: More frames than this is a mistake, not an animation.
MAX_FRAMES = 3600
#: The files an animation can be written to, and the Matplotlib writer of each.
ANIMATION_SUFFIXES = {".gif": "pillow", ".mp4": "ffmpeg"}
JOINTS = ["B_x", "B_y", "C_x", "C_y"]


@dataclass(frozen=True)
class Rendered:
    """What :func:`animate` wrote: the file, its frame count and the crank angles (rad) that could not close."""

    path: Path
    frames: int
    unassembled: tuple[float, ...]


def frame_positions(a: float, b: float, c: float, d: float, *, branch: int = 1, frames: int = FRAMES,
                    coupler_point: tuple[float, float] | None = None,
                    linkage: Linkage | None = None) -> dict[str, numpy.ndarray]:
    """Crank angles ``theta`` (``2 pi k / frames``) and the joints B, C (and P) at each, positions only.

    ``coupler_point`` is (distance from B, angle from B->C in radians).  A
    fresh linkage is derived unless ``linkage`` is given (the four-bar, or
    :func:`~symlink.plot.coupler_point_linkage` for a coupler point).
    """
    assembled_crank_range(a, b, c, d)
    check_coupler_point(coupler_point)
    if isinstance(frames, bool) or not isinstance(frames, (int, numpy.integer)) or not 1 <= frames <= MAX_FRAMES:
        raise ValueError(f"frames must be a whole number from 1 to {MAX_FRAMES}, got {frames!r}")
    if linkage is None:
        linkage = fourbar() if coupler_point is None else coupler_point_linkage()
    theta = 2 * math.pi * numpy.arange(frames) / frames
    outputs = JOINTS + (["P_x", "P_y"] if coupler_point is not None else [])
    result = fourbar_positions(a, b, c, d, theta, branch, outputs, coupler_point, linkage=linkage)
    return {"theta": theta, **result}


def _writer(path: Path, fps: float):
    from matplotlib import animation
    suffix = path.suffix.lower()
    if suffix not in ANIMATION_SUFFIXES:
        raise ValueError(f"cannot animate into {str(path)!r}: the file must end in {' or '.join(ANIMATION_SUFFIXES)}")
    if suffix == ".gif":
        return animation.PillowWriter(fps=fps)
    if not animation.writers.is_available("ffmpeg"):
        raise ValueError(f"writing {path.name} needs ffmpeg, which was not found on PATH "
                         "(or at Matplotlib's animation.ffmpeg_path); install it, or write a .gif")
    return animation.FFMpegWriter(fps=fps, codec="libx264", extra_args=["-pix_fmt", "yuv420p"])


def animate(a: float, b: float, c: float, d: float, path, *, branch: int = 1, frames: int = FRAMES,
            coupler_point: tuple[float, float] | None = None, fps: float = 10,
            size_px: tuple[int, int] = (480, 360), progress: Callable[[int, int], None] | None = None,
            linkage: Linkage | None = None) -> Rendered:
    """Animate a four-bar over a crank turn into ``path`` (.gif, or .mp4 where ffmpeg is present).

    ``progress(done, total)`` is called after each frame.  The file is written
    atomically: it appears whole or not at all.
    """
    from matplotlib.figure import Figure
    path = Path(path)
    if not (math.isfinite(fps) and fps > 0):
        raise ValueError(f"fps must be a positive number, got {fps}")
    writer = _writer(path, fps)
    width, height = (int(v) for v in size_px)
    if width < 16 or height < 16 or width % 2 or height % 2:
        raise ValueError(f"the frame size must be even and at least 16 pixels, got {width}x{height}")
    positions = frame_positions(a, b, c, d, branch=branch, frames=frames, coupler_point=coupler_point,
                                linkage=linkage)
    dpi = 100
    figure = Figure(figsize=(width / dpi, height / dpi), dpi=dpi, layout="constrained")
    axes = figure.add_subplot()
    xs, ys = [0.0, d, positions["B_x"], positions["C_x"]], [0.0, 0.0, positions["B_y"], positions["C_y"]]
    if coupler_point is not None:
        theta = turn_angles(a, b, c, d, TURN_SAMPLES)
        curve = fourbar_positions(a, b, c, d, theta, branch, ["P_x", "P_y"], coupler_point, linkage=linkage)
        axes.plot(curve["P_x"], curve["P_y"], color="tab:purple", linewidth=1, alpha=0.7, zorder=1)
        xs += [positions["P_x"], curve["P_x"]]
        ys += [positions["P_y"], curve["P_y"]]
    (x0, x1), (y0, y1) = extent(numpy.concatenate([numpy.ravel(v) for v in xs]),
                                numpy.concatenate([numpy.ravel(v) for v in ys]), margin=0.12)
    axes.set_xlim(x0, x1)
    axes.set_ylim(y0, y1)
    axes.set_aspect("equal")
    axes.grid(True, alpha=0.3)
    axes.tick_params(labelsize="small")
    drawing = MechanismDrawing(axes, coupler_point=coupler_point is not None)
    title = axes.set_title("", fontsize="medium")
    unassembled = []
    with tempfile.TemporaryDirectory() as folder:
        scratch = Path(folder) / f"frames{path.suffix.lower()}"
        with writer.saving(figure, str(scratch), dpi):
            for k, angle in enumerate(positions["theta"]):
                B = (positions["B_x"][k], positions["B_y"][k])
                assembled = bool(positions["assembled"][k])
                C = (positions["C_x"][k], positions["C_y"][k]) if assembled else None
                P = (positions["P_x"][k], positions["P_y"][k]) if coupler_point is not None else None
                drawing.update(d, B, C, P)
                label = f"θ = {math.degrees(angle):.0f}°"
                title.set_text(label if assembled else f"{label}: cannot be assembled")
                if not assembled:
                    unassembled.append(float(angle))
                writer.grab_frame()
                if progress is not None:
                    progress(k + 1, len(positions["theta"]))
        write_atomic(path, scratch.read_bytes())
    return Rendered(path, len(positions["theta"]), tuple(unassembled))
