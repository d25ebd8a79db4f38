"""Warm requests: cached scenes and warm command lines, each in a new process, beside ``import numpy``.

The Watt II six-bar (``watt2`` in the catalog), one scene of its output angle and one of the torque
driving it with every moving link massive (``[dynamics]`` in the scene): each run once with an empty
cache (cold: derivation), then three times more, each in a new process with the disk cache only
(warm); printed: the seconds of each (best warm), and warm dynamics over warm kinematics (target:
within 2x).  Timed inside the process, from before ``import symlink`` to the evaluated scene.

Then the command line (wall time of ``python -m symlink ...`` in a new process, best of five warm runs
after one cold run with the same ``SYMLINK_CACHE``): warm tables of a closed-form linkage, a Newton linkage
(no closed form) and a linkage file, the four-bar with mass columns, a scene file of the Watt II's driving
torque (``symlink run``), and the start of a sweep (five designs
on the synchronous scheduler: its start-up, Dask and Parquet, is most of it), each over the wall time of
``python -c "import numpy"`` measured in the same run (target for a warm table: within 1.2x).  The time of
``python -c "import sympy"`` is printed beside them: what a warm command that imported SymPy would pay.
Bytecode is cached (in the run's folder, ``PYTHONPYCACHEPREFIX``) as for an installed package, even where
``PYTHONDONTWRITEBYTECODE`` is set: else every run compiles symlink's modules again (about 0.1 s).
CPU of the measured machine: AMD EPYC, 2 cores, AVX2 (shared; ratios only).

    python -m benchmarks.warm_requests
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
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


#: Warm command lines (arguments of ``python -m symlink``); ``{folder}`` is a fresh folder of the run.
COMMANDS = {
    "table watt2 (closed form)": ["table", "watt2", "--angles", "0,50", "--format", "csv", "--branch", "+1"],
    "table stephenson2 (Newton)": ["table", "stephenson2", "--angles", "0,50", "--format", "csv", "--guess",
                                   "coupler=-33,mu=-35,rocker=-73,eta=-68"],
    "table FILE (jansen.toml)": ["table", "{folder}/jansen.toml", "--angles", "0,50", "--format", "csv",
                                 "--branch", "+1"],
    "fourbar --masses": ["fourbar", "--crank", "20", "--coupler", "66", "--rocker", "56", "--ground", "80",
                         "--masses", "1,2,3", "--angles", "0,50", "--format", "csv", "--branch", "1"],
    "run torque scene (watt2)": ["run", "{folder}/torque.toml"],
    "sweep start (5 designs)": ["sweep", "fourbar", "{folder}/sweep-{run}", "--vary", "a=10:20", "--set",
                                "b=66,c=56,d=80", "--grid", "5", "--scheduler", "synchronous", "--no-progress"],
}


def wall(arguments: list[str], env: dict[str, str]) -> float:
    """Seconds of wall time of ``python ARGUMENTS`` in a new process (it must succeed)."""
    start = time.perf_counter()
    subprocess.run([sys.executable, *arguments], capture_output=True, text=True, env=env, check=True)
    return time.perf_counter() - start


def measure_commands(repeats: int = 5) -> dict[str, float]:
    """Best warm wall time of each of :data:`COMMANDS`, and of ``import numpy`` and ``import sympy``."""
    found: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as folder:
        env = dict(os.environ, SYMLINK_CACHE=str(Path(folder) / "cache"), PYTHONPATH=str(ROOT), MPLBACKEND="Agg",
                   PYTHONPYCACHEPREFIX=str(Path(folder) / "pycache"))  # compiled once, as an installed package is
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        (Path(folder) / "jansen.toml").write_text((ROOT / "symlink" / "linkages" / "jansen.toml").read_text())
        (Path(folder) / "torque.toml").write_text(scene_text(["input_torque"], True))
        for library in ("numpy", "sympy"):
            found[f"import {library}"] = min(wall(["-c", f"import {library}"], env) for _ in range(repeats))
        for label, arguments in COMMANDS.items():
            runs = [[a.format(folder=folder, run=run) for a in arguments] for run in range(repeats + 1)]
            wall(["-m", "symlink", *runs[0]], env)  # cold: derives, compiles and fills the cache
            found[label] = min(wall(["-m", "symlink", *run], env) for run in runs[1:])
    return found


def main() -> None:
    found = measure()
    for label, times in found.items():
        print(f"{label:>10}: cold {times['cold']:.3f} s, warm {times['warm']:.3f} s (new process, disk cache)")
    ratio = found["torque"]["warm"] / found["kinematics"]["warm"]
    print(f"warm torque / warm kinematics: {ratio:.2f}x (target <= 2x); load {os.getloadavg()[0]:.2f}")
    commands = measure_commands()
    numpy_seconds = commands["import numpy"]
    print("\nwarm command lines, wall time in a new process (best of 5), over python -c 'import numpy':")
    for label, seconds in commands.items():
        print(f"{label:>28}: {seconds:.3f} s  {seconds / numpy_seconds:5.2f}x")
    print(f"(target: a warm table within 1.2x of import numpy; load {os.getloadavg()[0]:.2f})")


if __name__ == "__main__":
    main()
