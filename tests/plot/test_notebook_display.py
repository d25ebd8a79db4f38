"""What a notebook shows of symlink's objects survives offline and in ``jupyter nbconvert --to html``.

The animation player loads nothing from the network; a rendered GIF embeds
itself as an ``<img>`` (nbconvert's HTML keeps ``text/html`` and drops
``image/gif``, which is how the example notebook's HTML came to show
``<IPython.core.display.Image object>``); result records show as HTML tables.
The export itself is checked where nbconvert is installed (the notebook extra).
"""
import base64
import html.parser
import importlib.util
import math
import re

import matplotlib

matplotlib.use("Agg")

import numpy  # noqa: E402
import pytest  # noqa: E402

from symlink.analysis.report import analyze_linkage  # noqa: E402
from symlink.mechanism.catalog import fourbar  # noqa: E402
from symlink.common.display import record_html  # noqa: E402
from symlink.plot.animation import (PLAYER_SYMBOLS, animate_linkage, inline_animation,  # noqa: E402
                                    self_contained_player)

SEED001 = dict(a=0.1, b=0.4, c=0.25, d=0.3)  # the Maple worksheet's four-bar (m)
ADDRESS = re.compile(r"(?:https?:)?//[\w.-]+\.[a-z]{2,}/")


class Buttons(html.parser.HTMLParser):
    """The visible text of each ``<button>``."""

    def __init__(self):
        super().__init__()
        self.labels, self.inside = [], False

    def handle_starttag(self, tag, attrs):
        if tag == "button":
            self.labels.append("")
            self.inside = True

    def handle_endtag(self, tag):
        if tag == "button":
            self.inside = False

    def handle_data(self, data):
        if self.inside:
            self.labels[-1] += data.strip()


def test_the_inline_player_loads_nothing_and_every_button_has_a_symbol():
    shown = inline_animation(fourbar(), SEED001, frames=3, size_px=(160, 120))
    assert ADDRESS.search(shown.html) is None, "the player refers to a network address"
    assert "<link" not in shown.html and 'class="fa' not in shown.html
    buttons = Buttons()
    buttons.feed(shown.html)
    assert len(buttons.labels) == len(PLAYER_SYMBOLS) and all(buttons.labels)
    assert set(buttons.labels) == set(PLAYER_SYMBOLS.values())


def test_a_player_that_still_loads_something_is_refused():
    with pytest.raises(ValueError, match="loads https://cdn.example.org/"):
        self_contained_player('<script src="https://cdn.example.org/player.js"></script>')


def test_a_rendered_gif_embeds_its_own_bytes(tmp_path):
    rendered = animate_linkage(fourbar(), SEED001, tmp_path / "seed001.gif", frames=3, size_px=(160, 120))
    bundle = rendered._repr_mimebundle_()
    written = (tmp_path / "seed001.gif").read_bytes()
    assert base64.b64decode(bundle["image/gif"]) == written
    source = re.fullmatch(r'<img src="data:image/gif;base64,([A-Za-z0-9+/=]+)" alt="[^"]*">', bundle["text/html"])
    assert source is not None and base64.b64decode(source.group(1)) == written
    assert written[:6] in (b"GIF87a", b"GIF89a")


def test_the_linkage_report_shows_as_a_table_with_its_numbers():
    report = analyze_linkage(fourbar(), dict(a=20, b=66, c=56, d=80), output="rocker")
    text = report._repr_html_()
    assert "<caption>LinkageReport</caption>" in text and "<caption>Mobility</caption>" in text
    # seed 003's crank-rocker: the rocker's stroke between its limit positions by the cosine rule, crank and
    # coupler folded (b - a = 46) and stretched (a + b = 86): the angle at D of triangle A, D, C
    folded = math.acos((56 ** 2 + 80 ** 2 - 46 ** 2) / (2 * 56 * 80))
    stretched = math.acos((56 ** 2 + 80 ** 2 - 86 ** 2) / (2 * 56 * 80))
    assert f"<th>stroke</th><td>{abs(folded - stretched):.6g}</td>" in text
    assert "<th>full_turn</th><td>True</td>" in text  # a property, shown with the fields
    assert "<th>dof</th><td>1</td>" in text  # Gruebler: 3 (4 - 1) - 2 * 4 = 1


def test_record_text_is_escaped():
    from dataclasses import dataclass

    @dataclass
    class Named:
        name: str
        values: numpy.ndarray

    text = record_html(Named("<script>alert(1)</script>", numpy.arange(100.0)))
    assert "<script>" not in text and "&lt;script&gt;" in text
    assert "array (100,) of float64, from 0 to 99" in text


EXPORT = ("nbformat", "nbconvert", "IPython")


@pytest.mark.skipif(any(importlib.util.find_spec(name) is None for name in EXPORT),
                    reason="the notebook extra is not installed (nbformat, nbconvert, IPython): "
                           "pip install -e '.[notebook]'")
def test_nbconvert_html_keeps_the_animation_and_the_report(tmp_path):
    import nbformat
    from IPython.core.interactiveshell import InteractiveShell
    from nbconvert import HTMLExporter

    shell = InteractiveShell.instance()
    rendered = animate_linkage(fourbar(), SEED001, tmp_path / "seed001.gif", frames=3, size_px=(160, 120))
    shown = [rendered, inline_animation(fourbar(), SEED001, frames=3, size_px=(160, 120)),
             analyze_linkage(fourbar(), dict(a=20, b=66, c=56, d=80), output="rocker")]
    cells = []
    for index, value in enumerate(shown):
        data, metadata = shell.display_formatter.format(value)
        cell = nbformat.v4.new_code_cell(f"value_{index}", execution_count=index + 1)
        cell.outputs = [nbformat.v4.new_output("execute_result", data=data, metadata=metadata,
                                               execution_count=index + 1)]
        cells.append(cell)
    page, _ = HTMLExporter().from_notebook_node(nbformat.v4.new_notebook(cells=cells))
    assert "IPython.core.display" not in page and "Rendered(path=" not in page
    assert page.count("data:image/gif;base64,") == 1 and "<caption>LinkageReport</caption>" in page
    assert page.count("data:image/png;base64,") >= 3 and "anim_slider" in page  # the player and its 3 frames
    assert "font-awesome" not in page and "fa fa-play" not in page
