"""`symlink analyze`: a four-bar's analysis from the command line, against the law of cosines."""
import json
import math

import pytest

from symlink.cli import main


def analyze(capsys, *lengths, fmt="json", units="deg"):
    argv = ["analyze"] + [x for name, v in zip(("--crank", "--coupler", "--rocker", "--ground"), lengths)
                          for x in (name, str(v))] + ["--format", fmt, "--units", units]
    status = main(argv)
    out, err = capsys.readouterr()
    return status, out, err


def law_of_cosines(opposite, side1, side2):
    return math.acos((side1**2 + side2**2 - opposite**2) / (2 * side1 * side2))


def test_seed_003_crank_rocker(capsys):
    a, b, c, d = 20, 66, 56, 80
    status, out, _ = analyze(capsys, a, b, c, d)
    report = json.loads(out)
    assert status == 0 and report["grashof"] == "crank-rocker" and report["dof"] == 1 and report["toggles"] == []
    # transmission angle: |BD| = d - a at theta = 0, d + a at theta = 180
    assert report["transmission_min"] == pytest.approx(math.degrees(law_of_cosines(d - a, b, c)), abs=1e-9)
    assert report["transmission_max"] == pytest.approx(math.degrees(law_of_cosines(d + a, b, c)), abs=1e-9)
    assert (report["transmission_min_at"], report["transmission_max_at"]) == (0.0, 180.0)
    # limit positions: crank and coupler in line, |AC| = a + b or b - a; C above the ground (branch +1)
    extended_crank = law_of_cosines(c, a + b, d)
    folded_crank = law_of_cosines(c, b - a, d) - math.pi
    extended_rocker = math.pi - law_of_cosines(a + b, c, d)
    folded_rocker = math.pi - law_of_cosines(b - a, c, d)
    limits = report["limit_positions"]
    assert limits["extended_crank"] == pytest.approx(math.degrees(extended_crank), abs=1e-9)
    assert limits["folded_crank"] == pytest.approx(math.degrees(folded_crank), abs=1e-9)
    assert report["stroke"] == pytest.approx(math.degrees(folded_rocker - extended_rocker), abs=1e-9)
    forward = (folded_crank - extended_crank) % (2 * math.pi)
    assert report["time_ratio"] == pytest.approx(max(forward, 2 * math.pi - forward) / min(forward, 2 * math.pi - forward),
                                                 rel=1e-12)


def test_seed_002_printed_linkage(capsys):
    # seeds/002 prints: stroke 39.950 deg, time ratio 1.114, transmission 50.277 to 90.380 deg
    _, out, _ = analyze(capsys, 16.084, 69.743, 50, 70)
    report = json.loads(out)
    assert round(report["stroke"], 2) == 39.95 and round(report["time_ratio"], 3) == 1.114
    assert round(report["transmission_min"], 3) == 50.277
    assert abs(report["transmission_max"] - 90.380) < 2e-3  # 90.381 from the printed (rounded) lengths


def test_crank_that_cannot_turn_has_toggles_and_no_stroke(capsys):
    a, b, c, d = 50, 20, 40, 30
    _, out, _ = analyze(capsys, a, b, c, d, units="rad")
    report = json.loads(out)
    toggle = law_of_cosines(b + c, a, d)  # coupler and rocker in line, extended
    assert report["toggles"] == pytest.approx([-toggle, toggle], abs=1e-12)
    assert report["limit_positions"] is None and report["stroke"] is None and report["grashof"] == "change-point"


def test_table_names_every_result(capsys):
    status, out, _ = analyze(capsys, 20, 66, 56, 80, fmt="table")
    for label in ("degrees of freedom", "Grashof", "crank range", "limit positions", "stroke", "time ratio",
                  "transmission angle"):
        assert label in out


@pytest.mark.parametrize("lengths", [(1, 1, 1, 10), (0, 1, 1, 1), (-1, 2, 2, 2)])
def test_impossible_or_bad_lengths_exit_2(capsys, lengths):
    status, out, err = analyze(capsys, *lengths)
    assert status == 2 and out == "" and err.startswith("symlink: error: ") and err.count("\n") == 1


def test_any_linkage_by_name_against_the_slider_cranks_hand_stroke(capsys):
    """An offset slider-crank's stroke, sqrt((a + b)^2 - e^2) - sqrt((b - a)^2 - e^2), from `analyze NAME`."""
    import json
    import math
    a, b, e = 1.3, 4.1, 0.7
    assert main(["analyze", "slider-crank", "--set", f"a={a},b={b},offset={e}", "--output", "slider",
                 "--format", "json"]) == 0
    report = json.loads(capsys.readouterr().out)
    stroke = math.sqrt((a + b) ** 2 - e**2) - math.sqrt((b - a) ** 2 - e**2)
    assert report["dof"] == 1 and report["full_turn"] and report["exact"]
    assert abs(report["limits"]["stroke"] - stroke) < 1e-12
    extended = math.degrees(math.asin(e / (a + b)))  # crank and rod in line, pointing along the guide
    assert any(abs(p["at"] - extended) < 1e-9 and p["kind"] == "maximum" for p in report["limits"]["positions"])


def test_a_file_and_its_transmission_in_text(capsys):
    from symlink.io.linkage_file import catalog_file
    shipped = catalog_file("fourbar")
    assert main(["analyze", str(shipped), "--output", "phi"]) == 0
    out = capsys.readouterr().out
    assert "degrees of freedom   1" in out and "transmission ABCD" in out and "limit of phi" in out
