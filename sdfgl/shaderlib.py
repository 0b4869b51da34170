"""Loads the .glsl files that ship in ``shaders/`` (installed as the ``sdfgl.shaders`` package)."""
from __future__ import annotations

import functools
import re
from pathlib import Path

from .errors import SdfglError

_HERE = Path(__file__).resolve().parent


def shader_dir() -> Path:
    """Directory holding the GLSL sources: the installed copy, else the source tree's."""
    for d in (_HERE / "shaders", _HERE.parent / "shaders"):
        if (d / "mains" / "fullscreen.vert.glsl").is_file():
            return d
    raise SdfglError(f"sdfgl's GLSL files are missing: looked in {_HERE / 'shaders'} and {_HERE.parent / 'shaders'}")


@functools.lru_cache(maxsize=None)
def read(name: str) -> str:
    """Text of ``shaders/<name>.glsl`` (``name`` may include a subfolder, e.g. ``lib/sd_box``)."""
    path = shader_dir() / f"{name}.glsl"
    try:
        return path.read_text(encoding="utf-8")
    except OSError as exc:
        raise SdfglError(f"cannot read shader file {path}: {exc}") from exc


_REQUIRES = re.compile(r"^//\s*requires:\s*(.+)$", re.MULTILINE)


@functools.lru_cache(maxsize=None)
def requires(name: str) -> tuple[str, ...]:
    """Library functions that ``lib/<name>.glsl`` calls, from its ``// requires: a, b`` line."""
    m = _REQUIRES.search(read(f"lib/{name}"))
    return tuple(x.strip() for x in m.group(1).split(",")) if m else ()
