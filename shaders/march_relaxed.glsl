// Over-relaxed sphere tracing, two step rules sharing one safety net.
//   relaxed  (Keinert et al. 2014): the step is OMEGA times the distance, OMEGA in (1, 2).
//   enhanced (Balint & Valasek 2018, re-derived; the seed's printed pseudo-code has
//            typos): the last two samples give the slope s at which the distance falls
//            along the ray; for a plane, the step 2r / (1 + s) makes the next unbounding
//            sphere tangent to this one. The step is r + OMEGA r (1 - s) / (1 + s), OMEGA
//            in (0, 1].
// When the new unbounding sphere does not overlap the previous one, or an enlarged step
// leaves the ray's range unchecked, a surface may lie in the gap: the ray goes back to
// where plain sphere tracing would stand and continues with plain steps (relaxed) or
// with a fresh slope (enhanced).
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float t = tmin;
    float rPrev = 0.0;
    float step = 0.0;
    bool relax = true;       // relaxed: false once a step failed
    bool haveSlope = false;  // enhanced: the previous sample is usable
    for (int i = 0; i < MAX_STEPS; i++) {
        float r = map(ro + rd * t);
        steps++;
        if (step > rPrev && abs(r) + rPrev < step) {
            t += rPrev - step;  // back to t_prev + r_prev
            relax = haveSlope = false;
            step = 0.0;
            continue;
        }
        if (r < hitEpsilon(t)) {
            return refineHit(ro, rd, tmin, t, r, steps);
        }
#ifdef ENHANCED
        float next = r;
        if (haveSlope) {
            float s = clamp((rPrev - r) / step, -0.5, 1.0);
            next = r + OMEGA * r * (1.0 - s) / (1.0 + s);
        }
        haveSlope = true;
#else
        float next = relax ? OMEGA * r : r;
#endif
        rPrev = r;
        step = next;
        t += step;
        if (t > tmax) {
            if (step <= r) {
                break;
            }
            t += r - step;  // an enlarged step left the range unchecked: take the plain one
            step = 0.0;
            relax = haveSlope = false;
        }
    }
    return -1.0;
}
