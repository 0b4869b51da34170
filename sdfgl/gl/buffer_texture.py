"""Buffer textures (GL 3.1 ``samplerBuffer``): the desktop shaders' data tables.

A table read by index is cheaper as a buffer texture than as a 2D texture on llvmpipe:
``texelFetch(samplerBuffer, i)`` is one clamped load, where a 2D fetch splits the index
into a texel position and goes through the level and layout code of a sampled image
(the grid scene of 1024 spheres draws in 0.73x the time; see the issue-12 notes). moderngl
has no buffer textures (and sets no samplerBuffer uniform), so the few GL calls they need
go through ctypes here, loaded from whichever API (EGL headless, GLFW in a window) made the
calling thread's context current.
"""
from __future__ import annotations

import ctypes
from ctypes import POINTER, byref, c_int, c_uint
from typing import TYPE_CHECKING, Any, Callable

import moderngl

from ..errors import ContextError, SdfglError

if TYPE_CHECKING:  # pragma: no cover
    import numpy as np

TEXTURE_BUFFER, RGBA32F, TEXTURE0 = 0x8C2A, 0x8814, 0x84C0

_SIGNATURES: dict[str, tuple[Any, ...]] = {
    "glGenTextures": (None, c_int, POINTER(c_uint)),
    "glDeleteTextures": (None, c_int, POINTER(c_uint)),
    "glBindTexture": (None, c_uint, c_uint),
    "glActiveTexture": (None, c_uint),
    "glTexBuffer": (None, c_uint, c_uint, c_uint),
    "glGetUniformLocation": (c_int, c_uint, ctypes.c_char_p),
    "glProgramUniform1i": (None, c_uint, c_int, c_int),
}


class _Functions:
    """The GL entry points of buffer textures, loaded through one API's ``get`` (address by name)."""

    def __init__(self, get: Callable[[str], int | None]) -> None:
        for name, (restype, *argtypes) in _SIGNATURES.items():
            addr = get(name)
            if not addr:
                raise ContextError(f"the OpenGL driver lacks {name} (buffer textures need OpenGL 3.1, "
                                   f"glProgramUniform1i 4.1 or ARB_separate_shader_objects)")
            setattr(self, name, ctypes.CFUNCTYPE(restype, *argtypes)(addr))


def _glfw_address(name: str) -> int | None:
    import glfw
    return glfw.get_proc_address(name)


_loaded: dict[str, _Functions] = {}


def _functions() -> _Functions:
    """The functions for the calling thread's context: loaded from EGL when an EGL context
    is current (headless), else from GLFW (a window's), once per API."""
    from .context import egl_current, egl_proc_address
    api = "egl" if egl_current() else "glfw"
    if api not in _loaded:
        _loaded[api] = _Functions(egl_proc_address if api == "egl" else _glfw_address)
    return _loaded[api]


class BufferTexture:
    """Float32 RGBA texels ``data`` (bytes, 16 per texel) in a buffer texture of ``ctx``.
    Create, use and release it on the context's thread."""

    def __init__(self, ctx: moderngl.Context, data: bytes | np.ndarray) -> None:
        texels = len(data) // 16
        limit = int(ctx.info.get("GL_MAX_TEXTURE_BUFFER_SIZE", 65536))
        if texels > limit:
            raise SdfglError(f"scene data of {texels} texels exceeds this GL implementation's buffer texture limit "
                             f"(GL_MAX_TEXTURE_BUFFER_SIZE = {limit}); use fewer or smaller unions kept as data")
        self.gl = _functions()
        self.buffer = ctx.buffer(data)
        name = c_uint(0)
        self.gl.glGenTextures(1, byref(name))
        self.glo = name.value
        self.gl.glBindTexture(TEXTURE_BUFFER, self.glo)
        self.gl.glTexBuffer(TEXTURE_BUFFER, RGBA32F, self.buffer.glo)
        self.gl.glBindTexture(TEXTURE_BUFFER, 0)

    def use(self, unit: int) -> None:
        """Bind to texture unit ``unit`` (a samplerBuffer uniform set to ``unit`` reads it)."""
        self.gl.glActiveTexture(TEXTURE0 + unit)
        self.gl.glBindTexture(TEXTURE_BUFFER, self.glo)

    def point(self, prog: Any, name: str, unit: int) -> None:
        """Set sampler uniform ``name`` of ``prog`` to ``unit``. moderngl sets no samplerBuffer
        uniform (the value stays 0), so a moderngl program's is set here; a viewer's program
        (sdfgl.viewer.programs.RawProgram) sets its own. Nothing to set where the driver dropped
        the sampler (the code does not read it)."""
        if not isinstance(prog, moderngl.Program):
            if name in prog:
                prog[name].value = unit
            return
        loc = self.gl.glGetUniformLocation(prog.glo, name.encode())
        if loc >= 0:
            self.gl.glProgramUniform1i(prog.glo, loc, unit)

    def release(self) -> None:
        """Free the texture and its buffer."""
        if self.glo:
            self.gl.glDeleteTextures(1, byref(c_uint(self.glo)))
            self.glo = 0
            self.buffer.release()
