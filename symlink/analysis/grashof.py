"""The Grashof class of a four-bar: which link turns fully, decided by the shortest and longest links.

>>> grashof(20, 66, 56, 80).name
'crank-rocker'
"""
from __future__ import annotations

from dataclasses import dataclass

from ..display import record_html
from ..solver import check_lengths

__all__ = ["Grashof", "GRASHOF_CLASSES", "grashof"]


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

    >>> grashof(4, 5, 6, 2).name, grashof(5, 6, 7, 10).name
    ('double-crank', 'triple-rocker')
    """
    check_lengths(crank=a, coupler=b, rocker=c, ground=d)
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
