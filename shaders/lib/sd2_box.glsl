// Exact distance to a 2D rectangle with half extents b and corners rounded by r (IQ, MIT).
float sd2Box(vec2 p, vec2 b, float r) {
    vec2 q = abs(p) - b + r;
    return length(max(q, 0.0)) + min(max(q.x, q.y), 0.0) - r;
}
