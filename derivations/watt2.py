"""The Watt II six-bar, two four-bars in series, in the worksheet style of derivations/fourbar.py.

Run ``python derivations/watt2.py`` to rewrite ``generated/watt2.py`` (a
NumPy-only solver) and ``generated/watt2.tex`` (the equations).  The output is
byte for byte reproducible; ``tests/test_generated.py`` checks it.
"""
from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

from symlink import (coordinates, kinematics_module, latex_document, lengths, Linkage, Loop, Vector, watt2,
                     write_generated)

GENERATED = Path(__file__).resolve().parent.parent / "generated"
REGENERATE = "python derivations/watt2.py"


def derive() -> dict[str, str]:
    """Every generated file of the Watt II six-bar: name -> text."""
    theta, beta, phi, mu, psi = coordinates("theta beta phi mu psi")
    a, b, c, d, e, f, g = lengths("a b c d e f g")
    alpha, gx, gy = sp.symbols("alpha gx gy", real=True)
    # First four-bar: crank AB, coupler BC, rocker DC about D = (d, 0).
    AB, BC, DC, AD = Vector(a, theta, "AB"), Vector(b, beta, "BC"), Vector(c, phi, "DC"), Vector(d, 0, "AD")
    # The rocker is a ternary link DCE: DE turns with DC, alpha ahead of it.
    DE = Vector(e, phi + alpha, "DE")
    # Second four-bar: coupler EF and output rocker GF about G = (gx, gy).
    EF, GF = Vector(f, mu, "EF"), Vector(g, psi, "GF")
    AG = Vector(gx, 0, "AGx") + Vector(gy, sp.pi / 2, "AGy")

    first = Loop(AD + DC - BC - AB, name="ABCD")
    second = Loop(AG + GF - EF - DE - AD, name="DEFG")

    # Each loop, in turn, has two unknown angles (case 3): the first loop
    # gives phi, which the second one then knows.
    linkage = Linkage("watt2", [first, second], inputs=[theta], unknowns=[beta, phi, mu, psi],
                      parameters=[a, b, c, d, e, f, g, alpha, gx, gy])
    assert [(step.loop.name, step.case.name) for step in linkage.plan] == [("ABCD", "3"), ("DEFG", "3")]
    assert phi in linkage.plan[1].intermediates[sp.Symbol("Wx_2", real=True)].free_symbols

    catalog = watt2()
    assert catalog.positions == linkage.positions
    solver = kinematics_module(
        catalog, ["coupler", "rocker", "coupler2", "output"], [f"{p}_{axis}" for p in "BCEF" for axis in "xy"],
        title="Watt II six-bar solver: four-bar ABCD, then DEFG driven by the ternary rocker DCE.",
        regenerate=REGENERATE,
        joints_doc="Joints B, C, E and F (the pivots are A = (0, 0), D = (d, 0), G = (gx, gy)).")
    tex = latex_document(catalog, "Watt II six-bar")
    return {"watt2.py": solver, "watt2.tex": tex}


def main() -> int:
    return write_generated(derive(), GENERATED)


if __name__ == "__main__":
    sys.exit(main())
