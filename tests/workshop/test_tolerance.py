"""Tolerance stack-ups (symlink.workshop.tolerance) against 50-digit differences, brute force and Monte Carlo.

Every expected value comes from outside the code under test: the four-bar at 50 digits
(tests/references.py, circle intersection), differentiated here by central differences;
the tolerance box's corners solved one by one; a sample of 10^5 builds solved with the
vectorised solver; and the slider-crank's hand formula s = a + b at theta = 0.
"""
from __future__ import annotations

import itertools
import math

import mpmath as mp
import numpy
import pytest

from symlink.mechanism.catalog import fourbar, slider_crank
from symlink.numeric.solver import Solver
from symlink.workshop.tolerance import Tolerance, stack_up
from tests.references import mp_fourbar

DESIGN = {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0, "branch": 1}
LENGTHS = ("a", "b", "c", "d")
ANGLES = numpy.radians([0.0, 40.0, 130.0, 250.0])


def _mp_phi(values: dict, theta: float):
    return mp_fourbar(values["a"], values["b"], values["c"], values["d"], theta, 1)["phi"]


def _mp_derivatives(theta: float, name: str):
    """d(phi)/d(name) and d2(phi)/d(name)^2 by central differences at 50 digits (steps 1e-20 and 1e-12)."""
    with mp.workdps(50):
        base = {k: mp.mpf(DESIGN[k]) for k in LENGTHS}

        def phi(shift):
            return _mp_phi({**base, name: base[name] + shift}, theta)
        h1, h2 = mp.mpf("1e-20"), mp.mpf("1e-12")
        first = (phi(h1) - phi(-h1)) / (2 * h1)
        second = (phi(h2) - 2 * phi(0) + phi(-h2)) / h2 ** 2
        return float(first), float(second)


@pytest.fixture(scope="module")
def reference():
    """(sensitivity, curvature), each (lengths, angles), from the 50-digit four-bar."""
    pairs = [[_mp_derivatives(float(theta), name) for theta in ANGLES] for name in LENGTHS]
    return numpy.array([[p[0] for p in row] for row in pairs]), numpy.array([[p[1] for p in row] for row in pairs])


def test_sensitivities_and_bands_equal_50_digit_differences(reference):
    slopes, _ = reference
    bands = numpy.array([0.05, 0.02, 0.1, 0.03])
    sigmas = numpy.array([0.01, 0.02 / 3, 0.05, 0.01])
    tolerances = {"a": Tolerance(0.05, sigma=0.01), "b": 0.02, "c": Tolerance(0.1, 0.05), "d": Tolerance(sigma=0.01)}
    result = stack_up(fourbar(), "rocker", DESIGN, tolerances, inputs={"theta": ANGLES})
    assert result.dimensions == LENGTHS
    numpy.testing.assert_allclose(result.band, [0.05, 0.02, 0.1, 0.03], rtol=1e-15)
    numpy.testing.assert_allclose(result.sensitivity[0], slopes, rtol=1e-9)
    worst = (numpy.abs(slopes) * bands[:, None]).sum(axis=0)
    rss = 3 * numpy.sqrt(((slopes * sigmas[:, None]) ** 2).sum(axis=0))
    numpy.testing.assert_allclose(result.worst_case[0], worst, rtol=1e-9)
    numpy.testing.assert_allclose(result.rss[0], rss, rtol=1e-9)
    shares = (slopes * sigmas[:, None]) ** 2 / ((slopes * sigmas[:, None]) ** 2).sum(axis=0)
    numpy.testing.assert_allclose(result.contributions[0], shares, rtol=1e-8)
    assert result.largest_contributor("rocker") == [LENGTHS[j] for j in numpy.argmax(shares, axis=0)]
    spread = (numpy.abs(slopes) * sigmas[:, None]).max(axis=1)
    assert [name for name, _ in result.ranking("rocker")] == [LENGTHS[j] for j in numpy.argsort(-spread)]


def test_mean_shift_from_second_derivatives_equals_50_digit_differences(reference):
    _, curvature = reference
    result = stack_up(fourbar(), ["rocker"], DESIGN, dict.fromkeys(LENGTHS, 0.3), inputs={"theta": ANGLES})
    numpy.testing.assert_allclose(result.curvature[0], curvature, rtol=1e-6, atol=1e-12)
    numpy.testing.assert_allclose(result.mean_shift[0], 0.5 * (curvature * 0.1 ** 2).sum(axis=0), rtol=1e-6)


def test_worst_case_equals_the_worst_corner_of_the_tolerance_box_to_first_order():
    band = 1e-4
    solver = Solver(fourbar(), ["rocker"])
    nominal = solver(theta=ANGLES, **DESIGN)["rocker"]
    corners = numpy.array(list(itertools.product((-band, band), repeat=4)))  # 16 designs
    built = solver(theta=ANGLES[None, :], **{n: DESIGN[n] + corners[:, [j]] for j, n in enumerate(LENGTHS)},
                   branch=1)["rocker"]
    brute = numpy.abs(built - nominal).max(axis=0)
    result = stack_up(fourbar(), "rocker", DESIGN, dict.fromkeys(LENGTHS, band), inputs={"theta": ANGLES})
    numpy.testing.assert_allclose(result.worst_case[0], brute, rtol=1e-3)  # the rest is second order in band
    assert numpy.all(result.worst_case[0] > numpy.abs(result.sensitivity[0].sum(axis=0)) * band)  # signs matter


@pytest.mark.parametrize("band, agrees", [(0.05, True), (12.0, False)])
def test_rss_and_mean_against_a_monte_carlo_sample_of_100000_builds(band, agrees):
    """Small tolerances: the sample's spread, mean and 3-sigma percentiles agree with the first-order
    prediction within the sampling error; large ones (12 mm on a 20 mm crank): its tails depart from the
    symmetric linear band by more than 8 %."""
    count, theta = 100_000, numpy.radians([40.0, 250.0])
    sigma = band / 3
    rng = numpy.random.default_rng(20261126)
    sample = {name: DESIGN[name] + sigma * rng.standard_normal((count, 1)) for name in LENGTHS}
    built = Solver(fourbar(), ["rocker"])(theta=theta[None, :], **sample, branch=1)
    rocker = numpy.where(built["assembled"], built["rocker"], numpy.nan)
    result = stack_up(fourbar(), "rocker", DESIGN, dict.fromkeys(LENGTHS, band), inputs={"theta": theta})
    deviation = rocker - result.nominal[0]  # no wrap: the rocker stays far from +-180 degrees here
    low, high = numpy.nanpercentile(deviation, [0.135, 99.865], axis=0)  # -3 and +3 sigma of a normal
    tails = numpy.abs(numpy.array([-low, high]) / result.rss[0] - 1)
    if agrees:
        assert numpy.isfinite(rocker).all()
        # the sample's standard deviation has relative standard error 1/sqrt(2 N) = 0.22 %: 4 of them
        numpy.testing.assert_allclose(deviation.std(axis=0), result.standard_deviation[0],
                                      rtol=4 / numpy.sqrt(2 * count))
        error_of_mean = 4 * result.standard_deviation[0] / numpy.sqrt(count)
        assert numpy.all(numpy.abs(deviation.mean(axis=0) - result.mean_shift[0]) < error_of_mean)
        assert tails.max() < 0.04  # a 0.135 % percentile of 10^5 builds: about 2 % of sampling error
    else:
        assert tails.max() > 0.08


def test_slider_crank_worst_case_by_hand_formula():
    """At theta = 0 with no offset the slider sits at s = a + b: ds/da = ds/db = 1, so the worst case is the
    sum of the bands and the RSS their root sum of squares."""
    result = stack_up(slider_crank(), "slider", {"a": 1.0, "b": 3.0, "offset": 0.0, "branch": 1},
                      {"a": 0.02, "b": Tolerance(0.03, sigma=0.02)}, inputs={"theta": [0.0]})
    numpy.testing.assert_allclose(result.sensitivity[0, :, 0], [1.0, 1.0], rtol=1e-14)
    assert result.worst_case[0, 0] == pytest.approx(0.05, rel=1e-14)
    assert result.rss[0, 0] == pytest.approx(3 * numpy.hypot(0.02 / 3, 0.02), rel=1e-14)


def test_default_inputs_are_a_full_turn_every_10_degrees():
    result = stack_up(fourbar(), "rocker", DESIGN, {"a": 0.1})
    numpy.testing.assert_allclose(numpy.degrees(result.inputs["theta"]), numpy.arange(0, 360, 10), atol=1e-12)
    assert result.worst_case.shape == (1, 36) and result.assembled.all()


def test_nothing_assembled_is_nan_not_a_number():
    result = stack_up(fourbar(), "rocker", {"a": 1, "b": 1, "c": 1, "d": 10, "branch": 1}, {"a": 0.1},
                      inputs={"theta": [0.0]})
    assert not result.assembled[0] and numpy.isnan(result.worst_case[0, 0]) and numpy.isnan(result.rss[0, 0])
    assert result.largest_contributor("rocker") == [""]


@pytest.mark.parametrize("outputs, nominal, tolerances, inputs, message", [
    ("rocker", DESIGN, {"e": 0.1}, None, "no parameter 'e'"),
    ("rocker", DESIGN, {"a": -0.1}, None, "positive finite band"),
    ("rocker", DESIGN, {"a": float("nan")}, None, "positive finite band"),
    ("rocker", DESIGN, {"a": "0.1"}, None, "a number"),
    ("rocker", DESIGN, {}, None, "at least one dimension"),
    ("rocker", {"a": 20.0, "b": 66.0, "c": 56.0}, {"a": 0.1}, None, "give the value of d"),
    ("rocker", DESIGN, {"a": 0.1}, {"psi": [0.0]}, "no input 'psi'"),
    ("rocker", DESIGN, {"a": 0.1}, {"theta": [[0.0, 1.0]]}, "one-dimensional"),
    ("rocker_speed", DESIGN, {"a": 0.1}, None, "nominal: give the value of thetadot"),  # a rate needs its input's
])
def test_bad_input_is_a_value_error_naming_it(outputs, nominal, tolerances, inputs, message):
    with pytest.raises(ValueError, match=message):
        stack_up(fourbar(), outputs, nominal, tolerances, inputs=inputs)
    with pytest.raises(ValueError, match="band or a sigma"):
        Tolerance()


# --- the command line ------------------------------------------------------------------

COMMAND = ["tolerance", "fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80"]


def test_command_prints_the_stack_up_in_degrees_as_csv(capsys):
    from symlink.cli import main
    assert main(COMMAND + ["--tolerance", "0.05", "--output", "rocker", "--angles", "0,40", "--format", "csv"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "theta,rocker,worst_case,rss,mean_shift,largest"
    rows = [line.split(",") for line in lines[1:]]
    result = stack_up(fourbar(), "rocker", DESIGN, dict.fromkeys(LENGTHS, 0.05), inputs={"theta": ANGLES[:2]})
    assert float(rows[0][1]) == pytest.approx(110.74, abs=0.005)  # seed 003 at theta = 0
    for row, k in zip(rows, range(2)):
        assert float(row[2]) == pytest.approx(numpy.degrees(result.worst_case[0, k]), rel=1e-12)
        assert float(row[3]) == pytest.approx(numpy.degrees(result.rss[0, k]), rel=1e-12)
        assert row[5] == "b"


def test_command_bands_of_chosen_dimensions_and_sigmas(capsys):
    """--tolerances and --sigma name dimensions one by one; a slider's travel is in length units."""
    from symlink.cli import main
    assert main(["tolerance", "slider-crank", "--set", "a=1,b=3,offset=0", "--tolerances", "a=0.02",
                 "--sigma", "b=0.02", "--angles", "0", "--format", "csv"]) == 0
    row = capsys.readouterr().out.splitlines()[1].split(",")
    assert float(row[1]) == pytest.approx(4.0, rel=1e-14)  # s = a + b at theta = 0
    assert float(row[2]) == pytest.approx(0.02 + 0.06, rel=1e-14)  # b's band: 3 sigma
    assert float(row[3]) == pytest.approx(3 * numpy.hypot(0.02 / 3, 0.02), rel=1e-14)
    assert row[5] == "b"


# --- pin play (joint clearance) -----------------------------------------------------------

def _rocker_with_pins_moved(theta, shift_b, shift_d, branch=1):
    """The four-bar's rocker angle when the coupler starts at B + shift_b and the rocker's pivot sits at
    D + shift_d (complex), by intersecting the circle of radius b about B' with that of radius c about D'."""
    a, b, c, d = (DESIGN[k] for k in LENGTHS)
    B = a * numpy.exp(1j * theta) + shift_b
    D = d + shift_d
    e = D - B
    L = numpy.abs(e)
    along = (b * b - c * c + L * L) / (2 * L)
    h = numpy.sqrt(b * b - along * along)
    C = B + e / L * (along + 1j * branch * h)  # branch +1: C to the left of B -> D
    return numpy.angle(C - D)


def test_pin_play_worst_case_equals_an_optimisation_over_the_play_directions():
    """Play r at each of A, B, C, D: the crank pin B moves by r e^{i psi_A} + r e^{i psi_B} and the rocker
    pivot by r e^{i psi_C} + r e^{i psi_D} (the directions free); the largest rocker deviation over the four
    directions, found by a grid and Nelder-Mead, equals the linear worst case to first order in r."""
    from scipy.optimize import minimize

    from symlink.workshop.pin_play import pin_play
    r = 1e-3
    thetas = numpy.radians([40.0, 250.0])
    result = pin_play(fourbar(), "rocker", DESIGN, dict.fromkeys("ABCD", r), inputs={"theta": thetas})
    assert result.joints == ("A", "B", "C", "D")
    grid = numpy.linspace(-numpy.pi, numpy.pi, 12, endpoint=False)
    psi = numpy.stack(numpy.meshgrid(grid, grid, grid, grid, indexing="ij"), axis=-1).reshape(-1, 4)
    for k, theta in enumerate(thetas):
        nominal = _rocker_with_pins_moved(theta, 0, 0)

        def deviation(p):
            p = numpy.atleast_2d(p)
            moved = _rocker_with_pins_moved(theta, r * (numpy.exp(1j * p[:, 0]) + numpy.exp(1j * p[:, 1])),
                                            r * (numpy.exp(1j * p[:, 2]) + numpy.exp(1j * p[:, 3])))
            return numpy.abs(moved - nominal)
        start = psi[numpy.argmax(deviation(psi))]
        best = minimize(lambda p: -deviation(p)[0], start, method="Nelder-Mead",
                        options={"xatol": 1e-10, "fatol": 1e-16, "maxiter": 20000})
        assert -best.fun == pytest.approx(result.worst_case[0, k], rel=1e-3)  # the rest is second order in r
        assert result.nominal[0, k] == pytest.approx(nominal, abs=1e-12)


def test_pin_play_of_one_pin_is_its_play_times_the_gradient_of_a_moved_pivot():
    """Play only at D: the rocker's pivot moves by delta; by finite differences of the circle intersection
    (written above) in x and y, the gradient's length times the play is the worst case."""
    from symlink.workshop.pin_play import pin_play
    theta, h = numpy.radians(130.0), 1e-6
    gx = (_rocker_with_pins_moved(theta, 0, h) - _rocker_with_pins_moved(theta, 0, -h)) / (2 * h)
    gy = (_rocker_with_pins_moved(theta, 0, 1j * h) - _rocker_with_pins_moved(theta, 0, -1j * h)) / (2 * h)
    result = pin_play(fourbar(), "rocker", DESIGN, {"D": 0.02}, inputs={"theta": [theta]})
    assert result.worst_case[0, 0] == pytest.approx(0.02 * numpy.hypot(gx, gy), rel=1e-7)


def test_pin_play_bad_input():
    from symlink.workshop.pin_play import pin_play
    with pytest.raises(ValueError, match="no joint 'E'"):
        pin_play(fourbar(), "rocker", DESIGN, {"E": 0.01})
    with pytest.raises(ValueError, match=">= 0"):
        pin_play(fourbar(), "rocker", DESIGN, {"B": -0.01})
    with pytest.raises(ValueError, match="at least one pin"):
        pin_play(fourbar(), "rocker", DESIGN, {})


def test_command_adds_the_pins_play_as_a_column(capsys):
    from symlink.cli import main
    from symlink.workshop.pin_play import pin_play
    assert main(COMMAND + ["--tolerance", "0.05", "--play", "B=0.02,C=0.03", "--angles", "130", "--format",
                           "csv"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].endswith(",largest,play")
    # by hand: the play's worst case is sum_j r_j |g_j|, each gradient from the library's pin_play
    result = pin_play(fourbar(), "rocker", DESIGN, {"B": 0.02, "C": 0.03}, inputs={"theta": ANGLES[2:3]})
    gradient = numpy.hypot(result.gradient[0, :, 0, 0], result.gradient[0, :, 1, 0])
    assert float(lines[1].split(",")[6]) == pytest.approx(numpy.degrees(0.02 * gradient[0] + 0.03 * gradient[1]),
                                                          rel=1e-12)


@pytest.mark.parametrize("theta_degrees", [40.0, 250.0])
def test_the_exact_play_envelope_equals_an_optimisation_over_the_play_directions(theta_degrees):
    """Play 0.5 at each of A, B, C, D (large: the envelope is no longer symmetric about the nominal): the
    library's lowest and highest rocker angle equal the extremes that a grid and Nelder-Mead find over the
    four directions of the circle-intersection model written above."""
    from scipy.optimize import minimize

    from symlink.workshop.pin_play import pin_play_envelope
    r, theta = 0.5, numpy.radians(theta_degrees)
    envelope = pin_play_envelope(fourbar(), "rocker", DESIGN, dict.fromkeys("ABCD", r), at={"theta": theta})
    nominal = _rocker_with_pins_moved(theta, 0, 0)
    assert envelope.nominal == pytest.approx(nominal, abs=1e-12)

    def rocker(p):
        p = numpy.atleast_2d(p)
        return _rocker_with_pins_moved(theta, r * (numpy.exp(1j * p[:, 0]) + numpy.exp(1j * p[:, 1])),
                                       r * (numpy.exp(1j * p[:, 2]) + numpy.exp(1j * p[:, 3])))
    grid = numpy.linspace(-numpy.pi, numpy.pi, 12, endpoint=False)
    psi = numpy.stack(numpy.meshgrid(grid, grid, grid, grid, indexing="ij"), axis=-1).reshape(-1, 4)
    extremes = []
    for sign in (1, -1):
        start = psi[numpy.argmax(sign * rocker(psi))]
        best = minimize(lambda p: -sign * rocker(p)[0], start, method="Nelder-Mead",
                        options={"xatol": 1e-10, "fatol": 1e-16, "maxiter": 20000})
        extremes.append(-sign * best.fun)
    highest, lowest = extremes
    assert envelope.highest - nominal == pytest.approx(highest - nominal, rel=1e-7)
    assert nominal - envelope.lowest == pytest.approx(nominal - lowest, rel=1e-7)
    assert abs((highest - nominal) - (nominal - lowest)) > 1e-4 * (highest - lowest)  # not symmetric any more


# --- the Monte Carlo check --------------------------------------------------------------------

def test_sampled_builds_agree_with_the_linear_bands_where_tolerances_are_small():
    from symlink.workshop.sampled_builds import sample_builds
    count, theta = 100_000, numpy.radians([40.0, 250.0])
    tolerances = dict.fromkeys(LENGTHS, 0.05)
    sampled = sample_builds(fourbar(), "rocker", DESIGN, tolerances, inputs={"theta": theta}, builds=count, seed=7)
    linear = stack_up(fourbar(), "rocker", DESIGN, tolerances, inputs={"theta": theta})
    assert sampled.built.min() == 1.0
    numpy.testing.assert_allclose(sampled.standard_deviation[0], linear.standard_deviation[0],
                                  rtol=4 / numpy.sqrt(2 * count))
    low, high = sampled.percentile([0.135, 99.865])[:, 0]
    numpy.testing.assert_allclose(-low, linear.rss[0], rtol=0.04)
    numpy.testing.assert_allclose(high, linear.rss[0], rtol=0.04)
    runs = [sample_builds(fourbar(), "rocker", DESIGN, tolerances, inputs={"theta": theta}, builds=1000, seed=seed)
            for seed in (7, 7, 8)]
    assert numpy.array_equal(runs[0].deviation, runs[1].deviation)  # seeded: a run repeats
    assert not numpy.array_equal(runs[0].deviation, runs[2].deviation)


def test_a_length_drawn_non_positive_is_a_build_that_cannot_be_made():
    """The crank a = 20 with sigma 20: a share Phi(-1) = 0.1587 of the builds has a <= 0 (a normal CDF)."""
    from symlink.workshop.sampled_builds import sample_builds
    count = 20_000
    sampled = sample_builds(fourbar(), "rocker", DESIGN, {"a": Tolerance(sigma=20.0)}, inputs={"theta": [1.0]},
                            builds=count, seed=3)
    unmade = 0.5 * math.erfc(1 / math.sqrt(2))
    assert sampled.built[0, 0] <= 1 - unmade + 4 * math.sqrt(unmade * (1 - unmade) / count)
    with pytest.raises(ValueError, match="builds must be a whole number"):
        sample_builds(fourbar(), "rocker", DESIGN, {"a": 0.1}, builds=0)
    with pytest.raises(ValueError, match="sample_builds keeps; ask for at most 1,388,888 builds"):  # 36 input values
        sample_builds(fourbar(), "rocker", DESIGN, {"a": 0.1}, builds=10**7)


def test_builds_of_a_cached_solver_are_those_of_the_linkage():
    """solved_builds (what a warm ``symlink tolerance --samples`` runs, no linkage) draws and solves the builds of
    sample_builds: the same deviations, bit for bit, the crank's non-positive draws thrown away alike."""
    from symlink.numeric.cached_solver import CachedSolver
    from symlink.workshop.sampled_builds import sample_builds, solved_builds
    tolerances = {"a": Tolerance(sigma=10.0), "b": 0.3}
    theta = numpy.radians([0.0, 130.0])
    expected = sample_builds(fourbar(), "rocker", DESIGN, tolerances, inputs={"theta": theta}, builds=3000, seed=5,
                             chunk=1000)
    found = solved_builds(lambda: CachedSolver("fourbar", ["rocker"]), "fourbar", ["theta"], dict.fromkeys(LENGTHS, True),
                          lambda: [True], ["rocker"], DESIGN, tolerances, inputs={"theta": theta}, builds=3000, seed=5,
                          chunk=1000)
    assert 0 < numpy.isnan(expected.deviation).sum() < expected.deviation.size  # a <= 0 drawn now and then
    assert numpy.array_equal(found.deviation, expected.deviation, equal_nan=True)
    with pytest.raises(ValueError, match="fourbar has no parameter 'e'"):
        solved_builds(lambda: CachedSolver("fourbar", ["rocker"]), "fourbar", ["theta"], dict.fromkeys(LENGTHS, True),
                      lambda: [True], ["rocker"], DESIGN, {"e": 0.1}, builds=10)


def test_command_samples_builds_beside_the_linear_bands(capsys):
    from symlink.cli import main
    assert main(COMMAND + ["--tolerance", "0.05", "--builds", "100000", "--angles", "40", "--format", "csv"]) == 0
    header, row = capsys.readouterr().out.splitlines()
    assert header.endswith(",largest,sampled_low,sampled_high")
    cells = row.split(",")
    rss, low, high = float(cells[3]), float(cells[6]), float(cells[7])
    assert -low == pytest.approx(rss, rel=0.04) and high == pytest.approx(rss, rel=0.04)


def test_pin_play_of_a_slider_crank_by_hand():
    """At theta = 0 the slider sits at s = B_x + sqrt(b^2 - (e - B_y)^2) (offset e): play moving the crank pin
    B (at A or at B) or the block's pin C moves s by (1, (e - B_y) / sqrt(b^2 - (e - B_y)^2)) . delta."""
    from symlink.workshop.pin_play import pin_play
    a, b, e = 1.3, 4.1, 0.7
    result = pin_play(slider_crank(), "slider", {"a": a, "b": b, "offset": e, "branch": 1},
                      {"A": 0.01, "B": 0.02, "C": 0.03}, inputs={"theta": [0.0]})
    slope = e / math.sqrt(b * b - e * e)
    assert result.worst_case[0, 0] == pytest.approx(0.06 * math.hypot(1, slope), rel=1e-12)
    numpy.testing.assert_allclose(numpy.abs(result.gradient[0, :, :, 0]), [[1, slope]] * 3, rtol=1e-12)


def test_command_draws_the_bands_and_the_contributions(tmp_path, capsys):
    from symlink.cli import main
    path = tmp_path / "bands.png"
    assert main(COMMAND + ["--tolerance", "0.05", "--samples", "1000", "--step", "30", "--plot", str(path)]) == 0
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert main(COMMAND + ["--tolerance", "0.05", "--plot", str(tmp_path / "bands.pdf")]) == 2
    assert "must end in .png or .svg" in capsys.readouterr().err
