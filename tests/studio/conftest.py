"""The studio's fixtures: Hoeken's four-bar as a drawing, a guarded app for Starlette's TestClient."""
from __future__ import annotations

import copy

import pytest

#: Hoeken's straight-line linkage as docs/howto/joints.md draws it: crank AB = 1, coupler BC = 2.5 carried on
#: to P at BP = 5, rocker DC = 2.5, ground AD = 2, the crank straight up.
HOEKEN = {
    "name": "hoeken",
    "joints": [{"name": "A", "x": 0, "y": 0, "ground": True}, {"name": "B", "x": 0, "y": 1},
               {"name": "C", "x": 2, "y": 2.5}, {"name": "D", "x": 2, "y": 0, "ground": True},
               {"name": "P", "x": 4, "y": 4}],
    "links": [["A", "B"], ["B", "C", "P"], ["D", "C"]],
    "driver": {"joint": "A"},
    "sliders": [],
}
#: Its from_joints arguments, written out (the expected values of the description).
HOEKEN_LINKS = {"ground": ["A", "D"], "link1": ["A", "B"], "link2": ["B", "C", "P"], "link3": ["D", "C"]}
HOEKEN_COORDINATES = {"A": (0, 0), "B": (0, 1), "C": (2, 2.5), "D": (2, 0), "P": (4, 4)}

PORT = 38123
TOKEN = "test-token-not-secret"


@pytest.fixture
def hoeken() -> dict:
    return copy.deepcopy(HOEKEN)


@pytest.fixture
def client():
    """A TestClient of the studio app for 127.0.0.1:PORT (its token sent as the header)."""
    pytest.importorskip("starlette", reason="the studio's server needs the studio extra (starlette)")
    pytest.importorskip("httpx", reason="Starlette's TestClient needs httpx (the test extra)")
    import warnings

    from symlink.studio.server import create_app
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # newer Starlette warns that it prefers httpx2 for its TestClient
        from starlette.testclient import TestClient
        with TestClient(create_app(PORT, TOKEN), base_url=f"http://127.0.0.1:{PORT}") as test_client:
            yield test_client
