"""Solve plans: loop order, cases, unknowns, what each step uses; the numeric fallback; `symlink plan`."""
import pytest
import sympy as sp

from symlink.mechanism.catalog import CATALOG, fivebar, fourbar, inverted_slider_crank, slider_crank, stephenson2, watt2
from symlink.cli import main
from symlink.symbolic.linkage import Linkage
from symlink.symbolic.loops import Loop
from symlink.symbolic.plan import solve_plan
from symlink.symbolic.vectors import Vector, coordinates, lengths


def test_fourbar_is_one_case_3_step_from_the_crank():
    plan = solve_plan(fourbar())
    assert plan.closed_form and len(plan.steps) == 1
    step = plan.steps[0]
    assert (step.loops, step.case, step.unknowns, step.uses, step.branch) == (
        ("ABCD",), "3", ("beta", "phi"), {"theta": 0}, "branch")


@pytest.mark.parametrize("build, case, unknowns, branch", [
    (slider_crank, "2b", ("beta", "s"), "branch"),
    (inverted_slider_crank, "2a", ("phi", "r"), None),
    (fivebar, "3", ("beta", "phi"), "branch"),
])
def test_one_loop_entries(build, case, unknowns, branch):
    (step,) = solve_plan(build()).steps
    assert (step.case, step.unknowns, step.branch) == (case, unknowns, branch)


def test_fivebar_step_uses_both_inputs():
    assert solve_plan(fivebar()).steps[0].uses == {"theta": 0, "psi": 0}


def test_watt2_second_loop_uses_the_first_loops_rocker():
    plan = solve_plan(watt2())
    first, second = plan.steps
    assert first.uses == {"theta": 0} and second.uses == {"phi": 1}
    assert second.unknowns == ("mu", "psi") and second.branch == "branch_DEFG"
    assert str(plan).splitlines() == [
        "watt2: closed form, loop by loop (inputs: theta)",
        "  1. loop ABCD, case 3 (two angles): beta, phi from theta; branch sign branch_ABCD",
        "  2. loop DEFG, case 3 (two angles): mu, psi from phi (step 1); branch sign branch_DEFG",
    ]


def test_loops_given_out_of_order_are_planned_in_order():
    theta, beta, phi, gamma, psi = coordinates("theta beta phi gamma psi")
    a, b, c, d, e, f, g = lengths("a b c d e f g")
    first = Loop(Vector(a, theta) + Vector(b, beta) - Vector(c, phi) - Vector(d, 0), name="first")
    second = Loop(Vector(c, phi) + Vector(e, gamma) - Vector(f, psi) - Vector(g, 0), name="second")
    plan = solve_plan(Linkage("pair", [second, first], inputs=[theta], unknowns=[beta, phi, gamma, psi]))
    assert [step.loops for step in plan.steps] == [("first",), ("second",)]
    assert plan.steps[1].uses == {"phi": 1}


def test_stephenson2_has_no_closed_form_and_says_why():
    linkage = stephenson2()
    plan = solve_plan(linkage)
    assert not plan.closed_form
    (step,) = plan.steps
    assert step.case == "numeric" and step.loops == ("ABCFD", "ABEHD") and step.branch is None
    assert "ABCFD: beta, mu, phi; ABEHD: beta, phi, eta" in plan.note
    with pytest.raises(ValueError, match="no closed-form solve plan exists"):
        linkage.plan
    assert linkage.branches == ()


def test_every_catalog_entry_has_a_plan():
    for name, build in CATALOG.items():
        plan = solve_plan(build())
        assert plan.linkage == name and plan.steps
        assert {u for step in plan.steps for u in step.unknowns} == {u.name for u in build().unknowns}


def test_symlink_plan_prints_the_plan(capsys):
    assert main(["plan", "stephenson2"]) == 0
    out, err = capsys.readouterr()
    # the plan, then its mobility: 6 links, 7 revolute joints -> 3 * 5 - 2 * 7 = 1
    assert err == "" and out == str(solve_plan(stephenson2())) + "\n" + (
        "degrees of freedom: 1 (Gruebler: 6 links with the ground, 7 revolute and 0 prismatic joints)\n")
    assert "Newton's method on all 4 closure equations" in out


def test_symlink_plan_unknown_name_is_one_line_exit_2(capsys):
    assert main(["plan", "sevenbar"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "no linkage 'sevenbar' in the catalog" in err  # plan takes a file too
