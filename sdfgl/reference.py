"""Float64 ground truth: first hits of camera rays on the numpy twin, and error metrics.

Rays are clipped to the scene bounds like the shader's, then marched on the float64
twin with steps of f / L (L = the scene's Lipschitz factor), which cannot pass the
first root. Within ``near`` of the surface the step never drops below ``near``; once the
field changes sign, bisection pins the root to float64 precision. Fields with no
Lipschitz bound (implicit surfaces) are marched with a fixed small step instead and
refined the same way. Everything is vectorised over the rays still in flight.

A float32 renderer cannot decide a ray that grazes the solid: one that dips below f = 0
by less than float32 rounding and comes out again is a hit or a miss by rounding alone.
Such rays (on fields with a Lipschitz bound) are marked undecided, like rays the
reference cannot settle, and left out of the figures: the band is ``ROUNDING`` times the
ray's distance from the scene centre (a few float32 ulps of the positions the shader
evaluates) times the field's Lipschitz factor (a warp magnifies position rounding by up
to that factor). Rays that touch f = 0 without going below stay misses (a sheet where two
faces coincide is no surface: drawing it is a false hit).
"""
from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Callable

import numpy as np

from .camera import Camera
from .compiler.analysis import scene_frame
from .nodes.base import Node
from .render import RenderResult, shader_origin

MAX_ITERATIONS = 200_000
ROUNDING = 2.0 ** -21   # the float32 band below f = 0: 8 unit roundoffs of |o - centre| + t (the
                        # ray position takes two roundings, the field a few more)


@dataclass
class Reference:
    """Ground truth for the rays of one camera; arrays are (H, W)."""

    t: np.ndarray          # float64 ray parameter of the first hit, inf on a miss
    normal: np.ndarray     # float64 (H, W, 3) unit normal, 0 on a miss or where the gradient vanishes
    undecided: np.ndarray  # bool: rays the reference could not settle within its iteration limit,
                           #   or that graze the solid within float32 rounding (see the module doc)
    pixel_angle: float
    pixel_size: float = 0.0  # an orthographic camera's pixel width (its footprint at every t)

    @property
    def hit(self) -> np.ndarray:
        return np.isfinite(self.t)


def _clip(scene: Node, o: np.ndarray, d: np.ndarray, max_dist: float) -> tuple[np.ndarray, np.ndarray]:
    lo, hi, scale = scene_frame(scene)
    pad = 1e-3 * scale
    safe = np.where(d == 0, 1e-30, d)
    t0 = (lo - pad - o) / safe
    t1 = (hi + pad - o) / safe
    tn = np.minimum(t0, t1).max(axis=-1)
    tf = np.maximum(t0, t1).min(axis=-1)
    far = max_dist if not (np.all(np.isfinite(scene.bounds[0])) and np.all(np.isfinite(scene.bounds[1]))) else np.inf
    return np.maximum(tn, 0.0), np.minimum(tf, far)


def _bisect(scene: Node, o: np.ndarray, d: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Root in [a, b] of f(o + t d), given f(a) > 0 >= f(b), to float64 resolution."""
    for _ in range(64):
        m = 0.5 * (a + b)
        inside = scene.distance(o + d * m[:, None]) <= 0
        b = np.where(inside, m, b)
        a = np.where(inside, a, m)
    return b


def trace_rays(scene: Node, o: np.ndarray, d: np.ndarray, max_dist: float = 1000.0,
               step: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """First-hit t (inf for a miss) of (N, 3) float64 rays, and an 'undecided' mask."""
    n = o.shape[0]
    lo, hi, scale = scene_frame(scene)
    tmin, tmax = _clip(scene, o, d, max_dist)
    t_hit = np.full(n, np.inf)
    undecided = np.zeros(n, dtype=bool)
    lip = scene.lipschitz
    fixed = step if step is not None else scale / 2000.0
    bounded = np.isfinite(lip)
    # positions the shader evaluates are relative to its origin (sdfgl.render.shader_origin: the
    # scene's centre, or near the eye where the scene spans scales, or, for an unbounded scene,
    # the moving eye)
    reach = np.linalg.norm(o - shader_origin(scene, o[0]), axis=-1) if np.all(np.isfinite(scene.bounds)) and n \
        else np.zeros(n)
    near = near_step(scale, reach)

    idx = np.nonzero(tmin <= tmax)[0]
    t = tmin[idx].copy()
    f = scene.distance(o[idx] + d[idx] * t[:, None])
    start_inside = f < 0  # on the surface (f = 0) is not inside: a ray leaving the solid goes on
    t_hit[idx[start_inside]] = t[start_inside]
    keep = ~start_inside
    idx, t, f = idx[keep], t[keep], f[keep]

    for _ in range(MAX_ITERATIONS):
        if idx.size == 0:
            break
        h = np.maximum(f / lip, near(idx, t)) if bounded else np.full_like(t, fixed)
        t_new = t + h
        f_new = scene.distance(o[idx] + d[idx] * t_new[:, None])
        crossed = f_new < 0
        if crossed.any():
            j = idx[crossed]
            t_hit[j] = _bisect(scene, o[j], d[j], t[crossed], t_new[crossed])
        gone = crossed | (t_new > tmax[idx])
        idx, t, f = idx[~gone], t_new[~gone], f_new[~gone]
    undecided[idx] = True
    if bounded:
        hit = np.isfinite(t_hit)
        floor = np.full(n, np.inf)
        floor[hit] = near(np.nonzero(hit)[0], t_hit[hit])
        undecided |= _shallow(scene, o, d, t_hit, ROUNDING * max(lip, 1.0) * (reach + t_hit), lip, floor)
    return t_hit, undecided


def near_step(scale: float, reach: np.ndarray) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    """The smallest step of the march for rays ``idx`` at ``t``: 1e-7 of the scene size, or of
    the distance from the shader origin where that is less (a part a few millimetres from
    the eye, the origin there, in a scene a thousand wide keeps its float64 detail)."""
    def near(idx: np.ndarray, t: np.ndarray) -> np.ndarray:
        return 1e-7 * np.clip(reach[idx] + t, 1e-3 * scale, scale)
    return near


def _shallow(scene: Node, o: np.ndarray, d: np.ndarray, t_hit: np.ndarray, band: np.ndarray,
             lip: float, near: np.ndarray, limit: int = 2048) -> np.ndarray:
    """True for hits whose dip below f = 0 stays shallower than ``band`` until the ray leaves
    the solid again (a graze within float32 rounding). Only rays that start shallow are followed,
    in steps of at least ``band / lip``: between two samples above -band the field cannot fall
    below -1.5 band, and a graze along a gently curved face (thousands of ``near`` steps long)
    is followed to its end within ``limit`` steps."""
    out = np.zeros(t_hit.shape, dtype=bool)
    idx = np.nonzero(np.isfinite(t_hit))[0]
    t = t_hit[idx] + near[idx]
    for _ in range(limit):
        if idx.size == 0:
            break
        f = scene.distance(o[idx] + d[idx] * t[:, None])
        keep = f > -band[idx]  # deeper than the band: a plain hit, no longer followed
        idx, t, f = idx[keep], t[keep], f[keep]
        left = f >= 0
        out[idx[left]] = True  # out again without going deeper than the band
        idx, t, f = idx[~left], t[~left], f[~left]
        t = t + np.maximum(np.maximum(np.abs(f), band[idx]) / lip, near[idx])
    return out


def normals(scene: Node, p: np.ndarray, reach: np.ndarray | None = None) -> np.ndarray:
    """Unit gradients of the float64 twin at (N, 3) points by central differences (0 where it vanishes).

    The offset is 1e-6 of the scene size, or of ``reach`` (per point: its distance from
    the shader origin) where that is less, so a part far smaller than the scene near the
    origin is not straddled, but at least 1e-12 of the point's distance from the world origin."""
    _, _, scale = scene_frame(scene)
    if reach is None:
        h = 1e-6 * scale
    else:  # at least 1e-12 of the point's own magnitude: float64 differences stay well above rounding
        h = np.maximum(1e-6 * np.clip(reach, 1e-6 * scale, scale), 1e-12 * np.linalg.norm(p, axis=-1))[:, None]
    g = np.stack([scene.distance(p + h * e) - scene.distance(p - h * e) for e in np.eye(3)], axis=-1)
    n = np.linalg.norm(g, axis=-1, keepdims=True)
    return np.where(n > 1e-12 * h, g / np.where(n > 0, n, 1.0), 0.0)


def trace(scene: Node, camera: Camera, size: tuple[int, int], max_dist: float = 1000.0,
          step: float | None = None) -> Reference:
    """Ground truth for every pixel-centre ray of ``camera`` at ``size`` = (width, height)."""
    w, h = size
    o, d = camera.rays(w, h)
    t, undecided = trace_rays(scene, o.reshape(-1, 3), d.reshape(-1, 3), max_dist, step)
    nrm = np.zeros((w * h, 3))
    hit = np.isfinite(t)
    if hit.any():
        p = o.reshape(-1, 3)[hit] + d.reshape(-1, 3)[hit] * t[hit, None]
        nrm[hit] = normals(scene, p, np.linalg.norm(p - shader_origin(scene, camera.eye), axis=-1))
    return Reference(t.reshape(h, w), nrm.reshape(h, w, 3), undecided.reshape(h, w), camera.pixel_angle(h),
                     float(camera.footprint(0.0, h)) if camera.orthographic else 0.0)


@dataclass
class ErrorReport:
    """Render-vs-reference errors. Depth errors are also given in pixel footprints (t * pixel angle)."""

    pixels: int
    hits: int                   # reference hits
    depth_abs_median: float
    depth_abs_p99: float
    depth_abs_max: float
    depth_px_median: float      # |t - t*| / footprint
    depth_px_p99: float
    depth_px_max: float
    depth_outliers: int         # both hit, but more than 2 footprints apart: a near miss of one
                                #   surface taken for a hit where the reference goes on to another
    silhouette_mismatch: int    # pixels hit in one image and not in the other
    false_hits: int             # render hit, reference miss
    lost_hits: int              # reference hit, render miss
    normal_deg_median: float
    normal_deg_p99: float
    normal_deg_max: float
    nan_count: int              # NaN anywhere in depth or normal, Inf in normal
    undecided: int              # rays the reference could not settle (left out of the figures)
    surface_px_p99: float = float("nan")  # render hits: distance along the ray to the nearest
    surface_px_max: float = float("nan")  #   sign change of the twin, in footprints (surface_offsets)

    def as_dict(self) -> dict[str, float]:
        return asdict(self)


def _stats(x: np.ndarray) -> tuple[float, float, float]:
    if x.size == 0:
        return 0.0, 0.0, 0.0
    return float(np.median(x)), float(np.percentile(x, 99)), float(x.max())


def compare(result: RenderResult, ref: Reference) -> ErrorReport:
    """Hold a render (with depth and normal outputs) against the float64 reference."""
    if result.depth is None or result.normal is None:
        raise ValueError("compare() needs a render made with outputs including 'depth' and 'normal'")
    depth = result.depth.astype(np.float64)
    nan_count = int(np.isnan(depth).sum() + np.isnan(result.normal).sum() + np.isinf(result.normal).sum())
    decided = ~ref.undecided
    r_hit = np.isfinite(depth) & decided
    g_hit = ref.hit & decided
    both = r_hit & g_hit
    err = np.abs(depth[both] - ref.t[both])
    foot = (np.full(err.shape, ref.pixel_size) if ref.pixel_size
            else np.maximum(ref.t[both], 1e-12) * ref.pixel_angle)
    gn = ref.normal[both]
    defined = np.linalg.norm(gn, axis=-1) > 0.5
    cosang = np.sum(gn[defined] * result.normal[both][defined].astype(np.float64), axis=-1)
    ang = np.degrees(np.arccos(np.clip(cosang, -1.0, 1.0)))
    a = _stats(err)
    p = _stats(err / foot)
    nd = _stats(ang)
    return ErrorReport(
        pixels=int(depth.size), hits=int(g_hit.sum()),
        depth_abs_median=a[0], depth_abs_p99=a[1], depth_abs_max=a[2],
        depth_px_median=p[0], depth_px_p99=p[1], depth_px_max=p[2],
        depth_outliers=int((err / foot > 2.0).sum()),
        silhouette_mismatch=int((r_hit != g_hit).sum()), false_hits=int((r_hit & ~g_hit).sum()),
        lost_hits=int((~r_hit & g_hit).sum()),
        normal_deg_median=nd[0], normal_deg_p99=nd[1], normal_deg_max=nd[2],
        nan_count=nan_count, undecided=int(ref.undecided.sum()))


def surface_offsets(scene: Node, camera: Camera, result: RenderResult, reach: float = 2.0,
                    samples: int = 801) -> np.ndarray:
    """For every pixel the render hit: how far (in pixel footprints, along the ray) its
    hit lies from the nearest sign change of the float64 twin, searched within ``reach``
    footprints either side (inf where there is none: the hit is on no surface).

    This is the "reported hit within x footprints of the true surface" figure; unlike the
    depth error it does not ask which surface along the ray comes first.
    """
    if result.depth is None:
        raise ValueError("surface_offsets() needs a render made with the 'depth' output")
    h, w = result.depth.shape
    o, d = camera.rays(w, h)
    hit = np.isfinite(result.depth)
    t = result.depth[hit].astype(np.float64)
    o, d = o[hit], d[hit]
    foot = np.maximum(t, 1e-12) * camera.pixel_angle(h)
    out = np.full(t.shape, np.inf)
    fine = np.linspace(-0.01, 0.01, 201)  # slivers: a chord far below a footprint near the hit
    u = np.unique(np.concatenate([np.linspace(-reach, reach, samples), fine]))
    for s0 in range(0, t.size, 256):
        sl = slice(s0, s0 + 256)
        ts = t[sl, None] + foot[sl, None] * u[None, :]
        f = scene.distance((o[sl, None, :] + d[sl, None, :] * ts[..., None]).reshape(-1, 3)).reshape(ts.shape)
        change = (f[:, :-1] > 0) != (f[:, 1:] > 0)
        near = np.minimum(np.abs(u[:-1]), np.abs(u[1:]))  # the nearer end of each interval
        near = np.where((u[:-1] < 0) & (u[1:] > 0), 0.0, near)
        out[sl] = np.where(change, near[None, :], np.inf).min(axis=1)
    start = t <= 0.0
    if start.any():  # a ray that starts inside the solid hits at t = 0
        out[start] = np.where(scene.distance(o[start]) <= 0, 0.0, out[start])
    return out
