"""``sdfgl studio``: the browser node editor on a scene document (see :mod:`sdfgl.studio`)."""
from __future__ import annotations

import argparse
import signal
import time
from typing import Any

from .common import image_size


def add_parser(sub: Any, command: str | None) -> None:
    """Register ``sdfgl studio``."""
    s = sub.add_parser("studio", help="edit a scene as a node graph in the browser (a local server)")
    s.add_argument("document", nargs="?", help="the scene document (.json) to edit; Save writes it "
                                               "(created on the first save if missing)")
    s.add_argument("--port", type=int, default=0, help="port on 127.0.0.1 (default: a free one)")
    s.add_argument("--size", type=image_size, default=(640, 400), help="view WIDTHxHEIGHT (default 640x400)")
    s.add_argument("--no-browser", action="store_true", help="print the URL only; do not open a browser")
    s.add_argument("--osc", type=int, metavar="PORT", help="receive OSC on this UDP port (0: a free one) for --bindings")
    s.add_argument("--midi", metavar="NAME", help="read MIDI control changes from this input port (\"\": the first)")
    s.add_argument("--bindings", metavar="FILE", help="a live-control bindings file (MIDI / OSC -> parameters)")
    s.set_defaults(func=run)


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl studio`` until interrupted."""
    from ..studio import open_studio
    live = None
    if a.osc is not None or a.midi is not None or a.bindings:
        from ..extras import require_extra
        require_extra("live", purpose="sdfgl studio --osc / --midi")
        from ..live import LiveControl
        live = LiveControl(osc=a.osc, midi=a.midi)
    st = open_studio(path=a.document, size=a.size, open_browser=not a.no_browser, port=a.port, live=live)
    if live is not None and a.bindings:
        live.load(a.bindings)
    if live is not None and live.osc_port is not None:
        print(f"sdfgl studio: OSC on udp://127.0.0.1:{live.osc_port}", flush=True)
    # Ctrl+C (SIGINT) and SIGTERM stop it however it was started: a shell without job control
    # starts a background command with SIGINT ignored, and Python then leaves it ignored
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    try:  # (a signal may come as soon as the URL is out)
        print(f"sdfgl studio: {st.url}  (Ctrl+C stops it)", flush=True)
        while True:
            time.sleep(3600)
    except KeyboardInterrupt:
        pass
    finally:
        st.stop()
    return 0
