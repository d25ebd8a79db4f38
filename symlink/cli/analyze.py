"""``symlink analyze``: mobility, Grashof class, crank range, limit positions and transmission of a four-bar."""
from __future__ import annotations

import argparse
import json
from typing import Any

from ..common.angles import from_radians
from .options import (add_fourbar_lengths, add_units_option, assignments, command_help, fourbar_lengths,
                      fourbar_or_linkage, linkage_values, require_held_inputs)

#: Fields of :func:`~symlink.analysis.fourbar_closed_form.fourbar_report` that are angles (converted to the command's units).
ANGLE_FIELDS = {"stroke", "transmission_min", "transmission_min_at", "transmission_max", "transmission_max_at",
                "worst_transmission", "extended_crank", "extended_rocker", "folded_crank", "folded_rocker"}



def _cell(value: float) -> str:
    """A number of the report to four decimals, never ``-0.0000`` (:func:`~symlink.cli.output.table_cell`)."""
    from .output import table_cell
    return table_cell(float(value))

def in_units(report: dict, units: str) -> dict:
    """The report with its angles in ``units``."""
    convert = lambda x: float(from_radians(x, units))  # noqa: E731
    shown = dict(report)
    for key in ANGLE_FIELDS & set(report):
        if report[key] is not None:
            shown[key] = convert(report[key])
    shown["crank_range"] = [[convert(lo), convert(hi)] for lo, hi in report["crank_range"]]
    shown["toggles"] = [convert(x) for x in report["toggles"]]
    if report["limit_positions"] is not None:
        shown["limit_positions"] = {k: convert(v) for k, v in report["limit_positions"].items()}
    return shown


def register(commands) -> None:
    """Register ``symlink analyze``."""
    commands.add_parser("analyze", populate=_add_options, **command_help(
        "mobility, reachable range, toggles, transmission angles and limit positions of a linkage",
        "lengths in any one unit; printed angles in --units (deg by default)",
        "symlink analyze --crank 20 --coupler 66 --rocker 56 --ground 80",
        "With NAME|FILE any one-input linkage (values from its file or the catalog's example, --set to change):\n"
        "symlink analyze jansen --output H_y"))


def _add_options(command: argparse.ArgumentParser) -> None:
    command.add_argument("linkage", nargs="?", metavar="NAME|FILE",
                         help="a catalog linkage or a linkage file (without it: the four-bar of the length options)")
    add_fourbar_lengths(command, beside_linkage=True)
    command.add_argument("--set", type=assignments("NAME=VALUE"), default={}, metavar="NAME=VALUE,...",
                         help="with NAME|FILE: parameter values (fixed angles in --units)")
    command.add_argument("--output", metavar="NAME", help="with NAME|FILE: the output whose limit positions to find")
    command.add_argument("--branch", choices=["+1", "1", "-1"], default="+1",
                         help="assembly (every loop's sign) for the limit positions (default +1)")
    add_units_option(command, "printed angles")
    command.add_argument("--format", choices=["table", "json"], default="table", help="default table")
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    if fourbar_or_linkage(args, "analyze", linkage_only=("set", "output")):
        return run_linkage(args)
    from ..analysis.fourbar_closed_form import fourbar_report  # closed form: no SymPy, cold or warm
    a, b, c, d = fourbar_lengths(args)
    report = in_units(fourbar_report(a, b, c, d, int(args.branch)), args.units)
    if args.format == "json":
        print(json.dumps(report, indent=1))
        return 0
    unit = args.units
    spans = ("full turn" if not report["toggles"] else
             ", ".join(f"[{_cell(lo)}, {_cell(hi)}] {unit}" for lo, hi in report["crank_range"]))
    lines = [
        f"four-bar: crank {a:g}, coupler {b:g}, rocker {c:g}, ground {d:g}",
        f"degrees of freedom   {report['dof']}",
        f"Grashof              {report['grashof']} (s + l = {report['shortest_plus_longest']:g}, "
        f"p + q = {report['other_two']:g}; shortest: {report['shortest']})",
        f"crank range          {spans}",
    ]
    if report["toggles"]:
        lines.append("toggle positions     crank at " + ", ".join(_cell(x) for x in report["toggles"]) + f" {unit}")
    if report["limit_positions"] is not None:
        limits = report["limit_positions"]
        lines += [
            f"limit positions      extended: crank {_cell(limits['extended_crank'])}, rocker "
            f"{_cell(limits['extended_rocker'])} {unit}; folded: crank {_cell(limits['folded_crank'])}, "
            f"rocker {_cell(limits['folded_rocker'])} {unit} (branch {int(args.branch):+d})",
            f"stroke               {_cell(report['stroke'])} {unit}",
            f"time ratio           {_cell(report['time_ratio'])}",
        ]
    lines.append(f"transmission angle   {_cell(report['transmission_min'])} at crank "
                 f"{_cell(report['transmission_min_at'])} "
                 f"to {_cell(report['transmission_max'])} at crank {_cell(report['transmission_max_at'])} {unit}")
    print("\n".join(lines))
    return 0


def run_linkage(args: argparse.Namespace) -> int:
    """``symlink analyze NAME|FILE``: the general analysis of any one-input linkage."""
    from ..analysis import analyze_linkage
    from ..symbolic.closure import is_angle
    from ..io.linkage_file import load_linkage
    found = load_linkage(args.linkage)
    require_held_inputs(found.linkage, args.set, "analyze")
    linkage, values = found.linkage, linkage_values(found, args.set, args.units)
    known = {s.name: s for s in linkage.parameters + linkage.inputs}
    values = {name: value for name, value in values.items() if name not in {q.name for q in linkage.inputs[:1]}}
    values.update({branch.name: int(args.branch) for branch in linkage.branches})
    if not linkage.has_closed_form:
        raise ValueError(f"{linkage.name} has no closed form; analyze it from Python with analyze_linkage(..., "
                         "guess=...) (its assemblies must be chosen)")
    report = analyze_linkage(linkage, values, args.output)
    unit = args.units
    angle = lambda x: float(from_radians(x, unit))  # noqa: E731
    reach = report.reach
    shown_input = angle if is_angle(linkage, known[report.input]) else float
    record: dict[str, Any] = {
        "linkage": linkage.name, "input": report.input, "dof": report.mobility.dof,
        "reachable": [[shown_input(lo), shown_input(hi)] for lo, hi in reach.spans], "full_turn": reach.full_turn,
        "exact": reach.exact,
        "toggles": [{"at": shown_input(t.at), "loop": t.loop, "ends_range": t.ends_range, "degenerate": t.degenerate}
                    for t in reach.toggles],
        "transmission": [{"loop": t.loop, "joint": t.joint, "minimum": angle(t.minimum),
                          "minimum_at": shown_input(t.minimum_at), "maximum": angle(t.maximum),
                          "maximum_at": shown_input(t.maximum_at)} for t in report.transmission],
        "limits": None if report.limits is None else {
            "output": report.limits.output,
            "positions": [{"at": shown_input(p.at), "value": angle(p.value) if report.limits.angle else p.value,
                           "kind": p.kind} for p in report.limits.positions],
            "stroke": None if report.limits.stroke is None else
            (angle(report.limits.stroke) if report.limits.angle else report.limits.stroke),
            "time_ratio": report.limits.time_ratio},
    }
    if args.format == "json":
        print(json.dumps(record, indent=1))
        return 0
    spans = "full turn" if reach.full_turn else ", ".join(f"[{_cell(lo)}, {_cell(hi)}]"
                                                          for lo, hi in record["reachable"])
    lines = [f"{linkage.name}: input {report.input}",
             f"degrees of freedom   {report.mobility.dof}",
             f"reachable range      {spans}{'' if reach.full_turn else ' ' + unit} "
             f"({'exact' if reach.exact else 'scanned'})"]
    for toggle in record["toggles"]:
        what = "degenerate" if toggle["degenerate"] else "toggle" if toggle["ends_range"] else "change point"
        lines.append(f"{what:<21}{report.input} = {_cell(toggle['at'])} (loop {toggle['loop']})")
    for t in record["transmission"]:
        lines.append(f"transmission {t['loop']:<8}at {t['joint']}: {_cell(t['minimum'])} at "
                     f"{_cell(t['minimum_at'])} to "
                     f"{_cell(t['maximum'])} at {_cell(t['maximum_at'])} {unit}")
    if record["limits"] is not None:
        limits = record["limits"]
        for p in limits["positions"]:
            lines.append(f"limit of {limits['output']:<12}{p['kind']} {p['value']:.6g} at {report.input} = "
                         f"{_cell(p['at'])}")
        if limits["stroke"] is not None:
            lines.append(f"stroke               {limits['stroke']:.6g}; time ratio {_cell(limits['time_ratio'])}")
    print("\n".join(lines))
    return 0
