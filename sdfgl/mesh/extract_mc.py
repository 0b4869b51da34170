"""Marching cubes per chunk (scikit-image's Lewiner variant), welded into one mesh.

Lewiner's tables resolve the ambiguous faces and cells of the original algorithm with the
asymptotic decider, so the surface is a closed 2-manifold wherever the samples are; a
face shared by two chunks has the same four values in both, so both triangulate it alike.
Every vertex lies inside one lattice edge; that edge (axis + lower sample) is its key, and
equal keys from neighbouring chunks weld into one vertex.
"""
from __future__ import annotations

import numpy as np

from .lattice import BLOCK, CHUNK, Lattice
from .sparse import Chunk


def dense(ch: Chunk) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The chunk's samples as one array cropped to its active blocks: skipped blocks hold the
    (sign-correct) value at their centre. Returns (volume, mask of sampled points, offset in
    samples of the crop within the chunk)."""
    b0, b1 = ch.active.min(0), ch.active.max(0) + 1
    nb = b1 - b0
    coarse = np.pad(ch.coarse[b0[0]:b1[0], b0[1]:b1[1], b0[2]:b1[2]], ((0, 1),) * 3, mode="edge")
    B = BLOCK
    vol = np.empty(tuple((nb + 1) * B), np.float32)
    mask = np.zeros(vol.shape, bool)
    v6 = vol.reshape(nb[0] + 1, B, nb[1] + 1, B, nb[2] + 1, B)
    m6 = mask.reshape(v6.shape)
    v6[...] = coarse[:, None, :, None, :, None]
    a = (ch.active - b0).T
    for d in np.ndindex(2, 2, 2):  # block interiors, then far faces, edges and corner
        src = ch.fine[(slice(None), *[B if x else slice(0, B) for x in d])]
        dst = (a[0] + d[0], 0 if d[0] else slice(None), a[1] + d[1], 0 if d[1] else slice(None),
               a[2] + d[2], 0 if d[2] else slice(None))
        v6[dst] = src
        m6[dst] = True
    n = nb * B + 1
    return (np.ascontiguousarray(vol[:n[0], :n[1], :n[2]]), np.ascontiguousarray(mask[:n[0], :n[1], :n[2]]),
            b0 * B)


def edge_keys(v: np.ndarray, offset: np.ndarray, samples: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """int64 key of the lattice edge holding each vertex (local coords ``v`` + ``offset``), and
    whether that edge lies in a chunk's boundary plane (only those can be found twice)."""
    frac = np.abs(v - np.round(v))
    axis = np.argmax(frac, axis=1)
    base = np.round(v).astype(np.int64)
    rows = np.arange(len(v))
    base[rows, axis] = np.floor(v[rows, axis]).astype(np.int64)
    g = base + offset
    seam = ((g % (CHUNK * BLOCK)) == 0) & (np.arange(3)[None, :] != axis[:, None])
    return ((axis * samples[0] + g[:, 0]) * samples[1] + g[:, 1]) * samples[2] + g[:, 2], seam.any(axis=1)


def separate(vol: np.ndarray, step: float) -> None:
    """Move samples off the level (|f| >= 1e-3 step) so every vertex is strictly inside an edge."""
    tiny = np.float32(1e-3 * step)
    near = np.abs(vol) < tiny
    vol[near] = np.where(vol[near] < 0, -tiny, tiny)


def march(chunks, lat: Lattice) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # noqa: ANN001
    """(vertices (N, 3) world, triangles (M, 3) outward-wound (as scikit-image winds them at
    level 0 of a field negative inside), edge keys (N,))."""
    from .deps import require
    marching_cubes = require("skimage.measure").marching_cubes
    samples = np.asarray(lat.cells, np.int64) + 1
    verts, faces, keys, seams = [], [], [], []
    n = 0
    for ch in chunks:
        vol, mask, off = dense(ch)
        separate(vol, lat.step)
        if min(vol.shape) < 2 or not ((vol < 0).any() and (vol > 0).any()):
            continue
        v, f, _, _ = marching_cubes(vol, 0.0, mask=mask, allow_degenerate=True)
        if len(f) == 0:
            continue
        gofs = np.asarray(ch.origin, np.int64) * BLOCK + off
        k, seam = edge_keys(v.astype(np.float64), gofs, samples)
        keys.append(k)
        seams.append(seam)
        verts.append(lat.start + (v.astype(np.float64) + gofs) * lat.step)
        faces.append(f.astype(np.int64) + n)
        n += len(v)
    if not verts:
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64), np.zeros(0, np.int64)
    k = np.concatenate(keys)
    V = np.concatenate(verts)
    F = np.concatenate(faces)
    # only vertices on edges in a chunk's boundary plane can appear twice: weld those
    seam = np.nonzero(np.concatenate(seams))[0]
    uk, first, inv = np.unique(k[seam], return_index=True, return_inverse=True)
    target = np.arange(len(k))
    target[seam] = seam[first][inv]
    keep = np.zeros(len(k), bool)
    keep[target] = True
    remap = np.cumsum(keep) - 1
    return V[keep], remap[target][F], k[keep]

