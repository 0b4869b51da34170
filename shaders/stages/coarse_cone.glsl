// The coarse pass's cone: one per tile of COARSE_TILE x COARSE_TILE pixels, holding every
// ray of the tile's pixels (their anti-aliasing samples and the image's jitter included).
// The point at t along any of those rays lies within coneRadius(t) of the axis point at t:
// for a pinhole, t |d - a| with d the ray's and a the axis's unit direction, largest at a
// corner of the tile (the angle to the axis has convex level sets on the image plane);
// for parallel rays, the distance between their origins.
#define CONE_STEPS 128       // map() calls a cone may take
#define CONE_CLOSE 0.5       // a cone stops once its step falls below this share of its radius
#define CONE_BACK 2.0         // a tile's start lies this many cone radii before where the cone stopped
#define EMPTY_TILE 1.0e38    // the start of a tile whose cone crossed the scene without meeting it
#define LIT_TILE 2.0e38      // ... whose rays all meet the ground where AO is 1 and no shadow falls
#define SKY_TILE 3.0e38      // ... and none of whose rays can meet the ground plane either

struct Cone {
    vec3 ro;       // the axis's origin
    vec3 rd;       // the axis's unit direction
    float spread;  // radius per unit of t (the largest |d - a|)
    float width;   // radius at t = 0 (the farthest ray origin from the axis's)
};

// The cone of the tile whose corners are window positions lo and hi.
Cone tileCone(vec2 lo, vec2 hi) {
    vec2 mid = 0.5 * (lo + hi);
    Cone c = Cone(rayOrigin(mid), rayDir(mid), 0.0, 0.0);
    for (int k = 0; k < 4; k++) {
        vec2 corner = vec2(k == 1 || k == 3 ? hi.x : lo.x, k >= 2 ? hi.y : lo.y);
        c.spread = max(c.spread, length(rayDir(corner) - c.rd));
        c.width = max(c.width, length(rayOrigin(corner) - c.ro));
    }
    // float32 slack: directions and origins round at a few ulps
    c.spread = c.spread * 1.001 + 1e-6;
    c.width = c.width * 1.001 + 1e-6 * length(c.ro);
    return c;
}

// The cone's radius at t, widened by the hit threshold: a tile's rays start marching at
// least that far from any surface, so the march still sees its approach.
float coneRadius(Cone c, float t) {
    return c.spread * t + c.width + hitEpsilon(t) + 1e-6 * (t + length(c.ro));
}

// Euclidean distance from p to the scene box (0 inside): no surface the march can hit lies
// nearer, and it is 1-Lipschitz too.
float boxGap(vec3 p) {
    return length(max(max(BOUNDS_LO - p, p - BOUNDS_HI), vec3(0.0)));
}

// The ray parameter up to which no ray of cone c meets a surface inside the scene box:
// sphere tracing along the axis by the lower bound max(map / LIPSCHITZ, boxGap) of the
// distance to such a surface, less the cone's radius. Each step's ball holds every ray's
// stretch from t to the next t, so the way is proven for all of them; EMPTY_TILE where the
// cone passed every point of the box (or MAX_DIST) first. The start lies CONE_BACK cone
// radii before where the cone stopped (at most one step back): the rays then march their own
// approach to the surface (from where the cone stopped, a ray's first samples lie near it
// with no slope yet, and a grazing ray's settling may take another root).
float coneStart(Cone c) {
    vec3 centre = 0.5 * (BOUNDS_LO + BOUNDS_HI);
    float far = min(length(c.ro - centre) + c.width + 0.5 * length(BOUNDS_HI - BOUNDS_LO), MAX_DIST);
    float t = 0.0;
    float back = 0.0;  // t before the last step
    for (int i = uZero; i < CONE_STEPS; i++) {
        vec3 p = c.ro + c.rd * t;
        float need = coneRadius(c, t);
        float r = boxGap(p);
        if (r <= (1.0 + CONE_CLOSE) * need) r = max(r, map(p) / LIPSCHITZ);
        float step = r - need;
        if (step < CONE_CLOSE * need) return max(back, t - CONE_BACK * need);
        back = t;
        t += step;
        if (t >= far) return EMPTY_TILE;
    }
    return back;
}

// Whether a ray of the tile with corners lo and hi may meet the analytic ground plane: one
// going down from above it. The ray origins' heights (parallel rays) or the directions' y
// (a pinhole: linear across the image plane before normalising) are extreme at the corners;
// a direction within 1e-4 of level counts as going down.
bool tileSeesGround(vec2 lo, vec2 hi) {
#ifdef GROUND
    for (int k = 0; k < 4; k++) {
        vec2 corner = vec2(k == 1 || k == 3 ? hi.x : lo.x, k >= 2 ? hi.y : lo.y);
        if (rayDir(corner).y < 1e-4 && rayOrigin(corner).y > GROUND_Y) return true;
    }
#endif
    return false;
}

// Whether every ray of the tile with corners lo and hi meets the ground where ambient occlusion
// is exactly 1 and no shadow ray can enter the scene box: its ground shading needs no map()
// call. The ground points of the tile's rays lie in the convex quadrilateral of its corners'
// (the plane's image of a rectangle below the horizon), so within r of their centre c. AO is 1
// where every sample d = map(p + h n) >= h: map is LIPSCHITZ-Lipschitz, so map(c) -
// LIPSCHITZ (r + hmax) >= hmax proves it for every sample of every point.
bool tileGroundLit(vec2 lo, vec2 hi) {
#ifdef GROUND
    vec3 g[4];
    for (int k = 0; k < 4; k++) {
        vec2 corner = vec2(k == 1 || k == 3 ? hi.x : lo.x, k >= 2 ? hi.y : lo.y);
        vec3 ro = rayOrigin(corner), rd = rayDir(corner);
        if (!(rd.y < -1e-4 && ro.y > GROUND_Y)) return false;
        float t = (GROUND_Y - ro.y) / rd.y;
        if (!(t <= MAX_DIST)) return false;
        g[k] = ro + rd * t;
    }
    vec3 c = 0.25 * (g[0] + g[1] + g[2] + g[3]);
    float r = 0.0;
    for (int k = 0; k < 4; k++) r = max(r, length(g[k] - c));
    r = r * 1.01 + 1e-5 * SCENE_SCALE;  // float32 slack
#ifdef AO
    float hmax = aoSampleHeight(4);  // calcAO's farthest sample
    if (!(map(c) - LIPSCHITZ * (r + hmax) >= hmax * 1.01)) return false;
#endif
    return tileUnshadowed(c, r + 1e-3 * SCENE_SCALE);  // the rays start a little above the ground
#else
    return false;
#endif
}
