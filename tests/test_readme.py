"""The README is a current front page: every example runs, every transcript prints what it shows, every link lands.

* every ```python block of the README runs;
* every `$ symlink ...` transcript in a plain block, of the README and of the docs pages, prints what
  it shows (commands that open windows, time things or read a scene file from the reader's folder
  are left out; where a transcript shows a warning, it stands before the output as on a terminal);
* every `symlink ...` line of the README's ```sh blocks runs in a scratch folder and writes the
  files its comment names;
* the README stays a front page: at most 15 KB, images by absolute URL (they must work on PyPI)
  that name files in docs/images, links into the docs site that name a page the site has.
"""
import math
import re
import shlex
import shutil

import pytest

from readme_text import DOCS, DOCS_URL, IMAGES_URL, README, ROOT, fenced_blocks, readme
from symlink.cli import main

NOT_REPLAYED = {"bench", "view", "run"}
WRITES_FILES = {"--out", "--plot", "--plot-transmission", "--save", "--json", "--record", "--folder", "--svg", "--dxf",
                "--assembly"}
#: The markdown files whose transcripts are replayed: the README and every docs page.
TRANSCRIBED = [README, *sorted(DOCS.rglob("*.md"))]
#: Docs pages generated at build time (not in the source tree), by their path on the site.
GENERATED_PAGES = {"reference/cli"}


def transcripts() -> list[tuple[str, str, str]]:
    """(file, command, what it prints) for every replayable `$ symlink ...` in a plain block."""
    found = []
    for path in TRANSCRIBED:
        if "_build" in path.parts:
            continue
        for block in fenced_blocks(path.read_text(encoding="utf-8"), ""):
            for command, output in re.findall(r"^\$ (symlink .*)\n((?:(?!\$ ).*\n)*)", block, flags=re.M):
                argv = shlex.split(command)
                if argv[1] not in NOT_REPLAYED and not WRITES_FILES & set(argv):
                    found.append((str(path.relative_to(ROOT)), command, output))
    return found


PYTHON = fenced_blocks(readme(), "python")
TRANSCRIPTS = transcripts()
SHELL = [line.split("#")[0].strip() for block in fenced_blocks(readme(), "sh") for line in block.splitlines()
         if line.startswith("symlink ")]


@pytest.mark.parametrize("index", range(len(PYTHON)))
def test_readme_python_block_runs(index, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    exec(compile(PYTHON[index], f"README block {index}", "exec"), {"__name__": "__readme__"})  # our own README


@pytest.mark.parametrize("where, command, output", TRANSCRIPTS, ids=[f"{w}:{c[:50]}" for w, c, _ in TRANSCRIPTS])
def test_transcript_is_current(capsys, where, command, output):
    assert main(shlex.split(command)[1:]) == 0
    out, err = capsys.readouterr()
    assert output in (out, err + out) or any(same_but_last_digits(output, text) for text in (out, err + out)), out


#: A number as the command line prints it.
NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")


def same_but_last_digits(shown: str, printed: str) -> bool:
    """The same text, its numbers equal to 1e-13 relative: a full-precision number (JSON) may differ in its last
    digits between the NumPy module and the compiled backend, which agree to a few units in the last place."""
    if NUMBER.sub("#", shown) != NUMBER.sub("#", printed):
        return False
    return all(math.isclose(float(a), float(b), rel_tol=1e-13, abs_tol=1e-300)
               for a, b in zip(NUMBER.findall(shown), NUMBER.findall(printed)))


def test_every_table_command_has_a_transcript():
    shown = {shlex.split(command)[1] for _, command, _ in TRANSCRIPTS}
    assert {"fourbar", "loop", "analyze", "quick-return", "plan", "slider-crank", "watt2", "table"} <= shown


@pytest.mark.parametrize("command", SHELL)
def test_readme_shell_command_writes_its_files(command, tmp_path, monkeypatch, capsys):
    shutil.copytree(ROOT / "linkages", tmp_path / "linkages")  # `symlink derive linkages/fourbar.toml` as in a checkout
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    assert main(shlex.split(command)[1:]) == 0, capsys.readouterr().err
    line = next(line for block in fenced_blocks(readme(), "sh") for line in block.splitlines()
                if line.startswith(command))
    named = re.findall(r"(\S+\.(?:png|tex|gif))", line.split("#", 1)[1]) if "#" in line else []
    out = shlex.split(command)[shlex.split(command).index("--out") + 1]
    for name in named or [out]:
        path = tmp_path / name
        assert path.exists() and (path.is_dir() or path.stat().st_size > 100), f"{command} did not write {name}"


def test_derive_latex_example_writes_the_closed_forms(tmp_path, monkeypatch, capsys):
    """The README's `symlink derive fourbar --to latex` writes a document with the closure and the rates."""
    assert any(command.startswith("symlink derive fourbar --to latex") for command in SHELL)
    monkeypatch.chdir(tmp_path)
    assert main(["derive", "fourbar", "--to", "latex", "--out", "build"]) == 0
    tex = (tmp_path / "build" / "fourbar.tex").read_text()
    assert tex.startswith(r"\documentclass") and tex.rstrip().endswith(r"\end{document}")
    assert "Closure" in tex and r"\dot{\phi}" in tex and r"\ddot{\phi}" in tex  # positions, rates, accelerations


def test_readme_first_command_installs_from_a_checkout_and_prints_the_seed_table(capsys):
    """The README's first command is an install from the checkout (``pip install -e .``, which works on a fresh
    machine: this folder is an installable project with the ``symlink`` command) followed by the main job; the
    package index's install is named as what it is, not given as the way in."""
    first = fenced_blocks(readme(), "sh")[0].strip().splitlines()[0]
    assert readme().index("```") == readme().index("```sh\n" + first)  # the README's first block of all
    install, _, job = first.partition(" && ")
    assert install == "pip install -e ."
    assert readme().index(first) < readme().index("pip install symlink-kinematics")
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert 'name = "symlink-kinematics"' in pyproject and 'symlink = "symlink.__main__:entry"' in pyproject
    assert job.startswith("symlink fourbar ")
    assert main(shlex.split(job)[1:]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split()[:2] == ["crank", "(deg)"]
    assert lines[1].split()[:4] == ["0.0000", "+1", "52.5127", "110.7424"]  # seed 003 at theta = 0
    assert "published" in readme().split("pip install symlink-kinematics")[1].split("\n\n")[0]


def test_readme_is_a_front_page():
    text = readme()
    assert len(text.encode("utf-8")) <= 15 * 1024
    assert "pip install -e '.[test]' && pytest -n auto\n" in text  # the test command, exactly


def test_ci_runs_the_readme_test_command_as_written():
    """.ci/run takes the README's line that installs the test extra and runs it, so the two cannot drift."""
    script = (ROOT / ".ci" / "run").read_text()
    rule = "grep -m 1 \"^pip install -e '.\\[test\\]'\" README.md"
    assert rule in script and 'bash -c "$tests"' in script
    lines = [line for line in readme().splitlines() if re.match(r"^pip install -e '\.\[test\]'", line)]
    assert lines[0] == "pip install -e '.[test]' && pytest -n auto"


def test_readme_images_are_absolute_and_exist():
    text = readme()
    images = re.findall(r"!\[[^\]]*\]\(([^)\s]+)", text) + re.findall(r'<img [^>]*src="([^"]+)"', text)
    assert images, "the README shows no picture"
    for url in images:
        assert url.startswith(IMAGES_URL), f"{url}: images must be absolute URLs under {IMAGES_URL} (PyPI)"
        assert (DOCS / "images" / url[len(IMAGES_URL):]).is_file(), f"{url}: no such file in docs/images"


def test_readme_links_into_the_docs_land_on_pages():
    pages = re.findall(re.escape(DOCS_URL) + r"([\w/.-]+)\.html", readme())
    assert len(pages) >= 10
    for page in pages:
        source = DOCS / f"{page}.md"
        generated = page in GENERATED_PAGES or re.fullmatch(r"reference/api/symlink(\.\w+)*", page)
        assert source.is_file() or generated, f"{DOCS_URL}{page}.html: no docs/{page}.md"
        if page.startswith("reference/api/"):
            module = page.rsplit("/", 1)[1]
            assert (ROOT / (module.replace(".", "/") + ".py")).is_file() or \
                   (ROOT / module.replace(".", "/") / "__init__.py").is_file(), f"{module}: no such module"
    assert all(re.fullmatch(r"[^\s]+", link) for link in re.findall(r"\]\(([^)]+)\)", readme())), \
        "a link with a space"
    assert not re.findall(r"\]\((?!https?://)[^)]+\)", readme()), "relative links break on PyPI"
