"""The NumPy printer: CSE, no SymPy or Piecewise in the output, broadcasting, assembly mask, escaped docstrings."""
import ast
import collections

import numpy
import sympy as sp

from symlink.catalog import fourbar
from symlink.codegen.numpy import docstring_text, export_files, load_numpy_module, numpy_module


def test_common_subexpressions_are_computed_once():
    source = numpy_module([("f", fourbar().program(["coupler_accel", "rocker_accel"]), "")])
    function = next(n for n in ast.parse(source).body if isinstance(n, ast.FunctionDef) and n.name == "f")
    values = [ast.dump(node.value) for node in function.body if isinstance(node, ast.Assign)]
    calls = collections.Counter(ast.dump(n) for v in function.body if isinstance(v, ast.Assign)
                                for n in ast.walk(v.value) if isinstance(n, ast.Call))
    assert len(values) == len(set(values))
    assert max(calls.values()) == 1, [c for c, k in calls.items() if k > 1]


def test_no_sympy_no_piecewise_no_eval():
    source = numpy_module([("f", fourbar().program(fourbar().output_names()), "")])
    assert "sympy" not in source and "Piecewise" not in source and "select(" not in source
    assert "eval(" not in source


def test_constant_outputs_broadcast_to_the_input_shape():
    namespace = load_numpy_module(numpy_module([("f", fourbar().program(["A_x", "D_x", "rocker"]), "")]))
    result = namespace["f"](numpy.zeros(4), 20, 66, 56, 80)
    assert result["A_x"].shape == (4,) and result["D_x"].tolist() == [80.0] * 4


def test_module_header_names_versions():
    source = numpy_module([("f", fourbar().program(["rocker"]), "")], regenerate="python derivations/x.py")
    assert f"SymPy {sp.__version__}" in source and "Regenerate with: python derivations/x.py" in source


def test_titles_and_docstrings_cannot_break_out_of_the_module():
    hostile = 'x""" + __import__("os").system("echo no") + """\\'
    source = numpy_module([("f", fourbar().program(["rocker"]), hostile)], title=hostile, regenerate=hostile)
    tree = ast.parse(source)  # still a docstring, the import, TOLERANCE and functions: nothing else would run
    assert ast.get_docstring(tree).startswith(hostile)
    assert [type(n).__name__ for n in tree.body] == ["Expr", "Import", "Assign"] + ["FunctionDef"] * 3
    function = next(n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "f")
    assert ast.get_docstring(function).startswith(hostile)
    assert [type(n).__name__ for n in function.body[:2]] == ["Expr", "Assign"]


def test_docstring_text_reads_back_as_the_text():
    for text in ['"', '""', '"""', "\\", "a\\", '\\"""', "tab\there", "nul\x00", "line\u2028sep", "é"]:
        assert ast.literal_eval('"""' + docstring_text(text) + '\n"""') == text + "\n", text


def test_export_files_is_one_module():
    files = export_files(fourbar(), "fb", [("positions", ["rocker"], "Rocker."), ("speeds", ["rocker_speed"], "")],
                         "Four-bar.", "make it")
    assert list(files) == ["fb.py"]
    namespace = load_numpy_module(files["fb.py"])
    assert {"positions", "speeds"} <= set(namespace)
