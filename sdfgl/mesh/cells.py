"""Which crossing edges of a lattice cell belong to one piece of surface (one dual vertex),
and the triangles of each piece for marching cubes.

Corner c of a cell is at offset (c & 1, c >> 1 & 1, c >> 2 & 1); the case of a cell has bit
c set where corner c is inside (f < 0). Edge 4 * a + o1 + 2 * o2 runs along axis a from the
corner at offsets o1, o2 on the next two axes ((a + 1) % 3, (a + 2) % 3). On each face,
crossing edges are joined in pairs: the two of a face with two, and on an ambiguous face
(four, signs alternating) the two around each outside corner. The rule reads only the
face's own corners, so both cells that share a face join its edges alike: every dual
edge then lies on exactly two quads (a manifold mesh, where one vertex per cell is not).
For marching cubes the same joins order each piece's edges into a polygon; a fan of it,
wound to face the outside corners, gives the cell's triangles, and the segments two cells
draw on their shared face are the same, so the surface closes.
"""
from __future__ import annotations

import numpy as np


def edge_index(axis: int, o1: int, o2: int) -> int:
    return 4 * axis + o1 + 2 * o2


def _corner(axis: int, along: int, o1: int, o2: int) -> int:
    off = [0, 0, 0]
    off[axis], off[(axis + 1) % 3], off[(axis + 2) % 3] = along, o1, o2
    return off[0] + 2 * off[1] + 4 * off[2]


def _edge_geometry(e: int) -> tuple[np.ndarray, np.ndarray]:
    """Midpoint of cell edge ``e`` and the unit vector along it (in cell units)."""
    a = e // 4
    mid = np.zeros(3)
    mid[a], mid[(a + 1) % 3], mid[(a + 2) % 3] = 0.5, e % 2, e // 2 % 2
    return mid, np.eye(3)[a]


def _analyse(case: int) -> tuple[list[int], list[list[int]]]:
    """(component of each edge or -1, the triangles (local edges) of the case, outward)."""
    inside = [(case >> c) & 1 for c in range(8)]
    crossing = [inside[_corner(e // 4, 0, e % 2, e // 2 % 2)] != inside[_corner(e // 4, 1, e % 2, e // 2 % 2)]
                for e in range(12)]
    parent = list(range(12))
    links: dict[int, list[int]] = {e: [] for e in range(12)}

    def find(x: int) -> int:
        while parent[x] != x:
            x = parent[x]
        return x

    def join(x: int, y: int) -> None:
        parent[find(x)] = find(y)
        links[x].append(y)
        links[y].append(x)
    for f in range(3):          # face normal axis
        for s in range(2):      # side
            # corners of the face in cyclic order, and the edge between corner k and k + 1
            b, c = (f + 1) % 3, (f + 2) % 3
            ring = [(0, 0), (1, 0), (1, 1), (0, 1)]
            corners, edges = [], []
            for k, (u, v) in enumerate(ring):
                off = [0, 0, 0]
                off[f], off[b], off[c] = s, u, v
                corners.append(off[0] + 2 * off[1] + 4 * off[2])
                u2, v2 = ring[(k + 1) % 4]
                a = b if v == v2 else c  # axis of the edge from ring[k] to ring[k + 1]
                lo = [0, 0, 0]
                lo[f], lo[b], lo[c] = s, min(u, u2), min(v, v2)
                edges.append(edge_index(a, lo[(a + 1) % 3], lo[(a + 2) % 3]))
            cross = [e for e in edges if crossing[e]]
            if len(cross) == 2:
                join(cross[0], cross[1])
            elif len(cross) == 4:
                for k in range(4):
                    if not inside[corners[k]]:  # outside corner k lies between edges k - 1 and k
                        join(edges[k - 1], edges[k])
    roots: dict[int, int] = {}
    comp = [roots.setdefault(find(e), len(roots)) if crossing[e] else -1 for e in range(12)]
    triangles: list[list[int]] = []
    for r in range(len(roots)):
        start = comp.index(r)
        loop, prev, cur = [start], -1, start
        while True:  # every edge of a piece has two joins: walk the cycle
            nxt = links[cur][0] if links[cur][0] != prev else links[cur][1]
            if nxt == start:
                break
            loop.append(nxt)
            prev, cur = cur, nxt
        pts = [_edge_geometry(e)[0] for e in loop]
        normal = sum(np.cross(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts)))
        # outward: from the inside end of each crossing edge to its outside end
        out = sum(_edge_geometry(e)[1] * (1 if inside[_corner(e // 4, 0, e % 2, e // 2 % 2)] else -1) for e in loop)
        if np.dot(normal, out) < 0:
            loop.reverse()
        triangles += [[loop[0], loop[i], loop[i + 1]] for i in range(1, len(loop) - 1)]
    return comp, triangles


_CASES = [_analyse(case) for case in range(256)]
COMPONENT = np.array([c for c, _ in _CASES], dtype=np.int8)  # (256, 12): piece of each edge, -1: none
MAX_TRIANGLES = max(len(t) for _, t in _CASES)
TRIANGLES = np.full((256, MAX_TRIANGLES, 3), -1, dtype=np.int8)  # local edges, outward wound
for _case, (_, _tris) in enumerate(_CASES):
    if _tris:
        TRIANGLES[_case, :len(_tris)] = _tris
# lattice offset of each cell edge's lower end, and its axis
EDGE_OFFSET = np.array([[(1 if ax == (e // 4 + 1) % 3 else 0) * (e % 2) + (1 if ax == (e // 4 + 2) % 3 else 0) * (e // 2 % 2)
                         for ax in range(3)] for e in range(12)], dtype=np.int64)
EDGE_AXIS = np.array([e // 4 for e in range(12)], dtype=np.int64)
