"""Flywheel sizing: the driving torque over a cycle, its energy fluctuation, the inertia that holds the speed.

The classic machine-design calculation, from a linkage's inverse dynamics:

1. the driving torque ``T(theta)`` over one turn of the input at a constant mean speed
   ``w`` (the model's ``input_torque`` at ``theta' = w``, ``theta'' = 0``);
2. the mean (load) torque ``T_mean``, which a motor of constant torque supplies;
3. the energy fluctuation ``dE``: the largest minus the smallest value over the cycle
   of ``E(theta) = integral of (T - T_mean) dtheta``;
4. the flywheel inertia for a coefficient of speed fluctuation
   ``Cs = (w_max - w_min) / w_mean``, with ``w_mean = (w_max + w_min) / 2`` (the
   convention of Shigley's *Mechanical Engineering Design* and Norton's *Design of
   Machinery*): ``I = dE / (Cs w^2)``.

Step 4 is the textbook approximation: it treats ``I`` as the whole inertia on the input
shaft and the torque as that at constant speed.  It is exact for a rigid rotor of
inertia ``I`` driven by a torque that depends on the angle only, since
``I (w_max^2 - w_min^2) / 2 = I Cs w_mean^2``; a linkage's own inertia varies over the
cycle, and its inertia torque ``M'(theta) theta'^2 / 2`` follows the actual speed.
:meth:`FlywheelSizing.exact_inertia` removes the approximation: with constant motor
torque and loads that depend on the position only, energy gives the speed over the
cycle in closed form,

    ``(J + M(theta)) w(theta)^2 = C + 2 integral of (T_mean + Q_applied) dtheta``,

and it finds the flywheel ``J`` added to the linkage, and the constant ``C``, that make
``(w_max + w_min) / 2 = w`` and ``(w_max - w_min) / w = Cs`` exactly.
:meth:`FlywheelSizing.speed_band` checks either inertia by integrating the forward
dynamics (:class:`~symlink.dynamics.forward.ForwardDynamics`) over one cycle with the
flywheel on the input and a motor holding ``T_mean``.

Integrals over the cycle are spectral: the torque is sampled at ``samples`` equally
spaced angles, integrated term by term as a Fourier series (exact for a trigonometric
polynomial of degree below ``samples / 2``), and the extremes of the energy are refined
by Newton's method on that series.

>>> import numpy
>>> angles = numpy.linspace(0, 2 * numpy.pi, 64, endpoint=False)
>>> cycle = energy_fluctuation(3.0 + 2.0 * numpy.sin(2 * angles))  # E = -cos(2 theta): dE = 2
>>> round(cycle.mean_torque, 12), round(cycle.energy_fluctuation, 12)
(3.0, 2.0)
>>> flywheel_inertia(2.0, 10.0, 0.02)  # dE / (Cs w^2)
1.0
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Mapping

import numpy

from ..common.display import record_html
from .forward import ConstantTorque, EquationCode, ForwardDynamics, Motion, require_scipy

if TYPE_CHECKING:  # a model is worked on (SymPy) where one is given; its cached code (EquationCode) needs none
    from .model import DynamicModel

__all__ = ["TorqueCycle", "energy_fluctuation", "flywheel_inertia", "FlywheelSizing", "SpeedBand", "size_flywheel",
           "rpm_to_rad_per_s"]


def rpm_to_rad_per_s(rpm: float) -> float:
    """Revolutions per minute in rad/s.

    >>> round(rpm_to_rad_per_s(60.0), 12) == round(2 * math.pi, 12)
    True
    """
    return rpm * 2 * math.pi / 60


def _finite(value: Any, name: str, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, numpy.floating, numpy.integer)):
        raise ValueError(f"{name} must be a number, got {value!r}")
    value = float(value)
    if not math.isfinite(value) or (positive and value <= 0):
        raise ValueError(f"{name} must be a {'positive ' if positive else ''}finite number, got {value!r}")
    return value


#: Complex terms of a series evaluated at once off the grid (16 MB): its memory stays bounded however many samples.
SERIES_CHUNK = 1 << 20


class _Periodic:
    """A periodic function from equally spaced samples over one period, as a Fourier series.

    On an equally spaced grid from 0 with at least as many points as samples (the samples' own
    angles, a finer grid) the series is summed by an inverse FFT: O(N log N) time and O(N) memory.
    Elsewhere (Newton steps, a few points) it is summed directly, a bounded chunk of points at a time.
    """

    def __init__(self, samples: numpy.ndarray, period: float) -> None:
        self.count, self.period = len(samples), period
        self.coefficients = numpy.fft.rfft(samples) / self.count
        self.wavenumbers = 2 * math.pi / period * numpy.arange(len(self.coefficients))
        if self.count % 2 == 0:  # the Nyquist term: half of it is the cosine, its derivative is not resolved
            self.coefficients = self.coefficients.copy()
            self.coefficients[-1] = 0.5 * self.coefficients[-1].real

    @property
    def mean(self) -> float:
        return float(self.coefficients[0].real)

    def _series(self, x, coefficients) -> numpy.ndarray:
        """``2 Re(sum of c_k e^(i w_k x)) - Re(c_0)`` at the points ``x``, ``SERIES_CHUNK`` terms at a time."""
        x = numpy.asarray(x, dtype=float)
        flat = x.reshape(-1)
        rows = max(1, SERIES_CHUNK // len(coefficients))
        terms = numpy.empty(len(flat))
        for start in range(0, len(flat), rows):
            phases = numpy.exp(1j * numpy.multiply.outer(flat[start:start + rows], self.wavenumbers))
            terms[start:start + rows] = (phases @ coefficients).real
        return (2 * terms - coefficients[0].real).reshape(x.shape)

    def _on_grid(self, points: int, coefficients) -> numpy.ndarray:
        """The series at ``points`` equally spaced angles ``period * j / points`` (``points`` at least the count)."""
        size = points // 2 + 1
        padded = numpy.zeros(size, dtype=complex)
        padded[:len(coefficients)] = coefficients
        if points % 2 == 0 and len(coefficients) == size:  # irfft counts the Nyquist term once, the series twice
            padded[-1] = 2 * padded[-1].real
        return numpy.fft.irfft(padded, n=points) * points

    def value(self, x) -> numpy.ndarray:
        return self._series(x, self.coefficients)

    def value_on_grid(self, points: int) -> numpy.ndarray:
        """:meth:`value` at ``points`` equally spaced angles from 0 over one period."""
        return self._on_grid(points, self.coefficients)

    def slope(self, x) -> numpy.ndarray:
        return self._series(x, 1j * self.wavenumbers * self.coefficients)

    def _integrated(self) -> numpy.ndarray:
        k = self.wavenumbers[1:]
        return numpy.concatenate([[0.0], self.coefficients[1:] / (1j * k)])

    def integral(self, x) -> numpy.ndarray:
        """``integral from 0 to x of (f - mean)``: periodic."""
        integrated = self._integrated()
        return self._series(x, integrated) - self._series(0.0, integrated)

    def integral_on_grid(self, points: int) -> numpy.ndarray:
        """:meth:`integral` at ``points`` equally spaced angles from 0 over one period."""
        integrated = self._integrated()
        return self._on_grid(points, integrated) - self._series(0.0, integrated)


@dataclass(frozen=True)
class TorqueCycle:
    """A driving torque over one cycle and its energy: ``angles`` from 0, ``torque`` there, ``energy``
    ``E(theta) = integral of (T - T_mean)`` from 0, and ``(angle, E)`` where E is largest and smallest.

    With ``torque`` the torque a linkage needs and a motor supplying its mean, the linkage
    has drawn the most energy from the flywheel where E is largest: the speed is lowest
    there, and highest where E is smallest (for an engine's output torque, the reverse).
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    angles: numpy.ndarray
    torque: numpy.ndarray
    mean_torque: float
    energy: numpy.ndarray
    energy_fluctuation: float
    energy_max: tuple[float, float]
    energy_min: tuple[float, float]
    series: Any = field(repr=False, default=None)


def energy_fluctuation(torque, period: float = 2 * math.pi) -> TorqueCycle:
    """The mean torque and energy fluctuation of ``torque`` sampled at equally spaced angles over one ``period``.

    The samples start at angle 0 and leave out the end of the period (which repeats the
    start); a four-stroke engine's cycle is ``period = 4 pi``.  ``ValueError`` for fewer than
    four samples or values that are not finite.

    Parameters
    ----------
    torque : array_like
        The torque at equally spaced angles over one period, the end left out.
    period : float, optional
        The cycle's length in radians (default ``2 pi``; ``4 pi`` for a four-stroke engine).

    Returns
    -------
    TorqueCycle
        The angles, the torque, its mean, the energy ``E(theta)`` and its fluctuation ``dE``.

    Raises
    ------
    ValueError
        For fewer than four samples or values that are not finite.

    Examples
    --------
    >>> import numpy, symlink
    >>> angles = numpy.linspace(0, 2 * numpy.pi, 64, endpoint=False)
    >>> cycle = symlink.energy_fluctuation(3.0 + 2.0 * numpy.sin(2 * angles))  # E = -cos(2 theta): dE = 2
    >>> round(cycle.mean_torque, 12), round(cycle.energy_fluctuation, 12)
    (3.0, 2.0)
    """
    values = numpy.asarray(torque, dtype=float)
    if values.ndim != 1 or len(values) < 4:
        raise ValueError(f"the torque must be at least 4 equally spaced samples over one cycle, got shape "
                         f"{values.shape}")
    if not numpy.all(numpy.isfinite(values)):
        raise ValueError("the torque must be finite at every sample (can the linkage turn through the whole cycle?)")
    period = _finite(period, "period", positive=True)
    series = _Periodic(values, period)
    angles = numpy.arange(len(values)) * period / len(values)
    energy = series.integral_on_grid(len(values))
    extremes = []
    for index in (int(numpy.argmax(energy)), int(numpy.argmin(energy))):
        x = float(angles[index])
        for _ in range(8):  # Newton on E' = T - T_mean = 0, from the best sample
            curvature = float(series.slope(x))
            if curvature == 0:
                break
            step = float(series.value(x) - series.mean) / curvature
            if abs(step) > period / len(values):
                break  # not converging near this sample: keep the sample
            x -= step
            if abs(step) < 1e-15 * period:
                break
        best = float(series.integral(x))
        sample = float(energy[index])
        extremes.append((x, best) if (best >= sample) == (index == int(numpy.argmax(energy))) else
                        (float(angles[index]), sample))
    (high_angle, high), (low_angle, low) = extremes
    return TorqueCycle(angles, values, series.mean, energy, high - low, (high_angle % period, high),
                       (low_angle % period, low), series)


def flywheel_inertia(energy: float, mean_speed: float, coefficient: float) -> float:
    """``dE / (Cs w^2)``: the inertia that keeps the speed within ``Cs`` of the mean ``w`` (rad/s).

    Parameters
    ----------
    energy : float
        The energy fluctuation ``dE`` over a cycle.
    mean_speed : float
        The mean speed ``w``, rad/s.
    coefficient : float
        The coefficient of speed fluctuation ``Cs``.

    Returns
    -------
    float
        The inertia ``dE / (Cs w^2)``.

    Examples
    --------
    >>> import symlink
    >>> symlink.flywheel_inertia(2.0, 10.0, 0.02)  # 2 / (0.02 * 10^2)
    1.0
    """
    energy = _finite(energy, "energy fluctuation")
    if energy < 0:
        raise ValueError(f"the energy fluctuation must not be negative, got {energy!r}")
    mean_speed = _finite(mean_speed, "mean speed", positive=True)
    coefficient = _finite(coefficient, "coefficient of speed fluctuation", positive=True)
    if coefficient >= 2:
        raise ValueError(f"the coefficient of speed fluctuation must be below 2 (the speed stays positive), "
                         f"got {coefficient!r}")
    return energy / (coefficient * mean_speed * mean_speed)


@dataclass(frozen=True)
class SpeedBand:
    """The input speed over one cycle with a flywheel ``inertia``: its highest and lowest value, their mean
    ``(highest + lowest) / 2`` and the ``coefficient`` ``(highest - lowest) / mean`` achieved, from ``motion``."""

    _repr_html_ = record_html  # a notebook shows the fields as a table

    inertia: float
    highest: float
    lowest: float
    mean: float
    coefficient: float
    motion: Motion | None = field(repr=False, default=None)


class FlywheelSizing:
    """A flywheel for a one-input ``model`` at parameter ``values`` running at ``mean_speed`` (rad/s) with
    speed fluctuation ``coefficient``; see the module docstring.

    ``cycle`` is the :class:`TorqueCycle` of the driving torque at constant speed;
    ``inertia`` the textbook flywheel ``dE / (Cs w^2)`` (the whole inertia on the input shaft).

    Parameters
    ----------
    model : DynamicModel or EquationCode
        A one-input model, or its generated code (:func:`~symlink.dynamics.forward.equation_code`: from the disk
        cache, no SymPy).
    values : mapping of str to float
        Every parameter of its dynamic linkage by name.
    mean_speed : float
        The input's mean speed, rad/s.
    coefficient : float
        The coefficient of speed fluctuation ``Cs = (w_max - w_min) / w_mean``.
    branch : int or mapping of str to int, optional
        The assembly, as for :class:`ForwardDynamics` (default +1).
    samples : int, optional
        Torque samples over the cycle (default 720).

    Examples
    --------
    >>> import symlink
    >>> model = symlink.DynamicModel(symlink.fourbar(), [symlink.MassProperties("crank", "m", distance="r")],
    ...                              gravity=symlink.Gravity(0, -9.81))
    >>> sizing = symlink.FlywheelSizing(model, dict(a=20, b=66, c=56, d=80, m=1.0, r=0.1), mean_speed=10.0,
    ...                                 coefficient=0.02)
    >>> round(sizing.cycle.energy_fluctuation, 9), round(sizing.inertia, 9)  # dE = 2 m g r, I = dE / (Cs w^2)
    (1.962, 0.981)
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    def __init__(self, model: DynamicModel | EquationCode, values: Mapping[str, float], mean_speed: float,
                 coefficient: float, branch: int | Mapping[str, int] = 1, samples: int = 720) -> None:
        self.mean_speed = _finite(mean_speed, "mean speed", positive=True)
        self.coefficient = _finite(coefficient, "coefficient of speed fluctuation", positive=True)
        if isinstance(samples, bool) or not isinstance(samples, int) or samples < 16:
            raise ValueError(f"samples must be a whole number of at least 16, got {samples!r}")
        self.dynamics = ForwardDynamics(model, values, branch)
        code = self.dynamics.code
        if code.effort_name != "input_torque":
            raise ValueError(f"a flywheel turns with a crank; the input of {code.name} is a slider")
        if self.dynamics.takes_speed:
            raise ValueError("the loads depend on speed (a damper): the flywheel sizing needs loads that depend on "
                             "the position only")
        self.samples = samples
        angles = numpy.arange(samples) * 2 * math.pi / samples
        takes = code.arguments_of(code.effort)
        arguments = {name: value for name, value in self.dynamics.values.items() if name in takes}
        motion = {code.input: angles, code.rate: self.mean_speed, code.acceleration: 0.0}
        if code.rate not in takes:  # a torque that no speed changes: nothing moving has mass
            raise ValueError(f"{code.name} has no mass or moment of inertia that moves: a flywheel holds the speed "
                             "of a linkage with inertia (give its bodies masses)")
        with numpy.errstate(invalid="ignore", divide="ignore"):
            found = code.effort(**{name: value for name, value in motion.items() if name in takes}, **arguments)
        if not numpy.all(found["assembled"]):
            first = float(angles[~numpy.asarray(found["assembled"])][0])
            raise ValueError(f"{code.name} cannot be assembled at crank angle {math.degrees(first):.6g} deg: "
                             "the crank does not turn a whole cycle, so there is no flywheel cycle")
        self.cycle = energy_fluctuation(found["input_torque"])
        self._terms: tuple[_Periodic, _Periodic] | None = None
        self._fine: dict[int, tuple[numpy.ndarray, numpy.ndarray]] = {}
        self.inertia = flywheel_inertia(self.cycle.energy_fluctuation, self.mean_speed, self.coefficient)

    @property
    def mean_torque(self) -> float:
        """The mean driving torque over the cycle: the constant torque a motor supplies."""
        return self.cycle.mean_torque

    @property
    def energy_fluctuation(self) -> float:
        return self.cycle.energy_fluctuation

    # --- the speed from energy ------------------------------------------------------------
    def _energy_terms(self) -> tuple[_Periodic, _Periodic]:
        """``M(theta)`` and the work ``integral of (T_mean + Q_applied)`` as periodic series (made once)."""
        if self._terms is None:
            terms = self.dynamics.terms(self.cycle.angles)
            self._terms = (_Periodic(terms["generalised_inertia"] - self.dynamics.input_inertia, 2 * math.pi),
                           _Periodic(self.mean_torque + terms["applied_generalised_force"], 2 * math.pi))
        return self._terms

    def _fine_terms(self, fine: int) -> tuple[numpy.ndarray, numpy.ndarray]:
        """``M`` and the work at ``fine`` times the samples (made once a ``fine``)."""
        if fine not in self._fine:
            inertia_series, work_series = self._energy_terms()
            points = fine * self.samples
            self._fine[fine] = (inertia_series.value_on_grid(points), work_series.integral_on_grid(points))
        return self._fine[fine]

    def _energy_band(self, flywheel: float, fine: int = 8) -> tuple[SpeedBand, float]:
        """The band with ``flywheel`` added from the energy equation, its mean at the mean speed, and its ``C``."""
        optimize = _require_optimize()
        inertia, work = self._fine_terms(fine)
        inertia = flywheel + inertia

        def band(constant: float) -> tuple[float, float]:
            speeds = numpy.sqrt(numpy.maximum(constant + 2 * work, 0.0) / inertia)
            return _refined_max(speeds), -_refined_max(-speeds)

        lowest_constant = float(numpy.max(-2 * work))  # below it the speed would vanish somewhere
        scale = max(abs(lowest_constant), float(numpy.max(inertia)) * self.mean_speed ** 2)
        low, high = lowest_constant, lowest_constant + 4 * scale
        while sum(band(high)) / 2 < self.mean_speed:
            high += 4 * scale
        constant = optimize.brentq(lambda c: sum(band(c)) / 2 - self.mean_speed, low, high, xtol=1e-15 * scale,
                                   rtol=1e-15)
        highest, lowest = band(constant)
        mean = (highest + lowest) / 2
        return SpeedBand(flywheel, highest, lowest, mean, (highest - lowest) / mean), float(constant)

    def speed_from_energy(self, flywheel: float) -> SpeedBand:
        """The speed band with ``flywheel`` added, from the energy equation, its mean set to the mean speed.

        Exact (to the sampling) where the motor torque is constant and the loads depend on the
        position only; needs SciPy (a root of the mean condition).
        """
        flywheel = _finite(flywheel, "flywheel inertia")
        if flywheel < 0:
            raise ValueError(f"the flywheel inertia must not be negative, got {flywheel!r}")
        return self._energy_band(flywheel)[0]

    def exact_inertia(self) -> float:
        """The flywheel to add to the linkage so that the speed band is exactly the coefficient asked for.

        0 when the linkage alone keeps the speed within it.  Needs SciPy.
        """
        optimize = _require_optimize()
        target = self.coefficient

        def excess(flywheel: float) -> float:
            return self.speed_from_energy(flywheel).coefficient - target

        if excess(0.0) <= 0:
            return 0.0
        high = max(self.inertia, 1e-300)
        while excess(high) > 0:
            high *= 2
        return float(optimize.brentq(excess, 0.0, high, xtol=1e-13 * high, rtol=1e-14))

    # --- the check by forward dynamics ------------------------------------------------------
    def speed_band(self, flywheel: float | None = None, rtol: float = 1e-10) -> SpeedBand:
        """The speed over one cycle by integrating the forward dynamics, with ``flywheel`` (default the textbook
        :attr:`inertia`) on the input and a motor holding the mean torque.

        The run starts at angle 0 at the speed that the energy equation gives there for a
        mean speed of ``w`` and lasts one cycle; the band is read from the dense solution.
        """
        flywheel = self.inertia if flywheel is None else _finite(flywheel, "flywheel inertia")
        if flywheel < 0:
            raise ValueError(f"the flywheel inertia must not be negative, got {flywheel!r}")
        _, constant = self._energy_band(flywheel)
        inertia_series, work_series = self._energy_terms()
        points = self.samples  # the start speed, and the time of one cycle, from the energy equation, at the samples
        speeds = numpy.sqrt((constant + 2 * work_series.integral_on_grid(points))
                            / (flywheel + inertia_series.value_on_grid(points)))
        period = float(numpy.mean(1.0 / speeds)) * 2 * math.pi
        parameters = {name: self.dynamics.values[name] for name in self.dynamics.code.parameters}
        dynamics = ForwardDynamics(self.dynamics.code, parameters, _branches(self.dynamics), input_inertia=flywheel)
        motion = dynamics.simulate(0.0, float(speeds[0]), period, ConstantTorque(self.mean_torque), rtol=rtol,
                                   atol=rtol * self.mean_speed)
        if not motion.finished:
            raise ValueError(f"the forward dynamics stopped: {motion.message}")
        times = numpy.arange(8 * self.samples) * period / (8 * self.samples)  # one period of a periodic motion
        simulated = motion.solution.sol(times)[1]
        highest, lowest = _refined_max(simulated), -_refined_max(-simulated)
        mean = (highest + lowest) / 2
        return SpeedBand(flywheel, highest, lowest, mean, (highest - lowest) / mean, motion)


def _branches(dynamics: ForwardDynamics) -> dict[str, int]:
    return {name: int(dynamics.values[name]) for name in dynamics.code.branches}


def _refined_max(values: numpy.ndarray) -> float:
    """The largest of equally spaced samples over one period of a smooth periodic function, refined by the
    parabola through it and its two neighbours."""
    index = int(numpy.argmax(values))
    left, middle, right = values[index - 1], values[index], values[(index + 1) % len(values)]
    denominator = left - 2 * middle + right
    return float(middle - (right - left) ** 2 / (8 * denominator)) if denominator < 0 else float(middle)


def _require_optimize() -> Any:
    require_scipy()
    import scipy.optimize
    return scipy.optimize


def size_flywheel(model: DynamicModel, values: Mapping[str, float], mean_speed: float, coefficient: float,
                  branch: int | Mapping[str, int] = 1, samples: int = 720) -> FlywheelSizing:
    """A :class:`FlywheelSizing` (the textbook numbers at once; the exact inertia and the check on request)."""
    return FlywheelSizing(model, values, mean_speed, coefficient, branch, samples)
