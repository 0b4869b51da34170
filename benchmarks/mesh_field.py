"""Figures of a triangle mesh as a field (sg.from_mesh): a 100 000-triangle closed mesh (a
bumpy torus, 500 x 100 quads), against libigl and float64 ray casts.

- signed distance at 10^6 points: sg.evaluate (GPU) against igl.signed_distance (pseudonormal
  sign, the node's float64 twin), time ratio, max |difference| / bbox diagonal, sign
  disagreements farther than 1e-4 diagonals;
- rendering the mesh as a field at 640x480 (median warm frame), beside drawing the same
  triangles with moderngl (depth-tested rasterisation, same size); the rendered depth against a
  float64 ray-triangle cast (every triangle) on sampled pixels, in pixel footprints;
- the mesh drilled by three cylinders, meshed again: watertight, and its volume against the
  twin's (a 128^3 lattice of the twin's inside test).

    python benchmarks/mesh_field.py            # full sizes
    python benchmarks/mesh_field.py --quick    # 10^5 points, 160x120, 500 pixels
"""
import argparse
import os
import time

import moderngl
import numpy as np
import trimesh

import sdfgl as sg
from sdfgl.gl.context import describe


def bumpy_torus(nu: int = 500, nv: int = 100) -> trimesh.Trimesh:
    """A torus (R 0.6, r 0.2 in XZ) with bumps of 15 % of r: 2 nu nv triangles, closed."""
    u = np.arange(nu) * 2 * np.pi / nu
    v = np.arange(nv) * 2 * np.pi / nv
    uu, vv = np.meshgrid(u, v, indexing="ij")
    r = 0.2 * (1 + 0.15 * np.sin(7 * uu) * np.sin(5 * vv))
    pts = np.stack([(0.6 + r * np.cos(vv)) * np.cos(uu), r * np.sin(vv), (0.6 + r * np.cos(vv)) * np.sin(uu)], -1)
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a, b = i * nv + j, ((i + 1) % nu) * nv + j
    c, d = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
    faces = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return trimesh.Trimesh(pts.reshape(-1, 3), faces, process=False)


def ray_mesh(o: np.ndarray, d: np.ndarray, tri: np.ndarray, chunk: int = 8) -> np.ndarray:
    """float64 Moller-Trumbore, every ray against every triangle: nearest t >= 0, inf on a miss."""
    a, e1, e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    out = np.full(len(o), np.inf)
    for s in range(0, len(o), chunk):
        oo, dd = o[s:s + chunk, None], d[s:s + chunk, None]
        pv = np.cross(dd, e2)
        inv = 1.0 / (e1 * pv).sum(-1)
        tv = oo - a
        u = (tv * pv).sum(-1) * inv
        qv = np.cross(tv, e1)
        v = (dd * qv).sum(-1) * inv
        t = (e2 * qv).sum(-1) * inv
        out[s:s + chunk] = np.where((u >= 0) & (v >= 0) & (u + v <= 1) & (t >= 0), t, np.inf).min(axis=1)
    return out


RASTER_VS = """#version 330
uniform mat4 mvp;
in vec3 pos;
in vec3 nrm;
out vec3 n;
void main() { n = nrm; gl_Position = mvp * vec4(pos, 1.0); }
"""
RASTER_FS = """#version 330
in vec3 n;
out vec4 color;
void main() { color = vec4(vec3(0.2 + 0.8 * max(dot(normalize(n), normalize(vec3(1, 2, 1))), 0.0)), 1.0); }
"""


def raster_frame(mesh: trimesh.Trimesh, cam: sg.Camera, size: tuple[int, int], frames: int) -> float:
    """Median time of drawing ``mesh`` depth-tested at ``size`` with moderngl (EGL), finish() included."""
    ctx = moderngl.create_context(standalone=True, backend="egl")
    prog = ctx.program(vertex_shader=RASTER_VS, fragment_shader=RASTER_FS)
    r, u, f = cam.basis()
    view = np.eye(4)
    view[0, :3], view[1, :3], view[2, :3] = r, u, -f
    view[:3, 3] = -view[:3, :3] @ cam.eye
    near, far, t = 0.05, 20.0, cam.tan_half_fov
    proj = np.zeros((4, 4))
    proj[0, 0], proj[1, 1] = 1 / (t * size[0] / size[1]), 1 / t
    proj[2, 2], proj[2, 3], proj[3, 2] = -(far + near) / (far - near), -2 * far * near / (far - near), -1
    prog["mvp"].write((proj @ view).T.astype("f4").tobytes())
    tri = np.asarray(mesh.triangles, dtype="f4").reshape(-1, 3)
    nrm = np.repeat(np.asarray(mesh.face_normals, dtype="f4"), 3, axis=0)
    vbo = ctx.buffer(np.hstack([tri, nrm]).astype("f4").tobytes())
    vao = ctx.vertex_array(prog, [(vbo, "3f 3f", "pos", "nrm")])
    fbo = ctx.framebuffer(ctx.renderbuffer(size), ctx.depth_renderbuffer(size))
    fbo.use()
    ctx.enable(moderngl.DEPTH_TEST)
    times = []
    for _ in range(frames + 1):
        t0 = time.perf_counter()
        fbo.clear(0.5, 0.5, 0.5, 1.0)
        vao.render()
        ctx.finish()
        times.append(time.perf_counter() - t0)
    ctx.release()
    return float(np.median(times[1:]))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="small sizes (a smoke run)")
    a = ap.parse_args()
    npts, size, pixels, frames = (10 ** 5, (160, 120), 500, 2) if a.quick else (10 ** 6, (640, 480), 3000, 3)
    import igl
    renderer = sg.Renderer()
    print(f"machine: {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}; GL: {describe(renderer.ctx)}")
    tm = bumpy_torus()
    t0 = time.perf_counter()
    node = sg.from_mesh(tm, name="bumpy torus")
    t1 = time.perf_counter()
    node.bvh
    t2 = time.perf_counter()
    lo, hi = node.bounds
    diag = float(np.linalg.norm(hi - lo))
    print(f"mesh: {len(node.faces)} triangles, diagonal {diag:.4f}; from_mesh {t1 - t0:.2f} s, hierarchy "
          f"{t2 - t1:.2f} s (depth {node.bvh.depth})")

    rng = np.random.default_rng(0)
    pts = np.concatenate([rng.uniform(lo - 0.1 * diag, hi + 0.1 * diag, (npts // 2, 3)),
                          node.vertices[rng.integers(0, len(node.vertices), npts - npts // 2)]
                          + rng.normal(scale=0.01 * diag, size=(npts - npts // 2, 3))])
    sg.evaluate(node, pts[:1000], renderer=renderer)  # compile and upload once
    t0 = time.perf_counter()
    gpu = sg.evaluate(node, pts, renderer=renderer).astype(np.float64)
    t_gpu = time.perf_counter() - t0
    t0 = time.perf_counter()
    ref = igl.signed_distance(pts, node.vertices, node.faces, sign_type=igl.SIGNED_DISTANCE_TYPE_PSEUDONORMAL)[0]
    t_igl = time.perf_counter() - t0
    far = np.abs(ref) > 1e-4 * diag
    flips = int(np.count_nonzero(np.sign(gpu[far]) != np.sign(ref[far])))
    print(f"distance at {npts} points: GPU {t_gpu:.2f} s, libigl {t_igl:.2f} s, ratio {t_gpu / t_igl:.2f}x; "
          f"max |diff| {np.abs(gpu - ref).max() / diag:.2e} diagonals; sign disagreements beyond 1e-4 "
          f"diagonals: {flips} of {int(far.sum())}")

    cam = sg.OrbitCamera.framing(lo, hi, aspect=size[0] / size[1])
    st = {"outputs": ("color", "depth"), "shadows": False, "ao": False}
    renderer.render(node, cam, size, **st)
    times = []
    for _ in range(frames):
        t0 = time.perf_counter()
        res = renderer.render(node, cam, size, **st)
        times.append(time.perf_counter() - t0)
    t_field = float(np.median(times))
    t_raster = raster_frame(tm, cam, size, 5)
    print(f"render {size[0]}x{size[1]} (no shadows/AO): field {t_field:.3f} s/frame, moderngl raster "
          f"{t_raster:.4f} s/frame, ratio {t_field / t_raster:.1f}x")
    o, d = cam.rays(*size)
    idx = rng.choice(size[0] * size[1], pixels, replace=False)
    ref_t = ray_mesh(o.reshape(-1, 3)[idx], d.reshape(-1, 3)[idx], np.asarray(tm.triangles))
    got = res.depth.reshape(-1)[idx].astype(np.float64)
    hit_ref, hit_got = np.isfinite(ref_t), np.isfinite(got)
    both = hit_ref & hit_got
    off = np.abs(got[both] - ref_t[both]) / cam.footprint(ref_t[both], size[1])
    print(f"hits on {pixels} sampled pixels: {int(both.sum())} both, {int((hit_got & ~hit_ref).sum())} false, "
          f"{int((hit_ref & ~hit_got).sum())} lost; within 0.01 footprints {np.mean(off <= 0.01) * 100:.2f} %, "
          f"median {np.median(off):.4f}, max {off.max():.3f} footprints")

    drilled = node - sg.union(*(sg.cylinder(0.08, 2).orient(ax).translate((0.6, 0, 0)) for ax in (sg.Y, sg.Z)))
    t0 = time.perf_counter()
    out = sg.mesh(drilled, step=0.008 if not a.quick else 0.01, colors=False)
    t_mesh = time.perf_counter() - t0
    em = trimesh.Trimesh(out.vertices, out.faces, process=False)
    n = 128 if not a.quick else 64
    c = lo + (np.arange(n)[:, None] + 0.5) * (hi - lo) / n
    grid = np.stack(np.meshgrid(c[:, 0], c[:, 1], c[:, 2], indexing="ij"), -1).reshape(-1, 3)
    twin = float(np.prod(hi - lo)) * np.mean(drilled.distance(grid) < 0)
    print(f"drilled and meshed again ({len(em.faces)} triangles, {t_mesh:.1f} s): watertight {em.is_watertight}, "
          f"volume {em.volume:.5f} vs twin {twin:.5f} ({(em.volume / twin - 1) * 100:+.2f} %)")


if __name__ == "__main__":
    main()
