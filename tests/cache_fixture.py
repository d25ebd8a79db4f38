"""A private, empty scene cache (memory and disk) for the tests that use it."""
import pytest

from symlink.numeric.cache import clear_memory
from symlink.numeric.compiled_library import wait_for_builds


@pytest.fixture
def empty_cache(tmp_path, monkeypatch):
    """An empty cache folder and an empty memory cache: a first run; yields the folder.

    Background builds of earlier tests finish first, and this test's before the next: none runs across two tests.
    """
    wait_for_builds()
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "cache"))
    clear_memory()
    yield tmp_path / "cache"
    wait_for_builds()
    clear_memory()
