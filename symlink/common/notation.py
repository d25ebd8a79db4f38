r"""How symlink's own symbols are written for people, the same in every display.

The generated code names a loop's branch sign ``branch`` (one loop) or
``branch_<loop>``; the equations write it :math:`\sigma` and
:math:`\sigma_{\mathrm{ABCD}}`.  The closed forms' intermediates get their
textbook names too: loop 1's closing vector ``Wx_1, Wy_1`` is
:math:`W_{x,1}, W_{y,1}`, its scaled lengths ``rho_2_1`` are
:math:`\rho_{2,1}`.  The LaTeX printer (:mod:`symlink.codegen.latex`) and the
displays of vectors, loops, plans and scenes all use these functions, so a
branch sign looks the same wherever it appears.

>>> branch_latex("branch_ABCD"), branch_html("branch_ABCD")
('\\sigma_{\\mathrm{ABCD}}', 'σ<sub>ABCD</sub>')
>>> x = sp.Symbol("Wx_1")
>>> latex_names([x + sp.Symbol("branch")])[x]
'W_{x,1}'
"""
from __future__ import annotations

import html
import re
from typing import Iterable

import sympy as sp

__all__ = ["BRANCH", "branch_latex", "branch_html", "latex_names", "math_text"]

#: The name of the branch sign of a one-loop linkage; a loop's own is ``branch_<loop>``.
BRANCH = "branch"

_SCALED_LENGTH = re.compile(r"rho_([0-9]+)_([0-9]+)\Z")


def math_text(text: str) -> str:
    r"""``text`` (a name: letters, digits, underscores, spaces, hyphens) as upright text inside LaTeX mathematics.

    An underscore prints as one (``\_`` between ``\text`` pieces), which LaTeX and MathJax both accept.

    >>> math_text("loop_1")
    '\\text{loop}\\_\\text{1}'
    """
    return r"\_".join(r"\text{%s}" % part for part in text.split("_"))


def branch_latex(name: str) -> str:
    r"""The branch sign named ``name`` in the generated code (``branch``, ``branch_<loop>``) as LaTeX.

    >>> branch_latex("branch"), branch_latex("branch_loop_2")
    ('\\sigma', '\\sigma_{\\mathrm{loop\\_2}}')
    """
    if name == BRANCH:
        return r"\sigma"
    loop = name[len(BRANCH) + 1:].replace("_", r"\_")
    return r"\sigma_{\mathrm{%s}}" % loop


def branch_html(name: str) -> str:
    """The branch sign named ``name`` in the generated code as HTML: σ, with the loop's name as a subscript."""
    if name == BRANCH:
        return "σ"
    return f"σ<sub>{html.escape(name[len(BRANCH) + 1:])}</sub>"


#: The separator in a design sensitivity's name, ``phi__d_a`` (the scheme of :mod:`symlink.symbolic.sensitivity`, which
#: takes it from here: this module sits below it, so every display can read it).
SENSITIVITY_SEPARATOR = "__d_"


def latex_names(expressions: Iterable[sp.Basic]) -> dict[sp.Symbol, str]:
    """LaTeX names for the generated symbols among the expressions' free symbols (a ``symbol_names`` mapping).

    Branch signs print as sigma, a loop's closing vector as ``W_{x,1}``, its
    scaled lengths as ``\\rho_{2,1}`` (length 2 of loop 1), a design sensitivity
    ``phi__d_a`` as the partial derivative it is; a user's name with a double
    underscore as written (SymPy would print ``x__y`` as the power ``x^{y}``);
    every other symbol keeps SymPy's own name.

    >>> print(latex_names([sp.Symbol("phi__d_a")])[sp.Symbol("phi__d_a")])
    \\frac{\\partial \\phi}{\\partial a}
    """
    names = {}
    for symbol in set().union(*(sp.sympify(e).free_symbols for e in expressions)):
        stem, _, label = symbol.name.partition("_")
        scaled = _SCALED_LENGTH.match(symbol.name)
        if symbol.name == BRANCH or stem == BRANCH:
            names[symbol] = branch_latex(symbol.name)
        elif stem in ("Wx", "Wy") and label.isdigit():
            names[symbol] = "W_{%s,%s}" % (stem[1], label)
        elif scaled:
            names[symbol] = r"\rho_{%s,%s}" % scaled.groups()
        elif SENSITIVITY_SEPARATOR in symbol.name:
            output, _, parameter = symbol.name.rpartition(SENSITIVITY_SEPARATOR)
            names[symbol] = r"\frac{\partial %s}{\partial %s}" % (sp.latex(sp.Symbol(output)),
                                                                   sp.latex(sp.Symbol(parameter)))
        elif "__" in symbol.name:  # x__y: a name, not x to the power y
            names[symbol] = r"\mathit{%s}" % symbol.name.replace("_", r"\_")
    return names
