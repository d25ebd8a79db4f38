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
from typing import Any

from .files import excerpt

__all__ = ["number_from_text", "float_of", "is_zero_digits", "toml_data"]


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
        found = re.search(r"line (\d+)", str(error))
        message = re.sub(r"\s*\(at line \d+, column \d+\)|^line \d+: ", "", str(error))
        raise ValueError(f"line {found.group(1) if found else '1'}: not valid TOML: {message}") from None
