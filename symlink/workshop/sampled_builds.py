"""A Monte Carlo check of a tolerance stack-up: many builds drawn from its tolerance model and solved.

:func:`sample_builds` draws builds from the same model as :func:`~symlink.workshop.tolerance.stack_up` (each
dimension normal, its sigma from its band), solves them vectorised over the builds, in chunks of bounded memory
each from its own seeded generator, and sets their deviation's percentiles beside the linear prediction; with
``folder=`` on Dask, the chunks are written to a sweep's folder, so that a long check stops and resumes.
:func:`solved_builds` is the same from a solver alone (a warm command line: no SymPy).
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

import numpy

from ..common.display import record_html
from ..common.limits import format_bytes, require_memory
from .tolerance import Tolerance, TolerancesLike, input_values, stack_up, tolerance_arrays

if TYPE_CHECKING:  # the symbolic side is imported where a linkage is worked on
    from ..symbolic.linkage import Linkage

__all__ = ["SampledBuilds", "sample_builds", "solved_builds", "MAX_SAMPLED_VALUES", "BUILDS_PER_CHUNK",
           "BUILD_SCHEDULERS", "BUILDS_KIND"]


MAX_SAMPLED_VALUES = 50_000_000
#: Builds a chunk of :func:`sample_builds`: drawn from their own seeded generator and solved together.
BUILDS_PER_CHUNK = 10_000
#: Dask's local schedulers that :func:`sample_builds` runs its chunks on (``"auto"`` chooses one).
BUILD_SCHEDULERS = ("auto", "threads", "synchronous")
#: What the manifest of a folder of builds says it holds (a sweep's folder holds designs).
BUILDS_KIND = "tolerance builds"


@dataclass(frozen=True)
class SampledBuilds:
    """Builds drawn from a tolerance model and solved (see :func:`sample_builds`).

    ``deviation[i]`` is output i's deviation from its nominal value, shape (builds, input values) (angles
    wrapped to (-pi, pi]), NaN for a build that cannot be assembled there or has a dimension drawn
    non-positive where it must be positive; ``nominal[i, k]`` the nominal output; ``reused``: the chunks
    found done in the folder of a resumed run (0 in memory).
    """

    _repr_html_ = record_html  # a notebook shows its fields as a table

    outputs: tuple[str, ...]
    inputs: dict[str, numpy.ndarray]
    nominal: numpy.ndarray
    deviation: numpy.ndarray
    reused: int = 0

    @property
    def built(self) -> numpy.ndarray:
        """The share of builds assembled at each input value (outputs, inputs)."""
        return numpy.isfinite(self.deviation).mean(axis=1)

    def percentile(self, q: float | Sequence[float]) -> numpy.ndarray:
        """Percentiles ``q`` (0 to 100) of each output's deviation over the assembled builds at each input."""
        return numpy.nanpercentile(self.deviation, q, axis=1)

    @property
    def mean(self) -> numpy.ndarray:
        """The mean deviation over the assembled builds (outputs, inputs): compare with the mean shift."""
        return numpy.nanmean(self.deviation, axis=1)

    @property
    def standard_deviation(self) -> numpy.ndarray:
        """The deviation's standard deviation over the assembled builds (outputs, inputs)."""
        return numpy.nanstd(self.deviation, axis=1)


@dataclass(frozen=True)
class _BuildModel:
    """Everything a chunk of builds needs: it draws chunk ``index`` from its own generator, seeded by
    ``(seed, index)``, so that a chunk is the same whichever run, route or worker makes it."""

    solver: object
    outputs: tuple[str, ...]
    dimensions: tuple[str, ...]
    sigmas: numpy.ndarray
    positive: tuple[bool, ...]
    design: dict[str, float]
    sweep: dict[str, numpy.ndarray]
    nominal: numpy.ndarray
    angular: tuple[bool, ...]
    builds: int
    chunk: int
    seed: int

    def chunk_range(self, index: int) -> tuple[int, int]:
        first = index * self.chunk
        return first, min(first + self.chunk, self.builds)

    def draw(self, index: int) -> tuple[dict[str, numpy.ndarray], numpy.ndarray]:
        """Chunk ``index``: the dimensions drawn (each (size,)) and the outputs' deviations (outputs, size, inputs)."""
        from ..common.angles import wrap
        first, stop = self.chunk_range(index)
        size = stop - first
        generator = numpy.random.default_rng([self.seed, index])
        drawn = {name: self.design[name] + self.sigmas[j] * generator.standard_normal(size)
                 for j, name in enumerate(self.dimensions)}
        unmade = numpy.zeros((size, 1), dtype=bool)
        solved = {}
        for name, positive in zip(self.dimensions, self.positive):
            values = drawn[name][:, None].copy()
            if positive:
                unmade |= values <= 0
                values[values <= 0] = self.design[name]  # solved at the nominal, then thrown away
            solved[name] = values
        count = self.nominal.shape[1]
        found = self.solver(**{k: v[None, :] for k, v in self.sweep.items()},  # type: ignore[operator]
                            **{**self.design, **solved})
        good = numpy.broadcast_to(found["assembled"], (size, count)) & ~unmade
        deviation = numpy.empty((len(self.outputs), size, count))
        for i, name in enumerate(self.outputs):
            change = numpy.broadcast_to(found[name], (size, count)) - self.nominal[i]
            if self.angular[i]:
                change = wrap(change)
            deviation[i] = numpy.where(good, change, numpy.nan)
        return drawn, deviation

    def columns(self) -> list[str]:
        """The columns of a chunk's table: the build's number, each dimension drawn, each output's deviation
        at each input value (``rocker[3]``: at the fourth)."""
        count = self.nominal.shape[1]
        return ["build", *self.dimensions, *(f"{name}[{k}]" for name in self.outputs for k in range(count))]

    def table(self, index: int) -> bytes:
        """Chunk ``index`` as the bytes of a Parquet file (what a Dask task returns)."""
        from ..io.sweep_folder import parquet_bytes
        first, stop = self.chunk_range(index)
        drawn, deviation = self.draw(index)
        data = {"build": numpy.arange(first, stop, dtype=numpy.int64), **drawn}
        names = iter(self.columns()[1 + len(self.dimensions):])
        for i in range(len(self.outputs)):
            for k in range(deviation.shape[2]):
                data[next(names)] = deviation[i, :, k]
        return parquet_bytes(data)

    def settings(self, name: str, definition: str) -> dict[str, object]:
        """What decides the sample, as the folder's manifest keeps it (a resumed run must match it): ``name`` and
        ``definition`` are the linkage's name and the digest of its definition
        (:func:`~symlink.numeric.cache.definition_digest`, which a warm run reads from the cached facts)."""
        return {"kind": BUILDS_KIND, "linkage": name, "definition": definition,
                "outputs": list(self.outputs), "design": self.design,
                "sigmas": {name: float(s) for name, s in zip(self.dimensions, self.sigmas)},
                "inputs": {name: [float(v) for v in values] for name, values in self.sweep.items()},
                "seed": self.seed}


def _require_builds(builds: int, per_build: int, what: str) -> None:
    """``ValueError`` (one line, with the estimate and the most builds that would do) for builds of ``per_build``
    values each beyond :data:`MAX_SAMPLED_VALUES` or beyond the memory available: the deviations are kept, and
    joined from their chunks (twice their size for a moment)."""
    values = builds * per_build
    if values > MAX_SAMPLED_VALUES:
        raise ValueError(f"{what} are {values:,} values (about {format_bytes(16 * values)} of memory), more than the "
                         f"{MAX_SAMPLED_VALUES:,} sample_builds keeps; ask for at most "
                         f"{max(1, MAX_SAMPLED_VALUES // per_build):,} builds")
    require_memory(builds, 16 * per_build, f"keeping {what}",
                   advice=lambda fits: f"ask for at most {fits:,} builds")


def sample_builds(linkage: Linkage, outputs: str | Sequence[str], nominal: Mapping[str, float],
                  tolerances: TolerancesLike, inputs: Mapping[str, object] | None = None,
                  builds: int = 100_000, seed: int = 0, *, folder: str | os.PathLike | None = None,
                  scheduler: str = "auto", workers: int | None = None,
                  chunk: int = BUILDS_PER_CHUNK) -> SampledBuilds:
    """``builds`` linkages with each toleranced dimension drawn from a normal distribution (its sigma, a
    band read as 3 sigma: :class:`Tolerance`), about ``nominal``, solved at every input value.

    The Monte Carlo counterpart of :func:`stack_up`: where tolerances are small its percentiles agree
    with the linear bands, where they are large they show how far the linear model departs.  Closed
    forms only.  A dimension drawn non-positive where it must be positive (a length) is a build that
    cannot be made: NaN.

    The builds come in chunks of ``chunk``, each drawn from its own generator seeded by ``(seed, chunk
    number)``: a run repeats exactly, and the sample does not depend on where or in which order the chunks
    were made.  Without ``folder`` they are made here, in memory (NumPy only).  With ``folder`` they run
    as tasks on Dask (``scheduler``: ``"auto"``, ``"threads"`` or ``"synchronous"``, ``workers`` of them)
    and each chunk is written to the folder as it is done, as a sweep's are (Parquet chunks beside a
    manifest, verified when read: :mod:`symlink.io.sweep_folder`).  A long check can be stopped (Ctrl-C, a
    kill) and run again with the same arguments: it makes only the chunks missing and gives the same
    sample as a run never stopped (``reused`` counts the chunks found done).  Other arguments on the same
    folder are refused.  The folder needs the ``sweep`` extra (dask, pyarrow).

    Parameters
    ----------
    linkage : Linkage
        A linkage with a closed-form plan.
    outputs : str or sequence of str
        The outputs, as for :func:`stack_up`.
    nominal : mapping
        Every parameter's value and each branch sign.
    tolerances : mapping
        Dimension name -> a band (read as 3 sigma) or a :class:`Tolerance`.
    inputs : mapping, optional
        Input name -> the values to evaluate at (default: a full turn every 10 degrees).
    builds : int, optional
        How many builds (default 100000).
    seed : int, optional
        The seed of the chunks' generators (default 0).
    folder : str or os.PathLike, optional
        Run on Dask and keep each chunk in this folder (needs the ``sweep`` extra).
    scheduler : str, optional
        Dask's local scheduler with ``folder``: ``"auto"``, ``"threads"`` or ``"synchronous"``.
    workers : int, optional
        How many with ``folder``.
    chunk : int, optional
        Builds a chunk (default 10000).

    Returns
    -------
    SampledBuilds
        The deviations of every build from nominal, which builds could be made, and their percentiles.

    Examples
    --------
    >>> import symlink
    >>> sampled = symlink.sample_builds(symlink.fourbar(), "rocker", {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1},
    ...                                 {"b": 0.3}, inputs={"theta": [0.0]}, builds=1000)
    >>> sampled.deviation.shape, bool(sampled.built.all())
    ((1, 1000, 1), True)
    """
    from ..numeric.cache import definition_digest
    from ..numeric.solver import Solver
    from ..numeric.units import output_units
    chosen = [outputs] if isinstance(outputs, str) else list(outputs)
    if not linkage.has_closed_form:
        _check_sampling(builds, chunk, seed, scheduler)
        raise ValueError(f"{linkage.name} has no closed form: sample_builds solves closed forms only")
    # NumPy, not the compiled backend (which agrees to a few ulps): every chunk's last digits are the same in every
    # run, on every machine, with or without a C compiler; on blocks of builds the two are as fast (measured).
    return solved_builds(
        lambda: Solver(linkage, chosen, backend="numpy"), linkage.name, [q.name for q in linkage.inputs],
        {s.name: bool(s.is_positive) for s in linkage.parameters},
        lambda: [output_units(linkage, [o]).get(o) == "rad" for o in chosen], chosen, nominal, tolerances,
        inputs, builds, seed, folder=folder, scheduler=scheduler, workers=workers, chunk=chunk,
        settings=lambda model: model.settings(linkage.name, definition_digest(linkage)))


def _check_sampling(builds: int, chunk: int, seed: int, scheduler: str) -> None:
    """``ValueError`` for a number of builds, a chunk, a seed or a scheduler that :func:`sample_builds` cannot take."""
    for what, value in (("builds", builds), ("chunk", chunk)):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise ValueError(f"{what} must be a whole number >= 1, got {value!r}")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ValueError(f"seed must be a whole number >= 0, got {seed!r}")
    if scheduler not in BUILD_SCHEDULERS:
        raise ValueError(f"scheduler must be one of {', '.join(BUILD_SCHEDULERS)}, got {scheduler!r}")


def solved_builds(solver: Callable[[], Any], name: str, input_names: Sequence[str], parameters: Mapping[str, bool],
                  angular: Callable[[], Sequence[bool]], outputs: Sequence[str], nominal: Mapping[str, float],
                  tolerances: TolerancesLike, inputs: Mapping[str, object] | None = None, builds: int = 100_000,
                  seed: int = 0, *, folder: str | os.PathLike | None = None, scheduler: str = "auto",
                  workers: int | None = None, chunk: int = BUILDS_PER_CHUNK,
                  settings: Callable[[Any], dict[str, object]] | None = None) -> SampledBuilds:
    """:func:`sample_builds` of a closed-form solver of ``outputs`` without its linkage: what a warm ``symlink
    tolerance --samples`` runs (its solver from the disk cache, no SymPy).

    ``solver()`` makes the solver (NumPy: a :class:`~symlink.numeric.solver.Solver` or a cached one, with
    ``required`` and a call as theirs), once the arguments are checked; ``name`` and ``input_names`` are the
    linkage's; ``parameters`` maps each parameter's name to whether it must be positive (a length);
    ``angular()`` says which outputs are angles (wrapped); ``settings(model)``: what a folder's manifest keeps of
    the sample (needed with ``folder``).  The rest as for :func:`sample_builds`.

    >>> from symlink.numeric.cached_solver import CachedSolver
    >>> sampled = solved_builds(lambda: CachedSolver("fourbar", ["rocker"]), "fourbar", ["theta"],
    ...                         {"a": True, "b": True, "c": True, "d": True}, lambda: [True], ["rocker"],
    ...                         {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1}, {"b": 0.3}, {"theta": [0.0]}, 1000)
    >>> sampled.deviation.shape, bool(sampled.built.all())
    ((1, 1000, 1), True)
    """
    chosen = list(outputs)
    dimensions, _, sigmas = tolerance_arrays(tolerances)
    _check_sampling(builds, chunk, seed, scheduler)
    sweep = input_values(name, list(input_names), inputs)
    count = len(next(iter(sweep.values())))
    _require_builds(builds, count * len(chosen), f"{builds:,} builds x {count:,} input value{'s' if count != 1 else ''} x {len(chosen)} "
                    f"output{'s' if len(chosen) != 1 else ''}")
    for dimension in dimensions:
        if dimension not in parameters:
            raise ValueError(f"{name} has no parameter {dimension!r}; it has {', '.join(parameters)}")
    if folder is not None:
        if settings is None:
            raise ValueError("builds in a folder need what its manifest keeps of them (settings)")
        from .sweep import SWEEP_EXTRA, missing_modules
        absent = missing_modules(("dask", "pyarrow"))
        if absent:
            raise ImportError(f"builds in a folder need {', '.join(absent)}: {SWEEP_EXTRA} (or give no folder: "
                              "the builds are then made in memory with NumPy)")
    solving = solver()
    wanted = [argument for argument in solving.required if argument not in sweep]
    missing = [argument for argument in wanted if argument not in nominal]
    if missing:
        raise ValueError(f"nominal: give the value of {', '.join(missing)}")
    design = {argument: float(nominal[argument]) for argument in wanted}
    centre = solving(**sweep, **design)
    nominal_values = numpy.stack([numpy.asarray(numpy.broadcast_to(centre[o], (count,)), dtype=float)
                                  for o in chosen])
    model = _BuildModel(solving, tuple(chosen), tuple(dimensions), sigmas,
                        tuple(parameters[dimension] for dimension in dimensions), design, sweep, nominal_values,
                        tuple(angular()), builds, chunk, seed)
    chunks = -(-builds // chunk)
    if folder is None:
        deviation = numpy.concatenate([model.draw(index)[1] for index in range(chunks)], axis=1)
        return SampledBuilds(tuple(chosen), sweep, nominal_values, deviation)
    assert settings is not None  # checked above
    reused = _builds_in_folder(model, settings(model), Path(folder), scheduler, workers)
    return SampledBuilds(tuple(chosen), sweep, nominal_values, _read_builds(model, Path(folder)), reused)


def _builds_in_folder(model: _BuildModel, settings: dict[str, object], folder: Path, scheduler: str,
                      workers: int | None) -> int:
    """Make the chunks of ``model`` that ``folder`` does not hold yet on Dask, writing each as it is done;
    the number of chunks found done."""
    from .sweep import local_chunks, local_scheduler
    from ..io.sweep_folder import open_folder
    from ..version import __version__
    header = {"symlink": __version__, "settings": settings, "columns": model.columns()}
    with open_folder(folder, header, model.builds, model.chunk) as opened:
        todo = list(opened.todo)
        reused = -(-model.builds // model.chunk) - len(todo)
        chosen = local_scheduler(len(todo), workers) if scheduler == "auto" else scheduler

        def land(index: int, result: bytes) -> None:  # in this thread, as each chunk ends
            first, stop = model.chunk_range(index)
            opened.stage(index, result, rows=stop - first)

        local_chunks(model.table, todo, chosen, workers, None, land)
    return reused


def _read_builds(model: _BuildModel, folder: Path) -> numpy.ndarray:
    """The deviations (outputs, builds, inputs) of every chunk of ``folder``, each verified against the manifest
    and checked to hold its builds in the model's columns; ``ValueError`` naming one that does not."""
    import pyarrow
    import pyarrow.parquet

    from ..io.sweep_folder import numpy_column, verified_chunks
    count = model.nominal.shape[1]
    deviation = numpy.full((len(model.outputs), model.builds, count), numpy.nan)
    names = model.columns()
    done = numpy.zeros(model.builds, dtype=bool)
    for record, data in verified_chunks(folder):
        # one file, read as one: read_table goes through pyarrow.dataset (imported for it alone)
        table = pyarrow.parquet.ParquetFile(pyarrow.BufferReader(data)).read()
        numbers = numpy_column(table, "build") if "build" in table.column_names else None
        if (table.column_names != names or numbers is None
                or not numpy.array_equal(numbers, numpy.arange(record.first, record.last + 1))):
            raise ValueError(f"{folder / record.name} does not hold builds {record.first} to {record.last} in the "
                             "manifest's columns; run again with the same arguments to rebuild it")
        column = 1 + len(model.dimensions)
        for i in range(len(model.outputs)):
            for k in range(count):
                deviation[i, record.first:record.last + 1, k] = numpy_column(table, names[column])
                column += 1
        done[record.first:record.last + 1] = True
    if not done.all():
        raise ValueError(f"{folder} holds {int(done.sum())} of {model.builds} builds: run again with the same "
                         "arguments to make the rest")
    return deviation
