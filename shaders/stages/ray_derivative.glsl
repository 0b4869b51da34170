// d/dt of map(ro + t rd) at t by a forward difference: (map(p + rd h) - f) / h at
// p = ro + rd t, one map() call beyond f = map(p), taken by the marcher's own loop.
// The offset h is 1e-4 of the scene size or of |p|, whichever is larger (float32 noise).
float rayDerivativeStep(vec3 p) {
    return 1e-4 * max(SCENE_SCALE, length(p));
}
