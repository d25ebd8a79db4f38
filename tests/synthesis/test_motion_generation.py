"""Motion generation by Burmester theory, checked against four-bars whose poses the test computes itself.

The poses of a known four-bar's coupler are computed here at 40 digits with mpmath (circle
intersection for the joint C on the chosen branch, coupler point and angle from B and C),
in a frame that is moved and turned off the conventions' one, never with the code under
test.  The synthesis must then find the four-bar's own two dyads (fixed pivot and moving
pivot) among the Burmester points of five of its poses, and its centre-point curve must
pass through them for four.  Circle and centre points of two and three poses are checked
with distances and with the perpendicular bisectors solved as a linear system.
"""
import cmath
import json
import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from symlink.synthesis.motion import (Dyad, as_record, burmester_curves, burmester_points, centre_point,
                                      check_poses, circle_point, four_pose_dyads, fourbar_from_dyads,
                                      motion_generation, pole, pole_triangle, two_pose_centre)

mp.mp.dps = 40


class KnownFourbar:
    """A four-bar placed anywhere: crank pivot A, rocker pivot D, coupler frame at P = B + p e^{i(beta + gamma)}."""

    def __init__(self, a, b, c, d, p, gamma, offset, origin=0j, turn=0.0, branch=1):
        self.a, self.b, self.c, self.d = (mp.mpf(x) for x in (a, b, c, d))
        self.p, self.gamma, self.offset = mp.mpf(p), mp.mpf(gamma), mp.mpf(offset)
        self.origin, self.turn, self.branch = mp.mpc(origin), mp.mpf(turn), branch

    def _ground(self, z):
        return self.origin + z * mp.expj(self.turn)

    @property
    def crank_pivot(self):
        return self._ground(mp.mpc(0))

    @property
    def rocker_pivot(self):
        return self._ground(mp.mpc(self.d))

    def joints(self, theta):
        """B and C (ground frame) at crank angle theta on the branch (C left of B->D for +1)."""
        b = self.a * mp.expj(theta)
        to_d = self.d - b
        length = abs(to_d)
        along = (self.b ** 2 - self.c ** 2 + length ** 2) / (2 * length)
        height = mp.sqrt(self.b ** 2 - along ** 2)
        unit = to_d / length
        c = b + along * unit + self.branch * height * 1j * unit
        return self._ground(b), self._ground(c)

    def pose(self, theta):
        b, c = self.joints(theta)
        beta = mp.arg(c - b)
        point = b + self.p * mp.expj(beta + self.gamma)
        return (float(point.real), float(point.imag), float(beta + self.offset))

    def poses(self, thetas):
        return [self.pose(mp.mpf(theta)) for theta in thetas]

    def moving_pivots(self, theta):
        return self.joints(mp.mpf(theta))


def random_crank_rocker(rng, branch=1):
    """A crank-rocker (a shortest, s + l < p + q, decided here by hand) placed at random."""
    while True:
        a = 1.0
        b, c, d = rng.uniform(1.5, 4.0, 3)
        links = sorted([a, b, c, d])
        if links[0] + links[3] < links[1] + links[2] - 0.2:
            break
    return KnownFourbar(a, b, c, d, rng.uniform(0.5, 3), rng.uniform(-math.pi, math.pi),
                        rng.uniform(-math.pi, math.pi), complex(*rng.uniform(-5, 5, 2)), rng.uniform(-math.pi, math.pi),
                        branch)


def spread_angles(rng, count):
    """Increasing crank angles at least 0.3 rad apart within one turn."""
    while True:
        angles = np.sort(rng.uniform(0, 2 * math.pi, count))
        if np.all(np.diff(angles) > 0.3) and angles[-1] - angles[0] < 2 * math.pi - 0.3:
            return angles


def close(point, expected, scale, tolerance=1e-8):
    return abs(complex(*point) - complex(expected)) <= tolerance * scale


def find(dyads, fixed, moving, poses, scale):
    return [dyad for dyad in dyads if close(dyad.fixed, fixed, scale) and close(dyad.circle_point(poses), moving, scale)]


# --- five poses: the Burmester points recover the linkage ---------------------------------------

@pytest.mark.parametrize("seed", range(40))
def test_five_poses_of_a_fourbar_recover_its_two_dyads(seed):
    rng = np.random.default_rng(seed)
    linkage = random_crank_rocker(rng, branch=int(rng.choice([1, -1])))
    thetas = spread_angles(rng, 5)
    poses = linkage.poses(thetas)
    scale = float(linkage.d + linkage.b)
    dyads = burmester_points(poses)
    assert 2 <= len(dyads) <= 4
    b1, c1 = linkage.moving_pivots(thetas[0])
    cranks = find(dyads, linkage.crank_pivot, b1, poses, scale)
    rockers = find(dyads, linkage.rocker_pivot, c1, poses, scale)
    assert len(cranks) == 1 and len(rockers) == 1
    # The four-bar they make is the original one, on its branch, in order, with its class.
    design = fourbar_from_dyads(poses, cranks[0], rockers[0])
    assert np.allclose([design.crank, design.coupler, design.rocker, design.ground],
                       [float(x) for x in (linkage.a, linkage.b, linkage.c, linkage.d)], rtol=1e-8)
    assert design.branches == (linkage.branch,) * 5
    assert not design.branch_defect and not design.order_defect and design.order_direction == 1
    assert design.grashof == "crank-rocker"
    assert design.coupler_point_distance == pytest.approx(float(linkage.p), rel=1e-8)
    assert cmath.exp(1j * design.coupler_point_angle) == pytest.approx(cmath.exp(1j * float(linkage.gamma)), abs=1e-8)
    assert cmath.exp(1j * design.pose_angle_offset) == pytest.approx(cmath.exp(1j * float(linkage.offset)), abs=1e-8)
    expected_thetas = np.exp(1j * thetas)
    assert np.allclose(np.exp(1j * np.array(design.crank_angles)), expected_thetas, atol=1e-8)
    # Every Burmester dyad found carries its moving pivot round a circle (distances computed here).
    for dyad in dyads:
        places = [complex(*poses[j][:2]) + cmath.exp(1j * poses[j][2]) * complex(*dyad.moving) for j in range(5)]
        radii = [abs(place - complex(*dyad.fixed)) for place in places]
        assert max(radii) - min(radii) <= 1e-9 * scale


def test_the_front_door_returns_the_original_fourbar_first_among_defect_free_designs():
    rng = np.random.default_rng(7)
    linkage = random_crank_rocker(rng)
    thetas = spread_angles(rng, 5)
    poses = linkage.poses(thetas)
    designs = motion_generation(poses)
    assert designs and all(isinstance(design.crank, float) for design in designs)
    scale = float(linkage.d + linkage.b)
    matching = [design for design in designs if close(design.crank_pivot, linkage.crank_pivot, scale)
                and close(design.rocker_pivot, linkage.rocker_pivot, scale)]
    assert len(matching) == 1 and matching[0].defect_free
    # sorted: defect-free first
    flags = [design.defect_free for design in designs]
    assert flags == sorted(flags, reverse=True)
    assert motion_generation(poses, defect_free=True) == [design for design in designs if design.defect_free]


def test_burmester_points_do_not_depend_on_the_units_or_the_frame():
    rng = np.random.default_rng(3)
    linkage = random_crank_rocker(rng)
    poses = np.array(linkage.poses(spread_angles(rng, 5)))
    moved = poses.copy()
    moved[:, :2] = poses[:, :2] * 1000.0 + [2.5e4, -1.0e4]
    first = burmester_points(poses)
    second = burmester_points(moved)
    assert len(first) == len(second)
    for one, two in zip(first, second):
        assert np.allclose(np.array(one.fixed) * 1000 + [2.5e4, -1.0e4], two.fixed, rtol=1e-9, atol=1e-6)
        assert np.allclose(np.array(one.moving) * 1000, two.moving, rtol=1e-9, atol=1e-6)


@pytest.mark.parametrize("seed", range(3))
def test_no_solution_found_by_brute_force_is_missing(seed):
    """Random poses; scipy's least squares from 60 random starts on the equal-radius equations finds no dyad we miss."""
    from scipy.optimize import least_squares
    rng = np.random.default_rng(500 + seed)
    poses = np.column_stack([rng.uniform(-1, 1, (5, 2)), rng.uniform(-1.5, 1.5, 5)])
    origins, turns = poses[:, 0] + 1j * poses[:, 1], np.exp(1j * poses[:, 2])

    def residual(x):  # unknowns: fixed pivot G and the moving pivot's frame coordinates m
        places = origins + turns * complex(x[2], x[3])
        radii = np.abs(places - complex(x[0], x[1])) ** 2
        return radii[1:] - radii[0]

    brute = []
    for _ in range(60):
        fit = least_squares(residual, rng.uniform(-4, 4, 4), xtol=1e-15, ftol=1e-15, gtol=1e-15)
        g, m = complex(*fit.x[:2]), complex(*fit.x[2:])
        if np.abs(residual(fit.x)).max() < 1e-10 and abs(origins[0] + turns[0] * m - g) > 1e-6 and abs(g) < 50:
            brute.append((g, m))
    dyads = burmester_points(poses)
    assert brute, "the brute force found nothing to compare"
    assert len(dyads) <= 4
    ours = [(complex(*dyad.fixed), complex(*dyad.moving)) for dyad in dyads]
    for g, m in brute:
        assert min(abs(g - g0) + abs(m - m0) for g0, m0 in ours) < 1e-6
    for dyad in dyads:
        assert dyad.radius_spread(poses) < 1e-9 * max(1.0, dyad.length(poses))


# --- four poses: the curves pass through the pivots ------------------------------------------------

@pytest.mark.parametrize("seed", range(10))
def test_four_pose_dyads_at_the_true_crank_rotation_are_the_fourbars_own(seed):
    rng = np.random.default_rng(100 + seed)
    linkage = random_crank_rocker(rng)
    thetas = spread_angles(rng, 4)
    poses = linkage.poses(thetas)
    scale = float(linkage.d + linkage.b)
    b1, c1 = linkage.moving_pivots(thetas[0])
    crank_rotation = thetas[1] - thetas[0]
    assert find(four_pose_dyads(poses, crank_rotation), linkage.crank_pivot, b1, poses, scale)
    # the rocker's rotation from pose 1 to 2, measured here
    c2 = linkage.moving_pivots(thetas[1])[1]
    rocker_rotation = float(mp.arg((c2 - linkage.rocker_pivot) / (c1 - linkage.rocker_pivot)))
    assert find(four_pose_dyads(poses, rocker_rotation), linkage.rocker_pivot, c1, poses, scale)
    # and motion_generation with the two rotations contains the four-bar itself
    designs = motion_generation(poses, rotations=[crank_rotation, rocker_rotation])
    assert any(close(design.crank_pivot, linkage.crank_pivot, scale)
               and close(design.rocker_pivot, linkage.rocker_pivot, scale) and design.defect_free
               for design in designs)


@pytest.mark.parametrize("seed", range(5))
def test_the_centre_point_curve_passes_through_the_pole_p12(seed):
    """Burmester: the pole P12 is a centre point; its crank turns with the coupler (beta_2 = alpha_2)."""
    rng = np.random.default_rng(300 + seed)
    poses = np.column_stack([rng.uniform(-1, 1, (4, 2)), rng.uniform(-1.5, 1.5, 4)])
    turn = cmath.exp(1j * (poses[1, 2] - poses[0, 2]))
    first, second = complex(*poses[0, :2]), complex(*poses[1, :2])
    p12 = (second - turn * first) / (1 - turn)  # the fixed point of the displacement from pose 1 to 2
    fixed = [complex(*dyad.fixed) for dyad in four_pose_dyads(poses, poses[1, 2] - poses[0, 2])]
    assert min(abs(f - p12) for f in fixed) < 1e-9 * max(1.0, abs(p12))


def test_sampled_curves_pass_near_the_pivots_and_every_sample_is_a_dyad():
    rng = np.random.default_rng(11)
    linkage = random_crank_rocker(rng)
    thetas = spread_angles(rng, 4)
    poses = linkage.poses(thetas)
    curves = burmester_curves(poses, samples=2001)
    b1, c1 = linkage.moving_pivots(thetas[0])
    for pivot, moving in ((linkage.crank_pivot, b1), (linkage.rocker_pivot, c1)):
        centres = curves.centre_points.reshape(-1, 2)
        circles = curves.circle_points.reshape(-1, 2)
        distance = np.nanmin(np.hypot(*(centres - [float(pivot.real), float(pivot.imag)]).T))
        nearest = np.nanargmin(np.hypot(*(centres - [float(pivot.real), float(pivot.imag)]).T))
        assert distance < 0.02 * float(linkage.d)
        assert np.hypot(*(circles[nearest] - [float(moving.real), float(moving.imag)])) < 0.05 * float(linkage.d)
    # each sample: the circle point's four positions are equidistant from the centre point
    for way in range(2):
        for fixed, first in zip(curves.centre_points[way][::50], curves.circle_points[way][::50]):
            if np.isnan(fixed).any() or np.abs(fixed).max() > 1e3:
                continue
            local = (complex(*first) - complex(*poses[0][:2])) * cmath.exp(-1j * poses[0][2])
            radii = [abs(complex(*pose[:2]) + cmath.exp(1j * pose[2]) * local - complex(*fixed)) for pose in poses]
            assert max(radii) - min(radii) <= 1e-9 * max(radii)


# --- two and three poses ------------------------------------------------------------------------------

def bisector_centre(points):
    """The centre of the circle through three points, from two perpendicular bisectors (a 2x2 solve)."""
    (x1, y1), (x2, y2), (x3, y3) = points
    matrix = np.array([[x2 - x1, y2 - y1], [x3 - x1, y3 - y1]])
    right = 0.5 * np.array([x2 ** 2 - x1 ** 2 + y2 ** 2 - y1 ** 2, x3 ** 2 - x1 ** 2 + y3 ** 2 - y1 ** 2])
    return np.linalg.solve(matrix, right)


def positions(poses, local):
    return [(x + math.cos(t) * local[0] - math.sin(t) * local[1], y + math.sin(t) * local[0] + math.cos(t) * local[1])
            for x, y, t in poses]


poses3 = st.lists(st.tuples(st.floats(-10, 10), st.floats(-10, 10), st.floats(-3, 3)), min_size=3, max_size=3)


def well_conditioned(points, size):
    """Three places far enough apart and far enough from a line (10^-6 of ``size``) that the circle through them
    is fixed to about 10^-10: nearly coincident places (poses 10^-9 rad apart, a pole) let rounding move it."""
    a, b, c = (complex(*point) for point in points)
    sides = (abs(b - a), abs(c - a), abs(c - b))
    return min(sides) > 1e-6 * size and abs(((b - a).conjugate() * (c - a)).imag) > 1e-6 * max(sides) ** 2


@settings(max_examples=60, deadline=None)
@given(poses3, st.tuples(st.floats(-10, 10), st.floats(-10, 10)))
def test_three_positions_of_the_circle_point_lie_on_a_circle_about_the_centre_point(poses, start):
    try:
        dyad = centre_point(poses, start)
    except ValueError:
        return  # the positions are in line, two coincide or the poses coincide: reported, not returned
    places = positions(poses, dyad.moving)
    assert np.allclose(places[0], start, atol=1e-9)
    radii = [math.dist(place, dyad.fixed) for place in places]
    size = max(10.0, max(radii))
    if not well_conditioned(places, size):
        return
    assert max(radii) - min(radii) <= 1e-9 * size
    if min(radii) < 1e3:  # well-conditioned: compare with the bisectors solved directly
        assert np.allclose(dyad.fixed, bisector_centre(places), rtol=1e-7, atol=1e-7)
        # the inverse problem is well-conditioned only where the fixed pivot, seen from the moving body, is on a
        # circle of moderate size too, through places well apart (its three relative places nearly in line or
        # nearly coincident put that circle's centre, the circle point, out of reach of rounding)
        seen = [(math.cos(t) * (dyad.fixed[0] - x) + math.sin(t) * (dyad.fixed[1] - y),
                 -math.sin(t) * (dyad.fixed[0] - x) + math.cos(t) * (dyad.fixed[1] - y)) for x, y, t in poses]
        if not well_conditioned(seen, size) or not math.dist(bisector_centre(seen), seen[0]) < 1e3:
            return
        inverse = circle_point(poses, dyad.fixed)
        assert np.allclose(inverse.circle_point(poses), start, rtol=1e-6, atol=1e-6)


def test_two_poses_centre_on_the_bisector_and_the_pole():
    poses = [(1.0, 2.0, 0.3), (3.0, 1.0, 1.1)]
    dyad = two_pose_centre(poses, (0.5, 0.5), 2.0)
    first, second = positions(poses, dyad.moving)
    assert np.allclose(first, (0.5, 0.5))
    assert math.dist(first, dyad.fixed) == pytest.approx(math.dist(second, dyad.fixed), rel=1e-12)
    midpoint = np.add(first, second) / 2
    assert math.dist(midpoint, dyad.fixed) == pytest.approx(2.0, rel=1e-12)
    travel = np.subtract(second, first)
    towards = np.subtract(dyad.fixed, midpoint)
    assert travel[0] * towards[1] - travel[1] * towards[0] > 0  # to the left of the travel
    # the pole stays put: its frame coordinates in pose 1 and pose 2 give the same ground point
    point = pole(poses)
    locals_ = [((point[0] - x) * math.cos(t) + (point[1] - y) * math.sin(t),
                -(point[0] - x) * math.sin(t) + (point[1] - y) * math.cos(t)) for x, y, t in poses]
    assert np.allclose(locals_[0], locals_[1], atol=1e-12)


def test_pole_triangle_of_a_rotation_about_one_point_is_that_point():
    centre = (2.0, -1.0)
    poses = []
    for angle in (0.2, 0.9, 1.7):  # the frame origin at distance 3 from the centre, turning about it
        poses.append((centre[0] + 3 * math.cos(angle), centre[1] + 3 * math.sin(angle), angle))
    for point in pole_triangle(poses):
        assert np.allclose(point, centre, atol=1e-12)


# --- defects ---------------------------------------------------------------------------------------------

def known_dyads(linkage, theta, poses):
    b, c = linkage.moving_pivots(theta)
    crank = Dyad((float(linkage.crank_pivot.real), float(linkage.crank_pivot.imag)), local_of(poses, b))
    rocker = Dyad((float(linkage.rocker_pivot.real), float(linkage.rocker_pivot.imag)), local_of(poses, c))
    return crank, rocker


def local_of(poses, point):
    x, y, t = poses[0]
    z = (complex(point) - complex(x, y)) * cmath.exp(-1j * t)
    return (z.real, z.imag)


def test_a_branch_switch_between_poses_is_a_branch_defect():
    rng = np.random.default_rng(5)
    up = random_crank_rocker(rng, branch=1)
    down = KnownFourbar(up.a, up.b, up.c, up.d, up.p, up.gamma, up.offset, up.origin, up.turn, branch=-1)
    thetas = spread_angles(rng, 5)
    poses = up.poses(thetas[:3]) + down.poses(thetas[3:])
    crank, rocker = known_dyads(up, thetas[0], poses)
    design = fourbar_from_dyads(poses, crank, rocker)
    assert design.branches == (1, 1, 1, -1, -1)
    assert design.branch_defect and not design.order_defect
    # the Burmester synthesis finds this pair too (the dyads do not know the branch) and flags it
    scale = float(up.d + up.b)
    flagged = [d for d in motion_generation(poses) if close(d.crank_pivot, up.crank_pivot, scale)
               and close(d.rocker_pivot, up.rocker_pivot, scale)]
    assert len(flagged) == 1 and flagged[0].branch_defect


def test_poses_out_of_the_crank_order_are_an_order_defect():
    rng = np.random.default_rng(6)
    linkage = random_crank_rocker(rng)
    thetas = spread_angles(rng, 5)
    shuffled = thetas[[0, 2, 1, 3, 4]]
    poses = linkage.poses(shuffled)
    crank, rocker = known_dyads(linkage, shuffled[0], poses)
    design = fourbar_from_dyads(poses, crank, rocker)
    assert design.order_defect and design.order_direction == 0 and not design.branch_defect
    # the same poses in reverse order are visited turning clockwise
    backwards = linkage.poses(thetas[::-1])
    crank, rocker = known_dyads(linkage, thetas[-1], backwards)
    design = fourbar_from_dyads(backwards, crank, rocker)
    assert not design.order_defect and design.order_direction == -1


def test_a_rocker_input_must_move_monotonically_within_its_range():
    # Driven from the rocker (swap the dyads), the input only swings: a crank-rocker's rocker
    # angles at increasing crank angles rise, then fall (its two limit positions): an order defect.
    linkage = KnownFourbar(1.0, 3.0, 2.5, 3.2, 1.0, 0.4, 0.0)
    thetas = np.radians([10, 80, 150, 220, 290])
    poses = linkage.poses(thetas)
    crank, rocker = known_dyads(linkage, thetas[0], poses)
    design = fourbar_from_dyads(poses, rocker, crank)
    assert design.grashof == "rocker-crank"
    angles = []
    for theta in thetas:  # the rocker's angle, computed here
        c = linkage.moving_pivots(theta)[1]
        angles.append(float(mp.arg(c - linkage.rocker_pivot)))
    monotonic = np.all(np.diff(angles) > 0) or np.all(np.diff(angles) < 0)
    assert design.order_defect == (not monotonic) and not monotonic


# --- records and bad input ---------------------------------------------------------------------------------

def test_record_is_json_ready_and_in_degrees():
    rng = np.random.default_rng(9)
    linkage = random_crank_rocker(rng)
    poses = linkage.poses(spread_angles(rng, 5))
    design = motion_generation(poses)[0]
    record = as_record(design)
    json.dumps(record)
    assert record["crank"] == design.crank
    assert record["ground_angle"] == pytest.approx(math.degrees(design.ground_angle))
    assert [record[f"branch_{j}"] for j in range(1, 6)] == list(design.branches)
    assert {"crank_pivot_x", "rocker_pivot_y", "branch_defect", "order_defect", "grashof"} <= set(record)


SQUARE = [(0, 0, 0), (1, 0, 0.2), (1, 1, 0.5), (0, 1, 0.9), (-0.5, 0.5, 1.4)]


@pytest.mark.parametrize("call, message", [
    (lambda: check_poses([(0, 0)]), "rows of three numbers"),
    (lambda: check_poses("abc"), "rows of three numbers"),
    (lambda: check_poses([(0, 0, 0), (1, float("nan"), 0)]), "finite"),
    (lambda: check_poses([(0, 0, 0)]), "2 to 5 poses"),
    (lambda: check_poses([(0, 0, 0)] * 6), "2 to 5 poses"),
    (lambda: check_poses([(0, 0, 0), (1, 1, 1), (0, 0, 2 * math.pi)]), "poses 1 and 3 are the same"),
    (lambda: pole([(0, 0, 0), (1, 1, 0)]), "translation only"),
    (lambda: pole([(0, 0, 0), (1, 1, 1)], 1, 3), "pose numbers run from 1 to 2"),
    (lambda: centre_point([(0, 0, 0), (1, 0, 0), (2, 0, 0)], (0, 0)), "in line"),
    (lambda: centre_point(SQUARE[:3], (0, float("inf"))), "moving pivot must be two finite"),
    # the moving pivot at the pole of poses 1 and 2 (rotation about the origin): two of its places coincide
    (lambda: centre_point([(0, 0, 0), (0, 0, 1), (1, 0, 0)], (0, 0)), "two of the three positions of the moving pivot coincide"),
    # a fixed pivot at the one pole of three rotations about (0, 1): seen from the coupler it never moves
    (lambda: circle_point([(0, 1, 0), (0, 1, 1), (0, 1, 2)], (0, 1 + 1e-17)), "coincide"),
    (lambda: two_pose_centre([(0, 0, 0), (1, 1, math.pi / 2)], (0, 1), 1.0), "pole"),
    (lambda: four_pose_dyads(SQUARE[:4], float("nan")), "rotation must be finite"),
    (lambda: burmester_curves(SQUARE[:4], samples=2), "at least 3 samples"),
    (lambda: burmester_points(SQUARE[:4]), "takes 5 poses"),
    (lambda: motion_generation(SQUARE[:3]), "either two moving pivots or two fixed pivots"),
    (lambda: motion_generation(SQUARE[:3], moving_pivots=[(0, 0)]), "give two moving pivots, got 1"),
    (lambda: motion_generation(SQUARE[:4]), "give two rotations"),
    (lambda: motion_generation(SQUARE, rotations=[1, 2]), "rotations cannot be chosen"),
    (lambda: motion_generation(SQUARE[:2], moving_pivots=[(0, 0), (1, 0)]), "give two offsets"),
    (lambda: fourbar_from_dyads(SQUARE[:3], Dyad((0, 0), (1, 0)), Dyad((0, 0), (1, 0))), "share a pivot"),
    (lambda: fourbar_from_dyads(SQUARE[:3], Dyad((0, 0), (1, 0)), Dyad((3, 0), (1, 2))), "does not reach the poses"),
])
def test_bad_input_is_refused_with_a_reason(call, message):
    with pytest.raises(ValueError, match=message):
        call()


@pytest.mark.slow
def test_burmester_recovery_of_many_fourbars_of_every_class():
    """1000 random four-bars of any class and branch, crank angles anywhere it assembles (close pairs too)."""
    rng = np.random.default_rng(12345)
    recovered = tried = 0
    while tried < 1000:
        a, b, c, d = rng.uniform(0.3, 4, 4)
        thetas = rng.uniform(-math.pi, math.pi, 5)
        diagonals = np.abs(d - a * np.exp(1j * thetas))
        if not np.all((abs(b - c) < diagonals) & (diagonals < b + c)):
            continue
        linkage = KnownFourbar(a, b, c, d, rng.uniform(0, 3), rng.uniform(-3, 3), rng.uniform(-3, 3),
                               complex(*rng.uniform(-5, 5, 2)), rng.uniform(-3, 3), int(rng.choice([1, -1])))
        poses = linkage.poses(thetas)
        tried += 1
        dyads = burmester_points(poses)
        assert len(dyads) <= 4
        b1, c1 = linkage.moving_pivots(thetas[0])
        scale = float(linkage.d + linkage.b)
        recovered += bool(find(dyads, linkage.crank_pivot, b1, poses, scale)
                          and find(dyads, linkage.rocker_pivot, c1, poses, scale))
    assert recovered == tried
