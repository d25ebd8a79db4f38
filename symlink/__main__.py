"""``python -m symlink`` is the ``symlink`` command; :func:`entry` is its console script.

The command line's own module (:mod:`symlink.cli`) imports NumPy and the command modules: an
interrupt (Ctrl-C) during that import would otherwise end in a traceback.  :func:`entry` imports
it under the same rule as every command: one line, exit status 130.
"""
import sys


def entry() -> int:
    """Run the ``symlink`` command; an interrupt at any moment, its import included, is one line and 130."""
    try:
        from .cli import main
    except KeyboardInterrupt:
        print("symlink: interrupted", file=sys.stderr)
        return 130
    return main()


if __name__ == "__main__":
    sys.exit(entry())
