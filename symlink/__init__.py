"""symlink: symbolic derivation of planar linkage kinematics.

Describe a linkage as vector loops (or by its joints), get its closure
equations, their closed-form solution with the assembly branch, velocities and
accelerations by differentiation, LaTeX, and fast generated NumPy, C, Octave
and JavaScript solvers; analyse, synthesize, tolerance and draw it.

``import symlink`` is the front door: every public name is an attribute of the
package (``symlink.fourbar()``, ``symlink.Solver``, ``symlink.from_joints``),
listed in :data:`__all__`.  Each is loaded from its layer's module on first use
(PEP 562), so that ``import symlink`` alone, as the command line does for a
scene it finds in its cache, costs no SymPy import.

>>> import symlink
>>> linkage = symlink.fourbar()
>>> result = symlink.Solver(linkage, ["rocker"])(theta=0.0, a=20, b=66, c=56, d=80)
>>> round(float(result["rocker"]) * 180 / 3.141592653589793, 2)
110.74

The layers, in the order data flows through them (each imports only the ones
before it): :mod:`symlink.common`, :mod:`symlink.symbolic`,
:mod:`symlink.mechanism`, :mod:`symlink.codegen`, :mod:`symlink.numeric`,
:mod:`symlink.dynamics`, :mod:`symlink.io`, :mod:`symlink.analysis`,
:mod:`symlink.synthesis`, :mod:`symlink.workshop`, :mod:`symlink.plot`, and the
leaves :mod:`symlink.studio` and :mod:`symlink.cli`.
"""
from __future__ import annotations

import importlib

#: ``typing.TYPE_CHECKING`` without importing :mod:`typing` (some milliseconds): the console script imports this
#: package before :mod:`symlink.__main__` can hold back an interrupt, so the package imports next to nothing.
TYPE_CHECKING = False

from .version import __version__

#: Every public name -> the module that defines it (and, where the names differ, its name there).
#: One table, so that ``__all__``, the lazy loader and the API reference agree.
PUBLIC: dict[str, tuple[str, str]] = {}


def _public(module: str, names: str) -> None:
    for entry in names.split():
        public, _, original = entry.partition("=")
        PUBLIC[public] = (module, original or public)


# the definition and its derivation
_public("symlink.symbolic.vectors", "Vector VectorSum coordinates lengths rate acceleration time_derivative")
_public("symlink.symbolic.loops", "Loop")
_public("symlink.symbolic.linkage", "Linkage")
_public("symlink.symbolic.plan", "solve_plan SolvePlan")
_public("symlink.symbolic.closure", "closure_system")
# the mechanism: joints, structure, the atlas and the catalog
_public("symlink.mechanism.catalog", "fourbar slider_crank inverted_slider_crank offset_inverted_slider_crank watt2 "
        "stephenson2 stephenson3 fivebar jansen with_point CATALOG EXAMPLE_VALUES")
_public("symlink.mechanism.joints", "from_joints Slider JointLinkage JointDescription")
_public("symlink.mechanism.atlas", "atlas_entry ATLAS six_bar_name")
_public("symlink.mechanism.mobility", "degrees_of_freedom Mobility")
# code generation
_public("symlink.codegen.latex", "latex_document newton_document")
_public("symlink.codegen.numpy", "numpy_module")
_public("symlink.codegen.javascript", "javascript_geometry")
_public("symlink.codegen.newton", "numeric_module")
_public("symlink.codegen", "printer PRINTERS")
# numeric evaluation
_public("symlink.numeric.solver", "Solver NumericSolver shared_solver")
_public("symlink.numeric.compiled", "compiled_solver CompiledSolver")
_public("symlink.numeric.results", "Results")
_public("symlink.numeric.reachability", "reachable_range InputRange Toggle")
_public("symlink.numeric.crank_ranges", "crank_range")
_public("symlink.numeric.design_jacobian", "design_jacobian")
# dynamics
_public("symlink.dynamics", "DynamicModel DynamicLinkage MassProperties Gravity PointForce BodyTorque Spring Damper "
        "dynamic_linkage ForwardDynamics ConstantTorque LinearMotor FlywheelSizing energy_fluctuation "
        "flywheel_inertia")
# files and formats
_public("symlink.io.linkage_file", "read_linkage write_linkage load_linkage linkage_text linkage_from_text")
_public("symlink.io.scene", "Scene read_scene catalog_linkage")
_public("symlink.io.export", "export export_texts write_latex FORMATS")
_public("symlink.io.derivation", "write_generated kinematics_module")
_public("symlink.io.pylinkage", "read_pylinkage write_pylinkage")
_public("symlink.io.pyslvs", "read_pyslvs read_pyslvs_project write_pyslvs")
_public("symlink.common.files", "write_atomic")
# analysis
_public("symlink.analysis", "analyze_linkage grashof GRASHOF_CLASSES output_limits transmission_angles "
        "loop_transmissions")
_public("symlink.analysis.fourbar_closed_form", "fourbar_report limit_positions")
_public("symlink.numeric.fourbar_transmission", "transmission_range")
_public("symlink.analysis.loopcase", "solve_case")
# synthesis: the four-bar's own routes and the routes for any linkage
_public("symlink.synthesis.general", "synthesize_path traced_points")
_public("symlink.synthesis.general_function", "synthesize_function function_values chebyshev_inputs")
_public("symlink.synthesis.general_motion", "synthesize_motion link_poses")
_public("symlink.synthesis.shape", "synthesize_shape shape_distance similarity_transform")
_public("symlink.synthesis.path", "synthesize_fourbar_path=synthesize_path fourbar_design path_fourbar "
        "check_design PathDesign")
_public("symlink.synthesis.function", "function_generator")
_public("symlink.synthesis.motion", "motion_generation burmester_points burmester_curves")
_public("symlink.synthesis.quick_return", "quick_return")
# the workshop
_public("symlink.workshop.tolerance", "stack_up Tolerance")
_public("symlink.workshop.pin_play", "pin_play pin_play_envelope")
_public("symlink.workshop.sampled_builds", "sample_builds")
_public("symlink.workshop.fabrication", "link_parts write_svg write_dxf svg_text dxf_text assembly_svg_text "
        "read_design write_design")
_public("symlink.workshop.sweep", "run_sweep read_sweep evaluate_designs SweepSettings")
# pictures
_public("symlink.plot", "angle_figure transmission_figure coupler_curve_figure draw_loop save_figure")
_public("symlink.plot.drawing", "draw_linkage")
_public("symlink.plot.animation", "animate animate_linkage inline_animation")
_public("symlink.plot.view", "FourbarView LinkageView")
_public("symlink.plot.tolerance", "tolerance_figure band_figure distribution_figure")
_public("symlink.plot.synthesis", "motion_figure")
# the studio in a notebook (loaded by name only, on first use: nothing in the library imports the studio)
_public("symlink.studio.widget", "LinkageWidget")

__all__ = sorted(PUBLIC) + ["__version__"]

if TYPE_CHECKING:
    from typing import Any

    from .symbolic.linkage import Linkage
    from .symbolic.loops import Loop
    from .symbolic.vectors import Vector, VectorSum, acceleration, coordinates, lengths, rate, time_derivative


def __getattr__(name: str) -> Any:
    """A public name, imported from its module when first asked for (PEP 562)."""
    try:
        module, attribute = PUBLIC[name]
    except KeyError:
        raise AttributeError(f"module 'symlink' has no attribute {name!r}") from None
    value = getattr(importlib.import_module(module), attribute)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
