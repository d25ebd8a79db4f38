"""``symlink studio``: a local web app to draw a linkage by its joints, read its equations and watch it move.

A leaf over the library, as the command line is (only :mod:`symlink.cli` imports it, and users the widget):

* :mod:`.drawing`: a drawing (joints, links, ground, driver, sliders as JSON) checked and turned into a
  linkage by :func:`symlink.mechanism.joints.from_joints`; its structure, derivation, generated JavaScript
  solver and exports; a catalog linkage, an atlas entry or another tool's file turned into a drawing;
* :mod:`.page`: the self-contained HTML page of a drawing (solver, KaTeX and equations inlined);
* :mod:`.server`: the Starlette app on uvicorn, bound to 127.0.0.1 and guarded by a random token;
* :mod:`.widget`: the studio in a notebook, :class:`~symlink.studio.widget.LinkageWidget` (anywidget), also
  ``symlink.LinkageWidget`` through the front door, which loads it by name on first use.

The page itself (``static/``: ``index.html``, ``studio.js``, ``studio.css`` and the vendored KaTeX) draws and
animates, as does the widget's ``static/widget.js``; their kinematics is the generated solver, never code
written by hand in JavaScript.
"""
