"""Code generation: CSE, no SymPy or Piecewise in the output, broadcasting, assembly mask."""
import ast
import collections

import numpy
import sympy as sp

from symlink.catalog import fourbar
from symlink.codegen import load_numpy_module, numpy_module, straight_line


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


def test_straight_line_defines_before_use():
    code = straight_line(fourbar().program(["coupler_accel", "transmission", "C_y"]))
    defined = set(code.arguments)
    for symbol, expr in code.assignments:
        assert expr.free_symbols <= defined, symbol
        defined.add(symbol)
    for expr in code.outputs.values():
        assert expr.free_symbols <= defined


def test_constant_outputs_broadcast_to_the_input_shape():
    namespace = load_numpy_module(numpy_module([("f", fourbar().program(["A_x", "D_x", "rocker"]), "")]))
    result = namespace["f"](numpy.zeros(4), 20, 66, 56, 80)
    assert result["A_x"].shape == (4,) and result["D_x"].tolist() == [80.0] * 4


def test_module_header_names_versions():
    source = numpy_module([("f", fourbar().program(["rocker"]), "")], regenerate="python derivations/x.py")
    assert f"SymPy {sp.__version__}" in source and "Regenerate with: python derivations/x.py" in source
