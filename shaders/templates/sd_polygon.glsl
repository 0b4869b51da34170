// Exact signed distance to a simple polygon with POLYN vertices v (Inigo Quilez, MIT).
// POLYN is replaced by the vertex count of each polygon a scene uses.
float sdPolygonPOLYN(vec2 p, vec2 v[POLYN]) {
    float d = dot(p - v[0], p - v[0]);
    float s = 1.0;
    for (int i = 0, j = POLYN - 1; i < POLYN; j = i, i++) {
        vec2 e = v[j] - v[i];
        vec2 w = p - v[i];
        vec2 b = w - e * clamp(dot(w, e) / dot(e, e), 0.0, 1.0);
        d = min(d, dot(b, b));
        bvec3 c = bvec3(p.y >= v[i].y, p.y < v[j].y, e.x * w.y > e.y * w.x);
        if (all(c) || all(not(c))) s *= -1.0;
    }
    return s * sqrt(d);
}
