"""The slider-crank with offset, derived step by step in the worksheet style of derivations/fourbar.py.

Run ``python derivations/slider_crank.py`` to rewrite ``generated/slider_crank.py``
(a NumPy-only solver) and ``generated/slider_crank.tex`` (the equations).  The
output is byte for byte reproducible; ``tests/test_generated.py`` checks it.
"""
from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

from symlink import (coordinates, kinematics_module, latex_document, lengths, Linkage, Loop, slider_crank, Vector,
                     write_generated)

GENERATED = Path(__file__).resolve().parent.parent / "generated"
REGENERATE = "python derivations/slider_crank.py"


def derive() -> dict[str, str]:
    """Every generated file of the slider-crank: name -> text."""
    # The crank turns by theta and the connecting rod by beta; the slider pin
    # travels along the line y = offset, at x = s.  The offset may be zero or
    # negative, so it is a real symbol, not a length.
    theta, beta, s = coordinates("theta beta s")
    a, b = lengths("a b")
    offset = sp.Symbol("offset", real=True)
    AB = Vector(a, theta, "AB")             # crank
    BC = Vector(b, beta, "BC")              # connecting rod
    AS = Vector(s, 0, "AS")                 # slider travel: its length is the unknown
    SC = Vector(offset, sp.pi / 2, "SC")    # the guide's offset, at a fixed angle

    # a e^{i theta} + b e^{i beta} = s + i offset
    closure = Loop(AB + BC - SC - AS, name="ABC")
    x, y = closure.equations()
    assert sp.expand(x - (a * sp.cos(theta) + b * sp.cos(beta) - s)) == 0
    assert sp.expand(y - (a * sp.sin(theta) + b * sp.sin(beta) - offset)) == 0

    # A length and another vector's angle are unknown: case 2b, two
    # assemblies; branch +1 is the one with the larger s.
    linkage = Linkage("slider-crank", [closure], inputs=[theta], unknowns=[beta, s])
    assert [step.case.name for step in linkage.plan] == ["2b"]

    catalog = slider_crank()
    assert catalog.positions == linkage.positions
    solver = kinematics_module(
        catalog, ["conrod", "slider"], ["B_x", "B_y", "C_x", "C_y"],
        title="Slider-crank solver: a e^{i theta} + b e^{i beta} = s + i offset; branch +1 has the larger s.",
        regenerate=REGENERATE, joints_doc="Crank pin B and slider pin C (the crank pivot A is the origin).")
    tex = latex_document(catalog, "Slider-crank with offset")
    return {"slider_crank.py": solver, "slider_crank.tex": tex}


def main() -> int:
    return write_generated(derive(), GENERATED)


if __name__ == "__main__":
    sys.exit(main())
