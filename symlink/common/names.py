"""The names a user gives a linkage, and the rule that keeps them out of generated code's way.

Every name a user writes (symbols of lengths, angles and coordinates, loop and
point names, roles, extra outputs) becomes an identifier in generated Python,
C, MATLAB/Octave and JavaScript code and a key of its results.  So each one must be an
ASCII identifier (a letter, then letters, digits and underscores; no unicode
lookalikes), must not be a keyword of any of those languages, and must not be
a name the generated code uses itself: the module ``numpy``, the math
functions C and Octave call, the local ``shape``, the intermediates of the
closed forms (``Wx_1``, ``w_1``, ``Delta_1``, ...), the common subexpressions
(``cse_0``), the branch signs (``branch``, ``branch_<loop>``) and the
``symlink_`` prefix of C helpers.  A linkage's own name is free text in
messages and docstrings only, so it may also have single spaces and hyphens
between its words.

JavaScript is the exception: its reserved words and the globals its generated
code reads (:data:`JAVASCRIPT_KEYWORDS`: ``delete``, ``this``, ``Math``, ...)
are not refused, since the JavaScript printer renames such a local
(``delete_``) while the keys of its arguments and results keep the user's
name; a name refused for it would break linkage files written before it.

Checking at definition time means a bad name is refused with a sentence
saying which name and why, rather than ending in a SyntaxError or a wrong
value in code generated later.

>>> identifier("theta", "coordinate")
'theta'
>>> identifier("w_1", "parameter")
Traceback (most recent call last):
ValueError: parameter 'w_1' clashes with a generated intermediate (closed-form helpers are named Wx_1, w_1, Delta_1, size_1, ...); rename it
>>> label("inverted slider-crank")
'inverted slider-crank'
"""
from __future__ import annotations

import keyword
import re

__all__ = ["identifier", "label", "reason_reserved", "INTERMEDIATE_FAMILIES", "MAX_LENGTH", "RESERVED", "PLAIN_NAME",
           "C_KEYWORDS", "OCTAVE_KEYWORDS", "JAVASCRIPT_KEYWORDS", "FORMER_CATALOG_NAMES", "SIX_BAR_DEFINITIONS",
           "FORMER_SIX_BAR_NAMES", "SixBarNameNote", "former_name_note"]

#: Longest user name: derived names (``<name>ddot``, ``<role>_accel``, ``branch_<loop>``) must fit
#: MATLAB's 63 characters.
MAX_LENGTH = 56

#: The shape of every name in generated code: an ASCII letter, then ASCII letters, digits or underscores.
PLAIN_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z", re.ASCII)
_LABEL = re.compile(r"[A-Za-z][A-Za-z0-9_]*(?:[ -][A-Za-z0-9_]+)*\Z", re.ASCII)

#: Names of the closed forms' intermediates, each followed by ``_<loop number>`` (see symlink.symbolic.position).
INTERMEDIATE_FAMILIES = ("Wx", "Wy", "w", "wsq", "Delta", "size", "rho")
_INTERMEDIATE = re.compile(r"(?:%s)(?:_[0-9]+)+\Z" % "|".join(INTERMEDIATE_FAMILIES))

C_KEYWORDS = frozenset("""
auto break case char const continue default do double else enum extern float for goto if inline int long
register restrict return short signed sizeof static struct switch typedef union unsigned void volatile while
_Bool _Complex _Imaginary size_t ptrdiff_t NAN INFINITY""".split())
OCTAVE_KEYWORDS = frozenset("""
break case catch classdef continue do else elseif end end_try_catch end_unwind_protect endclassdef
endenumeration endevents endfor endfunction endif endmethods endparfor endproperties endspmd endswitch
endwhile enumeration events for function global if methods otherwise parfor persistent properties
return spmd switch try until unwind_protect unwind_protect_cleanup while nargin nargout varargin
varargout ans""".split())
#: JavaScript's reserved words (ECMAScript 2015, strict mode and the future reserved ones), the literals
#: and the globals that generated JavaScript reads, which a local of it must not shadow: the JavaScript
#: printer renames a symbol so named (``delete`` -> ``delete_``) instead of refusing it (see above).
JAVASCRIPT_KEYWORDS = frozenset("""
break case catch class const continue debugger default delete do else enum export extends finally for
function if implements import in instanceof interface let new package private protected public return
static super switch this throw try typeof var void while with yield await null true false eval arguments
undefined NaN Infinity Math Object Number Array String Error RangeError TypeError Float64Array Uint8Array
Uint32Array JSON globalThis self window module exports require root factory""".split())
#: Functions and constants the generated code calls by their bare name (C's math.h, Octave's builtins).
_FUNCTIONS = frozenset("""
sin cos tan asin acos atan atan2 sinh cosh tanh asinh acosh atanh exp log log10 log2 sqrt cbrt pow hypot
abs fabs floor ceil round fmod fmax fmin max min sign copysign isfinite isnan isinf size true false ones all
isnumeric isreal error
zeros nan NaN Inf inf pi""".split())
#: Names the generated modules use themselves: modules, locals, outputs and the Newton driver's globals.
_GENERATED = frozenset("""
numpy math sympy shape check solve singular assembled residual guess inputs parameters unknowns positions
velocities accelerations sensitivities TOLERANCE EPSILON RESIDUAL_TOLERANCE SINGULAR_CONDITION POSITION_TOLERANCE
MAX_PREDICTION MAX_CORRECTION CONTRACTION MAX_ITERATIONS ASSEMBLY_ITERATIONS MIN_FRACTION LARGEST_BLOCK
INPUTS PARAMETERS UNKNOWNS ANGLE_INPUTS ROLES""".split())

#: Every whole name a user may not take (prefixes and intermediate families are checked apart).
#: The keyword of a solver call that takes the caller's output arrays (``solver(..., out=arrays)``).
_CALL_KEYWORDS = frozenset({"out"})

RESERVED = frozenset(keyword.kwlist) | C_KEYWORDS | OCTAVE_KEYWORDS | _FUNCTIONS | _GENERATED | _CALL_KEYWORDS


def reason_reserved(name: str) -> str | None:
    """Why generated code cannot take ``name`` (a clause), or None if it can.

    >>> reason_reserved("lambda")
    'is a keyword of Python, C or MATLAB/Octave'
    >>> reason_reserved("beta") is None
    True
    """
    if name in keyword.kwlist or name in C_KEYWORDS or name in OCTAVE_KEYWORDS:
        return "is a keyword of Python, C or MATLAB/Octave"
    if name in _FUNCTIONS:
        return "is a function or constant that the generated C or MATLAB/Octave code calls"
    if name in _GENERATED:
        return "is a name the generated code uses itself"
    if name in _CALL_KEYWORDS:
        return "is the keyword a solver call takes for the caller's output arrays (out=)"
    if _INTERMEDIATE.match(name):
        return ("clashes with a generated intermediate (closed-form helpers are named "
                "Wx_1, w_1, Delta_1, size_1, ...)")
    if name == "branch" or name.startswith("branch_"):
        return "clashes with the branch signs (branch, branch_<loop>) that the linkage adds"
    if name.startswith("cse_"):
        return "starts with 'cse_', the prefix of generated common subexpressions"
    if name.startswith("symlink_"):
        return "starts with 'symlink_', the prefix of generated helpers"
    return None


def identifier(name: object, what: str) -> str:
    """``name`` if generated code can take it as an identifier; ``ValueError`` naming ``what`` and why otherwise."""
    if not isinstance(name, str):
        raise ValueError(f"{what} name must be text, got {name!r}")
    if not PLAIN_NAME.match(name):
        raise ValueError(f"{what} {name!r} is not a plain name: use an ASCII letter, then ASCII letters, "
                         "digits or underscores")
    if len(name) > MAX_LENGTH:
        raise ValueError(f"{what} {name!r} is longer than {MAX_LENGTH} characters")
    why = reason_reserved(name)
    if why:
        raise ValueError(f"{what} {name!r} {why}; rename it")
    return name


def label(name: object, what: str = "linkage name") -> str:
    """A linkage's display name: words of ASCII letters, digits and underscores, single spaces or hyphens between.

    It reaches docstrings, comments and messages only, but never as raw text: no quotes, backslashes,
    newlines, comment markers or percent signs can get in.

    >>> label("x*/")
    Traceback (most recent call last):
    ValueError: linkage name 'x*/' may hold only ASCII letters, digits and underscores, with single spaces or hyphens between words
    """
    if not isinstance(name, str):
        raise ValueError(f"{what} must be text, got {name!r}")
    if not _LABEL.match(name):
        raise ValueError(f"{what} {name!r} may hold only ASCII letters, digits and underscores, "
                         "with single spaces or hyphens between words")
    if len(name) > 2 * MAX_LENGTH:
        raise ValueError(f"{what} {name!r} is longer than {2 * MAX_LENGTH} characters")
    if name in keyword.kwlist or name in C_KEYWORDS or name in OCTAVE_KEYWORDS:
        raise ValueError(f"{what} {name!r} is a keyword of Python, C or MATLAB/Octave; rename it")
    return name


#: Catalog linkages by a former name (the catalog's Stephenson six-bar was ``stephenson3`` before the six-bars were
#: numbered as :mod:`symlink.mechanism.atlas` cites): the one table of them, SymPy-free, so that a warm command by
#: the former name is as warm as by the current one.
FORMER_CATALOG_NAMES = {"stephenson3": "stephenson2"}


#: The six-bars by their atlas names, and what each is (the one table of them: :mod:`symlink.mechanism.atlas` cites
#: the numbering).  Plain text, SymPy-free, so that a warm command by a former name says what it names.
SIX_BAR_DEFINITIONS = {
    "watt-i": "Watt chain (the ternary links share a pin), the ground a binary link",
    "watt-ii": "Watt chain (the ternary links share a pin), the ground a ternary link",
    "stephenson-i": "Stephenson chain (binary links keep the ternary links apart), the ground a binary link pinned "
                    "to both ternary links",
    "stephenson-ii": "Stephenson chain (binary links keep the ternary links apart), the ground a binary link pinned "
                     "to one ternary link",
    "stephenson-iii": "Stephenson chain (binary links keep the ternary links apart), the ground a ternary link",
}

#: Names symlink gave before its numbering was fixed, and what they name now: the catalog's Stephenson six-bar
#: (its ground a binary link pinned to one ternary link) was ``stephenson3``.
FORMER_SIX_BAR_NAMES = {"stephenson3": "stephenson-ii"}


class SixBarNameNote(UserWarning):
    """A six-bar name read as an alias (the other numbering, or a former name): the one-line note says what it names."""


def former_name_note(text: str) -> str | None:
    """The one-line note that ``text`` is a former six-bar name and what it names now; None for any other text.

    Every reader of a former name (the atlas's :func:`~symlink.mechanism.atlas.six_bar_name`, a warm table command)
    says it in these words.

    Parameters
    ----------
    text : str
        A name as the user gave it.

    Returns
    -------
    str or None
        The note, or None where ``text`` is no former name.

    Examples
    --------
    >>> former_name_note("stephenson3").startswith("'stephenson3' is symlink's former name of stephenson-ii: ")
    True
    >>> former_name_note("stephenson2") is None
    True
    """
    plain = text.strip()
    name = FORMER_SIX_BAR_NAMES.get(plain.lower())
    if name is None:
        return None
    return (f"{plain!r} is symlink's former name of {name}: {SIX_BAR_DEFINITIONS[name]} (symlink numbered "
            "Stephenson II and III the other way before)")
