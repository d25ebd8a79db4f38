"""Dynamics from linkage files: the ``[dynamics]`` table, scenes, ``symlink table``, and the NumPy, C, Octave
and LaTeX exports of the dynamic outputs.

The expected values are the hand formulas of a four-bar whose crank alone has mass
(massless coupler and rocker carry no force): about the fixed pivot A,
``T + T_load = (I2 + m2 r2^2) theta'' + m2 g r2 cos(theta)`` and the pin A carries
``m2 (a_G + g)``, with ``a_G = r2 (theta'' t - theta'^2 n)`` (n along the crank, t
across it).  A file with every kind of load is checked against the same model built
in Python (what the file format must mean).
"""
from __future__ import annotations

import math
import textwrap

import numpy
import pytest
import sympy

from codegen.test_c import build, call
from codegen.test_octave import _octave, run_octave
from symlink.cli import main
from symlink.codegen.c import c_code, c_function
from symlink.codegen.octave import octave_function
from symlink.dynamics.inverse import dynamic_linkage
from symlink.dynamics.model import BodyTorque, Damper, DynamicModel, Gravity, MassProperties, PointForce, Spring
from symlink.io.export import export_texts
from symlink.mechanism.catalog import fourbar
from symlink.io.linkage_file import linkage_from_text, linkage_text
from symlink.io.scene import Scene

FOURBAR = linkage_text(fourbar())  # the catalog four-bar as a linkage file, without defaults

CRANK_ONLY = FOURBAR + """
[defaults]
a = 0.2
b = 0.66
c = 0.56
d = 0.8
m2 = 1.5
r2 = 0.08
g = 9.81
T_load = 0.7

[dynamics]
gravity = [0, "-g"]

[dynamics.masses.crank]
mass = "m2"
distance = "r2"
inertia = 0.02

[[dynamics.torques]]
body = "crank"
torque = "T_load"
"""


def crank_only():
    return linkage_from_text(CRANK_ONLY, "crank.toml")


def hand(theta, speed, accel, m2=1.5, r2=0.08, g=9.81, load=0.7, inertia=0.02):
    """The hand formulas of the module docstring: (torque, joint A x, joint A y)."""
    torque = (inertia + m2 * r2 * r2) * accel + m2 * g * r2 * numpy.cos(theta) - load
    ax = r2 * (-accel * numpy.sin(theta) - speed ** 2 * numpy.cos(theta))
    ay = r2 * (accel * numpy.cos(theta) - speed ** 2 * numpy.sin(theta))
    return torque, m2 * ax, m2 * (ay + g)


def random_states(count: int, seed: int) -> dict[str, numpy.ndarray]:
    rng = numpy.random.default_rng(seed)
    theta = rng.uniform(-math.pi, math.pi, count)
    theta[:4] = [0.0, math.pi / 2, math.pi, -math.pi / 2]  # where the crank's lever arms vanish
    return {"theta": theta, "thetadot": rng.uniform(-5, 5, count), "thetaddot": rng.uniform(-20, 20, count)}


def arguments(found, program, states) -> dict[str, numpy.ndarray]:
    count = len(states["theta"])
    values = {**found.defaults, **states, "branch": 1.0}
    return {s.name: numpy.broadcast_to(numpy.asarray(values[s.name], dtype=float), (count,)).copy()
            for s in program.arguments}


OUTPUTS = ["input_torque", "joint_A_x", "joint_A_y", "joint_B_x", "joint_C_y", "joint_D_x"]


def assert_hand(result, states):
    torque, ax, ay = hand(states["theta"], states["thetadot"], states["thetaddot"])
    assert numpy.allclose(result["input_torque"], torque, rtol=1e-12, atol=1e-12)
    assert numpy.allclose(result["joint_A_x"], ax, rtol=1e-12, atol=1e-12)
    assert numpy.allclose(result["joint_A_y"], ay, rtol=1e-12, atol=1e-12)
    for name in ("joint_B_x", "joint_C_y", "joint_D_x"):  # massless links carry nothing
        assert numpy.allclose(result[name], 0.0, atol=1e-12)
    assert numpy.all(result["assembled"])


def test_the_file_gives_the_hand_formulas_in_numpy():
    found = crank_only()
    assert found.model is not None and "input_torque" not in found.linkage.output_names()
    linkage = found.dynamic_linkage()
    states = random_states(50, 1)
    result = Scene(linkage, OUTPUTS, {**found.defaults, **states}).evaluate()[1]
    assert_hand(result, states)


def test_the_c_export_of_the_dynamic_outputs(tmp_path):
    found = crank_only()
    linkage = found.dynamic_linkage()
    program = linkage.program(OUTPUTS)
    header, source = c_code([("crank_dynamics", program, "Torque and joint forces.")], "crank")
    library = build(tmp_path, header, source, "crank")
    states = random_states(40, 2)
    result = call(library, c_function(program, "crank_dynamics"), arguments(found, program, states))
    assert_hand(result, states)


def test_the_octave_export_of_the_dynamic_outputs(tmp_path):
    _octave()
    found = crank_only()
    program = found.dynamic_linkage().program(OUTPUTS)
    (tmp_path / "crank_dynamics.m").write_text(octave_function(program, "crank_dynamics", "Torque."))
    states = random_states(30, 3)
    values = arguments(found, program, states)
    names = [s.name for s in program.arguments]
    numpy.array([values[n] for n in names]).tofile(tmp_path / "in.bin")
    outputs = [f"o{k}" for k in range(len(OUTPUTS) + 1)]
    script = textwrap.dedent(f"""\
        fid = fopen('in.bin', 'r'); v = fread(fid, [30, {len(names)}], 'double'); fclose(fid);
        {' '.join(f"{n} = v(:, {k + 1})';" for k, n in enumerate(names))}
        [{', '.join(outputs)}] = crank_dynamics({', '.join(names)});
        fid = fopen('out.bin', 'w'); fwrite(fid, double([{'; '.join(o + '(:)' for o in outputs)}]), 'double');
        fclose(fid);
        """)
    run_octave(tmp_path, script)
    data = numpy.fromfile(tmp_path / "out.bin").reshape(len(OUTPUTS) + 1, 30)
    result = {**dict(zip(OUTPUTS, data[:-1])), "assembled": data[-1].astype(bool)}
    assert_hand(result, states)


def test_the_latex_derivation_writes_the_dynamics():
    found = crank_only()
    (text,) = export_texts(found.dynamic_linkage(), "latex", ["input_torque", "joint_A_y"]).values()
    for heading in ("Mass properties", "Driving effort by virtual power", "Newton-Euler equations",
                    "Equation of motion"):
        assert heading in text
    # The crank's balances, as the hand derivation writes them (the massless coupler's: 0 = ...).
    assert "m_{crank} a_{G,crank,x} &= F_{A,x} - F_{B,x}" in text
    assert "0 &= F_{B,x} - F_{C,x}" in text
    assert "M \\ddot{\\theta} + \\frac{1}{2} M' \\dot{\\theta}^{2} &= Q + T_{\\theta}" in text


def test_the_default_export_sets_add_a_dynamics_set():
    from symlink.io.export import output_sets
    linkage = crank_only().dynamic_linkage()
    sets = {name: outputs for name, outputs, _ in output_sets(linkage)}
    assert "input_torque" in sets["dynamics"] and "input_torque" not in sets["accelerations"]
    assert "generalised_inertia" in sets["dynamics"]


# --- the command line ------------------------------------------------------------------------

def run(capsys, *argv):
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_symlink_table_of_a_file_with_dynamics_prints_the_force_columns(tmp_path, capsys):
    path = tmp_path / "crank.toml"
    path.write_text(CRANK_ONLY)
    status, out, err = run(capsys, "table", path, "--angles", "0,90,150", "--crank-speed", "3", "--crank-accel", "2",
                           "--branch", "+1", "--format", "csv")
    assert status == 0, err
    header, *lines = out.splitlines()
    columns = header.split(",")
    assert columns[-12:] == ["input_torque", "joint_A_x", "joint_A_y", "joint_B_x", "joint_B_y", "joint_C_x",
                             "joint_C_y", "joint_D_x", "joint_D_y", "shaking_force_x", "shaking_force_y",
                             "shaking_moment"]
    for line in lines:
        row = dict(zip(columns, line.split(",")))
        theta = math.radians(float(row["crank"]))
        speed = math.sqrt(3 ** 2 + 2 * 2 * theta)  # uniform acceleration from the first angle
        torque, ax, ay = hand(theta, speed, 2.0)
        assert float(row["input_torque"]) == pytest.approx(torque, rel=1e-12)
        assert float(row["joint_A_y"]) == pytest.approx(ay, rel=1e-12)


def test_a_scene_file_asks_for_the_torque_of_a_linkage_file(tmp_path, capsys):
    (tmp_path / "crank.toml").write_text(CRANK_ONLY)
    (tmp_path / "scene.toml").write_text('linkage = "crank.toml"\noutputs = ["input_torque"]\nformat = "csv"\n'
                                         "[parameters]\nm2 = 2.0\n[input]\nangles = [30]\nspeed = 0\naccel = 4\n")
    status, out, err = run(capsys, "run", tmp_path / "scene.toml")
    assert status == 0, err
    torque, _, _ = hand(math.radians(30), 0.0, 4.0, m2=2.0)
    assert float(out.splitlines()[1].split(",")[-1]) == pytest.approx(torque, rel=1e-12)


def test_a_scene_file_gives_a_catalog_linkage_its_masses(tmp_path, capsys):
    (tmp_path / "scene.toml").write_text(textwrap.dedent("""\
        linkage = "fourbar"
        outputs = ["input_torque", "joint_A_y"]
        format = "csv"
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
        """))
    status, out, err = run(capsys, "run", tmp_path / "scene.toml")
    assert status == 0, err
    for line in out.splitlines()[1:]:
        crank, _, torque, force = (float(v) for v in line.split(","))
        speed = math.sqrt(2 * 2.0 * math.radians(crank))
        expected = hand(math.radians(crank), speed, 2.0, load=0.0)
        assert (torque, force) == pytest.approx((expected[0], expected[2]), rel=1e-12)


def test_a_scene_cannot_give_masses_twice(tmp_path, capsys):
    (tmp_path / "crank.toml").write_text(CRANK_ONLY)
    (tmp_path / "scene.toml").write_text('linkage = "crank.toml"\noutputs = ["input_torque"]\n'
                                         '[dynamics.masses.rocker]\nmass = 1\n')
    status, out, err = run(capsys, "run", tmp_path / "scene.toml")
    assert status == 2 and "has a [dynamics] table of its own" in err and len(err.strip().splitlines()) == 1


def test_symlink_derive_of_a_file_with_dynamics_writes_the_dynamics_set(tmp_path, capsys):
    path = tmp_path / "crank.toml"
    path.write_text(CRANK_ONLY)
    status, out, err = run(capsys, "derive", path, "--to", "numpy", "--out", tmp_path / "build")
    assert status == 0, err
    text = (tmp_path / "build" / "fourbar.py").read_text()
    assert "def dynamics(" in text and "input_torque" in text and "import sympy" not in text


# --- the table means what the Python model means ---------------------------------------------

EVERY_LOAD = FOURBAR + """
[dynamics]
gravity = [0.5, "-g"]

[dynamics.masses.crank]
mass = 1.1
distance = 0.07
angle = "10 deg"
inertia = 0.01

[dynamics.masses.coupler]
mass = "m3"
distance = 0.3
angle = "-0.2 rad"
inertia = "I3"
origin = "B"

[dynamics.masses.rocker]
mass = 0.9
distance = 0.25
inertia = 0.02
origin = "D"

[[dynamics.forces]]
point = "C"
x = 3
y = "-F"

[[dynamics.torques]]
body = "rocker"
torque = "-T4"

[[dynamics.springs]]
first = "B"
second = "D"
stiffness = 40
free_length = 0.5

[[dynamics.dampers]]
first = "C"
second = "A"
coefficient = 1.5
"""


def test_every_kind_of_entry_means_what_the_python_model_means():
    found = linkage_from_text(EVERY_LOAD, "every.toml")
    def minus(name):
        return -sympy.Symbol(name, real=True)

    python = DynamicModel(found.linkage, [
        MassProperties("crank", 1.1, 0.07, math.radians(10), 0.01),
        MassProperties("coupler", "m3", 0.3, -0.2, "I3", origin="B"),
        MassProperties("rocker", 0.9, 0.25, 0, 0.02, origin="D")],
        [PointForce("C", 3, minus("F")), BodyTorque("rocker", minus("T4")), Spring("B", "D", 40, 0.5),
         Damper("C", "A", 1.5)], Gravity(0.5, minus("g")))
    values = {"a": 0.2, "b": 0.66, "c": 0.56, "d": 0.8, "m3": 2.1, "I3": 0.07, "F": 12.0, "T4": 3.0, "g": 9.81}
    states = random_states(20, 4)
    outputs = ["input_torque", "joint_B_x", "joint_C_y", "shaking_moment", "generalised_inertia"]
    from_file = Scene(found.dynamic_linkage(), outputs, {**values, **states}).evaluate()[1]
    from_python = Scene(dynamic_linkage(python), outputs, {**values, **states}).evaluate()[1]
    for name in outputs:
        assert numpy.allclose(from_file[name], from_python[name], rtol=1e-13, atol=1e-13), name


# --- bad tables: one line naming the file, the line and the problem --------------------------

BAD = [
    ("[dynamics]\nmass = 1\n", "{line}: dynamics.mass: unknown key"),
    ("[dynamics]\ngravity = [0]\n", "dynamics.gravity must be [x, y]"),
    ("[dynamics]\ngravity = [0, true]\n", "dynamics.gravity must be a number or a name, got True"),
    ("[dynamics.masses.crank]\nmass = 1\nwidth = 2\n", "{line}: dynamics.masses.crank.width: unknown key"),
    ("[dynamics.masses.crank]\ndistance = 1\n", "dynamics.masses.crank: missing mass"),
    ("[dynamics.masses.handle]\nmass = 1\n", "no body 'handle'"),
    ("[dynamics.masses.crank]\nmass = \"2*m\"\n", "dynamics.masses.crank.mass:"),
    ("[dynamics.masses.crank]\nmass = \"theta\"\n", "'theta' is a coordinate"),
    ("[dynamics.masses.crank]\nmass = 1\nangle = \"30 furlongs\"\n", "dynamics.masses.crank.angle:"),
    ("[dynamics.masses.crank]\nmass = 1\norigin = \"Z\"\n", "'Z' is not a joint or point of it"),
    ("[[dynamics.forces]]\nx = 1\n", "dynamics.forces[0]: missing point"),
    ("[[dynamics.forces]]\npoint = \"C\"\n[[dynamics.forces]]\npoint = \"Q\"\n", "no point or joint 'Q'"),
    ("[[dynamics.forces]]\npoint = \"C\"\nx = 1\nz = 2\n", "{line}: dynamics.forces[0].z: unknown key"),
    ("[[dynamics.torques]]\nbody = \"crank\"\n", "dynamics.torques[0]: missing torque"),
    ("[[dynamics.springs]]\nfirst = \"B\"\nsecond = \"D\"\n", "dynamics.springs[0]: missing stiffness"),
    ("[dynamics]\nforces = 3\n", "dynamics.forces must be a list of tables"),
    ("[dynamics.masses.crank]\nmass = \"import\"\n", "'import'"),
    ("[defaults]\nm9 = 1\n[dynamics.masses.crank]\nmass = \"m2\"\n", "defaults.m9: only constants, inputs and the "
                                                                         "names of [dynamics] have defaults"),
]


@pytest.mark.parametrize("tail, message", BAD)
def test_a_bad_dynamics_table_is_one_line_naming_the_problem(tail, message):
    text = FOURBAR + "\n" + tail
    with pytest.raises(ValueError) as caught:
        linkage_from_text(text, "crank.toml")
    found = str(caught.value)
    if "{line}" in message:  # the line of the offending key: the last line of the tail
        message = message.format(line=f"crank.toml:{len(text.splitlines())}")
    assert message in found and "\n" not in found and found.startswith("crank.toml:")
