"""Path generation, checked independently: coupler points by 30-digit circle intersections (mpmath), the
Jacobian by central differences of those, Grashof classes and transmission angles by hand formulas."""
import math
from dataclasses import replace

import mpmath as mp
import numpy as np
import pytest

from symlink.synthesis.path import (DESIGN_NAMES, _Constraints, _accelerated_levenberg_marquardt,
                                    _active_set_levenberg_marquardt, _arc_position, _distinct, _linear_walls,
                                    check_design, fourbar_design, path_jacobian, synthesize_path)


def mp_point(vector, theta, branch):
    """The coupler point of the design vector (x0, y0, frame, a, b, c, d, u, v) at crank angle theta, 30 digits."""
    with mp.workdps(30):
        x0, y0, frame, a, b, c, d, u, v = (mp.mpf(float(x)) if not isinstance(x, mp.mpf) else x for x in vector)
        B = a * mp.expj(theta)
        w = abs(d - B)
        along = (b ** 2 - c ** 2 + w ** 2) / (2 * w)
        unit = (d - B) / w
        C = B + along * unit + branch * mp.sqrt(b ** 2 - along ** 2) * 1j * unit  # +1: C left of B->D
        beta = mp.arg(C - B)
        return mp.mpc(x0, y0) + mp.expj(frame) * (B + mp.mpc(u, v) * mp.expj(beta))


def random_crank_rocker(rng):
    """A random crank-rocker (s + l < p + q, crank shortest: the hand rule) placed anywhere, with a coupler point."""
    while True:
        a, b, c, d = rng.uniform(0.2, 1.0), *rng.uniform(0.5, 3.0, 3)
        s, l = min(a, b, c, d), max(a, b, c, d)
        if a == s and s + l < a + b + c + d - s - l - 0.05:
            break
    return fourbar_design(tuple(rng.normal(size=2)), rng.uniform(-3, 3), (a, b, c, d),
                          (rng.uniform(-1, 2) * b, rng.uniform(-1, 1) * b), branch=int(rng.choice([-1, 1])))


def test_generated_jacobian_against_mpmath_central_differences():
    vector = [0.3, -0.2, 0.7, 0.8, 2.4, 2.0, 2.6, 1.1, -0.5]
    values, slopes, assembled = path_jacobian().arrays(np.array([0.4, 2.5]), 0.0, *vector, -1.0)
    keywords = dict(zip(DESIGN_NAMES, vector), theta=np.array([0.4, 2.5]), crank_phase=0.0, branch=-1.0)
    checked_values, checked_slopes = path_jacobian()(**keywords)  # the checked call gives the same numbers
    assert np.array_equal(np.moveaxis(checked_slopes, 0, -1), slopes)
    assert np.array_equal(checked_values["P_x"], values[0]) and assembled.all()
    for k, theta in enumerate((0.4, 2.5)):
        point = mp_point(vector, mp.mpf(theta), -1)
        assert values[0, k] == pytest.approx(float(point.real), abs=1e-13)
        assert values[1, k] == pytest.approx(float(point.imag), abs=1e-13)
        # column 0 is the crank phase, whose derivative is the crank angle's
        for index, name in enumerate(("theta",) + DESIGN_NAMES):
            with mp.workdps(30):
                h = mp.mpf("1e-12")

                def shifted(step):
                    values = [mp.mpf(x) for x in vector]
                    angle = mp.mpf(theta)
                    if index == 0:
                        angle += step
                    else:
                        values[index - 1] += step
                    return mp_point(values, angle, -1)
                derivative = (shifted(h) - shifted(-h)) / (2 * h)
            assert slopes[0, index, k] == pytest.approx(float(derivative.real), rel=1e-9, abs=1e-11), name
            assert slopes[1, index, k] == pytest.approx(float(derivative.imag), rel=1e-9, abs=1e-11), name


def test_jacobian_is_no_number_where_the_four_bar_cannot_close():
    # crank 1, coupler and rocker 0.1, ground 1.5: |BD| >= 0.5 > b + c, never assembled; d/dx0 is a constant 1
    values, slopes, assembled = path_jacobian().arrays(np.array([0.0, 3.0]), 0.0, 0.0, 0.0, 0.0, 1.0, 0.1, 0.1,
                                                       1.5, 0.5, 0.2, 1.0)
    assert not assembled.any()
    assert np.isnan(values).all() and np.isnan(slopes).all()
    keywords = dict(zip(DESIGN_NAMES, (0.0, 0.0, 0.0, 1.0, 0.1, 0.1, 1.5, 0.5, 0.2)), theta=np.array([0.0, 3.0]),
                    crank_phase=0.0, branch=1.0)
    checked_values, checked_slopes = path_jacobian()(**keywords)
    assert not checked_values["assembled"].any() and np.isnan(checked_slopes).all()


def _check_against_mpmath(design, targets):
    """The design's own points (mpmath) at its crank angles match the targets; its reported errors are right."""
    for theta, target, error in zip(design.theta, targets, design.errors):
        point = mp_point(design.vector, mp.mpf(theta), design.branch)
        distance = float(abs(point - mp.mpc(*target)))
        assert error == pytest.approx(distance, abs=1e-12)


@pytest.mark.parametrize("seed", [3, 11])
def test_timed_recovery_of_a_random_crank_rocker(seed):
    rng = np.random.default_rng(seed)
    true = random_crank_rocker(rng)
    theta = np.sort(rng.uniform(0, 2 * np.pi, 8))
    targets = np.array([[float(p.real), float(p.imag)] for p in (mp_point(true.vector, t, true.branch)
                                                                 for t in theta)])
    designs = synthesize_path(targets, theta, seed=seed)
    best = designs[0]
    assert best.error < 1e-8
    assert best.theta == pytest.approx(tuple(theta))
    _check_against_mpmath(best, targets)
    size = math.hypot(*(targets.max(axis=0) - targets.min(axis=0)))
    assert max(best.errors) / size == pytest.approx(best.error)


def test_untimed_recovery_finds_angles_in_order():
    rng = np.random.default_rng(7)
    true = fourbar_design((0.2, 0.1), 0.4, (0.5, 2.0, 1.8, 2.2), (1.0, 0.6), branch=1)
    theta = np.sort(rng.uniform(0, 2 * np.pi, 6))
    targets = true.points(theta)
    best = synthesize_path(targets, None, seed=5)[0]
    assert best.error < 1e-8
    steps = np.diff(best.theta)
    assert np.all(steps > 0) or np.all(steps < 0)
    assert abs(best.theta[-1] - best.theta[0]) < 2 * math.pi
    _check_against_mpmath(best, targets)


def _recovery_problem(seed: int):
    """Ten points of a random crank-rocker's coupler curve, and their crank angles."""
    rng = np.random.default_rng(100 + seed)
    true = random_crank_rocker(rng)
    theta = np.sort(rng.uniform(0, 2 * np.pi, 10))
    return true.points(theta), theta


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(10))
def test_many_timed_recoveries(seed):
    targets, theta = _recovery_problem(seed)
    assert synthesize_path(targets, theta, seed=seed)[0].error < 1e-8


@pytest.mark.slow
def test_untimed_recoveries_keep_their_measured_rate():
    """Without timing the crank angles are unknowns too, and the search is harder: on these ten problems all ten
    reach 1e-8 (9 did with plain Levenberg-Marquardt and screened starts: seed 1 stopped at 7e-8 along a flat
    valley); the test keeps that rate from falling.  Each call's work is bounded (four batches of starts, at most
    two long second refinements): under 10 s for the ten on the loaded machine it was measured on."""
    errors = [synthesize_path(*_recovery_problem(seed)[:1], None, seed=seed)[0].error for seed in range(10)]
    assert sum(error < 1e-8 for error in errors) >= 10, errors


def test_accelerated_levenberg_marquardt_walks_the_rosenbrock_valley():
    # Rosenbrock's function as least squares, r = (10 (y - x^2), 1 - x): the curved valley the geodesic
    # acceleration is for; its only minimum, (1, 1), by hand.
    def residuals(x):
        return np.array([10 * (x[1] - x[0] ** 2), 1 - x[0]]), np.array([[-20 * x[0], 10.0], [-1.0, 0.0]])

    x, cost, used = _accelerated_levenberg_marquardt(residuals, np.array([-1.2, 1.0]), 500, 1e-15)
    assert x == pytest.approx([1.0, 1.0], abs=1e-10) and cost < 1e-20 and used <= 500


def test_accelerated_levenberg_marquardt_never_accepts_an_infeasible_trial():
    # Trials with x > 0.5 are infeasible: the walk must stop at the wall, short of (1, 1), where the least cost left
    # is (1 - 0.5)^2 / 2 = 0.125 at (0.5, 0.25).
    def residuals(x):
        if x[0] > 0.5:
            return None
        return np.array([10 * (x[1] - x[0] ** 2), 1 - x[0]]), np.array([[-20 * x[0], 10.0], [-1.0, 0.0]])

    x, cost, _ = _accelerated_levenberg_marquardt(residuals, np.array([-1.2, 1.0]), 500, 1e-15)
    assert x[0] <= 0.5 and 0.125 <= cost < 0.14
    assert _accelerated_levenberg_marquardt(residuals, np.array([0.6, 0.0]), 500, 1e-15) is None


def rosenbrock(x):
    return np.array([10 * (x[1] - x[0] ** 2), 1 - x[0]]), np.array([[-20 * x[0], 10.0], [-1.0, 0.0]])


NO_WALLS = np.zeros((0, 2)), np.zeros(0)


def test_active_set_levenberg_marquardt_ends_on_the_wall_exactly():
    # The same valley with the wall x <= 0.5 (a bound): the least cost on the wall is at y = x^2 = 0.25, where
    # (1 - 0.5)^2 / 2 = 0.125, and it is the constrained minimum, as the cost's slope by x there,
    # d/dx [50 (y - x^2)^2 + (1 - x)^2 / 2] = -(1 - x) = -0.5, pushes into the wall (all by hand).
    x, cost, used = _active_set_levenberg_marquardt(rosenbrock, np.array([-1.2, 1.0]), np.array([-np.inf, -np.inf]),
                                                    np.array([0.5, np.inf]), *NO_WALLS, 500, 1e-15)
    assert x[0] == 0.5 and x[1] == pytest.approx(0.25, abs=1e-10) and cost == pytest.approx(0.125, rel=1e-12)
    assert used <= 500
    # The same wall as an inequality row (x <= 0.5 written 2 x <= 1)
    x, cost, _ = _active_set_levenberg_marquardt(rosenbrock, np.array([-1.2, 1.0]), np.full(2, -np.inf),
                                                 np.full(2, np.inf), np.array([[2.0, 0.0]]), np.array([1.0]), 500,
                                                 1e-15)
    assert x[0] <= 0.5 and x == pytest.approx([0.5, 0.25], abs=1e-10) and cost == pytest.approx(0.125, rel=1e-12)


def distance_to(target):
    return lambda x: (x - target, np.eye(2))


@pytest.mark.parametrize("start, target, expected", [
    # from the wall x >= 0 to the point (2, -5), inside both walls: the wall is let go, the point reached
    ((0.0, 0.0), (2.0, -5.0), (2.0, -5.0)),
    # from the wall x >= 0 to the wall x + y <= 1: the nearest point to (2, 2) on the line x + y = 1 is (0.5, 0.5)
    ((0.0, 0.3), (2.0, 2.0), (0.5, 0.5)),
])
def test_active_set_levenberg_marquardt_lets_go_of_a_wall_the_cost_falls_away_from(start, target, expected):
    x, cost, _ = _active_set_levenberg_marquardt(distance_to(np.array(target)), np.array(start),
                                                 np.array([0.0, -np.inf]), np.full(2, np.inf),
                                                 np.array([[1.0, 1.0]]), np.array([1.0]), 200, 1e-15)
    assert x == pytest.approx(expected, abs=1e-9)  # (the cost, 2.25 in the second, stalls to rounding first)
    assert x[0] >= 0 and x[0] + x[1] <= 1 + 1e-15


def test_active_set_levenberg_marquardt_never_accepts_an_infeasible_trial():
    def residuals(x):
        return None if x[1] > 0.2 else rosenbrock(x)  # a wall it cannot see, refused like a toggle

    x, cost, _ = _active_set_levenberg_marquardt(residuals, np.array([-1.2, 0.1]), np.full(2, -np.inf),
                                                 np.array([0.5, np.inf]), *NO_WALLS, 500, 1e-15)
    assert x[1] <= 0.2 and x[0] <= 0.5 and cost < rosenbrock(np.array([-1.2, 0.1]))[0] @ rosenbrock(
        np.array([-1.2, 0.1]))[0] / 2
    assert _active_set_levenberg_marquardt(residuals, np.array([0.0, 0.5]), np.full(2, -np.inf),
                                           np.full(2, np.inf), *NO_WALLS, 500, 1e-15) is None


@pytest.mark.parametrize("name, shortest", [("crank-rocker", 0), ("double-rocker", 1), ("rocker-crank", 2),
                                            ("double-crank", 3)])
def test_grashof_walls_are_the_class_by_the_hand_rule(name, shortest):
    # s + l < p + q with the named link the shortest (the hand rule), against the rows' normals @ x <= 0
    rng = np.random.default_rng(shortest)
    lower, upper, normals, offsets = _linear_walls(_Constraints(name), np.zeros(9))
    assert normals.shape == (3, 9) and np.all(offsets == 0) and np.all(np.isinf(lower)) and np.all(np.isinf(upper))
    agree = 0
    for _ in range(400):
        lengths = rng.uniform(0.1, 3.0, 4)
        s, l = lengths.min(), lengths.max()
        margin = abs(s + l - (lengths.sum() - s - l))
        if margin < 1e-6 or np.sum(lengths == s) > 1:
            continue
        by_hand = s + l < lengths.sum() - s - l and lengths[shortest] == s
        x = np.concatenate([[0.0, 0.0, 0.0], lengths, [0.0, 0.0]])
        assert bool(np.all(normals @ x <= offsets)) == by_hand
        agree += by_hand
    assert agree > 20  # both outcomes were met


def test_arc_positions_of_a_uniform_circle_are_proportional():
    # A circle sampled at equal angles: its arc length grows evenly, so the fraction f lies at sample f * samples
    # (a hand formula), whatever the radius.
    samples = 96
    angles = np.linspace(-math.pi, math.pi, samples + 1)[:-1]
    curves = np.stack([np.exp(1j * angles), 3 * np.exp(1j * angles) + 2])
    closed = np.concatenate([curves, curves[:, :1]], axis=1)
    arc = np.concatenate([np.zeros((2, 1)), np.cumsum(np.abs(np.diff(closed, axis=1)), axis=1)], axis=1)
    arc /= arc[:, -1:]
    table = np.array([np.interp(np.linspace(0, 1, 513), row, np.arange(samples + 1.0)) for row in arc])
    fractions = np.array([0.0, 0.1, 0.37, 0.5, 0.999, 1.0])
    assert _arc_position(table, fractions) == pytest.approx(np.tile(fractions * samples, (2, 1)), abs=1e-9)


def test_designs_a_turn_apart_in_frame_are_one_design():
    first = fourbar_design((0.0, 0.0), 0.5, (1.0, 3.0, 2.5, 3.2), (1.5, 0.8))
    same = replace(first, frame=0.5 - 2 * math.pi)
    other = replace(first, frame=0.6)
    assert _distinct([first, same, other], 3, 1.0) == [first, other]
    assert _distinct([first, same, other], 0, 1.0) == []


def hand_transmission_worst(a, b, c, d, samples=3601):
    """The worst transmission angle over a crank turn: cos mu = (b^2 + c^2 - |BD|^2) / (2 b c)."""
    theta = np.linspace(-math.pi, math.pi, samples)
    bd2 = a * a + d * d - 2 * a * d * np.cos(theta)
    mu = np.arccos(np.clip((b * b + c * c - bd2) / (2 * b * c), -1, 1))
    return float(np.min(np.minimum(mu, math.pi - mu)))


def test_constraints_hold_in_every_returned_design():
    # Points off any one crank-rocker's curve (a wobbly arc), so the constraints bind.
    angles = np.linspace(0.3, 2.2, 7)
    targets = np.stack([3 * np.cos(angles), 2 * np.sin(angles) + 0.2 * np.sin(5 * angles)], axis=1)
    theta = np.linspace(0.0, 3.0, 7)
    limit = math.radians(35)
    designs = synthesize_path(targets, theta, grashof_class="crank-rocker", max_link_ratio=6.0,
                              min_transmission=limit, designs=2, starts=3, seed=2)
    for design in designs:
        a, b, c, d = design.lengths
        s, l = min(design.lengths), max(design.lengths)
        assert a == s and s + l < a + b + c + d - s - l  # crank-rocker by hand
        assert l / s <= 6.0
        assert hand_transmission_worst(a, b, c, d) >= limit - 1e-3
        _check_against_mpmath(design, targets)


def test_impossible_constraints_are_reported():
    targets = np.array([[0.0, 0.0], [1.0, 0.2], [2.0, 0.1], [3.0, 0.5]])
    with pytest.raises(ValueError, match="no four-bar"):
        synthesize_path(targets, [0.0, 0.5, 1.0, 1.5], max_link_ratio=1.0, starts=2)


def test_branch_and_order_defects_are_refused():
    # A triple rocker: its crank swings between two toggles; points on both sides of a toggle cannot be reached in
    # order on one branch.
    design = fourbar_design((0.0, 0.0), 0.0, (2.0, 1.0, 2.5, 3.0), (0.5, 0.3), branch=1)
    # |BD|^2 = 13 - 12 cos(theta) between (c - b)^2 and (b + c)^2: theta in [26.4, 86.4] deg and its mirror
    lower_toggle = math.acos((4 + 9 - (2.5 - 1) ** 2) / (2 * 2 * 3))  # |BD| = c - b
    inside = [lower_toggle + 0.1, lower_toggle + 0.3]
    targets = design.points(inside)
    checked = check_design(design, targets, inside)
    assert checked.error < 1e-12
    across = [lower_toggle + 0.1, -(lower_toggle + 0.1)]  # through theta = 0, where it cannot be assembled
    with pytest.raises(ValueError, match="cannot move from point 1 to point 2"):
        check_design(design, design.points([lower_toggle + 0.1, lower_toggle + 0.2]), across)


TARGETS = np.array([[0.0, 0.0], [1.0, 0.2], [2.0, 0.1], [3.0, 0.5]])
BAD = [
    ("not rows of two", dict(targets=np.zeros((4, 3))), "rows of"),
    ("NaN target", dict(targets=np.array([[0, 0], [1, np.nan], [2, 0], [3, 1]])), "finite"),
    ("too few", dict(targets=TARGETS[:2], theta=[0.0, 1.0]), "at least 3"),
    ("too few untimed", dict(targets=TARGETS[:3]), "at least 4"),
    ("angles mismatch", dict(targets=TARGETS, theta=[0.0, 1.0]), "crank angles"),
    ("NaN angle", dict(targets=TARGETS, theta=[0.0, 1.0, np.nan, 2.0]), "finite"),
    ("one point", dict(targets=np.ones((4, 2)), theta=[0.0, 1.0, 2.0, 3.0]), "same point"),
    ("grashof", dict(targets=TARGETS, grashof_class="crank"), "grashof_class"),
    ("ratio", dict(targets=TARGETS, max_link_ratio=0.5), "link ratio"),
    ("transmission", dict(targets=TARGETS, min_transmission=2.0), "transmission"),
    ("starts", dict(targets=TARGETS, starts=0), "starts"),
]


@pytest.mark.parametrize("name,kwargs,message", BAD, ids=[b[0] for b in BAD])
def test_bad_input(name, kwargs, message):
    with pytest.raises(ValueError, match=message):
        synthesize_path(**kwargs)


@pytest.mark.parametrize("kwargs,message", [
    (dict(lengths=(1, -2, 3, 4)), "coupler must be a positive"),
    (dict(branch=0), "branch"),
    (dict(frame=float("inf")), "finite"),
])
def test_bad_designs(kwargs, message):
    base = dict(crank_pivot=(0, 0), frame=0.0, lengths=(1, 2, 3, 4), coupler_point=(1, 1), branch=1)
    with pytest.raises(ValueError, match=message):
        fourbar_design(**{**base, **kwargs})


@pytest.mark.parametrize("scale", [1e300, 1e-300])
def test_targets_too_large_or_too_small_are_refused_by_name(scale):
    """Points at 1e300 or spanning 1e-300 would over- or underflow the design's squared lengths: refused, not solved."""
    from symlink.synthesis.path import synthesize_path
    points = np.array([[0.0, 0.0], [1.0, 0.5], [2.0, 0.0], [1.0, -0.5], [0.5, 0.2]]) * scale
    with pytest.raises(ValueError, match="target points must lie within"):
        synthesize_path(points)


# --- the transmission angle held over the motion the design runs (issue 32, item 2) ---------------------------

def hand_worst_over(a, b, c, d, low, high, samples=3600):
    """min(mu, pi - mu) over crank angles low..high, the law of cosines over the diagonal BD, in degrees."""
    theta = np.linspace(low, high, samples)
    bd2 = a * a + d * d - 2 * a * d * np.cos(theta)
    mu = np.arccos(np.clip((b * b + c * c - bd2) / (2 * b * c), -1, 1))
    return math.degrees(float(np.min(np.minimum(mu, math.pi - mu))))


def crank_turns_by_hand(a, b, c, d):
    """Grashof (s + l < p + q) with the crank or the ground the shortest: the crank turns fully."""
    s, p, q, l = sorted((a, b, c, d))
    return s + l < p + q and min(a, b, c, d) in (a, d)


def test_min_transmission_holds_over_the_rocking_range_of_a_rocker():
    # A triple rocker (2.6 + 3.2 > 3.0 + 2.5) through seven timed points: between its first and last target its
    # worst transmission angle is 39.7 deg (by hand, below), though it reaches 0 at its toggles.  The search
    # held 35 deg over every crank angle it could reach, refused every rocker, and returned a crank-rocker
    # 2.4e-3 of the targets' size off; held over the rocking range it runs, the exact design is found.
    truth = fourbar_design((0.0, 0.0), 0.0, (2.6, 3.0, 2.5, 3.2), (1.5, 0.8), branch=1)
    theta = np.linspace(0.9, 2.2, 7)
    assert hand_worst_over(2.6, 3.0, 2.5, 3.2, 0.9, 2.2) == pytest.approx(39.69, abs=0.01)
    (found,) = synthesize_path(truth.points(theta), theta, min_transmission=math.radians(35), starts=3,
                               designs=1)
    assert found.error < 1e-8
    a, b, c, d = found.lengths
    assert not crank_turns_by_hand(a, b, c, d)
    assert hand_worst_over(a, b, c, d, min(found.theta), max(found.theta)) >= 35 - 1e-6
    assert found.transmission_over == f"input {math.degrees(min(theta)):.6g}-{math.degrees(max(theta)):.6g} deg"
    assert math.degrees(found.worst_transmission) == pytest.approx(hand_worst_over(a, b, c, d, 0.9, 2.2), abs=1e-6)


def test_min_transmission_holds_over_the_full_turn_of_a_crank():
    # A crank-rocker whose transmission angle is 44.6 deg and more at its targets but 34.5 deg at theta = 0: held at
    # 35 deg over the full turn it runs, not at the targets alone.
    truth = fourbar_design((0.0, 0.0), 0.0, (1.5, 3.0, 2.5, 3.2), (1.5, 0.8), branch=1)
    theta = np.linspace(0.6, 2.6, 7)
    assert hand_worst_over(1.5, 3.0, 2.5, 3.2, -math.pi, math.pi) < 35 < hand_worst_over(1.5, 3.0, 2.5, 3.2, 0.6, 2.6)
    designs = synthesize_path(truth.points(theta), theta, grashof_class="crank-rocker",
                              min_transmission=math.radians(35), starts=3, designs=2)
    for found in designs:
        a, b, c, d = found.lengths
        assert crank_turns_by_hand(a, b, c, d)
        assert hand_worst_over(a, b, c, d, -math.pi, math.pi) >= 35 - 1e-6
        assert found.transmission_over == "the full turn"


def test_a_transmission_angle_no_design_can_hold_is_refused():
    truth = fourbar_design((0.0, 0.0), 0.0, (1.5, 3.0, 2.5, 3.2), (1.5, 0.8), branch=1)
    theta = np.linspace(0.6, 2.6, 5)
    with pytest.raises(ValueError, match="no four-bar satisfying the constraints .*89.5 deg held over the motion"):
        synthesize_path(truth.points(theta), theta, min_transmission=math.radians(89.5), starts=2, designs=1)
