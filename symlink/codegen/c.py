"""C export: a header and a source in plain C99 with ``math.h``, one loop function per output set.

Each function evaluates ``n`` configurations in one loop, without allocating.
Every argument is passed as a pointer and a step: configuration ``i`` reads
``x[i * x_step]``, so a step of 1 walks an array of ``n`` values and a step of
0 shares one value (a link length, say) between all of them.  Each output is
an array of ``n`` doubles, and ``assembled[i]`` is 1 where the linkage closes,
0 where it cannot be assembled (its outputs are NaN there)::

    void fourbar_positions(size_t n,
        const double *theta, ptrdiff_t theta_step, const double *a, ptrdiff_t a_step, ...,
        double *coupler, double *rocker, unsigned char *assembled);

The body is the same common-subexpression-eliminated straight-line code as the
NumPy module (:func:`symlink.codegen.program.straight_line`), in an inline function
called once per configuration and always inlined into the loop (GCC and Clang), so
that the loop stays one vectorisable body however large the linkage.  The clamped square root has exactly the
semantics of the NumPy module's ``_clamped_sqrt``; small integer powers become
multiplications.  As in the NumPy module, the sines and cosines of the solved
angles and of their sums (which the rates need) are computed from the
arguments of the ``atan2`` that gave each angle and the addition theorems
(:func:`~symlink.codegen.trigonometry.angle_sums`), not called again, so that
full kinematics call the vector math library no more often than positions do.

>>> from symlink.mechanism.catalog import fourbar
>>> header, source = c_code([("fourbar_positions", fourbar().program(["rocker"]), "Rocker angle.")], "fourbar")
>>> print(header.split("void ")[1].split(";")[0])
fourbar_positions(size_t n,
    const double *theta, ptrdiff_t theta_step,
    const double *a, ptrdiff_t a_step,
    const double *b, ptrdiff_t b_step,
    const double *c, ptrdiff_t c_step,
    const double *d, ptrdiff_t d_step,
    const double *branch, ptrdiff_t branch_step,
    double *rocker, unsigned char *assembled)
>>> "atan2(" in source and "malloc" not in source
True
"""
from __future__ import annotations

import textwrap
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Sequence

import sympy as sp
from sympy.printing.c import C99CodePrinter

from ..version import __version__
from ..common.names import C_KEYWORDS as RESERVED_IN_C, PLAIN_NAME
from ..common.rounding import TOLERANCE
from .translation_units import UNIT_MARK, translation_units
from ..symbolic.position import PowerOfTwoBelow
from .numpy import ARGUMENT_CONTRACT
from .program import require_loop_units, FreshNames, StraightLine, is_flag, named_straight_line
from .trigonometry import angle_sums

if TYPE_CHECKING:
    from ..symbolic.linkage import Linkage, Program

__all__ = ["CFunction", "c_function", "c_library", "c_code", "c_identifier", "c_comment", "c_packed", "PACKED_CALL", "export_files",
           "translation_units", "PIECE_SIZE", "UNIT_MARK"]

#: The C type of true/false values inside a loop (1 and 0), before they are written out as bytes.
FLAG_LANE = "unsigned short"

#: The same in a loop that computes more numbers than the positions its closed forms solve (rates):
#: 32-bit lanes, so that GCC takes half as many configurations at a time (16 with AVX-512) into a kernel
#: that holds more values across its vector-math calls. Measured (10^6 values, interleaved, best of 30):
#: four-bar full kinematics 1.13-1.20x -> 0.98-1.05x the hand-written loop, Watt II 4-5 % faster, Jansen
#: -5 to +5 %; positions alone were 7-16 % slower with it (four-bar, Watt II, Jansen), so they keep 16 bits.
RATE_FLAG_LANE = "unsigned int"

#: The same in a program of pieces (:data:`PIECE_SIZE`), where every loop is of doubles.
PIECE_FLAG_LANE = "double"

#: Integer powers up to this size are written as multiplications.
LARGEST_MULTIPLIED_POWER = 4

#: C's keywords and the names its headers define, which no identifier may take.
C_KEYWORDS = frozenset(C99CodePrinter.reserved_words) | RESERVED_IN_C


def c_identifier(name: str, what: str = "name") -> str:
    """``name`` if it is a plain name (:data:`symlink.common.names.PLAIN_NAME`) that is not a C keyword; ``ValueError`` otherwise.

    >>> c_identifier("phi_1")
    'phi_1'
    """
    if not PLAIN_NAME.match(name) or name in C_KEYWORDS or name.startswith("symlink_"):
        raise ValueError(f"{what} {name!r} is not usable as a C identifier "
                         "(an ASCII letter, then letters, digits and underscores; not a keyword; "
                         "not starting with 'symlink_')")
    return name


class CPrinter(C99CodePrinter):
    """C99 printer with symlink's clamped square root, exact double literals and multiplied powers."""

    def __init__(self):
        super().__init__({"math_macros": {}, "allow_unknown_functions": False})

    def _print_Symbol(self, expr):
        return c_identifier(expr.name, "symbol")

    def _print_Float(self, expr):
        return repr(float(expr))

    _print_Integer = _print_Rational = _print_Float  # the nearest double, as NumPy would compute it

    def _print_NumberSymbol(self, expr):  # pi and E as literals: M_PI is not C99
        return repr(float(expr))

    _print_Pi = _print_Exp1 = _print_NumberSymbol

    def _print_Pow(self, expr, rational=False):
        base, exponent = expr.base, expr.exp
        if exponent.is_Integer and 0 < abs(int(exponent)) <= LARGEST_MULTIPLIED_POWER:
            # Parenthesised, so that a*x**2 multiplies a by x*x as NumPy does.
            factor = self._print(base) if base.is_Atom or base.is_Function else f"({self._print(base)})"
            text = {1: factor, 2: f"({factor}*{factor})", 3: f"({factor}*{factor}*{factor})",
                    4: f"(({factor}*{factor})*({factor}*{factor}))"}[abs(int(exponent))]
            return text if exponent > 0 else f"1.0/{text}"
        if exponent == sp.S.Half:
            return f"sqrt({self._print(base)})"
        if exponent == -sp.S.Half:
            return f"1.0/sqrt({self._print(base)})"
        return f"pow({self._print(base)}, {self._print(sp.Float(exponent) if exponent.is_Rational else exponent)})"

    # Or and And as sums and products of 1.0/0.0 selects: no short circuit, and no mix of int and double
    # lanes, either of which keeps GCC from vectorising a loop with a flag output such as singular.
    def _print_Or(self, expr):
        return "(" + " + ".join(f"({self._print(a)} ? 1.0 : 0.0)" for a in sorted(expr.args, key=sp.default_sort_key)) + ")"

    def _print_And(self, expr):
        return "(" + " * ".join(f"({self._print(a)} ? 1.0 : 0.0)" for a in sorted(expr.args, key=sp.default_sort_key)) + ")"

    def _print_BooleanTrue(self, expr):
        return "1"

    def _print_BooleanFalse(self, expr):
        return "0"

    def _print_PowerOfTwoBelow(self, expr):  # the prelude defines symlink_power_of_two_below
        return f"symlink_power_of_two_below({self._print(expr.args[0])})"

    def _print_CosineOfAtan2(self, expr):  # the prelude defines symlink_cos_atan2 and symlink_sin_atan2
        return f"symlink_cos_atan2({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_SineOfAtan2(self, expr):
        return f"symlink_sin_atan2({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_ClampedSqrt(self, expr):  # the source's prelude defines symlink_clamped_sqrt
        require_loop_units(expr)
        return f"symlink_clamped_sqrt({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_NonzeroSquare(self, expr):  # the source's prelude defines symlink_nonzero_square
        return f"symlink_nonzero_square({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_Piecewise(self, expr):  # pragma: no cover - a guard, never reached by symlink's own forms
        raise ValueError("symlink never writes Piecewise into generated code")


@dataclass(frozen=True)
class CFunction:
    """One generated C function: its name, arguments and outputs in calling order, and its text.

    ``arguments`` and ``outputs`` are the names of the generated Python
    function's arguments and result keys; ``output_parameters`` are the C
    names of the output arrays (an output named like an argument gets
    ``_out``); ``flags`` tells the true/false outputs (``unsigned char``
    arrays of 0 and 1) from the numbers (``double`` arrays).  ``prototype``
    goes into the header, ``definition`` into the source.  ``pieces`` are
    the loop functions of a large program's pieces (:data:`PIECE_SIZE`), each
    its own text that ``definition`` calls in order; ``piece_prototypes``
    declare them.  A small program has none: its one kernel is inlined into
    ``definition``.
    """

    name: str
    arguments: tuple[str, ...]
    outputs: tuple[str, ...]
    output_parameters: tuple[str, ...]
    flags: tuple[bool, ...]
    prototype: str
    definition: str
    pieces: tuple[str, ...] = ()
    piece_prototypes: tuple[str, ...] = ()


def c_comment(text: str, indent: str = "") -> str:
    """``text`` as a C block comment that it can neither end nor nest: ``*/``, ``/*`` and ``??`` are spaced out.

    (``??`` could start a trigraph; ``-Wall`` warns of one that ends a line.)

    >>> print(c_comment("Ends */ here, /* nests??/\\nSecond line."))
    /* Ends * / here, / * nests? ?/
     * Second line.
     */
    """
    text = text.strip().replace("*/", "* /").replace("/*", "/ *")
    while "??" in text:
        text = text.replace("??", "? ?")
    lines = text.splitlines() or [""]
    return "\n".join([f"{indent}/* {lines[0]}".rstrip()] + [f"{indent} * {line}".rstrip() for line in lines[1:]]
                     ) + (" */" if len(lines) == 1 else f"\n{indent} */")


#: A straight-line program whose assignments print to more than this many characters of C is cut into pieces
#: of at most about this size, each its own loop function (:func:`c_function`): a compiler's time grows faster
#: than the length of one function (register allocation, CSE after reload), and pieces can be compiled apart,
#: in parallel (:func:`translation_units`).  Measured with GCC 12 (``-O3``, three target clones) on chains of
#: k four-bars (about 2,300 characters each): one loop of k = 4 takes 2.8 CPU seconds to compile, two pieces
#: 0.7 (a piece's loop is of doubles alone: no 16-bit lanes, which GCC vectorises four times as wide); at
#: k = 16, pieces of 3,000 to 12,000 characters cost 3.3-4.3 s in all, 24,000 a bit more.  The catalog's
#: linkages (Jansen's leg's full kinematics, the largest, print 7,342) stay one loop, as fast as before.
PIECE_SIZE = 8000

def _piece_bounds(costs: Sequence[int], size: int) -> list[tuple[int, int]]:
    """Consecutive ranges of assignments, of about equal total cost, each at most about ``size`` (one if all fit).

    >>> _piece_bounds([5, 5, 5, 5], 12), _piece_bounds([5, 5, 5, 5], 20)
    ([(0, 2), (2, 4)], [(0, 4)])
    """
    total = sum(costs)
    count = max(1, -(-total // size))
    bounds: list[tuple[int, int]] = []
    start = running = 0
    for index, cost in enumerate(costs):
        running += cost
        if running * count >= total * (len(bounds) + 1) and len(bounds) < count - 1:
            bounds.append((start, index + 1))
            start = index + 1
    bounds.append((start, len(costs)))
    return bounds


def _clustered(code: StraightLine, uses: dict[sp.Symbol, frozenset]) -> tuple[tuple[sp.Symbol, sp.Expr], ...]:
    """The assignments in an order that computes each output's values together, so that few values are live
    from piece to piece: next always the output that needs the fewest values not computed yet (in a chain of
    loops: one loop's position, rate and acceleration, then the next loop's).  Each value after those it uses
    (``uses``: each assignment's free symbols).
    """
    expression = dict(code.assignments)
    needs = {symbol: sorted((s for s in uses[symbol] if s in expression), key=str) for symbol, _ in code.assignments}
    # Sets of values as bits of a whole number (bit i: the i-th assignment): a chain of n loops has values
    # that need O(n) others, and OR-ing machine words keeps building and asking these sets nearly linear.
    bit = {symbol: 1 << index for index, (symbol, _) in enumerate(code.assignments)}
    closure: dict[sp.Symbol, int] = {}
    for symbol, _ in code.assignments:  # in order: every value's needs come before it
        below = bit[symbol]
        for s in needs[symbol]:
            below |= closure[s]
        closure[symbol] = below
    wanted = [sorted((s for s in e.free_symbols if s in expression), key=str) for e in code.outputs.values()]
    wanted.append(list(code.roots))
    missing = []
    for group in wanted:
        union = 0
        for symbol in group:
            union |= closure[symbol]
        missing.append(union)
    done: set = set()
    done_bits = 0
    order: list[sp.Symbol] = []
    left = set(range(len(wanted)))
    while left:
        # One AND and bit count of machine words an output left (no call a comparison).
        _, k = min([((missing[j] & ~done_bits).bit_count(), j) for j in left])
        left.discard(k)
        for first in wanted[k]:
            stack = [(first, iter(needs[first]))]
            while stack:  # depth first, each value after what it needs
                symbol, pending = stack[-1]
                following = next((s for s in pending if s not in done), None)
                if following is not None:
                    stack.append((following, iter(needs[following])))
                    continue
                stack.pop()
                if symbol not in done:
                    done.add(symbol)
                    done_bits |= bit[symbol]
                    order.append(symbol)
    order += [symbol for symbol, _ in code.assignments if symbol not in done]
    return tuple((symbol, expression[symbol]) for symbol in order)


def c_function(program: Program, name: str, doc: str = "", piece_size: int = PIECE_SIZE) -> CFunction:
    """The C loop function (and its inline kernel, or its pieces) that computes the program's outputs.

    A program whose C is longer than ``piece_size`` characters is cut into
    pieces (:data:`PIECE_SIZE`): each a loop function over a block of
    configurations that reads the values it needs from the block's arrays
    and writes those that later pieces need into block arrays on the stack;
    the function calls them in order, block by block.  Every value is the
    same operation on the same operands as in one loop (no contraction, no
    reassociation), so the results are bit-identical.
    """
    code, arguments = named_straight_line(program, name, c_identifier, "C")
    code = angle_sums(code, set(arguments))
    printer = CPrinter()
    locals_ = [c_identifier(s.name, "symbol") for s, _ in code.assignments]
    names = FreshNames(arguments + locals_, C_KEYWORDS)
    steps = [names(f"{a}_step") for a in arguments]
    outputs = list(code.outputs)
    output_parameters = [names(c_identifier(o, "output") if o not in arguments else f"{o}_out") for o in outputs]
    flags = [is_flag(e) for e in code.outputs.values()]
    solved = sum(len(solution.positions) for solution in program.plan)
    lane = RATE_FLAG_LANE if program.plan and flags.count(False) > solved else FLAG_LANE
    assembled, count, start, size, index, out = (names(w) for w in ("assembled", "n", "start", "m", "i", "out"))
    blocks = [names(f"{a}_block") for a in arguments]
    views = [names(f"{a}_at") for a in arguments]
    kernel = f"symlink_{name}_at"

    inputs = ",\n".join(f"    const double *{a}, ptrdiff_t {s}" for a, s in zip(arguments, steps))
    results = ", ".join(f"{'unsigned char' if flag else 'double'} *{o}"
                        for o, flag in zip(output_parameters, flags)) + f", unsigned char *{assembled}"
    signature = f"void {name}(size_t {count},\n" + (inputs + ",\n" if inputs else "") + f"    {results})"
    summary = (doc.strip() + "\n" if doc.strip() else "") + (
        f"Outputs (arrays of n doubles): {', '.join(o for o, f in zip(output_parameters, flags) if not f)};\n"
        + "".join(f"{o}[i] is 1 where true, 0 where false;\n" for o, f in zip(output_parameters, flags) if f) +
        f"{assembled}[i] is 1 where the linkage closes, 0 where it cannot be assembled (outputs NaN).")
    prototype = c_comment(summary) + "\n" + signature + ";\n"

    # A loop's unit's reciprocal from its exponent bits (exact, no division), where the unit is a value.
    units = {symbol for symbol, expr in code.assignments if isinstance(expr, PowerOfTwoBelow)}

    def text_of_value(expr: sp.Expr) -> str:
        if expr.is_Pow and expr.exp == -1 and expr.base in units:
            return f"symlink_reciprocal_power_of_two({printer.doprint(expr.base)})"
        return printer.doprint(expr)

    printed = [(symbol.name, text_of_value(expr)) for symbol, expr in code.assignments]
    bounds = _piece_bounds([len(text) + 20 for _, text in printed], piece_size)
    uses = {symbol: frozenset(expr.free_symbols) for symbol, expr in code.assignments}
    if len(bounds) > 1:  # pieces: each output's values computed together, so that few cross from piece to piece
        text_of = dict(printed)
        code = replace(code, assignments=_clustered(code, uses))
        locals_ = [s.name for s, _ in code.assignments]
        printed = [(name_, text_of[name_]) for name_ in locals_]
        bounds = _piece_bounds([len(text) + 20 for _, text in printed], piece_size)
    last = len(bounds) - 1
    defined_in = {symbol.name: p for p, (low, high) in enumerate(bounds) for symbol, _ in code.assignments[low:high]}
    # A number output that is a value of an earlier piece is written by that piece; the last writes the others.
    expressions = list(code.outputs.values())
    written_in = {k: defined_in[e.name] for k, e in enumerate(expressions)
                  if not flags[k] and isinstance(e, sp.Symbol) and defined_in.get(e.name, last) != last}
    written = [[k for k in written_in if written_in[k] == p] for p in range(len(bounds))]
    at_end = [k for k in range(len(outputs)) if k not in written_in]
    # Which names each piece reads; the last piece also reads its outputs' names and the roots.
    reads = [set().union(set(), *(uses[s] for s, _ in code.assignments[low:high])) for low, high in bounds]
    reads[last] |= set().union(*(expressions[k].free_symbols for k in at_end), code.roots)
    read_names = [{s.name for s in piece} for piece in reads]
    order = {name_: k for k, name_ in enumerate(arguments + locals_)}
    piece_inputs = [sorted((v for v in read_names[p] if defined_in.get(v, -1) != p), key=order.__getitem__)
                    for p in range(len(bounds))]
    last_read = {v: p for p in range(len(bounds)) for v in read_names[p]}
    piece_outputs = [[v for v in locals_[low:high] if last_read.get(v, p) > p] for p, (low, high) in enumerate(bounds)]

    def kernel_lines(function: str, given: Sequence[str], low: int, high: int, returns: bool) -> list[str]:
        """One configuration of a piece (or of the whole program): its assignments, then what it hands on."""
        kind = "double" if returns else "void"
        lines = [f"SYMLINK_INLINE {kind} {function}(" + ", ".join([f"double {a}" for a in given]
                                                                 + [f"double *restrict {out}"]) + ")", "{"]
        for symbol, text in printed[low:high]:
            lines.append(f"    const double {symbol} = {text};")
        return lines

    def final_lines(lines: list[str]) -> list[str]:
        """The kernel's outputs and its return: whether every root is finite."""
        for k, (output, expr, flag) in enumerate((outputs[j], expressions[j], flags[j]) for j in at_end):
            # A true/false output as 1.0 or 0.0: no int or char lane in the loop, which would make GCC
            # vectorise it by 16 or 32 configurations at a time (and run calls of fewer one at a time).
            value = f"({printer.doprint(expr)}) ? 1.0 : 0.0" if flag else text_of_value(expr)
            lines.append(f"    {out}[{k}] = {value};  /* {output} */")
        # All roots finite: 0*x is 0 for a finite x and NaN for an infinite or NaN one, so the sum is 0
        # exactly where every root is finite. One test, no short-circuit branches, so that the loop stays
        # vectorisable however many loops the linkage has.
        finite = f"{' + '.join(f'0.0 * {r.name}' for r in code.roots)} == 0.0 ? 1.0 : 0.0" if code.roots else "1.0"
        return lines + [f"    return {finite};", "}", ""]

    def run_lines(head: str, run: str, given: Sequence[str], function: str, lane: str = lane) -> list[str]:
        """The loop of the last piece (or of the whole program) over m configurations whose arguments are
        contiguous; true/false outputs as 1 and 0 in ``lane``."""
        return [f"{head} void {run}(size_t {size}, " + ", ".join(
            [f"const double *restrict {a}" for a in given]
            + [f"{lane if flags[k] else 'double'} *restrict {output_parameters[k]}" for k in at_end]
            + [f"{lane} *restrict {assembled}"]) + ")", "{",
            f"    for (size_t {index} = 0; {index} < {size}; ++{index}) {{",
            f"        double {out}[{len(at_end)}];",
            f"        {assembled}[{index}] = ({lane}){function}(" + ", ".join(
                [f"{a}[{index}]" for a in given] + [out]) + ");"] + [
            f"        {output_parameters[j]}[{index}] = " + (f"({lane}){out}[{k}];" if flags[j] else f"{out}[{k}];")
            for k, j in enumerate(at_end)] + ["    }", "}", ""]

    pieces: list[str] = []
    piece_prototypes: list[str] = []
    # Each loop function the function calls: its name, what it reads, what it hands on (None: the last) and writes.
    calls: list[tuple[str, list[str], list[str] | None, list[int]]] = []
    run = f"symlink_{name}_run"
    if len(bounds) == 1:
        lines = [f"SYMLINK_INLINE double {kernel}(" + ", ".join([f"double {a}" for a in arguments]
                                                                + [f"double *restrict {out}"]) + ")", "{"]
        used = set().union(*uses.values(),
                           *(e.free_symbols for e in code.outputs.values()))
        lines += [f"    (void){s.name};  /* not needed by these outputs */" for s in code.arguments if s not in used]
        # The angles that only outputs read (atan2, a vector-math call) last: values computed before a call
        # live across it in memory (the call clobbers every vector register), and fewer do when the rates
        # come first. The same operations on the same operands: bit-identical. Measured (interleaved, best of
        # 30-40): full kinematics 4-5 % faster (four-bar), 3 % (Watt II), 7 % (Jansen); positions unchanged.
        read = set().union(*uses.values())
        angles = {symbol.name for symbol, expr in code.assignments if isinstance(expr, sp.atan2) and symbol not in read}
        printed = [p for p in printed if p[0] not in angles] + [p for p in printed if p[0] in angles]
        lines += [f"    const double {symbol} = {text};" for symbol, text in printed]
        lines = final_lines(lines)
        # The kernel over m configurations whose arguments are contiguous; true/false outputs as 16-bit
        # 1 and 0 (32-bit in a loop of rates: RATE_FLAG_LANE). GCC vectorises the loop by its narrowest lane: byte outputs made it take 32
        # configurations at a time with AVX2 (64 with AVX-512), so that a call of fewer ran one at a
        # time, about 5x slower; 16-bit lanes take 16 (32), which measured fastest (floats, 8 at a
        # time, ran positions 5-10 % slower; doubles alone, 4 at a time, 20 % slower).
        lines += run_lines("SYMLINK_INLINE", run, arguments, kernel)
        calls.append((run, list(arguments), None, at_end))
    else:
        lines = []
        for p, (low, high) in enumerate(bounds):
            function, loop = f"symlink_{name}_piece{p}_at", f"symlink_{name}_piece{p}"
            text = kernel_lines(function, piece_inputs[p], low, high, p == last)
            if p == last:
                # True/false values as doubles: one lane width in every piece, so that each is vectorised
                # by as many doubles as a register holds (16-bit lanes make GCC take 4x as many at a time,
                # and take 4x as long to compile the loop).
                text = final_lines(text) + run_lines("SYMLINK_PIECE SYMLINK_LOOP", loop, piece_inputs[p], function,
                                                     PIECE_FLAG_LANE)
                head = run_lines("SYMLINK_PIECE", loop, piece_inputs[p], function, PIECE_FLAG_LANE)[0]
            else:
                # What later pieces read (into block arrays), then the outputs this piece writes.
                handed = piece_outputs[p] + [expressions[k].name for k in written[p]]
                targets_ = piece_outputs[p] + [output_parameters[k] for k in written[p]]
                text += [f"    {out}[{k}] = {v};" for k, v in enumerate(handed)] + ["}", ""]
                head = f"SYMLINK_PIECE void {loop}(size_t {size}, " + ", ".join(
                    [f"const double *restrict {a}" for a in piece_inputs[p]]
                    + [f"double *restrict {v}" for v in targets_]) + ")"
                text += [head.replace("SYMLINK_PIECE", "SYMLINK_PIECE SYMLINK_LOOP", 1), "{",
                         f"    for (size_t {index} = 0; {index} < {size}; ++{index}) {{",
                         f"        double {out}[{len(handed)}];",
                         f"        {function}(" + ", ".join([f"{a}[{index}]" for a in piece_inputs[p]] + [out]) + ");"]
                text += [f"        {v}[{index}] = {out}[{k}];" for k, v in enumerate(targets_)] + ["    }", "}", ""]
            pieces.append("\n".join(text))
            piece_prototypes.append(head + ";")
            calls.append((loop, piece_inputs[p], piece_outputs[p] if p != last else None,
                          written[p] if p != last else at_end))

    # Block arrays for the values that one piece hands to later ones, each reused once its last reader is done.
    slot_of: dict[str, str] = {}
    free_slots: list[str] = []
    slots: list[str] = []
    for p, (_, _, hands, _) in enumerate(calls):
        for v in hands or ():
            if not free_slots:
                slots.append(names(f"{v}_block"))
                free_slots.append(slots[-1])
            slot_of[v] = free_slots.pop(0)
        free_slots += [slot_of[v] for v in slot_of if last_read.get(v) == p and defined_in[v] < p]
    needed = set(arguments) if len(bounds) == 1 else {a for _, given, _, _ in calls for a in given if a in arguments}
    restricted = "SYMLINK_LOOP " + signature.replace("double *", "double *restrict ").replace(
        "unsigned char *", "unsigned char *restrict ")
    # Blocks of configurations: each argument's values of a block are contiguous (the array itself
    # at step 1, else copied). The last block of a call, if its size is not a multiple of
    # SYMLINK_LANES, is padded to one (its inputs copied, the last value repeated; its number
    # outputs written to tails, then copied), so that every value, of a call of 10 as of 10^6, is
    # evaluated by the vectorised loop, none by a scalar remainder (which would also call libm's
    # scalar functions, not always equal to the vector ones in the last place).
    numbers_out = [o for o, flag in zip(output_parameters, flags) if not flag]
    flags_out = [o for o, flag in zip(output_parameters, flags) if flag] + [assembled]
    width = names("w")
    tails = [names(f"{o}_tail") for o in numbers_out]
    targets = [names(f"{o}_to") for o in numbers_out]
    flag_blocks = [names(f"{o}_block") for o in flags_out]
    if len(bounds) > 1:
        lines = _driver_of_pieces(restricted.replace("SYMLINK_LOOP ", "", 1), arguments, steps, [a for a in arguments if a in needed], slots, slot_of,
                                  numbers_out, flags_out, output_parameters, calls, assembled, (count, start, size,
                                                                                                width, index))
        return CFunction(name, tuple(arguments), tuple(outputs), tuple(output_parameters), tuple(flags),
                         prototype, "\n".join(lines) + "\n", tuple(pieces), tuple(piece_prototypes))
    lines += [restricted, "{"]
    if needed:
        lines.append("    double " + ", ".join(f"{b}[SYMLINK_BLOCK]" for a, b in zip(arguments, blocks) if a in needed)
                     + ";")
    if slots:
        lines.append("    double " + ", ".join(f"{b}[SYMLINK_BLOCK]" for b in slots) + ";")
    if tails:
        lines.append("    double " + ", ".join(f"{t}[SYMLINK_BLOCK]" for t in tails) + ";")
    lines.append(f"    {lane} " + ", ".join(f"{b}[SYMLINK_BLOCK]" for b in flag_blocks) + ";")
    lines += [f"    for (size_t {start} = 0; {start} < {count}; {start} += SYMLINK_BLOCK) {{",
              f"        const size_t {size} = {count} - {start} < SYMLINK_BLOCK ? {count} - {start} : SYMLINK_BLOCK;",
              f"        const size_t {width} = ({size} + SYMLINK_LANES - 1) / SYMLINK_LANES * SYMLINK_LANES;"]
    lines += [f"        const double *{v} = symlink_block({b}, {a}, {s}, {start}, {size}, {width});"
              for a, s, b, v in zip(arguments, steps, blocks, views) if a in needed]
    lines += [f"        double *{t} = {width} == {size} ? {o} + {start} : {tail};"
              for o, t, tail in zip(numbers_out, targets, tails)]
    destination = {**dict(zip(numbers_out, targets)), **dict(zip(flags_out, flag_blocks))}
    source_of = {**dict(zip(arguments, views)), **slot_of}
    for function, given, hands, writes in calls:
        if hands is not None:
            lines.append(f"        {function}({width}, " + ", ".join(
                [source_of[v] for v in given] + [slot_of[v] for v in hands]
                + [destination[output_parameters[k]] for k in writes]) + ");")
    final, given, _, writes = calls[-1]
    lines.append(f"        {final}({width}, " + ", ".join(
        [source_of[v] for v in given] + [destination[output_parameters[k]] for k in writes]
        + [destination[assembled]]) + ");")
    lines += [f"        for (size_t {index} = 0; {index} < {size}; ++{index}) {{"]
    lines += [f"            {o}[{start} + {index}] = (unsigned char)({b}[{index}] != 0);"
              for o, b in zip(flags_out, flag_blocks)]
    lines.append("        }")
    if tails:
        lines += [f"        if ({width} != {size}) {{",
                  f"            for (size_t {index} = 0; {index} < {size}; ++{index}) {{"]
        lines += [f"                {o}[{start} + {index}] = {t}[{index}];" for o, t in zip(numbers_out, tails)]
        lines += ["            }", "        }"]
    lines += ["    }", "}"]
    return CFunction(name, tuple(arguments), tuple(outputs), tuple(output_parameters), tuple(flags),
                     prototype, "\n".join(lines) + "\n", tuple(pieces), tuple(piece_prototypes))


def _driver_of_pieces(signature: str, arguments: Sequence[str], steps: Sequence[str], needed: Sequence[str],
                      slots: Sequence[str], slot_of: dict[str, str], numbers_out: Sequence[str],
                      flags_out: Sequence[str], output_parameters: Sequence[str],
                      calls: Sequence[tuple[str, list[str], list[str] | None, list[int]]], assembled: str,
                      locals_: tuple[str, str, str, str, str]) -> list[str]:
    """The loop function of a program in pieces: block by block, its arguments' values made contiguous, each
    piece called in order, the true/false outputs and a last short block's outputs copied out.

    As the one-piece function does, but with its arguments, handed values and outputs in arrays walked by
    loops, so that its text (and its compile time) stays small however many arguments and outputs it has.
    Every local name starts with ``symlink_``, which no name of a program may (:func:`c_identifier`).
    """
    count, start, size, width, index = locals_
    kept = {a: k for k, a in enumerate(needed)}
    slot = {s: k for k, s in enumerate(slots)}
    number = {o: k for k, o in enumerate(numbers_out)}
    flag = {o: k for k, o in enumerate(flags_out)}

    def read(value: str) -> str:
        return f"symlink_at[{kept[value]}]" if value in kept else f"symlink_handed[{slot[slot_of[value]]}]"

    def write(output: str) -> str:
        return f"symlink_to[{number[output]}]" if output in number else f"symlink_flags[{flag[output]}]"

    lines = [signature, "{"]
    lines += [f"    (void){a}; (void){s};  /* not needed by these outputs */"
              for a, s in zip(arguments, steps) if a not in kept]
    step_of = dict(zip(arguments, steps))
    if needed:
        lines += [f"    const double *const symlink_arguments[{len(needed)}] = {{{', '.join(needed)}}};",
                  f"    const ptrdiff_t symlink_steps[{len(needed)}] = {{{', '.join(step_of[a] for a in needed)}}};",
                  f"    double symlink_blocks[{len(needed)}][SYMLINK_BLOCK];",
                  f"    const double *symlink_at[{len(needed)}];"]
    if slots:
        lines.append(f"    double symlink_handed[{len(slots)}][SYMLINK_BLOCK];")
    if numbers_out:
        lines += [f"    double *const symlink_numbers[{len(numbers_out)}] = {{{', '.join(numbers_out)}}};",
                  f"    double symlink_tails[{len(numbers_out)}][SYMLINK_BLOCK];",
                  f"    double *symlink_to[{len(numbers_out)}];"]
    lines += [f"    unsigned char *const symlink_flag_outputs[{len(flags_out)}] = {{{', '.join(flags_out)}}};",
              f"    {PIECE_FLAG_LANE} symlink_flags[{len(flags_out)}][SYMLINK_BLOCK];",
              f"    for (size_t {start} = 0; {start} < {count}; {start} += SYMLINK_BLOCK) {{",
              f"        const size_t {size} = {count} - {start} < SYMLINK_BLOCK ? {count} - {start} : SYMLINK_BLOCK;",
              f"        const size_t {width} = ({size} + SYMLINK_LANES - 1) / SYMLINK_LANES * SYMLINK_LANES;"]
    if needed:
        lines += [f"        for (size_t symlink_k = 0; symlink_k < {len(needed)}; ++symlink_k) {{",
                  "            symlink_at[symlink_k] = symlink_block(symlink_blocks[symlink_k], "
                  f"symlink_arguments[symlink_k], symlink_steps[symlink_k], {start}, {size}, {width});",
                  "        }"]
    if numbers_out:
        lines += [f"        for (size_t symlink_k = 0; symlink_k < {len(numbers_out)}; ++symlink_k) {{",
                  f"            symlink_to[symlink_k] = {width} == {size} ? symlink_numbers[symlink_k] + {start} "
                  ": symlink_tails[symlink_k];", "        }"]
    for function, given, hands, writes in calls:
        lines.append(f"        {function}({width}, " + ", ".join(
            [read(v) for v in given] + [f"symlink_handed[{slot[slot_of[v]]}]" for v in hands or ()]
            + [write(output_parameters[k]) for k in writes] + ([] if hands is not None else [write(assembled)]))
            + ");")
    lines += [f"        for (size_t symlink_k = 0; symlink_k < {len(flags_out)}; ++symlink_k) {{",
              f"            for (size_t {index} = 0; {index} < {size}; ++{index}) {{",
              f"                symlink_flag_outputs[symlink_k][{start} + {index}] = "
              f"(unsigned char)(symlink_flags[symlink_k][{index}] != 0);",
              "            }", "        }"]
    if numbers_out:
        lines += [f"        if ({width} != {size}) {{",
                  f"            for (size_t symlink_k = 0; symlink_k < {len(numbers_out)}; ++symlink_k) {{",
                  f"                for (size_t {index} = 0; {index} < {size}; ++{index}) {{",
                  f"                    symlink_numbers[symlink_k][{start} + {index}] = "
                  f"symlink_tails[symlink_k][{index}];",
                  "                }", "            }", "        }"]
    return lines + ["    }", "}"]


#: The one argument of every ``<name>_packed`` wrapper (:func:`c_packed`), defined once a source.
PACKED_CALL = """#ifndef SYMLINK_PACKED_CALL
#define SYMLINK_PACKED_CALL
/* One call of a <name>_packed wrapper: n configurations; the arguments' arrays and steps in calling
 * order; the outputs as the rows of two blocks, numbers (the number outputs, n doubles a row) and
 * flags (the true/false outputs, then assembled, n bytes a row). */
struct symlink_packed_call {
    size_t n;
    void *const *pointers;
    const ptrdiff_t *steps;
    double *numbers;
    unsigned char *flags;
};
#endif
"""


def c_packed(function: CFunction, lengths: Sequence[str] = (), signs: Sequence[str] = ()) -> str:
    """A wrapper ``<name>_packed(call)`` of a loop function that checks its arguments, ``call`` one struct.

    ``call`` (``struct symlink_packed_call``, :data:`PACKED_CALL`, defined
    before the wrapper) holds the count ``n``, the arguments' arrays and
    steps in calling order, and the outputs as the rows of two blocks,
    ``numbers`` (the number outputs, ``n`` doubles a row, in order) and
    ``flags`` (the true/false outputs, then ``assembled``, ``n`` bytes a
    row).  It first checks the arguments as the NumPy module does (``signs``
    exactly +1 or -1, ``lengths`` from 1e-305 to 1e305, every other value
    finite) and returns ``k + 1`` for the first argument ``k`` that breaks
    that, without evaluating; else it runs the loop and returns 0.  That
    check alone is ``<name>_check(call)`` (the same return, nothing
    evaluated, the outputs not read): a caller writing into outputs of its
    own checks through it, then calls the loop function.  ``<name>_into(call, outputs)`` checks
    and evaluates chunk by chunk (:data:`FUSED_CHUNK` values), into ``outputs`` (a pointer for each
    output, then ``assembled``; ``call``'s blocks are not read): each chunk of a large call's arguments
    is read from memory once, checked and evaluated while it is in the cache (where it refuses an
    argument, the chunks before are written).  A caller
    from another language (symlink's compiled backend through ctypes) then
    passes one pointer a call, to a struct it fills once for many calls, and
    checks nothing itself.

    >>> from symlink.mechanism.catalog import fourbar
    >>> for line in c_packed(c_function(fourbar().program(["rocker"]), "rocker")).splitlines():
    ...     if line.startswith("int "):
    ...         print(line)
    int rocker_check(const struct symlink_packed_call *call)
    int rocker_packed(const struct symlink_packed_call *call)
    int rocker_into(const struct symlink_packed_call *call, void *const *outputs)
    """
    checker = f"symlink_{function.name}_valid"
    tests = []
    kinds = [1 if argument in signs else 2 if argument in lengths else 0 for argument in function.arguments]
    if function.pieces and kinds:  # many arguments: one loop over them, not one inlined check each (short to compile)
        tests.append(f"    static const int kinds[{len(kinds)}] = {{{', '.join(map(str, kinds))}}};\n"
                     f"    for (size_t k = 0; k < {len(kinds)}; ++k) {{\n"
                     f"        if (!{checker}((const double *)pointers[k], steps[k], n, kinds[k])) {{\n"
                     f"            return (int)k + 1;\n        }}\n    }}\n")
    for k, kind in enumerate(kinds if not function.pieces else []):
        tests.append(f"    if (!{checker}((const double *)pointers[{k}], steps[{k}], n, {kind})) {{\n"
                     f"        return {k + 1};\n    }}\n")
    arguments = [f"(const double *)pointers[{k}], steps[{k}]" for k in range(len(function.arguments))]
    rows = {False: 0, True: 0}
    outputs = []
    for flag in list(function.flags) + [True]:
        block = "call->flags" if flag else "call->numbers"
        outputs.append(f"{block} + {rows[flag]} * n")
        rows[flag] += 1
    call = ",\n        ".join(["n"] + arguments + outputs)
    return (PACKED_CALL + "\n"
            f"/* Whether the n values of x (one value at a step of 0) are finite (kind 0), +1 or -1 (1), or a length\n"
            f" * from 1e-305 to 1e305 (2).  Contiguous values are tested by their bits (as signed integers, the\n"
            f" * order of the positive doubles; a negative one or a NaN falls outside), so that the loop is\n"
            f" * vectorised: the same answers as the comparisons of the strided loop. */\n"
            f"SYMLINK_LOOP static int {checker}(const double *x, ptrdiff_t step, size_t n, int kind)\n{{\n"
            f"    const double bounds[3] = {{1e-305, 1e305, 1.0}};\n"
            f"    int64_t low, high, one, bad = 0;\n"
            f"    memcpy(&low, &bounds[0], 8);\n    memcpy(&high, &bounds[1], 8);\n    memcpy(&one, &bounds[2], 8);\n"
            f"    const int64_t exponent = INT64_C(0x7ff0000000000000), magnitude = INT64_MAX;\n"
            f"    const size_t m = step == 0 ? 1 : n;\n"
            f"    if (step == 0 || step == 1) {{\n"
            f"        for (size_t j = 0; j < m; ++j) {{\n"
            f"            int64_t u;\n            memcpy(&u, x + j, 8);\n"
            f"            bad |= kind == 1 ? (u & magnitude) ^ one : kind == 2 ? (int64_t)((u < low) | (u > high)) "
            f": (int64_t)((u & exponent) == exponent);\n"
            f"        }}\n        return bad == 0;\n    }}\n"
            f"    for (size_t j = 0; j < m; ++j) {{\n"
            f"        const double v = x[(ptrdiff_t)j * step];\n"
            f"        bad |= !(kind == 1 ? (v == 1.0 || v == -1.0) : kind == 2 ? (v >= 1e-305 && v <= 1e305) "
            f": v - v == 0.0);\n"
            f"    }}\n    return bad == 0;\n}}\n\n"
            f"int {function.name}_check(const struct symlink_packed_call *call)\n{{\n"
            f"    const size_t n = call->n;\n"
            + (f"    void *const *pointers = call->pointers;\n    const ptrdiff_t *steps = call->steps;\n"
               if function.arguments else "    (void)n;\n")
            + "".join(tests)
            + "    return 0;\n}\n\n"
            f"int {function.name}_packed(const struct symlink_packed_call *call)\n{{\n"
            f"    const int refused = {function.name}_check(call);\n"
            f"    if (refused) {{\n        return refused;\n    }}\n"
            f"    const size_t n = call->n;\n"
            + (f"    void *const *pointers = call->pointers;\n    const ptrdiff_t *steps = call->steps;\n"
               if function.arguments else "")
            + f"    {function.name}({call});\n    return 0;\n}}\n\n"
            + _fused(function, kinds, checker))


#: Values a fused call (``<name>_into``, :func:`c_packed`) checks, then evaluates, at a time: their
#: arguments (six per-value arrays of the four-bar: 192 KB) stay in the cache between the two.
FUSED_CHUNK = 2048


def _fused(function: CFunction, kinds: Sequence[int], checker: str) -> str:
    """``<name>_into(call, outputs)``: the check and the loop of :func:`c_packed`, chunk by chunk, into
    ``outputs`` (one pointer an output, then assembled), so that each chunk of the arguments is read from
    memory once; the first argument refused stops it (``k + 1``; the chunks before are written)."""
    count = len(function.arguments)
    tests = "".join(
        f"        if (!{checker}((const double *)pointers[{k}] + (ptrdiff_t)start * steps[{k}], steps[{k}], m, "
        f"{kind})) {{\n            return {k + 1};\n        }}\n" for k, kind in enumerate(kinds))
    if function.pieces and kinds:  # many arguments: one loop over them (short to compile)
        tests = (f"        static const int kinds[{len(kinds)}] = {{{', '.join(map(str, kinds))}}};\n"
                 f"        for (size_t k = 0; k < {len(kinds)}; ++k) {{\n"
                 f"            if (!{checker}((const double *)pointers[k] + (ptrdiff_t)start * steps[k], steps[k], m, "
                 f"kinds[k])) {{\n                return (int)k + 1;\n            }}\n        }}\n")
    arguments = [f"(const double *)pointers[{k}] + (ptrdiff_t)start * steps[{k}], steps[{k}]" for k in range(count)]
    outputs = [f"({'unsigned char' if flag else 'double'} *)outputs[{k}] + start"
               for k, flag in enumerate(list(function.flags) + [True])]
    call = ",\n            ".join(["m"] + arguments + outputs)
    return (f"int {function.name}_into(const struct symlink_packed_call *call, void *const *outputs)\n{{\n"
            f"    const size_t n = call->n;\n"
            + (f"    void *const *pointers = call->pointers;\n    const ptrdiff_t *steps = call->steps;\n"
               if count else "")
            + f"    for (size_t start = 0; start < n; start += {FUSED_CHUNK}) {{\n"
            f"        const size_t m = n - start < {FUSED_CHUNK} ? n - start : {FUSED_CHUNK};\n"
            + f"        {function.name}({call});\n"
            + tests
            + "    }\n    return 0;\n}\n")


_HEADER = """{title}

Generated by symlink {version} with SymPy {sympy}. Plain C99 and math.h, no allocation; do not edit.{regenerate}

Every function evaluates n configurations in one loop. Each argument x comes
as a pointer and a step: configuration i reads x[i * x_step], so a step of 1
walks an array of n values and a step of 0 uses one value for all of them.
Each output is an array of n doubles, not overlapping the inputs;
assembled[i] is 1 where the linkage closes and 0 where it cannot be
assembled (the outputs are NaN there). Angles in radians.

The arguments must satisfy what the NumPy module checks:
{contract}
These loops do not check them (they never allocate or fail): a NaN gives
NaN outputs and assembled 0, but a branch sign other than +1 or -1 or a
length that is not positive gives meaningless numbers."""

_PRELUDE = """\
/* SYMLINK_LOOP may mark the loop functions for the compiler (symlink's compiled
 * backend defines it to vectorise them); it is empty by default. */
#ifndef SYMLINK_LOOP
#define SYMLINK_LOOP
#endif

/* The per-configuration kernels are inlined into their loops whatever their size,
 * so that a compiler can vectorise the loop of a large linkage too. */
#if defined(__GNUC__)
#define SYMLINK_INLINE static inline __attribute__((always_inline))
#else
#define SYMLINK_INLINE static inline
#endif

static const double symlink_tolerance = {tolerance!r};

/* Configurations a loop function works on at a time, and a multiple of those it evaluates at
 * once (32: the 16-bit lanes of the widest vector registers); SYMLINK_BLOCK is a multiple of it. */
#define SYMLINK_BLOCK 128
#define SYMLINK_LANES 32

/* The copies of arrays for symlink_block (strided, or ending in a short block): not inlined, as a
 * copy inlined for each argument, vectorised for each target, made GCC take 2-3 times as long over a
 * six-bar; one call an array a block costs nothing measurable beside the copy.  Compiled for each
 * target as the loops are (SYMLINK_LOOP): a copy for baseline x86-64 alone, called from an AVX-512
 * loop, made a call of 10 values half a microsecond slower. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
SYMLINK_LOOP static const double *symlink_copy_block(double *restrict block, const double *restrict x,
                                                     ptrdiff_t step, size_t start, size_t m, size_t w)
{{
    for (size_t j = 0; j < m; ++j) {{
        block[j] = x[(ptrdiff_t)(start + j) * step];
    }}
    for (size_t j = m; j < w; ++j) {{
        block[j] = block[m - 1];
    }}
    return block;
}}

/* The values of one argument for configurations start to start + m - 1, contiguous, and
 * up to start + w - 1 (w >= m) repeating the last one: the array itself where its step is 1
 * and w = m, else copied into block. A step of 0 repeats one value, copied on the first block
 * only (w values: all of a call of at most SYMLINK_BLOCK, else the whole block). */
static inline const double *symlink_block(double *block, const double *x, ptrdiff_t step, size_t start, size_t m,
                                          size_t w)
{{
    if (step == 1 && w == m) {{
        return x + start;
    }}
    if (step == 0) {{
        if (start == 0) {{
            for (size_t j = 0; j < w; ++j) {{
                block[j] = *x;
            }}
        }}
        return block;
    }}
    return symlink_copy_block(block, x, step, start, m, w);
}}

/* sqrt(x), taking x >= -tolerance*scale as rounding at a toggle (0) and anything lower,
 * or NaN, as no assembly (NaN). The same as sqrt(fmax(x, 0.0)) where x is not NaN. */
SYMLINK_INLINE double symlink_clamped_sqrt(double x, double scale)
{{
    return x >= -symlink_tolerance * scale ? sqrt(x > 0.0 ? x : 0.0) : NAN;
}}

/* A squared length that must not vanish: x where x >= smallest, NaN below it or for NaN (a
 * direction that is undefined: not assembled). The guard of symlink_clamped_sqrt with a
 * negative scale, for a length that is only ever used squared. */
SYMLINK_INLINE double symlink_nonzero_square(double x, double smallest)
{{
    return x >= smallest ? x : NAN;
}}

/* The largest power of two not above x (a loop's unit), from x's exponent bits: the bits of x
 * with its mantissa cleared. Exact, no logarithm, and vectorised as a bitwise and. For positive
 * normal x, which a loop's mean length is (lengths are checked from 1e-305 to 1e305). */
SYMLINK_INLINE double symlink_power_of_two_below(double x)
{{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    bits &= UINT64_C(0x7ff0000000000000);
    memcpy(&x, &bits, sizeof x);
    return x;
}}

/* 1/x for what symlink_power_of_two_below returns (a loop's unit), as the division gives it and
 * without a division: for a power of two from 2^-1022 to 2^1022 the exponent 2046 - e, for 2^1023 the
 * subnormal 2^-1023, for 0 (a mean length below 2^-1022) infinity. Dividing by the unit once a value
 * was 3-5 % of a loop of full kinematics. Infinity (an infinite or NaN mean length, whose outputs are
 * NaN either way) gives -infinity where the division gives 0. (Which selects and in which domain was
 * measured: this form, an integer select and a double one, was the fastest of those tried.) */
SYMLINK_INLINE double symlink_reciprocal_power_of_two(double x)
{{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    uint64_t inverse = UINT64_C(0x7fe0000000000000) - bits;
    inverse = bits == UINT64_C(0x7fe0000000000000) ? UINT64_C(0x0008000000000000) : inverse;
    double reciprocal;
    memcpy(&reciprocal, &inverse, sizeof reciprocal);
    return x == 0.0 ? INFINITY : reciprocal;
}}

/* cos and sin of atan2(y, x) without calling them, from r = sqrt(x*x + y*y): x/r and y/r
 * (one division for both once inlined), and atan2's values where x = y = 0: cos 1 or -1 by
 * the sign of x, sin the signed zero y. */
SYMLINK_INLINE double symlink_cos_atan2(double x, double r)
{{
    return r != 0.0 ? x * (1.0 / r) : copysign(1.0, x);
}}

SYMLINK_INLINE double symlink_sin_atan2(double y, double r)
{{
    return r != 0.0 ? y * (1.0 / r) : y;
}}
"""


_PIECES_PRELUDE = """\
/* The loop functions of a large program's pieces, which the functions below call in order. External,
 * so that each piece can be compiled apart (see symlink.codegen.c.translation_units), but not exported
 * from a shared library. */
#if defined(__GNUC__)
#define SYMLINK_PIECE __attribute__((visibility("hidden")))
#else
#define SYMLINK_PIECE
#endif
"""


def c_library(functions: Sequence[CFunction], name: str, title: str = "A symlink solver.",
              regenerate: str = "", standalone: bool = False) -> tuple[str, str]:
    """``(header, source)`` of the functions; the source includes ``"<name>.h"``, or repeats its prototypes if ``standalone``."""
    c_identifier(name, "library name")
    seen = [f.name for f in functions]
    if len(set(seen)) != len(seen):
        raise ValueError(f"function names repeat: {', '.join(seen)}")
    comment = c_comment(_HEADER.format(title=title, version=__version__, sympy=sp.__version__,
                                      contract=textwrap.fill(ARGUMENT_CONTRACT + ".", 76),
                                      regenerate=f"\nRegenerate with: {regenerate}" if regenerate else ""))
    guard = f"SYMLINK_{name.upper()}_H"
    header = "\n".join([comment, f"#ifndef {guard}", f"#define {guard}", "", "#include <stddef.h>", "",
                        "#ifdef __cplusplus", 'extern "C" {', "#endif", ""]
                       + [f.prototype for f in functions]
                       + ["#ifdef __cplusplus", "}", "#endif", "", f"#endif /* {guard} */", ""])
    if standalone:
        own = ["#include <stddef.h>", ""] + [f.prototype for f in functions]
    else:
        own = [f'#include "{name}.h"', ""]
    common = [comment, "#include <math.h>", "#include <stdint.h>", "#include <string.h>", ""] + own + [
        _PRELUDE.format(tolerance=TOLERANCE)]
    if not any(f.pieces for f in functions):
        return header, "\n".join(common + [f.definition for f in functions])
    # A large program's pieces: after the common part, each piece and each function its own translation unit.
    common += [_PIECES_PRELUDE] + [prototype for f in functions for prototype in f.piece_prototypes] + [""]
    units = [text for f in functions for text in (*f.pieces, f.definition)]
    return header, "\n".join(common + [f"{UNIT_MARK}\n{text}" for text in units])


def c_code(functions: Sequence[tuple[str, Program, str]], name: str, title: str = "A symlink solver.",
           regenerate: str = "") -> tuple[str, str]:
    """``(header, source)`` with one loop function for each ``(function name, program, docstring)``."""
    return c_library([c_function(p, function, doc) for function, p, doc in functions], name, title, regenerate)


def export_files(linkage: Linkage, stem: str, functions: Sequence[tuple[str, Sequence[str], str]],
                 title: str, regenerate: str = "", form: str = "atan2") -> dict[str, str]:
    """``{"<stem>.h": header, "<stem>.c": source}``: a loop function ``<stem>_<name>`` each ``(name, outputs, doc)``.
    ``form`` is the LaTeX printer's (a seed paper's form of the equations): code has one form, the atan2 form.
    """
    programs = [(f"{stem}_{name}", linkage.program(list(outputs)), doc) for name, outputs, doc in functions]
    header, source = c_code(programs, stem, title, regenerate)
    return {f"{stem}.h": header, f"{stem}.c": source}
