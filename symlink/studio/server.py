"""The studio's web server: a Starlette app on uvicorn, for one user on this machine.

Guarded as Jupyter guards its server, because a page on any web site can send requests to a port on
127.0.0.1:

* it listens on ``127.0.0.1`` only;
* every request carries a random token (:func:`secrets.token_urlsafe`): ``?token=`` on the page's URL (the
  answer sets it as a ``SameSite=Strict`` cookie), then the cookie or an ``X-Symlink-Token`` header;
  without it: 403;
* a request whose ``Host`` is not ``127.0.0.1:PORT`` or ``localhost:PORT`` (DNS rebinding), or whose
  ``Origin`` is another site's: 403;
* a path outside the app: 404.

The API answers JSON to POSTs (``/api/structure``, ``/api/derive``, ``/api/solver``, ``/api/analyze``, ``/api/open``) and
files to ``/api/export?format=...``; ``/api/synthesize`` starts a path synthesis in a worker process
(:mod:`symlink.studio.jobs`), ``GET /api/synthesize/<id>`` says how it goes and gives its result,
``DELETE /api/synthesize/<id>`` cancels it; every ``ValueError`` of the library is a JSON ``{"error": ...}`` with
status 400 (a request that is no drawing) or 422 (a drawing that is no linkage), never a traceback.
The work is :mod:`symlink.studio.drawing`'s; this module only routes and guards.
"""
from __future__ import annotations

import io
import secrets
import socket
import zipfile
from http.cookies import SimpleCookie
from pathlib import Path
from typing import Any, Awaitable, Callable, Mapping
from urllib.parse import parse_qs

from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Route
from starlette.concurrency import run_in_threadpool

from ..common.numbers import json_data
from . import design, drawing
from .jobs import Jobs

__all__ = ["create_app", "free_port", "PREFERRED_PORTS", "serve", "TOKEN_COOKIE", "TOKEN_HEADER", "STATIC", "MAX_BODY"]

STATIC = Path(__file__).resolve().parent / "static"
TOKEN_COOKIE = "symlink_studio_token"
TOKEN_HEADER = "x-symlink-token"
#: The largest request body read (a drawing, or a file's text to open).
MAX_BODY = 2 << 20
_TYPES = {".html": "text/html; charset=utf-8", ".js": "text/javascript; charset=utf-8",
          ".css": "text/css; charset=utf-8", ".woff2": "font/woff2", ".md": "text/plain; charset=utf-8"}
_MEDIA = {".tex": "text/x-tex", ".py": "text/x-python", ".c": "text/x-c", ".h": "text/x-c", ".m": "text/plain",
          ".js": "text/javascript", ".toml": "application/toml", ".json": "application/json",
          ".html": "text/html; charset=utf-8"}


#: The ports tried first, in order: the page's local storage belongs to its origin (host and port), so a
#: studio started again on the same port finds the last drawing there.
PREFERRED_PORTS = range(8765, 8775)


def _bindable(port: int) -> bool:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        try:
            probe.bind(("127.0.0.1", port))
        except OSError:
            return False
        return True


def free_port(preferred: bool = False) -> int:
    """A port on 127.0.0.1 that nothing listens on now: with ``preferred``, the first free one of
    :data:`PREFERRED_PORTS` if any, else one the system picks."""
    for port in PREFERRED_PORTS if preferred else ():
        if _bindable(port):
            return port
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


class _Guard:
    """ASGI middleware: Host, Origin and token checked before anything else runs."""

    def __init__(self, app: Callable, port: int, token: str) -> None:
        self.app, self.token = app, token
        self.hosts = {f"127.0.0.1:{port}", f"localhost:{port}"}
        self.origins = {f"http://{host}" for host in self.hosts}

    async def __call__(self, scope: dict, receive: Callable, send: Callable) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope.get("headers", [])}
        problem = None
        if headers.get("host") not in self.hosts:
            problem = "this server answers requests to 127.0.0.1 or localhost on its own port only"
        elif "origin" in headers and headers["origin"] not in self.origins:
            problem = "requests from other sites are refused"
        elif not self._token_ok(scope, headers):
            problem = "a valid token is needed: open the URL that 'symlink studio' printed"
        if problem is not None:
            await JSONResponse({"error": problem}, status_code=403)(scope, receive, send)
            return
        await self.app(scope, receive, send)

    def _token_ok(self, scope: dict, headers: Mapping[str, str]) -> bool:
        given = []
        query = parse_qs(scope.get("query_string", b"").decode("latin-1"))
        given += query.get("token", [])
        if TOKEN_HEADER in headers:
            given.append(headers[TOKEN_HEADER])
        if "cookie" in headers:
            cookie = SimpleCookie()
            try:
                cookie.load(headers["cookie"])
            except Exception:  # noqa: BLE001 - a malformed cookie header is no token
                pass
            if TOKEN_COOKIE in cookie:
                given.append(cookie[TOKEN_COOKIE].value)
        return any(secrets.compare_digest(value.encode(), self.token.encode()) for value in given)


def _error(message: str, status: int, **more: Any) -> JSONResponse:
    return JSONResponse({"error": message, **more}, status_code=status)


async def _body(request: Request) -> Any:
    """The request's JSON; ``ValueError`` for a body too large or not JSON."""
    data = b""
    async for chunk in request.stream():
        data += chunk
        if len(data) > MAX_BODY:
            raise ValueError(f"the request is larger than {MAX_BODY // (1 << 20)} MB")
    return json_data(data, "the request")  # strict: numbers range-checked, keys given once, nesting bounded


def _api(work: Callable[[Any, Request], Any]) -> Callable[[Request], Awaitable[Response]]:
    """An endpoint: the body read as JSON, ``work`` run in a worker thread, errors as JSON messages."""
    async def endpoint(request: Request) -> Response:
        try:
            data = await _body(request)
        except ValueError as error:
            return _error(str(error), 400)
        try:
            result = await run_in_threadpool(work, data, request)
        except drawing.StructureError as error:
            return _error(str(error), 422, mobility=error.mobility)
        except RecursionError:
            return _error("the request is nested too deeply", 400)
        except ValueError as error:
            return _error(" ".join(str(error).split())[:2000], 422 if isinstance(data, dict) else 400)
        except Exception as error:  # noqa: BLE001 - a bug: a message, never a traceback in the page
            return _error(f"internal error ({type(error).__name__}: {error}); please report it", 500)
        return result if isinstance(result, Response) else JSONResponse(result)
    return endpoint


def _open(data: Any, request: Request) -> dict[str, Any]:
    if not isinstance(data, dict) or "source" not in data:
        raise ValueError('give {"source": a catalog or atlas name, a linkage file\'s text, pylinkage JSON or a '
                         'Pyslvs expression}')
    return drawing.open_source(data["source"], data.get("kind", "auto"))


def files_response(files: Mapping[str, bytes], stem: str) -> Response:
    """One file as itself, several as a zip archive (members in name order, fixed dates)."""
    if len(files) == 1:
        (name, data), = files.items()
        media = _MEDIA.get(Path(name).suffix, "application/octet-stream")
        return Response(data, media_type=media, headers={"Content-Disposition": f'attachment; filename="{name}"'})
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for name in sorted(files):
            archive.writestr(zipfile.ZipInfo(name, (1980, 1, 1, 0, 0, 0)), files[name])
    return Response(buffer.getvalue(), media_type="application/zip",
                    headers={"Content-Disposition": f'attachment; filename="{stem}.zip"'})


def _export(data: Any, request: Request) -> Response:
    fmt = request.query_params.get("format", "")
    if fmt == "html":
        from .page import standalone_page
        found = drawing.drawn_linkage(drawing.description(data))
        files = {f"{found.linkage.name.replace(' ', '_')}.html": standalone_page(data).encode()}
    else:
        files = drawing.export_bytes(data, fmt)
    stem = Path(sorted(files)[0]).stem
    return files_response(files, f"{stem}-{fmt}")


def create_app(port: int, token: str, initial: Mapping[str, Any] | None = None) -> Starlette:
    """The studio app for a server on ``127.0.0.1:port`` guarded by ``token``; ``initial`` is the drawing the
    page opens with (a linkage named on the command line), else the page's own last one."""
    start = dict(initial) if initial is not None else None

    async def page(request: Request) -> Response:
        response = FileResponse(STATIC / "index.html", media_type=_TYPES[".html"],
                                headers={"Cache-Control": "no-store"})
        response.set_cookie(TOKEN_COOKIE, token, httponly=True, samesite="strict", path="/")
        return response

    async def static(request: Request) -> Response:
        relative = request.path_params["path"]
        target = (STATIC / relative).resolve()
        if STATIC not in target.parents or not target.is_file() or target.suffix not in _TYPES:
            return _error("not found", 404)
        return FileResponse(target, media_type=_TYPES[target.suffix])

    async def initial_drawing(request: Request) -> Response:
        return JSONResponse({"drawing": start})

    jobs = Jobs()

    def synthesize(data: Any, request: Request) -> Response:
        checked = design.synthesis_request(data)  # bad input answered at once, before a process starts
        try:
            key = jobs.start("synthesis", checked)
        except ValueError as error:
            return _error(str(error), 409)
        return JSONResponse(jobs.status(key), status_code=202)

    async def synthesis_status(request: Request) -> Response:
        found = jobs.status(request.path_params["key"])
        return _error("no such synthesis", 404) if found is None else JSONResponse(found)

    async def synthesis_cancel(request: Request) -> Response:
        found = await run_in_threadpool(jobs.cancel, request.path_params["key"])
        return _error("no such synthesis", 404) if found is None else JSONResponse(found)

    async def not_found(request: Request, exc: Exception) -> Response:
        return _error("not found", 404)

    async def not_allowed(request: Request, exc: Exception) -> Response:
        return _error("method not allowed", 405)

    routes = [
        Route("/", page, methods=["GET"]),
        Route("/static/{path:path}", static, methods=["GET"]),
        Route("/api/initial", initial_drawing, methods=["GET"]),
        Route("/api/structure", _api(lambda data, request: drawing.structure(data)), methods=["POST"]),
        Route("/api/derive", _api(lambda data, request: drawing.derivation(data)), methods=["POST"]),
        Route("/api/solver", _api(lambda data, request: drawing.solver(data)), methods=["POST"]),
        Route("/api/analyze", _api(lambda data, request: design.analysis(data)), methods=["POST"]),
        Route("/api/tolerance", _api(lambda data, request: design.tolerance_band(data)), methods=["POST"]),
        Route("/api/synthesize", _api(synthesize), methods=["POST"]),
        Route("/api/synthesize/{key:str}", synthesis_status, methods=["GET"]),
        Route("/api/synthesize/{key:str}", synthesis_cancel, methods=["DELETE"]),
        Route("/api/open", _api(_open), methods=["POST"]),
        Route("/api/export", _api(_export), methods=["POST"]),
    ]
    app = Starlette(routes=routes, exception_handlers={404: not_found, 405: not_allowed})
    app.state.jobs = jobs
    app.add_middleware(_Guard, port=port, token=token)
    return app


def serve(port: int | None = None, initial: Mapping[str, Any] | None = None, open_browser: bool = True,
          announce: Callable[[str], None] = print) -> None:
    """Run the studio until Ctrl-C: announce its URL (with the token) and open it in the browser."""
    import uvicorn
    port = port or free_port(preferred=True)
    token = secrets.token_urlsafe(24)
    app = create_app(port, token, initial)
    config = uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning", access_log=False,
                            lifespan="off")
    url = f"http://127.0.0.1:{port}/?token={token}"

    class Server(uvicorn.Server):
        """uvicorn's server, which says its URL (and opens the browser) once it listens."""

        async def startup(self, sockets: Any = None) -> None:
            await super().startup(sockets)
            if self.started:
                announce(f"symlink studio: {url}")
                if open_browser:
                    import threading
                    import webbrowser
                    threading.Thread(target=webbrowser.open, args=(url,), daemon=True).start()

    Server(config).run()
