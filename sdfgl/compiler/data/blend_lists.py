"""The cell lists of a smooth union kept as data: the left fold pruned exactly, per cell.

A smooth union folds its children in order, acc = smin(acc, d_i). Each blend has a
*support* R (``BLEND_SUPPORT``: k for the quadratic and the chamfer, k / (1 - sqrt(1/2))
for the circular one): where |a - b| >= R, smin(a, b) is min(a, b) exactly (h = 0), in
float64 and in float32. Two facts bound the fold: it never exceeds any value folded so
far (smin(a, b) <= a, b), and the fold of r values is never more than min(R, (r - 1) L)
below the least of them, L being what one blend lowers at most (``BLEND_REACH``; R: smin
is monotone, and smin(m - R, m) = m - R). So over a cell, where the j-th child's value
lies in [lo_j, hi_j]:

- j is *skipped* where lo_j >= min(hi_i, i < j) + R: the fold is R below it all over the
  cell, so smin leaves the fold as it is;
- j *drops* every child before it where hi_j + R + min(R, (j - 1) L) <= min(lo_i, i < j):
  the fold is then R above d_j all over the cell, so smin makes it d_j.

A cell's list is the last dropping child and every later one not skipped, in the union's
order, so folding it from 3e38 (smin(3e38, d) = d) gives the code version's value at
every point of the cell: the skipped and dropped steps change nothing, and the kept
ones are the same operations in the same order. The field is min(that fold, cap), as a
hard union's is min(its children, cap) (``cap``: two cells beyond the blend's support):
equal to the code version's wherever that is below the cap, and a cell where the whole
fold lies above the cap (empty space) lists nothing. A child's interval is its exact extremes
over the cell for a sphere, else its value at the cell centre plus and minus the half
diagonal (the children are 1-Lipschitz) and at least its box gap (their fields are
exact), widened by a float32 slack. The lists are built coarse to fine: the whole grid is
one cell that lists every child, and each cell's list is pruned from its parent's (the
parent's list folds to the code version's value over it, so it stands for the union).

Outside the grid box, which lies ``Blend.pad`` (>= R) beyond every child's box, the field
is the distance to the box plus pad - R: at most the code version's, and positive (no
surface lies there).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ...nodes.booleans import BLEND_REACH, BLEND_SUPPORT, smooth_min
from ...nodes.primitives import Sphere

if TYPE_CHECKING:  # pragma: no cover
    from .grid import Grid

ENTRIES_CHUNK = 1 << 21  # list entries pruned in one numpy pass
CAP_CELLS = 2.0        # the cap, in cells beyond the blend's support
CELL_FACTOR = 0.25     # cell edge / (volume per child)^(1/3) (see the benchmark)
MAX_DIMS = 128         # cells per axis at most
WIDEST = 2.0           # a blend's support at most this many spacings of the children (else lists hold most of them)


@dataclass(frozen=True)
class Blend:
    """A smooth union's blend as its cells need it: radius ``k``, ``kind`` (quadratic,
    circular, chamfer), ``support`` R (beyond it the blend is the min) and ``lowering``
    L (what one blend lowers min(a, b) at most)."""

    k: float
    kind: str
    support: float
    lowering: float

    @classmethod
    def of(cls, k: float, kind: str) -> "Blend":
        """The blend of a smooth union with radius ``k`` and blend ``kind``."""
        return cls(float(k), kind, BLEND_SUPPORT[kind] * float(k), BLEND_REACH[kind] * float(k))

    @property
    def pad(self) -> float:
        """How far the grid box reaches beyond the children's boxes (outside it the field is
        the distance to the box plus pad - R)."""
        return 1.5 * self.support

    def fold(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """One step of the float64 fold, as the union's twin does it."""
        return smooth_min(a, b, self.k, self.kind)


def fits(boxes: np.ndarray, blend: Blend) -> bool:
    """Whether a blend this wide leaves the cells short lists: its support at most WIDEST
    times the spacing of the children (boxes (n, 2, 3)), (volume per child)^(1/3)."""
    extent = np.maximum(boxes[:, 1].max(axis=0) - boxes[:, 0].min(axis=0), 1e-9)
    return blend.support <= WIDEST * float(np.prod(extent) / len(boxes)) ** (1 / 3)


@dataclass(frozen=True)
class Level:
    """Cells of edge ``size`` from the grid's low corner ``lo``, ``dims`` per axis: the grid
    itself or a coarser level (each cell 2 x 2 x 2 of the next finer one)."""

    lo: np.ndarray
    size: float
    dims: np.ndarray

    def ijk(self, cells: np.ndarray) -> np.ndarray:
        """(n, 3) integer coordinates of cell indices."""
        x = cells % self.dims[0]
        y = (cells // self.dims[0]) % self.dims[1]
        return np.stack([x, y, cells // (self.dims[0] * self.dims[1])], axis=-1)

    def index(self, ijk: np.ndarray) -> np.ndarray:
        """Cell indices of (..., 3) integer coordinates."""
        return (ijk[..., 2] * self.dims[1] + ijk[..., 1]) * self.dims[0] + ijk[..., 0]


class Children:
    """What the pruning reads of the union's children: boxes, spheres' centres and radii."""

    def __init__(self, grid: "Grid") -> None:
        self.grid = grid
        self.n = len(grid.children)
        self.los, self.his = grid.los, grid.his
        self.spheres = type(grid.types[0].inner) is Sphere
        self.centre = grid.centre
        if self.spheres:  # float32, relative to the grid's centre: the slack covers the rounding
            at = np.array([t + s * (r @ np.asarray(sph.c, dtype=float)) for sph, t, r, s, _ in grid.peeled])
            self.at = [(at[:, axis] - grid.centre[axis]).astype(np.float32) for axis in range(3)]
            self.rad = np.array([s * float(sph.r) for sph, _, _, s, _ in grid.peeled], dtype=np.float32)
        self.cap = cap(grid)
        ext = float(np.abs(grid.dims * grid.cell).max())
        self.slack = 1e-5 * max(1.0, ext)  # float32 rounding here, of values and of the shader's point

    def gap(self, mid: np.ndarray, size: float, kid: np.ndarray) -> np.ndarray:
        """Euclidean gaps between cells (centres (..., 3)) and the children's boxes."""
        out = 0.0
        for axis in range(3):
            c = mid[..., axis]
            below, above = c - 0.5 * size - self.his[:, axis][kid], self.los[:, axis][kid] - (c + 0.5 * size)
            g = np.maximum(np.maximum(below, above), 0.0)
            out = out + g * g
        return np.sqrt(out)

    def intervals(self, mid: np.ndarray, size: float, kid: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Bounds (lo, hi) on each child's value over its cell (centres (..., 3) and children
        (...), broadcast): a sphere's exact extremes, any other child's value at the cell
        centre plus and minus the half diagonal (1-Lipschitz) and at least its box gap
        (its field is exact)."""
        if self.spheres:  # in place where it can be: these arrays are the pass's largest
            h = np.float32(0.5 * size)
            rel = (mid - self.centre).astype(np.float32)
            lo2 = hi2 = None
            for axis in range(3):
                u = self.at[axis][kid] - rel[..., axis]
                np.abs(u, out=u)
                g = u - h
                np.maximum(g, np.float32(0.0), out=g)
                g *= g
                u += h
                u *= u
                lo2, hi2 = (g, u) if lo2 is None else (np.add(lo2, g, out=lo2), np.add(hi2, u, out=hi2))
            r = self.rad[kid]
            np.sqrt(lo2, out=lo2)
            np.sqrt(hi2, out=hi2)
            lo2 -= r
            lo2 -= np.float32(self.slack)
            hi2 -= r
            hi2 += np.float32(self.slack)
            return lo2, hi2
        half = size * np.sqrt(3.0) / 2
        shape = np.broadcast_shapes(mid.shape[:-1], kid.shape)
        flat_kid = np.broadcast_to(kid, shape).ravel()
        centre = np.broadcast_to(mid, shape + (3,)).reshape(-1, 3)
        value = np.empty(len(flat_kid))
        order = np.argsort(flat_kid, kind="stable")
        bounds = np.searchsorted(flat_kid[order], np.arange(self.n + 1))
        for i in np.flatnonzero(np.diff(bounds)):
            rows = order[bounds[i]:bounds[i + 1]]
            value[rows] = self.grid.children[i]._distance(centre[rows])
        value = value.reshape(shape)
        return np.maximum(value - half, self.gap(mid, size, kid)) - self.slack, value + half + self.slack


def cap(grid: "Grid") -> float:
    """The cap of a blend's grid: inside its box the field is min(the union's fold, cap)."""
    assert grid.blend is not None
    return CAP_CELLS * grid.cell + grid.blend.support


def entries(grid: "Grid") -> tuple[np.ndarray, np.ndarray]:
    """(cell index, child index) of every list entry, sorted by cell, then by child (the
    union's order): from one cell holding every child, each level of cells half the edge
    of the one before prunes its parents' lists."""
    blend = grid.blend
    assert blend is not None
    kids = Children(grid)
    levels = [Level(grid.lo, grid.cell, grid.dims)]
    while np.any(levels[-1].dims > 1):
        last = levels[-1]
        levels.append(Level(last.lo, 2 * last.size, (last.dims + 1) // 2))
    cells, child = np.zeros(kids.n, dtype=np.int64), np.arange(kids.n)
    for level in reversed(levels[:-1]):
        cells, child = _refine(kids, level, cells, child, blend)
    order = np.argsort(cells, kind="stable")
    return cells[order], child[order]


def _refine(kids: Children, level: Level, parent_cells: np.ndarray, parent_child: np.ndarray,
            blend: Blend) -> tuple[np.ndarray, np.ndarray]:
    """The lists of ``level`` from those of its parent level (entries grouped by parent
    cell, in the union's order within each): each of a parent's 8 cells prunes its list."""
    parent = Level(level.lo, 2 * level.size, (level.dims + 1) // 2)
    starts = np.flatnonzero(np.r_[True, parent_cells[1:] != parent_cells[:-1]])
    length = np.r_[starts[1:], len(parent_cells)] - starts
    offsets = np.array([(i, j, k) for k in (0, 1) for j in (0, 1) for i in (0, 1)])
    sub = 2 * parent.ijk(parent_cells[starts])[:, None, :] + offsets[None, :, :]  # (parents, 8, 3)
    real = np.all(sub < level.dims, axis=-1)
    rows = level.index(np.minimum(sub, level.dims - 1))
    mids = level.lo + (sub + 0.5) * level.size
    cells_out, child_out = [], []
    by_length = np.argsort(-length, kind="stable")  # chunks of like lengths (little padding), longest first
    at = 0
    while at < len(by_length):
        take = by_length[at:at + max(1, ENTRIES_CHUNK // (8 * max(1, int(length[by_length[at]]))))]
        at += len(take)
        keep, kid = _prune(kids, level, mids[take], parent_child, starts[take], length[take], blend)
        keep &= real[take][:, :, None]
        cells_out.append(np.broadcast_to(rows[take][:, :, None], keep.shape)[keep])
        child_out.append(np.broadcast_to(kid[:, None, :], keep.shape)[keep])
    return np.concatenate(cells_out), np.concatenate(child_out)  # each cell's entries together, in order


def _prune(kids: Children, level: Level, mids: np.ndarray, child: np.ndarray, first: np.ndarray,
           length: np.ndarray, blend: Blend) -> tuple[np.ndarray, np.ndarray]:
    """Prune the lists child[first[i]:first[i] + length[i]] (in the union's order) over the
    8 cells of centres mids[i] (parents, 8, 3) of ``level``: the kept entries' mask
    (parents, 8, width) and the children (parents, width)."""
    width = int(length.max())
    rank = np.arange(width)
    valid = rank[None, :] < length[:, None]
    kid = child[np.where(valid, first[:, None] + rank[None, :], 0)]
    lo, hi = kids.intervals(mids[:, :, None, :], level.size, kid[:, None, :])
    out = ~valid[:, None, :]
    lo[np.broadcast_to(out, lo.shape)] = np.inf
    hi[np.broadcast_to(out, hi.shape)] = np.inf
    before_lo, before_hi = _least_before(lo), _least_before(hi)
    R = blend.support + kids.slack
    # the fold of r values is at most min(R, (r - 1) L) below their least
    lowered = np.minimum(blend.support, np.maximum(rank - 1, 0) * blend.lowering).astype(lo.dtype)
    drops = hi + R + lowered <= before_lo  # the first entry always: nothing is before it
    drops &= valid[:, None, :]
    start = width - 1 - np.argmax(drops[:, :, ::-1], axis=2)
    keep = (rank >= start[:, :, None]) & ~(lo >= before_hi + R)
    keep &= valid[:, None, :]
    # a cell where the whole fold is at least the cap lists nothing: its field is the cap
    floor = lo.min(axis=2) - np.minimum(blend.support, np.maximum(length - 1, 0) * blend.lowering)[:, None]
    keep &= (floor < kids.cap)[:, :, None]
    return keep, kid


def _least_before(v: np.ndarray) -> np.ndarray:
    """Along the last axis, the least of the values before each (inf before the first)."""
    out = np.empty_like(v)
    out[..., 0] = np.inf
    out[..., 1:] = v[..., :-1]
    return np.minimum.accumulate(out, axis=-1, out=out)


def field(grid: "Grid", p: np.ndarray) -> np.ndarray:
    """The float64 twin of the shader's field: inside the grid box min(the fold over the
    point's cell list, cap), which is min(the code version's value, cap); outside it the
    distance to the box plus pad - R."""
    blend = grid.blend
    assert blend is not None
    flat = p.reshape(-1, 3)
    ijk = np.clip(np.floor((flat - grid.lo) / grid.cell), 0, grid.dims - 1).astype(np.int64)
    top = grid.lo + grid.dims * grid.cell
    away = np.sqrt(np.sum(np.maximum(np.maximum(grid.lo - flat, flat - top), 0.0) ** 2, axis=-1))
    cell = (ijk[:, 2] * grid.dims[1] + ijk[:, 1]) * grid.dims[0] + ijk[:, 0]
    cells, child = grid.entries()
    acc = np.full(len(flat), np.inf)
    order = np.argsort(child, kind="stable")
    bounds = np.searchsorted(child[order], np.arange(len(grid.children) + 1))
    listed = np.zeros(int(np.prod(grid.dims)), dtype=bool)
    for i, c in enumerate(grid.children):
        mine = cells[order[bounds[i]:bounds[i + 1]]]
        if not len(mine):
            continue
        listed[mine] = True
        m = listed[cell]
        listed[mine] = False
        if m.any():
            acc[m] = blend.fold(acc[m], c._distance(flat[m]))
    out = np.where(away > 0, away + blend.pad - blend.support, np.minimum(acc, cap(grid)))
    return out.reshape(p.shape[:-1])
