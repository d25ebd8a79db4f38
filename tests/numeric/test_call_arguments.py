"""Every solver names an unknown or a missing argument in a ValueError, never a raw TypeError."""
import numpy as np
import pytest

from symlink.numeric.cached_solver import CachedSolver
from symlink.numeric.call_arguments import check_argument_names, required_arguments
from symlink.mechanism.catalog import fourbar
from symlink.numeric.compiled import CompiledSolver, CompilerUnavailable
from symlink.numeric.solver import NumericSolver, Solver

GOOD = dict(theta=np.array([0.0, 0.5]), a=20.0, b=66.0, c=56.0, d=80.0, branch=1)


def compiled():
    try:
        return CompiledSolver(fourbar(), ["rocker"])
    except CompilerUnavailable as error:
        pytest.skip(f"no working C compiler, the compiled backend is not tested: {error}")


SOLVERS = {"numpy": lambda: Solver(fourbar(), ["rocker"]), "cached": lambda: CachedSolver("fourbar", ["rocker"]),
           "compiled": compiled}


@pytest.mark.parametrize("kind", SOLVERS)
@pytest.mark.parametrize("left_out", ["theta", "a", "d"])
def test_a_missing_argument_is_named(kind, left_out):
    solver = SOLVERS[kind]()
    values = {name: value for name, value in GOOD.items() if name != left_out}
    with pytest.raises(ValueError, match=rf"^fourbar needs {left_out} \(missing\); it takes theta, a, b, c, d, branch"):
        solver(**values)


@pytest.mark.parametrize("kind", SOLVERS)
def test_an_unknown_argument_is_named(kind):
    solver = SOLVERS[kind]()
    with pytest.raises(ValueError, match=r"^fourbar takes theta, a, b, c, d, branch; not crank, lenght"):
        solver(**GOOD, lenght=3.0, crank=1.0)


@pytest.mark.parametrize("kind", SOLVERS)
def test_the_rates_and_the_branch_may_be_left_out(kind):
    solver = SOLVERS[kind]()
    values = {name: value for name, value in GOOD.items() if name != "branch"}
    # theta = 0: the crank lies along the ground, the diagonal is d - a = 60; branch +1 by default
    gamma = np.arccos((56.0 ** 2 + 60.0 ** 2 - 66.0 ** 2) / (2 * 56.0 * 60.0))
    assert solver(**values)["rocker"][0] == pytest.approx(np.pi - gamma, rel=1e-12)


def test_the_numeric_solver_names_a_missing_guess_and_length():
    solver = NumericSolver(fourbar())
    with pytest.raises(ValueError, match=r"^fourbar needs guess \(missing\)"):
        solver(theta=[0.0], a=20, b=66, c=56, d=80)
    with pytest.raises(ValueError, match=r"^fourbar needs c \(missing\)"):
        solver(theta=[0.0], a=20, b=66, d=80, guess={"beta": 1.0, "phi": 2.0})
    with pytest.raises(ValueError, match=r"^fourbar takes .*; not gamma$"):
        solver(theta=[0.0], a=20, b=66, c=56, d=80, gamma=1.0, guess={"beta": 1.0, "phi": 2.0})


def test_unknown_names_come_before_missing_ones():
    with pytest.raises(ValueError, match="^s takes x, y; not z$"):
        check_argument_names("s", ["x", "y"], ["x", "y"], ["z"])


def test_required_arguments_are_those_without_defaults():
    def solve(theta, a, branch=1, thetadot=0.0, *, check=True):
        return theta
    assert required_arguments(solve) == ["theta", "a"]
