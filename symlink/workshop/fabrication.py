"""Drawings to cut the links from: every link of a linkage as a flat part, written as SVG or DXF.

A designed linkage has to be made.  :func:`link_parts` reads the linkage's
rigid bodies and joints (:func:`symlink.mechanism.bodies.mechanism`), places them at a
pose (:class:`symlink.numeric.poses.Geometry`, the drawing's own solver) and
takes each body into its own frame: the first pin hole at the origin, the
second on the +x axis.  So a binary link is a **bar** with rounded ends and
holes at 0 and at its length; a ternary or larger link is a **rounded
polygon** through its holes (and its named points that are no joints, such as
a coupler point); a slider's block is a short bar along its guide around its
pin; a guide that is a part (a slotted link, or the ground plate) gets the
**slot** that the block's pin travels in over the input's reachable range.
The ground is a part (a base plate) where it has two pivots or a slot.

Outlines are the convex hull of a part's holes, corners and slot ends, grown
by half the link ``width`` (default twice the pin diameter): straight edges
and arcs, closed.  Coordinates are in the linkage's own length unit; ``unit``
(mm, cm, m or in) says which, so that the SVG's width and the DXF's
``$INSUNITS`` give the parts their real size.  The slot is sampled at
:data:`TRAVEL_SAMPLES` input values (its ends are turning points, where the
sampling error is second order).

SVG is plain XML, one ``<g>`` a part, labelled with its name and hole-to-hole
dimensions (:func:`svg_text`); DXF (:func:`dxf_text`) needs ``ezdxf`` (``pip install
symlink-kinematics[fabrication]``).  Both are written atomically (:func:`symlink.common.files.write_atomic`);
:func:`assembly_svg_text` draws the parts assembled at the pose they were read at.  On the command
line, ``symlink parts`` writes any set of these files together.

A design travels between programs as JSON (:func:`design_json`, :func:`read_design`): its unit, its
links and joints (names, kinds, which links each joint joins) and the linkage itself with its
dimensions, as the mapping of a linkage file (:func:`symlink.io.linkage_file.linkage_text`), which
symlink reads back to the same linkage.

>>> from symlink.mechanism.catalog import fourbar
>>> parts = link_parts(fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80}, pin_diameter=4)
>>> [(part.name, part.dimensions) for part in parts][:2]
[('ground', {'AD': 80.0}), ('crank', {'AB': 20.0})]
>>> parts[2].holes["C"]  # the coupler: B at the origin, C at its length on +x
(66.0, 0.0)
"""
from __future__ import annotations

import io
import itertools
import json
import math
import os
import tomllib
from dataclasses import dataclass, field
from typing import Mapping
from xml.sax.saxutils import escape, quoteattr

import numpy

from ..common.display import record_html
from ..mechanism.bodies import PRISMATIC, REVOLUTE, mechanism
from ..common.files import excerpt, write_atomic
from ..common.numbers import finite_float, json_data
from ..symbolic.linkage import Linkage

__all__ = ["Part", "link_parts", "svg_text", "write_svg", "dxf_text", "write_dxf", "UNITS_IN_MM", "TRAVEL_SAMPLES",
           "LinkageDesign", "design_json", "read_design", "write_design", "DESIGN_FORMAT", "assembly_svg_text"]

#: The length units a drawing can be in, and their size in millimetres.
UNITS_IN_MM = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4}
#: DXF ``$INSUNITS`` codes of those units.
_DXF_UNITS = {"mm": 4, "cm": 5, "m": 6, "in": 1}
#: Input values a slot's travel is sampled at (a full turn of the first input).
TRAVEL_SAMPLES = 1441
#: Two holes closer than this (relative to the part's size) are one hole.
_SAME = 1e-9

Point = tuple[float, float]


@dataclass(frozen=True)
class Part:
    """One link as a flat part, in its own frame and the linkage's length unit.

    ``holes`` maps each pin joint to its centre, ``corners`` the named points on
    the link that are no joints (outline corners without a hole), ``slots`` the
    centre lines (start, end) of slots a pin slides in.  ``radius`` is half the
    link's width (the outline's distance from every hole centre, corner and slot end);
    ``dimensions`` the distance between each pair of holes (``"AB": 20.0``) and from each hole to each
    mark (``"BP"``), ``marks`` the points the design traces, ``paths`` their paths in the assembly.
    """

    _repr_html_ = record_html  # a notebook shows its fields as a table

    name: str
    holes: dict[str, Point]
    corners: dict[str, Point]
    slots: tuple[tuple[Point, Point], ...]
    pin_diameter: float
    radius: float
    dimensions: dict[str, float] = field(default_factory=dict)
    #: Where the part sits in the assembly at the pose it was read at: its frame's origin (x, y) and angle.
    placement: tuple[float, float, float] = (0.0, 0.0, 0.0)
    #: The named points on the link that are no joints (a coupler point the design traces), in the part's frame:
    #: each is marked on the part (a centre-punch mark), dimensioned from every hole.
    marks: dict[str, Point] = field(default_factory=dict)
    #: Each mark's path over the input's reachable range, in the assembly's (world) coordinates.
    paths: dict[str, tuple[Point, ...]] = field(default_factory=dict)

    def placed(self, point: Point) -> Point:
        """A point of the part's frame in the assembly's (world) coordinates."""
        x0, y0, angle = self.placement
        c, s = math.cos(angle), math.sin(angle)
        return (x0 + c * point[0] - s * point[1], y0 + s * point[0] + c * point[1])

    def outline(self) -> list[tuple[Point, Point, Point]]:
        """The closed outline as ``(line start, line end, centre of the arc that follows)`` in order.

        Counter-clockwise: each straight edge is followed by an arc of ``radius``, counter-clockwise about
        its centre (a hull vertex), to the next edge's start.
        """
        hull = _hull(list(self.holes.values()) + list(self.corners.values())
                     + [end for slot in self.slots for end in slot], self.radius)
        pieces = []
        for k, start in enumerate(hull):
            end = hull[(k + 1) % len(hull)]
            dx, dy = end[0] - start[0], end[1] - start[1]
            size = math.hypot(dx, dy)
            nx, ny = dy / size * self.radius, -dx / size * self.radius  # outward: to the right of a CCW edge
            pieces.append(((start[0] + nx, start[1] + ny), (end[0] + nx, end[1] + ny), end))
        return pieces

    def extent(self) -> tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)`` of the part (hull points grown by ``radius``)."""
        points = numpy.array(list(self.holes.values()) + list(self.corners.values())
                             + [end for slot in self.slots for end in slot])
        low, high = points.min(axis=0) - self.radius, points.max(axis=0) + self.radius
        return float(low[0]), float(low[1]), float(high[0]), float(high[1])

    def label(self, unit: str) -> str:
        """``crank: AB = 20 mm; holes 4 mm``: the part's name and dimensions."""
        sizes = ", ".join(f"{name} = {value:.6g} {unit}" for name, value in self.dimensions.items())
        slots = "; ".join(f"slot {math.dist(*slot):.6g} {unit}" for slot in self.slots)
        return "; ".join(item for item in (f"{self.name}: {sizes}" if sizes else self.name, slots,
                                           f"holes {self.pin_diameter:.6g} {unit}") if item)


def _hull(points: list[Point], radius: float) -> list[Point]:
    """The convex hull, counter-clockwise, of distinct points (monotone chain); a single point becomes two
    (a round-ended stub of length ``radius``) so that every outline has edges."""
    unique = sorted(set((round(x, 12), round(y, 12)) for x, y in points))
    if len(unique) == 1:
        return [unique[0], (unique[0][0] + radius, unique[0][1])]

    def cross(o: Point, a: Point, b: Point) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list[Point] = []
    upper: list[Point] = []
    for p in unique:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(unique):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def _check_size(name: str, value: float) -> float:
    found = finite_float(value) if isinstance(value, (int, float)) else None
    if found is None or found <= 0:
        raise ValueError(f"{name} must be a positive finite length, got {excerpt(value)}")
    return found


def link_parts(linkage: Linkage, values: Mapping[str, float], pin_diameter: float,
               width: float | None = None) -> list[Part]:
    """Every link of ``linkage`` as a :class:`Part`, ground first (where it is a part), in the bodies' order.

    ``values``: every parameter (lengths in the drawing's unit, fixed angles in radians), optionally the
    inputs (the pose the parts are read at; 0 by default) and branch signs (+1 by default).  ``width``:
    the width of a bar (default ``2 * pin_diameter``), more than the pin diameter.  ``ValueError`` for a
    bad size, a missing value, or a pose where the linkage cannot be assembled.

    Parameters
    ----------
    linkage : Linkage
        Any linkage.
    values : mapping of str to float
        Every parameter, optionally the inputs (the pose, 0 by default) and branch signs.
    pin_diameter : float
        The pins' diameter.
    width : float, optional
        The bars' width (default twice the pin diameter).

    Returns
    -------
    list of Part
        Every link, ground first: its holes, outline, slots and dimensions.

    Raises
    ------
    ValueError
        For a bad size, a missing value, or a pose where the linkage cannot be assembled.

    Examples
    --------
    >>> import symlink
    >>> parts = symlink.link_parts(symlink.fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80}, pin_diameter=4)
    >>> [(part.name, part.dimensions) for part in parts][:2]
    [('ground', {'AD': 80.0}), ('crank', {'AB': 20.0})]
    """
    from ..numeric.poses import Geometry  # the drawing's placement of every joint: its twin, reused
    pin = _check_size("pin_diameter", pin_diameter)
    bar = _check_size("width", 2 * pin if width is None else width)
    if bar <= pin:
        raise ValueError(f"width ({bar:g}) must exceed pin_diameter ({pin:g}): the holes would cut the link")
    geometry = Geometry(linkage)
    found = mechanism(linkage)
    pose = geometry.poses(values)
    if not bool(pose.assembled.all()):
        raise ValueError(f"{linkage.name} cannot be assembled at the pose given "
                         f"({', '.join(f'{q.name} = {float(pose.inputs[q.name][0]):g}' for q in linkage.inputs)})")
    place = {name: complex(position[0]) for name, position in pose.positions.items()}
    travel = _travels(geometry, values, found) if any(j.kind == PRISMATIC for j in found.joints) else {}
    parts = []
    for body in found.bodies:
        pins = [j for j in body.joints if found.joint(j).kind == REVOLUTE and j in place]
        guides = [found.joint(j) for j in body.joints
                  if found.joint(j).kind == PRISMATIC and found.joint(j).bodies[0] == body.name]
        blocks = [found.joint(j) for j in body.joints
                  if found.joint(j).kind == PRISMATIC and found.joint(j).bodies[0] != body.name]
        if body.is_ground and len(pins) < 2 and not guides:
            continue  # one pivot and no slot: the frame, not a part to cut
        slots_world = [travel[g.name] for g in guides if g.name in travel]
        if len(pins) >= 2:
            origin, axis = place[pins[0]], place[pins[1]] - place[pins[0]]
        elif blocks:
            origin, axis = place[pins[0]] if pins else 0j, complex(numpy.exp(1j * pose.directions[blocks[0].name][0]))
        elif slots_world:  # a slotted link: its pivot (else the slot's start) at the origin, the slot along +x
            origin = place[pins[0]] if pins else slots_world[0][0]
            axis = slots_world[0][1] - slots_world[0][0]
        else:
            origin, axis = (place[pins[0]] if pins else 0j), 1 + 0j
        turn = abs(axis) / axis if abs(axis) > 0 else 1 + 0j

        def local(z: complex) -> Point:
            w = (z - origin) * turn
            return (float(w.real) + 0.0, float(w.imag) + 0.0)  # + 0.0: no -0.0

        holes = {name: local(place[name]) for name in pins}
        if len(pins) >= 2:  # on the axis by construction: exactly, to the last bit
            holes[pins[0]], holes[pins[1]] = (0.0, 0.0), (abs(axis), 0.0)
        holes = _distinct(holes, bar)
        corners = {name: local(place[name]) for name in body.points if name not in holes and name in place}
        slots = tuple((local(start), local(end)) for start, end in slots_world)
        if blocks and len(holes) == 1 and not corners:  # a slider's block: a short bar along its guide
            (x, y), = holes.values()
            corners = {"block": (x + bar, y)}
            holes = dict(holes)
            corners["block_back"] = (x - bar, y)
        dimensions = {a + b: math.dist(holes[a], holes[b]) for a, b in itertools.combinations(holes, 2)}
        marks = {name: corner for name, corner in corners.items() if name in linkage.points}
        dimensions.update({hole + mark: math.dist(holes[hole], at) for mark, at in marks.items() for hole in holes})
        for (a, b), apart in zip(itertools.combinations(holes, 2), dimensions.values()):
            if apart < pin:
                raise ValueError(f"the holes {a} and {b} of {body.name} are {apart:g} apart, less than the pin "
                                 f"diameter {pin:g}: they would run into each other (take smaller pins)")
        placement = (float(origin.real), float(origin.imag), float(numpy.angle(1 / turn)))
        parts.append(Part(body.name, holes, corners, slots, pin, bar / 2, dimensions, placement, marks))
    traced = [name for part in parts for name in part.marks]
    if traced:  # what the design is for: the marks' paths, drawn on the assembly
        from ..numeric.poses import traced_paths
        found_paths = traced_paths(geometry, values, traced)
        for part in parts:
            part.paths.update({name: tuple((float(z.real), float(z.imag)) for z in found_paths[name]
                                           if numpy.isfinite(z)) for name in part.marks})
    return parts


def _distinct(holes: dict[str, Point], size: float) -> dict[str, Point]:
    """The holes with coincident ones (two joint names at one place) kept once."""
    kept: dict[str, Point] = {}
    for name, point in holes.items():
        if all(math.dist(point, other) > _SAME * size for other in kept.values()):
            kept[name] = point
    return kept


def _travels(geometry, values: Mapping[str, float], found) -> dict[str, tuple[complex, complex]]:
    """Each slider's slot on its guide, as world points at the pose of ``values``: the block's pin over the
    first input's sampled turn, taken into the guide's frame and back, from its least to its greatest travel."""
    name = geometry.input_names[0]
    base = float(values.get(name, 0.0))
    turn = base + numpy.linspace(0.0, 2 * math.pi, TRAVEL_SAMPLES)
    poses = geometry.poses(values, {name: turn})
    here = geometry.poses(values)
    slots = {}
    for joint in found.joints:
        if joint.kind != PRISMATIC:
            continue
        block = found.body(joint.bodies[1])
        pins = [j for j in block.joints if found.joint(j).kind == REVOLUTE]
        guide = found.body(joint.bodies[0])
        anchors = [j for j in guide.joints if found.joint(j).kind == REVOLUTE and j in poses.positions]
        if not pins or pins[0] not in poses.positions:
            continue
        ok = poses.assembled
        path = poses.positions[pins[0]][ok]
        direction = numpy.exp(1j * poses.directions[joint.name][ok])
        anchor = poses.positions[anchors[0]][ok] if anchors else numpy.zeros(len(path), complex)
        along = ((path - anchor) * numpy.conj(direction)).real  # travel along the guide, in the guide's frame
        across = ((path - anchor) * numpy.conj(direction)).imag
        if len(along) == 0:
            continue
        low, high = int(numpy.argmin(along)), int(numpy.argmax(along))
        now_anchor = here.positions[anchors[0]][0] if anchors else 0j
        now_direction = complex(numpy.exp(1j * here.directions[joint.name][0]))
        ends = [complex(now_anchor + (along[k] + 1j * across[k]) * now_direction) for k in (low, high)]
        slots[joint.name] = (ends[0], ends[1])
    return slots


def _layout(parts: list[Part], unit: str) -> list[tuple[Part, float, float]]:
    """Each part with the shift that puts it in a row, left to right, bottoms at y = 0, a width apart and far
    enough apart that the labels above them (text of the largest ``radius`` in size) do not overlap."""
    placed, x = [], 0.0
    text_size = max(p.radius for p in parts)
    for part in parts:
        xmin, ymin, xmax, _ = part.extent()
        placed.append((part, x - xmin, -ymin))
        x += max(xmax - xmin, _label_width(part, unit, text_size)) + 2 * part.radius
    return placed


def _label_width(part: Part, unit: str, size: float) -> float:
    """About how wide the label of ``part`` is in text of ``size`` (a character is at most 0.6 of its size in
    common sans-serif fonts)."""
    return 0.6 * size * len(part.label(unit))


def _check_unit(unit: str) -> str:
    if unit not in UNITS_IN_MM:
        raise ValueError(f"unit must be one of {', '.join(UNITS_IN_MM)}, got {unit!r}")
    return unit


def _number(value: float) -> str:
    return repr(float(value)) if value != 0 else "0"


def svg_text(parts: list[Part], unit: str = "mm") -> str:
    """The parts as an SVG document, in a row, one ``<g>`` a part (``id`` its name) with its outline (a
    ``<path>``), its holes (``<circle>`` with ``data-joint``), its slots and its label; y points up in the
    design and down in SVG, so every y is negated.  Its width and height are the real size in ``unit``.

    Parameters
    ----------
    parts : list of Part
        The parts (:func:`link_parts`).
    unit : str, optional
        The drawing's unit (default ``"mm"``).

    Returns
    -------
    str
        The SVG document.

    Examples
    --------
    >>> import symlink
    >>> parts = symlink.link_parts(symlink.fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80}, pin_diameter=4)
    >>> text = symlink.svg_text(parts)
    >>> text.count("<g id="), 'data-unit="mm"' in text  # one group a part
    (4, True)
    """
    _check_unit(unit)
    if not parts:
        raise ValueError("no parts to draw")
    placed = _layout(parts, unit)
    text_size = max(p.radius for p in parts)
    width = max(max(dx + p.extent()[2], dx + p.extent()[0] + _label_width(p, unit, text_size))
                for p, dx, _ in placed) + parts[-1].radius
    height = max(dy + p.extent()[3] for p, _, dy in placed)
    top = -(height + 3 * text_size)
    size_mm = UNITS_IN_MM[unit]
    full_height = height + 3 * text_size
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<svg xmlns="http://www.w3.org/2000/svg" width="{width * size_mm:.6g}mm" '
             f'height="{full_height * size_mm:.6g}mm" viewBox="0 {_number(top)} {_number(width)} '
             f'{_number(full_height)}" data-unit="{unit}">']
    stroke = f'fill="none" stroke="black" stroke-width="{_number(text_size / 20)}"'
    for part, dx, dy in placed:
        def at(point: Point) -> str:
            return f"{_number(point[0] + dx)} {_number(-(point[1] + dy))}"
        lines.append(f"<g id={quoteattr(part.name)}>")
        pieces = part.outline()
        path = [f"M {at(pieces[0][0])}"]
        for k, (_, end, _centre) in enumerate(pieces):
            following = pieces[(k + 1) % len(pieces)][0]
            path.append(f"L {at(end)}")
            path.append(f"A {_number(part.radius)} {_number(part.radius)} 0 0 0 {at(following)}")
        lines.append(f'<path class="outline" d="{" ".join(path)} Z" {stroke}/>')
        for name, centre in part.holes.items():
            x, y = at(centre).split()
            lines.append(f'<circle class="hole" data-joint={quoteattr(name)} cx="{x}" cy="{y}" '
                         f'r="{_number(part.pin_diameter / 2)}" {stroke}/>')
        for start, end in part.slots:
            lines.append(f'<path class="slot" d="{_slot_path(start, end, part.pin_diameter / 2, at)}" {stroke}/>')
        lines += _mark_svg(part, at, stroke)
        xmin, ymin, _, ymax = part.extent()
        lines.append(f'<text x="{_number(xmin + dx)}" y="{_number(-(ymax + dy) - text_size)}" '
                     f'font-size="{_number(text_size)}">{escape(part.label(unit))}</text>')
        lines.append("</g>")
    lines.append("</svg>")
    return "\n".join(lines) + "\n"


def assembly_svg_text(parts: list[Part], unit: str = "mm") -> str:
    """The assembly drawing: every part's outline, holes and slots where it sits at the pose the parts were read
    at (:func:`link_parts` with the input's value in ``values``), one ``<g>`` a part, ground first, labelled
    with the part's name at the middle of its holes.

    Parameters
    ----------
    parts : list of Part
        The parts (:func:`link_parts`), read at a pose.
    unit : str, optional
        The drawing's unit (default ``"mm"``).

    Returns
    -------
    str
        The SVG document of the assembly.

    Examples
    --------
    >>> import math, symlink
    >>> parts = symlink.link_parts(symlink.fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80, "theta": math.pi / 2},
    ...                            pin_diameter=4)
    >>> [round(v, 9) for v in parts[1].placed(parts[1].holes["B"])]  # the crank pin B straight above A
    [0.0, 20.0]
    >>> symlink.assembly_svg_text(parts).count("<g ")
    4
    """
    _check_unit(unit)
    if not parts:
        raise ValueError("no parts to draw")
    corners = [part.placed((x, y)) for part in parts for x, y in _extent_corners(part)]
    xmin, ymin = min(x for x, _ in corners), min(y for _, y in corners)
    xmax, ymax = max(x for x, _ in corners), max(y for _, y in corners)
    size = UNITS_IN_MM[unit]
    text_size = max(p.radius for p in parts)
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<svg xmlns="http://www.w3.org/2000/svg" width="{(xmax - xmin) * size:.6g}mm" '
             f'height="{(ymax - ymin) * size:.6g}mm" viewBox="{_number(xmin)} {_number(-ymax)} '
             f'{_number(xmax - xmin)} {_number(ymax - ymin)}" data-unit="{unit}">']
    stroke = f'fill="none" stroke="black" stroke-width="{_number(text_size / 20)}"'
    for part in parts:
        def at(point: Point, part: Part = part) -> str:
            x, y = part.placed(point)
            return f"{_number(x)} {_number(-y)}"
        lines.append(f"<g id={quoteattr(part.name)}>")
        pieces = part.outline()
        path = [f"M {at(pieces[0][0])}"]
        for k, (_, end, _centre) in enumerate(pieces):
            path += [f"L {at(end)}", f"A {_number(part.radius)} {_number(part.radius)} 0 0 0 "
                                     f"{at(pieces[(k + 1) % len(pieces)][0])}"]
        lines.append(f'<path class="outline" d="{" ".join(path)} Z" {stroke}/>')
        for name, centre in part.holes.items():
            x, y = at(centre).split()
            lines.append(f'<circle class="hole" data-joint={quoteattr(name)} cx="{x}" cy="{y}" '
                         f'r="{_number(part.pin_diameter / 2)}" {stroke}/>')
        for start, end in part.slots:
            lines.append(f'<path class="slot" d="{_slot_path(start, end, part.pin_diameter / 2, at)}" {stroke}/>')
        lines += _mark_svg(part, at, stroke)
        for name, traced in part.paths.items():
            if len(traced) > 1:
                drawn = " ".join(f"{_number(x)},{_number(-y)}" for x, y in traced)
                lines.append(f'<polyline class="traced-path" data-point={quoteattr(name)} points="{drawn}" '
                             f'fill="none" stroke="black" stroke-dasharray="{_number(part.radius / 2)}" '
                             f'stroke-width="{_number(text_size / 30)}"/>')
        points = list(part.holes.values()) + list(part.corners.values()) + [end for slot in part.slots for end in slot]
        x, y = at((sum(p[0] for p in points) / len(points), sum(p[1] for p in points) / len(points))).split()
        lines.append(f'<text x="{x}" y="{y}" font-size="{_number(part.radius)}" text-anchor="middle">'
                     f'{escape(part.name)}</text>')
        lines.append("</g>")
    lines.append("</svg>")
    return "\n".join(lines) + "\n"


def _mark_svg(part: Part, at, stroke: str) -> list[str]:
    """Each mark of ``part`` (a point the design traces) as SVG: a cross of a pin's diameter and a centre dot."""
    lines = []
    arm = part.pin_diameter / 2
    for name, (x, y) in part.marks.items():
        cross = f"M {at((x - arm, y))} L {at((x + arm, y))} M {at((x, y - arm))} L {at((x, y + arm))}"
        cx, cy = at((x, y)).split()
        lines += [f'<path class="mark" data-point={quoteattr(name)} d="{cross}" {stroke}/>',
                  f'<circle class="mark-centre" data-point={quoteattr(name)} cx="{cx}" cy="{cy}" '
                  f'r="{_number(part.pin_diameter / 8)}" {stroke}/>']
    return lines


def _extent_corners(part: Part) -> list[Point]:
    xmin, ymin, xmax, ymax = part.extent()
    return [(xmin, ymin), (xmin, ymax), (xmax, ymin), (xmax, ymax)]


def _slot_path(start: Point, end: Point, radius: float, at) -> str:
    """A stadium of ``radius`` about the centre line start-end, as SVG path data."""
    dx, dy = end[0] - start[0], end[1] - start[1]
    size = math.hypot(dx, dy) or 1.0
    nx, ny = dy / size * radius, -dx / size * radius
    r = _number(radius)
    return (f"M {at((start[0] + nx, start[1] + ny))} L {at((end[0] + nx, end[1] + ny))} "
            f"A {r} {r} 0 0 0 {at((end[0] - nx, end[1] - ny))} L {at((start[0] - nx, start[1] - ny))} "
            f"A {r} {r} 0 0 0 {at((start[0] + nx, start[1] + ny))} Z")


def write_svg(path: str | os.PathLike, parts: list[Part], unit: str = "mm") -> None:
    """Write :func:`svg_text` of ``parts`` to ``path`` atomically (all or nothing).

    Parameters
    ----------
    path : str or os.PathLike
        Where to write.
    parts : list of Part
        The parts (:func:`link_parts`).
    unit : str, optional
        The drawing's unit (default ``"mm"``).

    Returns
    -------
    None

    Examples
    --------
    >>> import symlink
    >>> parts = symlink.link_parts(symlink.fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80}, pin_diameter=4)
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "parts.svg"
    >>> symlink.write_svg(path, parts)
    >>> path.read_text() == symlink.svg_text(parts)
    True
    """
    write_atomic(path, svg_text(parts, unit))


def write_dxf(path: str | os.PathLike, parts: list[Part], unit: str = "mm") -> None:
    """Write :func:`dxf_text` of ``parts`` to ``path`` atomically (all or nothing).

    Needs ``ezdxf``: ``pip install symlink-kinematics[fabrication]``.

    Parameters
    ----------
    path : str or os.PathLike
        Where to write.
    parts : list of Part
        The parts (:func:`link_parts`).
    unit : str, optional
        The drawing's unit (default ``"mm"``).

    Returns
    -------
    None

    Examples
    --------
    >>> import symlink
    >>> parts = symlink.link_parts(symlink.fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80}, pin_diameter=4)
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "parts.dxf"
    >>> symlink.write_dxf(path, parts)  # needs ezdxf (the fabrication extra)
    >>> "LWPOLYLINE" in path.read_text()
    True
    """
    write_atomic(path, dxf_text(parts, unit))


def dxf_text(parts: list[Part], unit: str = "mm") -> str:
    """The parts as DXF text (R2010), in a row as in :func:`svg_text`: per part, on a layer named after it, one
    closed LWPOLYLINE outline (arcs as bulges), a CIRCLE a hole, a closed LWPOLYLINE a slot and a TEXT label;
    ``$INSUNITS`` says the unit, so that a CAD program or laser cutter reads the parts at their real size.

    Needs ``ezdxf``: ``pip install symlink-kinematics[fabrication]``.

    Parameters
    ----------
    parts : list of Part
        The parts (:func:`link_parts`).
    unit : str, optional
        The drawing's unit (default ``"mm"``).

    Returns
    -------
    str
        The DXF document (R2010).

    Examples
    --------
    >>> import symlink
    >>> parts = symlink.link_parts(symlink.fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80}, pin_diameter=4)
    >>> text = symlink.dxf_text(parts)  # needs ezdxf (the fabrication extra)
    >>> "AC1024" in text, "LWPOLYLINE" in text  # R2010, the outlines
    (True, True)
    """
    _check_unit(unit)
    if not parts:
        raise ValueError("no parts to draw")
    try:
        import ezdxf
    except ImportError:
        raise ModuleNotFoundError("writing DXF needs ezdxf: pip install symlink-kinematics[fabrication]") from None
    document = ezdxf.new("R2010")
    document.header["$INSUNITS"] = _DXF_UNITS[unit]
    space = document.modelspace()
    for part, dx, dy in _layout(parts, unit):
        layer = {"layer": part.name}
        if part.name not in document.layers:
            document.layers.add(part.name)
        vertices = []
        for start, end, centre in part.outline():
            vertices.append((start[0] + dx, start[1] + dy, 0.0))
            following_angle = _arc_angle(end, centre, part)
            vertices.append((end[0] + dx, end[1] + dy, math.tan(following_angle / 4)))
        space.add_lwpolyline(vertices, format="xyb", close=True, dxfattribs=layer)
        for centre in part.holes.values():
            space.add_circle((centre[0] + dx, centre[1] + dy), part.pin_diameter / 2, dxfattribs=layer)
        for start, end in part.slots:
            space.add_lwpolyline(_slot_vertices(start, end, part.pin_diameter / 2, dx, dy), format="xyb",
                                 close=True, dxfattribs=layer)
        for (x, y) in part.marks.values():  # a centre-punch mark: a point and a cross
            arm = part.pin_diameter / 2
            space.add_point((x + dx, y + dy), dxfattribs=layer)
            space.add_line((x + dx - arm, y + dy), (x + dx + arm, y + dy), dxfattribs=layer)
            space.add_line((x + dx, y + dy - arm), (x + dx, y + dy + arm), dxfattribs=layer)
        xmin, _, _, ymax = part.extent()
        space.add_text(part.label(unit), height=part.radius,
                       dxfattribs={**layer, "insert": (xmin + dx, ymax + dy + part.radius)})
    stream = io.StringIO()
    document.write(stream)
    return stream.getvalue()


def _arc_angle(end: Point, centre: Point, part: Part) -> float:
    """The counter-clockwise angle of the arc after the edge ending at ``end`` (about ``centre``)."""
    pieces = part.outline()
    index = next(k for k, piece in enumerate(pieces) if piece[1] == end and piece[2] == centre)
    following = pieces[(index + 1) % len(pieces)][0]
    a0 = math.atan2(end[1] - centre[1], end[0] - centre[0])
    a1 = math.atan2(following[1] - centre[1], following[0] - centre[0])
    return (a1 - a0) % (2 * math.pi)


def _slot_vertices(start: Point, end: Point, radius: float, dx: float, dy: float) -> list[tuple[float, float, float]]:
    ddx, ddy = end[0] - start[0], end[1] - start[1]
    size = math.hypot(ddx, ddy) or 1.0
    nx, ny = ddy / size * radius, -ddx / size * radius
    return [(start[0] + nx + dx, start[1] + ny + dy, 0.0), (end[0] + nx + dx, end[1] + ny + dy, 1.0),
            (end[0] - nx + dx, end[1] - ny + dy, 0.0), (start[0] - nx + dx, start[1] - ny + dy, 1.0)]


#: The ``format`` of a design's JSON, and its version.
DESIGN_FORMAT, DESIGN_VERSION = "symlink-design", 1


@dataclass(frozen=True)
class LinkageDesign:
    """A design read from JSON: the linkage, its values by name (lengths in ``unit``, angles in radians), its unit."""

    _repr_html_ = record_html  # a notebook shows its fields as a table

    linkage: Linkage
    values: dict[str, float]
    unit: str


def design_json(linkage: Linkage, values: Mapping[str, float], unit: str = "mm") -> str:
    """A design as JSON text: ``format``, ``version``, ``unit``, its ``links`` (name, joints) and ``joints``
    (name, kind, the links joined), and ``linkage``, the linkage file's mapping with ``values`` as its
    defaults: every dimension, and the inputs that ``values`` gives (the pose, such as a five-bar's second
    crank angle; branch signs are not kept).  Extras such as the transmission angle are Python only and left out.

    >>> from symlink.mechanism.catalog import fourbar
    >>> text = design_json(fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80})
    >>> design = read_design(text)
    >>> design.linkage.name, design.values["b"], design.unit
    ('fourbar', 66.0, 'mm')
    """
    from ..io.linkage_file import linkage_text
    _check_unit(unit)
    found = mechanism(linkage)
    names = {s.name for s in linkage.parameters}
    missing = sorted(names - set(values))
    if missing:
        raise ValueError(f"{linkage.name} needs a value for {', '.join(missing)}")
    dimensions = {name: _finite(name, values[name]) for name in [s.name for s in linkage.parameters]}
    dimensions.update({q.name: _finite(q.name, values[q.name]) for q in linkage.inputs if q.name in values})
    record = {
        "format": DESIGN_FORMAT, "version": DESIGN_VERSION, "unit": unit,
        "links": [{"name": body.name, "joints": list(body.joints)} for body in found.bodies],
        "joints": [{"name": joint.name, "kind": joint.kind, "links": list(joint.bodies)} for joint in found.joints],
        "linkage": tomllib.loads(linkage_text(linkage, dimensions)),
    }
    return json.dumps(record, indent=1) + "\n"


#: The most bytes (and characters) of a design's JSON text: that of a linkage file.
MAX_DESIGN_BYTES = 4 << 20


def _finite(name: str, value: object) -> float:
    found = finite_float(value) if isinstance(value, (int, float)) else None
    if found is None:
        raise ValueError(f"{name} must be a finite number, got {excerpt(value)}")
    return found


def read_design(text: str, source: str = "<design>") -> LinkageDesign:
    """The :class:`LinkageDesign` of :func:`design_json`'s text; ``ValueError`` naming what is wrong (not JSON, another
    format or version, an unknown unit, a bad linkage, links or joints that are not the linkage's).

    Parameters
    ----------
    text : str
        The JSON text of a design.
    source : str, optional
        What to call it in error messages.

    Returns
    -------
    LinkageDesign
        The linkage, its values and unit.

    Raises
    ------
    ValueError
        Naming what is wrong: not JSON, another format or version, an unknown unit, a bad linkage.

    Examples
    --------
    >>> import symlink, tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "design.json"
    >>> symlink.write_design(path, symlink.fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80})
    >>> design = symlink.read_design(path.read_text())
    >>> design.linkage.name, design.values["b"], design.unit
    ('fourbar', 66.0, 'mm')
    """
    from ..io.linkage_file import linkage_from_mapping
    record = json_data(text, source, limit=MAX_DESIGN_BYTES)
    if not isinstance(record, dict) or record.get("format") != DESIGN_FORMAT:
        raise ValueError(f"{source}: not a symlink design (its format must be {DESIGN_FORMAT!r})")
    if record.get("version") != DESIGN_VERSION:
        raise ValueError(f"{source}: design version {record.get('version')!r}; this symlink reads {DESIGN_VERSION}")
    unit = record.get("unit")
    if unit not in UNITS_IN_MM:
        raise ValueError(f"{source}: unit must be one of {', '.join(UNITS_IN_MM)}, got {unit!r}")
    found = linkage_from_mapping(record.get("linkage") or {}, f"{source}: linkage")
    linkage = found.linkage
    try:
        derived = mechanism(linkage)
    except ValueError as error:
        raise ValueError(f"{source}: linkage: {error}") from None
    links = [{"name": body.name, "joints": list(body.joints)} for body in derived.bodies]
    joints = [{"name": joint.name, "kind": joint.kind, "links": list(joint.bodies)} for joint in derived.joints]
    if record.get("links") != links or record.get("joints") != joints:
        raise ValueError(f"{source}: its links and joints are not those of its linkage "
                         f"({', '.join(body.name for body in derived.bodies)})")
    missing = [s.name for s in linkage.parameters if s.name not in found.defaults]
    if missing:
        raise ValueError(f"{source}: no value for {', '.join(missing)}")
    return LinkageDesign(linkage, dict(found.defaults), unit)


def write_design(path: str | os.PathLike, linkage: Linkage, values: Mapping[str, float], unit: str = "mm") -> None:
    """Write :func:`design_json` to ``path`` atomically.

    Parameters
    ----------
    path : str or os.PathLike
        Where to write.
    linkage : Linkage
        The linkage.
    values : mapping of str to float
        Its parameters' values.
    unit : str, optional
        The lengths' unit (default ``"mm"``).

    Returns
    -------
    None

    Examples
    --------
    >>> import symlink, tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "design.json"
    >>> symlink.write_design(path, symlink.fourbar(), {"a": 20, "b": 66, "c": 56, "d": 80})
    >>> design = symlink.read_design(path.read_text())
    >>> design.linkage.name, design.values["b"], design.unit
    ('fourbar', 66.0, 'mm')
    """
    write_atomic(path, design_json(linkage, values, unit))
