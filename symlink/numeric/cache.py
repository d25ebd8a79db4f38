"""Derived code, cached in memory and on disk, so that the second run of a scene derives nothing.

The key of an entry is a SHA-256 over a canonical description of the linkage
(its loops, inputs, unknowns, parameters, points, roles and extras, written
with :func:`sympy.srepr`), the outputs asked for, the kind of code, the
versions of symlink and SymPy and a digest of the modules that shape
generated code (:data:`CODE_SHAPING`: a change to a derivation or a printer
is a new key; a change to a plot or the command line is not).

Entries live in ``$SYMLINK_CACHE``, else ``$XDG_CACHE_HOME/symlink``, else
``~/.cache/symlink`` (an empty ``SYMLINK_CACHE`` turns the disk cache off),
one JSON file a key, written atomically.  Each entry carries its key and a
checksum of key and content: an entry that cannot be read, belongs to
another key or fails its checksum is rebuilt and rewritten, never used.

The cache holds code that symlink runs, so only its owner may write it: the
folder is created 0700 and entries 0600 whatever the umask, and nothing is
loaded from a folder or an entry that another user owns or that group or
others can write (a :class:`CacheWarning` says so once, and the code is
derived again in memory).  Entries are opened without blocking and only if
they are regular files; anything unreadable is rebuilt.  A cache folder that
cannot be created or written is skipped silently (the memory cache still
works).

A generated module's entry has a second file beside it: the module's compiled
bytecode (:func:`cached_module`), named for the Python that compiled it (its
bytecode magic number, :data:`importlib.util.MAGIC_NUMBER`, and optimization
level), so that a warm process runs the module without compiling it.  It is
bound by a checksum to the entry's key and text: a bytecode file that is
truncated, corrupted, of another Python or of another entry's text is ignored
(the verified text is compiled again and the file rewritten), never an error
and never run.  It is written whether or not ``PYTHONDONTWRITEBYTECODE`` is set:
like the text entry, it is symlink's own cache, not Python's (an empty
``SYMLINK_CACHE`` turns both off).

>>> import os, tempfile
>>> previous = os.environ.get("SYMLINK_CACHE")
>>> os.environ["SYMLINK_CACHE"] = tempfile.mkdtemp()
>>> clear_memory()  # as in a new process
>>> from symlink.mechanism.catalog import fourbar
>>> code = generated_code(fourbar(), ["rocker"])
>>> sorted(code.function(theta=0.0, a=20, b=66, c=56, d=80))
['assembled', 'rocker']
>>> entry_path(cache_directory(), code.key).is_file(), entry_path(cache_directory(), code.key, bytecode=True).is_file()
(True, True)
>>> _ = os.environ.pop("SYMLINK_CACHE") if previous is None else os.environ.update(SYMLINK_CACHE=previous)
"""
from __future__ import annotations

import importlib.util
import inspect
import json
import marshal
import os
import re
import sys
import warnings
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from types import CodeType
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

from ..version import __version__
from ..common.files import blake2b, sha256, LEFTOVER_AGE, NotPrivate, private_folder, read_private, remove_leftovers, write_atomic

if TYPE_CHECKING:
    from ..symbolic.linkage import Linkage

__all__ = ["GeneratedCode", "generated_code", "cache_directory", "trusted_directory", "definition", "cache_key",
           "cached_text", "clear_memory", "warn_once", "CacheWarning", "CODE_SHAPING", "code_shaping_files",
           "ENVIRONMENT_VARIABLE", "COMPILED_FOLDER", "TEXT_SUFFIX", "BYTECODE_SUFFIX",
           "CATALOG_SHAPING", "catalog_key", "sympy_version", "cached_module", "entry_path"]

ENVIRONMENT_VARIABLE = "SYMLINK_CACHE"
#: Bumped whenever the layout of an entry changes.
FORMAT = 1
#: The name of the function in every cached solver module.
FUNCTION = "solve"

#: What builds and prints a catalog linkage (:mod:`symlink.mechanism.catalog` and every symlink module it imports,
#: directly or not, and the printers), relative to the package, without ``.py``; a name may be a module or a
#: package folder (then every module in it counts).  Its digest stands in for the linkage's definition in
#: :func:`catalog_key`, so that a cached catalog scene is found without building the linkage (or importing
#: SymPy); it is hashed at every warm start, so it holds nothing a catalog linkage does not use.
CATALOG_SHAPING = ("common/names", "common/notation", "common/rounding", "symbolic", "mechanism/catalog", "codegen",
                   "io/export", "numeric/compiled")
#: The modules whose text shapes generated code: their digest is part of every key.  Add a module here
#: when it starts to shape generated text; benchmarks, plots and the command line stay out, so that editing
#: them keeps the cache.  Beyond the catalog's: what builds a linkage with masses and its derivation text.
CODE_SHAPING = CATALOG_SHAPING + ("mechanism/bodies", "dynamics")
#: Largest entry read back (a generated module is some kilobytes; anything far larger is not ours).
ENTRY_LIMIT = 64 << 20

#: The sub-folder of the cache folder where :mod:`symlink.numeric.compiled` keeps its libraries.
COMPILED_FOLDER = "compiled"
#: The endings of an entry's two files (:func:`entry_path`): its text, and its text's bytecode for one Python.
TEXT_SUFFIX, BYTECODE_SUFFIX = ".json", ".code"
#: The first bytes of a bytecode file (the layout's version); then the Python it is for, the checksum of the
#: entry it was compiled from, a SHA-256 of all of that and the code, and the code (:mod:`marshal`).
_BYTECODE_FORMAT = b"symlink bytecode 1\n"

#: The package's folder: where the modules that shape generated code are found, and part of the source digest's key.
_PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

_TEXTS: dict[str, str] = {}
_CODES: dict[str, CodeType] = {}  # key -> the compiled code of its text
_LOADED: dict[str, "GeneratedCode"] = {}
_FOLDERS: dict[str, Path | None] = {}  # folder -> itself when trusted and usable, else None (decided once)
_WARNED: set[str] = set()


class CacheWarning(RuntimeWarning):
    """Something in the disk cache was not used (not private to this user, or unreadable); it was rebuilt."""


def warn_once(message: str, category: type[Warning] = CacheWarning) -> None:
    """Warn with ``message`` the first time this process meets it (``clear_memory`` forgets)."""
    if message not in _WARNED:
        _WARNED.add(message)
        warnings.warn(message, category, stacklevel=3)


def cache_directory() -> Path | None:
    """Where entries live: ``$SYMLINK_CACHE``, else ``$XDG_CACHE_HOME/symlink``, else ``~/.cache/symlink``.

    ``None`` when ``SYMLINK_CACHE`` is set empty (no disk cache).  A relative
    ``XDG_CACHE_HOME`` is ignored, as the XDG specification says.
    """
    configured = os.environ.get(ENVIRONMENT_VARIABLE)
    if configured is not None:
        return Path(configured).expanduser() if configured.strip() else None
    xdg = os.environ.get("XDG_CACHE_HOME", "")
    if xdg and Path(xdg).is_absolute():
        return Path(xdg) / "symlink"
    return Path.home() / ".cache" / "symlink"


def trusted_directory(folder: Path | None = None) -> Path | None:
    """``folder`` (default :func:`cache_directory`) if it is usable: private to this user, created 0700.

    ``None`` when the disk cache is off, when the folder cannot be created
    (silently), or when another user owns it or group or others can write it
    (with a :class:`CacheWarning`: nothing is loaded from it or written to it).
    Decided once a process; the first time, leftovers of killed runs in it
    are removed.
    """
    folder = cache_directory() if folder is None else folder
    if folder is None:
        return None
    name = str(folder)
    try:
        return _FOLDERS[name]
    except KeyError:  # not decided yet in this process
        pass
    decided: Path | None
    try:
        decided = private_folder(folder)
        remove_leftovers(folder, (".build-", ".load-"), LEFTOVER_AGE)
    except NotPrivate as why:
        warn_once(f"symlink: not using the cache folder: {why}; only you may be able to write it "
                  f"(chmod go-w, or set {ENVIRONMENT_VARIABLE} to a folder of your own)")
        decided = None
    except OSError:
        decided = None  # read-only, or a file in the way: the memory cache still works
    _FOLDERS[name] = decided
    return decided  # not read back: another thread may clear the memory (tests) meanwhile


def _terms(vectors) -> list:
    import sympy as sp
    return [[sign, sp.srepr(v.length), sp.srepr(v.angle), v.name] for sign, v in vectors.terms]


def definition(linkage: Linkage) -> str:
    """A canonical text of everything that the derived code of ``linkage`` depends on.

    >>> from symlink.mechanism.catalog import fourbar
    >>> definition(fourbar()) == definition(fourbar())
    True
    """
    import sympy as sp
    symbols = lambda items: [sp.srepr(s) for s in items]  # noqa: E731
    described = {
        "name": linkage.name,
        "loops": [[loop.name, _terms(loop.vectors)] for loop in linkage.loops],
        "inputs": symbols(linkage.inputs),
        "unknowns": symbols(linkage.unknowns),
        "parameters": symbols(linkage.parameters),
        "points": [[name, None if v is None else _terms(v.as_sum())] for name, v in linkage.points.items()],
        "roles": [[role, sp.srepr(q)] for role, q in linkage.roles.items()],
        "extras": _described_extras(linkage),
    }
    return json.dumps(described, separators=(",", ":"))


def definition_digest(linkage: Linkage) -> str:
    """The SHA-256 (hex) of :func:`definition` of ``linkage``: what names its definition in a folder's manifest (a
    stack-up's sampled builds), and what a command keeps among a linkage's cached facts so that a warm run can
    write it without building the linkage (SymPy).

    >>> from symlink.mechanism.catalog import fourbar, slider_crank
    >>> len(definition_digest(fourbar())), definition_digest(fourbar()) == definition_digest(slider_crank())
    (64, False)
    """
    return sha256(definition(linkage).encode()).hexdigest()


def _described_extras(linkage: Linkage) -> list:
    """The extras of ``linkage`` for its definition: each one's expression, or what the linkage says they are
    made from where it can say so without deriving them (a dynamic linkage: its model as given)."""
    import sympy as sp
    described = getattr(linkage, "described_extras", None)
    found = described() if callable(described) else None
    return [[name, sp.srepr(e)] for name, e in linkage.extras.items()] if found is None else found


def code_shaping_files(modules: Sequence[str] = CODE_SHAPING) -> list[Path]:
    """The files of the :data:`CODE_SHAPING` modules (or of ``modules``), in a fixed order.

    >>> names = {path.stem for path in code_shaping_files()}
    >>> "position" in names, "plot" in names
    (True, False)
    """
    return [Path(_PACKAGE) / name for name in _code_shaping_names(tuple(modules))]


@lru_cache(maxsize=4)
def _code_shaping_names(modules: tuple[str, ...]) -> tuple[str, ...]:
    """The files of ``modules`` relative to the package (POSIX), each folder's in the order of their parts.

    Listed with :func:`os.walk` on plain strings (not :meth:`pathlib.Path.rglob`, whose pattern machinery costs a
    warm command some milliseconds); the order is ``sorted(folder.rglob("*.py"))``'s, so the digest is unchanged.
    """
    names: list[str] = []
    for name in modules:
        if os.path.isfile(os.path.join(_PACKAGE, f"{name}.py")):
            names.append(f"{name}.py")
        found: list[str] = []
        for folder, subfolders, files in os.walk(os.path.join(_PACKAGE, name)):
            subfolders[:] = [sub for sub in subfolders if sub != "__pycache__"]
            relative = os.path.relpath(folder, _PACKAGE).replace(os.sep, "/")
            found.extend(f"{relative}/{file}" for file in files if file.endswith(".py"))
        names.extend(sorted(found, key=lambda path: path.split("/")))
    return tuple(names)


def _module_bytes(path: Path) -> bytes:
    return path.read_bytes()


def _module_stat(path: str) -> list[int]:
    """What changes when a file is edited, replaced or checked out again: its modification time (ns), size and
    inode (what Python's own bytecode cache checks, and more)."""
    status = os.stat(path)
    return [status.st_mtime_ns, status.st_size, status.st_ino]


@lru_cache(maxsize=None)
def _module_digest(name: str) -> bytes:
    """BLAKE2b of the package file ``name`` (relative, POSIX): read once a process, though both digests cover it."""
    return blake2b(_module_bytes(Path(_PACKAGE) / name)).digest()


@lru_cache(maxsize=4)
def _source_digest(modules: Sequence[str] = CODE_SHAPING) -> str:
    """BLAKE2b of the modules that shape generated code (each file's name and digest): a change to any of them is a
    new key.

    Hashing that half a megabyte was a sixth of what a warm table adds to NumPy's import, so the digest itself is
    an entry of the cache, keyed by each file's name, modification time, size and inode: a warm process reads it
    after a ``stat`` of each file, and any edit (a new time or size) hashes the files again.  (BLAKE2b, not
    SHA-256 as for the keys and entries: without OpenSSL it is the faster of the two.)
    """
    names = _code_shaping_names(tuple(modules))
    signature = [[name, *_module_stat(os.path.join(_PACKAGE, name))] for name in names]
    key = sha256(json.dumps(["source digest", FORMAT, _PACKAGE, signature], separators=(",", ":")).encode())
    return cached_text(key.hexdigest(), lambda: _hashed_sources(names))


def _hashed_sources(names: Sequence[str]) -> str:
    digest = blake2b()
    for name in names:
        digest.update(name.encode() + b"\0" + _module_digest(name))
    return digest.hexdigest()


def cache_key(linkage: Linkage, outputs: Sequence[str], kind: str = "numpy") -> str:
    """The key of the ``kind`` code of ``outputs`` of ``linkage``: 64 hex digits."""
    import sympy as sp
    described = json.dumps({
        "format": FORMAT, "kind": kind, "outputs": list(outputs), "linkage": definition(linkage),
        "symlink": __version__, "sympy": sp.__version__, "source": _source_digest(),
    }, separators=(",", ":"))
    return sha256(described.encode()).hexdigest()


@lru_cache(maxsize=1)
def sympy_version() -> str:
    """The installed SymPy's version, read from its ``release.py`` without importing SymPy (which takes 0.5 s).

    Where that file cannot be read, its location and modification time stand in: still a new key whenever
    SymPy is replaced.

    >>> import sympy
    >>> sympy_version() == sympy.__version__
    True
    """
    spec = importlib.util.find_spec("sympy")
    if spec is None or spec.origin is None:
        return "none"
    release = Path(spec.origin).parent / "release.py"
    try:
        found = re.search(r"""^__version__\s*=\s*["']([^"']+)["']""", release.read_text(encoding="utf-8"), re.MULTILINE)
        if found:
            return found.group(1)
        return f"{release}@{release.stat().st_mtime_ns}"
    except (OSError, UnicodeDecodeError):
        return f"{spec.origin}@unreadable"


def catalog_key(name: str, outputs: Sequence[str], kind: str, extras: Mapping[str, Any] | None = None,
                shaping: Sequence[str] = ()) -> str:
    """The key of the ``kind`` entry of ``outputs`` of the catalog linkage ``name``, without building it.

    A catalog linkage takes no arguments: it is a function of the catalog's code, the modules that code
    uses (:data:`CATALOG_SHAPING`, hashed) and SymPy's version, so those stand in for its definition.
    Computed in about a millisecond, with no SymPy import.  ``extras``: plain values (JSON) that shape the entry
    besides, such as the mass properties of a catalog linkage's dynamics; the modules of :data:`CODE_SHAPING`
    (and ``shaping``, more modules in its form: those that read a linkage file, say) then stand in for the code.

    >>> key = catalog_key("fourbar", ["rocker"], "scene")
    >>> len(key), key == catalog_key("fourbar", ["coupler"], "scene")
    (64, False)
    """
    facts: dict[str, Any] = {
        "format": FORMAT, "kind": kind, "outputs": list(outputs), "catalog": name,
        "symlink": __version__, "sympy": sympy_version(), "source": _source_digest(CATALOG_SHAPING),
    }
    if extras is not None:  # plain values that shape the entry beyond the catalog (masses, loads): so do dynamics
        facts.update(extras=extras, source=_source_digest(CODE_SHAPING + tuple(shaping)))
    described = json.dumps(facts, separators=(",", ":"), sort_keys=extras is not None)
    return sha256(described.encode()).hexdigest()


def entry_path(folder: Path, key: str, bytecode: bool = False) -> Path:
    """The file of the entry ``key`` in the cache ``folder``: its text, or (``bytecode``) the bytecode of its text
    compiled by this Python (:func:`cached_module`), named for this Python's bytecode magic number and
    optimization level, so that Pythons sharing a cache keep a file each.

    >>> entry_path(Path("cache"), "0" * 64).name == "0" * 64 + ".json"
    True
    >>> entry_path(Path("cache"), "0" * 64, bytecode=True).suffix
    '.code'
    """
    if not bytecode:
        return folder / f"{key}{TEXT_SUFFIX}"
    python = importlib.util.MAGIC_NUMBER.hex() + (f".opt-{sys.flags.optimize}" if sys.flags.optimize else "")
    return folder / f"{key}.{python}{BYTECODE_SUFFIX}"


def _checksum(key: str, text: str) -> str:
    return sha256(key.encode() + b"\0" + text.encode()).hexdigest()


def _read(path: Path, key: str) -> str | None:
    """The entry's text if it is private to this user, whole and belongs to ``key``; ``None`` otherwise.

    A missing entry is ``None`` silently; anything else that is not used says
    why in one :class:`CacheWarning`.
    """
    try:
        entry = json.loads(read_private(path, ENTRY_LIMIT).decode("utf-8"))
        if not isinstance(entry, dict):
            raise ValueError("not a JSON object")
        text = entry["text"]
        if entry["format"] != FORMAT or entry["key"] != key or not isinstance(text, str):
            raise ValueError("written for another key or format")
        if entry["sha256"] != _checksum(key, text):
            raise ValueError("its checksum does not match")
        return text
    except FileNotFoundError:
        return None
    except NotPrivate as why:
        warn_once(f"symlink: not loading a cache entry: {why}; rebuilt")
    except RecursionError:
        warn_once(f"symlink: cache entry {path} is nested too deeply to be ours; rebuilt")
    except (OSError, ValueError, KeyError, TypeError, MemoryError) as why:
        warn_once(f"symlink: cache entry {path} is unreadable ({why}); rebuilt")
    return None


def _write(path: Path, data: str | bytes) -> None:
    """Write an entry's file atomically, 0600; a full disk, a read-only folder or a folder in the way: nothing
    written (the caller keeps what it made in memory)."""
    try:
        if path.is_symlink() or (path.exists() and not path.is_file() and not path.is_dir()):
            path.unlink()  # a FIFO or device in the cache is replaced by the entry, never written into
        write_atomic(path, data, mode=0o600)
    except OSError:
        pass


def cached_text(key: str, build: Callable[[], str]) -> str:
    """The text stored under ``key``: from memory, else from a verified disk entry, else ``build()``.

    A built text is kept in memory and written to disk; an entry that fails
    verification is rebuilt and overwritten.
    """
    if key in _TEXTS:
        return _TEXTS[key]
    folder = trusted_directory()
    path = None if folder is None else entry_path(folder, key)
    text = None if path is None else _read(path, key)
    if text is None:
        text = build()
        if path is not None:
            entry = {"format": FORMAT, "key": key, "sha256": _checksum(key, text), "text": text}
            _write(path, json.dumps(entry, indent=0) + "\n")
    _TEXTS[key] = text
    return text


def _bytecode_header(key: str, text: str) -> bytes:
    """What a bytecode file of the entry ``key`` with ``text`` starts with: the layout, this Python (magic number,
    optimization level) and the entry's checksum (of key and text), so that it pairs with that entry only."""
    python = importlib.util.MAGIC_NUMBER + f" {sys.flags.optimize} ".encode()
    return _BYTECODE_FORMAT + python + _checksum(key, text).encode() + b"\n"


def _read_bytecode(path: Path, header: bytes) -> CodeType | None:
    """The code in the bytecode file ``path`` if it is private to this user, starts with ``header`` and its
    checksum matches; ``None`` otherwise (silently: the text is compiled again; one warning if not private)."""
    try:
        data = read_private(path, ENTRY_LIMIT)
    except NotPrivate as why:
        warn_once(f"symlink: not loading a cache entry's bytecode: {why}; compiled again")
        return None
    except OSError:  # missing, not a regular file, too large
        return None
    digest_end = len(header) + 64
    if not data.startswith(header) or data[len(header):digest_end] != _bytecode_digest(header, data[digest_end:]):
        return None
    try:
        code = marshal.loads(data[digest_end:])
    except (EOFError, ValueError, TypeError):  # checked above: only if the checksum itself were forged
        return None
    return code if isinstance(code, CodeType) else None


def _bytecode_digest(header: bytes, code: bytes) -> bytes:
    return sha256(header + code).hexdigest().encode()


def cached_module(key: str, build: Callable[[], str]) -> tuple[str, dict]:
    """The generated NumPy module stored under ``key`` (:func:`cached_text`): its text and the namespace of running it.

    Its code comes from memory, else from its verified bytecode file beside the entry (:func:`entry_path`), else
    is compiled from the verified text (:func:`~symlink.codegen.loading.compile_numpy_module`) and written
    there.  A bytecode file that cannot be used is ignored and rewritten; a folder that is not trusted is
    neither read nor written, and one that cannot be written costs a compilation per process, nothing more.

    >>> import os, tempfile
    >>> previous = os.environ.get("SYMLINK_CACHE")
    >>> os.environ["SYMLINK_CACHE"] = tempfile.mkdtemp()
    >>> clear_memory()
    >>> text, namespace = cached_module("f" * 64, lambda: "ANSWER = 6 * 7\\n")
    >>> namespace["ANSWER"], entry_path(cache_directory(), "f" * 64, bytecode=True).is_file()
    (42, True)
    >>> clear_memory()  # a new process: the code is read, not compiled
    >>> cached_module("f" * 64, lambda: "never built")[1]["ANSWER"]
    42
    >>> _ = os.environ.pop("SYMLINK_CACHE") if previous is None else os.environ.update(SYMLINK_CACHE=previous)
    """
    from ..codegen.loading import compile_numpy_module, run_numpy_module
    text = cached_text(key, build)
    code = _CODES.get(key)
    if code is None:
        folder = trusted_directory()
        path = None if folder is None else entry_path(folder, key, bytecode=True)
        header = b"" if path is None else _bytecode_header(key, text)
        code = None if path is None else _read_bytecode(path, header)
        if code is None:
            code = compile_numpy_module(text)  # from the verified text: what the bytecode file holds
            if path is not None:
                payload = marshal.dumps(code)
                _write(path, header + _bytecode_digest(header, payload) + payload)
        _CODES[key] = code
    return text, run_numpy_module(code)


def clear_memory() -> None:
    """Forget what is cached in memory (the disk cache stays): the state of a new process."""
    _TEXTS.clear()
    _CODES.clear()
    _LOADED.clear()
    _FOLDERS.clear()
    _WARNED.clear()


@dataclass(frozen=True)
class GeneratedCode:
    """A loaded solver module for some outputs: its ``key``, ``source`` and function."""

    def _repr_html_(self) -> str:
        """A notebook shows the fields as a table (the display module imported only then)."""
        from ..common.display import record_html
        return record_html(self)

    key: str
    source: str
    function: Callable[..., dict]

    @property
    def arguments(self) -> list[str]:
        """The function's argument names, in calling order (not the keyword-only ``check``)."""
        return [name for name, parameter in inspect.signature(self.function).parameters.items()
                if parameter.kind is not parameter.KEYWORD_ONLY]


def generated_code(linkage: Linkage, outputs: Sequence[str]) -> GeneratedCode:
    """The NumPy solver of ``outputs``, derived (only what they need) on the first request only.

    The key is made from what the request names (the linkage's definition and the output names),
    so a request whose code is cached does no symbolic work: not even checking its names, which for a
    sensitivity derives it (an entry exists only for names that were checked when it was derived).
    Unknown output names raise ``ValueError`` before anything is derived or cached.
    """
    from ..codegen.numpy import numpy_module
    outputs = list(outputs)
    if not outputs:
        raise ValueError(f"ask {linkage.name} for at least one output; it has {', '.join(linkage.output_names())}")
    key = cache_key(linkage, outputs)
    if key not in _LOADED:
        def derive() -> str:
            for name in outputs:
                linkage.output(name)  # ValueError naming the outputs there are, before any work
            doc = f"{linkage.name}: {', '.join(outputs)}."
            return numpy_module([(FUNCTION, linkage.program(outputs), doc)])
        source, namespace = cached_module(key, derive)
        _LOADED[key] = GeneratedCode(key, source, namespace[FUNCTION])
    return _LOADED[key]
