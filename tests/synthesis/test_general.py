"""Path synthesis of any one-input linkage (symlink.synthesis.general), on problems with a known answer.

Targets are traced by a known design; the synthesis starts from a perturbed one (and random
designs within the bounds) and must pass through the targets.  Every check of a found design
places its point with hand formulas written here (circle intersections, the slider's
triangle), never with the code under test; the Jacobian is checked against central
differences of the generated solver's points.
"""
from __future__ import annotations

import math

import numpy
import pytest

from symlink.mechanism.catalog import EXAMPLE_VALUES, fourbar, jansen, slider_crank, watt2, with_point
from symlink.symbolic.linkage import Linkage
from symlink.synthesis.general import FRAME_NAMES, path_residuals, synthesize_path, traced_points


# --- linkages with a point on a moving link ------------------------------------------------------------

def slider_point() -> Linkage:
    base = slider_crank()
    return with_point(base, "B", base.roles["conrod"], "slider_crank_point")


def fourbar_point() -> Linkage:
    base = fourbar()
    return with_point(base, "B", base.roles["coupler"], "fourbar_point")


def watt_point() -> Linkage:
    """Watt II with a point on its second coupler EF (the coupler of the second loop)."""
    base = watt2()
    return with_point(base, "E", base.roles["coupler2"], "watt2_point")


# --- hand references ---------------------------------------------------------------------------------

def circle_left(B: complex, D: complex, b: float, c: float, sign: int) -> complex:
    """The point at distance b from B and c from D, left of the directed line B->D for sign +1 (right for -1)."""
    L = abs(D - B)
    along = (b * b - c * c + L * L) / (2 * L)
    across = math.sqrt(b * b - along * along)
    unit = (D - B) / L
    return B + unit * (along + 1j * sign * across)


def jansen_foot(design: dict, q: float) -> complex:
    """Jansen's foot H at crank angle q on the branches +1, by circle intersections (catalog's description)."""
    B = design["m"] * complex(math.cos(q), math.sin(q))
    D = complex(-design["a"], -design["l"])
    C = circle_left(D, B, design["b"], design["j"], 1)  # C left of D -> B
    F = circle_left(B, D, design["k"], design["c"], 1)  # F left of B -> D
    phi = math.atan2((C - D).imag, (C - D).real)
    E = D + design["d"] * complex(math.cos(phi + design["alpha"]), math.sin(phi + design["alpha"]))
    G = circle_left(F, E, design["g"], design["f"], 1)  # G left of F -> E
    eta = math.atan2((G - F).imag, (G - F).real)
    return F + design["i"] * complex(math.cos(eta + design["gamma"]), math.sin(eta + design["gamma"]))


def hand_point(kind: str, design: dict, q: float, branches: dict) -> complex:
    """The point P in the linkage's frame at input q, from the hand formulas."""
    if kind == "jansen":
        return jansen_foot(design, q)
    u, v = design["u"], design["v"]
    B = design["a"] * complex(math.cos(q), math.sin(q))
    if kind == "slider":  # offset = a sin q + b sin beta, the slider to the right (cos beta > 0)
        beta = math.asin((design["offset"] - B.imag) / design["b"])
        return B + complex(u, v) * complex(math.cos(beta), math.sin(beta))
    D = complex(design["d"], 0.0)
    C = circle_left(B, D, design["b"], design["c"], branches.get("branch", branches.get("branch_ABCD", 1)))
    if kind == "fourbar":
        return B + complex(u, v) * (C - B) / abs(C - B)
    phi = math.atan2((C - D).imag, (C - D).real)
    E = D + design["e"] * complex(math.cos(phi + design["alpha"]), math.sin(phi + design["alpha"]))
    F = circle_left(E, complex(design["gx"], design["gy"]), design["f"], design["g"], branches["branch_DEFG"])
    return E + complex(u, v) * (F - E) / abs(F - E)


def hand_error(kind: str, found, targets: numpy.ndarray) -> float:
    """The largest distance from a target to the found design's placed point, over the targets' size (by hand)."""
    p = found.placement
    turn = p["scale"] * complex(math.cos(p["angle"]), math.sin(p["angle"]))
    worst = 0.0
    for q, target in zip(found.inputs, targets):
        placed = complex(p["x0"], p["y0"]) + turn * hand_point(kind, found.design, q, found.branches)
        worst = max(worst, abs(placed - complex(*target)))
    return worst / math.hypot(*(targets.max(axis=0) - targets.min(axis=0)))


PROBLEMS = {
    "slider": (slider_point, dict(a=1.3, b=4.1, offset=0.7, u=1.2, v=0.9), ("a", "b", "offset", "u", "v"), {}),
    "fourbar": (fourbar_point, dict(a=1.0, b=3.0, c=2.5, d=3.2, u=1.5, v=0.8), ("a", "b", "c", "d", "u", "v"),
                {"branch": 1}),
    "watt": (watt_point, dict(a=1.0, b=3.5, c=3.0, d=3.2, e=2.0, f=4.0, g=3.0, alpha=0.6, gx=4.5, gy=3.5, u=1.8,
                              v=0.7), ("f", "g", "gx", "gy", "u", "v"), {"branch_ABCD": 1, "branch_DEFG": 1}),
}
PLACEMENT = {"x0": 0.4, "y0": -1.1, "angle": 0.7, "scale": 1.0}


@pytest.mark.parametrize("timed", [True, False])
def test_jansen_foot_path_recovery(timed):
    """Jansen's leg: six of its lengths recovered from its foot's path, its ground and crank kept (no placement)."""
    linkage = jansen()
    truth = dict(EXAMPLE_VALUES["jansen"])
    branches = {s.name: 1 for s in linkage.branches}
    inputs = numpy.linspace(-2.5, 2.5, 12)
    targets = traced_points(linkage, "H", truth, inputs, branches)
    for q, target in zip(inputs, targets):  # the targets agree with the hand formulas
        assert abs(jansen_foot(truth, q) - complex(*target)) < 1e-9
    free = ("b", "c", "d", "g", "i", "k")
    rng = numpy.random.default_rng(11)
    start = {name: value * (1 + 0.04 * rng.uniform(-1, 1)) if name in free else value for name, value in truth.items()}
    bounds = {name: (0.7 * truth[name], 1.3 * truth[name]) for name in free}
    found = synthesize_path(linkage, "H", targets, bounds, values=start, frame=(), timed=inputs if timed else None,
                            branches=branches)
    assert found.assembled, found.why
    assert found.error < 1e-10
    size = math.hypot(*(targets.max(axis=0) - targets.min(axis=0)))
    worst = max(abs(jansen_foot(found.design, q) - complex(*t)) for q, t in zip(found.inputs, targets))
    assert worst / size < 1e-10


def problem(kind: str, inputs: numpy.ndarray, seed: int = 3):
    build, truth, free, branches = PROBLEMS[kind]
    linkage = build()
    targets = traced_points(linkage, "P", truth, inputs, branches, PLACEMENT)
    assert numpy.all(numpy.isfinite(targets))
    for q, target in zip(inputs, targets):  # the targets themselves agree with the hand formulas
        placed = complex(PLACEMENT["x0"], PLACEMENT["y0"]) + complex(math.cos(0.7), math.sin(0.7)) * hand_point(
            kind, truth, q, branches)
        assert abs(placed - complex(*target)) < 1e-12
    rng = numpy.random.default_rng(seed)
    start = {name: value * (1 + 0.04 * rng.uniform(-1, 1)) if name in free else value for name, value in truth.items()}
    bounds = {name: tuple(sorted((0.5 * truth[name], 1.5 * truth[name]))) for name in free}
    return linkage, targets, start, bounds, branches


@pytest.mark.parametrize("kind", sorted(PROBLEMS))
def test_timed_recovery(kind):
    inputs = numpy.linspace(0.2, 2.6, 7)
    linkage, targets, start, bounds, branches = problem(kind, inputs)
    found = synthesize_path(linkage, "P", targets, bounds, values=start, frame=("x0", "y0", "angle"), timed=inputs,
                            branches=branches)
    assert found.assembled
    assert found.error < 1e-10
    assert hand_error(kind, found, targets) < 1e-10
    assert found.inputs == tuple(inputs)


@pytest.mark.parametrize("kind", sorted(PROBLEMS))
def test_untimed_recovery(kind):
    inputs = numpy.linspace(0.3, 3.0, 12)
    linkage, targets, start, bounds, branches = problem(kind, inputs)
    found = synthesize_path(linkage, "P", targets, bounds, values=start, frame=("x0", "y0", "angle"), timed=None,
                            branches=branches)
    assert found.assembled, found.why
    assert found.error < 1e-10
    assert hand_error(kind, found, targets) < 1e-10
    steps = numpy.diff(found.inputs)
    assert numpy.all(steps >= 0) or numpy.all(steps <= 0)  # reached in order


def test_jacobian_against_central_differences():
    """Every column (free parameters, placement, input values) against differences of the generated solver's points."""
    linkage = watt_point()
    _, design, free, branches = PROBLEMS["watt"]
    free = ("f", "gx", "alpha", "u")
    placement = {"x0": 0.4, "y0": -1.1, "angle": 0.7, "scale": 1.3}
    inputs = numpy.array([0.3, 1.1, 2.0])
    targets = numpy.array([[0.0, 0.0], [1.0, 2.0], [3.0, -1.0]])
    size = math.hypot(3.0, 3.0)
    r, J = path_residuals(linkage, "P", targets, design, inputs, free, FRAME_NAMES, placement, branches)

    def residuals(design_values, place, qs):
        return ((traced_points(linkage, "P", design_values, qs, branches, place) - targets) / size).ravel()

    assert numpy.allclose(r, residuals(design, placement, inputs), atol=1e-14)
    h = 1e-6
    columns = []
    for name in free:
        up, down = dict(design), dict(design)
        up[name] += h
        down[name] -= h
        columns.append((residuals(up, placement, inputs) - residuals(down, placement, inputs)) / (2 * h))
    for name in FRAME_NAMES:
        up, down = dict(placement), dict(placement)
        up[name] += h
        down[name] -= h
        columns.append((residuals(design, up, inputs) - residuals(design, down, inputs)) / (2 * h))
    for k in range(len(inputs)):
        step = numpy.zeros(len(inputs))
        step[k] = h
        columns.append((residuals(design, placement, inputs + step) - residuals(design, placement, inputs - step))
                       / (2 * h))
    differences = numpy.stack(columns, axis=1)
    assert J.shape == differences.shape == (6, len(free) + 4 + 3)
    assert numpy.allclose(J, differences, rtol=1e-7, atol=1e-8)


def test_unreachable_targets_report_their_error():
    """A crank pin can only trace a circle about the origin: points on a square leave an honest, non-zero error."""
    linkage = slider_crank()
    inputs = numpy.array([0.0, math.pi / 2, math.pi, 1.5 * math.pi]) * 0.9
    targets = numpy.array([[1.0, 0.0], [0.0, 2.0], [-1.0, 0.0], [0.0, -2.0]])
    found = synthesize_path(linkage, "B", targets, {"a": (0.5, 3.0)}, values={"b": 5.0, "offset": 0.0}, frame=(),
                            timed=inputs)
    assert found.assembled
    a = found.design["a"]
    by_hand = max(abs(a * complex(math.cos(q), math.sin(q)) - complex(*t)) for q, t in zip(inputs, targets))
    size = math.hypot(2.0, 4.0)
    assert found.error > 0.1
    shown = found._repr_html_()  # a notebook shows the record as a table: design, error, assembled, evaluations
    assert all(f"<th>{field}</th>" in shown for field in ("design", "error", "assembled", "evaluations"))
    assert found.error == pytest.approx(by_hand / size, rel=1e-12)
    # the least-squares optimum: a minimises sum |a e^{iq} - t|^2, a = mean of Re(conj(e^{iq}) t)
    best = numpy.mean([(complex(math.cos(q), -math.sin(q)) * complex(*t)).real for q, t in zip(inputs, targets)])
    assert a == pytest.approx(best, rel=1e-7)  # the cost is quadratic there: flat to rounding within ~1e-8


@pytest.mark.parametrize("change, message", [
    (dict(free={"z": (0, 1)}), "no parameter 'z'"),
    (dict(free={"a": (2, 1)}), "low < high"),
    (dict(values={"b": 5.0}), "offset"),
    (dict(frame=("x0", "turn")), "frame"),
    (dict(timed=[0.0, 1.0]), "input values"),
    (dict(point="Q"), "no output"),
    (dict(targets=[[0.0, numpy.nan], [1.0, 1.0], [2.0, 0.0]]), "finite"),
])
def test_bad_input_names_the_problem(change, message):
    arguments = dict(linkage=slider_crank(), point="B", targets=[[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]],
                     free={"a": (0.5, 2.0)}, values={"b": 5.0, "offset": 0.0}, frame=(), timed=[0.0, 1.5, 3.0])
    arguments.update(change)
    with pytest.raises(ValueError, match=message):
        synthesize_path(**arguments)

