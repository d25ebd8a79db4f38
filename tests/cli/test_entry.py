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


#: A child that sends itself SIGINT while an extension module's import (NumPy's, which imports ``datetime`` from C)
#: is under way, then runs the console script's entry.  An interrupt raised there surfaces as an ImportError ("bad
#: install") or is swallowed, so it must be held back until the import is done.
_INTERRUPTED_IN_AN_EXTENSION_IMPORT = """
import os, signal, sys
class InterruptOnce:
    def find_spec(self, name, path=None, target=None):
        if name == "datetime":
            sys.meta_path.remove(self)
            os.kill(os.getpid(), signal.SIGINT)
        return None
from symlink.__main__ import entry
assert "numpy" not in sys.modules and "datetime" not in sys.modules
sys.meta_path.insert(0, InterruptOnce())
sys.argv = ["symlink", "--version"]
sys.exit(entry())
"""


def test_an_interrupt_inside_an_extension_import_is_held_to_the_end_of_the_import():
    from tests.interrupts import interruptible
    done = subprocess.run([sys.executable, "-c", _INTERRUPTED_IN_AN_EXTENSION_IMPORT], capture_output=True,
                          text=True, preexec_fn=interruptible, timeout=120)
    assert (done.returncode, done.stderr, done.stdout) == (130, "symlink: interrupted\n", "")


def test_the_package_and_the_entry_import_little_before_the_hold_starts():
    """What runs before :func:`symlink.__main__.entry` can hold an interrupt back is kept small: no typing, no signal."""
    done = subprocess.run([sys.executable, "-c", "import sys; import symlink.__main__; "
                           "print(sorted({'typing', 'signal', 'numpy'} & set(sys.modules)))"],
                          capture_output=True, text=True)
    assert done.stdout.strip() == "[]", done.stderr
