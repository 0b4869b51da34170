// Sphere tracing and its over-relaxed variants, sharing one safety net and one hit test.
//   sphere   (Hart 1996): the step is the distance.
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
// The hit test (refine.glsl): a sample within the hit threshold (hitEpsilon) of a
// surface probes past the root the slope predicts and needs a sign change; a near miss
// goes on marching. A sample below 0 brackets the root. Far from the surface, a ray
// closing in at a shallow angle probes the predicted root every fourth step; a probe that
// lands inside past a gap the spheres do not cover proves nothing of the gap (an object
// standing on a ground plane may fill it), so the ray marches on where the budget left
// affords the way to the surface (roundsToNear), and settles the probe only where not.
// Budget: at most MAX_STEPS loop rounds away from surfaces and 2 MAX_STEPS in all; the
// rounds that start within the hit threshold (near misses, probes from closer in) are
// counted apart, so a ray that passes near many surfaces (a repetition seen at a low
// angle) keeps the sphere steps a ray without near misses has. A ray out of steps is a
// miss: undecided, it is not drawn as a surface that may not be there.
// One loop and one map() call a loop round: a round either samples t (a marching round)
// or takes the next sample of a settling (settleUpdate); a settling that ends with the
// field known where marching goes on (the probe, the sample before a dip) starts the next
// marching round at once, with no sample of its own. On llvmpipe the lanes of a block then
// share every round whether they march or settle, where a nested settle() loop made the
// marching lanes wait and each call site added a copy of map().
#if defined(ENHANCED)
#define STEP_FALL 2.0    // enhanced: tangent spheres along a straight surface
#elif defined(OMEGA)
#define STEP_FALL OMEGA
#else
#define STEP_FALL 1.0
#endif

// The marching rounds from a sample (t, r), the field falling at slope s along the ray as
// towards a straight surface, to where that surface's root is within the hit threshold:
// each round shrinks r by about STEP_FALL s of itself.
float roundsToNear(float t, float r, float s) {
    return log(max(r / hitEpsilon(t + r / s), 1.0)) / (STEP_FALL * s);
}

float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float roLen = length(ro);
    float t = tmin;
    float tPrev = tmin;
    float rPrev = -1.0;      // < 0: no previous sample
    bool over = false;       // the step to t was longer than rPrev: check the spheres overlap
    bool relax = true;       // relaxed: false once a step failed
    bool haveSlope = false;  // enhanced: the previous sample is usable
    int rounds = 0;          // probes from closer in while r stopped shrinking
    float rRound = 3.0e38;   // r when rounds last restarted
    int sinceProbe = 0;      // steps since the last shallow-angle probe
    bool farProbes = true;   // false once a shallow-angle probe landed inside unproven
    int nearSteps = 0;
    int marchRounds = 0;
    int nearRounds = 0;      // rounds that started within the hit threshold
    int settling = 0;        // 0: marching; 1: a bracketed root, 2: a near probe, 3: a shallow-angle probe
    Settle S = settleStart(0.0, 0.0, 0.0, 0.0);
    float ms = 0.0;          // a near probe's minimum step
    float sProbe = 0.0;      // a shallow-angle probe's slope
#ifdef RAY_FREE
    rayFreeStart(rd);
#endif
    for (int i = uZero; i < 2 * MAX_STEPS * (SETTLE_CALLS + 1); i++) {
        if (settling == 0 && (marchRounds >= 2 * MAX_STEPS || marchRounds - nearRounds >= MAX_STEPS)) break;
        float c = settling == 0 ? t : settlePoint(S);
#ifdef RAY_FREE
        gFreeAsk = settling == 0;
#endif
        float r = map(ro + rd * c);
#ifdef RAY_FREE
        gFreeAsk = false;
        float free = settling == 0 ? gFree : 0.0;  // the way proven empty from t (lib/ray_free.glsl)
#endif
        steps++;
        float s = 0.0;
        bool stepOnly = false;  // the shallow-angle probe found no way on: the round's usual step
        if (settling == 3 && r < 0.0 && S.fa0 - r < 0.999 * (c - S.a0) &&
            roundsToNear(S.a0, S.fa0, sProbe) < 0.5 * float(MAX_STEPS - (marchRounds - nearRounds))) {
            // the shallow-angle probe landed inside past a gap that its ball and f(t)'s do not
            // cover: a near object may stand in the gap (a box on a ground plane), so the way
            // there is marched where the budget affords it; a root lies before the probe, so
            // the ray probes from afar only once the way left costs more than the budget left
            settling = 0;
            farProbes = false;
            r = S.fa0;
            s = sProbe;
            stepOnly = true;
        }
        if (settling != 0) {
            float th = settleUpdate(S, c, r);
            if (th < -3.5) continue;
            int kind = settling;
            settling = 0;
            if (kind == 1 || th >= 0.0) {
                return kind == 1 || th <= tmax ? th : -1.0;
            }
            float r0 = S.fa0;  // f(t): the sample the probe started from
            // (S.b, S.fb): the probe and f there, read only when th is -1.0
            if (kind == 2) {
                tPrev = t;
                rPrev = r0;
                over = false;
                haveSlope = true;
                bool on = true;  // marching goes on with f known: r
                if (th < -2.5) {
                    t = settleT;  // the probe's scan saw the field dip: go on from before the dip
                    r = settleF;
                } else if (th > -1.5 && nearMiss(t, r0, S.b, S.fb, ms, rounds)) {
                    t = S.b;  // go on from the probe
                    r = S.fb;
                    rounds = 0;
                    rRound = 3.0e38;
                } else {
                    t += max(r0, ms);  // a thin part may lie in the gap: the safe step (never 0), then probe again
                    on = false;
                    if (r0 < 0.9 * rRound) {
                        rRound = r0;  // still closing in: not stuck
                        rounds = 0;
                    } else {
                        rounds++;
                    }
                }
                if (t > tmax) return -1.0;
                if (!on) continue;
            } else if (th < -2.5 || (th > -1.5 && r0 + S.fb >= 0.999 * (S.b - t))) {
                tPrev = t;   // the spheres cover the way: go on from the probe (or from
                rPrev = r0;  // before the dip the probe's scan saw)
                t = th < -2.5 ? settleT : S.b;
                r = th < -2.5 ? settleF : S.fb;
                over = false;
                if (t > tmax) return -1.0;
            } else {
                r = r0;
                s = sProbe;
                stepOnly = true;
            }
            if (!stepOnly && (marchRounds >= 2 * MAX_STEPS || marchRounds - nearRounds >= MAX_STEPS)) break;
        }
        if (!stepOnly) {
            marchRounds++;
            if (over && abs(r) + rPrev < t - tPrev) {
                t = tPrev + rPrev;  // back to where a plain step stands
                over = relax = haveSlope = false;
                continue;
            }
            bool inside = r < 0.0;  // a bracketed root
            if (inside && rPrev < 0.0) return t;  // the ray starts inside
            s = rPrev >= 0.0 ? (rPrev - r) / max(t - tPrev, 1e-30) : 0.0;
            bool near = !inside && r < hitEpsilon(t);
            // at a shallow angle, every other round near the surface takes the method's own
            // step (over-relaxed where the method is, the overlap checked next round) instead
            // of a probe: most such rays pass by
            bool stepNear = false;
            if (near) {
                nearRounds++;
                stepNear = s < 0.5 && (++nearSteps & 1) == 0;
            }
            // far from the surface, closing in at a shallow angle: every fourth step, probe
            // past the root the slope predicts (a plane seen at 0.5 degrees would take
            // hundreds of steps)
            bool shallow = !inside && !near && s > 1e-3 && s < 0.5 && ++sinceProbe >= 4 &&
                (farProbes || roundsToNear(t, r, s) >= 0.5 * float(MAX_STEPS - (marchRounds - nearRounds)));
            if (inside || (near && !stepNear) || shallow) {
                if (shallow) sinceProbe = 0;
                ms = minProbe(t, roLen);
                S = settleStart(inside ? tPrev : t, inside ? rPrev : r,  // (WebGL: no ?: on structs)
                                inside ? t : t + probeStep(r, s, ms), inside ? r : UNSAMPLED);
                settling = inside ? 1 : near ? 2 : 3;
                sProbe = s;
                continue;
            }
        }
#if defined(ENHANCED)
        float next = r;
        if (haveSlope) {
            float sc = clamp(s, -0.5, 1.0);
            next = r + OMEGA * r * (1.0 - sc) / (1.0 + sc);
        }
        haveSlope = true;
#elif defined(OMEGA)
        float next = relax ? OMEGA * r : r;
#else
        float next = r;
#endif
#ifdef RAY_FREE
        // the union's free way: land a hit threshold short of what the ray meets; no
        // overlap to check afterwards, the whole segment is proven empty
        bool proven = free - hitEpsilon(t) > next;
        if (proven) next = free - hitEpsilon(t);
#else
        bool proven = false;
#endif
        tPrev = t;
        rPrev = proven ? -1.0 : r;  // a slope over a proven stride says nothing of the field here
        haveSlope = haveSlope && !proven;
        t += next;
        over = next > r && !proven;
        if (t > tmax) {
            if (!over) return -1.0;
            t = tPrev + r;  // an enlarged step left the range unchecked: take the plain one
            over = relax = haveSlope = false;
        }
    }
    return -1.0;  // out of steps: undecided, drawn as a miss (never a hit that may be a ghost)
}
