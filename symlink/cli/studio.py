"""``symlink studio [NAME|FILE] [--port P] [--no-browser]`` and ``symlink studio --html OUT NAME|FILE``.

The studio (:mod:`symlink.studio`) needs the ``studio`` extra (Starlette and uvicorn); without it the
command says so in one line and exits 2.  ``--html`` writes the self-contained page of a linkage and
needs neither.
"""
from __future__ import annotations

import argparse
import socket
import sys

from .options import UsageError, command_help, output_file, whole

#: The one line said when the server's packages are missing.
MISSING = "symlink studio needs the studio extra: pip install 'symlink-kinematics[studio]'"


def register(commands) -> None:
    """Register ``symlink studio``."""
    commands.add_parser("studio", populate=_add_options, **command_help(
        "draw a linkage by its joints in the browser: structure, equations, motion (a local web app)",
        "coordinates in any one unit; angles in the page in degrees", "symlink studio fourbar"))


def _add_options(command: argparse.ArgumentParser) -> None:
    command.add_argument("name", metavar="NAME|FILE", nargs="?",
                         help="open a catalog linkage, an atlas entry (atlas:NAME), a linkage file (.toml), "
                              "pylinkage JSON (.json) or a Pyslvs expression (.txt, .pmks)")
    command.add_argument("--port", type=whole, metavar="P", help="the port on 127.0.0.1 (default: the first free one from 8765, where the browser keeps the "
                              "last drawing, else any free one)")
    command.add_argument("--no-browser", action="store_true", help="print the URL, do not open a browser")
    command.add_argument("--html", type=output_file, metavar="OUT.html",
                         help="write NAME|FILE as one self-contained HTML page that animates offline, and stop")
    command.set_defaults(run=run)


def _initial(name: str) -> dict:
    """The drawing of NAME|FILE: a name as such, a file by its text."""
    from pathlib import Path

    from ..common.files import read_input_text
    from ..studio.drawing import MAX_SOURCE, open_source
    path = Path(name)
    if path.suffix in (".toml", ".json", ".txt", ".pmks") or path.exists():
        text = read_input_text(path, MAX_SOURCE, "linkage file")
        kind = {".toml": "linkage", ".json": "pylinkage"}.get(path.suffix, "auto")
        return open_source(text, kind)
    return open_source(name, "name")


def _check_port(port: int) -> None:
    if not 1 <= port <= 65535:
        raise ValueError(f"--port {port}: a port is 1 to 65535")
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        try:
            probe.bind(("127.0.0.1", port))
        except OSError as error:
            raise ValueError(f"--port {port}: cannot listen there ({error.strerror or error})") from None


def run(args: argparse.Namespace) -> int:
    if args.html is not None:
        if args.name is None:
            raise ValueError("--html OUT.html needs NAME|FILE: the linkage to write")
        for option, given in (("--no-browser", args.no_browser), ("--port", args.port is not None)):
            if given:
                raise UsageError(f"--html and {option} conflict: --html writes a page and starts no server; give "
                                 "one or the other")
        from ..common.files import write_atomic
        from ..studio.page import standalone_page
        write_atomic(args.html, standalone_page(_initial(args.name)))
        print(f"wrote {args.html}")
        return 0
    try:
        import starlette  # noqa: F401
        import uvicorn  # noqa: F401
    except ImportError:
        print(f"symlink: error: {MISSING}", file=sys.stderr)
        return 2
    initial = _initial(args.name) if args.name is not None else None
    if args.port is not None:
        _check_port(args.port)
    from ..studio.server import serve
    serve(args.port, initial, open_browser=not args.no_browser, announce=lambda line: print(line, flush=True))
    print("symlink studio: stopped", file=sys.stderr)
    return 0
