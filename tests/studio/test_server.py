"""The studio's server: its guard (token, Host, Origin, paths) and its API, through Starlette's TestClient."""
from __future__ import annotations

import io
import json
import math
import zipfile

import pytest

from conftest import PORT, TOKEN  # noqa: F401 - tests/ is on the path; this is tests/studio/conftest.py
from symlink.cli import main

AUTH = {"X-Symlink-Token": TOKEN}


# --- the guard ------------------------------------------------------------------------------------

def test_the_page_needs_the_token(client):
    assert client.get("/").status_code == 403
    assert client.get("/?token=wrong").status_code == 403
    assert client.post("/api/structure", json={}).status_code == 403
    assert client.post("/api/structure", json={}, headers={"X-Symlink-Token": "wrong"}).status_code == 403


def test_the_page_with_the_token_sets_the_cookie_that_api_calls_then_carry(client, hoeken):
    page = client.get(f"/?token={TOKEN}")
    assert page.status_code == 200 and "<svg id=\"canvas\"" in page.text
    assert "samesite=strict" in page.headers["set-cookie"].lower()
    assert "httponly" in page.headers["set-cookie"].lower()
    answer = client.post("/api/structure", json=hoeken)  # the cookie alone
    assert answer.status_code == 200


def test_a_foreign_host_is_refused(client):
    for host in ("evil.example:%d" % PORT, "127.0.0.1:1", "localhost", "127.0.0.1"):
        assert client.get(f"/?token={TOKEN}", headers={"Host": host}).status_code == 403, host
    assert client.get(f"/?token={TOKEN}", headers={"Host": f"localhost:{PORT}"}).status_code == 200


def test_a_foreign_origin_is_refused(client, hoeken):
    answer = client.post("/api/structure", json=hoeken, headers={**AUTH, "Origin": "http://evil.example"})
    assert answer.status_code == 403
    answer = client.post("/api/structure", json=hoeken, headers={**AUTH, "Origin": f"http://127.0.0.1:{PORT + 1}"})
    assert answer.status_code == 403
    answer = client.post("/api/structure", json=hoeken, headers={**AUTH, "Origin": f"http://127.0.0.1:{PORT}"})
    assert answer.status_code == 200


def test_paths_outside_the_app_are_not_found(client):
    for path in ("/nothing", "/static/nothing.js", "/static/../server.py", "/static/%2e%2e/server.py",
                 "/static/katex", "/api/nothing"):
        answer = client.get(path, headers=AUTH)
        assert answer.status_code == 404, path
        assert "Traceback" not in answer.text
    assert client.get("/static/studio.js", headers=AUTH).status_code == 200
    assert client.get("/static/katex/fonts/KaTeX_Main-Regular.woff2", headers=AUTH).status_code == 200


# --- the API ----------------------------------------------------------------------------------------

def test_the_structure_of_hoekens_four_bar(client, hoeken):
    answer = client.post("/api/structure", json=hoeken, headers=AUTH)
    assert answer.status_code == 200
    found = answer.json()
    # Gruebler by hand: 4 links, 4 pins: 3 (4 - 1) - 2 * 4 = 1.
    assert found["mobility"] == {"dof": 1, "links": 4, "revolute": 4, "prismatic": 0}
    assert found["closed_form"] is True and found["loops"] == ["ABCD"]
    assert found["inputs"] == ["theta_AB"] and found["unknowns"] == ["theta_BC", "theta_DC"]
    assert found["parameters"]["BP"] == pytest.approx(5.0) and found["parameters"]["AD"] == pytest.approx(2.0)


def test_a_rigid_triangle_says_it_is_over_constrained(client):
    triangle = {"joints": [{"name": "A", "x": 0, "y": 0, "ground": True}, {"name": "B", "x": 1, "y": 1},
                           {"name": "C", "x": 2, "y": 0, "ground": True}],
                "links": [["A", "B"], ["B", "C"]], "driver": {"joint": "A"}}
    answer = client.post("/api/structure", json=triangle, headers=AUTH)
    assert answer.status_code == 422
    found = answer.json()
    # 3 links, 3 pins: 3 (3 - 1) - 2 * 3 = 0, and a driver on top.
    assert found["mobility"]["dof"] == 0
    assert "over-constrained" in found["error"] and "ground, link1, link2" in found["error"]
    undriven = client.post("/api/structure", json={**triangle, "driver": None}, headers=AUTH).json()
    assert "mobility 0" in undriven["error"] or "over-constrained" in undriven["error"]


def test_a_five_bar_with_one_driver_says_it_is_under_constrained(client):
    five = {"joints": [{"name": "A", "x": 0, "y": 0, "ground": True}, {"name": "B", "x": 0, "y": 1},
                       {"name": "C", "x": 1.5, "y": 2}, {"name": "D", "x": 3, "y": 1},
                       {"name": "E", "x": 3, "y": 0, "ground": True}],
            "links": [["A", "B"], ["B", "C"], ["C", "D"], ["D", "E"]], "driver": {"joint": "A"}}
    answer = client.post("/api/structure", json=five, headers=AUTH)
    assert answer.status_code == 422
    found = answer.json()
    # 5 links, 5 pins: 3 (5 - 1) - 2 * 5 = 2, one driver.
    assert found["mobility"]["dof"] == 2
    assert "under-constrained" in found["error"] and "mobility 2" in found["error"]


def test_a_link_that_hangs_by_one_joint_is_named(client, hoeken):
    hoeken["joints"].append({"name": "F", "x": 5, "y": 3})
    hoeken["links"].append(["P", "F"])
    found = client.post("/api/structure", json=hoeken, headers=AUTH).json()
    # 5 links, 5 pins: mobility 2 with one driver; the fourth link (P-F) is on no loop.
    assert found["mobility"]["dof"] == 2
    assert "link link4 (P-F) is on no loop" in found["error"]


def test_a_drawing_without_a_driver_or_ground_says_what_to_do(client, hoeken):
    found = client.post("/api/structure", json={**hoeken, "driver": None}, headers=AUTH).json()
    assert "no driver" in found["error"] and found["mobility"]["dof"] == 1
    flat = [{**j, "ground": False} for j in hoeken["joints"]]
    found = client.post("/api/structure", json={**hoeken, "joints": flat}, headers=AUTH).json()
    assert "ground" in found["error"]


@pytest.mark.parametrize("body, words", [
    (b"{not json", "not JSON"),
    (b"\xff\xfe", "not JSON"),
    (b"[1, 2]", "JSON object"),
    (json.dumps({"joints": [{"name": "__import__('os')", "x": 0, "y": 0}], "links": []}).encode(), "name"),
    (json.dumps({"joints": [{"name": "A", "x": "1e3", "y": 0}], "links": []}).encode(), "number"),
    (json.dumps({"joints": [{"name": "A", "x": 0, "y": 0}], "links": [["A", "Z"]]}).encode(), "no joint"),
    (json.dumps({"joints": [], "links": [], "shell": 1}).encode(), "no entry"),
    (json.dumps({"joints": [{"name": f"J{k}", "x": k, "y": 0} for k in range(30)],
                 "links": [[f"J{k}", f"J{k + 1}"] for k in range(29)]}).encode(), "at most 24"),
])
def test_bad_requests_get_a_clean_message(client, body, words):
    answer = client.post("/api/structure", content=body, headers={**AUTH, "Content-Type": "application/json"})
    assert answer.status_code in (400, 422)
    found = answer.json()
    assert words in found["error"] and "Traceback" not in found["error"]


def test_a_body_too_large_is_refused(client):
    answer = client.post("/api/structure", content=b" " * (3 << 20), headers=AUTH)
    assert answer.status_code == 400 and "larger than" in answer.json()["error"]


def test_the_derivation_is_the_linkages_own_latex(client, hoeken):
    from symlink.mechanism.joints import from_joints
    from conftest import HOEKEN_COORDINATES, HOEKEN_LINKS
    found = client.post("/api/derive", json=hoeken, headers=AUTH).json()
    linkage = from_joints(HOEKEN_LINKS, HOEKEN_COORDINATES, driver="A", name="hoeken").linkage
    assert "$" + found["equations"] + "$" == linkage._repr_latex_()
    assert r"\dot" in found["velocities"] and r"\ddot" in found["accelerations"]
    assert found["loops"] == ["ABCD"]


def test_the_seed_papers_forms_are_there_on_request(client, hoeken):
    """Freudenstein's constants and the half-angle quadratic, in the linkage's own (Greek) symbols."""
    import sympy as sp

    from symlink.mechanism.joints import from_joints
    from symlink.symbolic.seed_forms import seed_form_rows
    from conftest import HOEKEN_COORDINATES, HOEKEN_LINKS
    found = client.post("/api/derive", json=hoeken, headers=AUTH).json()
    forms = {entry["form"]: entry for entry in found["forms"]}
    assert set(forms) == {"complex", "freudenstein", "half-angle"}
    linkage = from_joints(HOEKEN_LINKS, HOEKEN_COORDINATES, driver="A", name="hoeken").linkage
    unknown = sp.latex(linkage.unknowns[0])  # \theta_{BC}: a Greek letter as Greek
    assert f"K_{{{unknown},1}}" in forms["freudenstein"]["latex"]
    assert "\\tan" in forms["half-angle"]["latex"] and "- 4 A_" in forms["half-angle"]["latex"]  # B^2 - 4AC
    assert len(seed_form_rows(linkage, "freudenstein")) >= 4


@pytest.mark.parametrize("source", ["fourbar", "atlas:watt-ii", "slider-crank"])
def test_open_a_catalog_or_atlas_linkage_gives_a_drawing_that_moves(client, source):
    drawing = client.post("/api/open", json={"source": source}, headers=AUTH)
    assert drawing.status_code == 200
    found = client.post("/api/structure", json=drawing.json(), headers=AUTH).json()
    assert found["mobility"]["dof"] == 1


def test_open_a_pyslvs_expression_and_refuse_nonsense(client):
    text = ("M[J[R, color[Green], P[0.0, 0.0], L[ground, L1]], J[R, color[Green], P[0, 20], L[L1, L2]],"
            " J[R, color[Green], P[60, 50], L[L2, L3]], J[R, color[Green], P[80.0, 0.0], L[ground, L3]]]")
    drawing = client.post("/api/open", json={"source": text}, headers=AUTH).json()
    assert [j["name"] for j in drawing["joints"]] == ["A", "B", "C", "D"]
    assert drawing["driver"]["joint"] == "A"
    for source in ("no-such-linkage", "M[J[", "{\"joints\": 3}", "name = 1\n[vectors]\n", 42, ""):
        answer = client.post("/api/open", json={"source": source}, headers=AUTH)
        assert answer.status_code in (400, 422), source
        assert answer.json()["error"] and "Traceback" not in answer.json()["error"]


def _files(answer) -> dict[str, bytes]:
    if answer.headers["content-type"] == "application/zip":
        with zipfile.ZipFile(io.BytesIO(answer.content)) as archive:
            return {name: archive.read(name) for name in archive.namelist()}
    name = answer.headers["content-disposition"].split('filename="')[1].rstrip('"')
    return {name: answer.content}


@pytest.mark.parametrize("fmt", ["numpy", "c", "latex", "octave", "javascript"])
def test_export_gives_the_bytes_the_command_line_writes(client, hoeken, tmp_path, fmt, capsys):
    answer = client.post(f"/api/export?format={fmt}", json=hoeken, headers=AUTH)
    assert answer.status_code == 200
    linkage_file = client.post("/api/export?format=joints", json=hoeken, headers=AUTH)
    (tmp_path / "hoeken.toml").write_bytes(linkage_file.content)
    assert main(["export", str(tmp_path / "hoeken.toml"), "--to", fmt, "--out", str(tmp_path / "out")]) == 0
    written = {path.name: path.read_bytes() for path in (tmp_path / "out").iterdir()}
    assert _files(answer) == written and written


def test_export_of_a_linkage_file_reads_back_to_the_same_drawing(client, hoeken):
    text = client.post("/api/export?format=joints", json=hoeken, headers=AUTH).text
    assert '[links]' in text and 'P = [4.0, 4.0]' in text
    drawing = client.post("/api/open", json={"source": text}, headers=AUTH).json()
    assert drawing["links"] == hoeken["links"]
    assert {j["name"]: (j["x"], j["y"]) for j in drawing["joints"]} == {"A": (0, 0), "B": (0, 1), "C": (2, 2.5),
                                                                        "D": (2, 0), "P": (4, 4)}
    pylinkage = client.post("/api/export?format=pylinkage", json=hoeken, headers=AUTH)
    assert {j["id"]: j["type"] for j in pylinkage.json()["joints"]} == {
        "A": "ground", "B": "revolute", "C": "revolute", "D": "ground", "P": "tracker"}
    reopened = client.post("/api/open", json={"source": pylinkage.text}, headers=AUTH).json()
    assert sorted(map(sorted, reopened["links"])) == [["A", "B"], ["B", "C", "P"], ["C", "D"]]
    assert {j["name"]: (j["x"], j["y"]) for j in reopened["joints"]} == {
        "A": (0, 0), "B": (0, 1), "C": (2, 2.5), "D": (2, 0), "P": (4, 4)}


def test_export_of_the_vector_linkage_file_reads_back_as_a_linkage(client, hoeken):
    from symlink import linkage_from_text
    text = client.post("/api/export?format=linkage", json=hoeken, headers=AUTH).text
    found = linkage_from_text(text)
    assert [q.name for q in found.linkage.inputs] == ["theta_AB"]
    assert [q.name for q in found.linkage.unknowns] == ["theta_BC", "theta_DC"]
    assert found.defaults["BP"] == pytest.approx(5.0) and found.defaults["theta_AB"] == pytest.approx(math.pi / 2)


def test_an_unknown_export_format_is_a_message(client, hoeken):
    answer = client.post("/api/export?format=exe", json=hoeken, headers=AUTH)
    assert answer.status_code == 422 and "no export format 'exe'" in answer.json()["error"]


def test_the_self_contained_page_holds_everything(client, hoeken):
    answer = client.post("/api/export?format=html", json=hoeken, headers=AUTH)
    assert answer.status_code == 200
    page = answer.text
    assert "window.SYMLINK_EMBEDDED" in page and "katex" in page
    assert 'src="static/' not in page and 'href="static/' not in page  # nothing left to fetch
    assert "data:font/woff2;base64," in page
    assert len(answer.content) < 3 << 20
