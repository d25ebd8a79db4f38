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

>>> report = analyze_linkage(fourbar(), dict(a=20, b=66, c=56, d=80), output="rocker")
>>> round(math.degrees(report.transmission[0].minimum), 2), grashof(20, 66, 56, 80).name
(58.23, 'crank-rocker')
"""
from __future__ import annotations

import math  # noqa: F401 - the doctests' namespace

from ..common.angles import wrap_angle
from ..mechanism.catalog import fourbar  # noqa: F401 - the doctests' namespace
from ..numeric.reachability import InputRange, Toggle, crank_range, reachable_range
from .grashof import GRASHOF_CLASSES, Grashof, grashof
from .limits import LimitPosition, LimitPositions, OutputLimits, limit_positions, output_limits
from ..mechanism.mobility import Mobility, degrees_of_freedom
from .report import LinkageReport, analyze_linkage, fourbar_report
from .transmission import (LoopTransmission, TransmissionJoint, TransmissionRange, loop_transmissions,
                           transmission_angles, transmission_curve, transmission_joints, transmission_range,
                           triangle_angle)

__all__ = [
    "Mobility", "degrees_of_freedom", "Grashof", "GRASHOF_CLASSES", "grashof",
    "LimitPositions", "limit_positions", "TransmissionRange", "transmission_range",
    "transmission_curve", "triangle_angle", "wrap_angle", "crank_range",
    "LimitPosition", "OutputLimits", "output_limits", "TransmissionJoint", "transmission_joints",
    "transmission_angles", "LoopTransmission", "loop_transmissions", "LinkageReport", "analyze_linkage",
    "fourbar_report", "InputRange", "Toggle", "reachable_range",
]
