"""`symlink view`, driven headless: the widgets' callbacks move the drawing and the readout."""
import math

import matplotlib

matplotlib.use("Agg")

import numpy  # noqa: E402
import pytest  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from PIL import Image  # noqa: E402

from references import mp_fourbar  # noqa: E402
from symlink.cli import main  # noqa: E402
from symlink.plot.view import FourbarView  # noqa: E402

SEED003 = dict(crank=20.0, coupler=66.0, rocker=56.0, ground=80.0)


@pytest.fixture(scope="module")
def view():
    return FourbarView(**SEED003, figure=Figure())


def readout(view):
    """The readout's lines as {label: text after '='}."""
    lines = {}
    for line in view.text.get_text().splitlines():
        if "=" in line:
            label, _, value = line.partition("=")
            lines[label.split()[0] + " " + label.split()[1]] = value.strip()
    return lines


def joints(view):
    links = view.drawing.links
    return {name: numpy.transpose(line.get_data()) for name, line in links.items()}


@pytest.mark.parametrize("angle, branch, speed", [(40.0, "+1", 10.5), (200.0, "-1", -3.0), (0.0, "+1", 1.0)])
def test_sliders_and_branch_buttons_drive_drawing_and_readout(view, angle, branch, speed):
    view.branch_buttons.set_active(0 if branch == "+1" else 1)
    view.sliders["speed"].set_val(speed)
    view.sliders["angle"].set_val(angle)
    theta, sign = math.radians(angle), int(branch)
    ref = mp_fourbar(20, 66, 56, 80, theta, sign, speed)
    B = numpy.array([20 * math.cos(theta), 20 * math.sin(theta)])
    C = B + 66 * numpy.array([math.cos(float(ref["beta"])), math.sin(float(ref["beta"]))])
    drawn = joints(view)
    assert numpy.allclose(drawn["crank"], [[0, 0], B], atol=1e-12)
    assert numpy.allclose(drawn["coupler"], [B, C], atol=1e-12)
    assert numpy.allclose(drawn["rocker"], [[80, 0], C], atol=1e-12)
    state = view.state()
    assert state["assembled"]
    assert abs(state["rocker_speed"] - float(ref["phi_speed"])) < 1e-12 * max(1, abs(speed))
    assert abs(state["coupler_speed"] - float(ref["beta_speed"])) < 1e-12 * max(1, abs(speed))
    text = readout(view)

    def wrapped(radians):
        return (math.degrees(radians) + 180) % 360 - 180

    assert float(text["rocker angle"].rstrip("°")) == pytest.approx(wrapped(float(ref["phi"])), abs=1e-3)
    assert float(text["coupler angle"].rstrip("°")) == pytest.approx(wrapped(float(ref["beta"])), abs=1e-3)
    assert float(text["rocker speed"].split()[0]) == pytest.approx(float(ref["phi_speed"]), abs=1e-4)
    # transmission angle: law of cosines in the triangle B, C, D
    diagonal = math.hypot(80 - B[0], B[1])
    mu = math.degrees(math.acos((66**2 + 56**2 - diagonal**2) / (2 * 66 * 56)))
    assert float(text["transmission μ"].rstrip("°")) == pytest.approx(mu, abs=1e-3)
    assert "full turn" in view.text.get_text()
    assert "Grashof class: crank-rocker" in view.text.get_text()  # 20 + 80 < 66 + 56, crank shortest


def test_seed_003_first_row_is_shown(view):
    view.branch_buttons.set_active(0)
    view.sliders["speed"].set_val(10.5)
    view.sliders["angle"].set_val(0.0)
    assert readout(view)["rocker angle"] == "110.742°"  # DESIGN.md: +1 branch of seed 003 at theta = 0


def test_unassemblable_positions_are_shown_as_such():
    view = FourbarView(figure=Figure())  # seed 001 data by default
    assert view.sliders["crank"].val == 0.1 and view.sliders["ground"].val == 0.30
    view.sliders["crank"].set_val(0.3)
    view.sliders["coupler"].set_val(0.1)
    view.sliders["angle"].set_val(200.0)
    assert not view.state()["assembled"]
    drawn = joints(view)
    assert drawn["coupler"].size == 0 and drawn["rocker"].size == 0  # nothing made up
    theta = math.radians(200)
    assert numpy.allclose(drawn["crank"], [[0, 0], [0.3 * math.cos(theta), 0.3 * math.sin(theta)]])
    text = view.text.get_text()
    assert "cannot be assembled" in text and "coupler angle" not in text and "nan" not in text
    assert view.axes.get_title() == "cannot be assembled at this crank angle"
    # reachable crank range from the law of cosines: |BD| <= b + c
    far = math.degrees(math.acos((0.3**2 + 0.3**2 - 0.35**2) / (2 * 0.3 * 0.3)))
    assert f"{far:.6g}" in text
    view.sliders["angle"].set_val(50.0)  # inside the reachable arc again
    assert view.state()["assembled"] and "cannot" not in view.text.get_text().split("reachable")[0]
    assert joints(view)["coupler"].shape == (2, 2)


def test_toggle_rates_are_undefined_not_numbers():
    text = FourbarView.describe(
        dict(crank=1.0, coupler=2.0, rocker=2.0, ground=2.0, theta=1.0, thetadot=1.0, branch=1),
        dict(assembled=True, coupler=0.5, rocker=0.5, coupler_speed=math.nan, rocker_speed=math.nan,
             transmission=0.0, B_x=0, B_y=0, C_x=0, C_y=0))
    assert text.count("undefined (toggle)") == 2 and "nan" not in text
    assert "outside the usual 45°–135°" in text


def test_bad_lengths_are_refused():
    with pytest.raises(ValueError, match="crank must be a positive finite length"):
        FourbarView(crank=-1, figure=Figure())


def test_view_command(tmp_path, capsys):
    path = tmp_path / "view.png"
    assert main(["view", "--crank-angle", "30", "--branch", "-1", "--save", str(path)]) == 0
    with Image.open(path) as image:
        assert image.size == (1000, 650)
    assert main(["view"]) == 2  # Agg: no window can open
    assert "--save" in capsys.readouterr().err
    assert main(["view", "--rocker", "0", "--save", str(path)]) == 2
    assert "rocker must be a positive finite length" in capsys.readouterr().err


def test_any_linkage_gets_a_slider_for_each_parameter_and_input():
    from matplotlib.figure import Figure

    from symlink.mechanism.catalog import EXAMPLE_VALUES, jansen
    from symlink.plot.view import LinkageView
    linkage = jansen()
    view = LinkageView(linkage, EXAMPLE_VALUES["jansen"], trace=["H"], figure=Figure())
    assert set(view.sliders) == {s.name for s in linkage.parameters + linkage.inputs}
    assert {"alpha", "gamma", "theta"} <= view.angles  # fixed corner angles and the crank, in degrees
    view.sliders["theta"].set_val(90.0)
    assert view.message == "" and abs(view.values()["theta"] - math.pi / 2) < 1e-12
    view.sliders["m"].set_val(200.0)  # a crank longer than the leg: cannot close
    assert "cannot be assembled" in view.message and view.shown["m"] == EXAMPLE_VALUES["jansen"]["m"]


def test_views_build_on_a_given_figure_and_never_show_it(monkeypatch):
    """In a notebook (ipympl) the figure is shown by Jupyter: a view must not call pyplot.show itself."""
    import matplotlib.pyplot as pyplot
    from symlink.mechanism.catalog import slider_crank
    from symlink.plot.view import LinkageView

    def no_show(*arguments, **keywords):
        raise AssertionError("a view called pyplot.show")

    monkeypatch.setattr(pyplot, "show", no_show)
    figure = Figure()
    fourbar_view = FourbarView(**SEED003, figure=figure)
    fourbar_view.sliders["angle"].set_val(45)
    assert fourbar_view.figure is figure and fourbar_view.axes in figure.axes
    other = Figure()
    linkage_view = LinkageView(slider_crank(), dict(a=1.3, b=4.1, offset=0.7), figure=other)
    linkage_view.sliders["theta"].set_val(30)
    assert linkage_view.figure is other and linkage_view.axes in other.axes


def test_the_inline_backend_is_refused_with_the_notebook_advice(monkeypatch):
    import matplotlib.pyplot as pyplot
    from symlink.plot.view import interactive_backend
    monkeypatch.setattr(pyplot, "get_backend", lambda: "module://matplotlib_inline.backend_inline")
    with pytest.raises(ValueError, match="%matplotlib widget"):
        interactive_backend()
    monkeypatch.setattr(pyplot, "get_backend", lambda: "module://ipympl.backend_nbagg")
    assert interactive_backend() is pyplot
