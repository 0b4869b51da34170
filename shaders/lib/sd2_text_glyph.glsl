// One placed glyph of a text (sdfgl/nodes/text.py; the tables are described in
// sd2_text.glsl): lowers d to the distance to its outline pieces where that is nearer
// (skipped when its box is no nearer than d; a piece is solved only where the box of its
// control points, which holds the piece, is nearer than d) and, where p lies in its box, adds the
// glyph's crossings of the ray from p towards +x (half-open in y) to wind.
// requires: data_table, sd_bezier, sd2_segment
void sd2TextGlyph(vec2 p, int g, int glyphs, inout float d, inout int wind) {
    vec4 box = dataFetch(glyphs + 2 * g);
    vec2 k = max(max(box.xy - p, p - box.zw), 0.0);
    float bd2 = dot(k, k);
    bool inside = bd2 == 0.0;
    if (!inside && bd2 >= d * d) return;
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
        vec2 pk = max(max(min(min(a, b), c) - q, q - max(max(a, b), c)), 0.0);
        if (dot(pk, pk) < d * d)
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
