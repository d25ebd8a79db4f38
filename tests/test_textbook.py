"""The equations a user reads are the textbook's: the linkage's own symbols, no numeric plumbing.

Expected forms come from the geometry written out here (the four-bar's loop, Heron's formula,
Freudenstein's equation as seed 002 prints it, the half-angle quadratic of seed 003), never from
symlink's output.
"""
from __future__ import annotations

import math
import random

import numpy
import pytest
import sympy as sp

from symlink.mechanism.catalog import CATALOG, fourbar, jansen, watt2
from symlink.codegen.latex import latex_document
from symlink.symbolic.position import ClampedSqrt
from symlink.symbolic.seed_forms import half_angle_solution, seed_form_rows

CLOSED_FORM = [name for name in CATALOG if CATALOG[name]().has_closed_form]


def named(linkage, name):
    return next(s for s in linkage.positions if s.name == name)


def test_fourbar_positions_are_the_textbook_solution():
    linkage = fourbar()
    a, b, c, d = linkage.parameters
    theta, = linkage.inputs
    branch, = linkage.branches
    wx, wy, w, delta = (named(linkage, n) for n in ("Wx_1", "Wy_1", "w_1", "Delta_1"))
    beta, phi = linkage.unknowns
    positions = linkage.positions
    # The crank pin B = a e^{i theta}, the rocker pivot D = d: the coupler and rocker close W = B - D.
    assert sp.expand(positions[wx] - (a * sp.cos(theta) - d)) == 0
    assert sp.expand(positions[wy] - a * sp.sin(theta)) == 0
    assert positions[w] == sp.sqrt(wx**2 + wy**2)
    # Heron: the triangle of sides b, c, w; its area is Delta/4.
    heron = (b + c + w) * (b + c - w) * (w + b - c) * (w + c - b)
    assert sp.expand(positions[delta].args[0] - heron) == 0 and len(positions[delta].args) == 1
    allowed = {a, b, c, d, theta, branch, wx, wy, w, delta}
    for expr in positions.values():
        assert expr.free_symbols <= allowed
    # Numbers: C = B + b e^{i beta} = D + c e^{i phi}, C left of B->D for branch +1.
    for sign in (1, -1):
        values = {a: 20.0, b: 66.0, c: 56.0, d: 80.0, theta: 0.7, branch: sign}
        known = dict(values)
        for symbol, expr in positions.items():
            known[symbol] = expr.subs(known).evalf(30)
        pin_b = 20.0 * complex(math.cos(0.7), math.sin(0.7))
        joint_c = pin_b + 66.0 * complex(math.cos(float(known[beta])), math.sin(float(known[beta])))
        assert abs(joint_c - (80.0 + 56.0 * complex(math.cos(float(known[phi])), math.sin(float(known[phi]))))) < 1e-12
        cross = ((80.0 - pin_b).conjugate() * (joint_c - pin_b)).imag  # > 0: C left of the line B -> D
        assert numpy.sign(cross) == sign


@pytest.mark.parametrize("name", CLOSED_FORM)
def test_no_numeric_plumbing_in_what_a_user_reads(name):
    linkage = CATALOG[name]()
    sets = [linkage.positions, linkage.velocities, linkage.accelerations,
            linkage.sensitivities(linkage.parameters[0])]
    for equations in sets:
        for symbol, expr in equations.items():
            assert not expr.atoms(sp.Float), (symbol, expr)
            assert not expr.atoms(sp.floor) and not expr.atoms(sp.log), (symbol, expr)
            assert not [p for p in expr.atoms(sp.Pow) if p.base == 2], (symbol, expr)
            assert not symbol.name.startswith(("size_", "rho_")), symbol
        assert hasattr(equations, "_repr_latex_")


@pytest.mark.parametrize("make", [fourbar, watt2, jansen], ids=["fourbar", "watt2", "jansen"])
def test_latex_has_no_units_of_scale(make):
    text = latex_document(make(), "t")
    for plumbing in ("size", "\\rho", "\\lfloor", "\\log", "e-294", "e-14"):
        assert plumbing not in text, plumbing


def test_a_linkage_file_derives_textbook_latex(tmp_path):
    from symlink.io.linkage_file import load_linkage
    from symlink.io.export import export_texts
    files = sorted(p for p in __import__("pathlib").Path(__file__).resolve().parents[1].glob("**/fourbar.toml")
                   if ".ci" not in p.parts)
    if not files:
        pytest.skip("no fourbar.toml linkage file in this checkout")
    linkage = load_linkage(str(files[0])).linkage
    text, = export_texts(linkage, "latex").values()
    assert "\\rho" not in text and "size" not in text and "W_{x,1}" in text


def _random_fourbar(rng: random.Random, sign: int):
    """Lengths that assemble at the crank angle drawn (rejection sampling), well away from the toggles."""
    while True:
        a, b, c, d = (rng.uniform(0.2, 5.0) for _ in range(4))
        theta = rng.uniform(-math.pi, math.pi)
        w = math.hypot(a * math.cos(theta) - d, a * math.sin(theta))
        if abs(b - c) + 1e-3 < w < b + c - 1e-3:
            return theta, a, b, c, d, sign  # the call signature's order


@pytest.mark.parametrize("sign", [1, -1])
def test_the_seeds_forms_equal_the_atan2_form(sign):
    """Seed 003's half-angle solution and seed 002's Freudenstein equation agree with the atan2 form (1000 linkages)."""
    linkage = fourbar()
    a, b, c, d = linkage.parameters
    theta, = linkage.inputs
    branch, = linkage.branches
    beta, phi = linkage.unknowns
    step = linkage.plan[0]
    _, half_angle = half_angle_solution(step)
    arguments = [theta, a, b, c, d, branch]
    intermediates = [(s, e) for s, e in linkage.positions.items() if s not in (beta, phi)]

    def compiled(expr):
        for symbol, definition in reversed(intermediates):
            expr = expr.xreplace({symbol: definition})
        expr = expr.replace(ClampedSqrt, lambda x: sp.sqrt(x))  # [x]_+: positive away from the toggles
        return sp.lambdify(arguments, expr, "math")
    atan2_beta, atan2_phi = compiled(linkage.positions[beta]), compiled(linkage.positions[phi])
    half_beta, half_phi = compiled(half_angle[beta]), compiled(half_angle[phi])
    rng = random.Random(20 + sign)
    for _ in range(1000):
        values = _random_fourbar(rng, sign)
        for exact, seed in ((atan2_beta, half_beta), (atan2_phi, half_phi)):
            difference = exact(*values) - seed(*values)
            assert abs(math.remainder(difference, 2 * math.pi)) < 1e-12, values
        # Freudenstein (seed 002): K1 cos(phi) - K2 cos(theta) + K3 = cos(theta - phi) with
        # K1 = d/a, K2 = d/c, K3 = (a^2 - b^2 + c^2 + d^2)/(2 a c), at the atan2 solution.
        theta_, a_, b_, c_, d_, _ = values
        phi_ = atan2_phi(*values)
        k1, k2, k3 = d_ / a_, d_ / c_, (a_**2 - b_**2 + c_**2 + d_**2) / (2 * a_ * c_)
        assert abs(k1 * math.cos(phi_) - k2 * math.cos(theta_) + k3 - math.cos(theta_ - phi_)) < 1e-12 * (1 + k1 + k2 + abs(k3))


def test_the_freudenstein_rows_are_seed_002s_constants():
    linkage = fourbar()
    a, b, c, d = linkage.parameters
    rows = dict(seed_form_rows(linkage, "freudenstein"))
    constants = {str(k): v for k, v in rows.items() if str(k).startswith("K_{\\phi")}
    assert sp.simplify(constants["K_{\\phi,1}"] - d / a) == 0
    assert sp.simplify(constants["K_{\\phi,2}"] + d / c) == 0
    assert sp.simplify(constants["K_{\\phi,3}"] - (a**2 - b**2 + c**2 + d**2) / (2 * a * c)) == 0


def test_forms_are_named_and_checked():
    linkage = fourbar()
    assert "tan" in linkage.equations(form="half-angle")._repr_latex_()
    assert "e^{i \\theta}" in linkage.equations(form="complex")._repr_latex_()
    with pytest.raises(ValueError, match="no form 'tangent'"):
        linkage.equations(form="tangent")


def test_dynamics_outputs_display_as_maths_in_the_linkages_symbols():
    """Joint forces and the equation of motion are equations too: shown as LaTeX, no numeric plumbing."""
    from symlink.dynamics.inverse import equation_of_motion, reactions
    from symlink.dynamics.model import BodyTorque, DynamicModel, MassProperties
    model = DynamicModel(fourbar(), [MassProperties("coupler", "m_3", "r_3", "delta_3", "I_3")],
                         [BodyTorque("rocker", "T_4")])
    for equations in (reactions(model), equation_of_motion(model)):
        assert equations._repr_latex_().startswith("$\\displaystyle")
        for expr in equations.values():
            assert not expr.atoms(sp.floor) and not expr.atoms(sp.log) and not expr.atoms(sp.Float)
            assert not {s.name for s in expr.free_symbols} & {"size_1", "rho_1_1"}
