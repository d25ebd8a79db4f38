"""A sweep's folder: Parquet chunks trusted only when they match what the manifest recorded of them.

A sweep (:mod:`symlink.workshop.sweep`) writes its table as ``chunk-NNNNNN.parquet``
files beside ``manifest.json``.  The manifest holds the settings, the columns
and, for every chunk written, a record: its row count, the design numbers it
holds (first and last) and the size and SHA-256 of its file.  A chunk is
written as a temporary file first; its record is added to the manifest
(rewritten atomically), and only then is the file renamed into place, so a
killed run leaves a recorded chunk that is missing (done again), never a
chunk that is there and unrecorded.

When a sweep continues in a folder (:func:`open_folder`), the folder is
locked (a second sweep into it is refused), the temporaries of killed writes
are removed, and every file named ``chunk-*.parquet`` is checked against its
record: one that is truncated, empty, swapped with another, copied from
another sweep, a folder, a link or unrecorded is removed, rebuilt and never
counted, with one warning line (:class:`SweepWarning`) that names it.
A manifest that is damaged (truncated, not JSON, keys missing or of the wrong
type, or no manifest beside the chunks) can verify nothing: continuing the
sweep starts it again there, with one warning, when the folder holds only the
sweep's own files (anything else is left alone and the run refused); a
manifest of another symlink (version or layout) is refused in one line that
says how to go on.  Reading a folder (:func:`verified_chunks`) checks the same and also the
rows and design numbers inside each file, and refuses a bad chunk by name:
a table never holds a design twice or a design from another sweep.

>>> import tempfile, pathlib
>>> path = pathlib.Path(tempfile.mkdtemp()) / "sweep"
>>> with open_folder(path, {"settings": {}, "columns": ["design"]}, designs=5, chunk=2) as folder:
...     folder.todo
...     folder.stage(0, b"two rows", rows=2)
[0, 1, 2]
>>> [(record.name, record.first, record.last) for record in read_manifest(path)[1].values()]
[('chunk-000000.parquet', 0, 1)]
"""
from __future__ import annotations

import hashlib
import json
import os
import re
import secrets
import shutil
import stat
import time
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterator, Mapping

from ..common.display import record_html
from ..common.files import LEFTOVER_AGE, TEMPORARY_SUFFIX, excerpt, write_atomic
from ..common.numbers import json_data

__all__ = ["MANIFEST", "FORMAT", "DamagedManifest", "SweepWarning", "ChunkRecord", "SweepFolder", "open_folder", "read_manifest",
           "verified_chunks", "chunk_name", "chunk_range", "parquet_bytes", "numpy_column"]

#: The manifest's file name in a sweep's folder.
MANIFEST = "manifest.json"
#: The layout of the manifest (2: with a record a chunk).
FORMAT = 2
#: The names of chunks (an index of six digits or more).
CHUNK_NAME = re.compile(r"chunk-(\d{6,})\.parquet\Z")
#: What the glob of chunks matches: anything that could be taken for a chunk.
CHUNK_GLOB = "chunk-*.parquet"
#: The temporary files of the writes to a sweep's folder (as :func:`symlink.common.files.write_atomic` names them).
TEMPORARY_NAME = re.compile(rf"\.(?:chunk-\d{{6,}}\.parquet|{re.escape(MANIFEST)})\.[0-9a-f]{{12}}"
                            rf"{re.escape(TEMPORARY_SUFFIX)}\Z")
#: Bytes of a record in the manifest, at most (with its indentation): bounds the manifest read back.
RECORD_BYTES = 256
#: The most chunks a sweep may have: each has a record in the manifest, which is rewritten as chunks are done.
MAX_CHUNKS = 1 << 20
#: The largest manifest read back: the settings and columns, and a record a chunk.
MANIFEST_LIMIT = (1 << 20) + RECORD_BYTES * MAX_CHUNKS
#: Bytes read at a time to hash a chunk.
READ_BLOCK = 1 << 20
#: How many bad chunks the warning names (the rest are counted).
NAMED = 3
#: A commit rewrites the manifest: at most this share of a run's time goes to that (the manifest grows).
COMMIT_SHARE = 0.1


class DamagedManifest(ValueError):
    """A manifest that cannot be read as one (truncated, not JSON, wrong types, keys missing): ``reason`` says
    why.  Continuing the sweep rebuilds the folder (:func:`open_folder`); reading it is refused."""

    def __init__(self, message: str, reason: str) -> None:
        super().__init__(message)
        self.reason = reason


class _OtherLayout(ValueError):
    """A manifest of another layout (an older symlink's): refused, never rebuilt without a word."""


class SweepWarning(UserWarning):
    """Something in a sweep's folder was not what the manifest recorded: it was removed and is done again."""


@dataclass(frozen=True)
class ChunkRecord:
    """What the manifest knows of a chunk: its file ``name``, ``rows``, the designs ``first`` to ``last``
    (included), and its file's ``size`` in bytes and ``sha256``."""

    _repr_html_ = record_html  # a notebook shows the fields as a table

    name: str
    rows: int
    first: int
    last: int
    size: int
    sha256: str

    def as_json(self) -> dict[str, Any]:
        return {"rows": self.rows, "designs": [self.first, self.last], "bytes": self.size, "sha256": self.sha256}

    @classmethod
    def from_json(cls, name: str, data: object) -> "ChunkRecord | None":
        """The record of ``data`` as the manifest holds it, or ``None`` if it is not one."""
        if not isinstance(data, dict):
            return None
        designs, digest = data.get("designs"), data.get("sha256")
        whole = [data.get("rows"), data.get("bytes"), *(designs if isinstance(designs, list) and len(designs) == 2
                                                         else [None, None])]
        if not all(type(value) is int and value >= 0 for value in whole):
            return None
        if not isinstance(digest, str) or not re.fullmatch("[0-9a-f]{64}", digest):
            return None
        rows, size, first, last = (int(value) for value in whole)
        return cls(name, rows, first, last, size, digest)


def _arrow_column(values: Any) -> Any:
    """One column as a ``pyarrow.Array`` made from its buffers: int64, float64 (NaN kept as a value) or bool
    arrays, or a list of strings (None for a missing one)."""
    import numpy
    import pyarrow
    if isinstance(values, numpy.ndarray):
        values = numpy.ascontiguousarray(values)
        if values.dtype == bool:
            bits = numpy.packbits(values, bitorder="little")
            return pyarrow.Array.from_buffers(pyarrow.bool_(), len(values), [None, pyarrow.py_buffer(bits)])
        kinds = {numpy.dtype(numpy.int64): pyarrow.int64(), numpy.dtype(numpy.float64): pyarrow.float64()}
        if values.dtype not in kinds:
            raise TypeError(f"a Parquet column holds int64, float64 or bool arrays or strings, not {values.dtype}")
        return pyarrow.Array.from_buffers(kinds[values.dtype], len(values), [None, pyarrow.py_buffer(values)])
    texts = list(values)
    encoded = [b"" if text is None else str(text).encode("utf-8") for text in texts]
    offsets = numpy.concatenate([[0], numpy.cumsum([len(e) for e in encoded])]).astype(numpy.int32)
    missing = [text is None for text in texts]
    valid = (None if not any(missing) else
             pyarrow.py_buffer(numpy.packbits(~numpy.array(missing, dtype=bool), bitorder="little")))
    return pyarrow.Array.from_buffers(pyarrow.string(), len(texts),
                                      [valid, pyarrow.py_buffer(offsets), pyarrow.py_buffer(b"".join(encoded))],
                                      null_count=sum(missing))


def parquet_bytes(columns: Mapping[str, Any]) -> bytes:
    """Columns by name (NumPy int64, float64 or bool arrays, or lists of strings) as the bytes of a Parquet file.

    Made from the columns' buffers: ``pyarrow.table`` and ``pyarrow.array`` import pandas wherever it is
    installed (a second's start-up of every sweep and every worker, for nothing).
    """
    import io

    import pyarrow
    import pyarrow.parquet
    table = pyarrow.Table.from_arrays([_arrow_column(values) for values in columns.values()], names=list(columns))
    sink = io.BytesIO()
    pyarrow.parquet.write_table(table, sink)
    return sink.getvalue()



def numpy_column(table: Any, name: str) -> Any:
    """Column ``name`` of a Parquet chunk's table (``pyarrow.Table``) as a NumPy array, read from its buffer where it
    is int64 or float64 without nulls (what :func:`parquet_bytes` writes): ``to_numpy`` imports pandas wherever it
    is installed (0.3 s of a run that reads its chunks back).  Any other column: ``to_numpy`` as it is.

    >>> import numpy, pyarrow, pyarrow.parquet
    >>> data = parquet_bytes({"build": numpy.arange(3, dtype=numpy.int64), "x": numpy.array([0.5, numpy.nan, 2.0])})
    >>> table = pyarrow.parquet.ParquetFile(pyarrow.BufferReader(data)).read()
    >>> numpy_column(table, "build").tolist(), numpy_column(table, "x").tolist()
    ([0, 1, 2], [0.5, nan, 2.0])
    """
    import numpy
    import pyarrow
    column = table.column(name).combine_chunks()
    kinds = {pyarrow.int64(): numpy.int64, pyarrow.float64(): numpy.float64}
    kind = kinds.get(column.type)
    if kind is None or column.null_count:
        return column.to_numpy(zero_copy_only=False)
    size = numpy.dtype(kind).itemsize
    return numpy.frombuffer(column.buffers()[1], dtype=kind, count=len(column), offset=size * column.offset)

def chunk_name(index: int) -> str:
    """The file name of chunk ``index``.

    >>> chunk_name(7)
    'chunk-000007.parquet'
    """
    return f"chunk-{index:06d}.parquet"


def chunk_range(index: int, designs: int, chunk: int) -> tuple[int, int]:
    """The first and last design numbers (included) of chunk ``index`` of ``designs`` in chunks of ``chunk``.

    >>> chunk_range(2, designs=10, chunk=4)
    (8, 9)
    """
    first = index * chunk
    return first, min(first + chunk, designs) - 1


def _read_regular(path: Path, limit: int) -> bytes:
    """The bytes of ``path`` if it is a regular file of at most ``limit`` bytes (no link followed, no wait on a
    FIFO); ``OSError`` saying why not."""
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    handle = os.open(path, flags)
    try:
        status = os.fstat(handle)
        if not stat.S_ISREG(status.st_mode):
            raise OSError(f"{path} is not a regular file")
        if status.st_size > limit:
            raise OSError(f"{path} is larger than {limit} bytes")
        parts: list[bytes] = []
        size = 0
        while True:
            part = os.read(handle, min(READ_BLOCK, limit + 1 - size))
            if not part:
                return b"".join(parts)
            parts.append(part)
            size += len(part)
            if size > limit:
                raise OSError(f"{path} is larger than {limit} bytes")
    finally:
        os.close(handle)


def read_manifest(folder: str | os.PathLike) -> tuple[dict[str, Any], dict[str, ChunkRecord]]:
    """The manifest of a sweep's ``folder`` (a dict) and its chunk records by file name.

    ``ValueError`` when there is no manifest or it is not a sweep's.  A record
    that is not well formed is left out (its chunk then counts as unrecorded).
    """
    folder = Path(folder)
    path = folder / MANIFEST
    if not os.path.lexists(path):
        raise ValueError(f"{folder} holds no sweep (no {MANIFEST})")
    try:
        manifest = json_data(_read_regular(path, MANIFEST_LIMIT), "its JSON")
        if not isinstance(manifest, dict) or not isinstance(manifest.get("settings"), dict):
            raise ValueError("no settings in it")
        designs, chunks, chunk = (manifest.get(key) for key in ("designs", "chunks", "chunk"))
        layout = manifest.get("format", 1)
        if layout != FORMAT and type(layout) is int:
            raise _OtherLayout(f"{path} is not a sweep's manifest of this symlink (of another layout, {layout!r}, not "
                             f"{FORMAT}: an older symlink's sweep, whose chunks cannot be verified); continue it with "
                             f"that symlink, or remove {path} to do the sweep again there, or choose another folder")
        if layout != FORMAT:
            raise ValueError(f"its layout is {excerpt(layout)}")
        if not (type(designs) is int and type(chunks) is int and type(chunk) is int and chunk >= 1 and designs >= 0
                and chunks == -(-designs // chunk) and isinstance(manifest.get("columns"), list)):
            raise ValueError("no designs, chunks, chunk or columns in it")
    except (OSError, ValueError, RecursionError) as error:
        if isinstance(error, _OtherLayout):
            raise
        reason = getattr(error, "strerror", None) or str(error)
        raise DamagedManifest(f"{path} is damaged, not a sweep's manifest ({reason}): run the sweep again with the "
                              "same settings to rebuild the folder, or choose another folder", reason) from None
    done = manifest.get("done")
    records = {}
    for name, data in (done.items() if isinstance(done, dict) else ()):
        record = ChunkRecord.from_json(name, data) if isinstance(name, str) and CHUNK_NAME.match(name) else None
        if record is not None:
            records[name] = record
    return manifest, records


def _digest(path: Path, limit: int) -> tuple[int, str]:
    """Size and SHA-256 of the regular file ``path`` (``OSError`` if it is none), reading at most ``limit + 1``
    bytes."""
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    handle = os.open(path, flags)
    try:
        if not stat.S_ISREG(os.fstat(handle).st_mode):
            raise OSError(f"{path} is not a regular file")
        digest, size = hashlib.sha256(), 0
        while size <= limit:
            part = os.read(handle, READ_BLOCK)
            if not part:
                break
            digest.update(part)
            size += len(part)
        return size, digest.hexdigest()
    finally:
        os.close(handle)


def _problem(path: Path, record: ChunkRecord | None, expected: tuple[int, int] | None) -> str | None:
    """Why the chunk file at ``path`` is not the one ``record`` describes (``None`` when it is)."""
    try:
        status = os.lstat(path)
    except FileNotFoundError:
        return "missing"
    if stat.S_ISLNK(status.st_mode):
        return "a symbolic link"
    if stat.S_ISDIR(status.st_mode):
        return "a folder"
    if not stat.S_ISREG(status.st_mode):
        return "not a regular file"
    if expected is None:
        return "not a chunk of this sweep"
    if record is None:
        return "not recorded in the manifest"
    if (record.first, record.last) != expected or record.rows != expected[1] - expected[0] + 1:
        return f"recorded for designs {record.first} to {record.last}, not {expected[0]} to {expected[1]}"
    if status.st_size == 0:
        return "empty"
    if status.st_size != record.size:
        return f"{status.st_size} bytes where the manifest recorded {record.size}: truncated or overwritten"
    try:
        size, digest = _digest(path, record.size)
    except OSError as error:
        return f"unreadable ({error.strerror or error})"
    if size != record.size or digest != record.sha256:
        return "its SHA-256 is not the manifest's (another chunk's or another sweep's file)"
    return None


def _remove(path: Path) -> None:
    """Remove what is at ``path`` (a folder with what it holds; a link, not what it points to)."""
    try:
        if stat.S_ISDIR(os.lstat(path).st_mode):
            shutil.rmtree(path)
        else:
            os.unlink(path)
    except FileNotFoundError:
        pass


def _listing(bad: Mapping[str, str]) -> str:
    named = [f"{name} ({why})" for name, why in sorted(bad.items())[:NAMED]]
    more = len(bad) - len(named)
    return "; ".join(named) + (f"; and {more} more" if more else "")


def _index(name: str, chunks: int) -> int | None:
    """The index of a chunk of this sweep named ``name``, or ``None`` (another name, or beyond the last chunk)."""
    found = CHUNK_NAME.match(name)
    if found is None:
        return None
    index = int(found.group(1))
    return index if index < chunks and name == chunk_name(index) else None


class SweepFolder:
    """A sweep's folder open for writing (see :func:`open_folder`): ``todo`` lists the chunks to do.

    :meth:`stage` writes a finished chunk as a temporary file; :meth:`commit`
    records the staged chunks in the manifest and then renames them into
    place (called now and then by :meth:`stage`, and by :meth:`close`).
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    def __init__(self, path: Path, manifest: dict[str, Any], records: dict[str, ChunkRecord], designs: int,
                 chunk: int, todo: list[int], lock: int | None) -> None:
        self.path, self.manifest, self.records = path, manifest, records
        self.designs, self.chunk, self.todo = designs, chunk, todo
        self._lock = lock
        self._staged: list[tuple[Path, ChunkRecord]] = []
        self._last_commit = time.monotonic()
        self._commit_seconds = 0.0

    def stage(self, index: int, data: bytes, rows: int) -> None:
        """Write chunk ``index`` (``data``, the Parquet bytes of ``rows`` rows) as a temporary file; it is
        counted once a :meth:`commit` has recorded it.  ``ValueError`` if ``rows`` is not the chunk's count."""
        first, last = chunk_range(index, self.designs, self.chunk)
        if rows != last - first + 1:
            raise ValueError(f"chunk {index} came back with {rows} rows, not {last - first + 1}")
        name = chunk_name(index)
        temporary = self.path / f".{name}.{secrets.token_hex(6)}{TEMPORARY_SUFFIX}"
        flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
        handle = os.open(temporary, flags, 0o666)
        try:
            try:
                view = memoryview(data)
                while view:
                    view = view[os.write(handle, view):]
                os.fsync(handle)
            finally:
                os.close(handle)
        except BaseException:
            temporary.unlink(missing_ok=True)
            raise
        self._staged.append((temporary, ChunkRecord(name, rows, first, last, len(data),
                                                    hashlib.sha256(data).hexdigest())))
        # The manifest grows with the chunks done: rewritten no more often than keeps it a small share of the time.
        if time.monotonic() - self._last_commit >= self._commit_seconds / COMMIT_SHARE:
            self.commit()

    def commit(self) -> int:
        """Record the staged chunks in the manifest (written atomically), then rename them into place.

        Returns how many were committed.  A kill between the two leaves recorded chunks that are missing:
        they are done again, and their temporaries are removed, by the next run.
        """
        if not self._staged:
            return 0
        started = time.monotonic()
        staged, self._staged = self._staged, []
        try:
            for _, record in staged:
                self.records[record.name] = record
            self._write_manifest()
            for temporary, record in staged:
                os.replace(temporary, self.path / record.name)
        except BaseException:
            for temporary, _ in staged:
                temporary.unlink(missing_ok=True)
            raise
        self._last_commit = time.monotonic()
        self._commit_seconds = self._last_commit - started
        return len(staged)

    def _write_manifest(self) -> None:
        done = {name: self.records[name].as_json() for name in sorted(self.records)}
        write_atomic(self.path / MANIFEST, json.dumps({**self.manifest, "format": FORMAT, "done": done},
                                                      indent=1) + "\n")

    def close(self) -> None:
        """Commit what is staged (even after an error or Ctrl-C: finished chunks are kept), then unlock."""
        try:
            self.commit()
        finally:
            for temporary, _ in self._staged:
                temporary.unlink(missing_ok=True)
            self._staged = []
            if self._lock is not None:
                os.close(self._lock)  # closing the folder's descriptor releases its lock
                self._lock = None

    def __enter__(self) -> "SweepFolder":
        return self

    def __exit__(self, *exception: object) -> None:
        self.close()


def _locked(folder: Path) -> int | None:
    """A descriptor of ``folder`` holding an exclusive lock on it (``None`` where locks are not available);
    ``ValueError`` when another process holds it."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not on POSIX
        return None
    handle = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0) | getattr(os, "O_CLOEXEC", 0))
    try:
        fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        os.close(handle)
        raise ValueError(f"another sweep is writing into {folder} (it is locked); wait for it to end, "
                         "or choose another folder") from None
    except OSError:  # a file system without locks: go on without one
        pass
    return handle


def open_folder(folder: str | os.PathLike, manifest: dict[str, Any], designs: int, chunk: int) -> SweepFolder:
    """Open a sweep's ``folder`` for writing: create it and its ``manifest``, or check and continue it.

    ``manifest`` holds the sweep's ``settings`` and ``columns`` (and whatever
    else the manifest should say; the numbers of ``designs``, of chunks and
    of designs a ``chunk`` are added); a folder holding another sweep's
    settings, or other files and no sweep, is refused (``ValueError``).  The folder is
    locked until :meth:`SweepFolder.close`; the temporaries of killed writes
    are removed; every chunk that is not what its record says is removed
    with one :class:`SweepWarning` and is done again.
    """
    path = Path(folder)
    chunks = -(-designs // chunk)
    if chunks > MAX_CHUNKS:
        raise ValueError(f"{chunks:,} chunks are too many to record (at most {MAX_CHUNKS:,}): give a chunk of at "
                         f"least {-(-designs // MAX_CHUNKS):,} designs (--chunk)")
    if os.path.lexists(path) and not path.is_dir():
        raise ValueError(f"{path} is not a folder: choose a new or empty folder for the sweep")
    path.mkdir(parents=True, exist_ok=True)
    lock = _locked(path)
    try:
        for name in os.listdir(path):  # a killed write's: none is under way, the folder is ours (locked)
            if TEMPORARY_NAME.match(name) and (lock is not None or _older(path / name)):
                _remove(path / name)
        header = {**manifest, "designs": designs, "chunks": chunks, "chunk": chunk}
        new_settings = json.loads(json.dumps(header["settings"]))
        damage = None
        if not os.path.lexists(path / MANIFEST):
            names = os.listdir(path)
            if names and not all(CHUNK_NAME.match(name) for name in names):
                raise ValueError(f"{path} is not empty and holds no sweep: choose a new or empty folder")
            damage = f"no {MANIFEST}" if names else None
        else:
            try:
                old, records = read_manifest(path)
            except DamagedManifest as error:
                damage = error.reason
            else:
                damage = _damaged_settings(old.get("settings"), new_settings)
                if damage is None and old.get("symlink", header.get("symlink")) != header.get("symlink"):
                    raise ValueError(f"{path} holds a sweep of symlink {excerpt(old.get('symlink'))}, not "
                                     f"{header.get('symlink')}: its rows may differ from this version's; continue it "
                                     f"with that symlink, or remove {path / MANIFEST} to do the sweep again there, or "
                                     "choose another folder")
        if damage is not None or not os.path.lexists(path / MANIFEST):
            if damage is not None:
                _start_again(path, damage)
            opened = SweepFolder(path, header, {}, designs, chunk, list(range(chunks)), lock)
            opened._write_manifest()
            return opened
        old_settings = old.get("settings")
        if old_settings != new_settings or (old["designs"], old["chunk"]) != (designs, chunk):
            old_settings = old_settings if isinstance(old_settings, dict) else {}
            keys = sorted(k for k in set(old_settings) | set(new_settings)
                          if old_settings.get(k) != new_settings.get(k))
            raise ValueError(f"{path} holds a sweep with other settings ({', '.join(keys) or 'its size'} "
                             "differ); choose another folder or the same settings to continue it")
        good: dict[str, ChunkRecord] = {}
        bad: dict[str, str] = {}
        for name in sorted(set(_chunk_like(path)) | set(records)):
            index = _index(name, chunks)
            expected = None if index is None else chunk_range(index, designs, chunk)
            why = _problem(path / name, records.get(name), expected)
            if why is None:
                good[name] = records[name]
            elif why != "missing":
                bad[name] = why
        for name in bad:
            _remove(path / name)
        opened = SweepFolder(path, header, good, designs, chunk,
                             [k for k in range(chunks) if chunk_name(k) not in good], lock)
        if good != records or bad:
            opened._write_manifest()
        if bad:
            warnings.warn(f"{path}: {len(bad)} chunk{'s' if len(bad) > 1 else ''} did not match the manifest and "
                          f"will be done again: {_listing(bad)}", SweepWarning, stacklevel=3)
        return opened
    except BaseException:
        if lock is not None:
            os.close(lock)
        raise


def _damaged_settings(old: object, new: Mapping[str, Any]) -> str | None:
    """Why the recorded settings ``old`` are damaged rather than another sweep's (a value of another JSON type
    than this sweep's, NaN among them), or ``None``."""
    if not isinstance(old, dict):
        return "its settings are not a table"
    for key, value in new.items():
        if key not in old:
            continue
        recorded = old[key]
        if (type(recorded) is not type(value) and recorded is not None and value is not None) or (
                recorded is None and isinstance(value, (dict, list))):
            return f"settings.{key} is {excerpt(recorded)}, not a {type(value).__name__}"
    return None


def _start_again(path: Path, damage: str) -> None:
    """Rebuild a sweep's folder whose manifest is damaged: its chunks (which nothing can verify now) and the
    manifest are removed, with one warning; ``ValueError`` if the folder holds anything else (left alone)."""
    names = [name for name in os.listdir(path) if name != MANIFEST]
    others = [name for name in names if not CHUNK_NAME.match(name)]
    if os.path.lexists(path / MANIFEST) and not stat.S_ISREG(os.lstat(path / MANIFEST).st_mode):
        others.insert(0, MANIFEST)  # a folder or a link by that name is not the sweep's to remove
    if others:
        raise ValueError(f"{path / MANIFEST} is damaged ({damage}) and {path} holds other files ({excerpt(others[0])}"
                         f"{' and more' if len(others) > 1 else ''}): move them, or choose another folder")
    for name in names:
        _remove(path / name)
    _remove(path / MANIFEST)
    warnings.warn(f"{path}: {MANIFEST} was damaged ({damage}); the sweep starts again there"
                  + (f" ({len(names)} chunk{'s' if len(names) != 1 else ''} found, which nothing can verify now, "
                     "done again)" if names else ""), SweepWarning, stacklevel=4)


def _chunk_like(folder: Path) -> list[str]:
    """The names in ``folder`` that could be taken for chunks (``chunk-*.parquet``)."""
    with os.scandir(folder) as entries:
        return [entry.name for entry in entries if entry.name.startswith("chunk-") and entry.name.endswith(".parquet")]


def _older(path: Path) -> bool:
    """Untouched for :data:`symlink.common.files.LEFTOVER_AGE`: where no lock tells, a temporary this old is no running
    write's."""
    try:
        return time.time() - os.lstat(path).st_mtime >= LEFTOVER_AGE
    except OSError:
        return False


def verified_chunks(folder: str | os.PathLike) -> Iterator[tuple[ChunkRecord, bytes]]:
    """Each chunk of a sweep's ``folder`` that is done, in design order: its record and its file's bytes,
    checked against the record (size and SHA-256).

    ``ValueError`` naming the first chunk that is not what its record says, and
    for a file named like a chunk that the manifest does not record: a folder
    with a bad chunk gives no table, rather than one with designs twice or
    missing.  A recorded chunk whose file is missing is one not done yet (a
    run under way, or killed).
    """
    path = Path(folder)
    manifest, records = read_manifest(path)
    designs, chunks, chunk = manifest["designs"], manifest["chunks"], manifest["chunk"]
    again = "; run the sweep again with the same settings to rebuild it"
    for name in sorted(set(_chunk_like(path)) - set(records)):
        index = _index(name, chunks)
        expected = None if index is None else chunk_range(index, designs, chunk)
        raise ValueError(f"{path / name}: {_problem(path / name, None, expected)}{again}")
    for name in sorted(records, key=lambda n: int(CHUNK_NAME.match(n).group(1))):  # type: ignore[union-attr]
        record = records[name]
        index = _index(name, chunks)
        where = path / name
        expected = None if index is None else chunk_range(index, designs, chunk)
        if not os.path.lexists(where):
            if expected is not None and (record.first, record.last) == expected:
                continue  # not done yet: a run under way, or killed between its manifest and its renames
        else:
            try:
                data = _read_regular(where, record.size)
            except OSError:
                data = None
            if (data is not None and expected is not None and (record.first, record.last) == expected
                    and len(data) == record.size and hashlib.sha256(data).hexdigest() == record.sha256):
                yield record, data
                continue
        raise ValueError(f"{where}: {_problem(where, record, expected) or 'changed while it was read'}{again}")
