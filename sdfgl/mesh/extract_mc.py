"""Marching cubes over the crossing cells only, table-driven and vectorised, chunk by chunk.

The triangles of each of the 256 cases come from sdfgl.mesh.cells (each surface piece of a
cell a polygon over its crossing edges, ambiguous faces split the same way from both sides),
so the mesh is closed and manifold; a vertex is the linear-interpolation crossing of its
lattice edge, shared by every cell around that edge. The cost follows the number of
crossing cells (the surface), not the volume of the lattice.

Every crossing edge belongs to the cell at its lower end (it is that cell's edge 0, 4 or 8,
and that cell crosses too), so a chunk numbers its vertices cell by cell and finds the
vertex of any cell edge through a dense chunk-sized table of vertex numbers: no sort, no search.
Only edges owned by a cell of the next chunk (the chunk's upper faces) are matched by key,
against the vertices the other chunks hold on their lower faces. Chunks are analysed on a
worker thread while the GPU samples the next ones (sdfgl.mesh.sparse.analysed).
"""
from __future__ import annotations

import threading
from dataclasses import dataclass

import numpy as np

from .cells import EDGE_AXIS, EDGE_OFFSET, TRIANGLES
from .crossings import separate
from .lattice import BLOCK, CHUNK, Lattice
from .sparse import analysed

WORKERS = 2            # threads extracting chunks while the GPU samples the next ones
_CELLS = CHUNK * BLOCK  # cells per chunk side
_S = _CELLS + 1         # side of a chunk's vertex table: one layer more, always empty (next chunk)
# the vertices a cell owns: its crossing edges among edges 0, 4, 8 (from corner 0 along x, y, z)
_OWNS = ((np.arange(256)[:, None] ^ np.arange(256)[:, None] >> np.array([1, 2, 4])) & 1).astype(bool)
# a chunk's vertex table has entry 3 * cell + axis (cell = (x * _S + y) * _S + z, chunk-local) for
# the vertex on that cell's edge along axis; edge e of a cell is at this offset from 3 * cell
_EDGE_STEP = (3 * (EDGE_OFFSET @ np.array([_S * _S, _S, 1])) + EDGE_AXIS).astype(np.int32)
_STEP_EDGE = np.zeros(_EDGE_STEP.max() + 1, np.intp)
_STEP_EDGE[_EDGE_STEP] = np.arange(12)
_TRI_COUNT = (TRIANGLES[:, :, 0] >= 0).sum(1).astype(np.int32)
# the triangles of all cases one after another, as table offsets; case c's start at _TRI_FIRST[c]
_TRI_FLAT = _EDGE_STEP[TRIANGLES[TRIANGLES[:, :, 0] >= 0]]
_TRI_FIRST = (np.cumsum(_TRI_COUNT) - _TRI_COUNT).astype(np.int32)


def _on_one_face() -> np.ndarray:
    """(256, T) True for table triangles whose three edges lie on one cell face: the only
    triangles the cell across that face can repeat."""
    out = np.zeros(TRIANGLES.shape[:2], bool)
    for c in range(256):
        for t, tri in enumerate(TRIANGLES[c]):
            if tri[0] < 0:
                continue
            common = np.ones((3, 2), bool)
            for e in tri:
                faces = np.zeros((3, 2), bool)
                for f in range(3):
                    if f != EDGE_AXIS[e]:
                        faces[f, EDGE_OFFSET[e][f]] = True
                common &= faces
            out[c, t] = common.any()
    return out


ON_FACE = _on_one_face()
_HAS_ON_FACE = ON_FACE.any(1)


@dataclass
class Part:
    """One chunk's share: its vertices, triangles (chunk-local vertex numbers; -1 where the
    vertex is another chunk's, found by ``ext_key``), which triangles could repeat a
    neighbour's, and the keys of its vertices on the chunk's lower faces."""

    verts: np.ndarray       # (n, 3) float64, world
    faces: np.ndarray       # (m * 3,) int32
    ext_at: np.ndarray      # positions in faces of other chunks' vertices
    ext_key: np.ndarray     # their edge keys
    seam_key: np.ndarray    # keys of this chunk's vertices other chunks may use
    seam_vid: np.ndarray    # and their chunk-local numbers
    maybe_repeat: np.ndarray  # triangle numbers that lie on a cell face


def edge_keys(cell: np.ndarray, axis: np.ndarray, cells: tuple[int, int, int]) -> np.ndarray:
    """int64 key of the lattice edge along ``axis`` from the lower corner of global ``cell`` (N, 3)."""
    c = cell.astype(np.int64)
    return ((c[:, 0] * cells[1] + c[:, 1]) * cells[2] + c[:, 2]) * 3 + axis


def _cases(inside: np.ndarray) -> np.ndarray:
    """(K, B, B, B) uint8 cube cases from (K, B+1, B+1, B+1) inside flags (uint8 0/1): bit
    x + 2y + 4z for the corner at offsets (x, y, z), gathered one axis at a time."""
    z = inside[..., :-1] | inside[..., 1:] << np.uint8(4)
    y = z[:, :, :-1] | z[:, :, 1:] << np.uint8(2)
    return y[:, :-1] | y[:, 1:] << np.uint8(1)


_TABLES: list[np.ndarray] = []  # spare vertex tables, all -1 (25 MB each; kept for the next mesh)
_TABLES_LOCK = threading.Lock()


def _take_table() -> np.ndarray:
    with _TABLES_LOCK:
        if _TABLES:
            return _TABLES.pop()
    return np.full(3 * _S ** 3, -1, np.int32)


def _give_table(table: np.ndarray) -> None:
    with _TABLES_LOCK:
        _TABLES.append(table)


def _cube_lookup(B: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For cell r of a B^3 cube (r = (i * B + j) * B + k): (i, j, k), the flat index of its
    lower sample in the cube's (B+1)^3 samples, and its offset in a chunk's vertex table."""
    ijk = np.argwhere(np.ones((B,) * 3, bool)).astype(np.int32)
    P = B + 1
    return ijk, (ijk @ np.array([P * P, P, 1])).astype(np.int32), (ijk @ np.array([_S * _S, _S, 1])).astype(np.int32)


_CUBES = {b: _cube_lookup(b) for b in (4, 8)}


def _chunk(ch, lat: Lattice) -> Part:  # noqa: ANN001
    B = ch.block
    f = ch.fine
    P = B + 1
    case = _cases((f < 0).view(np.uint8))
    flat = np.flatnonzero((case - np.uint8(1)) < 254).astype(np.int32)   # cases 1..254: crossing cells
    cc = case.reshape(-1)[flat]
    shift = (B ** 3).bit_length() - 1                                     # cubes are 4^3 or 8^3 cells
    kb, r = flat >> shift, flat & np.int32(B ** 3 - 1)
    ijk, sample_off, cell_off = _CUBES[B]
    active = ch.active.astype(np.int32)
    local = active[kb] + ijk[r]                                            # chunk-local cell
    cf = (active @ np.array([_S * _S, _S, 1], np.int32))[kb] + cell_off[r]  # its place in the table
    # vertices, numbered cell by cell in axis order: linear interpolation along each owned edge
    # (samples moved off the level first)
    vc, va = np.nonzero(_OWNS[cc])
    vc, va = vc.astype(np.int32), va.astype(np.int32)
    s0 = kb[vc] * P ** 3 + sample_off[r[vc]]
    ff = f.reshape(-1)
    v0, v1 = ff[s0], ff[s0 + np.array([P * P, P, 1], np.int32)[va]]
    h = lat.step
    separate(v0, h)
    separate(v1, h)
    origin = np.asarray(ch.origin, np.int64) * BLOCK
    lv = local[vc]
    verts = lv.astype(np.float64)
    verts += origin
    verts.reshape(-1)[np.arange(0, 3 * len(va), 3) + va] += v0 / (v0.astype(np.float64) - v1)
    verts *= h
    verts += lat.start
    # triangles: table edges -> entries of the chunk's vertex table
    cnt = _TRI_COUNT[cc]
    first = np.cumsum(cnt, dtype=np.int32) - cnt                           # first triangle of each cell
    ci = np.repeat(np.arange(len(cc), dtype=np.int32), cnt)
    row = (_TRI_FIRST[cc] - first)[ci] + np.arange(len(ci), dtype=np.int32)
    steps = _TRI_FLAT[row]                                                 # (M, 3) table offsets
    entry = 3 * cf[vc] + va
    table = _take_table()
    table[entry] = np.arange(len(entry), dtype=np.int32)
    steps += (3 * cf)[ci][:, None]
    faces = np.take(table, steps.reshape(-1))
    table[entry] = -1  # (a table an exception leaves dirty is not given back)
    _give_table(table)
    ext = np.flatnonzero(faces < 0)  # vertices a cell of the next chunk holds
    e_ext = _STEP_EDGE[steps.reshape(-1)[ext] - 3 * cf[ci[ext // 3]]]
    ext_key = edge_keys(origin + local[ci[ext // 3]] + EDGE_OFFSET[e_ext], EDGE_AXIS[e_ext], lat.cells)
    seam_vid = np.flatnonzero(lv[:, 0] * lv[:, 1] * lv[:, 2] == 0)  # vertices on the chunk's lower faces
    seam_key = edge_keys(origin + lv[seam_vid], va[seam_vid], lat.cells)
    cand = np.flatnonzero(_HAS_ON_FACE[cc])
    crow, slot = np.nonzero(ON_FACE[cc[cand]])
    repeat = first[cand[crow]] + slot
    return Part(verts, faces, ext, ext_key, seam_key, seam_vid.astype(np.int32), repeat)


def _merge(parts: list[Part]) -> tuple[np.ndarray, np.ndarray]:
    """Chunk shares -> one vertex array and (M, 3) int64 triangles, seams joined by key."""
    vstart = np.cumsum([0] + [len(p.verts) for p in parts])
    fstart = np.cumsum([0] + [len(p.faces) for p in parts])
    faces = np.empty(fstart[-1], np.int64)
    for p, v0, f0 in zip(parts, vstart, fstart):
        faces[f0:f0 + len(p.faces)] = p.faces + v0
    ext_at = np.concatenate([p.ext_at + f0 for p, f0 in zip(parts, fstart)])
    if len(ext_at):
        ext_key = np.concatenate([p.ext_key for p in parts])
        keys = np.concatenate([p.seam_key for p in parts])
        vid = np.concatenate([p.seam_vid + v0 for p, v0 in zip(parts, vstart)])
        order = np.argsort(keys)
        keys, vid = keys[order], vid[order]
        at = np.minimum(np.searchsorted(keys, ext_key), max(len(keys) - 1, 0))
        found = keys[at] == ext_key if len(keys) else np.zeros(len(ext_key), bool)
        faces[ext_at] = np.where(found, vid[at] if len(keys) else -1, -1)
    faces = faces.reshape(-1, 3)
    verts = np.concatenate([p.verts for p in parts])
    keep = _first_copies(faces, np.concatenate([p.maybe_repeat + f0 // 3 for p, f0 in zip(parts, fstart)]))
    if faces.min() < 0:  # an edge no chunk holds (the skip test failed): its triangles go
        keep &= (faces >= 0).all(1)
    return verts, faces if keep.all() else faces[keep]


def _first_copies(faces: np.ndarray, candidates: np.ndarray) -> np.ndarray:
    """False for each face that repeats an earlier one (same three vertices). Only triangles on
    a cell face can repeat (the cell across the face may draw the same one): only they are checked."""
    keep = np.ones(len(faces), bool)
    if len(candidates) > 1:
        _, first = np.unique(np.sort(faces[candidates], axis=1), axis=0, return_index=True)
        keep[candidates] = False
        keep[candidates[first]] = True
    return keep


def march(chunks, lat: Lattice) -> tuple[np.ndarray, np.ndarray]:  # noqa: ANN001
    """(vertices (N, 3) world, triangles (M, 3) int64, wound counter-clockwise seen from
    outside; no degenerate or repeated triangles, every vertex used unless a crossing edge
    lies in a block the skip test dropped, whose triangles are then left out)."""
    parts = [p for p in analysed(chunks, _chunk, lat, workers=WORKERS) if len(p.verts)]
    if not parts:
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64)
    return _merge(parts)
