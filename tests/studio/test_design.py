"""The studio's "Analyse and design" API (/api/analyze, /api/synthesize) through Starlette's TestClient."""
from __future__ import annotations

import math

import pytest

from conftest import TOKEN  # noqa: F401 - tests/ is on the path; this is tests/studio/conftest.py

AUTH = {"X-Symlink-Token": TOKEN}


def circles(p, r, q, s, upper=True):
    """Where the circle about p of radius r meets the circle about q of radius s (left of p -> q if upper)."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    span = math.hypot(dx, dy)
    along = (r * r - s * s + span * span) / (2 * span)
    height = math.sqrt(r * r - along * along) * (1 if upper else -1)
    return (p[0] + along * dx / span - height * dy / span, p[1] + along * dy / span + height * dx / span)


def seed_fourbar(crank_deg: float = 60.0) -> dict:
    """The seed-003 four-bar a, b, c, d = 20, 66, 56, 80 drawn by its joints, A = (0, 0), D = (80, 0)."""
    a, b, c = 20.0, 66.0, 56.0
    B = (a * math.cos(math.radians(crank_deg)), a * math.sin(math.radians(crank_deg)))
    C = circles(B, b, (80.0, 0.0), c)
    return {"name": "seed", "joints": [{"name": "A", "x": 0, "y": 0, "ground": True},
                                       {"name": "B", "x": B[0], "y": B[1]}, {"name": "C", "x": C[0], "y": C[1]},
                                       {"name": "D", "x": 80, "y": 0, "ground": True}],
            "links": [["A", "B"], ["B", "C"], ["D", "C"]], "driver": {"joint": "A"}, "sliders": []}


def test_the_seed_fourbar_is_a_crank_rocker_with_its_transmission_range(client):
    answer = client.post("/api/analyze", json=seed_fourbar(), headers=AUTH)
    assert answer.status_code == 200, answer.text
    found = answer.json()
    a, b, c, d = 20.0, 66.0, 56.0, 80.0
    # by hand: s + l = 20 + 80 = 100 < p + q = 66 + 56 = 122, the shortest is the crank
    assert found["grashof"]["name"] == "crank-rocker"

    def mu(theta: float) -> float:  # the law of cosines over the diagonal BD
        return math.acos((b * b + c * c - (a * a + d * d - 2 * a * d * math.cos(theta))) / (2 * b * c))
    low, high = math.degrees(mu(0.0)), math.degrees(mu(math.pi))
    assert (round(low, 2), round(high, 2)) == (58.23, 109.83)
    (loop,) = found["transmission"]
    assert math.degrees(loop["minimum"]) == pytest.approx(low, abs=1e-7)
    assert math.degrees(loop["maximum"]) == pytest.approx(high, abs=1e-7)
    assert found["reach"]["full_turn"] is True and found["reach"]["toggles"] == []
    (rocker,) = found["limits"]
    assert rocker["output"] == "theta_DC" and len(rocker["positions"]) == 2
    # the rocker's limits: crank and coupler in line, |AC| = b + a (extended) and b - a (folded)
    extended = math.pi - math.acos((c * c + d * d - (a + b) ** 2) / (2 * c * d))
    folded = math.pi - math.acos((c * c + d * d - (b - a) ** 2) / (2 * c * d))
    values = sorted(p["value"] for p in rocker["positions"])
    assert values == pytest.approx(sorted([extended, folded]), abs=1e-9)


def test_a_crank_that_cannot_turn_has_a_partial_range_with_toggles(client):
    drawing = seed_fourbar()
    # crank 40 with coupler 30, rocker 56, ground 80: s + l = 30 + 80 > 40 + 56: a triple rocker
    B = (40 * math.cos(math.radians(60)), 40 * math.sin(math.radians(60)))
    C = circles(B, 30.0, (80.0, 0.0), 56.0)
    drawing["joints"][1].update(x=B[0], y=B[1])
    drawing["joints"][2].update(x=C[0], y=C[1])
    found = client.post("/api/analyze", json=drawing, headers=AUTH).json()
    assert found["grashof"]["name"] == "triple-rocker"
    assert found["reach"]["full_turn"] is False and len(found["reach"]["toggles"]) >= 2
    # a toggle where crank and coupler are in line: |BD| = c + b = 86, by the law of cosines at A
    toggle = math.acos((40 ** 2 + 80 ** 2 - 86 ** 2) / (2 * 40 * 80))
    ends = [abs(t["at"]) for t in found["reach"]["toggles"]]
    assert min(abs(e - toggle) for e in ends) < 1e-9


def test_analysis_of_a_drawing_that_is_no_linkage_says_so(client):
    answer = client.post("/api/analyze", json={"joints": [], "links": []}, headers=AUTH)
    assert answer.status_code == 422 and "ground" in answer.json()["error"]
    assert client.post("/api/analyze", json=[1, 2], headers=AUTH).status_code == 400
