"""One way in for batch jobs and the CLI: a scene by file, Python (``.py``) or a JSON scene document."""
from __future__ import annotations

from pathlib import Path

from ..errors import SceneFileError
from ..scenefile import SceneFile, load_scene_file


def load_scene(path: str | Path) -> SceneFile:
    """Load ``path``: a ``.py`` scene file (defines ``scene``, maybe ``camera`` and ``settings``) or a
    ``.json`` scene document (read by ``sdfgl.scene_io`` where that package is installed)."""
    p = Path(path)
    if p.suffix.lower() == ".json":
        try:
            from .. import scene_io  # type: ignore[attr-defined]
        except ImportError:
            raise SceneFileError(f"scene '{p}': JSON scene documents need sdfgl.scene_io, which this "
                                 "installation lacks; use a Python scene file") from None
        return scene_io.load_scene_file(p)
    if p.suffix.lower() != ".py":
        raise SceneFileError(f"scene '{p}': expected a Python scene file (.py) or a JSON scene document (.json)")
    return load_scene_file(p)
