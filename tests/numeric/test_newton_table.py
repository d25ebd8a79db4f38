"""The table of a linkage without a closed form (:mod:`symlink.numeric.newton_table`): the first start that gets
through the whole sweep, its columns by label; the first failure where none does; a sweep too large refused."""
import numpy
import pytest

from symlink.numeric.newton_table import newton_results

FACTS = {"name": "two", "inputs": ["theta"], "parameters": ["a"],
         "newton": {"unknowns": {"rocker": "phi"}, "outputs": {"rocker": "phi", "rocker_speed": "phidot"}}}
INPUTS = {"theta": numpy.array([0.0, 0.5, 1.0]), "thetadot": 2.0, "thetaddot": 0.0}


class StubSolver:
    """A Newton solver that gets through from a positive guess of phi only (then phi = guess + a theta), and
    fails, naming the guess, from any other; it keeps the guesses it was given."""

    def __init__(self, bytes_per_value=8):
        self.bytes_per_value, self.guesses = bytes_per_value, []

    def __call__(self, guess, theta, thetadot, thetaddot, a):
        self.guesses.append(guess["phi"])
        if guess["phi"] <= 0:
            raise ValueError(f"no assembly from phi = {guess['phi']}")
        return {"phi": guess["phi"] + a * theta, "phidot": a * thetadot + 0 * theta, "beta": 0 * theta,
                "assembled": theta == theta}


def test_the_first_start_that_gets_through_gives_the_columns_by_label():
    solver = StubSolver()
    results = newton_results(FACTS, lambda: solver, {"a": 3.0, "other": 1.0}, INPUTS, [{"phi": -1.0}, {"phi": 0.5},
                                                                                        {"phi": 2.0}])
    assert solver.guesses == [-1.0, 0.5]  # the third is never tried
    assert list(results) == [1] and list(results[1]) == ["rocker", "rocker_speed", "assembled"]
    assert results[1]["rocker"].tolist() == [0.5, 2.0, 3.5] and results[1]["rocker_speed"].tolist() == [6.0] * 3


@pytest.mark.parametrize("starts, message", [
    ([{"phi": -1.0}, {"phi": 0.0}], r"no assembly from phi = -1.0\Z"),  # the first failure, not the last
    ([], "two: no assembly to start Newton's method from"),
])
def test_no_start_that_gets_through_is_one_value_error(starts, message):
    with pytest.raises(ValueError, match=message):
        newton_results(FACTS, StubSolver, {"a": 3.0}, INPUTS, starts)


def test_a_sweep_too_large_for_memory_is_refused_with_the_advice_given():
    huge = StubSolver(bytes_per_value=1 << 62)
    with pytest.raises(ValueError, match=r"a table of 3 crank angles of two \(solved by Newton's method all at once\)"
                                         r" needs about .* use at most 1 crank angles \(fewer\)"):
        newton_results(FACTS, lambda: huge, {"a": 3.0}, INPUTS, [{"phi": 1.0}],
                       advice=lambda fits: f"use at most {fits:,} crank angles (fewer)")
    assert huge.guesses == []  # refused before Newton's method runs
