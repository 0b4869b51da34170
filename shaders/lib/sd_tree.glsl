// requires: sd_capsule
// A branching tree by mirror recursion: a trunk capsule, then per level: move to the top
// of the branch, fold x and z (four branches from one), lean out by angle, shrink. The
// distance to each level's capsule is scaled back and kept if nearest.
float sdTree(vec3 p, int levels, float h, float r, float c, float s, float shrink) {
    float scale = 1.0;
    float d = sdCapsule(p, vec3(0.0), vec3(0.0, h, 0.0), r);
    for (int i = 0; i < levels; i++) {
        p.y -= h;
        p.xz = abs(p.xz);
        p.xy = vec2(c * p.x - s * p.y, s * p.x + c * p.y);
        p.zy = vec2(c * p.z - s * p.y, s * p.z + c * p.y);
        p /= shrink;
        scale *= shrink;
        d = min(d, sdCapsule(p, vec3(0.0), vec3(0.0, h, 0.0), r) * scale);
    }
    return d;
}
