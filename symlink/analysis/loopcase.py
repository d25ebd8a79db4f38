"""The loop of the MATLAB GUI paper, ``z1 + z2 + z3 + z4 = 0``, with two of its eight values missing.

Each ``z_n = r_n e^{i t_n}``.  Leave out exactly two of ``r1..r4, t1..t4``: they become the
unknowns of a :class:`~symlink.symbolic.loops.Loop` of four :class:`~symlink.symbolic.vectors.Vector`, the
loop names its case (``"1"`` two lengths, ``"2a"`` length and angle of one vector,
``"2b"`` length and angle of different vectors, ``"3"`` two angles),
:func:`~symlink.symbolic.position.solve_loop` gives the closed form with its branch, and the
generated NumPy code (:class:`~symlink.numeric.solver.Solver`) evaluates it, for both branches
where the case has two.

Branches, in the order the solutions are listed: case 3, +1 then -1, where +1 turns the
first unknown vector (in the order r1..r4, t1..t4) counter-clockwise from the sum of the
two unknown vectors; case 2b, +1 (the larger unknown length) then -1.  A solution with a
negative length (a vector that would have to point backwards) is left out and noted; a
loop that cannot close raises ``ValueError`` saying why.

>>> from math import radians
>>> result = solve_case({"r1": 300, "t1": radians(270), "r2": 640.3124, "t2": radians(308.663),
...                      "t3": radians(180), "t4": radians(63.435)})
>>> result.case, [round(result.solutions[0][k], 4) for k in ("r3", "r4")]
('1', [800.0158, 894.4019])
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping


from . import wrap_angle
from ..common.display import record_html
from ..symbolic.linkage import Linkage
from ..symbolic.loops import CASE_NAMES, Loop
from ..numeric.solver import check_lengths, shared_solver
from ..symbolic.vectors import Vector, coordinates, lengths

__all__ = ["NAMES", "LoopCaseResult", "solve_case", "loop_linkage"]

#: The eight values of the loop, in the order that fixes which unknown is "first".
NAMES = ("r1", "r2", "r3", "r4", "t1", "t2", "t3", "t4")

#: Relative size (of the longest known length) below which a length is rounding, not negative.
ROUNDING = 1e-12


@dataclass(frozen=True)
class LoopCaseResult:
    """The solved loop: its case, the missing values and one dict of them per solution (radians).

    ``branches`` holds each solution's branch (+1 or -1; 0 where the case has one
    solution); ``notes`` say which solutions were left out and why.
    """

    _repr_html_ = record_html  # a notebook shows the fields as a table

    case: str
    missing: tuple[str, str]
    given: dict[str, float]
    solutions: tuple[dict[str, float], ...]
    branches: tuple[int, ...]
    notes: tuple[str, ...]

    @property
    def description(self) -> str:
        return CASE_NAMES[self.case]

    def values(self, index: int = 0) -> dict[str, float]:
        """All eight values of one solution (angles in radians), in the order of :data:`NAMES`."""
        merged = {**self.given, **self.solutions[index]}
        return {name: merged[name] for name in NAMES}


def loop_linkage(missing: tuple[str, str]) -> Linkage:
    """The loop ``z1 + z2 + z3 + z4 = 0`` as a linkage whose unknowns are the two ``missing`` values."""
    r, t = lengths("r1 r2 r3 r4"), coordinates("t1 t2 t3 t4")
    symbol = dict(zip(NAMES, r + t))
    z1, z2, z3, z4 = (Vector(r[k], t[k], f"z{k + 1}") for k in range(4))
    loop = Loop(z1 + z2 + z3 + z4, name="z1_z2_z3_z4")
    return Linkage("seed_000_loop", [loop], inputs=[], unknowns=[symbol[n] for n in missing],
                   parameters=[symbol[n] for n in NAMES if n not in missing])


def _check(values: Mapping[str, float | None]) -> tuple[dict[str, float], tuple[str, str]]:
    unknown = set(values) - set(NAMES)
    if unknown:
        raise ValueError(f"the loop has values {', '.join(NAMES)}; not {', '.join(sorted(unknown))}")
    given = {n: float(value) for n in NAMES if (value := values.get(n)) is not None}
    missing = tuple(n for n in NAMES if n not in given)
    if len(missing) != 2:
        listed = f" ({', '.join(missing)})" if missing else ""
        raise ValueError(f"exactly two of the eight values r1..r4, t1..t4 must be missing (the unknowns); "
                         f"{len(missing)} {'is' if len(missing) == 1 else 'are'} missing{listed}")
    check_lengths(**{n: v for n, v in given.items() if n.startswith("r")})
    for name, value in given.items():
        if not math.isfinite(value):
            raise ValueError(f"{name} must be finite, got {value}")
    return given, missing


def _known_sum(given: dict[str, float], missing: tuple[str, str]) -> complex:
    """W: what the two vectors with unknowns must add up to, ``-(sum of the known vectors)``."""
    owners = {name[1] for name in missing}
    return -sum(given[f"r{k}"] * complex(math.cos(given[f"t{k}"]), math.sin(given[f"t{k}"]))
                for k in "1234" if k not in owners)


def _why_not(case: str, given: dict[str, float], missing: tuple[str, str]) -> str:
    """Why a loop of this case cannot close with these values (a sentence)."""
    w = _known_sum(given, missing)
    if case == "3":
        p, q = (f"r{name[1]}" for name in missing)
        if abs(w) > given[p] + given[q]:
            return (f"z{p[1]} and z{q[1]} (lengths {given[p]:g} and {given[q]:g}) reach at most "
                    f"{given[p] + given[q]:g}, but the other two vectors leave a gap of {abs(w):.6g}")
        return (f"z{p[1]} and z{q[1]} (lengths {given[p]:g} and {given[q]:g}) differ by "
                f"{abs(given[p] - given[q]):g}, more than the gap of {abs(w):.6g} the other two vectors leave")
    length = next(n for n in missing if n.startswith("r"))
    angle = next(n for n in missing if n.startswith("t"))
    direction = given[f"t{length[1]}"]
    across = abs(w.imag * math.cos(direction) - w.real * math.sin(direction))
    return (f"z{angle[1]} (length {given[f'r{angle[1]}']:g}) cannot reach the line of z{length[1]}, which "
            f"passes {across:.6g} from the end of the other vectors")


def _parallel_lengths(given: dict[str, float], missing: tuple[str, str]) -> None:
    """Case 1 with the two unknown lengths along one line: ``ValueError``, saying which way it fails."""
    tp, tq = (given[f"t{name[1]}"] for name in missing)
    if abs(math.sin(tq - tp)) > 1e-12:
        return
    w = _known_sum(given, missing)
    across = abs(w.imag * math.cos(tp) - w.real * math.sin(tp))
    scale = max(given[n] for n in given if n.startswith("r"))
    p, q = (f"z{name[1]}" for name in missing)
    if across <= ROUNDING * scale:
        raise ValueError(f"{p} and {q} are parallel and the other vectors close along their line: "
                         f"any {missing[0]}, {missing[1]} with the right sum or difference closes the loop, "
                         "so the two lengths are not determined")
    raise ValueError(f"the loop cannot close: {p} and {q} are parallel, and the other vectors leave a gap of "
                     f"{across:.6g} across their line")


def solve_case(values: Mapping[str, float | None]) -> LoopCaseResult:
    """Solve ``z1 + z2 + z3 + z4 = 0`` for the two values missing from ``values`` (radians).

    ``values`` maps names of :data:`NAMES` to numbers; leave the two unknowns out (or
    give them as None).  Lengths must be positive.  ``ValueError`` for any other count of
    missing values, and for a loop that cannot close, saying why.

    Parameters
    ----------
    values : mapping of str to float or None
        Six of ``r1..r4, t1..t4`` (radians) by name; the two unknowns left out or None.

    Returns
    -------
    LoopCaseResult
        The case's name and its solutions, one a branch (a dict of all eight values each).

    Raises
    ------
    ValueError
        For other than two missing values, a length that is not positive, or a loop that cannot close.

    Examples
    --------
    >>> import math, symlink
    >>> result = symlink.solve_case(dict(r1=20, t1=0.0, r2=66, r3=56, r4=80, t4=math.pi))  # seed 003
    >>> result.case, [round(math.degrees(s["t3"]) + 180, 2) for s in result.solutions]  # the rocker: t3 + 180
    ('3', [110.74, 249.26])
    """
    given, missing = _check(values)
    solver = shared_solver(loop_linkage, missing, missing)
    case = solver.linkage.plan[0].case.name
    if case == "1":
        _parallel_lengths(given, missing)
    if case == "2a" and abs(_known_sum(given, missing)) <= ROUNDING * max(given[n] for n in given if n[0] == "r"):
        raise ValueError(f"the other three vectors close the loop already: z{missing[0][1]} would have no "
                         "length, and so no angle")
    signs = (1, -1) if case in ("2b", "3") else (0,)
    scale = max(v for n, v in given.items() if n.startswith("r"))
    solutions, branches, notes = [], [], []
    for sign in signs:
        result = solver(**given, **({"branch": sign} if sign else {}))
        if not bool(result["assembled"]):
            raise ValueError(f"the loop cannot close: {_why_not(case, given, missing)}")
        solution = {}
        for name in missing:
            value = float(result[name])
            if name.startswith("t"):
                value = wrap_angle(value)
            elif -ROUNDING * scale <= value < 0:
                value = 0.0
            solution[name] = value
        negative = [n for n in missing if n.startswith("r") and solution[n] < 0]
        if negative:
            name = negative[0]
            reason = f"{name} = {solution[name]:.6g} < 0 (z{name[1]} would have to point opposite to t{name[1]})"
            notes.append(f"branch {sign:+d} left out: {reason}" if sign else reason)
            continue
        solutions.append(solution)
        branches.append(sign)
    if not solutions:
        raise ValueError("the loop cannot close with positive lengths: " + "; ".join(notes))
    return LoopCaseResult(case, missing, given, tuple(solutions), tuple(branches), tuple(notes))
