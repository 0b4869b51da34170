"""Dual contouring (Ju et al. 2002), vectorised: sharp edges and corners from field gradients.

Every lattice edge whose ends differ in sign gives a crossing point (linear interpolation
of the samples, then Newton steps along the edge) and a normal (the GPU gradient there; a
crossing on a crease of the field gets its faces' normals instead, sdfgl.mesh.creases). Each
cell that touches crossing edges gets one vertex, the minimiser of the quadric sum((n_i . (x - p_i))^2), solved with
small singular values cut (so flat and edge cells fall back towards the crossings' mean,
as in Lindstrom's and Ju's treatment) and kept inside the cell. Each crossing edge gives
one quad over the four cells around it, wound so it faces increasing field. A cell that
two pieces of surface pass through gets one vertex per piece (sdfgl.mesh.cells), so the
mesh stays manifold where plain dual contouring pinches two sheets into one vertex.
"""
from __future__ import annotations

import numpy as np

from .cells import COMPONENT, edge_index
from .creases import planes
from .crossings import crossings
from .eigen3 import symmetric_eigen
from .lattice import BLOCK, Lattice
from .sample import GPUField

SVD_CUT = 0.03  # singular values below this share of the largest are dropped
# how far (cells) a vertex may leave its cell: the planes of a cell often meet at a corner or
# edge just beside it (clipped to the cell, 45 of 60 random boxes had a corner > 0.1 cell off)
REACH = 1.0
EPS = 0.02  # gradient stencils this share of a cell wide


def refine(field: GPUField, lat: Lattice, low: np.ndarray, axis: np.ndarray, t: np.ndarray, inside: np.ndarray,
           iterations: int = 6) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Crossing points put on the surface along their edges and the field gradient there.

    Linear interpolation is off where the field bends, as it does beside an edge or a corner of
    the solid; Newton steps along the edge fix that, kept inside the bracket that the signs
    seen so far allow (a step that would leave it bisects instead: inside a box near a corner
    the slope along the edge can be nearly zero). Points within ``1e-4`` cell stop early.
    Returns (t, gradient, bend of its stencil: see sdfgl.mesh.creases)."""
    h = lat.step
    unit = np.eye(3)[axis]
    lo, hi = np.zeros_like(t), np.ones_like(t)
    f, grad, bend = field.gradient_bend(lat.start + (low + unit * t[:, None]) * h, EPS * h)
    for _ in range(iterations):
        todo = np.nonzero(np.abs(f) > 1e-4 * h)[0]
        if len(todo) == 0:
            break
        tt, ff = t[todo], f[todo]
        beyond = (ff < 0) == inside[todo]  # same sign as the lower end: the root lies above
        lo[todo] = np.where(beyond, tt, lo[todo])
        hi[todo] = np.where(beyond, hi[todo], tt)
        slope = grad[todo, axis[todo]] * h
        newton = tt - ff / np.where(slope != 0, slope, 1.0)
        good = (slope != 0) & (newton > lo[todo]) & (newton < hi[todo])
        t[todo] = np.where(good, newton, (lo[todo] + hi[todo]) / 2)
        f[todo], grad[todo], bend[todo] = field.gradient_bend(
            lat.start + (low[todo] + unit[todo] * t[todo, None]) * h, EPS * h)
    return t, grad, bend


RING = np.array([(-1, -1), (0, -1), (0, 0), (-1, 0)])


def _quad_cells(low: np.ndarray, axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(E, 4, 3) cells around each edge, counter-clockwise seen from the +axis side, and the
    edge's index within each of them (E, 4)."""
    out = np.repeat(low[:, None, :], 4, axis=1)
    for a in range(3):
        sel = axis == a
        b, c = (a + 1) % 3, (a + 2) % 3
        out[sel, :, b] += RING[:, 0]
        out[sel, :, c] += RING[:, 1]
    local = np.array([[edge_index(a, -r[0], -r[1]) for r in RING] for a in range(3)])
    return out, local[axis]


def _solve(ata: np.ndarray, atb: np.ndarray, mass: np.ndarray) -> np.ndarray:
    """Minimiser of x^T A x - 2 b^T x nearest the mass point, small singular values cut.
    A is symmetric positive semi-definite, so its singular values are the magnitudes of its
    eigenvalues and its singular vectors its eigenvectors: a symmetric eigensolver gives the
    same pseudo-inverse as an SVD (sdfgl.mesh.eigen3: all cells' matrices at once)."""
    s, v = symmetric_eigen(ata)                    # eigenvalues, eigenvectors in columns
    s = np.abs(s)
    inv = np.where(s > SVD_CUT * s.max(axis=1, keepdims=True), 1.0 / np.where(s > 0, s, 1.0), 0.0)
    rhs = atb - np.einsum("nij,nj->ni", ata, mass)
    y = np.einsum("nji,nj->ni", v, rhs) * inv      # V^T rhs, scaled
    return mass + np.einsum("nij,nj->ni", v, y)


def dual_contour(chunks, lat: Lattice, field: GPUField) -> tuple[np.ndarray, np.ndarray]:  # noqa: ANN001
    """(vertices (N, 3) world, triangles (M, 3) outward-wound)."""
    found = crossings(chunks, lat)
    if found is None:
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64)
    low, axis, t, inside, cell_keys, cell_cases, _ = found
    h = lat.step
    t, grad, bend = refine(field, lat, low, axis, t, inside)
    points = lat.start + (low + np.eye(3)[axis] * t[:, None]) * h
    owner, n, w = planes(field, points, grad, bend, EPS * h)
    cells, local_edge = _quad_cells(low, axis)           # (E, 4, 3), (E, 4)
    nc = np.asarray(lat.cells, np.int64)
    keys = (cells[..., 0] * nc[1] + cells[..., 1]) * nc[2] + cells[..., 2]
    case = cell_cases[np.minimum(np.searchsorted(cell_keys, keys), len(cell_keys) - 1)]
    piece = COMPONENT[case, local_edge].astype(np.int64)  # which surface piece of the cell
    uk, inv = np.unique(keys * 4 + piece, return_inverse=True)
    inv = inv.reshape(-1, 4)
    uk //= 4
    # quadric of each vertex, accumulated over its crossing edges (in cell units about the cell corner)
    cell_lo = np.stack([uk // (nc[1] * nc[2]), (uk // nc[2]) % nc[1], uk % nc[2]], 1)
    idx = inv[owner].ravel()
    local = (np.repeat((low + np.eye(3)[axis] * t[:, None])[owner], 4, axis=0) - cell_lo[idx])
    nn = np.repeat(n, 4, axis=0)
    w = np.repeat(w, 4)
    m = len(uk)
    ata = np.empty((m, 3, 3))
    for i in range(3):
        for j in range(i, 3):
            ata[:, i, j] = ata[:, j, i] = np.bincount(idx, w * nn[:, i] * nn[:, j], m)
    d = np.einsum("ij,ij->i", nn, local) * w
    atb = np.stack([np.bincount(idx, nn[:, i] * d, m) for i in range(3)], 1)
    first = slice(0, 4 * len(t))  # the crossings' own rows, one each: the mass point
    cnt = np.bincount(idx[first], minlength=m)[:, None]
    mass = np.stack([np.bincount(idx[first], local[first, i], m) for i in range(3)], 1) / cnt
    x = np.clip(_solve(ata, atb, mass), -REACH, 1.0 + REACH)
    verts = lat.start + (cell_lo + x) * h
    quads = np.where(inside[:, None], inv, inv[:, ::-1])
    extra, polygons, plain = unpinch(quads, len(verts), low, axis, inside, points)
    verts = np.concatenate([verts, extra])
    return verts, np.concatenate([split_quads(verts, quads[plain]), polygons])


def unpinch(quads: np.ndarray, n: int, low: np.ndarray, axis: np.ndarray, inside: np.ndarray,
            points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Keep the mesh manifold where two cells share an ambiguous face and each holds one piece
    through both of its segments: the two vertices are then joined by one dual edge per
    segment, i.e. four quads on one edge. Each segment gets its own vertex on the face (the
    mean of its two crossings, put on the surface later), inserted into the two quads of
    that segment, which become pentagons (fanned from the new vertex). Returns (new vertices
    (K, 3), numbered from ``n``, the triangles of the changed quads, mask of the quads left as
    they were). ``quads[i]`` is the dual polygon of crossing edge i (lower end ``low[i]`` on ``axis[i]``)."""
    a, b = quads, np.roll(quads, -1, axis=1)
    key = np.minimum(a, b) * n + np.maximum(a, b)                       # (E, 4) undirected sides
    plain = np.ones(len(quads), bool)
    ranked = np.sort(key.ravel())
    if not np.any(ranked[2:] == ranked[:-2]):  # the usual case, found by a sort: no side on three quads
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64), plain
    uk, inv, counts = np.unique(key.ravel(), return_inverse=True, return_counts=True)
    over = np.nonzero(counts[inv] > 2)[0]
    q, side = over // 4, over % 4
    # a segment joins the two crossing edges of the face that meet at an outside corner
    end = low[q] + np.eye(3, dtype=np.int64)[axis[q]] * inside[q][:, None]  # the outside end
    group = np.unique(np.column_stack([inv[over], end]), axis=0, return_inverse=True)[1].ravel()
    order = np.argsort(group, kind="stable")
    if np.any(np.bincount(group) != 2):
        raise AssertionError("dual contouring: an over-used edge whose segments do not pair up")
    first, second = order[0::2], order[1::2]
    extra = (points[q[first]] + points[q[second]]) / 2
    inserted: dict[int, list[tuple[int, int]]] = {}
    for k, (i, j) in enumerate(zip(first, second)):
        for m in (i, j):
            inserted.setdefault(int(q[m]), []).append((int(side[m]), n + k))
    tris = []
    for quad, sides in inserted.items():
        plain[quad] = False
        ring: list[int] = []
        for s in range(4):
            ring.append(int(quads[quad, s]))
            ring += [v for s2, v in sides if s2 == s]
        start = ring.index(sides[0][1])
        ring = ring[start:] + ring[:start]
        tris += [(ring[0], ring[i], ring[i + 1]) for i in range(1, len(ring) - 1)]
    return extra, np.array(tris, np.int64).reshape(-1, 3), plain


def split_quads(verts: np.ndarray, quads: np.ndarray) -> np.ndarray:
    """Two triangles per quad, along the diagonal whose triangles agree best in direction.
    Coordinates are gathered as rows (x, y, z), each contiguous: products of whole rows are
    several times faster than np.cross on (N, 3) arrays."""
    xyz = np.ascontiguousarray(np.asarray(verts, np.float64).T)
    q = [xyz[:, quads[:, i]] for i in range(4)]

    def cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
        return np.stack([u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]])

    def agreement(a, b, c, d):  # noqa: ANN001, ANN202 - triangles (a, b, c) and (a, c, d)
        n1 = cross(b - a, c - a)
        n2 = cross(c - a, d - a)
        dot = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2]
        size = np.sqrt(n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]) * np.sqrt(n2[0] * n2[0] + n2[1] * n2[1] + n2[2] * n2[2])
        return dot / np.maximum(size, 1e-300)

    first = agreement(q[0], q[1], q[2], q[3]) >= agreement(q[1], q[2], q[3], q[0])
    t1 = np.where(first[:, None], quads[:, [0, 1, 2]], quads[:, [1, 2, 3]])
    t2 = np.where(first[:, None], quads[:, [0, 2, 3]], quads[:, [1, 3, 0]])
    return np.concatenate([t1, t2])
