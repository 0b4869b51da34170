// Hart's sphere tracing: step by the distance bound until it falls below the hit
// threshold. Returns the hit t (refined by refineHit) or -1.0 and adds the map()
// evaluations it spent to steps.
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float t = tmin;
    for (int i = 0; i < MAX_STEPS; i++) {
        float d = map(ro + rd * t);
        steps++;
        if (d < hitEpsilon(t)) {
            return refineHit(ro, rd, tmin, t, d, steps);
        }
        t += d;
        if (t > tmax) {
            break;
        }
    }
    return -1.0;
}
