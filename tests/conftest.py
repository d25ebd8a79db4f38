"""Make ``tests/`` importable (``from references import ...``) and keep tests out of the user's cache."""

import pathlib
import sys

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).parent))


@pytest.fixture(autouse=True, scope="session")
def private_scene_cache(tmp_path_factory):
    """One scene cache for the whole run, in a temporary folder, never ~/.cache/symlink."""
    folder = tmp_path_factory.mktemp("symlink-cache")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("SYMLINK_CACHE", str(folder))
        yield folder
