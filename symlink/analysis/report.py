"""The analysis of a linkage in one record: :func:`analyze_linkage` for any one-input linkage, and the four-bar's.

:func:`fourbar_report` is the special case: the four-bar of the catalog
through :func:`analyze_linkage` (range, toggles, limit positions of the
rocker, stroke and time ratio), plus what only a four-bar has: its Grashof
class, and its transmission extremes from the closed form over the diagonal
(exactly at crank angles 0 and pi where it gets there).

>>> report = analyze_linkage(fourbar(), dict(a=20, b=66, c=56, d=80), output="rocker")
>>> report.reach.full_turn, report.mobility.dof, round(math.degrees(report.limits.stroke), 4)
(True, 1, 42.0886)
"""
from __future__ import annotations

import math  # noqa: F401 - the doctests' namespace
from dataclasses import dataclass
from typing import Mapping

from ..common.angles import wrap_angle
from ..mechanism.catalog import fourbar
from ..common.display import record_html
from ..symbolic.linkage import Linkage
from ..numeric.reachability import SCAN_POINTS, InputMotion, InputRange, assembled_crank_range, reachable_range
from ..numeric.solver import shared_solver
from .grashof import grashof
from .limits import OutputLimits, output_limits
from ..mechanism.mobility import Mobility, degrees_of_freedom
from .transmission import LoopTransmission, loop_transmissions, transmission_range

__all__ = ["LinkageReport", "analyze_linkage", "fourbar_report"]


@dataclass(frozen=True)
class LinkageReport:
    """What :func:`analyze_linkage` finds (radians, lengths in the values' unit).

    ``reach``: the reachable range of the moving input and its toggles;
    ``transmission``: one entry a two-angle loop; ``limits``: the limit
    positions of ``output`` (None when no output was asked for).
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    linkage: str
    input: str
    values: dict
    mobility: Mobility
    reach: InputRange
    transmission: tuple[LoopTransmission, ...]
    limits: OutputLimits | None


def analyze_linkage(linkage: Linkage, values: Mapping[str, float], output: str | None = None, *,
                    input: str | None = None, guess: Mapping[str, float] | None = None, start: float = 0.0,
                    interval: tuple[float, float] | None = None, points: int = SCAN_POINTS,
                    numeric: bool = False) -> LinkageReport:
    """Mobility, reachable input range and toggles, transmission angles and an output's limit positions.

    ``values`` by name: every parameter, branch signs (default +1) and the
    inputs other than the moving one (``input``, default the first).  A linkage
    without a closed form needs ``guess``: its unknowns near the wanted
    assembly at input ``start``.  A length input needs the ``interval`` to
    search; ``numeric=True`` solves by Newton's method even where a closed
    form exists.  ``ValueError`` for missing or unknown names, and where the
    linkage cannot be assembled at any input.

    Parameters
    ----------
    linkage : Linkage
        A linkage with one moving input.
    values : mapping of str to float
        Every parameter, branch signs (default +1) and the inputs other than the moving one.
    output : str, optional
        The output whose limit positions to find (none by default).
    input : str, optional
        The moving input (default: the first).
    guess : mapping of str to float, optional
        For a linkage without a closed form: its unknowns near the wanted assembly at ``start``.
    start : float, optional
        The input value of ``guess`` (default 0).
    interval : (float, float), optional
        The span to search for a length input.
    points : int, optional
        The scan's number of input values (default 3600).
    numeric : bool, optional
        Solve by Newton's method even where a closed form exists.

    Returns
    -------
    LinkageReport
        Its mobility, reachable range and toggles, transmission angles and the output's limits (radians).

    Raises
    ------
    ValueError
        For missing or unknown names, and where the linkage cannot be assembled at any input.

    Examples
    --------
    >>> import math, symlink
    >>> report = symlink.analyze_linkage(symlink.fourbar(), dict(a=20, b=66, c=56, d=80), output="rocker")
    >>> report.mobility.dof, round(math.degrees(report.transmission[0].minimum), 2)  # acos(3892 / 7392)
    (1, 58.23)
    >>> round(math.degrees(report.limits.stroke), 2), round(report.limits.time_ratio, 4)
    (42.09, 1.0433)
    """
    motion = InputMotion(linkage, values, input=input, guess=guess, start=start, numeric=numeric)
    reach = reachable_range(linkage, values, interval=interval, points=points, motion=motion)
    if not reach.spans:
        raise ValueError(f"{linkage.name} cannot be assembled at any {motion.input} with these values")
    transmission = loop_transmissions(linkage, values, reach=reach, motion=motion, points=points)
    limits = None if output is None else output_limits(linkage, values, output, reach=reach, motion=motion,
                                                       points=points)
    return LinkageReport(linkage.name, motion.input, dict(motion.values), degrees_of_freedom(linkage), reach,
                         transmission, limits)


def fourbar_report(a: float, b: float, c: float, d: float, branch: int = 1) -> dict:
    """Everything :mod:`symlink.analysis` says of one four-bar, as a flat record (radians).

    ``limit_positions``, ``stroke`` and ``time_ratio`` are None unless the linkage is a
    crank-rocker (otherwise the output does not swing between two limits as the crank
    turns); ``toggles`` are the ends of the crank's range (empty for a full turn).

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths.
    branch : int, optional
        The assembly, +1 (default) or -1.

    Returns
    -------
    dict
        A flat record: ``grashof``, ``dof``, the crank's range and toggles, the transmission extremes,
        and for a crank-rocker ``limit_positions``, ``stroke`` and ``time_ratio`` (radians).

    Examples
    --------
    >>> import math, symlink
    >>> report = symlink.fourbar_report(20, 66, 56, 80)  # seed 003
    >>> report["grashof"], report["dof"], round(math.degrees(report["transmission_min"]), 2)
    ('crank-rocker', 1, 58.23)
    """
    assembled_crank_range(a, b, c, d)  # ValueError for bad lengths or a four-bar that closes nowhere
    if branch not in (1, -1):
        raise ValueError(f"branch must be +1 or -1, got {branch}")
    kind = grashof(a, b, c, d)
    crank_rocker = kind.name == "crank-rocker"
    general = analyze_linkage(fourbar(), dict(a=a, b=b, c=c, d=d, branch=branch),
                              output="rocker" if crank_rocker else None)
    spans = list(general.reach.spans)
    transmission = transmission_range(a, b, c, d)
    swing = general.limits  # asked for (output="rocker") exactly when the four-bar is a crank-rocker
    limits = None
    if swing is not None:
        # extended: the crank along the coupler; folded: back along it (the rocker's two extremes)
        found = swing.positions
        extended = min(found, key=lambda p: abs(wrap_angle(_coupler(a, b, c, d, p.at, branch) - p.at)))
        folded = next(p for p in found if p is not extended)
        limits = {"extended_crank": extended.at, "extended_rocker": extended.value,
                  "folded_crank": folded.at, "folded_rocker": folded.value}
    return {
        "crank": a, "coupler": b, "rocker": c, "ground": d, "branch": branch,
        "dof": general.mobility.dof,
        "grashof": kind.name, "shortest": kind.shortest, "longest": kind.longest,
        "shortest_plus_longest": kind.shortest_plus_longest, "other_two": kind.other_two,
        "crank_range": spans,
        "toggles": [] if general.reach.full_turn else [t.at for t in general.reach.toggles if t.ends_range],
        "limit_positions": limits,
        "stroke": None if swing is None else swing.stroke,
        "time_ratio": None if swing is None else swing.time_ratio,
        "transmission_min": transmission.minimum, "transmission_min_at": transmission.minimum_at,
        "transmission_max": transmission.maximum, "transmission_max_at": transmission.maximum_at,
        "worst_transmission": transmission.worst,
    }


def _coupler(a: float, b: float, c: float, d: float, theta: float, branch: int) -> float:
    """The four-bar's coupler angle at crank angle ``theta``."""
    solved = shared_solver(fourbar, ("coupler",))(theta=theta, a=a, b=b, c=c, d=d, branch=branch)
    return float(solved["coupler"])
