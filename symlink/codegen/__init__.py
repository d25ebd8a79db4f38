"""Code generation: one intermediate form, one printer module per language, chosen through one table.

* :mod:`symlink.codegen.program`: the straight-line program with common
  subexpressions eliminated, which every printer prints;
* :mod:`symlink.codegen.numpy`, :mod:`symlink.codegen.c`,
  :mod:`symlink.codegen.octave`, :mod:`symlink.codegen.javascript`,
  :mod:`symlink.codegen.latex`: the printers;
* :mod:`symlink.codegen.scalar`: one state on single floats (for an integrator);
* :mod:`symlink.codegen.newton` and :mod:`symlink.codegen.newton_driver`: the
  numeric fallback's NumPy module and the Newton driver it embeds.

Every printer module offers ``export_files(linkage, stem, functions, title,
regenerate) -> {file name: text}``, where ``functions`` are ``(name, outputs,
docstring)``; :func:`printer` picks the module of a language from
:data:`PRINTERS`.  The printers are imported on first use only, so importing
this package costs nothing (and imports no linkage).

>>> sorted(PRINTERS)
['c', 'javascript', 'latex', 'numpy', 'octave']
>>> printer("octave").__name__
'symlink.codegen.octave'
"""
from __future__ import annotations

import importlib
from types import ModuleType

__all__ = ["PRINTERS", "printer"]

#: Language -> the printer module (in this package) that writes it.
PRINTERS = {"numpy": "numpy", "c": "c", "octave": "octave", "javascript": "javascript", "latex": "latex"}


def printer(language: str) -> ModuleType:
    """The printer module of ``language``; ``ValueError`` naming the languages there are.

    Parameters
    ----------
    language : str
        One of :data:`PRINTERS`: ``"numpy"``, ``"c"``, ``"octave"`` or ``"latex"``.

    Returns
    -------
    module
        The printer module (``symlink.codegen.c`` for ``"c"``).

    Raises
    ------
    ValueError
        For any other language, naming those there are.

    Examples
    --------
    >>> import symlink
    >>> symlink.printer("c").__name__, sorted(symlink.PRINTERS)
    ('symlink.codegen.c', ['c', 'javascript', 'latex', 'numpy', 'octave'])
    """
    if language not in PRINTERS:
        raise ValueError(f"unknown export format {language!r}; choose one of {', '.join(PRINTERS)}")
    return importlib.import_module(f"{__name__}.{PRINTERS[language]}")
