"""A solver's compiled backend, built in the background while its NumPy module answers (one home for both solvers).

Imports nothing of the compiled backend itself: a warm table whose solver never builds stays without it.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .compiled_library import Build

__all__ = ["BackgroundBackend"]


class BackgroundBackend:
    """What a solver says of its compiled backend, built in the background while its NumPy module answers.

    A solver sets ``_compiled`` (the compiled function, or None) and ``_build`` (a
    :class:`~symlink.numeric.compiled_library.Build` under way, or None); a build that has finished is adopted at
    the next call.  Shared by :class:`symlink.numeric.solver.Solver` and
    :class:`symlink.numeric.cached_solver.CachedSolver`.
    """

    _compiled: Any = None
    _build: Build | None = None

    @property
    def backend(self) -> str:
        """``"compiled"`` or ``"numpy"``: the backend that answers the next call."""
        return "numpy" if self._answering() is None else "compiled"

    def wait_for_backend(self, timeout: float | None = None) -> str:
        """Wait (at most ``timeout`` seconds) for a background build of the compiled backend; the backend then."""
        if self._build is not None:
            self._build.wait(timeout)
        return self.backend

    def _answering(self) -> Any:
        """The compiled function where it answers (a background build just finished is adopted here), else None."""
        if self._build is not None and self._build.done():
            self._compiled, self._build = self._build.entry(), None
        return self._compiled
