"""The offset inverted slider-crank, in the worksheet style of derivations/fourbar.py.

Run ``python derivations/offset_inverted_slider_crank.py`` to rewrite
``generated/offset_inverted_slider_crank.py`` (a NumPy-only solver) and
``generated/offset_inverted_slider_crank.tex`` (the equations).  The output is
byte for byte reproducible; ``tests/test_generated.py`` checks it.
"""
from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

from symlink import (coordinates, kinematics_module, latex_document, lengths, Linkage, Loop,
                     offset_inverted_slider_crank, Vector, write_generated)

GENERATED = Path(__file__).resolve().parent.parent / "generated"
REGENERATE = "python derivations/offset_inverted_slider_crank.py"


def derive() -> dict[str, str]:
    """Every generated file of the offset inverted slider-crank: name -> text."""
    # The crank AB turns by theta about A.  The rocker turns by phi about D = (d, 0); its guide does not pass
    # through D but stands off it by e: the guide's foot is T, a quarter turn ahead of the guide's direction.
    # The block pinned at B slides along the guide, s from T.
    theta, phi, s = coordinates("theta phi s")
    a, d, e = lengths("a d e")
    AB = Vector(a, theta, "AB")              # crank
    AD = Vector(d, 0, "AD")                  # frame
    DT = Vector(e, phi + sp.pi / 2, "DT")    # the offset, turning with the rocker
    TB = Vector(s, phi, "TB")                # along the guide, up to the block

    # a e^{i theta} = d + e e^{i (phi + pi/2)} + s e^{i phi}, walked A -> B -> T -> D -> A
    closure = Loop(AB - TB - DT - AD, name="ABTD")
    x, y = closure.equations()
    assert sp.expand(x - (a * sp.cos(theta) - s * sp.cos(phi) + e * sp.sin(phi) - d)) == 0

    # phi turns two vectors (DT and TB) and s is the length of one of them: the two unknowns sit on one turning
    # body, case 2c.  Its closed form: B lies at distance sqrt(e^2 + s^2) from D, so s = +-sqrt(|DB|^2 - e^2)
    # (the guide is a tangent from B to the circle of radius e about D), two assemblies, branch +1 the larger s.
    linkage = Linkage("offset-inverted-slider-crank", [closure], inputs=[theta], unknowns=[phi, s])
    assert [step.case.name for step in linkage.plan] == ["2c"]

    catalog = offset_inverted_slider_crank()
    assert catalog.positions == linkage.positions
    solver = kinematics_module(
        catalog, ["rocker", "slider"], ["T_x", "T_y"],
        title="Offset inverted slider-crank solver: a e^{i theta} = d + e e^{i (phi + pi/2)} + s e^{i phi}.",
        regenerate=REGENERATE, joints_doc="The guide's foot T.")
    tex = latex_document(catalog, "Offset inverted slider-crank")
    return {"offset_inverted_slider_crank.py": solver, "offset_inverted_slider_crank.tex": tex}


def main() -> int:
    return write_generated(derive(), GENERATED)


if __name__ == "__main__":
    sys.exit(main())
