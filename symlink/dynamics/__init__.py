"""Dynamics of a linkage from its closed-form kinematics: mass properties and loads, inverse dynamics.

:mod:`symlink.dynamics.model` holds the model (masses, centres, inertias, loads; the
generalised inertia ``M(q)``, ``dM/dq`` and applied forces); :mod:`symlink.dynamics.inverse`
derives the driving effort, joint reactions and shaking force and moment, and
:func:`~symlink.dynamics.inverse.dynamic_linkage` makes them outputs of a linkage;
:mod:`symlink.dynamics.forward` integrates the motion under a motor (SciPy, the extra
``dynamics``) and :mod:`symlink.dynamics.flywheel` sizes a flywheel.
"""
from .flywheel import FlywheelSizing, SpeedBand, TorqueCycle, energy_fluctuation, flywheel_inertia
from .forward import ConstantTorque, ForwardDynamics, LinearMotor, Motion, Stop
from .inverse import DynamicLinkage, dynamic_linkage
from .model import BodyTorque, Damper, DynamicModel, Gravity, MassProperties, PointForce, Spring

__all__ = ["BodyTorque", "Damper", "DynamicLinkage", "DynamicModel", "Gravity", "MassProperties", "PointForce",
           "Spring", "dynamic_linkage", "ConstantTorque", "ForwardDynamics", "LinearMotor", "Motion", "Stop",
           "FlywheelSizing", "SpeedBand", "TorqueCycle", "energy_fluctuation", "flywheel_inertia"]
