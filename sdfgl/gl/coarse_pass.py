"""The coarse pass of a render: one fragment per tile of pixels, drawn before the image, writing
the ray parameter from which the tile's rays march (shaders/mains/coarse_main.glsl); and the
image drawn after it tile by tile (shaders/mains/tiles.vert.glsl): the image's program on the
tiles the pass left open, the same program with less on the tiles it proved empty (see the
tile kinds below)."""
from __future__ import annotations

import dataclasses
from typing import Callable

import moderngl

from ..compiler.source import ShaderSource
from .targets import Targets

START = ("start",)  # the coarse pass's one output: a float per tile
TILES_VERTEX = "mains/tiles.vert"
"""The vertex shader that draws an image's tiles of one kind."""


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


OPEN, EMPTY, SKY, LIT = 0, 1, 2, 3
"""Kinds of tile after a coarse pass: left open (marched), proven empty (no march: background,
ground, raster meshes), proven empty with no ray meeting the ground (no march, no ground),
proven empty with every ray meeting the ground where no shadow falls and AO is 1 (no march,
no shadow or AO: no map() call)."""
WHOLE = -1
"""The image's program drawing every pixel (its first frame, before the other kinds are linked)."""
_KIND_DEFINES = {OPEN: (), EMPTY: ("EMPTY_TILES",), SKY: ("EMPTY_TILES", "SKY_TILES"),
                 LIT: ("EMPTY_TILES", "LIT_TILES")}


def tile_sources(source: ShaderSource) -> list[tuple[ShaderSource, int]]:
    """The programs that draw the image ``source`` tile by tile after its coarse pass, each with
    its kind of tile: the image's own on the open tiles, then the same shader with less on the
    empty ones (where the image has no ground, the sky kind is its only empty one)."""
    kinds = (OPEN, EMPTY, LIT, SKY) if source.ground else (OPEN, SKY)
    return [(with_defines(source, _KIND_DEFINES[k]), k) for k in kinds]


def with_defines(source: ShaderSource, names: tuple[str, ...]) -> ShaderSource:
    """``source`` with ``#define`` lines for ``names`` after its #version line."""
    if not names:
        return source
    head, rest = source.text.split("\n", 1)
    lines = "".join(f"#define {n}\n" for n in names)
    return dataclasses.replace(source, text=f"{head}\n{lines}{rest}",
                               owners=(source.owners[0],) + ("(coarse pass: tile kind)",) * len(names)
                               + source.owners[1:])


def draw_tiles(ctx: moderngl.Context, set_uniform: Callable[[str, object], None], draw: Callable[[int, int], None],
               size: tuple[int, int], tile: int, kind: int) -> None:
    """Draw the tiles of ``kind`` (OPEN, EMPTY, LIT or SKY; WHOLE: every pixel, as one triangle) of an
    image of ``size`` in ``tile``-pixel tiles with a TILES_VERTEX program into the bound target:
    ``set_uniform(name, value)`` sets the program's uniforms, ``draw(mode, count)`` draws ``count``
    vertices of primitive ``mode`` (moderngl's constants). An empty kind is drawn first as points
    four tiles a side over each 4x4 block of its tiles, then two tiles a side over the 2x2 blocks
    outside those, then tile by tile where neither covers a tile (fewer, larger points: less of
    llvmpipe's work a pixel). The viewport spans whole 4x4 blocks (the target clips the part past its edge),
    so no point is clipped away. Call on the context's thread."""
    cols, rows = coarse_size(size, tile)
    view = (4 * tile * -(-cols // 4), 4 * tile * -(-rows // 4))
    for name, value in (("uTiles", (cols, rows)), ("uTileSide", tile), ("uTileKind", kind), ("uView", view)):
        set_uniform(name, value)
    if kind == WHOLE:
        draw(moderngl.TRIANGLES, 3)
        return
    ctx.viewport = (0, 0, *view)
    ctx.enable(moderngl.PROGRAM_POINT_SIZE)
    try:
        for block in ((4, 2, 1) if kind != OPEN else (1,)):
            set_uniform("uBlock", block)
            draw(moderngl.POINTS, -(-cols // block) * -(-rows // block))
    finally:
        ctx.disable(moderngl.PROGRAM_POINT_SIZE)
        ctx.viewport = (0, 0, *size)
