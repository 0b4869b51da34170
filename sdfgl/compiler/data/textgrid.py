"""A long text's placed glyphs listed per cell of a 2D uniform grid.

A point looks only at the glyphs listed in its cell (those whose box comes within one
margin of the cell), so a page of a thousand glyphs costs about what a few do. The sign is
exact: the winding number only changes inside a glyph's box, and a box holding the point
meets its cell, so it is listed. The magnitude is min(listed glyphs' outlines, cap) with the
cap of sdfgl.compiler.data.grid2: the exact distance wherever that is below the cap (about
half a cell), a bound beyond. The float64 twin computes sign * min(|exact distance|, cap).
Cells of a fifth of a glyph keep a point's work to the one or two glyphs near it (cells of a
glyph's size list about seven); the smaller cap only shortens the steps in the gaps between
glyphs.
"""
from __future__ import annotations

import numpy as np

from .grid2 import cell_cap, list_in_cells

GRID_GLYPHS = 48  # texts with at least this many placed glyphs use the grid
MAX_DIMS = 256
MARGIN = 0.5  # of a cell: lists hold the glyphs whose box comes this near the cell
CELL = 0.2  # a cell's side, of a glyph's size (or of the page's area per glyph, if larger)


class TextGrid:
    """Cells over a text's bounds listing the placed glyphs near each."""

    def __init__(self, boxes: np.ndarray) -> None:
        lo, hi = boxes[:, :2].min(axis=0), boxes[:, 2:].max(axis=0)
        ext = np.maximum(hi - lo, 1e-9)
        glyph = float(np.median((boxes[:, 2:] - boxes[:, :2]).max(axis=1)))
        cell = max(CELL * glyph, CELL * float(np.sqrt(ext[0] * ext[1] / len(boxes))), float(ext.max()) / MAX_DIMS)
        self.dims = np.minimum(np.ceil(ext / cell).astype(int), MAX_DIMS)
        self.lo, self.cell, self.margin = lo, cell, MARGIN * cell
        _, glyph_of, self.cells = list_in_cells(boxes[:, :2], boxes[:, 2:], lo, cell, self.dims, self.margin)
        self.entries = np.zeros((len(glyph_of), 4))
        self.entries[:, 0] = glyph_of

    def box(self) -> tuple[np.ndarray, np.ndarray]:
        """The grid's box (lo, hi): outside it the capped field is at least the distance to it
        (inside, the cap may lie below the distance to the parts' own box)."""
        return self.lo, self.lo + self.dims * self.cell

    def cap(self, q: np.ndarray) -> np.ndarray:
        """Every unlisted glyph is at least this far from the (..., 2) points."""
        return cell_cap(q, self.lo, self.cell, self.dims, self.margin)

    def defines(self, em: "object", cells: int, entries: int) -> str:
        """The GLSL arguments of this grid (its tables are at data texels cells, entries)."""
        num = em.num  # type: ignore[attr-defined]
        return (f"vec2({num(self.lo[0])}, {num(self.lo[1])}), {num(self.cell)}, "
                f"ivec2({int(self.dims[0])}, {int(self.dims[1])}), {num(self.margin)}, {cells}, {entries}")


def build(boxes: np.ndarray) -> TextGrid | None:
    """The glyph grid of a text with at least GRID_GLYPHS placed glyphs (``boxes``: (n, 4) lo.xy,
    hi.xy each), else None."""
    return TextGrid(boxes) if len(boxes) >= GRID_GLYPHS else None
