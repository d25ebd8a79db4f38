"""Drawings: angle plots, transmission angle, coupler curves and the seed 000 loop, checked by their data and files."""
import math
import re
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import numpy  # noqa: E402
import pytest  # noqa: E402
from PIL import Image  # noqa: E402

from references import mp_fourbar  # noqa: E402
from symlink.cli import main  # noqa: E402
from symlink.plot import (angle_figure, coupler_curve_figure, coupler_point_linkage, draw_loop,  # noqa: E402
                          fourbar_positions, save_figure, transmission_figure)
from symlink.numeric.reachability import turn_angles  # noqa: E402

SEED001 = (0.1, 0.4, 0.25, 0.30)          # crank-rocker of the worksheet (m)
SEED002 = (16.084, 69.743, 50.0, 70.0)    # crank L2, coupler L3, rocker L4, ground L1 (mm), seed 002 case 4.3
NOT_A_CRANK = (0.3, 0.1, 0.25, 0.30)      # non-Grashof: the crank reaches two arcs only


def wrapped_degrees(radians):
    wrapped = math.remainder(math.degrees(radians), 360.0)
    return 180.0 if wrapped == -180.0 else wrapped


def toggle_angles(a, b, c, d):
    """Crank angles (deg, in [0, 360)) where coupler and rocker are in line: |BD| = b + c or |b - c| (law of cosines)."""
    found = []
    for diagonal in (b + c, abs(b - c)):
        cosine = (a * a + d * d - diagonal * diagonal) / (2 * a * d)
        if -1 < cosine < 1:
            angle = math.degrees(math.acos(cosine))
            found += [angle, 360 - angle]
    return sorted(found)


def lines_by_label(axes):
    return {line.get_label(): line for line in axes.get_lines()}


def finite_points(line, every=17):
    x, y = (numpy.asarray(v, dtype=float) for v in line.get_data())
    keep = numpy.isfinite(x) & numpy.isfinite(y)
    return x[keep][::every], y[keep][::every]


@pytest.mark.parametrize("lengths", [SEED001, NOT_A_CRANK])
def test_angle_plot_lines_match_the_50_digit_reference(lengths):
    figure = angle_figure(*lengths)
    coupler_axes, rocker_axes = figure.axes
    for sign in (1, -1):
        for axes, key in ((coupler_axes, "beta"), (rocker_axes, "phi")):
            x, y = finite_points(lines_by_label(axes)[f"branch {sign:+d}"])
            assert len(x) > 5
            for crank, value in zip(x, y):
                if min((abs(crank - t) for t in toggle_angles(*lengths)), default=1) < 1e-6:
                    continue  # the float toggle angle may fall outside by rounding: checked below
                expected = wrapped_degrees(float(mp_fourbar(*lengths, math.radians(crank), sign)[key]))
                assert abs(value - expected) < 1e-9 or abs(abs(value - expected) - 360) < 1e-9
    assert coupler_axes.get_ylabel() == "coupler angle β (deg)"
    assert rocker_axes.get_xlabel() == "crank angle θ (deg)"


def test_angle_plot_lines_end_at_the_toggles_and_the_rest_is_shaded():
    figure = angle_figure(*NOT_A_CRANK)
    toggles = toggle_angles(*NOT_A_CRANK)
    assert len(toggles) == 4
    x, _ = lines_by_label(figure.axes[1])["branch +1"].get_data()
    x = numpy.asarray(x, dtype=float)
    for toggle in toggles:
        assert numpy.min(numpy.abs(x - toggle)) < 1e-9
    first_reachable = x[numpy.isfinite(lines_by_label(figure.axes[1])["branch +1"].get_ydata())][0]
    for axes in figure.axes:  # the branches meet at the toggles
        lines = lines_by_label(axes)
        for toggle in toggles:
            ends = []
            for sign in ("+1", "-1"):
                line_x, line_y = (numpy.asarray(v, dtype=float) for v in lines[f"branch {sign}"].get_data())
                ends.append(line_y[int(numpy.nanargmin(numpy.abs(line_x - toggle)))])
            assert numpy.isfinite(ends[0]) and abs(ends[0] - ends[1]) < 1e-5
    assert abs(first_reachable - toggles[0]) < 1e-9
    shaded = [patch for patch in figure.axes[1].patches if patch.get_label() == "cannot be assembled"]
    spans = sorted((p.get_x(), p.get_x() + p.get_width()) for p in figure.axes[1].patches)
    assert len(shaded) == 1 and len(spans) == 3
    expected = [(0, toggles[0]), (toggles[1], toggles[2]), (toggles[3], 360)]
    assert numpy.allclose(spans, expected, atol=1e-9)


def test_angle_plot_in_radians_and_one_branch():
    figure = angle_figure(*SEED001, branches=(-1,), units="rad")
    line = lines_by_label(figure.axes[1])["branch -1"]
    assert set(lines_by_label(figure.axes[1])) == {"branch -1"}
    x, y = finite_points(line)
    expected = [math.remainder(float(mp_fourbar(*SEED001, t, -1)["phi"]), 2 * math.pi) for t in x]
    assert numpy.allclose(y, expected, atol=1e-12, rtol=0)
    assert figure.axes[1].get_ylabel() == "rocker angle φ (rad)"


def test_transmission_curve_against_the_law_of_cosines_and_seed_002():
    a, b, c, d = SEED002
    figure = transmission_figure(*SEED002)
    x, y = finite_points(lines_by_label(figure.axes[0])["transmission angle μ"], every=7)
    diagonal = numpy.sqrt(a * a + d * d - 2 * a * d * numpy.cos(numpy.radians(x)))
    expected = numpy.degrees(numpy.arccos((b * b + c * c - diagonal**2) / (2 * b * c)))
    assert numpy.allclose(y, expected, atol=1e-9, rtol=0)
    # Seed 002 prints 50.277 and 90.380 deg from these (rounded) lengths.
    labels = set(lines_by_label(figure.axes[0]))
    assert {"min 50.277° at θ = 0°", "max 90.381° at θ = 180°"} <= labels
    full_x, full_y = lines_by_label(figure.axes[0])["transmission angle μ"].get_data()
    assert abs(numpy.nanmin(full_y) - 50.277) < 1e-3 and abs(numpy.nanmax(full_y) - 90.380) < 1e-3


def test_coupler_point_is_measured_from_b_along_the_turned_coupler():
    a, b, c, d = SEED001
    assert str(coupler_point_linkage().expression("P_y")) == "a*sin(theta) + p*sin(beta + gamma)"
    theta = numpy.radians([0.0, 100.0, 250.0])
    at_c = fourbar_positions(a, b, c, d, theta, 1, ["P_x", "P_y", "C_x", "C_y"], coupler_point=(b, 0.0))
    assert numpy.allclose(at_c["P_x"], at_c["C_x"], atol=1e-15) and numpy.allclose(at_c["P_y"], at_c["C_y"])
    point = (0.3, math.radians(30))
    figure = coupler_curve_figure(a, b, c, d, *point, branches=(1, -1))
    for sign in (1, -1):
        x, y = lines_by_label(figure.axes[0])[f"coupler curve, branch {sign:+d}"].get_data()
        theta = turn_angles(a, b, c, d)  # the documented samples: a full turn, no gaps for a crank-rocker
        assert len(x) == len(theta)
        for k in range(0, len(theta), 37):
            beta = float(mp_fourbar(a, b, c, d, theta[k], sign)["beta"])
            assert abs(a * math.cos(theta[k]) + 0.3 * math.cos(beta + point[1]) - x[k]) < 1e-12
            assert abs(a * math.sin(theta[k]) + 0.3 * math.sin(beta + point[1]) - y[k]) < 1e-12
        full_x, full_y = lines_by_label(figure.axes[0])[f"coupler curve, branch {sign:+d}"].get_data()
        assert abs(full_x[0] - full_x[-1]) < 1e-12 and abs(full_y[0] - full_y[-1]) < 1e-12  # closed over a turn


def test_coupler_curve_draws_the_mechanism_at_the_asked_crank_angle():
    a, b, c, d = SEED001
    figure = coupler_curve_figure(a, b, c, d, 0.3, math.radians(30), crank_angle=math.radians(60))
    reference = mp_fourbar(a, b, c, d, math.radians(60), 1)
    B = (a * math.cos(math.radians(60)), a * math.sin(math.radians(60)))
    C = (B[0] + b * math.cos(float(reference["beta"])), B[1] + b * math.sin(float(reference["beta"])))
    coupler = lines_by_label(figure.axes[0])["coupler"]
    assert numpy.allclose(numpy.transpose(coupler.get_data()), [B, C], atol=1e-12)
    rocker = lines_by_label(figure.axes[0])["rocker"]
    assert numpy.allclose(numpy.transpose(rocker.get_data()), [(d, 0), C], atol=1e-12)


def test_files_are_written_and_read_back(tmp_path):
    png, svg = tmp_path / "angles.png", tmp_path / "angles.svg"
    figure = angle_figure(*SEED001)
    save_figure(figure, png)
    save_figure(figure, svg)
    with Image.open(png) as image:
        assert image.format == "PNG" and image.size == (700, 600)
    root = ElementTree.parse(svg).getroot()
    assert root.tag.endswith("svg") and root.get("width") == "504pt" and root.get("height") == "432pt"
    first = png.read_bytes()
    save_figure(angle_figure(*SEED001), png)
    assert png.read_bytes() == first  # no timestamps: reruns give the same bytes
    assert sorted(p.name for p in tmp_path.iterdir()) == ["angles.png", "angles.svg"]


def test_bad_requests_are_refused_clearly(tmp_path):
    figure = angle_figure(*SEED001)
    with pytest.raises(ValueError, match=r"\.png or \.svg"):
        save_figure(figure, tmp_path / "angles.jpg")
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(ValueError, match="cannot be assembled at any crank angle"):
        angle_figure(1, 10, 1, 1)
    with pytest.raises(ValueError, match="crank must be a positive finite length"):
        transmission_figure(-1, 4, 2.5, 3)
    with pytest.raises(ValueError, match="branches"):
        angle_figure(*SEED001, branches=(2,))
    with pytest.raises(ValueError, match="units"):
        angle_figure(*SEED001, units="grad")
    with pytest.raises(ValueError, match="distance from B must be a positive"):
        coupler_curve_figure(*SEED001, 0.0, 0.0)


SEED000 = ([300, 640.3124, 800.0158, 894.4019], [270, 308.663, 180, 63.435])  # worked example (deg)


def test_draw_loop_draws_the_seed_000_loop_head_to_tail_in_its_colours(tmp_path):
    lengths, degrees = SEED000
    path = tmp_path / "loop.png"
    figure = draw_loop(lengths, [math.radians(t) for t in degrees], path, title="seed 000")
    with Image.open(path) as image:
        assert image.size == (640, 520)
    lines = [line for line in figure.axes[0].get_lines() if line.get_label().startswith("z")]
    assert [matplotlib.colors.to_hex(line.get_color()) for line in lines] == [
        "#ff0000", "#ffff00", "#0000ff", "#008000"]  # red, yellow, blue, green as in the paper
    tip = numpy.zeros(2)
    for line, length, angle in zip(lines, lengths, degrees):
        (x0, x1), (y0, y1) = line.get_data()
        assert numpy.allclose((x0, y0), tip)
        tip = tip + length * numpy.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
        assert numpy.allclose((x1, y1), tip)
    assert numpy.linalg.norm(tip) < 1e-3  # the paper's rounded numbers close to 1e-3 of ~2600
    legend = [text.get_text() for text in figure.legends[0].get_texts()]
    assert legend[0] == "z1: R1 = 300, θ1 = -90°" and legend[2] == "z3: R3 = 800.0158, θ3 = 180°"
    assert figure.axes[0].get_title() == "seed 000"


def test_draw_loop_refuses_a_loop_that_does_not_close(tmp_path):
    with pytest.raises(ValueError, match="does not close"):
        draw_loop([1, 1, 1, 1], [0, 0, 0, 0], tmp_path / "loop.png")
    with pytest.raises(ValueError, match="four lengths and four angles"):
        draw_loop([1, 1, 1], [0, 0, 0], tmp_path / "loop.png")
    with pytest.raises(ValueError, match="finite"):
        draw_loop([1, 1, 1, math.nan], [0, 0, 0, 0], tmp_path / "loop.png")
    assert list(tmp_path.iterdir()) == []


FOURBAR = ["fourbar", "--crank", "0.1", "--coupler", "0.4", "--rocker", "0.25", "--ground", "0.3", "--step", "90"]


def test_fourbar_command_draws_the_tables_linkage(tmp_path, capsys):
    angles, mu = tmp_path / "angles.svg", tmp_path / "mu.png"
    assert main([*FOURBAR, "--branch", "-1", "--plot", str(angles), "--plot-transmission", str(mu)]) == 0
    out, err = capsys.readouterr()
    assert err == "" and len(out.splitlines()) == 5
    assert ElementTree.parse(angles).getroot().tag.endswith("svg")
    assert "branch -1" in angles.read_text() and "branch +1" not in angles.read_text()
    with Image.open(mu) as image:
        assert image.size == (700, 420)


def test_curve_command(tmp_path, capsys):
    out = tmp_path / "curve.png"
    argv = ["curve", "--crank", "0.1", "--coupler", "0.4", "--rocker", "0.25", "--ground", "0.3",
            "--coupler-point", "0.3,30", "--branch", "both", "--out", str(out)]
    assert main(argv) == 0
    with Image.open(out) as image:
        assert image.size == (640, 520)
    assert main([*argv[:-2], "--out", str(tmp_path / "curve.gif")]) == 2
    assert "must end in .png or .svg" in capsys.readouterr().err
    assert main([*argv[:-4], "--out", str(out), "--coupler-point", "0.3"]) == 2
    assert "DIST,ANGLE" in capsys.readouterr().err
    assert main([*FOURBAR, "--plot", str(tmp_path / "x.pdf")]) == 2
    assert not (tmp_path / "x.pdf").exists()


def test_gallery_pictures_exist_and_the_gif_is_small():
    root = Path(__file__).resolve().parents[2]
    text = (root / "docs" / "gallery.md").read_text(encoding="utf-8")
    pictures = re.findall(r"^```\{figure\} (\S+)$", text, re.MULTILINE)
    assert len(pictures) >= 6 and "python docs/pictures.py" in text
    for name in pictures:
        with Image.open(root / "docs" / name) as image:
            assert image.size[0] >= 300
    for gif in (root / "docs/images/fourbar.gif", root / "docs/images/jansen.gif"):
        assert gif.stat().st_size < 400_000
        with Image.open(gif) as image:
            assert image.n_frames == 30


# --- notebooks: figures on given axes, figures that display themselves -------------------------------------------
def test_every_figure_draws_on_given_axes(tmp_path):
    from matplotlib.figure import Figure
    mine = Figure()
    grid = mine.subplots(2, 3)
    assert angle_figure(*SEED001, axes=grid[:, 0]) is mine
    assert transmission_figure(*SEED001, ax=grid[0, 1]) is mine
    assert coupler_curve_figure(*SEED001, 0.2, 0.5, ax=grid[1, 1]) is mine
    angles = [math.radians(t) for t in (270, 308.663, 180, 63.435)]
    assert draw_loop([300, 640.3124, 800.0158, 894.4019], angles, ax=grid[0, 2]) is mine
    assert len(mine.axes) == 6 and not grid[1, 2].get_lines()
    assert set(lines_by_label(grid[0, 0])) >= {"branch +1", "branch -1"}
    assert grid[0, 0].get_ylabel().startswith("coupler angle") and grid[1, 0].get_ylabel().startswith("rocker angle")
    assert any(line.get_label() == "transmission angle μ" for line in grid[0, 1].get_lines())
    assert any(line.get_label().startswith("coupler curve") for line in grid[1, 1].get_lines())
    assert len(grid[0, 2].get_lines()) >= 4 and grid[0, 2].get_legend() is not None
    assert list(tmp_path.iterdir()) == []  # draw_loop without a path writes nothing


def test_given_axes_are_checked():
    from matplotlib.figure import Figure
    one = Figure().add_subplot()
    with pytest.raises(ValueError, match="2 Matplotlib Axes"):
        angle_figure(*SEED001, axes=[one])
    with pytest.raises(ValueError, match="one Matplotlib Axes"):
        transmission_figure(*SEED001, ax="not axes")


def test_returned_figures_display_in_a_notebook_without_pyplot():
    import matplotlib.pyplot as pyplot
    before = pyplot.get_fignums()
    for figure in (angle_figure(*SEED001), transmission_figure(*SEED001),
                   coupler_curve_figure(*SEED001, 0.2, 0.5)):
        png = figure._repr_png_()
        assert png[:8] == b"\x89PNG\r\n\x1a\n"
        with Image.open(__import__("io").BytesIO(png)) as image:
            assert image.width > 200 and image.height > 200
    assert pyplot.get_fignums() == before  # nothing registered with pyplot


def test_ipython_shows_a_returned_figure_as_png_once():
    interactiveshell = pytest.importorskip("IPython.core.interactiveshell",
                                           reason="IPython comes with the notebook extra: pip install -e '.[notebook]'")
    shell = interactiveshell.InteractiveShell.instance()
    data, _ = shell.display_formatter.format(transmission_figure(*SEED001))
    assert "image/png" in data
