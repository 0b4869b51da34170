"""Text as a 2D shape: the exact signed distance to a font's glyph outlines.

The outlines (sdfgl.nodes.text_font: quadratic Bezier pieces and line segments, cubics
split into quadratics within 1e-7 em) are data, not code: the shader loops over the
placed glyphs in one data table and over each glyph's pieces in another, so a long
string compiles as fast as one letter; a text of many glyphs lists them per cell of a 2D
grid (sdfgl.compiler.data.textgrid), exact in sign and exact in distance below the grid's
cap. Otherwise a glyph whose bounding box (of its control
points) is farther than the nearest piece found so far is skipped, and so is a group of
16 consecutive glyphs whose joint box is (the distance to one outline point per group
bounds it first): a point outside a glyph's box has winding number 0 for it, so only the
distance could change, and it cannot. The twin computes the same minimum over all pieces. The distance to a quadratic is Inigo Quilez's closed form (MIT) polished by two
Newton steps (shaders/lib/sd_bezier.glsl); the sign is the nonzero winding number of a
ray towards +x, so counters (o, e, A) are holes.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..errors import ParameterError
from ..values import validate as v
from .base import BOUND, EXACT
from .bezier import quadratic_distance2
from .layouts import layout
from .shapes2d import Shape2D
from .text_font import DEFAULT_FONT, LINE, QUAD, load_font
from .text_font import layout as place_glyphs

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.data.textgrid import TextGrid
    from ..compiler.emitter import Emitter

ALIGNS = ("left", "center", "right")
CHUNK = 8192  # points per block in the float64 twin
GROUP = 16  # consecutive placed glyphs per group (one box) in the shader


def segment_distance2(p: np.ndarray, a: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Squared distances from points p to segments a -> c (arrays (..., 2), broadcast)."""
    pa, ba = p - a, c - a
    h = np.clip(np.sum(pa * ba, axis=-1) / np.sum(ba * ba, axis=-1), 0.0, 1.0)
    e = pa - ba * h[..., None]
    return np.sum(e * e, axis=-1)


def crossings(p: np.ndarray, pieces: np.ndarray, kinds: np.ndarray) -> np.ndarray:
    """Winding number (M,) of the pieces (S, 3, 2; each monotonic in y) about points p (M, 2):
    signed crossings of the ray from p towards +x, half-open in y."""
    a, b, c = pieces[:, 0], pieces[:, 1], pieces[:, 2]
    py, px = p[:, 1:2], p[:, 0:1]
    hit = (a[:, 1] <= py) != (c[:, 1] <= py)
    alpha, beta, gamma = a[:, 1] - 2 * b[:, 1] + c[:, 1], 2 * (b[:, 1] - a[:, 1]), a[:, 1] - py
    with np.errstate(invalid="ignore", divide="ignore"):
        root = np.sqrt(np.maximum(beta * beta - 4 * alpha * gamma, 0.0))
        qq = -0.5 * (beta + np.where(beta >= 0, root, -root))
        t1 = np.where(alpha != 0, qq / alpha, np.inf)
        t2 = np.where(qq != 0, gamma / qq, 0.0)
        tq = np.clip(np.where(np.abs(t2 - 0.5) <= np.abs(t1 - 0.5), t2, t1), 0.0, 1.0)
        tl = np.clip((py - a[:, 1]) / (c[:, 1] - a[:, 1]), 0.0, 1.0)
    t = np.where(kinds == QUAD, tq, tl)
    x = (1 - t) ** 2 * a[:, 0] + 2 * t * (1 - t) * b[:, 0] + t * t * c[:, 0]
    x = np.where(kinds == QUAD, x, a[:, 0] + t * (c[:, 0] - a[:, 0]))
    up = np.where(c[:, 1] > a[:, 1], 1, -1)
    return np.sum(np.where(hit & (x > px), up, 0), axis=-1)


class Text(Shape2D):
    """A string set in a font: the exact signed distance to its glyph outlines (2D)."""

    kind = "text"
    costly = True

    def __init__(self, string: str, font: str | None = None, size: float = 1.0, align: str = "left") -> None:
        if not isinstance(string, str) or not string:
            raise ParameterError(f"{self.kind}: 'string' must be a non-empty string, got {string!r}")
        if font is not None and not isinstance(font, str):
            raise ParameterError(f"{self.kind}: 'font' must be a font file path (a string) or None, got "
                                 f"{type(font).__name__}")
        s = v.scalar(self.kind, "size", size, positive=True)
        v.fixed(self.kind, "the outlines are data scaled by it", size=s)
        if align not in ALIGNS:
            raise ParameterError(f"{self.kind}: 'align' must be one of {', '.join(ALIGNS)}, got {align!r}")
        f = load_font(font)
        placed = place_glyphs(string.replace("\r\n", "\n"), f, float(s), align)
        glyphs: dict[str, int] = {}
        pieces, kinds, spans, boxes, offsets = [], [], [], [], []
        for name, x, y in placed:
            pc, kd = f.outline(name)
            if not len(pc):
                continue  # a space: advance only
            if name not in glyphs:
                glyphs[name] = len(spans)
                spans.append((sum(len(k) for k in kinds), len(kd)))
                pieces.append(pc * float(s))
                kinds.append(kd)
            i = glyphs[name]
            local = pieces[i].reshape(-1, 2)
            boxes.append(np.concatenate([local.min(axis=0) + (x, y), local.max(axis=0) + (x, y)]))
            offsets.append((i, x, y))
        if not offsets:
            raise ParameterError(f"{self.kind}: {string!r} has no visible glyph in font {f.name!r}")
        super().__init__(string=string, font=font if font is not None else DEFAULT_FONT, size=s, align=align)
        self.pieces = np.concatenate(pieces)  # (n, 3, 2) scene units, glyph-local
        self.kinds = np.concatenate(kinds)
        self.spans = np.array(spans)  # per distinct glyph: first piece, count
        self.boxes = np.array(boxes)  # per placed glyph: lo.xy, hi.xy
        self.placed = offsets  # per placed glyph: (distinct glyph, x, y)

    def label(self) -> str:
        """ASCII on one line (escapes as Python's ascii()): labels go into GLSL comments."""
        p = self.params
        return f"text({ascii(p['string'])}, font={ascii(p['font'])}, size={float(p['size']):g}, align={p['align']})"

    def expr(self, em: "Emitter", q: str) -> str:
        texels = np.zeros((len(self.pieces), 2, 4))
        texels[:, 0, :2], texels[:, 0, 2:] = self.pieces[:, 0], self.pieces[:, 1]
        texels[:, 1, :2], texels[:, 1, 2] = self.pieces[:, 2], self.kinds
        first = em.table(texels.reshape(-1, 4))
        table = np.zeros((len(self.placed), 2, 4))
        table[:, 0] = self.boxes
        for k, (i, x, y) in enumerate(self.placed):
            start, count = self.spans[i]
            table[k, 1] = (first + 2 * start, count, x, y)
        glyphs = em.table(table.reshape(-1, 4))
        grid = self.grid
        cap = em.distance_cap.get(id(self), "3.0e38")  # what the caller needs of it at most (compiler.guards)
        if grid is not None:  # a long text: the glyphs near each cell of a 2D grid
            em.require("sd2_text_grid")
            return (f"sd2TextGrid({q}, {grid.defines(em, em.table(grid.cells), em.table(grid.entries))}, {glyphs}, "
                    f"{cap})")
        em.require("sd2_text")
        n = len(self.placed)
        groups = np.zeros(((n + GROUP - 1) // GROUP, 2, 4))
        for j, g0 in enumerate(range(0, n, GROUP)):
            box = self.boxes[g0:g0 + GROUP]
            i, x, y = self.placed[g0]
            groups[j, 0] = (*box[:, :2].min(axis=0), *box[:, 2:].max(axis=0))
            point = self.pieces[self.spans[i][0], 0] + (x, y)  # on an outline: bounds the distance
            groups[j, 1] = (g0, min(GROUP, n - g0), *point)
        return f"sd2Text({q}, {em.table(groups.reshape(-1, 4))}, {len(groups)}, {glyphs}, {cap})"

    @property
    def exactness(self) -> str:  # type: ignore[override]
        """Exact, or a bound where a long text's glyph grid caps the distance far from the glyphs."""
        return BOUND if self.grid is not None else EXACT

    @property
    def grid(self) -> "TextGrid | None":
        """The glyph grid of a long text (sdfgl.compiler.data.textgrid), else None."""
        if "_grid" not in self.__dict__:
            build = layout("text")
            self.__dict__["_grid"] = build(self.boxes) if build is not None else None
        return self.__dict__["_grid"]

    def distance2(self, q: np.ndarray) -> np.ndarray:
        pts = np.asarray(q, dtype=np.float64).reshape(-1, 2)
        out = np.empty(len(pts))
        for s in range(0, len(pts), CHUNK):
            out[s:s + CHUNK] = self._block(pts[s:s + CHUNK])
        grid = self.grid
        if grid is not None:
            out = np.sign(out) * np.minimum(np.abs(out), grid.cap(pts))
        return out.reshape(np.shape(q)[:-1])

    def _block(self, p: np.ndarray) -> np.ndarray:
        d2 = np.full(len(p), np.inf)
        wind = np.zeros(len(p), dtype=np.int64)
        for box, (i, x, y) in zip(self.boxes, self.placed):
            k = np.maximum(np.maximum(box[:2] - p, p - box[2:]), 0.0)
            bd2 = np.sum(k * k, axis=-1)
            inside = bd2 == 0
            sel = inside | (bd2 < d2)
            if not sel.any():
                continue
            best = self._nearest2(p[sel] - (x, y), *self._glyph(i))
            d2[sel] = np.minimum(d2[sel], best)
            if inside.any():
                wind[inside] += crossings(p[inside] - (x, y), *self._glyph(i))
        return np.where(wind != 0, -1.0, 1.0) * np.sqrt(d2)

    def _glyph(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        start, count = self.spans[i]
        return self.pieces[start:start + count], self.kinds[start:start + count]

    @staticmethod
    def _nearest2(p: np.ndarray, pieces: np.ndarray, kinds: np.ndarray) -> np.ndarray:
        """Squared distance from each point (M, 2) to the nearest piece: only the pieces whose
        box comes nearer than the nearest piece end are solved (the same minimum)."""
        lo, hi = pieces.min(axis=1), pieces.max(axis=1)
        k = np.maximum(np.maximum(lo - p[:, None], p[:, None] - hi), 0.0)
        box2 = np.sum(k * k, axis=-1)
        ends = np.sum((p[:, None] - pieces[:, 0]) ** 2, axis=-1).min(axis=1)
        pt, pc = np.nonzero(box2 <= ends[:, None])
        quad = kinds[pc] == QUAD
        d = np.empty(len(pt))
        d[quad] = quadratic_distance2(p[pt[quad]], *np.moveaxis(pieces[pc[quad]], 1, 0))
        d[~quad] = segment_distance2(p[pt[~quad]], pieces[pc[~quad], 0], pieces[pc[~quad], 2])
        best = ends.copy()
        np.minimum.at(best, pt, d)
        return best

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        """The glyphs' box, or a long text's grid box around it (its capped field can be below
        the distance to the glyphs' box between the two)."""
        lo, hi = self.boxes[:, :2].min(axis=0), self.boxes[:, 2:].max(axis=0)
        grid = self.grid
        if grid is None:
            return lo, hi
        glo, ghi = grid.box()
        return np.minimum(lo, glo), np.maximum(hi, ghi)


def text(string: str, font: str | None = None, size: float = 1.0, align: str = "left") -> Text:
    """A string set in a font, as a 2D shape in the XY plane (make it solid with
    :func:`extrude` or :func:`revolve`).

    Args:
        string: the text, non-empty; ``\\n`` starts a new line. Every character must be in
            the font.
        font: a TTF or OTF file path, or None (or ``"DejaVuSans"``) for DejaVu Sans, which
            ships with sdfgl (Bitstream Vera licence). Needs fontTools:
            ``pip install 'sdfgl[text]'``.
        size: the em size (font size) in scene units, > 0.
        align: ``"left"`` (lines start at x = 0), ``"center"`` or ``"right"`` (lines end at x = 0).

    The first line's baseline lies on y = 0, later lines one line height (the font's
    ascender - descender + line gap) lower each. Glyphs are spaced by their advances and
    the font's pair kerning (its kern table, else the GPOS kern feature's pair
    adjustments). Exact in 2D: the distance to the quadratic outline curves is solved in
    closed form, cubic curves are split into quadratics within 1e-7 em, and the sign is
    the nonzero winding number (where two glyphs' outlines overlap the distance counts
    the hidden outline too, a bound). A text of 48 or more glyphs lists them per cell of a
    grid: the distance is then exact below the grid's cap (about half a glyph) and a bound
    beyond it (``exactness`` is ``"bound"``).

    Example:
        >>> sg.extrude(sg.text("sdfgl", size=0.3), 0.05).exactness
        'exact'
    """
    return Text(string, font, size, align)
