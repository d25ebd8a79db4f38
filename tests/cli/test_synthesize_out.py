"""Synthesis ends in a design you can use (issue 32, item 2): every route writes ``--out`` as a linkage file.

Synthesize (a four-bar route, the general route) -> ``--out`` -> ``symlink table`` and ``symlink analyze`` on
the written file: the numbers printed are the numbers written, the table's angles at the design's inputs are
those of a four-bar solved here by intersecting two circles from the printed numbers (no symlink solver),
its traced point reaches the targets as the design says, and the worst transmission angle printed over the
motion the design runs equals a dense scan of the triangle's angle here (and, for a crank, ``analyze``'s).
"""
from __future__ import annotations

import cmath
import json
import math

import numpy
import pytest

from symlink.cli import main
from symlink.io.linkage_file import read_linkage

POINTS = "x,y\n1.0,2.0\n1.5,2.4\n2.0,2.5\n2.5,2.3\n3.0,1.9\n"


def hand_fourbar(theta, a, b, c, d, branch, pivot=0j, frame=0.0):
    """B, C, the coupler's and the rocker's absolute angles at the crank angle ``theta`` from the ground line
    (branch +1: C to the left of B -> D)."""
    turn = cmath.exp(1j * frame)
    B = pivot + a * cmath.exp(1j * (theta + frame))
    D = pivot + d * turn
    e = D - B
    L = abs(e)
    along = (b * b - c * c + L * L) / (2 * L)
    C = B + e / L * (along + 1j * branch * math.sqrt(b * b - along * along))
    return B, C, cmath.phase(C - B), cmath.phase(C - D)


def hand_worst_transmission(a, b, c, d, low, high, samples=200_001):
    """min(mu, pi - mu) over crank angles low..high, mu from the triangle over the diagonal BD."""
    theta = numpy.linspace(low, high, samples)
    bd2 = a * a + d * d - 2 * a * d * numpy.cos(theta)
    mu = numpy.arccos(numpy.clip((b * b + c * c - bd2) / (2 * b * c), -1, 1))
    return float(numpy.min(numpy.minimum(mu, math.pi - mu)))


def run(capsys, *arguments) -> tuple[int, str, str]:
    code = main(list(arguments))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def csv_rows(text: str) -> list[dict[str, str]]:
    lines = text.strip().splitlines()
    return [dict(zip(lines[0].split(","), line.split(","))) for line in lines[1:]]


@pytest.fixture()
def points(tmp_path):
    path = tmp_path / "points.csv"
    path.write_text(POINTS)
    return path


def test_fourbar_path_route_writes_the_design_that_table_and_analyze_read(tmp_path, points, capsys):
    out = tmp_path / "design.toml"
    code, text, err = run(capsys, "synthesize", "path", str(points), "--designs", "1", "--starts", "2",
                          "--grashof", "crank-rocker", "--format", "json", "--out", str(out))
    assert code == 0 and f"wrote {out}" in err
    (row,) = json.loads(text)
    a, b, c, d, u, v, x0, y0 = (float(row[k]) for k in ("crank", "coupler", "rocker", "ground", "u", "v", "x0", "y0"))
    frame, branch = math.radians(float(row["frame"])), int(row["branch"])
    written = read_linkage(out)
    assert {k: written.defaults[k] for k in "abcduv"} == dict(a=a, b=b, c=c, d=d, u=u, v=v)  # printed = written
    assert (written.defaults["place_x"], written.defaults["place_y"]) == (x0, y0)
    assert written.defaults["place_angle"] == pytest.approx(frame, abs=1e-13)
    assert "P" in written.linkage.points  # the traced point
    crank_angles = row["theta"]
    # table: the file's own assembly (+1) is the design's, at the design's crank angles
    code, text, _ = run(capsys, "table", str(out), "--angles", ",".join(map(repr, crank_angles)), "--branch", "+1",
                        "--format", "csv")
    assert code == 0
    targets = [complex(*map(float, line.split(","))) for line in POINTS.splitlines()[1:]]
    for theta_deg, table_row, target in zip(crank_angles, csv_rows(text), targets):
        B, C, beta, phi = hand_fourbar(math.radians(theta_deg), a, b, c, d, branch, complex(x0, y0), frame)
        assert math.radians(float(table_row["coupler"])) == pytest.approx(beta, abs=1e-6)
        assert math.radians(float(table_row["rocker"])) == pytest.approx(phi, abs=1e-6)
        P = B + complex(u, v) * cmath.exp(1j * beta)
        assert abs(P - target) < 1e-6  # the traced point reaches the target (error ~1e-15 of the size)
    # the worst transmission over the full turn (a crank): printed = analyze's = a dense scan here
    worst = math.radians(float(row["worst_transmission"]))
    assert worst == pytest.approx(hand_worst_transmission(a, b, c, d, -math.pi, math.pi), abs=1e-6)
    assert "over the full turn" in err and row["transmission_over"] == "full turn"
    code, text, _ = run(capsys, "analyze", str(out), "--format", "json")
    (loop,) = json.loads(text)["transmission"]
    assert math.radians(min(loop["minimum"], 180 - loop["maximum"])) == pytest.approx(worst, abs=1e-9)
    assert ("warning: design 1 transmits badly" in err) == (worst < math.radians(30))
    # tolerance of the written file: its six lengths banded (a..d, u, v), never where it stands (place_*)
    theta = math.radians(crank_angles[0])

    def point_x(**change):
        values = {**dict(a=a, b=b, c=c, d=d, u=u, v=v), **change}
        B, _, beta, _ = hand_fourbar(theta, *(values[k] for k in "abcd"), branch, complex(x0, y0), frame)
        return (B + complex(values["u"], values["v"]) * cmath.exp(1j * beta)).real

    slopes = [(point_x(**{k: value + 1e-6}) - point_x(**{k: value - 1e-6})) / 2e-6
              for k, value in dict(a=a, b=b, c=c, d=d, u=u, v=v).items()]
    code, text, err = run(capsys, "tolerance", str(out), "--tolerance", "0.01", "--output", "P_x",
                          "--angles", repr(crank_angles[0]), "--format", "csv")
    assert code == 0 and "place" not in err
    assert float(csv_rows(text)[0]["worst_case"]) == pytest.approx(0.01 * sum(map(abs, slopes)), rel=1e-6)


def test_general_route_prints_the_scaled_lengths_it_writes(tmp_path, points, capsys):
    out = tmp_path / "general.toml"
    code, text, err = run(capsys, "synthesize", "path", "fourbar", str(points), "--point", "C", "--free", "a,b,c,d",
                          "--starts", "2", "--format", "json", "--out", str(out))
    assert code == 0
    record = json.loads(text)
    placement, design = record["placement"], record["design"]
    assert placement["scale"] != 1.0  # the lengths printed are those written, after scaling
    written = read_linkage(out).defaults
    assert {k: written[k] for k in "abcd"} == design
    assert (written["place_x"], written["place_y"]) == (placement["x0"], placement["y0"])
    a, b, c, d = (design[k] for k in "abcd")
    branch = record["branches"]["branch"]
    frame = math.radians(placement["angle"])
    code, text, _ = run(capsys, "table", str(out), "--angles", ",".join(map(repr, record["inputs"])),
                        "--branch", "+1", "--format", "csv")
    assert code == 0
    for theta_deg, row, target, error in zip(record["inputs"], csv_rows(text), record["targets"], record["errors"]):
        _, C, beta, phi = hand_fourbar(math.radians(theta_deg), a, b, c, d, branch,
                                       complex(placement["x0"], placement["y0"]), frame)
        assert math.radians(float(row["coupler"])) == pytest.approx(beta, abs=1e-6)
        assert math.radians(float(row["rocker"])) == pytest.approx(phi, abs=1e-6)
        assert abs(C - complex(*target)) == pytest.approx(error, abs=1e-6)  # the traced point C
    low, high = (math.radians(x) for x in (min(record["inputs"]), max(record["inputs"])))
    assert record["transmission_over"].startswith("rocking range")
    assert math.radians(record["worst_transmission"]) == pytest.approx(hand_worst_transmission(a, b, c, d, low, high),
                                                                       abs=1e-6)
    assert ("warning: the design transmits badly" in err) == (record["worst_transmission"] < 30)


def test_fourbar_function_route_writes_its_design(tmp_path, capsys):
    """Three precision points: the written four-bar's rocker passes through them (offsets as the file says)."""
    pairs = tmp_path / "pairs.csv"
    pairs.write_text("theta,phi\n0,60\n30,80\n60,95\n")
    out = tmp_path / "function.toml"
    code, text, err = run(capsys, "synthesize", "function", str(pairs), "--format", "csv", "--out", str(out))
    assert code == 0
    row = csv_rows(text)[0]
    a, b, c, d = (float(row[k]) for k in ("crank", "coupler", "rocker", "ground"))
    assert {k: read_linkage(out).defaults[k] for k in "abcd"} == dict(a=a, b=b, c=c, d=d)
    offset, rocker_offset = float(row["crank_offset"]), float(row["rocker_offset"])
    code, text, _ = run(capsys, "table", str(out), "--angles", ",".join(repr(t + offset) for t in (0, 30, 60)),
                        "--branch", row["branch"], "--format", "csv")
    for wanted, table_row in zip((60, 80, 95), csv_rows(text)):
        turned = float(table_row["rocker"]) - rocker_offset - wanted
        assert abs(math.remainder(turned, 360)) < 1e-6
    theta = [math.radians(t + offset) for t in (0, 30, 60)]
    hand = hand_worst_transmission(a, b, c, d, -math.pi, math.pi) if "over the full turn" in err else \
        hand_worst_transmission(a, b, c, d, min(theta), max(theta))
    assert math.radians(float(row["worst_transmission"])) == pytest.approx(hand, abs=1e-6)


HOEKEN_JOINTS = """name = "hoeken"
driver = "A"

[links]
ground = ["A", "D"]
crank = ["A", "B"]
coupler = ["B", "C", "P"]
rocker = ["D", "C"]

[joints]
A = [0, 0]
B = [0, 1]
C = [2, 2.5]
D = [2, 0]
P = [4, 4]
"""


@pytest.mark.slow
def test_a_joints_file_synthesized_with_a_transmission_angle_then_every_command_reads_the_design(tmp_path, capsys):
    """Joints file -> synthesize path (--min-transmission 35 --full-rotation) -> --out -> analyze, table, parts and
    tolerance on the written file: the same numbers everywhere, the units asked for, the traced point P in the
    parts, and the transmission angle held over the full turn the crank runs (Hoeken's own linkage falls to
    23.1 deg at theta = 0, so the targets traced from it cannot be reached exactly)."""
    linkage = tmp_path / "hoeken.toml"
    linkage.write_text(HOEKEN_JOINTS)
    # Hoeken's P (on the coupler line B->C, |BP| = 5) at six crank angles, by hand
    inputs = [60.0, 90.0, 120.0, 150.0, 180.0, 210.0]
    rows = ["input,x,y"]
    for q in inputs:
        B, C, _, _ = hand_fourbar(math.radians(q), 1.0, 2.5, 2.5, 2.0, 1)
        P = B + 5.0 * (C - B) / abs(C - B)
        rows.append(f"{q!r},{P.real!r},{P.imag!r}")
    targets = tmp_path / "targets.csv"
    targets.write_text("\n".join(rows) + "\n")
    assert hand_worst_transmission(1.0, 2.5, 2.5, 2.0, -math.pi, math.pi) < math.radians(35)
    out = tmp_path / "design.toml"
    code, text, err = run(capsys, "synthesize", "path", str(linkage), str(targets), "--point", "P", "--free",
                          "AB,BC,DC,AD,BP", "--min-transmission", "35", "--full-rotation", "--starts", "2",
                          "--format", "json", "--out", str(out))
    assert code == 0, err
    record = json.loads(text)
    written = read_linkage(out).defaults
    design = record["design"]
    assert {k: written[k] for k in ("AB", "BC", "DC", "AD", "BP")} == {k: design[k] for k in ("AB", "BC", "DC", "AD",
                                                                                               "BP")}
    a, b, c, d, bp = (design[k] for k in ("AB", "BC", "DC", "AD", "BP"))
    shortest, longest = min(a, b, c, d), max(a, b, c, d)
    assert shortest in (a, d) and shortest + longest < a + b + c + d - shortest - longest  # the crank turns
    # held over the full turn, in the search and in what is printed: a dense scan here agrees
    worst = hand_worst_transmission(a, b, c, d, -math.pi, math.pi)
    assert worst >= math.radians(35) - math.radians(1e-6)
    assert record["transmission_over"] == "full turn"
    assert math.radians(record["worst_transmission"]) == pytest.approx(worst, abs=1e-6)
    assert any(text.startswith("transmission angle at ABCD >= 35 deg over the full turn")
               for text in record["constraints"])
    assert "warning" not in err
    # analyze, in radians as asked: the same worst over the full turn
    code, text, _ = run(capsys, "analyze", str(out), "--format", "json", "--units", "rad")
    analysis = json.loads(text)
    (loop,) = analysis["transmission"]
    assert analysis["full_turn"] and min(loop["minimum"], math.pi - loop["maximum"]) == pytest.approx(worst, abs=1e-6)
    # table at the design's inputs: coupler and rocker angles by hand, and P within the printed error of its target
    placement = record["placement"]
    pivot, frame = complex(placement["x0"], placement["y0"]), math.radians(placement["angle"])
    branch = record["branches"]["branch"]
    code, text, _ = run(capsys, "table", str(out), "--angles", ",".join(map(repr, record["inputs"])), "--branch",
                        "+1", "--format", "csv")
    assert code == 0
    for theta_deg, row, target, error in zip(record["inputs"], csv_rows(text), record["targets"], record["errors"]):
        B, _, beta, phi = hand_fourbar(math.radians(theta_deg), a, b, c, d, branch, pivot, frame)
        assert math.radians(float(row["coupler"])) == pytest.approx(beta, abs=1e-6)
        assert math.radians(float(row["rocker"])) == pytest.approx(phi, abs=1e-6)
        P = B + bp * cmath.exp(1j * beta)
        assert abs(P - complex(*target[1:])) == pytest.approx(error, abs=1e-6)
    # parts: the coupler carries the traced point P, |BP| as written and |CP| = |BP - BC| (P on the line B->C)
    code, text, _ = run(capsys, "parts", str(out), "--pin-diameter", "0.1", "--format", "csv")
    assert code == 0
    parts = {(row["part"], row["dimension"]): float(row["length"]) for row in csv_rows(text)}
    assert [parts[key] for key in (("coupler", "BP"), ("coupler", "BC"), ("crank", "AB"), ("rocker", "DC"),
                                   ("ground", "AD"), ("coupler", "CP"))] == pytest.approx([bp, b, a, c, d, abs(bp - b)],
                                                                                         rel=1e-12)
    # tolerance of P_x at the first target: the worst case is the band times the sum of |slopes|, by hand
    theta = math.radians(record["inputs"][0])

    def point_x(**change):
        values = {**dict(AB=a, BC=b, DC=c, AD=d, BP=bp), **change}
        B, _, beta, _ = hand_fourbar(theta, values["AB"], values["BC"], values["DC"], values["AD"], branch, pivot,
                                     frame)
        return (B + values["BP"] * cmath.exp(1j * beta)).real

    slopes = [(point_x(**{k: v + 1e-6}) - point_x(**{k: v - 1e-6})) / 2e-6
              for k, v in dict(AB=a, BC=b, DC=c, AD=d, BP=bp).items()]
    code, text, _ = run(capsys, "tolerance", str(out), "--tolerance", "0.01", "--output", "P_x",
                        "--angles", repr(record["inputs"][0]), "--format", "csv")
    assert code == 0
    assert float(csv_rows(text)[0]["worst_case"]) == pytest.approx(0.01 * sum(map(abs, slopes)), rel=1e-6)


def test_fourbar_path_route_refuses_a_transmission_angle_no_design_holds_in_one_line(tmp_path, points, capsys):
    out = tmp_path / "never.toml"
    code, _, err = run(capsys, "synthesize", "path", str(points), "--starts", "2", "--min-transmission", "89.5",
                       "--out", str(out))
    assert code == 2 and len(err.strip().splitlines()) == 1 and not out.exists()
    assert "89.5 deg held over the motion each design runs" in err
