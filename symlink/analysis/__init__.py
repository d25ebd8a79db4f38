"""Analysis of linkages: mobility, reachable ranges and toggles, transmission angles, limit positions.

One concept a module:

* :mod:`~symlink.mechanism.mobility`: Gruebler/Kutzbach mobility of any linkage;
* :mod:`~symlink.analysis.grashof`: the Grashof class of a four-bar;
* :mod:`~symlink.analysis.transmission`: the transmission angle of a four-bar and of every
  two-angle loop of any linkage;
* :mod:`~symlink.analysis.limits`: limit positions of a four-bar's rocker and of any output;
* :mod:`~symlink.analysis.report`: :func:`analyze_linkage` (any one-input linkage) and
  :func:`fourbar_report`, its special case.

Reachable input ranges and toggles live in :mod:`symlink.numeric.reachability` (their one home).

Importing one submodule (a sweep's :mod:`~symlink.analysis.grashof`) loads only what it needs: the names
below are loaded from their modules when first used (PEP 562), so that a SymPy-free module stays SymPy-free.

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

# SymPy-free, and imported now: the function grashof must win over its module's name (symlink.analysis.grashof)
from .grashof import GRASHOF_CLASSES, Grashof, grashof

#: Where each public name lives (its one home), by name.
_HOMES = {
    "wrap_angle": "symlink.common.angles",
    **dict.fromkeys(("InputRange", "Toggle", "crank_range", "reachable_range"), "symlink.numeric.reachability"),
    **dict.fromkeys(("LimitPosition", "LimitPositions", "OutputLimits", "limit_positions", "output_limits"),
                    "symlink.analysis.limits"),
    **dict.fromkeys(("Mobility", "degrees_of_freedom"), "symlink.mechanism.mobility"),
    **dict.fromkeys(("LinkageReport", "analyze_linkage", "fourbar_report"), "symlink.analysis.report"),
    **dict.fromkeys(("LoopTransmission", "TransmissionJoint", "TransmissionRange", "loop_transmissions",
                     "transmission_angles", "transmission_curve", "transmission_joints", "transmission_range",
                     "triangle_angle"), "symlink.analysis.transmission"),
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
    """A public name, imported from its module on first use (and kept)."""
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(home), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
