"""Loading a generated NumPy module: its source run into a fresh namespace, without SymPy.

The printers (:mod:`symlink.codegen.numpy`) need SymPy; running what they wrote does not, so
that a solver read from the disk cache (:mod:`symlink.numeric.cached_solver`) loads in a process that
never imports SymPy.

>>> load_numpy_module("def solve(x):\\n    return 2 * x\\n")["solve"](3)
6
"""
from __future__ import annotations

__all__ = ["load_numpy_module"]


def load_numpy_module(source: str) -> dict:
    """Run generated module source (symlink's own output, never user text) and return its namespace."""
    namespace: dict = {"__name__": "symlink_generated"}
    exec(compile(source, "<symlink generated>", "exec"), namespace)  # noqa: S102 - our own generated code
    return namespace
