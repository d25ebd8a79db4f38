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
* with :func:`~symlink.workshop.pin_play.pin_play`, the worst case of the pins' **radial play** (joint
  clearance), linearised, and with :func:`~symlink.workshop.pin_play.pin_play_envelope` its exact range at
  chosen poses (a search over the play directions);
* with :func:`~symlink.workshop.sampled_builds.sample_builds`, a **Monte Carlo** check: many builds drawn from
  the same tolerance model and solved (vectorised over the builds), their deviation's percentiles beside the
  linear prediction; with ``folder=`` on Dask, in chunks written to a sweep's folder, so that a long check stops
  and resumes.

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
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Mapping, Sequence, Union

import numpy

from ..common.display import record_html
from ..numeric.design_jacobian import DesignJacobian

if TYPE_CHECKING:  # the symbolic side is imported where a linkage is worked on: a stack-up model read from the
    # disk cache (StackUpModel.from_entry) runs without SymPy
    from ..symbolic.linkage import Linkage

__all__ = ["Tolerance", "StackUp", "StackUpModel", "stack_up", "tolerance_arrays", "input_values", "SIGMAS_PER_BAND"]

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


def input_values(linkage: str, known: Sequence[str], inputs: Mapping[str, object] | None) -> dict[str, numpy.ndarray]:
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
        sweep = input_values(self.name, self.inputs, inputs)
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
