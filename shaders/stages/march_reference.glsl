// Brute-force march for validation: fixed steps of REF_STEP until the field changes
// sign, then settling (refine.glsl) pins the root down, in a loop after the marching one.
// Needs no distance property at all; its cost is the ray length over REF_STEP.
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float t = tmin;
    float f = map(ro + rd * t);
    steps++;
    if (f < 0.0) {
        return tmin;
    }
    float tNext = t;
    float fNext = f;
    bool inside = false;  // a sign change: [t, tNext] brackets a root
    for (int i = 0; i < MAX_STEPS; i++) {
        tNext = t + REF_STEP;
        fNext = map(ro + rd * tNext);
        steps++;
        if (fNext < 0.0) {
            inside = true;
            break;
        }
        t = tNext;
        f = fNext;
        if (t > tmax) {
            break;
        }
    }
    if (!inside) return -1.0;
    Settle S = settleStart(t, f, tNext, fNext);
    float th = SETTLE_MORE;
    for (int i = uZero; i < SETTLE_CALLS && th < -3.5; i++) {
        float c = settlePoint(S);
        float fc = map(ro + rd * c);
        steps++;
        th = settleUpdate(S, c, fc);
    }
    return th;
}
