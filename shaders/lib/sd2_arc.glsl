// Exact signed distance to an arc of radius ra and thickness 2 rb, symmetric about +Y,
// sc = (sin, cos) of half its aperture (Inigo Quilez, MIT).
float sd2Arc(vec2 p, vec2 sc, float ra, float rb) {
    p.x = abs(p.x);
    return ((sc.y * p.x > sc.x * p.y) ? length(p - sc * ra) : abs(length(p) - ra)) - rb;
}
