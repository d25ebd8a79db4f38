"""Forward dynamics of a one-input linkage: how it moves under a motor and its loads.

A one-input linkage with a :class:`~symlink.dynamics.model.DynamicModel` moves by

    ``M(q) q'' + M'(q) q'^2 / 2 = Q_applied(q, q') + Q_motor(q, q')``

where ``M`` is the generalised inertia about the input (plus any inertia added on the
input shaft, a flywheel), ``M' = dM/dq``, ``Q_applied`` the virtual power of the loads
per unit input rate (gravity, forces, torques, springs, dampers) and ``Q_motor`` the
torque (a force, for a slider input) that drives the input.  ``M``, ``M'`` and
``Q_applied`` are outputs of :func:`~symlink.dynamics.inverse.dynamic_linkage`, so the
right-hand side is generated NumPy code like any other output (derived once, cached on disk), never text evaluated
at run time.  :class:`ForwardDynamics` integrates it with
:func:`scipy.integrate.solve_ivp` (SciPy is the optional extra ``dynamics``).

A motor is any callable of ``(angle, speed)`` returning the torque; :class:`ConstantTorque`
and :class:`LinearMotor` (a straight speed-torque curve, as of a DC or induction motor
near its working point) are built in.  The result, a :class:`Motion`, lists every place
where the input's speed passes through zero (:class:`Stop`: the motion stops, and
reverses where the acceleration there is not zero), found by ``solve_ivp``'s event
location, and says where the linkage cannot be assembled: a toggle (dead point) that
the motion runs into ends the integration there with a message, and no step is ever
taken through a position where the generated code gives NaN.

For a slider input ``angle`` reads "travel" and torque "force" throughout.

>>> from symlink.mechanism.catalog import fourbar
>>> from symlink.dynamics.model import DynamicModel, MassProperties
>>> model = DynamicModel(fourbar(), [MassProperties("crank", 2.0, distance=10.0, inertia=50.0)])
>>> crank = ForwardDynamics(model, dict(a=20, b=66, c=56, d=80))
>>> float(crank.acceleration(0.0, 0.0, 250.0))  # 250 / (50 + 2 * 10^2)
1.0
"""
from __future__ import annotations

import functools
import inspect
import math
import weakref
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Mapping

import numpy

from ..numeric.cache import cache_key, cached_module
from ..common.display import record_html

if TYPE_CHECKING:  # the symbolic side is imported where a model is worked on: code read from the disk cache
    # (EquationCode) runs without SymPy
    from ..symbolic.linkage import Linkage
    from .model import DynamicModel

__all__ = ["ForwardDynamics", "Motion", "Stop", "ConstantTorque", "LinearMotor", "Motor", "require_scipy",
           "EquationCode", "equation_code", "model_equation_code", "equation_entry_text"]


#: How close (in the loops' normalised square-root argument, about radians of the input) the motion may
#: come to a toggle before the integration stops there.
TOGGLE_MARGIN = 1e-9

#: A motor: the torque on the input as a function of its angle and speed.
Motor = Callable[[float, float], float]


def require_scipy() -> Any:
    """``scipy.integrate``, or an ImportError saying which extra to install."""
    try:
        import scipy.integrate
    except ImportError:
        raise ImportError("forward dynamics integrates with SciPy: pip install 'symlink-kinematics[dynamics]'") \
            from None
    return scipy.integrate


#: The cache kind of the scalar right-hand side; bump it when :func:`scalar_source` prints differently.
SCALAR_KIND = "forward-dynamics-scalar-3"


_EQUATION_LINKAGES: "weakref.WeakKeyDictionary[DynamicModel, Linkage]" = weakref.WeakKeyDictionary()


def equation_linkage(model: DynamicModel) -> Linkage:
    """The model's kinematic linkage with the outputs of :data:`~symlink.dynamics.inverse.EQUATION_OUTPUTS` and
    ``input_torque`` only.

    The same expressions as those outputs of :func:`~symlink.dynamics.inverse.dynamic_linkage`, without the
    joint reactions: what
    forward dynamics and the flywheel need derives (and keys the code cache) in a
    fraction of the time.  Made once a model.
    """
    from .inverse import driving_efforts, equation_of_motion, linkage_with_outputs
    if model not in _EQUATION_LINKAGES:
        if len(model.kinematics.inputs) != 1:
            raise ValueError(f"forward dynamics is for one-input linkages; {model.kinematics.name} has "
                             f"{len(model.kinematics.inputs)} inputs ({', '.join(map(str, model.kinematics.inputs))})")
        outputs = {**equation_of_motion(model), model.input_effort_name(0): driving_efforts(model)[0]}
        _EQUATION_LINKAGES[model] = linkage_with_outputs(model, outputs)
    return _EQUATION_LINKAGES[model]


def scalar_source(linkage: Linkage, outputs: tuple[str, ...] | None = None) -> str:
    """A module with ``solve(<arguments>)`` for one state, as floats: ``outputs``, ``assembled``, ``margin``.

    The same straight-line program (common subexpressions eliminated) as the NumPy
    solvers, printed with :mod:`math` (:mod:`symlink.codegen.scalar`): an integrator
    calls it once a stage, with single numbers.  ``margin`` is the smallest of the
    loops' square-root arguments, each divided by its scale: positive where the
    linkage assembles, zero at a toggle (``inf`` without square roots), so that an
    integrator can stop on reaching one.  It may raise ``ZeroDivisionError`` exactly
    at a toggle.
    """
    from dataclasses import replace

    from ..codegen.program import in_loop_units
    from ..codegen.scalar import scalar_module
    from ..symbolic.position import ClampedSqrt
    from .inverse import EQUATION_OUTPUTS
    outputs = EQUATION_OUTPUTS if outputs is None else outputs
    program = in_loop_units(linkage.program(list(outputs)))
    roots = [expr for _, expr in program.assignments if isinstance(expr, ClampedSqrt)]
    margins = {f"margin_{k}": expr.args[0] / abs(expr.args[1]) for k, expr in enumerate(roots)}
    program = replace(program, outputs={**program.outputs, **margins})
    return scalar_module(program, outputs, smallest=list(margins))


#: The cache kind of a model's NumPy code of the equation of motion and the driving effort (:func:`equation_entry_text`).
EQUATION_KIND = "forward-dynamics-equations/1"
#: The names of the two functions of that module, and of the dictionary of what a call needs.
EQUATIONS, EFFORT, DESCRIPTION = "equation_of_motion", "driving_effort", "EQUATION_DESCRIPTION"


def equation_entry_text(model: DynamicModel) -> str:
    """The cache entry of a one-input ``model``'s NumPy code: the equation of motion (``M``, ``dM/dq``,
    ``Q_applied``; :func:`equation_linkage`) and the driving effort, one function each, and what a call needs
    (names, plain data), so that :func:`equation_code` runs them without the model (symbolic work, done once)."""
    from ..codegen.numpy import numpy_module
    from ..symbolic.vectors import acceleration, rate
    from .inverse import EQUATION_OUTPUTS
    linkage = equation_linkage(model)
    effort = model.input_effort_name(0)
    driven = linkage.inputs[0]
    described = {
        "name": linkage.name, "input": driven.name, "rate": rate(driven).name,
        "acceleration": acceleration(driven).name, "effort": effort,
        "parameters": [s.name for s in linkage.parameters], "branches": [s.name for s in linkage.branches],
        "lengths": [s.name for s in linkage.parameters if s.is_positive],
    }
    source = numpy_module([(EQUATIONS, linkage.program(list(EQUATION_OUTPUTS)), f"{linkage.name}: M, dM/dq, Q_applied."),
                           (EFFORT, linkage.program([effort]), f"{linkage.name}: {effort}.")])
    return f"{source.rstrip()}\n\n\n#: What a call needs, for symlink.dynamics.forward.EquationCode.\n{DESCRIPTION} = {described!r}\n"


@dataclass(frozen=True)
class EquationCode:
    """The generated code that forward dynamics and a flywheel run for one model, and the names a call needs.

    Plain names and functions, read from the disk cache (:func:`equation_code`): a process whose code is cached
    builds no model and imports no SymPy.  ``equation`` gives ``M``, ``dM/dq``, ``Q_applied`` and ``assembled``
    on arrays, ``effort`` the driving effort (``input_torque``, or ``input_force`` for a slider), ``scalar`` the
    equation for one state as floats (:func:`scalar_source`), ``check`` the generated argument check.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    name: str
    input: str
    rate: str
    acceleration: str
    effort_name: str
    parameters: tuple[str, ...]
    branches: tuple[str, ...]
    lengths: tuple[str, ...]
    equation: Callable[..., dict]
    effort: Callable[..., dict]
    scalar: Callable[..., tuple]
    check: Callable[..., Any]

    @staticmethod
    def arguments_of(function: Callable[..., Any]) -> list[str]:
        """The argument names of a generated function, in calling order (not the keyword-only ``check``)."""
        return [name for name, parameter in inspect.signature(function).parameters.items()
                if parameter.kind is not parameter.KEYWORD_ONLY]


def equation_code(key: str, scalar_key: str, model: Callable[[], DynamicModel]) -> EquationCode:
    """The :class:`EquationCode` stored under the cache keys ``key`` (:func:`equation_entry_text`) and
    ``scalar_key`` (:func:`scalar_source`); ``model()`` makes the model where an entry is derived (once).

    Keys made without the model (:func:`symlink.numeric.cache.catalog_key` of what names it, as ``symlink flywheel``
    makes them from its options' numbers) find cached code without SymPy; :func:`model_equation_code` keys it by
    the model's definition.
    """
    made: list[DynamicModel] = []

    def built() -> DynamicModel:
        if not made:
            made.append(model())
        return made[0]

    # verified entries of a private cache (never user text), run from their cached bytecode
    _, namespace = cached_module(key, lambda: equation_entry_text(built()))
    _, scalar = cached_module(scalar_key, lambda: scalar_source(equation_linkage(built())))
    described = namespace[DESCRIPTION]
    return EquationCode(described["name"], described["input"], described["rate"], described["acceleration"],
                        described["effort"], tuple(described["parameters"]), tuple(described["branches"]),
                        tuple(described["lengths"]), namespace[EQUATIONS], namespace[EFFORT], scalar["solve"],
                        namespace["_arguments"])


def model_equation_code(model: DynamicModel) -> EquationCode:
    """The :class:`EquationCode` of ``model``, keyed by its equation linkage's definition (derived once)."""
    from .inverse import EQUATION_OUTPUTS
    linkage = equation_linkage(model)
    outputs = list(EQUATION_OUTPUTS)
    return equation_code(cache_key(linkage, [*outputs, model.input_effort_name(0)], EQUATION_KIND),
                         cache_key(linkage, outputs, SCALAR_KIND), lambda: model)


@dataclass(frozen=True)
class ConstantTorque:
    """A motor giving the same torque at every angle and speed.

    Parameters
    ----------
    torque : float
        The torque on the input.

    Examples
    --------
    >>> import symlink
    >>> symlink.ConstantTorque(3.0)(1.0, 20.0)  # (angle, speed) -> torque
    3.0
    """

    torque: float

    def __call__(self, angle: float, speed: float) -> float:
        return self.torque


@dataclass(frozen=True)
class LinearMotor:
    """A straight speed-torque curve: ``stall_torque`` at rest, none at ``no_load_speed`` (rad/s).

    ``torque = stall_torque (1 - speed / no_load_speed)``; above the no-load speed it brakes.

    Parameters
    ----------
    stall_torque : float
        The torque at rest.
    no_load_speed : float
        The speed (rad/s) at which the torque is zero.

    Examples
    --------
    >>> import symlink
    >>> symlink.LinearMotor(10.0, 100.0)(0.0, 25.0)  # 10 (1 - 25 / 100)
    7.5
    """

    stall_torque: float
    no_load_speed: float

    def __post_init__(self) -> None:
        if not (math.isfinite(self.stall_torque) and math.isfinite(self.no_load_speed)):
            raise ValueError("a motor's stall torque and no-load speed must be finite")
        if self.no_load_speed == 0:
            raise ValueError("a motor's no-load speed must not be zero")

    def __call__(self, angle: float, speed: float) -> float:
        return self.stall_torque * (1.0 - speed / self.no_load_speed)


@dataclass(frozen=True)
class Stop:
    """A zero of the input's speed: at ``time`` and ``angle``, with the ``acceleration`` there.

    Where the acceleration is not zero the motion reverses; where it is (to rounding), the
    linkage has come to rest in an equilibrium.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    time: float
    angle: float
    acceleration: float

    @property
    def reverses(self) -> bool:
        """Whether the speed changes sign here (else the linkage rests)."""
        return self.acceleration != 0.0


@dataclass(frozen=True)
class Motion:
    """The input's motion: ``time``, ``angle``, ``speed``, ``acceleration`` (arrays), its stops, how it ended.

    ``toggle`` is the angle beyond which the linkage cannot be assembled when the motion ran
    into it (None otherwise); ``message`` says how the integration ended; ``solution`` is
    SciPy's result (``solution.sol(t)`` interpolates the state ``[angle, speed]``).
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    time: numpy.ndarray
    angle: numpy.ndarray
    speed: numpy.ndarray
    acceleration: numpy.ndarray
    stops: tuple[Stop, ...]
    toggle: float | None
    message: str
    solution: Any

    @property
    def finished(self) -> bool:
        """Whether the motion was integrated over the whole time asked for."""
        return self.toggle is None and self.solution.status == 0


class ForwardDynamics:
    """The equation of motion of a one-input ``model`` at parameter ``values`` (by symbol name), on ``branch``.

    ``values`` give every parameter of :func:`dynamic_linkage(model) <symlink.dynamics.inverse.dynamic_linkage>` (lengths, masses, inertias,
    gravity, load values); ``branch`` is +1 or -1 for every loop, or a mapping of the
    branch argument names (``branch_<loop>``) to signs.  ``input_inertia`` is a
    constant inertia added on the input (a flywheel on the crank shaft).

    Parameters
    ----------
    model : DynamicModel or EquationCode
        A one-input model, or its generated code (:func:`equation_code`: read from the disk cache, no SymPy).
    values : mapping of str to float
        Every parameter of its dynamic linkage by name (lengths, masses, inertias, loads).
    branch : int or mapping of str to int, optional
        +1 or -1 for every loop, or a sign a branch argument (default +1).
    input_inertia : float, optional
        A constant inertia added on the input (a flywheel), default 0.

    Examples
    --------
    >>> import symlink
    >>> model = symlink.DynamicModel(symlink.fourbar(), [symlink.MassProperties("crank", "m2", inertia="I2")])
    >>> motion = symlink.ForwardDynamics(model, dict(a=20, b=66, c=56, d=80, m2=1.0, I2=0.5))
    >>> float(motion.acceleration(0.3, 1.0, 2.0))  # theta'' = T / I2 = 2.0 / 0.5
    4.0
    """

    def __init__(self, model: DynamicModel | EquationCode, values: Mapping[str, float],
                 branch: int | Mapping[str, int] = 1, input_inertia: float = 0.0) -> None:
        if isinstance(model, EquationCode):
            code, self.model = model, None
        else:
            from .model import DynamicModel
            if not isinstance(model, DynamicModel):
                raise ValueError(f"forward dynamics needs a DynamicModel, not {model!r}")
            code, self.model = model_equation_code(model), model
        self.code = code
        self._function = functools.partial(code.equation, check=False)
        self.arguments = code.arguments_of(code.equation)
        self.takes_speed = code.rate in self.arguments
        self._scalar = code.scalar  # our own generated code, never user text
        parameters = list(code.parameters)
        unknown = sorted(set(values) - set(parameters))
        if unknown:
            raise ValueError(f"{code.name} has no parameter {unknown[0]!r}; its parameters are "
                             f"{', '.join(parameters)}")
        missing = [name for name in parameters if name not in values]
        if missing:
            raise ValueError(f"{code.name} needs values for {', '.join(missing)}")
        branches = list(code.branches)
        signs = dict(branch) if isinstance(branch, Mapping) else {name: branch for name in branches}
        if set(signs) != set(branches):
            raise ValueError(f"branch: give a sign for each of {', '.join(branches) or 'no loop'}, got "
                             f"{', '.join(signs) or 'none'}")
        names = parameters + branches + ["input_inertia"]
        arrays, shape = code.check(True, tuple(names), tuple([values[n] for n in parameters]
                                                             + [signs[n] for n in branches] + [input_inertia]),
                                   code.lengths, tuple(branches))
        if shape != ():
            raise ValueError("forward dynamics takes one number for each parameter, not arrays")
        self.values = {name: float(array) for name, array in zip(names, arrays)}
        self.input_inertia = self.values.pop("input_inertia")
        if self.input_inertia < 0:
            raise ValueError(f"input_inertia must not be negative, got {self.input_inertia!r}")
        self._fixed = {name: value for name, value in self.values.items() if name in self.arguments}

    @property
    def linkage(self) -> Linkage:
        """The model's equation linkage (:func:`equation_linkage`; builds it: SymPy), where a model was given."""
        if self.model is None:
            raise ValueError(f"forward dynamics of {self.code.name} runs code from the disk cache: it has no linkage")
        return equation_linkage(self.model)

    # --- the equation of motion ---------------------------------------------------------
    def terms(self, angle, speed=0.0) -> dict[str, numpy.ndarray]:
        """``M`` (with the input inertia), ``dM/dq``, ``Q_applied`` and ``assembled`` at angles and speeds (arrays)."""
        values = dict(self._fixed)
        values[self.code.input] = angle
        if self.takes_speed:
            values[self.code.rate] = speed
        with numpy.errstate(invalid="ignore", divide="ignore"):
            found = self._function(**values)
        return {"generalised_inertia": found["generalised_inertia"] + self.input_inertia,
                "generalised_inertia_slope": found["generalised_inertia_slope"],
                "applied_generalised_force": found["applied_generalised_force"],
                "assembled": found["assembled"]}

    def acceleration(self, angle, speed, effort=0.0) -> numpy.ndarray:
        """``q'' = (Q_applied + effort - M'(q) q'^2 / 2) / M(q)`` (NaN where the linkage cannot be assembled)."""
        found = self.terms(angle, speed)
        speed = numpy.asarray(speed, dtype=float)
        with numpy.errstate(invalid="ignore", divide="ignore"):
            return (found["applied_generalised_force"] + effort
                    - 0.5 * found["generalised_inertia_slope"] * speed * speed) / found["generalised_inertia"]

    # --- integration ----------------------------------------------------------------------
    def simulate(self, angle: float, speed: float, duration: float, motor: Motor | None = None, *,
                 samples: int | None = None, until_stop: bool = False, method: str = "DOP853",
                 rtol: float = 1e-10, atol: float = 1e-10, max_step: float = math.inf) -> Motion:
        """Integrate from ``angle`` (rad) and ``speed`` (rad/s) for ``duration`` seconds under ``motor``.

        ``motor(angle, speed)`` is the torque on the input (default none).  ``samples``
        evenly spaced output times (default: the integrator's own steps);
        ``until_stop`` ends at the first stop.  ``method``, ``rtol``, ``atol`` and
        ``max_step`` go to :func:`scipy.integrate.solve_ivp` (an explicit method: the
        steps it rejects are how a toggle is found).  ``ValueError`` for bad values or a
        start where the linkage cannot be assembled or has no inertia.
        """
        integrate = require_scipy()
        for name, value in (("angle", angle), ("speed", speed), ("duration", duration)):
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                raise ValueError(f"{name} must be a finite number, got {value!r}")
        if duration <= 0:
            raise ValueError(f"duration must be positive, got {duration!r}")
        if samples is not None and (isinstance(samples, bool) or not isinstance(samples, int) or samples < 2):
            raise ValueError(f"samples must be a whole number of at least 2, got {samples!r}")
        if motor is not None and not callable(motor):
            raise ValueError(f"motor must be a callable of (angle, speed), got {motor!r}")
        start = self.terms(float(angle), float(speed))
        if not bool(start["assembled"]):
            raise ValueError(f"{self.code.name} cannot be assembled at the starting angle {angle!r}")
        inertia = float(start["generalised_inertia"])
        if not inertia > 0:
            raise ValueError(f"the generalised inertia at the start is {inertia:g}: give the bodies mass "
                             "(or an input inertia)")
        unassembled: list[float] = []

        scalar, fixed, extra = self._scalar, self._fixed, self.input_inertia
        name, speed_name = self.code.input, (self.code.rate if self.takes_speed else None)

        def right_hand_side(t: float, state: numpy.ndarray) -> list[float]:
            q, w = float(state[0]), float(state[1])
            values = {name: q, speed_name: w} if speed_name else {name: q}
            try:
                inertia, slope, applied, assembled, _ = scalar(**fixed, **values)
            except (ZeroDivisionError, ValueError, OverflowError):  # exactly at a toggle
                assembled = False
            if not assembled:
                unassembled.append(q)
                return [w, math.nan]  # the step is rejected: solve_ivp never accepts a NaN state
            effort = 0.0 if motor is None else float(motor(q, w))
            return [w, (applied + effort - 0.5 * slope * w * w) / (inertia + extra)]

        def speed_zero(t: float, state: numpy.ndarray) -> float:
            return float(state[1])

        def toggle_near(t: float, state: numpy.ndarray) -> float:
            values = {name: float(state[0]), speed_name: float(state[1])} if speed_name else {name: float(state[0])}
            try:
                margin = scalar(**fixed, **values)[-1]
            except (ZeroDivisionError, ValueError, OverflowError):
                return -1.0
            return (margin if math.isfinite(margin) else -1.0) - TOGGLE_MARGIN

        speed_zero.terminal = until_stop  # type: ignore[attr-defined]
        toggle_near.terminal, toggle_near.direction = True, -1  # type: ignore[attr-defined]
        t_eval = None if samples is None else numpy.linspace(0.0, float(duration), samples)
        solution = integrate.solve_ivp(right_hand_side, (0.0, float(duration)), [float(angle), float(speed)],
                                       method=method, t_eval=t_eval, events=[speed_zero, toggle_near], dense_output=True,
                                       rtol=rtol, atol=atol, max_step=max_step)
        time, states = solution.t, solution.y
        toggle = None
        last_t = float(time[-1]) if len(time) else 0.0
        last = states[:, -1] if len(time) else numpy.array([angle, speed], dtype=float)
        if solution.sol is not None:
            last_t = float(solution.sol.t_max)
            last = solution.sol(last_t)
        if solution.status == 0:
            message = f"integrated over the whole time ({float(duration):g} s)"
        elif solution.status == 1 and len(solution.t_events[1]):
            toggle = float(solution.y_events[1][0][0])
            message = (f"reached a toggle (dead point) at angle {toggle:.10g} rad, t = "
                       f"{float(solution.t_events[1][0]):.10g} s, speed {float(solution.y_events[1][0][1]):.6g} "
                       "rad/s: the linkage cannot be assembled beyond it; stopped there")
        elif solution.status == 1:
            message = f"stopped at angle {float(solution.y_events[0][-1][0]):.10g} rad, t = " \
                      f"{float(solution.t_events[0][-1]):.10g} s"
        elif unassembled:
            toggle = float(last[0])
            message = (f"the linkage cannot be assembled beyond angle {toggle:.10g} rad (a toggle), reached at "
                       f"t = {last_t:.10g} s with speed {float(last[1]):.6g} rad/s: stopped there")
        else:
            message = f"the integration failed at t = {last_t:.10g} s: {solution.message}"
        stops = []
        for t_event, y_event in zip(solution.t_events[0], solution.y_events[0]):
            if t_event <= 0.0:
                continue
            a = float(self.acceleration(float(y_event[0]), 0.0,
                                        0.0 if motor is None else float(motor(float(y_event[0]), 0.0))))
            stops.append(Stop(float(t_event), float(y_event[0]), a))
        angles, speeds = numpy.asarray(states[0], dtype=float), numpy.asarray(states[1], dtype=float)
        efforts = numpy.array([0.0 if motor is None else float(motor(q, w)) for q, w in zip(angles, speeds)])
        return Motion(numpy.asarray(time, dtype=float), angles, speeds,
                      numpy.asarray(self.acceleration(angles, speeds, efforts), dtype=float) if len(angles)
                      else numpy.empty(0), tuple(stops), toggle, message, solution)
