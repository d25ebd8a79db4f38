"""A private, empty scene cache (memory and disk) for the tests that use it."""
import pytest

from symlink.cache import clear_memory


@pytest.fixture
def empty_cache(tmp_path, monkeypatch):
    """An empty cache folder and an empty memory cache: a first run; yields the folder."""
    monkeypatch.setenv("SYMLINK_CACHE", str(tmp_path / "cache"))
    clear_memory()
    yield tmp_path / "cache"
    clear_memory()
