"""Dynamics on the command line: mass columns for ``symlink fourbar`` and ``symlink flywheel``.

Mass properties of the four-bar's crank (2), coupler (3) and rocker (4), each a comma
list in that order:

* ``--masses m2,m3,m4`` (mass units), ``--inertias I2,I3,I4`` (about each centre of mass);
* ``--centres r2:angle2,r3:angle3,r4:angle4``: each centre at distance r from the link's
  pivot end, at the angle (in ``--units``) counter-clockwise from the link line: the
  crank from A along AB, the coupler from B along BC, the rocker from D along DC
  (``--centres 10:0,33:0,28:0`` puts them on the link lines);
* ``--gravity G[,ANGLE]``: gravity of size G pointing at ANGLE (in ``--units``; default
  -90 deg, straight down), default none;
* ``--load-torque T``: a torque on the crank shaft, counter-clockwise positive (a load
  resisting a counter-clockwise crank is negative).

With ``--masses`` the four-bar table gets the columns of :data:`MASS_COLUMNS`: the
driving torque and the force of each pin's first body on its second (the ground's on
the crank at A, the crank's on the coupler at B, the coupler's on the rocker at C, the
ground's on the rocker at D), and the shaking force and moment on the frame.  Units
follow the inputs: with lengths in metres, masses in kg and speeds in rad/s, torques
are in N m and forces in N.
"""
from __future__ import annotations

import argparse
import math
from typing import TYPE_CHECKING

from ..common.angles import to_radians
from .budget import add_time_budget_option, require_budget
from .options import (add_branch_option, add_fourbar_lengths, add_format_option, add_units_option, command_help,
                      finite, fourbar_lengths, number_list, whole)
from .output import print_rows

if TYPE_CHECKING:  # the symbolic side is imported when the options ask for dynamics (a plain table needs no SymPy)
    from ..dynamics.forward import EquationCode
    from ..dynamics.model import DynamicModel
    from ..numeric.cached_solver import CachedSolver
    from ..symbolic.linkage import Linkage

__all__ = ["MASS_COLUMNS", "FLYWHEEL_COLUMNS", "add_mass_options", "fourbar_dynamics", "fourbar_dynamics_solver",
           "fourbar_mass_options", "flywheel_code",
           "register"]

LINKS = ("crank", "coupler", "rocker")
ORIGINS = ("A", "B", "D")
#: The columns ``symlink fourbar`` adds with ``--masses``.
MASS_COLUMNS = ["input_torque", "joint_A_x", "joint_A_y", "joint_B_x", "joint_B_y", "joint_C_x", "joint_C_y",
                "joint_D_x", "joint_D_y", "shaking_force_x", "shaking_force_y", "shaking_moment"]
#: Memory and time of ``symlink flywheel`` a sample, and its fixed time, measured (1.0 kB and 47 us a sample, 5 s,
#: at 20,000 and 200,000 samples on a shared machine) with a margin: see :mod:`.budget`.
FLYWHEEL_BYTES_PER_SAMPLE = 1500
FLYWHEEL_SECONDS_PER_SAMPLE = 1e-4
FLYWHEEL_SECONDS = 10.0
#: The csv header of ``symlink flywheel``.
FLYWHEEL_COLUMNS = ["mean_speed", "coefficient", "mean_torque", "energy_fluctuation", "flywheel_inertia",
                    "speed_max", "speed_min", "achieved_coefficient", "exact_flywheel_inertia"]


def _triple(what: str):
    def parse(text: str) -> list[float]:
        values = number_list(text)
        if len(values) != 3:
            raise argparse.ArgumentTypeError(f"expected {what} of the crank, coupler and rocker (three numbers), "
                                             f"got {text!r}")
        return values
    return parse


def _centres(text: str) -> list[tuple[float, float]]:
    items = [item.strip() for item in text.split(",")]
    if len(items) != 3:
        raise argparse.ArgumentTypeError(f"expected R:ANGLE for the crank, coupler and rocker (three of them), "
                                         f"got {text!r}")
    found = []
    for item in items:
        distance, colon, angle = item.partition(":")
        found.append((finite(distance), finite(angle) if colon else 0.0))
    return found


def _gravity(text: str) -> tuple[float, float | None]:
    values = number_list(text)
    if len(values) not in (1, 2):
        raise argparse.ArgumentTypeError(f"expected G or G,ANGLE, got {text!r}")
    return values[0], values[1] if len(values) == 2 else None


def add_mass_options(parser: argparse.ArgumentParser,
                     title: str = "dynamics (adds the columns " + ",".join(MASS_COLUMNS) + ")") -> None:
    """``--masses --inertias --centres --gravity --load-torque`` (see the module docstring), under ``title``."""
    group = parser.add_argument_group(title)
    group.add_argument("--masses", type=_triple("masses"), metavar="M2,M3,M4", help="masses of crank, coupler, rocker")
    group.add_argument("--inertias", type=_triple("inertias"), metavar="I2,I3,I4",
                       help="moments of inertia about the centres of mass (default 0)")
    group.add_argument("--centres", type=_centres, metavar="R2:ANG2,R3:ANG3,R4:ANG4",
                       help="centres of mass: distance from A along AB, from B along BC, from D along DC, and an "
                            "angle from that line (in --units; default 0); default the link's midpoint")
    group.add_argument("--gravity", type=_gravity, metavar="G[,ANGLE]",
                       help="gravity of size G pointing at ANGLE (in --units, default -90 deg: down)")
    group.add_argument("--load-torque", type=finite, metavar="T", help="torque on the crank shaft, ccw positive")


def fourbar_dynamics(args: argparse.Namespace,
                     lengths: tuple[float, float, float, float]) -> tuple[Linkage, list[str]] | None:
    """The four-bar with the mass properties of ``args`` (its dynamic linkage) and the added columns; without
    ``--masses``, None (the plain table, from the disk cache without SymPy).  ``ValueError`` for dynamics
    options without ``--masses``."""
    if not _dynamics_asked(args):
        return None
    from ..dynamics.inverse import dynamic_linkage
    return dynamic_linkage(fourbar_model(args, lengths)), list(MASS_COLUMNS)


#: The options of a four-bar's dynamics beside ``--masses`` (their ``argparse`` names), which need it.
MASS_OPTIONS = ("inertias", "centres", "gravity", "load_torque")


def dynamics_options_given(args: argparse.Namespace) -> list[str]:
    """The four-bar's dynamics options ``args`` give, as written on the command line (``--masses`` first)."""
    return [f"--{name.replace('_', '-')}" for name in ("masses", *MASS_OPTIONS) if getattr(args, name, None) is not None]


def _dynamics_asked(args: argparse.Namespace) -> bool:
    """Whether ``args`` ask for the four-bar's dynamics (``--masses``); ``ValueError`` for dynamics options
    without it."""
    if args.masses is None:
        given = [name for name in MASS_OPTIONS if getattr(args, name) is not None]
        if given:
            raise ValueError(f"--{given[0].replace('_', '-')} needs --masses (the masses of crank, coupler, rocker)")
        return False
    return True


def fourbar_mass_options(args: argparse.Namespace, lengths: tuple[float, float, float, float]) -> dict | None:
    """The dynamics options of ``args`` as plain numbers (what the dynamic model of the four-bar of ``lengths`` is
    made of, and what keys its cache entries: no SymPy); None without ``--masses``, ``ValueError`` for dynamics
    options without it or values that cannot be."""
    return _mass_options(args, lengths) if _dynamics_asked(args) else None


def _mass_options(args: argparse.Namespace, lengths: tuple[float, float, float, float]) -> dict:
    """The dynamics options of ``args`` as plain numbers (angles in radians, defaults filled in), checked: what
    the dynamic model is made of, and the key of its cached table (no SymPy)."""
    if args.masses is None:
        raise ValueError("give the masses of crank, coupler and rocker: --masses M2,M3,M4")
    a, b, c, _ = lengths
    inertias = args.inertias or [0.0, 0.0, 0.0]
    centres = args.centres or [(a / 2, 0.0), (b / 2, 0.0), (c / 2, 0.0)]
    for what, values in (("--masses", args.masses), ("--inertias", inertias)):
        if any(value < 0 for value in values):
            raise ValueError(f"{what} must not be negative, got {','.join(f'{v:g}' for v in values)}")
    gravity = None
    if args.gravity is not None:
        size, angle = args.gravity
        direction = -math.pi / 2 if angle is None else float(to_radians(angle, args.units))
        gravity = [size * math.cos(direction), size * math.sin(direction)]
    return {"masses": [float(m) for m in args.masses], "inertias": [float(i) for i in inertias],
            "centres": [[float(distance), float(to_radians(angle, args.units))] for distance, angle in centres],
            "gravity": gravity, "load_torque": None if args.load_torque is None else float(args.load_torque)}


def fourbar_model(args: argparse.Namespace, lengths: tuple[float, float, float, float]) -> DynamicModel:
    """The dynamic model of the four-bar of ``lengths`` from the dynamics options of ``args`` (numbers only)."""
    from ..mechanism.catalog import fourbar
    from ..dynamics.model import BodyTorque, DynamicModel, Gravity, MassProperties
    options = _mass_options(args, lengths)
    masses = [MassProperties(link, mass, distance=distance, angle=angle, inertia=inertia, origin=origin)
              for link, mass, inertia, (distance, angle), origin in zip(LINKS, options["masses"], options["inertias"],
                                                                      options["centres"], ORIGINS)]
    gravity = None if options["gravity"] is None else Gravity(*options["gravity"])
    loads = [] if options["load_torque"] is None else [BodyTorque("crank", options["load_torque"])]
    return DynamicModel(fourbar(), masses, loads, gravity)


#: The kind of cache entry of ``symlink fourbar --masses``' table (:func:`fourbar_dynamics_solver`).
DYNAMICS_ENTRY_KIND = "fourbar-dynamics-table/1"


def fourbar_dynamics_solver(args: argparse.Namespace, lengths: tuple[float, float, float, float],
                            columns: list[str]) -> CachedSolver | None:
    """The solver of ``columns`` of the four-bar with the mass properties of ``args``, from the disk cache: keyed by
    the options' numbers, so that a warm request builds no model and imports no SymPy (derived on a miss).  None
    without ``--masses``; the lengths are checked first (by the generated check once cached)."""
    if not _dynamics_asked(args):
        return None
    from ..numeric.cache import catalog_key
    from ..numeric.cached_solver import CachedSolver
    options = _mass_options(args, lengths)
    named = dict(zip(("crank", "coupler", "rocker", "ground"), lengths))

    def derive() -> str:
        from ..dynamics.inverse import dynamic_linkage
        from ..numeric.cached_solver import entry_text
        from ..numeric.solver import check_lengths
        check_lengths(**named)  # before any model is made of them
        return entry_text(dynamic_linkage(fourbar_model(args, lengths)), columns)

    def full():
        from ..dynamics.inverse import dynamic_linkage
        from ..numeric.solver import Solver
        return Solver(dynamic_linkage(fourbar_model(args, lengths)), columns)

    key = catalog_key("fourbar", columns, DYNAMICS_ENTRY_KIND, {"lengths": [float(v) for v in lengths[:3]], **options},
                      ("cli/dynamics",))  # fourbar_model, here, builds the model from the options
    solver = CachedSolver("fourbar", columns, key=key, derive=derive, full=full)
    solver.check_lengths(**named)
    return solver


# --- symlink flywheel ---------------------------------------------------------------------

def _add_flywheel_options(command: argparse.ArgumentParser) -> None:
    add_fourbar_lengths(command)
    add_mass_options(command)
    speed = command.add_mutually_exclusive_group(required=True)
    speed.add_argument("--rpm", type=finite, metavar="N", help="mean crank speed in revolutions per minute")
    speed.add_argument("--rad-per-s", type=finite, metavar="W", help="mean crank speed in rad/s")
    command.add_argument("--coefficient", type=finite, required=True, metavar="CS",
                         help="coefficient of speed fluctuation (w_max - w_min) / w_mean, e.g. 0.02")
    command.add_argument("--samples", type=whole, default=720, metavar="N",
                         help="crank angles over the cycle (default 720)")
    add_time_budget_option(command)
    add_branch_option(command, both=False, default="+1")
    add_units_option(command, "angles of --centres and --gravity")
    add_format_option(command)
    command.set_defaults(run=run_flywheel)


#: The kinds of cache entry of ``symlink flywheel``'s code (:func:`flywheel_code`): the NumPy equation of motion and
#: driving torque, and the equation for one state that the integrator calls.
FLYWHEEL_ENTRY_KIND, FLYWHEEL_SCALAR_KIND = "flywheel-equations/1", "flywheel-scalar/1"


def flywheel_code(args: argparse.Namespace, lengths: tuple[float, float, float, float]) -> EquationCode:
    """The code that sizes the flywheel of the four-bar of ``lengths`` with the mass properties of ``args``, from the
    disk cache: keyed by the options' numbers (as :func:`fourbar_dynamics_solver`'s table), so that a warm run builds
    no model and imports no SymPy (derived on a miss).  ``ValueError`` without ``--masses`` or for bad values."""
    from ..dynamics.forward import equation_code
    from ..numeric.cache import catalog_key
    options = _mass_options(args, lengths)
    named = {"lengths": [float(v) for v in lengths[:3]], **options}
    outputs = ["input_torque"]
    links = dict(zip(("crank", "coupler", "rocker", "ground"), lengths))

    def model() -> DynamicModel:
        from ..numeric.solver import check_lengths
        check_lengths(**links)  # before any model is made of them
        return fourbar_model(args, lengths)

    code = equation_code(catalog_key("fourbar", outputs, FLYWHEEL_ENTRY_KIND, named, ("cli/dynamics",)),
                         catalog_key("fourbar", outputs, FLYWHEEL_SCALAR_KIND, named, ("cli/dynamics",)), model)
    code.check(True, tuple(links), tuple(links.values()), tuple(links))  # the ground is not in the key
    return code


def run_flywheel(args: argparse.Namespace) -> int:
    """``symlink flywheel``: the flywheel of a four-bar with mass properties, as one record."""
    from ..dynamics.flywheel import FlywheelSizing, rpm_to_rad_per_s
    lengths = fourbar_lengths(args)
    speed = rpm_to_rad_per_s(args.rpm) if args.rpm is not None else args.rad_per_s
    if not speed > 0:
        raise ValueError(f"the mean speed must be positive, got {args.rpm if args.rpm is not None else speed:g}")
    if args.masses is not None and not any(args.masses) and not any(args.inertias or []):
        raise ValueError(f"--masses {','.join(f'{m:g}' for m in args.masses)} with no --inertias: the four-bar has "
                         "no mass to size a flywheel for (give the crank, coupler or rocker a mass)")
    require_budget(args.samples, FLYWHEEL_BYTES_PER_SAMPLE, FLYWHEEL_SECONDS_PER_SAMPLE,
                   f"a flywheel of --samples {args.samples}", "--samples", fixed_seconds=FLYWHEEL_SECONDS)
    code = flywheel_code(args, lengths)  # the lengths checked there, from the disk cache without SymPy
    values = dict(zip("abcd", lengths))
    try:
        sizing = FlywheelSizing(code, values, speed, args.coefficient, int(args.branch), args.samples)
        band = sizing.speed_band()
        exact = sizing.exact_inertia()
    except ImportError as error:  # SciPy, the extra 'dynamics'
        raise ValueError(str(error)) from None
    row = {"mean_speed": speed, "coefficient": args.coefficient, "mean_torque": sizing.mean_torque,
           "energy_fluctuation": sizing.energy_fluctuation, "flywheel_inertia": sizing.inertia,
           "speed_max": band.highest, "speed_min": band.lowest, "achieved_coefficient": band.coefficient,
           "exact_flywheel_inertia": exact}
    print_rows([row], FLYWHEEL_COLUMNS, args.format)
    return 0


def register(commands: argparse._SubParsersAction) -> None:
    """Register ``symlink flywheel`` (the four-bar's mass columns hook into ``symlink fourbar``)."""
    commands.add_parser("flywheel", populate=_add_flywheel_options, **command_help(
        "flywheel for a four-bar with masses: mean torque, energy fluctuation, inertia, speed band",
        "lengths, masses and inertias in consistent units (m, kg, kg m^2: torques in N m, energy in J); "
        "speeds rad/s (--rpm converts); angles of --centres and --gravity in --units",
        "symlink flywheel --crank 0.2 --coupler 0.66 --rocker 0.56 --ground 0.8 --masses 1,2,1.5 "
        "--inertias 0.03,0.07,0.04 --gravity 9.81 --load-torque -15 --rpm 300 --coefficient 0.05",
        "The textbook flywheel_inertia = energy_fluctuation / (coefficient * mean_speed^2) is the whole inertia on "
        "the crank shaft, the linkage's own neglected; speed_max, speed_min and achieved_coefficient come from "
        "integrating the motion over one cycle with that flywheel on the crank and a motor holding the mean torque; "
        "exact_flywheel_inertia, added to the linkage, gives the coefficient exactly (by energy).\n\n"
        "csv header: " + ",".join(FLYWHEEL_COLUMNS)))
