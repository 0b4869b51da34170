"""OSC input: a UDP server (python-osc) on a background thread that hands every message to a handler.

Needs the optional extra ``sdfgl[live]``. The server binds 127.0.0.1 unless told otherwise
(a controller on another machine needs ``host="0.0.0.0"``).
"""
from __future__ import annotations

import threading
from typing import Any, Callable

from ..extras import require_extra
from .errors import LiveInputError


class OscServer:
    """Receive OSC on ``host``:``port`` (0: a free port, see :attr:`port`); ``handler(address, *args)``
    runs on the server's thread for each message."""

    def __init__(self, handler: Callable[..., None], port: int, host: str = "127.0.0.1") -> None:
        require_extra("live", "pythonosc", purpose="OSC input")
        from pythonosc.dispatcher import Dispatcher
        from pythonosc.osc_server import BlockingOSCUDPServer
        if not (isinstance(port, int) and 0 <= port <= 65535):
            raise LiveInputError(f"OSC: port must be 0..65535, got {port!r}")
        dispatcher = Dispatcher()
        dispatcher.set_default_handler(handler)
        try:
            self.server = BlockingOSCUDPServer((host, port), dispatcher)
        except OSError as exc:
            raise LiveInputError(f"OSC: cannot listen on {host}:{port}: {exc.strerror or exc}") from None
        self.thread = threading.Thread(target=self.server.serve_forever, kwargs={"poll_interval": 0.05},
                                       name="sdfgl-osc", daemon=True)
        self.thread.start()

    @property
    def port(self) -> int:
        """The UDP port the server listens on."""
        return int(self.server.server_address[1])

    @property
    def host(self) -> str:
        """The address the server listens on."""
        return str(self.server.server_address[0])

    def close(self) -> None:
        """Stop the server thread (within its 0.05 s poll) and close the socket."""
        self.server.shutdown()
        self.server.server_close()
        self.thread.join(timeout=5)


def send(address: str, *args: Any, port: int, host: str = "127.0.0.1") -> None:
    """Send one OSC message (e.g. to try a binding from a script): ``send("/radius", 0.8, port=9000)``."""
    require_extra("live", "pythonosc", purpose="sending OSC")
    from pythonosc.udp_client import SimpleUDPClient
    SimpleUDPClient(host, port).send_message(address, list(args))
