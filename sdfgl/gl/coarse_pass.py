"""The coarse pass of a render: one fragment per tile of pixels, drawn before the image, writing
the ray parameter from which the tile's rays march (shaders/mains/coarse_main.glsl)."""
from __future__ import annotations

from typing import Callable

import moderngl

from .targets import Targets

START = ("start",)  # the coarse pass's one output: a float per tile


def coarse_size(size: tuple[int, int], tile: int) -> tuple[int, int]:
    """(columns, rows) of ``tile``-pixel tiles covering an image of ``size``."""
    return -(-size[0] // tile), -(-size[1] // tile)


def tile_target(ctx: moderngl.Context, tiles: tuple[int, int]) -> Targets:
    """A tile-start target holding ``tiles`` (columns, rows) in its lower left part: its sides
    are odd and at least 3, never a power of two. llvmpipe builds the image's machine code anew
    when a texture the image reads changes between a power-of-two size and another, so every
    tile count must give the same kind of texture (the image reads it by texelFetch)."""
    return Targets(ctx, (max(3, tiles[0] | 1), max(3, tiles[1] | 1)), START)


def draw_coarse(ctx: moderngl.Context, draw: Callable[[], None], size: tuple[int, int], tile: int,
                target: Targets | None = None) -> Targets:
    """Draw the coarse pass (``draw`` draws its program's full-screen triangle, its uniforms set
    for the full image of ``size``) into ``target`` where it holds the tiles, else into a new
    :func:`tile_target` (``target`` is then released), and return the target drawn into. The
    caller releases it once done (it is small, and kept out of the target cache, which could
    release it before). Call on the context's thread."""
    tiles = coarse_size(size, tile)
    if target is None or target.size[0] < tiles[0] or target.size[1] < tiles[1]:
        if target is not None:
            target.release()
        target = tile_target(ctx, tiles)
    try:
        target.fbo.use()
        ctx.viewport = (0, 0, *tiles)
        draw()
    except BaseException:
        target.release()
        raise
    return target
