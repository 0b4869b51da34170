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
#define SCAN_POINTS 16     // samples across a long uncovered probe bracket (the near zone of a
                           // plane seen low may hold objects standing on it)
#define SCAN_SPACING 2.0   // ... at least this many hit thresholds apart (half a footprint by default:
                           // a bump that the ray clips a footprint before the far root dips below the line)
#define SCAN_DIP 0.7       // a scan sample below this share of the straight line, or above 1/SCAN_DIP of it: the line fails

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
// lies near the ray there) or rises well above it (the ray passes between things, so the
// line to the far root says nothing of what lies past the sample: a sphere the probe
// jumped in a repetition seen at a low angle) returns -3.0 with settleT/settleF set to the
// last scan sample the way to which is proven (its ball meets the one before it, back to
// a: marching goes on from there), or -2.0 when that is a itself. After the
// scan the bracket is kept only if the first secant sample agrees with the straight line
// (|f| below half of fa there, as on a face seen at a grazing angle), else -2.0: the
// marcher steps closer in and probes again.
// A marcher takes these samples in its own loop (settleStart, then settlePoint and
// settleUpdate once a round, each map() call counted in steps): llvmpipe runs every branch
// of a loop body for the whole block of pixels and a nested loop's body at least once per
// round, so a settle() loop inside the marching loop cost a map() per marching step.
#define SETTLE_MORE -4.0   // settleUpdate: the settling needs another sample

struct Settle {
    float a, fa, b, fb;   // the bracket (fb = UNSAMPLED: b is a probe not sampled yet)
    int side;             // Illinois: the side the last secant sample replaced
    bool check;           // the next secant sample must agree with the straight line
    int scan;             // scan samples still to take
    float scanStep;
    float a0, fa0, c0;    // the straight line the scan is held to: (a0, fa0) to (c0, 0)
    float pa, fpa;        // the last scan sample the way to is proven (the balls overlap), and f there
    int calls;            // samples taken
};

Settle settleStart(float a, float fa, float b, float fb) {
    return Settle(a, fa, b, fb, 0, false, 0, 0.0, a, fa, b, a, fa, 0);
}

// The ray parameter of the next sample.
float settlePoint(Settle S) {
    if (S.scan > 0) return S.a + S.scanStep;
    if (S.fb >= UNSAMPLED) return S.b;
    float c = S.b - S.fb * (S.b - S.a) / (S.fb - S.fa);
    return clamp(c, S.a + 0.01 * (S.b - S.a), S.b - 0.01 * (S.b - S.a));
}

// The root where the bracket ends: its straight line's zero.
float settleEnd(Settle S) {
    return S.a + S.fa * (S.b - S.a) / (S.fa - S.fb);
}

// Takes the sample fc = f(c) at c = settlePoint(S): the result as settle() describes it,
// or SETTLE_MORE while another sample is needed (at most SETTLE_CALLS in all).
float settleUpdate(inout Settle S, float c, float fc) {
    S.calls++;
    if (S.scan > 0) {
        S.scan--;
        float line = S.fa0 * (S.c0 - c) / (S.c0 - S.a0);  // the straight line to the far root, at c
        if (fc < 0.0) {
            S.b = c;  // an earlier surface: the bracket ends at the first sample inside
            S.fb = fc;
            S.scan = 0;
            S.check = false;
        } else if (fc < SCAN_DIP * line || fc * SCAN_DIP > line) {
            settleT = S.pa;
            settleF = S.fpa;
            return S.pa > S.a0 ? -3.0 : -2.0;
        } else {
            if (c - fc <= S.pa + S.fpa) {
                S.pa = c;  // its ball meets the last proven one's: the way to it is proven
                S.fpa = fc;
            }
            S.a = c;
            S.fa = fc;
        }
    } else if (S.fb >= UNSAMPLED) {
        S.fb = fc;
        if (fc >= 0.0) return -1.0;
        S.check = S.fa - fc < 0.999 * (S.b - S.a);
        if (S.check) {
            S.c0 = S.a + S.fa * (S.b - S.a) / (S.fa - fc);
            S.scan = min(SCAN_POINTS, int((S.c0 - S.a) / (SCAN_SPACING * hitEpsilon(S.a))));
            S.scanStep = (S.c0 - S.a) / float(S.scan + 1);
        }
    } else {
        float tol = SETTLE_TOL * hitEpsilon(c);
        if (S.check && abs(fc) > max(0.5 * S.fa, tol)) return -2.0;  // (within tol of 0 is a root anyway)
        S.check = false;
        float sLeft = (S.fa - fc) / (c - S.a);
        float sRight = (fc - S.fb) / (S.b - c);
        float sMin = min(sLeft, sRight);
        if (sMin > 0.0 && max(sLeft, sRight) < 2.0 * sMin && abs(fc) <= tol * sMin) {
            return c;  // f is near linear across the bracket and c within tol of its root
        }
        if (fc < 0.0) {
            S.b = c;
            S.fb = fc;
            if (S.side == -1) S.fa *= 0.5;
            S.side = -1;
        } else {
            S.a = c;
            S.fa = fc;
            if (S.side == 1) S.fb *= 0.5;
            S.side = 1;
        }
        if (S.b - S.a <= tol) S.calls = SETTLE_CALLS;  // the bracket is small enough: done
    }
    return S.calls < SETTLE_CALLS ? SETTLE_MORE : settleEnd(S);
}
