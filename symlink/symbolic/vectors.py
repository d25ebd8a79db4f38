"""Planar vectors made from a length and an angle, as in the MBsymba worksheet.

A :class:`Vector` is ``length * e^{i angle}``; either part may be a number, a
parameter (a link length) or a coordinate (a joint angle or a slider travel
that changes with time).  Vectors add and subtract into a :class:`VectorSum`,
which keeps its terms so that a loop can tell which vector carries which
unknown.

Coordinates are plain SymPy symbols.  Their time derivatives are the symbols
``<name>dot`` and ``<name>ddot`` (SymPy prints them as a dot and two dots in
LaTeX), and :func:`time_derivative` applies the chain rule with them, so the
derived expressions stay free of ``Derivative`` objects and print directly as
code.

>>> theta, beta = coordinates("theta beta")
>>> a, b = lengths("a b")
>>> (Vector(a, theta) + Vector(b, beta)).x
a*cos(theta) + b*cos(beta)
>>> time_derivative(a * sp.cos(theta), [theta])
-a*thetadot*sin(theta)
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable

import sympy as sp

from ..common.names import label
from ..common.notation import math_text

__all__ = [
    "Vector", "VectorSum", "expression", "coordinates", "lengths", "rate", "acceleration",
    "time_derivative",
]


def expression(value) -> sp.Expr:
    """A SymPy expression from a number or an expression, never from text (no parsing, no eval).

    >>> expression(2), expression(sp.pi / 2)
    (2, pi/2)
    >>> expression("a + 1")
    Traceback (most recent call last):
    ValueError: give a number or a SymPy expression, not text: 'a + 1'
    """
    if isinstance(value, str):
        raise ValueError(f"give a number or a SymPy expression, not text: {value!r}")
    try:
        return sp.sympify(value, strict=True)
    except sp.SympifyError:
        raise ValueError(f"not a number or a SymPy expression: {value!r}") from None


def coordinates(names: str) -> tuple[sp.Symbol, ...]:
    """Real symbols for time-varying coordinates (joint angles, slider travels).

    Parameters
    ----------
    names : str
        Their names, separated by spaces (``"theta beta phi"``).

    Returns
    -------
    tuple of sympy.Symbol
        One real symbol a name, in order.

    Examples
    --------
    >>> import symlink
    >>> theta, beta = symlink.coordinates("theta beta")
    >>> theta, theta.is_real
    (theta, True)
    """
    found = sp.symbols(names, real=True, seq=True)
    return tuple(found)


def lengths(names: str) -> tuple[sp.Symbol, ...]:
    """Positive symbols for link lengths and other constant dimensions.

    Parameters
    ----------
    names : str
        Their names, separated by spaces (``"a b c d"``).

    Returns
    -------
    tuple of sympy.Symbol
        One positive real symbol a name, in order.

    Examples
    --------
    >>> import symlink
    >>> a, b = symlink.lengths("a b")
    >>> a.is_positive, (a + b).is_positive
    (True, True)
    """
    return tuple(sp.symbols(names, positive=True, seq=True))


def rate(coordinate: sp.Symbol) -> sp.Symbol:
    """The symbol of a coordinate's first time derivative (``thetadot``).

    Parameters
    ----------
    coordinate : sympy.Symbol
        A coordinate made by :func:`coordinates`.

    Returns
    -------
    sympy.Symbol
        The real symbol named after it with ``dot`` appended.

    Examples
    --------
    >>> import symlink
    >>> theta, = symlink.coordinates("theta")
    >>> symlink.rate(theta)
    thetadot
    """
    return sp.Symbol(coordinate.name + "dot", real=True)


def acceleration(coordinate: sp.Symbol) -> sp.Symbol:
    """The symbol of a coordinate's second time derivative (``thetaddot``).

    Parameters
    ----------
    coordinate : sympy.Symbol
        A coordinate made by :func:`coordinates`.

    Returns
    -------
    sympy.Symbol
        The real symbol named after it with ``ddot`` appended.

    Examples
    --------
    >>> import symlink
    >>> theta, = symlink.coordinates("theta")
    >>> symlink.acceleration(theta)
    thetaddot
    """
    return sp.Symbol(coordinate.name + "ddot", real=True)


def time_derivative(expr: sp.Expr, coordinates: Iterable[sp.Symbol]) -> sp.Expr:
    """Total time derivative of ``expr`` by the chain rule.

    ``coordinates`` change with time; every other symbol is constant.  A
    coordinate's rate symbol differentiates to its acceleration symbol, so
    applying this twice gives second derivatives.

    Parameters
    ----------
    expr : sympy.Expr
        An expression of coordinates, their rates and constants.
    coordinates : iterable of sympy.Symbol
        The symbols that change with time.

    Returns
    -------
    sympy.Expr
        ``d(expr)/dt``, in the rate (and acceleration) symbols.

    Examples
    --------
    >>> import sympy, symlink
    >>> theta, = symlink.coordinates("theta")
    >>> a, = symlink.lengths("a")
    >>> symlink.time_derivative(a * sympy.cos(theta), [theta])
    -a*thetadot*sin(theta)
    >>> symlink.time_derivative(symlink.rate(theta), [theta])
    thetaddot
    """
    expr = expression(expr)
    chain = {}
    for q in coordinates:
        chain[q] = rate(q)
        chain[rate(q)] = acceleration(q)
    result = sp.S.Zero
    for symbol, derivative in chain.items():
        partial = sp.diff(expr, symbol)
        if partial != 0:
            result += partial * derivative
    return result


@dataclass(frozen=True)
class Vector:
    """A planar vector ``length * e^{i angle}``.

    ``name`` labels it in plans and drawings (``"AB"``).  A negative sign in a
    sum means the vector is walked backwards; it is not folded into the angle,
    so a loop still knows which of its vectors owns each unknown.

    Parameters
    ----------
    length : sympy.Expr
        The vector's length: a symbol of :func:`lengths`, a coordinate (a slider's travel) or an expression.
    angle : sympy.Expr
        Its angle from the x axis, counter-clockwise: a coordinate, a constant or an expression.
    name : str, optional
        A label for plans and drawings (``"AB"``); empty by default.

    Examples
    --------
    >>> import symlink
    >>> theta, = symlink.coordinates("theta")
    >>> a, = symlink.lengths("a")
    >>> AB = symlink.Vector(a, theta, "AB")
    >>> AB.x, AB.y
    (a*cos(theta), a*sin(theta))
    >>> (AB - AB).terms[1][0]  # walked backwards: the sign, not the angle
    -1
    """

    length: sp.Expr
    angle: sp.Expr
    name: str = ""

    def __post_init__(self) -> None:
        if self.name != "":
            label(self.name, "vector name")
        object.__setattr__(self, "length", expression(self.length))
        object.__setattr__(self, "angle", expression(self.angle))

    @property
    def x(self) -> sp.Expr:
        return self.length * sp.cos(self.angle)

    @property
    def y(self) -> sp.Expr:
        return self.length * sp.sin(self.angle)

    def as_sum(self) -> "VectorSum":
        return VectorSum(((1, self),))

    def __add__(self, other: "Vector | VectorSum") -> "VectorSum":
        return self.as_sum() + other

    def __sub__(self, other: "Vector | VectorSum") -> "VectorSum":
        return self.as_sum() - other

    def __neg__(self) -> "VectorSum":
        return -self.as_sum()

    def polar_text(self) -> str:
        """The vector as text, ``length*e^(i*angle)`` (the length alone at angle zero)."""
        length = f"({self.length})" if isinstance(self.length, sp.Add) else str(self.length)
        if self.angle == 0:
            return length
        return f"{length}*e^(i*{self.angle if self.angle.is_Atom else f'({self.angle})'})"

    def polar_latex(self) -> str:
        r"""The vector as LaTeX, ``a\,e^{i \theta}`` (the length alone at angle zero)."""
        length = sp.latex(self.length)
        if self.angle == 0:
            return length
        if isinstance(self.length, sp.Add):
            length = r"\left(%s\right)" % length
        angle = sp.latex(self.angle)
        return f"{length}\\,e^{{i {angle}}}" if self.angle.is_Atom else f"{length}\\,e^{{i\\left({angle}\\right)}}"

    def __str__(self) -> str:
        return self.name or self.polar_text()

    def _repr_latex_(self) -> str:
        r"""Jupyter's display: ``AB = a e^{i theta}`` with the name as an arrow over the letters.

        >>> a, theta = lengths("a")[0], coordinates("theta")[0]
        >>> print(Vector(a, theta + sp.pi / 2, "AB")._repr_latex_())
        $\overrightarrow{\text{AB}} = a\,e^{i\left(\theta + \frac{\pi}{2}\right)}$
        >>> print(Vector(a, theta + sp.pi / 2).polar_text())
        a*e^(i*(theta + pi/2))
        """
        if not self.name:
            return f"${self.polar_latex()}$"
        return f"$\\overrightarrow{{{math_text(self.name)}}} = {self.polar_latex()}$"


@dataclass(frozen=True)
class VectorSum:
    """A signed sum of vectors: ``terms`` are ``(sign, vector)`` with sign +1 or -1.

    Parameters
    ----------
    terms : tuple of (int, Vector)
        The signed vectors: ``(+1, v)`` walks ``v`` forwards, ``(-1, v)`` backwards.

    Examples
    --------
    >>> import symlink
    >>> theta, phi = symlink.coordinates("theta phi")
    >>> a, c = symlink.lengths("a c")
    >>> loop = symlink.Vector(a, theta) - symlink.Vector(c, phi)
    >>> type(loop).__name__, [sign for sign, _ in loop.terms]
    ('VectorSum', [1, -1])
    >>> loop.x
    a*cos(theta) - c*cos(phi)
    """

    terms: tuple[tuple[int, Vector], ...]

    @property
    def x(self) -> sp.Expr:
        return sp.Add(*(sign * v.x for sign, v in self.terms))

    @property
    def y(self) -> sp.Expr:
        return sp.Add(*(sign * v.y for sign, v in self.terms))

    def __add__(self, other: "Vector | VectorSum") -> "VectorSum":
        other = other.as_sum() if isinstance(other, Vector) else other
        return VectorSum(self.terms + other.terms)

    def __sub__(self, other: "Vector | VectorSum") -> "VectorSum":
        other = other.as_sum() if isinstance(other, Vector) else other
        return self + (-other)

    def __neg__(self) -> "VectorSum":
        return VectorSum(tuple((-sign, v) for sign, v in self.terms))

    def as_sum(self) -> "VectorSum":
        return self

    def __str__(self) -> str:
        text = ""
        for sign, vector in self.terms:
            text += (" - " if sign < 0 else (" + " if text else "")) + str(vector)
        return text.strip()

    def polar_latex(self) -> str:
        """The sum as LaTeX, each vector in polar form.

        >>> a, d = lengths("a d")
        >>> print((Vector(d, 0) - Vector(a, coordinates("theta")[0])).polar_latex())
        d - a\\,e^{i \\theta}
        """
        text = ""
        for sign, vector in self.terms:
            text += ("- " if sign < 0 else ("+ " if text else "")) + vector.polar_latex() + " "
        return text.strip()

    def _repr_latex_(self) -> str:
        return f"${self.polar_latex()}$"
