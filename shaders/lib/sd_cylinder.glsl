// Exact distance to a capped cylinder along Y: radius r, half height h (Inigo Quilez, MIT).
float sdCylinder(vec3 p, float r, float h) {
    vec2 d = abs(vec2(length(p.xz), p.y)) - vec2(r, h);
    return min(max(d.x, d.y), 0.0) + length(max(d, 0.0));
}
