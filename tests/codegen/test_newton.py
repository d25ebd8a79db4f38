"""The generator of the numeric fallback: a standalone NumPy module that embeds the driver from its source."""
import ast
from pathlib import Path

from symlink.mechanism.catalog import stephenson2
from symlink.codegen import newton_driver
from symlink.codegen.newton import driver_source, numeric_module

ROOT = Path(__file__).resolve().parent.parent.parent


def test_generated_module_imports_numpy_only():
    source = numeric_module(stephenson2())
    assert "import numpy" in source and "sympy" not in source.split('"""', 2)[2]
    imports = [node for node in ast.walk(ast.parse(source)) if isinstance(node, (ast.Import, ast.ImportFrom))]
    assert [alias.name for node in imports for alias in node.names] == ["numpy"]


def test_the_driver_is_embedded_from_its_module_whole():
    text = (ROOT / "symlink" / "codegen" / "newton_driver.py").read_text(encoding="utf-8")
    head, marker, tail = text.partition("\n" + newton_driver.DRIVER_BEGINS + "\n")
    assert marker and driver_source() == tail and tail.count("\ndef ") >= 10
    source = numeric_module(stephenson2())
    assert source.count(driver_source()) == 1
    # Every function of the driver is in the generated module, with its body.
    defined = {node.name: ast.dump(node) for node in ast.parse(source).body if isinstance(node, ast.FunctionDef)}
    for node in ast.parse(tail).body:
        if isinstance(node, ast.FunctionDef):
            assert defined[node.name] == ast.dump(node)


def test_the_placeholders_are_defined_by_every_generated_module():
    source = numeric_module(stephenson2())
    defined = {target.id for node in ast.parse(source).body if isinstance(node, ast.Assign)
               for target in node.targets if isinstance(target, ast.Name)}
    defined |= {node.name for node in ast.parse(source).body if isinstance(node, ast.FunctionDef)}
    placeholders = {"INPUTS", "PARAMETERS", "UNKNOWNS", "ANGLE_INPUTS", "ROLES",
                    "_closure", "_velocity_rhs", "_acceleration_rhs", "_outputs"}
    assert placeholders <= defined and all(hasattr(newton_driver, name) for name in placeholders)
