"""``symlink cache info`` and ``symlink cache clear``: what symlink keeps in its cache folder, and removing it.

The folder is :func:`symlink.numeric.cache.cache_directory` (``$SYMLINK_CACHE``, else
``$XDG_CACHE_HOME/symlink``, else ``~/.cache/symlink``) unless ``--folder``
names another.  ``clear`` removes only the files and build folders symlink
writes there, never anything else, and refuses a folder that another user
owns or that group or others can write (exit status 2).
"""
from __future__ import annotations

import argparse
from pathlib import Path

from ..numeric.cache import ENVIRONMENT_VARIABLE, cache_directory
from ..numeric.cache_folder import CacheContents, cache_contents, clear_cache
from .options import Parser, command_help

UNITS = "sizes in bytes"


def register(commands) -> None:
    """Register ``symlink cache info`` and ``symlink cache clear``."""
    command = commands.add_parser("cache", **command_help(
        "show or clear symlink's cache of derived code", UNITS, "symlink cache info",
        f"The folder: ${ENVIRONMENT_VARIABLE}, else $XDG_CACHE_HOME/symlink, else ~/.cache/symlink "
        f"({ENVIRONMENT_VARIABLE} set empty: no disk cache).  'symlink cache ACTION --help' describes an action."))
    actions = command.add_subparsers(dest="action", required=True, parser_class=Parser, metavar="ACTION")
    info = actions.add_parser("info", **command_help(
        "show the cache folder, how many entries and bytes symlink keeps there, and whether it is trusted",
        UNITS, "symlink cache info"))
    clear = actions.add_parser("clear", **command_help(
        "remove symlink's own entries from the cache folder (nothing else in it)", UNITS,
        "symlink cache clear",
        "Entries are derived again when next needed.  A folder that another user owns or that group or others "
        "can write is refused."))
    for action, run in ((info, run_info), (clear, run_clear)):
        action.add_argument("--folder", type=Path, metavar="PATH",
                            help="this folder instead of the configured one")
        action.set_defaults(run=run)


def _folder(args: argparse.Namespace) -> Path | None:
    return args.folder if args.folder is not None else cache_directory()


def _off() -> int:
    print(f"no disk cache: {ENVIRONMENT_VARIABLE} is set empty")
    return 0


def _others(contents: CacheContents) -> str:
    return f"others   {contents.others} (not written by symlink, left alone)"


def run_info(args: argparse.Namespace) -> int:
    folder = _folder(args)
    if folder is None:
        return _off()
    contents = cache_contents(folder)
    trusted = "yes (only you can write it)" if contents.trusted else f"no: {contents.problem}; symlink does not use it"
    lines = [f"folder   {contents.folder}{'' if contents.exists else ' (not created yet)'}",
             f"entries  {contents.entries}", f"bytes    {contents.size}", f"trusted  {trusted}"]
    if contents.trusted:
        lines.append(f"leftovers {contents.leftovers} (of builds or writes interrupted or failed"
                     + ("; 'symlink cache clear' removes them)" if contents.leftovers else ")"))
        lines.append(_others(contents))
    print("\n".join(lines))
    return 0


def run_clear(args: argparse.Namespace) -> int:
    folder = _folder(args)
    if folder is None:
        return _off()
    removed = clear_cache(folder)
    print(f"folder   {removed.folder}\nremoved  {removed.entries} entries, {removed.size} bytes\n{_others(removed)}")
    return 0
