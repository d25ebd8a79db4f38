"""The blackboard: vectors, closure loops and a linkage, and everything derived from them in the linkage's
own symbols.

:mod:`~symlink.symbolic.vectors` and :mod:`~symlink.symbolic.loops` are the language a linkage is written in;
:mod:`~symlink.symbolic.position` (closed forms of the four cases, the branch sign), :mod:`~symlink.symbolic.motion`
(rates), :mod:`~symlink.symbolic.sensitivity`, :mod:`~symlink.symbolic.closure`, :mod:`~symlink.symbolic.seed_forms`
and :mod:`~symlink.symbolic.typeset` derive; :mod:`~symlink.symbolic.linkage` holds a linkage with its derivation
(derived lazily, on first use), :mod:`~symlink.symbolic.plan` its solve plan and :mod:`~symlink.symbolic.outputs`
its standard output sets.  The definition and its derivation are one layer because a
:class:`~symlink.symbolic.linkage.Linkage` answers ``linkage.velocities`` itself.
"""
