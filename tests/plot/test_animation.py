"""Animation: frames read back from the GIF and MP4, positions against the reference, positions only derived."""
import json
import math
import shutil
import subprocess

import matplotlib

matplotlib.use("Agg")

import numpy  # noqa: E402
import pytest  # noqa: E402
from PIL import Image  # noqa: E402

from references import mp_fourbar  # noqa: E402
from symlink.numeric import cache  # noqa: E402
from symlink.plot.animation import FRAMES, animate, frame_positions  # noqa: E402
from symlink.mechanism.catalog import fourbar  # noqa: E402
from symlink.cli import main  # noqa: E402
from symlink.plot import coupler_point_linkage  # noqa: E402

SEED001 = (0.1, 0.4, 0.25, 0.30)
NOT_A_CRANK = (0.3, 0.1, 0.25, 0.30)
SMALL = (160, 120)


def gif_frames(path):
    with Image.open(path) as image:
        return image.n_frames, image.size


@pytest.fixture
def no_cached_code(tmp_path, monkeypatch):
    """An empty scene cache, so that the solvers are derived here and what is derived can be seen."""
    monkeypatch.setenv(cache.ENVIRONMENT_VARIABLE, str(tmp_path / "cache"))
    cache.clear_memory()
    yield
    cache.clear_memory()


def test_gif_of_seed_001_has_30_frames_and_derives_positions_only(tmp_path, no_cached_code):
    linkage = fourbar()
    path = tmp_path / "fourbar.gif"
    rendered = animate(*SEED001, path, size_px=SMALL, linkage=linkage)
    assert FRAMES == 30 and rendered.frames == 30 and rendered.unassembled == ()
    assert gif_frames(path) == (30, SMALL)
    # velocities and accelerations are cached properties: never touched, never derived
    assert "positions" in linkage.__dict__  # derived here, not taken from a cache
    assert "velocities" not in linkage.__dict__ and "accelerations" not in linkage.__dict__


def test_coupler_point_animation_derives_positions_only_too(tmp_path, no_cached_code):
    linkage = coupler_point_linkage()
    animate(*SEED001, tmp_path / "point.gif", frames=6, coupler_point=(0.3, 0.5), size_px=SMALL, linkage=linkage)
    assert gif_frames(tmp_path / "point.gif") == (6, SMALL)
    assert "positions" in linkage.__dict__
    assert "velocities" not in linkage.__dict__ and "accelerations" not in linkage.__dict__


@pytest.mark.parametrize("branch", [1, -1])
def test_frame_positions_match_the_reference(branch):
    a, b, c, d = SEED001
    point = (0.3, math.radians(30))
    positions = frame_positions(a, b, c, d, branch=branch, frames=30, coupler_point=point)
    assert numpy.allclose(positions["theta"], [2 * math.pi * k / 30 for k in range(30)], rtol=0, atol=1e-15)
    for k in range(0, 30, 4):
        theta = positions["theta"][k]
        beta = float(mp_fourbar(a, b, c, d, theta, branch)["beta"])
        B = (a * math.cos(theta), a * math.sin(theta))
        C = (B[0] + b * math.cos(beta), B[1] + b * math.sin(beta))
        P = (B[0] + point[0] * math.cos(beta + point[1]), B[1] + point[0] * math.sin(beta + point[1]))
        for name, expected in (("B", B), ("C", C), ("P", P)):
            assert abs(positions[f"{name}_x"][k] - expected[0]) < 1e-14
            assert abs(positions[f"{name}_y"][k] - expected[1]) < 1e-14
        assert abs(math.hypot(C[0] - d, C[1]) - c) < 1e-14  # the rocker's length, as a check on the check


def test_a_crank_that_cannot_turn_rocks_over_its_arc_and_every_frame_closes(tmp_path):
    a, b, c, d = NOT_A_CRANK
    progress = []
    rendered = animate(a, b, c, d, tmp_path / "partial.gif", frames=12, size_px=SMALL,
                       progress=lambda done, total: progress.append((done, total)))
    # law of cosines: |BD|^2 = a^2 + d^2 - 2 a d cos(theta) must lie in [(b - c)^2, (b + c)^2]; the arc below 0
    far = math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    near = math.acos((a * a + d * d - (b - c) ** 2) / (2 * a * d))
    assert rendered.unassembled == () and not rendered.full_turn
    assert numpy.allclose(rendered.spans[0], (-far, -near), rtol=0, atol=1e-12)
    theta = frame_positions(a, b, c, d, frames=12)["theta"]
    assert theta.min() >= -far - 1e-12 and theta.max() <= -near + 1e-12
    assert math.isclose(theta[0], -far, abs_tol=1e-12) and math.isclose(theta[6], -near, abs_tol=1e-12)
    assert numpy.allclose(theta[1:6], theta[11:6:-1], rtol=0, atol=1e-12)  # out and back over the same angles
    assert progress == [(k, 12) for k in range(1, 13)]
    assert gif_frames(tmp_path / "partial.gif") == (12, SMALL)
    assert [p.name for p in tmp_path.iterdir()] == ["partial.gif"]  # no hidden frames file left


def test_frames_are_written_beside_the_output_never_in_tmpdir(tmp_path, monkeypatch):
    """A killed run leaves ``.symlink-animation-*.tmp`` in the output folder; the next run removes old ones."""
    import os
    import time
    from symlink.plot import animation
    elsewhere = tmp_path / "tmpdir"
    elsewhere.mkdir()
    monkeypatch.setenv("TMPDIR", str(elsewhere))
    out = tmp_path / "out"
    out.mkdir()
    stale = out / f"{animation.LEFTOVER_PREFIX}dead.tmp"
    stale.mkdir()
    (stale / "frames.gif").write_bytes(b"GIF89a")
    old = time.time() - 2 * animation.LEFTOVER_AGE
    os.utime(stale, (old, old))
    young = out / f"{animation.LEFTOVER_PREFIX}running.tmp"  # a running process's: kept
    young.mkdir()
    seen = []

    def look(done, total):
        seen.append(sorted(p.name for p in out.iterdir()))

    animate(*SEED001, out / "fourbar.gif", frames=2, size_px=SMALL, progress=look)
    assert all(any(name.startswith(animation.LEFTOVER_PREFIX) and name.endswith(".tmp") and
                   name not in (young.name,) for name in names) for names in seen)
    assert sorted(p.name for p in out.iterdir()) == [young.name, "fourbar.gif"]
    assert list(elsewhere.iterdir()) == []


def test_frames_times_pixels_is_capped_before_anything_is_drawn(tmp_path):
    with pytest.raises(ValueError, match=r"3600 frames of 480x360 pixels is 622 million pixels .* lower the frames "
                                         r"to 578 or fewer"):
        animate(*SEED001, tmp_path / "fourbar.gif", frames=3600)
    assert 578 * 480 * 360 <= 100_000_000 < 579 * 480 * 360
    animate(*SEED001, tmp_path / "small.gif", frames=578 // 100, size_px=SMALL)  # well under: fine
    assert [p.name for p in tmp_path.iterdir()] == ["small.gif"]


def test_mp4_read_back_with_ffprobe(tmp_path):
    if shutil.which("ffmpeg") is None or shutil.which("ffprobe") is None:
        pytest.skip("ffmpeg/ffprobe not installed: MP4 output cannot be written or checked here")
    path = tmp_path / "fourbar.mp4"
    animate(*SEED001, path, frames=12, size_px=(320, 240))
    probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                            "stream=nb_read_frames,width,height,codec_name", "-of", "json", str(path)],
                           capture_output=True, text=True, check=True)
    stream = json.loads(probe.stdout)["streams"][0]
    assert (int(stream["nb_read_frames"]), stream["width"], stream["height"]) == (12, 320, 240)
    assert stream["codec_name"] == "h264"


def test_mp4_without_ffmpeg_is_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.setitem(matplotlib.rcParams, "animation.ffmpeg_path", str(tmp_path / "no-ffmpeg-here"))
    with pytest.raises(ValueError, match="needs ffmpeg"):
        animate(*SEED001, tmp_path / "fourbar.mp4", frames=2, size_px=SMALL)
    assert list(tmp_path.iterdir()) == []


def test_bad_requests(tmp_path):
    with pytest.raises(ValueError, match=r"\.gif or \.mp4"):
        animate(*SEED001, tmp_path / "fourbar.avi")
    with pytest.raises(ValueError, match="frames must be a whole number from 1 to 3600"):
        animate(*SEED001, tmp_path / "fourbar.gif", frames=0)
    with pytest.raises(ValueError, match="frames must be a whole number"):
        frame_positions(*SEED001, frames=100_000)
    with pytest.raises(ValueError, match="cannot be assembled at any crank angle"):
        animate(1, 10, 1, 1, tmp_path / "fourbar.gif")
    with pytest.raises(ValueError, match="even"):
        animate(*SEED001, tmp_path / "fourbar.gif", size_px=(161, 120))
    with pytest.raises(ValueError, match="fps"):
        animate(*SEED001, tmp_path / "fourbar.gif", fps=0)
    with pytest.raises(ValueError, match="branch must be"):
        frame_positions(*SEED001, branch=0)
    assert list(tmp_path.iterdir()) == []


def test_animate_command(tmp_path, capsys):
    out = tmp_path / "fourbar.gif"
    argv = ["animate", "--crank", "0.1", "--coupler", "0.4", "--rocker", "0.25", "--ground", "0.3",
            "--branch", "-1", "--frames", "8", "--coupler-point", "0.3,30", "--out", str(out)]
    assert main(argv) == 0
    stdout, stderr = capsys.readouterr()
    assert stdout.strip() == f"wrote {out} (8 frames)"
    assert "rendered 8/8 frames" in stderr
    assert gif_frames(out) == (8, (480, 360))  # the default size
    partial = ["animate", "--crank", "0.3", "--coupler", "0.1", "--rocker", "0.25", "--ground", "0.3",
               "--frames", "4", "--out", str(tmp_path / "partial.gif")]
    assert main(partial) == 0
    assert "the crank cannot turn fully: swept from -71.3707 to -28.955 deg and back" in capsys.readouterr().err
    assert main([*argv[:-2], "--out", str(tmp_path / "fourbar.webm")]) == 2
    assert "must end in .gif or .mp4" in capsys.readouterr().err
    assert main([*argv[:2], "-0.1", *argv[3:]]) == 2
    assert "crank must be a positive finite length" in capsys.readouterr().err


# --- inline in a notebook -----------------------------------------------------------------------------------------
def embedded_frames(html):
    """The PNG frames embedded in Matplotlib's HTML player, decoded."""
    import base64
    import io
    import re
    frames = re.findall(r'data:image/png;base64,([A-Za-z0-9+/=\\\n]+)"', html)
    return [Image.open(io.BytesIO(base64.b64decode(frame.replace("\\", "").replace("\n", "")))) for frame in frames]


def test_inline_animation_embeds_every_frame_and_leaves_no_file(tmp_path, monkeypatch):
    import tempfile
    from symlink.plot.animation import InlineAnimation, inline_animation
    elsewhere = tmp_path / "tmpdir"
    elsewhere.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(elsewhere))
    monkeypatch.chdir(tmp_path)
    seen = []
    shown = inline_animation(fourbar(), dict(a=0.1, b=0.4, c=0.25, d=0.3), frames=5, size_px=SMALL,
                             progress=lambda done, total: seen.append((done, total)))
    assert isinstance(shown, InlineAnimation) and shown._repr_html_() is shown.html
    assert (shown.frames, shown.unassembled, shown.full_turn) == (5, (), True)
    assert seen == [(k, 5) for k in range(1, 6)]  # each frame drawn once
    images = embedded_frames(shown.html)
    assert len(images) == 5
    assert all(image.size == SMALL for image in images)
    assert len({image.tobytes() for image in images}) == 5  # the mechanism moves from frame to frame
    assert "<script" in shown.html and "loop" in shown.html
    assert sorted(p.name for p in tmp_path.iterdir()) == ["tmpdir"] and list(elsewhere.iterdir()) == []


def test_inline_fourbar_animation_rocks_a_crank_that_cannot_turn():
    from symlink.plot.animation import inline_fourbar_animation
    shown = inline_fourbar_animation(*NOT_A_CRANK, frames=6, size_px=SMALL, coupler_point=(0.05, 0.3))
    assert shown.frames == 6 and shown.unassembled == () and not shown.full_turn
    assert len(embedded_frames(shown.html)) == 6


def test_inline_animation_is_capped_before_anything_is_drawn(monkeypatch):
    from symlink.plot import animation

    def never(*arguments, **keywords):
        raise AssertionError("drew before checking the size")

    monkeypatch.setattr(animation, "_linkage_frames", never)
    monkeypatch.setattr(animation, "_fourbar_frames", never)
    with pytest.raises(ValueError, match="lower the frames to 578 or fewer"):
        animation.inline_animation(fourbar(), dict(a=0.1, b=0.4, c=0.25, d=0.3), frames=3600)
    with pytest.raises(ValueError, match="lower the frames to 578 or fewer"):
        animation.inline_fourbar_animation(*SEED001, frames=3600)
    for fps in (0, -1.0, float("nan")):
        with pytest.raises(ValueError, match="fps must be a positive number"):
            animation.inline_fourbar_animation(*SEED001, frames=2, fps=fps)
