"""Pictures of linkages with Matplotlib: drawings of any linkage, four-bar figures, animations, the view.

* :mod:`~symlink.plot.drawing`: the mechanism of any linkage at a pose, with
  the paths of chosen points (:func:`draw_linkage`);
* :mod:`~symlink.plot.figures`: the four-bar's angle, transmission and
  coupler-curve figures, the seed 000 loop, and :func:`save_figure`;
* :mod:`~symlink.plot.animation`: animations of any linkage (and of the
  four-bar from its four lengths) as GIF or MP4, or inline in a notebook
  (:func:`~symlink.plot.animation.inline_animation`);
* :mod:`~symlink.plot.view`: the interactive four-bar and any linkage
  (in Jupyter with ``%matplotlib widget``, the ``notebook`` extra);
* :mod:`~symlink.plot.inline`: figures that display inline in a notebook.

Every figure function takes the Matplotlib axes to draw on (``ax=``).

The figure functions are importable from here.  Matplotlib is imported only
when a drawing is made, so the ``symlink`` command starts fast.
"""
from .figures import (FIGURE_SUFFIXES, MechanismDrawing, angle_figure, check_coupler_point, coupler_curve_figure,
                      coupler_point_linkage, draw_loop, extent, figure_suffix, fourbar_positions, reachable_turn,
                      save_figure, transmission_figure, turn_angles)

__all__ = ["coupler_point_linkage", "fourbar_positions", "reachable_turn", "turn_angles",
           "check_coupler_point", "angle_figure", "transmission_figure", "coupler_curve_figure", "draw_loop",
           "MechanismDrawing", "extent", "save_figure", "figure_suffix", "FIGURE_SUFFIXES"]
