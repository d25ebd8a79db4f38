"""LaTeX export of a linkage's equations: closure, solve plan, positions, velocities, accelerations.

>>> from symlink.catalog import fourbar
>>> text = latex_document(fourbar(), "Four-bar")
>>> r"\\dot{\\phi}" in text and r"\\begin{document}" in text
True
"""
from __future__ import annotations

import sympy as sp

from .linkage import Linkage
from .loops import CASE_NAMES

__all__ = ["equations_latex", "latex_document"]


def _symbol_names(expressions) -> dict[sp.Symbol, str]:
    """Textbook names: sigma for a branch, W_{x,1} for loop 1's closing vector."""
    names = {}
    for symbol in set().union(*(sp.sympify(e).free_symbols for e in expressions)):
        stem, _, label = symbol.name.partition("_")
        if symbol.name == "branch":
            names[symbol] = r"\sigma"
        elif stem == "branch":
            names[symbol] = r"\sigma_{\mathrm{%s}}" % label
        elif stem in ("Wx", "Wy") and label.isdigit():
            names[symbol] = "W_{%s,%s}" % (stem[1], label)
    return names


def _aligned(rows: list[tuple[sp.Expr, sp.Expr]]) -> str:
    names = _symbol_names([e for row in rows for e in row])
    return "\\\\\n".join(f"{sp.latex(lhs, symbol_names=names)} &= {sp.latex(rhs, symbol_names=names)}"
                         for lhs, rhs in rows)


def closure_rows(linkage: Linkage) -> list[tuple[sp.Expr, sp.Expr]]:
    """The closure equations ``x = 0`` and ``y = 0`` of every loop."""
    rows = []
    for loop in linkage.loops:
        x, y = loop.equations()
        rows += [(x, sp.S.Zero), (y, sp.S.Zero)]
    return rows


def equations_latex(linkage: Linkage) -> str:
    """All equations of the linkage as one ``aligned`` block (for Jupyter)."""
    rows = closure_rows(linkage) + list(linkage.positions.items())
    return "\\begin{aligned}" + _aligned(rows) + "\\end{aligned}"


def latex_document(linkage: Linkage, title: str, *, velocities: bool = True, accelerations: bool = True) -> str:
    """A standalone LaTeX document with the linkage's derivation, section by section."""
    parts = [
        "\\documentclass{article}", "\\usepackage{amsmath}", "\\allowdisplaybreaks",
        "\\begin{document}", f"\\section*{{{title}}}",
        "Angles are measured counter-clockwise from $+x$. "
        "$\\left[x\\right]_{+}$ is $\\max(x, 0)$ where $x$ is negative only by rounding "
        "(a toggle position); below that the linkage cannot be assembled.",
        "\\subsection*{Closure}", "\\begin{align*}", _aligned(closure_rows(linkage)), "\\end{align*}",
        "\\subsection*{Solve plan}", "\\begin{enumerate}",
    ]
    for step in linkage.plan:
        unknowns = ", ".join(f"${sp.latex(u)}$" for u in step.positions)
        branch = (f", branch ${sp.latex(step.branch, symbol_names=_symbol_names([step.branch]))} = \\pm 1$"
                  if step.branch is not None else "")
        parts.append(f"\\item loop {step.loop.name}: case {step.case.name} "
                     f"({CASE_NAMES[step.case.name]}), unknowns {unknowns}{branch}")
    parts += ["\\end{enumerate}", "\\subsection*{Positions}", "\\begin{align*}",
              _aligned(list(linkage.positions.items())), "\\end{align*}"]
    if velocities:
        parts += ["\\subsection*{Velocities}", "\\begin{align*}",
                  _aligned(list(linkage.velocities.items())), "\\end{align*}"]
    if accelerations:
        parts += ["\\subsection*{Accelerations}", "\\begin{align*}",
                  _aligned(list(linkage.accelerations.items())), "\\end{align*}"]
    parts.append("\\end{document}")
    return "\n".join(parts) + "\n"
