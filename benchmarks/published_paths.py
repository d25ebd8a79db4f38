"""Published path-synthesis problems, stated as published, solved with symlink, printed beside the published results.

Run from the repository root (not a test; SciPy needed)::

    python benchmarks/published_paths.py

**Morgan and Wampler's Problem 7** (A. P. Morgan and C. W. Wampler, "Solving a Planar Four-Bar
Design Problem Using Continuation", ASME Journal of Mechanical Design 112 (1990) 544-550), as
restated with its numbers in the documentation of PHCpack (J. Verschelde,
``src/Python/PHCpy3/doc/source/fourbar.rst``, section "visualization of a straight line design",
https://github.com/janverschelde/PHCpack): five precision points on a straight line, the fixed
pivots at (0, 0) and (1, 0), no prescribed timing.  The unknowns are the rotations of the
coupler from the first point to the other four and the two moving pivots ``x`` and ``y`` in the
first position, relative to the coupler point; the equations (one per point after the first,
per dyad) are

    ``(d_j^T R_j - d_0^T) x + (d_j^T d_j - d_0^T d_0) / 2 = 0``,
    ``((d_j - a)^T R_j - (d_0 - a)^T) y + (d_j^T d_j - d_0^T d_0) / 2 - a^T (d_j - d_0) = 0``.

Published results: 36 solutions for general points, 33 for these, "Of those 33 solutions, 15
are real", and "Not every real solution leads to a valid design": "the four angles computed
from the cosine and sine coordinates must be ordered, so that the precision points are reached
the same order as they are listed" (the coupler's rotations; no count of such designs is given).  The published objective is exact: every solution passes through the five
points, a sum of squared distances of 0.

What this script does with it:

1. finds the real solutions of the published equations by Newton's method from many random
   starts (written here from the equations above, independently of symlink) and counts the
   distinct ones (published: 15);
2. turns each into a symlink four-bar (crank pivot (0, 0), ground 1 along x) and evaluates
   symlink's closed-form coupler point at each point's crank angle, on the branch that
   reaches it: the sum of squared distances to the targets must be 0 to rounding, which ties
   symlink's conventions to the published formulation;
3. counts the solutions whose coupler rotations are in the points' order (the published
   condition), and checks each with :func:`symlink.synthesis.path.check_design`, symlink's
   stricter condition for a crank-driven design (every point on one branch, the crank turning
   one way from point to point, no toggle between them);
4. runs :func:`symlink.synthesis.path.synthesize_path` on the same points without timing.
   It searches the four-bar's whole design space (the pivots are free), a relaxation of the
   published statement, which fixes them; its objective is printed beside the published one.

**A nine-point problem** (the largest number of points a four-bar's coupler curve can be made
to pass through exactly; complete solution: C. W. Wampler, A. P. Morgan, A. J. Sommese,
"Complete Solution of the Nine-Point Path Synthesis Problem for Four-Bar Linkages", ASME J.
Mechanical Design 114 (1992) 153-159): the nine points of the example "Nine point path
synthesis problem" by P. Breiding, A. Eckhardt and S. Timme in the HomotopyContinuation.jl
documentation (``content/examples/9point.md`` of
https://github.com/JuliaHomotopyContinuation/juliahomotopycontinuation.github.io), given there
as complex numbers ``x + i y`` ("coupler points in isotropic coordinates").  Published: 8652
solutions for general points (1442 up to relabelling and Roberts cognates); the page animates
the third real four-bar it finds for these points (``F = fourbars[3])``, with a stray
parenthesis, a misprint), so exact real designs exist (their number is not printed).  symlink's ``synthesize_path`` is run on the points without timing (points reached
in their order, crank turning one way), and its sum of squared distances printed.

Not reproduced: the classic optimisation benchmarks of Cabrera, Simon and Prado (2002),
Kunjur and Krishnamurty (1997), Acharyya and Mandal (2009) and the comparison of Sedano et al.
(2012).  Their pages were found, but only their opening text could be read with the tools of
this work, not the tables of target points, bounds and best objective values; no number of
theirs is typed here from memory.
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from symlink.synthesis.path import PathDesign, check_design, fourbar_design, synthesize_path  # noqa: E402

#: Problem 7 of Morgan and Wampler (1990): the five precision points, as PHCpack's documentation copies them.
MORGAN_WAMPLER_POINTS = numpy.array([[0.50, 1.06], [-0.83, -0.27], [-0.34, 0.22], [-0.13, 0.43], [0.22, 0.78]])
#: The second fixed pivot (the first is the origin), "typically set to be (1, 0)" in the same documentation.
MORGAN_WAMPLER_PIVOT = numpy.array([1.0, 0.0])
#: Published: solutions of the polynomial system for these points, and how many are real.
MORGAN_WAMPLER_SOLUTIONS = 33
MORGAN_WAMPLER_REAL = 15


def _rotated_back(t: numpy.ndarray, v: numpy.ndarray) -> numpy.ndarray:
    """``R(t)^T v`` for a batch of angles t, as rows."""
    c, s = numpy.cos(t), numpy.sin(t)
    return numpy.stack([c * v[0] + s * v[1], -s * v[0] + c * v[1]], axis=-1)


def _rotated_back_slope(t: numpy.ndarray, v: numpy.ndarray) -> numpy.ndarray:
    """``d/dt R(t)^T v``."""
    c, s = numpy.cos(t), numpy.sin(t)
    return numpy.stack([-s * v[0] + c * v[1], -c * v[0] - s * v[1]], axis=-1)


def dyad_equations(z: numpy.ndarray, points: numpy.ndarray, pivot: numpy.ndarray):
    """The published equations and their Jacobian for a batch of unknowns ``z = (x1, x2, y1, y2, t1..t4)`` (rows)."""
    d, a = points, pivot
    x, y, t = z[:, 0:2], z[:, 2:4], z[:, 4:]
    count = len(d) - 1
    values = numpy.zeros((len(z), 2 * count))
    jacobian = numpy.zeros((len(z), 2 * count, 4 + count))
    for j in range(1, count + 1):
        row_x = _rotated_back(t[:, j - 1], d[j]) - d[0]
        values[:, j - 1] = numpy.sum(row_x * x, axis=1) + (d[j] @ d[j] - d[0] @ d[0]) / 2
        jacobian[:, j - 1, 0:2] = row_x
        jacobian[:, j - 1, 3 + j] = numpy.sum(_rotated_back_slope(t[:, j - 1], d[j]) * x, axis=1)
        row_y = _rotated_back(t[:, j - 1], d[j] - a) - (d[0] - a)
        values[:, count + j - 1] = numpy.sum(row_y * y, axis=1) + (d[j] @ d[j] - d[0] @ d[0]) / 2 - a @ (d[j] - d[0])
        jacobian[:, count + j - 1, 2:4] = row_y
        jacobian[:, count + j - 1, 3 + j] = numpy.sum(_rotated_back_slope(t[:, j - 1], d[j] - a) * y, axis=1)
    return values, jacobian


def real_solutions(points: numpy.ndarray, pivot: numpy.ndarray, starts: int = 20000, seed: int = 1,
                   steps: int = 80) -> list[numpy.ndarray]:
    """Distinct real solutions of the published equations: Newton's method (steps capped at length 1) from random starts."""
    rng = numpy.random.default_rng(seed)
    count = len(points) - 1
    z = numpy.concatenate([rng.normal(0.0, 2.0, (starts, 4)), rng.uniform(-math.pi, math.pi, (starts, count))], axis=1)
    for _ in range(steps):
        values, jacobian = dyad_equations(z, points, pivot)
        with numpy.errstate(all="ignore"):
            step = numpy.linalg.solve(jacobian + 1e-12 * numpy.eye(4 + count), -values[..., None])[..., 0]
            step = numpy.where(numpy.isfinite(step), step, 0.0)
            length = numpy.linalg.norm(step, axis=1, keepdims=True)
            z = z + numpy.where(length > 1, step / length, step)
    values, _ = dyad_equations(z, points, pivot)
    with numpy.errstate(invalid="ignore"):
        solved = numpy.all(numpy.isfinite(z), axis=1) & (numpy.max(numpy.abs(values), axis=1) < 1e-11)
    found: list[numpy.ndarray] = []
    for row in z[solved]:
        row = row.copy()
        row[4:] = numpy.angle(numpy.exp(1j * row[4:]))
        if not any(numpy.max(numpy.abs(row - other)) < 1e-6 for other in found):
            found.append(row)
    return found


def design_from_solution(solution: numpy.ndarray, points: numpy.ndarray,
                         pivot: numpy.ndarray) -> tuple[PathDesign, numpy.ndarray, numpy.ndarray, float]:
    """A published solution as a symlink four-bar: (design on branch +1, crank angles, branch at each point, objective).

    The moving pivots in position j are ``d_j + R(t_j) x`` and ``d_j + R(t_j) y``; the crank
    angle is the direction of the first; the branch at each point is the one on which
    symlink's coupler point reaches the target; the objective is the sum over the points of
    the squared distance from symlink's coupler point (on that branch) to the target.
    """
    x, y = solution[0:2], solution[2:4]
    t = numpy.concatenate([[0.0], solution[4:]])
    c, s = numpy.cos(t), numpy.sin(t)
    B = points + numpy.stack([c * x[0] - s * x[1], s * x[0] + c * x[1]], axis=1)
    C = points + numpy.stack([c * y[0] - s * y[1], s * y[0] + c * y[1]], axis=1)
    crank, rocker = float(numpy.hypot(*B[0])), float(numpy.hypot(*(C[0] - pivot)))
    coupler = float(numpy.hypot(*(C[0] - B[0])))
    along = (C[0] - B[0]) / coupler
    offset = points[0] - B[0]
    u, v = float(offset @ along), float(offset @ numpy.array([-along[1], along[0]]))
    design = fourbar_design((0.0, 0.0), math.atan2(pivot[1], pivot[0]), (crank, coupler, rocker,
                                                                          float(numpy.hypot(*pivot))), (u, v))
    theta = numpy.arctan2(B[:, 1], B[:, 0]) - design.frame
    branches = numpy.zeros(len(points), dtype=int)
    objective = 0.0
    for j, angle in enumerate(theta):
        squared = {}
        for branch in (1, -1):
            reached = fourbar_design(design.crank_pivot, design.frame, design.lengths, (u, v), branch).points([angle])
            squared[branch] = float(numpy.sum((reached[0] - points[j]) ** 2))
        branches[j] = min(squared, key=lambda b: squared[b] if math.isfinite(squared[b]) else math.inf)
        objective += squared[branches[j]]
    return design, theta, branches, objective


def ordered_angles(theta: numpy.ndarray) -> list[numpy.ndarray]:
    """The crank angles unwrapped to turn one way (each direction), where that takes less than a full turn."""
    found = []
    for direction in (1, -1):
        steps = numpy.mod(direction * numpy.diff(theta), 2 * math.pi)
        if numpy.sum(steps) < 2 * math.pi:
            found.append(theta[0] + direction * numpy.concatenate([[0.0], numpy.cumsum(steps)]))
    return found


def validity(design: PathDesign, theta: numpy.ndarray, branches: numpy.ndarray, points: numpy.ndarray) -> str:
    """'valid' when symlink's check_design accepts the design on one branch, in order; else why not."""
    if len(set(branches.tolist())) > 1:
        return "points on both branches"
    design = fourbar_design(design.crank_pivot, design.frame, design.lengths, design.coupler_point, int(branches[0]))
    reasons = []
    for angles in ordered_angles(theta):
        try:
            check_design(design, points, angles, max_link_ratio=math.inf)
            return "valid"
        except ValueError as why:
            reasons.append(str(why))
    return reasons[0] if reasons else "the points are not in order around the crank's turn"


def morgan_wampler(starts: int) -> None:
    points, pivot = MORGAN_WAMPLER_POINTS, MORGAN_WAMPLER_PIVOT
    print("Morgan & Wampler (1990) Problem 7: five points on a line, fixed pivots (0, 0) and (1, 0), no timing")
    began = time.perf_counter()
    solutions = real_solutions(points, pivot, starts=starts)
    print(f"  real solutions of the published equations found from {starts} Newton starts: {len(solutions)} "
          f"(published: {MORGAN_WAMPLER_REAL} real of {MORGAN_WAMPLER_SOLUTIONS})  [{time.perf_counter() - began:.1f} s]")
    print(f"  {'crank':>9} {'coupler':>9} {'rocker':>9} {'u':>9} {'v':>9}  {'branches':>9}  {'objective':>9}  "
          f"{'coupler turns in order':>22}  crank-driven design")
    valid = ordered = 0
    worst = 0.0
    for solution in sorted(solutions, key=lambda s: tuple(numpy.round(s, 6))):
        design, theta, branches, objective = design_from_solution(solution, points, pivot)
        verdict = validity(design, theta, branches, points)
        in_order = bool(ordered_angles(numpy.concatenate([[0.0], solution[4:]])))
        valid += verdict == "valid"
        ordered += in_order
        worst = max(worst, objective)
        a, b, c, _ = design.lengths
        print(f"  {a:9.4f} {b:9.4f} {c:9.4f} {design.coupler_point[0]:9.4f} {design.coupler_point[1]:9.4f}  "
              f"{''.join('+' if k > 0 else '-' for k in branches):>9}  {objective:9.1e}  {'yes' if in_order else 'no':>22}  "
              f"{verdict}")
    print(f"  symlink's coupler point at the published solutions: largest sum of squared distances {worst:.1e} "
          f"(published: 0); coupler rotations in the points' order (the published condition): {ordered}; "
          f"valid crank-driven designs (symlink's check: one branch, crank turning one way, no toggle): {valid}")
    began = time.perf_counter()
    found = synthesize_path(points, designs=1)[0]
    seconds = time.perf_counter() - began
    squared = float(numpy.sum((found.points(found.theta) - points) ** 2))
    print(f"  synthesize_path without timing, pivots free (a relaxation): sum of squared distances {squared:.1e}, "
          f"largest distance / size {found.error:.1e}, crank pivot ({found.crank_pivot[0]:.4f}, "
          f"{found.crank_pivot[1]:.4f}), rocker pivot ({found.rocker_pivot[0]:.4f}, {found.rocker_pivot[1]:.4f}), "
          f"{found.grashof} [{seconds:.1f} s]")


#: The nine points of the HomotopyContinuation.jl example (real and imaginary parts as x and y).
NINE_POINTS = numpy.array([[0.8961867, -0.09802917], [1.2156535, -1.18749100], [1.5151435, -0.85449808],
                           [1.6754775, -0.48768058], [1.7138690, -0.30099232], [1.7215236, 0.03269953],
                           [1.6642029, 0.33241088], [1.4984171, 0.74435576], [1.3011834, 0.92153806]])


def nine_points(starts: int) -> None:
    print("Nine-point problem (HomotopyContinuation.jl example; Wampler, Morgan & Sommese 1992): no timing, "
          "pivots free")
    began = time.perf_counter()
    found = synthesize_path(NINE_POINTS, starts=starts, designs=1)[0]
    seconds = time.perf_counter() - began
    squared = float(numpy.sum((found.points(found.theta) - NINE_POINTS) ** 2))
    print(f"  published: exact real four-bars exist (sum of squared distances 0); synthesize_path ({starts} starts): "
          f"sum of squared distances {squared:.1e}, largest distance / size {found.error:.1e}, {found.grashof}, "
          f"lengths {tuple(round(x, 4) for x in found.lengths)} [{seconds:.1f} s]")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--starts", type=int, default=20000, help="Newton starts for the published equations")
    parser.add_argument("--nine-starts", type=int, default=8, help="synthesize_path starts for the nine points")
    options = parser.parse_args(argv)
    morgan_wampler(options.starts)
    nine_points(options.nine_starts)
    print("Not reproduced (tables not readable here): Cabrera, Simon & Prado 2002; Kunjur & Krishnamurty 1997; "
          "Acharyya & Mandal 2009; Sedano et al. 2012.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
