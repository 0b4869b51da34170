"""The scene's generated map() on the GPU, as the mesh exporter needs it.

Four draws, all from the same codegen as render() (targets mesh_grid, mesh_gradient, mesh_project,
evaluate_color): lattice blocks of field values, value + gradient at points, points moved onto the
surface, colour at points. The field is
map() cut by the sampling box (shaders/stages/mesh_clip.glsl), so solids that leave the box close.
"""
from __future__ import annotations

import numpy as np

from ..compiler.generate import generate
from ..gl.context import finish
from ..nodes.base import Node
from ..render import Renderer, default_renderer, shader_origin
from ..uniforms import scene_uniforms
from ..settings import Settings

MAX_TEXELS = 1 << 22  # samples per draw: 16 MiB of float32 read back at a time
_WIDTH = 4096         # framebuffer width of the lattice draw


class GPUField:
    """Samples one scene's clipped field on the GPU (float32) at lattices and points."""

    def __init__(self, scene: Node, clip_lo: np.ndarray, clip_hi: np.ndarray,
                 renderer: Renderer | None = None) -> None:
        self.scene = scene
        self.r = renderer or default_renderer()
        centre = (np.asarray(clip_lo, float) + np.asarray(clip_hi, float)) / 2
        self.origin = shader_origin(scene, centre)
        self.clip = (np.asarray(clip_lo, float) - self.origin, np.asarray(clip_hi, float) - self.origin)
        self._progs: dict[str, tuple] = {}
        self.samples = 0        # lattice samples taken (coarse and fine)
        self.point_samples = 0  # map() calls for values and gradients at points

    def _program(self, target: str):  # -> (program, source)
        if target not in self._progs:
            source = generate(self.scene, Settings(shadows=False, ao=False), self.origin, target=target)
            prog = self.r.programs.get(source)
            self._progs[target] = (prog, source)
        prog, source = self._progs[target]
        scene_uniforms(prog, source, self.scene, self.origin, self.r.data)
        for name, v in (("uClipLo", self.clip[0]), ("uClipHi", self.clip[1])):
            if name in prog:
                prog[name].value = tuple(float(x) for x in v)
        return prog

    def _draw(self, prog, w: int, h: int, comps: int, inputs: np.ndarray | None = None,
              input_width: int = 0, outputs: int = 1) -> np.ndarray:
        """One full-screen draw of ``prog`` into ``outputs`` float targets of ``comps`` channels,
        ``inputs`` (N, 3) given as a texture ``input_width`` texels wide: (w * h, comps) read
        back, or (outputs, w * h, comps) when ``outputs`` > 1."""
        ctx = self.r.ctx
        tex = None
        if inputs is not None:
            iw = input_width
            ih = -(-len(inputs) // iw)
            data = np.zeros((ih * iw, 4), np.float32)
            data[:len(inputs), :3] = inputs
            tex = ctx.texture((iw, ih), 4, data.tobytes(), dtype="f4")
            tex.filter = (ctx.NEAREST, ctx.NEAREST)
        outs = [ctx.texture((w, h), comps, dtype="f4") for _ in range(outputs)]
        fbo = ctx.framebuffer(color_attachments=outs)
        try:
            if tex is not None:
                tex.use(0)
            fbo.use()
            ctx.viewport = (0, 0, w, h)
            self.r.vao(prog).render(vertices=3)
            finish(ctx)  # rasterizes with the GIL released: the extraction thread runs meanwhile
            got = [np.frombuffer(o.read(), dtype=np.float32).reshape(-1, comps) for o in outs]
            return got[0] if outputs == 1 else np.stack(got)
        finally:
            fbo.release()
            for o in outs:
                o.release()
            if tex is not None:
                tex.release()

    def blocks(self, start: np.ndarray, corners: np.ndarray, size: int, step: float) -> np.ndarray:
        """Field at ``size``^3 lattice points ``start + (corner + (i, j, k)) * step`` for each
        (M, 3) integer corner: float32 (M, size, size, size), indexed [block, i, j, k].
        The GL work runs on the renderer's GL thread (see sdfgl.gl.context)."""
        return self.r.run(self._blocks, start, corners, size, step)

    def _blocks(self, start: np.ndarray, corners: np.ndarray, size: int, step: float) -> np.ndarray:
        corners = np.asarray(corners, np.int64).reshape(-1, 3)
        if corners.size and corners.max() + size >= 1 << 24:
            raise ValueError("lattice coordinates beyond float32's exact integers")
        per = size ** 3
        out = np.empty((len(corners), size, size, size), np.float32)
        batch = max(1, MAX_TEXELS // per)
        prog = self._program("mesh_grid")
        prog["uBlock"].value = size
        prog["uStep"].value = float(step)
        prog["uStart"].value = tuple(float(x) for x in np.asarray(start, np.float64) - self.origin)
        prog["uBlocks"].value = 0
        for s in range(0, len(corners), batch):
            part = corners[s:s + batch]
            n = len(part) * per
            texels = -(-n // 4)  # four samples a texel
            w = min(_WIDTH, texels)
            h = -(-texels // w)
            bw = min(len(part), 4096)
            prog["uBlocksWidth"].value = bw
            prog["uWidth"].value = w
            vals = self._draw(prog, w, h, 4, part.astype(np.float32), bw)
            out[s:s + len(part)] = vals.reshape(-1)[:n].reshape(len(part), size, size, size)
        self.samples += len(corners) * per
        return out

    def _at_points(self, target: str, points: np.ndarray, comps: int, outputs: int = 1,
                   **uniforms: float) -> np.ndarray:
        return self.r.run(self._at_points_gl, target, points, comps, outputs, uniforms)

    def _at_points_gl(self, target: str, points: np.ndarray, comps: int, outputs: int,
                      uniforms: dict[str, float]) -> np.ndarray:
        """(outputs, N, comps) float32: ``target``'s outputs at points, ``uniforms`` set by name."""
        pts = np.asarray(points, np.float64).reshape(-1, 3)
        out = np.empty((outputs, len(pts), comps), np.float32)
        if len(pts) == 0:
            return out
        prog = self._program(target)
        for name, value in uniforms.items():
            if name in prog:
                prog[name].value = value
        if "uPoints" in prog:
            prog["uPoints"].value = 0
        for s in range(0, len(pts), MAX_TEXELS):
            part = pts[s:s + MAX_TEXELS]
            w = min(len(part), _WIDTH)
            h = -(-len(part) // w)
            got = self._draw(prog, w, h, comps if comps != 3 else 4, part - self.origin, w, outputs)
            out[:, s:s + len(part)] = got.reshape(outputs, -1, got.shape[-1])[:, :len(part), :comps]
        return out

    def gradient_bend(self, points: np.ndarray, eps: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(value (N,), gradient (N, 3), bend (N,)) of the clipped field at points, differences
        ``eps`` wide (IQ's tetrahedral stencil), and the stencil's bend, the mean of its four
        samples minus the value (shaders/stages/mesh_clip.glsl); ``|bend|`` of order
        ``eps |gradient|`` says the stencil straddles a crease and the gradient mixes its sides."""
        v, b = self._at_points("mesh_gradient", points, 4, 2, uEps=float(eps))
        self.point_samples += 5 * len(v)
        return v[:, 3].astype(np.float64), v[:, :3].astype(np.float64), b[:, 0].astype(np.float64)

    def project(self, points: np.ndarray, eps: float, tolerance: float, max_move: float,
                iterations: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Newton steps onto the surface, all in one draw (shaders/mains/mesh_project_main.glsl):
        (move to add to each point (N, 3) float64, unit gradient at the moved point (N, 3), the
        field there (N,)). Each step moves a point by -f grad / |grad|^2, at most ``max_move``; a
        point stops when |f| <= ``tolerance`` or after ``iterations`` steps; gradients are
        differences ``eps`` wide."""
        move, normal = self._at_points("mesh_project", points, 4, 2, uEps=float(eps), uTol=float(tolerance),
                                     uMaxMove=float(max_move), uIterations=int(iterations))
        self.point_samples += 5 * int(move[:, 3].sum())
        return move[:, :3].astype(np.float64), normal[:, :3].astype(np.float64), normal[:, 3].astype(np.float64)

    def colors(self, points: np.ndarray) -> np.ndarray:
        """The scene's colour field (linear RGB in 0..1, float32 (N, 3)) at points."""
        return self._at_points("evaluate_color", points, 3)[0]
