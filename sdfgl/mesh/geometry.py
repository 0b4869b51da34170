"""Geometry of triangle meshes in numpy: volume, area sampling, point-to-mesh distance."""
from __future__ import annotations

import numpy as np

from .deps import require


def volume(verts: np.ndarray, faces: np.ndarray) -> float:
    """Signed volume enclosed (positive for outward winding): the divergence theorem along z,
    sum over faces of (the face's xy-projected signed area) x (mean z), which needs only the
    coordinates' columns gathered, no cross products."""
    x, y, z = (np.ascontiguousarray(verts[:, i])[faces] for i in range(3))
    twice_area_z = (x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0]) - (y[:, 1] - y[:, 0]) * (x[:, 2] - x[:, 0])
    return float(np.sum(twice_area_z * z.sum(axis=1)) / 6.0)


def sample_surface(verts: np.ndarray, faces: np.ndarray, n: int, rng: np.random.Generator) -> np.ndarray:
    """``n`` points uniformly distributed over the triangles by area."""
    a, b, c = (verts[faces[:, i]] for i in range(3))
    area = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    tri = rng.choice(len(faces), size=n, p=area / area.sum())
    u, v = rng.random(n), rng.random(n)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    return a[tri] + u[:, None] * (b[tri] - a[tri]) + v[:, None] * (c[tri] - a[tri])


def _point_triangle(p: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Distance from points to triangles, row by row (Ericson, Real-Time Collision Detection 5.1.5)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    bp, cp = p - b, p - c
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    denom = va + vb + vc
    denom = np.where(denom == 0, 1e-300, denom)
    v, w = vb / denom, vc / denom
    q = a + v[:, None] * ab + w[:, None] * ac  # inside the face
    cases = [
        (d1 <= 0) & (d2 <= 0), (d3 >= 0) & (d4 <= d3), (d6 >= 0) & (d5 <= d6),
        (vc <= 0) & (d1 >= 0) & (d3 <= 0), (vb <= 0) & (d2 >= 0) & (d6 <= 0),
        (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0),
    ]

    def on(x, y, s):  # noqa: ANN001, ANN202 - clamp to segment x..y
        e = y - x
        t = np.clip(np.einsum("ij,ij->i", s - x, e) / np.maximum(np.einsum("ij,ij->i", e, e), 1e-300), 0, 1)
        return x + t[:, None] * e
    points = [a, b, c, on(a, b, p), on(a, c, p), on(b, c, p)]
    for m, r in zip(cases[::-1], points[::-1]):
        q = np.where(m[:, None], r, q)
    return np.linalg.norm(p - q, axis=1)


def distance_to_mesh(points: np.ndarray, verts: np.ndarray, faces: np.ndarray, k: int = 8) -> np.ndarray:
    """Exact unsigned distance from points to the mesh (to the nearest triangle, not a sample).

    A KD-tree over triangle centroids: the exact distance to the ``k`` triangles whose centroids
    are nearest gives an upper bound d; no triangle can come closer than (centroid distance -
    R), R the largest centroid-to-corner distance of any triangle, so a point is settled when
    its k-th centroid lies beyond d + R, and otherwise every triangle with a centroid within
    d + R is checked.
    """
    points = np.asarray(points, np.float64).reshape(-1, 3)
    if len(points) == 0 or len(faces) == 0:
        return np.full(len(points), np.inf)
    tri = verts[faces]
    centroid = tri.mean(axis=1)
    reach = float(np.linalg.norm(tri - centroid[:, None], axis=2).max())
    tree = require("scipy.spatial").cKDTree(centroid)
    k = min(k, len(faces))
    dist, idx = tree.query(points, k=k)
    dist, idx = np.asarray(dist).reshape(len(points), k), np.asarray(idx).reshape(len(points), k)
    best = np.full(len(points), np.inf)
    for j in range(k):
        f = faces[idx[:, j]]
        best = np.minimum(best, _point_triangle(points, verts[f[:, 0]], verts[f[:, 1]], verts[f[:, 2]]))
    open_ = np.nonzero(dist[:, -1] < best + reach)[0] if k < len(faces) else np.zeros(0, np.int64)
    if len(open_):
        lists = tree.query_ball_point(points[open_], best[open_] + reach)
        sizes = np.array([len(c) for c in lists])
        cand = np.concatenate([np.asarray(c, np.int64) for c in lists])
        owner = np.repeat(np.arange(len(open_)), sizes)
        f = faces[cand]
        d = _point_triangle(points[open_][owner], verts[f[:, 0]], verts[f[:, 1]], verts[f[:, 2]])
        near = np.full(len(open_), np.inf)
        np.minimum.at(near, owner, d)
        best[open_] = np.minimum(best[open_], near)
    return best
