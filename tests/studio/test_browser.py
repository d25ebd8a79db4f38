"""The studio in a real browser (Playwright driving Debian's chromium): draw, derive, move, reload, share, offline.

Hoeken's four-bar is drawn by clicks (no catalog), its structure and equations read from the page and
compared with :func:`symlink.mechanism.joints.from_joints`; the page's joints over a full turn are
compared with :class:`symlink.numeric.poses.Geometry` to 1e-12.  The tests skip, saying why, without
Playwright or chromium; those that move the linkage skip without the generated JavaScript solver
(``symlink.codegen.javascript``).  With ``SYMLINK_SCREENSHOTS=1`` they also write the tutorial's pictures
(``docs/images/studio_*.png``).
"""
from __future__ import annotations

import math
import os
import shutil
import threading
import time
from pathlib import Path

import numpy
import pytest

from conftest import HOEKEN

CHROMIUM = "/usr/bin/chromium"
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync"]
IMAGES = Path(__file__).resolve().parents[2] / "docs" / "images"
SCREENSHOTS = os.environ.get("SYMLINK_SCREENSHOTS") == "1"

pytestmark = [
    pytest.mark.skipif(shutil.which(CHROMIUM) is None and not os.path.exists(CHROMIUM),
                       reason=f"no chromium at {CHROMIUM} (apt-get install chromium)"),
]
playwright_api = pytest.importorskip("playwright.sync_api",
                                     reason="the browser tests need playwright (pip install playwright)")
pytest.importorskip("uvicorn", reason="the studio's server needs the studio extra (uvicorn)")

#: Where the test clicks Hoeken's joints (drawing units); the page names them A, B, C, D, E in this order.
CLICKS = [(0, 0), (0, 1), (2, 2.5), (2, 0), (4, 4)]
#: What the clicks draw, as from_joints arguments (E is Hoeken's tracing point P).
LINKS = {"ground": ["A", "D"], "link1": ["A", "B"], "link2": ["B", "C", "E"], "link3": ["D", "C"]}
COORDINATES = {"A": (0, 0), "B": (0, 1), "C": (2, 2.5), "D": (2, 0), "E": (4, 4)}


def has_javascript_solver() -> bool:
    try:
        from symlink.codegen import javascript  # noqa: F401
    except ImportError:
        return False
    return hasattr(javascript, "javascript_geometry")


needs_solver = pytest.mark.skipif(not has_javascript_solver(),
                                  reason="no generated JavaScript solver yet (symlink.codegen.javascript, "
                                         "branch js-printer): the page cannot move the linkage")


@pytest.fixture(scope="module")
def server():
    """The studio on a free port of 127.0.0.1, in a thread of this process; yields its base URL with the token."""
    import uvicorn

    from symlink.studio.server import create_app, free_port
    port, token = free_port(), "browser-test-token"
    config = uvicorn.Config(create_app(port, token), host="127.0.0.1", port=port, log_level="warning",
                            lifespan="off")
    running = uvicorn.Server(config)
    running.install_signal_handlers = lambda: None  # older uvicorn; newer ones skip signals off the main thread
    thread = threading.Thread(target=running.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 30
    while not running.started:
        if time.monotonic() > deadline or not thread.is_alive():
            pytest.fail("the studio's server did not start")
        time.sleep(0.05)
    yield f"http://127.0.0.1:{port}/?token={token}"
    running.should_exit = True
    thread.join(10)


@pytest.fixture(scope="module")
def browser():
    with playwright_api.sync_playwright() as driver:
        launched = driver.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        yield launched
        launched.close()


@pytest.fixture
def page(browser):
    context = browser.new_context(viewport={"width": 1280, "height": 760})
    opened = context.new_page()
    errors: list[str] = []
    opened.on("pageerror", lambda error: errors.append(str(error)))
    opened.errors = errors
    yield opened
    context.close()
    assert errors == [], f"errors in the page: {errors}"


def settle(page, solver: bool = False) -> None:
    """Wait until the page has its answers from the server (and its solver)."""
    page.wait_for_function("window.studio && window.studio.idle()" + (" && window.studio.solverReady()" if solver
                                                                       else ""), timeout=120_000)


def draw_hoeken(page, url: str) -> None:
    """Hoeken's four-bar drawn as a user does: five clicks, three links, the ground and the driver."""
    page.goto(url)
    page.wait_for_function("window.studio && window.studio.started")
    page.evaluate("window.studio.started")
    page.evaluate("localStorage.clear()")
    page.click("#tool-clear")
    page.evaluate("window.studio.setView(100, 150, 560)")
    at = lambda x, y: page.evaluate(f"window.studio.toScreen({x}, {y})")  # noqa: E731
    for x, y in CLICKS:
        page.mouse.click(*at(x, y))
    def select(*names: str) -> None:
        for name in names:
            page.click(f"circle[data-joint={name}]")
    for link in (["A", "B"], ["B", "C", "E"], ["D", "C"]):
        select(*link)
        page.keyboard.press("l")
    select("A", "D")
    page.keyboard.press("g")
    select("A")
    page.keyboard.press("m")
    settle(page)


def hoeken_linkage():
    from symlink.mechanism.joints import from_joints
    return from_joints(LINKS, COORDINATES, driver="A", name="drawing")


def test_draw_hoeken_by_clicks_and_read_its_structure_and_equations(server, page):
    draw_hoeken(page, server)
    design = page.evaluate("window.studio.design()")
    assert {j["name"]: (j["x"], j["y"]) for j in design["joints"]} == COORDINATES  # clicks snap to the 0.1 grid
    assert design["links"] == [["A", "B"], ["B", "C", "E"], ["D", "C"]]
    assert design["driver"] == {"joint": "A"}
    message = page.text_content("#structure-message")
    assert "mobility 1" in message and "closed form" in message
    page.wait_for_function("document.querySelector('#equations').dataset.latex")
    shown = page.get_attribute("#equations", "data-latex")
    assert "$" + shown + "$" == hoeken_linkage().linkage._repr_latex_()
    assert page.locator("#equations .katex").count() == 1  # typeset, not left as source
    if SCREENSHOTS:
        page.screenshot(path=str(IMAGES / "studio_draw.png"))


def expected_poses(angles, branch: int = 1):
    from symlink.numeric.poses import Geometry
    drawn = hoeken_linkage()
    values = {**drawn.defaults, "branch": branch}
    return Geometry(drawn.linkage).poses(values, {"theta_AB": numpy.asarray(angles)})


@needs_solver
def test_a_full_turn_in_the_page_matches_the_library(server, page):
    draw_hoeken(page, server)
    settle(page, solver=True)
    angles = numpy.linspace(0, 2 * math.pi, 73)
    expected = expected_poses(angles)
    assert expected.assembled.all()  # Hoeken's crank turns fully
    for k, angle in enumerate(angles):
        shown = page.evaluate(f"window.studio.setInput({float(angle)!r})")
        for joint in COORDINATES:
            place = expected.positions[joint][k]
            assert shown[joint][0] == pytest.approx(place.real, abs=1e-12), (joint, angle)
            assert shown[joint][1] == pytest.approx(place.imag, abs=1e-12), (joint, angle)
    if SCREENSHOTS:
        page.evaluate(f"window.studio.setInput({math.radians(200)!r})")
        page.screenshot(path=str(IMAGES / "studio_move.png"))


@needs_solver
def test_the_branch_switch_shows_the_other_assembly(server, page):
    draw_hoeken(page, server)
    settle(page, solver=True)
    page.select_option("select[data-branch=branch]", "-1")
    angle = math.radians(120)
    shown = page.evaluate(f"window.studio.setInput({angle!r})")
    other = expected_poses([angle], branch=-1)
    drawn = expected_poses([angle], branch=1)
    assert abs(other.positions["C"][0] - drawn.positions["C"][0]) > 0.1  # the two assemblies differ
    assert shown["C"] == pytest.approx([other.positions["C"][0].real, other.positions["C"][0].imag], abs=1e-12)


@needs_solver
def test_where_it_cannot_be_assembled_the_page_says_so(server, page):
    """A crank longer than the others allow: part of the turn cannot be assembled; no pose is shown there."""
    page.goto(server)
    page.evaluate("window.studio.started")
    rocker = {**HOEKEN, "joints": [{**j, "y": 1.8} if j["name"] == "B" else j for j in HOEKEN["joints"]]}
    page.evaluate(f"window.studio.setDesign({rocker!r})".replace("True", "true").replace("False", "false"))
    settle(page, solver=True)
    from symlink.mechanism.joints import from_joints
    drawn = from_joints({"ground": ["A", "D"], "link1": ["A", "B"], "link2": ["B", "C", "P"], "link3": ["D", "C"]},
                        {"A": (0, 0), "B": (0, 1.8), "C": (2, 2.5), "D": (2, 0), "P": (4, 4)}, driver="A")
    from symlink.numeric.poses import Geometry
    angles = numpy.linspace(-math.pi, math.pi, 181)
    expected = Geometry(drawn.linkage).poses(drawn.defaults, {"theta_AB": angles}).assembled
    assert not expected.all() and expected.any()
    for angle, ok in zip(angles, expected):
        shown = page.evaluate(f"window.studio.setInput({float(angle)!r})")
        assert (shown is not None) == bool(ok), angle
        if not ok:
            assert page.text_content("#motion-message") == "cannot be assembled here"


def test_reload_keeps_the_design_and_the_share_link_round_trips(server, page, browser):
    draw_hoeken(page, server)
    design = page.evaluate("window.studio.design()")
    page.reload()
    page.evaluate("window.studio.started")
    assert page.evaluate("window.studio.design()") == design
    page.goto(server)  # no hash: the design comes from local storage
    page.evaluate("window.studio.started")
    assert page.evaluate("window.studio.design()") == design
    link = page.evaluate("window.studio.shareLink()")
    assert "#d=" in link
    fresh = browser.new_context()  # another profile: no local storage
    try:
        other = fresh.new_page()
        other.goto(link)
        other.evaluate("window.studio.started")
        assert other.evaluate("window.studio.design()") == design
    finally:
        fresh.close()


def test_undo_and_redo(server, page):
    draw_hoeken(page, server)
    before = page.evaluate("window.studio.design()")
    page.keyboard.press("Control+z")  # the driver
    assert page.evaluate("window.studio.design()")["driver"] is None
    page.keyboard.press("Control+y")
    assert page.evaluate("window.studio.design()") == before


def test_the_self_contained_page_animates_offline(server, page, tmp_path):
    from symlink.cli import main
    source = tmp_path / "hoeken.toml"
    from symlink.io.joint_tables import joint_file_text
    source.write_text(joint_file_text(hoeken_linkage()))
    out = tmp_path / "hoeken.html"
    assert main(["studio", "--html", str(out), str(source)]) == 0
    asked: list[str] = []

    def only_the_file(route) -> None:
        asked.append(route.request.url)
        if route.request.url == out.as_uri():
            route.continue_()
        else:
            route.abort()
    page.route("**/*", only_the_file)
    page.goto(out.as_uri())
    page.evaluate("window.studio.started")
    assert asked == [out.as_uri()]  # nothing else was even asked for
    assert "mobility 1" in page.text_content("#structure-message")
    assert page.locator("#equations .katex").count() == 1
    if not has_javascript_solver():
        assert page.text_content("#motion-message")  # says why it cannot move
        pytest.skip("no generated JavaScript solver yet: the page shows the drawing and equations only")
    angle = math.radians(200)
    shown = page.evaluate(f"window.studio.setInput({angle!r})")
    expected = expected_poses([angle])
    assert shown["E"] == pytest.approx([expected.positions["E"][0].real, expected.positions["E"][0].imag], abs=1e-12)
    page.click("#play")
    page.wait_for_timeout(300)
    assert page.evaluate("window.studio.positions()")["E"] != shown["E"]  # it moves
    if SCREENSHOTS:
        page.screenshot(path=str(IMAGES / "studio_offline.png"))


def test_an_over_constrained_drawing_is_said_so_in_the_page(server, page):
    page.goto(server)
    page.evaluate("window.studio.started")
    triangle = {"name": "triangle", "joints": [{"name": "A", "x": 0, "y": 0, "ground": True},
                                               {"name": "B", "x": 1, "y": 1},
                                               {"name": "C", "x": 2, "y": 0, "ground": True}],
                "links": [["A", "B"], ["B", "C"]], "driver": {"joint": "A"}, "sliders": []}
    page.evaluate("design => window.studio.setDesign(design)", triangle)
    settle(page)
    message = page.locator("#structure-message")
    assert "over-constrained" in message.text_content()
    assert "error" in message.get_attribute("class")
    assert not page.evaluate("window.studio.solverReady()")
    assert page.is_disabled("#play")


@needs_solver
def test_a_slider_crank_opened_by_name_moves_as_the_library_says(server, page):
    page.goto(server)
    page.evaluate("window.studio.started")
    page.fill("#open-source", "slider-crank")
    page.click("#tool-open")
    page.wait_for_function("window.studio.design().name === 'slider-crank'")
    settle(page, solver=True)
    design = page.evaluate("window.studio.design()")
    (slider,) = design["sliders"]
    from symlink import Slider, from_joints
    from symlink.numeric.poses import Geometry
    ground = [j["name"] for j in design["joints"] if j["ground"]] + [slider["joint"]]
    links = {"ground": ground, **{f"link{k + 1}": held for k, held in enumerate(design["links"])}}
    drawn = from_joints(links, {j["name"]: (j["x"], j["y"]) for j in design["joints"]},
                        driver=[(design["driver"]["joint"], f"link{design['driver']['link'] + 1}")],
                        joints={slider["joint"]: Slider("ground", slider["angle"])}, name="slider-crank")
    angles = numpy.radians([0.0, 45.0, 100.0, 200.0, 300.0])
    expected = Geometry(drawn.linkage).poses(drawn.defaults, {drawn.linkage.inputs[0].name: angles})
    for k, angle in enumerate(angles):
        shown = page.evaluate(f"window.studio.setInput({float(angle)!r})")
        for joint in (j["name"] for j in design["joints"]):
            place = expected.positions[joint][k]
            assert shown[joint] == pytest.approx([place.real, place.imag], abs=1e-12), (joint, angle)


def test_dragging_a_joint_moves_it_on_the_grid_in_one_undo_step(server, page):
    draw_hoeken(page, server)
    start = page.evaluate("window.studio.toScreen(0, 1)")
    end = page.evaluate("window.studio.toScreen(-0.5, 1.5)")
    page.mouse.move(*start)
    page.mouse.down()
    page.mouse.move(*end, steps=5)
    page.mouse.up()
    moved = {j["name"]: (j["x"], j["y"]) for j in page.evaluate("window.studio.design()")["joints"]}
    assert moved["B"] == (-0.5, 1.5) and moved["C"] == (2, 2.5)
    settle(page)
    assert "mobility 1" in page.text_content("#structure-message")
    page.keyboard.press("Control+z")
    back = {j["name"]: (j["x"], j["y"]) for j in page.evaluate("window.studio.design()")["joints"]}
    assert back["B"] == (0, 1)
