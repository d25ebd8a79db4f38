"""Dynamics of a linkage from its closed-form kinematics: mass properties and loads, inverse dynamics.

:mod:`symlink.dynamics.model` holds the model (masses, centres, inertias, loads; the
generalised inertia ``M(q)``, ``dM/dq`` and applied forces); :mod:`symlink.dynamics.inverse`
derives the driving effort, joint reactions and shaking force and moment, and
:func:`~symlink.dynamics.inverse.dynamic_linkage` makes them outputs of a linkage;
:mod:`symlink.dynamics.forward` integrates the motion under a motor (SciPy, the extra
``dynamics``) and :mod:`symlink.dynamics.flywheel` sizes a flywheel.

Each name is loaded from its module on first use (PEP 562), as the names of :mod:`symlink` are: a warm
``symlink flywheel`` runs :mod:`~symlink.dynamics.flywheel` and :mod:`~symlink.dynamics.forward` on code from the
disk cache without importing the model's modules (SymPy).

>>> import symlink.dynamics
>>> symlink.dynamics.flywheel_inertia(2.0, 10.0, 0.02)
1.0
"""
from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the names as type checkers see them; at run time each is loaded by __getattr__
    from .flywheel import FlywheelSizing, SpeedBand, TorqueCycle, energy_fluctuation, flywheel_inertia
    from .forward import ConstantTorque, ForwardDynamics, LinearMotor, Motion, Stop
    from .inverse import DynamicLinkage, dynamic_linkage
    from .model import BodyTorque, Damper, DynamicModel, Gravity, MassProperties, PointForce, Spring

#: Every name of the package -> its module (relative to the package).
_NAMES = {
    **dict.fromkeys(("FlywheelSizing", "SpeedBand", "TorqueCycle", "energy_fluctuation", "flywheel_inertia"),
                    "flywheel"),
    **dict.fromkeys(("ConstantTorque", "ForwardDynamics", "LinearMotor", "Motion", "Stop"), "forward"),
    **dict.fromkeys(("DynamicLinkage", "dynamic_linkage"), "inverse"),
    **dict.fromkeys(("BodyTorque", "Damper", "DynamicModel", "Gravity", "MassProperties", "PointForce", "Spring"),
                    "model"),
}

__all__ = ["BodyTorque", "Damper", "DynamicLinkage", "DynamicModel", "Gravity", "MassProperties", "PointForce",
           "Spring", "dynamic_linkage", "ConstantTorque", "ForwardDynamics", "LinearMotor", "Motion", "Stop",
           "FlywheelSizing", "SpeedBand", "TorqueCycle", "energy_fluctuation", "flywheel_inertia"]


def __getattr__(name: str) -> object:
    """A name of the package, imported from its module when first asked for (PEP 562)."""
    try:
        module = _NAMES[name]
    except KeyError:
        raise AttributeError(f"module 'symlink.dynamics' has no attribute {name!r}") from None
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
