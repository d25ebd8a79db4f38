"""The benchmark's pylinkage four-bar: one linkage of the workload as pylinkage builds and simulates it.

pylinkage (``pip install 'symlink-kinematics[bench]'``) simulates a linkage whose crank turns by a
fixed step from where it is assembled, each position continuing from the one before (the nearest of
the dyad's two solutions).  So its workload is its own: for each sweep of the benchmark whose crank
turns fully, as many evenly spaced angles over a turn, starting on the sweep's branch
(:func:`pylinkage_sweeps`).
"""
from __future__ import annotations

import math

import numpy

__all__ = ["pylinkage_fourbar", "even_angles"]


def even_angles(start: float, count: int) -> tuple[numpy.ndarray, float]:
    """``count`` crank angles a turn apart evenly from ``start`` (the angles pylinkage steps through), and the step."""
    step = 2 * math.pi / count
    return start + step * numpy.arange(count), step


def pylinkage_fourbar(sweep):
    """``(linkage, crank, step)``: the pylinkage four-bar of ``sweep`` (scalar lengths, evenly spaced angles).

    Joints: ground A = (0, 0) and D = (d, 0), the crank's B, the dyad's C; C starts where the branch
    puts it one step before the first angle, so that the first position simulated is the first angle's.
    """
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import RRRDyad
    from pylinkage.simulation import Linkage

    a, b, c, d = (float(x) for x in sweep.lengths)
    branch = float(sweep.branch)
    step = float(sweep.theta[1] - sweep.theta[0]) if len(sweep.theta) > 1 else 2 * math.pi
    before = float(sweep.theta[0]) - step
    bx, by = a * math.cos(before), a * math.sin(before)
    ux, uy = d - bx, -by
    distance = math.hypot(ux, uy)
    along = (b * b - c * c + distance * distance) / (2 * distance)
    height = branch * math.sqrt(max(b * b - along * along, 0.0))
    cx, cy = bx + (along * ux - height * uy) / distance, by + (along * uy + height * ux) / distance
    ground_a, ground_d = Ground(0.0, 0.0, name="A"), Ground(d, 0.0, name="D")
    crank = Crank(anchor=ground_a, radius=a, angular_velocity=step, initial_angle=before, name="B")
    dyad = RRRDyad(crank.output, ground_d, distance1=b, distance2=c, x=cx, y=cy, name="C")
    return Linkage([ground_a, ground_d, crank, dyad], name=sweep.name), crank, step
