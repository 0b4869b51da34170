// The free way along the ray, for the marchers (RAY_FREE: the scene is one grid union,
// perhaps moved as a whole). map() leaves in gFree how far along gRayDir from its point
// nothing of the union lies: each listed sphere by where the ray enters it, each listed
// subtree, translated or turned (the direction turned into its frame by its record's
// quaternion), by where the ray enters its bounding box (infinite where the ray misses it
// or leaves it behind; the one whose box the ray enters first, by where it enters the
// balls and boxes of its parts: GRIDIDEnterN, from nodes/ray_entry.py), any other listed
// instance (scaled, or a primitive whose size is data) by its distance, and the
// unlisted ones, which lie at least the margin from the point's cell, by the way to the
// cell's far side plus the margin. Children of the union written as code beside the
// grid (a floor) narrow gFree to their distance in map() (Emitter.narrow_free_way).
// Outside the grid box it is the field's value (a plain distance). The marcher may step
// that far at once: the segment is proven empty. The globals are shaders/lib/ray_free.glsl's.

// Along the ray (inv = 1 / its direction) from p: the way to the far side of p's cell (low
// corner lo, from GRIDIDCell) plus the margin, or -1.0 where p lies outside the cell
// (outside the grid box).
float GRIDIDExit(vec3 p, vec3 inv, vec3 lo) {
    vec3 hi = lo + GRIDID_CELL;
    if (any(lessThan(p, lo)) || any(greaterThan(p, hi))) return -1.0;
    vec3 way = (mix(lo, hi, step(0.0, inv)) - p) * inv;
    return min(way.x, min(way.y, way.z)) + GRIDID_MARGIN;
}

// Along unit d from q (relative to a sphere's centre): where the ray enters the sphere of
// radius r (0 inside it), or 3e38 where it misses the sphere or moves away from it.
float GRIDIDRayBall(vec3 q, vec3 d, float r) {
    float b = dot(q, d);
    float c = dot(q, q) - r * r;
    if (c <= 0.0) return 0.0;
    float disc = b * b - c;
    if (b >= 0.0 || disc < 0.0) return 3.0e38;
    return c / (-b + sqrt(disc));  // the nearer root, without cancellation
}

// Along the ray (inv = 1 / its direction) from q (in an instance's frame): where it enters
// the box [lo, hi] (0 inside it), or 3e38 where it misses the box or moves away from it.
float GRIDIDRayBox(vec3 q, vec3 inv, vec3 lo, vec3 hi) {
    vec3 a = (lo - q) * inv;
    vec3 b = (hi - q) * inv;
    vec3 near = min(a, b);
    vec3 far = max(a, b);
    float enter = max(max(near.x, near.y), max(near.z, 0.0));
    float leave = min(min(far.x, far.y), far.z);
    return leave < enter ? 3.0e38 : enter;
}
