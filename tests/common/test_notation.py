"""A branch sign is written the same way in every display: sigma, with its loop's name as a subscript."""
from pathlib import Path

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


def test_a_users_name_with_a_double_underscore_is_typeset_as_written_not_as_a_power(tmp_path):
    """LaTeX is a target language too: SymPy prints ``x__y`` as ``x^{y}`` (x to the power y)."""
    from symlink.cli import main
    text = (Path(__file__).parents[2] / "symlink" / "linkages" / "fourbar.toml").read_text()
    renamed = text.replace('"a"', '"x__y"').replace('["a", "theta"]', '["x__y", "theta"]').replace("a = 20.0",
                                                                                                 "x__y = 20.0")
    assert renamed.count("x__y") == 3
    (tmp_path / "four.toml").write_text(renamed)
    assert main(["export", str(tmp_path / "four.toml"), "--to", "latex", "--out", str(tmp_path / "tex")]) == 0
    latex = "".join(path.read_text() for path in (tmp_path / "tex").iterdir())
    assert r"\mathit{x\_\_y}" in latex and "x^{y}" not in latex
