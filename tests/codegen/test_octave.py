"""The MATLAB/Octave export: the generated .m files run under GNU Octave and agree with the NumPy module.

All cases run in one Octave process (inputs and outputs pass through binary
files, bit for bit).  Without Octave the tests skip and say so.
"""
from __future__ import annotations

from dataclasses import replace

import shutil
import subprocess

import numpy
import pytest

from export_checks import angles_of, assert_agree, closed_form_catalog, export_sets, random_arguments, rounding_spread
from references import SEED003_LINKAGE, mp_fourbar
from symlink.codegen.numpy import load_numpy_module, numpy_module
from symlink.codegen.octave import comment_lines, octave_function, octave_identifier
from symlink.io.scene import catalog_linkage

SAMPLES = 300


def _octave() -> list[str]:
    if shutil.which("octave-cli"):
        return ["octave-cli", "--quiet", "--no-init-file"]
    if shutil.which("octave"):
        return ["octave", "--no-gui", "--quiet", "--no-init-file"]
    pytest.skip("GNU Octave is not installed (no octave-cli or octave on PATH): the .m files are not run")


def run_octave(folder, script: str) -> str:
    """Run ``script`` in ``folder`` under Octave; its standard output."""
    (folder / "driver.m").write_text(script)
    result = subprocess.run(_octave() + ["driver.m"], cwd=folder, capture_output=True, text=True,
                            timeout=600, check=False)
    assert result.returncode == 0 and "error:" not in result.stdout, result.stdout + result.stderr
    return result.stdout


class Case:
    """One call of a generated function: its inputs written for Octave, its outputs read back."""

    def __init__(self, index: int, name: str, set_name: str, outputs, function: str, arguments, values):
        self.index, self.name, self.set_name, self.outputs = index, name, set_name, list(outputs)
        self.function, self.arguments, self.values = function, list(arguments), values

    def script(self, folder) -> str:
        numpy.array([self.values[a] for a in self.arguments]).tofile(folder / f"in_{self.index}.bin")
        names = [f"o{k}" for k in range(len(self.outputs) + 1)]
        lines = [f"fid = fopen('in_{self.index}.bin', 'r'); v = fread(fid, [{SAMPLES}, {len(self.arguments)}], "
                 "'double'); fclose(fid);"]
        lines += [f"{a} = v(:, {k + 1})';" for k, a in enumerate(self.arguments)]
        lines.append(f"[{', '.join(names)}] = {self.function}({', '.join(self.arguments)});")
        lines.append(f"if ~islogical({names[-1]}), error('assembled is not logical'); end")
        lines.append(f"fid = fopen('out_{self.index}.bin', 'w'); "
                     f"fwrite(fid, double([{'; '.join(n + '(:)' for n in names)}]), 'double'); fclose(fid);")
        return "\n".join(lines) + "\n"

    def results(self, folder) -> dict[str, numpy.ndarray]:
        data = numpy.fromfile(folder / f"out_{self.index}.bin").reshape(len(self.outputs) + 1, SAMPLES)
        found = dict(zip(self.outputs, data[:-1]))
        found["assembled"] = data[-1].astype(bool)
        return found


@pytest.fixture(scope="module")
def octave_runs(tmp_path_factory):
    """Every default output set of every closed-form catalog entry, run once under Octave."""
    _octave()
    folder = tmp_path_factory.mktemp("octave")
    cases, expected, spreads = [], {}, {}
    for name in closed_form_catalog():
        linkage = catalog_linkage(name)
        stem = name.replace("-", "_")
        sets = export_sets(name)
        module = load_numpy_module(numpy_module([(s, linkage.program(o), d) for s, o, d in sets]))
        for set_name, outputs, doc in sets:
            function = f"{stem}_{set_name}"
            program = linkage.program(outputs)
            (folder / f"{function}.m").write_text(octave_function(program, function, doc))
            arguments = [s.name for s in program.arguments]
            values = random_arguments(linkage, arguments, SAMPLES, seed=len(cases))
            case = Case(len(cases), name, set_name, outputs, function, arguments, values)
            cases.append(case)
            with numpy.errstate(all="ignore"):
                expected[case.index] = {k: numpy.asarray(v) for k, v in module[set_name](**values).items()}
            spreads[case.index] = rounding_spread(module[set_name], values)
    run_octave(folder, "".join(case.script(folder) for case in cases))
    return [(case, case.results(folder), expected[case.index], spreads[case.index]) for case in cases]


@pytest.mark.parametrize("name", closed_form_catalog())
def test_every_catalog_entry_agrees_with_numpy(octave_runs, name):
    checked = 0
    for case, actual, expected, spread in octave_runs:
        if case.name != name:
            continue
        assert expected["assembled"].sum() > 30, f"{name}: too few assembled samples to test"
        assert (~expected["assembled"]).any() or name == "inverted-slider-crank"  # it always closes
        actual = {k: (v.astype(bool) if expected[k].dtype == bool else v) for k, v in actual.items()}
        assert_agree(actual, expected, angles_of(name, case.outputs), 1e-12, f"{name} {case.set_name}", spread)
        checked += 1
    assert checked >= 4


@pytest.fixture()
def fourbar_folder(tmp_path):
    _octave()
    linkage = catalog_linkage("fourbar")
    outputs = ["coupler", "rocker", "rocker_speed", "rocker_accel", "C_x"]
    (tmp_path / "fb.m").write_text(octave_function(linkage.program(outputs), "fb", "Four-bar."))
    return tmp_path, linkage, outputs


def test_fourbar_against_the_50_digit_reference_both_branches_and_unreachable(fourbar_folder):
    folder, _, _ = fourbar_folder
    a, b, c, d = (SEED003_LINKAGE[k] for k in "abcd")
    theta = numpy.radians(numpy.arange(0.0, 360.0, 40.0) + 0.25)
    lines = []
    for branch in (1, -1):
        lines.append(f"theta = [{' '.join(repr(float(t)) for t in theta)}];")
        lines.append(f"[cp, rk, rs, ra, cx, ok] = fb(theta, {a!r}, {b!r}, {c!r}, {d!r}, {branch}, 10.5, 3.0);")
        lines.append("fprintf('%.17g ', [cp; rk; rs; ra; double(ok)]); fprintf('\\n');")
    # Not every crank angle of a = 50, b = 30, c = 40, d = 45 can be assembled.
    lines.append("[cp, rk, rs, ra, cx, ok] = fb([0 pi/2 pi], 50, 30, 40, 45);")
    lines.append("fprintf('%.17g ', [rk; cx; double(ok)]); fprintf('\\n');")
    rows = run_octave(folder, "\n".join(lines) + "\n").strip().splitlines()
    for branch, row in zip((1, -1), rows):
        data = numpy.array([float(v) for v in row.split()]).reshape(len(theta), 5)
        assert data[:, 4].all()
        for angle, (coupler, rocker, speed, accel, _) in zip(theta, data):
            reference = mp_fourbar(a, b, c, d, float(angle), branch, 10.5, 3.0)
            for got, key in ((coupler, "beta"), (rocker, "phi"), (speed, "phi_speed"), (accel, "phi_accel")):
                want = float(reference[key])
                assert abs(got - want) <= 1e-12 * max(1.0, abs(want)), (branch, angle, key)
    data = numpy.array([float(v) for v in rows[2].split()]).reshape(3, 3)
    for angle, (rocker, cx, ok) in zip((0.0, numpy.pi / 2, numpy.pi), data):
        try:
            mp_fourbar(50.0, 30.0, 40.0, 45.0, angle, 1)
            reachable = True
        except ValueError:
            reachable = False
        assert bool(ok) == reachable
        assert numpy.isnan(rocker) == (not reachable) and numpy.isnan(cx) == (not reachable)
    assert not data[:, 2].all() and data[:, 2].any()


def test_broadcasting_and_defaults_follow_numpy(fourbar_folder):
    folder, linkage, outputs = fourbar_folder
    theta = numpy.linspace(-3.0, 3.0, 5)
    a = numpy.array([[15.0], [20.0], [25.0]])
    script = (f"theta = [{' '.join(repr(float(t)) for t in theta)}]; a = [15; 20; 25];\n"
              "[cp, rk, rs, ra, cx, ok] = fb(theta, a, 66, 56, 80);\n"
              "disp(size(cp)); disp(size(cx)); disp(size(ok));\n"
              "fprintf('%.17g ', [cp(:); rk(:); rs(:); cx(:)]); fprintf('\\n');\n"
              "[cp, rk, rs, ra, cx, ok] = fb(0.5, 20, [66 70], 56, 80, -1, 2);\n"
              "disp(size(cx)); fprintf('%.17g ', [rk(:); rs(:); cx(:)]); fprintf('\\n');\n")
    lines = run_octave(folder, script).strip().splitlines()
    assert [line.split() for line in lines[:3]] == [["3", "5"]] * 3
    module = load_numpy_module(numpy_module([("fb", linkage.program(outputs), "")]))
    want = module["fb"](theta, a, 66.0, 56.0, 80.0)  # branch 1 and zero rates by default, as in Octave
    got = numpy.array([float(v) for v in lines[3].split()]).reshape(4, 5, 3)  # Octave's order: columns first
    for k, key in enumerate(("coupler", "rocker", "rocker_speed", "C_x")):
        numpy.testing.assert_allclose(got[k].T, want[key], rtol=1e-12, atol=1e-12)
    assert lines[4].split() == ["1", "2"]
    want = module["fb"](0.5, 20.0, numpy.array([66.0, 70.0]), 56.0, 80.0, -1, 2.0)
    got = numpy.array([float(v) for v in lines[5].split()]).reshape(3, 2)
    for k, key in enumerate(("rocker", "rocker_speed", "C_x")):
        numpy.testing.assert_allclose(got[k], want[key], rtol=1e-12)


def test_a_guard_below_its_threshold_gives_nan_not_inf(tmp_path):
    """The inverted slider-crank with the crank pin on the pivot (|W| = 2.4e-16 at theta = 2 pi, a = d):
    not assembled, and then every output is NaN, as in NumPy; not sqrt(x)/0 = Inf and a finite angle."""
    _octave()
    linkage = catalog_linkage("inverted-slider-crank")
    (tmp_path / "isc.m").write_text(octave_function(linkage.program(["phi", "r"]), "isc", "Guard."))
    script = "[p, r, ok] = isc([2*pi 0 0.5], 1, 1); fprintf('%.17g ', [p; r; double(ok)]); fprintf('\\n');\n"
    got = numpy.array([float(v) for v in run_octave(tmp_path, script).split()]).reshape(3, 3)
    for (phi, r, ok), reachable in zip(got, (False, False, True)):
        assert bool(ok) == reachable
        assert numpy.isnan(phi) == numpy.isnan(r) == (not reachable)


def test_names_that_octave_cannot_take_are_refused():
    assert octave_identifier("Wx_1") == "Wx_1"
    for bad in ("end", "_x", "2x", "a-b", "x" * 64):
        with pytest.raises(ValueError, match="MATLAB/Octave"):
            octave_identifier(bad)
    with pytest.raises(ValueError, match="at least one output"):
        octave_function(catalog_linkage("fourbar").program([]), "f")


def test_output_names_that_collide_are_renamed_and_documented():
    linkage = catalog_linkage("fourbar")
    text = octave_function(linkage.program(["rocker", "crank"]), "fb")
    assert text.splitlines()[0] == "function [rocker, crank, assembled] = fb(theta, a, b, c, d, branch)"
    program = linkage.program(["rocker"])
    from symlink.symbolic.linkage import Program
    renamed = replace(program, outputs={"theta": program.arguments[0], "Wx_1": program.outputs["rocker"]})
    text = octave_function(renamed, "fb")
    assert text.splitlines()[0].startswith("function [theta_out, Wx_1_out, assembled] = fb(")
    assert "Output names: theta_out is theta, Wx_1_out is Wx_1." in text


def test_help_text_cannot_leave_the_comment():
    assert comment_lines("one\rtwo\u2028three\x00four") == ["one", "two", "three four"]
    text = octave_function(catalog_linkage("fourbar").program(["rocker"]), "fb_rocker",
                           "Rocker.\rdisp('injected')\u2028x = 1;")
    body = [line for line in text.splitlines() if not line.startswith("%")]
    assert not any("injected" in line or line.startswith("x = 1") for line in body)
    assert all(line.isprintable() for line in text.splitlines())


def test_export_files_are_one_function_file_each():
    from symlink.codegen.octave import export_files
    files = export_files(catalog_linkage("fourbar"), "fb", [("positions", ["rocker"], "Rocker."),
                                                              ("speeds", ["rocker_speed"], "Speed.")], "Four-bar.")
    assert list(files) == ["fb_positions.m", "fb_speeds.m"]
    assert files["fb_speeds.m"].startswith("function [rocker_speed, assembled] = fb_speeds(")


def test_the_function_checks_its_arguments(tmp_path):
    _octave()
    (tmp_path / "fb_rocker.m").write_text(octave_function(catalog_linkage("fourbar").program(["rocker"]),
                                                          "fb_rocker", "Rocker."))
    calls = {
        "branch 0": ("fb_rocker(0, 20, 66, 56, 80, 0)", "branch must be +1 or -1"),
        "branch 0.5": ("fb_rocker(0, 20, 66, 56, 80, [1, 0.5])", "branch must be +1 or -1"),
        "branch NaN": ("fb_rocker(0, 20, 66, 56, 80, NaN)", "branch must be +1 or -1"),
        "length Inf": ("fb_rocker(0, Inf, 66, 56, 80)", "a must be a positive finite length"),
        "length 0": ("fb_rocker(0, 20, [66, 0], 56, 80)", "b must be a positive finite length"),
        "complex length": ("fb_rocker(0, 20, 66, 56 + 1i, 80)", "c must be a positive finite length"),
        "complex angle": ("fb_rocker([0, 1i], 20, 66, 56, 80)", "theta must be finite real numbers"),
        "NaN angle": ("fb_rocker(NaN, 20, 66, 56, 80)", "theta must be finite real numbers"),
        "text": ("fb_rocker('0', 20, 66, 56, 80)", "theta must be finite real numbers"),
        "good": ("fb_rocker(0, 20, 66, 56, 80, -1)", "no error"),
    }
    script = "".join(f"try\n  {call};\n  disp('{label}: no error');\ncatch err\n  disp(['{label}: ' err.message]);\nend\n"
                     for label, (call, _) in calls.items())
    output = run_octave(tmp_path, script).splitlines()
    found = dict(line.split(": ", 1) for line in output if ": " in line)
    for label, (_, message) in calls.items():
        assert found.get(label) == message, (label, found.get(label))
