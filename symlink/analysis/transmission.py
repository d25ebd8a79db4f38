"""The transmission angle: of a four-bar in closed form, and of every two-angle or rod-and-slider loop of any linkage.

A loop whose two unknowns are angles (case 3) closes a triangle: its two
unknown vectors meet at a joint (C of the four-bar), and the transmission
angle is the interior angle there, in [0, pi]: 0 or pi at a toggle, where the
loop locks, and best near pi/2.  The four-bar's is the angle at C between
coupler and rocker (:func:`transmission_range`, :func:`transmission_curve`,
from the triangle over the diagonal BD); :func:`loop_transmissions` finds it
for each such loop of any one-input linkage over its reachable range, and
for each loop where a rod drives a slider (case 2b) the angle between the rod
and the normal of the guide.  A slider on a turning guide (cases 2a, 2c)
pushes normal to it whatever the input: it has no transmission angle to watch.

>>> [round(math.degrees(x), 2) for x in transmission_curve(20, 66, 56, 80, [0.0, math.pi])]
[58.23, 109.83]
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any, Callable, Collection, Mapping

import numpy

from ..common.angles import wrap
from ..common.display import record_html
from ..numeric.cached_linkage import CachedLinkage
from ..numeric.fourbar_transmission import (TransmissionRange, transmission_curve, transmission_range,  # noqa: F401
                                             triangle_angle)
from ..numeric.reachability import BISECTIONS, InputMotion, InputRange, reachable_range
from .joint_angles import direction_parts, joint_angle_arrays, joint_coordinates

if TYPE_CHECKING:  # the symbolic layer and the solvers are imported where used: a cached linkage needs neither
    import sympy as sp

    from ..numeric.solver import Solver
    from ..symbolic.linkage import Linkage
    from ..symbolic.vectors import Vector

__all__ = ["triangle_angle", "TransmissionRange", "transmission_range", "transmission_curve",
           "TransmissionJoint", "transmission_joints", "transmission_angles", "LoopTransmission",
           "loop_transmissions", "transmission_arrays", "transmission_coordinates", "RunTransmission",
           "run_transmission", "SANE_TRANSMISSION", "RUN_SAMPLES", "least_over_inputs", "HeldTransmission",
           "fourbar_held_transmission", "held_over_text"]

#: A transmission angle (its worst, ``min(mu, pi - mu)``) below this is flagged: the linkage drives badly near it
#: (30 degrees, the usual rule of thumb of the textbooks).
SANE_TRANSMISSION = math.radians(30.0)


def fourbar_transmission_solver() -> Solver:
    """The four-bar's transmission-angle solver, shared in a process: the one home of that request, so that a
    caller who needs its answers bit for bit the same over a search can settle its backend first
    (:func:`symlink.numeric.solver.settled`)."""
    from ..mechanism.catalog import fourbar
    from ..numeric.solver import shared_solver
    return shared_solver(fourbar, ("transmission",))


# --- any linkage ----------------------------------------------------------------------

@dataclass(frozen=True)
class TransmissionJoint:
    """The joint of a two-angle loop: the loop, and its two unknown vectors as walked into and out of it.

    ``into`` and ``out`` are ``(sign, vector, unknown)``: walking the loop's terms
    in order (a negative sign walks a vector backwards), ``into`` ends at the
    joint and ``out`` starts there; the interior angle at the joint is the angle
    between ``-into`` and ``out``.

    ``guide``: a rod driving a slider (case 2b: ``into`` is the slider's travel,
    ``out`` the rod).  The guide acts as a rocker of infinite length at right
    angles to it, so the transmission angle is the angle between the rod and
    the normal of the guide (turned a quarter turn counter-clockwise from the
    travel's own direction), in [0, pi]: pi/2 with the rod along the guide.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    loop: str
    into: tuple[int, Vector, sp.Symbol]
    out: tuple[int, Vector, sp.Symbol]
    guide: bool = False

    @property
    def name(self) -> str:
        """The joint, in the vectors' names: ``BC/DC``."""
        return f"{self.into[1].name or self.into[2]}/{self.out[1].name or self.out[2]}"


def transmission_joints(linkage: Linkage) -> tuple[TransmissionJoint, ...]:
    """The joint of every loop whose two unknowns are angles (case 3), in plan order.

    The two unknown vectors follow each other in the loop's terms (cyclically)
    when the loop is written in walking order, as every catalog loop is; if they
    do not, they are taken to meet head to head, as coupler and rocker do at C.

    >>> from symlink.mechanism.catalog import fourbar
    >>> [(j.loop, j.name) for j in transmission_joints(fourbar())]
    [('ABCD', 'DC/BC')]
    """
    joints = []
    if not linkage.has_closed_form:  # every loop has more than two unknowns: none closes a triangle alone
        return ()
    for step in linkage.plan:
        if step.case.name == "2b":
            travel, rod = ((step.case.first, step.case.second) if step.case.first.part == "length"
                           else (step.case.second, step.case.first))
            joints.append(TransmissionJoint(step.loop.name, (1, travel.vector, travel.symbol),
                                            (1, rod.vector, rod.symbol), guide=True))
            continue
        if step.case.name != "3":
            continue
        first, second = step.case.first, step.case.second
        terms = list(step.loop.terms)
        where = {}
        for unknown in (first, second):
            where[unknown.symbol] = next(k for k, (sign, vector) in enumerate(terms)
                                         if vector == unknown.vector and sign == unknown.sign)
        i, j = where[first.symbol], where[second.symbol]
        n = len(terms)
        if (i + 1) % n == j:
            into, out = (first, second)
        elif (j + 1) % n == i:
            into, out = (second, first)
        else:  # not walked one after the other: taken to meet head to head, the second walked back out
            into, out = (first, second)
            out = type(out)(out.symbol, -out.sign, out.vector, out.part, out.offset)
        joints.append(TransmissionJoint(step.loop.name, (into.sign, into.vector, into.symbol),
                                        (out.sign, out.vector, out.symbol)))
    return tuple(joints)


def _linear_terms(expr: sp.Expr, what: str) -> list[list]:
    """``expr`` as ``[[coefficient, name or None], ...]``: a sum of multiples of named values and a constant, in a
    fixed order (the constant first, then by name), so that every process adds them alike."""
    import sympy as sp
    terms: list[list] = []
    for term, coefficient in sp.expand(expr).as_coefficients_dict().items():
        if term.is_number:
            terms.append([float(coefficient * term), None])
        elif isinstance(term, sp.Symbol):
            terms.append([float(coefficient), term.name])
        else:
            raise ValueError(f"the {what} is not a sum of multiples of the linkage's values: {expr}")
    return sorted(terms, key=lambda t: (t[1] is not None, t[1] or ""))


def direction_recipe(sign: int, vector: Vector, known: Collection[str]) -> dict[str, Any]:
    """How a walked vector's direction follows from solved coordinates and ``known`` values, as plain data (JSON).

    ``coordinate``: the one coordinate its angle turns with (None for a guide at a fixed angle); ``offset``: the
    rest of its angle, and ``length``: its length where the values fix it and it may be negative (its sign turns
    it half a turn; None for a length, which is positive, or an unknown), each a sum of multiples of named values
    (:func:`_linear_terms`); ``sign``: walked forwards (+1) or back (-1, half a turn more).  A cached analysis and a sweep's facts keep it, so that a warm one needs no SymPy
    (:func:`~symlink.analysis.joint_angles.direction_parts` evaluates it).
    """
    import sympy as sp
    angle = vector.angle
    moving = [s for s in angle.free_symbols if s.name not in known]
    if len(moving) > 1 or (moving and sp.diff(angle, moving[0]) != 1):
        raise ValueError(f"the angle of {vector.name or vector} is not a coordinate plus a constant")
    fixed = (vector.length.free_symbols <= {s for s in vector.length.free_symbols if s.name in known}
             and not vector.length.is_positive)
    return {"sign": int(sign), "coordinate": moving[0].name if moving else None,
            "offset": _linear_terms(angle - moving[0] if moving else angle, f"angle of {vector.name or vector}"),
            "length": _linear_terms(vector.length, f"length of {vector.name or vector}") if fixed else None}


def _direction(recipe: Mapping[str, Any], values: Mapping[str, float], solved: Mapping[str, numpy.ndarray]):
    """The walked direction of a vector (radians) and its rate, from solved coordinates and values."""
    offset, flip = direction_parts(recipe, values)
    q = recipe["coordinate"]
    if q is None:  # a guide at a fixed angle
        return numpy.full(numpy.shape(solved["assembled"]), offset + flip), 0.0
    return solved[q] + offset + flip, solved[q + "dot"]


def joint_recipe(joint: TransmissionJoint, known: Collection[str]) -> dict[str, Any]:
    """A two-angle loop's joint as plain data (JSON): its loop, name, whether a guide, and the
    :func:`direction_recipe` of the vectors into and out of it (``known``: the names given values)."""
    return {"loop": joint.loop, "name": joint.name, "guide": joint.guide,
            "into": direction_recipe(*joint.into[:2], known), "out": direction_recipe(*joint.out[:2], known)}


def _interior(joint: Mapping[str, Any], values, solved) -> tuple[numpy.ndarray, numpy.ndarray]:
    """The interior angle at the joint (a :func:`joint_recipe`), in [0, pi], and its derivative with respect to
    the input."""
    into, into_rate = _direction(joint["into"], values, solved)
    out, out_rate = _direction(joint["out"], values, solved)
    turn = wrap(out - (into + (math.pi / 2 if joint["guide"] else math.pi)))  # from -into (or the normal) to out
    with numpy.errstate(invalid="ignore"):  # rates are not finite at a toggle
        return numpy.abs(turn), numpy.sign(turn) * (out_rate - into_rate)


def _joints(linkage: Any, known: Collection[str]) -> list[dict[str, Any]]:
    """The :func:`joint_recipe` of every two-angle loop of ``linkage``, or a cached linkage's own (no SymPy)."""
    if isinstance(linkage, CachedLinkage):
        return list(linkage.joints)
    return [joint_recipe(joint, known) for joint in transmission_joints(linkage)]


def transmission_angles(linkage: Linkage | CachedLinkage, values: Mapping[str, float], inputs, *,
                        input: str | None = None,
                        motion: InputMotion | None = None) -> dict[str, numpy.ndarray]:
    """The transmission angle (radians, [0, pi]) of every two-angle loop at ``inputs``, by loop name.

    NaN where the linkage cannot be assembled.  ``values`` as for
    :func:`~symlink.numeric.reachability.reachable_range`.

    Parameters
    ----------
    linkage : Linkage
        A linkage with one moving input.
    values : mapping of str to float
        As for :func:`reachable_range`.
    inputs : array_like
        The input values (radians for an angle).
    input : str, optional
        The moving input (default: the only one).
    motion : InputMotion, optional
        A motion of the same linkage and values to reuse.

    Returns
    -------
    dict of str to numpy.ndarray
        Each two-angle loop's transmission angle (radians, in [0, pi]) at ``inputs``.

    Examples
    --------
    >>> import math, symlink
    >>> angles = symlink.transmission_angles(symlink.fourbar(), dict(a=20, b=66, c=56, d=80), [0.0])
    >>> round(math.degrees(float(angles["ABCD"][0])), 2)  # acos((66^2 + 56^2 - 60^2) / (2 * 66 * 56))
    58.23
    """
    motion = InputMotion(linkage, values, input=input) if motion is None else motion
    solved = motion.at(inputs)
    return {joint["loop"]: _interior(joint, motion.values, solved)[0] for joint in _joints(linkage, motion.values)}


@lru_cache(maxsize=32)
def joint_recipes(linkage: Linkage) -> tuple[dict[str, Any], ...]:
    """The :func:`joint_recipe` of every two-angle loop, with the parameters and every input known (values, as a
    sweep or a synthesis passes them to :func:`~symlink.analysis.joint_angles.joint_angle_arrays`): made once a
    linkage.

    >>> from symlink.mechanism.catalog import slider_crank
    >>> [(j["loop"], j["guide"], j["into"]["coordinate"], j["out"]["coordinate"])
    ...  for j in joint_recipes(slider_crank())]
    [('ABC', True, None, 'beta')]
    """
    known = {s.name for s in linkage.parameters + linkage.inputs}
    return tuple(joint_recipe(joint, known) for joint in transmission_joints(linkage))


def transmission_arrays(linkage: Linkage, values: Mapping[str, Any], solved: Mapping[str, numpy.ndarray]
                        ) -> dict[str, numpy.ndarray]:
    """The transmission angle of every two-angle loop, by loop name, from solved coordinates of many designs.

    ``values``: the parameters (and held inputs) by name, numbers or arrays that broadcast against the
    solved coordinates (one row a design, say); ``solved``: the unknowns by name, as a solver of them
    returns them (NaN where not assembled).  The same angles as :func:`transmission_angles`, from the joints'
    recipes made once a linkage (:func:`joint_recipes`, evaluated by
    :func:`~symlink.analysis.joint_angles.joint_angle_arrays`): no SymPy per design.

    >>> from symlink.numeric.solver import Solver
    >>> from symlink.mechanism.catalog import fourbar
    >>> solved = Solver(fourbar(), ["beta", "phi"])(theta=numpy.array([0.0]), a=20.0, b=66.0, c=56.0, d=80.0,
    ...                                               branch=1)
    >>> round(math.degrees(float(transmission_arrays(fourbar(), {}, solved)["ABCD"][0])), 2)
    58.23
    """
    return joint_angle_arrays(joint_recipes(linkage), values, solved)


def transmission_coordinates(linkage: Linkage) -> list[str]:
    """The coordinates :func:`transmission_arrays` needs solved, by name."""
    return joint_coordinates(joint_recipes(linkage))


@dataclass(frozen=True)
class LoopTransmission(TransmissionRange):
    """One loop's transmission angle over the reachable input range: extremes and where (radians),
    with the loop and the joint (its two unknown vectors) where it is measured."""

    _repr_html_ = record_html  # a notebook shows the fields as a table

    loop: str = ""
    joint: str = ""


def loop_transmissions(linkage: Linkage | CachedLinkage, values: Mapping[str, float], *, input: str | None = None,
                       reach: InputRange | None = None, motion: InputMotion | None = None,
                       points: int = 3600) -> tuple[LoopTransmission, ...]:
    """Extremes of the transmission angle of every two-angle loop over the reachable input range.

    Candidates: the ends of each span, the loop's toggles (where it is 0 or
    pi: the triangle is flat), and the input values where its derivative
    changes sign, found on a scan of ``points`` and bisected to rounding.

    Parameters
    ----------
    linkage : Linkage
        A linkage with one moving input.
    values : mapping of str to float
        As for :func:`reachable_range`.
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
    tuple of LoopTransmission
        For each two-angle loop: its smallest and largest transmission angle and where they are.

    Examples
    --------
    >>> import math, symlink
    >>> (found,) = symlink.loop_transmissions(symlink.fourbar(), dict(a=20, b=66, c=56, d=80))
    >>> found.loop, round(math.degrees(found.minimum), 2), round(math.degrees(found.maximum), 2)
    ('ABCD', 58.23, 109.83)
    """
    motion = InputMotion(linkage, values, input=input) if motion is None else motion
    reach = reachable_range(linkage, values, motion=motion) if reach is None else reach
    joints = _joints(linkage, motion.values)
    if not reach.spans or not joints:
        return ()
    found = []
    for joint in joints:
        def angle_and_rate(inputs, joint=joint):
            return _interior(joint, motion.values, motion.at(inputs))

        candidates: dict[float, float] = {}
        for low, high in reach.spans:
            grid = numpy.linspace(low, high, max(8, int(points * (high - low) / (2 * math.pi))))
            mu, slope = angle_and_rate(grid)
            for at, value in zip(grid[[0, -1]], mu[[0, -1]]):
                if numpy.isfinite(value):
                    candidates[float(at)] = float(value)
            finite = numpy.isfinite(slope)
            turns = numpy.flatnonzero(finite[:-1] & finite[1:] & (numpy.sign(slope[:-1]) != numpy.sign(slope[1:])))
            if turns.size:
                rising = slope[turns] > 0

                def rises(inputs):
                    return angle_and_rate(inputs)[1] > 0

                lower, upper = _bisect_sign(rises, grid[turns], grid[turns + 1], rising)
                for at in numpy.concatenate([lower, upper]).tolist():
                    value = float(angle_and_rate(numpy.array([at]))[0][0])
                    if math.isfinite(value):
                        candidates[at] = value
        for toggle in reach.toggles:  # the loop's own toggles: flat, so exactly 0 or pi there
            if toggle.loop == joint["loop"] and not toggle.degenerate:
                value = float(angle_and_rate(numpy.array([toggle.at]))[0][0])
                if math.isfinite(value):
                    candidates[toggle.at] = 0.0 if value < math.pi / 2 else math.pi
        low_at = min(candidates, key=candidates.__getitem__)
        high_at = max(candidates, key=candidates.__getitem__)
        found.append(LoopTransmission(candidates[low_at], low_at, candidates[high_at], high_at,
                                      loop=joint["loop"], joint=joint["name"]))
    return tuple(found)


def _bisect_sign(test, low, high, low_value):
    for _ in range(BISECTIONS):
        middle = 0.5 * (low + high)
        same = numpy.asarray(test(middle), dtype=bool) == low_value
        low, high = numpy.where(same, middle, low), numpy.where(same, high, middle)
    return low, high


@dataclass(frozen=True)
class RunTransmission:
    """The worst transmission angle over the motion a design runs: ``worst`` (``min(mu, pi - mu)``, radians) at
    input ``at`` in loop ``loop``; ``over`` says over what (``full turn`` for a crank, else the rocking range
    ``low`` to ``high`` of the input, between its values at the targets)."""

    _repr_html_ = record_html  # a notebook shows the fields as a table

    worst: float
    at: float
    loop: str
    over: str
    low: float
    high: float

    @property
    def sane(self) -> bool:
        """Whether the worst is at least :data:`SANE_TRANSMISSION`."""
        return self.worst >= SANE_TRANSMISSION


def run_transmission(linkage: Linkage, values: Mapping[str, float], inputs, *,
                     guess: Mapping[str, float] | None = None) -> RunTransmission | None:
    """The worst transmission angle of every two-angle (or rod-and-slider) loop over the motion the linkage runs.

    A linkage whose input turns fully runs the full turn; otherwise it rocks, between the smallest and the
    largest of ``inputs`` (its input at the targets of a synthesis), within the span that holds the first.
    None where no loop has a transmission angle, or where the linkage cannot be assembled at ``inputs[0]``.

    >>> from symlink.mechanism.catalog import fourbar
    >>> run = run_transmission(fourbar(), dict(a=20, b=66, c=56, d=80), [0.0])
    >>> run.over, round(math.degrees(run.worst), 2)
    ('full turn', 58.23)
    """
    given = numpy.atleast_1d(numpy.asarray(inputs, dtype=float))
    name = linkage.inputs[0].name
    start = float(given[0])
    motion = InputMotion(linkage, values, guess=guess, start=start)
    reach = reachable_range(linkage, values, motion=motion, guess=guess, start=start)
    if not reach.spans or not transmission_joints(linkage):
        return None
    if reach.full_turn:
        run, over, low, high = reach, "full turn", -math.pi, math.pi
    else:
        if reach.periodic:  # the targets' inputs on the turn of the span that holds the first
            given = numpy.unwrap(given)
            span = next(((lo, hi) for lo, hi in reach.spans
                         for shift in (0.0, 2 * math.pi, -2 * math.pi) if lo <= start + shift <= hi), None)
            if span is None:
                return None
            shift = next(k * 2 * math.pi for k in (0, 1, -1) if span[0] <= start + k * 2 * math.pi <= span[1])
            given = given + shift
        low, high = float(given.min()), float(given.max())
        if high <= low:
            high = low + 1e-9 * max(1.0, abs(low))
        toggles = tuple(t for t in reach.toggles if low <= t.at <= high)
        run = InputRange(name, ((low, high),), toggles, reach.exact, reach.periodic)
        over = "rocking range"
    found = loop_transmissions(linkage, values, reach=run, motion=motion)
    if not found:
        return None
    worst_of = lambda t: (t.minimum, t.minimum_at) if t.minimum <= math.pi - t.maximum else (  # noqa: E731
        math.pi - t.maximum, t.maximum_at)
    loop = min(found, key=lambda t: worst_of(t)[0])
    worst, at = worst_of(loop)
    return RunTransmission(float(worst), float(at), loop.loop, over, low, high)


# --- held over the motion: what a synthesis checks each trial design against ------------------------------------

#: Input values a turn at which a synthesis samples a trial design's transmission angle over the motion it runs
#: (one a degree); the least of them is then refined (:func:`least_over_inputs`).
RUN_SAMPLES = 360
_REFINEMENTS = 8      # bracket refinements of the sampled least, each a quarter as wide ...
_BRACKET_POINTS = 9   # ... from this many input values across the bracket
_BASINS = 3           # the smallest sampled local minima refined (a deeper basin between two samples is found too)


def least_over_inputs(worst_at: Callable[[numpy.ndarray], numpy.ndarray], low: float, high: float, *,
                      periodic: bool = False, samples: int = RUN_SAMPLES) -> tuple[float, float]:
    """The least of ``worst_at`` over the inputs ``low`` to ``high`` and where: sampled, then refined.

    ``worst_at(inputs)`` gives a value at each input (an array), NaN where the design is not assembled.
    A grid of ``samples`` a turn (at least 16 over any range) finds the least sample; the bracket around each of
    the :data:`_BASINS` smallest local minima of the grid is then shrunk :data:`_REFINEMENTS` times (nine values
    across it, the bracket around their least kept: a quarter as wide each time), a derivative-free search that
    places a smooth minimum within ~1e-5 of a grid step, so the least returned is the function's to rounding,
    not a grid's. ``periodic``: the range is a whole turn (the brackets wrap). Returns ``(least, at)``; NaN
    (and where) if any value is NaN.

    Parameters
    ----------
    worst_at : callable
        Values at an array of inputs (NaN where not assembled).
    low, high : float
        The range of the input.
    periodic : bool, optional
        The range is a whole turn (default False).
    samples : int, optional
        Grid values a turn (default :data:`RUN_SAMPLES`).

    Returns
    -------
    (float, float)
        The least value found and the input where it is.

    Examples
    --------
    >>> least, at = least_over_inputs(lambda q: (q - 0.1234567) ** 2 + 1.0, -1.0, 1.0)
    >>> round(least, 12), round(at, 6)
    (1.0, 0.123457)
    """
    span = high - low
    count = max(16, int(math.ceil(samples * span / (2 * math.pi))))
    grid = numpy.linspace(low, high, count, endpoint=not periodic) if span > 0 else numpy.array([low])
    values = numpy.asarray(worst_at(grid), dtype=float)
    if not numpy.all(numpy.isfinite(values)):
        where = int(numpy.flatnonzero(~numpy.isfinite(values))[0])
        return math.nan, float(grid[where])
    least_index = int(numpy.argmin(values))
    least, at = float(values[least_index]), float(grid[least_index])
    if len(grid) < 3:
        return least, at
    step = grid[1] - grid[0]
    before = numpy.roll(values, 1) if periodic else numpy.concatenate([[numpy.inf], values[:-1]])
    after = numpy.roll(values, -1) if periodic else numpy.concatenate([values[1:], [numpy.inf]])
    minima = numpy.flatnonzero((values <= before) & (values <= after))
    minima = minima[numpy.argsort(values[minima], kind="stable")][:_BASINS]
    centres, half = grid[minima].astype(float), step
    across = numpy.linspace(-1.0, 1.0, _BRACKET_POINTS)
    for _ in range(_REFINEMENTS):
        trial = centres[:, None] + half * across[None, :]
        if not periodic:
            trial = numpy.clip(trial, low, high)
        found = numpy.asarray(worst_at(trial.ravel()), dtype=float).reshape(trial.shape)
        found = numpy.where(numpy.isfinite(found), found, -numpy.inf)  # not assembled inside: that is the least
        best = numpy.argmin(found, axis=1)
        rows = numpy.arange(len(centres))
        centres, values_now = trial[rows, best], found[rows, best]
        k = int(numpy.argmin(values_now))
        if values_now[k] < least:
            least, at = float(values_now[k]), float(centres[k])
        half *= 2.0 / (_BRACKET_POINTS - 1)
    if not math.isfinite(least):
        return math.nan, at
    return least, at


@dataclass(frozen=True)
class HeldTransmission:
    """The worst transmission angle (``min(mu, pi - mu)``, radians) of a design over the motion it runs: ``over``
    is ``full turn`` (the input turns fully) or ``rocking range`` (between the inputs ``low`` and ``high`` of
    its targets); ``at`` the input where it is worst."""

    _repr_html_ = record_html  # a notebook shows the fields as a table

    worst: float
    at: float
    over: str
    low: float
    high: float


def held_over_text(over: str, low: float, high: float, angle: bool = True) -> str:
    """``the full turn`` or ``input 12-87.5 deg``: what a constraint was held over, in words (degrees for an angle).

    >>> held_over_text("rocking range", math.radians(12.0), math.radians(87.5))
    'input 12-87.5 deg'
    """
    if over == "full turn":
        return "the full turn"
    show = (lambda x: f"{math.degrees(x):.6g}") if angle else (lambda x: f"{x:.6g}")  # noqa: E731
    return f"input {show(low)}-{show(high)}" + (" deg" if angle else "")


def fourbar_held_transmission(a: float, b: float, c: float, d: float, theta) -> HeldTransmission:
    """The four-bar's worst transmission angle over the motion it runs, in closed form.

    A crank that turns fully (Grashof crank-rocker or double-crank, or a change point with the crank or the ground
    the shortest link, which turns through its flat pose, transmission angle zero, as
    :func:`~symlink.numeric.reachability.reachable_range` has it) runs the full turn; any other rocks between
    the smallest and the largest crank angle ``theta`` of its targets.  ``|BD|^2 = a^2 + d^2 - 2 a d cos(theta)``
    and mu grows with ``|BD|``, so over a range of crank angles mu is extreme at its ends and at theta = 0 and pi
    (and their turns) inside it; ``min(mu, pi - mu)`` is least at an extreme of mu.

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths.
    theta : array_like
        The crank angles at the targets (radians), in the order they are reached.

    Returns
    -------
    HeldTransmission
        The worst, where, and over what.

    Examples
    --------
    >>> held = fourbar_held_transmission(20, 66, 56, 80, [0.0])  # a crank-rocker: |BD| = 60 at theta = 0
    >>> held.over, round(math.degrees(held.worst), 2)
    ('full turn', 58.23)
    >>> held = fourbar_held_transmission(2.0, 1.0, 2.5, 3.0, [0.6, 1.0])  # a triple rocker, between its targets
    >>> held.over, round(math.degrees(held.worst), 2)  # cos mu = (1 + 6.25 - 13 + 12 cos 0.6) / 5 at the near end
    ('rocking range', 33.82)
    """
    from .grashof import grashof
    angles = numpy.atleast_1d(numpy.asarray(theta, dtype=float))
    kind = grashof(a, b, c, d)
    if kind.name in ("crank-rocker", "double-crank") or (kind.name == "change-point"
                                                         and kind.shortest in ("crank", "ground")):
        over, low, high = "full turn", -math.pi, math.pi
        candidates = numpy.array([0.0, math.pi])
    else:
        over, low, high = "rocking range", float(angles.min()), float(angles.max())
        inside = numpy.arange(math.ceil(low / math.pi), math.floor(high / math.pi) + 1) * math.pi
        candidates = numpy.concatenate([[low, high], inside])
    diagonal = numpy.sqrt(numpy.maximum(a * a + d * d - 2 * a * d * numpy.cos(candidates), 0.0))
    mu = triangle_angle(diagonal, b, c)
    worst = numpy.minimum(mu, math.pi - mu)
    if not numpy.all(numpy.isfinite(worst)):
        k = int(numpy.flatnonzero(~numpy.isfinite(worst))[0])
        return HeldTransmission(math.nan, float(candidates[k]), over, low, high)
    k = int(numpy.argmin(worst))
    return HeldTransmission(float(worst[k]), float(candidates[k]), over, low, high)
