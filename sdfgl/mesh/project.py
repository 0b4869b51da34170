"""Vertices moved onto the surface with the field and its gradient (Newton steps along it)."""
from __future__ import annotations

import numpy as np

from .sample import GPUField

TOLERANCE = 1e-3  # stop when every |f| at a vertex is below this share of a cell


def project(field: GPUField, verts: np.ndarray, step: float, iterations: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """(vertices on the surface, unit outward normals there).

    Each step moves a vertex by -f grad / |grad|^2, at most half a cell, so a vertex near a
    thin wall or a crease stays on its own side of it.
    """
    v = np.array(verts, dtype=np.float64)
    eps = 0.05 * step
    f, g = field.gradient(v, eps)
    todo = np.nonzero(np.abs(f) > TOLERANCE * step)[0]  # only moved vertices can change
    for _ in range(iterations):
        if not len(todo):
            break
        gt = g[todo]
        d = (f[todo] / np.maximum(np.einsum("ij,ij->i", gt, gt), 1e-12))[:, None] * gt
        length = np.sqrt(np.einsum("ij,ij->i", d, d))[:, None]
        d *= np.minimum(1.0, 0.5 * step / np.maximum(length, 1e-300))
        v[todo] -= d
        f[todo], g[todo] = field.gradient(v[todo], eps)
        todo = todo[np.abs(f[todo]) > TOLERANCE * step]
    g /= np.maximum(np.sqrt(np.einsum("ij,ij->i", g, g)), 1e-30)[:, None]
    return v, g
