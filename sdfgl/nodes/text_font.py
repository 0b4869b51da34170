"""Glyph outlines and text layout from a font file (TTF or OTF), through fontTools.

A glyph becomes a list of curve pieces, each a quadratic Bezier curve (A, B, C) or a
line segment (A, C; B is the midpoint), in em units with the baseline on y = 0:

- TrueType quadratics are kept exactly;
- cubic curves (CFF/OTF fonts) are split into quadratics: each of n equal pieces of the
  cubic is replaced by the quadratic with control point (3 (P1 + P2) - P0 - P3) / 4,
  whose distance from the cubic piece is at most sqrt(3)/36 |P3 - 3 P2 + 3 P1 - P0|; n is
  the smallest that brings this under :data:`CUBIC_TOLERANCE` (1e-7 em);
- every quadratic is split at its y extremum, so each piece is monotonic in y and the
  winding number (nonzero rule) can count crossings of a horizontal ray exactly as for
  a polygon (half-open in y, so a ray through a vertex counts once).

Layout: glyph advances from ``hmtx``, pair kerning from the font's ``kern`` table
(format 0) where it has one, else the GPOS pair adjustments of its ``kern`` feature
(PairPos formats 1 and 2, the first glyph's x advance); ``\\n`` starts a new line one
``hhea`` line height (ascender - descender + line gap) lower.
"""
from __future__ import annotations

import functools
import math
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..extras import require_extra

DEFAULT_FONT = "DejaVuSans"
"""The name of the font that ships with sdfgl (DejaVu Sans, Bitstream Vera licence)."""
FONT_DIR = Path(__file__).resolve().parents[1] / "fonts"
CUBIC_TOLERANCE = 1e-7
"""Largest distance (in em) between a cubic outline curve and the quadratics that replace it."""
LINE = 0.0  # piece kinds, as stored in the data texture
QUAD = 1.0


def font_path(font: str | None) -> Path:
    """The file of ``font``: None or :data:`DEFAULT_FONT` is the font shipped with sdfgl,
    anything else a path to a TTF/OTF file."""
    if font is None or font == DEFAULT_FONT:
        return FONT_DIR / f"{DEFAULT_FONT}.ttf"
    path = Path(font).expanduser()
    if not path.is_file():
        raise ParameterError(f"text: font file {str(font)!r} not found (give a TTF/OTF path, or font=None for "
                             f"the default font {DEFAULT_FONT!r})")
    return path


def _cubic_pieces(p0: np.ndarray, p1: np.ndarray, p2: np.ndarray, p3: np.ndarray) -> list[np.ndarray]:
    """Quadratics (3, 2) within CUBIC_TOLERANCE of the cubic p0..p3 (em units)."""
    d3 = float(np.linalg.norm(p3 - 3 * p2 + 3 * p1 - p0))
    n = max(1, math.ceil((math.sqrt(3) / 36 * d3 / CUBIC_TOLERANCE) ** (1 / 3)))
    def point(t: float) -> np.ndarray:
        s = 1 - t
        return s ** 3 * p0 + 3 * s * s * t * p1 + 3 * s * t * t * p2 + t ** 3 * p3

    def tangent(t: float) -> np.ndarray:
        s = 1 - t
        return 3 * (s * s * (p1 - p0) + 2 * s * t * (p2 - p1) + t * t * (p3 - p2))
    out = []
    for i in range(n):
        t0, t1 = i / n, (i + 1) / n
        a, d = point(t0), point(t1)
        h = (t1 - t0) / 3  # the piece's own cubic control points, then its midpoint quadratic
        b, c = a + h * tangent(t0), d - h * tangent(t1)
        out.append(np.array([a, (3 * (b + c) - a - d) / 4, d]))
    return out


def _monotonic(q: np.ndarray) -> list[np.ndarray]:
    """The quadratic q (3, 2) split at its y extremum (de Casteljau), if that is inside."""
    a, b, c = q
    den = a[1] - 2 * b[1] + c[1]
    t = (a[1] - b[1]) / den if den != 0 else -1.0
    if not 0.0 < t < 1.0:
        return [q]
    ab, bc = a + t * (b - a), b + t * (c - b)
    m = ab + t * (bc - ab)
    ab[1] = bc[1] = m[1]  # the split point is the extremum: both halves stay monotonic in y
    return [np.array([a, ab, m]), np.array([m, bc, c])]


def _outline_pen(glyphset: Any, upm: float) -> Any:
    """A fontTools pen (a BasePen) that collects (A, B, C, kind) pieces in em units in
    ``.pieces`` (fontTools is imported here: it is an optional extra)."""
    from fontTools.pens.basePen import BasePen

    class Pen(BasePen):
        def __init__(self) -> None:
            super().__init__(glyphset)
            self.pieces: list[tuple[np.ndarray, float]] = []
            self.start: np.ndarray | None = None

        def _p(self, pt: Any) -> np.ndarray:
            return np.array(pt, dtype=np.float64) / upm

        def _moveTo(self, pt: Any) -> None:
            self.start = self._p(pt)

        def _lineTo(self, pt: Any) -> None:
            a, c = self._p(self._getCurrentPoint()), self._p(pt)
            if np.any(a != c):
                self.pieces.append((np.array([a, (a + c) / 2, c]), LINE))

        def _qCurveToOne(self, pt1: Any, pt2: Any) -> None:
            q = np.array([self._p(self._getCurrentPoint()), self._p(pt1), self._p(pt2)])
            self._quad(q)

        def _quad(self, q: np.ndarray) -> None:
            a, b, c = q
            if abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) <= 1e-14 and \
                    np.dot(b - a, c - b) >= 0:  # collinear, control point between: a line
                if np.any(a != c):
                    self.pieces.append((np.array([a, (a + c) / 2, c]), LINE))
                return
            for piece in _monotonic(q):
                self.pieces.append((piece, QUAD))

        def _curveToOne(self, pt1: Any, pt2: Any, pt3: Any) -> None:
            p0 = self._p(self._getCurrentPoint())
            for q in _cubic_pieces(p0, self._p(pt1), self._p(pt2), self._p(pt3)):
                self._quad(q)

        def _closePath(self) -> None:
            cur = self._getCurrentPoint()
            if cur is not None and self.start is not None and np.any(self._p(cur) != self.start):
                a = self._p(cur)
                self.pieces.append((np.array([a, (a + self.start) / 2, self.start]), LINE))

        _endPath = _closePath  # an open contour is closed: a glyph's outline bounds an area

    return Pen()


class Font:
    """A font file's outlines, advances, kerning and line height (em units).

    Args:
        path: a TTF or OTF file.
    """

    def __init__(self, path: Path) -> None:
        require_extra("text", "fontTools", purpose="sg.text")
        from fontTools.ttLib import TTFont
        try:
            self.tt = TTFont(str(path), lazy=True)
            self.cmap: dict[int, str] = self.tt.getBestCmap() or {}
            self.glyphset = self.tt.getGlyphSet()
            self.upm = float(self.tt["head"].unitsPerEm)
            hhea = self.tt["hhea"]
            self.line_height = (hhea.ascent - hhea.descent + hhea.lineGap) / self.upm
            self.hmtx = self.tt["hmtx"]
        except Exception as exc:  # fontTools raises many kinds on a file that is not a font
            raise ParameterError(f"text: cannot read font file {str(path)!r}: {type(exc).__name__}: {exc}") from None
        self.path = path
        self.name = path.stem
        self.kerning = self._kern_table() or self._gpos_pairs()
        self._outlines: dict[str, tuple[np.ndarray, np.ndarray]] = {}

    def glyph_name(self, ch: str) -> str:
        """The glyph of character ``ch``; a clear error if the font has none."""
        name = self.cmap.get(ord(ch))
        if name is None:
            raise ParameterError(f"text: the font {self.name!r} ({self.path}) has no glyph for {ch!r} "
                                 f"(U+{ord(ch):04X})")
        return name

    def advance(self, glyph: str) -> float:
        """The glyph's advance width, em."""
        return self.hmtx[glyph][0] / self.upm

    def kern(self, left: str, right: str) -> float:
        """Pair kerning between two glyphs, em (0 where the font has none)."""
        return self.kerning.get((left, right), 0.0)

    def outline(self, glyph: str) -> tuple[np.ndarray, np.ndarray]:
        """((n, 3, 2) pieces A, B, C in em; (n,) kinds LINE or QUAD) of the glyph."""
        if glyph not in self._outlines:
            pen = _outline_pen(self.glyphset, self.upm)
            try:
                self.glyphset[glyph].draw(pen)
            except Exception as exc:
                raise ParameterError(f"text: cannot read glyph {glyph!r} of font {str(self.path)!r}: "
                                     f"{type(exc).__name__}: {exc}") from None
            pieces = np.array([p for p, _ in pen.pieces]).reshape(-1, 3, 2)
            kinds = np.array([k for _, k in pen.pieces], dtype=np.float64)
            self._outlines[glyph] = (pieces, kinds)
        return self._outlines[glyph]

    def _kern_table(self) -> dict[tuple[str, str], float]:
        if "kern" not in self.tt:
            return {}
        out: dict[tuple[str, str], float] = {}
        for table in getattr(self.tt["kern"], "kernTables", []):
            if getattr(table, "format", None) == 0:
                for pair, value in table.kernTable.items():
                    out.setdefault(pair, value / self.upm)
        return out

    def _gpos_pairs(self) -> dict[tuple[str, str], float]:
        if "GPOS" not in self.tt:
            return {}
        gpos = self.tt["GPOS"].table
        if gpos.FeatureList is None or gpos.LookupList is None:
            return {}
        lookups = sorted({i for rec in gpos.FeatureList.FeatureRecord if rec.FeatureTag == "kern"
                          for i in rec.Feature.LookupListIndex})
        out: dict[tuple[str, str], float] = {}
        for i in lookups:
            for sub in gpos.LookupList.Lookup[i].SubTable:
                sub = getattr(sub, "ExtSubTable", sub)
                if getattr(sub, "LookupType", 2) != 2 or not hasattr(sub, "Format"):
                    continue
                firsts = sub.Coverage.glyphs
                if sub.Format == 1:
                    for left, pairset in zip(firsts, sub.PairSet):
                        for rec in pairset.PairValueRecord:
                            x = getattr(rec.Value1, "XAdvance", 0) if rec.Value1 else 0
                            if x:
                                out.setdefault((left, rec.SecondGlyph), x / self.upm)
                elif sub.Format == 2:
                    c1, c2 = sub.ClassDef1.classDefs, sub.ClassDef2.classDefs
                    seconds: dict[int, list[str]] = {}
                    for g, k in c2.items():
                        seconds.setdefault(k, []).append(g)
                    for left in firsts:
                        row = sub.Class1Record[c1.get(left, 0)]
                        for k, rec in enumerate(row.Class2Record):
                            x = getattr(rec.Value1, "XAdvance", 0) if rec.Value1 else 0
                            if x and k in seconds:
                                for right in seconds[k]:
                                    out.setdefault((left, right), x / self.upm)
        return out


@functools.lru_cache(maxsize=16)
def _load(path: str, mtime: float) -> Font:
    return Font(Path(path))


def load_font(font: str | None) -> Font:
    """The font ``font`` names (None: the default), read once per file version."""
    path = font_path(font)
    return _load(str(path.resolve()), path.stat().st_mtime)


def layout(text: str, font: Font, size: float, align: str) -> list[tuple[str, float, float]]:
    """(glyph name, x, y) of each visible glyph, in scene units: the em is ``size``, the
    first line's baseline is y = 0, lines start (left), are centred (center) or end
    (right) at x = 0."""
    out: list[tuple[str, float, float]] = []
    for row, line in enumerate(text.split("\n")):
        names = [font.glyph_name(ch) for ch in line]
        xs, x = [], 0.0
        for i, g in enumerate(names):
            xs.append(x)
            x += font.advance(g) + (font.kern(g, names[i + 1]) if i + 1 < len(names) else 0.0)
        shift = {"left": 0.0, "center": -x / 2, "right": -x}[align]
        y = -row * font.line_height * size
        out += [(g, (gx + shift) * size, y) for g, gx in zip(names, xs)]
    return out
