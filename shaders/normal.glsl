// Surface normal by central differences: six map() calls, in a loop so the compiler
// keeps one copy of map() here. The offset h is tiny against the scene (1e-4 of its
// size), so thin features (shells, bars) are not straddled, and large enough against
// float32 resolution at pos (1e-4 |pos|) to keep rounding noise near 0.1 degree. (The
// four-tap tetrahedron technique is cheaper, but its error is first order in h wherever
// the Hessian has off-diagonal terms.) A vanishing gradient (e.g. at the centre of a
// sphere) falls back to facing the viewer, never NaN.
#ifdef DETAIL_NORMALS
#define NORMAL_FIELD mapDetail  // a field with more detail than the one marched
#else
#define NORMAL_FIELD map
#endif

vec3 calcNormal(vec3 pos, float t, vec3 rd) {
    float h = 1e-4 * max(SCENE_SCALE, length(pos));
    vec3 g = vec3(0.0);
    for (int i = uZero; i < 6; i++) {
        float s = (i & 1) == 0 ? 1.0 : -1.0;
        vec3 e = vec3(0.0);
        e[i >> 1] = s * h;
        g[i >> 1] += s * NORMAL_FIELD(pos + e);
    }
    float len = length(g);
    return len > 1e-20 ? g / len : -rd;
}
