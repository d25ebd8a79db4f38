"""Derived code, cached in memory and on disk, so that the second run of a scene derives nothing.

The key of an entry is a SHA-256 over a canonical description of the linkage
(its loops, inputs, unknowns, parameters, points, roles and extras, written
with :func:`sympy.srepr`), the outputs asked for, the kind of code, the
versions of symlink and SymPy and a digest of symlink's own source files (so
that a development change to the derivations never serves stale code).

Entries live in ``$SYMLINK_CACHE`` (default ``~/.cache/symlink``; an empty
value turns the disk cache off), one JSON file a key, written atomically.
Each entry carries its key and a checksum of key and content: an entry that
cannot be read, belongs to another key or fails its checksum is rebuilt and
rewritten, never used.  The checksum detects corruption, not tampering: the
cache holds code that symlink runs, so keep the folder as private as your
Python installation.  A cache folder that cannot be written is skipped
silently (the memory cache still works).

>>> import os, tempfile
>>> previous = os.environ.get("SYMLINK_CACHE")
>>> os.environ["SYMLINK_CACHE"] = tempfile.mkdtemp()
>>> clear_memory()  # as in a new process
>>> from symlink.catalog import fourbar
>>> code = generated_code(fourbar(), ["rocker"])
>>> sorted(code.function(theta=0.0, a=20, b=66, c=56, d=80))
['assembled', 'rocker']
>>> (cache_directory() / f"{code.key}.json").is_file()
True
>>> _ = os.environ.pop("SYMLINK_CACHE") if previous is None else os.environ.update(SYMLINK_CACHE=previous)
"""
from __future__ import annotations

import hashlib
import inspect
import json
import os
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Callable, Sequence

import sympy as sp

from . import __version__
from .codegen.numpy import load_numpy_module, numpy_module
from .files import write_atomic
from .linkage import Linkage

__all__ = ["GeneratedCode", "generated_code", "cache_directory", "definition", "cache_key",
           "cached_text", "clear_memory", "ENVIRONMENT_VARIABLE"]

ENVIRONMENT_VARIABLE = "SYMLINK_CACHE"
#: Bumped whenever the layout of an entry changes.
FORMAT = 1
#: The name of the function in every cached solver module.
FUNCTION = "solve"

_TEXTS: dict[str, str] = {}
_LOADED: dict[str, "GeneratedCode"] = {}


def cache_directory() -> Path | None:
    """Where entries live: ``$SYMLINK_CACHE``, else ``~/.cache/symlink``; ``None`` when set empty."""
    configured = os.environ.get(ENVIRONMENT_VARIABLE)
    if configured is None:
        return Path.home() / ".cache" / "symlink"
    return Path(configured).expanduser() if configured.strip() else None


def _terms(vectors) -> list:
    return [[sign, sp.srepr(v.length), sp.srepr(v.angle), v.name] for sign, v in vectors.terms]


def definition(linkage: Linkage) -> str:
    """A canonical text of everything that the derived code of ``linkage`` depends on.

    >>> from symlink.catalog import fourbar
    >>> definition(fourbar()) == definition(fourbar())
    True
    """
    symbols = lambda items: [sp.srepr(s) for s in items]  # noqa: E731
    described = {
        "name": linkage.name,
        "loops": [[loop.name, _terms(loop.vectors)] for loop in linkage.loops],
        "inputs": symbols(linkage.inputs),
        "unknowns": symbols(linkage.unknowns),
        "parameters": symbols(linkage.parameters),
        "points": [[name, None if v is None else _terms(v.as_sum())] for name, v in linkage.points.items()],
        "roles": [[role, sp.srepr(q)] for role, q in linkage.roles.items()],
        "extras": [[name, sp.srepr(e)] for name, e in linkage.extras.items()],
    }
    return json.dumps(described, separators=(",", ":"))


@lru_cache(maxsize=1)
def _source_digest() -> str:
    """SHA-256 of symlink's own modules: a change to any derivation is a new key."""
    digest = hashlib.sha256()
    package = Path(__file__).parent
    for path in sorted(package.rglob("*.py")):  # the codegen package's printers included
        digest.update(path.relative_to(package).as_posix().encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


def cache_key(linkage: Linkage, outputs: Sequence[str], kind: str = "numpy") -> str:
    """The key of the ``kind`` code of ``outputs`` of ``linkage``: 64 hex digits."""
    described = json.dumps({
        "format": FORMAT, "kind": kind, "outputs": list(outputs), "linkage": definition(linkage),
        "symlink": __version__, "sympy": sp.__version__, "source": _source_digest(),
    }, separators=(",", ":"))
    return hashlib.sha256(described.encode()).hexdigest()


def _checksum(key: str, text: str) -> str:
    return hashlib.sha256(key.encode() + b"\0" + text.encode()).hexdigest()


def _read(path: Path, key: str) -> str | None:
    """The entry's text if it is whole and belongs to ``key``; ``None`` otherwise."""
    try:
        entry = json.loads(path.read_text(encoding="utf-8"))
        text = entry["text"]
        if (entry["format"] == FORMAT and entry["key"] == key and isinstance(text, str)
                and entry["sha256"] == _checksum(key, text)):
            return text
    except (OSError, ValueError, KeyError, TypeError):
        pass
    return None


def cached_text(key: str, build: Callable[[], str]) -> str:
    """The text stored under ``key``: from memory, else from a verified disk entry, else ``build()``.

    A built text is kept in memory and written to disk; an entry that fails
    verification is rebuilt and overwritten.
    """
    if key in _TEXTS:
        return _TEXTS[key]
    folder = cache_directory()
    path = None if folder is None else folder / f"{key}.json"
    text = None if path is None else _read(path, key)
    if text is None:
        text = build()
        if path is not None:
            entry = {"format": FORMAT, "key": key, "sha256": _checksum(key, text), "text": text}
            try:
                write_atomic(path, json.dumps(entry, indent=0) + "\n")
            except OSError:
                pass  # a read-only cache folder: keep the text in memory only
    _TEXTS[key] = text
    return text


def clear_memory() -> None:
    """Forget what is cached in memory (the disk cache stays): the state of a new process."""
    _TEXTS.clear()
    _LOADED.clear()


@dataclass(frozen=True)
class GeneratedCode:
    """A loaded solver module for some outputs: its ``key``, ``source`` and function."""

    key: str
    source: str
    function: Callable[..., dict]

    @property
    def arguments(self) -> list[str]:
        """The function's argument names, in calling order."""
        return list(inspect.signature(self.function).parameters)


def generated_code(linkage: Linkage, outputs: Sequence[str]) -> GeneratedCode:
    """The NumPy solver of ``outputs``, derived (only what they need) on the first request only.

    Unknown output names raise ``ValueError`` before anything is derived or cached.
    """
    outputs = list(outputs)
    if not outputs:
        raise ValueError(f"ask {linkage.name} for at least one output; it has {', '.join(linkage.output_names())}")
    for name in outputs:
        linkage.output(name)
    key = cache_key(linkage, outputs)
    if key not in _LOADED:
        doc = f"{linkage.name}: {', '.join(outputs)}."
        source = cached_text(key, lambda: numpy_module([(FUNCTION, linkage.program(outputs), doc)]))
        _LOADED[key] = GeneratedCode(key, source, load_numpy_module(source)[FUNCTION])
    return _LOADED[key]
