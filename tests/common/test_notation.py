"""A branch sign is written the same way in every display: sigma, with its loop's name as a subscript."""
import pytest

from symlink.mechanism.catalog import fourbar, watt2
from symlink.codegen.latex import latex_document
from symlink.common.notation import branch_html, branch_latex, latex_names, math_text
from symlink.symbolic.plan import solve_plan


@pytest.mark.parametrize("name, latex, html", [
    ("branch", r"\sigma", "σ"),
    ("branch_ABCD", r"\sigma_{\mathrm{ABCD}}", "σ<sub>ABCD</sub>"),
    ("branch_loop_2", r"\sigma_{\mathrm{loop\_2}}", "σ<sub>loop_2</sub>"),
    ("branch_A<B", r"\sigma_{\mathrm{A<B}}", "σ<sub>A&lt;B</sub>"),
])
def test_branch_names(name, latex, html):
    assert branch_latex(name) == latex and branch_html(name) == html


def test_every_display_writes_the_branch_sign_as_sigma():
    for linkage in (fourbar(), watt2()):
        branches = [step.branch.name for step in linkage.plan if step.branch is not None]
        document = latex_document(linkage, linkage.name)
        shown = linkage._repr_latex_()
        table = solve_plan(linkage)._repr_html_()
        for name in branches:
            assert branch_latex(name) in document and branch_latex(name) in shown
            assert branch_html(name) in table
        assert "branch_" not in shown and "branch}" not in shown.replace(r"\mathrm", "")


def test_generated_intermediates_get_textbook_names():
    import sympy as sp
    symbols = sp.symbols("Wx_1 Wy_12 rho_3_2 w_1 a")
    names = latex_names([sp.Add(*symbols)])
    assert [names.get(s) for s in symbols] == ["W_{x,1}", "W_{y,12}", r"\rho_{3,2}", None, None]


def test_math_text_keeps_underscores_and_spaces():
    assert math_text("scene of a_b") == r"\text{scene of a}\_\text{b}"
