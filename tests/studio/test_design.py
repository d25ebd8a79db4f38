"""The studio's "Analyse and design" API (/api/analyze, /api/synthesize) through Starlette's TestClient."""
from __future__ import annotations

import math

import pytest

from conftest import TOKEN  # tests/studio is on the path: its conftest

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


# --- path synthesis -----------------------------------------------------------------------------------

#: The drawing the synthesis starts from: Hoeken's four-bar with its coupler point E (a ternary coupler).
START = {"name": "hoeken", "joints": [{"name": "A", "x": 0, "y": 0, "ground": True}, {"name": "B", "x": 0, "y": 1},
                                      {"name": "C", "x": 2, "y": 2.5}, {"name": "D", "x": 2, "y": 0, "ground": True},
                                      {"name": "E", "x": 4, "y": 4}],
         "links": [["A", "B"], ["B", "C", "E"], ["D", "C"]], "driver": {"joint": "A"}, "sliders": []}


def hand_targets(angles_deg=(60, 100, 140, 180, 220)) -> list[list[float]]:
    """The coupler point of a hand four-bar (crank 1.1 from (0.5, -0.3), coupler 2.4, rocker 2.6, ground 2.1 at
    0.2 rad; E at 4.7 from B, 0.3 rad off BC) at five crank angles: circle intersections by hand."""
    A = (0.5, -0.3)
    D = (A[0] + 2.1 * math.cos(0.2), A[1] + 2.1 * math.sin(0.2))
    points = []
    for angle in angles_deg:
        t = math.radians(angle)
        B = (A[0] + 1.1 * math.cos(t), A[1] + 1.1 * math.sin(t))
        C = circles(B, 2.4, D, 2.6)
        heading = math.atan2(C[1] - B[1], C[0] - B[0]) + 0.3
        points.append([B[0] + 4.7 * math.cos(heading), B[1] + 4.7 * math.sin(heading)])
    return points


def path_distances(drawing: dict, point: str, inputs: list[float], targets: list[list[float]]) -> list[float]:
    """Distances from each target to the point of the drawing's own linkage (from_joints, Geometry) at its input."""
    import numpy

    from symlink.mechanism.joints import Slider, from_joints
    from symlink.numeric.poses import Geometry
    sliders = {s["joint"]: Slider("ground", s["angle"]) for s in drawing.get("sliders", [])}
    ground = [j["name"] for j in drawing["joints"] if j.get("ground")] + list(sliders)
    links = {"ground": ground, **{f"link{k + 1}": held for k, held in enumerate(drawing["links"])}}
    made = from_joints(links, {j["name"]: (j["x"], j["y"]) for j in drawing["joints"]},
                       driver=drawing["driver"]["joint"], joints=sliders or None)
    name = made.linkage.inputs[0].name
    values = {k: v for k, v in made.defaults.items() if k != name}
    poses = Geometry(made.linkage).poses(values, {name: numpy.asarray(inputs)})
    assert poses.assembled.all()
    return [abs(complex(poses.positions[point][k]) - complex(*target)) for k, target in enumerate(targets)]


def wait(client, key: str, limit: float = 300.0) -> dict:
    import time
    deadline = time.monotonic() + limit
    while True:
        found = client.get(f"/api/synthesize/{key}", headers=AUTH).json()
        if found["status"] not in ("starting", "deriving", "searching"):
            return found
        assert time.monotonic() < deadline, f"the synthesis did not end: {found}"
        time.sleep(0.25)


def test_a_synthesis_puts_the_coupler_point_through_the_targets(client):
    targets = hand_targets()
    size = max(max(t[0] for t in targets) - min(t[0] for t in targets),
               max(t[1] for t in targets) - min(t[1] for t in targets))
    answer = client.post("/api/synthesize", json={"drawing": START, "point": "E", "targets": targets, "starts": 4},
                         headers=AUTH)
    assert answer.status_code == 202, answer.text
    found = wait(client, answer.json()["id"])
    assert found["status"] == "done", found
    result = found["result"]
    assert result["assembled"] is True and result["exact"] is True
    distances = path_distances(result["drawing"], "E", result["inputs"], targets)
    assert max(distances) < 1e-6 * size
    # the drawing is the design at the first target: E drawn there
    (E,) = [j for j in result["drawing"]["joints"] if j["name"] == "E"]
    assert math.dist((E["x"], E["y"]), targets[0]) < 1e-6 * size


def test_a_slider_crank_with_a_coupler_point_is_designed_through_points_too(client):
    """Any drawn linkage: a slider-crank's coupler point E through five points of a hand slider-crank (crank 1.2
    about (0.3, 0.2), coupler 3.5 to a slider on the line y = 0.6, E at 2 from B turned 0.5 rad from BC; the
    new drawing's slider guide turned with the placement, and its own linkage through the points)."""
    drawing = {"name": "sc", "joints": [{"name": "A", "x": 0, "y": 0, "ground": True}, {"name": "B", "x": 0.5, "y": 1},
                                        {"name": "C", "x": 3, "y": 0}, {"name": "E", "x": 2, "y": 1.5}],
               "links": [["A", "B"], ["B", "C", "E"]], "driver": {"joint": "A"},
               "sliders": [{"joint": "C", "guide": "ground", "angle": 0.0}]}
    targets = []
    for t in (0.3, 0.6, 0.9, 1.2, 1.5):
        B = (0.3 + 1.2 * math.cos(t), 0.2 + 1.2 * math.sin(t))
        C = (B[0] + math.sqrt(3.5 ** 2 - (0.6 - B[1]) ** 2), 0.6)
        heading = math.atan2(C[1] - B[1], C[0] - B[0]) + 0.5
        targets.append([B[0] + 2 * math.cos(heading), B[1] + 2 * math.sin(heading)])
    answer = client.post("/api/synthesize", json={"drawing": drawing, "point": "E", "targets": targets, "starts": 4},
                         headers=AUTH)
    found = wait(client, answer.json()["id"])
    assert found["status"] == "done" and found["result"]["exact"] is True, found
    result = found["result"]
    size = max(max(p[0] for p in targets) - min(p[0] for p in targets),
               max(p[1] for p in targets) - min(p[1] for p in targets))
    assert max(path_distances(result["drawing"], "E", result["inputs"], targets)) < 1e-6 * size


def test_a_synthesis_can_be_cancelled(client):
    answer = client.post("/api/synthesize", json={"drawing": START, "point": "E", "targets": hand_targets(),
                                                  "starts": 64, "evaluations": 5000}, headers=AUTH)
    key = answer.json()["id"]
    again = client.post("/api/synthesize", json={"drawing": START, "point": "E", "targets": hand_targets()},
                        headers=AUTH)
    assert again.status_code == 409 and "already running" in again.json()["error"]
    stopped = client.delete(f"/api/synthesize/{key}", headers=AUTH)
    assert stopped.status_code == 200 and stopped.json()["status"] == "cancelled"
    assert client.get(f"/api/synthesize/{key}", headers=AUTH).json()["status"] == "cancelled"
    assert client.app.state.jobs.wait(key, 30)  # its watcher terminated and reaped the process
    assert client.get("/api/synthesize/nothing", headers=AUTH).status_code == 404


@pytest.mark.parametrize("change, message", [
    ({"targets": [[0, 0], [1, 1]]}, "3 to 40 target points"),
    ({"targets": [[0, 0]] * 41}, "3 to 40 target points"),
    ({"targets": [[0, 0], [1, "x"], [2, 2]]}, "targets[1] must be [x, y]"),
    ({"targets": [[1, 1], [1, 1], [1, 1]]}, "all one point"),
    ({"targets": [[0, 0], [1, 0.5], [0, 0]]}, "target points 1 and 3 are the same point"),  # not one after the other
    ({"starts": 100000}, "starts is a whole number from 1 to 64"),
    ({"evaluations": 10 ** 9}, "evaluations is a whole number from 10 to 5000"),
    ({"point": "A"}, "on the ground"),
    ({"point": "Z"}, "point must name a joint"),
    ({"point": "__import__('os')"}, "point must name a joint"),
])
def test_a_synthesis_request_out_of_bounds_is_refused_with_a_message(client, change, message):
    request = {"drawing": START, "point": "E", "targets": [[0, 0], [1, 0.5], [2, 0.7]], **change}
    answer = client.post("/api/synthesize", json=request, headers=AUTH)
    assert answer.status_code == 422
    assert message in answer.json()["error"]
    assert client.app.state.jobs.jobs == {}  # no process was started


def test_a_synthesis_request_with_a_huge_integer_is_refused_in_one_line():
    """From Python (a notebook), not JSON: an integer too large for a float is a ValueError, never OverflowError."""
    from symlink.studio.design import synthesis_request
    with pytest.raises(ValueError, match=r"targets\[1\] must be \[x, y\]"):
        synthesis_request({"drawing": START, "point": "E", "targets": [[0, 0], [1, 10 ** 400], [2, 2]]})


# --- a tolerance band ---------------------------------------------------------------------------------

def test_the_tolerance_band_of_the_crank_pin_and_the_rocker_pin(client):
    """Every length ± 0.01: the crank pin B moves across its circle by AB's band alone (A is exact); the rocker
    pin C across its circle about D by DC's band plus AD's, which moves D along x: 0.01 (1 + |cos phi|), phi
    the direction of DC (circle intersections by hand)."""
    band = 0.01
    found_b = client.post("/api/tolerance", json={"drawing": START, "point": "B", "band": band}, headers=AUTH).json()
    assert found_b["dimensions"] == ["AB", "BC", "DC", "AD", "BE"]
    assert len(found_b["widths"]) == 361 and all(w == pytest.approx(band, rel=1e-6) for w in found_b["widths"])
    found_c = client.post("/api/tolerance", json={"drawing": START, "point": "C", "band": band}, headers=AUTH).json()
    for theta, width, inner, outer in zip(found_c["inputs"], found_c["widths"], found_c["inner"], found_c["outer"]):
        B = (math.cos(theta), math.sin(theta))
        C = circles(B, 2.5, (2.0, 0.0), 2.5)  # the drawn assembly: C left of B -> D (a crank-rocker keeps it)
        phi = math.atan2(C[1], C[0] - 2.0)
        assert width == pytest.approx(band * (1 + abs(math.cos(phi))), rel=1e-6), theta
        assert math.dist(inner, outer) == pytest.approx(2 * width, rel=1e-9)


def test_a_tolerance_band_out_of_bounds_is_refused(client):
    for band, message in ((0, "above 0"), (5.0, "a tenth of the drawing"), ("0.1", "above 0")):
        answer = client.post("/api/tolerance", json={"drawing": START, "point": "E", "band": band}, headers=AUTH)
        assert answer.status_code == 422 and message in answer.json()["error"]


def test_a_job_that_runs_past_its_time_limit_is_stopped_with_a_message():
    from symlink.studio.jobs import Jobs
    jobs = Jobs(time_limit=0.5)  # far less than a fresh interpreter needs to import symlink and derive
    key = jobs.start("synthesis", {"drawing": START, "point": "E", "targets": hand_targets(), "starts": 64})
    # The watcher marks the job failed, then terminates (and if need be kills) and reaps its process.  The test
    # waits on the watcher, never joins the process itself: two threads reaping one child race for its status.
    assert jobs.wait(key, 60)
    found = jobs.status(key)
    assert found["status"] == "failed" and "stopped after 0.5 s" in found["error"]
