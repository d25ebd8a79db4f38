"""The Stephenson II six-bar, which has no loop-by-loop closed form, in the worksheet style of derivations/fourbar.py.

Run ``python derivations/stephenson2.py`` to rewrite ``generated/stephenson2.py``
(a NumPy-only Newton solver with the symbolic Jacobian) and
``generated/stephenson2.tex`` (the closure, Jacobian and rate systems).  The
output is byte for byte reproducible; ``tests/test_generated.py`` checks it.
"""
from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

from symlink import (Linkage, Loop, Vector, closure_system, coordinates, lengths, newton_document, numeric_module,
                     solve_plan, stephenson2, write_generated)

GENERATED = Path(__file__).resolve().parent.parent / "generated"
REGENERATE = "python derivations/stephenson2.py"


def derive() -> dict[str, str]:
    """Every generated file of the Stephenson II six-bar: name -> text."""
    theta, beta, mu, phi, eta = coordinates("theta beta mu phi eta")
    a, b, c, d, e, f, g, h = lengths("a b c d e f g h")
    alpha, delta = sp.symbols("alpha delta", real=True)
    AB = Vector(a, theta, "AB")                                          # crank, about A
    BC, BE = Vector(b, beta, "BC"), Vector(e, beta + alpha, "BE")        # ternary coupler BCE
    DF, DH = Vector(f, phi, "DF"), Vector(h, phi + delta, "DH")          # ternary rocker DFH, about D
    CF, EH = Vector(c, mu, "CF"), Vector(g, eta, "EH")                   # binary links
    AD = Vector(d, 0, "AD")                                              # frame

    outer = Loop(AB + BC + CF - DF - AD, name="ABCFD")
    inner = Loop(AB + BE + EH - DH - AD, name="ABEHD")

    # Three unknowns in each loop, whichever is taken first: no closed form.
    linkage = Linkage("stephenson2", [outer, inner], inputs=[theta], unknowns=[beta, mu, phi, eta],
                      parameters=[a, b, c, d, e, f, g, h, alpha, delta])
    assert not linkage.has_closed_form
    assert [len(loop.unknowns_among(linkage.unknowns)) for loop in linkage.loops] == [3, 3]
    assert not solve_plan(linkage).closed_form

    # Newton's method on all four closure equations, with the symbolic
    # Jacobian; the rates solve linear systems with the same matrix.
    system = closure_system(linkage)
    assert system.jacobian.shape == (4, 4)
    assert system.jacobian[0, 1] == -c * sp.sin(mu)   # d(x of ABCFD)/d(mu)

    catalog = stephenson2()
    assert closure_system(catalog).residuals == system.residuals
    solver = numeric_module(
        catalog, title="Stephenson II six-bar: Newton's method on loops ABCFD and ABEHD over a crank sweep.",
        regenerate=REGENERATE)
    tex = newton_document(catalog, "Stephenson II six-bar")
    return {"stephenson2.py": solver, "stephenson2.tex": tex}


def main() -> int:
    return write_generated(derive(), GENERATED)


if __name__ == "__main__":
    sys.exit(main())
