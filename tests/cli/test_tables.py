"""Table commands built from catalog entries: inverted-slider-crank, watt2, stephenson2, fivebar.

Every csv row is compared with a 50-digit reference computed here from the
closure equations typed out by hand (``mp_closures``: circle intersections or
``mpmath.findroot``, rates from mpmath linear solves); the crank speed of a
uniformly accelerating crank is recomputed here from ``omega^2 = W^2 + 2 AL
(theta - theta_first)``.  Also: angles that cannot be assembled, reachable
ranges checked against the same references just inside and outside their
ends, the Stephenson II assemblies against an independent multi-start root
search, and bad input (one line, exit 2).
"""
import csv
import io
import json
import math
import pathlib
import re

import mpmath as mp
import numpy as np
import pytest
from scipy.optimize import fsolve

import mp_closures as ref
from test_fourbar_table import run, wrapped_degrees
from symlink.cli.tables import loop_branches
from symlink.numeric.reachability import scanned_range

INVERTED = ["inverted-slider-crank", "--crank", "2", "--ground", "1.2"]
WATT2_P = dict(a=1.0, b=3.5, c=3.0, d=3.2, e=2.0, f=4.0, g=3.0, alpha=0.6, gx=4.5, gy=3.5)
WATT2 = ["watt2", "--crank", "1", "--coupler", "3.5", "--rocker", "3", "--ground", "3.2", "--rocker-arm", "2",
         "--rocker-arm-angle", str(math.degrees(0.6)), "--coupler2", "4", "--output", "3",
         "--output-x", "4.5", "--output-y", "3.5"]
FIVEBAR_P = dict(a=2.0, b=3.0, c=3.0, d=5.0, e=2.0)
FIVEBAR = ["fivebar", "--crank", "2", "--coupler", "3", "--coupler2", "3", "--crank2", "2", "--ground", "5"]
STEPHENSON2_P = dict(a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1, alpha=0.9, delta=0.3)
STEPHENSON2 = ["stephenson2", "--crank", "1", "--coupler", "3.1", "--link-cf", "2.2", "--ground", "4.5",
               "--coupler-arm", "3.9", "--rocker", "3.1", "--link-eh", "4.1", "--rocker-arm", "3.1",
               "--coupler-arm-angle", str(math.degrees(0.9)), "--rocker-arm-angle", str(math.degrees(0.3))]

HEADERS = {
    "inverted-slider-crank": "crank,branch,rocker,slider,rocker_speed,slider_speed,rocker_accel,slider_accel",
    "watt2": "crank,branch,coupler,rocker,coupler2,output,coupler_speed,rocker_speed,coupler2_speed,output_speed,"
             "coupler_accel,rocker_accel,coupler2_accel,output_accel",
    "stephenson2": "crank,branch,coupler,mu,rocker,eta,coupler_speed,mu_speed,rocker_speed,eta_speed,"
                   "coupler_accel,mu_accel,rocker_accel,eta_accel",
    "fivebar": "crank,branch,crank2,coupler,coupler2,coupler_speed,coupler2_speed,coupler_accel,coupler2_accel",
}


def csv_rows(out):
    return list(csv.DictReader(io.StringIO(out)))


def crank_speed(theta, first, speed, accel):
    return math.copysign(math.sqrt(speed**2 + 2 * accel * (theta - first)), speed if speed else accel)


def in_half_turn(degrees):
    """Degrees wrapped to (-180, 180], exactly for whole degrees."""
    wrapped = math.remainder(degrees, 360.0)
    return 180.0 if wrapped == -180.0 else wrapped


def assert_row(row, columns, q, qdot, qddot, size):
    """Angles (degrees, wrapped) and lengths, then speeds and accelerations, against the reference."""
    for k, (name, is_angle) in enumerate(columns):
        if is_angle:
            assert abs(math.remainder(float(row[name]) - wrapped_degrees(float(q[k])), 360)) < 1e-10, name
        else:
            assert abs(float(row[name]) - float(q[k])) < 1e-13 * size, name
        assert abs(float(row[name + "_speed"]) - float(qdot[k])) < 1e-11, name
        assert abs(float(row[name + "_accel"]) - float(qddot[k])) < 1e-9, name


def with_options(argv, **values):
    """argv with the values of some options replaced (option names with _ for -)."""
    argv = list(argv)
    for name, value in values.items():
        argv[argv.index("--" + name.replace("_", "-")) + 1] = value
    return argv


def mp_params(p):
    return {k: mp.mpf(v) for k, v in p.items()}


# --- headers and help ---------------------------------------------------------------------------------

@pytest.mark.parametrize("command", sorted(HEADERS))
def test_help_maps_each_option_to_its_catalog_symbol_and_shows_the_header(capsys, command):
    status, out, _ = run(capsys, command, "--help")
    assert status == 0 and HEADERS[command] in out
    if command == "watt2":
        assert "alpha = angle from DC to DE" in out and "gx = x of the output rocker's pivot G" in out


def test_docs_document_each_header():
    guide = (pathlib.Path(__file__).resolve().parents[2] / "docs" / "howto" / "tables.md").read_text(encoding="utf-8")
    for header in HEADERS.values():
        assert header in guide


# --- inverted slider-crank ---------------------------------------------------------------------------

def test_inverted_slider_crank_rows_match_50_digits(capsys):
    status, out, err = run(capsys, *INVERTED, "--start", "-170", "--step", "40", "--crank-speed", "3",
                           "--crank-accel", "0.5", "--format", "csv")
    assert status == 0 and err == "" and out.splitlines()[0] == HEADERS["inverted-slider-crank"]
    rows = csv_rows(out)
    assert len(rows) == 14 and {r["branch"] for r in rows} == {"1"}   # one assembly, printed as +1
    p = dict(a=2.0, d=1.2)
    for k, row in enumerate(rows):
        theta = math.radians(-170 + 40 * k)
        w = crank_speed(theta, math.radians(-170), 3, 0.5)
        with mp.workdps(ref.DPS):
            start = ref.inverted_positions([mp.mpf(theta)], mp_params(p))
        q, qdot, qddot, _ = ref.kinematics(ref.inverted_closure, [theta], start, p, [w], [0.5])
        assert float(row["crank"]) == in_half_turn(-170 + 40 * k)
        assert_row(row, [("rocker", True), ("slider", False)], q, qdot, qddot, 3.2)


def test_inverted_slider_crank_leaves_out_the_undetermined_rocker(capsys):
    # crank = ground: at crank angle 0, B sits on the pivot D and the rocker angle follows from nothing.
    status, out, err = run(capsys, "inverted-slider-crank", "--crank", "1", "--ground", "1", "--step", "90",
                           "--format", "csv")
    assert status == 0
    assert [float(r["crank"]) for r in csv_rows(out)] == [90.0, 180.0, -90.0]
    assert err.count("\n") == 1 and "cannot be assembled at crank angles 0 deg" in err
    assert "B passes over the rocker pivot D" in err


def test_inverted_slider_crank_has_no_branch_option(capsys):
    status, out, err = run(capsys, *INVERTED, "--branch", "-1")
    assert status == 2 and out == "" and "unrecognized arguments: --branch" in err


# --- Watt II ------------------------------------------------------------------------------------------

def test_watt2_rows_match_50_digits_on_every_branch_combination(capsys):
    status, out, err = run(capsys, *WATT2, "--step", "60", "--crank-speed", "2", "--crank-accel", "1.5",
                           "--format", "csv")
    assert status == 0 and err == "" and out.splitlines()[0] == HEADERS["watt2"]
    rows = csv_rows(out)
    assert [r["branch"] for r in rows[:4]] == ["+1/+1", "+1/-1", "-1/+1", "-1/-1"] and len(rows) == 24
    columns = [("coupler", True), ("rocker", True), ("coupler2", True), ("output", True)]
    for row in rows:
        theta = math.radians(float(row["crank"])) % (2 * math.pi)
        signs = tuple(int(s) for s in row["branch"].split("/"))
        w = crank_speed(theta, 0.0, 2, 1.5)
        with mp.workdps(ref.DPS):
            start = ref.watt2_positions([mp.mpf(theta)], mp_params(WATT2_P), signs)
        q, qdot, qddot, _ = ref.kinematics(ref.watt2_closure, [theta], start, WATT2_P, [w], [1.5], refine=False)
        assert_row(row, columns, q, qdot, qddot, 30)


@pytest.mark.parametrize("branch, expected", [
    ("+1,-1", ["+1/-1"]), ("-1", ["-1/-1"]), ("1", ["+1/+1"]), ("both,+1", ["+1/+1", "-1/+1"]),
    ("-1,both", ["-1/+1", "-1/-1"]), ("both", ["+1/+1", "+1/-1", "-1/+1", "-1/-1"]),
])
def test_watt2_branch_takes_one_sign_a_loop(capsys, branch, expected):
    status, out, _ = run(capsys, *WATT2, "--angles", "30", "--branch", branch, "--format", "json")
    assert status == 0 and [r["branch"] for r in json.loads(out)] == expected


def test_watt2_table_shows_the_branch_of_each_loop(capsys):
    _, out, _ = run(capsys, *WATT2, "--angles", "30", "--branch", "+1,-1")
    header, row = out.splitlines()
    names = [name for name in header.split() if not name.startswith("(")]  # units in the header: crank (deg)
    assert names == HEADERS["watt2"].split(",") and row.split()[:2] == ["30.0000", "+1/-1"]
    assert header.split()[:2] == ["crank", "(deg)"]


def spans_in(message):
    """The [low, high] deg intervals of a message."""
    return [(float(a), float(b)) for a, b in re.findall(r"\[([-\d.e+]+), ([-\d.e+]+)\] deg", message)]


def watt2_closes(theta_deg, p, signs):
    try:
        with mp.workdps(30):
            ref.watt2_positions([mp.radians(theta_deg)], mp_params(p), signs)
    except ValueError:
        return False
    return True


def test_watt2_unassembled_angles_are_named_branch_by_branch_with_the_scanned_range(capsys):
    p = dict(WATT2_P, f=2.0, g=1.0)   # a short output dyad: only part of the turn closes
    argv = with_options(WATT2, coupler2="2", output="1")
    status, out, err = run(capsys, *argv, "--step", "15", "--format", "csv")
    assert status == 0
    printed = {(float(r["crank"]), r["branch"]) for r in csv_rows(out)}
    lines = err.splitlines()
    assert len(lines) == 4 and all(line.startswith("symlink: branch ") for line in lines)
    for line in lines:
        label = line.split()[2]
        signs = tuple(int(s) for s in label.split("/"))
        named = [float(v) for v in re.search(r"crank angles (.*?) deg", line).group(1).split(", ")]
        for k in range(24):
            angle = in_half_turn(15 * k)
            assert ((angle, label) in printed) == watt2_closes(angle, p, signs) == (angle not in named)
        spans = spans_in(line)
        if "none" in line:
            assert spans == [] and not any(watt2_closes(t, p, signs) for t in range(0, 360, 3))
        for low, high in spans:   # printed to 6 digits: step 0.01 deg in and out of each end
            assert watt2_closes(low + 0.01, p, signs) and watt2_closes(high - 0.01, p, signs)
            assert not watt2_closes(low - 0.01, p, signs) and not watt2_closes(high + 0.01, p, signs)


# --- five-bar --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("ratio", [0.0, -1.0, 0.5])
def test_fivebar_rows_match_50_digits(capsys, ratio):
    status, out, err = run(capsys, *FIVEBAR, "--crank2-angle", "126", "--crank2-ratio", str(ratio),
                           "--angles", "-40,-10,20,50", "--crank-speed", "1.5", "--crank-accel", "2", "--format", "csv")
    assert status == 0 and out.splitlines()[0] == HEADERS["fivebar"]
    rows = csv_rows(out)
    assert rows and len(rows) + err.count(",") >= 4
    for row in rows:
        theta = math.radians(float(row["crank"]))
        psi = math.radians(126) + ratio * theta
        assert abs(float(row["crank2"]) - wrapped_degrees(psi)) < 1e-12
        w = crank_speed(theta, math.radians(-40), 1.5, 2)
        with mp.workdps(ref.DPS):
            start = ref.fivebar_positions([mp.mpf(theta), mp.mpf(psi)], mp_params(FIVEBAR_P), int(row["branch"]))
        q, qdot, qddot, _ = ref.kinematics(ref.fivebar_closure, [theta, psi], start, FIVEBAR_P,
                                           [w, ratio * w], [2, ratio * 2], refine=False)
        assert_row(row, [("coupler", True), ("coupler2", True)], q, qdot, qddot, 15)


def fivebar_closes(theta_deg, psi_deg):
    try:
        with mp.workdps(30):
            ref.fivebar_positions([mp.radians(theta_deg), mp.radians(psi_deg)], mp_params(FIVEBAR_P), 1)
    except ValueError:
        return False
    return True


@pytest.mark.parametrize("ratio", ["0", "2"])
def test_fivebar_reachable_range_exact_held_still_and_scanned_when_geared(capsys, ratio):
    status, out, err = run(capsys, *FIVEBAR, "--crank2-angle", "126", "--crank2-ratio", ratio, "--step", "20",
                           "--branch", "+1", "--format", "csv")
    assert status == 0 and err.count("\n") == 1 and "symlink: cannot be assembled at crank angles" in err
    psi = lambda theta: 126 + float(ratio) * theta   # noqa: E731
    printed = {float(r["crank"]) for r in csv_rows(out)}
    for k in range(18):
        angle = in_half_turn(20 * k)
        assert (angle in printed) == fivebar_closes(angle, psi(angle))
    spans = spans_in(err)
    assert spans
    for low, high in spans:
        assert fivebar_closes(low + 1e-3, psi(low + 1e-3)) and fivebar_closes(high - 1e-3, psi(high - 1e-3))
        assert not fivebar_closes(low - 1e-3, psi(low - 1e-3)) and not fivebar_closes(high + 1e-3, psi(high + 1e-3))


def test_fivebar_non_integer_ratio_says_the_range_is_not_computed(capsys):
    status, _, err = run(capsys, *FIVEBAR, "--crank2-angle", "0", "--crank2-ratio", "0.5", "--step", "20")
    assert status == 0 and "not periodic in the crank angle" in err


def test_fivebar_never_assembled_exits_2(capsys):
    status, out, err = run(capsys, "fivebar", "--crank", "1", "--coupler", "1", "--coupler2", "1", "--crank2", "1",
                           "--ground", "10", "--crank2-angle", "0")
    assert status == 2 and out == "" and err.count("\n") == 1
    assert "none: the links cannot close at any crank angle" in err


# --- Stephenson II ------------------------------------------------------------------------------------

def stephenson2_reference(thetas, start, w, al):
    solved = ref.continue_sweep(ref.stephenson2_closure, [(t,) for t in thetas], start, STEPHENSON2_P, substeps=6)
    return [ref.kinematics(ref.stephenson2_closure, [t], q, STEPHENSON2_P, [crank_speed(t, thetas[0], w, al)], [al],
                           refine=False)[:3] for t, q in zip(thetas, solved)]


def independent_assemblies(theta, p=STEPHENSON2_P):
    """(beta, phi) of every assembly at theta: multi-start fsolve on |C - F| = c, |E - H| = g."""

    def equations(x):
        beta, phi = x
        B = p["a"] * np.exp(1j * theta)
        C, E = B + p["b"] * np.exp(1j * beta), B + p["e"] * np.exp(1j * (beta + p["alpha"]))
        F, H = p["d"] + p["f"] * np.exp(1j * phi), p["d"] + p["h"] * np.exp(1j * (phi + p["delta"]))
        return [abs(C - F) ** 2 - p["c"] ** 2, abs(E - H) ** 2 - p["g"] ** 2]

    found = []
    for beta in np.linspace(-math.pi, math.pi, 16, endpoint=False):
        for phi in np.linspace(-math.pi, math.pi, 16, endpoint=False):
            x, _, status, _ = fsolve(equations, [beta, phi], full_output=True, xtol=1e-13)
            if status == 1 and max(abs(v) for v in equations(x)) < 1e-10:
                x = [math.remainder(v, 2 * math.pi) for v in x]
                if not any(max(abs(math.remainder(a - b, 2 * math.pi)) for a, b in zip(x, y)) < 1e-7 for y in found):
                    found.append(x)
    return sorted(found)


def test_stephenson2_lists_every_assembly_at_the_first_angle(capsys):
    status, out, _ = run(capsys, *STEPHENSON2, "--list-assemblies", "--start", "20", "--format", "csv")
    assert status == 0 and out.splitlines()[0] == "crank,coupler,mu,rocker,eta"
    rows = csv_rows(out)
    expected = independent_assemblies(math.radians(20))
    assert len(rows) == len(expected) == 4
    for row, (beta, phi) in zip(rows, expected):
        assert float(row["crank"]) == 20.0
        assert abs(float(row["coupler"]) - math.degrees(beta)) < 1e-8
        assert abs(float(row["rocker"]) - wrapped_degrees(phi)) < 1e-8
        q = [math.radians(float(row[n])) for n in ("coupler", "mu", "rocker", "eta")]
        with mp.workdps(ref.DPS):
            residual = ref.stephenson2_closure([mp.radians(20)], [mp.mpf(v) for v in q], mp_params(STEPHENSON2_P))
        assert max(abs(float(v)) for v in residual) < 1e-12


def test_stephenson2_default_assembly_rows_match_a_50_digit_continuation(capsys):
    # The default: the assemblies at the first angle in order of the coupler angle; the first one
    # (coupler -33.17 deg) continues over the whole turn.
    status, out, err = run(capsys, *STEPHENSON2, "--step", "60", "--crank-speed", "2", "--crank-accel", "0.5",
                           "--format", "csv")
    assert status == 0 and err == "" and out.splitlines()[0] == HEADERS["stephenson2"]
    rows = csv_rows(out)
    first = independent_assemblies(0.0)[0]
    assert abs(math.radians(float(rows[0]["coupler"])) - first[0]) < 1e-9
    start = [math.radians(float(rows[0][n])) for n in ("coupler", "mu", "rocker", "eta")]
    thetas = [math.radians(60 * k) for k in range(6)]
    columns = [("coupler", True), ("mu", True), ("rocker", True), ("eta", True)]
    for row, (q, qdot, qddot) in zip(rows, stephenson2_reference(thetas, start, 2, 0.5)):
        assert row["branch"] == "1"
        assert_row(row, columns, q, qdot, qddot, 20)


# Six assemblies at crank angle 0; the two of smallest coupler angle meet a dead centre within a turn.
AWKWARD_P = dict(a=1.0, b=2.6, c=2.8, d=4.5, e=2.8, f=4.3, g=3.6, h=2.8, alpha=1.5, delta=1.5)
AWKWARD = ["stephenson2", "--crank", "1", "--coupler", "2.6", "--link-cf", "2.8", "--ground", "4.5",
           "--coupler-arm", "2.8", "--rocker", "4.3", "--link-eh", "3.6", "--rocker-arm", "2.8",
           "--coupler-arm-angle", "1.5", "--rocker-arm-angle", "1.5", "--units", "rad", "--step", "0.5"]


def test_stephenson2_default_skips_assemblies_that_do_not_get_through(capsys):
    _, out, _ = run(capsys, *AWKWARD, "--list-assemblies", "--format", "json")
    listed = json.loads(out)
    expected = independent_assemblies(0.0, AWKWARD_P)
    assert len(listed) == len(expected) == 6
    assert all(abs(r["coupler"] - beta) < 1e-9 and abs(r["rocker"] - math.remainder(phi, 2 * math.pi)) < 1e-9
               for r, (beta, phi) in zip(listed, expected))
    for first in listed[:2]:   # each of the first two stops with one line
        guess = ",".join(f"{name}={first[name]!r}" for name in ("coupler", "mu", "rocker", "eta"))
        status, out, err = run(capsys, *AWKWARD, "--guess", guess)
        assert status == 2 and out == "" and err.count("\n") == 1
    status, out, err = run(capsys, *AWKWARD, "--format", "json")
    rows = json.loads(out)
    assert status == 0 and err == "" and len(rows) == 13
    assert abs(rows[0]["coupler"] - listed[2]["coupler"]) < 1e-12 and abs(rows[0]["eta"] - listed[2]["eta"]) < 1e-12


def test_stephenson2_guess_picks_the_nearest_assembly(capsys):
    status, out, _ = run(capsys, *STEPHENSON2, "--angles", "0,30,90", "--guess", "rocker=75,mu=20", "--format", "csv")
    assert status == 0
    rows = csv_rows(out)
    beta, phi = independent_assemblies(0.0)[-1]   # the assembly with rocker 80.93 deg
    assert abs(math.radians(float(rows[0]["rocker"])) - phi) < 1e-9
    start = [math.radians(float(rows[0][n])) for n in ("coupler", "mu", "rocker", "eta")]
    reference = stephenson2_reference([0.0, math.radians(30), math.radians(90)], start, 0, 0)
    for row, (q, qdot, qddot) in zip(rows, reference):
        assert_row(row, [("coupler", True), ("mu", True), ("rocker", True), ("eta", True)], q, qdot, qddot, 20)


def test_stephenson2_guess_in_radians(capsys):
    _, out, _ = run(capsys, *STEPHENSON2[:-4], "--coupler-arm-angle", "0.9", "--rocker-arm-angle", "0.3",
                    "--units", "rad", "--angles", "0", "--guess", "rocker=1.4", "--format", "csv")
    assert abs(float(csv_rows(out)[0]["rocker"]) - independent_assemblies(0.0)[-1][1]) < 1e-9


def test_stephenson2_that_cannot_continue_is_one_line_exit_2(capsys):
    # The folded assembly (rocker 165 deg at crank 0) meets a dead centre near 54.65 deg.
    status, out, err = run(capsys, *STEPHENSON2, "--step", "10", "--guess", "rocker=165")
    assert status == 2 and out == "" and err.count("\n") == 1
    assert err.startswith("symlink: error: ") and "54.6" in err


def test_stephenson2_not_assembled_at_the_first_angle_exits_2(capsys):
    status, out, err = run(capsys, *with_options(STEPHENSON2, ground="45"))
    assert status == 2 and out == "" and err.count("\n") == 1
    assert "cannot be assembled at the first crank angle, 0 deg" in err


# --- helpers --------------------------------------------------------------------------------------------

def test_scanned_range_across_the_half_turn_and_in_pieces():
    half = scanned_range(lambda t: np.cos(t) <= -0.5)
    assert [tuple(round(math.degrees(x), 9) for x in s) for s in half] == [(120.0, 240.0)]
    pieces = scanned_range(lambda t: np.abs(np.sin(t)) <= 0.5)
    assert [tuple(round(math.degrees(x), 9) for x in s) for s in pieces] == [(-30.0, 30.0), (150.0, 210.0)]
    assert scanned_range(lambda t: t == t) == [(-math.pi, math.pi)] and scanned_range(lambda t: t != t) == []


def test_loop_branches_parses_one_item_or_one_a_loop():
    parse = loop_branches(2)
    assert parse("both") == [(1, -1), (1, -1)] and parse("-1") == [(-1,), (-1,)]
    assert parse("+1, -1") == [(1,), (-1,)]


# --- bad input --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("argv", [
    [*INVERTED[:2], "0", *INVERTED[3:]],
    [*INVERTED[:4], "nan"],
    [*INVERTED, "--bogus", "1"],
    [*INVERTED, "--step", "0"],
    [*WATT2, "--branch", "+1,-1,1"],
    [*WATT2, "--branch", "2"],
    [*WATT2, "--branch", "+1,"],
    [*WATT2, "--rocker-arm-angle", "inf"],
    [*WATT2, "--output", "-3"],
    [*WATT2, "--units", "grad"],
    [*WATT2[:-2]],                                        # --output-y is required
    [*FIVEBAR],                                           # --crank2-angle is required
    [*FIVEBAR, "--crank2-angle", "10", "--crank2-ratio", "x"],
    [*FIVEBAR, "--crank2-angle", "10", "--branch", "+1,-1"],
    [*FIVEBAR, "--crank2-angle", "10", "--crank2", "0"],
    [*STEPHENSON2, "--guess", "rocker"],
    [*STEPHENSON2, "--guess", "rocker=abc"],
    [*STEPHENSON2, "--guess", "phi=80"],
    [*STEPHENSON2, "--branch", "+1"],
    [*STEPHENSON2, "--link-eh", "0"],
    [*STEPHENSON2, "--angles", "10", "--step", "5"],
])
def test_bad_input_one_line_exit_2(capsys, argv):
    status, out, err = run(capsys, *argv)
    assert status == 2 and out == ""
    assert err.startswith("symlink: error: ") and err.count("\n") == 1


def test_commands_build_their_linkage_only_when_used(monkeypatch, capsys):
    import symlink.cli.tables as tables  # a table command reads its linkage's facts (TableSource) when it is used
    from symlink.cli import build_parser

    def refuse(name):
        raise AssertionError(f"{name} built at start-up")
    monkeypatch.setattr(tables, "TableSource", refuse)
    parser = build_parser()  # every command registered, no linkage built
    assert parser.parse_args(["plan", "fourbar"]).command == "plan"
    with pytest.raises(AssertionError, match="watt2 built"):
        parser.parse_args(["watt2", "--help"])


def test_the_former_command_name_prints_the_same_table_with_a_note(capsys):
    # symlink stephenson3 was this table's command when symlink numbered Stephenson II and III the other way.
    status, out, err = run(capsys, *STEPHENSON2, "--step", "90", "--format", "csv")
    assert status == 0 and err == ""
    status, former, note = run(capsys, "stephenson3", *STEPHENSON2[1:], "--step", "90", "--format", "csv")
    assert status == 0 and former == out
    assert note.count("\n") == 1 and "symlink: warning: 'stephenson3' is symlink's former name of stephenson-ii" in note
    from symlink.cli.tables import FORMER_TABLE_COMMANDS
    from symlink.mechanism.atlas import FORMER_SIX_BAR_NAMES
    from symlink.io.linkage_file import SIX_BAR_ENTRIES
    assert FORMER_TABLE_COMMANDS == {name: SIX_BAR_ENTRIES[six] for name, six in FORMER_SIX_BAR_NAMES.items()}
