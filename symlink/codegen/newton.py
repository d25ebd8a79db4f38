"""The generator of the numeric fallback: a standalone NumPy module solving a linkage by Newton's method.

Where no loop-by-loop closed form exists (the Stephenson II six-bar), the
closure equations of all loops are solved together.  The residuals, their
Jacobian with respect to the unknowns and the right-hand sides of the
velocity and acceleration systems (:mod:`symlink.symbolic.closure`) are printed as
NumPy code (:func:`symlink.codegen.program.straight_line`, common
subexpressions eliminated), and the Newton driver
(:mod:`symlink.codegen.newton_driver`) is copied in from its source, so the
generated module imports NumPy only.  :class:`symlink.numeric.solver.NumericSolver`
loads it at run time.

>>> from symlink.mechanism.catalog import fourbar
>>> source = numeric_module(fourbar())
>>> "import sympy" in source, "def accelerations(theta, a, b, c, d, guess, thetadot=0.0, thetaddot=0.0, *, check=True):" in source
(False, True)
"""
from __future__ import annotations

import textwrap
from importlib import resources
from typing import Any, Sequence

import sympy as sp

from ..symbolic.closure import closure_system, is_angle
from ..symbolic.linkage import Linkage, Program
from ..symbolic.sensitivity import closure_parameter_rhs, sensitivity_name, sensitivity_symbol
from ..symbolic.vectors import acceleration, rate
from . import newton_driver
from .numpy import ARGUMENT_CONTRACT, NumPyCodePrinter, numpy_module
from .program import straight_line

__all__ = ["numeric_module", "driver_source"]


def driver_source() -> str:
    """The text of the Newton driver that every generated module embeds: its module's source after the marker.

    >>> driver_source().lstrip().startswith("EPSILON = ")
    True
    """
    text = resources.files(__package__).joinpath("newton_driver.py").read_text(encoding="utf-8")
    lines = text.splitlines(keepends=True)
    marker = [line.rstrip("\n") for line in lines].index(newton_driver.DRIVER_BEGINS)
    return "".join(lines[marker + 1:])


def _array_function(name: str, arguments: Sequence[sp.Symbol], results: Sequence[tuple[str, Any]],
                    doc: str) -> str:
    """Source of a function returning arrays: each result is a list (a vector) or a list of lists (a matrix)."""
    flat: dict[str, sp.Expr] = {}
    for label, value in results:
        if isinstance(value, sp.MatrixBase):
            for i in range(value.rows):
                for j in range(value.cols):
                    flat[f"{label}_{i}_{j}"] = value[i, j]
        else:
            for i, expr in enumerate(value):
                flat[f"{label}_{i}"] = sp.sympify(expr)
    code = straight_line(Program(tuple(arguments), (), flat))
    printer = NumPyCodePrinter()
    lines = [f"def {name}({', '.join(s.name for s in arguments)}):", f'    """{doc}"""']
    lines += [f"    {symbol.name} = {printer.doprint(expr)}" for symbol, expr in code.assignments]
    returned = []
    for label, value in results:
        if isinstance(value, sp.MatrixBase):
            rows = ", ".join("[" + ", ".join(printer.doprint(code.outputs[f"{label}_{i}_{j}"])
                                             for j in range(value.cols)) + "]" for i in range(value.rows))
            returned.append(f"_matrix([{rows}])")
        else:
            returned.append("_stack([" + ", ".join(printer.doprint(code.outputs[f"{label}_{i}"])
                                                   for i in range(len(value))) + "])")
    lines.append("    return " + ", ".join(returned))
    return "\n".join(lines) + "\n"


def _named_function(name: str, doc: str, arguments: Sequence[sp.Symbol], outputs: dict[str, sp.Expr]) -> str:
    """Source of a function returning a dict of named expressions of its arguments (CSE across them)."""
    if not outputs:
        return f"def {name}(*values):\n    return {{}}\n"
    code = straight_line(Program(tuple(arguments), (), outputs))
    printer = NumPyCodePrinter()
    lines = [f"def {name}({', '.join(s.name for s in arguments)}):", f'    """{doc}"""']
    lines += [f"    {symbol.name} = {printer.doprint(expr)}" for symbol, expr in code.assignments]
    lines.append("    return {")
    lines += [f"        {output!r}: {printer.doprint(code.outputs[output])}," for output in outputs]
    lines.append("    }")
    return "\n".join(lines) + "\n"


def _outputs_function(linkage: Linkage, arguments: Sequence[sp.Symbol]) -> tuple[str, list[str]]:
    """Source of ``_outputs``: roles, named points and extras, as expressions of the coordinates."""
    names = [f"{point}_{axis}" for point in linkage.points for axis in "xy"] + list(linkage.extras)
    source = _named_function("_outputs", "Named points and extra outputs from the solved coordinates.", arguments,
                             {name: linkage.output(name) for name in names})
    return source, names


def _sensitivity_function(linkage: Linkage, arguments: Sequence[sp.Symbol]) -> str:
    """Source of ``_sensitivity_outputs``: every position output's derivative by every parameter.

    Its arguments are ``arguments`` and then the unknowns' sensitivities (unknown by unknown, parameter by
    parameter), which the driver solves from ``J S = -dF/dp``; the outputs follow by the chain rule.
    """
    names = ([q.name for q in linkage.unknowns] + [role for role in linkage.roles]
             + [f"{point}_{axis}" for point in linkage.points for axis in "xy"] + list(linkage.extras))
    outputs = {sensitivity_name(name, p.name): linkage.output(sensitivity_name(name, p.name))
               for name in names for p in linkage.parameters}
    columns = tuple(sensitivity_symbol(q, p) for q in linkage.unknowns for p in linkage.parameters)
    return _named_function("_sensitivity_outputs", "Each position output's derivative by each parameter, from the "
                           "unknowns' (name + '__d_' + parameter).", tuple(arguments) + columns, outputs)


_PUBLIC = '''

def positions({signature}guess, *, check=True):
    """Positions over a sweep of {input_names} (one-dimensional), from an initial guess.

    guess: {unknown_names} near the wanted assembly at the first input value,
    as a dict or in that order.  Returns a dict of arrays: the unknowns by
    name, roles, points and extras; residual (each point's largest closure
    residual relative to its loop's size) and assembled (True: a point that
    cannot be solved raises ValueError naming its input value instead).
    The arguments are checked (ValueError naming the argument):
    {contract}
    """
    _arguments(check, {checked_names}, {checked_values}, {lengths})
    symlink_shape, symlink_inputs, symlink_q, _, _, symlink_residual = _sweep({inputs}, {parameters}, guess)
    return _results(symlink_shape, symlink_inputs, {parameters}, symlink_q, None, None, symlink_residual, 0)


def velocities({signature}guess, {rates}, *, check=True):
    """Positions and rates (name + 'dot', role + '_speed') over the sweep; see positions()."""
    _arguments(check, {checked_names_rates}, {checked_values_rates}, {lengths})
    symlink_shape, symlink_inputs, symlink_q, symlink_qdot, _, symlink_residual = _sweep(
        {inputs}, {parameters}, guess, {rate_names}, {zeros})
    return _results(symlink_shape, symlink_inputs, {parameters}, symlink_q, symlink_qdot, None,
                    symlink_residual, 1)


def accelerations({signature}guess, {rates}, {accels}, *, check=True):
    """Positions, rates and accelerations (name + 'ddot', role + '_accel') over the sweep; see positions()."""
    _arguments(check, {checked_names_accels}, {checked_values_accels}, {lengths})
    symlink_shape, symlink_inputs, symlink_q, symlink_qdot, symlink_qddot, symlink_residual = _sweep(
        {inputs}, {parameters}, guess, {rate_names}, {accel_names})
    return _results(symlink_shape, symlink_inputs, {parameters}, symlink_q, symlink_qdot, symlink_qddot,
                    symlink_residual, 2)


def sensitivities({signature}guess, *, check=True):
    """Positions and their derivatives by each parameter (output + '__d_' + parameter) over the sweep.

    The unknowns' derivatives solve J dq/dp = -dF/dp with the converged Jacobian J; roles, points and
    extras follow by the chain rule.  See positions() for the arguments; rates are not computed.
    """
    _arguments(check, {checked_names}, {checked_values}, {lengths})
    symlink_shape, symlink_inputs, symlink_q, _, _, symlink_residual = _sweep({inputs}, {parameters}, guess)
    return _sensitivity_results(symlink_shape, symlink_inputs, {parameters}, symlink_q, symlink_residual)
'''


def numeric_module(linkage: Linkage, title: str = "", regenerate: str = "") -> str:
    """Source of a standalone NumPy module solving ``linkage`` by Newton's method over an input sweep.

    It defines ``positions``, ``velocities``, ``accelerations`` and
    ``sensitivities`` (positions and their derivatives by the parameters) with the
    arguments ``inputs..., parameters..., guess, input rates..., input
    accelerations...`` (see their docstrings).

    Parameters
    ----------
    linkage : Linkage
        Any linkage.
    title : str, optional
        The module's docstring (default: one naming the linkage).
    regenerate : str, optional
        The command that regenerates it, written in its header.

    Returns
    -------
    str
        The module's Python source; it imports NumPy only.

    Examples
    --------
    >>> import math, symlink
    >>> namespace = {}
    >>> exec(symlink.numeric_module(symlink.fourbar()), namespace)  # our own generated code
    >>> result = namespace["positions"](theta=[0.0], a=20, b=66, c=56, d=80, guess={"beta": 1.0, "phi": 2.0})
    >>> round(math.degrees(float(result["phi"][0])), 2)
    110.74
    """
    system = closure_system(linkage)
    inputs, parameters, unknowns = linkage.inputs, linkage.parameters, linkage.unknowns
    input_rates = tuple(rate(x) for x in inputs)
    input_accels = tuple(acceleration(x) for x in inputs)
    unknown_rates = tuple(rate(u) for u in unknowns)
    title = title or f"{linkage.name}: Newton's method on the closure equations, over an input sweep."
    parts = [numpy_module([], title, regenerate)]
    names = lambda symbols: repr(tuple(s.name for s in symbols))  # noqa: E731
    parts.append(f"\n\nINPUTS = {names(inputs)}\nPARAMETERS = {names(parameters)}\nUNKNOWNS = {names(unknowns)}\n"
                 f"ANGLE_INPUTS = {names([x for x in inputs if is_angle(linkage, x)])}\n"
                 f"ROLES = {dict((role, q.name) for role, q in linkage.roles.items())!r}\n")
    parts.append(driver_source())
    base = inputs + parameters + unknowns
    parts.append("\n\n" + _array_function(
        "_closure", base, [("F", system.residuals), ("J", system.jacobian),
                           ("scale", system.scales), ("unit", system.units)],
        "Closure residuals F, Jacobian J = dF/dq, each equation's scale and each unknown's unit."))
    parts.append("\n\n" + _array_function(
        "_velocity_rhs", base + input_rates, [("r", system.velocity_rhs)],
        "Right-hand side of J qdot = r."))
    parts.append("\n\n" + _array_function(
        "_acceleration_rhs", base + unknown_rates + input_rates + input_accels,
        [("r", system.acceleration_rhs)], "Right-hand side of J qddot = r."))
    parts.append("\n\n" + _array_function(
        "_parameter_rhs", base, [("R", closure_parameter_rhs(system.residuals, parameters))],
        "Right-hand sides of J dq/dp = R, one column a parameter."))
    outputs, _ = _outputs_function(linkage, inputs + parameters + unknowns)
    parts.append("\n\n" + outputs)
    parts.append("\n\n" + _sensitivity_function(linkage, inputs + parameters + unknowns))
    as_tuple = lambda items: repr(tuple(items)).replace("'", "")  # noqa: E731  (names, not strings)
    checked = lambda symbols: {"names": repr(tuple(s.name for s in symbols)),  # noqa: E731
                               "values": as_tuple(s.name for s in symbols)}
    plain, with_rates, with_accels = (checked(inputs + parameters), checked(inputs + parameters + input_rates),
                                      checked(inputs + parameters + input_rates + input_accels))
    parts.append(_PUBLIC.format(
        contract=textwrap.fill(ARGUMENT_CONTRACT + "; check=False skips that.", 96, subsequent_indent="    "),
        lengths=repr(tuple(s.name for s in parameters if s.is_positive)),
        checked_names=plain["names"], checked_values=plain["values"],
        checked_names_rates=with_rates["names"], checked_values_rates=with_rates["values"],
        checked_names_accels=with_accels["names"], checked_values_accels=with_accels["values"],
        signature="".join(f"{s.name}, " for s in inputs + parameters),
        inputs=as_tuple(s.name for s in inputs), parameters=as_tuple(s.name for s in parameters),
        input_names=", ".join(s.name for s in inputs), unknown_names=", ".join(s.name for s in unknowns),
        rates=", ".join(f"{s.name}=0.0" for s in input_rates),
        accels=", ".join(f"{s.name}=0.0" for s in input_accels),
        rate_names=as_tuple(s.name for s in input_rates), accel_names=as_tuple(s.name for s in input_accels),
        zeros=as_tuple("0.0" for _ in inputs)))
    return "".join(parts)
