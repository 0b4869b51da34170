// Debug views of the pixel-centre ray: the step-count heat map, normals, or depth.
vec3 heat(float x) {
    x = clamp(x, 0.0, 1.0);
    return clamp(vec3(1.5 * x - 0.25, 1.5 - abs(2.0 * x - 1.0) * 1.5, 1.25 - 1.5 * x), 0.0, 1.0);
}

// Linear-space colour shown instead of the shaded image, for the pixel-centre ray's hit h.
vec3 debugView(vec3 ro, vec3 rd, Hit h) {
#if defined(DEBUG_STEPS)
    // 0 steps black, then blue -> green -> red on a log scale up to MAX_STEPS
    if (h.steps == 0) return vec3(0.0);
    return pow(heat(log2(float(h.steps)) / log2(float(MAX_STEPS))), vec3(2.2));
#elif defined(DEBUG_SELECT)
    // grey, tinted where the highlighted subtree is the surface that was hit
    if (h.t < 0.0) return vec3(0.0);
    vec3 nor = hitNormal(ro, rd, h);
    vec3 grey = vec3(0.12 + 0.5 * max(dot(nor, normalize(vec3(0.5, 0.8, 0.3))), 0.0));
    if (h.ground) return grey * 0.6;
    gSel = 1e30;
    float d = abs(map(ro + rd * h.t));
    return gSel <= 2.0 * d + 1e-3 * (h.t + SCENE_SCALE) ? grey * vec3(1.0, 0.45, 0.1) * 2.0 : grey;
#elif defined(DEBUG_NORMAL)
    if (h.t < 0.0) return vec3(0.0);
    return pow(0.5 + 0.5 * hitNormal(ro, rd, h), vec3(2.2));
#else
    if (h.t < 0.0) return vec3(0.0);
    return pow(vec3(exp(-h.t / (2.0 * SCENE_SCALE))), vec3(2.2));
#endif
}
