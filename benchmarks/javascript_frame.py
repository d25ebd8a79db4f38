"""The browser's frame: microseconds a ``solve`` call of a generated JavaScript solver, under Node.

A studio page calls its solver once an animation frame, one configuration a call.  This times
that call for Jansen's leg (:func:`symlink.mechanism.catalog.jansen`, three loops): the drawing
solver (:func:`symlink.codegen.javascript.javascript_geometry`: every joint's and point's x and
y) and the exported solver (``symlink export jansen --to javascript``: positions, speeds,
accelerations and the moving joints), each ``--calls`` calls (10^5 by default) of
``solve(values, out)`` with the crank a step further each call (``out`` reused, as a page keeps
it), after as many calls to warm V8 up; the best and the median of ``--repeats`` runs, with the
CPU model (``/proc/cpuinfo``) and Node's version.  ``solveMany`` over as many crank angles is
timed too (a coupler curve).  Node's clock is ``process.hrtime`` (wall clock).

    python -m benchmarks.javascript_frame [--calls 100000] [--repeats 7] [--linkage jansen]
"""
from __future__ import annotations

import argparse
import json
import platform
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

#: The Node script: argv is the solver's path, the values (JSON), the calls and the repeats.
TIMING = r"""
"use strict";
const solver = require(process.argv[2]);
const values = JSON.parse(process.argv[3]);
const calls = Number(process.argv[4]), repeats = Number(process.argv[5]);
const first = solver.inputs[0], step = 2 * Math.PI / 997;
const out = {};
let assembled = 0, checksum = 0;
function run(count) {
    const start = process.hrtime.bigint();
    for (let i = 0; i < count; i++) {
        values[first] = -Math.PI + step * (i % 997);
        solver.solve(values, out);
        assembled += out.assembled ? 1 : 0;
        checksum += out[solver.outputs[solver.outputs.length - 1]] || 0;
    }
    return Number(process.hrtime.bigint() - start) / 1000 / count;
}
run(calls);  // warm up: V8 optimises the solver
const frames = [];
for (let r = 0; r < repeats; r++) {
    frames.push(run(calls));
}
const angles = new Float64Array(calls);
for (let i = 0; i < calls; i++) {
    angles[i] = -Math.PI + step * (i % 997);
}
const columns = Object.assign({}, values, {[first]: angles});
solver.solveMany(columns);
const many = [];
for (let r = 0; r < repeats; r++) {
    const start = process.hrtime.bigint();
    const result = solver.solveMany(columns);
    many.push(Number(process.hrtime.bigint() - start) / 1000 / calls);
    checksum += result.output[0];
}
process.stdout.write(JSON.stringify({frames: frames, many: many, assembled: assembled / (calls * (repeats + 1)),
                                     checksum: checksum, outputs: solver.outputs.length, node: process.version}));
"""


def cpu_model() -> str:
    """The CPU's model name from ``/proc/cpuinfo`` (else what Python's platform module says)."""
    try:
        with open("/proc/cpuinfo") as info:
            for line in info:
                key, _, value = line.partition(":")
                if key.strip() in ("model name", "Hardware", "cpu model"):
                    return value.strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def solvers(name: str = "jansen") -> dict[str, tuple[str, dict[str, float]]]:
    """``{label: (text, values)}``: a catalog linkage's drawing solver and exported solver, at its example values."""
    from symlink.codegen.javascript import javascript_geometry
    from symlink.io.export import export_texts
    from symlink.io.scene import catalog_linkage
    from symlink.mechanism.catalog import EXAMPLE_VALUES
    linkage = catalog_linkage(name)
    values = {**EXAMPLE_VALUES[name], **{b.name: 1.0 for b in linkage.branches}, linkage.inputs[0].name: 0.0}
    exported, = export_texts(linkage, "javascript").values()
    return {"geometry (every joint's x, y)": (javascript_geometry(linkage), values),
            "export (positions, speeds, accelerations, joints)": (
                exported, {**values, **{s.name: 1.0 if k == 0 else 0.0
                                        for k, s in enumerate(linkage.call_signature()[-2 * len(linkage.inputs):])}})}


def measure(text: str, values: dict[str, float], calls: int, repeats: int, node: str = "node") -> dict:
    """Node's timings of ``solve`` (microseconds a call) and ``solveMany`` (a value) for one solver."""
    with tempfile.TemporaryDirectory() as folder:
        path, script = Path(folder) / "solver.js", Path(folder) / "timing.js"
        path.write_text(text)
        script.write_text(TIMING)
        result = subprocess.run([node, str(script), str(path), json.dumps(values), str(calls), str(repeats)],
                                capture_output=True, text=True, check=False)
    if result.returncode:
        raise RuntimeError(result.stderr.strip())
    return json.loads(result.stdout)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=100_000, help="solve calls a run (default 10^5)")
    parser.add_argument("--repeats", type=int, default=7, help="runs; the best and the median are printed")
    parser.add_argument("--linkage", default="jansen", help="a catalog linkage with a closed form (default jansen)")
    arguments = parser.parse_args(argv)
    node = shutil.which("node")
    if node is None:
        print("no node on PATH: the JavaScript solvers cannot be timed", file=sys.stderr)
        return 2
    found = {label: measure(text, values, arguments.calls, arguments.repeats, node)
             for label, (text, values) in solvers(arguments.linkage).items()}
    version = next(iter(found.values()))["node"]
    print(f"CPU: {cpu_model()}; Node {version}; {arguments.linkage}, {arguments.calls} solve calls a run, "
          f"best and median of {arguments.repeats} runs")
    for label, result in found.items():
        frames, many = sorted(result["frames"]), sorted(result["many"])
        print(f"{label}: {result['outputs']} outputs, {100 * result['assembled']:.0f} % assembled")
        print(f"  solve: {frames[0]:.3f} us a frame (median {frames[len(frames) // 2]:.3f})")
        print(f"  solveMany: {many[0]:.3f} us a value (median {many[len(many) // 2]:.3f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
