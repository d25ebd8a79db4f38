"""The studio's "Analyse and design": what a drawn linkage does over its motion, and a linkage designed to a path.

:func:`analysis` reports a drawing through the library: the reachable range of its input and its toggles
(:func:`symlink.numeric.reachability.reachable_range`), the transmission angle of every two-angle loop over
that range, the limit positions of each output link that turns about (or slides on) the ground
(:func:`symlink.analysis.analyze_linkage`, :func:`symlink.analysis.output_limits`), and for a four-bar its
Grashof class (:func:`symlink.analysis.grashof`) and the closed-form transmission range
(:func:`symlink.analysis.transmission_range`).  Angles are radians; the page shows degrees.

:func:`synthesis` designs the drawn linkage so that one of its joints passes through clicked points
(:func:`symlink.synthesis.general.synthesize_path`, untimed: the targets reached in their order) and gives
the design back as a drawing: the joints where the designed linkage puts them at the first target, so that
:func:`~symlink.mechanism.joints.from_joints` of the new drawing is the designed linkage.  The search has no
callback to stop it, so the server runs :func:`synthesis` in a worker process it can terminate
(:mod:`symlink.studio.jobs`).
"""
from __future__ import annotations

import math
from typing import Any, Mapping

from ..mechanism.joints import JointLinkage
from ..mechanism.topology import GROUND
from .drawing import CACHE, Description, description, drawn_linkage

__all__ = ["analysis", "fourbar_lengths", "synthesis_request", "synthesis", "MAX_TARGETS", "MIN_TARGETS",
           "MAX_STARTS", "MAX_EVALUATIONS"]

#: Bounds of a synthesis request: a drawing's few clicked points, a search that ends in minutes at most.
MIN_TARGETS = 3
MAX_TARGETS = 40
MAX_STARTS = 64
MAX_EVALUATIONS = 5000


def _input_values(drawn: JointLinkage) -> tuple[str, dict[str, float]]:
    """The moving input's name and the values analysis takes (every parameter and branch, not the input)."""
    linkage = drawn.linkage
    if len(linkage.inputs) != 1:
        raise ValueError(f"the drawing has {len(linkage.inputs)} inputs; analysis and design drive one joint")
    inputs = {q.name for q in linkage.inputs}
    return linkage.inputs[0].name, {k: float(v) for k, v in drawn.defaults.items() if k not in inputs}


def fourbar_lengths(found: Description) -> dict[str, Any] | None:
    """Crank a, coupler b, rocker c and ground d of a drawing that is a four-bar of pins driven at a ground
    pivot (the joints of each, by name), else None."""
    links = found.links
    moving = [name for name in links if name != GROUND]
    if found.sliders or len(moving) != 3 or GROUND not in links or len(found.drivers) != 1:
        return None
    driver = found.drivers[0]
    pivot = driver if isinstance(driver, str) else driver[0]
    ground = set(links[GROUND])
    if pivot not in ground:
        return None
    cranks = [name for name in moving if pivot in links[name]]
    if len(cranks) != 1:
        return None
    crank = cranks[0]
    shared = lambda one, two: [j for j in links[one] if j in links[two]]  # noqa: E731
    for coupler in moving:
        for rocker in moving:
            if len({crank, coupler, rocker}) != 3:
                continue
            b_joints, c_joints = shared(crank, coupler), shared(coupler, rocker)
            d_joints = [j for j in links[rocker] if j in ground and j != pivot]
            if len(b_joints) == 1 and len(c_joints) == 1 and len(d_joints) == 1 and not shared(crank, rocker):
                A, B, C, D = pivot, b_joints[0], c_joints[0], d_joints[0]
                xy = found.coordinates
                length = lambda p, q: math.hypot(xy[p][0] - xy[q][0], xy[p][1] - xy[q][1])  # noqa: E731
                return {"joints": [A, B, C, D], "a": length(A, B), "b": length(B, C), "c": length(C, D),
                        "d": length(A, D)}
    return None


def _outputs(found: Description, drawn: JointLinkage) -> list[str]:
    """The outputs whose limit positions are reported: the angle of each moving link (not the driven one) that
    holds a ground pivot, and the travel of each slider."""
    linkage = drawn.linkage
    ground = set(found.links.get(GROUND, []))
    driver = found.drivers[0] if found.drivers else None
    pivot = driver if isinstance(driver, str) else (driver[0] if driver else None)
    outputs = []
    for link, angle in linkage.roles.items():
        held = found.links.get(link, [])
        if pivot in held or not any(j in ground and j not in found.sliders for j in held):
            continue
        if str(angle) in {q.name for q in linkage.unknowns}:
            outputs.append(str(angle))
    outputs += [q.name for q in linkage.unknowns if q.name.startswith("s_")]
    return outputs


def analysis(data: Any) -> dict[str, Any]:
    """What the drawn linkage does over its motion (radians): ``reach`` (spans of the input, toggles),
    ``transmission`` (each two-angle loop's extremes and where), ``limits`` (each output's limit positions,
    stroke and time ratio), ``grashof`` and ``fourbar`` for a four-bar of pins; ``ValueError`` where it cannot
    be assembled at any input."""
    found = description(data)
    drawn = drawn_linkage(found)

    def make() -> dict[str, Any]:
        from ..analysis import analyze_linkage, grashof, output_limits, transmission_range
        linkage = drawn.linkage
        name, values = _input_values(drawn)
        interval = None
        if name.startswith("s_"):
            at = float(drawn.defaults[name])
            span = 2 * max(1.0, abs(at))
            interval = (at - span, at + span)
        outputs = _outputs(found, drawn)
        report = analyze_linkage(linkage, values, outputs[0] if outputs else None, interval=interval)
        limits = [report.limits] if report.limits is not None else []
        for output in outputs[1:]:
            limits.append(output_limits(linkage, values, output, reach=report.reach))
        result: dict[str, Any] = {
            "input": report.input, "angle": not name.startswith("s_"),
            "reach": {"spans": [list(span) for span in report.reach.spans], "full_turn": report.reach.full_turn,
                      "exact": report.reach.exact,
                      "toggles": [{"at": t.at, "loop": t.loop, "ends_range": t.ends_range} for t in report.reach.toggles]},
            "transmission": [{"loop": t.loop, "joint": t.joint, "minimum": t.minimum, "minimum_at": t.minimum_at,
                              "maximum": t.maximum, "maximum_at": t.maximum_at} for t in report.transmission],
            "limits": [{"output": found_limits.output, "angle": found_limits.angle,
                        "positions": [{"at": p.at, "value": p.value, "kind": p.kind} for p in found_limits.positions],
                        "stroke": found_limits.stroke, "time_ratio": found_limits.time_ratio}
                       for found_limits in limits],
            "grashof": None, "fourbar": None}
        four = fourbar_lengths(found)
        if four is not None:
            kind = grashof(four["a"], four["b"], four["c"], four["d"])
            closed = transmission_range(four["a"], four["b"], four["c"], four["d"])
            result["grashof"] = {"name": kind.name, "description": kind.description, "shortest": kind.shortest,
                                 "longest": kind.longest, "shortest_plus_longest": kind.shortest_plus_longest,
                                 "other_two": kind.other_two}
            result["fourbar"] = {**four, "transmission": {"minimum": closed.minimum, "minimum_at": closed.minimum_at,
                                                          "maximum": closed.maximum, "maximum_at": closed.maximum_at}}
        return result
    return CACHE.get("analysis", found.key, make)
