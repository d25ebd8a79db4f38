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


# --- a linkage without a closed form: a scene with a [guess], solved by Newton's method -------------------------

#: The catalog's Stephenson II (lengths; its two fixed angles in radians, 51.5 and 17.2 degrees, as a scene's
#: [parameters] take them whatever its units) and a guess near one of its assemblies at crank angle 0 (degrees).
STEPHENSON2 = dict(a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1, alpha=0.8988445647770797,
                   delta=0.30019663134302466)
STEPHENSON2_GUESS = "[guess]\ncoupler = -33\nmu = -35\nrocker = -73\neta = -68\n"


def stephenson2_scene(folder, guess=STEPHENSON2_GUESS, linkage='"stephenson2"', extra="",
                      outputs='["coupler", "mu", "rocker", "eta", "rocker_speed"]'):
    path = folder / "six.toml"
    values = "".join(f"{name} = {value!r}\n" for name, value in STEPHENSON2.items())
    path.write_text(f"linkage = {linkage}\noutputs = {outputs}\n{extra}\n[parameters]\n{values}"
                    f"[input]\nangles = [0, 50, 100, 150, 200]\nspeed = 2\n{guess}")
    return path


def stephenson2_loops(theta, beta, mu, phi, eta):
    """The two closure loops of the Stephenson II, by hand from its links (complex numbers): ABCFD,
    AB + BC + CF - DF - AD, and ABEHD, AB + BE + EH - DH - AD (BE at alpha from BC, DH at delta from DF)."""
    v = STEPHENSON2
    rect = numpy.exp
    ab = v["a"] * rect(1j * theta)
    return (ab + v["b"] * rect(1j * beta) + v["c"] * rect(1j * mu) - v["f"] * rect(1j * phi) - v["d"],
            ab + v["e"] * rect(1j * (beta + v["alpha"])) + v["g"] * rect(1j * eta)
            - v["h"] * rect(1j * (phi + v["delta"])) - v["d"])


def test_read_scene_solves_a_newton_scene_that_closes_both_loops(tmp_path):
    """read_scene takes a scene with a [guess] of a linkage without a closed form; its evaluation closes both loops,
    written out here by hand, to 1e-9 of the link lengths, on the assembly nearest the guess; the rocker's speed is
    the finite difference of its angle along the sweep (h = 1e-6 rad) times the crank speed."""
    from symlink.io.scene import NewtonSceneFile, read_scene
    found = read_scene(stephenson2_scene(tmp_path))
    assert isinstance(found, NewtonSceneFile)
    assert found.angles.tolist() == [0, 50, 100, 150, 200] and found.units == "deg" and found.input_column == "crank"
    assert found.angle_columns == {"coupler", "mu", "rocker", "eta"}
    results = found.scene.evaluate()
    assert list(results) == [1]
    result = results[1]
    assert list(result) == ["coupler", "mu", "rocker", "eta", "rocker_speed", "assembled"]
    assert result.units["rocker"] == "rad" and result.units["rocker_speed"] == "rad/s"
    theta = numpy.radians(found.angles)
    loops = stephenson2_loops(theta, result["coupler"], result["mu"], result["rocker"], result["eta"])
    assert numpy.all(result["assembled"]) and max(numpy.max(numpy.abs(loop)) for loop in loops) < 1e-9
    first = numpy.degrees([result[name][0] for name in ("coupler", "mu", "rocker", "eta")])
    assert numpy.max(numpy.abs(first - [-33, -35, -73, -68])) < 1  # the assembly nearest the guess, not another
    # the speed: the angles at the sweep's 50 deg, a step either side (a new sweep from the same guess)
    step = 1e-6
    near = [found.scene.evaluate(theta=numpy.radians([0.0, 50.0]) + [0.0, h], thetadot=2.0)[1]["rocker"][1]
            for h in (-step, step)]
    assert result["rocker_speed"][1] == pytest.approx((near[1] - near[0]) / (2 * step) * 2.0, rel=1e-6)


def test_a_newton_scene_of_a_linkage_file_takes_its_defaults(tmp_path):
    """A linkage file without a closed form (the catalog's own file, copied): its defaults stand in for the
    parameters the scene leaves out, and the poses are those of the catalog name's scene."""
    from symlink.io.linkage_file import catalog_file
    from symlink.io.scene import read_scene
    (tmp_path / "mine.toml").write_text(catalog_file("stephenson2").read_text())
    by_name = read_scene(stephenson2_scene(tmp_path)).scene.evaluate()[1]
    path = stephenson2_scene(tmp_path, linkage='"mine.toml"')
    path.write_text(path.read_text().replace("a = 1.0\n", ""))  # the file's default: a = 1
    found = read_scene(path)
    assert found.source == str(tmp_path / "mine.toml") and found.defaults["a"] == 1
    assert {k: v.tolist() for k, v in found.scene.evaluate()[1].items()} == {k: v.tolist() for k, v in by_name.items()}


#: A scene of a linkage with a closed form, given a [guess].
FOURBAR_GUESS = ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 20\nb = 66\nc = 56\nd = 80\n'
                 '[input]\nangles = [0]\n[guess]\nphi = 110\n')
NEWTON_REFUSALS = [  # (how the Stephenson II's scene is changed, or a scene's text; the message)
    (FOURBAR_GUESS, "guess: fourbar is solved in closed form, where branch chooses the assembly"),
    (dict(guess=""), r"guess: stephenson2 has no closed form: give a \[guess\] table of every unknown "
                     r"\(coupler, mu, rocker, eta\)"),
    (dict(guess="[guess]\ncoupler = -33\nmu = -35\nrocker = -73\n"),
     r"needs a guess of every unknown \(coupler, mu, rocker, eta\)"),
    (dict(guess=STEPHENSON2_GUESS + "zeta = 1\n"), "stephenson2 has no unknown 'zeta'"),
    (dict(outputs='["C_x"]'), r"stephenson2 \(solved by Newton's method\) has no output 'C_x'"),
    (dict(extra='branch = "both"'), "branch: stephenson2 has no closed form"),
    (dict(extra='[dynamics]\ngravity = 9.81'), "dynamics: stephenson2 has no closed form"),
]


@pytest.mark.parametrize("change, message", NEWTON_REFUSALS)
def test_read_scene_refuses_what_newton_cannot_solve(tmp_path, change, message):
    """A closed form given a [guess], a linkage without one given none, and a [guess] scene's bad keys: one
    ValueError starting with the file's name, in the words of symlink run."""
    import re

    from symlink.io.scene import read_scene
    if isinstance(change, dict):
        path = stephenson2_scene(tmp_path, **change)
    else:
        path = tmp_path / "scene.toml"
        path.write_text(change)
    with pytest.raises(ValueError) as caught:
        read_scene(path)
    assert str(caught.value).startswith(f"{path}: ") and "\n" not in str(caught.value), caught.value
    assert re.search(message, str(caught.value)), caught.value


def test_a_warm_newton_scene_imports_no_sympy(tmp_path):
    """read_scene of a [guess] scene and its evaluation, in a second process with the same disk cache: no SymPy
    (``python -X importtime``), and the same numbers as the first (cold) process."""
    import os
    import subprocess
    import sys

    from warm_runs import PROJECT, imported_packages
    stephenson2_scene(tmp_path)
    code = ("from symlink.io.scene import read_scene\n"
            "result = read_scene('six.toml').scene.evaluate()[1]\n"
            "print({name: values.tolist() for name, values in result.items()})\n")
    env = {**os.environ, "PYTHONPATH": str(PROJECT), "SYMLINK_CACHE": str(tmp_path / "cache")}
    runs = [subprocess.run([sys.executable, *flags, "-c", code], capture_output=True, text=True, env=env,
                           cwd=str(tmp_path), timeout=600) for flags in ([], ["-X", "importtime"])]
    assert [run.returncode for run in runs] == [0, 0], runs[1].stderr[-2000:]
    imported = imported_packages(runs[1].stderr)
    assert "symlink" in imported and "numpy" in imported  # the import list was read
    assert "sympy" not in imported, sorted(imported)
    assert runs[1].stdout == runs[0].stdout and "'rocker'" in runs[0].stdout
