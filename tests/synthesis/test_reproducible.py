"""Seeded synthesis repeats bit for bit, however long the compiled backend's background build takes.

The default ``auto`` backend answers with NumPy while the compiled library builds, then with the library;
the two agree to rounding only.  A search that crossed the switch followed other rounding from then on, so
two runs of one seeded synthesis could give two designs.  Each run here starts from an empty cache (a
fresh build in the background, as a new user's first run has).
"""
import math

import numpy
import pytest

import symlink
from symlink.numeric import solver as solver_module
from symlink.numeric.cache import clear_memory
from symlink.numeric.compiled_library import wait_for_builds
from symlink.synthesis import design_fit

#: Five points of the seed 003 four-bar's coupler point (B + 30 along BC + 20 to its left), by circle intersection.
def _coupler_points() -> numpy.ndarray:
    a, b, c, d, u, v = 20.0, 66.0, 56.0, 80.0, 30.0, 20.0
    points = []
    for degrees in (0.0, 60.0, 120.0, 200.0, 280.0):
        theta = math.radians(degrees)
        bx, by = a * math.cos(theta), a * math.sin(theta)
        dx, dy = d - bx, -by  # from B to D
        w = math.hypot(dx, dy)
        along = (b * b - c * c + w * w) / (2 * w)
        across = math.sqrt(b * b - along * along)
        cx, cy = bx + (along * dx - across * dy) / w, by + (along * dy + across * dx) / w  # branch +1: C left of B->D
        ex, ey = (cx - bx) / b, (cy - by) / b
        points.append((bx + u * ex - v * ey, by + u * ey + v * ex))
    return numpy.array(points)


def _fresh(tmp_path, monkeypatch, name: str) -> None:
    wait_for_builds()
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / name))
    clear_memory()
    for memo in (solver_module.shared_solver, design_fit._solver, design_fit._newton_solver):
        memo.cache_clear()


def test_settled_means_one_backend_answers_every_later_call(tmp_path, monkeypatch):
    _fresh(tmp_path, monkeypatch, "cache")
    solver = solver_module.settled(symlink.Solver(symlink.fourbar(), ["rocker"]))
    backend = solver.backend
    answers = [solver(theta=numpy.linspace(0, 6, 50), a=20, b=66, c=56, d=80)["rocker"] for _ in range(3)]
    assert solver.backend == backend and all(numpy.array_equal(answers[0], other) for other in answers[1:])


@pytest.mark.parametrize("route", ["four-bar path", "any linkage's path"])
def test_two_seeded_runs_from_empty_caches_give_the_same_design_bit_for_bit(route, tmp_path, monkeypatch):
    targets = _coupler_points()

    def run(name: str):
        _fresh(tmp_path, monkeypatch, name)
        if route == "four-bar path":
            designs = symlink.synthesize_fourbar_path(targets, starts=4, designs=1, seed=7)
            return designs[0].values if hasattr(designs[0], "values") else designs[0]
        linkage = symlink.with_point(symlink.fourbar(), "B", symlink.fourbar().roles["coupler"])
        free = {"a": (5.0, 60.0), "b": (20.0, 120.0), "c": (20.0, 120.0), "d": (40.0, 120.0),
                "u": (-60.0, 60.0), "v": (-60.0, 60.0)}
        found = symlink.synthesize_path(linkage, "P", targets, free, starts=4, seed=7, evaluations=300)
        return found.values if hasattr(found, "values") else found

    first, second = run("first"), run("second")
    if isinstance(first, dict):
        assert first.keys() == second.keys()
        assert all(first[k] == second[k] or (math.isnan(first[k]) and math.isnan(second[k])) for k in first), \
            {k: (first[k], second[k]) for k in first if first[k] != second[k]}
    else:
        assert repr(first) == repr(second), (repr(first), repr(second))
