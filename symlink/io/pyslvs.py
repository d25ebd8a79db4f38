"""Pyslvs mechanism expressions, read and written: ``M[J[R, color[Green], P[0, 0], L[ground, L1]], ...]``.

Pyslvs (and its interface Pyslvs-UI) describes a mechanism by its joints, one
``J[...]`` each, in the grammar of ``pyslvs/expression_parser.py``::

    mechanism := "M[" [joint ("," joint)* [","]] "]"
    joint     := "J[" type ["," "A[" number "]"] ["," color] "," "P[" number "," number "]" ","   (A: P and RP)
                 "L[" [name ("," name)* [","]] "]" "]"
    type      := "R" | "P" | "RP"
    color     := "color[" (colour name | "(" int "," int "," int ")") "]"

``#`` starts a comment to the end of the line, ``#[`` one that ends with the first ``#]`` after it
(Pyslvs's grammar).  The links named in ``L[...]``
hold the joint; ``ground`` is the frame.  An ``RP`` joint (a pin in a slot)
slides on the first of its links along a line at angle ``A`` (degrees,
drawn pose) and turns in the others: a :class:`~symlink.mechanism.joints.Slider`.  A
``P`` joint slides the same way but its other link (one) does not turn on
the guide: ``Slider(..., turns=False)``.  Joints are named ``A``, ``B``, ... in their order; the
driver, which an expression does not carry, is given as Pyslvs's input
pair ``(base, drive)``: joint indices, the base a pin on the ground and
the drive a joint on the driven link.

The example below is the seed four-bar (20, 66, 56, 80) at a crank angle of
50 degrees, with a coupler point.

This module has its own tokenizer and parser (no ``eval``, no Lark): any other
text is one ``ValueError`` naming the column and what was expected.

>>> description = read_pyslvs(
...     "M[J[R, color[Green], P[0.0, 0.0], L[ground, L1]], J[R, color[Green], P[12.86, 15.32], L[L1, L2]],"
...     " J[R, color[Green], P[66.15, 54.26], L[L2, L3]], J[R, color[Green], P[29.5, 59.79], L[L2]],"
...     " J[R, color[Green], P[80.0, 0.0], L[ground, L3]]]", inputs=[(0, 1)])
>>> description.links["L2"], description.drivers
(['B', 'C', 'D'], (('A', 'L1'),))
>>> print(write_pyslvs(description.build())[:46])
M[J[R, color[Green], P[0, 0], L[ground, L1]], 
"""
from __future__ import annotations

import math
import re
from typing import Any, Iterable, Mapping, Sequence

from ..common.files import excerpt
from ..common.numbers import number_from_text
from ..mechanism.joints import JointDescription, JointLinkage, Slider
from ..mechanism.topology import GROUND
from .linkage_file import MAX_LINKAGE_BYTES
from .pylinkage import MAX_COORDINATE

__all__ = ["read_pyslvs", "read_pyslvs_project", "write_pyslvs", "pyslvs_inputs", "pyslvs_joint_name"]

_TOKEN = re.compile(r"""
    (?P<space>\s+|\#(?!\[)[^\n]*)
  | (?P<number>[+-]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?)
  | (?P<name>[A-Za-z_][A-Za-z0-9_-]*)
  | (?P<punct>[\[\],()])
""", re.VERBOSE)

#: Pyslvs's colour names (``pyslvs/expression_parser.py``), in lower case.
COLOURS = frozenset("""red green blue cyan magenta brick-red yellow gray orange pink black white dark-red dark-green
dark-blue dark-cyan dark-magenta dark-yellow dark-gray dark-orange dark-pink""".split())


def pyslvs_joint_name(index: int) -> str:
    """The joint name of the joint at ``index`` of an expression: A ... Z, then J26, J27, ...

    >>> pyslvs_joint_name(0), pyslvs_joint_name(27)
    ('A', 'J27')
    """
    return chr(ord("A") + index) if index < 26 else f"J{index}"


class _Parser:
    def __init__(self, text: str) -> None:
        if not isinstance(text, str):
            raise ValueError(f"a Pyslvs expression is text, not {type(text).__name__}")
        if len(text) > MAX_LINKAGE_BYTES:
            raise ValueError(f"a Pyslvs expression of {len(text):,} characters is more than a mechanism needs "
                             f"(at most {MAX_LINKAGE_BYTES:,})")
        self.tokens: list[tuple[str, str, int]] = []
        position = 1 if text.startswith("\ufeff") else 0  # a byte-order mark, as a file's reader drops it
        while position < len(text):
            if text.startswith("#[", position):  # a block comment ends at its first #], never later
                end = text.find("#]", position + 2)
                if end < 0:
                    raise ValueError(f"Pyslvs expression, column {position + 1}: the comment '#[' opened here never "
                                     "ends (no '#]' after it)")
                position = end + 2
                continue
            match = _TOKEN.match(text, position)
            if match is None:
                raise ValueError(f"Pyslvs expression, column {position + 1}: unexpected {excerpt(text[position])}")
            kind = match.lastgroup
            assert kind is not None
            if kind != "space":
                self.tokens.append((kind, match.group(), position + 1))
            position = match.end()
        self.index = 0
        self.end = len(text) + 1

    def _where(self) -> str:
        column = self.tokens[self.index][2] if self.index < len(self.tokens) else self.end
        return f"Pyslvs expression, column {column}"

    def _found(self) -> str:
        return excerpt(self.tokens[self.index][1]) if self.index < len(self.tokens) else "the end"

    def peek(self) -> str | None:
        return self.tokens[self.index][1] if self.index < len(self.tokens) else None

    def expect(self, text: str) -> None:
        if self.peek() != text:
            raise ValueError(f"{self._where()}: expected {text!r}, found {self._found()}")
        self.index += 1

    def keyword(self, *words: str) -> str:
        found = self.peek()
        if found is None or found.upper() not in {w.upper() for w in words}:
            raise ValueError(f"{self._where()}: expected {' or '.join(map(repr, words))}, found {self._found()}")
        self.index += 1
        return found

    def number(self) -> float:
        if self.index >= len(self.tokens) or self.tokens[self.index][0] != "number":
            raise ValueError(f"{self._where()}: expected a number, found {self._found()}")
        try:  # any digits: a float, range-checked, never int()
            value = number_from_text(self.tokens[self.index][1])
        except ValueError as error:
            raise ValueError(f"{self._where()}: the number is out of range: {error}") from None
        if not math.isfinite(value) or abs(value) > MAX_COORDINATE:
            raise ValueError(f"{self._where()}: {self._found()} is out of range (at most {MAX_COORDINATE:g})")
        self.index += 1
        return value

    def name(self) -> str:
        if self.index >= len(self.tokens) or self.tokens[self.index][0] != "name":
            raise ValueError(f"{self._where()}: expected a link name, found {self._found()}")
        found = self.tokens[self.index][1]
        self.index += 1
        return found

    def mechanism(self) -> list[tuple[str, float | None, tuple[float, float], list[str]]]:
        self.keyword("M")
        self.expect("[")
        joints = []
        while self.peek() != "]":
            joints.append(self.joint())
            if self.peek() == ",":
                self.index += 1
            elif self.peek() != "]":
                raise ValueError(f"{self._where()}: expected ',' or ']' after a joint, found {self._found()}")
        self.expect("]")
        if self.index != len(self.tokens):
            raise ValueError(f"{self._where()}: expected the end after the mechanism, found {self._found()}")
        return joints

    def joint(self) -> tuple[str, float | None, tuple[float, float], list[str]]:
        self.keyword("J")
        self.expect("[")
        kind = self.keyword("R", "P", "RP").upper()
        self.expect(",")
        angle = None
        if kind != "R" or (self.peek() or "").upper() == "A":  # an angle is optional on an R joint (unused)
            self.keyword("A")
            self.expect("[")
            angle = self.number()
            self.expect("]")
            self.expect(",")
        if self.peek() is not None and self.peek().lower() == "color":  # type: ignore[union-attr]
            self.index += 1
            self.expect("[")
            if self.peek() == "(":
                self.index += 1
                for k in range(3):
                    self.number()
                    self.expect("," if k < 2 else ")")
            else:
                colour = self.name()
                if colour.lower() not in COLOURS:
                    self.index -= 1
                    raise ValueError(f"{self._where()}: {colour!r} is not a Pyslvs colour")
            self.expect("]")
            self.expect(",")
        self.keyword("P")
        self.expect("[")
        x = self.number()
        self.expect(",")
        y = self.number()
        self.expect("]")
        self.expect(",")
        self.keyword("L")
        self.expect("[")
        links: list[str] = []
        while self.peek() != "]":
            links.append(self.name())
            if self.peek() == ",":
                self.index += 1
            elif self.peek() != "]":
                raise ValueError(f"{self._where()}: expected ',' or ']' in a link list, found {self._found()}")
        self.expect("]")
        self.expect("]")
        return kind, angle, (x, y), links


def read_pyslvs(text: str, inputs: Iterable[Sequence[int]] = ((0, 1),), name: str = "pyslvs") -> JointDescription:
    """The joints, links and drawn pose of a Pyslvs expression, driven at Pyslvs's input pairs ``inputs``.

    ``ValueError`` for text outside the grammar, a ``P`` joint, a link name that is
    not a symlink name, or an input pair whose base is not a pin on the ground.

    Parameters
    ----------
    text : str
        A Pyslvs expression, ``M[J[R, P[0, 0], L[ground, L1]], ...]``.
    inputs : iterable of (int, int), optional
        Pyslvs's input pairs (base joint, driven joint), default ``((0, 1),)``.
    name : str, optional
        The linkage's name (default ``"pyslvs"``).

    Returns
    -------
    JointDescription
        Its links, joints, drivers and drawn pose; ``.build()`` makes the linkage.

    Raises
    ------
    ValueError
        For text outside the grammar, a ``P`` joint, a link name that is not a symlink name, or an input
        pair whose base is not a pin on the ground.

    Examples
    --------
    >>> import symlink
    >>> described = symlink.read_pyslvs("M[J[R, P[0, 0], L[ground, L1]], J[R, P[0, 1], L[L1, L2]],"
    ...                                 " J[R, P[3, 2], L[L2, L3]], J[R, P[3, 0], L[ground, L3]]]")
    >>> described.drivers, described.coordinates["C"], described.build().mobility.dof
    ((('A', 'L1'),), (3.0, 2.0), 1)
    """
    joints = _Parser(text).mechanism()
    if not joints:
        raise ValueError("the Pyslvs expression has no joints")
    links: dict[str, list[str]] = {}
    coordinates: dict[str, tuple[float, float]] = {}
    kinds: dict[str, object] = {}
    for index, (kind, angle, point, held) in enumerate(joints):
        joint = pyslvs_joint_name(index)
        if not held:
            raise ValueError(f"Pyslvs joint {index} ({joint}) is on no link")
        if len(set(held)) != len(held):
            raise ValueError(f"Pyslvs joint {index} ({joint}) lists a link twice: {', '.join(held)}")
        for link in held:
            if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", link):
                raise ValueError(f"Pyslvs joint {index}: link name {link!r} is not a symlink name "
                                 "(ASCII letters, digits, _)")
            links.setdefault(link, []).append(joint)
        coordinates[joint] = point
        if kind in ("RP", "P"):
            assert angle is not None
            if len(held) < 2:
                raise ValueError(f"Pyslvs joint {index} ({joint}) is a {kind} joint on one link only")
            kinds[joint] = Slider(held[0], math.radians(angle), turns=kind == "RP")
    drivers: list[str | tuple[str, str]] = []
    for pair in inputs:
        if len(pair) != 2 or not all(isinstance(k, int) and 0 <= k < len(joints) for k in pair):
            raise ValueError(f"input pair {tuple(pair)!r}: two joint indices from 0 to {len(joints) - 1}")
        base, drive = (pyslvs_joint_name(k) for k in pair)
        if GROUND not in joints[pair[0]][3]:
            raise ValueError(f"input pair {tuple(pair)!r}: its base joint {base} is not on the ground")
        shared = [link for link in joints[pair[0]][3] if link != GROUND and link in joints[pair[1]][3]]
        if not shared and base != drive:
            raise ValueError(f"input pair {tuple(pair)!r}: joints {base} and {drive} share no moving link")
        drivers.append(base if base == drive else (base, shared[0]))
    names = {str(k): pyslvs_joint_name(k) for k in range(len(joints))}
    return JointDescription(links, coordinates, tuple(drivers), kinds or None, GROUND, name, names)


def _number_text(value: float) -> str:
    """A number as Pyslvs's grammar reads it: an integer as an integer, else repr (round-trips exactly)."""
    if value == int(value) and abs(value) < 1e15:
        return str(int(value))
    return repr(float(value))


def write_pyslvs(drawn: JointLinkage) -> str:
    """The Pyslvs expression of a linkage from its joints, at its drawn pose (angles of RP joints in degrees).

    Pyslvs names no joints: they are written in the order of the drawn coordinates
    (a Pyslvs expression read here keeps its order, and so its input pairs).

    Parameters
    ----------
    drawn : JointLinkage
        A linkage from its joints (:func:`from_joints`).

    Returns
    -------
    str
        The Pyslvs expression.

    Examples
    --------
    >>> import symlink
    >>> drawn = symlink.from_joints({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C"],
    ...                              "rocker": ["D", "C"]},
    ...                             {"A": (0, 0), "B": (0, 1), "C": (3, 2), "D": (3, 0)}, driver="A")
    >>> symlink.write_pyslvs(drawn)
    'M[J[R, color[Green], P[0, 0], L[ground, crank]], J[R, color[Green], P[0, 1], L[crank, coupler]], J[R, color[Green], P[3, 2], L[coupler, rocker]], J[R, color[Green], P[3, 0], L[ground, rocker]]]'
    """
    chain = drawn.chain
    points = drawn.coordinates
    parts = []
    for joint in points:
        held = list(chain.links_of(joint))
        x, y = points[joint]
        position = f"P[{_number_text(x)}, {_number_text(y)}]"
        if joint in chain.sliders:
            guide = chain.sliders[joint]
            held.remove(guide)
            held.insert(0, guide)
            angle = math.degrees(drawn.slider_angles[joint])
            kind = "RP" if drawn.sliders[joint].turns else "P"
            parts.append(f"J[{kind}, A[{_number_text(angle)}], color[Green], {position}, L[{', '.join(held)}]]")
        else:
            parts.append(f"J[R, color[Green], {position}, L[{', '.join(held)}]]")
    return "M[" + ", ".join(parts) + "]"


def pyslvs_inputs(drawn: JointLinkage) -> list[tuple[int, int]]:
    """Pyslvs's input pairs of a linkage from its joints, by the joint order of :func:`write_pyslvs`:
    (the driven pin on the ground, another joint of the driven link), or (a slider, itself).

    >>> crank_rocker = ("M[J[R, P[0, 0], L[ground, L1]], J[R, P[0, 20], L[L1, L2]], J[R, P[60, 50], L[L2, L3]],"
    ...                 " J[R, P[80, 0], L[ground, L3]]]")
    >>> pyslvs_inputs(read_pyslvs(crank_rocker, [(0, 1)]).build())
    [(0, 1)]
    """
    order = {joint: k for k, joint in enumerate(drawn.coordinates)}
    pairs = []
    for joint, link in drawn.drivers:
        if joint in drawn.chain.sliders:
            pairs.append((order[joint], order[joint]))
            continue
        driven = link or next(m for m in drawn.chain.links_of(joint) if m != drawn.chain.ground)
        other = next(j for j in drawn.chain.links[driven] if j != joint)
        pairs.append((order[joint], order[other]))
    return pairs


def read_pyslvs_project(data: Mapping[str, Any] | str, name: str = "pyslvs") -> JointDescription:
    """A Pyslvs-UI project (its YAML text, or the mapping it loads to): the ``mechanism`` expression driven at
    the project's ``input`` pairs.  The other keys (paths, storage, synthesis settings) are left out.

    YAML text is read with PyYAML's ``safe_load`` (data only, no objects), which must be installed.

    Parameters
    ----------
    data : mapping or str
        A Pyslvs-UI project: its YAML text (needs PyYAML) or the mapping it loads to.
    name : str, optional
        The linkage's name (default ``"pyslvs"``).

    Returns
    -------
    JointDescription
        The ``mechanism`` expression's joints, driven at the project's ``input`` pairs.

    Examples
    --------
    >>> import symlink
    >>> symlink.read_pyslvs_project({"mechanism": "M[J[R, P[0, 0], L[ground, L1]], J[R, P[0, 1], L[L1, L2]],"
    ...                              " J[R, P[3, 2], L[L2, L3]], J[R, P[3, 0], L[ground, L3]]]",
    ...                              "input": [[0, 1]]}).drivers
    (('A', 'L1'),)
    """
    if isinstance(data, str):
        try:
            import yaml  # type: ignore[import-untyped]
        except ImportError:
            raise ValueError("reading a Pyslvs-UI project's YAML text needs PyYAML; or give the loaded mapping") from None
        try:
            data = yaml.safe_load(data)
        except yaml.YAMLError as error:
            raise ValueError(f"Pyslvs-UI project: not YAML ({' '.join(str(error).split())})") from None
    if not isinstance(data, Mapping):
        raise ValueError("a Pyslvs-UI project is a mapping with 'mechanism' and 'input'")
    expression = data.get("mechanism")
    if not isinstance(expression, str):
        raise ValueError(f"Pyslvs-UI project: 'mechanism' must be an expression, got {expression!r}")
    pairs = data.get("input", [])
    if not isinstance(pairs, list) or not pairs:
        raise ValueError(f"Pyslvs-UI project: 'input' must list the input pairs [base, drive], got {pairs!r}")
    for pair in pairs:
        if not isinstance(pair, (list, tuple)) or len(pair) != 2 or not all(
                isinstance(k, int) and not isinstance(k, bool) for k in pair):
            raise ValueError(f"Pyslvs-UI project: an input pair is [base, drive] (joint indices), got {pair!r}")
    return read_pyslvs(expression, [tuple(p) for p in pairs], name)
