"""The motion-generation drawing: the linkage it draws reaches the target poses, and the picture has its parts."""
import math

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from symlink.plot import save_figure  # noqa: E402
from symlink.plot.synthesis import achieved_poses, motion_figure  # noqa: E402
from symlink.synthesis.motion import motion_generation  # noqa: E402


def crank_rocker_poses(thetas, a=1.0, b=3.0, c=2.5, d=3.2, p=1.5, gamma=0.7, offset=0.3):
    """Poses of a crank-rocker's coupler (branch +1), by plain trigonometry written here."""
    poses = []
    for theta in thetas:
        bx, by = a * math.cos(theta), a * math.sin(theta)
        dx, dy = d - bx, -by
        diagonal = math.hypot(dx, dy)
        along = (b * b - c * c + diagonal * diagonal) / (2 * diagonal)
        height = math.sqrt(b * b - along * along)
        ux, uy = dx / diagonal, dy / diagonal
        cx, cy = bx + along * ux - height * uy, by + along * uy + height * ux
        beta = math.atan2(cy - by, cx - bx)
        poses.append((bx + p * math.cos(beta + gamma), by + p * math.sin(beta + gamma), beta + offset))
    return poses


POSES = crank_rocker_poses(np.radians([10, 70, 130, 200, 280]))


def test_the_drawn_linkage_reaches_every_target_pose():
    design = motion_generation(POSES, defect_free=True)[0]
    joints = achieved_poses(design)
    assert np.allclose(joints["P"], [complex(x, y) for x, y, _ in POSES], atol=1e-9)
    assert np.allclose(np.exp(1j * joints["angle"]), [np.exp(1j * t) for *_, t in POSES], atol=1e-9)
    assert np.allclose(np.abs(joints["B"] - joints["A"]), design.crank)
    assert np.allclose(np.abs(joints["C"] - joints["D"]), design.rocker)


def test_figure_of_five_poses_has_curves_burmester_points_linkage_and_poses():
    design = motion_generation(POSES, defect_free=True)[0]
    figure = motion_figure(POSES, design)
    (axes,) = figure.axes
    labels = {line.get_label() for line in axes.get_lines()}
    assert {"centre-point curve (poses 1-4)", "circle-point curve (pose 1)", "Burmester centre points",
            "crank", "rocker", "fixed pivots", "achieved poses", "coupler curve", "target poses"} <= labels
    targets = next(line for line in axes.get_lines() if line.get_label() == "target poses")
    assert np.allclose(targets.get_xydata(), np.array(POSES)[:, :2])
    assert "crank-rocker" in axes.get_title()


def test_draws_on_given_axes_and_saves(tmp_path):
    mine = Figure()
    left, right = mine.subplots(1, 2)
    assert motion_figure(POSES[:3], ax=right) is mine
    assert not left.get_lines() and right.get_lines()
    path = tmp_path / "motion.svg"
    save_figure(motion_figure(POSES[:4]), path)
    assert path.read_text().lstrip().startswith("<?xml")


def test_bad_axes_and_poses_are_refused():
    with pytest.raises(ValueError, match="Axes"):
        motion_figure(POSES, ax="not axes")
    with pytest.raises(ValueError, match="poses"):
        motion_figure([(0, 0, 0)])
