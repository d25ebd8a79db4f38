"""The hand-written C baselines of the benchmark: right answers, both branches, unreachable inputs flagged."""
from __future__ import annotations

import numpy
import pytest

from references import SEED003_LINKAGE, mp_fourbar, seed003_positions
from symlink.numeric import cache, compiled
from symlink.numeric.compiled import CompilerUnavailable, compiled_solver
from benchmarks.hand_c import hand_positions
from symlink.io.scene import catalog_linkage


@pytest.fixture(scope="module", autouse=True)
def module_cache(tmp_path_factory):
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("SYMLINK_CACHE", str(tmp_path_factory.mktemp("cache")))
        compiled._loaded.clear()
        cache.clear_memory()
        try:
            hand_positions(numpy.zeros(1), 1.0, 1.0, 1.0, 1.0)
        except CompilerUnavailable as error:
            pytest.skip(f"no working C compiler, the hand-written C is not tested: {error}")
        yield
    compiled._loaded.clear()
    cache.clear_memory()


@pytest.mark.parametrize("formula", ["atan2", "halfangle"])
@pytest.mark.parametrize("branch", [1, -1])
def test_hand_c_matches_the_50_digit_reference(formula, branch):
    a, b, c, d = (SEED003_LINKAGE[k] for k in "abcd")
    theta = numpy.radians(numpy.arange(-179.0, 180.0, 7.0))
    result = hand_positions(theta, a, b, c, d, branch, formula)
    assert result["assembled"].all()
    for angle, coupler, rocker in zip(theta, result["coupler"], result["rocker"]):
        reference = mp_fourbar(a, b, c, d, float(angle), branch)
        for got, key in ((coupler, "beta"), (rocker, "phi")):
            error = numpy.angle(numpy.exp(1j * (got - float(reference[key]))))
            assert abs(error) < 1e-12, (formula, angle, key)


def test_half_angle_c_is_the_seed_003_formula():
    a, b, c, d = (SEED003_LINKAGE[k] for k in "abcd")
    theta = numpy.linspace(-3.0, 3.0, 101)
    for branch in (1, -1):
        coupler, rocker = seed003_positions(a, b, c, d, theta, branch)
        result = hand_positions(theta, a, b, c, d, branch, "halfangle")
        numpy.testing.assert_allclose(numpy.cos(result["rocker"] - rocker), 1.0, rtol=0, atol=1e-24)
        numpy.testing.assert_allclose(numpy.cos(result["coupler"] - coupler), 1.0, rtol=0, atol=1e-24)


def test_unreachable_angles_are_flagged_by_both():
    theta = numpy.array([numpy.pi / 2, numpy.pi])  # a = 50, b = 30, c = 40, d = 45: B is 95 from D at pi
    for formula in ("atan2", "halfangle"):
        result = hand_positions(theta, 50.0, 30.0, 40.0, 45.0, 1, formula)
        assert result["assembled"].tolist() == [True, False]
        assert numpy.isnan(result["rocker"][1]) and numpy.isfinite(result["rocker"][0])


def test_hand_c_and_the_generated_c_agree():
    solver = compiled_solver(catalog_linkage("fourbar"), ["coupler", "rocker"])
    theta = numpy.linspace(-numpy.pi, numpy.pi, 1001)
    for branch in (1, -1):
        generated = solver(theta=theta, a=20.0, b=66.0, c=56.0, d=80.0, branch=branch)
        hand = hand_positions(theta, 20.0, 66.0, 56.0, 80.0, branch)
        for key in ("coupler", "rocker"):
            assert numpy.max(numpy.abs(numpy.angle(numpy.exp(1j * (generated[key] - hand[key]))))) < 1e-13


def test_unknown_formula_is_refused():
    with pytest.raises(ValueError, match="formula must be"):
        hand_positions(numpy.zeros(2), 1.0, 1.0, 1.0, 1.0, 1, "newton")


@pytest.mark.parametrize("branch", [1, -1])
def test_hand_c_full_kinematics_match_the_50_digit_reference(branch):
    from benchmarks.hand_c import hand_everything
    a, b, c, d = (SEED003_LINKAGE[k] for k in "abcd")
    theta = numpy.radians(numpy.arange(-179.0, 180.0, 11.0))
    result = hand_everything(theta, a, b, c, d, branch, 10.5, 2.0)
    assert result["assembled"].all() and not result["singular"].any()  # a crank-rocker: never at a toggle
    keys = {"coupler": "beta", "rocker": "phi", "coupler_speed": "beta_speed", "rocker_speed": "phi_speed",
            "coupler_accel": "beta_accel", "rocker_accel": "phi_accel"}
    for i, angle in enumerate(theta):
        reference = mp_fourbar(a, b, c, d, float(angle), branch, crank_speed=10.5, crank_accel=2.0)
        for mine, theirs in keys.items():
            exact = float(reference[theirs])
            if "_" not in mine:
                assert abs(numpy.angle(numpy.exp(1j * (result[mine][i] - exact)))) < 1e-12, (angle, mine)
            else:
                assert result[mine][i] == pytest.approx(exact, rel=1e-10, abs=1e-9), (angle, mine)


def test_hand_c_flags_a_toggle_singular_as_the_generated_code_does():
    # a = 1, b = 2, c = 1, d = 2 at theta = 0: W = a - d = -1, so w = 1 = b - c: a toggle, where Heron's
    # product ((b + c)^2 - w^2)(w^2 - (b - c)^2) = 8 * 0 is exactly zero (by hand): assembled, rates singular
    from benchmarks.hand_c import hand_everything
    result = hand_everything(numpy.array([0.0, 1.0]), 1.0, 2.0, 1.0, 2.0, 1, 1.0, 0.0)
    assert result["assembled"].tolist() == [True, True]
    assert result["singular"].tolist() == [True, False]
