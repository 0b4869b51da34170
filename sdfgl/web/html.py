"""One self-contained HTML file per scene: shader, data, viewer script and style inline.

It needs no network and no server: open it from disk in any browser with WebGL2.
"""
from __future__ import annotations

import html
import json
from pathlib import Path
from typing import Any

from ..camera import Camera
from ..errors import SdfglError
from ..nodes.base import Node
from . import assets
from .spec import build_spec


def to_html(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (800, 500), *,
            title: str | None = None, **settings: Any) -> str:
    """The text of the one-file HTML view of ``scene`` (see :func:`save_html`)."""
    spec = build_spec(scene, camera, size, **settings)
    # inside <script> only "</" could end the element early; "<\/" is the same JSON string
    data = json.dumps(spec, separators=(",", ":")).replace("</", "<\\/")
    page = assets.read("page.html")
    for key, value in (("__TITLE__", html.escape(title or f"sdfgl: {spec['title']}")),
                       ("__STYLE__", assets.read("style.css")),
                       ("__SCRIPT__", assets.read("viewer.js") + "\n" + assets.read("page.js")),
                       ("__SPEC__", data)):
        page = page.replace(key, value, 1)
    return page


def save_html(scene: Node, path: str | Path, camera: Camera | None = None, size: tuple[int, int] = (800, 500), *,
              title: str | None = None, **settings: Any) -> Path:
    """Write an interactive one-file HTML view of ``scene`` to ``path``.

    The page draws the scene's generated shader (GLSL ES 3.00, the same code as the
    desktop render) with WebGL2: drag to orbit, right drag to pan, wheel to zoom, keys
    A / S / O / D toggle AA, shadows, AO and debug views, and every ``sg.param`` gets a
    slider. ``settings`` are render settings (``ground=True``, ``method=...``); ``aa``,
    ``shadows``, ``ao`` and ``debug`` are the toggles' starting states.
    """
    text = to_html(scene, camera, size, title=title, **settings)
    p = Path(path)
    try:
        p.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise SdfglError(f"cannot write HTML file '{p}': {exc}") from exc
    return p
