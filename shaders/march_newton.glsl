// Newton marching and forward Newton marching (the seed thesis, re-derived).
//   newton:         Newton's method on f(t) = map(ro + t rd).
//   forward_newton: Newton on g(t) = f(t) (T - t) / (t - t0), with
//                   g'(t) = f'(t) (T - t) / (t - t0) - f (T - t0) / (t - t0)^2, which adds
//                   a root at the far limit T, so rays with no surface drift forward to T
//                   instead of stalling in a local minimum of f. (The printed pseudo-code
//                   has "eps^2" for t^2 and a flipped sign.) t0 lies behind the start of
//                   the ray by the field value there (at least 1e-6 of the scene size), so
//                   the march starts at tmin itself, a surface however close is found, and
//                   the first steps are not needlessly small.
// f'(t) comes from rayDerivative, so an iteration costs two map() calls. A step that
// would not go forward is replaced by a sphere step f. A sign change of f means the
// step crossed a surface: settle() pins the root down; a sample within the hit
// threshold hands over to settle() with a probe past the root Newton predicts (a near
// miss goes on from the probe). Works on implicit fields that are not distances (a
// product of SDFs); can take a far root when a step jumps a whole object. NEWTON_CAP (a
// setting, 2 by default) caps a Newton step at that many times the field value, which
// keeps it from jumping thin parts of fields that are near-distances (an implicit
// surface's f / |grad f|). Budget as in march_relaxed.glsl: MAX_STEPS rounds away from
// surfaces, the rounds that start within the hit threshold counted apart (2 MAX_STEPS in all).
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float roLen = length(ro);
#ifdef FORWARD_NEWTON
    float T = tmax;
    float t0 = tmin - 1e-4 * SCENE_SCALE;
#endif
    float t = tmin;
    float tOut = t;
    float fOut = -1.0;  // < 0: no sample outside yet
    bool carry = false;
    float fCarry = 0.0;
    int rounds = 0;
    float rRound = 3.0e38;  // the field when rounds last restarted
    int nearRounds = 0;     // rounds that started within the hit threshold: counted apart
    for (int i = 0; i < 2 * MAX_STEPS; i++) {
        if (i - nearRounds >= MAX_STEPS) break;  // out of steps away from surfaces
        float f = fCarry;
        if (!carry) {
            f = map(ro + rd * t);
            steps++;
        }
        carry = false;
        if (isnan(f) || isinf(f)) {  // an overflowing field (x^1000 far out): step on through it
            t += 0.05 * t + 1e-2 * SCENE_SCALE;
            if (t > tmax) return -1.0;
            continue;
        }
#ifdef FORWARD_NEWTON
        if (i == 0) t0 = tmin - max(f, 1e-6 * SCENE_SCALE);  // the pole as far back as the surface may be near
#endif
        if (f < 0.0) {
            if (fOut < 0.0) return t;  // the ray starts inside
            float fb = f;
            return settle(ro, rd, tOut, fOut, t, fb, steps);
        }
        float df = rayDerivative(ro, rd, t, f, steps);
        if (f < hitEpsilon(t)) {
            nearRounds++;
            float ms = minProbe(t, roLen);
            float b = t + probeStep(f, -df, ms);
            float fb = UNSAMPLED;
            float th = settle(ro, rd, t, f, b, fb, steps);
            if (th >= 0.0) {
                return th <= tmax ? th : -1.0;
            }
            tOut = t;
            fOut = f;
            if (th > -1.5 && nearMiss(t, f, b, fb, ms, rounds)) {
                t = b;
                carry = true;
                fCarry = fb;
                rounds = 0;
                rRound = 3.0e38;
            } else {
                // closer in: the root Newton predicts (f need not be a distance here)
                t += df < 0.0 ? min(f / -df, b - t) * 0.999 : f;
                if (f < 0.9 * rRound) {
                    rRound = f;  // still closing in: not stuck
                    rounds = 0;
                } else {
                    rounds++;
                }
            }
            if (t > tmax) return -1.0;
            continue;
        }
        tOut = t;
        fOut = f;
#ifdef FORWARD_NEWTON
        float w = (T - t) / (t - t0);
        float dg = df * w - f * (T - t0) / ((t - t0) * (t - t0));
        t += dg < 0.0 ? min(-f * w / dg, NEWTON_CAP * f) : f;
        if (t >= T * 0.9999) {
            return -1.0;
        }
#else
        t += df < 0.0 ? min(-f / df, NEWTON_CAP * f) : f;
        if (t > tmax) {
            return -1.0;
        }
#endif
    }
    return -1.0;  // out of steps: undecided, drawn as a miss (never a hit that may be a ghost)
}
