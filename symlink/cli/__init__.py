"""The ``symlink`` command: a leaf over the library (nothing in symlink imports it).

Every subcommand parses numbers and names only (never code), prints angles in
degrees (``--units rad`` for radians) wrapped to (-180, 180], writes results
to stdout and notes and progress to stderr.

Exit status: 0 success; 1 a file could not be written, or the machine ran
out of memory; 2 bad input (one line on stderr, ``symlink: error: ...``),
an input file (linkage, scene, csv) that is missing, unreadable, not a
regular file or too large among it, and a request beyond what a command
may use (:mod:`.budget`: memory and time are estimated before any work
starts); 130 interrupted (Ctrl-C).  A closed pipe (``| head``) ends the
command quietly.  No command shows a traceback, and a message quotes
hostile text as a short excerpt.

One module a command or family: :mod:`.tables` (``fourbar`` and a table
command for each catalog linkage), :mod:`.pictures` (``curve``, ``animate``,
``view``), :mod:`.plan`, :mod:`.run` (scene files), :mod:`.bench`,
:mod:`.analyze`, :mod:`.loop`, :mod:`.quick_return`, :mod:`.synthesize`, :mod:`.export`, :mod:`.cache`, :mod:`.sweep`,
:mod:`.dynamics` (``flywheel``, and the four-bar's mass columns), :mod:`.tolerance`, :mod:`.parts`,
:mod:`.studio` (the browser app); shared
options in :mod:`.options`, writers in :mod:`.output`.

A command module is imported when the command line needs it: ``symlink
fourbar ...`` imports :mod:`.tables` (and what its options use) and no other
command's module, so a warm table costs little beyond importing NumPy;
``symlink --help`` and a word that is no command import them all.
"""
from __future__ import annotations

import argparse
import importlib
import os
import re
import sys
import warnings
from typing import Sequence

import numpy

from ..common.files import EXCERPT_LENGTH
from ..version import __version__
from .budget import use_time_budget
from .options import Parser, check_outputs

__all__ = ["main", "build_parser", "COMMANDS"]

#: The command modules (in this package), in the order ``symlink --help`` lists their commands, each with the
#: commands its ``register(commands)`` adds to the subparsers ``commands``; :mod:`.tables` adds a table command
#: for each catalog linkage besides (named for it), so a word that no module lists here is looked for in order.
COMMANDS = {"tables": ("fourbar", "table"), "dynamics": ("flywheel",), "plan": ("plan",),
            "pictures": ("draw", "curve", "animate", "view"), "run": ("run",), "bench": ("bench",),
            "analyze": ("analyze",), "loop": ("loop",), "quick_return": ("quick-return",),
            "synthesize": ("synthesize",), "export": ("export", "derive"), "cache": ("cache",), "sweep": ("sweep",),
            "atlas": ("atlas",), "tolerance": ("tolerance",), "parts": ("parts",), "studio": ("studio",)}

EXIT_OK, EXIT_FAILED, EXIT_USAGE, EXIT_INTERRUPTED = 0, 1, 2, 130


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The ``symlink`` parser with every subcommand (each builds its options when used).

    With ``command`` (the first word of a command line), only the module that :data:`COMMANDS` lists it under
    is imported and registered (a catalog linkage's table command: the modules in order until one has
    registered it); the others are not imported.  A word that no module registers ends with every command
    registered, so that the error lists them all.

    >>> sorted(build_parser("fourbar")._subparsers._group_actions[0].choices)[:2]
    ['fivebar', 'fourbar']
    """
    parser = Parser(prog="symlink", description="Symbolic derivation toolkit for planar linkages.",
                    epilog="Exit status: 0 done, 1 a file could not be written, 2 bad input (an input file too), "
                           "130 interrupted.  'symlink COMMAND --help' describes a command.")
    parser.add_argument("--version", action="version", version=f"symlink {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, parser_class=Parser, metavar="COMMAND")
    owner = [name for name, words in COMMANDS.items() if command in words]
    for name in owner or COMMANDS:
        importlib.import_module(f"{__name__}.{name}").register(commands)
        if command is not None and command in commands.choices:
            break
    return parser


def _command_word(argv: Sequence[str] | None) -> str | None:
    """The command a command line names (its first word), or ``None`` when it starts with an option."""
    words = sys.argv[1:] if argv is None else argv
    return words[0] if words and not words[0].startswith("-") else None


#: A word of a message longer than this is hostile text (a 5000-character name, a megabyte expression): cut.
_LONG_WORD = re.compile(r"\S{100,}")
#: The most characters of one line of error or warning.
MAX_MESSAGE = 1000


def _one_line(message: object) -> str:
    """``message`` on one line, each overlong word cut to an excerpt and the whole to :data:`MAX_MESSAGE`.

    Messages quote what the user gave; a hostile value must not come back as megabytes on stderr.
    """
    text = " ".join(str(message).split())
    text = _LONG_WORD.sub(lambda word: word.group()[:EXCERPT_LENGTH] + "...", text)
    return text if len(text) <= MAX_MESSAGE else text[:MAX_MESSAGE] + "..."


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """Warnings as one line on stderr; NumPy's plain RuntimeWarnings (overflow, 0/0) are not shown at all."""
    if category is RuntimeWarning:
        return
    print(f"symlink: warning: {_one_line(message)}", file=sys.stderr)


def _quiet_stdout() -> None:
    """After a closed pipe: send what is left to /dev/null, so Python's exit flush stays quiet."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass


def _error(text: str, status: int) -> int:
    try:
        sys.stdout.flush()
    except (OSError, ValueError):
        pass
    print(f"symlink: error: {_one_line(text)}", file=sys.stderr)
    return status


def _os_error(error: OSError) -> str:
    reason = error.strerror or str(error)
    where = error.filename
    return f"cannot write or read {where}: {reason}" if where else reason


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (see the module's documentation)."""
    with warnings.catch_warnings(), numpy.errstate(all="ignore"):
        warnings.simplefilter("default")
        warnings.showwarning = _show_warning
        try:
            parser = build_parser(_command_word(argv))
            args, rest = parser.parse_known_args(argv)
            if getattr(args, "passes_arguments_on", False):
                args.arguments = rest
            elif rest:
                parser.error(f"unrecognized arguments: {' '.join(rest)}")
            use_time_budget(getattr(args, "time_budget", None))  # this command's, or the default (.budget)
            check_outputs(args)
            return args.run(args)
        except SystemExit as done:  # --help and --version
            return done.code if isinstance(done.code, int) else EXIT_OK
        except BrokenPipeError:
            _quiet_stdout()
            return EXIT_OK
        except KeyboardInterrupt:
            print("symlink: interrupted", file=sys.stderr)
            return EXIT_INTERRUPTED
        except RecursionError:
            return _error("the input is nested too deeply", EXIT_USAGE)
        except ValueError as error:  # UsageError included
            return _error(str(error), EXIT_USAGE)
        except OSError as error:
            return _error(_os_error(error), EXIT_FAILED)
        except MemoryError:
            return _error("out of memory: ask for fewer values at a time (a larger --step, fewer frames)",
                          EXIT_FAILED)
        except Exception as error:  # noqa: BLE001 - a bug: one line, never a traceback
            return _error(f"internal error ({type(error).__name__}: {error}); please report it with the "
                          "command line that caused it", EXIT_FAILED)


if __name__ == "__main__":
    sys.exit(main())
