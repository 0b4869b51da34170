"""render(): scene + camera + settings -> program -> one draw -> RenderResult."""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Sequence

import moderngl
import numpy as np
from PIL import Image

from .camera import Camera, OrbitCamera
from .codegen import BOUNDS_PAD, GLSL_FAR, ShaderSource, generate, scene_frame
from .errors import ParameterError, SdfglError
from .gl.context import headless_context
from .gl.programs import ProgramCache
from .gl.targets import Targets
from .nodes.base import Node
from .settings import Settings


def shader_origin(scene: Node, eye: np.ndarray) -> np.ndarray:
    """The world point the shader's float32 coordinates are taken relative to.

    The centre of a bounded scene (else the eye) is the anchor: where rays hit, float32
    then only has to resolve the scene relative to itself. Within 1000 of the world
    origin the origin stays 0; beyond, the anchor is snapped to a power-of-two grid
    about 1/1000 of its distance wide, so a moving camera seldom changes the source.
    """
    lo, hi = scene.bounds
    anchor = (lo + hi) / 2 if np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)) else eye
    r = float(np.max(np.abs(anchor)))
    if r <= 1000.0:
        return np.zeros(3)
    step = 2.0 ** math.ceil(math.log2(r * 1e-3))
    return np.round(anchor / step) * step


@dataclass
class RenderResult:
    """Images of one draw. Row 0 is the top row of the image."""

    color: np.ndarray                      # uint8 (H, W, 3), gamma-corrected
    depth: np.ndarray | None = None        # float32 (H, W): ray t of the pixel centre, inf on a miss
    normal: np.ndarray | None = None       # float32 (H, W, 3): unit normal, 0 on a miss
    steps: np.ndarray | None = None        # int32 (H, W): map() calls of the pixel-centre ray
    source: ShaderSource | None = None
    settings: Settings | None = None
    camera: Camera | None = None
    timings: dict[str, float] = field(default_factory=dict)

    def save(self, path: str | Path) -> Path:
        """Write the colour image as PNG (or any format Pillow knows from the suffix)."""
        p = Path(path)
        try:
            Image.fromarray(self.color).save(p)
        except (OSError, ValueError, KeyError) as exc:
            raise SdfglError(f"cannot write image file '{p}': {exc}") from exc
        return p


def _set_uniform(prog: moderngl.Program, name: str, value: object) -> None:
    if name in prog:  # the driver drops uniforms the code does not use
        prog[name].value = value


def _check_size(size: Sequence[int]) -> tuple[int, int]:
    try:
        w, h = (int(x) for x in size)
        ok = all(float(x) == int(x) for x in size)
    except (TypeError, ValueError):
        raise ParameterError(f"render: 'size' must be (width, height), got {size!r}") from None
    if not ok or not (1 <= w <= 16384 and 1 <= h <= 16384):
        raise ParameterError(f"render: 'size' must be two integers in 1..16384, got {size!r}")
    return w, h


def camera_uniforms(prog: moderngl.Program, camera: Camera, size: tuple[int, int], origin: np.ndarray,
                    jitter: tuple[float, float] = (0.0, 0.0)) -> None:
    """Set the camera uniforms common.glsl declares."""
    r, u, f = camera.basis()
    _set_uniform(prog, "uResolution", (float(size[0]), float(size[1])))
    _set_uniform(prog, "uEye", tuple((camera.eye - origin).tolist()))
    _set_uniform(prog, "uRight", tuple(r.tolist()))
    _set_uniform(prog, "uUp", tuple(u.tolist()))
    _set_uniform(prog, "uForward", tuple(f.tolist()))
    _set_uniform(prog, "uTanHalfFov", camera.tan_half_fov)
    _set_uniform(prog, "uJitter", jitter)
    _set_uniform(prog, "uZero", 0)


DATA_UNIT = 1  # first texture unit of scene data (unit 0 is evaluate()'s points)


def scene_uniforms(prog: moderngl.Program, source: ShaderSource, scene: Node, origin: np.ndarray) -> None:
    """Set the uniforms of live parameters (and the scene box they move) to their current values,
    and bind the textures of unions kept as data."""
    if source.data:
        bind_data(prog, source)
    for i, prm in enumerate(source.params):
        val = prm.value
        _set_uniform(prog, f"uP{i}", float(val) if np.ndim(val) == 0 else tuple(float(x) for x in val))
    if source.live_bounds:
        lo, hi, scale = scene_frame(scene)
        pad = BOUNDS_PAD * scale
        _set_uniform(prog, "uBoundsLo", tuple((lo - pad - origin).tolist()))
        _set_uniform(prog, "uBoundsHi", tuple((hi + pad - origin).tolist()))
        _set_uniform(prog, "uGroundY", float((lo[1] if lo[1] > -GLSL_FAR else 0.0) - origin[1]))
        _set_uniform(prog, "uSceneScale", float(scale))


_data_textures: dict[int, tuple[ShaderSource, list[moderngl.Texture]]] = {}


def bind_data(prog: moderngl.Program, source: ShaderSource) -> None:
    """Upload (once per source) and bind the data textures a shader samples."""
    entry = _data_textures.get(id(source))
    if entry is None or entry[0] is not source:
        if entry is not None:
            for t in entry[1]:
                t.release()
        texs = []
        for _, arr in source.data:
            tex = prog.ctx.texture((arr.shape[1], arr.shape[0]), 4, np.ascontiguousarray(arr).tobytes(), dtype="f4")
            tex.filter = (moderngl.NEAREST, moderngl.NEAREST)
            texs.append(tex)
        entry = _data_textures[id(source)] = (source, texs)
        while len(_data_textures) > 32:  # keep the most recent sources' textures
            for t in _data_textures.pop(next(iter(_data_textures)))[1]:
                t.release()
    for unit, ((name, _), tex) in enumerate(zip(source.data, entry[1]), start=DATA_UNIT):
        tex.use(unit)
        _set_uniform(prog, name, unit)


class Renderer:
    """Draws scenes on one GL context, caching programs by source and targets by size."""

    def __init__(self, ctx: moderngl.Context | None = None) -> None:
        self.ctx = ctx or headless_context()
        self.programs = ProgramCache(self.ctx)
        self._targets: Targets | None = None
        self._vao: dict[int, moderngl.VertexArray] = {}

    def _targets_for(self, size: tuple[int, int], outputs: tuple[str, ...]) -> Targets:
        t = self._targets
        if t is None or t.size != size or t.outputs != outputs:
            if t is not None:
                t.release()
            t = self._targets = Targets(self.ctx, size, outputs)
        return t

    def vao(self, prog: moderngl.Program) -> moderngl.VertexArray:
        """A buffer-less vertex array drawing the full-screen triangle with ``prog``."""
        key = id(prog)
        if key not in self._vao:
            self._vao[key] = self.ctx.vertex_array(prog, [])
        return self._vao[key]

    def render(self, scene: Node, camera: Camera | None = None, size: Sequence[int] = (640, 480),
               **settings: object) -> RenderResult:
        """Render ``scene``; see :func:`sdfgl.render`."""
        if not isinstance(scene, Node):
            raise ParameterError(f"render: 'scene' must be an sdfgl node, got {type(scene).__name__} {scene!r}")
        st = Settings.build(**settings)
        wh = _check_size(size)
        cam = camera if camera is not None else OrbitCamera.framing(*scene.bounds)
        if not isinstance(cam, Camera):
            raise ParameterError(f"render: 'camera' must be an sdfgl Camera, got {type(cam).__name__}")
        origin = shader_origin(scene, cam.eye)

        t0 = time.perf_counter()
        source = generate(scene, st, origin)
        t1 = time.perf_counter()
        prog = self.programs.get(source)
        compile_s = self.programs.last_compile_s
        targets = self._targets_for(wh, st.outputs)
        camera_uniforms(prog, cam, wh, origin)
        scene_uniforms(prog, source, scene, origin)
        targets.fbo.use()
        self.ctx.viewport = (0, 0, *wh)
        t2 = time.perf_counter()
        self.vao(prog).render(moderngl.TRIANGLES, vertices=3)
        self.ctx.finish()
        t3 = time.perf_counter()
        res = RenderResult(color=np.ascontiguousarray(targets.read("color")[..., :3]), source=source,
                           settings=dataclasses.replace(st, grid_min=source.grid_min), camera=cam)
        if "depth" in st.outputs:
            d = targets.read("depth")[..., 0].copy()
            d[d < 0] = np.inf
            res.depth = d
        if "normal" in st.outputs:
            res.normal = np.ascontiguousarray(targets.read("normal")[..., :3])
        if "steps" in st.outputs:
            res.steps = targets.read("steps")[..., 0].astype(np.int32)
        t4 = time.perf_counter()
        res.timings = {"codegen_s": t1 - t0, "compile_s": compile_s, "draw_s": t3 - t2, "read_s": t4 - t3,
                       "total_s": t4 - t0}
        return res


_default: Renderer | None = None


def default_renderer() -> Renderer:
    """The process-wide headless renderer (EGL)."""
    global _default
    if _default is None:
        _default = Renderer()
    return _default


def render(scene: Node, camera: Camera | None = None, size: Sequence[int] = (640, 480),
           **settings: object) -> RenderResult:
    """Render ``scene`` headless and return its images.

    ``camera`` defaults to an orbit camera framing the scene bounds. Settings (see
    :class:`sdfgl.settings.Settings`): ``aa`` 1..4, ``shadows`` False/"hard"/"soft",
    ``ao``, ``ground``, ``method``, ``max_steps``, ``hit``, ``hit_scale``, ``max_dist`` and
    ``outputs`` (any of "color", "depth", "normal", "steps").
    """
    return default_renderer().render(scene, camera, size, **settings)
