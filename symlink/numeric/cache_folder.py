"""What symlink keeps in a cache folder, and clearing it: the ``symlink cache`` command's two questions.

Apart from :mod:`symlink.numeric.cache` (keys and entries), which every warm command imports: listing and clearing
a folder is asked for by ``symlink cache`` and by a user, never on the way to a table.

Only the names symlink writes count (:data:`_OWN_NAMES`, :data:`_OWN_COMPILED_NAMES`); anything else in the
folder is counted as ``others`` and left alone, and nothing is followed through a symbolic link.

>>> import os, tempfile
>>> from pathlib import Path
>>> from symlink.numeric.cache import cache_directory, clear_memory, generated_code
>>> previous = os.environ.get("SYMLINK_CACHE")
>>> os.environ["SYMLINK_CACHE"] = tempfile.mkdtemp()
>>> clear_memory()  # as in a new process
>>> from symlink.mechanism.catalog import fourbar
>>> code = generated_code(fourbar(), ["rocker"])
>>> contents = cache_contents(cache_directory())
>>> contents.trusted, contents.entries >= 2  # the solver's text and bytecode, and the source digest if new
(True, True)
>>> clear_cache(cache_directory()).entries == contents.entries, cache_contents(cache_directory()).entries
(True, 0)
>>> _ = os.environ.pop("SYMLINK_CACHE") if previous is None else os.environ.update(SYMLINK_CACHE=previous)
"""
from __future__ import annotations

import os
import re
import stat
from dataclasses import dataclass
from pathlib import Path

from ..common.files import private_folder
from .cache import BYTECODE_SUFFIX, COMPILED_FOLDER, TEXT_SUFFIX, clear_memory

__all__ = ["CacheContents", "cache_contents", "clear_cache"]

_HEX64 = "[0-9a-f]{64}"
#: The names of entries' files (:func:`entry_path`): ``<key>.json``, ``<key>.<magic number, hex>[.opt-N].code``.
_ENTRY_NAMES = rf"{_HEX64}(?:\{TEXT_SUFFIX}|\.[0-9a-f]{{8}}(?:\.opt-[0-9])?\{BYTECODE_SUFFIX})"
#: The names symlink writes, and nothing else: what :func:`clear_cache` removes and :func:`cache_contents` counts.
#: In the cache folder: entries' files and the temporary files of their atomic writes (``.<name>.<12 hex>.tmp``).
#: (Patterns as text, compiled by :mod:`re` when the cache is listed or cleared: a warm command compiles none.)
_OWN_NAMES = rf"(?:{_ENTRY_NAMES}|\.{_ENTRY_NAMES}\.[0-9a-f]{{12}}\.tmp)\Z"
#: In ``compiled/``: libraries, their digests, the temporary files of the digests' writes, the private copies
#: made to load a library and the folders libraries are built in (:func:`tempfile.mkdtemp` names).
_OWN_COMPILED_NAMES = (rf"(?:{_HEX64}\.(?:so|sha256)|\.{_HEX64}\.sha256\.[0-9a-f]{{12}}\.tmp"
                       rf"|\.load-[0-9a-f]{{16}}\.so|\.build-[a-z0-9_]{{8}})\Z")



@dataclass(frozen=True)
class CacheContents:
    """What symlink keeps in a cache ``folder``: ``entries`` (files and build folders) of ``size`` bytes in all.

    ``trusted`` is False (and ``problem`` says why) when another user owns the
    folder or group or others can write it: symlink neither loads from it nor
    clears it.  ``others`` counts the names in it that symlink did not write
    (left alone).  A folder that does not exist is trusted and empty.
    """

    folder: Path
    exists: bool
    trusted: bool
    problem: str
    entries: int
    size: int
    others: int
    #: Of the ``entries``, those left by interrupted or failed builds and writes (build folders, temporaries).
    leftovers: int = 0


def _is_own(path: Path, names: str) -> bool:
    """True when ``path`` has one of ``names`` and the kind symlink writes there: a regular file, or a folder
    for a build folder (``.build-*``); never a symbolic link."""
    if not re.match(names, path.name):
        return False
    kind = stat.S_IFMT(os.lstat(path).st_mode)
    return kind == (stat.S_IFDIR if path.name.startswith(".build-") else stat.S_IFREG)


def _own_paths(folder: Path) -> tuple[list[Path], int]:
    """The paths symlink wrote in ``folder`` and its ``compiled/`` (that one only if private), and how many
    other names there are.  Nothing is followed through a symbolic link."""
    own: list[Path] = []
    others = 0
    for name in sorted(os.listdir(folder)):
        path = folder / name
        if name == COMPILED_FOLDER and stat.S_ISDIR(os.lstat(path).st_mode) and not _trust(path):
            inside = [path / item for item in sorted(os.listdir(path))]
            ours = [item for item in inside if _is_own(item, _OWN_COMPILED_NAMES)]
            own.extend(ours)
            others += len(inside) - len(ours)
        elif _is_own(path, _OWN_NAMES):
            own.append(path)
        else:
            others += 1  # anything else, a compiled/ that is a link or not private among them: left alone
    return own, others


def _size(path: Path) -> int:
    """Bytes of a regular file, or of the regular files in a folder (no symbolic link followed)."""
    status = os.lstat(path)
    if stat.S_ISREG(status.st_mode):
        return status.st_size
    if not stat.S_ISDIR(status.st_mode):
        return 0
    total = 0
    for root, _, names in os.walk(path):
        for name in names:
            inner = os.lstat(os.path.join(root, name))
            total += inner.st_size if stat.S_ISREG(inner.st_mode) else 0
    return total


def _trust(folder: Path) -> str:
    """Why ``folder`` is not to be trusted ('' when it is private to this user); never creates it."""
    try:
        private_folder(folder)
    except OSError as why:  # NotPrivate, or not a folder
        return str(why)
    return ""


def cache_contents(folder: str | os.PathLike) -> CacheContents:
    """What symlink keeps in the cache ``folder`` (e.g. :func:`cache_directory`), without changing anything.

    >>> import tempfile
    >>> contents = cache_contents(Path(tempfile.mkdtemp()) / "none")
    >>> contents.exists, contents.trusted, contents.entries
    (False, True, 0)
    """
    folder = Path(folder)
    if not os.path.lexists(folder):
        return CacheContents(folder, False, True, "", 0, 0, 0)
    problem = _trust(folder)
    if problem:
        return CacheContents(folder, True, False, problem, 0, 0, 0)
    own, others = _own_paths(folder)
    size = 0
    for path in own:
        try:
            size += _size(path)
        except OSError:  # removed meanwhile by another process
            pass
    leftovers = sum(path.name.startswith(".") for path in own)  # .build-*, .load-*, .*.tmp: never a finished entry
    return CacheContents(folder, True, True, "", len(own), size, others, leftovers)


def clear_cache(folder: str | os.PathLike) -> CacheContents:
    """Remove what symlink wrote in the cache ``folder``; returns what was removed (``entries``, ``size``).

    Only symlink's own names are removed (derived modules, compiled libraries
    and their digests, temporary files and build folders); anything else in
    the folder stays, and so does the folder.  ``ValueError`` for a folder
    that another user owns or that group or others can write: symlink does
    not touch it.  The memory cache of this process is cleared too.

    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> _ = (folder / "notes.txt").write_text("mine"), (folder / f"{'0' * 64}.json").write_text("{}")
    >>> removed = clear_cache(folder)
    >>> removed.entries, removed.size, sorted(path.name for path in folder.iterdir())
    (1, 2, ['notes.txt'])
    """
    contents = cache_contents(folder)
    if not contents.trusted:
        raise ValueError(f"not clearing the cache folder: {contents.problem}; only you may be able to write it")
    if not contents.exists:
        return contents
    own, others = _own_paths(contents.folder)
    removed = size = 0
    for path in own:
        try:
            bytes_ = _size(path)
            if stat.S_ISDIR(os.lstat(path).st_mode):
                import shutil
                shutil.rmtree(path)
            else:
                os.unlink(path)
        except FileNotFoundError:  # removed meanwhile by another process
            continue
        removed, size = removed + 1, size + bytes_
    compiled = contents.folder / COMPILED_FOLDER
    try:
        if stat.S_ISDIR(os.lstat(compiled).st_mode):
            os.rmdir(compiled)  # only if empty: symlink made it
    except OSError:
        pass
    clear_memory()
    return CacheContents(contents.folder, True, True, "", removed, size, others)
