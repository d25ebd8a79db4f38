"""LaTeX export and Jupyter rendering."""
from symlink.catalog import fourbar, stephenson3
from symlink.codegen.latex import latex_document, latex_text, newton_document


def test_document_has_every_section_and_textbook_names():
    text = latex_document(fourbar(), "Four-bar")
    for part in ("\\subsection*{Closure}", "\\subsection*{Solve plan}", "\\subsection*{Positions}",
                 "\\subsection*{Velocities}", "\\subsection*{Accelerations}", "\\end{document}"):
        assert part in text
    assert "\\sigma" in text and "W_{x,1}" in text and "\\ddot{\\phi}" in text
    assert "case 3 (two angles)" in text


def test_linkage_renders_in_jupyter():
    latex = fourbar()._repr_latex_()
    assert latex.startswith("$\\displaystyle \\begin{aligned}") and "\\operatorname{atan}_{2}" in latex


def test_text_is_escaped_and_one_preamble_is_shared():
    assert latex_text("50% of $x_1$ & {y} # ~ ^ \\") == (
        "50\\% of \\$x\\_1\\$ \\& \\{y\\} \\# \\textasciitilde{} \\textasciicircum{} \\textbackslash{}")
    assert latex_text("two\nlines") == "two lines"
    closed = latex_document(fourbar(), "A_1 & {B}")
    newton = newton_document(fourbar(), "A_1 & {B}")
    for text in (closed, newton):
        assert "\\section*{A\\_1 \\& \\{B\\}}" in text
        assert text.split("\\section*")[0] == closed.split("\\section*")[0]   # the same preamble
        assert text.endswith("\\end{document}\n") and text.count("\\begin{document}") == 1


def test_newton_document_has_the_jacobian_and_the_rate_systems():
    text = newton_document(stephenson3(), "Stephenson III")
    for part in ("\\subsection*{Closure}", "\\subsection*{Solve plan}", "\\subsection*{Jacobian}",
                 "\\subsection*{Velocities: $J", "\\subsection*{Accelerations: $J", "no closed form"):
        assert part in text
    assert "J_{11}" in text and "r_{1}" in text and "s_{4}" in text


def test_the_printer_does_not_import_linkage_at_run_time():
    # Linkage._repr_latex_ imports this module on first use: importing linkage back would close a cycle.
    import ast
    import inspect

    import symlink.codegen.latex as latex
    tree = ast.parse(inspect.getsource(latex))
    type_checking = {id(n) for node in tree.body if isinstance(node, ast.If) for n in ast.walk(node)}
    at_run_time = [n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and id(n) not in type_checking]
    assert "closure" in at_run_time and "linkage" not in at_run_time


def test_a_linkage_without_a_closed_form_displays_its_closure():
    """Jupyter shows the closure of a linkage the Newton fallback solves (it used to raise ValueError)."""
    from symlink.catalog import stephenson3
    shown = stephenson3()._repr_latex_()
    assert shown.startswith("$\\displaystyle \\begin{aligned}") and shown.count("= 0") == 4
