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
        "The file names a catalog linkage, its outputs, parameters and the input sweep; - reads it from stdin. A "
        "linkage without a closed form (stephenson2) takes a [guess] table of its unknowns and is solved by "
        "Newton's method."))


def _add_options(command: argparse.ArgumentParser) -> None:
    from ..io.scene_text import FORMATS
    command.add_argument("scene", help="a TOML scene file, or - for standard input")
    command.add_argument("--format", choices=list(FORMATS), help="override the file's format")
    command.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Print the scene's outputs at each input angle and branch.

    A scene whose facts are in the disk cache (the same linkage, outputs and dynamics as a scene run before,
    whatever its numbers) is evaluated from there, without SymPy (:mod:`symlink.io.scene_text`); the first run
    reads it in full and keeps them.  A scene with a ``[guess]`` table (a linkage without a closed form) is solved
    by Newton's method as ``symlink table NAME --guess ...`` solves it (:func:`_run_newton`), warm alike: its reader
    (:func:`symlink.io.scene.scene_from_text`) takes the table's facts and solver from the cache.
    """
    from pathlib import Path
    from ..common.files import read_input_text, read_stdin_text
    from ..io.scene_text import MAX_SCENE_BYTES, cache_scene, warm_scene
    if args.scene == "-":
        text, source, folder = read_stdin_text(MAX_SCENE_BYTES, "scene file"), "<stdin>", Path(".")
    else:
        path = Path(args.scene)
        text, source, folder = read_input_text(path, MAX_SCENE_BYTES, "scene file"), str(path), path.parent
    warm = warm_scene(text, folder)  # never a scene with a [guess]
    if warm is None:
        from ..io.scene import NewtonSceneFile, scene_from_text
        found = scene_from_text(text, source, folder)  # the full reader: SymPy, and the messages of bad input
        if isinstance(found, NewtonSceneFile):  # no closed form: Newton's method from the cache, no SymPy when warm
            return _run_newton(found, args)
        warm = cache_scene(text, folder, found)
        if warm is None:
            return _run_scene(found, args)
    return _run_warm(warm, args)


def _run_warm(warm, args: argparse.Namespace) -> int:
    """Print a scene evaluated from the cache (:class:`symlink.io.scene_text.WarmScene`)."""
    columns = [warm.input_column, "branch", *warm.outputs]

    def spans() -> str:
        if warm.name == "fourbar":
            from ..numeric.crank_ranges import crank_range, describe_spans
            return describe_spans(crank_range(*(warm.parameters[n] for n in "abcd")), warm.units)
        return f"not computed for {warm.name}"

    def blocks():
        for angles in warm.sweep.blocks():
            yield angles, warm.evaluate(angles)

    write_table(blocks(), columns, warm.units, args.format or warm.format, warm.angle_columns, spans)
    return 0


def _run_scene(found, args: argparse.Namespace) -> int:
    """Print a scene read in full (:class:`symlink.io.scene.SceneFile`): one the cache cannot key."""
    from ..io.scene import angle_outputs
    scene = found.scene
    columns = [found.input_column, "branch", *scene.outputs]

    def spans() -> str:
        if scene.linkage.name == "fourbar":
            from ..numeric.crank_ranges import crank_range, describe_spans
            return describe_spans(crank_range(*(cast(float, scene.values[n]) for n in "abcd")), found.units)
        return f"not computed for {scene.linkage.name}"

    def blocks():
        for angles in found.sweep.blocks():
            yield angles, scene.evaluate(**found.values_at(angles))

    angle_columns = {found.input_column} | angle_outputs(scene.linkage, scene.outputs)
    write_table(blocks(), columns, found.units, args.format or found.format, angle_columns, spans)
    return 0


def _run_newton(found, args: argparse.Namespace) -> int:
    """Print a scene of a linkage without a closed form (:class:`symlink.io.scene.NewtonSceneFile`), solved from its
    ``[guess]`` as ``symlink table NAME --guess ...`` solves it, over the whole sweep at once."""
    columns = [found.input_column, "branch", *found.scene.outputs]
    write_table([(found.angles, found.scene.evaluate())], columns, found.units, args.format or found.format,
                {found.input_column} | found.angle_columns, lambda: "", found.column_units)
    return 0
