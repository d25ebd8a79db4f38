"""The C of symlink's small-call extension: a CPython module that hands a call's keywords to a compiled loop.

A compiled call of a few values (:class:`symlink.numeric.compiled_library.CompiledFunction`)
costs far more in Python, walking its keyword arguments and filling the
loop's argument slots, than in the loop itself.  This module writes the C of
one small CPython extension, ``symlink_call``, that does that walk in C,
for every compiled function alike: each function describes itself once in a
*plan* (a tuple, see :data:`PLAN_FIELDS`), and a call is then
``symlink_call.call(plan, values)``.  The extension:

* looks each argument up by its interned name in ``values`` (the keyword
  dict), a default where one is left out; an unknown or a missing name
  refuses the call;
* takes a ``float``, ``numpy.float64`` or ``int`` as a number (read at a
  step of 0), a one-dimensional C-contiguous native float64 ``numpy.ndarray``
  of 1 to ``largest`` values (all of one length) as an array, read through
  the buffer protocol (no NumPy headers are needed); anything else refuses;
* finds a block of outputs no caller holds any more among the kept ones (the
  sum of their reference counts back at its value when made; the least
  recently used looked at first, at most ``keep`` of them), else makes a
  new one in C (one NumPy block and a view of it a row, through NumPy's C
  API: no Python step), and calls the loop's ``<name>_packed`` wrapper once,
  which checks the values as the NumPy module does.  The kept blocks grow
  past ``keep`` while a caller holds more results than that (up to
  ``keep_most`` blocks and ``keep_bytes`` bytes), so that a caller keeping
  each result for a number of calls is answered from a block made before,
  as one dropping each is; they shrink back by one a call once fewer are held;
* returns a new dict of the output rows (``call``), or a
  :class:`symlink.numeric.results.Results` made without ``__init__`` (``results``),
  or ``None`` where the call is refused: the caller's general path then
  answers, with its errors and broadcasting.

``large`` takes a call of any length (arrays may be strided, or of one value):
its own slots, the caller's ``out`` arrays checked through the buffer protocol
(type, dtype, shape, contiguity, writability, overlaps: O(outputs)) or a kept
block of larger calls nobody holds (a new one from the plan's ``make_large``, which checks
the memory first and bounds how many are kept: they grow while a caller holds results, and shrink back by one
a call to ``keep_large``), and ``<name>_into`` (checks and evaluates chunk by chunk)
called with the GIL released; a ``Results``, or ``None`` as above.

The plan's ``busy`` byte makes one small call at a time use the shared slots: a
call while another thread's small call is inside (only possible while a new
block's allocation runs the garbage collector) is refused, and answered by ``large``
or the general path.

It is compiled like the solver libraries (:func:`symlink.numeric.compiled_library.compile_shared`) with the
headers of the running Python and NumPy; the source names the Python and the NumPy it is for, so that
the cached library of one is never loaded by another.

>>> "PyInit_symlink_call" in extension_source()
True
"""
from __future__ import annotations

import sys
import sysconfig

__all__ = ["MODULE", "PLAN_FIELDS", "ENTRY_FIELDS", "extension_source", "python_include", "numpy_include"]

#: The extension module's name (its init function is ``PyInit_<MODULE>``).
MODULE = "symlink_call"

#: The fields of a plan tuple, in order: the argument names (interned str), their defaults (a float or
#: ``None``), the addresses of the numbers buffer, the pointer slots, the step slots and the
#: ``<name>_packed`` function, the kept output blocks (a list of entries), ``make(length)`` (a new entry,
#: kept), the most values a small call takes, ``numpy.ndarray``, ``numpy.float64``, the busy byte (a bytearray);
#: then, for :func:`large` calls: the result names in order (interned str, ``assembled`` last), their layout
#: (bytes, 1 for a true/false result, 0 for a number), the address of ``<name>_into`` (0: none), the kept
#: output blocks of large calls and ``make_large(length)`` (a new entry there, kept); how many blocks of
#: small calls are always kept (a new one is made in C, with NumPy's C API: a block and its rows, no Python
#: step), and the most blocks and bytes they may grow to while callers hold results (each call then finds one
#: free: a kept result costs what a dropped one does); how many blocks of large calls are always kept (more are
#: kept while callers hold results, as ``make_large`` bounds them: the list shrinks back by one a call).
PLAN_FIELDS = ("names", "defaults", "numbers", "pointers", "steps", "packed", "kept", "make", "largest",
               "array_type", "float64_type", "busy", "results", "layout", "into", "kept_large", "make_large",
               "keep", "keep_most", "keep_bytes", "keep_large")

#: The fields of a kept output block's entry: its length, the objects whose references say whether a
#: caller holds it (the block and its rows), the sum of their reference counts when free, the block (a
#: writable buffer: the number rows, ``length`` doubles each, then the true/false rows, ``length`` bytes
#: each, in the order of the plan's layout) and the dict of its rows by name.
ENTRY_FIELDS = ("length", "objects", "references", "block", "results")


def python_include() -> str | None:
    """The folder holding the running Python's ``Python.h``, or ``None`` where it is not installed."""
    folder = sysconfig.get_paths().get("include")
    if not folder:
        return None
    from pathlib import Path
    return folder if (Path(folder) / "Python.h").is_file() else None


def _enum(prefix: str, fields: tuple[str, ...]) -> str:
    return "enum { " + ", ".join(f"{prefix}_{name.upper()} = {k}" for k, name in enumerate(fields)) \
        + f", {prefix}_SIZE = {len(fields)} }};"


def numpy_include() -> str:
    """The folder holding NumPy's C headers (``numpy/arrayobject.h``), of the NumPy imported."""
    import numpy
    return numpy.get_include()


def extension_source() -> str:
    """The C source of the ``symlink_call`` extension for the running Python and NumPy."""
    import numpy
    abi = sysconfig.get_config_var("SOABI") or ""
    return _SOURCE.replace("@VERSION@", sys.version.replace("*/", "").replace("\n", " ")
                           + f", NumPy {numpy.__version__}") \
        .replace("@ABI@", abi).replace("@PLAN@", _enum("PLAN", PLAN_FIELDS)) \
        .replace("@ENTRY@", _enum("ENTRY", ENTRY_FIELDS)).replace("@MODULE@", MODULE)


_SOURCE = r"""/* symlink's small-call extension, for Python @VERSION@ (@ABI@). Generated by symlink.codegen.call_extension. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#include <numpy/arrayobject.h>
#include <stddef.h>
#include <string.h>

@PLAN@
@ENTRY@

/* struct symlink_packed_call (symlink.codegen.c.PACKED_CALL): the one argument of <name>_packed and <name>_into. */
struct symlink_call_struct {
    size_t n;
    void *const *pointers;
    const ptrdiff_t *steps;
    double *numbers;
    unsigned char *flags;
};
typedef int (*symlink_packed_function)(const struct symlink_call_struct *call);
typedef int (*symlink_into_function)(const struct symlink_call_struct *call, void *const *outputs);

/* Calls of more values than this run with the GIL released (other threads work meanwhile). */
#define SYMLINK_RELEASE_GIL 4096

static PyObject *empty_tuple, *name_units, *name_inputs, *name_input_units;

static int plan_is_one(PyObject *plan, PyObject *values)
{
    if (!PyTuple_CheckExact(plan) || PyTuple_GET_SIZE(plan) != PLAN_SIZE || !PyDict_CheckExact(values)
            || !PyTuple_CheckExact(PyTuple_GET_ITEM(plan, PLAN_NAMES))
            || !PyTuple_CheckExact(PyTuple_GET_ITEM(plan, PLAN_DEFAULTS))
            || PyTuple_GET_SIZE(PyTuple_GET_ITEM(plan, PLAN_NAMES)) != PyTuple_GET_SIZE(PyTuple_GET_ITEM(plan, PLAN_DEFAULTS))
            || !PyList_CheckExact(PyTuple_GET_ITEM(plan, PLAN_KEPT))
            || !PyByteArray_CheckExact(PyTuple_GET_ITEM(plan, PLAN_BUSY))
            || PyByteArray_GET_SIZE(PyTuple_GET_ITEM(plan, PLAN_BUSY)) < 1
            || !PyTuple_CheckExact(PyTuple_GET_ITEM(plan, PLAN_RESULTS))
            || !PyBytes_CheckExact(PyTuple_GET_ITEM(plan, PLAN_LAYOUT))
            || PyBytes_GET_SIZE(PyTuple_GET_ITEM(plan, PLAN_LAYOUT)) != PyTuple_GET_SIZE(PyTuple_GET_ITEM(plan, PLAN_RESULTS))
            || !PyList_CheckExact(PyTuple_GET_ITEM(plan, PLAN_KEPT_LARGE))) {
        PyErr_SetString(PyExc_TypeError, "symlink_call: a plan tuple and a dict of values are expected");
        return 0;
    }
    return 1;
}

static int entry_is_one(PyObject *entry)
{
    if (!PyTuple_CheckExact(entry) || PyTuple_GET_SIZE(entry) != ENTRY_SIZE
            || !PyTuple_CheckExact(PyTuple_GET_ITEM(entry, ENTRY_OBJECTS))
            || PyTuple_GET_SIZE(PyTuple_GET_ITEM(entry, ENTRY_OBJECTS)) < 1
            || !PyLong_CheckExact(PyTuple_GET_ITEM(entry, ENTRY_LENGTH))
            || !PyDict_CheckExact(PyTuple_GET_ITEM(entry, ENTRY_RESULTS))) {
        PyErr_SetString(PyExc_TypeError, "symlink_call: an output entry is not one");
        return 0;
    }
    return 1;
}

/* The rows of an entry's block of `length` values (the number rows, then the true/false rows, as `layout`
 * orders them): 0, or -1 with an exception where the block is not a writable buffer of their size. */
static int entry_rows(PyObject *entry, PyObject *layout, Py_ssize_t length, double **numbers, unsigned char **flags)
{
    const char *kinds = PyBytes_AS_STRING(layout);
    Py_ssize_t all = PyBytes_GET_SIZE(layout), rows = 0;
    for (Py_ssize_t k = 0; k < all; ++k) {
        rows += kinds[k] == 0;
    }
    Py_buffer view;
    if (PyObject_GetBuffer(PyTuple_GET_ITEM(entry, ENTRY_BLOCK), &view, PyBUF_WRITABLE | PyBUF_C_CONTIGUOUS) != 0) {
        return -1;
    }
    int good = view.len >= 8 * rows * length + (all - rows) * length;
    *numbers = (double *)view.buf;
    *flags = (unsigned char *)view.buf + 8 * rows * length;
    PyBuffer_Release(&view);  /* the block stays alive: the entry holds it */
    if (!good) {
        PyErr_SetString(PyExc_TypeError, "symlink_call: an output block is smaller than its rows");
        return -1;
    }
    return 0;
}

/* A new entry (ENTRY_FIELDS) of `length` values, appended to `kept` (its last `keep` kept): one block (NumPy's
 * uint8 array, the number rows then the true/false rows as the plan's layout orders them) and its rows, views
 * whose base is the block (so is the base of any view of them), in a dict by result name. No Python code. */
static PyObject *new_entry(PyObject *plan, PyObject *kept, Py_ssize_t keep, Py_ssize_t length)
{
    PyObject *results = PyTuple_GET_ITEM(plan, PLAN_RESULTS), *layout = PyTuple_GET_ITEM(plan, PLAN_LAYOUT);
    const char *kinds = PyBytes_AS_STRING(layout);
    Py_ssize_t all = PyBytes_GET_SIZE(layout), floats = 0, number_row = 0, flag_row = 0;
    for (Py_ssize_t k = 0; k < all; ++k) {
        floats += kinds[k] == 0;
    }
    npy_intp size = (npy_intp)((8 * floats + (all - floats)) * length), n = (npy_intp)length;
    PyObject *block = PyArray_SimpleNew(1, &size, NPY_UINT8), *objects = NULL, *rows = NULL, *entry = NULL;
    PyObject *count = NULL, *references = NULL;
    if (block == NULL) {
        return NULL;
    }
    char *data = PyArray_BYTES((PyArrayObject *)block);
    objects = PyTuple_New(all + 1);
    rows = PyDict_New();
    if (objects == NULL || rows == NULL) {
        goto fail;
    }
    Py_INCREF(block);
    PyTuple_SET_ITEM(objects, 0, block);
    for (Py_ssize_t k = 0; k < all; ++k) {
        char *at = kinds[k] ? data + 8 * floats * length + length * flag_row++ : data + 8 * length * number_row++;
        PyObject *row = PyArray_NewFromDescr(&PyArray_Type, PyArray_DescrFromType(kinds[k] ? NPY_BOOL : NPY_DOUBLE),
                                             1, &n, NULL, at, NPY_ARRAY_CARRAY, NULL);
        if (row == NULL) {
            goto fail;
        }
        Py_INCREF(block);
        if (PyArray_SetBaseObject((PyArrayObject *)row, block) < 0) {  /* takes the reference, even failing */
            Py_DECREF(row);
            goto fail;
        }
        PyTuple_SET_ITEM(objects, k + 1, row);
        if (PyDict_SetItem(rows, PyTuple_GET_ITEM(results, k), row) < 0) {
            goto fail;
        }
    }
    /* The references a free block keeps: the tuple's, the dict's, the rows' bases, and the entry's (one more,
     * to the block; `block` here is that one). */
    Py_ssize_t sum = 0;
    for (Py_ssize_t k = 0; k <= all; ++k) {
        sum += Py_REFCNT(PyTuple_GET_ITEM(objects, k));
    }
    count = PyLong_FromSsize_t(length);
    references = PyLong_FromSsize_t(sum);
    if (count == NULL || references == NULL) {
        goto fail;
    }
    entry = PyTuple_New(ENTRY_SIZE);
    if (entry == NULL) {
        goto fail;
    }
    PyTuple_SET_ITEM(entry, ENTRY_LENGTH, count);
    PyTuple_SET_ITEM(entry, ENTRY_OBJECTS, objects);
    PyTuple_SET_ITEM(entry, ENTRY_REFERENCES, references);
    PyTuple_SET_ITEM(entry, ENTRY_BLOCK, block);
    PyTuple_SET_ITEM(entry, ENTRY_RESULTS, rows);
    if (PyList_Append(kept, entry) < 0) {
        Py_DECREF(entry);
        return NULL;
    }
    Py_ssize_t held = PyList_GET_SIZE(kept);
    if (held > keep && PyList_SetSlice(kept, 0, held - keep, NULL) < 0) {
        Py_DECREF(entry);
        return NULL;
    }
    return entry;
fail:
    Py_XDECREF(count);
    Py_XDECREF(references);
    Py_XDECREF(objects);
    Py_XDECREF(rows);
    Py_DECREF(block);
    return NULL;
}

/* The length of `entry` where it is one of ours (ENTRY_FIELDS) that no caller holds, else -1: the sum of the
 * reference counts of its block and rows back at its value when made (a caller holding a row, or a view of one,
 * adds to it). Such an entry may be written again. */
static Py_ssize_t free_length(PyObject *entry)
{
    if (!PyTuple_CheckExact(entry) || PyTuple_GET_SIZE(entry) != ENTRY_SIZE
            || !PyLong_CheckExact(PyTuple_GET_ITEM(entry, ENTRY_LENGTH))
            || !PyLong_CheckExact(PyTuple_GET_ITEM(entry, ENTRY_REFERENCES))
            || !PyTuple_CheckExact(PyTuple_GET_ITEM(entry, ENTRY_OBJECTS))) {
        return -1;  /* not an entry of ours: never used */
    }
    PyObject *objects = PyTuple_GET_ITEM(entry, ENTRY_OBJECTS);
    Py_ssize_t sum = 0;
    for (Py_ssize_t k = 0; k < PyTuple_GET_SIZE(objects); ++k) {
        sum += Py_REFCNT(PyTuple_GET_ITEM(objects, k));
    }
    Py_ssize_t free_sum = PyLong_AsSsize_t(PyTuple_GET_ITEM(entry, ENTRY_REFERENCES));
    Py_ssize_t length = PyLong_AsSsize_t(PyTuple_GET_ITEM(entry, ENTRY_LENGTH));
    if ((free_sum == -1 || length == -1) && PyErr_Occurred()) {
        PyErr_Clear();
        return -1;
    }
    return sum == free_sum ? length : -1;  /* else a caller holds a row, or a view of one: never written again */
}

/* A free kept entry of `length` values among the first `window` of `kept` (moved last in the list), borrowed;
 * NULL if none. The list is in the order of use, the least recently used first: a caller keeping each result
 * for a few calls frees the first one, found with one look. While the list has more than `keep`, a free first
 * entry of another length is dropped on the way (a caller now calling with another length). */
static PyObject *free_entry(PyObject *kept, Py_ssize_t length, Py_ssize_t window, Py_ssize_t keep)
{
    for (Py_ssize_t p = 0; p < PyList_GET_SIZE(kept) && p < window;) {
        PyObject *entry = PyList_GET_ITEM(kept, p);
        Py_ssize_t free = free_length(entry);
        if (free != length) {
            if (free >= 0 && p == 0 && PyList_GET_SIZE(kept) > keep) {
                if (PyList_SetSlice(kept, 0, 1, NULL) < 0) {
                    PyErr_Clear();
                    return NULL;
                }
            } else {
                ++p;
            }
            continue;
        }
        if (p != PyList_GET_SIZE(kept) - 1) {  /* the caller of a loop holds the last one during the next call */
            Py_INCREF(entry);
            if (PyList_SetSlice(kept, p, p + 1, NULL) < 0 || PyList_Append(kept, entry) < 0) {
                Py_DECREF(entry);
                PyErr_Clear();
                return NULL;
            }
            Py_DECREF(entry);  /* the list holds it */
        }
        return entry;
    }
    return NULL;
}

/* The most blocks of `length` values the small calls keep (PLAN_KEEP_MOST, PLAN_KEEP_BYTES): as many as a
 * caller holds at once, plus one, so that each call finds a free one, up to `most` blocks and `bytes` bytes;
 * at least `keep`. */
static Py_ssize_t most_kept(PyObject *layout, Py_ssize_t length, Py_ssize_t keep, Py_ssize_t most, Py_ssize_t bytes)
{
    const char *kinds = PyBytes_AS_STRING(layout);
    Py_ssize_t all = PyBytes_GET_SIZE(layout), size = 0;
    for (Py_ssize_t k = 0; k < all; ++k) {
        size += kinds[k] ? length : 8 * length;
    }
    Py_ssize_t fit = size > 0 ? bytes / size : most;
    fit = fit < most ? fit : most;
    return fit > keep ? fit : keep;
}

/* Drop the first entry of `kept` where no caller holds it and the list has more than `keep`: called after a call
 * found a free block, so that the list shrinks by one a call back to `keep` once callers hold fewer results. */
static void drop_one_unused(PyObject *kept, Py_ssize_t keep)
{
    if (PyList_GET_SIZE(kept) > keep && free_length(PyList_GET_ITEM(kept, 0)) >= 0
            && PyList_SetSlice(kept, 0, 1, NULL) < 0) {
        PyErr_Clear();
    }
}

/* Whether every key of `values` is an exact str: other keys could run Python code when compared (and change
 * `values` meanwhile), so a call with one is refused. */
static int keys_are_str(PyObject *values)
{
    PyObject *key, *item;
    for (Py_ssize_t position = 0; PyDict_Next(values, &position, &key, &item);) {
        if (!PyUnicode_CheckExact(key)) {
            return 0;
        }
    }
    return 1;
}

/* The value of argument `i` (borrowed): looked up in `values` by its interned name (then counted in `found`),
 * else its default; NULL, no exception set, where it is missing (no default) or the look-up fails: the call is
 * refused, and the general path names the argument. The one walk of the keywords of `run` and `large`. */
static PyObject *argument_value(PyObject *values, PyObject *names, PyObject *defaults, Py_ssize_t i,
                                Py_ssize_t *found)
{
    PyObject *value = PyDict_GetItemWithError(values, PyTuple_GET_ITEM(names, i));  /* borrowed */
    if (value != NULL) {
        ++*found;
        return value;
    }
    if (PyErr_Occurred()) {
        PyErr_Clear();
        return NULL;
    }
    value = PyTuple_GET_ITEM(defaults, i);
    return value == Py_None ? NULL : value;
}

/* A number argument read as a double: 1 (`*number` set) for a float, a numpy.float64 or an int that fits, 0
 * where `value` is not of those types, -1 (no exception set) for an int too large for a double (refused: the
 * general path says so). */
static int number_value(PyObject *value, PyTypeObject *float64_type, double *number)
{
    PyTypeObject *kind = Py_TYPE(value);
    if (kind == &PyFloat_Type || kind == float64_type) {
        *number = PyFloat_AS_DOUBLE(value);
        return 1;
    }
    if (kind != &PyLong_Type) {
        return 0;
    }
    double read = PyLong_AsDouble(value);
    if (read == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        return -1;
    }
    *number = read;
    return 1;
}

/* Fill the slots from `values` and run the loop: a new reference to the entry's dict of rows, Py_None
 * (new) where the call is refused, NULL with an exception where the plan is not one or memory fails. */
static PyObject *run(PyObject *plan, PyObject *values)
{
    if (!plan_is_one(plan, values)) {
        return NULL;
    }
    char *busy = PyByteArray_AS_STRING(PyTuple_GET_ITEM(plan, PLAN_BUSY));
    if (busy[0]) {
        Py_RETURN_NONE;
    }
    PyObject *names = PyTuple_GET_ITEM(plan, PLAN_NAMES), *defaults = PyTuple_GET_ITEM(plan, PLAN_DEFAULTS);
    double *numbers = (double *)PyLong_AsVoidPtr(PyTuple_GET_ITEM(plan, PLAN_NUMBERS));
    void **pointers = (void **)PyLong_AsVoidPtr(PyTuple_GET_ITEM(plan, PLAN_POINTERS));
    Py_ssize_t *steps = (Py_ssize_t *)PyLong_AsVoidPtr(PyTuple_GET_ITEM(plan, PLAN_STEPS));
    symlink_packed_function packed = (symlink_packed_function)PyLong_AsVoidPtr(PyTuple_GET_ITEM(plan, PLAN_PACKED));
    Py_ssize_t largest = PyLong_AsSsize_t(PyTuple_GET_ITEM(plan, PLAN_LARGEST));
    PyTypeObject *array_type = (PyTypeObject *)PyTuple_GET_ITEM(plan, PLAN_ARRAY_TYPE);
    PyTypeObject *float64_type = (PyTypeObject *)PyTuple_GET_ITEM(plan, PLAN_FLOAT64_TYPE);
    if (PyErr_Occurred()) {
        return NULL;
    }
    if (!numbers || !pointers || !steps || !packed) {
        PyErr_SetString(PyExc_TypeError, "symlink_call: a plan address is null");
        return NULL;
    }
    Py_ssize_t count = PyTuple_GET_SIZE(names), found, length;
    PyObject *made = NULL, *entry = NULL;
    busy[0] = 1;
    if (!keys_are_str(values)) {
        goto refuse;
    }
walk:
    found = 0;
    length = 0;
    for (Py_ssize_t i = 0; i < count; ++i) {
        PyObject *value = argument_value(values, names, defaults, i, &found);
        if (value == NULL) {
            goto refuse;  /* a missing argument: the general path names it */
        }
        int number = number_value(value, float64_type, &numbers[i]);
        if (number < 0) {
            goto refuse;  /* too large for a double: the general path says so */
        }
        if (number) {
            pointers[i] = &numbers[i];
            steps[i] = 0;
        } else if (Py_TYPE(value) == array_type) {
            Py_buffer view;
            if (PyObject_GetBuffer(value, &view, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) != 0) {
                PyErr_Clear();
                goto refuse;
            }
            Py_ssize_t size = view.ndim == 1 ? view.shape[0] : 0;
            int good = view.ndim == 1 && view.itemsize == 8 && view.format != NULL && strcmp(view.format, "d") == 0
                && size > 0 && size <= largest && (length == 0 || size == length);
            void *data = view.buf;
            PyBuffer_Release(&view);  /* the array stays alive in `values` (or the defaults) during the call */
            if (!good) {
                goto refuse;
            }
            length = size;
            pointers[i] = data;
            steps[i] = 1;
        } else {
            goto refuse;
        }
    }
    if (found != PyDict_GET_SIZE(values) || length == 0) {
        goto refuse;  /* an unknown argument, or numbers only (shape-() results): the general path */
    }
    if (made != NULL) {  /* the walk after make(): its block, if the arguments are still of its length */
        if (PyLong_AsSsize_t(PyTuple_GET_ITEM(made, ENTRY_LENGTH)) != length) {
            PyErr_Clear();
            goto refuse;
        }
        entry = made;
    } else {
        PyObject *kept = PyTuple_GET_ITEM(plan, PLAN_KEPT);
        Py_ssize_t keep = PyLong_AsSsize_t(PyTuple_GET_ITEM(plan, PLAN_KEEP));
        Py_ssize_t most = PyLong_AsSsize_t(PyTuple_GET_ITEM(plan, PLAN_KEEP_MOST));
        Py_ssize_t bytes = PyLong_AsSsize_t(PyTuple_GET_ITEM(plan, PLAN_KEEP_BYTES));
        if (keep < 1 || most < 1 || bytes < 0) {
            if (!PyErr_Occurred()) {
                PyErr_SetString(PyExc_TypeError, "symlink_call: a plan keeps no block");
            }
            goto fail;
        }
        entry = free_entry(kept, length, keep, keep);  /* the first `keep`: a bounded look, however many are held */
        if (entry != NULL) {
            drop_one_unused(kept, keep);  /* (entry is last now, and held by the list) */
        } else {
            made = new_entry(plan, kept, most_kept(PyTuple_GET_ITEM(plan, PLAN_LAYOUT), length, keep, most, bytes),
                             length);
            if (made == NULL) {
                goto fail;
            }
            if (!entry_is_one(made)) {
                goto fail;
            }
            /* (The allocation may have run the garbage collector, so Python code: the pointers are taken again.) */
            goto walk;
        }
    }
    struct symlink_call_struct call = {(size_t)length, (void *const *)pointers, (const ptrdiff_t *)steps, NULL, NULL};
    if (entry_rows(entry, PyTuple_GET_ITEM(plan, PLAN_LAYOUT), length, &call.numbers, &call.flags) < 0) {
        goto fail;
    }
    int status = packed(&call);
    PyObject *rows = PyTuple_GET_ITEM(entry, ENTRY_RESULTS);
    Py_INCREF(rows);
    Py_XDECREF(made);
    busy[0] = 0;
    if (status != 0) {
        Py_DECREF(rows);
        Py_RETURN_NONE;  /* a value the NumPy module would refuse: the general path raises its error */
    }
    return rows;
refuse:
    Py_XDECREF(made);
    busy[0] = 0;
    Py_RETURN_NONE;
fail:
    Py_XDECREF(made);
    busy[0] = 0;
    return NULL;
}

static PyObject *symlink_call_call(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 2) {
        PyErr_SetString(PyExc_TypeError, "call(plan, values) takes two arguments");
        return NULL;
    }
    PyObject *rows = run(args[0], args[1]);
    if (rows == NULL || rows == Py_None) {
        return rows;
    }
    PyObject *copy = PyDict_Copy(rows);
    Py_DECREF(rows);
    return copy;
}

/* A new `type` (a dict subtype, made without __init__) holding `rows`, with the record's attributes: units,
 * inputs (a copy of `values`) and input units; NULL with an exception where memory fails. */
static PyObject *record(PyTypeObject *type, PyObject *rows, PyObject *values, PyObject *units, PyObject *input_units)
{
    PyObject *made = type->tp_new(type, empty_tuple, NULL);  /* dict's own __new__: no __init__, no checks */
    PyObject *units_copy = NULL, *inputs = NULL, *input_units_copy = NULL;
    if (made == NULL || PyDict_Update(made, rows) < 0) {
        goto fail;
    }
    units_copy = PyDict_Copy(units);
    inputs = PyDict_Copy(values);
    input_units_copy = PyDict_Copy(input_units);
    if (units_copy == NULL || inputs == NULL || input_units_copy == NULL
            || PyObject_SetAttr(made, name_units, units_copy) < 0 || PyObject_SetAttr(made, name_inputs, inputs) < 0
            || PyObject_SetAttr(made, name_input_units, input_units_copy) < 0) {
        goto fail;
    }
    Py_DECREF(units_copy);
    Py_DECREF(inputs);
    Py_DECREF(input_units_copy);
    return made;
fail:
    Py_XDECREF(made);
    Py_XDECREF(units_copy);
    Py_XDECREF(inputs);
    Py_XDECREF(input_units_copy);
    return NULL;
}

/* Whether [low, high) meets [other_low, other_high). */
static int overlap(char *low, char *high, char *other_low, char *other_high)
{
    return low < other_high && other_low < high;
}

/* large(plan, values, out, Results, units, input_units): a call of any length through <name>_into, into the
 * caller's arrays `out` (a dict by result name) or into a kept block nobody holds (else a new one from
 * make_large); a Results, or None where anything does not qualify or an argument is refused (the general
 * path then answers, with its errors). The slots are this call's own; the GIL is released during a large
 * loop, the arrays' buffers and the block held meanwhile. */
static PyObject *symlink_call_large(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 6 || !PyType_Check(args[3]) || !PyType_IsSubtype((PyTypeObject *)args[3], &PyDict_Type)
            || !PyDict_Check(args[4]) || !PyDict_Check(args[5])) {
        PyErr_SetString(PyExc_TypeError, "large(plan, values, out, dict subtype, units, input units) expected");
        return NULL;
    }
    PyObject *plan = args[0], *values = args[1], *out = args[2];
    if (!plan_is_one(plan, values)) {
        return NULL;
    }
    if (out != Py_None && !PyDict_CheckExact(out)) {
        Py_RETURN_NONE;
    }
    PyObject *names = PyTuple_GET_ITEM(plan, PLAN_NAMES), *defaults = PyTuple_GET_ITEM(plan, PLAN_DEFAULTS);
    PyObject *results = PyTuple_GET_ITEM(plan, PLAN_RESULTS), *layout = PyTuple_GET_ITEM(plan, PLAN_LAYOUT);
    PyTypeObject *array_type = (PyTypeObject *)PyTuple_GET_ITEM(plan, PLAN_ARRAY_TYPE);
    PyTypeObject *float64_type = (PyTypeObject *)PyTuple_GET_ITEM(plan, PLAN_FLOAT64_TYPE);
    symlink_into_function into = (symlink_into_function)PyLong_AsVoidPtr(PyTuple_GET_ITEM(plan, PLAN_INTO));
    if (PyErr_Occurred()) {
        return NULL;
    }
    if (into == NULL) {
        Py_RETURN_NONE;  /* a library without <name>_into */
    }
    const char *kinds = PyBytes_AS_STRING(layout);
    Py_ssize_t count = PyTuple_GET_SIZE(names), outputs_count = PyTuple_GET_SIZE(results);
    Py_ssize_t slots = count + outputs_count, held = 0, found = 0, length = 0;
    /* One allocation: the numbers, pointers, steps, argument extents, output pointers, the buffers held. */
    char *memory = PyMem_Calloc(1, (size_t)(count * (8 + sizeof(void *) + sizeof(ptrdiff_t) + 2 * sizeof(char *))
                                              + outputs_count * sizeof(void *) + slots * sizeof(Py_buffer)) + 1);
    if (memory == NULL) {
        return PyErr_NoMemory();
    }
    double *numbers = (double *)memory;
    void **pointers = (void **)(numbers + count);
    ptrdiff_t *steps = (ptrdiff_t *)(pointers + count);
    char **extents = (char **)(steps + count);  /* each argument array's first byte and the one past its last */
    void **outputs = (void **)(extents + 2 * count);
    Py_buffer *views = (Py_buffer *)(outputs + outputs_count);
    PyObject *result = NULL, *entry = NULL, *block = NULL;
    if (!keys_are_str(values)) {
        goto refuse;
    }
    for (Py_ssize_t i = 0; i < count; ++i) {
        PyObject *value = argument_value(values, names, defaults, i, &found);
        if (value == NULL) {
            goto refuse;
        }
        int number = number_value(value, float64_type, &numbers[i]);
        if (number < 0) {
            goto refuse;
        }
        if (number) {
            pointers[i] = &numbers[i];
            steps[i] = 0;
        } else if (Py_TYPE(value) == array_type) {
            Py_buffer *view = &views[held];
            if (PyObject_GetBuffer(value, view, PyBUF_STRIDES | PyBUF_FORMAT) != 0) {
                PyErr_Clear();
                goto refuse;
            }
            ++held;  /* released at the end: the array cannot be resized or freed while the loop reads it */
            Py_ssize_t size = view->ndim == 1 ? view->shape[0] : 0;
            if (view->ndim != 1 || view->itemsize != 8 || view->format == NULL || strcmp(view->format, "d") != 0
                    || size < 1 || view->strides[0] % 8 != 0 || (size != 1 && length != 0 && size != length)) {
                goto refuse;
            }
            if (size != 1) {
                length = size;
            }
            char *first = (char *)view->buf, *last = first + view->strides[0] * (size - 1);
            pointers[i] = view->buf;
            steps[i] = size == 1 ? 0 : view->strides[0] / 8;
            extents[2 * i] = first < last ? first : last;
            extents[2 * i + 1] = (first < last ? last : first) + 8;
        } else {
            goto refuse;
        }
    }
    if (found != PyDict_GET_SIZE(values) || length == 0) {
        goto refuse;  /* an unknown argument, or no array longer than one value: the general path */
    }
    if (out != Py_None) {
        if (PyDict_GET_SIZE(out) != outputs_count) {
            goto refuse;
        }
        for (Py_ssize_t k = 0; k < outputs_count; ++k) {
            PyObject *array = PyDict_GetItemWithError(out, PyTuple_GET_ITEM(results, k));
            if (array == NULL || Py_TYPE(array) != array_type) {
                PyErr_Clear();
                goto refuse;
            }
            Py_buffer *view = &views[held];
            if (PyObject_GetBuffer(array, view, PyBUF_WRITABLE | PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) != 0) {
                PyErr_Clear();
                goto refuse;
            }
            ++held;
            const char *format = kinds[k] ? "?" : "d";
            if (view->ndim != 1 || view->shape[0] != length || view->itemsize != (kinds[k] ? 1 : 8)
                    || view->format == NULL || strcmp(view->format, format) != 0) {
                goto refuse;
            }
            char *low = (char *)view->buf, *high = low + view->len;
            for (Py_ssize_t j = 0; j < k; ++j) {
                if (overlap(low, high, (char *)outputs[j], (char *)outputs[j] + (kinds[j] ? 1 : 8) * length)) {
                    goto refuse;
                }
            }
            for (Py_ssize_t i = 0; i < count; ++i) {
                if (pointers[i] != &numbers[i] && overlap(low, high, extents[2 * i], extents[2 * i + 1])) {
                    goto refuse;
                }
            }
            outputs[k] = view->buf;
        }
    } else {
        PyObject *kept_large = PyTuple_GET_ITEM(plan, PLAN_KEPT_LARGE);
        Py_ssize_t keep_large = PyLong_AsSsize_t(PyTuple_GET_ITEM(plan, PLAN_KEEP_LARGE));
        if (keep_large < 1) {
            if (!PyErr_Occurred()) {
                PyErr_SetString(PyExc_TypeError, "symlink_call: a plan keeps no large block");
            }
            goto fail;
        }
        entry = free_entry(kept_large, length, PY_SSIZE_T_MAX, keep_large);
        int reused = entry != NULL;
        if (reused) {
            Py_INCREF(entry);
        } else {
            if (PyErr_Occurred()) {
                goto fail;
            }
            PyObject *size = PyLong_FromSsize_t(length);
            if (size == NULL) {
                goto fail;
            }
            entry = PyObject_CallOneArg(PyTuple_GET_ITEM(plan, PLAN_MAKE_LARGE), size);  /* a memory check first */
            Py_DECREF(size);
            if (entry == NULL || !entry_is_one(entry)) {
                goto fail;
            }
            if (PyLong_AsSsize_t(PyTuple_GET_ITEM(entry, ENTRY_LENGTH)) != length) {
                PyErr_Clear();
                goto refuse;
            }
        }
        /* Held (one more reference to the block) until the Results holds its rows: never free meanwhile. */
        block = PyTuple_GET_ITEM(PyTuple_GET_ITEM(entry, ENTRY_OBJECTS), 0);
        Py_INCREF(block);
        if (reused) {  /* (after the block is held: this entry is not free, whatever the dropping runs) */
            drop_one_unused(kept_large, keep_large);  /* back by one a call once callers hold fewer results */
        }
        double *number_rows;
        unsigned char *flag_rows;
        if (entry_rows(entry, layout, length, &number_rows, &flag_rows) < 0) {
            goto fail;
        }
        Py_ssize_t number_row = 0, flag_row = 0;
        for (Py_ssize_t k = 0; k < outputs_count; ++k) {
            outputs[k] = kinds[k] ? (void *)(flag_rows + length * flag_row++) : (void *)(number_rows + length * number_row++);
        }
    }
    struct symlink_call_struct call = {(size_t)length, (void *const *)pointers, steps, NULL, NULL};
    int status;
    if (length > SYMLINK_RELEASE_GIL) {
        Py_BEGIN_ALLOW_THREADS
        status = into(&call, (void *const *)outputs);
        Py_END_ALLOW_THREADS
    } else {
        status = into(&call, (void *const *)outputs);
    }
    if (status != 0) {
        goto refuse;  /* a value the NumPy module would refuse: the general path raises its error */
    }
    if (out != Py_None) {
        PyObject *rows = PyDict_New();
        if (rows == NULL) {
            goto fail;
        }
        for (Py_ssize_t k = 0; k < outputs_count; ++k) {  /* in the order of the results, as the general path */
            PyObject *name = PyTuple_GET_ITEM(results, k);
            PyObject *array = PyDict_GetItemWithError(out, name);
            if (array == NULL || PyDict_SetItem(rows, name, array) < 0) {
                if (!PyErr_Occurred()) {
                    PyErr_SetString(PyExc_RuntimeError, "symlink_call: out changed during the call");
                }
                Py_DECREF(rows);
                goto fail;
            }
        }
        result = record((PyTypeObject *)args[3], rows, values, args[4], args[5]);
        Py_DECREF(rows);
    } else {
        result = record((PyTypeObject *)args[3], PyTuple_GET_ITEM(entry, ENTRY_RESULTS), values, args[4], args[5]);
    }
    goto done;
refuse:
    result = Py_None;
    Py_INCREF(result);
    goto done;
fail:
    result = NULL;
done:
    for (Py_ssize_t k = 0; k < held; ++k) {
        PyBuffer_Release(&views[k]);
    }
    Py_XDECREF(block);
    Py_XDECREF(entry);
    PyMem_Free(memory);
    return result;
}

static PyObject *symlink_call_results(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 5 || !PyType_Check(args[2]) || !PyType_IsSubtype((PyTypeObject *)args[2], &PyDict_Type)
            || !PyDict_Check(args[3]) || !PyDict_Check(args[4])) {
        PyErr_SetString(PyExc_TypeError, "results(plan, values, dict subtype, units, input units) expected");
        return NULL;
    }
    PyObject *rows = run(args[0], args[1]);
    if (rows == NULL || rows == Py_None) {
        return rows;
    }
    PyObject *made = record((PyTypeObject *)args[2], rows, args[1], args[3], args[4]);
    Py_DECREF(rows);
    return made;
}

static PyObject *symlink_call_references(PyObject *module, PyObject *objects)
{
    if (!PyTuple_CheckExact(objects)) {
        PyErr_SetString(PyExc_TypeError, "references(objects) takes a tuple");
        return NULL;
    }
    Py_ssize_t sum = 0;
    for (Py_ssize_t k = 0; k < PyTuple_GET_SIZE(objects); ++k) {
        sum += Py_REFCNT(PyTuple_GET_ITEM(objects, k));
    }
    return PyLong_FromSsize_t(sum);
}

static PyMethodDef methods[] = {
    {"call", (PyCFunction)(void (*)(void))symlink_call_call, METH_FASTCALL,
     "call(plan, values): a new dict of the output rows, or None where the call is refused."},
    {"results", (PyCFunction)(void (*)(void))symlink_call_results, METH_FASTCALL,
     "results(plan, values, Results, units, input_units): a Results, or None where the call is refused."},
    {"large", (PyCFunction)(void (*)(void))symlink_call_large, METH_FASTCALL,
     "large(plan, values, out, Results, units, input_units): a call of any length through <name>_into, "
     "into out or a kept block; a Results, or None where the call is refused."},
    {"references", symlink_call_references, METH_O,
     "references(objects): the sum of the reference counts of a tuple's items."},
    {NULL, NULL, 0, NULL}
};

static struct PyModuleDef definition = {PyModuleDef_HEAD_INIT, "@MODULE@", "symlink's small-call extension.", -1,
                                        methods, NULL, NULL, NULL, NULL};

PyMODINIT_FUNC PyInit_@MODULE@(void)
{
    import_array();  /* NumPy's C API (returns NULL with an ImportError where it fails) */
    if (empty_tuple == NULL) {
        empty_tuple = PyTuple_New(0);
        name_units = PyUnicode_InternFromString("units");
        name_inputs = PyUnicode_InternFromString("inputs");
        name_input_units = PyUnicode_InternFromString("input_units");
        if (empty_tuple == NULL || name_units == NULL || name_inputs == NULL || name_input_units == NULL) {
            return NULL;
        }
    }
    return PyModule_Create(&definition);
}
"""
