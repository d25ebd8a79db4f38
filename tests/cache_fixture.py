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


def forget_source_digests() -> None:
    """As in a new process: the digests of symlink's own source are worked out again (from the disk cache's entry
    where the files are unchanged)."""
    import symlink.numeric.cache as cache
    cache._source_digest.cache_clear()
    cache._module_digest.cache_clear()


def edit_module(monkeypatch, relative: str, addition: bytes = b"\n# edited\n") -> None:
    """As if ``addition`` were appended to the package file ``relative`` (``"codegen/c.py"``): its bytes, its size
    and its modification time change, as an edit changes them; the source digests are forgotten."""
    from pathlib import Path

    import symlink.numeric.cache as cache
    target = (Path(cache.__file__).parent.parent / relative).resolve()
    assert target.is_file(), f"symlink/{relative} is gone: name the module that took its place"
    read, status = cache._module_bytes, cache._module_stat

    def edited_bytes(path) -> bytes:
        return read(path) + (addition if Path(path).resolve() == target else b"")

    def edited_status(path) -> list[int]:
        mtime_ns, size, inode = status(path)
        return [mtime_ns + 1, size + len(addition), inode] if Path(path).resolve() == target else [mtime_ns, size, inode]
    monkeypatch.setattr(cache, "_module_bytes", edited_bytes)
    monkeypatch.setattr(cache, "_module_stat", edited_status)
    forget_source_digests()
