"""Everything the public API returns shows itself in a notebook: a rich display, not a one-line repr."""
import importlib
import inspect
import pkgutil
import typing

import pytest

import symlink

RICH = ("_repr_html_", "_repr_markdown_", "_repr_latex_", "_repr_mimebundle_", "_repr_png_", "_repr_svg_")
#: Classes the API returns that a notebook need not show richly, and why.
PLAIN = {
    "symlink.symbolic.linkage.Program": "the straight-line program a code printer takes; its code is what a user reads",
    "symlink.symbolic.loops.Unknown": "where an unknown sits in a loop, read by the solvers; its repr names it",
    "symlink.symbolic.loops.LoopCase": "the case of a loop, read by the solvers; Loop and LoopSolution show the maths",
    "symlink.numeric.cache_folder.CacheContents": "the `symlink cache` command's record; the cache module stays display-free "
                                   "on the warm start's path",
}


def returned_classes() -> dict[type, str]:
    """Each symlink class that a public function or method returns (by its annotation), with where.

    Annotations may name classes a module imports for type checking only (the symbolic layer, kept out of a warm
    start): they resolve against the front door's classes and SymPy.
    """
    import sympy
    names = {"sp": sympy, **{name: getattr(symlink, name) for name in symlink.__all__
                             if inspect.isclass(getattr(symlink, name))}}
    found: dict[type, str] = {}
    for info in pkgutil.walk_packages(symlink.__path__, "symlink."):
        if info.name.startswith(("symlink.cli", "symlink.codegen", "symlink.__main__")):
            continue
        module = importlib.import_module(info.name)
        for name in getattr(module, "__all__", []):
            value = getattr(module, name)
            if inspect.isfunction(value):
                functions = [value]
            elif inspect.isclass(value):
                functions = [f for n, f in vars(value).items() if inspect.isfunction(f) and not n.startswith("_")]
            else:
                continue
            for function in functions:
                try:
                    hint = typing.get_type_hints(function, localns=names).get("return")
                except Exception:  # noqa: BLE001 - an annotation that names an optional package: not ours
                    continue
                for outer in [hint, *typing.get_args(hint)]:
                    for candidate in [outer, *typing.get_args(outer)]:
                        if inspect.isclass(candidate) and candidate.__module__.startswith("symlink"):
                            found.setdefault(candidate, f"{module.__name__}.{function.__qualname__}")
    return found


RETURNED = returned_classes()


def test_the_scan_finds_the_result_classes():
    names = {f"{cls.__module__}.{cls.__qualname__}" for cls in RETURNED}
    assert {"symlink.analysis.report.LinkageReport", "symlink.numeric.results.Results", "symlink.numeric.solver.Solver",
            "symlink.plot.animation.Rendered", "symlink.symbolic.position.LoopSolution"} <= names


@pytest.mark.parametrize("cls", sorted(RETURNED, key=lambda c: f"{c.__module__}.{c.__qualname__}"),
                         ids=lambda c: c.__qualname__)
def test_every_returned_class_has_a_rich_display(cls):
    name = f"{cls.__module__}.{cls.__qualname__}"
    if name in PLAIN:
        pytest.skip(PLAIN[name])
    assert any(hasattr(cls, method) for method in RICH), \
        f"{name} (returned by {RETURNED[cls]}) has no rich display: give it _repr_html_ = record_html"
