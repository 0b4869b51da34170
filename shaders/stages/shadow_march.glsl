// Hard shadow for implicit fields (no distance bound, so no penumbra estimate): the
// scene's own march() decides whether anything blocks the light.
float shadow(vec3 ro, vec3 rd, float tmin, float tmax) {
    int ignored = 0;
    return march(ro, rd, tmin, tmax, ignored) < 0.0 ? 1.0 : 0.0;
}
