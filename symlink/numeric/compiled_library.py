"""Compiled C libraries: built with the system compiler, cached, loaded privately, called through ctypes.

The machinery under the compiled backend of :class:`symlink.numeric.solver.Solver` (and of
:class:`symlink.numeric.compiled.CompiledSolver`): a generated C source compiled into a shared
library, cached on disk, loaded from a checked private copy, and its loop function
called on NumPy arrays; the background builds of ``backend="auto"``; and the choice
of backend.  It imports no solver, so that :mod:`symlink.numeric.solver` can use it.
The library is compiled on first use with ``$CC`` (else ``cc``, ``gcc`` or
``clang``) and :data:`FLAGS`, and cached on disk by a hash of the source, the
flags and the compiler (in ``compiled/`` of symlink's cache folder, see
:mod:`symlink.numeric.cache`).  Each library is built in a ``.build-*`` folder beside
it and moved into place, 0600, with the SHA-256 of its bytes beside it.  It
is loaded only from a private copy: copied into a new 0600 file in the
owner-only folder, the copy's bytes checked against the digest, then the
copy handed to the loader, so that a library that is truncated or swapped
between the check and the load never reaches it.  A library that fails the
check is rebuilt.  Any failure to compile, link, write or load (no compiler,
a full disk, a folder where the library should go) falls back to the NumPy
module (:mod:`symlink.numeric.compiled` says how).

The flags are portable: no ``-march=native`` (a cache folder may be shared
between machines); ``-O3`` so that the loops are vectorised;
``-ffp-contract=off`` (no fused multiply-adds, so the arithmetic rounds as
NumPy's does); ``-fno-math-errno`` (only ``errno`` is affected; ``sqrt``
becomes one instruction); ``-fno-trapping-math`` (no program of ours traps
on a floating-point exception, so the compiler may evaluate both sides of the
clamped square root's test and ``floor`` in vector registers: without it no
loop with a square root or the size normalisation's ``floor`` vectorises;
values are unchanged).  ``-ffast-math`` is NOT used: it assumes that no
NaN occurs, and NaN is how an unassembled configuration is reported; it would
also let the compiler rewrite the arguments of ``atan2``.  Where GCC targets
glibc on x86-64, :data:`VECTOR_MATH` is included first: it tells GCC that
glibc's vector math library (libmvec) has ``sin``, ``cos``, ``atan2``, ``log`` and ``pow`` for
whole SIMD registers, and compiles each loop for baseline x86-64, AVX2 and
AVX-512, chosen when the library loads.  libmvec's functions are accurate to
a few units in the last place, as NumPy's own SIMD functions are.
"""
from __future__ import annotations

import atexit
import ctypes
import hashlib
import json
import math
import os
import platform
import secrets
import shlex
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time
import warnings
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping, Sequence

import numpy

from . import cache
from ..common.display import record_html
from .call_arguments import check_argument_names
from ..codegen.call_extension import ENTRY_FIELDS
from ..common.files import NotPrivate, read_private, write_atomic
from .results import checked_out, refuse_overlaps

if TYPE_CHECKING:
    from ..symbolic.linkage import Linkage, Program

# The C printer (symlink.codegen.c) and the linkage (SymPy) are imported where a library's source is made or
# built: loading a library that is built already, from a cache entry's facts, needs neither (a warm sweep).

__all__ = ["FLAGS", "FallbackWarning", "CompilerUnavailable", "CompileError", "cache_directory", "find_compiler",
           "compile_shared", "c_solver_source", "BACKENDS", "chosen_backend", "compiler_works", "built_library",
           "Build", "build_in_background", "wait_for_builds", "compiled_or_warning", "entry_or_build",
           "program_facts", "compiled_or_building", "call_extension", "NO_EXTENSION_VARIABLE"]

#: Compiler flags of every library symlink builds (see the module docstring for why these).
#: ``-fno-builtin-sin/cos`` keep GCC from fusing sin and cos into a scalar-only sincos.
FLAGS = ("-std=c99", "-O3", "-ffp-contract=off", "-fno-math-errno", "-fno-trapping-math", "-fno-builtin-sin",
         "-fno-builtin-cos", "-fPIC", "-shared")

#: Included before every source (``-include``); inert except for GCC on glibc x86-64.
VECTOR_MATH = r"""/* symlink: let GCC vectorise loops over sin, cos and atan2 with glibc's libmvec. */
#include <math.h>
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__) && __GNUC__ >= 11
#define SYMLINK_SIMD __attribute__((simd("notinbranch"), const, nothrow, leaf))
double sin(double) SYMLINK_SIMD;
double cos(double) SYMLINK_SIMD;
double exp(double) SYMLINK_SIMD;
double log(double) SYMLINK_SIMD;
double pow(double, double) SYMLINK_SIMD;
#if __GLIBC_PREREQ(2, 35)
double atan2(double, double) SYMLINK_SIMD;
double atan(double) SYMLINK_SIMD;
double asin(double) SYMLINK_SIMD;
double acos(double) SYMLINK_SIMD;
double tan(double) SYMLINK_SIMD;
#endif
#define SYMLINK_LOOP __attribute__((target_clones("default", "avx2", "arch=x86-64-v4")))
#endif
"""
_VECTOR_MATH_FILE = "symlink_vector_math.h"

_PROBE = "#include <math.h>\ndouble symlink_probe(double x) { return sqrt(x); }\n"
#: Largest library read back from the cache (ours are tens of kilobytes).
LIBRARY_LIMIT = 256 << 20
_loaded: dict[str, ctypes.CDLL] = {}
_private_folder: list[Path] = []
#: The folder a background build writes into: the one of the moment it was asked (set in its thread only).
_build_folder = threading.local()


class FallbackWarning(RuntimeWarning):
    """The compiled backend failed (no compiler, a full disk, a library that will not load): NumPy is used."""


class CompilerUnavailable(RuntimeError):
    """No C compiler, or one that cannot build a shared library with ``math.h``."""


class CompileError(RuntimeError):
    """The compiler works but rejected this source."""


def _private() -> Path:
    """A temporary folder of this process, removed when it exits."""
    if not _private_folder:
        _private_folder.append(Path(tempfile.mkdtemp(prefix="symlink-")))
        atexit.register(shutil.rmtree, _private_folder[0], ignore_errors=True)
    return _private_folder[0]


def cache_directory() -> Path:
    """Where compiled libraries are kept: ``compiled/`` in symlink's cache (:mod:`symlink.numeric.cache`), 0700.

    With the disk cache turned off (``SYMLINK_CACHE`` set empty), or a cache
    folder that cannot be written or is not private to this user, a private
    temporary folder of this process is used instead.

    >>> cache_directory().name
    'compiled'

    A background build uses the folder of the moment it was asked, even where
    ``SYMLINK_CACHE`` changed since (:func:`build_in_background`).
    """
    asked = getattr(_build_folder, "path", None)
    if asked is not None:
        return asked
    root = cache.trusted_directory()
    folder = None if root is None else cache.trusted_directory(root / "compiled")
    if folder is not None and os.access(folder, os.W_OK):
        return folder
    folder = cache.trusted_directory(_private() / "compiled")
    if folder is None:
        raise OSError(f"cannot create a private folder in {_private()}")
    return folder


def find_compiler() -> list[str]:
    """The compiler command: ``$CC`` if set, else the first of cc, gcc, clang on ``PATH``."""
    requested = os.environ.get("CC", "").strip()
    if requested:
        command = shlex.split(requested)
        if shutil.which(command[0]) is None:
            raise CompilerUnavailable(f"CC={requested!r} is not an executable on PATH")
        return command
    for candidate in ("cc", "gcc", "clang"):
        if shutil.which(candidate):
            return [candidate]
    raise CompilerUnavailable("no C compiler found (none of cc, gcc, clang on PATH, and CC is not set); "
                              "install one, e.g. apt-get install gcc libc6-dev")


def _identity(command: list[str]) -> dict:
    """What the cached binary depends on besides the source: the compiler file, flags, platform."""
    path = Path(shutil.which(command[0]) or command[0]).resolve()
    stat = path.stat()
    return {"compiler": [str(path)] + command[1:], "size": stat.st_size, "mtime": stat.st_mtime_ns,
            "flags": FLAGS, "vector_math": VECTOR_MATH, "machine": platform.machine(), "system": platform.system()}


#: Compilers running now (a background build's among them), with their build folders: stopped and removed at exit.
_running: dict[subprocess.Popen, Path] = {}
_exiting = threading.Event()


def _compiler_jobs() -> int:
    """How many compilers a build runs at once: the processors this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def _run_compiler(command: list[str], folder: Path, vector_math: bool = True,
                  units: int = 1) -> subprocess.CompletedProcess:
    """Compile ``folder/symlink.c`` into ``folder/symlink.so`` (run in the folder, so the bytes do not depend on it).

    A source of several translation units (``units`` > 1: ``symlink_0.c``, ``symlink_1.c``, ...,
    :func:`symlink.codegen.translation_units.translation_units`) is compiled unit by unit into object files, as many
    compilers at once as there are processors (:func:`_compiler_jobs`), then linked into the library.
    Each compiler is registered while it runs, so that a process that exits during a background build
    stops it and removes its folder (:func:`_stop_builds`) instead of leaving half a build behind.
    """
    # Without vectorised epilogues: the last few values of a loop run one at a time, and compiling is faster.
    include = ["-include", _VECTOR_MATH_FILE, "--param", "vect-epilogues-nomask=0"] if vector_math else []
    if units <= 1:
        return _run_all([command + list(FLAGS) + include + ["-o", "symlink.so", "symlink.c", "-lm"]], folder)[0]
    objects = [f"symlink_{k}.o" for k in range(units)]
    compiled = _run_all([command + list(FLAGS) + include + ["-c", "-o", o, o[:-2] + ".c"] for o in objects], folder)
    failed = next((result for result in compiled if result.returncode != 0), None)
    if failed is not None:
        return failed
    return _run_all([command + list(FLAGS) + ["-o", "symlink.so"] + objects + ["-lm"]], folder)[0]


def _run_all(commands: list[list[str]], folder: Path) -> list[subprocess.CompletedProcess]:
    """Run the compiler commands in ``folder``, as many at once as :func:`_compiler_jobs`; their results in order.

    After the first failure, the commands not started are not run (their results are that failure).
    """
    if _exiting.is_set():
        raise CompilerUnavailable("the process is exiting")
    # The compiler's own temporaries (its .s and .o) in the build folder too, so that stopping a build
    # (at exit) and removing its folder leaves nothing behind in the system's temporary folder.
    environment = {**os.environ, "TMPDIR": str(folder)}
    results: list[subprocess.CompletedProcess] = []
    running: list[tuple[list[str], subprocess.Popen]] = []
    pending = list(commands)
    try:
        while pending or running:
            while pending and len(running) < _compiler_jobs() and not any(r.returncode for r in results):
                arguments = pending.pop(0)
                process = subprocess.Popen(arguments, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                           text=True, env=environment)
                _running[process] = folder
                running.append((arguments, process))
            if not running:
                break
            arguments, process = running.pop(0)
            try:
                out, err = process.communicate(timeout=300)
            except subprocess.TimeoutExpired:
                process.kill()
                out, err = process.communicate()
            finally:
                _running.pop(process, None)
            results.append(subprocess.CompletedProcess(arguments, process.returncode, out, err))
    finally:
        for _, process in running:  # a failure to start one (OSError): stop the others
            process.kill()
            process.wait()
            _running.pop(process, None)
    failed = next((r for r in results if r.returncode != 0), None)
    return results + [failed] * (len(commands) - len(results))  # type: ignore[list-item]


@atexit.register
def _stop_builds() -> None:
    """At exit: stop the compilers of background builds still running and remove their build folders."""
    _exiting.set()
    for process, folder in list(_running.items()):
        try:
            process.kill()
            process.wait(timeout=5)
        except (OSError, subprocess.SubprocessError):
            pass
        shutil.rmtree(folder, ignore_errors=True)


def _build(source: str, headers: Mapping[str, str], command: list[str], target: Path) -> None:
    """Compile into a temporary folder beside ``target``, then move the library and its digest into place.

    With :data:`VECTOR_MATH` first; without it where that fails (a compiler
    that does not take ``-include`` or the attributes).
    """
    target.parent.mkdir(parents=True, exist_ok=True)
    folder = Path(tempfile.mkdtemp(prefix=".build-", dir=target.parent))
    from ..codegen.translation_units import translation_units  # text only: no printer, no SymPy
    units = translation_units(source)  # a large program's pieces, compiled apart
    try:
        files = {**headers, _VECTOR_MATH_FILE: VECTOR_MATH, "symlink.c": source}
        if len(units) > 1:
            files.update({f"symlink_{k}.c": unit for k, unit in enumerate(units)})
        for name, text in files.items():
            write_atomic(folder / name, text, mode=0o600)
        try:
            result = _run_compiler(command, folder, units=len(units))
            if result.returncode != 0:
                result = _run_compiler(command, folder, vector_math=False, units=len(units))
        except OSError as error:
            raise CompilerUnavailable(f"{command[0]} cannot be run: {error}") from None
        if result.returncode != 0:
            write_atomic(folder / "symlink.c", _PROBE, mode=0o600)
            if _run_compiler(command, folder, vector_math=False).returncode != 0:
                raise CompilerUnavailable(f"{' '.join(command)} cannot build a shared library with math.h "
                                          f"(missing libc6-dev?): {result.stderr.strip()[:500]}")
            raise CompileError(f"{' '.join(command)} rejected the source:\n{result.stderr.strip()[:2000]}")
        built = folder / "symlink.so"
        os.chmod(built, 0o600)  # read and mapped by its owner only; never executed as a program
        binary = built.read_bytes()
        os.replace(built, target)
        write_atomic(target.with_suffix(".sha256"), hashlib.sha256(binary).hexdigest() + "\n", mode=0o600)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _verified_bytes(target: Path) -> bytes | None:
    """The cached library's bytes if it and its digest are private to this user and agree; else ``None``."""
    try:
        expected = read_private(target.with_suffix(".sha256"), 1024).decode("ascii").strip()
        binary = read_private(target, LIBRARY_LIMIT)
    except NotPrivate as why:
        cache.warn_once(f"symlink: not loading a compiled library: {why}; rebuilt")
        return None
    except (OSError, UnicodeDecodeError):
        return None
    return binary if hashlib.sha256(binary).hexdigest() == expected else None


def _intact(target: Path) -> bool:
    """True when the cached library exists, is private to this user and its bytes match its digest."""
    return _verified_bytes(target) is not None


def _whole_elf(binary: bytes) -> bool:
    """False for an ELF file whose headers or loaded segments reach past its end (the loader would fault).

    Other formats are not inspected (True).

    >>> _whole_elf(b"\\x7fELF" + bytes(12)), _whole_elf(b"not ELF")
    (False, True)
    """
    if not binary.startswith(b"\x7fELF"):
        return True
    if len(binary) < 52 or binary[4] not in (1, 2) or binary[5] not in (1, 2):
        return False
    wide, order = binary[4] == 2, "<" if binary[5] == 1 else ">"
    header = f"{order}16xHHIQQQIHHHHHH" if wide else f"{order}16xHHIIIIIHHHHHH"
    if len(binary) < struct.calcsize(header):
        return False
    _, _, _, _, phoff, shoff, _, _, phentsize, phnum, shentsize, shnum, _ = struct.unpack_from(header, binary)
    if phoff + phentsize * phnum > len(binary) or shoff + shentsize * shnum > len(binary):
        return False
    segment = f"{order}IIQQQQ" if wide else f"{order}IIIIII"  # type, (flags,) offset, ..., size in file
    for index in range(phnum):
        fields = struct.unpack_from(segment, binary, phoff + index * phentsize)
        offset, size = (fields[2], fields[5]) if wide else (fields[1], fields[4])
        if offset + size > len(binary):
            return False
    return True


def _load(target: Path) -> ctypes.CDLL | None:
    """The cached library, loaded from a private copy whose bytes match its digest; ``None`` if it cannot be.

    The copy is a new file (``O_EXCL``, 0600) in the owner-only folder, so
    nothing can change it between its check and its load; it is removed once
    loaded (the loader keeps its mapping).
    """
    binary = _verified_bytes(target)
    if binary is None:
        return None
    expected = hashlib.sha256(binary).hexdigest()
    copy = target.parent / f".load-{secrets.token_hex(8)}.so"
    flags = os.O_RDWR | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    handle = os.open(copy, flags, 0o600)
    try:
        os.fchmod(handle, 0o600)
        view = memoryview(binary)
        while view:
            view = view[os.write(handle, view):]
        os.lseek(handle, 0, os.SEEK_SET)
        chunks = []
        while chunk := os.read(handle, 1 << 20):
            chunks.append(chunk)
        copied = b"".join(chunks)
        if hashlib.sha256(copied).hexdigest() != expected or not _whole_elf(copied):
            return None
        try:
            return ctypes.CDLL(str(copy))
        except OSError:
            return None  # not a library this loader takes (a truncated one with a recomputed digest): rebuilt
    finally:
        os.close(handle)
        try:
            os.unlink(copy)
        except OSError:
            pass


def compile_shared(source: str, headers: Mapping[str, str] | None = None,
                   options: Sequence[str] = ()) -> ctypes.CDLL:
    """A C source string compiled with :data:`FLAGS` into a shared library, cached, and loaded.

    ``headers`` are further files (name -> text) that the source includes;
    ``options`` further compiler arguments (``-I`` folders), part of the cache key.
    ``CompilerUnavailable`` where no compiler can build it, ``CompileError``
    where the source is at fault, ``OSError`` where it cannot be written or
    loaded.

    >>> library = compile_shared("double twice(double x) { return 2 * x; }")  # doctest: +SKIP
    >>> library.twice.restype = ctypes.c_double; library.twice.argtypes = [ctypes.c_double]  # doctest: +SKIP
    >>> library.twice(1.5)  # doctest: +SKIP
    3.0
    """
    headers = dict(headers or {})
    command = find_compiler() + list(options)
    key = _library_key(source, command, headers)
    if key in _loaded:
        return _loaded[key]
    target = cache_directory() / f"{key}.so"
    library = _load(target)
    if library is None:
        _build(source, headers, command, target)
        library = _load(target)
        if library is None:
            raise OSError(f"the library just built at {target} cannot be loaded")
    _loaded[key] = library
    return library


#: Set (to anything but empty) to turn the small-call extension off: small compiled calls take the Python path.
NO_EXTENSION_VARIABLE = "SYMLINK_NO_CALL_EXTENSION"

#: The small-call extension once looked for: ``[module]``, or ``[None]`` where it cannot be built or loaded.
_call_extension: list = []


def call_extension(build: bool = True) -> Any:
    """The small-call extension module (:mod:`symlink.codegen.call_extension`), or ``None`` where it is not there.

    Built once into the cache like the solver libraries (``build``; else only looked for, and looked for
    again on the next use where it is not built yet), with the running Python's headers; ``None`` where
    they are not installed, no compiler works, the build or the load fails, the Python has no GIL, or
    :data:`NO_EXTENSION_VARIABLE` is set.  Without it every compiled call works as before, in Python.
    """
    if _call_extension:
        return _call_extension[0]
    module = None
    if not os.environ.get(NO_EXTENSION_VARIABLE, "").strip():
        try:
            module = _load_call_extension(build)
        except (CompilerUnavailable, CompileError, OSError, subprocess.SubprocessError, AttributeError,
                ImportError, SystemError) as error:
            cache.warn_once(f"symlink: small compiled calls without the C extension: {error}", FallbackWarning)
            module = None
        if module is None and not build:
            return None
    _call_extension[:] = [module]
    return module


def _load_call_extension(build: bool) -> Any:
    """The extension module, built (``build``) or loaded from the cache; ``None`` where it cannot be."""
    import sysconfig
    from ..codegen.call_extension import MODULE, extension_source, numpy_include, python_include
    include = python_include()
    if include is None or sysconfig.get_config_var("Py_GIL_DISABLED") or not hasattr(sys, "getrefcount"):
        return None
    source, options = extension_source(), ["-I", include, "-I", numpy_include()]
    library = compile_shared(source, options=options) if build else built_library(source, options)
    if library is None:
        return None
    # Its init function called with the GIL held (a PYFUNCTYPE, not ctypes' default, which releases it).
    address = ctypes.cast(getattr(library, f"PyInit_{MODULE}"), ctypes.c_void_p).value
    return None if address is None else ctypes.PYFUNCTYPE(ctypes.py_object)(address)()


#: Calls of at most this many values take the fast path of :class:`CompiledFunction` (larger ones gain nothing from it).
SMALL_CALL = 4096

#: A ctypes type whose ``from_buffer`` hands a NumPy array's address to a C function (faster than ``.ctypes.data``).
_BYTE = ctypes.c_char * 1


class _PackedCall(ctypes.Structure):
    """``struct symlink_packed_call`` (:data:`symlink.codegen.c.PACKED_CALL`), the one argument of ``<name>_packed``."""

    _fields_ = [("n", ctypes.c_size_t), ("pointers", ctypes.c_void_p), ("steps", ctypes.c_void_p),
                ("numbers", ctypes.c_void_p), ("flags", ctypes.c_void_p)]


class CompiledFunction:
    """Calls one generated C loop function on NumPy arrays, broadcasting like the NumPy module.

    A small call (at most :data:`SMALL_CALL` values) whose arguments are
    numbers and one-dimensional contiguous float arrays of one length takes a
    fast path, so that a call of a few values costs a few microseconds: the
    argument slots (a pointer and a step each, a buffer for the numbers) are
    made once, and a slot is rewritten only where its argument is another
    object than in the call before (the very same float or array costs one
    comparison; an array is read again, so a change in place counts); the
    outputs are two allocations (the number outputs and the true/false ones,
    a row each), made with the one struct the library is called with (:class:`_Outputs`)
    and reused once no caller holds them; and the library is entered once,
    with that struct's address, through ``<name>_packed``
    (:func:`symlink.codegen.c.c_packed`), which checks the arguments as the
    NumPy module does before it evaluates.  A call that does not qualify, or
    whose arguments that check refuses, takes the general path.

    Where the small-call extension is there (:func:`call_extension`,
    :mod:`symlink.codegen.call_extension`: built once into the cache with the
    running Python's headers), that fast path runs in C instead, from a plan
    made here once (``_plan``): the keywords looked up by their interned names,
    the slots filled, a free output block found and the loop entered without a
    Python instruction between (a ten-value call then costs about half as much).
    Otherwise the Python fast path described above answers, with the same
    results bit for bit.  The two never serve one function (they share its slots).
    """

    _repr_html_ = record_html  # a notebook shows its fields as a table

    def __init__(self, library: ctypes.CDLL, name: str, arguments: Sequence[str], outputs: Sequence[str],
                 flags: Sequence[bool], defaults: Mapping[str, float]):
        self.name, self.arguments, self.outputs, self.flags = name, list(arguments), list(outputs), list(flags)
        self.defaults = dict(defaults)
        self.entry = getattr(library, name)
        self.entry.restype = None
        self.entry.argtypes = ([ctypes.c_size_t] + [ctypes.c_void_p, ctypes.c_ssize_t] * len(self.arguments)
                               + [ctypes.c_void_p] * (len(self.outputs) + 1))
        self.packed = getattr(library, f"{name}_packed", None)
        if self.packed is not None:
            self.packed.restype = ctypes.c_int
            self.packed.argtypes = [ctypes.c_void_p]
        self.check = getattr(library, f"{name}_check", None)  # the packed call's check alone (a library of before: none)
        if self.check is not None:
            self.check.restype = ctypes.c_int
            self.check.argtypes = [ctypes.c_void_p]
        self.into = getattr(library, f"{name}_into", None)  # the check and the loop, chunk by chunk, into outputs
        if self.into is not None:
            self.into.restype = ctypes.c_int
            self.into.argtypes = [ctypes.c_void_p, ctypes.c_void_p]
        count = len(self.arguments)
        self._index = {name: index for index, name in enumerate(self.arguments)}
        self._numbers: Any = (ctypes.c_double * max(count, 1))()  # the numbers of a call, each read at a step of 0
        self._numbers_at = ctypes.addressof(self._numbers)
        self._pointers: Any = (ctypes.c_void_p * max(count, 1))()
        self._steps: Any = (ctypes.c_ssize_t * max(count, 1))()
        self._pointers_at, self._steps_at = ctypes.addressof(self._pointers), ctypes.addressof(self._steps)
        # What each slot holds: the number (in the numbers buffer) or the array (kept, so that its pointer stays
        # valid) of the call before; and whether the slot points at anything but its number (an array, or nothing).
        self._held: list = [None] * count
        self._not_number: list[bool] = [True] * count
        self._float_names = [o for o, flag in zip(self.outputs, self.flags) if not flag]
        self._flag_names = [o for o, flag in zip(self.outputs, self.flags) if flag] + ["assembled"]
        floats = iter(range(len(self._float_names)))
        flags_ = iter(range(len(self._flag_names)))
        # Each result in order: (its name, is a flag, its row in the float or flag block).
        rows = [(True, next(flags_)) if flag else (False, next(floats)) for flag in self.flags] + [(True, next(flags_))]
        self._result_names = self.outputs + ["assembled"]
        self._result_rows = rows
        self._result_dtypes = {name: numpy.dtype(bool if flag else numpy.float64)
                               for name, flag in zip(self._result_names, self.flags + [True])}
        self._blocks: list[numpy.ndarray] = []  # the output blocks of larger calls, kept for reuse
        self._free_references = 3  # a kept block's reference count where no caller holds it (set when kept)
        self._kept: list[_Outputs] = []
        self._lock = threading.Lock()  # the slots are shared: one small call at a time
        # The small-call extension's plan of this function (symlink.codegen.call_extension.PLAN_FIELDS), or None
        # where the extension is not there (the Python fast path then answers).
        self._extension: Any = call_extension() if self.packed is not None else None
        self._entries: list[tuple] = []  # the extension's kept output blocks of small calls (ENTRY_FIELDS)
        self._large_entries: list[tuple] = []  # and of larger calls
        # Called with the count before a larger call's new output block is made (a memory check), if set.
        self.before_allocating: Any = None
        # The results by block row: the number rows, then the true/false rows (assembled last).
        self._block_names = self._float_names + self._flag_names
        self._plan: tuple | None = None
        if self._extension is not None and self.packed is not None:
            self._plan = (tuple(sys.intern(a) for a in self.arguments),
                          tuple(float(self.defaults[a]) if a in self.defaults else None for a in self.arguments),
                          self._numbers_at, self._pointers_at, self._steps_at,
                          ctypes.cast(self.packed, ctypes.c_void_p).value, self._entries, self._new_entry,
                          SMALL_CALL, numpy.ndarray, numpy.float64, bytearray(1),
                          tuple(sys.intern(a) for a in self._result_names),
                          bytes(int(flag) for flag, _ in self._result_rows),
                          0 if self.into is None else ctypes.cast(self.into, ctypes.c_void_p).value,
                          self._large_entries, self._new_large_entry, KEPT_OUTPUTS, KEPT_OUTPUTS_MOST,
                          KEPT_OUTPUTS_BYTES, KEPT_BLOCKS)

    def __call__(self, *, out: Any = None, **values) -> dict[str, numpy.ndarray]:
        """The outputs (and ``assembled``) at ``values``, by keyword: new arrays, or the caller's ``out``.

        New arrays are views of one block a call (:meth:`_output_block`); ``out``, a dict of
        arrays by output name (:func:`symlink.numeric.results.checked_out` says which it takes), is
        written in place and returned as it is, so that a large call writes no page the caller
        did not fault in before.
        """
        if self.packed is not None and out is None:
            result = self._small(values)
            if result is not None:
                return result
        check_argument_names(self.name, self.arguments, [a for a in self.arguments if a not in self.defaults],
                             values)
        arrays = [numpy.asarray(values[a] if a in values else self.defaults[a], dtype=numpy.float64)
                  for a in self.arguments]
        shape = numpy.broadcast_shapes(*(a.shape for a in arrays))
        count = math.prod(shape)
        if out is None:
            outputs = self._output_block(shape, count)
        else:
            outputs = checked_out(out, self._result_dtypes, shape, list(zip(self.arguments, arrays)))
        if count:
            strided = [_strided(array, shape) for array in arrays]  # keeps any copy alive during the call
            pointers = [value for pointer, step, _ in strided for value in (pointer, step)]
            self.entry(count, *pointers, *(_address(outputs[name]) for name in self._result_names))
        return outputs

    def checked_call(self, values: Mapping[str, Any], out: Any = None,
                     before_allocating: Any = None) -> dict[str, numpy.ndarray] | None:
        """The outputs at ``values`` checked and evaluated in C (``<name>_into``: each chunk of the arguments
        checked, then evaluated while it is in the cache; no temporaries), else ``None``.

        Takes a call whose arguments are numbers and float64 arrays of one dimension and one length
        (each read at its own step, none copied), as :meth:`__call__` does with ``out``; anything else,
        or arguments the check refuses, gives ``None``: the caller then checks them in NumPy (which
        says what is wrong) and calls :meth:`__call__`.  ``before_allocating()`` is called before a new
        output block is allocated (a memory check).  The caller's ``out`` is checked before anything is
        written; where an argument is refused, the chunks before it may have been written into it.
        """
        if self.into is None:
            return None
        index_of, count = self._index, len(self.arguments)
        if not values.keys() <= index_of.keys():
            return None
        numbers: Any = (ctypes.c_double * max(count, 1))()
        pointers: Any = (ctypes.c_void_p * max(count, 1))()
        steps: Any = (ctypes.c_ssize_t * max(count, 1))()
        start, length, kept = ctypes.addressof(numbers), 0, []
        for index, name in enumerate(self.arguments):
            value: Any = values[name] if name in values else self.defaults.get(name)
            kind = type(value)
            if kind in _NUMBER_TYPES:
                try:
                    numbers[index] = value
                except OverflowError:
                    return None
                pointers[index], steps[index] = start + 8 * index, 0
            elif kind is numpy.ndarray and value.dtype == _FLOAT and value.ndim == 1 \
                    and value.strides[0] % 8 == 0 and (length == 0 or value.shape[0] in (1, length)):
                if value.shape[0] != 1:
                    length = value.shape[0]
                pointers[index], steps[index] = _data_address(value) if value.flags.c_contiguous \
                    else value.ctypes.data, value.strides[0] // 8 if value.shape[0] != 1 else 0
                kept.append(value)
            else:
                return None  # a missing argument, another type or shape: checked in NumPy
        if length == 0 or any(v.shape[0] not in (1, length) for v in kept):
            return None
        shape = (length,)
        if out is not None:
            outputs = checked_out(out, self._result_dtypes, shape, overlaps=False)
        else:
            if before_allocating is not None and not self.allocates_nothing([], shape, None):
                before_allocating()
            outputs = self._output_block(shape, length)
        addresses = [_address(outputs[name]) for name in self._result_names]
        if out is not None:  # the extents in memory from the addresses at hand (asking NumPy costs more)
            spans = []
            for k in range(count):
                if steps[k] or pointers[k] != start + 8 * k:  # an array (a number is in our own buffer)
                    reach = 8 * steps[k] * (length - 1)
                    spans.append((self.arguments[k], (pointers[k] + min(reach, 0), pointers[k] + max(reach, 0) + 8)))
            refuse_overlaps([(name, (address, address + outputs[name].nbytes))
                             for name, address in zip(self._result_names, addresses)], spans)
        call = _PackedCall(length, ctypes.addressof(pointers), ctypes.addressof(steps), 0, 0)
        written: Any = (ctypes.c_void_p * len(addresses))(*addresses)  # alive (a name) while the call runs
        if self.into(ctypes.addressof(call), ctypes.addressof(written)):
            return None  # the NumPy check says which argument, and why
        return outputs

    def allocates_nothing(self, arrays: Sequence[numpy.ndarray], shape: tuple[int, ...], out: Any) -> bool:
        """Whether a general call of these checked ``arrays`` (of broadcast ``shape``) allocates no memory that
        grows with it: it writes into ``out`` or into a kept block nobody holds, and copies no argument."""
        if any(array.size > 1 and not (array.shape == shape and (array.flags.c_contiguous or array.ndim == 1))
               for array in arrays):
            return False  # an argument broadcast or strided in more than one dimension: copied
        if out is not None:
            return True
        count = math.prod(shape)
        size = 8 * len(self._float_names) * count + len(self._flag_names) * count
        references = sys.getrefcount
        # (each kept block's references counted as in _free_block: the list's, the loop's name and the argument)
        return any(block.nbytes == size and references(block) == self._free_references for block in self._blocks)

    def _output_block(self, shape: tuple[int, ...], count: int) -> dict[str, numpy.ndarray]:
        """The outputs of a call of ``count`` values: views of one block, the number rows then the true/false rows.

        The block is one allocation: a block of the same size that no caller holds any more (no view of it
        is referenced anywhere, :meth:`_free_block`) is written again instead, so that a caller who drops
        each result (or keeps it until the next call returns) faults in no new page.
        """
        numbers = 8 * len(self._float_names) * count
        block = self._free_block(numbers + len(self._flag_names) * count)
        number_rows = block[:numbers].view(numpy.float64).reshape((len(self._float_names),) + shape)
        flag_rows = block[numbers:].view(numpy.bool_).reshape((len(self._flag_names),) + shape)
        return {name: (flag_rows if flag else number_rows)[row, ...]  # an array even of shape ()
                for name, (flag, row) in zip(self._result_names, self._result_rows)}

    def _free_block(self, size: int) -> numpy.ndarray:
        """A block of ``size`` bytes: a kept one nothing else references (no result, row or view of it), else new.

        The last :data:`KEPT_BLOCKS` blocks of at most :data:`KEPT_BLOCK_BYTES` are kept.  Every view
        of a block (a result's row, a slice of it, a view of that) has the block as its base, so a
        block whose reference count is the one it had when it was kept (the list's, a name's and
        ``getrefcount``'s argument) is held by no caller, and is never written while one holds it.
        """
        kept, count = self._blocks, sys.getrefcount
        for block in kept:
            if block.nbytes == size and count(block) == self._free_references:
                return block
        block = numpy.empty(size, dtype=numpy.uint8)
        if size <= KEPT_BLOCK_BYTES:
            kept.append(block)
            del kept[:-KEPT_BLOCKS]
            self._free_references = count(block)  # as counted in the loop above: the list, a name, the argument
        return block

    def _new_entry(self, length: int, entries: list | None = None, keep: int | None = None) -> tuple:
        """A new output block of ``length`` values as the extension keeps it (``ENTRY_FIELDS``), kept in
        ``entries`` (the small calls' by default, the last ``keep``: :data:`KEPT_OUTPUTS` by default).

        One ``numpy.empty`` (the number rows, then the true/false rows) and its rows, made by iterating
        two views of it (no Python step an output): each row, and any view of one, has the block as its base.
        """
        floats, flags = len(self._float_names), len(self._flag_names)
        numbers = 8 * floats * length
        block = numpy.empty(numbers + flags * length, numpy.uint8)
        rows = [*block[:numbers].view(_FLOAT).reshape(floats, length),
                *block[numbers:].view(numpy.bool_).reshape(flags, length)]
        results = dict(zip(self._block_names, rows))
        if self._block_names != self._result_names:  # a flag among the outputs: the results in their order
            results = {name: results[name] for name in self._result_names}
        objects = (block, *rows)
        del block, rows  # the references left are those a free block keeps: the tuple's, the dict's, the rows' bases
        # (and the entry's own reference to the block, one more)
        entry = (length, objects, self._extension.references(objects) + 1, objects[0], results)
        entries = self._entries if entries is None else entries
        entries.append(entry)
        del entries[:-(KEPT_OUTPUTS if keep is None else keep)]
        return entry

    def _new_large_entry(self, length: int) -> tuple:
        """A new output block of a larger call, after :attr:`before_allocating` (a memory check) where it is set.

        A block of at most :data:`KEPT_BLOCK_BYTES` is kept for reuse (the extension makes one only where every
        kept block of its length is held): the last :data:`KEPT_BLOCKS` always, and more while they come to at
        most :data:`KEPT_LARGE_MOST` blocks and :data:`KEPT_LARGE_BYTES` bytes, so that a caller keeping each
        result for a few calls is answered from a block it freed, not fresh memory (the extension drops one
        free block a call, back to :data:`KEPT_BLOCKS`, once callers hold fewer).
        """
        if self.before_allocating is not None:
            self.before_allocating(length)
        size = (8 * len(self._float_names) + len(self._flag_names)) * length
        if size > KEPT_BLOCK_BYTES:
            return self._new_entry(length, [], KEPT_BLOCKS)
        entries = self._large_entries
        entry = self._new_entry(length, entries, KEPT_LARGE_MOST)
        while len(entries) > KEPT_BLOCKS and sum(kept[_BLOCK].nbytes for kept in entries) > KEPT_LARGE_BYTES:
            del entries[0]  # the least recently used (the new entry is last)
        return entry

    def _small(self, values: dict) -> dict[str, numpy.ndarray] | None:
        """The fast path's result, or ``None`` where the call does not qualify (the general path then runs)."""
        plan = self._plan
        if plan is not None:
            return self._extension.call(plan, values)
        outputs = self._small_outputs(values)
        return None if outputs is None else outputs.results.copy()

    def _small_outputs(self, values: dict) -> _Outputs | None:
        """The outputs the fast path wrote, or ``None`` where the call does not qualify."""
        packed, index_of = self.packed, self._index
        if packed is None or self._plan is not None:  # the extension's slots: never written from here too
            return None
        if len(values) != len(index_of):  # arguments left to their defaults
            if not values.keys() <= index_of.keys() or not self.defaults.keys() >= index_of.keys() - values.keys():
                return None  # an unknown or a missing argument: the general path says so
            values = {**{name: self.defaults[name] for name in index_of.keys() - values.keys()}, **values}
        # The slots, and the arrays held with their pointers, belong to one call at a time: a call while
        # another thread's small call runs takes the general path (no waiting, and no lock's context manager).
        lock = self._lock
        if not lock.acquire(False):
            return None
        try:
            held, not_number = self._held, self._not_number
            length = 0
            numbers, array, double, largest = _NUMBER_TYPES, numpy.ndarray, _FLOAT, SMALL_CALL  # local: read fast
            for name, value in values.items():
                index = index_of.get(name)
                if index is None:
                    return None
                kind = type(value)
                if kind in numbers:
                    if value is held[index]:  # the number of the call before, in the buffer already
                        continue
                    try:
                        self._numbers[index] = value
                    except OverflowError:
                        return None
                    held[index] = value
                    if not_number[index]:
                        not_number[index] = False
                        self._pointers[index] = self._numbers_at + 8 * index
                        self._steps[index] = 0
                elif kind is array and value.dtype is double and value.ndim == 1 \
                        and value.flags.c_contiguous and 0 < value.shape[0] <= largest \
                        and (length == 0 or value.shape[0] == length):
                    length = value.shape[0]
                    if value is not held[index]:
                        held[index] = value
                        not_number[index] = True
                        self._pointers[index] = _data_address(value)
                        self._steps[index] = 1
                else:
                    return None
            if not length:
                return None  # numbers only: the general path returns arrays of shape ()
            outputs = self._free_outputs(length)
            if packed(outputs.call):
                return None  # an argument the NumPy module would refuse: the general path
            return outputs
        finally:
            lock.release()

    def _free_outputs(self, length: int) -> _Outputs:
        """Output blocks of ``length`` values no caller holds any more (nothing of them referenced), else new ones.

        The last :data:`KEPT_OUTPUTS` blocks are kept: a caller that drops
        each result before the next call but one (``result = solver(...)`` in
        a loop), or keeps each for fewer calls than that (the last few of a
        sweep, a comparison with the call before), is then answered without
        allocating: a kept result costs what a dropped one does.  A block, or any of its
        rows, still referenced anywhere (a kept result, a view, a slice) is
        never written again.
        """
        kept, count = self._kept, sys.getrefcount
        for position, outputs in enumerate(kept):
            # outputs.free(), inline (a method call costs as much as the test)
            if outputs.length == length and sum(map(count, outputs._objects)) == outputs._references:
                if position != len(kept) - 1:
                    # Last in the list, looked at last: in that loop the caller holds it during the next call,
                    # and the block it held before (now first) is free, found with one look.
                    del kept[position]
                    kept.append(outputs)
                return outputs
        outputs = _Outputs(len(self._float_names), len(self._flag_names), length, self._result_rows,
                           self._result_names, (self._pointers_at, self._steps_at))
        kept.append(outputs)
        del kept[:-KEPT_OUTPUTS]
        return outputs


#: Output blocks of small calls kept for reuse by each compiled function (see :meth:`CompiledFunction._free_outputs`):
#: eight, so that results held for up to seven calls are answered from blocks already made (with the call
#: extension a new block and its rows cost about half a dropped call at 10 values, without it about three);
#: at most eight blocks of SMALL_CALL values a function without the call extension.  With it, these are the
#: blocks always kept, and the first looked at for a free one: more are kept while callers hold more results
#: (:data:`KEPT_OUTPUTS_MOST`).
KEPT_OUTPUTS = 8

#: With the call extension, the blocks of small calls kept grow past :data:`KEPT_OUTPUTS` while a caller holds
#: more results than that (a result kept for a number of calls: a deque of the last ones), one a call, up to
#: this many blocks and :data:`KEPT_OUTPUTS_BYTES` bytes: each call then finds a free block, and a kept result
#: costs what a dropped one does.  Once the caller holds fewer, they shrink back by one a call.  Only the
#: first :data:`KEPT_OUTPUTS` (the least recently used) are looked at for a free one.
KEPT_OUTPUTS_MOST = 128

#: The most bytes the blocks of small calls kept grow to (see :data:`KEPT_OUTPUTS_MOST`; never fewer than
#: :data:`KEPT_OUTPUTS` blocks).
KEPT_OUTPUTS_BYTES = 8 << 20

#: Output blocks of larger calls kept for reuse by each compiled function (:meth:`CompiledFunction._free_block`):
#: two, so that ``result = solver(...)`` in a loop (the result before held until the call returns) reuses them.
KEPT_BLOCKS = 2

#: The largest output block kept for reuse (a larger one is the caller's alone, returned to the system when dropped).
KEPT_BLOCK_BYTES = 1 << 28

#: With the call extension, the blocks of larger calls kept grow past :data:`KEPT_BLOCKS` while a caller holds
#: more results than that, up to this many blocks and :data:`KEPT_LARGE_BYTES` bytes (never fewer than
#: :data:`KEPT_BLOCKS`); once the caller holds fewer, they shrink back by one a call.  A block is kept only once
#: made; what is kept beyond the caller's results is the one block its next call writes.
KEPT_LARGE_MOST = 16

#: The most bytes the blocks of larger calls kept grow to (see :data:`KEPT_LARGE_MOST`): 256 MiB, so that a caller
#: keeping the last three results of 10^6 values of the four-bar's full kinematics (50 MB a block) is answered from
#: a block it freed.  The fresh memory of a block above glibc's largest mmap threshold (32 MiB) is returned to the
#: system when freed, and faulted in again a page at a time when it is made anew (measured in
#: ``benchmarks/call_cost.py``, :func:`kept_large_calls`: 1.4-1.5x the loop, kept 3 or 8 at 10^6 values); a block
#: freed and written again is not.
KEPT_LARGE_BYTES = 1 << 28

_BLOCK = ENTRY_FIELDS.index("block")  # where an extension entry holds its block


class _Outputs:
    """The outputs of one small call: a block of number rows and one of true/false rows, and how to fill them.

    ``rows`` are the results in order (views of the two blocks), ``results``
    maps their names to them, and ``call`` is the address of the
    :class:`_PackedCall` that the library is called with to fill them (the
    count, the argument slots ``slots`` of the compiled function, the blocks).
    """

    def __init__(self, numbers: int, flags: int, length: int, rows: Sequence[tuple[bool, int]],
                 names: Sequence[str], slots: tuple[int, int]):
        self.length = length
        # One allocation whose address ctypes knows (an array's address costs more to ask NumPy for than
        # the allocation): the number rows, then the true/false rows.
        size = numbers * length
        memory: Any = (ctypes.c_double * (size + (flags * length + 7) // 8))()  # a buffer NumPy reads
        address = ctypes.addressof(memory)
        number_block = numpy.frombuffer(memory, numpy.float64, size)
        flag_block = numpy.frombuffer(memory, numpy.bool_, flags * length, 8 * size)
        # Rows (and any view of them a caller makes) have the block as their base.
        self.rows = [(flag_block if flag else number_block)[row * length:(row + 1) * length] for flag, row in rows]
        self.results = dict(zip(names, self.rows))
        self._call = _PackedCall(length, slots[0], slots[1], address, address + 8 * size)
        self.call = ctypes.c_void_p(ctypes.addressof(self._call))
        self._objects = tuple(self.rows + [number_block, flag_block])  # a held result shows first in its rows
        del number_block, flag_block
        # References now, all of them ours, summed as free() sums them. No count can fall below its
        # own (ours stay), so the sum is the same exactly where every count is.
        self._references = sum(map(sys.getrefcount, self._objects))

    def free(self) -> bool:
        """Whether nothing but this object references the blocks and rows (no caller holds a result or a view)."""
        return sum(map(sys.getrefcount, self._objects)) == self._references


def _address(array: numpy.ndarray) -> int:
    """The address of a writable array's first byte (``ctypes.from_buffer``: faster than ``array.ctypes.data``)."""
    return ctypes.addressof(_BYTE.from_buffer(array))  # type: ignore[arg-type]  # an ndarray is a buffer


def _data_address(array: numpy.ndarray) -> int:
    """The address of a contiguous array's first byte, writable or not."""
    try:
        return _address(array)
    except (TypeError, BufferError, ValueError):  # a read-only array
        return array.ctypes.data


_FLOAT = numpy.dtype(numpy.float64)

#: The number types a small call takes as they are (each read at a step of 0).
_NUMBER_TYPES = frozenset({float, numpy.float64, int})


def _strided(array: numpy.ndarray, shape: tuple[int, ...]) -> tuple[int, int, numpy.ndarray]:
    """(data pointer, step in elements, the array): no copy for a scalar, a contiguous or a strided 1-d array."""
    item = array.itemsize
    if array.size == 1:
        return _data_address(array), 0, array
    if array.shape == shape and array.flags.c_contiguous:
        return _data_address(array), 1, array
    if array.shape == shape and array.ndim == 1 and array.strides[0] % item == 0:
        return array.ctypes.data, array.strides[0] // item, array
    copy = numpy.ascontiguousarray(numpy.broadcast_to(array, shape))
    return copy.ctypes.data, 1, copy


def program_facts(program: Program, name: str, doc: str, lengths: Sequence[str] = (),
                  piece_size: int | None = None) -> str:
    """The C of one straight-line ``program`` as function ``solve`` (plus its checked ``solve_packed``) and its
    calling facts, as JSON text: ``{"source", "arguments", "outputs", "flags", "defaults"}``.

    A large program comes in pieces (``piece_size``, :data:`symlink.codegen.c.PIECE_SIZE`), which
    :func:`compile_shared` compiles apart, in parallel.
    """
    from ..codegen.c import PIECE_SIZE, c_function, c_library, c_packed
    from ..symbolic.linkage import is_branch_name
    piece_size = PIECE_SIZE if piece_size is None else piece_size
    function = c_function(program, "solve", doc, piece_size)
    _, source = c_library([function], "solver", standalone=True)
    source += "\n" + c_packed(function, list(lengths), [a for a in function.arguments if is_branch_name(a)])
    return json.dumps({"source": source, "arguments": function.arguments, "outputs": function.outputs,
                       "flags": function.flags, "defaults": dict(program.defaults)})


def compiled_or_building(facts: Mapping[str, Any]) -> CompiledFunction | None:
    """The compiled function of ``facts`` (:func:`program_facts`) if its library is built (in memory or in the
    cache); else ``None``, and its background build started where a compiler works (NumPy answers meanwhile)."""
    library = built_library(facts["source"])
    if library is not None:
        return _entry(library, facts)
    if compiler_works():
        build_in_background(facts)
    return None


def c_solver_source(linkage: Linkage, outputs: Sequence[str]) -> dict:
    """The standalone C source of one function ``solve`` for ``outputs``, with its calling facts.

    Derived on the first request only, then read from symlink's cache
    (:func:`symlink.numeric.cache.cached_text`, keyed by the linkage's definition and the
    output names: a warm request does no symbolic work): ``{"source", "arguments",
    "outputs", "flags", "defaults"}``.
    """
    outputs = list(outputs)

    def build() -> str:
        for name in outputs:  # an entry exists only for checked names: a warm request checks (derives) nothing
            linkage.output(name)  # ValueError naming the outputs there are, before any work
        program = linkage.program(outputs)
        return program_facts(program, "solve", f"{linkage.name}: {', '.join(outputs)}.",
                             [s.name for s in program.arguments if s.is_positive])

    return json.loads(cache.cached_text(cache.cache_key(linkage, outputs, "c-solver"), build))


#: Seconds a sweep waits for a compiled library being built before it takes the NumPy module instead.
BUILD_WAIT = 600.0


# --- the backend a Solver uses ---------------------------------------------------------------------------------

#: The backends a :class:`~symlink.numeric.solver.Solver` can use (``backend=`` or the ``SYMLINK_BACKEND`` variable).
BACKENDS = ("auto", "numpy", "compiled")


def chosen_backend(backend: str | None = None) -> str:
    """``backend``, else ``$SYMLINK_BACKEND``, else ``"auto"``; ``ValueError`` naming any other value.

    >>> chosen_backend("numpy")
    'numpy'
    >>> chosen_backend("fortran")
    Traceback (most recent call last):
    ValueError: backend must be one of auto, numpy, compiled; got 'fortran'
    """
    where = "backend"
    if backend is None:
        backend, where = os.environ.get("SYMLINK_BACKEND", "").strip() or "auto", "SYMLINK_BACKEND"
    if backend not in BACKENDS:
        raise ValueError(f"{where} must be one of {', '.join(BACKENDS)}; got {backend!r}")
    return backend


_probed: dict[tuple, bool] = {}


def compiler_works() -> bool:
    """Whether a C compiler builds and loads a library here: probed once a process (and compiler), then remembered.

    The probe's library is cached on disk like any other, so a later process only loads it.
    """
    try:
        command = find_compiler()
    except CompilerUnavailable:
        return False
    identity = tuple(command)
    if identity not in _probed:
        try:
            compile_shared(_PROBE)
            _probed[identity] = True
        except (CompilerUnavailable, CompileError, OSError, subprocess.SubprocessError):
            _probed[identity] = False
    return _probed[identity]


def _library_key(source: str, command: list[str], headers: Mapping[str, str] | None = None) -> str:
    """The cache name of the library of ``source``: a hash of it, its headers and the compiler's identity."""
    return hashlib.sha256(json.dumps({"source": source, "headers": dict(headers or {}), **_identity(command)},
                                     sort_keys=True).encode()).hexdigest()


def built_library(source: str, options: Sequence[str] = ()) -> ctypes.CDLL | None:
    """The library of ``source`` if it is built already (in this process or in the disk cache), else ``None``.

    Never compiles (see :func:`compile_shared`, which does; ``options`` as there).
    """
    try:
        command = find_compiler() + list(options)
        key = _library_key(source, command)
        if key not in _loaded:
            library = _load(cache_directory() / f"{key}.so")
            if library is None:
                return None
            _loaded[key] = library
        return _loaded[key]
    except (CompilerUnavailable, OSError):
        return None


def _entry(library: ctypes.CDLL, facts: Mapping[str, Any]) -> CompiledFunction:
    return CompiledFunction(library, "solve", facts["arguments"], facts["outputs"], facts["flags"], facts["defaults"])


class Build:
    """A library compiled in the background: :meth:`done`, :meth:`wait`, and its :meth:`entry` once built.

    A failed build leaves ``entry()`` ``None`` and says why in ``error`` (the NumPy module keeps answering).
    """

    _repr_html_ = record_html  # a notebook shows its fields as a table

    def __init__(self, facts: Mapping[str, Any]):
        self.facts = dict(facts)
        self.error: BaseException | None = None
        self._library: ctypes.CDLL | None = None
        self._finished = threading.Event()
        try:
            self.folder: Path | None = cache_directory()  # where it was asked: the cache may change before it runs
        except OSError as error:
            self.folder, self.error = None, error

    def run(self) -> None:
        if self.folder is None:
            self._finished.set()
            return
        _build_folder.path = self.folder
        try:
            self._library = compile_shared(self.facts["source"])
            call_extension()  # built here too, so that the thread adopting the entry finds it in the cache
        except (CompilerUnavailable, CompileError, OSError, subprocess.SubprocessError) as error:
            self.error = error
        finally:
            _build_folder.path = None
            self._finished.set()

    def done(self) -> bool:
        return self._finished.is_set()

    def wait(self, timeout: float | None = None) -> bool:
        """Block until the build is over (at most ``timeout`` seconds); whether it is."""
        return self._finished.wait(timeout)

    def entry(self) -> CompiledFunction | None:
        return None if self._library is None else _entry(self._library, self.facts)


_builds: dict[str, Build] = {}
_queue: list[Build] = []
_queue_ready = threading.Condition()
_worker: list[threading.Thread] = []


def _work() -> None:
    """The background builder: one build at a time, in the order asked (a daemon thread, stopped at exit)."""
    while not _exiting.is_set():
        with _queue_ready:
            while not _queue:
                _queue_ready.wait()
            build = _queue.pop(0)
        build.run()


def build_in_background(facts: Mapping[str, Any]) -> Build:
    """The background build of ``facts["source"]`` (one a source and process; started here if it is not yet)."""
    key = hashlib.sha256(facts["source"].encode()).hexdigest()
    with _queue_ready:
        if key in _builds and not (_builds[key].done() and _builds[key].error is not None):
            return _builds[key]
        build = _builds[key] = Build(facts)
        _queue.append(build)
        if not _worker or not _worker[0].is_alive():
            _worker[:] = [threading.Thread(target=_work, name="symlink-compiler", daemon=True)]
            _worker[0].start()
        _queue_ready.notify()
    return build


def wait_for_builds(timeout: float | None = None) -> bool:
    """Block until every background build asked for so far is over (at most ``timeout`` seconds); whether they are."""
    with _queue_ready:
        pending = [build for build in _builds.values() if not build.done()]
    deadline = None if timeout is None else time.monotonic() + timeout
    for build in pending:
        left = None if deadline is None else max(0.0, deadline - time.monotonic())
        if not build.wait(left):
            return False
    return True


def compiled_or_warning(linkage: Linkage, outputs: Sequence[str]) -> CompiledFunction | None:
    """What ``backend="compiled"`` gets: the compiled function of ``outputs``, built now if it is not in the cache;
    where it cannot be built or loaded, one ``FallbackWarning`` and ``None`` (NumPy answers)."""
    try:
        facts = c_solver_source(linkage, outputs)
    except OSError as error:
        warnings.warn(f"symlink: no compiled backend, using NumPy instead: {error}", FallbackWarning, stacklevel=3)
        return None
    return compiled_or_warning_of(facts, stacklevel=4)


def compiled_or_warning_of(facts: Mapping[str, Any], stacklevel: int = 3) -> CompiledFunction | None:
    """:func:`compiled_or_warning` of a solver's C source and calling facts (:func:`program_facts`), as a cache
    entry holds them: no linkage needed."""
    try:
        return _entry(compile_shared(facts["source"]), facts)
    except (CompilerUnavailable, CompileError, OSError, subprocess.SubprocessError) as error:
        warnings.warn(f"symlink: no compiled backend, using NumPy instead: {error}", FallbackWarning,
                      stacklevel=stacklevel)
        return None


def entry_or_build(linkage: Linkage, outputs: Sequence[str]) -> tuple[CompiledFunction | None, Build | None]:
    """What ``backend="auto"`` gets: the compiled function if its library is built (in memory or on disk), else
    its background build (the NumPy module answers meanwhile), or neither where no compiler works.

    The C source is derived here, in the caller's thread (SymPy's evaluation settings are global: never
    derive in a background thread); only the compiler runs in the background.
    """
    if not compiler_works():
        return None, None
    try:
        facts = c_solver_source(linkage, outputs)
    except (OSError, ValueError, NotImplementedError, TypeError):
        return None, None  # a linkage the C printer cannot print: NumPy
    return entry_or_build_of(facts)


def entry_or_build_of(facts: Mapping[str, Any]) -> tuple[CompiledFunction | None, Build | None]:
    """:func:`entry_or_build` of a solver's C source and calling facts (:func:`program_facts`), as a cache entry
    holds them: no linkage needed, no SymPy."""
    if not compiler_works():
        return None, None
    library = built_library(facts["source"])
    if library is not None:
        return _entry(library, facts), None
    return None, build_in_background(facts)
