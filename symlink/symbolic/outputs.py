"""The standard output sets of a linkage, defined once: positions, velocities, accelerations, moving joints.

An unknown is named by its role where it has one (``rocker``), else by its
coordinate (``mu``); its rate and acceleration outputs are ``rocker_speed``
and ``rocker_accel`` (``mudot``, ``muddot`` without a role).  Exports,
derivation scripts and the table commands all take their sets from here.

>>> from symlink.mechanism.catalog import fourbar
>>> [(name, outputs) for name, outputs in output_sets(fourbar())][:2]
[('positions', ['coupler', 'rocker']), ('velocities', ['coupler', 'rocker', 'coupler_speed', 'rocker_speed'])]
>>> moving_joints(fourbar())
['B_x', 'B_y', 'C_x', 'C_y']
"""
from __future__ import annotations

from typing import Sequence

import sympy as sp

from .linkage import ACCEL_SUFFIX, SPEED_SUFFIX, Linkage
from .vectors import acceleration, rate

__all__ = ["label", "derivative_outputs", "moving_joints", "output_sets", "table_outputs"]


def label(linkage: Linkage, q: sp.Symbol) -> str:
    """A coordinate's name for people: its role, else its own name."""
    return next((role for role, symbol in linkage.roles.items() if symbol == q), q.name)


def derivative_outputs(linkage: Linkage, names: Sequence[str]) -> tuple[list[str], list[str]]:
    """The rate and acceleration outputs of the position outputs ``names`` (roles or coordinates)."""
    speeds, accels = [], []
    for name in names:
        if name in linkage.roles:
            speeds.append(name + SPEED_SUFFIX)
            accels.append(name + ACCEL_SUFFIX)
        else:
            q = next(q for q in linkage.coordinates if q.name == name)
            speeds.append(rate(q).name)
            accels.append(acceleration(q).name)
    return speeds, accels


def moving_joints(linkage: Linkage) -> list[str]:
    """``P_x``, ``P_y`` of every named point that moves (depends on a coordinate)."""
    coordinates = set(linkage.coordinates)
    return [f"{point}_{axis}" for point in linkage.points for axis in "xy"
            if linkage.point(point)[axis == "y"].free_symbols & coordinates]


def output_sets(linkage: Linkage, unknowns: Sequence[str] | None = None, joints: Sequence[str] | None = None,
                extras: bool = True) -> list[tuple[str, list[str]]]:
    """``(name, outputs)``: positions, velocities, accelerations (with the extras) and joints.

    ``unknowns`` default to every unknown by :func:`label`; ``joints`` to the
    :func:`moving_joints` (the set is left out where there are none).
    """
    positions = list(unknowns) if unknowns is not None else [label(linkage, q) for q in linkage.unknowns]
    speeds, accels = derivative_outputs(linkage, positions)
    joints = moving_joints(linkage) if joints is None else list(joints)
    dynamic = list(getattr(linkage, "dynamic_outputs", ()))
    kinematic_extras = [name for name in linkage.extras if name not in dynamic] if extras else []
    sets = [("positions", positions), ("velocities", positions + speeds),
            ("accelerations", positions + speeds + accels + kinematic_extras)]
    sets += [("joints", joints)] if joints else []
    return sets + ([("dynamics", positions + speeds + accels + dynamic)] if dynamic else [])


def table_outputs(linkage: Linkage) -> dict[str, str]:
    """The columns of a linkage's table and the outputs behind them: unknowns, their speeds, their accelerations."""
    names = [label(linkage, q) for q in linkage.unknowns]
    columns = dict(zip(names, (q.name for q in linkage.unknowns)))
    columns.update({name + SPEED_SUFFIX: rate(q).name for name, q in zip(names, linkage.unknowns)})
    columns.update({name + ACCEL_SUFFIX: acceleration(q).name for name, q in zip(names, linkage.unknowns)})
    columns.update({name: name for name in getattr(linkage, "force_outputs", ())})  # a linkage with mass properties
    return columns
