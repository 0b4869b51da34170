// Newton marching (the seed thesis, re-derived): Newton's method on f(t) = map(ro + t rd)
// with f'(t) from rayDerivative (so an iteration costs two map() calls). When f' >= 0
// the Newton step would not go forward: a sphere step f is taken instead. A sign change
// of f means the step crossed a surface: the root is then bracketed and pinned down by
// bracketRoot. Works on implicit fields that are not distances (e.g. a product of SDFs);
// it can take a far root when a step jumps a whole object.
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
    float t = tmin;
    float tOut = tmin;
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
        float dt = df < 0.0 ? -f / df : f;
        t += dt;
        if (t > tmax) {
            break;
        }
    }
    return -1.0;
}
