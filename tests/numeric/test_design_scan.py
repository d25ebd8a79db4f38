"""The scan of many designs' reach from the margins of their roots, NumPy only (symlink.numeric.design_scan): a
cache entry of a linkage's margins (symlink.numeric.reachability.margins_entry_text) scanned without the linkage,
against the slider-crank's hand formula, and the margins compiled or not giving the same spans."""
from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy
import pytest

from symlink.mechanism.catalog import slider_crank
from symlink.numeric.design_scan import fastest_margins, margin_spans
from symlink.numeric.reachability import MARGINS_DESCRIPTION, margins_entry_text

ROOT = Path(__file__).resolve().parent.parent.parent


def hand_spans(a: float, b: float, offset: float) -> list[tuple[float, float]]:
    """Where the rod reaches the guide: |offset - a sin(theta)| <= b bounds sin(theta) (both bounds inside)."""
    low, high = math.asin((offset - b) / a), math.asin((offset + b) / a)
    return [(low, high), (math.pi - high, math.pi - low)]


@pytest.mark.parametrize("compiled", [False, True])
def test_the_margins_of_a_cache_entry_scan_to_the_hand_spans(compiled):
    namespace: dict = {}
    exec(compile(margins_entry_text(slider_crank()), "<entry>", "exec"), namespace)
    described = namespace[MARGINS_DESCRIPTION]
    margins = namespace["margins"]
    if compiled:
        margins = fastest_margins(margins, lambda: described["c_margins"], described["lengths"], described["branches"])
        if not getattr(margins, "compiled", False):
            pytest.skip("no C compiler here")
    designs = {"a": numpy.array([2.0, 3.0, 0.5]), "b": numpy.array([1.0, 1.5, 1.0]), "offset": 0.5, "branch": 1.0}
    found = margin_spans(margins, [tuple(r) for r in described["roots"]], described["lengths"],
                         described["branches"], "theta", designs, 3, described["tolerance"])
    for spans, (a, b) in zip(found[:2], [(2.0, 1.0), (3.0, 1.5)]):
        assert len(spans) == 2
        for (low, high), (hand_low, hand_high) in zip(spans, hand_spans(a, b, 0.5)):
            assert low == pytest.approx(hand_low, abs=1e-12) and high == pytest.approx(hand_high, abs=1e-12)
    assert found[2] == [(-math.pi, math.pi)]  # a crank shorter than the rod less the offset turns fully


def test_a_bad_length_is_named():
    namespace: dict = {}
    exec(compile(margins_entry_text(slider_crank()), "<entry>", "exec"), namespace)
    described = namespace[MARGINS_DESCRIPTION]
    with pytest.raises(ValueError, match="a must be a positive finite length"):
        margin_spans(namespace["margins"], [tuple(r) for r in described["roots"]], described["lengths"],
                     described["branches"], "theta", {"a": -1.0, "b": 1.0, "offset": 0.0, "branch": 1.0}, 1,
                     described["tolerance"])


def test_it_imports_no_sympy():
    done = subprocess.run([sys.executable, "-c", "import sys, symlink.numeric.design_scan, symlink.numeric.cached_solver,"
                           " symlink.numeric.compiled_library; print('sympy' in sys.modules)"], capture_output=True,
                          text=True, check=True, env={"PYTHONPATH": str(ROOT), "PATH": ""})
    assert done.stdout.strip() == "False"
