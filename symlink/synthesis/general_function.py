"""Function generation for any one-input linkage: an output angle or a slider's travel as a function of the input.

:mod:`symlink.synthesis.function` designs four-bars with Freudenstein's equation; here the
linkage is any one with one input and a closed form (a catalog entry or a linkage file), and the
output any of its angles or lengths (a Watt II's output rocker ``psi``, a slider-crank's travel
``s``).  The user gives the input values and the wanted output at each (precision points when
there are as many as free parameters, least squares when there are more; :func:`chebyshev_inputs`
spaces them the way that keeps the error between them small), and the parameters that are free
with their bounds.

The residuals are generated minus wanted output at each input: for an angle the difference
wrapped to (-pi, pi] (radians), for a length over the wanted values' size (their largest
magnitude or span).  Their exact Jacobian comes from the generated sensitivities
(:class:`symlink.synthesis.design_fit.DesignOutputs`); the refinement is the accelerated
Levenberg-Marquardt of path synthesis, which never accepts an infeasible trial (outside the
bounds, not assembled at an input, or at a toggle).  Starts are random feasible designs (free
parameters uniform within the bounds, random branch signs, kept when assembled at every
input), the closest refined first; for the catalog four-bar with its rocker as the output,
Freudenstein's least-squares design (:func:`symlink.synthesis.function.least_squares_design`)
is the first start.  The best design is verified afresh with the linkage's own generated
solver: the output at each input, and between consecutive inputs one branch without a toggle.
``structural_error`` is the largest error at the given inputs (radians or the output's unit).

>>> from symlink.mechanism.catalog import slider_crank
>>> inputs = chebyshev_inputs(0.2, 2.8, 6)
>>> wanted = function_values(slider_crank(), "s", {"a": 1.3, "b": 4.1, "offset": 0.7}, inputs)
>>> found = synthesize_function(slider_crank(), "s", inputs, wanted, {"a": (0.5, 2.0), "b": (3.0, 5.0)},
...                             values={"offset": 0.7})
>>> found.assembled, found.structural_error < 1e-12, round(found.design["a"], 9), round(found.design["b"], 9)
(True, True, 1.3, 4.1)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Mapping

import numpy
from numpy.typing import ArrayLike

from ..common.angles import wrap
from ..common.display import record_html
from ..symbolic.linkage import Linkage
from .design_fit import (DesignOutputs, branch_break, check_branches, check_linkage, free_bounds, inside,
                         is_angle_output, refine, sample_count, sampled_designs, solved_outputs)
from .function import chebyshev_points, check_function_targets
from .path import check_starts

__all__ = ["FunctionSynthesis", "synthesize_function", "function_values", "chebyshev_inputs"]

_DONE = 1e-12  # a verified design whose error over the output's unit is below this ends the search
_LAWSON_STEPS = 40      # minimax: Lawson re-weightings of the least squares ...
_LAWSON_EVALUATIONS = 60  # ... each refined with at most this many evaluations


@dataclass(frozen=True)
class FunctionSynthesis:
    """A synthesised function generator: the design, its branches, and its errors at the given inputs.

    ``design`` holds every parameter (free and fixed); ``generated`` the output at each input
    from the linkage's own generated solver, ``errors`` generated minus wanted (an angle's
    difference wrapped to (-pi, pi]); ``structural_error`` the largest of their sizes;
    ``assembled`` whether the verification passed (assembled at every input, one branch and no
    toggle between them), ``why`` what failed if not; ``evaluations`` the residual evaluations spent.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    linkage: str
    output: str
    design: dict[str, float]
    branches: dict[str, int]
    inputs: tuple[float, ...]
    wanted: tuple[float, ...]
    generated: tuple[float, ...] = ()
    errors: tuple[float, ...] = ()
    structural_error: float = math.nan
    assembled: bool = False
    evaluations: int = 0
    why: str = field(default="", repr=False)
    #: Linkages without a closed form: the unknowns at the first input, the assembly the design is on (the
    #: ``guess`` of :class:`symlink.numeric.solver.NumericSolver`, continued along the inputs in their order); else empty.
    assembly: dict[str, float] = field(default_factory=dict)


def chebyshev_inputs(start: float, end: float, count: int) -> numpy.ndarray:
    """Chebyshev spacing of ``count`` input values in [start, end] (the precision points that keep the error small).

    Parameters
    ----------
    start, end : float
        The interval.
    count : int
        How many values.

    Returns
    -------
    numpy.ndarray
        ``(start + end) / 2 - (end - start) / 2 cos((2k - 1) pi / (2 count))`` for k = 1 .. count.

    Examples
    --------
    >>> import symlink
    >>> [round(float(q), 6) for q in symlink.chebyshev_inputs(0.0, 1.0, 3)]  # (1 - cos 30 deg) / 2, 1/2, ...
    [0.066987, 0.5, 0.933013]
    """
    return chebyshev_points(float(start), float(end), int(count))


def function_values(linkage: Linkage, output: str, values: Mapping[str, float], inputs: ArrayLike,
                    branches: Mapping[str, float] | None = None) -> numpy.ndarray:
    """The ``output`` of a design at each input, from the linkage's generated solver; NaN where not assembled.

    Parameters
    ----------
    linkage : Linkage
        Any linkage with one input.
    output : str
        The output's name.
    values : mapping of str to float
        Every parameter.
    inputs : array_like
        The input values.
    branches : mapping of str to int, optional
        Branch signs (default +1).

    Returns
    -------
    numpy.ndarray
        The output at each input; NaN where not assembled.

    Examples
    --------
    >>> import math, symlink
    >>> values = symlink.function_values(symlink.slider_crank(), "s", {"a": 1.0, "b": 3.0, "offset": 0.0}, [0.0, math.pi])
    >>> [round(float(s), 12) for s in values]  # b + a and b - a
    [4.0, 2.0]
    """
    return solved_outputs(linkage, (output,), values, branches or {}, numpy.asarray(inputs, dtype=float))[output]


class _Problem:
    def __init__(self, linkage: Linkage, output: str, inputs: numpy.ndarray, wanted: numpy.ndarray,
                 bounds: Mapping[str, tuple[float, float]], fixed: Mapping[str, float]) -> None:
        self.linkage, self.output, self.inputs, self.wanted = linkage, output, inputs, wanted
        self.angle = is_angle_output(linkage, output)
        self.unit = 1.0 if self.angle else max(float(numpy.max(numpy.abs(wanted))), float(numpy.ptp(wanted)), 1e-300)
        self.free = tuple(bounds)
        self.bounds = numpy.array([bounds[name] for name in self.free], dtype=float).reshape(len(self.free), 2)
        positive = {p.name for p in linkage.parameters if p.is_positive}
        self.positive = numpy.array([name in positive for name in self.free], dtype=bool)
        self.outputs = DesignOutputs(linkage, (output,), self.free, fixed)
        self.fixed = dict(fixed)

    def error(self, generated: numpy.ndarray) -> numpy.ndarray:
        difference = generated - self.wanted
        return wrap(difference) if self.angle else difference

    def residuals(self, x: numpy.ndarray, branches: Mapping[str, float], weights: numpy.ndarray | None = None):
        if not inside(x, self.bounds, self.positive):
            return None
        values, slopes, ok = self.outputs.at(x, self.inputs, branches)
        if not numpy.all(ok):
            return None
        scale = (1.0 if weights is None else numpy.sqrt(weights)) / self.unit
        return self.error(values[0]) * scale, slopes[0, :len(self.free)].T * numpy.reshape(scale, (-1, 1))

    def design(self, x: numpy.ndarray) -> dict[str, float]:
        return {**self.fixed, **{name: float(v) for name, v in zip(self.free, x)}}


def _freudenstein_start(problem: _Problem, given: Mapping[str, float]):
    """Freudenstein's least-squares four-bar (rows of free values, branch) where the linkage is the catalog four-bar."""
    from .function import least_squares_design, three_point_design
    linkage = problem.linkage
    if (linkage.name != "fourbar" or [p.name for p in linkage.parameters] != ["a", "b", "c", "d"]
            or problem.output not in ("phi", "rocker") or len(problem.inputs) < 3):
        return []
    ground = given.get("d", problem.fixed.get("d"))
    if ground is None:
        ground = float(numpy.mean(problem.bounds[problem.free.index("d")]))
    try:
        method = three_point_design if len(problem.inputs) == 3 else least_squares_design
        found = method(problem.inputs, problem.wanted, ground=ground)
    except ValueError:
        return []
    if found.crank_offset or found.rocker_offset:
        return []
    lengths = {"a": found.crank, "b": found.coupler, "c": found.rocker, "d": found.ground}
    row = [lengths.get(name, given.get(name, float(numpy.mean(bound)))) for name, bound in
           zip(problem.free, problem.bounds)]
    return [(row, {"branch": found.branch})]


def synthesize_function(linkage: Linkage, output: str, inputs: ArrayLike, wanted: ArrayLike,
                        free: Mapping[str, tuple[float, float]], *, values: Mapping[str, float] | None = None,
                        branches: Mapping[str, int] | None = None, starts: int = 8, seed: int | None = 0,
                        evaluations: int = 400, tolerance: float = 1e-15, minimax: bool = False) -> FunctionSynthesis:
    """A design of ``linkage`` whose ``output`` takes the ``wanted`` values at the ``inputs``, verified.

    ``output`` is an output name of the linkage (an angle, such as ``"psi"`` or a role, or a
    length, such as a slider's ``"s"``); angles in radians.  ``free`` maps each parameter that may
    change to its bounds ``(low, high)``; ``values`` gives every other parameter (and, if it gives
    free ones too, that design is the first start).  ``branches`` fixes branch signs by name
    (default: tried both ways across the starts).  The ``starts`` closest of the sampled feasible
    designs are refined with at most ``evaluations`` residual evaluations each; the search stops at
    the first verified design whose error is below 1e-12 of the output's unit.  ``minimax``: the
    best least-squares design is then re-weighted (Lawson: each point's weight times its error)
    towards the smallest largest error, the structural error a function generator is judged by,
    where no design meets every point (more points than free parameters).  Returns the best
    verified design, or the closest one with ``assembled`` False and its reason; ``ValueError`` for
    bad input or when no sampled design is assembled at every input.

    Parameters
    ----------
    linkage : Linkage
        Any linkage with one input.
    output : str
        The output to shape: an angle (radians) or a length.
    inputs : array_like
        The input values (the precision points).
    wanted : array_like
        The output's values wanted there.
    free : mapping of str to (float, float)
        Each parameter that may change, and its bounds.
    values : mapping of str to float, optional
        Every other parameter.
    branches : mapping of str to int, optional
        Branch signs to keep (default: tried both ways).
    starts : int, optional
        How many sampled designs are refined (default 8).
    seed : int or None, optional
        The sampling's seed (default 0).
    evaluations : int, optional
        Residual evaluations a refinement may take (default 400).
    tolerance : float, optional
        The refinement's step tolerance.
    minimax : bool, optional
        Re-weight the least-squares design towards the smallest largest error (default False).

    Returns
    -------
    FunctionSynthesis
        The best verified design (``design``, ``structural_error``, ...), or the closest with ``assembled`` False.

    Raises
    ------
    ValueError
        For bad input, or when no sampled design is assembled at every input.

    Examples
    --------
    >>> import symlink
    >>> inputs = symlink.chebyshev_inputs(0.2, 2.8, 6)
    >>> wanted = symlink.function_values(symlink.slider_crank(), "s", {"a": 1.3, "b": 4.1, "offset": 0.7}, inputs)
    >>> found = symlink.synthesize_function(symlink.slider_crank(), "s", inputs, wanted,
    ...                                     {"a": (0.5, 2.0), "b": (3.0, 5.0)}, values={"offset": 0.7})
    >>> found.assembled, found.structural_error < 1e-12, round(found.design["a"], 9), round(found.design["b"], 9)
    (True, True, 1.3, 4.1)
    """
    check_linkage(linkage, "function generation", newton=True)
    is_angle_output(linkage, output)  # ValueError naming the outputs there are
    if linkage.output(output) == linkage.inputs[0]:
        raise ValueError(f"the output {output!r} is the input itself; name an output the linkage moves")
    q = numpy.asarray(inputs, dtype=float)
    y = numpy.asarray(wanted, dtype=float)
    if q.ndim != 1 or q.shape != y.shape or len(q) < 1:
        raise ValueError(f"the inputs and the wanted values must be two lists of the same length, got shapes "
                         f"{q.shape} and {y.shape}")
    if not (numpy.all(numpy.isfinite(q)) and numpy.all(numpy.isfinite(y))):
        raise ValueError("the inputs and the wanted values must be finite numbers")
    check_function_targets(q, y)
    bounds, fixed = free_bounds(linkage, free, {k: v for k, v in (values or {}).items() if k not in free})
    chosen = check_branches(linkage, branches)
    check_starts(starts, evaluations, sample_count(linkage) + 2)  # the user's design and a closed form's besides
    problem = _Problem(linkage, output, q, y, bounds, fixed)
    given = {k: float(v) for k, v in (values or {}).items()}
    first = _freudenstein_start(problem, given)
    if all(name in given for name in problem.free):
        first.insert(0, ([given[name] for name in problem.free], chosen))
    rng = numpy.random.default_rng(seed)
    rows, signs = sampled_designs(linkage, bounds, rng, sample_count(linkage), chosen, first)
    found, ok = problem.outputs.batch(rows, signs, q)
    with numpy.errstate(all="ignore"):
        rms = numpy.sqrt(numpy.mean((problem.error(found[0]) / problem.unit) ** 2, axis=1))
    rms = numpy.where(numpy.all(ok, axis=1), rms, numpy.inf)
    rms[:len(first)] = numpy.where(numpy.isfinite(rms[:len(first)]), -1.0, numpy.inf)  # given starts go first
    order = [k for k in numpy.argsort(rms, kind="stable") if math.isfinite(rms[k])][:starts]
    if not order:
        raise ValueError(f"no design of {linkage.name} within the bounds is assembled at every input; widen the "
                         "bounds or change the fixed values")
    best: FunctionSynthesis | None = None
    spent = 0
    for k in order:
        sign = signs[k]
        problem.outputs.assembly = dict(sign) if problem.outputs.newton else None  # continued by the refinement
        result = refine(lambda x: problem.residuals(x, sign), rows[k], evaluations, tolerance)
        if result is None:
            continue
        x, _, used = result
        spent += used
        candidate = _verified(problem, x, sign, spent)
        if best is None or (candidate.assembled, -candidate.structural_error) > (best.assembled,
                                                                                 -best.structural_error):
            best = candidate
        if best.assembled and best.structural_error < _DONE * problem.unit:
            break
    if best is None:
        raise ValueError("no start could be refined")
    if minimax and best.assembled and best.structural_error >= _DONE * problem.unit:
        best, spent = _minimax(problem, best, spent)
    return FunctionSynthesis(**{**best.__dict__, "evaluations": spent})


def _minimax(problem: _Problem, best: FunctionSynthesis, spent: int) -> tuple[FunctionSynthesis, int]:
    """Lawson's re-weighted least squares from the least-squares design: the smallest largest error found."""
    x = numpy.array([best.design[name] for name in problem.free])
    start = best.assembly or best.branches
    problem.outputs.assembly = dict(best.assembly) if problem.outputs.newton else None
    weights = numpy.full(len(problem.inputs), 1.0 / len(problem.inputs))
    for _ in range(_LAWSON_STEPS):
        found = problem.residuals(x, start)
        if found is None:
            break
        errors = numpy.abs(found[0])
        if not numpy.sum(weights * errors) > 0:
            break
        weights = weights * errors / numpy.sum(weights * errors)
        result = refine(lambda y: problem.residuals(y, start, weights), x, _LAWSON_EVALUATIONS, 1e-15)
        if result is None:
            break
        x, _, used = result
        spent += used
        candidate = _verified(problem, x, start, spent)
        if candidate.assembled and candidate.structural_error < best.structural_error:
            best = candidate
    return best, spent


def _verified(problem: _Problem, x: numpy.ndarray, branches: Mapping[str, float], evaluations: int) -> FunctionSynthesis:
    design = problem.design(x)
    newton = problem.outputs.newton
    assembly: dict[str, float] = {}
    if newton:  # the assembly the refinement continued, found again at x: its unknowns at the first input
        problem.outputs.at(x, problem.inputs, branches)
        assembly = dict(problem.outputs.assembly or branches)
        branches = assembly
    generated = function_values(problem.linkage, problem.output, design, problem.inputs, branches)
    errors = problem.error(generated)
    why = "not assembled at every input" if not numpy.all(numpy.isfinite(errors)) else ""
    if not why:
        # without a closed form the assembly is continued along the inputs in their order, from the first
        order = numpy.arange(len(problem.inputs)) if newton else numpy.argsort(problem.inputs, kind="stable")
        why = branch_break(problem.linkage, design, branches, problem.inputs[order])
    return FunctionSynthesis(problem.linkage.name, problem.output, design, {} if newton else {k: int(v) for k, v in branches.items()},
                             tuple(map(float, problem.inputs)), tuple(map(float, problem.wanted)),
                             tuple(map(float, generated)), tuple(map(float, errors)),
                             float(numpy.max(numpy.abs(errors))) if not why else math.inf, not why, evaluations, why,
                             assembly)
