"""Results: still a dict, units per output, an HTML table and a pandas DataFrame (pandas optional)."""
import builtins
import html.parser

import numpy as np
import pytest

from symlink.mechanism.catalog import fourbar, slider_crank
from symlink.numeric.results import HTML_ROWS, Results
from symlink.numeric.solver import Solver
from symlink.numeric.units import argument_units, output_units


class TableParser(html.parser.HTMLParser):
    """The cells of an HTML table, row by row (header row first)."""

    def __init__(self):
        super().__init__()
        self.rows, self.cell = [], None

    def handle_starttag(self, tag, attrs):
        if tag == "tr":
            self.rows.append([])
        elif tag in ("td", "th"):
            self.cell = ""

    def handle_data(self, data):
        if self.cell is not None:
            self.cell += data

    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self.rows[-1].append(self.cell)
            self.cell = None


def fourbar_results(count=3):
    solver = Solver(fourbar(), ["rocker", "rocker_speed", "C_x"])
    return solver(theta=np.linspace(0.0, 1.0, count), a=20, b=66, c=56, d=80, branch=1, thetadot=2.0)


def test_results_stay_a_plain_dict():
    results = fourbar_results()
    assert isinstance(results, dict)
    # A rate divides by the loop's determinant: its request brings the singular mask, beside assembled.
    assert list(results) == ["rocker", "rocker_speed", "C_x", "singular", "assembled"]
    assert dict(results).keys() == results.keys()
    assert results["assembled"].all() and not results["singular"].any()


def test_units_of_angles_rates_lengths():
    assert fourbar_results().units == {"rocker": "rad", "rocker_speed": "rad/s", "C_x": "length", "singular": "",
                                       "assembled": ""}
    units = output_units(slider_crank(), ["s", "sdot", "sddot", "beta", "betaddot", "B_y"], "m")
    assert units == {"s": "m", "sdot": "m/s", "sddot": "m/s^2", "beta": "rad", "betaddot": "rad/s^2", "B_y": "m"}
    inputs = argument_units(slider_crank(), ["theta", "thetaddot", "a", "b", "branch"], "mm")
    assert inputs == {"theta": "rad", "thetaddot": "rad/s^2", "a": "mm", "b": "mm", "branch": ""}


def test_html_table_shows_the_first_rows_with_units():
    results = fourbar_results(HTML_ROWS + 5)
    text = results._repr_html_()
    parser = TableParser()
    parser.feed(text)
    header, *rows = parser.rows
    assert header == ["", "theta (rad)", "rocker (rad)", "rocker_speed (rad/s)", "C_x (length)", "singular", "assembled"]
    assert len(rows) == HTML_ROWS
    assert float(rows[1][1]) == pytest.approx(1.0 / (HTML_ROWS + 4), rel=1e-5)  # linspace(0, 1, 15)[1]
    assert float(rows[0][2]) == pytest.approx(np.pi - cosine_rule_gamma(56.0), rel=1e-5)
    assert rows[0][5:] == ["False", "True"]
    assert f"5 more rows of {HTML_ROWS + 5}" in text


def test_html_escapes_names():
    text = Results({"<b>": np.array([1.0])})._repr_html_()
    assert "<b>" not in text.replace("<th>", "").replace("</th>", "")


def cosine_rule_gamma(c, a=20.0, b=66.0, d=80.0):
    """The interior angle at D of the four-bar at theta = 0 (crank along the ground: the diagonal is d - a)."""
    diagonal = d - a
    return np.arccos((c ** 2 + diagonal ** 2 - b ** 2) / (2 * c * diagonal))


def test_scalar_results_make_one_row():
    results = Solver(fourbar(), ["rocker"])(theta=0.0, a=20, b=66, c=56, d=80, branch=1)
    parser = TableParser()
    parser.feed(results._repr_html_())
    assert len(parser.rows) == 2
    # The rocker angle at theta = 0 by the cosine rule (a = 20 along the ground, so the diagonal is 60).
    diagonal = 80 - 20
    gamma = np.arccos((56 ** 2 + diagonal ** 2 - 66 ** 2) / (2 * 56 * diagonal))
    assert float(parser.rows[1][1]) == pytest.approx(np.pi - gamma, rel=1e-5)


def test_to_frame_names_columns_plainly_with_the_input_and_units_in_attrs():
    pandas = pytest.importorskip("pandas")
    results = fourbar_results(4)
    frame = results.to_frame()
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == ["theta", "rocker", "rocker_speed", "C_x", "singular", "assembled"]
    assert frame.attrs["units"] == {"theta": "rad", "rocker": "rad", "rocker_speed": "rad/s", "C_x": "length",
                                    "singular": "", "assembled": ""}
    assert frame.attrs["constants"] == {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1, "thetadot": 2.0}
    np.testing.assert_array_equal(frame["theta"].to_numpy(), np.linspace(0.0, 1.0, 4))
    assert frame["rocker"].iloc[0] == pytest.approx(np.pi - cosine_rule_gamma(56.0), rel=1e-12)
    assert len(frame) == 4


def test_a_fourbar_solve_has_theta_beta_phi_columns():
    pytest.importorskip("pandas")
    frame = Solver(fourbar(), ["beta", "phi"])(theta=np.array([0.0, np.pi]), a=20, b=66, c=56, d=80,
                                               branch=1).to_frame()
    assert list(frame.columns) == ["theta", "beta", "phi", "assembled"]
    # theta = pi: the crank points back, the diagonal from B to D is a + d = 100, C above the ground (branch +1)
    diagonal = 100.0
    at_d = np.arccos((56 ** 2 + diagonal ** 2 - 66 ** 2) / (2 * 56 * diagonal))
    assert frame["phi"].iloc[1] == pytest.approx(np.pi - at_d, rel=1e-12)


def test_a_grid_keeps_its_axes_as_a_multiindex():
    pytest.importorskip("pandas")
    theta, rockers = np.array([0.0, 0.5, 1.0]), np.array([50.0, 56.0])
    results = Solver(fourbar(), ["rocker"])(theta=theta[:, None], a=20, b=66, c=rockers, d=80, branch=1)
    frame = results.to_frame()
    assert frame.index.names == ["theta", "c"]
    assert frame.index.tolist() == [(t, c) for t in theta for c in rockers]
    assert list(frame.columns) == ["rocker", "assembled"]
    assert frame.attrs["units"] == {"theta": "rad", "c": "length", "rocker": "rad", "assembled": ""}
    for c in rockers:
        assert frame.loc[(0.0, c), "rocker"] == pytest.approx(np.pi - cosine_rule_gamma(c), rel=1e-12)


def test_a_grid_axis_no_single_input_spans_is_numbered():
    pd = pytest.importorskip("pandas")
    frame = Results({"x": np.arange(6.0).reshape(2, 3)}, inputs={"t": np.ones((2, 3))}).to_frame()
    assert frame.index.names == ["axis_0", "axis_1"] and list(frame.columns) == ["t", "x"]
    assert isinstance(frame.index, pd.MultiIndex) and frame["x"].tolist() == [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]


def test_to_frame_broadcasts_scalars():
    pytest.importorskip("pandas")
    frame = Results({"x": np.array([1.0, 2.0, 3.0]), "y": np.float64(5.0)}).to_frame()
    assert frame["y"].tolist() == [5.0, 5.0, 5.0]


def test_to_frame_without_pandas_names_the_extra(monkeypatch):
    real_import = builtins.__import__

    def without_pandas(name, *args, **kwargs):
        if name == "pandas" or name.startswith("pandas."):
            raise ImportError("No module named 'pandas'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", without_pandas)
    with pytest.raises(ImportError, match=r"symlink-kinematics\[pandas\]"):
        fourbar_results().to_frame()


def test_a_grid_says_its_shape_in_html():
    results = Solver(fourbar(), ["rocker"])(theta=np.zeros((3, 1)), a=20, b=66, c=np.array([50.0, 56.0]), d=80,
                                            branch=1)
    assert "6 rows (a 3 x 2 grid, in row-major order)" in results._repr_html_()
