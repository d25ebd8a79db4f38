"""The benchmark (``python -m benchmarks``, also ``symlink bench``): run time against error of four-bar position solvers, in one run.

The workload is a fixed-seed set of four-bars: random ones (link lengths
log-uniform over a decade, scaled by 10^-3 to 10^3, half of them Grashof,
half not) and the seed linkages (seeds 001, 002 and 003), each on both
branches.  Every (linkage, branch) is one sweep of crank angles drawn
uniformly over the angles where it can be assembled (so non-Grashof sweeps
come close to their toggle positions); N input values are split evenly over
the sweeps, and each method is called once a sweep with scalar link lengths,
the way a crank sweep is computed.

Methods (``--methods`` picks some):

==================  ===========================================================
``symlink``          symlink's generated NumPy solver, positions + rates + accelerations
``symlink-positions`` the same, positions only (coupler and rocker angles)
``hand-numpy``       the half-angle (A, B, C) formula of seed paper 003, vectorised by hand
``lambdify-nocse``   symlink's expressions (positions + rates + accelerations), fully
                     substituted, through ``sympy.lambdify`` without common subexpressions
``fsolve``           ``scipy.optimize.fsolve`` on the loop closure, one call per value
``newton``           a vectorised Newton iteration on the loop closure
``sympy-evalf``      substitution into symlink's closed forms and ``evalf``, per value
``symlink-c``        symlink's generated C (positions), compiled (:mod:`symlink.compiled`)
``hand-c``           a hand-written C loop of the same formulas, same compiler and flags
==================  ===========================================================

``fsolve`` and ``newton`` start 0.05 rad from the answer (what one continuation
step of a few degrees gives) and ``fsolve`` uses its default tolerance;
``fsolve`` (scipy is an optional extra) and ``sympy-evalf`` run on a
subsample of the smallest N, the C methods only where a C compiler works.
Methods that are not available are skipped with a note.

Errors are measured against a 50-digit mpmath reference (the intersection
of two circles, computed independently of symlink), on every value for
N <= ``reference`` values and on a fixed-seed subsample above that (the
maximum is then the maximum over the subsample).  The closure residual
``|a e^{i theta} + b e^{i beta} - d - c e^{i phi}| / max(a, b, c, d)`` is
computed on every value, in extended precision.

>>> records = benchmark(sizes=[200], methods=["symlink-positions", "hand-numpy"], reference=50, verbose=False)
>>> sorted(r["method"] for r in records), all(r["max_error"] < 1e-6 for r in records)
(['hand-numpy', 'symlink-positions'], True)
"""
from __future__ import annotations

import argparse
import gc
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Sequence

import mpmath
import numpy

if __package__ in (None, ""):  # run as a script, python benchmarks/bench.py: import from this checkout
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from symlink.analysis import crank_range
from symlink.files import write_atomic

__all__ = ["benchmark", "METHODS", "main", "hand_numpy", "reference_positions"]

METHODS = ("symlink", "symlink-positions", "hand-numpy", "lambdify-nocse", "fsolve", "newton", "sympy-evalf",
           "symlink-c", "hand-c")
POSITIONS = ["coupler", "rocker"]
EVERYTHING = POSITIONS + ["coupler_speed", "rocker_speed", "coupler_accel", "rocker_accel"]
CRANK_SPEED, CRANK_ACCEL = 10.5, 2.0
START_OFFSET = 0.05
#: (a, b, c, d) of the seed papers' four-bars (seed 002: its time ratio 1.25 design).
SEED_LINKAGES = {"seed001": (0.1, 0.4, 0.25, 0.30), "seed002": (16.084, 69.743, 50.0, 70.0),
                 "seed003": (20.0, 66.0, 56.0, 80.0)}
FULL_SIZES = (10**3, 10**5, 10**6)
QUICK_SIZES = (10**3, 2 * 10**4)
ERROR_FLOOR = 1e-17  # where a plot needs a positive error


@dataclass
class Sweep:
    """One linkage on one branch: crank angles, and the reference at the sampled ones."""

    name: str
    lengths: tuple[float, float, float, float]
    branch: int
    theta: numpy.ndarray
    sample: numpy.ndarray = field(default_factory=lambda: numpy.zeros(0, dtype=int))
    reference: tuple[numpy.ndarray, ...] = ()  # beta_hi, beta_lo, phi_hi, phi_lo at the sample


# --- the workload and its reference ------------------------------------------

def is_grashof(a: float, b: float, c: float, d: float) -> bool:
    """s + l <= p + q: some link turns fully."""
    s, p, q, l = sorted((a, b, c, d))
    return s + l <= p + q


def random_fourbars(rng: numpy.random.Generator, count: int) -> list[tuple[str, tuple[float, ...]]]:
    """``count`` assemblable random four-bars, alternately Grashof and not, at random scales."""
    found: list[tuple[str, tuple[float, ...]]] = []
    while len(found) < count:
        want_grashof = len(found) % 2 == 0
        scale = 10.0 ** rng.uniform(-3, 3)
        lengths = tuple(float(v) for v in scale * 10.0 ** rng.uniform(0, 1, 4))
        spans = crank_range(*lengths)
        if is_grashof(*lengths) == want_grashof and sum(hi - lo for lo, hi in spans) > 0.1:
            found.append((f"{'grashof' if want_grashof else 'non-grashof'}-{len(found)}", lengths))
    return found


def _angles(rng: numpy.random.Generator, spans: list[tuple[float, float]], count: int) -> numpy.ndarray:
    widths = numpy.array([hi - lo for lo, hi in spans])
    which = rng.choice(len(spans), size=count, p=widths / widths.sum())
    lows = numpy.array([lo for lo, _ in spans])[which]
    return numpy.sort(lows + rng.uniform(0, 1, count) * widths[which])


def reference_positions(a: float, b: float, c: float, d: float, theta: float, branch: int):
    """(beta, phi) as mpmath numbers at 50 digits, or ``None`` where the loop cannot close.

    C is where the circle of radius b about B = a e^{i theta} meets the circle
    of radius c about D = (d, 0), on the left of B -> D for branch +1.

    >>> beta, phi = reference_positions(20, 66, 56, 80, 0.0, 1)
    >>> round(float(mpmath.degrees(phi)), 4)
    110.7424
    """
    with mpmath.workdps(50):
        a, b, c, d, theta = (mpmath.mpf(v) for v in (a, b, c, d, theta))
        bx, by = a * mpmath.cos(theta), a * mpmath.sin(theta)
        ux, uy = d - bx, -by
        distance = mpmath.hypot(ux, uy)
        along = (b * b - c * c + distance * distance) / (2 * distance)
        if b * b < along * along:
            return None
        height = branch * mpmath.sqrt(b * b - along * along)
        cx = bx + (along * ux - height * uy) / distance
        cy = by + (along * uy + height * ux) / distance
        return mpmath.atan2(cy - by, cx - bx), mpmath.atan2(cy, cx - d)


def _split(value) -> tuple[float, float]:
    """A 50-digit number as a double-double (hi + lo)."""
    high = float(value)
    return high, float(value - mpmath.mpf(high))


def workload(size: int, seed: int, reference: int) -> list[Sweep]:
    """The sweeps of ``size`` input values in all, with the reference on at most ``reference`` of them."""
    rng = numpy.random.default_rng(seed)
    linkages = random_fourbars(rng, 6) + list(SEED_LINKAGES.items())
    sweeps = [Sweep(name, lengths, branch, numpy.zeros(0)) for name, lengths in linkages for branch in (1, -1)]
    counts = numpy.full(len(sweeps), size // len(sweeps))
    counts[: size % len(sweeps)] += 1
    share = min(reference, size) / size
    for sweep, count in zip(sweeps, counts):
        sweep.theta = _angles(rng, crank_range(*sweep.lengths), int(count))
        picked = rng.choice(count, size=min(count, max(1, round(share * count))), replace=False)
        values = [reference_positions(*sweep.lengths, t, sweep.branch) for t in sweep.theta[picked]]
        kept = [i for i, v in zip(picked, values) if v is not None]
        sweep.sample = numpy.array(sorted(kept), dtype=int)
        exact = dict(zip(picked, values))
        parts = numpy.array([_split(exact[i][0]) + _split(exact[i][1]) for i in sweep.sample]).reshape(-1, 4)
        sweep.reference = tuple(parts.T)
    return sweeps


def angle_errors(sweep: Sweep, beta: numpy.ndarray, phi: numpy.ndarray) -> numpy.ndarray:
    """|error| (rad) of the worse of beta and phi at the sampled values; NaN where a method gave none."""
    beta_hi, beta_lo, phi_hi, phi_lo = sweep.reference
    def wrapped(x):
        return numpy.abs(numpy.remainder(x + numpy.pi, 2 * numpy.pi) - numpy.pi)
    return numpy.maximum(wrapped((beta[sweep.sample] - beta_hi) - beta_lo),
                         wrapped((phi[sweep.sample] - phi_hi) - phi_lo))


def closure_residual(sweep: Sweep, beta: numpy.ndarray, phi: numpy.ndarray) -> numpy.ndarray:
    """Relative loop closure residual at every value, in extended precision."""
    a, b, c, d = (numpy.longdouble(v) for v in sweep.lengths)
    with numpy.errstate(invalid="ignore"):
        theta, beta, phi = (numpy.asarray(v, dtype=numpy.longdouble) for v in (sweep.theta, beta, phi))
        x = a * numpy.cos(theta) + b * numpy.cos(beta) - d - c * numpy.cos(phi)
        y = a * numpy.sin(theta) + b * numpy.sin(beta) - c * numpy.sin(phi)
        return numpy.asarray(numpy.hypot(x, y) / max(a, b, c, d), dtype=float)


# --- the methods -------------------------------------------------------------

def hand_numpy(theta, a: float, b: float, c: float, d: float, branch: int):
    """(beta, phi) by the half-angle solution of seed paper 003, vectorised by hand.

    ``A t^2 + B t + C = 0`` with ``t = tan(phi/2)``, K = (a^2 - b^2 + c^2 + d^2)/2,
    A = K - a(d - c) cos(theta) - c d, B = -2 a c sin(theta),
    C = K - a(d + c) cos(theta) + c d; its "-" root is branch +1.  beta from
    the loop's x and y components with atan2 (the seed's asin loses the quadrant).

    >>> beta, phi = hand_numpy(numpy.array([0.0]), 20.0, 66.0, 56.0, 80.0, 1)
    >>> round(float(numpy.degrees(phi[0])), 4), round(float(numpy.degrees(beta[0])), 4)
    (110.7424, 52.5127)
    """
    cos_t, sin_t = numpy.cos(theta), numpy.sin(theta)
    k = (a * a - b * b + c * c + d * d) / 2
    A = (k - c * d) - a * (d - c) * cos_t
    B = (-2 * a * c) * sin_t
    C = (k + c * d) - a * (d + c) * cos_t
    with numpy.errstate(invalid="ignore", divide="ignore"):
        phi = 2 * numpy.arctan((-B - branch * numpy.sqrt(B * B - 4 * A * C)) / (2 * A))
    beta = numpy.arctan2(c * numpy.sin(phi) - a * sin_t, d + c * numpy.cos(phi) - a * cos_t)
    return beta, phi


def _start(sweep: Sweep) -> tuple[numpy.ndarray, numpy.ndarray]:
    beta, phi = hand_numpy(sweep.theta, *sweep.lengths, sweep.branch)
    return beta + START_OFFSET, phi + START_OFFSET


def newton(theta, a, b, c, d, beta, phi, iterations: int = 30):
    """Vectorised Newton on the closure's x and y from (beta, phi); stops when no step exceeds 1e-15 rad."""
    cos_t, sin_t = a * numpy.cos(theta) - d, a * numpy.sin(theta)
    with numpy.errstate(invalid="ignore", divide="ignore"):
        for _ in range(iterations):
            cb, sb, cp, sp_ = numpy.cos(beta), numpy.sin(beta), numpy.cos(phi), numpy.sin(phi)
            fx, fy = cos_t + b * cb - c * cp, sin_t + b * sb - c * sp_
            # J = [[-b sb, c sp], [b cb, -c cp]]; det = b c (sb cp - cb sp) = b c sin(beta - phi)
            det = b * c * (sb * cp - cb * sp_)
            step_beta = (-c * cp * fx - c * sp_ * fy) / det
            step_phi = (-b * cb * fx - b * sb * fy) / det
            beta, phi = beta - step_beta, phi - step_phi
            if not numpy.nanmax(numpy.abs(step_beta) + numpy.abs(step_phi), initial=0.0) > 1e-15:
                break
    return beta, phi


@dataclass
class Method:
    """A method's name, what it computes a sweep with, and how many values it can afford.

    A ``batched`` method broadcasts over link lengths too, so it gets all
    sweeps as one call (lengths and branch as arrays), as a user of a
    vectorised solver would call it; the others get one call per sweep.
    """

    name: str
    solve: Callable[[Sweep], tuple[numpy.ndarray, numpy.ndarray]]
    limit: int | None = None  # values per size, for the slow ones (taken from the reference sample)
    note: str = ""
    batched: bool = False


def stacked(sweeps: list[Sweep]) -> Sweep:
    """All sweeps as one, with per-value arrays for the lengths and the branch."""
    counts = [len(s.theta) for s in sweeps]
    lengths = tuple(numpy.repeat([s.lengths[k] for s in sweeps], counts) for k in range(4))
    return Sweep("all", lengths, numpy.repeat([s.branch for s in sweeps], counts),
                 numpy.concatenate([s.theta for s in sweeps]))


def unstacked(result: tuple[numpy.ndarray, ...], sweeps: list[Sweep]) -> list[tuple[numpy.ndarray, ...]]:
    """A stacked call's result, split back into one result per sweep."""
    bounds = numpy.cumsum([len(s.theta) for s in sweeps])[:-1]
    return list(zip(*(numpy.split(part, bounds) for part in result)))


class Unavailable(Exception):
    """A method that cannot run here (a missing optional dependency or compiler)."""


def _keywords(function: Callable[..., dict], **extra) -> Callable[[Sweep], tuple]:
    """A sweep solver from a function called as the generated ones are (keywords in, dict of arrays out)."""
    def solve(sweep):
        a, b, c, d = sweep.lengths
        result = function(theta=sweep.theta, a=a, b=b, c=c, d=d, branch=sweep.branch, **extra)
        return result["coupler"], result["rocker"]
    return solve


def _inlined(definitions) -> dict:
    """``(symbol, expression)`` pairs in dependency order, each with the earlier ones substituted."""
    whole: dict = {}
    for symbol, expr in definitions:
        whole[symbol] = expr.xreplace(whole)
    return whole


def _symlink(outputs: Sequence[str]):
    from symlink.cache import generated_code
    from symlink.scene import catalog_linkage
    function = generated_code(catalog_linkage("fourbar"), outputs).function
    rates = {"thetadot": CRANK_SPEED, "thetaddot": CRANK_ACCEL} if len(outputs) > 2 else {}
    return _keywords(function, **rates)


def _lambdify():
    import sympy as sp
    from symlink.position import ClampedSqrt
    from symlink.scene import catalog_linkage
    program = catalog_linkage("fourbar").program(EVERYTHING)
    whole = _inlined(program.assignments)
    expressions = [program.outputs[name].xreplace(whole).replace(ClampedSqrt, lambda x, _: sp.sqrt(x))
                   for name in EVERYTHING]
    function = sp.lambdify(program.arguments, expressions, modules="numpy", cse=False)

    def solve(sweep):
        with numpy.errstate(invalid="ignore", divide="ignore"):
            values = function(sweep.theta, *sweep.lengths, sweep.branch, CRANK_SPEED, CRANK_ACCEL)
        return values[0], values[1]
    return solve


def _fsolve():
    try:
        from scipy.optimize import fsolve
    except ImportError:
        raise Unavailable("scipy is not installed (pip install 'symlink-kinematics[bench]')") from None

    def closure(unknowns, theta, a, b, c, d):
        beta, phi = unknowns
        return [a * math.cos(theta) + b * math.cos(beta) - d - c * math.cos(phi),
                a * math.sin(theta) + b * math.sin(beta) - c * math.sin(phi)]

    def solve(sweep):
        starts = _start(sweep)
        beta, phi = numpy.empty_like(sweep.theta), numpy.empty_like(sweep.theta)
        for i, theta in enumerate(sweep.theta):
            beta[i], phi[i] = fsolve(closure, (starts[0][i], starts[1][i]), args=(theta, *sweep.lengths))
        return beta, phi
    return solve


def _newton():
    def solve(sweep):
        return newton(sweep.theta, *sweep.lengths, *_start(sweep))
    return solve


def _evalf():
    import sympy as sp
    from symlink.scene import catalog_linkage
    linkage = catalog_linkage("fourbar")
    whole = _inlined(linkage.positions.items())
    beta, phi = (whole[q] for q in linkage.unknowns)
    symbols = linkage.inputs + linkage.parameters + linkage.branches

    def solve(sweep):
        out = numpy.empty((2, len(sweep.theta)))
        for i, theta in enumerate(sweep.theta):
            values = dict(zip(symbols, (sp.Float(theta), *map(sp.Float, sweep.lengths), sweep.branch)))
            out[:, i] = [float(beta.subs(values).evalf()), float(phi.subs(values).evalf())]
        return out[0], out[1]
    return solve


def _compiled():
    try:
        from symlink.compiled import CompiledSolver, CompileError, CompilerUnavailable
    except ImportError:
        raise Unavailable("symlink.compiled is not available") from None
    from symlink.scene import catalog_linkage
    try:
        return _keywords(CompiledSolver(catalog_linkage("fourbar"), POSITIONS).function)
    except CompilerUnavailable as error:
        raise Unavailable(f"no C compiler: {error}") from None
    except (CompileError, OSError) as error:
        raise Unavailable(f"cannot build or load the library: {error}") from None


def _hand_c():
    try:
        from symlink.compiled import CompileError, CompilerUnavailable
        from benchmarks.hand_c import hand_library, hand_positions
    except ImportError:
        raise Unavailable("benchmarks.hand_c is not available") from None
    try:
        hand_library()
    except CompilerUnavailable as error:
        raise Unavailable(f"no C compiler: {error}") from None
    except (CompileError, OSError) as error:
        raise Unavailable(f"cannot build or load the library: {error}") from None

    def solve(sweep):
        result = hand_positions(sweep.theta, *sweep.lengths, sweep.branch)
        return result["coupler"], result["rocker"]
    return solve


def _methods(quick: bool) -> dict[str, Callable[[], Method]]:
    return {
        "symlink": lambda: Method("symlink", _symlink(EVERYTHING), batched=True),
        "symlink-positions": lambda: Method("symlink-positions", _symlink(POSITIONS), batched=True),
        "hand-numpy": lambda: Method("hand-numpy", lambda s: hand_numpy(s.theta, *s.lengths, s.branch),
                                     batched=True),
        "lambdify-nocse": lambda: Method("lambdify-nocse", _lambdify(), batched=True),
        "fsolve": lambda: Method("fsolve", _fsolve(), limit=200 if quick else 1000, note="default xtol"),
        "newton": lambda: Method("newton", _newton(), batched=True),
        "sympy-evalf": lambda: Method("sympy-evalf", _evalf(), limit=10 if quick else 60),
        "symlink-c": lambda: Method("symlink-c", _compiled()),  # per sweep, like hand-c
        "hand-c": lambda: Method("hand-c", _hand_c()),
    }


# --- measuring ---------------------------------------------------------------

def _subset(sweeps: list[Sweep], limit: int) -> list[Sweep]:
    """Sweeps cut down to about ``limit`` of their reference values in all (for the slow methods)."""
    total = sum(len(s.sample) for s in sweeps)
    cut = []
    for sweep in sweeps:
        keep = sweep.sample[: max(1, round(limit * len(sweep.sample) / max(total, 1)))]
        if not len(keep):
            continue
        part = Sweep(sweep.name, sweep.lengths, sweep.branch, sweep.theta[keep], numpy.arange(len(keep)),
                     tuple(r[: len(keep)] for r in sweep.reference))
        cut.append(part)
    return cut


def _timed(methods: list[Method], work: dict[str, list[Sweep]], budget: float) -> dict[str, tuple[float, list]]:
    """Best time of each method over all its sweeps, and its results.

    The methods take turns, round after round (up to 7), so that a change in
    the machine's load falls on all of them alike; a method sits out further
    rounds once its time would exceed ``budget`` seconds.  The garbage
    collector is off while timing, as in :mod:`timeit`.
    """
    best = {m.name: math.inf for m in methods}
    spent = {m.name: 0.0 for m in methods}
    results: dict[str, list] = {}
    calls = {m.name: [stacked(work[m.name])] if m.batched else work[m.name] for m in methods}
    gc.collect()
    gc.disable()
    try:
        for round_ in range(7):
            for method in methods:
                if round_ and spent[method.name] + best[method.name] > budget:
                    continue
                results[method.name] = []  # the previous round's arrays are freed before timing
                start = time.perf_counter()
                results[method.name] = [method.solve(sweep) for sweep in calls[method.name]]
                elapsed = time.perf_counter() - start
                best[method.name] = min(best[method.name], elapsed)
                spent[method.name] += elapsed
    finally:
        gc.enable()
    for method in methods:
        if method.batched:
            results[method.name] = unstacked(results[method.name][0], work[method.name])
    return {name: (best[name], results[name]) for name in best}


def _record(method: Method, sweeps: list[Sweep], seconds: float, results: list) -> dict:
    """One record: time per value and the errors of ``method`` on ``sweeps``."""
    n = sum(len(s.theta) for s in sweeps)
    errors = numpy.concatenate([angle_errors(s, *r) for s, r in zip(sweeps, results)])
    residuals = numpy.concatenate([closure_residual(s, *r) for s, r in zip(sweeps, results)])
    failures = int(numpy.sum(~numpy.isfinite(errors)))
    finite = errors[numpy.isfinite(errors)]
    return {
        "method": method.name, "n": n, "us_per_value": seconds / n * 1e6,
        "max_error": float(finite.max()) if finite.size else None,
        "median_error": float(numpy.median(finite)) if finite.size else None,
        "max_residual": float(numpy.nanmax(residuals)) if numpy.isfinite(residuals).any() else None,
        "failures": failures, "reference_n": int(errors.size), "note": method.note,
    }


def _ratios(records: list[dict]) -> None:
    """Each record's time per value over symlink's at the same N (the smallest N for subsampled methods)."""
    symlink = {r["n"]: r["us_per_value"] for r in records if r["method"] == "symlink"}
    for record in records:
        if not symlink:
            record["ratio_to_symlink"] = None
            continue
        size = record["n"] if record["n"] in symlink else min(symlink)
        record["ratio_to_symlink"] = record["us_per_value"] / symlink[size]
        record["compared_at_n"] = size


_DERIVATION_SCRIPT = r"""
import json, sys, time
started = time.perf_counter()
from symlink import cache
from symlink.scene import catalog_linkage
imported = time.perf_counter()
result = {"import_symlink": imported - started, "scenes": []}
for name, outputs in json.loads(sys.argv[1]):
    start = time.perf_counter()
    linkage = catalog_linkage(name)
    built = time.perf_counter()
    code = cache.generated_code(linkage, outputs)
    done = time.perf_counter()
    again = time.perf_counter()
    cache.generated_code(linkage, outputs)
    memory = time.perf_counter() - again
    result["scenes"].append({"linkage": name, "outputs": len(outputs), "build_linkage": built - start,
                             "code": done - built, "memory": memory, "source": code.source})
print(json.dumps(result))
"""


def derivation_scenes(quick: bool) -> list[tuple[str, list[str]]]:
    """The four-bar's positions and its full scene; unless quick, every closed-form catalog linkage's full scene."""
    from symlink.catalog import CATALOG
    from symlink.scene import catalog_linkage
    from symlink.vectors import acceleration, rate
    scenes = [("fourbar", POSITIONS), ("fourbar", EVERYTHING)]
    for name in ([] if quick else CATALOG):
        linkage = catalog_linkage(name)
        if name != "fourbar" and getattr(linkage, "has_closed_form", True):
            unknowns = linkage.unknowns
            scenes.append((name, [q.name for q in unknowns] + [rate(q).name for q in unknowns]
                           + [acceleration(q).name for q in unknowns]))
    return scenes


def derivation_times(scenes: list[tuple[str, list[str]]]) -> list[dict]:
    """Seconds to get each scene's code in a new process: with an empty cache, then from the disk cache."""
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        path = os.pathsep.join([str(Path(__file__).resolve().parent.parent), os.environ.get("PYTHONPATH", "")])
        env = dict(os.environ, SYMLINK_CACHE=folder, PYTHONPATH=path)
        runs = []
        for _ in ("cold", "cached"):
            done = subprocess.run([sys.executable, "-c", _DERIVATION_SCRIPT, json.dumps(scenes)],
                                  capture_output=True, text=True, env=env, check=True)
            runs.append(json.loads(done.stdout))
    from symlink.codegen.numpy import load_numpy_module
    for cold, cached in zip(runs[0]["scenes"], runs[1]["scenes"]):
        loads = []
        for _ in range(5):
            start = time.perf_counter()
            load_numpy_module(cold["source"])
            loads.append(time.perf_counter() - start)
        rows.append({"linkage": cold["linkage"], "outputs": cold["outputs"],
                     "cold": cold["build_linkage"] + cold["code"], "cached": cached["build_linkage"] + cached["code"],
                     "build_linkage": cached["build_linkage"], "memory": cold["memory"], "load_module": min(loads)})
    return rows


def benchmark(sizes: Sequence[int] = FULL_SIZES, methods: Sequence[str] = METHODS, quick: bool = False,
              seed: int = 2024, reference: int = 2000, verbose: bool = True) -> list[dict]:
    """Measure ``methods`` at each size; returns the records (and prints progress if ``verbose``)."""
    factories = _methods(quick)
    unknown = [m for m in methods if m not in factories]
    if unknown:
        raise ValueError(f"unknown method {unknown[0]!r}; choose from {', '.join(METHODS)}")
    if not sizes or any(n < 1 for n in sizes):
        raise ValueError(f"sizes must be positive, got {list(sizes)}")
    ready: list[Method] = []
    for name in methods:
        try:
            ready.append(factories[name]())
        except Unavailable as why:
            _say(verbose, f"skipped {name}: {why}")
    records = []
    for size in sorted(sizes):
        sweeps = workload(size, seed, reference)
        running = [m for m in ready if m.limit is None or size == min(sizes)]
        work = {m.name: sweeps if m.limit is None else _subset(sweeps, m.limit) for m in running}
        timed = _timed(running, work, budget=0.5 if quick else 2.0)
        for method in running:
            records.append(_record(method, work[method.name], *timed[method.name]))
            _say(verbose, f"  {method.name:>18} N={records[-1]['n']:<8} {records[-1]['us_per_value']:.4g} us/value")
    _ratios(records)
    return records


def _say(verbose: bool, text: str) -> None:
    """A progress line, on stderr (stdout carries the results only)."""
    if verbose:
        print(text, file=sys.stderr, flush=True)


# --- reporting ---------------------------------------------------------------

def _short(value, digits: int = 2) -> str:
    return "-" if value is None else f"{value:.{digits}e}"


def table(records: list[dict]) -> str:
    """The records as an aligned text table."""
    header = f"{'method':>18} {'N':>8} {'us/value':>10} {'ratio':>8} {'max err':>9} {'median err':>10} " \
             f"{'max resid':>9} {'fail':>5}"
    lines = [header]
    for r in records:
        ratio = "-" if r.get("ratio_to_symlink") is None else f"{r['ratio_to_symlink']:.3g}"
        lines.append(f"{r['method']:>18} {r['n']:>8} {r['us_per_value']:>10.4g} {ratio:>8} "
                     f"{_short(r['max_error']):>9} {_short(r['median_error']):>10} {_short(r['max_residual']):>9} "
                     f"{r['failures']:>5}")
    return "\n".join(lines)


def _find(records, method, n=None):
    found = [r for r in records if r["method"] == method and (n is None or r["n"] == n)]
    return found[-1] if found else None


def targets(records: list[dict]) -> list[str]:
    """The issue's targets, as ratios measured in this run, each marked held or missed."""
    lines = []
    largest = max((r["n"] for r in records if r["method"] == "symlink-positions"), default=None)

    def verdict(ok):
        return "held" if ok else "MISSED"
    positions, hand = _find(records, "symlink-positions", largest), _find(records, "hand-numpy", largest)
    if positions and hand:
        ratio = positions["us_per_value"] / hand["us_per_value"]
        accurate = (positions["max_error"] or 0) <= (hand["max_error"] or 0) and positions["failures"] <= hand["failures"]
        lines.append(f"symlink-positions / hand-numpy at N={largest}: {ratio:.2f}x (target <= 1.3x: "
                     f"{verdict(ratio <= 1.3)}); max error {_short(positions['max_error'])} vs "
                     f"{_short(hand['max_error'])} rad (at least as accurate: {verdict(accurate)})")
    full = _find(records, "symlink", largest)
    if positions and full:
        ratio = positions["us_per_value"] / full["us_per_value"]
        lines.append(f"symlink-positions / symlink at N={largest}: {ratio:.2f}x (target <= 0.5x: {verdict(ratio <= 0.5)})")
    fsolve = _find(records, "fsolve")
    if fsolve:  # one call a value: its time per value does not depend on N; both solve positions only
        for size in sorted({min(r["n"] for r in records if r["method"] == "symlink-positions"), largest} - {None}):
            symlink = _find(records, "symlink-positions", size)
            if symlink:
                ratio = fsolve["us_per_value"] / symlink["us_per_value"]
                lines.append(f"fsolve ({fsolve['n']} values) / symlink-positions at N={size}, per value: "
                             f"{ratio:.0f}x (target >= 100x: {verdict(ratio >= 100)})")
    compiled, hand_c = _find(records, "symlink-c", largest), _find(records, "hand-c", largest)
    if compiled and hand_c:
        ratio = compiled["us_per_value"] / hand_c["us_per_value"]
        lines.append(f"symlink-c / hand-c at N={largest}: {ratio:.2f}x (target <= 1.2x: {verdict(ratio <= 1.2)})")
    if compiled and positions:
        ratio = positions["us_per_value"] / compiled["us_per_value"]
        lines.append(f"symlink-positions / symlink-c at N={largest}: {ratio:.2f}x (target >= 3x: {verdict(ratio >= 3)})")
    return lines


def plot(records: list[dict], path: str | os.PathLike) -> None:
    """Log-log run time against error: one marker per method and N."""
    import io

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    markers = "os^vD<>pXh*"
    figure, axes = plt.subplots(figsize=(8, 5.5))
    names = list(dict.fromkeys(r["method"] for r in records))
    sizes = sorted({r["n"] for r in records})
    for index, name in enumerate(names):
        mine = [r for r in records if r["method"] == name and r["max_error"] is not None]
        axes.scatter([max(r["max_error"], ERROR_FLOOR) for r in mine], [r["us_per_value"] for r in mine],
                     s=[30 + 60 * sizes.index(r["n"]) for r in mine], marker=markers[index % len(markers)],
                     label=name, alpha=0.8)
        for r in mine:
            axes.annotate(f"{r['n']:.0e}".replace("e+0", "e"), (max(r["max_error"], ERROR_FLOOR), r["us_per_value"]),
                          fontsize=6, xytext=(4, 3), textcoords="offset points")
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("max angle error against 50-digit mpmath (rad)")
    axes.set_ylabel("run time per input value (microseconds)")
    axes.set_title("Four-bar positions: run time against error (marker size: N)")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=8, loc="best")
    figure.tight_layout()
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=110)
    plt.close(figure)
    write_atomic(path, buffer.getvalue())


def report_derivations(rows: list[dict]) -> list[str]:
    lines = ["symbolic side (scenes in this order in one new process: 'cold' with an empty cache, "
             "then 'cached' in another from the disk cache):"]
    for row in rows:
        lines.append(f"  {row['linkage']} ({row['outputs']} outputs): derive + generate + load cold "
                     f"{row['cold'] * 1e3:.1f} ms, from cache {row['cached'] * 1e3:.1f} ms (of which building "
                     f"the linkage {row['build_linkage'] * 1e3:.1f} ms), from memory {row['memory'] * 1e6:.0f} us; "
                     f"loading the generated module {row['load_module'] * 1e3:.2f} ms")
    return lines


# --- the command line ----------------------------------------------------------

class _UsageError(ValueError):
    """A bad command line: reported in one line, exit status 2."""


class _Parser(argparse.ArgumentParser):
    """argparse whose errors are one line (raised, then printed by :func:`main`), not a usage dump."""

    def error(self, message: str) -> None:
        raise _UsageError(message)


def _sizes(text: str) -> list[float]:
    """Comma-separated numbers (checked to be positive whole numbers later, with the other options)."""
    values = []
    for item in (part.strip() for part in text.split(",")):
        if not item:
            continue
        try:
            value = float(item)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a number: {item!r}") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"not a finite number: {item!r}")
        values.append(value)
    return values


def build_parser(prog: str = "python -m benchmarks") -> argparse.ArgumentParser:
    """The benchmark's options."""
    parser = _Parser(prog=prog, description="Run time against error of the four-bar position solvers. "
                     "Progress goes to stderr, the table and the targets to stdout.",
                     epilog=f"example: {prog} --quick --json bench.json --plot bench.png")
    parser.add_argument("--quick", action="store_true", help=f"N = {', '.join(map(str, QUICK_SIZES))} (under a minute)")
    parser.add_argument("--sizes", type=_sizes, metavar="LIST", help="comma-separated N (overrides --quick's)")
    parser.add_argument("--methods", metavar="LIST", help=f"comma-separated, from {', '.join(METHODS)} (default all)")
    parser.add_argument("--seed", type=int, default=2024, help="random four-bars (default 2024)")
    parser.add_argument("--json", metavar="FILE", help="write the records as JSON")
    parser.add_argument("--plot", metavar="FILE", help="write the run-time-against-error plot (PNG)")
    parser.add_argument("--no-derivation", action="store_true", help="skip the symbolic-side timings")
    return parser


def run(args: argparse.Namespace) -> int:
    """Run the benchmark as the options say: progress on stderr; the table, targets and symbolic timings on stdout."""
    if args.sizes is not None:
        if not args.sizes or any(n != int(n) or n < 1 for n in args.sizes):
            raise ValueError(f"--sizes must be positive whole numbers, got {args.sizes}")
        sizes = [int(n) for n in args.sizes]
    else:
        sizes = list(QUICK_SIZES if args.quick else FULL_SIZES)
    methods = METHODS if args.methods is None else [m.strip() for m in args.methods.split(",") if m.strip()]
    unknown = [m for m in methods if m not in METHODS]
    if unknown:
        raise ValueError(f"unknown method {unknown[0]!r}; choose from {', '.join(METHODS)}")
    for path in (args.json, args.plot):
        if path is not None and not Path(path).parent.is_dir():
            raise ValueError(f"cannot write {path}: no folder {Path(path).parent}")
    reference = 400 if args.quick else 2000
    _say(True, f"symlink bench: N = {', '.join(map(str, sizes))}; errors on up to {reference} values a size "
               f"(50-digit mpmath), residuals on all")
    records = benchmark(sizes, methods, quick=args.quick, seed=args.seed, reference=reference)
    print(table(records))
    print()
    for line in targets(records):
        print(line)
    if not args.no_derivation:
        print()
        for line in report_derivations(derivation_times(derivation_scenes(args.quick))):
            print(line)
    if args.json:
        write_atomic(args.json, json.dumps(records, indent=1) + "\n")
    if args.plot:
        plot(records, args.plot)
    return 0


def main(argv: Sequence[str] | None = None, prog: str = "python -m benchmarks") -> int:
    """Run the benchmark from command-line arguments; returns the exit status.

    Bad options: one line on stderr, status 2; a file that cannot be written:
    one line, status 1; Ctrl-C: status 130, quietly.
    """
    try:
        return run(build_parser(prog).parse_args(argv))
    except ValueError as error:
        print(f"symlink: error: {error}", file=sys.stderr)
        return 2
    except OSError as error:
        if isinstance(error, BrokenPipeError):
            return 0
        print(f"symlink: error: cannot write: {error}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    sys.exit(main(prog="python benchmarks/bench.py"))
