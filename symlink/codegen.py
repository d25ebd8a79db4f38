"""Code generation: common-subexpression elimination and vectorised NumPy modules.

A :class:`~symlink.linkage.Program` (straight-line assignments for some
outputs) becomes :class:`StraightLine` code with common subexpressions
eliminated across everything requested, and then a Python function that
imports NumPy only.  Every NumPy call broadcasts, so one call evaluates a
whole sweep of crank angles, or of link lengths.

The NaN of a square root that cannot be taken (:class:`ClampedSqrt`) spreads
to everything that depends on it; each function also returns ``assembled``,
the mask of the inputs where the linkage closes, so callers never have to
guess what a NaN means.

>>> from symlink.catalog import fourbar
>>> source = numpy_module([("rocker_angle", fourbar().program(["phi"]), "Rocker angle.")])
>>> "import sympy" in source, "numpy.arctan2" in source
(False, True)
>>> namespace = load_numpy_module(source)
>>> result = namespace["rocker_angle"](0.0, 20.0, 66.0, 56.0, 80.0)
>>> round(float(numpy.degrees(result["phi"])), 2), bool(result["assembled"])
(110.74, True)
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy
import sympy as sp
from sympy.printing.numpy import NumPyPrinter

from . import __version__
from .linkage import Program
from .position import TOLERANCE, ClampedSqrt

__all__ = ["StraightLine", "straight_line", "NumPyCodePrinter", "numpy_function", "numpy_module", "load_numpy_module",
           "format_default"]

CSE_PREFIX = "cse_"


@dataclass(frozen=True)
class StraightLine:
    """Program after common-subexpression elimination, ready for any printer.

    ``assignments`` define temporaries and the program's own symbols in an
    order where every right-hand side uses only arguments and earlier names;
    ``outputs`` map output names to expressions of those; ``roots`` are the
    square roots whose finiteness says that the linkage is assembled;
    ``defaults`` are the program's argument defaults.
    """

    arguments: tuple[sp.Symbol, ...]
    assignments: tuple[tuple[sp.Symbol, sp.Expr], ...]
    outputs: dict[str, sp.Expr]
    roots: tuple[sp.Symbol, ...]
    defaults: dict[str, float]


def straight_line(program: Program) -> StraightLine:
    """Eliminate common subexpressions across the program's assignments and outputs."""
    names = [s for s, _ in program.assignments]
    output_names = list(program.outputs)
    expressions = [e for _, e in program.assignments] + [program.outputs[n] for n in output_names]
    taken = {s.name for s in program.arguments} | {s.name for s in names}
    temporaries = (sp.Symbol(f"{CSE_PREFIX}{i}", real=True) for i in range(10**9)
                   if f"{CSE_PREFIX}{i}" not in taken)
    replacements, reduced = sp.cse(expressions, symbols=temporaries, order="none")
    nodes = list(replacements) + list(zip(names, reduced[:len(names)]))
    outputs = dict(zip(output_names, reduced[len(names):]))
    roots = tuple(s for s, e in program.assignments if isinstance(e, ClampedSqrt))
    return StraightLine(program.arguments, _dependency_order(nodes), outputs, roots, dict(program.defaults))


def _dependency_order(nodes: list[tuple[sp.Symbol, sp.Expr]]) -> tuple[tuple[sp.Symbol, sp.Expr], ...]:
    """Order assignments so that each one's symbols are defined before it (stable)."""
    defined_by = {s for s, _ in nodes}
    done: set[sp.Symbol] = set()
    ordered = []
    pending = list(nodes)
    while pending:
        for index, (symbol, expr) in enumerate(pending):
            if (expr.free_symbols & defined_by) <= done:
                ordered.append((symbol, expr))
                done.add(symbol)
                del pending[index]
                break
        else:
            raise ValueError("circular definitions in generated code")
    return tuple(ordered)


class NumPyCodePrinter(NumPyPrinter):
    """NumPy printer with symlink's clamped square root and plain ``numpy.`` names."""

    def __init__(self):
        super().__init__({"fully_qualified_modules": True, "inline": True, "allow_unknown_functions": False})

    def _print_Pow(self, expr, rational=False):
        if expr.exp == -1:
            return f"1/{self.parenthesize(expr.base, 1000)}"
        if expr.exp == 2:  # x*x, correctly rounded; a NumPy scalar's x**2.0 calls pow(), which is not
            return f"numpy.square({self._print(expr.base)})"
        return super()._print_Pow(expr, rational=rational)

    def _print_Integer(self, expr):
        return f"{float(expr)!r}"

    def _print_ClampedSqrt(self, expr):
        return f"_clamped_sqrt({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_Piecewise(self, expr):  # pragma: no cover - a guard, never reached by symlink's own forms
        raise ValueError("symlink never writes Piecewise into NumPy code")


def format_default(value: float) -> str:
    """An argument default as code: 1 for a branch, 0.0 for a rate."""
    return str(int(value)) if value == 1 else repr(value)  # branch=1, thetadot=0.0


def numpy_function(program: Program, name: str, doc: str = "") -> str:
    """Python source of one vectorised function computing the program's outputs."""
    code = straight_line(program)
    printer = NumPyCodePrinter()
    arguments = [s.name for s in code.arguments]
    signature = ", ".join(f"{a}={format_default(code.defaults[a])}" if a in code.defaults else a for a in arguments)
    outputs = ", ".join(code.outputs)
    lines = [f"def {name}({signature}):"]
    text = (doc.strip() + "\n\n" if doc else "") + (
        f"Returns a dict of arrays: {outputs};\n"
        "and assembled: False where the linkage cannot close (the outputs are NaN there).\n"
        "The arguments broadcast against each other.")
    lines.append('    """' + text.replace("\n", "\n    ") + '\n    """')
    if arguments:
        lines.append(f"    {', '.join(arguments)}{',' if len(arguments) == 1 else ''} = "
                     f"_as_arrays({', '.join(arguments)})")
        lines.append(f"    shape = numpy.broadcast_shapes({', '.join(f'numpy.shape({a})' for a in arguments)})")
    else:
        lines.append("    shape = ()")
    for symbol, expr in code.assignments:
        lines.append(f"    {symbol.name} = {printer.doprint(expr)}")
    if code.roots:
        assembled = " & ".join(f"numpy.isfinite({r.name})" for r in code.roots)
    else:
        assembled = "True"
    lines.append("    return {")
    for output, expr in code.outputs.items():
        lines.append(f"        {output!r}: numpy.broadcast_to({printer.doprint(expr)}, shape),")
    lines.append(f"        'assembled': numpy.broadcast_to({assembled}, shape),")
    lines.append("    }")
    return "\n".join(lines) + "\n"


_HEADER = '''"""{title}

Generated by symlink {version} with SymPy {sympy}. Imports NumPy only; do not edit.{regenerate}
"""
import numpy

TOLERANCE = {tolerance!r}


def _as_arrays(*values):
    return tuple(numpy.asarray(v, dtype=float) for v in values)


def _clamped_sqrt(x, scale):
    """sqrt(x), taking x >= -TOLERANCE*scale as rounding at a toggle (0) and anything lower as no assembly (NaN)."""
    return numpy.sqrt(numpy.where(x >= -TOLERANCE * scale, numpy.maximum(x, 0.0), numpy.nan))
'''


def numpy_module(functions: Sequence[tuple[str, Program, str]], title: str = "A symlink solver.",
                 regenerate: str = "") -> str:
    """A standalone module of vectorised functions, each ``(name, program, docstring)``."""
    header = _HEADER.format(title=title, version=__version__, sympy=sp.__version__, tolerance=TOLERANCE,
                            regenerate=f"\nRegenerate with: {regenerate}" if regenerate else "")
    return header + "".join("\n\n" + numpy_function(p, name, doc) for name, p, doc in functions)


def load_numpy_module(source: str) -> dict:
    """Run generated module source (symlink's own output, never user text) and return its namespace."""
    namespace: dict = {"__name__": "symlink_generated"}
    exec(compile(source, "<symlink generated>", "exec"), namespace)  # noqa: S102 - our own generated code
    return namespace
