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

import errno
import os
import stat
import time
from pathlib import Path
from functools import lru_cache
from typing import Any, Mapping

__all__ = ["write_atomic", "naming", "check_writable", "write_files_atomic", "write_files_together", "private_folder", "read_private", "NotPrivate", "TEMPORARY_SUFFIX",
           "remove_leftovers", "read_input", "read_input_text", "read_stdin_text", "excerpt", "EXCERPT_LENGTH", "sha256",
           "blake2b"]

#: The name of every temporary file of :func:`write_atomic` ends so: ``.<name>.<random>.tmp``.
TEMPORARY_SUFFIX = ".tmp"
_CAN_CHECK_OWNER = hasattr(os, "geteuid")


class NotPrivate(OSError):
    """A file or folder that someone other than this user could have written."""


def sha256(data: bytes = b"") -> Any:
    """A SHA-256 hash object of ``data`` (``update``, ``hexdigest``), the same digest as :func:`hashlib.sha256`.

    CPython's own SHA-256 where it has one: ``hashlib`` loads OpenSSL, a few milliseconds of a warm command's
    start, for the digests of cache keys and entries that are all a warm command computes.

    Parameters
    ----------
    data : bytes
        The first bytes to digest.

    Returns
    -------
    hash object
        With ``update(bytes)`` and ``hexdigest()``.

    Examples
    --------
    >>> sha256(b"abc").hexdigest()[:16]
    'ba7816bf8f01cfea'
    """
    return _builtin_hash(("_sha256", "_sha2"), "sha256")(data)  # CPython's module up to 3.11, and from 3.12


def blake2b(data: bytes = b"") -> Any:
    """A BLAKE2b hash object of ``data`` (``update``, ``hexdigest``: 128 hex digits), as :func:`hashlib.blake2b`.

    CPython's own BLAKE2b (no OpenSSL, as :func:`sha256`), about three times as fast as its SHA-256: for the
    digest of the modules that shape generated code (half a megabyte), hashed at every warm start.

    Parameters
    ----------
    data : bytes
        The first bytes to digest.

    Returns
    -------
    hash object
        With ``update(bytes)`` and ``hexdigest()``.

    Examples
    --------
    >>> blake2b(b"abc").hexdigest()[:16]
    'ba80a53f981c4d0d'
    """
    return _builtin_hash(("_blake2",), "blake2b")(data)


@lru_cache(maxsize=None)
def _builtin_hash(modules: tuple[str, ...], name: str) -> Any:
    """CPython's own constructor ``name`` from the first of ``modules`` that has it, else :mod:`hashlib`'s."""
    import importlib
    for module in modules:
        try:
            return getattr(importlib.import_module(module), name)
        except (ImportError, AttributeError):
            continue
    import hashlib
    return getattr(hashlib, name)


def _token() -> str:
    """Twelve random hex digits for a temporary name (``secrets``, imported when a file is first written)."""
    import secrets
    return secrets.token_hex(6)


def _write_all(handle: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(handle, view):]


def write_atomic(path: str | os.PathLike, data: str | bytes, mode: int | None = None) -> None:
    r"""Write ``data`` to ``path`` through a temporary file in the same folder and a rename.

    Text is written as UTF-8 with ``\n`` line ends.  Without ``mode`` the file
    gets the permissions ``open()`` would give it (0666 less the umask); with
    ``mode`` exactly that (e.g. 0o600), whatever the umask.  Missing parent
    folders are created.  On any failure nothing is left under ``path`` or
    beside it, and the old file (if any) is untouched; an ``OSError`` names
    ``path`` (never the hidden temporary) with the system's reason, such as
    ``No space left on device``.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.
    data : str or bytes
        What to write; text as UTF-8.
    mode : int, optional
        Exact permissions (``0o600``); default those ``open()`` would give.

    Returns
    -------
    None

    Raises
    ------
    OSError
        Naming ``path``, with the system's reason; nothing is left behind.

    Examples
    --------
    >>> import symlink, tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "deeper" / "note.txt"
    >>> symlink.write_atomic(path, "hello\n")
    >>> path.read_text(), sorted(p.name for p in path.parent.iterdir())  # no temporary left beside it
    ('hello\n', ['note.txt'])
    """
    path = Path(path)
    try:
        _refuse_unwritable_place(path)
        if _is_special(path):  # /dev/full, /dev/null, a FIFO: written through, never replaced by a file
            _write_through(path, data.encode("utf-8") if isinstance(data, str) else bytes(data))
        else:
            _write_through_temporary(path, data, mode)
    except OSError as error:
        raise naming(error, path) from None


def naming(error: OSError, path: str | os.PathLike) -> OSError:
    """``error`` naming the user's ``path`` (never a hidden temporary beside it) with the system's reason.

    >>> import errno
    >>> error = naming(OSError(errno.ENOSPC, "No space left on device", ".out.png.1a2b.tmp"), "out.png")
    >>> error.filename, error.strerror
    ('out.png', 'No space left on device')
    """
    if error.filename is not None and str(error.filename) == str(path):
        return error
    made = type(error)(error.errno, error.strerror or str(error), str(path))
    return made if isinstance(made, OSError) else OSError(error.errno, error.strerror or str(error), str(path))


def _is_special(path: Path) -> bool:
    """Whether ``path`` is a device, FIFO or socket (written through in place, not renamed over)."""
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return False
    return not (stat.S_ISREG(mode) or stat.S_ISDIR(mode))


def _write_through(path: Path, payload: bytes) -> None:
    """Write into a device or FIFO that is there (``/dev/full`` says "No space left on device")."""
    flags = os.O_WRONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    handle = os.open(path, flags)  # a FIFO with no reader: ENXIO at once, never a wait
    try:
        os.set_blocking(handle, True)
        _write_all(handle, payload)
    finally:
        os.close(handle)


def _refuse_unwritable_place(path: Path, folder: bool = False) -> None:
    """``OSError`` naming ``path`` when nothing can be written there: a folder where a file is to go
    (``folder`` False), or a file on the way to it (``out.png/x.png``: "out.png is a file, not a folder")."""
    if not folder and os.path.isdir(path):
        raise IsADirectoryError(errno.EISDIR, "it is a folder, not a file", str(path))
    for parent in path.parents if not folder else (path, *path.parents):
        try:
            status = os.stat(parent)
        except FileNotFoundError:
            continue
        except NotADirectoryError:  # a file further up: reported when the walk reaches it
            continue
        if not stat.S_ISDIR(status.st_mode):
            if parent == path:
                return  # the folder itself is a file: the command says so in its own words
            raise NotADirectoryError(errno.ENOTDIR, f"{parent} is a file, not a folder", str(path))
        return


def check_writable(path: str | os.PathLike, folder: bool = False) -> None:
    """``OSError`` naming ``path`` (with the real reason) when a file (or, ``folder``, a folder) cannot be
    written there: checked before a command starts its work, so that a bad output fails before any output.

    A folder where the file is to go, a file on the way to it, a folder that cannot be written (read-only,
    ``/proc``) are each refused; a device or FIFO there is written through (:func:`write_atomic`).  The check
    creates a hidden empty file in the nearest folder that exists and removes it at once.

    Parameters
    ----------
    path : str or os.PathLike
        The file (or folder) a command will write.
    folder : bool, optional
        ``path`` is a folder to be written into (created if missing).

    Returns
    -------
    None

    Examples
    --------
    >>> import tempfile, pathlib
    >>> here = pathlib.Path(tempfile.mkdtemp())
    >>> check_writable(here / "new" / "out.png")  # creates nothing
    >>> sorted(here.iterdir())
    []
    >>> (here / "notes.txt").write_text("x")
    1
    >>> try:
    ...     check_writable(here / "notes.txt" / "out.png")
    ... except NotADirectoryError as error:
    ...     print(error.strerror.endswith("notes.txt is a file, not a folder"), error.filename.endswith("out.png"))
    True True
    """
    path = Path(path)
    try:
        _refuse_unwritable_place(path, folder)
        if _is_special(path) or (folder and os.path.isdir(path) and not os.access(path, os.W_OK | os.X_OK)):
            if _is_special(path):
                return
            raise PermissionError(errno.EACCES, "Permission denied", str(path))
        existing = next((p for p in ((path,) if folder else ()) + tuple(path.parents) if os.path.isdir(p)), None)
        if existing is None:
            return
        probe = existing / f".symlink-probe-{_token()}{TEMPORARY_SUFFIX}"
        flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
        os.close(os.open(probe, flags, 0o600))
        os.unlink(probe)
    except OSError as error:
        raise naming(error, path) from None


def _write_through_temporary(path: Path, data: str | bytes, mode: int | None) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    payload = data.encode("utf-8") if isinstance(data, str) else bytes(data)
    temporary = path.parent / f".{path.name}.{_token()}{TEMPORARY_SUFFIX}"
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


#: Hostile text quoted in a message is cut to this many characters (and "...").
EXCERPT_LENGTH = 60


def excerpt(value: object, length: int = EXCERPT_LENGTH) -> str:
    """``repr`` of ``value`` cut to ``length`` characters and "...", so that a message never echoes megabytes.

    >>> excerpt("AB + BC")
    "'AB + BC'"
    >>> excerpt("x" * 1000) == repr("x" * EXCERPT_LENGTH) + "..."
    True
    """
    if isinstance(value, str):
        return repr(value) if len(value) <= length else repr(value[:length]) + "..."
    if isinstance(value, (list, tuple, dict)) and len(value) > length:  # never repr a huge container whole
        return f"{type(value).__name__} of {len(value):,} items"
    shown = repr(value)
    return shown if len(shown) <= length else shown[:length] + "..."


def _kind_of(mode: int) -> str:
    """What a file that is not a regular file is, in a user's words."""
    for test, name in ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


def read_input(path: str | os.PathLike, limit: int, what: str = "input file") -> bytes:
    """The bytes of a user's input file ``path``: a regular file of at most ``limit`` bytes.

    The one reader of every file a user hands to symlink (linkage files, scene
    files, csv targets).  It never blocks and never reads without bound: the
    file is opened non-blocking (a FIFO with no writer does not hang the
    open), and a folder, FIFO, device (``/dev/zero``) or socket is refused
    before a byte is read; a file that is (or grows) larger than ``limit`` is
    refused after at most ``limit + 1`` bytes.  Symbolic links are followed
    (the user named the file).  Every problem is a one-line ``ValueError``
    with the path and the reason (the system's words for an OS error),
    naming ``what`` the file was meant to be.

    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "points.csv"
    >>> _ = path.write_text("x,y\\n1,2\\n")
    >>> read_input(path, 100, "csv of targets")
    b'x,y\\n1,2\\n'
    >>> read_input("/dev/zero", 100, "csv of targets")
    Traceback (most recent call last):
    ValueError: cannot read csv of targets /dev/zero: it is a character device, not a regular file
    """
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    shown = os.fspath(path) if len(os.fspath(path)) <= 4 * EXCERPT_LENGTH else excerpt(os.fspath(path))
    try:
        handle = os.open(path, flags)
    except OSError as error:
        raise ValueError(f"cannot read {what} {shown}: {error.strerror or error}") from None
    except (TypeError, ValueError) as error:  # a NUL byte in the name
        raise ValueError(f"cannot read {what} {excerpt(shown)}: {error}") from None
    try:
        status = os.fstat(handle)
        if not stat.S_ISREG(status.st_mode):
            raise ValueError(f"cannot read {what} {shown}: it is {_kind_of(status.st_mode)}, not a regular file")
        too_large = (f"{what} {shown} is larger than {limit:,} bytes (the most symlink reads as a {what}); "
                     "is it the right file?")
        if status.st_size > limit:
            raise ValueError(too_large)
        chunks, size = [], 0
        while True:
            try:
                chunk = os.read(handle, min(1 << 20, limit + 1 - size))
            except OSError as error:
                raise ValueError(f"cannot read {what} {shown}: {error.strerror or error}") from None
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
            if size > limit:
                raise ValueError(too_large)
        return b"".join(chunks)
    finally:
        os.close(handle)


def read_input_text(path: str | os.PathLike, limit: int, what: str = "input file") -> str:
    """:func:`read_input` decoded as UTF-8 (a leading byte-order mark dropped); ``ValueError`` for other bytes."""
    data = read_input(path, limit, what)
    return decode_input(data, os.fspath(path), what)


def read_stdin_text(limit: int, what: str = "input") -> str:
    """Standard input as UTF-8 text, at most ``limit`` bytes (``symlink run -``, a csv of targets from ``-``).

    Reads at most ``limit + 1`` bytes whatever stdin is (``< /dev/zero`` included); ``ValueError`` beyond.
    """
    import sys
    stream = getattr(sys.stdin, "buffer", None)
    try:
        data = stream.read(limit + 1) if stream is not None else sys.stdin.read(limit + 1).encode("utf-8")
    except OSError as error:
        raise ValueError(f"cannot read {what} from standard input: {error.strerror or error}") from None
    if data is None:  # a non-blocking stdin with nothing in it
        data = b""
    if len(data) > limit:
        raise ValueError(f"{what} on standard input is larger than {limit:,} bytes (the most symlink reads as a "
                         f"{what})")
    return decode_input(data, "<stdin>", what)


def decode_input(data: bytes, shown: str, what: str = "input file") -> str:
    """UTF-8 bytes of a user's file as text; ``ValueError`` naming the line of the first byte that is not."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        line = data.count(b"\n", 0, error.start) + 1
        raise ValueError(f"{shown}:{line}: {what} is not UTF-8 text (byte {error.start})") from None
    return text[1:] if text.startswith("\ufeff") else text


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
                import shutil
                shutil.rmtree(path)
            else:
                os.unlink(path)
            removed.append(name)
        except OSError:
            pass
    return removed


#: Leftovers of killed runs older than this (seconds) are removed; younger ones may be a running process's.
LEFTOVER_AGE = 600.0


def write_files_together(texts: Mapping[Path, str | bytes]) -> list[Path]:
    """Write every file (they may be in several folders), or on any failure none, leaving old files as they were.

    Each file is first written in full beside its target under a hidden temporary name
    (:func:`write_atomic`); then each file already there is kept under a second name (a hard
    link) and the new one renamed over it.  A failure takes back every rename done: the old files are
    renamed back, new ones removed.  A device or FIFO named as a target (``/dev/full``) is written through,
    never replaced by a file: after every other file is staged and before any is renamed, so that its failure
    ("No space left on device") leaves the other targets as they were.  Every ``OSError`` names the user's
    path (never a hidden temporary) with the system's reason.  Returns the paths written.

    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> [p.name for p in write_files_together({folder / "a.svg": "<svg/>", folder / "sub" / "a.dxf": "0"})]
    ['a.svg', 'a.dxf']
    """
    def hidden(path: Path) -> Path:
        return path.parent / f".{path.name}.{_token()}{TEMPORARY_SUFFIX}"

    paths = {Path(path): data for path, data in texts.items()}
    for path in paths:
        try:
            _refuse_unwritable_place(path)  # a folder where the file goes, a file on the way to it
        except OSError as error:
            raise naming(error, path) from None
    special = [path for path in paths if _is_special(path)]  # written through, never renamed over
    made = sorted({parent for path in paths for parent in path.parents if not os.path.lexists(parent)},
                  key=lambda folder: len(folder.parts), reverse=True)  # folders this call makes, deepest first
    staged: dict[Path, Path] = {}
    kept: dict[Path, Path | None] = {}  # each target renamed over: its old file's second name (None: it had none)
    try:
        for path, data in paths.items():
            if path in special:
                continue
            temporary = hidden(path)
            try:
                path.parent.mkdir(parents=True, exist_ok=True)
                write_atomic(temporary, data)
            except OSError as error:
                raise type(error)(error.errno, error.strerror or str(error), str(path)) from None
            staged[path] = temporary
        for path in special:
            data = paths[path]
            try:
                _write_through(path, data.encode("utf-8") if isinstance(data, str) else bytes(data))
            except OSError as error:
                raise naming(error, path) from None
        for path, temporary in list(staged.items()):
            backup = hidden(path) if path.exists() else None
            if backup is not None:
                try:
                    os.link(path, backup)
                except OSError:  # a file system without hard links: a copy
                    import shutil
                    shutil.copy2(path, backup)
            kept[path] = backup
            os.replace(temporary, path)
            del staged[path]
    except BaseException:
        for path, backup in kept.items():
            if backup is not None:
                os.replace(backup, path)
            elif path not in staged:
                path.unlink(missing_ok=True)
        kept.clear()
        for temporary in staged.values():
            temporary.unlink(missing_ok=True)
        staged.clear()
        for folder in made:  # nothing written: not even the folders made for it
            try:
                os.rmdir(folder)
            except OSError:
                pass
        raise
    finally:
        for temporary in [*staged.values(), *(backup for backup in kept.values() if backup is not None)]:
            temporary.unlink(missing_ok=True)
    return list(paths)


def write_files_atomic(folder: str | os.PathLike, texts: Mapping[str, str | bytes]) -> list[Path]:
    """Write a set of files into ``folder``: all of them, or (on any failure) none (:func:`write_files_together`);
    a folder made for them is removed again when none could be written (nothing is left, not even it).

    Returns the paths written.

    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> [p.name for p in write_files_atomic(folder, {"a.h": "x", "a.c": "y"})]
    ['a.h', 'a.c']
    """
    folder = Path(folder)
    made = [parent for parent in (folder, *folder.parents) if not os.path.lexists(parent)]
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise naming(error, folder) from None
    remove_leftovers(folder, (), older_than=LEFTOVER_AGE)  # temporaries of killed runs
    try:
        return write_files_together({folder / name: data for name, data in texts.items()})
    except BaseException:
        for parent in made:  # the folders made here, innermost first, where still empty
            try:
                os.rmdir(parent)
            except OSError:
                break
        raise
