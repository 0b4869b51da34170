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
// closing in at a shallow angle probes the predicted root every fourth step.
// Budget: at most MAX_STEPS loop rounds away from surfaces and 2 MAX_STEPS in all; the
// rounds that start within the hit threshold (near misses, probes from closer in) are
// counted apart, so a ray that passes near many surfaces (a repetition seen at a low
// angle) keeps the sphere steps a ray without near misses has. A ray out of steps is a
// miss: undecided, it is not drawn as a surface that may not be there.
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float roLen = length(ro);
    float t = tmin;
    float tPrev = tmin;
    float rPrev = -1.0;      // < 0: no previous sample
    bool over = false;       // the step to t was longer than rPrev: check the spheres overlap
    bool relax = true;       // relaxed: false once a step failed
    bool haveSlope = false;  // enhanced: the previous sample is usable
    bool carry = false;      // f(t) is known already (rCarry), from settle()'s probe
    float rCarry = 0.0;
    int rounds = 0;          // probes from closer in while r stopped shrinking
    float rRound = 3.0e38;   // r when rounds last restarted
    int sinceProbe = 0;      // steps since the last shallow-angle probe
    int nearSteps = 0;
    int nearRounds = 0;      // rounds that started within the hit threshold
    for (int i = 0; i < 2 * MAX_STEPS; i++) {
        if (i - nearRounds >= MAX_STEPS) break;  // out of steps away from surfaces
        float r = rCarry;
        if (!carry) {
            r = map(ro + rd * t);
            steps++;
        }
        carry = false;
        if (over && abs(r) + rPrev < t - tPrev) {
            t = tPrev + rPrev;  // back to where a plain step stands
            over = relax = haveSlope = false;
            continue;
        }
        if (r < 0.0) {
            if (rPrev < 0.0) return t;  // the ray starts inside
            float fb = r;
            return settle(ro, rd, tPrev, rPrev, t, fb, steps);
        }
        float eps = hitEpsilon(t);
        float s = rPrev >= 0.0 ? (rPrev - r) / max(t - tPrev, 1e-30) : 0.0;
        if (r < eps) {
            nearRounds++;
            if (s < 0.5 && (++nearSteps & 1) == 0) {
                tPrev = t;  // at a shallow angle, every other step near the surface is a
                rPrev = r;  // plain one: most such rays pass by
                t += r;
                over = false;
                haveSlope = true;
                continue;
            }
            float ms = minProbe(t, roLen);
            float b = t + probeStep(r, s, ms);
            float fb = UNSAMPLED;
            float th = settle(ro, rd, t, r, b, fb, steps);
            if (th >= 0.0) {
                return th <= tmax ? th : -1.0;
            }
            tPrev = t;
            rPrev = r;
            over = false;
            haveSlope = true;
            if (th < -2.5) {
                t = settleT;  // the probe's scan saw the field dip: go on from before the dip
                carry = true;
                rCarry = settleF;
            } else if (th > -1.5 && nearMiss(t, r, b, fb, ms, rounds)) {
                t = b;  // go on from the probe
                carry = true;
                rCarry = fb;
                rounds = 0;
                rRound = 3.0e38;
            } else {
                t += max(r, ms);  // a thin part may lie in the gap: the safe step (never 0), then probe again
                if (r < 0.9 * rRound) {
                    rRound = r;  // still closing in: not stuck
                    rounds = 0;
                } else {
                    rounds++;
                }
            }
            if (t > tmax) return -1.0;
            continue;
        }
        if (s > 1e-3 && s < 0.5 && ++sinceProbe >= 4) {
            // closing in at a shallow angle: every fourth step, probe past the root the
            // slope predicts (a plane seen at 0.5 degrees would take hundreds of steps)
            sinceProbe = 0;
            float b = t + probeStep(r, s, minProbe(t, roLen));
            float fb = UNSAMPLED;
            float th = settle(ro, rd, t, r, b, fb, steps);
            if (th >= 0.0) {
                return th <= tmax ? th : -1.0;
            }
            if (th < -2.5 || (th > -1.5 && r + fb >= 0.999 * (b - t))) {
                tPrev = t;  // the spheres cover the way: go on from the probe (or from
                rPrev = r;  // before the dip the probe's scan saw)
                t = th < -2.5 ? settleT : b;
                carry = true;
                rCarry = th < -2.5 ? settleF : fb;
                over = false;
                if (t > tmax) return -1.0;
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
        tPrev = t;
        rPrev = r;
        t += next;
        over = next > r;
        if (t > tmax) {
            if (!over) return -1.0;
            t = tPrev + r;  // an enlarged step left the range unchecked: take the plain one
            over = relax = haveSlope = false;
        }
    }
    return -1.0;  // out of steps: undecided, drawn as a miss (never a hit that may be a ghost)
}
