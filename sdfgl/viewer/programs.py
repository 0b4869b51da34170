"""Programs linked off the window's thread, with plain GL calls through ctypes.

moderngl cannot link them: it keeps Python's interpreter lock through the driver's compile
(so every other thread of the viewer, the window's included, would stop) and refuses a
program made by another moderngl context. :func:`build` links with :mod:`rawgl` (which
releases the lock) and wraps the result as a :class:`RawProgram`.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, Callable, Union

import moderngl

from .. import shaderlib
from ..compiler.source import ShaderSource
from ..errors import SdfglError
from ..gl.dialect import of_source
from ..gl.coarse_pass import TILES_VERTEX, draw_tiles, tile_sources
from ..gl.programs import FULLSCREEN, explain_compile_error
from . import rawgl


class RawProgram:
    """A program linked through ctypes, with the little of moderngl's Program API the renderer's
    uniform helpers use: ``name in prog``, ``prog[name].value = v`` and ``prog.ctx`` (the moderngl
    context of the thread that draws it, where its data textures are made)."""

    def __init__(self, gl: rawgl.GL, glo: int, uniforms: dict[str, tuple[int, int]], ctx: moderngl.Context) -> None:
        self.gl, self.glo, self.ctx = gl, glo, ctx
        self._uniforms = {name.removesuffix("[0]"): v for name, v in uniforms.items()}

    def __contains__(self, name: str) -> bool:
        return name in self._uniforms

    def __getitem__(self, name: str) -> "_Uniform":
        return _Uniform(self, name)

    def set(self, name: str, value: Any) -> None:
        """Set uniform ``name`` (one the program has) to ``value``."""
        loc, typ = self._uniforms[name]
        self.gl.set_uniform(self.glo, loc, typ, value)

    def render(self, vao: int, size: tuple[int, int] | None = None) -> None:
        """Draw the full-screen triangle into the bound framebuffer (the interpreter lock is released
        meanwhile: llvmpipe builds a program's machine code at its first draw in each context)."""
        self.draw(vao, rawgl.TRIANGLES, 3)

    def draw(self, vao: int, mode: int, count: int) -> None:
        """Draw ``count`` vertices of primitive ``mode`` with no vertex buffer."""
        self.gl.glUseProgram(self.glo)
        self.gl.glBindVertexArray(vao)
        self.gl.glDrawArrays(mode, 0, count)

    def release(self) -> None:
        if self.glo:
            self.gl.glDeleteProgram(self.glo)
            self.glo = 0


class TiledProgram:
    """An image drawn tile by tile after its coarse pass (see :mod:`sdfgl.gl.coarse_pass`): one
    program per kind of tile, behind RawProgram's API. A uniform is set on each that has it; a
    draw draws them all."""

    def __init__(self, parts: list[tuple[RawProgram, int]], tile: int) -> None:
        self.parts, self.tile, self.ctx = parts, tile, parts[0][0].ctx

    def __contains__(self, name: str) -> bool:
        return any(name in p for p, _ in self.parts)

    def __getitem__(self, name: str) -> "_Uniform":
        return _Uniform(self, name)

    def set(self, name: str, value: Any) -> None:
        for p, _ in self.parts:
            if name in p:
                p.set(name, value)

    def render(self, vao: int, size: tuple[int, int] | None = None) -> None:
        """Draw the image's tiles of an image of ``size`` into the bound framebuffer."""
        if size is None:
            raise SdfglError("render: a tiled image needs its size to be drawn")
        for p, kind in self.parts:
            draw_tiles(self.ctx, lambda name, value, p=p: p.set(name, value) if name in p else None,
                       lambda mode, n, p=p: p.draw(vao, mode, n), size, self.tile, kind)

    def release(self) -> None:
        for p, _ in self.parts:
            p.release()


ImageProgram = Union[RawProgram, TiledProgram]
"""What draws a view's image in the render threads."""


class _Uniform:
    def __init__(self, prog: ImageProgram, name: str) -> None:
        self.prog, self.name = prog, name

    @property
    def value(self) -> Any:
        raise AttributeError("uniform values are write-only here")

    @value.setter
    def value(self, v: Any) -> None:
        self.prog.set(self.name, v)


@dataclass
class Job:
    """One compile: ``build`` makes the source (codegen runs off the window's thread too);
    ``scene`` and ``origin`` set the uniforms of the warm-up draw; ``meta`` comes back.
    ``mesh_build``, when the view has raster meshes, makes the source of their program;
    ``coarse_build`` makes the source of the coarse pass before the image from the image's
    source (None where the image has none)."""

    token: int
    build: Callable[[], ShaderSource]
    scene: Any = None
    origin: Any = None
    meta: Any = None
    mesh_build: Callable[[], ShaderSource] | None = None
    coarse_build: Callable[[ShaderSource], ShaderSource | None] | None = None


@dataclass
class Result:
    """A finished job: the program to show is ``source.text`` in the cache of render lane ``lane``."""

    token: int
    meta: Any
    lane: int = -1
    source: ShaderSource | None = None
    error: str = ""
    compiled: bool = False   # a new program was linked (not found in a cache)
    seconds: float = 0.0     # codegen + link + warm-up draw, off the window's thread
    timings: dict[str, float] = field(default_factory=dict)


def make_source(build: Callable[[], ShaderSource]) -> ShaderSource:
    """Run a job's codegen ``build``; any failure becomes one SdfglError (the overlay's message)."""
    try:
        return build()
    except SdfglError:
        raise
    except Exception as exc:  # codegen of a user's scene: report, never kill the thread
        raise SdfglError(f"code generation failed: {type(exc).__name__}: {exc}") from exc


def link(gl: rawgl.GL, source: ShaderSource, ctx: moderngl.Context, vertex_shader: str = FULLSCREEN) -> RawProgram:
    """Link ``source`` under the vertex shader ``shaders/<vertex_shader>.glsl`` in the current context
    (the calling thread's); SdfglError with the driver's log."""
    try:
        vertex = of_source(source.text).convert(shaderlib.read(vertex_shader))
        glo = gl.link(vertex, source.text)
    except rawgl.GLError as exc:
        raise SdfglError(explain_compile_error(source, str(exc))) from None
    return RawProgram(gl, glo, gl.uniforms(glo), ctx)


def link_image(gl: rawgl.GL, source: ShaderSource, ctx: moderngl.Context,
               tiled: bool) -> ImageProgram:
    """The image of ``source`` linked in the current context: one full-screen program, or where
    ``tiled`` (it has a coarse pass) the two programs of its tiles."""
    if not tiled:
        return link(gl, source, ctx)
    parts: list[tuple[RawProgram, int]] = []
    try:
        for src, kind in tile_sources(source):
            parts.append((link(gl, src, ctx, TILES_VERTEX), kind))
    except BaseException:
        for p, _ in parts:
            p.release()
        raise
    return TiledProgram(parts, source.coarse_tile)


def link_raster(source: ShaderSource, ctx: moderngl.Context) -> moderngl.Program:
    """Link the raster meshes' program of ``source`` in ``ctx`` (moderngl: the raster pass draws
    vertex buffers through it); SdfglError with the driver's log."""
    from ..render import RASTER_VERTEX
    try:
        vertex = of_source(source.text).convert(shaderlib.read(RASTER_VERTEX))
        return ctx.program(vertex_shader=vertex, fragment_shader=source.text)
    except moderngl.Error as exc:
        raise SdfglError(explain_compile_error(source, str(exc))) from None


def stamp(res: Result, t0: float, **phases: float) -> None:
    """Record a job's phase times and its wall-clock span in ``res``."""
    res.seconds = time.perf_counter() - t0
    res.timings = {**phases, "wall_end": time.time(), "wall_start": time.time() - res.seconds}
