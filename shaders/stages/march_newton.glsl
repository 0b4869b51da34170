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
// f'(t) comes from a forward difference (rayDerivativeStep), so an iteration costs two
// map() calls. A step that would not go forward is replaced by a sphere step f. A sign
// change of f means the step crossed a surface: settling (refine.glsl) pins the root
// down; a sample within the hit threshold settles with a probe past the root Newton predicts (a near
// miss goes on from the probe). Works on implicit fields that are not distances (a
// product of SDFs); can take a far root when a step jumps a whole object. NEWTON_CAP (a
// setting, 2 by default) caps a Newton step at that many times the field value, which
// keeps it from jumping thin parts of fields that are near-distances (an implicit
// surface's f / |grad f|); on an implicit field a step is also at most STEP_GROWTH times the
// last, since f / |grad f| is huge near a critical point outside the solid. A step past the
// box exit samples the exit first, so a sign change before it is found. Budget as in
// march_relaxed.glsl: MAX_STEPS rounds away from surfaces, the rounds that start within
// the hit threshold counted apart (2 MAX_STEPS in all).
// One loop and one map() call a loop round, as in march_relaxed.glsl: a loop round samples
// f at t, the derivative's second point, or the next point of a settling (settleUpdate).
#define STEP_GROWTH 2.0   // implicit fields: a Newton step at most this many times the last one
#define FIRST_STEP 0.01   // ... and the first at most this share of the scene size times STEP_GROWTH

float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float roLen = length(ro);
#ifdef FORWARD_NEWTON
    float T = tmax;
    float t0 = tmin - 1e-4 * SCENE_SCALE;
#endif
    float t = tmin;
#if defined(IMPLICIT_FIELD) && !defined(FORWARD_NEWTON)
    float lastStep = FIRST_STEP * SCENE_SCALE;  // the last Newton step (a first one of this share of the scene)
#endif
    float tOut = t;
    float fOut = -1.0;  // < 0: no sample outside yet
    int rounds = 0;
    float rRound = 3.0e38;  // the field when rounds last restarted
    int marchRounds = 0;
    int nearRounds = 0;     // rounds that started within the hit threshold: counted apart
    int phase = 0;          // the next sample: 0 f(t), 1 the derivative's, 2 a bracketed root's, 3 a near probe's
    Settle S = settleStart(0.0, 0.0, 0.0, 0.0);
    float f = 0.0;          // f(t)
    float h = 0.0;          // the derivative's offset
    float df = 0.0;         // f'(t), kept for a near probe
    float b = 0.0;          // a near probe's point
    float ms = 0.0;         // ... and its minimum step
    for (int i = uZero; i < 2 * MAX_STEPS * (SETTLE_CALLS + 2); i++) {
        if (phase == 0 && (marchRounds >= 2 * MAX_STEPS || marchRounds - nearRounds >= MAX_STEPS)) break;
        float c = phase >= 2 ? settlePoint(S) : t;
        vec3 p = ro + rd * c;
        if (phase == 1) p += rd * h;
        float v = map(p);
        steps++;
        if (phase == 1) {
            phase = 0;
            df = (v - f) / h;
            if (f < hitEpsilon(t)) {
                nearRounds++;
                ms = minProbe(t, roLen);
                b = t + probeStep(f, -df, ms);
                S = settleStart(t, f, b, UNSAMPLED);
                phase = 3;
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
            float step = df < 0.0 ? min(-f / df, NEWTON_CAP * f) : f;
#ifdef IMPLICIT_FIELD
            // f / |grad f| grows without bound near a critical point outside the solid (grad f = 0
            // where f > 0: between the lobes of a quartic, the centre of a shell): a step is at
            // most STEP_GROWTH times the last one, so a ray that meets such a point goes on in
            // steps that grow from the ones before it and does not leap whatever lies behind
            step = min(step, STEP_GROWTH * lastStep);
            lastStep = step;
#endif
            t += step;
            if (t > tmax) {
                if (tOut >= tmax) return -1.0;
                t = tmax;  // the step left the range: f at the exit shows a sign change before it
            }
#endif
            continue;
        }
        if (phase >= 2) {
            float th = settleUpdate(S, c, v);
            if (th < -3.5) continue;
            int kind = phase;
            phase = 0;
            if (kind == 2 || th >= 0.0) {
                return kind == 2 || th <= tmax ? th : -1.0;
            }
            tOut = t;
            fOut = f;
            if (th > -1.5 && nearMiss(t, f, b, S.fb, ms, rounds)) {
                t = b;  // a near miss: go on from the probe, its f known
                v = S.fb;
                rounds = 0;
                rRound = 3.0e38;
                if (t > tmax) return -1.0;
                if (marchRounds >= 2 * MAX_STEPS || marchRounds - nearRounds >= MAX_STEPS) break;
            } else {
                // closer in: the root Newton predicts (f need not be a distance here)
                t += df < 0.0 ? min(f / -df, b - t) * 0.999 : f;
                if (f < 0.9 * rRound) {
                    rRound = f;  // still closing in: not stuck
                    rounds = 0;
                } else {
                    rounds++;
                }
                if (t > tmax) return -1.0;
                continue;
            }
        }
        // a round: f at t is v
        marchRounds++;
        f = v;
        if (isnan(f) || isinf(f)) {  // an overflowing field (x^1000 far out): step on through it
            t += 0.05 * t + 1e-2 * SCENE_SCALE;
            if (t > tmax) return -1.0;
            continue;
        }
#ifdef FORWARD_NEWTON
        if (marchRounds == 1) t0 = tmin - max(f, 1e-6 * SCENE_SCALE);  // the pole as far back as the surface may be near
#endif
        if (f < 0.0) {
            if (fOut < 0.0) return t;  // the ray starts inside
            S = settleStart(tOut, fOut, t, f);
            phase = 2;
            continue;
        }
#ifndef FORWARD_NEWTON
        if (t >= tmax) return -1.0;  // outside at the exit: nothing in the range
#endif
        h = rayDerivativeStep(ro + rd * t);
        phase = 1;
    }
    return -1.0;  // out of steps: undecided, drawn as a miss (never a hit that may be a ghost)
}
