// Surface normal by central differences, in a loop so the compiler keeps one copy of
// map() here. The offset h starts at what the pixel resolves: a fiftieth of the hit's
// pixel footprint (so a small object beside a big one is not straddled), at most 1e-4 of
// the scene size, but never below the float32 resolution of the hit point (2e-5 of its
// distance from the shader origin, keeping rounding noise near 0.1 degree; the origin lies
// near the eye where a near part is far smaller than the scene) nor 1e-5 of the
// footprint (a hit at the origin itself). The stencil then follows the local feature: seven taps (the six
// neighbours and the hit itself) give the first differences a and the second differences
// b per axis; where the field bends within the stencil (|b| > NORMAL_BEND |a|: the taps
// straddle a wall thinner than 2h, or a crease) h shrinks eightfold, down to a tenth of
// that float32 floor (the taps then hold at least ~16 float32 steps). Each difference is
// divided by the offset the rounded taps really have, so the rounding of pos + h never
// tilts the normal. (The four-tap tetrahedron technique is cheaper, but its error is
// first order in h wherever the Hessian has off-diagonal terms.) A gradient that
// vanishes or is not finite (at the centre of a sphere, an overflowing implicit field)
// falls back to facing the viewer, never NaN. Where the scene is one mesh (MESH_NORMAL), the
// normal is the surface's where the ray met it, no map() call (sd_mesh_bvh.glsl).
#ifdef DETAIL_NORMALS
#define NORMAL_FIELD mapDetail  // a field with more detail than the one marched
#else
#define NORMAL_FIELD map
#endif

#define NORMAL_BEND 0.05    // |second difference| / |first difference| a straight field stays below
#define NORMAL_SHRINKS 3    // times h may shrink eightfold

vec3 calcNormal(vec3 pos, float t, vec3 rd) {
#ifdef MESH_NORMAL
    // the scene is one mesh: the normal where the cast met it, or at the march's last
    // sample's closest point (sd_mesh_bvh.glsl)
#ifdef MESH_NORMAL_TURN
    vec3 g = MESH_NORMAL_TURN * gMeshNormal;
#else
    vec3 g = gMeshNormal;
#endif
    float len = length(g);
    return len > 0.5 && len < 2.0 ? g / len : -rd;
#else
    float floorH = max(2e-5 * length(pos), 1e-5 * pixelAngle() * t);
    float h = max(min(0.02 * pixelAngle() * t, 1e-4 * SCENE_SCALE), floorH);
    float minH = 0.1 * floorH;
    vec3 g = vec3(0.0);
    for (int k = uZero; k <= NORMAL_SHRINKS; k++) {
        vec3 fp = vec3(0.0), fm = vec3(0.0), dp = vec3(0.0), dm = vec3(0.0);
        float f0 = 0.0;
        for (int i = uZero; i < 7; i++) {
            int ax = i >> 1;
            float s = (i & 1) == 0 ? 1.0 : -1.0;
            vec3 e = vec3(0.0);
            if (i < 6) e[ax] = s * h;
            vec3 q = pos + e;
            float f = NORMAL_FIELD(q);
            if (i == 6) f0 = f;
            else if (s > 0.0) { fp[ax] = f; dp[ax] = q[ax] - pos[ax]; }
            else { fm[ax] = f; dm[ax] = pos[ax] - q[ax]; }
        }
        g = (fp - fm) / max(dp + dm, vec3(1e-30));
        vec3 bend = 0.5 * (fp + fm) - f0;
        vec3 lin = 0.5 * (fp - fm);
        if (h <= minH || !(length(bend) > NORMAL_BEND * length(lin))) break;
        h = max(0.125 * h, minH);
    }
    float len = length(g);
    vec3 n = g / len;
    bool ok = len > 1e-20 && len < 1e30 && !any(isnan(n));
    return ok ? n : -rd;
#endif
}
