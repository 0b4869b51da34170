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
    acc = np.zeros((len(vertices), 3))
    for k in range(3):
        np.add.at(acc, faces[:, k], angle[:, k, None] * face)
    vertex = _unit(acc)[faces]
    # edge: the sum of its two faces' normals
    pairs = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    _, inverse = np.unique(pairs, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    eacc = np.zeros((inverse.max() + 1, 3))
    np.add.at(eacc, inverse, np.repeat(face, 3, axis=0))
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


def _box(tlo: np.ndarray, thi: np.ndarray, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return tlo[idx].min(axis=0), thi[idx].max(axis=0)


def _build(tlo: np.ndarray, thi: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """(triangle order, node texels (m * 4, 4), depth) of the hierarchy over boxes (lo, hi)."""
    n = len(tlo)
    cen = 0.5 * (tlo + thi)
    order = np.arange(n)
    nodes: list[np.ndarray] = [np.zeros((4, 4))]
    stack = [(0, 0, n, 1)]  # (node, start, end, depth)
    depth = 1
    while stack:
        node, s, e, d = stack.pop()
        depth = max(depth, d)
        idx = order[s:e]  # two or more triangles (a closed mesh has four or more)
        axis = int(np.argmax(np.ptp(cen[idx], axis=0)))
        mid = (s + e) // 2
        order[s:e] = idx[np.argpartition(cen[idx, axis], mid - s)]
        rec = nodes[node]
        for j, (a, b) in enumerate([(s, mid), (mid, e)]):
            lo, hi = _box(tlo, thi, order[a:b])
            rec[2 * j, :3], rec[2 * j + 1, :3] = lo, hi
            if b - a <= LEAF_SIZE:
                code = -(a * 8 + (b - a))
            else:
                code = len(nodes)
                nodes.append(np.zeros((4, 4)))
                stack.append((code, a, b, d + 1))
            rec[j, 3] = code
    return order, np.concatenate(nodes), depth


def build(vertices: np.ndarray, faces: np.ndarray) -> TriangleBVH:
    """The hierarchy and tables of a closed mesh (float64 vertices (v, 3), int faces (n, 3))."""
    return TriangleBVH(vertices, faces)
