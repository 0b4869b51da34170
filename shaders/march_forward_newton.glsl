// Forward Newton marching (the seed thesis, re-derived): Newton on
//     g(t) = f(t) (T - t) / t,   g'(t) = f'(t) (T - t) / t - f(t) T / t^2,
// which adds a root at the far limit T, so rays with no surface drift forward to T
// instead of stalling in a local minimum of f. (The printed pseudo-code has "eps^2" for
// t^2 and a flipped sign.) The hit test is on f itself; a sign change of f is bracketed.
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float T = tmax;
    float t = max(tmin, 1e-4 * SCENE_SCALE);
    float tOut = t;
    float fOut = 0.0;
    for (int i = 0; i < MAX_STEPS; i++) {
        float f = map(ro + rd * t);
        steps++;
        if (f < 0.0) {
            return i == 0 ? tmin : bracketRoot(ro, rd, tOut, fOut, t, f, steps);
        }
        float df = rayDerivative(ro, rd, t, f, steps);
        if (f < hitEpsilon(t)) {
            return df < 0.0 ? t + min(-f / df, 2.0 * hitEpsilon(t)) : t;
        }
        tOut = t;
        fOut = f;
        float w = (T - t) / t;
        float g = f * w;
        float dg = df * w - f * T / (t * t);
        float dt = dg < 0.0 ? -g / dg : f;
        t += dt;
        if (t >= T * 0.9999) {
            break;
        }
    }
    return -1.0;
}
