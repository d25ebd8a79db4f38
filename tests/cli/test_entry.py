"""The console script: an interrupt at any moment, the command line's own import included, is one line and 130."""
import builtins
import subprocess
import sys

import symlink.__main__ as entry_module


def test_an_interrupt_while_the_command_line_imports_is_one_line_and_130(monkeypatch, capsys):
    real_import = builtins.__import__

    def interrupted(name, globals=None, locals=None, fromlist=(), level=0):
        if level == 1 and name == "cli":  # `from .cli import main` in symlink/__main__.py
            raise KeyboardInterrupt
        return real_import(name, globals, locals, fromlist, level)

    monkeypatch.setattr(builtins, "__import__", interrupted)
    assert entry_module.entry() == 130
    captured = capsys.readouterr()
    assert captured.err == "symlink: interrupted\n" and captured.out == ""


def test_the_console_script_is_the_guarded_entry():
    from importlib.metadata import entry_points
    scripts = [e for e in entry_points(group="console_scripts") if e.name == "symlink"]
    if scripts:  # an installed checkout: the script calls entry(), not cli.main directly
        assert scripts[0].value == "symlink.__main__:entry"
    text = (__import__("pathlib").Path(entry_module.__file__).resolve().parents[1] / "pyproject.toml").read_text()
    assert 'symlink = "symlink.__main__:entry"' in text


def test_python_dash_m_runs_the_command():
    done = subprocess.run([sys.executable, "-m", "symlink", "--version"], capture_output=True, text=True)
    assert done.returncode == 0 and done.stdout.startswith("symlink ")
