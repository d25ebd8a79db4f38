r"""The LaTeX printer: a linkage's derivation as a document, and its equations for Jupyter.

:func:`latex_document` writes a closed-form derivation (closure, solve plan,
positions, velocities, accelerations); :func:`newton_document` writes the
numeric fallback's (closure, Newton's iteration, the Jacobian and the rate
systems).  Both share one preamble (:func:`document`), and text that is not
mathematics (titles, loop names) is escaped (:func:`latex_text`).

Equations fit a letter or A4 page: the positions print as the named
intermediates of the closed forms, one row each, and a right-hand side still
wider than the page breaks between terms, factors or ``atan2`` arguments and
continues on indented lines (standard ``amsmath`` only; where to break is
decided from an estimate of the typeset width, :func:`latex_width`).

This module imports no linkage at run time: ``Linkage._repr_latex_`` imports
it on first use.

>>> from symlink.catalog import fourbar
>>> text = latex_document(fourbar(), "Four-bar")
>>> r"\dot{\phi}" in text and r"\begin{document}" in text
True
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Sequence

import re

import sympy as sp
from sympy.printing.latex import LatexPrinter

from ..closure import closure_system
from ..loops import CASE_NAMES
from ..position import ClampedSqrt
from ..notation import branch_latex, latex_names
from ..vectors import acceleration, rate

if TYPE_CHECKING:
    from ..linkage import Linkage

__all__ = ["latex_text", "latex_width", "document", "closure_rows", "equations_latex", "latex_document", "newton_document",
           "export_files"]

_LATEX_ESCAPES = {
    "\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_", "{": r"\{", "}": r"\}",
    "~": r"\textasciitilde{}", "^": r"\textasciicircum{}", "<": r"\textless{}", ">": r"\textgreater{}",
    "|": r"\textbar{}",
}


def latex_text(text: str) -> str:
    r"""``text`` as LaTeX prints it in running text: special characters escaped, line breaks as spaces.

    >>> print(latex_text("a_1 & 50% of {x^2}"))
    a\_1 \& 50\% of \{x\textasciicircum{}2\}
    """
    return "".join(_LATEX_ESCAPES.get(c, c) if c.isprintable() else " " for c in text)


def document(title: str, body: Sequence[str]) -> str:
    """A standalone ``article`` with ``amsmath``: the title (escaped) as an unnumbered section, then ``body``."""
    parts = ["\\documentclass{article}", "\\usepackage{amsmath}", "\\allowdisplaybreaks",
             "\\begin{document}", f"\\section*{{{latex_text(title)}}}", *body, "\\end{document}"]
    return "\n".join(parts) + "\n"


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


def _aligned(rows: list[tuple[sp.Expr, sp.Expr]], width: float = DISPLAY_WIDTH) -> str:
    """Rows ``lhs &= rhs`` for an ``align*`` or ``aligned`` block; a right-hand side wider than the
    page left beside the widest left-hand side continues on further lines, indented."""
    printer = LatexPrinter({"symbol_names": latex_names([e for row in rows for e in row])})
    left = [printer.doprint(lhs) for lhs, _ in rows]
    room = width - max((latex_width(text) for text in left), default=0.0) - latex_width("=")
    body = []
    for lhs, (_, rhs) in zip(left, rows):
        lines = _lines(_pieces(rhs, printer, room - CONTINUATION_INDENT), room, room - CONTINUATION_INDENT)
        body.append(f"{lhs} &= " + "\\\\\n&\\qquad ".join(lines))
    return "\\\\\n".join(body)


def _align(rows: list[tuple[sp.Expr, sp.Expr]]) -> list[str]:
    return ["\\begin{align*}", _aligned(rows), "\\end{align*}"]


def closure_rows(linkage: Linkage) -> list[tuple[sp.Expr, sp.Expr]]:
    """The closure equations ``x = 0`` and ``y = 0`` of every loop."""
    rows = []
    for loop in linkage.loops:
        x, y = loop.equations()
        rows += [(x, sp.S.Zero), (y, sp.S.Zero)]
    return rows


def equations_latex(linkage: Linkage, velocities: bool = False, accelerations: bool = False) -> str:
    """All equations of the linkage as one ``aligned`` block (for Jupyter).

    The closure equations, then the closed-form positions where the linkage
    has a solve plan (and, when asked for, the velocities and accelerations);
    without one (the Newton fallback solves it) the closure alone.
    """
    rows = closure_rows(linkage)
    if linkage.has_closed_form:
        rows += list(linkage.positions.items())
        rows += list(linkage.velocities.items()) if velocities else []
        rows += list(linkage.accelerations.items()) if accelerations else []
    return "\\begin{aligned}" + _aligned(rows) + "\\end{aligned}"


def latex_document(linkage: Linkage, title: str, *, velocities: bool = True, accelerations: bool = True) -> str:
    """A standalone LaTeX document with the linkage's closed-form derivation, section by section."""
    parts = [
        "Angles are measured counter-clockwise from $+x$. "
        "$\\left[x\\right]_{+}$ is $\\max(x, 0)$ where $x$ is negative only by rounding "
        "(a toggle position); below that the linkage cannot be assembled.",
        "\\subsection*{Closure}", *_align(closure_rows(linkage)),
        "\\subsection*{Solve plan}", "\\begin{enumerate}",
    ]
    for step in linkage.plan:
        unknowns = ", ".join(f"${sp.latex(u)}$" for u in step.positions)
        branch = (f", branch ${branch_latex(step.branch.name)} = \\pm 1$ (argument \\texttt{{{latex_text(step.branch.name)}}})"
                  if step.branch is not None else "")
        parts.append(f"\\item loop {latex_text(step.loop.name)}: case {latex_text(step.case.name)} "
                     f"({latex_text(CASE_NAMES[step.case.name])}), unknowns {unknowns}{branch}")
    parts += ["\\end{enumerate}", "\\subsection*{Positions}", *_align(list(linkage.positions.items()))]
    if velocities:
        parts += ["\\subsection*{Velocities}", *_align(list(linkage.velocities.items()))]
    if accelerations:
        parts += ["\\subsection*{Accelerations}", *_align(list(linkage.accelerations.items()))]
    return document(title, parts)


def newton_document(linkage: Linkage, title: str) -> str:
    """A standalone LaTeX document: closure, why there is no closed form, Newton's iteration and the rate systems."""
    from ..plan import solve_plan

    system = closure_system(linkage)
    q = sp.Matrix(linkage.unknowns)
    qdot = sp.Matrix([rate(u) for u in linkage.unknowns])
    qddot = sp.Matrix([acceleration(u) for u in linkage.unknowns])
    plan = solve_plan(linkage)
    rows = [(sp.Symbol(f"J_{{{i + 1}{j + 1}}}"), system.jacobian[i, j])
            for i in range(system.jacobian.rows) for j in range(system.jacobian.cols) if system.jacobian[i, j] != 0]
    rhs = [(sp.Symbol(f"r_{{{i + 1}}}"), e) for i, e in enumerate(system.velocity_rhs)]
    rhs2 = [(sp.Symbol(f"s_{{{i + 1}}}"), e) for i, e in enumerate(system.acceleration_rhs)]
    return document(title, [
        "Angles are measured counter-clockwise from $+x$.",
        "\\subsection*{Closure}", *_align(closure_rows(linkage)),
        "\\subsection*{Solve plan}", latex_text(plan.note) + ".",
        f"The closure $F(q) = 0$, $q = {sp.latex(q.T)}^T$, is solved by Newton's method, "
        "$J\\,\\Delta q = -F$, with the Jacobian $J = \\partial F / \\partial q$ below; each input value "
        "continues from the previous one, and the first assembly (from an initial guess) fixes the branch.",
        "\\subsection*{Jacobian}", *_align(rows),
        f"\\subsection*{{Velocities: $J {sp.latex(qdot)} = r$}}", *_align(rhs),
        f"\\subsection*{{Accelerations: $J {sp.latex(qddot)} = s$}}", *_align(rhs2),
    ])


def export_files(linkage: Linkage, stem: str, functions: Sequence[tuple[str, Sequence[str], str]],
                 title: str, regenerate: str = "") -> dict[str, str]:
    """``{"<stem>.tex": document}``: the derivation, as far as the ``(name, outputs, doc)`` sets need it.

    The velocities are written if any output depends on a rate, the
    accelerations if any depends on an acceleration; ``regenerate`` is not written.
    """
    asked = set().union(*(linkage.output(o).free_symbols for _, outputs, _ in functions for o in outputs))
    accelerations = any(acceleration(q) in asked for q in linkage.unknowns)
    velocities = accelerations or any(rate(q) in asked for q in linkage.unknowns)
    return {f"{stem}.tex": latex_document(linkage, title, velocities=velocities, accelerations=accelerations)}
