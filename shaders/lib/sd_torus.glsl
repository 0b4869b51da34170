// Exact distance to a torus in the XZ plane: major radius t.x, minor radius t.y (Inigo Quilez, MIT).
float sdTorus(vec3 p, vec2 t) {
    vec2 q = vec2(length(p.xz) - t.x, p.y);
    return length(q) - t.y;
}
