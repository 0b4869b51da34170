// The default environment: a sky gradient by ray elevation.
vec3 background(vec3 rd) {
    float h = clamp(rd.y, -1.0, 1.0);
    vec3 horizon = vec3(0.86, 0.88, 0.91);
    vec3 zenith = vec3(0.38, 0.56, 0.84);
    vec3 below = vec3(0.55, 0.54, 0.52);
    return h >= 0.0 ? mix(horizon, zenith, sqrt(h)) : mix(horizon, below, sqrt(-h));
}
