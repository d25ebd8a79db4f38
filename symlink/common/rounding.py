"""The rounding tolerance every layer shares: how far below zero a square root's argument may round at a toggle.

Its one home, SymPy-free, so that the closed forms of the analysis
(:mod:`symlink.analysis.fourbar_closed_form`) decide a toggle exactly as the
generated code does (:mod:`symlink.symbolic.position` writes it into every
clamped square root) without importing the symbolic layer.

>>> TOLERANCE
1e-14
"""
from __future__ import annotations

__all__ = ["TOLERANCE"]

#: Relative size below which a negative square-root argument is rounding, not
#: a configuration that cannot be assembled: with the scales the cases give
#: (see ``symlink.symbolic.position._rounding_size``), inputs within ``TOLERANCE`` times the loop's size of
#: a toggle are taken as at the toggle (about 45 units in the last place).
TOLERANCE = 1e-14
