"""A linkage's placement from the disk cache (symlink.numeric.poses.cached_placement): where it puts the joints, checked
by hand (the four-bar's circles) and by rigid bodies (Newton's method on Stephenson II); a warm one derives nothing."""
from __future__ import annotations

import itertools
import math

import numpy
import pytest

from symlink.mechanism.catalog import EXAMPLE_VALUES, fourbar, stephenson2
from symlink.numeric import cache
from symlink.numeric.poses import Geometry, cached_placement
from references import fourbar_joint_c


@pytest.fixture
def private_cache(tmp_path, monkeypatch):
    """A disk cache of the test's own, and a memory cache as in a new process."""
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "cache"))
    cache.clear_memory()
    yield tmp_path / "cache"
    cache.clear_memory()


def _keys(name: str):
    return lambda outputs: cache.catalog_key(name, outputs, "placement-test/1")


def test_a_cached_placement_puts_the_four_bars_joints_where_the_circles_meet(private_cache):
    """The four-bar 60, 30, 50, 40 reaches crank angles within acos(-1/4) = 104.48 deg of 0: C where the circles
    meet there, NaN (and not assembled) at 150 deg."""
    placement = cached_placement(_keys("fourbar")(["placement"]), _keys("fourbar"), fourbar)
    a, b, c, d = 60.0, 30.0, 50.0, 40.0
    angles = numpy.radians([0.0, 45.0, 100.0, 150.0, -60.0])
    poses = placement.poses(dict(a=a, b=b, c=c, d=d), {"theta": angles})
    for k, theta in enumerate(angles):
        joint = fourbar_joint_c(float(theta), a, b, c, d)
        if joint is None:
            assert not poses.assembled[k] and numpy.isnan(poses.positions["C"][k])
            continue
        assert poses.assembled[k]
        assert poses.positions["C"][k] == pytest.approx(complex(*joint), abs=1e-12 * d)
        assert poses.positions["B"][k] == pytest.approx(a * complex(math.cos(theta), math.sin(theta)), abs=1e-12 * d)
        assert poses.positions["D"][k] == pytest.approx(d)
    assert list(poses.assembled) == [True, True, True, False, True]


def test_a_warm_placement_builds_no_linkage(private_cache):
    """The second process (the memory cache cleared) takes placement and solver from the disk: the linkage is never
    built, and the poses are those of the first."""
    built = []

    def linkage():
        built.append(1)
        return fourbar()

    values, sweep = EXAMPLE_VALUES["fourbar"], {"theta": numpy.linspace(0.0, 6.0, 7)}
    first = cached_placement(_keys("fourbar")(["placement"]), _keys("fourbar"), linkage).poses(values, sweep)
    assert built  # derived once
    cache.clear_memory()
    built.clear()
    again = cached_placement(_keys("fourbar")(["placement"]), _keys("fourbar"), linkage).poses(values, sweep)
    assert not built
    for name, place in first.positions.items():
        assert numpy.array_equal(place, again.positions[name], equal_nan=True)


def test_newtons_method_keeps_stephenson_iis_bodies_rigid(private_cache):
    """Without a closed form the cached placement follows Newton's method: along a sweep, the distance between any two
    joints of one body stays what it is at the start (each body is rigid), and every joint moves."""
    placement = cached_placement(_keys("stephenson2")(["placement"]), _keys("stephenson2"), stephenson2)
    assert not placement.closed_form
    angles = numpy.radians(numpy.linspace(0.0, 30.0, 7))
    poses = placement.poses(EXAMPLE_VALUES["stephenson2"], {"theta": angles})
    assert poses.assembled.all()
    for _, corners in placement.facts["bodies"]:
        for first, second in itertools.combinations(corners, 2):
            distance = numpy.abs(poses.positions[first] - poses.positions[second])
            assert distance == pytest.approx(numpy.full(len(angles), distance[0]), rel=1e-9)
    assert numpy.abs(poses.positions["B"] - poses.positions["B"][0]).max() > 0.1


def test_a_cached_placement_places_as_the_linkages_geometry_does(private_cache):
    """The placement from the cache and the one made from the linkage read the same facts."""
    placement = cached_placement(_keys("fourbar")(["placement"]), _keys("fourbar"), fourbar)
    assert placement.facts == Geometry(fourbar()).facts
