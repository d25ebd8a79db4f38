"""Warm requests: cached scenes and warm command lines, each in a new process, beside ``import numpy``.

The Watt II six-bar (``watt2`` in the catalog), one scene of its output angle and one of the torque
driving it with every moving link massive (``[dynamics]`` in the scene): each run once with an empty
cache (cold: derivation), then three times more, each in a new process with the disk cache only
(warm); printed: the seconds of each (best warm), and warm dynamics over warm kinematics (target:
within 2x).  Timed inside the process, from before ``import symlink`` to the evaluated scene.

Then the command line (``python -m symlink ...`` in a new process, after one cold run with the same
``SYMLINK_CACHE``; the median of 15 rounds, ``WARM_REPEATS`` to change, each round running every command and
baseline once in turn, so that a change of load falls on all): warm tables of the catalog's commands
(``symlink fourbar``, with ``--masses``, ``symlink slider-crank``, ``symlink watt2``), of ``symlink table`` for
a closed-form linkage, a Newton linkage (no closed form) and a linkage file, a scene file of the Watt II's
driving torque (``symlink run``), a tolerance stack-up of the four-bar's rocker (``symlink tolerance``), the
four-bar's analysis by its lengths (``symlink analyze --crank ...``: closed form, nothing cached) and of a catalog
linkage and a linkage file (``symlink analyze NAME|FILE``: its facts and code from the cache), a coupler curve
drawn to SVG (``symlink curve``: Matplotlib's import is most of it), pictures of catalog and file linkages
(``symlink curve NAME``, ``draw FILE``, ``animate NAME``) and a solve plan (``symlink plan``), and the start of a
sweep of a catalog linkage and of a linkage file (five designs each, the synchronous scheduler and the default one:
its start-up, Dask and Parquet, is most of it), each in wall time and in CPU time (user + system: less sensitive to
the load of a shared machine) over those of ``python -c "import numpy"`` measured in the same rounds (target for a
warm table: within 1.2x).  ``python -c "import sympy"`` is measured beside them: what a warm command that imported
SymPy would pay; ``python -c "import numpy, matplotlib.pyplot"``: what a picture pays; and ``python -c "import
numpy, dask, pyarrow"``: the floor of a sweep's start.  The load average is printed before and after.
Bytecode is cached (in the run's folder, ``PYTHONPYCACHEPREFIX``) as for an installed package, even where
``PYTHONDONTWRITEBYTECODE`` is set: else every run compiles symlink's modules again (about 0.1 s).
CPU of the measured machine (the performance page's table): Intel Xeon, 2 cores, AVX-512 (load 1.5-1.8; ratios only).

Wall and CPU times of a shared virtual machine wander by a tenth of NumPy's import between rounds, more than what
is measured; ``--instructions`` counts instead the instructions each warm command line of :data:`INSTRUCTION_COMMANDS`
executes (Valgrind's callgrind, ``OPENBLAS_NUM_THREADS=1``: the main thread's work, the same in every run to a few
parts in 10^4), over those of ``python -c "import numpy"``.

    python -m benchmarks.warm_requests
    python -m benchmarks.warm_requests --instructions
"""
from __future__ import annotations

import json
import os
import platform
import re
import resource
import statistics
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


#: The four-bar of the warm table measurements: a Grashof crank-rocker (lengths 2, 7, 9, 6).
FOURBAR_2796 = ["fourbar", "--crank", "2", "--coupler", "7", "--rocker", "9", "--ground", "6", "--step", "30"]
#: Warm command lines (arguments of ``python -m symlink``); ``{folder}`` is a fresh folder of the run.
COMMANDS = {
    "table fourbar": ["table", "fourbar", "--step", "30"],
    "fourbar 2 7 9 6": FOURBAR_2796,
    "fourbar 2 7 9 6 --masses": FOURBAR_2796 + ["--masses", "1,2,3", "--gravity", "9.81"],
    "slider-crank": ["slider-crank", "--crank", "20", "--conrod", "66", "--offset", "5", "--step", "30"],
    "watt2 (two loops)": ["watt2", "--crank", "1", "--coupler", "3.5", "--rocker", "3", "--ground", "3.2",
                          "--rocker-arm", "2", "--rocker-arm-angle", "35", "--coupler2", "4", "--output", "3",
                          "--output-x", "4.5", "--output-y", "3.5", "--step", "30"],
    "table watt2 (closed form)": ["table", "watt2", "--angles", "0,50", "--format", "csv", "--branch", "+1"],
    "table stephenson2 (Newton)": ["table", "stephenson2", "--angles", "0,50", "--format", "csv", "--guess",
                                   "coupler=-33,mu=-35,rocker=-73,eta=-68"],
    "table FILE (jansen.toml)": ["table", "{folder}/jansen.toml", "--angles", "0,50", "--format", "csv",
                                 "--branch", "+1"],
    "run torque scene (watt2)": ["run", "{folder}/torque.toml"],
    "tolerance fourbar 2 7 9 6": ["tolerance", *FOURBAR_2796, "--tolerance", "0.05", "--output", "rocker"],
    "analyze 2 7 9 6 (lengths)": ["analyze", *FOURBAR_2796[1:-2]],
    "analyze jansen --output H_y": ["analyze", "jansen", "--output", "H_y"],
    "analyze FILE (jansen.toml)": ["analyze", "{folder}/jansen.toml", "--set", "a=16"],
    "curve fourbar 2 7 9 6 (SVG)": ["curve", *FOURBAR_2796[1:-2], "--coupler-point", "3,20", "--out",
                                    "{folder}/curve-{run}.svg"],
    "curve fourbar --trace C (SVG)": ["curve", "fourbar", "--trace", "C", "--out", "{folder}/traced-{run}.svg"],
    "draw FILE (jansen.toml, SVG)": ["draw", "{folder}/jansen.toml", "--out", "{folder}/jansen-{run}.svg"],
    "animate fourbar (4 frames, GIF)": ["animate", "fourbar", "--frames", "4", "--out", "{folder}/turn-{run}.gif"],
    "tolerance fourbar --samples 1000 --folder": ["tolerance", *FOURBAR_2796, "--tolerance", "0.05", "--samples",
                                                  "1000", "--folder", "{folder}/builds-{run}"],
    "view fourbar --save (PNG)": ["view", "fourbar", "--save", "{folder}/view-{run}.png"],
    "view FILE --save (jansen.toml, PNG)": ["view", "{folder}/jansen.toml", "--save", "{folder}/view-file-{run}.png"],
    "view 2 7 9 6 --save (lengths, PNG)": ["view", *FOURBAR_2796[1:-2], "--save", "{folder}/view-lengths-{run}.png"],
    "plan watt2": ["plan", "watt2"],
    "sweep start (5 designs)": ["sweep", "fourbar", "{folder}/sweep-{run}", "--vary", "a=10:20", "--set",
                                "b=66,c=56,d=80", "--grid", "5", "--scheduler", "synchronous", "--no-progress"],
    "sweep FILE start (slider-crank.toml)": ["sweep", "{folder}/slider-crank.toml", "{folder}/sweep-file-{run}",
                                             "--vary", "a=0.5:2.5", "--grid", "5", "--samples", "36",
                                             "--no-progress"],
}
#: The baselines, measured in the same rounds: what every command pays (NumPy), what a warm command that
#: imported SymPy would pay, what every picture pays (Matplotlib's pyplot, as much as a drawing imports), and what
#: a sweep's start pays at least (its scheduler and its Parquet files).
BASELINES = {"import numpy": ["-c", "import numpy"], "import sympy": ["-c", "import sympy"],
             "import numpy, matplotlib.pyplot": ["-c", "import numpy, matplotlib.pyplot"],
             "import numpy, dask, pyarrow": ["-c", "import numpy, dask, pyarrow"]}


def wall(arguments: list[str], env: dict[str, str]) -> tuple[float, float]:
    """Seconds of wall time and of CPU time (user + system) of ``python ARGUMENTS`` in a new process (it must
    succeed)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([sys.executable, *arguments], capture_output=True, text=True, env=env, check=True)
    seconds = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return seconds, (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)


def measure_commands(repeats: int = 15) -> dict[str, tuple[float, float]]:
    """Median warm wall and CPU seconds of each of :data:`COMMANDS` and :data:`BASELINES`.

    After one cold run of each command (it derives, compiles and fills the cache), ``repeats`` rounds, each
    running every command and baseline once in turn (interleaved: a change of the machine's load falls on all).
    """
    times: dict[str, list[tuple[float, float]]] = {label: [] for label in [*BASELINES, *COMMANDS]}
    with tempfile.TemporaryDirectory() as folder:
        env = dict(os.environ, SYMLINK_CACHE=str(Path(folder) / "cache"), PYTHONPATH=str(ROOT), MPLBACKEND="Agg",
                   PYTHONPYCACHEPREFIX=str(Path(folder) / "pycache"))  # compiled once, as an installed package is
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        for name in ("jansen.toml", "slider-crank.toml"):
            (Path(folder) / name).write_text((ROOT / "symlink" / "linkages" / name).read_text())
        (Path(folder) / "torque.toml").write_text(scene_text(["input_torque"], True))

        def command(label: str, run: int) -> list[str]:
            if label in BASELINES:
                return BASELINES[label]
            return ["-m", "symlink", *(a.format(folder=folder, run=run) for a in COMMANDS[label])]

        for label in times:
            wall(command(label, -1), env)  # cold: derives, compiles and fills the cache (and the bytecode)
        for run in range(repeats):
            for label in times:
                times[label].append(wall(command(label, run), env))
    return {label: (statistics.median(w for w, _ in found), statistics.median(c for _, c in found))
            for label, found in times.items()}


#: The warm tables, the stack-up, the analysis by lengths and the plan: what ``--instructions`` counts.
INSTRUCTION_COMMANDS = ("table fourbar", "fourbar 2 7 9 6", "fourbar 2 7 9 6 --masses", "slider-crank",
                        "watt2 (two loops)", "table watt2 (closed form)", "table stephenson2 (Newton)",
                        "table FILE (jansen.toml)", "run torque scene (watt2)", "tolerance fourbar 2 7 9 6",
                        "analyze 2 7 9 6 (lengths)", "plan watt2")


def instructions(arguments: list[str], env: dict[str, str]) -> int:
    """The instructions ``python ARGUMENTS`` executes in a new process (Valgrind's callgrind; it must succeed)."""
    done = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", sys.executable,
                           *arguments], capture_output=True, text=True, env=env, check=True)
    return int(re.search(r"Collected : (\d+)", done.stderr).group(1))  # type: ignore[union-attr]


def measure_instructions() -> dict[str, int]:
    """Instructions of ``import numpy`` and of each warm command of :data:`INSTRUCTION_COMMANDS` (after a cold run
    and a warm one with the same cache), with ``OPENBLAS_NUM_THREADS=1``."""
    with tempfile.TemporaryDirectory() as folder:
        env = dict(os.environ, SYMLINK_CACHE=str(Path(folder) / "cache"), PYTHONPATH=str(ROOT), MPLBACKEND="Agg",
                   PYTHONPYCACHEPREFIX=str(Path(folder) / "pycache"), OPENBLAS_NUM_THREADS="1")
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        (Path(folder) / "jansen.toml").write_text((ROOT / "symlink" / "linkages" / "jansen.toml").read_text())
        (Path(folder) / "torque.toml").write_text(scene_text(["input_torque"], True))
        wall(["-c", "import numpy"], env)  # NumPy's bytecode written under the run's prefix
        found = {"import numpy": instructions(["-c", "import numpy"], env)}
        for label in INSTRUCTION_COMMANDS:
            arguments = ["-m", "symlink", *(a.format(folder=folder, run=0) for a in COMMANDS[label])]
            wall(arguments, env)  # cold
            wall(arguments, env)  # warm: the bytecode of symlink's modules and of the cached code written
            found[label] = instructions(arguments, env)
    return found


def main() -> None:
    if sys.argv[1:] == ["--instructions"]:
        counted = measure_instructions()
        print("instructions of each warm command line over those of python -c 'import numpy' (callgrind):")
        for label, count in counted.items():
            print(f"{label:>30}: {count:>12,} {count / counted['import numpy']:6.3f}x")
        return
    found = measure()
    for label, times in found.items():
        print(f"{label:>10}: cold {times['cold']:.3f} s, warm {times['warm']:.3f} s (new process, disk cache)")
    ratio = found["torque"]["warm"] / found["kinematics"]["warm"]
    print(f"warm torque / warm kinematics: {ratio:.2f}x (target <= 2x); load {os.getloadavg()[0]:.2f}")
    load_before = os.getloadavg()
    repeats = int(os.environ.get("WARM_REPEATS", "15"))
    commands = measure_commands(repeats)
    numpy_wall, numpy_cpu = commands["import numpy"]
    print(f"\nwarm command lines in a new process, median of {repeats} interleaved rounds, over "
          "python -c 'import numpy' (wall time and CPU time, user + system):")
    width = max(map(len, commands))
    print(f"{'':>{width}}  {'wall':>8} {'ratio':>6}  {'CPU':>8} {'ratio':>6}")
    for label, (seconds, cpu) in commands.items():
        print(f"{label:>{width}}: {seconds:.3f} s {seconds / numpy_wall:5.2f}x  {cpu:.3f} s {cpu / numpy_cpu:5.2f}x")
    print(f"(target: a warm table within 1.2x of import numpy; CPU: {platform.processor() or platform.machine()}, "
          f"{os.cpu_count()} cores; load average {load_before[0]:.2f} before, {os.getloadavg()[0]:.2f} after)")


if __name__ == "__main__":
    main()
