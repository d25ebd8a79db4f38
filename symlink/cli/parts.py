"""``symlink parts``: every link of a linkage as a part to cut (SVG, DXF), an assembly drawing and a design's JSON.

The linkage is a catalog NAME, a linkage FILE (.toml), an atlas entry
(``atlas:NAME``) or a design FILE (.json, :func:`symlink.workshop.fabrication.design_json`,
whose unit it keeps).  Stdout lists one row a dimension of each part: the
distance between each pair of its holes, each slot's length (the slider's
travel), a slider block's length.  The files asked for are made in memory
first and then written together: all of them, or (bad input, a failed write)
none.  The assembly drawing shows the parts at ``--angle`` (the first input,
in ``--units``); a linkage that cannot be assembled there is refused.
"""
from __future__ import annotations

import argparse
import math
import os
from pathlib import Path
from typing import Any

import numpy

from ..common.angles import from_radians, to_radians
from .options import (add_branch_option, add_format_option, add_units_option, angle, assignments, command_help, finite,
                      output_file)
from ..common.files import write_files_together
from .output import RowWriter, note

__all__ = ["register", "COLUMNS", "FILE_OPTIONS"]

#: The columns of the parts list on stdout.
COLUMNS = ["part", "dimension", "length", "unit"]
#: The file options, each with the suffix its file must have and what it holds.
FILE_OPTIONS = {"svg": (".svg", "the parts, in a row"), "dxf": (".dxf", "the parts, in a row (needs ezdxf)"),
                "assembly": (".svg", "the assembly drawing at --angle"),
                "json": (".json", "the design: links, joints, dimensions and unit, which symlink reads back")}
#: Input values scanned for a pose that assembles when no --angle is given and the first input's 0 does not.
SCAN = 720


def register(commands) -> None:
    """Register ``symlink parts``."""
    commands.add_parser("parts", populate=_add_options, **command_help(
        "every link of a linkage as a part to cut (SVG, DXF), an assembly drawing and the design as JSON",
        "lengths in the linkage's own unit, named by --unit (mm by default) in the drawings' real size; "
        "--angle and fixed angles in --units (deg by default)",
        "symlink parts fourbar --pin-diameter 4 --svg parts.svg --assembly assembly.svg --angle 40",
        "NAME|FILE: a catalog linkage, a linkage file (.toml), atlas:NAME or a design file (.json, its unit kept).\n"
        "Bars get rounded ends, ternary links are rounded polygons, a slider's guide gets the slot its pin travels.\n"
        "The files are written together: all of them, or none.\n"
        "csv header: part,dimension,length,unit"))


def _add_options(command: argparse.ArgumentParser) -> None:
    from ..workshop.fabrication import UNITS_IN_MM
    command.add_argument("linkage", metavar="NAME|FILE",
                         help="a catalog linkage, a linkage file (.toml), atlas:NAME or a design file (.json)")
    command.add_argument("--set", type=assignments("NAME=VALUE"), default={}, metavar="NAME=VALUE,...",
                         help="change the linkage's values (lengths in --unit, fixed angles in --units)")
    command.add_argument("--pin-diameter", type=finite, required=True, metavar="D",
                         help="diameter of the pin holes, in --unit")
    command.add_argument("--width", type=finite, metavar="W", help="width of a bar, more than D (default 2 D)")
    command.add_argument("--unit", choices=list(UNITS_IN_MM),
                         help="the length unit of the linkage's dimensions (default mm, or a design file's)")
    for option, (suffix, what) in FILE_OPTIONS.items():
        command.add_argument(f"--{option}", type=output_file, metavar="FILE", help=f"write {what} ({suffix})")
    command.add_argument("--angle", type=angle, metavar="A",
                         help="the first input's value for the assembly drawing (in --units; a length for a slider "
                              "input; default 0, or the nearest value where the linkage assembles)")
    add_branch_option(command, both=False, default="+1")
    add_units_option(command, "--angle and fixed angles")
    add_format_option(command)
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ..workshop.fabrication import assembly_svg_text, design_json, dxf_text, link_parts, svg_text
    targets = _targets(args)
    linkage, values, unit = _linkage(args)
    pin = _positive("--pin-diameter", args.pin_diameter)
    width = None if args.width is None else _positive("--width", args.width)
    if width is not None and width <= pin:
        raise ValueError(f"--width {width:g} must exceed --pin-diameter {pin:g}: the holes would cut the link")
    _pose(args, linkage, values)
    parts = link_parts(linkage, values, pin_diameter=pin, width=width)
    makers = {"svg": lambda: svg_text(parts, unit), "dxf": lambda: _dxf(dxf_text, parts, unit),
              "assembly": lambda: assembly_svg_text(parts, unit), "json": lambda: design_json(linkage, values, unit)}
    write_files_together({path: makers[option]() for option, path in targets.items()})
    writer = RowWriter(COLUMNS, args.format)
    writer.write(row for part in parts for row in _rows(part, unit))
    writer.close()
    for path in targets.values():
        note(f"wrote {path}")
    return 0


def _targets(args: argparse.Namespace) -> dict[str, Path]:
    """The files asked for by option, each with its suffix, none named twice; ``ValueError`` otherwise."""
    targets: dict[str, Path] = {}
    for option, (suffix, _) in FILE_OPTIONS.items():
        given = getattr(args, option)
        if given is None:
            continue
        if not given.strip() or Path(given).suffix.lower() != suffix:
            raise ValueError(f"--{option} {given!r}: the file must end in {suffix}")
        path = Path(given)
        for other, known in targets.items():
            if os.path.abspath(known) == os.path.abspath(path):
                raise ValueError(f"--{other} and --{option} name the same file {given!r}")
        targets[option] = path
    return targets


def _positive(option: str, value: float) -> float:
    if value <= 0:
        raise ValueError(f"{option} must be a positive length, got {value:g}")
    return value


def _linkage(args: argparse.Namespace) -> tuple[Any, dict[str, float], str]:
    """The linkage, its values (``--set``, ``--angle``, ``--branch`` applied) and the length unit."""
    from ..symbolic.closure import is_angle
    from ..io.linkage_file import LinkageFile, load_linkage
    from .options import linkage_values
    if str(args.linkage).lower().endswith(".json"):
        from ..workshop.fabrication import MAX_DESIGN_BYTES, read_design
        from ..common.files import read_input_text
        design = read_design(read_input_text(args.linkage, MAX_DESIGN_BYTES, "design file"), str(args.linkage))
        if args.unit is not None and args.unit != design.unit:
            raise ValueError(f"--unit {args.unit}: the design {args.linkage} is in {design.unit} (its lengths are "
                             "not converted); leave --unit out")
        found, unit = LinkageFile(design.linkage, design.values, str(args.linkage)), design.unit
    else:
        found, unit = load_linkage(args.linkage), args.unit or "mm"
    linkage = found.linkage
    values = linkage_values(found, args.set, args.units)
    if not linkage.inputs:
        raise ValueError(f"{linkage.name} has no input")
    if args.angle is not None:
        first = linkage.inputs[0]
        values[first.name] = float(to_radians(args.angle, args.units)) if is_angle(linkage, first) else args.angle
    for branch in linkage.branches:
        values[branch.name] = int(args.branch)
    return linkage, values, unit


def _pose(args: argparse.Namespace, linkage: Any, values: dict[str, float]) -> None:
    """Check that the linkage assembles at the pose asked for; without ``--angle``, where it does not at the
    first input's value, move that input to the nearest value where it does (the parts are the same at every
    pose; only the assembly drawing shows the pose) and say so."""
    from ..symbolic.closure import is_angle
    from ..numeric.poses import Geometry
    geometry = Geometry(linkage)
    first = linkage.inputs[0]
    turning = is_angle(linkage, first)
    here = float(values.get(first.name, 0.0))
    if bool(geometry.poses(values).assembled.all()):
        return
    shown = float(from_radians(here, args.units)) if turning else here
    where = f"{first.name} = {shown:g}{f' {args.units}' if turning else ''} (branch {int(args.branch):+d})"
    if args.angle is not None or not turning:
        raise ValueError(f"{linkage.name} cannot be assembled at {where}; choose another --angle or --branch")
    offsets = numpy.linspace(-math.pi, math.pi, SCAN, endpoint=False)
    offsets = offsets[numpy.argsort(numpy.abs(offsets), kind="stable")]
    assembled = geometry.poses(values, {first.name: here + offsets}).assembled
    if not assembled.any():
        raise ValueError(f"{linkage.name} cannot be assembled at any {first.name} (branch {int(args.branch):+d}): "
                         "check its dimensions")
    values[first.name] = here + float(offsets[int(numpy.argmax(assembled))])
    moved = float(from_radians(values[first.name], args.units))
    note(f"{linkage.name} cannot be assembled at {where}: parts read (and the assembly drawn) at "
         f"{first.name} = {moved:.6g} {args.units}")


def _dxf(dxf_text, parts, unit: str) -> str:
    try:
        return dxf_text(parts, unit)
    except ImportError as error:  # ezdxf, the extra 'fabrication'
        raise ValueError(str(error)) from None


def _rows(part, unit: str) -> list[dict[str, Any]]:
    """One row a dimension of ``part``: hole to hole, each slot's length, a block's length (when it has neither)."""
    rows = [{"part": part.name, "dimension": pair, "length": length, "unit": unit}
            for pair, length in part.dimensions.items()]
    rows += [{"part": part.name, "dimension": "slot" if k == 0 else f"slot{k + 1}", "length": math.dist(*slot),
              "unit": unit} for k, slot in enumerate(part.slots)]
    if not rows:
        xmin, _, xmax, _ = part.extent()
        rows.append({"part": part.name, "dimension": "block", "length": xmax - xmin, "unit": unit})
    return rows
