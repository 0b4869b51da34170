// Move a hit at t (field value d < hitEpsilon) onto the surface along the ray. A
// sphere step to t1 = t + d is always safe for a distance bound; the secant through
// the two close samples (t, d) and (t1, d1) then estimates the root, its slope
// clamped to [0.1, 1] (a 1-Lipschitz field falls at most 1 per unit of t). One more
// map() call checks the estimate and keeps it only if the field there is closer to 0
// than d1, so a secant cannot jump through a feature thinner than the hit threshold.
// Two map() calls per hit, counted in steps, made in one loop (one copy of map()).
float refineHit(vec3 ro, vec3 rd, float tmin, float t, float d, inout int steps) {
    if (d <= 0.0) {
        return max(t + d, tmin);
    }
    float t1 = t + d;
    float d1 = 0.0;
    float tSec = t1;
    for (int i = uZero; i < 2; i++) {
        float tq = i == 0 ? t1 : tSec;
        float dq = map(ro + rd * tq);
        steps++;
        if (i == 1) {
            return abs(dq) < d1 ? tSec : t1;
        }
        if (dq <= 0.0) {
            return t1 + dq;
        }
        d1 = dq;
        tSec = t1 + d1 / clamp((d - d1) / d, 0.1, 1.0);
    }
    return t1;
}
