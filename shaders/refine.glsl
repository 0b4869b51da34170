// Settling a ray near the surface, shared by every marcher. A hit needs a sign change of
// f(t) = map(ro + t rd): a ray that only comes close to f = 0 (a near miss at a
// silhouette, a sheet where two faces coincide and f touches 0 without going below) is
// no hit, and marching goes on.
//
// A marcher whose sample (t, r) comes within the hit threshold (hitEpsilon) probes
// past the root that the field's fall along the ray predicts (probeStep). settle()
// samples the probe and, where f < 0 there, pins the bracketed root down with the
// Illinois variant of regula falsi (no fixed slope clamp: the slope comes from the
// samples) to SETTLE_TOL hit thresholds in t: the bracket that small, or f near linear
// across it (the slopes either side of the last sample within 2x) and the sample's
// value below the tolerance times that slope. Where the probe finds f >= 0, the
// marcher decides (nearMiss): if the unbounding spheres of t and the probe overlap
// (the field is at most 1-Lipschitz), nothing lies between and the ray goes on from
// the probe; if not, a thin part may lie in the gap, so the ray takes the plain safe
// step r and probes again from closer in, until the probe lands inside, the spheres
// overlap, or r is below the probe's minimum step (a sheet where f touches 0: a
// near miss).
#define UNSAMPLED 3.0e38
#define SETTLE_CALLS 24
#define SETTLE_TOL 0.01
#define SCAN_POINTS 3      // samples across a long uncovered probe bracket
#define SCAN_SPACING 4.0   // ... at least this many hit thresholds apart (a footprint by default)
#define SCAN_DIP 0.7       // a scan sample below this share of the straight line: the field dips

// Where marching goes on after settle() returns -3.0: the last scan sample and f there.
float settleT;
float settleF;

// Smallest probe step at t: keeps progress above float32 resolution where r is 0.
float minProbe(float t, float roLen) {
    return max(0.3 * SETTLE_TOL * hitEpsilon(t), 4e-7 * (abs(t) + roLen));
}

// The probe distance past a near sample (field r, falling at slope s per unit of t): a
// quarter beyond the root the slope predicts, at least the covered step r, plus the
// minimum step (on implicit fields at most 4 r); where the field does not fall, 1.9 r.
float probeStep(float r, float s, float minStep) {
    if (s <= 1e-3) {
        return max(1.9 * r, r + minStep);  // not closing in: a step the two spheres cover
    }
    float step = max(1.25 * r / s, r);
#ifdef IMPLICIT_FIELD
    step = min(step, 4.0 * r);  // the field is no distance: its slope says little far off
#endif
    return step + minStep;
}

// True when a positive probe fb at b, from a near sample (t, r), shows a near miss.
// rounds counts the probes from closer in during which r stopped shrinking (a ray that
// runs along a surface at a tiny distance): the level below which r counts as a touch
// of f = 0 doubles every four of them, up to 16 times, so such a ray moves on. On an implicit field (no distance bound) only
// that level decides.
bool nearMiss(float t, float r, float b, float fb, float minStep, int rounds) {
#ifdef IMPLICIT_FIELD
    return r <= minStep * exp2(0.25 * float(rounds));  // no Lipschitz bound: no spheres to overlap
#else
    return r + fb >= 0.999 * (b - t) || r <= minStep * exp2(min(0.25 * float(rounds), 4.0));
#endif
}

// The root in [a, b] where f(a) = fa >= 0 and fb = f(b) < 0, or, with fb = UNSAMPLED,
// b is a probe sampled first: then -1.0 when f(b) >= 0, with fb set to f(b). A probe
// that lands inside with a gap the two spheres do not cover may have jumped an earlier
// surface (a thin part, a twisted blade the ray skims past). Where that gap is long (more
// than SCAN_SPACING hit thresholds to the root the straight line from (a, fa) to (b, fb)
// predicts), up to SCAN_POINTS samples scan it evenly first: a sample inside narrows the
// bracket to the first one; a sample that dips well below the straight line (something
// lies near the ray there) returns -3.0 with settleT/settleF set to the last sample before
// it that did not (marching goes on from there), or -2.0 when that is a itself. After the
// scan the bracket is kept only if the first secant sample agrees with the straight line
// (|f| below half of fa there, as on a face seen at a grazing angle), else -2.0: the
// marcher steps closer in and probes again. All map() calls are in one loop (one copy of
// map()) and counted in steps.
float settle(vec3 ro, vec3 rd, float a, float fa, float b, inout float fb, inout int steps) {
    int side = 0;
    bool check = false;
    int scan = 0;         // scan samples still to take
    float scanStep = 0.0;
    float a0 = a;         // the straight line the scan is held to: (a0, fa0) to (c0, 0)
    float fa0 = fa;
    float c0 = b;
    for (int i = uZero; i < SETTLE_CALLS; i++) {
        bool probing = fb >= UNSAMPLED;
        float c = b;
        if (scan > 0) {
            c = a + scanStep;
        } else if (!probing) {
            c = b - fb * (b - a) / (fb - fa);
            c = clamp(c, a + 0.01 * (b - a), b - 0.01 * (b - a));
        }
        float fc = map(ro + rd * c);
        steps++;
        if (scan > 0) {
            scan--;
            if (fc < 0.0) {
                b = c;  // an earlier surface: the bracket ends at the first sample inside
                fb = fc;
                scan = 0;
                check = false;
            } else if (fc < SCAN_DIP * fa0 * (c0 - c) / (c0 - a0)) {
                settleT = a;
                settleF = fa;
                return a > a0 ? -3.0 : -2.0;
            } else {
                a = c;
                fa = fc;
            }
            continue;
        }
        if (probing) {
            fb = fc;
            if (fc >= 0.0) return -1.0;
            check = fa - fc < 0.999 * (b - a);
            if (check) {
                c0 = a + fa * (b - a) / (fa - fc);
                scan = min(SCAN_POINTS, int((c0 - a) / (SCAN_SPACING * hitEpsilon(a))));
                scanStep = (c0 - a) / float(scan + 1);
            }
            continue;
        }
        float tol = SETTLE_TOL * hitEpsilon(c);
        if (check && abs(fc) > max(0.5 * fa, tol)) return -2.0;  // (within tol of 0 is a root anyway)
        check = false;
        float sLeft = (fa - fc) / (c - a);
        float sRight = (fc - fb) / (b - c);
        float sMin = min(sLeft, sRight);
        if (sMin > 0.0 && max(sLeft, sRight) < 2.0 * sMin && abs(fc) <= tol * sMin) {
            return c;  // f is near linear across the bracket and c within tol of its root
        }
        if (fc < 0.0) {
            b = c;
            fb = fc;
            if (side == -1) fa *= 0.5;
            side = -1;
        } else {
            a = c;
            fa = fc;
            if (side == 1) fb *= 0.5;
            side = 1;
        }
        if (b - a <= tol) break;
    }
    return a + fa * (b - a) / (fa - fb);
}
