"""The house stays standing: symlink's import graph has no cycle, and the command line is a leaf.

The graph is read from the source with ``ast``: every ``import`` and ``from
... import`` of a symlink module, at the top of a module or inside a
function, is an edge, and so is one under ``if TYPE_CHECKING:`` (a type hint is a
dependency too: a lower layer names a higher one's type only by importing
it).  Importing a name from a package counts as
importing that package's ``__init__``, its own parent packages included
(``from .. import x``); the parents Python loads on the way are not edges.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "symlink"


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(tree: ast.AST):
    """Every import node of a module, at the top, in functions, and under ``if TYPE_CHECKING:`` alike."""
    return (node for node in ast.walk(tree) if isinstance(node, (ast.Import, ast.ImportFrom)))


def imported_modules(path: Path, modules: set[str]) -> set[str]:
    """The symlink modules (and other top-level names, e.g. ``argparse``) that ``path`` imports."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in _imports(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            for alias in node.names:
                found.add(alias.name)
            continue
        if node.level:
            base = package.split(".")
            base = base[:len(base) - node.level + 1]
            target = ".".join(base + ([node.module] if node.module else []))
        else:
            target = node.module
        for alias in node.names:  # from package import submodule
            candidate = f"{target}.{alias.name}"
            found.add(candidate if candidate in modules else target)
    return found


def import_graph() -> dict[str, set[str]]:
    paths = sorted(PACKAGE.rglob("*.py"))
    modules = {module_name(p) for p in paths}
    graph = {}
    for path in paths:
        name = module_name(path)
        edges = set()
        for target in imported_modules(path, modules):
            if target in modules or target.split(".")[0] in {"argparse"}:
                if target != name:
                    edges.add(target)
        graph[name] = edges
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of the graph as a list of modules, or None."""
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        stack.append(node)
        for target in sorted(graph.get(node, ())):
            if target not in graph:
                continue
            if state.get(target) == 1:
                return stack[stack.index(target):] + [target]
            if target not in state:
                found = visit(target)
                if found:
                    return found
        stack.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def test_the_graph_is_read_from_the_source():
    graph = import_graph()
    assert "symlink.cli" in graph and "symlink.symbolic.linkage" in graph
    assert "symlink.symbolic.loops" in graph["symlink.symbolic.linkage"]  # a top-level import
    assert "symlink.symbolic.linkage" in graph["symlink.cli.tables"]


def test_a_name_imported_from_a_parent_package_is_an_edge(tmp_path):
    """``from .. import __version__`` in symlink/codegen/numpy.py would reach symlink/__init__ (and the linkage)."""
    module = PACKAGE / "codegen" / "numpy.py"
    modules = {"symlink", "symlink.codegen", "symlink.codegen.numpy", "symlink.version"}
    assert "symlink.version" in imported_modules(module, modules | {"symlink.version"})
    assert "symlink" not in imported_modules(module, modules)


def test_the_cycle_finder_finds_cycles():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set(), "c": {"a", "b"}}) is None


def test_no_import_cycle():
    cycle = find_cycle(import_graph())
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


@pytest.mark.parametrize("forbidden", ["symlink.cli", "argparse"])
def test_the_command_line_is_a_leaf(forbidden):
    """Nothing outside symlink/cli imports the command line or argparse (``__main__`` runs it)."""
    offenders = sorted(name for name, edges in import_graph().items()
                       if not (name == "symlink.cli" or name.startswith("symlink.cli.") or name == "symlink.__main__")
                       and any(e == forbidden or e.startswith(forbidden + ".") for e in edges))
    assert offenders == [], f"{forbidden} imported by {', '.join(offenders)}"


#: The layers, in the order the data flows through them: each imports only itself and the layers before it.
LAYERS = ("common", "symbolic", "mechanism", "codegen", "numeric", "dynamics", "io", "analysis", "synthesis",
          "workshop", "plot", "studio", "cli")
#: What may sit at the top of the package beside the layer folders.
TOP = {"symlink", "symlink.version", "symlink.__main__"}


def layer_of(module: str) -> int | None:
    parts = module.split(".")
    return LAYERS.index(parts[1]) if len(parts) > 1 and parts[1] in LAYERS else None


def test_the_top_of_the_package_holds_only_the_front_door_and_the_layers():
    graph = import_graph()
    loose = sorted(name for name in graph if name not in TOP and layer_of(name) is None)
    assert loose == [], f"modules outside the layer folders: {', '.join(loose)}"
    folders = sorted(p.name for p in PACKAGE.iterdir() if p.is_dir() and (p / "__init__.py").is_file())
    assert set(folders) <= set(LAYERS), f"folders that are no layer: {set(folders) - set(LAYERS)}"


def test_each_layer_imports_only_the_layers_before_it():
    offenders = []
    for name, edges in import_graph().items():
        own = layer_of(name)
        if own is None:
            continue
        for target in edges:
            if not target.startswith("symlink"):
                continue
            theirs = layer_of(target)
            if target == "symlink" or (theirs is not None and theirs > own):
                offenders.append(f"{name} -> {target}")
    assert offenders == [], "imports against the flow:\n" + "\n".join(sorted(offenders))


def test_the_studio_is_a_leaf_too():
    offenders = sorted(name for name, edges in import_graph().items()
                       if layer_of(name) != LAYERS.index("studio")
                       and not name.startswith("symlink.cli")
                       and any(e.startswith("symlink.studio") for e in edges))
    assert offenders == [], f"symlink.studio imported by {', '.join(offenders)}"


def test_the_layer_check_sees_a_backward_import():
    assert layer_of("symlink.numeric.solver") > layer_of("symlink.symbolic.linkage")
    assert layer_of("symlink.version") is None


def test_the_architecture_page_lists_every_module():
    page = (PACKAGE.parent / "docs" / "explanation" / "architecture.md").read_text(encoding="utf-8")
    missing = []
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(PACKAGE)
        if len(relative.parts) == 1 or path.name == "__init__.py":
            continue
        if f"### `symlink/{relative.parts[0]}/`" not in page or f"| `{path.name}` |" not in page:
            missing.append(str(relative))
    assert missing == [], f"docs/explanation/architecture.md does not list: {', '.join(missing)}"


def test_the_tests_mirror_the_layers():
    tests = PACKAGE.parent / "tests"
    for layer in LAYERS:
        if (PACKAGE / layer).is_dir() and any((PACKAGE / layer).glob("[!_]*.py")):
            assert (tests / layer).is_dir(), f"no tests/{layer}/ for symlink/{layer}/"
