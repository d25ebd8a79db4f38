"""``symlink synthesize function|path|motion``: four-bars from targets in a csv file.

Each kind of synthesis is one entry of :data:`KINDS` (its parser and its run).  Targets are read from a csv file with a
header row (``-`` reads stdin); numbers only, never expressions:

* ``function``: columns ``theta,phi`` (crank and rocker angle, degrees or ``--units rad``).
  Three rows: the exact three-point design; more: least squares.
* ``path``: columns ``x,y`` (the crank angles are found too, the points reached in their
  order), or ``theta,x,y`` (timing: the crank angle at each point, measured from the
  ground line).
* ``motion``: columns ``x,y,angle`` (2 to 5 poses of the coupler; the angle in degrees or
  ``--units rad``): Burmester theory, with the free choices of fewer than five poses given
  as options.

Designs are printed as a table, csv or json; ``--plot FILE`` (.png or .svg) draws target
against achieved: the points, the achieved curve, and the linkage at each precision point.
"""
from __future__ import annotations

import argparse
import csv
import io
import json
import math
import sys
from typing import Any, Callable, Mapping

import numpy

from ..common.angles import from_radians, to_radians, wrap
from ..common.files import excerpt, read_input_text, read_stdin_text
from ..common.numbers import number_from_text
from ..numeric.input_sweep import MAX_ANGLE
from ..common.limits import format_bytes
from .budget import MEMORY_BUDGET, add_time_budget_option, budget_text, format_duration, require_budget, time_budget
from .options import (Parser, add_format_option, add_units_option, angle, assignments, command_help, figure_path,
                      finite, given_options, linkage_values, name_list, output_file, pair, seed, whole)
from .output import json_number, note, print_rows

#: Columns a csv of targets may have, by kind.
FUNCTION_COLUMNS = (("theta", "phi"),)
PATH_COLUMNS = (("x", "y"), ("theta", "x", "y"))
MOTION_COLUMNS = (("x", "y", "angle"),)
#: The target columns that hold angles (the others are coordinates).
ANGLE_COLUMNS = frozenset({"theta", "phi", "angle"})
#: Most rows a target file may have.
MAX_ROWS = 10_000
#: Target files larger than this are refused unread (10,000 rows of three numbers fit in under 1 MB).
MAX_TARGET_BYTES = 4 << 20
#: Most linkage poses drawn by --plot (evenly chosen among the precision points).
MAX_POSES = 12


#: Target coordinates beyond this size, or non-zero below its inverse, are refused: a design's lengths are squared
#: and multiplied in its equations, and 1e100 ** 3 is still a float.
MAX_COORDINATE = 1e100


def _check_target(value: float, column: str, where: str, angles: frozenset[str] = ANGLE_COLUMNS) -> None:
    """``ValueError`` naming ``where`` for a target value that is not finite or out of range for its column."""
    if not math.isfinite(value):
        raise ValueError(f"{where}: {column} must be a finite number, got {value!r}")
    if column in angles:
        if abs(value) > MAX_ANGLE:
            raise ValueError(f"{where}: {column} must be at most {MAX_ANGLE:g} in size (larger angles have lost "
                             f"their precision), got {value:g}")
    elif value != 0 and not 1 / MAX_COORDINATE <= abs(value) <= MAX_COORDINATE:
        raise ValueError(f"{where}: {column} must be 0 or between {1 / MAX_COORDINATE:g} and {MAX_COORDINATE:g} in "
                         f"size (rescale the targets), got {value:g}")


def read_targets(path: str, allowed: tuple[tuple[str, ...], ...],
                 angles: frozenset[str] = ANGLE_COLUMNS) -> dict[str, numpy.ndarray]:
    """Columns of a csv file with one of the ``allowed`` headers, as float arrays; ``ValueError`` naming a bad line.

    Values of the columns named in ``angles`` are checked as angles, the others as coordinates.
    """
    if path == "-":
        text = read_stdin_text(MAX_TARGET_BYTES, "csv of targets")
    else:
        text = read_input_text(path, MAX_TARGET_BYTES, "csv of targets")
    expected = " or ".join(repr(",".join(a)) for a in allowed)
    rows: list[tuple[int, list[str]]] = []  # (line of the file, cells), blank lines left out
    reader = csv.reader(io.StringIO(text, newline=""))
    try:
        for row in reader:
            if any(cell.strip() for cell in row):
                rows.append((reader.line_num, row))
                if len(rows) - 1 > MAX_ROWS:
                    raise ValueError(f"{path}:{reader.line_num}: more than {MAX_ROWS:,} rows of targets")
    except csv.Error as error:  # a NUL byte, a field beyond the csv module's limit
        raise ValueError(f"{path}:{reader.line_num}: not a csv file: {error}") from None
    if not rows:
        raise ValueError(f"{path}: no header row; expected columns {expected}")
    header = tuple(cell.strip().lower() for cell in rows[0][1])
    if header not in allowed:
        raise ValueError(f"{path}:{rows[0][0]}: the header is {excerpt(','.join(header))}; expected {expected}")
    values = []
    for number, row in rows[1:]:
        if len(row) != len(header):
            raise ValueError(f"{path}:{number}: {len(row)} values, expected {len(header)} ({','.join(header)})")
        parsed = []
        for name, cell in zip(header, row):
            try:
                parsed.append(number_from_text(cell))
            except ValueError as error:
                raise ValueError(f"{path}:{number}: {name}: {error}") from None
        for name, value in zip(header, parsed):
            _check_target(value, name, f"{path}:{number}", angles)
        values.append(parsed)
    array = numpy.array(values, dtype=float).reshape(-1, len(header))
    return {name: array[:, k] for k, name in enumerate(header)}


# --- function generation ------------------------------------------------------------------------

def _register_function(kinds) -> None:
    command = kinds.add_parser("function", **command_help(
        "a four-bar whose rocker angle follows the crank angle through (theta, phi) pairs (Freudenstein)",
        "angles in degrees (--units rad); lengths in the ground's unit",
        "symlink synthesize function pairs.csv --ground 1",
        "The csv has the header theta,phi.  Three rows give the exact three-point design, more rows the least-"
        "squares design (weighted to rocker-angle error, re-weighted towards the smallest largest error).  The "
        "crank pivot is at the origin and the rocker pivot at (ground, 0)."))
    command.add_argument("linkage", nargs="?", metavar="LINKAGE", help="a catalog NAME or a linkage FILE: the "
                         "general route, for any linkage (without it: the four-bar)")
    command.add_argument("targets", metavar="FILE", help="csv of theta,phi; with LINKAGE INPUT,OUTPUT (- for stdin)")
    command.add_argument("--ground", type=finite, default=1.0, metavar="L", help="ground length (default 1)")
    add_units_option(command)
    add_format_option(command)
    command.add_argument("--plot", type=figure_path, metavar="FILE", help="draw wanted against generated (.png/.svg)")
    add_general_options(command, "function")
    command.set_defaults(run=_routed(_run_function, "function", command))


FUNCTION_FIELDS = ["crank", "coupler", "rocker", "ground", "branch", "crank_offset", "rocker_offset",
                   "K1", "K2", "K3", "structural_error", "worst_transmission"]


def _run_function(args: argparse.Namespace) -> int:
    from ..synthesis.function import least_squares_design, three_point_design
    columns = read_targets(args.targets, FUNCTION_COLUMNS)
    theta, phi = (numpy.asarray(to_radians(columns[name], args.units), dtype=float) for name in ("theta", "phi"))
    design = (three_point_design if len(theta) == 3 else least_squares_design)(theta, phi, ground=args.ground)
    angle = lambda x: float(from_radians(x, args.units))  # noqa: E731
    crank_angles = numpy.asarray(design.theta) + design.crank_offset  # the linkage's own crank angle
    linkage, (placed, defaults, left, signs) = fourbar_design_file("function", design.lengths, design.branch,
                                                                   crank_angles)
    run = design_transmission(placed, defaults, signs, crank_angles)
    row = {"method": design.method, "crank": design.crank, "coupler": design.coupler, "rocker": design.rocker,
           "ground": design.ground, "branch": design.branch, "crank_offset": angle(design.crank_offset),
           "rocker_offset": angle(design.rocker_offset), "K1": design.coefficients[0],
           "K2": design.coefficients[1], "K3": design.coefficients[2], "grashof": design.grashof,
           "structural_error": angle(design.structural_error),
           "worst_transmission": angle(run.worst) if run is not None else math.nan}
    if args.format == "json":
        print(json.dumps([{k: json_number(v) for k, v in row.items()}], indent=1))
    else:
        print_rows([row], FUNCTION_FIELDS, args.format, units=dict.fromkeys(
            ("crank_offset", "rocker_offset", "structural_error", "worst_transmission"), args.units))
        note(f"{design.method} design, {design.grashof}; structural error in {args.units} over the given crank angles")
    report_transmission(run, args.units)
    write_outputs({
        args.out: lambda: design_text(placed, defaults, (
            f"# Designed by 'symlink synthesize function' ({design.method}): structural error "
            f"{angle(design.structural_error):.6g} {args.units}; "
            f"{_branch_words(linkage, {'branch': design.branch}, left)}.\n"
            f"# The crank angle theta here is the targets' theta + crank_offset ({angle(design.crank_offset):.6g} "
            f"{args.units}), the rocker angle phi the targets' phi + rocker_offset "
            f"({angle(design.rocker_offset):.6g} {args.units}); theta is at the first target.\n")),
        args.plot: lambda: _function_figure(design, args.units)})
    return 0


def _function_figure(design, units: str):
    """Wanted against generated rocker angle of a four-bar function generator (a Matplotlib figure)."""
    from matplotlib.figure import Figure

    from ..synthesis.function import ERROR_SAMPLES, _solve_rocker
    figure = Figure(figsize=(7.0, 4.5), layout="constrained")
    axis = figure.subplots()
    theta = numpy.asarray(design.theta)
    sweep = numpy.linspace(theta.min(), theta.max(), ERROR_SAMPLES)
    generated = _solve_rocker(design.lengths, sweep, design.branch, design.offsets)["rocker"]
    generated = numpy.unwrap(numpy.asarray(generated))
    shift = 2 * math.pi * numpy.round((design.phi[0] - generated[numpy.argmin(abs(sweep - theta[0]))]) / (2 * math.pi))
    axis.plot(from_radians(sweep, units), from_radians(generated + shift, units), color="tab:blue",
              label="generated")
    axis.plot(from_radians(theta, units), from_radians(numpy.asarray(design.phi), units), "o", color="tab:red",
              label="wanted")
    axis.set_xlabel(f"crank angle theta ({units})")
    axis.set_ylabel(f"rocker angle phi ({units})")
    axis.set_title(f"Function generation ({design.method}): structural error "
                   f"{float(from_radians(design.structural_error, units)):.3g} {units}", fontsize="medium")
    axis.legend(loc="best", fontsize="small")
    return figure


# --- path generation ----------------------------------------------------------------------------

def _register_path(kinds) -> None:
    from ..synthesis.path import GRASHOF_CHOICES
    command = kinds.add_parser("path", **command_help(
        "a four-bar whose coupler point passes through points, with or without timing",
        "lengths in the points' unit; angles in degrees (--units rad)",
        "symlink synthesize path points.csv --grashof crank-rocker --plot path.png",
        "The csv has the header x,y (the crank angles are found too; the points are reached in their order) or "
        "theta,x,y (the crank angle at each point, from the ground line).  Needs SciPy: "
        "pip install 'symlink-kinematics[synthesis]'.  The coupler point is (u, v) in the coupler's frame "
        "(u along B->C, v to its left); frame is the direction from the crank pivot to the rocker pivot."))
    command.add_argument("linkage", nargs="?", metavar="LINKAGE", help="a catalog NAME or a linkage FILE: the "
                         "general route, for any linkage (without it: the four-bar)")
    command.add_argument("targets", metavar="FILE", help="csv of x,y or theta,x,y; with LINKAGE INPUT,x,y for the "
                         "timed form (- for stdin)")
    command.add_argument("--designs", type=whole, default=3, metavar="K", help="print up to K distinct designs (default 3)")
    command.add_argument("--starts", type=whole, default=8, metavar="N", help="refine N atlas starts (default 8)")
    command.add_argument("--grashof", choices=GRASHOF_CHOICES, default="any",
                         help="Grashof class (crank-turns: crank-rocker or double-crank; default any)")
    command.add_argument("--max-link-ratio", type=finite, default=20.0, metavar="R",
                         help="longest link at most R times the shortest (default 20; with LINKAGE: no bound "
                              "unless given)")
    command.add_argument("--min-transmission", type=angle, default=0.0, metavar="ANGLE",
                         help="worst transmission angle at least this over the motion each design runs: the "
                              "full turn for a crank that turns fully, else between its first and last target "
                              "(default 0; with LINKAGE: at every loop with two unknown angles)")
    command.add_argument("--seed", type=seed, default=0, help="seed of the atlas of starts (default 0)")
    add_units_option(command)
    add_format_option(command)
    command.add_argument("--plot", type=figure_path, metavar="FILE",
                         help="draw targets, achieved curve and the linkage at each point (.png/.svg)")
    add_general_options(command, "path")
    command.set_defaults(run=_routed(_run_path, "path", command))


PATH_FIELDS = ["rank", "error", "x0", "y0", "frame", "crank", "coupler", "rocker", "ground", "u", "v", "branch",
               "worst_transmission"]


#: Seconds of path synthesis a point and a start, measured with a margin (40 random points, which no four-bar
#: reaches, 8 starts: 23 s on a shared machine, every attempt run to its end); its memory grows with the square of
#: the points (a Jacobian of the points by their crank angles), about 1.1 GB at 9,000 points a copy.
PATH_SECONDS_PER_POINT_START = 0.1
PATH_BYTES_PER_POINT_SQUARED = 100


def _check_path_work(points: int, starts: int, kind: str = "path") -> None:
    """``ValueError`` (one line) for a ``kind`` synthesis beyond the command's memory or time (see :mod:`.budget`)."""
    if starts < 1:
        raise ValueError(f"--starts must be at least 1, got {starts}")
    memory = points ** 2 * PATH_BYTES_PER_POINT_SQUARED
    if memory > MEMORY_BUDGET:
        fits = math.isqrt(MEMORY_BUDGET // PATH_BYTES_PER_POINT_SQUARED)
        raise ValueError(f"a {kind} synthesis of {points:,} points would need about {format_bytes(memory)} of memory "
                         f"(at most {format_bytes(MEMORY_BUDGET)} a command); give at most {fits:,} points")
    seconds = points * starts * PATH_SECONDS_PER_POINT_START
    budget = time_budget()
    if seconds > budget:
        fits = int(budget / (points * PATH_SECONDS_PER_POINT_START) + 1e-9)  # 3600 / 0.6 is 6000, not 5999
        remedy = f"use --starts {fits:,} or fewer" if fits >= 1 else "give fewer points"
        raise ValueError(f"a {kind} synthesis of {points:,} points from {starts:,} starts could take about "
                         f"{format_duration(seconds)} ({budget_text()}); {remedy}")


def _run_path(args: argparse.Namespace) -> int:
    from ..synthesis.path import synthesize_path
    columns = read_targets(args.targets, PATH_COLUMNS)
    _check_path_work(len(columns["x"]), args.starts)
    targets = numpy.stack([columns["x"], columns["y"]], axis=1)
    theta = numpy.asarray(to_radians(columns["theta"], args.units), dtype=float) if "theta" in columns else None
    designs = synthesize_path(targets, theta, starts=args.starts, designs=args.designs, grashof_class=args.grashof,
                              max_link_ratio=args.max_link_ratio,
                              min_transmission=float(to_radians(args.min_transmission, args.units)), seed=args.seed)
    angle = lambda x: float(wrap(from_radians(x, args.units), 180.0 if args.units == "deg" else math.pi))  # noqa: E731
    rows, files = [], []
    for rank, design in enumerate(designs, start=1):
        files.append(fourbar_design_file("path", design.lengths, design.branch, design.theta,
                                         point=design.coupler_point, pivot=design.crank_pivot, frame=design.frame))
        placed, defaults, _, signs = files[-1][1]
        run = design_transmission(placed, defaults, signs, design.theta)
        rows.append({"rank": rank, "error": design.error, "x0": design.crank_pivot[0], "y0": design.crank_pivot[1],
                     "frame": angle(design.frame), "crank": design.crank, "coupler": design.coupler,
                     "rocker": design.rocker, "ground": design.ground, "u": design.coupler_point[0],
                     "v": design.coupler_point[1], "branch": design.branch, "grashof": design.grashof,
                     "worst_transmission": float(from_radians(run.worst, args.units)) if run is not None
                     else math.nan, "run": run})
    runs = [row.pop("run") for row in rows]
    if args.format == "json":
        for row, design, run in zip(rows, designs, runs):
            row.update(grashof=design.grashof, theta=[angle(t) for t in design.theta], errors=list(design.errors),
                       **({"transmission_over": transmission_over(run, args.units)} if run is not None else {}))
        print(json.dumps([{k: [json_number(x) for x in v] if isinstance(v, list) else json_number(v)
                           for k, v in row.items()} for row in rows], indent=1))
    else:
        print_rows(rows, PATH_FIELDS, args.format, units=dict.fromkeys(("frame", "worst_transmission"), args.units))
        for rank, design in enumerate(designs, start=1):
            note(f"design {rank}: {design.grashof}; crank angles at the points ({args.units}): "
                 + " ".join(f"{angle(t):.6g}" for t in design.theta))
    note("the error column: the largest distance from a target to the coupler point, over the targets' size "
         "(their bounding-box diagonal)")
    for rank, run in enumerate(runs, start=1):
        report_transmission(run, args.units, f"design {rank}")
    if args.min_transmission > 0:
        note(f"--min-transmission {args.min_transmission:g} {args.units} held over the motion each design runs "
             "(the full turn for a crank that turns fully, else between its first and last target), in every "
             "trial of the search")
    if files:  # the first design is the one written
        linkage, (placed, defaults, left, _) = files[0]
        write_outputs({
            args.out: lambda: design_text(placed, defaults, (
                f"# Designed by 'symlink synthesize path' (design 1 of {len(designs)}): error {designs[0].error:.3g}; "
                f"{_branch_words(linkage, {'branch': designs[0].branch}, left)}.\n"
                "# P is the traced coupler point; theta (from the ground line A->D) is at the first target.\n")),
            args.plot: lambda: path_figure(designs[0], targets)})
    return 0


def path_figure(design, targets: numpy.ndarray):
    """Targets, the achieved coupler curve, and the linkage at each precision point (up to :data:`MAX_POSES`)."""
    from matplotlib.figure import Figure
    from matplotlib.transforms import Affine2D

    from ..plot.figures import MechanismDrawing, frame_plane
    figure = Figure(figsize=(6.4, 5.6), layout="constrained")
    axis = figure.subplots()
    theta = numpy.asarray(design.theta)
    span = theta[-1] - theta[0]
    sweep = numpy.linspace(theta[0], theta[0] + (2 * math.pi if abs(span) < 1e-12 else 2 * math.pi * numpy.sign(span)),
                           721)
    curve = design.joints(sweep)["P"]
    axis.plot(curve.real, curve.imag, color="0.3", linewidth=1, label="coupler curve", zorder=4)
    place = Affine2D().rotate(design.frame).translate(*design.crank_pivot) + axis.transData
    shown = numpy.unique(numpy.linspace(0, len(theta) - 1, min(len(theta), MAX_POSES)).round().astype(int))
    everything = [curve, targets[:, 0] + 1j * targets[:, 1]]
    for index in shown:
        drawing = MechanismDrawing(axis, coupler_point=True)
        a, b, c, d = design.lengths
        local = design.joints([theta[index]])
        turn = complex(math.cos(-design.frame), math.sin(-design.frame))
        origin = complex(*design.crank_pivot)
        B, C, P = ((local[name][0] - origin) * turn for name in ("B", "C", "P"))
        drawing.update(d, (B.real, B.imag), (C.real, C.imag), (P.real, P.imag))
        for artist in drawing.artists:
            artist.set_transform(place)
            artist.set_alpha(0.35 if len(shown) > 1 else 1.0)
            if index != shown[0]:
                artist.set_label("_nolegend_")
        everything += [local[name] for name in ("A", "B", "C", "D")]
    axis.plot(targets[:, 0], targets[:, 1], "x", color="black", markersize=9, markeredgewidth=2, label="targets",
              zorder=7)
    points = numpy.concatenate([numpy.ravel(z) for z in everything])
    frame_plane(axis, points.real, points.imag)
    axis.set_title(f"Path generation: error {design.error:.2g} of the targets' size", fontsize="medium")
    axis.legend(loc="best", fontsize="small")
    return figure


# --- motion generation --------------------------------------------------------------------------

def _register_motion(kinds) -> None:
    command = kinds.add_parser("motion", **command_help(
        "four-bars whose coupler passes through 2 to 5 poses (rigid-body guidance, Burmester theory)",
        "lengths in the poses' unit; angles in degrees (--units rad)",
        "symlink synthesize motion poses.csv --defect-free --plot motion.png",
        "The csv has the header x,y,angle: the coupler's reference point and its angle in each pose.  Five "
        "poses: the Burmester points, every pair of them as crank and rocker.  Fewer poses leave free choices: "
        "four need --rotation twice (the crank's turn from pose 1 to pose 2 of each dyad), three need "
        "--moving-pivot twice (in pose 1's coupler position) or --fixed-pivot twice, two need --moving-pivot "
        "and --offset twice each (along the perpendicular bisectors).  Designs are listed defect-free first, "
        "then by their worst transmission angle at the poses."))
    command.add_argument("linkage", nargs="?", metavar="LINKAGE", help="a catalog NAME or a linkage FILE: the "
                         "general route, for any linkage (without it: the four-bar)")
    command.add_argument("targets", metavar="FILE", help="csv of x,y,angle; with LINKAGE also INPUT,x,y,angle "
                         "(- for stdin)")
    command.add_argument("--moving-pivot", type=pair("X,Y"), action="append", metavar="X,Y",
                         help="a moving pivot in pose 1 (give two)")
    command.add_argument("--fixed-pivot", type=pair("X,Y"), action="append", metavar="X,Y",
                         help="a fixed pivot (give two, three poses)")
    command.add_argument("--rotation", type=angle, action="append", metavar="ANGLE",
                         help="a dyad's turn from pose 1 to pose 2 (give two, four poses)")
    command.add_argument("--offset", type=finite, action="append", metavar="L",
                         help="a fixed pivot's place along its bisector (give two, two poses)")
    command.add_argument("--defect-free", action="store_true", help="only designs without a branch or order defect")
    command.add_argument("--designs", type=whole, default=12, metavar="K", help="print up to K designs (default 12)")
    add_units_option(command)
    add_format_option(command)
    command.add_argument("--plot", type=figure_path, metavar="FILE",
                         help="draw the poses, Burmester curves and the first design at each pose (.png/.svg)")
    add_general_options(command, "motion")
    command.set_defaults(run=_routed(_run_motion, "motion", command))


#: Columns of ``symlink synthesize motion`` before the per-pose ``crank_angle_K, branch_K``; angles in --units.
MOTION_FIELDS = ["rank", "crank", "coupler", "rocker", "ground", "crank_pivot_x", "crank_pivot_y", "rocker_pivot_x",
                 "rocker_pivot_y", "crank_moving_x", "crank_moving_y", "rocker_moving_x", "rocker_moving_y",
                 "ground_angle", "coupler_point_distance", "coupler_point_angle", "pose_angle_offset", "grashof",
                 "branch_defect", "order_defect", "order_direction", "transmission_worst", "pose_error",
                 "worst_transmission"]


def _run_motion(args: argparse.Namespace) -> int:
    from ..synthesis.motion import as_record, motion_generation
    if args.designs < 1:
        raise ValueError(f"--designs must be at least 1, got {args.designs}")
    columns = read_targets(args.targets, MOTION_COLUMNS)
    angles = numpy.asarray(to_radians(columns["angle"], args.units), dtype=float)
    poses = [(float(x), float(y), float(a)) for x, y, a in zip(columns["x"], columns["y"], angles)]
    rotations = None if args.rotation is None else [float(to_radians(r, args.units)) for r in args.rotation]
    designs = motion_generation(poses, moving_pivots=args.moving_pivot, fixed_pivots=args.fixed_pivot,
                                rotations=rotations, offsets=args.offset, defect_free=args.defect_free)
    if not designs:
        raise ValueError("no four-bar guides the coupler through these poses with the choices given"
                         + (" without a defect" if args.defect_free else ""))
    shown = designs[:args.designs]
    per_pose = [f"{name}_{k}" for k in range(1, len(poses) + 1) for name in ("crank_angle", "branch")]
    rows, files, runs = [], [], []
    for rank, design in enumerate(shown, start=1):
        distance, turn = design.coupler_point_distance, design.coupler_point_angle
        files.append(fourbar_design_file("motion", (design.crank, design.coupler, design.rocker, design.ground),
                                         design.branches[0], design.crank_angles,
                                         point=(distance * math.cos(turn), distance * math.sin(turn)),
                                         pivot=design.crank_pivot, frame=design.ground_angle))
        placed, defaults, _, signs = files[-1][1]
        runs.append(design_transmission(placed, defaults, signs, design.crank_angles))
        rows.append({"rank": rank, **as_record(design, args.units),
                     "worst_transmission": float(from_radians(runs[-1].worst, args.units)) if runs[-1] is not None
                     else math.nan})
    if args.format == "json":
        print(json.dumps([{k: json_number(v) if isinstance(v, float) else v for k, v in row.items()}
                          for row in rows], indent=1))
    else:
        angle_columns = ("ground_angle", "coupler_point_angle", "pose_angle_offset", "transmission_worst",
                         "pose_error", "worst_transmission", *(f"crank_angle_{k}" for k in range(1, len(poses) + 1)))
        print_rows(rows, MOTION_FIELDS + per_pose, args.format, units=dict.fromkeys(angle_columns, args.units))
        note(f"{len(designs)} design(s), {sum(d.defect_free for d in designs)} without a branch or order defect; "
             f"angles in {args.units}; transmission_worst at the poses, worst_transmission over the motion run")
    for rank, run in enumerate(runs, start=1):
        report_transmission(run, args.units, f"design {rank}")
    def figure():
        from ..plot.synthesis import motion_figure
        return motion_figure(poses, shown[0])
    if files:  # the first design is the one written
        linkage, (placed, defaults, left, _) = files[0]
        write_outputs({
            args.out: lambda: design_text(placed, defaults, (
                f"# Designed by 'symlink synthesize motion' (design 1 of {len(designs)}); "
                f"{_branch_words(linkage, {'branch': shown[0].branches[0]}, left)} at the first pose.\n"
                "# P is the guided point (the poses' origin); theta (from the ground line A->D) is at the first pose.\n")),
            args.plot: figure})
    return 0


# --- any linkage: LINKAGE|FILE given ------------------------------------------------------------

#: Options of the four-bar route of each kind (by destination): they do nothing with a LINKAGE.
FOURBAR_ONLY = {"function": ("ground",),
                "path": ("designs", "grashof"),
                "motion": ("moving_pivot", "fixed_pivot", "rotation", "offset", "defect_free", "designs")}
#: Options of the general route of each kind (by destination): they need a LINKAGE.
GENERAL_ONLY = {"function": ("set", "free", "bound", "branch", "output", "minimax", "record", "seed",
                             "starts"),
                "path": ("set", "free", "bound", "branch", "point", "frame", "record", "shape", "shape_kind",
                         "samples", "full_rotation"),
                "motion": ("set", "free", "bound", "branch", "point", "angle", "frame", "record", "seed",
                           "starts")}
#: Designs sampled for a shape match (``--shape``) unless --samples says.
SHAPE_SAMPLES = 2000
#: Suffixes of --record.
RECORD_SUFFIXES = (".json", ".csv")


def _bound(text: str) -> tuple[str, tuple[float, float]]:
    """``NAME=LO,HI`` of --bound (numbers only)."""
    name, equals, values = text.partition("=")
    numbers = values.split(",")
    if not equals or not name.strip() or len(numbers) != 2:
        raise argparse.ArgumentTypeError(f"expected NAME=LO,HI, got {excerpt(text)}")
    low, high = (finite(number) for number in numbers)
    if not low < high:
        raise argparse.ArgumentTypeError(f"{excerpt(name.strip())}: the low bound must be below the high one, "
                                         f"got {low:g},{high:g}")
    return name.strip(), (low, high)


def _names(text: str) -> list[str]:
    """Comma-separated names (``--free a,b``), each once."""
    return name_list(text)


def _frame(text: str) -> tuple[str, ...]:
    """``--frame x0,y0,angle,scale`` (the free parts of the placement) or ``none``."""
    from ..synthesis.general import FRAME_NAMES
    if text.strip() == "none":
        return ()
    names = tuple(_names(text))
    wrong = [name for name in names if name not in FRAME_NAMES]
    if wrong or len(set(names)) != len(names):
        raise argparse.ArgumentTypeError(f"expected some of {','.join(FRAME_NAMES)} each once, or none; got "
                                         f"{excerpt(text)}")
    return names


def _signs(text: str) -> dict[str, int]:
    """``--branch NAME=+1,NAME=-1``."""
    signs = {}
    for name, value in assignments("NAME=SIGN")(text).items():
        if value not in (1.0, -1.0):
            raise argparse.ArgumentTypeError(f"{excerpt(name)}: a branch is +1 or -1, got {value:g}")
        signs[name] = int(value)
    return signs


def _linkage_path(text: str) -> str:
    if not text.endswith(".toml"):
        raise argparse.ArgumentTypeError(f"the design is written as a linkage file: the name must end in .toml, got "
                                         f"{excerpt(text)}")
    return output_file(text)


def _record_path(text: str) -> str:
    if not text.lower().endswith(RECORD_SUFFIXES):
        raise argparse.ArgumentTypeError(f"the record is .json or .csv, got {excerpt(text)}")
    return output_file(text)


def add_general_options(command: argparse.ArgumentParser, kind: str) -> None:
    """The options of ``symlink synthesize KIND LINKAGE|FILE TARGETS``: any linkage, by exact gradients."""
    group = command.add_argument_group("any linkage (with LINKAGE)")
    group.add_argument("--free", type=_names, action="append", metavar="NAME[,NAME...]",
                       help="parameters that may change (bounds: --bound, else half to twice a length's value, "
                            "an angle's value +-180 deg, another's value +-max(1, |value|))")
    group.add_argument("--bound", type=_bound, action="append", metavar="NAME=LO,HI",
                       help="bounds of a free parameter (makes it free; angles in --units)")
    group.add_argument("--set", type=assignments("NAME=VALUE"), default={}, metavar="NAME=VALUE,...",
                       help="values of the parameters (default: the file's [defaults], a catalog entry's example)")
    group.add_argument("--branch", type=_signs, metavar="NAME=SIGN,...",
                       help="fix branch signs (default: both tried)")
    if kind in ("path", "motion"):
        group.add_argument("--point", metavar="NAME", help="the linkage's point that " + (
            "traces the path" if kind == "path" else "is the guided link's frame point (default: the named point "
                                                     "where the link at --angle starts)"))
        group.add_argument("--frame", type=_frame, metavar="LIST",
                           help="free parts of the placement: some of x0,y0,angle,scale, or none (default "
                                + ("all" if kind == "path" else "x0,y0,angle") + ")")
    if kind == "path":
        group.add_argument("--full-rotation", action="store_true",
                           help="the input turns a whole turn without leaving the assembly or passing a toggle")
        group.add_argument("--shape", action="store_true",
                           help="match the points' shape only (x,y in order along the curve, without timing, "
                                "position, turn or scale): sampled designs ranked by shape distance, the best "
                                "placed on the points and refined through them")
        kinds = group.add_mutually_exclusive_group()
        for name, what in (("closed", "the points go round a whole closed path: the input turns fully (default)"),
                           ("open", "the points are the whole path of an input that rocks between its limits"),
                           ("partial", "the points are a piece of a closed path")):
            kinds.add_argument(f"--{name}", dest="shape_kind", action="store_const", const=name,
                               help=f"with --shape: {what}")
        group.add_argument("--samples", type=whole, default=SHAPE_SAMPLES, metavar="N",
                           help=f"with --shape: designs sampled for the shape match (default {SHAPE_SAMPLES})")
    if kind == "function":
        group.add_argument("--output", metavar="NAME",
                           help="the output generated (default: the csv's second column, else the last unknown)")
        group.add_argument("--minimax", action="store_true",
                           help="level the errors: the smallest largest error (default: least squares)")
    if kind == "motion":
        group.add_argument("--angle", metavar="NAME", help="the output that is the guided link's angle")
    if kind != "path":  # path has its own
        group.add_argument("--starts", type=whole, default=8, metavar="N", help="refine N starts (default 8)")
        group.add_argument("--seed", type=seed, default=0, help="seed of the sampled starts (default 0)")
    command.add_argument("--out", type=_linkage_path, metavar="FILE.toml",
                         help="write the design (the first listed) as a linkage file with its [defaults], the "
                              "placement in its points" + ("" if kind == "function" else
                                                           ", the traced point P (the four-bar) or --point")
                              + ": every command reads it")
    group.add_argument("--record", type=_record_path, metavar="FILE",
                       help="write the design, targets and errors (.json) or one row a target (.csv)")
    add_time_budget_option(command)


def _routed(fourbar_run: Callable[[argparse.Namespace], int], kind: str,
            command: argparse.ArgumentParser) -> Callable[[argparse.Namespace], int]:
    """The run of a kind: the general route when a LINKAGE is given, else the four-bar's; options of the other
    route refused (they would do nothing)."""
    def run(args: argparse.Namespace) -> int:
        named = args.linkage is not None
        others = set(FOURBAR_ONLY[kind] if named else GENERAL_ONLY[kind])
        # appended and flag options are not tracked as given: they are given when they differ from their default
        given = given_options(args) | {dest for dest in others
                                       if getattr(args, dest, None) != command.get_default(dest)}
        unused = sorted(given & others)
        if unused:
            option = "--" + unused[0].replace("_", "-")
            raise ValueError(f"synthesize {kind}: {option} does nothing " + (
                f"with a LINKAGE ({args.linkage}); it belongs to the four-bar form (without LINKAGE)" if named else
                "without a LINKAGE (the four-bar form); it belongs to 'synthesize "
                f"{kind} LINKAGE FILE'"))
        return _run_general(args, kind) if named else fourbar_run(args)
    return run


def _general_setup(args: argparse.Namespace):
    """The linkage, the values of its parameters (radians) and the free parameters with their bounds."""
    from ..symbolic.closure import is_angle
    from ..io.linkage_file import load_linkage
    found = load_linkage(args.linkage)
    linkage = found.linkage
    if len(linkage.inputs) != 1:
        raise ValueError(f"{linkage.name} has {len(linkage.inputs)} inputs; synthesis drives one")
    values = linkage_values(found, args.set, args.units)
    symbols = {p.name: p for p in linkage.parameters}
    named = [name for names in (args.free or []) for name in names]
    bounds = dict(args.bound or [])
    for name in named + list(bounds):
        if name not in symbols:
            raise ValueError(f"{linkage.name} has no parameter {name!r}; it has {', '.join(symbols)}")
    free = {}
    for name in dict.fromkeys(named + list(bounds)):
        if name in bounds:
            low, high = bounds[name]
            if is_angle(linkage, symbols[name]):
                low, high = float(to_radians(low, args.units)), float(to_radians(high, args.units))
        elif name not in values:
            raise ValueError(f"give --bound {name}=LO,HI: {linkage.name} has no value of {name!r} to bound it by")
        elif symbols[name].is_positive:
            low, high = values[name] / 2, values[name] * 2
        else:
            half = math.pi if is_angle(linkage, symbols[name]) else max(1.0, abs(values[name]))
            low, high = values[name] - half, values[name] + half
        free[name] = (low, high)
    if not free:
        raise ValueError("name the parameters that may change: --free NAME or --bound NAME=LO,HI")
    known = {**{name: v for name, v in values.items() if name in symbols}}
    return found, linkage, known, free


def _input_column(linkage, header: tuple[str, ...]) -> str | None:
    first = header[0]
    return first if first in ("input", linkage.inputs[0].name) else None


def _run_general(args: argparse.Namespace, kind: str) -> int:
    from ..symbolic.closure import is_angle
    found, linkage, values, free = _general_setup(args)
    input_name = linkage.inputs[0].name
    input_is_angle = is_angle(linkage, linkage.inputs[0])
    inputs_in = ("input", input_name)
    if kind == "function":
        solved = [n for n in linkage.output_names() if linkage.output(n) in linkage.unknowns]
        seconds = ("output", args.output) if args.output else ("output", *solved)
        headers = tuple((first, second) for first in inputs_in for second in seconds)
        generic_angle = _angle_output(linkage, args.output or linkage.unknowns[-1].name)
        angles = frozenset([*(inputs_in if input_is_angle else ()), *(n for n in solved if _angle_output(linkage, n)),
                            *(("output",) if generic_angle else ())])
        columns = read_targets(args.targets, headers, angles)
        names = list(columns)
        output = args.output or (names[1] if names[1] != "output" else linkage.unknowns[-1].name)
        if linkage.output(output) not in linkage.unknowns:
            raise ValueError(f"--output: {output!r} is not an unknown of {linkage.name} (an angle or a length it "
                             f"solves for): name one of {', '.join(solved)}")
    else:
        extra = ("angle",) if kind == "motion" else ()
        headers = (("x", "y", *extra),) + tuple((first, "x", "y", *extra) for first in inputs_in)
        columns = read_targets(args.targets, headers,
                               frozenset(extra) | (frozenset(inputs_in) if input_is_angle else frozenset()))
        names = list(columns)
    count = len(next(iter(columns.values())))
    _check_path_work(count, args.starts, kind)
    timed_column = _input_column(linkage, tuple(names))
    timed = (None if timed_column is None else numpy.asarray(to_radians(columns[timed_column], args.units)
                                                             if input_is_angle else columns[timed_column], dtype=float))
    design: Any
    shape: dict[str, Any] = {}  # a shape match: its kind and the shape distances before and after refinement
    if kind == "function":
        from ..synthesis.general_function import synthesize_function
        wanted = columns[names[1]]
        if _angle_output(linkage, output):
            wanted = numpy.asarray(to_radians(wanted, args.units), dtype=float)
        assert timed is not None
        design = synthesize_function(linkage, output, timed, wanted, free, values=values, branches=args.branch,
                                     starts=args.starts, seed=args.seed, minimax=args.minimax)
        placement: dict[str, float] = {}
        point = output
    elif kind == "path" and args.shape:
        from ..synthesis.shape import synthesize_shape
        _check_shape_options(args, timed_column)
        point = _point_option(args, linkage)
        matched = synthesize_shape(linkage, point, numpy.stack([columns["x"], columns["y"]], axis=1), free,
                                   kind=args.shape_kind or "closed", values=values, branches=args.branch,
                                   designs=args.samples, refine=args.starts, seed=args.seed)
        design, placement = matched.path, matched.path.placement
        shape = {"shape": matched.kind, "sampled_distance": matched.sampled_distance,
                 "shape_distance": matched.distance}
    elif kind == "path":
        from ..synthesis.general import FRAME_NAMES, synthesize_path
        if args.shape_kind or args.samples != SHAPE_SAMPLES:
            option = f"--{args.shape_kind}" if args.shape_kind else "--samples"
            raise ValueError(f"{option} belongs to a shape match: add --shape")
        point = _point_option(args, linkage)
        targets = numpy.stack([columns["x"], columns["y"]], axis=1)
        ratio = args.max_link_ratio if "max_link_ratio" in given_options(args) else None  # no bound unless asked
        if ratio is not None and not ratio >= 1.0:
            raise ValueError(f"--max-link-ratio must be at least 1, got {args.max_link_ratio:g}")
        design = synthesize_path(linkage, point, targets, free, values=values,
                                 frame=FRAME_NAMES if args.frame is None else args.frame, timed=timed,
                                 branches=args.branch, starts=args.starts, seed=args.seed, max_link_ratio=ratio,
                                 min_transmission=float(to_radians(args.min_transmission, args.units)),
                                 full_rotation=args.full_rotation)
        placement = design.placement
    else:
        from ..synthesis.general_motion import frame_point, synthesize_motion
        if args.angle is None:
            raise ValueError("name the guided link's angle: --angle NAME (an unknown or role that is an angle)")
        point = frame_point(linkage, args.angle) if args.point is None else _point_option(args, linkage)
        poses = numpy.stack([columns["x"], columns["y"], numpy.asarray(to_radians(columns["angle"], args.units))],
                            axis=1)
        design = synthesize_motion(linkage, point, args.angle, poses, free, values=values,
                                   frame=("x0", "y0", "angle") if args.frame is None else args.frame, timed=timed,
                                   branches=args.branch, starts=args.starts, seed=args.seed)
        placement = design.placement
    error = design.structural_error if kind == "function" else design.error
    from ..synthesis.placement import placed_assembly
    placed, defaults, left, signs = design_linkage(linkage, design.design, design.branches, placement,
                                                   float(design.inputs[0]))
    assembly = getattr(design, "assembly", None)  # no closed form: the assembly found, as Newton's guess
    guess = placed_assembly(linkage, assembly, placement) if assembly else None
    symbols = {q.name: q for q in linkage.unknowns}
    run = design_transmission(placed, defaults, signs, design.inputs, guess) if design.assembled else None
    record = {**_general_record(args, kind, linkage, design, placement, error, columns,
                                {name: defaults[name] for name in design.design}, run), **shape}
    _print_general(args, record)
    if not design.assembled:
        raise ValueError(f"no verified design: {design.why}; the closest is printed above, nothing is written "
                         "(widen the bounds, free more parameters or give more --starts)")
    report_transmission(run, args.units)
    source = found.source if found.source != "catalog" else linkage.name
    measured = (f"position error {record['position_error']:.3g}, angle error {record['angle_error']:.3g} "
                f"{args.units}" if kind == "motion" else f"error {record['error']:.3g}")
    head = (f"# Designed by 'symlink synthesize {kind} {source}': {measured}; "
            f"{_branch_words(linkage, design.branches, left)}.\n")
    if assembly:  # no closed form: the assembly is the guess that finds it
        head += (f"# Assembly at the first target (the initial guess of Newton's method, angles in {args.units}): "
                 + ", ".join(f"{k}={float(from_radians(v, args.units)) if is_angle(linkage, symbols[k]) else v!r}"
                             for k, v in (guess or {}).items()) + ".\n")
    write_outputs({
        args.out: lambda: design_text(placed, defaults, head),
        args.record: lambda: _record_text(args.record, record),
        args.plot: lambda: _general_figure(kind, linkage, design, placement, columns, args.units, point)})
    return 0


def _check_shape_options(args: argparse.Namespace, timed_column: str | None) -> None:
    """``ValueError`` for what a shape match cannot take: timing, a placement that is not free, or more --samples
    than a command may trace (its designs are traced a chunk at a time: the memory stays bounded, the time not)."""
    from ..synthesis.shape import SECONDS_PER_DESIGN
    require_budget(args.samples, 0, SECONDS_PER_DESIGN, f"a shape match of --samples {args.samples:,}", "--samples")
    if timed_column is not None:
        raise ValueError(f"--shape matches points without timing: the csv's columns are x,y, not "
                         f"{timed_column},x,y")
    if args.frame is not None:
        raise ValueError("--frame does nothing with --shape: a shape's placement is free (shift, turn and scale)")
    for option, given in (("--max-link-ratio", "max_link_ratio" in given_options(args)),
                          ("--min-transmission", "min_transmission" in given_options(args)),
                          ("--full-rotation", args.full_rotation)):
        if given:
            raise ValueError(f"{option} does nothing with --shape (a path fit without --shape takes it)")


def _angle_output(linkage, name: str) -> bool:
    from ..synthesis.design_fit import is_angle_output
    return is_angle_output(linkage, name)


def _point_option(args: argparse.Namespace, linkage) -> str:
    if args.point is None:
        raise ValueError(f"name the point with --point NAME (one of {', '.join(linkage.points)})")
    if args.point not in linkage.points:
        raise ValueError(f"--point: {linkage.name} has no point {args.point!r}; it has {', '.join(linkage.points)}")
    return args.point


def _general_record(args, kind: str, linkage, design, placement, error: float, columns,
                    written: dict | None = None, run=None) -> dict:
    """What a general design is: printed (one row), and written whole by --record (angles in --units).

    ``written``: the design's parameters as the linkage file holds them (lengths times the placement's scale),
    printed in their place; ``run``: the worst transmission over the motion it runs."""
    from ..symbolic.closure import is_angle
    angles = {p.name for p in linkage.parameters if is_angle(linkage, p)}
    unit = lambda x: float(from_radians(x, args.units))  # noqa: E731
    as_input = unit if is_angle(linkage, linkage.inputs[0]) else float
    targets = [[float(columns[name][k]) for name in columns] for k in range(len(next(iter(columns.values()))))]
    # per target: path, the distance; function, generated - wanted (an angle in --units); motion, the distance (the
    # poses' length unit) and the angle's error (--units), each in its own field: one number would mix the units
    if kind == "motion":
        measured = {"position_error": float(design.position_error), "angle_error": unit(design.angle_error),
                    "poses_size": float(design.size)}
        per_target = {"position_errors": list(map(float, design.position_errors)),
                      "angle_errors": [unit(a) for a in design.angle_errors]}
    else:
        errors = design.errors
        if kind == "function" and _angle_output(linkage, design.output):
            error, errors = unit(error), [unit(e) for e in errors]  # an angle's error in the targets' unit
        measured, per_target = {"error": error}, {"errors": list(map(float, errors))}
    return {"kind": kind, "linkage": linkage.name, "assembled": design.assembled, **measured,
            "evaluations": design.evaluations,
            "design": {name: unit(v) if name in angles else v for name, v in (written or design.design).items()},
            "placement": {name: unit(v) if name == "angle" else v for name, v in placement.items()},
            "branches": dict(design.branches), "inputs": [as_input(q) for q in design.inputs],
            **({"assembly": {name: unit(v) if is_angle(linkage, q) else v
                             for q in linkage.unknowns for name, v in design.assembly.items() if name == q.name}}
               if getattr(design, "assembly", None) else {}),
            "columns": list(columns), "targets": targets, **per_target,
            **({"constraints": list(design.constraints), "active": list(design.active)}
               if getattr(design, "constraints", ()) else {}),
            **({"worst_transmission": unit(run.worst), "transmission_over": transmission_over(run, args.units, as_input)}
               if run is not None else {}),
            "units": args.units, "why": design.why}


def _print_general(args: argparse.Namespace, record: dict) -> None:
    measured = ("position_error", "angle_error") if record["kind"] == "motion" else ("error",)
    row = {**{name: record[name] for name in measured}, "assembled": "yes" if record["assembled"] else "no",
           **record["design"], **record["placement"], **{k: f"{v:+d}" for k, v in record["branches"].items()},
           **({"worst_transmission": record["worst_transmission"]} if "worst_transmission" in record else {})}
    if args.format == "json":
        print(json.dumps({k: ([json_number(x) for x in v] if isinstance(v, list) and v and not isinstance(v[0], list)
                              else {n: json_number(x) for n, x in v.items()} if isinstance(v, dict) else
                              json_number(v) if isinstance(v, float) else v) for k, v in record.items()}, indent=1))
        return
    print_rows([row], list(row), args.format)
    note(f"{record['kind']} design of {record['linkage']} ({record['evaluations']} evaluations); inputs at the "
         f"targets ({args.units}): " + " ".join(f"{q:.6g}" for q in record["inputs"]))
    if "shape" in record:
        note(f"{record['shape']} shape matched: shape distance {record['sampled_distance']:.3g} sampled, "
             f"{record['shape_distance']:.3g} refined (0: similar curves, at most 1)")
    for held in record.get("constraints", ()):
        if held.startswith("transmission angle"):
            note(f"held in every trial of the search: {held}")
    if record["placement"].get("scale", 1.0) != 1.0:
        note(f"lengths as written (the linkage's own scaled by {record['placement']['scale']:.6g})")
    if record["kind"] == "motion":
        note("the error columns: position_error, the largest distance from a pose to the link's point (the poses' "
             f"length unit); angle_error, the largest |link angle - pose angle| ({args.units}); the fit weighs one "
             f"radian as the poses' size, {record['poses_size']:.6g} (the diagonal of their bounding box)")
        return
    note("the error column: " + {"function": f"the largest |generated - wanted| output ({args.units} for an angle)",
                                 "path": "the largest distance from a target to the point, over the targets' size"
                                 }[record["kind"]])


def _record_text(path: str, record: dict) -> str:
    """The record of a design as ``path`` holds it: JSON for a .json file, else csv (one row a target)."""
    if path.lower().endswith(".json"):
        text = json.dumps(_json_ready(record), indent=1) + "\n"
    else:
        out = io.StringIO()
        writer = csv.writer(out, lineterminator="\n")
        # one column an error, named as the printed row names it: motion, position_error and angle_error
        fields = (("position_errors", "angle_errors") if record["kind"] == "motion" else ("errors",))
        writer.writerow(["target", "input", *record["columns"], *(name.removesuffix("s") for name in fields)])
        for k, (q, target) in enumerate(zip(record["inputs"], record["targets"])):
            writer.writerow([k + 1, repr(q), *map(repr, target), *(repr(record[name][k]) for name in fields)])
        text = out.getvalue()
    return text


def _json_ready(value):
    if isinstance(value, dict):
        return {k: _json_ready(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_json_ready(v) for v in value]
    if isinstance(value, float):
        return json_number(value)
    return value


def _general_figure(kind: str, linkage, design, placement, columns, units: str, point: str):
    """The design over its targets: the linkage at the first target with the traced path (motion: each pose's
    angle a short line from its point), or wanted against generated output (function)."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(6.4, 5.2), layout="constrained")
    axis = figure.subplots()
    inputs = numpy.asarray(design.inputs)
    if kind == "function":
        from ..synthesis.general_function import function_values
        assembly = getattr(design, "assembly", None)  # no closed form: continued from the first input, in order
        sweep = numpy.linspace(inputs[0], inputs[-1], 401) if assembly else numpy.linspace(inputs.min(), inputs.max(),
                                                                                           401)
        generated = function_values(linkage, design.output, design.design, sweep, assembly or design.branches)
        wanted = numpy.asarray(design.wanted)
        angle = _angle_output(linkage, design.output)
        degrees = lambda x: from_radians(x, units)  # noqa: E731
        output_shown = degrees if angle else numpy.asarray
        input_shown = degrees if _input_angle(linkage) else numpy.asarray
        if angle:  # the generated curve on the turn of the wanted values
            generated = numpy.unwrap(generated)
            generated += 2 * math.pi * numpy.round((wanted[0] - numpy.interp(inputs[0], sweep, generated))
                                                   / (2 * math.pi))
        axis.plot(input_shown(sweep), output_shown(generated), color="tab:blue", label="generated")
        axis.plot(input_shown(inputs), output_shown(wanted), "o", color="tab:red", label="wanted")
        axis.set_xlabel(f"{linkage.inputs[0].name}" + (f" ({units})" if _input_angle(linkage) else ""))
        axis.set_ylabel(design.output + (f" ({units})" if angle else ""))
        axis.set_title(f"Function generation, {linkage.name}: structural error {design.structural_error:.3g}",
                       fontsize="medium")
        axis.legend(loc="best", fontsize="small")
        return figure
    from ..plot.drawing import draw_linkage
    from ..synthesis.placement import placed_design
    from ..synthesis.placement import placed_assembly
    placed, values = placed_design(linkage, design.design, placement)
    assembly = getattr(design, "assembly", None)  # no closed form: the assembly found, as the drawing's guess
    draw_linkage(placed, {**values, **design.branches, linkage.inputs[0].name: float(inputs[0])}, axis,
                 guess=placed_assembly(linkage, assembly, placement) if assembly else None,
                 trace=[point], title=f"{kind.capitalize()} generation, {linkage.name}: error {design.error:.2g}")
    x, y = columns["x"], columns["y"]
    axis.plot(x, y, "x", color="black", markersize=9, markeredgewidth=2, label="targets", zorder=7)
    if kind == "motion":
        turn = numpy.asarray(to_radians(columns["angle"], units), dtype=float)
        size = max(float(numpy.hypot(numpy.ptp(x), numpy.ptp(y))), 1e-300) * 0.3
        for k, (px, py, a) in enumerate(zip(x, y, turn)):  # each pose's angle: a short line from its point
            axis.plot([px, px + size * math.cos(a)], [py, py + size * math.sin(a)], color="black", linewidth=2,
                      zorder=7, label="pose angles" if k == 0 else "_nolegend_")
    axis.legend(loc="best", fontsize="small")
    axis.relim()
    axis.autoscale_view()
    return figure


def _input_angle(linkage) -> bool:
    from ..symbolic.closure import is_angle
    return is_angle(linkage, linkage.inputs[0])



# --- a design you can use: written as a linkage file, its transmission over the motion it runs ---------------

def design_linkage(linkage, values: dict, branches: dict, placement: dict, input_value: float):
    """The design as a linkage of its own, as a linkage file holds it: the placement written into it
    (:func:`~symlink.synthesis.placement.placed_design`: lengths scaled, points shifted and turned), the found
    assembly every branch's +1 where it can be (:func:`~symlink.synthesis.placement.with_default_branches`).

    Returns the linkage, its defaults (every parameter and the input at the first target), the branch signs
    that are not +1 (a slider's loop keeps its sign) and every branch sign as a command takes it.
    """
    from ..synthesis.placement import placed_design, with_default_branches
    ordered, left = with_default_branches(linkage, branches)
    placed, defaults = placed_design(ordered, values, placement)
    defaults[linkage.inputs[0].name] = float(input_value)
    signs = {b.name: int(left.get(b.name, 1)) for b in placed.branches}
    return placed, defaults, left, signs


def design_text(placed, defaults: dict, head: str) -> str:
    """A designed linkage as a linkage file's text (``head``: comment lines saying where it came from)."""
    from ..io.linkage_file import linkage_text
    return head + linkage_text(placed, defaults)


def write_outputs(makers: Mapping[str | None, Callable[[], Any]]) -> None:
    """Write the files a synthesis was asked for (``--out``, ``--record``, ``--plot``: path -> what makes its text,
    bytes or figure; a path of ``None`` was not asked for): all of them or, on any failure (a full disk after the
    up-front check), none (:func:`~symlink.common.files.write_files_together`), then say which were written."""
    from pathlib import Path

    from ..common.files import write_files_together
    from ..plot.figures import figure_bytes
    wanted = {path: make for path, make in makers.items() if path}
    if not wanted:
        return
    made: dict[Path, str | bytes] = {}
    for path, make in wanted.items():
        content = make()
        made[Path(path)] = content if isinstance(content, (str, bytes)) else figure_bytes(content, path)
    write_files_together(made)
    for path in wanted:
        note(f"wrote {path}")


def _branch_words(linkage, branches: dict, left: dict) -> str:
    return (("found with branches " + ", ".join(f"{k}={v:+d}" for k, v in branches.items()) + ", written so that "
             if branches else "") + ("no branch signs" if not linkage.branches else
                                     "the default branch signs (+1) give the found assembly" if not left else
                                     "the found assembly is at " + ", ".join(f"{k}={v:+d}" for k, v in left.items())
                                     + " (a slider's loop keeps its sign), +1 elsewhere"))


def design_transmission(placed, defaults: dict, signs: dict, inputs, guess: dict | None = None):
    """The worst transmission angle over the motion the design runs (:func:`~symlink.analysis.transmission.
    run_transmission`: the full turn for a crank, the rocking range between the targets otherwise), or None."""
    from ..analysis.transmission import run_transmission
    values = {name: v for name, v in defaults.items() if name != placed.inputs[0].name}
    try:
        return run_transmission(placed, {**values, **signs}, inputs, guess=guess)
    except ValueError:
        return None


def transmission_over(run, units: str, as_input: Callable[[float], float] | None = None) -> str:
    """What a record says the worst transmission is over: ``full turn``, or ``rocking range LOW to HIGH`` of the
    input (in ``units`` for an angle: ``as_input`` converts, default an angle)."""
    if run.over == "full turn":
        return "full turn"
    shown = as_input or (lambda x: float(from_radians(x, units)))
    return f"rocking range {shown(run.low):.6g} to {shown(run.high):.6g}"


def transmission_text(run, units: str) -> str:
    """``12.3 deg over the full turn`` (or the rocking range), in ``units``."""
    if run is None:
        return "none (no loop with a transmission angle, or not assembled at the first target)"
    show = lambda x: f"{float(from_radians(x, units)):.4g}"  # noqa: E731
    over = ("the full turn" if run.over == "full turn" else
            f"the rocking range {show(run.low)} to {show(run.high)} {units}")
    return f"{show(run.worst)} {units} over {over} (loop {run.loop})"


def report_transmission(run, units: str, what: str = "the design") -> None:
    """A note of the worst transmission angle over the motion; a warning line below the sane default."""
    from ..analysis.transmission import SANE_TRANSMISSION
    note(f"{what}: worst transmission angle {transmission_text(run, units)}")
    if run is not None and not run.sane:
        note(f"warning: {what} transmits badly: its worst transmission angle "
             f"{float(from_radians(run.worst, units)):.4g} {units} is below "
             f"{float(from_radians(SANE_TRANSMISSION, units)):.4g} {units} (it may lock or need large forces)")


def _fourbar_for(point: tuple[float, float] | None):
    """The catalog four-bar, with the coupler point ``P`` at (u, v) in the coupler's frame when ``point`` is given."""
    from ..mechanism.catalog import fourbar, with_point
    base = fourbar()
    return with_point(base, "B", base.roles["coupler"]) if point is not None else base


def fourbar_design_file(kind: str, lengths, branch: int, inputs, *, point: tuple[float, float] | None = None,
                        pivot: tuple[float, float] = (0.0, 0.0), frame: float = 0.0):
    """A four-bar route's design as a linkage (placed, defaults, left, signs): crank a, coupler b, rocker c,
    ground d, the coupler point P at (u, v) (path, motion), its crank pivot at ``pivot`` and ground line at
    ``frame``; the input at the first of ``inputs``."""
    linkage = _fourbar_for(point)
    values = dict(zip("abcd", map(float, lengths)))
    if point is not None:
        values.update(u=float(point[0]), v=float(point[1]))
    placement = {"x0": float(pivot[0]), "y0": float(pivot[1]), "angle": float(frame)}
    return linkage, design_linkage(linkage, values, {"branch": int(branch)}, placement, float(inputs[0]))

#: The kinds of synthesis: name -> function registering its parser.
KINDS: dict[str, Callable] = {"function": _register_function, "path": _register_path, "motion": _register_motion}


def register(commands) -> None:
    """Register ``symlink synthesize KIND`` (the kinds are added when it is used: they need the synthesis modules)."""
    commands.add_parser("synthesize", populate=_add_kinds, **command_help(
        "synthesize four-bars, or any linkage, from targets in a csv: " + "|".join(KINDS),
        "angles in degrees (--units rad)", "symlink synthesize path points.csv",
        "'symlink synthesize KIND --help' describes a kind.  With a LINKAGE (a catalog NAME or a linkage FILE) "
        "before the csv, any one-input linkage is synthesised by exact gradients: --free/--bound name the "
        "parameters that may change, --out writes the design as a linkage file, --record the design and its "
        "errors."))


def _add_kinds(command: argparse.ArgumentParser) -> None:
    kinds = command.add_subparsers(dest="kind", required=True, parser_class=Parser, metavar="KIND")
    for add in KINDS.values():
        add(kinds)
