"""Tolerance stack-ups from exact sensitivities: how far an output moves when the links are made to tolerance.

A link is never made exactly to its drawing.  Given a tolerance for some of a
linkage's dimensions (its parameters: lengths, fixed angles, pivot
coordinates; masses and inertias of a :func:`~symlink.dynamics.inverse.dynamic_linkage`),
:func:`stack_up` tells, for each output along the input range (a position, a
rate, the driving torque),

* the **worst case**: ``sum_j |dy/dp_j| * band_j``, the largest first-order
  deviation when every dimension sits at the end of its ± band that hurts most;
* the **statistical** band: the output's standard deviation
  ``sqrt(sum_j (dy/dp_j * sigma_j)^2)`` (root sum of squares, the dimensions
  independent), reported as ``rss = 3 sigma`` so that it is comparable with
  bands read as 3 sigma;
* the **contribution** of each dimension (its share of the output's variance),
  the ranking a designer acts on: tighten the first, relax the last;
* the first-order **mean shift** ``1/2 sum_j d2y/dp_j^2 * sigma_j^2``: a
  curved output does not average to its nominal value;
* with :func:`pin_play`, the worst case of the pins' **radial play** (joint clearance), linearised, and
  with :func:`pin_play_envelope` its exact range at chosen poses (a search over the play directions);
* with :func:`sample_builds`, a **Monte Carlo** check: many builds drawn from the same tolerance model and
  solved (vectorised over the builds), their deviation's percentiles beside the linear prediction; with
  ``folder=`` on Dask, in chunks written to a sweep's folder, so that a long check stops and resumes.

:mod:`symlink.plot.tolerance` draws the bands along the cycle and the contributions.

The first derivatives are exact: generated from the closure equations by
:class:`~symlink.numeric.design_jacobian.DesignJacobian` (for any linkage, closed form
or Newton).  The second derivatives are **central differences of those exact
first derivatives** (step ``(3 eps)^(1/3)`` times the dimension's size), so they
carry about ten correct digits, plenty for a term that is itself a correction.

A ± band is read as 3 sigma of a normal distribution unless a sigma is given
(:class:`Tolerance`).  Everything is in the linkage's own units: lengths in
the user's length unit, angles in radians.

>>> import numpy
>>> from symlink.mechanism.catalog import fourbar
>>> result = stack_up(fourbar(), "rocker", {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1},
...                   {"a": 0.05, "b": 0.05, "c": 0.05, "d": 0.05}, inputs={"theta": [0.0]})
>>> slopes = result.sensitivity[0, :, 0]  # d(rocker)/d(a, b, c, d) in rad per length unit
>>> bool(numpy.isclose(result.worst_case[0, 0], 0.05 * numpy.abs(slopes).sum()))
True
>>> result.ranking("rocker")[0][0]  # the coupler b moves the rocker most at theta = 0
'b'
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence, Union

import numpy

from ..common.display import record_html
from ..common.limits import format_bytes, require_memory
from ..numeric.design_jacobian import DesignJacobian

if TYPE_CHECKING:  # the symbolic side is imported where a linkage is worked on: a stack-up model read from the
    # disk cache (StackUpModel.from_entry) runs without SymPy
    from ..symbolic.linkage import Linkage
    from ..symbolic.vectors import Vector, VectorSum

__all__ = ["Tolerance", "StackUp", "StackUpModel", "stack_up", "tolerance_arrays", "SIGMAS_PER_BAND", "PinPlay", "pin_play", "with_pin_play", "play_jacobian", "played_pins",
           "PlayEnvelope", "pin_play_envelope",
           "SampledBuilds", "sample_builds", "solved_builds", "MAX_SAMPLED_VALUES", "BUILDS_PER_CHUNK"]

#: A ± band without a given sigma is read as this many standard deviations.
SIGMAS_PER_BAND = 3.0
#: Relative step of the central differences of the exact first derivatives: (3 eps)^(1/3) balances the
#: truncation error (step^2) against rounding (eps / step).
_STEP = (3 * numpy.finfo(float).eps) ** (1 / 3)


@dataclass(frozen=True)
class Tolerance:
    """One dimension's tolerance: a ± ``band`` (worst case) and a standard deviation ``sigma`` (statistics).

    Give either or both: a band alone has ``sigma = band / 3``; a sigma alone has ``band = 3 sigma``.

    Parameters
    ----------
    band : float, optional
        The +- band (worst case).
    sigma : float, optional
        The standard deviation (statistics).

    Examples
    --------
    >>> import symlink
    >>> symlink.Tolerance(0.06).sigma, symlink.Tolerance(sigma=0.01).band  # a band is 3 sigma
    (0.02, 0.03)
    """

    band: float | None = None
    sigma: float | None = None

    def __post_init__(self) -> None:
        for what in ("band", "sigma"):
            value = getattr(self, what)
            if value is not None and not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise ValueError(f"a tolerance's {what} must be a positive finite number, got {value!r}")
        if self.band is None and self.sigma is None:
            raise ValueError("a tolerance needs a band or a sigma")
        if self.band is None:
            object.__setattr__(self, "band", SIGMAS_PER_BAND * float(self.sigma))  # type: ignore[arg-type]
        if self.sigma is None:
            object.__setattr__(self, "sigma", float(self.band) / SIGMAS_PER_BAND)  # type: ignore[arg-type]


TolerancesLike = Mapping[str, Union[float, Tolerance]]


@dataclass(frozen=True)
class StackUp:
    """A tolerance stack-up along the input range (see :func:`stack_up`).

    Arrays are output-major: ``nominal[i, k]`` is output i at input value k,
    ``sensitivity[i, j, k]`` d(output i)/d(dimension j) there and ``curvature[i, j, k]``
    d2(output i)/d(dimension j)^2.  NaN where the nominal linkage cannot be assembled.
    """

    _repr_html_ = record_html  # a notebook shows its fields as a table

    outputs: tuple[str, ...]
    dimensions: tuple[str, ...]
    inputs: dict[str, numpy.ndarray]
    nominal: numpy.ndarray
    sensitivity: numpy.ndarray
    curvature: numpy.ndarray
    band: numpy.ndarray
    sigma: numpy.ndarray
    assembled: numpy.ndarray

    @property
    def worst_case(self) -> numpy.ndarray:
        """``sum_j |dy/dp_j| band_j``: the first-order worst-case deviation (±), shape (outputs, inputs)."""
        return numpy.einsum("ijk,j->ik", numpy.abs(self.sensitivity), self.band)

    @property
    def standard_deviation(self) -> numpy.ndarray:
        """``sqrt(sum_j (dy/dp_j sigma_j)^2)``: the output's first-order standard deviation."""
        return numpy.sqrt(numpy.einsum("ijk,j->ik", self.sensitivity ** 2, self.sigma ** 2))

    @property
    def rss(self) -> numpy.ndarray:
        """The statistical band (±): ``3 *`` :attr:`standard_deviation`, the confidence of a band read as 3 sigma."""
        return SIGMAS_PER_BAND * self.standard_deviation

    @property
    def mean_shift(self) -> numpy.ndarray:
        """``1/2 sum_j d2y/dp_j^2 sigma_j^2``: how far the output's mean lies from its nominal value."""
        return 0.5 * numpy.einsum("ijk,j->ik", self.curvature, self.sigma ** 2)

    @property
    def contributions(self) -> numpy.ndarray:
        """Each dimension's share of the output's variance, ``(dy/dp_j sigma_j)^2 / variance``: (outputs,
        dimensions, inputs), summing to 1 over the dimensions (NaN where the variance is zero)."""
        parts = self.sensitivity ** 2 * (self.sigma ** 2)[None, :, None]
        with numpy.errstate(invalid="ignore", divide="ignore"):
            return parts / parts.sum(axis=1, keepdims=True)

    def largest_contributor(self, output: str) -> list[str]:
        """The dimension with the largest share of ``output``'s variance at each input value ('' where none)."""
        shares = self.contributions[self._index(output)]
        best = numpy.argmax(numpy.nan_to_num(shares, nan=-1.0), axis=0)
        valid = numpy.isfinite(shares).all(axis=0)
        return [self.dimensions[j] if ok else "" for j, ok in zip(best, valid)]

    def ranking(self, output: str) -> list[tuple[str, float]]:
        """The dimensions by the largest deviation of ``output`` each causes anywhere on the range,
        ``max_k |dy/dp_j| sigma_j`` (one standard deviation), largest first."""
        spread = numpy.abs(self.sensitivity[self._index(output)]) * self.sigma[:, None]
        with numpy.errstate(invalid="ignore"):
            largest = [float(numpy.nanmax(row)) if numpy.isfinite(row).any() else math.nan for row in spread]
        order = sorted(range(len(self.dimensions)), key=lambda j: -largest[j] if math.isfinite(largest[j]) else 0)
        return [(self.dimensions[j], largest[j]) for j in order]

    def _index(self, output: str) -> int:
        if output not in self.outputs:
            raise ValueError(f"this stack-up has no output {output!r}; it has {', '.join(self.outputs)}")
        return self.outputs.index(output)


def tolerance_arrays(tolerances: TolerancesLike) -> tuple[list[str], numpy.ndarray, numpy.ndarray]:
    """The toleranced dimensions' names, bands and sigmas (in that order) of ``tolerances`` (see :func:`stack_up`),
    checked: what :meth:`StackUpModel.stack_up` takes.

    >>> tolerance_arrays({"a": 0.3, "b": Tolerance(sigma=0.05)})
    (['a', 'b'], array([0.3 , 0.15]), array([0.1 , 0.05]))
    """
    if not tolerances:
        raise ValueError("give a tolerance for at least one dimension")
    names, bands, sigmas = [], [], []
    for name, given in tolerances.items():
        if isinstance(given, (int, float)) and not isinstance(given, bool):
            try:
                given = Tolerance(float(given))
            except ValueError:
                raise ValueError(f"the tolerance of {name} must be a positive finite band, got {given!r}") from None
        if not isinstance(given, Tolerance):
            raise ValueError(f"the tolerance of {name} must be a number (a ± band) or a Tolerance, got {given!r}")
        names.append(name)
        bands.append(given.band)
        sigmas.append(given.sigma)
    return names, numpy.array(bands, dtype=float), numpy.array(sigmas, dtype=float)


def _input_values(linkage: str, known: Sequence[str], inputs: Mapping[str, object] | None) -> dict[str, numpy.ndarray]:
    """The values of the inputs ``known`` of the linkage named ``linkage`` along a stack-up, checked."""
    if inputs is None:
        if len(known) != 1:
            raise ValueError(f"{linkage} has {len(known)} inputs: give the values of each in inputs=")
        return {known[0]: numpy.radians(numpy.arange(0.0, 360.0, 10.0))}
    for name in inputs:
        if name not in known:
            raise ValueError(f"{linkage} has no input {name!r}; its inputs are {', '.join(known)}")
    missing = [name for name in known if name not in inputs]
    if missing:
        raise ValueError(f"give the values of the input {', '.join(missing)} in inputs=")
    try:
        arrays = [numpy.atleast_1d(numpy.asarray(inputs[name], dtype=float)) for name in known]
        shape = numpy.broadcast_shapes(*(a.shape for a in arrays))
    except (TypeError, ValueError):
        raise ValueError("the input values must be numbers in arrays that broadcast together") from None
    if len(shape) != 1:
        raise ValueError(f"the input values must be one-dimensional, got shape {shape}")
    return {name: numpy.broadcast_to(array, shape).copy() for name, array in zip(known, arrays)}


#: The prefix of the parameters that stand in for the inputs' rates in a rate output's stack-up.
HELD_RATE_PREFIX = "held_"
#: Rounds of substituting the unknowns' rates and accelerations at most (one a loop of a chain, and two).
_SUBSTITUTIONS = 64


def _positions_only(linkage: Linkage, outputs: Sequence[str]) -> tuple[Linkage, dict[str, str]]:
    """``linkage`` with ``outputs`` as extras that depend on positions only; and how names map (user -> internal).

    An output that moves with the rates (a rocker's speed, the driving torque of a
    :func:`~symlink.dynamics.inverse.dynamic_linkage`) is a function of the positions, the inputs' rates and
    accelerations and the parameters once the unknowns' rates and accelerations are replaced by their closed
    forms (:attr:`~symlink.symbolic.linkage.Linkage.velocities`, :attr:`~symlink.symbolic.linkage.Linkage.accelerations`).
    At a held input motion the inputs' rates are constants: each becomes a parameter (``held_thetadot``)
    and the output an extra whose exact sensitivities :mod:`symlink.symbolic.sensitivity` derives by the chain rule.
    A linkage whose outputs are all positions comes back as it is.
    """
    import sympy as sp
    from ..symbolic.linkage import Linkage
    from ..symbolic.vectors import acceleration, rate
    moving = {rate(q) for q in linkage.coordinates} | {acceleration(q) for q in linkage.coordinates}
    expressions = {name: linkage.output(name) for name in outputs}  # ValueError naming an unknown output
    if not any(sp.sympify(e).free_symbols & moving for e in expressions.values()):
        return linkage, {}
    if not linkage.has_closed_form:
        raise ValueError(f"{linkage.name} has no closed form: the stack-up of a rate or a force needs one")
    definitions = {**dict(linkage.velocities), **dict(linkage.accelerations)}
    unknown = set(definitions)
    held = {}
    for q in linkage.inputs:
        for symbol in (rate(q), acceleration(q)):
            held[symbol] = sp.Symbol(HELD_RATE_PREFIX + symbol.name, real=True)
    extras = {name: e for name, e in linkage.extras.items() if not (sp.sympify(e).free_symbols & moving)}
    internal = {}
    for k, (name, expr) in enumerate(expressions.items()):
        for _ in range(_SUBSTITUTIONS):
            if not (expr.free_symbols & unknown):
                break
            expr = expr.xreplace(definitions)
        else:  # pragma: no cover - a plan whose rates refer to one another in a circle
            raise ValueError(f"{linkage.name}: the rates of {name} do not resolve into positions")
        expr = expr.xreplace(held)
        if expr.free_symbols & moving:  # pragma: no cover - a rate of a coordinate not an input nor an unknown
            raise ValueError(f"{linkage.name}: {name} moves with rates that are not the inputs'")
        internal[name] = f"held_output_{k}"
        extras[internal[name]] = expr
    appearing = set().union(*(extras[name].free_symbols for name in internal.values()))
    parameters = list(linkage.parameters) + [s for s in held.values() if s in appearing]
    return Linkage(linkage.name, linkage.loops, linkage.inputs, linkage.unknowns, parameters=parameters,
                   points=linkage.points, roles=linkage.roles, extras=extras), internal


def stack_up(linkage: Linkage, outputs: str | Sequence[str], nominal: Mapping[str, float],
             tolerances: TolerancesLike, inputs: Mapping[str, object] | None = None,
             guess: object = None) -> StackUp:
    """The tolerance stack-up of some position outputs of ``linkage`` along the input range.

    Parameters
    ----------
    linkage : Linkage
        Any linkage (a catalog entry, a linkage file's, your own).
    outputs : str or sequence of str
        Any outputs: a coordinate or its role (``rocker``), a point's ``C_x``, an extra output
        (``transmission``); also a rate or an acceleration (``rocker_speed``) and, of a
        :func:`~symlink.dynamics.inverse.dynamic_linkage`, the driving torque (``input_torque``), a reaction or
        a shaking force: these at a held input motion, its rates (``thetadot``, ``thetaddot``) given in
        ``nominal``.
    nominal : mapping
        The design: every parameter's value (a dynamic linkage's masses too) and each branch sign (extra
        names are ignored).
    tolerances : mapping
        Dimension name (a parameter: a length, a mass, an inertia, ...; or an input's rate, ``thetadot``)
        -> a ± band (a number, read as 3 sigma) or a :class:`Tolerance`.  Dimensions left out are exact.
    inputs : mapping, optional
        Input name -> the values (one-dimensional) to evaluate at; by default a one-input linkage's
        input over a full turn every 10 degrees (in radians).
    guess : optional
        For a linkage without a closed form: the unknowns near the wanted assembly at the first input
        value (see :class:`~symlink.numeric.design_jacobian.DesignJacobian`).

    Returns
    -------
    StackUp
        Worst case, RSS, mean shift and contributions for every output at every input value.

    ``ValueError`` names what is wrong: an unknown output or dimension, a bad band, a missing value.

    The sensitivities of a rate or a force are exact too: the unknowns' rates and accelerations are
    replaced by their closed forms, which leaves a function of the positions, the inputs' rates and the
    parameters whose derivatives :mod:`symlink.symbolic.sensitivity` derives by the chain rule (the torque's by the
    masses are the terms the masses multiply).

    Examples
    --------
    >>> import symlink
    >>> result = symlink.stack_up(symlink.fourbar(), "rocker", {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1}, {"b": 0.3},
    ...                           inputs={"theta": [0.0]})
    >>> solver = symlink.Solver(symlink.fourbar(), ["rocker"])  # the slope by central differences, independently
    >>> rocker = lambda b: float(solver(theta=0.0, a=20, b=b, c=56, d=80)["rocker"])
    >>> slope = (rocker(66 + 1e-6) - rocker(66 - 1e-6)) / 2e-6
    >>> round(float(result.worst_case[0, 0]), 7), round(abs(slope) * 0.3, 7)  # radians for b = 66 +- 0.3
    (0.0063013, 0.0063013)
    """
    chosen = [outputs] if isinstance(outputs, str) else list(outputs)
    dimensions, bands, sigmas = tolerance_arrays(tolerances)
    return StackUpModel.derive(linkage, chosen, dimensions).stack_up(nominal, bands, sigmas, inputs, guess)


@dataclass(frozen=True)
class StackUpModel:
    """What the stack-ups of some outputs by some dimensions need of a linkage, derived once: the exact Jacobian of
    the outputs by the dimensions (:class:`~symlink.numeric.design_jacobian.DesignJacobian`) and the names.

    :meth:`derive` works on the linkage (SymPy); :meth:`entry_text` keeps the model as a disk-cache entry and
    :meth:`from_entry` reads it back without the linkage, so that a stack-up of a cached model imports no SymPy
    (``symlink tolerance`` run warm).  Closed forms only in an entry.

    >>> from symlink.mechanism.catalog import fourbar
    >>> model = StackUpModel.derive(fourbar(), ["rocker"], ["b"])
    >>> again = StackUpModel.from_entry(model.entry_text())
    >>> design = {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1}
    >>> result = again.stack_up(design, numpy.array([0.3]), numpy.array([0.1]), {"theta": [0.0]})
    >>> round(float(result.worst_case[0, 0]), 7)  # as stack_up's example: |d(rocker)/db| * 0.3
    0.0063013
    """

    #: The outputs and the toleranced dimensions, by the user's names.
    outputs: tuple[str, ...]
    dimensions: tuple[str, ...]
    #: The linkage's name (for messages) and its inputs' names.
    name: str
    inputs: tuple[str, ...]
    #: d(outputs)/d(dimensions), by the linkage's internal names.
    jacobian: DesignJacobian
    #: An output's internal name (a rate output stands as a position extra), by the user's name.
    internal: Mapping[str, str]
    #: The user's name of each parameter that holds an input's rate or acceleration (``held_thetadot``).
    held: Mapping[str, str]

    @classmethod
    def derive(cls, linkage: Linkage, outputs: Sequence[str], dimensions: Sequence[str]) -> StackUpModel:
        """The model of ``outputs`` of ``linkage`` by ``dimensions`` (symbolic work; ``ValueError`` naming an unknown
        output or dimension)."""
        source, internal = _positions_only(linkage, outputs)
        # The inputs' rates of a rate output are parameters of ``source`` (held_thetadot): internal name -> user's.
        held = {HELD_RATE_PREFIX + name: name for q in linkage.inputs for name in (q.name + "dot", q.name + "ddot")}
        named = list(dimensions)
        if internal:
            named = [HELD_RATE_PREFIX + name if HELD_RATE_PREFIX + name in held else name for name in named]
        jacobian = DesignJacobian(source, [internal.get(name, name) for name in outputs], named)
        return cls(tuple(outputs), tuple(dimensions), linkage.name, tuple(q.name for q in linkage.inputs), jacobian,
                   internal, held)

    def entry_text(self, **more: Any) -> str:
        """The model as the text of a disk-cache entry (``more``: further plain facts, back in :attr:`facts`)."""
        return self.jacobian.entry_text(stack_up={
            "outputs": list(self.outputs), "dimensions": list(self.dimensions), "name": self.name,
            "inputs": list(self.inputs), "internal": dict(self.internal), "held": dict(self.held)}, **more)

    @classmethod
    def from_entry(cls, text: str, namespace: Mapping[str, Any] | None = None) -> StackUpModel:
        """The model of an entry's text (:meth:`entry_text`), without its linkage: no SymPy.  ``namespace``: the text
        already run (see :meth:`DesignJacobian.from_entry`)."""
        jacobian = DesignJacobian.from_entry(text, namespace)
        kept = jacobian.facts["stack_up"]
        return cls(tuple(kept["outputs"]), tuple(kept["dimensions"]), kept["name"], tuple(kept["inputs"]), jacobian,
                   dict(kept["internal"]), dict(kept["held"]))

    @property
    def facts(self) -> dict[str, Any]:
        """The further facts its entry was written with (:meth:`entry_text`); empty for a derived model."""
        return {name: value for name, value in self.jacobian.facts.items() if name != "stack_up"}

    def stack_up(self, nominal: Mapping[str, float], bands: numpy.ndarray, sigmas: numpy.ndarray,
                 inputs: Mapping[str, object] | None = None, guess: object = None) -> StackUp:
        """The stack-up at the design ``nominal`` with the dimensions' ``bands`` and ``sigmas`` (in the order of
        :attr:`dimensions`), along ``inputs`` (see :func:`stack_up`)."""
        jacobian, held, internal = self.jacobian, self.held, self.internal
        sweep = _input_values(self.name, self.inputs, inputs)
        wanted = [name for name in jacobian.arguments if name not in sweep]
        given = {**nominal, **{name: nominal[user] for name, user in held.items() if user in nominal}}
        missing = [held.get(name, name) for name in wanted if name not in given]
        if missing:
            raise ValueError(f"nominal: give the value of {', '.join(missing)}")
        design = {name: float(given[name]) for name in wanted}
        extra = {} if guess is None else {"guess": guess}

        def evaluate(values: Mapping[str, float]) -> tuple[dict[str, numpy.ndarray], numpy.ndarray]:
            return jacobian(**sweep, **values, **extra)

        found, slopes = evaluate(design)  # slopes: (inputs, outputs, dimensions)
        curvature = numpy.empty_like(slopes)
        for j, name in enumerate(jacobian.parameters):
            step = _STEP * max(abs(design[name]), bands[j])
            ahead = evaluate({**design, name: design[name] + step})[1][..., j]
            behind = evaluate({**design, name: design[name] - step})[1][..., j]
            curvature[..., j] = (ahead - behind) / (2 * step)
        nominal_values = numpy.stack([numpy.asarray(found[internal.get(name, name)], dtype=float)
                                      for name in self.outputs])
        return StackUp(self.outputs, self.dimensions, sweep, nominal_values,
                       numpy.moveaxis(slopes, 0, -1), numpy.moveaxis(curvature, 0, -1), bands, sigmas,
                       numpy.asarray(found["assembled"], dtype=bool))


# --- pin play (joint clearance) ------------------------------------------------------------

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
    sweep = _input_values(name, list(input_names), inputs)
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
MAX_SAMPLED_VALUES = 50_000_000
#: Builds a chunk of :func:`sample_builds`: drawn from their own seeded generator and solved together.
BUILDS_PER_CHUNK = 10_000
#: Dask's local schedulers that :func:`sample_builds` runs its chunks on (``"auto"`` chooses one).
BUILD_SCHEDULERS = ("auto", "threads", "synchronous")
#: What the manifest of a folder of builds says it holds (a sweep's folder holds designs).
BUILDS_KIND = "tolerance builds"


@dataclass(frozen=True)
class SampledBuilds:
    """Builds drawn from a tolerance model and solved (see :func:`sample_builds`).

    ``deviation[i]`` is output i's deviation from its nominal value, shape (builds, input values) (angles
    wrapped to (-pi, pi]), NaN for a build that cannot be assembled there or has a dimension drawn
    non-positive where it must be positive; ``nominal[i, k]`` the nominal output; ``reused``: the chunks
    found done in the folder of a resumed run (0 in memory).
    """

    _repr_html_ = record_html  # a notebook shows its fields as a table

    outputs: tuple[str, ...]
    inputs: dict[str, numpy.ndarray]
    nominal: numpy.ndarray
    deviation: numpy.ndarray
    reused: int = 0

    @property
    def built(self) -> numpy.ndarray:
        """The share of builds assembled at each input value (outputs, inputs)."""
        return numpy.isfinite(self.deviation).mean(axis=1)

    def percentile(self, q: float | Sequence[float]) -> numpy.ndarray:
        """Percentiles ``q`` (0 to 100) of each output's deviation over the assembled builds at each input."""
        return numpy.nanpercentile(self.deviation, q, axis=1)

    @property
    def mean(self) -> numpy.ndarray:
        """The mean deviation over the assembled builds (outputs, inputs): compare with the mean shift."""
        return numpy.nanmean(self.deviation, axis=1)

    @property
    def standard_deviation(self) -> numpy.ndarray:
        """The deviation's standard deviation over the assembled builds (outputs, inputs)."""
        return numpy.nanstd(self.deviation, axis=1)


@dataclass(frozen=True)
class _BuildModel:
    """Everything a chunk of builds needs: it draws chunk ``index`` from its own generator, seeded by
    ``(seed, index)``, so that a chunk is the same whichever run, route or worker makes it."""

    solver: object
    outputs: tuple[str, ...]
    dimensions: tuple[str, ...]
    sigmas: numpy.ndarray
    positive: tuple[bool, ...]
    design: dict[str, float]
    sweep: dict[str, numpy.ndarray]
    nominal: numpy.ndarray
    angular: tuple[bool, ...]
    builds: int
    chunk: int
    seed: int

    def chunk_range(self, index: int) -> tuple[int, int]:
        first = index * self.chunk
        return first, min(first + self.chunk, self.builds)

    def draw(self, index: int) -> tuple[dict[str, numpy.ndarray], numpy.ndarray]:
        """Chunk ``index``: the dimensions drawn (each (size,)) and the outputs' deviations (outputs, size, inputs)."""
        from ..common.angles import wrap
        first, stop = self.chunk_range(index)
        size = stop - first
        generator = numpy.random.default_rng([self.seed, index])
        drawn = {name: self.design[name] + self.sigmas[j] * generator.standard_normal(size)
                 for j, name in enumerate(self.dimensions)}
        unmade = numpy.zeros((size, 1), dtype=bool)
        solved = {}
        for name, positive in zip(self.dimensions, self.positive):
            values = drawn[name][:, None].copy()
            if positive:
                unmade |= values <= 0
                values[values <= 0] = self.design[name]  # solved at the nominal, then thrown away
            solved[name] = values
        count = self.nominal.shape[1]
        found = self.solver(**{k: v[None, :] for k, v in self.sweep.items()},  # type: ignore[operator]
                            **{**self.design, **solved})
        good = numpy.broadcast_to(found["assembled"], (size, count)) & ~unmade
        deviation = numpy.empty((len(self.outputs), size, count))
        for i, name in enumerate(self.outputs):
            change = numpy.broadcast_to(found[name], (size, count)) - self.nominal[i]
            if self.angular[i]:
                change = wrap(change)
            deviation[i] = numpy.where(good, change, numpy.nan)
        return drawn, deviation

    def columns(self) -> list[str]:
        """The columns of a chunk's table: the build's number, each dimension drawn, each output's deviation
        at each input value (``rocker[3]``: at the fourth)."""
        count = self.nominal.shape[1]
        return ["build", *self.dimensions, *(f"{name}[{k}]" for name in self.outputs for k in range(count))]

    def table(self, index: int) -> bytes:
        """Chunk ``index`` as the bytes of a Parquet file (what a Dask task returns)."""
        from ..io.sweep_folder import parquet_bytes
        first, stop = self.chunk_range(index)
        drawn, deviation = self.draw(index)
        data = {"build": numpy.arange(first, stop, dtype=numpy.int64), **drawn}
        names = iter(self.columns()[1 + len(self.dimensions):])
        for i in range(len(self.outputs)):
            for k in range(deviation.shape[2]):
                data[next(names)] = deviation[i, :, k]
        return parquet_bytes(data)

    def settings(self, name: str, definition: str) -> dict[str, object]:
        """What decides the sample, as the folder's manifest keeps it (a resumed run must match it): ``name`` and
        ``definition`` are the linkage's name and the digest of its definition
        (:func:`~symlink.numeric.cache.definition_digest`, which a warm run reads from the cached facts)."""
        return {"kind": BUILDS_KIND, "linkage": name, "definition": definition,
                "outputs": list(self.outputs), "design": self.design,
                "sigmas": {name: float(s) for name, s in zip(self.dimensions, self.sigmas)},
                "inputs": {name: [float(v) for v in values] for name, values in self.sweep.items()},
                "seed": self.seed}


def _require_builds(builds: int, per_build: int, what: str) -> None:
    """``ValueError`` (one line, with the estimate and the most builds that would do) for builds of ``per_build``
    values each beyond :data:`MAX_SAMPLED_VALUES` or beyond the memory available: the deviations are kept, and
    joined from their chunks (twice their size for a moment)."""
    values = builds * per_build
    if values > MAX_SAMPLED_VALUES:
        raise ValueError(f"{what} are {values:,} values (about {format_bytes(16 * values)} of memory), more than the "
                         f"{MAX_SAMPLED_VALUES:,} sample_builds keeps; ask for at most "
                         f"{max(1, MAX_SAMPLED_VALUES // per_build):,} builds")
    require_memory(builds, 16 * per_build, f"keeping {what}",
                   advice=lambda fits: f"ask for at most {fits:,} builds")


def sample_builds(linkage: Linkage, outputs: str | Sequence[str], nominal: Mapping[str, float],
                  tolerances: TolerancesLike, inputs: Mapping[str, object] | None = None,
                  builds: int = 100_000, seed: int = 0, *, folder: str | os.PathLike | None = None,
                  scheduler: str = "auto", workers: int | None = None,
                  chunk: int = BUILDS_PER_CHUNK) -> SampledBuilds:
    """``builds`` linkages with each toleranced dimension drawn from a normal distribution (its sigma, a
    band read as 3 sigma: :class:`Tolerance`), about ``nominal``, solved at every input value.

    The Monte Carlo counterpart of :func:`stack_up`: where tolerances are small its percentiles agree
    with the linear bands, where they are large they show how far the linear model departs.  Closed
    forms only.  A dimension drawn non-positive where it must be positive (a length) is a build that
    cannot be made: NaN.

    The builds come in chunks of ``chunk``, each drawn from its own generator seeded by ``(seed, chunk
    number)``: a run repeats exactly, and the sample does not depend on where or in which order the chunks
    were made.  Without ``folder`` they are made here, in memory (NumPy only).  With ``folder`` they run
    as tasks on Dask (``scheduler``: ``"auto"``, ``"threads"`` or ``"synchronous"``, ``workers`` of them)
    and each chunk is written to the folder as it is done, as a sweep's are (Parquet chunks beside a
    manifest, verified when read: :mod:`symlink.io.sweep_folder`).  A long check can be stopped (Ctrl-C, a
    kill) and run again with the same arguments: it makes only the chunks missing and gives the same
    sample as a run never stopped (``reused`` counts the chunks found done).  Other arguments on the same
    folder are refused.  The folder needs the ``sweep`` extra (dask, pyarrow).

    Parameters
    ----------
    linkage : Linkage
        A linkage with a closed-form plan.
    outputs : str or sequence of str
        The outputs, as for :func:`stack_up`.
    nominal : mapping
        Every parameter's value and each branch sign.
    tolerances : mapping
        Dimension name -> a band (read as 3 sigma) or a :class:`Tolerance`.
    inputs : mapping, optional
        Input name -> the values to evaluate at (default: a full turn every 10 degrees).
    builds : int, optional
        How many builds (default 100000).
    seed : int, optional
        The seed of the chunks' generators (default 0).
    folder : str or os.PathLike, optional
        Run on Dask and keep each chunk in this folder (needs the ``sweep`` extra).
    scheduler : str, optional
        Dask's local scheduler with ``folder``: ``"auto"``, ``"threads"`` or ``"synchronous"``.
    workers : int, optional
        How many with ``folder``.
    chunk : int, optional
        Builds a chunk (default 10000).

    Returns
    -------
    SampledBuilds
        The deviations of every build from nominal, which builds could be made, and their percentiles.

    Examples
    --------
    >>> import symlink
    >>> sampled = symlink.sample_builds(symlink.fourbar(), "rocker", {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1},
    ...                                 {"b": 0.3}, inputs={"theta": [0.0]}, builds=1000)
    >>> sampled.deviation.shape, bool(sampled.built.all())
    ((1, 1000, 1), True)
    """
    from ..numeric.cache import definition_digest
    from ..numeric.solver import Solver
    from ..numeric.units import output_units
    chosen = [outputs] if isinstance(outputs, str) else list(outputs)
    if not linkage.has_closed_form:
        _check_sampling(builds, chunk, seed, scheduler)
        raise ValueError(f"{linkage.name} has no closed form: sample_builds solves closed forms only")
    # NumPy, not the compiled backend (which agrees to a few ulps): every chunk's last digits are the same in every
    # run, on every machine, with or without a C compiler; on blocks of builds the two are as fast (measured).
    return solved_builds(
        lambda: Solver(linkage, chosen, backend="numpy"), linkage.name, [q.name for q in linkage.inputs],
        {s.name: bool(s.is_positive) for s in linkage.parameters},
        lambda: [output_units(linkage, [o]).get(o) == "rad" for o in chosen], chosen, nominal, tolerances,
        inputs, builds, seed, folder=folder, scheduler=scheduler, workers=workers, chunk=chunk,
        settings=lambda model: model.settings(linkage.name, definition_digest(linkage)))


def _check_sampling(builds: int, chunk: int, seed: int, scheduler: str) -> None:
    """``ValueError`` for a number of builds, a chunk, a seed or a scheduler that :func:`sample_builds` cannot take."""
    for what, value in (("builds", builds), ("chunk", chunk)):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise ValueError(f"{what} must be a whole number >= 1, got {value!r}")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ValueError(f"seed must be a whole number >= 0, got {seed!r}")
    if scheduler not in BUILD_SCHEDULERS:
        raise ValueError(f"scheduler must be one of {', '.join(BUILD_SCHEDULERS)}, got {scheduler!r}")


def solved_builds(solver: Callable[[], Any], name: str, input_names: Sequence[str], parameters: Mapping[str, bool],
                  angular: Callable[[], Sequence[bool]], outputs: Sequence[str], nominal: Mapping[str, float],
                  tolerances: TolerancesLike, inputs: Mapping[str, object] | None = None, builds: int = 100_000,
                  seed: int = 0, *, folder: str | os.PathLike | None = None, scheduler: str = "auto",
                  workers: int | None = None, chunk: int = BUILDS_PER_CHUNK,
                  settings: Callable[[Any], dict[str, object]] | None = None) -> SampledBuilds:
    """:func:`sample_builds` of a closed-form solver of ``outputs`` without its linkage: what a warm ``symlink
    tolerance --samples`` runs (its solver from the disk cache, no SymPy).

    ``solver()`` makes the solver (NumPy: a :class:`~symlink.numeric.solver.Solver` or a cached one, with
    ``required`` and a call as theirs), once the arguments are checked; ``name`` and ``input_names`` are the
    linkage's; ``parameters`` maps each parameter's name to whether it must be positive (a length);
    ``angular()`` says which outputs are angles (wrapped); ``settings(model)``: what a folder's manifest keeps of
    the sample (needed with ``folder``).  The rest as for :func:`sample_builds`.

    >>> from symlink.numeric.cached_solver import CachedSolver
    >>> sampled = solved_builds(lambda: CachedSolver("fourbar", ["rocker"]), "fourbar", ["theta"],
    ...                         {"a": True, "b": True, "c": True, "d": True}, lambda: [True], ["rocker"],
    ...                         {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1}, {"b": 0.3}, {"theta": [0.0]}, 1000)
    >>> sampled.deviation.shape, bool(sampled.built.all())
    ((1, 1000, 1), True)
    """
    chosen = list(outputs)
    dimensions, _, sigmas = tolerance_arrays(tolerances)
    _check_sampling(builds, chunk, seed, scheduler)
    sweep = _input_values(name, list(input_names), inputs)
    count = len(next(iter(sweep.values())))
    _require_builds(builds, count * len(chosen), f"{builds:,} builds x {count:,} input value{'s' if count != 1 else ''} x {len(chosen)} "
                    f"output{'s' if len(chosen) != 1 else ''}")
    for dimension in dimensions:
        if dimension not in parameters:
            raise ValueError(f"{name} has no parameter {dimension!r}; it has {', '.join(parameters)}")
    if folder is not None:
        if settings is None:
            raise ValueError("builds in a folder need what its manifest keeps of them (settings)")
        from .sweep import SWEEP_EXTRA, missing_modules
        absent = missing_modules(("dask", "pyarrow"))
        if absent:
            raise ImportError(f"builds in a folder need {', '.join(absent)}: {SWEEP_EXTRA} (or give no folder: "
                              "the builds are then made in memory with NumPy)")
    solving = solver()
    wanted = [argument for argument in solving.required if argument not in sweep]
    missing = [argument for argument in wanted if argument not in nominal]
    if missing:
        raise ValueError(f"nominal: give the value of {', '.join(missing)}")
    design = {argument: float(nominal[argument]) for argument in wanted}
    centre = solving(**sweep, **design)
    nominal_values = numpy.stack([numpy.asarray(numpy.broadcast_to(centre[o], (count,)), dtype=float)
                                  for o in chosen])
    model = _BuildModel(solving, tuple(chosen), tuple(dimensions), sigmas,
                        tuple(parameters[dimension] for dimension in dimensions), design, sweep, nominal_values,
                        tuple(angular()), builds, chunk, seed)
    chunks = -(-builds // chunk)
    if folder is None:
        deviation = numpy.concatenate([model.draw(index)[1] for index in range(chunks)], axis=1)
        return SampledBuilds(tuple(chosen), sweep, nominal_values, deviation)
    assert settings is not None  # checked above
    reused = _builds_in_folder(model, settings(model), Path(folder), scheduler, workers)
    return SampledBuilds(tuple(chosen), sweep, nominal_values, _read_builds(model, Path(folder)), reused)


def _builds_in_folder(model: _BuildModel, settings: dict[str, object], folder: Path, scheduler: str,
                      workers: int | None) -> int:
    """Make the chunks of ``model`` that ``folder`` does not hold yet on Dask, writing each as it is done;
    the number of chunks found done."""
    from .sweep import local_chunks, local_scheduler
    from ..io.sweep_folder import open_folder
    from ..version import __version__
    header = {"symlink": __version__, "settings": settings, "columns": model.columns()}
    with open_folder(folder, header, model.builds, model.chunk) as opened:
        todo = list(opened.todo)
        reused = -(-model.builds // model.chunk) - len(todo)
        chosen = local_scheduler(len(todo), workers) if scheduler == "auto" else scheduler

        def land(index: int, result: bytes) -> None:  # in this thread, as each chunk ends
            first, stop = model.chunk_range(index)
            opened.stage(index, result, rows=stop - first)

        local_chunks(model.table, todo, chosen, workers, None, land)
    return reused


def _read_builds(model: _BuildModel, folder: Path) -> numpy.ndarray:
    """The deviations (outputs, builds, inputs) of every chunk of ``folder``, each verified against the manifest
    and checked to hold its builds in the model's columns; ``ValueError`` naming one that does not."""
    import pyarrow
    import pyarrow.parquet

    from ..io.sweep_folder import numpy_column, verified_chunks
    count = model.nominal.shape[1]
    deviation = numpy.full((len(model.outputs), model.builds, count), numpy.nan)
    names = model.columns()
    done = numpy.zeros(model.builds, dtype=bool)
    for record, data in verified_chunks(folder):
        # one file, read as one: read_table goes through pyarrow.dataset (imported for it alone)
        table = pyarrow.parquet.ParquetFile(pyarrow.BufferReader(data)).read()
        numbers = numpy_column(table, "build") if "build" in table.column_names else None
        if (table.column_names != names or numbers is None
                or not numpy.array_equal(numbers, numpy.arange(record.first, record.last + 1))):
            raise ValueError(f"{folder / record.name} does not hold builds {record.first} to {record.last} in the "
                             "manifest's columns; run again with the same arguments to rebuild it")
        column = 1 + len(model.dimensions)
        for i in range(len(model.outputs)):
            for k in range(count):
                deviation[i, record.first:record.last + 1, k] = numpy_column(table, names[column])
                column += 1
        done[record.first:record.last + 1] = True
    if not done.all():
        raise ValueError(f"{folder} holds {int(done.sum())} of {model.builds} builds: run again with the same "
                         "arguments to make the rest")
    return deviation
