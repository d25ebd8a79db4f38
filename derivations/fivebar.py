"""The five-bar with two inputs (two degrees of freedom), in the worksheet style of derivations/fourbar.py.

Run ``python derivations/fivebar.py`` to rewrite ``generated/fivebar.py`` (a
NumPy-only solver) and ``generated/fivebar.tex`` (the equations).  The output
is byte for byte reproducible; ``tests/test_generated.py`` checks it.
"""
from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

from symlink import (coordinates, fivebar, kinematics_module, latex_document, lengths, Linkage, Loop, Vector,
                     write_generated)

GENERATED = Path(__file__).resolve().parent.parent / "generated"
REGENERATE = "python derivations/fivebar.py"


def derive() -> dict[str, str]:
    """Every generated file of the five-bar: name -> text."""
    # Two driven cranks, AB about A = (0, 0) and ED about E = (d, 0); the
    # links BC and DC meet at C.
    theta, psi, beta, phi = coordinates("theta psi beta phi")
    a, b, c, d, e = lengths("a b c d e")
    AB, BC, DC = Vector(a, theta, "AB"), Vector(b, beta, "BC"), Vector(c, phi, "DC")
    ED, AE = Vector(e, psi, "ED"), Vector(d, 0, "AE")

    # a e^{i theta} + b e^{i beta} = d + e e^{i psi} + c e^{i phi}
    closure = Loop(AE + ED + DC - BC - AB, name="ABCDE")
    # With both crank angles given, the loop has two unknown angles: case 3.
    linkage = Linkage("fivebar", [closure], inputs=[theta, psi], unknowns=[beta, phi])
    assert [step.case.name for step in linkage.plan] == ["3"]
    # Each rate is a sum of the two inputs' contributions.
    assert {sp.Symbol("thetadot", real=True), sp.Symbol("psidot", real=True)} <= linkage.velocities[
        sp.Symbol("phidot", real=True)].free_symbols

    catalog = fivebar()
    assert catalog.positions == linkage.positions
    solver = kinematics_module(
        catalog, ["coupler", "coupler2"], ["B_x", "B_y", "C_x", "C_y", "D_x", "D_y"],
        title="Five-bar solver: a e^{i theta} + b e^{i beta} = d + e e^{i psi} + c e^{i phi}; "
              "branch +1 puts C left of B->D.",
        regenerate=REGENERATE, joints_doc="Joints B, C and D (the pivots are A = (0, 0) and E = (d, 0)).")
    tex = latex_document(catalog, "Five-bar linkage with two inputs")
    return {"fivebar.py": solver, "fivebar.tex": tex}


def main() -> int:
    return write_generated(derive(), GENERATED)


if __name__ == "__main__":
    sys.exit(main())
