"""Figures that show themselves in a notebook, with or without pyplot.

A :class:`matplotlib.figure.Figure` made without pyplot shows in Jupyter only
once pyplot's inline backend has been set up (``%matplotlib inline``, or any
``import matplotlib.pyplot``); before that a notebook prints
``<Figure size 640x480 with 1 Axes>``.  :class:`NotebookFigure` adds
``_repr_png_``, so the figures symlink returns display inline in any case,
and exactly once: where the inline backend is active, IPython's own printer
for figures takes precedence over ``_repr_png_``.  Nothing is registered with
pyplot, so no figure is kept alive or shown twice.

>>> figure = NotebookFigure(figsize=(2, 1))
>>> _ = figure.add_subplot().plot([0, 1], [0, 1])
>>> figure._repr_png_()[:8] == b"\\x89PNG\\r\\n\\x1a\\n"
True
"""
from __future__ import annotations

import io

from matplotlib.figure import Figure

__all__ = ["NotebookFigure"]


class NotebookFigure(Figure):
    """A Matplotlib figure that a notebook displays as a PNG (``_repr_png_``) without pyplot state."""

    def _repr_png_(self) -> bytes:
        buffer = io.BytesIO()
        self.savefig(buffer, format="png", bbox_inches="tight")
        return buffer.getvalue()
