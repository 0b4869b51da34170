"""The JS, CSS and HTML files of the browser views (shipped in the wheel beside this module)."""
from __future__ import annotations

import functools
from pathlib import Path

from ..errors import SdfglError

_HERE = Path(__file__).resolve().parent


@functools.lru_cache(maxsize=None)
def read(name: str) -> str:
    """Text of ``sdfgl/web/<name>``."""
    path = _HERE / name
    try:
        return path.read_text(encoding="utf-8")
    except OSError as exc:
        raise SdfglError(f"sdfgl's browser viewer file is missing: {path}: {exc}") from exc
