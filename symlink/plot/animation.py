"""Animations of a linkage over its input, as GIF (Pillow) or MP4 (ffmpeg), or inline in a notebook.

:func:`animate_linkage` animates any linkage, drawn as
:mod:`symlink.plot.drawing` draws it, over a turn of its first input;
:func:`animate` the four-bar from its four lengths, as in the worksheet of
the Maple worksheet: 30 frames by default at crank angles ``2 pi k / frames``,
links drawn as bars, pin joints as disks and the ground pivots marked, with a
coupler point's plate and curve if asked for.  Only positions are derived
and evaluated: an animation never differentiates anything.

An input that cannot turn fully (a rocker, a non-Grashof four-bar) is swept
over its reachable range forward and back
(:func:`~symlink.numeric.poses.sweep_inputs`), so no frame shows a pose that
cannot be assembled.  Frames are written into a hidden file in the output
folder (``.symlink-animation-*.tmp``, removed by the next run if a run is
killed) and renamed into place when complete; an animation is capped by
frames times pixels (:data:`MAX_FRAME_PIXELS`) before anything is drawn.

In a notebook, :func:`inline_animation` and :func:`inline_fourbar_animation`
make the same frames into an :class:`InlineAnimation`: an HTML player with
the frames embedded as PNG (Matplotlib's ``to_jshtml``) that the notebook
shows and that survives ``jupyter nbconvert --to html``, with no file left
behind.  The player is self-contained: Matplotlib's loads its button icons
from a CDN (Font Awesome), so symlink drops that stylesheet and draws the
buttons with Unicode symbols (:data:`PLAYER_SYMBOLS`), and the page works
offline.  The :class:`Rendered` file that :func:`animate_linkage` returns
shows itself too, embedded (a GIF as an ``<img>``, an MP4 as a ``<video>``),
so a notebook whose cell ends with it keeps the animation in its HTML export.

>>> positions = frame_positions(0.1, 0.4, 0.25, 0.30, frames=4)
>>> [round(math.degrees(t)) for t in positions["theta"]]
[0, 90, 180, 270]
"""
from __future__ import annotations

import base64
import html as html_text
import math
import os
import re
import secrets
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Mapping, Sequence

import numpy

from ..common.files import LEFTOVER_AGE, TEMPORARY_SUFFIX, naming, remove_leftovers
from ..numeric.crank_ranges import TURN_SAMPLES, crank_range, turn_angles
from ..numeric.poses import Placement, input_range, sweep_inputs, traced_paths
from .drawing import LinkageDrawing
from .figures import (MechanismDrawing, check_coupler_point, coupler_point_linkage, fourbar_positions,
                      frame_plane)

if TYPE_CHECKING:  # the symbolic side (SymPy) only where a linkage is derived: a placement from the disk cache
    # animates without it (symlink.numeric.poses.cached_placement)
    from matplotlib.figure import Figure
    from numpy.typing import ArrayLike

    from ..numeric.poses import Geometry
    from ..symbolic.linkage import Linkage

__all__ = ["FRAMES", "MAX_FRAMES", "MAX_FRAME_PIXELS", "ANIMATION_SUFFIXES", "LEFTOVER_PREFIX", "frame_positions",
           "animate", "animate_linkage", "animate_placement", "check_animation_size", "Rendered", "InlineAnimation", "inline_animation",
           "inline_fourbar_animation", "self_contained_player", "PLAYER_SYMBOLS"]

#: Frames in a turn, as in the Maple worksheet (t from 0 to 29/30).
FRAMES = 30
#: More frames than this is a mistake, not an animation.
MAX_FRAMES = 3600
#: Frames times pixels an animation may have: a GIF's frames are held in memory (4 bytes a pixel) until written.
MAX_FRAME_PIXELS = 100_000_000
#: The start of the names of the hidden files that frames are written to, in the output folder.
LEFTOVER_PREFIX = ".symlink-animation-"
#: The files an animation can be written to, and the Matplotlib writer of each.
ANIMATION_SUFFIXES = {".gif": "pillow", ".mp4": "ffmpeg"}
JOINTS = ["B_x", "B_y", "C_x", "C_y"]


@dataclass(frozen=True)
class Rendered:
    """What an animation wrote: the file, its frame count, the input values (rad) that could not close
    (none where the input is swept over its reachable range) and that range, ``[(-pi, pi)]`` for a full turn."""

    path: Path
    frames: int
    unassembled: tuple[float, ...]
    spans: tuple[tuple[float, float], ...] = ((-math.pi, math.pi),)

    @property
    def full_turn(self) -> bool:
        """Whether the input turned fully (else it was swept forward and back over ``spans[0]``)."""
        return bool(self.spans) and self.spans[0][1] - self.spans[0][0] >= 2 * math.pi

    def _repr_mimebundle_(self, include=None, exclude=None) -> dict[str, str]:
        """The file embedded for a notebook: ``image/gif`` (what Jupyter shows) and ``text/html`` (an
        ``<img>`` or ``<video>`` with the data inline: what ``nbconvert --to html`` keeps), and a text line."""
        data = base64.b64encode(Path(self.path).read_bytes()).decode("ascii")
        title = html_text.escape(f"{Path(self.path).name}: {self.frames} frames", quote=True)
        if Path(self.path).suffix.lower() == ".gif":
            return {"image/gif": data, "text/html": f'<img src="data:image/gif;base64,{data}" alt="{title}">',
                    "text/plain": repr(self)}
        return {"text/html": f'<video controls loop autoplay muted title="{title}">'
                             f'<source type="video/mp4" src="data:video/mp4;base64,{data}"></video>',
                "text/plain": repr(self)}


@dataclass(frozen=True)
class InlineAnimation:
    """An animation for a notebook: ``html`` (a JavaScript player holding every frame as PNG), shown by
    ``_repr_html_``; ``frames``, ``unassembled`` and ``spans`` as :class:`Rendered` says."""

    html: str
    frames: int
    unassembled: tuple[float, ...]
    spans: tuple[tuple[float, float], ...] = ((-math.pi, math.pi),)

    full_turn = Rendered.full_turn

    def _repr_html_(self) -> str:
        return self.html


@dataclass
class _Frames:
    """A figure ready to animate: ``draw(k)`` poses frame ``k`` of ``count``; what could not close is collected."""

    figure: "Figure"
    count: int
    draw: Callable[[int], None]
    unassembled: list
    spans: tuple


def frame_positions(a: float, b: float, c: float, d: float, *, branch: int = 1, frames: int = FRAMES,
                    coupler_point: tuple[float, float] | None = None,
                    linkage: Linkage | None = None) -> dict[str, numpy.ndarray]:
    """Crank angles ``theta`` and the joints B, C (and P) at each, positions only.

    A crank that turns fully is at ``2 pi k / frames``; one that cannot is
    swept over its reachable range from 0 (or its first arc), forward and
    back (:func:`~symlink.numeric.poses.sweep_inputs`).  ``coupler_point`` is (distance from B, angle from B->C in radians).  A
    fresh linkage is derived unless ``linkage`` is given (the four-bar, or
    :func:`~symlink.plot.coupler_point_linkage` for a coupler point).
    """
    from ..numeric.reachability import assembled_crank_range
    assembled_crank_range(a, b, c, d)
    check_coupler_point(coupler_point)
    if isinstance(frames, bool) or not isinstance(frames, (int, numpy.integer)) or not 1 <= frames <= MAX_FRAMES:
        raise ValueError(f"frames must be a whole number from 1 to {MAX_FRAMES}, got {frames!r}")
    if linkage is None:
        from ..mechanism.catalog import fourbar
        linkage = fourbar() if coupler_point is None else coupler_point_linkage()
    theta = sweep_inputs(crank_range(a, b, c, d), 0.0, frames)
    outputs = JOINTS + (["P_x", "P_y"] if coupler_point is not None else [])
    result = fourbar_positions(a, b, c, d, theta, branch, outputs, coupler_point, linkage=linkage)
    return {"theta": theta, **result}


def _writer(path: Path, fps: float):
    from matplotlib import animation
    suffix = path.suffix.lower()
    if suffix not in ANIMATION_SUFFIXES:
        raise ValueError(f"cannot animate into {str(path)!r}: the file must end in {' or '.join(ANIMATION_SUFFIXES)}")
    if suffix == ".gif":
        return animation.PillowWriter(fps=fps)  # type: ignore[arg-type]  # Matplotlib takes a float rate
    if not animation.writers.is_available("ffmpeg"):
        raise ValueError(f"writing {path.name} needs ffmpeg, which was not found on PATH "
                         "(or at Matplotlib's animation.ffmpeg_path); install it, or write a .gif")
    return animation.FFMpegWriter(fps=fps, codec="libx264",  # type: ignore[arg-type]  # a float rate works
                                  extra_args=["-pix_fmt", "yuv420p"])


def check_animation_size(frames: int, size_px: tuple[int, int]) -> tuple[int, int]:
    """``(width, height)`` of a frame, after ``ValueError`` for a bad size or more than :data:`MAX_FRAME_PIXELS` in all.

    >>> check_animation_size(30, (480, 360))
    (480, 360)
    >>> check_animation_size(3600, (480, 360))
    Traceback (most recent call last):
    ValueError: an animation of 3600 frames of 480x360 pixels is 622 million pixels (about 2.5 GB of frames in memory); the limit is 100 million: lower the frames to 578 or fewer, or the frame size
    """
    width, height = (int(v) for v in size_px)
    if width < 16 or height < 16 or width % 2 or height % 2:
        raise ValueError(f"the frame size must be even and at least 16 pixels, got {width}x{height}")
    if isinstance(frames, bool) or not isinstance(frames, (int, numpy.integer)) or not 1 <= frames <= MAX_FRAMES:
        raise ValueError(f"frames must be a whole number from 1 to {MAX_FRAMES}, got {frames!r}")
    total = frames * width * height
    if total > MAX_FRAME_PIXELS:
        raise ValueError(f"an animation of {frames} frames of {width}x{height} pixels is {total / 1e6:.0f} million "
                         f"pixels (about {4 * total / 1e9:.2g} GB of frames in memory); the limit is "
                         f"{MAX_FRAME_PIXELS / 1e6:.0f} million: lower the frames to "
                         f"{MAX_FRAME_PIXELS // (width * height)} or fewer, or the frame size")
    return width, height


def _checked_request(path, fps: float, frames: int, size_px: tuple[int, int]):
    path = Path(path)
    _check_fps(fps)
    writer = _writer(path, fps)
    width, height = check_animation_size(frames, size_px)
    return path, writer, width, height


def _check_fps(fps: float) -> None:
    if not (isinstance(fps, (int, float, numpy.number)) and math.isfinite(fps) and fps > 0):
        raise ValueError(f"fps must be a positive number, got {fps}")


#: How an embedded frame starts in Matplotlib's HTML player.
FRAME_MARK = "data:image/png;base64,"
#: The Unicode symbol drawn on each button of the player, by the Font Awesome icon class Matplotlib gives it.
PLAYER_SYMBOLS = {"fa-minus": "\u2212", "fa-fast-backward": "\u23ee", "fa-step-backward": "|\u25c0",
                  "fa-play fa-flip-horizontal": "\u25c0", "fa-pause": "\u23f8", "fa-play": "\u25b6",
                  "fa-step-forward": "\u25b6|", "fa-fast-forward": "\u23ed", "fa-plus": "+"}
_STYLESHEET = re.compile(r"<link\b[^>]*>", re.IGNORECASE)
_ICON = re.compile(r'<i class="fa ([^"]*)"></i>')


def self_contained_player(text: str) -> str:
    """Matplotlib's ``to_jshtml`` player without anything loaded from the network.

    Its stylesheet link (Font Awesome, from a CDN) is dropped and each icon is
    replaced by a symbol of :data:`PLAYER_SYMBOLS`; ``ValueError`` where the
    player still refers to another address (a Matplotlib whose player changed).

    >>> self_contained_player('<link rel="stylesheet" href="https://x/fa.css"><button><i class="fa fa-play"></i></button>')
    '<button>\u25b6</button>'
    """
    text = _STYLESHEET.sub("", text)
    text = _ICON.sub(lambda icon: PLAYER_SYMBOLS.get(icon.group(1), "\u2022"), text)
    address = re.search(r"(?:https?:)?//[\w.-]+\.[a-z]{2,}/", text)
    if address is not None:
        raise ValueError(f"the notebook player loads {address.group(0)}: it would not work offline")
    return text


def _html_frames(frames: _Frames, fps: float, progress: Callable[[int, int], None] | None) -> str:
    """The frames as Matplotlib's JavaScript player (``to_jshtml``), every frame embedded, or ``ValueError``."""
    import matplotlib
    from matplotlib.animation import FuncAnimation

    def draw(k: int) -> list:
        frames.draw(k)
        if progress is not None:
            progress(k + 1, frames.count)
        return []

    width, height = frames.figure.canvas.get_width_height()
    # Matplotlib drops the frames past animation.embed_limit (MB) with a warning only: allow what the frame cap
    # allows (PNG frames are smaller than their raw pixels, base64 a third more), and check the count after.
    limit = max(matplotlib.rcParams["animation.embed_limit"], 4 * frames.count * width * height * 1.5 / 2 ** 20)
    with matplotlib.rc_context({"animation.embed_limit": limit}):
        player = FuncAnimation(frames.figure, draw, frames=frames.count, init_func=lambda: [], repeat=True,
                               cache_frame_data=False, interval=1000 / fps)
        text = player.to_jshtml(fps=fps, default_mode="loop")  # type: ignore[arg-type]  # a float rate works
    embedded = text.count(FRAME_MARK)
    if embedded != frames.count:
        raise ValueError(f"the notebook player holds {embedded} of {frames.count} frames; lower the frames or size")
    return self_contained_player(text)


def _write_frames(path: Path, writer, figure, count: int, draw: Callable[[int], None],
                  progress: Callable[[int, int], None] | None) -> None:
    """Draw ``count`` frames into a hidden file beside ``path`` and rename it into place when complete.

    The hidden file is ``.symlink-animation-<random>.tmp/frames.<suffix>`` in the
    output folder (never the system's temporary folder, which may be small or
    shared); what killed runs left there is removed first.
    """
    try:
        _write_frames_beside(path, writer, figure, count, draw, progress)
    except OSError as error:  # a full disk names the user's file, never the hidden one the frames went to
        raise naming(error, path) from None


def _write_frames_beside(path: Path, writer, figure, count: int, draw: Callable[[int], None],
                         progress: Callable[[int, int], None] | None) -> None:
    folder = path.parent
    remove_leftovers(folder if str(folder) else ".", (LEFTOVER_PREFIX,), LEFTOVER_AGE)
    folder.mkdir(parents=True, exist_ok=True)
    scratch_folder = folder / f"{LEFTOVER_PREFIX}{secrets.token_hex(6)}{TEMPORARY_SUFFIX}"
    scratch_folder.mkdir(mode=0o700)
    scratch = scratch_folder / f"frames{path.suffix.lower()}"
    try:
        with writer.saving(figure, str(scratch), figure.dpi):
            for k in range(count):
                draw(k)
                writer.grab_frame()
                if progress is not None:
                    progress(k + 1, count)
        os.chmod(scratch, 0o644)
        os.replace(scratch, path)
    finally:
        scratch.unlink(missing_ok=True)
        scratch_folder.rmdir()


def _figure(width: int, height: int):
    from matplotlib.figure import Figure
    dpi = 100
    figure = Figure(figsize=(width / dpi, height / dpi), dpi=dpi, layout="constrained")
    return figure, figure.add_subplot()


def animate(a: float, b: float, c: float, d: float, path, *, branch: int = 1, frames: int = FRAMES,
            coupler_point: tuple[float, float] | None = None, fps: float = 10,
            size_px: tuple[int, int] = (480, 360), progress: Callable[[int, int], None] | None = None,
            linkage: Linkage | None = None) -> Rendered:
    """Animate a four-bar over a crank turn into ``path`` (.gif, or .mp4 where ffmpeg is present).

    A crank that cannot turn fully is swept over its reachable arc (the one
    holding 0, else the first) forward and back.  ``progress(done, total)``
    is called after each frame.  The file appears whole or not at all.

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths.
    path : str or os.PathLike
        Where to write: ``.gif``, or ``.mp4`` where ffmpeg is present.
    branch : int, optional
        The assembly, +1 (default) or -1.
    frames : int, optional
        Frames over the turn (default 30).
    coupler_point : (float, float), optional
        A coupler point (distance from B, angle from B -> C) whose path is drawn.
    fps : float, optional
        Frames a second (default 10).
    size_px : (int, int), optional
        The frame's size in pixels (default 480 by 360).
    progress : callable, optional
        ``progress(done, total)``, called after each frame.
    linkage : Linkage, optional
        The four-bar to draw (default :func:`fourbar`).

    Returns
    -------
    Rendered
        The path written, the number of frames, and the input's spans.

    Examples
    --------
    >>> import tempfile, pathlib, symlink
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "fourbar.gif"
    >>> rendered = symlink.animate(20, 66, 56, 80, path, frames=2, size_px=(80, 60))
    >>> rendered.frames, rendered.full_turn, path.read_bytes()[:3]  # seed 003 is a crank-rocker
    (2, True, b'GIF')
    """
    path, writer, width, height = _checked_request(path, fps, frames, size_px)
    drawn = _fourbar_frames(a, b, c, d, branch, frames, coupler_point, linkage, width, height)
    _write_frames(path, writer, drawn.figure, drawn.count, drawn.draw, progress)
    return Rendered(path, drawn.count, tuple(drawn.unassembled), drawn.spans)


def inline_fourbar_animation(a: float, b: float, c: float, d: float, *, branch: int = 1, frames: int = FRAMES,
                             coupler_point: tuple[float, float] | None = None, fps: float = 10,
                             size_px: tuple[int, int] = (480, 360),
                             progress: Callable[[int, int], None] | None = None,
                             linkage: Linkage | None = None) -> InlineAnimation:
    """:func:`animate`'s frames as an :class:`InlineAnimation` for a notebook; no file is written.

    >>> shown = inline_fourbar_animation(0.1, 0.4, 0.25, 0.30, frames=3, size_px=(160, 120))
    >>> shown.frames, shown.html.count("data:image/png;base64,")
    (3, 3)
    """
    _check_fps(fps)
    width, height = check_animation_size(frames, size_px)
    drawn = _fourbar_frames(a, b, c, d, branch, frames, coupler_point, linkage, width, height)
    html = _html_frames(drawn, fps, progress)
    return InlineAnimation(html, drawn.count, tuple(drawn.unassembled), drawn.spans)


def _fourbar_frames(a: float, b: float, c: float, d: float, branch: int, frames: int,
                    coupler_point: tuple[float, float] | None, linkage: Linkage | None,
                    width: int, height: int) -> _Frames:
    """The four-bar's figure and frame drawer, as :func:`animate` describes."""
    positions = frame_positions(a, b, c, d, branch=branch, frames=frames, coupler_point=coupler_point,
                                linkage=linkage)
    figure, axes = _figure(width, height)
    xs: list["ArrayLike"] = [0.0, d, positions["B_x"], positions["C_x"]]
    ys: list["ArrayLike"] = [0.0, 0.0, positions["B_y"], positions["C_y"]]
    if coupler_point is not None:
        theta = turn_angles(a, b, c, d, TURN_SAMPLES)
        curve = fourbar_positions(a, b, c, d, theta, branch, ["P_x", "P_y"], coupler_point, linkage=linkage)
        axes.plot(curve["P_x"], curve["P_y"], color="tab:purple", linewidth=1, alpha=0.7, zorder=1)
        xs += [positions["P_x"], curve["P_x"]]
        ys += [positions["P_y"], curve["P_y"]]
    frame_plane(axes, numpy.concatenate([numpy.ravel(v) for v in xs]),
                numpy.concatenate([numpy.ravel(v) for v in ys]), None, margin=0.12)
    axes.tick_params(labelsize="small")
    drawing = MechanismDrawing(axes, coupler_point=coupler_point is not None)
    title = axes.set_title("", fontsize="medium")
    unassembled = []

    def draw(k: int) -> None:
        angle = positions["theta"][k]
        B = (positions["B_x"][k], positions["B_y"][k])
        assembled = bool(positions["assembled"][k])
        C = (positions["C_x"][k], positions["C_y"][k]) if assembled else None
        P = (positions["P_x"][k], positions["P_y"][k]) if coupler_point is not None else None
        drawing.update(d, B, C, P)
        label = f"θ = {math.degrees(angle):.0f}°"
        title.set_text(label if assembled else f"{label}: cannot be assembled")
        if not assembled:
            unassembled.append(float(angle))

    return _Frames(figure, len(positions["theta"]), draw, unassembled, tuple(crank_range(a, b, c, d)))


def animate_linkage(linkage: Linkage, values: Mapping[str, float], path, *, frames: int = FRAMES,
                    trace: Sequence[str] = (), fps: float = 10, size_px: tuple[int, int] = (480, 360),
                    unit: str | None = None, guess: Mapping[str, float] | None = None,
                    progress: Callable[[int, int], None] | None = None,
                    geometry: Geometry | None = None) -> Rendered:
    """Animate any linkage over its first input into ``path`` (.gif, or .mp4 where ffmpeg is present).

    ``values`` by symbol name as for :func:`~symlink.plot.drawing.draw_linkage`;
    the first input starts at its value there (default 0) and turns fully
    where it can, else is swept over its reachable range forward and back;
    ``trace`` names points whose paths are drawn.  Linkages without a closed
    form follow Newton's method from ``guess`` (default: one found).

    Parameters
    ----------
    linkage : Linkage
        Any linkage.
    values : mapping of str to float
        Every parameter by name, as for :func:`draw_linkage`; the first input starts at its value there.
    path : str or os.PathLike
        Where to write: ``.gif``, or ``.mp4`` where ffmpeg is present.
    frames : int, optional
        How many frames (default 30).
    trace : sequence of str, optional
        Points whose paths are drawn.
    fps : float, optional
        Frames a second (default 10).
    size_px : (int, int), optional
        The frame's size in pixels (default 480 by 360).
    unit : str, optional
        The lengths' unit, for the axes' labels.
    guess : mapping of str to float, optional
        For a linkage without a closed form: its unknowns near an assembly.
    progress : callable, optional
        ``progress(done, total)``, called after each frame.
    geometry : Geometry, optional
        The linkage's geometry, if made already.

    Returns
    -------
    Rendered
        The path written, the number of frames, unassembled inputs and the input's spans.

    Examples
    --------
    >>> import tempfile, pathlib, symlink
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "rocker.gif"
    >>> rendered = symlink.animate_linkage(symlink.fourbar(), dict(a=0.3, b=0.1, c=0.25, d=0.3), path, frames=4,
    ...                                    size_px=(160, 120))
    >>> rendered.frames, rendered.unassembled, rendered.full_turn  # a + d > b + c: the crank rocks
    (4, (), False)
    """
    if geometry is None:
        from ..numeric.poses import Geometry
        geometry = Geometry(linkage)
    return animate_placement(geometry, values, path, frames=frames, trace=trace, fps=fps, size_px=size_px, unit=unit,
                             guess=guess, progress=progress)


def animate_placement(geometry: Placement, values: Mapping[str, float], path, *, frames: int = FRAMES,
                      trace: Sequence[str] = (), fps: float = 10, size_px: tuple[int, int] = (480, 360),
                      unit: str | None = None, guess: Mapping[str, float] | None = None,
                      progress: Callable[[int, int], None] | None = None) -> Rendered:
    """:func:`animate_linkage` from a linkage's :class:`~symlink.numeric.poses.Placement`: what a drawing needs of
    it, as plain data and NumPy code, such as :func:`~symlink.numeric.poses.cached_placement` takes from the disk
    cache (the animation then imports no SymPy).  Arguments, result and ``ValueError`` as for
    :func:`animate_linkage`.

    >>> import tempfile, pathlib
    >>> from symlink.mechanism.catalog import fourbar
    >>> from symlink.numeric.poses import Geometry
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "fourbar.gif"
    >>> animate_placement(Geometry(fourbar()), dict(a=0.1, b=0.4, c=0.25, d=0.3), path, frames=2,
    ...                   size_px=(160, 120)).frames
    2
    """
    path, writer, width, height = _checked_request(path, fps, frames, size_px)
    drawn = _linkage_frames(geometry, values, frames, trace, unit, guess, width, height)
    _write_frames(path, writer, drawn.figure, drawn.count, drawn.draw, progress)
    return Rendered(path, drawn.count, tuple(drawn.unassembled), drawn.spans)


def inline_animation(linkage: Linkage, values: Mapping[str, float], *, frames: int = FRAMES,
                     trace: Sequence[str] = (), fps: float = 10, size_px: tuple[int, int] = (480, 360),
                     unit: str | None = None, guess: Mapping[str, float] | None = None,
                     progress: Callable[[int, int], None] | None = None,
                     geometry: Geometry | None = None) -> InlineAnimation:
    """:func:`animate_linkage`'s frames as an :class:`InlineAnimation` for a notebook; no file is written.

    The last expression of a notebook cell shows it as a player; ``.html``
    is the HTML itself (for ``IPython.display.HTML`` or a page).

    Parameters
    ----------
    linkage : Linkage
        Any linkage.
    values : mapping of str to float
        Every parameter by name, as for :func:`draw_linkage`; the first input starts at its value there.
    frames : int, optional
        How many frames (default 30).
    trace : sequence of str, optional
        Points whose paths are drawn.
    fps : float, optional
        Frames a second (default 10).
    size_px : (int, int), optional
        The frame's size in pixels (default 480 by 360).
    unit : str, optional
        The lengths' unit, for the axes' labels.
    guess : mapping of str to float, optional
        For a linkage without a closed form: its unknowns near an assembly.
    progress : callable, optional
        ``progress(done, total)``, called after each frame.
    geometry : Geometry, optional
        The linkage's geometry, if made already.

    Returns
    -------
    InlineAnimation
        The frames, shown as a player by a notebook; ``.html`` is the HTML.

    Examples
    --------
    >>> import symlink
    >>> shown = symlink.inline_animation(symlink.fourbar(), dict(a=0.1, b=0.4, c=0.25, d=0.3), frames=4,
    ...                                  size_px=(160, 120))
    >>> shown.frames, shown.full_turn, shown._repr_html_().count("data:image/png;base64,")
    (4, True, 4)
    """
    _check_fps(fps)
    width, height = check_animation_size(frames, size_px)
    if geometry is None:
        from ..numeric.poses import Geometry
        geometry = Geometry(linkage)
    drawn = _linkage_frames(geometry, values, frames, trace, unit, guess, width, height)
    html = _html_frames(drawn, fps, progress)
    return InlineAnimation(html, drawn.count, tuple(drawn.unassembled), drawn.spans)


def _linkage_frames(geometry: Placement, values: Mapping[str, float], frames: int, trace: Sequence[str],
                    unit: str | None, guess: Mapping[str, float] | None, width: int, height: int) -> _Frames:
    """Any linkage's figure and frame drawer, as :func:`animate_linkage` describes."""
    completed = geometry.check_values(values)
    first = geometry.input_names[0]
    spans = input_range(geometry, completed, guess)
    if not spans:
        raise ValueError(f"{geometry.name} cannot be assembled at any value of {first} with the values given")
    angles = sweep_inputs(spans, float(completed[first]), frames)
    if guess is None and not geometry.closed_form:
        guess = geometry.find_guess(completed)
    completed[first] = float(angles[0])
    poses = geometry.poses(completed, {first: angles}, guess)
    paths = traced_paths(geometry, completed, trace, guess)
    figure, axes = _figure(width, height)
    drawing = LinkageDrawing(axes, geometry, poses, paths, unit)
    axes.tick_params(labelsize="small")
    title = axes.set_title("", fontsize="medium")
    unassembled = []
    angle_input = first in geometry.angles

    def draw(k: int) -> None:
        drawing.update(k)
        value = angles[k]
        label = f"{first} = {math.degrees(value):.0f}°" if angle_input else f"{first} = {value:.4g}"
        if not poses.assembled[k]:
            unassembled.append(float(value))
            label += ": cannot be assembled"
        title.set_text(label)

    return _Frames(figure, frames, draw, unassembled, tuple(spans))
