"""Loops: closure equations and the four cases of seeds/000."""
import pytest
import sympy as sp

from symlink.symbolic.loops import Loop
from symlink.symbolic.vectors import Vector, coordinates, lengths

R1, R2, R3, R4 = lengths("R1 R2 R3 R4")
t1, t2, t3, t4 = coordinates("t1 t2 t3 t4")


def paper_loop():
    """z1 + z2 + z3 + z4 = 0, all symbolic."""
    return Loop(Vector(R1, t1) + Vector(R2, t2) + Vector(R3, t3) + Vector(R4, t4), name="z")


@pytest.mark.parametrize("unknowns, case", [
    ((R3, R4), "1"), ((R3, t3), "2a"), ((t3, R3), "2a"), ((R4, t3), "2b"), ((t3, R4), "2b"), ((t3, t4), "3"),
])
def test_cases_of_the_position_paper(unknowns, case):
    assert paper_loop().case(list(unknowns)).name == case


def test_closure_equations_are_the_real_and_imaginary_parts():
    x, y = paper_loop().equations()
    z = sum(R * sp.exp(sp.I * t) for R, t in ((R1, t1), (R2, t2), (R3, t3), (R4, t4)))
    assert sp.expand(x - sp.re(sp.expand_complex(z))) == 0
    assert sp.expand(y - sp.im(sp.expand_complex(z))) == 0


def test_three_unknowns_are_refused():
    with pytest.raises(ValueError, match="3 unknowns"):
        paper_loop().case([R3, R4, t3])


def test_unknown_turning_two_vectors_at_different_rates_is_refused():
    theta, = coordinates("theta")
    loop = Loop(Vector(R1, theta) + Vector(R2, 2 * theta) + Vector(R3, t3))
    with pytest.raises(ValueError, match="appears in 2 vectors"):
        loop.case([theta, t3])


def test_vectors_turning_together_combine_into_one():
    theta, = coordinates("theta")
    loop = Loop(Vector(R1, theta) + Vector(R2, theta + 1) + Vector(R3, t3) + Vector(R4, 0))
    case = loop.case([theta, t3])
    assert case.name == "3"
    combined = case.first.vector
    # R1 + R2 e^{i} as one vector: its length and its angle past theta.
    assert sp.simplify(combined.length**2 - (R1**2 + R2**2 + 2 * R1 * R2 * sp.cos(1))) == 0
    assert sp.simplify(case.first.offset - sp.atan2(R2 * sp.sin(1), R1 + R2 * sp.cos(1))) == 0


def test_length_on_the_turning_body_is_case_2c():
    theta, s = coordinates("theta s")
    loop = Loop(Vector(R1, t1) - Vector(s, theta) - Vector(R2, theta + sp.pi / 2) - Vector(R3, 0))
    case = loop.case([theta, s])
    assert case.name == "2c" and case.branches == 2
    assert [v for _, v in case.turning] == [Vector(R2, theta + sp.pi / 2)]


def test_unknown_inside_a_function_is_refused():
    loop = Loop(Vector(R1, sp.sin(t1)) + Vector(R2, t2) + Vector(R3, 0))
    with pytest.raises(ValueError, match="up to a known offset"):
        loop.case([t1, t2])


def test_angle_with_known_offset_is_accepted():
    loop = Loop(Vector(R1, t1 + sp.pi / 2) + Vector(R2, t2) + Vector(R3, 0))
    case = loop.case([t1, t2])
    assert case.name == "3" and case.first.offset == sp.pi / 2
