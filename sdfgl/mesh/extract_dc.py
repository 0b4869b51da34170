"""Dual contouring (Ju et al. 2002), vectorised: sharp edges and corners from field gradients.

Every lattice edge whose ends differ in sign gives a crossing point (linear interpolation
of the samples) and a normal (the GPU gradient there). Each cell that touches crossing
edges gets one vertex, the minimiser of the quadric sum((n_i . (x - p_i))^2), solved with
small singular values cut (so flat and edge cells fall back towards the crossings' mean,
as in Lindstrom's and Ju's treatment) and kept inside the cell. Each crossing edge gives
one quad over the four cells around it, wound so it faces increasing field.
"""
from __future__ import annotations

import numpy as np

from .extract_mc import separate
from .lattice import BLOCK, Lattice
from .sample import GPUField

SVD_CUT = 0.1  # singular values below this share of the largest are dropped


def crossings(chunks, lat: Lattice) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # noqa: ANN001
    """All crossing edges, each once: (lower sample (E, 3) int64, axis (E,), t in (0, 1),
    lower end inside (E,) bool)."""
    lows, axes, ts, ins = [], [], [], []
    for ch in chunks:
        f = ch.fine.copy()
        separate(f, lat.step)
        base = (np.asarray(ch.origin, np.int64) + ch.active) * BLOCK  # (K, 3) lower sample of each block
        for a in range(3):
            lo = f[:, :BLOCK, :BLOCK, :BLOCK]
            hi = np.roll(f, -1, axis=1 + a)[:, :BLOCK, :BLOCK, :BLOCK]
            m = (lo < 0) != (hi < 0)
            if not m.any():
                continue
            kb, i, j, k = np.nonzero(m)
            v0, v1 = lo[m].astype(np.float64), hi[m].astype(np.float64)
            lows.append(base[kb] + np.stack([i, j, k], 1))
            axes.append(np.full(len(kb), a, np.int8))
            ts.append(v0 / (v0 - v1))
            ins.append(v0 < 0)
    if not lows:
        return np.zeros((0, 3), np.int64), np.zeros(0, np.int8), np.zeros(0), np.zeros(0, bool)
    return np.concatenate(lows), np.concatenate(axes), np.concatenate(ts), np.concatenate(ins)


def _quad_cells(low: np.ndarray, axis: np.ndarray) -> np.ndarray:
    """(E, 4, 3) cells around each edge, counter-clockwise seen from the +axis side."""
    ring = np.array([(-1, -1), (0, -1), (0, 0), (-1, 0)])
    out = np.repeat(low[:, None, :], 4, axis=1)
    for a in range(3):
        sel = axis == a
        b, c = (a + 1) % 3, (a + 2) % 3
        out[sel, :, b] += ring[:, 0]
        out[sel, :, c] += ring[:, 1]
    return out


def _solve(ata: np.ndarray, atb: np.ndarray, mass: np.ndarray) -> np.ndarray:
    """Minimiser of x^T A x - 2 b^T x nearest the mass point, small singular values cut."""
    u, s, vt = np.linalg.svd(ata)
    inv = np.where(s > SVD_CUT * s[:, :1], 1.0 / np.where(s > 0, s, 1.0), 0.0)
    rhs = atb - np.einsum("nij,nj->ni", ata, mass)
    pinv = np.einsum("nji,nj,nkj->nik", vt, inv, u)
    return mass + np.einsum("nij,nj->ni", pinv, rhs)


def dual_contour(chunks, lat: Lattice, field: GPUField) -> tuple[np.ndarray, np.ndarray]:  # noqa: ANN001
    """(vertices (N, 3) world, triangles (M, 3) outward-wound)."""
    low, axis, t, inside = crossings(chunks, lat)
    if len(low) == 0:
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64)
    h = lat.step
    pts = lat.start + (low + np.eye(3)[axis] * t[:, None]) * h
    _, grad = field.gradient(pts, 0.05 * h)
    n = grad / np.maximum(np.linalg.norm(grad, axis=1, keepdims=True), 1e-30)
    cells = _quad_cells(low, axis)                       # (E, 4, 3)
    nc = np.asarray(lat.cells, np.int64)
    keys = (cells[..., 0] * nc[1] + cells[..., 1]) * nc[2] + cells[..., 2]
    uk, inv = np.unique(keys.ravel(), return_inverse=True)
    inv = inv.reshape(-1, 4)
    # quadric of each cell, accumulated over its crossing edges (in cell units about the cell corner)
    cell_lo = np.stack([uk // (nc[1] * nc[2]), (uk // nc[2]) % nc[1], uk % nc[2]], 1)
    idx = inv.ravel()
    local = (np.repeat(low + np.eye(3)[axis] * t[:, None], 4, axis=0) - cell_lo[idx])
    nn = np.repeat(n, 4, axis=0)
    m = len(uk)
    ata = np.empty((m, 3, 3))
    for i in range(3):
        for j in range(i, 3):
            ata[:, i, j] = ata[:, j, i] = np.bincount(idx, nn[:, i] * nn[:, j], m)
    d = np.einsum("ij,ij->i", nn, local)
    atb = np.stack([np.bincount(idx, nn[:, i] * d, m) for i in range(3)], 1)
    cnt = np.bincount(idx, minlength=m)[:, None]
    mass = np.stack([np.bincount(idx, local[:, i], m) for i in range(3)], 1) / cnt
    x = np.clip(_solve(ata, atb, mass), 0.0, 1.0)
    verts = lat.start + (cell_lo + x) * h
    quads = np.where(inside[:, None], inv, inv[:, ::-1])
    return verts, split_quads(verts, quads)


def split_quads(verts: np.ndarray, quads: np.ndarray) -> np.ndarray:
    """Two triangles per quad, along the diagonal whose triangles agree best in direction."""
    q = [verts[quads[:, i]] for i in range(4)]

    def agreement(a, b, c, d):  # noqa: ANN001, ANN202 - triangles (a, b, c) and (a, c, d)
        n1 = np.cross(b - a, c - a)
        n2 = np.cross(c - a, d - a)
        return np.einsum("ij,ij->i", n1, n2) / np.maximum(
            np.linalg.norm(n1, axis=1) * np.linalg.norm(n2, axis=1), 1e-300)

    first = agreement(q[0], q[1], q[2], q[3]) >= agreement(q[1], q[2], q[3], q[0])
    t1 = np.where(first[:, None], quads[:, [0, 1, 2]], quads[:, [1, 2, 3]])
    t2 = np.where(first[:, None], quads[:, [0, 2, 3]], quads[:, [1, 3, 0]])
    return np.concatenate([t1, t2])
