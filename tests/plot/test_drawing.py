"""Drawings and animations of every catalog linkage: what is drawn is where the joints are, links keep their lengths."""
import math

import matplotlib

matplotlib.use("Agg")

import numpy  # noqa: E402
import pytest  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from PIL import Image  # noqa: E402

from symlink.mechanism.catalog import CATALOG, EXAMPLE_VALUES, JANSEN_HOLY_NUMBERS, fourbar, jansen  # noqa: E402
from symlink.cli import main  # noqa: E402
from symlink.plot import save_figure  # noqa: E402
from symlink.plot.animation import animate_linkage  # noqa: E402
from symlink.numeric.poses import Geometry, sweep_inputs  # noqa: E402
from symlink.plot.drawing import draw_linkage  # noqa: E402

SMALL = (160, 120)
#: Links drawn per entry, counted by hand from each catalog sketch: (bars, polygons, slider blocks).
#: Jansen: crank, lower rocker, links j and k, tie f as bars; the triangles DCE and FGH as polygons.
#: The offset inverted slider-crank: crank AB and the rocker's offset arm DT as bars, the block on the guide.
HAND_COUNT = {"fourbar": (3, 0, 0), "slider-crank": (3, 0, 1), "inverted-slider-crank": (1, 0, 1),
              "offset-inverted-slider-crank": (2, 0, 1),
              "watt2": (4, 1, 0), "stephenson2": (3, 2, 0), "fivebar": (4, 0, 0), "jansen": (5, 2, 0)}


def joints_inside(drawing):
    (x0, x1), (y0, y1) = drawing.axes.get_xlim(), drawing.axes.get_ylim()
    for name, position in drawing.poses.positions.items():
        for z in position[numpy.isfinite(position)]:
            assert x0 < z.real < x1 and y0 < z.imag < y1, (name, z)


@pytest.mark.parametrize("name", sorted(CATALOG))
def test_every_catalog_drawing_has_its_links_and_every_joint_inside_the_axes(name, tmp_path):
    drawing = draw_linkage(CATALOG[name](), EXAMPLE_VALUES[name], trace=(list(CATALOG[name]().points)[-1],))
    assert (len(drawing.bars), len(drawing.polygons), len(drawing.blocks)) == HAND_COUNT[name]
    assert bool(drawing.poses.assembled[0])
    joints_inside(drawing)
    for path in drawing.traces.values():
        x, y = path.get_data()
        assert numpy.isfinite(x).sum() > 100
        (x0, x1), (y0, y1) = drawing.axes.get_xlim(), drawing.axes.get_ylim()
        assert x0 < numpy.nanmin(x) and numpy.nanmax(x) < x1 and y0 < numpy.nanmin(y) and numpy.nanmax(y) < y1
    assert drawing.axes.get_aspect() == 1.0 and "(length unit)" in drawing.axes.get_xlabel()
    save_figure(drawing.figure, tmp_path / "drawing.png")
    with Image.open(tmp_path / "drawing.png") as image:
        assert sum(1 for count in image.convert("L").histogram() if count) > 20  # not blank


def test_jansen_links_keep_jansens_lengths_along_the_foot_path():
    """Every pair of joints on one link stays at the holy-number distance, the triangles' third sides included."""
    n = JANSEN_HOLY_NUMBERS
    geometry = Geometry(jansen())
    poses = geometry.poses(EXAMPLE_VALUES["jansen"], {"theta": numpy.linspace(0, 2 * math.pi, 37)})
    p = poses.positions
    assert poses.assembled.all()
    for first, second, length in (("A", "B", n["m"]), ("B", "C", n["j"]), ("D", "C", n["b"]), ("B", "F", n["k"]),
                                  ("D", "F", n["c"]), ("E", "G", n["f"]), ("F", "G", n["g"]), ("F", "H", n["i"]),
                                  ("D", "E", n["d"]), ("C", "E", n["e"]), ("G", "H", n["h"])):
        assert numpy.allclose(abs(p[first] - p[second]), length, rtol=1e-12), (first, second)
    assert numpy.allclose(p["D"], complex(-n["a"], -n["l"]), rtol=0, atol=1e-12)
    assert (p["H"].imag < p["B"].imag).all()  # the foot hangs below the crank


def test_a_numeric_solution_is_drawn_closed():
    """The Stephenson II six-bar (Newton's method): its binary links keep their lengths in the drawing."""
    values = EXAMPLE_VALUES["stephenson2"]
    drawing = draw_linkage(CATALOG["stephenson2"](), values, trace=("H",))
    p = {name: complex(z[0]) for name, z in drawing.poses.positions.items()}
    assert math.isclose(abs(p["C"] - p["F"]), values["c"], rel_tol=1e-9)
    assert math.isclose(abs(p["E"] - p["H"]), values["g"], rel_tol=1e-9)
    assert math.isclose(abs(p["B"] - p["E"]), values["e"], rel_tol=1e-9)


def test_drawings_compose_on_given_axes():
    figure = Figure()
    left, right = figure.subplots(1, 2)
    first = draw_linkage(fourbar(), EXAMPLE_VALUES["fourbar"], ax=left, unit="mm")
    second = draw_linkage(jansen(), EXAMPLE_VALUES["jansen"], ax=right, trace=("H",))
    assert first.axes is left and second.axes is right and first.figure is figure
    assert left.get_xlabel() == "x (mm)" and right.get_legend() is not None


@pytest.mark.parametrize("name", sorted(CATALOG))
def test_every_catalog_entry_animates_and_every_frame_closes(name, tmp_path):
    path = tmp_path / f"{name}.gif"
    rendered = animate_linkage(CATALOG[name](), EXAMPLE_VALUES[name], path, frames=4, size_px=SMALL)
    assert rendered.frames == 4 and rendered.unassembled == ()
    with Image.open(path) as image:
        assert (image.n_frames, image.size) == (4, SMALL)
    assert [p.name for p in tmp_path.iterdir()] == [path.name]


def test_a_double_rocker_sweeps_its_range_forward_and_back(tmp_path):
    """Non-Grashof (a + b > c + d: the longest and shortest exceed the other two): the crank reaches [-far, far] only, law of cosines."""
    a, b, c, d = 3.2, 1.5, 2.5, 2.0
    far = math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    assert (a * a + d * d - (b - c) ** 2) / (2 * a * d) >= 1  # no inner toggle: one arc through 0
    values = dict(a=a, b=b, c=c, d=d)
    rendered = animate_linkage(fourbar(), values, tmp_path / "rocker.gif", frames=16, size_px=SMALL)
    assert rendered.unassembled == () and not rendered.full_turn
    assert numpy.allclose(rendered.spans, [(-far, far)], rtol=0, atol=1e-9)
    angles = sweep_inputs(rendered.spans, 0.0, 16)
    assert angles[0] == 0.0 and math.isclose(angles.max(), far, abs_tol=1e-9)
    assert math.isclose(angles.min(), -far, abs_tol=1e-9)
    poses = Geometry(fourbar()).poses(values, {"theta": angles})
    assert poses.assembled.all()


@pytest.mark.parametrize("values, trace, message", [
    (dict(a=20, b=66, c=56), (), "needs a value for d"),
    (dict(a=20, b=66, c=56, d=80, q=1), (), "has no value 'q'"),
    (dict(a=20, b=66, c=56, d=80), ("Z",), "no point or joint 'Z'"),
    (dict(a=1, b=10, c=1, d=1), (), "cannot be assembled at theta = 0"),
    (dict(a=20, b=66, c=56, d=float("nan")), (), "d must be a finite number"),
    (dict(a=-20, b=66, c=56, d=80), (), "a must be a positive finite length"),
])
def test_bad_drawing_requests(values, trace, message):
    with pytest.raises(ValueError, match=message):
        draw_linkage(fourbar(), values, trace=trace)


def test_draw_and_animate_commands(tmp_path, capsys):
    assert main(["draw", "jansen", "--angle", "30", "--out", str(tmp_path / "leg.svg")]) == 0
    assert capsys.readouterr().out.strip() == f"wrote {tmp_path / 'leg.svg'}"
    assert main(["animate", "fourbar", "--set", "a=3.2,b=1.5,c=2.5,d=2", "--frames", "4",
                 "--out", str(tmp_path / "rocker.gif")]) == 0
    assert "the crank cannot turn fully: swept from -97.9032 to 97.9032 deg and back" in capsys.readouterr().err
    for argv, message in ((["draw", "jansen", "--set", "zz=1"], "jansen has no value 'zz'"),
                          (["draw", "sixbar"], "no linkage 'sixbar' in the catalog"),
                          (["animate", "jansen", "--crank", "2"], "not both"),
                          (["animate"], "give a catalog NAME"),
                          (["draw", "jansen", "--set", "a"], "NAME=VALUE")):
        assert main([*argv, "--out", str(tmp_path / "x.gif" if argv[0] == "animate" else tmp_path / "x.png")]) == 2
        assert message in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["leg.svg", "rocker.gif"]
