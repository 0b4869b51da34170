"""The coarse pass of a render: one fragment per tile of pixels, drawn before the image, writing
the ray parameter from which the tile's rays march (shaders/mains/coarse_main.glsl)."""
from __future__ import annotations

import moderngl

from .targets import Targets

START = ("start",)  # the coarse pass's one output: a float per tile


def coarse_size(size: tuple[int, int], tile: int) -> tuple[int, int]:
    """(columns, rows) of ``tile``-pixel tiles covering an image of ``size``."""
    return -(-size[0] // tile), -(-size[1] // tile)


def draw_coarse(ctx: moderngl.Context, vao: moderngl.VertexArray, size: tuple[int, int], tile: int) -> Targets:
    """Draw the coarse pass (``vao``'s program, its uniforms set for the full image of ``size``)
    into a fresh tile target and return it; the caller releases it once the image is drawn (it
    is small, and kept out of the target cache, which could release it before). Call on the
    context's thread."""
    target = Targets(ctx, coarse_size(size, tile), START)
    try:
        target.fbo.use()
        ctx.viewport = (0, 0, *target.size)
        vao.render(moderngl.TRIANGLES, vertices=3)
    except BaseException:
        target.release()
        raise
    return target
