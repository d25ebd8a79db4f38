"""Planar vectors: components, sums, and time derivatives by the chain rule."""
import sympy as sp

from symlink.symbolic.vectors import Vector, acceleration, coordinates, lengths, rate, time_derivative


def test_components_follow_length_and_angle():
    a, = lengths("a")
    theta, = coordinates("theta")
    v = Vector(a, theta)
    assert v.x == a * sp.cos(theta) and v.y == a * sp.sin(theta)


def test_sum_and_difference_keep_signed_terms():
    theta, beta = coordinates("theta beta")
    a, b = lengths("a b")
    AB, BC = Vector(a, theta, "AB"), Vector(b, beta, "BC")
    total = AB - BC
    assert [s for s, _ in total.terms] == [1, -1]
    assert sp.expand(total.x - (a * sp.cos(theta) - b * sp.cos(beta))) == 0
    assert [s for s, _ in (-total).terms] == [-1, 1]
    assert str(total) == "AB - BC"


def test_numeric_vector_components():
    v = Vector(2, sp.pi / 2)
    assert (v.x, v.y) == (0, 2)


def test_time_derivative_chain_rule_twice():
    theta, = coordinates("theta")
    a, = lengths("a")
    x = a * sp.cos(theta)
    first = time_derivative(x, [theta])
    assert sp.expand(first + a * sp.sin(theta) * rate(theta)) == 0
    second = time_derivative(first, [theta])
    expected = -a * sp.cos(theta) * rate(theta) ** 2 - a * sp.sin(theta) * acceleration(theta)
    assert sp.expand(second - expected) == 0


def test_time_derivative_matches_sympy_functions_of_time():
    # Independent check: the same derivative with SymPy's own Function(t).diff(t).
    t = sp.Symbol("t")
    q, r = sp.Function("q")(t), sp.Function("r")(t)
    theta, s = coordinates("theta s")
    expr = s**2 * sp.sin(2 * theta) + sp.cos(theta) * s
    ours = time_derivative(time_derivative(expr, [theta, s]), [theta, s])
    theirs = expr.subs({theta: q, s: r}).diff(t, 2)
    theirs = theirs.subs({q.diff(t, 2): acceleration(theta), r.diff(t, 2): acceleration(s)})
    theirs = theirs.subs({q.diff(t): rate(theta), r.diff(t): rate(s)}).subs({q: theta, r: s})
    assert sp.expand(ours - theirs) == 0


def test_text_is_never_parsed():
    import pytest
    with pytest.raises(ValueError, match="not text"):
        Vector("__import__('os').system('true')", 0)
    with pytest.raises(ValueError, match="not text"):
        time_derivative("a*cos(theta)", [])
