// Signed distance to text (sdfgl/nodes/text.py). Placed glyphs come in groups of
// consecutive ones: ng groups at data texels groups + 2j: (box lo.xy, box hi.xy), (first
// glyph, glyph count, a point on an outline: x, y). Glyph k at texels glyphs + 2k:
// (box lo.xy, box hi.xy), (first piece texel, piece count, x, y). Each piece is two
// texels: (A.xy, B.xy), (C.xy, kind, -), kind 1 a quadratic Bezier A B C (monotonic in
// y), 0 the segment A C, in glyph-local coordinates. The groups' outline points bound the
// distance first; then a group or glyph whose box is farther than the nearest piece so far
// is skipped (outside its box its winding number is 0), so the result is the minimum over
// all pieces. The sign is the nonzero winding number of the ray from p towards +x
// (half-open in y).
// requires: data_table, sd_bezier, sd2_segment
float sd2Text(vec2 p, int groups, int ng, int glyphs) {
    float d = 1e30;
    for (int j = 0; j < ng; j++) d = min(d, length(p - dataFetch(groups + 2 * j + 1).zw));
    int wind = 0;
    for (int j = 0; j < ng; j++) {
        vec4 gbox = dataFetch(groups + 2 * j);
        vec2 gk = max(max(gbox.xy - p, p - gbox.zw), 0.0);
        float gd2 = dot(gk, gk);
        if (gd2 > 0.0 && gd2 >= d * d) continue;
        vec4 group = dataFetch(groups + 2 * j + 1);
        int g0 = int(group.x);
        int g1 = g0 + int(group.y);
        for (int g = g0; g < g1; g++) {
            vec4 box = dataFetch(glyphs + 2 * g);
            vec2 k = max(max(box.xy - p, p - box.zw), 0.0);
            float bd2 = dot(k, k);
            bool inside = bd2 == 0.0;
            if (!inside && bd2 >= d * d) continue;
            vec4 span = dataFetch(glyphs + 2 * g + 1);
            vec2 q = p - span.zw;
            int first = int(span.x);
            int count = int(span.y);
            for (int i = 0; i < count; i++) {
                vec4 s0 = dataFetch(first + 2 * i);
                vec4 s1 = dataFetch(first + 2 * i + 1);
                vec2 a = s0.xy;
                vec2 b = s0.zw;
                vec2 c = s1.xy;
                bool quad = s1.z > 0.5;
                d = min(d, quad ? sdBezier(vec3(q, 0.0), vec3(a, 0.0), vec3(b, 0.0), vec3(c, 0.0)) : sd2Segment(q, a, c));
                if (inside && ((a.y <= q.y) != (c.y <= q.y))) {
                    float x;
                    if (quad) {
                        float al = a.y - 2.0 * b.y + c.y;
                        float be = 2.0 * (b.y - a.y);
                        float ga = a.y - q.y;
                        float root = sqrt(max(be * be - 4.0 * al * ga, 0.0));
                        float qq = -0.5 * (be + (be >= 0.0 ? root : -root));
                        float t1 = al != 0.0 ? qq / al : 1e30;
                        float t2 = qq != 0.0 ? ga / qq : 0.0;
                        float t = clamp(abs(t2 - 0.5) <= abs(t1 - 0.5) ? t2 : t1, 0.0, 1.0);
                        x = (1.0 - t) * (1.0 - t) * a.x + 2.0 * t * (1.0 - t) * b.x + t * t * c.x;
                    } else {
                        float t = clamp((q.y - a.y) / (c.y - a.y), 0.0, 1.0);
                        x = a.x + t * (c.x - a.x);
                    }
                    if (x > q.x) wind += c.y > a.y ? 1 : -1;
                }
            }
        }
    }
    return wind != 0 ? -d : d;
}
