"""The README is current: every ```python block runs, and every `$ symlink ...` transcript prints what it shows.

Transcripts of commands that write files, open windows, read a scene file from
the reader's folder or time things (bench) are left out; where a transcript
shows a warning, it stands before the output as on a terminal (stderr, then stdout).
"""
import re
import shlex

import pytest

from readme_text import fenced_blocks, readme
from symlink.cli import main

NOT_REPLAYED = {"bench", "view", "animate", "curve", "run", "export"}
WRITES_FILES = {"--out", "--plot", "--plot-transmission", "--save", "--json"}


def transcripts() -> list[tuple[str, str]]:
    """(command, what it prints) for every replayable `$ symlink ...` in a plain block."""
    found = []
    for block in fenced_blocks(readme(), ""):
        for command, output in re.findall(r"^\$ (symlink .*)\n((?:(?!\$ ).*\n)*)", block, flags=re.M):
            argv = shlex.split(command)
            if argv[1] not in NOT_REPLAYED and not WRITES_FILES & set(argv):
                found.append((command, output))
    return found


PYTHON = fenced_blocks(readme(), "python")
TRANSCRIPTS = transcripts()


@pytest.mark.parametrize("index", range(len(PYTHON)))
def test_readme_python_block_runs(index, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    exec(compile(PYTHON[index], f"README block {index}", "exec"), {"__name__": "__readme__"})  # our own README


@pytest.mark.parametrize("command, output", TRANSCRIPTS, ids=[c[:50] for c, _ in TRANSCRIPTS])
def test_readme_transcript_is_current(capsys, command, output):
    assert main(shlex.split(command)[1:]) == 0
    out, err = capsys.readouterr()
    assert output in (out, err + out)


def test_every_table_command_has_a_transcript():
    shown = {shlex.split(command)[1] for command, _ in TRANSCRIPTS}
    assert {"fourbar", "loop", "analyze", "quick-return", "plan", "slider-crank", "watt2"} <= shown
