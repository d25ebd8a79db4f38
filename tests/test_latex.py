"""LaTeX export and Jupyter rendering."""
from symlink.catalog import fourbar
from symlink.latex import latex_document


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
