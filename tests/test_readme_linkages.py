"""The README's own-linkage example (the press): it prints what its comments say, and what it defines is right.

The slider position is checked against plain geometry, not against symlink: joint C is where the
circles about B (radius b) and D (radius c) meet, left of B->D on branch +1; F lies on the line
y = h at distance e from C, the larger x on branch +1 (case 2b: +1 is the larger length).
"""
import contextlib
import io
import math

import numpy
import pytest

from readme_text import fenced_blocks, readme


def run_example(tmp_path, monkeypatch) -> tuple[str, dict]:
    """Run the README's first python block in ``tmp_path``; (what it printed, its namespace)."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    code = fenced_blocks(readme(), "python")[0]
    assert "Linkage(" in code and len(code.strip().splitlines()) <= 20  # a new linkage, short
    namespace: dict = {"__name__": "__readme__"}
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "README own linkage", "exec"), namespace)  # our own README
    return out.getvalue(), namespace


def press_by_geometry(theta, a, b, c, d, e, h):
    """Slider position s of the press on branches +1, +1, by circle intersections (no symlink)."""
    bx, by = a * math.cos(theta), a * math.sin(theta)
    dx, dy = d - bx, -by
    w = math.hypot(dx, dy)
    along = (w * w + b * b - c * c) / (2 * w)          # from B towards D, to the foot of C
    across = math.sqrt(b * b - along * along)         # C's distance from the line B->D
    cx = bx + (along * dx - across * dy) / w          # the left normal of B->D is (-dy, dx)
    cy = by + (along * dy + across * dx) / w
    return cx + math.sqrt(e * e - (h - cy) ** 2)


def test_the_press_prints_its_plan_and_its_slider_speed(tmp_path, monkeypatch):
    printed, _ = run_example(tmp_path, monkeypatch)
    assert "loop ABCD, case 3 (two angles): beta, phi from theta" in printed
    assert "loop DCF, case 2b (length and angle of different vectors): psi, s from phi (step 1)" in printed
    assert r"- \frac{c \dot{\phi} \sin{\left(\phi - \psi \right)}}{\cos{\left(\psi \right)}}" in printed
    tex = (tmp_path / "press.tex").read_text()
    assert tex.startswith(r"\documentclass") and "A press" in tex


@pytest.mark.parametrize("theta", [0.0, 0.7, 2.0, 4.0])
def test_the_press_solves_to_the_geometry(tmp_path, monkeypatch, theta):
    from symlink.numeric.solver import Solver

    _, namespace = run_example(tmp_path, monkeypatch)
    lengths = dict(a=1.0, b=3.5, c=3.0, d=3.2, e=4.0, h=4.0)
    result = Solver(namespace["press"], ["s"])(theta=theta, branch_ABCD=1, branch_DCF=1, **lengths)
    assert float(result["s"]) == pytest.approx(press_by_geometry(theta, **lengths), rel=1e-12)


def test_the_press_slider_speed_is_the_slope_of_its_position(tmp_path, monkeypatch):
    """ds/dt at unit crank speed against a central difference of the geometric position."""
    from symlink.numeric.solver import Solver

    _, namespace = run_example(tmp_path, monkeypatch)
    lengths = dict(a=1.0, b=3.5, c=3.0, d=3.2, e=4.0, h=4.0)
    theta, step = 1.1, 1e-5
    slope = (press_by_geometry(theta + step, **lengths) - press_by_geometry(theta - step, **lengths)) / (2 * step)
    result = Solver(namespace["press"], ["sdot"])(theta=numpy.array([theta]), thetadot=1.0,
                                                 branch_ABCD=1, branch_DCF=1, **lengths)
    assert float(result["sdot"][0]) == pytest.approx(slope, rel=1e-8)
