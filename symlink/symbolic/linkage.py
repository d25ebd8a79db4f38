"""A linkage: its loops, inputs and unknowns, named points, and what can be asked of it.

The data flows one way: the loops' closure equations, then a solve plan (one
loop at a time, each with two unknowns left, in closed form), then the
velocity and acceleration of each loop by differentiation, then the outputs a
request names.  Every stage is derived on first use and kept, so a request
for positions never differentiates anything.

Outputs are named by strings:

* a coordinate (``"phi"``), its rate (``"phidot"``) or acceleration (``"phiddot"``);
* a role given to a coordinate (``"rocker"``), with ``"rocker_speed"`` and
  ``"rocker_accel"`` for its derivatives;
* a point's coordinates (``"C_x"``, ``"C_y"``) and any extra named expression
  (the four-bar's ``"transmission"``);
* the derivative of any of those positions by a parameter, ``"rocker__d_a"``
  (see :mod:`symlink.symbolic.sensitivity`): derived only when asked for, without rates.

>>> from symlink.mechanism.catalog import fourbar
>>> linkage = fourbar()
>>> [step.case.name for step in linkage.plan]
['3']
>>> linkage.expression("rocker_speed")
a*thetadot*sin(beta - theta)/(c*sin(beta - phi))
"""
from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from functools import cached_property
from typing import Iterable, Mapping, Sequence

import sympy as sp

from .loops import Loop
from ..common.names import identifier, label
from .motion import loop_rates
from .position import ClampedSqrt, LoopSolution, solve_loop
from .seed_forms import FORMS, seed_form_rows
from .sensitivity import (plan_sensitivities, sensitivity_name, sensitivity_symbol, split_sensitivity_name,
                          total_derivative)
from .typeset import EquationSet, closure_rows, display_latex
from .vectors import Vector, VectorSum, acceleration, expression, rate

__all__ = ["Linkage", "Equations", "Program", "is_branch_name"]

BRANCH = "branch"
SPEED_SUFFIX = "_speed"
ACCEL_SUFFIX = "_accel"


def is_branch_name(name: str) -> bool:
    """Whether an argument name is a branch sign (``branch``, ``branch_<loop>``).

    >>> is_branch_name("branch_ABCD"), is_branch_name("b")
    (True, False)
    """
    return name == BRANCH or name.startswith(BRANCH + "_")


def depended_on(needed: Iterable[sp.Symbol], definitions: Mapping[sp.Symbol, sp.Expr]) -> set[sp.Symbol]:
    """The defined symbols that ``needed`` depends on, directly or through other definitions.

    >>> x, y, z = sp.symbols("x y z")
    >>> sorted(depended_on({z}, {x: sp.S.One, y: x + 1, z: 2 * y}), key=str)
    [x, y, z]
    """
    keep: set[sp.Symbol] = set()
    stack = [s for s in needed if s in definitions]
    while stack:
        symbol = stack.pop()
        if symbol not in keep:
            keep.add(symbol)
            stack += [s for s in definitions[symbol].free_symbols if s in definitions]
    return keep


@dataclass(frozen=True)
class Program:
    """Straight-line code for a set of outputs: what a code printer needs.

    ``arguments`` are the free symbols in calling order; ``assignments`` are
    ``(symbol, expression)`` in dependency order; ``outputs`` maps output
    names to the symbols or expressions that hold them; ``defaults`` gives
    the arguments that may be left out their values (a branch +1, an input's
    rate and acceleration 0).  ``plan`` holds the closed-form loop solutions whose
    textbook assignments code generation computes in loop units instead
    (:func:`symlink.codegen.program.in_loop_units`); empty once that is done.
    """

    arguments: tuple[sp.Symbol, ...]
    assignments: tuple[tuple[sp.Symbol, sp.Expr], ...]
    outputs: dict[str, sp.Expr]
    defaults: dict[str, float] = field(default_factory=dict)
    plan: tuple[LoopSolution, ...] = ()


@dataclass(frozen=True)
class Equations:
    """A linkage's equations as a Jupyter display: closure, positions, and optionally rates and sensitivities."""

    linkage: "Linkage"
    velocities: bool = False
    accelerations: bool = False
    sensitivities: tuple[sp.Symbol, ...] = ()
    form: str = "atan2"

    def _repr_latex_(self) -> str:
        """The closure equations, then the closed forms where the linkage has a solve plan (and the rates asked
        for); without one (the Newton fallback solves it) the closure alone."""
        linkage = self.linkage
        rows = closure_rows(linkage.loops)
        if linkage.has_closed_form:
            rows += seed_form_rows(linkage, self.form)
            rows += list(linkage.velocities.items()) if self.velocities else []
            rows += list(linkage.accelerations.items()) if self.accelerations else []
            for parameter in self.sensitivities:
                rows += list(linkage.sensitivities(parameter).items())
        return display_latex(rows)



def _output_name(output: object) -> str:
    """An output as its name: a name as it is, a symbol (``beta``) by its name; anything else is refused."""
    if isinstance(output, str):
        return output
    if isinstance(output, sp.Symbol):
        return output.name
    raise ValueError(f"an output is named by a string (such as 'rocker'), not by a {type(output).__name__}")

class Linkage:
    """A planar linkage described by vector loops.

    ``inputs`` are the driven coordinates (a crank angle), ``unknowns`` the
    coordinates the loops determine, in the order that fixes each loop's
    branch rule (see :mod:`symlink.symbolic.position`).  ``parameters`` (link lengths
    and fixed angles) default to every other symbol, sorted by name.
    ``points`` are named vector sums from the origin, ``roles`` give
    coordinates plain names (``{"rocker": phi}``) and ``extras`` are further
    named expressions of the coordinates.

    Making a linkage checks it and solves nothing: its plan, closed forms and
    rates (:attr:`plan`, :attr:`positions`, :attr:`velocities`,
    :attr:`accelerations`) are derived on first use and kept.  In Jupyter it
    displays as its closure equations and their solution.

    Parameters
    ----------
    name : str
        An identifier; it names the generated functions and files.
    loops : sequence of Loop
        The closure loops, each a signed sum of vectors that must vanish.
    inputs : sequence of sympy.Symbol
        The driven coordinates (from :func:`~symlink.symbolic.vectors.coordinates`).
    unknowns : sequence of sympy.Symbol
        The coordinates the loops determine: two per loop.
    parameters : sequence of sympy.Symbol, optional
        The constants, in the order generated functions take them; default
        every other symbol of the loops, sorted by name.
    points : mapping of str to Vector, VectorSum or None, optional
        Named points as vector sums from the origin (``None`` is the origin);
        each gives the outputs ``<name>_x`` and ``<name>_y``.
    roles : mapping of str to sympy.Symbol, optional
        Plain names of coordinates: ``{"rocker": phi}`` gives the outputs
        ``rocker``, ``rocker_speed`` and ``rocker_accel``.
    extras : mapping of str to sympy.Expr, optional
        Further named outputs, expressions of the coordinates and parameters.

    Raises
    ------
    ValueError
        A name that is not an identifier or is used twice (or is a reserved
        word of a target language), a loop that is not a :class:`Loop`, an
        input or unknown that is not a symbol or appears in no loop, or a
        number of unknowns other than two per loop.

    See Also
    --------
    symlink.mechanism.catalog : ready-made linkages.
    symlink.io.linkage_file.read_linkage : a linkage from a TOML file.
    symlink.numeric.solver.Solver : numbers from a linkage.

    Examples
    --------
    >>> from symlink import Loop, Vector, coordinates, lengths
    >>> theta, beta, phi = coordinates("theta beta phi")
    >>> a, b, c, d = lengths("a b c d")
    >>> AB, BC, DC, AD = Vector(a, theta), Vector(b, beta), Vector(c, phi), Vector(d, 0)
    >>> fourbar = Linkage("fourbar", [Loop(AD + DC - BC - AB)], inputs=[theta], unknowns=[beta, phi],
    ...                   roles={"rocker": phi})
    >>> fourbar.parameters, [step.case.name for step in fourbar.plan]
    ((a, b, c, d), ['3'])
    >>> fourbar.expression("rocker_speed")
    a*thetadot*sin(beta - theta)/(c*sin(beta - phi))
    """

    def __init__(self, name: str, loops: Sequence[Loop], inputs: Sequence[sp.Symbol],
                 unknowns: Sequence[sp.Symbol], *, parameters: Sequence[sp.Symbol] | None = None,
                 points: Mapping[str, Vector | VectorSum | None] | None = None,
                 roles: Mapping[str, sp.Symbol] | None = None,
                 extras: Mapping[str, sp.Expr] | None = None) -> None:
        self.name = label(name, "linkage name")
        self.loops = tuple(loops)
        for loop in self.loops:
            if not isinstance(loop, Loop):
                raise ValueError(f"{name}: loops must be Loop objects, not {loop!r}")
        self.inputs = tuple(inputs)
        self.unknowns = tuple(unknowns)
        self.points = dict(points or {})
        self.roles = dict(roles or {})
        self.extras = {k: expression(v) for k, v in (extras or {}).items()}
        self._sensitivities: dict[sp.Symbol, EquationSet] = {}
        for kind, symbols in (("input", self.inputs), ("unknown", self.unknowns)):
            for symbol in symbols:
                if not isinstance(symbol, sp.Symbol):
                    raise ValueError(f"{name}: {kind} {symbol!r} must be a SymPy symbol (see vectors.coordinates)")
        listed = self.inputs + self.unknowns
        seen: set[sp.Symbol] = set()
        twice = []
        for q in listed:
            if q in seen:
                twice.append(q.name)
            seen.add(q)
        if twice:
            raise ValueError(f"{name}: coordinate {twice[0]!r} is listed twice among inputs and unknowns")
        coordinates = set(listed)
        found = set().union(*(loop.symbols() for loop in self.loops))
        missing = [u for u in self.unknowns if u not in found]
        if missing:
            raise ValueError(f"unknowns {', '.join(map(str, missing))} appear in no loop")
        if parameters is None:
            parameters = sorted(found - coordinates, key=lambda s: s.name)
        self.parameters = tuple(parameters)
        for symbol in self.parameters:
            if not isinstance(symbol, sp.Symbol):
                raise ValueError(f"{name}: parameter {symbol!r} must be a SymPy symbol")
        self._check_names()
        if 2 * len(self.loops) != len(self.unknowns):
            self.plan  # raises, saying how many unknowns each loop has
            raise ValueError(f"{name}: {len(self.loops)} loops give {2 * len(self.loops)} equations "
                             f"for {len(self.unknowns)} unknowns")

    def _check_names(self) -> None:
        """Refuse names that generated code cannot take or that clash with each other (see symlink.common.names)."""
        derived = {rate(q) for q in self.coordinates} | {acceleration(q) for q in self.coordinates}
        kinds: dict[sp.Symbol, str] = {}
        for symbol in self.parameters:
            kinds[symbol] = "parameter"
        for symbol in self.inputs:
            kinds[symbol] = "input"
        for symbol in self.unknowns:
            kinds[symbol] = "unknown"
        others = set().union(*(loop.symbols() for loop in self.loops))
        for vectors in self.points.values():
            if vectors is not None:
                if not isinstance(vectors, (Vector, VectorSum)):
                    raise ValueError(f"{self.name}: a point is a Vector, a sum of vectors or None, not {vectors!r}")
                others |= vectors.x.free_symbols | vectors.y.free_symbols
        for expr in self.extras.values():
            others |= expr.free_symbols
        for symbol in others - set(kinds) - derived:
            kinds[symbol] = "symbol"
        by_name: dict[str, sp.Symbol] = {}
        for symbol, kind in kinds.items():
            identifier(symbol.name, kind)
            if symbol.name in by_name and by_name[symbol.name] != symbol:
                raise ValueError(f"two different symbols are named {symbol.name!r} (with different assumptions, "
                                 f"such as a positive length and a real coordinate); use one symbol")
            by_name[symbol.name] = symbol
        # A coordinate's rate and acceleration are names too: <q>dot and <q>ddot.
        made_by: dict[str, str] = {}
        for q in self.coordinates:
            for what, symbol in (("rate", rate(q)), ("acceleration", acceleration(q))):
                source = f"the {what} of {kinds[q]} {q.name!r}"
                if symbol.name in made_by:
                    raise ValueError(f"{made_by[symbol.name]} and {source} are both named {symbol.name!r}; "
                                     "rename one of the coordinates")
                made_by[symbol.name] = source
                if symbol.name in by_name and (kinds[by_name[symbol.name]] != "symbol"
                                               or by_name[symbol.name] != symbol):
                    other = by_name[symbol.name]
                    raise ValueError(f"{kinds[other]} {other.name!r} clashes with {source}; rename it")
        loop_names = Counter(loop.name for loop in self.loops)
        for loop_name, count in loop_names.items():
            if count > 1:
                raise ValueError(f"{self.name}: two loops are named {loop_name!r}; each loop needs its own name "
                                 "(it names the loop's branch sign)")
        # Output names: distinct from each other and from the symbols.
        outputs: dict[str, str] = {}

        def output(name: str, source: str) -> None:
            try:
                identifier(name, "output")
            except ValueError as error:
                raise ValueError(f"{source}: {error}") from None
            if name in outputs:
                raise ValueError(f"{source} gives the output {name!r}, as {outputs[name]} does; rename one")
            if name in by_name and not (name in made_by or kinds[by_name[name]] in ("input", "unknown")):
                raise ValueError(f"{source} gives the output {name!r}, which is also the name of "
                                 f"{kinds[by_name[name]]} {name!r}; rename one")
            outputs[name] = source

        for q in self.coordinates:
            output(q.name, f"{kinds[q]} {q.name!r}")
            output(rate(q).name, made_by[rate(q).name])
            output(acceleration(q).name, made_by[acceleration(q).name])
        for role, q in self.roles.items():
            identifier(role, "role")
            if not isinstance(q, sp.Symbol) or q not in kinds or kinds[q] not in ("input", "unknown"):
                raise ValueError(f"role {role!r} names {q!r}, which is not an input or unknown of {self.name}")
            output(role, f"role {role!r}")
            output(role + SPEED_SUFFIX, f"the speed of role {role!r}")
            output(role + ACCEL_SUFFIX, f"the acceleration of role {role!r}")
        for point in self.points:
            identifier(point, "point")
            output(f"{point}_x", f"point {point!r}")
            output(f"{point}_y", f"point {point!r}")
        for extra in self.extras:
            identifier(extra, "extra output")
            output(extra, f"extra output {extra!r}")

    @cached_property
    def branches(self) -> tuple[sp.Symbol, ...]:
        """The branch symbols (+1 or -1 each), one a loop with two assemblies, in plan order."""
        if not self.has_closed_form:
            return ()
        return tuple(step.branch for step in self.plan if step.branch is not None)

    @property
    def coordinates(self) -> tuple[sp.Symbol, ...]:
        return self.inputs + self.unknowns

    def _branch_symbol(self, loop: Loop) -> sp.Symbol:
        return sp.Symbol(BRANCH if len(self.loops) == 1 else f"{BRANCH}_{loop.name}", integer=True)

    @cached_property
    def plan(self) -> tuple[LoopSolution, ...]:
        """The solve plan: loops in an order where each has exactly two unknowns left, solved in closed form."""
        return tuple(solve_loop(loop, left, self._branch_symbol(loop), str(number))
                     for number, (loop, left) in enumerate(self._solve_order, start=1))

    @cached_property
    def _solve_order(self) -> tuple[tuple[Loop, list[sp.Symbol]], ...]:
        """The plan's loops and the two unknowns each solves, without solving them (cheap: a warm solver asks).

        ``ValueError`` where no closed-form order exists, or a loop's two unknowns form no case.
        """
        solved: set[sp.Symbol] = set()
        order: list[tuple[Loop, list[sp.Symbol]]] = []
        waiting = list(self.loops)
        # Each loop's unknowns, in the unknowns' order, found once (not a pass over every unknown a loop a step).
        position = {u: k for k, u in enumerate(self.unknowns)}
        own = {id(loop): sorted((s for s in loop.symbols() if s in position), key=position.__getitem__)
               for loop in waiting}
        while waiting:
            for at, loop in enumerate(waiting):
                left = [u for u in own[id(loop)] if u not in solved]
                if len(left) == 2:
                    loop.case(left)  # ValueError for two unknowns no closed form takes
                    order.append((loop, left))
                    solved.update(left)
                    del waiting[at]
                    break
            else:
                counts = ", ".join(f"{loop.name}: {len([u for u in own[id(loop)] if u not in solved])}"
                                   for loop in waiting)
                raise ValueError(
                    f"no loop of {self.name!r} has exactly two unknowns left ({counts}); "
                    "no closed-form solve plan exists")
        unsolved = [u for u in self.unknowns if u not in solved]
        if unsolved:
            raise ValueError(f"the loops of {self.name!r} do not determine {', '.join(map(str, unsolved))}")
        return tuple(order)

    @cached_property
    def has_closed_form(self) -> bool:
        """Whether a loop-by-loop closed-form :attr:`plan` exists; if not, use :class:`symlink.numeric.solver.NumericSolver`.

        A linkage whose loops give as many equations as it has unknowns but no
        closed-form order (the Stephenson II six-bar) is still a linkage; any
        other reason for having no plan is an error in its definition.
        """
        try:
            self._solve_order
        except ValueError:
            if 2 * len(self.loops) != len(self.unknowns):
                raise
            return False
        return True

    @cached_property
    def positions(self) -> EquationSet:
        """Every unknown and intermediate in closed form, in plan order, as a textbook writes them.

        In the linkage's own lengths and angles and each loop's intermediates
        (``Wx_k, Wy_k``: the vector the unknowns close, ``w_k`` its length,
        ``Delta_k`` the root); generated code computes the same in loop units
        (:func:`symlink.codegen.program.in_loop_units`).

        >>> from symlink.mechanism.catalog import fourbar
        >>> for symbol, expr in list(fourbar().positions.items())[:3]:
        ...     print(symbol, "=", expr)
        Wx_1 = a*cos(theta) - d
        Wy_1 = a*sin(theta)
        w_1 = sqrt(Wx_1**2 + Wy_1**2)
        """
        result = EquationSet()
        for step in self.plan:
            result.update(step.intermediates)
            result.update(step.positions)
        return result

    def _rates(self, order: int) -> EquationSet:
        result = EquationSet()
        for step in self.plan:
            result.update(loop_rates(step.loop, list(step.positions), self.coordinates, order))
        return result

    @cached_property
    def velocities(self) -> EquationSet:
        """The unknowns' rates, in terms of positions and the inputs' rates."""
        return self._rates(1)

    @cached_property
    def accelerations(self) -> EquationSet:
        """The unknowns' accelerations, in terms of positions, rates and the inputs' accelerations."""
        return self._rates(2)

    @cached_property
    def singular(self) -> sp.Expr:
        """Output ``"singular"``: True where a loop's square root is zero (a toggle: its two branches meet).

        The generated rates divide by that root, so they are inf or NaN exactly there and
        finite elsewhere.  Loops with one assembly (no root) never set it.  Asked for with
        other outputs, it looks at the loops those outputs depend on (:meth:`program`).
        """
        return self._toggles(None)

    def _toggles(self, keep: set[sp.Symbol] | None) -> sp.Expr:
        """Whether a loop's root is zero, of every loop or of the loops whose roots are in ``keep``."""
        roots = [s for step in self.plan for s, e in step.in_loop_units.intermediates.items()
                 if isinstance(e, ClampedSqrt) and (keep is None or s in keep)]
        return sp.Or(*(sp.Eq(root, 0) for root in roots))

    def divides_by_determinant(self, name: str) -> bool:
        """Whether output ``name`` is solved through a loop's determinant, which vanishes at a toggle.

        The rates and accelerations of the unknowns, what is made of them, and the sensitivities by a
        parameter that closes a loop divide by the determinant of a loop's linear system (the
        derivative of its closure by its unknowns); at a toggle that determinant is zero and they are
        not finite (or not meaningful), where the ``singular`` output says why.  Positions never are.

        >>> from symlink.mechanism.catalog import fourbar
        >>> [fourbar().divides_by_determinant(n) for n in ("rocker", "rocker_speed", "rocker__d_a", "thetadot")]
        [False, True, True, False]
        """
        if name == "singular":
            return False
        found = split_sensitivity_name(name, self.parameters)
        if found is not None:
            return any(found[1] in loop.symbols() for loop in self.loops)
        moving = {rate(q) for q in self.unknowns} | {acceleration(q) for q in self.unknowns}
        return bool(self.output(name).free_symbols & moving)

    def with_singular(self, outputs: Sequence[str]) -> list[str]:
        """``outputs``, and ``"singular"`` after them where one of them divides by a loop's determinant.

        What the solvers compute, so that a result that is inf or NaN at an assembled pose says why:
        ``singular`` is True there, beside ``assembled``.

        >>> from symlink.mechanism.catalog import fourbar
        >>> fourbar().with_singular(["rocker", "rocker_speed"]), fourbar().with_singular(["rocker"])
        (['rocker', 'rocker_speed', 'singular'], ['rocker'])

        A request that repeats itself is collapsed (each output once, in the order first asked), and an
        unknown's symbol stands for its name:

        >>> fourbar().with_singular(["rocker", "rocker", fourbar().unknowns[0]])
        ['rocker', 'beta']
        """
        outputs = list(dict.fromkeys(_output_name(output) for output in outputs))
        if "singular" in outputs or not any(self.divides_by_determinant(n) for n in outputs):
            return outputs
        return outputs + ["singular"] if self.has_closed_form else outputs

    def point(self, name: str) -> tuple[sp.Expr, sp.Expr]:
        """A named point's x and y."""
        vectors = self.points[name]
        if vectors is None:
            return sp.S.Zero, sp.S.Zero
        return vectors.x, vectors.y

    # --- outputs --------------------------------------------------------
    def output_names(self) -> list[str]:
        """Every output name this linkage answers to."""
        names = [q.name for q in self.unknowns]
        names += [rate(q).name for q in self.unknowns] + [acceleration(q).name for q in self.unknowns]
        for role in self.roles:
            names += [role, role + SPEED_SUFFIX, role + ACCEL_SUFFIX]
        for point in self.points:
            names += [f"{point}_x", f"{point}_y"]
        return names + list(self.extras) + (["singular"] if self.has_closed_form else [])

    def output(self, name: str) -> sp.Expr:
        """What an output name stands for: a coordinate or rate symbol, or an expression of them."""
        by_name = {}
        for q in self.coordinates:
            by_name.update({q.name: q, rate(q).name: rate(q), acceleration(q).name: acceleration(q)})
        for role, q in self.roles.items():
            by_name.update({role: q, role + SPEED_SUFFIX: rate(q), role + ACCEL_SUFFIX: acceleration(q)})
        if name in by_name:
            return by_name[name]
        if name == "singular":
            return self.singular
        if name in self.extras:
            return self.extras[name]
        point, _, axis = name.rpartition("_")
        if point in self.points and axis in ("x", "y"):
            return self.point(point)[axis == "y"]
        found = split_sensitivity_name(name, self.parameters)
        if found is not None:
            return self._sensitivity_output(*found)
        raise ValueError(f"{self.name} has no output {name!r}; it has {', '.join(self.output_names())}")

    def _sensitivity_output(self, name: str, parameter: sp.Symbol) -> sp.Expr:
        """d(output)/d(parameter) at fixed inputs, in terms of the coordinates and the unknowns' sensitivities."""
        if split_sensitivity_name(name, self.parameters) is not None:
            raise ValueError(f"{self.name}: {sensitivity_name(name, parameter.name)!r} is a second derivative; "
                             "only first derivatives by parameters are derived")
        expr = self.output(name)
        moving = {rate(q) for q in self.coordinates} | {acceleration(q) for q in self.coordinates}
        if name == "singular" or expr.free_symbols & moving:
            raise ValueError(f"{self.name}: {sensitivity_name(name, parameter.name)!r} asks for a sensitivity of "
                             f"{name!r}; sensitivities are derived for positions (coordinates, roles, points and "
                             "extras) only, not for rates, accelerations or flags")
        taken = {s.name: s for s in self.coordinates + self.parameters}
        for q in self.unknowns:
            symbol = sensitivity_symbol(q, parameter)
            if symbol.name in taken:
                raise ValueError(f"{self.name}: the sensitivity {symbol.name!r} of {q.name!r} by {parameter.name!r} "
                                 "has the name of a coordinate or parameter; rename one")
        # A parameter of the points or extras alone (a coupler-point offset, a pivot placing the whole
        # linkage) moves no unknown: no chain terms, so nothing multiplies a zero in generated code.
        closes = any(parameter in loop.symbols() for loop in self.loops)
        return total_derivative(expr, self.unknowns if closes else (), parameter)

    def sensitivities(self, parameter: sp.Symbol) -> EquationSet:
        """Every unknown's derivative by ``parameter`` (``phi__d_a``), in plan order; derived once, on first use.

        >>> from symlink.mechanism.catalog import fourbar
        >>> linkage = fourbar()
        >>> a = linkage.parameters[0]
        >>> linkage.sensitivities(a)[sensitivity_symbol(linkage.unknowns[1], a)]
        cos(beta - theta)/(c*sin(beta - phi))
        """
        if parameter not in self.parameters:
            raise ValueError(f"{self.name} has no parameter {parameter!r}; "
                             f"it has {', '.join(s.name for s in self.parameters)}")
        if parameter not in self._sensitivities:
            self._sensitivities[parameter] = EquationSet(plan_sensitivities(self.plan, parameter))
        return self._sensitivities[parameter]

    def expression(self, name: str, simplify: bool = False) -> sp.Expr:
        """The closed form behind an output name, one level deep (in terms of coordinates and rates).

        ``simplify=True`` runs SymPy's ``simplify`` on it: opt-in, for reading, since it can be
        slow and the derived forms are already compact; generated code never uses it.

        >>> from symlink.mechanism.catalog import fourbar
        >>> fourbar().expression("rocker_accel", simplify=True)
        (a*thetaddot*sin(beta - theta) - a*thetadot**2*cos(beta - theta) - b*betadot**2 + c*phidot**2*cos(beta - phi))/(c*sin(beta - phi))
        """
        symbol = self.output(name)
        found = self._definitions_of([symbol]).get(symbol, symbol)
        return sp.simplify(found) if simplify else found

    def _definitions_of(self, symbols: Iterable[sp.Symbol]) -> dict[sp.Symbol, sp.Expr]:
        """The definitions that the symbols need: positions, and rates or sensitivities only if asked for."""
        symbols = set(symbols)
        unknown_rates = {rate(q) for q in self.unknowns}
        unknown_accels = {acceleration(q) for q in self.unknowns}
        definitions = dict(self.positions)
        if symbols & (unknown_rates | unknown_accels):
            definitions.update(self.velocities)
        if symbols & unknown_accels:
            definitions.update(self.accelerations)
        for parameter in self.parameters:
            if {sensitivity_symbol(q, parameter) for q in self.unknowns} & symbols:
                definitions.update(self.sensitivities(parameter))
        return definitions

    def program(self, outputs: Sequence[str]) -> Program:
        """Straight-line code for ``outputs``: only what they depend on is derived and kept.

        ``singular`` asked for with other outputs is True where a loop they depend on is at a toggle.
        """
        wanted = {name: self.output(name) for name in outputs}
        others = [expr for name, expr in wanted.items() if name != "singular"]
        if "singular" in wanted and others:
            wanted["singular"] = self._toggles(self._kept(self._needs(others))[0])
        needed = self._needs(wanted.values())
        keep, definitions = self._kept(needed)
        assignments = tuple((s, e) for s, e in definitions.items() if s in keep)
        free = set(needed) - keep
        for _, expr in assignments:
            free |= expr.free_symbols - keep - set(definitions)
        free -= keep
        order = self.call_signature()
        unexpected = free - set(order)
        if unexpected:
            raise ValueError(f"outputs depend on unknown symbols {sorted(map(str, unexpected))}")
        always = set(self.inputs) | set(self.parameters) | set(self.branches)
        arguments = tuple(s for s in order if s in free or s in always)
        defaults = {s.name: 1.0 for s in self.branches}
        defaults.update({s.name: 0.0 for q in self.inputs for s in (rate(q), acceleration(q))})
        return Program(arguments, assignments, wanted, {a.name: defaults[a.name] for a in arguments if a.name in defaults},
                       self.plan if self.has_closed_form else ())

    @staticmethod
    def _needs(expressions: Iterable[sp.Expr]) -> set[sp.Symbol]:
        return set().union(*(sp.sympify(e).free_symbols for e in expressions))

    def _kept(self, needed: set[sp.Symbol]) -> tuple[set[sp.Symbol], dict[sp.Symbol, sp.Expr]]:
        """The definitions that ``needed`` depends on (their symbols), and the definitions code is made from."""
        definitions = self._definitions_of(needed)
        return depended_on(needed, definitions), definitions

    def call_signature(self) -> tuple[sp.Symbol, ...]:
        """The order of a generated function's arguments: inputs, parameters, branches, input rates."""
        return (self.inputs + self.parameters + self.branches
                + tuple(rate(q) for q in self.inputs) + tuple(acceleration(q) for q in self.inputs))

    def _repr_latex_(self) -> str:
        return self.equations()._repr_latex_()

    def equations(self, velocities: bool = False, accelerations: bool = False,
                  sensitivities: Sequence[str] = (), form: str = "atan2") -> "Equations":
        r"""The closure and the closed forms as a Jupyter display (velocities, accelerations and the
        unknowns' derivatives by the named parameters on request).

        Displaying a linkage shows the closure and positions; this shows more
        without deriving anything that is not asked for.  ``form`` writes the
        positions as a seed paper does (``"complex"``, ``"freudenstein"``,
        ``"half-angle"``: :mod:`symlink.symbolic.seed_forms`); generated code always
        computes symlink's own ``"atan2"`` form.

        >>> from symlink.mechanism.catalog import fourbar
        >>> "\\dot{\\phi}" in fourbar().equations(velocities=True)._repr_latex_()
        True
        >>> "\\frac{\\partial \\phi}{\\partial a}" in fourbar().equations(sensitivities=["a"])._repr_latex_()
        True
        """
        by_name = {p.name: p for p in self.parameters}
        unknown = [name for name in sensitivities if name not in by_name]
        if unknown:
            raise ValueError(f"{self.name} has no parameter {unknown[0]!r}; it has {', '.join(by_name)}")
        if form not in FORMS:
            raise ValueError(f"no form {form!r}; the forms are {', '.join(FORMS)}")
        return Equations(self, velocities, accelerations, tuple(by_name[name] for name in sensitivities), form)

    def __repr__(self) -> str:
        return (f"Linkage({self.name!r}, loops={[loop.name for loop in self.loops]}, "
                f"inputs={list(self.inputs)}, unknowns={list(self.unknowns)})")
