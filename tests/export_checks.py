"""Shared helpers of the export tests (C, Octave, compiled): random arguments, closed-form catalog entries, comparisons."""
from __future__ import annotations

import numpy

from symlink.mechanism.catalog import CATALOG
from symlink.io.export import output_sets
from symlink.io.scene import angle_outputs, catalog_linkage


def closed_form_catalog() -> list[str]:
    """Catalog names that have a closed-form solve plan (the ones that can be exported)."""
    return [name for name in CATALOG if getattr(catalog_linkage(name), "has_closed_form", True)]


def export_sets(name: str) -> list[tuple[str, list[str], str]]:
    """The default output sets of an export, plus one set of every output the linkage has."""
    linkage = catalog_linkage(name)
    everything = [o for o in linkage.output_names() if o in _evaluable(linkage)]
    return output_sets(linkage) + [("everything", everything, "Every output.")]


def _evaluable(linkage) -> set[str]:
    names = set()
    for name in linkage.output_names():
        try:
            linkage.output(name)
        except ValueError:
            continue
        names.add(name)
    return names


def random_arguments(linkage, arguments, count: int, seed: int) -> dict[str, numpy.ndarray]:
    """Arrays of ``count`` random values for each argument name: angles, lengths, signed parameters, rates, branches."""
    rng = numpy.random.default_rng(seed)
    by_name = {s.name: s for s in linkage.call_signature()}
    values = {}
    for name in arguments:
        symbol = by_name[name]
        if symbol in linkage.branches:
            values[name] = rng.choice([-1.0, 1.0], count)
        elif symbol in linkage.inputs:
            values[name] = rng.uniform(-numpy.pi, numpy.pi, count)
        elif symbol.is_positive:
            values[name] = rng.uniform(0.5, 2.0, count)
        elif symbol in linkage.parameters:
            values[name] = rng.uniform(-0.5, 0.5, count)
        else:  # input rates and accelerations
            values[name] = rng.uniform(-3.0, 3.0, count)
    return values


def rounding_spread(function, values: dict, seed: int = 0) -> dict[str, numpy.ndarray]:
    """How far each output of ``function`` moves when every argument moves by a unit or two in the last place.

    This measures the conditioning of each output at each sample: two correct
    implementations whose sin, cos and atan2 differ by an ulp or two may
    differ by about this much (much more than 1e-12 relative near a toggle,
    where the rates and accelerations are ill-conditioned).  Branch signs stay.
    """
    rng = numpy.random.default_rng(seed)
    moved = {}
    for name, value in values.items():
        value = numpy.asarray(value, dtype=float)
        if name.startswith("branch"):
            moved[name] = value
        else:
            moved[name] = value * (1 + rng.choice([-1.0, 1.0], value.shape) * 2.0**-51)
    with numpy.errstate(all="ignore"):
        base, shifted = function(**values), function(**moved)
        return {k: numpy.nan_to_num(numpy.abs(numpy.asarray(shifted[k], dtype=float) - numpy.asarray(base[k], dtype=float)))
                for k in base if k != "assembled"}


def assert_agree(actual: dict, expected: dict, angles: set[str], rtol: float, where: str = "",
                 spread: dict | None = None) -> None:
    """Same keys, same assembled mask and NaN pattern; values within ``rtol`` of each output's scale.

    Angles are compared modulo 2 pi (atan2 may return pi for one and -pi for the other).
    The scale of an output is the largest magnitude it takes over the sample.  Where
    ``spread`` (:func:`rounding_spread`) is given, a sample may also differ by 64 times its
    spread: the ill-conditioned samples near a toggle.
    """
    assert sorted(actual) == sorted(expected), where
    assert numpy.array_equal(numpy.asarray(actual["assembled"], dtype=bool),
                             numpy.asarray(expected["assembled"], dtype=bool)), where
    for key, want in expected.items():
        if key == "assembled":
            continue
        got, want = numpy.asarray(actual[key], dtype=float), numpy.asarray(want, dtype=float)
        assert got.shape == want.shape, (where, key)
        assert numpy.array_equal(numpy.isnan(got), numpy.isnan(want)), (where, key)
        finite = numpy.isfinite(want)
        if not finite.any():
            continue
        difference = numpy.abs(got[finite] - want[finite])
        if key in angles:
            difference = numpy.abs(numpy.angle(numpy.exp(1j * difference)))
        scale = max(numpy.max(numpy.abs(want[finite])), 1e-300)
        allowed = rtol * scale + (64 * numpy.broadcast_to(spread[key], want.shape)[finite] if spread else 0 * difference)
        worst = numpy.argmax(difference - allowed)
        assert difference[worst] <= allowed[worst], (
            f"{where} {key}: difference {difference[worst]:.3g} at a value of {want[finite][worst]:.6g} "
            f"(scale {scale:.3g}) exceeds {rtol:g} relative")


def angles_of(name: str, outputs) -> set[str]:
    return angle_outputs(catalog_linkage(name), list(outputs))


def atan2_angle_case():
    """``(program, arguments, expected)``: q = atan2(y, x) with cos q, sin q, cos t, sin t, sin(q - t) and cos(q - t).

    The arguments start with zeros of both signs (where atan2 picks the quadrant) and the axes; the expected
    values are NumPy's own calls.  For the printers' sines and cosines of solved angles (``angle_sums``).
    """
    import sympy as sp
    from symlink.symbolic.linkage import Program
    x, y, t, q = sp.symbols("x y t q", real=True)
    program = Program((x, y, t), ((q, sp.atan2(y, x)),),
                      {"q": q, "cos_q": sp.cos(q), "sin_q": sp.sin(q), "sin_t": sp.sin(t), "cos_t": sp.cos(t),
                       "sin_difference": sp.sin(q - t), "cos_difference": sp.cos(q - t)})
    rng = numpy.random.default_rng(5)
    xs = numpy.concatenate([[0.0, -0.0, 0.0, -0.0, 3.0, -3.0, 0.0, 0.0], rng.normal(size=200)])
    ys = numpy.concatenate([[0.0, 0.0, -0.0, -0.0, 0.0, -0.0, 2.0, -2.0], rng.normal(size=200)])
    ts = rng.uniform(-4, 4, size=xs.size)
    angle = numpy.arctan2(ys, xs)
    expected = {"q": angle, "cos_q": numpy.cos(angle), "sin_q": numpy.sin(angle), "sin_t": numpy.sin(ts),
                "cos_t": numpy.cos(ts), "sin_difference": numpy.sin(angle - ts), "cos_difference": numpy.cos(angle - ts)}
    return program, {"x": xs, "y": ys, "t": ts}, expected


def assert_atan2_angles(result: dict, expected: dict) -> None:
    """``result`` agrees with :func:`atan2_angle_case`'s expected values: a few ulps of 1, atan2's exact values at zero."""
    for key, want in expected.items():  # a few units in the last place of 1 (angle - ts itself rounds by 4e-16)
        numpy.testing.assert_allclose(result[key], want, rtol=0, atol=1.5e-15 if "difference" in key else 4.5e-16,
                                      err_msg=key)
    # where x = y = 0, atan2 picks 0 or pi by the sign of x, and the sine keeps y's signed zero
    numpy.testing.assert_array_equal(result["cos_q"][:8], [1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 0.0, 0.0])
    numpy.testing.assert_array_equal(result["sin_q"][:8], [0.0, 0.0, -0.0, -0.0, 0.0, -0.0, 1.0, -1.0])
    numpy.testing.assert_array_equal(numpy.signbit(result["sin_q"][:6]), numpy.signbit(expected["sin_q"][:6]))
