"""Files symlink writes and reads back: atomic writes, owner-only folders, reads that never block."""
import errno
import os
import stat
import threading

import pytest

from symlink.common import files
from symlink.common.files import NotPrivate, private_folder, read_private, remove_leftovers, write_atomic


def mode_of(path) -> int:
    return stat.S_IMODE(os.lstat(path).st_mode)


@pytest.fixture
def umask():
    """Set the umask for one test (tests run one at a time); restored after."""
    previous = os.umask(0o022)
    os.umask(previous)
    yield lambda mask: os.umask(mask)
    os.umask(previous)


def test_writes_text_and_bytes_with_umask_permissions(tmp_path):
    write_atomic(tmp_path / "a.txt", "text\n")
    write_atomic(tmp_path / "sub" / "b.bin", b"\x00\x01")
    assert (tmp_path / "a.txt").read_text() == "text\n" and (tmp_path / "sub" / "b.bin").read_bytes() == b"\x00\x01"
    mask = os.umask(0)
    os.umask(mask)
    assert mode_of(tmp_path / "a.txt") == 0o666 & ~mask


@pytest.mark.parametrize("mask", [0o000, 0o022, 0o077, 0o277])
def test_a_mode_asked_for_is_exact_whatever_the_umask(tmp_path, umask, mask):
    umask(mask)
    write_atomic(tmp_path / "private", "x", mode=0o600)
    write_atomic(tmp_path / "ordinary", "x")
    assert mode_of(tmp_path / "private") == 0o600
    assert mode_of(tmp_path / "ordinary") == 0o666 & ~mask


def test_failure_leaves_the_old_file_and_no_temporary(tmp_path):
    target = tmp_path / "keep.txt"
    target.write_text("old")

    class Boom:
        def __str__(self):
            raise RuntimeError

    with pytest.raises(TypeError):
        write_atomic(target, Boom())
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["keep.txt"]


def test_a_full_disk_leaves_the_old_file_and_no_temporary(tmp_path, monkeypatch):
    target = tmp_path / "keep.txt"
    target.write_text("old")

    def full(*_):
        raise OSError(errno.ENOSPC, "No space left on device")
    with pytest.MonkeyPatch.context() as disk:
        disk.setattr(os, "write", full)
        with pytest.raises(OSError, match="No space left"):
            write_atomic(target, "new" * 1000)
    assert target.read_text() == "old" and [p.name for p in tmp_path.iterdir()] == ["keep.txt"]


def test_the_process_umask_is_never_changed(tmp_path, monkeypatch):
    def forbidden(*_):
        raise AssertionError("write_atomic changed the process umask")
    monkeypatch.setattr(os, "umask", forbidden)
    write_atomic(tmp_path / "a", "x")
    write_atomic(tmp_path / "b", b"x", mode=0o600)
    private_folder(tmp_path / "c")


def test_no_permission_drift_while_another_thread_creates_folders(tmp_path, umask):
    """An unrelated thread makes folders with the default mode while symlink writes files."""
    umask(0o022)
    stop, drifted, made = threading.Event(), [], []

    def make_folders():
        index = 0
        while not stop.is_set():
            path = tmp_path / "folders" / str(index)
            os.makedirs(path)
            made.append(path)
            if mode_of(path) != 0o755:
                drifted.append((path.name, oct(mode_of(path))))
            index += 1

    (tmp_path / "folders").mkdir()
    worker = threading.Thread(target=make_folders)
    worker.start()
    try:
        for index in range(400):
            write_atomic(tmp_path / "files" / f"{index}.txt", "x", mode=0o600 if index % 2 else None)
            private_folder(tmp_path / "private" / str(index))
    finally:
        stop.set()
        worker.join()
    assert made and drifted == []
    assert {mode_of(p) for p in (tmp_path / "files").iterdir()} == {0o600, 0o644}
    assert {mode_of(p) for p in (tmp_path / "private").iterdir()} == {0o700}


def test_private_folder_is_created_0700_and_an_open_one_is_refused(tmp_path, umask):
    umask(0)
    assert mode_of(private_folder(tmp_path / "a" / "b")) == 0o700
    open_folder = tmp_path / "open"
    open_folder.mkdir(0o777)
    with pytest.raises(NotPrivate, match="writable by group and others"):
        private_folder(open_folder)
    assert mode_of(open_folder) == 0o777  # checked, never changed
    (tmp_path / "file").write_text("")
    with pytest.raises(NotADirectoryError):
        private_folder(tmp_path / "file")


def test_read_private_takes_only_a_regular_file_of_this_user(tmp_path):
    good = tmp_path / "good"
    good.write_bytes(b"data")
    good.chmod(0o600)
    assert read_private(good, 100) == b"data"
    with pytest.raises(OSError, match="larger than 3 bytes"):
        read_private(good, 3)
    with pytest.raises(FileNotFoundError):
        read_private(tmp_path / "missing", 100)
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    with pytest.raises(OSError, match="not a regular file"):
        read_private(fifo, 100)  # returns at once: opened without blocking
    (tmp_path / "link").symlink_to(good)
    with pytest.raises(OSError, match="symbolic link"):
        read_private(tmp_path / "link", 100)
    good.chmod(0o622)
    with pytest.raises(NotPrivate, match="writable by group and others"):
        read_private(good, 100)
    good.chmod(0o600)
    try:
        os.chown(good, 65534, -1)
    except PermissionError:
        pytest.skip("cannot give a file to another user here")
    with pytest.raises(NotPrivate, match="owned by user 65534"):
        read_private(good, 100)


def test_leftovers_older_than_the_age_are_removed(tmp_path):
    old, young = tmp_path / ".build-1", tmp_path / ".x.json.ab12.tmp"
    old.mkdir()
    young.write_text("")
    kept = tmp_path / "entry.json"
    kept.write_text("")
    os.utime(old, (0, 0))
    os.utime(kept, (0, 0))
    assert remove_leftovers(tmp_path, (".build-",), older_than=60) == [".build-1"]
    assert sorted(p.name for p in tmp_path.iterdir()) == [".x.json.ab12.tmp", "entry.json"]
    assert files.TEMPORARY_SUFFIX == ".tmp"


# --- read_input: the one reader of a user's input files -------------------------------------------------------------

from symlink.common.files import excerpt, read_input, read_input_text  # noqa: E402


def test_read_input_reads_a_regular_file_and_follows_a_link(tmp_path):
    (tmp_path / "a.csv").write_bytes(b"x,y\n1,2\n")
    os.symlink(tmp_path / "a.csv", tmp_path / "link.csv")
    assert read_input(tmp_path / "a.csv", 8, "csv") == b"x,y\n1,2\n"  # exactly at the limit
    assert read_input_text(tmp_path / "link.csv", 100, "csv") == "x,y\n1,2\n"


@pytest.mark.parametrize("kind, make, words", [
    ("folder", lambda p: p.mkdir(), "it is a folder, not a regular file"),
    ("fifo", lambda p: os.mkfifo(p), "it is a FIFO (named pipe), not a regular file"),
    ("missing", lambda p: None, "No such file or directory"),
    ("too large", lambda p: p.write_bytes(b"1" * 101), "is larger than 100 bytes"),
    ("unreadable", lambda p: (p.write_text("x"), p.chmod(0)), "Permission denied"),
])
def test_read_input_refuses_what_is_not_a_small_regular_file(kind, make, words, tmp_path):
    if kind == "unreadable" and hasattr(os, "geteuid") and os.geteuid() == 0:
        pytest.skip("root reads any file")
    path = tmp_path / "input"
    make(path)
    with pytest.raises(ValueError) as caught:
        read_input(path, 100, "linkage file")
    assert words in str(caught.value) and str(path) in str(caught.value), caught.value


def test_read_input_refuses_a_device_and_names_it():
    with pytest.raises(ValueError, match=r"^cannot read scene file /dev/zero: it is a character device, not a "
                                         r"regular file$"):
        read_input("/dev/zero", 1 << 20, "scene file")


def test_a_fifo_with_no_writer_is_refused_at_once(tmp_path):
    """Opened non-blocking: the open returns (a blocking open would wait for a writer forever)."""
    path = tmp_path / "pipe.toml"
    os.mkfifo(path)
    outcome = []
    worker = threading.Thread(target=lambda: outcome.append(pytest.raises(ValueError, read_input, path, 10)),
                              daemon=True)
    worker.start()
    worker.join(10)
    assert not worker.is_alive() and "FIFO" in str(outcome[0].value)


def test_read_input_stops_at_the_limit_when_the_file_grows(tmp_path, monkeypatch):
    """A size that fstat does not show (a file still being written, /proc) is caught by counting the bytes read."""
    path = tmp_path / "growing.csv"
    path.write_bytes(b"1" * 50)
    real_fstat = os.fstat
    monkeypatch.setattr(files.os, "fstat", lambda handle: os.stat_result(
        (*real_fstat(handle)[:6], 0, *real_fstat(handle)[7:])))  # st_size reported as 0
    with pytest.raises(ValueError, match="larger than 20 bytes"):
        read_input(path, 20)


def test_non_utf8_names_the_line(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_bytes(b"name = 'x'\n\xff\n")
    with pytest.raises(ValueError, match=r"bad\.toml:2: linkage file is not UTF-8 text"):
        read_input_text(path, 100, "linkage file")


def test_excerpt_cuts_hostile_text():
    assert excerpt("x" * 10_000) == repr("x" * 60) + "..."
    assert excerpt(list(range(10_000))) == "list of 10,000 items"
    assert excerpt("AB") == "'AB'"


def test_a_failed_write_names_the_users_file_not_the_temporary(tmp_path, monkeypatch):
    """A full disk fails os.write, which names no file: the error names the file asked for, with the reason."""
    def full(handle, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(files.os, "write", full)
    with pytest.raises(OSError) as caught:
        write_atomic(tmp_path / "out.png", b"x")
    assert caught.value.filename == str(tmp_path / "out.png") and caught.value.errno == errno.ENOSPC
    assert caught.value.strerror == os.strerror(errno.ENOSPC)
    assert os.listdir(tmp_path) == []  # and nothing left behind


def test_a_folder_that_cannot_be_written_is_named_with_the_file(tmp_path):
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        pytest.skip("root writes anywhere")
    (tmp_path / "locked").mkdir(mode=0o500)
    with pytest.raises(PermissionError) as caught:
        write_atomic(tmp_path / "locked" / "out.txt", "x")
    assert caught.value.filename == str(tmp_path / "locked" / "out.txt")


@pytest.mark.parametrize("data", [b"", b"abc", bytes(range(256)) * 1000])
def test_the_sha256_of_a_warm_command_is_hashlibs(data):
    """common.files.sha256 (CPython's own, without OpenSSL) digests as hashlib does, whole or in pieces."""
    import hashlib
    from symlink.common.files import sha256
    assert sha256(data).hexdigest() == hashlib.sha256(data).hexdigest()
    pieces = sha256()
    for start in range(0, len(data), 1000):
        pieces.update(data[start:start + 1000])
    assert pieces.hexdigest() == hashlib.sha256(data).hexdigest()
