// Hard shadow: 0 if anything lies between ro and the light along rd, else 1. Where the free
// way along the ray ends where the ray meets the surface (RAY_FREE_HIT: the scene is one
// mesh), a step also takes that way, landing a hit threshold short: one cast, one more map().
float shadow(vec3 ro, vec3 rd, float tmin, float tmax) {
    float t = tmin;
#ifdef RAY_FREE_HIT
    rayFreeStart(rd);
#endif
    for (int i = 0; i < 96; i++) {
#ifdef RAY_FREE_HIT
        gFreeAsk = true;
#endif
        float h = map(ro + rd * t);
#ifdef RAY_FREE_HIT
        gFreeAsk = false;
        if (h >= hitEpsilon(t)) h = max(h, gFree - hitEpsilon(t));
#endif
        if (h < hitEpsilon(t)) return 0.0;
        t += h;
        if (t > tmax) break;
    }
    return 1.0;
}
