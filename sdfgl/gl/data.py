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

    Keyed by the arrays of the source's data (the sources an image's tile programs are made from
    share their image's; its coarse pass's source has the same arrays, sdfgl.compiler.tables): they
    are immutable, and the entry keeps them alive, so an id is never reused while its entry exists."""

    def __init__(self, budget: Callable[[], CacheBudget]) -> None:
        self._budget = budget
        self._lru: LRU[tuple[tuple, list[Texture]]] = LRU(_release)

    def textures(self, ctx: moderngl.Context, source: ShaderSource) -> list[Texture]:
        """The uploaded textures of ``source.data``; call on the context's thread. Keyed by the
        arrays themselves: sources that hold the same ones share their upload."""
        data_of = source.data
        as_buffer = of_source(source.text) is DESKTOP  # desktop: buffer textures; WebGL2: 2D ones
        key = (as_buffer, *(id(arr) for _, arr in data_of))
        entry = self._lru.get(key)
        if entry is None or any(a is not b for (_, a), (_, b) in zip(entry[0], data_of)):
            texs: list[Texture] = []
            nbytes = 0
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
            self._lru.put(key, entry, nbytes)
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
