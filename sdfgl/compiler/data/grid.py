"""Big unions as data: instances of a few types, listed per type in the cells of a uniform grid.

Each grid cell lists, per type (sdfgl.compiler.data.instances), the instances whose bounds
come within MARGIN (half a cell) of it, with the instance's data (inverse transform,
parameters, colour) inline in the list, so the shader runs one tight loop per type over
what is near a point: no type branches run masked, and a list entry costs one to four
texel fetches (shaders/templates/grid_union.glsl finds the cell; the loops are written by
sdfgl.compiler.data.grid_code). The field is min(listed, cap), where every unlisted
instance is at least ``cap`` away; the float64 twin computes min(all children, cap) with
the same cap.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ...errors import SdfglError
from ...nodes.base import Node, box_of
from ...nodes.primitives import Sphere
from . import blend_lists, grid_record
from .slots import slot_values

if TYPE_CHECKING:  # pragma: no cover
    from .blend_lists import Blend
    from .instances import InstanceType

GRID_MIN = 32       # fewer children than this are written out as code (see the benchmark)
LIST_WIDTH = 1024   # texels per row of the cell and list textures (a power of two)
MAX_DIMS = 64       # cells per axis at most
# chosen on the growth scene (1024 spheres; see the benchmark and docs/design/big-scenes.md)
CELL_FACTOR = 0.5  # cell edge / (volume per instance)^(1/3)
MARGIN = 0.5       # in cells: how near an instance's bounds must come to a cell to be listed
SHAPE_GROUP = 64   # the fewest children of one shape (cells per axis) listed by vector passes


class Grid:
    """The instances of one union, their types and the cell lists over their bounds."""

    def __init__(self, children: list[Node], peeled: list[tuple], types: list[InstanceType], single_cell: bool = False,
                 boxes: np.ndarray | None = None, blend: Blend | None = None, rest: list[Node] | None = None) -> None:
        """``single_cell`` makes one cell list every instance: a plain data-driven loop
        (the uber-shader the benchmark compares against); ``boxes`` (n, 2, 3) are the
        children's bounds when the caller has them; ``blend`` is a smooth union's (its
        cells list what the blend needs: sdfgl.compiler.data.blend_lists); ``rest`` are the
        union's other children, which stay code beside the grid (each once)."""
        self.children, self.types = children, types
        self.rest: list[Node] = rest or []
        self.peeled = peeled  # (inner, t, R, s, colour) per child
        self.blend = blend
        if boxes is None:
            boxes = np.array([bounds_of(c) for c in children])
        los, his = boxes[:, 0], boxes[:, 1]
        lo, hi = los.min(axis=0), his.max(axis=0)
        if blend is not None:
            lo, hi = lo - blend.pad, hi + blend.pad
        extent = np.maximum(hi - lo, 1e-9)
        factor, most = (CELL_FACTOR, MAX_DIMS) if blend is None else (blend_lists.CELL_FACTOR, blend_lists.MAX_DIMS)
        cell = factor * float(np.prod(extent) / len(children)) ** (1 / 3)
        cell = float(extent.max()) * 1.001 if single_cell else max(cell, float(extent.max()) / most)
        self.dims = np.minimum(np.ceil(extent / cell).astype(int), most)
        self.cell, self.lo = cell, lo
        self.margin = MARGIN * cell
        self.centre = lo + 0.5 * self.dims * cell  # data and code are relative to it (float32 precision)
        self.los, self.his = los, his  # per instance, its box (n, 3) each
        self._ball_at, self._ball_r = _balls(peeled, boxes) if peeled and not single_cell and blend is None \
            else (None, None)
        self._textures: dict[tuple, dict[str, np.ndarray]] = {}

    @property
    def free_way(self) -> bool:
        """Whether the marcher may step this union's free way along the ray: a hard union's
        (a blend's field is not capped, so its cells' free way is seldom longer than its
        value: measured on the blended slab, steps alike and frames 15 % slower)."""
        return self.blend is None

    # -- the twin's cap (the same number the shader computes) --------------------------
    def cap(self, p: np.ndarray) -> np.ndarray:
        """The distance below which every unlisted instance lies, at (..., 3) points."""
        rel = (p - self.lo) / self.cell
        cell = np.clip(np.floor(rel), 0, self.dims - 1)
        cell_lo = self.lo + cell * self.cell
        # outside the clamped cell only outside the grid box, by the distance to the box
        out = np.sqrt(np.sum(np.maximum(np.maximum(cell_lo - p, p - (cell_lo + self.cell)), 0.0) ** 2, axis=-1))
        return np.maximum(self.margin - out, out)

    def field(self, p: np.ndarray) -> np.ndarray:
        """The float64 twin of the shader's loop: min over the instances listed in each
        point's cell, and the cap (for exact instances, min(all, cap)); for a blend, the
        fold over each cell's list (sdfgl.compiler.data.blend_lists.field)."""
        if self.blend is not None:
            return blend_lists.field(self, p)
        flat = p.reshape(-1, 3)
        cell = np.clip(np.floor((flat - self.lo) / self.cell), 0, self.dims - 1).astype(np.int64)
        d = self.cap(flat)
        # each point's list, as (point, instance) pairs grouped by instance: one call of each
        # listed instance's twin on its points (a Python loop over the instances present)
        listed, child = self.entries()
        index = (cell[:, 2] * self.dims[1] + cell[:, 1]) * self.dims[0] + cell[:, 0]
        first = np.searchsorted(listed, index, "left")
        count = np.searchsorted(listed, index, "right") - first
        point = np.repeat(np.arange(len(flat)), count)
        kid = child[np.repeat(first, count) + (np.arange(int(count.sum())) - np.repeat(np.cumsum(count) - count, count))]
        order = np.argsort(kid, kind="stable")
        point, kid = point[order], kid[order]
        kinds, starts = np.unique(kid, return_index=True)
        for i, sel in zip(kinds, np.split(point, starts[1:])):
            d[sel] = np.minimum(d[sel], self.children[int(i)]._distance(flat[sel]))
        return d.reshape(p.shape[:-1])

    def _ranges(self) -> tuple[np.ndarray, np.ndarray]:
        """Per instance, the first and last cell (per axis) whose list holds it."""
        a = np.clip(np.floor((self.los - self.margin - self.lo) / self.cell).astype(np.int64), 0, self.dims - 1)
        b = np.clip(np.floor((self.his + self.margin - self.lo) / self.cell).astype(np.int64), 0, self.dims - 1)
        return a, b

    # -- data ------------------------------------------------------------------------
    def entries(self) -> tuple[np.ndarray, np.ndarray]:
        """(cell index, child index) of every list entry, sorted by cell (then, for a
        blend, by child: the union's order; built once)."""
        found = self.__dict__.get("_found")
        if found is None:
            found = self.__dict__["_found"] = self._entries() if self.blend is None else blend_lists.entries(self)
        return found

    def _entries(self) -> tuple[np.ndarray, np.ndarray]:
        """(cell index, child index) of every list entry, sorted by cell, then by child.

        Each entry is one int64 key, cell * n + child, and one sort of the keys orders
        them. Children of one shape (cells spanned per axis) are listed together, one
        vector pass per cell offset over all of them in the order of their first cell,
        so each pass gives an ascending run of keys and the sort merges runs."""
        a, b = self._ranges()
        n = b - a + 1
        count = len(self.children)
        first = (a[:, 2] * self.dims[1] + a[:, 1]) * self.dims[0] + a[:, 0]
        order = np.sort(first * count + np.arange(count)) % count  # by first cell, then by index
        shape = (n[order] * [1, MAX_DIMS + 1, (MAX_DIMS + 1) ** 2]).sum(axis=1)
        by_shape = order[np.argsort(shape, kind="stable")]
        _, starts, sizes = np.unique(np.sort(shape), return_index=True, return_counts=True)
        keys, rest = [], []
        for start, size in zip(starts.tolist(), sizes.tolist()):
            members = by_shape[start:start + size]
            if size < SHAPE_GROUP or int(n[members[0]].prod()) > size:  # few, or big: entry by entry
                rest.append(members)
            else:
                keys += self._shape_keys(members, a[members], n[members[0]], first[members])
        if rest:
            keys.append(self._spread_keys(np.concatenate(rest), a, n))
        key = np.sort(np.concatenate(keys), kind="stable")
        cells = key // count
        return cells, key - cells * count

    def _gaps(self, child: np.ndarray, axis: int, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(squared gap from ``child``'s ball centre, squared gap from its box) to the cells
        ``index`` along ``axis`` (zero inside)."""
        lo = self.lo[axis] + index * self.cell
        at = self._ball_at[child, axis]
        ball = np.maximum(np.maximum(lo - at, at - (lo + self.cell)), 0.0)
        box = np.maximum(np.maximum(lo - self.his[child, axis], self.los[child, axis] - (lo + self.cell)), 0.0)
        return ball * ball, box * box

    def _shape_keys(self, child: np.ndarray, a: np.ndarray, n: np.ndarray, first: np.ndarray) -> list[np.ndarray]:
        """The keys of children that span ``n`` cells per axis from their first cells ``a``."""
        step = (1, int(self.dims[0]), int(self.dims[0] * self.dims[1]))
        base = first * len(self.children) + child
        if self._ball_at is None:  # every cell of the ranges
            return [base + (jx * step[0] + jy * step[1] + jz * step[2]) * len(self.children)
                    for jz in range(int(n[2])) for jy in range(int(n[1])) for jx in range(int(n[0]))]
        gaps = [[self._gaps(child, axis, a[:, axis] + j) for j in range(int(n[axis]))] for axis in range(3)]
        reach = self._ball_r[child] + self.margin
        reach2, margin2 = reach * reach, self.margin * self.margin
        out = []
        for jz, (bz, xz) in enumerate(gaps[2]):
            for jy, (by, xy) in enumerate(gaps[1]):
                for jx, (bx, xx) in enumerate(gaps[0]):
                    keep = ((bx + by + bz) <= reach2) & ((xx + xy + xz) <= margin2)
                    out.append(base[keep] + (jx * step[0] + jy * step[1] + jz * step[2]) * len(self.children))
        return out

    def _spread_keys(self, members: np.ndarray, a: np.ndarray, n: np.ndarray) -> np.ndarray:
        """The keys of ``members`` of any shapes, entry by entry (few children, or big ones)."""
        a, n = a[members], n[members]
        counts = n.prod(axis=1)
        child = np.repeat(members, counts)
        local = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        nx, ny = np.repeat(n[:, 0], counts), np.repeat(n[:, 1], counts)
        x = np.repeat(a[:, 0], counts) + local % nx
        y = np.repeat(a[:, 1], counts) + (local // nx) % ny
        z = np.repeat(a[:, 2], counts) + local // (nx * ny)
        if self._ball_at is not None:
            keep = self._near_ball(x, y, z, child)
            x, y, z, child = x[keep], y[keep], z[keep], child[keep]
        return ((z * self.dims[1] + y) * self.dims[0] + x) * len(self.children) + child

    def _near_ball(self, x: np.ndarray, y: np.ndarray, z: np.ndarray, child: np.ndarray) -> np.ndarray:
        """Whether each instance ``child`` (n,) lies within the margin of cell (x, y, z) by its
        ball and by the Euclidean gap between its box and the cell (see _balls): the per-axis
        cell ranges alone list a sphere in cells near its box's corners (22 % of the growth
        scene's entries), and a box by its corners too (5 % of 1000 robot copies'). The
        cap's promise holds: an unlisted instance is at least the margin from the cell, by
        its box or by its ball."""
        ball2 = np.zeros(len(child))
        box2 = np.zeros(len(child))
        for axis, index in enumerate((x, y, z)):
            ball, box = self._gaps(child, axis, index)
            ball2 += ball
            box2 += box
        reach = self._ball_r[child] + self.margin
        return (ball2 <= reach * reach) & (box2 <= self.margin * self.margin)

    def records(self, t: InstanceType, default_color: tuple[float, float, float]) -> np.ndarray:
        """float32 (members, texels, 4): each member's move (grid_record), parameters, colour."""
        sizes = [len(v) for _, v in slot_values(t.inner)] if t.slots is not None else []
        peeled = [self.peeled[i] for i in t.members]
        rot = np.array([u[2] for u in peeled]) if t.affine else None  # None: no member turns
        move = grid_record.kind(t, rot)
        scale_at, slots_at, color_at, texels = t.layout(sizes, move)
        out = np.zeros((len(t.members), texels * 4), dtype=np.float64)
        tr = np.array([u[1] for u in peeled]) - self.centre
        s = np.array([u[3] for u in peeled], dtype=np.float64)
        out[:, :grid_record.floats(move)] = grid_record.encode(move, tr, rot, s)
        if t.scaled:
            out[:, scale_at] = s
        if t.slots is not None:
            pos = slots_at
            for name, size in zip(t.slots, sizes):
                out[:, pos:pos + size] = _slot_column([u[0].__dict__[name] for u in peeled], size)
                pos += size
        if t.color_in_record:
            out[:, color_at:color_at + 3] = [u[4] if u[4] is not None else default_color for u in peeled]
        return out.astype(np.float32).reshape(len(t.members), texels, 4)

    def textures(self, default_color: tuple[float, float, float]) -> dict[str, np.ndarray]:
        """float32 RGBA arrays (rows, LIST_WIDTH, 4): per cell and type (first texel, count)
        pairs, and the list records."""
        key = tuple(default_color)
        if key in self._textures:
            return self._textures[key]
        cells, child = self.entries()
        type_of = np.zeros(len(self.children), dtype=np.int64)
        local = np.zeros(len(self.children), dtype=np.int64)
        for ti, t in enumerate(self.types):
            type_of[t.members] = ti
            local[t.members] = np.arange(len(t.members))
        etype = type_of[child]
        if len(self.types) > 1:  # entries() sorts by cell: one type needs no more
            order = np.lexsort((etype, cells))  # by cell, then type
            cells, child, etype = cells[order], child[order], etype[order]
        recs = [self.records(t, default_color) for t in self.types]
        size = np.array([r.shape[1] for r in recs])
        width = size[etype]
        offset = np.concatenate([[0], np.cumsum(width)[:-1]])
        total = int(width.sum())
        lst = np.zeros((max(1, -(-total // LIST_WIDTH)) * LIST_WIDTH, 4), dtype=np.float32)
        if total >= 2 ** 24:
            raise SdfglError(f"union: {total} list texels exceed the float32 index limit of 2^24; "
                             "use fewer or larger instances")
        if len(recs) == 1:  # one type: the records follow each other, entry by entry
            lst[:total] = recs[0][local[child]].reshape(-1, 4)
        for ti, r in enumerate(recs if len(recs) > 1 else ()):
            sel = np.nonzero(etype == ti)[0]
            rows = offset[sel][:, None] + np.arange(r.shape[1])[None, :]
            lst[rows.ravel()] = r[local[child[sel]]].reshape(-1, 4)
        ntypes = len(self.types)
        per_cell = -(-ntypes // 2)
        ncell = int(np.prod(self.dims))
        table = np.zeros((ncell, per_cell * 2, 2), dtype=np.float64)
        flat = cells * ntypes + etype
        counts = np.bincount(flat, minlength=ncell * ntypes)
        firsts = np.zeros(ncell * ntypes, dtype=np.int64)
        firsts[flat[::-1]] = offset[::-1]  # the first entry of each (cell, type) group
        table[:, :ntypes, 0] = firsts.reshape(ncell, ntypes)
        table[:, :ntypes, 1] = counts.reshape(ncell, ntypes)
        cell_tex = np.zeros((-(-ncell * per_cell // LIST_WIDTH) * LIST_WIDTH, 4), dtype=np.float32)
        cell_tex[:ncell * per_cell] = table.reshape(ncell * per_cell, 4)
        out = {"Cells": cell_tex.reshape(-1, LIST_WIDTH, 4), "List": lst.reshape(-1, LIST_WIDTH, 4)}
        self._textures[key] = out
        return out


def _slot_column(values: list, size: int) -> np.ndarray:
    """(n, size) float64 of one data slot's values (numbers or arrays of ``size`` numbers)."""
    try:  # values alike in shape: one conversion
        return np.array(values, dtype=np.float64).reshape(len(values), size)
    except ValueError:  # a number beside a one-element array, say
        return np.array([np.ravel(v) for v in values], dtype=np.float64)


def _balls(peeled: list[tuple], boxes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A ball holding each instance (centres (n, 3), radii (n,)): a sphere itself (the ball
    its world box ``boxes`` (n, 2, 3) is drawn round), any other node the ball round its
    own box, moved with the instance (a rotated instance's ball is tighter than its world box)."""
    centre = (boxes[:, 0] + boxes[:, 1]) / 2
    radius = (boxes[:, 1, 0] - boxes[:, 0, 0]) / 2
    for i, (inner, t, r, s, _) in enumerate(peeled):
        if type(inner) is not Sphere:
            lo, hi = bounds_of(inner)
            centre[i] = t + s * (r @ ((lo + hi) / 2))
            radius[i] = s * float(np.linalg.norm(hi - lo)) / 2
    return centre, radius


def bounds_of(node: Node) -> np.ndarray:
    """node.bounds without the defensive copies: (lo, hi) rows, read only."""
    return box_of(node)
