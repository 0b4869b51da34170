"""PBRImage: a path-traced image (linear HDR with coverage) and its settings."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image

from ..errors import SdfglError

GAMMA = 2.2  # as the real-time renderer writes its PNGs


@dataclass
class PBRImage:
    """A path-traced image. Row 0 is the top row.

    rgba: float32 (H, W, 4), linear radiance of the scene premultiplied by coverage
        (alpha = share of a pixel's samples that hit geometry).
    background: float32 (H, W, 3), linear radiance of the sky seen through each pixel.
    settings: what was rendered (variant, spp, grid, material, ...); timings in seconds.
    """

    rgba: np.ndarray
    background: np.ndarray
    settings: dict[str, Any] = field(default_factory=dict)
    timings: dict[str, float] = field(default_factory=dict)

    @property
    def alpha(self) -> np.ndarray:
        """Coverage in [0, 1], (H, W)."""
        return self.rgba[..., 3]

    @property
    def hdr(self) -> np.ndarray:
        """Linear RGB over the sky, float32 (H, W, 3)."""
        return self.rgba[..., :3] + (1.0 - self.alpha[..., None]) * self.background

    def to_uint8(self, exposure: float = 1.0, transparent: bool = False) -> np.ndarray:
        """Gamma-encoded 8-bit RGB (or RGBA with the coverage as alpha when ``transparent``)."""
        if transparent:
            a = self.alpha[..., None]
            rgb = np.where(a > 0, self.rgba[..., :3] / np.maximum(a, 1e-8), 0.0)
            out = np.concatenate([_encode(rgb * exposure), np.round(np.clip(a, 0, 1) * 255).astype(np.uint8)], -1)
            return out
        return _encode(self.hdr * exposure)

    def save(self, path: str | Path, exposure: float = 1.0, transparent: bool = False) -> Path:
        """Write the image: PNG/JPEG/... (8-bit, gamma 2.2), or ``.exr`` (linear float RGBA
        over a transparent background) or ``.npy`` (the float32 rgba array)."""
        p = Path(path)
        try:
            if p.suffix.lower() == ".npy":
                np.save(p, self.rgba)
            elif p.suffix.lower() == ".exr":
                from .backend import import_mitsuba
                import_mitsuba().Bitmap(np.ascontiguousarray(self.rgba)).write(str(p))
            else:
                Image.fromarray(self.to_uint8(exposure, transparent)).save(p)
        except (OSError, ValueError, KeyError, RuntimeError) as exc:
            raise SdfglError(f"cannot write image file '{p}': {exc}") from exc
        return p

    def _repr_png_(self) -> bytes:
        import io
        buf = io.BytesIO()
        Image.fromarray(self.to_uint8()).save(buf, format="PNG")
        return buf.getvalue()

    def __repr__(self) -> str:
        h, w = self.alpha.shape
        s = self.settings
        return (f"PBRImage({w}x{h}, {s.get('spp')} spp, {s.get('variant')}, "
                f"{self.timings.get('total_s', float('nan')):.2f} s)")


def _encode(rgb: np.ndarray) -> np.ndarray:
    return np.round(np.clip(np.nan_to_num(rgb), 0.0, 1.0) ** (1.0 / GAMMA) * 255).astype(np.uint8)
