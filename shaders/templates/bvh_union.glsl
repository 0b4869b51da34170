// A big union kept as data, traversed as a bounding volume hierarchy (sdfgl/nodes/bvh.py;
// the prototype measured against the uniform grid, setting grid="bvh"). GRIDID is
// replaced per union; p is relative to the union's centre. Node i is 4 texels from
// GRIDID_NODES + 4 i: (lo_a, child_a), (hi_a, child_b), (lo_b, 0), (hi_b, 0); a child
// k >= 0 is node k, k < 0 is leaf -1 - k, whose per-type (first, count) pairs start at
// GRIDID_CELLS + (-1 - k) * GRIDID_PER_LEAF, with its records from GRIDID_LIST.

float GRIDIDBox(vec3 p, vec3 lo, vec3 hi) {
    vec3 c = 0.5 * (lo + hi);
    vec3 k = abs(p - c) - 0.5 * (hi - lo);
    return length(max(k, 0.0)) + min(max(k.x, max(k.y, k.z)), 0.0);
}

// Where the field starts: below this, every instance counts; the root box's distance
// when that is larger.
float GRIDIDTruncate(vec3 p) {
    return max(GRIDID_TRUNCATE, GRIDIDBox(p, GRIDID_ROOT_LO, GRIDID_ROOT_HI));
}

// Node n's two children: their box distances from p and their indices.
void GRIDIDChildren(vec3 p, int n, out float da, out float db, out int a, out int b) {
    int at = GRIDID_NODES + 4 * n;
    vec4 loA = dataFetch(at);
    vec4 hiA = dataFetch(at + 1);
    vec4 loB = dataFetch(at + 2);
    vec4 hiB = dataFetch(at + 3);
    da = GRIDIDBox(p, loA.xyz, hiA.xyz);
    db = GRIDIDBox(p, loB.xyz, hiB.xyz);
    a = int(loA.w);
    b = int(hiA.w);
}
