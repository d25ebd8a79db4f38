"""Closed forms of the four cases, both branches, against loops built closed by construction.

Each example draws a random closed loop z1 + z2 + z3 + z4 = 0 (z4 is made to
close it), hides two of its eight values, and asks symlink for them: one of
the branches must give back the hidden values exactly, and every branch must
close the loop.
"""
import cmath
import math

import numpy
import pytest
import sympy as sp
from hypothesis import given, settings, strategies as st

from mp_closures import offset_inverted_positions
from symlink.symbolic.linkage import Linkage
from symlink.symbolic.loops import Loop
from symlink.symbolic.position import ClampedSqrt
from symlink.numeric.solver import Solver
from symlink.symbolic.vectors import Vector, coordinates, lengths

NAMES = ("R1", "R2", "R3", "R4", "t1", "t2", "t3", "t4")
HIDDEN = {"1": ("R3", "R4"), "2a": ("R3", "t3"), "2b": ("R4", "t3"), "2b'": ("t2", "R4"), "3": ("t3", "t4"),
          "3'": ("t4", "t2")}


def solve_numerically(values: dict, hidden: tuple[str, str]) -> list[dict]:
    """Every branch's values of the hidden pair, through the generated NumPy code."""
    symbols = {n: (coordinates(n)[0] if n in hidden or n.startswith("t") else lengths(n)[0]) for n in NAMES}
    loop = Loop(sum((Vector(symbols[f"R{k}"], symbols[f"t{k}"]) for k in (2, 3, 4)),
                    Vector(symbols["R1"], symbols["t1"]).as_sum()))
    linkage = Linkage("z", [loop], inputs=[], unknowns=[symbols[h] for h in hidden])
    solver = Solver(linkage, list(hidden))
    known = {n: v for n, v in values.items() if n not in hidden}
    signs = [1, -1] if linkage.branches else [None]
    found = []
    for sign in signs:
        result = solver(**known, **({"branch": sign} if sign else {}))
        assert bool(result["assembled"])
        found.append({h: float(result[h]) for h in hidden})
    return found


def closure_residual(values: dict) -> float:
    return abs(sum(values[f"R{k}"] * cmath.exp(1j * values[f"t{k}"]) for k in (1, 2, 3, 4)))


def angle_distance(x: float, y: float) -> float:
    return abs(math.remainder(x - y, 2 * math.pi))


closed_loops = st.tuples(
    st.floats(0.5, 5), st.floats(0.5, 5), st.floats(0.5, 5),
    st.floats(-math.pi, math.pi), st.floats(-math.pi, math.pi), st.floats(-math.pi, math.pi),
).map(lambda p: _close(*p)).filter(lambda v: v["R4"] > 0.1)


def _close(r1, r2, r3, t1, t2, t3):
    z4 = -(r1 * cmath.exp(1j * t1) + r2 * cmath.exp(1j * t2) + r3 * cmath.exp(1j * t3))
    return dict(R1=r1, R2=r2, R3=r3, R4=abs(z4), t1=t1, t2=t2, t3=t3, t4=cmath.phase(z4))


@pytest.mark.parametrize("case", sorted(HIDDEN))
@settings(max_examples=60, deadline=None, derandomize=True)
@given(values=closed_loops)
def test_every_case_recovers_the_hidden_values(case, values):
    hidden = HIDDEN[case]
    if case.startswith("1"):  # two lengths need non-parallel directions
        if abs(math.sin(values["t4"] - values["t3"])) < 0.05:
            return
    if case.startswith("2b"):  # the angle's own vector must not be nearly along the length's vector
        length, angle = (h for h in sorted(hidden, key=lambda n: n[0] == "t"))
        if abs(math.cos(values["t" + angle[1]] - values["t" + length[1]])) < 0.05:
            return
    if case.startswith("3"):  # away from the flat triangle (toggle)
        first, second = hidden
        if abs(math.sin(values[first] - values[second])) < 0.05:
            return
    solutions = solve_numerically(values, hidden)
    scale = max(values[f"R{k}"] for k in (1, 2, 3, 4))
    errors = []
    for solution in solutions:
        candidate = {**values, **solution}
        assert closure_residual(candidate) < 1e-12 * scale * 10
        errors.append(max(abs(solution[h] - values[h]) / scale if h[0] == "R" else angle_distance(solution[h], values[h])
                          for h in hidden))
    assert min(errors) < 1e-11


def test_case_2b_branch_plus_one_is_the_larger_length():
    values = _close(1.0, 2.0, 1.5, 0.3, 2.0, -1.0)
    plus, minus = solve_numerically(values, ("R4", "t3"))
    assert plus["R4"] > minus["R4"]


def test_case_3_branch_plus_one_turns_the_first_vector_counter_clockwise_from_w():
    values = _close(1.0, 2.0, 1.5, 0.3, 2.0, -1.0)
    plus, minus = solve_numerically(values, ("t3", "t4"))
    w = -(values["R1"] * cmath.exp(1j * values["t1"]) + values["R2"] * cmath.exp(1j * values["t2"]))
    for solution, sign in ((plus, 1), (minus, -1)):
        turn = math.remainder(solution["t3"] - cmath.phase(w), 2 * math.pi)
        assert math.copysign(1, turn) == sign


def test_seed000_worked_example_case_1():
    # seeds/000 eq. 12-13: R3 = 800.0158, R4 = 894.4019 (its angles are given to 3 decimals).
    values = dict(R1=300, t1=math.radians(270), R2=640.3124, t2=math.radians(308.663),
                  t3=math.radians(180), t4=math.radians(63.435))
    (solution,) = solve_numerically({**values, "R3": 0, "R4": 0}, ("R3", "R4"))
    assert round(solution["R3"], 4) == 800.0158
    assert round(solution["R4"], 4) == 894.4019


def test_clamped_sqrt_rounding_and_no_assembly():
    assert ClampedSqrt(sp.Float(-1e-15), 1) == 0
    assert ClampedSqrt(sp.Float(-1e-3), 1) is sp.nan
    assert ClampedSqrt(9, 100) == 3
    x, s = sp.symbols("x s")
    assert sp.diff(ClampedSqrt(x, s), x) == 1 / (2 * ClampedSqrt(x, s))


def test_unreachable_loop_is_reported_not_garbage():
    values = dict(R1=1.0, t1=0.0, R2=1.0, t2=0.0, R3=0.1, R4=0.1)  # 2 + 0.1 + 0.1 cannot close
    symbols = {n: (coordinates(n)[0] if n.startswith("t") else lengths(n)[0]) for n in NAMES}
    loop = Loop(sum((Vector(symbols[f"R{k}"], symbols[f"t{k}"]) for k in (2, 3, 4)),
                    Vector(symbols["R1"], symbols["t1"]).as_sum()))
    solver = Solver(Linkage("z", [loop], inputs=[], unknowns=[symbols["t3"], symbols["t4"]]), ["t3"])
    result = solver(**values, branch=1)
    assert not bool(result["assembled"]) and numpy.isnan(result["t3"])


def test_seed003_fourbar_gives_the_same_angles_at_any_scale():
    """a, b, c, d = 20, 66, 56, 80 scaled by 1e-300 ... 1e300: the same angles as at unit scale, lengths scaled back.

    The scaled inputs are themselves rounded, so bit equality is not expected; measured (73 angles, both
    branches, every 25th power of ten): angles within 2 ulps of max(|angle|, 1) (9 ulps of a coupler angle
    near zero, in its own ulps), points within 2.5 ulps of 86, the largest coordinate."""
    from symlink.mechanism.catalog import fourbar
    solver = Solver(fourbar(), ["beta", "phi", "C_x", "C_y"])
    theta = numpy.linspace(-numpy.pi, numpy.pi, 73)
    for branch in (1, -1):
        unit = solver(theta=theta, a=20.0, b=66.0, c=56.0, d=80.0, branch=branch)
        assert unit["assembled"].all()
        for exponent in range(-300, 301, 25):
            k = 10.0 ** exponent
            scaled = solver(theta=theta, a=20 * k, b=66 * k, c=56 * k, d=80 * k, branch=branch)
            assert scaled["assembled"].all(), exponent
            for name in ("beta", "phi"):
                ulps = numpy.abs(scaled[name] - unit[name]) / numpy.spacing(numpy.maximum(numpy.abs(unit[name]), 1.0))
                assert ulps.max() <= 4, (exponent, name, ulps.max())
            for name in ("C_x", "C_y"):
                ulps = numpy.abs(scaled[name] / k - unit[name]) / numpy.spacing(86.0)
                assert ulps.max() <= 4, (exponent, name, ulps.max())


@pytest.mark.parametrize("branch", [1, -1])
def test_offset_inverted_slider_crank_in_closed_form_against_mpmath(branch):
    import mpmath as mp
    theta, phi, s = coordinates("theta phi s")
    a, d, e = lengths("a d e")
    loop = Loop(Vector(a, theta) - Vector(d, 0) - Vector(s, phi) - Vector(e, phi + sp.pi / 2), name="ABD")
    linkage = Linkage("offset inverted slider-crank", [loop], [theta], [phi, s])
    assert linkage.plan[0].case.name == "2c"
    solver = Solver(linkage, ["phi", "s", "phidot", "sdot", "phiddot", "sddot"])
    values = dict(a=1.0, d=2.5, e=0.4)
    omega, alpha = 1.7, -0.6
    for angle in numpy.linspace(-3.0, 3.0, 13):
        got = solver(theta=angle, branch=branch, thetadot=omega, thetaddot=alpha, **values)
        assert bool(got["assembled"])
        with mp.workdps(50):
            position = lambda t, k: offset_inverted_positions(t, 1, mp.mpf(5) / 2, mp.mpf(2) / 5, branch)[k]  # noqa: E731
            t0 = mp.mpf(float(angle))
            for k, name in ((0, "s"), (1, "phi")):
                exact = position(t0, k)
                first, second = mp.diff(lambda t: position(t, k), t0, 1), mp.diff(lambda t: position(t, k), t0, 2)
                expected = {name: exact, name + "dot": first * omega,
                            name + "ddot": second * omega**2 + first * alpha}
                for key, value in expected.items():
                    difference = float(got[key]) - float(value)
                    if name == "phi" and key == "phi":
                        difference = math.remainder(difference, 2 * math.pi)
                    assert abs(difference) <= 1e-13 * (1 + abs(float(value))), (angle, key, float(got[key]), float(value))
