"""Everyday command-line habits: --version, help with units and an example, stdin, Ctrl-C, pipes, streaming."""
from __future__ import annotations

import os
import signal
import subprocess
import sys

import pytest

from symlink import __version__
from interrupts import interruptible
from symlink.cli import build_parser, main

FOURBAR = ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80"]
SCENE = 'linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 20\nb = 66\nc = 56\nd = 80\n[input]\nangles = [0]\n'


def command(*argv: str, cache=None, **options) -> subprocess.Popen:
    environment = {**os.environ, "PYTHONUNBUFFERED": "1", **({"SYMLINK_CACHE": str(cache)} if cache else {})}
    return subprocess.Popen([sys.executable, "-m", "symlink", *argv], env=environment, **options)


def test_version(capsys):
    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"symlink {__version__}"


@pytest.mark.parametrize("name", sorted(build_parser()._subparsers._group_actions[0].choices))
def test_every_command_has_a_summary_units_and_an_example(name, capsys):
    commands = build_parser()._subparsers._group_actions[0]
    # an alias (derive of export) shares its command's parser and summary
    same = [other for other, parser in commands.choices.items() if parser is commands.choices[name]]
    summary = next(action.help for action in commands._choices_actions if action.dest.split(" (")[0] in same)
    assert summary and "\n" not in summary
    text = commands.choices[name].format_help()  # table commands add their options (and text) when used
    assert "units:" in text and any(f"example: symlink {other}" in text for other in same)


def test_an_example_in_the_help_runs(capsys, tmp_path):
    """Each help example that writes no file runs as shown."""
    commands = build_parser()._subparsers._group_actions[0].choices
    for name in ("fourbar", "slider-crank", "inverted-slider-crank", "watt2", "fivebar", "plan", "analyze", "loop",
                 "quick-return"):
        example = next(line for line in commands[name].format_help().splitlines() if line.startswith("example:"))
        argv = example.split()[2:]
        assert main(argv) == 0, (name, capsys.readouterr().err)
        capsys.readouterr()


def test_a_scene_from_stdin():
    done = subprocess.run([sys.executable, "-m", "symlink", "run", "-", "--format", "csv"], input=SCENE,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    header, row = done.stdout.splitlines()[:2]
    assert header == "crank,branch,rocker" and abs(float(row.split(",")[2]) - 110.7424) < 1e-4


def test_runtime_warnings_never_reach_the_terminal():
    """A toggle divides by zero in the rates: the row is named on stderr, and no RuntimeWarning is shown."""
    done = subprocess.run([sys.executable, "-W", "default", "-m", "symlink", "fourbar", "--crank", "1",
                           "--coupler", "2", "--rocker", "2", "--ground", "3", "--angles", "0,180",
                           "--crank-speed", "1"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0
    assert "Warning" not in done.stderr and "singular" in done.stderr


def test_a_closed_pipe_ends_the_command_quietly():
    child = command(*FOURBAR, "--step", "0.001", "--format", "csv", stdout=subprocess.PIPE,
                    stderr=subprocess.PIPE)
    assert child.stdout.readline().startswith(b"crank,branch")
    child.stdout.close()  # like `| head -1`
    _, err = child.communicate(timeout=120)
    assert child.returncode == 0 and err == b""


# The child takes SIGINT as a terminal's foreground job does (tests/interrupts.py): run as a background job of a
# shell without job control (a CI script's `pytest -n auto &`), every process inherits SIGINT ignored, and this
# child then ran on through its 7.2 million rows (the clean-clone run that did not stop within 120 s).
def test_ctrl_c_exits_130_without_a_traceback():
    child = command(*FOURBAR, "--step", "0.0001", "--format", "csv", stdout=subprocess.PIPE,
                    stderr=subprocess.PIPE, preexec_fn=interruptible)
    assert child.stdout.readline()  # running
    child.send_signal(signal.SIGINT)
    try:  # both pipes drained while it stops (a child blocked on a full stderr pipe would never end)
        _, err = child.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        child.kill()
        child.communicate()
        raise
    assert child.returncode == 130
    assert b"Traceback" not in err and err.strip().splitlines()[-1] == b"symlink: interrupted"


def test_a_long_table_streams_its_first_rows_before_the_rest_is_computed(tmp_path):
    """With 7.2 million rows ahead, the header and first rows arrive while the command still runs."""
    child = command(*FOURBAR, "--step", "0.0001", "--format", "csv", stdout=subprocess.PIPE,
                    stderr=subprocess.DEVNULL)
    try:
        lines = [child.stdout.readline() for _ in range(3)]
        assert lines[0].startswith(b"crank,branch") and lines[1].startswith(b"0.0,1,")
        assert child.poll() is None
    finally:
        child.kill()
        child.communicate()


@pytest.mark.parametrize("module", sorted(__import__("symlink.cli", fromlist=["COMMANDS"]).COMMANDS))
def test_each_command_module_registers_what_the_command_list_says(module):
    """``symlink.cli.COMMANDS`` names each module's commands, so that a command line imports that module alone;
    the table module registers the catalog's table commands besides."""
    import importlib

    from symlink.cli import COMMANDS
    from symlink.cli.options import Parser
    commands = Parser(prog="symlink").add_subparsers(dest="command", parser_class=Parser)
    importlib.import_module(f"symlink.cli.{module}").register(commands)
    registered = set(commands.choices)
    assert set(COMMANDS[module]) <= registered
    if module != "tables":
        assert registered == set(COMMANDS[module])


def test_a_command_line_imports_the_module_of_its_command_only():
    program = ("import sys, symlink.cli as cli; cli.build_parser('tolerance'); "
               "print(*sorted(name for name in sys.modules if name.startswith('symlink.cli.')))")
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, check=True, timeout=120)
    imported = set(done.stdout.split())
    assert "symlink.cli.tolerance" in imported
    assert not {"symlink.cli.sweep", "symlink.cli.analyze", "symlink.cli.tables"} & imported
