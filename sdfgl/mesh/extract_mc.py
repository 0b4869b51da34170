"""Marching cubes over the crossing cells only, table-driven and vectorised.

The triangles of each of the 256 cases come from sdfgl.mesh.cells (each surface piece of a
cell a polygon over its crossing edges, ambiguous faces split the same way from both sides),
so the mesh is closed and manifold; a vertex is the linear-interpolation crossing of its
lattice edge, shared by every cell around that edge. The cost follows the number of
crossing cells (the surface), not the volume of the lattice.
"""
from __future__ import annotations

import numpy as np

from .cells import EDGE_AXIS, EDGE_OFFSET, TRIANGLES
from .crossings import crossings
from .lattice import Lattice

BATCH = 1 << 18  # crossing cells per batch


def march(chunks, lat: Lattice) -> tuple[np.ndarray, np.ndarray]:  # noqa: ANN001
    """(vertices (N, 3) world, triangles (M, 3) wound counter-clockwise seen from outside)."""
    found = crossings(chunks, lat)
    if found is None:
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64)
    low, axis, t, _, _, cell_cases, cell_lo = found
    ns = np.asarray(lat.cells, np.int64) + 1   # samples per axis
    ekey = ((axis.astype(np.int64) * ns[0] + low[:, 0]) * ns[1] + low[:, 1]) * ns[2] + low[:, 2]
    order = np.argsort(ekey)
    ekey = ekey[order]
    # an edge's key is linear in its lower sample: the cell's key plus a per-edge offset
    base = (cell_lo[:, 0] * ns[1] + cell_lo[:, 1]) * ns[2] + cell_lo[:, 2]
    offset = EDGE_AXIS * int(np.prod(ns)) + (EDGE_OFFSET[:, 0] * ns[1] + EDGE_OFFSET[:, 1]) * ns[2] + EDGE_OFFSET[:, 2]
    faces = []
    for s in range(0, len(cell_cases), BATCH):  # in batches: bounded temporaries
        tri = TRIANGLES[cell_cases[s:s + BATCH]]          # (C, T, 3) local edges
        cell_idx, slot = np.nonzero(tri[:, :, 0] >= 0)
        key = base[s + cell_idx][:, None] + offset[tri[cell_idx, slot]]
        faces.append(order[np.searchsorted(ekey, key)])
    faces = np.concatenate(faces)
    verts = lat.start + (low + np.eye(3)[axis] * t[:, None]) * lat.step
    return verts, faces
