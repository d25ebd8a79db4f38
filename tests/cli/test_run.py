"""``symlink run scene.toml``: scene files of numbers and names, checked key by key."""
import csv
import io
import json
import math
import re

import pytest

from cache_fixture import empty_cache  # noqa: F401 - a fixture
from references import SEED003_LINKAGE, mp_fourbar
from symlink.cli import main

SCENE = """\
linkage = "fourbar"
outputs = {outputs}
branch = {branch}
{extra}
[parameters]
a = 20
b = 66
c = 56
d = 80

[input]
{sweep}
"""


pytestmark = pytest.mark.usefixtures("empty_cache")  # every test derives from scratch


def scene_file(tmp_path, outputs='["coupler", "rocker", "rocker_speed", "transmission"]', branch='"both"',
               extra="", sweep="step = 40\nspeed = 10.5"):
    path = tmp_path / "scene.toml"
    path.write_text(SCENE.format(outputs=outputs, branch=branch, extra=extra, sweep=sweep))
    return path


def run(capsys, *argv):
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return status, out, err


def wrapped_degrees(radians):
    degrees = math.degrees(float(radians))
    return degrees - 360 * math.floor((degrees + 180) / 360) if degrees != 180 else degrees


def test_csv_rows_match_the_reference(tmp_path, capsys):
    status, out, err = run(capsys, "run", scene_file(tmp_path), "--format", "csv")
    assert status == 0 and err == ""
    rows = list(csv.DictReader(io.StringIO(out)))
    assert list(rows[0]) == ["crank", "branch", "coupler", "rocker", "rocker_speed", "transmission"]
    assert len(rows) == 18  # 9 angles, both branches, a full turn (Grashof crank-rocker)
    for row in rows:
        theta, branch = math.radians(float(row["crank"])), int(row["branch"])
        expected = mp_fourbar(**SEED003_LINKAGE, theta=theta, branch=branch, crank_speed=10.5)
        assert float(row["rocker"]) == pytest.approx(wrapped_degrees(expected["phi"]), abs=1e-10)
        assert float(row["coupler"]) == pytest.approx(wrapped_degrees(expected["beta"]), abs=1e-10)
        assert float(row["rocker_speed"]) == pytest.approx(float(expected["phi_speed"]), rel=1e-10)
        interior = abs(wrapped_degrees(expected["phi"] - expected["beta"]))  # the angle at C
        assert float(row["transmission"]) == pytest.approx(interior, abs=1e-10)


def test_format_and_units_from_the_file(tmp_path, capsys):
    path = scene_file(tmp_path, outputs='["rocker"]', branch="-1", extra='units = "rad"\nformat = "json"',
                      sweep="angles = [0, 0.5]")
    status, out, _ = run(capsys, "run", path)
    assert status == 0
    records = json.loads(out)
    assert [r["crank"] for r in records] == [0.0, 0.5] and {r["branch"] for r in records} == {-1}
    for record in records:
        expected = mp_fourbar(**SEED003_LINKAGE, theta=record["crank"], branch=-1)
        assert record["rocker"] == pytest.approx(float(expected["phi"]), abs=1e-13)


def test_table_format_and_uniform_crank_acceleration(tmp_path, capsys):
    path = scene_file(tmp_path, outputs='["rocker_accel"]', branch="1",
                      sweep="angles = [0, 90]\nspeed = 2\naccel = 3")
    status, out, _ = run(capsys, "run", path)
    assert status == 0 and out.split()[:3] == ["crank", "branch", "rocker_accel"]
    speed = math.sqrt(2**2 + 2 * 3 * math.pi / 2)  # omega^2 = W^2 + 2 AL (theta - theta_0)
    expected = mp_fourbar(**SEED003_LINKAGE, theta=math.pi / 2, branch=1, crank_speed=speed, crank_accel=3)
    assert float(out.splitlines()[2].split()[2]) == pytest.approx(float(expected["phi_accel"]), abs=5e-5)


def test_positions_only_scene_ignores_the_crank_speed(tmp_path, capsys):
    status, out, _ = run(capsys, "run", scene_file(tmp_path, outputs='["C_x", "C_y"]', branch="1"), "--format", "csv")
    assert status == 0 and out.splitlines()[0] == "crank,branch,C_x,C_y"


def test_unassemblable_angles_are_named(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 50\nb = 20\nc = 20\nd = 60\n'
                    "[input]\nangles = [0, 180]\n")
    status, out, err = run(capsys, "run", path, "--format", "csv")
    assert status == 0 and len(out.splitlines()) == 2
    assert "cannot be assembled at crank angles 180 deg" in err


BAD = [
    ('linkage = "fourbar"\nlinkage = "x"\n', "not valid TOML"),
    ('linkage = "fourbar"\ncolour = "red"\n', "unknown key colour"),
    ('outputs = ["rocker"]\n', "missing key linkage"),
    ('linkage = "__import__(\'os\').system(\'true\')"\noutputs = ["rocker"]\n', "no linkage .* in the catalog"),
    ('linkage = 3\noutputs = ["rocker"]\n', "linkage must be a catalog name"),
    ('linkage = "fourbar"\noutputs = "rocker"\n', "outputs must be a non-empty list"),
    ('linkage = "fourbar"\noutputs = []\n', "outputs must be a non-empty list"),
    ('linkage = "fourbar"\noutputs = ["rocker", "piston"]\n', "no output 'piston'"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\nbranch = 2\n', "branch must be one of 1, -1, 'both'"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\nbranch = true\n', "branch must be one of"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\nunits = "grad"\n', "units must be one of 'deg', 'rad'"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\nformat = "xml"\n', "format must be one of"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 1\nb = 1\nc = 1\n', "missing parameters.d"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\nparameters = 3\n', "parameters must be a table"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 1\nb = 1\nc = 1\nd = 1\ne = 1\n',
     "unknown key parameters.e"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = -1\nb = 1\nc = 1\nd = 1\n',
     "parameters.a must be a positive length"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = "1"\nb = 1\nc = 1\nd = 1\n',
     "parameters.a must be a number"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = true\nb = 1\nc = 1\nd = 1\n',
     "parameters.a must be a number"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = nan\nb = 1\nc = 1\nd = 1\n',
     "parameters.a must be finite"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 1\nb = 1\nc = 1\nd = 1\n[input]\nstep = -5\n',
     "step must be positive"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 1\nb = 1\nc = 1\nd = 1\n[input]\n'
     "step = 5\nangles = [1]\n", "either angles or start/stop/step"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 1\nb = 1\nc = 1\nd = 1\n[input]\nangles = []\n',
     "angles needs at least one angle"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 1\nb = 1\nc = 1\nd = 1\n[input]\n'
     'angles = [1, "x"]\n', r"input.angles\[1\] must be a number"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 1\nb = 1\nc = 1\nd = 1\n[input]\nspin = 1\n',
     "unknown key input.spin"),
    ('linkage = "fourbar"\noutputs = ["rocker_speed"]\n[parameters]\na = 1\nb = 1\nc = 1\nd = 1\n[input]\n'
     "speed = 1\naccel = -100\n", "the crank stops"),
    ('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 1\nb = 1\nc = 1\nd = 10\n',
     "cannot be assembled at any requested crank angle"),
]


@pytest.mark.parametrize("text, message", BAD)
def test_bad_scene_files_one_line_exit_2(tmp_path, capsys, text, message):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    status, out, err = run(capsys, "run", path)
    assert status == 2 and out == ""
    assert err.startswith(f"symlink: error: {path}: ") or "cannot be assembled" in err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert re.search(message, err), err


def test_missing_file_and_bad_option(tmp_path, capsys):
    status, _, err = run(capsys, "run", tmp_path / "none.toml")
    assert status == 2 and "cannot read scene file" in err and err.count("\n") == 1
    status, _, err = run(capsys, "run", scene_file(tmp_path), "--format", "xml")
    assert status == 2 and err.count("\n") == 1


def test_a_table_defined_twice_is_one_line_of_bad_toml(tmp_path, capsys):
    path = scene_file(tmp_path)
    path.write_text(path.read_text() + "[input]\n")
    status, _, err = run(capsys, "run", path)
    assert status == 2 and err.count("\n") == 1
    assert "not valid TOML" in err and "('input',) twice" in err, err


# --- a linkage without a closed form: [guess] and Newton's method ---------------------

#: The catalog's Stephenson II (lengths; the two fixed angles in radians, 51.5 and 17.2 degrees, as a scene's
#: [parameters] take them whatever its units) and a guess near one of its assemblies (degrees).
STEPHENSON2_VALUES = dict(a=1, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1, alpha=0.8988445647770797, delta=0.30019663134302466)
STEPHENSON2_GUESS = "[guess]\ncoupler = -33\nmu = -35\nrocker = -73\neta = -68\n"


def stephenson2_scene(tmp_path, guess=STEPHENSON2_GUESS, outputs='["coupler", "mu", "rocker", "eta"]', extra=""):
    path = tmp_path / "six.toml"
    values = "".join(f"{name} = {value}\n" for name, value in STEPHENSON2_VALUES.items())
    path.write_text(f'linkage = "stephenson2"\noutputs = {outputs}\nformat = "csv"\n{extra}\n[parameters]\n{values}'
                    f"[input]\nangles = [0, 50, 100, 150]\n{guess}")
    return path


def test_a_newton_scene_closes_both_loops(tmp_path, capsys):
    """The printed angles close both loops of the linkage file (AB + BC + CF - DF - AD and AB + BE + EH - DH - AD),
    written out here by hand, to 1e-9 of the link lengths."""
    status, out, err = run(capsys, "run", stephenson2_scene(tmp_path))
    assert status == 0, err
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [float(r["crank"]) for r in rows] == [0, 50, 100, 150] and {r["branch"] for r in rows} == {"1"}
    v = STEPHENSON2_VALUES
    alpha, delta = v["alpha"], v["delta"]
    for row in rows:
        theta, beta, mu, phi, eta = (math.radians(float(row[k])) for k in ("crank", "coupler", "mu", "rocker", "eta"))
        z = [cmath_rect(v["a"], theta) + cmath_rect(v["b"], beta) + cmath_rect(v["c"], mu)
             - cmath_rect(v["f"], phi) - v["d"],
             cmath_rect(v["a"], theta) + cmath_rect(v["e"], alpha + beta) + cmath_rect(v["g"], eta)
             - cmath_rect(v["h"], delta + phi) - v["d"]]
        assert max(abs(loop) for loop in z) < 1e-9, (row, z)
    first = rows[0]  # the assembly nearest the guess, not another one
    assert abs(float(first["coupler"]) + 33) < 1 and abs(float(first["rocker"]) + 73) < 1


def cmath_rect(length, angle):
    return complex(length * math.cos(angle), length * math.sin(angle))


def test_a_newton_scene_prints_what_the_table_command_prints(tmp_path, capsys):
    """The same solver through ``symlink table NAME --guess``: the same numbers, the scene's columns only, in
    radians too (the guess in the scene's units)."""
    rad = STEPHENSON2_VALUES
    guess = "[guess]\n" + "".join(f"{k} = {math.radians(x)!r}\n"
                                  for k, x in dict(beta=-33, mu=-35, phi=-73, eta=-68).items())
    path = stephenson2_scene(tmp_path, guess=guess, outputs='["rocker", "eta_speed"]', extra='units = "rad"')
    text = path.read_text().replace("angles = [0, 50, 100, 150]", "angles = [0, 1, 2]\nspeed = 3")
    path.write_text(text)
    status, out, err = run(capsys, "run", path)
    assert status == 0, err
    settings = ",".join(f"{k}={x!r}" for k, x in rad.items())
    status, table, err = run(capsys, "table", "stephenson2", "--set", settings, "--angles", "0,1,2", "--units", "rad",
                             "--crank-speed", "3", "--format", "csv", "--guess", "coupler=-0.5759586531581288,"
                             f"mu={math.radians(-35)!r},rocker={math.radians(-73)!r},eta={math.radians(-68)!r}")
    assert status == 0, err
    expected = [(r["crank"], r["branch"], r["rocker"], r["eta_speed"]) for r in csv.DictReader(io.StringIO(table))]
    assert [tuple(r.values()) for r in csv.DictReader(io.StringIO(out))] == expected
    assert len(expected) == 3 and all(float(r[3]) != 0 for r in expected)


@pytest.mark.parametrize("units", ["deg", "rad"])
def test_a_newton_scene_prints_what_read_scene_returns(tmp_path, capsys, units):
    """``symlink run`` prints the numbers of the Python API's evaluation of the same scene
    (:func:`symlink.io.scene.read_scene`), in degrees and in radians: angles wrapped here by hand to half a turn
    either side of 0, rates and accelerations as they are; the crank column is the sweep, wrapped."""
    from symlink.io.scene import read_scene
    half = 180.0 if units == "deg" else math.pi
    guess = "[guess]\n" + "".join(f"{k} = {x if units == 'deg' else math.radians(x)!r}\n"
                                  for k, x in dict(coupler=-33, mu=-35, rocker=-73, eta=-68).items())
    path = stephenson2_scene(tmp_path, guess=guess, extra=f'units = "{units}"',
                             outputs='["coupler", "mu", "rocker", "eta", "rocker_speed", "eta_accel"]')
    sweep = "angles = [0, 50, 100, 150, 200, 250]" if units == "deg" else "angles = [0, 1, 2, 3, 4]"
    path.write_text(path.read_text().replace("angles = [0, 50, 100, 150]", f"{sweep}\nspeed = 2\naccel = 1"))
    status, out, err = run(capsys, "run", path)
    assert status == 0, err
    rows = list(csv.DictReader(io.StringIO(out)))
    found = read_scene(path)
    result = found.scene.evaluate()[1]

    def wrapped(value):
        shown = math.degrees(value) if units == "deg" else value
        return shown - 2 * half * math.floor((shown + half) / (2 * half))

    assert len(rows) == len(found.angles) == len(result["rocker"])
    for k, row in enumerate(rows):
        assert float(row["crank"]) == pytest.approx(wrapped(math.radians(found.angles[k]) if units == "deg"
                                                            else found.angles[k]), abs=1e-12)
        for column in ("coupler", "mu", "rocker", "eta"):
            assert float(row[column]) == pytest.approx(wrapped(float(result[column][k])), rel=1e-13, abs=1e-12)
        for column in ("rocker_speed", "eta_accel"):
            assert float(row[column]) == float(result[column][k])


NEWTON_BAD = [  # (what is changed in the scene: guess, outputs, extra keys), the message
    (dict(guess="[guess]\ncoupler = -33\nmu = -35\nrocker = -73\nzeta = 1\n"), "stephenson2 has no unknown 'zeta'"),
    (dict(guess="[guess]\ncoupler = -33\nmu = -35\nrocker = -73\neta = \"x\"\n"), "guess.eta must be a number"),
    (dict(guess="[guess]\ncoupler = -33\nmu = -35\nrocker = -73\neta = inf\n"), "guess.eta must be finite"),
    (dict(guess="[guess]\ncoupler = -33\nmu = -35\nrocker = -73\n"),
     r"needs a guess of every unknown \(coupler, mu, rocker, eta\)"),
    (dict(guess=""), r"no closed form: give a \[guess\] table of every unknown \(coupler, mu, rocker, eta\)"),
    (dict(guess="", extra="guess = 3"), "guess must be a table"),
    (dict(outputs='["C_x"]'), r"stephenson2 \(solved by Newton's method\) has no output 'C_x'"),
    (dict(outputs='["mu", "mu"]'), "outputs lists 'mu' more than once"),
    (dict(extra='branch = "both"'), "branch: stephenson2 has no closed form"),
    (dict(extra='[dynamics]\ngravity = 9.81'), "dynamics: stephenson2 has no closed form"),
]


@pytest.mark.parametrize("change, message", NEWTON_BAD)
def test_bad_newton_scenes_one_line_exit_2(tmp_path, capsys, change, message):
    path = stephenson2_scene(tmp_path, **change)
    status, out, err = run(capsys, "run", path)
    assert status == 2 and out == ""
    assert err.startswith(f"symlink: error: {path}: ") and err.count("\n") == 1, err
    assert re.search(message, err), err


def test_a_guess_for_a_closed_form_is_refused(tmp_path, capsys):
    path = scene_file(tmp_path, extra="", sweep="angles = [0]\n[guess]\nphi = 110")
    status, out, err = run(capsys, "run", path)
    assert status == 2 and out == "" and err.count("\n") == 1
    assert "guess: fourbar is solved in closed form, where branch chooses the assembly" in err, err


def test_a_newton_scenes_speed_is_the_finite_difference_of_its_angle(tmp_path, capsys):
    """rocker_speed = dphi/dtheta * crank speed: a central difference of the printed rocker angle (h = 1e-4 deg)."""
    path = stephenson2_scene(tmp_path, outputs='["rocker", "rocker_speed"]')
    path.write_text(path.read_text().replace("angles = [0, 50, 100, 150]", "angles = [0, 49.9999, 50, 50.0001]\n"
                                             "speed = 2.5"))
    status, out, err = run(capsys, "run", path)
    assert status == 0, err
    rows = list(csv.DictReader(io.StringIO(out)))
    low, mid, high = (float(r["rocker"]) for r in rows[1:])
    difference = math.radians(high - low) / math.radians(2e-4) * 2.5
    assert abs(float(rows[2]["rocker_speed"]) - difference) < 1e-6 * max(1.0, abs(difference))
    assert abs(difference) > 0.1  # a rocker that moves there
