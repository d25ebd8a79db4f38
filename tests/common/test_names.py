"""Names that cannot clash: every bad name is refused when the linkage is defined, naming it and why."""
import pytest
import sympy as sp

from symlink.symbolic.linkage import Linkage
from symlink.symbolic.loops import Loop
from symlink.common.names import identifier, label
from symlink.symbolic.vectors import Vector

DEFAULTS = {"a": "a", "b": "b", "c": "c", "d": "d", "theta": "theta", "beta": "beta", "phi": "phi",
            "linkage": "fourbar", "loop": "ABCD", "point": "C", "role": "rocker", "extra": "gap"}


def fourbar(**renamed):
    """A four-bar whose names are the defaults with some renamed; a second loop if ``second_loop`` is given."""
    names = {**DEFAULTS, **renamed}
    a, b, c, d = (sp.Symbol(names[k], positive=True) for k in "abcd")
    theta, beta, phi = (sp.Symbol(names[k], real=True) for k in ("theta", "beta", "phi"))
    AB, BC, DC, AD = Vector(a, theta), Vector(b, beta), Vector(c, phi), Vector(d, 0)
    loops = [Loop(AB + BC - DC - AD, name=names["loop"])]
    unknowns = [beta, phi]
    if "second_loop" in renamed:
        e, f, g = sp.symbols("e f g", positive=True)
        psi, mu = sp.symbols("psi mu", real=True)
        loops.append(Loop(Vector(c, phi) + Vector(e, mu) - Vector(f, psi) - Vector(g, 0), name=names["second_loop"]))
        unknowns += [mu, psi]
    return Linkage(names["linkage"], loops, inputs=[theta], unknowns=unknowns,
                   points={"A": None, names["point"]: AB + BC}, roles={names["role"]: phi},
                   extras={names["extra"]: beta - phi})


BAD = [
    # (what is renamed, to what, the name the message must contain)
    ("a", "w_1", "w_1"), ("b", "Delta_1", "Delta_1"), ("c", "Wx_1", "Wx_1"), ("d", "Wy_2", "Wy_2"),
    ("a", "cse_0", "cse_0"), ("a", "symlink_x", "symlink_x"),
    ("a", "lambda", "lambda"), ("b", "branch", "branch"), ("b", "branch_ABCD", "branch_ABCD"),
    ("d", "thetadot", "thetadot"), ("d", "phiddot", "phiddot"), ("c", "shape", "shape"),
    ("c", "numpy", "numpy"), ("c", "math", "math"), ("c", "TOLERANCE", "TOLERANCE"),
    ("a", "guess", "guess"), ("a", "assembled", "assembled"), ("a", "singular", "singular"),
    ("a", "out", "out"), ("theta", "out", "out"),  # a solver call's keyword for the caller's arrays
    ("a", "for", "for"), ("a", "class", "class"), ("a", "None", "None"), ("a", "int", "int"),
    ("a", "double", "double"), ("a", "restrict", "restrict"), ("a", "end", "end"), ("a", "function", "function"),
    ("a", "sin", "sin"), ("a", "atan2", "atan2"), ("a", "sqrt", "sqrt"), ("a", "isfinite", "isfinite"),
    ("a", "pi", "pi"), ("a", "a b", "a b"), ("a", "a-b", "a-b"), ("a", "_a", "_a"), ("a", "1a", "1a"),
    ("a", "\u0430", "\u0430"),           # Cyrillic a, a lookalike of ASCII a
    ("theta", "\u03b8", "\u03b8"),        # a Greek theta: not ASCII
    ("a", "x" * 57, "x" * 57),
    ("phi", "beta", "beta"),              # two coordinates with one name
    ("phi", "b", "b"),                    # a coordinate named like a length (different assumptions)
    ("beta", "thetad", "thetaddot"),      # theta and thetad both give thetaddot
    ("role", "lambda", "lambda"), ("role", "theta", "theta"), ("role", "a", "a"),
    ("role", "C_x", "C_x"), ("role", "gap", "gap"),
    ("point", "cse", "cse_x"), ("point", "lambda", "lambda"), ("point", "x y", "x y"), ("point", "C.x", "C.x"),
    ("extra", "C_x", "C_x"), ("extra", "rocker_speed", "rocker_speed"), ("extra", "phidot", "phidot"),
    ("extra", "while", "while"), ("extra", "d", "d"),
    ("loop", "ABCD\n", "ABCD\\n"), ("loop", "lambda", "lambda"), ("loop", "z1+z2", "z1+z2"),
    ("linkage", 'x"""; import os; os.system("true"); """', '"""'), ("linkage", "x'", "x'"),
    ("linkage", "line\nbreak", "line\\nbreak"), ("linkage", "a */ b", "*/"), ("linkage", "50%", "50%"),
    ("linkage", "back\\slash", "back\\\\slash"), ("linkage", "f\u043eurbar", "f\u043eurbar"),
    ("linkage", "lambda", "lambda"), ("linkage", "while", "while"), ("linkage", "two  spaces", "two  spaces"),
    ("linkage", "", "''"), ("linkage", "${x}", "${x}"),
]


@pytest.mark.parametrize("what, name, shown", BAD, ids=[f"{w}={n!r}"[:40] for w, n, _ in BAD])
def test_bad_name_is_refused_naming_it(what, name, shown):
    with pytest.raises(ValueError) as error:
        fourbar(**{what: name})
    assert shown in str(error.value)


def test_at_least_forty_bad_definitions():
    assert len(BAD) >= 40


def test_reported_messages_say_why():
    with pytest.raises(ValueError, match=r"parameter 'w_1' clashes with a generated intermediate.*rename it"):
        fourbar(a="w_1")
    with pytest.raises(ValueError, match=r"parameter 'thetadot' clashes with the rate of input 'theta'"):
        fourbar(d="thetadot")
    with pytest.raises(ValueError, match=r"'phid' and .*'phi' are both named 'phiddot'"):
        fourbar(beta="phid")
    with pytest.raises(ValueError, match=r"'lambda' is a keyword"):
        fourbar(a="lambda")
    with pytest.raises(ValueError, match=r"'shape' is a name the generated code uses"):
        fourbar(c="shape")
    with pytest.raises(ValueError, match=r"'out' is the keyword a solver call takes for the caller's output arrays"):
        fourbar(d="out")


def test_two_loops_with_one_name_are_refused():
    with pytest.raises(ValueError, match="two loops are named 'ABCD'"):
        fourbar(second_loop="ABCD")
    assert [b.name for b in fourbar(second_loop="DEFG").branches] == ["branch_ABCD", "branch_DEFG"]


def test_good_names_pass():
    linkage = fourbar(linkage="inverted slider-crank", a="a_1", theta="q", role="output_2", point="P2",
                      extra="phi_minus_beta")
    assert {"output_2_speed", "P2_x", "phi_minus_beta"} <= set(linkage.output_names())
    assert linkage.output("qdot") == sp.Symbol("qdot", real=True)


def test_an_extra_may_use_a_rate():
    theta = sp.Symbol("theta", real=True)
    linkage = fourbar(extra="power")
    Linkage("ok", linkage.loops, linkage.inputs, linkage.unknowns,
            extras={"power": sp.Symbol("thetadot", real=True) * 2})


@pytest.mark.parametrize("vectors, why", [
    (lambda a, b, t: Vector(a, t).as_sum(), "one vector"),
    (lambda a, b, t: Vector(a, t) + Vector(b, t), "one half-plane"),
    (lambda a, b, t: Vector(a, t) + Vector(b, t + sp.pi / 3), "one half-plane"),
    (lambda a, b, t: Vector(a, 0) - Vector(b, sp.pi), "one half-plane"),
    (lambda a, b, t: Vector(a, t) + Vector(b, t + 1) + Vector(3, t - 1), "one half-plane"),
])
def test_a_loop_that_cannot_close_for_any_values_is_refused(vectors, why):
    a, b = sp.symbols("a b", positive=True)
    theta = sp.Symbol("theta", real=True)
    with pytest.raises(ValueError, match=f"loop 'ABC' .*{why}.*ground vector"):
        Loop(vectors(a, b, theta), name="ABC")


@pytest.mark.parametrize("vectors", [
    lambda a, b, t: Vector(a, t) - Vector(b, t),                  # closes where a = b
    lambda a, b, t: Vector(a, t) + Vector(b, t + sp.pi),          # the same, written with an angle
    lambda a, b, t: Vector(a, t) + Vector(b, t + 2) + Vector(1, t - 2),  # spans more than a half-plane
    lambda a, b, t: Vector(a, t) + Vector(b, sp.Symbol("beta", real=True)),  # b = a, beta = t + pi
])
def test_loops_that_can_close_are_kept(vectors):
    a, b = sp.symbols("a b", positive=True)
    Loop(vectors(a, b, sp.Symbol("theta", real=True)), name="ABC")


def test_identifier_and_label_refuse_non_text():
    with pytest.raises(ValueError, match="must be text"):
        identifier(3, "parameter")
    with pytest.raises(ValueError, match="must be text"):
        label(None)
