"""``symlink analyze``: mobility, Grashof class, crank range, limit positions and transmission of a four-bar."""
from __future__ import annotations

import argparse
import json
from functools import cached_property
from typing import Any

from ..common.angles import from_radians
from ..io.table_source import ANALYSIS_SHAPING, TableSource
from .options import (add_fourbar_lengths, add_units_option, assignments, command_help, fourbar_lengths,
                      fourbar_or_linkage, require_held_inputs)

#: Fields of :func:`~symlink.analysis.fourbar_closed_form.fourbar_report` that are angles (converted to the
#: command's units).
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


class AnalysisSource(TableSource):
    """A linkage named on the command line (a catalog or atlas name, or a linkage file), as the general analysis
    needs it: a :class:`~symlink.numeric.cached_linkage.CachedLinkage` of its facts and generated code from the disk
    cache, keyed as ``symlink table NAME|FILE`` keys its entries (a :class:`~symlink.io.table_source.TableSource`:
    by what names the linkage, a former name noted alike warm or cold), so that a warm ``symlink analyze NAME|FILE``
    builds no linkage and imports no SymPy.  A file too large to key is analysed from the linkage itself.
    """

    dynamics = False  # the analysis reads no [dynamics]

    def key(self, outputs: list[str], analysis: bool = True) -> str:
        """The cache key of an entry: the table's (:meth:`symlink.io.table_source.TableSource.key`), with the
        analysis's code besides (``analysis``) for its own entries; the solver's is the table's own."""
        if not analysis:
            return super().key(outputs)
        from ..io.table_source import GENERIC_ENTRY_KIND, GENERIC_SHAPING
        from ..numeric.cache import catalog_key
        return catalog_key("table", outputs, GENERIC_ENTRY_KIND, self.request, GENERIC_SHAPING + ANALYSIS_SHAPING)

    @cached_property
    def facts(self) -> dict[str, Any]:  # the analysis's facts, not the table's
        """:func:`~symlink.analysis.report.analysis_facts` of the linkage, with its defaults (``defaults``)."""
        def now() -> dict[str, Any]:
            from ..analysis.report import analysis_facts
            found = self.found()
            return {**analysis_facts(found.linkage),
                    "defaults": {name: float(value) for name, value in found.defaults.items()}}
        if self.request is None:
            return now()
        from ..numeric.cache import cached_text
        return json.loads(cached_text(self.key(["(analysis)"]), lambda: json.dumps(now())))

    def linkage(self) -> Any:
        """What :func:`~symlink.analysis.analyze_linkage` takes: the cached linkage, or the linkage itself."""
        if self.request is None:
            return self.found().linkage
        from ..numeric.cached_linkage import CachedLinkage
        return CachedLinkage(self.facts, self._solver, self._margins, self._output)

    def _solver(self, outputs: Any) -> Any:
        from ..numeric.cached_solver import CachedSolver, entry_text
        outputs = list(outputs)

        def full() -> Any:
            from ..numeric.solver import Solver
            return Solver(self.found().linkage, outputs)

        return CachedSolver(self.facts["name"], outputs, key=self.key(outputs, analysis=False),
                            derive=lambda: entry_text(self.found().linkage, outputs), full=full)

    def _margins(self) -> Any:  # the one entry of the margins, a sweep's too (a keyed linkage's: see linkage())
        from ..io.table_source import margins_entry
        assert self.request is not None
        return margins_entry(self.request, lambda: self.found().linkage)["margins"]

    def _output(self, name: str) -> tuple[Any, bool]:
        from ..analysis.limits import check_named_output
        from ..numeric.cache import cached_module, cached_text
        check_named_output(self.facts, name)  # no position output: refused from the facts (no SymPy), as derived

        def angle() -> str:  # a name that is no position output is refused here, and nothing is kept
            from ..analysis.limits import check_position_output, is_angle_output
            check_position_output(self.found().linkage, name)
            return json.dumps(is_angle_output(self.found().linkage, name))

        is_angle = json.loads(cached_text(self.key(["(output)", name]), angle))

        def text() -> str:
            from ..analysis.limits import output_text
            return output_text(self.found().linkage, name)

        return cached_module(self.key(["(output-and-rate)", name]), text)[1]["output"], is_angle


def run_linkage(args: argparse.Namespace) -> int:
    """``symlink analyze NAME|FILE``: the general analysis of any one-input linkage (warm: no SymPy)."""
    from ..analysis.report import analyze_linkage
    from ..io.table_source import facts_values
    source = AnalysisSource(args.linkage)
    facts = source.facts
    linkage = source.linkage()
    require_held_inputs(linkage, args.set, "analyze")
    values = facts_values(facts, args.set, args.units)
    values = {name: value for name, value in values.items() if name not in facts["inputs"][:1]}
    values.update({branch: int(args.branch) for branch in facts["branches"]})
    if not facts["closed_form"]:
        raise ValueError(f"{facts['name']} has no closed form; analyze it from Python with analyze_linkage(..., "
                         "guess=...) (its assemblies must be chosen)")
    report = analyze_linkage(linkage, values, args.output)
    unit = args.units
    angle = lambda x: float(from_radians(x, unit))  # noqa: E731
    reach = report.reach
    shown_input = angle if report.input in facts["angles"] else float
    record: dict[str, Any] = {
        "linkage": facts["name"], "input": report.input, "dof": report.mobility.dof,
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
    lines = [f"{facts['name']}: input {report.input}",
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
