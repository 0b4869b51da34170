"""The raster pass of a render: triangle meshes drawn with the march's camera into colour,
ray-parameter and normal textures (and a depth buffer for their own hiding)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

import moderngl
import numpy as np

NO_HIT = -1.0  # what the t and normal textures hold where no mesh is drawn


@dataclass
class RasterImages:
    """What the raster pass drew: the t and gamma-encoded colour textures (the march reads them;
    no mesh: t -1, alpha 0), and read back as numpy (row 0 on top) t and the normals.
    ``release()`` frees the GL objects."""

    depth_texture: moderngl.Texture
    color_texture: moderngl.Texture
    t: np.ndarray
    normal: np.ndarray
    gl_objects: tuple[Any, ...]

    def release(self) -> None:
        """Release the framebuffer and its textures (on the context's thread)."""
        for obj in self.gl_objects:
            obj.release()


def view_range(camera: Any, meshes: Sequence[Any]) -> tuple[float, float]:
    """(near, far) along the view direction holding every mesh vertex; what lies behind the eye
    (perspective: near > 0) or behind the image plane through it (orthographic) is clipped."""
    f = camera.basis()[2]
    z = np.concatenate([(m.vertices - camera.eye) @ f for m in meshes])
    lo, hi = float(z.min()), float(z.max())
    far = max(hi, 0.0) * 1.01 + 1e-6 * max(abs(hi), abs(lo), 1.0)
    if camera.orthographic:  # rays start on the image plane through the eye: nothing behind it
        return max(lo - 1e-3 * (far - lo), 0.0), far
    near = max(lo * 0.99, far * 1e-5)
    return near, far


def draw_meshes(ctx: moderngl.Context, prog: moderngl.Program, meshes: Sequence[Any], size: tuple[int, int],
                origin: np.ndarray) -> RasterImages:
    """Draw ``meshes`` with ``prog`` (its uniforms but the mesh's own already set) into fresh
    textures of ``size``; vertices are taken relative to ``origin``."""
    color = ctx.texture(size, 4, dtype="f1")
    t_tex = ctx.texture(size, 1, dtype="f4")
    nor = ctx.texture(size, 4, dtype="f4")
    depth = ctx.depth_renderbuffer(size)
    for tex in (t_tex, nor):
        tex.filter = (moderngl.NEAREST, moderngl.NEAREST)
    fbo = ctx.framebuffer(color_attachments=[color, t_tex, nor], depth_attachment=depth)
    images = RasterImages(t_tex, color, np.empty(0), np.empty(0), (fbo, depth, color, t_tex, nor))
    try:
        _draw(ctx, prog, meshes, fbo, size, origin)
        w, h = size
        for att, comps, name in ((1, 1, "t"), (2, 3, "normal")):
            raw = np.empty((h, w, comps), dtype=np.float32)
            fbo.read_into(raw, components=comps, attachment=att, alignment=1, dtype="f4")
            setattr(images, name, raw[::-1, :, 0].copy() if comps == 1 else raw[::-1].copy())
    except BaseException:
        images.release()
        raise
    return images


def _draw(ctx: moderngl.Context, prog: moderngl.Program, meshes: Sequence[Any], fbo: moderngl.Framebuffer,
          size: tuple[int, int], origin: np.ndarray) -> None:
    """Clear ``fbo`` to no mesh and draw each mesh into it, depth-tested, with its own material."""
    fbo.use()
    ctx.viewport = (0, 0, *size)
    fbo.clear(NO_HIT, NO_HIT, NO_HIT, NO_HIT, depth=1.0)
    ctx.enable(moderngl.DEPTH_TEST)
    try:
        for mesh in meshes:
            data = np.hstack([mesh.vertices - origin, mesh.normals]).astype(np.float32)
            vbo = ctx.buffer(data.tobytes())
            ibo = ctx.buffer(np.ascontiguousarray(mesh.faces, dtype=np.int32).tobytes())
            vao = ctx.vertex_array(prog, [(vbo, "3f 3f", "inPos", "inNormal")], index_buffer=ibo, index_element_size=4)
            mat = mesh.material
            for name, value in (("uMeshAlbedo", mesh.color), ("uMeshEmission", mat["emission"]),
                                ("uMeshSurface", (mat["specular"], mat["shininess"], mat["metallic"], 0.0))):
                if name in prog:
                    prog[name].value = tuple(float(x) for x in value)
            vao.render(moderngl.TRIANGLES)
            vao.release()
            vbo.release()
            ibo.release()
    finally:
        ctx.disable(moderngl.DEPTH_TEST)
