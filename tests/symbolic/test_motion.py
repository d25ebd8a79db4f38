"""Rates and accelerations by projection, against a direct linear solve of the differentiated closure."""
import random

import sympy as sp

from symlink.symbolic.loops import Loop
from symlink.symbolic.motion import loop_rates
from symlink.symbolic.vectors import Vector, acceleration, coordinates, lengths, rate, time_derivative


def direct_solution(loop, unknowns, coords, order):
    """Solve the time-differentiated closure (a 2x2 linear system) with sympy.linsolve."""
    x, y = loop.equations()
    for _ in range(order):
        x, y = time_derivative(x, coords), time_derivative(y, coords)
    target = [rate(u) if order == 1 else acceleration(u) for u in unknowns]
    (solution,) = sp.linsolve([x, y], target)
    return dict(zip(target, solution))


def check(loop, unknowns, coords, values):
    for order in (1, 2):
        ours = loop_rates(loop, unknowns, coords, order)
        theirs = direct_solution(loop, unknowns, coords, order)
        numbers = dict(values)
        if order == 2:  # the accelerations use the rates: substitute ours (checked at order 1)
            numbers.update({k: v.subs(values) for k, v in loop_rates(loop, unknowns, coords, 1).items()})
        for symbol in ours:
            assert abs(float(ours[symbol].subs(numbers)) - float(theirs[symbol].subs(numbers))) < 1e-12


def test_fourbar_angles():
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, d = lengths("a b c d")
    loop = Loop(Vector(d, 0) + Vector(c, phi) - Vector(b, beta) - Vector(a, theta))
    values = {a: 1.1, b: 2.3, c: 1.7, d: 2.9, theta: 0.4, beta: 0.9, phi: 2.1,
              rate(theta): 1.3, acceleration(theta): -0.7}
    check(loop, [beta, phi], [theta, beta, phi], values)


def test_slider_length_and_angle_with_offsets():
    theta, beta, s = coordinates("theta beta s")
    a, b, e = lengths("a b e")
    loop = Loop(Vector(a, theta) + Vector(b, beta + sp.pi / 3) - Vector(s + e, 0.25) - Vector(e, sp.pi / 2))
    values = {a: 1.0, b: 3.0, e: 0.4, theta: 1.0, beta: -0.3, s: 2.2, rate(theta): 2.0, acceleration(theta): 0.5}
    check(loop, [s, beta], [theta, beta, s], values)


def test_length_and_angle_of_one_vector():
    theta, r, psi = coordinates("theta r psi")
    a, d = lengths("a d")
    loop = Loop(Vector(a, theta) - Vector(r, psi) - Vector(d, 0))
    values = {a: 1.0, d: 2.0, theta: 0.7, r: 1.5, psi: 2.5, rate(theta): -1.0, acceleration(theta): 2.0}
    check(loop, [r, psi], [theta, r, psi], values)


def test_two_lengths_with_a_moving_guide():
    theta, p, q = coordinates("theta p q")
    a, = lengths("a")
    loop = Loop(Vector(a, theta) - Vector(p, theta / 2) - Vector(q, 1.2))
    rng = random.Random(0)
    values = {a: 2.0, theta: 0.3, p: rng.uniform(1, 2), q: rng.uniform(1, 2),
              rate(theta): 0.8, acceleration(theta): 0.1}
    check(loop, [p, q], [theta, p, q], values)
