"""``python -m symlink`` is the ``symlink`` command; :func:`entry` is its console script.

The command line's own module (:mod:`symlink.cli`) imports NumPy and the command modules: an
interrupt (Ctrl-C) during that import would otherwise end in a traceback, or worse, land inside
an extension module's import (NumPy then reports a "bad install" and goes on, or the interrupt is
swallowed and the command runs to its end).  :func:`entry` therefore holds an interrupt back
while it imports, and answers it as every command does: one line, exit status 130.  What Python
does before this module runs (its own start and ``site``) is outside any package's reach.
"""
import sys

# The C module: ``signal`` itself imports ``enum``, milliseconds before the hold can start.
import _signal as signal  # type: ignore[import-not-found]


def entry() -> int:
    """Run the ``symlink`` command; an interrupt at any moment, its import included, is one line and 130."""
    interrupted = []
    held_back = signal.getsignal(signal.SIGINT) is signal.default_int_handler  # not where the caller ignores it
    if held_back:
        signal.signal(signal.SIGINT, lambda number, frame: interrupted.append(number))
    try:
        from .cli import main
    except KeyboardInterrupt:
        interrupted.append(signal.SIGINT)
    finally:
        if held_back:
            signal.signal(signal.SIGINT, signal.default_int_handler)
    if interrupted:
        print("symlink: interrupted", file=sys.stderr)
        return 130
    return main()


if __name__ == "__main__":
    sys.exit(entry())
