"""Path synthesis of a linkage without a closed form: the Stephenson II six-bar, solved by Newton's method.

Targets are the true design's coupler point E from a 30-digit mpmath reference written here (the
closure of the catalog's Stephenson II, continued along the crank by ``mpmath.findroot`` in small
steps from a hand-found assembly: ``tests/mp_closures.py``'s ``stephenson2_continued``, which
``tests/codegen/test_newton_c.py`` uses too); the found design is
checked with the same reference: continued from the assembly synthesis reports, through its inputs,
placed, it must pass through the targets to 1e-8 of their size.  Nothing of symlink's derivation
is used by the reference.
"""
import math

import mpmath as mp
import numpy as np
import pytest
from mp_closures import STEPHENSON2_UNKNOWNS as UNKNOWNS
from mp_closures import stephenson2_continued

from symlink.mechanism.catalog import stephenson2
from symlink.synthesis.general import synthesize_path

TRUTH = dict(a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1, alpha=0.9, delta=0.3)
#: An assembly of TRUTH at theta = 0 whose crank turns fully (tests/codegen/test_newton_c.py).
ASSEMBLY = dict(beta=0.96, mu=0.27, phi=1.43, eta=-0.16)


def coupler_points(design, thetas, guess, placement=None, substeps=8):
    """E = a e^{i theta} + e e^{i (beta + alpha)} at each theta (30 digits), continued in small steps from the
    assembly nearest ``guess`` at thetas[0]; placed by (x0, y0) + scale R(angle) E.  Rows (x, y) as floats."""
    where = {"x0": 0.0, "y0": 0.0, "angle": 0.0, "scale": 1.0, **(placement or {})}
    positions = stephenson2_continued(design, thetas, guess, substeps=substeps)
    with mp.workdps(30):
        p = {k: mp.mpf(v) for k, v in design.items()}
        rows = []
        for theta, q in zip(map(mp.mpf, thetas), positions):
            point = p["a"] * mp.expj(theta) + p["e"] * mp.expj(q[0] + p["alpha"])
            placed = (mp.mpc(where["x0"], where["y0"])
                      + mp.mpf(where["scale"]) * mp.expj(mp.mpf(where["angle"])) * point)
            rows.append((float(placed.real), float(placed.imag)))
    return np.array(rows)


def _size(targets):
    return float(np.hypot(*(targets.max(axis=0) - targets.min(axis=0))))


def _check_recovered(found, targets, free):
    assert found.assembled, found.why
    assert found.error < 1e-8
    assert found.branches == {} and set(found.assembly) == set(UNKNOWNS)
    reached = coupler_points(found.design, found.inputs, found.assembly, found.placement)
    assert np.max(np.hypot(*(reached - targets).T)) < 1e-8 * _size(targets)


@pytest.mark.slow
def test_timed_recovery_of_the_stephenson2_coupler_curve():
    inputs = np.linspace(0.3, 1.5, 7)
    targets = coupler_points(TRUTH, inputs, ASSEMBLY)
    free = {"b": (2.5, 3.7), "e": (3.3, 4.5), "g": (3.5, 4.7)}
    values = {k: v for k, v in TRUTH.items() if k not in free}
    found = synthesize_path(stephenson2(), "E", targets, free, values=values, frame=(), timed=inputs, starts=8,
                            seed=1)
    _check_recovered(found, targets, free)


@pytest.mark.slow
def test_timed_recovery_with_a_free_placement():
    inputs = np.linspace(-0.4, 1.2, 8)
    placement = {"x0": 1.5, "y0": -0.7, "angle": 0.4}
    targets = coupler_points(TRUTH, inputs, ASSEMBLY, placement)
    free = {"b": (2.6, 3.6), "g": (3.6, 4.6), "alpha": (0.6, 1.2)}
    values = {k: v for k, v in TRUTH.items() if k not in free}
    found = synthesize_path(stephenson2(), "E", targets, free, values=values, frame=("x0", "y0", "angle"),
                            timed=inputs, starts=12, seed=2)
    _check_recovered(found, targets, free)


@pytest.mark.slow
def test_untimed_recovery_of_the_stephenson2_coupler_curve():
    inputs = np.linspace(0.3, 1.5, 7)
    targets = coupler_points(TRUTH, inputs, ASSEMBLY)
    free = {"b": (2.5, 3.7), "e": (3.3, 4.5), "g": (3.5, 4.7)}
    values = {k: v for k, v in TRUTH.items() if k not in free}
    found = synthesize_path(stephenson2(), "E", targets, free, values=values, frame=(), starts=8, seed=1)
    _check_recovered(found, targets, free)
    steps = np.diff(found.inputs)
    assert np.all(steps > 0) or np.all(steps < 0)  # the targets in order, the input moving one way


def test_the_users_design_and_assembly_start_the_search():
    """Given the true design and its assembly, the first start is already on the targets."""
    inputs = np.linspace(0.3, 1.5, 5)
    targets = coupler_points(TRUTH, inputs, ASSEMBLY)
    found = synthesize_path(stephenson2(), "E", targets, {"b": (2.5, 3.7)}, values=TRUTH, frame=(),
                            timed=inputs, starts=1, guess=ASSEMBLY)
    _check_recovered(found, targets, {"b": (2.5, 3.7)})
    assert found.design["b"] == pytest.approx(3.1, abs=1e-9)
    assert found.assembly["beta"] == pytest.approx(float(coupler_beta(inputs[0])), abs=1e-9)


def coupler_beta(theta):
    """beta of the ASSEMBLY continued to ``theta`` by the reference (for the reported assembly)."""
    return stephenson2_continued(TRUTH, [0.0, theta], ASSEMBLY)[-1][0]


@pytest.mark.parametrize("keywords, message", [
    ({"min_transmission": 0.3}, "no loop of it has exactly two unknown angles"),
    ({"guess": {"beta": 1.0}}, "guess gives the unknowns"),
    ({"guess": {"beta": 1.0, "mu": 0.2, "phi": 1.4, "eta": math.nan}}, "guess gives the unknowns"),
])
def test_bad_input_names_the_problem(keywords, message):
    targets = [[0.0, 4.0], [0.3, 4.4], [0.4, 4.6]]
    with pytest.raises(ValueError, match=message):
        synthesize_path(stephenson2(), "E", targets, {"b": (2.5, 3.7)}, values=TRUTH, frame=(),
                        timed=[0.0, 0.3, 0.6], **keywords)


#: An assembly of TRUTH at theta = 0 on a circuit that folds back near theta = 54.65 deg (tests/codegen/test_newton_c.py;
#: the 50-digit check of the fold is in tests/test_solver.py).
FOLDING = dict(beta=0.785649, mu=-2.447163, phi=2.88568, eta=-1.361976)


def test_full_rotation_holds_newton_linkages_to_a_circuit_whose_crank_turns():
    """Targets on the folding circuit are reached without the constraint and refused with it; targets on the
    circuit whose crank turns (ASSEMBLY) are reached with it, and the design says so."""
    inputs = np.linspace(0.0, 0.8, 5)
    targets = coupler_points(TRUTH, inputs, FOLDING)
    keywords = dict(values=TRUTH, frame=(), timed=inputs, starts=1, evaluations=200)
    folding = synthesize_path(stephenson2(), "E", targets, {"b": (3.0, 3.2)}, guess=FOLDING, **keywords)
    _check_recovered(folding, targets, {"b": (3.0, 3.2)})
    with pytest.raises(ValueError, match="no start could be refined"):
        synthesize_path(stephenson2(), "E", targets, {"b": (3.0, 3.2)}, guess=FOLDING, full_rotation=True,
                        **keywords)
    targets = coupler_points(TRUTH, inputs, ASSEMBLY)
    turning = synthesize_path(stephenson2(), "E", targets, {"b": (3.0, 3.2)}, guess=ASSEMBLY, full_rotation=True,
                              **keywords)
    _check_recovered(turning, targets, {"b": (3.0, 3.2)})
    assert "the input turns fully" in turning.constraints


def rocker_angles(design, thetas, guess, substeps=8):
    """phi (the rocker DF's angle) at each theta from the same 30-digit continuation as :func:`coupler_points`."""
    return np.array([float(q[2]) for q in stephenson2_continued(design, thetas, guess, substeps=substeps)])


@pytest.mark.slow
def test_function_generation_of_the_stephenson2_rocker():
    """The rocker angle of another design at six inputs, found again from the catalog's dimensions."""
    from symlink.synthesis.general_function import synthesize_function
    truth = {**TRUTH, "b": 3.3, "g": 4.0}
    inputs = np.linspace(0.0, 1.2, 6)
    wanted = rocker_angles(truth, inputs, ASSEMBLY)
    found = synthesize_function(stephenson2(), "phi", inputs, wanted, {"b": (2.5, 3.7), "g": (3.5, 4.7)},
                                values=TRUTH)
    assert found.assembled, found.why
    assert found.branches == {} and set(found.assembly) == set(UNKNOWNS)
    assert found.structural_error < 1e-10
    reached = rocker_angles(found.design, inputs, found.assembly)
    assert np.max(np.abs(np.angle(np.exp(1j * (reached - wanted))))) < 1e-10


def coupler_poses(design, thetas, guess, placement):
    """The coupler's pose (B placed, beta + the placement's angle) at each theta, by the 30-digit continuation."""
    where = {"x0": 0.0, "y0": 0.0, "angle": 0.0, **placement}
    positions = stephenson2_continued(design, thetas, guess)
    with mp.workdps(30):
        p = {k: mp.mpf(v) for k, v in design.items()}
        rows = []
        for theta, q in zip(map(mp.mpf, thetas), positions):
            B = mp.mpc(where["x0"], where["y0"]) + mp.expj(where["angle"]) * p["a"] * mp.expj(theta)
            rows.append((float(B.real), float(B.imag), float(q[0] + where["angle"])))
    return np.array(rows)


@pytest.mark.slow
def test_timed_motion_generation_of_the_stephenson2_coupler():
    from symlink.synthesis.general_motion import synthesize_motion
    truth = {**TRUTH, "b": 3.3, "g": 4.0}
    inputs = np.linspace(0.0, 1.2, 5)
    placement = {"x0": 0.5, "y0": 0.2, "angle": 0.3}
    poses = coupler_poses(truth, inputs, ASSEMBLY, placement)
    found = synthesize_motion(stephenson2(), "B", "beta", poses, {"b": (2.5, 3.7), "g": (3.5, 4.7)}, values=TRUTH,
                              timed=inputs)
    assert found.assembled and found.error < 1e-10, found.why
    assert found.branches == {} and set(found.assembly) == set(UNKNOWNS)
    reached = coupler_poses(found.design, inputs, found.assembly, found.placement)
    size = float(np.hypot(*np.ptp(poses[:, :2], axis=0)))
    assert np.max(np.hypot(*(reached[:, :2] - poses[:, :2]).T)) < 1e-8 * size
    assert np.max(np.abs(np.angle(np.exp(1j * (reached[:, 2] - poses[:, 2]))))) < 1e-10


def test_untimed_motion_of_a_newton_linkage_is_refused():
    from symlink.synthesis.general_motion import synthesize_motion
    with pytest.raises(ValueError, match="needs the input at each pose"):
        synthesize_motion(stephenson2(), "B", "beta", [[1.0, 0.0, 1.0], [0.9, 0.4, 0.9]], {"b": (2.5, 3.7)},
                          values=TRUTH)


@pytest.mark.slow
def test_a_from_joints_linkage_that_needs_newton_recovers_its_lengths():
    """The Stephenson II drawn by its joints and driven at D (no loop has two unknowns: Newton); two link lengths
    changed by 7 % are found again from the drawing's, through the coupler point E's path.  The targets come from
    the numeric solver (the mpmath tests above check that); what this checks is that a ``from_joints`` linkage
    without a closed form goes through: the known lengths are recovered."""
    from symlink.mechanism.joints import from_joints
    from symlink.synthesis.general import traced_points
    drawing = {"A": (0.0, 0.0), "D": (4.5, 0.0), "B": (0.3, 0.95), "C": (3.2, 2.0), "E": (1.5, 4.2),
               "F": (5.3, 2.8), "H": (4.8, 4.6)}
    links = {"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C", "E"], "rocker": ["D", "F", "H"],
             "cf": ["C", "F"], "eh": ["E", "H"]}
    drawn = from_joints(links, drawing, driver="D")
    linkage = drawn.linkage
    assert not linkage.has_closed_form
    values = dict(drawn.parameters)
    truth = {**values, "EH": values["EH"] * 1.07, "CF": values["CF"] * 1.07}
    inputs = drawn.pose[linkage.inputs[0].name] + np.linspace(0.0, 0.5, 6)
    targets = traced_points(linkage, "E", truth, inputs, guess=drawn.guess)
    assert np.all(np.isfinite(targets))
    free = {name: (values[name] * 0.8, values[name] * 1.3) for name in ("EH", "CF")}
    found = synthesize_path(linkage, "E", targets, free, values=values, frame=(), timed=inputs, guess=drawn.guess)
    assert found.assembled and found.error < 1e-10, found.why
    for name in free:
        assert found.design[name] == pytest.approx(truth[name], rel=1e-8)


#: Generated untimed problems: their count, and how many must be recovered (the issue's bar, 95 %).
RECOVERY_PROBLEMS, RECOVERY_NEEDED = 20, 19
RECOVERY_FREE = {"b": (2.5, 3.7), "e": (3.3, 4.5), "g": (3.5, 4.7), "alpha": (0.6, 1.2)}


def untimed_problem(seed):
    """A random Stephenson II (b, e, g, alpha within the free bounds), 5-10 targets over 1-3 rad of the crank,
    placed at random: (design, inputs, placement, targets), the targets from the 30-digit reference.  Designs
    whose assembly (ASSEMBLY's, continued from theta = 0) cannot be continued there are drawn again."""
    rng = np.random.default_rng(2000 + seed)
    while True:
        truth = dict(TRUTH, b=rng.uniform(2.7, 3.5), e=rng.uniform(3.5, 4.3), g=rng.uniform(3.7, 4.5),
                     alpha=rng.uniform(0.7, 1.1))
        count, start, span = int(rng.integers(5, 11)), rng.uniform(-math.pi, math.pi), rng.uniform(1.0, 3.0)
        inputs = np.concatenate([[start], start + np.sort(rng.uniform(0.0, span, count - 2)), [start + span]])
        placement = {"x0": rng.uniform(-2, 2), "y0": rng.uniform(-2, 2), "angle": rng.uniform(-math.pi, math.pi)}
        try:
            there = stephenson2_continued(truth, [0.0, start], ASSEMBLY, substeps=32)[-1]
            targets = coupler_points(truth, inputs, dict(zip(UNKNOWNS, map(float, there))), placement)
        except (ValueError, ZeroDivisionError):  # findroot found no position: not assembled along the way
            continue
        return truth, inputs, placement, targets


@pytest.mark.slow
def test_untimed_recovery_of_generated_problems_reaches_the_bar():
    """Issue 25's bar: at least 95 % of untimed problems recovered to 1e-8 of the curve's size, by the reference."""
    recovered = []
    for seed in range(RECOVERY_PROBLEMS):
        truth, inputs, placement, targets = untimed_problem(seed)
        values = {k: v for k, v in truth.items() if k not in RECOVERY_FREE}
        found = synthesize_path(stephenson2(), "E", targets, RECOVERY_FREE, values=values,
                                frame=("x0", "y0", "angle"), seed=seed)
        ok = found.assembled and set(found.assembly) == set(UNKNOWNS)
        if ok:
            reached = coupler_points(found.design, found.inputs, found.assembly, found.placement)
            ok = bool(np.max(np.hypot(*(reached - targets).T)) < 1e-8 * _size(targets))
        recovered.append(ok)
    assert sum(recovered) >= RECOVERY_NEEDED, [seed for seed, ok in enumerate(recovered) if not ok]


def test_designs_traced_at_once_follow_the_30_digit_reference():
    """newton_traced_batch continues three designs together: two from ASSEMBLY (their cranks turn) match the
    reference continued from the same assembly, the third (on the folding circuit) stops before its fold."""
    from symlink.synthesis.design_fit import newton_traced_batch
    thetas = np.linspace(0.0, 1.5, 31)
    designs = [TRUTH, {**TRUTH, "b": 3.3, "g": 4.0}, TRUTH]
    starts = np.array([[ASSEMBLY[n] for n in UNKNOWNS]] * 2 + [[FOLDING[n] for n in UNKNOWNS]])
    values = {name: np.array([design[name] for design in designs]) for name in TRUTH}
    unknowns, assembled = newton_traced_batch(stephenson2(), values, thetas, np.random.default_rng(0), starts=starts)
    assert assembled[:2].all()
    for k in range(2):
        reference = stephenson2_continued(designs[k], thetas[::5], ASSEMBLY)
        got = unknowns[k, ::5]
        assert np.max(np.abs(got - np.array([[float(v) for v in q] for q in reference]))) < 1e-10
    fold = np.radians(54.65)  # the fold of this circuit (tests/test_solver.py)
    assert assembled[2, thetas < fold - 0.05].all() and not assembled[2, thetas > fold + 0.05].any()
