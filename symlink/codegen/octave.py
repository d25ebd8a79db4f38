"""MATLAB/Octave export: one vectorised ``.m`` function file per output set.

The body is the same common-subexpression-eliminated straight-line code as the
NumPy module (:func:`symlink.codegen.program.straight_line`), printed element-wise
(``.*``, ``./``, ``.^``), so one call evaluates whole arrays of crank angles,
or of link lengths: the arguments are scalars or arrays whose sizes broadcast
(implicit expansion, MATLAB R2016b and later, GNU Octave).  The function
returns the outputs in order and then ``assembled``, false where the linkage
cannot be assembled (the outputs are NaN there).

The clamped square root is ``sqrt(max(x, 0)) + 0 ./ (x >= -tol*scale)``: the
root of x where it is not negative, 0 where it is negative only by rounding,
and 0/0 = NaN below the threshold (or where x is NaN), exactly as the NumPy
module's ``_clamped_sqrt``; also for a guard (negative scale), whose threshold
is positive.

>>> from symlink.mechanism.catalog import fourbar
>>> text = octave_function(fourbar().program(["rocker"]), "fourbar_rocker", "Rocker angle (rad).")
>>> print(text.splitlines()[0])
function [rocker, assembled] = fourbar_rocker(theta, a, b, c, d, branch)
>>> "atan2(" in text and ".*" in text
True
"""
from __future__ import annotations

import textwrap
from typing import TYPE_CHECKING, Sequence

import sympy as sp
from sympy.printing.octave import OctaveCodePrinter

from ..version import __version__
from ..symbolic.linkage import is_branch_name
from ..common.names import OCTAVE_KEYWORDS, PLAIN_NAME
from ..common.rounding import TOLERANCE
from .numpy import ARGUMENT_CONTRACT
from .program import require_loop_units, format_default, is_flag, named_straight_line

if TYPE_CHECKING:
    from ..symbolic.linkage import Linkage, Program

__all__ = ["octave_function", "octave_identifier", "comment_lines", "export_files"]

#: MATLAB's longest name.
_LONGEST = 63


def octave_identifier(name: str, what: str = "name") -> str:
    """``name`` if MATLAB and Octave take it as a variable or function name; ``ValueError`` otherwise.

    >>> octave_identifier("Wx_1")
    'Wx_1'
    """
    if not PLAIN_NAME.match(name) or len(name) > _LONGEST or name in OCTAVE_KEYWORDS:
        raise ValueError(f"{what} {name!r} is not usable as a MATLAB/Octave name "
                         "(a letter, then up to 62 letters, digits or underscores; not a keyword)")
    return name


def comment_lines(text: str) -> list[str]:
    """The lines of ``text`` for ``%`` comments: no line break of any kind (nor other control character) left in one.

    >>> comment_lines("First.\\rSecond.\\u2028Third.")
    ['First.', 'Second.', 'Third.']
    """
    return ["".join(c if c.isprintable() else " " for c in line) for line in text.strip().splitlines()]


class _OctavePrinter(OctaveCodePrinter):
    """Element-wise Octave printer with symlink's clamped square root and exact double literals."""

    def __init__(self):
        super().__init__({"allow_unknown_functions": False})

    def _print_Symbol(self, expr):
        return octave_identifier(expr.name, "symbol")

    def _print_Float(self, expr):
        return repr(float(expr))

    def _print_NumberSymbol(self, expr):  # pi as a literal, safe from a variable named pi
        return repr(float(expr))

    _print_Pi = _print_NumberSymbol

    def _print_PowerOfTwoBelow(self, expr):  # a loop's unit; any power of two near x scales exactly
        return f"pow2(floor(log2({self._print(expr.args[0])})))"

    def _print_ClampedSqrt(self, expr):  # inline: a function file holds one function
        require_loop_units(expr)
        x, scale = (self._print(a) for a in expr.args)
        # + 0/flag, not ./flag: a guard (negative scale) fails for a positive x, and sqrt(x)/0 is Inf, not NaN
        return f"(sqrt(max({x}, 0)) + 0 ./ (({x}) >= {-TOLERANCE!r} .* ({scale})))"

    def _print_NonzeroSquare(self, expr):  # x, and NaN (0/0) where x is below smallest
        x, smallest = (self._print(a) for a in expr.args)
        return f"(({x}) + 0 ./ (({x}) >= {smallest}))"

    def _print_Piecewise(self, expr):  # pragma: no cover - a guard, never reached by symlink's own forms
        raise ValueError("symlink never writes Piecewise into generated code")


def _arguments_behind(code, expr: sp.Expr) -> set[sp.Symbol]:
    """The arguments that an expression depends on, through the assignments."""
    definitions = dict(code.assignments)
    found, stack, seen = set(), list(expr.free_symbols), set()
    while stack:
        symbol = stack.pop()
        if symbol in seen:
            continue
        seen.add(symbol)
        if symbol in definitions:
            stack += list(definitions[symbol].free_symbols)
        else:
            found.add(symbol)
    return found & set(code.arguments)


def _argument_checks(symbols: Sequence[sp.Symbol], arguments: Sequence[str]) -> list[str]:
    """One line an argument: ``error()`` naming it unless it is real, finite, and a positive length or a sign."""
    lines = []
    for symbol, argument in zip(symbols, arguments):
        real = f"isnumeric({argument}) && isreal({argument})"
        if is_branch_name(argument):
            test, wanted = f"all(abs({argument}(:)) == 1)", "must be +1 or -1"
        elif symbol.is_positive:
            test, wanted = f"all({argument}(:) > 0 & {argument}(:) < Inf)", "must be a positive finite length"
        else:
            test, wanted = f"all(isfinite({argument}(:)))", "must be finite real numbers"
        lines.append(f"  if ~({real} && {test}), error('symlink:argument', '{argument} {wanted}'); end")
    return lines


def octave_function(program: Program, name: str, doc: str = "") -> str:
    """The text of ``<name>.m``: one vectorised function computing the program's outputs, then ``assembled``."""
    code, arguments = named_straight_line(program, name, octave_identifier, "MATLAB/Octave")
    printer = _OctavePrinter()
    taken = set(arguments) | {octave_identifier(s.name, "symbol") for s, _ in code.assignments} | {name}
    variables = []
    for output in code.outputs:
        variable = octave_identifier(output, "output")
        while variable in taken or variable in ("assembled", "shape"):
            variable += "_out"
        taken.add(variable)
        variables.append(variable)
    assembled, shape = ("assembled", "shape")
    results = ", ".join(variables + [assembled])
    call = f"[{results}] = {name}({', '.join(arguments)})"
    defaults = [(i, s.name, format_default(code.defaults[s.name])) for i, s in enumerate(code.arguments, 1)
                if s.name in code.defaults]
    described = comment_lines(doc)
    summary = described[0] if described else f"Outputs {', '.join(code.outputs)} of a linkage."
    help_lines = [f"%{name.upper()} {summary}", f"%   {call}"] + [f"%   {line}" for line in described[1:]]
    help_lines += [
        "%   evaluates element-wise: the arguments are scalars or arrays of sizes that",
        "%   broadcast. assembled is false where the linkage cannot close (the outputs are",
        "%   NaN there). Angles in radians."]
    if defaults:
        help_lines.append("%   Defaults: " + ", ".join(f"{arg} = {value}" for _, arg, value in defaults) + ".")
    renamed = [f"{v} is {o}" for v, o in zip(variables, code.outputs) if v != o]
    if renamed:
        help_lines.append("%   Output names: " + ", ".join(renamed) + ".")
    help_lines += ["%   The arguments are checked (an error naming the argument):"]
    help_lines += [f"%   {line}" for line in textwrap.wrap(ARGUMENT_CONTRACT + ".", 80)]
    help_lines += ["%", f"%   Generated by symlink {__version__} with SymPy {sp.__version__}; do not edit."]
    lines = [f"function {call}"] + help_lines
    for position, argument, value in defaults:
        lines += [f"  if nargin < {position}", f"    {argument} = {value};", "  end"]
    lines += _argument_checks(code.arguments, arguments)
    for symbol, expr in code.assignments:
        lines.append(f"  {symbol.name} = {printer.doprint(expr)};")
    everything = set(code.arguments)
    expressions = list(code.outputs.values())
    finite = " & ".join(f"isfinite({r.name})" for r in code.roots)
    if any(_arguments_behind(code, e) != everything for e in expressions) or not code.roots or (
            set().union(*(_arguments_behind(code, r) for r in code.roots)) != everything):
        lines.append(f"  {shape} = size({' + '.join(arguments) or '0'});")
        broadcast = True
    else:
        broadcast = False
    for variable, expr in zip(variables, expressions):
        text = printer.doprint(expr)
        if broadcast and _arguments_behind(code, expr) != everything:
            text = f"({text}) & true({shape})" if is_flag(expr) else f"({text}) .* ones({shape})"
        lines.append(f"  {variable} = {text};")
    if not code.roots:
        lines.append(f"  {assembled} = true({shape});")
    elif broadcast and set().union(*(_arguments_behind(code, r) for r in code.roots)) != everything:
        lines.append(f"  {assembled} = ({finite}) & true({shape});")
    else:
        lines.append(f"  {assembled} = {finite};")
    lines.append("end")
    return "\n".join(lines) + "\n"


def export_files(linkage: Linkage, stem: str, functions: Sequence[tuple[str, Sequence[str], str]],
                 title: str, regenerate: str = "", form: str = "atan2") -> dict[str, str]:
    """``{"<stem>_<name>.m": text}``: one function file for each ``(name, outputs, doc)``.

    A function file has no room for a module title: ``title`` and
    ``regenerate`` are taken for the common shape of the printers and not written.
    
    ``form`` is the LaTeX printer's (a seed paper's form of the equations): code has one form, the atan2 form.
    """
    return {f"{stem}_{name}.m": octave_function(linkage.program(list(outputs)), f"{stem}_{name}", doc)
            for name, outputs, doc in functions}
