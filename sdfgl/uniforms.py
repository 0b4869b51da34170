"""The uniforms and textures every program drawing a scene reads: the camera, the live
parameters and the scene box they move, a moving origin, the scene's data textures, the raster
meshes' images and the coarse pass's tile starts. Each helper takes a moderngl program or the
viewer's (:class:`sdfgl.viewer.programs.RawProgram`); call them on the context's thread."""
from __future__ import annotations

import weakref

import moderngl
import numpy as np

from .camera import Camera
from .compiler.analysis import BOUNDS_PAD, GLSL_FAR, analytic_relative, analytic_shape, scene_frame
from .compiler.source import ShaderSource
from .compiler.tables import origin_values
from .errors import ParameterError
from .gl.buffer_texture import BufferTexture
from .gl.cache import default_budget
from .gl.data import DataTextures
from .gl.targets import Targets
from .nodes.base import Node


def set_uniform(prog: moderngl.Program, name: str, value: object) -> None:
    """Set uniform ``name`` of ``prog`` (a moderngl program or the viewer's) where the driver kept it."""
    if name in prog:  # the driver drops uniforms the code does not use
        prog[name].value = value


def camera_uniforms(prog: moderngl.Program, camera: Camera, size: tuple[int, int], origin: np.ndarray,
                    jitter: tuple[float, float] = (0.0, 0.0)) -> None:
    """Set the camera uniforms common.glsl declares."""
    r, u, f = camera.basis()
    set_uniform(prog, "uResolution", (float(size[0]), float(size[1])))
    set_uniform(prog, "uEye", tuple((camera.eye - origin).tolist()))
    set_uniform(prog, "uRight", tuple(r.tolist()))
    set_uniform(prog, "uUp", tuple(u.tolist()))
    set_uniform(prog, "uForward", tuple(f.tolist()))
    set_uniform(prog, "uTanHalfFov", camera.tan_half_fov)
    set_uniform(prog, "uOrthoHalfHeight", 0.5 * camera.ortho_height)
    set_uniform(prog, "uJitter", jitter)
    set_uniform(prog, "uZero", 0)


DATA_UNIT = 1  # first texture unit of scene data (unit 0 is evaluate()'s points)


def scene_uniforms(prog: moderngl.Program, source: ShaderSource, scene: Node, origin: np.ndarray,
                   data: DataTextures | None = None) -> None:
    """Set the uniforms of live parameters (and the scene box they move) to their current values,
    and bind the textures of unions kept as data (uploaded once into ``data``, by default a
    cache kept per context). Call on the context's thread."""
    if source.data:
        bind_data(prog, source, data)
    for i, prm in enumerate(source.params):
        val = prm.value
        set_uniform(prog, f"uP{i}", float(val) if np.ndim(val) == 0 else tuple(float(x) for x in val))
    if source.live_bounds:
        for name, value in live_frame(scene, origin).items():
            set_uniform(prog, name, value)
    for name, value in origin_uniforms(source, scene, origin).items():
        set_uniform(prog, name, value)


def origin_uniforms(source: ShaderSource, scene: Node, origin: np.ndarray) -> dict[str, tuple]:
    """The uniforms of a moving origin (uOrgN, uAnalytic) for ``origin``, at the current parameter values."""
    if source.origin_offsets is None:
        return {}
    out: dict[str, tuple] = dict(origin_values(source.origin_offsets, origin))
    worst = max((max(abs(x) for x in v) for v in out.values()), default=0.0)
    if not worst < 1e30:
        raise ParameterError(f"render: the shader origin {tuple(np.asarray(origin).tolist())} (the eye of an unbounded "
                             f"scene) lies {worst:g} from the scene's parts, beyond what float32 can hold (1e30)")
    shape = analytic_shape(scene)
    if shape is not None:
        out["uAnalytic"] = tuple(float(x) for x in analytic_relative(shape[0], shape[1], origin))
    return out


def live_frame(scene: Node, origin: np.ndarray) -> dict[str, object]:
    """The uniforms a shader with live parameters reads for the scene box, at the current values."""
    lo, hi, scale = scene_frame(scene)
    pad = BOUNDS_PAD * scale
    return {"uBoundsLo": tuple((lo - pad - origin).tolist()), "uBoundsHi": tuple((hi + pad - origin).tolist()),
            "uGroundY": float((lo[1] if lo[1] > -GLSL_FAR else 0.0) - origin[1]), "uSceneScale": float(scale)}


_data_by_ctx: "weakref.WeakKeyDictionary[moderngl.Context, DataTextures]" = weakref.WeakKeyDictionary()


def bind_data(prog: moderngl.Program, source: ShaderSource, data: DataTextures | None = None) -> None:
    """Upload (once per source) and bind the data textures a shader samples."""
    if data is None:
        data = _data_by_ctx.get(prog.ctx)
        if data is None:
            data = _data_by_ctx[prog.ctx] = DataTextures(default_budget)
    texs = data.textures(prog.ctx, source)
    for unit, ((name, _), tex) in enumerate(zip(source.data, texs), start=DATA_UNIT):
        tex.use(unit)
        if isinstance(tex, BufferTexture):
            tex.point(prog, name, unit)  # moderngl cannot set a samplerBuffer uniform
        else:
            set_uniform(prog, name, unit)


def bind_raster_images(prog: moderngl.Program, source: ShaderSource, depth: moderngl.Texture, color: moderngl.Texture) -> None:
    """Bind the raster meshes' t and colour textures for the march ``prog`` of ``source`` (a
    moderngl program or the viewer's RawProgram), on the texture units after the scene's data."""
    first = DATA_UNIT + len(source.data)
    for unit, (name, tex) in enumerate(zip(("uMeshDepth", "uMeshColor"), (depth, color)), start=first):
        tex.use(unit)
        set_uniform(prog, name, unit)


def bind_coarse(prog: moderngl.Program, source: ShaderSource, starts: Targets) -> None:
    """Bind the coarse pass's tile starts for the image ``prog`` (of ``source``) on the unit
    after the scene's data. Call on the context's thread."""
    unit = DATA_UNIT + len(source.data)
    starts.textures["start"].use(unit)
    set_uniform(prog, "uCoarseStart", unit)
