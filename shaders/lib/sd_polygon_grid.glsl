// A polygon with many vertices as data (sdfgl/nodes/polygrid.py): the edges near a point
// are listed in its cell of a 2D grid. Data texels from `cells`, one per cell:
// (first entry, count, reference inside, reference candidate); from `edges`, one per entry:
// (from.xy, to.xy). The sign is the cell's reference point's (its centre, or the candidate
// fract(1/2 + k * step) of the cell clear of every edge), flipped by each listed edge the
// segment reference -> p crosses; the magnitude is min(listed edges, cap), a bound exact below the cap.
// requires: data_table, grid2_cap
float sdPolygonGrid(vec2 p, vec2 lo, float cell, ivec2 dims, int cells, int edges) {
    ivec2 c;
    float boxDist;
    float cap = grid2Cap(p, lo, cell, dims, cell, c, boxDist);
    vec2 cellLo = lo + vec2(c) * cell;
    vec4 span = dataFetch(cells + c.y * dims.x + c.x);
    vec2 centre = cellLo + cell * fract(vec2(0.5) + span.w * vec2(0.6180339887, 0.7548776662));
    float s = (boxDist > 0.0 || span.z < 0.5) ? 1.0 : -1.0;
    bool inGrid = boxDist <= 0.0;
    float d = cap * cap;
    int first = int(span.x);
    int count = int(span.y);
    for (int i = 0; i < count; i++) {
        vec4 e = dataFetch(edges + first + i);
        vec2 a = e.xy;
        vec2 b = e.zw;
        vec2 ab = b - a;
        vec2 w = p - a;
        vec2 h = w - ab * clamp(dot(w, ab) / dot(ab, ab), 0.0, 1.0);
        d = min(d, dot(h, h));
        if (inGrid) {  // does the segment centre -> p cross this edge?
            vec2 cp = p - centre;
            float o1 = cp.x * (a.y - centre.y) - cp.y * (a.x - centre.x);
            float o2 = cp.x * (b.y - centre.y) - cp.y * (b.x - centre.x);
            float o3 = ab.x * (centre.y - a.y) - ab.y * (centre.x - a.x);
            float o4 = ab.x * w.y - ab.y * w.x;
            if ((o1 > 0.0) != (o2 > 0.0) && (o3 > 0.0) != (o4 > 0.0)) s = -s;
        }
    }
    return s * min(sqrt(d), cap);
}
