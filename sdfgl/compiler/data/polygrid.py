"""A polygon with many vertices as data: its edges listed per cell of a 2D uniform grid.

A point looks at the edges listed in its cell only (those whose bounds come within one
margin of the cell), so a polygon of 10 000 vertices costs about what one of a few
dozen does. The sign comes from a reference point of the cell (its centre unless that lies
on or near an edge; inside or not, found once in float64) and the listed edges the segment
from it to the point crosses (it stays in the cell, so every edge it crosses is listed); outside the grid the point is outside the
polygon. The magnitude is min(listed edges, cap) with the cap of sdfgl.compiler.data.grid: a
distance bound equal to the exact distance wherever that is below the cap. The float64
twin computes sign * min(|exact distance|, cap), the same number.
"""
from __future__ import annotations

import numpy as np

from .grid2 import cell_cap, list_in_cells

GRID_VERTICES = 64  # polygons with at least this many vertices use the grid
MAX_DIMS = 256


# Where in its cell the point a cell's sign is taken at may sit: candidate k is the fraction
# fract(1/2 + k * REFERENCE_STEP) of the cell (k = 0: its centre), stored per cell so the
# shader computes the same point. A candidate closer than REFERENCE_MARGIN cells to a listed
# edge is passed over: a reference point on an edge (polygons on round coordinates put cell
# centres on edges) has no well-defined side, and the shader's crossing test and the
# scanline that classified it would disagree.
REFERENCE_STEP = np.array([0.6180339887, 0.7548776662])
REFERENCE_CANDIDATES = 16
REFERENCE_MARGIN = 0.02


def reference_fractions() -> np.ndarray:
    """(REFERENCE_CANDIDATES, 2): each candidate reference point as a fraction of its cell."""
    k = np.arange(REFERENCE_CANDIDATES)[:, None]
    return np.mod(0.5 + k * REFERENCE_STEP, 1.0)


def _segment_distance(q: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab, w = b - a, q - a
    t = np.clip((w * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-300), 0.0, 1.0)
    return np.hypot(*np.moveaxis(w - ab * t[..., None], -1, 0))


def _reference_choice(cells: np.ndarray, edge: np.ndarray, a: np.ndarray, b: np.ndarray, lo: np.ndarray,
                      cell: float, dims: np.ndarray) -> np.ndarray:
    """Per cell, the first candidate at least REFERENCE_MARGIN cells from every listed edge
    (``cells``/``edge``: the sorted (cell, edge) entries); unlisted edges are a cell away."""
    ncell = int(np.prod(dims))
    choice = np.full(ncell, -1)
    cell_lo = lo + np.stack([cells % dims[0], cells // dims[0]], axis=-1) * cell
    for k, frac in enumerate(reference_fractions()):
        d = _segment_distance(cell_lo + frac * cell, a[edge], b[edge])
        near = np.zeros(ncell, dtype=bool)
        near[cells[d < REFERENCE_MARGIN * cell]] = True
        choice[(choice < 0) & ~near] = k
    return np.maximum(choice, 0)  # no candidate clear of every edge: a cell crowded by edges


def _inside(a: np.ndarray, b: np.ndarray, lo: np.ndarray, cell: float, dims: np.ndarray,
            choice: np.ndarray) -> np.ndarray:
    """Per cell, is its reference point inside the polygon (even-odd rule, one half-open
    scanline per row of cells and candidate)."""
    fracs = reference_fractions()
    out = np.zeros(int(np.prod(dims)), dtype=bool)
    index = np.arange(out.size)
    key = (index // dims[0]) * REFERENCE_CANDIDATES + choice
    order = np.argsort(key, kind="stable")
    keys, starts = np.unique(key[order], return_index=True)
    for key_here, sel in zip(keys, np.split(order, starts[1:])):
        j, k = divmod(int(key_here), REFERENCE_CANDIDATES)
        y = lo[1] + (j + fracs[k, 1]) * cell
        hit = (a[:, 1] <= y) != (b[:, 1] <= y)
        if not hit.any():
            continue
        pa, pb = a[hit], b[hit]
        x = pa[:, 0] + (y - pa[:, 1]) * (pb[:, 0] - pa[:, 0]) / (pb[:, 1] - pa[:, 1])
        xs = lo[0] + (sel % dims[0] + fracs[k, 0]) * cell
        out[sel] = np.searchsorted(np.sort(x), xs) % 2 == 1
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
        cells, edge, self.cells = list_in_cells(elo, ehi, lo, cell, self.dims, self.margin)
        choice = _reference_choice(cells, edge, a, b, lo, cell, self.dims)
        self.cells[:, 2] = _inside(a, b, lo, cell, self.dims, choice)
        self.cells[:, 3] = choice
        self.edges = np.concatenate([b[edge], a[edge]], axis=1)  # (from, to) per entry

    def box(self) -> tuple[np.ndarray, np.ndarray]:
        """The grid's box (lo, hi): outside it the capped field is at least the distance to it
        (inside, the cap may lie below the distance to the parts' own box)."""
        return self.lo, self.lo + self.dims * self.cell

    def cap(self, q: np.ndarray) -> np.ndarray:
        """Every unlisted edge is at least this far from the (..., 2) points."""
        return cell_cap(q, self.lo, self.cell, self.dims, self.margin)

    def defines(self, em: "object", name: str, cells: int, edges: int) -> str:
        """The GLSL constants of this grid (its tables are at data texels cells, edges)."""
        num = em.num  # type: ignore[attr-defined]
        return (f"vec2({num(self.lo[0])}, {num(self.lo[1])}), {num(self.cell)}, "
                f"ivec2({int(self.dims[0])}, {int(self.dims[1])}), {cells}, {edges}")


def build(vertices: np.ndarray) -> PolygonGrid | None:
    """The edge grid of a polygon with at least GRID_VERTICES vertices, else None."""
    return PolygonGrid(vertices) if len(vertices) >= GRID_VERTICES else None
