"""evaluate(): the generated GLSL map() run on the GPU at arbitrary points."""
from __future__ import annotations

import numpy as np

from .codegen import EVALUATE_CHANNELS, generate, material_channels
from .errors import ParameterError
from .nodes.base import Node, as_points
from .render import Renderer, default_renderer, scene_uniforms
from .settings import Settings

_ROW = 1024  # points per texture row


def evaluate(scene: Node, points: object, origin: object = (0.0, 0.0, 0.0),
             renderer: Renderer | None = None) -> np.ndarray:
    """Float32 values of the scene's generated map() at (..., 3) points, computed on the GPU.

    Args:
        scene: the scene node.
        points: array-like of shape (..., 3), scene units.
        origin: subtracted from the points in float64 and folded into the shader (as
            render() does for far-away cameras), so points far from the world origin keep
            float32 precision relative to it.
        renderer: the GL context to use (default: the process-wide headless one).

    Returns a float32 array of shape (...). It matches ``scene.distance(points)`` (the
    float64 twin) to float32 rounding.

    Example:
        >>> float(sg.evaluate(sg.sphere(1), [(0, 2, 0)])[0])
        1.0
    """
    return _run(scene, points, origin, renderer, "evaluate", 1, "evaluate")


def evaluate_channel(scene: Node, points: object, channel: str = "color", origin: object = (0.0, 0.0, 0.0),
                     renderer: Renderer | None = None) -> np.ndarray:
    """Float32 (..., 4) array: a material channel of the generated shader and map() at points.

    ``channel`` "color": mapColor(), the linear albedo the renderer shades with; "surface":
    mapSurface(), (specular, shininess, metallic) where nodes set them; "emission":
    mapEmission(). Away from the surface a channel is that of the nearest part of the
    scene, as the generated function picks it. A scene without the surface or emission
    channel (no node sets it) has no such function: ask ``codegen.material_channels``.
    """
    target = f"evaluate_{channel}"
    if target not in EVALUATE_CHANNELS:
        raise ParameterError(f"evaluate_channel: 'channel' must be one of color, surface, emission, got {channel!r}")
    if channel != "color" and isinstance(scene, Node) and channel not in material_channels(scene):
        raise ParameterError(f"evaluate_channel: no node of {scene.label()} sets the {channel} channel")
    return _run(scene, points, origin, renderer, target, 4, "evaluate_channel")


def _run(scene: Node, points: object, origin: object, renderer: Renderer | None, target: str, comps: int,
         caller: str) -> np.ndarray:
    if not isinstance(scene, Node):
        raise ParameterError(f"{caller}: 'scene' must be an sdfgl node, got {type(scene).__name__}")
    p = as_points(points)
    shape = p.shape[:-1] + ((comps,) if comps > 1 else ())
    flat = p.reshape(-1, 3)
    if flat.shape[0] == 0:
        return np.zeros(shape, dtype=np.float32)
    if not np.all(np.isfinite(flat)):
        raise ParameterError(f"{caller}: points must be finite")
    org = np.asarray(origin, dtype=np.float64)
    r = renderer or default_renderer()
    ctx = r.ctx
    source = generate(scene, Settings(shadows=False, ao=False), org, target=target)
    prog = r.programs.get(source)
    scene_uniforms(prog, source, scene, org)
    n = flat.shape[0]
    w = min(n, _ROW)
    h = -(-n // w)
    data = np.zeros((h * w, 4), dtype=np.float32)
    data[:n, :3] = flat - org
    tex = ctx.texture((w, h), 4, data.tobytes(), dtype="f4")
    tex.filter = (ctx.NEAREST, ctx.NEAREST)
    out = ctx.texture((w, h), comps, dtype="f4")
    fbo = ctx.framebuffer(color_attachments=[out])
    try:
        tex.use(0)
        if "uPoints" in prog:
            prog["uPoints"].value = 0
        fbo.use()
        ctx.viewport = (0, 0, w, h)
        r.vao(prog).render(vertices=3)
        vals = np.frombuffer(out.read(), dtype=np.float32)[:n * comps].copy()
    finally:
        fbo.release()
        out.release()
        tex.release()
    return vals.reshape(shape)
