"""Which crossing edges of a lattice cell belong to one piece of surface (one dual vertex).

Corner c of a cell is at offset (c & 1, c >> 1 & 1, c >> 2 & 1); the case of a cell has bit
c set where corner c is inside (f < 0). Edge 4 * a + o1 + 2 * o2 runs along axis a from the
corner at offsets o1, o2 on the next two axes ((a + 1) % 3, (a + 2) % 3). On each face,
crossing edges are joined in pairs: the two of a face with two, and on an ambiguous face
(four, signs alternating) the two around each outside corner. The rule reads only the
face's own corners, so both cells that share a face join its edges alike: every dual
edge then lies on exactly two quads (a manifold mesh, where one vertex per cell is not).
"""
from __future__ import annotations

import numpy as np


def edge_index(axis: int, o1: int, o2: int) -> int:
    return 4 * axis + o1 + 2 * o2


def _corner(axis: int, along: int, o1: int, o2: int) -> int:
    off = [0, 0, 0]
    off[axis], off[(axis + 1) % 3], off[(axis + 2) % 3] = along, o1, o2
    return off[0] + 2 * off[1] + 4 * off[2]


def _components(case: int) -> list[int]:
    inside = [(case >> c) & 1 for c in range(8)]
    crossing = [inside[_corner(e // 4, 0, e % 2, e // 2 % 2)] != inside[_corner(e // 4, 1, e % 2, e // 2 % 2)]
                for e in range(12)]
    parent = list(range(12))

    def find(x: int) -> int:
        while parent[x] != x:
            x = parent[x]
        return x
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
                parent[find(cross[0])] = find(cross[1])
            elif len(cross) == 4:
                for k in range(4):
                    if not inside[corners[k]]:  # outside corner k lies between edges k - 1 and k
                        parent[find(edges[k - 1])] = find(edges[k])
    roots: dict[int, int] = {}
    out = []
    for e in range(12):
        out.append(roots.setdefault(find(e), len(roots)) if crossing[e] else -1)
    return out


COMPONENT = np.array([_components(case) for case in range(256)], dtype=np.int8)  # (256, 12)
