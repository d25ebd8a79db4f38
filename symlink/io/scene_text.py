"""Scene files as plain data, and a warm scene from the disk cache: no SymPy.

A scene file (:mod:`symlink.io.scene`) is numbers and names; what it needs of
its linkage (which names are parameters, lengths or angles, the driven input,
the angle columns) is plain data too.  The first run of a scene
(:func:`cache_scene`) keeps those facts in the disk cache, keyed by what shapes
them: the linkage (a catalog or atlas name, or the bytes of a linkage file),
the outputs and the ``[dynamics]`` table.  A later run of a scene with the same
key (:func:`warm_scene`, other numbers welcome) checks its numbers against the
facts, and evaluates the cached NumPy module
(:class:`~symlink.numeric.cached_solver.CachedSolver`): it builds no linkage
and imports no SymPy.  Anything the warm checks do not accept as it is goes
to the full reader, which says what is wrong.

>>> number(20, "parameters.a"), choice("csv", "format", FORMATS)
(20.0, 'csv')
>>> number(True, "parameters.a")
Traceback (most recent call last):
ValueError: parameters.a must be a number, got True
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, Callable, Mapping, Sequence

import numpy

from ..common.angles import to_radians
from ..common.display import record_html
from ..common.names import FORMER_CATALOG_NAMES
from ..common.files import excerpt, sha256
from ..common.numbers import toml_data
from ..numeric.input_sweep import MAX_ANGLE, InputSweep, crank_speeds


__all__ = ["BRANCH_CHOICES", "UNITS", "FORMATS", "TOP_KEYS", "INPUT_KEYS", "MAX_SCENE_BYTES", "MAX_ANGLE",
           "MAX_MAGNITUDE", "number", "choice", "table", "linkage_request", "catalog_file_names", "WarmScene",
           "warm_scene", "cache_scene", "SCENE_ENTRY_KIND", "NewtonScene", "newton_scene"]

BRANCH_CHOICES = (1, -1, "both")
UNITS = ("deg", "rad")
FORMATS = ("table", "csv", "json")
TOP_KEYS = {"linkage", "outputs", "branch", "units", "format", "parameters", "input", "dynamics", "guess"}
INPUT_KEYS = {"start", "stop", "step", "angles", "speed", "accel"}
#: Scene files larger than this are refused unread (a scene is a few lines).
MAX_SCENE_BYTES = 1 << 20
#: Numbers of a scene file other than angles: 0 or between its inverse and it in size (the bound of linkage files,
#: :data:`symlink.io.linkage_file.MAX_MAGNITUDE`, and of the command line's numbers).
MAX_MAGNITUDE = 1e50
#: The kind of cache entry of a scene's facts (:func:`symlink.numeric.cache.catalog_key`).
SCENE_ENTRY_KIND = "scene-facts/1"
#: Besides the code that shapes generated code: what reads scenes and linkage files.
SCENE_SHAPING = ("io/scene", "io/scene_text", "io/linkage_file")
#: A linkage file larger than this is not keyed (its reader refuses it anyway).
_KEYED_FILE_BYTES = 4 << 20


def number(value: Any, where: str, angle: bool = False) -> float:
    """A number of a scene file: finite, and in range as in linkage files (an ``angle`` within 1e9, any other
    value 0 or between 1e-50 and 1e50 in size); ``ValueError`` naming ``where``."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{where} must be a number, got {excerpt(value)}")
    try:
        found = float(value)
    except OverflowError:
        found = math.inf
    if not math.isfinite(found):
        raise ValueError(f"{where} must be finite, got {value if isinstance(value, float) else 'a huge integer'}")
    if angle and abs(found) > MAX_ANGLE:
        raise ValueError(f"{where} must be at most {MAX_ANGLE:g} in size (larger angles have lost their precision), "
                         f"got {found:g}")
    if not angle and found != 0 and not 1 / MAX_MAGNITUDE <= abs(found) <= MAX_MAGNITUDE:
        raise ValueError(f"{where} must be 0 or between {1 / MAX_MAGNITUDE:g} and {MAX_MAGNITUDE:g} in size, "
                         f"got {found:g}")
    return found


def choice(value: Any, where: str, choices: Sequence) -> Any:
    """``value`` if it is one of ``choices`` (a bool or a float never is); ``ValueError`` naming ``where``."""
    if isinstance(value, (bool, float)) or value not in choices:
        raise ValueError(f"{where} must be one of {', '.join(map(repr, choices))}, got {value!r}")
    return value


def table(data: Any, where: str, allowed: set[str] | None) -> dict:
    """``data`` if it is a TOML table whose keys are all ``allowed``; ``ValueError`` naming the first other."""
    if not isinstance(data, dict):
        raise ValueError(f"{where} must be a table ([{where}]), got {data!r}")
    if allowed is not None:
        unknown = sorted(set(data) - allowed)
        if unknown:
            raise ValueError(f"unknown key {where + '.' if where else ''}{unknown[0]} "
                             f"(allowed: {', '.join(sorted(allowed))})")
    return data


#: The catalog's files, one a catalog linkage: :data:`symlink.io.linkage_file.CATALOG_FOLDER`, named here without
#: importing that reader (SymPy).
_CATALOG_FILES = Path(__file__).resolve().parent.parent / "linkages"


def catalog_file_names() -> list[str]:
    """The names of the catalog's linkages, read off its files (no linkage built, no SymPy), sorted.

    >>> from symlink.mechanism.catalog import CATALOG
    >>> catalog_file_names() == sorted(CATALOG)
    True
    """
    return sorted(path.stem for path in _CATALOG_FILES.glob("*.toml"))


def _bytes_digest(path: Path) -> str:
    """The SHA-256 of a file's bytes, hex: what names a linkage file in a cache key (:func:`linkage_request`)."""
    return sha256(path.read_bytes()).hexdigest()


def linkage_request(source: str, folder: str | Path | None = None, digest: Callable[[Path], str] = _bytes_digest
                    ) -> dict[str, str] | None:
    """What names a linkage in a cache key, found without building it (no SymPy): a catalog or atlas name, or
    the ``digest`` of a linkage file (SHA-256 of its bytes by default; a relative path looked for in ``folder``, as
    :func:`symlink.io.linkage_file.load_linkage` does); None where it is none of these, or the file cannot be read
    (the reader then says what is wrong).  A caller that keys a file by something else of it (a sweep, by its text)
    passes that as ``digest``, so that the file is read and hashed once.

    >>> linkage_request("fourbar"), linkage_request("atlas:watt-ii"), linkage_request("no/such/file.toml")
    ({'catalog': 'fourbar'}, {'atlas': 'atlas:watt-ii'}, None)
    """
    source = FORMER_CATALOG_NAMES.get(source, source)
    if source and all(c.isalnum() or c in "-_" for c in source) and (_CATALOG_FILES / f"{source}.toml").is_file():
        return {"catalog": source}
    if source.startswith("atlas:"):
        return {"atlas": source}
    try:
        path = Path(folder) / source if folder is not None else Path(source)
        if not path.is_file() or path.stat().st_size > _KEYED_FILE_BYTES:
            return None
        return {"file_sha256": digest(path)}
    except (OSError, ValueError):  # a UnicodeError (a digest of the text) is a ValueError
        return None


def _key(data: Mapping[str, Any], folder: str | Path) -> str | None:
    """The cache key of a parsed scene's facts; None where its linkage or its outputs cannot be keyed."""
    from ..numeric.cache import catalog_key
    source, outputs = data.get("linkage"), data.get("outputs")
    if (not isinstance(source, str) or not isinstance(outputs, list) or not all(isinstance(o, str) for o in outputs)
            or len(set(outputs)) != len(outputs)):  # a repeated output: the cold path says why
        return None
    request = linkage_request(source, folder)
    if request is None:
        return None
    try:
        dynamics = json.loads(json.dumps(data.get("dynamics"), sort_keys=True))
    except (TypeError, ValueError):  # a date or a time in the table: not plain data
        return None
    return catalog_key("scene", outputs, SCENE_ENTRY_KIND, {"linkage": request, "dynamics": dynamics}, SCENE_SHAPING)


class WarmScene:
    """A scene file evaluated from the cache: its facts (plain data), its numbers, and the cached solver.

    Evaluated as :class:`symlink.io.scene.SceneFile` is: a block of input angles at a time, each branch sign.
    """

    _repr_html_ = record_html

    def __init__(self, facts: Mapping[str, Any], solver: Any, parameters: Mapping[str, float], sweep: InputSweep,
                 units: str, fmt: str, branch: int | str, speed: float, accel: float) -> None:
        self.facts, self.solver, self.parameters, self.sweep = facts, solver, dict(parameters), sweep
        self.units, self.format, self.branch, self.speed, self.accel = units, fmt, branch, speed, accel
        self.outputs: list[str] = list(facts["outputs"])
        self.input_column: str = facts["input_column"]
        self.angle_columns: set[str] = {self.input_column, *facts["angle_columns"]}
        self.name: str = facts["name"]

    def values_at(self, angles: numpy.ndarray) -> dict[str, object]:
        """The driven input at ``angles`` (in ``units``): its angle in radians, and the rate and acceleration where
        the outputs need them."""
        theta = to_radians(angles, self.units)
        values: dict[str, object] = {self.facts["input"]: theta}
        if self.facts["rate"] in self.solver.arguments:
            first = float(to_radians(self.sweep.first, self.units))
            values[self.facts["rate"]] = crank_speeds(theta, self.speed, self.accel, first)
        if self.facts["accel"] in self.solver.arguments:
            values[self.facts["accel"]] = self.accel
        return values

    def evaluate(self, angles: numpy.ndarray) -> dict[int, Any]:
        """The outputs on each branch sign at ``angles``."""
        signs = (1, -1) if self.branch == "both" else (int(self.branch),)
        merged = {**self.parameters, **self.values_at(angles)}
        return {sign: self.solver(**merged, **{name: sign for name in self.solver.branches}) for sign in signs}


class _Cold(Exception):
    """The cache lacks an entry the warm scene needs: the full reader takes over."""


def _cold() -> str:
    raise _Cold


def _plain_scene(data: Mapping[str, Any], facts: Mapping[str, Any], solver: Any) -> WarmScene:
    """A :class:`WarmScene` of the parsed scene ``data`` with its ``facts``; ``ValueError`` for anything the full
    reader (:func:`symlink.io.scene.scene_from_mapping`) might see otherwise."""
    if "guess" in table(dict(data), "", TOP_KEYS):  # a closed form or not: the full reader says which
        raise ValueError("guess")
    names = facts["parameters"]
    given = {**{n: v for n, v in facts["defaults"].items() if n in names},
             **table(data.get("parameters", {}), "parameters", set(names))}
    if any(n not in given for n in names):
        raise ValueError("missing parameters")
    parameters = {}
    for name, value in given.items():
        parameters[name] = number(value, f"parameters.{name}", angle=name in facts["angles"])
        if name in facts["positive"] and parameters[name] <= 0:
            raise ValueError("a length that is not positive")
    units = choice(data.get("units", "deg"), "units", UNITS)
    sweep, speed, accel = input_table(data, units)
    return WarmScene(facts, solver, parameters, sweep, units, choice(data.get("format", "table"), "format", FORMATS),
                     choice(data.get("branch", 1), "branch", BRANCH_CHOICES), speed, accel)


def input_table(data: Mapping[str, Any], units: str) -> tuple[InputSweep, float, float]:
    """A scene's ``[input]`` table: the sweep of its input angle (in ``units``), its speed and its acceleration.

    The one reading of it, for the full reader (:func:`symlink.io.scene.scene_from_mapping`) and a warm scene;
    ``ValueError`` naming the key for anything wrong.

    >>> sweep, speed, accel = input_table({"input": {"angles": [0, 90], "speed": 10.5}}, "deg")
    >>> sweep.array().tolist(), speed, accel
    ([0.0, 90.0], 10.5, 0.0)
    """
    sweep_table = table(data.get("input", {}), "input", INPUT_KEYS)
    options: dict[str, Any] = {key: (None if key not in sweep_table else
                                     number(sweep_table[key], f"input.{key}", angle=key != "step"))
                               for key in ("start", "stop", "step")}
    angles = sweep_table.get("angles")
    if angles is not None:
        if not isinstance(angles, list):
            raise ValueError("input.angles must be a list of numbers")
        angles = [number(v, f"input.angles[{i}]", angle=True) for i, v in enumerate(angles)]
    try:
        sweep = InputSweep.from_options(angles=angles, units=units, **options)
    except ValueError as error:
        raise ValueError(f"input: {error}") from None
    return sweep, number(sweep_table.get("speed", 0.0), "input.speed"), number(sweep_table.get("accel", 0.0),
                                                                             "input.accel")


def _solver(facts: Mapping[str, Any], derive: Any) -> Any:
    from ..numeric.cached_solver import CachedSolver
    return CachedSolver(facts["name"], facts["outputs"], key=facts["solver_key"], derive=derive)


def warm_scene(text: str, folder: str | Path = ".") -> WarmScene | None:
    """The scene of TOML ``text`` from the disk cache alone (no SymPy); None where the cache does not hold what it
    needs, or anything in the text is not plainly right (then :func:`symlink.io.scene.scene_from_text` reads it
    and says what is wrong)."""
    from ..numeric.cache import cached_text
    if len(text) > MAX_SCENE_BYTES:
        return None
    try:
        data = toml_data(text)
        key = _key(data, folder)
        if key is None:
            return None
        facts = json.loads(cached_text(key, _cold))
        return _plain_scene(data, facts, _solver(facts, _cold))
    except (_Cold, ValueError, TypeError, KeyError, RecursionError):
        return None


def cache_scene(text: str, folder: str | Path, found: Any) -> WarmScene | None:
    """Keep the facts of the scene file ``found`` (:class:`symlink.io.scene.SceneFile`, read from TOML ``text``)
    in the disk cache and return it as a :class:`WarmScene`, so that the next run of a scene like it is warm;
    None where it cannot be keyed (its linkage named by a path that is not a file, say)."""
    from ..numeric.cache import cached_text, catalog_key
    data = toml_data(text)
    key = _key(data, folder)
    if key is None:
        return None
    scene = found.scene
    linkage, outputs = scene.linkage, list(scene.outputs)
    request = getattr(scene, "request", None)  # a dynamics request (symlink.io.scene.DynamicScene) has its own entry
    if request is not None:
        solver_key, derive = request.key, request.derive
        parameters = list(request.parameters.values())
    else:
        from ..numeric.cached_solver import entry_text
        solver_key = catalog_key("scene-solver", outputs, SCENE_ENTRY_KIND, {"scene": key})

        def derive() -> str:
            return entry_text(linkage, outputs)
        parameters = list(linkage.parameters)
    from ..symbolic.closure import is_angle
    from ..symbolic.vectors import acceleration, rate
    driven = linkage.inputs[0]
    names = [p.name for p in parameters]
    known = {s.name: s for s in linkage.parameters}
    defaults = {} if found.source == "catalog" else {n: v for n, v in found.defaults.items() if n in names}
    facts = {
        "name": linkage.name, "outputs": outputs, "parameters": names,
        "positive": [p.name for p in parameters if p.is_positive],
        "angles": [n for n in names if n in known and is_angle(linkage, known[n])],
        "defaults": defaults, "input": driven.name, "rate": rate(driven).name, "accel": acceleration(driven).name,
        "input_column": found.input_column, "angle_columns": sorted(found.angle_columns),
        "solver_key": solver_key,
    }
    stored = json.loads(cached_text(key, lambda: json.dumps(facts)))
    return _plain_scene(data, stored, _solver(stored, derive))


class NewtonScene:
    """A scene file of a linkage without a closed form, checked against its table's facts (plain data, no SymPy):
    what :class:`symlink.io.scene.NewtonSceneFile` gives the Newton solver of ``symlink table NAME --guess ...``
    (:func:`symlink.numeric.newton_table.newton_results`), and how to print it."""

    _repr_html_ = record_html

    def __init__(self, outputs: list[str], values: dict[str, float], sweep: InputSweep, speed: float, accel: float,
                 guess: dict[str, float], units: str, fmt: str, input_column: str, angle_columns: set[str],
                 column_units: dict[str, str]) -> None:
        self.outputs, self.values, self.sweep, self.speed, self.accel = outputs, values, sweep, speed, accel
        self.guess, self.units, self.format, self.input_column = guess, units, fmt, input_column
        self.angle_columns, self.column_units = angle_columns, column_units


def newton_scene(data: Mapping[str, Any], facts: Mapping[str, Any], defaults: bool) -> NewtonScene:
    """The scene of parsed ``data`` with a ``[guess]`` table, from its linkage's table facts
    (:func:`symlink.io.table_source.table_facts`); ``defaults``: a linkage file's defaults stand in for
    parameters the scene leaves out (a catalog scene names every one); fixed angles in radians, as in every scene's
    ``[parameters]``.  ``ValueError`` naming the first bad key or value, and for
    a linkage with a closed form (where ``branch`` chooses the assembly).

    >>> facts = {"name": "two", "closed_form": False, "parameters": ["a"], "positive": ["a"], "angles": ["theta"],
    ...          "inputs": ["theta"], "labels": {"theta": "crank"}, "defaults": {}, "column_units": {},
    ...          "angle_columns": ["crank", "rocker"], "newton": {"unknowns": {"rocker": "phi"},
    ...                                                         "outputs": {"rocker": "phi"}}}
    >>> scene = newton_scene({"linkage": "two", "outputs": ["rocker"], "parameters": {"a": 2},
    ...                       "input": {"angles": [0, 90]}, "guess": {"phi": 30}}, facts, False)
    >>> scene.guess, scene.values, sorted(scene.angle_columns)
    ({'rocker': 30.0}, {'a': 2.0}, ['crank', 'rocker'])
    >>> newton_scene({"outputs": ["rocker"], "parameters": {"a": 2}, "guess": {}}, facts, False)
    Traceback (most recent call last):
    ValueError: guess: two needs a guess of every unknown (rocker) at the first input angle
    """
    table(dict(data), "", TOP_KEYS)
    name, newton = facts["name"], facts["newton"]
    if facts["closed_form"]:
        raise ValueError(f"guess: {name} is solved in closed form, where branch chooses the assembly; "
                         "[guess] is for linkages without a closed form")
    if "dynamics" in data:
        raise ValueError(f"dynamics: {name} has no closed form; scene files give dynamics only for linkages "
                         "solved in closed form")
    inputs = facts["inputs"]
    if len(inputs) != 1 or inputs[0] not in facts["angles"]:
        raise ValueError(f"scene files drive linkages with one input angle; {name} has {', '.join(inputs)}")
    known = list(newton["outputs"])
    outputs = data.get("outputs")
    if not isinstance(outputs, list) or not outputs or not all(isinstance(o, str) for o in outputs):
        raise ValueError(f"outputs must be a non-empty list of output names of {name} ({', '.join(known)}), "
                         f"got {excerpt(outputs)}")
    for k, output in enumerate(outputs):
        if output not in known:
            raise ValueError(f"outputs: {name} (solved by Newton's method) has no output {excerpt(output)}; "
                             f"it has {', '.join(known)}")
        if output in outputs[:k]:
            raise ValueError(f"outputs lists {excerpt(output)} more than once; list each output once")
    if choice(data.get("branch", 1), "branch", BRANCH_CHOICES) != 1:
        raise ValueError(f"branch: {name} has no closed form: its one assembly is the one [guess] starts from; "
                         "give branch = 1 or leave it out")
    units = choice(data.get("units", "deg"), "units", UNITS)
    fmt = choice(data.get("format", "table"), "format", FORMATS)
    names = facts["parameters"]
    given = {**({n: v for n, v in facts["defaults"].items() if n in names} if defaults else {}),
             **table(data.get("parameters", {}), "parameters", set(names))}
    missing = [n for n in names if n not in given]
    if missing:
        raise ValueError(f"missing parameters.{missing[0]} ({name} needs {', '.join(names)})")
    values = {}
    for key, value in given.items():
        values[key] = number(value, f"parameters.{key}", angle=key in facts["angles"])
        if key in facts["positive"] and values[key] <= 0:
            raise ValueError(f"parameters.{key} must be a positive length, got {value!r}")
    sweep, speed, accel = input_table(data, units)
    labels = newton["unknowns"]  # label: name
    label_of = {**{label: label for label in labels}, **{n: label for label, n in labels.items()}}
    guess_table = table(data["guess"], "guess", None)
    guess = {}
    for key, value in guess_table.items():
        if key not in label_of:
            raise ValueError(f"guess: {name} has no unknown {excerpt(key)}; its unknowns are "
                             f"{', '.join(f'{label} ({n})' if label != n else label for label, n in labels.items())}")
        guess[label_of[key]] = number(value, f"guess.{key}", angle=True)
    if len(guess) != len(labels):
        raise ValueError(f"guess: {name} needs a guess of every unknown ({', '.join(labels)}) at the first input "
                         "angle")
    input_column = facts["labels"][inputs[0]]
    angle_columns = {input_column} | (set(facts["angle_columns"]) & set(outputs))
    column_units = {c: (units if u == "rad" else u) for c, u in facts["column_units"].items()
                    if c in outputs or c == input_column}
    return NewtonScene(list(outputs), values, sweep, speed, accel, guess, units, fmt, input_column, angle_columns,
                       column_units)
