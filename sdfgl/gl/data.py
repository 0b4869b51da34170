"""Data textures (big unions kept as data), uploaded once per source's data and kept in an LRU.

A desktop shader reads its tables from a buffer texture (shaders/lib/data_buffer.glsl), a
WebGL2 one from a 2D texture (data_table.glsl); the source's dialect says which to upload."""
from __future__ import annotations

from typing import Callable

import moderngl
import numpy as np

from ..compiler.source import ShaderSource
from .buffer_texture import BufferTexture
from .cache import LRU, MB, CacheBudget
from .dialect import DESKTOP, of_source

Texture = moderngl.Texture | BufferTexture


def _release(entry: tuple[tuple, list[Texture]]) -> None:
    for t in entry[1]:
        t.release()


class DataTextures:
    """The textures each shader source samples, least recently used released beyond ``budget().data_mb``.

    Keyed by the source's data tuple (the sources an image's tile programs are made from share
    their image's): it is immutable, and the entry keeps it alive, so an id is never reused
    while its entry exists."""

    def __init__(self, budget: Callable[[], CacheBudget]) -> None:
        self._budget = budget
        self._lru: LRU[tuple[tuple, list[Texture]]] = LRU(_release)

    def textures(self, ctx: moderngl.Context, source: ShaderSource) -> list[Texture]:
        """The uploaded textures of ``source.data``; call on the context's thread. Keyed by the
        data itself: the sources made from one another (an image's tile programs) share it."""
        data_of = source.data
        entry = self._lru.get(id(data_of))
        if entry is None or entry[0] is not data_of:
            texs: list[Texture] = []
            nbytes = 0
            as_buffer = of_source(source.text) is DESKTOP
            for _, arr in source.data:
                data = np.ascontiguousarray(arr, dtype=np.float32)
                if as_buffer:
                    texs.append(BufferTexture(ctx, data))
                else:
                    tex = ctx.texture((arr.shape[1], arr.shape[0]), 4, data, dtype="f4")
                    tex.filter = (moderngl.NEAREST, moderngl.NEAREST)
                    texs.append(tex)
                nbytes += data.nbytes
            entry = (data_of, texs)
            self._lru.put(id(data_of), entry, nbytes)
            mb = self._budget().data_mb
            self._lru.trim(max_bytes=None if mb is None else mb * MB)
        return entry[1]

    def forget(self) -> None:
        self._lru.forget()

    def clear(self) -> None:
        """Release every texture."""
        self._lru.clear()

    @property
    def bytes(self) -> int:
        return self._lru.bytes

    def __len__(self) -> int:
        return len(self._lru)
