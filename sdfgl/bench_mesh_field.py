"""Benchmark rows of a triangle mesh as a field (``sg.from_mesh``), against libigl and rasterisation.

- signed distance at N points: ``sg.evaluate`` (GPU, the BVH) against ``igl.signed_distance``
  (pseudonormal sign, the node's float64 twin) on the same points: time ratio, max
  |difference| / bbox diagonal, and sign agreement beyond 1e-4 diagonals of the surface;
- a frame of the mesh as a field (median warm frame, no shadows or AO) against drawing the same
  triangles with moderngl (depth-tested rasterisation, same size): time ratio;
- the field's rendered depth against a float64 ray-triangle cast on sampled pixels, and the mesh
  drilled and meshed again (watertight, volume against the twin's): :func:`depth_row`,
  :func:`remesh_row` (``benchmarks/mesh_field.py`` prints all four).

The mesh is a bumpy torus (closed; 2 nu nv triangles). ``sdfgl bench`` runs
:func:`run_mesh_field`: 100 000 triangles, 10^6 points and 640x480 in the full bench, a
960-triangle torus, 10^4 points and 64x48 with ``--quick``.
"""
from __future__ import annotations

import time
from typing import Any

import moderngl
import numpy as np

from .camera import Camera, OrbitCamera
from .evaluate import evaluate
from .extras import require_extra
from .meshin import from_mesh
from .nodes.mesh_field import MeshField
from .render import Renderer

FULL = {"nu": 500, "nv": 100, "points": 10 ** 6, "size": (640, 480), "frames": 3}
QUICK = {"nu": 40, "nv": 12, "points": 10 ** 4, "size": (64, 48), "frames": 2}
"""The sizes of the full bench and of ``--quick``."""


def bumpy_torus(nu: int = 500, nv: int = 100) -> Any:
    """A torus (R 0.6, r 0.2 in XZ) with bumps of 15 % of r: a closed ``trimesh.Trimesh`` of
    2 nu nv triangles."""
    require_extra("meshin", "trimesh", purpose="the mesh-as-field benchmark")
    import trimesh
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


def diagonal(node: MeshField) -> float:
    """The length of the mesh's bounding box diagonal."""
    lo, hi = node.bounds
    return float(np.linalg.norm(hi - lo))


def sample_points(node: MeshField, n: int, rng: np.random.Generator) -> np.ndarray:
    """``n`` points: half uniform in the box grown by 10 % of the diagonal, half near the surface."""
    lo, hi = node.bounds
    diag = diagonal(node)
    near = n - n // 2
    return np.concatenate([rng.uniform(lo - 0.1 * diag, hi + 0.1 * diag, (n // 2, 3)),
                           node.vertices[rng.integers(0, len(node.vertices), near)]
                           + rng.normal(scale=0.01 * diag, size=(near, 3))])


def distance_row(node: MeshField, points: np.ndarray, renderer: Renderer) -> dict[str, float]:
    """GPU signed distance at ``points`` against libigl's on the same points: times, their ratio,
    max |difference| / diagonal, and the share of points beyond 1e-4 diagonals whose signs agree."""
    require_extra("meshin", "igl", purpose="the mesh-as-field benchmark")
    import igl
    evaluate(node, points[:1000], renderer=renderer)  # compile and upload once
    t0 = time.perf_counter()
    gpu = evaluate(node, points, renderer=renderer).astype(np.float64)
    t_gpu = time.perf_counter() - t0
    t0 = time.perf_counter()
    ref = igl.signed_distance(points, node.vertices, node.faces, sign_type=igl.SIGNED_DISTANCE_TYPE_PSEUDONORMAL)[0]
    t_igl = time.perf_counter() - t0
    diag = diagonal(node)
    far = np.abs(ref) > 1e-4 * diag
    agree = float(np.mean(np.sign(gpu[far]) == np.sign(ref[far]))) if far.any() else 1.0
    return {"points": len(points), "gpu_s": t_gpu, "igl_s": t_igl, "ratio": t_gpu / t_igl,
            "max_diff_diag": float(np.abs(gpu - ref).max()) / diag, "sign_agreement": agree}


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


def _mvp(cam: Camera, size: tuple[int, int]) -> np.ndarray:
    """The perspective view-projection matrix of ``cam`` (near 0.05, far 20)."""
    r, u, f = cam.basis()
    view = np.eye(4)
    view[0, :3], view[1, :3], view[2, :3] = r, u, -f
    view[:3, 3] = -view[:3, :3] @ cam.eye
    near, far, t = 0.05, 20.0, cam.tan_half_fov
    proj = np.zeros((4, 4))
    proj[0, 0], proj[1, 1] = 1 / (t * size[0] / size[1]), 1 / t
    proj[2, 2], proj[2, 3], proj[3, 2] = -(far + near) / (far - near), -2 * far * near / (far - near), -1
    return proj @ view


def raster_frame(mesh: Any, cam: Camera, size: tuple[int, int], frames: int) -> float:
    """Median seconds of drawing the trimesh ``mesh`` depth-tested at ``size`` with moderngl (its own
    EGL context), finish() included."""
    ctx = moderngl.create_context(standalone=True, backend="egl")
    try:
        prog = ctx.program(vertex_shader=RASTER_VS, fragment_shader=RASTER_FS)
        prog["mvp"].write(_mvp(cam, size).T.astype("f4").tobytes())
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
    finally:
        ctx.release()
    return float(np.median(times[1:]))


FRAME_SETTINGS = {"outputs": ("color", "depth"), "shadows": False, "ao": False}


def field_frame(node: MeshField, cam: Camera, size: tuple[int, int], frames: int, renderer: Renderer) -> tuple[float, Any]:
    """(median seconds of a warm frame of the mesh as a field, the last frame's result)."""
    renderer.render(node, cam, size, **FRAME_SETTINGS)
    times, res = [], None
    for _ in range(frames):
        t0 = time.perf_counter()
        res = renderer.render(node, cam, size, **FRAME_SETTINGS)
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), res


def frame_row(mesh: Any, node: MeshField, size: tuple[int, int], frames: int, renderer: Renderer) -> dict[str, Any]:
    """The field frame against the raster frame of the same triangles, framed alike."""
    cam = OrbitCamera.framing(*node.bounds, aspect=size[0] / size[1])
    t_field, res = field_frame(node, cam, size, frames, renderer)
    t_raster = raster_frame(mesh, cam, size, max(frames, 5))
    return {"size": list(size), "field_s": t_field, "raster_s": t_raster, "ratio": t_field / t_raster,
            "_camera": cam, "_result": res}


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


def depth_row(mesh: Any, frame: dict[str, Any], pixels: int, rng: np.random.Generator) -> dict[str, float]:
    """The field frame's depth against a float64 ray cast of every triangle on ``pixels`` sampled
    pixels: hits found by both, false and lost hits, and the depth error in pixel footprints."""
    cam, res = frame["_camera"], frame["_result"]
    w, h = frame["size"]
    o, d = cam.rays(w, h)
    idx = rng.choice(w * h, pixels, replace=False)
    ref_t = ray_mesh(o.reshape(-1, 3)[idx], d.reshape(-1, 3)[idx], np.asarray(mesh.triangles))
    got = res.depth.reshape(-1)[idx].astype(np.float64)
    hit_ref, hit_got = np.isfinite(ref_t), np.isfinite(got)
    both = hit_ref & hit_got
    off = np.abs(got[both] - ref_t[both]) / cam.footprint(ref_t[both], h)
    return {"pixels": pixels, "both": int(both.sum()), "false": int((hit_got & ~hit_ref).sum()),
            "lost": int((hit_ref & ~hit_got).sum()), "within_0.01": float(np.mean(off <= 0.01)),
            "median_px": float(np.median(off)), "max_px": float(off.max())}


def remesh_row(node: MeshField, step: float, lattice: int) -> dict[str, Any]:
    """The mesh drilled by two cylinders and meshed again (``sg.mesh``): watertight, and its volume
    against the twin's inside test on a ``lattice``^3 grid."""
    import trimesh

    from . import mesh as build_mesh
    from .nodes import cylinder, union
    lo, hi = node.bounds
    drilled = node - union(*(cylinder(0.08, 2).orient(np.array(ax)).translate((0.6, 0, 0))
                                  for ax in ((0.0, 1.0, 0.0), (0.0, 0.0, 1.0))))
    t0 = time.perf_counter()
    out = build_mesh(drilled, step=step, colors=False)
    t_mesh = time.perf_counter() - t0
    em = trimesh.Trimesh(out.vertices, out.faces, process=False)
    c = lo + (np.arange(lattice)[:, None] + 0.5) * (hi - lo) / lattice
    grid = np.stack(np.meshgrid(c[:, 0], c[:, 1], c[:, 2], indexing="ij"), -1).reshape(-1, 3)
    twin = float(np.prod(hi - lo)) * float(np.mean(drilled.distance(grid) < 0))
    return {"triangles": len(em.faces), "mesh_s": t_mesh, "watertight": bool(em.is_watertight),
            "volume": float(em.volume), "twin_volume": twin}


def run_mesh_field(quick: bool, renderer: Renderer | None = None) -> tuple[str, dict[str, Any]]:
    """The bench's mesh rows (sizes :data:`FULL`, or :data:`QUICK`): (markdown, data)."""
    sizes = QUICK if quick else FULL
    renderer = renderer or Renderer()
    tm = bumpy_torus(sizes["nu"], sizes["nv"])
    node = from_mesh(tm, name="bumpy torus")
    rng = np.random.default_rng(0)
    dist = distance_row(node, sample_points(node, sizes["points"], rng), renderer)
    frame = frame_row(tm, node, sizes["size"], sizes["frames"], renderer)
    w, h = frame["size"]
    md = "\n".join([
        f"A bumpy torus of {len(node.faces)} triangles as a field (`sg.from_mesh`).", "",
        "| row | sdfgl | other | ratio | accuracy |", "|---|---|---|---|---|",
        f"| signed distance at {dist['points']} points | GPU {dist['gpu_s']:.3f} s | libigl {dist['igl_s']:.3f} s | "
        f"{dist['ratio']:.2f} | max abs difference {dist['max_diff_diag']:.1e} diagonals; signs agree at "
        f"{100 * dist['sign_agreement']:.3f} % of points beyond 1e-4 diagonals |",
        f"| frame {w}x{h} (no shadows, AO) | field {1000 * frame['field_s']:.1f} ms | raster "
        f"{1000 * frame['raster_s']:.2f} ms | {frame['ratio']:.1f} | |",
    ])
    data = {"triangles": len(node.faces), "distance": dist,
            "frame": {k: v for k, v in frame.items() if not k.startswith("_")}}
    return md, data
