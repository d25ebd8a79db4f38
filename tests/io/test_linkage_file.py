"""Linkage files: every catalog entry round-trips, the shipped examples are current, bad files say where."""
from pathlib import Path
import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings, strategies as st

from symlink.mechanism.catalog import CATALOG, EXAMPLE_VALUES
from symlink.io.linkage_file import (catalog_file, linkage_from_mapping, linkage_from_text, linkage_text, read_linkage,
                                  write_catalog_files, write_linkage)
from symlink.numeric.solver import Solver


@pytest.mark.parametrize("name", sorted(CATALOG))
def test_every_catalog_entry_round_trips(name, tmp_path):
    original = CATALOG[name]()
    path = tmp_path / f"{name}.toml"
    write_linkage(original, path, EXAMPLE_VALUES[name])
    found = read_linkage(path)
    copy = found.linkage
    assert [loop.equations() for loop in copy.loops] == [loop.equations() for loop in original.loops]
    assert [loop.name for loop in copy.loops] == [loop.name for loop in original.loops]
    assert (copy.inputs, copy.unknowns, copy.parameters) == (original.inputs, original.unknowns, original.parameters)
    assert copy.call_signature() == original.call_signature()
    assert {p: copy.point(p) for p in copy.points} == {p: original.point(p) for p in original.points}
    assert copy.roles == original.roles
    assert copy.has_closed_form == original.has_closed_form
    if original.has_closed_form:
        assert copy.positions == original.positions
    assert found.defaults == pytest.approx(EXAMPLE_VALUES[name], rel=0, abs=0)
    assert linkage_text(copy, found.defaults) == path.read_text()  # and the text is a fixed point


@pytest.mark.parametrize("name", sorted(CATALOG))
def test_shipped_example_files_are_current(name):
    path = catalog_file(name)
    regenerate = "python -c \"from symlink.io.linkage_file import write_catalog_files; write_catalog_files()\""
    assert path.exists(), f"symlink/linkages/{name}.toml is missing: run {regenerate}"
    assert path.read_text() == linkage_text(CATALOG[name](), EXAMPLE_VALUES[name]), f"stale: run {regenerate}"


def test_write_catalog_files_writes_one_file_per_entry(tmp_path):
    written = write_catalog_files(tmp_path)
    assert sorted(p.name for p in written) == sorted(f"{n}.toml" for n in CATALOG)


def test_a_file_linkage_solves_like_the_catalog():
    found = read_linkage(catalog_file("fourbar"))
    theta = np.radians(np.arange(0.0, 360.0, 40.0))
    by_file = Solver(found.linkage, ["rocker"])(theta=theta, **found.defaults)["rocker"]
    # seed 003: a=20, b=66, c=56, d=80 at theta = 0 on branch +1 gives phi = 110.74 deg
    assert round(math.degrees(by_file[0]), 2) == 110.74
    assert np.array_equal(by_file, Solver(CATALOG["fourbar"](), ["rocker"])(theta=theta, **found.defaults)["rocker"])


# --- the grammar -------------------------------------------------------------------

HEAD = 'name = "x"\ninputs = ["theta"]\nunknowns = ["beta", "phi"]\nlengths = ["a", "b", "c", "d"]\n'
LOOP = '[loops]\nABCD = "AD + DC - BC - AB"\n'


def angle_of(text):
    vectors = f'[vectors]\nAB = ["a", "{text}"]\nBC = ["b", "beta"]\nDC = ["c", "phi"]\nAD = ["d", 0]\n'
    constants = 'constants = ["alpha"]\n' if "alpha" in text else ""
    found = linkage_from_text(HEAD + constants + vectors + LOOP)
    return found.linkage.loops[0].terms[-1][1].angle


THETA, ALPHA = sp.Symbol("theta", real=True), sp.Symbol("alpha", real=True)


@pytest.mark.parametrize("text, expected", [
    ("theta", THETA),
    ("theta + 35 deg", THETA + 7 * sp.pi / 36),
    ("theta - pi/2", THETA - sp.pi / 2),
    ("-theta", -THETA),
    ("theta + 3*pi/4", THETA + 3 * sp.pi / 4),
    ("theta + 0.5 rad", THETA + sp.Float(0.5)),
    ("theta + 1/3", THETA + sp.Rational(1, 3)),
    ("theta + alpha - 10deg", THETA + ALPHA - sp.pi / 18),
    ("theta + 1e-3", THETA + sp.Float(0.001)),
])
def test_angle_grammar(text, expected):
    assert angle_of(text) == expected


constants = st.one_of(st.integers(-720, 720).map(lambda k: sp.pi * k / 180),
                      st.integers(-9, 9).map(sp.Integer),
                      st.fractions(max_denominator=12).filter(lambda f: abs(f) < 50).map(sp.Rational))


@settings(max_examples=60, deadline=None)
@given(sign=st.sampled_from([1, -1]), constant=constants, with_alpha=st.booleans())
def test_written_angles_read_back(sign, constant, with_alpha):
    """Any angle the grammar can hold is written by the writer and read back to the same expression."""
    theta, alpha = sp.Symbol("theta", real=True), sp.Symbol("alpha", real=True)
    from symlink import Linkage, Loop, Vector, lengths
    beta, phi = sp.symbols("beta phi", real=True)
    a, b, c, d = lengths("a b c d")
    angle = sign * theta + constant + (alpha if with_alpha else 0)
    AB, BC, DC, AD = Vector(a, angle, "AB"), Vector(b, beta, "BC"), Vector(c, phi, "DC"), Vector(d, 0, "AD")
    linkage = Linkage("x", [Loop(AD + DC - BC - AB, name="ABCD")], [theta], [beta, phi])
    copy = linkage_from_text(linkage_text(linkage)).linkage
    assert copy.loops[0].terms[-1][1].angle == angle


# --- malformed files: one line naming the file, the line and the problem ------------------

GOOD = """\
name = "fourbar"
inputs = ["theta"]
unknowns = ["beta", "phi"]
lengths = ["a", "b", "c", "d"]

[vectors]
AB = ["a", "theta"]
BC = ["b", "beta"]
DC = ["c", "phi"]
AD = ["d", 0]

[loops]
ABCD = "AD + DC - BC - AB"

[points]
A = "0"
C = "AB + BC"

[roles]
crank = "theta"

[defaults]
a = 20
theta = "30 deg"
"""


def replaced(old, new):
    assert old in GOOD, old
    return GOOD.replace(old, new, 1)


MALFORMED = [
    # (file text, line of the problem, words of the message)
    (replaced('name = "fourbar"', 'name = "fourbar'), 1, "not valid TOML"),
    (replaced("[roles]", "[roles]\n[roles]"), 20, "not valid TOML"),
    (replaced('name = "fourbar"', 'colour = "red"'), 1, "unknown key 'colour'"),
    (replaced('name = "fourbar"\n', ""), 1, "missing name"),
    (replaced('name = "fourbar"', "name = 3"), 1, "name must be a non-empty string"),
    (replaced('name = "fourbar"', 'name = ""'), 1, "name must be a non-empty string"),
    (replaced('inputs = ["theta"]', 'inputs = "theta"'), 2, "inputs must be a list of names"),
    (replaced('inputs = ["theta"]', 'inputs = ["theta", 3]'), 2, "inputs must be a list of names"),
    (replaced('inputs = ["theta"]\n', ""), 1, "missing inputs"),
    (replaced('unknowns = ["beta", "phi"]', 'unknowns = ["beta", "2phi"]'), 3, "'2phi' is not a name"),
    (replaced('unknowns = ["beta", "phi"]', 'unknowns = ["beta", "pi"]'), 3, "reserved"),
    (replaced('unknowns = ["beta", "phi"]', 'unknowns = ["beta", "phi", "theta"]'), 3, "listed in inputs and again"),
    (replaced('lengths = ["a", "b", "c", "d"]', 'lengths = ["a", "b", "c", "d", "e"]'), 4, "'e' appears in no vector"),
    (replaced('lengths = ["a", "b", "c", "d"]', 'lengths = ["a", "b", "c", "d"]\nconstants = ["gx"]'), 5,
     "'gx' appears in no vector"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a"]'), 7, "vectors.AB must be [length, angle]"),
    (replaced('AB = ["a", "theta"]', 'AB = "a"'), 7, "vectors.AB must be [length, angle]"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", "theta * 2"]'), 7, "a name cannot be multiplied"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", "2 * theta"]'), 7, "a name cannot be multiplied"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", "gamma"]'), 7, "'gamma' is not a coordinate or constant"),
    (replaced('AB = ["a", "theta"]', 'AB = ["2 deg", "theta"]'), 7, "a unit (deg) belongs to angles only"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", "theta + 35 km"]'), 7, "units are deg and rad"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", "theta +"]'), 7, "ends too early"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", "theta $ 2"]'), 7, "unexpected '$'"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", "theta + pi/0"]'), 7, "division by zero"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", true]'), 7, "must be a number or a string"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", ""]'), 7, "is empty"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", "theta deg"]'), 7, "expected + or - before 'deg'"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", "deg"]'), 7, "'deg' must follow a number"),
    (replaced('AB = ["a", "theta"]', 'AB = ["a", "theta + 2 * 3"]'), 7, "only pi may follow '*'"),
    (replaced('AD = ["d", 0]', 'AD = ["d", 0]\nXY = ["d", "pi"]'), 11, "vectors.XY is in no loop and no point"),
    (replaced('AD = ["d", 0]', 'AD = ["d", 0]\nA-B = ["d", "pi"]'), 11, "vectors.A-B: a name is ASCII"),
    (replaced('ABCD = "AD + DC - BC - AB"', 'AB-CD = "AD + DC - BC - AB"'), 13, "loops.AB-CD: a name is ASCII"),
    (replaced('C = "AB + BC"', '2C = "AB + BC"'), 17, "points.2C: a name is ASCII"),
    (replaced('crank = "theta"', '"the crank" = "theta"'), 20, "roles.the crank: a name is ASCII"),
    (replaced('AD = ["d", 0]', 'AD = ["d", 0]\n[vectors.EF]\nlength = "d"'), 11, "nested tables"),
    (replaced('ABCD = "AD + DC - BC - AB"', 'ABCD = "AD + DC - BC - XY"'), 13, "'XY' is not a vector"),
    (replaced('ABCD = "AD + DC - BC - AB"', 'ABCD = "AD + DC BC - AB"'), 13, "expected + or - between vectors"),
    (replaced('ABCD = "AD + DC - BC - AB"', 'ABCD = "AD + DC - BC - AB -"'), 13, "ends with '-'"),
    (replaced('ABCD = "AD + DC - BC - AB"', "ABCD = 5"), 13, "must be a string"),
    (replaced('ABCD = "AD + DC - BC - AB"', 'ABCD = "AD + DC - BC - AB"\nBACK = "AB - AB"'), 14,
     "no loop of 'fourbar' has exactly two unknowns left"),  # the line of the loop at fault, not [loops]
    (replaced('[loops]\nABCD = "AD + DC - BC - AB"\n', ""), 1, "no loops"),
    (replaced('C = "AB + BC"', 'C = "AB + ZZ"'), 17, "'ZZ' is not a vector"),
    (replaced('crank = "theta"', 'crank = "a"'), 20, "roles.crank must name a coordinate"),
    (replaced("a = 20", "a = -1"), 23, "defaults.a: -1 must be a positive length"),
    (replaced("a = 20", "zz = 1"), 23, "only constants, inputs and the names of [dynamics] have defaults"),
    (replaced("a = 20", "a = nan"), 23, "must be finite"),
    (replaced('theta = "30 deg"', 'theta = "30 km"'), 24, "units are deg and rad"),
    (replaced("a = 20", 'a = "30 deg"'), 23, "a unit (deg) belongs to angles only"),
    (replaced('theta = "30 deg"', 'theta = "theta"'), 24, "'theta' is not a coordinate or constant"),
    (replaced("[roles]", "[roles2]"), 19, "unknown key 'roles2'"),
    (GOOD.split("[defaults]")[0].replace('name = "fourbar"', 'name = "fourbar"\ndefaults = 3'), 2,
     "defaults must be a table"),
    (replaced('C = "AB + BC"', 'C = ["AB", "BC"]'), 17, "must be a string"),
]


def test_there_are_enough_malformed_files():
    assert len(MALFORMED) >= 30


@pytest.mark.parametrize("text, line, words", MALFORMED, ids=[f"{n}-{c[2][:30]}" for n, c in enumerate(MALFORMED)])
def test_malformed_file_names_file_line_and_problem(text, line, words, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ValueError) as caught:
        read_linkage(path)
    message = str(caught.value)
    assert "\n" not in message
    assert message.startswith(f"{path}:{line}: "), message
    assert words in message, message


def test_the_good_file_is_good(tmp_path):
    path = tmp_path / "good.toml"
    path.write_text(GOOD)
    found = read_linkage(path)
    assert found.defaults == {"a": 20.0, "theta": pytest.approx(math.pi / 6, rel=1e-15)}
    assert found.source == str(path)


def test_unreadable_file(tmp_path):
    with pytest.raises(ValueError, match=r"^cannot read linkage file .*missing\.toml: No such file or directory$"):
        read_linkage(tmp_path / "missing.toml")


def test_mapping_without_text_names_the_source_only():
    with pytest.raises(ValueError, match=r"^from Python: missing inputs"):
        linkage_from_mapping({"name": "x"}, source="from Python")


def test_the_writer_refuses_what_the_grammar_cannot_hold(tmp_path):
    from symlink import Linkage, Loop, Vector, coordinates, lengths
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, d = lengths("a b c d")
    bent = Vector(c, sp.acos(a / d) + phi, "DC")
    linkage = Linkage("x", [Loop(Vector(d, 0, "AD") + bent - Vector(b, beta, "BC") - Vector(a, theta, "AB"))],
                      [theta], [beta, phi])
    with pytest.raises(ValueError, match="cannot be written in a linkage file"):
        write_linkage(linkage, tmp_path / "x.toml")
    assert not (tmp_path / "x.toml").exists()


GUIDE = Path(__file__).resolve().parent.parent.parent / "docs" / "howto" / "linkage_files.md"  # the how-to guide on linkage files


def test_guide_shows_the_shipped_fourbar_file():
    from readme_text import fenced_blocks
    (shown,) = fenced_blocks(GUIDE.read_text(encoding="utf-8"), "toml")
    assert shown == catalog_file("fourbar").read_text()
    assert linkage_from_text(shown).linkage.positions == CATALOG["fourbar"]().positions


def test_guide_error_example_is_what_the_reader_says():
    text = catalog_file("fourbar").read_text().replace('AB = ["a", "theta"]', 'AB = ["a", "theta * 2"]')
    with pytest.raises(ValueError) as caught:
        linkage_from_text(text, "fourbar.toml")
    assert f"`{caught.value}`" in GUIDE.read_text(encoding="utf-8")


@settings(max_examples=200, deadline=None)
@given(st.text(alphabet="thetapidegr0123456789.+-*/ eE_$()", max_size=20))
def test_any_angle_text_reads_or_fails_with_one_located_line(text):
    document = GOOD.replace('AB = ["a", "theta"]', f'AB = ["a", "{text}"]')
    try:
        linkage_from_text(document, "any.toml")
    except ValueError as error:
        message = str(error)
        assert message.startswith("any.toml:") and "\n" not in message
        assert message.split(":")[1].isdigit()


def test_catalog_file_names_the_catalog_for_an_unknown_name():
    with pytest.raises(ValueError, match=r"no linkage 'fourbars' in the catalog; it has .*fourbar"):
        catalog_file("fourbars")


def test_every_shipped_linkage_file_is_a_catalog_entry():
    shipped = {path.stem for path in catalog_file("fourbar").parent.glob("*.toml")}
    assert shipped == set(CATALOG)  # nothing stale left beside them


# --- hostile values: every value finite and in range, refused where it is read, with the line of the value ----------

DYNAMIC = GOOD + """
[dynamics]
gravity = [0, -9.81]

[dynamics.masses.crank]
mass = 1.2
inertia = 0.5
distance = 10
angle = "0 deg"
"""


def dynamic_replaced(old, new):
    assert old in DYNAMIC, old
    return DYNAMIC.replace(old, new, 1)


def fixed_length(text):
    """The good file with a vector EF of length ``text`` (a TOML value) on line 11, ending at a point."""
    return replaced('AD = ["d", 0]', f'AD = ["d", 0]\nEF = [{text}, 0]').replace('C = "AB + BC"', 'C = "AB + BC"\nE = "EF"')


HUGE_INTEGER = "1" + "0" * 399  # 400 digits: no float holds it

HOSTILE_VALUES = [
    # (file text, line of the value, words of the message)
    (replaced('AD = ["d", 0]', 'AD = ["d", "1/1e-999 deg"]'), 10, "too small for a float"),
    (replaced('AD = ["d", 0]', 'AD = ["d", "pi/1e-400"]'), 10, "too small for a float"),
    (replaced('AD = ["d", 0]', 'AD = ["d", "1e308*pi"]'), 10, "not a finite number"),
    (replaced('AD = ["d", 0]', 'AD = ["d", "1e300*pi"]'), 10, "more than 1e+09 in size"),
    (replaced('AD = ["d", 0]', 'AD = ["d", "1.7e308 + 1.7e308"]'), 10, "more than a float can hold"),
    (replaced('AD = ["d", 0]', 'AD = ["d", "pi/0.0"]'), 10, "division by zero"),
    (replaced('AD = ["d", 0]', 'AD = ["d", "pi/0e5"]'), 10, "division by zero"),
    (replaced('AD = ["d", 0]', 'AD = ["d", "1e999 deg"]'), 10, "too large for a float"),
    (replaced('AD = ["d", 0]', f'AD = ["d", "{HUGE_INTEGER}"]'), 10, "a number of 400 characters"),
    (replaced('AD = ["d", 0]', f'AD = ["d", "{HUGE_INTEGER} deg"]'), 10, "a number of 400 characters"),
    (replaced('AD = ["d", 0]', 'AD = ["d", 1e300]'), 10, "more than 1e+09 in size"),
    (replaced('AD = ["d", 0]', 'AD = ["d", "2e9"]'), 10, "more than 1e+09 in size"),
    (fixed_length('"1e60"'), 11, "between 1e-50 and 1e+50"),
    (fixed_length('"1e-60"'), 11, "between 1e-50 and 1e+50"),
    (fixed_length("-3"), 11, "must be a positive length"),
    (fixed_length('"0.0"'), 11, "must be a positive length"),
    (fixed_length('"1 - 1"'), 11, "must be a positive length"),
    (fixed_length('"1/' + "3" * 70 + '"'), 11, "a number of 70 characters"),
    (replaced("a = 20", "a = 1e300"), 23, "between 1e-50 and 1e+50"),
    (replaced("a = 20", 'a = "1/1e-999"'), 23, "too small for a float"),
    (replaced('theta = "30 deg"', 'theta = "1e308*pi"'), 24, "not a finite number"),
    (replaced('theta = "30 deg"', 'theta = 1e300'), 24, "more than 1e+09 in size"),
    (replaced('theta = "30 deg"', 'theta = "pi/0.0"'), 24, "division by zero"),
    (dynamic_replaced("mass = 1.2", "mass = -1.2"), 30, "must not be negative"),
    (dynamic_replaced("mass = 1.2", 'mass = "-m2"'), 30, "must not be negative"),
    (dynamic_replaced("mass = 1.2", 'mass = "1/1e-999"'), 30, "too small for a float"),
    (dynamic_replaced("mass = 1.2", "mass = 1e308"), 30, "between 1e-50 and 1e+50"),
    (dynamic_replaced("mass = 1.2", 'mass = "m2"').replace("a = 20", "a = 20\nm2 = -3"), 24,
     "defaults.m2: -3 must not be negative"),
    (dynamic_replaced("inertia = 0.5", "inertia = -0.5"), 31, "must not be negative"),
    (dynamic_replaced("inertia = 0.5", "inertia = 1e99"), 31, "between 1e-50 and 1e+50"),
    (dynamic_replaced("distance = 10", 'distance = "1.7e308 + 1.7e308"'), 32, "more than a float can hold"),
    (dynamic_replaced('angle = "0 deg"', 'angle = "1e308*pi"'), 33, "not a finite number"),
    (dynamic_replaced("gravity = [0, -9.81]", 'gravity = [0, "1/1e-999"]'), 27, "too small for a float"),
    (dynamic_replaced("gravity = [0, -9.81]", "gravity = [0, -1e300]"), 27, "between 1e-50 and 1e+50"),
]


@pytest.mark.parametrize("text, line, words", HOSTILE_VALUES,
                         ids=[f"{n}-{c[2][:24]}" for n, c in enumerate(HOSTILE_VALUES)])
def test_hostile_values_are_refused_at_their_line(text, line, words, tmp_path):
    path = tmp_path / "hostile.toml"
    path.write_text(text)
    with pytest.raises(ValueError) as caught:
        read_linkage(path)
    message = str(caught.value)
    assert "\n" not in message and len(message) < 300, message
    assert message.startswith(f"{path}:{line}: "), message
    assert words in message, message


def test_the_dynamic_file_is_good():
    found = linkage_from_text(DYNAMIC, "dynamic.toml")
    assert found.model is not None and found.defaults["a"] == 20.0


@pytest.mark.parametrize("text, expected", [
    ("pi/2 + 30 deg", 2 * math.pi / 3),        # exact: pi/2 + pi/6
    ("1/3 + 2/3", 1.0),                        # exact fractions add to exactly 1
    ("1e-300 + 1", 1.0),                       # a tiny float is a value, not an underflow
    ("0.000 deg", 0.0),                        # zero written with a point is zero, not too small
    ("-1e9", -1e9),                            # the largest angle allowed
    ("1.5*pi/4 - 0.25 rad", 1.5 * math.pi / 4 - 0.25),
])
def test_constant_angles_are_their_hand_values(text, expected):
    found = linkage_from_text(replaced('theta = "30 deg"', f'theta = "{text}"'), "x.toml")
    assert found.defaults["theta"] == pytest.approx(expected, rel=1e-15, abs=1e-300)


def test_hostile_text_in_a_message_is_cut_to_an_excerpt():
    hostile = "theta $ " + "x" * 50_000
    with pytest.raises(ValueError) as caught:
        linkage_from_text(replaced('AB = ["a", "theta"]', f'AB = ["a", "{hostile}"]'), "x.toml")
    assert len(str(caught.value)) < 300 and "..." in str(caught.value)


@pytest.mark.parametrize("text, line, words", [
    # a problem of the linkage or the dynamics as a whole: the line that names what the message names
    (DYNAMIC.replace("[dynamics.masses.crank]", "[dynamics.masses.crank2]"), 29, "crank2"),
    (DYNAMIC + '\n[[dynamics.forces]]\npoint = "Q"\nx = 1\n', 36, "Q"),
    (replaced('ABCD = "AD + DC - BC - AB"', 'ABCD = "AD + DC - BC - AB"\nBACK = "AB - AB"'), 14, "BACK"),
])
def test_whole_linkage_problems_point_at_the_line_at_fault(text, line, words, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ValueError) as caught:
        read_linkage(path)
    assert str(caught.value).startswith(f"{path}:{line}: ") and words in str(caught.value), caught.value


@pytest.mark.parametrize("text, line, words", [
    (replaced('ABCD = "AD + DC - BC - AB"', 'ABCD = "AD + DC - BC - AB' + " + AB - AB" * 600 + '"'), 13,
     "a sum of 1,204 vectors (at most 1,000)"),
    (replaced('AD = ["d", 0]', 'AD = ["d", 0]\n' + "".join(f'V{k} = ["a", "theta"]\n' for k in range(1001))), 6,
     "[vectors] has 1,005 entries (at most 1,000"),
    (replaced('unknowns = ["beta", "phi"]', "unknowns = [" + ", ".join(f'"u{k}"' for k in range(1001)) + "]"), 3,
     "unknowns has 1,001 names (at most 1,000)"),
])
def test_a_data_set_is_not_a_linkage(text, line, words, tmp_path):
    """Tens of thousands of vectors or terms would keep the symbolic layer busy for minutes: refused at once."""
    path = tmp_path / "big.toml"
    path.write_text(text)
    with pytest.raises(ValueError) as caught:
        read_linkage(path)
    assert str(caught.value).startswith(f"{path}:{line}: ") and words in str(caught.value), caught.value
