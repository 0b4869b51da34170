// Surface normal by central differences: six map() calls, in a loop so the compiler
// keeps one copy of map() here. The offset h follows what the pixel resolves: a fiftieth
// of the hit's pixel footprint (so a small object beside a big one is not straddled),
// at most 1e-4 of the scene size (thin parts of a scene seen from afar, such as a 1e-3
// shell, are not straddled either), but never below the float32 resolution of
// the hit point (2e-5 of its distance from the shader origin, which lies at the scene,
// keeping rounding noise near 0.1 degree) nor 1e-7 of the scene size. (The four-tap
// tetrahedron technique is cheaper, but its error is first order in h wherever the
// Hessian has off-diagonal terms.) A gradient that vanishes or is not finite (at the
// centre of a sphere, an overflowing implicit field) falls back to facing the viewer,
// never NaN.
#ifdef DETAIL_NORMALS
#define NORMAL_FIELD mapDetail  // a field with more detail than the one marched
#else
#define NORMAL_FIELD map
#endif

vec3 calcNormal(vec3 pos, float t, vec3 rd) {
    float h = max(min(0.02 * pixelAngle() * t, 1e-4 * SCENE_SCALE), max(2e-5 * length(pos), 1e-7 * SCENE_SCALE));
    vec3 g = vec3(0.0);
    for (int i = uZero; i < 6; i++) {
        float s = (i & 1) == 0 ? 1.0 : -1.0;
        vec3 e = vec3(0.0);
        e[i >> 1] = s * h;
        g[i >> 1] += s * NORMAL_FIELD(pos + e);
    }
    float len = length(g);
    vec3 n = g / len;
    bool ok = len > 1e-20 && len < 1e30 && !any(isnan(n));
    return ok ? n : -rd;
}
