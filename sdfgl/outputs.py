"""Writing a render's images: colour, depth, normal and step-count pictures, or one .npz.

PNGs are written by :func:`sdfgl.png.encode_png` (one "Sub" filter, deflate level 1): at
1920x1080 a third of Pillow's level-1 time, a tenth with the ``fast`` extra, for files no larger
(benchmarks/png_write_times.py). Options, or other formats, go to Pillow.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any, Sequence

import numpy as np

from .errors import SdfglError
from .files import write_bytes_atomically, written_atomically
from .png import can_encode, encode_png

PNG_OPTIONS = {"compress_level": 1}  # Pillow's PNG options where a caller passes its own


def write_image(array: np.ndarray, path: str | Path, **options: Any) -> Path:
    """Write an image array (format from the suffix). A PNG without ``options`` is encoded
    by :func:`sdfgl.png.encode_png`; anything else goes to Pillow with ``options``."""
    p = Path(path)
    png = p.suffix.lower() == ".png"
    if png and not options and can_encode(array):
        return write_bytes_atomically(p, encode_png(array), "image file")
    from PIL import Image
    opts = {**(PNG_OPTIONS if png else {}), **options}
    fmt = Image.registered_extensions().get(p.suffix.lower())
    if fmt is None:
        raise SdfglError(f"cannot write image file '{p}': unknown image format {p.suffix or '(no suffix)'!r}")
    try:
        with written_atomically(p, "image file") as tmp:
            Image.fromarray(array).save(tmp, format=fmt, **opts)
    except (ValueError, KeyError) as exc:
        raise SdfglError(f"cannot write image file '{p}': {exc}") from exc
    return p


def depth_image(depth: np.ndarray) -> np.ndarray:
    """16-bit grey picture of a depth image: nearest hit white, farthest dark grey, misses black."""
    hit = np.isfinite(depth)
    out = np.zeros(depth.shape, dtype=np.uint16)
    if hit.any():
        near, far = float(depth[hit].min()), float(depth[hit].max())
        scale = (far - near) or 1.0
        out[hit] = (65535 - 60000 * (depth[hit] - near) / scale).astype(np.uint16)
    return out


def normal_image(normal: np.ndarray) -> np.ndarray:
    """RGB picture of unit normals, 0.5 + 0.5 n (a miss, n = 0, is mid grey)."""
    return np.clip(np.rint((0.5 + 0.5 * normal) * 255), 0, 255).astype(np.uint8)


def steps_image(steps: np.ndarray) -> np.ndarray:
    """16-bit grey picture of map() calls per pixel (the count itself, unscaled)."""
    return np.clip(steps, 0, 65535).astype(np.uint16)


_PICTURES = {"depth": depth_image, "normal": normal_image, "steps": steps_image}


def save_outputs(res: Any, path: str | Path, outputs: Sequence[str] = ("color",)) -> list[Path]:
    """Write ``res``'s images: ``path`` gets the colour image and ``stem.NAME.png`` beside it
    each other output; a ``.npz`` path gets every output as its raw array instead
    (color uint8, depth float32 with inf on a miss, normal float32, steps int32)."""
    p = Path(path)
    if p.suffix.lower() == ".npz":
        arrays = {name: getattr(res, name) for name in outputs if getattr(res, name, None) is not None}
        with written_atomically(p, "output file") as tmp, open(tmp, "wb") as fh:
            np.savez_compressed(fh, **arrays)
        return [p]
    written = [write_image(res.color, p)]
    for name in outputs:
        if name != "color":
            written.append(write_image(_PICTURES[name](getattr(res, name)), p.with_name(f"{p.stem}.{name}.png")))
    return written
