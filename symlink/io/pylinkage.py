"""pylinkage's JSON mechanisms (``pylinkage.mechanism.serialization``), read and written.

The format (pylinkage 1.x ``mechanism_to_dict``)::

    {"name": "Four-Bar Linkage",
     "joints": [{"id": "O1", "type": "ground", "position": [0, 0]},
                {"id": "B", "type": "revolute", "position": [17.68, 17.68]},
                {"id": "S", "type": "prismatic", "position": [-61.7, 0], "axis": [1, 0], "line_point": [0, 0]},
                {"id": "T", "type": "tracker", "position": [26.3, 100.2], "ref_joint1_id": "B",
                 "ref_joint2_id": "C", "distance": 25.0, "angle": 0.0}, ...],
     "links": [{"id": "ground", "type": "ground", "joints": ["O1", "O2"]},
               {"id": "crank", "type": "driver", "joints": ["O1", "B"], "motor_joint": "O1", ...},
               {"id": "coupler", "type": "link", "joints": ["B", "C"]}, ...],
     "ground": "ground"}

Read as joints: a ``ground`` joint is a pin on the ground link (listed there or not),
a ``prismatic`` joint a slider on the ground along ``axis`` (pylinkage's slide
axes are fixed in the frame), a ``tracker`` joint a point riding on the link
that holds both of its reference joints; a ``driver`` (or ``arc_driver``) link
is driven at its ``motor_joint``.  Joint ids that are not symlink names
(pylinkage's builder writes ``crank.motor_ground.O1``) are renamed ``A``, ``B``,
... in file order, and ``names`` of the result says which is which.  Anything
else (a missing key, a position that is not two finite numbers, an unknown
type, a slider off its line) is one ``ValueError`` naming the entry.

>>> description = read_pylinkage({"joints": [
...     {"id": "O1", "type": "ground", "position": [0, 0]}, {"id": "O2", "type": "ground", "position": [100, 0]},
...     {"id": "B", "type": "revolute", "position": [0, 25]}, {"id": "C", "type": "revolute", "position": [60, 50]}],
...     "links": [{"id": "ground", "type": "ground", "joints": ["O1", "O2"]},
...               {"id": "crank", "type": "driver", "joints": ["O1", "B"], "motor_joint": "O1"},
...               {"id": "coupler", "type": "link", "joints": ["B", "C"]},
...               {"id": "rocker", "type": "link", "joints": ["C", "O2"]}], "ground": "ground"})
>>> description.links["rocker"], description.drivers
(['C', 'O2'], (('O1', 'crank'),))
>>> write_pylinkage(description.build())["links"][1]["motor_joint"]
'O1'
"""
from __future__ import annotations

import math
import re
from typing import Any, Mapping

from ..common.files import excerpt
from ..common.numbers import finite_float, json_data
from ..mechanism.joints import JointDescription, JointLinkage, Slider
from ..mechanism.topology import GROUND
from .linkage_file import MAX_LINKAGE_BYTES

#: The largest coordinate or length a mechanism file may hold (the bound of the joints' coordinates).
MAX_COORDINATE = 1e100

__all__ = ["read_pylinkage", "write_pylinkage"]

_PLAIN = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")
_JOINT_TYPES = ("ground", "revolute", "prismatic", "tracker")
_LINK_TYPES = ("ground", "driver", "arc_driver", "link")
#: Relative distance (of the drawing's size) within which a prismatic joint lies on its line.
_ON_LINE = 1e-9


def _entry(data: Any, what: str, keys: tuple[str, ...]) -> Mapping[str, Any]:
    if not isinstance(data, Mapping):
        raise ValueError(f"pylinkage {what}: expected an object, found {type(data).__name__}")
    for key in keys:
        if key not in data:
            raise ValueError(f"pylinkage {what}: no {key!r}")
    return data


def _pair(value: Any, what: str) -> tuple[float, float]:
    if (not isinstance(value, (list, tuple)) or len(value) != 2
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)):
        raise ValueError(f"pylinkage {what}: expected two numbers, found {excerpt(value)}")
    x, y = finite_float(value[0]), finite_float(value[1])
    if x is None or y is None:
        raise ValueError(f"pylinkage {what}: {excerpt(value)} is not finite")
    return x, y


def _link_name(identifier: Any, what: str) -> str:
    if not isinstance(identifier, str) or not identifier:
        raise ValueError(f"pylinkage {what}: an id is a text, not {identifier!r}")
    name = re.sub(r"[^A-Za-z0-9_]", "_", identifier)
    return name if name[0].isalpha() else f"L_{name}"


def _coordinate_range(value: float, token: str) -> None:
    """A pylinkage number is one a mechanism can hold: at most :data:`MAX_COORDINATE` in size."""
    if abs(value) > MAX_COORDINATE:
        raise ValueError(f"the number {excerpt(token)} is out of range (at most {MAX_COORDINATE:g})")


def _json_data(text: str) -> Any:
    """The JSON text of a pylinkage mechanism, read strictly (:func:`~symlink.common.numbers.json_data`): size
    capped, every number range-checked, ``NaN``/``Infinity`` and keys given twice refused, deep nesting refused;
    every problem one ``ValueError``."""
    if len(text) > MAX_LINKAGE_BYTES:
        raise ValueError(f"pylinkage JSON: {len(text):,} characters, more than a mechanism needs "
                         f"(at most {MAX_LINKAGE_BYTES:,})")
    return json_data(text, "pylinkage JSON", number=_coordinate_range)


def read_pylinkage(data: Mapping[str, Any] | str) -> JointDescription:
    """A pylinkage mechanism (a dict, or its JSON text) as joints, links, drivers and the drawn pose.

    Both of pylinkage's JSON formats are read: the mechanism format (joints and links, above) and the
    legacy format of ``Linkage.to_dict`` (pylinkage before 1.0: ``Static``, ``Crank``, ``Revolute``,
    ``Fixed`` and ``Prismatic``/``Linear`` joints, see :func:`_read_legacy`).

    Parameters
    ----------
    data : mapping or str
        A pylinkage mechanism: the dict, or its JSON text (either of pylinkage's formats).

    Returns
    -------
    JointDescription
        Its links, joints, drivers and drawn pose; ``.build()`` makes the linkage.

    Raises
    ------
    ValueError
        For data that is not a pylinkage mechanism symlink can read.

    Examples
    --------
    >>> import symlink
    >>> drawn = symlink.from_joints({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"],
    ...                              "rocker": ["D", "C"]},
    ...                             {"A": (0, 0), "B": (0, 1), "C": (3, 2), "D": (3, 0)}, driver="A")
    >>> described = symlink.read_pylinkage(symlink.write_pylinkage(drawn))
    >>> described.drivers, described.build().linkage.unknowns
    ((('A', 'crank'),), (theta_BC, theta_DC))
    """
    if isinstance(data, str):
        data = _json_data(data)
    if isinstance(data, Mapping) and _is_legacy(data):
        return _read_legacy(data)
    top = _entry(data, "mechanism", ("joints", "links"))
    joints, links = top["joints"], top["links"]
    if not isinstance(joints, list) or not isinstance(links, list) or not joints or not links:
        raise ValueError("pylinkage mechanism: 'joints' and 'links' must be non-empty lists")
    ids = []
    for k, joint in enumerate(joints):
        entry = _entry(joint, f"joints[{k}]", ("id",))
        if not isinstance(entry["id"], str) or not entry["id"]:
            raise ValueError(f"pylinkage joints[{k}]: an id is a text, not {entry['id']!r}")
        ids.append(entry["id"])
    twice = [i for k, i in enumerate(ids) if i in ids[:k]]
    if twice:
        raise ValueError(f"pylinkage joints: the id {twice[0]!r} is used twice")
    keep = all(_PLAIN.match(i) for i in ids)
    names = {i: (i if keep else (chr(ord("A") + k) if k < 26 else f"J{k}")) for k, i in enumerate(ids)}

    ground_id = top.get("ground")
    link_joints: dict[str, list[str]] = {}
    ground_name = None
    drivers: list[str | tuple[str, str]] = []
    speeds: dict[str, float] = {}
    for k, link in enumerate(links):
        entry = _entry(link, f"links[{k}]", ("id", "joints"))
        kind = entry.get("type", "link")
        if kind not in _LINK_TYPES:
            raise ValueError(f"pylinkage links[{k}]: type {kind!r} is not one of {', '.join(_LINK_TYPES)}")
        if not isinstance(entry["joints"], list):
            raise ValueError(f"pylinkage links[{k}]: 'joints' must be a list of joint ids")
        unknown = [j for j in entry["joints"] if j not in names]
        if unknown:
            raise ValueError(f"pylinkage links[{k}] ({entry['id']}): no joint {unknown[0]!r}")
        is_ground = kind == "ground" and (ground_name is None) and (ground_id in (None, entry["id"]))
        name = GROUND if is_ground else _link_name(entry["id"], f"links[{k}]")
        if name in link_joints:
            raise ValueError(f"pylinkage links[{k}]: a second link named {name!r}")
        if is_ground:
            ground_name = name
        link_joints[name] = [names[j] for j in entry["joints"]]
        if kind in ("driver", "arc_driver"):
            motor = entry.get("motor_joint")
            if motor is None:
                motor = next((j for j in entry["joints"] if _joint_type(joints, ids, j) == "ground"), None)
            if motor not in names or names[motor] not in link_joints[name]:
                raise ValueError(f"pylinkage links[{k}] ({entry['id']}): its motor joint {motor!r} is not one of "
                                 "its joints")
            drivers.append((names[motor], name))
            if "angular_velocity" in entry:
                speeds[names[motor]] = _speed(entry["angular_velocity"],
                                              f"links[{k}] ({entry['id']}) angular_velocity")
    if ground_name is None:
        link_joints = {GROUND: [], **link_joints}
    if not drivers:
        raise ValueError("pylinkage mechanism: no driver link (type 'driver' with a 'motor_joint')")

    coordinates: dict[str, tuple[float, float]] = {}
    kinds: dict[str, object] = {}
    trackers = []
    for k, joint in enumerate(joints):
        kind = joint.get("type", "revolute")
        name = names[ids[k]]
        if kind not in _JOINT_TYPES:
            raise ValueError(f"pylinkage joints[{k}] ({ids[k]}): type {kind!r} is not one of "
                             f"{', '.join(_JOINT_TYPES)}")
        if "position" not in joint:
            raise ValueError(f"pylinkage joints[{k}] ({ids[k]}): no 'position'")
        coordinates[name] = _pair(joint["position"], f"joints[{k}] ({ids[k]}) position")
        if kind in ("ground", "prismatic") and name not in link_joints[GROUND]:
            link_joints[GROUND].append(name)
        if kind == "prismatic":
            ax, ay = _pair(joint.get("axis", [1.0, 0.0]), f"joints[{k}] ({ids[k]}) axis")
            if math.hypot(ax, ay) == 0:
                raise ValueError(f"pylinkage joints[{k}] ({ids[k]}): its axis has no direction")
            kinds[name] = Slider(GROUND, math.atan2(ay, ax))
            px, py = _pair(joint.get("line_point", joint["position"]), f"joints[{k}] ({ids[k]}) line_point")
            x, y = coordinates[name]
            off = abs((x - px) * ay - (y - py) * ax) / math.hypot(ax, ay)
            if off > _ON_LINE * max(1.0, abs(x), abs(y), abs(px), abs(py)):
                raise ValueError(f"pylinkage joints[{k}] ({ids[k]}): its position is {off:.6g} off its line")
        if kind == "tracker":
            trackers.append((k, name, joint))
    for k, name, joint in trackers:
        refs = [joint.get("ref_joint1_id"), joint.get("ref_joint2_id")]
        if not all(r in names for r in refs):
            raise ValueError(f"pylinkage joints[{k}] ({ids[k]}): its reference joints {refs!r} are not joints")
        holder = next((link for link, held in link_joints.items()
                       if names[refs[0]] in held and names[refs[1]] in held), None)
        if holder is None:
            raise ValueError(f"pylinkage joints[{k}] ({ids[k]}): no link holds both its reference joints")
        if name not in link_joints[holder]:
            link_joints[holder].append(name)
    return JointDescription(link_joints, coordinates, tuple(drivers), kinds or None, GROUND,
                            str(top.get("name") or "pylinkage"), names, speeds or None)


def _speed(value: Any, what: str) -> float:
    """A driver's speed: a finite number."""
    found = finite_float(value)
    if found is None:
        raise ValueError(f"pylinkage {what}: a driver's speed must be a finite number, got {excerpt(value)}")
    return found


def _joint_type(joints: list, ids: list[str], identifier: str) -> str:
    return joints[ids.index(identifier)].get("type", "revolute")


def write_pylinkage(drawn: JointLinkage) -> dict[str, Any]:
    """A pylinkage mechanism dict (``json.dumps`` it) of a linkage from its joints, at its drawn pose.

    Pins on the ground are ``ground`` joints, sliders ``prismatic`` joints on a fixed axis (a slider on a
    moving guide has no pylinkage form: ``ValueError``), points held by one link ``tracker`` joints on its
    first two joints; the links driven at the ground are ``driver`` links, with the ``angular_velocity``
    their drivers had when read (:attr:`~symlink.mechanism.joints.JointLinkage.speeds`; none: pylinkage's
    default).

    Parameters
    ----------
    drawn : JointLinkage
        A linkage from its joints (:func:`from_joints`).

    Returns
    -------
    dict
        The pylinkage mechanism; ``json.dumps`` it.

    Raises
    ------
    ValueError
        For a slider on a moving guide, which pylinkage cannot write.

    Examples
    --------
    >>> import symlink
    >>> drawn = symlink.from_joints({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"],
    ...                              "rocker": ["D", "C"]},
    ...                             {"A": (0, 0), "B": (0, 1), "C": (3, 2), "D": (3, 0)}, driver="A")
    >>> mechanism = symlink.write_pylinkage(drawn)
    >>> [(joint["id"], joint["type"]) for joint in mechanism["joints"]]
    [('A', 'ground'), ('D', 'ground'), ('B', 'revolute'), ('C', 'revolute')]
    """
    chain = drawn.chain
    joints: list[dict[str, Any]] = []
    for joint in chain.joints:
        x, y = drawn.coordinates[joint]
        holders = chain.links_of(joint)
        entry: dict[str, Any] = {"id": joint, "type": "revolute", "position": [x, y]}
        if joint in chain.sliders:
            if joint in chain.translating:
                raise ValueError(f"joint {joint!r} is a block that slides without turning: pylinkage's prismatic "
                                 "joints are pins in a slot")
            if chain.sliders[joint] != chain.ground:
                raise ValueError(f"slider {joint!r} slides on {chain.sliders[joint]!r}, a moving link: pylinkage's "
                                 "prismatic joints slide along an axis fixed in the frame")
            angle = drawn.slider_angles[joint]
            entry.update(type="prismatic", axis=[math.cos(angle), math.sin(angle)], line_point=[x, y],
                         slide_distance=0.0)
        elif chain.ground in holders:
            entry["type"] = "ground"
        elif len(holders) == 1:
            others = [j for j in chain.links[holders[0]] if j != joint]
            first, second = drawn.coordinates[others[0]], drawn.coordinates[others[1]]
            base = math.atan2(second[1] - first[1], second[0] - first[0])
            entry.update(type="tracker", ref_joint1_id=others[0], ref_joint2_id=others[1],
                         distance=math.dist(first, (x, y)), angle=math.atan2(y - first[1], x - first[0]) - base)
        joints.append(entry)
    links: list[dict[str, Any]] = []
    driven = {}
    for driver, link in drawn.drivers:
        if driver in chain.sliders or chain.ground not in chain.links_of(driver):
            raise ValueError(f"driver {driver!r}: pylinkage drives a link about a ground joint (not a slider, "
                             "not a pin between two moving links)")
        driven[link or next(m for m in chain.links_of(driver) if m != chain.ground)] = driver
    for link, held in chain.links.items():
        shown = [j for j in held if not (link == chain.ground and j in chain.sliders)]
        entry = {"id": link, "type": "ground" if link == chain.ground else "link", "joints": shown}
        if link in driven:
            motor = driven[link]
            tip = next(j for j in held if j != motor)
            (x0, y0), (x1, y1) = drawn.coordinates[motor], drawn.coordinates[tip]
            entry.update(type="driver", initial_angle=math.atan2(y1 - y0, x1 - x0), motor_joint=motor)
            if motor in drawn.speeds:  # the driver's speed as it was read (rad a step)
                entry["angular_velocity"] = float(drawn.speeds[motor])
        links.append(entry)
    return {"name": drawn.linkage.name, "joints": joints, "links": links, "ground": chain.ground}


_LEGACY_TYPES = ("Static", "Crank", "Revolute", "Fixed", "Prismatic", "Linear")


def _is_legacy(data: Mapping[str, Any]) -> bool:
    joints = data.get("joints")
    return (isinstance(joints, list) and bool(joints) and "links" not in data
            and all(isinstance(j, Mapping) and j.get("type") in _LEGACY_TYPES for j in joints))


def _circles(p: tuple[float, float], r: float, q: tuple[float, float], s: float,
             near: tuple[float, float]) -> tuple[float, float] | None:
    """The meeting point of the circles (p, r) and (q, s) nearest ``near``, or None where they do not meet."""
    d = math.dist(p, q)
    if d == 0:
        return None
    along = (r * r - s * s + d * d) / (2 * d)
    across2 = r * r - along * along
    if across2 < -1e-12 * max(r, s, d) ** 2:
        return None
    across = math.sqrt(max(across2, 0.0))
    ux, uy = (q[0] - p[0]) / d, (q[1] - p[1]) / d
    found = [(p[0] + along * ux - k * across * uy, p[1] + along * uy + k * across * ux) for k in (1, -1)]
    return min(found, key=lambda point: math.dist(point, near))


def _read_legacy(data: Mapping[str, Any]) -> JointDescription:
    """pylinkage's legacy ``Linkage.to_dict``: joints that each place themselves from their parents.

    ``Static`` joints (listed, or written inline as a parent) are pins on the ground; a
    ``Crank`` turns about its ``joint0`` at ``distance``; a ``Revolute`` joins two links from
    ``joint0`` and ``joint1`` (``distance0``, ``distance1``); a ``Fixed`` joint rides on the link of
    ``joint0`` and ``joint1`` at ``distance`` and ``angle`` from ``joint0`` (measured from the
    direction to ``joint1``); a ``Prismatic`` (``Linear``) joint is a pin on a link from ``joint0``
    (``revolute_radius``) sliding along the line through ``joint1`` and ``joint2``.  The given
    distances are the dimensions: each joint is placed from its parents in dependency order, where
    two circles (or a circle and a line) meet nearest its stored position, as pylinkage does.
    """
    raw = data["joints"]
    entries: list[dict[str, Any]] = []
    inline: dict[tuple, str] = {}

    def reference(value: Any, where: str) -> str | None:
        if value is None:
            return None
        if not isinstance(value, Mapping):
            raise ValueError(f"pylinkage {where}: a parent is {{'ref': name}} or an inline Static, not {value!r}")
        if value.get("inline"):
            x, y = _pair([value.get("x"), value.get("y")], f"{where} (inline Static)")
            key = (value.get("name"), x, y)
            if key not in inline:
                inline[key] = str(value.get("name") or f"static{len(inline) + 1}")
                entries.append({"type": "Static", "name": inline[key], "x": x, "y": y})
            return inline[key]
        if not isinstance(value.get("ref"), str):
            raise ValueError(f"pylinkage {where}: a parent reference names a joint, not {value!r}")
        return value["ref"]

    parents: dict[str, list[str | None]] = {}
    listed = []
    for k, joint in enumerate(raw):
        name = joint.get("name")
        if not isinstance(name, str) or not name:
            raise ValueError(f"pylinkage joints[{k}]: a legacy joint needs a name, got {name!r}")
        listed.append(dict(joint))
        parents[name] = [reference(joint.get(key), f"joints[{k}] ({name}) {key}")
                         for key in ("joint0", "joint1", "joint2")]
    entries = listed + [e for e in entries if e["name"] not in {j["name"] for j in listed}]
    ids = [e["name"] for e in entries]
    twice = [i for k, i in enumerate(ids) if i in ids[:k]]
    if twice:
        raise ValueError(f"pylinkage joints: the name {twice[0]!r} is used twice")
    keep = all(_PLAIN.match(i) for i in ids)
    names = {i: (i if keep else (chr(ord("A") + k) if k < 26 else f"J{k}")) for k, i in enumerate(ids)}
    kind = {e["name"]: e["type"] for e in entries}
    for name, refs in parents.items():
        for ref in refs:
            if ref is not None and ref not in kind:
                raise ValueError(f"pylinkage joint {name!r}: its parent {ref!r} is not a joint")

    def number(entry: Mapping[str, Any], key: str) -> float:
        value = entry.get(key)
        found = finite_float(value)
        if found is None:
            raise ValueError(f"pylinkage joint {excerpt(entry['name'])}: {key} must be a finite number, got "
                             f"{excerpt(value)}")
        return found

    # Place every joint from its parents, in dependency order.
    placed: dict[str, tuple[float, float]] = {}
    pending = list(entries)
    while pending:
        progress = False
        for entry in list(pending):
            name, refs = entry["name"], parents.get(entry["name"], [None, None, None])
            if any(r is not None and r not in placed for r in refs):
                continue
            stored = _pair([entry.get("x"), entry.get("y")], f"joint {name!r} position")
            if entry["type"] == "Static":
                point: tuple[float, float] | None = stored
            elif entry["type"] == "Crank":
                centre, radius = placed[_required(refs[0], name, "joint0")], number(entry, "distance")
                angle = math.atan2(stored[1] - centre[1], stored[0] - centre[0])
                point = (centre[0] + radius * math.cos(angle), centre[1] + radius * math.sin(angle))
            elif entry["type"] == "Revolute":
                point = _circles(placed[_required(refs[0], name, "joint0")], number(entry, "distance0"),
                                 placed[_required(refs[1], name, "joint1")], number(entry, "distance1"), stored)
            elif entry["type"] == "Fixed":
                a, b = placed[_required(refs[0], name, "joint0")], placed[_required(refs[1], name, "joint1")]
                angle = math.atan2(b[1] - a[1], b[0] - a[0]) + number(entry, "angle")
                radius = number(entry, "distance")
                point = (a[0] + radius * math.cos(angle), a[1] + radius * math.sin(angle))
            else:  # Prismatic / Linear: the circle about joint0 meets the line through joint1 and joint2
                centre = placed[_required(refs[0], name, "joint0")]
                a, b = placed[_required(refs[1], name, "joint1")], placed[_required(refs[2], name, "joint2")]
                point = _circle_and_line(centre, number(entry, "revolute_radius"), a, b, stored)
            if point is None:
                raise ValueError(f"pylinkage joint {name!r} cannot be placed: its constraints do not meet")
            placed[name] = point
            pending.remove(entry)
            progress = True
        if not progress:
            raise ValueError(f"pylinkage joints {', '.join(e['name'] for e in pending)}: their parents form a "
                             "loop that no joint starts")

    links: dict[str, list[str]] = {GROUND: [names[e["name"]] for e in entries if e["type"] == "Static"]}
    kinds: dict[str, object] = {}
    drivers: list[str | tuple[str, str]] = []
    speeds: dict[str, float] = {}

    def new_link(*members: str) -> str:
        link = f"L{len(links)}"
        links[link] = [names[m] for m in members]
        return link

    fixed = []
    for entry in entries:  # the parents a joint needs were checked when it was placed
        name = entry["name"]
        r = [ref or "" for ref in parents.get(name, [None, None, None])]
        if entry["type"] == "Crank":
            if kind[r[0]] != "Static":
                raise ValueError(f"pylinkage crank {name!r} turns about {r[0]!r}, which is not a Static joint")
            drivers.append((names[r[0]], new_link(r[0], name)))
            if entry.get("angle") is not None:  # a Crank turns by its angle each step
                speeds[names[r[0]]] = _speed(entry["angle"], f"crank {name!r} angle")
        elif entry["type"] == "Revolute":
            new_link(r[0], name)
            new_link(r[1], name)
        elif entry["type"] in ("Prismatic", "Linear"):
            new_link(r[0], name)
            line = [names[r[1]], names[r[2]]]
            guide = next((link for link, held in links.items() if all(j in held for j in line)), None)
            if guide is None:
                raise ValueError(f"pylinkage joint {name!r} slides along {r[1]!r}-{r[2]!r}, which no link "
                                 "holds both of")
            links[guide].append(names[name])
            (x1, y1), (x2, y2) = placed[r[1]], placed[r[2]]
            kinds[names[name]] = Slider(guide, math.atan2(y2 - y1, x2 - x1))
        elif entry["type"] == "Fixed":
            fixed.append((name, r))
    for name, r in fixed:  # a Fixed joint rides on the link that holds both of its parents
        pair = [names[r[0]], names[r[1]]]
        holder = next((link for link, held in links.items() if all(j in held for j in pair)), None)
        if holder is None:
            holder = new_link(r[0], r[1])
        links[holder].append(names[name])
    if not drivers:
        raise ValueError("pylinkage legacy linkage: no Crank joint to drive it")
    coordinates = {names[n]: placed[n] for n in ids}
    return JointDescription(links, coordinates, tuple(drivers), kinds or None, GROUND,
                            str(data.get("name") or "pylinkage"), names, speeds or None)


def _required(ref: str | None, name: str, key: str) -> str:
    if ref is None:
        raise ValueError(f"pylinkage joint {name!r} has no {key}")
    return ref


def _circle_and_line(centre: tuple[float, float], radius: float, a: tuple[float, float], b: tuple[float, float],
                     near: tuple[float, float]) -> tuple[float, float] | None:
    """Where the circle (centre, radius) meets the line through a and b, nearest ``near``; None if nowhere."""
    length = math.dist(a, b)
    if length == 0:
        return None
    ux, uy = (b[0] - a[0]) / length, (b[1] - a[1]) / length
    along = (centre[0] - a[0]) * ux + (centre[1] - a[1]) * uy
    across = (centre[1] - a[1]) * ux - (centre[0] - a[0]) * uy
    half2 = radius * radius - across * across
    if half2 < -1e-12 * radius * radius:
        return None
    half = math.sqrt(max(half2, 0.0))
    found = [(a[0] + (along + k * half) * ux, a[1] + (along + k * half) * uy) for k in (1, -1)]
    return min(found, key=lambda point: math.dist(point, near))
