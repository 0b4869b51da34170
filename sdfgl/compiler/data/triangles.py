"""A closed triangle mesh as data: its triangles in a bounding volume hierarchy.

The shader (shaders/lib/sd_mesh_bvh.glsl) walks the hierarchy nearest box first and skips
every box farther than the closest triangle met so far, so a point costs about
log2(triangles) boxes and a few triangles. Two tables go to the data texture:

- nodes, 4 texels each: (lo_a, child_a), (hi_a, child_b), (lo_b, 0), (hi_b, 0), the boxes
  of the node's two children; a child code k >= 0 is node k, k < 0 a leaf of the
  ``-k & 7`` triangles from ``-k >> 3``;
- triangles (in leaf order), TRIANGLE_TEXELS each: vertices a, b, c with the unit face
  normal in their w components, then the pseudonormals of edges ab, bc, ca and of
  vertices a, b, c (Baerentzen and Aanaes: angle-weighted at the vertices, the two faces'
  sum at an edge), the sign's normal at whichever feature holds the closest point.
"""
from __future__ import annotations

import numpy as np

LEAF_SIZE = 4            # triangles in a leaf, at most (the code keeps 3 bits for it)
TRIANGLE_TEXELS = 9      # texels of a triangle record
STACK_DEPTH = 32         # the shader's traversal stack: the tree is balanced, ~log2(n / LEAF_SIZE) deep


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.divide(v, n, out=np.zeros_like(v), where=n > 0)


def _sum_by(index: np.ndarray, values: np.ndarray, size: int) -> np.ndarray:
    """(size, 3): the sum of the rows of ``values`` with each index."""
    return np.stack([np.bincount(index, values[:, k], minlength=size) for k in range(3)], axis=1)


def pseudonormals(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(face (n, 3), edge (n, 3, 3) for ab, bc, ca, vertex (n, 3, 3) for a, b, c) unit
    pseudonormals of a closed mesh, per face."""
    tri = vertices[faces]
    face = _unit(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]))
    # vertex: angle-weighted sum of the incident faces' normals
    angle = np.zeros(faces.shape)
    for k in range(3):
        e1 = _unit(tri[:, (k + 1) % 3] - tri[:, k])
        e2 = _unit(tri[:, (k + 2) % 3] - tri[:, k])
        angle[:, k] = np.arccos(np.clip((e1 * e2).sum(-1), -1.0, 1.0))
    weighted = angle[:, :, None] * face[:, None, :]  # (n, corner, xyz)
    acc = _sum_by(faces.reshape(-1), weighted.reshape(-1, 3), len(vertices))
    vertex = _unit(acc)[faces]
    # edge: the sum of its two faces' normals
    a, b = faces[:, [0, 1, 2]].reshape(-1), faces[:, [1, 2, 0]].reshape(-1)
    key = np.minimum(a, b).astype(np.int64) * len(vertices) + np.maximum(a, b)
    _, inverse = np.unique(key, return_inverse=True)
    eacc = _sum_by(inverse, np.repeat(face, 3, axis=0), int(inverse.max()) + 1)
    edge = _unit(eacc)[inverse].reshape(-1, 3, 3)
    return face, edge, vertex


class TriangleBVH:
    """A balanced hierarchy (median splits on the longest axis) over a mesh's triangles."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray) -> None:
        tri = vertices[faces]
        face, edge, vertex = pseudonormals(vertices, faces)
        area2 = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=-1)
        # a zero-area triangle lies on its neighbours' edges: the distance does not change without it
        keep = np.flatnonzero(area2 > 0)
        tlo, thi = tri[keep].min(axis=1), tri[keep].max(axis=1)
        order, self.nodes, self.depth = _build(tlo, thi)
        if self.depth >= STACK_DEPTH:  # a walk holds at most one entry a level, plus one
            raise ValueError(f"triangle hierarchy of depth {self.depth} does not fit the shader's stack")
        sel = keep[order]
        rec = np.zeros((len(sel), TRIANGLE_TEXELS, 4))
        rec[:, 0:3, :3] = tri[sel]
        rec[:, 0:3, 3] = face[sel]
        rec[:, 3:6, :3] = edge[sel]
        rec[:, 6:9, :3] = vertex[sel]
        self.triangles = rec.reshape(-1, 4)
        self.count = len(sel)


def _ranges(start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """The positions start[i] .. end[i] - 1 of every range, concatenated."""
    size = end - start
    return np.repeat(start - np.concatenate([[0], np.cumsum(size)[:-1]]), size) + np.arange(size.sum())


def _build(tlo: np.ndarray, thi: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """(triangle order, node texels (m * 4, 4), depth) of the hierarchy over boxes (lo, hi),
    built a level at a time: every node of a level is split at once (numpy, no per-node loop)."""
    cen = 0.5 * (tlo + thi)
    order = np.arange(len(tlo))
    nodes: list[np.ndarray] = []  # per level, the records of its nodes (ids run on from level to level)
    ids, start, end = np.array([0]), np.array([0]), np.array([len(tlo)])  # two or more triangles each
    count, depth = 1, 0
    while len(ids):
        depth += 1
        pos = _ranges(start, end)
        offsets = np.concatenate([[0], np.cumsum(end - start)[:-1]])
        c = cen[order[pos]]
        axis = np.argmax(np.maximum.reduceat(c, offsets) - np.minimum.reduceat(c, offsets), axis=1)
        seg = np.repeat(np.arange(len(ids)), end - start)
        perm = np.lexsort((c[np.arange(len(pos)), axis[seg]], seg))  # each range sorted on its longest axis
        order[pos] = order[pos[perm]]
        mid = (start + end) // 2
        lo_a, hi_a = np.stack([start, mid], 1), np.stack([mid, end], 1)  # (node, child) ranges
        sub = np.stack([offsets, offsets + mid - start], 1).ravel()  # where each child starts in pos
        blo = np.minimum.reduceat(tlo[order[pos]], sub)
        bhi = np.maximum.reduceat(thi[order[pos]], sub)
        size = (hi_a - lo_a).ravel()
        inner = size > LEAF_SIZE
        code = -(lo_a.ravel() * 8 + size)
        code[inner] = count + np.arange(int(inner.sum()))
        rec = np.zeros((len(ids), 4, 4))
        rec[:, 0, :3], rec[:, 1, :3] = blo[0::2], bhi[0::2]
        rec[:, 2, :3], rec[:, 3, :3] = blo[1::2], bhi[1::2]
        rec[:, 0, 3], rec[:, 1, 3] = code[0::2], code[1::2]
        nodes.append(rec)
        ids = code[inner]
        start, end = lo_a.ravel()[inner], hi_a.ravel()[inner]
        count += len(ids)
    return order, np.concatenate(nodes).reshape(-1, 4), depth


def build(vertices: np.ndarray, faces: np.ndarray) -> TriangleBVH:
    """The hierarchy and tables of a closed mesh (float64 vertices (v, 3), int faces (n, 3))."""
    return TriangleBVH(vertices, faces)
