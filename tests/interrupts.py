"""Children that a test interrupts (Ctrl-C) must take SIGINT as a terminal's Ctrl-C, whatever runs the tests.

A shell without job control starts a background job (``pytest -n auto &`` in a CI script) with SIGINT and
SIGQUIT ignored (POSIX: an asynchronous list inherits ``SIG_IGN`` for both), and every process below inherits that;
a Python started with SIGINT ignored installs no ``KeyboardInterrupt`` handler, so a SIGINT sent to it does
nothing.  That was the Ctrl-C test that did not stop within 120 s on a clean clone under ``pytest -n auto``: the
command was right to ignore the signal its caller had told it to ignore.  ``preexec_fn=interruptible`` gives the
child the default disposition, as a terminal's foreground job has it.
"""
from __future__ import annotations

import signal

__all__ = ["interruptible"]


def interruptible() -> None:
    """In a child between fork and exec: SIGINT and SIGQUIT as a foreground job has them (not ignored)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGQUIT, signal.SIG_DFL)
