"""What derivation scripts share: the standard solver module of a linkage, and writing generated/.

A script in ``derivations/`` derives a linkage step by step, then hands the
result here: :func:`kinematics_module` writes the NumPy module with
``positions``, ``velocities``, ``accelerations`` (and ``joints``) functions
for some role outputs, and :func:`write_generated` writes every file
atomically.

>>> from symlink.mechanism.catalog import slider_crank
>>> source = kinematics_module(slider_crank(), ["conrod", "slider"], ["C_x"], "Slider-crank.")
>>> [line.split("(")[0] for line in source.splitlines() if line.startswith("def ") and "_" not in line[4]]
['def positions', 'def velocities', 'def accelerations', 'def joints']
>>> "conrod (rad), slider (length)" in source
True
"""
from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence

from ..symbolic.closure import is_angle
from ..codegen.numpy import numpy_module
from ..common.files import write_atomic
from ..symbolic.linkage import Linkage
from ..symbolic.outputs import derivative_outputs, output_sets

__all__ = ["kinematics_module", "write_generated"]


def kinematics_module(linkage: Linkage, roles: Sequence[str], joints: Sequence[str], title: str,
                      regenerate: str = "", joints_doc: str = "Joint positions.") -> str:
    """A NumPy module: positions, velocities and accelerations of the ``roles``, and the ``joints``' x and y.

    Parameters
    ----------
    linkage : Linkage
        A linkage with a closed-form plan.
    roles : sequence of str
        The roles whose positions, speeds and accelerations the module computes.
    joints : sequence of str
        The outputs of the ``joints`` function (``"C_x"``, ``"C_y"``).
    title : str
        The module's docstring.
    regenerate : str, optional
        The command that regenerates it.
    joints_doc : str, optional
        The docstring of its ``joints`` function.

    Returns
    -------
    str
        The module's source, with the functions ``positions``, ``velocities``, ``accelerations`` and ``joints``.

    Examples
    --------
    >>> import math, symlink
    >>> namespace = {}
    >>> exec(symlink.kinematics_module(symlink.fourbar(), ["rocker"], ["C_x", "C_y"], "Four-bar."), namespace)
    >>> result = namespace["positions"](theta=0.0, a=20, b=66, c=56, d=80)
    >>> round(math.degrees(float(result["rocker"])), 2)  # seed 003
    110.74
    """
    speeds, accels = derivative_outputs(linkage, roles)

    def described(names, units):
        angles = [is_angle(linkage, linkage.roles[role]) for role in roles]
        return ", ".join(f"{name} ({units[angle]})" for name, angle in zip(names, angles))

    docs = {"positions": f"Positions: {described(roles, ('length', 'rad'))}.",
            "velocities": f"Positions and speeds: {described(speeds, ('length/s', 'rad/s'))}.",
            "accelerations": f"Positions, speeds and accelerations: {described(accels, ('length/s^2', 'rad/s^2'))}.",
            "joints": joints_doc}
    functions = [(name, linkage.program(outputs), docs[name])
                 for name, outputs in output_sets(linkage, roles, joints, extras=False)]
    return numpy_module(functions, title=title, regenerate=regenerate)


def write_generated(files: Mapping[str, str], folder: str | Path) -> int:
    r"""Write each ``{name: text}`` into ``folder`` atomically, saying so; the exit status of a script (0).

    Parameters
    ----------
    files : mapping of str to str
        Each file's name and text.
    folder : str or pathlib.Path
        The folder to write them into.

    Returns
    -------
    int
        0, the exit status of a derivation script.

    Examples
    --------
    >>> import symlink, tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> symlink.write_generated({"note.txt": "hello\n"}, folder) == 0  # doctest: +ELLIPSIS
    wrote .../note.txt
    True
    >>> (folder / "note.txt").read_text()
    'hello\n'
    """
    for name, text in files.items():
        write_atomic(Path(folder) / name, text)
        print(f"wrote {Path(folder).name}/{name}")
    return 0
