// Exact signed distance to a simple polygon whose n vertices are data: data texel
// first + i holds vertex i in .xy (Inigo Quilez's polygon, MIT, as a loop over a
// texture: compile time does not grow with the vertex count).
// requires: data_table
float sdPolygonData(vec2 p, int first, int n) {
    vec2 vj = dataFetch(first + n - 1).xy;
    vec2 v0 = dataFetch(first).xy;
    float d = dot(p - v0, p - v0);
    float s = 1.0;
    for (int i = 0; i < n; i++) {
        vec2 vi = dataFetch(first + i).xy;
        vec2 e = vj - vi;
        vec2 w = p - vi;
        vec2 b = w - e * clamp(dot(w, e) / dot(e, e), 0.0, 1.0);
        d = min(d, dot(b, b));
        bvec3 c = bvec3(p.y >= vi.y, p.y < vj.y, e.x * w.y > e.y * w.x);
        if (all(c) || all(not(c))) s *= -1.0;
        vj = vi;
    }
    return s * sqrt(d);
}
