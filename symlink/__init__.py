"""symlink: symbolic derivation of planar linkage kinematics.

Describe a linkage as vector loops, get its closure equations, their
closed-form solution with the assembly branch, velocities and accelerations
by differentiation, LaTeX, and fast vectorised NumPy solvers.

Its public names (Vector, Loop, Linkage, ...) are loaded on first use (they need SymPy): ``import symlink``
alone, as the command line does for a scene it finds in its cache, costs no
SymPy import.
"""
from typing import TYPE_CHECKING, Any

from .version import __version__

if TYPE_CHECKING:
    from .linkage import Linkage
    from .loops import Loop
    from .vectors import Vector, VectorSum, acceleration, coordinates, lengths, rate, time_derivative

_VECTOR_NAMES = ("Vector", "VectorSum", "coordinates", "lengths", "rate", "acceleration", "time_derivative")

__all__ = ["Vector", "VectorSum", "Loop", "Linkage", "coordinates", "lengths", "rate", "acceleration",
           "time_derivative", "__version__"]


def __getattr__(name: str) -> Any:
    """The public names, imported when first asked for (PEP 562)."""
    if name in _VECTOR_NAMES:
        from . import vectors
        value = getattr(vectors, name)
    elif name == "Loop":
        from . import loops
        value = loops.Loop
    elif name == "Linkage":
        from . import linkage
        value = linkage.Linkage
    else:
        raise AttributeError(f"module 'symlink' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
