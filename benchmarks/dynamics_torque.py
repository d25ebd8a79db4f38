"""What the dynamics cost beside the kinematics, in the generated NumPy module and compiled (not a test).

The four-bar with all three links massive (centres off the link lines, gravity), at N crank
angles: the full kinematics (angles, their rates and accelerations), the driving torque
alone, and every dynamic force output (torque, the four pins' reactions, shaking force and
moment), each evaluated by the generated NumPy module (a :class:`symlink.numeric.solver.Solver`) and
by the compiled C loop (:class:`symlink.numeric.compiled.CompiledSolver`).  Printed: CPU nanoseconds a
value and the ratios within this one run (targets: torque at most 3x the full kinematics in
NumPy; compiled keeps its ratio to NumPy).

    python -m benchmarks.dynamics_torque [-n 1e6]
"""
from __future__ import annotations

import argparse
import math

import numpy

from benchmarks.compiled_loops import cpu_time

VALUES = dict(a=20.0, b=66.0, c=56.0, d=80.0, m2=1.0, r2=10.0, I2=5.0, m3=2.0, r3=30.0, d3=0.2, I3=40.0,
              m4=1.5, r4=28.0, I4=30.0)


def measure(n: int) -> dict[str, dict[str, float]]:
    from symlink.mechanism.catalog import fourbar
    from symlink.numeric.compiled import CompiledSolver
    from symlink.dynamics import DynamicModel, Gravity, MassProperties, dynamic_linkage
    from symlink.numeric.solver import Solver
    model = DynamicModel(fourbar(), [MassProperties("crank", "m2", "r2", 0, "I2"),
                                     MassProperties("coupler", "m3", "r3", "d3", "I3"),
                                     MassProperties("rocker", "m4", "r4", 0, "I4")], gravity=Gravity(0, -9.81))
    linkage = dynamic_linkage(model)
    kinematics = ["coupler", "rocker", "coupler_speed", "rocker_speed", "coupler_accel", "rocker_accel"]
    requests = {"full kinematics": kinematics, "torque": ["input_torque"],
                "all forces": list(linkage.force_outputs)}
    theta = numpy.linspace(0, 2 * math.pi, n)
    given = dict(VALUES, theta=theta, thetadot=10.5, thetaddot=3.0, branch=1)
    found: dict[str, dict[str, float]] = {}
    for label, outputs in requests.items():
        found[label] = {}
        for backend, make in (("numpy", Solver), ("compiled", CompiledSolver)):
            solver = make(linkage, outputs)
            solver(**given)  # loads (or compiles) once before timing
            found[label][backend] = 1e9 * cpu_time(lambda: solver(**given)) / n
    return found


def report(found: dict[str, dict[str, float]], n: int) -> str:
    lines = [f"four-bar dynamics at N={n}: CPU ns a value", f"{'request':>16} {'numpy':>9} {'compiled':>9} "
             f"{'numpy/compiled':>15}"]
    for label, times in found.items():
        lines.append(f"{label:>16} {times['numpy']:>9.1f} {times['compiled']:>9.1f} "
                     f"{times['numpy'] / times['compiled']:>15.2f}")
    base = found["full kinematics"]
    for label in ("torque", "all forces"):
        lines.append(f"{label} / full kinematics: numpy {found[label]['numpy'] / base['numpy']:.2f}x, "
                     f"compiled {found[label]['compiled'] / base['compiled']:.2f}x")
    lines.append("target: torque at most 3x the full kinematics in NumPy; compiled keeps its ratio to NumPy")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("-n", type=float, default=1e6, help="crank angles a call")
    n = int(parser.parse_args().n)
    print(report(measure(n), n))


if __name__ == "__main__":
    main()
