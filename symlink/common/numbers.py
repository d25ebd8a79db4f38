"""Numbers read from text of any digits: the one reader of every number a user types or a file holds.

``float()`` takes any digits and rounds them without a word: ``1e999`` and a 1 followed by 400
zeros become ``inf``, ``1e-400`` becomes ``0.0`` (a length that was given becomes no length, a
speed that was given becomes none).  :func:`number_from_text` refuses both in one line: a number
whose digits are not all zeros is never read as zero, and one that is not ``inf`` is never read
as infinite.  ``nan`` and ``inf`` written as such are returned as they are, for the caller's own
message (most refuse them).  :func:`float_of` is the same for a whole number that a parser
(TOML, JSON) has already made an ``int`` of.

>>> number_from_text("-0"), number_from_text("1e3")
(-0.0, 1000.0)
>>> number_from_text("1e-400")
Traceback (most recent call last):
ValueError: 1e-400 is too small for a float: its digits are not all zeros, but it would be read as 0
"""
from __future__ import annotations

import math
import re
import sys
from typing import Any, Callable

from .files import excerpt

__all__ = ["number_from_text", "float_of", "finite_float", "is_zero_digits", "toml_data", "json_data"]


def _toml_loads() -> Any:
    """The TOML reader, imported when a text is read (a command that reads none starts without it)."""
    if sys.version_info >= (3, 11):
        from tomllib import loads
    else:  # Python 3.10: tomli is tomllib before it joined the standard library
        from tomli import loads
    return loads


def is_zero_digits(text: str) -> bool:
    """Whether the digits of a number's mantissa (before any exponent) are all zeros.

    >>> is_zero_digits("-0.000e-5"), is_zero_digits("1e-400")
    (True, False)
    """
    mantissa = text.strip().lower().split("e")[0]
    return not any(c in "123456789" for c in mantissa)


def number_from_text(text: str) -> float:
    """The float of a decimal number's ``text`` (any digits); ``ValueError`` in one line for text that is no
    number, or whose value does not fit a float (it would be read as ``inf``, or as 0 with digits that are not
    all zeros).

    Parameters
    ----------
    text : str
        A decimal number as a user or a file wrote it: ``"20"``, ``"-1.5e3"``, ``"nan"``.

    Returns
    -------
    float
        Its value; ``nan`` and ``inf`` written as such are returned for the caller to refuse in its words.

    Examples
    --------
    >>> from symlink.common.numbers import number_from_text
    >>> number_from_text("2.5e-3")
    0.0025
    >>> number_from_text("1" + "0" * 400)
    Traceback (most recent call last):
    ValueError: 100000000000000000000000000000000000000000000000000000000000... is too large for a float (at most 1.8e+308)
    """
    stripped = text.strip()
    try:
        value = float(stripped)
    except (ValueError, OverflowError):
        raise ValueError(f"not a number: {excerpt(text)}") from None
    shown = stripped if len(stripped) <= 60 else stripped[:60] + "..."
    written_infinite = stripped.lower().lstrip("+-") in ("inf", "infinity", "nan")
    if math.isinf(value) and not written_infinite:
        raise ValueError(f"{shown} is too large for a float (at most 1.8e+308)")
    if value == 0 and not is_zero_digits(stripped):
        raise ValueError(f"{shown} is too small for a float: its digits are not all zeros, but it would be read as 0")
    return value


def float_of(value: int | float) -> float:
    """A parsed number (``int`` of any digits, or ``float``) as a float: ``inf`` for an integer too large for
    one, never an ``OverflowError``.

    >>> float_of(3), float_of(10 ** 400)
    (3.0, inf)
    """
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf


def finite_float(value: object) -> float | None:
    """The float of a number that a parser or a caller's mapping holds (an ``int`` of any digits, a ``float``,
    a NumPy number), or ``None`` when it is no number (``True``, text, ``None``) or not finite (``nan``, ``inf``,
    ``10 ** 400``): the one check behind every "must be a finite number" of a mapping's value, which never
    raises ``OverflowError``.

    >>> finite_float(3), finite_float(2.5), finite_float(True), finite_float(10 ** 400), finite_float("1")
    (3.0, 2.5, None, None, None)
    """
    import numbers
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return None
    try:
        found = float(value)
    except (OverflowError, TypeError, ValueError):
        return None
    return found if math.isfinite(found) else None


class _NumberOutOfRange(ValueError):
    """A TOML number whose digits do not fit a float (:func:`number_from_text`)."""

    def __init__(self, token: str, message: str) -> None:
        super().__init__(message)
        self.token = token


def _toml_float(token: str) -> float:
    try:
        return number_from_text(token.replace("_", ""))
    except ValueError as error:
        raise _NumberOutOfRange(token, str(error)) from None


def toml_data(text: str) -> dict[str, Any]:
    """The TOML ``text`` of a linkage or scene file, every float's digits range-checked (``1e-400`` is not read
    as 0, ``1e999`` not as infinity); ``ValueError`` ``"line L: problem"`` for text that is not valid TOML.

    >>> toml_data("a = 2.5")
    {'a': 2.5}
    >>> toml_data("b = 1e-400")
    Traceback (most recent call last):
    ValueError: line 1: 1e-400 is too small for a float: its digits are not all zeros, but it would be read as 0
    """
    try:
        return _toml_loads()(text, parse_float=_toml_float)
    except _NumberOutOfRange as error:
        at = text.find(error.token)
        raise ValueError(f"line {text.count(chr(10), 0, max(at, 0)) + 1}: {error}") from None
    except RecursionError:
        raise ValueError("line 1: nested too deeply") from None
    except ValueError as error:  # tomllib.TOMLDecodeError: its message ends "(at line L, column C)"
        if "integer string conversion" in str(error):  # int() of more digits than Python converts (4300)
            long = re.search(r"[0-9][0-9_]{4000,}", text)
            line = text.count(chr(10), 0, long.start()) + 1 if long else 1
            raise ValueError(f"line {line}: a whole number of thousands of digits is too large for a float "
                             "(at most 1.8e+308)") from None
        found = re.search(r"line (\d+)", str(error))
        message = re.sub(r"\s*\(at line \d+, column \d+\)|^line \d+: ", "", str(error))
        raise ValueError(f"line {found.group(1) if found else '1'}: not valid TOML: {message}") from None


def _json_number(check: Callable[[float, str], None] | None, whole: bool = False) -> Callable[[str], float]:
    def read(token: str) -> float:
        try:
            value = number_from_text(token)  # any digits, range-checked: never int() of 5000 digits
        except ValueError as error:
            raise ValueError(f"the number is out of range: {error}") from None
        if check is not None:
            check(value, token)
        return int(token) if whole else value  # a whole number that fits a float has at most 309 digits
    return read


def _json_constant(token: str) -> float:
    raise ValueError(f"{token} is not a number (JSON has no NaN or Infinity)")


def _json_object(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    found: dict[str, Any] = {}
    for key, value in pairs:
        if key in found:
            raise ValueError(f"the key {excerpt(key)} is given twice in one object")
        found[key] = value
    return found


def json_data(text: str | bytes, what: str = "JSON", limit: int | None = None,
              number: Callable[[float, str], None] | None = None) -> Any:
    """The JSON ``text`` of a user's file or request, read strictly: ``ValueError`` ``"WHAT: problem"`` in one
    line for text that is not JSON, larger than ``limit`` characters, nested too deeply, with a key given
    twice in one object (JSON readers keep the last without a word), or with a number that does not fit a
    float (:func:`number_from_text`: ``1e-400`` is not read as 0, ``1e999`` not as infinity); ``NaN`` and
    ``Infinity`` (not JSON) are refused.

    Parameters
    ----------
    text : str or bytes
        The JSON text (bytes as UTF-8; a leading byte-order mark is dropped).
    what : str, optional
        What the text is, for messages (``"pylinkage JSON"``).
    limit : int, optional
        The most characters read.
    number : callable, optional
        ``number(value, token)`` further checks each number (a range of the format's own), raising
        ``ValueError``.

    Returns
    -------
    object
        The parsed value: dicts, lists, strings, numbers (whole numbers as ``int``), booleans and None.

    Examples
    --------
    >>> from symlink.common.numbers import json_data
    >>> json_data('{"a": [1, 2.5]}')
    {'a': [1, 2.5]}
    >>> json_data('{"a": 1, "a": 2}', "design")
    Traceback (most recent call last):
    ValueError: design: the key 'a' is given twice in one object
    """
    if isinstance(text, (bytes, bytearray)):
        try:
            text = bytes(text).decode("utf-8")
        except UnicodeDecodeError as error:
            raise ValueError(f"{what}: not JSON: not UTF-8 text (byte {error.start})") from None
    if text.startswith("\ufeff"):
        text = text[1:]
    if limit is not None and len(text) > limit:
        raise ValueError(f"{what}: {len(text):,} characters, more than it may hold (at most {limit:,})")
    import json  # here, not at the top: a warm table reads no JSON and starts without it
    try:
        return json.loads(text, parse_int=_json_number(number, whole=True), parse_float=_json_number(number),
                          parse_constant=_json_constant, object_pairs_hook=_json_object)
    except json.JSONDecodeError as error:
        raise ValueError(f"{what}: not JSON: {error.msg} at line {error.lineno}, column {error.colno}") from None
    except RecursionError:
        raise ValueError(f"{what}: nested too deeply") from None
    except ValueError as error:
        raise ValueError(f"{what}: {error}") from None
