"""For the tests and the doctests alike: a private scene cache, never ~/.cache/symlink.

Set when pytest starts, before collection (some test modules build solvers at
import), and removed when it ends.
"""
import os
import shutil
import tempfile

_previous = None
_folder = None


def pytest_configure(config):
    global _previous, _folder
    _previous = os.environ.get("SYMLINK_CACHE")
    _folder = tempfile.mkdtemp(prefix="symlink-test-cache-")
    os.environ["SYMLINK_CACHE"] = _folder


def pytest_unconfigure(config):
    if _previous is None:
        os.environ.pop("SYMLINK_CACHE", None)
    else:
        os.environ["SYMLINK_CACHE"] = _previous
    if _folder:
        shutil.rmtree(_folder, ignore_errors=True)
