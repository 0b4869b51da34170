"""A polygon with many vertices as data: its edges listed per cell of a 2D uniform grid.

A point looks at the edges listed in its cell only (those whose bounds come within one
margin of the cell), so a polygon of 10 000 vertices costs about what one of a few
dozen does. The sign comes from the cell centre (inside or not, found once in float64)
and the listed edges the segment from the centre to the point crosses (it stays in the
cell, so every edge it crosses is listed); outside the grid the point is outside the
polygon. The magnitude is min(listed edges, cap) with the cap of sdfgl.compiler.data.grid: a
distance bound equal to the exact distance wherever that is below the cap. The float64
twin computes sign * min(|exact distance|, cap), the same number.
"""
from __future__ import annotations

import numpy as np

GRID_VERTICES = 64  # polygons with at least this many vertices use the grid
MAX_DIMS = 256


def _inside_centres(a: np.ndarray, b: np.ndarray, lo: np.ndarray, cell: float, dims: np.ndarray) -> np.ndarray:
    """(rows, cols) booleans: is each cell centre inside the polygon (even-odd rule, one
    scanline per row of cells)."""
    xs_c = lo[0] + (np.arange(dims[0]) + 0.5) * cell
    out = np.zeros((dims[1], dims[0]), dtype=bool)
    for j in range(dims[1]):
        y = lo[1] + (j + 0.5) * cell
        hit = (a[:, 1] <= y) != (b[:, 1] <= y)
        if not hit.any():
            continue
        pa, pb = a[hit], b[hit]
        x = pa[:, 0] + (y - pa[:, 1]) * (pb[:, 0] - pa[:, 0]) / (pb[:, 1] - pa[:, 1])
        out[j] = np.searchsorted(np.sort(x), xs_c) % 2 == 1
    return out


class PolygonGrid:
    """Cells over a polygon's bounds listing nearby edges."""

    def __init__(self, v: np.ndarray) -> None:
        lo, hi = v.min(axis=0), v.max(axis=0)
        ext = np.maximum(hi - lo, 1e-9)
        n = len(v)
        cell = max(float(np.sqrt(ext[0] * ext[1] / n)), float(ext.max()) / MAX_DIMS)  # ~1 edge a cell
        self.dims = np.minimum(np.ceil(ext / cell).astype(int), MAX_DIMS)
        self.lo, self.cell, self.margin = lo, cell, cell
        a, b = v, np.roll(v, 1, axis=0)  # edge i runs from vertex i-1 to vertex i
        elo, ehi = np.minimum(a, b), np.maximum(a, b)
        c0 = np.clip(np.floor((elo - self.margin - lo) / cell).astype(np.int64), 0, self.dims - 1)
        c1 = np.clip(np.floor((ehi + self.margin - lo) / cell).astype(np.int64), 0, self.dims - 1)
        span = c1 - c0 + 1
        counts = span.prod(axis=1)
        edge = np.repeat(np.arange(n), counts)
        start = np.concatenate([[0], np.cumsum(counts)[:-1]])
        local = np.arange(counts.sum()) - np.repeat(start, counts)
        x = np.repeat(c0[:, 0], counts) + local % np.repeat(span[:, 0], counts)
        y = np.repeat(c0[:, 1], counts) + local // np.repeat(span[:, 0], counts)
        cells = y * self.dims[0] + x
        order = np.argsort(cells, kind="stable")
        cells, edge = cells[order], edge[order]
        ncell = int(np.prod(self.dims))
        count = np.bincount(cells, minlength=ncell)
        first = np.concatenate([[0], np.cumsum(count)[:-1]])
        self.cells = np.zeros((ncell, 4))
        self.cells[:, 0], self.cells[:, 1] = first, count
        self.cells[:, 2] = _inside_centres(a, b, lo, cell, self.dims).ravel()
        self.edges = np.concatenate([b[edge], a[edge]], axis=1)  # (from, to) per entry

    def cap(self, q: np.ndarray) -> np.ndarray:
        """Every unlisted edge is at least this far from the (..., 2) points."""
        rel = np.clip(np.floor((q - self.lo) / self.cell), 0, self.dims - 1)
        cell_lo = self.lo + rel * self.cell
        outside = np.maximum(np.maximum(cell_lo - q, q - (cell_lo + self.cell)), 0.0)
        half = 0.5 * self.dims * self.cell
        k = np.abs(q - (self.lo + half)) - half
        box = np.hypot(*np.moveaxis(np.maximum(k, 0.0), -1, 0)) + np.minimum(k.max(axis=-1), 0.0)
        return np.maximum(self.margin - np.hypot(*np.moveaxis(outside, -1, 0)), box)

    def defines(self, em: "object", name: str, cells: int, edges: int) -> str:
        """The GLSL constants of this grid (its tables are at data texels cells, edges)."""
        num = em.num  # type: ignore[attr-defined]
        return (f"vec2({num(self.lo[0])}, {num(self.lo[1])}), {num(self.cell)}, "
                f"ivec2({int(self.dims[0])}, {int(self.dims[1])}), {cells}, {edges}")


def build(vertices: np.ndarray) -> PolygonGrid | None:
    """The edge grid of a polygon with at least GRID_VERTICES vertices, else None."""
    return PolygonGrid(vertices) if len(vertices) >= GRID_VERTICES else None
