"""Gruebler/Kutzbach mobility of any linkage, from the bodies and joints its loops and points make.

:class:`Mobility` is plain data (a cached analysis rebuilds it without SymPy); counting a linkage's
bodies and joints (:func:`degrees_of_freedom`) imports the symbolic layer.

>>> from symlink.mechanism.catalog import jansen
>>> degrees_of_freedom(jansen()).dof
1
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..common.display import record_html

if TYPE_CHECKING:
    from ..symbolic.linkage import Linkage

__all__ = ["Mobility", "degrees_of_freedom"]


@dataclass(frozen=True)
class Mobility:
    """Links and joints of a planar linkage, and its Gruebler/Kutzbach mobility.

    ``links`` counts the ground; every joint is a one-freedom pair (revolute or
    prismatic), so ``dof = 3 (links - 1) - 2 (revolute + prismatic)``.

    Parameters
    ----------
    links : int
        The links, the ground counted.
    revolute : int
        The revolute joints (a pin joining k links counts k - 1).
    prismatic : int
        The prismatic joints.

    Examples
    --------
    >>> import symlink
    >>> symlink.Mobility(links=4, revolute=4, prismatic=0).dof  # the four-bar: 3 * 3 - 2 * 4
    1
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    links: int
    revolute: int
    prismatic: int

    @property
    def joints(self) -> int:
        return self.revolute + self.prismatic

    @property
    def dof(self) -> int:
        return 3 * (self.links - 1) - 2 * self.joints


def degrees_of_freedom(linkage: Linkage) -> Mobility:
    """Gruebler/Kutzbach mobility of ``linkage``: ``3 (n - 1) - 2 j1 - j2`` over its bodies and joints.

    The bodies and joints are those :func:`symlink.mechanism.bodies.mechanism` derives
    from the loops and points (a pin joining k bodies counts as k - 1 joints;
    a slider on its guide is one prismatic joint).

    Parameters
    ----------
    linkage : Linkage
        Any linkage.

    Returns
    -------
    Mobility
        Its links (the ground counted), revolute and prismatic joints, and ``dof``.

    Examples
    --------
    >>> import symlink
    >>> symlink.degrees_of_freedom(symlink.fourbar()).dof
    1
    >>> symlink.degrees_of_freedom(symlink.watt2())  # 3 (6 - 1) - 2 * 7 = 1
    Mobility(links=6, revolute=7, prismatic=0)
    """
    from .bodies import PRISMATIC, mechanism  # the symbolic layer: imported with the first linkage counted
    found = mechanism(linkage)
    prismatic = sum(joint.kind == PRISMATIC for joint in found.joints)
    return Mobility(len(found.bodies), found.one_freedom_joints - prismatic, prismatic)
