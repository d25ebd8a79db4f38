"""``symlink studio`` on the command line: the URL with its token, Ctrl-C, the missing extra, bad input, --html."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import urllib.request
from pathlib import Path

import pytest

from interrupts import interruptible
from symlink.cli import main

ROOT = Path(__file__).resolve().parents[2]


def _environment() -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}


def test_the_server_prints_its_url_answers_it_and_stops_on_ctrl_c():
    pytest.importorskip("uvicorn", reason="the studio's server needs the studio extra (uvicorn)")
    from symlink.studio.server import free_port
    port = free_port()
    process = subprocess.Popen([sys.executable, "-m", "symlink", "studio", "--no-browser", "--port", str(port)],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=_environment(),
                               preexec_fn=interruptible)  # Ctrl-C as a terminal's, whatever runs the tests
    try:
        line = process.stdout.readline().strip()
        assert line.startswith(f"symlink studio: http://127.0.0.1:{port}/?token="), line
        token = line.split("token=", 1)[1]
        assert len(token) >= 24
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/?token={token}", timeout=30) as answer:
            assert answer.status == 200 and b"symlink studio" in answer.read()
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=30)
        assert refused.value.code == 403
        refused.value.close()
        process.send_signal(signal.SIGINT)
        _, errors = process.communicate(timeout=60)
    finally:
        if process.poll() is None:
            process.kill()
            process.communicate()
    assert process.returncode in (0, 130)
    assert "Traceback" not in errors and len(errors.strip().splitlines()) <= 1, errors


def test_without_the_studio_extra_it_says_what_to_install():
    code = ("import sys; sys.modules['starlette'] = None; from symlink.cli import main; "
            "sys.exit(main(['studio', '--no-browser']))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=_environment(),
                          timeout=120)
    assert done.returncode == 2
    assert done.stderr.strip() == ("symlink: error: symlink studio needs the studio extra: "
                                   "pip install 'symlink-kinematics[studio]'")


@pytest.mark.parametrize("arguments, words", [
    (["studio", "no-such-linkage", "--no-browser"], "no linkage 'no-such-linkage'"),
    (["studio", "--html", "out.html"], "needs NAME|FILE"),
    (["studio", "--port", "70000", "--no-browser"], "a port is 1 to 65535"),
])
def test_bad_input_is_one_line_and_exit_2(arguments, words, capsys, tmp_path, monkeypatch):
    pytest.importorskip("uvicorn", reason="the studio's server needs the studio extra (uvicorn)")
    monkeypatch.chdir(tmp_path)
    assert main(arguments) == 2
    errors = capsys.readouterr().err
    assert words in errors and len(errors.strip().splitlines()) == 1


def test_html_writes_one_self_contained_page(tmp_path, capsys):
    out = tmp_path / "fourbar.html"
    assert main(["studio", "--html", str(out), "fourbar"]) == 0
    page = out.read_text(encoding="utf-8")
    assert page.startswith("<!DOCTYPE html>") and "window.SYMLINK_EMBEDDED" in page
    assert 'src="static/' not in page and 'href="static/' not in page
    assert f"wrote {out}" in capsys.readouterr().out


def test_the_default_port_is_the_first_free_preferred_one():
    """The page's local storage belongs to its port: a studio started again should find the same one."""
    import socket
    pytest.importorskip("starlette", reason="the studio's server needs the studio extra (starlette)")
    from symlink.studio.server import PREFERRED_PORTS, free_port
    first = free_port(preferred=True)
    if first not in PREFERRED_PORTS:
        pytest.skip("every preferred port is taken on this machine")
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as held:
        held.bind(("127.0.0.1", first))
        held.listen()
        second = free_port(preferred=True)
    assert second != first
    assert second in PREFERRED_PORTS[PREFERRED_PORTS.index(first) + 1:] or second not in PREFERRED_PORTS
