"""JavaScript export: a solver for the browser (and Node), one configuration a call, in plain ES2015.

The body is the same common-subexpression-eliminated straight-line code as the
NumPy module (:func:`symlink.codegen.program.straight_line`, the sines and cosines
of the solved angles from their ``atan2`` arguments by
:func:`~symlink.codegen.trigonometry.angle_sums`), printed with the same operations
in the same order on scalars: the same clamped square root and tolerance, the same
loop units (exact powers of two), ``x*x`` for NumPy's ``square``.  The values differ
from the NumPy module's only where ``Math.sin``, ``Math.cos`` and ``Math.atan2`` differ
from the C library's in the last place.

The text needs no import and is usable three ways (a UMD wrapper):

* ``<script>``: it adds the solver to the global ``SymlinkSolvers`` under the
  linkage's name (``SymlinkSolvers["fourbar"]``);
* Node: ``require("./fourbar.js")`` is the solver (``module.exports``);
* ``new Function("return " + text)()`` is the solver (the text is one expression
  statement whose value is the solver; ``new Function(text)()`` registers it in
  ``globalThis.SymlinkSolvers`` as a script does).

The solver is an object ``{name, arguments, inputs, parameters, branches, rates,
defaults, outputs, flags, sets, solve, solveMany}``:

* ``arguments`` are every argument's name in the NumPy module's order, split
  into ``inputs``, ``parameters``, ``branches`` and ``rates`` (the inputs'
  rates and accelerations); ``defaults`` are the NumPy module's defaults
  (a branch +1, a rate 0), for a caller to fill in: ``solve`` takes none;
* ``solve(values, out)`` takes an object mapping every argument's name to a
  number (one configuration: an animation frame) and fills and returns ``out``
  (an object, created if absent) with every output by name and ``assembled``
  (true or false).  Where the linkage cannot be assembled (a clamped square root's
  argument below its tolerance, the NumPy module's test) every output is NaN and
  ``assembled`` false: never a wrong pose.  A missing argument, or one that is not
  a finite number (a branch exactly +1 or -1, a length from 1e-305 to 1e305, as
  the NumPy module checks), throws a ``RangeError`` naming it;
* ``solveMany(values, count)`` takes an array (a ``Float64Array``, another typed
  array or an array) of ``count`` values or one number (shared by all) for each
  argument and returns ``{output, assembled, count}``: ``output`` a
  ``Float64Array`` whose ``count`` values from ``k * count`` are output ``k`` (in
  the order of ``outputs``), ``assembled`` a ``Uint8Array`` of 1 and 0.  ``count``
  may be left out when an argument is an array;
* true/false outputs (``flags``: ``singular``) are the numbers 1 and 0, NaN where
  not assembled, like every other output.

Names: every argument and output keeps its linkage name as a key; inside the code
a symbol whose name JavaScript reserves or the code reads as a global
(:data:`symlink.common.names.JAVASCRIPT_KEYWORDS`: ``delete``, ``this``, ``Math``)
is renamed (``delete_``), and every name of the code's own starts with ``symlink_``,
which no linkage name may.  Names reach strings only through JSON
(:func:`js_string`), and text reaches comments only through :func:`js_comment`.

:func:`javascript_geometry` writes the solver a drawing needs: every joint's and
named point's ``x_<point>`` and ``y_<point>`` (with a ``points`` list that maps the
names to them), each slider's ``direction_<joint>``, and the bodies through them.

>>> from symlink.mechanism.catalog import fourbar
>>> text = javascript_solver(fourbar().program(["rocker"]), "fourbar", fourbar())
>>> text.startswith("(function (root, factory) {") and "Math.atan2(" in text
True
>>> js_string('a "quoted" </script> name')
'"a \\\\"quoted\\\\" \\\\u003c/script\\\\u003e name"'
"""
from __future__ import annotations

import json
import math
import re
import textwrap
from dataclasses import replace
from typing import TYPE_CHECKING, Iterable, Mapping, Sequence

import sympy as sp
from sympy.printing.jscode import JavascriptCodePrinter

from ..version import __version__
from ..common.names import JAVASCRIPT_KEYWORDS, PLAIN_NAME
from ..mechanism.bodies import PRISMATIC, drawn_points, mechanism
from ..symbolic.linkage import is_branch_name
from ..common.rounding import TOLERANCE
from .numpy import sum_text
from .program import FreshNames, is_flag, require_loop_units, straight_line
from .trigonometry import angle_sums

if TYPE_CHECKING:
    from ..symbolic.linkage import Linkage, Program

__all__ = ["JavaScriptPrinter", "javascript_solver", "javascript_geometry", "geometry_program", "javascript_names",
           "js_string", "js_comment", "export_files", "NO_CLOSED_FORM"]

#: The refusal of a linkage without a closed form (solved by Newton's method, which this printer does not port).
NO_CLOSED_FORM = "no closed form: the JavaScript printer needs one"

#: What ``solve`` and ``solveMany`` accept, in words (the NumPy module's checks, on numbers).
CONTRACT = ("numbers only (typeof \"number\"); branch signs exactly +1 or -1; lengths positive, from 1e-305 "
            "to 1e305; every other value finite")

#: The prefix of every name the generated code defines itself; no linkage name may start with it.
PREFIX = "symlink_"


def js_string(text: str) -> str:
    """``text`` as a JavaScript string literal (JSON, ASCII only) that is also safe inside an HTML ``<script>``.

    ``<``, ``>`` and ``&`` are escaped too, so that no ``</script>`` or ``<!--`` can appear.

    >>> print(js_string("delete"))
    "delete"
    """
    return (json.dumps(text, ensure_ascii=True).replace("<", "\\u003c").replace(">", "\\u003e")
            .replace("&", "\\u0026"))


def js_comment(text: str, indent: str = "") -> str:
    """``text`` as a JavaScript block comment that nothing in it can end, nor end a ``<script>`` around it.

    ``*/`` and ``/*`` are spaced out, and so are ``</`` and ``<!`` (which could end or hide an
    HTML script block); every character that is not printable becomes a space.

    >>> print(js_comment("Ends */ here </script>\\nSecond\\u2028line."))
    /* Ends * / here < /script>
     * Second line.
     */
    """
    text = "".join(c if c.isprintable() or c == "\n" else " " for c in text.strip())
    text = text.replace("*/", "* /").replace("/*", "/ *").replace("</", "< /").replace("<!", "< !")
    lines = text.splitlines() or [""]
    return "\n".join([f"{indent}/* {lines[0]}".rstrip()] + [f"{indent} * {line}".rstrip() for line in lines[1:]]
                     ) + (" */" if len(lines) == 1 else f"\n{indent} */")


def javascript_names(names: Iterable[str]) -> dict[str, str]:
    """Each name's JavaScript identifier: itself, or with underscores added where JavaScript reserves it.

    ``ValueError`` for a name that is not plain (:data:`~symlink.common.names.PLAIN_NAME`) or that starts
    with ``symlink_``, the generated code's own prefix.

    >>> javascript_names(["theta", "delete", "delete_", "Math"])
    {'theta': 'theta', 'delete': 'delete__', 'delete_': 'delete_', 'Math': 'Math_'}
    """
    names = list(dict.fromkeys(names))
    for name in names:
        if not PLAIN_NAME.match(name) or name.startswith(PREFIX):
            raise ValueError(f"name {name!r} is not usable in JavaScript (an ASCII letter, then letters, digits "
                             f"and underscores; not starting with {PREFIX!r})")
    fresh = FreshNames({n for n in names if n not in JAVASCRIPT_KEYWORDS}, JAVASCRIPT_KEYWORDS)
    return {name: fresh(name) if name in JAVASCRIPT_KEYWORDS else name for name in names}


def _number(value: float) -> str:
    """A double as a JavaScript literal that reads back as the same double."""
    if math.isnan(value):
        return "NaN"
    if math.isinf(value):
        return "Infinity" if value > 0 else "(-Infinity)"
    return repr(value)


class JavaScriptPrinter(JavascriptCodePrinter):
    """ES2015 on numbers with the NumPy printer's operations, symlink's helpers and renamed symbols.

    ``names`` maps each symbol's name to its identifier (:func:`javascript_names`); any other symbol is refused.
    """

    def __init__(self, names: Mapping[str, str]):
        super().__init__({"allow_unknown_functions": False})
        self.names = dict(names)

    def _print_Symbol(self, expr):
        if expr.name not in self.names:
            raise ValueError(f"symbol {expr.name!r} is not defined in the generated JavaScript")
        return self.names[expr.name]

    def _print_Float(self, expr):
        return _number(float(expr))

    # Every number as the nearest double, as the NumPy module computes it (1/4 is 0.25 there too).
    _print_Integer = _print_Rational = _print_Float

    def _print_NumberSymbol(self, expr):
        return _number(float(expr))

    _print_Pi = _print_Exp1 = _print_NumberSymbol

    def _print_Pow(self, expr, rational=False):
        base, exponent = expr.base, expr.exp
        if exponent == -1:  # as the NumPy printer: 1/x
            return f"1/{self.parenthesize(base, 1000)}"
        if exponent == 2:  # NumPy's square, x*x exactly
            factor = self._print(base) if base.is_Symbol or base.is_Function else f"({self._print(base)})"
            return f"({factor}*{factor})"
        if exponent == sp.S.Half:
            return f"Math.sqrt({self._print(base)})"
        if exponent == -sp.S.Half:
            return f"1/Math.sqrt({self._print(base)})"
        return f"Math.pow({self._print(base)}, {self._print(sp.Float(exponent) if exponent.is_Rational else exponent)})"

    def _print_Add(self, expr, order=None):
        """As the NumPy printer writes a sum (``y - x`` for ``-x + y``), so the terms are added in the same order."""
        return sum_text(self, expr, order)

    def _print_Abs(self, expr):
        return f"Math.abs({self._print(expr.args[0])})"

    def _print_Relational(self, expr):
        op = {"==": "===", "!=": "!=="}.get(expr.rel_op, expr.rel_op)
        return f"({self._print(expr.lhs)} {op} {self._print(expr.rhs)})"

    def _print_And(self, expr):
        return "(" + " && ".join(self._print(a) for a in sorted(expr.args, key=sp.default_sort_key)) + ")"

    def _print_Or(self, expr):
        return "(" + " || ".join(self._print(a) for a in sorted(expr.args, key=sp.default_sort_key)) + ")"

    def _print_Not(self, expr):
        return f"(!{self._print(expr.args[0])})"

    def _print_BooleanTrue(self, expr):
        return "true"

    def _print_BooleanFalse(self, expr):
        return "false"

    def _print_PowerOfTwoBelow(self, expr):  # the prelude defines the helpers
        return f"symlink_power_of_two_below({self._print(expr.args[0])})"

    def _print_CosineOfAtan2(self, expr):
        return f"symlink_cos_atan2({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_SineOfAtan2(self, expr):
        return f"symlink_sin_atan2({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_ClampedSqrt(self, expr):
        require_loop_units(expr)
        return f"symlink_clamped_sqrt({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_NonzeroSquare(self, expr):
        return f"symlink_nonzero_square({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_Piecewise(self, expr):  # pragma: no cover - a guard, never reached by symlink's own forms
        raise ValueError("symlink never writes Piecewise into generated code")

    def doprint(self, expr, assign_to=None):
        text = super().doprint(expr, assign_to)
        if "--" in text or "++" in text:  # pragma: no cover - a guard: JavaScript would read a decrement
            raise ValueError(f"generated JavaScript would read {text!r} as an increment or decrement")
        return text


_PRELUDE = """\
    "use strict";

    const symlink_tolerance = {tolerance};

    /* sqrt(x), taking x >= -tolerance*scale as rounding at a toggle (0) and anything lower, or NaN, as no
     * assembly (NaN): the NumPy module's _clamped_sqrt. */
    function symlink_clamped_sqrt(x, scale) {{
        return x >= -symlink_tolerance * scale ? Math.sqrt(x > 0 ? x : 0) : NaN;
    }}

    /* A squared length that must not vanish: x where x >= smallest, NaN below it or for NaN. */
    function symlink_nonzero_square(x, smallest) {{
        return x >= smallest ? x : NaN;
    }}

    /* The largest power of two not above x (a loop's unit), from x's exponent bits: exact, as the
     * NumPy module's ldexp(0.5, frexp(x)[1]) for the positive normal x that a loop's mean length is. */
    const symlink_bits = new Float64Array(1);
    const symlink_words = new Uint32Array(symlink_bits.buffer);
    const symlink_high = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1 ? 1 : 0;
    function symlink_power_of_two_below(x) {{
        symlink_bits[0] = x;
        symlink_words[symlink_high] &= 0x7ff00000;
        symlink_words[1 - symlink_high] = 0;
        return symlink_bits[0];
    }}

    /* cos and sin of atan2(y, x) from r = sqrt(x*x + y*y): x/r and y/r, and atan2's values where
     * x = y = 0 (cos 1 or -1 by the sign of x, sin the signed zero y), as the NumPy module. */
    function symlink_cos_atan2(x, r) {{
        return r !== 0 ? x / r : (1 / x < 0 ? -1 : 1);
    }}

    function symlink_sin_atan2(y, r) {{
        return y / (r !== 0 ? r : 1);
    }}

    /* The RangeError of an argument that is missing or out of its range (kind 0: a finite number,
     * 1: a branch sign, +1 or -1, 2: a length from 1e-305 to 1e305). */
    function symlink_refuse(name, value, kind, own, where) {{
        const wanted = kind === 1 ? "must be +1 or -1"
            : kind === 2 ? "must be a positive finite length, from 1e-305 to 1e305" : "must be a finite number";
        const got = typeof value === "number" ? String(value) : typeof value === "string" ? JSON.stringify(value)
            : value === null ? "null" : "a value of type " + typeof value;
        if (value === undefined || (!own && typeof value !== "number")) {{
            throw new RangeError(symlink_name + ": the argument " + name + " is missing" + where
                                 + "; the arguments are " + symlink_arguments.join(", "));
        }}
        throw new RangeError(symlink_name + ": " + name + where + " " + wanted + ", got " + got);
    }}

    function symlink_values_of(values, what) {{
        if (values === null || typeof values !== "object") {{
            throw new TypeError(symlink_name + ": " + what + " takes an object mapping every argument's name "
                                + "to a number; the arguments are " + symlink_arguments.join(", "));
        }}
        return values;
    }}

    function symlink_good(value, kind) {{
        return typeof value === "number" && (kind === 1 ? value === 1 || value === -1
            : kind === 2 ? value >= 1e-305 && value <= 1e305 : value - value === 0);
    }}

    /* One argument's values for solveMany: an array-like of count numbers, or one number for all
     * (a Float64Array of length 1). */
    function symlink_column(values, name, kind, count) {{
        const own = Object.prototype.hasOwnProperty.call(values, name);
        const value = values[name];
        if (typeof value === "number") {{
            if (!symlink_good(value, kind)) {{
                symlink_refuse(name, value, kind, own, "");
            }}
            return new Float64Array([value]);
        }}
        if (value === null || typeof value !== "object" || typeof value.length !== "number") {{
            symlink_refuse(name, value, kind, own, "");
        }}
        if (value.length !== count) {{
            throw new RangeError(symlink_name + ": " + name + " has " + value.length + " values, not " + count);
        }}
        for (let i = 0; i < count; i++) {{
            if (!symlink_good(value[i], kind)) {{
                symlink_refuse(name, value[i], kind, true, "[" + i + "]");
            }}
        }}
        return value instanceof Float64Array ? value : Float64Array.from(value);
    }}

    /* How many configurations solveMany evaluates: count, else the length of the first array argument. */
    function symlink_count_of(values, count) {{
        if (count === undefined) {{
            count = 1;
            for (let k = 0; k < symlink_arguments.length; k++) {{
                const value = values[symlink_arguments[k]];
                if (value !== null && typeof value === "object" && typeof value.length === "number") {{
                    count = value.length;
                    break;
                }}
            }}
        }}
        if (!(typeof count === "number" && Number.isInteger(count) && count >= 0 && count <= 4294967295)) {{
            throw new RangeError(symlink_name + ": solveMany's count must be a whole number, got " + String(count));
        }}
        return count;
    }}
"""


def _kind(symbol: sp.Symbol) -> int:
    """An argument's check: 1 a branch sign, 2 a length, 0 any finite number (as the NumPy module checks)."""
    return 1 if is_branch_name(symbol.name) else 2 if symbol.is_positive else 0


def _groups(arguments: Sequence[str], linkage: Linkage | None) -> dict[str, list[str]]:
    """The argument names as the linkage's inputs, parameters, branches and rates (without one: by their names)."""
    if linkage is None:
        branches = [a for a in arguments if is_branch_name(a)]
        return {"inputs": [a for a in arguments if a not in branches], "parameters": [], "branches": branches,
                "rates": []}
    kinds = {"inputs": {s.name for s in linkage.inputs}, "parameters": {s.name for s in linkage.parameters},
             "branches": {s.name for s in linkage.branches}}
    groups = {group: [a for a in arguments if a in names] for group, names in kinds.items()}
    grouped = set().union(*kinds.values())
    groups["rates"] = [a for a in arguments if a not in grouped]
    return groups


def _json(value: object) -> str:
    """A JSON value as JavaScript: every string through :func:`js_string`."""
    if isinstance(value, str):
        return js_string(value)
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{js_string(k)}: {_json(v)}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_json(v) for v in value) + "]"
    if isinstance(value, bool) or value is None:
        return json.dumps(value)
    if isinstance(value, (int, float)):
        return _number(float(value)) if isinstance(value, float) else str(value)
    raise TypeError(f"no JavaScript for {value!r}")  # pragma: no cover - a guard


def _frozen(value: object) -> str:
    """A JSON value as JavaScript, its arrays and objects frozen (a caller cannot change a solver's lists)."""
    if isinstance(value, Mapping):
        return "Object.freeze({" + ", ".join(f"{js_string(k)}: {_frozen(v)}" for k, v in value.items()) + "})"
    if isinstance(value, (list, tuple)):
        return "Object.freeze([" + ", ".join(_frozen(v) for v in value) + "])"
    return _json(value)


def javascript_solver(program: Program, name: str, linkage: Linkage | None = None, title: str = "",
                      doc: str = "", regenerate: str = "", sets: Mapping[str, Sequence[str]] | None = None,
                      extra: Mapping[str, object] | None = None) -> str:
    """The text of a solver computing the program's outputs (see the module's documentation for its use).

    ``name`` is the solver's name and the key it is registered under (the linkage's name); ``linkage``,
    where given, sorts the arguments into inputs, parameters, branches and rates.  ``sets`` (set name ->
    output names) and ``extra`` (more fields, JSON values) are copied into the solver object.
    """
    if not isinstance(name, str) or not name:
        raise ValueError("a JavaScript solver needs a name")
    if not program.outputs:
        raise ValueError(f"{name}: a JavaScript solver needs at least one output")
    if "assembled" in program.outputs:
        raise ValueError(f"{name}: no output may be named 'assembled', which every solver adds")
    code = straight_line(program)
    arguments = [s.name for s in code.arguments]
    code = angle_sums(code, set(arguments))
    names = javascript_names(arguments + [s.name for s, _ in code.assignments])
    printer = JavaScriptPrinter(names)
    outputs = list(code.outputs)
    expressions = list(code.outputs.values())
    flags = [o for o, e in zip(outputs, expressions) if is_flag(e)]
    groups = _groups(arguments, linkage)
    count = len(outputs)

    parameters = [names[a] for a in arguments] + ["symlink_out", "symlink_at", "symlink_step"]
    lines = ["    /* One configuration: its outputs into symlink_out[symlink_at + k * symlink_step], k in the order of",
             "     * the outputs; whether it is assembled (else every output is NaN). */",
             f"    function symlink_kernel({', '.join(parameters)}) {{"]
    for symbol, expr in code.assignments:
        lines.append(f"        const {names[symbol.name]} = {printer.doprint(expr)};")
    if code.roots:
        finite = " + ".join(f"({names[r.name]} - {names[r.name]})" for r in code.roots)
        lines += [f"        if (!({finite} === 0)) {{  /* a root is NaN: not assembled */",
                  f"            for (let symlink_k = 0; symlink_k < {count}; symlink_k++) {{",
                  "                symlink_out[symlink_at + symlink_k * symlink_step] = NaN;",
                  "            }", "            return false;", "        }"]
    for k, (output, expr) in enumerate(zip(outputs, expressions)):
        value = f"{printer.doprint(expr)} ? 1 : 0" if is_flag(expr) else printer.doprint(expr)
        place = "symlink_at" + ("" if k == 0 else " + symlink_step" if k == 1 else f" + {k} * symlink_step")
        lines.append(f"        symlink_out[{place}] = {value};  {js_comment(output)}")
    lines += ["        return true;", "    }", ""]

    # solve: one configuration, its arguments read by name and checked.
    lines += [f"    const symlink_scratch = new Float64Array({count});", "",
              "    function symlink_solve(symlink_values, symlink_result) {",
              '        symlink_values_of(symlink_values, "solve");']
    for k, symbol in enumerate(code.arguments):
        key, kind = js_string(symbol.name), _kind(symbol)
        test = {1: f"symlink_a{k} === 1 || symlink_a{k} === -1",
                2: f"symlink_a{k} >= 1e-305 && symlink_a{k} <= 1e305", 0: f"symlink_a{k} - symlink_a{k} === 0"}[kind]
        lines += [f"        const symlink_a{k} = symlink_values[{key}];",
                  f"        if (typeof symlink_a{k} !== \"number\" || !({test})) {{",
                  f"            symlink_refuse({key}, symlink_a{k}, {kind}, "
                  f"Object.prototype.hasOwnProperty.call(symlink_values, {key}), \"\");", "        }"]
    call = ", ".join([f"symlink_a{k}" for k in range(len(arguments))] + ["symlink_scratch", "0", "1"])
    lines += [f"        const symlink_assembled = symlink_kernel({call});",
              "        const symlink_out = symlink_result === undefined || symlink_result === null ? {} : symlink_result;"]
    lines += [f"        symlink_out[{js_string(output)}] = symlink_scratch[{k}];" for k, output in enumerate(outputs)]
    lines += ["        symlink_out.assembled = symlink_assembled;", "        return symlink_out;", "    }", ""]

    # solveMany: count configurations, each argument an array or one number.
    lines += ["    function symlink_solve_many(symlink_values, symlink_count) {",
              '        symlink_values_of(symlink_values, "solveMany");',
              "        const symlink_n = symlink_count_of(symlink_values, symlink_count);"]
    for k, symbol in enumerate(code.arguments):
        lines += [f"        const symlink_c{k} = symlink_column(symlink_values, {js_string(symbol.name)}, "
                  f"{_kind(symbol)}, symlink_n);",
                  f"        const symlink_s{k} = symlink_c{k}.length === symlink_n ? 1 : 0;"]
    call = ", ".join([f"symlink_c{k}[symlink_i * symlink_s{k}]" for k in range(len(arguments))]
                     + ["symlink_output", "symlink_i", "symlink_n"])
    lines += [f"        const symlink_output = new Float64Array({count} * symlink_n);",
              "        const symlink_assembled = new Uint8Array(symlink_n);",
              "        for (let symlink_i = 0; symlink_i < symlink_n; symlink_i++) {",
              f"            symlink_assembled[symlink_i] = symlink_kernel({call}) ? 1 : 0;",
              "        }",
              "        return {output: symlink_output, assembled: symlink_assembled, count: symlink_n};", "    }", ""]

    fields: dict[str, object] = {"name": name, "arguments": arguments, **groups,
                                 "defaults": {a: code.defaults[a] for a in arguments if a in code.defaults},
                                 "outputs": outputs, "flags": flags,
                                 "sets": {k: list(v) for k, v in (sets or {"solve": outputs}).items()}}
    for key, value in (extra or {}).items():
        if key in fields or key in ("solve", "solveMany"):
            raise ValueError(f"{name}: the solver field {key!r} is the printer's own")
        fields[key] = value
    lines += ["    const symlink_solver = {"]
    lines += [f"        {key}: {_frozen(value)}," for key, value in fields.items()]
    lines += ["        solve: symlink_solve,", "        solveMany: symlink_solve_many", "    };",
              "    return Object.freeze(symlink_solver);"]

    text = _HEADER.format(title=title or f"{name} solver.", version=__version__, sympy=sp.__version__,
                          name=json.dumps(name), arguments=", ".join(arguments), outputs=", ".join(outputs),
                          contract=CONTRACT)
    paragraphs = [textwrap.fill(paragraph, 100) for paragraph in text.split("\n\n")]
    if regenerate:  # one line, as the other printers write it
        paragraphs[1] += f"\nRegenerate with: {regenerate}"
    described = [textwrap.fill(line, 100, subsequent_indent="  ") for line in doc.strip().splitlines() if line.strip()]
    paragraphs[1:1] = ["\n".join(described)] if described else []
    header = js_comment("\n\n".join(paragraphs), "    ")
    prelude = (_PRELUDE.format(tolerance=_number(TOLERANCE))
               + f"\n    const symlink_name = {js_string(name)};\n"
               f"    const symlink_arguments = {_json(arguments)};\n\n")
    key = js_string(name)
    return ("(function (root, factory) {\n"
            "    var solver = factory();\n"
            '    if (typeof module === "object" && module && module.exports) {\n'
            "        module.exports = solver;\n"
            "    } else if (root) {\n"
            f"        root.SymlinkSolvers = Object.assign(root.SymlinkSolvers || {{}}, {{[{key}]: solver}});\n"
            "    }\n"
            "    return solver;\n"
            '})(typeof self !== "undefined" ? self : this, function () {\n'
            + header + "\n" + prelude + "\n".join(lines) + "\n});\n")


_HEADER = """{title}

Generated by symlink {version} with SymPy {sympy}. Plain ES2015, no imports; do not edit.

Use: a script element adds the solver to SymlinkSolvers[{name}]; in Node, require() returns it; so does \
new Function("return " + text)().

solver.solve(values, out) takes an object of numbers, one a name: {arguments}; and fills out (an object, \
created if absent) with {outputs}; and assembled (false where the linkage cannot close: every output is NaN \
there). Angles in radians. A missing argument, or one that breaks the contract, throws a RangeError naming \
it. The contract: {contract}.

solver.solveMany(values, count) takes for each argument an array of count numbers (or one number for all) \
and returns {{output, assembled, count}}: output[k * count + i] is output k of configuration i (in the order \
of solver.outputs), assembled[i] is 1 or 0. True/false outputs (solver.flags) are 1 or 0 (NaN where not \
assembled)."""


def geometry_program(linkage: Linkage, outputs: Sequence[str] = (),
                     bodies: Mapping[str, Sequence[str]] | None = None) -> tuple[Program, dict[str, object]]:
    """The program of a drawing's solver and the fields that say what its outputs are.

    Its outputs are ``outputs`` (the linkage's, by name) and then, for every joint, slider guide and named
    point of :func:`~symlink.mechanism.bodies.drawn_points` in its order, ``x_<point>`` and ``y_<point>``
    (characters other than letters, digits and ``_`` become ``_``; a name taken already gets more ``_``),
    and ``direction_<joint>`` for every slider (its guide's angle).  The fields are ``points`` (each
    ``{name, x, y, kind}``: kind ``joint``, ``guide`` or ``point``), ``bodies`` (each ``{name, joints,
    points}``, the names of the points on it that are placed) and ``sliders`` (each ``{name, guide,
    direction}``).  ``bodies`` places vectors on bodies where their directions alone are ambiguous, as
    :func:`~symlink.mechanism.bodies.mechanism` takes it.  ``ValueError`` (:data:`NO_CLOSED_FORM`) without a
    closed form.
    """
    if not linkage.has_closed_form:
        raise ValueError(f"{linkage.name}: {NO_CLOSED_FORM}")
    drawing = mechanism(linkage, bodies)
    sums = drawn_points(linkage, drawing)
    outputs = list(dict.fromkeys(outputs))
    program = linkage.program([q.name for q in linkage.unknowns] + [o for o in outputs
                                                                     if o not in {q.name for q in linkage.unknowns}])
    wanted = {o: program.outputs[o] for o in outputs}
    taken = set(wanted) | {"assembled"}

    def fresh(text: str) -> str:
        while text in taken:
            text += "_"
        taken.add(text)
        return text

    joints = {j.name for j in drawing.joints}
    guides = {f"{j.name} guide" for j in drawing.joints if j.kind == PRISMATIC}
    points = []
    for point, total in sums.items():
        stem = re.sub(r"[^A-Za-z0-9_]", "_", point)
        x, y = fresh(f"x_{stem}"), fresh(f"y_{stem}")
        wanted[x] = sp.Add(*(sign * vector.x for sign, vector in total.terms))
        wanted[y] = sp.Add(*(sign * vector.y for sign, vector in total.terms))
        kind = "guide" if point in guides else "joint" if point in joints else "point"
        points.append({"name": point, "x": x, "y": y, "kind": kind})
    sliders = []
    for joint in drawing.joints:
        if joint.kind == PRISMATIC:
            direction = fresh("direction_" + re.sub(r"[^A-Za-z0-9_]", "_", joint.name))
            wanted[direction] = sp.sympify(joint.direction)
            sliders.append({"name": joint.name, "guide": f"{joint.name} guide" if f"{joint.name} guide" in sums
                            else None, "direction": direction})
    placed = set(sums)
    drawn_bodies = [{"name": body.name, "joints": [j for j in body.joints if j in placed],
                     "points": [p for p in body.points if p in placed]} for body in drawing.bodies]
    return replace(program, outputs=wanted), {"points": points, "bodies": drawn_bodies, "sliders": sliders}


def javascript_geometry(linkage: Linkage, outputs: Sequence[str] = (), title: str = "", regenerate: str = "",
                        bodies: Mapping[str, Sequence[str]] | None = None) -> str:
    """The text of a solver that places every joint and point of ``linkage`` (and computes ``outputs``, by name).

    Its outputs and fields are :func:`geometry_program`'s: ``x_B``, ``y_B`` for a point ``B``, listed in
    ``solver.points`` as ``{name: "B", x: "x_B", y: "y_B", kind: "joint"}``, so that a page can draw any
    linkage from this solver alone (``solver.sets``: ``requested``, the ``outputs`` asked for, and
    ``geometry``, the rest); as :meth:`symlink.numeric.poses.Geometry.poses` places them, NaN where
    the linkage cannot be assembled.  ``ValueError`` (:data:`NO_CLOSED_FORM`) without a closed form.

    Parameters
    ----------
    linkage : Linkage
        A linkage with a closed form.
    outputs : sequence of str, optional
        More outputs to compute beside the joints' places, by name.
    title, regenerate : str, optional
        The solver's title and the command that regenerates it, written in its header comment.
    bodies : mapping of str to sequence of str, optional
        The links by name and their joints, where the linkage's own bodies are not wanted.

    Returns
    -------
    str
        The JavaScript text (ES2015, no imports): ``require`` it, load it as a script, or ``new Function``.

    Examples
    --------
    >>> import symlink
    >>> text = symlink.javascript_geometry(symlink.fourbar())
    >>> text.startswith("(function"), '"x_C"' in text, "Math.sqrt" in text
    (True, True, True)
    """
    program, fields = geometry_program(linkage, outputs, bodies)
    placed = [p["name"] for p in fields["points"]]  # type: ignore[attr-defined]
    requested = list(dict.fromkeys(outputs))
    sets = ({"requested": requested} if requested else {}) | {"geometry": list(program.outputs)[len(requested):]}
    return javascript_solver(program, linkage.name, linkage, title or f"{linkage.name}: every joint and point placed.",
                             f"Points: {', '.join(placed)}.", regenerate, sets, fields)


def export_files(linkage: Linkage, stem: str, functions: Sequence[tuple[str, Sequence[str], str]],
                 title: str, regenerate: str = "", form: str = "atan2") -> dict[str, str]:
    """``{"<stem>.js": text}``: one solver of every output of the ``(name, outputs, doc)`` sets, in order.

    A browser page calls one solver a frame, so the sets (positions, velocities, accelerations, joints)
    are one solver, whose ``sets`` field names each set's outputs.
    ``form`` is the LaTeX printer's (a seed paper's form of the equations): code has one form, the atan2 form.
    """
    if not getattr(linkage, "has_closed_form", True):
        raise ValueError(f"{linkage.name}: {NO_CLOSED_FORM}")
    outputs = list(dict.fromkeys(o for _, names, _ in functions for o in names))
    sets = {name: list(names) for name, names, _ in functions}
    doc = "\n".join(f"{name}: {text.strip()}" for name, _, text in functions if text.strip())
    text = javascript_solver(linkage.program(outputs), linkage.name, linkage, title, doc, regenerate, sets)
    return {f"{stem}.js": text}
