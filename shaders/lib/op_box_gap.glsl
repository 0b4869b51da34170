// How far q lies outside the box of half extents h centred at the origin: its distance to
// the box where q is outside, -3e38 inside (where it bounds nothing). A costly child of a
// hard union or difference is evaluated only where this bound, divided by the child's
// level factor, does not already prove it cannot change the result (sdfgl/compiler/guards.py).
float opBoxGap(vec3 q, vec3 h) {
    vec3 d = abs(q) - h;
    return any(greaterThan(d, vec3(0.0))) ? length(max(d, 0.0)) : -3.0e38;
}
