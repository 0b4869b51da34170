"""A 2D uniform grid whose cells list the parts (edges, glyphs) near them, and the cap that
bounds the distance to every part a cell does not list (shaders/lib/grid2_cap.glsl)."""
from __future__ import annotations

import numpy as np


def list_in_cells(lo_parts: np.ndarray, hi_parts: np.ndarray, lo: np.ndarray, cell: float, dims: np.ndarray,
                  margin: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """List each part (its box: rows of ``lo_parts``, ``hi_parts``) in every cell of a 2D grid
    its box comes within ``margin`` of. Returns the entries sorted by cell (cell index, part
    index) and the cells' table (ncell, 4): first entry, count, and two zero columns."""
    c0 = np.clip(np.floor((lo_parts - margin - lo) / cell).astype(np.int64), 0, dims - 1)
    c1 = np.clip(np.floor((hi_parts + margin - lo) / cell).astype(np.int64), 0, dims - 1)
    span = c1 - c0 + 1
    counts = span.prod(axis=1)
    part = np.repeat(np.arange(len(lo_parts)), counts)
    start = np.concatenate([[0], np.cumsum(counts)[:-1]])
    local = np.arange(counts.sum()) - np.repeat(start, counts)
    x = np.repeat(c0[:, 0], counts) + local % np.repeat(span[:, 0], counts)
    y = np.repeat(c0[:, 1], counts) + local // np.repeat(span[:, 0], counts)
    cells = y * dims[0] + x
    order = np.argsort(cells, kind="stable")
    cells, part = cells[order], part[order]
    ncell = int(np.prod(dims))
    count = np.bincount(cells, minlength=ncell)
    table = np.zeros((ncell, 4))
    table[:, 0], table[:, 1] = np.concatenate([[0], np.cumsum(count)[:-1]]), count
    return cells, part, table


def cell_cap(q: np.ndarray, lo: np.ndarray, cell: float, dims: np.ndarray, margin: float) -> np.ndarray:
    """The twin of shaders/lib/grid2_cap.glsl: at (..., 2) points, how far at least every part
    not listed in the (clamped) cell of a 2D grid lies, when lists hold all parts within
    ``margin`` of their cell."""
    rel = np.clip(np.floor((q - lo) / cell), 0, dims - 1)
    cell_lo = lo + rel * cell
    outside = np.maximum(np.maximum(cell_lo - q, q - (cell_lo + cell)), 0.0)
    half = 0.5 * dims * cell
    k = np.abs(q - (lo + half)) - half
    box = np.hypot(*np.moveaxis(np.maximum(k, 0.0), -1, 0)) + np.minimum(k.max(axis=-1), 0.0)
    return np.maximum(margin - np.hypot(*np.moveaxis(outside, -1, 0)), box)
