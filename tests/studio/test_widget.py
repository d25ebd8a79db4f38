"""The studio in a notebook: :class:`symlink.studio.widget.LinkageWidget`, its traitlets and its front end.

The Python side: ``values`` and ``branch`` are checked (names, numbers, signs) and merged; the ES module
holds no linkage's data and the solver holds names only as quoted strings, in comments or inside
identifiers.  The front end runs in headless chromium (Playwright) on a minimal page with a fake
anywidget ``model`` (get/set/on/off/save_changes): a length slider moved by the keyboard changes the
model's ``values``, and the drawn joints equal :class:`symlink.numeric.poses.Geometry`'s poses to 1e-12.
"""
from __future__ import annotations

import json
import math
import os
import re
import shutil

import pytest

from conftest import HOEKEN_COORDINATES, HOEKEN_LINKS

pytest.importorskip("anywidget", reason="the notebook widget needs anywidget (the notebook extra)")

import symlink  # noqa: E402
from symlink.numeric.poses import Geometry  # noqa: E402
from symlink.studio.widget import LinkageWidget, widget_esm  # noqa: E402

FOURBAR = {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0}


def hoeken():
    return symlink.from_joints(HOEKEN_LINKS, HOEKEN_COORDINATES, driver="A", name="hoeken")


# --- Python side --------------------------------------------------------------------------------

def test_a_drawn_linkage_starts_at_its_drawing():
    widget = LinkageWidget(hoeken())
    # crank AB = 1, coupler BC = 2.5 on to P at BP = 5, rocker DC = 2.5, ground AD = 2, the crank straight up
    assert widget.values == pytest.approx({"theta_AB": math.pi / 2, "AB": 1.0, "BC": 2.5, "DC": 2.5, "AD": 2.0,
                                           "alpha_AD": 0.0, "BP": 5.0, "alpha_BP": 0.0}, abs=1e-12)
    assert widget.branch == {"branch": 1}
    assert sorted(widget._lengths) == ["AB", "AD", "BC", "BP", "DC"]


def test_values_merge_and_come_back_as_solver_arguments():
    widget = LinkageWidget(symlink.fourbar(), FOURBAR)
    assert widget.values == {"theta": 0.0, **FOURBAR}   # the input starts at 0
    widget.values = {"a": 25, "theta": 0.5}
    assert widget.values == {"theta": 0.5, "a": 25.0, "b": 66.0, "c": 56.0, "d": 80.0}
    widget.branch = {"branch": -1}
    assert widget.linkage_values() == {"theta": 0.5, "a": 25.0, "b": 66.0, "c": 56.0, "d": 80.0, "branch": -1}
    widget.values = {"a": 20, "theta": 0.0}
    widget.branch = {"branch": 1}
    result = symlink.Solver(widget.linkage, ["rocker"])(**widget.linkage_values())
    assert round(math.degrees(float(result["rocker"])), 2) == 110.74   # the front door's doctest


def test_what_the_page_sends_is_checked_as_python_assignments_are():
    # ipywidgets hands a message from the page to set_state: the same checks apply
    widget = LinkageWidget(symlink.fourbar(), FOURBAR)
    widget.set_state({"values": {"theta": 0.25, "a": 20.0, "b": 66.0, "c": 56.0, "d": 81.5}})
    assert widget.values == {"theta": 0.25, "a": 20.0, "b": 66.0, "c": 56.0, "d": 81.5}
    widget.set_state({"branch": {"branch": -1}})
    assert widget.linkage_values()["branch"] == -1
    with pytest.raises(ValueError, match="no input or parameter '__proto__'"):
        widget.set_state({"values": {"__proto__": 1.0}})
    with pytest.raises(ValueError, match="positive"):
        widget.set_state({"values": {"d": -80.0}})
    with pytest.raises(ValueError, match="finite"):
        widget.set_state({"values": {"a": 1.0, "d": float("nan")}, "branch": {"branch": 1}})
    assert widget.values == {"theta": 0.25, "a": 20.0, "b": 66.0, "c": 56.0, "d": 81.5}   # all undone
    assert widget.branch == {"branch": -1}


def test_branches_may_come_with_the_values():
    widget = LinkageWidget(symlink.fourbar(), {**FOURBAR, "theta": 1.0, "branch": -1})
    assert widget.branch == {"branch": -1}
    assert widget.values["theta"] == 1.0


@pytest.mark.parametrize("bad, words", [
    ({"e": 1.0}, "no input or parameter 'e'"),
    ({"branch": 1}, "set widget.branch"),
    ({"a": float("nan")}, "finite"),
    ({"a": float("inf")}, "finite"),
    ({"theta": -float("inf")}, "finite"),
    ({"a": -1.0}, "positive"),
    ({"a": 0}, "positive"),
    ({"a": True}, "number"),
    ({"a": "3"}, "number"),
    ({"a": None}, "number"),
    ({"<img src=x onerror=alert(1)>": 1.0}, "no input or parameter"),
    ([("a", 1.0)], "dict"),
])
def test_bad_values_are_refused_and_change_nothing(bad, words):
    widget = LinkageWidget(symlink.fourbar(), FOURBAR)
    before = dict(widget.values)
    with pytest.raises(ValueError, match=re.escape(words)):
        widget.values = bad
    assert widget.values == before


@pytest.mark.parametrize("bad, words", [({"branch": 0}, "+1 or -1"), ({"branch": 2}, "+1 or -1"),
                                        ({"branch": True}, "+1 or -1"), ({"other": 1}, "no branch 'other'")])
def test_bad_branches_are_refused(bad, words):
    widget = LinkageWidget(symlink.fourbar(), FOURBAR)
    with pytest.raises(ValueError, match=re.escape(words)):
        widget.branch = bad
    assert widget.branch == {"branch": 1}


def test_a_linkage_needs_its_parameters():
    with pytest.raises(ValueError, match="give a value for c, d"):
        LinkageWidget(symlink.fourbar(), {"a": 1.0, "b": 2.0})
    with pytest.raises(ValueError, match="no input or parameter 'z'"):
        LinkageWidget(symlink.fourbar(), {**FOURBAR, "z": 1.0})


def test_ranges_hold_the_values_and_can_be_given():
    widget = LinkageWidget(symlink.fourbar(), FOURBAR, ranges={"b": (60, 70)})
    assert widget._ranges["theta"][:2] == [-math.pi, math.pi]
    assert widget._ranges["b"] == pytest.approx([60, 70, 0.01])
    assert widget._ranges["a"][:2] == [2.0, 60.0]        # a tenth to three times the length
    with pytest.raises(ValueError, match="must go up"):
        LinkageWidget(symlink.fourbar(), FOURBAR, ranges={"b": (70, 60)})
    with pytest.raises(ValueError, match="to give a range"):
        LinkageWidget(symlink.fourbar(), FOURBAR, ranges={"q": (0, 1)})


def test_no_name_reaches_the_code_unquoted():
    names = {"ground": ["Qzx", "Wvk"], "crank": ["Qzx", "Jmy"], "rod": ["Jmy", "Kpl"], "arm": ["Wvk", "Kpl"]}
    coordinates = {"Qzx": (0, 0), "Jmy": (0, 1), "Kpl": (2, 2.5), "Wvk": (2, 0)}
    odd = LinkageWidget(symlink.from_joints(names, coordinates, driver="Qzx", name="odd names"))
    plain = LinkageWidget(symlink.fourbar(), FOURBAR)
    assert odd._esm == plain._esm == widget_esm()   # the module is the same for every linkage: no data in it
    for name in ["Qzx", "Jmy", "Kpl", "Wvk", "crank", "odd names"]:
        assert name not in odd._esm
    widget_js = widget_esm().split("var katex = module.exports;", 1)[1]
    assert "innerHTML" not in widget_js and "insertAdjacentHTML" not in widget_js and "eval(" not in widget_js
    # in the solver a joint's name is in JSON strings and comments, or inside the linkage's own symbols
    # (plain identifiers such as theta_Qzx_Jmy that the linkage checked, or cos_theta_Qzx_Jmy made of them),
    # never code of its own
    code = re.sub(r"/\*.*?\*/", "", odd._solver, flags=re.S)
    code = re.sub(r'"(?:[^"\\\n]|\\.)*"', '""', code)
    symbols = {s.name for s in [*odd.linkage.inputs, *odd.linkage.parameters, *odd.linkage.unknowns,
                                *odd.linkage.branches]}
    for name in ["Qzx", "Jmy", "Kpl", "Wvk"]:
        assert f'"x_{name}"' in odd._solver and f'"y_{name}"' in odd._solver
        holding = set(re.findall(rf"[A-Za-z0-9_]*{name}[A-Za-z0-9_]*", code))
        stray = {word for word in holding if not any(symbol in word for symbol in symbols)}
        assert holding and not stray, (name, stray)
    state = odd.get_state()
    assert json.loads(json.dumps(state["values"])) == odd.values


# --- in a browser -----------------------------------------------------------------------------------

CHROMIUM = "/usr/bin/chromium"
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync"]

#: A fake anywidget model: the page's side of the traitlets.  ``set`` fires the change listeners at once
#: (as Backbone does); ``save_changes`` records what would go to Python.
HARNESS = """async ([esm, state]) => {
  const listeners = {};
  const saved = [];
  const model = {
    get: (name) => state[name],
    set: (name, value) => {
      state[name] = value;
      (listeners["change:" + name] || []).slice().forEach((f) => f());
    },
    on: (event, f) => { (listeners[event] = listeners[event] || []).push(f); },
    off: (event, f) => { listeners[event] = (listeners[event] || []).filter((g) => g !== f); },
    save_changes: () => { saved.push(JSON.parse(JSON.stringify({values: state.values, branch: state.branch}))); },
  };
  window.fakeModel = model;
  window.saved = saved;
  const url = URL.createObjectURL(new Blob([esm], {type: "text/javascript"}));
  const widget = (await import(url)).default;
  window.cleanup = widget.render({model: model, el: document.getElementById("root")});
}"""

JOINTS = """() => Array.from(document.querySelectorAll("circle[data-joint]")).map(
  (c) => [c.getAttribute("data-joint"), c.getAttribute("data-x"), c.getAttribute("data-y")])"""


def needs_browser():
    if shutil.which(CHROMIUM) is None and not os.path.exists(CHROMIUM):
        pytest.skip(f"no chromium at {CHROMIUM} (apt-get install chromium)")
    return pytest.importorskip("playwright.sync_api",
                               reason="the browser test needs playwright (pip install playwright)")


@pytest.fixture
def widget_page():
    api = needs_browser()
    with api.sync_playwright() as driver:
        browser = driver.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        page = browser.new_page(viewport={"width": 1100, "height": 800})
        errors: list[str] = []
        page.on("pageerror", lambda error: errors.append(str(error)))
        yield page
        browser.close()
        assert errors == [], f"errors in the page: {errors}"


def load(page, widget: LinkageWidget) -> None:
    page.set_content("<!doctype html><html><head><meta charset='utf-8'></head>"
                     "<body><div id='root'></div></body></html>")
    page.add_style_tag(content=widget._css)
    state = {k: v for k, v in widget.get_state().items() if k in {"values", "branch", "_solver", "_ranges",
                                                                  "_lengths", "_equations"}}
    page.evaluate(HARNESS, [widget._esm, state])


def drawn(page) -> dict[str, tuple[float, float]]:
    return {name: (float(x), float(y)) for name, x, y in page.evaluate(JOINTS)}


def expected(linkage, values) -> dict[str, tuple[float, float]]:
    """Every joint and point that Geometry places, less the points that only give a guide's direction."""
    poses = Geometry(linkage).poses(values)
    assert bool(poses.assembled[0])
    return {name: (float(place[0].real), float(place[0].imag)) for name, place in poses.positions.items()
            if not name.endswith(" guide")}


def assert_same_pose(found, wanted) -> None:
    assert sorted(found) == sorted(wanted)
    for name, (x, y) in wanted.items():
        assert found[name][0] == pytest.approx(x, abs=1e-12), name
        assert found[name][1] == pytest.approx(y, abs=1e-12), name


def test_a_length_slider_moves_the_drawing_and_tells_python(widget_page):
    page = widget_page
    widget = LinkageWidget(hoeken(), ranges={"BC": (2.0, 3.0)})   # step 0.001: 2.5 is on the slider's grid
    load(page, widget)
    # the drawing as drawn: the joints at their coordinates
    assert_same_pose(drawn(page), {j: (float(x), float(y)) for j, (x, y) in HOEKEN_COORDINATES.items()})
    assert page.locator(".symlink-equations .katex").count() == 1    # typeset by KaTeX
    assert page.locator("input[data-kind=length]").count() == 5
    slider = page.locator("input[data-name=BC]")
    slider.focus()
    for _ in range(10):
        page.keyboard.press("ArrowRight")
    values = page.evaluate("() => window.fakeModel.get('values')")
    assert values["BC"] == pytest.approx(2.51, abs=1e-12)
    assert {k: v for k, v in values.items() if k != "BC"} == {k: v for k, v in widget.values.items() if k != "BC"}
    assert page.evaluate("() => window.saved.length") == 10           # each step went to Python
    widget.values = values                                            # what the comm does with it
    assert widget.values["BC"] == values["BC"]
    at = expected(widget.linkage, widget.linkage_values())
    assert_same_pose(drawn(page), at)
    assert at["C"] != pytest.approx((2.0, 2.5), abs=1e-3)            # it did move


def test_python_moves_the_drawing_and_the_branch_switch_flips_it(widget_page):
    page = widget_page
    widget = LinkageWidget(hoeken())
    load(page, widget)
    widget.values = {"theta_AB": 0.3, "DC": 2.7}                      # set from Python ...
    page.evaluate("(v) => window.fakeModel.set('values', v)", widget.values)   # ... and synced
    assert_same_pose(drawn(page), expected(widget.linkage, widget.linkage_values()))
    step = widget._ranges["DC"][2]
    assert abs(float(page.locator("input[data-name=DC]").input_value()) - 2.7) <= step / 2   # on its grid
    assert page.locator("label:has(input[data-name=DC]) .symlink-value").text_content() == "2.7"
    page.select_option("select[data-branch=branch]", "-1")
    branch = page.evaluate("() => window.fakeModel.get('branch')")
    assert branch == {"branch": -1}
    widget.branch = branch
    assert_same_pose(drawn(page), expected(widget.linkage, widget.linkage_values()))
    # a crank of 10 cannot reach the rocker (BC + DC = 5.2): no pose, and the page says so
    widget.values = {"AB": 10.0}
    assert not bool(Geometry(widget.linkage).poses(widget.linkage_values()).assembled[0])
    page.evaluate("(v) => window.fakeModel.set('values', v)", widget.values)
    assert page.locator("svg.symlink-drawing").get_attribute("data-assembled") == "false"
    assert drawn(page) == {}
    assert page.locator(".symlink-message").text_content() == "cannot be assembled here"


@pytest.mark.parametrize("name", ["fourbar", "slider-crank", "inverted-slider-crank", "jansen", "watt2"])
def test_catalog_linkages_move_as_geometry_places_them(widget_page, name):
    from symlink.io.linkage_file import load_linkage
    found = load_linkage(name)
    widget = LinkageWidget(found.linkage, found.defaults)
    load(widget_page, widget)
    wanted = expected(widget.linkage, widget.linkage_values())
    assert_same_pose(drawn(widget_page), wanted)
    slider = widget_page.locator(f"input[data-name={widget.linkage.inputs[0].name}]")
    slider.focus()
    for _ in range(25):
        widget_page.keyboard.press("ArrowRight")
    widget.values = widget_page.evaluate("() => window.fakeModel.get('values')")
    assert_same_pose(drawn(widget_page), expected(widget.linkage, widget.linkage_values()))
    # each slider's guide is drawn at the angle Geometry gives its line
    poses = Geometry(widget.linkage).poses(widget.linkage_values())
    slots = {line.get_attribute("data-slider"): float(line.get_attribute("data-angle"))
             for line in widget_page.locator("line.symlink-guide").all()}
    assert sorted(slots) == sorted(poses.directions)
    for joint, angle in slots.items():
        turn = math.remainder(angle - float(poses.directions[joint][0]), 2 * math.pi)
        assert abs(turn) < 1e-9, joint


def test_play_turns_the_input_and_stop_tells_python(widget_page):
    page = widget_page
    widget = LinkageWidget(symlink.fourbar(), FOURBAR)
    load(page, widget)
    page.click("button.symlink-play")
    page.wait_for_function("() => window.fakeModel.get('values').theta > 0.1")   # it turns (no timing asserted)
    assert page.evaluate("() => window.saved.length") == 0     # while it plays, the page keeps the motion
    page.click("button.symlink-play")
    values = page.evaluate("() => window.fakeModel.get('values')")
    assert page.evaluate("() => window.saved[window.saved.length - 1].values") == values
    assert values["theta"] > 0.1 and {k: values[k] for k in FOURBAR} == FOURBAR
    widget.values = values
    assert_same_pose(drawn(page), expected(widget.linkage, widget.linkage_values()))
