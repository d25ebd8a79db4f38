"""symlink: symbolic derivation of planar linkage kinematics.

Describe a linkage as vector loops, get its closure equations, their
closed-form solution with the assembly branch, velocities and accelerations
by differentiation, LaTeX, and fast vectorised NumPy solvers.
"""
from .version import __version__

from .vectors import Vector, VectorSum, coordinates, lengths, rate, acceleration, time_derivative  # noqa: E402
from .loops import Loop  # noqa: E402
from .linkage import Linkage  # noqa: E402

__all__ = ["Vector", "VectorSum", "Loop", "Linkage", "coordinates", "lengths", "rate", "acceleration",
           "time_derivative", "__version__"]
