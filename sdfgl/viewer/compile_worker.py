"""Compiles off the window's loop: codegen and link in a worker thread.

The worker owns a hidden glfw window whose context shares objects with the viewer's.
moderngl cannot be used there: it keeps Python's interpreter lock through the driver's
compile (so the window's loop would stop all the same) and refuses a program made by
another moderngl context. So the worker links with plain GL calls through ctypes
(which release the lock); the window draws the program as a :class:`RawProgram`.

Not covered: Mesa's llvmpipe builds a program's machine code at its first draw in each
context (a warm-up draw in the worker's context was measured not to carry over), so
that part still runs on the window's thread, at the first frame of a new program and
of each target format. Drawing the scene in the worker's context is the next step.
"""
from __future__ import annotations

import queue
import threading
import time
from collections import OrderedDict
from dataclasses import dataclass, field
from typing import Any, Callable

import glfw
import moderngl

from .. import shaderlib
from ..codegen import ShaderSource
from ..errors import SdfglError
from ..gl.dialect import of_source
from ..gl.programs import explain_compile_error
from . import rawgl

CACHE_SIZE = 24  # programs kept for instant toggling back


class RawProgram:
    """A program linked by the worker, with the little of moderngl's Program API the renderer's
    uniform helpers use: ``name in prog``, ``prog[name].value = v`` and ``prog.ctx``."""

    def __init__(self, gl: rawgl.GL, glo: int, uniforms: dict[str, tuple[int, int]], ctx: moderngl.Context) -> None:
        self.gl, self.glo, self.ctx = gl, glo, ctx
        self._uniforms = {name.removesuffix("[0]"): v for name, v in uniforms.items()}

    def __contains__(self, name: str) -> bool:
        return name in self._uniforms

    def __getitem__(self, name: str) -> "_Uniform":
        return _Uniform(self, name)

    def render(self, vao: int) -> None:
        """Draw the full-screen triangle into the bound framebuffer (main thread)."""
        self.gl.glUseProgram(self.glo)
        self.gl.glBindVertexArray(vao)
        self.gl.glDrawArrays(rawgl.TRIANGLES, 0, 3)

    def release(self) -> None:
        if self.glo:
            self.gl.glDeleteProgram(self.glo)
            self.glo = 0


class _Uniform:
    def __init__(self, prog: RawProgram, name: str) -> None:
        self.prog, self.name = prog, name

    @property
    def value(self) -> Any:
        raise AttributeError("uniform values are write-only here")

    @value.setter
    def value(self, v: Any) -> None:
        loc, typ = self.prog._uniforms[self.name]
        self.prog.gl.set_uniform(self.prog.glo, loc, typ, v)


@dataclass
class Job:
    """One compile: ``build`` makes the source (codegen runs in the worker too); ``meta`` comes back."""

    token: int
    build: Callable[[], ShaderSource]
    meta: Any = None


@dataclass
class Result:
    token: int
    meta: Any
    program: RawProgram | None = None
    source: ShaderSource | None = None
    error: str = ""
    compiled: bool = False   # a new program was linked (not found in the cache)
    seconds: float = 0.0     # codegen + link in the worker
    timings: dict[str, float] = field(default_factory=dict)


class CompileWorker:
    """A thread that turns jobs into programs for the window's context; results are collected with poll()."""

    def __init__(self, window: Any, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.gl = rawgl.GL()  # the main thread's context is current: load the entry points here
        self.vao = self.gl.vertex_array()
        glfw.window_hint(glfw.VISIBLE, False)
        self._hidden = glfw.create_window(16, 16, "sdfgl compiler", None, window)
        glfw.default_window_hints()
        glfw.make_context_current(window)
        if not self._hidden:
            raise SdfglError("glfw could not create the compile worker's shared context")
        self._cache: OrderedDict[str, RawProgram] = OrderedDict()
        self._jobs: queue.Queue[Job | None] = queue.Queue()
        self._results: list[Result] = []
        self._lock = threading.Lock()
        self._busy = False
        self._thread = threading.Thread(target=self._run, name="sdfgl-compile", daemon=True)
        self._thread.start()

    # -- main thread ------------------------------------------------------------------
    def submit(self, job: Job) -> None:
        """Queue a compile; older queued jobs are dropped (the newest request wins)."""
        self._jobs.put(job)

    def poll(self) -> list[Result]:
        """Results finished since the last call, oldest first; their programs enter the cache."""
        with self._lock:
            out, self._results = self._results, []
        for r in out:
            if r.program is not None and r.source is not None:
                self._cache[r.source.text] = r.program
                self._cache.move_to_end(r.source.text)
        return out

    @property
    def busy(self) -> bool:
        return self._busy or not self._jobs.empty()

    def close(self) -> None:
        """Stop the thread and release the programs and the hidden window (main thread)."""
        self._jobs.put(None)
        self._thread.join(timeout=120)
        for prog in self._cache.values():
            prog.release()
        self._cache.clear()
        if self._hidden:
            glfw.destroy_window(self._hidden)
            self._hidden = None

    def trim(self, *keep: RawProgram | None) -> None:
        """Release the least recently made programs beyond CACHE_SIZE (never those in ``keep``)."""
        while len(self._cache) > CACHE_SIZE:
            text, prog = next(iter(self._cache.items()))
            if any(prog is k for k in keep):
                self._cache.move_to_end(text)
                continue
            del self._cache[text]
            prog.release()

    # -- worker thread ----------------------------------------------------------------
    def _newest(self, job: Job) -> Job | None:
        while True:
            try:
                nxt = self._jobs.get_nowait()
            except queue.Empty:
                return job
            if nxt is None:
                return None
            job = nxt

    def _run(self) -> None:
        glfw.make_context_current(self._hidden)
        gl = rawgl.GL()
        while True:
            job = self._jobs.get()
            if job is not None:
                self._busy = True
                job = self._newest(job)
            if job is None:
                break
            result = self._compile(gl, job)
            with self._lock:
                self._results.append(result)
            self._busy = False
            glfw.post_empty_event()  # wake the window's wait_events
        glfw.make_context_current(None)

    def _compile(self, gl: rawgl.GL, job: Job) -> Result:
        t0 = time.perf_counter()
        res = Result(job.token, job.meta)
        try:
            source = job.build()
        except SdfglError as exc:
            res.error = str(exc)
            return res
        except Exception as exc:  # codegen of a user's scene: report, never kill the thread
            res.error = f"code generation failed: {type(exc).__name__}: {exc}"
            return res
        res.source = source
        t1 = time.perf_counter()
        cached = self._cache.get(source.text)
        if cached is not None:
            res.program = cached
            res.seconds = time.perf_counter() - t0
            return res
        try:
            vertex = of_source(source.text).convert(shaderlib.read("fullscreen.vert"))
            glo = gl.link(vertex, source.text)
        except rawgl.GLError as exc:
            res.error = explain_compile_error(source, str(exc))
            return res
        uniforms = gl.uniforms(glo)
        gl.glFinish()  # the program is complete before the main thread sees it
        t2 = time.perf_counter()
        res.program = RawProgram(self.gl, glo, uniforms, self.ctx)
        res.compiled = True
        res.seconds = t2 - t0
        res.timings = {"codegen_s": t1 - t0, "link_s": t2 - t1,
                       "wall_end": time.time(), "wall_start": time.time() - (t2 - t0)}
        return res

