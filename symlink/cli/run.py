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
    by Newton's method as ``symlink table NAME --guess ...`` solves it (:func:`_run_newton`), warm alike.
    """
    from pathlib import Path
    from ..common.files import read_input_text, read_stdin_text
    from ..io.scene_text import MAX_SCENE_BYTES, cache_scene, warm_scene
    if args.scene == "-":
        text, source, folder = read_stdin_text(MAX_SCENE_BYTES, "scene file"), "<stdin>", Path(".")
    else:
        path = Path(args.scene)
        text, source, folder = read_input_text(path, MAX_SCENE_BYTES, "scene file"), str(path), path.parent
    newton = _newton_source(text, folder)
    if newton is not None:
        return _run_newton(text, source, newton, args)
    warm = warm_scene(text, folder)
    if warm is None:
        from ..io.scene import scene_from_text
        found = scene_from_text(text, source, folder)  # the full reader: SymPy, and the messages of bad input
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


def _newton_source(text: str, folder) -> object | None:
    """The table source (:class:`symlink.io.table_source.TableSource`) of a scene that gives a ``[guess]``
    table, whose linkage (a catalog name or a linkage file) is keyed; None for any other (the scene readers say what
    is wrong)."""
    from pathlib import Path
    from ..common.numbers import toml_data
    from ..io.scene_text import MAX_SCENE_BYTES, linkage_request
    if len(text) > MAX_SCENE_BYTES:
        return None
    try:
        data = toml_data(text)
    except ValueError:
        return None
    source = data.get("linkage")
    if "guess" not in data or not isinstance(source, str):
        return None
    request = linkage_request(source, folder)
    if request is None:
        return None
    from ..io.table_source import TableSource
    return TableSource(source if "file_sha256" not in request else str(Path(folder) / source))


def _run_newton(text: str, where: str, source, args: argparse.Namespace) -> int:
    """Print a scene of a linkage without a closed form, solved as ``symlink table NAME --guess ...`` solves it
    (:func:`symlink.cli.tables.newton_table`), from its ``[guess]`` (the facts and the solver from the disk cache:
    a warm run imports no SymPy); ``where``: the scene's name in messages."""
    from ..common.numbers import toml_data
    from ..io.scene_text import newton_scene  # plain data: no SymPy
    from .tables import newton_table
    facts = source.facts
    try:
        scene = newton_scene(toml_data(text), facts, defaults="file_sha256" in (source.request or {}))
    except ValueError as error:
        raise ValueError(f"{where}: {error}") from None
    blocks = newton_table(facts, source.solver, scene.values, scene.sweep.array(), scene.speed, scene.accel,
                          scene.guess, scene.units)
    write_table(blocks, [scene.input_column, "branch", *scene.outputs], scene.units, args.format or scene.format,
                scene.angle_columns, lambda: "", scene.column_units)
    return 0
