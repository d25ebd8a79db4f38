r"""The seed papers' own forms of a linkage's solution, for teaching from them (never used for numbers).

symlink solves a loop with two unknown angles (case 3) with ``atan2`` and
Heron's root (:mod:`symlink.symbolic.position`): finite and exact up to the toggles.
The papers write the same solution in other forms, and a reader teaching from
one of them can ask for it (``linkage.equations(form=...)``):

* ``"complex"`` (seed 000): each loop as a sum of complex vectors,
  :math:`\sum_k s_k r_k e^{i t_k} = 0`.
* ``"freudenstein"`` (seed 002): the other unknown eliminated, the loop becomes
  a relation between cosines of angle differences; divided by the coefficient of
  the cosine that couples the unknown to the first moving known vector, its other
  coefficients are the constants :math:`K_1, K_2, \dots` (for the four-bar,
  Freudenstein's :math:`K_1 \cos\phi - K_2 \cos\theta + K_3 = \cos(\theta - \phi)`).
* ``"half-angle"`` (seed 003): the same equation in :math:`t = \tan(x/2)`,
  :math:`A t^2 + B t + C = 0`, solved as :math:`x = 2\,\mathrm{atan2}(-B + s\sqrt{B^2 - 4AC}, 2A)`,
  where the sign :math:`s` is the loop's branch for its first unknown and minus the
  branch for its second (the branch rule of :mod:`symlink.symbolic.position`).

Derivation: with the known part :math:`K = \sum_{\text{known}} s_k r_k e^{i t_k} = -W`,
unknown vectors :math:`P = s_p r_p e^{i t_p}` and :math:`Q`, the closure
:math:`K + P + Q = 0` gives :math:`|K + P|^2 = r_q^2`, i.e.
:math:`a \cos t_p + b \sin t_p + c = 0` with :math:`a = -2 s_p r_p W_x`,
:math:`b = -2 s_p r_p W_y`, :math:`c = w^2 + r_p^2 - r_q^2`; then
:math:`A = c - a`, :math:`B = 2b`, :math:`C = c + a`.

>>> from symlink.mechanism.catalog import fourbar
>>> rows = seed_form_rows(fourbar(), "half-angle")
>>> [str(lhs) for lhs, _ in rows][3:7]
['A_beta', 'B_beta', 'C_beta', 'A_beta*tan(beta/2)**2 + B_beta*tan(beta/2) + C_beta']
"""
from __future__ import annotations

from typing import Mapping, Protocol, Sequence

import sympy as sp

from .loops import Loop, LoopCase, Unknown
from .position import LoopSolution
from .typeset import written_in_order


class Linkage(Protocol):
    """What the forms read of a :class:`symlink.symbolic.linkage.Linkage` (named here so that the two modules do not import each other)."""

    @property
    def loops(self) -> Sequence[Loop]: ...

    @property
    def plan(self) -> Sequence[LoopSolution]: ...

    @property
    def positions(self) -> Mapping[sp.Symbol, sp.Expr]: ...

    @property
    def coordinates(self) -> Sequence[sp.Symbol]: ...

__all__ = ["FORMS", "SEED_FORM_TITLES", "seed_form_rows", "half_angle_solution", "freudenstein_equation"]

#: The forms ``Linkage.equations(form=...)`` takes: symlink's own and the seeds'.
FORMS = ("atan2", "complex", "freudenstein", "half-angle")

#: What each form is called in a document's heading.
SEED_FORM_TITLES = {"atan2": "atan2 form", "complex": "complex-number form",
                    "freudenstein": "Freudenstein form", "half-angle": "tangent half-angle form"}


def _named(step: LoopSolution, prefix: str) -> sp.Symbol:
    return next(s for s in step.intermediates if s.name == f"{prefix}_{step.label}")


def _roles(case: LoopCase) -> tuple[tuple[Unknown, Unknown, int], ...]:
    """Each unknown angle with the other unknown and the sign of its branch (``+1`` first, ``-1`` second)."""
    return ((case.first, case.second, 1), (case.second, case.first, -1))


def _cosine_equation(step: LoopSolution, unknown: Unknown, other: Unknown) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """``(a, b, c)`` of ``a cos t + b sin t + c = 0`` for the unknown's vector angle ``t`` (the other eliminated)."""
    wx, wy, w = (_named(step, name) for name in ("Wx", "Wy", "w"))
    rp, rq = unknown.vector.length, other.vector.length
    return -2 * unknown.sign * rp * wx, -2 * unknown.sign * rp * wy, w**2 + rp**2 - rq**2


def half_angle_solution(step: LoopSolution) -> tuple[list[tuple[sp.Expr, sp.Expr]], dict[sp.Symbol, sp.Expr]]:
    """Seed 003's rows for a case-3 loop (coefficients, quadratic, solution) and the solution of each unknown.

    The solutions use the loop's intermediates ``Wx_k, Wy_k, w_k`` (see
    :attr:`symlink.symbolic.linkage.Linkage.positions`) and its branch.
    """
    rows: list[tuple[sp.Expr, sp.Expr]] = []
    solutions: dict[sp.Symbol, sp.Expr] = {}
    branch = step.branch if step.branch is not None else sp.S.One
    for unknown, other, sign in _roles(step.case):
        a, b, c = _cosine_equation(step, unknown, other)
        name = unknown.symbol.name
        big_a, big_b, big_c = (sp.Symbol(f"{letter}_{name}", real=True) for letter in "ABC")
        angle = unknown.vector.angle
        half = sp.tan(angle / 2)
        root = sp.sqrt(written_in_order(sp.Add(big_b**2, -4 * big_a * big_c, evaluate=False)))  # B^2 - 4AC
        value = 2 * sp.atan2(-big_b + sign * branch * root, 2 * big_a) - unknown.offset
        rows += [(big_a, c - a), (big_b, 2 * b), (big_c, c + a),
                 (big_a * half**2 + big_b * half + big_c, sp.S.Zero), (unknown.symbol, value)]
        solutions[unknown.symbol] = value.xreplace({big_a: c - a, big_b: 2 * b, big_c: c + a})
    return rows, solutions


def freudenstein_equation(step: LoopSolution, linkage: Linkage) -> list[tuple[sp.Expr, sp.Expr]]:
    """Seed 002's rows for a case-3 loop: the constants ``K_j`` and each unknown's cosine relation.

    The other unknown is eliminated from ``|K + P|^2 = r_q^2``, the cosines of
    angle differences are collected and the relation is divided by the coefficient
    of the cosine that couples the unknown to the first known vector that moves.
    """
    rows: list[tuple[sp.Expr, sp.Expr]] = []
    moving = set(linkage.coordinates)
    for unknown, other, _ in _roles(step.case):
        terms = [(sign, vector) for sign, vector in step.case.known] + [(unknown.sign, unknown.vector)]
        relation = sum((vector.length**2 for _, vector in terms), sp.S.Zero) - other.vector.length**2
        cosines: dict[sp.Expr, sp.Expr] = {}
        for i, (sign_i, vector_i) in enumerate(terms):
            for sign_j, vector_j in terms[i + 1:]:
                difference = vector_i.angle - vector_j.angle
                if sp.cos(difference).could_extract_minus_sign():
                    difference = -difference
                cosines[difference] = cosines.get(difference, sp.S.Zero) + 2 * sign_i * sign_j * vector_i.length * vector_j.length
        anchor = next((sp.Add(vector.angle, -unknown.vector.angle) for _, vector in step.case.known
                       if vector.angle.free_symbols & moving), None)
        key = next((d for d in cosines if anchor is not None and (d - anchor == 0 or d + anchor == 0)), None)
        if key is None:
            continue
        scale = -cosines.pop(key)
        left = sp.S.Zero
        # Freudenstein's order: the unknown's own cosines, then the others, then the constant.
        ordered = sorted(cosines.items(), key=lambda item: unknown.symbol not in item[0].free_symbols)
        for number, (difference, coefficient) in enumerate(ordered + [(None, relation)], start=1):
            # K_{\phi,1}: the unknown's own LaTeX (a Greek letter as Greek), as a textbook prints it
            constant = sp.Symbol(f"K_{{{sp.latex(unknown.symbol)},{number}}}", real=True)
            rows.append((constant, sp.factor_terms(coefficient / scale)))
            left += constant * (sp.cos(difference) if difference is not None else 1)
        rows.append((left, sp.cos(key)))
    return rows


def seed_form_rows(linkage: Linkage, form: str) -> list[tuple[sp.Expr, sp.Expr]]:
    """The rows ``lhs = rhs`` of ``linkage``'s solution in one of :data:`FORMS` (``atan2``: its positions).

    Loops that are not case 3 (two unknown angles) have no other form and show their closed forms.
    ``ValueError`` for an unknown form.

    >>> from symlink.mechanism.catalog import fourbar
    >>> rows = seed_form_rows(fourbar(), "freudenstein")
    >>> for lhs, rhs in rows[-4:]:
    ...     print(lhs, "=", rhs)
    K_{\\phi,1} = d/a
    K_{\\phi,2} = -d/c
    K_{\\phi,3} = (a**2 - b**2 + c**2 + d**2)/(2*a*c)
    K_{\\phi,1}*cos(phi) + K_{\\phi,2}*cos(theta) + K_{\\phi,3} = cos(phi - theta)
    """
    if form not in FORMS:
        raise ValueError(f"no form {form!r}; the forms are {', '.join(FORMS)}")
    if form == "atan2":
        return list(linkage.positions.items())
    if form == "complex":
        rows = []
        for loop in linkage.loops:
            terms = [sign * vector.length * sp.exp(sp.I * vector.angle) for sign, vector in loop.vectors.terms]
            rows.append((sp.Add(*terms, evaluate=False), sp.S.Zero))
        return rows
    rows = []
    for step in linkage.plan:
        own = [(s, e) for s, e in step.intermediates.items() if s.name.split("_")[0] in ("Wx", "Wy", "w")]
        if step.case.name != "3":
            rows += list(step.intermediates.items()) + list(step.positions.items())
        elif form == "half-angle":
            rows += own + half_angle_solution(step)[0]
        else:
            rows += own + freudenstein_equation(step, linkage)
    return rows
