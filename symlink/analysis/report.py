"""The analysis of a linkage in one record: :func:`analyze_linkage` for any one-input linkage, and the four-bar's.

:func:`fourbar_report` is the special case of the four-bar by its lengths, in closed form
(:mod:`~symlink.analysis.fourbar_closed_form`, its home): the same range, toggles and
limit positions of the rocker as :func:`analyze_linkage` of the catalog's four-bar finds
by its scan, plus what only a four-bar has: its Grashof class, and its transmission
extremes over the diagonal (exactly at crank angles 0 and pi where it gets there).

>>> from symlink.mechanism.catalog import fourbar
>>> report = analyze_linkage(fourbar(), dict(a=20, b=66, c=56, d=80), output="rocker")
>>> report.reach.full_turn, report.mobility.dof, round(math.degrees(report.limits.stroke), 4)
(True, 1, 42.0886)
"""
from __future__ import annotations

import math  # noqa: F401 - the doctests' namespace
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Mapping

from ..common.display import record_html
from ..numeric.cached_linkage import CachedLinkage
from ..numeric.reachability import SCAN_POINTS, InputMotion, InputRange, reachable_range
from .limits import OutputLimits, output_limits
from ..mechanism.mobility import Mobility
from .transmission import LoopTransmission, loop_transmissions
from .fourbar_closed_form import fourbar_report  # noqa: F401 - its home (closed form, SymPy-free)

if TYPE_CHECKING:  # the symbolic layer is imported where a linkage is derived: a cached linkage needs none of it
    from ..symbolic.linkage import Linkage

__all__ = ["LinkageReport", "analyze_linkage", "fourbar_report", "analysis_facts"]


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


def analyze_linkage(linkage: Linkage | CachedLinkage, values: Mapping[str, float], output: str | None = None, *,
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
    linkage : Linkage or CachedLinkage
        A linkage with one moving input, or its facts and code from the disk cache
        (:class:`~symlink.numeric.cached_linkage.CachedLinkage`: no SymPy; closed form, the first input).
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
    if isinstance(linkage, CachedLinkage):
        mobility = Mobility(**linkage.mobility)
    else:
        from ..mechanism.mobility import degrees_of_freedom
        mobility = degrees_of_freedom(linkage)
    return LinkageReport(linkage.name, motion.input, dict(motion.values), mobility, reach, transmission, limits)


def analysis_facts(linkage: Linkage) -> dict[str, Any]:
    """What :func:`analyze_linkage` needs of ``linkage`` beyond its solver and generated code, as plain data (JSON):
    the facts of a :class:`~symlink.numeric.cached_linkage.CachedLinkage` (with the first input moving).

    Derived once with SymPy and kept in the disk cache by ``symlink analyze NAME|FILE``: names (inputs, parameters
    and the lengths among them, branch signs, unknowns, rates, the angles), whether it has a closed form, its
    mobility, the margins of its clamped roots (:func:`~symlink.numeric.reachability.margin_roots`), the joints
    of its two-angle loops (:func:`~symlink.analysis.transmission.joint_recipe`), and its outputs, each with whether
    it is a position output (:func:`~symlink.analysis.limits.output_kinds`, ``outputs``; ``output_names``: those
    a refusal names; ``sensitivity_suffixes``: how a sensitivity's name ends), so that an output that has no limit positions is refused without SymPy.

    >>> from symlink.mechanism.catalog import fourbar
    >>> facts = analysis_facts(fourbar())
    >>> facts["unknowns"], facts["roots"], facts["joints"][0]["name"], facts["mobility"]["links"]
    (['beta', 'phi'], [['margin_0', 'ABCD']], 'DC/BC', 4)
    """
    from ..mechanism.mobility import degrees_of_freedom
    from ..numeric.reachability import margin_roots
    from ..symbolic.closure import is_angle
    from ..symbolic.vectors import rate
    from ..common.notation import SENSITIVITY_SEPARATOR
    from .limits import output_kinds
    from .transmission import joint_recipe, transmission_joints
    named = linkage.parameters + linkage.inputs
    closed = bool(linkage.has_closed_form)
    known = [s.name for s in linkage.parameters + linkage.inputs[1:] + linkage.branches]
    mobility = degrees_of_freedom(linkage)
    return {
        "name": linkage.name, "closed_form": closed,
        "inputs": [q.name for q in linkage.inputs], "parameters": [s.name for s in linkage.parameters],
        "positive": [s.name for s in linkage.parameters if s.is_positive],
        "branches": [s.name for s in linkage.branches], "unknowns": [q.name for q in linkage.unknowns],
        "angles": [s.name for s in named if is_angle(linkage, s)],
        "rates": {q.name: rate(q).name for q in linkage.unknowns + linkage.inputs},
        "mobility": {"links": mobility.links, "revolute": mobility.revolute, "prismatic": mobility.prismatic},
        "roots": [list(root) for root in margin_roots(linkage)] if closed else [],
        "joints": [joint_recipe(joint, known) for joint in transmission_joints(linkage)] if closed else [],
        "outputs": output_kinds(linkage), "output_names": linkage.output_names(),
        "sensitivity_suffixes": [SENSITIVITY_SEPARATOR + s.name for s in linkage.parameters],
    }
