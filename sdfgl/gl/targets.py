"""Offscreen render targets: one texture per requested output, read back as numpy."""
from __future__ import annotations

import moderngl
import numpy as np

# output name -> (components, dtype) of its texture
FORMATS = {"color": (4, "f1"), "depth": (1, "f4"), "normal": (4, "f4"), "steps": (1, "f4")}


class Targets:
    """A framebuffer whose colour attachments are the outputs, in Settings.outputs order."""

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int], outputs: tuple[str, ...]) -> None:
        self.size, self.outputs = size, outputs
        self.textures = {name: ctx.texture(size, FORMATS[name][0], dtype=FORMATS[name][1]) for name in outputs}
        self.fbo = ctx.framebuffer(color_attachments=[self.textures[n] for n in outputs])

    def read(self, name: str) -> np.ndarray:
        """Output ``name`` as an (H, W, C) array with row 0 at the top."""
        comps, dtype = FORMATS[name]
        w, h = self.size
        data = np.frombuffer(self.textures[name].read(), dtype=np.uint8 if dtype == "f1" else np.float32)
        return data.reshape(h, w, comps)[::-1]

    def release(self) -> None:
        self.fbo.release()
        for t in self.textures.values():
            t.release()
