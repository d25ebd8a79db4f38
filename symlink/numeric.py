"""The numeric fallback: a generated Newton solver on the closure equations.

Where no loop-by-loop closed form exists (the Stephenson III six-bar), the
closure equations of all loops are solved together.  The residuals, their
Jacobian with respect to the unknowns and the right-hand sides of the
velocity and acceleration systems are derived symbolically and printed as
NumPy code (:func:`symlink.codegen.straight_line`, common subexpressions
eliminated); the generated module imports NumPy only.

How the generated solver works:

* The first input value is assembled by damped Newton from an initial
  guess; that assembly fixes the branch for the whole sweep.
* Each further input value continues from the previous one: a second-order
  Taylor predictor (from the same velocity and acceleration systems) and a
  Newton corrector, vectorised over a block of the sweep at once.  A point is
  accepted only if the first correction is small and each further correction
  contracts, so Newton cannot jump to another assembly; otherwise the step is
  split, down to ``MIN_FRACTION`` of an input step.
* Iteration stops when every closure equation is zero to rounding
  (``RESIDUAL_TOLERANCE`` relative to its loop's size).
* Failure to converge and a singular Jacobian (a dead-centre position, where
  the positions do not follow from the input) raise ``ValueError`` naming the
  input value; a wrong configuration is never returned silently.
* Velocities and accelerations solve ``J qdot = r1`` and ``J qddot = r2``
  over the whole sweep with ``numpy.linalg.solve``.

>>> from symlink.catalog import fourbar
>>> solver = fourbar().numeric()
>>> result = solver(theta=[0.0, 0.1], a=20, b=66, c=56, d=80, guess={"beta": 1.0, "phi": 2.0})
>>> [round(float(v), 2) for v in numpy.degrees(result["rocker"])]
[110.74, 108.94]
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy
import sympy as sp

from .codegen import NumPyCodePrinter, load_numpy_module, numpy_module, straight_line
from .linkage import Linkage, Program
from .solver import check_lengths
from .vectors import acceleration, rate, time_derivative

__all__ = ["ClosureSystem", "closure_system", "numeric_module", "numeric_latex", "NumericSolver", "is_angle"]


@dataclass(frozen=True)
class ClosureSystem:
    """The closure of all loops at once, and its linear velocity and acceleration systems.

    ``residuals`` (two a loop) must vanish; ``jacobian`` is their derivative by
    the unknowns; the unknowns' rates solve ``jacobian * qdot = velocity_rhs``
    and their accelerations ``jacobian * qddot = acceleration_rhs``.
    ``scales`` give each equation's size (the sum of its loop's vector
    lengths) and ``units`` each unknown's (1 for an angle, a mean link length
    for a length), so that tolerances are relative.
    """

    linkage: Linkage
    residuals: tuple[sp.Expr, ...]
    jacobian: sp.Matrix
    velocity_rhs: tuple[sp.Expr, ...]
    acceleration_rhs: tuple[sp.Expr, ...]
    scales: tuple[sp.Expr, ...]
    units: tuple[sp.Expr, ...]


def closure_system(linkage: Linkage) -> ClosureSystem:
    """Derive the closure system of ``linkage``; ``ValueError`` unless it has as many equations as unknowns.

    >>> from symlink.catalog import slider_crank
    >>> system = closure_system(slider_crank())
    >>> system.jacobian
    Matrix([
    [-b*sin(beta), -1],
    [ b*cos(beta),  0]])
    """
    unknowns = linkage.unknowns
    if 2 * len(linkage.loops) != len(unknowns):
        raise ValueError(f"{linkage.name}: {len(linkage.loops)} loops give {2 * len(linkage.loops)} equations "
                         f"for {len(unknowns)} unknowns; Newton's method needs as many of each")
    residuals, scales = [], []
    for loop in linkage.loops:
        size = sp.Add(*(sp.Abs(vector.length) for _, vector in loop.terms))
        residuals += list(loop.equations())
        scales += [size, size]
    jacobian = sp.Matrix(residuals).jacobian(unknowns)
    coordinates = linkage.coordinates
    first = [time_derivative(f, coordinates) for f in residuals]
    velocity_rhs = tuple(-f.subs({rate(u): 0 for u in unknowns}) for f in first)
    second = [time_derivative(f, coordinates) for f in first]
    acceleration_rhs = tuple(-f.subs({acceleration(u): 0 for u in unknowns}) for f in second)
    units = []
    for u in unknowns:
        if is_angle(linkage, u):
            units.append(sp.S.One)
        else:
            loop = next(loop for loop in linkage.loops if u in loop.symbols())
            units.append(sp.Add(*(sp.Abs(v.length) for _, v in loop.terms)) / len(loop.terms))
    return ClosureSystem(linkage, tuple(residuals), jacobian, velocity_rhs, acceleration_rhs,
                         tuple(scales), tuple(units))


def _array_function(name: str, arguments: Sequence[sp.Symbol], results: Sequence[tuple[str, object]],
                    doc: str) -> str:
    """Source of a function returning arrays: each result is a list (a vector) or a list of lists (a matrix)."""
    flat: dict[str, sp.Expr] = {}
    for label, value in results:
        if isinstance(value, sp.MatrixBase):
            for i in range(value.rows):
                for j in range(value.cols):
                    flat[f"{label}_{i}_{j}"] = value[i, j]
        else:
            for i, expr in enumerate(value):
                flat[f"{label}_{i}"] = sp.sympify(expr)
    code = straight_line(Program(tuple(arguments), (), flat))
    printer = NumPyCodePrinter()
    lines = [f"def {name}({', '.join(s.name for s in arguments)}):", f'    """{doc}"""']
    lines += [f"    {symbol.name} = {printer.doprint(expr)}" for symbol, expr in code.assignments]
    returned = []
    for label, value in results:
        if isinstance(value, sp.MatrixBase):
            rows = ", ".join("[" + ", ".join(printer.doprint(code.outputs[f"{label}_{i}_{j}"])
                                             for j in range(value.cols)) + "]" for i in range(value.rows))
            returned.append(f"_matrix([{rows}])")
        else:
            returned.append("_stack([" + ", ".join(printer.doprint(code.outputs[f"{label}_{i}"])
                                                   for i in range(len(value))) + "])")
    lines.append("    return " + ", ".join(returned))
    return "\n".join(lines) + "\n"


def _outputs_function(linkage: Linkage, arguments: Sequence[sp.Symbol]) -> tuple[str, list[str]]:
    """Source of ``_outputs``: roles, named points and extras, as expressions of the coordinates."""
    names = [f"{point}_{axis}" for point in linkage.points for axis in "xy"] + list(linkage.extras)
    expressions = [linkage.output(name) for name in names]
    if not names:
        return "def _outputs(*values):\n    return {}\n", []
    code = straight_line(Program(tuple(arguments), (), dict(zip(names, expressions))))
    printer = NumPyCodePrinter()
    lines = [f"def _outputs({', '.join(s.name for s in arguments)}):",
             '    """Named points and extra outputs from the solved coordinates."""']
    lines += [f"    {symbol.name} = {printer.doprint(expr)}" for symbol, expr in code.assignments]
    lines.append("    return {")
    lines += [f"        {name!r}: {printer.doprint(code.outputs[name])}," for name in names]
    lines.append("    }")
    return "\n".join(lines) + "\n", names


_DRIVER = '''
EPSILON = float(numpy.finfo(float).eps)
#: Converged when every closure equation is this small relative to its loop's size.
RESIDUAL_TOLERANCE = 64 * EPSILON
#: A (scaled) Jacobian with a larger condition number is singular: a dead-centre position.
SINGULAR_CONDITION = 1e10
#: Converged also needs the last correction to be this small (rad, or link lengths): near a
#: singular position the residual is at rounding while the position is not yet determined.
POSITION_TOLERANCE = 1e-9
#: Continuation: the largest predicted change and first Newton correction accepted (rad, or
#: link lengths), and the factor by which every further correction must shrink, so that
#: Newton stays on its branch.
MAX_PREDICTION = 0.5
MAX_CORRECTION = 0.1
CONTRACTION = 0.5
MAX_ITERATIONS = 12
ASSEMBLY_ITERATIONS = 100
MIN_FRACTION = 2.0 ** -30
LARGEST_BLOCK = 256


def _stack(items):
    return numpy.stack(numpy.broadcast_arrays(*items), axis=-1)


def _matrix(rows):
    return numpy.stack(numpy.broadcast_arrays(*[_stack(row) for row in rows]), axis=-2)


def _solve(matrices, vectors):
    return numpy.linalg.solve(matrices, vectors[..., None])[..., 0]


def _where(inputs):
    """The input values of one point, for messages."""
    parts = []
    for name, value in zip(INPUTS, inputs):
        value = float(numpy.ravel(value)[0])
        parts.append(f"{name} = {value:.10g} rad ({numpy.degrees(value):.8g} deg)" if name in ANGLE_INPUTS
                     else f"{name} = {value:.10g}")
    return ", ".join(parts)


def _singular(inputs, condition, why=""):
    return ValueError(f"singular Jacobian at {_where(inputs)} (condition {condition:.3g}): a dead-centre "
                      f"position{why}, where the positions do not follow from the input")


def _system(inputs, parameters, q):
    """Residuals, Jacobian, condition numbers and scales at points q (m, n)."""
    F, J, scale, unit = _closure(*inputs, *parameters, *numpy.moveaxis(q, -1, 0))
    scale, unit = numpy.broadcast_to(scale, F.shape), numpy.broadcast_to(unit, F.shape)
    residual = numpy.max(numpy.abs(F) / scale, axis=-1)
    with numpy.errstate(invalid="ignore", divide="ignore"):
        condition = numpy.linalg.cond(J * unit[..., None, :] / scale[..., :, None])
    condition = numpy.where(numpy.isfinite(condition), condition, numpy.inf)
    return F, J, residual, condition, unit


def _rates(inputs, parameters, q, J, input_rates, input_accels):
    """The unknowns' rates and accelerations from the linear systems, over all points at once."""
    qdot = _solve(J, _velocity_rhs(*inputs, *parameters, *numpy.moveaxis(q, -1, 0), *input_rates))
    qddot = _solve(J, _acceleration_rhs(*inputs, *parameters, *numpy.moveaxis(q, -1, 0),
                                        *numpy.moveaxis(qdot, -1, 0), *input_rates, *input_accels))
    return qdot, qddot


def _predict(here, parameters, q, targets):
    """Second-order Taylor guesses at the targets from the solved point (here, q)."""
    inputs = tuple(numpy.asarray([x]) for x in here)
    steps = tuple(t - x for t, x in zip(targets, here))
    _, J, _, _, unit = _system(inputs, parameters, q[None, :])
    J = numpy.broadcast_to(J, (len(steps[0]),) + J.shape[1:])
    first, second = _rates(inputs, parameters, q[None, :], J, steps, tuple(0.0 * s for s in steps))
    change = first + 0.5 * second
    local = numpy.max(numpy.abs(change) / unit, axis=-1) <= MAX_PREDICTION
    return q + change, local


def _correct(inputs, parameters, guess):
    """Newton from guesses (m, n) at m points at once.

    Returns the points, which of them converged while staying on their
    branch, which failed at a singular Jacobian, and the final conditions.
    """
    q = numpy.array(guess, dtype=float)
    active = numpy.ones(len(q), dtype=bool)
    good = numpy.zeros(len(q), dtype=bool)
    singular = numpy.zeros(len(q), dtype=bool)
    previous = numpy.full(len(q), numpy.inf)
    for iteration in range(MAX_ITERATIONS + 1):
        F, J, residual, condition, unit = _system(inputs, parameters, q)
        broken = active & (condition > SINGULAR_CONDITION)
        singular |= broken
        active &= ~broken
        converged = active & (residual <= RESIDUAL_TOLERANCE)
        if iteration == MAX_ITERATIONS or not active.any():
            good |= converged
            break
        step = -_solve(J[active], F[active])
        size = numpy.max(numpy.abs(step) / unit[active], axis=-1)
        limit = MAX_CORRECTION if iteration == 0 else numpy.maximum(CONTRACTION * previous[active], 1e3 * EPSILON)
        # Converged points take this last (rounding-sized) correction and stop; where it is
        # not small, the residual is flat: a singular position.
        indices = numpy.flatnonzero(active)
        final = converged[active]
        keep = (size <= limit) | final
        q[indices[keep]] += step[keep]
        previous[indices] = size
        good[indices[final & (size <= POSITION_TOLERANCE)]] = True
        singular[indices[final & (size > POSITION_TOLERANCE)]] = True
        active[indices[~keep | final]] = False
    return q, good, singular, condition


def _assemble(inputs, parameters, guess):
    """Damped Newton from the initial guess at the first input value: this fixes the branch."""
    q = numpy.array(guess, dtype=float)[None, :]
    for _ in range(ASSEMBLY_ITERATIONS):
        F, J, residual, condition, unit = _system(inputs, parameters, q)
        if condition[0] > SINGULAR_CONDITION:
            raise _singular(inputs, condition[0], " (or an initial guess where links line up)")
        step = -_solve(J, F)
        if residual[0] <= RESIDUAL_TOLERANCE:
            if numpy.max(numpy.abs(step) / unit) > POSITION_TOLERANCE:
                raise _singular(inputs, condition[0])
            return q[0] + step[0]  # a last, rounding-sized correction
        step /= max(1.0, float(numpy.max(numpy.abs(step) / unit)) / 0.5)  # at most half a radian a step
        fraction = 1.0
        while fraction > 1e-3:
            trial = q + fraction * step
            if _system(inputs, parameters, trial)[2][0] < residual[0]:
                break
            fraction /= 2
        q = trial
    raise ValueError(f"Newton's method did not converge at {_where(inputs)} from the initial guess "
                     f"(residual {residual[0]:.3g} of the loop size): the linkage may not be assembled there, "
                     "or the guess is too far from an assembly")


def _substeps(here, parameters, q, there):
    """Continue from (here, q) to the input values `there` in as many steps as it takes."""
    done, fraction = 0.0, 1.0
    while True:
        start = tuple(a + done * (b - a) for a, b in zip(here, there))
        end = min(done + fraction, 1.0)
        target = tuple(numpy.asarray([a + end * (b - a)]) for a, b in zip(here, there))
        guess, local = _predict(start, parameters, q, target)
        solved, good, singular, condition = _correct(target, parameters, guess)
        if good[0] and local[0] and condition[0] <= SINGULAR_CONDITION:
            done, q = end, solved[0]
            if done >= 1.0:
                return q
            fraction *= 2
            continue
        fraction /= 2
        if fraction < MIN_FRACTION:
            if singular[0] or condition[0] > SINGULAR_CONDITION:
                raise _singular(target, condition[0])
            raise ValueError(f"Newton's method did not converge beyond {_where(start)} on the way to "
                             f"{_where(there)}: the linkage cannot be assembled past there, "
                             "or it passes a dead-centre position")


def _continue(inputs, parameters, q0):
    """Positions (N, n) over the sweep, each continued from the previous input value."""
    count = len(inputs[0])
    q = numpy.empty((count, len(q0)))
    q[0] = q0
    i, block = 0, 1
    while i < count - 1:
        stop = min(count, i + 1 + block)
        here = tuple(float(x[i]) for x in inputs)
        targets = tuple(x[i + 1:stop] for x in inputs)
        guess, local = _predict(here, parameters, q[i], targets)
        solved, good, singular, condition = _correct(targets, parameters, guess)
        good &= local & (condition <= SINGULAR_CONDITION)
        accepted = len(good) if good.all() else int(numpy.argmin(good))
        if accepted == 0:
            q[i + 1] = _substeps(here, parameters, q[i], tuple(float(x[i + 1]) for x in inputs))
            i, block = i + 1, 1
            continue
        q[i + 1:i + 1 + accepted] = solved[:accepted]
        block = min(2 * block, LARGEST_BLOCK) if accepted == len(good) else accepted
        i += accepted
    return q


def _sweep(inputs, parameters, guess, input_rates=None, input_accels=None):
    """Solve the sweep; returns (shape, inputs, positions, rates, accelerations, residuals)."""
    inputs = numpy.broadcast_arrays(*(numpy.asarray(x, dtype=float) for x in inputs))
    shape = inputs[0].shape
    if len(shape) > 1:
        raise ValueError(f"the input sweep must be one-dimensional, got shape {shape}")
    inputs = tuple(numpy.ravel(x) for x in inputs)
    if inputs[0].size == 0:
        raise ValueError("the input sweep is empty")
    parameters = tuple(numpy.asarray(p, dtype=float) for p in parameters)
    for name, value in zip(INPUTS + PARAMETERS, inputs + parameters):
        if not numpy.all(numpy.isfinite(value)):
            raise ValueError(f"{name} must be finite, got {value}")
    for name, value in zip(PARAMETERS, parameters):
        if value.ndim:
            raise ValueError(f"{name} must be one number: the numeric solver sweeps the inputs only")
    if isinstance(guess, dict):
        missing = [name for name in UNKNOWNS if name not in guess]
        unexpected = sorted(set(guess) - set(UNKNOWNS))
        if missing or unexpected:
            raise ValueError(f"the initial guess needs exactly {', '.join(UNKNOWNS)}; "
                             f"missing {missing}, unexpected {unexpected}")
        guess = [guess[name] for name in UNKNOWNS]
    guess = numpy.asarray(guess, dtype=float)
    if guess.shape != (len(UNKNOWNS),) or not numpy.all(numpy.isfinite(guess)):
        raise ValueError(f"the initial guess must be {len(UNKNOWNS)} finite numbers ({', '.join(UNKNOWNS)})")
    first = _assemble(tuple(x[:1] for x in inputs), parameters, guess)
    q = _continue(inputs, parameters, first)
    F, J, residual, condition, unit = _system(inputs, parameters, q)
    if not numpy.all(residual <= RESIDUAL_TOLERANCE) or numpy.any(condition > SINGULAR_CONDITION):
        worst = int(numpy.argmax(residual / RESIDUAL_TOLERANCE + condition / SINGULAR_CONDITION))
        raise ValueError(f"no converged, regular position at {_where(tuple(x[worst] for x in inputs))}")
    qdot = qddot = None
    if input_rates is not None:
        input_rates = tuple(numpy.broadcast_to(numpy.asarray(r, dtype=float), shape).ravel() for r in input_rates)
        input_accels = tuple(numpy.broadcast_to(numpy.asarray(r, dtype=float), shape).ravel() for r in input_accels)
        for name, value in zip(INPUTS, input_rates + input_accels):
            if not numpy.all(numpy.isfinite(value)):
                raise ValueError(f"the rates and accelerations of {name} must be finite")
        qdot, qddot = _rates(inputs, parameters, q, J, input_rates, input_accels)
    return shape, inputs, q, qdot, qddot, residual


def _results(shape, inputs, parameters, q, qdot, qddot, residual, order):
    """The output dict, reshaped to the sweep's shape."""
    columns = numpy.moveaxis(q, -1, 0)
    result = {name: q[:, k] for k, name in enumerate(UNKNOWNS)}
    if order >= 1:
        result.update({name + "dot": qdot[:, k] for k, name in enumerate(UNKNOWNS)})
    if order >= 2:
        result.update({name + "ddot": qddot[:, k] for k, name in enumerate(UNKNOWNS)})
    values = dict(zip(INPUTS, inputs))
    values.update(result)
    for role, name in ROLES.items():
        if name in values:
            result[role] = values[name]
        if order >= 1 and name + "dot" in values:
            result[role + "_speed"] = values[name + "dot"]
        if order >= 2 and name + "ddot" in values:
            result[role + "_accel"] = values[name + "ddot"]
    result.update(_outputs(*inputs, *parameters, *columns))
    result["residual"] = residual
    result["assembled"] = numpy.ones(len(residual), dtype=bool)
    return {name: numpy.reshape(numpy.broadcast_to(value, residual.shape), shape) for name, value in result.items()}
'''

_PUBLIC = '''

def positions({signature}guess):
    """Positions over a sweep of {input_names} (one-dimensional), from an initial guess.

    guess: {unknown_names} near the wanted assembly at the first input value,
    as a dict or in that order.  Returns a dict of arrays: the unknowns by
    name, roles, points and extras; residual (each point's largest closure
    residual relative to its loop's size) and assembled (True: a point that
    cannot be solved raises ValueError naming its input value instead).
    """
    shape, inputs, q, _, _, residual = _sweep({inputs}, {parameters}, guess)
    return _results(shape, inputs, {parameters}, q, None, None, residual, 0)


def velocities({signature}guess, {rates}):
    """Positions and rates (name + 'dot', role + '_speed') over the sweep; see positions()."""
    shape, inputs, q, qdot, _, residual = _sweep({inputs}, {parameters}, guess, {rate_names}, {zeros})
    return _results(shape, inputs, {parameters}, q, qdot, None, residual, 1)


def accelerations({signature}guess, {rates}, {accels}):
    """Positions, rates and accelerations (name + 'ddot', role + '_accel') over the sweep; see positions()."""
    shape, inputs, q, qdot, qddot, residual = _sweep({inputs}, {parameters}, guess, {rate_names}, {accel_names})
    return _results(shape, inputs, {parameters}, q, qdot, qddot, residual, 2)
'''


def is_angle(linkage: Linkage, symbol: sp.Symbol) -> bool:
    """Whether a coordinate is an angle (it turns a vector) rather than a length (a slider's travel)."""
    return any(symbol in vector.angle.free_symbols for loop in linkage.loops for _, vector in loop.terms)


def numeric_module(linkage: Linkage, title: str = "", regenerate: str = "") -> str:
    """Source of a standalone NumPy module solving ``linkage`` by Newton's method over an input sweep.

    It defines ``positions``, ``velocities`` and ``accelerations`` with the
    arguments ``inputs..., parameters..., guess, input rates..., input
    accelerations...`` (see their docstrings).
    """
    system = closure_system(linkage)
    inputs, parameters, unknowns = linkage.inputs, linkage.parameters, linkage.unknowns
    input_rates = tuple(rate(x) for x in inputs)
    input_accels = tuple(acceleration(x) for x in inputs)
    unknown_rates = tuple(rate(u) for u in unknowns)
    title = title or f"{linkage.name}: Newton's method on the closure equations, over an input sweep."
    parts = [numpy_module([], title, regenerate)]
    names = lambda symbols: repr(tuple(s.name for s in symbols))  # noqa: E731
    parts.append(f"\n\nINPUTS = {names(inputs)}\nPARAMETERS = {names(parameters)}\nUNKNOWNS = {names(unknowns)}\n"
                 f"ANGLE_INPUTS = {names([x for x in inputs if is_angle(linkage, x)])}\n"
                 f"ROLES = {dict((role, q.name) for role, q in linkage.roles.items())!r}\n")
    parts.append(_DRIVER)
    base = inputs + parameters + unknowns
    parts.append("\n\n" + _array_function(
        "_closure", base, [("F", system.residuals), ("J", system.jacobian),
                           ("scale", system.scales), ("unit", system.units)],
        "Closure residuals F, Jacobian J = dF/dq, each equation's scale and each unknown's unit."))
    parts.append("\n\n" + _array_function(
        "_velocity_rhs", base + input_rates, [("r", system.velocity_rhs)],
        "Right-hand side of J qdot = r."))
    parts.append("\n\n" + _array_function(
        "_acceleration_rhs", base + unknown_rates + input_rates + input_accels,
        [("r", system.acceleration_rhs)], "Right-hand side of J qddot = r."))
    outputs, _ = _outputs_function(linkage, inputs + parameters + unknowns)
    parts.append("\n\n" + outputs)
    as_tuple = lambda items: repr(tuple(items)).replace("'", "")  # noqa: E731  (names, not strings)
    parts.append(_PUBLIC.format(
        signature="".join(f"{s.name}, " for s in inputs + parameters),
        inputs=as_tuple(s.name for s in inputs), parameters=as_tuple(s.name for s in parameters),
        input_names=", ".join(s.name for s in inputs), unknown_names=", ".join(s.name for s in unknowns),
        rates=", ".join(f"{s.name}=0.0" for s in input_rates),
        accels=", ".join(f"{s.name}=0.0" for s in input_accels),
        rate_names=as_tuple(s.name for s in input_rates), accel_names=as_tuple(s.name for s in input_accels),
        zeros=as_tuple("0.0" for _ in inputs)))
    return "".join(parts)


def numeric_latex(linkage: Linkage, title: str) -> str:
    """A standalone LaTeX document: closure, why there is no closed form, Newton's iteration and the rate systems."""
    from .latex import _aligned, closure_rows
    from .plan import solve_plan

    system = closure_system(linkage)
    q = sp.Matrix(linkage.unknowns)
    qdot = sp.Matrix([rate(u) for u in linkage.unknowns])
    qddot = sp.Matrix([acceleration(u) for u in linkage.unknowns])
    plan = solve_plan(linkage)
    rows = [(sp.Symbol(f"J_{{{i + 1}{j + 1}}}"), system.jacobian[i, j])
            for i in range(system.jacobian.rows) for j in range(system.jacobian.cols) if system.jacobian[i, j] != 0]
    rhs = [(sp.Symbol(f"r_{{{i + 1}}}"), e) for i, e in enumerate(system.velocity_rhs)]
    rhs2 = [(sp.Symbol(f"s_{{{i + 1}}}"), e) for i, e in enumerate(system.acceleration_rhs)]
    parts = [
        "\\documentclass{article}", "\\usepackage{amsmath}", "\\allowdisplaybreaks",
        "\\begin{document}", f"\\section*{{{title}}}",
        "Angles are measured counter-clockwise from $+x$.",
        "\\subsection*{Closure}", "\\begin{align*}", _aligned(closure_rows(linkage)), "\\end{align*}",
        "\\subsection*{Solve plan}", plan.note.replace("_", "\\_") + ".",
        f"The closure $F(q) = 0$, $q = {sp.latex(q.T)}^T$, is solved by Newton's method, "
        "$J\\,\\Delta q = -F$, with the Jacobian $J = \\partial F / \\partial q$ below; each input value "
        "continues from the previous one, and the first assembly (from an initial guess) fixes the branch.",
        "\\subsection*{Jacobian}", "\\begin{align*}", _aligned(rows), "\\end{align*}",
        f"\\subsection*{{Velocities: $J {sp.latex(qdot)} = r$}}", "\\begin{align*}", _aligned(rhs), "\\end{align*}",
        f"\\subsection*{{Accelerations: $J {sp.latex(qddot)} = s$}}", "\\begin{align*}", _aligned(rhs2),
        "\\end{align*}", "\\end{document}",
    ]
    return "\n".join(parts) + "\n"


class NumericSolver:
    """Newton's method on a linkage's closure, generated as NumPy code and loaded.

    Call it with the inputs (a one-dimensional sweep), the parameters (one
    number each), ``guess`` (the unknowns near the wanted assembly at the first
    input value) and optionally the inputs' rates and accelerations; it
    returns positions, rates and accelerations like the closed-form solvers.
    """

    def __init__(self, linkage: Linkage) -> None:
        from .cache import cache_key, cached_text
        self.linkage = linkage
        # Derived once, then from the scene cache, as every other generated solver.
        self.source = cached_text(cache_key(linkage, [], "numeric"), lambda: numeric_module(linkage))
        self.functions = load_numpy_module(self.source)

    @property
    def arguments(self) -> list[str]:
        signature = self.linkage.inputs + self.linkage.parameters
        rates = tuple(rate(x) for x in self.linkage.inputs) + tuple(acceleration(x) for x in self.linkage.inputs)
        return [s.name for s in signature] + ["guess"] + [s.name for s in rates]

    def __call__(self, guess: Mapping[str, float] | Sequence[float], **values) -> dict[str, numpy.ndarray]:
        names = self.arguments
        unknown = set(values) - set(names)
        missing = [s.name for s in self.linkage.inputs + self.linkage.parameters if s.name not in values]
        if unknown or missing:
            raise ValueError(f"{self.linkage.name} takes {', '.join(names)}; "
                             + (f"not {', '.join(sorted(unknown))}" if unknown else f"missing {', '.join(missing)}"))
        check_lengths(**{s.name: values[s.name] for s in self.linkage.parameters if s.is_positive})
        return self.functions["accelerations"](guess=guess, **values)
