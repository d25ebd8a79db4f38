"""Sphinx extension of the symlink site: pages generated from the package itself, so they cannot drift.

* ``reference/api/public.md``: the front door, every name of ``symlink.__all__`` (autodoc of
  ``symlink.<name>``), grouped by layer (in the order data flows), each in the order of :data:`symlink.PUBLIC`;
* ``reference/api/<module>.md``: one page per module of :mod:`symlink` (autodoc), the internals, and
  ``reference/api/internals.md``, their table of contents grouped by layer folder;
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
#: The layers of symlink, in the order data flows through them: (package, title). The public API is grouped
#: by them, and so are the internals (one group per layer folder, the package itself first).
LAYERS = (
    ("symlink.common", "Shared by every layer: names, notation, angles, displays, files, memory budgets"),
    ("symlink.symbolic", "The blackboard: vectors, loops, a linkage and its derivation"),
    ("symlink.mechanism", "The mechanism: bodies, joints, structure, the atlas and the catalog"),
    ("symlink.codegen", "Code generation: one straight-line program, one printer per language"),
    ("symlink.numeric", "Evaluation: solvers, the compiled backend, the cache, results, poses, reachability"),
    ("symlink.dynamics", "Dynamics: masses and loads, driving torque and reactions, forward dynamics, flywheels"),
    ("symlink.io", "Files and formats: linkage, joint-table and scene files, exports, interchange, sweep folders"),
    ("symlink.analysis", "Analysis: Grashof, transmission angles, limit positions, reports"),
    ("symlink.synthesis", "Synthesis: quick-return, function, path, motion and shape, of the four-bar and any linkage"),
    ("symlink.workshop", "The workshop: tolerances, parts, design sweeps"),
    ("symlink.plot", "Pictures: drawings, figures, animations, interactive views"),
    ("symlink.studio", "The studio: the browser app (a leaf)"),
)
#: The internals' groups: the package's own modules, then one group per layer folder; a module goes to the
#: first group whose prefixes it matches (the last group takes the rest).
GROUPS = (("The package", ("symlink", "symlink.version")),
          *((f"`{package.replace('.', '/')}/`: {title}", (package,)) for package, title in LAYERS))
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


def layer_of(module: str) -> str:
    """The layer package of ``module`` (``symlink.io.scene`` -> ``symlink.io``)."""
    return ".".join(module.split(".")[:2])


def data_comment(name: str, module: str) -> str:
    """The ``#:`` comment of the constant ``name``, from ``module`` or, for a package re-exporting it, its modules."""
    from sphinx.pycode import ModuleAnalyzer

    candidates = [module] + [other for other in public_modules() if other.startswith(module + ".")]
    for candidate in candidates:
        try:
            comments = ModuleAnalyzer.for_module(candidate).find_attr_docs()
        except Exception:  # noqa: BLE001 - a module without source: try the next
            continue
        if ("", name) in comments:
            return "\n".join(line for line in comments[("", name)] if line.strip())
    return ""


def public_entry(name: str, module: str, attribute: str) -> list[str]:
    """The reStructuredText of one public name: autodoc of ``symlink.<name>``, or a constant's own comment."""
    import inspect

    value = getattr(importlib.import_module(module), attribute)
    home = f"``{module}.{attribute}``"
    if inspect.isclass(value):
        return [f".. autoclass:: symlink.{name}", "", f"   Defined in {home}; its members are in the internals.", ""]
    if callable(value):
        return [f".. autofunction:: symlink.{name}", ""]
    comment = data_comment(attribute, module) or f"A constant of {home}."
    return [f".. py:data:: {name}", "", *(f"   {line}" for line in comment.splitlines()), "",
            f"   Defined in {home}.", ""]


def public_page() -> str:
    """The page of ``import symlink``: every name of ``symlink.__all__``, by layer in the order data flows
    through them, each layer's names in ``PUBLIC``'s order."""
    import symlink

    lines = ["# The public API: `import symlink`", "",
             "Every name of `symlink.__all__`, an attribute of the package (`symlink.fourbar()`,",
             "`symlink.Solver`), loaded from its layer's module on first use. Grouped by layer, in the order",
             "data flows through symlink. Each module, with the members of each class and what the front",
             "door leaves out, has its own page in {doc}`internals`.", "",
             "```{eval-rst}", ".. currentmodule:: symlink", "```", ""]
    titles = dict(LAYERS)
    layers: dict[str, list[tuple[str, str, str]]] = {}
    for name, (module, attribute) in symlink.PUBLIC.items():
        layers.setdefault(layer_of(module), []).append((name, module, attribute))
    order = [package for package, _ in LAYERS]
    for layer, entries in sorted(layers.items(), key=lambda item: order.index(item[0]) if item[0] in order else 99):
        lines += [f"## {titles.get(layer, layer)}", "", "```{eval-rst}"]
        for name, module, attribute in entries:
            lines += public_entry(name, module, attribute)
        lines += ["```", ""]
    lines += ["## The version", "", "```{eval-rst}", ".. py:data:: __version__", "",
              "   The version of symlink, a string (``symlink.version``).", "```", ""]
    return "\n".join(lines)


def public_names_as_aliases(app, env) -> None:
    """Let a short cross-reference (``Linkage`` in a type) resolve to the module's own object, not the front door's.

    The public page and the internals describe the same objects under two names (``symlink.Linkage``
    and ``symlink.symbolic.linkage.Linkage``); the front door's names count as aliases, which Sphinx
    sets aside when a search by the last part finds both, so that no reference is ambiguous. A
    reference to ``symlink.Linkage`` in full still goes to the public page.
    """
    import symlink

    domain = env.get_domain("py")
    for name in symlink.PUBLIC:
        entry = domain.objects.get(f"symlink.{name}")
        if entry is not None and not entry.aliased:
            domain.objects[f"symlink.{name}"] = entry._replace(aliased=True)


def write_api_pages() -> None:
    modules = public_modules()
    written = {"public", "internals"}
    for module in modules:
        write_if_changed(API / f"{module}.md", module_page(module))
        written.add(module)
    for stale in API.glob("*.md"):
        if stale.stem not in written:
            stale.unlink()
    write_if_changed(API / "public.md", public_page())
    index = ["# Internals: every module", "",
             "One page per module of symlink, from its docstrings, grouped by layer the way data flows:",
             "definition, equations, solution, code, evaluation, tables and pictures. What a user needs is",
             "on {doc}`public` (`import symlink`); the command line has its own page, {doc}`../cli`.", ""]
    for title, _ in GROUPS:
        members = [module for module in modules if group_of(module) == title]
        if members:
            index += [f"## {title}", "", "```{toctree}", ":maxdepth: 1", "", *members, "```", ""]
    write_if_changed(API / "internals.md", "\n".join(index))


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
    app.connect("env-check-consistency", public_names_as_aliases)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
