"""The scene is drawn off the window's thread, by two render lanes.

A lane is a thread with a hidden glfw window whose context shares objects with the
viewer's. The *active* lane draws the shown program into its own targets (jittered
full-resolution samples summed in a float texture, or one low-resolution frame while the
camera moves) and resolves each frame into a display texture; the window's thread only
presents the newest display texture, the panel and the overlay, and answers input.

The *idle* lane takes compile jobs: codegen, link, then a warm-up draw into 1x1 targets of
both formats. llvmpipe builds a program's machine code at its first draw in each context
(seconds for a big scene), so that happens in the lane that will draw the program, while
the other lane keeps drawing the old one; the window then switches lanes. Heavy GL calls
(link, draw, finish) go through :mod:`rawgl`, which releases Python's interpreter lock.

Frames are handed over through an :class:`Exchange`: the window writes the newest
:class:`FrameSpec` (what to draw), a lane publishes a :class:`Frame` (a display buffer and
how it was drawn). Display buffers rotate so that a lane never draws into the one on
screen nor the newest one.
"""
from __future__ import annotations

import math
import os
import threading
import time
from collections import OrderedDict
from dataclasses import dataclass, field
from typing import Any

import glfw
import moderngl
import numpy as np

from .. import shaderlib
from ..camera import Camera, OrbitCamera
from ..compiler.source import ShaderSource
from ..errors import SdfglError
from ..gl.cache import default_budget
from ..gl.data import DataTextures
from ..nodes.base import Node
from ..gl.coarse_pass import draw_coarse
from ..gl.raster_pass import RasterImages
from ..gl.targets import Targets
from ..render import raster_pass
from ..uniforms import bind_coarse, bind_raster_images, camera_uniforms, scene_uniforms
from . import rawgl
from .programs import ImageProgram, Job, RawProgram, Result, link, link_image, link_raster, make_source, stamp

LANES = 2
CACHE_SIZE = 12          # warm programs kept per lane, for instant toggling back
STEPS_EVERY_S = 0.25     # the mean-steps readout reads the steps image at most this often
COMPILE_NICE = 10        # how much lower the CPU priority of compiles is than drawing's


def describe_error(exc: BaseException, where: str) -> str:
    """One message for the overlay, whatever the exception (ours name their node or file)."""
    if isinstance(exc, SdfglError):
        return str(exc)
    if isinstance(exc, RecursionError):
        return f"{where}: the scene is nested too deeply for Python's recursion limit ({exc})"
    text = f"{where}: {type(exc).__name__}: {exc}"
    return text if len(text) < 800 else text[:800] + " ..."


def r2(n: int) -> tuple[float, float]:
    """The n-th point of the R2 low-discrepancy sequence, centred on 0 (sub-pixel jitter)."""
    g = 1.32471795724474602596
    return ((0.5 + n / g) % 1.0) - 0.5, ((0.5 + n / (g * g)) % 1.0) - 0.5


@dataclass(frozen=True)
class FrameSpec:
    """What the active lane draws: a new version restarts its accumulation."""

    version: int
    lane: int
    key: str                 # the program's source text (the lane's cache key)
    source: ShaderSource
    scene: Node
    origin: np.ndarray
    camera: Camera           # a copy: the window's camera keeps moving
    size: tuple[int, int]    # the view's size in pixels
    moving: bool
    max_samples: int
    target_ms: float
    adaptive: bool
    meshes: tuple[Any, ...] = ()   # raster meshes (sg.raster), drawn by the raster pass before the march


class DisplayBuffer:
    """An RGBA8 texture at the view's size that the window presents (made in a lane's context)."""

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int]) -> None:
        self.size = size
        self.tex = ctx.texture(size, 4, dtype="f1")
        self.tex.filter = (moderngl.NEAREST, moderngl.NEAREST)
        self.fbo = ctx.framebuffer(color_attachments=[self.tex])
        self.glo = self.tex.glo

    def release(self) -> None:
        self.fbo.release()
        self.tex.release()


@dataclass
class Frame:
    """A published frame: where it is and how it was drawn."""

    spec: FrameSpec
    buffer: DisplayBuffer
    samples: int             # accumulated samples (0 for a low-resolution frame)
    scale: float             # resolution scale (1 when still)
    ms: float                # the scene draw, in the lane (finish included)
    steps: float | None      # mean map() calls per pixel of the pixel-centre rays, when measured
    serial: int = 0


@dataclass
class Exchange:
    """State shared by the window's thread and the lanes; every field is read and written under ``cond``."""

    cond: threading.Condition = field(default_factory=threading.Condition)
    spec: FrameSpec | None = None
    job: Job | None = None                      # the newest compile request (older ones are dropped)
    latest: Frame | None = None
    showing: DisplayBuffer | None = None        # on screen: no lane draws into it
    serial: int = 0
    results: list[Result] = field(default_factory=list)
    errors: list[tuple[int, str]] = field(default_factory=list)   # (spec version, message)
    shot_paths: list[str] = field(default_factory=list)           # screenshots waiting for a finished image
    shots: list[tuple[list[str], np.ndarray]] = field(default_factory=list)
    keep: set[str] = field(default_factory=set)                   # program keys the window may go back to
    lanes: list["Lane"] = field(default_factory=list)
    closing: bool = False

    def busy(self, buf: DisplayBuffer) -> bool:
        return buf is self.showing or (self.latest is not None and buf is self.latest.buffer)


class _Target:
    """A lane's colour + steps framebuffer at one size."""

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int], dtype: str) -> None:
        self.size = size
        self.color = ctx.texture(size, 4, dtype=dtype)
        self.color.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self.steps = ctx.texture(size, 1, dtype="f4")
        self.fbo = ctx.framebuffer(color_attachments=[self.color, self.steps])

    def mean_steps(self, samples: int) -> float:
        arr = np.frombuffer(self.steps.read(), dtype=np.float32)
        return float(arr.mean()) / max(samples, 1)

    def release(self) -> None:
        for obj in (self.fbo, self.color, self.steps):
            obj.release()


class Lane:
    """One render thread and its hidden shared-context window (made on the window's thread)."""

    def __init__(self, index: int, window: Any, exchange: Exchange) -> None:
        self.index, self.ex = index, exchange
        glfw.window_hint(glfw.VISIBLE, False)
        self._hidden = glfw.create_window(16, 16, f"sdfgl render {index}", None, window)
        glfw.default_window_hints()
        glfw.make_context_current(window)
        if not self._hidden:
            raise SdfglError("glfw could not create a render thread's shared context")
        self.warm: OrderedDict[str, ImageProgram] = OrderedDict()  # linked here and drawn once here
        # program key -> the raster meshes' program that goes with it (views with meshes)
        self.raster_programs: dict[str, tuple[ShaderSource, moderngl.Program]] = {}
        # program key -> the coarse pass drawn before it (linked here too), where it has one
        self.coarse_programs: dict[str, tuple[ShaderSource, RawProgram]] = {}
        self._tiles: Targets | None = None  # the coarse pass's tile starts (its lower left part at smaller sizes)
        self._raster: tuple[tuple[int, tuple[int, int]], RasterImages] | None = None  # (spec version, size), images
        self.failed = ""
        self._ready = threading.Event()
        self._drawn = -1          # version of the spec the targets hold
        self._samples = 0
        self._scale = 1.0
        self._last_ms = 0.0
        self._was_moving = False
        self._steps_at = 0.0
        self._last: DisplayBuffer | None = None
        self._pool: list[DisplayBuffer] = []
        self._retired: list[DisplayBuffer] = []
        self._accum: _Target | None = None
        self._low: _Target | None = None
        self._thread = threading.Thread(target=self._run, name=f"sdfgl-render-{index}", daemon=True)
        self._thread.start()

    def wait_ready(self, timeout: float = 60.0) -> None:
        """Block until the lane's GL set-up is done; raise its failure."""
        self._ready.wait(timeout)
        if self.failed:
            raise SdfglError(f"the viewer's render thread could not start: {self.failed}")

    def join(self, timeout: float) -> None:
        self._thread.join(timeout)

    def destroy_window(self) -> None:
        """Destroy the hidden window (window's thread, after join)."""
        if self._hidden:
            glfw.destroy_window(self._hidden)
            self._hidden = None

    # -- the thread -------------------------------------------------------------------
    def _run(self) -> None:
        glfw.make_context_current(self._hidden)
        try:
            self._setup()
        except Exception as exc:  # noqa: BLE001 - reported by wait_ready
            self.failed = describe_error(exc, "render thread")
            self._ready.set()
            glfw.make_context_current(None)
            return
        self._ready.set()
        try:
            while True:
                work = self._next()
                if work is None:
                    break
                if isinstance(work, Job):
                    self._compile(work)
                else:
                    self._frame(work)
        finally:
            self._teardown()
            glfw.make_context_current(None)

    def _setup(self) -> None:
        self.gl = rawgl.GL()
        self.ctx = moderngl.create_context()
        self.vao = self.gl.vertex_array()
        self.data = DataTextures(default_budget)
        self.resolve = self.ctx.program(vertex_shader=shaderlib.read("mains/fullscreen.vert"),
                                        fragment_shader=shaderlib.read("mains/viewer_resolve.frag"))
        self._warm_targets = (_Target(self.ctx, (1, 1), "f4"), _Target(self.ctx, (1, 1), "f1"))
        buf = DisplayBuffer(self.ctx, (1, 1))  # the resolve program's own first draw, here and now
        self._resolve(self._warm_targets[0].color, 1.0, buf)
        self.gl.glFinish()
        buf.release()

    def _teardown(self) -> None:
        for text in list(self.warm):
            self._release_program(text)
        if self._raster is not None:
            self._raster[1].release()
        self.data.clear()
        for t in (self._accum, self._low, self._tiles, *self._warm_targets):
            if t is not None:
                t.release()
        for b in self._pool + self._retired:
            b.release()
        self.gl.glFinish()

    def _next(self) -> Job | FrameSpec | None:
        ex = self.ex
        with ex.cond:
            while True:
                self._free_retired()
                if ex.closing:
                    return None
                spec = ex.spec
                mine = spec is not None and spec.lane == self.index
                if mine and self._wants_draw(spec, bool(ex.shot_paths)):
                    return spec
                if not mine and ex.job is not None:
                    job, ex.job = ex.job, None
                    return job
                ex.cond.wait()

    def _wants_draw(self, spec: FrameSpec, shot: bool) -> bool:
        if spec.version != self._drawn:
            return True
        return not spec.moving and (self._samples < spec.max_samples or shot)

    # -- compiles (idle lane) -----------------------------------------------------------
    def _compile(self, job: Job) -> None:
        """Build ``job`` in a short-lived thread of lower CPU priority (on Linux; its context is this
        lane's): on a busy machine the link and machine-code build then yield to the drawing lane
        and the window's thread, which answer input."""
        glfw.make_context_current(None)
        worker = threading.Thread(target=self._compile_niced, args=(job,), name=f"sdfgl-compile-{self.index}")
        worker.start()
        worker.join()
        glfw.make_context_current(self._hidden)

    def _compile_niced(self, job: Job) -> None:
        try:
            tid = threading.get_native_id()
            os.setpriority(os.PRIO_PROCESS, tid, min(19, os.getpriority(os.PRIO_PROCESS, tid) + COMPILE_NICE))
        except (AttributeError, OSError):  # not Linux, or not allowed: compile at the same priority
            pass
        glfw.make_context_current(self._hidden)
        try:
            self._build(job)
        finally:
            glfw.make_context_current(None)

    def _build(self, job: Job) -> None:
        ex = self.ex
        t0 = time.perf_counter()
        res = Result(job.token, job.meta)
        try:
            source = make_source(job.build)
            res.source = source
            t1 = time.perf_counter()
            with ex.cond:
                active = ex.spec.lane if ex.spec is not None else -1
                found = [i for i in (active, self.index) if i >= 0 and source.text in ex.lanes[i].warm]
            if found:  # warm already: switching to it costs nothing
                res.lane = found[0]
                stamp(res, t0, codegen_s=t1 - t0)
            else:
                coarse_build = job.coarse_build
                coarse_src = None if coarse_build is None else make_source(lambda: coarse_build(source))
                prog = link_image(self.gl, source, self.ctx, tiled=coarse_src is not None)
                raster = coarse = None
                try:
                    if job.mesh_build is not None:
                        mesh_source = make_source(job.mesh_build)
                        raster = (mesh_source, link_raster(mesh_source, self.ctx))
                    if coarse_src is not None:  # linked like the image: the link does not hold the Python lock
                        coarse = (coarse_src, link(self.gl, coarse_src, self.ctx))
                    t2 = time.perf_counter()
                    self._warm_up(prog, source, job, coarse)
                except Exception:
                    for obj in (prog, raster and raster[1], coarse and coarse[1]):
                        if obj:
                            obj.release()
                    raise
                t3 = time.perf_counter()
                with ex.cond:
                    self.warm[source.text] = prog
                    if raster is not None:
                        self.raster_programs[source.text] = raster
                    if coarse is not None:
                        self.coarse_programs[source.text] = coarse
                    self._trim()
                res.lane, res.compiled = self.index, True
                stamp(res, t0, codegen_s=t1 - t0, link_s=t2 - t1, warm_s=t3 - t2)
        except Exception as exc:  # noqa: BLE001 - a user's scene may fail anywhere: report, keep the thread
            res.error = describe_error(exc, "compile")
        with ex.cond:
            ex.results.append(res)
        glfw.post_empty_event()  # wake the window's wait_events

    def _warm_up(self, prog: ImageProgram, source: ShaderSource, job: Job,
                 coarse: tuple[ShaderSource, RawProgram] | None) -> None:
        """Draw once into 1x1 targets of both formats (and the coarse pass once): llvmpipe builds
        the machine code of each now."""
        if coarse is not None:
            self._coarse_pass(coarse, job.scene, OrbitCamera(), (1, 1), job.origin, (0.0, 0.0))
            bind_coarse(prog, source, self._tiles)
        camera_uniforms(prog, OrbitCamera(), (1, 1), job.origin)
        scene_uniforms(prog, source, job.scene, job.origin, self.data)
        for target, blend in zip(self._warm_targets, (True, False)):
            self._draw(prog, target, (0.0, 0.0), blend)

    def _coarse_pass(self, coarse: tuple[ShaderSource, RawProgram], scene: Node, camera: Camera,
                     size: tuple[int, int], origin: np.ndarray, jitter: tuple[float, float]) -> None:
        """Draw the coarse pass of an image of ``size`` (its rays offset by ``jitter``) into the
        tile target."""
        source, cprog = coarse
        camera_uniforms(cprog, camera, size, origin, jitter)
        scene_uniforms(cprog, source, scene, origin, self.data)
        # kept while big enough (moving frames change size every frame); a failed draw releases it
        tiles, self._tiles = self._tiles, None
        self._tiles = draw_coarse(self.ctx, lambda: cprog.render(self.vao), size, source.coarse_tile, tiles)

    def _trim(self) -> None:
        """Release the least recently made programs beyond CACHE_SIZE (never one the window may show)."""
        ex = self.ex
        keep = set(ex.keep)
        for frame_spec in (ex.spec, ex.latest.spec if ex.latest else None):
            if frame_spec is not None:
                keep.add(frame_spec.key)
        for text in list(self.warm):
            if len(self.warm) <= CACHE_SIZE:
                break
            if text not in keep:
                self._release_program(text)

    def _release_program(self, text: str) -> None:
        """Release the warm program ``text`` and those drawn with it (its raster meshes', its coarse pass)."""
        self.warm.pop(text).release()
        for extra in (self.raster_programs.pop(text, None), self.coarse_programs.pop(text, None)):
            if extra is not None:
                extra[1].release()

    def _bind_meshes(self, spec: FrameSpec, prog: ImageProgram, size: tuple[int, int]) -> None:
        """Draw the spec's raster meshes at ``size`` (once per spec and size: they do not take the
        samples' jitter) and bind their textures for the march ``prog``."""
        key = (spec.version, size)
        if self._raster is None or self._raster[0] != key:
            if self._raster is not None:
                self._raster[1].release()
                self._raster = None
            found = self.raster_programs.get(spec.key)
            if found is None:
                raise SdfglError("render: the raster meshes' program is not in this render thread's cache")
            mesh_source, mesh_prog = found
            self._raster = key, raster_pass(mesh_prog, mesh_source, spec.scene, spec.camera, size, spec.origin,
                                            spec.meshes, self.data)
        images = self._raster[1]
        bind_raster_images(prog, spec.source, images.depth_texture, images.color_texture)

    # -- frames (active lane) -------------------------------------------------------------
    def _draw(self, prog: ImageProgram, target: _Target, jitter: tuple[float, float], blend: bool,
              size: tuple[int, int] | None = None) -> float:
        target.fbo.use()
        self.ctx.viewport = (0, 0, *(size or target.size))
        if blend:
            self.ctx.enable(moderngl.BLEND)
            self.ctx.blend_func = moderngl.ONE, moderngl.ONE
        t0 = time.perf_counter()
        prog.render(self.vao, size or target.size)
        self.gl.glFinish()
        ms = 1000 * (time.perf_counter() - t0)
        if blend:
            self.ctx.disable(moderngl.BLEND)
        return ms

    def _frame(self, spec: FrameSpec) -> None:
        try:
            self._frame_or_raise(spec)
        except Exception as exc:  # noqa: BLE001 - shown in the window, which goes back to what drew last
            self._drawn, self._samples = spec.version, spec.max_samples
            with self.ex.cond:
                self.ex.errors.append((spec.version, describe_error(exc, "render")))
            glfw.post_empty_event()

    def _frame_or_raise(self, spec: FrameSpec) -> None:
        ex = self.ex
        if spec.version == self._drawn and not spec.moving and self._samples >= spec.max_samples:
            self._deliver_shots()
            return
        prog = self.warm.get(spec.key)
        if prog is None:
            raise SdfglError("render: the program to draw is not in this render thread's cache")
        if spec.version != self._drawn:
            self._drawn, self._samples = spec.version, 0
        scene_uniforms(prog, spec.source, spec.scene, spec.origin, self.data)
        if spec.moving:
            if spec.adaptive and not self._was_moving and self._last_ms > spec.target_ms:
                # the first moving frame: start from what the last full-resolution frame cost
                self._scale = max(0.1, min(self._scale, math.sqrt(spec.target_ms / self._last_ms)))
            scale = self._scale if spec.adaptive else 1.0
            size = (max(1, int(spec.size[0] * scale)), max(1, int(spec.size[1] * scale)))
            if self._low is None or self._low.size[0] < size[0] or self._low.size[1] < size[1]:
                if self._low is not None:
                    self._low.release()
                self._low = _Target(self.ctx, spec.size, "f1")  # room for any scale of this view
            camera_uniforms(prog, spec.camera, size, spec.origin, (0.0, 0.0))
            if spec.meshes:
                self._bind_meshes(spec, prog, size)
            ms = self._coarse_before(spec, prog, size, (0.0, 0.0))
            ms += self._draw(prog, self._low, (0.0, 0.0), False, size)
            if spec.adaptive:  # area scales with scale^2; damp the correction
                want = scale * math.sqrt(spec.target_ms / max(ms, 1e-3))
                self._scale = float(min(1.0, max(0.1, 0.5 * scale + 0.5 * want)))
            source, weight, samples = self._low, 1.0, 0
            uv_scale = (size[0] / self._low.size[0], size[1] / self._low.size[1])
        else:
            scale = 1.0
            if self._accum is None or self._accum.size != spec.size:
                if self._accum is not None:
                    self._accum.release()
                self._accum = _Target(self.ctx, spec.size, "f4")
            if self._samples == 0:
                self._accum.fbo.clear(0.0, 0.0, 0.0, 0.0)
            camera_uniforms(prog, spec.camera, spec.size, spec.origin, r2(self._samples))
            if spec.meshes:
                self._bind_meshes(spec, prog, spec.size)
            ms = self._coarse_before(spec, prog, spec.size, r2(self._samples))
            ms += self._draw(prog, self._accum, r2(self._samples), True)
            self._samples += 1
            source, weight, samples = self._accum, 1.0 / self._samples, self._samples
            uv_scale = (1.0, 1.0)
        self._was_moving, self._last_ms = spec.moving, ms
        buf = self._free_buffer(spec.size)
        self._resolve(source.color, weight, buf, uv_scale)
        self.gl.glFinish()
        now = time.perf_counter()
        steps = None
        if now - self._steps_at > STEPS_EVERY_S or samples >= spec.max_samples or spec.moving:
            steps = self._mean_steps(source, samples, uv_scale)
            self._steps_at = now
        self._last = buf
        with ex.cond:
            if ex.spec is None or ex.spec.lane != self.index:
                return  # the window switched lanes meanwhile: this frame is not wanted
            ex.serial += 1
            ex.latest = Frame(spec, buf, samples, scale, ms, steps, ex.serial)
        if samples >= spec.max_samples:
            self._deliver_shots()
        glfw.post_empty_event()

    def _coarse_before(self, spec: FrameSpec, prog: ImageProgram, size: tuple[int, int],
                       jitter: tuple[float, float]) -> float:
        """Draw the coarse pass of the spec's program (where it has one) for an image of ``size``
        whose rays are offset by ``jitter``, and bind its tile starts for ``prog``; its ms."""
        coarse = self.coarse_programs.get(spec.key)
        if coarse is None:
            return 0.0
        t0 = time.perf_counter()
        self._coarse_pass(coarse, spec.scene, spec.camera, size, spec.origin, jitter)
        bind_coarse(prog, spec.source, self._tiles)
        return 1000 * (time.perf_counter() - t0)

    def _mean_steps(self, target: _Target, samples: int, uv_scale: tuple[float, float]) -> float:
        if uv_scale == (1.0, 1.0):
            return target.mean_steps(samples)
        w, h = (max(1, round(s * n)) for s, n in zip(uv_scale, target.size))
        arr = np.frombuffer(target.steps.read(), dtype=np.float32).reshape(target.size[1], target.size[0])
        return float(arr[:h, :w].mean())

    def _resolve(self, source: moderngl.Texture, weight: float, buf: DisplayBuffer,
                 uv_scale: tuple[float, float] = (1.0, 1.0)) -> None:
        source.use(0)
        self.resolve["uSource"].value = 0
        self.resolve["uWeight"].value = weight
        self.resolve["uSize"].value = (buf.size[0] / uv_scale[0], buf.size[1] / uv_scale[1])
        buf.fbo.use()
        self.ctx.viewport = (0, 0, *buf.size)
        self.gl.glUseProgram(self.resolve.glo)
        self.gl.glBindVertexArray(self.vao)
        self.gl.glDrawArrays(rawgl.TRIANGLES, 0, 3)

    def _free_buffer(self, size: tuple[int, int]) -> DisplayBuffer:
        with self.ex.cond:
            for b in [b for b in self._pool if b.size != size]:
                self._pool.remove(b)
                self._retired.append(b)
            self._free_retired()
            for b in self._pool:
                if not self.ex.busy(b) and b is not self._last:
                    return b
        buf = DisplayBuffer(self.ctx, size)
        self._pool.append(buf)
        return buf

    def _free_retired(self) -> None:
        """Release display buffers of an old size that are no longer on screen (holding ``cond``)."""
        for b in [b for b in self._retired if not self.ex.busy(b)]:
            self._retired.remove(b)
            if b is self._last:
                self._last = None
            b.release()

    def _deliver_shots(self) -> None:
        """Hand the finished image to the screenshots waiting for it (rows top first, RGB)."""
        ex = self.ex
        if self._last is None:
            return
        with ex.cond:
            paths, ex.shot_paths = ex.shot_paths, []
        if not paths:
            return
        w, h = self._last.size
        img = np.frombuffer(self._last.tex.read(), dtype=np.uint8).reshape(h, w, 4)[::-1, :, :3].copy()
        with ex.cond:
            ex.shots.append((paths, img))
        glfw.post_empty_event()
