"""The lattice edges the surface crosses, found block by block from the sparse samples.

Both extractors start here: marching cubes puts its vertices on these edges, dual
contouring puts one inside each surface piece of the cells around them. Each edge is found
once, in the block that holds its lower end (blocks share their faces' samples, and equal
samples give equal signs, so the cells on both sides agree).
"""
from __future__ import annotations

import numpy as np

from .lattice import Lattice
from .sparse import analysed


def separate(vol: np.ndarray, step: float) -> None:
    """Move samples off the level (|f| >= 1e-3 step) so every crossing is strictly inside an edge."""
    tiny = np.float32(1e-3 * step)
    near = np.abs(vol) < tiny
    vol[near] = np.where(vol[near] < 0, -tiny, tiny)


def _chunk(ch, lat: Lattice) -> tuple[np.ndarray, ...]:  # noqa: ANN001
    """One chunk's crossing edges (lower sample, axis, t, lower end inside) and crossing cells
    (lower corner, case)."""
    B = ch.block
    f = ch.fine.copy()
    separate(f, lat.step)
    base = ch.base  # (K, 3) lower sample of each cube
    inside = (f < 0).view(np.uint8)
    case = np.zeros((len(f), B, B, B), np.uint8)
    for c in range(8):
        x, y, z = c & 1, c >> 1 & 1, c >> 2 & 1
        case |= inside[:, x:x + B, y:y + B, z:z + B] << np.uint8(c)
    kb, i, j, k = np.nonzero((case != 0) & (case != 255))
    cells, cases = base[kb] + np.stack([i, j, k], 1), case[kb, i, j, k]
    lows, axes, ts, ins = [], [], [], []
    lo_in = inside[:, :B, :B, :B]
    for a, hi in enumerate((f[:, 1:, :B, :B], f[:, :B, 1:, :B], f[:, :B, :B, 1:])):
        m = lo_in != (hi < 0)
        kb, i, j, k = np.nonzero(m)
        v0, v1 = f[:, :B, :B, :B][m].astype(np.float64), hi[m].astype(np.float64)
        lows.append(base[kb] + np.stack([i, j, k], 1))
        axes.append(np.full(len(kb), a, np.int8))
        ts.append(v0 / (v0 - v1))
        ins.append(v0 < 0)
    return (np.concatenate(lows), np.concatenate(axes), np.concatenate(ts), np.concatenate(ins), cells, cases)


def crossings(chunks, lat: Lattice):  # noqa: ANN001, ANN201
    """All crossing edges, each once: (lower sample (E, 3) int64, axis (E,), t in (0, 1),
    lower end inside (E,) bool), and the cells they touch, sorted by key: (keys, cases
    (0..255), lower corners (C, 3)). Chunks are analysed on a worker thread while the GPU
    samples the next ones (sdfgl.mesh.sparse.analysed)."""
    parts = [p for p in analysed(chunks, _chunk, lat, workers=2) if len(p[0])]
    if not parts:
        return None
    low, axis, t, ins, g, cs = (np.concatenate(x) for x in zip(*parts))
    nc = np.asarray(lat.cells, np.int64)
    ck = (g[:, 0] * nc[1] + g[:, 1]) * nc[2] + g[:, 2]
    order = np.argsort(ck)
    return low, axis, t, ins, ck[order], cs[order], g[order]
