"""Shape targets of the literature: symlink's shape match and refinement, 20 seeds a target, medians stated.

Each target is a curve given as points without timing, position, turn or scale; symlink's
:func:`symlink.synthesis.shape.synthesize_shape` matches a four-bar coupler curve to it (2000
sampled designs ranked by the Fourier-descriptor shape distance, the best three placed and
refined through the points by exact gradients) once a seed, and the table states the best, the
median and the worst shape distance (:func:`symlink.synthesis.shape.shape_distance`, closed:
0 for similar curves, at most 1) over the seeds, with the time of a run, and, where a published
answer linkage is known, that linkage's shape distance to the same target, computed here by
circle intersections (our own four-bar formulas), its curve traced as densely as symlink's
refined one.  "points error" is the largest distance of a target point from the refined
design's point over the target's size (0 to rounding where the target is a four-bar's curve);
for a target drawn from a linkage, that linkage's own distance is the floor the target's
polygon leaves (the chords).  Run from the repository root::

    python -m benchmarks.literature_shapes                 # 20 seeds a target, the table
    python -m benchmarks.literature_shapes --seeds 3 --targets yu1,wu1

:func:`shapes_table` gives the table to ``python -m benchmarks.synthesis --literature --shapes``.

**Sources.** Only target coordinates (numbers published in the papers) are transcribed below,
each with its paper; they were read in the files of the repository KmolYuan/four-bar-rs
(``test-fb/`` and ``test-fb/refer/``, read at commit 00e68872c36401d1617e304f58fbb42464b60344),
whose code and files are not used or shipped.  The published linkages of four-bar-rs are given
as a ground pivot ``(p1x, p1y)``, the ground's angle ``a`` and length ``l1``, crank ``l2``,
coupler ``l3``, rocker ``l4`` and the coupler point at ``l5`` from the crank's moving joint,
turned ``g`` from the coupler; this module reads them so (crank pivot A = (p1x, p1y), rocker
pivot D = A + l1 e^{i a}, B = A + l2 e^{i (a + theta)}, C on the circles (B, l3) and (D, l4) to
the left of B -> D, P = B + l5 e^{i (arg(C - B) + g)}), for the target and the answer alike.
"""
from __future__ import annotations

import argparse
import cmath
import math
import statistics
import time

import numpy

from symlink.mechanism.catalog import fourbar, with_point
from symlink.symbolic.linkage import Linkage
from symlink.synthesis.shape import shape_distance, synthesize_shape

#: McGarva, J. R. (1994). Rapid search and selection of path generating mechanisms from a library. Mechanism and
#: Machine Theory, 29(2), 223-235, https://doi.org/10.1016/0094-114X(94)90032-9 (read in four-bar-rs
#: test-fb/mcgarva.closed.csv): 36 points of a closed curve.
MCGARVA = [
    (53.129710635271394, 71.09548499062436), (43.88075278565084, 71.12057099863611),
    (34.78160925198469, 70.85023434303328), (27.182660455254414, 69.57166588355919),
    (21.947350879671248, 66.98830542625824), (17.15750757515258, 63.540602931307575),
    (14.416032479975563, 59.947254090866124), (12.65682494666995, 54.50134434447122),
    (11.789696022302618, 49.14527267701302), (11.799466715687087, 44.3832980197824),
    (11.573203202188205, 38.642229320146654), (11.58343424485069, 33.66777640979497),
    (11.577748827657164, 28.48382492755202), (11.600870418177685, 24.325586118193065),
    (11.575210056457536, 19.56552000892165), (11.60761067692598, 15.969681563765272),
    (11.6058362188868, 14.180576525204753), (11.48444898607098, 12.957358191381187),
    (11.52190927026825, 12.186228831518758), (11.551954375908867, 11.36490063762871),
    (11.654725443149985, 10.645226088319745), (12.494754772828372, 11.921320586914634),
    (13.133110638566805, 12.904500646899207), (14.288439202715658, 15.312954042452937),
    (15.831210096010986, 17.20711288996677), (18.030243231375596, 20.180863710817494),
    (22.7401256868248, 24.378923980315804), (27.365985146232077, 28.76740068523864),
    (32.08110231437042, 33.442845138497916), (37.83568766271256, 39.14327289515019),
    (43.910939689649226, 43.94515034393466), (50.04595182417367, 48.98630838725289),
    (56.088336036554466, 54.79424876988042), (59.90199840530059, 61.70391535005011),
    (59.20415282231929, 67.7921691846899),
]

#: H. Yu, D. Tang and Z. Wang (2007). Study on a new computer path synthesis method of a four-bar linkage. Mechanism
#: and Machine Theory, 42(4), 383-392 (read in four-bar-rs test-fb/yu1.closed.csv): 20 points of a closed curve.
YU_TANG_WANG = [
    (-27.0, 1.0), (-21.857, -3.214), (-16.7, -7.428), (-11.571, -11.642), (-6.428, -15.857), (-1.285, -20.071),
    (3.857, -24.285), (9.0, -28.5), (15.0, -29.9), (20.0, -30.0), (27.2, -25.0), (29.2, -20.0), (28.0, -10.0),
    (22.7, 2.0), (15.0, 10.6), (5.0, 16.5), (-10.0, 19.6), (-22.0, 17.0), (-28.0, 11.0), (-29.0, 5.0),
]

#: R. R. Bulatovic, G. Miodragovic and M. S. Boskovic (2016). Modified Krill Herd (MKH) algorithm and its application
#: in dimensional synthesis of a four-bar linkage. Mechanism and Machine Theory, 95, 1-21,
#: https://doi.org/10.1016/j.mechmachtheory.2015.08.004 (read in four-bar-rs test-fb/mkh1.closed.csv): the 18-point
#: closed curve, here as a shape only.
BULATOVIC = [
    (0.5, 1.1), (0.4, 1.1), (0.3, 1.1), (0.2, 1.0), (0.1, 0.9), (0.05, 0.75), (0.02, 0.6), (0.0, 0.5), (0.0, 0.4),
    (0.03, 0.3), (0.1, 0.25), (0.15, 0.2), (0.2, 0.3), (0.3, 0.4), (0.4, 0.5), (0.5, 0.7), (0.6, 0.9), (0.6, 1.0),
]

#: J. Wu, Q. J. Ge, F. Gao and W. Z. Guo (2011). On the extension of a Fourier descriptor based method for planar
#: four-bar linkage synthesis for generation of open and closed paths. Journal of Mechanisms and Robotics, 3(3),
#: https://doi.org/10.1115/1.4004227: the closed target is the coupler curve of this four-bar (read in four-bar-rs
#: test-fb/wu1.closed.ron), and the answer linkage it reports (test-fb/refer/wu1.closed.ron).
WU_TARGET = dict(p1x=10.0, p1y=14.0, a=0.1745, l1=11.0, l2=6.0, l3=8.0, l4=10.0, l5=7.0, g=0.6981)
WU_ANSWER = dict(p1x=10.0022, p1y=13.9988, a=0.1743, l1=10.8390, l2=5.9969, l3=7.9621, l4=9.9527, l5=7.0004,
                 g=0.6867)

#: Points of a four-bar's coupler curve drawn here (the Wu target, the answers): over a turn of the crank.
CURVE_POINTS = 72


def coupler_curve(linkage: dict, count: int = CURVE_POINTS) -> numpy.ndarray:
    """A four-bar's coupler point over a turn of its crank (rows x, y), by circle intersections (see the module)."""
    A = complex(linkage["p1x"], linkage["p1y"])
    D = A + linkage["l1"] * cmath.exp(1j * linkage["a"])
    points = []
    for theta in numpy.linspace(0.0, 2 * math.pi, count, endpoint=False):
        B = A + linkage["l2"] * cmath.exp(1j * (linkage["a"] + theta))
        w = abs(D - B)
        along = (linkage["l3"] ** 2 - linkage["l4"] ** 2 + w * w) / (2 * w)
        across = linkage["l3"] ** 2 - along * along
        if across < 0:
            raise ValueError("the published linkage is not assembled over a whole turn")
        C = B + (D - B) / w * (along + 1j * math.sqrt(across))
        P = B + linkage["l5"] * cmath.exp(1j * (cmath.phase(C - B) + linkage["g"]))
        points.append((P.real, P.imag))
    return numpy.array(points)


#: name -> (target points, what it is, the published answer linkage or None)
TARGETS = {
    "mcgarva": (numpy.array(MCGARVA), "McGarva 1994, 36 points", None),
    "yu1": (numpy.array(YU_TANG_WANG), "Yu, Tang & Wang 2007, 20 points", None),
    "bulatovic": (numpy.array(BULATOVIC), "Bulatovic et al. 2016, 18 points", None),
    "wu1": (coupler_curve(WU_TARGET), f"Wu et al. 2011, a four-bar's curve ({CURVE_POINTS} points)", WU_ANSWER),
}

#: The crank is 1 (the placement's scale sizes the design); the other lengths and the coupler point within these.
FREE = {"b": (0.3, 8.0), "c": (0.3, 8.0), "d": (0.3, 8.0), "u": (-5.0, 5.0), "v": (-5.0, 5.0)}


def coupler_point_fourbar() -> Linkage:
    """The catalog four-bar with a coupler point P = B + u along B -> C + v to its left."""
    base = fourbar()
    return with_point(base, "B", base.roles["coupler"])


def run_target(name: str, seed: int, linkage: Linkage | None = None) -> dict:
    """One run of the shape match and refinement on a target: its shape distances, error and time."""
    target = TARGETS[name][0]
    started = time.perf_counter()
    try:
        found = synthesize_shape(linkage or coupler_point_fourbar(), "P", target, FREE, values={"a": 1.0},
                                 seed=seed)
    except ValueError as error:
        return {"target": name, "seed": seed, "distance": math.inf, "sampled": math.inf, "error": math.inf,
                "seconds": time.perf_counter() - started, "why": str(error)}
    return {"target": name, "seed": seed, "distance": found.distance, "sampled": found.sampled_distance,
            "error": found.error, "seconds": time.perf_counter() - started, "why": ""}


#: Points of a published linkage's curve compared with the target: as many as symlink's refined curve has.
DENSE = 720


def published_distance(name: str) -> float:
    """The published answer's shape distance to the target, its curve traced as densely as symlink's refined one
    (NaN where no answer is known)."""
    target, _, answer = TARGETS[name]
    return math.nan if answer is None else shape_distance(target, coupler_curve(answer, DENSE))


def floor_distance(name: str) -> float:
    """A target drawn from a linkage (Wu's): that linkage's own distance to it, the floor its polygon leaves."""
    return shape_distance(TARGETS[name][0], coupler_curve(WU_TARGET, DENSE)) if name == "wu1" else math.nan


def shapes_table(seeds: int = 20, names: list[str] | None = None) -> str:
    """The markdown table: each target's best, median and worst shape distance over ``seeds`` runs, and time."""
    linkage = coupler_point_fourbar()
    lines = ["| target | best | median | worst | sampled (median) | points error (median) | median s a run | "
             "published answer | target's own linkage |", "|---|---|---|---|---|---|---|---|---|"]
    for name in names or list(TARGETS):
        runs = [run_target(name, seed, linkage) for seed in range(seeds)]
        distances = sorted(run["distance"] for run in runs)
        published, floor = published_distance(name), floor_distance(name)
        lines.append(f"| {TARGETS[name][1]} | {distances[0]:.3g} | {statistics.median(distances):.3g} | "
                     f"{distances[-1]:.3g} | {statistics.median(run['sampled'] for run in runs):.3g} | "
                     f"{statistics.median(run['error'] for run in runs):.3g} | "
                     f"{statistics.median(run['seconds'] for run in runs):.3g} | "
                     + " | ".join("-" if math.isnan(v) else f"{v:.3g}" for v in (published, floor)) + " |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, default=20, help="runs a target (seeds 0 ... N-1; default 20)")
    parser.add_argument("--targets", default=",".join(TARGETS), help=f"comma-separated, of {','.join(TARGETS)}")
    parser.add_argument("--shapes", action="store_true", help="(the flag of benchmarks.synthesis --literature)")
    args = parser.parse_args(argv)
    names = [name.strip() for name in args.targets.split(",") if name.strip()]
    unknown = [name for name in names if name not in TARGETS]
    if unknown or args.seeds < 1:
        parser.error(f"targets are among {', '.join(TARGETS)} and seeds at least 1")
    print(shapes_table(args.seeds, names))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
