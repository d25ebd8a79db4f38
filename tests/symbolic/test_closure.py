"""The symbolic closure system: residuals, Jacobian and rate systems, against hand derivations."""
import pytest
import sympy as sp

from symlink.mechanism.catalog import fivebar, fourbar, slider_crank, stephenson2
from symlink.symbolic.closure import closure_system, is_angle
from symlink.symbolic.vectors import acceleration, rate


def test_fourbar_against_the_hand_derivation():
    # The catalog closes the four-bar as d + c e^{i phi} - b e^{i beta} - a e^{i theta} = 0.
    linkage = fourbar()
    system = closure_system(linkage)
    theta, beta, phi = linkage.coordinates
    a, b, c, d = (sp.Symbol(n, positive=True) for n in "abcd")
    w, al = rate(theta), acceleration(theta)
    wb, wc = rate(beta), rate(phi)
    residuals = [d + c * sp.cos(phi) - b * sp.cos(beta) - a * sp.cos(theta),
                 c * sp.sin(phi) - b * sp.sin(beta) - a * sp.sin(theta)]
    jacobian = sp.Matrix([[b * sp.sin(beta), -c * sp.sin(phi)], [-b * sp.cos(beta), c * sp.cos(phi)]])
    # d/dt F = J qdot + (dF/dtheta) thetadot = 0, and once more for the accelerations.
    velocity = [-a * w * sp.sin(theta), a * w * sp.cos(theta)]
    accel = [-a * w**2 * sp.cos(theta) - a * al * sp.sin(theta) - b * wb**2 * sp.cos(beta) + c * wc**2 * sp.cos(phi),
             -a * w**2 * sp.sin(theta) + a * al * sp.cos(theta) - b * wb**2 * sp.sin(beta) + c * wc**2 * sp.sin(phi)]
    for got, want in zip(list(system.residuals) + list(system.velocity_rhs) + list(system.acceleration_rhs),
                         residuals + velocity + accel):
        assert sp.simplify(got - want) == 0
    assert sp.simplify(system.jacobian - jacobian) == sp.zeros(2, 2)
    assert system.scales == (a + b + c + d,) * 2 and system.units == (1, 1)


def test_stephenson2_jacobian_has_the_symbolic_structure():
    system = closure_system(stephenson2())
    beta, mu, phi, eta = stephenson2().unknowns
    assert system.jacobian[0, 3] == 0 and system.jacobian[2, 1] == 0   # eta is not in ABCFD, mu not in ABEHD
    assert sp.simplify(system.jacobian[2, 2] - sp.Symbol("h", positive=True) * sp.sin(
        phi + sp.Symbol("delta", real=True))) == 0


def test_a_slider_unknown_gets_a_length_unit():
    linkage = slider_crank()
    system = closure_system(linkage)
    s = linkage.unknowns[1]
    a, b = (sp.Symbol(n, positive=True) for n in ("a", "b"))
    offset = sp.Symbol("offset", real=True)  # either side of the crank pivot
    # The slider's travel is measured in the loop's mean vector length: (a + b + |s| + |offset|) / 4.
    assert system.units[0] == 1
    assert sp.simplify(system.units[1] - (a + b + sp.Abs(s) + sp.Abs(offset)) / 4) == 0
    assert s.name == "s" and not is_angle(linkage, s)


@pytest.mark.parametrize("make, expected", [
    (fourbar, {"theta": True, "beta": True, "phi": True}),
    (slider_crank, {"theta": True, "beta": True, "s": False}),
    (fivebar, {"theta": True, "psi": True, "beta": True, "phi": True}),
])
def test_is_angle(make, expected):
    linkage = make()
    assert {q.name: is_angle(linkage, q) for q in linkage.coordinates} == expected
