"""Pictures of a tolerance stack-up: the output's band along the cycle and the dimensions' contributions.

:func:`band_figure` draws, against the input, the output's nominal value (top) and its
deviations (bottom): the worst-case band (``± sum |dy/dp| band``, light), the statistical band
(mean shift ± 3 sigma, darker) and, given a Monte Carlo sample
(:func:`~symlink.tolerance.sample_builds`), the sampled 0.135 and 99.865 percentiles (the
3-sigma points of a normal) and the sampled mean as dots, so the linear prediction and the
sample are read side by side.  :func:`contribution_figure` is a bar chart of each dimension's
share of the output's variance where the statistical band is widest: the dimension to
tighten first is the longest bar.  :func:`tolerance_figure` puts the three panels on one
figure (what ``symlink tolerance ... --plot FILE`` writes).

Angles (the input, an angular output and its deviations) are drawn in ``units`` (deg by
default) when the flags ``angular_input`` and ``angular_output`` say they are angles;
lengths in the linkage's own unit.  Matplotlib is imported only when a drawing is made.

>>> from symlink.catalog import fourbar
>>> from symlink.tolerance import stack_up
>>> result = stack_up(fourbar(), "rocker", {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1},
...                   {"a": 0.05, "b": 0.05, "c": 0.05, "d": 0.05})
>>> figure = tolerance_figure(result)
>>> [axes.get_ylabel() for axes in figure.axes[:2]], figure.axes[2].get_xlabel()
(['rocker (deg)', 'deviation of rocker (deg)'], 'share of the variance (%)')
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Sequence

import numpy

from ..angles import wrap
from .figures import _given, _new_figure

if TYPE_CHECKING:  # Matplotlib is imported when a drawing is made
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from ..tolerance import SampledBuilds, StackUp

__all__ = ["band_figure", "contribution_figure", "tolerance_figure", "SAMPLED_PERCENTILES"]

#: The percentiles of a sample drawn beside the linear bands: -3 and +3 sigma of a normal distribution.
SAMPLED_PERCENTILES = (0.135, 99.865)
_UNITS = ("deg", "rad")


def _output(result: "StackUp", output: str | None) -> tuple[str, int]:
    name = result.outputs[0] if output is None else output
    return name, result._index(name)  # ValueError naming the outputs there are


def _scales(units: str, angular_input: bool, angular_output: bool) -> tuple[float, float]:
    if units not in _UNITS:
        raise ValueError(f"units must be deg or rad, got {units!r}")
    turn = 180 / math.pi if units == "deg" else 1.0
    return (turn if angular_input else 1.0), (turn if angular_output else 1.0)


def band_figure(result: "StackUp", output: str | None = None, sampled: "SampledBuilds | None" = None, *,
                units: str = "deg", angular_input: bool = True, angular_output: bool = True,
                axes: "Sequence[Axes] | None" = None) -> "Figure":
    """The output's nominal value and its worst-case, statistical and sampled bands along the input.

    ``result``: a :class:`~symlink.tolerance.StackUp` (its first input is the x axis); ``output``: which of
    its outputs (default: the first); ``sampled``: builds of the same output at the same input values, whose
    percentiles :data:`SAMPLED_PERCENTILES` and mean are drawn as dots.  ``axes``: two Matplotlib Axes (the
    nominal value, the deviations); default a new figure.  ``ValueError`` for an output the stack-up does not
    have or a sample taken elsewhere.
    """
    name, i = _output(result, output)
    x_scale, y_scale = _scales(units, angular_input, angular_output)
    first, values = next(iter(result.inputs.items()))
    x = numpy.asarray(values, dtype=float) * x_scale
    figure, (top, bottom) = _new_figure(7.0, 6.0, rows=2, given=axes)
    nominal = (wrap(result.nominal[i]) if angular_output else result.nominal[i]) * y_scale
    top.plot(x, nominal, "-", color="black", label="nominal")
    worst, rss, shift = (result.worst_case[i] * y_scale, result.rss[i] * y_scale, result.mean_shift[i] * y_scale)
    bottom.fill_between(x, -worst, worst, color="tab:blue", alpha=0.18, lw=0, label="worst case (± Σ|∂y/∂p| band)")
    bottom.fill_between(x, shift - rss, shift + rss, color="tab:blue", alpha=0.45, lw=0,
                        label="statistical (mean shift ± 3σ)")
    bottom.axhline(0.0, color="black", lw=0.8, label="nominal")
    if sampled is not None:
        if name not in sampled.outputs or sampled.deviation.shape[2] != len(x) or not numpy.allclose(
                numpy.asarray(sampled.inputs[first], dtype=float), values, equal_nan=True):
            raise ValueError(f"the sampled builds are not of {name} at the stack-up's input values")
        j = sampled.outputs.index(name)
        low, high = sampled.percentile(list(SAMPLED_PERCENTILES))[:, j] * y_scale
        bottom.plot(x, low, "v", color="tab:red", ms=4,
                    label=f"sampled {SAMPLED_PERCENTILES[0]} / {SAMPLED_PERCENTILES[1]} % "
                          f"({sampled.deviation.shape[1]:,} builds)")
        bottom.plot(x, high, "^", color="tab:red", ms=4)
        bottom.plot(x, sampled.mean[j] * y_scale, ".", color="tab:red", ms=3, label="sampled mean")
    unit = units if angular_output else "length"
    top.set_ylabel(f"{name} ({unit})")
    bottom.set_ylabel(f"deviation of {name} ({unit})")
    bottom.set_xlabel(f"{first} ({units if angular_input else 'length'})")
    low_end, high_end = bottom.get_ylim()
    bottom.set_ylim(low_end, high_end + 0.8 * (high_end - low_end))  # room for the legend above the bands
    for panel in (top, bottom):
        panel.grid(True, alpha=0.4)
    top.legend(loc="best", fontsize="small")
    bottom.legend(loc="upper center", ncols=2, fontsize="x-small")
    return figure


def contribution_figure(result: "StackUp", output: str | None = None, *, ax: "Axes | None" = None,
                        units: str = "deg", angular_input: bool = True) -> "Figure":
    """Each dimension's share of the output's variance (percent) where its statistical band is widest, as bars,
    the largest on top: the ranking a designer acts on (tighten the top one, relax the bottom ones)."""
    name, i = _output(result, output)
    x_scale, _ = _scales(units, angular_input, False)
    figure, (axes,) = _new_figure(6.0, 3.5, given=_given(ax))
    shares = result.contributions[i]
    width = numpy.where(numpy.isfinite(result.rss[i]), result.rss[i], -numpy.inf)
    if not numpy.isfinite(width).any() or not numpy.isfinite(shares[:, int(numpy.argmax(width))]).all():
        raise ValueError(f"{name} has no statistical band anywhere on the range (never assembled, or no variance)")
    k = int(numpy.argmax(width))
    order = numpy.argsort(shares[:, k])
    axes.barh([result.dimensions[j] for j in order], 100 * shares[order, k], color="tab:blue")
    for row, j in enumerate(order):
        axes.annotate(f"{100 * shares[j, k]:.1f} %", (100 * shares[j, k], row), xytext=(3, 0),
                      textcoords="offset points", va="center", fontsize="small")
    first, values = next(iter(result.inputs.items()))
    axes.set_xlim(0, 110)
    axes.set_xlabel("share of the variance (%)")
    axes.set_title(f"contributions to {name} at {first} = {float(values[k]) * x_scale:.4g}, where its band is widest",
                   fontsize="medium")
    axes.grid(True, axis="x", alpha=0.4)
    return figure


def tolerance_figure(result: "StackUp", output: str | None = None, sampled: "SampledBuilds | None" = None, *,
                     units: str = "deg", angular_input: bool = True, angular_output: bool = True,
                     title: str | None = None) -> "Figure":
    """:func:`band_figure` and :func:`contribution_figure` on one new figure (three panels)."""
    from .inline import NotebookFigure
    name, _ = _output(result, output)
    figure = NotebookFigure(figsize=(7.0, 9.0), layout="constrained")
    top, middle, bottom = figure.subplots(3, 1, height_ratios=(1.0, 1.4, 1.0))
    middle.sharex(top)
    band_figure(result, name, sampled, units=units, angular_input=angular_input, angular_output=angular_output,
                axes=[top, middle])
    contribution_figure(result, name, ax=bottom, units=units, angular_input=angular_input)
    figure.suptitle(title if title is not None else f"tolerance stack-up of {name}")
    return figure
