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
from typing import Any, Mapping

import numpy

from ..common.angles import from_radians, to_radians, wrap
from .options import (FOURBAR_LENGTHS, output_folder, refuse_together, add_branch_option, add_format_option, add_units_option, assignments,
                      command_help, figure_path, finite, fourbar_lengths, input_sweep, distinct_number_list,
                      seed, whole)
from .dynamics import add_mass_options, dynamics_options_given, fourbar_dynamics, fourbar_mass_options
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


#: The kinds of cache entry of ``symlink tolerance``: the facts of the linkage it needs (:func:`stack_up_facts`) and
#: the stack-up model of one output by some dimensions (:class:`~symlink.workshop.tolerance.StackUpModel`).
FACTS_ENTRY_KIND, MODEL_ENTRY_KIND = "tolerance-facts/1", "tolerance-model/1"
#: The kinds of cache entry of the solver of the output that sampled builds (``--samples``) solve, and of the exact
#: gradients of the output by the pins' play (``--play``: :func:`symlink.workshop.pin_play.play_jacobian`).
SOLVER_ENTRY_KIND, PLAY_ENTRY_KIND = "tolerance-solver/1", "tolerance-play/1"
#: Besides the code that shapes generated code: what reads a linkage file or an atlas name, what derives a stack-up's
#: model, what takes the command's facts from the linkage, and what writes the digest of its definition that the
#: facts keep (:func:`symlink.numeric.cache.definition_digest`, for the manifest of sampled builds in a folder).
TOLERANCE_SHAPING = ("io/linkage_file", "mechanism/atlas", "mechanism/joints", "workshop/tolerance",
                     "numeric/design_jacobian", "numeric/units", "numeric/cache", "cli/tolerance", "cli/dynamics")


def stack_up_facts(linkage: Any, source: str, defaults: Mapping[str, float]) -> dict[str, Any]:
    """What ``symlink tolerance`` needs of ``linkage`` besides its stack-up model, as plain data (JSON): names, kinds
    of the parameters (:func:`symlink.numeric.units.parameter_kinds`), which are angles, the defaults, and the digest
    of its definition (:func:`symlink.numeric.cache.definition_digest`: what the manifest of sampled builds kept in
    a ``--folder`` names it by).  ``source`` says where the linkage was read (``catalog``, ...;
    :class:`symlink.io.linkage_file.LinkageFile`).

    Kept in the disk cache for a linkage named by a catalog name, an atlas name or a file, so that a warm stack-up
    builds no linkage and imports no SymPy.
    """
    from ..numeric.cache import definition_digest
    from ..numeric.units import parameter_kinds
    from ..symbolic.closure import is_angle
    named = linkage.parameters + linkage.inputs
    return {"name": linkage.name, "source": source, "closed_form": bool(linkage.has_closed_form),
            "inputs": [q.name for q in linkage.inputs], "parameters": [s.name for s in linkage.parameters],
            "positive": [s.name for s in linkage.parameters if s.is_positive],
            "kinds": parameter_kinds(linkage), "angles": [s.name for s in named if is_angle(linkage, s)],
            "branches": [b.name for b in linkage.branches],
            "last_unknown": linkage.unknowns[-1].name if linkage.unknowns else None,
            "defaults": {name: float(value) for name, value in defaults.items()},
            "definition": definition_digest(linkage)}


def _keyed_request(args: argparse.Namespace, name: str) -> dict[str, str] | None:
    """What names the linkage in the keys of the command's cache entries, where the request can be answered from
    them (a linkage named by a catalog or atlas name or a file's bytes; the four-bar's masses and the pins' play key
    the entries further; the manifest of builds kept in a folder names the linkage's definition by the digest that
    its facts keep); else None."""
    from ..common.names import FORMER_CATALOG_NAMES
    from ..io.scene_text import linkage_request
    if name in FORMER_CATALOG_NAMES:
        return None
    return linkage_request(name)


def _key(request: Mapping[str, str], kind: str, outputs: list[str], **more: Any) -> str:
    from ..numeric.cache import catalog_key
    return catalog_key("tolerance", outputs, kind, {"linkage": dict(request), **more}, TOLERANCE_SHAPING)


def run(args: argparse.Namespace) -> int:
    """``symlink tolerance``: the stack-up table.

    A linkage named by a catalog or atlas name or a file is answered from the disk cache: its facts
    (:func:`stack_up_facts`) and the stack-up model of the output by the toleranced dimensions
    (:class:`~symlink.workshop.tolerance.StackUpModel`), and with ``--samples`` the output's solver, are keyed by what
    names it (and by the four-bar's ``--masses`` and the pins of ``--play``: the entry of the gradients by the pins'
    play), so that a warm stack-up (builds kept in a ``--folder`` too: their manifest takes the definition's digest
    from the facts) builds no linkage and imports no SymPy; the cold run takes the same path.
    """
    import json
    from ..numeric.cache import cached_module, cached_text
    from ..workshop.tolerance import StackUpModel, tolerance_arrays
    from ..io.table_source import facts_values
    lengths = fourbar_lengths(args)
    given = [value is not None for value in lengths]
    name = args.linkage if args.linkage is not None else "fourbar"
    if args.linkage is None and not all(given):
        raise ValueError("tolerance: give a catalog NAME (e.g. fourbar) or a linkage FILE, or all of --crank "
                         "--coupler --rocker --ground")
    request = _keyed_request(args, name)
    found: Any = None
    linkage: Any = None  # the linkage, read where the request is not answered from the disk cache
    keyed: dict[str, Any] = {}  # what keys the entries besides the linkage and the output: the four-bar's masses
    dynamic_lengths: tuple[float, float, float, float] | None = None  # the four-bar's, where it has masses

    def read() -> Any:
        from ..io.linkage_file import load_linkage
        return load_linkage(name)

    def read_linkage() -> Any:
        """The linkage of the stack-up: as read, or the four-bar with the masses of the options (SymPy)."""
        if dynamic_lengths is None:
            return read().linkage
        dynamic = fourbar_dynamics(args, dynamic_lengths)
        assert dynamic is not None  # dynamic_lengths is set where the options ask for masses
        return dynamic[0]

    if request is not None:
        def now() -> str:
            read_now = read()
            return json.dumps(stack_up_facts(read_now.linkage, read_now.source, read_now.defaults))
        facts = json.loads(cached_text(_key(request, FACTS_ENTRY_KIND, []), now))
    else:
        found = read()
        linkage = found.linkage
        facts = stack_up_facts(linkage, found.source, found.defaults)
    values = facts_values(facts, args.set, args.units)
    fourbar = facts["source"] == "catalog" and facts["name"] == "fourbar"
    if any(given):
        if not fourbar:
            raise ValueError("tolerance: --crank --coupler --rocker --ground belong to the four-bar; give the values "
                             f"of {facts['name']} with --set NAME=VALUE,...")
        values.update({k: v for k, v in zip("abcd", lengths) if v is not None})
    given_dynamics = dynamics_options_given(args)
    if given_dynamics and not fourbar:  # never silently left out: a stack-up of another linkage has no masses
        raise ValueError(f"tolerance: {given_dynamics[0]} and the other dynamics options belong to the four-bar")
    if fourbar:
        four = (values["a"], values["b"], values["c"], values["d"])
        options = fourbar_mass_options(args, four)  # ValueError for dynamics options without --masses
        if options is not None:  # masses at fixed places on the links: the lengths' tolerances do not move them
            dynamic_lengths = four
            if request is not None:  # keyed by the options' numbers: a warm stack-up builds no model
                keyed["dynamics"] = options
                kinematic = facts
                facts = json.loads(cached_text(_key(request, FACTS_ENTRY_KIND, [], **keyed), lambda: json.dumps(
                    stack_up_facts(read_linkage(), kinematic["source"], kinematic["defaults"]))))
            else:
                linkage = read_linkage()
                facts = stack_up_facts(linkage, found.source, found.defaults)
    if not facts["closed_form"]:
        raise ValueError(f"{facts['name']} has no closed form; take its stack-up from Python with stack_up(..., "
                         "guess=...) (its assembly must be chosen)")
    if not facts["inputs"]:
        raise ValueError(f"{facts['name']} has no input to sweep")
    tolerances = _tolerances(args, facts)
    output = args.output or facts["last_unknown"]
    sweep = input_sweep(args)
    if len(sweep) > MAX_POINTS:
        raise ValueError(f"{len(sweep)} input values are too many for a stack-up (at most {MAX_POINTS}); give a "
                         "larger --step")
    first, *others = facts["inputs"]
    swept_angle = first in facts["angles"]
    shown = sweep.array()
    inputs: dict[str, Any] = {first: to_radians(shown, args.units) if swept_angle else shown}
    for other in others:
        if other not in values:
            raise ValueError(f"{facts['name']} needs a value for its input {other} (--set {other}=VALUE)")
        inputs[other] = numpy.full(len(shown), values[other])
    values.update({branch: int(args.branch) for branch in facts["branches"]})
    values.update({f"{first}dot": args.crank_speed, f"{first}ddot": args.crank_accel})
    play_model: Any = None  # the exact gradients of the output by the pins' play (--play)
    if args.play:
        joints = list(args.play)

        def derive_play(playing: Any) -> Any:
            from ..symbolic.vectors import acceleration, rate
            from ..workshop.pin_play import play_jacobian
            moving = {rate(q) for q in playing.coordinates} | {acceleration(q) for q in playing.coordinates}
            if playing.output(output).free_symbols & moving:  # ValueError naming the outputs for an unknown one
                raise ValueError(f"--play is modelled for positions; {output} moves with the rates")
            return play_jacobian(playing, [output], joints)
        if request is not None:  # keyed by the pins: a warm run reads the gradients' code (no SymPy)
            from ..numeric.design_jacobian import DesignJacobian
            play_model = DesignJacobian.from_entry(*cached_module(
                _key(request, PLAY_ENTRY_KIND, [output], joints=joints, **keyed),
                lambda: derive_play(read_linkage()).entry_text()))
        else:
            play_model = derive_play(linkage)
    dimensions, bands, sigmas = tolerance_arrays(tolerances)
    if request is not None:
        def derive() -> str:
            from ..numeric.units import output_units
            derived = read_linkage()
            model = StackUpModel.derive(derived, [output], dimensions)  # ValueError naming an unknown output
            return model.entry_text(output_unit=output_units(derived, [output]).get(output))
        # a verified entry of a private cache (never user text), run from its cached bytecode
        model = StackUpModel.from_entry(*cached_module(_key(request, MODEL_ENTRY_KIND, [output], dimensions=dimensions,
                                                            **keyed), derive))
        output_unit = model.facts["output_unit"]
    else:
        from ..numeric.units import output_units
        model = StackUpModel.derive(linkage, [output], dimensions)
        output_unit = output_units(linkage, [output]).get(output)
    angular = output_unit == "rad"
    result = model.stack_up(values, bands, sigmas, inputs)
    if not result.assembled.any():  # every row would be NaN: refused, as every table command refuses it
        raise ValueError(f"{facts['name']} cannot be assembled at any of the input values asked for with these "
                         "dimensions: there is no stack-up to print")
    play = None
    if args.play:
        from ..workshop.pin_play import played_pins
        play = played_pins(play_model, facts["name"], facts["inputs"], values, args.play, inputs=inputs).worst_case[0]
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
        if linkage is None:  # the output's solver from the disk cache (derived once): a warm sample imports no SymPy
            from ..numeric.cached_solver import CachedSolver, entry_text
            from ..workshop.sampled_builds import solved_builds
            assert request is not None  # the linkage is read where the request is not keyed
            known = request

            def solver() -> CachedSolver:
                return CachedSolver(facts["name"], [output], key=_key(known, SOLVER_ENTRY_KIND, [output], **keyed),
                                    derive=lambda: entry_text(read_linkage(), [output]))
            positive = set(facts["positive"])
            builds = solved_builds(solver, facts["name"], facts["inputs"],
                                   {dimension: dimension in positive for dimension in facts["parameters"]},
                                   lambda: [angular], [output], values, tolerances, inputs=inputs, builds=args.builds,
                                   seed=args.seed, folder=args.folder,
                                   settings=lambda model: model.settings(facts["name"], facts["definition"]))
        else:
            from ..workshop.sampled_builds import sample_builds
            builds = sample_builds(linkage, output, values, tolerances, inputs=inputs, builds=args.builds,
                                   seed=args.seed, folder=args.folder)
        sampled = builds.percentile([0.135, 99.865])[:, 0]
        if args.folder is not None:
            note(f"{args.builds} builds in {args.folder}: {builds.reused} chunk{'s' if builds.reused != 1 else ''} "
                 "found done there")
    convert = (lambda x: from_radians(x, args.units)) if angular else (lambda x: numpy.asarray(x))  # noqa: E731
    nominal = convert(wrap(result.nominal[0]) if angular else result.nominal[0])
    worst, rss, shift = convert(result.worst_case[0]), convert(result.rss[0]), convert(result.mean_shift[0])
    largest = result.largest_contributor(output)
    columns = ([first, output, "worst_case", "rss", "mean_shift", "largest"] + (["play"] if args.play else [])
               + (["sampled_low", "sampled_high"] if sampled is not None else []))
    plays = convert(play) if play is not None else numpy.zeros(len(shown))
    lows, highs = (convert(sampled[0]), convert(sampled[1])) if sampled is not None else (plays, plays)
    shown_unit = args.units if angular else ""
    writer = RowWriter(columns, args.format, units={
        first: args.units if swept_angle else "", **{c: shown_unit for c in (
            output, "worst_case", "rss", "mean_shift", "play", "sampled_low", "sampled_high")}})
    writer.write({first: float(x), output: float(y), "worst_case": float(w), "rss": float(r),
                  "mean_shift": float(m), "largest": big or "-", "play": float(p), "sampled_low": float(lo),
                  "sampled_high": float(hi)}
                 for x, y, w, r, m, big, p, lo, hi in zip(shown, nominal, worst, rss, shift, largest, plays, lows,
                                                          highs))
    writer.close()
    kind = output_unit or "the output's units"
    unit = args.units if angular else {"length": "length units"}.get(kind, kind)
    ranking = ", ".join(f"{dim} {float(convert(dev)):.4g}" for dim, dev in result.ranking(output))
    note(f"largest 1-sigma deviation of {output} each dimension causes on the range ({unit}): {ranking}")
    if args.plot is not None:
        from ..plot import save_figure
        from ..plot.tolerance import tolerance_figure
        save_figure(tolerance_figure(result, output, builds, units=args.units, angular_input=swept_angle,
                                     angular_output=angular, title=f"tolerance stack-up of {facts['name']}: {output}"),
                    args.plot)
    return 0


def _tolerances(args: argparse.Namespace, facts: Mapping[str, Any]) -> dict[str, Any]:
    """The dimensions' tolerances from ``--tolerance``, ``--tolerances`` and ``--sigma`` (angles to radians).

    One rule for every linkage, by the kind of each parameter (:func:`symlink.numeric.units.parameter_kinds`, in
    the linkage's ``facts``: :func:`stack_up_facts`): ``--tolerance`` bands the lengths only (never a fixed angle,
    a placement or a mass); a band or a sigma of an angle is read in ``--units``; a placement (where the linkage
    stands: a drawing's ``x_A``) is toleranced only when named.
    """
    from ..workshop.tolerance import Tolerance
    symbols, kinds, angles = facts["parameters"], facts["kinds"], set(facts["angles"])
    for option, given in (("--tolerances", args.tolerances), ("--sigma", args.sigma)):
        for name in given:
            if name not in symbols:
                raise ValueError(f"{option}: {facts['name']} has no dimension {name!r}; it has {', '.join(symbols)}")

    def plain(name: str, value: float) -> float:
        return float(to_radians(value, args.units)) if kinds.get(name) == "angle" or (
            kinds.get(name) == "placement" and name in angles) else value

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
