"""Program cache keyed by source, and compile errors that name the node at fault."""
from __future__ import annotations

import re
import time

import moderngl

from .. import shaderlib
from ..codegen import ShaderSource
from ..errors import ShaderCompileError
from .dialect import of_source

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


class ProgramCache:
    """Compiled programs for one context, keyed by the full fragment source."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self._programs: dict[str, moderngl.Program] = {}
        self.compiles = 0
        self.last_compile_s = 0.0

    def get(self, source: ShaderSource) -> moderngl.Program:
        """The program for ``source``, compiling it only if this exact source is new."""
        prog = self._programs.get(source.text)
        if prog is None:
            t0 = time.perf_counter()
            try:
                vertex = of_source(source.text).convert(shaderlib.read("fullscreen.vert"))
                prog = self.ctx.program(vertex_shader=vertex, fragment_shader=source.text)
            except moderngl.Error as exc:
                raise ShaderCompileError(explain_compile_error(source, str(exc))) from None
            self.last_compile_s = time.perf_counter() - t0
            self.compiles += 1
            self._programs[source.text] = prog
        else:
            self.last_compile_s = 0.0
        return prog

    def __len__(self) -> int:
        return len(self._programs)
