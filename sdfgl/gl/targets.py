"""Offscreen render targets: one texture per requested output, read back as numpy; an LRU of them."""
from __future__ import annotations

from typing import Callable

import moderngl
import numpy as np

from .cache import LRU, MB, CacheBudget

# output name -> (components, dtype) of its texture ("start": the coarse pass's per tile)
FORMATS = {"color": (4, "f1"), "depth": (1, "f4"), "normal": (4, "f4"), "steps": (1, "f4"), "start": (1, "f4")}


def target_bytes(size: tuple[int, int], outputs: tuple[str, ...]) -> int:
    """GPU memory of the textures of one target."""
    per_px = sum(FORMATS[n][0] * (1 if FORMATS[n][1] == "f1" else 4) for n in outputs)
    return size[0] * size[1] * per_px


class Targets:
    """A framebuffer whose colour attachments are the outputs, in Settings.outputs order."""

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int], outputs: tuple[str, ...]) -> None:
        self.size, self.outputs = size, outputs
        self.textures = {name: ctx.texture(size, FORMATS[name][0], dtype=FORMATS[name][1]) for name in outputs}
        self.fbo = ctx.framebuffer(color_attachments=[self.textures[n] for n in outputs])

    def read(self, name: str, components: int | None = None) -> np.ndarray:
        """Output ``name`` as a C-contiguous (H, W, C) array with row 0 at the top.

        ``components`` (default: all of the texture's) keeps the first C channels: the GL
        read converts them (RGBA -> RGB), and one row-reversing copy puts the top row first.
        """
        comps, dtype = FORMATS[name]
        c = comps if components is None else components
        if not 1 <= c <= comps:
            raise ValueError(f"output {name!r} has {comps} components, cannot read {c}")
        w, h = self.size
        raw = np.empty((h, w, c), dtype=np.uint8 if dtype == "f1" else np.float32)
        self.fbo.read_into(raw, components=c, attachment=self.outputs.index(name), alignment=1, dtype=dtype)
        return raw[::-1].copy()

    def release(self) -> None:
        self.fbo.release()
        for t in self.textures.values():
            t.release()


class TargetCache:
    """Render targets by (size, outputs), least recently used released beyond ``budget().targets_mb``."""

    def __init__(self, budget: Callable[[], CacheBudget]) -> None:
        self._budget = budget
        self._lru: LRU[Targets] = LRU(Targets.release)

    def get(self, ctx: moderngl.Context, size: tuple[int, int], outputs: tuple[str, ...]) -> Targets:
        """The target for ``size`` and ``outputs`` (made if new); call on the context's thread."""
        key = (size, outputs)
        t = self._lru.get(key)
        if t is None:
            t = Targets(ctx, size, outputs)
            self._lru.put(key, t, target_bytes(size, outputs))
            mb = self._budget().targets_mb
            self._lru.trim(max_bytes=None if mb is None else mb * MB)
        return t

    def forget(self) -> None:
        self._lru.forget()

    def clear(self) -> None:
        """Release every target."""
        self._lru.clear()

    def __len__(self) -> int:
        return len(self._lru)
