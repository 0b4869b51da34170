// Signed distance to a long text (sdfgl/compiler/data/textgrid.py): the placed glyphs near
// each cell of a 2D grid are listed in it. Data texels from `cells`, one per cell: (first
// entry, count, -, -); from `entries`, one per entry: (placed glyph, -, -, -); the glyph and
// piece tables as in sd2_text.glsl. Exact sign (a glyph box holding p meets p's cell); the
// magnitude is min(listed glyphs, cap), exact below the cap.
// requires: data_table, grid2_cap, sd2_text_glyph
float sd2TextGrid(vec2 p, vec2 lo, float cell, ivec2 dims, float margin, int cells, int entries, int glyphs) {
    ivec2 c;
    float boxDist;
    float d = grid2Cap(p, lo, cell, dims, margin, c, boxDist);
    vec4 span = dataFetch(cells + c.y * dims.x + c.x);
    int first = int(span.x);
    int count = int(span.y);
    int wind = 0;
    for (int i = 0; i < count; i++) sd2TextGlyph(p, int(dataFetch(entries + first + i).x), glyphs, d, wind);
    return wind != 0 ? -d : d;
}
