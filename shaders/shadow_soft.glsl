// Soft shadow with Inigo Quilez's improved penumbra estimate (MIT): 1 lit, 0 in shadow.
float shadow(vec3 ro, vec3 rd, float tmin, float tmax) {
    float res = 1.0;
    float t = tmin;
    float ph = 1e10;
    for (int i = 0; i < 96; i++) {
        float h = map(ro + rd * t);
        float y = h * h / (2.0 * ph);
        float d = sqrt(max(h * h - y * y, 0.0));
        res = min(res, 8.0 * d / max(t - y, 1e-6));
        ph = h;
        t += clamp(h, 0.002 * SCENE_SCALE, 0.25 * SCENE_SCALE);
        if (res < 1e-4 || t > tmax) break;
    }
    res = clamp(res, 0.0, 1.0);
    return res * res * (3.0 - 2.0 * res);
}
