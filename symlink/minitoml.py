"""A strict reader of the small part of TOML that scene files use, for Python 3.10 (no ``tomllib``).

On Python 3.11 and later, scene files are read with the standard ``tomllib``;
this module only stands in for it on 3.10, and gives the same result on every
document of the subset below.  Anything outside the subset is an error naming
the line, never a guess:

* comments (``# ...``) and blank lines;
* table headers ``[name]`` with a bare name, each table once;
* ``key = value`` with a bare key (letters, digits, ``_`` and ``-``), each key once a table;
* values: basic strings in double quotes without escapes, decimal integers,
  floats (``1.5``, ``-2e-3``, ``inf``, ``nan``), ``true``/``false``, and
  arrays of those on one line (``[0, 40, 80]``), not nested.

>>> loads('linkage = "fourbar"  # catalog name\\n[parameters]\\na = 20\\nb = 6.6e1\\n')
{'linkage': 'fourbar', 'parameters': {'a': 20, 'b': 66.0}}
>>> loads("[input]\\nangles = [0, 40,]\\n")
{'input': {'angles': [0, 40]}}
"""
from __future__ import annotations

import re

__all__ = ["loads"]

_BARE = r"[A-Za-z0-9_-]+"
_DIGITS = r"[0-9](?:_?[0-9])*"
_INTEGER = re.compile(rf"[+-]?(?:0|[1-9](?:_?[0-9])*)")
_FLOAT = re.compile(rf"[+-]?(?:0|[1-9](?:_?[0-9])*)(?:\.{_DIGITS})?(?:[eE][+-]?{_DIGITS})?|[+-]?(?:inf|nan)")
_HEADER = re.compile(rf"\[\s*({_BARE})\s*\]")
_PAIR = re.compile(rf"({_BARE})\s*=\s*(.*)")
_STRING = re.compile(r'"([^"\\\x00-\x08\x0a-\x1f\x7f]*)"')
_TOKEN = re.compile(r'\s*("[^"]*"|[^,\s\]\[]+)\s*')


def _scalar(text: str, line: int):
    string = _STRING.fullmatch(text)
    if string:
        return string.group(1)
    if text.startswith('"'):
        raise ValueError(f"line {line}: unsupported string {text} (escapes and multi-line strings are not supported)")
    if text in ("true", "false"):
        return text == "true"
    if _INTEGER.fullmatch(text):
        return int(text)
    if _FLOAT.fullmatch(text):
        return float(text)
    raise ValueError(f"line {line}: not a value: {text!r}")


def _array(text: str, line: int) -> list:
    inner = text[1:-1]
    if "[" in inner or "]" in inner:
        raise ValueError(f"line {line}: nested arrays are not supported")
    items, position = [], 0
    while position < len(inner):
        token = _TOKEN.match(inner, position)
        if not token or not token.group(1):
            if inner[position:].strip() == "":
                break
            raise ValueError(f"line {line}: malformed array {text}")
        items.append(_scalar(token.group(1), line))
        position = token.end()
        if position < len(inner):
            if inner[position] != ",":
                raise ValueError(f"line {line}: expected ',' in array {text}")
            position += 1
    return items


def _strip_comment(text: str) -> str:
    """The line without its comment (a ``#`` outside a string)."""
    inside = False
    for index, char in enumerate(text):
        if char == '"':
            inside = not inside
        elif char == "#" and not inside:
            return text[:index]
    return text


def loads(text: str) -> dict:
    """Parse a document of the subset; ``ValueError`` naming the line for anything else."""
    document: dict = {}
    table = document
    for number, raw in enumerate(text.splitlines(), start=1):
        line = _strip_comment(raw).strip()
        if not line:
            continue
        header = _HEADER.fullmatch(line)
        if header:
            name = header.group(1)
            if name in document:
                raise ValueError(f"line {number}: [{name}] is defined twice")
            table = document[name] = {}
            continue
        pair = _PAIR.fullmatch(line)
        if not pair:
            raise ValueError(f"line {number}: expected 'key = value' or '[table]', got {line!r}")
        key, value = pair.group(1), pair.group(2).strip()
        if key in table:
            raise ValueError(f"line {number}: {key!r} is defined twice")
        if value.startswith("["):
            if not value.endswith("]"):
                raise ValueError(f"line {number}: arrays must close on the same line")
            table[key] = _array(value, number)
        else:
            table[key] = _scalar(value, number)
    return document
