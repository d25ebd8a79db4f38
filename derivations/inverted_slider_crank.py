"""The inverted slider-crank (crank-shaper, Whitworth quick return), in the worksheet style of derivations/fourbar.py.

Run ``python derivations/inverted_slider_crank.py`` to rewrite
``generated/inverted_slider_crank.py`` (a NumPy-only solver) and
``generated/inverted_slider_crank.tex`` (the equations).  The output is byte
for byte reproducible; ``tests/test_generated.py`` checks it.
"""
from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

from symlink import (coordinates, inverted_slider_crank, kinematics_module, latex_document, lengths, Linkage, Loop,
                     Vector, write_generated)

GENERATED = Path(__file__).resolve().parent.parent / "generated"
REGENERATE = "python derivations/inverted_slider_crank.py"


def derive() -> dict[str, str]:
    """Every generated file of the inverted slider-crank: name -> text."""
    # The crank AB turns by theta about A; a block pinned at B slides on the
    # rocker, which turns by phi about D = (d, 0).  The block's distance from
    # D along the rocker, r, is a length that changes with time.
    theta, phi, r = coordinates("theta phi r")
    a, d = lengths("a d")
    AB = Vector(a, theta, "AB")   # crank
    DB = Vector(r, phi, "DB")     # rocker, up to the sliding block
    AD = Vector(d, 0, "AD")       # frame

    # a e^{i theta} = d + r e^{i phi}
    closure = Loop(AB - DB - AD, name="ABD")
    x, y = closure.equations()
    assert sp.expand(x - (a * sp.cos(theta) - r * sp.cos(phi) - d)) == 0

    # Both unknowns belong to the vector DB: case 2a, one assembly (r >= 0).
    linkage = Linkage("inverted-slider-crank", [closure], inputs=[theta], unknowns=[phi, r])
    assert [step.case.name for step in linkage.plan] == ["2a"]

    catalog = inverted_slider_crank()
    assert catalog.positions == linkage.positions
    solver = kinematics_module(
        catalog, ["rocker", "slider"], [],
        title="Inverted slider-crank solver: a e^{i theta} = d + r e^{i phi}; one assembly, r >= 0.",
        regenerate=REGENERATE)
    tex = latex_document(catalog, "Inverted slider-crank (crank-shaper, Whitworth)")
    return {"inverted_slider_crank.py": solver, "inverted_slider_crank.tex": tex}


def main() -> int:
    return write_generated(derive(), GENERATED)


if __name__ == "__main__":
    sys.exit(main())
