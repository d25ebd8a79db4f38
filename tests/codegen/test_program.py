"""The straight-line program: CSE across outputs, dependency order, names checked for the target language."""
import pytest
import sympy as sp

from symlink.mechanism.catalog import fourbar
from symlink.codegen.program import (CSE_PREFIX, _dependency_order, in_loop_units, format_default, is_flag, named_straight_line,
                                     straight_line)
from symlink.symbolic.linkage import Program


def test_straight_line_defines_before_use():
    code = straight_line(fourbar().program(["coupler_accel", "transmission", "C_y"]))
    defined = set(code.arguments)
    for symbol, expr in code.assignments:
        assert expr.free_symbols <= defined, symbol
        defined.add(symbol)
    for expr in code.outputs.values():
        assert expr.free_symbols <= defined


def test_the_program_is_unchanged_in_value():
    program = fourbar().program(["rocker_accel", "transmission"])
    code = straight_line(program)
    values = {s: v for s, v in zip(program.arguments, (0.7, 20.0, 66.0, 56.0, 80.0, 1.0, 2.5, -0.3))}
    assert [s.name for s in program.arguments] == ["theta", "a", "b", "c", "d", "branch", "thetadot", "thetaddot"]

    def evaluate(assignments, outputs):
        known = dict(values)
        for symbol, expr in assignments:
            known[symbol] = expr.subs(known).evalf(30)
        return {name: complex(expr.subs(known).evalf(30)) for name, expr in outputs.items()}
    assert evaluate(code.assignments, code.outputs) == pytest.approx(evaluate(program.assignments, program.outputs),
                                                                    rel=1e-25)
    # The guarded values: the clamped root, and the squared length of W that must not vanish (no square root for it).
    assert code.roots == tuple(s for s, e in in_loop_units(program).assignments
                               if type(e).__name__ in ("ClampedSqrt", "NonzeroSquare"))
    assert [s.name for s in code.roots] == ["wsq_1", "Delta_1"]


def test_temporaries_avoid_names_the_program_uses():
    x, taken = sp.symbols(f"x {CSE_PREFIX}0", real=True)
    program = Program((x, taken), (), {"f": sp.sin(x + taken) ** 2 + sp.cos(x + taken), "g": sp.sin(x + taken)})
    code = straight_line(program)
    assert code.assignments and all(symbol != taken for symbol, _ in code.assignments)


def test_circular_definitions_are_refused():
    p, q = sp.symbols("p q")
    with pytest.raises(ValueError, match="circular"):
        _dependency_order([(p, q + 1), (q, p + 1)])


def _identifier(name, what):
    if not name.isidentifier():
        raise ValueError(f"{what} {name!r} is not usable")
    return name


@pytest.mark.parametrize("outputs, name, message", [
    (["rocker"], "not a name", "function name 'not a name' is not usable"),
    ([], "f", "f: a Python function needs at least one output"),
])
def test_named_straight_line_refuses(outputs, name, message):
    with pytest.raises(ValueError, match=message):
        named_straight_line(fourbar().program(outputs), name, _identifier, "Python")


def test_named_straight_line_checks_the_arguments():
    code, arguments = named_straight_line(fourbar().program(["rocker"]), "f", _identifier, "Python")
    assert arguments == ["theta", "a", "b", "c", "d", "branch"] and list(code.outputs) == ["rocker"]


def test_defaults_and_flags():
    x = sp.Symbol("x")
    assert (format_default(1.0), format_default(0.0), format_default(-1.0)) == ("1", "0.0", "-1.0")
    assert is_flag(sp.Lt(x, 1)) and is_flag(sp.And(sp.Lt(x, 1), sp.Gt(x, 0))) and not is_flag(x + 1)
