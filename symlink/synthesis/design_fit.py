"""Outputs of any linkage's design and their exact Jacobian: what function and motion generation share.

Function generation (:mod:`symlink.synthesis.general_function`) and motion generation
(:mod:`symlink.synthesis.general_motion`) for any one-input linkage with a closed form both fit
some position outputs (an output angle, a slider's travel, a link's point and angle) at many input
values by moving chosen parameters, with the exact Jacobian.  :class:`DesignOutputs` gives the
outputs and their derivatives by the free parameters *and by the input* (for poses whose input
values are unknowns too), from the generated sensitivities of the linkage with its input shifted
by a phase (the trick of :mod:`symlink.synthesis.general`: held at zero, d/d(phase) is d/d(input)),
for one design or a batch of sampled designs at once.  :func:`sampled_designs` draws the random
feasible starts, :func:`free_bounds` checks what the user made free, :func:`branch_break` verifies
with the linkage's own generated solver that the input moves between targets on one branch, and
:func:`refine` is the accelerated Levenberg-Marquardt of path synthesis.

>>> from symlink.mechanism.catalog import slider_crank
>>> outputs = DesignOutputs(slider_crank(), ("s",), ("a",), {"b": 3.0, "offset": 0.0})
>>> values, slopes, ok = outputs.at(numpy.array([1.0]), numpy.array([0.0]), {"branch": 1})
>>> float(values[0, 0]), float(slopes[0, 0, 0]), bool(ok[0])  # s = a + b at theta = 0; ds/da = 1
(4.0, 1.0, True)
"""
from __future__ import annotations

import math
from functools import lru_cache
from typing import Callable, Mapping, Sequence

import numpy
import sympy as sp

from ..symbolic.closure import is_angle
from ..numeric.design_jacobian import DesignJacobian
from ..symbolic.linkage import Linkage
from ..symbolic.loops import Loop
from ..numeric.solver import NumericSolver, Solver, settled
from ..symbolic.vectors import Vector, VectorSum
from .path import _accelerated_levenberg_marquardt

__all__ = ["DesignOutputs", "free_bounds", "sampled_designs", "branch_break", "refine", "is_angle_output",
           "solved_outputs", "sample_count", "SAMPLED", "BRANCH_SAMPLES"]

#: Random designs drawn for the starts.
SAMPLED = 1000
#: Input values checked between consecutive targets by the verification.
BRANCH_SAMPLES = 24
#: Without a closed form: random initial guesses tried for the assembly of each sampled design ...
NEWTON_GUESSES = 4
#: ... and the designs sampled (each solved by Newton's method, not by one vectorised call).
NEWTON_SAMPLED = 120


def sample_count(linkage: Linkage) -> int:
    """How many random designs to draw for the starts: :data:`SAMPLED`, or :data:`NEWTON_SAMPLED` without a closed form."""
    return SAMPLED if linkage.has_closed_form else NEWTON_SAMPLED


#: The parameter added to the input in the Jacobian's copy of the linkage (:func:`with_input_phase`).
INPUT_PHASE = "input_phase"


def _shifted(expr: sp.Expr, input_symbol: sp.Symbol, phase: sp.Symbol) -> sp.Expr:
    return sp.sympify(expr).xreplace({input_symbol: input_symbol + phase})


def _shifted_sum(vectors: Vector | VectorSum | None, input_symbol: sp.Symbol, phase: sp.Symbol):
    if vectors is None:
        return None
    return VectorSum(tuple((sign, Vector(_shifted(v.length, input_symbol, phase),
                                         _shifted(v.angle, input_symbol, phase), v.name))
                           for sign, v in vectors.as_sum().terms))


@lru_cache(maxsize=32)
def with_input_phase(linkage: Linkage) -> Linkage:
    """The linkage with its input ``q`` replaced by ``q + input_phase``: d/d(input_phase) at 0 is d/dq."""
    (input_symbol,) = linkage.inputs
    phase = sp.Symbol(INPUT_PHASE, real=True)
    taken = {s.name for s in linkage.parameters + linkage.coordinates}
    if INPUT_PHASE in taken:
        raise ValueError(f"{linkage.name} already has a symbol named {INPUT_PHASE!r}, which path synthesis needs")
    loops = [Loop(_shifted_sum(loop.vectors, input_symbol, phase), name=loop.name) for loop in linkage.loops]
    return Linkage(f"{linkage.name}with_input_phase", loops, inputs=[input_symbol], unknowns=list(linkage.unknowns),
                   parameters=list(linkage.parameters) + [phase],
                   points={k: _shifted_sum(v, input_symbol, phase) for k, v in linkage.points.items()},
                   roles=dict(linkage.roles),
                   extras={k: _shifted(v, input_symbol, phase) for k, v in linkage.extras.items()})


@lru_cache(maxsize=32)
def _jacobian(linkage: Linkage, outputs: tuple[str, ...], free: tuple[str, ...]) -> DesignJacobian:
    return DesignJacobian(with_input_phase(linkage), list(outputs), list(free) + [INPUT_PHASE])


@lru_cache(maxsize=32)
def _solver(linkage: Linkage, outputs: tuple[str, ...]) -> Solver:
    return settled(Solver(linkage, list(outputs)))  # one backend for a whole search: seeded runs repeat exactly


#: Random initial guesses tried by :func:`find_assembly` before it gives up.
_ASSEMBLY_GUESSES = 12


def find_assembly(linkage: Linkage, values: Mapping[str, float], at: float, rng: numpy.random.Generator,
                  tries: int = _ASSEMBLY_GUESSES) -> dict[str, float] | None:
    """An assembly of a linkage without a closed form at input ``at``: its unknowns, or None if none is found.

    Newton's method of the linkage's numeric solver from random initial guesses (angles over a
    turn, lengths within the sum of the parameters), the first that closes; which assembly
    that is depends on ``rng``.  (The same search as the drawing's, which synthesis may not import.)

    >>> from symlink.mechanism.catalog import stephenson2, EXAMPLE_VALUES
    >>> found = find_assembly(stephenson2(), EXAMPLE_VALUES["stephenson2"], 0.0, numpy.random.default_rng(0))
    >>> sorted(found)
    ['beta', 'eta', 'mu', 'phi']
    """
    solver = _newton_solver(linkage)
    parameters = {p.name: float(values[p.name]) for p in linkage.parameters}
    scale = sum(abs(v) for v in parameters.values()) or 1.0
    for _ in range(tries):
        guess = {q.name: float(rng.uniform(-math.pi, math.pi)) if is_angle(linkage, q)
                 else float(rng.uniform(-scale, scale)) for q in linkage.unknowns}
        try:
            with numpy.errstate(all="ignore"):
                solved = solver(guess=guess, **parameters, **{linkage.inputs[0].name: numpy.array([float(at)])})
        except ValueError:
            continue
        return {q.name: float(numpy.asarray(solved[q.name])[0]) for q in linkage.unknowns}
    return None


@lru_cache(maxsize=32)
def _newton_solver(linkage: Linkage) -> NumericSolver:
    return settled(NumericSolver(linkage))


def is_angle_output(linkage: Linkage, name: str) -> bool:
    """Whether the output ``name`` of ``linkage`` is an angle (it turns a vector), not a length or a point's coordinate.

    >>> from symlink.mechanism.catalog import slider_crank
    >>> [is_angle_output(slider_crank(), name) for name in ("conrod", "slider", "B_x")]
    [True, False, False]
    """
    expr = linkage.output(name)  # ValueError naming the outputs there are
    return isinstance(expr, sp.Symbol) and expr in linkage.coordinates and is_angle(linkage, expr)


def free_bounds(linkage: Linkage, free: Mapping[str, tuple[float, float]],
                values: Mapping[str, float] | None) -> tuple[dict[str, tuple[float, float]], dict[str, float]]:
    """The free parameters' bounds (checked) and the values of the fixed ones; ``ValueError`` naming a problem."""
    known = [p.name for p in linkage.parameters]
    if not free:
        raise ValueError("name at least one free parameter with its bounds")
    bounds = {}
    for name, bound in free.items():
        if name not in known:
            raise ValueError(f"{linkage.name} has no parameter {name!r}; it has {', '.join(known)}")
        try:
            low, high = (float(b) for b in bound)
        except (TypeError, ValueError):
            raise ValueError(f"the bounds of {name!r} are two numbers (low, high), got {bound!r}") from None
        if not (math.isfinite(low) and math.isfinite(high) and low < high):
            raise ValueError(f"the bounds of {name!r} must be finite with low < high, got {bound!r}")
        bounds[name] = (low, high)
    given = {k: float(v) for k, v in (values or {}).items()}
    unknown = sorted(set(given) - set(known))
    if unknown:
        raise ValueError(f"{linkage.name} has no parameter {unknown[0]!r}; it has {', '.join(known)}")
    if not all(math.isfinite(v) for v in given.values()):
        raise ValueError("the given values must be finite numbers")
    missing = [name for name in known if name not in free and name not in given]
    if missing:
        raise ValueError(f"give values for the parameters that are not free: {', '.join(missing)}")
    return bounds, {name: given[name] for name in known if name not in free}


def check_branches(linkage: Linkage, branches: Mapping[str, int] | None) -> dict[str, int]:
    """The branch signs a user fixed, checked: names of the linkage's branches, each +1 or -1."""
    names = {s.name for s in linkage.branches}
    for name, sign in (branches or {}).items():
        if name not in names or sign not in (1, -1):
            raise ValueError(f"branches maps {', '.join(sorted(names)) or 'no branch'} to +1 or -1; "
                             f"got {name!r}: {sign!r}")
    return {k: int(v) for k, v in (branches or {}).items()}


def check_linkage(linkage: Linkage, what: str, newton: bool = False) -> None:
    """``ValueError`` unless ``linkage`` has one input and a closed form (or ``newton``: may be solved by Newton)."""
    if len(linkage.inputs) != 1:
        raise ValueError(f"{what} drives one input; {linkage.name} has {len(linkage.inputs)}")
    if not linkage.has_closed_form and not newton:
        raise ValueError(f"{linkage.name} has no closed form; {what} of Newton-solved linkages is not supported yet")


class DesignOutputs:
    """Outputs of ``linkage`` and their exact derivatives by the ``free`` parameters and by the input.

    ``fixed`` holds the values of every other parameter.  :meth:`at` evaluates one design,
    :meth:`batch` many at once; both give the derivative by the input as the last column.

    A linkage without a closed form has no branch signs: where the others take ``branches``,
    it takes its assembly (the unknowns near it at the first input, Newton's initial guess).
    :meth:`at` continues :attr:`assembly` (the unknowns at the first input of its last
    converged call) when it is set, so that a refinement carries its start's assembly along;
    :meth:`batch` finds each design's assembly by :func:`find_assembly`
    and writes it into that design's entry of ``signs``.
    """

    def __init__(self, linkage: Linkage, outputs: Sequence[str], free: Sequence[str],
                 fixed: Mapping[str, float]) -> None:
        self.linkage = linkage
        self.outputs = tuple(outputs)
        self.free = tuple(free)
        self.fixed = dict(fixed)
        self.newton = not linkage.has_closed_form
        self.unknown_names = tuple(q.name for q in linkage.unknowns) if self.newton else ()
        #: Without a closed form: the unknowns at the first input of the last converged :meth:`at`, or None.
        self.assembly: dict[str, float] | None = None
        self.jacobian = _jacobian(linkage, self.outputs + tuple(n for n in self.unknown_names if n not in self.outputs),
                                  self.free)
        self.input = linkage.inputs[0].name
        self.branch_names = [s.name for s in linkage.branches]

    def _newton_at(self, free: numpy.ndarray, inputs: numpy.ndarray, start: Mapping[str, float]):
        inputs = numpy.atleast_1d(numpy.asarray(inputs, dtype=float))
        count, width = len(inputs), len(self.free) + 1
        given = {**self.fixed, **{name: float(v) for name, v in zip(self.free, free)}, INPUT_PHASE: 0.0,
                 self.input: inputs}
        try:
            with numpy.errstate(all="ignore"):
                found, slopes = self.jacobian(guess=dict(self.assembly if self.assembly is not None else start),
                                              **given)
        except ValueError:
            return (numpy.full((len(self.outputs), count), numpy.nan),
                    numpy.full((len(self.outputs), width, count), numpy.nan), numpy.zeros(count, dtype=bool))
        values = numpy.stack([numpy.asarray(found[name], dtype=float) for name in self.outputs])
        jac = numpy.moveaxis(numpy.asarray(slopes[:, :len(self.outputs), :], dtype=float), 0, -1)
        ok = (numpy.asarray(found["assembled"], dtype=bool) & numpy.all(numpy.isfinite(values), axis=0)
              & numpy.all(numpy.isfinite(jac), axis=(0, 1)))
        if numpy.all(ok):
            self.assembly = {name: float(numpy.asarray(found[name])[0]) for name in self.unknown_names}
        return values, jac, ok

    def _call(self, given: dict, shape: tuple[int, ...]):
        arguments = [numpy.broadcast_to(numpy.asarray(given[name], dtype=float), shape)
                     for name in self.jacobian.arguments]
        with numpy.errstate(all="ignore"):
            values, slopes, assembled = self.jacobian.arrays(*arguments)
        values = numpy.broadcast_to(values, values.shape[:1] + shape)
        slopes = numpy.broadcast_to(slopes, slopes.shape[:2] + shape)
        ok = (numpy.broadcast_to(assembled, shape) & numpy.all(numpy.isfinite(values), axis=0)
              & numpy.all(numpy.isfinite(slopes), axis=(0, 1)))
        return values, slopes, ok

    def at(self, free: numpy.ndarray, inputs: numpy.ndarray, branches: Mapping[str, float]):
        """``(values (outputs, N), slopes (outputs, free + 1, N), ok (N))`` of one design at the ``inputs``.

        ``ok`` is False where the design is not assembled or at a toggle (a derivative is no number).
        """
        if self.newton:
            return self._newton_at(free, inputs, branches)
        given: dict[str, object] = {**self.fixed, INPUT_PHASE: 0.0, self.input: inputs,
                                    **{name: float(branches.get(name, 1)) for name in self.branch_names}}
        given.update({name: float(v) for name, v in zip(self.free, free)})
        return self._call(given, numpy.shape(inputs))

    def batch(self, rows: numpy.ndarray, signs: Sequence[Mapping[str, int]], inputs: numpy.ndarray):
        """Many designs (rows of free values, their branch signs) at the same inputs: values (outputs, M, N), ok (M, N)."""
        if self.newton:
            rng = numpy.random.default_rng(len(rows))
            values = numpy.full((len(self.outputs), len(rows), len(inputs)), numpy.nan)
            ok = numpy.zeros((len(rows), len(inputs)), dtype=bool)
            for k, row in enumerate(rows):
                design = {**self.fixed, **{name: float(v) for name, v in zip(self.free, row)}}
                start = (dict(signs[k]) if set(signs[k]) == set(self.unknown_names)
                         else find_assembly(self.linkage, design, float(inputs[0]), rng, NEWTON_GUESSES))
                if start is None:
                    continue
                self.assembly = None
                values[:, k], _, ok[k] = self._newton_at(row, inputs, start)
                if numpy.all(ok[k]) and self.assembly is not None:
                    signs[k].clear()
                    signs[k].update(self.assembly)
            self.assembly = None
            return values, ok
        given: dict[str, object] = {**self.fixed, INPUT_PHASE: 0.0, self.input: inputs[None, :]}
        for k, name in enumerate(self.free):
            given[name] = rows[:, k:k + 1]
        for name in self.branch_names:
            given[name] = numpy.array([[float(sign[name])] for sign in signs])
        values, _, ok = self._call(given, (len(rows), len(inputs)))
        return values, ok


def sampled_designs(linkage: Linkage, bounds: Mapping[str, tuple[float, float]], rng: numpy.random.Generator,
                    count: int, branch_choice: Mapping[str, int],
                    first: Sequence[tuple[Sequence[float], Mapping[str, int]]] = ()):
    """Rows of free values uniform within the ``bounds`` (after the ``first`` designs given), with branch signs.

    Branch signs are random unless ``branch_choice`` fixes them.
    """
    names = [s.name for s in linkage.branches]
    low = numpy.array([b[0] for b in bounds.values()])
    high = numpy.array([b[1] for b in bounds.values()])
    rows = [list(row) for row, _ in first]
    signs = [{n: int(branch_choice.get(n, sign.get(n, 1))) for n in names} for _, sign in first]
    for _ in range(count):
        rows.append(list(rng.uniform(low, high)))
        signs.append({n: int(branch_choice[n]) if n in branch_choice else int(rng.choice([-1, 1])) for n in names})
    return numpy.array(rows, dtype=float).reshape(len(rows), len(bounds)), signs


def inside(x: numpy.ndarray, bounds: numpy.ndarray, positive: numpy.ndarray) -> bool:
    """Whether the free values ``x`` lie within their ``bounds`` (rows low, high) and the positive ones above 0."""
    return bool(numpy.all(numpy.isfinite(x)) and numpy.all((x >= bounds[:, 0]) & (x <= bounds[:, 1]))
                and numpy.all(x[positive] > 0))


def solved_outputs(linkage: Linkage, outputs: Sequence[str], design: Mapping[str, float],
                   branches: Mapping[str, float], inputs: numpy.ndarray) -> dict[str, numpy.ndarray]:
    """The outputs at the inputs from the linkage's own generated solver (not the Jacobian's code); NaN where not assembled."""
    if not linkage.has_closed_form:  # Newton's method continued along the inputs from the assembly ``branches``
        swept = numpy.atleast_1d(numpy.asarray(inputs, dtype=float))
        try:
            with numpy.errstate(all="ignore"):
                found = _newton_solver(linkage)(guess=dict(branches), **design, **{linkage.inputs[0].name: swept})
        except ValueError:
            return {name: numpy.full(swept.shape, numpy.nan) for name in outputs}
        return {name: numpy.asarray(found[name], dtype=float) for name in outputs}
    arguments: dict[str, object] = {**design, linkage.inputs[0].name: numpy.asarray(inputs, dtype=float)}
    arguments.update({s.name: int(branches.get(s.name, 1)) for s in linkage.branches})
    solved = _solver(linkage, tuple(outputs))(**arguments)
    ok = numpy.asarray(solved["assembled"])
    return {name: numpy.where(ok, numpy.asarray(solved[name], dtype=float), numpy.nan) for name in outputs}


def branch_break(linkage: Linkage, design: Mapping[str, float], branches: Mapping[str, float],
                 inputs: numpy.ndarray) -> str:
    """Why the input cannot move from target to target on one branch ("" if it can), by the generated solver.

    Between consecutive inputs the linkage must stay assembled and off a toggle (checked at
    :data:`BRANCH_SAMPLES` values), so that all the targets are reached on one branch.
    """
    steps = numpy.linspace(0.0, 1.0, BRANCH_SAMPLES + 1)
    if len(inputs) < 2:
        moves = numpy.asarray(inputs, dtype=float)[:, None]
    else:
        moves = inputs[:-1, None] + numpy.diff(inputs)[:, None] * steps[None, :]
    if not linkage.has_closed_form:  # Newton's method continued from the assembly ``branches`` at inputs[0]
        try:
            with numpy.errstate(all="ignore"):
                _newton_solver(linkage)(guess=dict(branches), **design, **{linkage.inputs[0].name: moves.ravel()})
        except ValueError as error:
            return f"the input cannot move along the targets on one assembly: {error}"
        return ""
    arguments: dict[str, object] = {**design, linkage.inputs[0].name: moves}
    arguments.update({s.name: int(branches.get(s.name, 1)) for s in linkage.branches})
    solved = _solver(linkage, ("singular",))(**arguments)
    ok = numpy.asarray(solved["assembled"]) & ~numpy.asarray(solved["singular"], dtype=bool)
    if numpy.all(ok):
        return ""
    where = numpy.argwhere(~ok)[0]
    return (f"the input cannot move from target {where[0] + 1} to target {where[0] + 2} on one branch "
            f"(no assembly or a toggle at {float(moves[tuple(where)]):.6g})")


def refine(residuals: Callable[[numpy.ndarray], tuple[numpy.ndarray, numpy.ndarray] | None], x0: numpy.ndarray,
           evaluations: int, tolerance: float):
    """``(x, cost, evaluations)`` from the accelerated Levenberg-Marquardt of path synthesis, None if x0 is infeasible.

    ``residuals(x)`` gives ``(r, J)``, or None for an infeasible ``x`` (never accepted).
    """
    return _accelerated_levenberg_marquardt(residuals, numpy.asarray(x0, dtype=float).copy(), evaluations, tolerance)


#: Batched assembly search: Newton iterations from each random guess, and the residual (over the loop size) that
#: counts as closed ...
_BATCH_ASSEMBLY_ITERATIONS = 40
_BATCH_RESIDUAL = 1e-10
#: ... and along the sweep: Newton iterations a step, the largest first correction after the predictor (rad, or
#: link lengths) and the singularity past which a position is a dead centre (Hadamard's ratio below its inverse).
_BATCH_STEP_ITERATIONS = 8
_BATCH_MAX_CORRECTION = 0.1
_BATCH_SINGULAR = 1e10


def _batch_closure(functions, theta, parameters: Sequence[numpy.ndarray], q: numpy.ndarray, checked: bool = False):
    """Residuals over the loop size (M), Newton step (M, n), regular (M) and Jacobian (M, n, n) at ``q`` (M, n).

    ``checked``: regular means the (scaled) Jacobian's Hadamard ratio (|det| over the product of its
    column norms: 1 for orthogonal columns, 0 at a dead centre) above 1 / :data:`_BATCH_SINGULAR`;
    else only a finite step.  Where not regular the step is NaN.
    """
    F, J, scale, unit = functions["_closure"](theta, *parameters, *numpy.moveaxis(q, -1, 0))
    F, J = numpy.broadcast_to(F, q.shape), numpy.broadcast_to(J, q.shape + (q.shape[-1],))
    scale = numpy.broadcast_to(scale, q.shape)
    unit = numpy.broadcast_to(unit, q.shape)
    with numpy.errstate(all="ignore"):
        residual = numpy.max(numpy.abs(F) / scale, axis=-1)
        regular = numpy.all(numpy.isfinite(J), axis=(1, 2)) & numpy.all(numpy.isfinite(F), axis=1)
        if checked:  # Hadamard's ratio |det| / product of the column norms (an LU, not an SVD, a design)
            scaled = numpy.where(regular[:, None, None], J, 1.0) * unit[..., None, :] / scale[..., :, None]
            ratio = numpy.abs(numpy.linalg.det(scaled)) / numpy.prod(numpy.linalg.norm(scaled, axis=-2), axis=-1)
            regular &= numpy.isfinite(ratio) & (ratio > 1.0 / _BATCH_SINGULAR)
        safe = numpy.where(regular[:, None, None], J, numpy.eye(q.shape[-1]))
        try:
            step = -numpy.linalg.solve(safe, numpy.where(regular[:, None], F, 0.0)[..., None])[..., 0]
        except numpy.linalg.LinAlgError:  # an exactly singular matrix among them: one at a time
            step = numpy.full(q.shape, numpy.nan)
            for k in numpy.flatnonzero(regular):
                try:
                    step[k] = -numpy.linalg.solve(safe[k], F[k])
                except numpy.linalg.LinAlgError:
                    regular[k] = False
    step = numpy.where(regular[:, None], step, numpy.nan)
    return residual, step, regular & numpy.all(numpy.isfinite(step), axis=1), safe


def newton_traced_batch(linkage: Linkage, designs: Mapping[str, float | numpy.ndarray], sweep: numpy.ndarray,
                        rng: numpy.random.Generator, guesses: int = 8,
                        starts: numpy.ndarray | None = None) -> tuple[numpy.ndarray, numpy.ndarray]:
    """Many designs of a linkage without a closed form continued along one input ``sweep`` at once.

    ``designs`` maps every parameter to a number or an array (M,), one entry a design.  Each
    design is assembled at ``sweep[0]`` from ``starts`` (M, unknowns; NaN rows: none) or else
    the first of ``guesses`` random initial guesses (angles over a turn, lengths within the sum of
    the parameters) from which Newton's method closes, then continued value by value: a
    first-order predictor along the unknowns' rates (the closure's velocity system), then at most
    a few Newton corrections, the first no larger than a tenth of a radian (so that a step does not
    jump to another assembly) and each further one smaller, all designs in one vectorised
    evaluation of the generated closure.  A design stops where a step does not converge or meets a
    dead centre (the scaled Jacobian's Hadamard ratio under 1e-10): nothing after is assembled.  The same method as
    :class:`~symlink.numeric.solver.NumericSolver`'s continuation, but over the designs, not along one.

    Returns ``(unknowns (M, N, n), assembled (M, N))``: the unknowns in the linkage's order, NaN where
    not assembled.

    >>> from symlink.mechanism.catalog import stephenson2, EXAMPLE_VALUES
    >>> values = dict(EXAMPLE_VALUES["stephenson2"])
    >>> values["d"] = numpy.array([values["d"], 100.0])  # the second's ground is longer than its other links
    >>> near = numpy.array([[0.96, 0.27, 1.43, -0.16]] * 2)  # beta, mu, phi, eta near the assembly whose crank turns
    >>> unknowns, assembled = newton_traced_batch(stephenson2(), values, numpy.linspace(0.0, 2 * numpy.pi, 97),
    ...                                           numpy.random.default_rng(0), starts=near)
    >>> assembled.all(axis=1).tolist(), round(float(unknowns[0, -1, 0] - unknowns[0, 0, 0]), 9)  # beta back after a turn
    ([True, False], 0.0)
    """
    functions = _newton_solver(linkage).functions
    # the generated module's order of the parameters and unknowns (the linkage's, checked here)
    assert tuple(functions["UNKNOWNS"]) == tuple(u.name for u in linkage.unknowns)
    arrays = [numpy.atleast_1d(numpy.asarray(designs[name], dtype=float)) for name in functions["PARAMETERS"]]
    count = max(len(a) for a in arrays)
    parameters = [numpy.broadcast_to(a, (count,)) for a in arrays]
    n = len(linkage.unknowns)
    sweep = numpy.asarray(sweep, dtype=float)
    q = numpy.full((count, n), numpy.nan)
    if starts is not None:
        q[:] = starts
    angles = numpy.array([is_angle(linkage, u) for u in linkage.unknowns])
    reach = numpy.sum(numpy.abs(numpy.stack(parameters)), axis=0)
    # assembly at the first input: the given starts, then random guesses for the designs still without one
    for attempt in range(guesses + 1):
        todo = ~numpy.all(numpy.isfinite(q), axis=1) if attempt else numpy.all(numpy.isfinite(q), axis=1)
        if not todo.any():
            continue
        here = q[todo] if attempt == 0 else numpy.where(
            angles, rng.uniform(-math.pi, math.pi, (int(todo.sum()), n)),
            rng.uniform(-1.0, 1.0, (int(todo.sum()), n)) * reach[todo, None])
        sub = [p[todo] for p in parameters]
        for _ in range(_BATCH_ASSEMBLY_ITERATIONS):
            _, step, regular, _ = _batch_closure(functions, sweep[0], sub, here)
            here = here + numpy.where(regular[:, None], step, 0.0)
        residual, _, regular, _ = _batch_closure(functions, sweep[0], sub, here, checked=True)
        closed = (residual < _BATCH_RESIDUAL) & regular
        q[numpy.flatnonzero(todo)[~closed]] = numpy.nan
        q[numpy.flatnonzero(todo)[closed]] = here[closed]
    unknowns = numpy.full((count, len(sweep), n), numpy.nan)
    alive = numpy.all(numpy.isfinite(q), axis=1)
    unknowns[alive, 0] = q[alive]
    rhs = functions["_velocity_rhs"]
    for k in range(1, len(sweep)):
        index = numpy.flatnonzero(alive)
        if not len(index):
            break
        sub = [p[index] for p in parameters]
        current = q[index]
        _, _, _, J = _batch_closure(functions, sweep[k - 1], sub, current)
        with numpy.errstate(all="ignore"):
            rate = numpy.linalg.solve(J, numpy.broadcast_to(
                rhs(sweep[k - 1], *sub, *numpy.moveaxis(current, -1, 0), 1.0), current.shape)[..., None])[..., 0]
        here = current + rate * (sweep[k] - sweep[k - 1])
        ok = numpy.all(numpy.isfinite(here), axis=1)
        limit = numpy.full(len(index), _BATCH_MAX_CORRECTION)
        for _ in range(_BATCH_STEP_ITERATIONS):
            residual, step, regular, _ = _batch_closure(functions, sweep[k], sub, here)
            size = numpy.max(numpy.abs(numpy.where(regular[:, None], step, numpy.inf)), axis=1)
            ok &= (residual < _BATCH_RESIDUAL) | (regular & (size <= limit))
            here = here + numpy.where((ok & regular)[:, None], step, 0.0)
            limit = numpy.maximum(size * 0.5, 1e-12)
            if numpy.all(~ok | (size < 1e-12)):
                break
        residual, _, regular, _ = _batch_closure(functions, sweep[k], sub, here, checked=True)
        ok &= (residual < _BATCH_RESIDUAL) & regular
        alive[index[~ok]] = False
        q[index[ok]] = here[ok]
        unknowns[index[ok], k] = here[ok]
    return unknowns, numpy.all(numpy.isfinite(unknowns), axis=2)
