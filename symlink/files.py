"""Files that symlink writes and reads back: atomic writes, owner-only folders, reads that never block.

:func:`write_atomic` writes through a temporary file in the same folder and a
rename, so a reader sees the old file or the new one, never half of one.  The
process umask is never changed (another thread may be creating files): a new
file gets what ``open()`` would give it, or exactly ``mode`` when one is asked
for.  :func:`private_folder` and :func:`read_private` are the two halves of a
cache that only its owner can write: a folder made 0700 whatever the umask,
and a read that refuses anything but a regular file owned by this user and
writable by no one else.

>>> import tempfile, pathlib
>>> path = pathlib.Path(tempfile.mkdtemp()) / "out.txt"
>>> write_atomic(path, "done\\n")
>>> path.read_text()
'done\\n'
"""
from __future__ import annotations

import os
import secrets
import shutil
import stat
import time
from pathlib import Path
from typing import Mapping

__all__ = ["write_atomic", "write_files_atomic", "private_folder", "read_private", "NotPrivate", "TEMPORARY_SUFFIX",
           "remove_leftovers"]

#: The name of every temporary file of :func:`write_atomic` ends so: ``.<name>.<random>.tmp``.
TEMPORARY_SUFFIX = ".tmp"
_CAN_CHECK_OWNER = hasattr(os, "geteuid")


class NotPrivate(OSError):
    """A file or folder that someone other than this user could have written."""


def _write_all(handle: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(handle, view):]


def write_atomic(path: str | os.PathLike, data: str | bytes, mode: int | None = None) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder and a rename.

    Text is written as UTF-8 with ``\\n`` line ends.  Without ``mode`` the file
    gets the permissions ``open()`` would give it (0666 less the umask); with
    ``mode`` exactly that (e.g. 0o600), whatever the umask.  Missing parent
    folders are created.  On any failure nothing is left under ``path`` or
    beside it, and the old file (if any) is untouched.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    payload = data.encode("utf-8") if isinstance(data, str) else bytes(data)
    temporary = path.parent / f".{path.name}.{secrets.token_hex(6)}{TEMPORARY_SUFFIX}"
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    handle = os.open(temporary, flags, 0o666 if mode is None else mode & 0o777)  # the kernel applies the umask
    try:
        try:
            if mode is not None:
                os.fchmod(handle, mode & 0o777)  # exactly this, whatever the umask took away
            _write_all(handle, payload)
            os.fsync(handle)
        finally:
            os.close(handle)
        os.replace(temporary, path)
    except BaseException:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise


def _owner_problem(status: os.stat_result) -> str | None:
    """Why a file with this status is not private to this user; ``None`` when it is."""
    if not _CAN_CHECK_OWNER:
        return None
    if status.st_uid != os.geteuid():
        return f"owned by user {status.st_uid}, not by you ({os.geteuid()})"
    writers = [who for who, bit in (("group", stat.S_IWGRP), ("others", stat.S_IWOTH)) if status.st_mode & bit]
    if writers:
        return f"writable by {' and '.join(writers)} (mode {stat.S_IMODE(status.st_mode):04o})"
    return None


def private_folder(path: str | os.PathLike) -> Path:
    """``path`` as a folder only this user can write: created 0700 if missing (whatever the umask).

    An existing folder is checked, not changed: ``NotPrivate`` when another
    user owns it or group or others can write it; ``OSError`` when it cannot
    be created or is not a folder.

    >>> import tempfile, pathlib, stat
    >>> folder = private_folder(pathlib.Path(tempfile.mkdtemp()) / "cache")
    >>> oct(stat.S_IMODE(folder.stat().st_mode))
    '0o700'
    """
    path = Path(path)
    try:
        os.mkdir(path, 0o700)
    except FileNotFoundError:
        path.parent.mkdir(parents=True, exist_ok=True)
        return private_folder(path)
    except FileExistsError:
        pass
    else:
        os.chmod(path, 0o700)  # the umask can only have taken bits away: never wider than 0700 meanwhile
        return path
    status = os.stat(path)
    if not stat.S_ISDIR(status.st_mode):
        raise NotADirectoryError(f"{path} is not a folder")
    problem = _owner_problem(status)
    if problem:
        raise NotPrivate(f"{path} is {problem}")
    return path


def read_private(path: str | os.PathLike, limit: int) -> bytes:
    """The bytes of ``path`` if it is a regular file of at most ``limit`` bytes that only this user can write.

    Never blocks (a FIFO or device at ``path`` is refused, not opened for a
    read that waits) and follows no symbolic link.  ``FileNotFoundError``
    when there is nothing; ``NotPrivate`` when another user owns it or group
    or others can write it; ``OSError`` for anything else that is not such a
    file.
    """
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        handle = os.open(path, flags)
    except OSError as error:
        if isinstance(error, FileNotFoundError):
            raise
        raise OSError(error.errno, f"cannot open {path}: {error.strerror} (a symbolic link?)") from None
    try:
        status = os.fstat(handle)
        if not stat.S_ISREG(status.st_mode):
            raise OSError(f"{path} is not a regular file")
        problem = _owner_problem(status)
        if problem:
            raise NotPrivate(f"{path} is {problem}")
        if status.st_size > limit:
            raise OSError(f"{path} is larger than {limit} bytes")
        chunks, size = [], 0
        while True:
            chunk = os.read(handle, min(1 << 20, limit + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
            if size > limit:
                raise OSError(f"{path} is larger than {limit} bytes")
        return b"".join(chunks)
    finally:
        os.close(handle)


def remove_leftovers(folder: str | os.PathLike, prefixes: tuple[str, ...], older_than: float) -> list[str]:
    """Remove what killed runs left in ``folder``: names starting with one of ``prefixes``, or temporary
    files of :func:`write_atomic`, untouched for ``older_than`` seconds (younger ones may be a running
    process's).  Returns the names removed; never follows a symbolic link, never fails.
    """
    removed: list[str] = []
    now = time.time()
    try:
        names = os.listdir(folder)
    except OSError:
        return removed
    for name in names:
        temporary = name.startswith(".") and name.endswith(TEMPORARY_SUFFIX)
        if not (temporary or name.startswith(prefixes)):
            continue
        path = os.path.join(folder, name)
        try:
            status = os.lstat(path)
            if now - status.st_mtime < older_than:
                continue
            if stat.S_ISDIR(status.st_mode):
                shutil.rmtree(path)
            else:
                os.unlink(path)
            removed.append(name)
        except OSError:
            pass
    return removed


#: Leftovers of killed runs older than this (seconds) are removed; younger ones may be a running process's.
LEFTOVER_AGE = 600.0


def write_files_atomic(folder: str | os.PathLike, texts: Mapping[str, str | bytes]) -> list[Path]:
    """Write a set of files into ``folder``: all of them, or (on any failure) none.

    Every file is written first into a hidden temporary folder beside them,
    then each is renamed into place; a failure removes what was written.
    Returns the paths written.

    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> [p.name for p in write_files_atomic(folder, {"a.h": "x", "a.c": "y"})]
    ['a.h', 'a.c']
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    remove_leftovers(folder, (), older_than=LEFTOVER_AGE)  # staging folders of killed runs end in .tmp too
    staging = folder / f".symlink-files-{secrets.token_hex(6)}{TEMPORARY_SUFFIX}"
    staging.mkdir(mode=0o700)
    moved: list[Path] = []
    try:
        for name, data in texts.items():
            write_atomic(staging / name, data)
        for name in texts:
            os.replace(staging / name, folder / name)
            moved.append(folder / name)
    except BaseException:
        for path in moved:
            path.unlink(missing_ok=True)
        raise
    finally:
        for leftover in staging.iterdir():
            leftover.unlink(missing_ok=True)
        staging.rmdir()
    return moved
