"""A one-input linkage as the general analysis sees it, from the disk cache: names and generated code, no SymPy.

:func:`symlink.analysis.analyze_linkage` needs of a linkage its names (inputs,
parameters and which are lengths, branch signs, unknowns and their rates, which
are angles), its solver of the unknowns and their rates, the margins of its
clamped roots (:mod:`symlink.numeric.reachability`), the joints of its two-angle
loops (:func:`symlink.analysis.transmission.joint_recipe`), an output and its
rate (:mod:`symlink.analysis.limits`) and its mobility.  Derived once with SymPy
(:func:`symlink.analysis.report.analysis_facts`), these are plain data and NumPy
modules in the disk cache; :class:`CachedLinkage` holds them, and the analysis
takes it wherever it takes a :class:`~symlink.symbolic.linkage.Linkage`, so that
``symlink analyze NAME|FILE`` run warm imports no SymPy.

>>> linkage = CachedLinkage({"name": "pendulum", "inputs": ["theta"], "parameters": ["a"], "positive": ["a"],
...                          "branches": [], "unknowns": [], "closed_form": True, "angles": ["theta"],
...                          "rates": {"theta": "thetadot"}, "joints": [], "roots": [],
...                          "mobility": {"links": 2, "revolute": 1, "prismatic": 0}},
...                         solver=None, margins=None, output=None)
>>> [p.name for p in linkage.parameters if p.is_positive], linkage.is_angle("theta")
(['a'], True)
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Mapping, Sequence

__all__ = ["CachedLinkage", "Named"]


@dataclass(frozen=True)
class Named:
    """A name of a cached linkage (an input, parameter, branch sign or unknown); ``is_positive`` for a length."""

    name: str
    is_positive: bool = False


class CachedLinkage:
    """What the general analysis needs of a one-input linkage with a closed form, from cached facts and code.

    ``facts``: plain data (:func:`symlink.analysis.report.analysis_facts`); ``solver(outputs)``: a solver of those
    outputs (a :class:`~symlink.numeric.cached_solver.CachedSolver`); ``margins()``: the generated margins function
    of its clamped roots; ``output(name)``: the generated function of an output and its rate, and whether the
    output is an angle.  Each callable reads the disk cache (deriving there once, with SymPy, where it is cold).
    """

    def __init__(self, facts: Mapping[str, Any], solver: Callable[[Sequence[str]], Any] | None,
                 margins: Callable[[], Callable[..., dict]] | None,
                 output: Callable[[str], tuple[Callable[..., dict], bool]] | None) -> None:
        positive = set(facts["positive"])
        self.name: str = facts["name"]
        self.inputs = [Named(name) for name in facts["inputs"]]
        self.parameters = [Named(name, name in positive) for name in facts["parameters"]]
        self.branches = [Named(name) for name in facts["branches"]]
        self.unknowns = [Named(name) for name in facts["unknowns"]]
        self.has_closed_form: bool = facts["closed_form"]
        self.angles = frozenset(facts["angles"])
        self.rates: dict[str, str] = dict(facts["rates"])
        self.joints: list[dict[str, Any]] = list(facts["joints"])
        self.roots: list[tuple[str, str]] = [(name, loop) for name, loop in facts["roots"]]
        self.mobility: dict[str, int] = dict(facts["mobility"])
        self._solver, self._margins, self._output = solver, margins, output

    def is_angle(self, name: str) -> bool:
        """Whether the input or parameter ``name`` is an angle."""
        return name in self.angles

    def solver(self, outputs: Sequence[str]) -> Any:
        """The solver of ``outputs`` (unknowns and rates by name)."""
        assert self._solver is not None
        return self._solver(outputs)

    def margins(self) -> tuple[Callable[..., dict], list[tuple[str, str]]]:
        """The generated function of the margins of the clamped roots, and each root's (margin name, loop)."""
        assert self._margins is not None
        return self._margins(), self.roots

    def output(self, name: str) -> tuple[Callable[..., dict], bool]:
        """The generated function of output ``name`` and its rate (from the coordinates and their rates), and
        whether it is an angle."""
        assert self._output is not None
        return self._output(name)
