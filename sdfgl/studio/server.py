"""The studio's local web server (tornado): the page, its assets and one websocket.

Security, as Jupyter does it: the server binds 127.0.0.1 on a free port; every request
needs the per-run token (``?token=`` in the URL the studio opens, then an HttpOnly cookie
set by the page), a ``Host`` header naming 127.0.0.1 or localhost at this port (a DNS
rebinding page has its own host name), and the websocket an ``Origin`` equal to the
server's own. Messages are JSON data: the server decodes documents with
:mod:`sdfgl.scene_io` (no code runs) and writes only the workspace's own file.

Websocket messages, page -> server: ``{"type": "doc", "gen", "doc"}`` (compile),
``{"type": "values", "values": {name: value}}`` (a slider moved: no compile),
``{"type": "save", "doc"}``, ``{"type": "python"}``, ``{"type": "export", "format"}``,
``{"type": "parametric", "x", "y", "z", "bounds"}``, ``{"type": "primitive", "kind", "fields",
"params"}`` (the primitives panel: an implicit, parametric or GLSL primitive with named parameters),
``{"type": "preview", "node", "gen", "doc"}`` (compile a node's subtree for its live preview). Server -> page:
``hello`` (the document, the file name), ``spec`` (the view spec, ``gen``, ``compiles``),
``error`` (``path``, ``message``, ``gen``, ``request``), ``saved``, ``python``, ``export``
(``file``, ``b64``),
``parametric`` (an implicit node), ``primitive`` (``node``, ``params``: a node and its
parameter table), ``preview`` (``node``, ``gen``, ``spec``: the preview's view spec, its
shader in the WebGL2 dialect and its live-parameter layout, ``previews``: the preview compile
count), ``values`` (live
parameters moved by a MIDI or OSC controller, :mod:`sdfgl.live`), ``failed``.
"""
from __future__ import annotations

import asyncio
import base64
import html
import json
import secrets
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import TYPE_CHECKING, Any
from urllib.parse import urlsplit

from ..errors import SdfglError
from ..extras import require_extra
from .palette import palette
from .workspace import Workspace, error_of

if TYPE_CHECKING:
    from ..live import LiveControl

ASSETS = Path(__file__).resolve().parent / "assets"   # built by js/build.sh (npm run build)
PAGE = Path(__file__).resolve().parent / "page.html"
ASSET_TYPES = {".js": "text/javascript", ".css": "text/css"}
WEB_FILES = {"viewer.js": "viewer.js", "viewer.css": "style.css"}   # served from sdfgl/web
COOKIE = "sdfgl-studio-token-{port}"  # cookies do not tell ports apart: one name a server


def _json_value(v: Any) -> Any:
    """A parameter value as JSON (a 3-vector as a list)."""
    return v.tolist() if hasattr(v, "tolist") else float(v)


def _page(boot: dict[str, Any]) -> str:
    from ..web.html import script_safe_json
    text = PAGE.read_text(encoding="utf-8")
    return text.replace("__BOOT__", script_safe_json(boot)).replace("__TITLE__", html.escape(boot["title"]))


class Studio:
    """A running studio server on one :class:`Workspace` (start with :meth:`start`)."""

    def __init__(self, workspace: Workspace, host: str = "127.0.0.1", port: int = 0,
                 live: LiveControl | None = None) -> None:
        require_extra("studio", "tornado", purpose="sdfgl studio")
        self.workspace = workspace
        self.live = live
        self.sockets: set[Any] = set()  # the open pages
        if live is not None:  # values from controllers reach the pages through this server's loop
            live.deferred = True
            live.wake = self.wake
            live.use(list(workspace.document.params.values()))
        self.host = host
        self.port = port
        self.token = secrets.token_urlsafe(24)
        self.loop: asyncio.AbstractEventLoop | None = None
        self._thread: threading.Thread | None = None
        self._ready = threading.Event()
        self._error: BaseException | None = None
        self._server: Any = None
        # one worker: compiles and renders run in order, off the server's event loop
        self.worker = ThreadPoolExecutor(1, thread_name_prefix="sdfgl-studio")

    @property
    def origin(self) -> str:
        """The server's own origin, ``http://127.0.0.1:PORT``."""
        return f"http://{self.host}:{self.port}"

    @property
    def url(self) -> str:
        """The page's URL with the token."""
        return f"{self.origin}/?token={self.token}"

    def _repr_html_(self) -> str:
        """The page in an iframe: ``sg.studio(scene)`` as the last line of a notebook cell shows the editor."""
        return (f'<iframe src="{html.escape(self.url)}" width="100%" height="720" '
                f'style="border: 1px solid #ccc"></iframe>')

    def allowed_hosts(self) -> set[str]:
        """The Host headers the server answers (no DNS rebinding)."""
        return {f"127.0.0.1:{self.port}", f"localhost:{self.port}", f"[::1]:{self.port}"}

    def allowed_origins(self) -> set[str]:
        """The websocket Origins the server accepts: its own."""
        return {f"http://{h}" for h in self.allowed_hosts()}

    def token_ok(self, given: str | None) -> bool:
        """Whether ``given`` is this run's token (compared in constant time)."""
        return bool(given) and secrets.compare_digest(given.encode(), self.token.encode())

    # -- live control -------------------------------------------------------------------
    def wake(self) -> None:
        """Called by the live control's threads when a controller moved a parameter."""
        if self.loop is not None:
            self.loop.call_soon_threadsafe(self.apply_live)

    def apply_live(self) -> None:
        """Take the controllers' values (on the server's loop) and send them to every page:
        uniforms only, no recompile."""
        assert self.live is not None
        changed = self.live.apply_pending()
        known = self.workspace.doc.get("params", {})
        values = {self.live.key(p): _json_value(p.value) for p in changed if self.live.key(p) in known}
        if not values:
            return
        self.workspace.set_values(values)
        for socket in list(self.sockets):
            socket.send({"type": "values", "values": values})

    def compiled(self) -> None:
        """After a compile: the live control drives the new document's parameters."""
        if self.live is not None:
            self.live.use(list(self.workspace.document.params.values()))

    # -- running ------------------------------------------------------------------------
    def start(self) -> "Studio":
        """Start serving on a background thread; returns when the port is bound."""
        self._thread = threading.Thread(target=self._run, name="sdfgl-studio-server", daemon=True)
        self._thread.start()
        self._ready.wait()
        if self._error is not None:
            raise SdfglError(f"sdfgl studio could not start its server: {self._error}") from self._error
        return self

    def _run(self) -> None:
        from tornado.httpserver import HTTPServer
        from tornado.netutil import bind_sockets
        self.loop = asyncio.new_event_loop()
        asyncio.set_event_loop(self.loop)
        try:
            sockets = bind_sockets(self.port, self.host)
            self.port = sockets[0].getsockname()[1]
            self._server = HTTPServer(make_app(self))
            self._server.add_sockets(sockets)
        except BaseException as exc:  # noqa: BLE001 - reported by start()
            self._error = exc
            self._ready.set()
            return
        self._ready.set()
        self.loop.run_forever()
        self.loop.close()

    def stop(self) -> None:
        """Stop the server, its worker and its live control (if any)."""
        if self.live is not None:
            self.live.stop()
        if self.loop is not None and self._thread is not None and self._thread.is_alive():
            def halt() -> None:
                self._server.stop()
                assert self.loop is not None
                self.loop.stop()
            self.loop.call_soon_threadsafe(halt)
            self._thread.join(10)
        self.worker.shutdown(wait=False, cancel_futures=True)

    def __enter__(self) -> "Studio":
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.stop()


def make_app(studio: Studio) -> Any:
    """The tornado application of ``studio``: ``/``, ``/assets/NAME`` (``viewer.js`` is the browser
    viewer's own file, :mod:`sdfgl.web`), ``/stats`` (the compile counts), ``/ws``."""
    import tornado.web
    import tornado.websocket

    class Guarded(tornado.web.RequestHandler):
        def prepare(self) -> None:
            if self.request.host not in studio.allowed_hosts():
                raise tornado.web.HTTPError(403, "unknown Host")
            given = self.get_query_argument("token", None) or self.get_cookie(COOKIE.format(port=studio.port))
            if not studio.token_ok(given):
                raise tornado.web.HTTPError(403, "missing or wrong token")

        def set_default_headers(self) -> None:
            self.set_header("X-Content-Type-Options", "nosniff")
            self.set_header("Cache-Control", "no-store")

    class PageHandler(Guarded):
        def get(self) -> None:
            self.set_cookie(COOKIE.format(port=studio.port), studio.token, httponly=True, samesite="Strict")
            self.set_header("Content-Security-Policy", "default-src 'self'; img-src 'self' data: blob:; "
                                                       "style-src 'self' 'unsafe-inline'; connect-src 'self'")
            path = studio.workspace.path
            self.write(_page({"title": f"sdfgl studio: {path.name}" if path else "sdfgl studio",
                              "palette": palette(), "file": path.name if path else None}))

    class AssetHandler(Guarded):
        def get(self, name: str) -> None:
            if name in WEB_FILES:  # the browser viewer's own files, not copies
                from ..web import assets
                text = assets.read(WEB_FILES[name])
                suffix = Path(name).suffix
            else:
                target = ASSETS / name
                if target.parent != ASSETS or target.suffix not in ASSET_TYPES or not target.is_file():
                    raise tornado.web.HTTPError(404)
                text = target.read_text(encoding="utf-8")
                suffix = target.suffix
            self.set_header("Content-Type", ASSET_TYPES[suffix])
            self.write(text)

    class StatsHandler(Guarded):
        def get(self) -> None:
            self.write({"compiles": studio.workspace.compiles, "previews": studio.workspace.preview_compiles})

    class NoIcon(Guarded):
        def get(self) -> None:
            self.set_status(204)

    class Socket(tornado.websocket.WebSocketHandler):
        def prepare(self) -> None:
            Guarded.prepare(self)  # type: ignore[arg-type]

        def check_origin(self, origin: str) -> bool:
            return origin in studio.allowed_origins() and urlsplit(origin).netloc == self.request.host

        def open(self) -> None:
            studio.sockets.add(self)
            s = studio.workspace
            self.send({"type": "hello", "doc": s.doc, "file": s.path.name if s.path else None,
                       "compiles": s.compiles})

        def on_close(self) -> None:
            studio.sockets.discard(self)

        def send(self, msg: dict[str, Any]) -> None:
            try:
                self.write_message(json.dumps(msg, allow_nan=False))
            except tornado.websocket.WebSocketClosedError:
                pass

        async def on_message(self, message: str | bytes) -> None:
            try:
                msg = json.loads(message)
                kind = msg.get("type") if isinstance(msg, dict) else None
            except ValueError:
                kind = None
            if kind is None:
                self.send({"type": "failed", "message": "a message must be a JSON object with 'type'"})
                return
            loop = asyncio.get_running_loop()
            s = studio.workspace
            try:
                if kind == "doc":
                    spec = await loop.run_in_executor(studio.worker, s.compile, msg.get("doc"))
                    studio.compiled()
                    self.send({"type": "spec", "gen": msg.get("gen"), "spec": spec, "compiles": s.compiles})
                elif kind == "values":
                    s.set_values(dict(msg.get("values") or {}))
                elif kind == "save":
                    path = await loop.run_in_executor(studio.worker, s.save, msg.get("doc"))
                    self.send({"type": "saved", "file": path.name})
                elif kind == "python":
                    self.send({"type": "python", "code": s.python()})
                elif kind == "parametric":
                    node = await loop.run_in_executor(studio.worker, s.parametric, msg.get("x"), msg.get("y"),
                                                      msg.get("z"), msg.get("bounds"))
                    self.send({"type": "parametric", "node": node})
                elif kind == "primitive":
                    made = await loop.run_in_executor(studio.worker, s.primitive, msg.get("kind"), msg.get("fields"),
                                                      msg.get("params"))
                    self.send({"type": "primitive", **made})
                elif kind == "preview":
                    spec = await loop.run_in_executor(studio.worker, s.preview, msg.get("doc"))
                    self.send({"type": "preview", "node": msg.get("node"), "gen": msg.get("gen"), "spec": spec,
                               "previews": s.preview_compiles})
                elif kind == "export":
                    name, data = await loop.run_in_executor(studio.worker, s.export, msg.get("format"))
                    self.send({"type": "export", "file": name, "b64": base64.b64encode(data).decode("ascii")})
                else:
                    self.send({"type": "failed", "message": f"unknown message type {kind!r}"})
            except SdfglError as exc:
                err = error_of(exc).to_json()
                self.send({**err, "gen": msg.get("gen"), "request": kind, "node": msg.get("node")})
            except (TypeError, ValueError, AttributeError) as exc:  # a message of the wrong shape
                self.send({"type": "error", "path": "", "message": f"bad {kind!r} message: {exc}",
                           "gen": msg.get("gen"), "request": kind, "node": msg.get("node")})

    return tornado.web.Application([
        (r"/", PageHandler),
        (r"/stats", StatsHandler),
        (r"/favicon\.ico", NoIcon),
        (r"/ws", Socket),
        (r"/assets/([A-Za-z0-9_.-]+)", AssetHandler),
    ], websocket_max_message_size=32 * 1024 * 1024)
