"""Loading a generated NumPy module: its source compiled and run into a fresh namespace, without SymPy.

The printers (:mod:`symlink.codegen.numpy`) need SymPy; running what they wrote does not, so
that a solver read from the disk cache (:mod:`symlink.numeric.cached_solver`) loads in a process that
never imports SymPy.  Compiling and running are two steps, so that the disk cache can keep the
compiled bytecode of a module beside its text (:func:`symlink.numeric.cache.cached_module`) and a
warm process skips the compilation (some milliseconds, about 20 for a 40 kB Newton module).

>>> load_numpy_module("def solve(x):\\n    return 2 * x\\n")["solve"](3)
6
>>> run_numpy_module(compile_numpy_module("TWICE = 2 * 21\\n"))["TWICE"]
42
"""
from __future__ import annotations

from types import CodeType

__all__ = ["load_numpy_module", "compile_numpy_module", "run_numpy_module", "MODULE_FILENAME"]

#: The file name of every generated module's code (in tracebacks).
MODULE_FILENAME = "<symlink generated>"


def compile_numpy_module(source: str) -> CodeType:
    """The code object of generated module source (symlink's own output, never user text).

    Compiled on its own flags (no ``__future__`` feature of this module is inherited), at the interpreter's
    optimization level: the same source gives the same code in any caller.
    """
    return compile(source, MODULE_FILENAME, "exec", dont_inherit=True)


def run_numpy_module(code: CodeType) -> dict:
    """Run the code of a generated module (:func:`compile_numpy_module`) and return its namespace."""
    namespace: dict = {"__name__": "symlink_generated"}
    exec(code, namespace)  # noqa: S102 - our own generated code
    return namespace


def load_numpy_module(source: str) -> dict:
    """Compile and run generated module source (symlink's own output, never user text); its namespace."""
    return run_numpy_module(compile_numpy_module(source))
