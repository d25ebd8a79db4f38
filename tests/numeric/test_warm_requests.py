"""Warm means warm: a cached dynamics request does no symbolic work (no dynamic model, no derivation)."""
from __future__ import annotations

import math
import textwrap

import pytest
import sympy

from symlink.numeric import cache
from symlink.io.scene import scene_from_text

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
    from symlink.io import linkage_file, scene
    from symlink.dynamics import inverse, model
    monkeypatch.setattr(inverse, "dynamic_linkage", forbidden)
    monkeypatch.setattr(model, "DynamicModel", forbidden)
    monkeypatch.setattr(linkage_file, "dynamic_model", forbidden)
    monkeypatch.setattr(scene, "dynamic_model", forbidden)
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
    from symlink.mechanism.catalog import stephenson3
    values = dict(theta=0.3, a=20.0, b=66.0, c=56.0, d=80.0, branch=1.0)
    cold = Solver(fourbar(), ["rocker__d_a", "rocker"], backend=backend)(**values)
    lengths = {k: v for k, v in values.items() if k != "branch"}
    Scene(fourbar(), ["rocker__d_a"], lengths).evaluate()
    NumericSolver(stephenson3())
    cache.clear_memory()  # a new process: the disk cache only
    forbid_derivatives(monkeypatch)
    warm = Solver(fourbar(), ["rocker__d_a", "rocker"], backend=backend)(**values)
    assert float(warm["rocker__d_a"]) == pytest.approx(float(cold["rocker__d_a"]), rel=1e-13)
    scene = Scene(fourbar(), ["rocker__d_a"], lengths)
    assert float(scene.evaluate()[1]["rocker__d_a"]) == pytest.approx(float(cold["rocker__d_a"]), rel=1e-13)
    NumericSolver(stephenson3())  # Newton's module, from the cache too
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
