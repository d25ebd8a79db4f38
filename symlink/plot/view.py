"""``symlink view``: the four-bar as an interactive Matplotlib figure, the GUIs of the MATLAB papers.

Sliders set the four link lengths, the crank angle and the crank speed; a
radio button picks the branch.  The mechanism is redrawn and the angles,
rates and transmission angle shown as the sliders move.  Where the linkage
cannot close, the figure says so (and shows the reachable crank range)
instead of drawing anything made up; at a toggle the rates are undefined and
shown as such.

The views never call ``pyplot.show`` themselves: the ``symlink view``
command does.  In Jupyter they are interactive with ipympl (the ``notebook``
extra, ``pip install 'symlink-kinematics[notebook]'``): run
``%matplotlib widget`` first, then ``FourbarView()`` and the last figure of
the cell has working sliders.  With the inline backend a figure is a still
picture, so a view without a figure is refused there with that advice.

The view works on any Matplotlib figure, so it can be driven without a
display, as the tests do:

>>> from matplotlib.figure import Figure
>>> view = FourbarView(figure=Figure())
>>> view.sliders["angle"].set_val(90)
>>> print(view.text.get_text().splitlines()[0])
crank angle       θ =   90.000°
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy

from ..analysis import grashof
from ..codegen.arguments import check_lengths
from ..common.angles import wrap
from .figures import MechanismDrawing, TRANSMISSION_LIMITS, _catalog_solver, extent
from ..numeric.reachability import crank_range, describe_spans

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..numeric.poses import Placement
    from ..symbolic.linkage import Linkage

# The views take their solvers and placements from the disk cache (the catalog four-bar's solver entry; a linkage's
# Placement), so that a view whose code is cached imports no SymPy: ``symlink view --save`` run warm.

__all__ = ["FourbarView", "LinkageView", "SEED001", "OUTPUTS"]

#: The Maple worksheet's data, metres: the view's default linkage.
SEED001 = {"crank": 0.1, "coupler": 0.4, "rocker": 0.25, "ground": 0.30}
OUTPUTS = ["B_x", "B_y", "C_x", "C_y", "coupler", "rocker", "coupler_speed", "rocker_speed", "transmission"]
LENGTH_SLIDERS = (("crank", "crank a"), ("coupler", "coupler b"), ("rocker", "rocker c"), ("ground", "ground d"))
NON_INTERACTIVE = {"agg", "cairo", "pdf", "pgf", "ps", "svg", "template"}
#: A length slider spans the longest length divided by this to the longest times :data:`SLIDER_ABOVE`.
SLIDER_BELOW, SLIDER_ABOVE = 50.0, 2.5


def check_slider_range(crank: float, coupler: float, rocker: float, ground: float, crank_speed: float = 1.0) -> None:
    """``ValueError`` unless the lengths are positive and fit the sliders (which would clamp them silently).

    >>> check_slider_range(0.1, 0.4, 0.25, 0.3)
    >>> check_slider_range(0.001, 0.4, 0.25, 0.3)
    Traceback (most recent call last):
    ValueError: the view's length sliders span 1/50 of the longest length to 2.5 times it (0.008 to 1); crank 0.001 is outside: write a picture of the table instead, or scale the lengths
    """
    check_lengths(crank=crank, coupler=coupler, rocker=rocker, ground=ground)
    lengths = {"crank": crank, "coupler": coupler, "rocker": rocker, "ground": ground}
    top = max(lengths.values())
    low, high = top / SLIDER_BELOW, top * SLIDER_ABOVE
    for name, value in lengths.items():
        if not low <= value <= high:
            raise ValueError(f"the view's length sliders span 1/{SLIDER_BELOW:g} of the longest length to "
                             f"{SLIDER_ABOVE:g} times it ({low:g} to {high:g}); {name} {value:g} is outside: "
                             "write a picture of the table instead, or scale the lengths")
    if not math.isfinite(crank_speed) or abs(crank_speed) > 1e6:
        raise ValueError(f"the view's crank speed must be finite and at most 1e6 rad/s in size, got {crank_speed:g}")


def interactive_backend():
    """pyplot, where Matplotlib has an interactive backend; ``ValueError`` saying what to do otherwise."""
    import matplotlib.pyplot as pyplot
    backend = pyplot.get_backend().lower()
    if "inline" in backend:
        raise ValueError("Matplotlib draws still pictures in this notebook (the inline backend): run "
                         "%matplotlib widget first (pip install 'symlink-kinematics[notebook]' for ipympl), "
                         "or pass figure= to drive the view from code")
    if backend in NON_INTERACTIVE:
        raise ValueError(f"Matplotlib has no interactive backend here (it uses {backend!r}: no display?); "
                         "set MPLBACKEND to one (e.g. TkAgg, QtAgg), or write a picture with --save FILE.png")
    return pyplot


class FourbarView:
    """An interactive four-bar on a Matplotlib figure (sliders, branch buttons, drawing and readout).

    Lengths in any one unit; ``crank_angle`` in radians, ``crank_speed`` in
    rad/s, ``branch`` +1 or -1.  ``figure`` defaults to a new pyplot figure.
    ``sliders`` (``crank``, ``coupler``, ``rocker``, ``ground``, ``angle`` in
    degrees, ``speed``), ``branch_buttons`` and ``text`` are the widgets and
    the readout; :meth:`state` is what is shown, as numbers.

    Parameters
    ----------
    crank, coupler, rocker, ground : float, optional
        The lengths, in any one unit.
    crank_angle : float, optional
        The crank angle, radians (default 0).
    branch : int, optional
        The assembly, +1 (default) or -1.
    crank_speed : float, optional
        The crank's speed, rad/s (default 1).
    figure : matplotlib.figure.Figure, optional
        Where to draw (default: a new pyplot figure).

    Examples
    --------
    >>> import symlink
    >>> view = symlink.FourbarView(20, 66, 56, 80)
    >>> state = view.state()
    >>> round(state["rocker"], 6), round(state["C_x"], 3)  # seed 003 at theta = 0: C_x = 80 + 56 cos(110.74 deg)
    (1.932819, 60.167)
    """

    def __init__(self, crank: float = SEED001["crank"], coupler: float = SEED001["coupler"],
                 rocker: float = SEED001["rocker"], ground: float = SEED001["ground"], *,
                 crank_angle: float = 0.0, branch: int = 1, crank_speed: float = 1.0,
                 figure: "Figure | None" = None) -> None:
        from matplotlib.widgets import RadioButtons, Slider
        initial = {"crank": crank, "coupler": coupler, "rocker": rocker, "ground": ground}
        check_slider_range(crank, coupler, rocker, ground, crank_speed)
        self.solver = _catalog_solver(tuple(OUTPUTS))  # the catalog four-bar's cached solver (NumPy)
        self.solver(theta=crank_angle, a=crank, b=coupler, c=rocker, d=ground, branch=branch,
                    thetadot=crank_speed)  # validates everything with the solver's own messages
        if figure is None:
            import matplotlib.pyplot as pyplot
            figure = pyplot.figure(figsize=(10, 6.5))
        self.figure = figure
        self.axes = figure.add_axes((0.06, 0.40, 0.56, 0.56))
        self.axes.set_aspect("equal", adjustable="box")
        self.axes.grid(True, alpha=0.3)
        self.drawing = MechanismDrawing(self.axes)
        panel = figure.add_axes((0.65, 0.50, 0.34, 0.46))
        panel.set_axis_off()
        self.text = panel.text(0.0, 1.0, "", va="top", ha="left", family="monospace", fontsize=9,
                               transform=panel.transAxes)
        top = max(initial.values())
        self.sliders: dict[str, Slider] = {}
        rows = [(name, label, top / SLIDER_BELOW, top * SLIDER_ABOVE, initial[name], "%.4g")
                for name, label in LENGTH_SLIDERS]
        rows.append(("angle", "crank θ (deg)", 0.0, 360.0, float(numpy.mod(math.degrees(crank_angle), 360)),
                     "%.1f"))
        speed_range = max(10.0, 2 * abs(crank_speed))
        rows.append(("speed", "crank ω (rad/s)", -speed_range, speed_range, crank_speed, "%.3g"))
        for row, (name, label, low, high, value, fmt) in enumerate(rows):
            slider_axes = figure.add_axes((0.18, 0.30 - row * 0.05, 0.45, 0.03))
            self.sliders[name] = Slider(slider_axes, label, low, high, valinit=value, valfmt=fmt)
            self.sliders[name].on_changed(self.update)
        button_axes = figure.add_axes((0.72, 0.12, 0.14, 0.16))
        button_axes.set_title("branch", fontsize="small")
        self.branch_buttons = RadioButtons(button_axes, ("+1", "-1"), active=0 if branch == 1 else 1)
        self.branch_buttons.on_clicked(self.update)
        self.update()

    def values(self) -> dict[str, float]:
        """The inputs as set: lengths, ``theta`` (rad), ``thetadot`` (rad/s) and ``branch``."""
        values = {name: float(self.sliders[name].val) for name, _ in LENGTH_SLIDERS}
        values["theta"] = math.radians(float(self.sliders["angle"].val))
        values["thetadot"] = float(self.sliders["speed"].val)
        values["branch"] = int(self.branch_buttons.value_selected)
        return values

    def state(self) -> dict[str, float | bool]:
        """What the view shows: ``assembled`` and the solver's outputs (radians, rad/s, lengths)."""
        v = self.values()
        result = self.solver(theta=v["theta"], a=v["crank"], b=v["coupler"], c=v["rocker"], d=v["ground"],
                             branch=v["branch"], thetadot=v["thetadot"])
        state = {name: float(result[name]) for name in OUTPUTS}
        state["assembled"] = bool(result["assembled"])
        return state

    def update(self, _changed=None) -> None:
        """Redraw the mechanism and the readout from the widgets (every widget calls this)."""
        v, state = self.values(), self.state()
        B = (state["B_x"], state["B_y"])
        C = (state["C_x"], state["C_y"]) if state["assembled"] else None
        self.drawing.update(v["ground"], B, C)
        a, c, d = v["crank"], v["rocker"], v["ground"]
        (x0, x1), (y0, y1) = extent([-a, a, d - c, d + c], [-a, a, -c, c])  # B and C stay on these circles
        self.axes.set_xlim(x0, x1)
        self.axes.set_ylim(y0, y1)
        self.axes.set_title(f"four-bar, branch {v['branch']:+d}" if state["assembled"] else
                            "cannot be assembled at this crank angle", color="black" if state["assembled"] else "red")
        self.text.set_text(self.describe(v, state))
        self.figure.canvas.draw_idle()

    @staticmethod
    def describe(values: dict[str, float], state: dict[str, float | bool]) -> str:
        """The readout: angles in degrees wrapped to (-180, 180], rates in rad/s, the transmission angle."""
        def degrees(angle: float) -> str:
            return f"{float(wrap(math.degrees(angle), 180.0)):8.3f}°"

        def speed(value: float) -> str:
            return f"{value:8.4f} rad/s" if math.isfinite(value) else "undefined (toggle)"

        def row(label: str, symbol: str, value: str) -> str:
            return f"{label:<14}{symbol:>5} = {value}"

        spans = crank_range(values["crank"], values["coupler"], values["rocker"], values["ground"])
        lines = [row("crank angle", "θ", degrees(values["theta"]))]
        if not state["assembled"]:
            lines += ["", "cannot be assembled here:", "the coupler and rocker", "cannot reach each other"]
        else:
            mu = math.degrees(state["transmission"])
            low, high = TRANSMISSION_LIMITS
            lines += [row("coupler angle", "β", degrees(state["coupler"])),
                      row("rocker angle", "φ", degrees(state["rocker"])),
                      "",
                      row("crank speed", "dθ/dt", f"{values['thetadot']:8.4f} rad/s"),
                      row("coupler speed", "dβ/dt", speed(state["coupler_speed"])),
                      row("rocker speed", "dφ/dt", speed(state["rocker_speed"])),
                      "",
                      row("transmission", "μ", f"{mu:8.3f}°")]
            if not low <= mu <= high:
                lines.append(f"  (outside the usual {low:g}°–{high:g}°)")
        lines += ["", f"Grashof class: {grashof(values['crank'], values['coupler'], values['rocker'], values['ground']).name}",
                  "reachable crank range:"]
        lines += ["  " + describe_spans(pieces, "deg") for pieces in ([[span] for span in spans] or [[]])]
        return "\n".join(lines)


class LinkageView:
    """Any linkage as an interactive figure: its drawing, a slider for each parameter and input, branch buttons.

    ``linkage``: a :class:`~symlink.symbolic.linkage.Linkage`, or its :class:`~symlink.numeric.poses.Placement`
    (such as :func:`~symlink.numeric.poses.cached_placement` reads from the disk cache: then no SymPy);
    ``values`` by symbol name (lengths, fixed angles and inputs in radians);
    each length's slider spans a fifth of its value to three times it, each
    angle's a full turn (in degrees).  Moving a slider redraws the linkage
    (:func:`~symlink.plot.drawing.draw_linkage`); a pose that cannot be
    assembled is said in the title, and the last drawing stays.  ``figure``
    defaults to a new pyplot figure; :meth:`values` is what is set.

    Parameters
    ----------
    linkage : Linkage or Placement
        Any linkage, or its placement.
    values : mapping of str to float
        Every parameter and input by name (angles in radians).
    trace : sequence of str, optional
        Points whose paths are drawn.
    figure : matplotlib.figure.Figure, optional
        Where to draw (default: a new pyplot figure).

    Examples
    --------
    >>> import symlink
    >>> view = symlink.LinkageView(symlink.fourbar(), dict(a=20, b=66, c=56, d=80, theta=0.0))
    >>> view.values()
    {'theta': 0.0, 'branch': 1, 'a': 20.0, 'b': 66.0, 'c': 56.0, 'd': 80.0}
    """

    def __init__(self, linkage: "Linkage | Placement", values, *, trace=(), figure: "Figure | None" = None) -> None:
        from matplotlib.widgets import RadioButtons, Slider

        from ..numeric.poses import Geometry, Placement
        self.geometry = linkage if isinstance(linkage, Placement) else Geometry(linkage)
        self.trace = tuple(trace)
        facts = self.geometry.facts
        self.branches: list[str] = list(facts["branches"])
        self.fixed = self.geometry.check_values(values)  # every value, checked (lengths positive and finite)
        if figure is None:
            import matplotlib.pyplot as pyplot
            figure = pyplot.figure(figsize=(10, 7))
        self.figure = figure
        adjustable = list(facts["parameters"]) + list(facts["inputs"])
        positive = set(facts["positive"])
        # a length that is not positive is refused as given (its slider would span it inverted, and the solver
        # would name the slider's clamped value instead)
        check_lengths(**{name: self.fixed[name] for name in adjustable if name in positive})
        rows = len(adjustable)
        top = 0.06 + 0.035 * rows
        self.axes = figure.add_axes((0.06, top + 0.06, 0.62, 0.90 - top - 0.06))
        self.sliders: dict[str, Slider] = {}
        turning = set(facts["turning"])  # what turns a named point's vectors
        self.angles = {name for name in adjustable if name in self.geometry.angles or name in turning}
        for row, name in enumerate(adjustable):
            value = float(self.fixed[name])
            if name in self.angles:
                low, high, shown, fmt = -180.0, 180.0, float(wrap(math.degrees(value), 180.0)), "%.1f°"
            else:
                size = abs(value) or 1.0
                low, high, shown, fmt = (value / 5, value * 3, value, "%.4g") if name in positive else \
                    (value - 2 * size, value + 2 * size, value, "%.4g")
            slider_axes = figure.add_axes((0.16, 0.02 + 0.035 * (rows - 1 - row), 0.50, 0.025))
            self.sliders[name] = Slider(slider_axes, name, low, high, valinit=shown, valfmt=fmt)
            self.sliders[name].on_changed(self.update)
        self.branch_buttons = None
        if self.branches:
            button_axes = figure.add_axes((0.74, 0.70, 0.12, 0.14))
            button_axes.set_title("branch", fontsize="small")
            self.branch_buttons = RadioButtons(button_axes, ("+1", "-1"), active=0)
            self.branch_buttons.on_clicked(self.update)
        self.message = ""
        self.shown = dict(self.fixed)  # the values of the drawing on screen
        self.update()

    def values(self) -> dict[str, float]:
        """The values as set: the sliders' (angles in radians) and the branch sign on every loop."""
        values = dict(self.fixed)
        for name, slider in self.sliders.items():
            values[name] = math.radians(float(slider.val)) if name in self.angles else float(slider.val)
        sign = 1 if self.branch_buttons is None else int(self.branch_buttons.value_selected)
        values.update({branch: sign for branch in self.branches})
        return values

    def update(self, _changed=None) -> None:
        """Redraw the linkage at the values set (every widget calls this)."""
        from .drawing import draw_placement
        values = self.values()
        poses = self.geometry.poses(self.geometry.check_values(values))
        self.message = "" if poses.assembled[0] else (
            f"{self.geometry.name} cannot be assembled here; the drawing shows the last pose that can")
        if not self.message:
            self.shown = values
        self.axes.clear()
        draw_placement(self.geometry, self.shown, ax=self.axes, trace=self.trace)
        if self.message:
            self.axes.set_title(self.message, color="red", fontsize="small")
        self.figure.canvas.draw_idle()
