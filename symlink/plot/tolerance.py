"""Pictures of a tolerance stack-up: the output's band along the cycle and the dimensions' contributions.

:func:`band_figure` draws, against the input, the output's nominal value (top) and its
deviations (bottom): the worst-case band (``± sum |dy/dp| band``, light), the statistical band
(mean shift ± 3 sigma, darker) and, given a Monte Carlo sample
(:func:`~symlink.workshop.sampled_builds.sample_builds`), the sampled 0.135 and 99.865 percentiles (the
3-sigma points of a normal) and the sampled mean as dots, so the linear prediction and the
sample are read side by side.  :func:`contribution_figure` is a bar chart of each dimension's
share of the output's variance where the statistical band is widest: the dimension to
tighten first is the longest bar.  :func:`tolerance_figure` puts the three panels on one
figure (what ``symlink tolerance ... --plot FILE`` writes).  :func:`distribution_figure` shows
the sampled deviation at one input value as a histogram beside the normal density that the
linear model predicts (mean shift, first-order sigma), with its worst-case and 3-sigma ends.

Angles (the input, an angular output and its deviations) are drawn in ``units`` (deg by
default) when the flags ``angular_input`` and ``angular_output`` say they are angles;
lengths in the linkage's own unit.  Matplotlib is imported only when a drawing is made.

>>> from symlink.mechanism.catalog import fourbar
>>> from symlink.workshop.tolerance import stack_up
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

from ..common.angles import wrap
from .figures import _given, _new_figure

if TYPE_CHECKING:  # Matplotlib is imported when a drawing is made
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from ..workshop.tolerance import StackUp

    from ..workshop.sampled_builds import SampledBuilds

__all__ = ["band_figure", "contribution_figure", "distribution_figure", "tolerance_figure", "SAMPLED_PERCENTILES"]

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

    ``result``: a :class:`~symlink.workshop.tolerance.StackUp` (its first input is the x axis); ``output``: which of
    its outputs (default: the first); ``sampled``: builds of the same output at the same input values, whose
    percentiles :data:`SAMPLED_PERCENTILES` and mean are drawn as dots.  ``axes``: two Matplotlib Axes (the
    nominal value, the deviations); default a new figure.  ``ValueError`` for an output the stack-up does not
    have or a sample taken elsewhere.

    Parameters
    ----------
    result : StackUp
        A tolerance stack-up (:func:`stack_up`); its first input is the x axis.
    output : str, optional
        Which of its outputs (default: the first).
    sampled : SampledBuilds, optional
        Builds of the same output at the same inputs (:func:`sample_builds`), drawn as percentiles.
    units : {"deg", "rad"}, optional
        The angles' unit (default degrees).
    angular_input, angular_output : bool, optional
        Whether the input and the output are angles (default True).
    axes : two Matplotlib Axes, optional
        Where to draw the nominal value and the deviations (default: a new figure).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Raises
    ------
    ValueError
        For an output the stack-up does not have, or a sample taken elsewhere.

    Examples
    --------
    >>> import numpy, symlink
    >>> design, bands = {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1}, {"a": 0.1, "b": 0.1}
    >>> result = symlink.stack_up(symlink.fourbar(), "rocker", design, bands, inputs={"theta": numpy.radians([0, 90])})
    >>> figure = symlink.band_figure(result)
    >>> [axes.get_ylabel() for axes in figure.axes]
    ['rocker (deg)', 'deviation of rocker (deg)']
    >>> round(float(figure.axes[0].lines[0].get_ydata()[0]), 2)  # the nominal rocker at theta = 0, seed 003
    110.74
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
    k = _widest(result, i)
    if not numpy.isfinite(shares[:, k]).all():
        raise ValueError(f"{name} has no variance where its band is widest: no dimension contributes")
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


def _widest(result: "StackUp", i: int) -> int:
    """The input index where output ``i``'s statistical band is widest (ValueError where it has none)."""
    width = numpy.where(numpy.isfinite(result.rss[i]), result.rss[i], -numpy.inf)
    if not numpy.isfinite(width).any():
        raise ValueError(f"{result.outputs[i]} has no statistical band anywhere on the range (never assembled)")
    return int(numpy.argmax(width))


def distribution_figure(result: "StackUp", sampled: "SampledBuilds", output: str | None = None,
                        at: int | None = None, *, bins: int = 80, units: str = "deg", angular_input: bool = True,
                        angular_output: bool = True, ax: "Axes | None" = None) -> "Figure":
    """The sampled deviation of ``output`` at input value number ``at`` (default: where its statistical band is
    widest) as a histogram of density, beside the linear prediction: the normal density of mean ``mean_shift``
    and standard deviation ``standard_deviation``, and the ends of the worst-case (dashed) and statistical
    (dotted) bands.  Where they part, the linear model no longer describes the builds.

    Parameters
    ----------
    result : StackUp
        A tolerance stack-up (:func:`stack_up`).
    sampled : SampledBuilds
        Builds of the same output at the same inputs (:func:`sample_builds`).
    output : str, optional
        Which output (default: the first).
    at : int, optional
        The input value's number (default: where the statistical band is widest).
    bins : int, optional
        The histogram's bins (default 80).
    units : {"deg", "rad"}, optional
        The angles' unit (default degrees).
    angular_input, angular_output : bool, optional
        Whether the input and the output are angles (default True).
    ax : Matplotlib Axes, optional
        Where to draw (default: a new figure's).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Examples
    --------
    >>> import symlink
    >>> design, bands = {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1}, {"a": 0.1, "b": 0.1}
    >>> result = symlink.stack_up(symlink.fourbar(), "rocker", design, bands, inputs={"theta": [0.5]})
    >>> builds = symlink.sample_builds(symlink.fourbar(), "rocker", design, bands, inputs={"theta": [0.5]},
    ...                                builds=2000)
    >>> symlink.distribution_figure(result, builds).axes[0].get_xlabel()
    'deviation of rocker (deg)'
    """
    name, i = _output(result, output)
    x_scale, y_scale = _scales(units, angular_input, angular_output)
    first, values = next(iter(result.inputs.items()))
    if name not in sampled.outputs or sampled.deviation.shape[2] != len(values) or not numpy.allclose(
            numpy.asarray(sampled.inputs[first], dtype=float), values, equal_nan=True):
        raise ValueError(f"the sampled builds are not of {name} at the stack-up's input values")
    k = _widest(result, i) if at is None else at
    if isinstance(k, bool) or not isinstance(k, (int, numpy.integer)) or not 0 <= k < len(values):
        raise ValueError(f"at must be the number of an input value, 0 to {len(values) - 1}, got {at!r}")
    if isinstance(bins, bool) or not isinstance(bins, int) or bins < 1:
        raise ValueError(f"bins must be a whole number >= 1, got {bins!r}")
    deviation = sampled.deviation[sampled.outputs.index(name), :, k] * y_scale
    built = deviation[numpy.isfinite(deviation)]
    figure, (axes,) = _new_figure(6.0, 3.8, given=_given(ax))
    if built.size:
        axes.hist(built, bins=bins, density=True, color="tab:red", alpha=0.45,
                  label=f"sampled ({built.size:,} builds)")
    shift, sigma = result.mean_shift[i, k] * y_scale, result.standard_deviation[i, k] * y_scale
    worst, rss = result.worst_case[i, k] * y_scale, result.rss[i, k] * y_scale
    if numpy.isfinite(sigma) and sigma > 0:
        x = numpy.linspace(min(-worst, shift - 4 * sigma), max(worst, shift + 4 * sigma), 400)
        axes.plot(x, numpy.exp(-0.5 * ((x - shift) / sigma) ** 2) / (math.sqrt(2 * math.pi) * sigma),
                  color="tab:blue", label="linear prediction (normal)")
        for end in (-worst, worst):
            axes.axvline(end, color="tab:blue", ls="--", lw=1)
        for end in (shift - rss, shift + rss):
            axes.axvline(end, color="tab:blue", ls=":", lw=1)
    unit = units if angular_output else "length"
    axes.set_xlabel(f"deviation of {name} ({unit})")
    axes.set_ylabel("density")
    axes.set_title(f"{name} at {first} = {float(values[k]) * x_scale:.4g}: worst case dashed, ± 3σ dotted",
                   fontsize="medium")
    axes.legend(loc="best", fontsize="small")
    axes.grid(True, alpha=0.4)
    return figure


def tolerance_figure(result: "StackUp", output: str | None = None, sampled: "SampledBuilds | None" = None, *,
                     units: str = "deg", angular_input: bool = True, angular_output: bool = True,
                     title: str | None = None) -> "Figure":
    """:func:`band_figure` and :func:`contribution_figure` on one new figure (three panels).

    Parameters
    ----------
    result : StackUp
        A tolerance stack-up (:func:`stack_up`); its first input is the x axis.
    output : str, optional
        Which of its outputs (default: the first).
    sampled : SampledBuilds, optional
        Builds of the same output at the same inputs (:func:`sample_builds`), drawn as percentiles.
    units : {"deg", "rad"}, optional
        The angles' unit (default degrees).
    angular_input, angular_output : bool, optional
        Whether the input and the output are angles (default True).
    title : str, optional
        The figure's title.

    Returns
    -------
    matplotlib.figure.Figure
        Three panels: the nominal value, the bands, the contributions.

    Examples
    --------
    >>> import numpy, symlink
    >>> design, bands = {"a": 20, "b": 66, "c": 56, "d": 80, "branch": 1}, {"a": 0.1, "b": 0.1}
    >>> result = symlink.stack_up(symlink.fourbar(), "rocker", design, bands, inputs={"theta": numpy.radians([0, 90])})
    >>> len(symlink.tolerance_figure(result).axes)
    3
    """
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
