"""The one intermediate form of code generation: a straight-line program with common subexpressions eliminated.

A :class:`~symlink.symbolic.linkage.Program` (the assignments a linkage derives for
some outputs) becomes a :class:`StraightLine`: common subexpressions are
eliminated across everything requested, and the assignments are ordered so
that each uses only arguments and earlier names.  Every printer (NumPy, C,
MATLAB/Octave) prints this same form, so the languages compute the same
thing in the same order.

>>> from symlink.mechanism.catalog import fourbar
>>> code = straight_line(fourbar().program(["rocker"]))
>>> [s.name for s in code.arguments], list(code.outputs), [r.name for r in code.roots]
(['theta', 'a', 'b', 'c', 'd', 'branch'], ['rocker'], ['wsq_1', 'Delta_1'])
"""
from __future__ import annotations

import heapq
import weakref

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Callable

import sympy as sp
from sympy.core.relational import Relational
from sympy.logic.boolalg import BooleanAtom, BooleanFunction

from ..symbolic.linkage import depended_on
from ..symbolic.position import ClampedSqrt, NonzeroSquare

if TYPE_CHECKING:
    from ..symbolic.linkage import Program

__all__ = ["StraightLine", "in_loop_units", "require_loop_units", "straight_line", "named_straight_line", "format_default", "is_flag", "FreshNames", "CSE_PREFIX"]

#: The prefix of the temporaries that common-subexpression elimination introduces.
CSE_PREFIX = "cse_"


@dataclass(frozen=True)
class StraightLine:
    """Program after common-subexpression elimination, ready for any printer.

    ``assignments`` define temporaries and the program's own symbols in an
    order where every right-hand side uses only arguments and earlier names;
    ``outputs`` map output names to expressions of those; ``roots`` are the
    guarded values (clamped square roots, squared lengths that must not
    vanish) whose finiteness says that the linkage is assembled;
    ``defaults`` are the program's argument defaults; ``radii`` map a solved
    angle ``atan2(y, x)`` to ``sqrt(x^2 + y^2)`` where its loop knows that
    length without a square root (:attr:`symlink.symbolic.position.LoopSolution.radii`).
    """

    arguments: tuple[sp.Symbol, ...]
    assignments: tuple[tuple[sp.Symbol, sp.Expr], ...]
    outputs: dict[str, sp.Expr]
    roots: tuple[sp.Symbol, ...]
    defaults: dict[str, float]
    radii: dict[sp.Symbol, sp.Expr] = field(default_factory=dict)


def in_loop_units(program: Program) -> Program:
    """The program as generated code computes it: each closed-form loop in its own units, its roots guarded.

    A linkage's equations are written as a textbook writes them, in its own
    lengths (:attr:`symlink.symbolic.linkage.Linkage.positions`).  Floating point needs
    more: every loop is computed in units of its mean known length (a power of
    two, so the division is exact), which keeps the angles exact from lengths of
    1e-300 to 1e300, and every square root carries the scale that tells
    rounding at a toggle from a loop that cannot close.  This swaps each loop's
    textbook assignments for that form (:attr:`symlink.symbolic.position.LoopSolution.in_loop_units`:
    one square root a loop, ``w`` kept squared where only its square is needed),
    and writes the sines and cosines that vanish at the toggles through the
    loops' roots, so that rates divide by exactly zero there.  Every printer
    (NumPy, C, Octave, scalar Python) prints the result; nothing a user reads shows it.

    >>> from symlink.mechanism.catalog import fourbar
    >>> program = fourbar().program(["rocker"])
    >>> [s.name for s, _ in program.assignments][:3]
    ['Wx_1', 'Wy_1', 'w_1']
    >>> [s.name for s, _ in in_loop_units(program).assignments][:3]
    ['size_1', 'rho_1_1', 'rho_2_1']
    """
    if not program.plan:
        return program
    defined = {s for s, _ in program.assignments}
    loop_code: list[tuple[sp.Symbol, sp.Expr]] = []
    replaced: set[sp.Symbol] = set()
    factors: dict[sp.Expr, sp.Expr] = {}
    for step in program.plan:
        own = set(step.intermediates) | set(step.positions)
        if own & defined:
            code = step.in_loop_units
            loop_code += list(code.intermediates.items()) + list(code.positions.items())
            replaced |= own
            factors.update(code.singular_factors)
    rest = [(s, e.xreplace(factors)) for s, e in program.assignments if s not in replaced]
    outputs = program.outputs
    assignments = loop_code + rest
    # Keep what the outputs need (a loop's code form may define helpers the outputs do not use).
    keep = depended_on({s for e in outputs.values() for s in e.free_symbols}, dict(assignments))
    return replace(program, assignments=tuple((s, e) for s, e in assignments if s in keep), outputs=outputs,
                   plan=())


def require_loop_units(root: ClampedSqrt) -> None:
    """``ValueError`` for a textbook square root in a printer: its program lost the plan that scales it.

    A :class:`~symlink.symbolic.linkage.Program` copied field by field loses its ``plan``;
    ``dataclasses.replace(program, outputs=...)`` keeps it.
    """
    if len(root.args) != 2:
        raise ValueError("a program with textbook square roots but no plan to compute them in loop units; "
                         "copy programs with dataclasses.replace, which keeps their plan")


#: The straight line of each program still alive (by identity): the NumPy module and the C source of one
#: program eliminate its common subexpressions once between them (SymPy's own cache, of a fixed number of
#: entries, no longer holds a large program's work by the time the second printer asks).
_STRAIGHT_LINES: dict[int, StraightLine] = {}


def straight_line(program: Program) -> StraightLine:
    """Eliminate common subexpressions across the program's assignments and outputs (in loop units).

    The result is kept while ``program`` lives, so that every printer of one program shares one elimination
    (its time grows a little faster than the program).
    """
    key = id(program)
    if key in _STRAIGHT_LINES:
        return _STRAIGHT_LINES[key]
    code = _eliminated(program)
    try:
        weakref.finalize(program, _STRAIGHT_LINES.pop, key, None)
    except TypeError:  # an object without weak references: not kept
        return code
    _STRAIGHT_LINES[key] = code
    return code


def _eliminated(program: Program) -> StraightLine:
    """:func:`straight_line`, computed."""
    radii = {angle: radius for step in program.plan for angle, radius in step.in_loop_units.radii.items()}
    program = in_loop_units(program)
    names = [s for s, _ in program.assignments]
    output_names = list(program.outputs)
    expressions = [e for _, e in program.assignments] + [program.outputs[n] for n in output_names]
    taken = {s.name for s in program.arguments} | {s.name for s in names}
    temporaries = (sp.Symbol(f"{CSE_PREFIX}{i}", real=True) for i in range(10**9)
                   if f"{CSE_PREFIX}{i}" not in taken)
    replacements, reduced = sp.cse(expressions, symbols=temporaries, order="none")
    nodes = list(replacements) + list(zip(names, reduced[:len(names)]))
    outputs = dict(zip(output_names, reduced[len(names):]))
    roots = tuple(s for s, e in program.assignments if isinstance(e, (ClampedSqrt, NonzeroSquare)))
    # The radii of the angles the program computes, in the names it defines (a loop's rho and wsq).
    defined = set(names) | set(program.arguments)
    radii = {angle: radius for angle, radius in radii.items() if angle in defined and radius.free_symbols <= defined}
    return StraightLine(program.arguments, _dependency_order(nodes), outputs, roots, dict(program.defaults), radii)


def _dependency_order(nodes: list[tuple[sp.Symbol, sp.Expr]]) -> tuple[tuple[sp.Symbol, sp.Expr], ...]:
    """Order assignments so that each one's symbols are defined before it (stable: of the assignments whose
    symbols are all defined, the first in ``nodes`` comes next).

    Each assignment's free symbols are found once and the ready ones kept in a heap by position, so the
    order costs n log n, not the n^2 of scanning from the start for each (a chain of 16 four-bars has
    thousands of assignments).

    >>> x, y, z = sp.symbols("x y z")
    >>> _dependency_order([(z, x + y), (y, 2 * x), (x, sp.Integer(1))])
    ((x, 1), (y, 2*x), (z, x + y))
    """
    position = {symbol: index for index, (symbol, _) in enumerate(nodes)}
    waiting_for = [0] * len(nodes)
    needed_by: dict[int, list[int]] = {}
    for index, (_, expr) in enumerate(nodes):
        for symbol in expr.free_symbols:
            if symbol in position:
                waiting_for[index] += 1
                needed_by.setdefault(position[symbol], []).append(index)
    ready = [index for index, count in enumerate(waiting_for) if count == 0]
    heapq.heapify(ready)
    ordered = []
    while ready:
        index = heapq.heappop(ready)
        ordered.append(nodes[index])
        for dependent in needed_by.get(index, ()):
            waiting_for[dependent] -= 1
            if waiting_for[dependent] == 0:
                heapq.heappush(ready, dependent)
    if len(ordered) != len(nodes):
        raise ValueError("circular definitions in generated code")
    return tuple(ordered)


def named_straight_line(program: Program, name: str, identifier: Callable[[str, str], str],
                        language: str) -> tuple[StraightLine, list[str]]:
    """The program after CSE and its argument names, checked by ``identifier`` for ``language``.

    ``ValueError`` for a name the language cannot take or a program without outputs.
    """
    identifier(name, "function name")
    if not program.outputs:
        raise ValueError(f"{name}: a {language} function needs at least one output")
    code = straight_line(program)
    return code, [identifier(s.name, "argument") for s in code.arguments]


def format_default(value: float) -> str:
    """An argument default as code (Python and MATLAB alike): 1 for a branch, 0.0 for a rate.

    >>> format_default(1.0), format_default(0.0)
    ('1', '0.0')
    """
    return str(int(value)) if value == 1 else repr(value)  # branch=1, thetadot=0.0


def is_flag(expr: sp.Basic) -> bool:
    """Whether an output is true/false (a comparison or a logical combination) rather than a number.

    >>> x = sp.Symbol("x")
    >>> is_flag(sp.Eq(x, 0)), is_flag(sp.false), is_flag(x)
    (True, True, False)
    """
    return isinstance(expr, (Relational, BooleanFunction, BooleanAtom))


class FreshNames:
    """Names for new temporaries that collide neither with each other, nor with ``taken``, nor with ``reserved`` words.

    >>> fresh = FreshNames({"x"}, reserved={"x_"})
    >>> fresh("x"), fresh("x"), fresh("y")
    ('x__', 'x___', 'y')
    """

    def __init__(self, taken, reserved=frozenset()):
        self.taken = set(taken)
        self.reserved = reserved

    def __call__(self, wanted: str) -> str:
        name = wanted
        while name in self.taken or name in self.reserved:
            name += "_"
        self.taken.add(name)
        return name
