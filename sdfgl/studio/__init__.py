"""sdfgl studio: a node editor in the browser that writes scene documents.

    sdfgl studio part.json          # opens http://127.0.0.1:PORT/?token=... ; Save writes part.json
    st = sg.studio(scene)           # the same editor on a scene, from Python (returns the Studio)

``sg.studio`` is this package, callable: calling it calls :func:`open_studio`.

The page edits a graph that is the versioned JSON scene document (docs/scene-format.md);
a local server (:mod:`sdfgl.studio.server`, tornado) decodes it with :mod:`sdfgl.scene_io`,
compiles it with the same compiler as the HTML view (:mod:`sdfgl.web.spec`) and sends the
WebGL2 shaders to the page, which draws them with the browser viewer. The node palette is
generated from the node registry (:mod:`sdfgl.studio.palette`).
"""
from __future__ import annotations

import sys
import types
import webbrowser
from pathlib import Path
from typing import Any

from ..camera import Camera
from .server import Studio
from .workspace import Workspace

__all__ = ["Studio", "Workspace", "open_studio"]


def open_studio(scene: Any = None, path: str | Path | None = None, camera: Camera | None = None, *,
                size: tuple[int, int] = (640, 400), open_browser: bool = True, port: int = 0,
                settings: dict[str, Any] | None = None, live: Any = None) -> Studio:
    """Start the studio on ``scene`` (a node) or on the document file ``path``; returns the
    running :class:`Studio` (``.url``, ``.stop()``).

    Args:
        scene: a scene node to start from (saved to ``path`` only when the page saves).
        path: the scene document to open and save (created on the first save if missing).
        camera: the starting camera (with ``scene``).
        size: the page's view size in pixels.
        open_browser: open the page in the system's browser.
        port: the port on 127.0.0.1 (0: a free one).
        settings: render settings (with ``scene``).
        live: a :class:`sdfgl.live.LiveControl` (MIDI / OSC bindings) whose values move the
            page's sliders; the studio starts it (and stops it with itself), switches it to
            deferred delivery and offers it each compiled document's parameters.

    Needs the ``studio`` extra (tornado).
    """
    doc = None
    if scene is not None:
        from ..scene_io import to_dict
        doc = to_dict(scene, camera, settings)
    workspace = Workspace(path, doc, size)
    st = Studio(workspace, port=port, live=live).start()
    if live is not None:
        live.start()
    if open_browser:
        webbrowser.open(st.url)
    return st


class CallablePackage(types.ModuleType):
    """The class of this package's module object: ``sg.studio(...)`` is :func:`open_studio`."""

    def __call__(self, *args: Any, **kwargs: Any) -> Studio:
        return open_studio(*args, **kwargs)


sys.modules[__name__].__class__ = CallablePackage
