"""render(): scene + camera + settings -> program -> one draw -> RenderResult."""
from __future__ import annotations

import atexit
import dataclasses
import threading
import time
import weakref
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Sequence, TypeVar

import moderngl
import numpy as np

from .camera import Camera, OrbitCamera
from .compiler.generate import generate
from .compiler.source import ShaderSource
from .compiler.analysis import moving_origin, near_work
from .errors import ParameterError, SdfglError
from .gl.cache import CacheBudget, default_budget
from .gl.context import CurrentContext, GLThread, describe, gl_thread
from .gl.coarse_pass import TILES_VERTEX, WHOLE, coarse_size, draw_coarse, draw_tiles, tile_sources
from .gl.data import DataTextures
from .gl.programs import FULLSCREEN, ProgramCache
from .gl.raster_pass import RasterImages, draw_meshes, view_range
from .gl.targets import TargetCache, Targets
from .nodes.base import Node
from .raster import RasterMesh
from .settings import OUTPUTS, Settings
from .uniforms import bind_coarse, bind_raster_images, camera_uniforms, origin_uniforms, scene_uniforms, set_uniform

T = TypeVar("T")


def shader_origin(scene: Node, eye: np.ndarray) -> np.ndarray:
    """The world point the shader's float32 coordinates are taken relative to: the centre
    of the scene's box (at the parameters' current values), or the eye for an unbounded scene.

    float32 then only has to resolve the scene relative to that point, the same at any
    offset from the world origin. A bounded scene without live parameters has the point
    folded into its constants (it never moves); elsewhere (:func:`sdfgl.compiler.analysis.moving_origin`)
    the shader reads it through uniforms summed in float64 at every draw
    (:func:`origin_uniforms`), so a moving camera or parameter never changes the source.

    A scene that spans scales around the eye (a part near the eye far smaller than the whole
    box, :func:`sdfgl.compiler.analysis.near_work`) takes the point at the eye instead,
    rounded to a grid of the near part's distance (so nearby eyes share it): float32 then
    resolves the near part as finely as its own size asks.
    """
    lo, hi = scene.bounds
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        return np.asarray(eye, dtype=np.float64)
    near = near_work(scene, eye)
    if near is not None and near > 0:
        cell = 2.0 ** np.floor(np.log2(near))
        return np.round(np.asarray(eye, dtype=np.float64) / cell) * cell
    return np.asarray((lo + hi) / 2, dtype=np.float64)


def origin_key(scene: Node, origin: np.ndarray) -> bytes | None:
    """What of ``origin`` the render source depends on (None where the origin is a uniform)."""
    return None if moving_origin(scene) else np.asarray(origin, dtype=np.float64).tobytes()


@dataclass
class RenderResult:
    """Images of one draw. Row 0 is the top row of the image.

    ``color`` is uint8 (H, W, 3), gamma-corrected; ``depth`` float32 (H, W), the ray
    parameter t of the pixel centre (inf on a miss); ``normal`` float32 (H, W, 3) unit
    normals (0 on a miss); ``steps`` int32 map() calls. ``save(path)`` writes the colour
    image; :func:`sdfgl.outputs.save_outputs` writes the others or an .npz.

    Example:
        >>> res = sg.render(sg.box(1), size=(16, 12))
        >>> res.color.dtype.name, res.depth is None
        ('uint8', True)
    """

    color: np.ndarray                      # uint8 (H, W, 3), gamma-corrected; (H, W, 4) with alpha=True
    depth: np.ndarray | None = None        # float32 (H, W): ray t of the pixel centre, inf on a miss
    normal: np.ndarray | None = None       # float32 (H, W, 3): unit normal, 0 on a miss
    steps: np.ndarray | None = None        # int32 (H, W): map() calls of the pixel-centre ray
    source: ShaderSource | None = None
    settings: Settings | None = None
    camera: Camera | None = None
    timings: dict[str, float] = field(default_factory=dict)

    def __repr__(self) -> str:
        h, w = self.color.shape[:2]
        outs = ", ".join(n for n in ("color", "depth", "normal", "steps") if getattr(self, n) is not None)
        ms = f", {1000 * self.timings['total_s']:.1f} ms" if "total_s" in self.timings else ""
        lines = f", {len(self.source.owners)} GLSL lines" if self.source is not None else ""
        return f"<RenderResult {w}x{h} [{outs}]{ms}{lines}>"

    def _repr_png_(self) -> bytes:
        """The colour image as PNG: Jupyter shows a result inline."""
        from .png import encode_png
        return encode_png(self.color)

    def save(self, path: str | Path, **options: object) -> Path:
        """Write the colour image as PNG (or any format Pillow knows from the suffix);
        ``options`` go to Pillow (a PNG without them is written by :func:`sdfgl.png.encode_png`)."""
        from .outputs import write_image
        return write_image(self.color, path, **options)


def checked_size(size: Sequence[int], what: str = "render", limit: int = 16384) -> tuple[int, int]:
    """(width, height) from ``size``, refused (naming ``what``) unless two whole numbers in 1..limit."""
    try:
        w, h = (int(x) for x in size)
        ok = all(float(x) == int(x) for x in size)
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(f"{what}: 'size' must be (width, height), got {size!r}") from None
    if not ok or not (1 <= w <= limit and 1 <= h <= limit):
        raise ParameterError(f"{what}: 'size' must be two integers in 1..{limit}, got {size!r}")
    return w, h


def check_float32_camera(camera: Camera, origin: np.ndarray) -> None:
    """Refuse a camera whose eye, relative to the shader origin, float32 cannot hold."""
    rel = np.asarray(camera.eye, dtype=np.float64) - origin
    if not np.all(np.abs(rel) < 1e30):
        raise ParameterError(f"render: camera eye {tuple(np.asarray(camera.eye).tolist())} is {float(np.max(np.abs(rel))):g} "
                             f"from the scene, beyond what the shader's float32 can hold (1e30)")


def check_size(ctx: moderngl.Context, size: tuple[int, int], what: str = "render: 'size'") -> None:
    """Refuse an image larger than the GL implementation's textures and viewports can hold."""
    info = ctx.info
    limit = min(int(info.get("GL_MAX_TEXTURE_SIZE", 16384)), *(int(x) for x in info.get("GL_MAX_VIEWPORT_DIMS",
                                                                                          (16384, 16384))))
    if max(size) > limit:
        raise ParameterError(f"{what} {size[0]}x{size[1]} exceeds this GL implementation's largest texture and "
                             f"viewport side ({limit}, GL_MAX_TEXTURE_SIZE / GL_MAX_VIEWPORT_DIMS of "
                             f"{describe(ctx)})")


class _Limits:
    """A renderer's own budget, or the global one: what its caches ask for their limits."""

    def __init__(self, budget: CacheBudget | None) -> None:
        self.budget = budget

    def __call__(self) -> CacheBudget:
        return self.budget if self.budget is not None else default_budget()


def _free_caches(gl: GLThread | CurrentContext, epoch: list[int], programs: ProgramCache, data: DataTextures,
                 targets: TargetCache) -> None:
    """Release a renderer's GL objects (on its context's thread); forget them if the context is gone."""
    if epoch[0] != gl.epoch:
        data.forget()
        targets.forget()
    else:
        data.clear()
        targets.clear()
    programs._clear()  # syncs with the context itself


class Renderer:
    """Draws scenes on one GL context, caching programs by source and targets by size (LRU, bounded).

    Without ``ctx`` it renders headless on the process's GL thread (see :mod:`sdfgl.gl.context`):
    every method may be called from any thread, and survives ``fork``. With ``ctx`` (a window's
    context) its GL work runs on the calling thread, which must be the one that context is
    current on. ``budget`` gives it cache limits of its own (default: ``sg.cache_budget()``).
    
    Example:
        >>> r = sg.Renderer()
        >>> r.render(sg.sphere(1), size=(8, 8)).color.shape
        (8, 8, 3)
    """

    def __init__(self, ctx: moderngl.Context | None = None, budget: CacheBudget | None = None) -> None:
        self.gl: GLThread | CurrentContext = gl_thread() if ctx is None else CurrentContext(ctx)
        self._limits = _Limits(budget)
        self.programs = ProgramCache(self.gl, self._limits)
        self.data = DataTextures(self._limits)
        self.targets = TargetCache(self._limits)
        self._epoch = [self.gl.epoch]
        self._last_source: tuple | None = None  # (key, scene, source, coarse source): frames of one scene skip codegen
        if isinstance(self.gl, GLThread):  # a dropped headless renderer frees its GL objects
            fin = weakref.finalize(self, self.gl.submit, _free_caches, self.gl, self._epoch, self.programs,
                                   self.data, self.targets)
            fin.atexit = False

    def forget_scene(self) -> None:
        """Let go of the last scene drawn, which is kept so that its next frame skips code
        generation (the next render of it generates its source again)."""
        self._last_source = None

    @property
    def budget(self) -> CacheBudget | None:
        """This renderer's own cache limits (None: those of ``sg.cache_budget()``)."""
        return self._limits.budget

    @budget.setter
    def budget(self, value: CacheBudget | None) -> None:
        self._limits.budget = value

    @property
    def ctx(self) -> moderngl.Context:
        """The GL context (GL calls on it belong on its thread: use :meth:`run`)."""
        return self.gl.ctx

    def run(self, fn: Callable[..., T], *args: object, **kwargs: object) -> T:
        """Run ``fn(*args, **kwargs)`` where this renderer's context is current (the GL thread)."""
        return self.gl.call(self._synced, fn, args, kwargs)

    def _synced(self, fn: Callable[..., T], args: tuple, kwargs: dict) -> T:
        self.gl.ctx  # noqa: B018 - (re)creates the context first, so a replaced one is noticed below
        if self._epoch[0] != self.gl.epoch:  # the context was replaced (fork): its objects are gone
            self.programs.sync()
            self.data.forget()
            self.targets.forget()
            self._epoch[0] = self.gl.epoch
        return fn(*args, **kwargs)

    def release(self) -> None:
        """Release every cached program, texture and target now (they are rebuilt when needed)."""
        self.gl.call(_free_caches, self.gl, self._epoch, self.programs, self.data, self.targets)

    def vao(self, prog: moderngl.Program) -> moderngl.VertexArray:
        """The buffer-less vertex array drawing the full-screen triangle with cached ``prog``."""
        return self.programs.vao(prog)

    def render(self, scene: Node, camera: Camera | None = None, size: Sequence[int] = (640, 480),
               meshes: Sequence[RasterMesh] = (), **settings: object) -> RenderResult:
        """Render ``scene``; see :func:`sdfgl.render`. Safe to call from any thread."""
        if not isinstance(scene, Node):
            raise ParameterError(f"render: 'scene' must be an sdfgl node, got {type(scene).__name__} {scene!r}")
        meshes = checked_meshes(meshes)
        st = Settings.build(**settings).resolved(scene.exactness)
        wh = checked_size(size)
        cam = camera if camera is not None else OrbitCamera.framing(*scene.bounds, aspect=wh[0] / wh[1])
        if not isinstance(cam, Camera):
            raise ParameterError(f"render: 'camera' must be an sdfgl Camera, got {type(cam).__name__}")
        origin = shader_origin(scene, cam.eye)
        check_float32_camera(cam, origin)

        t0 = time.perf_counter()
        if meshes:
            return self._render_meshes(scene, cam, wh, st, origin, meshes, t0)
        source, coarse = self._sources(scene, st, origin, cam.projection)
        origin_uniforms(source, scene, origin)  # refuses an origin float32 cannot hold, before drawing
        t1 = time.perf_counter()
        res = self.run(self._draw, scene, cam, wh, st, source, origin, None, coarse)
        res.timings["codegen_s"] = t1 - t0
        res.timings["total_s"] = time.perf_counter() - t0
        return res

    def _sources(self, scene: Node, st: Settings, origin: np.ndarray,
                 projection: str) -> tuple[ShaderSource, ShaderSource | None]:
        """The image's source and its coarse pass's (None where it has none), kept for the next frame."""
        key = (id(scene), st, origin_key(scene, origin), projection)  # nodes are immutable, params are uniforms:
        last = self._last_source                  # the same scene, settings and origin give the same source
        if last is not None and last[0] == key and last[1] is scene:
            return last[2], last[3]
        source = generate(scene, st, origin, projection=projection)
        coarse = coarse_source(scene, source, st, origin, projection)
        self._last_source = (key, scene, source, coarse)
        return source, coarse

    def coarse_starts(self, scene: Node, camera: Camera | None = None, size: Sequence[int] = (640, 480),
                      **settings: object) -> np.ndarray | None:
        """The coarse pass of ``render(scene, camera, size, **settings)`` alone: per tile of pixels
        (``Settings.coarse`` a side; row 0 on top) the float32 ray parameter before which no surface
        lies on any of the tile's rays (1e38 or more where the tile is proven empty: 2e38 where its
        ground needs no shadow or AO, 3e38 where no ray of it meets the ground), or None where that
        render has no coarse pass."""
        st = Settings.build(**settings).resolved(scene.exactness)
        wh = checked_size(size)
        cam = camera if camera is not None else OrbitCamera.framing(*scene.bounds, aspect=wh[0] / wh[1])
        origin = shader_origin(scene, cam.eye)
        check_float32_camera(cam, origin)
        source, coarse = self._sources(scene, st, origin, cam.projection)
        if coarse is None:
            return None
        return self.run(self._read_starts, scene, cam, wh, coarse, origin)

    def _read_starts(self, scene: Node, cam: Camera, wh: tuple[int, int], coarse: ShaderSource,
                     origin: np.ndarray) -> np.ndarray:
        starts = self.coarse_pass(scene, cam, wh, coarse, origin)
        cols, rows = coarse_size(wh, coarse.coarse_tile)
        try:  # the tiles are the target's lower left part: the last rows once row 0 is on top
            return starts.read("start")[-rows:, :cols, 0].copy()
        finally:
            starts.release()

    def coarse_pass(self, scene: Node, cam: Camera, wh: tuple[int, int], coarse: ShaderSource,
                    origin: np.ndarray) -> Targets:
        """Draw the coarse pass ``coarse`` (:func:`coarse_source`) of an image of size ``wh``;
        its tile target, for :func:`bind_coarse`, to release once the image is drawn. Call on the
        context's thread."""
        prog, vao = self.programs.entry(coarse)
        camera_uniforms(prog, cam, wh, origin)
        scene_uniforms(prog, coarse, scene, origin, self.data)
        return draw_coarse(self.ctx, lambda: vao.render(moderngl.TRIANGLES, vertices=3), wh, coarse.coarse_tile)

    def _render_meshes(self, scene: Node, cam: Camera, wh: tuple[int, int], st: Settings, origin: np.ndarray,
                       meshes: tuple[RasterMesh, ...], t0: float) -> RenderResult:
        """The raster meshes drawn first, then the scene marched up to their depth, composited."""
        wanted = st.outputs
        # the march writes depth (and normals when asked) for the compositing
        st_draw = dataclasses.replace(st, outputs=tuple(o for o in OUTPUTS if o in wanted or o == "depth"))
        source, mesh_source = mesh_sources(scene, st_draw, origin, cam.projection)
        origin_uniforms(source, scene, origin)
        t1 = time.perf_counter()
        res = self.run(self._draw_with_meshes, scene, cam, wh, st_draw, source, mesh_source, origin, meshes)
        if "depth" not in wanted:
            res.depth = None
        res.settings = dataclasses.replace(res.settings, outputs=wanted)
        res.timings["codegen_s"] = t1 - t0
        res.timings["total_s"] = time.perf_counter() - t0
        return res

    def _draw_with_meshes(self, scene: Node, cam: Camera, wh: tuple[int, int], st: Settings, source: ShaderSource,
                          mesh_source: ShaderSource, origin: np.ndarray,
                          meshes: tuple[RasterMesh, ...]) -> RenderResult:
        ctx = self.ctx
        check_size(ctx, wh)
        prog, _ = self.programs.entry(mesh_source, RASTER_VERTEX)
        t2 = time.perf_counter()
        raster = raster_pass(prog, mesh_source, scene, cam, wh, origin, meshes, self.data)
        raster_s = time.perf_counter() - t2
        try:
            res = self._draw(scene, cam, wh, st, source, origin, (raster.depth_texture, raster.color_texture))
        finally:
            raster.release()
        # the march stops at the mesh (where the shader took the mesh's colour): any hit lies in front
        mesh = (raster.t >= 0) & ~(res.depth < np.inf)
        res.depth[mesh] = raster.t[mesh]
        if res.normal is not None:
            res.normal[mesh] = raster.normal[mesh]
        res.timings["raster_s"] = raster_s
        return res

    def _draw(self, scene: Node, cam: Camera, wh: tuple[int, int], st: Settings, source: ShaderSource,
              origin: np.ndarray, meshes: tuple[moderngl.Texture, moderngl.Texture] | None = None,
              coarse: ShaderSource | None = None) -> RenderResult:
        check_size(self.ctx, wh)
        t0 = time.perf_counter()
        starts = None if coarse is None else self.coarse_pass(scene, cam, wh, coarse, origin)
        coarse_compile_s = 0.0 if coarse is None else self.programs.last_compile_s
        coarse_s = time.perf_counter() - t0 - coarse_compile_s
        try:
            res = self._draw_image(scene, cam, wh, st, source, origin, meshes, starts)
        finally:
            if starts is not None:
                starts.release()
        res.timings["compile_s"] += coarse_compile_s
        res.timings["draw_s"] += coarse_s
        return res

    def _draw_image(self, scene: Node, cam: Camera, wh: tuple[int, int], st: Settings, source: ShaderSource,
                    origin: np.ndarray, meshes: tuple[moderngl.Texture, moderngl.Texture] | None,
                    starts: Targets | None) -> RenderResult:
        """The image's draw (after the coarse pass, whose tile ``starts`` it reads) and its read-back."""
        ctx = self.ctx
        draws, compile_s = image_draws(self.programs, source, starts is not None)
        try:
            targets = self.targets.get(ctx, wh, st.outputs)
        except moderngl.Error as exc:
            raise SdfglError(f"render: cannot allocate {wh[0]}x{wh[1]} targets for {', '.join(st.outputs)}: "
                             f"{exc}") from None
        bind_image(draws, scene, cam, wh, origin, self.data, meshes, starts)
        targets.fbo.use()
        ctx.viewport = (0, 0, *wh)
        t2 = time.perf_counter()
        draw_image(ctx, draws, wh)
        ctx.finish()
        t3 = time.perf_counter()
        res = RenderResult(color=targets.read("color", 4 if st.alpha else 3), source=source,
                           settings=dataclasses.replace(st, grid_min=source.grid_min), camera=cam)
        if "depth" in st.outputs:
            d = targets.read("depth")[..., 0]
            d[d < 0] = np.inf
            res.depth = d
        if "normal" in st.outputs:
            res.normal = targets.read("normal", 3)
        if "steps" in st.outputs:
            res.steps = targets.read("steps")[..., 0].astype(np.int32)
        res.timings = {"compile_s": compile_s, "draw_s": t3 - t2, "read_s": time.perf_counter() - t3}
        return res


@dataclass
class ImageDraw:
    """One program drawing an image: the image's own over the whole view (``kind`` None), or
    after a coarse pass the program of one kind of tile (sdfgl.gl.coarse_pass: OPEN, EMPTY, LIT, SKY,
    or WHOLE: the image's program over every tile)."""

    prog: moderngl.Program
    vao: moderngl.VertexArray
    source: ShaderSource
    kind: int | None = None


def image_draws(programs: ProgramCache, source: ShaderSource, tiled: bool) -> tuple[list[ImageDraw], float]:
    """The programs that draw the image of ``source`` from the cache ``programs``, and the
    seconds their links took. After a coarse pass (``tiled``) the image is drawn tile by tile,
    one program per kind of tile, except in its first frame: then the image's program (not yet
    linked) draws every pixel, so a single image links and builds one program, not three.
    Call on the context's thread."""
    if not tiled:
        kinds: list[tuple[ShaderSource, int | None]] = [(source, None)]
    elif not programs.cached(source, TILES_VERTEX):
        kinds = [(source, WHOLE)]
    else:
        kinds = list(tile_sources(source))
    draws, seconds = [], 0.0
    for src, kind in kinds:
        prog, vao = programs.entry(src, FULLSCREEN if kind is None else TILES_VERTEX)
        seconds += programs.last_compile_s
        draws.append(ImageDraw(prog, vao, src, kind))
    return draws, seconds


def bind_image(draws: Sequence[ImageDraw], scene: Node, cam: Camera, wh: tuple[int, int], origin: np.ndarray,
               data: DataTextures, meshes: tuple[moderngl.Texture, moderngl.Texture] | None = None,
               starts: Targets | None = None) -> None:
    """Set the uniforms and bind the textures of every program of an image (the scene's data,
    the raster meshes' images, the coarse pass's tile ``starts``). Call on the context's thread."""
    for d in draws:
        camera_uniforms(d.prog, cam, wh, origin)
        scene_uniforms(d.prog, d.source, scene, origin, data)
        if meshes is not None:
            bind_raster_images(d.prog, d.source, *meshes)
        if starts is not None:
            bind_coarse(d.prog, d.source, starts)


def draw_image(ctx: moderngl.Context, draws: Sequence[ImageDraw], wh: tuple[int, int]) -> None:
    """Draw an image of size ``wh`` by its programs (bound by :func:`bind_image`) into the bound
    target. Call on the context's thread."""
    for d in draws:
        if d.kind is None:
            d.vao.render(moderngl.TRIANGLES, vertices=3)
        else:
            draw_tiles(ctx, lambda name, value, prog=d.prog: set_uniform(prog, name, value),
                       lambda mode, n, vao=d.vao: vao.render(mode, vertices=n), wh, d.source.coarse_tile, d.kind)


RASTER_VERTEX = "mains/raster_mesh.vert"
"""The vertex shader of the raster meshes' program (its fragment shader: the "raster_mesh" target)."""


def mesh_sources(scene: Node, st: Settings, origin: np.ndarray, projection: str) -> tuple[ShaderSource, ShaderSource]:
    """The two programs of a frame with raster meshes: the march that stops at the meshes' depth
    ("render_over_mesh") and the meshes' own fragments, shaded by the scene ("raster_mesh")."""
    return (generate(scene, st, origin, target="render_over_mesh", projection=projection),
            generate(scene, st, origin, target="raster_mesh", projection=projection))


def raster_pass(prog: moderngl.Program, mesh_source: ShaderSource, scene: Node, cam: Camera, size: tuple[int, int],
                origin: np.ndarray, meshes: Sequence[RasterMesh], data: DataTextures) -> RasterImages:
    """Draw ``meshes`` with the linked "raster_mesh" program ``prog`` (a moderngl program of the
    current context) through ``cam`` at ``size``: the textures the march then reads."""
    camera_uniforms(prog, cam, size, origin)
    scene_uniforms(prog, mesh_source, scene, origin, data)
    set_uniform(prog, "uOrtho", 1.0 if cam.orthographic else 0.0)
    set_uniform(prog, "uNearFar", view_range(cam, meshes))
    return draw_meshes(prog.ctx, prog, meshes, size, origin)


def coarse_source(scene: Node, source: ShaderSource, st: Settings, origin: np.ndarray,
                  projection: str = "perspective") -> ShaderSource | None:
    """The coarse pass of the image ``source`` (generated from ``scene`` and resolved settings
    ``st``), or None where the image has none."""
    if not source.coarse_tile:
        return None
    return generate(scene, dataclasses.replace(st, debug=None, outputs=("color",)), origin, target="coarse",
                    projection=projection)


_default: Renderer | None = None
_default_lock = threading.Lock()


def default_renderer() -> Renderer:
    """The process-wide headless renderer (EGL)."""
    global _default
    if _default is None:
        with _default_lock:
            if _default is None:
                _default = Renderer()
    return _default


def _forget_default_scene() -> None:
    """At exit, the process-wide renderer lets go of the last scene it drew: the scene's graph
    is then freed when the script's own names go, early in the interpreter's shutdown, not
    after the collections it makes of every module (a 10^6-node union took about 5 s to exit
    held here, about 2 s let go)."""
    if _default is not None:
        _default.forget_scene()


atexit.register(_forget_default_scene)


def checked_meshes(meshes: object) -> tuple[RasterMesh, ...]:
    """The raster meshes of a render as a tuple, refused (by position) unless each is a :class:`RasterMesh`."""
    if isinstance(meshes, RasterMesh):
        return (meshes,)
    if not isinstance(meshes, (list, tuple)):
        raise ParameterError(f"render: 'meshes' must be a list of sg.raster(...) meshes, got {type(meshes).__name__}")
    for i, m in enumerate(meshes):
        if not isinstance(m, RasterMesh):
            raise ParameterError(f"render: meshes[{i}] must be an sg.raster(...) mesh, got {type(m).__name__}; "
                                 f"wrap a trimesh or a file path in sg.raster()")
    return tuple(meshes)


def render(scene: Node, camera: Camera | None = None, size: Sequence[int] = (640, 480),
           meshes: Sequence[RasterMesh] = (), **settings: object) -> RenderResult:
    """Render ``scene`` headless (EGL) and return its images.

    Args:
        scene: the scene node.
        camera: a :class:`Camera` or :class:`OrbitCamera`; default: an orbit camera
            framing the scene's bounds.
        size: (width, height) in pixels, each 1..16384.
        settings: see :class:`sdfgl.settings.Settings`: ``aa`` 1..4 (n x n samples per
            pixel), ``shadows`` False/"hard"/"soft", ``ao``, ``ground``, ``method``,
            ``max_steps``, ``hit``, ``hit_scale``, ``max_dist``, ``debug`` and ``outputs``
            (any of "color", "depth", "normal", "steps").
        meshes: triangle meshes made by :func:`sdfgl.raster` to draw by rasterisation in the
            same frame: drawn first with the same camera and lights, they end the march at
            their depth, so mesh and scene hide each other per pixel; the scene's shadows
            and AO fall on them. ``depth`` and ``normal`` include them.

    Returns a :class:`RenderResult`: ``color`` uint8 (H, W, 3), and as asked ``depth``
    (float32 ray parameter t along the unit direction, inf on a miss), ``normal`` and
    ``steps``. Row 0 is the top row. No output ever holds NaN.

    Safe to call from any thread and in forked children: the GL work runs on sdfgl's GL
    thread (see :mod:`sdfgl.gl.context`); caches are bounded by :func:`sdfgl.cache_budget`.

    Example:
        >>> res = sg.render(sg.sphere(1), sg.OrbitCamera(distance=4), (32, 24), outputs=("color", "depth"))
        >>> res.color.shape, bool(res.depth.min() < 4)
        ((24, 32, 3), True)
    """
    return default_renderer().render(scene, camera, size, meshes, **settings)
