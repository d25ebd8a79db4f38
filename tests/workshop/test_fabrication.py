"""Parts to cut (symlink.workshop.fabrication): hole centres at the design's dimensions, in the SVG and the DXF.

Expected dimensions come from the design's values by hand (a bar's length, the law of
cosines for a ternary link, a slider's travel from Pythagoras), not from the code under test.
The SVG is read back with xml.etree and its arcs are taken to their centres by the SVG
specification's own endpoint-to-centre conversion (SVG 1.1, appendix F.6.5), written here.
"""
from __future__ import annotations

import importlib.util
import math
import os
import sys
import xml.etree.ElementTree as ET

import numpy
import pytest

from symlink.mechanism.catalog import EXAMPLE_VALUES, fourbar, inverted_slider_crank, slider_crank, watt2
from symlink.workshop.fabrication import link_parts, svg_text, write_dxf, write_svg

SVG = "{http://www.w3.org/2000/svg}"
FOURBAR = {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0}
PIN = 4.0


def _fourbar_parts():
    return link_parts(fourbar(), FOURBAR, pin_diameter=PIN)


def test_every_link_of_the_four_bar_is_a_bar_with_holes_at_its_length():
    parts = _fourbar_parts()
    assert [p.name for p in parts] == ["ground", "crank", "coupler", "rocker"]
    expected = {"ground": ("A", "D", 80.0), "crank": ("A", "B", 20.0), "coupler": ("B", "C", 66.0),
                "rocker": ("C", "D", 56.0)}
    for part in parts:
        first, second, length = expected[part.name]
        assert part.holes[first] == (0.0, 0.0)
        assert part.holes[second][0] == pytest.approx(length, abs=1e-9) and part.holes[second][1] == 0.0
        assert part.radius == PIN and part.pin_diameter == PIN  # width 2 x pin by default
        assert len(part.outline()) == 2  # two straight edges, each followed by a half circle


def test_a_ternary_link_and_the_ground_plate_by_the_law_of_cosines():
    v = EXAMPLE_VALUES["watt2"]
    parts = {p.name: p for p in link_parts(watt2(), v, pin_diameter=0.3)}
    rocker, ground = parts["rocker"], parts["ground"]
    assert rocker.dimensions["CD"] == pytest.approx(v["c"], abs=1e-9)
    assert rocker.dimensions["DE"] == pytest.approx(v["e"], abs=1e-9)
    ce = math.sqrt(v["c"] ** 2 + v["e"] ** 2 - 2 * v["c"] * v["e"] * math.cos(v["alpha"]))
    assert rocker.dimensions["CE"] == pytest.approx(ce, abs=1e-9)
    assert len(rocker.outline()) == 3  # a rounded triangle
    assert ground.dimensions == pytest.approx({"AD": v["d"], "AG": math.hypot(v["gx"], v["gy"]),
                                               "DG": math.hypot(v["gx"] - v["d"], v["gy"])}, abs=1e-9)


def test_slots_span_the_travel_of_the_slider():
    """Slider-crank: the block's pin runs along y = offset from sqrt((b - a)^2 - e^2) to sqrt((a + b)^2 - e^2);
    the inverted slider-crank's slotted rocker carries the crank pin from |a - d| to a + d from its pivot."""
    v = EXAMPLE_VALUES["slider-crank"]
    a, b, e = v["a"], v["b"], v["offset"]
    parts = {p.name: p for p in link_parts(slider_crank(), v, pin_diameter=0.2)}
    (start, end), = parts["ground"].slots
    travel = math.sqrt((a + b) ** 2 - e ** 2) - math.sqrt((b - a) ** 2 - e ** 2)
    assert math.dist(start, end) == pytest.approx(travel, rel=1e-6)  # turning points sampled: 2nd order
    assert parts["ground"].holes["A"] == (0.0, 0.0)
    assert abs(start[1] - end[1]) < 1e-9 and math.hypot(*start) == pytest.approx(
        math.hypot(math.sqrt((b - a) ** 2 - e ** 2), e), rel=1e-6)
    assert set(parts["slider"].holes) == {"C"}
    v = EXAMPLE_VALUES["inverted-slider-crank"]
    rocker = {p.name: p for p in link_parts(inverted_slider_crank(), v, pin_diameter=0.2)}["rocker"]
    (start, end), = rocker.slots
    assert start[0] == pytest.approx(abs(v["a"] - v["d"]), rel=1e-6)
    assert end[0] == pytest.approx(v["a"] + v["d"], rel=1e-6)
    assert abs(start[1]) < 1e-12 and abs(end[1]) < 1e-12


def _arc_centre_and_middle(x1, y1, r, large, sweep, x2, y2):
    """SVG 1.1 F.6.5 for rx = ry = r, no rotation: the arc's centre and its middle point."""
    hx, hy = (x1 - x2) / 2, (y1 - y2) / 2
    radicand = max(0.0, (r * r - hx * hx - hy * hy) / (hx * hx + hy * hy))
    c = (-1 if large == sweep else 1) * math.sqrt(radicand)
    cx, cy = c * hy + (x1 + x2) / 2, -c * hx + (y1 + y2) / 2
    t1 = math.atan2(y1 - cy, x1 - cx)
    t2 = math.atan2(y2 - cy, x2 - cx)
    delta = (t2 - t1) % (2 * math.pi)
    if not sweep:
        delta -= 2 * math.pi  # sweep 0: the negative-angle direction
    middle = t1 + delta / 2
    return (cx, cy), (cx + r * math.cos(middle), cy + r * math.sin(middle))


def _to_segment(point, p, q):
    """The distance from ``point`` to the segment p-q (a point where p is q)."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    t = 0.0 if dx == dy == 0 else max(0.0, min(1.0, ((point[0] - p[0]) * dx + (point[1] - p[1]) * dy)
                                                  / (dx * dx + dy * dy)))
    return math.dist(point, (p[0] + t * dx, p[1] + t * dy))


def _arcs(d: str):
    words = d.replace(",", " ").split()
    arcs, position, k = [], None, 0
    while k < len(words):
        word = words[k]
        if word in ("M", "L"):
            position = (float(words[k + 1]), float(words[k + 2]))
            k += 3
        elif word == "A":
            r, _, _, large, sweep, x, y = (float(w) for w in words[k + 1:k + 8])
            arcs.append(_arc_centre_and_middle(*position, r, int(large), int(sweep), x, y) + (r,))
            position = (x, y)
            k += 8
        elif word == "Z":
            k += 1
        else:
            raise AssertionError(f"unexpected path word {word!r}")
    return arcs


@pytest.mark.parametrize("build, values, pin", [(fourbar, FOURBAR, PIN), (watt2, EXAMPLE_VALUES["watt2"], 0.3)])
def test_the_svg_parses_with_holes_at_the_design_and_outlines_around_them(build, values, pin):
    parts = link_parts(build(), values, pin_diameter=pin)
    root = ET.fromstring(svg_text(parts, "mm"))
    groups = root.findall(f"{SVG}g")
    assert [g.get("id") for g in groups] == [p.name for p in parts]
    for group, part in zip(groups, parts):
        circles = {c.get("data-joint"): (float(c.get("cx")), float(c.get("cy"))) for c in group.iter(f"{SVG}circle")}
        assert set(circles) == set(part.holes)
        assert all(float(c.get("r")) == pin / 2 for c in group.iter(f"{SVG}circle"))
        for pair, length in part.dimensions.items():
            assert math.dist(circles[pair[0]], circles[pair[1]]) == pytest.approx(length, abs=1e-9)
        outline, = [p for p in group.iter(f"{SVG}path") if p.get("class") == "outline"]
        centres = list(circles.values())
        for centre, middle, r in _arcs(outline.get("d")):
            assert r == pytest.approx(pin)  # width 2 x pin: the outline keeps one pin diameter from each centre
            assert min(math.dist(centre, hole) for hole in centres) < 1e-9  # every arc turns about a hole
            assert all(_to_segment(middle, p, q) >= r - 1e-9  # and bulges outward, away from every bar
                       for k, p in enumerate(centres) for q in centres[k:])
        assert part.name in group.find(f"{SVG}text").text
    assert root.get("data-unit") == "mm" and root.get("width").endswith("mm")


def test_the_svg_is_written_atomically_and_bad_sizes_are_refused(tmp_path):
    parts = _fourbar_parts()
    path = tmp_path / "links.svg"
    write_svg(path, parts, "mm")
    assert ET.parse(path).getroot().tag == f"{SVG}svg" and os.listdir(tmp_path) == ["links.svg"]
    with pytest.raises(ValueError, match="unit must be one of"):
        write_svg(tmp_path / "other.svg", parts, "furlong")
    assert os.listdir(tmp_path) == ["links.svg"]
    with pytest.raises(ValueError, match="pin_diameter must be a positive finite length"):
        link_parts(fourbar(), FOURBAR, pin_diameter=-1)
    with pytest.raises(ValueError, match="must exceed pin_diameter"):
        link_parts(fourbar(), FOURBAR, pin_diameter=4, width=3)
    with pytest.raises(ValueError, match="cannot be assembled"):
        link_parts(fourbar(), {"a": 1, "b": 1, "c": 1, "d": 10}, pin_diameter=0.1)
    # holes that run into each other: the crank's two pins are a = 20 apart, so pins of 21 cannot both be drilled
    with pytest.raises(ValueError, match=r"holes A and B of crank are 20 apart, less than the pin diameter 21"):
        link_parts(fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80}, pin_diameter=21)
    assert len(link_parts(fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80}, pin_diameter=19.9)) == 4


def test_dxf_without_ezdxf_names_the_extra(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "ezdxf", None)
    with pytest.raises(ModuleNotFoundError, match=r"symlink-kinematics\[fabrication\]"):
        write_dxf(tmp_path / "links.dxf", _fourbar_parts())
    assert os.listdir(tmp_path) == []


def test_the_dxf_reopens_with_one_closed_outline_a_link_and_holes_at_the_joints(tmp_path):
    ezdxf = pytest.importorskip("ezdxf", reason="pip install symlink-kinematics[fabrication]")
    v = EXAMPLE_VALUES["watt2"]
    parts = link_parts(watt2(), v, pin_diameter=0.3)
    path = tmp_path / "links.dxf"
    write_dxf(path, parts, "mm")
    document = ezdxf.readfile(path)
    assert document.header["$INSUNITS"] == 4
    space = document.modelspace()
    for part in parts:
        outlines = space.query(f'LWPOLYLINE[layer=="{part.name}"]')
        assert len(outlines) == 1 and outlines[0].closed
        holes = [(c.dxf.center.x, c.dxf.center.y) for c in space.query(f'CIRCLE[layer=="{part.name}"]')]
        assert len(holes) == len(part.holes)
        assert all(c.dxf.radius == 0.15 for c in space.query(f'CIRCLE[layer=="{part.name}"]'))
        distances = sorted(math.dist(p, q) for k, p in enumerate(holes) for q in holes[k + 1:])
        assert distances == pytest.approx(sorted(part.dimensions.values()), abs=1e-9)
        bulges = [vertex[4] for vertex in outlines[0].get_points("xyseb")]
        assert all(b >= 0 for b in bulges) and sum(b > 0 for b in bulges) == len(part.outline())
    rocker = {p.name: p for p in parts}["rocker"]
    ce = math.sqrt(v["c"] ** 2 + v["e"] ** 2 - 2 * v["c"] * v["e"] * math.cos(v["alpha"]))
    assert rocker.dimensions["CE"] == pytest.approx(ce, abs=1e-9)


# --- the JSON interchange of a design ----------------------------------------------------

def test_a_design_round_trips_through_json_to_the_same_linkage(tmp_path):
    import json

    import numpy

    from symlink.workshop.fabrication import read_design, write_design
    from symlink.io.linkage_file import linkage_text
    from symlink.numeric.solver import Solver
    v = EXAMPLE_VALUES["watt2"]
    path = tmp_path / "watt2.json"
    write_design(path, watt2(), v, "cm")
    record = json.loads(path.read_text())
    assert record["unit"] == "cm" and [link["name"] for link in record["links"]][:2] == ["ground", "crank"]
    assert {"name": "E", "kind": "revolute", "links": ["rocker", "coupler2"]} in record["joints"]
    design = read_design(path.read_text(), str(path))
    assert design.unit == "cm" and design.values == v
    assert linkage_text(design.linkage, design.values) == linkage_text(watt2(), v)
    theta = numpy.radians([0.0, 100.0, 250.0])
    ours = Solver(design.linkage, ["psi", "E_x"])(theta=theta, **design.values, branch_ABCD=1, branch_DEFG=1)
    theirs = Solver(watt2(), ["psi", "E_x"])(theta=theta, **v, branch_ABCD=1, branch_DEFG=1)
    assert numpy.array_equal(ours["psi"], theirs["psi"]) and numpy.array_equal(ours["E_x"], theirs["E_x"])


@pytest.mark.parametrize("change, message", [
    (lambda r: "not json {", "not JSON"),
    (lambda r: {**r, "format": "pyslvs"}, "not a symlink design"),
    (lambda r: {**r, "version": 2}, "design version 2"),
    (lambda r: {**r, "unit": "furlong"}, "unit must be one of"),
    (lambda r: {**r, "links": r["links"][:-1]}, "links and joints are not those"),
    (lambda r: {**r, "linkage": {**r["linkage"], "loops": {"ABCD": "AD + XY - BC - AB"}}}, "<design>: linkage"),
    (lambda r: {**r, "linkage": {**r["linkage"], "loops": {"ABCD": "AD + DC - BC"}}}, "<design>: linkage"),
])
def test_a_bad_design_is_a_value_error_naming_it(change, message):
    import json

    from symlink.workshop.fabrication import design_json, read_design
    record = json.loads(design_json(fourbar(), FOURBAR))
    changed = change(record)
    with pytest.raises(ValueError, match=message):
        read_design(changed if isinstance(changed, str) else json.dumps(changed))


def test_the_assembly_drawing_puts_every_hole_where_its_joint_is_at_the_chosen_angle():
    """Crank at 40 degrees: A at the origin, B = a e^{i theta}, D = (d, 0), C = D + c e^{i phi} with phi from
    the 50-digit four-bar of tests/references.py; both links at a joint have their hole there."""
    from symlink.workshop.fabrication import assembly_svg_text
    from tests.references import mp_fourbar
    theta = math.radians(40.0)
    phi = float(mp_fourbar(20, 66, 56, 80, theta, 1)["phi"])
    expected = {"A": (0.0, 0.0), "B": (20 * math.cos(theta), 20 * math.sin(theta)), "D": (80.0, 0.0),
                "C": (80 + 56 * math.cos(phi), 56 * math.sin(phi))}
    parts = link_parts(fourbar(), {**FOURBAR, "theta": theta, "branch": 1}, pin_diameter=PIN)
    root = ET.fromstring(assembly_svg_text(parts))
    seen = {}
    for circle in root.iter(f"{SVG}circle"):
        seen.setdefault(circle.get("data-joint"), []).append((float(circle.get("cx")), -float(circle.get("cy"))))
    assert {name: len(places) for name, places in seen.items()} == {"A": 2, "B": 2, "C": 2, "D": 2}
    for name, places in seen.items():
        for place in places:
            assert math.dist(place, expected[name]) < 1e-9, name


# --- every linkage: one part a link, a hole at every joint ----------------------------------

#: Each linkage's links and the pin joints each holds, by hand from its sketch (the catalog's docstrings);
#: the slots are the guides' (a slider's pin runs in its guide's slot).
LINKS = {
    "fourbar": {"ground": "AD", "crank": "AB", "coupler": "BC", "rocker": "CD"},
    "slider-crank": {"ground": "A", "crank": "AB", "slider": "C", "conrod": "BC"},
    "inverted-slider-crank": {"ground": "AD", "crank": "AB", "rocker": "D", "slider": "B"},
    "fivebar": {"ground": "AE", "crank": "AB", "coupler": "BC", "crank2": "DE", "coupler2": "CD"},
    "watt2": {"ground": "ADG", "crank": "AB", "coupler": "BC", "rocker": "CDE", "coupler2": "EF", "output": "FG"},
    "stephenson2": {"ground": "AD", "crank": "AB", "coupler": "BCE", "rocker": "DFH", "mu": "CF", "eta": "EH"},
    "jansen": {"ground": "AD", "crank": "AB", "upper_rocker": "CDE", "lower_rocker": "DF", "leg": "FG",
               "upper_link": "BC", "lower_link": "BF", "tie": "EG"},
}
SLOTS = {"slider-crank": "ground", "inverted-slider-crank": "rocker"}


def _law_of_cosines(p, q, angle):
    return math.sqrt(p * p + q * q - 2 * p * q * math.cos(angle))


#: Hole-to-hole lengths by hand: the example values, Jansen's published numbers (a = 38, l = 7.8, m = 15,
#: b = 41.5, c = 39.3, d = 40.1, e = 55.8, f = 39.4, g = 36.7, j = 50, k = 61.9), a ternary link's third side
#: by the law of cosines (Stephenson II: coupler BCE with angle alpha at B, rocker DFH with angle delta at D).
HAND_LENGTHS = {
    "fivebar": {("ground", "AE"): 3.0, ("crank", "AB"): 2.0, ("coupler", "BC"): 4.0, ("crank2", "DE"): 2.0,
                ("coupler2", "CD"): 4.0},
    "stephenson2": {("ground", "AD"): 4.5, ("crank", "AB"): 1.0, ("coupler", "BC"): 3.1, ("coupler", "BE"): 3.9,
                    ("coupler", "CE"): _law_of_cosines(3.1, 3.9, 0.9), ("rocker", "DF"): 3.1,
                    ("rocker", "DH"): 3.1, ("rocker", "FH"): _law_of_cosines(3.1, 3.1, 0.3), ("mu", "CF"): 2.2,
                    ("eta", "EH"): 4.1},
    "jansen": {("ground", "AD"): math.hypot(38, 7.8), ("crank", "AB"): 15, ("upper_rocker", "CD"): 41.5,
               ("upper_rocker", "DE"): 40.1, ("upper_rocker", "CE"): 55.8, ("lower_rocker", "DF"): 39.3,
               ("leg", "FG"): 36.7, ("upper_link", "BC"): 50, ("lower_link", "BF"): 61.9, ("tie", "EG"): 39.4},
}


def _distance(part, pair):
    first, second = pair
    return math.dist(part.holes[first], part.holes[second])


@pytest.mark.parametrize("name", list(LINKS))
def test_every_catalog_linkage_gives_one_part_a_link_with_a_hole_at_each_of_its_joints(name):
    from symlink.mechanism.catalog import CATALOG
    parts = {p.name: p for p in link_parts(CATALOG[name](), EXAMPLE_VALUES[name], pin_diameter=0.1)}
    assert len(parts) == len(LINKS[name]) and set(parts) == set(LINKS[name])
    for link, joints in LINKS[name].items():
        part = parts[link]
        assert sorted(part.holes) == sorted(joints), link
        assert len(part.slots) == (1 if SLOTS.get(name) == link else 0), link
        if len(joints) == 3:  # a ternary link: a rounded triangle through its three holes
            assert len(part.outline()) == 3, link
        elif len(joints) == 2 and not part.corners:  # a bar with rounded ends
            assert len(part.outline()) == 2, link
    for (link, pair), length in HAND_LENGTHS.get(name, {}).items():
        assert _distance(parts[link], pair) == pytest.approx(length, rel=1e-12), (link, pair)
    if name == "jansen":  # the foot H: a corner of the leg, h = 65.7 from G and i = 49 from F
        leg = parts["leg"]
        assert math.dist(leg.corners["H"], leg.holes["G"]) == pytest.approx(65.7, rel=1e-12)
        assert math.dist(leg.corners["H"], leg.holes["F"]) == pytest.approx(49.0, rel=1e-12)
        assert len(leg.outline()) == 3


def test_a_from_joints_linkage_gives_its_drawn_lengths_a_slot_and_a_rounded_triangle():
    """The hole distances are the distances between the drawn joints; the slider's slot spans the travel of a
    crank-slider of crank |AB|, rod |BC| and offset 0.5 (the guide's line y = 0.5): from
    sqrt((BC - AB)^2 - 0.25) to sqrt((AB + BC)^2 - 0.25) along x."""
    from symlink.mechanism.joints import Slider, from_joints
    drawn = {"A": (0, 0), "B": (1, 1), "C": (4, 2), "D": (5, 0), "E": (3, 4), "F": (6, 4), "G": (8, 0)}
    links = {"ground": "ADG", "crank": "AB", "coupler": "BCE", "rocker": "CD", "link": "EF", "output": "FG"}
    sixbar = from_joints({link: list(joints) for link, joints in links.items()}, drawn, driver="A")
    parts = {p.name: p for p in link_parts(sixbar.linkage, sixbar.defaults, pin_diameter=0.1)}
    assert set(parts) == set(links)
    for link, joints in links.items():
        part = parts[link]
        assert sorted(part.holes) == sorted(joints)
        for k, first in enumerate(joints):
            for second in joints[k + 1:]:
                assert _distance(part, (first, second)) == pytest.approx(math.dist(drawn[first], drawn[second]),
                                                                         rel=1e-12)
    assert len(parts["coupler"].outline()) == 3
    slider = from_joints({"ground": ["A", "C"], "crank": ["A", "B"], "rod": ["B", "C"]},
                         {"A": (0, 0), "B": (1, 1), "C": (4, 0.5)}, driver="A", joints={"C": Slider("ground", 0.0)})
    parts = {p.name: p for p in link_parts(slider.linkage, slider.defaults, pin_diameter=0.1)}
    assert len(parts) == 4  # ground (pivot A and the slot), crank, rod and the slider's block
    ab, bc = math.sqrt(2), math.hypot(3, 0.5)
    (start, end), = parts["ground"].slots
    assert sorted([start[0], end[0]]) == pytest.approx([math.sqrt((bc - ab) ** 2 - 0.25),
                                                        math.sqrt((ab + bc) ** 2 - 0.25)], rel=1e-6)
    assert start[1] == pytest.approx(0.5, abs=1e-12) and end[1] == pytest.approx(0.5, abs=1e-12)
    assert set(parts["ground"].holes) == {"A"} and _distance(parts["rod"], ("B", "C")) == pytest.approx(bc)
    block, = [p for p in parts.values() if p.name not in ("ground", "crank", "rod")]
    assert set(block.holes) == {"C"}


# --- the DXF and the SVG put every hole where the design has it --------------------------------

def _expected_holes():
    """Each part's holes in its own frame, by hand: the first hole at the origin, the second on +x.  Watt II's
    ternary rocker: C at 0, D at c, and E = D + e e^{i(phi + alpha)} seen from C along D - C (angle phi + pi),
    that is (c - e cos alpha, -e sin alpha); its ternary ground: A, D = (d, 0) and G = (gx, gy)."""
    w = EXAMPLE_VALUES["watt2"]
    c, e, alpha = w["c"], w["e"], w["alpha"]
    s = EXAMPLE_VALUES["slider-crank"]
    return {
        "fourbar": (fourbar, FOURBAR, {"ground": {"A": (0, 0), "D": (80, 0)}, "crank": {"A": (0, 0), "B": (20, 0)},
                                       "coupler": {"B": (0, 0), "C": (66, 0)}, "rocker": {"C": (0, 0), "D": (56, 0)}},
                    {}),
        "watt2": (watt2, w, {"ground": {"A": (0, 0), "D": (w["d"], 0), "G": (w["gx"], w["gy"])},
                             "crank": {"A": (0, 0), "B": (w["a"], 0)}, "coupler": {"B": (0, 0), "C": (w["b"], 0)},
                             "rocker": {"C": (0, 0), "D": (c, 0), "E": (c - e * math.cos(alpha), -e * math.sin(alpha))},
                             "coupler2": {"E": (0, 0), "F": (w["f"], 0)}, "output": {"F": (0, 0), "G": (w["g"], 0)}},
                  {}),
        "slider-crank": (slider_crank, s, {"ground": {"A": (0, 0)}, "crank": {"A": (0, 0), "B": (s["a"], 0)},
                                           "slider": {"C": (0, 0)}, "conrod": {"B": (0, 0), "C": (s["b"], 0)}},
                         {"ground": 1}),
    }


def _one_shift(found, expected):
    """The translation that takes the ``expected`` holes onto ``found`` centres (lists of points), or None."""
    names = list(expected)
    for candidate in found:
        shift = (candidate[0] - expected[names[0]][0], candidate[1] - expected[names[0]][1])
        moved = [(x + shift[0], y + shift[1]) for x, y in expected.values()]
        if all(min(math.dist(point, centre) for centre in found) < 1e-9 for point in moved):
            return shift
    return None


@pytest.mark.parametrize("name", ["fourbar", "watt2", "slider-crank"])
def test_dxf_and_svg_holes_are_within_1e_9_of_the_design_and_each_link_has_one_closed_outline(name, tmp_path):
    ezdxf = pytest.importorskip("ezdxf", reason="pip install symlink-kinematics[fabrication]")
    build, values, holes, slots = _expected_holes()[name]
    parts = link_parts(build(), values, pin_diameter=0.1)
    path = tmp_path / "parts.dxf"
    write_dxf(path, parts, "mm")
    space = ezdxf.readfile(path).modelspace()
    root = ET.fromstring(svg_text(parts, "mm"))
    groups = {group.get("id"): group for group in root.findall(f"{SVG}g")}
    assert set(groups) == set(holes) == {layer.dxf.name for layer in ezdxf.readfile(path).layers} - {"0", "Defpoints"}
    for link, expected in holes.items():
        centres = [(c.dxf.center.x, c.dxf.center.y) for c in space.query(f'CIRCLE[layer=="{link}"]')]
        assert len(centres) == len(expected) and _one_shift(centres, expected) is not None, link
        polylines = space.query(f'LWPOLYLINE[layer=="{link}"]')
        assert all(p.closed for p in polylines) and len(polylines) == 1 + slots.get(link, 0), link
        boxes = [numpy.array([(x, y) for x, y, *_ in p.get_points("xy")]) for p in polylines]
        outer = [k for k, box in enumerate(boxes)  # the outline holds every hole and every slot
                 if all((box.min(axis=0) <= point).all() and (point <= box.max(axis=0)).all()
                        for point in [numpy.array(c) for c in centres] + [v for other in boxes for v in other])]
        assert len(outer) == 1, link
        svg_centres = {c.get("data-joint"): (float(c.get("cx")), -float(c.get("cy")))
                       for c in groups[link].iter(f"{SVG}circle")}
        assert set(svg_centres) == set(expected)
        shift = _one_shift(list(svg_centres.values()), expected)
        assert shift is not None, link
        for joint, (x, y) in expected.items():  # by name: each hole is the joint's
            assert math.dist(svg_centres[joint], (x + shift[0], y + shift[1])) < 1e-9, (link, joint)


# --- the JSON interchange gives the same linkage ----------------------------------------------

def _round_trip_cases():
    from symlink.mechanism.catalog import CATALOG
    from symlink.mechanism.joints import Slider, from_joints
    cases = {name: (CATALOG[name](), EXAMPLE_VALUES[name]) for name in LINKS}
    drawn = {"A": (0, 0), "B": (1, 1), "C": (4, 2), "D": (5, 0), "E": (3, 4), "F": (6, 4), "G": (8, 0)}
    sixbar = from_joints({"ground": list("ADG"), "crank": list("AB"), "coupler": list("BCE"), "rocker": list("CD"),
                          "link": list("EF"), "output": list("FG")}, drawn, driver="A")
    slider = from_joints({"ground": ["A", "C"], "crank": ["A", "B"], "rod": ["B", "C"]},
                         {"A": (0, 0), "B": (1, 1), "C": (4, 0.5)}, driver="A", joints={"C": Slider("ground", 0.0)})
    cases["from_joints six-bar"] = (sixbar.linkage, sixbar.defaults)
    cases["from_joints slider"] = (slider.linkage, slider.defaults)
    return cases


@pytest.mark.parametrize("name", [*LINKS, "from_joints six-bar", "from_joints slider"])
def test_a_design_read_back_from_json_puts_every_point_where_the_original_does_at_20_inputs(name):
    """Both linkages posed at 20 values of the first input (each branch +1; the five-bar's second crank at the
    angle the design keeps): every joint and named point at the same place to 1e-13 of the linkage's size, and
    assembled at the same inputs."""
    from symlink.workshop.fabrication import design_json, read_design
    from symlink.numeric.poses import Geometry
    linkage, values = _round_trip_cases()[name]
    design = read_design(design_json(linkage, values, "cm"))
    assert design.unit == "cm" and design.linkage.name == linkage.name
    first = linkage.inputs[0].name
    # Stephenson II's example crank meets a dead centre at +-54.6 degrees: 20 angles inside; else a full turn.
    span = (-0.9, 0.9) if name == "stephenson2" else (0.0, 2 * math.pi * 19 / 20)
    turn = {first: numpy.linspace(*span, 20)}
    ours = Geometry(design.linkage).poses(design.values, turn)
    theirs = Geometry(linkage).poses(values, turn)
    assert ours.assembled.sum() >= 10 and numpy.array_equal(ours.assembled, theirs.assembled)
    size = max(abs(v) for v in values.values())
    assert set(ours.positions) == set(theirs.positions) and len(ours.positions) >= 3
    for point, places in theirs.positions.items():
        ok = theirs.assembled
        assert numpy.max(numpy.abs(ours.positions[point][ok] - places[ok])) <= 1e-13 * size, point


# --- parts carry what the design is for: the traced point ---------------------------------------------------------

def test_a_traced_point_is_marked_on_its_link_with_its_dimensions_and_its_path_on_the_assembly():
    """Seed 003's four-bar with a coupler point P = B + (u + i v) e^{i beta}, u = 30, v = 20: by hand |BP| =
    sqrt(30^2 + 20^2) and |CP| = sqrt((66 - 30)^2 + 20^2); P's path passes through the pose's P."""
    import symlink
    linkage = symlink.with_point(symlink.fourbar(), "B", symlink.fourbar().roles["coupler"])
    values = {"a": 20, "b": 66, "c": 56, "d": 80, "u": 30, "v": 20}
    parts = {part.name: part for part in symlink.link_parts(linkage, values, pin_diameter=4)}
    coupler = next(part for part in parts.values() if "P" in part.marks)
    assert set(coupler.holes) == {"B", "C"} and coupler.marks["P"] == pytest.approx((30.0, 20.0), abs=1e-12)
    assert coupler.dimensions["BP"] == pytest.approx(math.hypot(30, 20), rel=1e-14)
    assert coupler.dimensions["CP"] == pytest.approx(math.hypot(66 - 30, 20), rel=1e-14)
    assert all(not part.marks for part in parts.values() if part is not coupler)
    svg = symlink.svg_text(list(parts.values()))
    assert 'class="mark" data-point="P"' in svg and "BP = 36.0555 mm" in svg
    assembly = symlink.assembly_svg_text(list(parts.values()))
    assert 'class="traced-path" data-point="P"' in assembly
    # the pose's P (theta = 0: B = (20, 0), beta from the triangle B C D) lies on the drawn path
    here = complex(*coupler.placed(coupler.marks["P"]))
    path = numpy.array([complex(x, y) for x, y in coupler.paths["P"]])
    assert len(path) > 100 and numpy.min(numpy.abs(path - here)) < 1e-9 * 80
    if importlib.util.find_spec("ezdxf"):
        assert "POINT" in symlink.dxf_text(list(parts.values()))


def test_a_linkage_without_a_traced_point_has_no_marks():
    import symlink
    parts = symlink.link_parts(symlink.fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80}, pin_diameter=4)
    assert all(not part.marks and not part.paths for part in parts)
    assert 'class="mark"' not in symlink.svg_text(parts)
