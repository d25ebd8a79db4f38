"""Analysis of linkages: mobility, reachable ranges and toggles, transmission angles, limit positions.

One concept a module:

* :mod:`~symlink.mechanism.mobility`: Gruebler/Kutzbach mobility of any linkage;
* :mod:`~symlink.analysis.grashof`: the Grashof class of a four-bar;
* :mod:`~symlink.analysis.fourbar_closed_form`: a four-bar by its lengths in closed form (SymPy-free):
  its crank's spans, :func:`limit_positions` and :func:`fourbar_report`;
* :mod:`~symlink.analysis.transmission`: the transmission angle of every two-angle loop of any linkage
  (a four-bar's curve and extremes, and :func:`triangle_angle`, are at home in
  :mod:`symlink.numeric.fourbar_transmission`);
* :mod:`~symlink.analysis.joint_angles`: the interior angles at the joints of many designs at once (SymPy-free);
* :mod:`~symlink.analysis.limits`: limit positions of any output;
* :mod:`~symlink.analysis.report`: :func:`analyze_linkage` (any one-input linkage).

Reachable input ranges and toggles live in :mod:`symlink.numeric.reachability` (their one home).

Names load lazily (PEP 562): importing one submodule, or asking for a closed-form
name, does not import the symbolic layer (SymPy) that the general analysis needs.

>>> import math
>>> from symlink.analysis import analyze_linkage, grashof
>>> from symlink.mechanism.catalog import fourbar
>>> report = analyze_linkage(fourbar(), dict(a=20, b=66, c=56, d=80), output="rocker")
>>> round(math.degrees(report.transmission[0].minimum), 2), grashof(20, 66, 56, 80).name
(58.23, 'crank-rocker')
"""
from __future__ import annotations

import importlib
from typing import Any

# Eager, being SymPy-free, and because the function shares its module's name: importing the submodule binds
# ``grashof`` in this package to the module, which this import then rebinds to the function.
from .grashof import GRASHOF_CLASSES, Grashof, grashof

#: Each public name and the module that is its home (relative to this package, or absolute).
_HOMES = {
    "Mobility": "symlink.mechanism.mobility", "degrees_of_freedom": "symlink.mechanism.mobility",
    "LimitPositions": ".fourbar_closed_form", "limit_positions": ".fourbar_closed_form",
    "fourbar_report": ".fourbar_closed_form",
    "TransmissionRange": "symlink.numeric.fourbar_transmission",
    "transmission_range": "symlink.numeric.fourbar_transmission",
    "triangle_angle": "symlink.numeric.fourbar_transmission",
    "transmission_curve": "symlink.numeric.fourbar_transmission", "TransmissionJoint": ".transmission",
    "transmission_joints": ".transmission", "transmission_angles": ".transmission",
    "LoopTransmission": ".transmission", "loop_transmissions": ".transmission",
    "LimitPosition": ".limits", "OutputLimits": ".limits", "output_limits": ".limits",
    "LinkageReport": ".report", "analyze_linkage": ".report",
    "wrap_angle": "symlink.common.angles",
    "crank_range": "symlink.numeric.crank_ranges",
    "InputRange": "symlink.numeric.reachability", "Toggle": "symlink.numeric.reachability",
    "reachable_range": "symlink.numeric.reachability",
}

__all__ = [
    "Mobility", "degrees_of_freedom", "Grashof", "GRASHOF_CLASSES", "grashof",
    "LimitPositions", "limit_positions", "TransmissionRange", "transmission_range",
    "transmission_curve", "triangle_angle", "wrap_angle", "crank_range",
    "LimitPosition", "OutputLimits", "output_limits", "TransmissionJoint", "transmission_joints",
    "transmission_angles", "LoopTransmission", "loop_transmissions", "LinkageReport", "analyze_linkage",
    "fourbar_report", "InputRange", "Toggle", "reachable_range",
]


def __getattr__(name: str) -> Any:
    """A public name, imported from its home on first use (then kept in this module)."""
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(home, __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
