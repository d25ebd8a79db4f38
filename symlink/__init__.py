"""symlink: symbolic derivation of planar linkage kinematics.

Describe a linkage as vector loops, get its closure equations, their
closed-form solution with the assembly branch, velocities and accelerations
by differentiation, LaTeX, and fast vectorised NumPy solvers.
"""
__version__ = "0.1.0"

from .vectors import Vector, VectorSum, coordinates, lengths, rate, acceleration, time_derivative  # noqa: E402
from .loops import Loop  # noqa: E402
from .linkage import Linkage  # noqa: E402

__all__ = ["Vector", "VectorSum", "Loop", "Linkage", "coordinates", "lengths", "rate", "acceleration",
           "time_derivative", "__version__"]
