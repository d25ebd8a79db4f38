"""Dynamics of a linkage from its closed-form kinematics: mass properties and loads, inverse dynamics.

:mod:`symlink.dynamics.model` holds the model (masses, centres, inertias, loads; the
generalised inertia ``M(q)``, ``dM/dq`` and applied forces); :mod:`symlink.dynamics.inverse`
derives the driving effort, joint reactions and shaking force and moment, and
:func:`~symlink.dynamics.inverse.dynamic_linkage` makes them outputs of a linkage.
"""
from .inverse import DynamicLinkage, dynamic_linkage
from .model import BodyTorque, Damper, DynamicModel, Gravity, MassProperties, PointForce, Spring

__all__ = ["BodyTorque", "Damper", "DynamicLinkage", "DynamicModel", "Gravity", "MassProperties", "PointForce",
           "Spring", "dynamic_linkage"]
