"""Warm means warm: a cached dynamics request does no symbolic work (no dynamic model, no derivation)."""
from __future__ import annotations

import math
import textwrap

import pytest
import sympy

from symlink.numeric import cache
from symlink.io.scene import scene_from_text
from warm_runs import imported_packages, run_twice

SCENE = textwrap.dedent("""\
    linkage = "fourbar"
    outputs = ["input_torque", "joint_A_y"]
    [parameters]
    a = 0.2
    b = 0.66
    c = 0.56
    d = 0.8
    m2 = 1.5
    g = 9.81
    [input]
    angles = [0, 50]
    accel = 2
    [dynamics]
    gravity = [0, "-g"]
    [dynamics.masses.crank]
    mass = "m2"
    distance = 0.08
    inertia = 0.02
    """)


def crank_alone(theta: float, speed: float, accel: float) -> tuple[float, float]:
    """Torque and the vertical force at A of a crank alone (the coupler and rocker are massless), by hand.

    The crank (mass m, centre at r along it, inertia I about its centre) turns about A; the massless
    coupler carries no force, so the torque balances the crank's inertia and weight:
    ``T = (I + m r^2) alpha + m g r cos(theta)``, and A carries the crank's weight and its centre's
    acceleration: ``A_y = m (g + r alpha cos(theta) - r w^2 sin(theta))``.
    """
    m, r, inertia, g = 1.5, 0.08, 0.02, 9.81
    return ((inertia + m * r * r) * accel + m * g * r * math.cos(theta),
            m * (g + r * accel * math.cos(theta) - r * speed * speed * math.sin(theta)))


@pytest.fixture()
def disk_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "cache"))
    cache.clear_memory()
    yield
    cache.clear_memory()


def torques(scene_file):
    scene = scene_file.scene
    result = scene.evaluate()[1]
    return list(zip(result["input_torque"], result["joint_A_y"]))


def test_a_warm_dynamics_scene_derives_nothing(disk_cache, monkeypatch):
    cold = torques(scene_from_text(SCENE, "scene.toml"))  # derives the equation of motion, once
    cache.clear_memory()  # a new process: the disk cache only

    def forbidden(*args, **kwargs):
        raise AssertionError("symbolic work in a warm request")
    for name in ("diff", "cse", "simplify", "solve", "Matrix"):
        monkeypatch.setattr(sympy, name, forbidden)
    monkeypatch.setattr(sympy.Expr, "diff", forbidden)  # every derivative, as a function or a method
    monkeypatch.setattr(sympy.Derivative, "__new__", forbidden)
    from symlink.io import linkage_file
    from symlink.dynamics import inverse, model
    monkeypatch.setattr(inverse, "dynamic_linkage", forbidden)
    monkeypatch.setattr(model, "DynamicModel", forbidden)
    monkeypatch.setattr(linkage_file, "dynamic_model", forbidden)  # the scene reader imports it from there when called
    warm = torques(scene_from_text(SCENE, "scene.toml"))
    assert warm == cold
    for theta, (torque, force) in zip((0.0, math.radians(50)), warm):
        speed = math.sqrt(2 * 2.0 * theta)  # uniform acceleration 2 rad/s^2 from rest at the first angle
        assert (torque, force) == pytest.approx(crank_alone(theta, speed, 2.0), rel=1e-12)


def test_a_changed_table_or_output_is_another_request(disk_cache):
    first = torques(scene_from_text(SCENE, "scene.toml"))
    heavier = torques(scene_from_text(SCENE.replace("inertia = 0.02", "inertia = 0.05"), "scene.toml"))
    assert heavier[0][0] == pytest.approx(first[0][0] + 0.03 * 2.0, rel=1e-12)  # (I + m r^2) alpha: 0.03 more
    with pytest.raises(ValueError, match="outputs: fourbar has no output 'joint_Z_x'"):
        scene_from_text(SCENE.replace('"joint_A_y"', '"joint_Z_x"'), "scene.toml")


def forbid_derivatives(monkeypatch):
    def forbidden(*args, **kwargs):
        raise AssertionError("symbolic work in a warm request")
    for name in ("diff", "cse", "simplify", "solve"):
        monkeypatch.setattr(sympy, name, forbidden)
    monkeypatch.setattr(sympy.Expr, "diff", forbidden)
    monkeypatch.setattr(sympy.Derivative, "__new__", forbidden)


@pytest.mark.parametrize("backend", ["numpy", "auto"])
def test_a_warm_sensitivity_request_derives_nothing(disk_cache, monkeypatch, backend):
    from symlink.mechanism.catalog import fourbar
    from symlink.io.scene import Scene
    from symlink.numeric.solver import NumericSolver, Solver
    from symlink.mechanism.catalog import stephenson2
    values = dict(theta=0.3, a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0)
    cold = Solver(fourbar(), ["rocker__d_a", "rocker"], backend=backend)(**values)
    lengths = {k: v for k, v in values.items() if k != "branch"}
    Scene(fourbar(), ["rocker__d_a"], lengths).evaluate()
    NumericSolver(stephenson2())
    cache.clear_memory()  # a new process: the disk cache only
    forbid_derivatives(monkeypatch)
    warm = Solver(fourbar(), ["rocker__d_a", "rocker"], backend=backend)(**values)
    assert float(warm["rocker__d_a"]) == pytest.approx(float(cold["rocker__d_a"]), rel=1e-13)
    scene = Scene(fourbar(), ["rocker__d_a"], lengths)
    assert float(scene.evaluate()[1]["rocker__d_a"]) == pytest.approx(float(cold["rocker__d_a"]), rel=1e-13)
    NumericSolver(stephenson2())  # Newton's module, from the cache too
    monkeypatch.undo()
    # finite differences of the rocker angle, an independent check of the derivative's value
    step = 1e-6
    ahead = Solver(fourbar(), ["rocker"], backend="numpy")(**{**values, "a": 20.0 + step})["rocker"]
    behind = Solver(fourbar(), ["rocker"], backend="numpy")(**{**values, "a": 20.0 - step})["rocker"]
    assert float(warm["rocker__d_a"]) == pytest.approx(float(ahead - behind) / (2 * step), rel=1e-6)


def crank_model():
    """The scene's model by the Python route: a crank of mass m2 (a parameter), the rest massless, under gravity."""
    from symlink.mechanism.catalog import fourbar
    from symlink.dynamics.model import DynamicModel, Gravity, MassProperties
    return DynamicModel(fourbar(), [MassProperties("crank", "m2", distance=0.08, inertia=0.02)],
                        gravity=Gravity(0, -9.81))


def forbid_dynamics(monkeypatch):
    """Every derivation of the dynamic outputs raises (the model may be built: the user does that)."""
    from symlink.dynamics import inverse, model

    def forbidden(*args, **kwargs):
        raise AssertionError("symbolic work in a warm request")
    forbid_derivatives(monkeypatch)
    for name in ("dynamic_outputs", "driving_efforts", "reactions", "newton_euler", "equation_of_motion"):
        monkeypatch.setattr(inverse, name, forbidden)
    for name in ("generalised_inertia", "generalised_inertia_slope", "applied_generalised_forces"):
        monkeypatch.setattr(model.DynamicModel, name, forbidden)


@pytest.mark.parametrize("backend", ["numpy", "auto"])
def test_a_warm_dynamic_linkage_request_derives_nothing(disk_cache, monkeypatch, backend):
    import numpy
    from symlink.dynamics.inverse import dynamic_linkage
    from symlink.numeric.solver import Solver
    angles = numpy.radians([0.0, 50.0])
    speeds = numpy.sqrt(2 * 2.0 * angles)  # uniform acceleration 2 rad/s^2 from rest at 0
    values = dict(theta=angles, a=0.2, b=0.66, c=0.56, d=0.8, m2=1.5, branch=1, thetadot=speeds, thetaddot=2.0)
    outputs = ["input_torque", "joint_A_y"]
    cold = Solver(dynamic_linkage(crank_model()), outputs, backend=backend)(**values)
    from symlink.io.scene import Scene
    scene_values = {k: v for k, v in values.items() if k != "branch"}
    Scene(dynamic_linkage(crank_model()), outputs, scene_values).evaluate()
    cache.clear_memory()  # a new process: the disk cache only
    forbid_dynamics(monkeypatch)
    linkage = dynamic_linkage(crank_model())
    assert linkage.output_names()[-4:-1] == ["generalised_inertia", "generalised_inertia_slope",
                                           "applied_generalised_force"]  # named without deriving them
    warm = Solver(linkage, outputs, backend=backend)(**values)
    for name in outputs:
        numpy.testing.assert_allclose(warm[name], cold[name], rtol=1e-13, atol=0)
    if backend == "numpy":  # a scene of the same linkage answers from the cache too
        scene = Scene(dynamic_linkage(crank_model()), outputs, scene_values)
        numpy.testing.assert_allclose(scene.evaluate()[1]["input_torque"], cold["input_torque"], rtol=1e-13, atol=0)
    for k, theta in enumerate(angles):
        torque, force = crank_alone(float(theta), float(speeds[k]), 2.0)
        assert float(warm["input_torque"][k]) == pytest.approx(torque, rel=1e-12)
        assert float(warm["joint_A_y"][k]) == pytest.approx(force, rel=1e-12)


def test_a_changed_model_is_another_dynamic_linkage_request(disk_cache):
    """The key of the Python route is made from the model as given: another mass is another entry."""
    from symlink.mechanism.catalog import fourbar
    from symlink.dynamics.inverse import dynamic_linkage
    from symlink.dynamics.model import DynamicModel, MassProperties
    from symlink.numeric.solver import Solver
    values = dict(theta=0.0, a=0.2, b=0.66, c=0.56, d=0.8, branch=1, thetadot=0.0, thetaddot=2.0)
    torques = [float(Solver(dynamic_linkage(DynamicModel(fourbar(), [MassProperties("crank", 1.5, distance=0.08,
                                                                                      inertia=inertia)])),
                            ["input_torque"], backend="numpy")(**values)["input_torque"])
               for inertia in (0.02, 0.05)]
    assert torques[1] == pytest.approx(torques[0] + 0.03 * 2.0, rel=1e-12)  # (I + m r^2) alpha: 0.03 more


def test_the_dynamic_outputs_are_named_as_derived():
    """The names a dynamic linkage gives before deriving are those the derivation makes, in order."""
    from symlink.mechanism.catalog import CATALOG
    from symlink.dynamics.inverse import dynamic_linkage, dynamic_outputs
    from symlink.dynamics.model import DynamicModel, MassProperties
    for name, body in (("fourbar", "coupler"), ("slider-crank", "conrod"), ("watt2", "crank")):
        model = DynamicModel(CATALOG[name](), [MassProperties(body, 1.0, inertia=0.1)])
        linkage = dynamic_linkage(model)
        assert list(linkage.dynamic_outputs) == list(dynamic_outputs(model))
        assert list(linkage.extras) == [*model.kinematics.extras, *dynamic_outputs(model)]


# --- warm from the command line: a second run in a new process imports no SymPy ------------------------------

def _run_twice(tmp_path, arguments: list[str]) -> tuple[str, str, set[str]]:
    """``symlink ARGUMENTS`` in a fresh cache folder twice, each in a new process, the second with ``-X importtime``:
    the two outputs and what the second imported (:func:`warm_runs.run_twice`)."""
    runs = run_twice(tmp_path, arguments)
    return runs.cold, runs.warm, runs.imported


#: The Stephenson six-bar's (stephenson2, formerly stephenson3) assembly near which its table starts (coupler, mu, rocker, eta at crank angle 0, degrees).
NEWTON_GUESS = "coupler=-33,mu=-35,rocker=-73,eta=-68"
WARM_COMMANDS = {
    "catalog table": ["table", "watt2", "--angles", "0,50", "--format", "csv", "--branch", "+1"],
    "linkage file table": ["table", "mywatt.toml", "--angles", "0,50", "--format", "csv", "--branch", "+1"],
    "atlas table": ["table", "atlas:watt-ii", "--angles", "0,30", "--format", "csv", "--branch", "+1"],
    "Newton table": ["table", "stephenson2", "--angles", "0,50", "--format", "csv", "--guess", NEWTON_GUESS],
    "Newton table by its former name": ["table", "stephenson3", "--angles", "0,50", "--format", "csv", "--guess",
                                        NEWTON_GUESS],
    "Newton linkage file table": ["table", "mystephenson.toml", "--angles", "0,50", "--format", "csv", "--guess",
                                  NEWTON_GUESS],
    "four-bar with masses": ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
                             "--masses", "1,2,3", "--gravity", "9.81", "--angles", "0,50", "--format", "csv", "--branch", "1"],
}


@pytest.mark.parametrize("name", WARM_COMMANDS)
def test_a_warm_command_imports_no_sympy(name, tmp_path):
    from symlink.io.linkage_file import catalog_file
    (tmp_path / "mywatt.toml").write_text(catalog_file("watt2").read_text())
    (tmp_path / "mystephenson.toml").write_text(catalog_file("stephenson2").read_text())
    cold, warm, imported = _run_twice(tmp_path, WARM_COMMANDS[name])
    assert "symlink" in imported and "numpy" in imported  # the import list was read
    assert "sympy" not in imported
    assert warm == cold and len(warm.splitlines()) == 3  # a header and two rows, the same from the cache


def test_a_warm_table_is_the_table_of_the_linkage(tmp_path):
    """The cached table's numbers are the linkage's own solver's (an independent evaluation, in this process)."""
    import numpy
    from symlink.mechanism.catalog import EXAMPLE_VALUES, watt2
    from symlink.numeric.solver import Solver
    _, warm, _ = _run_twice(tmp_path, ["table", "watt2", "--angles", "0,50", "--format", "csv", "--branch", "+1"])
    header, *rows = warm.splitlines()
    columns = header.split(",")
    linkage = watt2()
    values = {k: v for k, v in EXAMPLE_VALUES["watt2"].items() if k != "theta"}
    branches = {b.name: 1 for b in linkage.branches}
    solved = Solver(linkage, ["rocker", "output"], backend="numpy")(theta=numpy.radians([0.0, 50.0]), **values,
                                                                      **branches)
    for k, row in enumerate(rows):
        cells = dict(zip(columns, row.split(",")))
        for name in ("rocker", "output"):
            expected = (math.degrees(float(solved[name][k])) + 180.0) % 360.0 - 180.0
            assert float(cells[name]) == pytest.approx(expected, abs=1e-9)


# --- warm scene files: symlink run, a second time in a new process, imports no SymPy ----------------------------

KINEMATIC_SCENE = textwrap.dedent("""\
    linkage = "LINKAGE"
    outputs = OUTPUTS
    format = "csv"
    [parameters]
    a = 20
    b = 66
    c = 56
    d = 80
    [input]
    angles = ANGLES
    speed = 10.5
    """)
WARM_SCENES = {
    "kinematics": KINEMATIC_SCENE.replace("OUTPUTS", '["rocker", "rocker_speed"]'),
    "sensitivities": KINEMATIC_SCENE.replace("OUTPUTS", '["rocker__d_a"]'),
    "linkage file": KINEMATIC_SCENE.replace("OUTPUTS", '["rocker"]').replace('"LINKAGE"', '"legs/four.toml"'),
    "dynamics": 'format = "csv"\n' + SCENE.replace("angles = [0, 50]", "angles = ANGLES"),
}


def _scene_text(name: str, angles: str = "[0, 50]") -> str:
    return WARM_SCENES[name].replace('"LINKAGE"', '"fourbar"').replace("ANGLES", angles)


@pytest.mark.parametrize("name", WARM_SCENES)
def test_a_warm_scene_imports_no_sympy(name, tmp_path):
    from symlink.io.linkage_file import catalog_file
    (tmp_path / "legs").mkdir()
    (tmp_path / "legs" / "four.toml").write_text(catalog_file("fourbar").read_text())
    (tmp_path / "scene.toml").write_text(_scene_text(name))
    cold, warm, imported = _run_twice(tmp_path, ["run", "scene.toml"])
    assert "symlink" in imported and "numpy" in imported
    assert "sympy" not in imported
    assert warm == cold and len(warm.splitlines()) == 3


def test_a_warm_scene_with_other_numbers_is_warm_and_right(tmp_path):
    """The cache keys a scene by its linkage, outputs and dynamics: other input angles are still warm, and the
    torques are the crank's by hand (:func:`crank_alone`)."""
    (tmp_path / "scene.toml").write_text(_scene_text("dynamics"))
    _run_twice(tmp_path, ["run", "scene.toml"])
    (tmp_path / "scene.toml").write_text(_scene_text("dynamics", "[10, 60, 120]"))
    _, warm, imported = _run_twice(tmp_path, ["run", "scene.toml"])
    assert "sympy" not in imported
    header, *rows = warm.splitlines()
    assert header == "crank,branch,input_torque,joint_A_y" and len(rows) == 3
    for row in rows:
        theta = math.radians(float(row.split(",")[0]))
        speed = math.sqrt(2 * 2.0 * (theta - math.radians(10)))  # 2 rad/s^2 from rest at the first angle
        torque, force = crank_alone(theta, speed, 2.0)
        assert [float(v) for v in row.split(",")[2:]] == pytest.approx([torque, force], rel=1e-12)


@pytest.mark.parametrize("old, new, message", [
    ("a = 20", "a = -20", "parameters.a must be a positive length, got -20"),
    ("b = 66", 'b = "66"', "parameters.b must be a number, got"),
    ("[input]", "[input]\nstep = 0", "input: give either angles or start/stop/step, not both"),
    ('format = "csv"', 'format = "xml"', "format must be one of 'table', 'csv', 'json', got 'xml'"),
    ("[parameters]", "colour = 1\n[parameters]", "unknown key colour"),
])
def test_a_bad_warm_scene_gets_the_full_readers_message(old, new, message, tmp_path, disk_cache, capsys):
    from symlink.cli import main
    (tmp_path / "scene.toml").write_text(_scene_text("kinematics"))
    assert main(["run", str(tmp_path / "scene.toml")]) == 0  # cold: the facts are cached
    capsys.readouterr()
    (tmp_path / "scene.toml").write_text(_scene_text("kinematics").replace(old, new))
    assert main(["run", str(tmp_path / "scene.toml")]) == 2
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and message in lines[0], lines


def test_a_warm_newton_table_closes_both_loops(tmp_path):
    """The Stephenson III's cached table (Newton's method, no closed form) closes its two loops at every row:
    AB + BC + CF = AD + DF and AB + BE + EH = AD + DH, with the catalog's lengths, by hand in complex numbers."""
    import cmath
    _, warm, _ = _run_twice(tmp_path, WARM_COMMANDS["Newton table"])
    header, *rows = warm.splitlines()
    p = dict(a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1, alpha=0.9, delta=0.3)  # stephenson2.toml

    def vector(length: float, angle: float) -> complex:
        return cmath.rect(length, angle)
    assert len(rows) == 2
    for row in rows:
        cells = {k: math.radians(float(v)) for k, v in zip(header.split(","), row.split(",")) if k != "branch"}
        theta, beta, mu, phi, eta = (cells[k] for k in ("crank", "coupler", "mu", "rocker", "eta"))
        first = vector(p["a"], theta) + vector(p["b"], beta) + vector(p["c"], mu) - vector(p["f"], phi) - p["d"]
        second = (vector(p["a"], theta) + vector(p["e"], p["alpha"] + beta) + vector(p["g"], eta)
                  - vector(p["h"], p["delta"] + phi) - p["d"])
        assert abs(first) < 1e-10 and abs(second) < 1e-10
    assert abs(math.degrees(cells["rocker"]) - (-94.16)) < 0.01  # the assembly near the guess, carried to 50 deg


def test_a_sweep_starts_without_distributed_or_pandas(tmp_path):
    pytest.importorskip("dask")
    pytest.importorskip("pyarrow")
    arguments = ["sweep", "fourbar", "{folder}", "--vary", "a=10:20", "--set", "b=66,c=56,d=80", "--grid", "5",
                 "--scheduler", "synchronous", "--no-progress"]
    import os
    import subprocess
    import sys
    project = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env = {**os.environ, "PYTHONPATH": project, "MPLBACKEND": "Agg", "SYMLINK_CACHE": str(tmp_path / "cache")}
    for number, flags in enumerate(([], ["-X", "importtime"])):
        run = subprocess.run([sys.executable, *flags, "-m", "symlink",
                              *(a.format(folder=tmp_path / f"sweep{number}") for a in arguments)],
                             capture_output=True, text=True, env=env, cwd=str(tmp_path), timeout=600)
        assert run.returncode == 0, run.stderr[-2000:]
    imported = imported_packages(run.stderr)
    assert {"dask", "pyarrow"} <= imported  # the sweep ran on Dask and wrote Parquet
    assert not imported & {"distributed", "pandas"}
    chunks = [(tmp_path / f"sweep{n}" / "chunk-000000.parquet").read_bytes() for n in (0, 1)]
    assert chunks[0] == chunks[1]  # the same table, byte for byte
