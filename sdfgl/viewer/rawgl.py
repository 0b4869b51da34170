"""The few OpenGL entry points the render threads (and the window, to bind their images) call through ctypes.

moderngl holds Python's global interpreter lock while the driver compiles and links,
so a moderngl compile or draw in a thread still stops the window's loop; a ctypes call releases
the lock for the length of the call. A program linked here lives in the share group of
the viewer's context and is drawn by :class:`sdfgl.viewer.programs.RawProgram`.
"""
from __future__ import annotations

import ctypes
from ctypes import POINTER, byref, c_char, c_char_p, c_float, c_int, c_uint
from typing import Any

import glfw

from ..errors import ContextError

VERTEX_SHADER, FRAGMENT_SHADER = 0x8B31, 0x8B30
COMPILE_STATUS, LINK_STATUS, INFO_LOG_LENGTH = 0x8B81, 0x8B82, 0x8B84
ACTIVE_UNIFORMS = 0x8B86
FLOAT, FLOAT_VEC2, FLOAT_VEC3, FLOAT_VEC4, INT, SAMPLER_2D = 0x1406, 0x8B50, 0x8B51, 0x8B52, 0x1404, 0x8B5E
INT_VEC2 = 0x8B53
SAMPLER_BUFFER = 0x8DC2
POINTS, TRIANGLES = 0x0000, 0x0004
TEXTURE_2D, TEXTURE0 = 0x0DE1, 0x84C0

_SIGNATURES: dict[str, tuple[Any, ...]] = {
    "glCreateShader": (c_uint, c_uint),
    "glShaderSource": (None, c_uint, c_int, POINTER(c_char_p), POINTER(c_int)),
    "glCompileShader": (None, c_uint),
    "glGetShaderiv": (None, c_uint, c_uint, POINTER(c_int)),
    "glGetShaderInfoLog": (None, c_uint, c_int, POINTER(c_int), POINTER(c_char)),
    "glDeleteShader": (None, c_uint),
    "glCreateProgram": (c_uint,),
    "glAttachShader": (None, c_uint, c_uint),
    "glLinkProgram": (None, c_uint),
    "glGetProgramiv": (None, c_uint, c_uint, POINTER(c_int)),
    "glGetProgramInfoLog": (None, c_uint, c_int, POINTER(c_int), POINTER(c_char)),
    "glDeleteProgram": (None, c_uint),
    "glGetActiveUniform": (None, c_uint, c_uint, c_int, POINTER(c_int), POINTER(c_int), POINTER(c_uint),
                           POINTER(c_char)),
    "glGetUniformLocation": (c_int, c_uint, c_char_p),
    "glProgramUniform1f": (None, c_uint, c_int, c_float),
    "glProgramUniform2f": (None, c_uint, c_int, c_float, c_float),
    "glProgramUniform3f": (None, c_uint, c_int, c_float, c_float, c_float),
    "glProgramUniform4f": (None, c_uint, c_int, c_float, c_float, c_float, c_float),
    "glProgramUniform1i": (None, c_uint, c_int, c_int),
    "glProgramUniform2i": (None, c_uint, c_int, c_int, c_int),
    "glUseProgram": (None, c_uint),
    "glGenVertexArrays": (None, c_int, POINTER(c_uint)),
    "glBindVertexArray": (None, c_uint),
    "glDrawArrays": (None, c_uint, c_int, c_int),
    "glFinish": (None,),
    "glActiveTexture": (None, c_uint),
    "glBindTexture": (None, c_uint, c_uint),
}


class GL:
    """GL functions by name (``gl.glLinkProgram(p)``), loaded while a context is current."""

    def __init__(self) -> None:
        for name, (restype, *argtypes) in _SIGNATURES.items():
            addr = glfw.get_proc_address(name)
            if not addr:
                raise ContextError(f"the OpenGL driver lacks {name} (the viewer's background compiles need "
                                   f"OpenGL 4.1 or ARB_separate_shader_objects)")
            setattr(self, name, ctypes.CFUNCTYPE(restype, *argtypes)(addr))

    def _log(self, getter: Any, logger: Any, obj: int) -> str:
        n = c_int(0)
        getter(obj, INFO_LOG_LENGTH, byref(n))
        buf = ctypes.create_string_buffer(max(n.value, 1))
        logger(obj, len(buf), None, buf)
        return buf.value.decode("utf-8", "replace")

    def _shader(self, kind: int, text: str) -> int:
        sh = self.glCreateShader(kind)
        data = text.encode()
        self.glShaderSource(sh, 1, byref(c_char_p(data)), byref(c_int(len(data))))
        self.glCompileShader(sh)
        ok = c_int(0)
        self.glGetShaderiv(sh, COMPILE_STATUS, byref(ok))
        if not ok.value:
            log = self._log(self.glGetShaderiv, self.glGetShaderInfoLog, sh)
            self.glDeleteShader(sh)
            raise GLError(f"{'vertex' if kind == VERTEX_SHADER else 'fragment'}_shader\n{'=' * 15}\n{log}")
        return sh

    def link(self, vertex: str, fragment: str) -> int:
        """A linked program's name; GLError with the driver's log on failure."""
        vs = self._shader(VERTEX_SHADER, vertex)
        try:
            fs = self._shader(FRAGMENT_SHADER, fragment)
        except GLError:
            self.glDeleteShader(vs)
            raise
        prog = self.glCreateProgram()
        self.glAttachShader(prog, vs)
        self.glAttachShader(prog, fs)
        self.glLinkProgram(prog)
        self.glDeleteShader(vs)
        self.glDeleteShader(fs)
        ok = c_int(0)
        self.glGetProgramiv(prog, LINK_STATUS, byref(ok))
        if not ok.value:
            log = self._log(self.glGetProgramiv, self.glGetProgramInfoLog, prog)
            self.glDeleteProgram(prog)
            raise GLError(f"program\n{'=' * 7}\n{log}")
        return prog

    def uniforms(self, prog: int) -> dict[str, tuple[int, int]]:
        """Active uniforms of ``prog``: name -> (location, GL type)."""
        n = c_int(0)
        self.glGetProgramiv(prog, ACTIVE_UNIFORMS, byref(n))
        out = {}
        buf = ctypes.create_string_buffer(256)
        for i in range(n.value):
            length, size, typ = c_int(0), c_int(0), c_uint(0)
            self.glGetActiveUniform(prog, i, len(buf), byref(length), byref(size), byref(typ), buf)
            name = buf.value.decode()
            out[name] = (self.glGetUniformLocation(prog, name.encode()), typ.value)
        return out

    def set_uniform(self, prog: int, location: int, typ: int, value: Any) -> None:
        """Set a float/vecN/int/ivec2/sampler uniform of ``prog`` (no binding needed)."""
        if typ in (INT, SAMPLER_2D, SAMPLER_BUFFER):
            self.glProgramUniform1i(prog, location, int(value))
        elif typ == FLOAT:
            self.glProgramUniform1f(prog, location, float(value))
        elif typ == INT_VEC2:
            self.glProgramUniform2i(prog, location, *(int(x) for x in value))
        else:
            setter = {FLOAT_VEC2: self.glProgramUniform2f, FLOAT_VEC3: self.glProgramUniform3f,
                      FLOAT_VEC4: self.glProgramUniform4f}.get(typ)
            if setter is None:
                raise GLError(f"uniform type 0x{typ:x} is not supported by the viewer")
            setter(prog, location, *(float(x) for x in value))

    def bind_texture(self, unit: int, texture: int) -> None:
        """Bind 2D texture ``texture`` (a GL name, possibly from a shared context) to ``unit``."""
        self.glActiveTexture(TEXTURE0 + unit)
        self.glBindTexture(TEXTURE_2D, texture)

    def vertex_array(self) -> int:
        """An empty vertex array object (core profile draws need one bound)."""
        vao = c_uint(0)
        self.glGenVertexArrays(1, byref(vao))
        return vao.value


class GLError(Exception):
    """The driver rejected a shader or program; the message is its log."""
