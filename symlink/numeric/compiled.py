"""An optional compiled backend: the generated C, built with the system compiler, called through ctypes.

NumPy evaluates one operation at a time over whole arrays; the compiled loop
evaluates every operation of one configuration in registers before moving to
the next.  :func:`compiled_solver` takes the same outputs and is called with
the same keywords as :class:`symlink.numeric.solver.Solver` and returns the same dict
of arrays; where no C compiler exists it says so in a warning and returns the
NumPy solver.

How the library is compiled, cached, checked and loaded (and where that fails, the one warning and the
NumPy solver) is :mod:`symlink.numeric.compiled_library`'s to say.

The compiler flags, and glibc's vector math library that the loops call, are described in
:mod:`symlink.numeric.compiled_library`, which builds and loads the libraries.

>>> import numpy
>>> from symlink.mechanism.catalog import fourbar
>>> solver = compiled_solver(fourbar(), ["rocker"])
>>> result = solver(theta=numpy.radians([0.0, 40.0]), a=20, b=66, c=56, d=80, branch=1)
>>> numpy.degrees(result["rocker"]).round(2).tolist(), result["assembled"].tolist()
([110.74, 103.82], [True, True])
"""

from __future__ import annotations

import subprocess
import warnings
from functools import cached_property
from typing import Sequence

from .compiled_library import *  # noqa: F401,F403 - this module's public names, kept where callers import them
from .compiled_library import (CompileError, CompilerUnavailable, FallbackWarning, CompiledFunction, _builds,  # noqa: F401
                               _entry, _intact, _loaded, _private_folder, _probed, c_solver_source, compile_shared)
from .compiled_library import __all__ as _library_names
from ..symbolic.linkage import Linkage
from .solver import Solver

__all__ = ["CompiledSolver", "compiled_solver", *_library_names]


class CompiledSolver(Solver):
    """A :class:`~symlink.numeric.solver.Solver` whose arithmetic runs in the compiled C loop, built now.

    ``CompilerUnavailable`` where no C compiler works; :func:`compiled_solver`
    (and ``Solver(..., backend="compiled")``) fall back to NumPy instead.
    ``function`` is the compiled function (called with keywords, as the NumPy module's is)
    and ``source`` its C source.

    Parameters
    ----------
    linkage : Linkage
        A linkage with a closed-form plan.
    outputs : sequence of str
        The outputs, as for :class:`Solver`.

    Raises
    ------
    symlink.numeric.compiled_library.CompilerUnavailable
        Where no C compiler works.

    Examples
    --------
    >>> import math, symlink
    >>> solver = symlink.CompiledSolver(symlink.fourbar(), ["rocker"])  # doctest: +SKIP
    >>> # skipped: it builds a C library with the system's compiler (seconds, and a compiler is optional)
    >>> solver.backend, round(math.degrees(float(solver(theta=0.0, a=20, b=66, c=56, d=80)["rocker"])), 2)  # doctest: +SKIP
    ('compiled', 110.74)
    """

    def __init__(self, linkage: Linkage, outputs: Sequence[str]) -> None:
        outputs = list(outputs)
        if not outputs:
            raise ValueError(f"ask {linkage.name} for at least one output; it has {', '.join(linkage.output_names())}")
        super().__init__(linkage, outputs, backend="numpy")  # self.outputs: with the singular flag they need
        facts = c_solver_source(linkage, self.outputs)
        self.backend_choice = "compiled"
        self.source = facts["source"]
        self.arguments = list(facts["arguments"])
        self.library = compile_shared(self.source)
        self.function: CompiledFunction = _entry(self.library, facts)
        self._compiled = self.function

    @cached_property
    def required(self) -> list[str]:
        """The arguments a call must give: those of the C function without a default."""
        return [name for name in self.arguments if name not in self.function.defaults]


def compiled_solver(linkage: Linkage, outputs: Sequence[str]) -> Solver:
    """The compiled solver of ``outputs``, or the NumPy :class:`~symlink.numeric.solver.Solver` with one warning.

    Any failure to compile, link, write or load (no compiler, a full disk, a
    folder at the library's name) falls back; bad ``outputs`` still raise
    ``ValueError``.

    Parameters
    ----------
    linkage : Linkage
        A linkage with a closed-form plan.
    outputs : sequence of str
        The outputs, as for :class:`Solver`.

    Returns
    -------
    Solver
        A :class:`CompiledSolver`, or where compiling fails the NumPy :class:`Solver` (one ``FallbackWarning``).

    Examples
    --------
    >>> import math, symlink
    >>> solver = symlink.compiled_solver(symlink.fourbar(), ["rocker"])  # doctest: +SKIP
    >>> # skipped: it builds a C library with the system's compiler (seconds, and a compiler is optional)
    >>> round(math.degrees(float(solver(theta=0.0, a=20, b=66, c=56, d=80)["rocker"])), 2)  # doctest: +SKIP
    110.74
    """
    for name in outputs:
        linkage.output(name)  # ValueError naming the outputs there are, whatever the backend
    try:
        return CompiledSolver(linkage, outputs)
    except (CompilerUnavailable, CompileError, OSError, subprocess.SubprocessError) as error:
        warnings.warn(f"symlink: no compiled backend, using NumPy instead: {error}", FallbackWarning, stacklevel=2)
        return Solver(linkage, outputs, backend="numpy")
