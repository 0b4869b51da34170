// d/dt of map(ro + t rd) at t by a forward difference: one map() call beyond f = map(p).
// The offset is 1e-4 of the scene size or of |p|, whichever is larger (float32 noise).
float rayDerivative(vec3 ro, vec3 rd, float t, float f, inout int steps) {
    vec3 p = ro + rd * t;
    float h = 1e-4 * max(SCENE_SCALE, length(p));
    steps++;
    return (map(p + rd * h) - f) / h;
}
