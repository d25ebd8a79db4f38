r"""The LaTeX printer: a linkage's derivation as a document.

:func:`latex_document` writes a closed-form derivation (closure, solve plan,
positions, velocities, accelerations); :func:`newton_document` writes the
numeric fallback's (closure, Newton's iteration, the Jacobian and the rate
systems).  Both share one preamble (:func:`document`), and text that is not
mathematics (titles, loop names) is escaped (:func:`latex_text`).

Equations fit a letter or A4 page: the positions print as the named
intermediates of the closed forms, one row each, and a right-hand side still
wider than the page breaks across lines (:mod:`symlink.symbolic.typeset`, which
``Linkage._repr_latex_`` uses too).

>>> from symlink.mechanism.catalog import fourbar
>>> text = latex_document(fourbar(), "Four-bar")
>>> r"\dot{\phi}" in text and r"\begin{document}" in text
True
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Sequence

import sympy as sp

from ..symbolic.closure import closure_system
from ..symbolic.loops import CASE_NAMES
from ..common.notation import branch_latex
from ..symbolic.seed_forms import SEED_FORM_TITLES, seed_form_rows
from ..symbolic.sensitivity import sensitivity_symbol
from ..symbolic.typeset import align_block, closure_rows
from ..symbolic.vectors import acceleration, rate

if TYPE_CHECKING:
    from ..symbolic.linkage import Linkage

__all__ = ["latex_text", "document", "latex_document", "newton_document", "export_files"]

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


def latex_document(linkage: Linkage, title: str, *, velocities: bool = True, accelerations: bool = True,
                   sensitivities: Sequence[sp.Symbol] = (), dynamics: bool = False, form: str = "atan2") -> str:
    r"""A standalone LaTeX document with the linkage's closed-form derivation, section by section.

    ``sensitivities`` names parameters whose design sensitivities (the unknowns' derivatives by them,
    :mod:`symlink.symbolic.sensitivity`) get a section of their own; ``dynamics`` adds the sections of a linkage
    with mass properties (its ``derivation_sections``: see :mod:`symlink.dynamics.inverse`).
    ``form`` other than ``"atan2"`` adds the positions in that seed paper's form
    (:data:`symlink.symbolic.seed_forms.FORMS`) after symlink's own, which generated code computes.

    Parameters
    ----------
    linkage : Linkage
        The linkage, with a closed-form plan.
    title : str
        The document's title.
    velocities, accelerations : bool, optional
        Whether to derive the rates and accelerations (default True).
    sensitivities : sequence of sympy.Symbol, optional
        Parameters whose design sensitivities get a section.
    dynamics : bool, optional
        Add the dynamics sections of a linkage with mass properties (default False).
    form : str, optional
        ``"atan2"`` (default, symlink's own) or a seed paper's form to add after it.

    Returns
    -------
    str
        The LaTeX source of a complete document (``\documentclass`` to ``\end{document}``).

    Examples
    --------
    >>> import symlink
    >>> text = symlink.latex_document(symlink.fourbar(), "The four-bar")
    >>> text.startswith("\\documentclass"), "The four-bar" in text, text.rstrip().endswith("\\end{document}")
    (True, True, True)
    """
    parts = [
        "Angles are measured counter-clockwise from $+x$. "
        "$\\left[x\\right]_{+}$ is $\\max(x, 0)$ where $x$ is negative only by rounding "
        "(a toggle position); below that the linkage cannot be assembled.",
        "\\subsection*{Closure}", *align_block(closure_rows(linkage.loops)),
        "\\subsection*{Solve plan}", "\\begin{enumerate}",
    ]
    for step in linkage.plan:
        unknowns = ", ".join(f"${sp.latex(u)}$" for u in step.positions)
        branch = (f", branch ${branch_latex(step.branch.name)} = \\pm 1$ (argument \\texttt{{{latex_text(step.branch.name)}}})"
                  if step.branch is not None else "")
        parts.append(f"\\item loop {latex_text(step.loop.name)}: case {latex_text(step.case.name)} "
                     f"({latex_text(CASE_NAMES[step.case.name])}), unknowns {unknowns}{branch}")
    parts += ["\\end{enumerate}", "\\subsection*{Positions}", *align_block(list(linkage.positions.items()))]
    rows = seed_form_rows(linkage, form)
    if form != "atan2":
        parts += [f"\\subsection*{{Positions in the {latex_text(SEED_FORM_TITLES[form])}}}", *align_block(rows)]
    if velocities:
        parts += ["\\subsection*{Velocities}", *align_block(list(linkage.velocities.items()))]
    if accelerations:
        parts += ["\\subsection*{Accelerations}", *align_block(list(linkage.accelerations.items()))]
    for parameter in sensitivities:
        parts += [f"\\subsection*{{Sensitivities to ${sp.latex(parameter)}$}}",
                  *align_block(list(linkage.sensitivities(parameter).items()))]
    if dynamics:
        for heading, rows in linkage.derivation_sections():  # type: ignore[attr-defined]
            parts += [f"\\subsection*{{{latex_text(heading)}}}", *align_block(rows)]
    return document(title, parts)


def newton_document(linkage: Linkage, title: str) -> str:
    r"""A standalone LaTeX document: closure, why there is no closed form, Newton's iteration and the rate systems.

    Parameters
    ----------
    linkage : Linkage
        Any linkage (usually one without a closed form).
    title : str
        The document's title.

    Returns
    -------
    str
        The LaTeX source of a complete document.

    Examples
    --------
    >>> import symlink
    >>> text = symlink.newton_document(symlink.stephenson2(), "Stephenson II")
    >>> "Newton" in text, text.rstrip().endswith("\\end{document}")
    (True, True)
    """
    from ..symbolic.plan import solve_plan

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
        "\\subsection*{Closure}", *align_block(closure_rows(linkage.loops)),
        "\\subsection*{Solve plan}", latex_text(plan.note) + ".",
        f"The closure $F(q) = 0$, $q = {sp.latex(q.T)}^T$, is solved by Newton's method, "
        "$J\\,\\Delta q = -F$, with the Jacobian $J = \\partial F / \\partial q$ below; each input value "
        "continues from the previous one, and the first assembly (from an initial guess) fixes the branch.",
        "\\subsection*{Jacobian}", *align_block(rows),
        f"\\subsection*{{Velocities: $J {sp.latex(qdot)} = r$}}", *align_block(rhs),
        f"\\subsection*{{Accelerations: $J {sp.latex(qddot)} = s$}}", *align_block(rhs2),
    ])


def export_files(linkage: Linkage, stem: str, functions: Sequence[tuple[str, Sequence[str], str]],
                 title: str, regenerate: str = "", form: str = "atan2") -> dict[str, str]:
    """``{"<stem>.tex": document}``: the derivation, as far as the ``(name, outputs, doc)`` sets need it.

    The velocities are written if any output depends on a rate, the
    accelerations if any depends on an acceleration, the sensitivities to a
    parameter if any output is a derivative by it; ``regenerate`` is not written.
    ``form`` writes the positions in a seed paper's form (:mod:`symlink.symbolic.seed_forms`).
    """
    asked = set().union(*(linkage.output(o).free_symbols for _, outputs, _ in functions for o in outputs))
    accelerations = any(acceleration(q) in asked for q in linkage.unknowns)
    velocities = accelerations or any(rate(q) in asked for q in linkage.unknowns)
    sensitivities = [p for p in linkage.parameters if any(sensitivity_symbol(q, p) in asked for q in linkage.unknowns)]
    dynamic = set(getattr(linkage, "dynamic_outputs", ()))
    dynamics = any(o in dynamic for _, outputs, _ in functions for o in outputs)
    return {f"{stem}.tex": latex_document(linkage, title, velocities=velocities or dynamics,
                                          accelerations=accelerations or dynamics, sensitivities=sensitivities,
                                          dynamics=dynamics, form=form)}
