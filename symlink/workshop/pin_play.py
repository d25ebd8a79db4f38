"""Pins' radial play (joint clearance): how far an output moves when each pin sits anywhere in its hole.

A pin of radial play r lets the link beyond it start anywhere within r of the hole's centre
(:func:`with_pin_play` adds that free vector to every loop and point that passes the pin).
:func:`pin_play` gives the worst case, linearised from exact derivatives
(:class:`~symlink.numeric.design_jacobian.DesignJacobian`) along the input range; :func:`pin_play_envelope`
the exact range at chosen poses, by a search over the play directions.  The stack-up of the links' dimensions is
:mod:`symlink.workshop.tolerance`; a Monte Carlo check of it, :mod:`symlink.workshop.sampled_builds`.

>>> from symlink.mechanism.catalog import fourbar
>>> result = pin_play(fourbar(), "rocker", {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1}, {"B": 0.01},
...                   inputs={"theta": [0.0]})
>>> bool(result.worst_case[0, 0] > 0)
True
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Mapping, Sequence

import numpy

from ..common.display import record_html
from ..numeric.design_jacobian import DesignJacobian
from .tolerance import input_values

if TYPE_CHECKING:  # the symbolic side is imported where a linkage is worked on
    from ..symbolic.linkage import Linkage
    from ..symbolic.vectors import Vector, VectorSum

__all__ = ["PinPlay", "pin_play", "with_pin_play", "play_jacobian", "played_pins", "PlayEnvelope", "pin_play_envelope"]


def _play_names(joint: str) -> tuple[str, str]:
    return f"play_{joint}_x", f"play_{joint}_y"


def with_pin_play(linkage: Linkage, joints: Sequence[str]) -> Linkage:
    """``linkage`` with a small free vector at each pin of ``joints``: its play, ``(play_J_x, play_J_y)``.

    The model: a pin of radial play r sits anywhere in its hole, so the link beyond it starts at the hole's
    centre plus a vector of length at most r and any direction.  Each loop and point that passes the pin
    (walking from one link's vectors to the other's) gets that vector, ``+`` walking from the first link
    of the joint to the second, ``-`` the other way, so that every loop sees the same play.  Zero play
    gives back the linkage's equations.  Pins only, each joining two links; ``ValueError`` otherwise.
    """
    import sympy as sp
    from ..mechanism.bodies import GROUND, PRISMATIC, REVOLUTE, mechanism
    from ..symbolic.linkage import Linkage
    from ..symbolic.loops import Loop
    from ..symbolic.vectors import Vector, VectorSum
    found = mechanism(linkage)
    body_of = {vector: body.name for body in found.bodies for vector in body.vectors}
    pins = {}
    for name in joints:
        joint = found.joint(name)  # ValueError naming the joints there are
        if joint.kind != REVOLUTE or len(joint.bodies) != 2:
            raise ValueError(f"pin play is modelled at pins joining two links; {name} is a {joint.kind} joint "
                             f"joining {', '.join(joint.bodies)}")
        pins[frozenset(joint.bodies)] = joint
    play = {}
    for name in joints:
        x, y = (sp.Symbol(n, real=True) for n in _play_names(name))
        play[name] = (Vector(x, 0, f"{_play_names(name)[0]}"), Vector(y, sp.pi / 2, f"{_play_names(name)[1]}"))

    travels = {joint.name: joint for joint in found.joints if joint.kind == PRISMATIC}

    def ends(sign: int, vector: Vector) -> tuple[str, str]:
        """The links a term is walked from and to: one link for a vector on it; guide to block for a slider's
        travel (its tail on the guide, its head on the block), block to guide walked backwards."""
        if vector.name in travels:
            guide, block = travels[vector.name].bodies
            return (guide, block) if sign > 0 else (block, guide)
        if vector.name not in body_of:
            raise ValueError(f"{linkage.name}: vector {vector.name or vector} is on no link; pin play needs every "
                             "vector of a loop on a link or a slider's travel")
        return body_of[vector.name], body_of[vector.name]

    def walked(terms: tuple[tuple[int, Vector], ...], before: str | None) -> VectorSum:
        """``terms`` with the play of every chosen pin they pass; ``before``: the link the walk starts on
        (the ground for a point's sum from the origin), ``None`` for a loop (it starts where it ends)."""
        links = [ends(sign, vector) for sign, vector in terms]
        passes = [(links[k - 1][1] if k else (before if before is not None else links[-1][1]), links[k][0])
                  for k in range(len(links))]
        total = VectorSum(terms)
        for leaving, entering in passes:
            joint = pins.get(frozenset((leaving, entering)))
            if joint is not None and leaving != entering:
                x, y = play[joint.name]
                total = total + (x + y if joint.bodies[0] == leaving else -(x + y))
        return total

    loops = [Loop(walked(loop.vectors.terms, None), loop.name) for loop in linkage.loops]
    points: dict[str, Vector | VectorSum | None] = {
        name: None if point is None else walked(point.as_sum().terms, GROUND) for name, point in linkage.points.items()}
    return Linkage(f"{linkage.name}_play", loops, linkage.inputs, linkage.unknowns, points=points,
                   roles=linkage.roles, extras=linkage.extras)


@dataclass(frozen=True)
class PinPlay:
    """The linearised effect of the pins' radial play on some outputs (see :func:`pin_play`).

    ``gradient[i, j, :, k]`` is the gradient (x, y) of output i by the play vector of pin j at input k;
    ``worst_case[i, k] = sum_j play_j |gradient[i, j, :, k]|``, the largest first-order deviation over all
    play directions; ``direction[i, j, k]`` the direction (radians) of pin j's play that raises output i most.
    """

    _repr_html_ = record_html  # a notebook shows its fields as a table

    outputs: tuple[str, ...]
    joints: tuple[str, ...]
    inputs: dict[str, numpy.ndarray]
    nominal: numpy.ndarray
    gradient: numpy.ndarray
    play: numpy.ndarray

    @property
    def worst_case(self) -> numpy.ndarray:
        """``sum_j play_j |g_j|``: the largest first-order deviation over every play direction (outputs, inputs)."""
        return numpy.einsum("ijk,j->ik", numpy.hypot(self.gradient[:, :, 0], self.gradient[:, :, 1]), self.play)

    @property
    def direction(self) -> numpy.ndarray:
        """The direction (radians) of each pin's play that raises each output most (outputs, pins, inputs)."""
        return numpy.arctan2(self.gradient[:, :, 1], self.gradient[:, :, 0])


def pin_play(linkage: Linkage, outputs: str | Sequence[str], nominal: Mapping[str, float],
             play: Mapping[str, float], inputs: Mapping[str, object] | None = None) -> PinPlay:
    """The worst case of the pins' radial play (joint clearance) on some outputs, linearised, along the inputs.

    ``play`` maps pin joints (their names, as :func:`symlink.mechanism.bodies.mechanism` gives them) to their radial
    play (the hole's radius less the pin's).  Each pin's play is a free vector of length at most its play
    (:func:`with_pin_play`); to first order the output moves by ``g_j . delta_j``, the largest of which over
    all directions is ``|g_j| play_j``, so the worst case is ``sum_j |g_j| play_j``, the plays pointing
    along their gradients (``direction``).  The gradients are exact sensitivities at zero play.  Assumes
    the links rigid, the play small beside the links, and every pin free to sit anywhere in its hole (no
    load that keeps it on one side).  Sliders are taken without play.

    Parameters
    ----------
    linkage : Linkage
        Any linkage.
    outputs : str or sequence of str
        The outputs.
    nominal : mapping
        Every parameter's value and each branch sign.
    play : mapping of str to float
        Pin joint -> its radial play (the hole's radius less the pin's).
    inputs : mapping, optional
        Input name -> the values to evaluate at (default: a full turn every 10 degrees).

    Returns
    -------
    PinPlay
        The worst case of each output at each input, and the plays' directions that give it.

    Examples
    --------
    >>> import symlink
    >>> result = symlink.pin_play(symlink.fourbar(), "rocker", {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1},
    ...                           {"B": 0.01, "C": 0.01}, inputs={"theta": [0.0]})
    >>> envelope = symlink.pin_play_envelope(symlink.fourbar(), "rocker", {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1},
    ...                                      {"B": 0.01, "C": 0.01}, at={"theta": 0.0})
    >>> result.worst_case.shape, bool(abs(envelope.highest - envelope.nominal - result.worst_case[0, 0]) < 1e-5)
    ((1, 1), True)
    """
    chosen = [outputs] if isinstance(outputs, str) else list(outputs)
    _check_play(play)
    return played_pins(play_jacobian(linkage, chosen, list(play)), linkage.name, [q.name for q in linkage.inputs],
                       nominal, play, inputs)


def _check_play(play: Mapping[str, float]) -> None:
    """``ValueError`` unless ``play`` gives at least one pin a finite play >= 0."""
    if not play:
        raise ValueError("give the radial play of at least one pin")
    for name, value in play.items():
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
            raise ValueError(f"the play of pin {name} must be a finite number >= 0, got {value!r}")


def play_jacobian(linkage: Linkage, outputs: Sequence[str], joints: Sequence[str]) -> DesignJacobian:
    """The exact derivatives of ``outputs`` by the play vectors (x, y) of the pins ``joints``, at zero play: what
    :func:`pin_play` evaluates (symbolic work; :meth:`DesignJacobian.entry_text` keeps it in the disk cache, so that
    a warm ``symlink tolerance --play`` runs it without SymPy through :func:`played_pins`)."""
    return DesignJacobian(with_pin_play(linkage, list(joints)), list(outputs),
                          [n for joint in joints for n in _play_names(joint)])


def played_pins(jacobian: DesignJacobian, name: str, input_names: Sequence[str], nominal: Mapping[str, float],
                play: Mapping[str, float], inputs: Mapping[str, object] | None = None) -> PinPlay:
    """:func:`pin_play` from its :func:`play_jacobian` (derived, or read from a cache entry: no linkage), for the
    linkage ``name`` with the inputs ``input_names``; the pins are those of ``play``, in the Jacobian's order.

    >>> from symlink.mechanism.catalog import fourbar
    >>> jacobian = DesignJacobian.from_entry(play_jacobian(fourbar(), ["rocker"], ["B"]).entry_text())
    >>> found = played_pins(jacobian, "fourbar", ["theta"], {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1},
    ...                     {"B": 0.01}, inputs={"theta": [0.0]})
    >>> expected = pin_play(fourbar(), "rocker", {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1}, {"B": 0.01},
    ...                     inputs={"theta": [0.0]})
    >>> bool(found.worst_case[0, 0] == expected.worst_case[0, 0] > 0)
    True
    """
    _check_play(play)
    chosen = list(jacobian.outputs)
    joints = list(play)
    names = [n for joint in joints for n in _play_names(joint)]
    if list(jacobian.parameters) != names:
        raise ValueError(f"the Jacobian is by {', '.join(jacobian.parameters)}, not by the play of {', '.join(joints)}")
    sweep = input_values(name, list(input_names), inputs)
    wanted = [name for name in jacobian.arguments if name not in sweep and name not in names]
    missing = [name for name in wanted if name not in nominal]
    if missing:
        raise ValueError(f"nominal: give the value of {', '.join(missing)}")
    values = {name: float(nominal[name]) for name in wanted} | dict.fromkeys(names, 0.0)
    found, slopes = jacobian(**sweep, **values)  # (inputs, outputs, 2 x joints)
    gradient = numpy.moveaxis(slopes.reshape(slopes.shape[:2] + (len(joints), 2)), 0, -1)
    nominal_values = numpy.stack([numpy.asarray(found[name], dtype=float) for name in chosen])
    return PinPlay(tuple(chosen), tuple(joints), sweep, nominal_values, gradient,
                   numpy.array([float(play[j]) for j in joints]))


#: Directions scanned per pin and round by :func:`pin_play_envelope` (a coarse turn, then a fine step about the best).
_SCAN = 3601
#: Rounds of the pin-by-pin search at most (it stops sooner when a round changes nothing).
_ROUNDS = 20


@dataclass(frozen=True)
class PlayEnvelope:
    """The exact range of an output over all play directions at one pose (see :func:`pin_play_envelope`).

    ``lowest`` and ``highest`` bound the output; ``low_directions`` and ``high_directions`` are the pins'
    play directions (radians, by joint) that reach them.
    """

    _repr_html_ = record_html  # a notebook shows its fields as a table

    output: str
    nominal: float
    lowest: float
    highest: float
    low_directions: dict[str, float]
    high_directions: dict[str, float]


def pin_play_envelope(linkage: Linkage, output: str, nominal: Mapping[str, float], play: Mapping[str, float],
                      at: Mapping[str, float]) -> PlayEnvelope:
    """The exact lowest and highest ``output`` over every direction of the pins' play, at the inputs ``at``.

    Not linearised: the linkage with its play vectors (:func:`with_pin_play`) is solved in closed form
    with each pin at the edge of its hole (``|delta_j| = play_j``, where a smooth output that moves with
    the play takes its extremes), and the directions are searched pin by pin (a scan of a full turn, then
    a fine scan about the best, repeated until a round changes nothing), starting from the linearised
    optimum (:func:`pin_play`).  Same assumptions as :func:`pin_play` otherwise.

    Parameters
    ----------
    linkage : Linkage
        A linkage with a closed-form plan.
    output : str
        The output.
    nominal : mapping
        Every parameter's value and each branch sign.
    play : mapping of str to float
        Pin joint -> its radial play.
    at : mapping of str to float
        The inputs' values.

    Returns
    -------
    PlayEnvelope
        The nominal output, its lowest and highest values, and the directions of the plays there.

    Examples
    --------
    >>> import symlink
    >>> envelope = symlink.pin_play_envelope(symlink.fourbar(), "rocker", {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1},
    ...                                      {"B": 0.05}, at={"theta": 0.0})
    >>> bool(envelope.lowest < envelope.nominal < envelope.highest), round(envelope.nominal, 6)  # seed 003: 110.74 deg
    (True, 1.932819)
    """
    from ..numeric.solver import Solver
    joints = list(play)
    linear = pin_play(linkage, output, nominal, play, inputs={k: [float(v)] for k, v in at.items()})
    playing = with_pin_play(linkage, joints)
    solver = Solver(playing, [output])
    fixed = {name: float(nominal[name]) for name in solver.required
             if name not in at and not name.startswith("play_")} | {k: float(v) for k, v in at.items()}
    radii = numpy.array([float(play[j]) for j in joints])

    def value(directions: numpy.ndarray) -> numpy.ndarray:
        """The output for rows of directions (one column a pin); NaN where it cannot be assembled."""
        arguments = dict(fixed)
        for j, joint in enumerate(joints):
            x, y = _play_names(joint)
            arguments[x], arguments[y] = radii[j] * numpy.cos(directions[:, j]), radii[j] * numpy.sin(directions[:, j])
        found = solver(**arguments)
        return numpy.where(found["assembled"], numpy.asarray(found[output], dtype=float), numpy.nan)

    def search(sign: float) -> tuple[float, numpy.ndarray]:
        best = linear.direction[0, :, 0] + (0.0 if sign > 0 else math.pi)
        best_value = sign * float(value(best[None, :])[0])
        coarse = numpy.linspace(-math.pi, math.pi, _SCAN, endpoint=False)
        step = 2 * math.pi / _SCAN
        for _ in range(_ROUNDS):
            before = best_value
            for j in range(len(joints)):
                for turn in (coarse, best[j] + numpy.linspace(-2 * step, 2 * step, _SCAN)):
                    trial = numpy.repeat(best[None, :], len(turn), axis=0)
                    trial[:, j] = turn
                    scores = sign * value(trial)
                    if numpy.isfinite(scores).any() and numpy.nanmax(scores) > best_value:
                        k = int(numpy.nanargmax(scores))
                        best, best_value = trial[k].copy(), float(scores[k])
            if best_value <= before:
                break
        return sign * best_value, best

    highest, high = search(1.0)
    lowest, low = search(-1.0)
    wrap_turn = lambda angles: {j: float(math.remainder(a, 2 * math.pi)) for j, a in zip(joints, angles)}  # noqa: E731
    return PlayEnvelope(output, float(linear.nominal[0, 0]), lowest, highest, wrap_turn(low), wrap_turn(high))


#: Builds x input values x outputs that :func:`sample_builds` keeps at most (8 bytes each).
