// The image: trace each sample's primary ray, shade it, average, gamma-correct; write
// depth, normal and step count of the pixel-centre ray when those outputs are on.
layout(location = 0) out vec4 outColor;
#ifdef OUT_DEPTH
layout(location = LOC_DEPTH) out float outDepth;
#endif
#ifdef OUT_NORMAL
layout(location = LOC_NORMAL) out vec4 outNormal;
#endif
#ifdef OUT_STEPS
layout(location = LOC_STEPS) out float outSteps;
#endif

struct Hit {
    float t;       // ray parameter of the hit, -1.0 for a miss
    int steps;     // map() evaluations spent
    bool ground;   // the hit is on the analytic ground plane
};

Hit tracePrimary(vec3 ro, vec3 rd) {
    Hit h = Hit(-1.0, 0, false);
    vec2 range = sceneRange(ro, rd);
#ifdef GROUND
    float tg = groundHit(ro, rd);
    if (tg > 0.0) range.y = min(range.y, tg);
#endif
    if (range.x <= range.y) {
        h.t = march(ro, rd, range.x, range.y, h.steps);
    }
#ifdef GROUND
    if (h.t < 0.0 && tg > 0.0) {
        h.t = tg;
        h.ground = true;
    }
#endif
    return h;
}

vec3 hitNormal(vec3 ro, vec3 rd, Hit h) {
#ifdef GROUND
    if (h.ground) return vec3(0.0, 1.0, 0.0);
#endif
    return calcNormal(ro + rd * h.t, h.t, rd);
}

vec3 radiance(vec3 ro, vec3 rd, Hit h) {
    if (h.t < 0.0) return background(rd);
    vec3 pos = ro + rd * h.t;
    vec3 nor = hitNormal(ro, rd, h);
#ifdef GROUND
    if (h.ground) {
        vec3 col = shadeSurface(pos, nor, rd, groundAlbedo(pos), h.t);
        float fog = 1.0 - exp(-h.t / (SCENE_SCALE * 40.0));
        return mix(col, background(rd), fog);
    }
#endif
    return shadeSurface(pos, nor, rd, mapColor(pos), h.t);
}

void main() {
    vec3 ro = uEye;
#if AA == 1
    vec3 rd = rayDir(gl_FragCoord.xy);
    Hit h = tracePrimary(ro, rd);
    vec3 col = radiance(ro, rd, h);
#else
    vec3 col = vec3(0.0);
    for (int j = 0; j < AA; j++) {
        for (int i = 0; i < AA; i++) {
            vec2 off = (vec2(float(i), float(j)) + 0.5) / float(AA) - 0.5;
            vec3 rds = rayDir(gl_FragCoord.xy + off);
            col += radiance(ro, rds, tracePrimary(ro, rds));
        }
    }
    col /= float(AA * AA);
#ifdef AUX_OUTPUTS
    vec3 rd = rayDir(gl_FragCoord.xy);
    Hit h = tracePrimary(ro, rd);
#endif
#endif
    outColor = vec4(pow(clamp(col, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
#ifdef OUT_DEPTH
    outDepth = h.t;
#endif
#ifdef OUT_NORMAL
    outNormal = vec4(h.t >= 0.0 ? hitNormal(ro, rd, h) : vec3(0.0), 0.0);
#endif
#ifdef OUT_STEPS
    outSteps = float(h.steps);
#endif
}
