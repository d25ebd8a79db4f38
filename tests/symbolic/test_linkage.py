"""Linkage: solve plan, lazy derivation, and programs that keep only what outputs need."""
import pytest
import sympy as sp

from symlink.mechanism.catalog import fourbar
from symlink.codegen.program import in_loop_units
from symlink.symbolic.linkage import Linkage
from symlink.symbolic.loops import Loop
from symlink.symbolic.vectors import Vector, coordinates, lengths


def test_positions_only_never_differentiate():
    linkage = fourbar()
    linkage.program(["rocker", "C_x", "C_y"])
    assert "velocities" not in linkage.__dict__ and "accelerations" not in linkage.__dict__
    linkage.program(["rocker_speed"])
    assert "velocities" in linkage.__dict__ and "accelerations" not in linkage.__dict__


def test_rocker_only_does_not_solve_for_the_coupler():
    program = fourbar().program(["rocker"])
    assert [s.name for s, _ in program.assignments] == ["Wx_1", "Wy_1", "w_1", "Delta_1", "phi"]
    # Generated code computes the same steps in loop units, with w squared (wsq_1): no square root for w.
    assert [s.name for s, _ in in_loop_units(program).assignments] == [
        "size_1", "rho_1_1", "rho_2_1", "Wx_1", "Wy_1", "rho_3_1", "rho_4_1", "wsq_1", "Delta_1", "phi"]
    assert "thetadot" not in [s.name for s in program.arguments]


def test_arguments_follow_the_call_signature():
    program = fourbar().program(["rocker_accel"])
    assert [s.name for s in program.arguments] == ["theta", "a", "b", "c", "d", "branch", "thetadot", "thetaddot"]


def test_output_names_and_errors():
    linkage = fourbar()
    assert {"crank", "rocker_speed", "coupler_accel", "C_x", "transmission", "phiddot"} <= set(linkage.output_names())
    with pytest.raises(ValueError, match="no output 'piston'"):
        linkage.output("piston")


def test_no_closed_form_plan_is_reported():
    theta, p, q, r = coordinates("theta p q r")
    a, b, c = lengths("a b c")
    loop = Loop(Vector(a, theta) + Vector(b, p) + Vector(c, q) + Vector(1, r))
    with pytest.raises(ValueError, match="no loop of 'three' has exactly two unknowns"):
        Linkage("three", [loop], inputs=[theta], unknowns=[p, q, r]).plan


def test_two_loop_plan_uses_earlier_results():
    theta, beta, phi, gamma, psi = coordinates("theta beta phi gamma psi")
    a, b, c, d, e, f, g = lengths("a b c d e f g")
    first = Loop(Vector(a, theta) + Vector(b, beta) - Vector(c, phi) - Vector(d, 0), name="first")
    second = Loop(Vector(c, phi) + Vector(e, gamma) - Vector(f, psi) - Vector(g, 0), name="second")
    linkage = Linkage("watt", [second, first], inputs=[theta], unknowns=[beta, phi, gamma, psi])
    assert [step.loop.name for step in linkage.plan] == ["first", "second"]
    assert [b.name for b in linkage.branches] == ["branch_first", "branch_second"]
    assert phi in linkage.positions[sp.Symbol("Wx_2", real=True)].free_symbols


def test_unknown_in_no_loop_is_refused():
    theta, beta, phi, extra = coordinates("theta beta phi extra")
    a, b, c, d = lengths("a b c d")
    loop = Loop(Vector(a, theta) + Vector(b, beta) - Vector(c, phi) - Vector(d, 0))
    with pytest.raises(ValueError, match="extra appear in no loop"):
        Linkage("x", [loop], inputs=[theta], unknowns=[beta, phi, extra])


def test_simplify_is_opt_in_and_keeps_the_value():
    linkage = fourbar()
    plain, simple = linkage.expression("rocker_accel"), linkage.expression("rocker_accel", simplify=True)
    values = dict(zip(sp.symbols("a b c theta beta phi thetadot thetaddot betadot phidot", real=True),
                      (1.1, 2.3, 1.7, 0.4, 0.9, 2.1, 1.3, -0.7, 0.2, 0.5)))
    by_name = {s.name: v for s, v in values.items()}
    at = lambda e: float(e.subs({s: by_name[s.name] for s in e.free_symbols}))  # noqa: E731
    assert abs(at(plain) - at(simple)) < 1e-12
