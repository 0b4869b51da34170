// Brute-force march for validation: fixed steps of REF_STEP until the field changes
// sign, then settle() pins the root down. Needs no distance property at all; its cost is the ray
// length over REF_STEP.
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float t = tmin;
    float f = map(ro + rd * t);
    steps++;
    if (f < 0.0) {
        return tmin;
    }
    for (int i = 0; i < MAX_STEPS; i++) {
        float tNext = t + REF_STEP;
        float fNext = map(ro + rd * tNext);
        steps++;
        if (fNext < 0.0) {
            return settle(ro, rd, t, f, tNext, fNext, steps);
        }
        t = tNext;
        f = fNext;
        if (t > tmax) {
            break;
        }
    }
    return -1.0;
}
