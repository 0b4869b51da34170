"""Program cache keyed by source (LRU within a budget), and compile errors that name the node at fault."""
from __future__ import annotations

import re
import time
from typing import Callable, Union

import moderngl

from .. import shaderlib
from ..compiler.source import ShaderSource
from ..errors import ShaderCompileError
from .cache import LRU, CacheBudget
from .context import CurrentContext, GLThread
from .dialect import of_source

GL = Union[GLThread, CurrentContext]

# Mesa: "0:12(5): error: ...", NVIDIA: "0(12) : error ...", ANGLE/others: "ERROR: 0:12: ..."
_LINE = re.compile(r"(?:^|\s)0[:(](\d+)[:)(]")


def explain_compile_error(source: ShaderSource, message: str) -> str:
    """Annotate a driver's compile log with the owner and text of each failing line."""
    lines = source.text.split("\n")
    notes = []
    for raw in message.splitlines():
        m = _LINE.search(raw)
        if not m:
            continue
        n = int(m.group(1))
        code = lines[n - 1].strip() if 1 <= n <= len(lines) else ""
        notes.append(f"  line {n} (from {source.owner_of(n)}): {code}")
    where = "\n".join(dict.fromkeys(notes)) or "  (the driver named no line)"
    return f"the GL driver rejected the generated shader:\n{message.strip()}\nat:\n{where}"


FULLSCREEN = "mains/fullscreen.vert"
"""The vertex shader of the full-screen triangle most programs draw."""


class ProgramCache:
    """Compiled programs (with their full-screen vertex arrays) of one context, keyed by the full
    fragment source; the least recently used are released beyond ``budget().programs``.

    ``get`` may be called from any thread: the compile runs where the context lives."""

    def __init__(self, gl: GL, budget: Callable[[], CacheBudget]) -> None:
        self.gl = gl
        self._budget = budget
        self._lru: LRU[tuple[moderngl.Program, moderngl.VertexArray]] = LRU(self._release)
        self._vaos: dict[int, moderngl.VertexArray] = {}
        self._epoch = gl.epoch
        self.compiles = 0
        self.evictions = 0
        self.last_compile_s = 0.0

    @property
    def ctx(self) -> moderngl.Context:
        return self.gl.ctx

    def get(self, source: ShaderSource) -> moderngl.Program:
        """The program for ``source``, compiling it only if this exact source is not cached."""
        return self.gl.call(self._get, source)[0]

    def entry(self, source: ShaderSource, vertex: str = FULLSCREEN) -> tuple[moderngl.Program, moderngl.VertexArray]:
        """(program, vertex array) for ``source`` under the vertex shader ``shaders/<vertex>.glsl``
        (default: the full-screen triangle, which the vertex array draws); call on the context's thread."""
        return self._get(source, vertex)

    def cached(self, source: ShaderSource, vertex: str = FULLSCREEN) -> bool:
        """Whether the program for ``source`` under ``vertex`` is linked and cached (in this context)."""
        self.sync()
        return self._lru.get(self._key(source, vertex)) is not None

    def vao(self, prog: moderngl.Program) -> moderngl.VertexArray:
        """The buffer-less vertex array that draws the full-screen triangle with cached ``prog``."""
        vao = self._vaos.get(id(prog))
        if vao is None:
            raise ShaderCompileError("this program is no longer cached (evicted or its context was replaced); "
                                     "get it again from the cache")
        return vao

    def _release(self, entry: tuple[moderngl.Program, moderngl.VertexArray]) -> None:
        self._vaos.pop(id(entry[0]), None)
        entry[1].release()
        entry[0].release()

    def sync(self) -> None:
        """Forget every entry if the context was replaced (after a fork): its objects are gone."""
        if self._epoch != self.gl.epoch:
            self._lru.forget()
            self._vaos.clear()
            self._epoch = self.gl.epoch

    @staticmethod
    def _key(source: ShaderSource, vertex: str) -> str:
        return source.text if vertex == FULLSCREEN else f"{vertex}\n{source.text}"

    def _get(self, source: ShaderSource, vertex: str = FULLSCREEN) -> tuple[moderngl.Program, moderngl.VertexArray]:
        ctx = self.gl.ctx
        self.sync()
        key = self._key(source, vertex)
        entry = self._lru.get(key)
        if entry is not None:
            self.last_compile_s = 0.0
            return entry
        t0 = time.perf_counter()
        try:
            vert = of_source(source.text).convert(shaderlib.read(vertex))
            prog = ctx.program(vertex_shader=vert, fragment_shader=source.text)
        except moderngl.Error as exc:
            raise ShaderCompileError(explain_compile_error(source, str(exc))) from None
        self.last_compile_s = time.perf_counter() - t0
        self.compiles += 1
        entry = (prog, ctx.vertex_array(prog, []))
        self._lru.put(key, entry)
        self._vaos[id(prog)] = entry[1]
        before = len(self._lru)
        self._lru.trim(max_items=self._budget().programs)
        self.evictions += before - len(self._lru)
        return entry

    def clear(self) -> None:
        """Release every cached program."""
        self.gl.call(self._clear)

    def _clear(self) -> None:
        self.sync()
        self._lru.clear()
        self._vaos.clear()

    def __len__(self) -> int:
        return len(self._lru)
