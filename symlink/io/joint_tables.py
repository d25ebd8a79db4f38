"""The ``[links]`` and ``[joints]`` tables of a linkage file: a linkage by its joints, without a loop written.

A linkage file may describe its linkage by its joints instead of its vectors
and loops (:func:`symlink.mechanism.joints.from_joints` derives those)::

    name = "hoeken"
    driver = "A"                 # the driven joint, or a list of them (one a degree of freedom)

    [links]                      # link name = the joints it holds; the first two give its angle
    ground = ["A", "D"]
    crank = ["A", "B"]
    coupler = ["B", "C", "P"]    # P, held by one link only, is a point of it (a coupler point)
    rocker = ["D", "C"]

    [joints]                     # joint name = [x, y] in one assembled pose (a pin)
    A = [0, 0]
    B = [-0.5, 0.866]
    C = [1.72, 2.20]
    D = [2, 0]
    P = [3.95, 3.53]
    # a slider (pin in a slot) on a guide link, its line at an angle through the joint:
    # S = {at = [4, 0.5], slider = "ground", angle = "10 deg"}
    # a block that slides on its guide without turning on it (the one other link that holds it):
    # T = {at = [1, 2], block = "rocker", angle = 0}

The angle is a number (radians) or a constant of the linkage file grammar
(``"10 deg"``, ``"pi/2"``), read by the caller's grammar (``angle``).  The
linkage's defaults are the dimensions of the drawing and the inputs at the
drawn pose; every branch sign is +1 there (see :mod:`symlink.mechanism.joints`).  Problems are :class:`TableProblem`
naming the table and key, which :mod:`symlink.io.linkage_file` turns into its
``file:line`` errors.

>>> drawn = linkage_from_tables({"name": "fourbar", "driver": "A",
...     "links": {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
...     "joints": {"A": [0, 0], "B": [0, 20], "C": [60, 50], "D": [80, 0]}}, angle=float)
>>> drawn.linkage.unknowns, drawn.defaults["branch"]
((theta_BC, theta_DC), 1.0)
"""
from __future__ import annotations

from typing import Any, Callable, Mapping

from ..common.files import excerpt
from ..common.numbers import finite_float
from ..mechanism.joints import JointLinkage, Slider, from_joints

__all__ = ["TableProblem", "linkage_from_tables", "joint_file_text", "TOP_KEYS", "TABLES"]

TOP_KEYS = ("name", "driver")
TABLES = ("links", "joints")


class TableProblem(ValueError):
    """A problem at ``table``.``key`` ("" for the top level or the whole table)."""

    def __init__(self, table: str, key: str, message: str) -> None:
        super().__init__(message)
        self.table, self.key = table, key


def _number(value: Any, table: str, key: str, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TableProblem(table, key, f"{table}.{key}: {what} must be a number, got {excerpt(value)}")
    found = finite_float(value)
    if found is None:  # nan, inf, or an integer too large for a float: never an OverflowError
        shown = "an integer too large for a float" if isinstance(value, int) else excerpt(value)
        raise TableProblem(table, key, f"{table}.{key}: {what} must be a finite number, got {shown}")
    return found


def _point(value: Any, key: str) -> tuple[float, float]:
    if not isinstance(value, list) or len(value) != 2:
        raise TableProblem("joints", key, f"joints.{key}: a position is [x, y], got {value!r}")
    return _number(value[0], "joints", key, "x"), _number(value[1], "joints", key, "y")


def linkage_from_tables(data: Mapping[str, Any], angle: Callable[[Any], float]) -> JointLinkage:
    """The linkage of a file's ``name``, ``driver``, ``[links]`` and ``[joints]`` (``angle`` reads a slider's angle)."""
    for key in data:
        if key not in TOP_KEYS + TABLES:
            raise TableProblem("", key, f"unknown key {key!r} (a linkage file by its joints has "
                                        f"{', '.join(TOP_KEYS + TABLES)})")
    for key in ("name", "driver") + TABLES:
        if key not in data:
            raise TableProblem("", "", f"missing {key} (a linkage file by its joints has name, driver, [links] "
                                       "and [joints])")
    name, driver = data["name"], data["driver"]
    if not isinstance(name, str) or not name.strip():
        raise TableProblem("", "name", f"name must be a non-empty string, got {name!r}")
    if not (isinstance(driver, str) or (isinstance(driver, list) and driver
                                        and all(isinstance(d, str) for d in driver))):
        raise TableProblem("", "driver", f"driver must be a joint name or a list of them, got {excerpt(driver)}")
    twice = next((d for k, d in enumerate(driver) if d in driver[:k]), None) if isinstance(driver, list) else None
    if twice is not None:  # one joint driven twice: a request that repeats itself, not a second input
        raise TableProblem("", "driver", f"driver lists {excerpt(twice)} more than once; list each driven joint once")
    links = data["links"]
    if not isinstance(links, dict) or not links:
        raise TableProblem("", "links", f"links must be a table of link = [joints], got {links!r}")
    for key, joints in links.items():
        if not isinstance(joints, list) or not all(isinstance(j, str) for j in joints):
            raise TableProblem("links", key, f"links.{key} must be a list of joint names, got {joints!r}")
    table = data["joints"]
    if not isinstance(table, dict) or not table:
        raise TableProblem("", "joints", f"joints must be a table of joint = [x, y], got {table!r}")
    coordinates: dict[str, tuple[float, float]] = {}
    kinds: dict[str, object] = {}
    for key, value in table.items():
        if isinstance(value, dict):
            kind = "block" if "block" in value else "slider"
            if set(value) != {"at", kind, "angle"}:
                raise TableProblem("joints", key, f"joints.{key}: a slider is {{at = [x, y], slider = \"guide link\", "
                                                  f"angle = \"10 deg\"}} (block = for a block that does not turn on "
                                                  f"its guide), got {value!r}")
            coordinates[key] = _point(value["at"], key)
            if not isinstance(value[kind], str):
                raise TableProblem("joints", key, f"joints.{key}: {kind} names its guide link, got {value[kind]!r}")
            try:
                kinds[key] = Slider(value[kind], angle(value["angle"]), turns=kind == "slider")
            except ValueError as error:
                raise TableProblem("joints", key, f"joints.{key}: angle {error}") from None
        else:
            coordinates[key] = _point(value, key)
    try:
        return from_joints(links, coordinates, driver=driver, joints=kinds or None, name=name)
    except ValueError as error:
        where = _where(str(error), links, table)
        raise TableProblem(*where, f"{where[0] + '.' + where[1] + ': ' if where[1] else ''}{error}") from None


def _where(message: str, links: Mapping[str, Any], joints: Mapping[str, Any]) -> tuple[str, str]:
    """The table and key a message of :func:`from_joints` is about: the first link or joint it quotes."""
    if message.startswith("coordinates:"):
        return "joints", ""
    for key in links:
        if f"link {key!r}" in message or f"links {key}" in message:
            return "links", key
    for key in joints:
        if f"joint {key!r}" in message or f"joints {key!r}" in message or f"{key!r}" in message:
            return "joints", key
    return "links", ""


def _toml_number(value: float) -> str:
    text = repr(float(value))
    return text if text not in ("inf", "-inf", "nan") else "nan"


def joint_file_text(drawn: JointLinkage) -> str:
    """The text of a linkage file by joints (``[links]``, ``[joints]``) for a linkage from its joints.

    Whatever described it (Python, a Pyslvs expression, a pylinkage mechanism), the
    file reads back to the same linkage (:func:`symlink.io.linkage_file.linkage_from_text`).

    >>> drawn = from_joints({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"], "rocker": ["D", "C"]},
    ...                     {"A": (0, 0), "B": (0, 20), "C": (60, 50), "D": (80, 0)}, driver="A", name="fourbar")
    >>> print(joint_file_text(drawn).splitlines()[2])
    driver = ["A"]
    """
    drivers = []
    for joint, link in drawn.drivers:
        if link is not None and sum(1 for other in drawn.chain.links_of(joint) if other != drawn.chain.ground) > 1:
            raise ValueError(f"driver ({joint!r}, {link!r}): a linkage file names driven joints only, and {joint!r} "
                             "holds several moving links")
        drivers.append(joint)
    lines = ["# A symlink linkage file by its joints (see symlink.io.joint_tables).",
             f"name = {_quoted(drawn.linkage.name)}",
             f"driver = [{', '.join(_quoted(d) for d in drivers)}]", "", "[links]"]
    for link, joints in drawn.chain.links.items():
        lines.append(f"{link} = [{', '.join(_quoted(j) for j in joints)}]")
    lines += ["", "[joints]"]
    for joint, (x, y) in drawn.coordinates.items():
        at = f"[{_toml_number(x)}, {_toml_number(y)}]"
        slider = drawn.sliders.get(joint)
        if slider is None:
            lines.append(f"{joint} = {at}")
        else:
            kind = "slider" if slider.turns else "block"
            lines.append(f"{joint} = {{at = {at}, {kind} = {_quoted(slider.guide)}, "
                         f"angle = {_toml_number(slider.angle)}}}")
    return "\n".join(lines) + "\n"


def _quoted(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'
