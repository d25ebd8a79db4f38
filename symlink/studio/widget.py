"""The studio in a notebook: :class:`LinkageWidget`, a Jupyter widget (anywidget) that draws a linkage, moves it and
hands its edits back to Python.

The one exception to ``import symlink``: the studio is a leaf that the front door never imports, so the
widget is imported from its module::

    from symlink.studio.widget import LinkageWidget

The widget shows the linkage drawn by its joints, animated by the generated JavaScript solver
(:func:`symlink.codegen.javascript.javascript_geometry`; no kinematics is written by hand in JavaScript),
a slider for the input and for each parameter, a switch for each branch, and the linkage's equations typeset
by the vendored KaTeX.  Two traitlets sync both ways: ``values`` (inputs and parameters, name -> number) and
``branch`` (branch name -> +1 or -1).  Moving a slider in the page updates ``widget.values``; setting
``widget.values`` (all names or some of them) moves the drawing.  A name the linkage does not have, or a value
that is no finite number (or not positive, for a length), is refused with :class:`RefusedValue` (a
``ValueError``), whether Python or the page sent it.  :meth:`LinkageWidget.linkage_values` gives
the present values as keyword arguments of :class:`symlink.Solver`.

Needs ``anywidget`` (``pip install 'symlink-kinematics[notebook]'``).
"""
from __future__ import annotations

import math
import numbers
import re
from pathlib import Path
from typing import Any, Mapping

try:
    import anywidget
    import traitlets
except ImportError as error:  # pragma: no cover - the message is the point
    raise ImportError("symlink.studio.widget needs anywidget: pip install 'symlink-kinematics[notebook]' "
                      "(or pip install anywidget)") from error

from ..common.numbers import finite_float
from ..mechanism.joints import JointLinkage

__all__ = ["LinkageWidget", "RefusedValue", "widget_esm", "widget_css"]

STATIC = Path(__file__).resolve().parent / "static"

_WIDGET_CSS = """
.symlink-widget { font-family: system-ui, sans-serif; font-size: 13px; display: flex; flex-wrap: wrap; gap: 12px; }
.symlink-widget .symlink-drawing { background: #fbfbfd; border: 1px solid #ddd; }
.symlink-widget .symlink-link { fill: rgba(70, 110, 200, 0.18); stroke: #3a5fb0; stroke-width: 3;
  stroke-linejoin: round; }
.symlink-widget polyline.symlink-link { fill: none; }
.symlink-widget .symlink-ground { fill: none; stroke: #999; stroke-width: 2; stroke-dasharray: 6 4; }
.symlink-widget .symlink-pivot { fill: #bbb; stroke: #666; }
.symlink-widget .symlink-guide { stroke: #999; stroke-width: 1.5; stroke-dasharray: 2 3; }
.symlink-widget .symlink-block { fill: rgba(70, 110, 200, 0.25); stroke: #3a5fb0; stroke-width: 1.5; }
.symlink-widget .symlink-joint { fill: #fff; stroke: #222; stroke-width: 1.5; }
.symlink-widget .symlink-label { font-size: 12px; fill: #333; }
.symlink-widget .symlink-message.symlink-error { color: #b00; }
.symlink-widget .symlink-controls { display: flex; flex-direction: column; gap: 4px; min-width: 260px; }
.symlink-widget .symlink-row { display: flex; align-items: center; gap: 6px; }
.symlink-widget .symlink-name { min-width: 5em; font-family: monospace; }
.symlink-widget .symlink-value { min-width: 5em; font-family: monospace; }
.symlink-widget .symlink-equations { flex-basis: 100%; overflow-x: auto; }
"""

#: Names of fixed angles among a linkage's parameters (their sliders turn a full turn).
_ANGLE = re.compile(r"^(alpha|beta|gamma|delta|phi|psi|theta)(_|$)")


def widget_esm() -> str:
    """The widget's ES module: the vendored KaTeX (as a module-local ``katex``) and ``static/widget.js``.

    It holds no linkage's data: names, numbers, the solver and the equations come through the model.

    >>> widget_esm().rstrip().endswith("export default { render: render };")
    True
    """
    katex = (STATIC / "katex" / "katex.min.js").read_text(encoding="utf-8")
    return ("var module = { exports: {} }; var exports = module.exports;\n" + katex
            + "\nvar katex = module.exports;\n" + (STATIC / "widget.js").read_text(encoding="utf-8"))


def widget_css() -> str:
    """The widget's style sheet: KaTeX's (its fonts as data URIs) and the drawing's.

    >>> ".symlink-widget" in widget_css() and "data:font/woff2" in widget_css()
    True
    """
    from .page import _katex_css
    return _katex_css() + _WIDGET_CSS


def _number(name: str, value: Any, positive: bool) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name} must be a number, not {type(value).__name__}")
    found = finite_float(value)
    if found is None:
        raise ValueError(f"{name} must be finite, not {value!r}" if isinstance(value, float) else
                         f"{name} must be finite, not a number this large")
    number = found
    if positive and not number > 0:
        raise ValueError(f"{name} is a length and must be positive, not {number!r}")
    return number


def _latex(linkage: Any) -> str:
    text = linkage._repr_latex_().strip()
    if text.startswith("$") and text.endswith("$"):
        text = text.strip("$")
    return text


class RefusedValue(traitlets.TraitError, ValueError):
    """A value the widget refuses: a ``ValueError``, and a ``TraitError`` so that traitlets undoes what the page
    sent with it (``set_state`` rolls back on a ``TraitError`` only).

    >>> issubclass(RefusedValue, ValueError)
    True
    """


class _Table(traitlets.Dict):
    """A dict traitlet that refuses anything else with a ``ValueError`` (traitlets' own error is a TraitError)."""

    def validate(self, obj: Any, value: Any) -> Any:
        if not isinstance(value, Mapping):
            raise RefusedValue(f"{self.name} must be a dict of name -> number, not {type(value).__name__}")
        return super().validate(obj, dict(value))


class LinkageWidget(anywidget.AnyWidget):
    """A linkage in a notebook: drawn, animated by its generated JavaScript solver, edited by sliders.

    ``linkage`` is a :class:`~symlink.Linkage` (then ``values`` gives its parameters; inputs default to 0)
    or what :func:`symlink.from_joints` returns (its drawn values are the defaults; ``values`` overrides
    some).  ``values`` may name branches too (``branch=-1``); they go to the ``branch`` traitlet.  ``ranges``
    gives a slider's (min, max) where the default (a tenth to three times a length, a full turn for an angle)
    does not suit.  The front door gives it (``symlink.LinkageWidget``), loaded by name on first use:
    nothing in the library imports the studio.

    Parameters
    ----------
    linkage : Linkage or JointLinkage
        The linkage, or a linkage drawn by its joints (its drawn values are the defaults).
    values : mapping of str to float, optional
        Parameters, inputs and branch signs by name.
    ranges : mapping of str to (float, float), optional
        A slider's (min, max) by name.

    Examples
    --------
    >>> import symlink
    >>> widget = symlink.LinkageWidget(symlink.fourbar(), dict(a=20, b=66, c=56, d=80))
    >>> widget.values = {"a": 25}              # what a slider in the page does, from Python
    >>> widget.values["a"], widget.branch
    (25.0, {'branch': 1})
    >>> sorted(widget.linkage_values())
    ['a', 'b', 'branch', 'c', 'd', 'theta']
    """

    _esm = widget_esm()
    _css = widget_css()

    values = _Table().tag(sync=True)
    branch = _Table().tag(sync=True)
    _solver = traitlets.Unicode("").tag(sync=True)
    _ranges = traitlets.Dict().tag(sync=True)
    _lengths = traitlets.List(traitlets.Unicode()).tag(sync=True)
    _equations = traitlets.Unicode("").tag(sync=True)

    def __init__(self, linkage: Any, values: Mapping[str, float] | None = None, *,
                 ranges: Mapping[str, tuple[float, float]] | None = None, **kwargs: Any) -> None:
        drawn = linkage if isinstance(linkage, JointLinkage) else None
        self.linkage = drawn.linkage if drawn is not None else linkage
        inputs = [q.name for q in self.linkage.inputs]
        parameters = [p.name for p in self.linkage.parameters]
        branches = [b.name for b in self.linkage.branches]
        self._names = tuple(inputs + parameters)
        self._branch_names = tuple(branches)
        self._positive = frozenset(p.name for p in self.linkage.parameters if p.is_positive)
        given = dict(values or {})
        start: dict[str, Any] = {name: 0.0 for name in inputs}
        signs: dict[str, Any] = {name: 1 for name in branches}
        if drawn is not None:
            start.update(drawn.values)
            signs.update(drawn.branches)
        for name in branches:
            if name in given:
                signs[name] = given.pop(name)
        start.update(given)
        missing = [name for name in self._names if name not in start]
        if missing:
            raise ValueError(f"{self.linkage.name}: give a value for {', '.join(missing)}")
        start = self._checked_values(start, {})
        signs = self._checked_branch(signs, {})
        try:
            from ..codegen.javascript import javascript_geometry
            source = javascript_geometry(self.linkage)
        except (ImportError, ValueError, NotImplementedError) as error:
            raise ValueError(f"{self.linkage.name}: no JavaScript solver to animate it: {error}") from error
        super().__init__(**kwargs)
        self._solver = source
        self._equations = _latex(self.linkage)
        self._lengths = sorted(self._positive)
        self._ranges = self._slider_ranges(start, ranges or {})
        self.branch = signs
        self.values = start

    # --- checks ---------------------------------------------------------------------------------
    def _checked_values(self, proposal: Any, current: Mapping[str, float]) -> dict[str, float]:
        if not isinstance(proposal, Mapping):
            raise ValueError(f"values must be a dict of name -> number, not {type(proposal).__name__}")
        merged = dict(current)
        for name, value in proposal.items():
            if name not in self._names:
                shown = name[:40] if isinstance(name, str) else name
                where = " (set widget.branch for a branch)" if name in self._branch_names else ""
                raise ValueError(f"{self.linkage.name} has no input or parameter {shown!r}{where}; "
                                 f"it has {', '.join(self._names)}")
            merged[name] = _number(name, value, name in self._positive)
        return {name: merged[name] for name in self._names if name in merged}

    def _checked_branch(self, proposal: Any, current: Mapping[str, int]) -> dict[str, int]:
        if not isinstance(proposal, Mapping):
            raise ValueError(f"branch must be a dict of branch name -> +1 or -1, not {type(proposal).__name__}")
        merged = dict(current)
        for name, sign in proposal.items():
            if name not in self._branch_names:
                shown = name[:40] if isinstance(name, str) else name
                raise ValueError(f"{self.linkage.name} has no branch {shown!r}"
                                 + (f"; it has {', '.join(self._branch_names)}" if self._branch_names else ""))
            if isinstance(sign, bool) or not isinstance(sign, numbers.Real) or float(sign) not in (1.0, -1.0):
                raise ValueError(f"branch {name} is +1 or -1, not {sign!r}")
            merged[name] = int(float(sign))
        return {name: merged[name] for name in self._branch_names if name in merged}

    @traitlets.validate("values")
    def _validate_values(self, proposal: Any) -> dict[str, float]:
        try:
            return self._checked_values(proposal["value"], self.values)
        except RefusedValue:
            raise
        except ValueError as error:
            raise RefusedValue(str(error)) from None

    @traitlets.validate("branch")
    def _validate_branch(self, proposal: Any) -> dict[str, int]:
        try:
            return self._checked_branch(proposal["value"], self.branch)
        except ValueError as error:
            raise RefusedValue(str(error)) from None

    def _slider_ranges(self, start: Mapping[str, float],
                       given: Mapping[str, tuple[float, float]]) -> dict[str, list[float]]:
        found: dict[str, list[float]] = {}
        inputs = {q.name for q in self.linkage.inputs}
        for name in self._names:
            value = start[name]
            if name in given:
                low, high = (_number(name, v, False) for v in given[name])
                if not low < high:
                    raise ValueError(f"the range of {name} must go up, not ({low}, {high})")
            elif name in self._positive:
                low, high = value / 10, value * 3
            elif (name in inputs and not name.startswith("s_")) or _ANGLE.match(name):
                low, high = (-math.pi, math.pi) if name in inputs else (value - math.pi, value + math.pi)
            else:
                span = 2 * max(1.0, abs(value))
                low, high = value - span, value + span
            found[name] = [low, high, (high - low) / 1000]
        for name in given:
            if name not in found:
                raise ValueError(f"{self.linkage.name} has no input or parameter {str(name)[:40]!r} to give a range")
        return found

    # --- use ------------------------------------------------------------------------------------
    def linkage_values(self) -> dict[str, float]:
        """The present inputs, parameters and branch signs: keyword arguments of :class:`symlink.Solver`.

        >>> import symlink
        >>> from symlink.studio.widget import LinkageWidget
        >>> widget = LinkageWidget(symlink.fourbar(), dict(a=20, b=66, c=56, d=80, theta=0.5, branch=-1))
        >>> widget.linkage_values()
        {'theta': 0.5, 'a': 20.0, 'b': 66.0, 'c': 56.0, 'd': 80.0, 'branch': -1}
        """
        return {**self.values, **self.branch}
