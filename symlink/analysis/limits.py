"""Limit positions: where an output stops and turns back as the input moves on (its rate vanishes).

* :func:`limit_positions`: a four-bar's rocker extremes in closed form (crank and
  coupler in line), with the rocker's stroke and the crank-rocker's time ratio (its home is
  :mod:`~symlink.analysis.fourbar_closed_form`);
* :func:`output_limits`: the same for any output of any one-input linkage, found
  where the output's rate with respect to the input changes sign (a scan of the
  reachable range, each change bisected to rounding).  They are the dead
  centres of the linkage driven from that output: there it cannot move the input.

>>> limits = limit_positions(16.0843, 69.9385, 50, 70)
>>> round(math.degrees(limits.stroke), 2), round(limits.time_ratio, 3)
(40.0, 1.115)
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Mapping

from typing import TYPE_CHECKING

import numpy

from ..common.angles import wrap_angle
from ..numeric.cache import cache_key, cached_module
from ..common.display import record_html
from ..numeric.cached_linkage import CachedLinkage
from ..numeric.reachability import BISECTIONS, InputMotion, InputRange, reachable_range
from .fourbar_closed_form import LimitPositions, limit_positions  # noqa: F401 - their home

if TYPE_CHECKING:  # the symbolic layer is imported where an output is derived: a cached linkage needs none of it
    from ..symbolic.linkage import Linkage

__all__ = ["LimitPositions", "limit_positions", "LimitPosition", "OutputLimits", "output_limits"]


# --- any output of any one-input linkage --------------------------------------------------

@dataclass(frozen=True)
class LimitPosition:
    """An output's extreme: at input ``at`` it reaches ``value`` (``"maximum"`` or ``"minimum"``) and turns back."""

    _repr_html_ = record_html  # a notebook shows the fields as a table

    at: float
    value: float
    kind: str


@dataclass(frozen=True)
class OutputLimits:
    """The limit positions of one output over the reachable input range, in input order.

    ``stroke`` (the output's travel between them) and ``time_ratio`` (slow
    stroke over quick stroke at constant input speed) are given when the input
    turns fully and the output has exactly two limits; otherwise None.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    output: str
    angle: bool
    positions: tuple[LimitPosition, ...]
    stroke: float | None
    time_ratio: float | None


_OUTPUT_FUNCTIONS: dict[str, Callable[..., dict]] = {}


def _output_function(linkage: Linkage, output: str) -> Callable[..., dict]:
    """Generated code of an output and its time derivative from the coordinates and their rates (kept by key)."""
    check_position_output(linkage, output)
    key = cache_key(linkage, [output], "output-and-rate")
    if key not in _OUTPUT_FUNCTIONS:
        _OUTPUT_FUNCTIONS[key] = cached_module(key, lambda: output_text(linkage, output))[1]["output"]
    return _OUTPUT_FUNCTIONS[key]


def _not_a_position_output(name: str, output: str) -> ValueError:
    """The refusal of ``output``, an output of the linkage ``name`` that is no position output."""
    return ValueError(f"{output!r} is not a position output of {name}; give a coordinate, role, point coordinate or "
                      "extra")


def check_position_output(linkage: Linkage, output: str) -> None:
    """``ValueError`` unless ``output`` is a position output of ``linkage`` (a coordinate, role, point coordinate
    or extra; not a rate, the singularity flag, nor a sensitivity by a parameter, which the output's code would
    take as an argument it is not given)."""
    import sympy as sp

    from ..symbolic.sensitivity import split_sensitivity_name
    expr = linkage.output(output)
    if any(isinstance(s, sp.Symbol) and s.name.endswith("dot") and s not in linkage.coordinates
           for s in getattr(expr, "free_symbols", ())) or output == "singular" \
            or split_sensitivity_name(output, linkage.parameters) is not None:
        raise _not_a_position_output(linkage.name, output)


def output_kinds(linkage: Linkage) -> dict[str, bool]:
    """Each output of ``linkage`` by name (its inputs and unknowns with their rates and accelerations, roles, points'
    coordinates, extras, the singularity flag) and whether it is a position output (:func:`check_position_output`):
    plain data that a cached analysis keeps (:func:`~symlink.analysis.report.analysis_facts`), so that an output
    asked for is refused without SymPy (:func:`check_named_output`).

    >>> from symlink.mechanism.catalog import fourbar
    >>> kinds = output_kinds(fourbar())
    >>> kinds["phi"], kinds["rocker"], kinds["C_x"], kinds["phidot"], kinds["thetaddot"], kinds["singular"]
    (True, True, True, False, False, False)
    """
    from ..symbolic.vectors import acceleration, rate
    names = [name for q in linkage.coordinates for name in (q.name, rate(q).name, acceleration(q).name)]
    names += [name for name in linkage.output_names() if name not in names]
    kinds = {}
    for name in names:
        try:
            check_position_output(linkage, name)
        except ValueError:
            kinds[name] = False
        else:
            kinds[name] = True
    return kinds


def check_named_output(facts: Mapping[str, Any], output: str) -> bool:
    """Whether the cached ``facts`` of a linkage (:func:`~symlink.analysis.report.analysis_facts`) decide that
    ``output`` is one of its position outputs; ``ValueError`` in the words of :func:`check_position_output` (and of
    :meth:`~symlink.symbolic.linkage.Linkage.output` for a name it does not have) where they decide it is not (a
    sensitivity's name, ``<output>__d_<parameter>``, too: ``sensitivity_suffixes``); False where they cannot tell (a name that is the
    sensitivity by two parameters: the linkage's own words, derived).  SymPy-free.

    >>> facts = {"name": "pendulum", "outputs": {"theta": True, "thetadot": False}, "output_names": ["thetadot"],
    ...          "sensitivity_suffixes": ["__d_a"]}
    >>> check_named_output(facts, "theta")
    True
    >>> check_named_output(facts, "theta__d_a")
    Traceback (most recent call last):
    ValueError: 'theta__d_a' is not a position output of pendulum; give a coordinate, role, point coordinate or extra
    """
    kinds = facts["outputs"]
    if output in kinds:
        if not kinds[output]:
            raise _not_a_position_output(facts["name"], output)
        return True
    by = [suffix for suffix in facts["sensitivity_suffixes"] if output.endswith(suffix) and len(output) > len(suffix)]
    if len(by) > 1:
        return False
    if by:
        raise _not_a_position_output(facts["name"], output)
    # the words of Linkage.output for a name that it does not answer to
    raise ValueError(f"{facts['name']} has no output {output!r}; it has {', '.join(facts['output_names'])}")


def output_text(linkage: Linkage, output: str) -> str:
    """The NumPy module of :func:`_output_function` (function ``output``: ``value`` and ``rate``), derived with
    SymPy: a cached analysis keeps it."""
    from ..codegen.numpy import numpy_module
    from ..symbolic.linkage import Program
    from ..symbolic.vectors import rate, time_derivative
    expr = linkage.output(output)
    coordinates = linkage.coordinates
    arguments = tuple(coordinates) + tuple(rate(q) for q in coordinates) + tuple(linkage.parameters)
    program = Program(arguments, (), {"value": expr, "rate": time_derivative(expr, coordinates)})
    return numpy_module([("output", program, f"{linkage.name}: {output} and its rate.")])


def is_angle_output(linkage: Linkage, output: str) -> bool:
    """Whether ``output`` of ``linkage`` is an angle (:func:`~symlink.io.scene.angle_outputs`)."""
    from ..io.scene import angle_outputs
    return output in angle_outputs(linkage, [output])


def output_limits(linkage: Linkage | CachedLinkage, values: Mapping[str, float], output: str, *,
                  input: str | None = None,
                  reach: InputRange | None = None, motion: InputMotion | None = None,
                  points: int = 3600) -> OutputLimits:
    """Where ``output`` reaches its extremes as the input moves over its reachable range (radians).

    The output's rate with respect to the input (its time derivative at unit
    input speed, by the chain rule through the solved rates) changes sign
    there; each change on a scan of ``points`` over a turn is bisected to
    rounding.  ``values`` as for :func:`~symlink.numeric.reachability.reachable_range`.

    Parameters
    ----------
    linkage : Linkage
        A linkage with one moving input.
    values : mapping of str to float
        As for :func:`reachable_range`.
    output : str
        The output whose extremes to find.
    input : str, optional
        The moving input (default: the only one).
    reach : InputRange, optional
        Its reachable range, if found already.
    motion : InputMotion, optional
        A motion of the same linkage and values to reuse.
    points : int, optional
        The scan's number of input values (default 3600).

    Returns
    -------
    OutputLimits
        The limit positions (input value, output value, maximum or minimum), the stroke and the time ratio.

    Examples
    --------
    >>> import symlink
    >>> found = symlink.output_limits(symlink.slider_crank(), dict(a=1.0, b=3.0, offset=0.0), "slider")
    >>> [(round(p.at, 12) + 0.0, round(p.value, 12), p.kind) for p in found.positions], round(found.stroke, 12)
    ([(0.0, 4.0, 'maximum'), (3.14159265359, 2.0, 'minimum')], 2.0)
    """
    motion = InputMotion(linkage, values, input=input) if motion is None else motion
    reach = reachable_range(linkage, values, motion=motion) if reach is None else reach
    if isinstance(linkage, CachedLinkage):  # generated code and facts from the disk cache: no SymPy
        function, angle = linkage.output(output)
    else:
        function, angle = _output_function(linkage, output), is_angle_output(linkage, output)
    held = {q.name: motion.values[q.name] for q in linkage.inputs if q.name != motion.input}
    parameters = {s.name: motion.values[s.name] for s in linkage.parameters}

    def value_and_rate(inputs: numpy.ndarray) -> tuple[numpy.ndarray, numpy.ndarray]:
        solved = motion.at(inputs)
        arguments: dict[str, Any] = {name: solved[name] for name in motion.names + motion.rates}
        arguments.update({motion.input: inputs, **held, **parameters})
        arguments.update(motion.speeds)  # the moving input's rate 1, the others' 0
        with numpy.errstate(all="ignore"):
            found = function(**arguments)
        return numpy.asarray(found["value"], dtype=float), numpy.asarray(found["rate"], dtype=float)

    positions = []
    for low, high in reach.spans:
        grid = numpy.linspace(low, high, max(8, int(points * (high - low) / (2 * math.pi))))
        if reach.full_turn:
            grid = grid[:-1]  # a turn: the last point is the first
        _, slope = value_and_rate(grid)
        ahead = numpy.roll(slope, -1) if reach.full_turn else slope[1:]
        here = slope if reach.full_turn else slope[:-1]
        turns = numpy.flatnonzero(numpy.isfinite(here) & numpy.isfinite(ahead) & (here != 0)
                                  & (numpy.sign(here) != numpy.sign(ahead)))
        for i in turns.tolist():
            left = float(grid[i])
            right = float(grid[i + 1]) if i + 1 < len(grid) else float(grid[0] + 2 * math.pi)
            rising = bool(here[i] > 0)
            for _ in range(BISECTIONS):
                middle = 0.5 * (left + right)
                middle_rate = float(value_and_rate(numpy.array([middle]))[1][0])
                if middle_rate == 0:
                    left = right = middle
                    break
                if (middle_rate > 0) == rising:
                    left = middle
                else:
                    right = middle
            at = wrap_angle(left) if reach.full_turn else left
            value = float(value_and_rate(numpy.array([at]))[0][0])
            positions.append(LimitPosition(at, value, "maximum" if rising else "minimum"))
    positions.sort(key=lambda p: p.at)
    stroke = time_ratio = None
    if reach.full_turn and len(positions) == 2:
        first, second = positions
        travel = second.value - first.value
        stroke = abs(wrap_angle(travel)) if angle else abs(travel)
        forward = (second.at - first.at) % (2 * math.pi)
        time_ratio = max(forward, 2 * math.pi - forward) / min(forward, 2 * math.pi - forward)
    return OutputLimits(output, angle, tuple(positions), stroke, time_ratio)
