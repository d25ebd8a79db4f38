"""The names a solver call takes: an unknown or a missing argument is a ``ValueError`` naming it.

Every solver (:class:`~symlink.numeric.solver.Solver` and its compiled subclass,
:class:`~symlink.numeric.solver.NumericSolver`, :class:`~symlink.numeric.cached_solver.CachedSolver`)
checks the names of its keyword arguments here, before any value is looked
at, so that a forgotten length or a misspelt input reads the same everywhere
and never surfaces as Python's ``TypeError`` from inside generated code.
NumPy only: the cached solver's fast path imports it without SymPy.

>>> check_argument_names("fourbar", ["theta", "a", "thetadot"], ["theta", "a"], {"theta": 0.0})
Traceback (most recent call last):
ValueError: fourbar needs a (missing); it takes theta, a, thetadot
"""
from __future__ import annotations

import inspect
from typing import Callable, Collection, Sequence

__all__ = ["check_argument_names", "required_arguments"]


def check_argument_names(solver: str, accepted: Sequence[str], required: Collection[str],
                         given: Collection[str]) -> None:
    """``ValueError`` naming the arguments of ``given`` that ``solver`` does not take, else those of
    ``required`` it lacks; ``accepted`` in calling order, for the message.

    >>> check_argument_names("fourbar", ["theta", "a"], ["theta", "a"], ["theta", "a", "alpha"])
    Traceback (most recent call last):
    ValueError: fourbar takes theta, a; not alpha
    >>> check_argument_names("fourbar", ["theta", "a"], ["theta", "a"], ["a", "theta"])  # all there: nothing
    """
    unknown = [name for name in given if name not in accepted]
    if unknown:
        raise ValueError(f"{solver} takes {', '.join(accepted)}; not {', '.join(sorted(unknown))}")
    missing = [name for name in accepted if name in required and name not in given]
    if missing:
        raise ValueError(f"{solver} needs {', '.join(missing)} (missing); it takes {', '.join(accepted)}")


def required_arguments(function: Callable[..., object]) -> list[str]:
    """The arguments of a (generated) function that have no default value, in order (not keyword-only ones).

    >>> def solve(theta, a, thetadot=0.0, *, check=True): ...
    >>> required_arguments(solve)
    ['theta', 'a']
    """
    return [name for name, parameter in inspect.signature(function).parameters.items()
            if parameter.default is parameter.empty
            and parameter.kind in (parameter.POSITIONAL_ONLY, parameter.POSITIONAL_OR_KEYWORD)]
