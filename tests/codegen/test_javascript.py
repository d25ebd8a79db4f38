"""The JavaScript export: the generated solvers run under Node and agree with the NumPy module and the poses.

Every closed-form catalog entry's solver (the union of its export sets, every output) is run through
``solve`` (one configuration a call, as a browser frame) and ``solveMany``, in one Node process, on random
arguments (both branches, assemblies that fail included) and on points near the toggles (the edges of
the first input's range, bisected to rounding, then moved in by 1e-15 to 1e-6 and out likewise), and
compared with the NumPy module printed from the same program (the reference).  The drawing solver
(:func:`~symlink.codegen.javascript.javascript_geometry`) places every joint where
:class:`symlink.numeric.poses.Geometry` does.  Without Node the tests skip and say so.

Agreement is to 1e-13 relative (absolute below 1): V8's ``Math.sin``, ``Math.cos`` and ``Math.atan2``
(fdlibm) differ from the C library's that NumPy calls in the last place for some arguments (about 3 %
of sines and cosines, 16 % of arctangents here), which near a toggle the closed forms amplify as they
amplify any rounding; there a sample may also differ by 64 times its rounding spread
(:func:`export_checks.rounding_spread`: how far the NumPy output moves when the arguments move by an ulp
or two), as the C and Octave tests allow.
"""
from __future__ import annotations

import json
import shutil
import subprocess

import numpy
import pytest
import sympy as sp

from export_checks import angles_of, closed_form_catalog, export_sets, random_arguments, rounding_spread
from symlink.codegen.javascript import (NO_CLOSED_FORM, export_files, geometry_program, javascript_geometry,
                                        javascript_names, javascript_solver, js_comment, js_string)
from symlink.codegen.numpy import load_numpy_module, numpy_module
from symlink.mechanism.catalog import EXAMPLE_VALUES
from symlink.numeric.poses import Geometry
from symlink.symbolic.linkage import Linkage
from symlink.symbolic.loops import Loop
from symlink.symbolic.vectors import Vector, coordinates, lengths
from symlink.io.scene import catalog_linkage

RANDOM_SAMPLES = 300
TOGGLE_ROWS = 24
#: How far from a toggle (relative to the input's step across it) the samples near it sit, inside and out.
TOGGLE_OFFSETS = (0.0, 1e-15, 1e-13, 1e-11, 1e-9, 1e-7, 1e-6)
RTOL = 1e-13

DRIVER = r"""
"use strict";
const fs = require("fs");
const manifest = JSON.parse(fs.readFileSync(process.argv[2], "utf8"));
function read(path) {
    const bytes = fs.readFileSync(path);
    return new Float64Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length));
}
function write(path, array) {
    fs.writeFileSync(path, Buffer.from(array.buffer, array.byteOffset, array.byteLength));
}
const report = [];
for (const c of manifest.cases) {
    const solver = require(c.solver);
    const data = read(c.input), n = c.count, m = solver.arguments.length, k = solver.outputs.length;
    const one = new Float64Array((k + 1) * n);
    const values = {}, out = {};
    for (let i = 0; i < n; i++) {
        for (let a = 0; a < m; a++) {
            values[solver.arguments[a]] = data[a * n + i];
        }
        if (solver.solve(values, out) !== out) {
            throw new Error("solve returned another object");
        }
        for (let j = 0; j < k; j++) {
            one[j * n + i] = out[solver.outputs[j]];
        }
        one[k * n + i] = out.assembled === true ? 1 : out.assembled === false ? 0 : NaN;
    }
    write(c.solved, one);
    const columns = {};
    for (let a = 0; a < m; a++) {
        columns[solver.arguments[a]] = data.subarray(a * n, (a + 1) * n);
    }
    const many = solver.solveMany(columns, n);
    const all = new Float64Array((k + 1) * n);
    all.set(many.output);
    for (let i = 0; i < n; i++) {
        all[k * n + i] = many.assembled[i];
    }
    write(c.many, all);
    report.push({name: solver.name, arguments: solver.arguments, outputs: solver.outputs, flags: solver.flags,
                 inputs: solver.inputs, parameters: solver.parameters, branches: solver.branches,
                 rates: solver.rates, count: many.count, fresh: n ? Object.keys(solver.solve(values)).length : null,
                 points: solver.points || null});
}
process.stdout.write(JSON.stringify(report));
"""


def _node() -> str:
    node = shutil.which("node")
    if node is None:
        pytest.skip("Node.js is not installed (no node on PATH): the generated JavaScript is not run")
    return node


def run_node(folder, script: str, *arguments: str, check: bool = True) -> subprocess.CompletedProcess:
    """Run ``script`` (written to ``folder``) under Node."""
    path = folder / "script.js"
    path.write_text(script)
    result = subprocess.run([_node(), str(path), *arguments], cwd=folder, capture_output=True, text=True,
                            timeout=120, check=False)
    if check:
        assert result.returncode == 0, result.stderr
    return result


class Case:
    """One solver run on one set of arguments (rows of a binary file), its two results read back."""

    def __init__(self, folder, index: int, text: str, arguments, values: dict):
        self.folder, self.index = folder, index
        self.count = len(next(iter(values.values())))
        (folder / f"solver_{index}.js").write_text(text)
        numpy.array([numpy.broadcast_to(values[a], (self.count,)) for a in arguments], dtype=float).tofile(
            folder / f"in_{index}.bin")

    def entry(self) -> dict:
        return {"solver": str(self.folder / f"solver_{self.index}.js"), "input": str(self.folder / f"in_{self.index}.bin"),
                "solved": str(self.folder / f"solve_{self.index}.bin"), "many": str(self.folder / f"many_{self.index}.bin"),
                "count": self.count}

    def results(self, outputs) -> tuple[dict, dict]:
        found = []
        for kind in ("solve", "many"):
            data = numpy.fromfile(self.folder / f"{kind}_{self.index}.bin").reshape(len(outputs) + 1, self.count)
            found.append({**dict(zip(outputs, data[:-1])), "assembled": data[-1]})
        return found[0], found[1]


def run_cases(folder, cases) -> list[dict]:
    (folder / "manifest.json").write_text(json.dumps({"cases": [case.entry() for case in cases]}))
    return json.loads(run_node(folder, DRIVER, str(folder / "manifest.json")).stdout)


def masked(expected: dict) -> dict[str, numpy.ndarray]:
    """The NumPy module's results as the JavaScript solver gives them: numbers (flags 1 and 0), NaN where not assembled."""
    assembled = numpy.asarray(expected["assembled"], dtype=bool)
    shape = assembled.shape
    return {key: numpy.where(assembled, numpy.broadcast_to(numpy.asarray(value, dtype=float), shape), numpy.nan)
            if key != "assembled" else assembled.astype(float) for key, value in expected.items()}


def rounding_edge(function, values: dict, trials: int = 6) -> numpy.ndarray:
    """Where the NumPy module's own ``assembled`` changes when the arguments move by an ulp or two: samples
    on a toggle to rounding, where either answer is right (and an ulp of a sine decides)."""
    with numpy.errstate(all="ignore"):
        base = numpy.asarray(function(**values, check=False)["assembled"], dtype=bool)
        edge = numpy.zeros(base.shape, dtype=bool)
        for seed in range(trials):
            rng = numpy.random.default_rng(seed)
            moved = {k: v if k.startswith("branch") else v * (1 + rng.choice([-2.0, -1.0, 1.0, 2.0], v.shape) * 2.0**-52)
                     for k, v in values.items()}
            edge |= numpy.asarray(function(**moved, check=False)["assembled"], dtype=bool) != base
    return edge


def assert_close(actual: dict, expected: dict, angles, where: str, spread: dict | None = None,
                 rtol: float = RTOL, edge: numpy.ndarray | None = None) -> None:
    """Same keys, assembled and non-finite values; every finite value within ``rtol`` relative (absolute
    below 1), or 64 times its rounding spread; angles modulo 2 pi.  Samples on the ``edge``
    (:func:`rounding_edge`) need only be consistent: where not assembled, every output NaN."""
    assert sorted(actual) == sorted(expected), where
    if edge is not None and edge.any():
        for key, got in actual.items():
            if key != "assembled":
                assert numpy.isnan(got[edge & (actual["assembled"] == 0)]).all(), (where, key)
        actual = {key: value[~edge] for key, value in actual.items()}
        expected = {key: value[~edge] for key, value in expected.items()}
        spread = {key: numpy.broadcast_to(value, edge.shape)[~edge] for key, value in (spread or {}).items()}
    assert numpy.array_equal(actual["assembled"], expected["assembled"]), (
        where, numpy.flatnonzero(actual["assembled"] != expected["assembled"])[:5])
    for key, want in expected.items():
        got = actual[key]
        finite = numpy.isfinite(want)
        assert numpy.array_equal(got[~finite], want[~finite], equal_nan=True), (where, key)
        difference = numpy.abs(got[finite] - want[finite])
        if key in angles:
            difference = numpy.abs(numpy.angle(numpy.exp(1j * difference)))
        allowed = rtol * numpy.maximum(numpy.abs(want[finite]), 1.0)
        if spread is not None and key in spread:
            allowed = allowed + 64 * numpy.broadcast_to(spread[key], want.shape)[finite]
        if difference.size:
            worst = numpy.argmax(difference - allowed)
            assert difference[worst] <= allowed[worst], (
                f"{where} {key}: difference {difference[worst]:.3g} at a value of {want[finite][worst]:.17g}")


def toggle_arguments(function, linkage, arguments, rows: int, seed: int) -> dict[str, numpy.ndarray]:
    """Arguments at and near the toggles: for random other arguments, the first input where the linkage
    stops closing (a scan, then bisection to rounding), then moved in and out by :data:`TOGGLE_OFFSETS`."""
    values = random_arguments(linkage, arguments, rows, seed)
    first = linkage.inputs[0].name
    grid = numpy.linspace(-numpy.pi, numpy.pi, 181)
    repeated = {k: numpy.repeat(v, grid.size) for k, v in values.items()}
    repeated[first] = numpy.tile(grid, rows)
    with numpy.errstate(all="ignore"):
        closes = numpy.asarray(function(**repeated, check=False)["assembled"]).reshape(rows, grid.size)
    change = closes[:, 1:] != closes[:, :-1]
    keep = change.any(axis=1)
    column = numpy.argmax(change, axis=1)[keep]
    inside = numpy.where(closes[keep, column], grid[column], grid[column + 1])
    outside = numpy.where(closes[keep, column], grid[column + 1], grid[column])
    others = {k: v[keep] for k, v in values.items()}
    for _ in range(64):  # bisection: inside always closes, outside never
        middle = (inside + outside) / 2
        with numpy.errstate(all="ignore"):
            closed = numpy.asarray(function(**{**others, first: middle}, check=False)["assembled"], dtype=bool)
        inside, outside = numpy.where(closed, middle, inside), numpy.where(closed, outside, middle)
    step = outside - inside
    samples = [inside + sign * offset * numpy.sign(step) * numpy.pi for offset in TOGGLE_OFFSETS for sign in (-1, 1)]
    samples += [outside]
    count = len(samples)
    result = {k: numpy.tile(v, count) for k, v in others.items()}
    result[first] = numpy.concatenate(samples)
    return result


@pytest.fixture(scope="module")
def catalog_runs(tmp_path_factory):
    """Every closed-form catalog entry's exported solver, run on random arguments and at its toggles."""
    folder = tmp_path_factory.mktemp("javascript")
    cases, expected = [], []
    for name in closed_form_catalog():
        linkage = catalog_linkage(name)
        sets = export_sets(name)
        text = export_files(linkage, name.replace("-", "_"), sets, f"{name} solver.")[f"{name.replace('-', '_')}.js"]
        outputs = list(dict.fromkeys(o for _, names, _ in sets for o in names))
        program = linkage.program(outputs)
        function = load_numpy_module(numpy_module([("solve", program, "")]))["solve"]
        arguments = [s.name for s in program.arguments]
        for kind, values in (("random", random_arguments(linkage, arguments, RANDOM_SAMPLES, seed=len(cases))),
                             ("toggles", toggle_arguments(function, linkage, arguments, TOGGLE_ROWS, len(cases)))):
            if not len(values[arguments[0]]):
                continue  # no toggle along the input (the inverted slider-crank always closes)
            with numpy.errstate(all="ignore"):
                want = masked(function(**values))
            spread = rounding_spread(function, values)
            cases.append(Case(folder, len(cases), text, arguments, values))
            expected.append((name, kind, outputs, arguments, want, spread, rounding_edge(function, values)))
    reports = run_cases(folder, cases)
    return [(case, report, *rest) for case, report, rest in zip(cases, reports, expected)]


@pytest.mark.parametrize("name", closed_form_catalog())
def test_every_catalog_entry_agrees_with_numpy(catalog_runs, name):
    runs = [run for run in catalog_runs if run[2] == name]
    assert [run[3] for run in runs] == ["random"] + (["toggles"] if name != "inverted-slider-crank" else [])
    for case, report, _, kind, outputs, arguments, want, spread, edge in runs:
        assert report["name"] == name and report["outputs"] == outputs and report["arguments"] == arguments
        assert report["count"] == case.count and report["fresh"] == len(outputs) + 1
        linkage = catalog_linkage(name)
        assert report["inputs"] == [q.name for q in linkage.inputs]
        assert report["branches"] == [b.name for b in linkage.branches]
        assert report["flags"] == (["singular"] if "singular" in outputs else [])
        assembled = want["assembled"].astype(bool)
        assert 10 < assembled.sum() < assembled.size or name == "inverted-slider-crank", (name, kind)
        solved, many = case.results(outputs)
        for key in solved:  # one kernel: the two calls give the same bits
            numpy.testing.assert_array_equal(solved[key], many[key], err_msg=f"{name} {kind} {key}")
        assert edge.sum() <= (3 * TOGGLE_ROWS if kind == "toggles" else 0), (name, kind, edge.sum())
        assert_close(solved, want, angles_of(name, outputs), f"{name} {kind}", spread, edge=edge)


def test_the_toggles_are_reached(catalog_runs):
    """Near-toggle samples sit within rounding of where the linkage stops closing: both sides are tested."""
    for case, _, name, kind, _, _, want, _, edge in catalog_runs:
        if kind == "toggles":
            assembled = want["assembled"].astype(bool)[~edge]
            assert assembled.sum() > 5 * TOGGLE_ROWS // 2 and (~assembled).sum() > 5 * TOGGLE_ROWS // 2, name


SAME_SINES = r"""
"use strict";
// Math.sin, Math.cos and Math.atan2 answer from the tables Python wrote (NumPy's values); an argument
// missing from them is answered by V8 and written out, for Python to add to the tables for the next run.
const fs = require("fs");
const manifest = JSON.parse(fs.readFileSync(process.argv[2], "utf8"));
function read(path) {
    const bytes = fs.readFileSync(path);
    return new Float64Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length));
}
const original = {sin: Math.sin, cos: Math.cos, atan2: Math.atan2};
const missed = {sin: [], cos: [], atan2: []};
const tables = {sin: new Map(), cos: new Map(), atan2: new Map()};
for (const f of ["sin", "cos", "atan2"]) {
    if (fs.existsSync(manifest.tables + "_" + f + "_out.bin")) {
        const keys = read(manifest.tables + "_" + f + "_in.bin"), values = read(manifest.tables + "_" + f + "_out.bin");
        for (let i = 0; i < values.length; i++) {
            tables[f].set(f === "atan2" ? keys[2 * i] + "," + keys[2 * i + 1] : keys[i], values[i]);
        }
    }
}
function wrapped(f) {
    return function (x, y) {
        if (x === 0 || x !== x || (f === "atan2" && (y === 0 || y !== y))) {
            return original[f](x, y);  // exact in both libraries: zeros and NaN
        }
        const key = f === "atan2" ? x + "," + y : x;
        if (tables[f].has(key)) {
            return tables[f].get(key);
        }
        missed[f].push(x);
        if (f === "atan2") {
            missed[f].push(y);
        }
        return original[f](x, y);
    };
}
Math.sin = wrapped("sin");
Math.cos = wrapped("cos");
Math.atan2 = wrapped("atan2");
for (const c of manifest.cases) {
    const solver = require(c.solver);
    const data = read(c.input), n = c.count, m = solver.arguments.length, k = solver.outputs.length;
    const columns = {};
    for (let a = 0; a < m; a++) {
        columns[solver.arguments[a]] = data.subarray(a * n, (a + 1) * n);
    }
    const many = solver.solveMany(columns, n);
    const all = new Float64Array((k + 1) * n);
    all.set(many.output);
    for (let i = 0; i < n; i++) {
        all[k * n + i] = many.assembled[i];
    }
    fs.writeFileSync(c.many, Buffer.from(all.buffer));
}
let misses = 0;
for (const f of ["sin", "cos", "atan2"]) {
    misses += missed[f].length;
    fs.writeFileSync(manifest.tables + "_" + f + "_missed.bin", Buffer.from(new Float64Array(missed[f]).buffer));
}
process.stdout.write(JSON.stringify({misses: misses}));
"""


def test_with_numpys_sines_the_javascript_computes_numpys_bits(catalog_runs, tmp_path):
    """The printed arithmetic is the NumPy module's, operation for operation: with NumPy's values of
    sin, cos and atan2 in place of V8's (each argument V8 is asked for answered from a table of NumPy's
    values, filled over a few runs, as an angle found feeds a later sine), every output of every catalog
    entry, at random and at its toggles, is bit for bit the NumPy module's."""
    cases = [case for case, *_ in catalog_runs]
    manifest = tmp_path / "manifest.json"
    manifest.write_text(json.dumps({"cases": [case.entry() for case in cases], "tables": str(tmp_path / "t")}))
    for _ in range(6):
        if json.loads(run_node(tmp_path, SAME_SINES, str(manifest)).stdout)["misses"] == 0:
            break
        for f in ("sin", "cos", "atan2"):
            known = tmp_path / f"t_{f}_in.bin"
            arguments = numpy.concatenate([numpy.fromfile(known) if known.exists() else numpy.zeros(0),
                                           numpy.fromfile(tmp_path / f"t_{f}_missed.bin")])
            values = numpy.arctan2(arguments[0::2], arguments[1::2]) if f == "atan2" else getattr(numpy, f)(arguments)
            arguments.tofile(known)
            values.tofile(tmp_path / f"t_{f}_out.bin")
    else:
        pytest.fail("the tables of sines never covered every call")
    for case, _, name, kind, outputs, _, want, _, _ in catalog_runs:
        _, many = case.results(outputs)
        for key, value in want.items():
            numpy.testing.assert_array_equal(many[key], value, err_msg=f"{name} {kind} {key}")


# --- the drawing's solver: every joint placed as Geometry places it ------------------------------------

GEOMETRY_SAMPLES = 181


@pytest.fixture(scope="module")
def geometry_runs(tmp_path_factory):
    """Every closed-form catalog entry's drawing solver over a turn of its input, at its example values and
    at values moved by up to 10 %, on both branches (every loop's, then a mix), beside Geometry's poses."""
    folder = tmp_path_factory.mktemp("geometry")
    cases, expected = [], []
    rng = numpy.random.default_rng(7)
    for name in closed_form_catalog():
        linkage = catalog_linkage(name)
        geometry = Geometry(linkage)
        program, fields = geometry_program(linkage)
        function = load_numpy_module(numpy_module([("solve", program, "")]))["solve"]
        first = linkage.inputs[0].name
        sweep = numpy.linspace(-numpy.pi, numpy.pi, GEOMETRY_SAMPLES)
        branches = [b.name for b in linkage.branches]
        runs = []
        for signs in ([1] * len(branches), [-1] * len(branches), list(rng.choice([-1, 1], len(branches)))):
            for moved in (False, True):
                values = {k: v * (rng.uniform(0.9, 1.1) if moved else 1.0) for k, v in EXAMPLE_VALUES[name].items()}
                runs.append({**values, **dict(zip(branches, map(int, signs)))})
        columns = {a.name: numpy.concatenate([numpy.broadcast_to(sweep if a.name == first else float(run[a.name]),
                                                                 sweep.shape) for run in runs])
                   for a in program.arguments}
        poses = [geometry.poses(run, {first: sweep}) for run in runs]
        want = {"assembled": numpy.concatenate([p.assembled for p in poses]).astype(float)}
        for point in fields["points"]:
            place = numpy.concatenate([p.positions[point["name"]] for p in poses])
            want[point["x"]], want[point["y"]] = place.real, place.imag
        for slider in fields["sliders"]:
            direction = numpy.concatenate([numpy.broadcast_to(p.directions[slider["name"]], sweep.shape) for p in poses])
            want[slider["direction"]] = numpy.where(want["assembled"] == 1, direction, numpy.nan)
        text = javascript_geometry(linkage)
        cases.append(Case(folder, len(cases), text, list(columns), columns))
        expected.append((name, list(program.outputs), fields, want, rounding_spread(function, columns),
                         rounding_edge(function, columns)))
    reports = run_cases(folder, cases)
    return [(case, report, *rest) for case, report, rest in zip(cases, reports, expected)]


@pytest.mark.parametrize("name", closed_form_catalog())
def test_the_drawing_solver_places_every_joint_as_geometry_does(geometry_runs, name):
    (case, report, _, outputs, fields, want, spread, edge), = [run for run in geometry_runs if run[2] == name]
    assert report["outputs"] == outputs and report["points"] == fields["points"]
    assert sorted(want) == sorted(outputs + ["assembled"])  # every output is a point's x or y, or a direction
    assert 0 < want["assembled"].sum(), name
    assert edge.sum() <= 6, (name, edge.sum())
    solved, many = case.results(outputs)
    for key in solved:
        numpy.testing.assert_array_equal(solved[key], many[key], err_msg=f"{name} {key}")
    assert_close(solved, want, {p["direction"] for p in fields["sliders"]}, f"{name} geometry", spread, 1e-12, edge)


def test_the_drawing_solver_names_its_points_bodies_and_sliders():
    program, fields = geometry_program(catalog_linkage("slider-crank"))
    assert [(p["name"], p["x"], p["y"], p["kind"]) for p in fields["points"]] == [
        ("A", "x_A", "y_A", "joint"), ("B", "x_B", "y_B", "joint"), ("C", "x_C", "y_C", "joint"),
        ("AS", "x_AS", "y_AS", "joint"), ("AS guide", "x_AS_guide", "y_AS_guide", "guide")]
    assert fields["sliders"] == [{"name": "AS", "guide": "AS guide", "direction": "direction_AS"}]
    assert {"name": "conrod", "joints": ["B", "C"], "points": ["B", "C"]} in fields["bodies"]
    assert list(program.outputs)[-1] == "direction_AS"
    # Outputs asked for come first; a point name that would repeat an output name gets another underscore.
    program, fields = geometry_program(catalog_linkage("fourbar"), ["rocker", "rocker_speed"])
    assert list(program.outputs)[:3] == ["rocker", "rocker_speed", "x_A"]
    assert [a.name for a in program.arguments][-1] == "thetadot"
    text = javascript_geometry(catalog_linkage("fourbar"), ["rocker", "rocker_speed"])
    assert 'sets: Object.freeze({"requested": Object.freeze(["rocker", "rocker_speed"]), "geometry": ' \
           'Object.freeze(["x_A", ' in text


def test_a_linkage_without_a_closed_form_is_refused_with_the_reason():
    linkage = catalog_linkage("stephenson2")
    with pytest.raises(ValueError, match=NO_CLOSED_FORM):
        javascript_geometry(linkage)
    with pytest.raises(ValueError, match=NO_CLOSED_FORM):
        export_files(linkage, "s3", [("positions", ["beta"], "")], "Six-bar.")


# --- how a page loads it, what it refuses, and names -------------------------------------------------------

LOADING = r"""
"use strict";
const fs = require("fs"), vm = require("vm");
const text = fs.readFileSync(process.argv[2], "utf8");
const name = process.argv[3];
const found = {};
found.required = require(process.argv[2]);
const page = {self: undefined};
page.self = page;  // a browser's global: self is the window
vm.runInNewContext(text, page);
found.script = page.SymlinkSolvers[name];
found.returned = new Function("return " + text)();
new Function(text)();  // sloppy mode: this is the global object, as a script's
found.global = globalThis.SymlinkSolvers[name];
const module_ = {exports: {}};
new Function("module", text)(module_);
found.commonjs = module_.exports;
let syntax = "acorn unavailable";
try {
    const acorn = require("internal/deps/acorn/acorn/dist/acorn");
    acorn.parse(text, {ecmaVersion: 2015, sourceType: "script"});
    syntax = "ES2015";
} catch (error) {
    if (error instanceof SyntaxError) {
        syntax = "not ES2015: " + error.message;
    }
}
const values = JSON.parse(process.argv[4]);
const results = {};
for (const way of Object.keys(found)) {
    const solver = found[way];
    results[way] = solver && solver.name === name ? solver.solve(values) : null;
}
process.stdout.write(JSON.stringify({results: results, syntax: syntax, frozen: Object.isFrozen(found.required)
                                     && Object.isFrozen(found.required.outputs)}));
"""


def load_everywhere(tmp_path, text: str, name: str, values: dict) -> dict:
    (tmp_path / "solver.js").write_text(text)
    (tmp_path / "load.js").write_text(LOADING)
    result = subprocess.run([_node(), "--expose-internals", str(tmp_path / "load.js"), str(tmp_path / "solver.js"), name,
                             json.dumps(values)], cwd=tmp_path, capture_output=True, text=True, timeout=60, check=False)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def test_a_script_node_and_new_function_all_load_the_same_solver(tmp_path):
    linkage = catalog_linkage("fourbar")
    text = javascript_geometry(linkage, ["rocker"])
    values = dict(theta=0.5, a=20.0, b=66.0, c=56.0, d=80.0, branch=-1)
    found = load_everywhere(tmp_path, text, "fourbar", values)
    assert found["syntax"] in ("ES2015", "acorn unavailable"), found["syntax"]
    assert found["frozen"]
    results = found["results"]
    assert set(results) == {"required", "script", "returned", "global", "commonjs"}
    assert all(result == results["required"] for result in results.values())
    want = load_numpy_module(numpy_module([("f", geometry_program(linkage, ["rocker"])[0], "")]))["f"](**values)
    assert results["required"]["assembled"] is True
    assert abs(results["required"]["rocker"] - float(want["rocker"])) < 1e-13
    assert abs(results["required"]["x_C"] - float(want["x_C"])) < 1e-12


ERRORS = r"""
"use strict";
const solver = require(process.argv[2]);
const good = {theta: 0.5, a: 20, b: 66, c: 56, d: 80, branch: 1, thetadot: 2, thetaddot: 0};
function attempt(f) {
    try {
        f();
        return "no error";
    } catch (error) {
        return error.constructor.name + ": " + error.message;
    }
}
const withTheta = (value) => Object.assign({}, good, {theta: value});
const without = (key) => { const v = Object.assign({}, good); delete v[key]; return v; };
const report = {
    missing: attempt(() => solver.solve(without("c"))),
    missingMany: attempt(() => solver.solveMany(without("thetadot"), 3)),
    nan: attempt(() => solver.solve(withTheta(NaN))),
    infinite: attempt(() => solver.solve(withTheta(Infinity))),
    text: attempt(() => solver.solve(withTheta("0.5"))),
    object: attempt(() => solver.solve(withTheta({}))),
    branch: attempt(() => solver.solve(Object.assign({}, good, {branch: 0}))),
    length: attempt(() => solver.solve(Object.assign({}, good, {a: -20}))),
    tiny: attempt(() => solver.solve(Object.assign({}, good, {a: 1e-306}))),
    notValues: attempt(() => solver.solve(null)),
    column: attempt(() => solver.solveMany(Object.assign({}, good, {theta: [0, NaN, 1]}))),
    short: attempt(() => solver.solveMany(Object.assign({}, good, {theta: new Float64Array(2)}), 3)),
    count: attempt(() => solver.solveMany(good, 1.5)),
};
const out = {kept: "here"};
const same = solver.solve(good, out);
const many = solver.solveMany(Object.assign({}, good, {theta: [0.5, 0.5]}));
const scalars = solver.solveMany(good);
report.out = {same: same === out, kept: out.kept, rocker: out.rocker, assembled: out.assembled};
report.many = {count: many.count, types: [many.output.constructor.name, many.assembled.constructor.name],
               rocker: Array.from(many.output.subarray(0, many.count)), assembled: Array.from(many.assembled)};
report.scalars = scalars.count;
report.unassembled = solver.solve(Object.assign({}, good, {a: 50, b: 30, c: 40, d: 45, theta: 0}));
report.extra = solver.solve(Object.assign({}, good, {extra: "ignored"})).assembled;
process.stdout.write(JSON.stringify(report, (k, v) => (typeof v === "number" && v !== v ? "NaN" : v)));
"""


def test_bad_arguments_throw_naming_them_and_out_is_filled(tmp_path):
    linkage = catalog_linkage("fourbar")
    (tmp_path / "fb.js").write_text(export_files(linkage, "fb", [("speeds", ["rocker", "rocker_speed"], "")], "Fb.")["fb.js"])
    report = json.loads(run_node(tmp_path, ERRORS, str(tmp_path / "fb.js")).stdout)
    arguments = "the arguments are theta, a, b, c, d, branch, thetadot"  # no thetaddot: not needed
    assert report["missing"] == f"RangeError: fourbar: the argument c is missing; {arguments}"
    assert report["missingMany"] == f"RangeError: fourbar: the argument thetadot is missing; {arguments}"
    assert report["nan"] == "RangeError: fourbar: theta must be a finite number, got NaN"
    assert report["infinite"] == "RangeError: fourbar: theta must be a finite number, got Infinity"
    assert report["text"] == 'RangeError: fourbar: theta must be a finite number, got "0.5"'
    assert report["object"] == "RangeError: fourbar: theta must be a finite number, got a value of type object"
    assert report["branch"] == "RangeError: fourbar: branch must be +1 or -1, got 0"
    assert report["length"] == "RangeError: fourbar: a must be a positive finite length, from 1e-305 to 1e305, got -20"
    assert report["tiny"].startswith("RangeError: fourbar: a must be a positive finite length")
    assert report["notValues"].startswith("TypeError: fourbar: solve takes an object mapping every argument's name")
    assert report["column"] == "RangeError: fourbar: theta[1] must be a finite number, got NaN"
    assert report["short"] == "RangeError: fourbar: theta has 2 values, not 3"
    assert report["count"] == "RangeError: fourbar: solveMany's count must be a whole number, got 1.5"
    want = load_numpy_module(numpy_module([("f", linkage.program(["rocker", "rocker_speed"]), "")]))["f"](
        0.5, 20.0, 66.0, 56.0, 80.0, 1, 2.0)
    assert report["out"]["same"] and report["out"]["kept"] == "here" and report["out"]["assembled"] is True
    assert abs(report["out"]["rocker"] - float(want["rocker"])) < 1e-13
    assert report["many"]["count"] == 2 and report["many"]["types"] == ["Float64Array", "Uint8Array"]
    assert report["many"]["rocker"] == [report["out"]["rocker"]] * 2 and report["many"]["assembled"] == [1, 1]
    assert report["scalars"] == 1 and report["extra"] is True
    # a = 50 with b + c = 70 < a + d - ...: theta = 0 cannot be assembled; every output NaN, never a wrong pose.
    assert report["unassembled"] == {"rocker": "NaN", "rocker_speed": "NaN", "assembled": False}


def test_a_guard_below_its_threshold_gives_nan_everywhere(tmp_path):
    """The inverted slider-crank with the crank pin on the pivot (|W| = 2.4e-16 at theta = 2 pi, a = d): not
    assembled, every output NaN, as in NumPy (not sqrt(x)/0 = Inf and a finite angle)."""
    linkage = catalog_linkage("inverted-slider-crank")
    program = linkage.program(["phi", "r"])
    (tmp_path / "isc.js").write_text(javascript_solver(program, "isc", linkage))
    values = {"theta": numpy.array([2 * numpy.pi, 0.0, 0.5]), "a": numpy.ones(3), "d": numpy.ones(3)}
    case = Case(tmp_path, 0, javascript_solver(program, "isc", linkage), list(values), values)
    run_cases(tmp_path, [case])
    solved, _ = case.results(["phi", "r"])
    assert list(solved["assembled"]) == [0.0, 0.0, 1.0]
    assert numpy.isnan(solved["phi"][:2]).all() and numpy.isnan(solved["r"][:2]).all()
    assert numpy.isfinite(solved["phi"][2]) and numpy.isfinite(solved["r"][2])


#: Symbol names that JavaScript reserves, that an object inherits, or that the generated code reads as globals.
JS_HOSTILE = {"coordinate": "constructor", "length": "delete", "vector": "this", "loop": "new", "point": "eval",
              "role": "toString", "extra": "hasOwnProperty", "unknown": "arguments", "other": "Math"}


def hostile_fourbar() -> Linkage:
    """The four-bar with names JavaScript cannot take as locals or that every object has (constructor, ...)."""
    theta = sp.Symbol(JS_HOSTILE["coordinate"], real=True)
    beta, phi = coordinates(f"let {JS_HOSTILE['unknown']}")
    a = sp.Symbol(JS_HOSTILE["length"], positive=True)
    b, c = lengths(f"{JS_HOSTILE['other']} valueOf")
    d = sp.Symbol("delete_", positive=True)  # the renamed local of delete must not take it
    AB, BC = Vector(a, theta, JS_HOSTILE["vector"]), Vector(b, beta, "BC")
    loop = Loop(Vector(d, 0, "AD") + Vector(c, phi, "DC") - BC - AB, name=JS_HOSTILE["loop"])
    return Linkage("four bar", [loop], inputs=[theta], unknowns=[beta, phi],
                   points={"B": AB.as_sum(), JS_HOSTILE["point"]: AB + BC},
                   roles={"crank": theta, JS_HOSTILE["role"]: phi}, extras={JS_HOSTILE["extra"]: beta - phi})


def test_hostile_names_make_javascript_that_runs_and_agrees(tmp_path):
    linkage = hostile_fourbar()
    outputs = [JS_HOSTILE["role"], f"{JS_HOSTILE['role']}_speed", "let", JS_HOSTILE["extra"], "eval_x", "singular"]
    program = linkage.program(outputs)
    names = [s.name for s in program.arguments]
    assert sorted(names) == sorted(["constructor", "delete", "Math", "valueOf", "delete_", "branch", "constructordot"])
    # A solver name with quotes, a script's end, a comment's start and a line separator stays a string.
    name = 'he said "hi" </script><!-- */ \u2028 ${x} \\'
    text = javascript_solver(program, name, linkage, title=name, doc=name)
    assert "</script>" not in text and "<!--" not in text and "\u2028" not in text
    values = {"constructor": 0.5, "delete": 20.0, "Math": 66.0, "valueOf": 56.0, "delete_": 80.0, "branch": -1.0,
              "constructordot": 3.0}
    found = load_everywhere(tmp_path, text, name, values)
    assert found["syntax"] in ("ES2015", "acorn unavailable"), found["syntax"]
    assert all(result == found["results"]["required"] for result in found["results"].values())
    got = found["results"]["required"]
    want = load_numpy_module(numpy_module([("f", program, "")]))["f"](**values)
    assert sorted(got) == sorted(outputs + ["assembled"]) and got["assembled"] is True
    for key in outputs:
        assert abs(got[key] - float(want[key])) <= 1e-13 * max(1.0, abs(float(want[key]))), key
    # The geometry too: its points are B and eval, with the linkage's name as the key.
    found = load_everywhere(tmp_path, javascript_geometry(linkage), "four bar", values)
    assert found["results"]["script"]["assembled"] is True and "x_eval" in found["results"]["script"]


def test_names_and_text_reach_javascript_escaped():
    assert javascript_names(["theta", "delete", "delete_", "this", "Math", "constructor"]) == {
        "theta": "theta", "delete": "delete__", "delete_": "delete_", "this": "this_", "Math": "Math_",
        "constructor": "constructor"}
    for bad in ("symlink_x", "2x", "a-b", "_x", "x y", "th\u0435ta"):
        with pytest.raises(ValueError, match="not usable in JavaScript"):
            javascript_names([bad])
    assert js_string("a</script>&\u2028") == '"a\\u003c/script\\u003e\\u0026\\u2028"'
    assert js_comment("a */ b /* c </d <!e\u2028f") == "/* a * / b / * c < /d < !e f */"
    with pytest.raises(ValueError, match="at least one output"):
        javascript_solver(catalog_linkage("fourbar").program([]), "f")
