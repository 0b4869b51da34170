// Hard shadow: 0 if anything lies between ro and the light along rd, else 1.
float shadow(vec3 ro, vec3 rd, float tmin, float tmax) {
    float t = tmin;
    for (int i = 0; i < 96; i++) {
        float h = map(ro + rd * t);
        if (h < hitEpsilon(t)) return 0.0;
        t += h;
        if (t > tmax) break;
    }
    return 1.0;
}
