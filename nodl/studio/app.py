"""The studio's web application: the page, its files and its JSON API (Starlette).

Every request passes :class:`Guarded` first: the ``Host`` must be the loopback server's
and the token must be given (``?token=`` for the page and its files, the
``X-Nodl-Token`` header for the API), else 403.  Responses are never cached, send no
referrer (the token is in the address) and forbid scripts from anywhere but the studio.

The API edits one :class:`~nodl.studio.session.Session` (one at a time: a lock); every
edit answers with the whole new state (nodes, ports, edges, findings), so the page
redraws from what the server holds, never from a guess of its own.
"""

from __future__ import annotations

import json
import threading
from collections.abc import Awaitable, Callable, MutableMapping
from pathlib import Path
from typing import Any
from urllib.parse import parse_qs

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, PlainTextResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from nodl.studio.guard import TOKEN_HEADER, TOKEN_QUERY, allowed_host, same_token
from nodl.studio.session import Session, StudioError

__all__ = ['SECURITY_HEADERS', 'STATIC', 'create_app']

#: The page's own files (HTML, JS, CSS) and the vendor folder.
STATIC = Path(__file__).resolve().parent / 'static'

#: Sent with every response.
SECURITY_HEADERS = {
    'cache-control': 'no-store',
    'referrer-policy': 'no-referrer',
    'x-content-type-options': 'nosniff',
    'x-frame-options': 'DENY',
    'content-security-policy': ("default-src 'none'; script-src 'self'; "
                                # Cytoscape.js sets its container's style attribute
                                "style-src 'self' 'unsafe-inline'; "
                                "img-src 'self' data: blob:; connect-src 'self'; "
                                "frame-ancestors 'none'; base-uri 'none'; form-action 'none'"),
}

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]


class Guarded:
    """ASGI middleware: the host and the token of every request, and the security headers."""

    def __init__(self, app: ASGIApp, token: str, port: Callable[[], int]) -> None:
        self.app = app
        self.token = token
        self.port = port

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope['type'] != 'http':
            if scope['type'] == 'lifespan':
                await self.app(scope, receive, send)
            return
        headers = {k.decode('latin-1').lower(): v.decode('latin-1') for k, v in scope['headers']}
        query = parse_qs(scope.get('query_string', b'').decode('latin-1'))
        given = headers.get(TOKEN_HEADER) or (query.get(TOKEN_QUERY) or [None])[0]
        why = None
        if not allowed_host(headers.get('host'), self.port()):
            why = 'forbidden: nodl studio answers only on its loopback address'
        elif not same_token(given, self.token):
            why = 'forbidden: open the address nodl studio printed (it carries the token)'
        if why is not None:
            response: Response = PlainTextResponse(why, status_code=403)
            await self._send(response, scope, receive, send)
            return

        async def send_secured(message: Message) -> None:
            if message['type'] == 'http.response.start':
                raw = [(k, v) for k, v in message.get('headers', [])
                       if k.decode('latin-1').lower() not in SECURITY_HEADERS]
                raw += [(k.encode(), v.encode()) for k, v in SECURITY_HEADERS.items()]
                message['headers'] = raw
            await send(message)

        await self.app(scope, receive, send_secured)

    async def _send(self, response: Response, scope: Scope, receive: Receive, send: Send) -> None:
        for key, value in SECURITY_HEADERS.items():
            response.headers[key] = value
        await response(scope, receive, send)


def create_app(session: Session, token: str, port: Callable[[], int] | int) -> Guarded:
    """The application serving ``session``; ``port``: the port it answers on (a function
    when it is known only once the server is bound)."""
    lock = threading.Lock()
    port_of = port if callable(port) else (lambda: port)

    def page(request: Request) -> Response:
        text = (STATIC / 'index.html').read_text(encoding='utf-8')
        return HTMLResponse(text.replace('__TOKEN__', token))

    def answer(call: Callable[[], Any]) -> Response:
        with lock:
            try:
                return JSONResponse(call())
            except StudioError as exc:
                return JSONResponse({'ok': False, 'error': exc.message,
                                     'diagnostics': [d for d in exc.diagnostics]},
                                    status_code=exc.status)

    async def body(request: Request) -> dict[str, Any]:
        raw = await request.body()
        if not raw:
            return {}
        try:
            data = json.loads(raw)
        except ValueError as exc:
            raise StudioError(f'the request is not JSON: {exc}') from exc
        if not isinstance(data, dict):
            raise StudioError('the request must be a JSON object')
        return data

    def api(method: Callable[[dict[str, Any]], Any]) -> Callable[[Request], Awaitable[Response]]:
        async def endpoint(request: Request) -> Response:
            try:
                data = await body(request)
            except StudioError as exc:
                return JSONResponse({'ok': False, 'error': exc.message, 'diagnostics': []},
                                    status_code=400)
            # the session's work (reading definitions, analysing) runs off the event loop
            return await run_in_threadpool(answer, lambda: method(data))
        return endpoint

    routes = [
        Route('/', page),
        Route('/api/state', api(lambda d: session.state()), methods=['GET', 'POST']),
        Route('/api/palette', api(lambda d: session.palette()), methods=['GET', 'POST']),
        Route('/api/add', api(session.add), methods=['POST']),
        Route('/api/remove', api(session.remove), methods=['POST']),
        Route('/api/connect', api(session.connect), methods=['POST']),
        Route('/api/compatible', api(session.compatible), methods=['POST']),
        Route('/api/disconnect', api(session.disconnect), methods=['POST']),
        Route('/api/parameter', api(session.set_parameter), methods=['POST']),
        Route('/api/rename', api(session.rename), methods=['POST']),
        Route('/api/remaps', api(session.set_remaps), methods=['POST']),
        Route('/api/save', api(session.save), methods=['POST']),
        Route('/api/positions', api(session.save_positions), methods=['POST']),
        Route('/api/export', api(session.export), methods=['POST']),
        Route('/api/run-code', api(session.run_code), methods=['POST']),
        Mount('/static', app=StaticFiles(directory=STATIC), name='static'),
    ]
    app = Starlette(routes=routes)
    return Guarded(app, token, port_of)
