// Signed distance to text (sdfgl/nodes/text.py). Placed glyphs come in groups of
// consecutive ones: ng groups at data texels groups + 2j: (box lo.xy, box hi.xy), (first
// glyph, glyph count, a point on an outline: x, y). Glyph k at texels glyphs + 2k:
// (box lo.xy, box hi.xy), (first piece texel, piece count, x, y). Each piece is two
// texels: (A.xy, B.xy), (C.xy, kind, -), kind 1 a quadratic Bezier A B C (monotonic in
// y), 0 the segment A C, in glyph-local coordinates. The groups' outline points bound the
// distance first; then a group or glyph whose box is farther than the nearest piece so far
// is skipped (outside its box its winding number is 0), so the result is the minimum over
// all pieces. The sign is the nonzero winding number of the ray from p towards +x
// (half-open in y). Where the caller needs no distance above `cap` (a costly child's box
// test, sdfgl/compiler/guards.py; 3e38 for none), the search starts at cap: outside the
// glyphs the result is the exact distance where that is below cap, and cap or more beyond;
// inside one, where nothing below cap was found, the search runs again without it.
// requires: data_table, sd2_text_glyph
float sd2Text(vec2 p, int groups, int ng, int glyphs, float cap) {
    float d = cap;
    int wind = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (int j = 0; j < ng; j++) d = min(d, length(p - dataFetch(groups + 2 * j + 1).zw));
        wind = 0;
        for (int j = 0; j < ng; j++) {
            vec4 gbox = dataFetch(groups + 2 * j);
            vec2 gk = max(max(gbox.xy - p, p - gbox.zw), 0.0);
            float gd2 = dot(gk, gk);
            if (gd2 > 0.0 && gd2 >= d * d) continue;
            vec4 group = dataFetch(groups + 2 * j + 1);
            int g0 = int(group.x);
            int g1 = g0 + int(group.y);
            for (int g = g0; g < g1; g++) sd2TextGlyph(p, g, glyphs, d, wind);
        }
        if (wind == 0 || d < cap || pass == 1) break;
        d = 1e30;  // inside a glyph, farther than cap from its outline: the exact distance
    }
    return wind != 0 ? -d : d;
}
