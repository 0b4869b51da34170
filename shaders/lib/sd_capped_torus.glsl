// Exact distance to a torus of radii ra, rb in the XY plane cut to the arc within the
// half-aperture whose (sin, cos) is sc, symmetric about +Y (Inigo Quilez, MIT), written as
// the distance to the nearest point of the centre arc (no cancellation in float32).
float sdCappedTorus(vec3 p, vec2 sc, float ra, float rb) {
    p.x = abs(p.x);
    float d = (sc.y * p.x > sc.x * p.y) ? length(p - vec3(sc * ra, 0.0)) : length(vec2(length(p.xy) - ra, p.z));
    return d - rb;
}
