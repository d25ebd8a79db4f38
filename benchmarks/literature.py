"""The literature's classical path-synthesis problems, each with its own objective, solved by symlink 20 times.

Run from the repository root (SciPy needed)::

    python -m benchmarks.synthesis --literature            # 20 seeds a problem, the table
    python -m benchmarks.literature --seeds 5 --problems case2,case4
    python -m benchmarks.literature --method general       # symlink.synthesis.general on every problem

The records, from an actual run, are in ``docs/explanation/synthesis_benchmark.md``.

**Source.** The five problems, their target points, prescribed crank angles, variable bounds,
objective and constraints are those of the MATLAB code of S. Nguyen-Van, Q. X. Lieu, N.
Xuan-Mung and T. T. N. Nguyen, "A New Study on Optimization of Four-Bar Mechanisms Based on a
Hybrid-Combined Differential Evolution and Jaya Algorithm", Symmetry 14 (2022) 381,
https://doi.org/10.3390/sym14020381, published with its result files in the repository
https://github.com/sy-nguyen-van/DE_Jaya_Synthesis_Four_Bar_Mechanisms (CC0 1.0; read at
commit 67acf78bd606546d1c67cf9a2d31818034d45d0e): ``CaseN/ObjfN.m`` (targets, timing,
objective), ``CaseN/ConsN.m`` with ``INDEX.m`` and ``sequence.m`` (constraints),
``Additional-functions/Mechanisms.m`` (bounds) and ``CaseN/Records_<method>_CaseN.txt`` (50
runs of each method: rows 1-50 the best objective of each run, then the best, the evaluation
budget, the worst, the mean and the standard deviation).  Only the numbers are copied here,
each next to the file it comes from; no file of the repository is shipped.

**The objective, as the code states it.** The design vector is ``x = (r1, r2, r3, r4, rcx,
rcy, x0, y0, theta0, theta2_1 ...)``: ground r1, crank r2, coupler r3, rocker r4, the coupler
point (rcx, rcy) in the coupler's frame (rcx along it), the crank pivot (x0, y0), the ground
line's angle theta0 and the crank angles from the ground line.  The coupler angle is
Freudenstein's half-angle root ``theta3 = 2 atan((-E - sqrt(E^2 - 4 D F)) / (2 D))`` with
``K1 = r1/r2``, ``K4 = r1/r3``, ``K5 = (r4^2 - r1^2 - r2^2 - r3^2) / (2 r3 r2)``,
``D = cos(theta2) - K1 + K4 cos(theta2) + K5``, ``E = -2 sin(theta2)``,
``F = K1 + (K4 - 1) cos(theta2) + K5``; the coupler point is placed as
``R(theta0) (r2 e^{i theta2} + (rcx + i rcy) e^{i theta3}) + (x0, y0)`` and the objective is the
**sum over the targets of the squared distance** from it to the target (not normalised).  That
root is symlink's assembly branch +1 (checked in ``tests/test_bench_literature.py``), so symlink
searches that branch only.  Constraints: the variable bounds; Grashof's condition (cases 1 and
4: with the crank the shortest link, a crank-rocker); cases 1 and 5 (crank angles free) the
angles, read cyclically from the smallest, increasing (the crank turns counter-clockwise
through the targets in order, less than a turn).  The MATLAB code takes the real part of a
complex root where the four-bar cannot be assembled; symlink's designs are assembled at every
target and between them (a stricter condition), and symlink asks for a crank-rocker or
double-crank (a crank that turns) where the paper asks for any Grashof linkage.

**What symlink runs.** :func:`symlink.synthesis.path.synthesize_path` for the four problems
whose frame is free (branch +1; untimed ones with ``direction=+1``; case 3 with
``free_phase=True``: its angles are equal 20 degree steps from an unknown first one), and
:func:`symlink.synthesis.general.synthesize_path` on the placed four-bar with the frame held
(case 2: crank pivot at the origin, ground along x) and the paper's bounds as the free
parameters' bounds.  Each design found is turned into the paper's vector and scored by
:func:`objective`, a line-by-line transcription of ``ObjfN.m``; a design outside the paper's
bounds or constraints is counted as infeasible, never scored.

**Rounding.** The published best of case 1 (8.8e-29) is below what double precision can
resolve: one unit in the last place of the largest coordinate (45) is 7.1e-15; the formula's
ten-odd rounded operations leave each coordinate of each point a few such units off, a sum of
squares of ~5e-27 over the six points (:func:`rounding_floor`).  Values below the floor are
printed as such, and two values below it count as equal (both exact to rounding).
"""
from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from symlink.analysis import grashof  # noqa: E402

REPOSITORY = "sy-nguyen-van/DE_Jaya_Synthesis_Four_Bar_Mechanisms"
COMMIT = "67acf78bd606546d1c67cf9a2d31818034d45d0e"
PAPER = "Nguyen-Van et al., Symmetry 14 (2022) 381"


@dataclass(frozen=True)
class Published:
    """One method's statistics over its runs, from ``CaseN/Records_<method>_CaseN.txt``.

    The file's last five rows hold (first column) the best, the evaluation budget, the worst,
    the mean and the standard deviation of the runs above them (50; 20 for mDE); the median is
    computed from the runs' rows.
    """

    method: str
    runs: int
    best: float
    median: float
    mean: float
    worst: float
    file: str
    meets_constraints: bool = True  # the recorded best design meets the paper's own constraints (checked in the test)


@dataclass(frozen=True)
class Problem:
    """A classical problem as the paper's code states it."""

    key: str
    title: str
    targets: tuple[tuple[float, float], ...]
    crank_angles: tuple[float, ...] | None  # prescribed crank angles, or None (free, one per target)
    first_angle_free: bool                  # the prescribed angles are steps from a free first angle (case 3)
    frame_free: bool                        # x0, y0 and theta0 are variables (all but case 2)
    length_bound: float                     # r1..r4 in [0, length_bound]
    offset_bound: float                     # rcx, rcy (and x0, y0) in [-offset_bound, offset_bound]
    crank_shortest: bool                    # Grashof with the crank the shortest link (else any Grashof linkage)
    ordered: bool                           # free crank angles increasing cyclically (cases 1 and 5)
    source: str                             # the files of the repository the numbers come from
    published: tuple[Published, ...] = field(default=())
    # where the published best design breaks the paper's own constraints (by the rounding of its printed digits):
    # the least objective that meets them, and how it was found (checked in tests/test_bench_literature.py)
    feasible_best: float | None = None
    remark: str = ""

    @property
    def points(self) -> numpy.ndarray:
        return numpy.array(self.targets, dtype=float)

    @property
    def best_published(self) -> Published:
        """The smallest published best whose recorded design meets the paper's constraints."""
        return min((p for p in self.published if p.meets_constraints), key=lambda p: p.best)


def _records(case: int, method: str, runs: int, best: float, mean: float, worst: float, median: float,
             meets_constraints: bool = True) -> Published:
    return Published(method, runs, best, median, mean, worst, f"Case{case}/Records_{method}_Case{case}.txt",
                     meets_constraints)


PROBLEMS = (
    # Case1/Objf1.m (Cdx, Cdy), Mechanisms.m 'Case1' (bounds 60, 60, angles [0, 2 pi]), Cons1.m (Grashof, crank
    # shortest, sequence)
    Problem("case1", "six collinear points, no timing",
            ((20.0, 20.0), (20.0, 25.0), (20.0, 30.0), (20.0, 35.0), (20.0, 40.0), (20.0, 45.0)),
            None, False, True, 60.0, 60.0, True, True,
            "Case1/Objf1.m, Case1/Cons1.m, Additional-functions/Mechanisms.m",
            (_records(1, "HCDJ", 50, 8.8352421e-29, 2.8596392e+00, 6.2500000e+01, 1.0249e-03),
             _records(1, "DE", 50, 8.7979826e-04, 7.1198401e-01, 1.3522592e+01, 3.0337e-02),
             _records(1, "Jaya", 50, 8.5738795e-03, 3.0609603e+01, 4.3750007e+02, 1.2407e+01))),
    # Case2/Objf2.m (Cdx, Cdy, Teta2), Mechanisms.m 'Case2' (bounds 50, 50; no placement), Cons2.m (Grashof)
    Problem("case2", "five points, prescribed timing",
            ((3.0, 3.0), (2.759, 3.363), (2.372, 3.663), (1.890, 3.862), (1.355, 3.943)),
            (math.pi / 6, math.pi / 4, math.pi / 3, 5 * math.pi / 12, math.pi / 2), False, False, 50.0, 50.0,
            False, False, "Case2/Objf2.m, Case2/Cons2.m, Additional-functions/Mechanisms.m",
            (_records(2, "HCDJ", 50, 1.9239227e-06, 9.6101276e-02, 4.6681741e-01, 1.3758e-01),
             _records(2, "DE", 50, 9.5748900e-04, 1.0045619e-01, 5.1897081e-01, 3.6828e-03),
             _records(2, "Jaya", 50, 9.6775475e-04, 3.5056121e-01, 3.9252582e+00, 1.2772e-01))),
    # Case3/Objf3.m (CD; teta2 = x(10) + (i-1) pi/9), Mechanisms.m 'Case3' (bounds 50, 50), Cons3.m (Grashof)
    Problem("case3", "18-point closed curve (Bulatovic et al.), 20 degree steps",
            ((0.5, 1.1), (0.4, 1.1), (0.3, 1.1), (0.2, 1.0), (0.1, 0.9), (0.05, 0.75), (0.02, 0.6), (0.0, 0.5),
             (0.0, 0.4), (0.03, 0.3), (0.1, 0.25), (0.15, 0.2), (0.2, 0.3), (0.3, 0.4), (0.4, 0.5), (0.5, 0.7),
             (0.6, 0.9), (0.6, 1.0)),
            tuple(k * math.pi / 9 for k in range(18)), True, True, 50.0, 50.0, False, False,
            "Case3/Objf3.m, Case3/Cons3.m, Additional-functions/Mechanisms.m",
            (_records(3, "HCDJ", 50, 1.6077817e-02, 3.0314304e-01, 2.5111626e+00, 6.1503e-02),
             _records(3, "DE", 50, 1.0598671e-01, 1.4681714e+00, 9.4391087e+00, 1.0280e+00),
             _records(3, "mDE", 20, 3.4016539e-02, 5.3847598e-01, 1.9937844e+00, 1.7526e-01),
             _records(3, "Jaya", 50, 1.3193569e+00, 1.7293288e+01, 8.3158381e+01, 1.2681e+01))),
    # Case4/Objf4.m (C1..C6, Teta2), Mechanisms.m 'Case4' (bounds 50, 50), Cons4.m (Grashof, crank shortest)
    Problem("case4", "six points on an arc, prescribed timing",
            ((0.0, 0.0), (1.9098, 5.8779), (6.9098, 9.5106), (13.09, 9.5106), (18.09, 5.8779), (20.0, 0.0)),
            (math.pi / 6, math.pi / 3, math.pi / 2, 2 * math.pi / 3, 5 * math.pi / 6, math.pi), False, True, 50.0,
            50.0, True, False, "Case4/Objf4.m, Case4/Cons4.m, Additional-functions/Mechanisms.m",
            (_records(4, "HCDJ", 50, 1.2162122e+00, 2.6064417e+01, 4.4212869e+02, 4.8700e+00),
             _records(4, "DE", 50, 1.2900783e+00, 7.4515674e+00, 1.4028193e+01, 5.7749e+00),
             # the recorded best mDE design breaks Cons4.m (crank not the shortest) and is not assembled at two
             # targets (ObjfN.m takes the real part of a complex root): not counted as the published best
             _records(4, "mDE", 20, 6.2107963e-01, 4.0475466e+00, 1.3721922e+01, 9.9045e-01, False),
             _records(4, "Jaya", 50, 5.6016350e+00, 2.4154431e+01, 1.4492840e+02, 1.9492e+01)),
            # Case4/x_best_HCDJ_Case4.txt: r1 = 49.99998, r2 = 1.3484315, r3 = 1.3484507, r4 = 50, so s + l - p - q
            # = +8.0e-7 > 0, which Cons4.m refuses.  The least objective with s + l <= p + q, found by least squares
            # with it held as an equality and r4 at its bound 50 (both active there):
            1.2162121387,
            "the published best design (Case4/x_best_HCDJ_Case4.txt, 1.2162125 re-scored) breaks Cons4.m's Grashof "
            "condition: s + l - p - q = +8.0e-7 at its printed digits; the least objective that meets it is "
            "1.2162121387 (Grashof's condition an equality, the rocker at its bound 50)"),
    # Case5/Objf5.m (C1..C10, C10 = C1), Mechanisms.m 'Case5' (bounds 80, 80), Cons5.m (Grashof, sequence)
    # (Issue 25 calls it "ten points on a circle": the numbers are an ellipse, semi-axes 10 and 8 about (10, 10).)
    Problem("case5", "ten points on an ellipse (the last the first again), no timing",
            ((20.0, 10.0), (17.66, 15.142), (11.736, 17.878), (5.0, 16.928), (0.60307, 12.736), (0.60307, 7.2638),
             (5.0, 3.0718), (11.736, 2.1215), (17.66, 4.8577), (20.0, 10.0)),
            None, False, True, 80.0, 80.0, False, True,
            "Case5/Objf5.m, Case5/Cons5.m, Additional-functions/Mechanisms.m",
            (_records(5, "HCDJ", 50, 4.2014375e-04, 2.3324925e+00, 9.9259430e+01, 5.9405e-03),
             _records(5, "DE", 50, 2.3369647e-03, 7.3045251e-01, 1.2529242e+01, 4.6388e-02),
             _records(5, "Jaya", 50, 4.8257144e-01, 1.3847894e+02, 8.2819476e+02, 5.7427e+01))),
)
BY_KEY = {p.key: p for p in PROBLEMS}


# --- the paper's objective and constraints, transcribed ------------------------------------------------------

def coupler_points(x: numpy.ndarray, crank_angles: numpy.ndarray, placed: bool) -> numpy.ndarray:
    """The coupler points (rows x, y) of the paper's vector at its crank angles, as ``ObjfN.m`` computes them.

    The half-angle root and its ``real(2*atan(...))`` of a complex number (where the linkage
    cannot be assembled) are MATLAB's; NumPy's complex square root and arctangent give the same.
    """
    r1, r2, r3, r4, rcx, rcy = (float(v) for v in x[:6])
    teta2 = numpy.asarray(crank_angles, dtype=float)
    k1, k4, k5 = r1 / r2, r1 / r3, (r4 ** 2 - r1 ** 2 - r2 ** 2 - r3 ** 2) / (2 * r3 * r2)
    d = numpy.cos(teta2) - k1 + k4 * numpy.cos(teta2) + k5
    e = -2 * numpy.sin(teta2)
    f = k1 + (k4 - 1) * numpy.cos(teta2) + k5
    teta3 = numpy.real(2 * numpy.arctan((-e - numpy.sqrt(e ** 2 - 4 * d * f + 0j)) / (2 * d)))
    crx = r2 * numpy.cos(teta2) + rcx * numpy.cos(teta3) - rcy * numpy.sin(teta3)
    cry = r2 * numpy.sin(teta2) + rcx * numpy.sin(teta3) + rcy * numpy.cos(teta3)
    if not placed:
        return numpy.stack([crx, cry], axis=1)
    c, s = math.cos(x[8]), math.sin(x[8])
    return numpy.stack([c * crx - s * cry + x[6], s * crx + c * cry + x[7]], axis=1)


def crank_angles_of(problem: Problem, x: numpy.ndarray) -> numpy.ndarray:
    """The crank angles the paper's vector gives: prescribed, prescribed steps from x(10), or x(10:end)."""
    if problem.crank_angles is None:
        return numpy.asarray(x[9:9 + len(problem.targets)], dtype=float)
    angles = numpy.array(problem.crank_angles)
    return x[9] + angles if problem.first_angle_free else angles


def objective(problem: Problem, x: numpy.ndarray) -> float:
    """The paper's objective: the sum over the targets of the squared distance from the coupler point (``ObjfN.m``)."""
    x = numpy.asarray(x, dtype=float)
    reached = coupler_points(x, crank_angles_of(problem, x), problem.frame_free)
    return float(numpy.sum((reached - problem.points) ** 2))


def bounds(problem: Problem) -> tuple[numpy.ndarray, numpy.ndarray]:
    """The variable bounds of ``Mechanisms.m``: lengths, then rcx, rcy (x0, y0), then the angles in [0, 2 pi]."""
    lengths, offsets = problem.length_bound, problem.offset_bound
    low, high = [0.0] * 4 + [-offsets] * 2, [lengths] * 4 + [offsets] * 2
    if problem.frame_free:
        low, high = low + [-offsets] * 2 + [0.0], high + [offsets] * 2 + [2 * math.pi]
    angles = 1 if problem.first_angle_free else (len(problem.targets) if problem.crank_angles is None else 0)
    return numpy.array(low + [0.0] * angles), numpy.array(high + [2 * math.pi] * angles)


def violations(problem: Problem, x: numpy.ndarray) -> list[str]:
    """The paper's constraints that ``x`` breaks (``ConsN.m``, ``INDEX.m``, ``sequence.m``, the bounds); [] if none."""
    x = numpy.asarray(x, dtype=float)
    broken = []
    low, high = bounds(problem)
    if x.shape != low.shape:
        return [f"the vector has {x.size} entries, the problem {low.size}"]
    if numpy.any(x < low) or numpy.any(x > high):
        broken.append("bounds")
    lengths = x[:4]
    if lengths.max() + lengths.min() - (lengths.sum() - lengths.max() - lengths.min()) > 0:
        broken.append("Grashof")
    elif problem.crank_shortest and x[1] != lengths.min():
        broken.append("crank shortest")
    if problem.ordered:
        angles = x[9:]
        start = int(numpy.argmin(angles))
        cyclic = angles[(start + numpy.arange(len(angles))) % len(angles)]
        if not numpy.all(numpy.diff(cyclic) > 0):
            broken.append("order")
    return broken


ROUNDING_ULPS = 4  # units in the last place a coordinate of the transcribed formula's coupler point may be off


def rounding_floor(problem: Problem) -> float:
    """A sum of squares double precision cannot resolve: every target off by a few ulps of the largest coordinate.

    The transcribed formula takes about ten rounded operations (a square root, an arctangent,
    sines and cosines, products and sums) from the design to the point, each off by up to half
    an ulp: :data:`ROUNDING_ULPS` ulps of the largest target coordinate, in each of the two
    coordinates of every target.
    """
    points = problem.points
    return float(2 * len(points) * (ROUNDING_ULPS * numpy.spacing(numpy.abs(points).max())) ** 2)


# --- symlink on the problems --------------------------------------------------------------------------------

def _paper_vector(problem: Problem, lengths, coupler_point, pivot, frame: float, angles) -> numpy.ndarray:
    """A four-bar (crank a, coupler b, rocker c, ground d) as the paper's vector, angles wrapped to [0, 2 pi)."""
    a, b, c, d = lengths
    vector = [d, a, b, c, coupler_point[0], coupler_point[1]]
    angles = numpy.mod(numpy.asarray(angles, dtype=float), 2 * math.pi)
    if problem.frame_free:
        vector += [pivot[0], pivot[1], float(numpy.mod(frame, 2 * math.pi))]
    if problem.first_angle_free:
        vector += [float(angles[0])]
    elif problem.crank_angles is None:
        vector += list(angles)
    return numpy.array(vector, dtype=float)


def solve_general(problem: Problem, seed: int) -> numpy.ndarray:
    """:func:`symlink.synthesis.general.synthesize_path` on the placed four-bar for any problem, as the paper's vector.

    The four-bar's own placement (``x0, y0, frame``) is held at zero and the general placement
    (``x0, y0, angle``) is free where the paper's is; a free first crank angle (case 3) is the
    linkage's ``crank_phase``, free in [0, 2 pi].  The paper's bounds bound the free
    parameters and the pivot; the input turns fully (the paper's Grashof condition, as for
    path.py) and, without timing, grows from target to target.
    """
    from symlink.synthesis.general import synthesize_path as synthesize_any
    from symlink.synthesis.path import path_fourbar
    length, offset = problem.length_bound, problem.offset_bound
    free = {**{name: (1e-3 * length, length) for name in "abcd"}, "u": (-offset, offset), "v": (-offset, offset)}
    values = {"crank_phase": 0.0, "x0": 0.0, "y0": 0.0, "frame": 0.0}
    if problem.first_angle_free:
        free["crank_phase"] = (0.0, 2 * math.pi)
    timed = None if problem.crank_angles is None else numpy.array(problem.crank_angles)
    found = synthesize_any(path_fourbar(), ("P_x", "P_y"), problem.points, free, values=values,
                           frame=("x0", "y0", "angle") if problem.frame_free else (),
                           frame_bounds={"x0": (-offset, offset), "y0": (-offset, offset)} if problem.frame_free
                           else None, timed=timed, branches={"branch": 1}, seed=seed,
                           full_rotation=problem.frame_free, direction=None if timed is not None else 1)
    if not found.assembled:
        raise ValueError(found.why)
    d, where = found.design, found.placement
    angles = numpy.array(found.inputs) + d["crank_phase"]
    return _paper_vector(problem, (d["a"], d["b"], d["c"], d["d"]), (d["u"], d["v"]), (where["x0"], where["y0"]),
                         where["angle"], angles)


def solve(problem: Problem, seed: int) -> numpy.ndarray:
    """symlink's design for the problem, as the paper's vector (ValueError if none is found)."""
    targets = problem.points
    if problem.frame_free:
        from symlink.synthesis.path import synthesize_path
        timed = problem.crank_angles is not None
        length, offset = problem.length_bound, problem.offset_bound
        box = {**{name: (0.0, length) for name in "abcd"},
               **{name: (-offset, offset) for name in ("u", "v", "x0", "y0")}}
        found = synthesize_path(targets, numpy.array(problem.crank_angles) if timed else None, designs=1, seed=seed,
                                grashof_class="crank-rocker" if problem.crank_shortest else "crank-turns",
                                branch=1, direction=None if timed else 1, free_phase=problem.first_angle_free,
                                max_link_ratio=math.inf,
                                bounds=box)[0]
        return _paper_vector(problem, found.lengths, found.coupler_point, found.crank_pivot, found.frame, found.theta)
    from symlink.synthesis.general import synthesize_path as synthesize_any
    from symlink.synthesis.path import path_fourbar
    low = 1e-3 * problem.length_bound  # the paper's bounds, lengths kept off zero
    free = {"a": (low, problem.length_bound), "b": (low, problem.length_bound), "c": (low, problem.length_bound),
            "d": (low, problem.length_bound), "u": (-problem.offset_bound, problem.offset_bound),
            "v": (-problem.offset_bound, problem.offset_bound)}
    design = synthesize_any(path_fourbar(), ("P_x", "P_y"), targets, free,
                            values={"crank_phase": 0.0, "x0": 0.0, "y0": 0.0, "frame": 0.0}, frame=(),
                            timed=numpy.array(problem.crank_angles), branches={"branch": 1}, seed=seed, starts=4,
                            evaluations=300).design
    if not design:
        raise ValueError("no design")
    return _paper_vector(problem, (design["a"], design["b"], design["c"], design["d"]), (design["u"], design["v"]),
                         (0.0, 0.0), 0.0, problem.crank_angles or ())


@dataclass
class Run:
    problem: str
    seed: int
    objective: float
    seconds: float
    broken: list[str]


def run(problem: Problem, seed: int, method: str = "path") -> Run:
    """One seed: the design's objective by the paper's definition (inf if none is found or it breaks a constraint).

    ``method``: "path" (:func:`solve`: the four-bar's own synthesis where the frame is free) or
    "general" (:func:`solve_general`: the synthesis of any linkage, on the four-bar).
    """
    began = time.perf_counter()
    try:
        x = (solve_general if method == "general" else solve)(problem, seed)
    except ValueError as why:
        return Run(problem.key, seed, math.inf, time.perf_counter() - began, [f"none found: {why}"])
    seconds = time.perf_counter() - began
    broken = violations(problem, x)
    return Run(problem.key, seed, objective(problem, x) if not broken else math.inf, seconds, broken)


def _value(v: float, floor: float) -> str:
    if not math.isfinite(v):
        return "infeasible"
    return f"{v:.3g} (< rounding {floor:.0e})" if v < floor else f"{v:.8g}"


def table(runs: list[Run]) -> str:
    """The records: per problem symlink's best, median and worst objective, time, and the published best beside it."""
    lines = ["| problem | seeds | symlink best | symlink median | symlink worst | median s/seed | "
             "published best (method, runs; its median) | source | median <= published best |",
             "|---|---|---|---|---|---|---|---|---|"]
    for problem in PROBLEMS:
        mine = [r for r in runs if r.problem == problem.key]
        if not mine:
            continue
        values = sorted(r.objective for r in mine)
        floor = rounding_floor(problem)
        median = statistics.median(values)
        published = problem.best_published
        met = median <= published.best or median < floor
        lines.append(f"| {problem.key}: {problem.title} | {len(mine)} | {_value(values[0], floor)} | "
                     f"{_value(median, floor)} | {_value(values[-1], floor)} | "
                     f"{statistics.median(r.seconds for r in mine):.2f} | {published.best:.8g} ({published.method}, "
                     f"{published.runs}; {published.median:.3g}) | {published.file} | {'yes' if met else 'no'} |")
    for problem in PROBLEMS:
        mine = [r.objective for r in runs if r.problem == problem.key]
        if mine and problem.feasible_best is not None:
            median = statistics.median(mine)
            lines.append(f"\n{problem.key}: {problem.remark}. symlink's median {median:.10g} is "
                         f"{median - problem.best_published.best:+.2g} from the published best and "
                         f"{median - problem.feasible_best:+.2g} from that feasible least value.")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=20, help="seeds a problem (default 20)")
    parser.add_argument("--problems", default=",".join(BY_KEY), help="which problems, e.g. case1,case3")
    parser.add_argument("--method", choices=("path", "general"), default="path",
                        help="symlink.synthesis.path (the four-bar's; default) or symlink.synthesis.general")
    args = parser.parse_args(argv)
    chosen = [BY_KEY[k] for k in args.problems.split(",") if k in BY_KEY]
    if not chosen or args.seeds < 1:
        print(f"error: --problems names some of {', '.join(BY_KEY)} and --seeds is at least 1", file=sys.stderr)
        return 2
    runs: list[Run] = []
    began = time.perf_counter()
    for problem in chosen:
        for seed in range(args.seeds):
            runs.append(run(problem, seed, args.method))
            if runs[-1].broken:
                print(f"{problem.key} seed {seed}: {'; '.join(runs[-1].broken)}", file=sys.stderr)
        print(f"{problem.key} done", file=sys.stderr, flush=True)
    print(f"method: symlink.synthesis.{args.method}; published values from {REPOSITORY} ({PAPER})")
    print(table(runs))
    print(f"\nwhole run {time.perf_counter() - began:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
