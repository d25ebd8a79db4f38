"""The four-bar by its lengths in closed form: hand values, 50-digit mpmath triangles, an independent scan, no SymPy.

Expected values come from the law of cosines worked by hand, from C found by intersecting two circles (written
here), or from the general analysis of the catalog's four-bar (:func:`symlink.analysis.analyze_linkage`,
a scan of generated code: an independent formulation of the same facts).
"""
import math
import subprocess
import sys

import numpy as np
import pytest

from symlink.analysis.fourbar_closed_form import crank_spans, fourbar_report, limit_positions
from symlink.numeric.fourbar_transmission import transmission_range
from references import fourbar_joint_c

SEED003 = (20.0, 66.0, 56.0, 80.0)


def law_of_cosines(opposite, side1, side2):
    """The angle between side1 and side2, by the plain law of cosines (well-shaped triangles only)."""
    return math.acos((side1**2 + side2**2 - opposite**2) / (2 * side1 * side2))


# --- SymPy-free ------------------------------------------------------------------------------

@pytest.mark.parametrize("statement", [
    "import symlink.analysis.fourbar_closed_form",
    "from symlink.analysis import fourbar_report, transmission_range, limit_positions, triangle_angle, grashof",
    "import symlink.numeric.fourbar_transmission; symlink.numeric.fourbar_transmission.transmission_range(2, 1, 1, 2)",
    "import symlink; symlink.fourbar_report(20, 66, 56, 80)",
])
def test_the_closed_form_imports_no_sympy(statement):
    heavy = "('sympy', 'symlink.symbolic', 'symlink.codegen.numpy', 'symlink.numeric.solver')"
    found = subprocess.run([sys.executable, "-c", f"{statement}\nimport sys\n"
                            f"print(sorted(m for m in sys.modules if m.startswith({heavy})))"],
                           capture_output=True, text=True, check=True)
    assert found.stdout.strip() == "[]"


# --- limit positions -------------------------------------------------------------------------

@pytest.mark.parametrize("branch", [1, -1])
@pytest.mark.parametrize("lengths", [SEED003, (16.084, 69.743, 50.0, 70.0), (1.0, 4.0, 3.0, 3.5)])
def test_limit_positions_against_the_circles_by_hand(lengths, branch):
    """At each limit the hand's C (the circles about B and D, on the branch) lies on the line A, B at distance a + b
    (extended) or b - a (folded) from A; the rocker angle is C's about D; the stroke is the rocker's swing over a
    dense scan, and the time ratio the crank's turns between the two."""
    a, b, c, d = lengths
    found = limit_positions(a, b, c, d, branch)
    for crank, rocker, reach in ((found.extended_crank, found.extended_rocker, a + b),
                                 (found.folded_crank, found.folded_rocker, b - a)):
        cx, cy = fourbar_joint_c(crank, a, b, c, d, branch)
        assert math.hypot(cx, cy) == pytest.approx(reach, rel=1e-9)
        assert cx * math.sin(crank) - cy * math.cos(crank) == pytest.approx(0.0, abs=1e-9 * (a + b))  # on line A, B
        assert rocker == pytest.approx(math.atan2(cy, cx - d), abs=1e-9)
    rockers = np.unwrap([math.atan2(p[1], p[0] - d) for p in
                         (fourbar_joint_c(t, a, b, c, d, branch) for t in np.linspace(-math.pi, math.pi, 200001))])
    assert found.stroke == pytest.approx(rockers.max() - rockers.min(), abs=1e-8)
    forward = (found.folded_crank - found.extended_crank) % (2 * math.pi)
    assert found.time_ratio == pytest.approx(max(forward, 2 * math.pi - forward) / min(forward, 2 * math.pi - forward))


# --- the crank's spans and the report against the general analysis ---------------------------------

#: Four-bars whose crank range is a full turn, one span, two spans, a single point, or cut where B passes D.
REACH_CASES = [SEED003, (60.0, 30.0, 50.0, 40.0), (0.3, 0.1, 0.25, 0.30), (50.0, 20.0, 40.0, 30.0),
               (2.0, 1.0, 1.0, 2.0), (1.0, 2.0, 2.0, 1.0), (2.0, 3.0, 3.0, 2.0), (1.0, 1.0, 2.0, 4.0),
               (2.0, 6.0, 2.0, 2.0), (5.0, 6.0, 7.0, 10.0), (4.0, 5.0, 6.0, 2.0), (3.0, 1.0, 1.0, 1.0)]


@pytest.mark.parametrize("lengths", REACH_CASES)
def test_the_report_is_what_the_general_analysis_finds(lengths):
    """The closed-form record against analyze_linkage of the catalog's four-bar (a scan of its generated margins,
    each end bisected): the same spans and toggles (the scan widens a single point by its rounding tolerance, under
    1e-7 rad), the same limit positions, and the transmission extremes where that scan is not at B on D."""
    from symlink.analysis import analyze_linkage
    from symlink.mechanism.catalog import fourbar
    a, b, c, d = lengths
    report = fourbar_report(a, b, c, d)
    kind = report["grashof"]
    general = analyze_linkage(fourbar(), dict(a=a, b=b, c=c, d=d, branch=1),
                              output="rocker" if kind == "crank-rocker" else None)
    assert report["dof"] == general.mobility.dof == 1
    assert len(report["crank_range"]) == len(general.reach.spans)
    for mine, theirs in zip(report["crank_range"], general.reach.spans):
        assert mine == pytest.approx(theirs, abs=1e-7)
    ends = [] if general.reach.full_turn else [t.at for t in general.reach.toggles if t.ends_range]
    assert len(report["toggles"]) == len(ends)
    for mine, theirs in zip(report["toggles"], ends):  # a toggle at pi may be found at -pi
        assert abs(math.remainder(mine - theirs, 2 * math.pi)) < 1e-7
    if kind == "crank-rocker":
        assert sorted([report["limit_positions"]["extended_crank"], report["limit_positions"]["folded_crank"]]) \
            == pytest.approx([p.at for p in general.limits.positions], abs=1e-9)
        assert report["stroke"] == pytest.approx(general.limits.stroke, abs=1e-12)
        assert report["time_ratio"] == pytest.approx(general.limits.time_ratio, rel=1e-9)
    else:
        assert report["limit_positions"] is report["stroke"] is report["time_ratio"] is None


def test_crank_spans_cut_where_b_passes_over_d():
    """a = d and b = c: B reaches D at theta = 0, where the coupler's direction is undefined; the range is cut
    there into [-60, 0] and [0, 60] degrees (cos(60 deg) = (4 + 4 - 4) / 8)."""
    spans = crank_spans(2.0, 1.0, 1.0, 2.0)
    assert [math.degrees(x) for span in spans for x in span] == pytest.approx([-60, 0, 0, 60], abs=1e-12)
    beside = crank_spans(2.0, 1.0, 1.0, 2.0 + 1e-9)  # B passes beside D: one span
    assert len(beside) == 1 and beside[0] == pytest.approx((-math.pi / 3, math.pi / 3), abs=1e-8)


def test_a_four_bar_that_closes_only_at_half_a_turn():
    """Crank 2, coupler 6, rocker 2, ground 2: at theta = pi BD is a + d = 4 = b - c long, the triangle over it
    flat; anywhere else BD is shorter and the coupler cannot reach.  Its range is that one angle, whose two ends
    are named -pi and pi (the general analysis scans from -pi)."""
    report = fourbar_report(2.0, 6.0, 2.0, 2.0)
    assert report["crank_range"] == [(math.pi, math.pi)] and report["toggles"] == [-math.pi, math.pi]
    assert (report["transmission_min"], report["transmission_max"]) == (0.0, 0.0)


# --- bad input -------------------------------------------------------------------------------

@pytest.mark.parametrize("call, message", [
    (lambda: fourbar_report(0.0, 1.0, 1.0, 1.0), "crank must be a positive finite length, got 0.0"),
    (lambda: fourbar_report(1.0, -2.0, 1.0, 1.0), "coupler must be a positive finite length, got -2.0"),
    (lambda: fourbar_report(1.0, 1.0, math.nan, 1.0), "rocker must be a positive finite length, got nan"),
    (lambda: fourbar_report(1.0, 1.0, 1.0, math.inf), "ground must be a positive finite length, got inf"),
    (lambda: fourbar_report(1e306, 1.0, 1.0, 1.0), "crank must be from 1e-305 to 1e305 in size"),
    (lambda: fourbar_report(1.0, 1.0, 1.0, 10.0), "cannot be assembled at any crank angle"),
    (lambda: fourbar_report(*SEED003, branch=2), "branch must be +1 or -1, got 2"),
    (lambda: limit_positions(1.0, 1.0, 3.0, 3.0), "crank and coupler are equally long"),
    (lambda: limit_positions(1.0, 5.0, 1.0, 10.0), "the extended limit position"),
    (lambda: transmission_range(1.0, 1.0, 1.0, 10.0), "cannot be assembled at any crank angle"),
])
def test_bad_input_is_a_value_error_naming_it(call, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace("+", r"\+")):
        call()
