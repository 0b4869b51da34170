// Signed distance to a long text (sdfgl/compiler/data/textgrid.py): the placed glyphs near
// each cell of a 2D grid are listed in it. Data texels from `cells`, one per cell: (first
// entry, count, -, -); from `entries`, one per entry: (placed glyph, -, -, -); the glyph and
// piece tables as in sd2_text.glsl. Exact sign (a glyph box holding p meets p's cell); the
// magnitude is min(listed glyphs, cap), exact below the cap. `need` is sd2Text's cap (the
// caller needs no distance above it; 3e38 for none), searched from the same way.
// requires: data_table, grid2_cap, sd2_text_glyph
float sd2TextGrid(vec2 p, vec2 lo, float cell, ivec2 dims, float margin, int cells, int entries, int glyphs,
                  float need) {
    ivec2 c;
    float boxDist;
    float gridCap = grid2Cap(p, lo, cell, dims, margin, c, boxDist);
    vec4 span = dataFetch(cells + c.y * dims.x + c.x);
    int first = int(span.x);
    int count = int(span.y);
    float d = min(gridCap, need);
    int wind = 0;
    for (int pass = 0; pass < 2; pass++) {
        wind = 0;
        for (int i = 0; i < count; i++) sd2TextGlyph(p, int(dataFetch(entries + first + i).x), glyphs, d, wind);
        if (wind == 0 || d < need || need >= gridCap || pass == 1) break;
        d = gridCap;  // inside a glyph, farther than need from its outline: the grid's own value
    }
    return wind != 0 ? -d : d;
}
