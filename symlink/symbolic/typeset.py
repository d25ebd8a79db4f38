r"""Typesetting equations in LaTeX so that they fit the page: a width estimate and line breaking.

Rows ``lhs = rhs`` become an ``align*``/``aligned`` block; a right-hand side
wider than the page breaks between terms, factors or ``atan2`` arguments
and continues on indented lines (standard ``amsmath`` only).  Where to break
is decided from an estimate of the typeset width (:func:`latex_width`), so
text is reproducible without running TeX.  Used by the LaTeX printer
(:mod:`symlink.codegen.latex`) and by a linkage's Jupyter display; it knows
equations, not linkages.

>>> theta = sp.Symbol("theta")
>>> print(aligned_rows([(sp.Symbol("x"), sp.cos(theta))]))
x &= \cos{\left(\theta \right)}
"""
from __future__ import annotations

import re
from typing import Iterable

import sympy as sp
from sympy.printing.latex import LatexPrinter

from .loops import Loop
from ..common.notation import latex_names
from .position import ClampedSqrt

__all__ = ["DISPLAY_WIDTH", "CONTINUATION_INDENT", "latex_width", "aligned_rows", "align_block", "closure_rows",
           "written_in_order"]


#: The width a display may fill: the text width of a 10pt ``article`` (345pt) less a margin for the estimate.
DISPLAY_WIDTH = 330.0
#: How far a continued line of a long right-hand side is indented (``\qquad``).
CONTINUATION_INDENT = 20.0

_TOKEN = re.compile(r"\\[A-Za-z]+|\\.|.", re.DOTALL)
_NAMED_FUNCTIONS = {"cos", "sin", "tan", "log", "exp", "max", "min", "sign", "cot", "sec", "csc"}
_SPACES = {"\\qquad": 20.0, "\\quad": 10.0, "\\;": 2.8, "\\:": 2.2, "\\,": 1.7, "\\ ": 3.3, "\\!": -1.7}
_SIZES = {"\\left", "\\right", "\\bigl", "\\bigr", "\\Bigl", "\\Bigr", "\\big", "\\Big"}
_SAME_WIDTH = {"\\dot", "\\ddot", "\\mathrm", "\\text", "\\operatorname", "\\mathit", "\\bar", "\\hat"}


def latex_width(text: str) -> float:
    r"""An estimate, in points, of the width of ``text`` typeset as 10pt display mathematics.

    Close enough (within about 10%, on the larger side) to decide where a long equation
    breaks without running TeX: letters, operators with their spacing, fractions as
    their wider part, sub- and superscripts at 70%.

    >>> latex_width(r"a + b") < latex_width(r"\frac{a + b + c}{d}") < latex_width(r"a + b + c + d")
    True
    """
    tokens = _TOKEN.findall(text)
    width, _ = _group_width(tokens, 0)
    return width


def _atom_width(tokens: list[str], position: int) -> tuple[float, int]:
    """The width of the group or single token at ``position``, and the position after it."""
    while position < len(tokens) and tokens[position] == " ":
        position += 1
    if position >= len(tokens):
        return 0.0, position
    if tokens[position] == "{":
        return _group_width(tokens, position + 1)
    return _group_width(tokens, position, single=True)


def _group_width(tokens: list[str], position: int, single: bool = False) -> tuple[float, int]:
    total = 0.0
    while position < len(tokens):
        token = tokens[position]
        position += 1
        if token == "}":
            return total, position
        if token == "{":
            width, position = _group_width(tokens, position)
        elif token in ("_", "^"):
            width, position = _atom_width(tokens, position)
            width *= 0.7
        elif token == "\\frac":
            numerator, position = _atom_width(tokens, position)
            denominator, position = _atom_width(tokens, position)
            width = max(numerator, denominator) + 2.0
        elif token == "\\sqrt":
            width, position = _atom_width(tokens, position)
            width += 10.0
        elif token in _SIZES:
            width, position = _atom_width(tokens, position)
            width = 0.0 if tokens[position - 1] == "." else 4.0
        elif token in _SAME_WIDTH:
            width, position = _atom_width(tokens, position)
        elif token in _SPACES:
            width = _SPACES[token]
        elif token.startswith("\\") and token[1:] in _NAMED_FUNCTIONS:
            width = 5.0 * (len(token) - 1) + 2.0
        elif token.startswith("\\") and token[1:].isalpha():
            width = 6.5  # a Greek letter or a symbol
        elif token in "+-=<>" or token in ("\\pm", "\\cdot"):
            width = 12.0
        elif token in "()[]|":
            width = 4.0
        elif token == ",":
            width = 4.5
        elif token == " ":
            width = 0.0
        elif token.isupper():
            width = 7.5
        else:
            width = 5.5
        total += width
        if single:
            break
    return total, position


def _delimited(opening: str, inner: list[str], closing: str = "", brackets: str = "()") -> list[str]:
    r"""``inner`` pieces between big brackets that may break across lines (``\bigl(``, unlike ``\left(``)."""
    size = "\\Big" if any("\\frac" in piece for piece in inner) else "\\big"
    inner = list(inner)
    inner[0] = f"{opening}{size}l{brackets[0]}{inner[0]}"
    inner[-1] = f"{inner[-1]}{size}r{brackets[1]}{closing}"
    return inner


def _pieces(expr: sp.Expr, printer: LatexPrinter, limit: float) -> list[str]:
    r"""``expr`` as LaTeX pieces, each narrower than ``limit`` where the expression allows a break there.

    A sum breaks between its terms; a fraction with a long numerator becomes
    ``\frac{1}{denominator}`` times the numerator in parentheses; a product
    breaks between its factors; ``atan2`` breaks between or inside its arguments; a clamped
    root of a long argument is written as a power, ``[x]_+^{1/2}``.  Anything else (a
    function of a long argument) is one piece.
    """
    text = printer.doprint(expr)
    if latex_width(text) <= limit:
        return [text]
    if isinstance(expr, sp.Add):
        pieces = []
        for index, term in enumerate(printer._as_ordered_terms(expr, order=None)):
            sign = ""
            if index and term.could_extract_minus_sign():
                sign, term = "- ", -term
            elif index:
                sign = "+ "
            inner = _pieces(term, printer, limit)
            if isinstance(term, sp.Add):  # a sum inside a sum keeps its parentheses
                inner = _delimited("", inner)
            inner[0] = sign + inner[0]
            pieces += inner
        return pieces
    if isinstance(expr, sp.atan2):
        y, x = (_pieces(argument, printer, limit) for argument in expr.args)
        return _delimited("\\operatorname{atan}_{2}", [*y[:-1], y[-1] + ",", *x])
    if isinstance(expr, sp.Mul):
        if expr.could_extract_minus_sign():
            inner = _pieces(-expr, printer, limit)
            inner[0] = "- " + inner[0]
            return inner
        numerator, denominator = sp.fraction(expr, exact=True)
        if denominator != 1:
            inner = _pieces(numerator, printer, limit)
            if len(inner) == 1:
                return [text]
            return _delimited("\\frac{1}{%s} " % printer.doprint(denominator), inner)
        pieces = []
        for factor in expr.as_ordered_factors():  # a product breaks between its factors, or inside a wide one
            inner = _pieces(factor, printer, limit)
            if isinstance(factor, sp.Add):
                inner = _delimited("", inner) if len(inner) > 1 else ["\\left(%s\\right)" % inner[0]]
            pieces += inner
        return pieces
    if isinstance(expr, ClampedSqrt):
        return _delimited("", _pieces(expr.args[0], printer, limit), "_{+}^{1/2}", "[]")
    return [text]


def _lines(pieces: list[str], first: float, rest: float) -> list[str]:
    """Pack pieces greedily into lines of at most ``first`` (the first line) and ``rest`` (the others) points."""
    lines = [pieces[0]]
    for piece in pieces[1:]:
        candidate = f"{lines[-1]} {piece}"
        if latex_width(candidate) <= (first if len(lines) == 1 else rest):
            lines[-1] = candidate
        else:
            lines.append(piece)
    return lines


#: Sums to print in the order they were written (``B^2 - 4AC``), not SymPy's; see :func:`written_in_order`.
_WRITTEN_ORDER: set[sp.Expr] = set()


def written_in_order(total: sp.Expr) -> sp.Expr:
    """``total`` (an unevaluated ``Add``), marked to print its terms in the order they were written.

    A textbook writes the discriminant ``B^2 - 4AC``; SymPy's printing order would give
    ``- 4 A C + B^2``.  Only the mark's printing changes: the expression is the same.

    >>> A, B, C = sp.symbols("A B C")
    >>> aligned_rows([(sp.Symbol("D"), written_in_order(sp.Add(B**2, -4 * A * C, evaluate=False)))])
    'D &= B^{2} - 4 A C'
    """
    _WRITTEN_ORDER.add(total)
    return total


class _Printer(LatexPrinter):
    """SymPy's LaTeX printer, but for sums marked :func:`written_in_order`."""

    def _print_Add(self, expr: sp.Expr, order: str | None = None) -> str:
        return super()._print_Add(expr, "none" if expr in _WRITTEN_ORDER else order)


def aligned_rows(rows: list[tuple[sp.Expr, sp.Expr]], width: float = DISPLAY_WIDTH) -> str:
    """Rows ``lhs &= rhs`` for an ``align*`` or ``aligned`` block; a right-hand side wider than the
    page left beside the widest left-hand side continues on further lines, indented."""
    printer = _Printer({"symbol_names": latex_names([e for row in rows for e in row])})
    left = [printer.doprint(lhs) for lhs, _ in rows]
    room = width - max((latex_width(text) for text in left), default=0.0) - latex_width("=")
    body = []
    for lhs, (_, rhs) in zip(left, rows):
        lines = _lines(_pieces(rhs, printer, room - CONTINUATION_INDENT), room, room - CONTINUATION_INDENT)
        body.append(f"{lhs} &= " + "\\\\\n&\\qquad ".join(lines))
    return "\\\\\n".join(body)


def display_latex(rows: list[tuple[sp.Expr, sp.Expr]]) -> str:
    """Rows as one Jupyter display: ``$\\displaystyle \\begin{aligned} ... \\end{aligned}$``.

    One short equation shows on one line, as a textbook sets it, without an ``aligned`` block.

    >>> x, y = sp.symbols("x y")
    >>> display_latex([(y, 2 * x)])
    '$\\\\displaystyle y = 2 x$'
    """
    body = aligned_rows(rows)
    if len(rows) == 1 and "\\\\" not in body:
        return "$\\displaystyle " + body.replace(" &= ", " = ", 1) + "$"
    return "$\\displaystyle \\begin{aligned}" + body + "\\end{aligned}$"


class EquationSet(dict):
    r"""Equations ``symbol: expression`` (positions, rates, sensitivities, forces) that display as maths in Jupyter.

    Keys are symbols, or output names (joint forces, efforts), shown as symbols of that name.

    A plain ``dict`` in every other way, so code that reads equations is unchanged.

    >>> theta, a = sp.symbols("theta a")
    >>> shown = EquationSet({sp.Symbol("x"): a * sp.cos(theta)})._repr_latex_()
    >>> shown  # one short equation: one line
    '$\\displaystyle x = a \\cos{\\left(\\theta \\right)}$'
    """

    def _repr_latex_(self) -> str:
        return display_latex([(sp.Symbol(name) if isinstance(name, str) else name, expr) for name, expr in self.items()])


def align_block(rows: list[tuple[sp.Expr, sp.Expr]]) -> list[str]:
    """Rows as an ``align*`` environment, one line a list item."""
    return ["\\begin{align*}", aligned_rows(rows), "\\end{align*}"]


def closure_rows(loops: Iterable[Loop]) -> list[tuple[sp.Expr, sp.Expr]]:
    """The closure equations ``x = 0`` and ``y = 0`` of every loop."""
    rows = []
    for loop in loops:
        x, y = loop.equations()
        rows += [(x, sp.S.Zero), (y, sp.S.Zero)]
    return rows
