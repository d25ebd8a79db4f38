"""The Grashof class of a four-bar: which link turns fully, decided by the shortest and longest links.

>>> grashof(20, 66, 56, 80).name
'crank-rocker'
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy

from ..codegen.arguments import checked_arguments
from ..common.display import record_html

__all__ = ["Grashof", "GRASHOF_CLASSES", "grashof", "grashof_names"]


#: Grashof classes of a four-bar, by name.
GRASHOF_CLASSES = {
    "crank-rocker": "Grashof, shortest link is the crank: the crank turns fully, the rocker swings",
    "rocker-crank": "Grashof, shortest link is the rocker: the rocker turns fully, the crank only swings",
    "double-crank": "Grashof, shortest link is the ground: crank and rocker both turn fully (drag link)",
    "double-rocker": "Grashof, shortest link is the coupler: crank and rocker both swing, "
                     "the coupler turns fully",
    "change-point": "s + l = p + q: every inversion passes a change point where all links line up",
    "triple-rocker": "non-Grashof (s + l > p + q): no link turns fully relative to another",
}

_LINK_NAMES = ("crank", "coupler", "rocker", "ground")


@dataclass(frozen=True)
class Grashof:
    """A four-bar's Grashof class and the sums it was decided by."""

    _repr_html_ = record_html  # a notebook shows the fields as a table

    name: str
    shortest: str
    longest: str
    shortest_plus_longest: float
    other_two: float

    @property
    def description(self) -> str:
        return GRASHOF_CLASSES[self.name]

    @property
    def is_grashof(self) -> bool:
        """Some link turns fully: ``s + l <= p + q`` (the change point included)."""
        return self.name != "triple-rocker"


def grashof(a: float, b: float, c: float, d: float, tolerance: float = 1e-12) -> Grashof:
    """Grashof class of the four-bar with crank a, coupler b, rocker c and ground d.

    With s and l the shortest and longest links and p, q the others: ``s + l < p + q``
    is Grashof, and then the class depends on where the shortest link is (crank:
    crank-rocker; ground: double-crank; coupler: double-rocker; rocker: rocker-crank).
    ``s + l = p + q`` (within ``tolerance`` times l) is a change point and
    ``s + l > p + q`` a non-Grashof triple rocker.

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths.
    tolerance : float, optional
        Relative to the longest link, how near ``s + l = p + q`` is a change point (default 1e-12).

    Returns
    -------
    Grashof
        The class's name, the shortest and longest links, ``s + l`` and ``p + q``.

    Examples
    --------
    >>> import symlink
    >>> symlink.grashof(20, 66, 56, 80)  # 20 + 80 < 66 + 56, shortest the crank
    Grashof(name='crank-rocker', shortest='crank', longest='ground', shortest_plus_longest=100.0, other_two=122.0)
    >>> symlink.grashof(4, 5, 6, 2).name, symlink.grashof(5, 6, 7, 10).name
    ('double-crank', 'triple-rocker')
    """
    checked_arguments(_LINK_NAMES, (a, b, c, d), lengths=_LINK_NAMES)  # ValueError naming the first bad length
    links = [float(a), float(b), float(c), float(d)]
    shortest = min(range(4), key=links.__getitem__)
    longest = max(range(4), key=links.__getitem__)
    ordered = sorted(links)
    s_l, p_q = ordered[0] + ordered[3], ordered[1] + ordered[2]
    if abs(s_l - p_q) <= tolerance * ordered[3]:
        name = "change-point"
    elif s_l > p_q:
        name = "triple-rocker"
    else:
        name = {"crank": "crank-rocker", "rocker": "rocker-crank", "ground": "double-crank",
                "coupler": "double-rocker"}[_LINK_NAMES[shortest]]
    return Grashof(name, _LINK_NAMES[shortest], _LINK_NAMES[longest], s_l, p_q)


#: The class of a Grashof four-bar by its shortest link (crank, coupler, rocker, ground).
_BY_SHORTEST = ("crank-rocker", "double-rocker", "rocker-crank", "double-crank")


def grashof_names(a: Any, b: Any, c: Any, d: Any, tolerance: float = 1e-12) -> list[str]:
    """The Grashof class names of many four-bars at once (arrays of their lengths, broadcast): :func:`grashof`'s
    ``name`` of each, decided alike, without a Python call a four-bar (a sweep classifies every design).

    >>> grashof_names([4.0, 5.0, 20.0, 1.0], [5.0, 6.0, 66.0, 2.0], [6.0, 7.0, 56.0, 2.0], [2.0, 10.0, 80.0, 1.0])
    ['double-crank', 'triple-rocker', 'crank-rocker', 'change-point']
    """
    arrays = numpy.broadcast_arrays(*(numpy.asarray(x, dtype=float) for x in (a, b, c, d)))
    checked_arguments(_LINK_NAMES, arrays, lengths=_LINK_NAMES)  # ValueError naming the first length that is not one
    links = numpy.stack([x.ravel() for x in arrays], axis=1)
    shortest = links.argmin(axis=1)  # the first of equal shortest links, as min() finds it
    ordered = numpy.sort(links, axis=1)
    s_l, p_q = ordered[:, 0] + ordered[:, 3], ordered[:, 1] + ordered[:, 2]
    names = numpy.array(_BY_SHORTEST, dtype=object)[shortest]
    names[s_l > p_q] = "triple-rocker"
    names[numpy.abs(s_l - p_q) <= tolerance * ordered[:, 3]] = "change-point"
    return names.tolist()
