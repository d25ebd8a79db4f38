"""Theo Jansen's strandbeest leg: three four-bar-like loops in a chain, in the style of derivations/fourbar.py.

Run ``python derivations/jansen.py`` to rewrite ``generated/jansen.py`` (a
NumPy-only solver) and ``generated/jansen.tex`` (the equations).  The output is
byte for byte reproducible; ``tests/test_generated.py`` checks it.

The lengths are Jansen's "holy numbers" (strandbeest.com; the Wikipedia
article "Jansen's linkage"): see ``symlink.mechanism.catalog.JANSEN_HOLY_NUMBERS``.
"""
from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

from symlink import (coordinates, jansen, kinematics_module, latex_document, lengths, Linkage, Loop, Vector,
                     write_generated)

GENERATED = Path(__file__).resolve().parent.parent / "generated"
REGENERATE = "python derivations/jansen.py"


def derive() -> dict[str, str]:
    """Every generated file of the Jansen leg: name -> text."""
    theta, phi, beta, mu, psi, eta, kappa = coordinates("theta phi beta mu psi eta kappa")
    a, b, c, d, f, g, i, j, k, l, m = lengths("a b c d f g i j k l m")
    alpha, gamma = sp.symbols("alpha gamma", real=True)
    # The crank AB turns about the axle A; the fixed pivot D sits a to the left of A and l below it.
    AB = Vector(m, theta, "AB")
    ADx, ADy = Vector(a, sp.pi, "ADx"), Vector(l, -sp.pi / 2, "ADy")
    # The upper triangle DCE turns about D: DC = b, and DE = d, alpha ahead of DC (alpha is the corner
    # angle opposite Jansen's side e, from the law of cosines; see catalog.jansen_parameters).
    DC, DE = Vector(b, phi, "DC"), Vector(d, phi + alpha, "DE")
    # The links j and k join the crank pin B to C and to F, the end of the lower rocker DF = c.
    BC, BF, DF = Vector(j, beta, "BC"), Vector(k, mu, "BF"), Vector(c, psi, "DF")
    # The lower triangle FGH (g, i and the angle gamma opposite h) hangs from F and is tied to E by f = EG.
    FG, FH, EG = Vector(g, eta, "FG"), Vector(i, eta + gamma, "FH"), Vector(f, kappa, "EG")

    # Three loops, each a four-bar with two unknown angles (case 3), in a chain: the first gives
    # phi (so DE), the second psi (so F); the third closes the leg through E and F.
    upper = Loop(ADx + ADy + DC - BC - AB, name="ABCD")
    lower = Loop(AB + BF - DF - ADy - ADx, name="ABFD")
    legs = Loop(DF + FG - EG - DE, name="DFGE")
    linkage = Linkage("jansen", [upper, lower, legs], inputs=[theta], unknowns=[phi, beta, mu, psi, eta, kappa],
                      parameters=[a, b, c, d, f, g, i, j, k, l, m, alpha, gamma])
    assert [(step.loop.name, step.case.name) for step in linkage.plan] == [
        ("ABCD", "3"), ("ABFD", "3"), ("DFGE", "3")]

    catalog = jansen()
    assert catalog.positions == linkage.positions
    solver = kinematics_module(
        catalog, ["upper_rocker", "upper_link", "lower_link", "lower_rocker", "leg", "tie"],
        [f"{p}_{axis}" for p in "BCEFGH" for axis in "xy"],
        title="Theo Jansen leg solver: loops ABCD and ABFD from the crank, then DFGE; foot H.",
        regenerate=REGENERATE,
        joints_doc="Joints B, C, E, F, G and the foot H (the pivots are A = (0, 0) and D = (-a, -l)).")
    tex = latex_document(catalog, "Theo Jansen leg")
    return {"jansen.py": solver, "jansen.tex": tex}


def main() -> int:
    return write_generated(derive(), GENERATED)


if __name__ == "__main__":
    sys.exit(main())
