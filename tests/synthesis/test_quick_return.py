"""Quick-return synthesis (seed 002), re-checked by an independent computation.

The check never uses the synthesis' own numbers beyond the linkage it returns (lengths and
pivots): it rebuilds the linkage in the synthesis' frame (rocker pivot at the origin) with
mpmath circle intersections, finds the limit positions as the crank angles where crank and
coupler are in line (sign changes of their cross product, solved with scipy's brentq), and
takes stroke and time ratio from those.
"""
import cmath
import math

import mpmath as mp
import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from symlink.synthesis.quick_return import GOOD_TRANSMISSION, as_record, delta_for_time_ratio, quick_return

deg = math.radians
PAPER = dict(time_ratio=1.25, stroke=deg(40), rocker=50.0, rocker_min_angle=deg(90))


class Rebuilt:
    """The synthesized linkage rebuilt from its lengths and pivots, at 30 digits."""

    def __init__(self, design, rocker_min_angle):
        self.a, self.b, self.c = (mp.mpf(x) for x in (design.crank, design.coupler, design.rocker))
        self.p = mp.mpc(*design.crank_pivot)
        # The assembly that reaches the rocker's minimum position: C on the same side of the
        # ground line (crank pivot -> rocker pivot at 0) as that position.
        b1 = self.c * mp.expj(rocker_min_angle)
        self.side = mp.sign(self._cross(-self.p, b1 - self.p))

    @staticmethod
    def _cross(u, v):
        return u.real * v.imag - u.imag * v.real

    def joints(self, theta):
        with mp.workdps(30):
            b = self.p + self.a * mp.expj(theta)
            length = abs(b)
            along = (self.c**2 - self.b**2 + length**2) / (2 * length)
            h = mp.sqrt(self.c**2 - along**2)
            u = b / length
            points = [along * u + s * h * 1j * u for s in (1, -1)]
            c = max(points, key=lambda q: self.side * self._cross(-self.p, q - self.p))
            return b, c

    def crank_coupler_cross(self, theta):
        b, c = self.joints(theta)
        return float(self._cross(b - self.p, c - b) / (self.a * self.b))

    def limit_positions(self):
        grid = np.linspace(-math.pi, math.pi, 361)
        values = [self.crank_coupler_cross(t) for t in grid]
        roots = [brentq(self.crank_coupler_cross, lo, hi, xtol=1e-15, rtol=1e-15)
                 for lo, hi, f1, f2 in zip(grid, grid[1:], values, values[1:]) if f1 * f2 < 0]
        assert len(roots) == 2
        rockers = [float(mp.arg(self.joints(t)[1])) for t in roots]
        return roots, rockers

    def transmission(self, theta):
        """Interior angle at C between C->B and C->O4."""
        b, c = self.joints(theta)
        return float(abs(mp.arg((b - c) / (-c))))

    def transmission_extremes(self):
        grid = np.linspace(-math.pi, math.pi, 721)
        values = np.array([self.transmission(t) for t in grid])
        found = []
        for sign in (1, -1):
            i = int(np.argmin(sign * values))
            best = minimize_scalar(lambda t: sign * self.transmission(t), bounds=(grid[i - 1], grid[i + 1]),
                                   method="bounded", options={"xatol": 1e-10})
            found.append(sign * best.fun)
        return found


def stroke_and_time_ratio(roots, rockers):
    stroke = abs(math.remainder(rockers[1] - rockers[0], 2 * math.pi))
    turn = (roots[1] - roots[0]) % (2 * math.pi)
    return stroke, max(turn, 2 * math.pi - turn) / min(turn, 2 * math.pi - turn), rockers


# --- the paper's procedure, crank pivot fixed ----------------------------------------

def test_paper_data_with_its_crank_pivot():
    design = quick_return(**PAPER, crank_pivot=(-70.0, 0.0))
    # Seed 002 prints L2 = 16.084 for this request, and a time ratio of 1.114 (its coupler was drawn).
    assert round(design.crank, 3) == 16.084
    assert design.ground == 70.0 and design.grashof == "crank-rocker"
    # By hand: O2 B1 = |(70, 50)|, O2 B2 = |(70 + 50 cos 130, 50 sin 130)|; a, b half their difference and sum.
    far, near = math.hypot(70, 50), abs(70 + 50 * cmath.exp(1j * deg(130)))
    assert design.crank == pytest.approx((far - near) / 2, rel=1e-13)
    assert design.coupler == pytest.approx((far + near) / 2, rel=1e-13)
    stroke, ratio, rockers = stroke_and_time_ratio(*Rebuilt(design, deg(90)).limit_positions())
    assert abs(design.time_ratio - ratio) < 1e-9 and abs(design.stroke - stroke) < 1e-9
    assert round(ratio, 3) == 1.115 and abs(stroke - deg(40)) < 1e-9
    assert sorted(rockers) == pytest.approx([deg(90), deg(130)], abs=1e-9)
    (warning,) = design.warnings
    assert "requested time ratio 1.25 is not met" in warning and "1.1151" in warning and "-0.1349" in warning


def test_fixed_pivot_ignores_the_requested_ratio_as_the_paper_did():
    # The paper's cases 4.1 (TR 1), 4.2 (TR 1.15) and 4.3 (TR 1.25) all use this pivot and get one linkage.
    designs = [quick_return(ratio, deg(40), 50.0, deg(90), (-70.0, 0.0)) for ratio in (1.0, 1.15, 1.25)]
    assert len({(d.crank, d.coupler, d.ground) for d in designs}) == 1
    assert all("is not met" in d.warnings[0] for d in designs)


def test_fixed_pivot_between_the_rocker_ends_warns_about_the_stroke():
    # Ground line between B1 and B2: they are on different assembly branches.
    design = quick_return(**PAPER, crank_pivot=(20.0, -200.0))
    stroke, ratio, _ = stroke_and_time_ratio(*Rebuilt(design, deg(90)).limit_positions())
    assert stroke < deg(39)
    assert any("not the requested 40 deg" in w and "different assembly branches" in w for w in design.warnings)


@pytest.mark.parametrize("pivot, message", [
    ((0.0, 50.0), "coincides"),
    ((0.0, 0.0), "coincides"),
    ((100 * math.cos(deg(110)), 100 * math.sin(deg(110))), "equally far"),
    ((0.0, 1000.0), "change-point, not a crank-rocker"),
])
def test_fixed_pivots_that_give_no_quick_return(pivot, message):
    with pytest.raises(ValueError, match=message):
        quick_return(**PAPER, crank_pivot=pivot)


# --- exact synthesis, best transmission angle ----------------------------------------

def test_exact_design_meets_ratio_and_stroke():
    design = quick_return(**PAPER)
    rebuilt = Rebuilt(design, deg(90))
    stroke, ratio, rockers = stroke_and_time_ratio(*rebuilt.limit_positions())
    assert abs(ratio - 1.25) < 1e-9 and abs(stroke - deg(40)) < 1e-9
    assert sorted(rockers) == pytest.approx([deg(90), deg(130)], abs=1e-9)
    assert abs(design.time_ratio - ratio) < 1e-9 and abs(design.stroke - stroke) < 1e-9
    low, high = rebuilt.transmission_extremes()
    assert abs(design.transmission.minimum - low) < 1e-9 and abs(design.transmission.maximum - high) < 1e-9
    assert design.grashof == "crank-rocker"


@pytest.mark.parametrize("ratio, stroke, rocker, lowest", [
    (1.1, 30.0, 10.0, 0.0), (1.5, 60.0, 2.5, -120.0), (1.05, 75.0, 100.0, 200.0), (1.3, 20.0, 7.0, 45.0),
])
def test_other_exact_designs_meet_ratio_and_stroke(ratio, stroke, rocker, lowest):
    design = quick_return(ratio, deg(stroke), rocker, deg(lowest))
    found_stroke, found_ratio, rockers = stroke_and_time_ratio(*Rebuilt(design, deg(lowest)).limit_positions())
    assert abs(found_ratio - ratio) < 1e-9 and abs(found_stroke - deg(stroke)) < 1e-9
    ends = sorted(math.remainder(r - deg(lowest), 2 * math.pi) for r in rockers)
    assert ends == pytest.approx([0.0, deg(stroke)], abs=1e-9)
    assert design.grashof == "crank-rocker"


def test_best_worst_transmission_is_42_8_deg_and_below_45():
    design = quick_return(**PAPER)
    assert round(math.degrees(design.transmission.worst), 1) == 42.8
    assert design.transmission.worst < GOOD_TRANSMISSION
    assert any("42.81 deg, the best reachable" in w and "below the usual 45 deg" in w for w in design.warnings)


def worst_by_hand(a, b, c, d):
    """Worst transmission angle of a crank-rocker: mu at |BD| = d - a and d + a (law of cosines)."""
    mus = [math.acos((b * b + c * c - e * e) / (2 * b * c)) for e in (d - a, d + a)]
    return min(min(mu, math.pi - mu) for mu in mus)


def test_no_pivot_on_the_arcs_does_better():
    # Brute force over both circles on which B1 B2 subtends delta (inscribed angle theorem).
    b1, b2 = 50 * cmath.exp(1j * deg(90)), 50 * cmath.exp(1j * deg(130))
    delta = delta_for_time_ratio(1.25)
    chord = abs(b2 - b1)
    radius = chord / (2 * math.sin(delta))
    middle, normal = (b1 + b2) / 2, 1j * (b2 - b1) / chord
    best = -1.0
    for centre in (middle + normal * radius * math.cos(delta), middle - normal * radius * math.cos(delta)):
        for s in np.linspace(0, 2 * math.pi, 20000, endpoint=False):
            p = centre + radius * cmath.exp(1j * s)
            subtended = abs(cmath.phase((b2 - p) / (b1 - p)))
            if abs(subtended - delta) > 1e-9:
                continue  # the minor arc sees the chord at 180 - delta
            far, near = sorted((abs(b1 - p), abs(b2 - p)), reverse=True)
            a, b, d = (far - near) / 2, (far + near) / 2, abs(p)
            side1 = (-p.conjugate() * (b1 - p)).imag
            side2 = (-p.conjugate() * (b2 - p)).imag
            links = sorted((a, b, 50.0, d))
            if side1 * side2 <= 0 or links[0] != a or links[0] + links[3] >= links[1] + links[2]:
                continue
            best = max(best, worst_by_hand(a, b, 50.0, d))
    design = quick_return(**PAPER)
    assert best <= design.transmission.worst + 1e-9
    assert best >= design.transmission.worst - 1e-4


def test_the_design_turns_with_the_rocker_min_angle():
    upright, turned = quick_return(**PAPER), quick_return(**{**PAPER, "rocker_min_angle": deg(-35)})
    # The worst angle is flat at its maximum: its value is sharp, the place only to about 1e-8.
    assert turned.transmission.worst == pytest.approx(upright.transmission.worst, abs=1e-13)
    for name in ("crank", "coupler", "ground"):
        assert getattr(turned, name) == pytest.approx(getattr(upright, name), rel=1e-6)
    rotation = cmath.exp(1j * deg(-125))
    assert complex(*turned.crank_pivot) == pytest.approx(complex(*upright.crank_pivot) * rotation, abs=1e-5)


def test_time_ratio_one_is_limited_by_the_link_ratio():
    design = quick_return(1.0, deg(40), 50.0)
    stroke, ratio, _ = stroke_and_time_ratio(*Rebuilt(design, deg(90)).limit_positions())
    assert abs(ratio - 1) < 1e-9 and abs(stroke - deg(40)) < 1e-9
    assert max(design.coupler, design.ground) / design.crank == pytest.approx(10, rel=1e-6)
    assert any("limited to 10 times the crank" in w for w in design.warnings)
    looser = quick_return(1.0, deg(40), 50.0, max_link_ratio=20)
    assert looser.transmission.worst > design.transmission.worst


def test_the_record_has_the_issue_keys():
    record = as_record(quick_return(**PAPER))
    for key in ("crank", "coupler", "rocker", "ground", "crank_pivot", "rocker_pivot", "stroke", "time_ratio",
                "transmission_min", "transmission_max", "grashof"):
        assert key in record
    assert record["rocker_pivot"] == [0.0, 0.0] and len(record["crank_pivot"]) == 2
    assert record["stroke"] == pytest.approx(40, abs=1e-9)


@pytest.mark.parametrize("request_, message", [
    (dict(time_ratio=0.9), "time ratio must be .* at least 1"),
    (dict(time_ratio=math.nan), "time ratio must be"),
    (dict(stroke=0.0), "stroke must lie strictly between 0 and 180"),
    (dict(stroke=math.pi), "stroke must lie strictly between 0 and 180"),
    (dict(stroke=deg(200)), "got 200 deg"),
    (dict(stroke=-0.1), "stroke must"),
    (dict(rocker=0.0), "rocker must be a positive"),
    (dict(rocker=-5.0), "rocker must be a positive"),
    (dict(time_ratio=5.0, stroke=deg(20)), "no crank-rocker gives a time ratio of 5"),
])
def test_impossible_requests(request_, message):
    with pytest.raises(ValueError, match=message):
        quick_return(**{**PAPER, **request_})
