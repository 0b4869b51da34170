"""One self-contained HTML file per scene: shader, data, viewer script and style inline.

It needs no network and no server: open it from disk in any browser with WebGL2.
"""
from __future__ import annotations

import html
import json
import re
from pathlib import Path
from typing import Any

from ..camera import Camera
from ..files import write_text_atomically
from ..nodes.base import Node
from . import assets
from .spec import build_spec

PLACEHOLDER = re.compile(r"__(?:TITLE|STYLE|SCRIPT|SPEC)__")


def script_safe_json(value: Any) -> str:
    """JSON text that can stand inside a ``<script>`` element in any HTML parsing state:
    every ``<``, ``>`` and ``&`` is written as a ``\\u`` escape (the same JSON string), so no
    ``</script``, ``<!--`` or ``<script`` can appear in the page's text."""
    text = json.dumps(value, separators=(",", ":"))
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def to_html(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (800, 500), *,
            title: str | None = None, **settings: Any) -> str:
    """The text of the one-file HTML view of ``scene`` (see :func:`save_html`)."""
    spec = build_spec(scene, camera, size, **settings)
    data = script_safe_json(spec)
    values = {"__TITLE__": html.escape(title or f"sdfgl: {spec['title']}"),
              "__STYLE__": assets.read("style.css"),
              "__SCRIPT__": assets.read("viewer.js") + "\n" + assets.read("page.js"),
              "__SPEC__": data}
    # one pass, so a title or parameter name that spells a placeholder is left as text
    page = PLACEHOLDER.sub(lambda m: values[m.group(0)], assets.read("page.html"))
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
    return write_text_atomically(Path(path), text, "HTML file")
