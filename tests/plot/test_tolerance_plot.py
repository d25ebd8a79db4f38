"""The tolerance pictures draw the bands and shares that hand formulas give, and the sample's own percentiles."""
import math

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from symlink.mechanism.catalog import fourbar, slider_crank  # noqa: E402
from symlink.plot import save_figure  # noqa: E402
from symlink.plot.tolerance import band_figure, contribution_figure, tolerance_figure  # noqa: E402
from symlink.workshop.tolerance import stack_up
from symlink.workshop.sampled_builds import sample_builds  # noqa: E402

DESIGN = {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0, "branch": 1}
THETA = np.radians(np.arange(0.0, 360.0, 30.0))


def _band_edges(axes, label):
    """The lower and upper edges of the band drawn with ``label``: its polygon's lowest and highest vertex at each
    x (theta in degrees), and those x."""
    band = next(item for item in axes.collections if item.get_label() == label)
    vertices = band.get_paths()[0].vertices
    x = np.degrees(THETA)
    at = [vertices[np.isclose(vertices[:, 0], value, rtol=0, atol=1e-9), 1] for value in x]
    return np.array([v.min() for v in at]), np.array([v.max() for v in at]), x


def test_the_bands_of_a_crank_pin_coordinate_are_the_hand_formula():
    """B_x = a cos(theta): with a band of 0.3 on a, the worst case and the 3-sigma band are 0.3 |cos theta| and
    the mean shift is zero (B_x is linear in a); the x axis is theta in degrees, B_x a length."""
    result = stack_up(fourbar(), "B_x", DESIGN, {"a": 0.3}, inputs={"theta": THETA})
    figure = band_figure(result, angular_output=False)
    top, bottom = figure.axes
    hand = 0.3 * np.abs(np.cos(THETA))
    for label in ("worst case (± Σ|∂y/∂p| band)", "statistical (mean shift ± 3σ)"):
        low, high, _ = _band_edges(bottom, label)
        np.testing.assert_allclose(high, hand, rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(low, -hand, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(top.lines[0].get_ydata(), 20 * np.cos(THETA), rtol=1e-12, atol=1e-12)
    assert top.get_ylabel() == "B_x (length)" and bottom.get_xlabel() == "theta (deg)"
    np.testing.assert_allclose(top.lines[0].get_xdata(), np.arange(0.0, 360.0, 30.0), rtol=1e-12)


def test_the_sampled_dots_are_the_samples_percentiles_and_mean():
    tolerances = dict.fromkeys("abcd", 0.3)
    result = stack_up(fourbar(), "rocker", DESIGN, tolerances, inputs={"theta": THETA})
    sampled = sample_builds(fourbar(), "rocker", DESIGN, tolerances, inputs={"theta": THETA}, builds=2000, seed=4)
    bottom = band_figure(result, sampled=sampled).axes[1]
    deviation = np.degrees(sampled.deviation[0])
    by_marker = {line.get_marker(): line.get_ydata() for line in bottom.lines}
    np.testing.assert_allclose(by_marker["v"], np.percentile(deviation, 0.135, axis=0), rtol=1e-12)
    np.testing.assert_allclose(by_marker["^"], np.percentile(deviation, 99.865, axis=0), rtol=1e-12)
    np.testing.assert_allclose(by_marker["."], deviation.mean(axis=0), rtol=1e-9)
    elsewhere = sample_builds(fourbar(), "rocker", DESIGN, tolerances, inputs={"theta": THETA[:3]}, builds=10)
    with pytest.raises(ValueError, match="not of rocker at the stack-up's input values"):
        band_figure(result, sampled=elsewhere)
    with pytest.raises(ValueError, match="no output 'coupler'"):
        band_figure(result, "coupler")
    with pytest.raises(ValueError, match="units must be deg or rad"):
        band_figure(result, units="grad")


def test_the_bars_are_the_shares_of_the_variance_by_hand():
    """Slider-crank at theta = 0: s = a + sqrt(b^2 - e^2), so ds/da = 1, ds/db = b / r, ds/de = -e / r with
    r = sqrt(b^2 - e^2); equal sigmas share the variance as 1 : b^2/r^2 : e^2/r^2."""
    a, b, e = 1.3, 4.1, 2.2
    result = stack_up(slider_crank(), "slider", {"a": a, "b": b, "offset": e, "branch": 1},
                      {"a": 0.01, "b": 0.01, "offset": 0.01}, inputs={"theta": [0.0]})
    axes = contribution_figure(result).axes[0]
    r2 = b * b - e * e
    parts = {"a": 1.0, "b": b * b / r2, "offset": e * e / r2}
    total = sum(parts.values())
    drawn = {label.get_text(): bar.get_width() for label, bar in zip(axes.get_yticklabels(), axes.patches)}
    assert drawn == pytest.approx({k: 100 * v / total for k, v in parts.items()}, rel=1e-9)
    assert [label.get_text() for label in axes.get_yticklabels()][-1] == "b"  # the largest on top


def test_the_figure_of_three_panels_is_written(tmp_path):
    result = stack_up(fourbar(), "rocker", DESIGN, dict.fromkeys("abcd", 0.05), inputs={"theta": THETA})
    path = tmp_path / "bands.svg"
    save_figure(tolerance_figure(result, title="four-bar"), path)
    text = path.read_text()
    assert text.startswith("<?xml") and "four-bar" in text and "share of the variance" in text
    assert math.isfinite(result.rss.max())


def test_the_distribution_is_the_samples_histogram_beside_the_hand_normal():
    """B_x = a at theta = 0 with a band of 0.3 on a: the linear prediction is the normal density of sigma 0.1
    about 0 (peak 1 / (sqrt(2 pi) 0.1)), its worst-case ends at ± 0.3; the bars are the sample's histogram."""
    from symlink.plot.tolerance import distribution_figure
    result = stack_up(fourbar(), "B_x", DESIGN, {"a": 0.3}, inputs={"theta": [0.0]})
    sampled = sample_builds(fourbar(), "B_x", DESIGN, {"a": 0.3}, inputs={"theta": [0.0]}, builds=5000, seed=9)
    axes = distribution_figure(result, sampled, bins=40, angular_output=False).axes[0]
    curve = axes.lines[0]
    assert curve.get_ydata().max() == pytest.approx(1 / (math.sqrt(2 * math.pi) * 0.1), rel=1e-4)
    assert curve.get_xdata()[curve.get_ydata().argmax()] == pytest.approx(0.0, abs=0.002)
    dashed = sorted(line.get_xdata()[0] for line in axes.lines if line.get_linestyle() == "--")
    assert dashed == pytest.approx([-0.3, 0.3], rel=1e-12)
    heights, _ = np.histogram(sampled.deviation[0, :, 0], bins=40, density=True)
    np.testing.assert_allclose([bar.get_height() for bar in axes.patches], heights, rtol=1e-12)
    with pytest.raises(ValueError, match="at must be the number of an input value, 0 to 0"):
        distribution_figure(result, sampled, at=1)
