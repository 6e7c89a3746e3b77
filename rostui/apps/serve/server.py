"""The web server of `rostui serve`: textual-serve's, with the page, the sessions and their apps kept in hand.

textual-serve gives the protocol between the page and an app (its ``AppService``: packets over the
app's stdin and stdout, Textual's web driver at the other end) and the static files (xterm.js, the
font).  Here, around them:

- every request passes :class:`~rostui.apps.serve.access.Access` (token, Host, Origin) first;
- the page is rostui's own (:mod:`rostui.apps.serve.page`): nothing from another site;
- a session is refused beyond ``max_sessions``, with the reason on the page and one line here;
- what a page sends is read strictly (:mod:`rostui.apps.serve.messages`): sizes clamped, anything
  else ends that session;
- each app leads a process group of its own and ends when its page goes: asked to quit, then
  SIGTERM, then SIGKILL (:func:`~rostui.apps.serve.processes.end_app`);
- Ctrl-C, SIGTERM and SIGHUP (serve's terminal closed) stop the server the same way, after every
  app has ended.
"""

from __future__ import annotations

import asyncio
import logging
import shlex
import signal
import sys
import time
from typing import Any, Awaitable, Optional, Sequence

import psutil
from aiohttp import WSCloseCode, WSMsgType, web
from aiohttp.web_runner import GracefulExit
from textual_serve.app_service import AppService
from textual_serve.server import Server

from rostui.apps.serve.access import TOKEN_PARAMETER, Access, Refusal
from rostui.apps.serve.messages import BadMessage, Focus, Ping, Resize, Stdin, parse, size_from_query
from rostui.apps.serve.page import SCRIPT, SCRIPT_PATH, SECURITY_HEADERS, STYLE, STYLE_PATH, page
from rostui.apps.serve.processes import TERM_GRACE, end_app, start_app

#: The largest message a page may send (a paste), in bytes.
MAX_MESSAGE_BYTES = 1 << 20

#: Seconds an app may leave its input unread (its pipe full) before its session is ended.
INPUT_TIMEOUT = 10.0

#: Seconds between two lines about the same kind of refusal in serve's terminal.
NOTE_INTERVAL = 10.0


class Notes:
    """One line in serve's terminal for each kind of event, at most every :data:`NOTE_INTERVAL` seconds."""

    def __init__(self) -> None:
        self._last: dict[str, float] = {}
        self._held: dict[str, int] = {}

    def say(self, kind: str, line: str) -> None:
        """Print ``line`` unless a line of ``kind`` was printed lately (those are counted in the next one)."""
        now = time.monotonic()
        if now - self._last.get(kind, -NOTE_INTERVAL) < NOTE_INTERVAL:
            self._held[kind] = self._held.get(kind, 0) + 1
            return
        held = self._held.pop(kind, 0)
        self._last[kind] = now
        print(line + (f" (and {held} more like it)" if held else ""), flush=True)


class OneLineFormatter(logging.Formatter):
    """Log records as ``rostui serve: MESSAGE``, an exception as its last line, never a traceback."""

    def format(self, record: logging.LogRecord) -> str:
        """The record's one line."""
        line = f"rostui serve: {record.getMessage()}"
        if record.exc_info and record.exc_info[1] is not None:
            error = record.exc_info[1]
            line += f": {type(error).__name__}: {error}"
        return line


class AppSession(AppService):
    """One page's app: started as ``argv`` in a process group of its own, its screen sent while the page is there."""

    def __init__(self, argv: Sequence[str], websocket: web.WebSocketResponse, server: AppServer) -> None:
        super().__init__(shlex.join(argv), write_bytes=self._send_bytes, write_str=self._send_str,
                         close=self._close_page, download_manager=server.download_manager)
        self.argv = list(argv)
        self.websocket = websocket
        self.quit_grace = server.quit_grace
        self.ended: Optional[asyncio.Task[None]] = None

    async def _open_app_process(self, width: int = 80, height: int = 24) -> asyncio.subprocess.Process:
        process = await start_app(self.argv, self._build_environment(width=width, height=height))
        assert process.stdin is not None
        self._process, self._stdin = process, process.stdin
        return process

    async def _send_bytes(self, data: bytes) -> None:
        # The app's output is read to its end whether or not the page is still there (an app that cannot
        # write cannot quit either).
        if not self.websocket.closed:
            try:
                await self.websocket.send_bytes(data)
            except ConnectionError:
                pass

    async def _send_str(self, data: str) -> None:
        if not self.websocket.closed:
            try:
                await self.websocket.send_str(data)
            except ConnectionError:
                pass

    async def _close_page(self) -> None:
        await self.websocket.close()

    async def to_app(self, sending: Awaitable[bool]) -> bool:
        """Hand the app a packet; False when it has not taken its input for :data:`INPUT_TIMEOUT` seconds."""
        try:
            return await asyncio.wait_for(sending, INPUT_TIMEOUT)
        except asyncio.TimeoutError:
            return False

    @property
    def app_pid(self) -> Optional[int]:
        """The app's process id, once it has started."""
        return None if self._process is None else self._process.pid

    async def stop(self) -> None:
        """Ask the app to quit; SIGTERM, then SIGKILL if it will not; wait until its output is read to the end."""
        reading, process = self._task, self._process
        if reading is None or process is None:
            return
        self._task = None
        await self._download_manager.cancel_app_downloads(app_service_id=self.app_service_id)
        asking = asyncio.ensure_future(self.to_app(self.send_meta({"type": "quit"})))
        await end_app(process, self.quit_grace, TERM_GRACE)
        asking.cancel()
        await asyncio.wait({reading}, timeout=TERM_GRACE)  # a process it started may still hold its stdout
        reading.cancel()
        await asyncio.gather(reading, asking, return_exceptions=True)


class AppServer(Server):
    """Serves ``argv`` (a rostui app's command line) to the pages that hold ``access``'s token.

    At most ``max_sessions`` pages at once; an app whose page went has ``quit_grace`` seconds to quit.
    """

    def __init__(self, argv: Sequence[str], *, host: str, port: int, public_url: str, title: str,
                 announce: Sequence[str], access: Access, max_sessions: int, quit_grace: float) -> None:
        super().__init__(shlex.join(argv), host=host, port=port, title=title, public_url=public_url)
        self.argv = list(argv)
        self.announce = list(announce)
        self.access = access
        self.max_sessions = max_sessions
        self.quit_grace = quit_grace
        self.sessions: set[AppSession] = set()
        self.notes = Notes()
        self.stopping = False

    # -- logging and the start -------------------------------------------------------------------------
    def initialize_logging(self) -> None:
        """Warnings and errors of the server and its libraries, one line each, on stdout."""
        handler = logging.StreamHandler(sys.stdout)
        handler.setFormatter(OneLineFormatter())
        logging.basicConfig(level=logging.WARNING, handlers=[handler], force=True)

    async def on_startup(self, app: web.Application) -> None:
        """Say where the app is served, and that the token is required."""
        for line in self.announce:
            print(line, flush=True)

    async def _make_app(self) -> web.Application:
        app = web.Application(middlewares=[self._guard], client_max_size=MAX_MESSAGE_BYTES)
        app.add_routes([
            web.get("/", self.handle_index, name="index"),
            web.get("/ws", self.handle_websocket, name="websocket"),
            web.get("/download/{key}", self.handle_download, name="download"),
            web.get(STYLE_PATH, self._style),
            web.get(SCRIPT_PATH, self._script),
            web.static("/static", self.statics_path, name="static"),
        ])
        app.on_startup.append(self.on_startup)
        app.on_shutdown.append(self.on_shutdown)
        return app

    def serve(self, debug: bool = False) -> None:
        """Run until Ctrl-C, SIGTERM or SIGHUP; then end every session's app and return."""
        self.debug = debug
        self.initialize_logging()
        loop = asyncio.new_event_loop()
        asyncio.set_event_loop(loop)
        for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            loop.add_signal_handler(signum, self.request_exit)
        try:
            web.run_app(self._make_app(), host=self.host, port=self.port, handle_signals=False, loop=loop,
                        print=None, shutdown_timeout=self.quit_grace + 2 * TERM_GRACE + 5.0)
        finally:
            loop.close()

    def request_exit(self) -> None:
        """The first stop signal stops the server; later ones only say that it is stopping."""
        if self.stopping:
            self.notes.say("stopping", "rostui serve: stopping: the apps are ending")
            return
        self.stopping = True
        raise GracefulExit()

    # -- every request ---------------------------------------------------------------------------------
    @web.middleware
    async def _guard(self, request: web.Request, handler: Any) -> web.StreamResponse:
        """Refuse what :class:`Access` refuses; move the token from the page's URL into its cookie."""
        query_token = request.query.get(TOKEN_PARAMETER)
        refusal = self.access.check(request.headers.get("Host"), request.headers.get("Origin"), query_token,
                                    request.cookies.get(self.access.cookie))
        if refusal is not None:
            return self._refuse(request, refusal)
        if query_token is not None and request.path == "/":
            rest = request.rel_url.with_query({k: v for k, v in request.query.items() if k != TOKEN_PARAMETER})
            # relative, so that a proxy serving the page under a path of its own keeps it
            location = "./" + (f"?{rest.query_string}" if rest.query_string else "")
            response: web.StreamResponse = web.HTTPSeeOther(location)
            response.set_cookie(self.access.cookie, self.access.token, httponly=True, samesite="Strict", path="/",
                                secure=self.access.public_scheme == "https")
        else:
            response = await handler(request)
        if not response.prepared:
            response.headers.update(SECURITY_HEADERS)
        return response

    def _refuse(self, request: web.Request, refusal: Refusal) -> web.Response:
        peer = request.remote or "?"
        self.notes.say(f"refused {refusal.check}", f"{refusal.reason} (refused {request.method[:10]!r} "
                                                    f"{request.path[:40]!r} from {peer})")
        return web.Response(status=refusal.status, text=refusal.reason + "\n", headers=SECURITY_HEADERS)

    # -- the page ---------------------------------------------------------------------------------------
    async def handle_index(self, request: web.Request) -> web.Response:
        """The page: the app's screen, once its websocket is open."""
        try:
            font_size = int(request.query.get("fontsize", "16"))
        except ValueError:
            font_size = 16
        return web.Response(text=page(self.title, font_size), content_type="text/html")

    async def _style(self, request: web.Request) -> web.Response:
        return web.Response(text=STYLE, content_type="text/css")

    async def _script(self, request: web.Request) -> web.Response:
        return web.Response(text=SCRIPT, content_type="text/javascript")

    # -- sessions ---------------------------------------------------------------------------------------
    async def handle_websocket(self, request: web.Request) -> web.WebSocketResponse:
        """One page's session: its app starts, gets the page's keys and sizes, and ends when the page goes."""
        websocket = web.WebSocketResponse(heartbeat=15, max_msg_size=MAX_MESSAGE_BYTES)
        await websocket.prepare(request)
        if self.stopping or len(self.sessions) >= self.max_sessions:
            await self._refuse_session(websocket, request)
            return websocket
        session = AppSession(self.argv, websocket, self)
        self.sessions.add(session)
        session.ended = asyncio.ensure_future(self._run_session(session, request))
        session.ended.add_done_callback(lambda _task: self.sessions.discard(session))
        await asyncio.shield(session.ended)  # a handler cancelled at shutdown still lets its app end
        return websocket

    async def _refuse_session(self, websocket: web.WebSocketResponse, request: web.Request) -> None:
        if self.stopping:
            reason = "rostui serve: the server is stopping"
        else:
            reason = (f"rostui serve: {len(self.sessions)} tabs are open, the most this server allows "
                      f"(--max-sessions {self.max_sessions}); close one and reload")
        self.notes.say("session limit", f"{reason} (refused a tab from {request.remote or '?'})")
        await websocket.close(code=WSCloseCode.TRY_AGAIN_LATER, message=reason.encode()[:123])

    async def _run_session(self, session: AppSession, request: web.Request) -> None:
        websocket = session.websocket
        try:
            await session.start(*size_from_query(request.query.get("width"), request.query.get("height")))
            assert session._task is not None
            session._task.add_done_callback(lambda _task: asyncio.ensure_future(websocket.close()))
            problem = await self._relay(websocket, session)
            if problem is not None:
                code, reason = problem
                self.notes.say(f"bad {code}", f"{reason} (ended a tab from {request.remote or '?'})")
                await websocket.close(code=code, message=reason.encode()[:123])
        except OSError as exc:
            self.notes.say("start", f"rostui serve: cannot start {shlex.join(self.argv)}: {exc}")
            await websocket.close(code=WSCloseCode.INTERNAL_ERROR, message=b"rostui serve: the app did not start")
        finally:
            await session.stop()

    async def _relay(self, websocket: web.WebSocketResponse,
                     session: AppSession) -> Optional[tuple[WSCloseCode, str]]:
        """Hand the page's messages to the app until the page goes (None) or sends what it never sends."""
        async for message in websocket:
            if message.type == WSMsgType.ERROR:
                return WSCloseCode.MESSAGE_TOO_BIG, f"rostui serve: a message the page does not send ({message.data})"
            if message.type != WSMsgType.TEXT:
                return WSCloseCode.UNSUPPORTED_DATA, "rostui serve: a binary message the page does not send"
            try:
                parsed = parse(message.data)
            except BadMessage as exc:
                return WSCloseCode.UNSUPPORTED_DATA, f"rostui serve: {exc}"
            if isinstance(parsed, Stdin):
                taken = await session.to_app(session.send_bytes(parsed.text.encode("utf-8", "replace")))
            elif isinstance(parsed, Resize):
                taken = await session.to_app(session.send_meta({"type": "resize", "width": parsed.width,
                                                                "height": parsed.height}))
            elif isinstance(parsed, Focus):
                taken = await session.to_app(session.send_meta({"type": "focus" if parsed.focused else "blur"}))
            else:
                assert isinstance(parsed, Ping)
                await websocket.send_json(["pong", parsed.text])
                taken = True
            if not taken and session._task is not None and not session._task.done():
                return WSCloseCode.POLICY_VIOLATION, "rostui serve: the app stopped reading its input"
        return None

    async def on_shutdown(self, app: web.Application) -> None:
        """Close every page (its app then ends as when a tab closes) and wait until every app has ended."""
        self.stopping = True
        sessions = list(self.sessions)
        await asyncio.gather(*(s.websocket.close(code=WSCloseCode.GOING_AWAY, message=b"rostui serve stopped")
                               for s in sessions), return_exceptions=True)
        endings = [s.ended for s in sessions if s.ended is not None]
        if endings:
            await asyncio.wait(endings, timeout=self.quit_grace + 2 * TERM_GRACE + 2.0)
        await end_children(0.0, TERM_GRACE)


async def end_children(grace: float, kill_grace: float) -> None:
    """Wait up to ``grace`` seconds until this process has no children left (each reaped by asyncio's
    child watcher, while the loop still runs); SIGTERM those still there, SIGKILL them after ``kill_grace``."""
    me = psutil.Process()
    children = await _children_after(me, grace)
    for child in children:
        _signal(child, terminate=True)
    children = await _children_after(me, kill_grace)
    for child in children:
        _signal(child, terminate=False)
    await _children_after(me, kill_grace)


async def _children_after(me: psutil.Process, timeout: float) -> list[psutil.Process]:
    """This process's children once none is left, or those still there after ``timeout`` seconds."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + timeout
    while (children := [c for c in me.children() if _running(c)]) and loop.time() < deadline:
        await asyncio.sleep(0.05)
    return children


def _running(process: psutil.Process) -> bool:
    try:
        return process.status() != psutil.STATUS_ZOMBIE
    except psutil.Error:
        return False


def _signal(child: psutil.Process, *, terminate: bool) -> None:
    """SIGTERM (or SIGKILL) one child, if it is still there."""
    try:
        child.terminate() if terminate else child.kill()
    except psutil.NoSuchProcess:
        pass
