"""The one way in for scenes: a Python scene file, a JSON scene document, or the demo.

    sf = load_scene_file("scene.py")   # .scene, .camera, .settings, .camera_path
    sf = load_demo()                   # the built-in showcase scene, on its ground plane

A Python scene file defines ``scene`` (a node) and optionally ``camera`` (a fixed camera),
``settings`` (a dict of render settings) and ``camera_path`` (``sg.turntable(...)``,
``sg.camera_path(...)`` or a function of time, for ``sdfgl animate``) and ``parts`` (a dict of
part names to nodes, which ``sdfgl mesh`` writes as separate parts with their materials). A ``.json`` file is
read as a scene document (no code runs; see :mod:`sdfgl.scene_io`). Every command line
subcommand, the batch workers and the viewer's hot reload load scenes through here.
"""
from __future__ import annotations

import runpy
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .camera import Camera
from .errors import SceneFileError, SdfglError
from .nodes.base import Node


@dataclass
class SceneFile:
    """A loaded scene and what its file asks for.

    path: the file (None for the demo).
    scene: the scene node.
    camera: the file's fixed camera, or None (frame the scene).
    settings: render settings the file asks for (e.g. ``{"method": "newton"}``).
    camera_path: the file's camera over time for animations (a ``CameraPath`` or a
        function of time), or None.
    parts: the file's named parts to print (``{"body": node, ...}``), or None.
    """

    path: Path | None
    scene: Node
    camera: Camera | None
    settings: dict[str, Any] = field(default_factory=dict)
    camera_path: Any = None
    parts: dict[str, Node] | None = None


def load_demo() -> SceneFile:
    """The built-in showcase scene with its camera, asking for the ground plane."""
    from .demo import demo_camera, demo_scene
    return SceneFile(None, demo_scene(), demo_camera(), {"ground": True})


def load_scene_file(path: str | Path) -> SceneFile:
    """Load ``path``: run a Python scene file, or read a ``.json`` scene document.

    Returns its ``scene``, ``camera``, ``settings`` and ``camera_path``; errors name the
    file (and for Python, the line)."""
    p = Path(path)
    if not p.is_file():
        raise SceneFileError(f"scene file '{p}' does not exist")
    if p.suffix.lower() == ".json":
        from .scene_io import load_scene
        doc = load_scene(p)
        return SceneFile(p, doc.scene, doc.camera, dict(doc.settings))
    try:
        ns = runpy.run_path(str(p), run_name="__sdfgl_scene__")
    except SyntaxError as exc:
        raise SceneFileError(f"scene file '{p}', line {exc.lineno}: syntax error: {exc.msg}") from exc
    except (Exception, SystemExit) as exc:  # a user's script may raise (or exit) anything: report, not obey
        frames = [f for f in traceback.extract_tb(exc.__traceback__) if Path(f.filename).resolve() == p.resolve()]
        where = f", line {frames[-1].lineno}" if frames else ""
        what = (str(exc) if isinstance(exc, SdfglError) else
                f"called sys.exit({exc.code!r}); a scene file must define 'scene', not exit"
                if isinstance(exc, SystemExit) else f"{type(exc).__name__}: {exc}")
        raise SceneFileError(f"scene file '{p}'{where}: {what}") from exc
    scene = ns.get("scene")
    if scene is None:
        raise SceneFileError(f"scene file '{p}' does not define 'scene'")
    if not isinstance(scene, Node):
        raise SceneFileError(f"scene file '{p}': 'scene' must be an sdfgl node, got {type(scene).__name__}")
    camera = ns.get("camera")
    if camera is not None and not isinstance(camera, Camera):
        hint = "; a camera that moves goes in 'camera_path'" if callable(getattr(camera, "camera", None)) else ""
        raise SceneFileError(f"scene file '{p}': 'camera' must be an sdfgl Camera, got {type(camera).__name__}{hint}")
    settings = ns.get("settings", {})
    if not isinstance(settings, dict):
        raise SceneFileError(f"scene file '{p}': 'settings' must be a dict, got {type(settings).__name__}")
    path_ = ns.get("camera_path")
    if path_ is not None and not (callable(getattr(path_, "camera", None)) or callable(path_)):
        raise SceneFileError(f"scene file '{p}': 'camera_path' must be sg.turntable(...), sg.camera_path(...) "
                             f"or a function of time, got {type(path_).__name__}")
    parts = ns.get("parts")
    if parts is not None:
        if not isinstance(parts, dict) or not parts:
            raise SceneFileError(f"scene file '{p}': 'parts' must be a non-empty dict of name -> node, "
                                 f"got {type(parts).__name__}")
        for name, node in parts.items():
            if not isinstance(name, str) or not isinstance(node, Node):
                raise SceneFileError(f"scene file '{p}': 'parts' must map names (strings) to sdfgl nodes; "
                                     f"{name!r} maps to {type(node).__name__}")
        parts = dict(parts)
    return SceneFile(p, scene, camera, dict(settings), path_, parts)
