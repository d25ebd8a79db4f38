"""``symlink export NAME|FILE`` (alias ``symlink derive``): a linkage's solvers as NumPy, C, Octave, JavaScript or LaTeX."""
from __future__ import annotations

import argparse

from .options import command_help, name_list, output_folder


def _add_options(command: argparse.ArgumentParser) -> None:
    from ..io.export import FORMATS
    from ..symbolic.seed_forms import FORMS
    command.add_argument("--to", required=True, choices=list(FORMATS), help="the format")
    command.add_argument("--out", type=output_folder, required=True, metavar="DIR", help="the folder to write into")
    command.add_argument("--form", default="atan2", choices=list(FORMS),
                         help="with --to latex: also write the positions in a seed paper's form (complex: seed 000, "
                              "freudenstein: seed 002, half-angle: seed 003); generated code always computes atan2")
    command.add_argument("--outputs", type=_outputs, metavar="LIST",
                         help="comma-separated output names, as one function (default: positions, velocities, "
                              "accelerations and joints; and dynamics for a linkage file with [dynamics])")
    command.set_defaults(run=run)


def _outputs(text: str) -> list[str]:
    """``--outputs``: names, each once; none at all is left for the export to refuse in its own words."""
    return name_list(text) if text.replace(",", "").strip() else []


def register(commands) -> None:
    """Register ``symlink export`` and its alias ``symlink derive``: one command, two names."""
    units = "the generated functions take angles in rad, speeds in rad/s, lengths in any one unit"
    commands.add_parser("export", aliases=["derive"], populate=_add_export_options, **command_help(
        "derive a linkage's closed forms and write its solvers as NumPy, C, Octave, JavaScript or LaTeX (alias: derive)", units,
        "symlink export fourbar --to c --out build/"))


def _add_export_options(command: argparse.ArgumentParser) -> None:
    from ..mechanism.catalog import CATALOG
    command.add_argument("name", metavar="NAME|FILE",
                         help=f"a catalog linkage ({', '.join(sorted(CATALOG))}) or a linkage file (.toml)")
    _add_options(command)


def run(args: argparse.Namespace) -> int:
    """Write the files (all or none) and name them."""
    from ..io.export import export
    from ..io.linkage_file import load_linkage
    outputs = args.outputs
    for path in export(load_linkage(args.name).with_dynamics().linkage, args.to, args.out, outputs, args.form):
        print(f"wrote {path}")
    return 0
