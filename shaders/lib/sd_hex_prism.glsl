// Exact distance to a hexagonal prism along Y: inradius r (centre to flat side), half
// height h (Inigo Quilez, MIT; axes swapped so the prism runs along Y).
float sdHexPrism(vec3 p, float r, float h) {
    const vec3 k = vec3(-0.8660254, 0.5, 0.57735027);
    p = abs(p.xzy);
    p.xy -= 2.0 * min(dot(k.xy, p.xy), 0.0) * k.xy;
    vec2 d = vec2(length(p.xy - vec2(clamp(p.x, -k.z * r, k.z * r), r)) * sign(p.y - r), p.z - h);
    return min(max(d.x, d.y), 0.0) + length(max(d, 0.0));
}
