"""Where a linkage named by a catalog name, an atlas name or a linkage file comes from: its table's facts and its
solver, from the disk cache (SymPy-free when warm).

A table (``symlink table NAME|FILE``, the catalog's table commands, a scene solved by Newton's method), a sweep
(:mod:`symlink.workshop.sweep`) and a stack-up need of a linkage a few plain facts (names, labels, units, columns:
:func:`table_facts`) and a solver of its outputs.  :class:`TableSource` keys both by what names the linkage (the
catalog name or the file's bytes, :func:`symlink.io.scene_text.linkage_request`), derives them once (SymPy) and
reads them from the cache afterwards, so that a warm request builds no linkage.  The command line's table commands
(:mod:`symlink.cli.tables`) add their options and printing on top; nothing here reads an argparse namespace.

>>> from symlink.io.scene import catalog_linkage
>>> print(", ".join(table_columns(catalog_linkage("watt2"))))
crank, branch, coupler, rocker, coupler2, output, coupler_speed, rocker_speed, coupler2_speed, output_speed, coupler_accel, rocker_accel, coupler2_accel, output_accel
>>> facts = TableSource("fourbar").facts
>>> facts["parameters"], facts["branches"]
(['a', 'b', 'c', 'd'], ['branch'])
"""
from __future__ import annotations

import warnings
from functools import cached_property
from typing import TYPE_CHECKING, Any, Callable, Collection, Mapping

from ..common.angles import to_radians
from ..common.names import SixBarNameNote, former_name_note

if TYPE_CHECKING:
    from ..symbolic.linkage import Linkage

# The symbolic side (linkages, their labels, Solver: SymPy) is imported inside the functions that need it, so that
# a request whose facts and solver are in the disk cache never imports SymPy (symlink.numeric.cached_solver).

__all__ = ["TableSource", "table_facts", "table_columns", "newton_facts", "units_of_columns", "facts_values",
           "GENERIC_ENTRY_KIND", "GENERIC_SHAPING", "ANALYSIS_SHAPING", "MARGINS_ENTRY_KIND", "margins_entry"]


def table_columns(linkage: Linkage) -> list[str]:
    """The csv header of a linkage's table command."""
    from ..symbolic.outputs import label, table_outputs
    first, *further = linkage.inputs
    return [label(linkage, first), "branch"] + [label(linkage, x) for x in further] + list(table_outputs(linkage))


def newton_facts(linkage: Linkage) -> dict[str, Any]:
    """What a table solved by Newton's method needs of ``linkage``, as plain data (kept in a table's facts):
    the label of each unknown and its name, and the symbol each column shows."""
    from ..symbolic.outputs import label, table_outputs
    return {"unknowns": {label(linkage, u): u.name for u in linkage.unknowns},
            "outputs": dict(table_outputs(linkage))}


def units_of_columns(linkage: Linkage, columns: Collection[str]) -> dict[str, str]:
    """The unit of each column of ``linkage``'s table in radians (``rad``, ``rad/s``); none for a length (its
    unit is the user's, unknown here) or a column without one.  Plain data, kept in a table's facts.

    >>> from symlink.mechanism.catalog import slider_crank
    >>> units_of_columns(slider_crank(), ["crank", "branch", "conrod", "slider", "conrod_speed", "slider_speed"])
    {'crank': 'rad', 'conrod': 'rad', 'conrod_speed': 'rad/s'}
    """
    from ..numeric.units import output_units
    found = output_units(linkage, list(columns))
    return {name: unit for name, unit in found.items() if unit and "length" not in unit}


def table_facts(linkage: Linkage, defaults: Mapping[str, float] | None = None) -> dict[str, Any]:
    """What a table needs of ``linkage``, as plain data (JSON): names, labels, units, columns, the solved outputs.

    Kept in the disk cache beside the solver of ``symlink table NAME|FILE``, so that a warm table builds no
    linkage and imports no SymPy.
    """
    from ..symbolic.closure import is_angle
    from ..symbolic.outputs import label, table_outputs
    from ..symbolic.vectors import acceleration, rate
    named = linkage.parameters + linkage.inputs
    return {
        "name": linkage.name, "closed_form": bool(linkage.has_closed_form),
        "inputs": [x.name for x in linkage.inputs], "rates": [rate(x).name for x in linkage.inputs],
        "accelerations": [acceleration(x).name for x in linkage.inputs],
        "labels": {x.name: label(linkage, x) for x in linkage.inputs},
        "parameters": [s.name for s in linkage.parameters],
        "positive": [s.name for s in linkage.parameters + linkage.inputs[1:] if s.is_positive],
        "angles": [s.name for s in named if is_angle(linkage, s)],
        "branches": [b.name for b in linkage.branches],
        "outputs": dict(table_outputs(linkage)) if linkage.has_closed_form else {},
        "newton": None if linkage.has_closed_form else newton_facts(linkage),
        "columns": table_columns(linkage),
        "column_units": units_of_columns(linkage, table_columns(linkage)),
        "angle_columns": sorted({label(linkage, q) for q in linkage.coordinates if is_angle(linkage, q)}),
        "defaults": {name: float(value) for name, value in (defaults or {}).items()},
    }


#: The kind of cache entry of ``symlink table NAME|FILE`` (its facts, and its solver: :class:`TableSource`).
GENERIC_ENTRY_KIND = "generic-table/2"
#: Besides the code that shapes generated code: what reads a linkage file and what takes a table's facts from it,
#: and what an atlas name (atlas:NAME) stands for: the atlas's names and example drawings, and the joints reader.
GENERIC_SHAPING = ("io/linkage_file", "io/table_source", "mechanism/atlas", "mechanism/joints")
#: Besides what shapes a table's entries: the code whose text shapes the general analysis's facts and generated
#: modules (``symlink analyze NAME|FILE``), and the margins of a linkage's roots (:func:`margins_entry`).
ANALYSIS_SHAPING = ("analysis", "numeric/reachability", "numeric/cached_linkage", "mechanism/mobility", "cli/analyze")
#: The kind of the cache entry of the margins of a linkage's clamped roots (:func:`margins_entry`).
MARGINS_ENTRY_KIND = "root-margins/1"


def margins_entry(request: Mapping[str, str], linkage: Callable[[], Linkage]) -> dict[str, Any]:
    """The margins of the clamped roots of the linkage ``request`` names (:func:`symlink.io.scene_text.
    linkage_request`), from the disk cache: the namespace of their module
    (:func:`symlink.numeric.reachability.margins_entry_text`: the function ``margins`` and the dictionary
    ``MARGINS_DESCRIPTION`` of their roots, lengths, branch signs, rounding and C), derived once from ``linkage()``
    (SymPy).

    The one entry of the margins of a linkage named by what names it: ``symlink analyze NAME|FILE`` evaluates its
    ``margins`` and a sweep scans with it (:func:`symlink.numeric.design_scan.margin_spans`).  Keyed with the
    analysis's code (:data:`ANALYSIS_SHAPING`, which holds the margins' :mod:`symlink.numeric.reachability`), so
    that a warm analysis hashes no other code.

    >>> namespace = margins_entry({"catalog": "slider-crank"}, lambda: TableSource("slider-crank").found().linkage)
    >>> namespace["MARGINS_DESCRIPTION"]["roots"], sorted(namespace["margins"](a=1.0, b=4.0, offset=0.5,
    ...                                                                           theta=0.0, branch=1))
    ([['margin_0', 'ABC']], ['assembled', 'margin_0'])
    """
    from ..numeric.cache import cached_module, catalog_key

    def derive() -> str:
        from ..numeric.reachability import margins_entry_text
        return margins_entry_text(linkage())

    key = catalog_key("margins", [], MARGINS_ENTRY_KIND, dict(request), GENERIC_SHAPING + ANALYSIS_SHAPING)
    return cached_module(key, derive)[1]


def facts_values(facts: Mapping[str, Any], settings: Mapping[str, float], units: str,
                  extra: Collection[str] = ()) -> dict[str, float]:
    """The parameter values by symbol name (angles in radians) from a table's facts: the defaults updated by
    ``settings`` (``--set``, angles in ``units``), as :func:`symlink.cli.options.linkage_values` makes them of a
    linkage; ``ValueError`` naming a value the linkage does not take (``extra``: more names it takes).

    >>> facts_values(TableSource("fourbar").facts, {"a": 25.0}, "deg")["a"]
    25.0
    """
    known = facts["parameters"] + facts["inputs"]
    for name in settings:
        if name not in known and name not in extra:
            raise ValueError(f"--set: {facts['name']} has no value {name!r}; it takes {', '.join([*known, *extra])}")
    values = dict(facts["defaults"])
    values.update({name: float(to_radians(value, units)) if name in facts["angles"] else value
                   for name, value in settings.items()})
    return values


class TableSource:
    """A linkage named on the command line (a catalog name, an atlas name or a linkage file): its table's facts
    (:func:`table_facts`) and its solver, from the disk cache.

    The one home of a table's cache entries: ``symlink table NAME|FILE`` and the catalog's table commands
    (``symlink watt2``) key them by what names the linkage (:func:`symlink.io.scene_text.linkage_request`: the catalog
    name or the file's bytes), so that a warm table builds no linkage and imports no SymPy.  A former name
    (``stephenson3``) is noted on stderr in the same words warm or cold (:func:`symlink.common.names.former_name_note`).
    """

    #: Whether the linkage is read with its ``[dynamics]`` (a table's torques and forces); the analysis reads none.
    dynamics = True

    def __init__(self, source: str) -> None:
        from .scene_text import linkage_request
        self.source = source
        self.request = linkage_request(source)
        self._found: Any = None
        note = former_name_note(source) if self.request is not None else None
        if note is not None:
            warnings.warn(note, SixBarNameNote, stacklevel=2)
        self._noted = note is not None

    def found(self) -> Any:
        """The linkage file or catalog entry, read (SymPy): only where the cache has no entry yet."""
        if self._found is None:
            from .linkage_file import load_linkage
            with warnings.catch_warnings():
                if self._noted:  # said once already, in the same words
                    warnings.simplefilter("ignore", SixBarNameNote)
                found = load_linkage(self.source)
                self._found = found.with_dynamics() if self.dynamics else found  # [dynamics]: torques and forces
        return self._found

    def key(self, outputs: list[str]) -> str:
        """The cache key of the entry of ``outputs`` (``[]``: the facts; ``["newton"]``: Newton's solver)."""
        from ..numeric.cache import catalog_key
        return catalog_key("table", outputs, GENERIC_ENTRY_KIND, self.request, GENERIC_SHAPING)

    @cached_property
    def facts(self) -> dict[str, Any]:
        """:func:`table_facts` of the linkage with its defaults (from the cache where the linkage is keyed)."""
        import json
        from ..numeric.cache import cached_text

        def now() -> dict[str, Any]:
            return table_facts(self.found().linkage, self.found().defaults)
        return now() if self.request is None else json.loads(cached_text(self.key([]), lambda: json.dumps(now())))

    def solver(self) -> Any:
        """The solver of the table's outputs from the cache (:class:`~symlink.numeric.cached_solver.CachedSolver`,
        or :class:`~symlink.numeric.cached_solver.CachedNewtonSolver` without a closed form); None where the
        linkage is not keyed (a file too large to key: solved from the linkage itself)."""
        if self.request is None:
            return None
        facts = self.facts
        if facts["closed_form"]:  # derived once, with SymPy
            from ..numeric.cached_solver import CachedSolver, entry_text
            outputs = list(facts["outputs"].values())

            def full():
                from ..numeric.solver import Solver
                return Solver(self.found().linkage, outputs)

            return CachedSolver(facts["name"], outputs, key=self.key(outputs),
                                derive=lambda: entry_text(self.found().linkage, outputs), full=full)
        from ..numeric.cached_solver import CachedNewtonSolver, newton_entry_text  # its NumPy module: no SymPy when warm
        return CachedNewtonSolver(facts["name"], self.key(["newton"]), lambda: newton_entry_text(self.found().linkage))
