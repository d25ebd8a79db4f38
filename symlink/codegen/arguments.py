"""The check every generated function makes of its arguments, and its one home: NumPy only, no SymPy.

The NumPy printer (:mod:`symlink.codegen.numpy`) copies the source of :func:`_arguments` into every module it
writes, so that a generated module checks its arguments alike without importing symlink; a process that needs
the check without printing anything (a Grashof class of many designs, a warm sweep) imports it from here.

>>> checked_arguments(["theta", "branch"], [[0.0, 1.0], 1])[1]
(2,)
"""
from __future__ import annotations

from typing import Sequence

import numpy

__all__ = ["checked_arguments", "check_lengths"]


def _arguments(check, names, values, lengths=(), signs=()):
    """The arguments as float64 arrays and their broadcast shape; with ``check``, ``ValueError`` naming a bad one.

    Every dtype is computed in float64 (float16, float32, ints and bools are
    converted; float64 arrays are used as they are, without a copy).
    Checked, one vectorised test an argument: real numbers only (a complex
    value is refused rather than cut to its real part), shapes that broadcast
    together, branch signs exactly +1 or -1, lengths positive and finite
    from 1e-305 to 1e305 (so that a loop's sums and its unit stay normal
    doubles), every other value finite.  ``check=False`` converts only, for hot loops.
    """
    if not check:
        arrays = tuple(numpy.asarray(value, dtype=float) for value in values)
        shapes = {array.shape for array in arrays} - {()}
        return arrays, shapes.pop() if len(shapes) == 1 else numpy.broadcast_shapes(*(a.shape for a in arrays))
    arrays = []
    for name, value in zip(names, values):
        if type(value) is float:  # the usual length, sign or rate: no conversion to check
            arrays.append(numpy.float64(value))
            continue
        array = numpy.asarray(value)
        kind = array.dtype.kind
        if array.dtype != numpy.float64:  # float64 arrays as they are (no copy); all else computed in float64
            try:
                if kind not in "fbiuO":
                    raise TypeError
                array = array.astype(numpy.float64)  # float16/32, ints, bools, Python numbers; complex: TypeError
            except (TypeError, ValueError, OverflowError):
                why = " (its imaginary part would be lost)" if kind == "c" else ""
                raise ValueError(f"{name} must be real numbers, got {array.dtype} values{why}") from None
        arrays.append(array)
    shapes = {array.shape for array in arrays} - {()}
    try:
        shape = shapes.pop() if len(shapes) == 1 else numpy.broadcast_shapes(*(array.shape for array in arrays))
    except ValueError:
        shapes = ", ".join(f"{name} has shape {array.shape}" for name, array in zip(names, arrays) if array.ndim)
        raise ValueError(f"the arguments do not broadcast together: {shapes}") from None
    for name, array in zip(names, arrays):
        if array.ndim == 0:  # a single number, the usual length or sign: tested without NumPy's overhead
            x = float(array)
            if name in signs:
                good = x == 1.0 or x == -1.0
            elif name in lengths:
                good = 1e-305 <= x <= 1e305
            else:
                good = x - x == 0.0
        elif name in signs:
            good = numpy.abs(array) == 1.0
        elif name in lengths:  # two passes without a temporary; a NaN fails both comparisons
            good = array.size == 0 or bool(1e-305 <= array.min() and array.max() <= 1e305)
        else:
            good = numpy.isfinite(array)
        if not (good if array.ndim == 0 or name in lengths else good.all()):
            if name in lengths:
                good = (array >= 1e-305) & (array <= 1e305)
            bad = float(array if array.ndim == 0 else array[~good].flat[0])
            wanted = ("must be +1 or -1" if name in signs else "must be a positive finite length" if name in lengths
                      else "must be finite")
            if name in lengths and 0.0 < bad < numpy.inf:  # lengths whose sums or squares would over- or underflow
                wanted = "must be from 1e-305 to 1e305 in size (express the lengths in another unit)"
            raise ValueError(f"{name} {wanted}, got {bad!r}")
    return tuple(arrays), shape


def checked_arguments(names: Sequence[str], values: Sequence[object], lengths: Sequence[str] = (),
                      signs: Sequence[str] = ()) -> tuple[tuple[numpy.ndarray, ...], tuple[int, ...]]:
    """The arguments as float arrays and their broadcast shape, checked as every generated function checks them.

    The one home of the check: its source is copied into each generated module.

    >>> checked_arguments(["theta", "branch"], [[0.0, 1.0], 1])[1]
    (2,)
    >>> checked_arguments(["a"], [-1.0], lengths=["a"])
    Traceback (most recent call last):
    ValueError: a must be a positive finite length, got -1.0
    >>> checked_arguments(["theta"], [1j])
    Traceback (most recent call last):
    ValueError: theta must be real numbers, got complex128 values (its imaginary part would be lost)
    """
    return _arguments(True, tuple(names), tuple(values), tuple(lengths), tuple(signs))


def check_lengths(**lengths: float) -> None:
    """``ValueError`` naming the first length that is not a positive finite (real) number.

    >>> check_lengths(crank=20.0, rocker=[56.0, -1.0])
    Traceback (most recent call last):
    ValueError: rocker must be a positive finite length, got -1.0
    """
    checked_arguments(list(lengths), list(lengths.values()), lengths=list(lengths))
