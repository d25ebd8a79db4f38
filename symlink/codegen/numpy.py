"""The NumPy printer: vectorised Python modules that import NumPy only.

A program's :class:`~symlink.codegen.program.StraightLine` form becomes a
Python function; every NumPy call broadcasts, so one call evaluates a whole
sweep of crank angles, or of link lengths.

The NaN of a square root that cannot be taken (:class:`ClampedSqrt`) spreads
to everything that depends on it; each function also returns ``assembled``,
the mask of the inputs where the linkage closes, so callers never have to
guess what a NaN means.  The sines and cosines that speeds and accelerations
need come from the solved angles' ``atan2`` arguments
(:func:`~symlink.codegen.trigonometry.angle_sums`): full kinematics call the
transcendental functions no more often than positions do.

>>> from symlink.mechanism.catalog import fourbar
>>> source = numpy_module([("rocker_angle", fourbar().program(["phi"]), "Rocker angle.")])
>>> "import sympy" in source, "numpy.arctan2" in source
(False, True)
>>> namespace = load_numpy_module(source)
>>> result = namespace["rocker_angle"](0.0, 20.0, 66.0, 56.0, 80.0)
>>> round(float(numpy.degrees(result["phi"])), 2), bool(result["assembled"])
(110.74, True)
"""
from __future__ import annotations

import inspect
import textwrap
from typing import TYPE_CHECKING, Sequence

import numpy
import sympy as sp
from sympy.printing.numpy import NumPyPrinter
from sympy.printing.precedence import precedence

from ..version import __version__
from ..symbolic.linkage import is_branch_name
from ..common.rounding import TOLERANCE
from .arguments import _arguments, checked_arguments  # noqa: F401 - copied into every module; re-exported
from .loading import load_numpy_module
from .program import require_loop_units, format_default, is_flag, straight_line
from .trigonometry import angle_sums

if TYPE_CHECKING:
    from ..symbolic.linkage import Linkage, Program

__all__ = ["NumPyCodePrinter", "numpy_function", "numpy_module", "load_numpy_module", "docstring_text",
           "export_files", "checked_arguments", "ARGUMENT_CONTRACT"]

#: What every generated function accepts, in words: its docstring, and the C and Octave exports' header comments.
ARGUMENT_CONTRACT = ("branch signs exactly +1 or -1; lengths positive and finite; every value finite and real "
                     "(complex values are refused); array arguments whose shapes broadcast together")


#: Values a generated kernel evaluates at a time (see ``_evaluate``): a block's temporaries stay in cache
#: (128 KiB each), and a NumPy call's fixed cost (about half a microsecond) is shared by enough values.
BLOCK = 16384

_PYTHON_ESCAPES = {"\\": "\\\\", '"': '\\"'}


def docstring_text(text: str) -> str:
    r"""``text`` as it may stand inside a triple-quoted docstring: it can neither end it nor escape out of it.

    Backslashes and double quotes are escaped, and so is every character that
    is not printable but the newline, so that the docstring reads as ``text``.

    >>> print(docstring_text('say ' + '"' * 3 + ' and \\ and \x00'))
    say \"\"\" and \\ and \x00
    """
    return "".join(_PYTHON_ESCAPES.get(character, character) if character == "\n" or character.isprintable()
                   else character.encode("unicode_escape").decode("ascii") for character in text)



def sum_text(printer, expr: sp.Expr, order: str | None = None) -> str:
    """A sum as ``printer`` writes its terms, but ``y - x`` for ``-x + y``: the NumPy and JavaScript printers' one rule.

    Only the first two terms trade places (``(-x) + y`` is ``y - x`` exactly), so every later term is added
    in the same order as SymPy's, and the generated languages compute the same bits.
    """
    terms = printer._as_ordered_terms(expr, order=order)
    printed = [printer._print(term) for term in terms]
    if len(terms) > 1 and printed[0].startswith("-") and not terms[0].is_Add and not printed[1].startswith("-"):
        terms[0], terms[1] = terms[1], terms[0]
        printed[0], printed[1] = printed[1], printed[0]
    prec = precedence(expr)
    parts = []
    for term, text in zip(terms, printed):
        sign = "+"
        if text.startswith("-") and not term.is_Add:
            sign, text = "-", text[1:]
        parts += [sign, f"({text})" if precedence(term) < prec or term.is_Add else text]
    sign = parts.pop(0)
    return ("" if sign == "+" else sign) + " ".join(parts)


class NumPyCodePrinter(NumPyPrinter):
    """NumPy printer with symlink's clamped square root and plain ``numpy.`` names."""

    def __init__(self):
        super().__init__({"fully_qualified_modules": True, "inline": True, "allow_unknown_functions": False})

    def _print_PowerOfTwoBelow(self, expr):  # a loop's unit: the module header defines it
        return f"_power_of_two_below({self._print(expr.args[0])})"

    def _print_Pow(self, expr, rational=False):
        if expr.exp == -1:
            return f"1/{self.parenthesize(expr.base, 1000)}"
        if expr.exp == 2:  # x*x, correctly rounded; a NumPy scalar's x**2.0 calls pow(), which is not
            return f"numpy.square({self._print(expr.base)})"
        return super()._print_Pow(expr, rational=rational)

    def _print_Add(self, expr, order=None):
        """As SymPy prints a sum, but ``y - x`` for ``-x + y``: one negation of an array fewer, the same bits.

        Only the first two terms trade places (``(-x) + y`` is ``y - x`` exactly, and ``(-a)*b`` is
        ``-(a*b)``), so every later term is added in the same order as before.
        """
        return sum_text(self, expr, order)

    def _print_Integer(self, expr):
        return f"{float(expr)!r}"

    def _print_CosineOfAtan2(self, expr):  # the module header defines _cos_atan2 and _sin_atan2
        return f"_cos_atan2({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_SineOfAtan2(self, expr):
        return f"_sin_atan2({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_ClampedSqrt(self, expr):  # the module header defines _clamped_sqrt
        require_loop_units(expr)
        return f"_clamped_sqrt({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_NonzeroSquare(self, expr):  # the module header defines _nonzero_square
        return f"_nonzero_square({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_Piecewise(self, expr):  # pragma: no cover - a guard, never reached by symlink's own forms
        raise ValueError("symlink never writes Piecewise into NumPy code")


def _evaluate(kernel, arguments, shape, keys, flags):
    """``{key: array}``: the kernel's results broadcast to ``shape``; a long input evaluated a block of rows at a time.

    Up to :data:`BLOCK` values, one call of ``kernel`` on the whole arguments.
    Beyond, the outputs are allocated once (``flags`` tells the true/false
    ones) and the kernel is called on consecutive slices of the leading axis
    of about ``BLOCK`` values each (an argument that broadcasts along that axis
    is passed whole), so its temporaries stay in cache and the memory a call
    needs beyond its outputs does not grow with the input.  A block is at most
    1/16 of the input (and at least ``BLOCK // 4`` values): a block's few dozen
    temporaries then take less memory than two outputs, which the C allocator
    keeps for the next block instead of handing it back to the system and
    faulting it in again (measured: blocks of ``BLOCK`` values over inputs of
    2-4 blocks ran 1.4x slower a value).  Every value is computed by the same
    elementwise operations either way: the results are bit for bit those of
    one call on the whole arguments.
    """
    count = 1
    for extent in shape:
        count *= extent
    if count <= BLOCK:
        results, taken = {}, {id(argument) for argument in arguments}
        for key, result in zip(keys, kernel(*arguments)):
            if type(result) is numpy.ndarray and result.shape == shape and id(result) not in taken:
                taken.add(id(result))  # a fresh array of its own, as it is
            else:  # a scalar, a smaller shape, an argument or another output: broadcast (a read-only view)
                result = numpy.broadcast_to(result, shape)
            results[key] = result
        return results
    rows, dimensions = shape[0], len(shape)
    step = max(1, max(BLOCK // 4, min(BLOCK, count // 16)) // (count // rows))
    outputs = [numpy.empty(shape, dtype=bool if flag else float) for flag in flags]
    sliced = [argument.ndim == dimensions and argument.shape[0] != 1 for argument in arguments]
    for start in range(0, rows, step):
        stop = start + step
        results = kernel(*[argument[start:stop] if cut else argument for argument, cut in zip(arguments, sliced)])
        for output, result in zip(outputs, results):
            output[start:stop] = result
    return dict(zip(keys, outputs))


def _last_uses(code) -> dict[int, list[str]]:
    """``{statement index: temporaries no later statement or output needs}``: where the kernel may drop them."""
    kept = {s.name for s in set().union(*(expr.free_symbols for expr in code.outputs.values())) | set(code.roots)}
    last: dict[str, int] = {}
    for index, (symbol, expr) in enumerate(code.assignments):
        for used in expr.free_symbols:
            last[used.name] = index
        last.setdefault(symbol.name, index)
    arguments = {s.name for s in code.arguments}
    dropped: dict[int, list[str]] = {}
    for name, index in last.items():
        if name not in arguments and name not in kept:
            dropped.setdefault(index, []).append(name)
    return dropped


def numpy_function(program: Program, name: str, doc: str = "") -> str:
    """Python source of one vectorised function computing the program's outputs.

    Its arguments are checked (see :func:`checked_arguments`) unless it is
    called with ``check=False``.  The arithmetic lives in a kernel beside it,
    ``_<name>_block``, called by ``_evaluate`` once for a short input and a
    block at a time for a long one; the kernel drops each temporary once no
    later line needs it, so that its arrays are reused while they are in cache.
    """
    code = straight_line(program)
    arguments = [s.name for s in code.arguments]
    code = angle_sums(code, set(arguments))
    printer = NumPyCodePrinter()
    lengths = tuple(s.name for s in code.arguments if s.is_positive)
    signs = tuple(a for a in arguments if is_branch_name(a))
    signature = ", ".join([f"{a}={format_default(code.defaults[a])}" if a in code.defaults else a
                           for a in arguments] + ["*", "check=True"])
    outputs = ", ".join(code.outputs)
    kernel = f"_{name}_block"
    lines = [f"def {name}({signature}):"]
    text = (docstring_text(doc.strip()) + "\n\n" if doc else "") + (
        f"Returns a dict of arrays: {outputs};\n"
        "and assembled: False where the linkage cannot close (the outputs are NaN there).\n"
        "The arguments broadcast against each other.  They are checked (ValueError naming the argument):\n"
        + textwrap.fill(f"{ARGUMENT_CONTRACT}; check=False skips that for hot loops.", 96))
    lines.append('    """' + text.replace("\n", "\n    ") + '\n    """')
    listed = "".join(f"{a}, " for a in arguments)
    if arguments:
        lines.append(f"    ({listed}), shape = _arguments(\n"
                     f"        check, {tuple(arguments)!r}, ({listed}), {lengths!r}, {signs!r})")
    else:
        lines.append("    shape = ()")
    flags = tuple(is_flag(expr) for expr in code.outputs.values()) + (True,)
    keys = tuple(code.outputs) + ("assembled",)
    lines.append(f"    return _evaluate({kernel}, ({listed}), shape, {keys!r}, {flags!r})")
    lines += ["", "", f"def {kernel}({', '.join(arguments)}):",
              f'    """The outputs of {name} and the assembled mask, for arguments that broadcast together."""']
    dropped = _last_uses(code)
    for index, (symbol, expr) in enumerate(code.assignments):
        lines.append(f"    {symbol.name} = {printer.doprint(expr)}")
        if dropped.get(index):
            lines.append(f"    del {', '.join(sorted(dropped[index]))}")
    if code.roots:
        assembled = " & ".join(f"numpy.isfinite({r.name})" for r in code.roots)
    else:
        assembled = "True"
    lines.append("    return (")
    for output, expr in code.outputs.items():
        lines.append(f"        {printer.doprint(expr)},  # {output}")
    lines.append(f"        {assembled},  # assembled")
    lines.append("    )")
    return "\n".join(lines) + "\n"


_HEADER = '''"""{title}

Generated by symlink {version} with SymPy {sympy}. Imports NumPy only; do not edit.{regenerate}
"""
import numpy

TOLERANCE = {tolerance!r}

#: Values a kernel evaluates at a time: its temporaries of one block stay in cache.
BLOCK = {block!r}


{arguments}

{evaluate}

def _clamped_sqrt(x, scale):
    """sqrt(x), taking x >= -TOLERANCE*scale as rounding at a toggle (0) and anything lower as no assembly (NaN)."""
    return numpy.sqrt(numpy.where(x >= -TOLERANCE * scale, numpy.maximum(x, 0.0), numpy.nan))


def _nonzero_square(x, smallest):
    """A squared length that must not vanish: x where x >= smallest, NaN below it (an undefined direction)."""
    return numpy.where(x >= smallest, x, numpy.nan)


def _power_of_two_below(x):
    """2.0**floor(log2(x)) for positive x (a loop's unit): the largest power of two not above x, from x's exponent.

    ``frexp`` splits x into a mantissa in [0.5, 1) and a power of two, so the
    power is exact where a logarithm rounded near a power of two could be one off.
    """
    return numpy.ldexp(0.5, numpy.frexp(x)[1])


def _cos_atan2(x, r):
    """cos(atan2(y, x)) from r = sqrt(x*x + y*y): x/r, and atan2's 1 or -1 by the sign of x where x = y = 0."""
    nonzero = r != 0.0  # a quotient only where it is one: no division by zero, no warning
    return numpy.where(nonzero, x, numpy.copysign(1.0, x)) / numpy.where(nonzero, r, 1.0)


def _sin_atan2(y, r):
    """sin(atan2(y, x)) from r = sqrt(x*x + y*y): y/r, and the signed zero y where x = y = 0."""
    return y / numpy.where(r != 0.0, r, 1.0)
'''


def numpy_module(functions: Sequence[tuple[str, Program, str]], title: str = "A symlink solver.",
                 regenerate: str = "") -> str:
    """A standalone module of vectorised functions, each ``(name, program, docstring)``.

    Parameters
    ----------
    functions : sequence of (str, Program, str)
        Each function's name, its straight-line program (``linkage.program(outputs)``) and docstring.
    title : str, optional
        The module's docstring.
    regenerate : str, optional
        The command that regenerates it, written in its header.

    Returns
    -------
    str
        The module's Python source; it imports NumPy only.

    Examples
    --------
    >>> import math, symlink
    >>> linkage = symlink.fourbar()
    >>> source = symlink.numpy_module([("rocker_angle", linkage.program(["phi"]), "Rocker angle.")])
    >>> namespace = {}
    >>> exec(source, namespace)  # our own generated code
    >>> round(math.degrees(float(namespace["rocker_angle"](theta=0.0, a=20, b=66, c=56, d=80)["phi"])), 2)
    110.74
    """
    again = f"\nRegenerate with: {docstring_text(regenerate)}" if regenerate else ""
    header = _HEADER.format(title=docstring_text(title), version=__version__, sympy=sp.__version__,
                            tolerance=TOLERANCE, regenerate=again,
                            arguments=inspect.getsource(_arguments), block=BLOCK,
                            evaluate=inspect.getsource(_evaluate))
    return header + "".join("\n\n" + numpy_function(p, name, doc) for name, p, doc in functions)


def export_files(linkage: Linkage, stem: str, functions: Sequence[tuple[str, Sequence[str], str]],
                 title: str, regenerate: str = "", form: str = "atan2") -> dict[str, str]:
    """``{"<stem>.py": module}``: one function for each ``(name, outputs, docstring)``; the shape of every printer.
    ``form`` is the LaTeX printer's (a seed paper's form of the equations): code has one form, the atan2 form.
    """
    programs = [(name, linkage.program(list(outputs)), doc) for name, outputs, doc in functions]
    return {f"{stem}.py": numpy_module(programs, title, regenerate)}
