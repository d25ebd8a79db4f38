"""``symlink run SCENE.toml``: evaluate a scene file (``-`` reads it from stdin)."""
from __future__ import annotations

import argparse
from typing import cast

from .options import command_help
from .tables import write_table


def register(commands) -> None:
    """Register ``symlink run``."""
    commands.add_parser("run", populate=_add_options, **command_help(
        "evaluate a scene file (TOML: numbers and names only)",
        "as the file says: units = \"deg\" (default) or \"rad\" for input and printed angles",
        "symlink run scene.toml --format csv",
        "The file names a catalog linkage, its outputs, parameters and the input sweep; - reads it from stdin."))


def _add_options(command: argparse.ArgumentParser) -> None:
    from ..io.scene import FORMATS
    command.add_argument("scene", help="a TOML scene file, or - for standard input")
    command.add_argument("--format", choices=list(FORMATS), help="override the file's format")
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Print the scene's outputs at each input angle and branch."""
    from ..common.files import read_stdin_text
    from ..io.scene import MAX_SCENE_BYTES, angle_outputs, read_scene, scene_from_text
    if args.scene == "-":
        found = scene_from_text(read_stdin_text(MAX_SCENE_BYTES, "scene file"), "<stdin>")
    else:
        found = read_scene(args.scene)
    scene = found.scene
    columns = [found.input_column, "branch", *scene.outputs]

    def spans() -> str:
        if scene.linkage.name == "fourbar":
            from ..numeric.reachability import crank_range, describe_spans
            return describe_spans(crank_range(*(cast(float, scene.values[n]) for n in "abcd")), found.units)
        return f"not computed for {scene.linkage.name}"

    def blocks():
        for angles in found.sweep.blocks():
            yield angles, scene.evaluate(**found.values_at(angles))

    angle_columns = {found.input_column} | angle_outputs(scene.linkage, scene.outputs)
    write_table(blocks(), columns, found.units, args.format or found.format, angle_columns, spans)
    return 0
