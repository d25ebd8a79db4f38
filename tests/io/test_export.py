"""`symlink export NAME --to numpy|c|octave|javascript|latex --out DIR [--outputs LIST]`."""
from __future__ import annotations

import ctypes
import shutil
import subprocess

import numpy
import pytest

from references import mp_fourbar
from symlink.numeric import cache
from symlink.mechanism.catalog import CATALOG
from symlink.cli import main
from symlink.codegen.numpy import load_numpy_module
from symlink.io.export import export_texts, output_sets
from symlink.io.scene import catalog_linkage


@pytest.fixture(autouse=True)
def private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "cache"))
    cache.clear_memory()
    yield
    cache.clear_memory()


def run(capsys, *argv):
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_numpy_export_is_a_working_module_with_the_default_sets(tmp_path, capsys):
    status, out, err = run(capsys, "export", "fourbar", "--to", "numpy", "--out", tmp_path / "out")
    assert status == 0 and err == "" and out == f"wrote {tmp_path / 'out' / 'fourbar.py'}\n"
    module = load_numpy_module((tmp_path / "out" / "fourbar.py").read_text())
    for name in ("positions", "velocities", "accelerations", "joints"):
        assert callable(module[name])
    result = module["velocities"](0.3, 20.0, 66.0, 56.0, 80.0, -1, 10.5)
    reference = mp_fourbar(20.0, 66.0, 56.0, 80.0, 0.3, -1, 10.5)
    assert abs(float(result["rocker"]) - float(reference["phi"])) < 1e-13
    assert abs(float(result["rocker_speed"]) - float(reference["phi_speed"])) < 1e-12
    assert "Regenerate with: symlink export fourbar --to numpy" in (tmp_path / "out" / "fourbar.py").read_text()


def test_c_export_compiles_and_names_its_functions(tmp_path, capsys):
    status, out, _ = run(capsys, "export", "slider-crank", "--to", "c", "--out", tmp_path)
    assert status == 0 and out.split() == ["wrote", str(tmp_path / "slider_crank.h"),
                                           "wrote", str(tmp_path / "slider_crank.c")]
    header = (tmp_path / "slider_crank.h").read_text()
    for name in ("positions", "velocities", "accelerations", "joints"):
        assert f"void slider_crank_{name}(size_t n," in header
    compiler = shutil.which("cc") or shutil.which("gcc")
    if compiler is None:
        pytest.skip("no C compiler on PATH: the exported C is not compiled")
    result = subprocess.run([compiler, "-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-fPIC", "-shared",
                             "-o", "sc.so", "slider_crank.c", "-lm"], cwd=tmp_path, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    library = ctypes.CDLL(str(tmp_path / "sc.so"))
    assert library.slider_crank_positions and library.slider_crank_accelerations


def test_octave_export_writes_one_file_per_function(tmp_path, capsys):
    status, out, _ = run(capsys, "export", "fourbar", "--to", "octave", "--out", tmp_path)
    assert status == 0
    names = sorted(p.name for p in tmp_path.glob("*.m"))
    assert names == ["fourbar_accelerations.m", "fourbar_joints.m", "fourbar_positions.m", "fourbar_velocities.m"]
    first = (tmp_path / "fourbar_positions.m").read_text().splitlines()[0]
    assert first == "function [coupler, rocker, assembled] = fourbar_positions(theta, a, b, c, d, branch)"


def test_javascript_export_is_one_solver_of_every_set(tmp_path, capsys):
    status, out, _ = run(capsys, "export", "fourbar", "--to", "javascript", "--out", tmp_path)
    assert status == 0 and out == f"wrote {tmp_path / 'fourbar.js'}\n"
    text = (tmp_path / "fourbar.js").read_text()
    assert text.startswith("(function (root, factory) {") and "Regenerate with: symlink export fourbar --to javascript" in text
    import symlink
    written = symlink.export(catalog_linkage("slider-crank"), "javascript", tmp_path / "api")
    assert [p.name for p in written] == ["slider_crank.js"]
    node = shutil.which("node")
    if node is None:
        pytest.skip("Node.js is not installed (no node on PATH): the exported JavaScript is not run")
    script = ("const s = require(process.argv[1]);\n"
              "const r = s.solve({theta: 0.3, a: 20, b: 66, c: 56, d: 80, branch: -1, thetadot: 10.5, thetaddot: 0});\n"
              "process.stdout.write(JSON.stringify({sets: s.sets, rocker: r.rocker, speed: r.rocker_speed, "
              "C_x: r.C_x, assembled: r.assembled}));\n")
    result = subprocess.run([node, "-e", script, str(tmp_path / "fourbar.js")], capture_output=True, text=True,
                            check=False)
    assert result.returncode == 0, result.stderr
    found = __import__("json").loads(result.stdout)
    assert list(found["sets"]) == ["positions", "velocities", "accelerations", "joints"]
    assert found["sets"]["joints"] == ["B_x", "B_y", "C_x", "C_y"] and found["assembled"] is True
    reference = mp_fourbar(20.0, 66.0, 56.0, 80.0, 0.3, -1, 10.5)
    assert abs(found["rocker"] - float(reference["phi"])) < 1e-13
    assert abs(found["speed"] - float(reference["phi_speed"])) < 1e-12


def test_outputs_make_one_function_and_latex_follows_them(tmp_path, capsys):
    status, _, _ = run(capsys, "export", "fourbar", "--to", "c", "--out", tmp_path, "--outputs", "rocker, C_x")
    assert status == 0
    header = (tmp_path / "fourbar.h").read_text()
    assert header.count("\nvoid ") == 1 and "double *rocker, double *C_x, unsigned char *assembled" in header
    status, _, _ = run(capsys, "export", "fourbar", "--to", "latex", "--out", tmp_path, "--outputs", "rocker")
    tex = (tmp_path / "fourbar.tex").read_text()
    assert status == 0 and r"\begin{document}" in tex and "Velocities" not in tex
    run(capsys, "export", "fourbar", "--to", "latex", "--out", tmp_path, "--outputs", "rocker_speed")
    tex = (tmp_path / "fourbar.tex").read_text()
    assert "Velocities" in tex and "Accelerations" not in tex


def test_default_sets_use_role_names_and_moving_joints_only():
    sets = {name: outputs for name, outputs, _ in output_sets(catalog_linkage("fourbar"))}
    assert sets["positions"] == ["coupler", "rocker"]
    assert sets["joints"] == ["B_x", "B_y", "C_x", "C_y"]  # A and D are fixed pivots
    assert sets["accelerations"][-1] == "transmission"


@pytest.mark.parametrize("argv, message", [
    (["nope", "--to", "c"], "no linkage 'nope' in the catalog"),
    (["fourbar", "--to", "java"], "invalid choice: 'java'"),
    (["fourbar", "--to", "c", "--outputs", "rocker,nope"], "fourbar has no output 'nope'"),
    (["fourbar", "--to", "c", "--outputs", ","], "--outputs needs at least one output"),
])
def test_bad_requests_are_one_line_and_exit_2_writing_nothing(tmp_path, capsys, argv, message):
    status, out, err = run(capsys, "export", *argv, "--out", tmp_path / "out")
    assert status == 2 and out == "" and message in err and err.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_a_linkage_without_closed_form_is_refused(tmp_path, capsys):
    names = [n for n in CATALOG if not getattr(catalog_linkage(n), "has_closed_form", True)]
    if not names:
        pytest.skip("every catalog entry has a closed form")
    for fmt in ("c", "javascript"):
        status, _, err = run(capsys, "export", names[0], "--to", fmt, "--out", tmp_path / "out")
        assert status == 2 and "no closed-form solve plan" in err and not (tmp_path / "out").exists()


def test_out_must_be_a_folder(tmp_path, capsys):
    (tmp_path / "file").write_text("x")
    status, _, err = run(capsys, "export", "fourbar", "--to", "numpy", "--out", tmp_path / "file")
    assert status == 2 and "not a folder" in err


def test_texts_come_from_the_cache_the_second_time(monkeypatch):
    first = export_texts("fourbar", "octave")
    cache.clear_memory()
    monkeypatch.setattr(type(catalog_linkage("fourbar")), "program",
                        lambda *_: pytest.fail("derived again instead of reading the cache"))
    assert export_texts("fourbar", "octave") == first


def test_latex_in_a_seed_papers_form_and_refused_for_code(tmp_path, capsys):
    """``--form`` writes the seed's form beside the atan2 form; generated code has one form, so code refuses it."""
    status, out, err = run(capsys, "export", "fourbar", "--to", "latex", "--form", "half-angle", "--out", tmp_path / "t")
    text = (tmp_path / "t" / "fourbar.tex").read_text()
    assert status == 0 and "tangent half-angle form}" in text and "\\tan^{2}" in text
    assert "B_{\\beta}^{2} - 4 A_{\\beta} C_{\\beta}" in text  # as a textbook writes the discriminant
    assert "seed 00" not in text  # headings in words a reader of the PDF understands
    status, out, err = run(capsys, "export", "fourbar", "--to", "c", "--form", "freudenstein", "--out", tmp_path / "c")
    assert status == 2 and "applies to --to latex only" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "c").exists()
