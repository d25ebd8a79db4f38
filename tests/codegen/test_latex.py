"""LaTeX export and Jupyter rendering, and the page width of the documents (checked with pdflatex where installed)."""
import re
import shutil
import subprocess
from pathlib import Path

import pytest
import sympy as sp

from symlink.mechanism.catalog import fourbar, stephenson2
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
    text = newton_document(stephenson2(), "Stephenson II")
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
    assert any(m and m.endswith("closure") for m in at_run_time)
    assert not any(m and m.endswith("linkage") for m in at_run_time)


def test_a_linkage_without_a_closed_form_displays_its_closure():
    """Jupyter shows the closure of a linkage the Newton fallback solves (it used to raise ValueError)."""
    from symlink.mechanism.catalog import stephenson2
    shown = stephenson2()._repr_latex_()
    assert shown.startswith("$\\displaystyle \\begin{aligned}") and shown.count("= 0") == 4


# --- fitting the page --------------------------------------------------------
ROOT = Path(__file__).resolve().parents[2]
PDFLATEX = shutil.which("pdflatex")
needs_tex = pytest.mark.skipif(PDFLATEX is None, reason="pdflatex is not installed (Debian: apt-get install "
                               "texlive-latex-base texlive-latex-recommended); the page-width check needs TeX")
#: An overfull line this much wider than the text is a line that runs into the margin.
OVERFULL_POINTS = 10.0


def overfull_widths(tex: str, folder: Path) -> list[float]:
    """Compile ``tex`` with pdflatex and return the widths (pt) of its overfull boxes; fail if it does not compile."""
    (folder / "doc.tex").write_text(tex, encoding="utf-8")
    done = subprocess.run([PDFLATEX, "-interaction=nonstopmode", "-halt-on-error", "-no-shell-escape", "doc.tex"],
                          cwd=folder, capture_output=True, text=True, timeout=120)
    log = (folder / "doc.log").read_text(encoding="latin-1")
    assert done.returncode == 0, log[-2000:]
    return [float(width) for width in re.findall(r"Overfull \\hbox \(([0-9.]+)pt too wide\)", log)]


@needs_tex
@pytest.mark.parametrize("path", sorted((ROOT / "generated").glob("*.tex")), ids=lambda p: p.stem)
def test_every_generated_document_fits_the_page(path, tmp_path):
    """No line of a committed derivation runs more than 10pt into the margin (a Jansen leg's ran 327pt)."""
    widths = overfull_widths(path.read_text(encoding="utf-8"), tmp_path)
    assert max(widths, default=0.0) <= OVERFULL_POINTS, widths


@needs_tex
def test_long_sums_products_fractions_roots_and_atan2_break_across_lines(tmp_path):
    """Each breakable form, far wider than the page, is broken to fit; the row count shows it was broken."""
    from symlink.symbolic.typeset import align_block as _align
    from symlink.symbolic.position import ClampedSqrt

    angles = sp.symbols("theta_1:25", real=True)
    lengths = sp.symbols("a_1:25", positive=True)
    terms = [r * sp.cos(q) for r, q in zip(lengths, angles)]
    long_sum = sp.Add(*terms)
    x = sp.Symbol("x")
    rows = [(x, long_sum),
            (x, long_sum / (lengths[0] * sp.sin(angles[1] - angles[2]))),
            (x, sp.atan2(long_sum, sp.Add(*(r * sp.sin(q) for r, q in zip(lengths, angles))))),
            (x, ClampedSqrt(sp.Mul(*(r + s - q for r, s, q in zip(lengths, lengths[1:], angles))), 1)),
            (x, -lengths[0] * sp.Mul(*(r + s for r, s in zip(lengths, lengths[1:]))))]
    block = _align(rows)
    first = block[1].split("\\\\\nx &=")[0]
    assert first.count("\\cos") == 24 and len(re.findall(r"(?<![a-z])a_\{", first)) == 24  # every term, once
    assert [row.count("&\\qquad") >= 1 for row in block[1].split("\\\\\nx &=")] == [True] * len(rows)
    body = ["\\begin{align*}", *block[1:-1], "\\end{align*}"]
    tex = "\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n" + "\n".join(body) + "\n\\end{document}\n"
    widths = overfull_widths(tex, tmp_path)
    assert max(widths, default=0.0) <= OVERFULL_POINTS, widths


def test_a_short_row_stays_on_one_line():
    from symlink.symbolic.typeset import aligned_rows as _aligned
    a, theta = sp.symbols("a theta")
    assert _aligned([(sp.Symbol("x"), a * sp.cos(theta))]) == "x &= a \\cos{\\left(\\theta \\right)}"


def test_the_width_estimate_tracks_tex(tmp_path):
    """The estimate that decides the breaks is within 25% of TeX's own measure, checked where TeX is installed."""
    from symlink.symbolic.typeset import latex_width
    samples = [r"\frac{m \dot{\theta} \sin{\left(\beta - \theta \right)}}{b \sin{\left(\beta - \phi \right)}}",
               r"\Delta_{1} W_{x,1} \sigma_{\mathrm{ABCD}} + W_{y,1} \left(w_{1}^{2} + \left(\rho_{4,1} - \rho_{5,1}\right)\right)",
               r"c \ddot{\psi} \sin{\left(\kappa - \psi \right)} - c \dot{\psi}^{2} \cos{\left(\kappa - \psi \right)}",
               r"\operatorname{atan}_{2}\bigl(a + b,\ c\bigr)"]
    if PDFLATEX is None:
        pytest.skip("pdflatex is not installed: no TeX measure to compare with")
    lines = [f"\\setbox0\\hbox{{$\\displaystyle {s}$}}\\typeout{{WIDTH {k} \\the\\wd0}}" for k, s in enumerate(samples)]
    tex = "\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n" + "\n".join(lines) + "\n\\end{document}\n"
    overfull_widths(tex, tmp_path)
    log = (tmp_path / "doc.log").read_text(encoding="latin-1")
    measured = {int(k): float(w) for k, w in re.findall(r"WIDTH (\d+) ([0-9.]+)pt", log)}
    for k, sample in enumerate(samples):
        assert 0.75 <= latex_width(sample) / measured[k] <= 1.25, (sample, latex_width(sample), measured[k])


@needs_tex
@pytest.mark.parametrize("form", ["atan2", "complex", "freudenstein", "half-angle"])
def test_every_form_of_the_fourbar_and_a_linkage_file_compile_without_overfull_boxes(form, tmp_path):
    """The seeds' forms (issue 20) and a linkage file's derivation compile, with no overfull line at all."""
    from symlink.io.export import export_texts
    from symlink.io.linkage_file import catalog_file, load_linkage
    linkage = load_linkage(catalog_file("fourbar")).linkage if form == "atan2" else "fourbar"
    text, = export_texts(linkage, "latex", form=form).values()
    assert overfull_widths(text, tmp_path) == []
