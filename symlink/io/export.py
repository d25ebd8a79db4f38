"""Exports: a linkage's solvers as NumPy, C, MATLAB/Octave, JavaScript or LaTeX files (``symlink export``, ``symlink derive``).

By default each format gets the output sets an engineer reaches for: the
positions of the unknowns, then with velocities, then with accelerations and
the extras, and the joints' coordinates.  ``--outputs`` asks for one set
instead.  The texts are derived once and then read from symlink's cache
(:mod:`symlink.numeric.cache`), and written atomically only after all of them exist.

>>> sets = output_sets(catalog_linkage("fourbar"))
>>> [(name, outputs) for name, outputs, _ in sets][:2]
[('positions', ['coupler', 'rocker']), ('velocities', ['coupler', 'rocker', 'coupler_speed', 'rocker_speed'])]
"""
from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Sequence

from ..numeric import cache
from ..mechanism.catalog import CATALOG
from ..codegen import PRINTERS, printer
from ..symbolic.linkage import Linkage
from ..symbolic.outputs import output_sets as standard_output_sets
from .scene import catalog_linkage
from ..symbolic.seed_forms import FORMS

__all__ = ["FORMATS", "output_sets", "export_texts", "export", "write_latex"]

FORMATS = tuple(PRINTERS)


#: What each standard output set holds, for the exported functions' documentation.
SET_DESCRIPTIONS = {"positions": "Positions of the unknowns (angles in rad).",
                    "velocities": "Positions and their rates (per second).",
                    "accelerations": "Positions, rates, accelerations (per second squared) and the extras.",
                    "joints": "Coordinates of the moving joints.",
                    "dynamics": "Positions, rates, accelerations, the driving efforts, joint reactions and shaking "
                                "loads, and the generalised inertia, its slope and the applied generalised force."}


def output_sets(linkage: Linkage) -> list[tuple[str, list[str], str]]:
    """The default ``(name, outputs, description)`` sets: positions, velocities, accelerations, joints."""
    return [(name, outputs, SET_DESCRIPTIONS[name]) for name, outputs in standard_output_sets(linkage)]


def _identifier(name: str) -> str:
    stem = re.sub(r"\W", "_", name)
    return stem if re.match(r"[A-Za-z]", stem) else f"linkage_{stem}"


def export_texts(linkage: Linkage | str, fmt: str, outputs: Sequence[str] | None = None,
                 form: str = "atan2") -> dict[str, str]:
    """File name -> text of ``linkage`` (or a catalog name) in format ``fmt`` (cached; nothing is written).

    ``form`` adds the positions in a seed paper's form to a LaTeX document (:mod:`symlink.symbolic.seed_forms`).

    Parameters
    ----------
    linkage : Linkage or str
        The linkage, or a catalog name.
    fmt : str
        One of :data:`FORMATS`.
    outputs : sequence of str, optional
        The outputs of the solvers (default: the standard output sets).
    form : str, optional
        For LaTeX, a seed paper's form of the positions to add.

    Returns
    -------
    dict of str to str
        Each file's name and text.

    Examples
    --------
    >>> import symlink
    >>> sorted(symlink.export_texts("fourbar", "octave"))
    ['fourbar_accelerations.m', 'fourbar_joints.m', 'fourbar_positions.m', 'fourbar_velocities.m']
    """
    if fmt not in FORMATS:
        raise ValueError(f"unknown export format {fmt!r}; choose one of {', '.join(FORMATS)}")
    if form not in FORMS:
        raise ValueError(f"no form {form!r}; the forms are {', '.join(FORMS)}")
    if form != "atan2" and fmt != "latex":
        raise ValueError(f"--form {form} is a way of writing the equations: it applies to --to latex only "
                         "(generated code always computes the atan2 form)")
    if isinstance(linkage, str):
        linkage = catalog_linkage(linkage)
    name = linkage.name
    if not getattr(linkage, "has_closed_form", True):
        raise ValueError(f"{name} has no closed-form solve plan; only closed forms can be exported")
    if outputs is not None:
        outputs = list(outputs)
        if not outputs:
            raise ValueError(f"--outputs needs at least one output of {name}; it has {', '.join(linkage.output_names())}")
        for output in outputs:
            linkage.output(output)  # ValueError naming the outputs there are
        sets = [("solve", outputs, f"{name}: {', '.join(outputs)}.")]
    else:
        sets = output_sets(linkage)
    stem = _identifier(name)
    wanted = sorted({o for _, names, _ in sets for o in names})
    verb = "export" if name in CATALOG else "derive"
    command = f"symlink {verb} {name} --to {fmt}" + (f" --outputs {','.join(outputs)}" if outputs else "")
    command += f" --form {form}" if form != "atan2" else ""
    kind = "export:" + json.dumps([fmt, stem, sets] + ([form] if form != "atan2" else []))
    build = lambda: json.dumps(_build(linkage, fmt, stem, sets, command, form))  # noqa: E731
    return json.loads(cache.cached_text(cache.cache_key(linkage, wanted, kind), build))


def _build(linkage: Linkage, fmt: str, stem: str, sets, command: str, form: str = "atan2") -> dict[str, str]:
    doc = (CATALOG[linkage.name].__doc__ or "").strip().splitlines() if linkage.name in CATALOG else []
    title = f"{linkage.name}: {doc[0]}" if doc else f"{linkage.name} solver."
    return printer(fmt).export_files(linkage, stem, sets, title, command, form)


def export(linkage: Linkage | str, fmt: str, folder: str | Path, outputs: Sequence[str] | None = None,
           form: str = "atan2") -> list[Path]:
    """Write the export files of ``linkage`` (or a catalog name) into ``folder``, all or none; returns their paths.

    Parameters
    ----------
    linkage : Linkage or str
        The linkage, or a catalog name.
    fmt : str
        One of :data:`FORMATS`: ``"numpy"``, ``"c"``, ``"octave"`` or ``"latex"``.
    folder : str or pathlib.Path
        Where to write (made if missing).
    outputs : sequence of str, optional
        The outputs of the solvers (default: the standard output sets).
    form : str, optional
        For LaTeX, a seed paper's form of the positions to add (default ``"atan2"``: symlink's own only).

    Returns
    -------
    list of pathlib.Path
        The files written.

    Examples
    --------
    >>> import symlink, tempfile
    >>> [path.name for path in symlink.export("fourbar", "c", tempfile.mkdtemp())]
    ['fourbar.h', 'fourbar.c']
    """
    from ..common.files import write_files_atomic
    texts = export_texts(linkage, fmt, outputs, form)
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"--out {folder} exists and is not a folder")
    return write_files_atomic(folder, texts)


def write_latex(linkage: Linkage | str, path: str | Path, title: str | None = None) -> Path:
    """Write the whole derivation of ``linkage`` (or a catalog name) as a LaTeX document at ``path``, atomically.

    The document is :func:`~symlink.codegen.latex.latex_document`'s: the loops, the closure
    equations, the closed forms with their branch signs, the velocities and accelerations.

    Parameters
    ----------
    linkage : Linkage or str
        The linkage, or the name of a catalog linkage.
    path : str or pathlib.Path
        Where to write; the file appears whole or not at all.
    title : str, optional
        The document's title; by default the linkage's name.

    Returns
    -------
    pathlib.Path
        The path written.

    Examples
    --------
    >>> import symlink, tempfile, pathlib
    >>> folder = tempfile.mkdtemp()
    >>> path = symlink.write_latex(symlink.fourbar(), pathlib.Path(folder) / "fourbar.tex", "A four-bar")
    >>> path.read_text().splitlines()[0].endswith("documentclass{article}")
    True
    """
    from ..codegen.latex import latex_document
    from ..common.files import write_atomic
    if isinstance(linkage, str):
        linkage = catalog_linkage(linkage)
    path = Path(path)
    write_atomic(path, latex_document(linkage, title if title is not None else linkage.name))
    return path
