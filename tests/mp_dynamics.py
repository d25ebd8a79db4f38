"""50-digit references for the dynamics tests, written by hand without symlink's dynamics.

Each case types out, with mpmath, its linkage's closure (from mp_closures), a
geometric first guess of the unknowns on branch +1, and for every moving body the
origin of its frame and its angle (the documented frame of
``symlink.dynamics.model``).  From these the tests build their own centres of mass,
kinetic and potential energy, and take time derivatives by ``mpmath.diff`` along
the prescribed input motion ``x(t) = x0 + x' t + x'' t^2 / 2``, the unknowns' rates and
accelerations from mp_closures.kinematics (linear solves of the differentiated closure):
nothing is shared with the symbolic derivation.
"""
from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Callable

import mpmath as mp

from mp_closures import DPS, circle_point, kinematics, fivebar_closure, fourbar_closure, slider_closure, watt2_closure, \
    watt2_positions, fivebar_positions


@dataclass
class Case:
    """A catalog linkage as the tests see it: closure, guess, bodies (origin point name, origin, angle)."""

    name: str
    inputs: list[str]
    unknowns: list[str]
    closure: Callable
    guess: Callable  # (x, p) -> unknowns on branch +1
    bodies: dict  # body -> (origin point name, (x, q, p) -> complex origin, (x, q, p) -> angle)
    points: dict  # point name -> (x, q, p) -> complex position
    parameters: dict


def fourbar_guess(x, p):
    B, D = p["a"] * mp.expj(x[0]), mp.mpf(p["d"])
    C = circle_point(B, p["b"], D, p["c"], 1)
    return [mp.arg(C - B), mp.arg(C - D)]


def slider_guess(x, p):
    a, b, offset = p["a"], p["b"], p["offset"]
    s = a * mp.cos(x[0]) + mp.sqrt(b * b - (offset - a * mp.sin(x[0])) ** 2)
    return [mp.atan2(offset - a * mp.sin(x[0]), s - a * mp.cos(x[0])), s]


def fourbar_case() -> Case:
    B = lambda x, q, p: p["a"] * mp.expj(x[0])  # noqa: E731
    C = lambda x, q, p: B(x, q, p) + p["b"] * mp.expj(q[0])  # noqa: E731
    D = lambda x, q, p: mp.mpc(p["d"], 0)  # noqa: E731
    return Case("fourbar", ["theta"], ["beta", "phi"], fourbar_closure, fourbar_guess,
                {"crank": ("A", lambda x, q, p: mp.mpc(0), lambda x, q, p: x[0]),
                 "coupler": ("B", B, lambda x, q, p: q[0]),
                 "rocker": ("D", D, lambda x, q, p: q[1])},
                {"A": lambda x, q, p: mp.mpc(0), "B": B, "C": C, "D": D},
                dict(a=1.0, b=3.0, c=2.5, d=3.2))


def slider_case() -> Case:
    B = lambda x, q, p: p["a"] * mp.expj(x[0])  # noqa: E731
    C = lambda x, q, p: mp.mpc(q[1], p["offset"])  # noqa: E731
    return Case("slider-crank", ["theta"], ["beta", "s"], slider_closure, slider_guess,
                {"crank": ("A", lambda x, q, p: mp.mpc(0), lambda x, q, p: x[0]),
                 "conrod": ("B", B, lambda x, q, p: q[0]),
                 "slider": ("C", C, lambda x, q, p: mp.mpf(0))},
                {"A": lambda x, q, p: mp.mpc(0), "B": B, "C": C, "AS": lambda x, q, p: mp.mpc(q[1], 0)},
                dict(a=1.3, b=4.1, offset=0.7))


def watt2_case() -> Case:
    B = lambda x, q, p: p["a"] * mp.expj(x[0])  # noqa: E731
    C = lambda x, q, p: B(x, q, p) + p["b"] * mp.expj(q[0])  # noqa: E731
    D = lambda x, q, p: mp.mpc(p["d"], 0)  # noqa: E731
    E = lambda x, q, p: p["d"] + p["e"] * mp.expj(q[1] + p["alpha"])  # noqa: E731
    F = lambda x, q, p: E(x, q, p) + p["f"] * mp.expj(q[2])  # noqa: E731
    G = lambda x, q, p: mp.mpc(p["gx"], p["gy"])  # noqa: E731
    return Case("watt2", ["theta"], ["beta", "phi", "mu", "psi"], watt2_closure,
                lambda x, p: watt2_positions(x, p, (1, 1)),
                {"crank": ("A", lambda x, q, p: mp.mpc(0), lambda x, q, p: x[0]),
                 "coupler": ("B", B, lambda x, q, p: q[0]),
                 "rocker": ("D", D, lambda x, q, p: q[1]),
                 "coupler2": ("E", E, lambda x, q, p: q[2]),
                 "output": ("G", G, lambda x, q, p: q[3])},
                {"A": lambda x, q, p: mp.mpc(0), "B": B, "C": C, "D": D, "E": E, "F": F, "G": G},
                dict(a=1.0, alpha=0.6, b=3.5, c=3.0, d=3.2, e=2.0, f=4.0, g=3.0, gx=4.5, gy=3.5))


def fivebar_case() -> Case:
    B = lambda x, q, p: p["a"] * mp.expj(x[0])  # noqa: E731
    C = lambda x, q, p: B(x, q, p) + p["b"] * mp.expj(q[0])  # noqa: E731
    E = lambda x, q, p: mp.mpc(p["d"], 0)  # noqa: E731
    D = lambda x, q, p: p["d"] + p["e"] * mp.expj(x[1])  # noqa: E731
    return Case("fivebar", ["theta", "psi"], ["beta", "phi"], fivebar_closure,
                lambda x, p: fivebar_positions(x, p, 1),
                {"crank": ("A", lambda x, q, p: mp.mpc(0), lambda x, q, p: x[0]),
                 "coupler": ("B", B, lambda x, q, p: q[0]),
                 "crank2": ("E", E, lambda x, q, p: x[1]),
                 "coupler2": ("D", D, lambda x, q, p: q[1])},
                {"A": lambda x, q, p: mp.mpc(0), "B": B, "C": C, "D": D, "E": E},
                dict(a=2.0, b=4.0, c=4.0, d=3.0, e=2.0))


CASES = {"fourbar": fourbar_case, "slider-crank": slider_case, "watt2": watt2_case, "fivebar": fivebar_case}


class Motion:
    """The prescribed input motion and the unknowns along it, at 50 digits; positions memoised by t."""

    def __init__(self, case: Case, p: dict, x0, xdot, xddot) -> None:
        self.case, self.p = case, {k: mp.mpf(v) for k, v in p.items()}
        self.x0, self.xdot, self.xddot = ([mp.mpf(v) for v in values] for values in (x0, xdot, xddot))
        with mp.workdps(DPS):
            guess = [mp.mpf(v) for v in case.guess(self.x0, self.p)]
            self.q0, self.qdot, self.qddot, _ = kinematics(case.closure, self.x0, guess, self.p, self.xdot,
                                                          self.xddot)

    def x(self, t):
        return [x0 + v * t + a * t * t / 2 for x0, v, a in zip(self.x0, self.xdot, self.xddot)]

    def q(self, t):
        """The unknowns along the quadratic path with the true position, rate and acceleration at t = 0.

        Every first and second time derivative at t = 0 of a function of the coordinates
        is then exact, and so is the first derivative of one of their rates."""
        return [q + v * t + a * t * t / 2 for q, v, a in zip(self.q0, self.qdot, self.qddot)]

    def point(self, function: Callable, t):
        return function(self.x(t), self.q(t), self.p)

    def centre(self, body: str, distance, angle, t):
        _, origin, turn = self.case.bodies[body]
        x, q = self.x(t), self.q(t)
        return origin(x, q, self.p) + distance * mp.expj(turn(x, q, self.p) + angle)

    def body_angle(self, body: str, t):
        _, _, turn = self.case.bodies[body]
        return turn(self.x(t), self.q(t), self.p)


def derivative(function: Callable, order: int = 1):
    """d^order/dt^order at t = 0 of a real or complex function of t, at 50 digits."""
    with mp.workdps(DPS):
        value = function(mp.mpf(0))
        if isinstance(value, mp.mpc):
            return mp.mpc(mp.diff(lambda t: mp.re(function(t)), 0, order), mp.diff(lambda t: mp.im(function(t)), 0, order))
        return mp.diff(function, 0, order)


def random_masses(case: Case, rng: random.Random) -> dict:
    """body -> (mass, distance, angle, inertia), random and well away from zero."""
    return {body: (rng.uniform(0.5, 2.0), rng.uniform(0.1, 1.5), rng.uniform(-3, 3), rng.uniform(0.05, 0.8))
            for body in case.bodies}
