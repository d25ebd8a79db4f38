"""Scenes derive, generate and evaluate exactly what their outputs need."""
import ast

import numpy
import pytest
from hypothesis import given, settings, strategies as st

from cache_fixture import empty_cache  # noqa: F401 - a fixture
from references import mp_fourbar
from symlink.mechanism.catalog import fourbar
from symlink.io.scene import Scene, angle_outputs, catalog_linkage
from symlink.symbolic.vectors import acceleration, rate

SEED003 = dict(a=20.0, b=66.0, c=56.0, d=80.0)
ANGLES = numpy.radians([0.0, 40.0, 135.0, 250.0])


pytestmark = pytest.mark.usefixtures("empty_cache")  # every test derives from scratch


def assignments(source: str) -> list[str]:
    """Names assigned in the generated function, in order."""
    function = next(node for node in ast.parse(source).body
                    if isinstance(node, ast.FunctionDef) and node.name == "_solve_block")
    return [target.id for node in function.body if isinstance(node, ast.Assign)
            for target in node.targets if isinstance(target, ast.Name)]


def dead_assignments(source: str) -> set[str]:
    """Names the generated function computes and never uses."""
    function = next(node for node in ast.parse(source).body
                    if isinstance(node, ast.FunctionDef) and node.name == "_solve_block")
    arguments = {a.arg for a in function.args.args}
    assigned = set(assignments(source)) - arguments
    used = {node.id for node in ast.walk(function) if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)}
    return assigned - used


def reference(theta, branch, speed=0.0, accel=0.0):
    return mp_fourbar(**SEED003, theta=theta, branch=branch, crank_speed=speed, crank_accel=accel)


def test_positions_only_scene_never_differentiates():
    linkage = fourbar()
    scene = Scene(linkage, ["coupler", "rocker", "C_x", "C_y", "transmission"], dict(theta=ANGLES, **SEED003))
    result = scene.evaluate()[1]
    assert "velocities" not in linkage.__dict__ and "accelerations" not in linkage.__dict__
    assert "dot" not in scene.source
    for i, theta in enumerate(ANGLES):
        assert result["rocker"][i] == pytest.approx(float(reference(theta, 1)["phi"]), abs=1e-13)


def test_rates_scene_differentiates_once_only():
    linkage = fourbar()
    scene = Scene(linkage, ["rocker_speed"], dict(theta=ANGLES, **SEED003, thetadot=10.5), branch=-1)
    result = scene.evaluate()[-1]
    assert "velocities" in linkage.__dict__ and "accelerations" not in linkage.__dict__
    assert "ddot" not in scene.source
    for i, theta in enumerate(ANGLES):
        assert result["rocker_speed"][i] == pytest.approx(float(reference(theta, -1, 10.5)["phi_speed"]), rel=1e-12)


def test_rocker_only_scene_does_not_compute_the_coupler_angle():
    scene = Scene(fourbar(), ["rocker"], dict(theta=ANGLES, **SEED003), branch="both")
    names = assignments(scene.source)
    assert "phi" in names and "beta" not in names
    assert scene.source.count("numpy.arctan2(") == 1
    for sign, result in scene.evaluate().items():
        expected = [float(reference(theta, sign)["phi"]) for theta in ANGLES]
        numpy.testing.assert_allclose(result["rocker"], expected, rtol=0, atol=1e-13)


def test_coupler_point_scene_does_not_compute_the_rocker_angle():
    scene = Scene(fourbar(), ["C_x", "C_y"], dict(theta=ANGLES, **SEED003))
    assert "phi" not in assignments(scene.source)
    result = scene.evaluate()[1]
    for i, theta in enumerate(ANGLES):
        expected = reference(theta, 1)
        x = SEED003["d"] + SEED003["c"] * numpy.cos(float(expected["phi"]))
        assert result["C_x"][i] == pytest.approx(x, abs=1e-12)


OUTPUT_NAMES = fourbar().output_names()


@settings(max_examples=25, deadline=None)
@given(st.lists(st.sampled_from(OUTPUT_NAMES), min_size=1, max_size=5, unique=True))
def test_common_subexpressions_are_shared_among_the_requested_outputs_only(outputs):
    scene = Scene(catalog_linkage("fourbar"), outputs)
    assert dead_assignments(scene.source) == set()
    linkage = scene.linkage
    asked = {linkage.output(name) for name in outputs}
    accels = bool(asked & {acceleration(q) for q in linkage.unknowns})
    rates = accels or bool(asked & {rate(q) for q in linkage.unknowns})
    names = assignments(scene.source)
    assert any(n.endswith("dot") for n in names) == rates
    assert any(n.endswith("ddot") for n in names) == accels
    # Exactly the outputs asked for, plus the assembled mask.
    values = dict(theta=0.3, **SEED003, thetadot=1.0, thetaddot=0.5)
    result = scene.code.function(**{k: v for k, v in values.items() if k in scene.code.arguments})
    assert set(result) == set(outputs) | {"assembled"}


def test_evaluate_on_both_branches_with_rates_and_accelerations():
    values = dict(theta=ANGLES, **SEED003, thetadot=10.5, thetaddot=3.0)
    results = Scene("fourbar", ["coupler_accel", "rocker_accel"], values, branch="both").evaluate()
    assert sorted(results) == [-1, 1]
    for sign, result in results.items():
        for i, theta in enumerate(ANGLES):
            expected = reference(theta, sign, 10.5, 3.0)
            assert result["rocker_accel"][i] == pytest.approx(float(expected["phi_accel"]), rel=1e-11)
            assert result["coupler_accel"][i] == pytest.approx(float(expected["beta_accel"]), rel=1e-11)


def test_values_can_be_given_late_and_are_checked():
    scene = Scene("fourbar", ["rocker"])
    with pytest.raises(ValueError, match=r"fourbar needs theta, a, b, c, d \(missing\)"):
        scene.evaluate()
    result = scene.evaluate(theta=0.0, **SEED003)[1]
    assert numpy.degrees(float(result["rocker"])) == pytest.approx(110.7424, abs=1e-4)  # seed 003 table
    with pytest.raises(ValueError, match="a must be a positive finite length"):
        scene.evaluate(theta=0.0, **dict(SEED003, a=-1.0))
    with pytest.raises(ValueError, match="takes theta, a, b, c, d, branch; not thetadot"):
        scene.evaluate(theta=0.0, **SEED003, thetadot=1.0)


def test_unassembled_values_are_reported_in_the_mask():
    result = Scene("fourbar", ["rocker"], dict(theta=numpy.radians([0.0, 180.0]), a=50, b=20, c=20, d=60)).evaluate()[1]
    assert result["assembled"].tolist() == [True, False]  # |BD| = 10 reaches, |BD| = 110 > b + c does not
    assert numpy.isnan(result["rocker"][1])


@pytest.mark.parametrize("arguments, message", [
    (("fourbar", ["piston"]), "no output 'piston'"),
    (("fourbar", []), "at least one output"),
    (("sixbar-of-nowhere", ["rocker"]), "no linkage 'sixbar-of-nowhere' in the catalog; it has .*fourbar"),
    (("fourbar", ["rocker"], None, 2), "branch must be 1, -1 or 'both'"),
    (("fourbar", ["rocker"], None, True), "branch must be 1, -1 or 'both'"),
])
def test_bad_scenes_are_refused(arguments, message):
    with pytest.raises(ValueError, match=message):
        Scene(*arguments)


def test_angle_outputs():
    linkage = catalog_linkage("fourbar")
    assert angle_outputs(linkage, linkage.output_names()) == {
        "beta", "phi", "crank", "coupler", "rocker", "transmission"}


@pytest.mark.parametrize("change, words", [
    (("a = 20", "a = 1e300"), "parameters.a must be 0 or between 1e-50 and 1e+50"),
    (("a = 20", "a = 1e-300"), "parameters.a must be 0 or between 1e-50 and 1e+50"),
    (("angles = [0]", "angles = [1e300]"), "input.angles[0] must be at most 1e+09 in size"),
    (("angles = [0]", "angles = [0]\nspeed = 1e300"), "input.speed must be 0 or between"),
    (("angles = [0]", "start = -1e10"), "input.start must be at most 1e+09 in size"),
])
def test_scene_values_are_in_range(change, words, tmp_path):
    from symlink.io.scene import read_scene
    text = ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 20\nb = 66\nc = 56\nd = 80\n'
            '[input]\nangles = [0]\n')
    path = tmp_path / "scene.toml"
    path.write_text(text.replace(*change))
    with pytest.raises(ValueError) as caught:
        read_scene(path)
    assert str(caught.value).startswith(f"{path}: ") and words in str(caught.value), caught.value
