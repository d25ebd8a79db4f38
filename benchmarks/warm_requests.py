"""Warm requests: a cached dynamics scene against a cached kinematics scene, each in a new process.

The Watt II six-bar (``watt2`` in the catalog), one scene of its output angle and one of the torque
driving it with every moving link massive (``[dynamics]`` in the scene): each run once with an empty
cache (cold: derivation), then three times more, each in a new process with the disk cache only
(warm); printed: the seconds of each (best warm), and warm dynamics over warm kinematics (target:
within 2x).  Timed inside the process, from before ``import symlink`` to the evaluated scene.

    python -m benchmarks.warm_requests
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BODIES = ("crank", "coupler", "rocker", "coupler2", "output")
PARAMETERS = dict(a=20.0, b=66.0, c=56.0, d=80.0, e=50.0, f=60.0, g=70.0, alpha=0.3, gx=120.0, gy=10.0)

_RUN = r"""
import sys, time
start = time.perf_counter()
from symlink.io.scene import read_scene
found = read_scene(sys.argv[1])
result = found.scene.evaluate()
print(time.perf_counter() - start)
"""


def scene_text(outputs: list[str], dynamics: bool) -> str:
    lines = ['linkage = "watt2"', f"outputs = {json.dumps(outputs)}", "[parameters]"]
    lines += [f"{name} = {value}" for name, value in PARAMETERS.items()]
    if dynamics:
        lines += [f"m{i} = {1.0 + i}" for i in range(len(BODIES))] + [f"I{i} = {0.5 + i}" for i in range(len(BODIES))]
    lines += ["[input]", "angles = [0, 30, 60, 90]", "speed = 10.5"]
    if dynamics:
        for i, body in enumerate(BODIES):
            lines += [f"[dynamics.masses.{body}]", f'mass = "m{i}"', f'inertia = "I{i}"']
    return "\n".join(lines) + "\n"


def seconds(scene: Path, cache: str) -> float:
    env = dict(os.environ, SYMLINK_CACHE=cache, PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-c", _RUN, str(scene)], capture_output=True, text=True, env=env,
                          check=True)
    return float(done.stdout.split()[-1])


def measure(repeats: int = 3) -> dict[str, dict[str, float]]:
    found: dict[str, dict[str, float]] = {}
    with tempfile.TemporaryDirectory() as folder:
        for label, outputs, dynamics in (("kinematics", ["output"], False), ("torque", ["input_torque"], True)):
            scene = Path(folder) / f"{label}.toml"
            scene.write_text(scene_text(outputs, dynamics))
            cache = str(Path(folder) / f"cache-{label}")
            cold = seconds(scene, cache)
            found[label] = {"cold": cold, "warm": min(seconds(scene, cache) for _ in range(repeats))}
    return found


def main() -> None:
    found = measure()
    for label, times in found.items():
        print(f"{label:>10}: cold {times['cold']:.3f} s, warm {times['warm']:.3f} s (new process, disk cache)")
    ratio = found["torque"]["warm"] / found["kinematics"]["warm"]
    print(f"warm torque / warm kinematics: {ratio:.2f}x (target <= 2x); load {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
