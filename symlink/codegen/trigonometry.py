"""Sines and cosines of solved angles without calling them: the ``atan2`` arguments and the addition theorems.

A solved angle ``q = atan2(y, x)`` has ``cos q = x/r`` and ``sin q = y/r`` with
``r = sqrt(x*x + y*y)``: a square root and a division instead of two calls of
the math library, each as costly as a dozen multiplications.  Full kinematics
need the sines and cosines of the unknown angles and of their differences
(``cos(beta - phi)``, ``sin(theta - phi)``); :func:`angle_sums` rewrites a
straight-line program so that it computes them from those quotients and the
angles it already knows, so that full kinematics call ``sin``, ``cos`` and
``atan2`` no more often than positions do.  The NumPy and C printers both print
the rewritten program (``CosineOfAtan2`` and ``SineOfAtan2`` are their two new
functions); the values agree with the calls to a few units in the last place.

>>> from symlink.mechanism.catalog import fourbar
>>> from symlink.codegen.program import straight_line
>>> code = straight_line(fourbar().program(["coupler_speed"]))
>>> calls = lambda code: sorted({str(f.func) for _, e in code.assignments for f in e.atoms(sp.sin, sp.cos, sp.atan2)})
>>> calls(code), calls(angle_sums(code, set()))
(['atan2', 'cos', 'sin'], ['cos', 'sin'])
"""
from __future__ import annotations

import sympy as sp

from .program import FreshNames, StraightLine, _dependency_order

__all__ = ["CosineOfAtan2", "SineOfAtan2", "angle_sums"]


class CosineOfAtan2(sp.Function):
    """``cos(atan2(y, x))`` given ``(x, r)`` with ``r = sqrt(x*x + y*y)``: ``x/r``, and atan2's ``copysign(1, x)`` at ``r = 0``."""


class SineOfAtan2(sp.Function):
    """``sin(atan2(y, x))`` given ``(y, r)`` with ``r = sqrt(x*x + y*y)``: ``y/r``, and ``y`` (a signed zero) at ``r = 0``."""


def _linear_form(expr: sp.Expr, definitions: dict) -> dict | None:
    """``expr`` as ``{atom: integer coefficient}`` of a sum, following names defined as sums; ``None`` with a constant term."""
    form: dict = {}

    def add(term: sp.Expr, factor: int) -> bool:
        if term in definitions and (definitions[term].is_Add or definitions[term].is_Mul):
            coefficient, _ = definitions[term].as_coeff_Mul()
            if definitions[term].is_Add or (coefficient.is_Integer and coefficient != 1):
                return add(definitions[term], factor)
        if term.is_Add:
            return all(add(part, factor) for part in term.args)
        if term.is_Mul:
            coefficient, rest = term.as_coeff_Mul()
            if coefficient.is_Integer and coefficient != 1:
                return add(rest, factor * int(coefficient))
        if term.is_Number:
            return False
        form[term] = form.get(term, 0) + factor
        return True

    return {atom: k for atom, k in form.items() if k} if add(expr, 1) else None


def angle_sums(code: StraightLine, taken: set[str]) -> StraightLine:
    """The program with every ``sin`` and ``cos`` it can spare written as sums of angles it already knows.

    Full kinematics call ``sin`` and ``cos`` of the unknown angles and of their
    differences (``cos(beta - phi)``), each as costly as a square root and a
    division or two: about as many calls again as the positions make.  Every
    unknown angle ``q = atan2(y, x)`` has ``cos q = x/r`` and ``sin q = y/r``
    with ``r = sqrt(x*x + y*y)``; an angle whose ``sin`` and ``cos`` are both
    called (the input ``theta``, a coupler angle ``alpha + phi``) is a known
    pair.  A ``sin`` or ``cos`` of a sum of these with coefficients +1 and -1
    is then expanded by the addition theorems, so that full kinematics cost
    no more calls than positions.  The values agree with the calls to a few
    units in the last place of the pair (the angle differences themselves
    round that much).  ``taken`` holds names the new temporaries must avoid.
    """
    definitions = dict(code.assignments)
    angles = {s: e for s, e in code.assignments if isinstance(e, sp.atan2)}
    calls: set = set()
    for expr in [*definitions.values(), *code.outputs.values()]:
        calls |= expr.atoms(sp.sin, sp.cos)
    if not angles or not calls:
        return code
    linear = {call.args[0]: _linear_form(call.args[0], definitions) for call in calls}
    forms: dict[sp.Expr, dict] = {argument: form for argument, form in linear.items() if form}
    called = {(call.func, call.args[0]) for call in calls}
    # The known pairs, each with its rank: the largest sums first (of equal sums, the later known first); and
    # each atom, the known pairs whose sums hold it, so that a sum is matched against the pairs that share its
    # atoms, not against all of them (a chain of n loops knows pairs in proportion to n).
    rank: dict = {}
    holding: dict = {}

    def know(pair) -> None:
        rank[pair] = -len(rank)
        for atom in forms[pair]:
            holding.setdefault(atom, []).append(pair)

    def parts(form: dict) -> list | None:
        """``form`` as known pairs and unknown angles, each +1 or -1 times; ``None`` where it is not."""
        remaining, found = dict(form), []
        candidates = {pair for atom in form for pair in holding.get(atom, ())}
        for pair in sorted(candidates, key=rank.__getitem__):  # largest first
            for sign in (1, -1):
                if all(remaining.get(atom) == sign * k for atom, k in forms[pair].items()):
                    for atom in forms[pair]:
                        del remaining[atom]
                    found.append((pair, sign))
                    break
        if any(atom not in angles or abs(k) != 1 for atom, k in remaining.items()):
            return None
        return found + sorted(remaining.items(), key=lambda item: sp.default_sort_key(item[0]))

    # A pair is known unless it is itself a sum of smaller known pairs and unknown angles (beta - theta).
    for argument in sorted((argument for argument in forms
                            if (sp.sin, argument) in called and (sp.cos, argument) in called),
                           key=lambda argument: (len(forms[argument]), sp.default_sort_key(argument))):
        if parts(forms[argument]) is None:
            know(argument)

    names = FreshNames(taken | {s.name for s in code.arguments} | {s.name for s, _ in code.assignments})
    added: list = []
    known: dict = {}  # an angle or pair -> (its sine, its cosine) as symbols

    def sine_cosine(element) -> tuple[sp.Symbol, sp.Symbol]:
        if element not in known:
            stem = element.name if isinstance(element, sp.Symbol) else "angle"
            if element in angles:
                y, x = angles[element].args
                parts_ = []
                for role, value in (("y", y), ("x", x)):
                    if not isinstance(value, sp.Symbol):
                        symbol = sp.Symbol(names(f"{stem}_{role}"), real=True)
                        added.append((symbol, value))
                        value = symbol
                    parts_.append(value)
                y, x = parts_
                definitions[element] = sp.atan2(y, x)
                radius = sp.Symbol(names(f"{stem}_r"), real=True)
                # The length of (x, y): known to its loop without a square root where it says so.
                added.append((radius, code.radii.get(element, sp.sqrt(x**2 + y**2))))
                values = (SineOfAtan2(y, radius), CosineOfAtan2(x, radius))
            else:
                values = (sp.sin(element), sp.cos(element))
            sine, cosine = sp.Symbol(names(f"sin_{stem}"), real=True), sp.Symbol(names(f"cos_{stem}"), real=True)
            added.extend([(sine, values[0]), (cosine, values[1])])
            known[element] = (sine, cosine)
        return known[element]

    sums: dict = {}  # a tuple of (element, sign) -> (sine, cosine) of their sum

    def sum_of(terms: tuple) -> tuple[sp.Expr, sp.Expr]:
        if terms not in sums:
            element, sign = terms[-1]
            sine, cosine = sine_cosine(element)
            if len(terms) == 1:
                sums[terms] = (sign * sine, cosine)
            else:
                before_sine, before_cosine = sum_of(terms[:-1])
                if len(terms) > 2:  # the partial sum before: named, as other sums may share it
                    named = sp.Symbol(names("sin_sum"), real=True), sp.Symbol(names("cos_sum"), real=True)
                    added.extend(zip(named, (before_sine, before_cosine)))
                    before_sine, before_cosine = named
                sums[terms] = (before_sine * cosine + sign * before_cosine * sine,
                               before_cosine * cosine - sign * before_sine * sine)
        return sums[terms]

    replacements = {}
    for call in sorted(calls, key=sp.default_sort_key):
        argument = call.args[0]
        form = forms.get(argument)
        if not form or argument in rank:
            continue
        found = parts(form)
        if found is None:
            continue
        sine, cosine = sum_of(tuple(found))
        replacements[call] = sine if call.func is sp.sin else cosine
    if not replacements:
        return code
    calls_made = {}  # the known pairs' own calls, made once under their names
    for element, (sine, cosine) in known.items():
        if element not in angles:
            calls_made.update({sine: sp.sin(element), cosine: sp.cos(element)})
            replacements.update({sp.sin(element): sine, sp.cos(element): cosine})
    rewritten = [(s, definitions[s].xreplace(replacements)) for s, _ in code.assignments]
    outputs = {name: expr.xreplace(replacements) for name, expr in code.outputs.items()}
    nodes = [(s, calls_made.get(s, e.xreplace(replacements))) for s, e in added] + rewritten
    needed = set(code.roots).union(*(e.free_symbols for e in outputs.values()))
    kept = []
    for symbol, expr in reversed(_dependency_order(nodes)):
        if symbol in needed:
            kept.append((symbol, expr))
            needed |= expr.free_symbols
    return StraightLine(code.arguments, tuple(reversed(kept)), outputs, code.roots, code.defaults, code.radii)
