"""Design-space sweeps: properties of many designs of one linkage, chunk by chunk, on Dask, to Parquet.

A sweep varies some parameters of a linkage (a catalog name or a linkage
file) over a box: a ``grid`` (every combination of ``count`` evenly spaced
values of each, both ends included) or a ``random`` sample (``count`` designs,
uniform in the box, seeded).  Designs are numbered 0, 1, ... and made lazily
from that number, chunk by chunk, so memory stays bounded whatever their
number.  Inside a chunk the designs are evaluated together: one call of the
generated solver (compiled where a C compiler works, as a
:class:`~symlink.numeric.solver.Solver` would run it) a block of designs times
``samples`` input values over a turn, not a Python loop a design.

Chunks run on Dask: the local scheduler by default (``"threads"`` or
``"processes"``), or any ``distributed`` cluster by its address
(``"tcp://HOST:PORT"``).  Each chunk comes back as Parquet bytes and is
written atomically as ``chunk-NNNNNN.parquet`` in the output folder, beside
``manifest.json`` (the settings, the columns, and each chunk's rows, design
numbers and SHA-256: :mod:`symlink.io.sweep_folder`).  A sweep started again on
the same folder with the same settings skips the chunks already there and
verified, so an interrupted run continues where it stopped; a chunk that is
not what the manifest recorded is done again, with one warning; different
settings are refused; a sweep that could not end (a year, or more disk than
there is, even at optimistic rates) is refused before it starts.
Dask, distributed and pyarrow are the optional extra ``sweep``
(``pip install 'symlink-kinematics[sweep]'``).

The columns (a contract; angles in radians):

======================  ======================================================================
column                  what it holds
======================  ======================================================================
``design``              the design's number (int64): its grid index or its random sample's number
one per parameter       every parameter of the linkage (float64), the swept ones and the fixed ones
``assembles``           it assembles over the whole turn of its input (bool)
``reach``               the share of the turn where it assembles, 0 to 1 (its reachable range)
``spans``               how many separate intervals of the input it assembles in (int64)
``grashof``             the four-bar's Grashof class (``crank-rocker`` ...); empty for others
``transmission_min``    the smallest transmission angle (every two-angle loop) over the sampled
                        input values where it assembles; NaN without such a loop
``transmission_max``    the largest, likewise
``worst_transmission``  ``min(transmission_min, pi - transmission_max)``: how near it locks
``stroke``              the chosen output's travel between its two limit positions, when it
                        assembles over the turn and the output has exactly two; else NaN
``time_ratio``          slow over quick stroke at constant input speed (1 or more), likewise
``path_K_re``           real part of the Fourier coefficient ``c_K`` of the chosen point's path
                        ``x + i y = sum c_K exp(i K input)`` over the turn, ``K`` from ``-H``
                        to ``H``, written ``m2, m1, 0, p1, p2`` for H = 2: the centre (``0``),
                        the ellipse of best fit (``p1``, ``m1``), the shape's detail; NaN unless
                        it assembles over the turn
``path_K_im``           its imaginary part
======================  ======================================================================

The reachable range comes from :mod:`symlink.numeric.reachability` (the four-bar's
closed form; for another linkage the sampled mask where every sample
assembles, else its bisected scan, every design of a chunk at once:
:func:`~symlink.numeric.reachability.design_spans`'s scan, :func:`~symlink.numeric.design_scan.margin_spans`,
which scans every 20th point first and the points between only where a root's margin may change sign); the
Grashof class from :func:`~symlink.analysis.grashof.grashof_names` (all designs
at once); the transmission angle from the four-bar's ``transmission`` output,
or for another linkage from its solved coordinates
(:func:`~symlink.analysis.joint_angles.joint_angle_arrays` of its joints' recipes,
plain data kept with its facts).  Extremes are the samples' refined by the parabola through each extreme
and its neighbours (errors of order ``step**3``).

Every chunk is computed by the same code: where the compiled backend is being
built (the first sweep of a linkage on a machine with a C compiler), the sweep
waits for it (once a process) rather than answering with NumPy meanwhile, so a
resumed sweep ends with the very table of one whole run.

Warm is warm: what a sweep needs of its linkage (:func:`sweep_facts`), its
solver and the margins of its roots are cache entries keyed by what names the
linkage (the catalog or atlas name, or the SHA-256 of the file's text), derived
once with SymPy; a later sweep, and every worker of this one, reads them and
builds no linkage (no SymPy), and computes the very chunks a cold run does.

>>> settings = SweepSettings("fourbar", {"a": (0.2, 0.4)}, values={"b": 1.0, "c": 1.0, "d": 1.0}, count=3)
>>> table = evaluate_designs(settings, range(3))
>>> table["a"].tolist(), table["grashof"]
([0.2, 0.30000000000000004, 0.4], ['crank-rocker', 'crank-rocker', 'crank-rocker'])
"""
from __future__ import annotations

import hashlib
import json
import math
import sys
from dataclasses import asdict, dataclass, field
from functools import lru_cache, partial
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Iterable, Mapping, Sequence

import numpy

from ..analysis.joint_angles import joint_angle_arrays, joint_coordinates
from ..common.limits import require_memory
from ..io.sweep_folder import (MANIFEST, SweepWarning, chunk_name, chunk_range, open_folder, parquet_bytes, read_manifest,
                               verified_chunks)
from ..io.table_source import GENERIC_SHAPING
from ..numeric.compiled_library import BUILD_WAIT
from ..numeric.crank_ranges import crank_range
from ..version import __version__

if TYPE_CHECKING:
    from ..io.linkage_file import LinkageFile
    from ..symbolic.linkage import Linkage

# The symbolic side (the linkage, its solver's derivation, SymPy) is imported inside the functions that need it: a
# sweep whose linkage's facts and solver are in the disk cache (a warm sweep, and every worker process of a sweep
# once its first chunk is done) builds no linkage and imports no SymPy (:func:`linkage_facts`, :func:`_solver`).

__all__ = ["SweepSettings", "evaluate_designs", "design_values", "columns", "run_sweep", "read_sweep",
           "SWEEP_EXTRA", "MANIFEST", "SCHEDULERS", "missing_modules", "chunk_name", "chunk_table", "sweep_cost",
           "SweepWarning", "local_scheduler"]

#: What to install for sweeps.
SWEEP_EXTRA = "pip install 'symlink-kinematics[sweep]'"
#: Dask's local schedulers by name (any other scheduler is a distributed cluster's address).
SCHEDULERS = ("threads", "processes", "synchronous")
#: Values (designs times samples) a solver call evaluates at once: fast in NumPy, small in memory.
BLOCK_VALUES = 1 << 16
#: The most designs a sweep may number (the design numbers are int64).
MAX_DESIGNS = 1 << 62
MODES = ("grid", "random")
#: Bytes a chunk holds for each design and sample: its arrays (a complex path among them) and temporaries.
CHUNK_BYTES_PER_VALUE = 8 * 12
#: Rounds of :func:`_polish`: each one takes the bracket of an extreme down by a factor of 8.
POLISH_ROUNDS = 4
#: Designs a worker evaluates a second, at best: about twice the best measured (a four-bar at 60 samples, 11,600
#: designs/s on one core); a slider-crank managed 540 to 750.  Only for refusing sweeps that cannot end.
FASTEST_DESIGNS_PER_SECOND = 20_000
#: Bytes of Parquet a design takes, at least (measured 50 to 170 in chunks of 1000 designs).
LEAST_BYTES_PER_DESIGN = 16
#: A sweep that even at :data:`FASTEST_DESIGNS_PER_SECOND` would take longer than this is refused (a year).
LONGEST_SWEEP_SECONDS = 365 * 86400
#: The kind of cache entry of a sweep's facts of its linkage (:func:`linkage_facts`) and of its solvers, keyed by
#: what names the linkage (the catalog or atlas name, or the digest of the linkage file's text).
SWEEP_ENTRY_KIND = "sweep/1"
#: What shapes those entries besides the code that shapes generated code: what reads a linkage and names it
#: (:data:`symlink.io.table_source.GENERIC_SHAPING`) and what takes a sweep's facts from it (this module, and the
#: joints' recipes of :mod:`symlink.analysis.transmission`).
SWEEP_SHAPING = (*GENERIC_SHAPING, "workshop/sweep", "analysis/transmission")


def missing_modules(names: Sequence[str] = ("dask", "distributed", "pyarrow")) -> list[str]:
    """The modules of the ``sweep`` extra that cannot be imported here."""
    import importlib.util
    return [name for name in names if importlib.util.find_spec(name) is None]


def _require(names: Sequence[str]) -> None:
    missing = missing_modules(names)
    if missing:
        raise ImportError(f"sweeps need {', '.join(missing)}: {SWEEP_EXTRA}")


@dataclass(frozen=True)
class SweepSettings:
    """What a sweep evaluates: everything that decides its table (stored in the manifest).

    ``linkage``: a catalog name or a linkage file's path; ``ranges``: the swept
    parameters, ``(low, high)`` each; ``values``: the other parameters and any
    held input (the catalog's example or the file's defaults fill in the rest);
    ``mode``: ``"grid"`` (``count`` values a parameter) or ``"random"``
    (``count`` designs, ``seed``); ``samples``: input values over the turn;
    ``output``: the output whose stroke and time ratio are found (default: the
    last role, a four-bar's rocker); ``point``: the point whose path is
    described (default: the last point with a path); ``harmonics``: H;
    ``branch``: every branch sign; ``chunk``: designs a chunk.

    Parameters
    ----------
    linkage : str
        A catalog name or a linkage file's path.
    ranges : mapping of str to (float, float)
        The swept parameters' ranges.
    values : mapping of str to float, optional
        The other parameters and held inputs.
    mode : {"grid", "random"}, optional
        ``count`` values a parameter, or ``count`` random designs.
    count : int, optional
        See ``mode`` (default 10).
    seed : int, optional
        The random designs' seed.
    samples : int, optional
        Input values over the turn (default 360).
    output : str, optional
        The output whose stroke and time ratio are found.
    point : str, optional
        The point whose path is described.
    harmonics : int, optional
        The path descriptors' order (default 3).
    branch : int, optional
        Every branch sign (default 1).
    chunk : int, optional
        Designs a chunk (default 1000).
    linkage_text : str, optional
        The linkage file's text, kept in the manifest.

    Examples
    --------
    >>> import symlink
    >>> settings = symlink.SweepSettings("fourbar", {"a": (0.2, 0.4)}, values={"b": 1.0, "c": 1.0, "d": 1.0}, count=3)
    >>> settings.designs, settings.mode
    (3, 'grid')
    """

    linkage: str
    ranges: Mapping[str, tuple[float, float]]
    values: Mapping[str, float] = field(default_factory=dict)
    mode: str = "grid"
    count: int = 10
    seed: int = 0
    samples: int = 360
    output: str | None = None
    point: str | None = None
    harmonics: int = 3
    branch: int = 1
    chunk: int = 1000
    linkage_text: str | None = None  # a linkage file's text, so that workers anywhere read the same linkage

    def __post_init__(self) -> None:
        facts = sweep_facts(self.linkage, self.linkage_text)  # from the disk cache where it has them: no SymPy
        name = facts["name"]
        object.__setattr__(self, "ranges", {name: (float(low), float(high))
                                            for name, (low, high) in dict(self.ranges).items()})
        object.__setattr__(self, "values", {name: float(value) for name, value in dict(self.values).items()})
        if self.linkage_text is None and facts["kind"] == "file":
            object.__setattr__(self, "linkage_text", Path(self.linkage).read_text(encoding="utf-8"))
        parameters = facts["parameters"]
        positive = set(facts["positive"])
        if not self.ranges:
            raise ValueError(f"a sweep varies at least one parameter of {name}: "
                             f"{', '.join(parameters)}")
        for swept, (low, high) in self.ranges.items():
            if swept not in parameters:
                raise ValueError(f"{name} has no parameter {swept!r}; it has {', '.join(parameters)}")
            if not (math.isfinite(low) and math.isfinite(high)) or high < low:
                raise ValueError(f"the range of {swept} must be two finite numbers, low < high; got {low:g}:{high:g}")
            if high == low and not (self.mode == "grid" and self.count == 1):  # one design is one value a parameter
                raise ValueError(f"the range {swept}={low:g}:{high:g} has zero length (every design would be the same):"
                                 f" give {swept} as a value instead (--set {swept}={low:g})")
            if swept in positive and low <= 0:
                raise ValueError(f"{swept} is a length: its range must be positive, got {low:g}:{high:g}")
        held = facts["inputs"][1:]
        for given, value in self.values.items():
            if given not in parameters and given not in held:
                raise ValueError(f"{name} takes values for {', '.join([*parameters, *held])}; not {given!r}")
            if not math.isfinite(value):
                raise ValueError(f"{given} must be a finite number, got {value}")
        missing = [n for n in [*parameters, *held] if n not in self.ranges and n not in self.fixed]
        if missing:
            raise ValueError(f"give {name} a value or a range for {', '.join(missing)}")
        if not facts["closed_form"]:
            raise ValueError(f"{name} has no closed form: a sweep needs one (its assemblies are chosen by sign)")
        if not facts["input_is_angle"]:
            raise ValueError(f"{name}'s input is not an angle: a sweep evaluates designs over a turn")
        if self.mode not in MODES:
            raise ValueError(f"mode must be 'grid' or 'random', got {self.mode!r}")
        for setting, value, least in (("count", self.count, 1), ("samples", self.samples, 8), ("chunk", self.chunk, 1),
                                      ("harmonics", self.harmonics, 0)):
            if isinstance(value, bool) or not isinstance(value, int) or value < least:
                raise ValueError(f"{setting} must be a whole number, at least {least}; got {value!r}")
        if self.samples > 100_000:
            raise ValueError(f"samples must be at most 100000 a turn, got {self.samples}")
        if 2 * self.harmonics + 1 > self.samples:
            raise ValueError(f"{self.harmonics:,} harmonics need at least {2 * self.harmonics + 1:,} samples a turn; "
                             f"with {self.samples:,} samples use at most {(self.samples - 1) // 2:,} harmonics")
        if self.mode == "grid" and self.count == 1 and any(low != high for low, high in self.ranges.values()):
            raise ValueError("a grid of 1 value a parameter cannot span a range: give count 2 or more")
        _require_chunk_memory(min(self.chunk, self.designs), self.samples)
        if self.designs > MAX_DESIGNS:
            raise ValueError(f"{self.designs:.3g} designs are too many to number (at most 2^62, and a sweep that "
                             "can end has far fewer): ask for fewer values a parameter (--grid) or designs (--random)")
        if self.branch not in (1, -1) or isinstance(self.branch, bool):
            raise ValueError(f"branch must be +1 or -1, got {self.branch!r}")
        if not isinstance(self.seed, int) or isinstance(self.seed, bool) or self.seed < 0:
            raise ValueError(f"seed must be a whole number, at least 0; got {self.seed!r}")
        if self.output is None:
            object.__setattr__(self, "output", facts["default_output"])
        _position_output(facts, str(self.output))
        if self.point is None:
            moving = facts["moving_points"]
            object.__setattr__(self, "point", moving[-1] if moving else None)
        if self.point is None or self.point not in facts["points"]:
            raise ValueError(f"{name} has no point {self.point!r}; it has {', '.join(facts['points'])}")

    def facts(self) -> dict[str, Any]:
        """What the sweep needs of its linkage, as plain data (:func:`sweep_facts`; from the disk cache)."""
        return sweep_facts(self.linkage, self.linkage_text)

    def found(self) -> LinkageFile:
        """The linkage and its default values (read, SymPy: a sweep needs it only where its facts and solvers are
        not in the disk cache, and for the rare design whose reach is scanned one by one)."""
        return _linkage(self.linkage, self.linkage_text)

    @property
    def fixed(self) -> dict[str, float]:
        """The values of everything not swept: the defaults updated by ``values``."""
        defaults = {name: value for name, value in self.facts()["defaults"].items() if name not in self.ranges}
        return {**defaults, **{k: v for k, v in self.values.items() if k not in self.ranges}}

    @property
    def designs(self) -> int:
        """How many designs the sweep has."""
        return self.count ** len(self.ranges) if self.mode == "grid" else self.count

    @property
    def chunks(self) -> int:
        """How many chunks the sweep has."""
        return -(-self.designs // self.chunk)

    def manifest(self) -> dict[str, Any]:
        """The settings as JSON data (a linkage file's text by its SHA-256)."""
        data = asdict(self)
        data["ranges"] = {name: list(bounds) for name, bounds in self.ranges.items()}
        text = data.pop("linkage_text")
        data["linkage_sha256"] = None if text is None else _text_digest(text)
        data["fixed"] = self.fixed
        return data


def _require_chunk_memory(designs: int, samples: int) -> None:
    """``ValueError`` if a chunk's designs-by-samples arrays (mask, output, complex path, temporaries) do not fit."""
    require_memory(designs * samples, CHUNK_BYTES_PER_VALUE, f"a chunk of {designs:,} designs x {samples} samples",
                   advice=lambda fits: f"give a chunk of at most {max(1, fits // samples):,} designs (--chunk)")


@lru_cache(maxsize=16)
def _linkage(source: str, text: str | None) -> LinkageFile:
    from ..io.linkage_file import linkage_from_text, load_linkage
    return load_linkage(source) if text is None else linkage_from_text(text, source)


def _request(source: str, text: str | None) -> dict[str, str] | None:
    """What names a sweep's linkage in a cache key, found without reading it (no SymPy): its catalog or atlas name,
    or the SHA-256 of a linkage file's text (``text``, as the workers have it; else read from ``source``, hashed
    once); None where it is none of these (the reader then says what is wrong).

    The text, not the file's bytes (as :func:`symlink.io.scene_text.linkage_request` hashes them by default): a
    worker has only the text, read with its line ends made ``\\n``, and must find the entries its sweep keyed.
    """
    if text is None:
        from ..io.scene_text import linkage_request
        return linkage_request(source, digest=lambda path: _text_digest(path.read_text(encoding="utf-8")))
    return {"file_sha256": _text_digest(text)}


def _text_digest(text: str) -> str:
    """The SHA-256 of a linkage file's text (UTF-8), hex: what names it in a sweep's keys and in its manifest."""
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _key(request: Mapping[str, str], outputs: Sequence[str]) -> str:
    """The cache key of a sweep's entry of ``outputs`` of the linkage ``request`` names (``[]``: its facts)."""
    from ..numeric.cache import catalog_key
    return catalog_key("sweep", list(outputs), SWEEP_ENTRY_KIND, dict(request), SWEEP_SHAPING)


def linkage_facts(found: LinkageFile) -> dict[str, Any]:
    """What a sweep needs of a linkage, as plain data (JSON): its names, which parameters are lengths and angles,
    its outputs and points, and how its transmission angles are found.

    Kept in the disk cache (:func:`sweep_facts`), so that a warm sweep, and each worker of a sweep, builds no
    linkage.  ``joints``: the recipes of the joints of its two-angle loops
    (:func:`symlink.analysis.transmission.joint_recipes`, which
    :func:`symlink.analysis.joint_angles.joint_angle_arrays` evaluates), where it has no ``transmission`` output.

    >>> from symlink.io.linkage_file import load_linkage
    >>> facts = linkage_facts(load_linkage("slider-crank"))
    >>> facts["parameters"], facts["default_output"], facts["moving_points"]
    (['a', 'b', 'offset'], 'slider', ['B', 'C'])
    >>> [(j["loop"], j["guide"], j["into"]["coordinate"], j["out"]["coordinate"]) for j in facts["joints"]]
    [('ABC', True, None, 'beta')]
    """
    from ..analysis.transmission import joint_recipes
    from ..io.scene import angle_outputs
    from ..symbolic.closure import is_angle
    linkage = found.linkage
    names = linkage.output_names()
    positions = [n for n in names if n != "singular" and not n.endswith(("_speed", "_accel", "dot"))]
    moving = set(linkage.unknowns) | set(linkage.inputs)
    roles = list(linkage.roles)
    transmission = "transmission" in names
    joints = list(joint_recipes(linkage)) if linkage.has_closed_form and not transmission else []
    return {
        "name": linkage.name, "kind": found.source if found.source in ("catalog", "atlas") else "file",
        "defaults": {name: float(value) for name, value in found.defaults.items()},
        "parameters": [s.name for s in linkage.parameters],
        "positive": [s.name for s in linkage.parameters if s.is_positive],
        "inputs": [q.name for q in linkage.inputs],
        "input_is_angle": bool(linkage.inputs) and bool(is_angle(linkage, linkage.inputs[0])),
        "angles": [s.name for s in linkage.parameters + linkage.inputs if is_angle(linkage, s)],
        "closed_form": bool(linkage.has_closed_form),
        "branches": [b.name for b in linkage.branches],
        "default_output": roles[-1] if roles else (linkage.unknowns[-1].name if linkage.unknowns else None),
        "outputs": names, "positions": positions,
        "angle_outputs": sorted(angle_outputs(linkage, positions)),
        "points": list(linkage.points),
        "moving_points": [name for name in linkage.points
                          if moving & (linkage.output(f"{name}_x").free_symbols
                                       | linkage.output(f"{name}_y").free_symbols)],
        "fourbar": _is_fourbar(linkage),
        "transmission": transmission,
        "joints": joints,
    }


@lru_cache(maxsize=16)
def _cached_facts(source: str, text: str | None, keyed: str | None) -> str:
    """The facts' JSON text, once a process for each linkage (``keyed``: its request as JSON, so that a file
    changed since is read again)."""
    request = None if keyed is None else json.loads(keyed)

    def now() -> str:
        return json.dumps(linkage_facts(_linkage(source, text)))

    if request is None:  # not keyed (a file too large to key, or one that cannot be read: its reader says why)
        return now()
    from ..numeric.cache import cached_text
    return cached_text(_key(request, []), now)


def sweep_facts(source: str, text: str | None = None) -> dict[str, Any]:
    """:func:`linkage_facts` of a catalog name, an atlas name or a linkage file (``text``: the file's text, as a
    sweep's workers have it), from the disk cache: derived once (SymPy), then read without building the linkage.

    >>> sweep_facts("fourbar")["positive"]
    ['a', 'b', 'c', 'd']
    """
    request = _request(source, text)
    return json.loads(_cached_facts(source, text, None if request is None else json.dumps(request, sort_keys=True)))


def _position_output(facts: Mapping[str, Any], output: str) -> None:
    names = facts["outputs"]
    if output not in names or output == "singular" or output.endswith(("_speed", "_accel", "dot")):
        raise ValueError(f"{facts['name']} has no position output {output!r}; it has {', '.join(facts['positions'])}")


def design_values(settings: SweepSettings, designs: Iterable[int]) -> dict[str, numpy.ndarray]:
    """The swept parameters of the numbered designs, by name (arrays, in the order of ``designs``).

    A grid design's number is its index in the grid (the first parameter varies
    slowest); a random design's values come from a generator seeded with
    ``(seed, chunk)``, so any chunk is made again alike on its own.

    >>> settings = SweepSettings("fourbar", {"a": (1, 2), "b": (3, 5)}, count=3)
    >>> {k: v.tolist() for k, v in design_values(settings, [0, 1, 5]).items()}
    {'a': [1.0, 1.0, 1.5], 'b': [3.0, 4.0, 5.0]}
    """
    numbers = numpy.asarray(list(designs), dtype=numpy.int64)
    if numbers.size and (numbers.min() < 0 or numbers.max() >= settings.designs):
        raise ValueError(f"design numbers run from 0 to {settings.designs - 1}")
    names = list(settings.ranges)
    if settings.mode == "grid":
        found = {}
        rest = numbers.copy()
        for name in reversed(names):
            index = rest % settings.count
            rest //= settings.count
            low, high = settings.ranges[name]
            found[name] = low + (high - low) * index / max(settings.count - 1, 1)
        return {name: found[name] for name in names}
    found = {name: numpy.empty(numbers.size) for name in names}
    chunks = numbers // settings.chunk
    for chunk in numpy.unique(chunks).tolist():
        draws = numpy.random.default_rng([settings.seed, chunk]).random((settings.chunk, len(names)))
        where = chunks == chunk
        rows = numbers[where] - chunk * settings.chunk
        for k, name in enumerate(names):
            low, high = settings.ranges[name]
            found[name][where] = low + (high - low) * draws[rows, k]
    return found


def columns(settings: SweepSettings) -> list[str]:
    """The table's column names, in order (see the module docstring)."""
    return (["design", *settings.facts()["parameters"], "assembles", "reach", "spans", "grashof",
             "transmission_min", "transmission_max", "worst_transmission", "stroke", "time_ratio"]
            + [f"path_{_harmonic(k)}_{part}" for k in _harmonics(settings.harmonics) for part in ("re", "im")])


def _harmonics(count: int) -> list[int]:
    return list(range(-count, count + 1))


def _harmonic(k: int) -> str:
    return "0" if k == 0 else f"{'p' if k > 0 else 'm'}{abs(k)}"


def _is_fourbar(linkage: Linkage) -> bool:
    return (linkage.name == "fourbar" and [s.name for s in linkage.parameters] == ["a", "b", "c", "d"]
            and [q.name for q in linkage.inputs] == ["theta"])


@lru_cache(maxsize=16)
def _solver(source: str, text: str | None, outputs: tuple[str, ...]) -> Any:
    """The sweep's solver of ``outputs`` of its linkage (``source`` and ``text`` as :func:`sweep_facts` takes
    them), made once a process from the disk cache: its NumPy module and the C source of its compiled backend,
    derived once (SymPy) and then loaded without building the linkage
    (:class:`~symlink.numeric.cached_solver.CachedSolver`); it answers as a
    :class:`~symlink.numeric.solver.Solver` of the linkage does, with the same code.  Where its compiled code is
    being built (the first request for it on this machine), it is waited for, so that a table never depends on
    when a background build finished (a sweep resumed computes its chunks with the code that computed the
    others).  A linkage the cache cannot key is solved by a ``Solver`` of the linkage itself."""
    request = _request(source, text)
    if request is None:
        from ..numeric.solver import Solver
        solver: Any = Solver(_linkage(source, text).linkage, list(outputs))
    else:
        from ..numeric.cached_solver import CachedSolver

        def derive() -> str:
            from ..numeric.cached_solver import entry_text
            from ..numeric.compiled_library import c_solver_source
            linkage = _linkage(source, text).linkage
            flagged = linkage.with_singular(list(outputs))
            try:
                c_solver: str | None = json.dumps(c_solver_source(linkage, flagged))
            except (OSError, ValueError, NotImplementedError, TypeError):
                c_solver = None  # a linkage the C printer cannot print: NumPy, as a Solver would
            return entry_text(linkage, list(outputs), c_solver=c_solver)

        solver = CachedSolver(sweep_facts(source, text)["name"], list(outputs), key=_key(request, outputs),
                              derive=derive, full=lambda: _linkage(source, text).linkage, compiled=True)
    solver.wait_for_backend(BUILD_WAIT)
    return solver


def _refined(values: numpy.ndarray, at: numpy.ndarray, step: float) -> tuple[numpy.ndarray, numpy.ndarray]:
    """The extreme of the parabola through the samples before, at and after index ``at`` of each row (cyclic).

    Returns the value and the input offset (in samples' units of ``step``).
    """
    rows = numpy.arange(values.shape[0])
    count = values.shape[1]
    before, here, after = (values[rows, (at - 1) % count], values[rows, at], values[rows, (at + 1) % count])
    curvature = before - 2 * here + after
    with numpy.errstate(all="ignore"):
        offset = numpy.where(curvature != 0, 0.5 * (before - after) / curvature, 0.0)
    offset = numpy.where(numpy.isfinite(offset) & (numpy.abs(offset) <= 1), offset, 0.0)
    value = here - 0.25 * (before - after) * offset
    value = numpy.where(numpy.isfinite(value), value, here)
    return value, offset * step


def evaluate_designs(settings: SweepSettings, designs: Iterable[int]) -> dict[str, Any]:
    """The table's rows for the numbered designs: a dict of columns (lists or arrays) by name.

    Parameters
    ----------
    settings : SweepSettings
        What to evaluate.
    designs : iterable of int
        The designs' numbers.

    Returns
    -------
    dict of str to list or numpy.ndarray
        The table's columns: the design numbers, parameters, Grashof class, transmission, stroke, path descriptors.

    Examples
    --------
    >>> import symlink
    >>> settings = symlink.SweepSettings("fourbar", {"a": (0.2, 0.4)}, values={"b": 1.0, "c": 1.0, "d": 1.0}, count=3)
    >>> table = symlink.evaluate_designs(settings, range(3))
    >>> table["a"].round(12).tolist(), table["grashof"]  # a + 1 < 1 + 1: crank-rockers
    ([0.2, 0.3, 0.4], ['crank-rocker', 'crank-rocker', 'crank-rocker'])
    """
    facts = settings.facts()
    parameters = facts["parameters"]
    if hasattr(designs, "__len__"):  # refused before anything is allocated
        _require_chunk_memory(len(designs), settings.samples)  # type: ignore[arg-type]
    numbers = numpy.asarray(list(designs), dtype=numpy.int64)
    _require_chunk_memory(numbers.size, settings.samples)
    swept = design_values(settings, numbers)
    fixed = settings.fixed
    table: dict[str, Any] = {"design": numbers}
    for name in parameters:
        table[name] = swept[name] if name in swept else numpy.full(numbers.size, float(fixed[name]))
    count = numbers.size
    samples = settings.samples
    step = 2 * math.pi / samples
    inputs = step * numpy.arange(samples)
    fourbar = facts["fourbar"]
    transmission_output = facts["transmission"]
    outputs = [settings.output, f"{settings.point}_x", f"{settings.point}_y"]
    # transmission angles from the coordinates and the joints' recipes (plain data: no linkage)
    joints = facts["joints"]
    if transmission_output:
        outputs.append("transmission")
    else:
        outputs += joint_coordinates(joints)
    solver = _solver(settings.linkage, settings.linkage_text, tuple(dict.fromkeys(outputs)))
    input_name = facts["inputs"][0]
    held = {name: fixed[name] for name in facts["inputs"][1:]}
    mask = numpy.zeros((count, samples), dtype=bool)
    output = numpy.full((count, samples), numpy.nan)
    path = numpy.full((count, samples), numpy.nan, dtype=complex)
    mu = numpy.full((count, samples), numpy.nan)
    block = max(1, BLOCK_VALUES // samples)
    for first in range(0, count, block):
        rows = slice(first, min(first + block, count))
        arguments = {name: (table[name][rows, None] if name in swept else float(fixed[name]))
                     for name in parameters}
        arguments.update({input_name: inputs[None, :], **held})
        arguments.update({name: settings.branch for name in solver.branches})
        solved = solver(**arguments)
        mask[rows] = solved["assembled"]
        output[rows] = solved[settings.output]
        path[rows] = solved[f"{settings.point}_x"] + 1j * solved[f"{settings.point}_y"]
        if transmission_output:
            mu[rows] = solved["transmission"]
        elif joints:  # every design of the block at once
            with numpy.errstate(all="ignore"):
                mu[rows] = numpy.fmin.reduce(list(joint_angle_arrays(joints, arguments, solved).values()))
    output[~mask] = numpy.nan
    path[~mask] = numpy.nan
    mu[~mask] = numpy.nan

    # reachable range: the four-bar's closed form; else every sample, or the bisected scan
    reach, spans, assembles, classes = numpy.zeros(count), numpy.zeros(count, dtype=numpy.int64), \
        numpy.zeros(count, dtype=bool), [""] * count
    sampled_full = numpy.asarray(mask.all(axis=1))
    scanned: dict[int, list[tuple[float, float]]] = {}
    partial = numpy.flatnonzero(~sampled_full)
    if not fourbar and partial.size and facts["closed_form"]:  # every partial design's scan at once
        values_of = {name: table[name][partial] for name in parameters}
        values_of.update({**held, **{name: float(settings.branch) for name in facts["branches"]}})
        scanned = dict(zip(partial.tolist(), _design_spans(settings, values_of, partial.size, input_name)))
    if fourbar:  # every design's class at once
        from ..analysis.grashof import grashof_names
        classes = grashof_names(table["a"], table["b"], table["c"], table["d"])
        lengths = list(zip(*(table[name].tolist() for name in "abcd")))
    for k in range(count):
        if fourbar:
            found_spans = crank_range(*lengths[k])
        elif sampled_full[k]:
            found_spans = [(-math.pi, math.pi)]
        elif k in scanned:
            found_spans = scanned[k]
        else:
            from ..numeric.reachability import InputMotion, reachable_range
            linkage = settings.found().linkage
            values = {name: float(table[name][k]) for name in parameters}
            motion = InputMotion(linkage, {**values, **held, **{name: settings.branch for name in facts["branches"]}})
            found_spans = list(reachable_range(linkage, motion.values, motion=motion).spans)
        spans[k] = len(found_spans)
        assembles[k] = found_spans == [(-math.pi, math.pi)]
        reach[k] = min(sum(high - low for low, high in found_spans) / (2 * math.pi), 1.0)
    assembles &= sampled_full
    table.update(assembles=assembles, reach=reach, spans=spans, grashof=classes)

    # transmission extremes over the assembled samples, refined where the turn is whole
    with numpy.errstate(all="ignore"):
        anywhere = numpy.isfinite(mu).any(axis=1)
        filled_low, filled_high = numpy.where(numpy.isfinite(mu), mu, numpy.inf), numpy.where(numpy.isfinite(mu),
                                                                                            mu, -numpy.inf)
        low_at, high_at = filled_low.argmin(axis=1), filled_high.argmax(axis=1)
        every = numpy.arange(count)
        low, _ = _refined(mu, low_at, step)
        high, _ = _refined(mu, high_at, step)
        low = numpy.where(assembles, numpy.clip(low, 0.0, math.pi), mu[every, low_at])
        high = numpy.where(assembles, numpy.clip(high, 0.0, math.pi), mu[every, high_at])
        low, high = numpy.where(anywhere, low, numpy.nan), numpy.where(anywhere, high, numpy.nan)
    table.update(transmission_min=low, transmission_max=high, worst_transmission=numpy.minimum(low, math.pi - high))

    # stroke and time ratio: exactly two limits of the output over a whole turn, each polished on the solver
    angle = settings.output in facts["angle_outputs"]
    with numpy.errstate(all="ignore"):
        steps = numpy.roll(output, -1, axis=1) - output
        if angle:
            steps = (steps + math.pi) % (2 * math.pi) - math.pi
        unwrapped = output[:, :1] + numpy.concatenate([numpy.zeros((count, 1)), numpy.cumsum(steps[:, :-1], axis=1)],
                                                      axis=1)
        signs = numpy.sign(steps)
        changes = numpy.count_nonzero((signs != numpy.roll(signs, 1, axis=1)) & (signs != 0), axis=1)
        two = assembles & (changes == 2) & numpy.isfinite(unwrapped).all(axis=1)
    table["stroke"] = numpy.full(count, numpy.nan)
    table["time_ratio"] = numpy.full(count, numpy.nan)
    if two.any():
        chosen = numpy.flatnonzero(two)
        curve = unwrapped[chosen]
        given = {name: (table[name][chosen, None] if name in swept else float(fixed[name])) for name in parameters}

        def evaluate(at: numpy.ndarray) -> numpy.ndarray:
            arguments = {**given, input_name: at, **held, **{name: settings.branch for name in solver.branches}}
            found = solver(**arguments)
            return numpy.where(found["assembled"], found[settings.output], numpy.nan)

        extremes = []
        for sign in (1.0, -1.0):
            at = curve.argmax(axis=1) if sign > 0 else curve.argmin(axis=1)
            value, shift = _refined(sign * curve, at, step)
            extremes.append(_polish(evaluate, inputs[at] + shift, sign * value, step, sign, angle))
        (top_at, top), (bottom_at, bottom) = extremes
        forward = (top_at - bottom_at) % (2 * math.pi)
        with numpy.errstate(all="ignore"):
            table["stroke"][chosen] = top - bottom
            table["time_ratio"][chosen] = (numpy.maximum(forward, 2 * math.pi - forward)
                                           / numpy.minimum(forward, 2 * math.pi - forward))

    # the path's Fourier coefficients over the whole turn
    coefficients = numpy.fft.fft(path, axis=1) / samples
    for k in _harmonics(settings.harmonics):
        value = coefficients[:, k % samples]
        table[f"path_{_harmonic(k)}_re"] = numpy.where(assembles, value.real, numpy.nan)
        table[f"path_{_harmonic(k)}_im"] = numpy.where(assembles, value.imag, numpy.nan)
    return table


def _polish(evaluate, at: numpy.ndarray, value: numpy.ndarray, step: float, sign: float,
            angle: bool) -> tuple[numpy.ndarray, numpy.ndarray]:
    """An extreme near ``at`` (largest for ``sign`` +1), polished by parabolas through the solver's values
    at ever closer points (an eighth of the width each round): to about 1e-9 of the input from a sample's."""
    width = step
    for _ in range(POLISH_ROUNDS):
        width /= 8
        found = evaluate(at[:, None] + width * numpy.array([-1.0, 0.0, 1.0]))
        if angle:  # the three on one sheet: unwrapped about the middle one
            found = found[:, 1:2] + (found - found[:, 1:2] + math.pi) % (2 * math.pi) - math.pi
            found += 2 * math.pi * numpy.round((value[:, None] - found[:, 1:2]) / (2 * math.pi))  # the curve's sheet
        new_value, shift = _refined(sign * found, numpy.ones(len(at), dtype=int), width)
        good = numpy.isfinite(found).all(axis=1)
        at = numpy.where(good, at + shift, at)
        value = numpy.where(good, sign * new_value, value)
    return at, value


def _design_spans(settings: SweepSettings, values: Mapping[str, Any], count: int, driven: str
                  ) -> list[list[tuple[float, float]]]:
    """The reachable spans of ``count`` designs (``values``) over a turn of the input ``driven``, as
    :func:`~symlink.numeric.reachability.design_spans` scans them, with the margins of the linkage's roots from
    the disk cache (:func:`_margins`): no linkage where the cache keys it."""
    from ..numeric.design_scan import margin_spans
    margins = _margins(settings.linkage, settings.linkage_text)
    if margins is None:
        from ..numeric.reachability import design_spans
        return design_spans(settings.found().linkage, values, count, input=driven)
    function, roots, lengths, branches, tolerance = margins
    return margin_spans(function, roots, lengths, branches, driven, values, count, tolerance)


@lru_cache(maxsize=16)
def _margins(source: str, text: str | None) -> tuple | None:
    """The margins of the linkage's clamped roots from the disk cache (the entry ``symlink analyze NAME|FILE``
    reads too: :func:`symlink.io.table_source.margins_entry`, derived once), compiled where a compiler works
    (:func:`~symlink.numeric.design_scan.fastest_margins`), their roots (name, loop), lengths, branch signs and
    rounding; None where the cache cannot key the linkage."""
    request = _request(source, text)
    if request is None:
        return None
    from ..io.table_source import margins_entry
    from ..numeric.design_scan import fastest_margins

    namespace = margins_entry(request, lambda: _linkage(source, text).linkage)  # a verified entry of a private cache
    described = namespace["MARGINS_DESCRIPTION"]
    function = fastest_margins(namespace["margins"], lambda: described["c_margins"], described["lengths"],
                               described["branches"])
    return (function, [tuple(root) for root in described["roots"]], described["lengths"], described["branches"],
            described["tolerance"])


# --- chunks, Parquet and Dask ------------------------------------------------------------------

def chunk_table(settings: SweepSettings, index: int) -> bytes:
    """Chunk ``index`` of the sweep evaluated, as the bytes of a Parquet file (what a worker returns)."""
    first, last = chunk_range(index, settings.designs, settings.chunk)
    found = evaluate_designs(settings, range(first, last + 1))
    return parquet_bytes({name: found[name] for name in columns(settings)})


def sweep_cost(settings: SweepSettings, workers: int) -> tuple[float, int]:
    """Lower bounds of a sweep's cost on ``workers`` workers: seconds, and bytes of Parquet on disk.

    Both are optimistic on purpose (a sweep is refused only when even they are
    too much): :data:`FASTEST_DESIGNS_PER_SECOND` a worker (about twice the
    best measured, a four-bar at 60 samples) and :data:`LEAST_BYTES_PER_DESIGN`
    (measured 50 to 170 bytes a design in a chunk of 1000).

    >>> settings = SweepSettings("fourbar", {"a": (1, 2), "b": (3, 4), "c": (5, 6)}, values={"d": 5.0}, count=10**5)
    >>> seconds, size = sweep_cost(settings, workers=2)
    >>> f"{settings.designs:.0e} designs: {seconds / 86400 / 365:.0f} years, {size / 1e15:.0f} PB at least"
    '1e+15 designs: 793 years, 16 PB at least'
    """
    return (settings.designs / (FASTEST_DESIGNS_PER_SECOND * max(1, workers)),
            settings.designs * LEAST_BYTES_PER_DESIGN)


def _free_bytes(folder: Path) -> int | None:
    """Bytes the sweep may still write in ``folder``: the free space of its disk and what its chunks hold now."""
    import shutil
    there = folder
    while not there.exists() and there != there.parent:
        there = there.parent
    try:
        usage = shutil.disk_usage(there)
    except OSError:
        return None
    if usage.total == 0:  # a pseudo file system (/proc): no size to go by
        return None
    free = usage.free
    if folder.is_dir():  # continuing: the chunks done already take part of the table's room
        for path in folder.glob("chunk-*.parquet"):
            try:
                free += path.lstat().st_size
            except OSError:
                pass
    return free


def _require_feasible(settings: SweepSettings, folder: Path, workers: int) -> None:
    """``ValueError`` (one line) before anything is written, for a sweep that even at the rates of
    :func:`sweep_cost` would not fit on the disk or not end within :data:`LONGEST_SWEEP_SECONDS`; it says the
    estimate and how many designs would do."""
    from ..common.limits import format_bytes
    seconds, size = sweep_cost(settings, workers)
    free = _free_bytes(folder)
    too_long, too_big = seconds > LONGEST_SWEEP_SECONDS, free is not None and size > free
    if not (too_long or too_big):
        return
    most = int(LONGEST_SWEEP_SECONDS * FASTEST_DESIGNS_PER_SECOND * max(1, workers))
    if free is not None:
        most = min(most, free // LEAST_BYTES_PER_DESIGN)
    if most < 1:
        advice = "free some space on that disk, or choose a folder on another"
    elif settings.mode == "random":
        advice = f"ask for at most {most:,} designs: a random sample of at most {most:,} (--random)"
    else:
        dimensions = len(settings.ranges)
        per = int(round(most ** (1 / dimensions)))
        while per > 1 and per ** dimensions > most:
            per -= 1
        while (per + 1) ** dimensions <= most:
            per += 1
        advice = f"ask for at most {most:,} designs: " + (
            f"a grid of at most {per:,} values a parameter (--grid) for {dimensions} parameters" if per >= 2
            else "fewer swept parameters")
    taken = next(f"{seconds / span:.3g} {unit}" for unit, span in (("years", 365 * 86400), ("days", 86400),
                                                                     ("hours", 3600), ("seconds", 1))
                 if seconds >= span or unit == "seconds")
    room = "" if free is None else f" ({folder}'s disk has {format_bytes(free)} free)"
    raise ValueError(f"a sweep of {settings.designs:.3g} designs needs at least {format_bytes(size)} of disk for "
                     f"its table{room} and at least {taken} on {workers} worker{'s' if workers > 1 else ''} "
                     f"(at {FASTEST_DESIGNS_PER_SECOND:,} designs/s each, an optimistic rate); {advice}")


def local_scheduler(chunks: int, workers: int | None = None) -> str:
    """The fastest local scheduler for ``chunks`` chunks to do (what ``scheduler="auto"`` runs on).

    ``"synchronous"`` (this process, no pool) for one chunk, one worker or one core: a pool only adds its
    start and the transfer of every table; else ``"threads"``: the solvers' work runs in NumPy or in the
    compiled C loop, both of which release the GIL, so threads share it without starting a Python (and
    importing symlink, and loading the solvers again) in each worker as processes do.  Measured
    (``benchmarks/sweep.py --blocked``, from the kernel's per-thread scheduler statistics): two worker
    threads spend 1 to 2 % of their time blocked on the GIL, for the four-bar and for Jansen's leg, so
    with a core each they would gain 1.6 to 1.9 times one; a process pool costs more CPU a design than
    threads (its start, and each chunk's table sent back) at every size measured.

    >>> local_scheduler(1), local_scheduler(8, workers=1), local_scheduler(8, workers=2)
    ('synchronous', 'synchronous', 'threads')
    """
    import os
    count = workers or os.cpu_count() or 1
    return "synchronous" if chunks <= 1 or count <= 1 else "threads"


def run_sweep(settings: SweepSettings, folder: str | Path, *, scheduler: Any = "auto", workers: int | None = None,
              progress: bool = False, window: int | None = None) -> dict[str, Any]:
    """Evaluate the sweep into ``folder`` (one Parquet file a chunk and the manifest), continuing a run there.

    ``scheduler``: ``"auto"`` (the fastest local one for the sweep's size,
    :func:`local_scheduler`), ``"threads"``, ``"processes"`` or ``"synchronous"`` (Dask's
    local schedulers, ``workers`` of them), or a ``distributed`` scheduler's
    address (``"tcp://HOST:PORT"``), or a ``distributed.Client``.  At most
    ``window`` chunks (default four a worker) are under way at once, so memory
    is bounded.  Returns what was done: designs, chunks written and skipped,
    seconds and designs per second.

    Before anything is written, a sweep too large to end (:func:`sweep_cost`)
    is refused.  The folder is verified as :mod:`symlink.io.sweep_folder`
    describes: continuing, a chunk that is not what the manifest recorded is
    done again (one :class:`~symlink.io.sweep_folder.SweepWarning`).  Worker
    processes (``"processes"``) ignore Ctrl-C, which the caller handles, and
    die with the process that started them (``kill -9`` of the sweep included).
    Interrupted or failed, the sweep keeps every chunk finished before.

    Parameters
    ----------
    settings : SweepSettings
        What to evaluate.
    folder : str or pathlib.Path
        The sweep's folder (made, or continued).
    scheduler : str or distributed.Client, optional
        ``"auto"``, ``"threads"``, ``"processes"``, ``"synchronous"``, a scheduler's address or a client.
    workers : int, optional
        How many local workers.
    progress : bool, optional
        Show a progress bar.
    window : int, optional
        Chunks under way at once (default four a worker).

    Returns
    -------
    dict
        ``designs``, ``chunks``, ``written``, ``skipped``, ``seconds`` and ``designs_per_second``.

    Examples
    --------
    >>> import symlink
    >>> settings = symlink.SweepSettings("fourbar", {"a": (0.2, 0.4)}, values={"b": 1.0, "c": 1.0, "d": 1.0}, count=3)
    >>> import tempfile
    >>> folder = tempfile.mkdtemp()
    >>> symlink.run_sweep(settings, folder, scheduler="synchronous")["written"]  # doctest: +SKIP
    1
    >>> # skipped: it needs Dask and pyarrow (the sweep extra) and takes seconds
    """
    import os
    import time
    local = isinstance(scheduler, str) and (scheduler in SCHEDULERS or scheduler == "auto")
    _require(("dask", "pyarrow") if local else ("dask", "distributed", "pyarrow"))
    client, own = None, False
    if not local:
        from distributed import Client
        if isinstance(scheduler, Client):
            client = scheduler
        elif isinstance(scheduler, str) and scheduler.startswith(("tcp://", "tls://", "inproc://", "ucx://")):
            try:  # reached before anything is written
                client, own = Client(scheduler, timeout="10s"), True
            except OSError as error:
                raise OSError(f"cannot reach the Dask scheduler at {scheduler}: {error}") from None
        else:
            raise ValueError(f"scheduler must be auto, {', '.join(SCHEDULERS)}, a cluster's address (tcp://HOST:PORT) "
                             f"or a distributed.Client; got {scheduler!r}")
    try:
        folder = Path(folder)
        count = (1 if scheduler == "synchronous" else workers or os.cpu_count() or 1) if client is None else \
            max(1, sum(client.nthreads().values()))
        _require_feasible(settings, folder, count)
        header = {"symlink": __version__, "settings": settings.manifest(), "columns": columns(settings)}
        with open_folder(folder, header, settings.designs, settings.chunk) as opened:
            todo = opened.todo
            skipped = settings.chunks - len(todo)
            started = time.perf_counter()
            bar = None
            if progress:
                try:
                    from tqdm import tqdm
                    bar = tqdm(total=settings.chunks, initial=skipped, unit="chunk", file=sys.stderr, desc="sweep")
                except ImportError:
                    bar = None
            written = 0

            def land(index: int, data: bytes) -> None:  # each chunk as soon as it is done
                nonlocal written
                opened.stage(index, data, rows=_parquet_rows(data))
                written += 1
                if bar is not None:
                    bar.update(1)

            try:
                if scheduler == "auto":
                    scheduler = local_scheduler(len(todo), workers)
                if client is None:
                    local_chunks(partial(chunk_table, settings), todo, str(scheduler), workers, window, land)
                else:
                    _cluster_chunks(settings, todo, client, window, land)
            finally:
                if bar is not None:
                    bar.close()
    finally:
        if own and client is not None:
            client.close()
    seconds = time.perf_counter() - started
    evaluated = sum(min(settings.chunk, settings.designs - k * settings.chunk) for k in todo)
    return {"designs": settings.designs, "chunks": settings.chunks, "written": written, "skipped": skipped,
            "seconds": seconds, "designs_per_second": evaluated / seconds if evaluated and seconds > 0 else math.nan}


def _parquet_rows(data: bytes) -> int:
    """The rows of the Parquet file ``data`` (from its footer); -1 when it is not one."""
    import pyarrow
    import pyarrow.parquet
    try:
        return int(pyarrow.parquet.read_metadata(pyarrow.BufferReader(data)).num_rows)
    except (pyarrow.ArrowException, OSError, ValueError):
        return -1


# --- worker processes that leave Ctrl-C to their parent and die with it -------------------------

#: prctl(2)'s option that has the kernel signal a process when its parent ends (Linux).
PR_SET_PDEATHSIG = 1
#: The warning filter that keeps multiprocessing's resource tracker quiet about a killed sweep's semaphores.
QUIET_TRACKER = "ignore::UserWarning:multiprocessing.resource_tracker"
#: How often a worker process looks for its parent, where the kernel cannot be asked to signal it (seconds).
WATCH_SECONDS = 0.5


def _worker_start(parent: int) -> None:
    """Initializer of a sweep's worker process: Ctrl-C is the parent's to handle (no worker tracebacks), and the
    worker ends when ``parent`` does, killed by the kernel (Linux) or by its own watch of ``parent``."""
    import os
    import signal
    import threading
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    direct = os.getppid() == parent
    if direct and sys.platform.startswith("linux"):
        try:
            import ctypes
            ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
        except (OSError, AttributeError):
            pass
    threading.Thread(target=_watch_parent, args=(parent, direct), daemon=True, name="symlink-watch-parent").start()


def _watch_parent(parent: int, direct: bool) -> None:
    """End this process as soon as ``parent`` is gone (its child: when this process is handed to another)."""
    import os
    import time
    while True:
        if direct:
            gone = os.getppid() != parent
        else:  # started by a fork server: ask for the parent by its number
            try:
                os.kill(parent, 0)
                gone = False
            except ProcessLookupError:
                gone = True
            except OSError:
                gone = False
        if gone:
            os._exit(1)
        time.sleep(WATCH_SECONDS)


def _process_pool(count: int) -> Any:
    """A pool of ``count`` worker processes (see :func:`_worker_start`), started now with Ctrl-C ignored.

    A worker takes seconds to import symlink before its initializer runs; a
    Ctrl-C meanwhile would print its traceback.  So the workers are started
    here, while this process ignores SIGINT (a disposition they inherit from
    their first instruction): one task each, submitted while none is idle yet.
    Off the main thread (where signals cannot be set) only the initializer
    ignores it.  Multiprocessing's resource tracker, started with the pool,
    is told not to warn of the pool's semaphores when this process is killed
    (``-W``, which spawned processes take from ``sys.warnoptions``).
    """
    import os
    import signal
    import threading
    from concurrent.futures import ProcessPoolExecutor

    import dask.multiprocessing
    previous = signal.getsignal(signal.SIGINT)
    ignore = previous is not None and threading.current_thread() is threading.main_thread()
    if ignore:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    options = list(sys.warnoptions)
    sys.warnoptions.append(QUIET_TRACKER)
    try:
        pool = ProcessPoolExecutor(count, mp_context=dask.multiprocessing.get_context(), initializer=_worker_start,
                                   initargs=(os.getpid(),))
        for _ in range(count):
            pool.submit(int)
    finally:
        sys.warnoptions[:] = options
        if ignore:
            signal.signal(signal.SIGINT, previous)
    return pool


def _stop_processes(pool: Any) -> None:
    """End a process pool's workers now (their chunks are lost; they would be done again).

    Through the executor's ``_processes``: ``concurrent.futures`` has no public way to end a pool's workers at
    once (``shutdown`` waits for the chunks under way, or leaves them running); absent, nothing is done.
    """
    for process in list((getattr(pool, "_processes", None) or {}).values()):
        try:
            process.terminate()
        except (OSError, ValueError, AttributeError):
            pass


def _local_get(scheduler: str) -> Callable[..., Any]:
    """Dask's scheduler function of a local scheduler's name (:data:`SCHEDULERS`)."""
    if scheduler == "synchronous":
        from dask.local import get_sync
        return get_sync
    if scheduler == "threads":
        from dask.threaded import get
        return get
    if scheduler == "processes":
        from dask.multiprocessing import get as get_processes
        return get_processes
    raise ValueError(f"scheduler must be one of {', '.join(SCHEDULERS)}, got {scheduler!r}")


def local_chunks(make: Callable[[int], bytes], todo: list[int], scheduler: str, workers: int | None,
                 window: int | None, land: Callable[[int, bytes], None]) -> None:
    """``make(index)`` for each chunk in ``todo`` on a local Dask scheduler, a window of chunks at a time:
    ``land(index, its bytes)`` as soon as each is done (in this thread: a Dask callback), so that a stop keeps
    every chunk done.  ``make`` must pickle for the ``processes`` scheduler.  The sweeps' and the tolerance
    Monte Carlo's one loop over chunks.

    Stopped early (an error, Ctrl-C), a process pool's workers are ended at once and a thread pool's are
    left to finish the chunk they are on, unwaited.
    """
    import os
    from concurrent.futures import Executor, ThreadPoolExecutor

    import dask
    from dask.callbacks import Callback
    # Dask's scheduler function itself, not its name: given a name, Dask imports distributed (a second) to look
    # for a client first.
    get = _local_get(scheduler)
    count = workers or os.cpu_count() or 1
    width = window or 4 * count
    # One pool for the whole sweep: Dask would start (and import symlink in) a new one every compute.
    pool: Executor | None = (_process_pool(count) if scheduler == "processes"
                             else ThreadPoolExecutor(count) if scheduler == "threads" else None)
    finished = False
    indices: dict[Any, int] = {}

    def done(key: Any, result: bytes, *rest: Any) -> None:
        if key in indices:  # not another computation's task
            land(indices.pop(key), result)

    try:
        with Callback(posttask=done):
            for start in range(0, len(todo), width):  # a window at a time: bounded memory, however many chunks
                tasks = [dask.delayed(make, pure=False)(k) for k in todo[start:start + width]]
                indices.update((task.key, k) for task, k in zip(tasks, todo[start:start + width]))
                dask.compute(*tasks, scheduler=get, pool=pool, num_workers=count)
                if indices:
                    raise RuntimeError(f"Dask did not report chunks {sorted(indices.values())} done")
        finished = True
    finally:
        if pool is not None:
            if not finished:
                _stop_processes(pool)
            pool.shutdown(wait=finished, cancel_futures=True)


def _cluster_chunks(settings: SweepSettings, todo: list[int], client: Any, window: int | None,
                    land: Callable[[int, bytes], None]) -> None:
    """Each chunk in ``todo`` on a distributed cluster: ``land(index, Parquet bytes)`` as each finishes."""
    from distributed import as_completed
    width = window or 4 * max(1, sum(client.nthreads().values()))
    pending = iter(todo)
    futures = {}
    for k in pending:
        futures[client.submit(chunk_table, settings, k, pure=False)] = k
        if len(futures) >= width:
            break
    running = as_completed(list(futures))
    try:
        for future in running:
            index = futures.pop(future)
            land(index, future.result())
            for k in pending:  # one more under way for each one done
                new = client.submit(chunk_table, settings, k, pure=False)
                futures[new] = k
                running.add(new)
                break
    finally:
        if futures:  # stopped early: what is under way is not wanted any more
            client.cancel(list(futures))


def read_sweep(folder: str | Path):
    """The table of a sweep's folder (a ``pyarrow.Table``, rows in design order), from the chunks done so far.

    Every chunk is checked against the manifest's record of it (size,
    SHA-256, rows, design numbers, columns): ``ValueError`` naming the first
    that is not what it should be (run the sweep again to rebuild it), never a
    table with a design twice or another sweep's rows.  The ``design`` column
    says which designs are in a table read while a sweep is under way.

    Parameters
    ----------
    folder : str or pathlib.Path
        A sweep's folder.

    Returns
    -------
    pyarrow.Table
        The rows of the chunks done so far, in design order.

    Raises
    ------
    ValueError
        Naming the first chunk that is not what the manifest recorded.

    Examples
    --------
    >>> import symlink
    >>> settings = symlink.SweepSettings("fourbar", {"a": (0.2, 0.4)}, values={"b": 1.0, "c": 1.0, "d": 1.0}, count=3)
    >>> import tempfile
    >>> folder = tempfile.mkdtemp()
    >>> _ = symlink.run_sweep(settings, folder, scheduler="synchronous")  # doctest: +SKIP
    >>> symlink.read_sweep(folder).column("a").to_pylist()  # doctest: +SKIP
    [0.2, 0.3, 0.4]
    >>> # skipped: it needs Dask and pyarrow (the sweep extra) and takes seconds
    """
    _require(("pyarrow",))
    import pyarrow
    import pyarrow.parquet
    folder = Path(folder)
    manifest, _ = read_manifest(folder)
    names = [str(name) for name in manifest["columns"]]
    tables = []
    for record, data in verified_chunks(folder):
        where = folder / record.name
        try:
            table = pyarrow.parquet.read_table(pyarrow.BufferReader(data))
        except (pyarrow.ArrowException, OSError, ValueError) as error:
            raise ValueError(f"{where} is not a Parquet file ({error}); run the sweep again to rebuild it") from None
        designs = table.column("design").to_numpy() if "design" in table.column_names else None
        if (table.column_names != names or table.num_rows != record.rows or designs is None
                or not numpy.array_equal(designs, numpy.arange(record.first, record.last + 1))):
            raise ValueError(f"{where} does not hold the rows of designs {record.first} to {record.last} in the "
                             "manifest's columns; run the sweep again to rebuild it")
        tables.append(table)
    if not tables:
        return pyarrow.table({name: [] for name in names})
    return pyarrow.concat_tables(tables)
