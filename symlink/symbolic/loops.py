"""A vector loop: its closure equations and the case its two unknowns make.

A loop is a signed sum of vectors that must vanish.  With two unknowns the
loop falls into one of the four cases of the position-study paper
(the four cases of the MATLAB GUI paper on vector loops):

==== ==================================================================
case unknowns
==== ==================================================================
1    two lengths
2a   the length and the angle of one vector
2b   the length of one vector and the angle of another
2c   the length of one vector and an angle that turns it and others (an offset guide)
3    two angles
==== ==================================================================

An unknown owns one vector of the loop: it is that vector's length, or its
angle up to a known offset (a guide at a fixed angle to a rocker is
``Vector(r, phi + pi/2)``).  An unknown angle may also turn several vectors
together (a slider and its offset on one rocker): those with known lengths add
up to one vector of known length at a constant angle to the others, and the
loop falls into case 2b or 3 with that vector, or, when the unknown length is
on the same body, into case 2c.  Anything else (an unknown inside a sine, a
length that turns with its own unknown angle) has no closed form here and
raises ``ValueError``.

>>> from symlink.symbolic.vectors import Vector, coordinates, lengths
>>> theta, beta, phi = coordinates("theta beta phi")
>>> a, b, c, d = lengths("a b c d")
>>> closure = Loop(Vector(d, 0) + Vector(c, phi) - Vector(b, beta) - Vector(a, theta))
>>> closure.case([beta, phi]).name
'3'
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import sympy as sp

from ..common.names import identifier
from ..common.notation import math_text
from .vectors import Vector, VectorSum

__all__ = ["Loop", "Unknown", "LoopCase", "CASE_NAMES"]

CASE_NAMES = {
    "1": "two lengths",
    "2a": "length and angle of one vector",
    "2b": "length and angle of different vectors",
    "2c": "length of a vector and an angle that turns it with others",
    "3": "two angles",
}


@dataclass(frozen=True)
class Unknown:
    """Where an unknown sits in a loop: which term, and whether it is the length or the angle."""

    symbol: sp.Symbol
    sign: int
    vector: Vector
    part: str  # "length" or "angle"
    offset: sp.Expr  # the vector's length or angle minus the unknown


@dataclass(frozen=True)
class LoopCase:
    """A loop with two unknowns: its case name, the two unknowns in order, and the known rest."""

    name: str
    first: Unknown
    second: Unknown
    known: tuple[tuple[int, Vector], ...]
    #: Case 2c: the known-length vectors that the unknown angle turns with the unknown length.
    turning: tuple[tuple[int, Vector], ...] = ()

    @property
    def branches(self) -> int:
        """How many assemblies the case has (1 or 2)."""
        return 2 if self.name in ("2b", "2c", "3") else 1


class Loop:
    """A closed vector loop ``sum of signed vectors = 0``.

    Parameters
    ----------
    vectors : VectorSum or Vector
        The signed sum of vectors that closes the loop; at least two vectors.
    name : str, optional
        An identifier for plans and errors (default ``"loop"``).

    Raises
    ------
    ValueError
        A name that is not an identifier, fewer than two vectors, or a loop that cannot close for any values.

    Examples
    --------
    >>> import symlink
    >>> theta, beta, phi = symlink.coordinates("theta beta phi")
    >>> a, b, c, d = symlink.lengths("a b c d")
    >>> loop = symlink.Loop(symlink.Vector(d, 0) + symlink.Vector(c, phi) - symlink.Vector(b, beta)
    ...                     - symlink.Vector(a, theta), "ABCD")
    >>> loop.case([beta, phi]).name  # two angles unknown: the four-bar's case
    '3'
    >>> loop.equations()[1]
    -a*sin(theta) - b*sin(beta) + c*sin(phi)
    """

    def __init__(self, vectors: VectorSum | Vector, name: str = "loop") -> None:
        self.name = identifier(name, "loop name")
        if not isinstance(vectors, (Vector, VectorSum)):
            raise ValueError(f"loop {name!r} is a sum of Vector objects, not {vectors!r}")
        self.vectors = vectors.as_sum()
        if len(self.vectors.terms) < 2:
            raise ValueError(f"loop {name!r} has one vector, which closes only at zero length: "
                             "a loop needs at least two vectors (did you forget the ground vector?)")
        why = self._never_closes()
        if why:
            raise ValueError(f"loop {name!r} cannot close for any values: {why} (did you forget the ground vector?)")

    def _never_closes(self) -> str | None:
        """Why the closure has no solution for any values, where that is certain; else None.

        A sound, cheap test: when every vector turns with one common angle (or none turns) and
        every length is known positive, the closure is ``e^{i t} sum_k s_k r_k e^{i c_k}`` with
        constant directions ``s_k e^{i c_k}``.  If those directions lie in an open half-plane
        (the widest gap between them exceeds a half turn) no positive lengths sum them to zero.
        """
        reference = self.terms[0][1].angle
        directions = []
        for sign, vector in self.terms:
            offset = sp.expand(vector.angle - reference)
            if offset.free_symbols or vector.length.is_positive is not True:
                return None
            directions.append(float(offset) + (0.0 if sign > 0 else math.pi))
        turns = sorted(d % (2 * math.pi) for d in directions)
        gaps = [b - a for a, b in zip(turns, turns[1:])] + [turns[0] + 2 * math.pi - turns[-1]]
        if max(gaps) > math.pi + 1e-9:
            return ("its vectors turn together and all point into one half-plane, "
                    "so no positive lengths make them add up to zero")
        return None

    @property
    def terms(self) -> tuple[tuple[int, Vector], ...]:
        return self.vectors.terms

    def equations(self) -> tuple[sp.Expr, sp.Expr]:
        """The closure's x and y components, each of which must be zero."""
        return self.vectors.x, self.vectors.y

    def symbols(self) -> set[sp.Symbol]:
        found: set[sp.Symbol] = set()
        for _, vector in self.terms:
            found |= vector.length.free_symbols | vector.angle.free_symbols
        return found

    def unknowns_among(self, candidates: Sequence[sp.Symbol]) -> list[sp.Symbol]:
        """The candidates that appear in this loop, in the candidates' order."""
        present = self.symbols()
        return [u for u in candidates if u in present]

    def locate(self, unknown: sp.Symbol) -> Unknown:
        """The one term that owns ``unknown``; ``ValueError`` if it is not a plain length or angle there."""
        owners = [(sign, v) for sign, v in self.terms
                  if unknown in v.length.free_symbols | v.angle.free_symbols]
        if len(owners) != 1:
            raise ValueError(
                f"{unknown} appears in {len(owners)} vectors of loop {self.name!r}; "
                "a closed form needs it in exactly one")
        sign, vector = owners[0]
        for part in ("length", "angle"):
            expr = getattr(vector, part)
            if unknown in expr.free_symbols:
                offset = sp.expand(expr - unknown)
                other = vector.angle if part == "length" else vector.length
                if unknown in offset.free_symbols or unknown in other.free_symbols:
                    raise ValueError(
                        f"{unknown} must be the {part} of vector {vector} (up to a known offset) "
                        f"in loop {self.name!r}")
                return Unknown(unknown, sign, vector, part, offset)
        raise AssertionError("unreachable")

    def case(self, unknowns: Sequence[sp.Symbol]) -> LoopCase:
        """Recognise which of the four cases the two ``unknowns`` make."""
        if len(unknowns) != 2:
            raise ValueError(
                f"loop {self.name!r} has {len(unknowns)} unknowns ({', '.join(map(str, unknowns)) or 'none'}); "
                "a loop gives two equations and needs exactly two")
        turning = [self._turning_group(u, unknowns) for u in unknowns]
        if any(turning):
            return self._turning_case(unknowns, turning)
        first, second = (self.locate(u) for u in unknowns)
        parts = {first.part, second.part}
        if first.vector is second.vector and first.sign == second.sign:
            if parts != {"length", "angle"}:
                raise ValueError(f"{first.symbol} and {second.symbol} sit in the same part of one vector")
            name = "2a"
        elif parts == {"length"}:
            name = "1"
        elif parts == {"angle"}:
            name = "3"
        else:
            name = "2b"
        owners = {id(first.vector), id(second.vector)}
        known = tuple((s, v) for s, v in self.terms if id(v) not in owners)
        return LoopCase(name, first, second, known)

    def _turning_group(self, unknown: sp.Symbol, unknowns: Sequence[sp.Symbol]) -> list[tuple[int, Vector]]:
        """The terms that ``unknown`` turns together, if it is the angle of more than one; else []."""
        owners = [(sign, v) for sign, v in self.terms
                  if unknown in v.length.free_symbols | v.angle.free_symbols]
        if len(owners) < 2:
            return []
        for _, vector in owners:
            offset = sp.expand(vector.angle - unknown)
            if (unknown in vector.length.free_symbols or offset.free_symbols & set(unknowns)):
                raise ValueError(
                    f"{unknown} appears in {len(owners)} vectors of loop {self.name!r}; a closed form needs it "
                    "in exactly one, or as the angle (up to known offsets) of vectors that turn together")
        return owners

    def _turning_case(self, unknowns: Sequence[sp.Symbol], turning) -> LoopCase:
        """Cases 2b, 3 (a combined vector) and 2c for an unknown angle that turns several vectors."""
        if all(turning):
            raise ValueError(f"{unknowns[0]} and {unknowns[1]} each turn several vectors of loop {self.name!r}; "
                             "no closed form here")
        index = 0 if turning[0] else 1
        angle, other = unknowns[index], unknowns[1 - index]
        group = turning[index]
        with_other = [(s, v) for s, v in group if other in v.length.free_symbols]
        rest = tuple((s, v) for s, v in group if other not in v.length.free_symbols)
        members = {id(v) for _, v in group}
        if with_other:  # case 2c: the unknown length is on the turning body
            sign, vector = with_other[0]
            offset = sp.expand(vector.length - other)
            if len(with_other) > 1 or other in offset.free_symbols:
                raise ValueError(f"{other} must be the length of one vector (up to a known offset) in loop {self.name!r}")
            length = Unknown(other, sign, vector, "length", offset)
            turned = Unknown(angle, sign, vector, "angle", sp.expand(vector.angle - angle))
            known = tuple((s, v) for s, v in self.terms if id(v) not in members)
            first, second = (length, turned) if index == 1 else (turned, length)
            return LoopCase("2c", first, second, known, rest)
        # Otherwise the turning vectors add up to one of known length L at angle angle + gamma.
        cx = sp.Add(*(s * v.length * sp.cos(sp.expand(v.angle - angle)) for s, v in group))
        cy = sp.Add(*(s * v.length * sp.sin(sp.expand(v.angle - angle)) for s, v in group))
        gamma = sp.atan2(cy, cx)
        combined = Vector(sp.sqrt(cx**2 + cy**2), angle + gamma)
        merged = Loop.__new__(Loop)
        merged.name, merged.vectors = self.name, VectorSum(
            tuple((s, v) for s, v in self.terms if id(v) not in members) + ((1, combined),))
        solved = merged.case(list(unknowns))
        return solved

    def __repr__(self) -> str:
        return f"Loop({self.vectors}, name={self.name!r})"

    def __str__(self) -> str:
        """The closure in words: the signed sum of the vectors by name, then what each named vector is.

        >>> from symlink.symbolic.vectors import Vector, coordinates, lengths
        >>> theta, = coordinates("theta")
        >>> a, d = lengths("a d")
        >>> print(Loop(Vector(d, 0, "AD") + Vector(a, theta, "DB") - Vector(d + a, 0), "ADB"))
        loop ADB: AD + DB - (a + d) = 0, where AD = d, DB = a*e^(i*theta)
        """
        named = [f"{vector.name} = {vector.polar_text()}" for _, vector in self.terms if vector.name]
        return f"loop {self.name}: {self.vectors} = 0" + (", where " + ", ".join(named) if named else "")

    def _repr_latex_(self) -> str:
        r"""Jupyter's display: the closure with every vector in polar form.

        >>> from symlink.mechanism.catalog import fourbar
        >>> print(fourbar().loops[0]._repr_latex_())
        $\text{ABCD}:\quad d + c\,e^{i \phi} - b\,e^{i \beta} - a\,e^{i \theta} = 0$
        """
        return f"${math_text(self.name)}:\\quad {self.vectors.polar_latex()} = 0$"
