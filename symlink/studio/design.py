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

from ..common.numbers import finite_float
from ..mechanism.joints import JointLinkage
from ..mechanism.topology import GROUND
from .drawing import CACHE, Description, description, drawn_linkage

__all__ = ["BAND_SAMPLES", "EXACT", "MAX_EVALUATIONS", "MAX_STARTS", "MAX_TARGETS", "MIN_TARGETS", "analysis",
           "complex_points", "fourbar_lengths", "synthesis", "synthesis_request", "tolerance_band"]

#: Bounds of a synthesis request: a drawing's few clicked points, a search that ends in minutes at most.
MIN_TARGETS = 3
MAX_TARGETS = 40
MAX_STARTS = 64
MAX_EVALUATIONS = 5000
#: A design passes through the targets when its largest distance to them is below this, over their size (the
#: search stops at 1e-10); above it the design is the closest found, and said so.
EXACT = 1e-9


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
    xy = found.coordinates

    def shared(one: str, two: str) -> list[str]:
        return [j for j in links[one] if j in links[two]]

    def length(p: str, q: str) -> float:
        return math.hypot(xy[p][0] - xy[q][0], xy[p][1] - xy[q][1])
    for coupler in moving:
        for rocker in moving:
            if len({crank, coupler, rocker}) != 3:
                continue
            b_joints, c_joints = shared(crank, coupler), shared(coupler, rocker)
            d_joints = [j for j in links[rocker] if j in ground and j != pivot]
            if len(b_joints) == 1 and len(c_joints) == 1 and len(d_joints) == 1 and not shared(crank, rocker):
                A, B, C, D = pivot, b_joints[0], c_joints[0], d_joints[0]
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
                      "toggles": [{"at": t.at, "loop": t.loop, "ends_range": t.ends_range}
                                  for t in report.reach.toggles]},
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


# --- path synthesis ---------------------------------------------------------------------------------

def _integer(value: Any, what: str, low: int, high: int, default: int) -> int:
    if value is None:
        return default
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise ValueError(f"{what} is a whole number from {low} to {high}, not {str(value)[:40]!r}")
    return value


def synthesis_request(data: Any) -> dict[str, Any]:
    """A checked synthesis request: ``{"drawing", "point", "targets": [[x, y], ...], "starts", "evaluations",
    "seed"}``; ``ValueError`` saying what is wrong (before any work is started)."""
    if not isinstance(data, dict):
        raise ValueError('a synthesis request is {"drawing": ..., "point": a joint, "targets": [[x, y], ...]}')
    unknown = sorted(set(data) - {"drawing", "point", "targets", "starts", "evaluations", "seed"})
    if unknown:
        raise ValueError(f"a synthesis request has no entry {unknown[0][:40]!r}")
    found = description(data.get("drawing"))
    drawn = drawn_linkage(found)
    _input_values(drawn)
    point = data.get("point")
    if not isinstance(point, str) or point not in found.coordinates:
        raise ValueError(f"point must name a joint of the drawing ({', '.join(found.coordinates)}), not "
                         f"{str(point)[:40]!r}")
    if point in found.links.get(GROUND, []) and point not in found.sliders:
        raise ValueError(f"{point} is on the ground and traces no path: choose a moving joint")
    targets = data.get("targets")
    if not isinstance(targets, list) or not MIN_TARGETS <= len(targets) <= MAX_TARGETS:
        count = len(targets) if isinstance(targets, list) else "no"
        raise ValueError(f"give {MIN_TARGETS} to {MAX_TARGETS} target points (click them with the Targets tool); "
                         f"there are {count}")
    rows: list[list[float]] = []
    for k, row in enumerate(targets):
        x, y = (finite_float(v) for v in row) if isinstance(row, list) and len(row) == 2 else (None, None)
        if x is None or y is None or abs(x) > 1e9 or abs(y) > 1e9:
            raise ValueError(f"targets[{k}] must be [x, y], two finite numbers")
        rows.append([x, y])
    span = max(max(r[0] for r in rows) - min(r[0] for r in rows), max(r[1] for r in rows) - min(r[1] for r in rows))
    if span <= 0:
        raise ValueError("the targets are all one point: click points apart")
    from ..synthesis.path import check_distinct_targets
    import numpy
    check_distinct_targets(numpy.array(rows))  # any two alike, as every synthesis refuses them
    if any(math.dist(p, q) <= 1e-9 * span for p, q in zip(rows, rows[1:])):
        raise ValueError("two consecutive targets are the same point")
    return {"drawing": data["drawing"], "point": point, "targets": rows,
            "starts": _integer(data.get("starts"), "starts", 1, MAX_STARTS, 8),
            "evaluations": _integer(data.get("evaluations"), "evaluations", 10, MAX_EVALUATIONS, 2000),
            "seed": _integer(data.get("seed"), "seed", 0, 2 ** 31 - 1, 0)}


def _free(found: Description, drawn: JointLinkage, targets: list[list[float]]) -> tuple[dict, dict]:
    """Bounds of the free parameters and the fixed values: every length and angle of the drawing is free
    except what the placement's shift and turn stand for (the first ground pivot's position, the first ground
    direction) and the direction of a slider's guide (turned with the placement)."""
    _, values = _input_values(drawn)
    values = {k: v for k, v in values.items() if k not in {b.name for b in drawn.linkage.branches}}
    ground = set(found.links.get(GROUND, []))
    xs = [xy[0] for xy in found.coordinates.values()] + [t[0] for t in targets]
    ys = [xy[1] for xy in found.coordinates.values()] + [t[1] for t in targets]
    size = max(max(xs) - min(xs), max(ys) - min(ys))
    lengths = {p.name for p in drawn.linkage.parameters if p.is_positive}
    free: dict[str, tuple[float, float]] = {}
    ground_angle_fixed = False
    for name, value in values.items():
        if name.startswith(("x_", "y_")):
            continue
        if name in lengths:
            free[name] = (min(0.01 * size, 0.5 * value), max(10 * size, 2 * value))
        elif name.startswith("alpha_"):
            joints = [j for j in found.coordinates if name[6:].startswith(j) or name[6:].endswith(j)]
            if any(j in found.sliders for j in joints):
                continue
            if all(j in ground for j in joints) and not ground_angle_fixed:
                ground_angle_fixed = True
                continue
            free[name] = (value - math.pi, value + math.pi)
    return free, values


def synthesis(request: Mapping[str, Any]) -> dict[str, Any]:
    """The drawn linkage designed so that ``point`` passes through ``targets`` in their order
    (:func:`symlink.synthesis.general.synthesize_path`, placement shifted and turned, not scaled), as a drawing.

    ``drawing``: the joints where the design puts them at the first target (sliders' guides turned with the
    placement); ``inputs``: the drawing's input at each target; ``path``: the point's path from the first
    target to the last, from the new drawing's own linkage (:func:`symlink.mechanism.joints.from_joints`),
    and ``distances`` from each target to that linkage's point at its input (the check that the drawing is the
    design).  When no verified design is found, ``assembled`` is False with ``why`` and no drawing.
    """
    import numpy

    from ..numeric.poses import Geometry
    from ..synthesis.general import synthesize_path
    request = synthesis_request(dict(request))
    found = description(request["drawing"])
    drawn = drawn_linkage(found)
    linkage = drawn.linkage
    name, _ = _input_values(drawn)
    targets = request["targets"]
    free, values = _free(found, drawn, targets)
    design = synthesize_path(linkage, request["point"], numpy.asarray(targets), free, values=values,
                             frame=("x0", "y0", "angle"), starts=request["starts"], seed=request["seed"],
                             evaluations=request["evaluations"])
    result: dict[str, Any] = {"point": request["point"], "targets": targets, "error": float(design.error),
                              "exact": bool(design.assembled) and float(design.error) < EXACT,
                              "errors": [float(e) for e in design.errors], "assembled": bool(design.assembled),
                              "why": design.why, "evaluations": int(design.evaluations),
                              "design": {k: float(v) for k, v in design.design.items()},
                              "placement": {k: float(v) for k, v in design.placement.items()},
                              "branches": {k: int(v) for k, v in (design.branches or {}).items()},
                              "drawing": None, "inputs": None, "path": None, "distances": None}
    if not design.assembled:
        return result
    # the joints at the first target, placed: (x0, y0) + R(angle) p
    turn, x0, y0 = design.placement["angle"], design.placement["x0"], design.placement["y0"]
    def placed(z: complex) -> complex:
        return complex(x0, y0) + complex(math.cos(turn), math.sin(turn)) * z
    arguments = {**design.design, **{k: float(v) for k, v in (design.branches or {}).items()}}
    poses = Geometry(linkage).poses(arguments, {name: numpy.asarray([design.inputs[0]])},
                                    guess=getattr(design, "assembly", None) or None)
    if not bool(poses.assembled[0]):
        raise ValueError("the design found cannot be assembled at its first target (please report it)")
    drawing = {**request["drawing"], "joints": [], "sliders": []}
    for joint in request["drawing"]["joints"]:
        where = placed(complex(poses.positions[joint["name"]][0])) if joint["name"] in poses.positions else None
        if where is None:
            drawing["joints"].append(dict(joint))  # a joint on no link yet: where it was drawn
        else:
            drawing["joints"].append({**joint, "x": where.real, "y": where.imag})
    for slider in request["drawing"].get("sliders") or []:
        drawing["sliders"].append({**slider, "angle": float(slider.get("angle", 0.0)) + turn})
    shift = turn if not name.startswith("s_") else 0.0
    inputs = [float(q) + shift for q in design.inputs]
    # the check: the new drawing's own linkage, at those inputs
    made = drawn_linkage(description(drawing))
    check = {k: v for k, v in made.defaults.items() if k != name}
    sweep = numpy.linspace(inputs[0], inputs[-1], 241)
    traced = Geometry(made.linkage).poses(check, {name: numpy.asarray(inputs + list(sweep))},
                                          guess=made.guess or None)
    along = traced.positions[request["point"]]
    ok = numpy.asarray(traced.assembled)
    distances = [float(abs(complex(along[k]) - complex(*targets[k]))) if ok[k] else None for k in range(len(inputs))]
    path = [[float(z.real), float(z.imag)] if good else None
            for z, good in zip(along[len(inputs):], ok[len(inputs):])]
    result.update(drawing=drawing, inputs=inputs, path=path, distances=distances)
    return result


# --- a tolerance band on a joint's path ---------------------------------------------------------------

#: Input values a tolerance band is computed at (a full turn of an angle input: every degree).
BAND_SAMPLES = 361


def complex_points(poses: Any, point: str) -> Any:
    """A joint's positions in :class:`~symlink.numeric.poses.Poses` as complex numbers, NaN where not assembled."""
    import numpy
    where = numpy.asarray(poses.positions[point], dtype=complex)
    return numpy.where(numpy.asarray(poses.assembled, dtype=bool), where, numpy.nan)


def tolerance_band(data: Any) -> dict[str, Any]:
    """The worst-case band of a joint's path when every length of the drawing is made to ``± band``:
    ``{"drawing", "point", "band"}`` -> the nominal path and, at each input value, ``width``: the largest
    first-order deviation across the path (:func:`symlink.workshop.tolerance.stack_up`'s sensitivities of the
    point's x and y, projected on the path's normal, its direction from the point 1e-5 of the range either
    way: ``sum_j |n . dP/dp_j| band_j``), and the band's edges ``inner`` and ``outer`` (``P -/+ width n``);
    None where the linkage cannot be assembled."""
    import numpy

    from ..workshop.tolerance import stack_up
    if not isinstance(data, dict) or set(data) - {"drawing", "point", "band"}:
        raise ValueError('a tolerance request is {"drawing": ..., "point": a joint, "band": ± on every length}')
    found = description(data.get("drawing"))
    drawn = drawn_linkage(found)
    name, values = _input_values(drawn)
    point = data.get("point")
    if not isinstance(point, str) or point not in found.coordinates:
        raise ValueError(f"point must name a joint of the drawing ({', '.join(found.coordinates)})")
    band = data.get("band")
    xs = [xy[0] for xy in found.coordinates.values()]
    ys = [xy[1] for xy in found.coordinates.values()]
    size = max(max(xs) - min(xs), max(ys) - min(ys))
    if isinstance(band, bool) or not isinstance(band, (int, float)) or not 0 < band <= 0.1 * size:
        raise ValueError(f"band is a number above 0 and at most a tenth of the drawing's size ({0.1 * size:.4g}): "
                         f"the first-order band of small tolerances, not {str(band)[:40]!r}")
    lengths = [p.name for p in drawn.linkage.parameters if p.is_positive]
    if name.startswith("s_"):
        at = float(drawn.defaults[name])
        span = 2 * max(1.0, abs(at))
        inputs = numpy.linspace(at - span, at + span, BAND_SAMPLES)
    else:
        inputs = numpy.linspace(-math.pi, math.pi, BAND_SAMPLES)
    found_band = stack_up(drawn.linkage, [f"{point}_x", f"{point}_y"], drawn.defaults,
                          {length: float(band) for length in lengths}, inputs={name: inputs},
                          guess=drawn.guess if not drawn.linkage.has_closed_form else None)
    where = found_band.nominal[0] + 1j * found_band.nominal[1]
    ok = numpy.asarray(found_band.assembled, dtype=bool) & numpy.isfinite(where)
    moved = found_band.sensitivity[0] + 1j * found_band.sensitivity[1]  # [dimension, input]
    # the path's direction: from the point a small step of the input either way (the mean of the two
    # directions, both turned forward: where the point stops and turns back, both follow the path)
    from ..numeric.poses import Geometry
    step = 1e-5 * float(inputs[-1] - inputs[0])
    geometry = Geometry(drawn.linkage)
    guess = drawn.guess if not drawn.linkage.has_closed_form else None
    ahead, behind = (complex_points(geometry.poses(values, {name: inputs + sign * step}, guess=guess), point)
                     for sign in (1, -1))
    nominal: list[Any] = []
    inner: list[Any] = []
    outer: list[Any] = []
    widths: list[Any] = []  # None where the point cannot be placed (JSON null)
    for k in range(len(inputs)):
        if not ok[k]:
            for column in (nominal, inner, outer, widths):
                column.append(None)
            continue
        forward, backward = ahead[k] - where[k], where[k] - behind[k]
        forward, backward = forward / abs(forward), backward / abs(backward)
        if (forward * backward.conjugate()).real < 0:  # the point stops and turns back here (a limit position)
            backward = -backward
        tangent = forward + backward
        if not numpy.isfinite(tangent) or abs(tangent) == 0:
            nominal.append([float(where[k].real), float(where[k].imag)]); inner.append(None); outer.append(None)
            widths.append(None)
            continue
        normal = 1j * tangent / abs(tangent)
        width = float(sum(abs((moved[j, k] * normal.conjugate()).real) * found_band.band[j]
                          for j in range(len(lengths))))
        nominal.append([float(where[k].real), float(where[k].imag)])
        inner.append([float((where[k] - width * normal).real), float((where[k] - width * normal).imag)])
        outer.append([float((where[k] + width * normal).real), float((where[k] + width * normal).imag)])
        widths.append(width)
    known = [(w, float(inputs[k])) for k, w in enumerate(widths) if w is not None]
    worst = max(known) if known else (None, None)
    return {"point": point, "band": float(band), "dimensions": lengths, "input": name,
            "inputs": [float(v) for v in inputs], "nominal": nominal, "inner": inner, "outer": outer,
            "widths": widths, "worst": worst[0], "worst_at": worst[1]}
