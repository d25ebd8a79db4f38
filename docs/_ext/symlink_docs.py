"""Sphinx extension of the symlink site: pages generated from the package itself, so they cannot drift.

* ``reference/api/<module>.md``: one page per public module of :mod:`symlink` (autodoc), and
  ``reference/api/index.md``, their table of contents grouped the way data flows;
* ``reference/cli.md``: the command line, from the ``symlink`` argparse parsers themselves
  (every subcommand, its summary, units and example, its usage and every option).

The pages are written when the builder starts (``builder-inited``), before Sphinx reads the
sources, and only when their text changed (so an incremental build stays incremental). They are
build products: ``.gitignore`` leaves them out of the repository.
"""
from __future__ import annotations

import argparse
import importlib
import os
from pathlib import Path

DOCS = Path(__file__).resolve().parent.parent
ROOT = DOCS.parent
API = DOCS / "reference" / "api"
CLI = DOCS / "reference" / "cli.md"

#: Modules the API reference leaves out: the command line (its own reference page, from its parsers),
#: ``python -m symlink`` and the TOML reader kept for Python 3.10.
NOT_IN_API = ("symlink.cli", "symlink.__main__", "symlink.minitoml")
#: The API's groups, in the order data flows through symlink; a module goes to the first group whose
#: prefixes it matches (the last group takes the rest).
GROUPS = (
    ("The package", ("symlink",)),
    ("Definition", ("symlink.common.names", "symlink.symbolic.vectors", "symlink.symbolic.loops", "symlink.symbolic.linkage", "symlink.mechanism.bodies",
                    "symlink.mechanism.catalog", "symlink.io.linkage_file")),
    ("Closed forms and rates", ("symlink.symbolic.position", "symlink.symbolic.motion", "symlink.symbolic.sensitivity", "symlink.symbolic.closure",
                                "symlink.symbolic.plan", "symlink.common.notation", "symlink.symbolic.outputs", "symlink.common.angles",
                                "symlink.symbolic.typeset", "symlink.analysis.loopcase", "symlink.numeric.assemblies")),
    ("Code generation and exports", ("symlink.codegen", "symlink.io.derivation", "symlink.io.export", "symlink.version")),
    ("Evaluation", ("symlink.numeric.solver", "symlink.numeric.results", "symlink.numeric.units", "symlink.numeric.compiled", "symlink.io.scene",
                    "symlink.numeric.cache", "symlink.numeric.cached_solver", "symlink.numeric.design_jacobian", "symlink.numeric.input_sweep",
                    "symlink.common.limits", "symlink.common.files")),
    ("Analysis, synthesis and sweeps", ("symlink.analysis", "symlink.numeric.reachability", "symlink.synthesis",
                                        "symlink.workshop.sweep")),
    ("Dynamics", ("symlink.dynamics",)),
    ("The studio", ("symlink.studio",)),
    ("Pictures", ("symlink.plot",)),  # last: it takes the modules no group names
)
#: autodoc options of modules that need other than ``:members:``: packages that re-export what
#: their modules document (so each object is described once) and one name shadowed by a method.
AUTOMODULE_OPTIONS = {
    "symlink": [":no-members:"],
    "symlink.dynamics": [":no-members:"],
    "symlink.analysis": [":no-members:"],
    "symlink.plot": [":no-members:"],
    "symlink.plot.inline": [":members:", ":exclude-members: set"],
}


def public_modules() -> list[str]:
    """Every module and package of symlink by dotted name, from the source tree, less ``NOT_IN_API``."""
    names = []
    for path in sorted((ROOT / "symlink").rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        if not any(name == hidden or name.startswith(hidden + ".") for hidden in NOT_IN_API):
            names.append(name)
    return names


def group_of(module: str) -> str:
    """The title of the API group that ``module`` belongs to."""
    for title, prefixes in GROUPS:
        if any(module == prefix or (prefix != "symlink" and module.startswith(prefix + ".")) for prefix in prefixes):
            return title
    return GROUPS[-1][0]


def write_if_changed(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` unless it holds it already (a changed source makes Sphinx re-read it)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        temporary = path.with_name(f".{path.name}.tmp")
        temporary.write_text(text, encoding="utf-8")
        temporary.replace(path)


def module_page(module: str) -> str:
    """The MyST page of one module: its title and autodoc's ``automodule``."""
    options = AUTOMODULE_OPTIONS.get(module, [":members:"])
    lines = [f"# `{module}`", "", "```{eval-rst}", f".. automodule:: {module}", *(f"   {o}" for o in options), "```", ""]
    if module in ("symlink", "symlink.dynamics", "symlink.analysis", "symlink.plot"):
        children = [name for name in public_modules() if name.startswith(module + ".") and name.count(".") ==
                    module.count(".") + 1]
        if children:
            lines += ["Modules:", ""] + [f"- [`{name}`]({name}.md)" for name in children] + [""]
    return "\n".join(lines)


def write_api_pages() -> None:
    modules = public_modules()
    for module in modules:
        write_if_changed(API / f"{module}.md", module_page(module))
    for stale in API.glob("symlink*.md"):
        if stale.stem not in modules:
            stale.unlink()
    index = ["# Python API", "",
             "One page per public module, from its docstrings; grouped the way data flows through symlink:",
             "definition, equations, solution, code, evaluation, tables and pictures. The command line has",
             "its own page, {doc}`../cli`.", ""]
    for title, _ in GROUPS:
        members = [module for module in modules if group_of(module) == title]
        index += [f"## {title}", "", "```{toctree}", ":maxdepth: 1", "", *members, "```", ""]
    write_if_changed(API / "index.md", "\n".join(index))


def _options_of(parser: argparse.ArgumentParser) -> list[argparse.Action]:
    parser.format_help()  # a symlink Parser adds a command's options when they are first needed
    return [action for action in parser._actions if not isinstance(action, argparse._SubParsersAction)]


def _subcommands(parser: argparse.ArgumentParser) -> list[tuple[str, str, argparse.ArgumentParser]]:
    """(name, one-line help, parser) of each subcommand of ``parser``, in the order ``--help`` lists them."""
    found = []
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            helps = {choice.dest: choice.help or "" for choice in action._choices_actions}
            for name, sub in action.choices.items():
                found.append((name, helps.get(name, ""), sub))
    return found


def _cell(text: object) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def _option_row(action: argparse.Action) -> str:
    names = ", ".join(f"`{name}`" for name in action.option_strings) or f"`{action.metavar or action.dest}`"
    if action.option_strings and action.nargs != 0:
        names += f" `{action.metavar or action.dest.upper()}`" if not isinstance(action.metavar, tuple) else ""
    choices = f"one of {', '.join(f'`{c}`' for c in action.choices)}" if action.choices else ""
    default = action.default
    shown = "" if default in (None, False, argparse.SUPPRESS) or isinstance(default, (list, dict)) and not default \
        else f"`{default}`"
    help_text = "" if action.help == argparse.SUPPRESS else (action.help or "")
    if "%(default)" in help_text:
        help_text = help_text.replace("%(default)s", str(default))
    what = "; ".join(part for part in (_cell(help_text), _cell(choices)) if part)
    return f"| {names} | {what} | {_cell(shown)} |"


def command_section(path: str, summary: str, parser: argparse.ArgumentParser, depth: int) -> list[str]:
    """The reference of one command (and of its subcommands, one heading level down)."""
    actions = _options_of(parser)
    lines = [f"{'#' * depth} `{path}`", ""]
    if summary:
        lines += [f"{summary[0].upper()}{summary[1:]}.", ""]
    usage = parser.format_usage().strip()
    lines += ["```text", usage, "```", ""]
    description = (parser.description or "").strip()
    rest = description.split("\n\n", 1)[1].strip() if summary and "\n\n" in description else \
        ("" if summary else description)
    if rest:
        lines += ["```text", rest, "```", ""]
    rows = [_option_row(action) for action in actions if action.help != argparse.SUPPRESS]
    if rows:
        lines += ["| argument | what it is | default |", "|---|---|---|", *rows, ""]
    if parser.epilog:
        lines += ["```text", parser.epilog.strip(), "```", ""]
    for name, help_text, sub in _subcommands(parser):
        lines += command_section(f"{path} {name}", help_text, sub, depth + 1)
    return lines


def write_cli_page() -> None:
    """The command-line reference, with usage lines wrapped at 100 columns whatever the terminal."""
    before = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = "100"  # argparse wraps at the terminal's width: make the page the same everywhere
    try:
        _write_cli_page()
    finally:
        if before is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = before


def _write_cli_page() -> None:
    cli = importlib.import_module("symlink.cli")
    parser = cli.build_parser()  # every command registered
    commands = _subcommands(parser)
    lines = ["# Command line", "",
             "Generated from the `symlink` command's own parsers when the site is built, so it lists every",
             "subcommand and option that `symlink --help` does. Angles are in degrees unless `--units rad`;",
             "results go to stdout, notes and progress to stderr. Exit status: 0 done, 1 a file could not be",
             "written or read, 2 bad input (one line, `symlink: error: ...`), 130 interrupted.", "",
             "```text", parser.format_help().strip(), "```", "",
             "| command | what it does |", "|---|---|",
             *[f"| [`{name}`](#symlink-{name.replace(' ', '-')}) | {_cell(help_text)} |"
               for name, help_text, _ in commands], ""]
    for name, help_text, sub in commands:
        lines += command_section(f"symlink {name}", help_text, sub, 2)
    write_if_changed(CLI, "\n".join(lines))


def generate(app) -> None:
    write_api_pages()
    write_cli_page()


def setup(app) -> dict:
    app.connect("builder-inited", generate)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
