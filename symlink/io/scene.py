"""Scenes: a request for some outputs of a linkage, and only what those outputs need.

A :class:`Scene` names a linkage (a :class:`~symlink.symbolic.linkage.Linkage` or a
catalog name), the outputs it needs, the values to evaluate them at (input
angles, link lengths, input rates) and the branch.  symlink derives,
generates and loads code for exactly those outputs and what they depend on:
a positions-only scene never differentiates, a rocker-only scene never
computes the coupler angle, and common subexpressions are shared among the
requested outputs only.  The code is cached in memory and on disk
(:mod:`symlink.numeric.cache`), so the second run of a scene does no symbolic work.
:class:`~symlink.numeric.solver.Solver`, which every command of the command line
uses, goes through the same cache.

>>> from symlink.mechanism.catalog import fourbar
>>> scene = Scene(fourbar(), ["rocker"], dict(theta=0.0, a=20, b=66, c=56, d=80), branch="both")
>>> {sign: round(float(numpy.degrees(result["rocker"])), 2) for sign, result in scene.evaluate().items()}
{1: 110.74, -1: -110.74}
>>> "beta =" in scene.source, "velocities" in scene.linkage.__dict__
(False, False)

Scene files (``symlink run scene.toml``) hold numbers and names only, never
code::

    linkage = "fourbar"                 # a catalog name, or a linkage file ("legs/jansen.toml", beside this one)
    outputs = ["rocker", "rocker_speed"]  # any of the linkage's output names
    branch = "both"                     # 1, -1 or "both" (default 1)
    units = "deg"                       # "deg" (default) or "rad": input and printed angles
    format = "table"                    # "table" (default), "csv" or "json"

    [parameters]                        # every link length of the linkage, by name
    a = 20
    b = 66
    c = 56
    d = 80

    [input]                             # the crank: start/stop/step (default 0, 360, 10 deg) or angles
    start = 0
    stop = 360
    step = 40
    # angles = [0, 40, 80]
    speed = 10.5                        # rad/s at the first angle (default 0)
    accel = 0                           # rad/s^2, uniform from the first angle (default 0)

    [dynamics.masses.crank]             # optional: masses and loads as in a linkage file's [dynamics]
    mass = "m2"                         # (a name's value under [parameters]); outputs may then name
    distance = 10                       # input_torque, joint_A_x, shaking_moment, ...

They are read with ``tomllib`` (Python 3.11 and later) or, on Python 3.10,
with ``tomli`` (the same reader, published separately).  Every key and value
is checked; anything unknown or out of range is one line of error.
"""
from __future__ import annotations

from functools import cached_property, lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping, Sequence

import numpy

from ..numeric.cache import GeneratedCode, generated_code
from ..numeric.call_arguments import check_argument_names
from ..common.files import excerpt, read_input_text
from ..common.display import record_html
from ..numeric.input_sweep import InputSweep, crank_speeds, table_inputs
from ..numeric.newton_table import newton_results
from .scene_text import (BRANCH_CHOICES, FORMATS, INPUT_KEYS, MAX_SCENE_BYTES, TOP_KEYS, UNITS,  # noqa: F401
                         NewtonScene, catalog_file_names, choice as _choice, input_table, linkage_request,
                         newton_scene, number as _number, table as _table)
from .table_source import TableSource
from ..common.numbers import toml_data
from ..common.angles import to_radians
from ..numeric.results import Results

if TYPE_CHECKING:
    import sympy as sp

    from ..numeric.solver import Solver
    from ..symbolic.linkage import Linkage, Program

# The symbolic side (linkages, their derivation, Solver: SymPy) is imported inside the functions that need it, so
# that a scene of a linkage without a closed form, its solver in the disk cache, is read and evaluated without SymPy.


__all__ = ["Scene", "SceneFile", "NewtonSceneFile", "catalog_linkage", "angle_outputs", "read_scene",
           "scene_from_mapping", "scene_from_text"]



def catalog_linkage(name: str) -> Linkage:
    """A fresh instance of the catalog's linkage ``name`` (cheap: its derivations happen on first use).

    Parameters
    ----------
    name : str
        A catalog name: ``"fourbar"``, ``"slider-crank"``, ``"watt2"`` ... (the keys of :data:`CATALOG`), or a
        six-bar's name in any spelling (``"Watt II"``: :func:`symlink.io.linkage_file.catalog_name`).

    Returns
    -------
    Linkage
        The linkage, the same instance for the same name in a process.

    Raises
    ------
    ValueError
        For a name not in the catalog, listing those there are.

    Examples
    --------
    >>> import symlink
    >>> linkage = symlink.catalog_linkage("slider-crank")
    >>> linkage.name, linkage.unknowns, linkage is symlink.catalog_linkage("slider-crank")
    ('slider-crank', (beta, s), True)
    """
    from .linkage_file import catalog_name
    return _catalog_linkage(catalog_name(name))


@lru_cache(maxsize=None)
def _catalog_linkage(name: str) -> Linkage:
    from ..mechanism.catalog import CATALOG
    return CATALOG[name]()


def angle_outputs(linkage: Linkage, outputs: Sequence[str]) -> set[str]:
    """The outputs that are angles: coordinates that turn a vector, and extras made by an inverse trig function.

    Rates and accelerations are not angles (they are per second); points are lengths.

    >>> sorted(angle_outputs(catalog_linkage("fourbar"), ["rocker", "rocker_speed", "C_x", "transmission"]))
    ['rocker', 'transmission']
    """
    import sympy as sp

    from ..symbolic.closure import is_angle
    found = set()
    known = set(linkage.output_names())
    for name in outputs:
        if name not in known:  # a torque or force of a cached dynamics request (never an angle)
            continue
        expr = linkage.output(name)
        if isinstance(expr, sp.Symbol) and expr in linkage.coordinates:
            if is_angle(linkage, expr):
                found.add(name)
        elif name in linkage.extras:
            while isinstance(expr, sp.Abs):
                expr = expr.args[0]
            if isinstance(expr, (sp.atan2, sp.atan, sp.asin, sp.acos)):
                found.add(name)
    return found


class Scene:
    """A linkage, the outputs it needs, the values to evaluate them at, and the branch.

    ``values`` are the generated function's arguments by name (inputs in
    radians, link lengths, input rates); they broadcast against each other.
    ``branch`` is +1, -1 or ``"both"``; it is given to every branch sign of
    the linkage.

    Parameters
    ----------
    linkage : Linkage or str
        The linkage, or a catalog name.
    outputs : sequence of str
        The outputs wanted (only what they need is derived).
    values : mapping of str to object, optional
        The generated function's arguments by name (inputs in radians, lengths, input rates).
    branch : {1, -1, "both"}, optional
        The assembly for every branch sign (default 1).

    Examples
    --------
    >>> import math, symlink
    >>> scene = symlink.Scene("fourbar", ["rocker"], dict(theta=0.0, a=20, b=66, c=56, d=80))
    >>> results = scene.evaluate()  # by branch
    >>> list(results), round(math.degrees(float(results[1]["rocker"])), 2)  # seed 003
    ([1], 110.74)
    """

    def __init__(self, linkage: Linkage | str, outputs: Sequence[str],
                 values: Mapping[str, object] | None = None, branch: int | str = 1) -> None:
        from ..symbolic.sensitivity import split_sensitivity_name
        self.linkage = catalog_linkage(linkage) if isinstance(linkage, str) else linkage
        self.outputs = tuple(outputs)
        if not self.outputs:
            raise ValueError(f"a scene needs at least one output of {self.linkage.name}; "
                             f"it has {', '.join(self.linkage.output_names())}")
        known = set(self.linkage.output_names())
        for name in self.outputs:
            if name not in known and split_sensitivity_name(name, self.linkage.parameters) is None:
                self.linkage.output(name)  # ValueError naming the outputs there are
        # (a sensitivity's name is checked where its code is derived, not here: that derives it)
        if branch not in BRANCH_CHOICES or isinstance(branch, bool):
            raise ValueError(f"branch must be 1, -1 or 'both', got {branch!r}")
        self.branch = branch
        self.values = dict(values or {})

    @property
    def signs(self) -> tuple[int, ...]:
        """The branch signs the scene is evaluated on."""
        return (1, -1) if self.branch == "both" else (int(self.branch),)

    @cached_property
    def code(self) -> GeneratedCode:
        """The generated and loaded code of exactly these outputs (cached)."""
        return generated_code(self.linkage, self.outputs)

    @property
    def source(self) -> str:
        """The generated NumPy module."""
        return self.code.source

    @cached_property
    def solver(self) -> Solver:
        """A checked solver of these outputs, with the ``singular`` flag where they divide by a loop's determinant."""
        from ..numeric.solver import Solver
        return Solver(self.linkage, self.outputs)

    def program(self) -> Program:
        """The straight-line program behind the code: symbolic work, for inspection only."""
        return self.linkage.program(self.outputs)

    def evaluate(self, **values) -> dict[int, Results]:
        """The outputs on each branch sign, at the scene's values updated by ``values``.

        Each is a :class:`~symlink.numeric.results.Results` (a dict that shows as a
        table and has ``to_frame()``); ``values`` may be pint quantities, as
        for :class:`~symlink.numeric.solver.Solver`, but not mixed with the scene's
        plain lengths.
        """
        merged = {**self.values, **values}
        branches = self.solver.branches
        # the scene gives the branch signs: a value missing or unknown is named as the solver names it
        check_argument_names(self.linkage.name, self.solver.arguments, self.solver.required, [*merged, *branches])
        return {sign: self.solver(**merged, **{name: sign for name in branches}) for sign in self.signs}

    def __repr__(self) -> str:
        return f"Scene({self.linkage.name!r}, {list(self.outputs)}, branch={self.branch!r})"

    def derivation(self) -> tuple[tuple[sp.Symbol, ...], tuple[sp.Symbol, ...]]:
        """What the scene's code computes and what it skips: unknowns, their rates and accelerations.

        Symbolic work (the positions, and the rates only if an output needs them),
        done once per linkage; ``ValueError`` for a linkage without a closed form.
        """
        from ..symbolic.vectors import acceleration, rate
        kept = {symbol for symbol, _ in self.program().assignments}
        unknowns = self.linkage.unknowns
        every = unknowns + tuple(rate(q) for q in unknowns) + tuple(acceleration(q) for q in unknowns)
        return tuple(s for s in every if s in kept), tuple(s for s in every if s not in kept)

    def _branch_words(self) -> str:
        return "both branches" if self.branch == "both" else f"branch {self.branch:+d}"

    def __str__(self) -> str:
        """What the scene asks for, and what its code will compute and skip.

        >>> from symlink.mechanism.catalog import fourbar
        >>> print(Scene(fourbar(), ["rocker"]))
        scene of fourbar: rocker (branch +1)
          computes phi
          skips beta, betadot, phidot, betaddot, phiddot
        """
        head = f"scene of {self.linkage.name}: {', '.join(self.outputs)} ({self._branch_words()})"
        if not self.linkage.has_closed_form:
            return head + "\n  no closed form: solved numerically, all loops at once (see symlink plan)"
        computed, skipped = self.derivation()
        return "\n".join([head, f"  computes {', '.join(map(str, computed)) or 'nothing'}",
                          f"  skips {', '.join(map(str, skipped)) or 'nothing'}"])

    def _repr_latex_(self) -> str:
        r"""Jupyter's display: the outputs, the branch sign, and the coordinates computed and skipped.

        >>> from symlink.mechanism.catalog import fourbar
        >>> print(Scene(fourbar(), ["rocker"], branch="both")._repr_latex_())
        $\begin{array}{ll}\text{scene of fourbar} & \text{rocker},\ \sigma = \pm 1\\ \text{computes} & \phi\\ \text{skips} & \beta, \dot{\beta}, \dot{\phi}, \ddot{\beta}, \ddot{\phi}\end{array}$
        """
        import sympy as sp

        from ..common.notation import math_text
        sign = r"\pm 1" if self.branch == "both" else f"{self.branch:+d}"
        rows = [f"{math_text('scene of ' + self.linkage.name)} & "
                f"{', '.join(math_text(o) for o in self.outputs)},\\ \\sigma = {sign}"]
        if not self.linkage.has_closed_form:
            rows.append(r"\text{no closed form} & \text{solved numerically, all loops at once}")
        else:
            computed, skipped = self.derivation()
            for word, symbols in (("computes", computed), ("skips", skipped)):
                rows.append(f"\\text{{{word}}} & " + (", ".join(sp.latex(s) for s in symbols) or r"\text{nothing}"))
        return "$\\begin{array}{ll}" + "\\\\ ".join(rows) + "\\end{array}$"


class _Positive:
    """A parameter of a cached request as the scene file's checks see it: its name and whether it is a length."""

    def __init__(self, name: str, is_positive: bool) -> None:
        self.name, self.is_positive = name, is_positive


class DynamicScene:
    """Torques or joint forces of a linkage with a scene's ``[dynamics]`` table, keyed by what the scene names.

    The cache key is made from the kinematic linkage's definition, the table as given and the outputs,
    so a warm request (the entry on disk) builds no dynamic model and derives nothing: the equation of
    motion is derived once, when the entry is made (:func:`symlink.numeric.cached_solver.entry_text`).
    """

    def __init__(self, kinematics: Linkage, outputs: Sequence[str], table: Mapping) -> None:
        import json

        from ..numeric.cache import cache_key
        from ..numeric.cached_solver import CachedSolver
        self.kinematics, self.outputs, self.table = kinematics, list(outputs), table
        try:
            described = json.dumps(table, sort_keys=True, default=str)
        except (TypeError, ValueError):
            raise ValueError(f"dynamics must be a table of names and numbers, got {table!r}") from None
        self.key = cache_key(kinematics, self.outputs, f"dynamic-scene:{described}")
        self.derive = self._derive  # the entry, the first time (SymPy): also what a warm scene file keeps the key of
        self.solver = CachedSolver(kinematics.name, self.outputs, key=self.key, derive=self._derive,
                                   full=self._full)
        facts = self.solver.description
        self.parameters = {name: _Positive(name, positive) for name, positive in facts["parameters"]}
        self.angles = set(facts["angles"])

    def dynamic_linkage(self) -> Linkage:
        """The linkage with its dynamic outputs (symbolic work: only where the entry is derived or quantities are given)."""
        from .linkage_file import LinkageFile, dynamic_model
        model = dynamic_model(self.table, self.kinematics)
        found = LinkageFile(self.kinematics, {}, "", model).with_dynamics().linkage
        for name in self.outputs:
            try:
                found.output(name)
            except ValueError:
                raise ValueError(f"outputs: {found.name} has no output {name!r}; "
                                 f"it has {', '.join(found.output_names())}") from None
        return found

    def _derive(self) -> str:
        from ..numeric.cached_solver import entry_text
        linkage = self.dynamic_linkage()
        return entry_text(linkage, self.outputs, parameters=[[p.name, bool(p.is_positive)] for p in linkage.parameters],
                          angles=sorted(angle_outputs(linkage, self.outputs)))

    def _full(self) -> Solver:
        from ..numeric.solver import Solver
        return Solver(self.dynamic_linkage(), self.outputs)

    def scene(self, values: Mapping[str, object], branch: int | str) -> Scene:
        """A :class:`Scene` of the request, answered from the cache entry."""
        return _CachedScene(self, values, branch)


class _CachedScene(Scene):
    """A scene whose code and solver come from a :class:`DynamicScene`'s cache entry (its linkage: the kinematic one)."""

    def __init__(self, request: DynamicScene, values: Mapping[str, object], branch: int | str) -> None:
        self.linkage, self.outputs, self.request = request.kinematics, tuple(request.outputs), request
        if branch not in BRANCH_CHOICES or isinstance(branch, bool):
            raise ValueError(f"branch must be 1, -1 or 'both', got {branch!r}")
        self.branch, self.values = branch, dict(values)

    @cached_property
    def code(self) -> GeneratedCode:
        entry = self.request.solver
        return GeneratedCode("", entry.source, entry.function)

    @cached_property
    def solver(self) -> Any:  # the cached entry's solver: called and asked for its branches as a Solver is
        return self.request.solver

    def program(self) -> Program:
        return self.request.dynamic_linkage().program(list(self.outputs))


# --- scene files -----------------------------------------------------------

class SceneFile:
    """A scene read from a file, with how to drive and print it.

    ``sweep`` holds the input angles in ``units``; :meth:`values_at` gives the
    scene's input values (radians, and the rates the outputs need) at a block
    of them, so that a long sweep is evaluated a block at a time.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    def __init__(self, scene: Scene, input_column: str, sweep: InputSweep, units: str, fmt: str,
                 speed: float = 0.0, accel: float = 0.0) -> None:
        self.scene, self.input_column, self.sweep, self.units, self.format = scene, input_column, sweep, units, fmt
        self.speed, self.accel = speed, accel
        self.source: str = "catalog"  # where the linkage came from, and the defaults that stood in for parameters
        self.defaults: dict[str, float] = {}

    @property
    def angle_columns(self) -> set[str]:
        """The outputs printed as angles (:func:`angle_outputs`): wrapped, and in ``units``."""
        return angle_outputs(self.scene.linkage, self.scene.outputs)

    @property
    def angles(self) -> numpy.ndarray:
        """Every input angle, in ``units``."""
        return self.sweep.array()

    def values_at(self, angles: numpy.ndarray) -> dict[str, object]:
        """The driven input's values at ``angles`` (in ``units``): its angle in radians, rate and acceleration."""
        from ..symbolic.vectors import acceleration, rate
        driven = self.scene.linkage.inputs[0]
        theta = to_radians(angles, self.units)
        values: dict[str, object] = {driven.name: theta}
        takes = self.scene.solver.arguments  # rates only where the outputs need them
        if rate(driven).name in takes:
            first = float(to_radians(self.sweep.first, self.units))
            values[rate(driven).name] = crank_speeds(theta, self.speed, self.accel, first)
        if acceleration(driven).name in takes:
            values[acceleration(driven).name] = self.accel
        return values


class _NewtonScene(Scene):
    """A scene of a linkage without a closed form: Newton's method from ``guess`` (each unknown by name, in
    radians) at the first input value, continued along the input values in their order, as ``symlink table NAME
    --guess ...`` solves it (:func:`symlink.numeric.newton_table.newton_results`); branch 1, its one assembly.

    Its table's facts and Newton solver come from the disk cache (:class:`~symlink.io.table_source.TableSource`),
    so a warm scene imports no SymPy; the linkage itself is built only when asked for.
    """

    def __init__(self, source: TableSource, outputs: Sequence[str], values: Mapping[str, object],
                 guess: Mapping[str, float]) -> None:
        self.table_source, self.facts = source, source.facts
        self.outputs, self.branch, self.values, self.guess = tuple(outputs), 1, dict(values), dict(guess)

    @cached_property
    def linkage(self) -> Linkage:  # type: ignore[override]  # built when asked for (SymPy), not to evaluate
        return self.table_source.found().linkage

    @cached_property
    def solver(self) -> Any:  # the cached Newton solver (symlink.numeric.cached_solver.CachedNewtonSolver)
        return self.table_source.solver()

    @cached_property
    def code(self) -> GeneratedCode:
        return GeneratedCode("", self.solver.source, self.solver.function)

    def evaluate(self, **values) -> dict[int, Results]:
        """The outputs on branch 1 at the scene's values updated by ``values`` (the input in radians, its rate and
        acceleration, the parameters), solved from the scene's guess at the first input value."""
        merged = {**self.values, **values}
        parameters = set(self.facts["parameters"])
        inputs = {name: value for name, value in merged.items() if name not in parameters}
        block = newton_results(self.facts, lambda: self.solver, merged, inputs, [self.guess])[1]
        shown = {**{name: block[name] for name in self.outputs}, "assembled": block["assembled"]}
        units = self.facts["column_units"]
        return {1: Results(shown, {name: units.get(name, "") for name in shown}, merged, self.solver.input_units)}

    def __repr__(self) -> str:
        return f"Scene({self.facts['name']!r}, {list(self.outputs)}, branch=1)"


class NewtonSceneFile(SceneFile):
    """A scene file of a linkage without a closed form, with its ``[guess]`` (checked by
    :func:`symlink.io.scene_text.newton_scene`): a :class:`SceneFile` whose scene is solved by Newton's method from
    the guess, as ``symlink run`` solves it, over the whole sweep at once (:attr:`SceneFile.angles`).

    ``column_units``: each printed column's unit (a table's header).
    """

    def __init__(self, source: TableSource, plain: NewtonScene, defaults: Mapping[str, float]) -> None:
        labels = source.facts["newton"]["unknowns"]  # label: name
        guess = {labels[label]: float(to_radians(value, plain.units)) for label, value in plain.guess.items()}
        super().__init__(_NewtonScene(source, plain.outputs, plain.values, guess), plain.input_column, plain.sweep,
                         plain.units, plain.format, plain.speed, plain.accel)
        self.column_units = dict(plain.column_units)
        self._facts, self._parameters = source.facts, plain.values
        self._angle_outputs = set(plain.angle_columns) - {plain.input_column}
        self.source, self.defaults = ("catalog", {}) if not defaults else (source.source, dict(defaults))
        self.scene.values.update(self.values_at(self.angles))

    @property
    def angle_columns(self) -> set[str]:
        """The outputs printed as angles: wrapped, and in ``units``."""
        return set(self._angle_outputs)

    def values_at(self, angles: numpy.ndarray) -> dict[str, object]:
        """The driven input at ``angles`` (in ``units``): its angle in radians, its rate and acceleration."""
        theta = to_radians(angles, self.units)
        speeds = crank_speeds(theta, self.speed, self.accel, float(to_radians(self.sweep.first, self.units)))
        return table_inputs(self._facts, self._parameters, theta, speeds, self.accel)


def _newton_scene_file(data: Mapping, folder: str | Path) -> NewtonSceneFile | None:
    """The scene of parsed ``data`` with a ``[guess]`` table whose linkage (a catalog name or a linkage file) is
    keyed, solved by Newton's method (its facts and solver from the disk cache: no SymPy when warm); ``ValueError``
    naming the first bad key or value, and for a linkage with a closed form.  None for any other scene."""
    linkage = data.get("linkage")
    if "guess" not in data or not isinstance(linkage, str):
        return None
    request = linkage_request(linkage, folder)
    if request is None:
        return None
    from_file = "file_sha256" in request
    source = TableSource(str(Path(folder) / linkage) if from_file else linkage)
    facts = source.facts
    return NewtonSceneFile(source, newton_scene(data, facts, defaults=from_file), facts["defaults"] if from_file else {})


def scene_from_mapping(data: Mapping, folder: str | Path = ".") -> SceneFile:
    """A :class:`SceneFile` from a parsed scene file; ``ValueError`` naming the first bad key or value.

    ``linkage`` is a catalog name or the path of a linkage file (relative to
    ``folder``, the scene file's folder); a linkage file's defaults stand in
    for parameters the scene leaves out.

    >>> found = scene_from_mapping({"linkage": "fourbar", "outputs": ["rocker"],
    ...                             "parameters": dict(a=20, b=66, c=56, d=80), "input": {"angles": [0]}})
    >>> round(float(numpy.degrees(found.scene.evaluate()[1]["rocker"][0])), 2)
    110.74

    A scene with a ``[guess]`` of a linkage without a closed form (the catalog's ``stephenson2``) is a
    :class:`NewtonSceneFile`, solved by Newton's method as ``symlink run`` solves it.
    """
    newton = _newton_scene_file(data, folder)
    if newton is not None:
        return newton
    data = _table(dict(data), "", TOP_KEYS)
    if "linkage" not in data:
        raise ValueError(f"missing key linkage (one of {', '.join(catalog_file_names())})")
    if not isinstance(data["linkage"], str):
        raise ValueError(f"linkage must be a catalog name or a linkage file, got {data['linkage']!r}")
    from ..symbolic.closure import is_angle
    from .linkage_file import LinkageFile, dynamic_model, load_linkage
    found = load_linkage(data["linkage"], folder)
    if "guess" in data and found.source == "catalog" and not found.linkage.has_closed_form:
        newton = _newton_scene_file({**data, "linkage": found.linkage.name}, folder)  # spelled otherwise: Stephenson II
        if newton is not None:
            return newton
    defaults = {} if found.source == "catalog" else found.defaults  # a catalog scene names every parameter
    outputs = data.get("outputs")
    if not isinstance(outputs, list) or not outputs or not all(isinstance(o, str) for o in outputs):
        raise ValueError(f"outputs must be a non-empty list of output names of {found.linkage.name} "
                         f"({', '.join(found.linkage.output_names())}), got {excerpt(outputs)}")
    twice = next((name for k, name in enumerate(outputs) if name in outputs[:k]), None)
    if twice is not None:  # a request that repeats itself: the same column twice
        raise ValueError(f"outputs lists {excerpt(twice)} more than once; list each output once")
    warm: DynamicScene | None = None
    if "dynamics" in data:  # mass properties and loads given in the scene, on a catalog linkage or a file's
        if found.model is not None:
            raise ValueError(f"dynamics: {data['linkage']} has a [dynamics] table of its own; give it in one place")
        if not set(outputs) <= set(found.linkage.output_names()):  # torques or joint forces: a cached request
            warm = DynamicScene(found.linkage, outputs, data["dynamics"])
        else:
            found = LinkageFile(found.linkage, found.defaults, found.source,
                                dynamic_model(data["dynamics"], found.linkage))
    if warm is None and found.model is not None and not set(outputs) <= set(found.linkage.output_names()):
        found = found.with_dynamics()  # torques or joint forces of a linkage file with a [dynamics] table
    linkage = found.linkage
    _check_guess(data, linkage)
    for name in outputs if warm is None else ():
        try:
            linkage.output(name)
        except ValueError:
            raise ValueError(f"outputs: {linkage.name} has no output {name!r}; "
                             f"it has {', '.join(linkage.output_names())}") from None
    branch = _choice(data.get("branch", 1), "branch", BRANCH_CHOICES)
    units = _choice(data.get("units", "deg"), "units", UNITS)
    fmt = _choice(data.get("format", "table"), "format", FORMATS)

    names = {s.name: s for s in linkage.parameters} if warm is None else warm.parameters
    given = _table(data.get("parameters", {}), "parameters", set(names))
    given = {**{n: v for n, v in defaults.items() if n in names}, **given}
    missing = [n for n in names if n not in given]
    if missing:
        raise ValueError(f"missing parameters.{missing[0]} ({linkage.name} needs {', '.join(names)})")
    parameters = {}
    for name, value in given.items():
        parameters[name] = _number(value, f"parameters.{name}", angle=is_angle(linkage, names[name]))
        if names[name].is_positive and parameters[name] <= 0:
            raise ValueError(f"parameters.{name} must be a positive length, got {value!r}")

    if len(linkage.inputs) != 1 or not is_angle(linkage, linkage.inputs[0]):
        raise ValueError(f"scene files drive linkages with one input angle; {linkage.name} has "
                         f"{', '.join(map(str, linkage.inputs))}")
    driven = linkage.inputs[0]
    sweep, speed, accel = input_table(data, units)
    scene = Scene(linkage, outputs, dict(parameters), branch) if warm is None else warm.scene(dict(parameters), branch)
    roles = [role for role, q in linkage.roles.items() if q == driven]
    scene_file = SceneFile(scene, roles[0] if roles else driven.name, sweep, units, fmt, speed, accel)
    scene_file.source, scene_file.defaults = found.source, defaults  # what a warm scene keeps (io.scene_text)
    scene.values.update(scene_file.values_at(sweep.array() if len(sweep) <= 4096 else sweep.block(0, 1)))
    return scene_file


def _check_guess(data: Mapping, linkage: Linkage) -> None:
    """``ValueError`` for a ``[guess]`` of a linkage with a closed form (where ``branch`` chooses the assembly), and
    for a linkage without one whose scene did not go to Newton's method (:class:`NewtonSceneFile`): it has no
    ``[guess]``, or its linkage could not be keyed."""
    if linkage.has_closed_form:
        if "guess" in data:
            raise ValueError(f"guess: {linkage.name} is solved in closed form, where branch chooses the assembly; "
                             "[guess] is for linkages without a closed form")
        return
    from ..symbolic.outputs import label
    unknowns = ", ".join(label(linkage, u) for u in linkage.unknowns)
    if "guess" not in data:
        raise ValueError(f"guess: {linkage.name} has no closed form: give a [guess] table of every unknown "
                         f"({unknowns}) at the first input angle, and symlink run solves it by Newton's method")
    raise ValueError(f"guess: {linkage.name} has no closed form, and its linkage could not be read again to solve "
                     "its scene by Newton's method; name it by its catalog name or a linkage file")


def scene_from_text(text: str, source: str, folder: str | Path = ".") -> SceneFile:
    """A :class:`SceneFile` from TOML text; ``ValueError`` starting with ``source`` on any problem.

    ``folder`` is where a linkage file named in the scene is looked for.
    """
    try:
        if len(text) > MAX_SCENE_BYTES:
            raise ValueError(f"larger than {MAX_SCENE_BYTES} bytes: not a scene file")
        data = toml_data(text)
        return scene_from_mapping(data, folder)
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None


def read_scene(path: str | Path) -> SceneFile:
    r"""Read and check a TOML scene file; ``ValueError`` starting with the file name on any problem.

    Parameters
    ----------
    path : str or pathlib.Path
        The scene file (TOML; see the scene file reference).

    Returns
    -------
    SceneFile
        The scene, its input sweep, units and output format; for a scene with a ``[guess]`` of a linkage without
        a closed form, a :class:`NewtonSceneFile`, solved by Newton's method as ``symlink run`` solves it (from the
        disk cache: a warm one imports no SymPy).

    Raises
    ------
    ValueError
        Starting with the file's name, for any problem.

    Examples
    --------
    >>> import symlink, tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "scene.toml"
    >>> _ = path.write_text('linkage = "fourbar"\noutputs = ["rocker"]\n[parameters]\na = 20\nb = 66\nc = 56\n'
    ...                     'd = 80\n[input]\nangles = [0, 90]\n')
    >>> found = symlink.read_scene(path)
    >>> found.scene.outputs, found.angles.tolist(), found.units
    (('rocker',), [0.0, 90.0], 'deg')
    """
    path = Path(path)
    return scene_from_text(read_input_text(path, MAX_SCENE_BYTES, "scene file"), str(path), path.parent)
