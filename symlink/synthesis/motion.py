"""Motion generation (rigid-body guidance) by Burmester theory: four-bars whose coupler passes through given poses.

A pose is ``(x, y, angle)``: where the coupler's frame is (its origin, the guided point)
and how it is turned (radians, counter-clockwise).  A point with coordinates ``m`` in the
coupler's frame is at ``P_j + e^{i angle_j} m`` in pose j.  A four-bar that guides the
coupler through the poses is two *dyads*: a crank turning about a fixed pivot (the
*centre point*) whose tip is pinned to the coupler at a moving pivot (the *circle
point*): the moving pivot's positions in the poses lie on a circle about the centre.

* Two poses: the pole (the one point that is in the same place in both poses); any
  circle point has its centre anywhere on the perpendicular bisector of its two
  positions (:func:`two_pose_centre`, the free offset along the bisector exposed).
* Three poses: the pole triangle (:func:`pole_triangle`); a chosen circle point has its
  centre in closed form, the circumcentre of its three positions (:func:`centre_point`),
  and a chosen centre its circle point (:func:`circle_point`, the same construction in the
  coupler's frame: the kinematic inversion).
* Four poses: the circle points and centre points form two cubic curves.  They are
  sampled with the standard dyad equations in complex numbers (Sandor & Erdman,
  *Advanced Mechanism Design*, vol. 2, ch. 3):
  ``W (e^{i beta_j} - 1) + Z (e^{i alpha_j} - 1) = delta_j``, with W the crank (centre to
  circle point in pose 1), Z the coupler vector from the circle point to the guided
  point, ``alpha_j`` the coupler's and ``beta_j`` the crank's rotation from pose 1 to
  pose j, and ``delta_j = P_j - P_1``.  Three such equations in two unknowns W, Z are
  compatible when a determinant vanishes,
  ``C_1 + C_2 e^{i beta_2} + C_3 e^{i beta_3} + C_4 e^{i beta_4} = 0``, a closed
  quadrilateral: for each crank rotation ``beta_2`` (the free choice) it closes in at
  most two ways (:func:`four_pose_dyads`, :func:`burmester_curves`).
* Five poses: the Burmester points, the dyads on the curves of poses 1234 and 1235 alike
  (up to four real, :func:`burmester_points`).  Eliminating ``e^{i beta_4}`` and
  ``e^{i beta_5}`` with the equations and their conjugates (``|e^{i beta}| = 1``) leaves
  two quadratics in ``e^{i beta_3}``; their resultant is a polynomial of degree 7 in
  ``e^{i beta_2}`` whose roots on the unit circle hold the solutions.  Each candidate is
  polished by Newton's method on the real equations (the moving pivot's five positions
  equidistant from the centre) and kept if it solves them; duplicates and the spurious
  roots (the poles, ``e^{i beta_2} = 0``) are dropped.

Pairs of dyads make four-bars (:func:`fourbar_from_dyads`), each checked
(:class:`Design`): its Grashof class, the assembly branch at each pose (with the
generated four-bar solver: the sign that puts the rocker where the dyad has it), a
*branch defect* (the poses lie on different branches: no motion of the input reaches
them all without a toggle or taking the linkage apart) and an *order defect* (the input
does not visit the poses in order turning one way).  :func:`motion_generation` is the
front door: poses in, four-bars out.

>>> poses = [(0.0, 0.0, 0.0), (1.0, 0.5, 0.3), (1.6, 1.5, 0.7)]
>>> design = motion_generation(poses, moving_pivots=[(0.0, 0.0), (1.0, 0.0)])[0]
>>> design.grashof, design.branches, design.branch_defect, design.order_defect
('double-crank', (-1, -1, -1), False, False)
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy

from ..analysis import grashof
from ..common.angles import wrap_angle
from ..mechanism.catalog import fourbar
from ..common.display import record_html
from ..numeric.reachability import crank_range
from ..numeric.solver import settled, shared_solver

__all__ = ["Dyad", "Design", "check_poses", "pole", "pole_triangle", "two_pose_centre", "centre_point",
           "circle_point", "four_pose_dyads", "BurmesterCurves", "burmester_curves", "burmester_points",
           "fourbar_from_dyads", "motion_generation", "as_record", "MAX_LENGTH"]

_TOLERANCE = 1e-9        # relative residual for a solution of the dyad equations
_DISTINCT = 1e-7         # relative distance below which two dyads or points are one
#: Default largest distance of a Burmester dyad's pivots from pose 1, in units of the poses' spread.
MAX_LENGTH = 1e3


# --- poses -----------------------------------------------------------------------------

def check_poses(poses, least: int = 2, most: int = 5) -> numpy.ndarray:
    """The poses as an ``(n, 3)`` float array of ``(x, y, angle)``; ``ValueError`` naming what is wrong.

    >>> check_poses([(0, 0, 0), (1, 0, 0.5)]).shape
    (2, 3)
    """
    try:
        array = numpy.array(poses, dtype=float)
    except (TypeError, ValueError):
        raise ValueError("the poses must be rows of three numbers (x, y, angle)") from None
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"the poses must be rows of three numbers (x, y, angle), got shape {array.shape}")
    if not least <= len(array) <= most:
        wanted = f"{least}" if least == most else f"{least} to {most}"
        raise ValueError(f"this construction takes {wanted} poses, got {len(array)}")
    if not numpy.all(numpy.isfinite(array)):
        raise ValueError("the poses must be finite numbers")
    for j in range(len(array)):
        for k in range(j):
            if _same_pose(array[j], array[k]):
                raise ValueError(f"poses {k + 1} and {j + 1} are the same")
    return array


def _same_pose(first: numpy.ndarray, second: numpy.ndarray) -> bool:
    scale = max(1.0, float(numpy.abs(first[:2]).max()), float(numpy.abs(second[:2]).max()))
    return (abs(complex(*first[:2]) - complex(*second[:2])) <= 1e-12 * scale
            and abs(wrap_angle(first[2] - second[2])) <= 1e-12)


def _origins(poses: numpy.ndarray) -> numpy.ndarray:
    return poses[:, 0] + 1j * poses[:, 1]


def _place(poses: numpy.ndarray, local: complex) -> numpy.ndarray:
    """The positions (complex) of the coupler point with frame coordinates ``local`` in each pose."""
    return _origins(poses) + numpy.exp(1j * poses[:, 2]) * local


def _local(poses: numpy.ndarray, point: complex, index: int = 0) -> complex:
    """Frame coordinates of the coupler point that is at ``point`` (ground) in pose ``index``."""
    x, y, angle = poses[index]
    return complex((point - complex(x, y)) * numpy.exp(-1j * angle))


def _point(value, name: str) -> complex:
    array = numpy.asarray(value, dtype=float)
    if array.shape != (2,) or not numpy.all(numpy.isfinite(array)):
        raise ValueError(f"the {name} must be two finite coordinates (x, y), got {value!r}")
    return complex(array[0], array[1])


def _pair(value: complex) -> tuple[float, float]:
    return (float(value.real) + 0.0, float(value.imag) + 0.0)


def _scale(poses: numpy.ndarray) -> float:
    """A length typical of the problem: the largest distance of a pose's origin from the first (1 if none)."""
    spread = float(numpy.abs(_origins(poses) - _origins(poses)[0]).max())
    return spread if spread > 0 else 1.0


# --- dyads -------------------------------------------------------------------------------

@dataclass(frozen=True)
class Dyad:
    """A crank from a fixed pivot (centre point, ground frame) to a moving pivot on the coupler.

    ``moving`` is the moving pivot in the coupler's frame; :meth:`positions` places it in
    every pose (its first position is the circle point as drawn in pose 1).
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    fixed: tuple[float, float]
    moving: tuple[float, float]

    def positions(self, poses) -> numpy.ndarray:
        """The moving pivot in each pose, rows of (x, y)."""
        places = _place(check_poses(poses, 1, 10**6), complex(*self.moving))
        return numpy.stack([places.real, places.imag], axis=-1)

    def circle_point(self, poses) -> tuple[float, float]:
        """The moving pivot in pose 1 (ground frame)."""
        return tuple(float(v) for v in self.positions(poses)[0])  # type: ignore[return-value]

    def length(self, poses) -> float:
        """The crank's length: the moving pivot's distance from the fixed pivot in pose 1."""
        x, y = self.circle_point(poses)
        return math.hypot(x - self.fixed[0], y - self.fixed[1])

    def angles(self, poses) -> numpy.ndarray:
        """The crank's angle (ground frame, radians in (-pi, pi]) in each pose."""
        places = self.positions(poses)
        return numpy.arctan2(places[:, 1] - self.fixed[1], places[:, 0] - self.fixed[0])

    def radius_spread(self, poses) -> float:
        """The largest difference of the moving pivot's distances from the fixed pivot over the poses (0 ideally)."""
        places = self.positions(poses)
        radii = numpy.hypot(places[:, 0] - self.fixed[0], places[:, 1] - self.fixed[1])
        return float(radii.max() - radii.min())


def _dyad(poses: numpy.ndarray, fixed: complex, first_position: complex) -> Dyad:
    return Dyad(_pair(fixed), _pair(_local(poses, first_position)))


# --- two and three poses -------------------------------------------------------------

def pole(poses, first: int = 1, second: int = 2) -> tuple[float, float]:
    """The pole of the displacement from pose ``first`` to pose ``second`` (1-based): the point they share.

    ``ValueError`` when the two poses differ by a translation only (the pole is at infinity).

    >>> [round(v, 12) + 0.0 for v in pole([(1, 0, 0), (0, 1, math.pi / 2)])]
    [0.0, 0.0]
    """
    poses = check_poses(poses, 2, 10**6)
    j, k = _indices(poses, first, second)
    turn = numpy.exp(1j * poses[j, 2]) - numpy.exp(1j * poses[k, 2])
    if abs(turn) <= 1e-12:
        raise ValueError(f"poses {first} and {second} differ by a translation only: their pole is at infinity")
    local = (_origins(poses)[k] - _origins(poses)[j]) / turn
    return _pair(_origins(poses)[j] + numpy.exp(1j * poses[j, 2]) * local)


def _indices(poses: numpy.ndarray, *numbers: int) -> list[int]:
    for number in numbers:
        if not 1 <= number <= len(poses):
            raise ValueError(f"pose numbers run from 1 to {len(poses)}, got {number}")
    if len(set(numbers)) != len(numbers):
        raise ValueError(f"the pose numbers must differ, got {numbers}")
    return [number - 1 for number in numbers]


def pole_triangle(poses) -> tuple[tuple[float, float], tuple[float, float], tuple[float, float]]:
    """The poles P12, P13 and P23 of three poses.

    >>> poles = pole_triangle([(0, 0, 0), (2, 0, math.pi / 2), (1, 3, math.pi)])
    >>> [tuple(round(v, 12) + 0.0 for v in p) for p in poles]
    [(1.0, 1.0), (0.5, 1.5), (0.0, 1.0)]
    """
    poses = check_poses(poses, 3, 3)
    return pole(poses, 1, 2), pole(poses, 1, 3), pole(poses, 2, 3)


def two_pose_centre(poses, moving_pivot: tuple[float, float], offset: float) -> Dyad:
    """For two poses, the dyad with the moving pivot at ``moving_pivot`` in pose 1 and its centre ``offset`` along the bisector.

    The centre of any crank that carries the moving pivot from its first to its second
    position lies on the perpendicular bisector of the two; ``offset`` is the signed
    distance from their midpoint, positive to the left of the direction of travel.
    ``ValueError`` when the moving pivot is the pole (it does not move, any centre does).

    >>> two_pose_centre([(0, 0, 0), (2, 0, 0)], (0.0, 0.0), 1.0).fixed
    (1.0, 1.0)
    """
    poses = check_poses(poses, 2, 2)
    start = _point(moving_pivot, "moving pivot")
    local = _local(poses, start)
    first, second = _place(poses, local)
    travel = second - first
    if abs(travel) <= 1e-12 * _scale(poses):
        raise ValueError("the moving pivot is the pole of the two poses: it does not move, so any centre serves")
    if not math.isfinite(offset):
        raise ValueError(f"the offset along the bisector must be finite, got {offset}")
    centre = (first + second) / 2 + 1j * travel / abs(travel) * offset
    return Dyad(_pair(centre), _pair(local))


def _circumcentre(points: numpy.ndarray, what: str, scale: float) -> complex:
    """The centre of the circle through three points; ``ValueError`` where two coincide or all are in line.

    ``scale`` is a length typical of the problem: points closer than a 10^-12 of it (or of their distance
    from the origin) coincide, whatever their own spread (three places of a pole differ by rounding only).
    """
    a, b, c = points
    ab, ac = b - a, c - a
    cross = (ab.conjugate() * ac).imag
    sides = (abs(ab), abs(ac), abs(c - b))
    size = max(sides)
    if min(sides) <= 1e-12 * max(scale, float(numpy.abs(points).max())):
        raise ValueError(f"two of the three positions of the {what} coincide (it is the pole of two of the poses): "
                         "no one circle is fixed by them; choose another point")
    if abs(cross) <= 1e-12 * size * size:
        raise ValueError(f"the three positions of the {what} are in line: the circle through them has no centre "
                         "(the crank would be infinitely long: a slider)")
    return a - 1j * (abs(ab) ** 2 * ac - abs(ac) ** 2 * ab) / (2 * cross)


def centre_point(poses, moving_pivot: tuple[float, float]) -> Dyad:
    """For three poses, the dyad whose moving pivot is at ``moving_pivot`` in pose 1: centre = circumcentre of its positions.

    >>> poses = [(0, 0, 0), (1, 1, math.pi / 2), (0, 2, math.pi)]
    >>> [round(v, 12) + 0.0 for v in centre_point(poses, (0.0, 0.0)).fixed]
    [0.0, 1.0]
    """
    poses = check_poses(poses, 3, 3)
    local = _local(poses, _point(moving_pivot, "moving pivot"))
    return Dyad(_pair(_circumcentre(_place(poses, local), "moving pivot", _scale(poses))), _pair(local))


def circle_point(poses, fixed_pivot: tuple[float, float]) -> Dyad:
    """For three poses, the dyad with its fixed pivot at ``fixed_pivot``: the inverse of :func:`centre_point`.

    Seen from the coupler, the fixed pivot takes three positions; the moving pivot is
    their circumcentre (in the coupler's frame).

    >>> poses = [(0, 0, 0), (2, 0, math.pi / 2), (1, 3, math.pi)]
    >>> centre = centre_point(poses, (0.0, 0.0)).fixed
    >>> [round(v, 12) + 0.0 for v in circle_point(poses, centre).circle_point(poses)]
    [0.0, 0.0]
    """
    poses = check_poses(poses, 3, 3)
    fixed = _point(fixed_pivot, "fixed pivot")
    seen = (fixed - _origins(poses)) * numpy.exp(-1j * poses[:, 2])
    return Dyad(_pair(fixed), _pair(_circumcentre(seen, "fixed pivot (seen from the coupler)", _scale(poses))))


# --- four poses: the standard dyad equations ---------------------------------------------

class _Normalised:
    """The poses moved so that pose 1's origin is at 0 and scaled to a typical length of 1."""

    def __init__(self, poses: numpy.ndarray) -> None:
        self.poses = poses
        self.scale = _scale(poses)
        self.origin = _origins(poses)[0]
        self.delta = (_origins(poses) - self.origin) / self.scale      # delta_j, delta_1 = 0
        self.turn = numpy.exp(1j * (poses[:, 2] - poses[0, 2]))          # e^{i alpha_j}

    def cofactors(self, rows: Sequence[int]) -> numpy.ndarray:
        """C_1..C_4 of ``C_1 + sum_j C_j e^{i beta_j} = 0`` for the three poses ``rows`` (0-based, after pose 1)."""
        j, k, l = rows
        z, d = self.turn - 1, self.delta
        c2 = z[k] * d[l] - z[l] * d[k]
        c3 = -(z[j] * d[l] - z[l] * d[j])
        c4 = z[j] * d[k] - z[k] * d[j]
        return numpy.array([-(c2 + c3 + c4), c2, c3, c4])

    def dyad(self, rotations: numpy.ndarray, rows: Sequence[int]) -> tuple[complex, complex] | None:
        """W and Z (normalised) from the dyad equations of ``rows`` with crank rotations e^{i beta_j}; None if singular."""
        matrix = numpy.stack([rotations[list(rows)] - 1, self.turn[list(rows)] - 1], axis=-1)
        if numpy.linalg.matrix_rank(matrix, tol=1e-10) < 2:
            return None
        (w, z), *_ = numpy.linalg.lstsq(matrix, self.delta[list(rows)], rcond=None)
        return complex(w), complex(z)

    def ground(self, w: complex, z: complex) -> tuple[complex, complex]:
        """Fixed pivot and moving pivot (pose 1), in the ground frame, from normalised W and Z."""
        moving = -z * self.scale + self.origin
        return moving - w * self.scale, moving


def four_pose_dyads(poses, rotation: float) -> list[Dyad]:
    """For four poses, the (at most two) dyads whose crank turns ``rotation`` (radians) from pose 1 to pose 2.

    The compatibility condition ``C_1 + C_2 e^{i beta_2} + C_3 e^{i beta_3} + C_4 e^{i beta_4} = 0``
    with ``beta_2 = rotation`` closes as a triangle with sides ``|C_3|`` and ``|C_4|``
    in zero, one or two ways; each gives W and Z from the dyad equations.

    >>> poses = [(0, 0, 0), (1, 0.2, 0.3), (1.8, 0.9, 0.8), (2.2, 2.0, 1.4)]
    >>> [round(d.radius_spread(poses), 12) for d in four_pose_dyads(poses, 0.5)]
    [0.0, 0.0]
    """
    poses = check_poses(poses, 4, 4)
    if not math.isfinite(rotation):
        raise ValueError(f"the crank's rotation must be finite, got {rotation}")
    frame = _Normalised(poses)
    return [_dyad(poses, *frame.ground(w, z)) for w, z in _four_pose_solutions(frame, numpy.array([rotation]))[0]]


def _four_pose_solutions(frame: _Normalised, beta2: numpy.ndarray) -> list[list[tuple[complex, complex]]]:
    c1, c2, c3, c4 = frame.cofactors((1, 2, 3))
    found = []
    for angle in beta2:
        t2 = numpy.exp(1j * angle)
        target = -(c1 + c2 * t2)               # C_3 T_3 + C_4 T_4 = target
        length, r3, r4 = abs(target), abs(c3), abs(c4)
        solutions = []
        if length > 0 and r3 > 0 and r4 > 0:
            cosine = (length * length + r3 * r3 - r4 * r4) / (2 * length * r3)
            if abs(cosine) <= 1 + 1e-12:
                opening = math.acos(max(-1.0, min(1.0, cosine)))
                for sign in ((1,) if opening == 0 else (1, -1)):
                    t3 = target / length * r3 * numpy.exp(1j * sign * opening) / c3
                    t4 = (target - c3 * t3) / c4
                    rotations = numpy.array([1, t2, t3, t4])
                    dyad = frame.dyad(rotations, (1, 2, 3))
                    if dyad is not None:
                        solutions.append(dyad)
        found.append(solutions)
    return found


@dataclass(frozen=True)
class BurmesterCurves:
    """The sampled centre-point and circle-point curves of four poses (ground frame, circle points in pose 1).

    ``rotation`` is the crank's rotation beta_2 from pose 1 to pose 2 at each sample and
    ``assembly`` the way (0 or 1) the compatibility quadrilateral closed; NaN rows where
    it does not close.  Each of the two branches is a run of samples in ``rotation``.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    rotation: numpy.ndarray
    centre_points: numpy.ndarray      # (2, samples, 2): assembly, sample, (x, y)
    circle_points: numpy.ndarray      # (2, samples, 2)


def burmester_curves(poses, samples: int = 721) -> BurmesterCurves:
    """The centre-point and circle-point curves of four poses, sampled over the crank rotation beta_2.

    Parameters
    ----------
    poses : array_like
        Four poses, rows (x, y, angle in radians).
    samples : int, optional
        Samples of the crank rotation (default 721).

    Returns
    -------
    BurmesterCurves
        The centre-point and circle-point curves, each (branches, samples, 2).

    Examples
    --------
    >>> import math, symlink
    >>> poses = [(0, 0, 0), (1, 0.2, 0.3), (1.8, 0.9, 0.8), (2.2, 2.0, 1.4), (2.0, 3.0, 2.0)]
    >>> curves = symlink.burmester_curves(poses[:4], samples=13)
    >>> curves.centre_points.shape
    (2, 13, 2)
    """
    poses = check_poses(poses, 4, 4)
    if not isinstance(samples, int) or samples < 3:
        raise ValueError(f"the curves need at least 3 samples, got {samples!r}")
    frame = _Normalised(poses)
    # Rotations near 0 are skipped: beta_2 = 0 is the pole P12, where the equations give no W.
    beta2 = numpy.linspace(-math.pi, math.pi, samples)
    centres = numpy.full((2, samples, 2), numpy.nan)
    circles = numpy.full((2, samples, 2), numpy.nan)
    for i, solutions in enumerate(_four_pose_solutions(frame, beta2)):
        for way, (w, z) in enumerate(solutions):
            fixed, moving = frame.ground(w, z)
            centres[way, i] = fixed.real, fixed.imag
            circles[way, i] = moving.real, moving.imag
    return BurmesterCurves(beta2, centres, circles)


# --- five poses: the Burmester points -------------------------------------------------------

def _quadratic_in_t3(cofactors: numpy.ndarray) -> list[numpy.ndarray]:
    """Coefficients (ascending powers of T_2) of a, b, c in ``a T_3^2 + b T_3 + c = 0``.

    From ``C_1 + C_2 T_2 + C_3 T_3 + C_k T_k = 0`` and its conjugate (``conj T = 1/T``)
    with T_k eliminated, multiplied by ``T_2 T_3 (C_1 + C_2 T_2 + C_3 T_3)``.
    """
    c1, c2, c3, ck = cofactors
    poly = numpy.polynomial.polynomial
    big_l = numpy.array([numpy.conj(c2), numpy.conj(c1)])          # conj C2 + conj C1 T2
    big_k = numpy.array([0, numpy.conj(c3)])                        # conj C3 T2
    rest = numpy.array([c1, c2])                                    # C1 + C2 T2
    a = big_l * c3
    b = poly.polysub(poly.polyadd(poly.polymul(big_l, rest), big_k * c3), numpy.array([0, abs(ck) ** 2]))
    c = poly.polymul(big_k, rest)
    return [a, b, c]


def _newton(origins: numpy.ndarray, turns: numpy.ndarray, fixed: complex,
            moving: complex) -> tuple[complex, complex, float]:
    """Polish a dyad (normalised ground frame): the moving pivot's positions equidistant from the centre.

    Unknowns: the centre G and the moving pivot's frame coordinates m; equations
    ``|M_j - G|^2 - |M_1 - G|^2 = 0`` for j = 2..n, with ``M_j = origins_j + turns_j m``.
    Returns G, M_1 (pose 1 is unturned at the origin) and the relative residual.
    """
    x = numpy.array([fixed.real, fixed.imag, moving.real, moving.imag])

    def residual(x):
        g, m = complex(x[0], x[1]), complex(x[2], x[3])
        places = origins + turns * m
        radii = numpy.abs(places - g) ** 2
        return radii[1:] - radii[0], places, g

    for _ in range(30):
        values, places, g = residual(x)
        arm = places - g
        # d|M_j - G|^2 / dG = -2 (M_j - G); / dm = 2 R_j^T (M_j - G)
        rotated = arm * numpy.conj(turns)
        rows = numpy.stack([-2 * arm.real, -2 * arm.imag, 2 * rotated.real, 2 * rotated.imag], axis=-1)
        jacobian = rows[1:] - rows[0]
        step, *_ = numpy.linalg.lstsq(jacobian, -values, rcond=None)
        x = x + step
        if numpy.abs(step).max() <= 1e-15 * max(1.0, numpy.abs(x).max()):
            break
    values, places, g = residual(x)
    size = max(1.0, float(numpy.abs(places - g).max()) ** 2)
    return g, complex(x[2], x[3]), float(numpy.abs(values).max()) / size


def burmester_points(poses, max_length: float = MAX_LENGTH) -> list[Dyad]:
    """The dyads that guide the coupler through five poses (up to four real), sorted by fixed pivot.

    Solved with the compatibility polynomial (see the module's docstring) and polished by
    Newton's method; every dyad returned carries its moving pivot through the five
    poses on a circle about its fixed pivot to rounding.  The elimination singles out
    two poses (1 and 2 of the module's docstring); it is run with the three most
    distinct pairs of poses in those roles and the solutions pooled, so that two poses
    close together cannot hide a solution.  Dyads whose crank or fixed pivot lies more
    than ``max_length`` times the poses' spread away are left out: they are sliders in
    all but name, and their pivots are not determined to working precision.

    Parameters
    ----------
    poses : array_like
        Five poses, rows (x, y, angle in radians).
    max_length : float, optional
        Leave out dyads whose crank or pivot lie further than this times the poses' spread (default 1000).

    Returns
    -------
    list of Dyad
        Up to four dyads, sorted by fixed pivot.

    Examples
    --------
    >>> import math, symlink
    >>> poses = [(0, 0, 0), (1, 0.2, 0.3), (1.8, 0.9, 0.8), (2.2, 2.0, 1.4), (2.0, 3.0, 2.0)]
    >>> dyads = symlink.burmester_points(poses)
    >>> len(dyads), max(d.radius_spread(poses) for d in dyads) < 1e-12  # each moving pivot on a circle
    (4, True)
    """
    poses = check_poses(poses, 5, 5)
    if not max_length > 0:
        raise ValueError(f"the largest crank length (relative to the poses' spread) must be positive, got {max_length}")
    frame = _Normalised(poses)
    found: list[tuple[complex, complex]] = []
    for order in _orders(frame):
        reordered = _Normalised(poses[list(order)])
        for fixed, first_position in _candidates(reordered):
            # the candidate in the frame of the poses as given: fixed pivot and the moving pivot in pose 1
            moving = _local(poses[list(order)], first_position)
            g = (fixed - frame.origin) / frame.scale
            m = (_place(poses[:1], moving)[0] - frame.origin) / frame.scale
            g, m, error = _newton(frame.delta, frame.turn, g, m)   # pose 1 at the origin, unturned
            size = max(abs(g), abs(m))
            if not (error <= _TOLERANCE and abs(m - g) > 1e-9 and size <= max_length):
                continue
            if all(abs(g - g0) + abs(m - m0) > _DISTINCT * (1 + size) for g0, m0 in found):
                found.append((g, m))
    dyads = [_dyad(poses, g * frame.scale + frame.origin, m * frame.scale + frame.origin) for g, m in found]
    return sorted(dyads, key=lambda dyad: dyad.fixed)


def _orders(frame: _Normalised, count: int = 3) -> list[tuple[int, ...]]:
    """Orders of the poses for the elimination: the ``count`` most distinct pairs first (as poses 1 and 2)."""
    pairs = []
    for j in range(5):
        for k in range(j + 1, 5):
            distance = abs(frame.turn[j] - frame.turn[k]) + abs(frame.delta[j] - frame.delta[k])
            pairs.append((distance, j, k))
    pairs.sort(reverse=True)
    return [(j, k) + tuple(i for i in range(5) if i not in (j, k)) for _, j, k in pairs[:count]]


def _candidates(frame: _Normalised) -> list[tuple[complex, complex]]:
    """Rough solutions (fixed pivot, moving pivot in pose 1; ground frame) from the compatibility resultant."""
    first = _quadratic_in_t3(frame.cofactors((1, 2, 3)))
    second = _quadratic_in_t3(frame.cofactors((1, 2, 4)))
    a, b, c = first
    d, e, f = second
    poly = numpy.polynomial.polynomial
    af_cd = poly.polysub(poly.polymul(a, f), poly.polymul(c, d))
    ae_bd = poly.polysub(poly.polymul(a, e), poly.polymul(b, d))
    bf_ce = poly.polysub(poly.polymul(b, f), poly.polymul(c, e))
    resultant = poly.polysub(poly.polymul(af_cd, af_cd), poly.polymul(ae_bd, bf_ce))
    resultant = numpy.trim_zeros(resultant / numpy.abs(resultant).max(), "b")
    roots = poly.polyroots(resultant) if len(resultant) > 1 else numpy.array([])
    c_first, c_second = frame.cofactors((1, 2, 3)), frame.cofactors((1, 2, 4))
    found = []
    for t2 in roots:
        if not abs(abs(t2) - 1) <= 1e-3:
            continue
        t2 = t2 / abs(t2)
        for t3 in _common_roots(first, second, t2):
            t4 = -(c_first[0] + c_first[1] * t2 + c_first[2] * t3) / c_first[3]
            t5 = -(c_second[0] + c_second[1] * t2 + c_second[2] * t3) / c_second[3]
            rotations = numpy.array([1, t2, t3, t4, t5])
            if not numpy.all(numpy.abs(numpy.abs(rotations) - 1) <= 1e-3):
                continue
            dyad = frame.dyad(rotations / numpy.abs(rotations), (1, 2, 3, 4))
            if dyad is not None:
                found.append(frame.ground(*dyad))
    return found


def _common_roots(first: list[numpy.ndarray], second: list[numpy.ndarray], t2: complex) -> list[complex]:
    """The roots in T_3 of the first quadratic (at T_2 = t2) that also (nearly) solve the second."""
    poly = numpy.polynomial.polynomial
    one = [complex(poly.polyval(t2, coefficients)) for coefficients in first]
    two = [complex(poly.polyval(t2, coefficients)) for coefficients in second]
    candidates = numpy.roots(one) if abs(one[0]) > 0 else numpy.roots(one[1:])
    kept = []
    for t3 in candidates:
        size = sum(abs(v) * abs(t3) ** (2 - i) for i, v in enumerate(two)) or 1.0
        if abs(numpy.polyval(two, t3)) <= 1e-4 * size:
            kept.append(complex(t3))
    return kept


# --- four-bars from dyads ---------------------------------------------------------------------

@dataclass(frozen=True)
class Design:
    """A four-bar made of two dyads, in the conventions' terms, with its defects (lengths, radians).

    The crank dyad drives: crank pivot A, its moving pivot B; the rocker dyad: pivot D,
    moving pivot C (both moving pivots in pose 1, ground frame).  ``ground_angle`` is the
    direction of A->D; ``crank_angles`` the crank's angle theta at each pose measured
    from it (the four-bar's own frame), ``branches`` the assembly sign at each pose.  The
    guided point (the poses' origin) is at distance ``coupler_point_distance`` from B at
    angle ``coupler_point_angle`` from the coupler's direction B->C, and a pose's angle
    is the coupler's angle beta plus ``pose_angle_offset``.  ``order_direction`` is +1
    when the crank visits the poses turning counter-clockwise, -1 clockwise, 0 when no
    monotonic motion does (``order_defect``).  ``transmission_worst`` is the smallest of
    ``min(mu, 180 deg - mu)`` over the poses, ``pose_error`` the largest difference between
    the rocker angle the generated solver gives at a pose and the rocker dyad's own.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    crank_dyad: Dyad
    rocker_dyad: Dyad
    crank: float
    coupler: float
    rocker: float
    ground: float
    crank_pivot: tuple[float, float]
    rocker_pivot: tuple[float, float]
    crank_moving_pivot: tuple[float, float]
    rocker_moving_pivot: tuple[float, float]
    ground_angle: float
    coupler_point_distance: float
    coupler_point_angle: float
    pose_angle_offset: float
    crank_angles: tuple[float, ...]
    branches: tuple[int, ...]
    grashof: str
    branch_defect: bool
    order_defect: bool
    order_direction: int
    transmission_worst: float
    pose_error: float

    @property
    def defect_free(self) -> bool:
        return not (self.branch_defect or self.order_defect)


def fourbar_from_dyads(poses, crank_dyad: Dyad, rocker_dyad: Dyad) -> Design:
    """The four-bar driven by ``crank_dyad`` with ``rocker_dyad`` as its rocker, checked for defects.

    The branch at each pose is the sign with which the generated four-bar solver puts
    the rocker where the rocker dyad has it; ``ValueError`` when the two dyads share a
    pivot or the solver cannot reproduce a pose (the dyads do not guide the poses).
    """
    poses = check_poses(poses, 2, 10**6)
    a_pivot, d_pivot = complex(*crank_dyad.fixed), complex(*rocker_dyad.fixed)
    b_places = _place(poses, complex(*crank_dyad.moving))
    c_places = _place(poses, complex(*rocker_dyad.moving))
    scale = max(_scale(poses), abs(a_pivot - d_pivot), float(numpy.abs(b_places - a_pivot).max()))
    crank, rocker = float(abs(b_places[0] - a_pivot)), float(abs(c_places[0] - d_pivot))
    coupler, ground = float(abs(c_places[0] - b_places[0])), float(abs(d_pivot - a_pivot))
    if min(crank, rocker, coupler, ground) <= 1e-9 * scale:
        raise ValueError("the two dyads share a pivot (or one has no crank): they make no four-bar")
    ground_angle = math.atan2(d_pivot.imag - a_pivot.imag, d_pivot.real - a_pivot.real)
    frame = numpy.exp(-1j * ground_angle)
    theta = numpy.angle((b_places - a_pivot) * frame)
    phi = numpy.angle((c_places - d_pivot) * frame)
    solver = settled(shared_solver(fourbar, ("coupler", "rocker")))
    branches, error = [], 0.0
    for j in range(len(poses)):
        solved = solver(theta=numpy.array([theta[j], theta[j]]), a=crank, b=coupler, c=rocker, d=ground,
                        branch=numpy.array([1.0, -1.0]))
        misses = numpy.abs(numpy.angle(numpy.exp(1j * (solved["rocker"] - phi[j]))))
        misses = numpy.where(solved["assembled"], misses, numpy.inf)
        best = int(numpy.argmin(misses))
        branches.append(1 if best == 0 else -1)
        error = max(error, float(misses[best]))
    if not error <= 1e-6:
        raise ValueError("the four-bar of these dyads does not reach the poses (the dyads do not guide them)")
    origin = _origins(poses)[0]
    coupler_point = origin - b_places[0]
    kind = grashof(crank, coupler, rocker, ground).name
    direction = _order_direction(theta, crank_range(crank, coupler, rocker, ground))
    mu = numpy.abs(numpy.angle((b_places - c_places) / (d_pivot - c_places)))
    worst = float(numpy.minimum(mu, math.pi - mu).min())
    coupler_angle = float(numpy.angle(c_places[0] - b_places[0]))
    return Design(
        crank_dyad, rocker_dyad, crank, coupler, rocker, ground, _pair(a_pivot), _pair(d_pivot),
        _pair(b_places[0]), _pair(c_places[0]), ground_angle, float(abs(coupler_point)),
        wrap_angle(math.atan2(coupler_point.imag, coupler_point.real) - coupler_angle),
        wrap_angle(poses[0, 2] - coupler_angle), tuple(float(t) for t in theta), tuple(branches), kind,
        len(set(branches)) > 1, direction == 0, direction, worst, error)


def _order_direction(theta: numpy.ndarray, spans: list[tuple[float, float]]) -> int:
    """+1 (counter-clockwise) or -1 if the crank reaches the angles ``theta`` in order turning one way, else 0."""
    turn = 2 * math.pi
    if spans == [(-math.pi, math.pi)]:
        forward = numpy.mod(numpy.diff(theta), turn)
        if forward.sum() < turn - 1e-9:
            return 1
        backward = numpy.mod(-numpy.diff(theta), turn)
        return -1 if backward.sum() < turn - 1e-9 else 0
    tolerance = 1e-9
    for low, high in spans:
        inside = low + numpy.mod(theta - low, turn)
        if numpy.all(inside <= high + tolerance):
            steps = numpy.diff(inside)
            return 1 if numpy.all(steps > 0) else -1 if numpy.all(steps < 0) else 0
    return 0                                    # the poses lie on different arcs of the crank's range


# --- front door --------------------------------------------------------------------------------

def motion_generation(poses, *, moving_pivots: Sequence[tuple[float, float]] | None = None,
                      fixed_pivots: Sequence[tuple[float, float]] | None = None,
                      rotations: Sequence[float] | None = None,
                      offsets: Sequence[float] | None = None, defect_free: bool = False) -> list[Design]:
    """Four-bars that guide the coupler through the poses (rows of x, y, angle in radians).

    * 5 poses: the Burmester points; every pair of them, each dyad as crank once.
    * 4 poses: ``rotations``, the crank's rotation from pose 1 to pose 2 of each of the
      two dyads (the free choice on the curves; up to two dyads each).
    * 3 poses: two ``moving_pivots`` (in pose 1) or two ``fixed_pivots``.
    * 2 poses: two ``moving_pivots`` (in pose 1) and their ``offsets`` along the bisectors.

    With ``defect_free`` only designs without a branch or order defect are returned.
    Designs come sorted: defect-free first, then by the worst transmission angle at the
    poses, best first.  ``ValueError`` for bad poses or choices.

    Parameters
    ----------
    poses : array_like
        Two to five poses, rows (x, y, angle in radians).
    moving_pivots : sequence of (float, float), optional
        Two moving pivots in pose 1 (two or three poses).
    fixed_pivots : sequence of (float, float), optional
        Two fixed pivots (three poses).
    rotations : sequence of float, optional
        The crank's rotation from pose 1 to pose 2 of each dyad (four poses).
    offsets : sequence of float, optional
        The fixed pivots' offsets along the bisectors (two poses).
    defect_free : bool, optional
        Return only designs without a branch or order defect.

    Returns
    -------
    list of Design
        Defect-free first, then by the worst transmission angle at the poses.

    Raises
    ------
    ValueError
        For bad poses or choices.

    Examples
    --------
    >>> import math, symlink
    >>> poses = [(0, 0, 0), (1, 0.2, 0.3), (1.8, 0.9, 0.8), (2.2, 2.0, 1.4), (2.0, 3.0, 2.0)]
    >>> designs = symlink.motion_generation(poses)  # five poses: pairs of the Burmester points
    >>> len(designs), sum(design.defect_free for design in designs)
    (12, 3)
    """
    poses = check_poses(poses, 2, 5)
    count = len(poses)
    pairs: list[tuple[Dyad, Dyad]] = []
    if count == 5:
        _unused(moving_pivots=moving_pivots, fixed_pivots=fixed_pivots, rotations=rotations, offsets=offsets)
        dyads = burmester_points(poses)
        pairs = [(first, second) for first in dyads for second in dyads if first is not second]
    elif count == 4:
        _unused(moving_pivots=moving_pivots, fixed_pivots=fixed_pivots, offsets=offsets)
        first, second = _two(rotations, "rotations (the crank's rotation from pose 1 to pose 2 of each dyad)")
        pairs = [(one, two) for one in four_pose_dyads(poses, first) for two in four_pose_dyads(poses, second)]
    elif count == 3:
        _unused(rotations=rotations, offsets=offsets)
        if (moving_pivots is None) == (fixed_pivots is None):
            raise ValueError("three poses need either two moving pivots or two fixed pivots (the free choices)")
        if moving_pivots is not None:
            one, two = (centre_point(poses, p) for p in _two(moving_pivots, "moving pivots"))
        else:
            one, two = (circle_point(poses, p) for p in _two(fixed_pivots, "fixed pivots"))
        pairs = [(one, two)]
    else:
        _unused(fixed_pivots=fixed_pivots, rotations=rotations)
        pivots = _two(moving_pivots, "moving pivots (in pose 1)")
        shifts = _two(offsets, "offsets (of each centre along its bisector)")
        pairs = [(two_pose_centre(poses, pivots[0], shifts[0]), two_pose_centre(poses, pivots[1], shifts[1]))]
    designs = []
    for crank_dyad, rocker_dyad in pairs:
        try:
            designs.append(fourbar_from_dyads(poses, crank_dyad, rocker_dyad))
        except ValueError:
            continue                      # coincident pivots: no four-bar
    if defect_free:
        designs = [design for design in designs if design.defect_free]
    return sorted(designs, key=lambda design: (not design.defect_free, -design.transmission_worst))


def _unused(**choices) -> None:
    given = [name for name, value in choices.items() if value is not None]
    if given:
        raise ValueError(f"{', '.join(given)} cannot be chosen for this number of poses")


def _two(values, what: str) -> list:
    if values is None:
        raise ValueError(f"give two {what}")
    values = list(values)
    if len(values) != 2:
        raise ValueError(f"give two {what}, got {len(values)}")
    return values


def as_record(design: Design, units: str = "deg") -> dict:
    """The design as JSON-ready values (lengths in the poses' unit, angles in ``units``: deg or rad), one row."""
    if units not in ("deg", "rad"):
        raise ValueError(f"units must be deg or rad, got {units!r}")
    deg = math.degrees if units == "deg" else float
    record = {
        "crank": design.crank, "coupler": design.coupler, "rocker": design.rocker, "ground": design.ground,
        "crank_pivot_x": design.crank_pivot[0], "crank_pivot_y": design.crank_pivot[1],
        "rocker_pivot_x": design.rocker_pivot[0], "rocker_pivot_y": design.rocker_pivot[1],
        "crank_moving_x": design.crank_moving_pivot[0], "crank_moving_y": design.crank_moving_pivot[1],
        "rocker_moving_x": design.rocker_moving_pivot[0], "rocker_moving_y": design.rocker_moving_pivot[1],
        "ground_angle": deg(design.ground_angle),
        "coupler_point_distance": design.coupler_point_distance,
        "coupler_point_angle": deg(design.coupler_point_angle),
        "pose_angle_offset": deg(design.pose_angle_offset),
        "grashof": design.grashof,
        "branch_defect": design.branch_defect, "order_defect": design.order_defect,
        "order_direction": design.order_direction,
        "transmission_worst": deg(design.transmission_worst),
        "pose_error": deg(design.pose_error),
    }
    for j, (theta, branch) in enumerate(zip(design.crank_angles, design.branches), start=1):
        record[f"crank_angle_{j}"] = deg(theta)
        record[f"branch_{j}"] = branch
    return record
