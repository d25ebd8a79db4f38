"""Generated C cut into translation units, to be compiled apart (in parallel) and linked into one library.

:func:`symlink.codegen.c.c_library` marks where a large program's pieces begin (:data:`UNIT_MARK`); the
compiled backend (:mod:`symlink.numeric.compiled_library`) cuts the source there when it builds.  Plain text
work, without SymPy: a warm process that builds a library from a cached C source imports no printer.
"""
from __future__ import annotations

__all__ = ["UNIT_MARK", "translation_units"]

#: The line between translation units in a source of pieces: what precedes the first is common to all.
UNIT_MARK = "/* symlink: translation unit */"


def translation_units(source: str) -> list[str]:
    r"""The C source cut where :func:`symlink.codegen.c.c_library` marks it (:data:`UNIT_MARK`): each unit the
    common part and one piece or function; ``[source]`` if unmarked.

    >>> translation_units("common\n" + UNIT_MARK + "\nf\n" + UNIT_MARK + "\ng\n")
    ['common\n\nf\n', 'common\n\ng\n']
    >>> translation_units("int f(void);\n")
    ['int f(void);\n']
    """
    common, *units = source.split(UNIT_MARK + "\n")
    return [common + "\n" + unit for unit in units] if units else [source]
