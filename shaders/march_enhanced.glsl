// Enhanced sphere tracing (Balint & Valasek 2018), with the formula re-derived (the
// seed's printed pseudo-code has typos): the last two samples give the slope s at which
// the distance falls along the ray; for a plane, the step 2r / (1 + s) makes the next
// unbounding sphere tangent to this one. The step is r + OMEGA r (1 - s) / (1 + s),
// OMEGA in (0, 1]. If the new sphere does not overlap the previous one, the ray goes
// back to the plain sphere-tracing point and forgets the slope.
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float t = tmin;
    float rPrev = 0.0;
    float step = 0.0;
    bool haveSlope = false;
    for (int i = 0; i < MAX_STEPS; i++) {
        float r = map(ro + rd * t);
        steps++;
        if (haveSlope && abs(r) + rPrev < step) {
            t += rPrev - step;  // back to t_prev + r_prev
            haveSlope = false;
            step = 0.0;
            continue;
        }
        if (r < hitEpsilon(t)) {
            return refineHit(ro, rd, tmin, t, r, steps);
        }
        float next = r;
        if (haveSlope) {
            float s = clamp((rPrev - r) / step, -0.5, 1.0);
            next = r + OMEGA * r * (1.0 - s) / (1.0 + s);
        }
        haveSlope = true;
        rPrev = r;
        step = next;
        t += step;
        if (t > tmax) {
            if (step <= r) {
                break;
            }
            t += r - step;  // an over-relaxed step left the range unchecked: take the plain one
            step = 0.0;
            haveSlope = false;
        }
    }
    return -1.0;
}
