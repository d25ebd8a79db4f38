"""The studio's "Analyse and design" in a real browser (Playwright driving Debian's chromium).

Hoeken's four-bar is drawn by clicks with its coupler point E on a ternary coupler; the Analysis panel is
read; five target points that a hand four-bar's coupler point passes through (circle intersections with
``math``) are clicked with the Targets tool and the linkage synthesised from the page.  The design the page
applies is checked in Python: :func:`~symlink.mechanism.joints.from_joints` of the page's new drawing,
:class:`~symlink.numeric.poses.Geometry` at the inputs the page was given, through every clicked target.
"""
from __future__ import annotations

import math

from test_browser import IMAGES, SCREENSHOTS, browser, draw_hoeken, needs_solver, page, server, settle  # noqa: F401
from test_design import hand_targets, path_distances


def test_the_analysis_panel_shows_hoekens_range_and_transmission_in_degrees(server, page):  # noqa: F811
    draw_hoeken(page, server)
    page.wait_for_function("window.studio.analysisDone()", timeout=120_000)
    # Hoeken's crank 1, coupler 2.5, rocker 2.5, ground 2: s + l = 3.5 < p + q = 4.5, the crank shortest
    assert "crank-rocker" in page.text_content("#analysis [data-key=grashof]")
    assert "turns fully" in page.text_content("#analysis [data-key=reach]")
    a, b, c, d = 1.0, 2.5, 2.5, 2.0
    low = math.degrees(math.acos((b * b + c * c - (a - d) ** 2) / (2 * b * c)))   # crank along the ground
    high = math.degrees(math.acos((b * b + c * c - (a + d) ** 2) / (2 * b * c)))  # crank turned back
    shown = page.text_content("#analysis [data-key=transmission-ABCD]")
    assert f"{low:.2f}° to {high:.2f}°" in shown, shown


@needs_solver
def test_targets_clicked_and_synthesised_are_on_the_designed_path(server, page):  # noqa: F811
    draw_hoeken(page, server)
    settle(page, solver=True)
    page.click("#tool-targets")
    hand = hand_targets()
    for x, y in hand:
        page.mouse.click(*page.evaluate(f"window.studio.toScreen({x}, {y})"))
    clicked = page.evaluate("window.studio.targets()")
    assert len(clicked) == 5 and len(page.evaluate("window.studio.design()")["joints"]) == 5  # no joint added
    for (x, y), (u, v) in zip(hand, clicked):  # within a pixel (1/100 of a unit) of the hand targets
        assert math.dist((x, y), (u, v)) < 0.015
    assert page.input_value("#synth-point") == "E"  # the coupler point is proposed
    page.fill("#synth-starts", "4")
    page.click("#synthesize")
    page.wait_for_function("!window.studio.synthesizing() && window.studio.synthesis() !== null", timeout=120_000)
    result = page.evaluate("window.studio.synthesis()")
    design = page.evaluate("window.studio.design()")
    assert design == result["drawing"]
    size = max(max(t[0] for t in clicked) - min(t[0] for t in clicked),
               max(t[1] for t in clicked) - min(t[1] for t in clicked))
    distances = path_distances(design, "E", result["inputs"], clicked)
    assert max(distances) < 1e-6 * size, distances
    assert page.locator("path.synth-path").count() == 1 and page.locator("path.target").count() == 5
    assert "passes through the 5 targets" in page.text_content("#synth-message")
    print(f"synthesis from the page: {page.evaluate('window.studio.synthesisSeconds()'):.1f} s")
    settle(page, solver=True)  # the new drawing is a linkage the page animates
    if SCREENSHOTS:
        page.click("#tolerance")
        page.wait_for_function("window.studio.band() !== null && window.studio.analysisDone()", timeout=120_000)
        page.screenshot(path=str(IMAGES / "studio_design.png"))
    page.keyboard.press("Control+z")
    assert page.evaluate("window.studio.design()")["joints"][1] == {"name": "B", "x": 0, "y": 1}


def test_a_synthesis_with_too_few_targets_says_so_and_can_be_cancelled(server, page):  # noqa: F811
    draw_hoeken(page, server)
    page.click("#tool-targets")
    for x, y in [(1, 4), (2, 4.5)]:
        page.mouse.click(*page.evaluate(f"window.studio.toScreen({x}, {y})"))
    assert page.is_disabled("#synthesize")
    assert "1 or more points" in page.text_content("#synth-message")
    page.mouse.click(*page.evaluate("window.studio.toScreen(3, 4.2)"))
    page.fill("#synth-starts", "64")
    page.click("#synthesize")
    page.wait_for_function("window.studio.state.job && window.studio.state.job.id")
    page.click("#synth-cancel")
    page.wait_for_function("document.querySelector('#synth-message').textContent === 'cancelled'")
    assert not page.evaluate("window.studio.synthesizing()")
    page.fill("#synth-starts", "1000")
    page.click("#synthesize")
    page.wait_for_function("document.querySelector('#synth-message').classList.contains('error')")
    assert "starts is a whole number from 1 to 64" in page.text_content("#synth-message")


def test_the_tolerance_band_of_the_coupler_point_is_drawn(server, page):  # noqa: F811
    draw_hoeken(page, server)
    page.fill("#tol-band", "0.01")
    assert page.input_value("#tol-point") == "E"
    page.click("#tolerance")
    page.wait_for_function("window.studio.band() !== null", timeout=120_000)
    band = page.evaluate("window.studio.band()")
    # the crank pin's band is AB's alone (A is exact): E's, moved by every length, is wider than that somewhere
    assert band["point"] == "E" and len(band["widths"]) == 361 and band["worst"] > 0.01
    assert page.locator("path.tol-band").count() == 1
    assert "strays at most" in page.text_content("#tol-message")
    page.fill("#tol-band", "-1")
    page.click("#tolerance")
    assert "above 0" in page.text_content("#tol-message")
