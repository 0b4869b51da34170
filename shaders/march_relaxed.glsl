// Over-relaxed sphere tracing (Keinert et al. 2014): steps of OMEGA times the distance
// while consecutive unbounding spheres overlap. When they stop overlapping a surface may
// lie in the gap: the ray goes back to where plain sphere tracing would stand and
// continues unrelaxed.
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float omega = OMEGA;
    float t = tmin;
    float rPrev = 0.0;
    float step = 0.0;
    for (int i = 0; i < MAX_STEPS; i++) {
        float r = map(ro + rd * t);
        steps++;
        if (omega > 1.0 && abs(r) + rPrev < step) {
            t += rPrev - step;  // back to t_prev + r_prev
            omega = 1.0;
            step = 0.0;
            continue;
        }
        if (r < hitEpsilon(t)) {
            return refineHit(ro, rd, tmin, t, r, steps);
        }
        rPrev = r;
        step = omega * r;
        t += step;
        if (t > tmax) {
            if (step <= r) {
                break;
            }
            t += r - step;  // an over-relaxed step left the range unchecked: take the plain one
            step = 0.0;
            omega = 1.0;
        }
    }
    return -1.0;
}
