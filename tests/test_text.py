"""sg.text: glyph outlines from a font file as an exact 2D signed distance.

The float64 twin is checked against an independent reference (a dense polyline of the
same outlines, read with fontTools' recording pen, with its own winding number), the GPU
against the twin, and the solid made from it renders, meshes watertight and saves.
"""
import numpy as np
import pytest

import sdfgl as sg
import sdfgl.extras
from sdfgl.nodes.text import Text
from sdfgl.nodes.text_font import CUBIC_TOLERANCE, DEFAULT_FONT, Font, font_path

fontTools = pytest.importorskip("fontTools")

EPS32 = float(np.finfo(np.float32).eps)


def cubic_font(path):
    """A CFF (cubic) OTF: 'o' as two cubic circles (outer and counter), 'c' open on the right,
    and GPOS pair kerning o-o of -100 units (em 1000)."""
    from fontTools.fontBuilder import FontBuilder
    from fontTools.pens.t2CharStringPen import T2CharStringPen

    def circle(pen, cx, cy, r, ccw):
        k = 0.5522847498 * r
        pts = [(cx + r, cy), (cx, cy + r), (cx - r, cy), (cx, cy - r)]
        if not ccw:
            pts = pts[::-1]
        pen.moveTo(pts[0])
        for i in range(4):
            a, b = pts[i], pts[(i + 1) % 4]
            ta = (-(a[1] - cy), a[0] - cx) if ccw else (a[1] - cy, -(a[0] - cx))
            tb = (-(b[1] - cy), b[0] - cx) if ccw else (b[1] - cy, -(b[0] - cx))
            pen.curveTo((a[0] + ta[0] * k / r, a[1] + ta[1] * k / r), (b[0] - tb[0] * k / r, b[1] - tb[1] * k / r), b)
        pen.closePath()

    def draw_o(pen):
        circle(pen, 300, 300, 280, True)
        circle(pen, 300, 300, 150, False)

    def draw_c(pen):
        pen.moveTo((500, 120))
        pen.curveTo((350, -60), (40, 40), (40, 300))
        pen.curveTo((40, 560), (350, 660), (500, 480))
        pen.lineTo((420, 420))
        pen.curveTo((300, 520), (160, 450), (160, 300))
        pen.curveTo((160, 150), (300, 80), (420, 180))
        pen.closePath()

    names = [".notdef", "o", "c", "space"]
    fb = FontBuilder(1000, isTTF=False)
    fb.setupGlyphOrder(names)
    fb.setupCharacterMap({ord("o"): "o", ord("c"): "c", 32: "space"})
    strings = {}
    for name, draw in ((".notdef", None), ("o", draw_o), ("c", draw_c), ("space", None)):
        pen = T2CharStringPen(600, None)
        if draw:
            draw(pen)
        strings[name] = pen.getCharString()
    fb.setupCFF("CubicTest", {"FullName": "CubicTest"}, strings, {})
    fb.setupHorizontalMetrics({n: (600, 0) for n in names})
    fb.setupHorizontalHeader(ascent=800, descent=-200)
    fb.setupNameTable({"familyName": "CubicTest", "styleName": "Regular"})
    fb.setupOS2(sTypoAscender=800, usWinAscent=800, usWinDescent=200)
    fb.setupPost()
    fb.addOpenTypeFeatures("feature kern { pos o o -100; } kern;")
    fb.save(str(path))
    return str(path)


def polyline_reference(node: sg.Shape2D, font: Font, pts: np.ndarray, spacing: float = 2e-4) -> np.ndarray:
    """Signed distance from pts to a dense polyline of the node's glyphs, sampled from the
    font's own drawing commands (fontTools' DecomposingRecordingPen) at most ``spacing`` em
    apart along each curve's control polygon (a chord of a curve of radius r then strays
    spacing^2 / 8r: 5e-7 em at r = 0.01 em), sign by the nonzero winding rule."""
    from fontTools.pens.basePen import decomposeQuadraticSegment, decomposeSuperBezierSegment
    from fontTools.pens.recordingPen import DecomposingRecordingPen
    from sdfgl.nodes.text_font import layout

    size = float(node.params["size"])
    polylines = []
    for name, x0, y0 in layout(node.params["string"], font, size, node.params["align"]):
        pen = DecomposingRecordingPen(font.glyphset)
        font.glyphset[name].draw(pen)
        cur = start = None
        line = []

        def ts(*ctrl):
            n = max(16, int(np.ceil(sum(np.linalg.norm(b - a) for a, b in zip(ctrl, ctrl[1:])) / font.upm / spacing)))
            return np.linspace(0, 1, n + 1)[1:, None]
        for op, args in pen.value:
            args = [np.array(a, dtype=float) if a is not None else None for a in args]
            if op == "moveTo":
                cur = start = args[0]
                line = [cur]
            elif op == "lineTo":
                cur = args[0]
                line.append(cur)
            elif op == "qCurveTo":
                for b, c in decomposeQuadraticSegment([tuple(a) for a in args]):
                    b, c = np.array(b), np.array(c)
                    t = ts(cur, b, c)
                    line.extend((1 - t) ** 2 * cur + 2 * t * (1 - t) * b + t * t * c)
                    cur = c
            elif op == "curveTo":
                for p1, p2, p3 in decomposeSuperBezierSegment([tuple(a) for a in args]):
                    p1, p2, p3 = np.array(p1), np.array(p2), np.array(p3)
                    t = ts(cur, p1, p2, p3)
                    line.extend((1 - t) ** 3 * cur + 3 * (1 - t) ** 2 * t * p1 + 3 * (1 - t) * t * t * p2 + t ** 3 * p3)
                    cur = p3
            elif op in ("closePath", "endPath"):
                line.append(start)
                polylines.append(np.array(line) / font.upm * size + (x0, y0))
    d2 = np.full(len(pts), np.inf)
    wind = np.zeros(len(pts), dtype=int)
    for poly in polylines:
        a, b = poly[:-1], poly[1:]
        for s in range(0, len(pts), 256):
            p = pts[s:s + 256, None, :]
            pa, ba = p - a, b - a
            h = np.clip(np.sum(pa * ba, -1) / np.maximum(np.sum(ba * ba, -1), 1e-300), 0, 1)
            d2[s:s + 256] = np.minimum(d2[s:s + 256], np.min(np.sum((pa - ba * h[..., None]) ** 2, -1), axis=1))
            up = (a[:, 1] <= p[..., 1]) & (b[:, 1] > p[..., 1])
            down = (a[:, 1] > p[..., 1]) & (b[:, 1] <= p[..., 1])
            side = ba[:, 0] * (p[..., 1] - a[:, 1]) - ba[:, 1] * (p[..., 0] - a[:, 0])
            wind[s:s + 256] += np.sum(up & (side > 0), axis=1) - np.sum(down & (side < 0), axis=1)
    return np.where(wind != 0, -1.0, 1.0) * np.sqrt(d2)


def near_points(node: sg.Shape2D, rng: np.random.Generator, n: int) -> np.ndarray:
    """Points over the text's box and just around it, half of them close to its outlines."""
    lo, hi = node.bounds2
    pad = 0.1 * float(node.params["size"])
    wide = rng.uniform(lo - pad, hi + pad, (n // 2, 2))
    pieces = node.pieces[rng.integers(0, len(node.pieces), n - n // 2)]
    i = rng.integers(0, len(node.placed), len(pieces))
    offset = np.array([node.placed[k][1:] for k in i])
    close = pieces[:, 0] + offset + rng.normal(scale=0.02 * pad, size=(len(pieces), 2))
    return np.concatenate([wide, close])


@pytest.mark.parametrize("string,align", [("sdfgl", "left"), ("AVo\nWe!", "center"), ("ÅÉß€", "right")])
@pytest.mark.slow
def test_twin_matches_a_dense_polyline_of_the_same_outlines(string, align):
    node = sg.text(string, size=1.0, align=align)
    pts = near_points(node, np.random.default_rng(1), 1500)
    ref = polyline_reference(node, Font(font_path(None)), pts)
    got = node.distance2(pts)
    assert np.abs(np.abs(got) - np.abs(ref)).max() <= 1e-5  # em = 1 here
    clear = np.abs(ref) > 1e-5
    assert np.array_equal(np.sign(got[clear]), np.sign(ref[clear]))


@pytest.mark.slow
def test_cubic_font_twin_matches_a_dense_polyline(tmp_path):
    path = cubic_font(tmp_path / "cubic.otf")
    node = sg.text("oc o", font=path, size=2.0)
    pts = near_points(node, np.random.default_rng(2), 1500)
    ref = polyline_reference(node, Font(font_path(path)), pts)
    got = node.distance2(pts)
    assert CUBIC_TOLERANCE <= 1e-7
    assert np.abs(np.abs(got) - np.abs(ref)).max() <= 1e-5 * 2.0
    clear = np.abs(ref) > 2e-5
    assert np.array_equal(np.sign(got[clear]), np.sign(ref[clear]))


def test_gpu_matches_twin(renderer, tmp_path):
    scenes = [sg.text("sdfgl", size=0.5), sg.text("Hello,\nwörld", size=0.3, align="center").rotate(20),
              sg.text("oco", font=cubic_font(tmp_path / "c.otf"), size=0.4, align="right"),
              sg.text("The quick brown fox\njumps over the lazy dog", size=0.1)]  # several groups of glyphs
    rng = np.random.default_rng(3)
    for shape in scenes:
        node = sg.extrude(shape, 0.1)
        lo, hi = node.bounds
        xy = near_points(shape, rng, 4000) if isinstance(shape, Text) else rng.uniform(lo[:2], hi[:2], (4000, 2))
        pts = np.concatenate([rng.uniform(lo - 0.1, hi + 0.1, (4000, 3)),
                              np.column_stack([xy, rng.uniform(-0.04, 0.04, len(xy))])])
        gpu = sg.evaluate(node, pts, renderer=renderer).astype(np.float64)
        ref = node.distance(pts)
        tol = 16 * EPS32 * (1 + np.abs(pts).max(axis=-1) + np.abs(ref))
        err = np.abs(gpu - ref)
        assert np.all(err <= tol), (shape.label(), err.max(), pts[np.argmax(err / tol)])


def test_o_has_a_hole_and_its_ring_is_inside(renderer):
    o = sg.text("o", size=1.0)
    lo, hi = o.bounds2
    centre = (lo + hi) / 2
    ring = np.array([lo[0] + 0.04, centre[1]])  # DejaVu's o stroke is ~0.09 em wide
    far = hi + 1.0
    d = o.distance2(np.array([centre, ring, far]))
    assert d[0] > 0.1 and d[1] < 0 and d[2] > 1.0
    gpu = sg.evaluate(sg.extrude(o, 1.0), [[*centre, 0], [*ring, 0]], renderer=renderer)
    assert gpu[0] > 0.1 and gpu[1] < 0


def test_counters_of_e_and_a_are_holes():
    for ch in "eA":
        node = sg.text(ch, size=1.0)
        lo, hi = node.bounds2
        xs, ys = np.meshgrid(np.linspace(lo[0], hi[0], 60), np.linspace(lo[1], hi[1], 60))
        d = node.distance2(np.stack([xs, ys], -1))
        inside = d < 0
        # the counter: an outside region enclosed by ink (flood fill from the border misses it)
        outside = ~inside
        reached = np.zeros_like(outside)
        reached[0, :], reached[-1, :], reached[:, 0], reached[:, -1] = (outside[0, :], outside[-1, :],
                                                                        outside[:, 0], outside[:, -1])
        for _ in range(200):
            grown = reached.copy()
            grown[1:] |= reached[:-1]
            grown[:-1] |= reached[1:]
            grown[:, 1:] |= reached[:, :-1]
            grown[:, :-1] |= reached[:, 1:]
            grown &= outside
            if np.array_equal(grown, reached):
                break
            reached = grown
        assert inside.any() and (outside & ~reached).any(), ch


def test_kerning_and_lines():
    font = Font(font_path(None))
    av = sg.text("AV", size=1.0)
    x_v = av.placed[1][1]
    assert x_v == pytest.approx(font.advance("A") + font.kern("A", "V")) and font.kern("A", "V") < 0
    two = sg.text("A\nA", size=2.0)
    assert two.placed[1][2] == pytest.approx(-2.0 * font.line_height)
    right = sg.text("AV", size=1.0, align="right")
    assert right.bounds2[1][0] <= 1e-9 < av.bounds2[1][0]
    centre = sg.text("AV", size=1.0, align="center")
    assert centre.placed[0][1] == pytest.approx(-x_v / 2 - font.advance("V") / 2)


def test_gpos_kerning_of_a_cubic_font(tmp_path):
    path = cubic_font(tmp_path / "k.otf")
    font = Font(font_path(path))
    assert "kern" not in font.tt and font.kern("o", "o") == pytest.approx(-0.1)
    assert sg.text("oo", font=path, size=1.0).placed[1][1] == pytest.approx(0.5)


def test_extruded_text_renders_and_meshes_watertight():
    trimesh = pytest.importorskip("trimesh")
    node = sg.extrude(sg.text("sdfgl", size=0.5, align="center"), 0.1)
    res = sg.render(node, None, (96, 48), outputs=("color", "depth"))
    assert np.isfinite(res.depth).mean() > 0.05
    m = sg.mesh(node, resolution=160)
    t = m.to_trimesh()
    assert isinstance(t, trimesh.Trimesh) and len(t.faces) > 1000 and t.is_watertight


def test_booleans_offsets_and_revolve_take_text():
    label = sg.text("sdfgl", size=0.3).round(0.01)
    plate = sg.rounded_box((2, 0.6, 0.2), 0.05)
    part = plate - sg.extrude(label, 0.05).translate((-0.5, -0.1, 0.1))
    xs, ys = np.meshgrid(np.linspace(0, 0.8, 81), np.linspace(-0.05, 0.25, 31))
    xy = np.stack([xs.ravel(), ys.ravel()], -1)
    d = label.distance2(xy)
    ink, bare = xy[d < -0.005], xy[d > 0.05]
    assert len(ink) and len(bare)
    just_below_top = np.column_stack([np.concatenate([ink, bare]) + (-0.5, -0.1), np.full(len(ink) + len(bare), 0.09)])
    inside_part = part.distance(just_below_top) < 0
    assert not inside_part[:len(ink)].any() and inside_part[len(ink):].all()  # engraved under the ink only
    o = sg.text("o", size=0.5)
    ring = sg.revolve(o, 0.2)
    q = np.random.default_rng(4).uniform(-0.5, 0.5, (200, 2))
    assert ring.exactness == "exact"
    assert np.allclose(ring.distance(np.column_stack([q[:, 0] + 0.2, q[:, 1], np.zeros(200)])),
                       o.distance2(np.column_stack([np.abs(q[:, 0] + 0.2) - 0.2, q[:, 1]])))


def test_scene_document_round_trip(tmp_path):
    cubic = cubic_font(tmp_path / "r.otf")
    for shape in (sg.text("Hi\nthere", size=0.2, align="center"), sg.text("oc", font=cubic, size=0.3)):
        node = sg.extrude(shape, 0.05)
        path = sg.save_scene(node, tmp_path / "t.json")
        back = sg.load_scene(path).scene
        assert sg.compile(back) == sg.compile(node)
    assert sg.text("x").params["font"] == DEFAULT_FONT == sg.text("x", font=DEFAULT_FONT).params["font"]


def test_label_is_one_ascii_line():
    label = sg.text("Hi\nwörld").label()
    assert label.isascii() and "\n" not in label and "w\\xf6rld" in label


def test_missing_glyph_names_the_character_and_font():
    with pytest.raises(sg.ParameterError, match=r"font 'DejaVuSans' .*no glyph for '中' \(U\+4E2D\)"):
        sg.text("a中")


def test_unreadable_and_missing_fonts(tmp_path):
    junk = tmp_path / "junk.ttf"
    junk.write_bytes(b"not a font at all" * 10)
    with pytest.raises(sg.ParameterError, match=r"text: cannot read font file .*junk\.ttf"):
        sg.text("a", font=str(junk))
    with pytest.raises(sg.ParameterError, match=r"text: font file .*nope\.ttf' not found"):
        sg.text("a", font=str(tmp_path / "nope.ttf"))


@pytest.mark.parametrize("kwargs,match", [
    ({"string": ""}, "'string' must be a non-empty string"),
    ({"string": 3}, "'string' must be a non-empty string"),
    ({"string": "a", "size": 0}, "size"),
    ({"string": "a", "size": -1}, "size"),
    ({"string": "a", "align": "middle"}, "'align' must be one of left, center, right"),
    ({"string": "a", "font": 12}, "'font' must be a font file path"),
    ({"string": "   "}, "has no visible glyph"),
])
def test_bad_parameters(kwargs, match):
    with pytest.raises(sg.ParameterError, match=match):
        sg.text(**kwargs)


def test_without_fonttools_the_error_names_the_extra(monkeypatch):
    monkeypatch.setattr(sdfgl.extras, "installed", lambda module: module != "fontTools")
    with pytest.raises(sdfgl.extras.MissingExtraError, match=r"pip install 'sdfgl\[text\]'"):
        Font(font_path(None))


@pytest.mark.parametrize("short,long", [("a", "abcdefghij" * 4), ("abcdefghij" * 5, "abcdefghij" * 60)])
def test_long_string_is_data_not_code(short, long):
    s, l = sg.compile(sg.extrude(sg.text(short), 0.1)), sg.compile(sg.extrude(sg.text(long), 0.1))
    code = [[line for line in src.splitlines() if not line.lstrip().startswith("//")] for src in (s, l)]
    assert len(code[0]) == len(code[1])  # one loop over data tables, whatever the length


def _page(glyphs: int, per_line: int = 30) -> str:
    rng = np.random.default_rng(glyphs)
    chars = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
    picks = "".join(chars[i] for i in rng.integers(len(chars), size=glyphs))
    return "\n".join(picks[j:j + per_line] for j in range(0, glyphs, per_line))


def test_a_page_of_glyphs_is_listed_per_cell_with_the_exact_sign_and_distance_below_the_cap(renderer):
    page = sg.text(_page(160), size=0.1)
    grid = page.grid
    assert grid is not None and page.exactness == sg.BOUND
    assert "sd2TextGrid" in sg.compile(sg.extrude(page, 0.02))
    assert sg.text("sdfgl").grid is None and sg.text("sdfgl").exactness == sg.EXACT  # short texts: exact
    rng = np.random.default_rng(4)
    lo, hi = page.bounds2
    xy = np.concatenate([rng.uniform(lo - 0.1, hi + 0.1, (8000, 2)), near_points(page, rng, 8000)])
    exact = page._block(xy)  # every glyph, no cap
    got = page.distance2(xy)
    cap = grid.cap(xy)
    assert np.all(np.abs(got) <= cap + 1e-12)
    below = np.abs(exact) < cap
    assert below.mean() > 0.5 and np.array_equal(got[below], exact[below])  # the exact distance where it is below the cap
    clear = np.abs(exact) > 1e-9
    assert np.array_equal(np.sign(got[clear]), np.sign(exact[clear]))  # the exact sign everywhere
    node = sg.extrude(page, 0.05)
    pts = np.column_stack([xy, rng.uniform(-0.03, 0.03, len(xy))])
    gpu = sg.evaluate(node, pts, renderer=renderer).astype(np.float64)
    ref = node.distance(pts)
    assert np.all(np.abs(gpu - ref) <= 16 * EPS32 * (1 + np.abs(pts).max(axis=-1) + np.abs(ref)))


def test_a_page_of_glyphs_compiles_as_glsl_es_300(renderer):
    from sdfgl.compiler.generate import generate
    from sdfgl.settings import Settings
    src = generate(sg.extrude(sg.text(_page(120), size=0.1), 0.02), Settings(), dialect="webgl2")
    assert "sd2TextGrid" in src.text
    renderer.programs.get(src)  # Mesa holds "#version 300 es" to ES's rules

