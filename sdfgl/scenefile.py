"""Scene files: Python files that define ``scene`` (a node) and optionally ``camera``."""
from __future__ import annotations

import runpy
import traceback
from dataclasses import dataclass
from pathlib import Path

from .camera import Camera
from .errors import SceneFileError, SdfglError
from .nodes.base import Node


@dataclass
class SceneFile:
    path: Path
    scene: Node
    camera: Camera | None
    settings: dict  # render settings the file asks for (e.g. {"method": "newton"})


def load_scene_file(path: str | Path) -> SceneFile:
    """Run ``path`` and return its ``scene``, ``camera`` and ``settings``; errors name the file and line.

    A ``.json`` file is read as a scene document instead (no code runs; see sdfgl.scene_io)."""
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
        raise SceneFileError(f"scene file '{p}': 'camera' must be an sdfgl Camera, got {type(camera).__name__}")
    settings = ns.get("settings", {})
    if not isinstance(settings, dict):
        raise SceneFileError(f"scene file '{p}': 'settings' must be a dict, got {type(settings).__name__}")
    return SceneFile(p, scene, camera, dict(settings))
