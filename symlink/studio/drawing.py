"""A drawing in the studio: joints placed by clicks, links, the ground and the driver, as JSON.

The page sends a drawing as::

    {"name": "hoeken",                                   # optional, a linkage name
     "joints": [{"name": "A", "x": 0, "y": 0, "ground": true}, {"name": "B", "x": 0, "y": 1}, ...],
     "links": [["A", "B"], ["B", "C", "P"], ["D", "C"]],  # the moving links, by their joints
     "driver": {"joint": "A"},                            # optional "link": the index of the driven link
     "sliders": [{"joint": "C", "guide": "ground", "angle": 0.0}]}   # guide: "ground" or a link index; radians

The joints marked ``ground`` make the ground link (in the order listed); a link whose joints are all on
the ground is part of it.  Link ``k`` (from 0) is named ``link<k+1>``.  A joint on no link is left out
and said so (a drawing in progress).  :func:`description` checks all of it and gives the arguments of
:func:`symlink.mechanism.joints.from_joints`; anything wrong is one ``ValueError`` naming the entry.  The
page's text never reaches ``eval`` or SymPy's parser: names must be plain identifiers and numbers JSON numbers.

What the studio asks of a drawing is here, with no web framework: :func:`structure` (mobility, loops,
closed form or Newton, a message naming what is over- or under-constrained), :func:`derivation` (the
equations as LaTeX), :func:`solver` (the generated JavaScript), :func:`export_bytes` (the files the
command line writes) and :func:`open_source` (a catalog linkage, an atlas entry, a linkage file's text,
pylinkage JSON or a Pyslvs expression, as a drawing).
"""
from __future__ import annotations

import json
import re
import threading
from collections import OrderedDict
from dataclasses import dataclass
from typing import Any, Callable, Mapping

from ..common.display import record_html
from ..common.numbers import finite_float
from ..common.names import PLAIN_NAME, label
from ..mechanism.joints import JointLinkage, Slider, from_joints
from ..mechanism.topology import GROUND, Chain

__all__ = ["Description", "description", "drawn_linkage", "structure", "derivation", "solver", "export_bytes",
           "EXPORT_FORMATS", "open_source", "drawing_of", "MAX_JOINTS", "MAX_LINKS", "StructureError"]

#: The most joints (and links) a drawing may have: a studio drawing is a sketch, not a data set.
MAX_JOINTS = 200
#: The most links a drawing may have: its loops are searched among the joint graph's simple cycles, whose
#: number grows fast with the links (the atlas stops at eight; Jansen's leg has eight).
MAX_LINKS = 24
#: The name a drawing's linkage gets when it gives none.
DEFAULT_NAME = "drawing"
#: Largest coordinate accepted (a drawing's units are anything, but not astronomical).
MAX_COORDINATE = 1e9


class StructureError(ValueError):
    """A drawing that is well formed but no linkage that moves as driven; ``mobility`` as far as it is known."""

    def __init__(self, message: str, mobility: dict[str, int] | None = None) -> None:
        super().__init__(message)
        self.mobility = mobility


@dataclass(frozen=True)
class Description:
    """The arguments of :func:`~symlink.mechanism.joints.from_joints` that a drawing gives, and what it left out."""

    _repr_html_ = record_html  # a notebook shows its fields as a table

    name: str
    links: dict[str, list[str]]
    coordinates: dict[str, tuple[float, float]]
    drivers: list[str | tuple[str, str]]
    sliders: dict[str, Slider]
    notes: tuple[str, ...]

    @property
    def key(self) -> str:
        """A canonical text of the description: equal drawings share their derivation in the cache."""
        return json.dumps([self.name, self.links, self.coordinates, self.drivers,
                           {j: [s.guide, s.angle, s.turns] for j, s in self.sliders.items()}], sort_keys=True)


def _name(value: Any, what: str) -> str:
    if not isinstance(value, str) or not PLAIN_NAME.match(value) or len(value) > 40:
        shown = value if not isinstance(value, str) else value[:40]
        raise ValueError(f"{what} must be a name of ASCII letters, digits and _ (starting with a letter), "
                         f"not {shown!r}")
    return value


def _number(value: Any, what: str) -> float:
    found = finite_float(value) if isinstance(value, (int, float)) else None
    if found is None:
        raise ValueError(f"{what} must be a finite number, not {str(value)[:40]!r}")
    if abs(found) > MAX_COORDINATE:
        raise ValueError(f"{what} is {found:g}; keep coordinates within {MAX_COORDINATE:g}")
    return found


def _list(value: Any, what: str) -> list:
    if not isinstance(value, list):
        raise ValueError(f"{what} must be a list, not {type(value).__name__}")
    if len(value) > MAX_JOINTS:
        raise ValueError(f"{what} has {len(value)} entries; a drawing has at most {MAX_JOINTS}")
    return value


def description(data: Any) -> Description:
    """The :func:`from_joints` arguments of a drawing (see the module's documentation); ``ValueError`` naming
    the entry that is wrong.

    >>> d = description({"joints": [{"name": "A", "x": 0, "y": 0, "ground": True}, {"name": "B", "x": 0, "y": 1},
    ...     {"name": "C", "x": 2, "y": 2.5}, {"name": "D", "x": 2, "y": 0, "ground": True}],
    ...     "links": [["A", "B"], ["B", "C"], ["D", "C"]], "driver": {"joint": "A"}})
    >>> d.links, d.drivers
    ({'ground': ['A', 'D'], 'link1': ['A', 'B'], 'link2': ['B', 'C'], 'link3': ['D', 'C']}, ['A'])
    """
    if not isinstance(data, dict):
        raise ValueError("a drawing is a JSON object with joints, links, driver and sliders")
    unknown = sorted(set(data) - {"name", "joints", "links", "driver", "sliders"})
    if unknown:
        raise ValueError(f"a drawing has no entry {unknown[0][:40]!r} (it has name, joints, links, driver, sliders)")
    name = data.get("name") or DEFAULT_NAME
    if not isinstance(name, str) or len(name) > 40:
        raise ValueError("name must be a short text")
    name = label(name)
    coordinates: dict[str, tuple[float, float]] = {}
    grounded: list[str] = []
    for k, joint in enumerate(_list(data.get("joints", []), "joints")):
        if not isinstance(joint, dict):
            raise ValueError(f"joints[{k}] must be an object {{name, x, y, ground}}")
        joint_name = _name(joint.get("name"), f"joints[{k}].name")
        if joint_name in coordinates:
            raise ValueError(f"two joints are named {joint_name!r}")
        if joint_name == GROUND:
            raise ValueError(f"joints[{k}]: {GROUND!r} names the ground link; call the joint something else")
        coordinates[joint_name] = (_number(joint.get("x"), f"joint {joint_name}: x"),
                                   _number(joint.get("y"), f"joint {joint_name}: y"))
        ground = joint.get("ground", False)
        if not isinstance(ground, bool):
            raise ValueError(f"joint {joint_name}: ground is true or false")
        if ground:
            grounded.append(joint_name)
    links: dict[str, list[str]] = {}
    indexed: list[str | None] = []  # the name of link k, None where it is part of the ground
    listed = _list(data.get("links", []), "links")
    if len(listed) > MAX_LINKS:
        raise ValueError(f"the drawing has {len(listed)} links; the studio takes at most {MAX_LINKS}")
    for k, held in enumerate(listed):
        held = _list(held, f"links[{k}]")
        for joint in held:
            if _name(joint, f"links[{k}]: a joint") not in coordinates:
                raise ValueError(f"links[{k}] holds {joint!r}, which is no joint of the drawing")
        if len(set(held)) != len(held):
            raise ValueError(f"links[{k}] lists a joint twice: {', '.join(held)}")
        if len(held) < 2:
            raise ValueError(f"links[{k}] holds {len(held)} joint; a link joins at least two joints")
        if all(joint in grounded for joint in held):
            indexed.append(None)
            continue
        indexed.append(f"link{k + 1}")
        links[f"link{k + 1}"] = list(held)
    sliders: dict[str, Slider] = {}
    for k, entry in enumerate(_list(data.get("sliders", []) or [], "sliders")):
        if not isinstance(entry, dict) or set(entry) - {"joint", "guide", "angle", "turns"}:
            raise ValueError(f"sliders[{k}] must be an object {{joint, guide, angle}}")
        joint = _name(entry.get("joint"), f"sliders[{k}].joint")
        if joint not in coordinates:
            raise ValueError(f"sliders[{k}]: {joint!r} is no joint of the drawing")
        guide = entry.get("guide", GROUND)
        if guide != GROUND:
            if isinstance(guide, bool) or not isinstance(guide, int) or not 0 <= guide < len(indexed):
                raise ValueError(f"sliders[{k}]: guide is \"ground\" or the index of a link (0 to {len(indexed) - 1})")
            guide = indexed[guide] or GROUND
        turns = entry.get("turns", True)
        if not isinstance(turns, bool):
            raise ValueError(f"sliders[{k}]: turns is true or false")
        sliders[joint] = Slider(guide, _number(entry.get("angle", 0.0), f"slider {joint}: angle"), turns)
        if guide == GROUND and joint not in grounded:
            grounded.append(joint)
    notes = []
    if len(grounded) == 1:
        raise ValueError(f"only {grounded[0]} is on the ground: mark at least two joints as ground (two pivots, "
                         "or a pivot and a slider on the ground)")
    if grounded:
        links = {GROUND: grounded, **links}
    for joint, slider in sliders.items():
        if joint not in links.get(slider.guide, []):
            links.setdefault(slider.guide, []).append(joint)
    held = {j for joints in links.values() for j in joints}
    loose = [j for j in coordinates if j not in held]
    if loose:
        notes.append(f"joint{'s' if len(loose) > 1 else ''} {', '.join(loose)} on no link yet (left out)")
        coordinates = {j: xy for j, xy in coordinates.items() if j in held}
    drivers: list[str | tuple[str, str]] = []
    driver = data.get("driver")
    if driver is not None:
        if not isinstance(driver, dict) or set(driver) - {"joint", "link"}:
            raise ValueError("driver must be an object {joint, link}")
        joint = _name(driver.get("joint"), "driver.joint")
        if joint not in held:
            raise ValueError(f"the driver {joint!r} is on no link")
        link = driver.get("link")
        if link is None:
            drivers.append(joint)
        else:
            if isinstance(link, bool) or not isinstance(link, int) or not 0 <= link < len(indexed) \
                    or indexed[link] is None:
                raise ValueError(f"driver.link must be the index of a moving link (0 to {len(indexed) - 1})")
            drivers.append((joint, str(indexed[link])))
    return Description(name, links, coordinates, drivers, sliders, tuple(notes))


def _mobility(chain: Chain) -> dict[str, int]:
    found = chain.mobility()
    return {"dof": found.dof, "links": found.links, "revolute": found.revolute, "prismatic": found.prismatic}


def _gruebler(mobility: Mapping[str, int]) -> str:
    return (f"Gruebler gives mobility {mobility['dof']} ({mobility['links']} links with the ground, "
            f"{mobility['revolute']} revolute and {mobility['prismatic']} prismatic joints)")


def _chain(found: Description) -> Chain:
    if GROUND not in found.links:
        raise StructureError("no ground yet: mark the joints that sit on the ground (select a joint, press G)")
    if len(found.links) < 2:
        raise StructureError("no moving link yet: select two or more joints and join them into a link (press L)")
    return Chain(found.links, {j: s.guide for j, s in found.sliders.items()}, GROUND,
                 frozenset(j for j, s in found.sliders.items() if not s.turns))


def _check(found: Description) -> tuple[Chain, dict[str, int]]:
    """The chain of a drawing and its mobility; :class:`StructureError` saying what to do where it cannot move."""
    chain = _chain(found)
    mobility = _mobility(chain)
    if found.drivers:
        return chain, mobility
    stuck = chain.overconstrained([])
    if stuck is not None:
        raise StructureError(f"links {', '.join(stuck)} are over-constrained: they have mobility "
                             f"{chain.local_mobility(stuck)} among themselves, so they cannot move (a rigid part, "
                             f"or a loop that closes twice); {_gruebler(mobility)}", mobility)
    if mobility["dof"] <= 0:
        raise StructureError(f"the linkage cannot move: {_gruebler(mobility)}; remove a link or add one", mobility)
    raise StructureError(f"no driver yet: {_gruebler(mobility)}; mark {mobility['dof']} driven "
                         f"joint{'s' if mobility['dof'] > 1 else ''} (a pin on the ground: select it, press M)",
                         mobility)


def _loose(chain: Chain, mobility: Mapping[str, int], drivers: int) -> str:
    """Where an under-constrained drawing is free: the moving links on no loop (they swing on one joint)."""
    if mobility["dof"] <= drivers:
        return ""
    looped = chain.looped_links()
    loose = [link for link in chain.links if link != chain.ground and link not in looped]
    if not loose:
        return "; every link is on a loop: drive another joint, or add a link that closes a loop"
    named = [f"{link} ({'-'.join(chain.links[link])})" for link in loose]
    if len(loose) == 1:
        return f"; link {named[0]} is on no loop and swings freely: join it to another link"
    return f"; links {', '.join(named)} are on no loop and swing freely: join them to other links"


class _Cache:
    """The last few drawings' linkages and derivations, by their canonical text; one derivation at a time.

    SymPy is not made for threads: derivations are serialised by one lock (the server answers a page, not
    a crowd)."""

    def __init__(self, size: int = 16) -> None:
        self.size = size
        self.entries: OrderedDict[tuple[str, str], Any] = OrderedDict()
        self.lock = threading.RLock()

    def get(self, kind: str, key: str, make: Callable[[], Any]) -> Any:
        with self.lock:
            if (kind, key) in self.entries:
                self.entries.move_to_end((kind, key))
                return self.entries[(kind, key)]
            value = make()
            self.entries[(kind, key)] = value
            while len(self.entries) > self.size:
                self.entries.popitem(last=False)
            return value


CACHE = _Cache()


def drawn_linkage(found: Description) -> JointLinkage:
    """The linkage of a checked drawing (cached); :class:`StructureError` with the mobility where it is none."""
    def make() -> JointLinkage | StructureError:
        chain, mobility = _check(found)
        try:
            return from_joints(found.links, found.coordinates, driver=found.drivers, joints=found.sliders or None,
                               name=found.name)
        except ValueError as error:
            return StructureError(str(error) + _loose(chain, mobility, len(found.drivers)), mobility)
    made = CACHE.get("linkage", found.key, make)
    if isinstance(made, StructureError):
        raise made
    return made


def structure(data: Any) -> dict[str, Any]:
    """What the drawing is: mobility, loops, closed form or Newton, the solve plan, the drawn pose's values."""
    found = description(data)
    drawn = drawn_linkage(found)
    linkage = drawn.linkage
    from ..symbolic.plan import solve_plan
    plan = solve_plan(linkage)
    mobility = {"dof": drawn.mobility.dof, "links": drawn.mobility.links, "revolute": drawn.mobility.revolute,
                "prismatic": drawn.mobility.prismatic}
    method = "closed form" if linkage.has_closed_form else "Newton's method"
    message = (f"mobility {mobility['dof']}, driven at {', '.join(d if isinstance(d, str) else d[0] for d in found.drivers)}: "
               f"{len(linkage.loops)} loop{'s' if len(linkage.loops) != 1 else ''}, solved by {method}")
    return {"ok": True, "message": message, "notes": list(found.notes), "mobility": mobility,
            "name": linkage.name, "loops": [loop.name for loop in linkage.loops],
            "closed_form": linkage.has_closed_form, "plan": str(plan),
            "steps": [{"loops": list(s.loops), "case": s.case, "unknowns": list(s.unknowns), "branch": s.branch}
                      for s in plan.steps],
            "groups": [[loop, list(links)] for loop, links in drawn.structure],
            "inputs": [q.name for q in linkage.inputs], "unknowns": [q.name for q in linkage.unknowns],
            "parameters": drawn.parameters, "pose": drawn.pose, "branches": drawn.branches,
            "links": found.links, "sliders": {j: {"guide": s.guide, "angle": s.angle, "turns": s.turns}
                                              for j, s in drawn.sliders.items()}}


def _inner(latex: str) -> str:
    """A ``$\\displaystyle ...$`` display's maths, for KaTeX (which is given display mode itself)."""
    latex = latex.strip()
    if latex.startswith("$") and latex.endswith("$"):
        latex = latex.strip("$")
    return latex


def derivation(data: Any) -> dict[str, Any]:
    """The derivation of a drawing as LaTeX: ``equations`` (the linkage's own display: closure and closed forms,
    exactly :func:`from_joints`' LaTeX), ``closure``, ``velocities``, ``accelerations`` and ``forms`` (the seed
    papers' forms of the positions: complex-number, Freudenstein, tangent half-angle; closed form only), the
    loops and the plan."""
    found = description(data)
    drawn = drawn_linkage(found)

    def make() -> dict[str, Any]:
        from ..symbolic.plan import solve_plan
        from ..symbolic.typeset import closure_rows, display_latex
        linkage = drawn.linkage
        result = {"name": linkage.name, "loops": [loop.name for loop in linkage.loops],
                  "plan": str(solve_plan(linkage)), "closed_form": linkage.has_closed_form,
                  "equations": _inner(linkage._repr_latex_()),
                  "closure": _inner(display_latex(closure_rows(linkage.loops))),
                  "velocities": None, "accelerations": None}
        if linkage.has_closed_form:
            from ..symbolic.seed_forms import FORMS, SEED_FORM_TITLES, seed_form_rows
            result["velocities"] = _inner(display_latex(list(linkage.velocities.items())))
            result["accelerations"] = _inner(display_latex(list(linkage.accelerations.items())))
            # The seed papers' forms of the positions, shown on request (a closed <details> in the page).
            result["forms"] = [{"form": form, "title": SEED_FORM_TITLES[form],
                                "latex": _inner(display_latex(seed_form_rows(linkage, form)))}
                               for form in FORMS if form != "atan2"]
        return result
    return CACHE.get("derivation", found.key, make)


def solver(data: Any) -> dict[str, Any]:
    """The generated JavaScript solver of a drawing (:func:`symlink.codegen.javascript.javascript_geometry`):
    every joint's ``x_<name>``, ``y_<name>``; with the drawn values it starts from."""
    found = description(data)
    drawn = drawn_linkage(found)

    def make() -> dict[str, Any]:
        try:
            from ..codegen.javascript import javascript_geometry
        except ImportError:
            raise ValueError("this symlink has no JavaScript printer (symlink.codegen.javascript) yet: "
                             "the page cannot animate") from None
        source = javascript_geometry(drawn.linkage)
        return {"name": drawn.linkage.name, "source": source, "defaults": drawn.defaults,
                "inputs": [q.name for q in drawn.linkage.inputs], "branches": drawn.branches,
                "joints": list(drawn.coordinates)}
    return CACHE.get("solver", found.key, make)


#: Formats of ``/api/export``: the command line's exports, a linkage file (by its vectors or its joints),
#: pylinkage's JSON and the self-contained page.
EXPORT_FORMATS = ("latex", "numpy", "c", "octave", "javascript", "linkage", "joints", "pylinkage", "html")


def export_bytes(data: Any, fmt: str) -> dict[str, bytes]:
    """File name -> bytes of a drawing in ``fmt``: for the code formats exactly what ``symlink export FILE --to
    fmt`` writes for the drawing's linkage file (:func:`symlink.io.export.export_texts`)."""
    if fmt not in EXPORT_FORMATS:
        raise ValueError(f"no export format {str(fmt)[:40]!r}; choose one of {', '.join(EXPORT_FORMATS)}")
    found = description(data)
    drawn = drawn_linkage(found)
    stem = re.sub(r"\W", "_", drawn.linkage.name)
    if fmt == "linkage":
        from ..io.linkage_file import linkage_text
        return {f"{stem}.toml": linkage_text(drawn.linkage, drawn.values).encode()}
    if fmt == "joints":
        from ..io.joint_tables import joint_file_text
        return {f"{stem}.toml": joint_file_text(drawn).encode()}
    if fmt == "pylinkage":
        from ..io.pylinkage import write_pylinkage
        return {f"{stem}.json": (json.dumps(write_pylinkage(drawn), indent=2) + "\n").encode()}
    if fmt == "html":
        raise ValueError("the self-contained page is symlink.studio.page.standalone_page's (format html of the server)")
    from ..io.export import export_texts
    return {name: text.encode() for name, text in export_texts(drawn.linkage, fmt).items()}


# --- opening: a linkage from elsewhere, as a drawing ---------------------------------------------

def drawing_of(drawn: JointLinkage) -> dict[str, Any]:
    """The studio drawing of a linkage made from its joints (an atlas entry, a file of another tool)."""
    chain = drawn.chain
    moving = [link for link in chain.links if link != chain.ground]
    slider_joints = set(chain.sliders)
    joints = [{"name": j, "x": float(x), "y": float(y),
               "ground": j in chain.links[chain.ground] and not (j in slider_joints
                                                                 and chain.sliders[j] == chain.ground)}
              for j, (x, y) in drawn.coordinates.items()]
    links = [[j for j in chain.links[link] if not (j in slider_joints and chain.sliders[j] == link)]
             for link in moving]
    sliders = []
    for joint, slider in drawn.sliders.items():
        guide: str | int = GROUND if slider.guide == chain.ground else moving.index(slider.guide)
        sliders.append({"joint": joint, "guide": guide, "angle": slider.angle, "turns": slider.turns})
    if len(drawn.drivers) != 1:
        raise ValueError(f"{drawn.linkage.name} has {len(drawn.drivers)} drivers; the studio drives one joint")
    joint, link = drawn.drivers[0]
    driver: dict[str, Any] = {"joint": joint}
    if link is not None:
        driver["link"] = moving.index(link)
    return {"name": drawn.linkage.name, "joints": joints, "links": links, "driver": driver, "sliders": sliders}


def _linkage_drawing(linkage: Any, values: Mapping[str, float]) -> dict[str, Any]:
    """A linkage defined by its vectors (a catalog entry, a linkage file) drawn by its joints at its values.

    The bodies and joints are :func:`symlink.mechanism.bodies.mechanism`'s, placed by
    :class:`~symlink.numeric.poses.Geometry` at the values; a block sliding on a guide becomes its pin, a
    slider on the guide at the guide's angle there.  The driver is the ground pivot of the link the input turns.
    """
    from ..mechanism.bodies import PRISMATIC, REVOLUTE
    from ..numeric.poses import Geometry
    if len(linkage.inputs) != 1:
        raise ValueError(f"{linkage.name} has {len(linkage.inputs)} inputs; the studio drives one joint")
    geometry = Geometry(linkage)
    inputs = {q.name: float(values.get(q.name, 0.0)) for q in linkage.inputs}
    wanted = {k: v for k, v in values.items() if k in {s.name for s in linkage.parameters}
              or k in {b.name for b in linkage.branches}}
    poses = geometry.poses({**wanted, **inputs})
    if not bool(poses.assembled[0]):
        raise ValueError(f"{linkage.name} cannot be assembled at its default values")
    mech = geometry.mechanism
    position = {name: complex(place[0]) for name, place in poses.positions.items()}
    bodies = {b.name: list(b.joints) for b in mech.bodies}
    blocks: dict[str, tuple[str, float]] = {}   # block body -> (guide, slider angle)
    for joint in mech.joints:
        if joint.kind == PRISMATIC:
            guide, block = joint.bodies
            blocks[block] = (guide, float(poses.directions[joint.name][0]))
    joints: dict[str, dict[str, Any]] = {}
    links: dict[str, list[str]] = {b: [] for b in bodies if b not in blocks}
    sliders: list[dict[str, Any]] = []
    for joint in mech.joints:
        if joint.kind != REVOLUTE:
            continue
        place = position.get(joint.name)
        if place is None:
            raise ValueError(f"{linkage.name}: joint {joint.name} is not placed by the linkage's points")
        joints[joint.name] = {"name": joint.name, "x": place.real, "y": place.imag,
                              "ground": GROUND in joint.bodies}
        for holder in joint.bodies:
            if holder in blocks:
                guide, angle = blocks[holder]
                links.setdefault(guide, []).append(joint.name)
                sliders.append({"joint": joint.name, "guide": guide, "angle": angle})
                joints[joint.name]["ground"] = False  # it slides: on the ground link, not fixed to it
            else:
                links[holder].append(joint.name)
    for body in mech.bodies:
        for point in body.points:
            if point not in joints and point in position and body.name in links:
                joints[point] = {"name": point, "x": position[point].real, "y": position[point].imag,
                                 "ground": body.name == GROUND}
                links[body.name].append(point)
    for entry in joints.values():
        if not PLAIN_NAME.match(entry["name"]):
            raise ValueError(f"{linkage.name}: joint {entry['name']!r} has no plain name to draw it by")
    moving = [b for b in links if b != GROUND]
    driven = next((b.name for b in mech.bodies if b.name in moving and any(
        str(v.angle) == linkage.inputs[0].name for loop in linkage.loops for _, v in loop.vectors.terms
        if v.name in b.vectors)), None)
    pivot = next((j for j in links.get(driven, []) if joints.get(j, {}).get("ground")), None) if driven else None
    if pivot is None or driven is None:
        raise ValueError(f"{linkage.name}: its input {linkage.inputs[0].name} turns no link about a ground pivot; "
                         "the studio drives a crank")
    for slider in sliders:
        slider["guide"] = GROUND if slider["guide"] == GROUND else moving.index(slider["guide"])
    return {"name": linkage.name, "joints": list(joints.values()), "links": [links[b] for b in moving],
            "driver": {"joint": pivot, "link": moving.index(driven)}, "sliders": sliders}


#: The most bytes of text ``/api/open`` reads (a linkage file's limit too).
MAX_SOURCE = 1 << 20


def open_source(source: Any, kind: str = "auto") -> dict[str, Any]:
    """A drawing from ``source``: a catalog name, ``atlas:NAME`` (or an atlas name), a linkage file's TOML text,
    pylinkage JSON or a Pyslvs expression (``kind`` one of ``auto``, ``name``, ``linkage``, ``pylinkage``,
    ``pyslvs``); ``ValueError`` saying what it is not."""
    if not isinstance(source, str) or not source.strip():
        raise ValueError("give a catalog or atlas name, a linkage file's text, pylinkage JSON or a Pyslvs expression")
    if len(source) > MAX_SOURCE:
        raise ValueError(f"the text is {len(source)} characters; at most {MAX_SOURCE}")
    text = source.removeprefix("\ufeff").strip()  # a byte-order mark, as a file's reader drops it
    kinds = ("auto", "name", "linkage", "pylinkage", "pyslvs")
    if kind not in kinds:
        raise ValueError(f"kind is one of {', '.join(kinds)}")
    if kind == "auto":
        kind = ("pylinkage" if text.startswith("{") else "pyslvs" if text.startswith("M[")
                else "name" if re.fullmatch(r"[A-Za-z0-9:_-]+", text) else "linkage")
    if kind == "name":
        from ..mechanism.atlas import ATLAS, atlas_entry
        from ..mechanism.catalog import CATALOG
        from ..io.linkage_file import catalog_name, load_linkage
        name = text.removeprefix("atlas:")
        if text.startswith("atlas:") or (name in ATLAS and name not in CATALOG):
            return drawing_of(atlas_entry(name).joint_linkage())
        found = load_linkage(catalog_name(text))  # a catalog name, or a six-bar's in any spelling
        return _linkage_drawing(found.linkage, found.defaults)
    if kind == "pylinkage":
        from ..io.pylinkage import read_pylinkage
        return drawing_of(read_pylinkage(text).build())
    if kind == "pyslvs":
        from ..io.pyslvs import read_pyslvs
        return drawing_of(read_pyslvs(text).build())
    return _file_drawing(text)


def _file_drawing(text: str) -> dict[str, Any]:
    """A linkage file's text as a drawing: by its ``[links]`` and ``[joints]`` tables, else by its vectors."""
    from ..io.linkage_file import linkage_from_text
    from ..common.numbers import toml_data
    try:
        data = toml_data(text)
    except ValueError as error:
        raise ValueError(f"not a name, pylinkage JSON, a Pyslvs expression or a linkage file's TOML: {error}") from None
    found = linkage_from_text(text)  # the file's own checks, with line numbers
    if "links" in data or "joints" in data:  # a linkage by its joints: read again, keeping its joints
        from ..io.joint_tables import linkage_from_tables
        from ..io.linkage_file import _expression
        return drawing_of(linkage_from_tables(data, lambda value: float(_expression(value, {}, units=True))))
    return _linkage_drawing(found.linkage, found.defaults)

