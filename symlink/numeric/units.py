"""Units of a linkage's arguments and outputs, and pint quantities converted to them.

symlink computes with plain numbers: angles in radians, lengths in any one
unit, rates per second (rad/s, length/s) and accelerations per second
squared.  :func:`output_units` names the unit of each output; 
:func:`plain_values` turns `pint <https://pint.readthedocs.io>`_ quantities
given as arguments into those plain numbers, consistently:

* angles (inputs and parameters that turn a vector) to radians, their rates
  to rad/s and accelerations to rad/s^2 (plain numbers are taken as radians);
* lengths to the unit of the first length given as a quantity, their rates
  and accelerations to that unit per second (squared).  Lengths are either all
  quantities or all plain numbers: a mix is refused (``ValueError``), since a
  plain number's unit cannot be known;
* a quantity of the wrong dimension (a length in seconds) is refused, and so is
  a quantity for a branch sign.

pint is never imported here: quantities are recognised by their attributes.

>>> from symlink.mechanism.catalog import fourbar
>>> plain, length_unit = plain_values(fourbar(), {"theta": 0.5, "a": 20.0, "b": 66.0})
>>> plain["a"], length_unit
(20.0, None)
>>> output_units(fourbar(), ["rocker", "rocker_speed", "C_x", "assembled"], "mm")
{'rocker': 'rad', 'rocker_speed': 'rad/s', 'C_x': 'mm', 'assembled': ''}
"""
from __future__ import annotations

from typing import Any, Mapping, Sequence

import sympy as sp

from ..symbolic.closure import is_angle
from ..symbolic.linkage import ACCEL_SUFFIX, SPEED_SUFFIX, Linkage, is_branch_name
from ..symbolic.sensitivity import split_sensitivity_name
from ..symbolic.vectors import acceleration, rate

__all__ = ["is_quantity", "plain_values", "output_units", "argument_units", "ANY_LENGTH", "parameter_kinds",
           "PARAMETER_KINDS", "PLACEMENT_NAMES"]

#: The name of the length unit where lengths were given as plain numbers.
ANY_LENGTH = "length"


#: The kinds of a linkage's parameter (:func:`parameter_kinds`): a part's length, a fixed angle, where the whole
#: linkage stands (not a part's dimension), and anything else (a mass, an inertia, a held speed).
PARAMETER_KINDS = ("length", "angle", "placement", "other")
#: The parameters that place a synthesised design in the plane (:func:`symlink.synthesis.placement.placed_design`):
#: the shift and the turn of all its points.
PLACEMENT_NAMES = ("place_x", "place_y", "place_angle")


def _shifts_everything(linkage: Linkage, symbol: sp.Symbol, equations: Sequence[sp.Expr]) -> bool:
    """Whether ``symbol`` moves the whole linkage without changing it: it is in no loop's closure and every
    point moves by the same constant step with it (the drawing's ``x_A``, a design's ``place_x``)."""
    if len(linkage.points) < 2 or any(symbol in e.free_symbols for e in equations):
        return False
    steps = set()
    for name in linkage.points:
        x, y = linkage.point(name)
        step = (sp.simplify(sp.diff(x, symbol)), sp.simplify(sp.diff(y, symbol)))
        if step[0].free_symbols or step[1].free_symbols:
            return False
        steps.add(step)
    return len(steps) == 1 and steps != {(0, 0)}


def parameter_kinds(linkage: Linkage) -> dict[str, str]:
    """Each parameter's kind (:data:`PARAMETER_KINDS`): ``"angle"`` if it turns a vector (of a loop or of a point),
    ``"placement"`` if it only says where the linkage stands (it moves every point alike and closes every loop
    alike: a drawing's first ground pivot ``x_A, y_A``, a placed design's :data:`PLACEMENT_NAMES`), ``"length"``
    if it is in a vector's length, ``"other"`` if in none (a mass).

    One rule for every command: a tolerance given to every length (``--tolerance``) goes to the lengths only,
    angles are read in the chosen unit, placements are toleranced only when named.

    >>> from symlink.mechanism.joints import from_joints
    >>> drawn = from_joints({"ground": ["A", "D"], "crank": ["A", "B"], "coupler": ["B", "C", "P"],
    ...                      "rocker": ["D", "C"]}, {"A": (1, 2), "B": (1, 4), "C": (6, 5), "D": (8, 2),
    ...                      "P": (4, 8)}, driver="A")
    >>> parameter_kinds(drawn.linkage)
    {'AB': 'length', 'BC': 'length', 'DC': 'length', 'AD': 'length', 'BP': 'length', 'alpha_AD': 'angle', \
'alpha_BP': 'angle', 'x_A': 'placement', 'y_A': 'placement'}
    """
    equations = [e for loop in linkage.loops for e in loop.equations()]
    vectors = [v for loop in linkage.loops for _, v in loop.terms]
    vectors += [v for sum_ in linkage.points.values() if sum_ is not None for _, v in sum_.as_sum().terms]
    in_lengths = set().union(*(v.length.free_symbols for v in vectors)) if vectors else set()
    kinds = {}
    for symbol in linkage.parameters:
        if is_angle(linkage, symbol):
            kinds[symbol.name] = "placement" if symbol.name in PLACEMENT_NAMES else "angle"
        elif symbol in in_lengths:
            kinds[symbol.name] = ("placement" if symbol.name in PLACEMENT_NAMES
                                  or _shifts_everything(linkage, symbol, equations) else "length")
        else:
            kinds[symbol.name] = "other"
    return kinds


def is_quantity(value: object) -> bool:
    """Whether ``value`` is a pint quantity (a magnitude with units), recognised without importing pint."""
    return all(hasattr(value, attribute) for attribute in ("magnitude", "units", "to", "dimensionality"))


def _angles(linkage: Linkage) -> set[sp.Symbol]:
    """The symbols that are angles: those that turn a vector of a loop or of a point."""
    angles = {s for s in linkage.inputs + linkage.unknowns + linkage.parameters if is_angle(linkage, s)}
    for name in linkage.points:
        for expression in linkage.point(name):
            for trig in expression.atoms(sp.cos, sp.sin):
                angles |= trig.free_symbols
    return angles


def _is_angle_function(expression: sp.Expr) -> bool:
    """Whether an extra output is an angle by its form: an inverse trigonometric function (or its size or
    negative), as the four-bar's transmission angle ``|atan2(sin(beta - phi), cos(beta - phi))|`` is.

    >>> beta, phi = sp.symbols("beta phi")
    >>> _is_angle_function(sp.Abs(sp.atan2(sp.sin(beta - phi), sp.cos(beta - phi)))), _is_angle_function(beta * phi)
    (True, False)
    """
    while isinstance(expression, sp.Abs) or (isinstance(expression, sp.Mul) and expression.args[0] == -1
                                             and len(expression.args) == 2):
        expression = expression.args[-1] if isinstance(expression, sp.Mul) else expression.args[0]
    return isinstance(expression, (sp.atan2, sp.atan, sp.asin, sp.acos))


def _argument_kinds(linkage: Linkage) -> dict[str, tuple[str, int]]:
    """``{argument name: ("angle" or "length", order of time derivative)}`` for the linkage's arguments."""
    angles = _angles(linkage)
    kinds = {}
    for symbol in linkage.inputs + linkage.parameters:
        kind = "angle" if symbol in angles else "length"
        kinds[symbol.name] = (kind, 0)
        kinds[rate(symbol).name] = (kind, 1)
        kinds[acceleration(symbol).name] = (kind, 2)
    return kinds


def _per_second(unit: str, order: int) -> str:
    return unit if order == 0 else f"{unit}/s" if order == 1 else f"{unit}/s^2"


def plain_values(linkage: Linkage, values: Mapping[str, object]) -> tuple[dict[str, object], str | None]:
    """The values with every pint quantity converted to symlink's units, and the length unit (None: not given).

    See the module's text for the rules.  Values that are not quantities are
    returned as they are.
    """
    if not any(is_quantity(value) for value in values.values()):
        return dict(values), None
    kinds = _argument_kinds(linkage)
    plain: dict[str, object] = {}
    length_unit = None
    lengths = [name for name in values if kinds.get(name, ("", 0))[0] == "length"]
    quantities = [name for name in lengths if is_quantity(values[name])]
    if quantities and len(quantities) < len(lengths):
        numbers = [name for name in lengths if name not in quantities]
        raise ValueError(f"{linkage.name}: {', '.join(quantities)} carry units but {', '.join(numbers)} "
                         "do not; give every length (and length rate) as a quantity, or none")
    if quantities:
        first = next((name for name in quantities if kinds[name][1] == 0), quantities[0])
        quantity: Any = values[first]  # a pint Quantity (pint is an optional extra: not imported here)
        unit = quantity.units
        for _ in range(kinds[first][1]):
            unit = unit * quantity._REGISTRY.second
        if str(unit.dimensionality) != "[length]":
            raise ValueError(f"{first} must be a length{'' if kinds[first][1] == 0 else ' per second'}, "
                             f"got {values[first]}")
        length_unit = str(unit)
    for name, value in values.items():
        if not is_quantity(value):
            plain[name] = value
            continue
        if is_branch_name(name) or name not in kinds:
            raise ValueError(f"{name} is a plain number (a branch sign or a setting), not a quantity; got {value}")
        kind, order = kinds[name]
        base = "radian" if kind == "angle" else length_unit
        if base is None:  # unreachable: every length quantity set length_unit above
            raise ValueError(f"{name}: no length unit to convert to")
        target = _per_second(base, order).replace("^", "**")
        given: Any = value
        try:
            plain[name] = given.to(target).magnitude
        except Exception as error:  # pint's DimensionalityError, without importing pint
            raise ValueError(f"{name} must be {'an angle' if kind == 'angle' else 'a length'}"
                             f"{'' if order == 0 else ' per second' if order == 1 else ' per second squared'}, "
                             f"got {value} ({error})") from None
    return plain, length_unit


def argument_units(linkage: Linkage, names: Sequence[str], length_unit: str | None = None) -> dict[str, str]:
    """The unit of each argument of a solver: ``rad`` or the length unit for an input or a parameter, per
    second for their rates, ``''`` for a branch sign or anything else.

    >>> from symlink.mechanism.catalog import slider_crank
    >>> argument_units(slider_crank(), ["theta", "a", "thetadot", "branch"], "mm")
    {'theta': 'rad', 'a': 'mm', 'thetadot': 'rad/s', 'branch': ''}
    """
    kinds = _argument_kinds(linkage)
    length = length_unit or ANY_LENGTH
    return {name: _per_second("rad" if kinds[name][0] == "angle" else length, kinds[name][1])
            if name in kinds else "" for name in names}


def output_units(linkage: Linkage, names: Sequence[str], length_unit: str | None = None) -> dict[str, str]:
    """The unit of each output: ``rad``, ``rad/s``, ``rad/s^2``, the length unit (per second), or ``''``.

    ``''`` for what has no unit (``assembled``) or whose unit symlink cannot
    know (``singular``, and extra outputs defined freely by the linkage, unless
    an extra is an inverse trigonometric function such as the four-bar's
    ``transmission``: that one is in ``rad``).  A
    design sensitivity ``<output>__d_<parameter>`` has the output's unit over
    the parameter's (``rad/mm``; ``''`` where they are the same).
    """
    length = length_unit or ANY_LENGTH
    angles = _angles(linkage)
    by_name: dict[str, tuple[sp.Symbol, int]] = {}
    for q in linkage.coordinates:
        by_name.update({q.name: (q, 0), rate(q).name: (q, 1), acceleration(q).name: (q, 2)})
    for role, q in linkage.roles.items():
        by_name.update({role: (q, 0), role + SPEED_SUFFIX: (q, 1), role + ACCEL_SUFFIX: (q, 2)})
    units = {}
    for name in names:
        point, _, axis = name.rpartition("_")
        if name in by_name:
            q, order = by_name[name]
            units[name] = _per_second("rad" if q in angles else length, order)
        elif point in linkage.points and axis in ("x", "y"):
            units[name] = length
        elif (name in linkage.extras and name not in getattr(linkage, "dynamic_outputs", ())  # forces: derive none
              and _is_angle_function(linkage.extras[name])):
            units[name] = "rad"
        elif (split := split_sensitivity_name(name, linkage.parameters)) is not None:
            output, parameter = split
            numerator = output_units(linkage, [output], length_unit)[output]
            denominator = "rad" if parameter in angles else length
            units[name] = "" if not numerator or numerator == denominator else f"{numerator}/{denominator}"
        else:
            units[name] = ""
    return units
