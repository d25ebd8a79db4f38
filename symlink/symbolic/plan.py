"""A readable solve plan: which loop is solved when, for what, and from which earlier results.

:attr:`symlink.symbolic.linkage.Linkage.plan` is the working plan (closed forms);
:func:`solve_plan` describes it for people: one :class:`PlanStep` a loop, with
its case, its two unknowns, the earlier results (inputs and unknowns solved by
earlier steps) that its equations use, and its branch sign.  Where no
closed-form order exists, the plan is one numeric step over all loops
(:mod:`symlink.codegen.newton`) and says why.  ``symlink plan NAME`` prints it for a
catalog entry.

>>> from symlink.mechanism.catalog import watt2
>>> print(solve_plan(watt2()))
watt2: closed form, loop by loop (inputs: theta)
  1. loop ABCD, case 3 (two angles): beta, phi from theta; branch sign branch_ABCD
  2. loop DEFG, case 3 (two angles): mu, psi from phi (step 1); branch sign branch_DEFG
"""
from __future__ import annotations

import html
from dataclasses import dataclass
from typing import TYPE_CHECKING

from .loops import CASE_NAMES
from ..common.notation import branch_html

if TYPE_CHECKING:
    from .linkage import Linkage

__all__ = ["PlanStep", "SolvePlan", "solve_plan"]

NUMERIC = "numeric"


@dataclass(frozen=True)
class PlanStep:
    """One step: ``loops`` solved for ``unknowns`` using earlier results ``uses`` (name -> step, 0 = input).

    ``case`` is a loop case of :mod:`symlink.symbolic.loops` (``"3"``) or ``"numeric"``;
    ``branch`` names the step's branch sign (None: one assembly, or numeric).
    """

    number: int
    loops: tuple[str, ...]
    case: str
    description: str
    unknowns: tuple[str, ...]
    uses: dict[str, int]
    branch: str | None

    def __str__(self) -> str:
        used = ", ".join(f"{name} (step {step})" if step else name for name, step in self.uses.items())
        branch = f"; branch sign {self.branch}" if self.branch else ""
        if self.case == NUMERIC:
            branch = "; the assembly is the one nearest the initial guess, continued along the inputs"
        loops = "loop " + self.loops[0] if len(self.loops) == 1 else "loops " + " and ".join(self.loops)
        return (f"{self.number}. {loops}, case {self.case} ({self.description}): "
                f"{', '.join(self.unknowns)} from {used or 'the parameters'}{branch}")


@dataclass(frozen=True)
class SolvePlan:
    """The steps of a linkage's solution; ``closed_form`` is False for the numeric fallback, ``note`` says why.

    Parameters
    ----------
    linkage : str
        The linkage's name.
    inputs : tuple of str
        Its inputs' names.
    closed_form : bool
        True when every step is a closed form, False for the numeric fallback.
    steps : tuple of PlanStep
        The steps in order.
    note : str
        One line on how it is solved (and, for the fallback, why).

    Examples
    --------
    >>> import symlink
    >>> plan = symlink.solve_plan(symlink.watt2())
    >>> plan.linkage, plan.inputs, plan.closed_form, len(plan.steps)
    ('watt2', ('theta',), True, 2)
    """

    linkage: str
    inputs: tuple[str, ...]
    closed_form: bool
    steps: tuple[PlanStep, ...]
    note: str

    def __str__(self) -> str:
        lines = [f"{self.linkage}: {self.note} (inputs: {', '.join(self.inputs)})"]
        lines += [f"  {step}" for step in self.steps]
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        """Jupyter's display: the note, then one table row a step, branch signs written as in the equations (σ).

        >>> from symlink.mechanism.catalog import fourbar
        >>> table = solve_plan(fourbar())._repr_html_()
        >>> "<td>ABCD</td>" in table, "σ" in table, "(argument branch)" in table
        (True, True, True)
        """
        def cell(text: str) -> str:
            return f"<td>{html.escape(text)}</td>"

        head = "".join(f"<th>{h}</th>" for h in ("step", "loops", "case", "unknowns", "from", "branch sign"))
        rows = []
        for step in self.steps:
            used = ", ".join(f"{name} (step {n})" if n else name for name, n in step.uses.items()) or "the parameters"
            sign = (f"<td>{branch_html(step.branch)} (argument {html.escape(step.branch)})</td>"
                    if step.branch else cell("none" if step.case != NUMERIC else "nearest the initial guess"))
            rows.append(f"<tr>{cell(str(step.number))}{cell(', '.join(step.loops))}"
                        f"{cell(f'{step.case} ({step.description})')}{cell(', '.join(step.unknowns))}"
                        f"{cell(used)}{sign}</tr>")
        caption = html.escape(f"{self.linkage}: {self.note} (inputs: {', '.join(self.inputs)})")
        return (f"<table><caption>{caption}</caption><tr>{head}</tr>" + "".join(rows) + "</table>")


def solve_plan(linkage: Linkage) -> SolvePlan:
    """Describe how ``linkage`` is solved: loop by loop in closed form, or all loops at once numerically.

    Parameters
    ----------
    linkage : Linkage
        The linkage to describe.

    Returns
    -------
    SolvePlan
        Its steps in order: the loops each solves, their case, the unknowns and what they use.

    Examples
    --------
    >>> import symlink
    >>> plan = symlink.solve_plan(symlink.stephenson2())
    >>> plan.closed_form, plan.steps[0].case, plan.steps[0].unknowns
    (False, 'numeric', ('beta', 'mu', 'phi', 'eta'))
    >>> plan = symlink.solve_plan(symlink.fourbar())
    >>> plan.closed_form, [step.case for step in plan.steps]
    (True, ['3'])
    """
    inputs = tuple(x.name for x in linkage.inputs)
    if not linkage.has_closed_form:
        counts = "; ".join(f"{loop.name}: {', '.join(u.name for u in loop.unknowns_among(linkage.unknowns))}"
                           for loop in linkage.loops)
        used = {x.name: 0 for x in linkage.inputs}
        step = PlanStep(1, tuple(loop.name for loop in linkage.loops), NUMERIC,
                        f"Newton's method on all {2 * len(linkage.loops)} closure equations",
                        tuple(u.name for u in linkage.unknowns), used, None)
        note = f"no closed form, every loop has more than two unknowns ({counts}); solved numerically"
        return SolvePlan(linkage.name, inputs, False, (step,), note)
    solved_in: dict = {x: 0 for x in linkage.inputs}
    place = {q: k for k, q in enumerate(linkage.coordinates)}  # a loop's earlier results in the coordinates' order
    steps = []
    for number, solution in enumerate(linkage.plan, start=1):
        present = sorted((q for q in solution.loop.symbols() if q in place and q in solved_in), key=place.__getitem__)
        uses = {q.name: solved_in[q] for q in present}
        steps.append(PlanStep(number, (solution.loop.name,), solution.case.name, CASE_NAMES[solution.case.name],
                              tuple(u.name for u in solution.positions), uses,
                              solution.branch.name if solution.branch is not None else None))
        solved_in.update({u: number for u in solution.positions})
    return SolvePlan(linkage.name, inputs, True, tuple(steps), "closed form, loop by loop")
