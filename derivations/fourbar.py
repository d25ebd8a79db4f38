"""The four-bar, derived step by step as in the MBSymba (Maple) worksheet.

Run ``python derivations/fourbar.py`` to rewrite ``generated/fourbar.py`` (a
NumPy-only solver) and ``generated/fourbar.tex`` (the equations).  The output
is byte for byte reproducible; ``tests/test_generated.py`` checks it.
"""
from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

from symlink import (coordinates, fourbar, latex_document, lengths, Linkage, Loop, numpy_module, Vector,
                     write_generated)

GENERATED = Path(__file__).resolve().parent.parent / "generated"
REGENERATE = "python derivations/fourbar.py"


def derive() -> dict[str, str]:
    """Every generated file of the four-bar: name -> text."""
    # Definition of the vectors: the crank rotates by q = theta, coupler and
    # rocker by beta and phi, the frame is fixed ("ground").
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, d = lengths("a b c d")
    AB = Vector(a, theta, "AB")   # crank
    BC = Vector(b, beta, "BC")    # coupler
    DC = Vector(c, phi, "DC")     # rocker
    AD = Vector(d, 0, "AD")       # frame

    # Closing the vector loop: this closure vector must be null.
    closure = Loop(AD + DC - BC - AB, name="ABCD")
    x, y = closure.equations()
    assert sp.expand(x - (d + c * sp.cos(phi) - b * sp.cos(beta) - a * sp.cos(theta))) == 0

    # Solve for the coupler and rocker angles as functions of the crank angle:
    # the loop is case 3 (two unknown angles), solved in closed form with the
    # assembly branch, not with solve() and its RootOf.
    linkage = Linkage("fourbar", [closure], inputs=[theta], unknowns=[beta, phi])
    assert [step.case.name for step in linkage.plan] == ["3"]

    # Differentiate: velocities and accelerations, linear in the unknown rates.
    linkage.velocities, linkage.accelerations

    # The catalog's four-bar is this same linkage, with named points and roles.
    catalog = fourbar()
    assert catalog.positions == linkage.positions
    angles = ["coupler", "rocker"]
    rates = ["coupler_speed", "rocker_speed"]
    accels = ["coupler_accel", "rocker_accel"]
    joints = [f"{p}_{axis}" for p in "BC" for axis in "xy"]
    solver = numpy_module([
        ("positions", catalog.program(angles), "Coupler and rocker angles (rad) of the four-bar."),
        ("velocities", catalog.program(angles + rates + ["singular"]),
         "Angles and angular speeds (rad/s); singular: at a toggle, where the speeds are not finite."),
        ("accelerations", catalog.program(angles + rates + accels + ["transmission", "singular"]),
         "Angles, angular speeds and accelerations (rad/s^2), the transmission angle, and singular."),
        ("joints", catalog.program(joints), "Joint positions B and C (the pivots are A = (0, 0), D = (d, 0))."),
    ], title="Four-bar solver: a e^{i theta} + b e^{i beta} = d + c e^{i phi}; branch +1 puts C left of B->D.",
        regenerate=REGENERATE)
    tex = latex_document(catalog, "Four-bar linkage")
    return {"fourbar.py": solver, "fourbar.tex": tex}


def main() -> int:
    return write_generated(derive(), GENERATED)


if __name__ == "__main__":
    sys.exit(main())
