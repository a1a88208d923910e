"""Serving the studio: uvicorn on 127.0.0.1 only, stopped cleanly by Ctrl-C or SIGTERM.

:class:`StudioServer` binds the socket itself (port 0: a free one), so that the address
printed is the one served, and runs uvicorn on it in the calling thread
(:meth:`StudioServer.run`) or in a thread of its own (:meth:`StudioServer.start`, for
tests and benchmarks).  SIGINT (Ctrl-C) and SIGTERM stop it: it stops taking requests,
finishes those under way and returns.
"""

from __future__ import annotations

import contextlib
import signal
import socket
import threading
import time
from collections.abc import Iterator
from typing import Any

import uvicorn

__all__ = ['HOST', 'StudioServer', 'bind']

#: The only address the studio listens on.
HOST = '127.0.0.1'


def bind(port: int = 0) -> socket.socket:
    """A listening TCP socket on ``127.0.0.1:port`` (0: a free port).  OSError when the port
    is taken or cannot be bound."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind((HOST, port))
        sock.listen(64)
    except OSError:
        sock.close()
        raise
    return sock


class _Server(uvicorn.Server):
    """uvicorn's server without its own signal handling (it raises the signal again once
    stopped, so that the process would end killed): :meth:`StudioServer.run` handles them."""

    @contextlib.contextmanager
    def capture_signals(self) -> Iterator[None]:
        yield


class StudioServer:
    """An ASGI application served by uvicorn on a socket bound to loopback."""

    def __init__(self, app: Any, sock: socket.socket) -> None:
        self.sock = sock
        config = uvicorn.Config(app, log_level='warning', access_log=False, lifespan='off',
                                server_header=False, date_header=False, proxy_headers=False,
                                timeout_graceful_shutdown=3)
        self.server = _Server(config)
        self._thread: threading.Thread | None = None

    @property
    def port(self) -> int:
        """The port served."""
        return int(self.sock.getsockname()[1])

    @property
    def host(self) -> str:
        """The address served (always 127.0.0.1)."""
        return str(self.sock.getsockname()[0])

    def run(self) -> None:
        """Serve until Ctrl-C or SIGTERM: the first stops taking requests and returns once
        the requests under way are answered; a second one stops at once."""
        def on_signal(number: int, frame: Any) -> None:
            if self.server.should_exit:
                self.server.force_exit = True
            self.server.should_exit = True

        previous = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
        try:
            self.server.run(sockets=[self.sock])
        finally:
            for number, handler in previous.items():
                signal.signal(number, handler)
            self.sock.close()

    def start(self, timeout: float = 10.0) -> None:
        """Serve in a thread (uvicorn installs no signal handlers outside the main thread);
        return once it answers."""
        self._thread = threading.Thread(target=self.server.run, kwargs={'sockets': [self.sock]},
                                        name='nodl-studio', daemon=True)
        self._thread.start()
        deadline = time.monotonic() + timeout
        while not self.server.started:
            if time.monotonic() > deadline or not self._thread.is_alive():
                raise RuntimeError('nodl studio did not start')
            time.sleep(0.01)

    def stop(self, timeout: float = 10.0) -> None:
        """Stop a server started with :meth:`start`."""
        self.server.should_exit = True
        if self._thread is not None:
            self._thread.join(timeout)
        self.sock.close()
