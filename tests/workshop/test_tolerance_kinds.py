"""Tolerances by the kind of each parameter: lengths, angles, placements (issue 32, item 1).

A four-bar drawn by its joints (``from_joints``) stands somewhere (its first ground pivot at ``x_A, y_A``),
has a tilted ground (``alpha_AD``) and a coupler point on a ternary link (``alpha_BP``, a fixed angle that
no loop turns).  ``--tolerance`` must band its lengths only, exactly as the same four-bar written by loops
(the catalog's), an angle's band is read in ``--units``, and a placement is toleranced only when named.
The expected values are central differences of a four-bar solved by intersecting two circles, written
here (no symlink solver).
"""
from __future__ import annotations

import cmath
import math

import pytest

from symlink.cli import main
from symlink.mechanism.joints import from_joints
from symlink.numeric.units import parameter_kinds

A0 = complex(10.0, 5.0)           # where the linkage stands
TILT = 0.3                        # the ground line's angle, rad
DESIGN = {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0, "p": 40.0, "gamma": 0.5}
DRAWN_AT = math.radians(40.0)     # the crank's angle from the ground line in the drawing
CHECKED = (0.0, 40.0, 130.0, 250.0)  # crank angles from the ground line, deg
BAND = 0.05


def pose(theta: float, a: float, b: float, c: float, d: float, p: float, gamma: float, tilt: float = TILT,
         origin: complex = A0) -> dict[str, complex | float]:
    """Joints and the rocker's angle at the crank's absolute angle ``theta`` (branch +1: C left of B -> D)."""
    A = origin
    D = A + d * cmath.exp(1j * tilt)
    B = A + a * cmath.exp(1j * theta)
    e = D - B
    L = abs(e)
    along = (b * b - c * c + L * L) / (2 * L)
    C = B + e / L * (along + 1j * math.sqrt(b * b - along * along))
    P = B + p * cmath.exp(1j * (cmath.phase(C - B) + gamma))
    return {"A": A, "B": B, "C": C, "D": D, "P": P, "rocker": cmath.phase(C - D)}


def slope(output, theta: float, name: str) -> float:
    """d(output)/d(name) by central differences: step 1e-6 of a length, 1e-7 rad of an angle, 1e-6 of where
    the first ground pivot stands (``x``)."""
    values = {**DESIGN, "tilt": TILT, "origin": A0}
    if name == "x":
        changed = lambda step: {**values, "origin": A0 + step}  # noqa: E731
        step = 1e-6
    else:
        changed = lambda step: {**values, name: values[name] + step}  # noqa: E731
        step = 1e-7 if name in ("gamma", "tilt") else 1e-6 * values[name]
    return (output(pose(theta, **changed(step))) - output(pose(theta, **changed(-step)))) / (2 * step)


@pytest.fixture(scope="module")
def drawing(tmp_path_factory):
    """The linkage file of the drawing, by its joints."""
    drawn = pose(TILT + DRAWN_AT, **DESIGN)
    rows = "\n".join(f"{j} = [{drawn[j].real!r}, {drawn[j].imag!r}]" for j in "ABCDP")
    path = tmp_path_factory.mktemp("kinds") / "drawn.toml"
    path.write_text('name = "drawn"\ndriver = "A"\n[links]\nground = ["A", "D"]\ncrank = ["A", "B"]\n'
                    f'coupler = ["B", "C", "P"]\nrocker = ["D", "C"]\n[joints]\n{rows}\n')
    return path


def rows(capsys, *arguments) -> list[list[str]]:
    assert main(["tolerance", *arguments, "--format", "csv"]) == 0
    return [line.split(",") for line in capsys.readouterr().out.splitlines()]


def test_every_parameter_knows_its_kind():
    drawn = pose(TILT + DRAWN_AT, **DESIGN)
    linkage = from_joints({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C", "P"],
                           "rocker": ["D", "C"]}, {j: (drawn[j].real, drawn[j].imag) for j in "ABCDP"},
                          driver="A").linkage
    assert parameter_kinds(linkage) == {"AB": "length", "BC": "length", "DC": "length", "AD": "length",
                                        "BP": "length", "alpha_AD": "angle", "alpha_BP": "angle",
                                        "x_A": "placement", "y_A": "placement"}


def test_placed_design_and_catalog_kinds():
    from symlink.mechanism.catalog import fourbar, watt2
    from symlink.synthesis.placement import placed_design
    placed, _ = placed_design(fourbar(), {"a": 1, "b": 3, "c": 3, "d": 3},
                              {"x0": 1.0, "y0": 2.0, "angle": 0.4, "scale": 1.0})
    assert parameter_kinds(placed) == {"a": "length", "b": "length", "c": "length", "d": "length",
                                       "place_x": "placement", "place_y": "placement", "place_angle": "placement"}
    kinds = parameter_kinds(watt2())  # a ground pivot's coordinates are the ground's dimensions, not a placement
    assert kinds["gx"] == kinds["gy"] == "length" and kinds["alpha"] == "angle"


def test_tolerance_by_joints_equals_the_same_linkage_by_loops(drawing, capsys):
    """--tolerance bands the four lengths (not the tilt, nor where A stands): the drawn linkage's rocker band
    equals the catalog four-bar's, and both equal the hand four-bar's central differences."""
    by_loops = rows(capsys, "fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
                    "--tolerance", str(BAND), "--output", "rocker", "--angles", ",".join(map(str, CHECKED)))
    absolute = [k + math.degrees(TILT) for k in CHECKED]
    by_joints = rows(capsys, str(drawing), "--tolerance", str(BAND), "--output", "theta_DC",
                     "--angles", ",".join(repr(t) for t in absolute))
    assert by_joints[0][:3] == ["theta_AB", "theta_DC", "worst_case"]
    for loops_row, joints_row, k in zip(by_loops[1:], by_joints[1:], CHECKED):
        theta = math.radians(k) + TILT
        slopes = [slope(lambda s: s["rocker"], theta, n) for n in "abcd"]
        worst = math.degrees(BAND * sum(abs(s) for s in slopes))
        rss = math.degrees(BAND * math.hypot(*slopes))
        for row in (loops_row, joints_row):
            assert float(row[2]) == pytest.approx(worst, rel=1e-6)
            assert float(row[3]) == pytest.approx(rss, rel=1e-6)
        assert float(joints_row[1]) == pytest.approx(float(loops_row[1]) + math.degrees(TILT), abs=1e-9)
        assert joints_row[5] == {"a": "AB", "b": "BC", "c": "DC", "d": "AD"}[loops_row[5]]
    note = capsys.readouterr().err
    assert "alpha" not in note and "x_A" not in note


def test_coupler_point_angle_is_banded_only_when_named_and_read_in_units(drawing, capsys):
    """A ternary link's fixed angle (off every loop) is an angle: no length band, and its named band in --units."""
    theta = TILT + math.radians(130.0)
    angle = repr(math.degrees(theta))
    point_x = lambda s: s["P"].real  # noqa: E731
    slopes = {n: slope(point_x, theta, n) for n in ("a", "b", "c", "d", "p")}
    lengths_only = rows(capsys, str(drawing), "--tolerance", str(BAND), "--output", "P_x", "--angles", angle)
    assert float(lengths_only[1][1]) == pytest.approx(pose(theta, **DESIGN)["P"].real, abs=1e-9)
    assert float(lengths_only[1][2]) == pytest.approx(BAND * sum(map(abs, slopes.values())), rel=1e-6)
    tilt_band = 0.1  # deg
    turned = rows(capsys, str(drawing), "--tolerance", str(BAND), "--tolerances", f"alpha_BP={tilt_band}",
                  "--units", "deg", "--output", "P_x", "--angles", angle)
    expected = BAND * sum(map(abs, slopes.values())) + math.radians(tilt_band) * abs(slope(point_x, theta, "gamma"))
    assert float(turned[1][2]) == pytest.approx(expected, rel=1e-6)
    in_radians = rows(capsys, str(drawing), "--tolerances", "alpha_BP=0.002", "--units", "rad", "--output", "P_x",
                      "--angles", repr(theta))
    assert float(in_radians[1][2]) == pytest.approx(0.002 * abs(slope(point_x, theta, "gamma")), rel=1e-6)


def test_a_placement_is_toleranced_only_when_named(drawing, capsys):
    """x_A moves every point alike: named, it moves P_x one for one; never by --tolerance."""
    angle = repr(math.degrees(TILT) + 40.0)
    named = rows(capsys, str(drawing), "--tolerances", "x_A=0.1", "--output", "P_x", "--angles", angle)
    assert float(named[1][2]) == pytest.approx(0.1 * slope(lambda s: s["P"].real, TILT + DRAWN_AT, "x"), rel=1e-6)
    assert float(named[1][2]) == pytest.approx(0.1, rel=1e-9)
    rows(capsys, str(drawing), "--tolerance", "0.1", "--output", "P_x", "--angles", angle)
    assert "x_A" not in capsys.readouterr().err
