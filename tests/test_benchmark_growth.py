"""The growth benchmark's arithmetic: the fitted exponent of a known power law, over the upper half of sizes."""
import math

import pytest

from benchmarks.growth import chain_by_joints, fitted_exponent, table


@pytest.mark.parametrize("power", [0.5, 1.0, 1.2, 2.0])
def test_the_fitted_exponent_of_a_power_law_is_its_power(power):
    rows = [{"n": n, "cost": 3.0 * n ** power} for n in (1, 2, 4, 8, 16, 32, 64)]
    assert fitted_exponent(rows, "cost") == pytest.approx(power, abs=1e-12)


def test_the_fit_reads_the_upper_half_where_fixed_costs_no_longer_hide_the_growth():
    # A fixed cost of 100 and a cost growing as n^2: the lower sizes are flat, the upper half follows n^2.
    rows = [{"n": n, "cost": 100.0 + n ** 2} for n in (1, 2, 4, 8, 16, 32, 64, 128)]
    upper = [(math.log(n), math.log(100.0 + n ** 2)) for n in (16, 32, 64, 128)]
    mx = sum(x for x, _ in upper) / 4
    my = sum(y for _, y in upper) / 4
    slope = sum((x - mx) * (y - my) for x, y in upper) / sum((x - mx) ** 2 for x, _ in upper)
    assert fitted_exponent(rows, "cost") == pytest.approx(slope, abs=1e-12)
    assert 1.7 < slope < 2.0


def test_the_table_ends_with_the_exponents_and_the_chain_is_a_one_freedom_linkage():
    text = table([{"n": n, "cost": float(n)} for n in (1, 2, 4, 8)], ["cost"], "n")
    assert text.splitlines()[-1] == "| exponent | 1.00 |"
    links, coordinates = chain_by_joints(5)
    assert len(links) == 2 + 2 * 5 and set(coordinates) == {j for js in links.values() for j in js}
    moving = len(links) - 1  # Gruebler: 3 (links - 1) - 2 pins, every pin joining two links
    pins = sum(len(js) for js in links.values()) - len(coordinates)
    assert 3 * moving - 2 * pins == 1
