"""Render the documentation's pictures into docs/images/: ``python docs/pictures.py``.

* ``angles_seed001.png``: coupler and rocker angle over a crank turn, both branches, for the
  data of the MBsymba worksheet "Kinematic Analysis of a Four Bar Linkage" (a1 = 0.1, a2 = 0.4,
  a3 = 0.25, a4 = 0.30 m);
* ``transmission_seed002.png``: the transmission angle over a turn of the linkage that the
  quick-return paper ("Matlab-Based Graphical Synthesis of Planar Mechanisms") synthesises for
  time ratio 1.25 (L1 = 70, L2 = 16.084, L3 = 69.743, L4 = 50 mm), as its Fig. 9;
* ``coupler_curve.png``: the curves of a coupler point of the seed 001 linkage, both branches;
* ``fourbar.gif``: the seed 001 linkage over a turn in 30 frames, with the coupler point;
* ``jansen.png`` and ``jansen.gif``: Theo Jansen's leg (his holy numbers) with the path of its foot H;
* ``design_atlas.png``: the four-bar's ratio space (crank and coupler over ground, at three rocker
  ratios) coloured by Grashof class and by worst transmission angle, computed by a design sweep;
* ``tolerance_bands.png`` and ``tolerance_large.png``: the tolerance stack-up of the rocker of the
  C-program paper's four-bar (a = 20, b = 66, c = 56, d = 80 mm) beside 10^5 sampled builds, with
  every length to ± 0.05 mm (the linear bands hold) and to ± 8 mm (they do not).

The same pictures come from the command line::

    symlink fourbar --crank 0.1 --coupler 0.4 --rocker 0.25 --ground 0.3 --plot angles.png
    symlink fourbar --crank 16.084 --coupler 69.743 --rocker 50 --ground 70 --plot-transmission mu.png
    symlink curve --crank 0.1 --coupler 0.4 --rocker 0.25 --ground 0.3 --coupler-point 0.3,30 --branch both --out curve.png
    symlink animate --crank 0.1 --coupler 0.4 --rocker 0.25 --ground 0.3 --coupler-point 0.3,30 --out fourbar.gif
    symlink draw jansen --trace H --out jansen.png
    symlink animate jansen --trace H --out jansen.gif
    symlink sweep fourbar atlas/ --vary a=0.05:3,b=0.05:3 --set c=1,d=1 --grid 121   # one slice of the atlas
    symlink tolerance fourbar --crank 20 --coupler 66 --rocker 56 --ground 80 --tolerance 0.05 \
        --samples 100000 --folder builds/ --plot tolerance_bands.png
"""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy

ROOT = Path(__file__).resolve().parent.parent
IMAGES = ROOT / "docs" / "images"
sys.path.insert(0, str(ROOT))

import matplotlib  # noqa: E402

matplotlib.use("Agg")

from symlink import (EXAMPLE_VALUES, angle_figure, animate, animate_linkage, coupler_curve_figure,  # noqa: E402
                     draw_linkage, jansen, save_figure, transmission_figure)

SEED001 = (0.1, 0.4, 0.25, 0.30)
SEED002 = (16.084, 69.743, 50.0, 70.0)  # crank L2, coupler L3, rocker L4, ground L1
COUPLER_POINT = (0.3, math.radians(30))
#: File names, in the order they are written.
PICTURES = ("angles_seed001.png", "transmission_seed002.png", "coupler_curve.png", "fourbar.gif", "jansen.png",
            "jansen.gif", "design_atlas.png", "tolerance_bands.png", "tolerance_large.png")
#: The atlas: crank and coupler over ground from ATLAS_RANGE, ATLAS_GRID values each, at these rocker ratios.
ATLAS_ROCKERS = (0.5, 1.0, 2.0)
ATLAS_RANGE = (0.05, 3.0)
ATLAS_GRID = 121


def render(folder: Path = IMAGES) -> list[Path]:
    """Write every picture into ``folder``; returns their paths."""
    paths = []
    for name in PICTURES:
        path = Path(folder) / name
        DRAWERS[name](path)
        paths.append(path)
    return paths


def angles_seed001(path: Path) -> None:
    """Coupler and rocker angle over a crank turn, both branches (the MBsymba worksheet's four-bar)."""
    save_figure(angle_figure(*SEED001, title="MBsymba four-bar worksheet: a1 = 0.1, a2 = 0.4, a3 = 0.25, "
                                             "a4 = 0.30 m"), path)


def transmission_seed002(path: Path) -> None:
    """The transmission angle over a turn of the quick-return paper's linkage, as its Fig. 9."""
    save_figure(transmission_figure(*SEED002, title="Quick-return paper: L1 = 70, L2 = 16.084, "
                                                    "L3 = 69.743, L4 = 50 mm"), path)


def coupler_curve(path: Path) -> None:
    """The curves of a coupler point of the worksheet's four-bar, both branches."""
    save_figure(coupler_curve_figure(*SEED001, *COUPLER_POINT, branches=(1, -1), crank_angle=math.radians(60),
                                     unit="m"), path)


def fourbar_gif(path: Path) -> None:
    """The worksheet's four-bar over a turn in 30 frames, with its coupler point."""
    animate(*SEED001, path, coupler_point=COUPLER_POINT, size_px=(400, 300), fps=10)


def jansen_png(path: Path) -> None:
    """Theo Jansen's leg (his holy numbers) and the path of its foot H."""
    save_figure(draw_linkage(jansen(), EXAMPLE_VALUES["jansen"], trace=("H",),
                             title="Theo Jansen's leg (holy numbers) and the path of its foot H").figure, path)


def jansen_gif(path: Path) -> None:
    """Theo Jansen's leg walking, 30 frames."""
    animate_linkage(jansen(), EXAMPLE_VALUES["jansen"], path, frames=30, trace=("H",), size_px=(360, 360), fps=10)


def design_atlas(path: Path) -> None:
    """The four-bar's design atlas (:func:`atlas_figure`)."""
    save_figure(atlas_figure(), path)


def atlas_figure():
    """The four-bar's design atlas: Grashof class and worst transmission angle over its ratio space.

    Three slices (rocker over ground 0.5, 1 and 2), each a grid sweep of crank
    and coupler over ground (:mod:`symlink.workshop.sweep`, run through Dask's local
    scheduler into Parquet chunks); white where the linkage does not turn its
    crank fully (no worst transmission angle over a turn).
    """
    import tempfile

    import numpy
    from matplotlib.colors import ListedColormap
    from matplotlib.figure import Figure

    from symlink import GRASHOF_CLASSES
    from symlink import SweepSettings, read_sweep, run_sweep

    classes = list(GRASHOF_CLASSES)
    colours = ListedColormap(["#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#222222", "#e6ab02"])
    figure = Figure(figsize=(11, 7.2), layout="constrained")
    axes = figure.subplots(2, len(ATLAS_ROCKERS), sharex=True, sharey=True)
    low, high = ATLAS_RANGE
    extent = (low, high, low, high)
    with tempfile.TemporaryDirectory() as folder:
        for column, rocker in enumerate(ATLAS_ROCKERS):
            settings = SweepSettings("fourbar", {"a": ATLAS_RANGE, "b": ATLAS_RANGE}, values={"c": rocker, "d": 1.0},
                                     count=ATLAS_GRID, samples=180, harmonics=1, chunk=2000)
            run_sweep(settings, Path(folder) / f"rocker-{column}", scheduler="threads", workers=2)
            table = read_sweep(Path(folder) / f"rocker-{column}")
            shape = (ATLAS_GRID, ATLAS_GRID)  # rows: crank a (the slower index), columns: coupler b
            kind = numpy.array([classes.index(name) for name in table.column("grashof").to_pylist()]).reshape(shape)
            worst = numpy.degrees(numpy.array(table.column("worst_transmission").to_numpy(zero_copy_only=False)))
            turns = numpy.array(table.column("assembles").to_pylist())
            worst = numpy.where(turns, worst, numpy.nan).reshape(shape)
            top, bottom = axes[0][column], axes[1][column]
            classes_image = top.imshow(kind.T, origin="lower", extent=extent, cmap=colours, vmin=-0.5,
                                       vmax=len(classes) - 0.5, interpolation="nearest")
            angle_image = bottom.imshow(worst.T, origin="lower", extent=extent, cmap="viridis", vmin=0, vmax=90,
                                        interpolation="nearest")
            top.set_title(f"rocker / ground = {rocker:g}")
            bottom.set_xlabel("crank / ground")
        for row in axes:
            row[0].set_ylabel("coupler / ground")
    bar = figure.colorbar(classes_image, ax=axes[0].tolist(), ticks=range(len(classes)), shrink=0.9)
    bar.ax.set_yticklabels(classes)
    figure.colorbar(angle_image, ax=axes[1].tolist(), shrink=0.9,
                    label="worst transmission angle over a turn (deg)")
    figure.suptitle("Four-bar design atlas: Grashof class (top) and worst transmission angle where the crank "
                    "turns fully (bottom)")
    return figure


def tolerance_bands(path: Path) -> None:
    """The rocker's tolerance bands with small tolerances (:func:`tolerance_bands_figure`)."""
    save_figure(tolerance_bands_figure(), path)


def tolerance_large(path: Path) -> None:
    """The rocker's tolerance bands with large tolerances (:func:`tolerance_large_figure`)."""
    save_figure(tolerance_large_figure(), path)


def tolerance_bands_figure():
    """The C-program paper's four-bar (mm), every length to ± 0.05 mm: the rocker's worst-case and statistical
    bands along the crank's turn, 10^5 builds sampled on Dask (resumable, in a folder) beside them, and the
    lengths' shares of the variance."""
    import tempfile

    from symlink import fourbar
    from symlink import tolerance_figure
    from symlink import sample_builds, stack_up

    design = {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0, "branch": 1}
    tolerances = dict.fromkeys("abcd", 0.05)
    theta = {"theta": numpy.radians(numpy.arange(0.0, 360.0, 10.0))}
    result = stack_up(fourbar(), "rocker", design, tolerances, inputs=theta)
    with tempfile.TemporaryDirectory() as folder:
        builds = sample_builds(fourbar(), "rocker", design, tolerances, inputs=theta, builds=100_000,
                               folder=Path(folder) / "builds")
    return tolerance_figure(result, sampled=builds, title="Four-bar a = 20, b = 66, c = 56, d = 80 mm, every "
                                                          "length ± 0.05 mm: the rocker")


def tolerance_large_figure():
    """The same four-bar with every length to ± 8 mm: the sampled percentiles leave the linear bands (the rocker
    is no longer linear in the lengths over the band), and where the band is widest the sampled distribution is
    skewed beside the normal one that the linear model predicts."""
    from matplotlib.figure import Figure

    from symlink import fourbar
    from symlink import band_figure, distribution_figure
    from symlink import sample_builds, stack_up

    design = {"a": 20.0, "b": 66.0, "c": 56.0, "d": 80.0, "branch": 1}
    tolerances = dict.fromkeys("abcd", 8.0)
    theta = {"theta": numpy.radians(numpy.arange(0.0, 360.0, 10.0))}
    result = stack_up(fourbar(), "rocker", design, tolerances, inputs=theta)
    builds = sample_builds(fourbar(), "rocker", design, tolerances, inputs=theta, builds=100_000)
    figure = Figure(figsize=(7.0, 9.0), layout="constrained")
    top, middle, bottom = figure.subplots(3, 1, height_ratios=(1.0, 1.4, 1.2))
    band_figure(result, sampled=builds, axes=[top, middle])
    distribution_figure(result, builds, ax=bottom)
    figure.suptitle("The same four-bar, every length ± 8 mm: the linear bands no longer hold")
    return figure


#: The function that draws each picture, by file name.
DRAWERS = {"angles_seed001.png": angles_seed001, "transmission_seed002.png": transmission_seed002,
           "coupler_curve.png": coupler_curve, "fourbar.gif": fourbar_gif, "jansen.png": jansen_png,
           "jansen.gif": jansen_gif, "design_atlas.png": design_atlas, "tolerance_bands.png": tolerance_bands,
           "tolerance_large.png": tolerance_large}

if __name__ == "__main__":
    for path in render():
        print(f"wrote {path.relative_to(ROOT)} ({path.stat().st_size // 1024} kB)")
