"""The cell lists of a smooth union kept as data: the left fold pruned exactly, per cell.

A smooth union folds its children in order, acc = smin(acc, d_i). Each blend has a
*support* R (``BLEND_SUPPORT``: k for the quadratic and the chamfer, k / (1 - sqrt(1/2))
for the circular one): where |a - b| >= R, smin(a, b) is min(a, b) exactly (h = 0), in
float64 and in float32. So over a cell, where child i's value lies in [lo_i, hi_i] and
the fold's so far in [lo, hi]:

- a child with lo_i >= hi + R leaves the fold as it is: it is skipped;
- a child with hi_i + R <= lo makes the fold its own value: everything before it is dropped;
- any other child is kept, and the fold's interval becomes
  [max(min(lo, lo_i) - L, min(lo + R, lo_i) - R), min(hi, hi_i)], where L is what one
  blend lowers at most (``BLEND_REACH``) and R what any fold of values >= m lowers below
  m at most (smin is monotone and is min(m - R, m) = m - R there).

A cell's list is what is kept after the last drop, in the union's order, so folding it
from 3e38 (smin(3e38, d) = d) gives the code version's value at every point of the cell:
the skipped and dropped steps change nothing, and the kept ones are the same operations
in the same order. The values' intervals are a child's value at the cell centre plus and
minus the cell's half diagonal (the children are 1-Lipschitz), widened by a float32
slack. Children whose box lies more than a radius r from the cell are not looked at one
by one: their fields are exact, so they are at least r away, and each run of them is one
"far" step (lo = r, hi = inf) between the looked-at ones. A cell whose fold still leans
on a far step at its end is done again with r doubled, until none does.

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

PAIRS_CHUNK = 1 << 21  # (cell, child) pairs looked at in one numpy pass
ROWS_CHUNK = 1 << 13   # cells folded side by side in one pass
TOP_CELLS = 4096       # the coarsest level has at most this many cells
CELL_FACTOR = 0.25     # cell edge / (volume per child)^(1/3) (see the benchmark)
MAX_DIMS = 128         # cells per axis at most


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

    def corner(self, cells: np.ndarray) -> np.ndarray:
        """The low corners (..., 3) of cell indices (...)."""
        return self.lo + self.ijk(cells) * self.size


class Children:
    """What the folds read of the union's children: boxes, and spheres' centres and radii."""

    def __init__(self, grid: "Grid") -> None:
        self.grid = grid
        self.n = len(grid.children)
        self.los, self.his = grid.los, grid.his
        self.spheres = type(grid.types[0].inner) is Sphere
        if self.spheres:
            at = np.array([t + s * (r @ np.asarray(sph.c, dtype=float)) for sph, t, r, s, _ in grid.peeled])
            self.at = [np.ascontiguousarray(at[:, axis]) for axis in range(3)]
            self.rad = np.array([s * float(sph.r) for sph, _, _, s, _ in grid.peeled])
        ext = np.abs(np.concatenate([grid.lo, grid.lo + grid.dims * grid.cell])).max()
        self.slack = 4e-6 * max(1.0, float(ext))  # float32 rounding of values and of the shader's point

    def gap(self, corner: np.ndarray, size: float, kid: np.ndarray) -> np.ndarray:
        """Euclidean gaps between cells (low corners (..., 3)) and the children's boxes."""
        g = np.maximum(np.maximum(corner - self.his[kid], self.los[kid] - (corner + size)), 0.0)
        return np.sqrt(np.sum(g * g, axis=-1))

    def intervals(self, corner: np.ndarray, size: float, kid: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Bounds (lo, hi) on each child's value over its cell (corners (..., 3), children
        (...)): a sphere's exact extremes, any other child's value at the cell centre plus
        and minus the half diagonal (1-Lipschitz) and at least its box gap (exact)."""
        if self.spheres:
            h = 0.5 * size
            lo2 = hi2 = 0.0
            for axis in range(3):
                u = np.abs(self.at[axis][kid] - (corner[..., axis] + h))
                g = np.maximum(u - h, 0.0)
                lo2 = lo2 + g * g
                u += h
                hi2 = hi2 + u * u
            r = self.rad[kid]
            lo, hi = np.sqrt(lo2) - r, np.sqrt(hi2) - r
        else:
            half = size * np.sqrt(3.0) / 2
            flat_kid, centre = kid.ravel(), np.broadcast_to(corner + 0.5 * size, kid.shape + (3,)).reshape(-1, 3)
            value = np.empty(len(flat_kid))
            order = np.argsort(flat_kid, kind="stable")
            bounds = np.searchsorted(flat_kid[order], np.arange(self.n + 1))
            for i in np.flatnonzero(np.diff(bounds)):
                rows = order[bounds[i]:bounds[i + 1]]
                value[rows] = self.grid.children[i]._distance(centre[rows])
            value = value.reshape(kid.shape)
            lo, hi = np.maximum(value - half, self.gap(corner, size, kid)), value + half
        return lo - self.slack, hi + self.slack


def entries(grid: "Grid") -> tuple[np.ndarray, np.ndarray]:
    """(cell index, child index) of every list entry, sorted by cell, then by child (the
    union's order): the coarsest level from scratch, then each finer one from its parent
    cells' lists (a parent's list is exact over it, so its children need no far steps)."""
    blend = grid.blend
    assert blend is not None
    kids = Children(grid)
    levels = [Level(grid.lo, grid.cell, grid.dims)]
    while int(np.prod(levels[-1].dims)) > TOP_CELLS:
        last = levels[-1]
        levels.append(Level(last.lo, 2 * last.size, (last.dims + 1) // 2))
    cells, child = _top(kids, levels[-1], blend)
    for level in reversed(levels[:-1]):
        cells, child = _refine(kids, level, cells, child, blend)
    order = np.argsort(cells, kind="stable")
    return cells[order], child[order]


def _top(kids: Children, level: Level, blend: Blend) -> tuple[np.ndarray, np.ndarray]:
    """The coarsest level's lists: the children within a radius of each cell, the others as
    far steps, the radius doubled for the cells whose fold still leans on one."""
    n, ncell = kids.n, int(np.prod(level.dims))
    radius = 2 * blend.support + level.size
    reach_all = float(np.linalg.norm(level.dims * level.size))  # a radius that looks at every child
    pending = np.arange(ncell)
    out_cells, out_child = [], []
    while pending.size:
        everything = radius >= reach_all
        if not everything and _range_pairs(kids, level, radius) < len(pending) * n:
            cell, kid = _near_pairs(kids, level, radius, pending)
        else:
            cell = np.repeat(pending, n)
            kid = np.tile(np.arange(n), len(pending))
        if not everything:
            near = kids.gap(level.corner(cell), level.size, kid) <= radius
            cell, kid = cell[near], kid[near]
        starts = np.flatnonzero(np.r_[True, cell[1:] != cell[:-1]]) if len(cell) else np.zeros(0, dtype=np.int64)
        rows = cell[starts]
        keep, dirty = _fold_rows(kids, level, rows, kid, starts, np.r_[starts[1:], len(cell)],
                                 np.inf if everything else radius, blend)
        out_cells.append(cell[keep])
        out_child.append(kid[keep])
        pending = np.union1d(rows[dirty], np.setdiff1d(pending, rows))  # no candidate: far steps only
        radius *= 2
    return np.concatenate(out_cells), np.concatenate(out_child)


def _ranges(kids: Children, level: Level, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """Per child, the first and last cell (per axis) of ``level`` within ``radius`` of its box."""
    a = np.clip(np.floor((kids.los - radius - level.lo) / level.size).astype(np.int64), 0, level.dims - 1)
    b = np.clip(np.floor((kids.his + radius - level.lo) / level.size).astype(np.int64), 0, level.dims - 1)
    return a, b


def _range_pairs(kids: Children, level: Level, radius: float) -> int:
    """How many (cell, child) pairs the children's cell ranges within ``radius`` hold."""
    a, b = _ranges(kids, level, radius)
    return int((b - a + 1).prod(axis=1).sum())


def _near_pairs(kids: Children, level: Level, radius: float, pending: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(cell, child) pairs of ``level``, sorted by cell then child, of the ``pending`` cells
    in the child's cell range (per axis) within ``radius`` of its box."""
    a, b = _ranges(kids, level, radius)
    span = b - a + 1
    counts = span.prod(axis=1)
    kid = np.repeat(np.arange(kids.n), counts)
    local = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    nx, ny = np.repeat(span[:, 0], counts), np.repeat(span[:, 1], counts)
    ijk = np.stack([np.repeat(a[:, 0], counts) + local % nx, np.repeat(a[:, 1], counts) + (local // nx) % ny,
                    np.repeat(a[:, 2], counts) + local // (nx * ny)], axis=-1)
    cell = level.index(ijk)
    wanted = np.zeros(int(np.prod(level.dims)), dtype=bool)
    wanted[pending] = True
    keep = wanted[cell]
    cell, kid = cell[keep], kid[keep]
    order = np.lexsort((kid, cell))
    return cell[order], kid[order]


def _refine(kids: Children, level: Level, parent_cells: np.ndarray, parent_child: np.ndarray,
            blend: Blend) -> tuple[np.ndarray, np.ndarray]:
    """The lists of ``level`` from those of its parent level (entries grouped by parent
    cell, in the union's order within each): each of a parent's 8 cells folds its list."""
    parent = Level(level.lo, 2 * level.size, (level.dims + 1) // 2)
    starts = np.flatnonzero(np.r_[True, parent_cells[1:] != parent_cells[:-1]])
    ends = np.r_[starts[1:], len(parent_cells)]
    base = 2 * parent.ijk(parent_cells[starts])
    offsets = np.array([(i, j, k) for k in (0, 1) for j in (0, 1) for i in (0, 1)])
    sub = base[:, None, :] + offsets[None, :, :]  # (parents, 8, 3)
    inside = np.all(sub < level.dims, axis=-1)
    which, o = np.nonzero(inside)
    rows = level.index(sub[which, o])
    keep, _ = _fold_rows(kids, level, rows, parent_child, starts[which], ends[which], np.inf, blend)
    length = ends[which] - starts[which]
    at = np.repeat(starts[which], length) + (np.arange(length.sum()) - np.repeat(np.cumsum(length) - length, length))
    return np.repeat(rows, length)[keep], parent_child[at][keep]


def _fold_rows(kids: Children, level: Level, rows: np.ndarray, child: np.ndarray, starts: np.ndarray,
               ends: np.ndarray, radius: float, blend: Blend) -> tuple[np.ndarray, np.ndarray]:
    """Fold the list child[starts[i]:ends[i]] (in the union's order) over cell rows[i] of
    ``level``, the children left out standing as far steps at least ``radius`` away (none
    when it is inf): which entries are kept (flat, row by row, in the order of the rows
    and their lists) and which rows still lean on a far step."""
    n = kids.n
    by_length = np.argsort(ends - starts, kind="stable")  # chunks of like lengths: little padding
    rows, starts, ends = rows[by_length], starts[by_length], ends[by_length]
    length = ends - starts
    kept_parts, dirty_parts = [], []
    R, L = blend.support + kids.slack, blend.lowering
    far_lo = radius - blend.support
    for r0 in range(0, len(rows), ROWS_CHUNK):
        s, ln = starts[r0:r0 + ROWS_CHUNK], length[r0:r0 + ROWS_CHUNK]
        m = len(s)
        width = int(ln.max()) if m else 0
        rank = np.arange(width)
        valid = rank[None, :] < ln[:, None]
        kid = np.where(valid, child[np.where(valid, s[:, None] + rank[None, :], 0)], n)
        corner = level.corner(rows[r0:r0 + ROWS_CHUNK])[:, None, :]
        glo, ghi = kids.intervals(corner, level.size, np.minimum(kid, n - 1))
        if np.isfinite(radius):  # far children between this one and the one before
            gap = valid & (kid - np.concatenate([np.full((m, 1), -1), kid[:, :-1]], axis=1) > 1)
        acc_lo, acc_hi = np.full(m, np.inf), np.full(m, np.inf)
        empty = np.ones(m, dtype=bool)
        dirty = np.zeros(m, dtype=bool)
        first = np.zeros(m, dtype=np.int64)  # the rank of the last drop
        keep = np.zeros((m, width), dtype=bool)
        for r in range(width):
            if np.isfinite(radius):
                far = gap[:, r]
                if far.any():
                    opened = far & empty
                    lean = far & ~empty & (acc_hi + R > radius)
                    acc_lo = np.where(opened, far_lo, np.where(lean, np.minimum(acc_lo, far_lo), acc_lo))
                    dirty |= opened | lean
                    empty &= ~opened
            v = valid[:, r]
            a, b = glo[:, r], ghi[:, r]
            live = v & ~empty
            skip = live & (a >= acc_hi + R)
            drop = live & ~skip & (acc_lo >= b + R)
            join = live & ~skip & ~drop
            anew = (v & empty) | drop
            acc_lo = np.where(join, np.maximum(np.minimum(acc_lo, a) - L, np.minimum(acc_lo + blend.support, a)
                                               - blend.support), np.where(anew, a, acc_lo))
            acc_hi = np.where(join, np.minimum(acc_hi, b), np.where(anew, b, acc_hi))
            first = np.where(anew, r, first)
            dirty &= ~anew
            empty &= ~v
            keep[:, r] = anew | join
        if np.isfinite(radius):
            tail = kid[np.arange(m), ln - 1] < n - 1
            dirty |= tail & (acc_hi + R > radius)
        keep &= (rank[None, :] >= first[:, None]) & ~dirty[:, None]
        kept_parts.append(keep[valid])
        dirty_parts.append(dirty)
    none = np.zeros(0, dtype=bool)
    kept, dirty = np.concatenate(kept_parts + [none]), np.concatenate(dirty_parts + [none])
    # back to the callers' order of rows (their entries, flat)
    unsort = np.empty_like(by_length)
    unsort[by_length] = np.arange(len(by_length))
    flat_start = np.cumsum(length) - length
    back = np.repeat(flat_start[unsort], length[unsort]) + (np.arange(length.sum()) - np.repeat(
        np.cumsum(length[unsort]) - length[unsort], length[unsort]))
    return kept[back], dirty[unsort]


def field(grid: "Grid", p: np.ndarray) -> np.ndarray:
    """The float64 twin of the shader's fold over each point's cell list (the code
    version's value inside the grid box), and outside it the distance to the box plus
    pad - R."""
    blend = grid.blend
    assert blend is not None
    flat = p.reshape(-1, 3)
    cell_ijk = np.floor((flat - grid.lo) / grid.cell)
    clamped = np.clip(cell_ijk, 0, grid.dims - 1)
    cell_lo = grid.lo + clamped * grid.cell
    away = np.sqrt(np.sum(np.maximum(np.maximum(cell_lo - flat, flat - (cell_lo + grid.cell)), 0.0) ** 2, axis=-1))
    ijk = clamped.astype(np.int64)
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
    out = np.where(away > 0, away + blend.pad - blend.support, acc)
    return out.reshape(p.shape[:-1])
