"""``symlink tolerance``: the tolerance stack-up of an output along the input range, as a table.

Each row: the input value, the output's nominal value, its worst-case and
statistical (RSS, 3 sigma) deviations (±), the first-order mean shift, and the
dimension that contributes most to its variance there (see :mod:`symlink.workshop.tolerance`).
Angles (inputs, angular outputs and their deviations, angular tolerances) are
in ``--units``; lengths in the linkage's own length unit; speeds in rad/s.

``--samples N`` adds the 3-sigma percentiles of N sampled builds, ``--folder DIR``
makes them on Dask in a resumable folder, ``--plot FILE`` draws the bands and the
contributions (:mod:`symlink.plot.tolerance`).  The output may be a rate
(``rocker_speed``, at ``--crank-speed``) or, with the four-bar's ``--masses``, the
driving torque or a reaction (``input_torque``, ``joint_B_x``; the centres of mass at
fixed distances along the links, so the lengths' tolerances do not move them).
"""
from __future__ import annotations

import argparse
from typing import Any

import numpy

from ..common.angles import from_radians, to_radians, wrap
from .options import (FOURBAR_LENGTHS, output_folder, refuse_together, add_branch_option, add_format_option, add_units_option, assignments,
                      command_help, figure_path, finite, fourbar_lengths, input_sweep, linkage_values, distinct_number_list,
                      seed, whole)
from .dynamics import add_mass_options, fourbar_dynamics
from .output import RowWriter, note

#: More input values than this make a stack-up a benchmark, not a table (each costs 1 + 2 x dimensions solves).
MAX_POINTS = 100_000


def register(commands) -> None:
    """Register ``symlink tolerance``."""
    commands.add_parser("tolerance", populate=_add_options, **command_help(
        "tolerance stack-up of an output along the input range: worst case, RSS and the largest contributor",
        "lengths and length tolerances in any one unit; angles and angular tolerances in --units (deg by default); "
        "a ± band is read as 3 sigma unless --sigma gives one",
        "symlink tolerance fourbar --crank 20 --coupler 66 --rocker 56 --ground 80 --tolerance 0.05 "
        "--output rocker",
        "With a catalog NAME or a linkage FILE, values from its defaults (--set to change); --tolerance applies to "
        "every length (never a fixed angle nor the placement), --tolerances NAME=BAND,... to chosen dimensions; "
        "--play B=0.02,C=0.02 adds the pins' play.\n"
        "--samples N (or --builds N) adds a Monte Carlo of N builds, --folder DIR makes it resumable (Dask, the "
        "extra 'sweep'), --plot FILE draws the bands and the contributions.\n"
        "csv header: INPUT,OUTPUT,worst_case,rss,mean_shift,largest[,play][,sampled_low,sampled_high]"))


def _add_options(command: argparse.ArgumentParser) -> None:
    command.add_argument("linkage", nargs="?", metavar="NAME|FILE",
                         help="a catalog linkage or a linkage file (default: the four-bar of the length options)")
    for option, what in FOURBAR_LENGTHS:
        command.add_argument(f"--{option}", type=finite, help=f"four-bar length {what} (with NAME fourbar, or none)")
    command.add_argument("--set", type=assignments("NAME=VALUE"), default={}, metavar="NAME=VALUE,...",
                         help="parameter values (fixed angles in --units)")
    command.add_argument("--tolerance", type=finite, metavar="BAND",
                         help="± band of every length (of every part: not the fixed angles, nor where the linkage "
                              "stands, such as a drawing's x_A; give those by name in --tolerances)")
    command.add_argument("--tolerances", type=assignments("NAME=BAND"), default={}, metavar="NAME=BAND,...",
                         help="± bands of chosen dimensions (angles in --units); these win over --tolerance")
    command.add_argument("--sigma", type=assignments("NAME=SIGMA"), default={}, metavar="NAME=SIGMA,...",
                         help="standard deviations of chosen dimensions (default: a third of the band)")
    command.add_argument("--play", type=assignments("PIN=PLAY"), default={}, metavar="PIN=PLAY,...",
                         help="radial play of chosen pins (hole radius less pin radius): adds the column "
                              "'play', the linearised worst case over all play directions")
    command.add_argument("--samples", "--builds", dest="builds", type=whole, metavar="N",
                         help="also sample N builds (Monte Carlo, seeded by --seed): adds the columns 'sampled_low' "
                              "and 'sampled_high', the deviation's 0.135 and 99.865 percentiles (3 sigma)")
    command.add_argument("--seed", type=seed, default=0, help="of the sampled builds (default 0)")
    command.add_argument("--folder", type=output_folder, metavar="DIR",
                         help="make the sampled builds on Dask in chunks written to DIR (a sweep's folder): stopped, "
                              "the same command again continues where it stopped (needs the extra 'sweep')")
    command.add_argument("--plot", type=figure_path, metavar="FILE",
                         help="draw the nominal output, its worst-case, statistical and sampled bands along the input "
                              "and the contributions of the dimensions (.png or .svg)")
    command.add_argument("--output", metavar="NAME", help="the output (default: the linkage's last unknown)")
    command.add_argument("--start", type=finite, help="first input value (default 0)")
    command.add_argument("--stop", type=finite, help="last input value, exclusive (default 360 deg)")
    command.add_argument("--step", type=finite, help="input step (default 10 deg)")
    command.add_argument("--angles", type=distinct_number_list, metavar="LIST", help="comma-separated input values")
    command.add_argument("--crank-speed", type=finite, default=0.0, metavar="W",
                         help="the input's speed, rad/s (default 0): for a rate or a force as --output")
    command.add_argument("--crank-accel", type=finite, default=0.0, metavar="AL",
                         help="the input's acceleration, rad/s^2 (default 0): for an acceleration or a force")
    add_branch_option(command, both=False, default="+1")
    add_units_option(command, "input, printed and tolerance angles")
    add_mass_options(command, "the four-bar's mass properties (with --masses, --output may name input_torque "
                              "or a joint force)")
    add_format_option(command)
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ..symbolic.closure import is_angle
    from ..io.linkage_file import load_linkage
    from ..workshop.tolerance import pin_play, sample_builds, stack_up
    from ..numeric.units import output_units
    lengths = fourbar_lengths(args)
    given = [value is not None for value in lengths]
    name = args.linkage if args.linkage is not None else "fourbar"
    if args.linkage is None and not all(given):
        raise ValueError("tolerance: give a catalog NAME (e.g. fourbar) or a linkage FILE, or all of --crank "
                         "--coupler --rocker --ground")
    found = load_linkage(name)
    linkage = found.linkage
    values = linkage_values(found, args.set, args.units)
    if any(given):
        if found.source != "catalog" or linkage.name != "fourbar":
            raise ValueError("tolerance: --crank --coupler --rocker --ground belong to the four-bar; give the values "
                             f"of {linkage.name} with --set NAME=VALUE,...")
        values.update({k: v for k, v in zip("abcd", lengths) if v is not None})
    if args.masses is not None and (found.source != "catalog" or linkage.name != "fourbar"):
        raise ValueError("tolerance: --masses and the other dynamics options belong to the four-bar")
    if linkage.name == "fourbar" and found.source == "catalog":
        dynamic = fourbar_dynamics(args, (values["a"], values["b"], values["c"], values["d"]))
        if dynamic is not None:  # masses at fixed places on the links: the lengths' tolerances do not move them
            linkage = dynamic[0]
    if not linkage.has_closed_form:
        raise ValueError(f"{linkage.name} has no closed form; take its stack-up from Python with stack_up(..., "
                         "guess=...) (its assembly must be chosen)")
    if not linkage.inputs:
        raise ValueError(f"{linkage.name} has no input to sweep")
    symbols = {s.name: s for s in linkage.parameters}
    tolerances = _tolerances(args, symbols, linkage)
    output = args.output or linkage.unknowns[-1].name
    sweep = input_sweep(args)
    if len(sweep) > MAX_POINTS:
        raise ValueError(f"{len(sweep)} input values are too many for a stack-up (at most {MAX_POINTS}); give a "
                         "larger --step")
    first = linkage.inputs[0]
    swept_angle = is_angle(linkage, first)
    shown = sweep.array()
    inputs: dict[str, Any] = {first.name: to_radians(shown, args.units) if swept_angle else shown}
    for other in linkage.inputs[1:]:
        if other.name not in values:
            raise ValueError(f"{linkage.name} needs a value for its input {other.name} (--set {other.name}=VALUE)")
        inputs[other.name] = numpy.full(len(shown), values[other.name])
    values.update({branch.name: int(args.branch) for branch in linkage.branches})
    values.update({f"{first.name}dot": args.crank_speed, f"{first.name}ddot": args.crank_accel})
    if args.play:
        from ..symbolic.vectors import acceleration, rate
        moving = {rate(q) for q in linkage.coordinates} | {acceleration(q) for q in linkage.coordinates}
        if linkage.output(output).free_symbols & moving:  # ValueError naming the outputs for an unknown one
            raise ValueError(f"--play is modelled for positions; {output} moves with the rates")
    result = stack_up(linkage, output, values, tolerances, inputs=inputs)
    if not result.assembled.any():  # every row would be NaN: refused, as every table command refuses it
        raise ValueError(f"{linkage.name} cannot be assembled at any of the input values asked for with these "
                         "dimensions: there is no stack-up to print")
    play = pin_play(linkage, output, values, args.play, inputs=inputs).worst_case[0] if args.play else None
    sampled, builds = None, None
    refuse_together(args, ("seed", "does nothing without --samples N", args.builds is None,
                           "only sampled builds are seeded; the worst case and RSS are not sampled"))
    if args.folder is not None and args.builds is None:
        raise ValueError("--folder holds sampled builds: give their number with --samples N")
    if args.builds is not None:
        if args.builds < 1:
            raise ValueError(f"--samples must be at least 1, got {args.builds}")
        if args.seed < 0:
            raise ValueError(f"--seed must be 0 or more, got {args.seed}")
        if args.folder is not None:
            from ..workshop.sweep import SWEEP_EXTRA, missing_modules
            missing = missing_modules(("dask", "pyarrow"))
            if missing:
                raise ValueError(f"--folder needs {', '.join(missing)}: {SWEEP_EXTRA} (or leave --folder out: the "
                                 "builds are then made in memory)")
        builds = sample_builds(linkage, output, values, tolerances, inputs=inputs, builds=args.builds,
                               seed=args.seed, folder=args.folder)
        sampled = builds.percentile([0.135, 99.865])[:, 0]
        if args.folder is not None:
            note(f"{args.builds} builds in {args.folder}: {builds.reused} chunk{'s' if builds.reused != 1 else ''} "
                 "found done there")
    angular = output_units(linkage, [output]).get(output) == "rad"
    convert = (lambda x: from_radians(x, args.units)) if angular else (lambda x: numpy.asarray(x))  # noqa: E731
    nominal = convert(wrap(result.nominal[0]) if angular else result.nominal[0])
    worst, rss, shift = convert(result.worst_case[0]), convert(result.rss[0]), convert(result.mean_shift[0])
    largest = result.largest_contributor(output)
    columns = ([first.name, output, "worst_case", "rss", "mean_shift", "largest"] + (["play"] if args.play else [])
               + (["sampled_low", "sampled_high"] if sampled is not None else []))
    plays = convert(play) if play is not None else numpy.zeros(len(shown))
    lows, highs = (convert(sampled[0]), convert(sampled[1])) if sampled is not None else (plays, plays)
    output_unit = args.units if angular else ""
    writer = RowWriter(columns, args.format, units={
        first.name: args.units if swept_angle else "", **{c: output_unit for c in (
            output, "worst_case", "rss", "mean_shift", "play", "sampled_low", "sampled_high")}})
    writer.write({first.name: float(x), output: float(y), "worst_case": float(w), "rss": float(r),
                  "mean_shift": float(m), "largest": big or "-", "play": float(p), "sampled_low": float(lo),
                  "sampled_high": float(hi)}
                 for x, y, w, r, m, big, p, lo, hi in zip(shown, nominal, worst, rss, shift, largest, plays, lows,
                                                          highs))
    writer.close()
    kind = output_units(linkage, [output]).get(output) or "the output's units"
    unit = args.units if angular else {"length": "length units"}.get(kind, kind)
    ranking = ", ".join(f"{dim} {float(convert(dev)):.4g}" for dim, dev in result.ranking(output))
    note(f"largest 1-sigma deviation of {output} each dimension causes on the range ({unit}): {ranking}")
    if args.plot is not None:
        from ..plot import save_figure
        from ..plot.tolerance import tolerance_figure
        save_figure(tolerance_figure(result, output, builds, units=args.units, angular_input=swept_angle,
                                     angular_output=angular, title=f"tolerance stack-up of {linkage.name}: {output}"),
                    args.plot)
    return 0


def _tolerances(args: argparse.Namespace, symbols: dict, linkage: Any) -> dict[str, Any]:
    """The dimensions' tolerances from ``--tolerance``, ``--tolerances`` and ``--sigma`` (angles to radians).

    One rule for every linkage, by the kind of each parameter (:func:`symlink.numeric.units.parameter_kinds`):
    ``--tolerance`` bands the lengths only (never a fixed angle, a placement or a mass); a band or a sigma of an
    angle is read in ``--units``; a placement (where the linkage stands: a drawing's ``x_A``) is toleranced only
    when named.
    """
    from ..numeric.units import parameter_kinds
    from ..symbolic.closure import is_angle
    from ..workshop.tolerance import Tolerance
    for option, given in (("--tolerances", args.tolerances), ("--sigma", args.sigma)):
        for name in given:
            if name not in symbols:
                raise ValueError(f"{option}: {linkage.name} has no dimension {name!r}; it has {', '.join(symbols)}")
    kinds = parameter_kinds(linkage)

    def plain(name: str, value: float) -> float:
        return float(to_radians(value, args.units)) if kinds.get(name) == "angle" or (
            kinds.get(name) == "placement" and is_angle(linkage, symbols[name])) else value

    bands: dict[str, float] = {}
    if args.tolerance is not None:
        bands.update({name: args.tolerance for name in symbols if kinds.get(name) == "length"})
    bands.update({name: plain(name, value) for name, value in args.tolerances.items()})
    sigmas = {name: plain(name, value) for name, value in args.sigma.items()}
    if not bands and not sigmas:
        raise ValueError("tolerance: give --tolerance BAND, --tolerances NAME=BAND,... or --sigma NAME=SIGMA,...")
    tolerances = {}
    for name in [*bands, *(s for s in sigmas if s not in bands)]:
        try:
            tolerances[name] = Tolerance(bands.get(name), sigmas.get(name))
        except ValueError as error:
            raise ValueError(f"tolerance of {name}: {error}") from None
    return tolerances
