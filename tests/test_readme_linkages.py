"""The README's 'New linkages and your own' section: its code runs and its printed output is current."""
import contextlib
import io

from readme_text import fenced_blocks, readme


def blocks(kind: str) -> list[str]:
    """The fenced blocks of the section whose language is ``kind`` ("" for plain ones)."""
    return fenced_blocks(readme("New linkages and your own"), kind)


def run_python(code: str) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "README linkages", "exec"), {"__name__": "__readme__"})  # our own README
    return out.getvalue()


def test_the_users_own_linkage_runs_and_prints_what_the_readme_says(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    user, numeric = blocks("python")
    assert len(user.strip().splitlines()) <= 30   # "about twenty lines" of derivation, solver and plot
    printed = run_python(user)
    plan = next(b for b in blocks("") if b.startswith("press: closed form"))
    assert printed.startswith(plan)
    assert "True 4.747 7.2297" in printed
    assert r"- \frac{c \dot{\phi} \sin{\left(\phi - \psi \right)}}{\cos{\left(\psi \right)}}" in printed
    tex = (tmp_path / "press.tex").read_text()
    assert r"s &= size_{2} \left(\Delta_{2} \sigma_{\mathrm{DCF}} - W_{x,2}\right)" in tex
    assert (tmp_path / "press.png").stat().st_size > 1000
    assert "sympy" not in (tmp_path / "press_solver.py").read_text().split('"""', 2)[2]
    printed = run_python(numeric)
    assert printed == "[ 80.934  86.891 111.938 111.949]\n[-0.5714  0.5903  0.3636 -0.402 ]\n"
