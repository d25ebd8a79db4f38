"""Newton's method over an input sweep: the driver that every generated numeric module embeds.

The generator (:mod:`symlink.codegen.newton`) copies this module's source,
from the line after :data:`DRIVER_BEGINS` to the end, into each module it
writes, so the generated module stays standalone (NumPy only), while the
driver is ordinary Python that is imported, linted and tested here.

The driver solves one closure system, which the generated module defines
around it and which stand here as placeholders (an empty system):

* ``INPUTS``, ``PARAMETERS``, ``UNKNOWNS``, ``ANGLE_INPUTS``: argument names;
  ``ROLES``: role name -> coordinate name;
* ``_closure(*inputs, *parameters, *unknowns) -> (F, J, scale, unit)``: the
  residuals (..., n), the Jacobian (..., n, n), each equation's scale and each
  unknown's unit;
* ``_velocity_rhs(*inputs, *parameters, *unknowns, *input_rates)`` and
  ``_acceleration_rhs(*inputs, *parameters, *unknowns, *unknown_rates,
  *input_rates, *input_accels)``: the right-hand sides of ``J qdot = r`` and
  ``J qddot = s``;
* ``_outputs(*inputs, *parameters, *unknowns) -> dict``: named points and extras;
* ``_parameter_rhs(*inputs, *parameters, *unknowns) -> R`` (..., n, parameters): the
  right-hand sides of ``J dq/dp = R`` (``-dF/dp``), and
  ``_sensitivity_outputs(*inputs, *parameters, *unknowns, *dq/dp) -> dict``: every position
  output's derivative by every parameter (the design sensitivities).

How it works:

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
  over the whole sweep with ``numpy.linalg.solve``, and the design
  sensitivities ``J dq/dp = -dF/dp`` with the same converged Jacobian.

>>> _stack([1.0, numpy.zeros(2)]).tolist()
[[1.0, 0.0], [1.0, 0.0]]
"""
import numpy

INPUTS: tuple[str, ...] = ()
PARAMETERS: tuple[str, ...] = ()
UNKNOWNS: tuple[str, ...] = ()
ANGLE_INPUTS: tuple[str, ...] = ()
ROLES: dict[str, str] = {}


def _closure(*values):
    """Closure residuals F, Jacobian J = dF/dq, each equation's scale and each unknown's unit (generated)."""
    raise NotImplementedError("the generated module defines the closure system")


def _velocity_rhs(*values):
    """Right-hand side of J qdot = r (generated)."""
    raise NotImplementedError("the generated module defines the closure system")


def _acceleration_rhs(*values):
    """Right-hand side of J qddot = r (generated)."""
    raise NotImplementedError("the generated module defines the closure system")


def _outputs(*values):
    """Named points and extra outputs from the solved coordinates (generated)."""
    raise NotImplementedError("the generated module defines the closure system")


def _parameter_rhs(*values):
    """Right-hand sides of J dq/dp = R, one column a parameter (generated)."""
    raise NotImplementedError("the generated module defines the closure system")


def _sensitivity_outputs(*values):
    """Each position output's derivative by each parameter, from the unknowns' (generated)."""
    raise NotImplementedError("the generated module defines the closure system")


#: The line after which the generated module copies this source, to the end.
DRIVER_BEGINS = "# symlink: the driver that generated modules embed begins here."
# symlink: the driver that generated modules embed begins here.

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


def _not_assembled(inputs, residual):
    return ValueError(f"Newton's method did not converge at {_where(inputs)} from the initial guess "
                      f"(residual {residual:.3g} of the loop size): the linkage may not be assembled there, "
                      "or the guess is too far from an assembly")


def _not_continued(start, there):
    return ValueError(f"Newton's method did not converge beyond {_where(start)} on the way to "
                      f"{_where(there)}: the linkage cannot be assembled past there, "
                      "or it passes a dead-centre position")


def _irregular(inputs):
    return ValueError(f"no converged, regular position at {_where(inputs)}")


def _failure(status, report):
    """The error of a compiled sweep's status (1 to 5) and report (condition, residual, index, start, target)."""
    count = len(INPUTS)
    start = tuple(float(v) for v in report[3:3 + count])
    target = tuple(float(v) for v in report[3 + count:3 + 2 * count])
    if status == 1:
        return _not_assembled(start, float(report[1]))
    if status == 2:
        return _singular(start, float(report[0]), " (or an initial guess where links line up)")
    if status == 3:
        return _singular(start, float(report[0]))
    if status == 4:
        return _not_continued(start, target)
    return _irregular(start)


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
    raise _not_assembled(inputs, residual[0])


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
            raise _not_continued(start, there)


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


def _prepared(inputs, parameters, guess, input_rates=None, input_accels=None):
    """The sweep's arguments checked (ValueError naming a bad one) and flattened:
    (shape, inputs, parameters, guess, input rates, input accelerations), the rates None where not asked for."""
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
    if input_rates is not None:
        input_rates = tuple(numpy.broadcast_to(numpy.asarray(r, dtype=float), shape).ravel() for r in input_rates)
        input_accels = tuple(numpy.broadcast_to(numpy.asarray(r, dtype=float), shape).ravel() for r in input_accels)
        for name, value in zip(INPUTS, input_rates + input_accels):
            if not numpy.all(numpy.isfinite(value)):
                raise ValueError(f"the rates and accelerations of {name} must be finite")
    return shape, inputs, parameters, guess, input_rates, input_accels


def _sweep(inputs, parameters, guess, input_rates=None, input_accels=None):
    """Solve the sweep; returns (shape, inputs, positions, rates, accelerations, residuals)."""
    shape, inputs, parameters, guess, input_rates, input_accels = _prepared(
        inputs, parameters, guess, input_rates, input_accels)
    first = _assemble(tuple(x[:1] for x in inputs), parameters, guess)
    q = _continue(inputs, parameters, first)
    F, J, residual, condition, unit = _system(inputs, parameters, q)
    if not numpy.all(residual <= RESIDUAL_TOLERANCE) or numpy.any(condition > SINGULAR_CONDITION):
        worst = int(numpy.argmax(residual / RESIDUAL_TOLERANCE + condition / SINGULAR_CONDITION))
        raise _irregular(tuple(x[worst] for x in inputs))
    qdot = qddot = None
    if input_rates is not None:
        qdot, qddot = _rates(inputs, parameters, q, J, input_rates, input_accels)
    return shape, inputs, q, qdot, qddot, residual


def _results(shape, inputs, parameters, q, qdot, qddot, residual, order, outputs=None):
    """The output dict, reshaped to the sweep's shape; ``outputs`` the named points and extras where they are
    computed already (by the compiled driver), else from ``_outputs``."""
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
    result.update(_outputs(*inputs, *parameters, *columns) if outputs is None else outputs)
    result["residual"] = residual
    result["assembled"] = numpy.ones(len(residual), dtype=bool)
    return {name: numpy.reshape(numpy.broadcast_to(value, residual.shape), shape) for name, value in result.items()}


def _sensitivity_results(shape, inputs, parameters, q, residual):
    """Positions and their derivatives by each parameter, from J dq/dp = -dF/dp at the converged points."""
    columns = numpy.moveaxis(q, -1, 0)
    _, J, _, _, _ = _system(inputs, parameters, q)
    rhs = numpy.broadcast_to(_parameter_rhs(*inputs, *parameters, *columns), J.shape[:-1] + (len(PARAMETERS),))
    slopes = numpy.linalg.solve(J, rhs)  # (points, unknowns, parameters)
    result = _results(shape, inputs, parameters, q, None, None, residual, 0)
    flat = numpy.moveaxis(slopes.reshape(len(q), -1), -1, 0)
    found = _sensitivity_outputs(*inputs, *parameters, *columns, *flat)
    result.update({name: numpy.reshape(numpy.broadcast_to(value, residual.shape), shape)
                   for name, value in found.items()})
    return result
