"""``sdfgl studio``: the browser node editor on a scene document (see :mod:`sdfgl.studio`)."""
from __future__ import annotations

import argparse
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
    s.set_defaults(func=run)


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl studio`` until interrupted."""
    from ..studio import open_studio
    st = open_studio(path=a.document, size=a.size, open_browser=not a.no_browser, port=a.port)
    print(f"sdfgl studio: {st.url}  (Ctrl+C stops it)", flush=True)
    try:
        while True:
            time.sleep(3600)
    except KeyboardInterrupt:
        pass
    finally:
        st.stop()
    return 0
