"""Results: still a dict, units per output, an HTML table and a pandas DataFrame (pandas optional)."""
import builtins
import html.parser

import numpy as np
import pytest

from symlink.catalog import fourbar, slider_crank
from symlink.results import HTML_ROWS, Results
from symlink.solver import Solver
from symlink.units import output_units


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


def test_html_table_shows_the_first_rows_with_units():
    results = fourbar_results(HTML_ROWS + 5)
    text = results._repr_html_()
    parser = TableParser()
    parser.feed(text)
    header, *rows = parser.rows
    assert header == ["", "rocker (rad)", "rocker_speed (rad/s)", "C_x (length)", "singular", "assembled"]
    assert len(rows) == HTML_ROWS
    # Row 0 at theta = 0: C_x = d + c cos(phi) with the closed form of the first row.
    assert float(rows[0][1]) == pytest.approx(float(results["rocker"][0]), rel=1e-5)
    assert rows[0][4:] == ["False", "True"]
    assert f"5 more rows of {HTML_ROWS + 5}" in text


def test_html_escapes_names():
    text = Results({"<b>": np.array([1.0])})._repr_html_()
    assert "<b>" not in text.replace("<th>", "").replace("</th>", "")


def test_scalar_results_make_one_row():
    results = Solver(fourbar(), ["rocker"])(theta=0.0, a=20, b=66, c=56, d=80, branch=1)
    parser = TableParser()
    parser.feed(results._repr_html_())
    assert len(parser.rows) == 2
    # The rocker angle at theta = 0 by the cosine rule (a = 20 along the ground, so the diagonal is 60).
    diagonal = 80 - 20
    gamma = np.arccos((56 ** 2 + diagonal ** 2 - 66 ** 2) / (2 * 56 * diagonal))
    assert float(parser.rows[1][1]) == pytest.approx(np.pi - gamma, rel=1e-5)


def test_to_frame_carries_units():
    pandas = pytest.importorskip("pandas")
    results = fourbar_results(4)
    frame = results.to_frame()
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == ["rocker (rad)", "rocker_speed (rad/s)", "C_x (length)", "singular", "assembled"]
    assert frame.attrs["units"] == results.units
    np.testing.assert_array_equal(frame["rocker (rad)"].to_numpy(), results["rocker"])
    assert len(frame) == 4


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
